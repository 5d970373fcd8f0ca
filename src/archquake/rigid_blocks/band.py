r"""Band solvers of the contact problem: Cholesky's factorisation and Gaussian elimination,
in general and written out for the half-bandwidth of an arch.

Two contacts couple only through a block they both touch, so with the contacts numbered along
the structure the Delassus matrix of the contact problem is a band matrix
(:mod:`archquake.rigid_blocks.contact_problem`, "Contact problem"), of a half-bandwidth that
does not grow with the number of blocks. A band matrix of half-bandwidth ``kl`` is stored by
rows, :math:`A_{ij}` = ``ab[i, j - i + kl]`` for :math:`|j - i| \le kl`, each row zero-padded to
``3 kl + 1`` columns (:func:`band_solve`). The system of the contact problem is solved by
Cholesky's factorisation where no contact slides (it is then symmetric positive definite:
:func:`band_cholesky_solve`), else by Gaussian elimination (:func:`band_lu_solve`), with partial
pivoting should a pivot be small (:func:`band_solve`); for an arch's half-bandwidth,
:data:`ARCH_BANDWIDTH`, the first two are written out (:func:`arch_cholesky_solve`,
:func:`arch_lu_solve`: the same operations, equal bit for bit).

Everything here is ``numba``-compiled without reference counting (``_nrt=False``: the solvers
work in place and allocate nothing). In the short loops the indices are unsigned: numba checks
a signed index for wrapping around at every access, which kept them from being vectorised (1.7
times slower).
"""

from __future__ import annotations

import math

import numba
import numpy as np

ARCH_BANDWIDTH = 7
"""Half-bandwidth of the impulses of an arch's contact problem [-]: each block touches the two
contacts of each of its two joints, so contacts up to 3 apart couple, and the impulses (two per
contact) up to ``2 * 3 + 1``. :func:`~.contact_problem.solve_active_set` solves an arch's
systems with the band solvers written out for this value (:func:`arch_cholesky_solve`,
:func:`arch_lu_solve`), any other structure's with the general ones, to the same results."""


@numba.njit(cache=True, _nrt=False)
def copy_1d(dst, src):
    """``dst[:] = src`` for two vectors of one length, by a loop: numba compiles a slice
    assignment between arrays with the formatting of its shape-mismatch message, seconds of
    every start on a cold cache."""
    for i in range(src.shape[0]):
        dst[i] = src[i]


@numba.njit(cache=True, _nrt=False)
def copy_2d(dst, src):
    """``dst[:, :] = src`` for two matrices of one shape, by loops (:func:`copy_1d`)."""
    for i in range(src.shape[0]):
        for j in range(src.shape[1]):
            dst[i, j] = src[i, j]


@numba.njit(cache=True, _nrt=False)
def band_solve(ab, b, n, kl):
    r"""Solve ``A x = b`` for a band matrix ``A`` (n x n, ``kl`` diagonals below and above the
    main one) by Gaussian elimination with partial pivoting, in place.

    ``A`` is stored by rows, :math:`A_{ij}` = ``ab[i, j - i + kl]`` for :math:`|j - i| \le kl`,
    in an array of at least ``3 kl + 1`` columns whose last ``kl`` are zero: the row
    interchanges widen the upper triangle of the factor to ``2 kl`` diagonals [1]_. The entries
    outside the band are zero and never touched, so the elimination, the pivots and the
    solution are those of the dense algorithm (the same operations in the same order, less the
    ones on zeros): ``(n kl (2 kl))`` operations instead of :math:`n^3 / 3`.

    Parameters
    ----------
    ab : array (>= n, >= 3 kl + 1)
        The band of ``A`` (any units); overwritten by the factor.
    b : array (>= n,)
        Right-hand side; overwritten by ``x`` (in the units of ``b`` over those of ``A``).
    n : int
        Size of the system.
    kl : int
        Half-bandwidth, >= 0.

    References
    ----------
    .. [1] G. H. Golub, C. F. Van Loan, "Matrix computations", 4th ed., Johns Hopkins (2013),
       Sect. 4.3 (band Gaussian elimination with partial pivoting).
    """
    upper = 2 * kl
    for k in range(n):
        last = min(n - 1, k + kl)
        p = k
        big = abs(ab[k, kl])
        for i in range(k + 1, last + 1):
            if abs(ab[i, k - i + kl]) > big:
                big = abs(ab[i, k - i + kl])
                p = i
        right = min(n - 1, k + upper)
        if p != k:
            for j in range(k, right + 1):
                ab[k, j - k + kl], ab[p, j - p + kl] = ab[p, j - p + kl], ab[k, j - k + kl]
            b[k], b[p] = b[p], b[k]
        pivot = ab[k, kl]
        for i in range(k + 1, last + 1):
            f = ab[i, k - i + kl] / pivot
            if f != 0.0:
                for j in range(k + 1, right + 1):
                    ab[i, j - i + kl] -= f * ab[k, j - k + kl]
                b[i] -= f * b[k]
    for k in range(n - 1, -1, -1):
        s = b[k]
        for j in range(k + 1, min(n - 1, k + upper) + 1):
            s -= ab[k, j - k + kl] * b[j]
        b[k] = s / ab[k, kl]


@numba.njit(cache=True, inline="always")
def _back_substitution(ab, b, n, kl):
    """Solve ``U x = y`` in place (``b`` holds ``y``, then ``x``) for the upper factor ``U`` of
    the band solvers, stored by rows with the inverse of its diagonal at ``ab[k, kl]`` and
    :math:`U_{k, k + s}` at ``ab[k, kl + s]``; by columns, unsigned indices
    (:func:`band_cholesky_solve`)."""
    ukl = np.uint64(kl)
    for k in range(n - 1, -1, -1):
        uk = np.uint64(k)
        b[uk] *= ab[uk, ukl]
        xk = b[uk]
        for s in range(1, min(kl, k) + 1):
            us = np.uint64(s)
            b[uk - us] -= ab[uk - us, ukl + us] * xk


@numba.njit(cache=True, _nrt=False)
def band_cholesky_solve(ab, b, n, kl):
    r"""Solve ``A x = b`` for a symmetric positive definite band matrix ``A`` (n x n, ``kl``
    diagonals on either side of the main one) by Cholesky's factorisation
    :math:`A = U^T U` [1]_, in place.

    ``A`` is stored by rows as for :func:`band_solve`, :math:`A_{ij}` =
    ``ab[i, j - i + kl]``; only the upper half (``j >= i``) is read, and it is overwritten by
    ``U``. About :math:`n\,kl^2 / 2` operations, no pivoting. Every loop runs along a row (the
    factorisation right-looking, the substitutions by columns), so that the innermost
    operations are independent of one another.

    Parameters
    ----------
    ab : array (>= n, >= 2 kl + 1)
        The band of ``A``; its upper half is overwritten by ``U``.
    b : array (>= n,)
        Right-hand side; overwritten by ``x``.
    n : int
        Size of the system.
    kl : int
        Half-bandwidth, >= 0.

    Returns
    -------
    bool
        False if a pivot is not positive (``A`` is not positive definite to round-off): ``ab``
        and ``b`` are then spoilt.

    References
    ----------
    .. [1] G. H. Golub, C. F. Van Loan, "Matrix computations", 4th ed., Johns Hopkins (2013),
       Sect. 4.3.5 (band Cholesky).
    """
    # unsigned indices: numba checks a signed index for wrapping around (a negative index
    # counts from the end), which keeps these short loops from being vectorised (measured:
    # 1.7 times slower); the rows are padded with zeros (at least 3 kl + 1 columns), so that
    # every update runs over kl + 1 entries whatever the row
    ukl = np.uint64(kl)
    for k in range(n):
        uk = np.uint64(k)
        d = ab[uk, ukl]
        if not d > 0.0:
            return False
        inverse = 1.0 / math.sqrt(d)
        ab[uk, ukl] = inverse  # the diagonal keeps 1 / U_kk: a product, not a division, below
        for t in range(1, kl + 1):
            ab[uk, ukl + np.uint64(t)] *= inverse
        for s in range(1, min(kl, n - 1 - k) + 1):
            us = np.uint64(s)
            f = ab[uk, ukl + us]
            if f != 0.0:
                ui = uk + us
                for t in range(kl + 1):
                    ut = np.uint64(t)
                    ab[ui, ukl + ut] -= f * ab[uk, ukl + us + ut]
    for k in range(n):  # U^T y = b
        uk = np.uint64(k)
        b[uk] *= ab[uk, ukl]
        yk = b[uk]
        for s in range(1, min(kl, n - 1 - k) + 1):
            us = np.uint64(s)
            b[uk + us] -= ab[uk, ukl + us] * yk
    _back_substitution(ab, b, n, kl)
    return True


@numba.njit(cache=True, _nrt=False)
def band_lu_solve(ab, b, n, kl, scale):
    r"""Solve ``A x = b`` for a band matrix ``A`` (n x n, ``kl`` diagonals on either side of
    the main one) by Gaussian elimination without pivoting, in place; False if a pivot falls
    below ``1e-10`` times its row's ``scale`` (the caller then pivots, :func:`band_solve`).

    ``A`` is stored by rows as for :func:`band_solve`, zero-padded to ``3 kl + 1`` columns;
    ``ab`` and ``b`` are overwritten by the factors and by ``x``. About :math:`n\,kl^2`
    operations, in loops of ``kl`` independent updates (see :func:`band_cholesky_solve`).

    Parameters
    ----------
    ab : array (>= n, >= 3 kl + 1)
        The band of ``A``; overwritten.
    b : array (>= n,)
        Right-hand side; overwritten by ``x``.
    n : int
        Size of the system.
    kl : int
        Half-bandwidth, >= 0.
    scale : array (>= n,)
        A positive size of every row (its diagonal) [units of ``A``].

    Returns
    -------
    bool
        Whether every pivot was large enough (if not, ``ab`` and ``b`` are spoilt).
    """
    ukl = np.uint64(kl)
    for k in range(n):
        uk = np.uint64(k)
        pivot = ab[uk, ukl]
        if not abs(pivot) > 1e-10 * scale[uk]:
            return False
        inverse = 1.0 / pivot
        ab[uk, ukl] = inverse  # the diagonal keeps 1 / U_kk: a product, not a division, below
        for s in range(1, min(kl, n - 1 - k) + 1):
            us = np.uint64(s)
            ui = uk + us
            f = ab[ui, ukl - us] * inverse
            if f != 0.0:
                for t in range(1, kl + 1):
                    ut = np.uint64(t)
                    ab[ui, ukl - us + ut] -= f * ab[uk, ukl + ut]
                b[ui] -= f * b[uk]
    _back_substitution(ab, b, n, kl)
    return True


@numba.njit(cache=True, _nrt=False)
def arch_cholesky_solve(ab, b, n):
    r""":func:`band_cholesky_solve` for the half-bandwidth of an arch, :data:`ARCH_BANDWIDTH` = 7,
    written out: the same operations in the same order on the same numbers (the results are
    equal bit for bit, tested), with the forward substitution done row by row as the factor
    is made, and nothing read outside the upper band (columns 7 to 14; the padding is not
    needed). Row ``k`` of the factor is held in registers while it updates the seven rows
    below it, which the loops over a band of a known length did not manage (measured: the
    factorisation and substitutions of 32 unknowns take 1.3 us instead of 1.7)."""
    for k in range(n):
        d = ab[k, 7]
        if not d > 0.0:
            return False
        inverse = 1.0 / math.sqrt(d)
        ab[k, 7] = inverse
        r1 = ab[k, 8] * inverse
        r2 = ab[k, 9] * inverse
        r3 = ab[k, 10] * inverse
        r4 = ab[k, 11] * inverse
        r5 = ab[k, 12] * inverse
        r6 = ab[k, 13] * inverse
        r7 = ab[k, 14] * inverse
        ab[k, 8] = r1
        ab[k, 9] = r2
        ab[k, 10] = r3
        ab[k, 11] = r4
        ab[k, 12] = r5
        ab[k, 13] = r6
        ab[k, 14] = r7
        b[k] *= inverse  # U^T y = b, row k
        yk = b[k]
        below = n - 1 - k
        if below >= 1:
            i = k + 1
            ab[i, 7] -= r1 * r1
            ab[i, 8] -= r1 * r2
            ab[i, 9] -= r1 * r3
            ab[i, 10] -= r1 * r4
            ab[i, 11] -= r1 * r5
            ab[i, 12] -= r1 * r6
            ab[i, 13] -= r1 * r7
            b[i] -= r1 * yk
        if below >= 2:
            i = k + 2
            ab[i, 7] -= r2 * r2
            ab[i, 8] -= r2 * r3
            ab[i, 9] -= r2 * r4
            ab[i, 10] -= r2 * r5
            ab[i, 11] -= r2 * r6
            ab[i, 12] -= r2 * r7
            b[i] -= r2 * yk
        if below >= 3:
            i = k + 3
            ab[i, 7] -= r3 * r3
            ab[i, 8] -= r3 * r4
            ab[i, 9] -= r3 * r5
            ab[i, 10] -= r3 * r6
            ab[i, 11] -= r3 * r7
            b[i] -= r3 * yk
        if below >= 4:
            i = k + 4
            ab[i, 7] -= r4 * r4
            ab[i, 8] -= r4 * r5
            ab[i, 9] -= r4 * r6
            ab[i, 10] -= r4 * r7
            b[i] -= r4 * yk
        if below >= 5:
            i = k + 5
            ab[i, 7] -= r5 * r5
            ab[i, 8] -= r5 * r6
            ab[i, 9] -= r5 * r7
            b[i] -= r5 * yk
        if below >= 6:
            i = k + 6
            ab[i, 7] -= r6 * r6
            ab[i, 8] -= r6 * r7
            b[i] -= r6 * yk
        if below >= 7:
            i = k + 7
            ab[i, 7] -= r7 * r7
            b[i] -= r7 * yk
    _back_substitution(ab, b, n, 7)
    return True


@numba.njit(cache=True, _nrt=False)
def arch_lu_solve(ab, b, n, scale):
    r""":func:`band_lu_solve` for the half-bandwidth of an arch, :data:`ARCH_BANDWIDTH` = 7,
    written out as :func:`arch_cholesky_solve`: the same operations in the same order (equal bit for
    bit, tested), row ``k`` of ``U`` held in registers while it updates the seven rows below
    it. Elimination without pivoting reads and writes the band only, never its padding."""
    for k in range(n):
        pivot = ab[k, 7]
        if not abs(pivot) > 1e-10 * scale[k]:
            return False
        inverse = 1.0 / pivot
        ab[k, 7] = inverse
        u1 = ab[k, 8]
        u2 = ab[k, 9]
        u3 = ab[k, 10]
        u4 = ab[k, 11]
        u5 = ab[k, 12]
        u6 = ab[k, 13]
        u7 = ab[k, 14]
        bk = b[k]
        below = n - 1 - k
        if below >= 1:
            i = k + 1
            f = ab[i, 6] * inverse
            if f != 0.0:
                ab[i, 7] -= f * u1
                ab[i, 8] -= f * u2
                ab[i, 9] -= f * u3
                ab[i, 10] -= f * u4
                ab[i, 11] -= f * u5
                ab[i, 12] -= f * u6
                ab[i, 13] -= f * u7
                b[i] -= f * bk
        if below >= 2:
            i = k + 2
            f = ab[i, 5] * inverse
            if f != 0.0:
                ab[i, 6] -= f * u1
                ab[i, 7] -= f * u2
                ab[i, 8] -= f * u3
                ab[i, 9] -= f * u4
                ab[i, 10] -= f * u5
                ab[i, 11] -= f * u6
                ab[i, 12] -= f * u7
                b[i] -= f * bk
        if below >= 3:
            i = k + 3
            f = ab[i, 4] * inverse
            if f != 0.0:
                ab[i, 5] -= f * u1
                ab[i, 6] -= f * u2
                ab[i, 7] -= f * u3
                ab[i, 8] -= f * u4
                ab[i, 9] -= f * u5
                ab[i, 10] -= f * u6
                ab[i, 11] -= f * u7
                b[i] -= f * bk
        if below >= 4:
            i = k + 4
            f = ab[i, 3] * inverse
            if f != 0.0:
                ab[i, 4] -= f * u1
                ab[i, 5] -= f * u2
                ab[i, 6] -= f * u3
                ab[i, 7] -= f * u4
                ab[i, 8] -= f * u5
                ab[i, 9] -= f * u6
                ab[i, 10] -= f * u7
                b[i] -= f * bk
        if below >= 5:
            i = k + 5
            f = ab[i, 2] * inverse
            if f != 0.0:
                ab[i, 3] -= f * u1
                ab[i, 4] -= f * u2
                ab[i, 5] -= f * u3
                ab[i, 6] -= f * u4
                ab[i, 7] -= f * u5
                ab[i, 8] -= f * u6
                ab[i, 9] -= f * u7
                b[i] -= f * bk
        if below >= 6:
            i = k + 6
            f = ab[i, 1] * inverse
            if f != 0.0:
                ab[i, 2] -= f * u1
                ab[i, 3] -= f * u2
                ab[i, 4] -= f * u3
                ab[i, 5] -= f * u4
                ab[i, 6] -= f * u5
                ab[i, 7] -= f * u6
                ab[i, 8] -= f * u7
                b[i] -= f * bk
        if below >= 7:
            i = k + 7
            f = ab[i, 0] * inverse
            if f != 0.0:
                ab[i, 1] -= f * u1
                ab[i, 2] -= f * u2
                ab[i, 3] -= f * u3
                ab[i, 4] -= f * u4
                ab[i, 5] -= f * u5
                ab[i, 6] -= f * u6
                ab[i, 7] -= f * u7
                b[i] -= f * bk
    _back_substitution(ab, b, n, 7)
    return True
