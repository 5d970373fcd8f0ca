import json
import os

import numpy as np
import pandas as pd
import pytest
from pandas.testing import assert_frame_equal

import archquake
from archquake.results_io import (
    StoredStudy,
    atomic_path,
    load_study,
    read_json,
    save_study,
    write_json,
)


@pytest.fixture
def table():
    """A tidy table with the column kinds a study produces, and awkward floats."""
    return pd.DataFrame({
        "item": np.array([0, 0, 1, 2], dtype=np.int64),
        "amplitude": [0.1, 1 / 3, 1e-300, np.pi],
        "duration": [np.nan, np.inf, -0.0, 2.5e10],
        "collapsed": [True, False, False, True],
        "outcome": ["collapse", "rest", "recovered", "collapse"],
    })


def test_parquet_round_trip_is_exact(tmp_path, table):
    metadata = {"seed": 7, "settings": {"tolerance": 0.05, "shape": "oppenheim"},
                "timings": {"wall_seconds": 1.5}}
    summary = {"median": np.float64(0.25), "counts": np.array([3, 1]), "n": np.int64(4)}
    save_study(tmp_path, table, metadata=metadata, summary=summary)
    stored = load_study(tmp_path)
    assert isinstance(stored, StoredStudy)
    assert_frame_equal(stored.table, table)
    assert stored.summary == {"median": 0.25, "counts": [3, 1], "n": 4}
    assert stored.metadata == {**metadata, "archquake_version": archquake.__version__}
    assert stored.table.attrs["study"] == stored.metadata


def test_csv_round_trip_is_exact_and_readable_by_plain_pandas(tmp_path, table):
    save_study(tmp_path, table, formats=("csv",))
    assert not (tmp_path / "results.parquet").exists()
    assert_frame_equal(load_study(tmp_path).table, table, check_dtype=False)
    # the CSV alone, read without our metadata, holds the same numbers
    plain = pd.read_csv(tmp_path / "results.csv")
    assert list(plain.columns) == list(table.columns)
    for name in ("item", "amplitude", "duration"):
        assert np.array_equal(plain[name].to_numpy(), table[name].to_numpy(), equal_nan=True)
    assert plain["outcome"].tolist() == table["outcome"].tolist()


def test_both_formats_hold_the_same_table(tmp_path, table):
    save_study(tmp_path, table)
    from_parquet = pd.read_parquet(tmp_path / "results.parquet")
    from_csv = pd.read_csv(tmp_path / "results.csv")
    assert_frame_equal(from_parquet, from_csv, check_dtype=False)


def test_metadata_defaults_to_the_table_attrs(tmp_path, table):
    table.attrs["study"] = {"seed": 3, "settings": {"a": [1, 2]}}
    save_study(tmp_path, table)
    record = json.loads((tmp_path / "summary.json").read_text())
    assert record["seed"] == 3 and record["settings"] == {"a": [1, 2]}
    assert record["rows"] == 4 and record["columns"]["item"] == "int64"
    assert load_study(tmp_path).metadata["seed"] == 3


def test_atomic_path_leaves_the_old_file_on_failure(tmp_path):
    target = tmp_path / "data.txt"
    target.write_text("old")
    with pytest.raises(RuntimeError), atomic_path(target) as tmp:
        tmp.write_text("half")
        raise RuntimeError("interrupted")
    assert target.read_text() == "old"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["data.txt"]
    with atomic_path(target) as tmp:
        tmp.write_text("new")
    assert target.read_text() == "new"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["data.txt"]


def test_failed_save_never_leaves_a_summary_vouching_for_stale_tables(tmp_path, table,
                                                                        monkeypatch):
    save_study(tmp_path, table)

    def broken(*args, **kwargs):
        raise OSError("disk full")

    monkeypatch.setattr(pd.DataFrame, "to_parquet", broken)
    with pytest.raises(OSError, match="disk full"):
        save_study(tmp_path, table.iloc[:2])
    assert_frame_equal(pd.read_parquet(tmp_path / "results.parquet"), table)  # untouched
    assert not list(tmp_path.glob(".*"))  # no temporary files left
    with pytest.raises(ValueError, match="resume"):
        load_study(tmp_path)


def test_json_helpers_round_trip_numpy_values(tmp_path):
    obj = {"a": np.float32(0.5), "b": np.arange(3), "c": [np.nan, np.inf], "d": tmp_path}
    write_json(tmp_path / "x.json", obj)
    back = read_json(tmp_path / "x.json")
    assert back["a"] == 0.5 and back["b"] == [0, 1, 2] and back["d"] == str(tmp_path)
    assert back["c"] == [None, None]  # strict JSON: no NaN, no Infinity


def test_json_writer_is_strict_json(tmp_path):
    """What write_json writes parses with a reader that refuses NaN and Infinity."""
    import json

    def refuse(name):
        raise AssertionError(f"{name} in the JSON")

    write_json(tmp_path / "x.json", {"t": np.float64("nan"), "u": [-np.inf, 1.0]})
    text = (tmp_path / "x.json").read_text()
    assert json.loads(text, parse_constant=refuse) == {"t": None, "u": [None, 1.0]}


def test_json_reader_refuses_duplicate_keys(tmp_path):
    (tmp_path / "x.json").write_text('{"a": 1, "b": 2, "a": 3}')
    with pytest.raises(ValueError, match="x.json is not valid JSON: the key 'a' is given twice"):
        read_json(tmp_path / "x.json")


@pytest.mark.parametrize("kwargs, message", [
    ({"formats": ("xlsx",)}, "formats"),
    ({"formats": ()}, "formats"),
    ({"summary": {"f": object()}}, "JSON"),
])
def test_save_study_rejects_invalid_input_without_writing(tmp_path, table, kwargs, message):
    with pytest.raises(ValueError, match=message):
        save_study(tmp_path / "out", table, **kwargs)
    assert not (tmp_path / "out").exists()


def test_save_study_rejects_non_tables(tmp_path):
    with pytest.raises(ValueError, match="DataFrame"):
        save_study(tmp_path, {"a": [1]})
    with pytest.raises(ValueError, match="strings"):
        save_study(tmp_path, pd.DataFrame({0: [1]}))


def test_load_study_explains_missing_results(tmp_path):
    with pytest.raises(ValueError, match="missing summary.json.*resume=True"):
        load_study(tmp_path)


@pytest.mark.parametrize("umask", [0o022, 0o077, 0o002])
def test_files_are_created_with_the_permissions_of_the_umask(tmp_path, umask):
    import stat

    import toy_tasks
    from archquake.execution import StudyPlan, run_study

    previous = os.umask(umask)
    try:
        run_study(toy_tasks.trivial_task, StudyPlan({}, 0, 4, 2), tmp_path / "study",
                  backend="serial", progress=False)
    finally:
        os.umask(previous)
    files = [p for p in (tmp_path / "study").rglob("*") if p.is_file()]
    assert {p.name for p in files} >= {"study.json", "chunk-000000.npz", "results.parquet",
                                       "results.csv", "summary.json"}
    for path in files:
        assert stat.S_IMODE(path.stat().st_mode) == 0o666 & ~umask, path.name


FORMULAS = ["=cmd|' /C calc'!A0", "+1+1", "-RSN6.AT2", "@SUM(A1)", "'=quoted", "''-twice", "'",
            "\t=tab.AT2",
            "plain.AT2", "a=b", "'plain"]


def test_record_names_in_csv_are_never_formulas_and_read_back_as_they_were(tmp_path):
    import csv

    from archquake.results_io import FORMULA_PREFIXES, read_spreadsheet_text, write_csv

    table = pd.DataFrame({"record": FORMULAS, "level": np.arange(len(FORMULAS)) - 3.0})
    save_study(tmp_path, table, formats=("csv",))
    with open(tmp_path / "results.csv", newline="") as fh:
        cells = [row["record"] for row in csv.DictReader(fh)]
    # what a spreadsheet sees: no cell starts like a formula, and the names are all there
    assert not [c for c in cells if c[:1] in FORMULA_PREFIXES]
    assert [read_spreadsheet_text(c) for c in cells] == FORMULAS
    assert cells[2] == "'-RSN6.AT2" and cells[8] == "plain.AT2"
    # numbers are numbers (a negative one is not text)
    assert pd.read_csv(tmp_path / "results.csv")["level"].tolist() == table["level"].tolist()
    assert_frame_equal(load_study(tmp_path).table, table)
    write_csv(tmp_path / "alone.csv", table)
    assert (tmp_path / "alone.csv").read_text() == (tmp_path / "results.csv").read_text()
