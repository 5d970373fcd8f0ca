"""Saving and loading study results: a tidy table (Parquet and CSV) beside a JSON summary.

A study directory written by :func:`save_study` holds

``results.parquet``
    the tidy table, one row per analysis (exact dtypes; the file to load);
``results.csv``
    the same table as text, for spreadsheets and other tools;
``summary.json``
    the metadata of the study (settings, seed, chunking, ``archquake_version``, timings), the
    columns and number of rows of the table, and a free ``summary`` dictionary (e.g. fitted
    fragility parameters). It is written last, so its presence means the table files are complete.

Every file is written atomically: the content goes to a temporary file in the same directory,
which is flushed to disk and then renamed over the target (:func:`os.replace`), so a reader or an
interrupted writer never sees a half-written file -- only the old file or the new one.

The other tables archquake writes as CSV live here too: :func:`write_csv` (any table; the
``curves.csv`` and ``incremental.csv`` of the studies), and the time histories of one analysis,
:func:`write_history_csv` (the four-link model) and :func:`write_block_history_csv` (the
rigid-block model). Text written into a CSV cell (a record's file name) is never read by a
spreadsheet as a formula (:func:`spreadsheet_text`).
"""

from __future__ import annotations

import json
import os
import secrets
from collections.abc import Iterator, Mapping
from contextlib import contextmanager, suppress
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from ._version import __version__
from .checks import json_dumps, json_loads

RESULTS_PARQUET = "results.parquet"
"""File name of the tidy table in Parquet, in a study directory (the file to load)."""
RESULTS_CSV = "results.csv"
"""File name of the tidy table as CSV text, in a study directory."""
SUMMARY_JSON = "summary.json"
"""File name of the JSON summary of a study, written last."""
TABLE_FORMATS = ("parquet", "csv")
"""Formats of the tidy table that :func:`save_study` can write."""

# pandas >= 3 parses floats exactly by default (and deprecates the option); before, ask for it.
_EXACT_FLOATS = {} if int(pd.__version__.split(".")[0]) >= 3 else {"float_precision": "round_trip"}

SUMMARY_FORMAT = "archquake-study-results"
"""Value of the ``format`` key of a summary, by which :func:`load_study` recognises one."""
SUMMARY_FORMAT_VERSION = 1
"""Version of the summary's layout, checked by :func:`load_study`."""


@contextmanager
def atomic_path(path: str | os.PathLike) -> Iterator[Path]:
    """Path of a temporary file that replaces ``path`` only if the ``with`` block succeeds.

    The temporary file lives in the same directory as ``path`` (so the final :func:`os.replace`
    is an atomic rename on the same file system), is hidden (its name starts with a dot) and ends
    in ``.tmp``. It is created like any new file, with the permissions the umask leaves of
    ``rw-rw-rw-`` (not the owner-only ones of :func:`tempfile.mkstemp`). On success it is
    flushed to disk and renamed to ``path``; on any exception (including ``KeyboardInterrupt``)
    it is removed and ``path`` is left untouched.

    Parameters
    ----------
    path : str or os.PathLike
        Final location of the file. Its directory must exist.

    Yields
    ------
    pathlib.Path
        The temporary file to write (it exists and is empty).
    """
    path = Path(path)
    for _ in range(100):
        tmp = path.parent / f".{path.name}.{secrets.token_hex(6)}.tmp"
        try:  # O_EXCL: a new file of our own; mode 0o666 less the umask, as open() gives
            os.close(os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666))
            break
        except FileExistsError:
            continue
    else:  # pragma: no cover - a hundred random names taken
        raise FileExistsError(f"no free temporary name beside {path}")
    try:
        yield tmp
        with open(tmp, "rb+") as f:
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except BaseException:
        with suppress(FileNotFoundError):
            tmp.unlink()
        raise


FORMULA_PREFIXES = ("=", "+", "-", "@", "\t", "\r")
"""First characters that make a spreadsheet read a CSV cell as a formula (OWASP's list: a tab
or a carriage return first is read so by some)."""


def spreadsheet_text(text: str) -> str:
    """``text`` as a CSV cell that no spreadsheet reads as a formula.

    A text that starts with one of :data:`FORMULA_PREFIXES` (a record named ``=cmd|...``, or
    ``-RSN6.AT2``) gets a single quote in front, which spreadsheets show as text; so does a text
    that already starts with single quotes followed by one of them, so that
    :func:`read_spreadsheet_text` returns every text exactly as it was.

    Parameters
    ----------
    text : str
        The text of a cell.

    Returns
    -------
    str
        The text to write.

    Examples
    --------
    >>> spreadsheet_text("=1+1"), spreadsheet_text("RSN6.AT2")
    ("'=1+1", 'RSN6.AT2')
    """
    return "'" + text if text.lstrip("'")[:1] in FORMULA_PREFIXES else text


def read_spreadsheet_text(text: str) -> str:
    """The text that :func:`spreadsheet_text` wrote as ``text`` (its inverse)."""
    if text[:1] == "'" and text.lstrip("'")[:1] in FORMULA_PREFIXES:
        return text[1:]
    return text


def _is_text(column: pd.Series) -> bool:
    return pd.api.types.is_object_dtype(column.dtype) or pd.api.types.is_string_dtype(column.dtype)


def write_csv(path: str | os.PathLike, table: pd.DataFrame) -> Path:
    """Write ``table`` to ``path`` as CSV, without its index, atomically (:func:`atomic_path`).

    Text cells that a spreadsheet would read as a formula are written as text
    (:func:`spreadsheet_text`); :func:`load_study` reads them back as they were.

    Parameters
    ----------
    path : str or os.PathLike
        The file; its directory must exist.
    table : pandas.DataFrame
        The table.

    Returns
    -------
    pathlib.Path
        ``path``.

    Raises
    ------
    OSError
        If the file cannot be written.
    """
    safe = table.copy(deep=False)
    for name in table.columns:
        if _is_text(table[name]):
            safe[name] = table[name].map(
                lambda cell: spreadsheet_text(cell) if isinstance(cell, str) else cell)
    with atomic_path(path) as tmp:
        safe.to_csv(tmp, index=False)
    return Path(path)


def write_history_csv(history, path: str | os.PathLike) -> Path:
    """Write a time history of the four-link model as CSV (what ``archquake simulate --output``
    writes).

    One row per recorded instant: ``t_s`` [s], ``phi_rad`` [rad] (+ Mech-l, - Mech-r),
    ``theta_dot_rad_s`` [rad/s] and ``mechanism`` (``l``, ``r`` or ``rest``); the floats are
    written with all their digits (``repr``), so the file reads back as the same numbers.

    Parameters
    ----------
    history : archquake.fourlink.time_history.TimeHistory
        The time history (``t``, ``phi``, ``mechanism`` and the ``segments`` with their
        ``theta_dot``).
    path : str or os.PathLike
        The file, written atomically (:func:`atomic_path`); its directory must exist.

    Returns
    -------
    pathlib.Path
        ``path``.

    Raises
    ------
    OSError
        If the file cannot be written.
    """
    theta_dot = np.concatenate([s.theta_dot for s in history.segments])
    table = np.column_stack([history.t, history.phi, theta_dot])
    with atomic_path(path) as tmp, open(tmp, "w") as fh:
        fh.write("t_s,phi_rad,theta_dot_rad_s,mechanism\n")
        for (t, phi, thd), mech in zip(table.tolist(), history.mechanism, strict=True):
            fh.write(f"{t!r},{phi!r},{thd!r},{mech}\n")  # Python floats: exact text
    return Path(path)


def write_block_history_csv(history, path: str | os.PathLike) -> Path:
    """Write a time history of the rigid-block model as CSV (what
    ``archquake rigid-blocks --output`` writes).

    One row per time step: ``t_s`` [s], ``crown_drop_m`` [m], the energies ``kinetic_J_m``,
    ``potential_J_m``, ``dissipated_J_m`` and ``input_J_m`` [J/m], every block's ``x{i}_m``,
    ``y{i}_m`` [m] and ``rotation{i}_rad`` [rad], and every joint's ``opening{j}_m`` and
    ``slip{j}_m`` [m]; the floats with all their digits (``repr``).

    Parameters
    ----------
    history : archquake.rigid_blocks.BlockHistory
        The time history.
    path : str or os.PathLike
        The file, written atomically (:func:`atomic_path`); its directory must exist.

    Returns
    -------
    pathlib.Path
        ``path``.

    Raises
    ------
    OSError
        If the file cannot be written.
    """
    nb, nj = history.assembly.n_blocks, history.assembly.n_joints
    columns = {"t_s": history.times, "crown_drop_m": history.crown_drop,
               "kinetic_J_m": history.kinetic_energy, "potential_J_m": history.potential_energy,
               "dissipated_J_m": history.dissipated_energy, "input_J_m": history.input_work}
    for i in range(nb):
        columns[f"x{i}_m"] = history.displacements[:, i, 0]
        columns[f"y{i}_m"] = history.displacements[:, i, 1]
        columns[f"rotation{i}_rad"] = history.rotations[:, i]
    for j in range(nj):
        columns[f"opening{j}_m"] = history.openings[:, j]
        columns[f"slip{j}_m"] = history.slips[:, j]
    table = np.column_stack(list(columns.values()))
    with atomic_path(path) as tmp, open(tmp, "w") as fh:
        fh.write(",".join(columns) + "\n")
        for row in table:
            fh.write(",".join(repr(float(x)) for x in row) + "\n")
    return Path(path)


def to_json_text(obj: Any) -> str:
    """Strict JSON text of ``obj`` (:func:`archquake.checks.json_dumps`): numpy scalars and
    arrays become numbers and lists, nan and infinities ``null`` (never ``NaN``, which strict
    readers refuse).
    """
    return json_dumps(obj, indent=2) + "\n"


def write_json(path: str | os.PathLike, obj: Any) -> Path:
    """Write ``obj`` as JSON to ``path`` atomically (see :func:`atomic_path`); return the path."""
    text = to_json_text(obj)  # serialise first: a TypeError must not leave a temporary file
    with atomic_path(path) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return Path(path)


def read_json(path: str | os.PathLike) -> Any:
    """Read a JSON file written by :func:`write_json`; a damaged file is a ValueError that
    names it."""
    path = Path(path)
    try:
        # NaN allowed: files of earlier versions hold it where a number was missing
        return json_loads(path.read_text(encoding="utf-8"), allow_nan=True)
    except UnicodeDecodeError as exc:
        raise ValueError(f"{path} is not valid JSON: not UTF-8 text (byte {exc.start})") from exc
    except json.JSONDecodeError as exc:
        raise ValueError(f"{path} is not valid JSON: {exc.msg} (line {exc.lineno})") from exc
    except ValueError as exc:
        raise ValueError(f"{path} is not valid JSON: {exc}") from exc


@dataclass(frozen=True, eq=False)
class StoredStudy:
    """A study loaded from disk by :func:`load_study`.

    Attributes
    ----------
    table : pandas.DataFrame
        The tidy table, one row per analysis; ``table.attrs["study"]`` is ``metadata``.
    metadata : dict
        Settings, seed, chunking, ``archquake_version`` and timings of the study.
    summary : dict
        The free summary dictionary passed to :func:`save_study` (empty if none).
    directory : pathlib.Path
        The study directory.
    """

    table: pd.DataFrame = field(repr=False)
    metadata: dict
    summary: dict
    directory: Path


def save_study(
    out_dir: str | os.PathLike,
    table: pd.DataFrame,
    *,
    metadata: Mapping[str, Any] | None = None,
    summary: Mapping[str, Any] | None = None,
    formats: tuple[str, ...] = TABLE_FORMATS,
) -> Path:
    """Save a tidy table and its JSON summary in a study directory.

    Parameters
    ----------
    out_dir : str or os.PathLike
        Study directory; created if missing. Existing result files in it are replaced.
    table : pandas.DataFrame
        Tidy table, one row per analysis, with string column names. The index is not saved.
    metadata : mapping, optional
        Settings, seed, timings, ... of the study (JSON-serialisable). Default:
        ``table.attrs["study"]`` as set by :func:`archquake.execution.run_study`, or empty.
        ``archquake_version`` is added if missing.
    summary : mapping, optional
        Free JSON-serialisable summary of the results (e.g. fitted fragility parameters).
    formats : tuple of str, optional
        Table formats to write, among ``("parquet", "csv")``; :func:`load_study` reads
        Parquet when present, else CSV.

    Returns
    -------
    pathlib.Path
        Path of ``summary.json``.

    Raises
    ------
    ValueError
        If ``table`` is not a DataFrame, a column name is not a string, ``formats`` is empty or
        names an unknown format, or ``metadata`` / ``summary`` is not JSON-serialisable.
    """
    if not isinstance(table, pd.DataFrame):
        raise ValueError(f"table must be a pandas.DataFrame, got {type(table).__name__}")
    bad = [c for c in table.columns if not isinstance(c, str)]
    if bad:
        raise ValueError(f"table column names must be strings, got {bad!r}")
    formats = tuple(formats)
    unknown = [f for f in formats if f not in TABLE_FORMATS]
    if not formats or unknown:
        raise ValueError(f"formats must be a non-empty subset of {TABLE_FORMATS}, got {formats!r}")
    if metadata is None:
        metadata = table.attrs.get("study", {})
    metadata = dict(metadata)
    metadata.setdefault("archquake_version", __version__)
    summary = dict(summary or {})
    record = {
        **metadata,
        "format": SUMMARY_FORMAT,
        "format_version": SUMMARY_FORMAT_VERSION,
        "rows": len(table),
        "columns": {name: str(dtype) for name, dtype in table.dtypes.items()},
        "files": [{"parquet": RESULTS_PARQUET, "csv": RESULTS_CSV}[f] for f in formats],
        "summary": summary,
    }
    try:
        text = to_json_text(record)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"metadata and summary must be JSON-serialisable: {exc}") from exc

    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    plain = table.reset_index(drop=True)
    plain.attrs = {}  # the metadata lives in summary.json, not inside the table files
    summary_path = out_dir / SUMMARY_JSON
    # An existing summary.json would vouch for table files that are about to change: remove it
    # first, write the tables, then the new summary last.
    with suppress(FileNotFoundError):
        summary_path.unlink()
    if "parquet" in formats:
        with atomic_path(out_dir / RESULTS_PARQUET) as tmp:
            plain.to_parquet(tmp, engine="pyarrow", index=False)
    if "csv" in formats:
        write_csv(out_dir / RESULTS_CSV, plain)
    with atomic_path(summary_path) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return summary_path


def load_study(out_dir: str | os.PathLike) -> StoredStudy:
    """Load a study saved by :func:`save_study` (or :func:`archquake.execution.run_study`).

    Parameters
    ----------
    out_dir : str or os.PathLike
        Study directory.

    Returns
    -------
    StoredStudy
        The table (from ``results.parquet``, else ``results.csv``), metadata and summary.

    Raises
    ------
    ValueError
        If the directory holds no complete results (no ``summary.json``, e.g. an interrupted
        study: run it again with ``resume=True``) or the files are inconsistent.
    """
    out_dir = Path(out_dir)
    summary_path = out_dir / SUMMARY_JSON
    if not summary_path.is_file():
        raise ValueError(
            f"{out_dir} holds no complete study results (missing {SUMMARY_JSON}); if the study "
            "was interrupted, run it again with resume=True (--resume)"
        )
    record = read_json(summary_path)
    if not isinstance(record, dict) or record.get("format") != SUMMARY_FORMAT:
        raise ValueError(f"{summary_path} is not an archquake results summary")
    files = record.get("files", [])
    columns = record.get("columns", {})
    try:
        if RESULTS_PARQUET in files:
            path = out_dir / RESULTS_PARQUET
            table = pd.read_parquet(path, engine="pyarrow")
        elif RESULTS_CSV in files:
            path = out_dir / RESULTS_CSV
            dtypes = {c: d for c, d in columns.items() if d != "object"}
            table = pd.read_csv(path, dtype=dtypes, keep_default_na=False, na_values=[""],
                                **_EXACT_FLOATS)
            for name in table.columns:
                if _is_text(table[name]):
                    table[name] = table[name].map(
                        lambda cell: read_spreadsheet_text(cell) if isinstance(cell, str)
                        else cell)
        else:
            raise ValueError(f"{summary_path} lists no table file")
    except (OSError, ValueError) as exc:  # pyarrow's errors are ValueErrors or OSErrors
        if str(summary_path) in str(exc):
            raise
        raise ValueError(f"{path} cannot be read ({type(exc).__name__}: {exc}); if the study's "
                         f"chunks are kept, rerun it with resume=True (--resume) to write it "
                         f"again") from exc
    if list(table.columns) != list(columns) or len(table) != record.get("rows"):
        raise ValueError(
            f"the table in {out_dir} does not match {SUMMARY_JSON} "
            f"(columns {list(table.columns)} vs {list(columns)}, rows {len(table)} vs "
            f"{record.get('rows')})"
        )
    summary = record.pop("summary", {})
    for key in ("format", "format_version", "rows", "columns", "files"):
        record.pop(key, None)
    table.attrs["study"] = record
    return StoredStudy(table=table, metadata=record, summary=summary, directory=out_dir)



# --------------------------------------------------------------------------------------------
# OpenQuake's NRML fragility model
# --------------------------------------------------------------------------------------------

NRML_NAMESPACE = "http://openquake.org/xmlns/nrml/0.5"
"""XML namespace of OpenQuake's NRML 0.5 (the fragility models of the OpenQuake engine)."""

OPENQUAKE_IMT = {"pga": ("PGA", 1.0), "pgv": ("PGV", 100.0), "pgd": ("PGD", 100.0),
                 "arias": ("IA", 1.0)}
"""archquake's intensity measure -> (OpenQuake's IMT, factor from archquake's unit to
OpenQuake's): PGA [g], PGV [cm/s], PGD [cm], IA [m/s]; ``sa(T)`` is ``SA(T)`` [g]
(:func:`openquake_imt`)."""


def openquake_imt(im_name: str) -> tuple[str, float]:
    """OpenQuake's name of an intensity measure and the factor that converts a value from
    archquake's unit to OpenQuake's (e.g. ``("PGV", 100.0)``: m/s to cm/s).

    Parameters
    ----------
    im_name : str
        archquake's name of the measure (:mod:`archquake.ground_motion.intensity`): ``pga``,
        ``pgv``, ``pgd``, ``arias`` or ``sa(T)`` with T the period [s] (case and spaces
        ignored).

    Returns
    -------
    imt : str
        OpenQuake's intensity measure type: ``PGA``, ``PGV``, ``PGD``, ``IA`` or ``SA(T)``.
    factor : float
        OpenQuake's value per archquake's value [-]: 1 for PGA and SA [g] and IA [m/s], 100
        for PGV [m/s -> cm/s] and PGD [m -> cm].

    Raises
    ------
    ValueError
        For a measure OpenQuake has no counterpart of (e.g. ``d5-95``).

    Examples
    --------
    >>> openquake_imt("pgv"), openquake_imt("SA(0.5)")
    (('PGV', 100.0), ('SA(0.5)', 1.0))
    """
    import re

    key = "".join(str(im_name).split()).lower()
    if key in OPENQUAKE_IMT:
        return OPENQUAKE_IMT[key]
    match = re.fullmatch(r"sa\(([^()]+)\)", key)
    if match:
        try:
            period = float(match.group(1))
        except ValueError:
            period = float("nan")
        if period > 0:
            return f"SA({period!r})", 1.0
    raise ValueError(f"intensity measure {im_name!r} has no OpenQuake counterpart; choose one "
                     f"of {', '.join(OPENQUAKE_IMT)} or sa(T)")


def lognormal_moments(median: float, dispersion: float) -> tuple[float, float]:
    r"""Mean and standard deviation (linear space) of a lognormal variable of ``median`` and
    logarithmic standard deviation ``dispersion``: OpenQuake's ``mean`` and ``stddev`` of a
    continuous ``logncdf`` fragility function.

    For :math:`\ln X \sim N(\ln\theta, \beta^2)`, the fragility function
    :math:`\Phi(\ln(x/\theta)/\beta)` is the CDF of :math:`X`, whose mean and standard deviation
    are

    .. math::

        m = \theta\, e^{\beta^2/2}, \qquad s = m \sqrt{e^{\beta^2} - 1},

    inverted by OpenQuake (``FragilityFunctionContinuous`` of ``openquake.risklib.scientific``
    [1]_) as

    .. math::

        \beta = \sqrt{\ln\left(1 + s^2/m^2\right)}, \qquad \theta = \frac{m^2}{\sqrt{m^2 + s^2}}.

    Parameters
    ----------
    median : float
        :math:`\theta` > 0 [the unit of the intensity measure].
    dispersion : float
        :math:`\beta` > 0 [-].

    Returns
    -------
    mean, stddev : float
        :math:`m` and :math:`s` [the unit of ``median``].

    Raises
    ------
    ValueError
        If ``median`` or ``dispersion`` is not a finite number > 0.

    References
    ----------
    .. [1] GEM Foundation. The OpenQuake engine: continuous fragility functions
       (``format="continuous"``, ``shape="logncdf"``) of NRML 0.5 fragility models.

    Examples
    --------
    >>> import math
    >>> m, s = lognormal_moments(0.5, 0.4)
    >>> round(m**2 / (m**2 + s**2) ** 0.5, 12), round(math.sqrt(math.log(1 + s**2 / m**2)), 12)
    (0.5, 0.4)
    """
    import math

    median, dispersion = float(median), float(dispersion)
    if not (math.isfinite(median) and median > 0 and math.isfinite(dispersion)
            and dispersion > 0):
        raise ValueError(f"a lognormal needs median > 0 and dispersion > 0, got {median!r}, "
                         f"{dispersion!r}")
    mean = median * math.exp(0.5 * dispersion * dispersion)
    return mean, mean * math.sqrt(math.expm1(dispersion * dispersion))


def write_fragility_nrml(path: str | os.PathLike, functions, *, im: str, min_iml: float,
                         max_iml: float, model_id: str = "archquake",
                         description: str = "archquake fragility model",
                         limit_state: str = "collapse", asset_category: str = "building",
                         loss_category: str = "structural") -> Path:
    """Write lognormal fragility functions as an OpenQuake NRML 0.5 fragility model.

    Each function is a ``fragilityFunction`` of ``format="continuous" shape="logncdf"`` with one
    limit state; OpenQuake takes its ``mean`` and ``stddev`` as those of the intensity
    measure's lognormal distribution in linear space (:func:`lognormal_moments`), in its own
    units (:func:`openquake_imt`), and clips the intensity to ``[minIML, maxIML]`` [1]_. The
    file reads back with OpenQuake's ``openquake.hazardlib.nrml.to_python`` (checked by the test
    suite when OpenQuake is installed).

    Parameters
    ----------
    path : str or os.PathLike
        The XML file (written atomically).
    functions : sequence of (str, float, float)
        ``(id, median, dispersion)`` of each function: an id (OpenQuake's taxonomy: no ``#``,
        ``'`` or ``"``), the median [archquake's unit of ``im``] and the dispersion beta [-].
    im : str
        archquake's intensity measure (``pga``, ``pgv``, ``pgd``, ``arias``, ``sa(T)``).
    min_iml, max_iml : float
        Range of intensities the functions were fitted on [archquake's unit of ``im``].
    model_id, description, limit_state, asset_category, loss_category : str
        Attributes of the fragility model.

    Returns
    -------
    pathlib.Path
        ``path``.

    Raises
    ------
    ValueError
        If there is no function, an id is empty or holds ``#``, ``'`` or ``"``, the range is
        not ``0 < min_iml < max_iml``, a median or dispersion is not > 0, or ``im`` has no
        OpenQuake counterpart.

    References
    ----------
    .. [1] GEM Foundation. The OpenQuake engine: NRML 0.5 fragility models
       (``fragilityModel``, continuous ``logncdf`` fragility functions).
    """
    import xml.etree.ElementTree as ET

    imt, factor = openquake_imt(im)
    functions = list(functions)
    if not functions:
        raise ValueError("no fragility function to write")
    if not (0 < float(min_iml) < float(max_iml)):
        raise ValueError(f"need 0 < min_iml < max_iml, got {min_iml!r}, {max_iml!r}")
    for ident, *_ in functions:
        if not ident or any(c in str(ident) for c in "#'\""):
            raise ValueError(f"fragility function id {ident!r} must be non-empty without # ' \"")

    def tag(name):
        return f"{{{NRML_NAMESPACE}}}{name}"

    ET.register_namespace("", NRML_NAMESPACE)
    root = ET.Element(tag("nrml"))
    model = ET.SubElement(root, tag("fragilityModel"), id=model_id,
                          assetCategory=asset_category, lossCategory=loss_category)
    ET.SubElement(model, tag("description")).text = description
    ET.SubElement(model, tag("limitStates")).text = limit_state
    for ident, median, dispersion in functions:
        mean, stddev = lognormal_moments(float(median) * factor, dispersion)
        function = ET.SubElement(model, tag("fragilityFunction"), id=str(ident),
                                 format="continuous", shape="logncdf")
        ET.SubElement(function, tag("imls"), imt=imt, minIML=repr(float(min_iml) * factor),
                      maxIML=repr(float(max_iml) * factor))
        ET.SubElement(function, tag("params"), ls=limit_state, mean=repr(mean),
                      stddev=repr(stddev))
    ET.indent(root)
    text = ET.tostring(root, encoding="unicode", xml_declaration=False)
    path = Path(path)
    with atomic_path(path) as tmp:
        tmp.write_text('<?xml version="1.0" encoding="utf-8"?>\n' + text + "\n",
                       encoding="utf-8")
    return path
