"""Bad and extreme inputs on the command line: every one is a one-line error that names the
option or file and the accepted range (exit status 2), refused before any long computation."""

import json
import threading
import time

import pytest

from archquake.cli import main
from archquake.studies.failure_domain import domain_slice


def run_error(capsys, argv, tmp_path=None):
    """Run ``archquake argv``; return its stderr, checking it is a clear error, quickly."""
    if argv[0] == "fragility" and "--out" not in argv:
        argv = [*argv, "--out", str(tmp_path / "study")]
    t0 = time.monotonic()
    try:
        code = main(argv)
    except SystemExit as exc:  # refused by the option parser: usage line, then the error
        code = exc.code
    assert code == 2
    assert time.monotonic() - t0 < 20  # refused, not attempted
    err = capsys.readouterr().err
    assert "Traceback" not in err
    assert err.startswith("archquake: error:") or "\narchquake " in err and " error: " in err
    return err


# ------------------------------------------------------------------ sizes and resolutions


def test_bisection_below_float_resolution_ends():
    # the classes change at a = 0.3 exactly; a tolerance below the spacing of floats must
    # still end, with the boundary between two neighbouring floats
    def classify(a):
        return ("collapse", 1) if a >= 0.3 else ("recovery", 0)

    done = []
    worker = threading.Thread(target=lambda: done.append(
        domain_slice(classify, [0.0, 1.0], resolution_g=1e-300)), daemon=True)
    worker.start()
    worker.join(10.0)
    assert done, "the bisection did not end"
    (_, second) = done[0].intervals
    assert abs(second.start - 0.3) <= 2e-16


@pytest.mark.parametrize("argv, message", [
    (["domain", "--resolution", "1e-16"], "--resolution must be >= 1e-09 g"),
    (["domain", "--resolution", "nan"], "--resolution"),
    (["domain", "--durations", "0.1:1000:0.0001"], "--durations: the range 0.1:1000:0.0001 "
                                                   "has 9999001 values"),
    (["domain", "--durations", "0.1:50:0.001", "--amplitudes", "0.05:1.5:0.001"],
     "at most 1000000"),
    (["fragility", "--samples", "1000000000"], "--samples must be an integer in [1, 100000]"),
    (["fragility", "--limit-samples", "1000000000"],
     "--limit-samples must be an integer in [1, 1000000]"),
    (["fragility", "--samples", "100000", "--amplitudes", "0.01:1.00:0.001"],
     "analyses"),
    (["fragility", "--durations", "0.1:10:0.001", "--amplitudes", "0.01:1.00:0.001"],
     "at most 1000000"),
    (["fragility", "--thickness", "0.5"], "the nominal arch cannot be analysed: the arch admits "
                                          "no thrust line"),
])
def test_huge_or_meaningless_sizes_are_refused(capsys, tmp_path, argv, message):
    err = run_error(capsys, argv, tmp_path)
    assert message in err


@pytest.mark.parametrize("voussoirs", ["100000", "1000000000", "1e9"])
def test_an_arch_of_too_many_voussoirs_is_refused(capsys, voussoirs):
    err = run_error(capsys, ["limit", "--voussoirs", voussoirs])
    assert "--voussoirs" in err


def test_a_geometry_file_of_too_many_voussoirs_is_refused(capsys, tmp_path):
    n = 10_001
    path = tmp_path / "many.json"
    path.write_text(json.dumps({"angles": [2.5 / n] * n, "thicknesses": [1.0] * n,
                                "radii": [10.0] * n}))
    err = run_error(capsys, ["limit", "--geometry", str(path)])
    assert str(path) in err and "voussoirs must be at most 10000" in err


# ------------------------------------------------------------------ geometry files

GOOD = {"angles": [0.5, 0.5, 0.5, 0.5], "thicknesses": [1.0] * 4, "radii": [10.0] * 4}


@pytest.mark.parametrize("content, message", [
    ({**GOOD, "angles": [0.5, True, 0.5, 0.5]}, "'angles' item 1 is true, not a number"),
    ({**GOOD, "radii": [10.0, "10.5", 10.0, 10.0]}, "'radii' item 1 is \"10.5\", not a number"),
    ({**GOOD, "thicknesses": [1.0, None, 1.0, 1.0]}, "'thicknesses' item 1 is null"),
    ({**GOOD, "density": "2000"}, "'density' is \"2000\", not a number"),
    ({**GOOD, "density": False}, "'density' is false, not a number"),
    ({**GOOD, "angles": [0.5, [0.5], 0.5, 0.5]}, "'angles' item 1 is [0.5], not a number"),
])
def test_geometry_values_must_be_json_numbers(capsys, tmp_path, content, message):
    path = tmp_path / "arch.json"
    path.write_text(json.dumps(content))
    err = run_error(capsys, ["limit", "--geometry", str(path)])
    assert str(path) in err and message in err


@pytest.mark.parametrize("make, message", [
    (lambda p: p.write_bytes(b'{"angles": [0.5]}\xff\xfe'), "is not UTF-8 text"),
    (lambda p: p.write_text(""), "is empty"),
    (lambda p: p.mkdir(), "is a directory"),
    (lambda p: p.write_text("{'angles': [1]}"), "is not valid JSON"),
    (lambda p: p.write_text(json.dumps({**GOOD, "angles": [0.5, -0.5, 0.5, 0.5]})),
     "angles must all be > 0"),
])
def test_geometry_file_problems_name_the_file(capsys, tmp_path, make, message):
    path = tmp_path / "arch.json"
    make(path)
    err = run_error(capsys, ["mechanism", "--geometry", str(path)])
    assert str(path) in err and message in err


# ------------------------------------------------------------------ options of the arch


@pytest.mark.parametrize("argv, message", [
    (["limit", "--embrace", "-10"], "--embrace must be in (0, 360) degrees, got -10"),
    (["limit", "--embrace", "360"], "--embrace must be in (0, 360) degrees"),
    (["limit", "--embrace", "nan"], "--embrace"),
    (["limit", "--radius", "inf"], "--radius must be a finite number > 0 [m], got inf"),
    (["limit", "--radius", "0"], "--radius"),
    (["limit", "--thickness", "25"], "--thickness must be < 2 x radius = 20.0 m, got 25.0 m"),
    (["limit", "--thickness", "nan"], "--thickness"),
    (["limit", "--voussoirs", "3"], "--voussoirs must be >= 4 for a four-hinge mechanism, got 3"),
    (["limit", "--voussoirs", "100000"], "--voussoirs must be at most 10000"),
    (["limit", "--epsilon", "0.1", "--seed", "-1"], "--seed must be an integer >= 0, got -1"),
    (["mechanism", "--epsilon", "nan"], "--epsilon must be in [0, 1), got nan"),
    (["simulate", "--epsilon", "-0.1"], "--epsilon must be in [0, 1), got -0.1"),
    (["limit", "--geometry", "{arch}", "--radius", "5"], "--geometry"),
    (["domain", "--geometry", "{arch}", "--voussoirs", "20"], "--voussoirs"),
])
def test_arch_options_are_named_with_their_units(capsys, tmp_path, argv, message):
    path = tmp_path / "arch.json"
    path.write_text(json.dumps(GOOD))
    err = run_error(capsys, [a.format(arch=path) for a in argv])
    assert message in err


@pytest.mark.parametrize("seed", ["1", "2"])
def test_a_tolerance_too_large_for_a_valid_arch_says_so(capsys, seed):
    # epsilon = 0.99 separates neighbouring voussoirs (their radial extents no longer overlap)
    err = run_error(capsys, ["limit", "--epsilon", "0.99", "--seed", seed])
    assert "--epsilon 0.99" in err and f"seed {seed}" in err and "too large" in err
    assert "must touch" in err


def test_an_irregular_arch_that_cannot_stand_is_an_error_not_a_negative_k(capsys):
    # epsilon = 0.9, seed 1: the drawn arch cannot carry its own weight (the static linear
    # program's largest multiplier is negative), so there is no activation threshold
    err = run_error(capsys, ["limit", "--epsilon", "0.9", "--seed", "1"])
    assert "cannot stand under its own weight" in err and "--epsilon 0.9" in err


# ------------------------------------------------------------------ ground motions


@pytest.mark.parametrize("argv, message", [
    (["simulate", "--amplitude", "1e300"], "--amplitude must be a finite acceleration within "
                                           "+-1000 g, got 1e+300"),
    (["simulate", "--amplitude=-1e150"], "--amplitude"),
    (["simulate", "--amplitude", "nan"], "--amplitude"),
    (["simulate", "--record", "{record}", "--scale-to", "1e300"], "--scale-to must be at most "
                                                                  "1000 g"),
    (["simulate", "--motion", "stochastic", "--scale-to", "1e300"], "--scale-to: ground "
                                                                    "acceleration must be at "
                                                                    "most 1000 g"),
    (["simulate", "--record", "{huge}"], "peak acceleration 1e+300 g is more than the 1000 g"),
    (["simulate", "--motion", "harmonic", "--amplitude", "0.5", "--cycles", "1e9"],
     "--cycles must be at most 10000 (MAX_CYCLES), got 1e+09"),
    (["simulate", "--motion", "harmonic", "--amplitude", "0.5", "--cycles", "-2"], "cycles"),
    (["simulate", "--duration", "inf"], "--duration must be a finite number > 0 [s], got inf"),
    (["simulate", "--t-end", "-1"], "--t-end"),
    (["simulate", "--phi0", "-0.1"], "phi0"),
    (["simulate", "--phi0", "5"], "phi0"),
])
def test_ground_motion_options_out_of_range(capsys, tmp_path, argv, message):
    record, huge = tmp_path / "record.csv", tmp_path / "huge.csv"
    record.write_text("0,0\n0.1,0.2\n0.2,0\n")
    huge.write_text("0,0\n0.1,1e300\n0.2,0\n")
    err = run_error(capsys, [a.format(record=record, huge=huge) for a in argv])
    assert message in err
    if "huge" in " ".join(argv):
        assert str(huge) in err


def test_a_motion_too_long_for_the_step_budget_is_a_clear_error():
    from archquake import oppenheim
    from archquake.fourlink.impact import restitution
    from archquake.fourlink.mechanism import mechanisms
    from archquake.fourlink.time_history import simulate
    from archquake.status import Status

    pair = mechanisms(oppenheim())
    c = restitution("elastic", *pair)  # rocks for ever: no outcome ends the record early
    with pytest.raises(ValueError, match=r"more than 2000 steps .* shorter t_end"):
        simulate(pair, None, c, initial=("l", 0.02, 0.0), t_end=1e4, max_steps=2000)
    huge = simulate(pair, None, c, initial=("l", 0.02, 0.0), t_end=1.0, max_steps=10**6)
    assert huge.outcome.status is Status.RECOVERY


# ------------------------------------------------------------------ options that conflict


@pytest.mark.parametrize("argv, message", [
    (["simulate", "--phi0", "0.01", "--record", "{record}"], "--phi0"),
    (["simulate", "--phi0", "0.01", "--amplitude", "-0.5"], "--amplitude"),
    (["simulate", "--phi0", "0.01", "--motion", "sine"], "--motion"),
    (["simulate", "--phi0", "0.01", "--duration", "0.3"], "--duration"),
    (["simulate", "--motion", "sine", "--record", "{record}"], "--motion sine"),
    (["simulate", "--record", "{record}", "--amplitude", "-1"], "--amplitude"),
    (["simulate", "--record", "{record}", "--duration", "0.3"], "--duration"),
    (["simulate", "--scale-to", "0.3", "--phi0", "0.01"], "--scale-to"),
])
def test_conflicting_options_are_refused_not_dropped(capsys, tmp_path, argv, message):
    record = tmp_path / "record.csv"
    record.write_text("0,0\n0.1,0.2\n0.2,0\n")
    err = run_error(capsys, [a.format(record=record) for a in argv])
    assert message in err and ("cannot" in err or "applies" in err)


def test_a_record_alone_and_free_vibration_alone_still_run(capsys, tmp_path):
    record = tmp_path / "record.csv"
    record.write_text("0,0\n0.1,0.2\n0.2,0\n")
    assert main(["simulate", "--record", str(record), "--json"]) == 0
    assert main(["simulate", "--motion", "record", "--record", str(record), "--json"]) == 0
    assert main(["simulate", "--phi0", "0.01", "--t-end", "2", "--json"]) == 0
    assert main(["simulate", "--motion", "sine", "--amplitude", "-0.3", "--json"]) == 0
    capsys.readouterr()


# ------------------------------------------------------------------ found by probing


@pytest.mark.parametrize("argv, message", [
    (["min-thickness", "--embrace", "1e-5"], "degenerate"),
    (["limit", "--radius", "1e300"], "--radius must be"),
    (["limit", "--radius", "1e-300", "--thickness", "1e-301"], "--radius must be"),
    (["domain", "--amplitudes", "-1:1:0.5"], "--amplitudes must be >= 0 [g]"),
    (["domain", "--amplitudes", "0:2000:100"], "at most 1000 g, got 2000.0"),
    (["domain", "--extend-to", "1e9"], "--extend-to must be"),
    (["fragility", "--workers", "100000"], "--workers must be an integer in [1, "),
    (["limit", "--plot", "{directory}"], "is a directory"),
    (["simulate", "--plot", "{directory}/figure"], "extension"),
])
def test_more_extreme_inputs_are_clear_errors(capsys, tmp_path, argv, message):
    err = run_error(capsys, [a.format(directory=tmp_path) for a in argv], tmp_path)
    assert message in err


def test_negative_numbers_are_option_values(capsys):
    # argparse alone takes "-1e-3" for an option and answers "expected one argument"
    assert main(["simulate", "--amplitude", "-1e-3", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["outcome"] == "rest"


@pytest.mark.parametrize("argv, message", [
    (["rigid-blocks", "--time-step", "1e-12"], "time steps"),
    (["rigid-blocks", "--t-end", "1e9"], "time steps"),
    (["rigid-blocks", "--animate", "{directory}", "--t-end", "0.2"], "is a directory"),
    (["rigid-blocks", "--animate", "{directory}/blocks.png", "--t-end", "0.2"], ".gif"),
    (["simulate", "--motion", "stochastic", "--param", "dt=1e-12"], "samples"),
    (["simulate", "--motion", "stochastic", "--param", "duration=1e9"], "samples"),
    (["simulate", "--motion", "mavroeidis-papageorgiou", "--amplitude", "0.5", "--param",
      "gamma=1e9"], "gamma must be"),
    (["simulate", "--motion", "cycloidal-c", "--amplitude", "0.5", "--param", "n=1e9"],
     "n (main cycles of a type-C_n pulse) must be"),
])
def test_sizes_of_the_other_models_and_motions_are_bounded(capsys, tmp_path, argv, message):
    err = run_error(capsys, [a.format(directory=tmp_path) for a in argv], tmp_path)
    assert message in err
