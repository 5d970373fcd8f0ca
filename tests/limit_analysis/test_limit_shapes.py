"""Limit analysis of arches of any shape: the static and kinematic methods agree (uniqueness
theorem), symmetric arches collapse alike both ways, thrust lines stay in the joints, and the
minimum thickness of the semicircle converges to Milankovitch's value."""

import math

import numpy as np
import pytest

from archquake import oppenheim
from archquake.geometry import (
    SHAPES,
    VOUSSOIR_FACES,
    irregular_sample,
    shaped_arch,
    surveyed_arch,
)
from archquake.limit_analysis import (
    AGREEMENT_TOLERANCE,
    both_directions,
    limit_analysis,
    load_multipliers_of,
    min_thickness,
    self_weight_margin,
    shaped_min_thickness,
)

SPAN = 10.0
RISES = {"circular": 3.5, "pointed": 7.5, "elliptical": 4.0, "parabolic": 4.5, "catenary": 4.5,
         "three-centred": 3.0}
CASES = [(shape, faces) for shape in SHAPES for faces in VOUSSOIR_FACES]
IDS = [f"{shape}-{faces}" for shape, faces in CASES]


def nominal_arch(shape, faces, voussoirs=8, thickness=0.8):
    return shaped_arch(shape, span=SPAN, rise=RISES[shape], thickness=thickness,
                       voussoirs=voussoirs, faces=faces)


def _agreement(shape, faces, count):
    nominal = nominal_arch(shape, faces)
    regular = [nominal_arch(shape, faces, voussoirs=n, thickness=t)
               for n in (6, 8, 10, 12) for t in (0.5, 0.8, 1.1)]
    arches = [nominal, *irregular_sample(nominal, 0.10, count, seed=7), *regular]
    static = load_multipliers_of(arches, "static")
    kinematic = load_multipliers_of(arches, "kinematic")
    stands = np.isfinite(static)
    assert np.all(stands[: count + 1]) and np.all(static[stands] > 0)
    assert np.max(np.abs(static[stands] - kinematic[stands])) <= AGREEMENT_TOLERANCE
    # a thin regular arch that cannot stand: no thrust line (nan), a self-weight mechanism
    assert np.all(kinematic[~stands] < 0)
    # the collapse mechanisms themselves agree (a subset: full analyses are slower)
    for arch in arches[:6]:
        for direction in ("l", "r"):
            s = limit_analysis(arch, direction, "static")
            k = limit_analysis(arch, direction, "kinematic")
            assert s.hinges == k.hinges and s.separation == k.separation
    return static


@pytest.mark.parametrize(("shape", "faces"), CASES, ids=IDS)
def test_static_and_kinematic_agree_on_arches_of_every_shape(shape, faces):
    """Nominal and 24 irregular arches (epsilon = 0.10) of each shape and face, and 12 regular
    ones of other thicknesses and numbers of voussoirs: the lower and upper bounds meet to 1e-9
    (the slow run checks 200 irregular arches of each)."""
    k = _agreement(shape, faces, 24)
    # symmetric nominal arch: the same multiplier both ways
    assert k[0, 0] == pytest.approx(k[0, 1], abs=1e-12)


@pytest.mark.slow
@pytest.mark.parametrize(("shape", "faces"), CASES, ids=IDS)
def test_static_and_kinematic_agree_on_200_arches_of_every_shape(shape, faces):
    _agreement(shape, faces, 200)


@pytest.mark.parametrize("shape", SHAPES)
def test_symmetric_arch_has_mirror_mechanisms(shape):
    left, right = both_directions(nominal_arch(shape, "curved", voussoirs=10))
    assert left.load_multiplier == pytest.approx(right.load_multiplier, abs=1e-12)
    assert left.hinges == right.hinges  # Mech-r is reported in the mirrored frame


@pytest.mark.parametrize(("shape", "faces"), CASES, ids=IDS)
def test_thrust_line_inside_every_joint_and_through_the_hinges(shape, faces):
    arch = irregular_sample(nominal_arch(shape, faces), 0.1, 3, seed=2)[2]
    for result in both_directions(arch):
        depth = result.arch.joint_lengths
        u = result.thrust_line.offsets
        assert np.all(u >= -1e-9 * depth) and np.all(u <= depth * (1 + 1e-9))
        assert result.thrust_line.radii is None
        for hinge in result.hinges:
            assert result.thrust_line.points[hinge.joint] == pytest.approx(
                hinge.point(result.arch), abs=1e-7 * depth[hinge.joint])
        # equilibrium of every voussoir under its weight and k times it, horizontally
        weight = result.arch.masses * 9.81
        f = result.thrust_line.forces
        residual = f[:-1] - f[1:] + np.column_stack((result.load_multiplier * weight, -weight))
        assert np.abs(residual).max() <= 1e-9 * result.arch.total_mass * 9.81
        # compressive: the normal force points along the joint's normal
        normal = np.sum(f * result.arch.joint_normals, axis=1)
        assert np.all(normal > 0)


def test_circular_shape_is_oppenheims_arch_in_another_frame(nominal, paper):
    """The same arch, springings on y = 0 instead of the centre at the origin: the same k and
    hinges (Table 1), hinge points moved by the frame's shift."""
    arch = shaped_arch("circular", radius=10.0, embrace=math.radians(157.5), thickness=1.5,
                       voussoirs=7)
    table = paper["table1"]["NA"]
    shift = np.array([0.0, -10.0 * math.cos(math.radians(157.5) / 2)])
    for method in ("static", "kinematic"):
        shaped = limit_analysis(arch, "l", method)
        circle = limit_analysis(nominal, "l", method)
        assert shaped.load_multiplier == pytest.approx(circle.load_multiplier, abs=1e-12)
        assert [h.joint for h in shaped.hinges] == table["joints"]
        assert [h.face for h in shaped.hinges] == table["faces"]
        assert shaped.hinge_angles == pytest.approx(table["beta"], abs=1e-4)
        assert shaped.hinge_points - shift == pytest.approx(circle.hinge_points, abs=1e-12)


def test_surveyed_oppenheim_arch_has_the_circular_arch_k_and_hinges(nominal, paper):
    """Oppenheim's arch given as polygons, its curved faces sampled at 400 points: the joints
    are found from the polygons and the k is the circular arch's to the polygons' loss of
    area (1e-6), the hinges the same (Table 1)."""
    survey = surveyed_arch([nominal.outline(i, 400)[:-1] for i in range(7)])
    table = paper["table1"]["NA"]
    for direction in ("l", "r"):
        for method in ("static", "kinematic"):
            result = limit_analysis(survey, direction, method)
            reference = limit_analysis(nominal, direction, method)
            assert result.load_multiplier == pytest.approx(reference.load_multiplier, rel=1e-6)
            assert result.hinges == reference.hinges
            assert [h.joint for h in result.hinges] == table["joints"]
            assert [h.face for h in result.hinges] == table["faces"]


@pytest.mark.parametrize("shape", SHAPES)
def test_surveyed_flat_faced_arch_is_the_shaped_arch(shape):
    """A flat-faced arch of any shape given as its quadrilaterals: the same arch, found again
    from the polygons alone."""
    arch = irregular_sample(nominal_arch(shape, "flat"), 0.1, 1, seed=4)[0]
    survey = surveyed_arch([arch.outline(i)[:-1] for i in range(arch.n_voussoirs)])
    assert survey.joints == pytest.approx(arch.joints, abs=1e-12)
    assert survey.masses == pytest.approx(arch.masses, rel=1e-12)
    assert load_multipliers_of([survey], "static") == pytest.approx(
        load_multipliers_of([arch], "static"), abs=1e-10)


# ------------------------------------------------------------------ minimum thickness
def test_semicircle_minimum_thickness_converges_to_milankovitch(paper):
    """t/R of the semicircle as the voussoirs multiply: the hinges move to the continuous
    ones and t/R approaches Milankovitch's 0.1075 (quoted to four digits: +-5e-5); the shaped
    circle and the paper's circular arch give the same thickness."""
    reference = paper["closed_form"]["semicircle_min_thickness_ratio"]
    errors = []
    for n in (25, 100, 400):
        ratio = shaped_min_thickness("circular", span=2.0, rise=1.0, voussoirs=n)
        assert ratio == pytest.approx(min_thickness(1.0, math.pi, n), rel=1e-10)
        errors.append(abs(ratio - reference))
    assert errors[0] > errors[1] > errors[2]
    assert errors[2] < 5e-5


@pytest.mark.parametrize(("shape", "faces"), [c for c in CASES if c != ("catenary", "curved")],
                         ids=[i for i in IDS if i != "catenary-curved"])
def test_minimum_thickness_is_where_each_shape_just_stands(shape, faces):
    t_min = shaped_min_thickness(shape, span=SPAN, rise=RISES[shape], voussoirs=12, faces=faces)
    above = shaped_arch(shape, span=SPAN, rise=RISES[shape], thickness=t_min * (1 + 1e-4),
                        voussoirs=12, faces=faces)
    below = shaped_arch(shape, span=SPAN, rise=RISES[shape], thickness=t_min * (1 - 1e-4),
                        voussoirs=12, faces=faces)
    assert self_weight_margin(above) > 0.0 > self_weight_margin(below)
    k_above = limit_analysis(above).load_multiplier
    assert 0.0 <= k_above < 1e-3
    with pytest.raises(ValueError, match="cannot stand"):
        limit_analysis(below)


def test_catenary_of_curved_voussoirs_is_the_funicular_of_its_weight():
    """A catenary of constant thickness carries a weight uniform along its centreline (to
    O(t^2)), lumped at the voussoirs' centroids: the funicular of its own weight is the
    centreline itself at every joint, whatever the thickness, so the margin of the thrust line
    (in units of the weight times the depth) does not shrink with the thickness and the minimum
    thickness vanishes."""
    margins = [self_weight_margin(shaped_arch("catenary", span=SPAN, rise=4.5, thickness=t,
                                              voussoirs=12)) for t in (1e-3, 1e-2)]
    assert margins[0] > 0.1 and margins[0] == pytest.approx(margins[1], rel=2e-3)
    assert shaped_min_thickness("catenary", span=SPAN, rise=4.5, voussoirs=12) < 1e-9 * SPAN


def test_catenary_is_the_thinnest_shape():
    """The catenary is the funicular of a load uniform along it: of the shapes of the same
    span and rise it needs the least thickness (with many voussoirs, a small fraction of the
    parabola's)."""
    thickness = {shape: shaped_min_thickness(shape, span=SPAN, rise=4.5, voussoirs=40)
                 for shape in ("circular", "elliptical", "parabolic", "catenary",
                               "three-centred")}
    assert min(thickness, key=thickness.get) == "catenary"
    assert thickness["catenary"] < 0.3 * thickness["parabolic"]


def test_oppenheim_arch_is_unchanged_by_the_general_joints(nominal, paper):
    assert limit_analysis(oppenheim()).load_multiplier == pytest.approx(
        paper["table1"]["NA"]["load_multiplier"], abs=1e-3)


@pytest.mark.parametrize("shape", SHAPES)
def test_plot_of_every_shape_draws_its_hinges_and_thrust_line(shape, tmp_path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from archquake.plotting import plot_limit_analysis

    nominal = nominal_arch(shape, "curved")
    result = both_directions(irregular_sample(nominal, 0.1, 1, seed=0)[0])[0]
    ax = plot_limit_analysis(result, nominal=nominal)
    assert [t.get_text() for t in ax.texts if len(t.get_text()) == 1] == ["A", "B", "C", "D"]
    # the whole arch is in view, the springings and the crown
    low, high = ax.get_ylim()
    outline = np.vstack([result.arch.outline(i) for i in range(result.arch.n_voussoirs)])
    assert low < outline[:, 1].min() and high > outline[:, 1].max()
    funicular = result.funicular()
    assert any(line.get_xydata().shape == funicular.shape
               and np.allclose(line.get_xydata(), funicular) for line in ax.lines)
    ax.figure.savefig(tmp_path / f"{shape}.png")
    plt.close("all")
