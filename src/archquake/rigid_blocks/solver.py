r"""Compiled Moreau-Jean time stepping of rigid blocks with unilateral Coulomb contacts.

Everything here is ``numba``-compiled; :func:`run` is the one driver of an analysis, the other
functions are its small helpers. :mod:`archquake.rigid_blocks.dynamics` prepares the arrays and
reads the results.

Frame and unknowns
------------------
The equations are written in the frame of the ground, which translates with the ground
displacement ``xg(t)``: the supports are fixed in it, and every block carries, besides its
weight, the inertial (d'Alembert) force ``-m_i xg''(t)`` along x at its centroid (no moment, the
frame does not turn). So the ground displacement is never needed (a record's integrated
displacement drifts), contacts are detected against fixed supports, and every displacement is
relative to the ground. Block ``i`` has the coordinates ``q_i = (x_i, y_i, theta_i)`` (centroid
displacement [m] and rotation [rad], counterclockwise) and the velocities ``v_i = (u_i, w_i,
omega_i)``; the mass matrix is ``diag(m_i, m_i, I_i)``.

Contacts and their detection
----------------------------
Each joint ``j`` between bodies ``a`` and ``b`` has a contact at each of its two ends
``k = 0, 1``. The contact follows two material points, one of each body, that coincide with
the end of the joint in the undeformed configuration: ``p_a`` (on body ``a``) and ``p_b``
(on body ``b``). The face of body ``a`` is the joint segment carried by ``a``, with normal
``n_a = R(theta_a) n_j`` and tangent ``t_a = R(theta_a) t_j``. The gap and the tangential
offset of the contact are

.. math::

    g = (p_b - p_a) \cdot n_a, \qquad s = (p_b - p_a) \cdot t_a

exactly, for any rotation (nothing is linearised). This is the corner-to-face contact of two
convex polygons that touch along a common flat face: while the two faces are in contact or
turn about one end (a hinge), that end is a material point of both blocks, so the pair of
points stays exact at large rotations; the other end lifts off (``g > 0``) and lands again.
Only sliding moves ``p_b`` along the face; the contact holds while the projection of ``p_b``
on the face lies on the face of body ``a`` (:attr:`Assembly.face_extents`: by default the joint
extended by 10 % of its length at each end, since beyond its end the exact contact would be the
corner of ``a`` on the face of ``b``, which differs to second order only, slip times relative
rotation). Contacts of other faces (an extrados on a neighbouring block) are not detected:
they cannot occur before an arch collapses.

Time stepping (Moreau-Jean, theta-method)
-----------------------------------------
On each step ``[t_k, t_k + h]``, with the contact geometry and the Jacobians evaluated at
``q_k`` [Jean 1999, Acary & Brogliato 2008, Sect. 10.1]:

.. math::

    M (v_{k+1} - v_k) = \int_{t_k}^{t_{k+1}} f\,dt + H^T P, \qquad
    q_{k+1} = q_k + h\,[(1 - \theta) v_k + \theta v_{k+1}]

where the impulse of the external forces is exact (weight, and the ground acceleration
integrated over the step by :func:`mean_acceleration`, so a jump of a pulse inside a step costs
no accuracy). The contacts whose predicted gap ``g_k + theta h u_n(v_k)`` is below
:data:`ACTIVATION_GAP` times the joint's length (zero but for round-off) form the active set;
for them the impulses ``P = (P_n, P_t)`` satisfy Newton's impact law with restitution 0 at
the velocity level and Coulomb's law (friction coefficient mu):

.. math::

    0 \le u_n(v_{k+1}) \perp P_n \ge 0, \qquad |P_t| \le \mu P_n, \qquad
    P_t u_t(v_{k+1}) \le 0, \quad u_t \ne 0 \Rightarrow |P_t| = \mu P_n

A closing contact penetrates by at most ``theta h |u_n|`` (0.25 mm for 0.5 m/s at h = 1 ms,
theta = 1/2) and never drifts at rest.

The contact problem of a step is solved exactly (to round-off) by a primal-dual active-set
method, :func:`solve_active_set`: guess the state of every contact (open, stick, slide either
way; the previous step's states), solve the linear system in the impulses that the states
define, switch the states that the solution contradicts, repeat (usually 1-2 solves of a system
of at most 2 x 2(n+1) unknowns; the sticking rows carry a compliance of
:data:`REGULARISATION` times their diagonal, which picks the smallest of the statically
indeterminate impulses). Should the states cycle (a few steps of a collapse at large amplitude,
where contacts slide and separate together; counted in the outcome), projected
Gauss-Seidel takes over [2, Sect. 13.4], :func:`solve_contacts`: sweeps forward and backward in
turn, each local problem solved exactly by :func:`local_coulomb`, stopping when no impulse
changes by more than ``tolerance * m_mean g h`` (the impulse of a mean block's weight over a
step, scaled) or after ``max_iterations`` sweeps (counted as unconverged). Gauss-Seidel alone
converges slowly on an arch (the thrust runs through a chain of blocks and the friction split
between the two ends of a joint is indeterminate), and its residual velocities make a still
arch creep; hence the direct method.

Energy
------
Kinetic energy in the ground frame, potential energy of the weights (zero in the undeformed
configuration), work of the inertial forces ``-m xg''`` (the input) and work of the contact
impulses, ``sum P . (u_k + u_{k+1}) / 2`` (its opposite is the dissipated energy). For
``theta = 1/2`` and these linear forces, ``E_{k+1} - E_k = W_input + W_contact`` holds exactly
per step, so the bookkeeping closes to round-off. The scheme is not exactly dissipative: the
contact Jacobians are those of ``q_k``, in which a persistent pivot's velocity ``v_k`` (made
zero in the configuration of the previous step) is not exactly zero, so the contact work can
be positive by O(h^2) per step; for a rocking block this is 0.15 % of its energy over 3 s at
h = 1 ms, halving with h (tested).

References
----------
[1] M. Jean, "The non-smooth contact dynamics method", Comput. Methods Appl. Mech. Engrg. 177
    (1999) 235-257.

[2] V. Acary, B. Brogliato, "Numerical methods for nonsmooth dynamical systems", Springer (2008),
    Ch. 10 (Moreau-Jean time stepping) and Ch. 12-13 (Gauss-Seidel for the contact problem).
"""

from __future__ import annotations

import math

import numba
import numpy as np

from ..ground_motion import HARMONIC, STEP

REGULARISATION = 1e-9
"""Compliance of the sticking rows of the contact problem, relative to their diagonal [-]."""

ACTIVE_SET_SOLVES = 60
"""Largest number of linear solves of the active-set method before Gauss-Seidel takes over."""

SINGLE_SWITCH_AFTER = 10
"""After this many solves the active-set method switches one contradicted state per solve (the
first one, in the manner of Murty's least-index rule) instead of all, which ends cycles."""

ACTIVATION_GAP = 1e-9
"""Predicted gap, as a fraction of the joint's length, below which a contact is active [-]: a
closed joint's round-off gap (1e-16 m) must not drop it from the contact problem."""

REST, RECOVERY, COLLAPSE = 0, 1, 2
"""Outcome codes of :func:`run`."""

SUMMARY_FIELDS = (
    "status", "decided", "collapse_time", "decision_time", "max_rotation", "max_crown_drop",
    "max_slip", "max_opening", "max_drop", "steps", "iterations", "max_iterations_used",
    "unconverged_steps", "final_time", "closed", "fallbacks",
)
"""Layout of the summary vector returned by :func:`run`."""

_N_SUMMARY = 16


@numba.njit(cache=True)
def mean_acceleration(t0, t1, kind, params, times, values):
    """Mean ground acceleration [m/s^2] over ``[t0, t1]`` [s]: its exact integral / (t1 - t0).

    For the compiled representation of :mod:`archquake.ground_motion` (STEP, LINEAR, HARMONIC);
    the same function as :func:`archquake.ground_motion.evaluate`, integrated in closed form.
    """
    total = 0.0
    if kind == HARMONIC:
        amplitude, period, cycles = params[0], params[1], params[2]
        a = max(t0, 0.0)
        b = min(t1, cycles * period)
        if b > a:
            w = 2.0 * math.pi / period
            total = amplitude / w * (math.cos(w * a) - math.cos(w * b))
        return total / (t1 - t0)
    n = times.size
    if n < 2 or t1 <= times[0] or t0 >= times[n - 1]:
        return 0.0
    i = max(np.searchsorted(times, t0, side="right") - 1, 0)
    while i < n - 1 and times[i] < t1:
        a = max(t0, times[i])
        b = min(t1, times[i + 1])
        if b > a:
            if kind == STEP:
                total += values[i] * (b - a)
            else:  # LINEAR
                slope = (values[i + 1] - values[i]) / (times[i + 1] - times[i])
                fa = values[i] + slope * (a - times[i])
                fb = values[i] + slope * (b - times[i])
                total += 0.5 * (fa + fb) * (b - a)
        i += 1
    return total / (t1 - t0)


@numba.njit(cache=True)
def local_coulomb(ufn, uft, wnn, wnt, wtt, mu):
    """Exact solution of one contact's problem: impulses ``(P_n, P_t)`` [N s/m].

    The local velocity is ``u = uf + W P`` (``uf`` without this contact's impulse, ``W`` its
    2 x 2 Delassus block); the law is ``0 <= u_n perp P_n >= 0`` with Coulomb friction. The cases
    are tried in turn: separation (``uf_n >= 0``: no impulse), sticking (``u = 0`` with ``P`` in
    the cone), sliding in either direction (``u_n = 0``, ``P_t = -+ mu P_n``, ``u_t`` of the
    opposite sign).
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


@numba.njit(cache=True)
def _rotate(c, s, x, y):
    return c * x - s * y, s * x + c * y


@numba.njit(cache=True)
def contact_geometry(q, centroids, ca, cb, ra, rb, normal, tangent, offset, face_lo, face_hi,
                     gap, slip, valid, jac):
    """Gap [m], tangential offset [m], validity and Jacobian rows of every contact at ``q``.

    A contact is valid while the projection of its point of body b on the face of body a,
    ``offset + slip`` along the face from the joint's first end [m], lies in
    ``[face_lo, face_hi]`` [m].

    ``jac[c]`` holds ``(Gn_a, Gt_a, Gn_b, Gt_b)``, each a row of 3 so that the normal and
    tangential relative velocities are ``u_n = Gn_a . v_a + Gn_b . v_b`` (same for ``t``).
    """
    for c in range(ca.size):
        a, b = ca[c], cb[c]
        if a >= 0:
            cos_a, sin_a = math.cos(q[a, 2]), math.sin(q[a, 2])
            xa, ya = _rotate(cos_a, sin_a, ra[c, 0], ra[c, 1])
            cax, cay = centroids[a, 0] + q[a, 0], centroids[a, 1] + q[a, 1]
            pax, pay = cax + xa, cay + ya
            nx, ny = _rotate(cos_a, sin_a, normal[c, 0], normal[c, 1])
            tx, ty = _rotate(cos_a, sin_a, tangent[c, 0], tangent[c, 1])
        else:
            cax = cay = 0.0
            pax, pay = ra[c, 0], ra[c, 1]
            nx, ny = normal[c, 0], normal[c, 1]
            tx, ty = tangent[c, 0], tangent[c, 1]
        if b >= 0:
            cos_b, sin_b = math.cos(q[b, 2]), math.sin(q[b, 2])
            xb, yb = _rotate(cos_b, sin_b, rb[c, 0], rb[c, 1])
            cbx, cby = centroids[b, 0] + q[b, 0], centroids[b, 1] + q[b, 1]
            pbx, pby = cbx + xb, cby + yb
        else:
            cbx = cby = 0.0
            pbx, pby = rb[c, 0], rb[c, 1]
        dx, dy = pbx - pax, pby - pay
        gap[c] = dx * nx + dy * ny
        slip[c] = dx * tx + dy * ty
        along = offset[c] + slip[c]
        valid[c] = face_lo[c] <= along <= face_hi[c]
        # lever arms from each centroid to the contact point p_b
        rax, ray = pbx - cax, pby - cay
        rbx, rby = pbx - cbx, pby - cby
        if a >= 0:
            jac[c, 0] = -nx
            jac[c, 1] = -ny
            jac[c, 2] = -(rax * ny - ray * nx)
            jac[c, 3] = -tx
            jac[c, 4] = -ty
            jac[c, 5] = -(rax * ty - ray * tx)
        else:
            jac[c, 0:6] = 0.0
        if b >= 0:
            jac[c, 6] = nx
            jac[c, 7] = ny
            jac[c, 8] = rbx * ny - rby * nx
            jac[c, 9] = tx
            jac[c, 10] = ty
            jac[c, 11] = rbx * ty - rby * tx
        else:
            jac[c, 6:12] = 0.0


@numba.njit(cache=True)
def _relative_velocity(v, a, b, jac, c):
    un = 0.0
    ut = 0.0
    if a >= 0:
        un += jac[c, 0] * v[a, 0] + jac[c, 1] * v[a, 1] + jac[c, 2] * v[a, 2]
        ut += jac[c, 3] * v[a, 0] + jac[c, 4] * v[a, 1] + jac[c, 5] * v[a, 2]
    if b >= 0:
        un += jac[c, 6] * v[b, 0] + jac[c, 7] * v[b, 1] + jac[c, 8] * v[b, 2]
        ut += jac[c, 9] * v[b, 0] + jac[c, 10] * v[b, 1] + jac[c, 11] * v[b, 2]
    return un, ut


@numba.njit(cache=True)
def _apply_impulse(v, inv_mass, inv_inertia, a, b, jac, c, pn, pt):
    if a >= 0:
        v[a, 0] += inv_mass[a] * (jac[c, 0] * pn + jac[c, 3] * pt)
        v[a, 1] += inv_mass[a] * (jac[c, 1] * pn + jac[c, 4] * pt)
        v[a, 2] += inv_inertia[a] * (jac[c, 2] * pn + jac[c, 5] * pt)
    if b >= 0:
        v[b, 0] += inv_mass[b] * (jac[c, 6] * pn + jac[c, 9] * pt)
        v[b, 1] += inv_mass[b] * (jac[c, 7] * pn + jac[c, 10] * pt)
        v[b, 2] += inv_inertia[b] * (jac[c, 8] * pn + jac[c, 11] * pt)


@numba.njit(cache=True)
def _delassus(inv_mass, inv_inertia, a, b, jac, c, w):
    wnn = wnt = wtt = 0.0
    for body, k in ((a, 0), (b, 6)):
        if body >= 0:
            im, ii = inv_mass[body], inv_inertia[body]
            wnn += im * (jac[c, k] ** 2 + jac[c, k + 1] ** 2) + ii * jac[c, k + 2] ** 2
            wnt += (im * (jac[c, k] * jac[c, k + 3] + jac[c, k + 1] * jac[c, k + 4])
                    + ii * jac[c, k + 2] * jac[c, k + 5])
            wtt += im * (jac[c, k + 3] ** 2 + jac[c, k + 4] ** 2) + ii * jac[c, k + 5] ** 2
    w[c, 0] = wnn
    w[c, 1] = wnt
    w[c, 2] = wtt


@numba.njit(cache=True)
def solve_contacts(v, inv_mass, inv_inertia, ca, cb, jac, w, active, impulse, mu, tol_impulse,
                   max_iterations):
    """Projected Gauss-Seidel on the active contacts; ``v`` enters free and leaves corrected
    (``w`` holds the 2 x 2 Delassus blocks of the active contacts).

    ``impulse`` holds the warm start and receives the solution. Returns the number of sweeps
    and whether the tolerance was met.
    """
    nc = ca.size
    for c in range(nc):
        if active[c]:
            _apply_impulse(v, inv_mass, inv_inertia, ca[c], cb[c], jac, c,
                           impulse[c, 0], impulse[c, 1])
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
            a, b = ca[c], cb[c]
            un, ut = _relative_velocity(v, a, b, jac, c)
            pn, pt = impulse[c, 0], impulse[c, 1]
            ufn = un - (w[c, 0] * pn + w[c, 1] * pt)
            uft = ut - (w[c, 1] * pn + w[c, 2] * pt)
            new_pn, new_pt = local_coulomb(ufn, uft, w[c, 0], w[c, 1], w[c, 2], mu)
            dpn, dpt = new_pn - pn, new_pt - pt
            if dpn != 0.0 or dpt != 0.0:
                _apply_impulse(v, inv_mass, inv_inertia, a, b, jac, c, dpn, dpt)
                impulse[c, 0] = new_pn
                impulse[c, 1] = new_pt
                change = max(change, abs(dpn) + abs(dpt))
        sweeps += 1
        if change <= tol_impulse:
            return sweeps, True
    return sweeps, False


@numba.njit(cache=True)
def _gauss_solve(a, b, m):
    """Solve ``a[:m, :m] x = b[:m]`` in place (partial pivoting); ``b`` receives x."""
    for k in range(m):
        p = k
        big = abs(a[k, k])
        for i in range(k + 1, m):
            if abs(a[i, k]) > big:
                big = abs(a[i, k])
                p = i
        if p != k:
            for j in range(k, m):
                a[k, j], a[p, j] = a[p, j], a[k, j]
            b[k], b[p] = b[p], b[k]
        pivot = a[k, k]
        for i in range(k + 1, m):
            f = a[i, k] / pivot
            if f != 0.0:
                for j in range(k + 1, m):
                    a[i, j] -= f * a[k, j]
                b[i] -= f * b[k]
    for k in range(m - 1, -1, -1):
        s = b[k]
        for j in range(k + 1, m):
            s -= a[k, j] * b[j]
        b[k] = s / a[k, k]


@numba.njit(cache=True)
def _coupling(inv_mass, inv_inertia, jac, c, side_c, d, side_d, body, out, i, k):
    """Add body ``body``'s part of the Delassus block of contacts c, d to ``out[2i:, 2k:]``."""
    im, ii = inv_mass[body], inv_inertia[body]
    for alpha in range(2):
        gc = side_c + 3 * alpha
        for beta in range(2):
            gd = side_d + 3 * beta
            out[2 * i + alpha, 2 * k + beta] += (
                im * (jac[c, gc] * jac[d, gd] + jac[c, gc + 1] * jac[d, gd + 1])
                + ii * jac[c, gc + 2] * jac[d, gd + 2])


@numba.njit(cache=True)
def solve_active_set(v, inv_mass, inv_inertia, ca, cb, jac, active, impulse, state, mu,
                     p_tol, u_tol, regularisation, max_iterations, idx, wmat, amat, rhs, uf):
    """Contact problem of a step by a primal-dual active-set method; ``v`` enters free.

    Every active contact has a state (-1 for an inactive one): 0 open (``P = 0``), 1 stick
    (``u = 0``), 2 slide with ``P_t = +mu P_n`` and 3 slide with ``P_t = -mu P_n``
    (``u_n = 0``). For the current states
    the impulses solve one linear system in the Delassus matrix ``W = H M^-1 H^T``; the states
    that the solution contradicts (``P_n < 0``; ``u_n < 0`` on an open contact; ``|P_t| >
    mu P_n`` when sticking; ``u_t`` along the friction when sliding) are switched and the
    system is solved again, until none is. The sticking rows carry a compliance of
    ``regularisation`` times their diagonal, which picks the smallest impulses among the
    statically indeterminate ones (the split of the friction force between the two ends of a
    joint). The states start from the previous step's. Returns the number of solves and
    whether the states converged (if not, the caller falls back to Gauss-Seidel).
    """
    nc = ca.size
    m = 0
    for c in range(nc):
        if active[c]:
            idx[m] = c
            m += 1
            if state[c] < 0:  # newly active: guess that it sticks
                state[c] = 1
        else:
            state[c] = -1
            impulse[c, 0] = 0.0
            impulse[c, 1] = 0.0
    if m == 0:
        return 0, True
    size = 2 * m
    wmat[:size, :size] = 0.0
    for i in range(m):
        c = idx[i]
        un, ut = _relative_velocity(v, ca[c], cb[c], jac, c)
        uf[2 * i] = un
        uf[2 * i + 1] = ut
        for k in range(i, m):
            d = idx[k]
            for side_c in (0, 6):
                body = ca[c] if side_c == 0 else cb[c]
                if body < 0:
                    continue
                if ca[d] == body:
                    _coupling(inv_mass, inv_inertia, jac, c, side_c, d, 0, body, wmat, i, k)
                if cb[d] == body:
                    _coupling(inv_mass, inv_inertia, jac, c, side_c, d, 6, body, wmat, i, k)
        for k in range(i + 1, m):
            for alpha in range(2):
                for beta in range(2):
                    wmat[2 * k + beta, 2 * i + alpha] = wmat[2 * i + alpha, 2 * k + beta]
    solves = 0
    converged = False
    while solves < max_iterations:
        amat[:size, :size] = 0.0
        for i in range(m):
            c = idx[i]
            rn, rt = 2 * i, 2 * i + 1
            st = state[c]
            if st == 0:
                amat[rn, rn] = 1.0
                rhs[rn] = 0.0
                amat[rt, rt] = 1.0
                rhs[rt] = 0.0
                continue
            for j in range(size):
                amat[rn, j] = wmat[rn, j]
            amat[rn, rn] += regularisation * wmat[rn, rn]
            rhs[rn] = -uf[rn]
            if st == 1:
                for j in range(size):
                    amat[rt, j] = wmat[rt, j]
                amat[rt, rt] += regularisation * wmat[rt, rt]
                rhs[rt] = -uf[rt]
            else:
                amat[rt, rt] = 1.0
                amat[rt, rn] = -mu if st == 2 else mu
                rhs[rt] = 0.0
        _gauss_solve(amat, rhs, size)
        solves += 1
        changed = False
        for i in range(m):
            c = idx[i]
            pn, pt = rhs[2 * i], rhs[2 * i + 1]
            un = uf[2 * i]
            ut = uf[2 * i + 1]
            for j in range(size):
                un += wmat[2 * i, j] * rhs[j]
                ut += wmat[2 * i + 1, j] * rhs[j]
            st = state[c]
            new = st
            if st == 0:
                if un < -u_tol:
                    new = 1
            elif pn < -p_tol:
                new = 0
            elif st == 1:
                if abs(pt) > mu * pn + p_tol:
                    new = 2 if pt > 0.0 else 3
            elif st == 2:
                if ut > u_tol:
                    new = 1
            elif ut < -u_tol:
                new = 1
            if new != st and not (changed and solves > SINGLE_SWITCH_AFTER):
                state[c] = new
                changed = True
        if not changed:
            converged = True
            break
    if converged:
        for i in range(m):
            c = idx[i]
            impulse[c, 0] = rhs[2 * i] if state[c] != 0 else 0.0
            impulse[c, 1] = rhs[2 * i + 1] if state[c] != 0 else 0.0
            _apply_impulse(v, inv_mass, inv_inertia, ca[c], cb[c], jac, c,
                           impulse[c, 0], impulse[c, 1])
    return solves, converged


@numba.njit(cache=True)
def run(masses, inertias, centroids, ca, cb, ra, rb, normal, tangent, offset, face_lo, face_hi,
        length,
        crown_block, crown_point, q0, v0,
        kind, params, times, values,
        h, theta, mu, tolerance, max_iterations, gravity,
        excitation_end, n_steps, drop_limit, rest_energy, closed_gap, rest_steps,
        open_rest_steps, moved_threshold, energy_margin, record_stride, tail_steps):
    """Integrate the blocks from ``(q0, v0)`` under the ground motion; decide the outcome.

    Parameters are the arrays of :func:`archquake.rigid_blocks.dynamics.contact_arrays`, the
    initial state, the compiled ground motion, and the settings (SI units; thresholds already
    scaled to the structure): time step ``h`` [s], ``theta`` [-], friction ``mu`` [-], Gauss-
    Seidel ``tolerance`` [-] and ``max_iterations``, ``gravity`` [m/s^2], ``excitation_end``
    [s], at most ``n_steps`` steps, the collapse ``drop_limit`` [m], the kinetic energy of rest
    ``rest_energy`` [J/m], the gap of a closed joint ``closed_gap`` [m], ``rest_steps`` steps of
    rest that decide a recovery (``open_rest_steps`` with a joint still open), the opening and
    slip ``moved_threshold`` [m] below which the structure never moved, the ``energy_margin``
    [J/m] of the energy test of collapse; with ``record_stride > 0`` every ``record_stride``-th
    state is recorded and the run goes on ``tail_steps`` steps after the outcome is decided (or
    to ``n_steps`` if ``tail_steps < 0``).

    Returns
    -------
    summary : array (len(SUMMARY_FIELDS),)
    records : tuple of arrays
        ``(t, q, gap, slip, impulse / h, energy)`` with energy columns kinetic, potential,
        dissipated, input [J/m]; empty when not recording.
    """
    nb = masses.size
    nc = ca.size
    inv_mass = 1.0 / masses
    inv_inertia = 1.0 / inertias
    tol_impulse = tolerance * masses.mean() * gravity * h
    q = q0.copy()
    v = v0.copy()
    v_old = np.empty_like(v)
    gap = np.zeros(nc)
    slip = np.zeros(nc)
    valid = np.zeros(nc, dtype=np.bool_)
    active = np.zeros(nc, dtype=np.bool_)
    jac = np.zeros((nc, 12))
    w = np.zeros((nc, 3))
    impulse = np.zeros((nc, 2))
    state = -np.ones(nc, dtype=np.int64)
    idx = np.zeros(nc, dtype=np.int64)
    wmat = np.zeros((2 * nc, 2 * nc))
    amat = np.zeros((2 * nc, 2 * nc))
    rhs = np.zeros(2 * nc)
    uf = np.zeros(2 * nc)
    p_tol = 1e-12 * masses.mean() * gravity * h
    u_tol = 1e-12 * gravity * h
    fallbacks = 0
    recording = record_stride > 0
    n_records = n_steps // record_stride + 2 if recording else 0
    rec_t = np.zeros(n_records)
    rec_q = np.zeros((n_records, nb, 3))
    rec_gap = np.zeros((n_records, nc))
    rec_slip = np.zeros((n_records, nc))
    rec_force = np.zeros((n_records, nc, 2))
    rec_energy = np.zeros((n_records, 4))
    n_rec = 0

    kinetic = 0.0
    for i in range(nb):
        kinetic += 0.5 * (masses[i] * (v[i, 0] ** 2 + v[i, 1] ** 2) + inertias[i] * v[i, 2] ** 2)
    dissipated = 0.0
    work_input = 0.0
    status = -1
    decided = False
    collapse_time = math.nan
    decision_time = math.nan
    max_rotation = 0.0
    max_crown_drop = 0.0
    max_slip = 0.0
    max_opening = 0.0
    max_drop = 0.0
    rest_count = 0
    closed = True
    iterations = 0
    max_used = 0
    unconverged = 0
    stop_step = n_steps
    step = 0
    t = 0.0
    while step < stop_step:
        t = step * h
        contact_geometry(q, centroids, ca, cb, ra, rb, normal, tangent, offset, face_lo,
                         face_hi, gap, slip, valid, jac)
        # --- measurements of the state at t_k
        potential = 0.0
        drop = 0.0
        for i in range(nb):
            potential += masses[i] * gravity * q[i, 1]
            drop = max(drop, -q[i, 1])
            max_rotation = max(max_rotation, abs(q[i, 2]))
        cos_c, sin_c = math.cos(q[crown_block, 2]), math.sin(q[crown_block, 2])
        cx, cy = _rotate(cos_c, sin_c, crown_point[0], crown_point[1])
        crown_drop = -(q[crown_block, 1] + cy - crown_point[1])
        max_crown_drop = max(max_crown_drop, crown_drop)
        drop = max(drop, crown_drop)
        max_drop = max(max_drop, drop)
        closed = True
        for j in range(nc // 2):
            c0, c1 = 2 * j, 2 * j + 1
            closer = c0 if gap[c0] <= gap[c1] else c1
            max_slip = max(max_slip, abs(slip[closer]))
            for c in (c0, c1):
                if valid[c]:
                    max_opening = max(max_opening, gap[c])
                    if gap[c] > closed_gap:
                        closed = False
                else:
                    closed = False
        if recording and step % record_stride == 0:
            rec_t[n_rec] = t
            rec_q[n_rec] = q
            rec_gap[n_rec] = gap
            rec_slip[n_rec] = slip
            for c in range(nc):
                rec_force[n_rec, c, 0] = impulse[c, 0] / h
                rec_force[n_rec, c, 1] = impulse[c, 1] / h
            rec_energy[n_rec, 0] = kinetic
            rec_energy[n_rec, 1] = potential
            rec_energy[n_rec, 2] = dissipated
            rec_energy[n_rec, 3] = work_input
            n_rec += 1
        # --- decisions
        if not decided:
            after = t >= excitation_end
            if drop >= drop_limit or (after and kinetic + potential < -energy_margin):
                status = COLLAPSE
                collapse_time = t
            elif after and kinetic <= rest_energy:
                rest_count += 1
                if rest_count >= (rest_steps if closed else open_rest_steps):
                    moved = max_opening > moved_threshold or max_slip > moved_threshold
                    status = RECOVERY if moved else REST
            else:
                rest_count = 0
            if status >= 0:
                decided = True
                decision_time = t
                if not recording:
                    break
                stop_step = n_steps if tail_steps < 0 else min(n_steps, step + tail_steps + 1)
                if step + 1 >= stop_step:
                    break
        # --- one Moreau-Jean step
        ag = mean_acceleration(t, t + h, kind, params, times, values)
        for i in range(nb):
            v_old[i, 0] = v[i, 0]
            v_old[i, 1] = v[i, 1]
            v_old[i, 2] = v[i, 2]
            v[i, 0] -= h * ag
            v[i, 1] -= h * gravity
        for c in range(nc):
            if valid[c]:
                un, _ = _relative_velocity(v_old, ca[c], cb[c], jac, c)
                active[c] = gap[c] + theta * h * un <= ACTIVATION_GAP * length[c]
            else:
                active[c] = False
        sweeps, converged = solve_active_set(
            v, inv_mass, inv_inertia, ca, cb, jac, active, impulse, state, mu, p_tol, u_tol,
            REGULARISATION, ACTIVE_SET_SOLVES, idx, wmat, amat, rhs, uf)
        if not converged:  # fall back to Gauss-Seidel from the last impulses
            fallbacks += 1
            for c in range(nc):
                if active[c]:
                    _delassus(inv_mass, inv_inertia, ca[c], cb[c], jac, c, w)
            sweeps, converged = solve_contacts(v, inv_mass, inv_inertia, ca, cb, jac, w, active,
                                               impulse, mu, tol_impulse, max_iterations)
        iterations += sweeps
        max_used = max(max_used, sweeps)
        if not converged:
            unconverged += 1
        # --- energy bookkeeping (exact for theta = 1/2) and positions
        contact_work = 0.0
        for c in range(nc):
            if active[c]:
                un0, ut0 = _relative_velocity(v_old, ca[c], cb[c], jac, c)
                un1, ut1 = _relative_velocity(v, ca[c], cb[c], jac, c)
                contact_work += 0.5 * ((un0 + un1) * impulse[c, 0] + (ut0 + ut1) * impulse[c, 1])
        dissipated -= contact_work
        kinetic = 0.0
        for i in range(nb):
            work_input -= masses[i] * h * ag * 0.5 * (v_old[i, 0] + v[i, 0])
            kinetic += 0.5 * (masses[i] * (v[i, 0] ** 2 + v[i, 1] ** 2)
                              + inertias[i] * v[i, 2] ** 2)
            for k in range(3):
                q[i, k] += h * ((1.0 - theta) * v_old[i, k] + theta * v[i, k])
        step += 1
    summary = np.zeros(_N_SUMMARY)
    summary[0] = status
    summary[1] = 1.0 if decided else 0.0
    summary[2] = collapse_time
    summary[3] = decision_time
    summary[4] = max_rotation
    summary[5] = max_crown_drop
    summary[6] = max_slip
    summary[7] = max_opening
    summary[8] = max_drop
    summary[9] = step
    summary[10] = iterations
    summary[11] = max_used
    summary[12] = unconverged
    summary[13] = step * h
    summary[14] = 1.0 if closed else 0.0
    summary[15] = fallbacks
    return summary, (rec_t[:n_rec], rec_q[:n_rec], rec_gap[:n_rec], rec_slip[:n_rec],
                     rec_force[:n_rec], rec_energy[:n_rec])
