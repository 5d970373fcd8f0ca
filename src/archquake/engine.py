"""Compiled integrator of the rocking motion of an arch [paper, Sects. 4.3-5.3].

The arch moves as a one-degree-of-freedom four-link mechanism, Mech-l or Mech-r, with equation of
motion [eqs. (6)-(7) of the paper]

    Mech-l:  M(theta) theta'' + L(theta) theta'^2 + F(theta) g =  P(theta) xg''(t)
    Mech-r:  M(theta) theta'' + L(theta) theta'^2 + F(theta) g = -P(theta) xg''(t)

(the frame of Mech-r is mirrored), ``theta <= theta_u`` and ``phi = theta_u - theta >= 0``. When
``theta`` returns to ``theta_u`` the joints close, an impact occurs and the other mechanism takes
over with ``theta = theta_u`` and ``theta' = -c theta'_before`` [paper, Sect. 4.4].

Design
------
- :func:`tabulate` samples ``M, L, F, P`` and the potential energy ``V`` [eq. (3)] of a mechanism
  once, as piecewise Chebyshev interpolants on ``[theta_lo, theta_u]``; nothing about the linkage
  is recomputed while integrating, and one table serves every analysis of that arch.
- The integrator is the explicit Dormand-Prince 8(5,3) pair with step-size control and its
  7th-order dense output (Hairer, Norsett & Wanner, Sect. II.10). Events (impact at ``theta_u``,
  kinematic limit, crossing of ``theta_cr``, turning points) are roots of the dense output, located
  to round-off by a bracketing (Illinois) iteration; after an impact the motion restarts exactly at
  ``theta_u``. Steps never cross a breakpoint of the ground motion (a pulse is discontinuous).
- One compiled driver, :func:`_run`, serves both the outcome-only path (no recording, stops as
  soon as the outcome is decided) and the recording path used for time histories and plots.

States and rules
----------------
REST
    the arch moves rigidly with the ground at ``theta_u`` of both mechanisms. Mech-l starts when
    ``P xg'' - F g < 0`` at ``theta_u``, i.e. ``xg''/g < -k_l``, Mech-r when ``xg''/g > k_r``
    [eq. (2)], with ``k = -F(theta_u)/P(theta_u)`` the activation multiplier. For a piecewise
    linear (recorded) ground motion the instant of activation between samples is located.
Impact
    mechanism switch, ``theta' <- -c theta'``; if then ``|theta'|`` is below ``rest_velocity``
    and the ground does not activate the new mechanism, the arch comes to REST (this ends the
    geometric sequence of ever shorter rocking cycles).
Collapse during the excitation
    the linkage reaches the end ``theta_lo`` of its table (its kinematic limit).
Decision after the excitation
    the system is then conservative between impacts: with ``E = M theta'^2 / 2 + V``, an arch
    moving away from ``theta_u`` with ``E > V(theta_cr)`` (or beyond ``theta_cr`` and not coming
    back) collapses. Otherwise it returns to ``theta_u`` with kinetic energy ``E - V(theta_u)``;
    the impact leaves ``c^2 M_new/M_old`` times that kinetic energy, compared with the barrier
    ``V(theta_cr) - V(theta_u)`` of the new mechanism, and after the second impact the arrival
    back into the first mechanism against its own barrier (the arch may have been on its way
    back with energy above it). Surviving both arrivals is recovery when ``c_lr c_rl <= 1``: two
    successive impacts multiply the kinetic energy at ``theta_u`` by
    ``(c_lr^2 M_r/M_l)(c_rl^2 M_l/M_r) = (c_lr c_rl)^2 <= 1``, so every later arrival into either
    mechanism has no more energy than the first checked one, which did not pass the barrier.
Collapse time
    the time of the last crossing of ``theta_cr`` away from ``theta_u`` before collapse: the
    point of no return (beyond it gravity drives the arch further away).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numba
import numpy as np

from . import _dop853 as dop
from .geometry import GRAVITY
from .ground_motion import HARMONIC, LINEAR, STEP, evaluate

# --- states and outcome codes (shared with time_history.py)
REST_STATE = -1
MECH_L, MECH_R = 0, 1
UNDECIDED, STATUS_REST, STATUS_RECOVERY, STATUS_COLLAPSE = -1, 0, 1, 2
STATUS_NAMES = {STATUS_REST: "rest", STATUS_RECOVERY: "recovery", STATUS_COLLAPSE: "collapse"}

# outcome vector returned by the compiled driver
OUT_STATUS, OUT_HALF_CYCLE, OUT_IMPACTS, OUT_COLLAPSE_TIME, OUT_MAX_PHI = 0, 1, 2, 3, 4
OUT_DECISION_TIME, OUT_STEPS, OUT_TRUNCATED, OUT_SIZE = 5, 6, 7, 8

DEFAULT_RTOL = 1e-11
"""Relative tolerance of the local error of a step [-]."""
DEFAULT_ATOL = 1e-13
"""Absolute tolerance of the local error of a step [rad, rad/s]."""
DEFAULT_REST_VELOCITY = 1e-6
"""Speed below which an arch that has just impacted, and is not pushed open, is at rest [rad/s]."""
DEFAULT_MAX_STEP = 0.25
"""Largest step [s] (keeps two roots of an event function from hiding inside one step)."""
DEFAULT_MAX_STEPS = 2_000_000
"""Safety limit on the number of steps of one analysis."""

TABLE_DEGREE = 16
"""Degree of every Chebyshev piece of a :class:`MechanismTable`."""
TABLE_TOLERANCE = 1e-12
"""Target interpolation error of a table, relative to the largest magnitude of each function."""


# ---------------------------------------------------------------------------------------------
# Tables of the coefficients
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class MechanismTable:
    """Coefficients of one mechanism as piecewise Chebyshev interpolants in ``theta``.

    Parameters
    ----------
    theta_u : float
        Undisplaced configuration [rad].
    theta_cr : float
        Critical angle, maximum of the potential energy [rad] (eq. (4) of the paper).
    theta_lo : float
        Lower end of the table [rad]: the kinematic limit of the linkage (reaching it during the
        excitation is collapse).
    activation : float
        Activation multiplier ``k = -F(theta_u)/P(theta_u)`` [-] (acceleration in g).
    direction : str
        ``"l"`` or ``"r"``.
    breaks : ndarray, shape (pieces + 1,)
        Ends of the pieces [rad], increasing from ``theta_lo`` to ``theta_u``.
    coefficients : ndarray, shape (pieces, 5, TABLE_DEGREE + 1)
        Chebyshev coefficients of ``M`` [kg m^2/m], ``L`` [kg m^2/m], ``F`` [kg m/m],
        ``P`` [kg m/m] and ``V`` [J/m] on every piece.
    max_error : ndarray, shape (5,)
        Largest interpolation error found on a check grid, relative to the largest magnitude of
        each function on the table [-].
    """

    theta_u: float
    theta_cr: float
    theta_lo: float
    activation: float
    direction: str
    breaks: np.ndarray
    coefficients: np.ndarray
    max_error: np.ndarray

    @property
    def pieces(self) -> int:
        """Number of Chebyshev pieces."""
        return self.breaks.size - 1

    def evaluate(self, theta) -> np.ndarray:
        """Interpolated ``(M, L, F, P, V)`` at ``theta`` [rad], shape ``(5,) + shape(theta)``."""
        theta = np.asarray(theta, dtype=float)
        flat = theta.ravel()
        out = np.empty((5, flat.size))
        _evaluate_table(flat, self.breaks, self.coefficients, out)
        return out.reshape((5,) + theta.shape)

    def coefficients_at(self, theta):
        """Interpolated ``(M, L, F, P)`` at ``theta`` [rad] (same units as the mechanism)."""
        m, l_, f, p, _ = self.evaluate(theta)
        return m, l_, f, p

    def potential_energy(self, theta):
        """Interpolated potential energy ``V`` [J/m] at ``theta`` [rad]."""
        return self.evaluate(theta)[4]


def _chebyshev_fit(func, a: float, b: float, degree: int) -> np.ndarray:
    """Coefficients (5, degree+1) of the interpolants of ``func`` at Chebyshev points on [a, b]."""
    n = degree + 1
    x = np.cos(np.pi * (np.arange(n) + 0.5) / n)
    values = func(0.5 * (a + b) + 0.5 * (b - a) * x)  # (5, n)
    # discrete Chebyshev transform at first-kind points
    k = np.arange(n)
    basis = np.cos(np.outer(k, np.pi * (np.arange(n) + 0.5) / n))  # T_k(x_j)
    coef = 2.0 / n * values @ basis.T
    coef[:, 0] *= 0.5
    return coef


def _exact_functions(mechanism):
    def func(theta):
        m, l_, f, p = (np.broadcast_to(np.asarray(c, dtype=float), theta.shape)
                       for c in mechanism.coefficients(theta))
        v = np.broadcast_to(np.asarray(mechanism.potential_energy(theta), dtype=float),
                            theta.shape)
        return np.vstack([m, l_, f, p, v])
    return func


def tabulate(mechanism, *, degree: int = TABLE_DEGREE, tolerance: float = TABLE_TOLERANCE,
             limit_margin: float = 1e-6, max_pieces: int = 64) -> MechanismTable:
    """Tabulate a mechanism's ``M, L, F, P, V`` for the compiled engine.

    The interval ``[theta_lo, theta_u]``, ``theta_lo = theta_limit + limit_margin``, is bisected
    until every Chebyshev piece of ``degree`` reproduces the mechanism's exact functions to
    ``tolerance`` (relative to each function's largest magnitude) on a check grid; a linkage whose
    coefficients are singular at its kinematic limit gets ever smaller pieces toward it.

    Parameters
    ----------
    mechanism : object
        Has ``theta_u``, ``theta_cr``, ``theta_limit`` [rad], ``direction`` (``"l"``/``"r"``),
        vectorised ``coefficients(theta) -> (M, L, F, P)`` and ``potential_energy(theta)``.
    degree : int
        Degree of each piece.
    tolerance : float
        Target relative interpolation error [-].
    limit_margin : float
        Distance [rad] kept from the kinematic limit, where a linkage may be singular.
    max_pieces : int
        Largest number of pieces.

    Returns
    -------
    MechanismTable
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
    func = _exact_functions(mechanism)
    grid = np.linspace(theta_lo, theta_u, 2001)
    scale = np.max(np.abs(func(grid)), axis=1)
    scale[scale == 0.0] = 1.0
    min_width = (theta_u - theta_lo) * 2.0 ** -20

    def check(a, b, coef):
        x = np.linspace(-1.0, 1.0, 4 * degree + 3)[1:-1]
        approx = np.polynomial.chebyshev.chebval(x, coef.T)  # (5, nx)
        exact = func(0.5 * (a + b) + 0.5 * (b - a) * x)
        return np.max(np.abs(approx - exact), axis=1) / scale

    pending = [(theta_lo, theta_u)]
    accepted = []
    while pending:
        a, b = pending.pop()
        coef = _chebyshev_fit(func, a, b, degree)
        err = check(a, b, coef)
        if (np.all(err <= tolerance) or b - a <= min_width
                or len(accepted) + len(pending) + 2 > max_pieces):
            accepted.append((a, b, coef, err))
        else:
            mid = 0.5 * (a + b)
            pending.extend([(mid, b), (a, mid)])
    accepted.sort(key=lambda item: item[0])
    breaks = np.array([item[0] for item in accepted] + [theta_u])
    coefficients = np.ascontiguousarray(np.stack([item[2] for item in accepted]))
    max_error = np.max(np.stack([item[3] for item in accepted]), axis=0)
    m, _, f, p, _ = _table_point(theta_u, breaks, coefficients)
    activation = -f / p
    for arr in (breaks, coefficients, max_error):
        arr.setflags(write=False)
    return MechanismTable(theta_u, theta_cr, theta_lo, float(activation), direction, breaks,
                          coefficients, max_error)


# ---------------------------------------------------------------------------------------------
# Compiled evaluation of a table
# ---------------------------------------------------------------------------------------------


@numba.njit(cache=True, inline="always")
def _piece(theta, n, breaks):
    if theta <= breaks[1] or n == 1:
        return 0
    if theta >= breaks[n - 1]:
        return n - 1
    lo, hi = 0, n
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if theta >= breaks[mid]:
            lo = mid
        else:
            hi = mid
    return lo


@numba.njit(cache=True, inline="always")
def _table_coefficients(theta, n, breaks, coefs):
    """(M, L, F, P) of one table at ``theta`` (Clenshaw recurrence, four functions at once)."""
    i = _piece(theta, n, breaks)
    a, b = breaks[i], breaks[i + 1]
    x = (2.0 * theta - a - b) / (b - a)
    x2 = 2.0 * x
    c = coefs[i]
    deg = c.shape[1] - 1
    m1 = m2 = l1 = l2 = f1 = f2 = p1 = p2 = 0.0
    for k in range(deg, 0, -1):
        m1, m2 = c[0, k] + x2 * m1 - m2, m1
        l1, l2 = c[1, k] + x2 * l1 - l2, l1
        f1, f2 = c[2, k] + x2 * f1 - f2, f1
        p1, p2 = c[3, k] + x2 * p1 - p2, p1
    return (c[0, 0] + x * m1 - m2, c[1, 0] + x * l1 - l2, c[2, 0] + x * f1 - f2,
            c[3, 0] + x * p1 - p2)


@numba.njit(cache=True)
def _table_function(theta, j, n, breaks, coefs):
    """Function ``j`` (0..4 = M, L, F, P, V) of one table at ``theta``."""
    i = _piece(theta, n, breaks)
    a, b = breaks[i], breaks[i + 1]
    x = (2.0 * theta - a - b) / (b - a)
    x2 = 2.0 * x
    c = coefs[i]
    b1 = b2 = 0.0
    for k in range(c.shape[1] - 1, 0, -1):
        b1, b2 = c[j, k] + x2 * b1 - b2, b1
    return c[j, 0] + x * b1 - b2


@numba.njit(cache=True)
def _evaluate_table(thetas, breaks, coefs, out):
    n = breaks.size - 1
    for q in range(thetas.size):
        for j in range(5):
            out[j, q] = _table_function(thetas[q], j, n, breaks, coefs)


def _table_point(theta, breaks, coefs):
    out = np.empty((5, 1))
    _evaluate_table(np.array([float(theta)]), breaks, coefs, out)
    return out[:, 0]


def pack_pair(table_l: MechanismTable, table_r: MechanismTable):
    """Stack the tables of Mech-l and Mech-r into the arrays the compiled driver takes.

    Returns ``(scalars, pieces, breaks, coefficients)``: ``scalars[m] = (theta_u, theta_cr,
    theta_lo, activation acceleration [m/s^2])`` with the activation acceleration ``-k_l g`` for
    Mech-l and ``+k_r g`` for Mech-r; arrays padded to the larger number of pieces.
    """
    if table_l.direction != "l" or table_r.direction != "r":
        raise ValueError("tables must be given as (Mech-l, Mech-r), with directions 'l' and 'r'")
    tables = (table_l, table_r)
    if table_l.coefficients.shape[1:] != table_r.coefficients.shape[1:]:
        raise ValueError("the two tables must have the same Chebyshev degree")
    npmax = max(t.pieces for t in tables)
    scalars = np.empty((2, 4))
    pieces = np.empty(2, dtype=np.int64)
    breaks = np.zeros((2, npmax + 1))
    coefs = np.zeros((2, npmax) + table_l.coefficients.shape[1:])
    for m, t in enumerate(tables):
        sign = -1.0 if m == MECH_L else 1.0
        scalars[m] = (t.theta_u, t.theta_cr, t.theta_lo, sign * t.activation * GRAVITY)
        pieces[m] = t.pieces
        breaks[m, : t.pieces + 1] = t.breaks
        breaks[m, t.pieces + 1:] = t.theta_u
        coefs[m, : t.pieces] = t.coefficients
    return scalars, pieces, breaks, coefs


# ---------------------------------------------------------------------------------------------
# Compiled integrator
# ---------------------------------------------------------------------------------------------

_A = dop.A
_B = dop.B
_C = dop.C
_E3 = dop.E3
_E5 = dop.E5
_D = dop.D


@numba.njit(cache=True)
def _ground(t, tcap, tcap_left, kind, params, times, values):
    """Ground acceleration at ``t``; a stage at the end ``tcap`` of a step landing on a
    breakpoint takes the left limit (the value on the step's side of the discontinuity)."""
    if t >= tcap:
        t = tcap_left
    return evaluate(t, kind, params, times, values)


@numba.njit(cache=True, inline="always")
def _rhs(t, th, thd, m, pieces, breaks, coefs, xg_step, tcap, tcap_left, kind, params, times,
         values):
    """theta'' from eq. (6) (Mech-l) or eq. (7) (Mech-r); ``xg_step`` is the ground acceleration
    if it is constant over the step (a piecewise-constant motion), else nan."""
    mm, ll, ff, pp = _table_coefficients(th, pieces[m], breaks[m], coefs[m])
    if xg_step == xg_step:
        xg = xg_step
    else:
        xg = _ground(t, tcap, tcap_left, kind, params, times, values)
    sign = 1.0 if m == MECH_L else -1.0
    return (sign * pp * xg - ff * GRAVITY - ll * thd * thd) / mm


@numba.njit(cache=True)
def _step(t, y0, y1, f0, f1, h, m, pieces, breaks, coefs, xg_step, tcap, tcap_left,
          kind, params, times, values, rtol, atol, K):
    """One Dormand-Prince 8(5,3) step; stages kept in ``K`` for the dense output.

    Returns ``(theta, theta', theta'', error_norm)`` at ``t + h``."""
    K[0, 0] = f0
    K[0, 1] = f1
    for s in range(1, 12):
        d0 = 0.0
        d1 = 0.0
        for j in range(s):
            a = _A[s, j]
            if a != 0.0:
                d0 += a * K[j, 0]
                d1 += a * K[j, 1]
        z0 = y0 + h * d0
        z1 = y1 + h * d1
        K[s, 0] = z1
        K[s, 1] = _rhs(t + _C[s] * h, z0, z1, m, pieces, breaks, coefs, xg_step, tcap,
                       tcap_left, kind, params, times, values)
    d0 = 0.0
    d1 = 0.0
    for j in range(12):
        d0 += _B[j] * K[j, 0]
        d1 += _B[j] * K[j, 1]
    n0 = y0 + h * d0
    n1 = y1 + h * d1
    K[12, 0] = n1
    K[12, 1] = _rhs(t + h, n0, n1, m, pieces, breaks, coefs, xg_step, tcap, tcap_left,
                    kind, params, times, values)
    sc0 = atol + rtol * max(abs(y0), abs(n0))
    sc1 = atol + rtol * max(abs(y1), abs(n1))
    e50 = e51 = e30 = e31 = 0.0
    for j in range(13):
        e50 += _E5[j] * K[j, 0]
        e51 += _E5[j] * K[j, 1]
        e30 += _E3[j] * K[j, 0]
        e31 += _E3[j] * K[j, 1]
    e50 /= sc0
    e51 /= sc1
    e30 /= sc0
    e31 /= sc1
    n5 = e50 * e50 + e51 * e51
    n3 = e30 * e30 + e31 * e31
    if n5 == 0.0 and n3 == 0.0:
        err = 0.0
    else:
        err = abs(h) * n5 / math.sqrt((n5 + 0.01 * n3) * 2.0)
    return n0, n1, K[12, 1], err


@numba.njit(cache=True)
def _dense(t, y0, y1, n0, n1, h, m, pieces, breaks, coefs, xg_step, tcap, tcap_left,
           kind, params, times, values, K, Fd):
    """Coefficients ``Fd`` (7, 2) of the 7th-order dense output of the last step."""
    # the same stage loop as in _step, written out: a shared helper costs 15 % per analysis
    # (measured; numba does not fold the call into this loop even with inline="always")
    for s in range(13, 16):
        d0 = 0.0
        d1 = 0.0
        for j in range(s):
            a = _A[s, j]
            if a != 0.0:
                d0 += a * K[j, 0]
                d1 += a * K[j, 1]
        z0 = y0 + h * d0
        z1 = y1 + h * d1
        K[s, 0] = z1
        K[s, 1] = _rhs(t + _C[s] * h, z0, z1, m, pieces, breaks, coefs, xg_step, tcap,
                       tcap_left, kind, params, times, values)
    for c in range(2):
        dy = (n0 - y0) if c == 0 else (n1 - y1)
        Fd[0, c] = dy
        Fd[1, c] = h * K[0, c] - dy
        Fd[2, c] = 2.0 * dy - h * (K[12, c] + K[0, c])
        for i in range(4):
            acc = 0.0
            for j in range(16):
                acc += _D[i, j] * K[j, c]
            Fd[3 + i, c] = h * acc


@numba.njit(cache=True)
def _dense_value(x, c, ya, Fd):
    """Component ``c`` of the dense output at fraction ``x`` of the step."""
    y = 0.0
    for i in range(6, -1, -1):
        y += Fd[i, c]
        if (6 - i) % 2 == 0:
            y *= x
        else:
            y *= 1.0 - x
    return y + ya


@numba.njit(cache=True)
def _dense_root(xa, xb, c, ya, Fd, level):
    """Root in ``[xa, xb]`` of ``dense_c(x) - level``, which changes sign there (Illinois)."""
    ga = _dense_value(xa, c, ya, Fd) - level
    gb = _dense_value(xb, c, ya, Fd) - level
    if ga == 0.0:
        return xa
    if gb == 0.0:
        return xb
    side = 0
    for _ in range(200):
        x = (xa * gb - xb * ga) / (gb - ga)
        if not (x > min(xa, xb) and x < max(xa, xb)):
            x = 0.5 * (xa + xb)
        g = _dense_value(x, c, ya, Fd) - level
        if g == 0.0:
            return x
        if (g > 0.0) == (gb > 0.0):
            xb, gb = x, g
            if side == 1:
                ga *= 0.5
            side = 1
        else:
            xa, ga = x, g
            if side == -1:
                gb *= 0.5
            side = -1
        if abs(xb - xa) <= 4e-16 * max(1.0, abs(xa)):
            break
    return xb if abs(gb) < abs(ga) else xa


@numba.njit(cache=True)
def _root_function(j, level, lo, hi, m, pieces, breaks, coefs):
    """theta in [lo, hi] where table function ``j`` equals ``level`` (sign change assumed)."""
    n = pieces[m]
    ga = _table_function(lo, j, n, breaks[m], coefs[m]) - level
    gb = _table_function(hi, j, n, breaks[m], coefs[m]) - level
    if ga == 0.0:
        return lo
    if gb == 0.0 or (ga > 0.0) == (gb > 0.0):
        return hi
    x = 0.5 * (lo + hi)
    for _ in range(200):
        g = _table_function(x, j, n, breaks[m], coefs[m]) - level
        if g == 0.0:
            return x
        if (g > 0.0) == (ga > 0.0):
            lo, ga = x, g
        else:
            hi = x
        # Newton step with dV/dtheta = F g when solving for V, else bisection
        x_new = 0.5 * (lo + hi)
        if j == 4:
            slope = _table_function(x, 2, n, breaks[m], coefs[m]) * GRAVITY
            if slope != 0.0:
                x_newton = x - g / slope
                if lo < x_newton < hi:
                    x_new = x_newton
        if x_new == x or hi - lo <= 4e-16 * max(1.0, abs(lo)):
            break
        x = x_new
    return x


@numba.njit(cache=True)
def _activated(xg, scal):
    """Mechanism activated by the ground acceleration ``xg`` at rest (eq. (2)), or -1."""
    if xg < scal[MECH_L, 3]:
        return MECH_L
    if xg > scal[MECH_R, 3]:
        return MECH_R
    return -1


@numba.njit(cache=True)
def _activation(t, t_stop, scal, kind, params, times, values, bps):
    """First instant in ``[t, t_stop)`` at which the ground activates a mechanism from rest.

    Returns ``(time, mechanism)``, ``(t_stop, -1)`` if none. Piecewise-constant motions are
    checked per interval, piecewise-linear ones per segment (one crossing at most), others on a
    fine sampling; a crossing is then bracketed to round-off by bisection.
    """
    nb = bps.size
    i = 0
    while i < nb and bps[i] <= t:
        i += 1
    ta = t
    while ta < t_stop:
        tb = bps[i] if i < nb else t_stop
        tb = min(tb, t_stop)
        if tb <= ta:
            i += 1
            continue
        if kind == STEP:
            m = _activated(evaluate(ta, kind, params, times, values), scal)
            if m >= 0:
                return ta, m
        else:
            nsub = 1
            if kind == HARMONIC:
                nsub = max(1, int(math.ceil((tb - ta) / (params[1] / 512.0))))
            tl = tb * (1.0 - 2.0 ** -52)
            prev = ta
            m = _activated(evaluate(ta, kind, params, times, values), scal)
            if m >= 0:
                return ta, m
            for q in range(1, nsub + 1):
                tq = ta + (tb - ta) * q / nsub
                if q == nsub:
                    tq = tl
                m = _activated(evaluate(tq, kind, params, times, values), scal)
                if m >= 0:
                    lo, hi = prev, tq  # not activated at lo, activated at hi
                    for _ in range(200):
                        mid = 0.5 * (lo + hi)
                        if mid <= lo or mid >= hi:
                            break
                        if _activated(evaluate(mid, kind, params, times, values), scal) >= 0:
                            hi = mid
                        else:
                            lo = mid
                    return hi, _activated(evaluate(hi, kind, params, times, values), scal)
                prev = tq
        ta = tb
        i += 1
    return t_stop, -1


@numba.njit(cache=True)
def _push(buf, n, v0, v1, v2, v3=0.0, v4=0.0):
    """Write row ``n`` of a record buffer (its first ``buf.shape[1]`` values), growing it."""
    if n >= buf.shape[0]:
        new = np.empty((2 * buf.shape[0], buf.shape[1]))
        new[:n] = buf[:n]
        buf = new
    vals = (float(v0), float(v1), float(v2), float(v3), float(v4))
    for j in range(buf.shape[1]):
        buf[n, j] = vals[j]
    return buf


@numba.njit(cache=True)
def _decide(m, th, thd, scal, pieces, breaks, coefs, c_lr, c_rl):
    """Outcome after the end of the excitation (see the module docstring).

    Returns ``(status, extra_half_cycles, peak_phi, time_known)``: ``extra_half_cycles`` is 0 if
    a collapse happens in the current half cycle, 1 (2) if after the next (second) impact;
    ``peak_phi`` the
    largest phi still to come if the arch recovers; ``time_known`` whether the point of no
    return has already been passed.
    """
    other = 1 - m
    n = pieces[m]
    th_u, th_cr = scal[m, 0], scal[m, 1]
    mm = _table_function(th, 0, n, breaks[m], coefs[m])
    v = _table_function(th, 4, n, breaks[m], coefs[m])
    v_cr = _table_function(th_cr, 4, n, breaks[m], coefs[m])
    v_u = _table_function(th_u, 4, n, breaks[m], coefs[m])
    energy = 0.5 * mm * thd * thd + v
    peak = 0.0
    if th <= th_cr:
        if thd <= 0.0 or energy <= v_cr:
            return STATUS_COLLAPSE, 0, peak, True
    elif thd < 0.0:
        if energy > v_cr:
            return STATUS_COLLAPSE, 0, peak, False
        peak = th_u - _root_function(4, energy, th_cr, th, m, pieces, breaks, coefs)
    # returns to theta_u, impacts into the other mechanism
    kinetic = max(energy - v_u, 0.0)
    c = c_lr if m == MECH_L else c_rl
    no = pieces[other]
    m_u = _table_function(th_u, 0, n, breaks[m], coefs[m])
    m_new = _table_function(scal[other, 0], 0, no, breaks[other], coefs[other])
    kinetic_new = c * c * m_new / m_u * kinetic
    v_u_new = _table_function(scal[other, 0], 4, no, breaks[other], coefs[other])
    barrier = _table_function(scal[other, 1], 4, no, breaks[other], coefs[other]) - v_u_new
    if kinetic_new > barrier:
        return STATUS_COLLAPSE, 1, peak, False
    th_peak = _root_function(4, v_u_new + kinetic_new, scal[other, 1], scal[other, 0],
                             other, pieces, breaks, coefs)
    peak = max(peak, scal[other, 0] - th_peak)
    # back into this mechanism after the second impact: its own barrier has not been checked
    # yet (the arch may be on its way back with more energy than the barrier); from then on
    # every full cycle multiplies the kinetic energy of an arrival by (c_lr c_rl)^2 <= 1
    c_back = c_rl if m == MECH_L else c_lr
    kinetic_back = c_back * c_back * m_u / m_new * kinetic_new
    if kinetic_back > v_cr - v_u:
        return STATUS_COLLAPSE, 2, peak, False
    th_peak = _root_function(4, v_u + kinetic_back, th_cr, th_u, m, pieces, breaks, coefs)
    peak = max(peak, th_u - th_peak)
    return STATUS_RECOVERY, 0, peak, True


@numba.njit(cache=True)
def _run(scal, pieces, breaks, coefs, c_lr, c_rl, kind, params, times, values, bps, duration,
         t_start, t_end, mech0, theta0, thetadot0, rtol, atol, rest_velocity, max_step,
         max_steps, record, record_dt):
    """Integrate one analysis; see the module docstring for the rules.

    Returns ``(out, rec, imp, crs)``: ``out`` the outcome vector (``OUT_*`` indices); in recording
    mode ``rec`` rows ``(t, theta, theta', state, segment)``, ``imp`` rows ``(t, mechanism before,
    theta' before, theta' after)`` and ``crs`` rows ``(t, mechanism, +1 outward / -1 inward)`` of
    the crossings of ``theta_cr``. Without recording the arrays are empty and the driver stops
    as soon as the outcome (with the collapse time) is known.
    """
    out = np.full(OUT_SIZE, np.nan)
    cap = 256 if record else 1
    rec = np.empty((cap, 5))
    imp = np.empty((cap, 4))
    crs = np.empty((cap, 3))
    nrec = nimp = ncrs = 0
    K = np.empty((16, 2))
    Fd = np.empty((7, 2))

    status = UNDECIDED
    half_cycle = 0
    impacts = 0
    decided_impacts = 0
    collapse_time = np.nan
    decision_time = np.nan
    pending = False  # collapse decided, point of no return still ahead
    max_phi = 0.0
    last_out = np.nan  # last outward crossing of theta_cr
    activated = mech0 >= 0
    m = mech0
    th = theta0
    thd = thetadot0
    t = t_start
    h = min(1e-3, max_step)
    steps = 0
    truncated = False
    seg = 0
    nb = bps.size
    ib = 0
    while ib < nb and bps[ib] <= t:
        ib += 1
    next_sample = t
    fsal = False  # theta'' of the current state known from the last stage of the last step
    f1 = 0.0
    if m >= 0:
        max_phi = scal[m, 0] - th
    if record:
        rec = _push(rec, 0, t, th if m >= 0 else np.nan, thd, m, seg)
        nrec = 1
        next_sample = t + record_dt

    while True:
        # -------- decision once the excitation is over
        if status == UNDECIDED and t >= duration:
            decision_time = t
            decided_impacts = impacts
            if m == REST_STATE:
                status = STATUS_RECOVERY if activated else STATUS_REST
            else:
                st, extra, peak, known = _decide(m, th, thd, scal, pieces, breaks, coefs,
                                                 c_lr, c_rl)
                status = st
                if st == STATUS_COLLAPSE:
                    half_cycle = impacts + 1 + extra
                    decided_impacts = half_cycle - 1
                    m_collapse = m if extra % 2 == 0 else 1 - m
                    max_phi = scal[m_collapse, 0] - scal[m_collapse, 2]
                    if known:
                        collapse_time = last_out
                    else:
                        pending = True
                else:
                    max_phi = max(max_phi, peak)
        if status != UNDECIDED and not pending and not record:
            break
        if t >= t_end:
            break
        if steps >= max_steps:
            truncated = True
            break

        # -------- at rest: wait for the ground to activate a mechanism
        if m == REST_STATE:
            if t < duration:
                t_act, m_act = _activation(t, min(duration, t_end), scal, kind, params, times,
                                           values, bps)
            else:  # the ground is still for ever
                t_act, m_act = t_end, -1
            steps += 1
            if record:
                rec = _push(rec, nrec, t_act, np.nan, 0.0, REST_STATE, seg)
                nrec += 1
            t = t_act
            while ib < nb and bps[ib] <= t:
                ib += 1
            if m_act >= 0:
                fsal = False
                m = m_act
                th = scal[m, 0]
                thd = 0.0
                activated = True
                seg += 1
                if record:
                    rec = _push(rec, nrec, t, th, thd, m, seg)
                    nrec += 1
                    next_sample = t + record_dt
            continue

        # -------- one step of the moving mechanism
        th_u, th_cr, th_lo = scal[m, 0], scal[m, 1], scal[m, 2]
        bnext = bps[ib] if ib < nb else np.inf
        t_stop = min(bnext, t_end)
        xg_step = evaluate(t, kind, params, times, values) if kind == STEP else np.nan
        f0 = thd
        if not fsal:
            f1 = _rhs(t, th, thd, m, pieces, breaks, coefs, xg_step, np.inf, np.inf,
                      kind, params, times, values)
        rejected = False
        while True:
            hh = min(h, max_step)
            landing = t + hh >= t_stop
            if landing:
                hh = t_stop - t
            if landing and t_stop == bnext:
                tcap = bnext
                tcap_left = bnext * (1.0 - 2.0 ** -52) if bnext > 0.0 else bnext
            else:
                tcap = np.inf
                tcap_left = np.inf
            n0, n1, nf, err = _step(t, th, thd, f0, f1, hh, m, pieces, breaks, coefs, xg_step,
                                    tcap, tcap_left, kind, params, times, values, rtol, atol, K)
            steps += 1
            if err < 1.0:
                fac = 10.0 if err == 0.0 else min(10.0, 0.9 * err ** (-1.0 / 8.0))
                if rejected:
                    fac = min(1.0, fac)
                if not landing or hh >= h:
                    h = hh * fac
                break
            h = hh * max(0.2, 0.9 * err ** (-1.0 / 8.0))
            rejected = True
            if steps >= max_steps:
                break
        t1 = t_stop if landing else t + hh

        # -------- events inside the step
        need_dense = (record or n0 > th_u or n0 < th_lo or (th - th_cr) * (n0 - th_cr) <= 0.0
                      or (f0 > 0.0) != (n1 > 0.0))
        event = 0  # 1 impact, 2 kinematic limit
        x_event = 1.0
        if need_dense:
            _dense(t, th, thd, n0, n1, hh, m, pieces, breaks, coefs, xg_step, tcap, tcap_left,
                   kind, params, times, values, K, Fd)
            # split the step at a turning point so that theta is monotonic on each part
            xs0 = 0.0
            xs1 = 1.0
            x_turn = 2.0
            if (f0 > 0.0) != (n1 > 0.0) and f0 != 0.0 and n1 != 0.0:
                x_turn = _dense_root(0.0, 1.0, 1, thd, Fd, 0.0)
            for part in range(2):
                if part == 0:
                    xa, xb = xs0, min(x_turn, xs1)
                else:
                    if x_turn >= 1.0:
                        break
                    xa, xb = x_turn, xs1
                ga = th if xa == 0.0 else _dense_value(xa, 0, th, Fd)
                gb = n0 if xb == 1.0 else _dense_value(xb, 0, th, Fd)
                if part == 0 and x_turn < 1.0 and status == UNDECIDED:
                    # the end of the first part is a turning point: a local extremum of phi
                    max_phi = max(max_phi, th_u - gb)
                # crossing of theta_cr (theta is monotonic on the part, so a crossing precedes
                # an impact or the kinematic limit found on the same part)
                if (ga - th_cr) * (gb - th_cr) < 0.0 or (gb == th_cr and ga != th_cr):
                    tc = t + _dense_root(xa, xb, 0, th, Fd, th_cr) * hh
                    outward = gb < ga
                    if outward:
                        last_out = tc
                        if pending:
                            collapse_time = tc
                            pending = False
                    if record:
                        crs = _push(crs, ncrs, tc, m, 1.0 if outward else -1.0)
                        ncrs += 1
                if gb > th_u and ga <= th_u:
                    event = 1
                    x_event = _dense_root(xa, xb, 0, th, Fd, th_u)
                    break
                if gb < th_lo and ga >= th_lo:
                    event = 2
                    x_event = _dense_root(xa, xb, 0, th, Fd, th_lo)
                    break
            if record:
                while next_sample < t + x_event * hh:
                    xq = (next_sample - t) / hh
                    rec = _push(rec, nrec, next_sample, _dense_value(xq, 0, th, Fd),
                                _dense_value(xq, 1, thd, Fd), m, seg)
                    nrec += 1
                    next_sample += record_dt
        if event == 0:
            t = t1
            th = n0
            thd = n1
            # the last stage is theta'' at the new point, unless the ground changes there
            fsal = not (landing and t_stop == bnext)
            f1 = nf
            if status == UNDECIDED and th_u - th > max_phi:
                max_phi = th_u - th
            while ib < nb and bps[ib] <= t:
                ib += 1
            if record:
                rec = _push(rec, nrec, t, th, thd, m, seg)
                nrec += 1
            continue

        # polish the event on the integrator's own solution: steps from t to the event time,
        # corrected by Newton (theta' is the slope), until theta hits the level to round-off
        level = th_u if event == 1 else th_lo
        h_ev = x_event * hh
        thd_ev = _dense_value(x_event, 1, thd, Fd)
        for _ in range(4):
            p0, p1, _, _ = _step(t, th, thd, f0, f1, h_ev, m, pieces, breaks, coefs, xg_step,
                                 tcap, tcap_left, kind, params, times, values, rtol, atol, K)
            thd_ev = p1
            if p1 == 0.0 or abs(p0 - level) <= 4e-16 * max(1.0, abs(level)):
                break
            h_new = h_ev - (p0 - level) / p1
            if not (0.0 < h_new <= hh):
                break
            h_ev = h_new
        t_ev = t + h_ev
        if event == 2:
            # kinematic limit: collapse (or the end of a collapse already decided)
            t = t_ev
            th = th_lo
            thd = thd_ev
            if record:
                rec = _push(rec, nrec, t, th, thd, m, seg)
                nrec += 1
            if status == UNDECIDED:
                status = STATUS_COLLAPSE
                half_cycle = impacts + 1
                decided_impacts = impacts
                decision_time = t
                collapse_time = last_out
                max_phi = th_u - th_lo
            pending = False
            break

        # impact at theta_u: switch mechanism
        t = t_ev
        fsal = False
        if record:
            rec = _push(rec, nrec, t, th_u, thd_ev, m, seg)
            nrec += 1
        c = c_lr if m == MECH_L else c_rl
        new_thd = -c * thd_ev
        if record:
            imp = _push(imp, nimp, t, m, thd_ev, new_thd)
            nimp += 1
        impacts += 1
        m = 1 - m
        th = scal[m, 0]
        thd = new_thd
        seg += 1
        while ib < nb and bps[ib] <= t:
            ib += 1
        if abs(thd) < rest_velocity:
            xg = evaluate(t, kind, params, times, values)
            if _activated(xg, scal) != m:
                m = REST_STATE
                thd = 0.0
        if record:
            rec = _push(rec, nrec, t, th if m >= 0 else np.nan, thd, m, seg)
            nrec += 1

    out[OUT_STATUS] = status
    out[OUT_HALF_CYCLE] = half_cycle if status == STATUS_COLLAPSE else 0
    out[OUT_IMPACTS] = decided_impacts
    out[OUT_COLLAPSE_TIME] = collapse_time if status == STATUS_COLLAPSE else np.nan
    out[OUT_MAX_PHI] = max_phi
    out[OUT_DECISION_TIME] = decision_time
    out[OUT_STEPS] = steps
    out[OUT_TRUNCATED] = 1.0 if truncated else 0.0
    return out, rec[:nrec], imp[:nimp], crs[:ncrs]


@numba.njit(cache=True)
def _grid(scal, pieces, breaks, coefs, c_lr, c_rl, kind, params0, times0, values0, amplitudes,
          durations, rtol, atol, rest_velocity, max_step, max_steps):
    """Outcomes of a scaled template motion for many (amplitude, duration) pairs."""
    n = amplitudes.size
    status = np.empty(n, dtype=np.int8)
    half_cycle = np.empty(n, dtype=np.int16)
    impacts = np.empty(n, dtype=np.int32)
    collapse_time = np.empty(n)
    max_phi = np.empty(n)
    params = params0.copy()
    for q in range(n):
        a = amplitudes[q]
        tp = durations[q]
        times = times0 * tp
        values = values0 * a
        if kind == HARMONIC:
            params[0] = params0[0] * a
            params[1] = params0[1] * tp
            duration = params[1] * params[2]
            bps = np.array([0.0, duration])
        else:
            duration = times[times.size - 1]
            bps = times
        out, _, _, _ = _run(scal, pieces, breaks, coefs, c_lr, c_rl, kind, params, times,
                            values, bps, duration, 0.0, np.inf, REST_STATE, 0.0, 0.0, rtol,
                            atol, rest_velocity, max_step, max_steps, False, 1.0)
        status[q] = int(out[OUT_STATUS])
        half_cycle[q] = int(out[OUT_HALF_CYCLE])
        impacts[q] = int(out[OUT_IMPACTS])
        collapse_time[q] = out[OUT_COLLAPSE_TIME]
        max_phi[q] = out[OUT_MAX_PHI]
    return status, half_cycle, impacts, collapse_time, max_phi


# ---------------------------------------------------------------------------------------------
# Python entry points
# ---------------------------------------------------------------------------------------------


def check_restitution(c_lr, c_rl) -> tuple[float, float]:
    """Validate the coefficients of restitution: finite, > 0, and ``c_lr c_rl <= 1``.

    A single coefficient may exceed 1: for an irregular arch the computed c_v is a ratio of the
    rates of two different coordinates (theta of Mech-l and theta of Mech-r), not of one speed.
    What an impact may not do is create energy. The kinetic energy ratio of one impact,
    ``c^2 M_to / M_from``, is <= 1 for the computed coefficients (Cauchy-Schwarz, see
    :mod:`archquake.impact`), and over a pair of impacts (l -> r -> l) the masses cancel, so the
    kinetic energy at ``theta_u`` is multiplied by ``(c_lr c_rl)^2``; the outcome decision after the
    excitation relies on that product being <= 1 (module docstring).
    """
    out = []
    for name, c in (("c_lr", c_lr), ("c_rl", c_rl)):
        try:
            c = float(c)
        except (TypeError, ValueError) as exc:
            raise ValueError(f"restitution {name} must be a finite number > 0, got {c!r}") from exc
        if not (math.isfinite(c) and c > 0.0):
            raise ValueError(f"restitution {name} must be a finite number > 0, got {c!r}")
        out.append(c)
    if out[0] * out[1] > 1.0 + 1e-12:
        raise ValueError(f"restitution c_lr * c_rl must be <= 1 (no energy gained over a pair of "
                         f"impacts), got {out[0]!r} * {out[1]!r} = {out[0] * out[1]!r}")
    return out[0], out[1]


def compiled_motion(motion):
    """``(kind, params, times, values, breakpoints, duration)`` of a GroundMotion for _run."""
    kind, params, times, values = motion.compiled()
    bps = np.ascontiguousarray(motion.breakpoints, dtype=float)
    return (int(kind), np.ascontiguousarray(params, dtype=float),
            np.ascontiguousarray(times, dtype=float), np.ascontiguousarray(values, dtype=float),
            bps, float(motion.duration))


def outcomes_grid(table_l: MechanismTable, table_r: MechanismTable, c_lr: float, c_rl: float,
                  durations, amplitudes, motion: str = "oppenheim", *,
                  rtol: float = DEFAULT_RTOL, atol: float = DEFAULT_ATOL,
                  rest_velocity: float = DEFAULT_REST_VELOCITY,
                  max_step: float = DEFAULT_MAX_STEP) -> dict[str, np.ndarray]:
    """Outcomes of one arch under many pulses, in one compiled call.

    Parameters
    ----------
    table_l, table_r : MechanismTable
        Tables of Mech-l and Mech-r of the arch (:func:`tabulate`).
    c_lr, c_rl : float
        Coefficients of restitution of the impacts Mech-l -> Mech-r and Mech-r -> Mech-l [-].
    durations : array_like
        Pulse durations t_p [s].
    amplitudes : array_like
        Signed ground accelerations of the pulse [m/s^2] (``-GRAVITY`` is the paper's -1 g);
        broadcast against ``durations``.
    motion : str
        Name of the pulse shape in :data:`archquake.ground_motion.GROUND_MOTIONS`; every shape of
        the registry is ``amplitude * shape(t / duration)``, which is how the cases are built.

    Returns
    -------
    dict of ndarray
        ``status`` (0 rest, 1 recovery, 2 collapse), ``half_cycle``, ``impacts``,
        ``collapse_time`` [s] and ``max_phi`` [rad], each of the broadcast shape.
    """
    from .ground_motion import ground_motion

    c_lr, c_rl = check_restitution(c_lr, c_rl)
    durations, amplitudes = np.broadcast_arrays(np.asarray(durations, dtype=float),
                                                np.asarray(amplitudes, dtype=float))
    shape = durations.shape
    if np.any(~np.isfinite(durations)) or np.any(durations <= 0):
        raise ValueError("durations must be finite numbers > 0 [s]")
    if np.any(~np.isfinite(amplitudes)):
        raise ValueError("amplitudes must be finite numbers [m/s^2]")
    template = ground_motion(motion, 1.0, 1.0)
    kind, params, times, values = (np.asarray(x) if i else x
                                   for i, x in enumerate(template.compiled()))
    if kind not in (STEP, LINEAR, HARMONIC):
        raise ValueError(f"unsupported ground motion kind {kind!r}")
    scal, pieces, breaks, coefs = pack_pair(table_l, table_r)
    res = _grid(scal, pieces, breaks, coefs, c_lr, c_rl, int(kind),
                np.ascontiguousarray(params, dtype=float), np.ascontiguousarray(times, float),
                np.ascontiguousarray(values, float), np.ascontiguousarray(amplitudes.ravel()),
                np.ascontiguousarray(durations.ravel()), rtol, atol, rest_velocity, max_step,
                DEFAULT_MAX_STEPS)
    names = ("status", "half_cycle", "impacts", "collapse_time", "max_phi")
    return {k: v.reshape(shape) for k, v in zip(names, res, strict=True)}
