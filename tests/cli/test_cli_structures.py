"""The command line's piers, fill and density options: the same numbers as the hand-drawn
surveyed-blocks file and as the library, "cannot stand" in one line naming the piers, and every
bad value named by its option."""

import json
import math

import pytest

from archquake import oppenheim
from archquake.cli import main
from archquake.geometry import Fill, Pier, Structure, shaped_arch
from archquake.limit_analysis import both_directions, min_pier_width
from structures_reference import piers_survey

FLAT = ["--faces", "flat"]


def run_json(capsys, argv):
    assert main(argv) == 0
    return json.loads(capsys.readouterr().out)


def hinges(out, direction):
    return [(h["joint"], h["face"]) for h in out["mechanisms"][direction]["hinges"]]


@pytest.mark.parametrize("faces", ["curved", "flat"])
def test_limit_on_piers_equals_the_surveyed_blocks_file(capsys, tmp_path, faces):
    """``limit --piers 3,6`` on Oppenheim's arch: k and the four hinges, the last at the right
    pier's outer toe, and the same numbers from the blocks drawn by hand in a geometry file
    (exactly with flat faces; to the sampling of the arcs, 400 points a face, with curved
    ones)."""
    extra = FLAT if faces == "flat" else []
    out = run_json(capsys, ["limit", "--piers", "3,6", "--json", *extra])
    assert out["k"] == pytest.approx(0.1439 if faces == "curved" else 0.1427, abs=1e-4)
    last = out["mechanisms"]["l"]["hinges"][-1]
    assert (last["face"], last["where"]) == ("extrados", "right pier base")
    arch = oppenheim() if faces == "curved" else shaped_arch(
        "circular", radius=10.0, embrace=math.radians(157.5), thickness=1.5, voussoirs=7,
        faces="flat")
    blocks, springings = piers_survey(arch, (3.0, 6.0), (3.0, 6.0))
    path = tmp_path / "piers.json"
    path.write_text(json.dumps({"blocks": blocks, "springings": springings}))
    survey = run_json(capsys, ["limit", "--geometry", str(path), "--json"])
    tolerance = 1e-11 if faces == "flat" else 1e-6
    assert survey["k_l"] == pytest.approx(out["k_l"], rel=tolerance)
    assert survey["k_r"] == pytest.approx(out["k_r"], rel=tolerance)
    for direction in ("l", "r"):
        assert hinges(survey, direction) == hinges(out, direction)


def test_piers_too_narrow_cannot_stand_in_one_line(capsys):
    assert main(["limit", "--piers", "2,6", "--json"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err
    assert err.startswith("archquake: error: the piers (rectangular pier 2 m wide, 6 m high, 1 "
                          "course) cannot carry the arch's thrust")


def test_min_pier_width(capsys):
    out = run_json(capsys, ["limit", "--min-pier-width", "--piers", ",6", "--json"])
    assert out == {"min_pier_width": pytest.approx(min_pier_width(oppenheim(), 6.0), rel=1e-9),
                   "height": 6.0, "courses": 1}
    assert main(["limit", "--min-pier-width", "--piers", ",6,3"]) == 0
    assert "width = 2.0" in capsys.readouterr().out
    assert main(["limit", "--min-pier-width", "--piers", "3,6"]) == 2
    assert "leave it blank" in capsys.readouterr().err


@pytest.mark.parametrize("passive", [False, True])
@pytest.mark.parametrize("inertia", ["none", "centroid", "extrados"])
def test_fill_models_give_the_library_s_k_and_hinges(capsys, inertia, passive):
    argv = ["limit", "--fill-cover", "0.5", "--fill-density", "1600", "--fill-inertia", inertia,
            "--json"] + (["--fill-passive", "30,0.33"] if passive else [])
    out = run_json(capsys, argv)
    fill = Fill(0.5, 1600.0, inertia, *((math.radians(30), 0.33) if passive else (None, None)))
    for r in both_directions(Structure(oppenheim(), fill=fill)):
        assert out[f"k_{r.direction}"] == pytest.approx(r.load_multiplier, rel=1e-12)
        assert hinges(out, r.direction) == [(h.joint, h.face) for h in r.hinges]


def test_only_the_ratio_of_the_densities_counts(capsys):
    """k is a ratio of forces: scaling the masonry's and the fill's densities together leaves
    it, changing one of them does not."""
    base = ["limit", "--piers", "3,6", "--fill-cover", "0.5", "--json"]
    one = run_json(capsys, base + ["--density", "2000", "--fill-density", "1600"])
    two = run_json(capsys, base + ["--density", "2500", "--fill-density", "2000"])
    other = run_json(capsys, base + ["--density", "2500", "--fill-density", "1600"])
    assert two["k"] == pytest.approx(one["k"], rel=1e-10)
    assert abs(other["k"] - one["k"]) > 1e-4


def test_unequal_piers_and_a_structure_file(capsys, tmp_path):
    out = run_json(capsys, ["limit", "--pier-left", "3,6", "--pier-right", "4,5,2", "--json"])
    assert out["k_l"] != pytest.approx(out["k_r"])
    path = tmp_path / "structure.json"
    path.write_text(json.dumps(Structure(oppenheim(), Pier(3.0, 6.0), Pier(4.0, 5.0, 2))
                               .to_dict()))
    again = run_json(capsys, ["limit", "--geometry", str(path), "--json"])
    assert again["k_l"] == pytest.approx(out["k_l"], rel=1e-12)
    assert main(["limit", "--geometry", str(path), "--piers", "3,6"]) == 2
    assert "describes a structure already" in capsys.readouterr().err


@pytest.mark.parametrize(("argv", "message"), [
    (["--piers", "1.2,6"], "--piers: left pier: pier width must be at least"),
    (["--piers", "3,x"], "--piers takes numbers separated by commas"),
    (["--piers", ",6"], "a blank WIDTH only with limit --min-pier-width"),
    (["--piers", "3,6,1.5"], "--piers: COURSES must be an integer"),
    (["--piers", "3,6", "--pier-left", "3,6"], "--piers gives both piers"),
    (["--pier-right", "3,-6"], "--pier-right: height must be"),
    (["--fill-density", "1600"], "the fill needs --fill-cover"),
    (["--fill-cover", "-1"], "--fill-cover: cover must be in"),
    (["--fill-cover", "0.5", "--fill-density", "0"], "--fill-density: fill density must be"),
    (["--fill-cover", "0.5", "--fill-passive", "95,0.3"], "--fill-passive: PHI must be in"),
    (["--fill-cover", "0.5", "--fill-passive", "30"], "--fill-passive takes 2 to 2 numbers"),
    (["--density", "-5"], "--density must be a number in [1, 100000] kg/m^3"),
])
def test_bad_values_name_their_option(capsys, argv, message):
    assert main(["limit", *argv]) == 2
    err = capsys.readouterr().err
    assert message in err and err.count("\n") == 1


def test_dynamics_refuse_a_fill_that_is_no_mass(capsys):
    assert main(["mechanism", "--fill-cover", "0.5", "--fill-inertia", "extrados"]) == 2
    assert "fill inertia 'extrados' is a limit-analysis model" in capsys.readouterr().err
    assert main(["mechanism", "--piers", "3,6", "--fill-cover", "0.5", "--json"]) == 0
