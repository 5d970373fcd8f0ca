"""The shape of the command line: one module per command, imported only when it runs or its help
is asked for (so that help answers without numpy), the library's checks named by option, and the
former names still accepted."""

import argparse
import json
import subprocess
import sys
from pathlib import Path

import pytest

from archquake.cli import COMMANDS, build_parser, command_module, main
from archquake.cli.options import OPTION_NAMES, RESTITUTION_METAVAR

ROOT = Path(__file__).resolve().parents[2]
DATA = ROOT / "tests" / "data"


def modules_after(argv: list[str]) -> set[str]:
    """The modules imported by ``archquake argv`` in a fresh interpreter."""
    code = ("import sys\nfrom archquake.cli import main\ntry:\n    main(sys.argv[1:])\n"
            "except SystemExit:\n    pass\nprint('\\nMODULES ' + ' '.join(sorted(sys.modules)))")
    done = subprocess.run([sys.executable, "-c", code, *argv], capture_output=True, text=True,
                          check=True, cwd=ROOT, env={"PYTHONPATH": str(ROOT / "src")})
    last = done.stdout.rstrip().rsplit("\n", 1)[-1]
    assert last.startswith("MODULES "), done.stdout + done.stderr
    return set(last.split()[1:])


def subparser(parser: argparse.ArgumentParser, name: str) -> argparse.ArgumentParser:
    (commands,) = [a for a in parser._actions if isinstance(a.choices, dict)]
    return commands.choices[name]


HELP = [["--help"], ["--version"]] + [[name, "--help"] for name in COMMANDS]


@pytest.mark.parametrize("argv", HELP, ids=" ".join)
def test_help_and_version_import_no_numpy(argv):
    loaded = modules_after(argv)
    assert "numpy" not in loaded
    commands = {m for m in loaded if m.startswith("archquake.cli.main_")}
    if argv[0].startswith("-"):
        assert not commands  # the table of commands: summaries without their modules
    else:
        assert commands == {f"archquake.cli.{COMMANDS[argv[0]].module}"}


def test_every_command_has_its_module_with_configure_and_run():
    for name, command in COMMANDS.items():
        module = command_module(name)
        assert module.__name__ == f"archquake.cli.{command.module}"
        assert callable(module.configure) and callable(module.run), name


def test_defaults_module_stays_light():
    loaded = modules_after(["--version"])
    assert "archquake.defaults" in loaded
    code = "import sys, archquake.defaults; print(sorted(sys.modules))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True, env={"PYTHONPATH": str(ROOT / "src")}).stdout
    assert "numpy" not in out and "archquake.geometry" not in out


def test_choices_and_defaults_shown_are_those_the_library_uses():
    from archquake import defaults
    from archquake.fourlink.impact import RESTITUTION_MODELS
    from archquake.geometry import CENTRELINES, VOUSSOIR_FACES
    from archquake.ground_motion import ANALYTIC_GROUND_MOTIONS, GROUND_MOTIONS
    from archquake.reference_arches import paper_values
    from archquake.rigid_blocks import BlockSettings

    assert tuple(CENTRELINES) == defaults.SHAPES
    assert VOUSSOIR_FACES == defaults.VOUSSOIR_FACES
    assert set(ANALYTIC_GROUND_MOTIONS) < set(GROUND_MOTIONS)
    # the rigid-block step is chosen from the structure: 1 ms exactly for Oppenheim's arch
    from archquake import oppenheim
    from archquake.rigid_blocks.dynamics import structure_time_step, time_step_for

    assert BlockSettings().time_step is None
    assert structure_time_step(defaults.REFERENCE_THICKNESS) == defaults.DEFAULT_TIME_STEP
    assert time_step_for(oppenheim()) == defaults.DEFAULT_TIME_STEP
    assert set(RESTITUTION_METAVAR.split("|")) == set(RESTITUTION_MODELS) | {"VALUE"}
    # Oppenheim's arch of the help is the paper's [Sect. 2]: R = 10 m, 157.5 deg, 1.5 m, n = 7
    arch = paper_values()["oppenheim"]
    args = build_parser(["limit"]).parse_args(["limit"])
    from archquake.cli.options import nominal_arch_from_args

    built = nominal_arch_from_args(args)
    assert built.n_voussoirs == arch["voussoirs"]
    assert built.radii.tolist() == [arch["radius"]] * arch["voussoirs"]
    assert built.thicknesses.tolist() == [arch["thickness"]] * arch["voussoirs"]
    help_text = " ".join(subparser(build_parser(["limit"]), "limit").format_help().split())
    assert (f"default: {arch['radius']:g} " in help_text
            and f"default: {arch['embrace_deg']:g})" in help_text)


def _options_of(parser: argparse.ArgumentParser) -> set[str]:
    found = set()
    for action in parser._actions:
        found |= set(action.option_strings)
        if isinstance(action.choices, dict):
            for sub in action.choices.values():
                found |= _options_of(sub)
    return found


def test_every_mapped_parameter_names_an_existing_option():
    options = _options_of(build_parser())
    assert set(OPTION_NAMES.values()) <= options


# --------------------------------------------------------------------------------------------
# one check, in the library: the command line names the option in the library's message
# --------------------------------------------------------------------------------------------


def library_message(call) -> str:
    with pytest.raises(ValueError) as exc:
        call()
    return str(exc.value)


def cli_error(capsys, argv) -> str:
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err
    return err.removeprefix("archquake: error: ").rstrip("\n")


def test_settings_errors_are_the_librarys_naming_the_option(capsys, tmp_path):
    from archquake.geometry import irregular_arch
    from archquake.reference_arches import oppenheim
    from archquake.rigid_blocks import BlockSettings
    from archquake.studies.fragility import FragilitySettings
    from archquake.studies.record_fragility import RecordFragilitySettings, RecordSuite

    out = ["--out", str(tmp_path / "study"), "--no-progress"]
    message = library_message(lambda: FragilitySettings(sample_size=0))
    assert message.startswith("sample_size ")
    assert cli_error(capsys, ["fragility", "--samples", "0", *out]) == (
        "--samples " + message.removeprefix("sample_size "))
    message = library_message(lambda: FragilitySettings(limit_sample_size=10**9))
    assert cli_error(capsys, ["fragility", "--limit-samples", "1000000000", *out]) == (
        "--limit-samples " + message.removeprefix("limit_sample_size "))
    message = library_message(lambda: irregular_arch(oppenheim(), 1.5, rng=0))
    for argv in (["limit", "--epsilon", "1.5"], ["fragility", "--epsilon", "1.5", *out]):
        assert cli_error(capsys, argv) == "--epsilon " + message.removeprefix("epsilon ")
    message = library_message(lambda: BlockSettings(friction=-1.0))
    assert cli_error(capsys, ["rigid-blocks", "--friction", "-1"]) == (
        "--friction " + message.removeprefix("friction "))
    suite = RecordSuite.from_paths([str(DATA / "decaying_sine.csv")])
    message = library_message(lambda: RecordFragilitySettings(suite=suite, levels=(1.0, 0.5)))
    argv = ["record-fragility", "--records", str(DATA / "decaying_sine.csv"), "--levels",
            "1,0.5", *out]
    assert cli_error(capsys, argv) == "--levels " + message.removeprefix("levels ")


def test_workers_are_checked_once_for_every_command(capsys, tmp_path):
    records = ["--records", str(DATA / "decaying_sine.csv"), "--levels", "0.5,1"]
    out = ["--out", str(tmp_path / "o"), "--no-progress"]
    messages = {cli_error(capsys, argv).rsplit(", got", 1)[0] for argv in (
        ["fragility", "--workers", "0", *out],
        ["record-fragility", *records, "--workers", "0", *out],
        ["compare", "--workers", "0", "--no-progress"])}
    assert len(messages) == 1 and messages.pop().startswith("--workers must be an integer in [1,")


# --------------------------------------------------------------------------------------------
# former names
# --------------------------------------------------------------------------------------------


@pytest.mark.parametrize("argv, refusal", [
    (["dem", "--json"], "invalid choice: 'dem'"),
    (["limit", "--tolerance", "0.1"], "unrecognized arguments: --tolerance"),
    (["limit", "--min-thickness"], "unrecognized arguments: --min-thickness"),
    (["fragility", "--records", "r.csv", "--levels", "0.5,1", "--out", "o"],
     "unrecognized arguments: --records"),
])
def test_former_spellings_are_refused_by_name(capsys, argv, refusal):
    """``dem`` (now ``rigid-blocks``), ``--tolerance`` (``--epsilon``), ``limit
    --min-thickness`` (``min-thickness``) and ``fragility --records`` (``record-fragility``)."""
    with pytest.raises(SystemExit) as exc:
        main(argv)
    assert exc.value.code == 2
    assert refusal in capsys.readouterr().err


def test_min_thickness_is_a_command(capsys, paper):
    from archquake.limit_analysis import min_thickness

    shape = ["--voussoirs", "40", "--radius", "1", "--embrace", "180"]
    assert main(["min-thickness", "--json", *shape]) == 0
    command = json.loads(capsys.readouterr().out)
    assert command["min_thickness"] == min_thickness(1.0, 3.141592653589793, 40)
    # Heyman's semicircular arch of many voussoirs: t/R = 0.107 (Ochsendorf's 0.1075)
    assert command["ratio"] == pytest.approx(0.1075, abs=1e-3)
