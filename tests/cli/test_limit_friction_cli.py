"""``archquake limit --friction``: both directions under both friction laws, against the
library's chain program where nothing can slide, and refusals named."""

import json

import pytest

import archquake
from archquake.cli import main
from archquake.limit_analysis import friction_margin, load_multipliers


def _json(argv, capsys):
    assert main([*argv, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_high_friction_gives_heymans_multipliers(capsys):
    # mu = 10: no joint of Oppenheim's arch is near sliding, so k is the frictionless chain
    # program's in both directions, under both laws, and the mechanism has four hinges
    out = _json(["limit", "--friction", "10"], capsys)
    k_l, k_r = load_multipliers(archquake.oppenheim())
    for direction, k in (("+x", k_l), ("-x", k_r)):
        for law in ("associative", "non-associative"):
            entry = out["directions"][direction][law]
            assert entry["load_multiplier"] == pytest.approx(k, rel=1e-8)
            assert len(entry["rocking"]) == 4 and entry["sliding"] == []


def test_infinite_friction_is_heymans_one_law_in_words_too(capsys):
    # mu = inf: nothing can slide, so the two laws are one ("no sliding") and the last line says
    # Heyman's k, the frictionless chain program's, not "under the non-associative law"
    assert main(["limit", "--friction", "inf"]) == 0
    last = capsys.readouterr().out.strip().splitlines()[-1]
    k = min(load_multipliers(archquake.oppenheim()))
    assert last == f"k = {k:.4f}: the least of the two directions (Heyman: no sliding)"


def test_low_friction_slides_and_lowers_k(capsys, tmp_path):
    out = _json(["limit", "--friction", "0.35", "--plot", str(tmp_path / "f.png")], capsys)
    plus = out["directions"]["+x"]["non-associative"]
    assert plus["sliding"] and plus["converged"]
    assert out["k"] < load_multipliers(archquake.oppenheim())[0]
    assert (tmp_path / "f.png").stat().st_size > 10_000


def test_friction_too_low_to_stand_is_one_line(capsys):
    assert friction_margin(archquake.oppenheim(), 0.1) == float("-inf")
    assert main(["limit", "--friction", "0.1"]) == 2
    assert "cannot stand" in capsys.readouterr().err


@pytest.mark.parametrize("argv, match", [
    (["--friction", "-0.2"], "friction"),
    (["--friction", "0.4", "--method", "kinematic"], "static"),
])
def test_bad_friction_is_refused_by_name(argv, match, capsys):
    assert main(["limit", *argv]) == 2
    assert match in capsys.readouterr().err


def test_the_arbiter_stands_beside_both_laws(capsys):
    # Oppenheim's arch at mu = 0.35: a springing slides beside three hinges; the rigid blocks
    # under a slow ramp (Coulomb without dilatancy, an independent model) start to move at the
    # programs' multiplier, within the ramp's stated error, at the same interfaces
    out = _json(["limit", "--friction", "0.35", "--arbiter"], capsys)
    ramp = {o["direction"]: o for o in out["rigid_blocks_ramp"]["onsets"]}
    for direction in ("+x", "-x"):
        program = out["directions"][direction]["non-associative"]
        onset = ramp[direction]
        assert onset["multiplier"] == pytest.approx(program["load_multiplier"],
                                                    abs=onset["error"] + 1e-6)
        assert sorted(onset["sliding_joints"]) == program["sliding"]
        assert sorted(onset["rocking_joints"]) == program["rocking"]


def test_arbiter_needs_friction(capsys):
    assert main(["limit", "--arbiter"]) == 2
    assert "--friction" in capsys.readouterr().err


def test_min_thickness_with_friction_and_its_verdict(capsys):
    # the semicircle of 44 voussoirs: thicker at mu = 0.35 than without friction; none at 0.30
    # (published least friction 0.309215, tests/limit_analysis/test_min_thickness_friction.py)
    shape = ["min-thickness", "--shape", "circular", "--radius", "1", "--embrace", "180",
             "--voussoirs", "44"]
    free = _json(shape, capsys)
    mixed = _json([*shape, "--friction", "0.35"], capsys)
    assert mixed["ratio"] > free["ratio"] * 1.3 and mixed["friction"] == 0.35
    none = _json([*shape, "--friction", "0.30"], capsys)
    assert none["min_thickness"] is None and "no thickness" in none["verdict"]
