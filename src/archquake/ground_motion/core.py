"""The ground-motion value: :class:`GroundMotion` and its compiled evaluation :func:`evaluate`.

Every ground motion is a horizontal base acceleration ``xg''(t)`` [m/s^2], positive toward +x,
held as a compiled representation ``(kind, params, times, values)``. :func:`evaluate` is the one
definition of the ground acceleration: the Python API (:meth:`GroundMotion.acceleration`), the
intensity measures and the compiled engine all call it.

Kinds of the compiled representation
------------------------------------
``STEP`` (0)
    piecewise constant: ``values[i]`` on ``[times[i], times[i+1])``; 0 before ``times[0]`` and from
    ``times[-1]`` on (``values`` has one entry fewer than ``times``).
``LINEAR`` (1)
    piecewise linear through ``(times[i], values[i])``; 0 outside ``[times[0], times[-1]]``.
``HARMONIC`` (2)
    ``params = (amplitude, period, cycles, phase)``:
    ``amplitude sin(2 pi t / period + phase)`` for ``0 <= t < cycles period``, else 0 (harmonic
    motions, the one-cycle sine pulse and Makris' cycloidal pulses).
``RICKER`` (3)
    ``params = (amplitude, period, centre, variant)``: the symmetric (``variant`` 0) or
    antisymmetric (``variant`` 1) Ricker wavelet of period ``period`` centred at
    ``centre * period``, on ``[0, 2 centre period)`` (see :func:`~.pulses.ricker_wavelet`).
``MAVROEIDIS_PAPAGEORGIOU`` (4)
    ``params = (coefficient, period, gamma, nu)``: the Mavroeidis-Papageorgiou pulse on
    ``[0, gamma period)`` (see :func:`~.pulses.mavroeidis_papageorgiou_pulse`).

The analytic kinds (``kind >= HARMONIC``) share one convention, which lets a pulse study scale a
template cheaply: ``params[0]`` multiplies the acceleration [m/s^2], ``params[1]`` is the time
scale [s] (the acceleration is ``params[0] * shape(t / params[1])``), the other parameters are
dimensionless, and the only breakpoints are the start ``t = 0`` and the end
:func:`analytic_duration` (the pulses are smooth in between; the acceleration or its slope may
jump at the ends).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numba
import numpy as np

from .._equality import value_equality
from ..constants import GRAVITY
from ..defaults import MAX_ACCELERATION_G

#: Kinds of the compiled representation ``(kind, params, times, values)``: ``STEP`` (0),
#: ``LINEAR`` (1), ``HARMONIC`` (2), ``RICKER`` (3), ``MAVROEIDIS_PAPAGEORGIOU`` (4); see the
#: module's description.
STEP, LINEAR, HARMONIC, RICKER, MAVROEIDIS_PAPAGEORGIOU = 0, 1, 2, 3, 4
ANALYTIC_KINDS = (HARMONIC, RICKER, MAVROEIDIS_PAPAGEORGIOU)
"""The analytic kinds: evaluated from ``params`` (no table); breakpoints only at ``t = 0`` and
:func:`analytic_duration`."""
KIND_NAMES = {STEP: "STEP", LINEAR: "LINEAR", HARMONIC: "HARMONIC", RICKER: "RICKER",
              MAVROEIDIS_PAPAGEORGIOU: "MAVROEIDIS_PAPAGEORGIOU"}
"""Name of every kind, by its number."""
_PARAM_COUNT = {HARMONIC: 4, RICKER: 4, MAVROEIDIS_PAPAGEORGIOU: 4}

RICKER_ANTISYMMETRIC_PEAK = math.sqrt(6.0 * (3.0 - math.sqrt(6.0))) * math.exp(
    -(3.0 - math.sqrt(6.0)) / 2.0)
r"""Peak of the antisymmetric Ricker shape [-], by which it is divided so that its peak is the
amplitude.

.. math:: \beta = \max_x \left| (x^2 - 3)\, x\, e^{-x^2/2} \right|
          = \sqrt{6 (3 - \sqrt{6})}\; e^{-(3 - \sqrt{6})/2} = 1.38012\ldots,

reached at :math:`x^2 = 3 - \sqrt{6}`."""


@numba.njit(cache=True)
def analytic_duration(kind, params):
    """Time [s] from which an analytic ground motion (``kind >= HARMONIC``) is zero."""
    if kind == HARMONIC:
        return params[1] * params[2]
    if kind == RICKER:
        return 2.0 * params[2] * params[1]
    return params[2] * params[1]  # MAVROEIDIS_PAPAGEORGIOU


@numba.njit(cache=True)
def evaluate(t, kind, params, times, values):
    """Ground acceleration [m/s^2] at time ``t`` [s] of a compiled ground motion."""
    if kind >= HARMONIC:
        if t < 0.0 or t >= analytic_duration(kind, params):
            return 0.0
        amplitude, period = params[0], params[1]
        if kind == HARMONIC:
            return amplitude * math.sin(2.0 * math.pi * t / period + params[3])
        if kind == RICKER:
            s = t / period - params[2]
            if params[3] == 0.0:  # symmetric: (1 - 2 x^2) exp(-x^2), x = pi (t - t0) / T
                x2 = (math.pi * s) ** 2
                return amplitude * (1.0 - 2.0 * x2) * math.exp(-x2)
            x = 2.0 * math.pi * s / math.sqrt(3.0)  # antisymmetric
            return (amplitude / RICKER_ANTISYMMETRIC_PEAK) * (x * x - 3.0) * x * math.exp(
                -0.5 * x * x)
        # MAVROEIDIS_PAPAGEORGIOU
        gamma, nu = params[2], params[3]
        u = 2.0 * math.pi * (t / period - 0.5 * gamma)
        return -(amplitude / gamma) * (math.sin(u / gamma) * math.cos(u + nu)
                                       + gamma * math.sin(u + nu) * (1.0 + math.cos(u / gamma)))
    n = times.size
    if n == 0 or t < times[0]:
        return 0.0
    if kind == STEP:
        if t >= times[n - 1]:
            return 0.0
        i = np.searchsorted(times, t, side="right") - 1
        return values[i]
    # LINEAR
    if t > times[n - 1]:
        return 0.0
    i = np.searchsorted(times, t, side="right") - 1
    if i >= n - 1:
        return values[n - 1]
    w = (t - times[i]) / (times[i + 1] - times[i])
    return values[i] + w * (values[i + 1] - values[i])


@numba.njit(cache=True)
def evaluate_many(t, kind, params, times, values):
    """:func:`evaluate` at every time of the array ``t`` [s]."""
    out = np.empty(t.size)
    for i in range(t.size):
        out[i] = evaluate(t[i], kind, params, times, values)
    return out


@value_equality
@dataclass(frozen=True)
class GroundMotion:
    """A horizontal ground acceleration history.

    Build one with a factory of :data:`~archquake.ground_motion.GROUND_MOTIONS` (pulses, records,
    the stochastic model) rather than directly.

    Parameters
    ----------
    kind : int
        ``STEP``, ``LINEAR`` or an analytic kind (see the module docstring).
    times : array of float
        Times [s] of the table (STEP and LINEAR).
    values : array of float
        Accelerations [m/s^2] of the table (STEP and LINEAR).
    params : array of float
        Parameters of an analytic kind [SI units]; a HARMONIC motion given three parameters
        ``(amplitude, period, cycles)`` gets ``phase = 0``.
    name : str
        Description, for plots, reports and tables.

    Two ground motions are equal (and hash equal) when every field is equal, arrays element by
    element.
    """

    kind: int
    times: np.ndarray = field(default_factory=lambda: np.zeros(0))
    values: np.ndarray = field(default_factory=lambda: np.zeros(0))
    params: np.ndarray = field(default_factory=lambda: np.zeros(0))
    name: str = ""

    def __post_init__(self):
        for key in ("times", "values", "params"):
            arr = np.array(getattr(self, key), dtype=float).ravel()
            if not np.all(np.isfinite(arr)):
                raise ValueError(f"ground motion {key} must be finite numbers")
            if key == "params" and self.kind == HARMONIC and arr.size == 3:
                arr = np.append(arr, 0.0)
            arr.setflags(write=False)
            object.__setattr__(self, key, arr)
        if self.kind in (STEP, LINEAR):
            if self.times.size < 2:
                raise ValueError("a ground motion table needs at least two time points")
            if np.any(np.diff(self.times) <= 0):
                raise ValueError("ground motion times must be strictly increasing")
            expected = self.times.size - 1 if self.kind == STEP else self.times.size
            if self.values.size != expected:
                raise ValueError(
                    f"ground motion table: expected {expected} values for {self.times.size} "
                    f"times, got {self.values.size}"
                )
        elif self.kind in ANALYTIC_KINDS:
            if self.params.size != _PARAM_COUNT[self.kind]:
                raise ValueError(f"a {KIND_NAMES[self.kind]} ground motion needs "
                                 f"{_PARAM_COUNT[self.kind]} parameters, got {self.params.size}")
            if self.params[1] <= 0 or self.params[2] <= 0:
                raise ValueError(f"a {KIND_NAMES[self.kind]} ground motion needs a time scale "
                                 f"params[1] > 0 [s] and params[2] > 0, got {self.params}")
        else:
            raise ValueError(f"unknown ground motion kind {self.kind!r}")
        # params[0] is the amplitude of every analytic kind: a cheap bound of the peak
        size = abs(float(self.params[0])) if self.kind in ANALYTIC_KINDS else (
            float(np.max(np.abs(self.values))) if self.values.size else 0.0)
        check_peak("ground acceleration", size)

    @property
    def is_analytic(self) -> bool:
        """True for the analytic kinds (a closed-form acceleration), False for tables."""
        return self.kind in ANALYTIC_KINDS

    @property
    def duration(self) -> float:
        """Time [s] from which the ground acceleration is zero for ever."""
        if self.is_analytic:
            return float(analytic_duration(self.kind, self.params))
        return float(self.times[-1])

    @property
    def breakpoints(self) -> np.ndarray:
        """Times [s] where the acceleration or its slope may jump, sorted, ending at duration."""
        if self.is_analytic:
            return np.array([0.0, self.duration])
        return np.unique(np.concatenate(([0.0], self.times)))

    @property
    def peak(self) -> float:
        """Peak absolute ground acceleration [m/s^2]."""
        if self.kind == HARMONIC:
            return _harmonic_peak(self.params)
        if self.kind == RICKER:
            return abs(float(self.params[0]))
        if self.is_analytic:
            return _sampled_peak(self)
        return float(np.max(np.abs(self.values))) if self.values.size else 0.0

    def compiled(self) -> tuple[int, np.ndarray, np.ndarray, np.ndarray]:
        """``(kind, params, times, values)`` for :func:`evaluate` and the compiled engine."""
        return self.kind, self.params, self.times, self.values

    def acceleration(self, t) -> np.ndarray:
        """Ground acceleration [m/s^2] at time(s) ``t`` [s]."""
        t_arr = np.ascontiguousarray(np.atleast_1d(np.asarray(t, dtype=float)).ravel())
        out = evaluate_many(t_arr, self.kind, self.params, self.times, self.values)
        if np.ndim(t):
            return out.reshape(np.shape(t))
        return float(out[0])

    def scaled(self, factor: float) -> GroundMotion:
        """The same motion with every acceleration multiplied by ``factor`` [-] (same name)."""
        factor = float(factor)
        if not math.isfinite(factor):
            raise ValueError(f"scale factor must be a finite number, got {factor!r}")
        params = self.params.copy()
        if self.is_analytic:
            params[0] *= factor
        return GroundMotion(self.kind, self.times, self.values * factor, params, self.name)

    def reversed(self) -> GroundMotion:
        """The other polarity, ``-xg''(t)``: the same motion with its sign flipped."""
        name = self.name[: -len(" (reversed)")] if self.name.endswith(" (reversed)") else (
            f"{self.name} (reversed)")
        return GroundMotion(self.kind, self.times, -self.values, _negated(self),
                            name)

    def renamed(self, name: str) -> GroundMotion:
        """The same motion under another ``name``."""
        return GroundMotion(self.kind, self.times, self.values, self.params, str(name))

    def tabulated(self, step: float | None = None) -> GroundMotion:
        """A ``LINEAR`` table of this motion: sampled every ``step`` [s] or finer.

        Tables (STEP, LINEAR) are returned as they are, except that a STEP motion is refused
        (its jumps have no piecewise-linear equivalent). Analytic kinds are sampled on a uniform
        grid over ``[0, duration]`` with spacing at most ``step`` (default: the time scale
        ``params[1]`` / 1024); the table's interpolation error is then about
        ``step^2 max|xg''''| / 8``.
        """
        if self.kind == LINEAR:
            return self
        if self.kind == STEP:
            raise ValueError("a piecewise-constant (STEP) motion has no linear table")
        duration = self.duration
        step = self.params[1] / 1024.0 if step is None else float(step)
        if not (math.isfinite(step) and step > 0):
            raise ValueError(f"step must be a finite time > 0 [s], got {step!r}")
        n = max(2, int(math.ceil(duration / step)) + 1)
        t = np.linspace(0.0, duration, n)
        a = self.acceleration(t[:-1])
        # the last sample takes the left limit, so the table ends where the pulse ends
        a_end = evaluate(np.nextafter(duration, 0.0), self.kind, self.params, self.times,
                         self.values)
        return GroundMotion(LINEAR, t, np.append(a, a_end), name=self.name)


def _negated(motion: GroundMotion) -> np.ndarray:
    params = motion.params.copy()
    if motion.is_analytic:
        params[0] = -params[0]
    return params


def _harmonic_peak(params) -> float:
    """max |A sin(theta)| over theta in [phase, phase + 2 pi cycles)."""
    amplitude, _, cycles, phase = (float(p) for p in params)
    lo, hi = phase, phase + 2.0 * math.pi * cycles
    first_peak = math.ceil((lo - math.pi / 2.0) / math.pi)  # peaks at pi/2 + k pi
    if math.pi / 2.0 + first_peak * math.pi < hi:
        return abs(amplitude)
    return abs(amplitude) * max(abs(math.sin(lo)), abs(math.sin(hi)))


def _sampled_peak(motion: GroundMotion) -> float:
    """Peak |acceleration| of an analytic motion: dense sampling, then a local refinement."""
    from scipy.optimize import minimize_scalar

    duration = motion.duration
    t = np.linspace(0.0, duration, 20001)[:-1]
    a = np.abs(motion.acceleration(t))
    i = int(np.argmax(a))
    lo, hi = t[max(i - 1, 0)], t[min(i + 1, t.size - 1)]
    if hi <= lo:
        return float(a[i])
    res = minimize_scalar(lambda x: -abs(motion.acceleration(x)), bounds=(lo, hi),
                          method="bounded", options={"xatol": 1e-14 * duration})
    return float(max(a[i], -res.fun))


def check_peak(what: str, peak: float) -> None:
    """Refuse accelerations beyond :data:`archquake.defaults.MAX_ACCELERATION_G` (``peak`` in
    m/s^2): far beyond any earthquake, and from about 1e150 g the integrator's steps underflow."""
    if peak > MAX_ACCELERATION_G * GRAVITY:
        raise ValueError(f"{what} must be at most {MAX_ACCELERATION_G:g} g in magnitude, got "
                         f"{peak / GRAVITY:.4g} g")


def check_number(name: str, value: float, unit: str, *, positive: bool = True,
                 at_most: float | None = None, limit_name: str = "") -> float:
    """``value`` as a finite float (``> 0`` if ``positive``, ``<= at_most`` if given), or a
    ValueError naming it (and ``limit_name``, the constant that sets ``at_most``)."""
    try:
        value = float(value)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be a number [{unit}], got {value!r}") from exc
    if not math.isfinite(value) or (positive and value <= 0):
        condition = "a finite number > 0" if positive else "a finite number"
        raise ValueError(f"{name} must be {condition} [{unit}], got {value!r}")
    if at_most is not None and value > at_most:
        named = f" ({limit_name})" if limit_name else ""
        raise ValueError(f"{name} must be at most {at_most:g} [{unit}]{named}, got {value!r}")
    return value


def still_ground() -> GroundMotion:
    """A still ground: no ground motion (what a free vibration runs under).

    Returns
    -------
    GroundMotion
        Zero acceleration; its name is ``"free vibration"``.
    """
    return GroundMotion(STEP, [0.0, 1e-300], [0.0], name="free vibration")


__all__ = ["ANALYTIC_KINDS", "GRAVITY", "HARMONIC", "LINEAR", "MAVROEIDIS_PAPAGEORGIOU", "RICKER",
           "STEP", "GroundMotion", "analytic_duration", "check_number", "evaluate",
           "evaluate_many", "still_ground"]
