"""Fuzzing the command line: option values valid, borderline and hostile, for every command
that answers in seconds. Each run keeps the contract of :mod:`fuzzing` (strict JSON with
finite numbers, or one error line naming an option or a file, status 2; no traceback; bounded
time). ``make fuzz`` runs these with many more examples (HYPOTHESIS_PROFILE=fuzz)."""

import pytest
from hypothesis import event, given
from hypothesis import strategies as st

from archquake.defaults import SHAPES, VOUSSOIR_FACES
from fuzzing import check_run, integers_text, numbers, options, run_cli, words

pytestmark = pytest.mark.fuzz

SHAPE = {
    "--shape": words(SHAPES), "--span": numbers(1.0, 40.0), "--rise": numbers(0.5, 20.0),
    "--radius": numbers(1.0, 40.0), "--embrace": numbers(30.0, 240.0),
    "--thickness": numbers(0.1, 3.0), "--voussoirs": integers_text(4, 60),
    "--faces": words(VOUSSOIR_FACES), "--density": numbers(100.0, 5000.0),
}
STRUCTURE = {
    "--piers": st.one_of(st.tuples(numbers(0.5, 5.0), numbers(0.5, 10.0)).map(",".join),
                         st.sampled_from(["1,2,3", "1", "", ",2", "1,2,0", "a,b"])),
    "--fill-cover": numbers(0.0, 3.0), "--fill-density": numbers(1000.0, 2500.0),
    "--fill-inertia": words(("none", "centroid", "extrados")),
}
IRREGULAR = {"--epsilon": numbers(0.0, 0.3), "--seed": integers_text(0, 1000)}
RESTITUTION = {"--restitution": st.one_of(
    words(("computed", "link", "nominal", "paper", "elastic", "measured", "blocks")),
    numbers(0.0, 1.0))}
MOTION = {
    "--motion": words(("oppenheim", "rectangular", "sine", "harmonic", "ricker",
                       "cycloidal-a", "mavroeidis-papageorgiou", "stochastic")),
    "--amplitude": numbers(-2.0, 2.0), "--duration": numbers(0.05, 2.0),
    "--cycles": numbers(1.0, 20.0), "--t-end": numbers(0.1, 10.0),
    "--param": st.sampled_from(["cycles=3", "gamma=2.5", "phase=1", "seed=3", "n=2",
                                "duration=5", "dt=0.01", "x=1", "gamma=", "=1", "gamma=nan"]),
    "--reverse": None,
}

COMMAND_LINES = st.one_of(
    st.tuples(st.just(["limit"]), options({**SHAPE, **STRUCTURE, **IRREGULAR,
                                          "--method": words(("static", "kinematic")),
                                          "--json": None})),
    st.tuples(st.just(["mechanism"]), options({**SHAPE, **IRREGULAR, **RESTITUTION,
                                              "--json": None})),
    st.tuples(st.just(["min-thickness"]), options({
        "--shape": words(SHAPES), "--span": numbers(1.0, 40.0), "--rise": numbers(0.5, 20.0),
        "--voussoirs": integers_text(4, 40), "--faces": words(VOUSSOIR_FACES),
        "--json": None})),
    st.tuples(st.just(["simulate"]), options({**{k: SHAPE[k] for k in ("--thickness",
                                                                       "--voussoirs")},
                                             **RESTITUTION, **MOTION,
                                             "--phi0": numbers(0.0, 1.5), "--json": None})),
    st.tuples(st.just(["domain", "--extend-to", "0"]), options({
        "--durations": st.one_of(numbers(0.1, 1.0),
                                 st.sampled_from(["0.2:0.6:0.2", "0.5,0.3", "0.1:1:0",
                                                  "1e6", "0.4:0.4:1"])),
        "--amplitudes": st.one_of(st.sampled_from(["0.2:1:0.1", "0.3:0.5:0.05", "1:0.2:0.1",
                                                   "0.2,0.1", "0:2000:100", "0.2:1.0:0.3"]),
                                  numbers(0.0, 3.0)),
        "--resolution": numbers(0.001, 0.05), "--direction": words(("l", "r")),
        "--thickness": SHAPE["--thickness"], "--json": None})),
    st.tuples(st.just(["check"]), options({
        **{k: SHAPE[k] for k in ("--thickness", "--voussoirs", "--span", "--rise", "--shape")},
        **STRUCTURE,
        "--code": words(("ntc2018", "ec8", "user", "nz")), "--ag": numbers(-0.1, 2.0),
        "--f0": numbers(1.5, 4.0), "--tc-star": numbers(0.0, 1.2),
        "--soil": words(("A", "B", "C", "D", "E", "F")),
        "--topography": words(("T1", "T4", "T5")), "--damping": numbers(0.0, 40.0),
        "--agr": numbers(0.0, 1.0), "--knowledge-level": words(("LC1", "LC3", "LC9")),
        "--limit-state": words(("SLV", "SLC", "SLO")),
        "--elevation": numbers(0.0, 30.0), "--building-height": numbers(1.0, 30.0),
        "--building-period": numbers(0.0, 2.0), "--storeys": integers_text(0, 10),
        "--json": None})),
    st.tuples(st.just(["spectrum"]), options({
        "--code": words(("ntc2018", "ec8", "user")), "--ag": numbers(-0.1, 2.0),
        "--f0": numbers(1.5, 4.0), "--tc-star": numbers(0.0, 1.2),
        "--soil": words(("A", "C", "E", "F")), "--agr": numbers(0.0, 1.0),
        "--type": words(("1", "2", "3")), "--periods": st.sampled_from(
            ["0:4:0.1", "0.5", "-1", "4:0:0.1", "nan", "0,1,2"]), "--json": None})),
)


def _names(argv):
    """What an error of ``argv`` may name: its options, and the arch or motion it describes."""
    return [a for a in argv if a.startswith("--")] + ["arch", "motion", "pulse", "record"]


@given(COMMAND_LINES)
def test_a_command_line_gives_a_result_or_one_error_line(parts):
    command, rest = parts
    argv = [*command, *rest]
    status, out, err = run_cli(argv)
    event(f"{command[0]}: {check_run(argv, status, out, err, names=_names(argv))}")


RIGID_BLOCK_LINES = st.tuples(st.just(["rigid-blocks"]), options({
    "--amplitude": numbers(-1.5, 1.5), "--duration": numbers(0.05, 1.0),
    "--friction": numbers(0.0, 1.0), "--time-step": numbers(1e-4, 1e-2),
    "--t-end": numbers(0.1, 5.0), "--json": None}))


@given(RIGID_BLOCK_LINES)
def test_a_rigid_block_command_line_gives_a_result_or_one_error_line(parts):
    command, rest = parts
    argv = [*command, *rest]
    status, out, err = run_cli(argv)
    event(f"{command[0]}: {check_run(argv, status, out, err, names=_names(argv))}")
