"""Rigid-block model of general assemblies: a wall in running bond, a stack of blocks.

Checks of the non-chain topology (blocks touching several others, several ground joints, joints
between non-consecutive blocks), of the renumbering of the joints (the same motion in either
order) and of the adapter from a block assembly (a stand-in object with the attributes of
``archquake.geometry.assembly.BlockAssembly``).
"""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest

from archquake.geometry import GRAVITY
from archquake.geometry.assembly import wall as geometry_wall
from archquake.ground_motion import rectangular_pulse
from archquake.rigid_blocks import (
    BlockSettings,
    block_outcome,
    from_block_assembly,
    simulate_blocks,
)
from archquake.rigid_blocks.dynamics import (
    MAX_ASSEMBLY_BLOCKS,
    check_size,
    joint_half_bandwidth,
    joint_order,
)


def running_bond_wall(courses: int, blocks: int, friction: float = 0.6):
    """The rigid blocks of a wall in running bond of 0.4 x 0.2 m blocks
    (:func:`archquake.geometry.assembly.wall`), its interfaces numbered as a geometry code that
    collects them by kind might: the foundation, then the bed joints, then the head joints, so a
    block's joints lie far apart in the numbering (the solver renumbers them)."""
    built = geometry_wall(courses, blocks, 0.4, 0.2, friction=friction)
    faces = built.interfaces
    order = np.argsort([("foundation", "bed", "head").index(k) for k in faces.kind],
                       kind="stable")
    interfaces = SimpleNamespace(**{name: np.asarray(getattr(faces, name))[order]
                                    for name in ("a", "b", "p0", "p1", "normal", "friction")})
    return from_block_assembly(SimpleNamespace(
        polygons=built.polygons, mass=built.mass, centroid=built.centroid,
        inertia=built.inertia, interfaces=interfaces))


def stack(n: int, b: float, h: float, friction: float = math.inf, density: float = 2000.0):
    """A stand-in block assembly: ``n`` equal blocks b x h stacked on the ground."""
    polygons = tuple(np.array([[-b / 2, k * h], [b / 2, k * h], [b / 2, (k + 1) * h],
                               [-b / 2, (k + 1) * h]]) for k in range(n))
    mass = np.full(n, density * b * h)
    a = np.arange(-1, n - 1)
    interfaces = SimpleNamespace(
        a=a, b=np.arange(n), p0=np.column_stack((np.full(n, b / 2), h * np.arange(n))),
        p1=np.column_stack((np.full(n, -b / 2), h * np.arange(n))),
        normal=np.tile([0.0, 1.0], (n, 1)), friction=np.full(n, friction))
    return SimpleNamespace(polygons=polygons, mass=mass,
                           centroid=np.column_stack((np.zeros(n), h * (np.arange(n) + 0.5))),
                           inertia=mass * (b**2 + h**2) / 12.0, interfaces=interfaces)


def test_adapter_reads_a_block_assembly():
    """Blocks, joints, friction, crown (top of the highest block) and thickness (the median
    shorter side: b = 0.3 m of 0.3 x 0.9 blocks) of a stack of three blocks."""
    assembly = from_block_assembly(stack(3, 0.3, 0.9, friction=0.7))
    assert assembly.n_blocks == 3 and assembly.n_joints == 3
    assert assembly.thickness == pytest.approx(0.3)
    assert assembly.crown[0] == 2 and np.allclose(assembly.crown[1], [0.0, 2.7])
    np.testing.assert_array_equal(assembly.friction, [0.7, 0.7, 0.7])
    assert assembly.total_mass == pytest.approx(3 * 2000 * 0.27)
    with pytest.raises(ValueError, match="block assembly"):
        from_block_assembly(SimpleNamespace(polygons=()))


def test_wall_topology_and_renumbering():
    """A wall of 4 courses of 6 and 7 blocks (26 blocks): 6 foundation joints, 3 x 12 bed
    joints (between a course of 6 and one of 7 offset by half a block, every block overlaps two:
    2 x 6 overlaps) and 5 + 6 + 5 + 6 head joints; the renumbered half-bandwidth is smaller
    than the natural one, and a column of blocks (a chain) keeps its own order."""
    wall = running_bond_wall(4, 6)
    assert wall.n_blocks == 6 + 7 + 6 + 7
    # bed joints between a course of 6 and one of 7 (joints offset by half a block): 12 overlaps
    foundation, bed, head = 6, 3 * 12, 5 + 6 + 5 + 6
    assert wall.n_joints == foundation + bed + head
    natural = joint_half_bandwidth(wall.joint_bodies, wall.n_blocks)
    order = joint_order(wall)
    assert sorted(order.tolist()) == list(range(wall.n_joints))
    assert joint_half_bandwidth(wall.joint_bodies, wall.n_blocks, order) < natural
    column = from_block_assembly(stack(4, 0.3, 0.9))
    np.testing.assert_array_equal(joint_order(column), np.arange(4))


def test_wall_at_rest_stays_at_rest():
    """A wall of 26 blocks on a still ground for 1 s: it carries its weight without moving.
    Bound: 1e-9 m, a millionth of a block's 0.2 m height -- the impulses at rest solve the static
    problem to round-off and the contacts sink by nothing (no closing velocity), so only
    round-off (1e-15 m per step over 2,700 steps of 0.37 ms) could move a block."""
    wall = running_bond_wall(4, 6)
    history = simulate_blocks(wall, None, t_end=1.0)
    assert history.times[-1] >= 1.0 - 2 * history.settings.time_step
    assert np.abs(history.displacements).max() < 1e-9
    assert np.abs(history.rotations).max() < 1e-9
    # the foundation carries the weight: sum of normal forces = M g
    weight = wall.total_mass * GRAVITY
    base = history.normal_forces[-1][:6].sum()
    assert base == pytest.approx(weight, rel=1e-6)
    assert block_outcome(wall, None).status.label == "rest"


def test_wall_of_100_blocks_at_rest_is_solved_without_cycling():
    """A wall of 100 blocks (8 courses in running bond, friction 0.6) on a still ground: every
    step's contact problem is decided by the active-set method in a few solves, nothing moves,
    and the foundation carries the weight. Its head joints carry no normal force at rest, where
    a velocity tolerance below the resolution of the contact problem's compliance once made the
    active-set method cycle at every step (60 solves, then Lemke's algorithm). The weight, by
    hand: courses of 12 blocks alternate with courses of 11 and two half blocks, 4 x 12 +
    4 x 12 = 96 blocks' worth of 0.4 x 0.2 m at 2000 kg/m^3: M g = 96 x 0.08 x 2000 x g =
    15,360 kg/m x g, on the 12 foundation joints."""
    wall = running_bond_wall(8, 12)
    assert wall.n_blocks == 4 * 12 + 4 * 13
    history = simulate_blocks(wall, None, t_end=0.01)
    assert history.outcome.fallback_steps == 0
    assert history.outcome.mean_iterations < 5.0
    assert np.abs(history.displacements).max() < 1e-9
    assert np.abs(history.rotations).max() < 1e-9
    weight = 96 * 0.4 * 0.2 * 2000.0 * GRAVITY
    assert history.normal_forces[-1][:12].sum() == pytest.approx(weight, rel=1e-6)


def test_renumbered_run_equals_natural_order():
    """A small wall (2 courses) under a pulse that slides it (0.8 g > mu = 0.6 g): the same
    outcome and the same histories, in the caller's joint order, to round-off."""
    wall = running_bond_wall(2, 2)
    assert joint_half_bandwidth(wall.joint_bodies, wall.n_blocks, joint_order(wall)) < \
        joint_half_bandwidth(wall.joint_bodies, wall.n_blocks)
    motion = rectangular_pulse(0.8 * GRAVITY, 0.05)
    runs = [simulate_blocks(wall, motion, t_end=0.1, reorder=r) for r in (True, False)]
    a, b = runs
    assert a.outcome.status == b.outcome.status
    assert np.abs(a.displacements).max() > 1e-4  # it moved
    scale = np.abs(a.displacements).max()
    np.testing.assert_allclose(a.displacements, b.displacements, atol=1e-9 * scale)
    np.testing.assert_allclose(a.rotations, b.rotations, atol=1e-9)
    # the wall is statically indeterminate: its contact forces are fixed only by the contact
    # problem's regularisation (a compliance of 1e-9 of the diagonal), which two orders of
    # elimination meet differently, to a few 1e-6 of the largest force (its motion is the same)
    force = np.abs(a.normal_forces).max()
    np.testing.assert_allclose(a.normal_forces, b.normal_forces, atol=1e-5 * force)
    np.testing.assert_allclose(a.gaps, b.gaps, atol=1e-9 * scale)


@pytest.mark.parametrize("factor, collapses", [(0.85, False), (1.6, True)])
def test_stack_rocking_threshold(factor, collapses):
    """Two equal blocks b = 0.2 m x h = 0.6 m stacked, friction infinite (no sliding). Under a
    constant ground acceleration a the stack rocks as one about its base corner once
    a > g b / H, H = 2 h = 1.2 m the stack's height (moment of the weight about the corner,
    M g b/2, against that of the inertia force, M a H/2): a_0 = 0.2/1.2 g = 0.1667 g (the upper
    block alone needs g b / h = 0.333 g). A rectangular pulse of 0.85 a_0 leaves it at rest;
    one of 1.6 a_0 held for 1.5 s topples it (it rotates past its slenderness
    atan(b/H) = 9.5 degrees before the pulse ends)."""
    assembly = from_block_assembly(stack(2, 0.2, 0.6))
    a0 = GRAVITY * 0.2 / 1.2
    outcome = block_outcome(assembly, rectangular_pulse(-factor * a0, 1.5),
                            BlockSettings(settle_time=1.0))
    assert outcome.collapsed is collapses
    if not collapses:
        assert outcome.status.label == "rest" and outcome.max_rotation < 1e-9


def test_assembly_size_limit():
    """An assembly may have up to MAX_ASSEMBLY_BLOCKS blocks; one more is refused by name."""
    check_size(MAX_ASSEMBLY_BLOCKS, MAX_ASSEMBLY_BLOCKS)
    with pytest.raises(ValueError, match="MAX_ASSEMBLY_BLOCKS"):
        check_size(MAX_ASSEMBLY_BLOCKS + 1, MAX_ASSEMBLY_BLOCKS)
