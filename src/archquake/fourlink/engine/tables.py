r"""Tables of a mechanism's coefficients and their compiled evaluation.

:func:`tabulate` samples a mechanism once, as piecewise polynomials (degree 9, interpolation at
Chebyshev points, 1e-12 relative accuracy) on :math:`[\theta_{lo}, \theta_u]`: the ratios
:math:`P/M` [1/m], :math:`gF/M` [1/s^2] and :math:`L/M` [-] that make up the right-hand side of
Eqs. (6) and (7) in [1]_ solved for :math:`\ddot\theta`,

.. math::

    \ddot\theta = s\,\frac{P}{M}\,\ddot x_g - \frac{gF}{M} - \frac{L}{M}\,\dot\theta^2,
    \qquad s = +1 \text{ (Mech-l)}, \; -1 \text{ (Mech-r)},

(no division while integrating), and the generalised mass :math:`M` [kg m^2/m] and the
potential energy :math:`V` [J/m] of Eq. (3) in [1]_ for the energy rules. Nothing about the
linkage is recomputed while integrating, and one table serves every analysis of that arch.
:func:`pack_pair` stacks the tables of Mech-l and Mech-r into the tuple the compiled driver takes.

The exact functions come from :mod:`archquake.fourlink.equations_of_motion` (:math:`M, L, F, P`) and
:meth:`archquake.fourlink.mechanism.FourLinkMechanism.potential_energy` (:math:`V`): the tables hold
no physics of their own.

References
----------
.. [1] The paper, Sect. 4.2, Eq. (3), and Sect. 4.3, Eqs. (6)-(7).
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numba
import numpy as np

from ...constants import GRAVITY
from ._types import F8, F8_1D, F8_3D, I8, I8_1D, PACKED_PAIR
from .codes import MECH_L

TABLE_DEGREE = 9
"""Degree of every polynomial piece of a :class:`MechanismTable`."""
TABLE_TOLERANCE = 1e-12
"""Target interpolation error of a table, relative to the largest magnitude of each function."""
TABLE_MAX_CELLS = 4096
"""Largest number of equal cells of the lookup from ``theta`` to its piece."""

TABLE_FUNCTIONS = ("P/M", "gF/M", "L/M", "M", "V")
"""Functions of a :class:`MechanismTable`, in the order of its rows: the three ratios of the
right-hand side ``theta'' = s P/M xg'' - gF/M - L/M theta'^2`` (``s = +1`` for Mech-l, ``-1`` for
Mech-r), then ``M`` and ``V`` for the energy rules."""
ROW_B, ROW_M, ROW_V, ROW_MAP = 1, 3, 4, 5  # rows 0-2 are read together by table_rhs

_SIG_TABLE_VALUE = F8(F8, I8, F8, F8, I8_1D, F8_1D, F8_3D)
_SIG_TABLE_FUNCTION = F8(F8, I8, I8, PACKED_PAIR)
_SIG_ROOT_FUNCTION = F8(I8, F8, F8, F8, I8, PACKED_PAIR)


@dataclass(frozen=True, eq=False)
class MechanismTable:
    """Coefficients of one mechanism as piecewise polynomials in ``theta``.

    Every piece ``[a, b]`` holds, for each function of :data:`TABLE_FUNCTIONS`, the monomial
    coefficients of its interpolant at Chebyshev points in the local variable
    ``x = (theta - (a + b)/2) / ((b - a)/2)`` in ``[-1, 1]`` (evaluated by Horner's rule); the
    pieces come from bisecting ``[theta_lo, theta_u]`` until each meets the tolerance, and a
    table of equal cells finds the piece of any ``theta`` without a search.

    Parameters
    ----------
    theta_u : float
        Undisplaced configuration [rad].
    theta_cr : float
        Critical angle [rad]: the maximum of the potential energy, where ``dV/d theta = g F``
        vanishes (Sect. 4.2 of the paper, Eq. (4)); ``theta_lo`` when the mechanism has no
        maximum inside the table (gravity then resists the motion down to the kinematic limit).
    theta_lo : float
        Lower end of the table [rad]: the kinematic limit of the linkage (reaching it during the
        excitation is collapse).
    activation_g : float
        Activation multiplier ``k = -F(theta_u)/P(theta_u)`` [-] (the ground acceleration in g
        that opens the mechanism, Eq. (2) of the paper), from the tabulated ``P/M`` and ``gF/M``.
    direction : str
        ``"l"`` (Mech-l) or ``"r"`` (Mech-r).
    breaks : ndarray, shape (pieces + 1,)
        Ends of the pieces [rad], increasing from ``theta_lo`` to ``theta_u``.
    coefficients : ndarray, shape (pieces, 6, TABLE_DEGREE + 1)
        Rows 0-4: monomial coefficients of ``P/M`` [1/m], ``gF/M`` [1/s^2], ``L/M`` [-], ``M``
        [kg m^2/m] and ``V`` [J/m] on every piece; row 5: ``(centre, 1/half-width)`` of the
        piece [rad, 1/rad], then zeros.
    cells : ndarray of int, shape (n_cells + 1,)
        ``cells[c]``: the piece holding the start of cell ``c`` of ``n_cells`` equal cells of
        ``[theta_lo, theta_u]``; ``cells[n_cells]`` is the last piece.
    max_error : ndarray, shape (5,)
        Largest interpolation error found on a check grid, relative to the largest magnitude of
        each function on the table [-].
    """

    theta_u: float
    theta_cr: float
    theta_lo: float
    activation_g: float
    direction: str
    breaks: np.ndarray
    coefficients: np.ndarray
    cells: np.ndarray
    max_error: np.ndarray

    @property
    def pieces(self) -> int:
        """Number of polynomial pieces."""
        return self.breaks.size - 1

    @property
    def n_cells(self) -> int:
        """Number of equal cells of the piece lookup."""
        return self.cells.size - 1

    def functions(self, theta) -> np.ndarray:
        """The tabulated functions at ``theta``.

        Parameters
        ----------
        theta : float or array_like
            Lagrangian coordinate [rad], in ``[theta_lo, theta_u]`` (outside it the end piece is
            extrapolated).

        Returns
        -------
        ndarray, shape ``(5,) + shape(theta)``
            ``P/M`` [1/m], ``gF/M`` [1/s^2], ``L/M`` [-], ``M`` [kg m^2/m] and ``V`` [J/m].
        """
        theta = np.asarray(theta, dtype=float)
        flat = np.ascontiguousarray(theta.ravel())
        out = np.empty((5, flat.size))
        inv_cell = self.n_cells / (self.theta_u - self.theta_lo)
        # writable copies: the compiled helpers are declared for writable arrays (the table's
        # own arrays are read-only)
        _evaluate_table(flat, self.theta_lo, inv_cell, self.cells.copy(), self.breaks.copy(),
                        self.coefficients.copy(), out)
        return out.reshape((5,) + theta.shape)

    def evaluate(self, theta) -> np.ndarray:
        """The coefficients of the equation of motion and the potential energy at ``theta``.

        Parameters
        ----------
        theta : float or array_like
            Lagrangian coordinate [rad].

        Returns
        -------
        ndarray, shape ``(5,) + shape(theta)``
            ``M`` [kg m^2/m], ``L`` [kg m^2/m], ``F`` [kg m/m], ``P`` [kg m/m] (rebuilt from
            the tabulated ratios and ``M``) and ``V`` [J/m].
        """
        a, b, c, m, v = self.functions(theta)
        return np.stack([m, c * m, b * m / GRAVITY, a * m, v])

    def potential_energy(self, theta):
        """Interpolated potential energy of eq. (3) of the paper at ``theta``.

        Parameters
        ----------
        theta : float or array_like
            Lagrangian coordinate [rad].

        Returns
        -------
        ndarray
            ``V`` [J/m], of the shape of ``theta``.
        """
        return self.functions(theta)[ROW_V]


def _table_functions(mechanism):
    """``theta -> (P/M, gF/M, L/M, M, V)`` from the mechanism's exact functions, shape (5, n)."""
    def func(theta):
        m, l_, f, p = (np.broadcast_to(np.asarray(c, dtype=float), theta.shape)
                       for c in mechanism.coefficients(theta))
        v = np.broadcast_to(np.asarray(mechanism.potential_energy(theta), dtype=float),
                            theta.shape)
        return np.vstack([p / m, GRAVITY * f / m, l_ / m, m, v])
    return func


@functools.lru_cache(maxsize=8)
def _fit_matrices(degree: int):
    """Chebyshev points, check points, and the matrix from values at the points to monomial
    coefficients."""
    n = degree + 1
    nodes = np.cos(np.pi * (np.arange(n) + 0.5) / n)
    checks = np.linspace(-1.0, 1.0, 4 * degree + 3)
    # values -> Chebyshev coefficients (discrete transform at first-kind points)
    to_cheb = 2.0 / n * np.cos(np.outer(np.arange(n), np.pi * (np.arange(n) + 0.5) / n))
    to_cheb[0] *= 0.5
    cheb_to_mono = np.zeros((n, n))
    for k in range(n):
        unit = np.zeros(n)
        unit[k] = 1.0
        mono = np.polynomial.chebyshev.cheb2poly(unit)
        cheb_to_mono[k, : mono.size] = mono
    to_mono = cheb_to_mono.T @ to_cheb  # (n, n): values at nodes -> monomial coefficients
    return nodes, checks, to_mono


def _horner(coef, x):
    """Monomial series ``coef[..., k] x^k`` by Horner's rule, as the compiled evaluation does:
    ``coef`` (..., n) and ``x`` (nc,) give (..., nc)."""
    out = np.broadcast_to(coef[..., -1:], coef.shape[:-1] + x.shape).copy()
    for k in range(coef.shape[-1] - 2, -1, -1):
        out = out * x + coef[..., k : k + 1]
    return out


def tabulate(mechanism, *, degree: int = TABLE_DEGREE, tolerance: float = TABLE_TOLERANCE,
             limit_margin: float = 1e-6, max_pieces: int = 1024) -> MechanismTable:
    r"""Tabulate a mechanism for the compiled engine: ``P/M, gF/M, L/M`` (the right-hand side of
    the equation of motion) and ``M, V`` (the energy rules).

    The right-hand side is that of Eqs. (6)-(7) in [1]_ solved for :math:`\ddot\theta`, and
    ``V`` is the potential energy of Eq. (3) in [1]_.

    The interval :math:`[\theta_{lo}, \theta_u]`, :math:`\theta_{lo} = \theta_{limit} + \delta`
    with :math:`\delta` = ``limit_margin``, is bisected until every piece :math:`[a, b]` of
    ``degree`` reproduces the mechanism's exact functions to ``tolerance`` (relative to each
    function's largest magnitude on the interval) on a check grid. On a piece each function is
    the interpolant at the Chebyshev points of the first kind,

    .. math::

        f(\theta) \approx \sum_{k=0}^{d} c_k\, x^k, \qquad
        x = \frac{\theta - (a + b)/2}{(b - a)/2} \in [-1, 1], \qquad
        x_i = \cos\frac{(i + 1/2)\pi}{d + 1}, \; i = 0 \dots d,

    checked in the monomial form the compiled code evaluates. A linkage that is singular near an
    end of its range (at its kinematic limit, or just beyond :math:`\theta_u` where the links
    line up) gets ever smaller pieces toward it. All pieces of one level of the bisection are
    fitted together (one call of the exact functions per level).

    Parameters
    ----------
    mechanism : FourLinkMechanism
        Or any object with ``theta_u``, ``theta_cr``, ``theta_limit`` [rad], ``direction``
        (``"l"``/``"r"``), vectorised ``coefficients(theta) -> (M, L, F, P)`` and
        ``potential_energy(theta)`` [J/m].
    degree : int
        Degree :math:`d` of each piece [-] (the compiled engine takes :data:`TABLE_DEGREE`).
    tolerance : float
        Target relative interpolation error [-].
    limit_margin : float
        Distance [rad] kept from the kinematic limit, where a linkage may be singular.
    max_pieces : int
        Largest number of pieces, about (with at most 20 levels of bisection); when it is
        reached the remaining pieces are kept as they are, and ``max_error`` of the table tells
        how far from ``tolerance`` they are.

    Returns
    -------
    MechanismTable
        The table; its ``theta_cr`` is raised to ``theta_lo`` if the mechanism's lies beyond
        it, and its ``activation_g`` is computed from the tabulated functions.

    Raises
    ------
    ValueError
        If ``direction`` is not ``"l"`` or ``"r"``, if ``theta_limit + limit_margin`` is not
        below ``theta_u``, or if ``theta_cr`` is not below ``theta_u``.

    References
    ----------
    .. [1] The paper, Sect. 4.2, Eq. (3), and Sect. 4.3, Eqs. (6)-(7).
    """
    theta_u = float(mechanism.theta_u)
    theta_cr = float(mechanism.theta_cr)
    theta_lo = float(mechanism.theta_limit) + float(limit_margin)
    direction = str(getattr(mechanism, "direction", "l"))
    if direction not in ("l", "r"):
        raise ValueError(f"mechanism direction must be 'l' or 'r', got {direction!r}")
    if not theta_lo < theta_u:
        raise ValueError(f"a mechanism needs theta_limit + limit_margin < theta_u, got "
                         f"{theta_lo!r} and {theta_u!r}")
    if not theta_cr < theta_u:
        raise ValueError(f"theta_cr must be < theta_u (gravity must resist the motion at rest), "
                         f"got {theta_cr!r} and {theta_u!r}")
    # gravity resisting down to the kinematic limit: the barrier is at the end of the table
    theta_cr = max(theta_cr, theta_lo)
    func = _table_functions(mechanism)
    scale = np.max(np.abs(func(np.linspace(theta_lo, theta_u, 2001))), axis=1)
    scale[scale == 0.0] = 1.0
    max_depth = 20
    nodes, checks, to_mono = _fit_matrices(degree)
    points = np.concatenate([nodes, checks])
    n = degree + 1

    lo = np.array([theta_lo])
    hi = np.array([theta_u])
    accepted_lo, accepted_coef, accepted_err, depths = [], [], [], []
    depth = 0
    while lo.size:
        centre, half = 0.5 * (lo + hi), 0.5 * (hi - lo)
        values = func((centre[:, None] + half[:, None] * points).ravel())
        values = values.reshape(5, lo.size, points.size)
        coef = values[:, :, :n] @ to_mono.T  # (5, k, n)
        approx = _horner(coef, checks)
        err = np.max(np.abs(approx - values[:, :, n:]), axis=2) / scale[:, None]  # (5, k)
        done = np.all(err <= tolerance, axis=0)
        if depth >= max_depth or len(accepted_lo) + lo.size + np.count_nonzero(~done) > max_pieces:
            done[:] = True
        accepted_lo.extend(lo[done])
        accepted_coef.extend(np.moveaxis(coef[:, done], 1, 0))
        accepted_err.extend(err[:, done].T)
        depths.extend([depth] * int(np.count_nonzero(done)))
        lo, hi, mid = lo[~done], hi[~done], centre[~done]
        lo, hi = np.concatenate([lo, mid]), np.concatenate([mid, hi])
        depth += 1
    order = np.argsort(accepted_lo)
    breaks = np.append(np.asarray(accepted_lo)[order], theta_u)
    coefficients = np.zeros((order.size, 6, n))
    coefficients[:, :5] = np.asarray(accepted_coef)[order]
    coefficients[:, ROW_MAP, 0] = 0.5 * (breaks[:-1] + breaks[1:])
    coefficients[:, ROW_MAP, 1] = 2.0 / (breaks[1:] - breaks[:-1])
    max_error = np.max(np.asarray(accepted_err), axis=0)
    # equal cells no finer than the smallest piece (up to TABLE_MAX_CELLS)
    n_cells = int(min(TABLE_MAX_CELLS, 2 ** max(depths)))
    starts = theta_lo + (theta_u - theta_lo) * np.arange(n_cells) / n_cells
    cells = np.append(np.searchsorted(breaks, starts, side="right") - 1, order.size - 1)
    cells = np.clip(cells, 0, order.size - 1).astype(np.int64)
    a, b, _, _, _ = _table_point(theta_u, theta_lo, n_cells / (theta_u - theta_lo), cells,
                                 breaks, coefficients)
    activation = -b / (GRAVITY * a)
    for arr in (breaks, coefficients, cells, max_error):
        arr.setflags(write=False)
    return MechanismTable(theta_u, theta_cr, theta_lo, float(activation), direction, breaks,
                          coefficients, cells, max_error)


# ---------------------------------------------------------------------------------------------
# Compiled evaluation of a table
# ---------------------------------------------------------------------------------------------


@numba.njit(cache=True, inline="always")
def _piece(theta, lo, inv_cell, cells, breaks):
    """Index of the piece holding ``theta``: its cell, then a short scan of the pieces that
    start inside that cell (pieces are at least one cell wide except near a singular end).

    A ``theta`` on a break (to round-off) may be given the piece on either side of it: the
    cell boundaries and the breaks are computed differently and can differ in the last bit,
    and both pieces interpolate the same function there."""
    n_cells = cells.size - 1
    c = int((theta - lo) * inv_cell) if theta > lo else 0
    if c >= n_cells:
        c = n_cells - 1
    i = cells[c]
    last = cells[c + 1]
    while i < last and theta >= breaks[i + 1]:
        i += 1
    return i


@numba.njit(cache=True, inline="always")
def _estrin9(c, x, x2, x4, x8):
    """``sum c[k] x^k``, k = 0..9, by Estrin's scheme (given the powers of ``x``)."""
    return ((c[0] + c[1] * x) + x2 * (c[2] + c[3] * x)
            + x4 * ((c[4] + c[5] * x) + x2 * (c[6] + c[7] * x)) + x8 * (c[8] + c[9] * x))


@numba.njit(cache=True, inline="always")
def table_rhs(theta, lo, inv_cell, cells, breaks, coefs):
    """``(P/M, gF/M, L/M)`` of one table of degree 9 at ``theta`` [rad], by Estrin's scheme
    (short dependency chains: the integrator's stages wait on these values).

    Degree 9 only (:data:`TABLE_DEGREE`; :func:`pack_pair` refuses other degrees): inlined at
    every stage of the step, a second branch for other degrees cost 15 % of the compile time
    of a fresh clone for code that never ran."""
    c = coefs[_piece(theta, lo, inv_cell, cells, breaks)]
    x = (theta - c[ROW_MAP, 0]) * c[ROW_MAP, 1]
    x2 = x * x
    x4 = x2 * x2
    x8 = x4 * x4
    a = _estrin9(c[0], x, x2, x4, x8)
    b = _estrin9(c[1], x, x2, x4, x8)
    r = _estrin9(c[2], x, x2, x4, x8)
    return a, b, r


@numba.njit(_SIG_TABLE_VALUE, cache=True)
def _table_value(theta, j, lo, inv_cell, cells, breaks, coefs):
    """Row ``j`` (0..4 = P/M, gF/M, L/M, M, V) of one table at ``theta``."""
    c = coefs[_piece(theta, lo, inv_cell, cells, breaks)]
    x = (theta - c[ROW_MAP, 0]) * c[ROW_MAP, 1]
    deg = c.shape[1] - 1
    y = c[j, deg]
    for k in range(deg - 1, -1, -1):
        y = y * x + c[j, k]
    return y


@numba.njit(_SIG_TABLE_FUNCTION, cache=True)
def table_function(theta, j, m, tab):
    """Row ``j`` (0..4 = P/M, gF/M, L/M, M, V) of mechanism ``m`` of a packed pair at
    ``theta``."""
    scal, cells, breaks, coefs = tab
    return _table_value(theta, j, scal[m, 2], scal[m, 4], cells[m], breaks[m], coefs[m])


@numba.njit(cache=True)
def _evaluate_table(thetas, lo, inv_cell, cells, breaks, coefs, out):
    """All five rows of one table at every ``thetas[q]`` [rad] into ``out[:, q]``."""
    for q in range(thetas.size):
        for j in range(5):
            out[j, q] = _table_value(thetas[q], j, lo, inv_cell, cells, breaks, coefs)


def _table_point(theta, lo, inv_cell, cells, breaks, coefs):
    """The five rows of one table at one ``theta`` [rad] (from Python)."""
    out = np.empty((5, 1))
    _evaluate_table(np.array([float(theta)]), lo, inv_cell, cells, breaks, coefs, out)
    return out[:, 0]


def pack_pair(table_l: MechanismTable, table_r: MechanismTable):
    """Stack the tables of Mech-l and Mech-r into the tuple the compiled driver takes.

    Parameters
    ----------
    table_l, table_r : MechanismTable
        Tables of Mech-l (direction ``"l"``) and Mech-r (direction ``"r"``), of degree
        :data:`TABLE_DEGREE`.

    Returns
    -------
    scalars : ndarray, shape (2, 5)
        ``scalars[m] = (theta_u [rad], theta_cr [rad], theta_lo [rad], activation acceleration
        [m/s^2], cells per radian [1/rad])``, ``m`` =
        :data:`~archquake.fourlink.engine.codes.MECH_L`,
        :data:`~archquake.fourlink.engine.codes.MECH_R`; the activation acceleration is ``-k_l g``
        for Mech-l and ``+k_r g`` for Mech-r (for reference: the engine tests activation by the sign
        of its own ``theta''``, :func:`archquake.fourlink.engine.rules._activated`).
    cells : ndarray of int, shape (2, n_cells + 1)
        ``cells`` of each table (:class:`MechanismTable`), padded to the larger number of cells
        of the two (a padded entry repeats the last piece, never reached).
    breaks : ndarray, shape (2, pieces + 1)
        ``breaks`` of each table [rad], padded with ``theta_u``.
    coefficients : ndarray, shape (2, pieces, 6, TABLE_DEGREE + 1)
        ``coefficients`` of each table, padded with zeros to the larger number of pieces.

    Raises
    ------
    ValueError
        If the tables are not (Mech-l, Mech-r) in that order, or not of degree
        :data:`TABLE_DEGREE`.
    """
    if table_l.direction != "l" or table_r.direction != "r":
        raise ValueError("tables must be given as (Mech-l, Mech-r), with directions 'l' and 'r'")
    tables = (table_l, table_r)
    for t in tables:
        if t.coefficients.shape[2] != TABLE_DEGREE + 1:
            raise ValueError(f"the compiled engine takes tables of degree {TABLE_DEGREE}, got "
                             f"degree {t.coefficients.shape[2] - 1} (tabulate(degree=...))")
    npmax = max(t.pieces for t in tables)
    ncmax = max(t.n_cells for t in tables)
    scalars = np.empty((2, 5))
    cells = np.zeros((2, ncmax + 1), dtype=np.int64)
    breaks = np.zeros((2, npmax + 1))
    coefs = np.zeros((2, npmax) + table_l.coefficients.shape[1:])
    for m, t in enumerate(tables):
        sign = -1.0 if m == MECH_L else 1.0
        # the cell width of each table is its own: cells beyond n_cells are never used
        scalars[m] = (t.theta_u, t.theta_cr, t.theta_lo, sign * t.activation_g * GRAVITY,
                      t.n_cells / (t.theta_u - t.theta_lo))
        cells[m, : t.n_cells + 1] = t.cells
        cells[m, t.n_cells + 1:] = t.pieces - 1
        breaks[m, : t.pieces + 1] = t.breaks
        breaks[m, t.pieces + 1:] = t.theta_u
        coefs[m, : t.pieces] = t.coefficients
    return scalars, cells, breaks, coefs


@numba.njit(_SIG_ROOT_FUNCTION, cache=True)
def root_function(j, level, lo, hi, m, tab):
    """``theta`` in ``[lo, hi]`` [rad] where row ``j`` of mechanism ``m`` of a packed pair equals
    ``level`` (a sign change there assumed; else the end nearer to it): bracketing with Newton
    steps for the potential energy (``dV/d theta = g F = (gF/M) M``), bisection otherwise."""
    ga = table_function(lo, j, m, tab) - level
    gb = table_function(hi, j, m, tab) - level
    if ga == 0.0:
        return lo
    if gb == 0.0 or (ga > 0.0) == (gb > 0.0):
        return hi
    x = 0.5 * (lo + hi)
    for _ in range(200):
        g = table_function(x, j, m, tab) - level
        if g == 0.0:
            return x
        if (g > 0.0) == (ga > 0.0):
            lo, ga = x, g
        else:
            hi = x
        # Newton step with dV/dtheta = F g = (gF/M) M when solving for V, else bisection
        x_new = 0.5 * (lo + hi)
        if j == ROW_V:
            slope = table_function(x, ROW_B, m, tab) * table_function(x, ROW_M, m, tab)
            if slope != 0.0:
                x_newton = x - g / slope
                if lo < x_newton < hi:
                    x_new = x_newton
        if x_new == x or hi - lo <= 4e-16 * max(1.0, abs(lo)):
            break
        x = x_new
    return x
