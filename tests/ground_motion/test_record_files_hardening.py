"""Record files that used to be read wrong without a word, or gave a message with no hint:
units, underscores, time steps, durations, encodings and conflicting headers."""

import warnings
from pathlib import Path

import numpy as np
import pytest

from archquake.constants import GRAVITY
from archquake.defaults import MAX_RECORD_DURATION, PLAUSIBLE_PEAK_G, RECORD_TIME_STEP_RANGE
from archquake.ground_motion import read_record

DATA = Path(__file__).parents[1] / "data"


def _sine(tmp_path, name="r.csv", factor=1.0, dt=0.01, encoding="utf-8"):
    t = np.arange(0.0, 2.0, dt)
    a = 0.3 * np.sin(2 * np.pi * t)
    path = tmp_path / name
    path.write_text("\n".join(f"{x!r},{y * factor!r}" for x, y in zip(t.tolist(), a.tolist(),
                                                                   strict=True)),
                    encoding=encoding)
    return path, t, a


def test_a_csv_in_cm_per_s2_warns_with_the_likely_unit(tmp_path):
    path, _, a = _sine(tmp_path, factor=100 * GRAVITY)  # 0.3 g written in cm/s^2
    with pytest.warns(UserWarning, match=r"peak acceleration 294.3 g is implausible.*in cm/s\^2 "
                                         r"the peak is 0.3 g"):
        read_record(path)


def test_a_record_in_g_reads_without_a_warning():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for name in ("decaying_sine.csv", "decaying_sine.AT2", "decaying_sine.ASC"):
            motion = read_record(DATA / name)
            assert np.max(np.abs(motion.values)) / GRAVITY < PLAUSIBLE_PEAK_G


def test_an_underscore_in_a_number_is_refused_not_read_as_digits(tmp_path):
    path = tmp_path / "u.csv"
    path.write_text("0,0.1\n0.01,1_0\n")
    with pytest.raises(ValueError, match=r"line 2: cannot read acceleration '1_0' as a number"):
        read_record(path)
    at2 = tmp_path / "u.AT2"
    at2.write_text("t\ne\nACCELERATION TIME SERIES IN UNITS OF G\nNPTS= 1_0, DT= .01 SEC\n"
                   + "0.1 " * 10 + "\n")
    with pytest.raises(ValueError, match="NPTS must be a whole number, got '1_0'"):
        read_record(at2)


@pytest.mark.parametrize("dt", [1e300, 2.0, 1e-9])
def test_a_time_step_outside_the_range_is_refused(tmp_path, dt):
    path = tmp_path / "dt.AT2"
    path.write_text(f"t\ne\nACCELERATION TIME SERIES IN UNITS OF G\nNPTS= 3, DT= {dt!r} SEC\n"
                    "0.0 0.1 0.0\n")
    low, high = RECORD_TIME_STEP_RANGE
    with pytest.raises(ValueError, match=rf"time step .* is outside \[{low:g}, {high:g}\] s"):
        read_record(path)


def test_a_record_longer_than_the_longest_accepted_is_refused(tmp_path):
    path = tmp_path / "long.csv"
    path.write_text(f"0,0.1\n0.5,0.0\n{MAX_RECORD_DURATION + 0.5!r},0.0\n")
    with pytest.raises(ValueError, match="time step"):  # the gap of an hour
        read_record(path)
    samples = int(MAX_RECORD_DURATION) + 2
    path.write_text("\n".join(f"{float(i)!r},0.1" for i in range(samples)))
    with pytest.raises(ValueError, match=rf"lasts {samples - 1} s, more than the "
                                         rf"{MAX_RECORD_DURATION:g} s"):
        read_record(path)


def test_conflicting_units_in_an_esm_header_are_refused(tmp_path):
    lines = (DATA / "decaying_sine.ASC").read_text().splitlines()
    at = next(i for i, line in enumerate(lines) if line.startswith("UNITS:"))
    same = tmp_path / "same.ASC"
    same.write_text("\n".join(lines[:at + 1] + [lines[at]] + lines[at + 1:]))
    assert np.array_equal(read_record(same).values,
                          read_record(DATA / "decaying_sine.ASC").values)
    conflict = tmp_path / "conflict.ASC"
    conflict.write_text("\n".join(lines[:at + 1] + ["UNITS: g"] + lines[at + 1:]))
    with pytest.raises(ValueError, match=rf"line {at + 2}: UNITS is 'g', but line {at + 1} gave "
                                         r"'cm/s\^2'"):
        read_record(conflict)


def test_a_utf16_record_is_read_with_its_byte_order_mark(tmp_path):
    path, t, a = _sine(tmp_path, encoding="utf-16")
    motion = read_record(path)
    assert np.array_equal(motion.times, t)
    assert motion.values == pytest.approx(a * GRAVITY, rel=1e-15)


def test_a_utf16_record_without_its_mark_says_the_encoding(tmp_path):
    path = tmp_path / "le.csv"
    path.write_bytes("0,0.1\n0.01,0.2\n".encode("utf-16-le"))
    with pytest.raises(ValueError, match="NUL bytes: it is not UTF-8 text.*UTF-16"):
        read_record(path)


def test_a_record_whose_name_holds_a_line_break_is_refused(tmp_path):
    """A carriage return in a file name is not quoted in a CSV table (pandas quotes only the
    line terminator): it would split the record's row of results.csv in two."""
    from archquake.ground_motion import RecordSuite

    path = tmp_path / "bad\rname.csv"
    path.write_bytes((DATA / "decaying_sine.csv").read_bytes())
    with pytest.raises(ValueError, match="control character"):
        RecordSuite.from_paths([path])
