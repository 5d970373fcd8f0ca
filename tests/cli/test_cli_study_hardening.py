"""Studies that say what they did and refuse what they cannot do in the user's words: a resume
refused names the option that differs, an option of the other model is refused naming it."""

import json
from pathlib import Path

import pytest

from archquake.cli import main

DATA = Path(__file__).resolve().parents[1] / "data"
FRAGILITY = ["fragility", "--durations", "0.4", "--amplitudes", "0.3:0.5:0.1",
             "--limit-samples", "2", "--no-progress", "--json"]


@pytest.mark.parametrize("option, first, second, setting", [
    ("--samples", "2", "3", "sample_size"),
    ("--samples", "3", "1", "sample_size"),
    ("--seed", "4", "7", "seed"),
    ("--epsilon", "0.1", "0.12", "epsilon"),
])
def test_a_refused_resume_names_the_option_that_differs(tmp_path, capsys, option, first,
                                                        second, setting):
    """A resume with another value of an option names that option (not n_items or
    chunk_size, what the study derives from it)."""
    out = ["--out", str(tmp_path / "s")]
    base = [a for a in FRAGILITY] + (["--samples", "2"] if option != "--samples" else [])
    assert main([*base, option, first, *out]) == 0
    capsys.readouterr()
    assert main([*base, option, second, *out, "--resume"]) == 2
    err = capsys.readouterr().err
    assert f"{option} (setting '{setting}') differs" in err
    assert "n_items" not in err and "chunk_size" not in err


def test_a_refused_resume_of_another_model_names_model(tmp_path, capsys):
    argv = ["record-fragility", "--records", str(DATA / "decaying_sine.csv"), "--levels",
            "0.3:0.9:0.3", "--samples", "1", "--seed", "3", "--no-progress", "--json",
            "--out", str(tmp_path / "r")]
    assert main(argv) == 0
    capsys.readouterr()
    assert main([*argv, "--model", "rigid-blocks", "--resume"]) == 2
    err = capsys.readouterr().err
    assert "--model (setting 'model') differs" in err and "chunk_size" not in err


COMMANDS = {
    "domain": ["domain", "--durations", "0.5", "--amplitudes", "0.3:0.5:0.1"],
    "fragility": FRAGILITY,
    "record-fragility": ["record-fragility", "--records", str(DATA / "decaying_sine.csv"),
                         "--levels", "0.3,0.6", "--samples", "1", "--no-progress"],
}


@pytest.mark.parametrize("command", sorted(COMMANDS))
@pytest.mark.parametrize("model, option, value, owner", [
    ("four-link", "--friction", "0.5", "rigid-blocks"),
    ("four-link", "--friction", "0.6", "rigid-blocks"),  # even its default, when given
    ("four-link", "--time-step", "0.002", "rigid-blocks"),
    ("four-link", "--coarse-factor", "1", "rigid-blocks"),
    ("rigid-blocks", "--restitution", "paper", "four-link"),
    ("rigid-blocks", "--restitution", "0.8", "four-link"),
])
def test_an_option_of_the_other_model_is_refused_naming_it(tmp_path, capsys, command, model,
                                                           option, value, owner):
    """Accepted, it would be recorded without effect and a resume without it refused."""
    out = tmp_path / "s"
    argv = [*COMMANDS[command], "--model", model, option, value]
    if command != "domain":
        argv += ["--out", str(out)]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert (f"archquake: error: {option} is a setting of the {owner} model, and this study "
            f"runs the {model} model") in err
    assert not out.exists()  # refused before anything is written


def test_the_model_options_of_the_model_run_are_taken(capsys):
    """The refusal is of the other model's options only: the rigid blocks take their own, the
    four-link model its restitution (the restitution printed: 'paper' = 0.875)."""
    assert main([*COMMANDS["domain"], "--restitution", "paper", "--extend-to", "0"]) == 0
    assert "restitution 0.8750 (l->r), 0.8750 (r->l)" in capsys.readouterr().out
    assert main([*COMMANDS["domain"], "--model", "rigid-blocks", "--friction", "0.7",
                 "--coarse-factor", "1", "--extend-to", "0"]) == 0
    assert "friction 0.7," in capsys.readouterr().out


class _Reached(Exception):
    """Raised in place of the analyses: the command got past its checks."""


def _stop_before_the_analyses(monkeypatch):
    from archquake.studies import failure_domain

    def reached(*args, **kwargs):
        raise _Reached

    monkeypatch.setattr(failure_domain, "_run_slices", reached)


@pytest.mark.parametrize("argv", [
    [],  # the defaults: 37 durations x (20 coarse points + 232 beyond) = 9324 <= 10000
    ["--durations", "0.2:1.0:0.1", "--search", "bisection", "--workers", "2"],  # the README's
    ["--durations", "0.1:1.0:0.02", "--extend-to", "5"],  # 46 x (20 + 44) = 2944
    ["--search", "exhaustive", "--extend-to", "0"],  # 37 x 146 = 5402
])
def test_the_scan_cap_of_a_rigid_block_domain_counts_what_its_search_analyses(monkeypatch,
                                                                             argv):
    """The cap (10000 rigid-block analyses) counts the coarse scan of a coarse search and its
    extension at its own step (the grid's 0.01 g times the stride 8), not every 0.01 g up to
    20 g: the default domain and the README's bisection example run. Hand count of the
    default: amplitudes 0.05:1.5:0.01 are 146 points, coarse indices 0, 8, ..., 144 (19) and
    the last, 145: 20; beyond 1.5 g up to 20 g every 0.08 g: ceil(18.5 / 0.08) = 232."""
    _stop_before_the_analyses(monkeypatch)
    with pytest.raises(_Reached):
        main(["domain", "--model", "rigid-blocks", *argv])


@pytest.mark.parametrize("argv, points", [
    (["--durations", "0.1:1.0:0.02"], 46 * (20 + 232)),  # 11592
    (["--durations", "0.1:1.0:0.02", "--stride", "16"], 46 * (11 + 116)),  # 5842: accepted
    (["--search", "exhaustive"], 37 * (146 + 1850)),  # 73852
    (["--search", "exhaustive", "--extend-to", "2.9"], 37 * (146 + 140)),  # 10582
])
def test_a_rigid_block_domain_too_large_is_refused_naming_extend_to(monkeypatch, capsys, argv,
                                                                   points):
    _stop_before_the_analyses(monkeypatch)
    if points <= 10000:
        with pytest.raises(_Reached):
            main(["domain", "--model", "rigid-blocks", *argv])
        return
    assert main(["domain", "--model", "rigid-blocks", *argv]) == 2
    err = capsys.readouterr().err
    assert f"= {points} analyses is too large: at most 10000" in err
    assert "--extend-to" in err


# --search bisection says on every output that it can miss bands, and how many points it
# inferred. Oppenheim's arch at t_p = 0.5 s (four-link model), exhaustively: recovery up to
# 0.485 g, collapse in the second half cycle 0.485-0.724 g, recovery 0.724-0.820 g. A grid
# whose coarse points (its two ends) both recover holds the collapse band wholly between them.
@pytest.mark.parametrize("amplitudes, points", [("0.45:0.78:0.01", 34),
                                                ("0.46:0.80:0.01", 35),
                                                ("0.40:0.76:0.02", 19)])
def test_bisection_that_misses_a_band_of_collapse_says_so_on_every_domain_output(
        capsys, amplitudes, points):
    argv = ["domain", "--durations", "0.5", "--amplitudes", amplitudes, "--extend-to", "0",
            "--resolution", "0.001"]
    assert main([*argv, "--json"]) == 0
    exhaustive = json.loads(capsys.readouterr().out)[0]
    assert exhaustive["failure_acceleration"] == pytest.approx(0.4847, abs=1e-3)
    assert main([*argv, "--json", "--search", "bisection", "--stride", str(points - 1)]) == 0
    row = json.loads(capsys.readouterr().out)[0]
    assert row["failure_acceleration"] is None  # the band is missed ...
    # ... and the output says so: two coarse points analysed (the ends), points - 2 inferred
    assert row["search"] == "bisection" and row["scan_points"] == points
    assert row["not_analysed"] == points - 2
    assert row["caveat"].startswith(f"search 'bisection' did not analyse {points - 2} of the "
                                    f"{points} grid points")
    assert "misses any band of collapse" in row["caveat"]
    assert main([*argv, "--search", "bisection", "--stride", str(points - 1)]) == 0
    text = capsys.readouterr().out
    assert "boundaries to 0.001 g where the search found them" in text
    assert f"warning: search 'bisection' did not analyse {points - 2} of the {points}" in text


def test_bisection_counts_the_extension_points_it_steps_over(capsys):
    """Beyond 0.78 g the scan goes on every 33 x 0.01 g: one point, 1.11 g, which collapses
    in the first half cycle (exhaustively from 0.820 g); the 33 points at 0.01 g up to it are
    scan points, 32 of them not analysed: 34 + 33 = 67 points, 32 + 32 = 64 not analysed."""
    assert main(["domain", "--durations", "0.5", "--amplitudes", "0.45:0.78:0.01", "--stride",
                 "33", "--search", "bisection", "--json"]) == 0
    row = json.loads(capsys.readouterr().out)[0]
    assert (row["scan_points"], row["not_analysed"], row["scanned_to"]) == (67, 64, 1.11)


@pytest.mark.parametrize("stride", [33, 10])
def test_bisection_says_so_in_a_pulse_study_and_its_files(tmp_path, capsys, monkeypatch,
                                                          stride):
    """Text, JSON and summary.json say it; the count is that of the points of the exhaustive
    grid (1 arch x 2 directions x 34 amplitudes = 68, and as many of the nominal arch's two
    domains) less those the search analysed (counted where it runs)."""
    from archquake.results_io import read_json
    from archquake.studies import strategies

    argv = ["fragility", "--samples", "1", "--durations", "0.5", "--amplitudes",
            "0.45:0.78:0.01", "--limit-samples", "2", "--no-progress",
            "--no-model-check"]  # the check's own rigid-block search is not the study's
    assert main([*argv, "--json", "--out", str(tmp_path / "e")]) == 0
    exhaustive = json.loads(capsys.readouterr().out)["search"]
    assert (exhaustive["grid_points"], exhaustive["not_analysed"]) == (68, 0)
    assert exhaustive["caveat"] is None
    real, seen = strategies.search_grid, []

    def counting(*args, **kwargs):
        keys, analysed = real(*args, **kwargs)
        seen.append((analysed.size, int(analysed.sum())))
        return keys, analysed

    monkeypatch.setattr(strategies, "search_grid", counting)
    bisection = [*argv, "--search", "bisection", "--stride", str(stride)]
    assert main([*bisection, "--json", "--out", str(tmp_path / "b")]) == 0
    search = json.loads(capsys.readouterr().out)["search"]
    assert search["grid_points"] == 68 and search["nominal_grid_points"] == 68
    inferred = sum(n - done for n, done in seen)
    assert search["not_analysed"] + search["nominal_not_analysed"] == inferred > 0
    assert search["caveat"].startswith(f"search 'bisection' did not analyse {inferred} of the "
                                       f"136 grid points")
    assert read_json(tmp_path / "b" / "summary.json")["summary"]["search"] == search
    assert main([*bisection, "--out", str(tmp_path / "c")]) == 0
    assert f"warning: {search['caveat']}" in capsys.readouterr().out


def test_bisection_says_so_in_a_record_study(tmp_path, capsys):
    argv = ["record-fragility", "--records", str(DATA / "decaying_sine.csv"), "--levels",
            "0.1:1.0:0.1", "--samples", "1", "--seed", "3", "--no-progress", "--search",
            "bisection", "--stride", "9"]
    assert main([*argv, "--json", "--out", str(tmp_path / "r")]) == 0
    search = json.loads(capsys.readouterr().out)["search"]
    # 2 arches (1 irregular, the nominal) x 1 record x 10 levels x 2 polarities = 40 points
    assert search["grid_points"] == 40 and 0 < search["not_analysed"] <= 40 - 2 * 2 * 2
    assert f"did not analyse {search['not_analysed']} of the 40 grid points" in search["caveat"]
    assert main([*argv, "--out", str(tmp_path / "t")]) == 0
    assert f"warning: {search['caveat']}" in capsys.readouterr().out


def test_bisection_says_so_in_compare(capsys):
    """The rigid-block column of compare: 7 amplitudes 0.3-0.6 g, coarse points every 6 steps
    (the two ends): at least 2 analysed, so at most 5 of the 7 inferred."""
    argv = ["compare", "--durations", "0.6", "--amplitudes", "0.3:0.6:0.05", "--resolution",
            "0.01", "--no-progress", "--search", "bisection", "--stride", "6"]
    assert main([*argv, "--json"]) == 0
    row = json.loads(capsys.readouterr().out)[0]
    assert row["search"] == "bisection" and row["scan_points"] == 7
    assert 0 <= row["not_analysed"] <= 5
    assert row["caveat"].startswith(f"rigid blocks: search 'bisection' did not analyse "
                                    f"{row['not_analysed']} of the 7 grid points")
    assert main(argv) == 0
    assert "warning: rigid blocks: search 'bisection' did not analyse" in (
        capsys.readouterr().out)


@pytest.mark.parametrize("argv", [["simulate", "--friction", "0.5"],
                                  ["simulate", "--time-step", "0.001"],
                                  ["compare", "--restitution", "paper"]])
def test_a_command_of_fixed_models_has_no_option_of_a_model_it_does_not_run(capsys, argv):
    """simulate runs the four-link model only, compare every restitution rule of it beside
    the rigid blocks: neither takes an option it would not use (refused by the parser)."""
    with pytest.raises(SystemExit) as exc:
        main(argv)
    assert exc.value.code == 2 and f"unrecognized arguments: {argv[1]}" in (
        capsys.readouterr().err)


@pytest.mark.parametrize("friction", ["0.7", "0.9"])
def test_a_rigid_block_record_study_header_names_the_rigid_blocks_not_a_restitution(
        tmp_path, capsys, friction):
    argv = ["record-fragility", "--model", "rigid-blocks", "--friction", friction,
            "--records", str(DATA / "decaying_sine.csv"), "--levels", "0.2:0.6:0.2",
            "--samples", "1", "--seed", "2", "--no-progress", "--out", str(tmp_path / "r")]
    assert main(argv) == 0
    header = next(line for line in capsys.readouterr().out.splitlines()
                  if line.startswith("Record-based fragility"))
    assert "restitution" not in header
    assert f"rigid-block model (friction {float(friction):g}" in header


@pytest.mark.parametrize("restitution, friction", [("paper", "0.6"), ("0.8", "0.75")])
def test_a_command_of_both_models_gives_each_its_own_options(restitution, friction):
    # records-for-site runs the rigid blocks and the four-link model: --restitution is the
    # four-link model's and --friction the rigid blocks', neither refused
    from archquake.cli import build_parser
    from archquake.cli.options import model_spec_from_args

    args = build_parser(("records-for-site",)).parse_args(
        ["records-for-site", "--code", "ntc2018", "--ag", "0.2", "--f0", "2.4", "--tc-star",
         "0.3", "--suite", "fema-p695-far-field", "--restitution", restitution,
         "--friction", friction])
    rigid = model_spec_from_args(args, "rigid-blocks", both=True)
    four = model_spec_from_args(args, "four-link", both=True)
    assert rigid.friction == float(friction) and four.name == "four-link"
    assert str(four.restitution) == restitution or four.restitution == float(restitution)
