"""Arches of several rings as the spans of a bridge (multi_span of multi_ring): blocks and
names, one ring against the chain arch's bridge, the fill over the chords of the extrados ring
by hand."""

import math

import pytest

from archquake.constants import GRAVITY
from archquake.geometry import Fill, Pier, circular_arch, multi_ring
from archquake.geometry.bridge import multi_span, rings_of, spans_of
from archquake.limit_analysis import assembly_limit

PIER, MIDDLE = Pier(1.5, 4.0, 3), Pier(2.0, 4.0, 3)


def test_three_spans_of_two_rings_blocks_names_and_seats():
    ring = multi_ring(5.0, math.pi, 0.6, rings=2, voussoirs=8, ring_friction=0.6)
    bridge = multi_span(ring, 3, end_piers=(PIER, PIER), middle_pier=MIDDLE)
    assert bridge.n_blocks == 3 * 2 * 8 + 4 * 3  # 60
    assert bridge.names[3] == "span 1 ring 0, voussoir 0"
    spans = [spans_of(bridge, [i]) for i in range(bridge.n_blocks)]
    assert sum(s == [2] for s in spans) == 16
    assert rings_of(bridge, range(bridge.n_blocks)) == [0, 1]
    # both rings of every span rest on the seats: 2 rings x 2 springings x 3 spans
    faces = bridge.interfaces
    seats = [i for i in range(faces.n_interfaces) if faces.a[i] >= 0 and sorted(
        bridge.names[int(body)].split()[0] for body in (faces.a[i], faces.b[i])) == ["pier",
                                                                                 "span"]]
    assert len(seats) == 12
    assert set(faces.kind[seats]) == {"bed"}
    # the ring arch's own friction: 0.6 between the rings, the rest does not slide
    assert set(faces.friction[faces.kind == "ring"]) == {0.6}
    assert set(faces.friction[faces.kind != "ring"]) == {math.inf}


def test_one_ring_is_the_chain_arch_on_the_same_piers():
    # a ring cut finely (sagitta 1e-4 of the thickness: chords of about 1.4 deg) and the chain
    # arch's outline of 64 points a face (2.8 deg chords) both converge to the circular arch,
    # their areas short by Delta^2 / 6 of it (3e-4 at most): k agrees to that order
    ring = multi_ring(5.0, math.pi, 0.6, rings=1, voussoirs=8, arc_error=1e-4)
    chain = circular_arch(5.0, math.pi, 0.6, 8)
    k_ring = assembly_limit(multi_span(ring, 2, end_piers=(PIER, PIER), middle_pier=MIDDLE))
    k_chain = assembly_limit(multi_span(chain, 2, end_piers=(PIER, PIER), middle_pier=MIDDLE,
                                        points=64))
    assert k_ring.load_multiplier == pytest.approx(k_chain.load_multiplier, rel=1e-3)


def test_the_fill_over_the_chords_of_the_extrados_ring_by_hand():
    # Semicircle of mean radius 5 m, two rings of 0.3 m: the extrados at R_e = 5.3 m drawn as
    # one chord per voussoir (sagitta 5.3 (1 - cos(11.25 deg)) = 0.102 m, below the allowed 0.3 x
    # 0.6 m), eight chords of pi/8 from (-5.3, 0) to (5.3, 0), a joint end at the crown (5.3 m).
    # Cover 0.5 m: surface at 5.8 m. Fill over a span: 10.6 x 5.8 - 8 x 5.3^2 / 2 x sin(pi/8)
    # = 61.48 - 42.991... ; over a middle pier 2 m between intrados springing points, the seats
    # 0.6 m each: 0.8 x 5.8 = 4.64 m^2.
    ring = multi_ring(5.0, math.pi, 0.6, rings=2, voussoirs=8, arc_error=0.3)
    bridge = multi_span(ring, 3, end_piers=(PIER, PIER), middle_pier=MIDDLE,
                        fill=Fill(0.5, 1800.0))
    assert bridge.level == pytest.approx(5.8, abs=1e-12)
    span = 10.6 * 5.8 - 8 * 5.3 ** 2 / 2 * math.sin(math.pi / 8)
    for k in (1, 2, 3):
        mine = [i for i in bridge.carriers if spans_of(bridge, [i]) == [k]]
        assert rings_of(bridge, mine) == [1]  # only the extrados ring carries fill
        assert bridge.fill_masses[mine].sum() == pytest.approx(1800.0 * span, rel=1e-12)
    assert bridge.fill_weight == pytest.approx(1800.0 * GRAVITY * (3 * span + 2 * 0.8 * 5.8),
                                               rel=1e-12)
    # the fill stabilises nothing it does not also shake (centroid model): k stays finite > 0
    k = assembly_limit(bridge).load_multiplier
    assert 0 < k < math.inf
