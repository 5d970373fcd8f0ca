"""The contact problem that is always solved: Lemke's algorithm on the LCP of Coulomb's law,
checked against the definition of the problem, against the exact one-contact solution, and
against the active-set method where both converge; arches of many voussoirs decided."""

import math

import numpy as np
import pytest

from archquake.geometry import circular_arch
from archquake.ground_motion import oppenheim_pulse
from archquake.rigid_blocks import BlockSettings, block_outcome, from_arch
from archquake.rigid_blocks.contact_problem import local_coulomb
from archquake.rigid_blocks.dynamics import simulate_blocks
from archquake.rigid_blocks.lemke import (
    LEMKE_COMPLIANCE,
    LEMKE_SOLVED,
    contact_lcp,
    lemke,
    solve_contact_lcp,
)

G = 9.81


def contact_problem(rng, contacts: int, dofs: int):
    """A Delassus matrix ``H M^-1 H^T`` of ``contacts`` contacts on ``dofs`` degrees of freedom
    (rank-deficient, as an arch's, when ``2 contacts > dofs``) and free velocities [m/s]."""
    jac = rng.normal(size=(2 * contacts, dofs))
    inv_mass = rng.uniform(0.5, 2.0, size=dofs) * 1e-3
    return jac @ np.diag(inv_mass) @ jac.T, rng.normal(size=2 * contacts)


def coulomb_violation(w, uf, mu, impulses, compliance=LEMKE_COMPLIANCE):
    """The largest violation of the contact law by ``impulses`` [-], relative to the scale of
    the velocities and impulses: non-penetration, complementarity, the cone, and the slip's
    direction (of a contact that slides faster than round-off)."""
    u = uf + w @ impulses + compliance * np.diag(w) * impulses
    un, ut, pn, pt = u[0::2], u[1::2], impulses[0::2], impulses[1::2]
    su = np.abs(uf).max()
    sp = max(np.abs(impulses).max(), 1e-300)
    out = [max(0.0, -un.min()) / su, max(0.0, -pn.min()) / sp,
           np.abs(un * pn).max() / (su * sp), max(0.0, (np.abs(pt) - mu * pn).max()) / sp]
    sliding = np.abs(ut) > 1e-3 * su  # beyond what the compliance can leave a sticking one
    if sliding.any():
        out.append(np.abs(pt[sliding] + mu * pn[sliding] * np.sign(ut[sliding])).max() / sp)
    return max(out)


@pytest.mark.parametrize("seed", range(40))
def test_lemke_solves_the_lcp(seed):
    """w = q + M z >= 0, z >= 0, w . z = 0 for the contact LCP of a random (rank-deficient)
    Delassus matrix, checked on the LCP as stated."""
    rng = np.random.default_rng(seed)
    contacts = int(rng.integers(1, 25))
    w, uf = contact_problem(rng, contacts, int(rng.integers(contacts, 2 * contacts + 3)))
    mat, q, _ = contact_lcp(w, uf, np.full(contacts, rng.uniform(0.0, 1.2)), LEMKE_COMPLIANCE)
    z, code, _ = lemke(mat, q, np.ones(q.size))
    assert code == LEMKE_SOLVED
    slack = q + mat @ z
    scale = np.abs(q).max()
    assert z.min() >= 0.0
    assert slack.min() >= -1e-9 * scale
    assert np.abs(z * slack).max() <= 1e-9 * scale * max(z.max(), 1.0)


@pytest.mark.parametrize("seed", range(40))
def test_lemke_satisfies_coulomb_law(seed):
    """The impulses of solve_contact_lcp obey the contact law with friction, and the states it
    returns are those the impulses show."""
    rng = np.random.default_rng(100 + seed)
    contacts = int(rng.integers(1, 30))
    w, uf = contact_problem(rng, contacts, int(rng.integers(contacts, 2 * contacts + 3)))
    mu = float(rng.uniform(0.0, 1.2))
    impulses = np.zeros(2 * contacts)
    states = np.zeros(contacts, dtype=np.int64)
    code, _ = solve_contact_lcp(w, uf, np.full(contacts, mu), LEMKE_COMPLIANCE, impulses,
                                states)
    assert code == LEMKE_SOLVED
    assert coulomb_violation(w, uf, mu, impulses) < 10 * LEMKE_COMPLIANCE  # to the compliance
    pn, pt = impulses[0::2], impulses[1::2]
    assert np.all(pn[states == 0] <= 1e-12 * max(pn.max(), 1e-300))
    # sliding on the cone, to the compliance of the slip rate
    atol = 1e-7 * np.abs(impulses).max()
    np.testing.assert_allclose(pt[states == 2], mu * pn[states == 2], rtol=1e-7, atol=atol)
    np.testing.assert_allclose(pt[states == 3], -mu * pn[states == 3], rtol=1e-7, atol=atol)


@pytest.mark.parametrize("ufn, uft, mu", [(-1.0, 0.2, 0.8), (-1.0, 3.0, 0.3), (-0.5, -4.0, 0.5),
                                          (0.7, 0.1, 0.8), (-1.0, 0.0, 0.0)])
def test_one_contact_is_the_exact_local_solution(ufn, uft, mu):
    """For one contact, Lemke's impulses are those of the closed-form local solution (stick,
    slide either way, separation)."""
    w = np.array([[2.0, 0.3], [0.3, 1.5]])
    impulses = np.zeros(2)
    code, _ = solve_contact_lcp(w, np.array([ufn, uft]), np.full(1, mu), 0.0, impulses,
                                np.zeros(1, dtype=np.int64))
    assert code == LEMKE_SOLVED
    exact = local_coulomb(ufn, uft, w[0, 0], w[0, 1], w[1, 1], mu)
    np.testing.assert_allclose(impulses, exact, rtol=1e-12, atol=1e-14)


def test_degenerate_problem_of_an_arch_does_not_end_on_a_ray():
    """Two contacts per joint make the Delassus matrix of an arch singular (4 impulses per
    joint, 3 relative motions): the problems on which Lemke's algorithm ended on a ray before its
    tableau was computed afresh from its basis, and before the slip rate carried the
    compliance."""
    rng = np.random.default_rng(7)
    for _ in range(20):
        w, uf = contact_problem(rng, 60, 70)
        impulses = np.zeros(120)
        code, _ = solve_contact_lcp(w, uf, np.full(60, 0.8), LEMKE_COMPLIANCE, impulses,
                                    np.zeros(60, dtype=np.int64))
        assert code == LEMKE_SOLVED
        assert coulomb_violation(w, uf, 0.8, impulses) < 10 * LEMKE_COMPLIANCE


@pytest.mark.parametrize("amplitude", [-0.4, -1.0])
def test_lemke_at_every_step_gives_the_active_set_motion(nominal, amplitude):
    """Where the active-set method converges, Lemke's algorithm at every step (its states
    solved again by the active-set method) gives the same motion to round-off: the same
    outcome, times and maxima, and the same trajectory (every step at h: a coarse step that the
    active-set method does not solve is taken again at h)."""
    motion = oppenheim_pulse(amplitude * G, 0.3)
    assembly = from_arch(nominal)
    fast, slow = (simulate_blocks(assembly, motion,
                                  BlockSettings(active_set_solves=n, coarse_factor=1),
                                  t_end=1.5, record_every=10) for n in (60, 0))
    assert slow.outcome.status == fast.outcome.status
    assert fast.outcome.fallback_steps == 0 and slow.outcome.fallback_steps > 0
    for name in ("max_rotation", "max_crown_drop", "max_opening"):
        assert getattr(slow.outcome, name) == pytest.approx(getattr(fast.outcome, name),
                                                            rel=1e-7, abs=1e-10)
    np.testing.assert_allclose(slow.rotations, fast.rotations, rtol=0, atol=1e-9)
    np.testing.assert_allclose(slow.displacements, fast.displacements, rtol=0, atol=1e-9)
    # the energy balance closes whichever method solved the steps
    balance = (slow.kinetic_energy + slow.potential_energy + slow.dissipated_energy
               - slow.input_work)
    assert np.ptp(balance) <= 1e-9 * np.abs(slow.potential_energy).max()


@pytest.mark.parametrize("voussoirs", [15, 20, 30])
def test_arch_of_many_voussoirs_is_decided(voussoirs):
    """Oppenheim's arch cut into 15-30 voussoirs under the pulse on which the active-set method
    cycled: decided, every step's contact problem solved, the energy balance closed."""
    arch = circular_arch(10.0, math.radians(157.5), 1.5, voussoirs)  # Oppenheim's arch
    outcome = block_outcome(arch, oppenheim_pulse(-1.0 * G, 0.27))
    assert outcome.decided and outcome.unconverged_steps == 0
    assert outcome.fallback_steps > 0  # the active-set method did cycle: Lemke decided


def test_active_set_solves_is_validated():
    with pytest.raises(ValueError, match="active_set_solves"):
        BlockSettings(active_set_solves=-1)
    with pytest.raises(ValueError, match="active_set_solves"):
        BlockSettings(active_set_solves=1.5)
    assert math.isfinite(BlockSettings(active_set_solves=0).active_set_solves)
