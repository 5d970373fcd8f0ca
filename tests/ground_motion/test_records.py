"""Recorded accelerograms: CSV and PEER NGA AT2 readers, scaling, and every bad-file error.

The files in tests/data are samples of the analytic accelerogram ``acceleration_g`` below
(written by tests/data/make_records.py); the reader is checked against the formula, not against
the writer.
"""

from pathlib import Path

import numpy as np
import pytest

from archquake.geometry import GRAVITY
from archquake.ground_motion import (
    GROUND_MOTIONS,
    LINEAR,
    RECORD_FORMATS,
    evaluate,
    ground_motion,
    read_record,
    record_format,
)

DATA = Path(__file__).parents[1] / "data"
CSV = DATA / "decaying_sine.csv"
AT2 = DATA / "decaying_sine.AT2"


def acceleration_g(t):
    """The synthetic accelerogram of the test files [g]."""
    return 0.4 * np.exp(-t / 0.5) * np.sin(2 * np.pi * t / 0.25)


def write(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text)
    return path


AT2_HEADER = (
    "PEER NGA STRONG MOTION DATABASE RECORD\n"
    "TEST EVENT, TEST STATION\n"
    "ACCELERATION TIME SERIES IN UNITS OF G\n"
)


# --- reading ---------------------------------------------------------------------------------

def test_csv_record_matches_the_analytic_accelerogram_in_m_per_s2():
    g = read_record(CSV)
    assert g.kind == LINEAR
    t = 0.01 * np.arange(201)
    assert g.times == pytest.approx(t, abs=1e-12)
    assert g.values == pytest.approx(GRAVITY * acceleration_g(t), abs=1e-9 * GRAVITY)
    assert g.duration == pytest.approx(2.0)
    assert g.name == "record decaying_sine.csv"


def test_at2_record_matches_the_analytic_accelerogram_on_i_dt():
    g = read_record(AT2)
    assert g.kind == LINEAR
    t = 0.005 * np.arange(300)
    assert g.times == pytest.approx(t, abs=1e-12)
    # 8 significant digits in the file (E15.7)
    assert g.values == pytest.approx(GRAVITY * acceleration_g(t), rel=1e-7, abs=1e-9)
    assert g.duration == pytest.approx(299 * 0.005)


@pytest.mark.parametrize("path", [CSV, AT2], ids=["csv", "at2"])
def test_interpolation_between_samples_is_linear(path):
    g = read_record(path)
    mid = 0.5 * (g.times[:-1] + g.times[1:])
    quarter = 0.75 * g.times[:-1] + 0.25 * g.times[1:]
    exact = GRAVITY * acceleration_g(g.times)
    assert g.acceleration(mid) == pytest.approx(0.5 * (exact[:-1] + exact[1:]), abs=1e-7)
    assert g.acceleration(quarter) == pytest.approx(0.75 * exact[:-1] + 0.25 * exact[1:],
                                                    abs=1e-7)


@pytest.mark.parametrize("path", [CSV, AT2], ids=["csv", "at2"])
def test_ground_is_still_before_and_after_the_record(path):
    g = read_record(path)
    assert g.acceleration([-1.0, g.duration + 1e-9, g.duration + 10.0]) == pytest.approx([0, 0, 0])
    assert g.breakpoints[0] == 0.0 and g.breakpoints[-1] == g.duration


@pytest.mark.parametrize("path", [CSV, AT2], ids=["csv", "at2"])
def test_compiled_linear_evaluation_agrees_with_numpy_interp(path):
    g = read_record(path)
    kind, params, times, values = g.compiled()
    rng = np.random.default_rng(20240611)
    t = np.concatenate((rng.uniform(-0.2, g.duration + 0.2, 2000), times))
    expected = np.interp(t, times, values, left=0.0, right=0.0)
    got = np.array([evaluate(x, kind, params, times, values) for x in t])
    np.testing.assert_allclose(got, expected, rtol=1e-13, atol=1e-13)


def test_format_is_chosen_by_extension_or_content(tmp_path):
    assert record_format(CSV) == "csv"
    assert record_format(AT2) == "at2"
    assert set(RECORD_FORMATS) == {"csv", "at2", "esm"}
    renamed_at2 = write(tmp_path, "motion.txt", AT2.read_text())
    renamed_csv = write(tmp_path, "motion.dat", CSV.read_text())
    assert record_format(renamed_at2) == "at2"
    assert record_format(renamed_csv) == "csv"
    assert read_record(renamed_at2).values == pytest.approx(read_record(AT2).values)
    assert read_record(renamed_csv).values == pytest.approx(read_record(CSV).values)


def test_whitespace_separated_csv_without_header(tmp_path):
    path = write(tmp_path, "w.txt", "# t a\n0.0   0.1\n0.5\t-0.2\n  1.0 0.0\n")
    g = read_record(path)
    assert g.times.tolist() == [0.0, 0.5, 1.0]
    assert g.values == pytest.approx(GRAVITY * np.array([0.1, -0.2, 0.0]))
    assert g.acceleration(0.25) == pytest.approx(GRAVITY * -0.05)


def test_csv_with_byte_order_mark_and_windows_line_ends(tmp_path):
    path = tmp_path / "bom.csv"
    path.write_bytes("\ufeff0.0,0.1\r\n1.0,0.3\r\n".encode())
    assert read_record(path).values == pytest.approx(GRAVITY * np.array([0.1, 0.3]))


def test_csv_starting_after_zero_gets_a_rest_point_at_zero(tmp_path):
    path = write(tmp_path, "late.csv", "time_s, acc_g\n0.5, 0.2\n1.0, -0.1\n")
    g = read_record(path)
    assert g.times.tolist() == [0.0, 0.5, 1.0]
    assert g.values == pytest.approx(GRAVITY * np.array([0.0, 0.2, -0.1]))
    assert g.acceleration(0.25) == pytest.approx(GRAVITY * 0.1)


@pytest.mark.parametrize("sampling", [
    "NPTS=  5, DT=   .0100 SEC",
    "NPTS= 5, DT= 0.01 SEC,",
    "NPTS= 5 DT= 0.01 SEC",
    "NPTS=5,DT=1.0E-02 SEC",
    "    5   .01000    NPTS, DT",
], ids=["nga", "trailing-comma", "no-commas", "compact", "older-layout"])
def test_at2_header_variants(tmp_path, sampling):
    path = write(tmp_path, "v.AT2", AT2_HEADER + sampling + "\n  .1000000E+00 -.2000000E+00\n"
                 "  .3000000E+00\n-.4000000E+00  0.0\n")
    g = read_record(path)
    assert g.times == pytest.approx([0.0, 0.01, 0.02, 0.03, 0.04])
    assert g.values == pytest.approx(GRAVITY * np.array([0.1, -0.2, 0.3, -0.4, 0.0]))


# --- scaling ---------------------------------------------------------------------------------

@pytest.mark.parametrize("path", [CSV, AT2], ids=["csv", "at2"])
def test_scale_to_target_peak_ground_acceleration(path):
    raw = read_record(path)
    g = read_record(path, scale_to=0.3)
    assert g.peak == pytest.approx(0.3 * GRAVITY, rel=1e-12)
    factor = 0.3 * GRAVITY / np.max(np.abs(GRAVITY * acceleration_g(raw.times)))
    assert g.values == pytest.approx(raw.values * factor, rel=1e-6, abs=1e-9)
    assert g.times.tolist() == raw.times.tolist()
    assert "0.3 g" in g.name


def test_scale_to_uses_the_negative_peak_when_it_is_larger(tmp_path):
    path = write(tmp_path, "neg.csv", "0,0.1\n1,-0.5\n2,0.2\n")
    g = read_record(path, scale_to=1.0)
    assert g.values == pytest.approx(GRAVITY * np.array([0.2, -1.0, 0.4]))


# --- registry --------------------------------------------------------------------------------

def test_record_is_registered_and_analytic_motions_are_unchanged():
    assert "record" in GROUND_MOTIONS
    g = ground_motion("record", CSV, scale_to=0.2)
    assert g.values == pytest.approx(read_record(CSV, scale_to=0.2).values)
    assert ground_motion("oppenheim", -GRAVITY, 0.27).acceleration(0.1) == -GRAVITY
    with pytest.raises(ValueError, match="file path"):
        ground_motion("record", 1.0, 0.5)


# --- bad files -------------------------------------------------------------------------------

BAD_FILES = {
    # name: (file name, text, expected message)
    "empty": ("empty.csv", "", "empty"),
    "blank": ("blank.AT2", "\n  \n", "empty"),
    "header only": ("header.csv", "# comment\ntime_s,acc_g\n", "no data"),
    "one sample": ("one.csv", "0.0,0.1\n", "at least two samples"),
    "three columns": ("cols.csv", "0,0\n0.1,0.2,0.3\n", r"line 2: expected 2 columns.*got 3"),
    "one column": ("cols1.csv", "0,0\n0.1\n", r"line 2: expected 2 columns.*got 1"),
    "non-numeric": ("text.csv", "t,a\n0,0\n0.1,abc\n", r"line 3: .*acceleration 'abc'"),
    "non-numeric time": ("text2.csv", "0,0\nx1,0.2\n", r"line 2: .*time 'x1'"),
    "half header": ("half.csv", "time,0.5\n1,2\n", r"line 1: .*time 'time'"),
    "nan": ("nan.csv", "0,0\n0.1,nan\n", r"line 2: .*'nan' is not a finite"),
    "inf": ("inf.csv", "0,0\n0.1,-inf\n", r"line 2: .*'-inf' is not a finite"),
    "repeated time": ("rep.csv", "0,0\n0.1,0.2\n0.1,0.3\n", r"line 3: repeated time"),
    "decreasing time": ("dec.csv", "0,0\n0.2,0.2\n0.1,0.3\n", r"line 3: decreasing time"),
    "negative time": ("neg.csv", "-0.1,0\n0.2,0.2\n", r"after 0 s, the first is -0\.1 s"),
    "short AT2": ("short.AT2", "TITLE\nEVENT\n", "4 header lines"),
    "no NPTS": ("nonpts.AT2", AT2_HEADER + "DT= 0.01 SEC\n0.1 0.2\n", "NPTS not found"),
    "no DT": ("nodt.AT2", AT2_HEADER + "NPTS= 2\n0.1 0.2\n", "DT not found"),
    "no sampling": ("none.AT2", AT2_HEADER + "0.1 0.2 0.3\n", "NPTS and DT not found"),
    "bad NPTS": ("badn.AT2", AT2_HEADER + "NPTS= 2.5, DT= 0.01\n0.1 0.2\n", "whole number"),
    "bad DT": ("baddt.AT2", AT2_HEADER + "NPTS= 2, DT= fast\n0.1 0.2\n", "DT 'fast'"),
    "zero DT": ("zerodt.AT2", AT2_HEADER + "NPTS= 2, DT= 0.0\n0.1 0.2\n", "DT must be > 0"),
    "too few values": ("few.AT2", AT2_HEADER + "NPTS= 4, DT= 0.01\n0.1 0.2\n0.3\n",
                       "NPTS = 4 but 3 acceleration values"),
    "too many values": ("many.AT2", AT2_HEADER + "NPTS= 2, DT= 0.01\n0.1 0.2 0.3\n",
                        "NPTS = 2 but 3 acceleration values"),
    "AT2 non-numeric": ("txt.AT2", AT2_HEADER + "NPTS= 3, DT= 0.01\n0.1 0.2\n0.3x\n",
                        r"line 6: .*'0.3x'"),
    "AT2 nan": ("nan.AT2", AT2_HEADER + "NPTS= 3, DT= 0.01\n0.1 NaN 0.2\n",
                r"line 5: .*'NaN' is not a finite"),
    "AT2 wrong units": ("cm.AT2", "TITLE\nEVENT\nACCELERATION TIME SERIES IN UNITS OF CM/S2\n"
                        "NPTS= 2, DT= 0.01\n1 2\n", "units of G"),
}


@pytest.mark.parametrize("name", list(BAD_FILES))
def test_bad_file_gives_error_naming_file_and_problem(tmp_path, name):
    file_name, text, message = BAD_FILES[name]
    path = write(tmp_path, file_name, text)
    with pytest.raises(ValueError, match=message) as info:
        read_record(path)
    assert file_name in str(info.value)


def test_missing_file(tmp_path):
    with pytest.raises(ValueError, match=r"nowhere\.AT2.*no such file"):
        read_record(tmp_path / "nowhere.AT2")
    with pytest.raises(ValueError, match="not a regular file"):
        read_record(tmp_path)


@pytest.mark.parametrize("scale_to", [0.0, -0.3, float("nan"), float("inf"), "big"])
def test_bad_scale_to(scale_to):
    with pytest.raises(ValueError, match=r"scale_to must be .*\[g\]"):
        read_record(CSV, scale_to=scale_to)


def test_all_zero_record_cannot_be_scaled(tmp_path):
    path = write(tmp_path, "still.csv", "0,0\n1,0\n2,0.0\n")
    assert read_record(path).peak == 0.0
    with pytest.raises(ValueError, match=r"still\.csv.*zero everywhere.*0\.3 g"):
        read_record(path, scale_to=0.3)


def test_unknown_file_format():
    with pytest.raises(ValueError, match=r"file_format 'mseed'.*\[.at2., .csv., .esm.\]"):
        read_record(CSV, file_format="mseed")
