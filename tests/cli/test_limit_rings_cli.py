"""``archquake limit --rings N``: Oppenheim's arch in rings that can separate, against the chain
program of the one-ring arch, and how ``--ring-friction`` combines with ``--friction``."""

import json
import math

import pytest

from archquake.cli import main
from archquake.geometry import circular_arch
from archquake.limit_analysis import load_multipliers


def _json(argv, capsys):
    assert main([*argv, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_two_rings_of_oppenheims_arch(capsys):
    # the rings cannot slide on each other: the one-ring four-hinge mechanism through both rings
    # is the weakest (tests/limit_analysis/test_rings_limit.py), so k is the chain program's
    # 0.37001 of Oppenheim's arch, within the chords' error (arc_error 1.5 mm: 3e-5)
    out = _json(["limit", "--rings", "2"], capsys)
    k_chain = load_multipliers(circular_arch(10.0, math.radians(157.5), 1.5, 7), "static")[0]
    assert out["k"] == pytest.approx(k_chain, abs=1e-4)
    assert out["rings"]["count"] == 2 and out["rings"]["bond"] == "aligned"
    assert len(out["rings"]["blocks"]) == 14
    for direction in ("+x", "-x"):
        entry = out["directions"][direction]["no sliding"]
        assert entry["load_multiplier"] == pytest.approx(k_chain, abs=1e-4)
        assert entry["sliding"] == []
        # four hinges: on bed or foundation joints of both rings, the rings moving together
        kinds = {m["kind"] for m in entry["moving_interfaces"] if m["state"] == "rocks"}
        assert kinds <= {"bed", "foundation", "ring"}
        assert out["rings"]["moving_rings"][direction]["no sliding"] == [0, 1]


def test_ring_friction_alone_lets_only_the_rings_slide(capsys):
    out = _json(["limit", "--rings", "2", "--ring-friction", "0.4"], capsys)
    assert out["ring_friction"] == 0.4 and out["friction"] is None
    for direction in ("+x", "-x"):
        for law, entry in out["directions"][direction].items():
            sliding = {m["kind"] for m in entry["moving_interfaces"] if "slides" in m["state"]}
            assert sliding == {"ring"}, law
    # rings that slide on each other are weaker than rings that cannot (a narrower cone)
    assert out["k"] < 0.37


def test_friction_is_the_other_interfaces_and_the_rings_without_ring_friction(capsys):
    # --friction alone gives every interface, the ring ones too, its coefficient: the same
    # multipliers as --friction MU --ring-friction MU
    alone = _json(["limit", "--rings", "2", "--friction", "0.5"], capsys)
    both = _json(["limit", "--rings", "2", "--friction", "0.5", "--ring-friction", "0.5"],
                 capsys)
    for direction in ("+x", "-x"):
        a = alone["directions"][direction]["associative"]["load_multiplier"]
        b = both["directions"][direction]["associative"]["load_multiplier"]
        assert a == pytest.approx(b, rel=1e-9)
    # a stiffer ring friction never lowers k (the static theorem: a wider cone)
    stiff = _json(["limit", "--rings", "2", "--friction", "0.5", "--ring-friction", "0.9"],
                  capsys)
    assert (stiff["directions"]["+x"]["associative"]["load_multiplier"]
            >= both["directions"]["+x"]["associative"]["load_multiplier"] - 1e-9)


def test_plot_of_the_rings(tmp_path, capsys):
    path = tmp_path / "rings.png"
    assert main(["limit", "--rings", "2", "--ring-bond", "staggered", "--ring-friction", "0.5",
                 "--plot", str(path)]) == 0
    assert path.stat().st_size > 10_000
    text = capsys.readouterr().out
    assert "friction mu = 0.5 between the rings, the other interfaces do not slide" in text


@pytest.mark.parametrize(("argv", "message"), [
    (["simulate", "--rings", "2"], "--rings: an arch of several rings is a block assembly"),
    (["compare", "--rings", "2", "--ring-bond", "staggered"], "--rings, --ring-bond: an arch"),
    (["limit", "--rings", "2", "--min-pier-width", "--piers", ",3"], "--rings"),
    (["limit", "--ring-friction", "0.3"], "--ring-friction: give --rings"),
    (["limit", "--rings", "2", "--piers", "1,3"], "--piers: left pier: pier width must be at "
                                                  "least the horizontal extent"),
    (["limit", "--rings", "2", "--shape", "pointed", "--span", "10", "--rise", "8"],
     "a pointed arch's crown is a corner: give another --shape"),
    (["limit", "--rings", "2", "--faces", "flat"], "cannot be combined with --faces"),
    (["limit", "--rings", "2", "--epsilon", "0.1"], "cannot be combined with --epsilon"),
    (["limit", "--rings", "0"], "--rings must be an integer >= 1"),
    (["limit", "--rings", "2", "--ring-friction", "-1"], "--ring-friction must be"),
])
def test_refusals_name_the_options(argv, message, capsys):
    assert main(argv) == 2
    assert message in capsys.readouterr().err


def test_a_passive_fill_over_rings(capsys):
    # the fill's passive reaction on the extrados ring's blocks: a resistance, so k rises
    # above that of the same fill without it
    fill = ["limit", "--rings", "2", "--fill-cover", "0.5"]
    without = _json(fill, capsys)["k"]
    passive = _json([*fill, "--fill-passive", "30,0.33"], capsys)["k"]
    assert passive > 1.05 * without


def test_blocks_named_by_ring(capsys):
    out = _json(["limit", "--rings", "3", "--voussoirs", "4", "--ring-bond", "staggered"],
                capsys)
    names = out["rings"]["blocks"]
    # rings 0 and 2 of 4 voussoirs, ring 1 of 3 and two halves
    assert len(names) == 4 + 5 + 4
    assert names[4] == "ring 1, voussoir 0" and names[-1] == "ring 2, voussoir 3"
    # staggered rings that cannot slide on each other lock (no mechanism): k = inf, null
    assert out["k"] is None


def test_rings_of_a_parabolic_arch(capsys):
    # one ring of a parabolic arch is the shaped arch of the chain program, within the chords
    # (arc_error 1e-3 of the thickness: 0.8 mm, k within 1e-4)
    from archquake.geometry import shaped_arch

    out = _json(["limit", "--rings", "1", "--shape", "parabolic", "--span", "10", "--rise", "3",
                 "--thickness", "0.8", "--voussoirs", "9"], capsys)
    k_chain = load_multipliers(shaped_arch("parabolic", span=10.0, rise=3.0, thickness=0.8,
                                           voussoirs=9), "static")[0]
    assert out["k"] == pytest.approx(k_chain, abs=1e-4)


def test_the_arbiter_names_rings_that_move_below_the_iteration(capsys):
    """Staggered rings with friction 0.8: the rigid blocks' ramp moves them 25 % below the
    non-associative k, and the command says to take the lower value; its lists of interfaces
    are the structure's (0-100), runs compressed."""
    from archquake.cli.main_limit import _listed

    assert _listed([5, 1, 2, 3, 9, 10]) == "1-3,5,9,10" and _listed([]) == "-"
    assert main(["limit", "--rings", "2", "--ring-bond", "staggered", "--friction", "0.8",
                 "--arbiter"]) == 0
    out = capsys.readouterr().out
    assert "k = 0.2417" in out and "take the rigid blocks' lower value" in out
    rows = [line for line in out.splitlines() if "rigid blocks" in line and "ramp" in line]
    assert len(rows) == 2 and all(" 0.18" in row for row in rows)
    assert all("-100" in row or "95-99" in row for row in rows)


def test_the_arbiter_says_when_the_rigid_blocks_do_not_stand(capsys):
    """Two staggered rings of a semicircle of radius 5 m and 0.6 m in 8 voussoirs, ring
    friction 0.6: both programs find it standing (k = 0.0728 associative, 0.0691 by the
    non-associative iteration), but the rigid blocks' rings slide under their own weight (a
    pulse of 0.001 g collapses them, ``rigid-blocks`` with the same options): the ramp's onset is
    0 (within its error), and the command says the structure does not stand in the rigid-block
    model instead of giving a multiplier 100 % below k."""
    assert main(["limit", "--radius", "5", "--embrace", "180", "--thickness", "0.6",
                 "--voussoirs", "8", "--rings", "2", "--ring-bond", "staggered",
                 "--ring-friction", "0.6", "--arbiter"]) == 0
    text = capsys.readouterr().out
    assert "k = 0.0691" in text  # the iteration's (associative 0.0728)
    assert "the rigid blocks do not stand: they move under their own weight" in text
    assert "% below k" not in text
