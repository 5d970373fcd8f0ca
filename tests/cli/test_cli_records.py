"""``archquake records`` (intensity measures of a suite) and the ground-motion options of
``archquake simulate`` (new pulses, --param, --reverse, stochastic motions)."""

import json
import re
import shutil
from pathlib import Path

import numpy as np
import pytest

from archquake.cli import main
from archquake.geometry import GRAVITY

DATA = Path(__file__).parents[1] / "data"


def run_json(capsys, *argv):
    assert main([*argv, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


# --- records ---------------------------------------------------------------------------------

def test_records_json_is_a_list_keyed_by_the_im_names(capsys, tmp_path):
    for name in ("decaying_sine.csv", "decaying_sine.AT2", "decaying_sine.ASC"):
        shutil.copy(DATA / name, tmp_path / name)
    (tmp_path / "notes.txt").write_text("not a record\n")
    out = run_json(capsys, "records", str(tmp_path), "--im", "pga,pgv,sa(0.5)")
    assert [row["record"] for row in out] == ["decaying_sine.ASC", "decaying_sine.AT2",
                                              "decaying_sine.csv"]
    assert all(list(row) == ["record", "pga", "pgv", "sa(0.5)"] for row in out)
    t, a_g = np.loadtxt(DATA / "decaying_sine.csv", delimiter=",", skiprows=3, unpack=True)
    assert out[2]["pga"] == pytest.approx(np.max(np.abs(a_g)), rel=1e-12)
    # ESM file in cm/s^2: its peak sample over 100 g
    cm = np.loadtxt(DATA / "decaying_sine.ASC", skiprows=64)
    assert out[0]["pga"] == pytest.approx(np.max(np.abs(cm)) / 100 / GRAVITY, rel=1e-12)
    # velocity of a linear interpolant at the samples: the trapezoid sums; between samples it
    # can exceed them by at most h max|a| / 4 (the parabola's bulge where a crosses zero)
    v = np.concatenate(([0.0], np.cumsum(np.diff(t) * (a_g[1:] + a_g[:-1]) / 2))) * GRAVITY
    bulge = 0.01 * np.max(np.abs(a_g)) * GRAVITY / 4
    assert np.max(np.abs(v)) <= out[2]["pgv"] <= np.max(np.abs(v)) + bulge


def test_records_table(capsys):
    assert main(["records", str(DATA / "decaying_sine.AT2"), "--im", "pga, arias"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].split() == ["record", "pga", "[g]", "arias", "[m/s]"]
    assert lines[1].startswith("decaying_sine.AT2")


@pytest.mark.parametrize("argv, message", [
    (["--im", "pga,pgz"], r"unknown intensity measure 'pgz'.*pga, pgv"),
    (["--im", "sa(-1)"], "period T of sa"),
    (["--im", "pga,PGA"], "twice"),
])
def test_records_bad_im(capsys, argv, message):
    assert main(["records", str(DATA / "decaying_sine.csv"), *argv]) == 2
    err = capsys.readouterr().err
    assert err.startswith("archquake: error:") and re.search(message, err)


def test_records_bad_files(capsys, tmp_path):
    (tmp_path / "bad.csv").write_text("0,0\n0.1,oops\n")
    assert main(["records", str(tmp_path / "bad.csv")]) == 2
    assert "bad.csv" in capsys.readouterr().err
    empty = tmp_path / "empty"
    empty.mkdir()
    assert main(["records", str(empty)]) == 2
    assert "no record files" in capsys.readouterr().err


# --- simulate --------------------------------------------------------------------------------

def test_reverse_of_a_pulse_on_the_symmetric_arch_is_the_mirror_case(capsys):
    """Oppenheim's arch is symmetric: -xg'' on it is +xg'' on the mirrored arch, with the same
    outcome and largest rotation."""
    forward = run_json(capsys, "simulate", "--amplitude", "0.8", "--duration", "0.4")
    reverse = run_json(capsys, "simulate", "--amplitude", "-0.8", "--duration", "0.4",
                       "--reverse")
    assert forward["outcome"] == reverse["outcome"] and forward["max_phi"] > 0
    assert reverse["max_phi"] == pytest.approx(forward["max_phi"], rel=1e-9)


def test_reverse_of_a_record_is_the_record_with_its_sign_flipped(capsys, tmp_path):
    t, a = np.loadtxt(DATA / "decaying_sine.csv", delimiter=",", skiprows=3, unpack=True)
    flipped = tmp_path / "flipped.csv"
    np.savetxt(flipped, np.column_stack([t, -a]), delimiter=",")
    a_ = run_json(capsys, "simulate", "--record", str(DATA / "decaying_sine.csv"),
                  "--scale-to", "0.8", "--reverse")
    b_ = run_json(capsys, "simulate", "--record", str(flipped), "--scale-to", "0.8")
    assert a_ == b_ and a_["max_phi"] > 0


@pytest.mark.parametrize("argv", [
    ["--motion", "ricker", "--amplitude", "-0.9", "--duration", "0.4"],
    ["--motion", "ricker-antisymmetric", "--amplitude", "0.9"],
    ["--motion", "cycloidal-c", "--param", "n=2", "--amplitude", "-0.6", "--duration", "0.5"],
    ["--motion", "mavroeidis-papageorgiou", "--param", "gamma=2.5", "--param", "phase=1.0",
     "--amplitude", "-1.2", "--duration", "0.8"],
    ["--motion", "harmonic", "--cycles", "3", "--amplitude", "-0.5", "--duration", "0.3"],
])
def test_simulate_offers_the_new_pulses(capsys, argv):
    from archquake import oppenheim
    from archquake.cli import build_parser
    from archquake.cli.options import motion_from_args
    from archquake.fourlink.impact import restitution
    from archquake.fourlink.mechanism import mechanisms
    from archquake.fourlink.time_history import simulate

    out = run_json(capsys, "simulate", *argv)
    motion = motion_from_args(build_parser().parse_args(["simulate", *argv]))
    mech = mechanisms(oppenheim())
    direct = simulate(mech, motion, restitution("computed", *mech), record=False)
    assert out["outcome"] == direct.status.label
    assert out["max_phi"] == pytest.approx(direct.max_phi, rel=1e-12)


def test_stochastic_motion_from_the_command_line(capsys):
    from archquake.cli import build_parser
    from archquake.cli.options import motion_from_args
    from archquake.ground_motion import stochastic_motion

    argv = ["simulate", "--motion", "stochastic", "--param", "seed=4", "--param",
            "significant_duration=8", "--param", "midpoint_time=5", "--scale-to", "0.5"]
    motion = motion_from_args(build_parser().parse_args(argv))
    raw = stochastic_motion(significant_duration=8.0, midpoint_time=5.0, rng=4)
    assert motion.values == pytest.approx(raw.values * 0.5 * GRAVITY / raw.peak)
    assert run_json(capsys, *argv)["outcome"] in ("rest", "recovery", "collapse")


@pytest.mark.parametrize("argv, message", [
    (["--motion", "ricker", "--param", "gamma=2"], "--param gamma does not apply"),
    (["--motion", "mavroeidis-papageorgiou", "--param", "gamma"], "NAME=VALUE"),
    (["--motion", "mavroeidis-papageorgiou", "--param", "gamma=two"], "not a number"),
    (["--motion", "mavroeidis-papageorgiou", "--param", "gamma=0.5"], "gamma must be > 1"),
    (["--motion", "cycloidal-c", "--param", "n=1.5"], "whole number"),
    (["--motion", "harmonic", "--param", "cycles=2", "--cycles", "3"], "twice"),
    (["--motion", "stochastic", "--amplitude", "0.5"], "--amplitude applies to an analytic"),
    (["--motion", "stochastic", "--param", "gamma=2"], "its parameters: seed"),
    (["--record", str(DATA / "decaying_sine.csv"), "--duration", "1"], "--duration applies"),
    (["--record", str(DATA / "decaying_sine.csv"), "--motion", "ricker"], "cannot be combined"),
    (["--motion", "ricker", "--scale-to", "0.3"], "--scale-to applies"),
])
def test_simulate_refuses_parameters_that_do_not_apply(capsys, argv, message):
    assert main(["simulate", *argv]) == 2
    assert message in capsys.readouterr().err
