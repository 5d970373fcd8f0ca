"""Ground motions: horizontal base accelerations xg''(t) [m/s^2], positive toward +x.

Every ground motion is a :class:`GroundMotion` with a vectorised :meth:`GroundMotion.acceleration`,
a ``duration`` after which the ground is still, the ``breakpoints`` where the acceleration or its
slope jumps (the integrator never steps across them), and a compiled representation
``(kind, params, times, values)`` evaluated by :func:`evaluate` -- the one definition of the ground
acceleration used by both the Python API and the compiled engine.

Kinds of the compiled representation
------------------------------------
``STEP`` (0)
    piecewise constant: ``values[i]`` on ``[times[i], times[i+1])``; 0 before ``times[0]`` and from
    ``times[-1]`` on (``values`` has one entry fewer than ``times``).
``LINEAR`` (1)
    piecewise linear through ``(times[i], values[i])``; 0 outside ``[times[0], times[-1]]``.
``HARMONIC`` (2)
    ``params = (amplitude, period, cycles)``: ``amplitude sin(2 pi t / period)`` for
    ``0 <= t < cycles period``, else 0.

Shapes are chosen by name from :data:`GROUND_MOTIONS`.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numba
import numpy as np

from .geometry import GRAVITY

STEP, LINEAR, HARMONIC = 0, 1, 2


@numba.njit(cache=True)
def evaluate(t, kind, params, times, values):
    """Ground acceleration [m/s^2] at time ``t`` [s] of a compiled ground motion."""
    if kind == HARMONIC:
        amplitude, period, cycles = params[0], params[1], params[2]
        if t < 0.0 or t >= cycles * period:
            return 0.0
        return amplitude * math.sin(2.0 * math.pi * t / period)
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


@dataclass(frozen=True)
class GroundMotion:
    """A horizontal ground acceleration history.

    Parameters
    ----------
    kind : int
        ``STEP``, ``LINEAR`` or ``HARMONIC`` (see the module docstring).
    times : array of float
        Times [s] of the table (STEP and LINEAR).
    values : array of float
        Accelerations [m/s^2] of the table (STEP and LINEAR).
    params : array of float
        Parameters of an analytic kind [SI units].
    name : str
        Description, for plots and reports.
    """

    kind: int
    times: np.ndarray = field(default_factory=lambda: np.zeros(0))
    values: np.ndarray = field(default_factory=lambda: np.zeros(0))
    params: np.ndarray = field(default_factory=lambda: np.zeros(0))
    name: str = ""

    def __post_init__(self):
        for key in ("times", "values", "params"):
            arr = np.ascontiguousarray(getattr(self, key), dtype=float)
            if not np.all(np.isfinite(arr)):
                raise ValueError(f"ground motion {key} must be finite numbers")
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
        elif self.kind == HARMONIC:
            if self.params.size != 3:
                raise ValueError("a harmonic ground motion needs (amplitude, period, cycles)")
        else:
            raise ValueError(f"unknown ground motion kind {self.kind!r}")

    @property
    def duration(self) -> float:
        """Time [s] from which the ground acceleration is zero for ever."""
        if self.kind == HARMONIC:
            return float(self.params[1] * self.params[2])
        return float(self.times[-1])

    @property
    def breakpoints(self) -> np.ndarray:
        """Times [s] where the acceleration or its slope may jump, sorted, ending at duration."""
        if self.kind == HARMONIC:
            return np.array([0.0, self.duration])
        return np.unique(np.concatenate(([0.0], self.times)))

    @property
    def peak(self) -> float:
        """Peak absolute ground acceleration [m/s^2]."""
        if self.kind == HARMONIC:
            return abs(float(self.params[0]))
        return float(np.max(np.abs(self.values))) if self.values.size else 0.0

    def compiled(self) -> tuple[int, np.ndarray, np.ndarray, np.ndarray]:
        """``(kind, params, times, values)`` for :func:`evaluate` and the compiled engine."""
        return self.kind, self.params, self.times, self.values

    def acceleration(self, t) -> np.ndarray:
        """Ground acceleration [m/s^2] at time(s) ``t`` [s]."""
        t_arr = np.atleast_1d(np.asarray(t, dtype=float))
        out = np.array([evaluate(x, self.kind, self.params, self.times, self.values)
                        for x in t_arr])
        return out if np.ndim(t) else float(out[0])

    def scaled(self, factor: float) -> GroundMotion:
        """The same motion with every acceleration multiplied by ``factor``."""
        params = self.params.copy()
        if self.kind == HARMONIC:
            params[0] *= factor
        return GroundMotion(self.kind, self.times, self.values * factor, params, self.name)


def _check(name: str, value: float, unit: str, *, positive: bool = True) -> float:
    try:
        value = float(value)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be a number [{unit}], got {value!r}") from exc
    if not math.isfinite(value) or (positive and value <= 0):
        condition = "a finite number > 0" if positive else "a finite number"
        raise ValueError(f"{name} must be {condition} [{unit}], got {value!r}")
    return value


def oppenheim_pulse(amplitude: float, duration: float) -> GroundMotion:
    """Oppenheim's pulse [paper, Sect. 5.3.1]: ``amplitude`` for ``duration`` t_p, then
    ``-amplitude/2`` for ``2 t_p``, then rest (zero net ground velocity).

    Parameters
    ----------
    amplitude : float
        Signed ground acceleration of the first pulse [m/s^2]; the paper's ``xg'' = -1 g`` is
        ``-GRAVITY``.
    duration : float
        Duration t_p of the first pulse [s].
    """
    a = _check("amplitude", amplitude, "m/s^2", positive=False)
    tp = _check("duration", duration, "s")
    return GroundMotion(STEP, [0.0, tp, 3.0 * tp], [a, -a / 2.0],
                        name=f"Oppenheim pulse {a / GRAVITY:+.3g} g, t_p = {tp:.3g} s")


def rectangular_pulse(amplitude: float, duration: float) -> GroundMotion:
    """One rectangular pulse: ``amplitude`` [m/s^2] for ``duration`` [s], then rest."""
    a = _check("amplitude", amplitude, "m/s^2", positive=False)
    tp = _check("duration", duration, "s")
    return GroundMotion(STEP, [0.0, tp], [a],
                        name=f"rectangular pulse {a / GRAVITY:+.3g} g, {tp:.3g} s")


def sine_pulse(amplitude: float, duration: float) -> GroundMotion:
    """One full cycle of ``amplitude sin(2 pi t / duration)`` [m/s^2], then rest."""
    return harmonic(amplitude, duration, cycles=1, name_prefix="one-cycle sine pulse")


def harmonic(amplitude: float, duration: float, cycles: float = 1,
             *, name_prefix: str = "harmonic") -> GroundMotion:
    """``cycles`` cycles of ``amplitude sin(2 pi t / duration)``: ``duration`` is the period [s]."""
    a = _check("amplitude", amplitude, "m/s^2", positive=False)
    period = _check("duration", duration, "s")
    cycles = _check("cycles", cycles, "-")
    return GroundMotion(HARMONIC, params=[a, period, cycles],
                        name=f"{name_prefix} {a / GRAVITY:+.3g} g, T = {period:.3g} s")


GROUND_MOTIONS: dict[str, Callable[..., GroundMotion]] = {
    "oppenheim": oppenheim_pulse,
    "rectangular": rectangular_pulse,
    "sine": sine_pulse,
    "harmonic": harmonic,
}
"""Registry of analytic ground motions: name -> factory(amplitude [m/s^2], duration [s], ...)."""


def ground_motion(name: str, amplitude: float, duration: float, **kwargs) -> GroundMotion:
    """Ground motion by name from :data:`GROUND_MOTIONS`; an unknown name lists the options."""
    try:
        factory = GROUND_MOTIONS[name]
    except KeyError:
        raise ValueError(
            f"unknown ground motion {name!r}; choose one of {sorted(GROUND_MOTIONS)}"
        ) from None
    return factory(amplitude, duration, **kwargs)


def free_vibration() -> GroundMotion:
    """No ground motion (a still ground), for free vibrations."""
    return GroundMotion(STEP, [0.0, 1e-300], [0.0], name="free vibration")
