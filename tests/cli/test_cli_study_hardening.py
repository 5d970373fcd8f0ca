"""Studies that say what they did and refuse what they cannot do in the user's words: a resume
refused names the option that differs, an option of the other model is refused naming it."""

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
