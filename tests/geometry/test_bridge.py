"""Several spans on shared piers (multi_span): one span is the arch on piers block for block, the
seat geometry of an intermediate pier by hand, the end span's collapse against the chain program
of the single arch, files."""

import math
import time

import numpy as np
import pytest

import archquake
from archquake.geometry import BlockAssembly, Pier, arch_on_piers, read_dxf, shaped_arch, write_dxf
from archquake.geometry.assembly import from_arch
from archquake.geometry.bridge import multi_span, spans_of
from archquake.geometry.structure import Structure
from archquake.limit_analysis import assembly_limits, load_multipliers

FLAT = shaped_arch("circular", span=4.0, rise=1.2, thickness=0.45, voussoirs=8, faces="flat")
"""A segmental arch of flat-faced voussoirs: its blocks are exact polygons, so the assembly's
mass properties are the chain's (no chords of curved faces)."""


def _k(assembly) -> tuple[float, float]:
    out = assembly_limits(assembly)
    return (out["+x"]["no sliding"].load_multiplier, out["-x"]["no sliding"].load_multiplier)


# ------------------------------------------------------------------ one span
@pytest.mark.parametrize("arch, left, right", [
    (archquake.oppenheim(), Pier(3.0, 6.0, 2), Pier(3.0, 6.0, 2)),
    (FLAT, Pier(1.2, 3.0, 3), Pier(1.6, 2.5, 1)),
    (shaped_arch("pointed", span=5.0, rise=3.0, thickness=0.5, voussoirs=10), None,
     Pier.tapered(1.5, 2.5, 4.0, 2)),
])
def test_one_span_is_the_arch_on_its_piers_block_for_block(arch, left, right):
    bridge = multi_span(arch, 1, end_piers=(left, right))
    reference = from_arch(Structure(arch, left, right))
    assert bridge.n_blocks == reference.n_blocks
    for mine, theirs in zip(bridge.polygons, reference.polygons, strict=True):
        assert np.array_equal(mine, theirs)  # bit for bit
    for mine, theirs in zip(bridge.supports, reference.supports, strict=True):
        assert np.array_equal(mine, theirs)
    assert bridge.kinds == reference.kinds
    assert bridge == reference


def test_one_span_has_the_chain_programs_multipliers():
    # the chain program of the arch on piers (joint resultants, load_multipliers) against the
    # assembly program of its blocks (end forces of every interface): unequal piers, so Mech-l
    # (load toward +x) and Mech-r (the mirror, i.e. the load toward -x) differ
    left, right = Pier(1.2, 3.0, 3), Pier(1.6, 2.5, 1)
    k_l, k_r = load_multipliers(Structure(FLAT, left, right))
    plus, minus = _k(multi_span(FLAT, 1, end_piers=(left, right)))
    assert plus == pytest.approx(k_l, rel=1e-9)
    assert minus == pytest.approx(k_r, rel=1e-9)
    assert k_l != pytest.approx(k_r, rel=1e-3)


# ------------------------------------------------------------------ the intermediate pier
def test_three_spans_blocks_names_and_interface_kinds():
    pier = Pier(1.5, 3.0, 3)
    bridge = multi_span(FLAT, 3, end_piers=(pier, pier), middle_pier=pier)
    assert bridge.n_blocks == 4 * 3 + 3 * 8
    assert bridge.names[:4] == ("pier 0 course 1", "pier 0 course 2", "pier 0 course 3",
                                "span 1 voussoir 1")
    assert bridge.names[-1] == "pier 3 course 1"  # the right end pier runs top down
    faces = bridge.interfaces
    # every pier's base on the ground, everything else a bed joint: 4 bases, 4 x 2 courses on
    # courses, 3 x 7 voussoir joints, 6 springings on the piers
    assert sorted(faces.kind.tolist()) == ["bed"] * (8 + 21 + 6) + ["foundation"] * 4
    # the arches stand the pier's width apart: span 2 is span 1 moved by chord + W
    chord = float(FLAT.joints[-1, 0, 0] - FLAT.joints[0, 0, 0])
    assert np.allclose(bridge.polygons[3 + 8 + 3] - bridge.polygons[3], [chord + 1.5, 0.0],
                       rtol=0, atol=1e-12)
    assert spans_of(bridge, range(bridge.n_blocks)) == [1, 2, 3]


def test_an_intermediate_pier_narrower_than_its_two_seats_is_refused_naming_the_width():
    # Segmental arch, centreline span 4 m and rise 1.2 m: radius R = (2^2 + 1.2^2) / (2 x 1.2)
    # = 5.44 / 2.4 = 2.2667 m; the springing joint is radial, at sin(phi) = 2 / R = 0.88235
    # from the vertical, and t = 0.45 m long: its horizontal extent is t sin(phi) = 0.45 x
    # 0.88235 = 0.397059 m. An intermediate pier carries two of them: 0.794118 m.
    needed = 2 * 0.45 * 2.0 / ((2.0 ** 2 + 1.2 ** 2) / 2.4)
    assert needed == pytest.approx(0.794118, abs=1e-6)
    with pytest.raises(ValueError, match=r"middle_pier: intermediate pier width must be at "
                                         r"least 0\.794118 m"):
        multi_span(FLAT, 2, end_piers=(None, None), middle_pier=Pier(0.79, 3.0))
    # exactly the two seats: the extrados ends meet, the top is a point between them
    bridge = multi_span(FLAT, 2, end_piers=(None, None), middle_pier=Pier(needed, 3.0))
    top = bridge.polygons[8]
    assert len(top) == 5  # two base corners, two intrados springing points, one extrados point


def test_refusals_name_the_parameter():
    with pytest.raises(ValueError, match="middle_pier must be a Pier"):
        multi_span(FLAT, 2)
    with pytest.raises(ValueError, match=r"spans must be an integer in \[1, 100\]"):
        multi_span(FLAT, 0)
    with pytest.raises(ValueError, match="intermediate pier is rectangular"):
        multi_span(FLAT, 2, middle_pier=Pier.tapered(1.0, 2.0, 3.0))
    with pytest.raises(ValueError, match="on piers already"):
        multi_span(arch_on_piers(FLAT, 1.0, 3.0), 2, middle_pier=Pier(1.0, 3.0))
    with pytest.raises(ValueError, match="end_piers must be a pair"):
        multi_span(FLAT, 2, end_piers=Pier(1.0, 3.0), middle_pier=Pier(1.0, 3.0))


# ------------------------------------------------------------------ files
def test_a_bridge_reads_back_from_json_and_dxf(tmp_path):
    pier = Pier(3.0, 6.0, 3)
    bridge = multi_span(archquake.oppenheim(), 3, end_piers=(pier, pier), middle_pier=pier)
    assert BlockAssembly.from_dict(bridge.to_dict()) == bridge
    path = tmp_path / "bridge.dxf"
    write_dxf(bridge, path)
    drawn = read_dxf(path)
    assert drawn.n_blocks == bridge.n_blocks
    for mine, theirs in zip(bridge.polygons, drawn.polygons, strict=True):
        assert np.array_equal(mine, theirs)
    for mine, theirs in zip(bridge.supports, drawn.supports, strict=True):
        assert np.array_equal(mine, theirs)
    # the drawing has no kinds: the same interfaces, and the same collapse
    assert np.array_equal(drawn.interfaces.a, bridge.interfaces.a)
    assert np.array_equal(drawn.interfaces.b, bridge.interfaces.b)
    assert _k(drawn) == pytest.approx(_k(bridge), rel=1e-9)


# ------------------------------------------------------------------ collapse
def test_on_massive_intermediate_piers_the_end_span_collapses_as_one_arch_on_its_pier():
    # A pier 40 m wide and 1.5 m high does not move, so the spans are decoupled: span 1 is the
    # arch on its end pier and a fixed right springing (a Structure, analysed by the chain
    # program), span 2 its mirror image. Under a load toward +x span 1 fails by its own Mech-l,
    # span 2 by the mirror's Mech-l, i.e. span 1's Mech-r: k(+x) = min(k_l, k_r) of span 1.
    end = Pier(1.0, 3.0, 2)
    k_l, k_r = load_multipliers(Structure(FLAT, end, None))
    bridge = multi_span(FLAT, 2, end_piers=(end, end), middle_pier=Pier(40.0, 1.5))
    plus, minus = _k(bridge)
    assert plus == pytest.approx(min(k_l, k_r), rel=1e-9)
    assert minus == pytest.approx(min(k_l, k_r), rel=1e-9)


@pytest.mark.parametrize("arch, pier", [
    (FLAT, Pier(1.2, 3.0, 2)),
    (archquake.oppenheim(), Pier(3.0, 6.0, 1)),
    (shaped_arch("pointed", span=5.0, rise=3.0, thickness=0.5, voussoirs=10), Pier(2.0, 4.0, 3)),
])
def test_more_spans_never_raise_the_multiplier(arch, pier):
    ks = [min(_k(multi_span(arch, n, end_piers=(pier, pier), middle_pier=pier)))
          for n in (1, 2, 3, 4)]
    assert all(b <= a * (1 + 1e-9) for a, b in zip(ks, ks[1:], strict=False)), ks


def test_a_three_span_bridge_is_analysed_quickly():
    # 3 spans of 8 voussoirs on 4 piers of 3 courses: 36 blocks; about 0.03 s (bounded loosely:
    # a shared machine)
    arch = shaped_arch("circular", span=4.0, rise=2.0, thickness=0.4, voussoirs=8)
    pier = Pier(1.5, 3.0, 3)
    assembly_limits(multi_span(arch, 1, end_piers=(pier, pier)))  # imports, first calls
    start = time.perf_counter()
    bridge = multi_span(arch, 3, end_piers=(pier, pier), middle_pier=pier)
    out = assembly_limits(bridge)
    elapsed = time.perf_counter() - start
    assert bridge.n_blocks == 36
    assert math.isfinite(out["+x"]["no sliding"].load_multiplier)
    assert elapsed < 1.0


def test_an_intermediate_pier_by_hand():
    # Seats: the left arch's right springing from P_i = (0, 0) to P_e = (0.4, 0.3), the right
    # arch's left springing from Q_i = (2, 0) to Q_e = (1.6, 0.3); a pier 2 m wide, 3 m high
    # (ground at y = -3), two courses of 1.5 m: a rectangle, then the top course up to the seats
    # with its top level at y = 0.3 between the extrados ends.
    from archquake.geometry.piers import middle_pier_blocks

    right, left = [(0.0, 0.0), (0.4, 0.3)], [(2.0, 0.0), (1.6, 0.3)]
    lower, top = middle_pier_blocks(Pier(2.0, 3.0, 2), right, left)
    assert lower.tolist() == [[0, -3], [2, -3], [2, -1.5], [0, -1.5]]
    assert top.tolist() == [[0, -1.5], [2, -1.5], [2, 0], [1.6, 0.3], [0.4, 0.3], [0, 0]]
    with pytest.raises(ValueError, match=r"at least 0\.8 m, .*\(0\.4 m \+ 0\.4 m"):
        middle_pier_blocks(Pier(0.7, 3.0), right, [(0.7, 0.0), (0.3, 0.3)])
    with pytest.raises(ValueError, match="two springings at one height"):
        middle_pier_blocks(Pier(2.0, 3.0), right, [(2.0, 0.1), (1.6, 0.4)])
