"""Curved joints: the ring interfaces of an arch of several rings as arcs of their circle.

Independent values: the circle of the rings (centre at the origin of ``multi_ring``'s frame,
radius 10 m between two rings of 0.75 m on a mean radius of 10 m), closed forms of the gap and
slip of a point turned about that centre or moved along its radius, and the normal velocity of
a relative rotation about it (zero on the arc, ``omega R sin(delta / 2)`` at a chord's end).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from archquake.geometry import multi_ring
from archquake.ground_motion import oppenheim_pulse
from archquake.rigid_blocks import Assembly, BlockSettings, RigidBlockModel, from_block_assembly
from archquake.rigid_blocks.assembly import curved_joints
from archquake.rigid_blocks.contacts import contact_geometry, relative_velocity
from archquake.rigid_blocks.dynamics import contact_arrays

ALPHA = math.radians(157.5)
RADIUS = 10.0  # the interface of two rings of 0.75 m on Oppenheim's mean radius


def two_rings(**kwargs):
    return multi_ring(RADIUS, ALPHA, 1.5, rings=2, voussoirs=7, **kwargs)


def test_each_pair_of_voussoirs_shares_one_arc_of_the_rings_circle():
    """Aligned bond: 7 ring interfaces (one a voussoir pair), each an arc of radius 10 m about
    the origin, its length the voussoir's angle times 10 m; the end normals are radial; the
    other interfaces are kept as they are."""
    arch = two_rings()
    assembly = from_block_assembly(arch)
    ring = np.asarray(arch.interfaces.kind) == "ring"
    curved = assembly.curvature != 0
    assert curved.sum() == 7
    assert assembly.n_joints == np.count_nonzero(~ring) + 7
    # the face of the inner ring (body a, the lower index) is convex: curvature + 1 / R
    np.testing.assert_allclose(assembly.curvature[curved], 1.0 / RADIUS, rtol=1e-12)
    assert np.all(assembly.joint_bodies[curved, 1] - assembly.joint_bodies[curved, 0] == 7)
    points = assembly.joint_points[curved]
    np.testing.assert_allclose(np.linalg.norm(points, axis=2), RADIUS, rtol=1e-12)
    np.testing.assert_allclose(assembly.arc_lengths[curved], RADIUS * ALPHA / 7, rtol=1e-12)
    np.testing.assert_allclose(assembly.end_normals()[curved], points / RADIUS, atol=1e-12)
    # every interface stands in exactly one joint; an arc for all the chords of its pair
    flat = sorted(i for group in assembly.sources for i in group)
    assert flat == list(range(arch.interfaces.n_interfaces))
    a, b = np.asarray(arch.interfaces.a), np.asarray(arch.interfaces.b)
    for j in np.flatnonzero(curved):
        pair = tuple(assembly.joint_bodies[j])
        assert assembly.interfaces_of([j]) == tuple(
            np.flatnonzero(ring & (a == pair[0]) & (b == pair[1])))
    chords = from_block_assembly(arch, arcs=False)
    assert chords.n_joints == arch.interfaces.n_interfaces and not chords.curvature.any()
    assert chords.interfaces_of([3, 1]) == (1, 3)
    assert assembly.total_mass == pytest.approx(chords.total_mass, rel=1e-15)


def test_staggered_rings_share_half_voussoir_arcs():
    """Staggered bond: every voussoir of one ring touches two of the other along half its
    length, so the arcs are half a voussoir long."""
    assembly = from_block_assembly(two_rings(bond="staggered"))
    curved = assembly.curvature != 0
    assert curved.sum() == 14
    np.testing.assert_allclose(assembly.arc_lengths[curved], RADIUS * ALPHA / 14, rtol=1e-12)


def test_chords_off_a_circle_or_of_different_friction_stay_chords():
    """A kinked chain (its middle corner 5 % of the chord off the circle of its ends) and a
    chain whose chords differ in friction are kept as chords; a chain of one chord is flat."""
    angles = np.radians([60.0, 75.0, 90.0, 105.0, 120.0])
    corners = np.column_stack((np.cos(angles), np.sin(angles)))
    p0, p1 = corners[:-1], corners[1:]
    tangents = (p1 - p0) / np.linalg.norm(p1 - p0, axis=1)[:, None]
    normals = np.column_stack((tangents[:, 1], -tangents[:, 0]))
    a, b = np.zeros(4, dtype=int), np.ones(4, dtype=int)
    ring = np.ones(4, dtype=bool)
    out = curved_joints(a, b, p0, p1, normals, np.full(4, 0.6), ring)
    assert out[0].size == 1 and out[6][0] == pytest.approx(1.0)  # convex face of body a
    assert out[2][0] == pytest.approx(corners[0]) and out[3][0] == pytest.approx(corners[-1])
    kinked = corners.copy()
    kinked[2] *= 1.0 + 0.05 * np.linalg.norm(corners[-1] - corners[0])
    k0, k1 = kinked[:-1], kinked[1:]
    kt = (k1 - k0) / np.linalg.norm(k1 - k0, axis=1)[:, None]
    kinked_out = curved_joints(a, b, k0, k1, np.column_stack((kt[:, 1], -kt[:, 0])),
                               np.full(4, 0.6), ring)
    assert kinked_out[0].size == 4 and not kinked_out[6].any()
    mixed = curved_joints(a, b, p0, p1, normals, np.array([0.6, 0.6, 0.5, 0.6]), ring)
    assert mixed[0].size == 4 and not mixed[6].any()
    single = curved_joints(a[:1], b[:1], p0[:1], p1[:1], normals[:1], np.full(1, 0.6), ring[:1])
    assert single[0].size == 1 and single[6][0] == 0.0


def _geometry(assembly, q):
    arrays = contact_arrays(assembly, reorder=False)
    nc, nb = arrays["contacts"].shape[0], assembly.n_blocks
    gap, slip = np.zeros(nc), np.zeros(nc)
    valid, jac = np.zeros(nc, dtype=bool), np.zeros((nc, 12))
    contact_geometry(q, arrays["bodies"], arrays["contacts"], arrays["contact_bodies"],
                     np.empty((nb, 2)), gap, slip, valid, jac)
    return arrays, gap, slip, valid, jac


def _turned(assembly, blocks, angle):
    """Displacements that turn ``blocks`` about the origin by ``angle`` [rad]."""
    q = np.zeros((assembly.n_blocks, 3))
    c, s = math.cos(angle), math.sin(angle)
    centroids = assembly.centroids[blocks]
    q[blocks, 0] = c * centroids[:, 0] - s * centroids[:, 1] - centroids[:, 0]
    q[blocks, 1] = s * centroids[:, 0] + c * centroids[:, 1] - centroids[:, 1]
    q[blocks, 2] = angle
    return q


def test_the_gap_of_an_arc_is_exact_for_a_turn_about_its_centre_and_a_radial_move():
    """The outer ring (blocks 7-13) turned about the centre by 0.02 rad slides on the inner
    one: every arc's gap stays 0 (to round-off) and its slip is R * 0.02 = 0.2 m exactly (the
    chords' corners would penetrate); moved out along the radius of a joint's end by 1 mm,
    that end opens by 1 mm."""
    arch = two_rings()
    assembly = from_block_assembly(arch)
    curved = np.repeat(assembly.curvature != 0, 2)
    outer = np.arange(7, 14)
    _, gap, slip, valid, _ = _geometry(assembly, _turned(assembly, outer, 0.02))
    assert np.abs(gap[curved]).max() < 1e-12
    np.testing.assert_allclose(slip[curved], RADIUS * 0.02, rtol=1e-12)
    assert valid[curved].all()
    chords = from_block_assembly(arch, arcs=False)
    ring = np.repeat(np.asarray(arch.interfaces.kind) == "ring", 2)
    _, chord_gap, *_ = _geometry(chords, _turned(chords, outer, 0.02))
    assert chord_gap[ring].min() < -1e-3  # a chord's corner cuts into the other ring
    j = int(np.flatnonzero(assembly.curvature)[3])
    q = np.zeros((assembly.n_blocks, 3))
    q[assembly.joint_bodies[j, 1], :2] = 1e-3 * assembly.end_normals()[j, 1]
    _, gap, *_ = _geometry(assembly, q)
    assert gap[2 * j + 1] == pytest.approx(1e-3, rel=1e-9)


def test_a_rotation_about_the_centre_moves_no_arc_contact_normally():
    """Velocity: the outer ring turning about the centre at 1 rad/s has a zero normal velocity
    at every arc contact, and slides at R = 10 m/s; at the chords' corners the normal velocity
    is +-R sin(delta / 2), delta the angle between two chords."""
    arch = two_rings()
    assembly = from_block_assembly(arch)
    v = np.zeros((assembly.n_blocks, 3))
    outer = np.arange(7, 14)
    v[outer, 0] = -assembly.centroids[outer, 1]
    v[outer, 1] = assembly.centroids[outer, 0]
    v[outer, 2] = 1.0
    arrays, *_, jac = _geometry(assembly, np.zeros((assembly.n_blocks, 3)))
    cb = arrays["contact_bodies"]
    for c in np.flatnonzero(np.repeat(assembly.curvature != 0, 2)):
        un, ut = relative_velocity(v, cb[c, 0], cb[c, 1], jac, c)
        assert abs(un) < 1e-12 and ut == pytest.approx(RADIUS, rel=1e-12)
    chords = from_block_assembly(arch, arcs=False)
    arrays, *_, jac = _geometry(chords, np.zeros((chords.n_blocks, 3)))
    cb = arrays["contact_bodies"]
    ring = np.flatnonzero(np.repeat(np.asarray(arch.interfaces.kind) == "ring", 2))
    lengths = np.repeat(chords.joint_lengths, 2)[ring]
    half_angle = np.arcsin(lengths / (2 * RADIUS))
    normal = np.array([relative_velocity(v, cb[c, 0], cb[c, 1], jac, c)[0] for c in ring])
    np.testing.assert_allclose(np.abs(normal), RADIUS * np.sin(half_angle), rtol=1e-9)


def test_a_curved_joint_is_refused_where_its_radius_is_below_half_its_chord():
    """A half circle (radius 1 m on a chord of 2 m) or a nan curvature is refused by name."""
    base = dict(masses=[1.0, 1.0], centroids=[[0, 0], [0, 1]], inertias=[1.0, 1.0],
                joint_bodies=[[-1, 0], [0, 1]], joint_points=[[[-1, 0], [1, 0]],
                                                              [[-1, 1], [1, 1]]],
                joint_normals=[[0, 1], [0, 1]])
    # radius 2 m over a chord of 2 m: an arc of 2 asin(1 / 2) = pi / 3 rad, 2 pi / 3 m long
    assert Assembly(**base, curvature=[0.0, 0.5]).arc_lengths[1] == pytest.approx(2 * math.pi / 3)
    with pytest.raises(ValueError, match="curvature must be 2 finite numbers"):
        Assembly(**base, curvature=[0.0, 1.0])
    with pytest.raises(ValueError, match="curvature"):
        Assembly(**base, curvature=[0.0, math.nan])


@pytest.mark.parametrize("amplitude", [0.22, 0.4])
def test_arcs_and_fine_chords_give_the_same_outcome(amplitude):
    """Two rings in staggered bond under Oppenheim's pulse of 0.5 s, the interfaces as arcs
    (chords of 0.05 t) and as chords 10 times finer: at 0.22 g and 0.4 g, on either side of
    the failure acceleration (0.28 g in aligned bond, ``benchmarks/ring_arches.py
    --rigid-blocks``), both collapse or neither does."""
    motion = oppenheim_pulse(-amplitude * 9.81, 0.5)
    settings = BlockSettings(friction=0.8)
    arcs = RigidBlockModel(two_rings(arc_error=0.05 * 1.5, bond="staggered"),
                           settings).outcome(motion)
    chords = RigidBlockModel(from_block_assembly(
        two_rings(arc_error=0.005 * 1.5, bond="staggered"), arcs=False), settings).outcome(motion)
    assert arcs.collapsed == chords.collapsed == (amplitude > 0.3)


def test_staggered_rings_move_below_the_iterations_multiplier():
    """Two staggered rings, friction 0.8: the ramp's onset (the cube law of a mechanism
    starting from rest, extrapolated from three crossings) lies between a held acceleration
    that leaves the blocks at rest (0.17 g for 1 s) and one that moves them (0.19 g), and well
    below the non-associative iteration's k (0.2417: no bound with non-associative friction;
    user guide, "Bridges: several rings")."""
    from archquake.constants import GRAVITY
    from archquake.ground_motion.pulses import rectangular_pulse
    from archquake.limit_analysis import assembly_limit
    from archquake.rigid_blocks.ramp import ramp_test

    arch = two_rings(bond="staggered")
    model = RigidBlockModel(arch, BlockSettings(friction=0.8))
    assert model.outcome(rectangular_pulse(-0.17 * GRAVITY, 1.0)).status.label == "rest"
    assert model.outcome(rectangular_pulse(-0.19 * GRAVITY, 1.0)).status.label != "rest"
    onset = ramp_test(arch, friction=0.8).onset("+x")
    assert 0.17 < onset.multiplier < 0.19 and onset.error < 0.005
    k = assembly_limit(arch.with_friction(0.8), law="non-associative").load_multiplier
    assert k > 1.2 * onset.multiplier
