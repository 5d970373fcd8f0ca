"""Recorded accelerograms: file formats and one record.

:func:`read_record` reads a recorded (or any tabulated) ground acceleration from a file, in one of
the formats of :data:`RECORD_FORMATS`, into a ``LINEAR`` ground motion
(:func:`~archquake.ground_motion.read_suite` of :mod:`~archquake.ground_motion.suites` reads a
folder or a list of files as a suite of records). Records come only from the user's files: nothing
is downloaded.

``csv``
    two columns, time [s] and acceleration [g], separated by a comma or by whitespace; lines
    starting with ``#`` are comments; the first non-comment line may be a header of column names
    (e.g. ``time_s,acc_g``).
``at2``
    the PEER NGA ``.AT2`` format: four header lines, the fourth giving the number of points and the
    time step (``NPTS=  5590, DT=   .0050 SEC``), then the accelerations [g], several per line,
    sampled at ``t_i = i DT``, ``i = 0 .. NPTS-1``.
``esm``
    the ASCII format of the Engineering Strong Motion database (ESM, esm-db.eu; header format
    "DYNA 1.2"): a header of ``KEY: value`` lines (64 of them in the database's files, from
    ``EVENT_NAME:`` to ``USER5:``), of which ``SAMPLING_INTERVAL_S`` (the time step [s]),
    ``NDATA`` (the number of samples), ``UNITS`` (``cm/s^2``, ``m/s^2`` or ``g``) and
    ``DATA_TYPE`` (must be ``ACCELERATION``) are read, then the NDATA accelerations, one (or
    several) per line, sampled at ``t_i = i SAMPLING_INTERVAL_S``.

Conventions for a record: times must start at or after 0 and increase strictly, by steps within
:data:`~archquake.defaults.RECORD_TIME_STEP_RANGE`, up to at most
:data:`~archquake.defaults.MAX_RECORD_DURATION`. Numbers are plain decimals (``1_0`` is refused,
not read as 10). A peak above :data:`~archquake.defaults.PLAUSIBLE_PEAK_G` is read with a warning
that names the likely unit (a CSV in cm/s^2 reads as hundreds of g); above
:data:`~archquake.defaults.MAX_ACCELERATION_G` it is refused. Files are UTF-8 (or ASCII) text;
UTF-16 with its byte-order mark is read too. If the first time
is after 0, a point ``(0, 0)`` is inserted, so the ground is at rest at ``t = 0`` and the
acceleration ramps linearly to the first sample (the ground is never moved before the record
starts). Between samples the acceleration is interpolated linearly, and the ground is still after
the last sample (``duration`` is the last time). Accelerations are converted to m/s^2 with
:data:`archquake.geometry.GRAVITY` (a record in cm/s^2 or m/s^2 is converted exactly).
"""

from __future__ import annotations

import math
import re
import warnings
from collections.abc import Callable
from pathlib import Path

import numpy as np

from ..constants import GRAVITY
from ..defaults import (
    MAX_ACCELERATION_G,
    MAX_RECORD_DURATION,
    MAX_RECORD_FILE_BYTES,
    PLAUSIBLE_PEAK_G,
    RECORD_TIME_STEP_RANGE,
)
from .core import LINEAR, GroundMotion, check_number, check_peak


def _record_error(path: Path, problem: str) -> ValueError:
    return ValueError(f"record file '{path}': {problem}")


def _parse_number(path: Path, cell: str, line_number: int, what: str) -> float:
    """``cell`` as a finite float, or a ValueError naming the file, the line and the cell."""
    try:
        if "_" in cell:  # float() reads "1_0" as 10
            raise ValueError(cell)
        value = float(cell)
    except ValueError:
        raise _record_error(
            path, f"line {line_number}: cannot read {what} {cell!r} as a number"
        ) from None
    if not math.isfinite(value):
        raise _record_error(path, f"line {line_number}: {what} {cell!r} is not a finite number")
    return value


def _split_cells(line: str) -> list[str]:
    """Cells of a CSV line: comma separated if it has a comma, else whitespace separated."""
    if "," in line:
        cells = [cell.strip() for cell in line.split(",")]
        while cells and cells[-1] == "":  # a trailing comma
            cells.pop()
        return cells
    return line.split()


def _is_number(cell: str) -> bool:
    try:
        float(cell.replace("_", "x"))
    except ValueError:
        return False
    return True


def parse_csv_record(path: str | Path) -> tuple[np.ndarray, np.ndarray]:
    """Times [s] and accelerations [g] of a two-column CSV record (see the module docstring).

    Every data line must hold exactly two numbers; the first non-comment line may instead be a
    header of column names (a line none of whose cells is a number). Times must increase strictly
    (an error names the offending line).

    Parameters
    ----------
    path : str or Path
        The file.

    Returns
    -------
    times : array of float
        Times [s].
    accelerations : array of float
        Ground accelerations [g].
    """
    path = Path(path)
    lines = _read_lines(path)
    times, accelerations = [], []
    header_allowed = True
    for line_number, raw in enumerate(lines, start=1):
        line = raw.strip()
        if not line or line.startswith("#"):
            continue
        cells = _split_cells(line)
        if header_allowed and cells and not any(_is_number(cell) for cell in cells):
            header_allowed = False  # a header of column names, e.g. "time_s,acc_g"
            continue
        header_allowed = False
        if len(cells) != 2:
            raise _record_error(
                path, f"line {line_number}: expected 2 columns (time [s], acceleration [g]), "
                f"got {len(cells)}: {line!r}"
            )
        time = _parse_number(path, cells[0], line_number, "time")
        if times and time <= times[-1]:
            kind = "repeated" if time == times[-1] else "decreasing"
            raise _record_error(
                path, f"line {line_number}: {kind} time {time!r} s after {times[-1]!r} s "
                "(times must increase strictly)"
            )
        times.append(time)
        accelerations.append(_parse_number(path, cells[1], line_number, "acceleration"))
    if not times:
        raise _record_error(path, "the file holds no data lines (only a header or comments)")
    return np.array(times), np.array(accelerations)


TIME_STEP_TOLERANCE = 1e-5
"""Relative tolerance on the ends of :data:`~archquake.defaults.RECORD_TIME_STEP_RANGE` [-]: the
difference of two times of an hour written to 6 decimals (steps of 1e-6 s) is the step up to a
round-off of about 2e-12 s, 2e-6 of it."""

_NPTS = re.compile(r"\bNPTS\s*=\s*([^\s,]+)", re.IGNORECASE)
_DT = re.compile(r"\bDT\s*=\s*([^\s,]+)", re.IGNORECASE)
_UNITS = re.compile(r"UNITS\s+OF\s+(\S+)", re.IGNORECASE)
_OLD_SAMPLING = re.compile(r"^\s*(\S+)\s+(\S+)\s+NPTS\s*,?\s*DT\b", re.IGNORECASE)
"""The older PEER layout of line 4: ``  3930   .01000    NPTS, DT``."""


def parse_at2_record(path: str | Path) -> tuple[np.ndarray, np.ndarray]:
    """Times [s] and accelerations [g] of a PEER NGA ``.AT2`` record.

    The four header lines are: a title, the event and station, the quantity and its units
    (``ACCELERATION TIME SERIES IN UNITS OF G``; other units are refused), and the sampling, e.g.
    ``NPTS=  5590, DT=   .0050 SEC`` (also accepted: ``NPTS= 5590, DT= 0.005 SEC,``, the same
    without commas, and the older layout ``  5590   .00500    NPTS, DT``). The accelerations [g]
    follow, several per line, separated by whitespace (or commas); there must be exactly NPTS of
    them. The time of value ``i`` is ``i DT``.

    Parameters
    ----------
    path : str or Path
        The file.

    Returns
    -------
    times : array of float
        Times ``i DT`` [s].
    accelerations : array of float
        Ground accelerations [g].
    """
    path = Path(path)
    lines = _read_lines(path)
    if len(lines) < 4:
        raise _record_error(
            path, f"an AT2 file needs 4 header lines, the file has only {len(lines)} line(s)"
        )
    units = _UNITS.search(lines[2])
    if units and units.group(1).rstrip(".,").upper() != "G":
        raise _record_error(
            path, f"line 3: accelerations must be in units of G, got {units.group(1)!r}"
        )
    header = lines[3]
    npts_match, dt_match = _NPTS.search(header), _DT.search(header)
    old_layout = _OLD_SAMPLING.search(header)
    if (npts_match is None or dt_match is None) and old_layout:
        npts_text, dt_text = old_layout.group(1), old_layout.group(2)
    elif npts_match is None or dt_match is None:
        missing = " and ".join(
            key for key, match in (("NPTS", npts_match), ("DT", dt_match)) if match is None
        )
        raise _record_error(
            path, f"line 4 of the AT2 header must give NPTS and DT "
            f"(e.g. 'NPTS=  5590, DT=   .0050 SEC'); {missing} not found in {header.strip()!r}"
        )
    else:
        npts_text, dt_text = npts_match.group(1), dt_match.group(1)
    npts = _parse_count(path, npts_text, 4, "NPTS")
    dt = _parse_number(path, dt_text, 4, "DT")
    if npts < 2:
        raise _record_error(path, f"line 4: NPTS must be >= 2, got {npts}")
    if dt <= 0.0:
        raise _record_error(path, f"line 4: DT must be > 0 [s], got {dt!r}")
    values = []
    for line_number, raw in enumerate(lines[4:], start=5):
        for cell in raw.replace(",", " ").split():
            values.append(_parse_number(path, cell, line_number, "acceleration"))
    if len(values) != npts:
        raise _record_error(
            path, f"the header gives NPTS = {npts} but {len(values)} acceleration values follow"
        )
    return np.arange(npts) * dt, np.array(values)


def _parse_count(path: Path, text: str, line_number: int, what: str) -> int:
    """``text`` as a whole number (digits only), or a ValueError naming the file and line."""
    if not text.strip().isdigit() or not text.strip().isascii():
        raise _record_error(path, f"line {line_number}: {what} must be a whole number, got "
                                  f"{text!r}")
    return int(text)


def _read_lines(path: Path) -> list[str]:
    if not path.exists():
        raise _record_error(path, "no such file")
    if not path.is_file():
        raise _record_error(path, "not a regular file")
    size = path.stat().st_size
    if size > MAX_RECORD_FILE_BYTES:
        raise _record_error(path, f"the file has {size} bytes, more than the "
                                  f"{MAX_RECORD_FILE_BYTES} read (MAX_RECORD_FILE_BYTES)")
    data = path.read_bytes()
    if data.startswith((b"\xff\xfe", b"\xfe\xff")):  # UTF-16 with its byte-order mark
        try:
            text = data.decode("utf-16")
        except UnicodeDecodeError:
            raise _record_error(path, "the file starts as UTF-16 text but is not; save it as "
                                      "UTF-8 text") from None
    elif b"\x00" in data:
        raise _record_error(path, "the file holds NUL bytes: it is not UTF-8 text (UTF-16 "
                                  "without a byte-order mark, or binary); save it as UTF-8 text")
    else:
        text = data.decode("utf-8-sig", errors="replace")
    if not text.strip():
        raise _record_error(path, "the file is empty")
    return text.splitlines()


_ESM_KEY = re.compile(r"^\s*([A-Z][A-Z0-9_/^.-]*)\s*:(.*)$")
_ESM_UNITS = {
    "cm/s^2": 0.01 / GRAVITY, "cm/s/s": 0.01 / GRAVITY, "cm/s2": 0.01 / GRAVITY,
    "cm/sec^2": 0.01 / GRAVITY, "gal": 0.01 / GRAVITY,
    "m/s^2": 1.0 / GRAVITY, "m/s/s": 1.0 / GRAVITY, "m/s2": 1.0 / GRAVITY,
    "m/sec^2": 1.0 / GRAVITY,
    "g": 1.0,
}
"""Units of an ESM record (lower case) -> factor to g."""


def _esm_header(path: Path, lines: list[str]) -> tuple[dict[str, tuple[str, int]], int]:
    """``{KEY: (value, line number)}`` of the leading ``KEY: value`` lines, and the index of the
    first line after them."""
    header: dict[str, tuple[str, int]] = {}
    i = 0
    while i < len(lines):
        line = lines[i]
        if not line.strip():
            i += 1
            continue
        match = _ESM_KEY.match(line)
        if match is None:
            break
        key, value = match.group(1), match.group(2).strip()
        if key in header and key in _ESM_READ and header[key][0] != value:
            first, where = header[key]
            raise _record_error(path, f"line {i + 1}: {key} is {value!r}, but line {where} gave "
                                      f"{first!r}; give it once")
        header.setdefault(key, (value, i + 1))
        i += 1
    return header, i


_ESM_READ = ("SAMPLING_INTERVAL_S", "NDATA", "UNITS", "DATA_TYPE")
"""The keys of an ESM header that are read: given twice with two values, the file is
refused."""


def parse_esm_record(path: str | Path) -> tuple[np.ndarray, np.ndarray]:
    """Times [s] and accelerations [g] of an ESM (Engineering Strong Motion database) ASCII file.

    The header is the leading run of ``KEY: value`` lines (64 in the database's files, header
    format "DYNA 1.2"); of it are read ``SAMPLING_INTERVAL_S`` (time step [s], > 0), ``NDATA``
    (number of samples, >= 2), ``UNITS`` (``cm/s^2``, ``m/s^2`` or ``g``; also spelt ``cm/s/s``,
    ``cm/s2``, ``gal``, ``m/s/s``, ``m/s2``) and ``DATA_TYPE``, which must be ``ACCELERATION``
    when given (velocity, displacement and spectra files are refused). The NDATA values follow,
    one or several per line; the time of value ``i`` is ``i SAMPLING_INTERVAL_S``.

    Parameters
    ----------
    path : str or Path
        The file (the database names them ``*.ASC``).

    Returns
    -------
    times : array of float
        Times [s].
    accelerations : array of float
        Ground accelerations [g], converted from the header's units.

    References
    ----------
    .. [1] Luzi, L., Puglia, R., Russo, E. and ORFEUS WG5 (2016). Engineering Strong Motion
       Database, version 1.0. Istituto Nazionale di Geofisica e Vulcanologia, Observatories &
       Research Facilities for European Seismology. doi:10.13127/ESM
    """
    path = Path(path)
    lines = _read_lines(path)
    header, first_data = _esm_header(path, lines)
    if "SAMPLING_INTERVAL_S" not in header and "NDATA" not in header:
        raise _record_error(
            path, "not an ESM file: no 'SAMPLING_INTERVAL_S:' and 'NDATA:' header lines"
        )
    for key in ("SAMPLING_INTERVAL_S", "NDATA", "UNITS"):
        if key not in header or not header[key][0]:
            raise _record_error(path, f"the ESM header has no {key} value (a line '{key}: ...')")
    data_type, line = header.get("DATA_TYPE", ("ACCELERATION", 0))
    if data_type and data_type.strip().upper() != "ACCELERATION":
        raise _record_error(
            path, f"line {line}: DATA_TYPE is {data_type!r}; only ACCELERATION records can be "
            "read (not velocity, displacement or spectra)"
        )
    units, line = header["UNITS"]
    factor = _ESM_UNITS.get(units.strip().lower().replace(" ", ""))
    if factor is None:
        raise _record_error(
            path, f"line {line}: UNITS {units!r} is not an acceleration unit; expected one of "
            "cm/s^2, m/s^2, g"
        )
    dt_text, line = header["SAMPLING_INTERVAL_S"]
    dt = _parse_number(path, dt_text, line, "SAMPLING_INTERVAL_S")
    if dt <= 0.0:
        raise _record_error(path, f"line {line}: SAMPLING_INTERVAL_S must be > 0 [s], got {dt!r}")
    npts_text, line = header["NDATA"]
    npts = _parse_count(path, npts_text, line, "NDATA")
    if npts < 2:
        raise _record_error(path, f"line {line}: NDATA must be >= 2, got {npts}")
    values = []
    for line_number, raw in enumerate(lines[first_data:], start=first_data + 1):
        for cell in raw.replace(",", " ").split():
            values.append(_parse_number(path, cell, line_number, "acceleration"))
    if len(values) != npts:
        raise _record_error(
            path, f"the header gives NDATA = {npts} but {len(values)} acceleration values follow"
        )
    return np.arange(npts) * dt, np.array(values) * factor


def _looks_like_esm(lines: list[str]) -> bool:
    keys = {m.group(1) for m in map(_ESM_KEY.match, lines[:200]) if m}
    return {"SAMPLING_INTERVAL_S", "NDATA"} <= keys


RECORD_FORMATS: dict[str, Callable[[str | Path], tuple[np.ndarray, np.ndarray]]] = {
    "csv": parse_csv_record,
    "at2": parse_at2_record,
    "esm": parse_esm_record,
}
"""Registry of record file formats: name -> parser(path) -> (times [s], accelerations [g])."""

RECORD_EXTENSIONS: dict[str, str] = {".at2": "at2", ".csv": "csv", ".asc": "esm"}
"""File extensions (lower case) of the record formats; a folder's records are its files with
these extensions."""


def record_format(path: str | Path) -> str:
    """Format name of a record file (a key of :data:`RECORD_FORMATS`).

    By extension (``.at2`` -> ``at2``, ``.csv`` -> ``csv``, ``.asc`` -> ``esm``); otherwise by
    content: ``esm`` if the header has ``SAMPLING_INTERVAL_S:`` and ``NDATA:`` lines, ``at2`` if
    the fourth line gives NPTS (``NPTS=`` or ``... NPTS, DT``), else ``csv``.
    """
    path = Path(path)
    suffix = path.suffix.lower()
    if suffix in RECORD_EXTENSIONS:
        return RECORD_EXTENSIONS[suffix]
    lines = _read_lines(path)
    if _looks_like_esm(lines):
        return "esm"
    if len(lines) >= 4 and (_NPTS.search(lines[3]) or _OLD_SAMPLING.search(lines[3])):
        return "at2"
    return "csv"


def read_record(
    path: str | Path, *, scale_to: float | None = None, file_format: str | None = None,
) -> GroundMotion:
    """A recorded accelerogram as a ``LINEAR`` ground motion [m/s^2].

    See the module docstring for the file formats and the conventions (start at ``t = 0``,
    linear interpolation, still ground after the last sample).

    Parameters
    ----------
    path : str or Path
        The record file: a two-column CSV (time [s], acceleration [g]), a PEER NGA ``.AT2`` or
        an ESM ASCII file (see the module docstring).
    scale_to : float, optional
        Target peak ground acceleration [g], > 0: the whole record is multiplied by one factor so
        that its largest absolute acceleration equals ``scale_to``. ``None`` keeps the record as is.
    file_format : str, optional
        A key of :data:`RECORD_FORMATS`; by default chosen by :func:`record_format`.

    Returns
    -------
    GroundMotion
        Kind ``LINEAR``, accelerations in m/s^2.

    Raises
    ------
    ValueError
        Naming the file and the problem: missing or empty file, malformed AT2 header, NPTS not
        matching the number of values, wrong number of columns or a non-numeric cell (with its
        line), non-finite values, times negative or not strictly increasing, fewer than two
        samples, ``scale_to`` not > 0, or a record that is zero everywhere and cannot be scaled.
    """
    path = Path(path)
    if scale_to is not None:
        scale_to = check_number("scale_to", scale_to, "g")
        check_peak("scale_to", scale_to * GRAVITY)
    if file_format is None:
        file_format = record_format(path)
    try:
        parser = RECORD_FORMATS[file_format]
    except KeyError:
        raise ValueError(
            f"unknown record file_format {file_format!r}; choose one of {sorted(RECORD_FORMATS)}"
        ) from None
    times, accelerations = parser(path)
    if times.size < 2:
        raise _record_error(path, f"a record needs at least two samples, got {times.size}")
    if times[0] < 0.0:
        raise _record_error(
            path, f"times must start at or after 0 s, the first is {float(times[0])!r} s"
        )
    steps = np.diff(times)
    if np.any(steps <= 0.0):
        i = int(np.argmax(steps <= 0.0))
        kind = "repeated" if steps[i] == 0.0 else "decreasing"
        raise _record_error(
            path, f"times must increase strictly; sample {i + 2} has a {kind} time "
            f"{float(times[i + 1])!r} s after {float(times[i])!r} s"
        )
    low, high = RECORD_TIME_STEP_RANGE
    # times written to a few decimals differ by a step that is the bound up to round-off
    outside = ((steps < low * (1.0 - TIME_STEP_TOLERANCE))
               | (steps > high * (1.0 + TIME_STEP_TOLERANCE)))
    if np.any(outside):
        i = int(np.argmax(outside))
        raise _record_error(
            path, f"the time step {float(steps[i]):.9g} s after sample {i + 1} is outside "
            f"[{low:g}, {high:g}] s (RECORD_TIME_STEP_RANGE): accelerographs sample at 50 to "
            f"1000 Hz; are the times in seconds?")
    if not times[-1] <= MAX_RECORD_DURATION:
        raise _record_error(
            path, f"the record lasts {float(times[-1]):.6g} s, more than the "
            f"{MAX_RECORD_DURATION:g} s accepted (MAX_RECORD_DURATION); are the times in "
            f"seconds?")
    if times[0] > 0.0:  # the ground is at rest at t = 0 and ramps to the first sample
        times = np.concatenate(([0.0], times))
        accelerations = np.concatenate(([0.0], accelerations))
    name = f"record {path.name}"
    _check_plausible_peak(path, float(np.max(np.abs(accelerations))))
    if scale_to is not None:
        peak = float(np.max(np.abs(accelerations)))
        if peak == 0.0:
            raise _record_error(
                path, f"the acceleration is zero everywhere; it cannot be scaled to a peak of "
                f"{scale_to:g} g"
            )
        accelerations = accelerations * (scale_to / peak)
        name += f" scaled to PGA {scale_to:.3g} g"
    peak = float(np.max(np.abs(accelerations)))
    if peak > MAX_ACCELERATION_G:
        raise _record_error(path, f"the peak acceleration {peak:.4g} g is more than the "
                                  f"{MAX_ACCELERATION_G:g} g accepted (are the values in g?)")
    return GroundMotion(LINEAR, times, accelerations * GRAVITY, name=name)


def _check_plausible_peak(path: Path, peak: float) -> None:
    """Warn when the peak [g] as read is above :data:`~archquake.defaults.PLAUSIBLE_PEAK_G`,
    saying what it would be in the likely units (refused above MAX_ACCELERATION_G later)."""
    if PLAUSIBLE_PEAK_G < peak <= MAX_ACCELERATION_G:
        warnings.warn(
            f"record file '{path}': its peak acceleration {peak:.4g} g is implausible for a "
            f"record (above {PLAUSIBLE_PEAK_G:g} g); if its values are in cm/s^2 the peak is "
            f"{peak / 100 / GRAVITY:.3g} g, in m/s^2 {peak / GRAVITY:.3g} g: convert them to g",
            stacklevel=3)


def record(path: str | Path, scale_to: float | None = None) -> GroundMotion:
    """Factory of the ``"record"`` entry of :data:`GROUND_MOTIONS`: :func:`read_record`.

    Parameters
    ----------
    path : str or Path
        The record file (CSV, PEER NGA ``.AT2`` or ESM; see :func:`read_record`).
    scale_to : float, optional
        Target peak ground acceleration [g], > 0.
    """
    if not isinstance(path, (str, Path)):
        raise ValueError(
            f"the 'record' ground motion takes a file path (and optionally scale_to [g]), "
            f"got {path!r}; use read_record(path, scale_to=...)"
        )
    return read_record(path, scale_to=scale_to)
