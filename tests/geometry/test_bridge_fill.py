"""Fill over several spans (multi_span with fill): one span is the arch on piers with fill (the
same loads and multipliers), the fill's weight over a span and over a pier by hand, the fill a
deeper cover adds, the rigid-block model's masses, refusals."""

import math

import numpy as np
import pytest

from archquake.constants import GRAVITY
from archquake.geometry import Fill, Pier, circular_arch, shaped_arch
from archquake.geometry.bridge import FilledAssembly, multi_span
from archquake.geometry.fill import fill_columns
from archquake.geometry.structure import Structure
from archquake.limit_analysis import assembly_limit, load_multipliers
from archquake.limit_analysis.assembly import contacts_of
from archquake.rigid_blocks import from_arch, from_block_assembly

FLAT = shaped_arch("circular", span=4.0, rise=1.2, thickness=0.45, voussoirs=8, faces="flat")
"""Flat-faced voussoirs: exact polygons, so the assembly's masonry is the chain's."""

LEFT, RIGHT = Pier(1.2, 3.0, 3), Pier(1.6, 2.5, 1)


PASSIVE = (math.radians(30.0), 0.33)
"""A passive reaction of the fill: phi = 30 deg, a third of Rankine's pressure mobilised."""


@pytest.mark.parametrize(("inertia", "passive"), [
    ("none", ()), ("centroid", ()), ("extrados", ()), ("centroid", PASSIVE),
    ("extrados", (math.radians(35.0), 1.0))])
def test_one_span_with_fill_is_the_arch_on_piers_with_fill(inertia, passive):
    # the same columns (fill_columns of the single arch), so the same loads block for block,
    # the passive reactions too, and the assembly program gives the chain program's k in both
    # directions (unequal piers)
    fill = Fill(0.5, 1800.0, inertia, *passive)
    single = Structure(FLAT, LEFT, RIGHT, fill)
    bridge = multi_span(FLAT, 1, end_piers=(LEFT, RIGHT), fill=fill)
    assert isinstance(bridge, FilledAssembly)
    mine, theirs = contacts_of(bridge), contacts_of(single)
    assert (mine.passive.max() > 0) == bool(passive)
    for name in ("vertical", "vertical_x", "horizontal", "horizontal_y", "passive",
                 "passive_y", "passive_sign"):
        a, b = getattr(mine, name), getattr(theirs, name)
        assert np.max(np.abs(a - b)) <= 1e-12 * np.max(np.abs(b)), name
    k_l, k_r = load_multipliers(single)
    plus, minus = (assembly_limit(bridge, d).load_multiplier for d in ("+x", "-x"))
    assert plus == pytest.approx(k_l, abs=1e-12)
    assert minus == pytest.approx(k_r, abs=1e-12)
    assert k_l != pytest.approx(k_r, rel=1e-3)


def test_the_fill_over_a_span_and_over_a_pier_by_hand():
    # A semicircular arch, intrados radius 1.6 m, thickness 0.4 m: extrados radius R_e = 2.0 m,
    # springings at y = 0, crown at 2.0 m; cover 0.6 m: the surface at y = 2.6 m.
    # Over one span (x from -2 to 2): 4 x 2.6 - pi 2^2 / 2 = 10.4 - 2 pi = 4.116815 m^2.
    # Middle pier 1.5 m between the intrados springing points: the seats take 0.4 m each, the
    # column over it is 1.5 - 0.8 = 0.7 m wide and 2.6 m high: 1.82 m^2.
    arch = circular_arch(1.8, math.pi, 0.4, 9)  # mean radius 1.8 m
    rho = 1700.0
    bridge = multi_span(arch, 3, end_piers=(Pier(1.0, 3.0),) * 2,
                        middle_pier=Pier(1.5, 3.0, 2), fill=Fill(0.6, rho))
    names = bridge.names
    for span in (1, 2, 3):
        mine = [i for i, n in enumerate(names) if n.startswith(f"span {span} ")]
        assert bridge.fill_masses[mine].sum() == pytest.approx(rho * (10.4 - 2 * math.pi),
                                                               rel=1e-12)
    tops = [i for i, n in enumerate(names) if n in ("pier 1 course 2", "pier 2 course 2")]
    assert bridge.fill_masses[tops] == pytest.approx([rho * 0.7 * 2.6] * 2, rel=1e-12)
    # its centroid halfway up, over the middle of the pier (intrados springing points at x = 1.6
    # and 3.1 m: x = 2.35 m)
    assert bridge.fill_centroids[tops[0]] == pytest.approx([2.35, 1.3], abs=1e-12)
    total = 3 * (10.4 - 2 * math.pi) + 2 * 1.82
    assert bridge.fill_weight == pytest.approx(rho * GRAVITY * total, rel=1e-12)
    # the end piers carry none (the fill beyond the end springings rests on the abutments)
    assert all(not n.startswith(("pier 0", "pier 3")) for n in np.asarray(names)[bridge.carriers])


def test_a_deeper_cover_adds_a_layer_of_fill_over_the_whole_bridge():
    # Raising the surface by dc adds, over every column, the rectangle between the two verticals
    # that bound it: rho dc times its width. The columns tile the bridge from the first extrados
    # springing point to the last without gaps, so the fill grows by exactly rho dc L, with
    # L = 3 x 4.0 + 2 x 0.7 = 13.4 m (the example above), whatever the arch's shape below.
    arch = circular_arch(1.8, math.pi, 0.4, 9)
    masses = []
    for cover in (0.6, 1.1):
        bridge = multi_span(arch, 3, end_piers=(Pier(1.0, 3.0),) * 2,
                            middle_pier=Pier(1.5, 3.0, 2), fill=Fill(cover, 1700.0))
        masses.append(bridge.fill_masses)
    assert np.all(masses[1] >= masses[0])  # more fill never lightens a column
    assert masses[1].sum() - masses[0].sum() == pytest.approx(1700.0 * 0.5 * 13.4, rel=1e-12)


def test_the_rigid_blocks_carry_the_fill_as_mass():
    fill = Fill(0.5, 1800.0)
    single = from_arch(Structure(FLAT, LEFT, RIGHT, fill))
    blocks = from_block_assembly(multi_span(FLAT, 1, end_piers=(LEFT, RIGHT), fill=fill))
    assert blocks.masses == pytest.approx(single.masses, rel=1e-12)
    assert blocks.centroids == pytest.approx(single.centroids, abs=1e-12)
    assert blocks.inertias == pytest.approx(single.inertias, rel=1e-12)
    with pytest.raises(ValueError, match="fill inertia 'none' is a limit-analysis model"):
        from_block_assembly(multi_span(FLAT, 1, end_piers=(LEFT, RIGHT),
                                       fill=Fill(0.5, 1800.0, "none")))


def test_the_passive_reaction_over_several_spans():
    # every span's voussoirs push toward the middle of their own span, with the single arch's
    # bounds; the spandrel columns over the piers offer none
    fill = Fill(0.5, 1800.0, "centroid", *PASSIVE)
    single = fill_columns(FLAT, fill)
    bridge = multi_span(FLAT, 3, end_piers=(LEFT, LEFT), middle_pier=LEFT, fill=fill)
    names = bridge.names
    for span in (1, 2, 3):
        mine = [i for i, n in enumerate(names) if n.startswith(f"span {span} ")]
        assert bridge.passive[mine] == pytest.approx(single.passive, rel=1e-12)
        assert bridge.passive_y[mine] == pytest.approx(single.passive_y, abs=1e-12)
        assert np.array_equal(bridge.passive_sign[mine], single.passive_sign)
        assert sorted(set(bridge.passive_sign[mine])) == [-1.0, 1.0]  # toward the middle
    assert np.all(bridge.passive[[i for i, n in enumerate(names) if n.startswith("pier")]] == 0)
    # a resistance only adds to the strength: k with it at least k without it, and the end
    # span fails as the single arch on the same piers with the same fill (its chain program)
    without = multi_span(FLAT, 3, end_piers=(LEFT, LEFT), middle_pier=LEFT,
                         fill=Fill(0.5, 1800.0, "centroid"))
    k_single = min(load_multipliers(Structure(FLAT, LEFT, LEFT, fill)))
    for direction in ("+x", "-x"):
        k = assembly_limit(bridge, direction).load_multiplier
        assert k > assembly_limit(without, direction).load_multiplier * 1.05
        assert k <= k_single * (1 + 1e-9)
    # the dynamic models carry no passive reaction, and say so
    with pytest.raises(ValueError, match="fill_passive: the fill's passive reaction"):
        from_block_assembly(bridge)


def test_refusals_name_the_parameter():
    with pytest.raises(ValueError, match="fill must be a Fill or None"):
        multi_span(FLAT, 2, end_piers=(LEFT, LEFT), middle_pier=LEFT, fill=0.5)
