"""ESM ASCII records (units from the header) and record suites (folders and lists of files).

``decaying_sine.ASC`` (written by tests/data/make_records.py) samples the analytic accelerogram
``acceleration_m_s2`` below in cm/s^2; the reader is checked against the formula.
"""

import shutil
from pathlib import Path

import numpy as np
import pytest

from archquake.ground_motion import LINEAR, read_record, read_suite, record_format

DATA = Path(__file__).resolve().parents[1] / "data"
ESM = DATA / "decaying_sine.ASC"
HEADER_LINES = ESM.read_text().splitlines()[:64]


def acceleration_m_s2(t):
    """The synthetic accelerogram of the ESM test file [m/s^2] (300 cm/s^2 amplitude)."""
    return 3.0 * np.exp(-t / 0.5) * np.sin(2 * np.pi * t / 0.25)


def esm_text(values, **changes):
    """An ESM file with the test file's header, some ``KEY: value`` lines changed (None
    removes the line)."""
    lines = []
    for line in HEADER_LINES:
        key = line.split(":", 1)[0]
        if key in changes:
            if changes[key] is not None:
                lines.append(f"{key}: {changes[key]}")
        else:
            lines.append(line)
    return "\n".join(lines + [str(v) for v in values]) + "\n"


def write(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text)
    return path


def test_esm_header_is_the_64_line_dyna_header():
    keys = [line.split(":", 1)[0] for line in HEADER_LINES]
    assert keys[0] == "EVENT_NAME" and keys[-1] == "USER5" and len(set(keys)) == 64
    assert {"SAMPLING_INTERVAL_S", "NDATA", "UNITS", "DATA_TYPE"} <= set(keys)


def test_esm_record_in_cm_per_s2_matches_the_analytic_accelerogram():
    g = read_record(ESM)
    assert record_format(ESM) == "esm" and g.kind == LINEAR
    t = 0.008 * np.arange(250)
    assert g.times == pytest.approx(t, abs=1e-12)
    assert g.values == pytest.approx(acceleration_m_s2(t), rel=1e-6, abs=1e-12)  # 7 digits
    assert g.duration == pytest.approx(249 * 0.008)


@pytest.mark.parametrize("units, factor", [("cm/s^2", 0.01), ("m/s^2", 1.0), ("g", 9.81),
                                           ("CM/S/S", 0.01), ("m/s2", 1.0)])
def test_esm_units_are_read_from_the_header(tmp_path, units, factor):
    path = write(tmp_path, "u.asc", esm_text([0.0, 1.5, -2.0], NDATA=3, UNITS=units))
    assert read_record(path).values == pytest.approx(factor * np.array([0.0, 1.5, -2.0]))


def test_esm_format_is_recognised_by_content_and_values_may_share_lines(tmp_path):
    text = esm_text([], NDATA=4) + "1.0 2.0\n3.0, 4.0\n"
    path = write(tmp_path, "IT.AMT..HNE.D.20160824.013632.C.ACC.txt", text)
    assert record_format(path) == "esm"
    assert read_record(path).values == pytest.approx([0.01, 0.02, 0.03, 0.04])


BAD_ESM = {
    "velocity": ({"DATA_TYPE": "VELOCITY", "NDATA": 2}, r"line 50: DATA_TYPE is 'VELOCITY'"),
    "units": ({"UNITS": "cm/s", "NDATA": 2}, r"line 33: UNITS 'cm/s' is not an acceleration"),
    "no units": ({"UNITS": None, "NDATA": 2}, "no UNITS value"),
    "no NDATA": ({"NDATA": None}, "no NDATA value"),
    "bad NDATA": ({"NDATA": "two"}, r"line 30: NDATA must be a whole number"),
    "bad dt": ({"SAMPLING_INTERVAL_S": "0", "NDATA": 2}, r"line 29: SAMPLING_INTERVAL_S must be"),
    "count": ({"NDATA": 5}, "NDATA = 5 but 2 acceleration values"),
}


@pytest.mark.parametrize("name", list(BAD_ESM))
def test_bad_esm_file_names_file_line_and_problem(tmp_path, name):
    changes, message = BAD_ESM[name]
    path = write(tmp_path, f"{name.replace(' ', '_')}.asc", esm_text([0.1, 0.2], **changes))
    with pytest.raises(ValueError, match=message) as info:
        read_record(path)
    assert path.name in str(info.value)


def test_esm_bad_value_names_its_line(tmp_path):
    path = write(tmp_path, "bad.asc", esm_text([0.1, "x2", 0.3], NDATA=3))
    with pytest.raises(ValueError, match=r"bad\.asc.*line 66: .*'x2'"):
        read_record(path)


def test_asc_file_that_is_not_esm(tmp_path):
    path = write(tmp_path, "other.asc", "0 1\n1 2\n")
    with pytest.raises(ValueError, match=r"other\.asc.*not an ESM file"):
        read_record(path)


# --- suites ----------------------------------------------------------------------------------

@pytest.fixture()
def folder(tmp_path):
    d = tmp_path / "suite"
    d.mkdir()
    for name in ("decaying_sine.csv", "decaying_sine.AT2"):
        shutil.copy(DATA / name, d / name)
    shutil.copy(ESM, d / "b_esm.ASC")
    (d / "README.txt").write_text("three records\n")
    (d / "decaying_sine.VT2").write_text("a PEER velocity file\n")
    (d / ".hidden.csv").write_text("junk\n")
    return d


def test_folder_is_a_sorted_suite_of_its_record_files(folder):
    suite = read_suite(folder)
    assert [g.name for g in suite] == ["b_esm.ASC", "decaying_sine.AT2", "decaying_sine.csv"]
    assert suite[0].values == pytest.approx(read_record(ESM).values)
    assert suite[2].values == pytest.approx(read_record(DATA / "decaying_sine.csv").values)


def test_list_of_files_and_folders_does_not_depend_on_order(folder):
    a = read_suite([DATA / "decaying_sine.csv", ESM])
    b = read_suite([str(ESM), DATA / "decaying_sine.csv"])
    assert [g.name for g in a] == [g.name for g in b] == ["decaying_sine.ASC",
                                                          "decaying_sine.csv"]
    mixed = read_suite([folder / "b_esm.ASC", DATA / "decaying_sine.ASC"])
    assert [g.name for g in mixed] == ["b_esm.ASC", "decaying_sine.ASC"]
    assert len(read_suite([folder, folder / "b_esm.ASC"])) == 3  # the same file once


def test_suite_errors(tmp_path, folder):
    empty = tmp_path / "empty"
    empty.mkdir()
    (empty / "notes.md").write_text("no records\n")
    with pytest.raises(ValueError, match=r"empty'.*no record files.*\.asc, \.at2, \.csv"):
        read_suite(empty)
    with pytest.raises(ValueError, match=r"missing.*no such file or folder"):
        read_suite([tmp_path / "missing"])
    with pytest.raises(ValueError, match="at least one"):
        read_suite([])
    with pytest.raises(ValueError, match=r"two records .* 'decaying_sine\.csv'"):
        read_suite([folder, DATA / "decaying_sine.csv"])
    (folder / "zz_bad.csv").write_text("0,0\n0.1,abc\n")
    with pytest.raises(ValueError, match=r"zz_bad\.csv.*line 2"):
        read_suite(folder)


def test_reversed_record_is_the_other_polarity():
    g = read_suite(ESM)[0]
    r = g.reversed()
    assert r.values == pytest.approx(-g.values) and r.times is not None
    t = np.linspace(0, 2.5, 101)
    assert r.acceleration(t) == pytest.approx(-g.acceleration(t))
    assert r.name == "decaying_sine.ASC (reversed)" and r.reversed().name == g.name
