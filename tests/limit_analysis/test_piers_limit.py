"""Limit analysis through piers: the rocking portal's closed form, the static and kinematic
methods against each other, the same numbers as the equivalent surveyed blocks, "cannot stand"
naming the part that fails, and the narrowest piers that stand."""

import math

import pytest

from archquake.errors import CannotStandError
from archquake.geometry import (
    Pier,
    Structure,
    arch_on_piers,
    circular_arch,
    shaped_arch,
    surveyed_arch,
)
from archquake.limit_analysis import (
    AGREEMENT_TOLERANCE,
    both_directions,
    limit_analysis,
    min_pier_width,
    self_weight_margin,
    standing,
)
from structures_reference import Lintel, piers_survey, portal_blocks

METHODS = ("static", "kinematic")


def hinges(result):
    return [(h.joint, h.face) for h in result.hinges]


@pytest.mark.parametrize("courses", [1, 2, 5])
@pytest.mark.parametrize("method", METHODS)
def test_rocking_portal_has_k_b_over_h(courses, method):
    """Two columns b x h under a rigid lintel sway as a parallelogram: by virtual work
    k = b / h whatever the lintel weighs [Housner's column; the portal frame's sway]; the hinges
    are the columns' toes and tops, through every course (hinges only at the base and the top)."""
    b, h = 0.6, 4.0
    portal = Structure(Lintel(3.0, b, 0.8), Pier(b, h, courses), Pier(b, h, courses))
    result = limit_analysis(portal, "l", method)
    assert result.load_multiplier == pytest.approx(b / h, rel=1e-12)
    n = 2 * courses + 1
    assert hinges(result) == [(0, "intrados"), (courses, "extrados"),
                              (courses + 1, "intrados"), (n, "extrados")]


def test_portal_of_surveyed_blocks_has_k_b_over_h():
    """The same portal drawn block by block (two or more courses: at least four blocks)."""
    blocks, springings = portal_blocks(0.6, 4.0, 3, 3.0, 0.8)
    for result in both_directions(surveyed_arch(blocks, springings)):
        assert result.load_multiplier == pytest.approx(0.15, rel=1e-12)


@pytest.mark.parametrize("piers", [(3.0, 6.0, 1), (3.0, 6.0, 3), (4.0, 10.0, 2)])
def test_static_and_kinematic_agree_through_the_piers(nominal, piers):
    structure = arch_on_piers(nominal, *piers)
    static, kinematic = (both_directions(structure, m) for m in METHODS)
    for s, k in zip(static, kinematic, strict=True):
        assert s.load_multiplier == pytest.approx(k.load_multiplier, abs=AGREEMENT_TOLERANCE)
        assert hinges(s) == hinges(k)


def test_oppenheim_arch_on_piers_hinges_at_a_pier_toe(nominal):
    """On piers 3 m x 6 m Oppenheim's arch loses 61 % of its k (0.37 -> 0.144): the right
    pier turns about its outer toe."""
    result_l, result_r = both_directions(arch_on_piers(nominal, 3.0, 6.0))
    assert result_l.load_multiplier == pytest.approx(result_r.load_multiplier, rel=1e-12)
    assert result_l.load_multiplier < 0.4 * both_directions(nominal)[0].load_multiplier
    assert hinges(result_l)[-1] == (9, "extrados")  # the right pier's base, outer end


@pytest.mark.parametrize("faces", ["curved", "flat"])
def test_same_numbers_as_the_equivalent_surveyed_blocks(nominal, faces):
    """The structure and the surveyed blocks drawn by hand give the same k and hinges: exactly
    with flat faces, to the sampling of the arcs with curved ones (400 points a face)."""
    arch = nominal if faces == "curved" else shaped_arch(
        "circular", radius=10.0, embrace=math.radians(157.5), thickness=1.5, voussoirs=7,
        faces="flat")
    for left, right in (((3.0, 6.0), (3.0, 6.0)), ((2.5, 5.0), (4.0, 7.0))):
        structure = Structure(arch, Pier(*left), Pier(*right))
        survey = surveyed_arch(*piers_survey(arch, left, right))
        assert survey.joints == pytest.approx(structure.joints, abs=1e-12)
        tolerance = 1e-11 if faces == "flat" else 1e-6
        for mine, theirs in zip(both_directions(structure), both_directions(survey),
                                strict=True):
            assert mine.load_multiplier == pytest.approx(theirs.load_multiplier, rel=tolerance)
            assert hinges(mine) == hinges(theirs)


@pytest.mark.parametrize("method", METHODS)
def test_cannot_stand_names_the_piers(nominal, method):
    with pytest.raises(CannotStandError, match=r"^the piers \(rectangular pier 2 m wide, 6 m "
                                               r"high, 1 course\) cannot carry the arch's "
                                               "thrust"):
        limit_analysis(arch_on_piers(nominal, 2.0, 6.0), "l", method)
    verdict = standing(Structure(nominal, Pier(2.0, 6.0), Pier(4.0, 6.0)))
    assert (verdict.stands, verdict.part) == (False, "left pier")
    for direction in ("l", "r"):  # named in the structure's own frame
        with pytest.raises(CannotStandError, match="^the left pier"):
            limit_analysis(Structure(nominal, Pier(2.0, 6.0), Pier(4.0, 6.0)), direction,
                           method)


def test_cannot_stand_names_the_arch_when_it_is_the_arch():
    thin = circular_arch(10.0, math.radians(157.5), 0.3, 7)
    verdict = standing(arch_on_piers(thin, 5.0, 6.0))
    assert (verdict.stands, verdict.part) == (False, "arch")
    with pytest.raises(CannotStandError, match="even on fixed springings"):
        limit_analysis(arch_on_piers(thin, 5.0, 6.0))
    assert standing(arch_on_piers(circular_arch(10.0, 2.7, 1.5, 7), 3.0, 6.0)).stands


def test_min_pier_width_is_where_the_kinematic_k_vanishes(nominal):
    """At the narrowest piers that stand under self-weight (the static margin's root) the
    collapse mechanism's multiplier falls to zero: a hair wider the kinematic k is a hair above
    0, a hair narrower the structure cannot stand."""
    width = min_pier_width(nominal, 6.0)
    assert 2.0 < width < 3.0
    k = limit_analysis(arch_on_piers(nominal, width * (1 + 1e-6), 6.0), "l",
                       "kinematic").load_multiplier
    assert 0.0 <= k < 1e-5
    assert self_weight_margin(arch_on_piers(nominal, width * (1 - 1e-6), 6.0)) < 0
    with pytest.raises(CannotStandError):
        limit_analysis(arch_on_piers(nominal, width * (1 - 1e-4), 6.0), "l", "kinematic")
    # taller piers must be wider; more courses cannot help
    assert min_pier_width(nominal, 10.0) > width
    assert min_pier_width(nominal, 6.0, 3) >= width - 1e-9


def test_min_pier_width_of_an_arch_that_cannot_stand():
    with pytest.raises(CannotStandError, match="no pier can make it stand"):
        min_pier_width(circular_arch(10.0, math.radians(157.5), 0.3, 7), 6.0)
    with pytest.raises(ValueError, match="height must be"):
        min_pier_width(circular_arch(10.0, 2.0, 1.0, 7), -1.0)


def test_irregular_arches_on_the_same_piers(nominal):
    """An irregular draw perturbs the arch (its voussoirs' draws) and keeps the piers and the
    fill; both methods agree on every arch of the sample."""
    from archquake.geometry import Fill, irregular_sample
    from archquake.limit_analysis import limit_sample

    structure = arch_on_piers(nominal, 3.0, 6.0, fill=Fill(0.5, 1600.0))
    sample = irregular_sample(structure, 0.1, 4, seed=0)
    assert all(s.left == structure.left and s.fill == structure.fill for s in sample)
    assert all(s.arch != nominal for s in sample)
    static = limit_sample(structure, 0.1, 4, 0, "static")
    kinematic = limit_sample(structure, 0.1, 4, 0, "kinematic")
    assert static.load_multiplier == pytest.approx(kinematic.load_multiplier,
                                                   abs=AGREEMENT_TOLERANCE)


def test_plot_of_the_mechanism_through_a_pier(nominal, tmp_path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    from archquake.geometry import Fill
    from archquake.plotting import plot_limit_analysis

    structure = arch_on_piers(nominal, 3.0, 6.0, 2, fill=Fill(0.5, 1600.0))
    result = both_directions(structure)[0]
    ax = plot_limit_analysis(result)
    assert [t.get_text() for t in ax.texts if len(t.get_text()) == 1] == ["A", "B", "C", "D"]
    low, high = ax.get_ylim()  # the piers' bases and the fill's surface in view
    assert low < structure.joints[0, 0, 1] and high > structure.fill_columns.level
    assert len(ax.patches) == 7  # a fill column over every voussoir
    ax.figure.savefig(tmp_path / "piers.png")
    plt.close("all")
    assert np.isfinite(result.funicular()).all()


def test_a_surveyed_arch_stands_on_piers_too(nominal):
    """Piers under the springings of a surveyed arch: the circular arch's k on the same piers,
    to the sampling of its arcs."""
    survey = surveyed_arch([nominal.outline(i, 400)[:-1] for i in range(7)])
    k_survey = both_directions(arch_on_piers(survey, 3.0, 6.0))[0].load_multiplier
    k_circle = both_directions(arch_on_piers(nominal, 3.0, 6.0))[0].load_multiplier
    assert k_survey == pytest.approx(k_circle, rel=1e-5)
