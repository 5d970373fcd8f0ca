r"""The contact problem of a time step: the impulses of the active contacts.

Everything here is ``numba``-compiled. The driver (:func:`archquake.rigid_blocks.solver.run`;
the law solved here is stated in that module's "Time stepping") calls :func:`solve_active_set`,
where it gives up :func:`solve_lemke`, and should that fail :func:`solve_contacts`. The
Delassus matrix is assembled here from the Jacobians of the contacts
(:mod:`archquake.rigid_blocks.contacts`) and its systems are solved by the band solvers of
:mod:`archquake.rigid_blocks.band`.

Contact problem
---------------
With the free velocity :math:`v^f = v_k + \mathbf{M}^{-1} \int f\,dt` (the step without contact
impulses), the local velocities of the active contacts are affine in their impulses, through
the Delassus matrix:

.. math::

    u = u^f + W P, \qquad u^f = H_k v^f, \qquad W = H_k \mathbf{M}^{-1} H_k^T.

It is solved exactly (to round-off) by a primal-dual active-set method,
:func:`solve_active_set`: guess the state of every contact (open, stick, slide either way; the
previous step's states), solve the linear system in the impulses that the states define, switch
the states that the solution contradicts, repeat (usually 1-2 solves; the normal rows of the
contacts that stick or slide and the tangential rows of the sticking ones carry a compliance of
:data:`REGULARISATION` times their diagonal, which picks the smallest of the statically
indeterminate impulses). Two contacts couple only through a block they both touch, so with the
contacts numbered joint by joint ``W`` is a band matrix (for an arch each joint couples with its
two neighbours: half-bandwidth 7 in the impulses, whatever the number of blocks; any other
assembly, a wall, has its joints renumbered by reverse Cuthill-McKee to narrow the band,
:func:`archquake.rigid_blocks.dynamics.joint_order`): it is
assembled block by block and solved in band storage, by Cholesky's factorisation when no
contact slides (the system is then symmetric positive definite), else by Gaussian elimination
(:func:`~.band.band_cholesky_solve`, :func:`~.band.band_lu_solve`, :func:`~.band.band_solve`):
a step costs time and memory linear in the number of blocks. Where the contacts outnumber the
blocks in a wide band (a wall), the same method solves each system in the blocks' velocities
instead (:func:`~archquake.rigid_blocks.block_space.solve_active_set_blocks`, chosen by
:func:`~archquake.rigid_blocks.dynamics.contact_unknowns`), and a step it gives up on is handed
to Lemke's algorithm on the assembled ``W`` as here.

The active-set method has no guarantee of convergence: its states can cycle (measured on
Oppenheim's arch cut into 50 voussoirs under its pulse: at 79 of 4,000 steps, at the onset of
the motion and at impacts, where tens of contacts change state at once; with one switch per
solve, in the manner of Murty's least-index rule, most of these still cycle after 2,000
solves). Where it gives up after :data:`ACTIVE_SET_SOLVES` solves, the step's problem is
solved by **Lemke's algorithm** (:func:`solve_lemke`, :mod:`archquake.rigid_blocks.lemke`),
which cannot cycle: in two dimensions Coulomb's law is exactly a linear complementarity problem
(Stewart and Trinkle's formulation, with the slip rate as an unknown), whose matrix, with a
compliance on ``W`` and on the slip rate (:data:`~archquake.rigid_blocks.lemke.LEMKE_COMPLIANCE`,
1e-5: a better conditioned tableau than at this module's 1e-9), is copositive-plus, and whose
problem is feasible; Lemke's algorithm with the lexicographic ratio test then ends on a solution
after finitely many pivots (Cottle, Pang and Stone, Thm. 4.4.13; the module's docstring). Its
solution's states are handed back to the active-set method, which solves the same states at
this module's compliance to round-off (so that both methods give the same impulses where both
converge); where it would switch them, Lemke's impulses are kept. The fallback costs a dense
tableau: 4 unknowns per active contact and about 1.3 pivots per unknown, 45 ms for the 74-98
active contacts of the 50-voussoir arch (``benchmarks/rigid_block_contact_solver.py``), paid
only at the steps where the active-set method gave up. The pivots per unknown are not bounded
by that figure: at the first step from rest of the bare three-span bridge of two rings
(``benchmarks/bridge.py``, ring friction 10, every contact newly active) Lemke's algorithm
took about 51,000 pivots, some 30 per unknown, and 51 s. Should Lemke's algorithm end without a
solution (never observed: a guard against round-off), projected Gauss-Seidel takes over [1]_
(Ch. 13), :func:`solve_contacts`: sweeps forward and backward in turn, each contact's problem solved
exactly by :func:`local_coulomb` with the others' impulses fixed,

.. math::

    P_c \leftarrow \operatorname{local}\bigl(u_c - W_{cc} P_c,\; W_{cc},\; \mu\bigr), \qquad
    v \leftarrow v + \mathbf{M}^{-1} H_c^T \Delta P_c,

stopping when :math:`\max_c (|\Delta P_{n,c}| + |\Delta P_{t,c}|) \le \mathrm{tol}\;\bar m g h`
(the impulse of a mean block's weight over a step, scaled) or after ``max_iterations`` sweeps
(counted as unconverged: the outcome is then undecided). Gauss-Seidel alone converges slowly on
an arch (the thrust runs through a chain of blocks and the friction split between the two ends
of a joint is indeterminate), and its residual velocities make a still arch creep; hence the
direct methods.

References
----------
.. [1] V. Acary, B. Brogliato, "Numerical methods for nonsmooth dynamical systems", Springer
   (2008), Ch. 12-13 (Gauss-Seidel for the contact problem).
"""

from __future__ import annotations

import math

import numba
import numpy as np

from .band import (
    ARCH_BANDWIDTH,
    arch_cholesky_solve,
    arch_lu_solve,
    band_cholesky_solve,
    band_lu_solve,
    band_solve,
    copy_1d,
    copy_2d,
)
from .contacts import apply_impulse, delassus_block, relative_velocity
from .lemke import LEMKE_COMPLIANCE, LEMKE_SOLVED, solve_contact_lcp

REGULARISATION = 1e-9
"""Compliance of the rows of the contact problem that hold a velocity to zero (the normal row of a
contact that sticks or slides, the tangential row of one that sticks), relative to their
diagonal [-]."""

SWITCH_VELOCITY = REGULARISATION
r"""Tolerance :math:`\epsilon_u` of the velocity tests of the active-set method
(:func:`solve_active_set`), relative to :math:`g h` [-] (the velocity a step's weight gives a
block, the scale of the free velocities of a structure at rest): the driver passes
``SWITCH_VELOCITY * g * h`` [m/s]. The velocities of a solve are exact only to the compliance: a
contact held at ``u = 0`` moves at :math:`\rho W_{cc} P_c` (:data:`REGULARISATION` times the
velocity its impulse cancels, about :math:`\rho\, g h` and more under a stack of blocks), and
every velocity computed from those impulses carries errors of that order. A tolerance below it
lets the residuals of the compliance decide states: with :math:`10^{-12}\, g h` a wall of 100
blocks at rest cycled at every step (a head joint, carrying no normal force, found closing at
:math:`u_n = -1.0 \times 10^{-14}` m/s when open, against a tolerance of
:math:`7.2 \times 10^{-15}` m/s, and pulling, :math:`P_n = -2.7 \times 10^{-3}` N s/m, when
held: 60 solves, then Lemke's algorithm). At :math:`\rho\, g h` (7 pm/s at h = 0.73 ms, a
penetration of 5e-15 m per step) only tests on velocities below the compliance's resolution
change."""

ACTIVE_SET_SOLVES = 60
"""Default largest number of linear solves of the active-set method in a step before Lemke's
algorithm takes over [-] (the setting ``active_set_solves``)."""

POLISH_SOLVES = 4
"""Largest number of linear solves of the active-set method from the states of Lemke's
solution [-] (:func:`solve_lemke`): one where they hold to its tolerances."""

SINGLE_SWITCH_AFTER = 10
"""After this many solves [-] the active-set method switches one contradicted state per solve (the
first one, in the manner of Murty's least-index rule) instead of all, which ends cycles."""


@numba.njit(cache=True, _nrt=False)
def local_coulomb(ufn, uft, wnn, wnt, wtt, mu):
    r"""Exact solution of one contact's problem: impulses ``(P_n, P_t)`` [N s/m].

    The local velocity is ``u = uf + W P`` (``uf`` without this contact's impulse, ``W`` its
    2 x 2 Delassus block); the law is ``0 <= u_n perp P_n >= 0`` with Coulomb friction. The cases
    are tried in turn:

    .. math::

        \text{separation:}\quad P = 0 \quad \text{if } u^f_n \ge 0,

        \text{stick:}\quad P = -W^{-1} u^f \quad \text{if } P_n \ge 0,\;
        |P_t| \le \mu P_n \quad (u = 0),

        \text{slide:}\quad P_t = \sigma \mu P_n, \quad
        P_n = \frac{-u^f_n}{W_{nn} + \sigma \mu W_{nt}} \quad
        \text{if } \sigma u_t \le 0 \quad (u_n = 0,\; \sigma = +1 \text{ then } -1),

    with :math:`u_t = u^f_t + (W_{nt} + \sigma \mu W_{tt}) P_n`; a sliding case whose
    denominator is not positive is skipped. Should none hold (not reached for a positive
    definite ``W`` and a moderate mu), a frictionless push :math:`P = (-u^f_n / W_{nn}, 0)` is
    returned.

    Parameters
    ----------
    ufn, uft : float
        Normal and tangential velocity without this contact's impulse [m/s].
    wnn, wnt, wtt : float
        Entries of the symmetric 2 x 2 Delassus block [m/kg], i.e. (m/s) per
        (N s/m).
    mu : float
        Friction coefficient [-], >= 0.

    Returns
    -------
    pn, pt : float
        Normal and tangential impulse [N s/m].
    """
    if ufn >= 0.0:
        return 0.0, 0.0
    det = wnn * wtt - wnt * wnt
    pn = (-ufn * wtt + uft * wnt) / det
    pt = (-uft * wnn + ufn * wnt) / det
    if pn >= 0.0 and abs(pt) <= mu * pn:
        return pn, pt
    for s in (1.0, -1.0):
        denominator = wnn + s * mu * wnt
        if denominator <= 0.0:
            continue
        pn = -ufn / denominator
        ut = uft + (wnt + s * mu * wtt) * pn
        if s * ut <= 0.0:
            return pn, s * mu * pn
    # not reached for a positive definite W and a moderate mu; fall back to a frictionless push
    return -ufn / wnn, 0.0


@numba.njit(cache=True, _nrt=False)
def solve_contacts(v, inv_mass, contact_bodies, jac, w, active, impulse, mu, tol_impulse,
                   max_iterations):
    r"""Projected Gauss-Seidel on the active contacts; ``v`` enters free and leaves corrected.

    The warm start ``impulse`` of the active contacts is applied first (the others are set to
    0); then every sweep visits the active contacts, forward on even sweeps and backward on odd
    ones, and replaces each one's impulse by the exact solution of its own problem with the
    others fixed [1]_:

    .. math::

        u^f_c = u_c(v) - W_{cc} P_c, \qquad
        P_c^{new} = \operatorname{local\_coulomb}(u^f_c, W_{cc}, \mu), \qquad
        v \leftarrow v + \mathbf{M}^{-1} H_c^T (P_c^{new} - P_c).

    It stops after the first sweep in which no impulse changed by more than ``tol_impulse``
    (measured as :math:`|\Delta P_n| + |\Delta P_t|`), or after ``max_iterations`` sweeps.

    Parameters
    ----------
    v : array (nb, 3)
        In: the free velocities; out: the velocities at the end of the step [m/s, m/s, rad/s].
    inv_mass : array (nb, >= 2)
        Inverse masses [m/kg] and inertias [1/(kg m)].
    contact_bodies : array of int (nc, 2)
        Bodies of every contact (-1: the ground).
    jac : array (nc, 12)
        Jacobian rows (:func:`~.contacts.contact_geometry`).
    w : array (nc, 3)
        Work space: the Delassus blocks ``(W_nn, W_nt, W_tt)`` of the active contacts [m/kg].
    active : array of bool (nc,)
        The active set.
    impulse : array (nc, 2)
        In: the warm start; out: the impulses ``(P_n, P_t)`` [N s/m].
    mu : array (nc,)
        Friction coefficient of every contact [-].
    tol_impulse : float
        Largest change of an impulse in the last sweep [N s/m].
    max_iterations : int
        Largest number of sweeps.

    Returns
    -------
    sweeps : int
        Sweeps made.
    converged : bool
        Whether the tolerance was met.

    References
    ----------
    .. [1] V. Acary, B. Brogliato, "Numerical methods for nonsmooth dynamical systems",
       Springer (2008), Ch. 13.
    """
    nc = contact_bodies.shape[0]
    for c in range(nc):
        if active[c]:
            a, b = contact_bodies[c, 0], contact_bodies[c, 1]
            w[c, 0], w[c, 1], w[c, 2] = delassus_block(inv_mass, a, b, jac, c)
            apply_impulse(v, inv_mass, a, b, jac, c, impulse[c, 0], impulse[c, 1])
        else:
            impulse[c, 0] = 0.0
            impulse[c, 1] = 0.0
    sweeps = 0
    while sweeps < max_iterations:
        change = 0.0
        for i in range(nc):
            c = i if sweeps % 2 == 0 else nc - 1 - i
            if not active[c]:
                continue
            a, b = contact_bodies[c, 0], contact_bodies[c, 1]
            un, ut = relative_velocity(v, a, b, jac, c)
            pn, pt = impulse[c, 0], impulse[c, 1]
            ufn = un - (w[c, 0] * pn + w[c, 1] * pt)
            uft = ut - (w[c, 1] * pn + w[c, 2] * pt)
            new_pn, new_pt = local_coulomb(ufn, uft, w[c, 0], w[c, 1], w[c, 2], mu[c])
            dpn, dpt = new_pn - pn, new_pt - pt
            if dpn != 0.0 or dpt != 0.0:
                apply_impulse(v, inv_mass, a, b, jac, c, dpn, dpt)
                impulse[c, 0] = new_pn
                impulse[c, 1] = new_pt
                change = max(change, abs(dpn) + abs(dpt))
        sweeps += 1
        if change <= tol_impulse:
            return sweeps, True
    return sweeps, False


@numba.njit(cache=True)
def incidence(contact_bodies, nb):
    """The contacts of every block, and the half-bandwidth of the contact problem.

    Parameters
    ----------
    contact_bodies : array of int (nc, 2)
        Bodies a and b of every contact (-1: the ground).
    nb : int
        Number of blocks.

    Returns
    -------
    pointer : array of int (nb + 1,)
        The contacts of block ``i`` are the rows ``pointer[i]:pointer[i + 1]`` of
        ``incident``.
    incident : array of int (2 nc, 2)
        Block by block, each of its contacts (increasing) and the block's side in it: 0 if it
        is body a, 1 if body b.
    half_bandwidth : int
        The largest ``|c - d|`` [-] of two contacts that touch one block: the Delassus block
        of ``c, d`` is zero beyond it (at least 1, the two ends of a joint).
    """
    nc = contact_bodies.shape[0]
    pointer = np.zeros(nb + 1, dtype=np.int64)
    for c in range(nc):
        for side in range(2):
            body = contact_bodies[c, side]
            if body >= 0:
                pointer[body + 1] += 1
    for i in range(nb):
        pointer[i + 1] += pointer[i]
    fill = pointer[:nb].copy()
    incident = np.zeros((max(pointer[nb], 1), 2), dtype=np.int64)
    for c in range(nc):
        for side in range(2):
            body = contact_bodies[c, side]
            if body >= 0:
                incident[fill[body], 0] = c
                incident[fill[body], 1] = side
                fill[body] += 1
    half_bandwidth = 1
    for i in range(nb):
        if pointer[i + 1] > pointer[i]:
            half_bandwidth = max(half_bandwidth,
                                 incident[pointer[i + 1] - 1, 0] - incident[pointer[i], 0])
    return pointer, incident, half_bandwidth


@numba.njit(cache=True, inline="always")
def _coupling(scaled, c, side_c, d, side_d, wband, i, k):
    """Add a block's part of the Delassus block of contacts c, d, ``H_c,b M_b^-1 H_d,b^T``
    [m/kg], to rows ``2i, 2i+1`` and columns ``2k, 2k+1`` (``k >= i``; for ``k = i`` the upper
    triangle only) of ``W`` in upper band storage ``wband`` (:func:`_assemble_delassus`), from
    the rows of ``scaled``: the Jacobian rows of each contact scaled by ``M_b^-1/2``;
    ``side_c``, ``side_d`` (0 or 6) say whether the block is body a or b of each contact."""
    uc, ud = np.uint64(side_c), np.uint64(side_d)
    rc, rd = np.uint64(c), np.uint64(d)
    cnx, cny, cnr = scaled[rc, uc], scaled[rc, uc + 1], scaled[rc, uc + 2]
    ctx, cty, ctr = scaled[rc, uc + 3], scaled[rc, uc + 4], scaled[rc, uc + 5]
    dnx, dny, dnr = scaled[rd, ud], scaled[rd, ud + 1], scaled[rd, ud + 2]
    dtx, dty, dtr = scaled[rd, ud + 3], scaled[rd, ud + 4], scaled[rd, ud + 5]
    rn, rt = np.uint64(2 * i), np.uint64(2 * i + 1)
    off = np.uint64(2 * (k - i))
    wband[rn, off] += cnx * dnx + cny * dny + cnr * dnr
    wband[rn, off + 1] += cnx * dtx + cny * dty + cnr * dtr
    wband[rt, off] += ctx * dtx + cty * dty + ctr * dtr
    if k > i:
        wband[rt, off - 1] += ctx * dnx + cty * dny + ctr * dnr


@numba.njit(cache=True, inline="always")
def _scaled_rows(inv_mass, body, jac, c, first, scaled):
    """Jacobian rows ``first .. first + 5`` of contact ``c`` (of block ``body``) scaled by
    ``M_body^-1/2``: ``(m^-1/2, m^-1/2, I^-1/2)`` per row of 3, into ``scaled[c]``."""
    ub, uc, f = np.uint64(body), np.uint64(c), np.uint64(first)
    sm, si = inv_mass[ub, 2], inv_mass[ub, 3]
    scaled[uc, f] = sm * jac[uc, f]
    scaled[uc, f + 1] = sm * jac[uc, f + 1]
    scaled[uc, f + 2] = si * jac[uc, f + 2]
    scaled[uc, f + 3] = sm * jac[uc, f + 3]
    scaled[uc, f + 4] = sm * jac[uc, f + 4]
    scaled[uc, f + 5] = si * jac[uc, f + 5]


@numba.njit(cache=True, inline="always")
def _assemble_delassus(v, inv_mass, contact_bodies, jac, m, idx, pos, pointer, incident, kl,
                       wband, uf, scaled):
    r"""The Delassus matrix :math:`W = H M^{-1} H^T = \sum_b H_b M_b^{-1} H_b^T` of the ``m``
    active contacts ``idx[:m]`` and their free velocities :math:`u^f = H v` (into ``uf``), rows
    ``2 i`` normal and ``2 i + 1`` tangential of the ``i``-th.

    ``W`` is symmetric: its upper band is stored, ``wband[r, s]`` = :math:`W_{r, r + s}`
    (``s = 0 .. kl``). Block by block (``pointer``, ``incident``: :func:`incidence`), every pair
    of active contacts that touch it couples: the cost is linear in the number of contacts.
    Each entry is a dot product of Jacobian rows scaled by :math:`M_b^{-1/2}` (``scaled``, work
    space (nc, 12))."""
    size = 2 * m
    for r in range(size):
        for off in range(kl + 1):
            wband[r, off] = 0.0
    for i in range(m):
        c = idx[i]
        a, b = contact_bodies[c, 0], contact_bodies[c, 1]
        uf[2 * i], uf[2 * i + 1] = relative_velocity(v, a, b, jac, c)
        if a >= 0:
            _scaled_rows(inv_mass, a, jac, c, 0, scaled)
        if b >= 0:
            _scaled_rows(inv_mass, b, jac, c, 6, scaled)
    for body in range(pointer.size - 1):
        end = pointer[body + 1]
        for e in range(pointer[body], end):
            c = incident[e, 0]
            i = pos[c]
            if i < 0:
                continue
            side_c = 6 * incident[e, 1]
            for e2 in range(e, end):  # contacts in increasing order: k >= i
                d = incident[e2, 0]
                k = pos[d]
                if k >= 0:
                    _coupling(scaled, c, side_c, d, 6 * incident[e2, 1], wband, i, k)


@numba.njit(cache=True, inline="always")
def _state_system(m, idx, state, mu, kl, wband, uf, aband, rhs, scale, full):
    r"""The linear system of the active-set method for the current ``state`` of every active
    contact (:func:`solve_active_set`), in the band ``aband`` (half-bandwidth ``kl``, rows
    zero-padded to ``3 kl + 1`` columns, :func:`~.band.band_solve`), ``rhs`` and the size of
    every row, ``scale``: ``W`` (from its upper band ``wband``) with the compliance on its
    diagonal; the rows and columns of an open contact those of the identity (``P = 0``); the
    tangential row of a sliding one ``P_t - sigma mu P_n = 0``.

    Returns whether a contact slides. If none does, the system is symmetric positive definite
    and only its upper half is written (what :func:`~.band.band_cholesky_solve` reads), unless
    ``full``. For an arch's half-bandwidth (:data:`~.band.ARCH_BANDWIDTH`) the entries outside
    the band are not written for Cholesky's factorisation (:func:`~.band.arch_cholesky_solve`
    does not read them), unless ``full`` (for :func:`~.band.band_solve`, whose row
    interchanges fill the padding)."""
    size = 2 * m
    sliding = False
    for i in range(m):
        sliding = sliding or state[idx[i]] >= 2
    ukl = np.uint64(kl)
    # the arch's Cholesky (arch_cholesky_solve) reads the upper band and nothing else
    lean = kl == ARCH_BANDWIDTH and not (sliding or full)
    for r in range(size):
        ur = np.uint64(r)
        if not lean:
            for off in range(kl):
                aband[ur, np.uint64(off)] = 0.0
            for off in range(2 * kl + 1, 3 * kl + 1):
                aband[ur, np.uint64(off)] = 0.0
        for off in range(kl + 1):
            aband[ur, ukl + np.uint64(off)] = wband[ur, np.uint64(off)]
        aband[ur, ukl] += REGULARISATION * wband[ur, 0]
        rhs[ur] = -uf[ur]
    if sliding or full:  # the lower half too
        for r in range(size):
            ur = np.uint64(r)
            for s in range(1, min(kl, size - 1 - r) + 1):
                us = np.uint64(s)
                aband[ur + us, ukl - us] = wband[ur, us]
    for i in range(m):
        st = state[idx[i]]
        if st == 0:
            for r in (2 * i, 2 * i + 1):
                for col in range(max(0, r - kl), min(size, r + kl + 1)):
                    aband[r, col - r + kl] = 0.0
                    aband[col, r - col + kl] = 0.0
                aband[r, kl] = 1.0
                rhs[r] = 0.0
        elif st >= 2:
            rt = 2 * i + 1
            for off in range(2 * kl + 1):
                aband[rt, off] = 0.0
            aband[rt, kl] = 1.0
            aband[rt, kl - 1] = -mu[idx[i]] if st == 2 else mu[idx[i]]
            rhs[rt] = 0.0
    for r in range(size):
        scale[r] = abs(aband[r, kl])
    return sliding


@numba.njit(cache=True, inline="always")
def _solve_states(m, idx, state, mu, kl, wband, uf, aband, rhs, scale):
    """The impulses of the current ``state`` of every active contact, into ``rhs``: the system
    of :func:`_state_system` solved by Cholesky's factorisation if no contact slides, else by
    Gaussian elimination, and with pivoting should a pivot be small (the solvers of
    :mod:`~.band`; the arch's own for its half-bandwidth)."""
    sliding = _state_system(m, idx, state, mu, kl, wband, uf, aband, rhs, scale, False)
    if sliding and kl == ARCH_BANDWIDTH:
        solved = arch_lu_solve(aband, rhs, 2 * m, scale)
    elif sliding:
        solved = band_lu_solve(aband, rhs, 2 * m, kl, scale)
    elif kl == ARCH_BANDWIDTH:
        solved = arch_cholesky_solve(aband, rhs, 2 * m)
    else:
        solved = band_cholesky_solve(aband, rhs, 2 * m, kl)
    if not solved:  # a small pivot: assemble again and pivot
        _state_system(m, idx, state, mu, kl, wband, uf, aband, rhs, scale, True)
        band_solve(aband, rhs, 2 * m, kl)


@numba.njit(cache=True, inline="always")
def _row_velocity(r, size, kl, wband, uf, impulses):
    r"""Row ``r`` of :math:`u = u^f + W P` [m/s] from the upper band ``wband`` of ``W``."""
    u = uf[r]
    for s in range(min(kl, size - 1 - r) + 1):
        u += wband[r, s] * impulses[r + s]
    for s in range(1, min(kl, r) + 1):
        u += wband[r - s, s] * impulses[r - s]
    return u


@numba.njit(cache=True, inline="always")
def switched_state(st, pn, pt, mu, p_tol, u_tol, u):
    """The state of an active contact that its impulses ``(pn, pt)`` and velocity ``u`` call
    for, from its state ``st`` (:func:`solve_active_set`: the switching tests, the one rule of
    both linear systems, :mod:`~archquake.rigid_blocks.block_space`): ``u`` is the normal
    velocity of an open contact, the tangential velocity of a sliding one, unused for a sticking
    one (it has ``u = 0`` up to the compliance)."""
    if st == 0:
        return 1 if u < -u_tol else 0
    if pn < -p_tol:
        return 0
    if st == 1:
        if abs(pt) > mu * pn + p_tol:
            return 2 if pt > 0.0 else 3
        return 1
    if st == 2:
        return 1 if u > u_tol else 2
    return 1 if u < -u_tol else 3


@numba.njit(cache=True, inline="always")
def _switch_states(m, idx, state, mu, p_tol, u_tol, kl, wband, uf, impulses, solves):
    """Switch the states that the impulses ``impulses`` (rows ``2 i``, ``2 i + 1`` of the
    ``i``-th active contact) contradict (:func:`switched_state`); after
    :data:`SINGLE_SWITCH_AFTER` solves only the first. The velocities ``u = u^f + W P`` are
    computed where a test needs them: the normal one of an open contact, the tangential one of
    a sliding contact. Returns whether any state changed."""
    size = 2 * m
    changed = False
    for i in range(m):
        c = idx[i]
        st = state[c]
        u = 0.0
        if st != 1:
            u = _row_velocity(2 * i + (0 if st == 0 else 1), size, kl, wband, uf, impulses)
        new = switched_state(st, impulses[2 * i], impulses[2 * i + 1], mu[c], p_tol, u_tol, u)
        if new != st and not (changed and solves > SINGLE_SWITCH_AFTER):
            state[c] = new
            changed = True
    return changed


@numba.njit(cache=True, _nrt=False)
def solve_active_set(v, inv_mass, contact_bodies, jac, active, impulse, state, mu, p_tol, u_tol,
                     work, max_solves):
    r"""Contact problem of a step by a primal-dual active-set method; ``v`` enters free.

    Every active contact has a state (-1 for an inactive one): 0 open (``P = 0``), 1 stick
    (``u = 0``), 2 slide with ``P_t = +mu P_n`` and 3 slide with ``P_t = -mu P_n``
    (``u_n = 0``). For the current states the impulses solve one linear system in the
    Delassus matrix ``W = H M^-1 H^T`` (assembled once), with
    ``u = u^f + W P`` and :math:`\rho` = :data:`REGULARISATION`:

    .. math::

        \text{open:}\quad P_n = 0,\; P_t = 0,

        \text{stick:}\quad (W P)_n + \rho W_{nn} P_n = -u^f_n, \quad
        (W P)_t + \rho W_{tt} P_t = -u^f_t,

        \text{slide } (\sigma = \pm 1):\quad (W P)_n + \rho W_{nn} P_n = -u^f_n, \quad
        P_t = \sigma \mu P_n.

    The states that the solution contradicts are switched and the system is solved again,
    until none is:

    .. math::

        \text{open} \to \text{stick if } u_n < -\epsilon_u; \qquad
        \text{stick or slide} \to \text{open if } P_n < -\epsilon_P;

        \text{stick} \to \text{slide } \operatorname{sign}(P_t) \text{ if }
        |P_t| > \mu P_n + \epsilon_P; \qquad
        \text{slide } \sigma \to \text{stick if } \sigma u_t > \epsilon_u

    (``u`` evaluated without the compliance). After :data:`SINGLE_SWITCH_AFTER` solves only the
    first contradicted state is switched per solve; after :data:`ACTIVE_SET_SOLVES` the method
    gives up. The compliance picks the smallest impulses among the statically indeterminate
    ones (the split of the friction force between the two ends of a joint). The states start
    from the previous step's; a newly active contact starts sticking. On convergence the
    impulses are written to ``impulse`` and applied to ``v``; otherwise ``v`` and ``impulse``
    keep their input values (the impulses of the previous step, 0 for an inactive contact) and
    the caller falls back to Gauss-Seidel.

    Two contacts couple only through a block they both touch, so ``W`` is a band matrix when
    the contacts are numbered along the structure (an arch: joint by joint, each coupled to its
    two neighbours): it is assembled block by block in band storage
    (:func:`_assemble_delassus`) and the system of the states solved by Cholesky's
    factorisation if no contact slides (:func:`~.band.band_cholesky_solve`: it is then
    symmetric positive definite), else by Gaussian elimination (:func:`~.band.band_lu_solve`,
    and with pivoting, :func:`~.band.band_solve`, should a pivot be small), at a cost linear in
    the number of contacts.

    Parameters
    ----------
    v : array (nb, 3)
        In: the free velocities; out (if converged): the velocities at the end of the step
        [m/s, m/s, rad/s].
    inv_mass : array (nb, 4)
        Inverse masses [m/kg] and inertias [1/(kg m)], and their square roots.
    contact_bodies : array of int (nc, 2)
        Bodies of every contact (-1: the ground).
    jac : array (nc, 12)
        Jacobian rows (:func:`~.contacts.contact_geometry`).
    active : array of bool (nc,)
        The active set.
    impulse : array (nc, 2)
        Out: the impulses ``(P_n, P_t)`` [N s/m] (0 for inactive contacts).
    state : array of int (nc,)
        In: the previous step's states; out: the new ones.
    mu : array (nc,)
        Friction coefficient of every contact [-].
    p_tol, u_tol : float
        Tolerances :math:`\epsilon_P` [N s/m] and :math:`\epsilon_u` [m/s] of the switching
        tests (the driver's :math:`\epsilon_u`: :data:`SWITCH_VELOCITY` times ``g h``).
    work : tuple
        ``(idx, pos, pointer, incident, kl, wband, aband, rhs, uf, scale, scaled)``: the block
        incidence ``pointer, incident`` of :func:`incidence` and the half-bandwidth of the
        impulses ``kl = 2 b + 1`` (``b`` that of the contacts); work space: ``idx``, ``pos``
        (nc,) int (the active contacts, and the position of each among them, -1 if inactive),
        ``wband`` (2 nc, kl + 1), ``aband`` (2 nc, 3 kl + 1), ``rhs``, ``uf``, ``scale``
        (2 nc,), ``scaled`` (nc, 12).

    Returns
    -------
    solves : int
        Linear solves made (0 if no contact is active).
    converged : bool
        Whether a consistent set of states was found.
    """
    idx, pos, pointer, incident, kl, wband, aband, rhs, uf, scale, scaled = work
    nc = contact_bodies.shape[0]
    m = 0
    for c in range(nc):
        if active[c]:
            idx[m] = c
            pos[c] = m
            m += 1
            if state[c] < 0:  # newly active: guess that it sticks
                state[c] = 1
        else:
            pos[c] = -1
            state[c] = -1
            impulse[c, 0] = 0.0
            impulse[c, 1] = 0.0
    if m == 0:
        return 0, True
    _assemble_delassus(v, inv_mass, contact_bodies, jac, m, idx, pos, pointer, incident, kl,
                       wband, uf, scaled)
    solves = 0
    converged = False
    while solves < max_solves:
        _solve_states(m, idx, state, mu, kl, wband, uf, aband, rhs, scale)
        solves += 1
        if not _switch_states(m, idx, state, mu, p_tol, u_tol, kl, wband, uf, rhs, solves):
            converged = True
            break
    if converged:
        for i in range(m):
            c = idx[i]
            impulse[c, 0] = rhs[2 * i] if state[c] != 0 else 0.0
            impulse[c, 1] = rhs[2 * i + 1] if state[c] != 0 else 0.0
            apply_impulse(v, inv_mass, contact_bodies[c, 0], contact_bodies[c, 1], jac, c,
                           impulse[c, 0], impulse[c, 1])
    return solves, converged


@numba.njit(cache=True, inline="always")
def _narrow(lo, hi, value, slope, limit):
    r"""The range ``[lo, hi]`` of :math:`\delta` narrowed to where
    :math:`value + \delta\,slope \le limit` (an empty range where it holds nowhere in it)."""
    if slope > 0.0:
        hi = min(hi, (limit - value) / slope)
    elif slope < 0.0:
        lo = max(lo, (limit - value) / slope)
    elif value > limit:
        hi = lo - 1.0
    return lo, hi


@numba.njit(cache=True, inline="always")
def _solve_once(base, v, inv_mass, contact_bodies, jac, active, impulses, state, states, mu,
                p_tol, u_tol, work):
    """One solve of the active-set method from the states ``state`` with the free velocities
    ``base``, on copies (``v``, ``states``, ``impulses``: its switching tests and impulses
    change only those); it leaves ``W``, :math:`u^f` and the solution in ``work``."""
    copy_1d(states, state)
    copy_2d(v, base)
    solve_active_set(v, inv_mass, contact_bodies, jac, active, impulses, states, mu, p_tol,
                     u_tol, work, np.int64(1))  # not a literal: run's compiled signature


@numba.njit(cache=True, _nrt=False)
def rest_range(v_free, dv, inv_mass, contact_bodies, jac, active, state, mu, p_tol, u_tol,
               energy_limit, work, path):
    r"""The ground accelerations under which a structure at rest stays at rest: the range of
    :math:`\delta = \bar a_g - a_0` over which the contact problem of a step keeps the states
    ``state`` of its active contacts and leaves the blocks still.

    For fixed states the step's problem is one linear system (:func:`solve_active_set`), whose
    right-hand side, the free velocities :math:`u^f = H v^f`, is affine in the step's mean
    ground acceleration: :math:`v^f(a_0 + \delta) = v^f(a_0) + \delta\,\partial v^f`, with
    :math:`\partial v^f = -h\,e_x` on every block (the inertial force of the frame of the
    ground). So are its impulses and the velocities at the end of the step:

    .. math::

        P(\delta) = P_0 + \delta\,\partial P, \qquad
        v(\delta) = v_0 + \delta\,\partial v, \quad
        v_0 = v^f(a_0) + \mathbf M^{-1} H^T P_0, \quad
        \partial v = \partial v^f + \mathbf M^{-1} H^T \partial P,

    (two solves of the same system). The active-set method keeps the states where none of its
    switching tests (:func:`switched_state`) holds: every test is linear in :math:`\delta`
    (:math:`P_n \ge -\epsilon_P` and :math:`|P_t| \le \mu P_n + \epsilon_P` of a sticking
    contact, :math:`u_n \ge -\epsilon_u` of an open one, :math:`P_n \ge -\epsilon_P` and the
    slip rate's sign of a sliding one), so where they hold is an interval; and the blocks stay
    still where the kinetic energy of :math:`v(\delta)`, a convex quadratic, is at most
    ``energy_limit``, another interval. On their intersection every step from rest solves to
    these states, ends at rest and moves no block (to the compliance and round-off: the
    velocities of rest, :math:`10^{-13}`-:math:`10^{-10}` m/s).

    Parameters
    ----------
    v_free : array (nb, 3)
        Free velocities of a step at :math:`a_0` [m/s, m/s, rad/s].
    dv : array (nb, 3)
        Their derivative with respect to the step's mean ground acceleration [s].
    inv_mass, contact_bodies, jac, active, mu, p_tol, u_tol, work
        As :func:`solve_active_set` (``jac`` of the configuration at rest).
    state : array of int (nc,)
        The states of the last step, unchanged.
    energy_limit : float
        Kinetic energy of a step at rest [J/m].
    path : tuple
        ``(p0, dp, uf0, v0, dvel, states, impulses)``: out, the impulses :math:`P_0` and
        :math:`\partial P` of the ``i``-th active contact at rows ``2 i``, ``2 i + 1`` of
        ``p0``, ``dp`` (2 nc,) [N s/m, N s^3/m^2]; work space ``uf0`` (2 nc,), ``v0`` and
        ``dvel`` (nb, 3), ``states`` (nc,) int and ``impulses`` (nc, 2). Each solve is one of
        :func:`solve_active_set` from copies of the states (its switching tests change only
        the copies): it leaves ``W``, :math:`u^f` and the solution in ``work``.

    Returns
    -------
    lo, hi : float
        The range of :math:`\delta` [m/s^2] (``lo > hi``: empty; an active contact without a
        state, or a structure that does not stay still even at :math:`a_0`).
    m : int
        The active contacts (their indices ``work[0][:m]``).
    """
    idx, pos, pointer, incident, kl, wband, aband, rhs, uf, scale, scaled = work
    p0, dp, uf0, v0, dvel, states, impulses = path
    nc = contact_bodies.shape[0]
    m = 0
    for c in range(nc):
        if active[c]:
            if state[c] < 0:
                return 1.0, -1.0, 0
            m += 1
    size = 2 * m
    # P0, the impulses at a0, and dP, their derivative (the derivative of u^f on the right)
    _solve_once(v_free, v0, inv_mass, contact_bodies, jac, active, impulses, state, states, mu,
                p_tol, u_tol, work)
    for r in range(size):
        uf0[r] = uf[r]
        p0[r] = rhs[r]
    _solve_once(dv, v0, inv_mass, contact_bodies, jac, active, impulses, state, states, mu,
                p_tol, u_tol, work)
    for r in range(size):
        dp[r] = rhs[r]
    lo, hi = -np.inf, np.inf
    for i in range(m):
        c = idx[i]
        st = state[c]
        n, t = 2 * i, 2 * i + 1
        if st == 0:  # open: u_n >= -u_tol
            u0 = _row_velocity(n, size, kl, wband, uf0, p0)
            du = _row_velocity(n, size, kl, wband, uf, dp)
            lo, hi = _narrow(lo, hi, -u0, -du, u_tol)
            continue
        lo, hi = _narrow(lo, hi, -p0[n], -dp[n], p_tol)  # P_n >= -p_tol
        if st == 1:  # stick: |P_t| <= mu P_n + p_tol
            lo, hi = _narrow(lo, hi, p0[t] - mu[c] * p0[n], dp[t] - mu[c] * dp[n], p_tol)
            lo, hi = _narrow(lo, hi, -p0[t] - mu[c] * p0[n], -dp[t] - mu[c] * dp[n], p_tol)
        else:  # slide: the slip rate keeps its sign (+P_t: u_t <= u_tol; -P_t: u_t >= -u_tol)
            sign = 1.0 if st == 2 else -1.0
            u0 = _row_velocity(t, size, kl, wband, uf0, p0)
            du = _row_velocity(t, size, kl, wband, uf, dp)
            lo, hi = _narrow(lo, hi, sign * u0, sign * du, u_tol)
    # the blocks' velocities v0 + delta dv: T(delta) = T0 + T1 delta + T2 delta^2 <= limit
    copy_2d(v0, v_free)
    copy_2d(dvel, dv)
    for i in range(m):
        c = idx[i]
        a, b = contact_bodies[c, 0], contact_bodies[c, 1]
        apply_impulse(v0, inv_mass, a, b, jac, c, p0[2 * i], p0[2 * i + 1])
        apply_impulse(dvel, inv_mass, a, b, jac, c, dp[2 * i], dp[2 * i + 1])
    t0 = t1 = t2 = 0.0
    for b in range(v_free.shape[0]):
        mass, inertia = 1.0 / inv_mass[b, 0], 1.0 / inv_mass[b, 1]
        t0 += 0.5 * (mass * (v0[b, 0] ** 2 + v0[b, 1] ** 2) + inertia * v0[b, 2] ** 2)
        t1 += (mass * (v0[b, 0] * dvel[b, 0] + v0[b, 1] * dvel[b, 1])
               + inertia * v0[b, 2] * dvel[b, 2])
        t2 += 0.5 * (mass * (dvel[b, 0] ** 2 + dvel[b, 1] ** 2) + inertia * dvel[b, 2] ** 2)
    excess = t0 - energy_limit
    if t2 > 0.0:
        disc = t1 * t1 - 4.0 * t2 * excess
        if disc < 0.0:
            return 1.0, -1.0, m
        root = math.sqrt(disc)
        lo = max(lo, (-t1 - root) / (2.0 * t2))
        hi = min(hi, (-t1 + root) / (2.0 * t2))
    else:
        lo, hi = _narrow(lo, hi, excess, t1, 0.0)
    return lo, hi, m


@numba.njit(cache=True)
def solve_lemke(v, inv_mass, contact_bodies, jac, active, impulse, state, mu, p_tol, u_tol,
                work):
    r"""Contact problem of a step by Lemke's algorithm, where the active-set method gave up;
    ``v`` enters free.

    The Delassus matrix and free velocities of the active contacts, as
    :func:`solve_active_set` left them in ``work``, are written out dense and the problem solved
    as a linear complementarity problem (:mod:`archquake.rigid_blocks.lemke`: a method that
    cannot cycle, and a problem that always has a solution). Its states are handed back to the
    active-set method, which then solves them to round-off (usually in one linear solve, the
    impulses then those it would have found had it converged); should it switch them and fail
    again, Lemke's impulses are applied as they are.

    Parameters
    ----------
    v, inv_mass, contact_bodies, jac, active, impulse, state, mu, p_tol, u_tol, work
        As for :func:`solve_active_set`, called just before with the same arguments (``v``
        unchanged since).

    Returns
    -------
    pivots : int
        Pivots of Lemke's algorithm and linear solves of the active-set method after it.
    converged : bool
        Whether the problem was solved (False only if Lemke's algorithm failed, not observed).
    """
    idx, pos, pointer, incident, kl, wband, aband, rhs, uf, scale, scaled = work
    nc = contact_bodies.shape[0]
    m = 0
    for c in range(nc):
        if active[c]:
            m += 1
    size = 2 * m
    dense = np.zeros((size, size))
    for r in range(size):
        for s in range(min(kl, size - 1 - r) + 1):
            dense[r, r + s] = wband[r, s]
            dense[r + s, r] = wband[r, s]
    free = uf[:size].copy()
    impulses = np.zeros(size)
    states = np.zeros(m, dtype=np.int64)
    mu_active = np.empty(m)
    for i in range(m):
        mu_active[i] = mu[idx[i]]
    code, pivots = solve_contact_lcp(dense, free, mu_active, LEMKE_COMPLIANCE, impulses, states)
    if code != LEMKE_SOLVED:
        return pivots, False
    for i in range(m):
        state[idx[i]] = states[i]
    v_free = v.copy()
    solves, converged = solve_active_set(v, inv_mass, contact_bodies, jac, active, impulse,
                                         state, mu, p_tol, u_tol, work,
                                         min(POLISH_SOLVES, 2 * m))  # an int64, as run's
    if converged:
        return pivots + solves, True
    copy_2d(v, v_free)  # the active-set method switched Lemke's states and failed: Lemke's impulses
    for i in range(m):
        c = idx[i]
        state[c] = states[i]
        impulse[c, 0] = impulses[2 * i]
        impulse[c, 1] = impulses[2 * i + 1]
        apply_impulse(v, inv_mass, contact_bodies[c, 0], contact_bodies[c, 1], jac, c,
                       impulse[c, 0], impulse[c, 1])
    return pivots + solves, True
