"""``archquake domain --model rigid-blocks`` of a block assembly (several spans, rings, a
drawing of one): the rigid blocks' failure domain, checked against the limit analysis; the
four-link model refused by name."""

import json

import pytest

from archquake.cli import main

BRIDGE = ["--spans", "2", "--piers", "3,6"]


def _json(argv, capsys):
    assert main([*argv, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_the_blocks_of_two_spans_start_moving_at_the_limit_analysis_multiplier(capsys):
    # an independent value: the linear program of the same bridge (no sliding at friction 0.8:
    # its mechanism rocks). Oppenheim's pulse holds -a g for t_p = 0.4 s, long enough for a
    # mechanism to open above k and never below it: the rest ends at k, to the bisection's
    # width
    k = _json(["limit", *BRIDGE], capsys)["k"]
    resolution = 0.002
    rows = _json(["domain", "--model", "rigid-blocks", *BRIDGE, "--durations", "0.4",
                  "--amplitudes", "0.1:0.5:0.02", "--resolution", str(resolution),
                  "--no-progress"], capsys)
    (row,) = rows
    assert row["model"] == "rigid-blocks" and row["undecided_analyses"] == 0
    rest, moving = row["intervals"][0], row["intervals"][1]
    assert rest["outcome"] == "rest" and moving["outcome"] != "rest"
    assert rest["to"] - resolution <= k <= rest["to"] + 1e-12
    # a pulse that moves the blocks does not topple them at once: collapse lies above k
    assert row["failure_acceleration"] > k + resolution


def test_the_screened_search_of_an_assembly_is_the_exhaustive_grids(capsys):
    # an assembly has no four-link model to screen it: its coarse scan alone, with the
    # safeguard that infers only rest and collapses during the pulse; on this grid it gives the
    # exhaustive grid's domain, with fewer analyses
    argv = ["domain", "--model", "rigid-blocks", *BRIDGE, "--durations", "0.3",
            "--amplitudes", "0.1:0.6:0.02", "--resolution", "0.002", "--extend-to", "0",
            "--no-progress"]
    (screened,) = _json(argv, capsys)
    (exhaustive,) = _json([*argv, "--search", "exhaustive"], capsys)
    assert screened["intervals"] == exhaustive["intervals"]
    assert screened["failure_acceleration"] == exhaustive["failure_acceleration"]


def test_the_text_names_the_rigid_blocks_and_the_undecided_count(capsys):
    assert main(["domain", "--model", "rigid-blocks", *BRIDGE, "--durations", "0.4",
                 "--amplitudes", "0.1:0.3:0.1", "--resolution", "0.01", "--extend-to", "0",
                 "--no-progress"]) == 0
    out = capsys.readouterr().out
    assert "rigid-block model, friction 0.8" in out
    assert "undecided: 0 of" in out


@pytest.mark.parametrize("argv", [BRIDGE, ["--rings", "2"]])
def test_the_four_link_model_of_an_assembly_is_refused_by_name(argv, capsys):
    assert main(["domain", "--model", "four-link", *argv]) == 2
    err = capsys.readouterr().err
    assert "has no four-link model: leave --model out or give --model rigid-blocks" in err


def test_an_assembly_takes_the_rigid_blocks_by_default_and_says_so(capsys):
    argv = [*BRIDGE, "--durations", "0.4", "--amplitudes", "0.1:0.3:0.1", "--no-progress",
            "--json"]
    assert main(["domain", *argv]) == 0
    captured = capsys.readouterr()
    assert "note: a block assembly" in captured.err and "the rigid-block model analyses it" \
        in captured.err
    (row,) = json.loads(captured.out)
    assert row["model"] == "rigid-blocks"
    assert main(["domain", "--model", "rigid-blocks", *argv]) == 0  # given: nothing to say
    captured = capsys.readouterr()
    assert "note:" not in captured.err and json.loads(captured.out) == [row]
