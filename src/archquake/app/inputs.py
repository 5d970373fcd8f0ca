"""What the page sends, turned into the library's values: the structure, the ground motion, the
site of the code check, the uploaded files, and the page's limits on their sizes.

The page describes a structure and a ground motion by named values (``{"thickness": 1.2,
"voussoirs": 9, "piers": "1.5,4,3", ...}``), the fields of the library's descriptions
(:class:`archquake.geometry.StructureSpec`, :class:`archquake.ground_motion.MotionSpec`), which
the command line's options map onto too: its JSON goes straight to them, so the page builds the
structure ``archquake limit`` builds from the same values, and refuses bad input with the same
message, which names the field where the command line names the option (``thickness must be
...`` for ``--thickness must be ...``).

Uploaded files are kept in the server's temporary folder under a random token
(:class:`Uploads`); a description names a file by its token, and :meth:`Uploads.resolve` puts the
file's path in its place before the description is built here or sent to a worker process. A
message about a file names it as the user did, as the command line names the path it was given.

The limits of :data:`LIMITS` keep one request from occupying the server: they are the page's, on
top of the library's own (which are meant for batch studies).
"""

from __future__ import annotations

import math
import re
import secrets
import threading
from collections import OrderedDict
from pathlib import Path, PurePath

LIMITS = {
    "blocks": 200,
    "geometry_bytes": 2 * 2**20,
    "record_bytes": 8 * 2**20,
    "record_samples": 200_000,
    "motion_duration": 120.0,
    "amplitude_g": 10.0,
    "request_bytes": 256 * 2**10,
    "uploads": 64,
    "uploads_bytes": 64 * 2**20,
    "domain_durations": 25,
    "domain_amplitudes": 80,
}
"""The page's limits: blocks of a structure (voussoirs and pier courses) [-], size of a geometry
file and of a record file [bytes], samples of a record [-], duration of any ground motion [s],
amplitude of a pulse and peak of a scaled record [g], size of a request's JSON body [bytes],
uploaded files kept [-] and their total size [bytes] (the oldest are deleted first), and pulse
durations and amplitudes of a failure domain [-]."""

TOKEN = re.compile(r"^[0-9a-f]{16}$")


def _with_path(spec, key: str) -> tuple[dict, dict | None]:
    """``(spec with the file under key as its path, the file)``: a resolved upload is
    ``{"path", "name"}`` (:meth:`Uploads.resolve`)."""
    file = spec.get(key) if isinstance(spec, dict) else None
    if not file:
        return spec, None
    if not isinstance(file, dict):
        raise ValueError(f"{key}: not the token of an uploaded file: {file!r}")
    return {**spec, key: file["path"]}, file


def _file_message(message: str, file: dict | None) -> str:
    """A message of the library about a file, naming the file as the user named it."""
    if file:
        message = message.replace(file["path"], file["name"])
    return message


def structure_from_spec(spec: dict):
    """The structure of a description (the arch after its irregular draw, if any) and the
    arch before it.

    Parameters
    ----------
    spec : dict
        The fields of a :class:`~archquake.geometry.StructureSpec`; ``geometry``, when given,
        is ``{"path": ..., "name": ...}`` (:meth:`Uploads.resolve`).

    Returns
    -------
    (BlockArch, BlockArch) or (BlockAssembly, BlockAssembly)
        ``(nominal, structure)`` (:meth:`~archquake.geometry.StructureSpec.arches`): a
        :class:`~archquake.geometry.BlockAssembly` for several spans, several rings or a file
        of one (:func:`is_assembly`).

    Raises
    ------
    ValueError
        The library's message for the same values, naming the field; or when the structure
        has more blocks than ``LIMITS["blocks"]``.
    """
    from ..geometry import StructureSpec

    data, file = _with_path(spec, "geometry")
    voussoirs = spec.get("voussoirs") if isinstance(spec, dict) else None
    if voussoirs not in (None, "") and _number(voussoirs) > LIMITS["blocks"]:
        raise ValueError(f"voussoirs must be at most {LIMITS['blocks']} on this page (the "
                         f"command line takes more), got {voussoirs}")
    try:
        described = StructureSpec.from_dict(data)
        _check_copies(described)
        nominal, structure = described.arches()
    except ValueError as exc:
        raise ValueError(_file_message(str(exc), file)) from None
    blocks = structure.n_blocks if is_assembly(structure) else structure.n_voussoirs
    if blocks > LIMITS["blocks"]:
        raise ValueError(f"the structure has {blocks} blocks (voussoirs and pier courses); "
                         f"this page takes at most {LIMITS['blocks']}")
    return nominal, structure


ASSEMBLY_UNAVAILABLE = {
    "four-link": "the four-link model is the four-hinge mechanism of one chain of voussoirs; "
                 "a structure of several spans or rings is a block assembly: its time history "
                 "is the rigid blocks' (archquake rigid-blocks --spans 3 --piers 3,6 on the "
                 "command line)",
}
"""What the page says of its parts that need one chain of voussoirs when the structure is a block
assembly (several spans, several rings, a file of one), by part: the four-link model's time
history and failure domain (the rigid blocks' are drawn alone, as ``archquake domain --model
rigid-blocks`` gives them; the code check takes the linear route alone, and the assessment
report is that of :mod:`archquake.report.assess.assembly`)."""


def is_assembly(structure) -> bool:
    """Whether ``structure`` is a :class:`~archquake.geometry.BlockAssembly` (several spans,
    several rings, a file of one) rather than one chain of voussoirs."""
    return hasattr(structure, "interfaces") and hasattr(structure, "polygons")


def _check_copies(spec) -> None:
    """Refuse, before it is built, a structure of more spans or rings than the page takes: at
    least a voussoir of every ring of every span is a block (``LIMITS["blocks"]``)."""
    voussoirs = spec.voussoirs or 7
    for name in ("spans", "rings"):
        copies = getattr(spec, name) or 1
        if copies * voussoirs > LIMITS["blocks"]:
            raise ValueError(f"{name} {copies} of {voussoirs} voussoirs make more than "
                             f"{LIMITS['blocks']} blocks, the most this page takes (the command "
                             f"line takes more)")


def _number(value) -> float:
    try:
        return float(value)
    except (TypeError, ValueError):
        return math.nan


def motion_from_spec(spec: dict):
    """The ground motion of a description (its warnings dropped: :func:`motion_and_warnings`
    keeps them).

    Parameters
    ----------
    spec : dict
        The fields of a :class:`~archquake.ground_motion.MotionSpec`: ``motion``,
        ``amplitude`` [g], ``duration`` [s], ``cycles``, ``params`` ``{name: value}``,
        ``record`` (``{"path", "name"}``, :meth:`Uploads.resolve`), or ``suite`` and
        ``suite_record`` (its index), ``scale_to`` [g], ``reverse``.

    Returns
    -------
    GroundMotion

    Raises
    ------
    ValueError
        As :func:`motion_and_warnings`.
    """
    return motion_and_warnings(spec)[0]


def motion_and_warnings(spec: dict, *, page_peak: bool = True):
    """The ground motion of a description and the library's warnings about it (a record whose
    peak is implausible in g, likely in cm/s^2 or m/s^2), for the page to show.

    The page's limits come on top of the library's (which the command line applies): the
    motion lasts at most ``LIMITS["motion_duration"]``, a record has at most
    ``LIMITS["record_samples"]``, and the peak of a pulse, of a scaled record and of any record,
    uploaded or of a suite, as it shakes the structure is at most ``LIMITS["amplitude_g"]``.

    Parameters
    ----------
    spec : dict
        As :func:`motion_from_spec` takes it.
    page_peak : bool
        Refuse a peak above ``LIMITS["amplitude_g"]`` (an uploaded record is read without, as it
        may be scaled when it is used).

    Returns
    -------
    (GroundMotion, list of str)
        The motion and the warnings' messages, which name a file as the user did.

    Raises
    ------
    ValueError
        The library's message for the same values, naming the field; for a motion longer than
        ``LIMITS["motion_duration"]``, or stronger than ``LIMITS["amplitude_g"]``.
    """
    import warnings

    from ..geometry import GRAVITY
    from ..ground_motion import LINEAR, MotionSpec

    data, file = _with_path(spec, "record")
    if isinstance(spec, dict):
        for name in ("amplitude", "scale_to"):
            if abs(_number(spec.get(name))) > LIMITS["amplitude_g"]:
                raise ValueError(f"{name} must be within +-{LIMITS['amplitude_g']:g} g on this "
                                 f"page, got {spec.get(name)}")
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            motion = MotionSpec.from_dict(data).build()
    except ValueError as exc:
        raise ValueError(_file_message(str(exc), file)) from None
    said = [_file_message(str(w.message), file) for w in caught]
    if not motion.duration <= LIMITS["motion_duration"]:
        raise ValueError(f"the ground motion lasts {motion.duration:.4g} s; this page takes at "
                         f"most {LIMITS['motion_duration']:g} s")
    if motion.times.size > LIMITS["record_samples"]:
        raise ValueError(f"the record has {motion.times.size} samples; this page takes at most "
                         f"{LIMITS['record_samples']}")
    if page_peak and motion.kind == LINEAR:
        peak = float(abs(motion.values).max()) / GRAVITY
        if not peak <= LIMITS["amplitude_g"]:
            raise ValueError(f"the ground motion's peak acceleration is {peak:.4g} g; this page "
                             f"takes at most {LIMITS['amplitude_g']:g} g (give scale_to, the "
                             f"peak to scale the record to, or check that its values are in g)")
    return motion, list(dict.fromkeys(said))


SITE_FIELDS = ("ag", "f0", "tc_star", "soil", "topography", "knowledge_level", "slc_ag",
               "slc_f0", "slc_tc_star")
"""The fields of a site on the page: the NTC 2018 spectrum of the SLV action (``ag`` [g], ``f0``
[-], ``tc_star`` [s], ``soil`` A-E, ``topography`` T1-T4), the structure's knowledge level
(LC1-LC3), and, optionally, the SLC action's ``slc_ag``, ``slc_f0``, ``slc_tc_star`` on the
same soil and topography."""

_SLC = ("slc_ag", "slc_f0", "slc_tc_star")


def site_from_spec(spec: dict):
    """The site's actions and the confidence factor of a description of the site.

    The spectra are NTC 2018's (§3.2.3.2, 5 % damping) and the check is Circolare 2019
    §C8.7.1's, as ``archquake check --code ntc2018`` makes it: the SLV action always, the SLC
    action when its three parameters are given.

    Parameters
    ----------
    spec : dict
        The fields of :data:`SITE_FIELDS` (numbers, or the text of numbers).

    Returns
    -------
    (list of SiteAction, float)
        The actions (:class:`~archquake.site.local_mechanism.SiteAction`, SLV first) and the
        confidence factor :math:`F_C` [-] of the knowledge level (default LC1).

    Raises
    ------
    ValueError
        The library's message, naming the field (``ag``, ``f0``, ``tc_star``, ``soil``,
        ``topography``, ``knowledge_level``; ``slc_ag`` ... for the SLC action's); for an
        unknown field, a missing one, or the SLC action given in part.
    """
    from ..site.local_mechanism import SiteAction, confidence_factor
    from ..site.spectra import ntc2018_spectrum

    if not isinstance(spec, dict):
        raise ValueError(f"the site must be a JSON object of {', '.join(SITE_FIELDS)}")
    unknown = sorted(set(spec) - set(SITE_FIELDS))
    if unknown:
        raise ValueError(f"unknown site field(s) {unknown}; the site's fields are "
                         f"{', '.join(SITE_FIELDS)}")
    for name, what in (("ag", "a_g [g]"), ("f0", "F0 [-]"), ("tc_star", "Tc* [s]")):
        if _blank(spec.get(name)):
            raise ValueError(f"{name} must be given: the site's {what} at SLV")
    soil = "A" if _blank(spec.get("soil")) else spec["soil"]
    topography = "T1" if _blank(spec.get("topography")) else spec["topography"]
    level = None if _blank(spec.get("knowledge_level")) else spec["knowledge_level"]
    fc = confidence_factor(level)
    actions = [SiteAction.of("SLV", ntc2018_spectrum(spec["ag"], spec["f0"], spec["tc_star"],
                                                     soil, topography))]
    given = [name for name in _SLC if not _blank(spec.get(name))]
    if given and len(given) < len(_SLC):
        missing = [name for name in _SLC if name not in given]
        raise ValueError(f"{', '.join(given)} needs {', '.join(missing)} too (the SLC action "
                         "is a spectrum of its own: a_g, F0 and Tc*)")
    if given:
        try:
            slc = ntc2018_spectrum(spec["slc_ag"], spec["slc_f0"], spec["slc_tc_star"], soil,
                                   topography)
        except ValueError as exc:  # the library names ag, f0 or tc_star first
            text = str(exc)
            name = text.split(" ", 1)[0]
            raise ValueError(f"slc_{text}" if f"slc_{name}" in _SLC else text) from None
        actions.append(SiteAction.of("SLC", slc))
    return actions, fc


def _blank(value) -> bool:
    return value is None or (isinstance(value, str) and not value.strip())


def suites() -> list[dict]:
    """The built-in record suites and their records, if the ``records`` extra is installed.

    Returns
    -------
    list of dict
        ``name``, ``description`` and ``records`` (the name of every ground motion, in the
        suite's order); empty without the extra.
    """
    from ..ground_motion import BUILTIN_SUITES

    out = []
    for name, suite in BUILTIN_SUITES.items():
        try:
            records = [r.name for r in _suite_records(name)]
        except ImportError:
            return []
        out.append({"name": name, "description": suite.description, "records": records})
    return out


def _suite_records(name: str):
    from ..ground_motion import builtin_suite

    return builtin_suite(name)


class Uploads:
    """Uploaded files in the server's temporary folder, by random token.

    Parameters
    ----------
    folder : pathlib.Path
        The folder (created if missing); nothing is written elsewhere.
    keep : int
        Files kept: the oldest is deleted when one more is uploaded.
    keep_bytes : int
        Their total size [bytes]: the oldest are deleted (never the newest) until the files
        kept are within it.
    """

    KINDS = {"geometry": (".json",), "record": (".at2", ".csv", ".asc")}
    """Kinds of upload and the file extensions each takes."""

    def __init__(self, folder: Path, keep: int = LIMITS["uploads"],
                 keep_bytes: int = LIMITS["uploads_bytes"]):
        self.folder = Path(folder)
        self.folder.mkdir(parents=True, exist_ok=True)
        self.keep = keep
        self.keep_bytes = keep_bytes
        self._files: OrderedDict[str, dict] = OrderedDict()
        self._lock = threading.Lock()

    def save(self, kind: str, name: str, data: bytes) -> dict:
        """Keep an uploaded file.

        Parameters
        ----------
        kind : {"geometry", "record"}
            What the file holds.
        name : str
            Its name on the user's machine (only its last part is kept, for messages).
        data : bytes
            Its content.

        Returns
        -------
        dict
            ``{"token", "kind", "name", "path", "bytes"}``.

        Raises
        ------
        ValueError
            For an unknown kind, or an extension the kind does not take.
        """
        if kind not in self.KINDS:
            raise ValueError(f"kind must be one of {list(self.KINDS)}, got {kind!r}")
        shown = PurePath(str(name).replace("\\", "/")).name[-120:] or f"{kind} file"
        suffix = PurePath(shown).suffix.lower()
        if suffix not in self.KINDS[kind]:
            raise ValueError(f"{shown!r}: a {kind} file is one of "
                             f"{', '.join(self.KINDS[kind])}")
        token = secrets.token_hex(8)
        path = self.folder / f"{kind}-{token}{suffix}"
        path.write_bytes(data)
        entry = {"token": token, "kind": kind, "name": shown, "path": str(path),
                 "bytes": len(data)}
        with self._lock:
            self._files[token] = entry
            while len(self._files) > 1 and (
                    len(self._files) > self.keep
                    or sum(e["bytes"] for e in self._files.values()) > self.keep_bytes):
                _, old = self._files.popitem(last=False)
                Path(old["path"]).unlink(missing_ok=True)
        return entry

    def forget(self, token: str) -> None:
        """Delete an uploaded file (one the server refused)."""
        with self._lock:
            entry = self._files.pop(token, None)
        if entry is not None:
            Path(entry["path"]).unlink(missing_ok=True)

    def file(self, token, kind: str) -> dict:
        """``{"path", "name"}`` of the file of ``token``.

        Raises
        ------
        ValueError
            For a token that names no file of this kind (or one no longer kept).
        """
        if not isinstance(token, str) or not TOKEN.match(token):
            raise ValueError(f"{kind}: not the token of an uploaded file: {token!r}")
        with self._lock:
            entry = self._files.get(token)
        if entry is None or entry["kind"] != kind:
            raise ValueError(f"the uploaded {kind} file is no longer kept by the server: upload "
                             f"it again")
        return {"path": entry["path"], "name": entry["name"]}

    def resolve(self, spec: dict, key: str, kind: str) -> dict:
        """``spec`` with the token under ``key`` replaced by ``{"path", "name"}`` of its file."""
        if not isinstance(spec, dict) or not spec.get(key):
            return spec
        return {**spec, key: self.file(spec[key], kind)}


def check_geometry_file(entry: dict):
    """The structure of an uploaded geometry file, checked as ``archquake limit --geometry``
    checks it; the message names the file as the user did.

    Returns
    -------
    BlockArch or BlockAssembly

    Raises
    ------
    ValueError
        The command line's message for the same file.
    """
    return structure_from_spec({"geometry": {"path": entry["path"], "name": entry["name"]}})[1]


def check_record_file(entry: dict) -> dict:
    """A summary of an uploaded record (its duration, samples and peak) and the warnings about
    it, read as ``archquake simulate --record`` reads it.

    Returns
    -------
    dict
        ``name``, ``duration`` [s], ``samples`` [-], ``pga_g`` [g] and ``warnings`` (the
        library's, naming the file as the user did; and the page's when the peak is more than it
        takes unscaled).

    Raises
    ------
    ValueError
        The command line's message for the same file, or one of the page's limits.
    """
    from ..geometry import GRAVITY

    motion, said = motion_and_warnings({"record": {"path": entry["path"],
                                                   "name": entry["name"]}}, page_peak=False)
    pga = float(abs(motion.values).max() / GRAVITY)
    if pga > LIMITS["amplitude_g"]:
        said.append(f"its peak acceleration {pga:.4g} g is more than the "
                    f"{LIMITS['amplitude_g']:g} g this page shakes a structure with: give a "
                    f"peak to scale it to (scale_to)")
    return {"name": entry["name"], "duration": float(motion.duration),
            "samples": int(motion.times.size), "pga_g": pga, "warnings": said}


__all__ = ["ASSEMBLY_UNAVAILABLE", "LIMITS", "SITE_FIELDS", "Uploads", "check_geometry_file",
           "check_record_file",
           "is_assembly", "motion_and_warnings", "motion_from_spec",
           "site_from_spec", "structure_from_spec", "suites"]
