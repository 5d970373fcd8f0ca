"""The command line's shape options: every subcommand that takes geometry takes any shape, and
conflicting options are refused in one line."""

import json
import math

import pytest

from archquake.cli import main
from archquake.fourlink.impact import restitution
from archquake.fourlink.mechanism import mechanisms
from archquake.geometry import SHAPES, shaped_arch, surveyed_arch
from archquake.limit_analysis import both_directions, shaped_min_thickness

RISES = {"circular": 3.5, "pointed": 7.5, "elliptical": 4.0, "parabolic": 4.5, "catenary": 4.5,
         "three-centred": 3.0}


def shape_args(shape, *extra):
    return ["--shape", shape, "--span", "10", "--rise", str(RISES[shape]), "--thickness", "0.8",
            "--voussoirs", "8", *extra]


def run_json(capsys, argv):
    assert main(argv) == 0
    return json.loads(capsys.readouterr().out)


@pytest.mark.parametrize("shape", SHAPES)
def test_limit_of_every_shape_matches_the_library(capsys, shape):
    out = run_json(capsys, ["limit", "--json", *shape_args(shape, "--faces", "flat")])
    arch = shaped_arch(shape, span=10.0, rise=RISES[shape], thickness=0.8, voussoirs=8,
                       faces="flat")
    results = both_directions(arch)
    assert (out["k_l"], out["k_r"]) == pytest.approx(
        tuple(r.load_multiplier for r in results), abs=1e-12)
    for r in results:
        hinges = out["mechanisms"][r.direction]["hinges"]
        assert [(h["joint"], h["face"]) for h in hinges] == [(h.joint, h.face)
                                                            for h in r.hinges]
        assert [h["beta"] for h in hinges] == pytest.approx(r.hinge_angles, abs=1e-12)


def test_limit_text_of_a_shape_gives_hinge_positions(capsys):
    assert main(["limit", *shape_args("pointed")]) == 0
    out = capsys.readouterr().out
    assert "pointed arch, span = 10 m, rise = 7.5 m" in out
    assert "x [m]" in out and "y [m]" in out and "beta [rad]" in out


def test_min_thickness_names_its_ratio(capsys):
    out = run_json(capsys, ["min-thickness", "--json", "--shape", "pointed", "--span",
                            "10", "--rise", "7.5", "--voussoirs", "8"])
    t = shaped_min_thickness("pointed", span=10.0, rise=7.5, voussoirs=8)
    assert out == pytest.approx({"min_thickness": t, "ratio": t / 10.0, "ratio_of": "span"})
    circle = run_json(capsys, ["min-thickness", "--json", "--span", "2", "--rise", "1",
                               "--voussoirs", "40"])
    assert circle["ratio_of"] == "radius" and circle["ratio"] == pytest.approx(
        circle["min_thickness"] / 1.0)
    paper = run_json(capsys, ["min-thickness", "--json", "--voussoirs", "40",
                              "--radius", "1", "--embrace", "180"])
    assert paper["ratio_of"] == "radius"
    assert paper["ratio"] == pytest.approx(circle["ratio"], rel=1e-9)


def test_flat_faced_oppenheim_arch_gives_the_papers_link_restitution(capsys):
    out = run_json(capsys, ["mechanism", "--faces", "flat", "--restitution", "link", "--json"])
    assert round(out["restitution"]["l_to_r"], 3) == 0.875
    arch = shaped_arch("circular", radius=10.0, embrace=math.radians(157.5), thickness=1.5,
                       voussoirs=7, faces="flat")
    assert out["restitution"]["l_to_r"] == pytest.approx(
        restitution("link", *mechanisms(arch))[0], rel=1e-12)


def test_surveyed_geometry_file(capsys, tmp_path, nominal):
    blocks = [nominal.outline(i, 60)[:-1].tolist() for i in range(7)]
    path = tmp_path / "survey.json"
    path.write_text(json.dumps({"blocks": blocks}))
    out = run_json(capsys, ["limit", "--json", "--geometry", str(path)])
    survey = surveyed_arch(blocks)
    assert (out["k_l"], out["k_r"]) == pytest.approx(
        tuple(r.load_multiplier for r in both_directions(survey)), abs=1e-12)
    assert out["k"] == pytest.approx(0.37, abs=2e-3)
    assert main(["limit", "--geometry", str(path), "--epsilon", "0.1"]) == 2
    assert "centreline" in capsys.readouterr().err


def test_irregular_shaped_arch_on_the_command_line_is_the_librarys(capsys):
    from archquake.geometry import irregular_arch
    from archquake.limit_analysis import load_multipliers

    out = run_json(capsys, ["limit", "--json", *shape_args("catenary"), "--epsilon", "0.1",
                            "--seed", "3"])
    arch = irregular_arch(shaped_arch("catenary", span=10.0, rise=4.5, thickness=0.8,
                                      voussoirs=8), 0.1, rng=3)
    assert (out["k_l"], out["k_r"]) == pytest.approx(load_multipliers(arch), abs=1e-12)


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["limit", "--shape", "pointed", "--radius", "3", "--voussoirs", "8"],
         "--radius apply to circular arches only"),
        (["limit", "--shape", "elliptical"], "an elliptical arch needs --span and --rise"),
        (["limit", "--span", "10"], "needs --span and --rise"),
        (["limit", "--span", "10", "--rise", "3", "--radius", "4"], "not both"),
        (["limit", "--shape", "pointed", "--span", "10", "--rise", "7", "--voussoirs", "7"],
         "divisible by 2"),
        (["limit", "--shape", "pointed", "--span", "10", "--rise", "4", "--voussoirs", "8"],
         "rise > span / 2"),
        (["limit", "--shape", "parabolic", "--span", "10", "--rise", "4", "--thickness", "7"],
         "radius of curvature"),
        (["limit", "--shape", "parabolic", "--span", "-10", "--rise", "4"], "--span"),
        (["limit", "--shape", "parabolic", "--span", "10", "--rise", "nan"], "--rise"),
        (["limit", "--geometry", "{file}", "--shape", "circular"], "--shape"),
        (["limit", "--geometry", "{file}", "--faces", "flat"], "--faces"),
        (["mechanism", "--geometry", "{file}", "--span", "10"], "--span"),
        (["domain", "--shape", "catenary", "--radius", "5"], "circular arches only"),
        (["simulate", "--shape", "three-centred", "--span", "10", "--rise", "1"],
         "three-centred"),
    ],
)
def test_conflicting_or_bad_shape_options_exit_2_with_one_line(capsys, tmp_path, argv, message):
    path = tmp_path / "arch.json"
    path.write_text(json.dumps({"angles": [0.5] * 4, "thicknesses": [1.0] * 4,
                                "radii": [10.0] * 4}))
    argv = [str(path) if a == "{file}" else a for a in argv]
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("archquake: error: ") and "\n" not in err
    assert message in err


@pytest.mark.parametrize("command", ["limit", "mechanism", "domain", "simulate",
                                     "rigid-blocks", "fragility"])
def test_every_geometry_subcommand_takes_the_shape_options(capsys, command):
    with pytest.raises(SystemExit) as exc:
        main([command, "--help"])
    assert exc.value.code == 0
    out = capsys.readouterr().out
    for option in ("--shape", "--span", "--rise", "--thickness", "--voussoirs", "--faces",
                   "--radius", "--embrace", "--geometry"):
        assert option in out


def test_limit_plot_of_a_shape(tmp_path, capsys):
    path = tmp_path / "pointed.png"
    assert main(["limit", *shape_args("pointed"), "--epsilon", "0.1", "--plot",
                 str(path)]) == 0
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
