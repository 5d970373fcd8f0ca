"""``archquake limit --geometry DRAWING.dxf``: any block assembly drawn in CAD, against closed
forms, and the drawings' conventions (units, outlines drawn by repeating their first vertex)."""

import json

import ezdxf
import pytest

from archquake.cli import main
from archquake.geometry.assembly import portal, wall
from archquake.geometry.dxf import write_dxf


def _json(argv, capsys):
    assert main([*argv, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_a_portal_sways_at_b_over_h(tmp_path, capsys):
    # Piers b x h, a lintel on them. The least mechanism: each pier rocks about its outer base
    # corner (the right one under a load toward +x) by theta, the lintel hinged on the piers'
    # top left corners translates by (theta h, theta b): gravity works W_p theta b/2 per pier and
    # W_l theta b, the loads k (W_p theta h/2 per pier + W_l theta h); with W_p = rho b h:
    # k (W_p h + W_l h) = b (W_p + W_l), so k = b/h = 0.5/2 = 0.25, whatever the lintel.
    path = tmp_path / "portal.dxf"
    write_dxf(portal(0.5, 2.0, 1.2, 0.3), path)
    out = _json(["limit", "--geometry", str(path)], capsys)
    for direction in ("+x", "-x"):
        entry = out["directions"][direction]["no sliding"]
        assert entry["load_multiplier"] == pytest.approx(0.25, rel=1e-9)
        assert len(entry["rocking"]) == 4 and entry["sliding"] == []


def test_a_wall_slides_at_mu_or_rocks_as_a_whole(tmp_path, capsys):
    # 6 courses x 8 blocks 0.4 x 0.2 m: 3.2 m wide, 1.2 m tall. Without sliding the least
    # mechanism here is the whole wall rocking about a base corner, k = B/H = 3.2/1.2; with
    # mu = 0.5 < B/H a course slides on the one below (or on the ground) at k = mu.
    path = tmp_path / "wall.dxf"
    write_dxf(wall(6, 8, 0.4, 0.2), path)
    rigid = _json(["limit", "--geometry", str(path)], capsys)
    assert rigid["k"] == pytest.approx(3.2 / 1.2, rel=1e-9)
    sliding = _json(["limit", "--geometry", str(path), "--friction", "0.5"], capsys)
    for direction in ("+x", "-x"):
        for law in ("associative", "non-associative"):
            entry = sliding["directions"][direction][law]
            assert entry["load_multiplier"] == pytest.approx(0.5, rel=1e-7)
            assert entry["sliding"] and entry["converged"]


def _block_drawing(path, units_code, scale, repeat):
    """Two stacked blocks 0.4 x 1 m drawn by hand, in the drawing's units, each outline
    repeating its first ``repeat`` vertices at its end (as some CAD exports do), not flagged
    closed."""
    doc = ezdxf.new("R2010")
    doc.header["$INSUNITS"] = units_code
    msp = doc.modelspace()
    for y0 in (0.0, 1.0):
        corners = [(-0.2, y0), (0.2, y0), (0.2, y0 + 1.0), (-0.2, y0 + 1.0)]
        points = [(x * scale, y * scale) for x, y in corners + corners[:repeat]]
        msp.add_lwpolyline(points, close=False)
    doc.saveas(path)


@pytest.mark.parametrize("units_code, scale, repeat", [(4, 1000.0, 1), (6, 1.0, 2)])
def test_a_stack_drawn_in_mm_rocks_at_its_closed_form(tmp_path, capsys, units_code, scale,
                                                      repeat):
    # two blocks b x h = 0.4 x 1 m: the stack rocks about its base corner at k = b / (2 h)
    path = tmp_path / "stack.dxf"
    _block_drawing(path, units_code, scale, repeat)
    out = _json(["limit", "--geometry", str(path)], capsys)
    assert out["k"] == pytest.approx(0.2, rel=1e-9)
    # the header's units: a scale-free multiplier, but --units changes the blocks' size
    assert main(["limit", "--geometry", str(path), "--units", "mm"]) == 0


def test_commands_without_assemblies_refuse_one_by_name(tmp_path, capsys):
    path = tmp_path / "wall.dxf"
    write_dxf(wall(2, 2, 0.4, 0.2), path)
    assert main(["domain", "--model", "four-link", "--geometry", str(path)]) == 2
    assert "block assembly" in capsys.readouterr().err
    assert main(["limit", "--geometry", str(path), "--method", "kinematic"]) == 2
    assert "static" in capsys.readouterr().err


def test_the_rigid_blocks_take_a_drawing(tmp_path, capsys):
    # Housner's block 0.4 x 1 m (friction 0.8 > b/h: it rocks, never slides): at rest under a
    # pulse below b/h = 0.4 g (closed form); above it, the outcome of the
    # block built by rigid_blocks.rectangular_block (Housner's block on its base, another
    # construction of the same model)
    from archquake.geometry.assembly import block_on_ground
    from archquake.ground_motion import oppenheim_pulse
    from archquake.rigid_blocks import block_outcome, rectangular_block

    path = tmp_path / "block.dxf"
    write_dxf(block_on_ground(0.4, 1.0), path)
    base = ["rigid-blocks", "--geometry", str(path), "--motion", "oppenheim"]
    assert _json([*base, "--amplitude", "0.35"], capsys)["outcome"] == "rest"
    drawn = _json([*base, "--amplitude", "0.5"], capsys)
    from archquake.constants import GRAVITY

    built = block_outcome(rectangular_block(0.4, 1.0), oppenheim_pulse(0.5 * GRAVITY, 0.27))
    # (the moment a collapse is called certain depends on each construction's length scale and
    # time step, so only the outcome is compared)
    assert drawn["outcome"] == built.status.label == "collapse"


def test_the_rigid_blocks_say_the_assemblys_own_friction(capsys):
    # an arch of two rings sliding on each other at 0.6, its other joints not at all: the run
    # uses (and says) the assembly's friction per kind, not the model's default 0.8
    out = _json(["rigid-blocks", "--rings", "2", "--ring-friction", "0.6", "--amplitude",
                 "0.05"], capsys)
    assert out["friction"] == {"foundation": None, "bed": None, "ring": 0.6}
    assert _json(["rigid-blocks", "--amplitude", "0.05"], capsys)["friction"] == 0.8
