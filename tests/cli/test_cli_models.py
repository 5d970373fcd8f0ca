"""``--model``, ``--search`` and ``--stride`` on the command line: the rigid-block model in the
failure domain and the studies, the same numbers as the library and as ``compare``."""

import json

import numpy as np
import pytest

from archquake.cli import main

DATA = __import__("pathlib").Path(__file__).resolve().parents[1] / "data"


def test_domain_of_the_rigid_blocks_equals_the_compare_column(capsys):
    """On the same scan and resolution, ``domain --model rigid-blocks`` gives the failure
    accelerations of ``compare``'s rigid-block column."""
    scan = ["--durations", "0.3,0.6", "--amplitudes", "0.3:1.2:0.1", "--resolution", "0.01"]
    assert main(["domain", "--model", "rigid-blocks", *scan, "--json", "--extend-to", "0"]) == 0
    domain = json.loads(capsys.readouterr().out)
    assert main(["compare", *scan, "--json", "--no-progress"]) == 0
    compare = json.loads(capsys.readouterr().out)
    assert [r["failure_acceleration"] for r in domain] == [r["rigid_block"] for r in compare]
    assert [r["recovery_above"] for r in domain] == [r["recovery_above"]["rigid_block"]
                                                      for r in compare]
    assert all(r["model"] == "rigid-blocks" for r in domain)


def test_domain_text_says_the_model(capsys):
    argv = ["--durations", "0.6", "--amplitudes", "0.3:0.6:0.1", "--resolution", "0.01",
            "--extend-to", "0"]
    assert main(["domain", "--model", "rigid-blocks", *argv]) == 0
    text = capsys.readouterr().out
    assert "rigid-block model" in text and "search screened" in text


@pytest.mark.parametrize("other", ["elastic", "dem", "blocks", "rigid_blocks"])
def test_a_model_has_one_name(capsys, other):
    with pytest.raises(SystemExit) as exc:  # refused by the option parser, with its usage line
        main(["domain", "--model", other])
    assert exc.value.code == 2
    assert (f"--model: must be one of 'four-link', 'rigid-blocks', got {other!r}"
            in capsys.readouterr().err)


def test_fragility_with_the_rigid_blocks_records_its_model_and_search(capsys, tmp_path):
    argv = ["fragility", "--model", "rigid-blocks", "--samples", "1", "--durations", "0.5",
            "--amplitudes", "0.3:0.7:0.05", "--limit-samples", "2", "--no-progress", "--json"]
    assert main([*argv, "--out", str(tmp_path / "a")]) == 0
    screened = json.loads(capsys.readouterr().out)
    assert screened["settings"]["model"] == "rigid-blocks"
    assert screened["settings"]["search"] == "screened"
    assert main([*argv, "--search", "exhaustive", "--out", str(tmp_path / "b")]) == 0
    exhaustive = json.loads(capsys.readouterr().out)
    assert exhaustive["settings"]["search"] == "exhaustive"
    a = np.loadtxt(tmp_path / "a" / "curves.csv", delimiter=",", skiprows=1, usecols=(2,))
    b = np.loadtxt(tmp_path / "b" / "curves.csv", delimiter=",", skiprows=1, usecols=(2,))
    np.testing.assert_array_equal(a, b)  # P_F at every amplitude
    # resume refuses a change of model
    assert main([*argv[:2], "four-link", *argv[3:], "--out", str(tmp_path / "a"),
                 "--resume"]) == 2
    assert "differ" in capsys.readouterr().err


def test_record_fragility_with_the_rigid_blocks(capsys, tmp_path):
    argv = ["record-fragility", "--records", str(DATA / "decaying_sine.csv"), "--levels",
            "0.3:0.9:0.3", "--samples", "1", "--seed", "3", "--no-progress", "--json",
            "--model", "rigid-blocks", "--out", str(tmp_path / "r")]
    assert main(argv) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["settings"]["model"] == "rigid-blocks"
    assert summary["settings"]["stride"] == 4  # the record study's default


def test_compare_on_piers_leaves_out_the_restitution_rule_that_does_not_apply(capsys):
    """On piers the paper's link rule gives c_v = 0 (the pier and the first voussoir are at
    rest before the impact): the comparison says so and runs the other rules; the rigid blocks
    decide at every duration."""
    argv = ["compare", "--piers", "3,6", "--durations", "0.7", "--amplitudes", "0.1:0.5:0.1",
            "--resolution", "0.01", "--no-progress"]
    assert main(argv) == 0
    text = capsys.readouterr().out
    assert "restitution 'link' left out" in text
    assert main([*argv, "--json"]) == 0
    rows = json.loads(capsys.readouterr().out)
    assert "link" not in rows[0]["four_link"] and rows[0]["rigid_block"] is not None
