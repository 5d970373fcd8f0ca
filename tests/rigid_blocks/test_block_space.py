"""The contact problem's systems solved in the blocks' velocities
(:mod:`archquake.rigid_blocks.block_space`) against a dense solve of the impulses' system and a
block at rest, whose impulses carry its weight."""

import math

import numpy as np
import pytest

from archquake import oppenheim
from archquake.geometry import GRAVITY, Fill, Pier, multi_ring
from archquake.geometry.assembly import wall as geometry_wall
from archquake.geometry.bridge import multi_span
from archquake.ground_motion import sine_pulse
from archquake.rigid_blocks import (
    BlockSettings,
    from_arch,
    from_block_assembly,
    rectangular_block,
    simulate_blocks,
)
from archquake.rigid_blocks.block_space import (
    AUGMENTED_SOLVES,
    block_band,
    solve_active_set_blocks,
    solve_states,
)
from archquake.rigid_blocks.contact_problem import (
    REGULARISATION,
    SWITCH_VELOCITY,
    incidence,
    solve_active_set,
)
from archquake.rigid_blocks.contacts import FRICTION, contact_geometry, relative_velocity
from archquake.rigid_blocks.dynamics import contact_arrays, contact_unknowns


def problem(assembly, h=1e-3, ag=0.0):
    """The first step's arrays at rest: free velocities of the weight and of ``-m ag``."""
    arrays = contact_arrays(assembly)
    bodies, contacts, cb = arrays["bodies"], arrays["contacts"], arrays["contact_bodies"]
    nb, nc = bodies.shape[0], contacts.shape[0]
    gap, slip, valid, jac = np.zeros(nc), np.zeros(nc), np.zeros(nc, bool), np.zeros((nc, 12))
    contact_geometry(np.zeros((nb, 3)), bodies, contacts, cb, np.empty((nb, 2)), gap, slip,
                     valid, jac)
    inv_mass = np.column_stack([1 / bodies[:, 0], 1 / bodies[:, 1]])
    v_free = np.zeros((nb, 3))
    v_free[:, 0] = -ag * h
    v_free[:, 1] = -GRAVITY * h
    big_h = np.zeros((2 * nc, 3 * nb))
    for c in range(nc):
        for side, first in ((0, 0), (1, 6)):
            body = cb[c, side]
            if body >= 0:
                big_h[2 * c, 3 * body:3 * body + 3] = jac[c, first:first + 3]
                big_h[2 * c + 1, 3 * body:3 * body + 3] = jac[c, first + 3:first + 6]
    minv = np.repeat(inv_mass, (2, 1), axis=1).reshape(-1)
    diag_w = np.einsum("ij,j,ij->i", big_h, minv, big_h)
    return dict(nb=nb, cb=cb, jac=jac, inv_mass=inv_mass, v_free=v_free, big_h=big_h,
                minv=minv, compliance=REGULARISATION * diag_w.reshape(-1, 2), bodies=bodies)


def dense_solution(p, state, mu):
    """The states' system of the impulses (open: 0; stick: u = -R P; slide: u_n = -R_n P_n,
    P_t = sigma mu P_n) solved densely by LAPACK: the velocity change M^-1 H^T P."""
    nc = state.size
    big_h, minv = p["big_h"], p["minv"]
    w = big_h @ (minv[:, None] * big_h.T)
    a = w + np.diag(p["compliance"].reshape(-1))
    rhs = -big_h @ p["v_free"].reshape(-1)
    for c in range(nc):
        n, t = 2 * c, 2 * c + 1
        if state[c] <= 0:
            for r in (n, t):
                a[r, :] = 0.0
                a[:, r] = 0.0
                a[r, r] = 1.0
                rhs[r] = 0.0
        elif state[c] >= 2:
            a[t, :] = 0.0
            a[t, t] = 1.0
            a[t, n] = -mu[c] if state[c] == 2 else mu[c]
            rhs[t] = 0.0
    impulses = np.linalg.solve(a, rhs)
    return (minv * (big_h.T @ impulses)).reshape(-1, 3), impulses.reshape(-1, 2)


def test_a_block_at_rest_carries_its_weight():
    """A block on the ground, both ends sticking: the impulses cancel the free velocity, the
    normal ones sum to the weight's impulse m g h and the tangential ones to none (no ground
    acceleration); by symmetry each end carries half."""
    p = problem(rectangular_block(0.4, 2.0))
    nc = p["cb"].shape[0]
    state = np.ones(nc, dtype=np.int64)
    mu = np.full(nc, 0.6)
    impulse, dv, refinements, berr = solve_states(
        p["v_free"], p["inv_mass"], p["cb"], p["jac"], state, mu, p["compliance"],
        np.zeros(1, dtype=np.int64), 2)
    weight = p["bodies"][0, 0] * GRAVITY * 1e-3
    assert refinements >= 0 and berr < 1e-15
    assert impulse[:, 0].sum() == pytest.approx(weight, rel=1e-8)  # the compliance: 1e-9
    assert impulse[:, 0] == pytest.approx([weight / 2, weight / 2], rel=1e-8)
    assert np.abs(impulse[:, 1]).max() < 1e-12 * weight
    assert np.abs(p["v_free"] + dv).max() < 1e-9 * GRAVITY * 1e-3


@pytest.mark.parametrize("slide", [False, True])
def test_a_wall_matches_a_dense_solve(slide):
    """A wall of 3 courses of 4 blocks under 0.3 g, every contact sticking (or every fourth
    sliding, another open): the velocity changes equal LAPACK's dense solve of the impulses'
    system to round-off, the impulses to the compliance's resolution."""
    p = problem(from_block_assembly(geometry_wall(3, 4, 0.4, 0.2, friction=0.6)),
                ag=0.3 * GRAVITY)
    nc = p["cb"].shape[0]
    state = np.ones(nc, dtype=np.int64)
    if slide:
        state[::4] = 2
        state[1::7] = 0
    mu = np.full(nc, 0.6)
    position = np.arange(p["nb"])
    cb = p["cb"][(p["cb"] >= 0).all(axis=1)]
    kb = 3 * int(np.abs(cb[:, 0] - cb[:, 1]).max()) + 2
    impulse, dv, refinements, berr = solve_states(
        p["v_free"], p["inv_mass"], p["cb"], p["jac"], state, mu, p["compliance"], position, kb)
    dv_dense, impulse_dense = dense_solution(p, state, mu)
    assert 0 <= refinements <= 5 and berr < 1e-14
    assert np.abs(dv - dv_dense).max() < 1e-13 * np.abs(dv_dense).max()
    assert np.abs(impulse - impulse_dense).max() < 1e-5 * np.abs(impulse_dense).max()
    if slide:
        assert impulse[::4, 1] == pytest.approx(0.6 * impulse[::4, 0], rel=1e-14)
        assert np.all(impulse[1::7][state[1::7] == 0] == 0.0)


def band_problem(cb, nb):
    """The work arrays of the band solver of the impulses (the driver's)."""
    nc = cb.shape[0]
    pointer, incident, half = incidence(cb, nb)
    kl = 2 * half + 1
    return (np.zeros(nc, dtype=np.int64), np.zeros(nc, dtype=np.int64), pointer, incident, kl,
            np.zeros((2 * nc, kl + 1)), np.zeros((2 * nc, 3 * kl + 1)), np.zeros(2 * nc),
            np.zeros(2 * nc), np.zeros(2 * nc), np.zeros((nc, 12)))


@pytest.mark.parametrize("ag", [0.3, 0.5])
def test_the_active_set_method_in_the_blocks_velocities_equals_the_band_solvers(ag):
    """A wall's first step under a ground acceleration (contacts open, stick and slide: the head
    joints carry little normal force): the active-set method with its systems in the blocks'
    velocities ends on the states of the band solver of the impulses, with the same velocities
    to round-off and the same impulses to the compliance's resolution."""
    p = problem(from_block_assembly(geometry_wall(4, 6, 0.4, 0.2, friction=0.6)),
                ag=ag * GRAVITY)
    cb, nb = p["cb"], p["nb"]
    nc = cb.shape[0]
    inv_mass = np.column_stack([p["inv_mass"], np.sqrt(p["inv_mass"])])
    mu = np.full(nc, 0.6)
    active = np.ones(nc, dtype=bool)
    p_tol = 1e-12 * p["bodies"][:, 0].mean() * GRAVITY * 1e-3
    u_tol = SWITCH_VELOCITY * GRAVITY * 1e-3
    results = []
    for blocks in (False, True):
        v, impulse = p["v_free"].copy(), np.zeros((nc, 2))
        state = -np.ones(nc, dtype=np.int64)
        if blocks:
            position, kb = block_band(cb, nb)
            solves, converged = solve_active_set_blocks(
                v, inv_mass, cb, p["jac"], active, impulse, state, mu, p_tol, u_tol, position,
                kb, 60)
        else:
            solves, converged = solve_active_set(v, inv_mass, cb, p["jac"], active, impulse,
                                                 state, mu, p_tol, u_tol,
                                                 band_problem(cb, nb), 60)
        assert converged
        results.append((v, impulse, state, solves))
    (v0, p0, s0, n0), (v1, p1, s1, n1) = results
    assert np.array_equal(s0, s1) and n0 == n1
    assert np.any(s0 == 0) and np.any(s0 == 1) and np.any(s0 >= 2)  # every state's rows
    assert np.abs(v1 - v0).max() < 1e-12 * np.abs(p["v_free"]).max()
    assert np.abs(p1 - p0).max() < 1e-5 * np.abs(p0).max()


def test_the_blocks_band_is_a_permutation_that_narrows_a_wall():
    """Reverse Cuthill-McKee renumbers a wall's blocks to a narrower band than the builder's
    course-by-course numbering; the half-bandwidth is 3 times the largest distance of two
    touching blocks' positions, plus 2; an arch keeps its own numbering."""
    wall = from_block_assembly(geometry_wall(10, 19, 0.4, 0.2, friction=0.6))
    cb = contact_arrays(wall)["contact_bodies"]
    position, kb = block_band(cb, wall.n_blocks)
    assert sorted(position) == list(range(wall.n_blocks))
    pairs = cb[(cb >= 0).all(axis=1)]
    assert kb == 3 * np.abs(position[pairs[:, 0]] - position[pairs[:, 1]]).max() + 2
    natural = 3 * np.abs(pairs[:, 0] - pairs[:, 1]).max() + 2
    assert kb < natural
    arch = from_arch(oppenheim())
    position, kb = block_band(contact_arrays(arch)["contact_bodies"], arch.n_blocks)
    assert list(position) == list(range(arch.n_blocks)) and kb == 5


def test_a_wall_moves_alike_in_either_unknowns_and_an_arch_keeps_the_impulses():
    """A wall of 4 courses of 12 blocks under a sine pulse of 0.7 g, 0.5 s (its bed joints slide
    and its blocks rock): the same motion to round-off whether the contact problems are solved
    in the impulses or in the blocks' velocities (``BlockSettings.unknowns``), the choice
    ``auto`` takes the velocities; an arch keeps the impulses."""
    wall = from_block_assembly(geometry_wall(4, 12, 0.4, 0.2, friction=0.6))
    motion = sine_pulse(0.7 * GRAVITY, 0.5)
    runs = [simulate_blocks(wall, motion, BlockSettings(friction=0.6, unknowns=unknowns),
                            t_end=0.2, record_every=10)
            for unknowns in ("impulses", "velocities")]
    a, b = runs
    assert a.outcome.steps == b.outcome.steps
    # where the switching tests cycle (2 steps here) the augmented states settle them (in the
    # velocities); in the impulses Lemke's algorithm solves them
    assert a.outcome.fallback_steps == 2 and b.outcome.fallback_steps == 0
    moved = np.abs(a.displacements[-1]).max()
    assert moved > 1e-4  # it moved
    assert np.abs(a.displacements - b.displacements).max() < 1e-9 * moved
    assert np.abs(a.rotations - b.rotations).max() < 1e-9 * moved / 0.2  # blocks 0.2 m high
    assert contact_unknowns(wall)[0].size == wall.n_blocks
    assert contact_unknowns(from_arch(oppenheim()))[0].size == 0


def test_the_unknowns_are_named():
    with pytest.raises(ValueError, match="unknowns must be one of auto, impulses, velocities"):
        BlockSettings(unknowns="blocks")


def test_where_the_switching_tests_cycle_the_augmented_states_end_on_coulombs_law():
    """The first step of a three-span bridge of two staggered rings under fill, at rest (the
    benchmark's, ``benchmarks/bridge.py``): the switching tests cycle through the first phase's
    60 solves, and the second phase (the augmented Lagrangian's states) ends on states that
    the tests accept; its impulses and velocities obey the contact law contact by contact:
    no pull, friction inside its cone, an open contact not closing, a sticking one still to
    the compliance, a sliding one moving against its friction."""
    ring = multi_ring(5.0, math.pi, 0.6, rings=2, voussoirs=8, bond="staggered",
                      arc_error=0.5, ring_friction=0.6)
    bridge = from_block_assembly(multi_span(ring, 3, end_piers=(Pier(1.5, 4.0, 3),) * 2,
                                            middle_pier=Pier(2.0, 4.0, 3),
                                            fill=Fill(0.5, 1800.0)))
    h = 1e-3
    p = problem(bridge, h=h)
    cb, nb, jac = p["cb"], p["nb"], p["jac"]
    nc = cb.shape[0]
    mu = contact_arrays(bridge)["contacts"][:, FRICTION].copy()
    mu[np.isnan(mu)] = 0.6
    inv_mass = np.column_stack([p["inv_mass"], np.sqrt(p["inv_mass"])])
    position, kb = block_band(cb, nb)
    p_tol = 1e-12 * p["bodies"][:, 0].mean() * GRAVITY * h
    u_tol = SWITCH_VELOCITY * GRAVITY * h
    v, impulse = p["v_free"].copy(), np.zeros((nc, 2))
    state = -np.ones(nc, dtype=np.int64)
    solves, converged = solve_active_set_blocks(v, inv_mass, cb, jac, np.ones(nc, bool),
                                                impulse, state, mu, p_tol, u_tol, position,
                                                kb, 60)
    assert converged and 60 < solves <= 60 + AUGMENTED_SOLVES
    u = np.array([relative_velocity(v, cb[c, 0], cb[c, 1], jac, c) for c in range(nc)])
    pn, pt = impulse[:, 0], impulse[:, 1]
    scale = p["bodies"][:, 0].max() * GRAVITY * h
    assert np.all(pn >= -p_tol)
    assert np.all(np.abs(pt) <= mu * pn + p_tol)
    assert np.all(u[state == 0, 0] >= -u_tol)
    held = state == 1
    assert np.abs(u[held]).max() < 1e-6 * GRAVITY * h  # the compliance's velocities
    sliding = state >= 2
    assert np.all(np.sign(pt[sliding]) * u[sliding, 1] <= u_tol)
    assert np.all(np.isin(state, (0, 1, 2, 3))) and impulse[:, 0].max() > scale * 1e-3
