"""Failure domain of one arch over (pulse duration, amplitude) [paper, Sect. 5.3.3, Fig. 16].

For every pulse duration t_p the amplitudes are split into intervals of one outcome class: at rest
(never activated), recovery, collapse after impacts (half cycle h >= 2) and collapse in the first
half cycle (h = 1). The outcome is not monotone in the amplitude in general, so every class change
is found: the amplitude axis is scanned on a grid, then every edge between two different classes is
bisected to the stated tolerance (recursively, should a third class appear inside an edge).

The search is written against any ``classify(duration, amplitude) -> (status, half_cycle)``
callable, so it is independent of how the outcome is computed; :func:`failure_domain` plugs in the
compiled engine.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

OutcomeKey = tuple[str, int]


@dataclass(frozen=True)
class Interval:
    """Amplitudes ``[start, end]`` [g] with one outcome class (status and half cycle)."""

    start: float
    end: float
    status: str
    half_cycle: int

    def to_dict(self) -> dict:
        return {"from": self.start, "to": self.end, "outcome": self.status,
                "half_cycle": self.half_cycle}


@dataclass(frozen=True)
class DomainSlice:
    """Outcome intervals of one pulse duration.

    Attributes
    ----------
    duration : float
        Pulse duration t_p [s].
    intervals : tuple of Interval
        Ordered, contiguous intervals covering the scanned amplitude range [g].
    tolerance : float
        Width [g] to which every boundary between intervals was bisected.
    """

    duration: float
    intervals: tuple[Interval, ...]
    tolerance: float

    @property
    def failure_acceleration(self) -> float:
        """Lowest amplitude [g] that collapses (nan if none in the scanned range)."""
        for iv in self.intervals:
            if iv.status == "collapse":
                return iv.start
        return math.nan

    @property
    def first_half_cycle_acceleration(self) -> float:
        """Lowest amplitude [g] that collapses in the first half cycle, with no impact."""
        for iv in self.intervals:
            if iv.status == "collapse" and iv.half_cycle == 1:
                return iv.start
        return math.nan

    def to_dict(self) -> dict:
        return {
            "duration": self.duration,
            "failure_acceleration": _json_float(self.failure_acceleration),
            "first_half_cycle_acceleration": _json_float(self.first_half_cycle_acceleration),
            "intervals": [iv.to_dict() for iv in self.intervals],
        }


def _json_float(x: float):
    return None if math.isnan(x) else x


def _key(outcome) -> OutcomeKey:
    status, half_cycle = outcome
    return str(status), int(half_cycle) if status == "collapse" else 0


def _refine(classify, lo, key_lo, hi, key_hi, tol, depth=0) -> list[tuple[float, OutcomeKey]]:
    """Boundaries in (lo, hi) between key_lo and key_hi, as (amplitude, key starting there)."""
    if depth > 60:
        raise RuntimeError("failure-domain bisection did not converge")
    while hi - lo > tol:
        mid = 0.5 * (lo + hi)
        key_mid = _key(classify(mid))
        if key_mid == key_lo:
            lo = mid
        elif key_mid == key_hi:
            hi = mid
        else:  # a third class inside the edge: resolve both halves
            return (_refine(classify, lo, key_lo, mid, key_mid, tol, depth + 1)
                    + _refine(classify, mid, key_mid, hi, key_hi, tol, depth + 1))
    return [(0.5 * (lo + hi), key_hi)]


def domain_slice(
    classify: Callable[[float], tuple[str, int]],
    amplitudes: Sequence[float],
    *,
    duration: float = math.nan,
    tolerance: float = 1e-4,
) -> DomainSlice:
    """Outcome intervals of ``classify(amplitude)`` over the scanned ``amplitudes``.

    Parameters
    ----------
    classify : callable
        ``classify(amplitude [g]) -> (status, half_cycle)``.
    amplitudes : sequence of float
        Increasing scan grid [g]; its ends are the ends of the domain.
    duration : float
        Pulse duration t_p [s] (recorded in the result).
    tolerance : float
        Bisection tolerance on the boundaries [g].
    """
    grid = np.asarray(amplitudes, dtype=float)
    if grid.ndim != 1 or grid.size < 2 or np.any(np.diff(grid) <= 0):
        raise ValueError("amplitudes must be an increasing sequence of at least two values [g]")
    if not (tolerance > 0):
        raise ValueError(f"tolerance must be > 0 [g], got {tolerance!r}")
    keys = [_key(classify(a)) for a in grid]
    starts: list[tuple[float, OutcomeKey]] = [(float(grid[0]), keys[0])]
    for i in range(grid.size - 1):
        if keys[i] != keys[i + 1]:
            starts += _refine(classify, grid[i], keys[i], grid[i + 1], keys[i + 1], tolerance)
    intervals = []
    for j, (start, key) in enumerate(starts):
        end = starts[j + 1][0] if j + 1 < len(starts) else float(grid[-1])
        intervals.append(Interval(float(start), float(end), key[0], key[1]))
    return DomainSlice(float(duration), tuple(intervals), float(tolerance))
