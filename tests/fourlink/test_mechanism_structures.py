"""The four-link model through piers and with fill: links that hold pier courses, activation at
the limit analysis' multiplier, mass properties against closed forms and the hand-drawn
surveyed equivalent, the fill carried as mass, and which restitution rules apply."""

import math

import numpy as np
import pytest

from archquake import GRAVITY, FourLinkModel
from archquake.fourlink.impact import kinetic_energy_ratio, link_restitution, restitution
from archquake.fourlink.mechanism import mechanisms
from archquake.geometry import Fill, Pier, Structure, arch_on_piers, shaped_arch, surveyed_arch
from archquake.ground_motion import oppenheim_pulse
from archquake.limit_analysis import both_directions
from structures_reference import piers_survey

FILL = Fill(0.5, 1600.0)

STRUCTURES = {
    "piers": lambda a: arch_on_piers(a, 3.0, 6.0),
    "piers, 3 courses": lambda a: arch_on_piers(a, 3.0, 6.0, 3),
    "unequal piers": lambda a: Structure(a, Pier(3.0, 6.0), Pier(4.0, 8.0, 2)),
    "fill": lambda a: Structure(a, fill=FILL),
    "piers and fill": lambda a: arch_on_piers(a, 3.0, 6.0, 2, fill=FILL),
}


@pytest.mark.parametrize("name", list(STRUCTURES))
def test_activation_is_the_limit_multiplier(nominal, name):
    """By virtual work the ground acceleration that starts a mechanism, -F/P of its equation
    of motion (written with the links' mass properties), is the limit analysis' multiplier of
    its hinges (written with the blocks' loads)."""
    structure = STRUCTURES[name](nominal)
    limit = both_directions(structure)
    for mech, la in zip(mechanisms(structure, limit), limit, strict=True):
        assert mech.activation_g == pytest.approx(la.load_multiplier, rel=1e-10)
        assert mech.is_admissible and mech.theta_limit < mech.theta_cr < mech.theta_u


def _polygon(points, density):
    """Mass, centroid and polar moment about the origin of a polygon (shoelace, either
    sense)."""
    x, y = np.asarray(points, dtype=float).T
    x1, y1 = np.roll(x, -1), np.roll(y, -1)
    c = x * y1 - x1 * y
    c = c if c.sum() > 0 else -c
    area = c.sum() / 2
    g = np.array([((x + x1) * c).sum(), ((y + y1) * c).sum()]) / (6 * area)
    polar = ((x * x + x * x1 + x1 * x1 + y * y + y * y1 + y1 * y1) * c).sum() / 12
    return density * area, g, density * polar


def test_a_link_holds_a_pier_and_a_voussoir(nominal):
    """Mech-l of Oppenheim's arch on piers 3 m x 6 m: its link CD is the last voussoir and the
    right pier, turning about the pier's outer toe D; its mass and moment of inertia about D
    from the annular sector's and the hand-drawn pier's closed forms."""
    structure = arch_on_piers(nominal, 3.0, 6.0)
    mech = mechanisms(structure)[0]
    assert [h.joint for h in mech.hinges] == [2, 4, 7, 9]
    blocks, _ = piers_survey(nominal, (3.0, 6.0), (3.0, 6.0))
    m_pier, g_pier, polar_pier = _polygon(blocks[-1], 2000.0)
    d = mech.hinge_points[3]
    assert d == pytest.approx(blocks[-1][-1])  # the outer toe
    ri, ro, alpha = 9.25, 10.75, math.radians(157.5) / 7
    m_v = 2000.0 * alpha / 2 * (ro**2 - ri**2)
    g_v = nominal.centroids[6]
    polar_v = 2000.0 * alpha / 4 * (ro**4 - ri**4)  # about O
    assert mech.block_masses[2] == pytest.approx(m_v + m_pier, rel=1e-12)
    j_d = (polar_v - 2 * m_v * g_v @ d + m_v * d @ d) + (polar_pier - 2 * m_pier * g_pier @ d
                                                         + m_pier * d @ d)
    assert mech.block_pivot_inertias[2] == pytest.approx(j_d, rel=1e-12)


def test_same_dynamics_as_the_surveyed_blocks():
    """Flat faces: the structure and its hand-drawn surveyed blocks are the same chain, to
    round-off: the same mechanisms, the same response to a pulse."""
    arch = shaped_arch("circular", radius=10.0, embrace=math.radians(157.5), thickness=1.5,
                       voussoirs=7, faces="flat")
    structure = Structure(arch, Pier(3.0, 6.0), Pier(4.0, 7.0))
    survey = surveyed_arch(*piers_survey(arch, (3.0, 6.0), (4.0, 7.0)))
    mine, theirs = FourLinkModel.from_arch(structure), FourLinkModel.from_arch(survey)
    for a, b in zip(mine.mechanisms, theirs.mechanisms, strict=True):
        assert a.parameters == pytest.approx(b.parameters, rel=1e-10, abs=1e-10)
    pulse = oppenheim_pulse(-1.5 * mine.load_multiplier * GRAVITY, 0.5)
    one, other = mine.outcome(pulse), theirs.outcome(pulse)
    assert one.status == other.status and one.max_phi == pytest.approx(other.max_phi, rel=1e-8)


def test_fill_moves_with_its_voussoir(nominal):
    """The links carry the fill: their masses add up to the moving voussoirs' and their
    columns'."""
    structure = Structure(nominal, fill=FILL)
    mech = mechanisms(structure)[0]
    ja, jd = mech.hinges[0].joint, mech.hinges[3].joint
    columns = structure.fill_columns.masses
    assert mech.block_masses.sum() == pytest.approx(
        nominal.masses[ja:jd].sum() + columns[ja:jd].sum(), rel=1e-12)


def test_dynamics_need_the_fill_as_mass(nominal):
    for inertia in ("none", "extrados"):
        with pytest.raises(ValueError, match=f"fill inertia '{inertia}' is a limit-analysis "
                                             "model"):
            FourLinkModel.from_arch(Structure(nominal, fill=Fill(0.5, 1600.0, inertia)))


def test_restitution_rules_through_the_piers(nominal):
    """The momentum balance of the arch (computed) and the rigid-block measure apply to any
    chain; the paper's link rule does not: Mech-l leaves the left pier and the first voussoir
    at rest (hinge A one joint above the springing), so the link A'B' of Mech-r that the rule
    follows has no momentum before the impact and the rule gives 0."""
    structure = arch_on_piers(nominal, 3.0, 6.0)
    mech_l, mech_r = mechanisms(structure)
    assert mech_l.hinges[0].joint == 2
    velocities, angular = mech_l.mode_shape()
    assert np.all(velocities[:2] == 0.0) and np.all(angular[:2] == 0.0)
    assert link_restitution(mech_l, mech_r) == 0.0
    c_lr, c_rl = restitution("computed", mech_l, mech_r)
    assert 0.0 < c_lr < 1.0 and c_lr == pytest.approx(c_rl, rel=1e-9)
    assert 0.0 < kinetic_energy_ratio(mech_l, mech_r) <= 1.0


def test_a_structure_responds_to_a_pulse(nominal):
    """The whole chain -- limit analysis, mechanisms through the pier, restitution, tables --
    runs, and a pulse below k leaves the structure at rest."""
    model = FourLinkModel.from_arch(arch_on_piers(nominal, 3.0, 6.0, fill=FILL))
    k = model.load_multiplier
    assert model.outcome(oppenheim_pulse(-0.9 * k * GRAVITY, 0.4)).status.label == "rest"
    assert model.outcome(oppenheim_pulse(-4 * k * GRAVITY, 0.4)).status.label != "rest"
