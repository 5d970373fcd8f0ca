"""The general block assembly: mass properties by hand, interfaces of walls counted by hand, an
arch's joints found again from its polygons, and every refusal naming its blocks."""

import json
import math
import time

import numpy as np
import pytest

from archquake.geometry import (
    arch_from_dict,
    arch_on_piers,
    load_arch,
    shaped_arch,
    surveyed_arch,
)
from archquake.geometry.assembly import (
    GROUND,
    BlockAssembly,
    block_on_ground,
    from_arch,
    portal,
    stack,
    wall,
)


def rectangle(x0, y0, x1, y1):
    return [[x0, y0], [x1, y0], [x1, y1], [x0, y1]]


def check_convention(interfaces):
    """The tangent (p1 - p0)/|p1 - p0| is the normal turned by +90 degrees; normals are unit."""
    n = interfaces.normal
    assert np.hypot(*n.T) == pytest.approx(1.0, abs=1e-12)
    assert interfaces.tangent == pytest.approx(np.column_stack((-n[:, 1], n[:, 0])), abs=1e-12)
    assert np.all(interfaces.b >= 0) and np.all(interfaces.a < interfaces.b)


# ------------------------------------------------------------------ mass properties by hand
def test_rectangle_mass_properties_by_hand():
    # 0.5 m x 2 m at (1, 3), rho = 2400: A = 1 m^2, m = 2400 kg/m, c = (1.25, 4),
    # I = m (b^2 + h^2) / 12 = 2400 (0.25 + 4) / 12 = 850 kg m
    a = BlockAssembly((rectangle(1, 3, 1.5, 5),), 2400.0, supports=(rectangle(0, 2, 3, 3),))
    assert a.area == pytest.approx([1.0], rel=1e-15)
    assert a.mass == pytest.approx([2400.0], rel=1e-15)
    assert a.centroid == pytest.approx(np.array([[1.25, 4.0]]), rel=1e-15)
    assert a.inertia == pytest.approx([850.0], rel=1e-13)
    assert a.weight == pytest.approx([2400.0 * 9.81], rel=1e-12)


def test_triangle_mass_properties_by_hand():
    # right triangle, legs b = 3 (x), h = 2 (y), rho = 1000: A = 3, c = (1, 2/3),
    # J about the centroid = b h (b^2 + h^2) / 36 = 6 * 13 / 36 = 13/6, times rho
    tri = [[0, 0], [3, 0], [0, 2]]
    a = BlockAssembly((tri,), 1000.0)
    assert a.area == pytest.approx([3.0])
    assert a.centroid == pytest.approx(np.array([[1.0, 2.0 / 3.0]]), rel=1e-14)
    assert a.inertia == pytest.approx([1000.0 * 13.0 / 6.0], rel=1e-13)


def test_l_shape_mass_properties_by_parallel_axes_and_either_sense():
    # L = [0,2]x[0,1] + [0,1]x[1,3]: two rectangles of area 2, centroids (1, 0.5) and (0.5, 2),
    # own polar moments 2 (2^2 + 1^2)/12 = 10/12 each; A = 4, c = (0.75, 1.25); offsets
    # (0.25, -0.75) and (-0.25, 0.75), |d|^2 = 0.625: J = 2 * 10/12 + 2 * 2 * 0.625 = 25/6
    ell = [[0, 0], [2, 0], [2, 1], [1, 1], [1, 3], [0, 3]]
    for outline in (ell, ell[::-1]):  # clockwise is taken counter-clockwise, silently
        a = BlockAssembly((outline,), 1.0)
        assert a.area == pytest.approx([4.0])
        assert a.centroid == pytest.approx(np.array([[0.75, 1.25]]), rel=1e-14)
        assert a.inertia == pytest.approx([25.0 / 6.0], rel=1e-13)
        x, y = a.polygons[0].T
        assert 0.5 * np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y) > 0


# ------------------------------------------------------------------ interfaces of builders
def test_block_on_ground_rests_on_its_base():
    a = block_on_ground(0.2, 1.0)
    i = a.interfaces
    assert i.a.tolist() == [GROUND] and i.b.tolist() == [0] and i.kind.tolist() == ["foundation"]
    assert i.normal.tolist() == [[0.0, 1.0]]
    # tangent (-1, 0): from the right corner to the left one
    assert i.p0.tolist() == [[0.1, 0.0]] and i.p1.tolist() == [[-0.1, 0.0]]
    assert i.friction.tolist() == [math.inf]


def test_stack_has_n_minus_one_beds():
    a = stack(5, 0.4, 0.3)
    kinds = a.interfaces.kind.tolist()
    assert kinds.count("bed") == 4 and kinds.count("foundation") == 1 and len(kinds) == 5
    assert a.interfaces.length == pytest.approx(0.4)
    check_convention(a.interfaces)


@pytest.mark.parametrize("courses, per", [(4, 3), (5, 1), (2, 6)])
def test_running_bond_wall_counts_and_overlaps(courses, per):
    """Even courses: `per` full blocks (per - 1 head joints); odd courses: a half block, per - 1
    full blocks, a half block (per head joints). Between two courses the cuts of both (per - 1
    and per interior cuts, none shared) split the wall length into 2 per overlaps of w/2 each.
    Foundation: the `per` blocks of course 0, each its width w. For (4, 3): 3 foundation,
    2 * 2 + 2 * 3 = 10 heads, 3 * 2 * 3 = 18 beds."""
    w, h = 0.4, 0.25
    a = wall(courses, per, w, h)
    i = a.interfaces
    odd, even = courses // 2, courses - courses // 2
    heads = even * (per - 1) + odd * per
    beds = (courses - 1) * 2 * per
    kinds = i.kind.tolist()
    assert a.n_blocks == even * per + odd * (per + 1)
    assert kinds.count("foundation") == per
    assert kinds.count("head") == heads
    assert kinds.count("bed") == beds
    assert i.length[i.kind == "bed"] == pytest.approx(w / 2, rel=1e-12)
    assert i.length[i.kind == "head"] == pytest.approx(h, rel=1e-12)
    assert i.length[i.kind == "foundation"] == pytest.approx(w, rel=1e-12)
    assert np.all(i.normal[i.kind == "bed"] == [0.0, 1.0])  # from the course below upwards
    check_convention(i)
    # every block's area adds up to the wall
    assert a.area.sum() == pytest.approx(courses * per * w * h, rel=1e-12)


def test_stack_bond_wall_counts():
    a = wall(3, 4, 0.5, 0.2, bond="stack")
    kinds = a.interfaces.kind.tolist()
    # beds 4 per course boundary x 2, heads 3 per course x 3, foundation 4
    assert (kinds.count("bed"), kinds.count("head"), kinds.count("foundation")) == (8, 9, 4)
    assert a.interfaces.length[a.interfaces.kind == "bed"] == pytest.approx(0.5)


def test_portal_lintel_rests_on_both_piers():
    a = portal(0.5, 2.0, 1.5, 0.4, pier_courses=2)
    i = a.interfaces
    lintel = a.n_blocks - 1
    on_lintel = i.b == lintel
    assert sorted(i.a[on_lintel].tolist()) == [1, 3]  # the top course of each pier
    assert i.length[on_lintel] == pytest.approx([0.5, 0.5])
    assert i.kind.tolist().count("foundation") == 2 and i.kind.tolist().count("head") == 0
    assert a.mass[lintel] == pytest.approx(2000 * (2 * 0.5 + 1.5) * 0.4)  # 2000 kg/m


def test_a_long_bed_touches_several_blocks():
    # one long block on the ground carries three blocks: three interfaces on its top edge
    blocks = [rectangle(0, 0, 3, 1), rectangle(0, 1, 1, 2), rectangle(1, 1, 2.5, 2),
              rectangle(2.5, 1, 3, 2)]
    i = BlockAssembly(blocks).interfaces
    top = i.a == 0
    assert sorted(i.b[top].tolist()) == [1, 2, 3]
    assert sorted(i.length[top].tolist()) == pytest.approx([0.5, 1.0, 1.5])


def test_collinear_pieces_of_one_face_merge():
    # the lower block's top drawn with two extra vertices: still one interface of length 1
    lower = [[0, 0], [1, 0], [1, 1], [0.7, 1], [0.3, 1], [0, 1]]
    i = BlockAssembly((lower, rectangle(0, 1, 1, 2))).interfaces
    assert i.kind.tolist() == ["foundation", "bed"]
    assert i.length == pytest.approx([1.0, 1.0])


def test_explicit_support_gives_the_foundation_and_its_normal():
    # a block on a tilted support: the normal points from the support into the block
    c, s = math.cos(0.3), math.sin(0.3)
    rot = np.array([[c, -s], [s, c]])
    block = np.array(rectangle(0, 0, 1, 2)) @ rot.T
    support = np.array(rectangle(-1, -1, 2, 0)) @ rot.T
    i = BlockAssembly((block,), supports=(support,)).interfaces
    assert i.a.tolist() == [GROUND] and i.kind.tolist() == ["foundation"]
    assert i.normal[0] == pytest.approx([-s, c], abs=1e-12)
    assert i.length == pytest.approx([1.0])


def test_head_and_bed_split_at_45_degrees():
    # two blocks meeting along a line at 40 deg from the vertical (normal 50 deg from it): head;
    # at 50 deg from the vertical (normal 40 deg from it): bed
    for angle, expected in ((40.0, "head"), (50.0, "bed")):
        t = math.radians(angle)
        top = (math.tan(t) * 2.0, 2.0)
        left = [[-1, 0], [0, 0], list(top), [-1, 2]]
        right = [[0, 0], [4, 0], [4, 2], list(top)]
        i = BlockAssembly((left, right)).interfaces
        assert i.kind[(i.a == 0) & (i.b == 1)].tolist() == [expected]


def test_non_convex_block_holds_a_block_in_its_notch():
    """The notch of an L-shaped block holds a square touching it along two edges: no overlap
    (a convex-hull test would refuse it); shifted 0.1 m into the L it overlaps."""
    ell = [[0, 0], [2, 0], [2, 1], [1, 1], [1, 2], [0, 2]]
    i = BlockAssembly((ell, rectangle(1, 1, 2, 2))).interfaces
    between = (i.a == 0) & (i.b == 1)
    assert sorted(i.kind[between].tolist()) == ["bed", "head"]
    assert i.length[between] == pytest.approx([1.0, 1.0])
    with pytest.raises(ValueError, match=r"block 0 and block 1 overlap \(by at least"):
        BlockAssembly((ell, rectangle(0.9, 1, 1.9, 2)))


def test_thousand_blocks_take_well_under_a_second():
    wall(25, 40, 0.4, 0.2)  # warm the compiled self-intersection test
    start = time.perf_counter()
    a = wall(25, 40, 0.4, 0.2)
    elapsed = time.perf_counter() - start
    assert a.n_blocks == 1012
    assert elapsed < 1.0


# ------------------------------------------------------------------ arches
def arch_joint_pairs(arch):
    """(a, b) of every joint of an arch as the assembly names them: joint 0 (GROUND, 0), joint
    j (j - 1, j), joint n (GROUND, n - 1) -- its normal reversed (from the support)."""
    n = arch.n_voussoirs
    return [(GROUND, 0)] + [(j - 1, j) for j in range(1, n)] + [(GROUND, n - 1)]


@pytest.mark.parametrize("make", [
    lambda nominal: nominal,
    lambda nominal: shaped_arch("pointed", span=10.0, rise=6.0, thickness=0.8, voussoirs=8),
    lambda nominal: shaped_arch("parabolic", span=8.0, rise=2.5, thickness=0.6, voussoirs=9,
                                faces="flat"),
    lambda nominal: arch_on_piers(nominal, 3.0, 6.0, 2),
    lambda nominal: surveyed_arch([nominal.outline(i, 40)[:-1] for i in range(7)]),
], ids=["oppenheim", "pointed", "parabolic-flat", "on-piers", "surveyed"])
def test_from_arch_interfaces_are_the_arch_joints(nominal, make):
    arch = make(nominal)
    a = from_arch(arch)
    i = a.interfaces
    n = arch.n_voussoirs
    assert i.n_interfaces == n + 1
    for j, (x, y) in enumerate(arch_joint_pairs(arch)):
        k = np.flatnonzero((i.a == x) & (i.b == y))
        assert k.size == 1, (j, x, y)
        k = int(k[0])
        p_in, p_out = arch.joints[j]
        if j == n:  # the normal from the right support into the last block: ends swapped
            p_in, p_out = p_out, p_in
        assert i.p0[k] == pytest.approx(p_in, abs=1e-9)
        assert i.p1[k] == pytest.approx(p_out, abs=1e-9)
        sign = -1.0 if j == n else 1.0
        assert i.normal[k] == pytest.approx(sign * arch.joint_normals[j], abs=1e-9)
        assert i.kind[k] == ("foundation" if j in (0, n) else "bed")
    check_convention(i)


def test_from_arch_masses_are_the_chords_of_the_voussoirs(nominal):
    """Each curved face of 24 points is 23 chords subtending Delta = (157.5/7)/23 deg; an
    annular sector drawn so has area (R^2 - r^2)/2 * m sin(Delta), the exact one
    (R^2 - r^2)/2 * m Delta: the ratio is sin(Delta)/Delta."""
    a = from_arch(nominal, points=24)
    delta = math.radians(157.5 / 7 / 23)
    assert a.mass == pytest.approx(nominal.masses * math.sin(delta) / delta, rel=1e-12)


def test_from_arch_refuses_fill(nominal):
    from archquake.geometry import Fill, Structure

    with pytest.raises(ValueError, match="without fill"):
        from_arch(Structure(nominal, fill=Fill(0.5, 1600.0)))


# ------------------------------------------------------------------ friction
def test_friction_by_kind_and_default():
    a = wall(2, 2, 0.4, 0.2, friction={"bed": 0.6, "head": 0.4, "foundation": 0.7})
    i = a.interfaces
    expected = {"bed": 0.6, "head": 0.4, "foundation": 0.7}
    assert i.friction.tolist() == [expected[k] for k in i.kind.tolist()]
    b = a.with_friction({"foundation": 0.5, "default": 0.3})
    assert b.interfaces.friction.tolist() == [0.5 if k == "foundation" else 0.3
                                              for k in i.kind.tolist()]
    assert np.array_equal(b.interfaces.p0, a.interfaces.p0)
    assert a.with_friction(0.8).interfaces.friction == pytest.approx(0.8)
    assert np.all(a.with_friction(None).interfaces.friction == math.inf)


def test_friction_missing_kind_is_named():
    with pytest.raises(ValueError, match=r"\['head'\]"):
        wall(2, 2, 0.4, 0.2, friction={"bed": 0.6, "foundation": 0.7})
    with pytest.raises(ValueError, match="unknown interface kind"):
        wall(2, 2, 0.4, 0.2, friction={"joint": 0.6})
    with pytest.raises(ValueError, match="friction must be a finite"):
        stack(2, 1.0, 1.0, friction=-0.1)


# ------------------------------------------------------------------ refusals
def test_overlapping_blocks_are_named():
    # identical squares: no edge crosses another and no vertex lies inside: still overlapping
    with pytest.raises(ValueError, match=r"block 1 and block 2 overlap"):
        BlockAssembly((rectangle(0, 0, 1, 1), rectangle(0, 1, 1, 2), rectangle(0, 1, 1, 2)))
    # a small block over a wide one's left half
    with pytest.raises(ValueError, match=r"block 0 and block 1 overlap"):
        BlockAssembly((rectangle(0, 0, 2, 1), rectangle(0, 0, 1, 1)))
    with pytest.raises(ValueError, match=r"block 0 and support 0 overlap"):
        BlockAssembly((rectangle(0, -0.1, 1, 1),), supports=(rectangle(-1, -1, 2, 0),))


@pytest.mark.parametrize("dx, dy", [(0.3, 0.9), (0.95, 0.2), (-0.6, 0.7), (0.0, 0.97)])
def test_overlap_of_convex_blocks_is_their_exact_penetration(dx, dy):
    """Two unit squares, the second shifted by (dx, dy) from the first: their projections
    overlap by 1 - |dx| along x and 1 - |dy| along y, the penetration is the smaller."""
    depth = min(1 - abs(dx), 1 - abs(dy))
    with pytest.raises(ValueError, match=rf"overlap \(by at least {depth:.3g} m"):
        BlockAssembly((rectangle(0, 0, 1, 1), rectangle(dx, dy, dx + 1, dy + 1)))


def test_an_overlap_within_the_tolerance_is_a_contact():
    # 1e-4 m of overlap on a tolerance of 1e-3 m: a bed joint
    a = BlockAssembly((rectangle(0, 0, 1, 1), rectangle(0, 0.9999, 1, 2)), tolerance=1e-3)
    assert a.interfaces.kind.tolist() == ["foundation", "bed"]


def test_block_touching_nothing_is_named():
    with pytest.raises(ValueError, match=r"block 1 touches nothing"):
        BlockAssembly((rectangle(0, 0, 1, 1), rectangle(3, 0.5, 4, 1.5)))


def test_floating_cluster_is_named():
    # blocks 1 and 2 touch each other, not the ground or block 0
    with pytest.raises(ValueError, match=r"floating group\): block 1, block 2"):
        BlockAssembly((rectangle(0, 0, 1, 1), rectangle(3, 2, 4, 3), rectangle(3, 3, 4, 4)))


def test_assembly_on_nothing_is_refused():
    diamond = [[0, 0], [1, 1], [0, 2], [-1, 1]]
    with pytest.raises(ValueError, match="rests on nothing: no block edge lies on the lowest"):
        BlockAssembly((diamond,))
    with pytest.raises(ValueError, match="rests on nothing: no block edge lies on a support"):
        BlockAssembly((rectangle(0, 0, 1, 1),), supports=(rectangle(5, -1, 6, 0),))


@pytest.mark.parametrize("polygon, message", [
    ([[0, 0], [1, 0]], "block 0 must have at least three distinct vertices"),
    ([[0, 0], [1, 0], [2, 0]], "block 0 encloses no area"),
    ([[0, 0], [1, 1], [1, 0], [0, 1]], "block 0 is not a simple polygon"),
    ([[0, 0], [1, math.nan], [0, 1]], "block 0 has a coordinate that is not a finite"),
])
def test_bad_polygons_are_named(polygon, message):
    with pytest.raises(ValueError, match=message):
        BlockAssembly((polygon,))


@pytest.mark.parametrize("kwargs, message", [
    ({"density": 0.0}, "density must be a finite number > 0"),
    ({"density": [2000.0, 1.0]}, "density must be"),
    ({"tolerance": 0.5}, "tolerance must be a distance"),
    ({"kinds": {(0, 5): "bed"}}, "kinds"),
    ({"kinds": {(GROUND, 0): "joint"}}, "must be one of"),
])
def test_bad_parameters_are_named(kwargs, message):
    with pytest.raises(ValueError, match=message):
        BlockAssembly((rectangle(0, 0, 1, 1),), **kwargs)


def test_names_appear_in_errors():
    with pytest.raises(ValueError, match=r"block 1 \(handle 2F, layer WALL\) touches nothing"):
        BlockAssembly((rectangle(0, 0, 1, 1), rectangle(3, 0.5, 4, 1.5)),
                      names=("handle 1E, layer WALL", "handle 2F, layer WALL"))


def test_kinds_override():
    a = BlockAssembly((rectangle(0, 0, 1, 1), rectangle(0, 1, 1, 2)), kinds={(1, 0): "ring"})
    assert a.interfaces.kind.tolist() == ["foundation", "ring"]
    assert a.kinds == ((0, 1, "ring"),)


# ------------------------------------------------------------------ JSON
def test_dict_round_trip_and_file_form(tmp_path):
    a = wall(3, 2, 0.4, 0.2, friction={"bed": 0.6, "default": 0.5})
    data = json.loads(json.dumps(a.to_dict()))
    assert BlockAssembly.from_dict(data) == a
    assert hash(BlockAssembly.from_dict(data)) == hash(a)
    assert arch_from_dict(data) == a
    path = tmp_path / "wall.json"
    path.write_text(json.dumps(data))
    assert load_arch(path) == a
    assert a != a.with_friction(0.3)


def test_dict_with_supports_is_an_assembly_and_survey_forms_still_read(nominal):
    data = {"blocks": [rectangle(0, 0, 1, 1)], "supports": []}
    assert isinstance(arch_from_dict(data), BlockAssembly)
    survey = {"blocks": [p[:-1].tolist() for p in (nominal.outline(i) for i in range(7))]}
    assert type(arch_from_dict(survey)).__name__ == "SurveyedArch"


@pytest.mark.parametrize("data, message", [
    ({"blocks": [rectangle(0, 0, 1, 1)], "supports": [], "colour": 1}, "unknown key"),
    ({"blocks": "x", "supports": []}, "needs 'blocks'"),
    ({"blocks": [rectangle(0, 0, 1, 1)], "supports": [], "kinds": [[0, "a", "bed"]]},
     "kinds must be"),
])
def test_bad_dicts_are_named(data, message):
    with pytest.raises(ValueError, match=message):
        BlockAssembly.from_dict(data)


def test_vectorised_polygon_formulas_equal_the_edge_integrals():
    # two routes to one polygon's mass properties: the shoelace sums over many polygons at once
    # and geometry.mass's edge integrals (region_properties), on an irregular pentagon and an L
    from archquake.geometry.mass import polygon_mass_properties, polygon_properties

    shapes = [np.array([[0.0, 0.0], [2.0, 0.1], [2.5, 1.3], [1.0, 2.2], [-0.3, 1.0]]),
              np.array([[0.0, 0.0], [3.0, 0.0], [3.0, 1.0], [1.0, 1.0], [1.0, 2.0],
                        [0.0, 2.0]])]
    _, mass, centroid, inertia = polygon_mass_properties(shapes, np.array([2000.0, 1800.0]))
    for k, (shape, rho) in enumerate(zip(shapes, (2000.0, 1800.0), strict=True)):
        m, c, i = polygon_properties(shape, rho)
        assert mass[k] == pytest.approx(m, rel=1e-12)
        np.testing.assert_allclose(centroid[k], c, rtol=1e-12)
        assert inertia[k] == pytest.approx(i, rel=1e-12)
