"""Intensity measures of a ground motion, by name, and scaling of a motion to an intensity level.

Every intensity measure (IM) is a function of any :class:`~.core.GroundMotion` (records and
analytic pulses) and has a name in :data:`INTENSITY_MEASURES`:

=========  ======  ==========================================================================
name       unit    quantity
=========  ======  ==========================================================================
``pga``    g       peak ground acceleration, ``max |xg''|``
``pgv``    m/s     peak ground velocity, ``max |xg'|`` over ``[0, duration]``
``pgd``    m       peak ground displacement, ``max |xg|`` over ``[0, duration]``
``arias``  m/s     Arias intensity ``pi / (2 g) int xg''^2 dt`` [1]_
``d5-95``  s       significant duration: time between 5 % and 95 % of the Arias intensity [2]_
``sa(T)``  g       5 %-damped pseudo-spectral acceleration ``omega^2 max |u|`` at period T [s]
=========  ======  ==========================================================================

How they are computed
---------------------
The ground is at rest at ``t = 0`` (velocity and displacement zero). Between its breakpoints a
table motion is piecewise linear (``LINEAR``) or constant (``STEP``), and its integrals are exact:
the velocity is piecewise quadratic, the displacement piecewise cubic, the Arias intensity a sum
of ``h (a_0^2 + a_0 a_1 + a_1^2) / 3``, and peaks inside a segment (where the acceleration or the
velocity changes sign) are found from those polynomials. An analytic pulse is first sampled as a
``LINEAR`` table at 4096 points per time scale (period or pulse duration; its interpolation
changes the IMs by less than 1e-6 relative, tested against closed forms); ``pga`` of a pulse is
its exact peak.

No baseline correction: ``pgv`` and ``pgd`` are those of the acceleration as given -- the motion
the arch is subjected to. Velocity and displacement are taken over the motion's time span
``[0, duration]`` (after it the ground keeps its final velocity; a record whose velocity does not
return to zero shows that drift in ``pgd``; database records are usually already processed).

``sa(T)``: the relative displacement ``u`` of a linear oscillator
``u'' + 2 zeta omega u' + omega^2 u = -xg''(t)``, ``omega = 2 pi / T``, ``zeta = 0.05``, is
advanced by the exact recursion of Nigam & Jennings [3]_ for a piecewise-linear excitation (on
sub-steps no longer than T/100); the peak of ``|u|`` between two sub-steps is located by cubic
Hermite interpolation of ``(u, u')`` (error below 1e-7 of the peak), and the free vibration after
the end of the motion is followed for one period, which holds its largest excursion.

References
----------
.. [1] Arias, A. (1970). A measure of earthquake intensity. In R. J. Hansen (ed.), Seismic Design
   for Nuclear Power Plants, MIT Press, 438-483.
.. [2] Trifunac, M. D. and Brady, A. G. (1975). A study on the duration of strong earthquake
   ground motion. Bulletin of the Seismological Society of America 65(3), 581-626.
.. [3] Nigam, N. C. and Jennings, P. C. (1969). Calculation of response spectra from strong-motion
   earthquake records. Bulletin of the Seismological Society of America 59(2), 909-922.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Iterable
from dataclasses import dataclass

import numba
import numpy as np

from ..constants import GRAVITY
from .core import STEP, GroundMotion, check_number

SAMPLES_PER_TIME_SCALE = 4096
"""Sampling of an analytic pulse for its IMs: points per time scale (period or duration)."""
SA_DAMPING = 0.05
"""Damping ratio of the oscillator of ``sa(T)`` [-]."""
SA_STEPS_PER_PERIOD = 100
"""Largest sub-step of the oscillator is ``T / SA_STEPS_PER_PERIOD`` (for locating its peak)."""


# --- the motion as pieces of straight lines --------------------------------------------------

def segments(motion: GroundMotion) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The ground acceleration as straight pieces: ``(t, a_start, a_end)``.

    Piece ``i`` runs from ``t[i]`` to ``t[i+1]`` [s] with acceleration going linearly from
    ``a_start[i]`` to ``a_end[i]`` [m/s^2] (a jump between pieces is allowed). ``t[0] = 0`` and
    ``t[-1]`` is the motion's duration. Exact for STEP and LINEAR motions; an analytic pulse is
    sampled (see the module docstring).
    """
    if not isinstance(motion, GroundMotion):
        raise ValueError(f"motion must be a GroundMotion, got {type(motion).__name__}")
    if motion.is_analytic:
        step = motion.params[1] / SAMPLES_PER_TIME_SCALE
        motion = motion.tabulated(step)
    t = motion.times
    if motion.kind == STEP:
        a0 = a1 = motion.values
    else:
        a0, a1 = motion.values[:-1], motion.values[1:]
    if t[0] > 0.0:  # still ground before the table starts
        t = np.concatenate(([0.0], t))
        a0 = np.concatenate(([0.0], a0))
        a1 = np.concatenate(([0.0], a1))
    return t, np.asarray(a0, dtype=float), np.asarray(a1, dtype=float)


def _velocity_nodes(t, a0, a1):
    h = np.diff(t)
    v = np.concatenate(([0.0], np.cumsum(h * (a0 + a1) / 2.0)))
    return h, v


def peak_ground_velocity(motion: GroundMotion) -> float:
    """Peak absolute ground velocity [m/s] over ``[0, duration]`` (exact for tables)."""
    t, a0, a1 = segments(motion)
    h, v = _velocity_nodes(t, a0, a1)
    peak = float(np.max(np.abs(v)))
    turn = a0 * a1 < 0.0  # the velocity has an extremum inside the piece
    if np.any(turn):
        s = a0[turn] / (a0[turn] - a1[turn])
        vi = v[:-1][turn] + h[turn] * (a0[turn] * s + (a1[turn] - a0[turn]) * s * s / 2.0)
        peak = max(peak, float(np.max(np.abs(vi))))
    return peak


def ground_displacement(motion: GroundMotion) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Ground velocity [m/s] and displacement [m] at the piece ends ``t`` [s] of
    :func:`segments`: ``(t, velocity, displacement)``, exact for tables."""
    t, a0, a1 = segments(motion)
    h, v = _velocity_nodes(t, a0, a1)
    d = np.concatenate(([0.0], np.cumsum(v[:-1] * h + h * h * (2.0 * a0 + a1) / 6.0)))
    return t, v, d


def peak_ground_displacement(motion: GroundMotion) -> float:
    """Peak absolute ground displacement [m] over ``[0, duration]``, no baseline correction
    (exact for tables)."""
    t, a0, a1 = segments(motion)
    h, v = _velocity_nodes(t, a0, a1)
    d = np.concatenate(([0.0], np.cumsum(v[:-1] * h + h * h * (2.0 * a0 + a1) / 6.0)))
    peak = float(np.max(np.abs(d)))
    # inside a piece, v(s) = v_i + h (a0 s + (a1 - a0) s^2 / 2), s in (0, 1); d has an extremum
    # where v = 0
    qa, qb, qc = h * (a1 - a0) / 2.0, h * a0, v[:-1]
    for root_sign in (-1.0, 1.0):
        with np.errstate(invalid="ignore", divide="ignore"):
            disc = qb * qb - 4.0 * qa * qc
            sq = np.sqrt(np.where(disc >= 0.0, disc, np.nan))
            # numerically stable roots: q = -(b + sign(b) sqrt(disc)) / 2; s = q / a or c / q
            q = -0.5 * (qb + np.copysign(sq, qb))
            s = np.where(root_sign < 0, q / qa, qc / q)
            s = np.where(np.abs(qa) < 1e-300, -qc / qb, s)
        inside = np.isfinite(s) & (s > 0.0) & (s < 1.0)
        if np.any(inside):
            i = np.nonzero(inside)[0]
            si = s[i]
            di = d[i] + v[i] * h[i] * si + h[i] ** 2 * (a0[i] * si ** 2 / 2.0
                                                        + (a1[i] - a0[i]) * si ** 3 / 6.0)
            peak = max(peak, float(np.max(np.abs(di))))
    return peak


# --- Arias intensity and significant duration ------------------------------------------------

def _arias_pieces(t, a0, a1):
    h = np.diff(t)
    return math.pi / (2.0 * GRAVITY) * h * (a0 * a0 + a0 * a1 + a1 * a1) / 3.0


def arias_intensity(motion: GroundMotion) -> float:
    """Arias intensity ``pi / (2 g) int xg''(t)^2 dt`` [m/s] [1]."""
    return float(np.sum(_arias_pieces(*segments(motion))))


def husid_time(motion: GroundMotion, fraction: float) -> float:
    """Time [s] at which the cumulative Arias intensity reaches ``fraction`` of its total."""
    from scipy.optimize import brentq

    fraction = check_number("fraction", fraction, "-")
    if fraction >= 1.0:
        raise ValueError(f"fraction must be in (0, 1) [-], got {fraction!r}")
    t, a0, a1 = segments(motion)
    pieces = _arias_pieces(t, a0, a1)
    cumulative = np.concatenate(([0.0], np.cumsum(pieces)))
    total = cumulative[-1]
    if total <= 0.0:
        raise ValueError(f"the ground motion {motion.name!r} is zero everywhere: it has no "
                         "Arias intensity to take a fraction of")
    target = fraction * total
    i = int(np.searchsorted(cumulative, target, side="left")) - 1
    i = min(max(i, 0), pieces.size - 1)
    h, a, b = t[i + 1] - t[i], a0[i], a1[i]
    c = math.pi / (2.0 * GRAVITY) * h
    # cumulative inside the piece: c (a^2 s + a (b - a) s^2 + (b - a)^2 s^3 / 3), s in [0, 1]
    def rest(s):
        return cumulative[i] + c * (a * a * s + a * (b - a) * s * s
                                    + (b - a) ** 2 * s ** 3 / 3.0) - target

    if rest(0.0) >= 0.0:
        return float(t[i])
    if rest(1.0) <= 0.0:
        return float(t[i + 1])
    return float(t[i] + h * brentq(rest, 0.0, 1.0, xtol=1e-15))


def significant_duration(motion: GroundMotion, start: float = 0.05, end: float = 0.95) -> float:
    """Significant duration [s]: the time between ``start`` and ``end`` fractions of the Arias
    intensity (D5-95 by default) [2]."""
    return husid_time(motion, end) - husid_time(motion, start)


# --- spectral acceleration -------------------------------------------------------------------

@numba.njit(cache=True)
def nigam_jennings(h, omega, zeta):
    """Coefficients of the exact step of ``u'' + 2 zeta omega u' + omega^2 u = p(t)`` over
    ``h`` with ``p`` linear from ``p_i`` to ``p_{i+1}`` (Nigam & Jennings 1969): ``u_{i+1} =
    A u_i + B v_i + C p_i + D p_{i+1}``, ``v_{i+1} = A' u_i + B' v_i + C' p_i + D' p_{i+1}``.

    Written out (Nigam & Jennings' closed form) for ``omega h >= 0.5`` and ``zeta < 1``;
    otherwise (where that form loses digits to cancellation, or a critically damped oscillator)
    the same coefficients come from the exponential of the augmented system matrix (state u, u',
    p, p') by its Taylor series, which has no cancellation.
    """
    if omega * h < 0.5 or zeta >= 1.0:
        return _nigam_jennings_series(h, omega, zeta)
    k = omega * omega
    sq = math.sqrt(1.0 - zeta * zeta)
    wd = omega * sq
    e = math.exp(-zeta * omega * h)
    s, c = math.sin(wd * h), math.cos(wd * h)
    a = e * (zeta / sq * s + c)
    b = e * s / wd
    cc = (2.0 * zeta / (omega * h) + e * (((1.0 - 2.0 * zeta * zeta) / (wd * h) - zeta / sq) * s
                                          - (1.0 + 2.0 * zeta / (omega * h)) * c)) / k
    d = (1.0 - 2.0 * zeta / (omega * h) + e * ((2.0 * zeta * zeta - 1.0) / (wd * h) * s
                                               + 2.0 * zeta / (omega * h) * c)) / k
    a2 = -e * omega / sq * s
    b2 = e * (c - zeta / sq * s)
    c2 = (-1.0 / h + e * ((omega / sq + zeta / (h * sq)) * s + c / h)) / k
    d2 = (1.0 - e * (zeta / sq * s + c)) / (k * h)
    return a, b, cc, d, a2, b2, c2, d2


@numba.njit(cache=True)
def _nigam_jennings_series(h, omega, zeta):
    """:func:`nigam_jennings` by the series of ``exp(M h)``, ``M`` the matrix of
    ``(u, u', p, p')' = (u', -omega^2 u - 2 zeta omega u' + p, p', 0)``: 30 terms of the
    series reach round-off for ``(1 + zeta) omega h < 0.5``; a longer step is halved ``s``
    times and the exponential squared back (``exp(M h) = exp(M h / 2^s)^(2^s)``)."""
    halvings = 0
    while (1.0 + zeta) * omega * h / 2.0 ** halvings >= 0.5:
        halvings += 1
    step = h / 2.0 ** halvings
    m = np.zeros((4, 4))
    m[0, 1] = step
    m[1, 0] = -omega * omega * step
    m[1, 1] = -2.0 * zeta * omega * step
    m[1, 2] = step
    m[2, 3] = step
    e = np.eye(4)
    term = np.eye(4)
    for j in range(1, 30):
        term = term @ m / j
        e += term
    for _ in range(halvings):
        e = e @ e
    # u(h) = E00 u + E01 v + E02 p_i + E03 (p_{i+1} - p_i) / h; likewise v(h) with row 1
    return (e[0, 0], e[0, 1], e[0, 2] - e[0, 3] / h, e[0, 3] / h,
            e[1, 0], e[1, 1], e[1, 2] - e[1, 3] / h, e[1, 3] / h)


@numba.njit(cache=True)
def _hermite_peak(u0, v0, u1, v1, h):
    """Largest |u| of the cubic Hermite interpolant of (u, u') on a step of length h."""
    best = max(abs(u0), abs(u1))
    if v0 * v1 >= 0.0:
        return best
    # p'(s) h^-1 ... derivative of the Hermite cubic in s in [0, 1]
    qa = 6.0 * u0 + 3.0 * h * v0 - 6.0 * u1 + 3.0 * h * v1
    qb = -6.0 * u0 - 4.0 * h * v0 + 6.0 * u1 - 2.0 * h * v1
    qc = h * v0
    roots = np.empty(2)
    nroots = 0
    if abs(qa) < 1e-300:
        if qb != 0.0:
            roots[0] = -qc / qb
            nroots = 1
    else:
        disc = qb * qb - 4.0 * qa * qc
        if disc >= 0.0:
            q = -0.5 * (qb + math.copysign(math.sqrt(disc), qb))
            roots[0] = q / qa
            nroots = 1
            if q != 0.0:
                roots[1] = qc / q
                nroots = 2
    for j in range(nroots):
        s = roots[j]
        if 0.0 < s < 1.0:
            h00 = 2.0 * s ** 3 - 3.0 * s * s + 1.0
            h10 = s ** 3 - 2.0 * s * s + s
            h01 = -2.0 * s ** 3 + 3.0 * s * s
            h11 = s ** 3 - s * s
            best = max(best, abs(h00 * u0 + h10 * h * v0 + h01 * u1 + h11 * h * v1))
    return best


@numba.njit(cache=True)
def _oscillator_peak(t, a0, a1, omega, zeta, max_step):
    """Peak |u| [m] of the oscillator under the pieces (t, a0, a1), then one period of free
    vibration."""
    u = 0.0
    v = 0.0
    peak = 0.0
    h_prev = -1.0
    a = b = cc = d = a2 = b2 = c2 = d2 = 0.0
    n = t.size - 1
    tail = 2.0 * math.pi / omega
    for i in range(n + 1):
        if i < n:
            span, p_start, p_end = t[i + 1] - t[i], -a0[i], -a1[i]
        else:  # free vibration after the motion
            span, p_start, p_end = tail, 0.0, 0.0
        m = max(1, int(math.ceil(span / max_step * (1.0 - 1e-9))))
        h = span / m
        # steps of a uniformly sampled record differ in the last bits of t[i+1] - t[i]: the
        # coefficients are reused while h stays within 1e-10 of the step they were made for
        if abs(h - h_prev) > 1e-10 * h:
            a, b, cc, d, a2, b2, c2, d2 = nigam_jennings(h, omega, zeta)
            h_prev = h
        for q in range(m):
            p0 = p_start + (p_end - p_start) * q / m
            p1 = p_start + (p_end - p_start) * (q + 1) / m
            un = a * u + b * v + cc * p0 + d * p1
            vn = a2 * u + b2 * v + c2 * p0 + d2 * p1
            peak = max(peak, _hermite_peak(u, v, un, vn, h))
            u, v = un, vn
    return peak


def spectral_displacement(motion: GroundMotion, period: float,
                          damping: float = SA_DAMPING) -> float:
    """Peak relative displacement ``max |u|`` [m] of a linear oscillator of ``period`` [s] and
    ``damping`` ratio [-] on the ground motion (see the module docstring)."""
    period = check_number("period", period, "s")
    damping = check_number("damping", damping, "-")
    if damping >= 1.0:
        raise ValueError(f"damping must be in (0, 1) [-], got {damping!r}")
    t, a0, a1 = segments(motion)
    omega = 2.0 * math.pi / period
    return float(_oscillator_peak(np.ascontiguousarray(t), np.ascontiguousarray(a0),
                                  np.ascontiguousarray(a1), omega, damping,
                                  period / SA_STEPS_PER_PERIOD))


def pseudo_spectral_acceleration(motion: GroundMotion, period: float,
                                 damping: float = SA_DAMPING) -> float:
    """Pseudo-spectral acceleration ``(2 pi / T)^2 max |u|`` [m/s^2] at ``period`` T [s]."""
    return (2.0 * math.pi / float(period)) ** 2 * spectral_displacement(motion, period, damping)


# --- registry --------------------------------------------------------------------------------

@dataclass(frozen=True)
class IntensityMeasure:
    """One intensity measure: ``im(motion)`` is its value in ``unit``.

    Attributes
    ----------
    name : str
        Its name, e.g. ``"pga"`` or ``"sa(0.5)"``.
    unit : str
        Unit of its values: ``g``, ``m/s``, ``m`` or ``s``.
    exponent : float
        ``im(motion.scaled(k)) = |k|^exponent im(motion)``: 1 for peaks and spectral values, 2 for
        the Arias intensity, 0 for a duration (not scalable).
    description : str
        What it is.
    function : callable
        ``function(motion) -> value`` [unit].
    """

    name: str
    unit: str
    exponent: float
    description: str
    function: Callable[[GroundMotion], float]

    def __call__(self, motion: GroundMotion) -> float:
        return float(self.function(motion))


def _pga_g(motion: GroundMotion) -> float:
    if not isinstance(motion, GroundMotion):
        raise ValueError(f"motion must be a GroundMotion, got {type(motion).__name__}")
    return motion.peak / GRAVITY


INTENSITY_MEASURES: dict[str, IntensityMeasure] = {
    im.name: im for im in (
        IntensityMeasure("pga", "g", 1.0, "peak ground acceleration", _pga_g),
        IntensityMeasure("pgv", "m/s", 1.0, "peak ground velocity", peak_ground_velocity),
        IntensityMeasure("pgd", "m", 1.0, "peak ground displacement (no baseline correction)",
                         peak_ground_displacement),
        IntensityMeasure("arias", "m/s", 2.0, "Arias intensity", arias_intensity),
        IntensityMeasure("d5-95", "s", 0.0, "significant duration D5-95",
                         significant_duration),
    )
}
"""Intensity measures of fixed name; ``sa(T)`` (any period T > 0 [s]) is parsed by
:func:`intensity_measure`."""

_SA = re.compile(r"^sa\(\s*([^()\s]+)\s*\)$")


def intensity_measure(name: str) -> IntensityMeasure:
    """The :class:`IntensityMeasure` of ``name`` (case and spaces ignored): one of
    :data:`INTENSITY_MEASURES` or ``sa(T)`` with T the oscillator period [s], e.g. ``sa(0.5)``.
    An unknown name lists the options."""
    if not isinstance(name, str):
        raise ValueError(f"intensity measure name must be a string, got {name!r}")
    key = "".join(name.split()).lower()
    if key in INTENSITY_MEASURES:
        return INTENSITY_MEASURES[key]
    match = _SA.match(key)
    if match:
        try:
            period = float(match.group(1))
        except ValueError:
            period = math.nan
        if not (math.isfinite(period) and period > 0.0):
            raise ValueError(f"intensity measure {name!r}: the period T of sa(T) must be a "
                             f"number > 0 [s], got {match.group(1)!r}")
        return IntensityMeasure(
            key, "g", 1.0, f"5%-damped pseudo-spectral acceleration at T = {period:g} s",
            lambda motion, T=period: pseudo_spectral_acceleration(motion, T) / GRAVITY)
    raise ValueError(f"unknown intensity measure {name!r}; choose one of "
                     f"{', '.join(INTENSITY_MEASURES)} or sa(T) with T the period [s], "
                     "e.g. sa(0.5)")


def parse_intensity_measures(names: str | Iterable[str]) -> list[IntensityMeasure]:
    """Intensity measures of a comma-separated list (``"pga,pgv,sa(0.5)"``) or of a list of
    names; commas inside ``sa(...)`` are not separators."""
    if isinstance(names, str):
        names = [part for part in re.split(r",(?![^(]*\))", names)]
    out = [intensity_measure(n) for n in names if not (isinstance(n, str) and not n.strip())]
    if not out:
        raise ValueError("no intensity measure given; choose from "
                         f"{', '.join(INTENSITY_MEASURES)} or sa(T)")
    return out


def intensity_measures(motion: GroundMotion, names: str | Iterable[str]) -> dict[str, float]:
    """``{name: value}`` of the intensity measures ``names`` of ``motion`` (values in the unit
    of each measure, see the module docstring)."""
    return {im.name: im(motion) for im in parse_intensity_measures(names)}


def scale_to_im(motion: GroundMotion, name: str, level: float) -> GroundMotion:
    """The motion scaled so that its intensity measure ``name`` equals ``level``.

    One multiplication: the IMs are homogeneous in the amplitude (degree 1 for pga, pgv, pgd and
    sa(T), 2 for the Arias intensity), so the factor is ``(level / im) ** (1 / degree)``; the
    significant duration does not change with the amplitude and cannot be scaled to.

    Parameters
    ----------
    motion : GroundMotion
        The motion.
    name : str
        An intensity measure (see :func:`intensity_measure`).
    level : float
        Target value, > 0, in the unit of the measure.

    Returns
    -------
    GroundMotion
        ``motion.scaled(factor)``, named ``"<name> x <factor>"``.
    """
    im = intensity_measure(name)
    level = check_number("level", level, im.unit)
    if im.exponent == 0.0:
        raise ValueError(f"intensity measure {im.name!r} ({im.description}) does not change "
                         "when a motion is scaled; choose pga, pgv, pgd, arias or sa(T)")
    value = im(motion)
    if not value > 0.0:
        raise ValueError(f"the ground motion {motion.name!r} has {im.name} = {value!r} "
                         f"{im.unit}; it cannot be scaled to {level:g} {im.unit}")
    factor = (level / value) ** (1.0 / im.exponent)
    return motion.scaled(factor).renamed(f"{motion.name} x {factor:.4g}")


__all__ = ["INTENSITY_MEASURES", "IntensityMeasure", "arias_intensity", "ground_displacement",
           "husid_time", "intensity_measure", "intensity_measures", "parse_intensity_measures",
           "peak_ground_displacement", "peak_ground_velocity", "pseudo_spectral_acceleration",
           "scale_to_im", "segments", "significant_duration", "spectral_displacement"]

