"""Arches of several rings (:func:`archquake.geometry.rings.multi_ring`): the blocks, the chords
and the interfaces against hand counts and closed forms."""

import math

import numpy as np
import pytest

from archquake.geometry import BlockAssembly, multi_ring

ALPHA = math.radians(157.5)  # Oppenheim's arch: R = 10 m, t = 1.5 m, 7 voussoirs


def chords_per(radius, angle, arc_error):
    """Fewest equal chords over ``angle`` with sagitta r (1 - cos(d/2)) <= arc_error."""
    return math.ceil(angle / (2 * math.acos(1 - arc_error / radius)) - 1e-12)


def test_chords_per_voussoir_by_hand():
    # arc_error 0.01 m on the extrados r = 10.75 m: the largest chord subtends
    # 2 acos(1 - 0.01/10.75) = 0.086274 rad; a voussoir subtends 22.5 deg = 0.392699 rad, so
    # ceil(0.392699 / 0.086274) = ceil(4.55) = 5 chords; on the intrados r = 9.25 m:
    # 2 acos(1 - 0.01/9.25) = 0.093005 rad, ceil(4.22) = 5 chords too.
    assert chords_per(10.75, math.radians(22.5), 0.01) == 5
    arch = multi_ring(10.0, ALPHA, 1.5, rings=1, voussoirs=7, arc_error=0.01)
    assert arch.n_blocks == 7
    assert all(len(p) == 2 * (5 + 1) for p in arch.polygons)  # 6 points on each face


def test_area_is_the_chord_polygons_closed_form():
    # the blocks of every ring, together, are bounded by the chords of the intrados and the
    # extrados (the ring interfaces cancel): area = sum over chords of r^2 sin(d)/2 outside
    # minus inside, with m equal chords of d = (alpha/7)/m per voussoir
    e = 0.02
    arch = multi_ring(10.0, ALPHA, 1.5, rings=3, voussoirs=7, arc_error=e)
    area = 0.0
    for r, sign in ((10.75, 1.0), (9.25, -1.0)):
        m = chords_per(r, ALPHA / 7, e)
        area += sign * 7 * m * r * r * math.sin(ALPHA / 7 / m) / 2
    assert float(arch.area.sum()) == pytest.approx(area, rel=1e-12)
    # and the sector ALPHA/2 (10.75^2 - 9.25^2) = 41.234 m^2 differs by the circular segments
    # between chords and arcs (added inside, cut off outside), each at most 2/3 chord x
    # sagitta: in all at most 2/3 x 0.02 x 10.75 x ALPHA = 0.394 m^2 (the longer face)
    sector = ALPHA / 2 * (10.75**2 - 9.25**2)
    assert abs(float(arch.area.sum()) - sector) <= 2 / 3 * e * 10.75 * ALPHA


def test_every_chord_within_arc_error_of_its_circle():
    e = 0.005
    arch = multi_ring(10.0, ALPHA, 1.5, rings=2, voussoirs=7, bond="staggered", arc_error=e)
    radii = (9.25, 10.0, 10.75)
    for p in arch.polygons:
        q = np.roll(p, -1, axis=0)
        r0, r1 = np.hypot(*p.T), np.hypot(*q.T)
        on_circle = np.isclose(r0, r1, atol=1e-9)  # the curved faces' chords
        middle = np.hypot(*((p + q) / 2).T)[on_circle]
        sagitta = r0[on_circle] - middle
        assert np.all(sagitta <= e + 1e-12)
        assert np.all(sagitta > 0)
        assert np.all(np.min(np.abs(r0[on_circle][:, None] - np.array(radii)), axis=1) < 1e-9)


@pytest.mark.parametrize(("bond", "blocks", "beds"), [("aligned", 14, 12), ("staggered", 15, 13)])
def test_interfaces_by_kind(bond, blocks, beds):
    # two rings of 7 voussoirs: aligned 2 x 7 blocks and 2 x 6 beds; staggered the outer ring 6
    # voussoirs and two halves (8 blocks, 7 beds). Foundations: every ring on each springing (4).
    # Ring interfaces: one per chord of the middle circle r = 10 m, through the joint ends of
    # both rings: aligned 7 voussoirs x m chords; staggered every half voussoir x m' chords
    e = 0.003
    arch = multi_ring(10.0, ALPHA, 1.5, rings=2, voussoirs=7, bond=bond, arc_error=e)
    kind = arch.interfaces.kind
    assert arch.n_blocks == blocks
    assert int(np.sum(kind == "bed")) == beds
    assert int(np.sum(kind == "foundation")) == 4
    if bond == "aligned":
        rings = 7 * chords_per(10.0, ALPHA / 7, e)
    else:
        rings = 14 * chords_per(10.0, ALPHA / 14, e)
    assert int(np.sum(kind == "ring")) == rings
    # every ring interface pairs a block of ring 0 (0..6) with one of ring 1
    ring = kind == "ring"
    assert np.all(arch.interfaces.a[ring] < 7) and np.all(arch.interfaces.b[ring] >= 7)
    # and their lengths add up to the chords of the middle circle: 2 r sin(d/2) each
    assert float(arch.interfaces.length[ring].sum()) == pytest.approx(
        rings * 2 * 10.0 * math.sin(ALPHA / (rings * 2)), rel=1e-12)


def test_staggered_joints_offset_by_half_a_voussoir():
    arch = multi_ring(10.0, ALPHA, 1.5, rings=2, voussoirs=7, bond="staggered")
    faces = arch.interfaces
    bed = faces.kind == "bed"
    beta = np.arctan2(faces.p0[bed, 1], -faces.p0[bed, 0])  # progressive angle of the joint
    outer = faces.a[bed] >= 7
    start, step = (math.pi - ALPHA) / 2, ALPHA / 7
    np.testing.assert_allclose(np.sort(beta[~outer]), start + step * np.arange(1, 7), atol=1e-12)
    np.testing.assert_allclose(np.sort(beta[outer]), start + step * (0.5 + np.arange(7)),
                               atol=1e-12)


def test_thicknesses_and_friction_by_kind():
    arch = multi_ring(10.0, ALPHA, 1.5, thicknesses=[0.5, 1.0], voussoirs=7, friction=0.6,
                      ring_friction=0.3)
    faces = arch.interfaces
    ring = faces.kind == "ring"
    assert np.all(faces.friction[ring] == 0.3)
    assert np.all(faces.friction[~ring] == 0.6)
    # the ring interface on r = 9.25 + 0.5 = 9.75 m
    np.testing.assert_allclose(np.hypot(*faces.p0[ring].T), 9.75, rtol=1e-12)
    only_rings = multi_ring(10.0, ALPHA, 1.5, rings=2, ring_friction=0.4)
    assert np.all(np.isinf(only_rings.interfaces.friction[only_rings.interfaces.kind != "ring"]))
    assert isinstance(only_rings, BlockAssembly)


@pytest.mark.parametrize(("kwargs", "message"), [
    ({"rings": 0}, "rings must be an integer >= 1"),
    ({"rings": 2, "thicknesses": [0.75, 0.75]}, "either rings"),
    ({}, "either rings"),
    ({"thicknesses": [0.5, 0.5]}, "thicknesses must add up"),
    ({"thicknesses": [1.5, 0.0]}, r"thicknesses\[1\] must be"),
    ({"rings": 2, "bond": "english"}, "bond must be one of"),
    ({"rings": 2, "arc_error": 0.0}, "arc_error must be"),
    ({"rings": 2, "arc_error": 1e-9}, "arc_error must be larger"),
    ({"rings": 2, "voussoirs": 0}, "voussoirs must be"),
    ({"rings": 2, "ring_friction": -0.1}, "ring_friction must be"),
])
def test_refusals_name_the_parameter(kwargs, message):
    with pytest.raises(ValueError, match=message):
        multi_ring(10.0, ALPHA, 1.5, **kwargs)


def test_a_description_builds_the_rings():
    from archquake.errors import DescriptionError
    from archquake.geometry import StructureSpec

    spec = StructureSpec.from_dict({"rings": 2, "ring_bond": "staggered", "ring_friction": "0.4",
                                    "thickness": 1.2})
    assert StructureSpec.from_dict(spec.to_dict()) == spec
    built = spec.build()
    # Oppenheim's radius and embrace, the thickness given, the default 7 voussoirs
    direct = multi_ring(10.0, ALPHA, 1.2, rings=2, voussoirs=7, bond="staggered",
                        ring_friction=0.4)
    assert built == direct
    with pytest.raises(DescriptionError, match="ring_bond must be one of"):
        StructureSpec(rings=2, ring_bond="english")
    with pytest.raises(DescriptionError, match="cannot be combined with faces"):
        StructureSpec(rings=2, faces="flat")
    # under fill: the rings on fixed springings in a bridge of one span
    filled = StructureSpec(rings=2, fill_cover=1.0).build()
    assert filled.fill.cover == 1.0 and filled.blocks.n_blocks == 14


def test_a_circle_by_span_and_rise_is_the_circle_by_radius_and_embrace():
    # the same semicircle (S = 10, H = 5: R = 5, embrace pi) built by the two paths (closed-form
    # circles about the origin; offset curves of the centreline about (0, H - R) = (0, 0)):
    # the same blocks to round-off
    by_angle = multi_ring(5.0, math.pi, 0.8, rings=2, voussoirs=9, bond="staggered")
    by_size = multi_ring(shape="circular", span=10.0, rise=5.0, thickness=0.8, rings=2,
                         voussoirs=9, bond="staggered")
    assert by_size.n_blocks == by_angle.n_blocks
    for p, q in zip(by_angle.polygons, by_size.polygons, strict=True):
        np.testing.assert_allclose(p, q, atol=1e-12)
    np.testing.assert_array_equal(by_size.interfaces.kind, by_angle.interfaces.kind)


@pytest.mark.parametrize("shape", ["parabolic", "elliptical", "catenary", "three-centred"])
def test_rings_follow_the_offset_curves_of_a_centreline(shape):
    from archquake.geometry import centreline

    e = 1e-3
    curve = centreline(shape, 10.0, 3.5)
    arch = multi_ring(shape=shape, span=10.0, rise=3.5, thickness=0.8, rings=2, voussoirs=9,
                      arc_error=e)
    kind = arch.interfaces.kind
    assert int(np.sum(kind == "bed")) == 16 and int(np.sum(kind == "foundation")) == 4
    # every ring interface's ends on the centreline (offset 0): nearest point of a dense
    # sampling of the centreline within the sampling's own error
    s = np.linspace(0.0, curve.length, 20001)
    dense = np.array([curve.point(x) for x in s])
    ends = arch.interfaces.p0[kind == "ring"]
    gap = np.min(np.hypot(*(ends[:, None, :] - dense[None, :, :]).transpose(2, 0, 1)), axis=1)
    assert gap.max() < 1e-3
    # the intrados ring: between the offset curves at d = -0.4 and 0 m, an area
    # int ds int (1 + d |kappa|) dd = 0.4 L - 0.08 Theta, Theta = int |kappa| ds the turning
    # angle of the tangent from springing to springing (parabola, S = 10, H = 3.5: slopes
    # +-4H/S = 1.4, Theta = 2 atan 1.4 = 1.9011 rad: 0.4 x 12.667 - 0.152 = 4.914 m^2), less
    # or more the chords' segments, each at most 2/3 chord x sagitta
    t0, t1 = curve.tangent(0.0), curve.tangent(curve.length)
    theta = abs(math.atan2(t0[0] * t1[1] - t0[1] * t1[0], t0 @ t1))
    inner = float(arch.area[:9].sum())
    assert abs(inner - (0.4 * curve.length - 0.08 * theta)) <= 2 / 3 * e * 2 * curve.length


def test_pointed_and_mixed_descriptions_are_refused():
    with pytest.raises(ValueError, match="pointed arch's crown is a corner"):
        multi_ring(shape="pointed", span=10.0, rise=8.0, thickness=0.8, rings=2)
    with pytest.raises(ValueError, match="radius and embrace"):
        multi_ring(10.0, ALPHA, 1.5, shape="parabolic", span=10.0, rise=3.0, rings=2)
