"""The rigid-block model of arches on piers and with fill: the piers are blocks on the ground,
the fill is mass carried by its voussoir; at rest the supports carry the whole weight, and the
motion starts within 1 % of the limit analysis' multiplier with its hinges."""

import numpy as np
import pytest

from archquake.geometry import GRAVITY, Fill, Pier, Structure, arch_on_piers
from archquake.ground_motion import rectangular_pulse
from archquake.limit_analysis import both_directions
from archquake.rigid_blocks import GROUND, block_outcome, from_arch, simulate_blocks

FILL = Fill(0.5, 1600.0)

STRUCTURES = {
    "piers": lambda a: arch_on_piers(a, 3.0, 6.0),
    "piers, 2 courses": lambda a: arch_on_piers(a, 3.0, 6.0, 2),
    "unequal piers": lambda a: Structure(a, Pier(3.0, 6.0), Pier(3.5, 5.0, 2)),
    "fill": lambda a: Structure(a, fill=FILL),
    "piers and fill": lambda a: arch_on_piers(a, 3.0, 6.0, fill=FILL),
}


def test_piers_stand_on_the_ground_and_fill_rides_on_the_voussoirs(nominal):
    structure = arch_on_piers(nominal, 3.0, 6.0, 2, fill=FILL)
    asm = from_arch(structure)
    n = structure.n_voussoirs
    assert n == 11 and asm.n_blocks == 11 and asm.n_joints == 12
    assert asm.joint_bodies[0].tolist() == [GROUND, 0]
    assert asm.joint_bodies[-1].tolist() == [n - 1, GROUND]
    assert asm.joint_points[0] == pytest.approx(structure.joints[0])  # the left pier's base
    voussoirs = slice(2, 9)
    assert asm.masses[voussoirs] == pytest.approx(nominal.masses
                                                  + structure.fill_columns.masses)
    assert asm.thickness == 1.5 and asm.crown[0] == 5
    assert "on two rectangular piers" in asm.name


def test_supports_carry_the_whole_weight(nominal):
    structure = arch_on_piers(nominal, 3.0, 6.0, fill=FILL)
    asm = from_arch(structure)
    weight = asm.total_mass * GRAVITY
    history = simulate_blocks(structure, None, t_end=0.5, record_every=10)
    assert history.outcome.max_opening < 1e-9
    total = np.zeros(2)
    for j, sign in ((0, 1.0), (asm.n_joints - 1, -1.0)):  # on the structure from each support
        normal = asm.joint_normals[j]
        tangent = np.array([-normal[1], normal[0]])
        total += sign * (history.normal_forces[-1, j].sum() * normal
                         + history.tangential_forces[-1, j].sum() * tangent)
    assert total == pytest.approx([0.0, weight], abs=1e-7 * weight)
    # the weight of the piers (b h plus the top above the intrados springing), arch and fill
    (x_in, y_in), (x_out, y_out) = nominal.joints[0]
    reach, rise = x_in - x_out, y_out - y_in
    pier = 3.0 * 6.0 + 3.0 * rise - 0.5 * reach * rise
    assert asm.total_mass == pytest.approx(2 * 2000.0 * pier + nominal.total_mass
                                           + structure.fill_columns.masses.sum(), rel=1e-12)


def opened_hinges(result, n):
    """(joint, end that opens) of every hinge, in the structure's own frame."""
    out = set()
    for hinge in result.hinges:
        joint = hinge.joint if result.direction == "l" else n - hinge.joint
        out.add((joint, 1 if hinge.face == "intrados" else 0))
    return out


@pytest.mark.parametrize("name", list(STRUCTURES))
@pytest.mark.parametrize("direction", ["l", "r"])
def test_activation_matches_limit_analysis_through_piers(nominal, name, direction):
    """A constant ground acceleration 1 % below k leaves the structure at rest; 1 % above it
    the four hinges of the limit analysis open, pier joints among them."""
    structure = STRUCTURES[name](nominal)
    result = both_directions(structure)[0 if direction == "l" else 1]
    k = result.load_multiplier
    sign = -1.0 if direction == "l" else 1.0
    below = block_outcome(structure, rectangular_pulse(sign * 0.99 * k * GRAVITY, 1.0))
    assert below.status.label == "rest" and below.max_opening < 1e-8
    history = simulate_blocks(structure, rectangular_pulse(sign * 1.01 * k * GRAVITY, 1.0),
                              t_end=1.0, record_every=50)
    opening = history.gaps[-1]
    assert opening.max() > 1e-3
    opened = {(int(j), int(e)) for j, e in zip(*np.nonzero(opening > 1e-4), strict=True)}
    assert opened == opened_hinges(result, structure.n_voussoirs)


def test_rigid_blocks_need_the_fill_as_mass(nominal):
    with pytest.raises(ValueError, match="fill inertia 'extrados' is a limit-analysis model"):
        from_arch(Structure(nominal, fill=Fill(0.5, 1600.0, "extrados")))
