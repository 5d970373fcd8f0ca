"""Irregular bridges: one irregular arch a span (``--spans N --epsilon E --seed S``), drawn one
after the other from one seeded generator, on the shared piers. Equal arches given one a span
are the bridge of one arch; the spans are the draws, moved; massive middle piers leave every
span to itself, as the chain program finds it; one level of fill over the highest crown."""

import numpy as np
import pytest

from archquake.cli import main
from archquake.geometry import Fill, Pier, StructureSpec, shaped_arch
from archquake.geometry.bridge import multi_span
from archquake.geometry.irregular import irregular_arch
from archquake.geometry.structure import Structure
from archquake.limit_analysis import assembly_limit, load_multipliers

FLAT = shaped_arch("circular", span=4.0, rise=1.2, thickness=0.45, voussoirs=8, faces="flat")
"""Flat-faced voussoirs: exact polygons, so the assembly's masonry is the chain's."""

PIER = Pier(1.2, 3.0, 2)


def _k(structure, direction):
    return assembly_limit(structure, direction).load_multiplier


@pytest.mark.parametrize("fill", [None, Fill(0.5, 1800.0)])
def test_equal_arches_one_a_span_are_the_bridge_of_one_arch(fill):
    one = multi_span(FLAT, 3, end_piers=(PIER, PIER), middle_pier=PIER, fill=fill)
    each = multi_span([FLAT] * 3, 3, end_piers=(PIER, PIER), middle_pier=PIER, fill=fill)
    assert one.names == each.names
    for a, b in zip(one.polygons, each.polygons, strict=True):
        assert np.allclose(a, b, rtol=0, atol=1e-12)
    for direction in ("+x", "-x"):
        assert _k(each, direction) == pytest.approx(_k(one, direction), rel=1e-12)


def test_the_spans_are_the_draws_moved_and_the_piers_seat_both_springings_at_one_height():
    spec = StructureSpec(shape="circular", span=4.0, rise=1.2, thickness=0.45, voussoirs=8,
                         faces="flat", spans=3, piers="1.2,3,2", epsilon=0.2, seed=7)
    nominal, bridge = spec.arches()
    rng = np.random.default_rng(7)
    draws = [irregular_arch(FLAT, 0.2, rng=rng) for _ in range(3)]
    names = bridge.names
    rights = []
    for k, draw in enumerate(draws):
        mine = [i for i, n in enumerate(names) if n.startswith(f"span {k + 1} ")]
        shift = bridge.polygons[mine[0]][0] - draw.outline(0)[0]
        for i, block in enumerate(mine):
            assert np.allclose(bridge.polygons[block], draw.outline(i)[:-1] + shift, atol=1e-12)
        left, right = draw.joints[0, 0] + shift, draw.joints[-1, 0] + shift
        if k > 0:  # the middle pier: both intrados springing points at one height, W apart
            assert left[1] == pytest.approx(rights[-1][1], abs=1e-12)
            assert left[0] - rights[-1][0] == pytest.approx(1.2, abs=1e-12)
        rights.append(right)
    assert not np.allclose(draws[0].joints, draws[1].joints)  # three different arches
    # the same seed, the same bridge; the nominal bridge is the arch's
    again = spec.build()
    assert all(np.array_equal(a, b) for a, b in zip(again.polygons, bridge.polygons,
                                                     strict=True))
    assert nominal.n_blocks == bridge.n_blocks


def test_massive_middle_piers_leave_every_irregular_span_to_itself():
    # middle piers 40 m wide and 2 m high do not move: each span fails as its own arch on its
    # springings (the end spans on their end pier), which the chain program gives
    rng = np.random.default_rng(3)
    draws = [irregular_arch(FLAT, 0.15, rng=rng) for _ in range(3)]
    bridge = multi_span(draws, 3, end_piers=(PIER, PIER), middle_pier=Pier(40.0, 2.0))
    alone = [Structure(draws[0], PIER, None), draws[1], Structure(draws[2], None, PIER)]
    k_l = min(load_multipliers(s)[0] for s in alone)
    k_r = min(load_multipliers(s)[1] for s in alone)
    assert _k(bridge, "+x") == pytest.approx(k_l, rel=1e-9)
    assert _k(bridge, "-x") == pytest.approx(k_r, rel=1e-9)


def test_one_level_of_fill_over_the_highest_crown():
    rng = np.random.default_rng(5)
    draws = [irregular_arch(FLAT, 0.2, rng=rng) for _ in range(3)]
    bridge = multi_span(draws, 3, end_piers=(PIER, PIER), middle_pier=PIER, fill=Fill(0.5))
    crowns = [max(float(np.max(p[:, 1])) for p, n in zip(bridge.polygons, bridge.names,
                                                         strict=True)
                  if n.startswith(f"span {k} ")) for k in (1, 2, 3)]
    assert len({round(c, 9) for c in crowns}) == 3  # three crowns at different heights
    assert bridge.level == pytest.approx(max(crowns) + 0.5, abs=1e-9)
    for outline in bridge.outlines:
        assert float(np.max(outline[:, 1])) == pytest.approx(bridge.level, abs=1e-9)


def test_the_command_line_draws_an_irregular_bridge(capsys):
    import json

    argv = ["limit", "--spans", "3", "--piers", "3,6", "--json"]
    assert main(argv) == 0
    nominal = json.loads(capsys.readouterr().out)["k"]
    ks = []
    for seed in ("2", "2", "3"):
        assert main([*argv, "--epsilon", "0.1", "--seed", seed]) == 0
        ks.append(json.loads(capsys.readouterr().out)["k"])
    assert ks[0] == ks[1] != ks[2]
    assert all(abs(k - nominal) > 1e-4 for k in ks)
    # the rigid blocks of the same irregular bridge: at rest under a tenth of its k
    assert main(["rigid-blocks", "--spans", "3", "--piers", "3,6", "--epsilon", "0.1",
                 "--seed", "2", "--amplitude", f"{0.1 * ks[0]:.4f}", "--json"]) == 0
    assert '"outcome": "rest"' in capsys.readouterr().out


def test_a_draw_whose_seats_the_middle_piers_cannot_take_is_refused_naming_it(capsys):
    # thicker end voussoirs need wider seats: 3 m carries the nominal arch's two (2.94 m), not
    # those of this draw
    assert main(["limit", "--spans", "3", "--piers", "3,6", "--epsilon", "0.1", "--seed",
                 "1"]) == 2
    err = capsys.readouterr().err
    assert ("the 3 irregular arches drawn with --epsilon 0.1 (seed 1), on these piers: --piers: "
            "intermediate pier width must be at least 3.06965 m") in err
