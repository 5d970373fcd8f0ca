"""Fuzzing the record readers and the motion builders: record files valid, borderline and
hostile (CSV, PEER .AT2, ESM; wrong units, steps, counts, encodings, bytes), read by
``read_record`` and by ``archquake records --json`` and ``archquake simulate --record``: a motion
with finite values and strict JSON, or one error naming the file; and every analytic motion built
from any amplitude and duration, or an error naming the parameter."""

import math
import string

import numpy as np
import pytest
from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st

from archquake.defaults import ANALYTIC_GROUND_MOTIONS
from archquake.ground_motion import ground_motion, read_record
from fuzzing import check_run, run_cli, time_limit

pytestmark = pytest.mark.fuzz

CELL = st.one_of(st.floats(-3, 3).map(repr), st.floats(allow_nan=True).map(repr),
                 st.sampled_from(["1_0", "", "nan", "inf", "1e400", "0x1", "1,5", "—", "1e",
                                  "2.5e-3", "-0", "+1", " 1 "]))
TIME = st.one_of(st.floats(0, 100).map(repr), st.sampled_from(["0", "1e300", "-1", "nan"]))


@st.composite
def _csv(draw):
    n = draw(st.integers(0, 30))
    dt = draw(st.sampled_from([0.01, 0.005, 1e-7, 2.0, 1e300]))
    factor = draw(st.sampled_from([1.0, 100 * 9.81, 9.81, 1e6]))
    rows = [f"{i * dt!r},{0.3 * factor * math.sin(i / 3)!r}" for i in range(n)]
    for _ in range(draw(st.integers(0, 3))):
        if rows:
            k = draw(st.integers(0, len(rows) - 1))
            rows[k] = draw(st.sampled_from([f"{draw(TIME)},{draw(CELL)}", draw(CELL),
                                            f"{draw(TIME)};{draw(CELL)}", "#", "time,acc",
                                            f"{draw(TIME)},{draw(CELL)},{draw(CELL)}"]))
    return "\n".join(rows)


@st.composite
def _at2(draw):
    npts = draw(st.one_of(st.integers(0, 20), st.sampled_from(["1_0", "x", "-3", "1e3"])))
    dt = draw(st.one_of(st.sampled_from([".0050", "1e300", "0", "-0.01", "nan", "1e-9"]),
                        st.floats(0.001, 0.05).map(repr)))
    units = draw(st.sampled_from(["G", "CM/S/S", "g.", ""]))
    count = npts if isinstance(npts, int) else 5
    values = " ".join(draw(st.lists(CELL, min_size=0, max_size=count + 2))
                      if draw(st.booleans()) else ["0.1"] * count)
    return (f"PEER\nEVENT\nACCELERATION TIME SERIES IN UNITS OF {units}\n"
            f"NPTS= {npts}, DT= {dt} SEC\n{values}\n")


@st.composite
def _esm(draw):
    n = draw(st.integers(0, 20))
    header = [f"SAMPLING_INTERVAL_S: {draw(st.sampled_from(['0.01', '0', '1e300', 'x']))}",
              f"NDATA: {draw(st.sampled_from([str(n), str(n + 1), '1_0', '']))}",
              f"UNITS: {draw(st.sampled_from(['cm/s^2', 'g', 'm/s^2', 'furlongs']))}"]
    if draw(st.booleans()):
        header.append(f"UNITS: {draw(st.sampled_from(['cm/s^2', 'g']))}")
    if draw(st.booleans()):
        header.append(f"DATA_TYPE: {draw(st.sampled_from(['ACCELERATION', 'VELOCITY']))}")
    values = [repr(30 * math.sin(i)) for i in range(n)]
    return "\n".join(header + values) + "\n"


@st.composite
def record_files(draw):
    """``(file name, bytes)``."""
    kind = draw(st.sampled_from(["csv", "AT2", "ASC", "bytes", "utf16"]))
    if kind == "csv":
        return "record.csv", draw(_csv()).encode()
    if kind == "AT2":
        return "record.AT2", draw(_at2()).encode()
    if kind == "ASC":
        return "record.ASC", draw(_esm()).encode()
    if kind == "utf16":
        return "record.csv", draw(_csv()).encode(draw(st.sampled_from(["utf-16",
                                                                       "utf-16-le"])))
    return draw(st.sampled_from(["record.csv", "record.dat"])), draw(
        st.one_of(st.binary(max_size=80), st.text(string.printable, max_size=80).map(
            str.encode)))


@pytest.mark.filterwarnings("ignore:record file .* is implausible:UserWarning")
@settings(suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])
@given(record_files())
def test_a_record_file_gives_a_motion_or_an_error_naming_it(tmp_path, record):
    name, content = record
    path = tmp_path / name
    path.write_bytes(content)
    try:
        with time_limit():
            motion = read_record(path)
    except ValueError as exc:
        assert name in str(exc), str(exc)
        motion = None
    event("motion" if motion is not None else "refused")
    if motion is not None:
        assert np.all(np.isfinite(motion.times)) and np.all(np.isfinite(motion.values))
    for argv in (["records", str(path), "--json"],
                 ["simulate", "--record", str(path), "--json"]):
        status, out, err = run_cli(argv)
        kind = check_run(argv, status, out, err, names=[name, "--record", "record"])
        assert (kind == "ok") <= (motion is not None)


NUMBER = st.one_of(st.floats(allow_nan=True, allow_infinity=True),
                   st.floats(-20, 20), st.sampled_from([0.0, 1e-300, 1e300, -1.0]))


@given(name=st.sampled_from(ANALYTIC_GROUND_MOTIONS), amplitude=NUMBER, duration=NUMBER)
def test_an_analytic_motion_builds_or_names_the_parameter(name, amplitude, duration):
    try:
        motion = ground_motion(name, amplitude, duration)
    except ValueError as exc:
        assert any(word in str(exc) for word in ("amplitude", "duration", "period", "peak",
                                                 "acceleration")), str(exc)
        return
    t = np.linspace(0.0, min(motion.duration, 100.0), 7)
    assert np.all(np.isfinite(motion.acceleration(t)))
