r"""The linear systems of the contact problem solved in the blocks' velocities: 3 unknowns a
block instead of 2 a contact, for walls, whose impulses outnumber the blocks' velocities.

With the rows ``H_s`` that the states of the active-set method hold (normal and tangential of a
sticking contact, normal of a sliding one), the directions ``H_g`` of their impulses (the
normal plus :math:`\sigma\mu` times the tangent for a sliding contact) and the compliance
``R`` (diagonal: :data:`~.contact_problem.REGULARISATION` times the diagonal of ``W``), the
system of the impulses :math:`(H_s M^{-1} H_g^T + R)\,p = r` is, by the Sherman-Morrison-Woodbury
identity [1]_,

.. math::

    K\,\Delta v = H_g^T R^{-1} r, \qquad K = M + H_g^T R^{-1} H_s, \qquad
    p = R^{-1} (r - H_s \Delta v),

a band system of ``3 nb`` unknowns (the blocks renumbered to narrow it). The difference
:math:`r - H_s \Delta v` cancels to the compliance, so that ``p`` is first good to about
:math:`\epsilon / \rho` relative only; it is refined iteratively [2]_ on the residual of the
impulses' own system, computed from ``H`` and ``M`` (no Delassus matrix), until the
componentwise backward error no longer halves (LAPACK's rule, ``xGERFS``). Measured on a wall of
195 blocks (``benchmarks/rigid_block_wall_block_space.py``): two refinements, after which the
velocity changes agree with the band solver's to 1e-13 and the impulses to 2e-7, as closely as
LAPACK's dense solve agrees with it (the statically indeterminate part of the impulses is fixed
only by the compliance and known to :math:`\epsilon / \rho` by any solver).

The driver takes this path where it needs fewer operations than the impulses' band
(:func:`~archquake.rigid_blocks.dynamics.contact_unknowns`): :func:`solve_active_set_blocks` is
the active-set method of :func:`~.contact_problem.solve_active_set` (the same states, tests and
compliance) with each system solved by :func:`solve_states`; the blocks are numbered by
:func:`block_band`. On the 195-block wall under a 0.3 g pulse a whole analysis runs 5.4 times
faster (``benchmarks/rigid_block_wall.py --all``).

References
----------
.. [1] G. H. Golub, C. F. Van Loan, "Matrix computations", 4th ed., Johns Hopkins (2013),
   Sect. 2.1.4 (the Sherman-Morrison-Woodbury formula), Sect. 4.3 (band elimination).
.. [2] N. J. Higham, "Accuracy and stability of numerical algorithms", 2nd ed., SIAM (2002),
   Ch. 12 (iterative refinement in fixed precision).
"""

from __future__ import annotations

import numba
import numpy as np

from .band import copy_1d, copy_2d
from .contact_problem import REGULARISATION, SINGLE_SWITCH_AFTER, switched_state
from .contacts import delassus_block, relative_velocity

REFINEMENTS = 5
"""Largest number of refinements of a solve [-] (LAPACK's ``ITMAX``)."""

AUGMENTED_SOLVES = 30
"""Largest number of linear solves [-] of the second phase of :func:`solve_active_set_blocks`,
whose states are those of the augmented Lagrangian, after the first phase's ``max_solves``
(none if ``max_solves`` is 0: Lemke's algorithm at every step)."""


@numba.njit(cache=True)
def _lu_factor(ab, n, kl):
    """Gaussian elimination without pivoting of the band ``ab`` (``A[i, j]`` at
    ``ab[i, j - i + kl]``, ``2 kl + 1`` columns), in place: ``L``'s multipliers below, ``U``
    above, ``1 / U_kk`` on the diagonal. False at a pivot that is not larger than 1e-14 times
    the row's diagonal before the elimination. Unsigned indices, as in
    :func:`~.band.band_lu_solve` (numba then vectorises the updates)."""
    scale = np.empty(n)
    for k in range(n):
        scale[k] = abs(ab[k, kl])
    ukl = np.uint64(kl)
    for k in range(n):
        uk = np.uint64(k)
        pivot = ab[uk, ukl]
        if not abs(pivot) > 1e-14 * scale[uk]:
            return False
        inverse = 1.0 / pivot
        ab[uk, ukl] = inverse
        for s in range(1, min(kl, n - 1 - k) + 1):
            us = np.uint64(s)
            ui = uk + us
            f = ab[ui, ukl - us] * inverse
            ab[ui, ukl - us] = f
            if f != 0.0:
                for t in range(1, kl + 1):
                    ut = np.uint64(t)
                    ab[ui, ukl - us + ut] -= f * ab[uk, ukl + ut]
    return True


@numba.njit(cache=True)
def _lu_substitute(ab, b, n, kl):
    """Solve with the factors of :func:`_lu_factor`, ``b`` overwritten by ``x``."""
    for k in range(n):
        for s in range(1, min(kl, n - 1 - k) + 1):
            b[k + s] -= ab[k + s, kl - s] * b[k]
    for k in range(n - 1, -1, -1):
        x = b[k]
        for t in range(1, min(kl, n - 1 - k) + 1):
            x -= ab[k, kl + t] * b[k + t]
        b[k] = x * ab[k, kl]


@numba.njit(cache=True)
def _rows(jac, c, state, mu, srow, grow, u):
    """Write the rows held (``srow``) and the impulses' directions (``grow``; 12 entries: body
    a, body b) of the unknowns of contact ``c`` in its ``state`` from row ``u`` on; returns
    their number (2 for a sticking contact, 1 for a sliding one)."""
    if state == 1:
        for k in range(2):
            for j in range(3):
                srow[u + k, j] = grow[u + k, j] = jac[c, 3 * k + j]
                srow[u + k, 6 + j] = grow[u + k, 6 + j] = jac[c, 6 + 3 * k + j]
        return 2
    sigma = mu[c] if state == 2 else -mu[c]
    for j in range(3):
        srow[u, j] = jac[c, j]
        srow[u, 6 + j] = jac[c, 6 + j]
        grow[u, j] = jac[c, j] + sigma * jac[c, 3 + j]
        grow[u, 6 + j] = jac[c, 6 + j] + sigma * jac[c, 9 + j]
    return 1


@numba.njit(cache=True)
def solve_states(v_free, inv_mass, contact_bodies, jac, state, mu, compliance, position, kb):
    r"""Impulses and velocity changes of the active-set system of given states, in the blocks'
    velocities (module docstring).

    Parameters
    ----------
    v_free : array (nb, 3)
        Free velocities [m/s, m/s, rad/s].
    inv_mass : array (nb, >= 2)
        Inverse masses [m/kg] and inertias [1/(kg m)].
    contact_bodies : array of int (nc, 2)
        Bodies of every contact (-1: the ground).
    jac : array (nc, 12)
        Jacobian rows (:func:`~.contacts.contact_geometry`).
    state : array of int (nc,)
        -1 inactive, 0 open, 1 stick, 2 and 3 slide with ``P_t = +mu P_n`` and ``-mu P_n``.
    mu : array (nc,)
        Friction coefficients [-].
    compliance : array (nc, 2)
        The compliance of the normal and tangential rows of every contact [m/kg].
    position : array of int (nb,)
        Position of every block in the band of ``K`` [-].
    kb : int
        Half-bandwidth of ``K``: 3 times the largest distance of two touching blocks' positions,
        plus 2 [-].

    Returns
    -------
    impulse : array (nc, 2)
        ``(P_n, P_t)`` [N s/m].
    dv : array (nb, 3)
        :math:`M^{-1} H^T P` [m/s, m/s, rad/s].
    refinements : int
        Refinements made; -1 if ``K`` had a small pivot (nothing solved).
    backward_error : float
        The last componentwise backward error of the impulses' system [-].
    """
    nb, nc = v_free.shape[0], contact_bodies.shape[0]
    n = 3 * nb
    ab = np.zeros((n, 2 * kb + 1))
    for i in range(nb):
        for j in range(3):
            ab[3 * position[i] + j, kb] = 1.0 / inv_mass[i, 0 if j < 2 else 1]
    # the unknowns: contact, its rows and directions, compliance and right-hand side
    count = 0
    for c in range(nc):
        count += 2 if state[c] == 1 else (1 if state[c] >= 2 else 0)
    owner = np.zeros(count, dtype=np.int64)
    srow = np.zeros((count, 12))
    grow = np.zeros((count, 12))
    rd = np.zeros(count)
    r = np.zeros(count)
    u = 0
    for c in range(nc):
        if state[c] <= 0:
            continue
        k = _rows(jac, c, state[c], mu, srow, grow, u)
        for e in range(k):
            owner[u] = c
            rd[u] = compliance[c, e]
            for side in range(2):
                body = contact_bodies[c, side]
                if body >= 0:
                    for j in range(3):
                        r[u] -= srow[u, 6 * side + j] * v_free[body, j]
            u += 1
    for e in range(count):  # K += g^T s / rd, block by block
        c = owner[e]
        for sa in range(2):
            ba = contact_bodies[c, sa]
            if ba < 0:
                continue
            for sb in range(2):
                bb = contact_bodies[c, sb]
                if bb < 0:
                    continue
                for ja in range(3):
                    row = 3 * position[ba] + ja
                    ga = grow[e, 6 * sa + ja] / rd[e]
                    for jb in range(3):
                        col = 3 * position[bb] + jb
                        ab[row, col - row + kb] += ga * srow[e, 6 * sb + jb]
    if not _lu_factor(ab, n, kb):
        return np.zeros((nc, 2)), np.zeros((nb, 3)), -1, np.inf
    p = np.zeros(count)
    rhs = r.copy()
    last = np.inf
    berr = np.inf
    refinements = -1
    y = np.zeros((nb, 3))
    ya = np.zeros((nb, 3))
    dv = np.zeros(n)
    while True:
        # the Woodbury solve of the right-hand side rhs: p += R^-1 (rhs - H_s K^-1 H_g^T R^-1 rhs)
        dv[:] = 0.0
        for e in range(count):
            c = owner[e]
            for side in range(2):
                body = contact_bodies[c, side]
                if body >= 0:
                    for j in range(3):
                        dv[3 * position[body] + j] += grow[e, 6 * side + j] * rhs[e] / rd[e]
        _lu_substitute(ab, dv, n, kb)
        for e in range(count):
            c = owner[e]
            hs = 0.0
            for side in range(2):
                body = contact_bodies[c, side]
                if body >= 0:
                    for j in range(3):
                        hs += srow[e, 6 * side + j] * dv[3 * position[body] + j]
            p[e] += (rhs[e] - hs) / rd[e]
        refinements += 1
        # the residual of the impulses' system and its backward error
        y[:] = 0.0
        ya[:] = 0.0
        for e in range(count):
            c = owner[e]
            for side in range(2):
                body = contact_bodies[c, side]
                if body >= 0:
                    for j in range(3):
                        w = inv_mass[body, 0 if j < 2 else 1]
                        y[body, j] += w * grow[e, 6 * side + j] * p[e]
                        ya[body, j] += w * abs(grow[e, 6 * side + j] * p[e])
        berr = 0.0
        for e in range(count):
            c = owner[e]
            ap = rd[e] * p[e]
            size = abs(r[e]) + abs(ap)
            for side in range(2):
                body = contact_bodies[c, side]
                if body >= 0:
                    for j in range(3):
                        ap += srow[e, 6 * side + j] * y[body, j]
                        size += abs(srow[e, 6 * side + j]) * ya[body, j]
            rhs[e] = r[e] - ap
            if size > 0.0:
                berr = max(berr, abs(rhs[e]) / size)
        if not (berr > 2.2e-16 and 2.0 * berr <= last and refinements < REFINEMENTS):
            break
        last = berr
    impulse = np.zeros((nc, 2))
    for e in range(count):
        c = owner[e]
        if state[c] == 1:
            impulse[c, 0 if e == 0 or owner[e - 1] != c else 1] = p[e]
        else:
            impulse[c, 0] = p[e]
            impulse[c, 1] = (mu[c] if state[c] == 2 else -mu[c]) * p[e]
    return impulse, y, refinements, berr


@numba.njit(cache=True)
def solve_active_set_blocks(v, inv_mass, contact_bodies, jac, active, impulse, state, mu, p_tol,
                            u_tol, position, kb, max_solves):
    r"""The contact problem of a step by the active-set method of
    :func:`~.contact_problem.solve_active_set`, each system of its states solved in the blocks'
    velocities (:func:`solve_states`); ``v`` enters free.

    The same states, switching tests (:func:`~.contact_problem.switched_state`), compliance
    (:data:`~.contact_problem.REGULARISATION` times the diagonal of ``W``) and rule of one switch
    a solve after :data:`~.contact_problem.SINGLE_SWITCH_AFTER` solves; the velocities of the
    tests are those of the blocks after the solve, :math:`H (v^f + \Delta v)`, which are
    :math:`u^f + W P` without assembling ``W``. On convergence the impulses are written to
    ``impulse`` and ``v`` is the velocity at the end of the step; otherwise (``max_solves``
    solves, or a small pivot of ``K``) ``v`` and ``impulse`` are unchanged and the states are the
    last ones tried, for the caller's fallback (Lemke's algorithm on the assembled problem).

    Where the switching tests have not settled after ``max_solves`` solves, a second phase of
    up to :data:`AUGMENTED_SOLVES` solves starts again from the step's first states and takes
    every contact's next state from Alart and Curnier's augmented Lagrangian [4]_ instead
    (:func:`_augmented_state`: open, stick or slide by the signs of :math:`P - r u`, with ``r``
    the inverse of the contact's diagonal of ``W``), all at once; it ends, as the first phase,
    only on states that the switching tests accept, so that the answer is the same kind of
    solution (its impulses exact to round-off for its states). Measured: at the first step of
    the three-span bridge of two rings under fill (``benchmarks/bridge.py``) the switching tests
    cycle through their 60 solves and the augmented states settle in 7 more; over the first
    0.05 s of its pulse 7 of 61 steps are left to Lemke's algorithm (14 in the impulses, which
    have no second phase), over the first 0.15 s 102 of 181, every one because the augmented
    states cycle (none at a fixed point that the tests contradict): 150 solves of the second
    phase instead of :data:`AUGMENTED_SOLVES` leave the same 102, and a line search on the
    residual of the augmented equations (the step halved down to 1e-3) 96; on a 48-block
    wall sliding under 0.7 g, none of 548 steps (2 in the impulses), the same motion to 1e-9
    (``tests/rigid_blocks/test_block_space.py``).

    Two ways around Lemke's algorithm that the bridge rules out (measured, not kept): the
    cycling is not local, since in the bridge's failing steps 139 of the 153 active contacts
    change state (130 more than twice), so a small complementarity problem of the contacts that
    cycle, the others held, would be nearly the whole one; and states read from projected
    Gauss-Seidel's impulses (:func:`~.contact_problem.solve_contacts`, 25 to 3,200 sweeps, then
    four solves of the switching tests) leave 20-60 contacts contradicted, since Gauss-Seidel
    approaches a solution of the problem without compliance, one of many in a statically
    indeterminate structure, not the regularised one whose states the tests check.

    References
    ----------
    .. [4] P. Alart, A. Curnier, "A mixed formulation for frictional contact problems prone to
       Newton like solution methods", Comput. Methods Appl. Mech. Engrg. 92 (1991) 353-375.

    Parameters
    ----------
    v, inv_mass, contact_bodies, jac, active, impulse, state, mu, p_tol, u_tol
        As for :func:`~.contact_problem.solve_active_set`.
    position : array of int (nb,)
        Position of every block in the band of ``K`` [-] (:func:`solve_states`).
    kb : int
        Half-bandwidth of ``K`` [-] (:func:`solve_states`).
    max_solves : int
        Largest number of linear solves [-].

    Returns
    -------
    solves : int
        Linear solves made (0 if no contact is active).
    converged : bool
        Whether a consistent set of states was found.
    """
    nc = contact_bodies.shape[0]
    compliance = np.zeros((nc, 2))
    m = 0
    for c in range(nc):
        if active[c]:
            m += 1
            if state[c] < 0:  # newly active: guess that it sticks
                state[c] = 1
            wnn, _, wtt = delassus_block(inv_mass, contact_bodies[c, 0], contact_bodies[c, 1],
                                         jac, c)
            compliance[c, 0] = REGULARISATION * wnn
            compliance[c, 1] = REGULARISATION * wtt
        else:
            state[c] = -1
            impulse[c, 0] = 0.0
            impulse[c, 1] = 0.0
    if m == 0:
        return 0, True
    solves = 0
    after = np.empty_like(v)
    initial = state.copy()
    augmented = False  # the second phase: the states of the augmented Lagrangian
    limit = max_solves + (AUGMENTED_SOLVES if max_solves > 0 else 0)
    while solves < limit:
        p, dv, refinements, _ = solve_states(v, inv_mass, contact_bodies, jac, state, mu,
                                             compliance, position, kb)
        if refinements < 0:  # a small pivot of K
            return solves, False
        solves += 1
        for i in range(v.shape[0]):
            for j in range(3):
                after[i, j] = v[i, j] + dv[i, j]
        changed = contradicted = False
        for c in range(nc):
            st = state[c]
            if st < 0:
                continue
            un, ut = relative_velocity(after, contact_bodies[c, 0], contact_bodies[c, 1], jac, c)
            u = 0.0 if st == 1 else (un if st == 0 else ut)
            new = switched_state(st, p[c, 0], p[c, 1], mu[c], p_tol, u_tol, u)
            contradicted = contradicted or new != st
            if augmented:
                new = _augmented_state(p[c, 0], p[c, 1], un, ut, compliance[c, 0],
                                       compliance[c, 1], mu[c])
            if new != st and not (changed and solves > SINGLE_SWITCH_AFTER and not augmented):
                state[c] = new
                changed = True
        if not contradicted:
            copy_2d(v, after)
            copy_2d(impulse, p)
            return solves, True
        if augmented and not changed:  # a fixed point of the augmented states that the
            return solves, False       # tests contradict: Lemke's algorithm decides
        if not augmented and solves >= max_solves:  # the second phase, from the first
            augmented = True                         # states
            copy_1d(state, initial)
    return solves, False


@numba.njit(cache=True)
def _augmented_state(pn, pt, un, ut, compliance_n, compliance_t, mu):
    r"""The state of a contact in Alart and Curnier's augmented Lagrangian
    (:func:`solve_active_set_blocks`): with
    :math:`r = 1 / W_{cc}` (``REGULARISATION / compliance``), open if
    :math:`\sigma_n = P_n - r_n u_n \le 0`, else stick if
    :math:`|\sigma_t| = |P_t - r_t u_t| \le \mu \sigma_n`, else slide in the direction of
    :math:`\sigma_t`."""
    sn = pn - REGULARISATION / compliance_n * un
    if not sn > 0.0:
        return 0
    st = pt - REGULARISATION / compliance_t * ut
    if abs(st) <= mu * sn:
        return 1
    return 2 if st > 0.0 else 3


def block_band(contact_bodies: np.ndarray, nb: int) -> tuple[np.ndarray, int]:
    """The blocks' positions in the band of ``K`` (:func:`solve_states`), renumbered by reverse
    Cuthill-McKee [3]_ where that narrows the band, and its half-bandwidth.

    Parameters
    ----------
    contact_bodies : array of int (nc, 2)
        Bodies of every contact (-1: the ground).
    nb : int
        Number of blocks.

    Returns
    -------
    position : array of int (nb,)
        Position of every block [-].
    kb : int
        Half-bandwidth of ``K``: 3 times the largest distance of two touching blocks'
        positions, plus 2 [-].

    References
    ----------
    .. [3] A. George, J. W. H. Liu, "Computer solution of large sparse positive definite
       systems", Prentice-Hall (1981), Sec. 4.3.
    """
    from scipy.sparse import csr_matrix
    from scipy.sparse.csgraph import reverse_cuthill_mckee

    pairs = contact_bodies[(contact_bodies >= 0).all(axis=1)]

    def half(position):
        if pairs.size == 0:
            return 2
        return 3 * int(np.abs(position[pairs[:, 0]] - position[pairs[:, 1]]).max()) + 2

    natural = np.arange(nb, dtype=np.int64)
    graph = csr_matrix((np.ones(2 * len(pairs)),
                        (np.r_[pairs[:, 0], pairs[:, 1]], np.r_[pairs[:, 1], pairs[:, 0]])),
                       shape=(nb, nb))
    order = np.asarray(reverse_cuthill_mckee(graph, symmetric_mode=True), dtype=np.int64)
    renumbered = np.empty(nb, dtype=np.int64)
    renumbered[order] = natural
    best = renumbered if half(renumbered) < half(natural) else natural
    return best, half(best)

