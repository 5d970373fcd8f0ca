"""Arches of any shape: centrelines, stereotomy, faces and mass properties, each checked against
formulas and integrations written independently here."""

import math

import numpy as np
import pytest
from scipy import integrate, optimize

from archquake import oppenheim
from archquake.geometry import (
    SHAPES,
    ShapedArch,
    centreline,
    circular_arch,
    irregular_arch,
    shaped_arch,
)

SPAN = 10.0
RISES = {"circular": 3.5, "pointed": 7.5, "elliptical": 4.0, "parabolic": 4.5, "catenary": 4.5,
         "three-centred": 3.0}
SQRT3 = math.sqrt(3.0)


# ------------------------------------------------------------------ independent curves
def curve(shape, span, rise):
    """Closed-form centreline of each shape, written here from its textbook definition:
    ``(point(u), derivative(u), u0, u1)``; the parameter runs left to right."""
    a = span / 2
    if shape == "elliptical":
        return (lambda u: np.array([-a * np.cos(u), rise * np.sin(u)]),
                lambda u: np.array([a * np.sin(u), rise * np.cos(u)]), 0.0, math.pi)
    if shape == "parabolic":
        return (lambda x: np.array([x, rise * (1 - (x / a) ** 2)]),
                lambda x: np.array([1.0, -2 * rise * x / a**2]), -a, a)
    if shape == "catenary":
        c = optimize.brentq(lambda c: c * (math.cosh(a / c) - 1) - rise, 0.01 * a, 1e4 * a,
                            xtol=1e-15, rtol=1e-15)
        return (lambda x: np.array([x, rise - c * (np.cosh(x / c) - 1)]),
                lambda x: np.array([1.0, -np.sinh(x / c)]), -a, a)
    raise ValueError(shape)


def arc_length(shape, span, rise, u0, u1):
    _, d, _, _ = curve(shape, span, rise)
    return integrate.quad(lambda u: np.hypot(*d(u)), u0, u1, epsabs=1e-15, epsrel=1e-13,
                          limit=200)[0]


def parameter_of(shape, span, rise, point):
    """The curve parameter of a point of the centreline."""
    if shape == "elliptical":
        return math.atan2(point[1] / rise, -point[0] / (span / 2))
    return point[0]


# ------------------------------------------------------------------ centrelines
@pytest.mark.parametrize("shape", SHAPES)
def test_centreline_passes_through_springings_and_crown(shape):
    line = centreline(shape, SPAN, RISES[shape])
    assert line.point(0.0) == pytest.approx([-SPAN / 2, 0.0], abs=1e-12)
    assert line.point(line.length) == pytest.approx([SPAN / 2, 0.0], abs=1e-12)
    assert line.point(line.length / 2) == pytest.approx([0.0, RISES[shape]], abs=1e-12)
    # symmetric: the point at s mirrors the point at L - s; the normal points out of the arch
    for s in np.linspace(0, line.length, 9):
        p, q = line.point(s), line.point(line.length - s)
        assert p == pytest.approx([-q[0], q[1]], abs=1e-11)
        assert line.normal(s) @ line.tangent(s) == pytest.approx(0.0, abs=1e-15)
        t, n = line.tangent(s), line.normal(s)
        assert t[0] * n[1] - t[1] * n[0] == pytest.approx(1.0)
    assert line.normal(line.length / 2, "left")[1] > 0


@pytest.mark.parametrize("shape", ["elliptical", "parabolic", "catenary"])
def test_centreline_length_matches_quadrature(shape):
    line = centreline(shape, SPAN, RISES[shape])
    _, _, u0, u1 = curve(shape, SPAN, RISES[shape])
    assert line.length == pytest.approx(arc_length(shape, SPAN, RISES[shape], u0, u1), rel=1e-13)


def test_circular_and_pointed_and_three_centred_lengths():
    # circle through the springings and the crown: R = (S^2/4 + H^2) / 2H
    h = RISES["circular"]
    r = (SPAN**2 / 4 + h * h) / (2 * h)
    alpha = 2 * math.asin(SPAN / 2 / r)
    assert centreline("circular", SPAN, h).length == pytest.approx(r * alpha, rel=1e-14)
    # equilateral pointed arch: radius = span, each half an arc of 60 degrees
    line = centreline("pointed", SPAN, SPAN * SQRT3 / 2)
    assert line.length == pytest.approx(2 * SPAN * math.pi / 3, rel=1e-14)
    assert line.corners == pytest.approx((line.length / 2,), rel=1e-15)
    # three-centred: three tangent arcs of 60 degrees; r1 + r2 = span
    line = centreline("three-centred", SPAN, RISES["three-centred"])
    r1, r2 = (p.radius for p in line.parts[:2])
    assert r1 + r2 == pytest.approx(SPAN)
    assert line.length == pytest.approx((2 * r1 + r2) * math.pi / 3, rel=1e-14)
    assert not line.corners  # tangent-continuous
    for a, b in zip(line.parts[:-1], line.parts[1:], strict=True):
        assert a.point(a.u1) == pytest.approx(b.point(b.u0), abs=1e-13)
        assert a.tangent(a.u1) == pytest.approx(b.tangent(b.u0), abs=1e-13)
    # vertical springings
    assert line.tangent(0.0) == pytest.approx([0.0, 1.0], abs=1e-15)


@pytest.mark.parametrize(
    ("shape", "span", "rise", "message"),
    [
        ("pointed", 10.0, 5.0, "rise > span / 2"),
        ("three-centred", 10.0, 1.0, "three-centred"),
        ("three-centred", 10.0, 5.5, "three-centred"),
        ("gothic", 10.0, 5.0, "shape must be one of"),
        ("parabolic", -1.0, 5.0, "span"),
        ("elliptical", 10.0, float("nan"), "rise"),
    ],
)
def test_bad_centreline_names_the_parameter(shape, span, rise, message):
    with pytest.raises(ValueError, match=message):
        centreline(shape, span, rise)


# ------------------------------------------------------------------ stereotomy
@pytest.mark.parametrize("shape", ["elliptical", "parabolic", "catenary"])
def test_voussoirs_of_equal_arc_length_with_joints_normal_to_the_centreline(shape):
    rise = RISES[shape]
    arch = shaped_arch(shape, span=SPAN, rise=rise, thickness=0.7, voussoirs=9)
    p, d, u0, u1 = curve(shape, SPAN, rise)
    mid = arch.joints.mean(axis=1)
    u = [parameter_of(shape, SPAN, rise, m) for m in mid]
    total = arc_length(shape, SPAN, rise, u0, u1)
    for j in range(arch.n_voussoirs):
        assert arc_length(shape, SPAN, rise, u[j], u[j + 1]) == pytest.approx(total / 9, rel=1e-11)
    for j, uj in enumerate(u):
        assert mid[j] == pytest.approx(p(uj), abs=1e-12)
        tangent = d(uj) / np.hypot(*d(uj))
        assert arch.joint_directions[j] @ tangent == pytest.approx(0.0, abs=1e-13)
    assert arch.joint_lengths == pytest.approx(np.full(10, 0.7), rel=1e-13)
    assert arch.is_symmetric(1e-11)


def test_pointed_arch_has_a_vertical_crown_joint_and_radial_joints_in_each_half():
    span, rise = 8.0, 6.0
    arch = shaped_arch("pointed", span=span, rise=rise, thickness=0.6, voussoirs=8)
    c = (rise**2 - span**2 / 4) / span
    crown = arch.joints[4]
    assert crown[:, 0] == pytest.approx([0.0, 0.0], abs=1e-14)
    assert arch.joint_directions[4] == pytest.approx([0.0, 1.0], abs=1e-15)
    # the crown joint spans the two offset circles of the halves where they cross x = 0
    radius = c + span / 2
    assert crown[:, 1] == pytest.approx([math.sqrt((radius - 0.3) ** 2 - c * c),
                                         math.sqrt((radius + 0.3) ** 2 - c * c)], rel=1e-14)
    for j, centre in [(0, c), (1, c), (2, c), (3, c), (5, -c), (6, -c), (7, -c), (8, -c)]:
        p, q = arch.joints[j]
        r = np.array([centre, 0.0]) - p
        assert (q - p)[0] * r[1] - (q - p)[1] * r[0] == pytest.approx(0.0, abs=1e-12)
    with pytest.raises(ValueError, match="divisible by 2"):
        shaped_arch("pointed", span=span, rise=rise, thickness=0.6, voussoirs=7)


def test_circular_shaped_arch_is_the_papers_arch_moved_to_its_springings(nominal):
    """By radius and embrace: Oppenheim's arch, its centre at (0, -R cos(alpha/2))."""
    arch = shaped_arch("circular", radius=10.0, embrace=math.radians(157.5), thickness=1.5,
                       voussoirs=7)
    shift = np.array([0.0, -10.0 * math.cos(math.radians(157.5) / 2)])
    inner, outer = nominal.joint_extents()
    beta = nominal.joint_angles
    assert arch.joints[:, 0] - shift == pytest.approx(nominal.point(inner, beta), abs=1e-13)
    assert arch.joints[:, 1] - shift == pytest.approx(nominal.point(outer, beta), abs=1e-13)
    assert arch.joint_angles == pytest.approx(beta, abs=1e-14)
    assert arch.masses == pytest.approx(nominal.masses, rel=1e-14)
    assert arch.centroids - shift == pytest.approx(nominal.centroids, abs=1e-13)
    assert arch.inertias == pytest.approx(nominal.inertias, rel=1e-12)
    # by span and rise, the same circle
    same = shaped_arch("circular", span=arch.span, rise=arch.rise, thickness=1.5, voussoirs=7)
    assert same.masses == pytest.approx(arch.masses, rel=1e-13)
    assert same.joints == pytest.approx(arch.joints, abs=1e-12)


def test_irregular_circular_arch_is_eq1_of_the_paper(nominal):
    """The generalised eq. (1) on a circular centreline draws the paper's irregular arches,
    seed for seed."""
    shaped = shaped_arch("circular", radius=10.0, embrace=math.radians(157.5), thickness=1.5,
                         voussoirs=7)
    shift = np.array([0.0, -10.0 * math.cos(math.radians(157.5) / 2)])
    for seed in range(5):
        a = irregular_arch(shaped, 0.1, rng=seed)
        b = irregular_arch(nominal, 0.1, rng=seed)
        assert isinstance(b, type(nominal))
        assert a.masses == pytest.approx(b.masses, rel=1e-13)
        assert a.centroids - shift == pytest.approx(b.centroids, abs=1e-12)
        assert a.inertias == pytest.approx(b.inertias, rel=1e-11)
        inner, outer = b.joint_extents()
        assert a.joints[:, 0] - shift == pytest.approx(b.point(inner, b.joint_angles), abs=1e-12)
        assert a.joints[:, 1] - shift == pytest.approx(b.point(outer, b.joint_angles), abs=1e-12)


@pytest.mark.parametrize("shape", SHAPES)
def test_irregular_arches_keep_the_centreline_and_the_crown_joint(shape):
    nominal = shaped_arch(shape, span=SPAN, rise=RISES[shape], thickness=0.6, voussoirs=8)
    arches = [irregular_arch(nominal, 0.1, rng=seed) for seed in range(40)]
    line = nominal.centreline
    for a in arches:
        assert isinstance(a, ShapedArch) and a.centreline == line
        for start, end in line.segments:
            inside = (a.joint_positions[:-1] >= start - 1e-9) & (a.joint_positions[1:] <= end
                                                                  + 1e-9)
            assert a.lengths[inside].sum() == pytest.approx(end - start, rel=1e-14)
        assert np.all(np.abs(a.thicknesses / 0.6 - 1) <= 0.1)
        assert np.all(np.abs(a.offsets) <= 0.1 * 0.6)
    if shape == "pointed":
        assert all(a.joint_directions[4] == pytest.approx([0, 1], abs=1e-15) for a in arches)
    assert irregular_arch(nominal, 0.0, rng=1) is nominal
    again = irregular_arch(nominal, 0.1, rng=np.random.default_rng(3))
    assert again == arches[3]
    assert again.mirrored().mirrored() == again


def test_irregular_arch_refuses_a_surveyed_arch(nominal):
    from archquake.geometry import surveyed_arch

    survey = surveyed_arch([nominal.outline(i, 5)[:-1] for i in range(7)])
    with pytest.raises(ValueError, match="centreline"):
        irregular_arch(survey, 0.1, rng=0)


# ------------------------------------------------------------------ mass properties
def curvilinear_properties(shape, span, rise, u0, u1, lo, hi, density):
    """Mass, centroid, centroidal polar inertia of the region {C(u) + v N(u)}: u0 < u < u1,
    lo < v < hi, by double quadrature in (u, v) with dA = |C'| (1 - v kappa) dv du."""
    _, d, _, _ = curve(shape, span, rise)
    p, _, _, _ = curve(shape, span, rise)
    h = 1e-5

    def frame(u):
        du = d(u)
        speed = np.hypot(*du)
        t = du / speed
        # curvature from a central difference of the tangent angle (independent of the package)
        ang = lambda x: math.atan2(d(x)[1], d(x)[0])  # noqa: E731
        kappa = (ang(u + h) - ang(u - h)) / (2 * h) / speed
        return p(u), np.array([-t[1], t[0]]), speed, kappa

    def moment(f):
        def integrand(v, u):
            c, n, speed, kappa = frame(u)
            x = c + v * n
            return f(x) * speed * (1 - v * kappa)
        return integrate.dblquad(integrand, u0, u1, lo, hi, epsabs=1e-13, epsrel=1e-12)[0]

    m = moment(lambda x: 1.0)
    g = np.array([moment(lambda x: x[0]), moment(lambda x: x[1])]) / m
    j = moment(lambda x: (x[0] - g[0]) ** 2 + (x[1] - g[1]) ** 2)
    return density * m, g, density * j


@pytest.mark.parametrize("shape", ["elliptical", "parabolic", "catenary"])
def test_mass_properties_of_curved_faces_match_curvilinear_integration(shape):
    rise = RISES[shape]
    nominal = shaped_arch(shape, span=SPAN, rise=rise, thickness=0.9, voussoirs=6,
                          density=1900.0)
    arch = irregular_arch(nominal, 0.1, rng=5)
    for i in (0, 2):
        u0 = parameter_of(shape, SPAN, rise, arch.centreline.point(arch.joint_positions[i]))
        u1 = parameter_of(shape, SPAN, rise, arch.centreline.point(arch.joint_positions[i + 1]))
        d, t = arch.offsets[i], arch.thicknesses[i]
        m, g, inertia = curvilinear_properties(shape, SPAN, rise, u0, u1, d - t / 2, d + t / 2,
                                               1900.0)
        # 1e-9: the quadrature's own accuracy (the curvature by finite differences: ~1e-10)
        assert arch.masses[i] == pytest.approx(m, rel=1e-9)
        assert arch.centroids[i] == pytest.approx(g, rel=1e-9, abs=1e-9)
        assert arch.inertias[i] == pytest.approx(inertia, rel=1e-9)


def annular_sector(centre, r0, r1, angle, lower, density):
    """Region r0 < r < r1 about ``centre`` between the polar angle ``lower(r)`` and ``angle``."""
    def moment(f):
        return integrate.dblquad(
            lambda th, r: f(centre[0] + r * math.cos(th), centre[1] + r * math.sin(th)) * r,
            r0, r1, lower, lambda r: angle, epsabs=1e-13, epsrel=1e-12)[0]

    m = moment(lambda x, y: 1.0)
    g = np.array([moment(lambda x, y: x), moment(lambda x, y: y)]) / m
    return density * m, g, density * moment(lambda x, y: (x - g[0]) ** 2 + (y - g[1]) ** 2)


def test_mass_properties_of_the_pointed_crown_voussoir_match_polar_integration():
    """The crown voussoir of the left half: an annular sector about the left centre (c, 0),
    cut by the vertical crown joint x = 0."""
    span, rise, t = 8.0, 6.0, 0.6
    arch = shaped_arch("pointed", span=span, rise=rise, thickness=t, voussoirs=8)
    c = (rise**2 - span**2 / 4) / span
    radius = c + span / 2
    p, q = arch.joints[3]
    angle = math.atan2(q[1] - p[1], q[0] - p[0])  # the radial joint's polar angle about (c, 0)
    m, g, inertia = annular_sector((c, 0.0), radius - t / 2, radius + t / 2, angle,
                                   lambda r: math.acos(-c / r), arch.density)
    assert arch.masses[3] == pytest.approx(m, rel=1e-10)
    assert arch.centroids[3] == pytest.approx(g, rel=1e-10)
    assert arch.inertias[3] == pytest.approx(inertia, rel=1e-10)
    assert arch.masses[4] == pytest.approx(m, rel=1e-12)  # the mirror voussoir


def test_mass_properties_of_a_three_centred_voussoir_across_two_arcs():
    span, rise, t = 10.0, 3.0, 0.5
    arch = shaped_arch("three-centred", span=span, rise=rise, thickness=t, voussoirs=7)
    line = arch.centreline
    side, crown = line.parts[0], line.parts[1]
    # voussoir 1 straddles the junction of the left arc and the crown arc (at 60 degrees)
    s = arch.joint_positions
    assert s[1] < side.length < s[2]
    junction = 2 * math.pi / 3
    p1 = arch.joints[1]
    a1 = math.atan2(*(p1[1] - p1[0])[::-1])
    p2 = arch.joints[2]
    a2 = math.atan2(*(p2[1] - p2[0])[::-1])
    parts = [annular_sector(side.centre, side.radius - t / 2, side.radius + t / 2, a1,
                            lambda r: junction, arch.density),
             annular_sector(crown.centre, crown.radius - t / 2, crown.radius + t / 2, junction,
                            lambda r: a2, arch.density)]
    m = sum(x[0] for x in parts)
    g = sum(x[0] * x[1] for x in parts) / m
    inertia = sum(x[2] + x[0] * (x[1] - g) @ (x[1] - g) for x in parts)
    assert arch.masses[1] == pytest.approx(m, rel=1e-10)
    assert arch.centroids[1] == pytest.approx(g, rel=1e-10)
    assert arch.inertias[1] == pytest.approx(inertia, rel=1e-10)


def test_flat_faces_are_the_quadrilaterals_of_the_joint_ends(nominal):
    arch = shaped_arch("circular", radius=10.0, embrace=math.radians(157.5), thickness=1.5,
                       voussoirs=7, faces="flat")
    shift = np.array([0.0, -10.0 * math.cos(math.radians(157.5) / 2)])
    for i in range(7):
        b0, b1 = nominal.joint_angles[i], nominal.joint_angles[i + 1]
        pts = np.array([[-r * math.cos(b), r * math.sin(b)]
                        for r, b in ((9.25, b0), (9.25, b1), (10.75, b1), (10.75, b0))])
        x, y = pts[:, 0], pts[:, 1]
        x1, y1 = np.roll(x, -1), np.roll(y, -1)
        c = x * y1 - x1 * y
        area = c.sum() / 2
        g = np.array([((x + x1) * c).sum(), ((y + y1) * c).sum()]) / (6 * area)
        polar = ((x * x + x * x1 + x1 * x1 + y * y + y * y1 + y1 * y1) * c).sum() / 12
        assert arch.masses[i] == pytest.approx(2000 * area, rel=1e-13)
        assert arch.centroids[i] - shift == pytest.approx(g, abs=1e-12)
        assert arch.inertias[i] == pytest.approx(2000 * (polar - area * g @ g), rel=1e-11)
    assert arch.total_mass < nominal.total_mass


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"shape": "pointed", "span": 10, "rise": 9, "thickness": 0.5, "voussoirs": 7},
         "divisible"),
        ({"shape": "parabolic", "span": 10, "rise": 4, "thickness": 6.5, "voussoirs": 8},
         "radius of curvature"),
        ({"shape": "parabolic", "span": 10, "rise": 4, "thickness": 0.5, "voussoirs": 3},
         "voussoirs"),
        ({"shape": "parabolic", "span": 10, "rise": 4, "thickness": -0.5, "voussoirs": 8},
         "thickness"),
        ({"shape": "parabolic", "span": 10, "rise": 4, "thickness": 0.5, "voussoirs": 8,
          "faces": "round"}, "faces"),
        ({"shape": "elliptical", "radius": 10, "embrace": 2.0, "thickness": 0.5,
          "voussoirs": 8}, "circular arches only"),
        ({"shape": "circular", "span": 10, "rise": 4, "radius": 10, "thickness": 0.5,
          "voussoirs": 8}, "not both"),
        ({"shape": "catenary", "span": 10, "thickness": 0.5, "voussoirs": 8}, "span and rise"),
        ({"shape": "oval", "span": 10, "rise": 4, "thickness": 0.5, "voussoirs": 8}, "shape"),
    ],
)
def test_bad_shaped_arch_input_names_the_parameter(kwargs, message):
    with pytest.raises(ValueError, match=message):
        shaped_arch(**kwargs)


def test_shaped_arch_dict_round_trip():
    for shape in SHAPES:
        arch = irregular_arch(shaped_arch(shape, span=SPAN, rise=RISES[shape], thickness=0.5,
                                          voussoirs=6, faces="flat"), 0.1, rng=2)
        assert ShapedArch.from_dict(arch.to_dict()) == arch
    arch = shaped_arch("circular", radius=3.0, embrace=2.0, thickness=0.3, voussoirs=5)
    assert ShapedArch.from_dict(arch.to_dict()) == arch


def test_oppenheim_circular_arch_unchanged():
    """The paper's circular arch keeps its own class, frame and closed forms."""
    assert circular_arch(10.0, math.radians(157.5), 1.5, 7) == oppenheim()
