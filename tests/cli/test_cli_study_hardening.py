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
