r"""Lemke's complementary pivoting on the contact problem: the fallback that cannot cycle.

The contact problem of a step (:mod:`archquake.rigid_blocks.contact_problem`, "Contact
problem") asks, for the ``m`` active contacts with Delassus matrix ``W`` (2m x 2m, symmetric
positive semidefinite) and free velocities :math:`u^f`, for impulses ``P = (P_n, P_t)`` with
:math:`u = u^f + W P` and

.. math::

    0 \le u_n \perp P_n \ge 0, \qquad |P_t| \le \mu P_n, \qquad
    u_t \ne 0 \Rightarrow P_t = -\mu P_n \operatorname{sign}(u_t).

In two dimensions Coulomb's cone is a pair of half-planes, so the problem is *exactly* a linear
complementarity problem (Stewart and Trinkle's [1]_ formulation, with no facetting error):
writing :math:`P_t = \beta^+ - \beta^-` and with :math:`\lambda` the magnitude of the slip
velocity,

.. math::

    w = \begin{pmatrix} u_n \\ \lambda + u_t \\ \lambda - u_t \\ \mu P_n - \beta^+ - \beta^-
    \end{pmatrix} = q + M z, \qquad
    z = \begin{pmatrix} P_n \\ \beta^+ \\ \beta^- \\ \lambda \end{pmatrix}, \qquad
    0 \le w \perp z \ge 0,

    M = \begin{pmatrix} W_{nn} & W_{nt} & -W_{nt} & 0 \\ W_{tn} & W_{tt} & -W_{tt} & E \\
    -W_{tn} & -W_{tt} & W_{tt} & E \\ \mu E & -E & -E & 0 \end{pmatrix}, \qquad
    q = \begin{pmatrix} u^f_n \\ u^f_t \\ -u^f_t \\ 0 \end{pmatrix}

(``E`` the identity): a contact that slides forward has :math:`\lambda = u_t > 0`, hence
:math:`\beta^+ = 0` and :math:`\beta^- = \mu P_n`; one that sticks :math:`\lambda = 0` and
:math:`u_t = 0`.

Why it has a solution, and why Lemke's algorithm finds it: the solver adds a compliance
:math:`\rho` (:data:`archquake.rigid_blocks.contact_problem.REGULARISATION`, relative to the
diagonal) to ``W``, which makes it positive definite (two contacts per joint make ``W`` itself
singular: four impulses for three relative motions), and here the same :math:`\rho` to the last
diagonal block, :math:`\mu P_n - \beta^+ - \beta^- + \rho \lambda \ge 0` (a friction force that may
exceed Coulomb's by :math:`\rho` times the slip rate, in the scaled units below: nothing a
double can hold beside the impulses). Then ``M`` is copositive-plus: :math:`z^T M z = P^T W P
+ \mu P_n \lambda + \rho \lambda^2 \ge 0` for :math:`z \ge 0` (the coupling of
:math:`\lambda` with :math:`\beta` cancels), and :math:`z^T M z = 0` leaves only
:math:`\beta^+ = \beta^-`, for which :math:`(M + M^T) z = 0`. And the problem is feasible: with
the frictionless impulses :math:`P_n \ge 0` (the LCP of the positive definite
:math:`W_{nn}`), :math:`\beta = 0` and :math:`\lambda` large, :math:`q + M z \ge 0`. Lemke's
algorithm with the lexicographic ratio test [3]_ visits no basis twice, and on a feasible
problem with a copositive-plus matrix it ends on a solution ([3]_, Thm. 4.4.13; Anitescu and
Potra [2]_ for the time-stepping problems of rigid bodies).

In floating point the singular ``W`` makes the tableau ill-conditioned (:math:`1/\rho`): the
solver hands Lemke's algorithm the problem with the compliance :data:`LEMKE_COMPLIANCE`
(1e-5), and solves the states it finds again at its own 1e-9 with the active-set method. The
tableau is computed afresh from its basis before a ray is accepted and at the end, and every
solution is checked against the problem as stated (:data:`ACCURACY`). Should round-off still
spoil an attempt (a ray or an inaccurate solution), it is made again with another covering
vector and then with ten and a hundred times the compliance (:data:`RETRY_FACTORS`).

Cost: the algorithm is written on a dense tableau of ``4 m`` rows (``m`` active contacts) and
``8 m + 2`` columns, one pivot costing about :math:`32 m^2` operations, and it takes about 1.5
pivots per row: 45 ms for the 74-98 active contacts of Oppenheim's arch cut into 50 voussoirs
(``benchmarks/rigid_block_contact_solver.py``). The solver uses it only where its active-set
method gave up.

The velocities and impulses are scaled by the mean diagonal of ``W`` so that every entry of the
tableau is of order one, and the tests of the pivots are relative.

References
----------
.. [1] D. E. Stewart, J. C. Trinkle, "An implicit time-stepping scheme for rigid body dynamics
   with inelastic collisions and Coulomb friction", Int. J. Numer. Methods Eng. 39 (1996)
   2673-2691.

.. [2] M. Anitescu, F. A. Potra, "Formulating dynamic multi-rigid-body contact problems with
   friction as solvable linear complementarity problems", Nonlinear Dynamics 14 (1997) 231-247.

.. [3] R. W. Cottle, J.-S. Pang, R. E. Stone, "The linear complementarity problem", Academic
   Press (1992), Sect. 4.4 (Lemke's method) and 4.9 (lexicographic degeneracy resolution).
"""

from __future__ import annotations

import numba
import numpy as np

from .band import copy_2d

PIVOT_TOLERANCE = 1e-11
"""A tableau entry smaller than this times the largest of its column is taken as zero in the
ratio test [-] (entries are of order one after scaling)."""

TIE_TOLERANCE = 1e-12
"""Ratios within this (relative) of the smallest are ties, broken lexicographically [-]."""

MAX_PIVOTS_PER_ROW = 50
"""Largest number of pivots per row of the tableau before the algorithm gives up [-] (never
reached in the tests; a guard against round-off loops)."""

LEMKE_COMPLIANCE = 1e-5
"""Compliance of the problem that Lemke's algorithm solves for the solver [-] (relative to the
diagonal of ``W``, and on the slip rate): larger than the solver's own (1e-9), since the
tableau's round-off grows with the inverse of the compliance (on the 79 problems at which the
active-set method gave up on the 50-voussoir arch: 79 solved at the first attempt in 25,900
pivots at 1e-5, 54 in 45,700 at 1e-9). The solver solves the states found again at its own
compliance (:func:`archquake.rigid_blocks.contact_problem.solve_lemke`)."""

RETRY_FACTORS = (1.0, 10.0, 100.0)
"""Factors of the compliance tried in turn, each with two covering vectors, should round-off
spoil an attempt of Lemke's algorithm (a ray or an inaccurate solution) [-]."""

ACCURACY = 1e-8
"""Largest violation of the LCP by a solution that :func:`lemke` returns, relative to the
largest entry of ``q`` [-]: a basis found on a nearly singular tableau can hold a solution that
round-off has spoilt, which is then refused (:data:`LEMKE_INACCURATE`)."""

LEMKE_SOLVED, LEMKE_RAY, LEMKE_PIVOTS, LEMKE_INACCURATE = 0, 1, 2, 3
"""Outcomes of :func:`lemke`: solved, ended on a secondary ray (no solution found: not reached
in exact arithmetic for the contact problem, module docstring), too many pivots, a solution
spoilt by round-off (:data:`ACCURACY`)."""


@numba.njit(cache=True)
def _pivot(tab, r, e):
    """Gauss-Jordan pivot of the tableau on row ``r``, column ``e``."""
    n_rows, n_cols = tab.shape
    inv = 1.0 / tab[r, e]
    for j in range(n_cols):
        tab[r, j] *= inv
    for i in range(n_rows):
        if i == r:
            continue
        f = tab[i, e]
        if f != 0.0:
            for j in range(n_cols):
                tab[i, j] -= f * tab[r, j]
            tab[i, e] = 0.0


@numba.njit(cache=True)
def _refactor(tab, original, basis):
    """The tableau computed afresh from the original one and the basis: ``B^-1 A`` with ``B``
    the basic columns of ``A`` (the round-off of the pivots so far is dropped), by Gaussian
    elimination with partial pivoting. Returns False, leaving ``tab`` spoilt, if ``B`` is
    singular to working precision (a pivot below ``1e-14`` of the largest entry of ``B``)."""
    n = basis.size
    nc = original.shape[1]
    b = np.empty((n, n))
    for k in range(n):
        for i in range(n):
            b[i, k] = original[i, basis[k]]
    copy_2d(tab, original)
    big = 0.0
    for i in range(n):
        for j in range(n):
            big = max(big, abs(b[i, j]))
    for k in range(n):
        p = k
        for i in range(k + 1, n):
            if abs(b[i, k]) > abs(b[p, k]):
                p = i
        if not abs(b[p, k]) > 1e-14 * big:
            return False
        if p != k:
            for j in range(n):
                b[k, j], b[p, j] = b[p, j], b[k, j]
            for j in range(nc):
                tab[k, j], tab[p, j] = tab[p, j], tab[k, j]
        inv = 1.0 / b[k, k]
        for i in range(k + 1, n):
            f = b[i, k] * inv
            if f != 0.0:
                for j in range(k, n):
                    b[i, j] -= f * b[k, j]
                for j in range(nc):
                    tab[i, j] -= f * tab[k, j]
    for k in range(n - 1, -1, -1):
        inv = 1.0 / b[k, k]
        for j in range(nc):
            tab[k, j] *= inv
        for i in range(k):
            f = b[i, k]
            if f != 0.0:
                for j in range(nc):
                    tab[i, j] -= f * tab[k, j]
                b[i, k] = 0.0
        for j in range(k + 1, n):  # row k of b is now e_k scaled: only the diagonal mattered
            b[k, j] = 0.0
    return True


@numba.njit(cache=True)
def _accurate(mat, q, z):
    """Whether ``z`` solves the LCP to :data:`ACCURACY`: ``w = q + M z`` not below
    ``-ACCURACY max|q|``, and ``w_i z_i`` not above ``ACCURACY max|q| max(z, 1)``."""
    n = q.size
    scale = 0.0
    big = 1.0
    for i in range(n):
        scale = max(scale, abs(q[i]))
        big = max(big, z[i])
    for i in range(n):
        w = q[i]
        for j in range(n):
            w += mat[i, j] * z[j]
        if w < -ACCURACY * scale or w * z[i] > ACCURACY * scale * big:
            return False
    return True


@numba.njit(cache=True)
def lemke(mat, q, cover):
    r"""Solve the linear complementarity problem :math:`w = q + M z`, :math:`0 \le w \perp z
    \ge 0` by Lemke's algorithm with the covering vector ``cover`` and the lexicographic ratio
    test (Cottle, Pang and Stone: the module docstring).

    The tableau is computed afresh from its basis before a ray is accepted and at the end, so
    that the round-off of many pivots does not decide; the solution is checked against the
    problem (:data:`ACCURACY`).

    Parameters
    ----------
    mat : array (n, n)
        The matrix ``M``.
    q : array (n,)
        The vector ``q``.
    cover : array (n,)
        The covering vector ``d > 0``.

    Returns
    -------
    z : array (n,)
        The solution (meaningful if ``code`` is :data:`LEMKE_SOLVED`).
    code : int
        :data:`LEMKE_SOLVED`, :data:`LEMKE_RAY`, :data:`LEMKE_PIVOTS` or
        :data:`LEMKE_INACCURATE`.
    pivots : int
        Pivots made.
    """
    n = q.size
    z = np.zeros(n)
    if n == 0 or q.min() >= 0.0:
        return z, LEMKE_SOLVED, 0
    # columns: w (0..n-1), z (n..2n-1), z0 (2n), rhs (2n+1); I w - M z - d z0 = q
    nc = 2 * n + 2
    original = np.zeros((n, nc))
    for i in range(n):
        original[i, i] = 1.0
        for j in range(n):
            original[i, n + j] = -mat[i, j]
        original[i, 2 * n] = -cover[i]
        original[i, nc - 1] = q[i]
    tab = original.copy()
    basis = np.arange(n)
    z0 = 2 * n
    r = np.argmin(q / cover)  # an int64 (a literal 0 would compile _pivot twice)
    _pivot(tab, r, z0)
    leaving = basis[r]
    basis[r] = z0
    entering = n + leaving  # the complement of w_r
    candidates = np.empty(n, dtype=np.int64)
    pivots = 1
    limit = MAX_PIVOTS_PER_ROW * n
    refreshed = False
    while pivots < limit:
        col_max = 0.0
        for i in range(n):
            col_max = max(col_max, abs(tab[i, entering]))
        threshold = PIVOT_TOLERANCE * col_max
        # ratio test on the right-hand side (a basic value below 0 by round-off counts as 0)
        best = np.inf
        for i in range(n):
            if tab[i, entering] > threshold:
                best = min(best, max(tab[i, nc - 1], 0.0) / tab[i, entering])
        if best == np.inf:
            if refreshed or not _refactor(tab, original, basis):  # a ray, or round-off?
                return z, LEMKE_RAY, pivots
            refreshed = True
            continue
        refreshed = False
        count = 0
        slack = TIE_TOLERANCE * max(1.0, abs(best))
        z0_row = -1
        for i in range(n):
            if (tab[i, entering] > threshold
                    and max(tab[i, nc - 1], 0.0) / tab[i, entering] <= best + slack):
                candidates[count] = i
                count += 1
                if basis[i] == z0:
                    z0_row = i
        if z0_row >= 0:
            r = z0_row
        else:
            # lexicographic: the columns of B^-1 (those of w) break the ties in turn
            col = 0
            while count > 1 and col < n:
                low = np.inf
                for k in range(count):
                    i = candidates[k]
                    low = min(low, tab[i, col] / tab[i, entering])
                kept = 0
                for k in range(count):
                    i = candidates[k]
                    if tab[i, col] / tab[i, entering] <= low + TIE_TOLERANCE:
                        candidates[kept] = i
                        kept += 1
                count = kept
                col += 1
            r = candidates[0]
        _pivot(tab, r, entering)
        pivots += 1
        leaving = basis[r]
        basis[r] = entering
        if leaving == z0:
            if not _refactor(tab, original, basis):
                return z, LEMKE_INACCURATE, pivots
            for i in range(n):
                b = basis[i]
                if n <= b < 2 * n:
                    z[b - n] = max(tab[i, nc - 1], 0.0)
            if not _accurate(mat, q, z):
                return z, LEMKE_INACCURATE, pivots
            return z, LEMKE_SOLVED, pivots
        entering = leaving + n if leaving < n else leaving - n
    return z, LEMKE_PIVOTS, pivots


@numba.njit(cache=True)
def contact_lcp(w, uf, mu, compliance):
    r"""The LCP of the contact problem (module docstring), scaled.

    Parameters
    ----------
    w : array (2m, 2m)
        The Delassus matrix ``W``, rows ``2 i`` normal and ``2 i + 1`` tangential of the
        ``i``-th active contact [m/kg].
    uf : array (2m,)
        Free velocities [m/s].
    mu : array (m,)
        Friction coefficient of every active contact [-].
    compliance : float
        Added to the diagonal of ``W``, relative to it, and on the slip rate [-].

    Returns
    -------
    mat, q : arrays (4m, 4m), (4m,)
        ``M`` and ``q`` with velocities divided by the mean diagonal ``s`` of ``W`` (every
        variable then in N s/m: :math:`\lambda` is scaled by ``1/s``).
    scale : float
        ``s`` [m/kg].
    """
    m = uf.size // 2
    s = 0.0
    for r in range(2 * m):
        s += w[r, r]
    s = s / max(2 * m, 1)
    if s <= 0.0:
        s = 1.0
    mat = np.zeros((4 * m, 4 * m))
    q = np.zeros(4 * m)
    for i in range(m):
        for j in range(m):
            wnn = w[2 * i, 2 * j] / s
            wnt = w[2 * i, 2 * j + 1] / s
            wtn = w[2 * i + 1, 2 * j] / s
            wtt = w[2 * i + 1, 2 * j + 1] / s
            if i == j:
                wnn *= 1.0 + compliance
                wtt *= 1.0 + compliance
            mat[i, j] = wnn
            mat[i, m + j] = wnt
            mat[i, 2 * m + j] = -wnt
            mat[m + i, j] = wtn
            mat[m + i, m + j] = wtt
            mat[m + i, 2 * m + j] = -wtt
            mat[2 * m + i, j] = -wtn
            mat[2 * m + i, m + j] = -wtt
            mat[2 * m + i, 2 * m + j] = wtt
        mat[m + i, 3 * m + i] = 1.0
        mat[2 * m + i, 3 * m + i] = 1.0
        mat[3 * m + i, i] = mu[i]
        mat[3 * m + i, m + i] = -1.0
        mat[3 * m + i, 2 * m + i] = -1.0
        mat[3 * m + i, 3 * m + i] = compliance
        q[i] = uf[2 * i] / s
        q[m + i] = uf[2 * i + 1] / s
        q[2 * m + i] = -uf[2 * i + 1] / s
    return mat, q, s


@numba.njit(cache=True)
def solve_contact_lcp(w, uf, mu, compliance, impulses, states):
    """Solve the contact problem by Lemke's algorithm (module docstring).

    Parameters
    ----------
    w, uf, mu, compliance
        As for :func:`contact_lcp`.
    impulses : array (2m,)
        Out: ``(P_n, P_t)`` of every active contact [N s/m]; an open contact's 0 and a sliding
        one's on the cone exactly (the friction of the compliance on the slip rate dropped).
    states : array of int (m,)
        Out: the state of every contact in the solver's code: 0 open, 1 stick, 2 slide with
        ``P_t = +mu P_n``, 3 with ``P_t = -mu P_n``.

    Returns
    -------
    code : int
        :data:`LEMKE_SOLVED`, :data:`LEMKE_RAY` or :data:`LEMKE_PIVOTS`.
    pivots : int
        Pivots made.
    """
    m = uf.size // 2
    pivots = 0
    code = LEMKE_RAY
    for attempt in range(2 * len(RETRY_FACTORS)):
        mat, q, s = contact_lcp(w, uf, mu, compliance * RETRY_FACTORS[attempt // 2])
        cover = np.ones(q.size)
        if attempt % 2 == 1:  # another path: the covering vector of a perturbed q
            for i in range(q.size):
                cover[i] = 1.0 + 0.5 * ((i * 7919) % 13) / 13.0
        z, code, used = lemke(mat, q, cover)
        pivots += used
        if code == LEMKE_SOLVED:
            break
    if code != LEMKE_SOLVED:
        return code, pivots
    # the largest impulse sets the scale below which an impulse is zero
    big = 0.0
    for i in range(m):
        big = max(big, z[i])
    tiny = 1e-12 * big
    for i in range(m):
        pn = z[i]
        pt = z[m + i] - z[2 * m + i]
        slip = z[3 * m + i]
        if pn <= tiny:  # open (a friction impulse of rho lambda dropped)
            states[i] = 0
            pn = pt = 0.0
        elif slip > tiny:  # sliding: on the cone exactly (rho lambda dropped)
            states[i] = 2 if pt > 0.0 else 3
            pt = mu[i] * pn if pt > 0.0 else -mu[i] * pn
        else:
            states[i] = 1
        impulses[2 * i] = pn
        impulses[2 * i + 1] = pt
    return code, pivots
