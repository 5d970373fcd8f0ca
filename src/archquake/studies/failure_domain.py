r"""Failure domain of one arch over (pulse duration, amplitude) [paper, Sect. 5.3.3, Fig. 16].

For every pulse duration :math:`t_p` [s] the amplitudes :math:`a` [g] are split into intervals of
one outcome class: at rest (the pulse never reaches an activation threshold, e.g.
:math:`a < k` for Oppenheim's pulse on the nominal arch), recovery (region (1) of Fig. 16 of
[1]_), collapse after impacts (half cycle :math:`h \ge 2`, region (2)) and collapse in the first
half cycle (:math:`h = 1`, region (3)). The lowest collapsing amplitude of a duration is the
failure curve of Fig. 16 of [1]_: its point :math:`Q = (\bar t_p, \bar{\ddot x}_g / g)` is the
threshold of the step fragility of the nominal arch, Eq. (10) in [1]_,

.. math::

    P_F(\bar t_p, \ddot x_g) = \begin{cases} 0 & \ddot x_g < \bar{\ddot x}_g, \\
    1 & \ddot x_g \ge \bar{\ddot x}_g \end{cases}

(:attr:`DomainSlice.failure_acceleration_g`). The outcome is not monotone in the amplitude in
general, so every class change is found: the amplitude axis is scanned on a grid, then every edge
between two different classes is bisected to the stated resolution (recursively, should a third
class appear inside an edge); a boundary is reported at the middle of its last bracket, within
half the resolution of the class change.

The search is written against any ``classify(amplitude) -> (status, half_cycle)`` callable, so it
is independent of how the outcome is computed; :func:`domain_of` plugs in an arch's
:class:`~archquake.fourlink.dynamics.ArchDynamics` (its mechanisms, tables and coefficients of
restitution, built once): the whole (duration x amplitude) scan is one compiled call, and only the
bisection steps are single analyses. ``ArchDynamics.from_arch(arch,
restitution).failure_domain(...)`` is the way in.

Direction of the pulse
----------------------
``direction="l"``: the first pulse is ``-a g`` (toward -x), which opens Mech-l when
``a >= k_l``; ``direction="r"``: ``+a g``, which opens Mech-r when ``a >= k_r`` [paper, eq. (2)].
Amplitudes ``a`` are given and reported in g, positive.

References
----------
.. [1] The paper, Sect. 5.3.3, Fig. 16 and Eq. (10).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from ..defaults import (
    DEFAULT_EXTEND_TO_G,
    DEFAULT_RESOLUTION_G,
    DOMAIN_AMPLITUDES_G,
    DOMAIN_DURATIONS,
    MAX_ACCELERATION_G,
    MAX_GRID_POINTS,
)

OutcomeKey = tuple[str, int]


@dataclass(frozen=True)
class Interval:
    """Amplitudes ``[start, end]`` [g] with one outcome class (status and half cycle).

    Attributes
    ----------
    start, end : float
        Ends of the interval [g].
    status : str
        Label of the outcome (:attr:`archquake.status.Status.label`): ``"rest"``,
        ``"recovery"`` or ``"collapse"``; ``"undecided"`` for amplitudes whose analyses the
        model left undecided (the rigid-block model can): neither a collapse nor a recovery.
    half_cycle : int
        Half cycle of the collapse [-] (1: the first, with no impact); 0 unless a collapse.
    """

    start: float
    end: float
    status: str
    half_cycle: int

    def to_dict(self) -> dict:
        """The interval as JSON-ready data.

        Returns
        -------
        dict
            ``{"from": start [g], "to": end [g], "outcome": status, "half_cycle": ...}``.
        """
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
    resolution : float
        Width [g] to which every boundary between intervals was bisected.
    """

    duration: float
    intervals: tuple[Interval, ...]
    resolution: float

    @property
    def failure_acceleration_g(self) -> float:
        """Lowest amplitude [g] that collapses, to the resolution (nan if none in the scanned
        range): the failure curve of Fig. 16 of the paper at this duration, i.e. its point Q,
        the threshold of the step fragility of eq. (10)."""
        for iv in self.intervals:
            if iv.status == "collapse":
                return iv.start
        return math.nan

    @property
    def first_half_cycle_acceleration_g(self) -> float:
        """Lowest amplitude [g] that collapses in the first half cycle, with no impact
        (Oppenheim's boundary in Fig. 16 of the paper; nan if none in the scanned range)."""
        for iv in self.intervals:
            if iv.status == "collapse" and iv.half_cycle == 1:
                return iv.start
        return math.nan

    @property
    def recovery_above_g(self) -> list[tuple[float, float]]:
        """Recovery intervals ``(from, to)`` [g] above the failure acceleration: amplitudes that
        collapse the arch less easily than a lower one (empty if none, or no collapse)."""
        failure = self.failure_acceleration_g
        if math.isnan(failure):
            return []
        return [(iv.start, iv.end) for iv in self.intervals
                if iv.status == "recovery" and iv.start > failure]

    @property
    def scanned_to_g(self) -> float:
        """Largest amplitude of the scan [g]: a boundary reported as nan lies beyond it."""
        return self.intervals[-1].end

    def to_dict(self) -> dict:
        """The slice as JSON-ready data.

        Returns
        -------
        dict
            ``duration`` [s], ``failure_acceleration``, ``first_half_cycle_acceleration`` (None
            for nan) and ``scanned_to`` [g], and the ``intervals`` (:meth:`Interval.to_dict`).
        """
        return {
            "duration": self.duration,
            "failure_acceleration": _json_float(self.failure_acceleration_g),
            "first_half_cycle_acceleration": _json_float(self.first_half_cycle_acceleration_g),
            "scanned_to": self.scanned_to_g,
            "intervals": [iv.to_dict() for iv in self.intervals],
        }


def _json_float(x: float):
    return None if math.isnan(x) else x


def _key(outcome) -> OutcomeKey:
    status, half_cycle = outcome
    label = str(status)  # a Status member or its label
    return label, int(half_cycle) if label == "collapse" else 0


def _refine(classify, lo, key_lo, hi, key_hi, tol, depth=0) -> list[tuple[float, OutcomeKey]]:
    """Boundaries in (lo, hi) between key_lo and key_hi, as (amplitude, key starting there)."""
    if depth > 60:
        raise RuntimeError("failure-domain bisection did not converge")
    while hi - lo > tol:
        mid = 0.5 * (lo + hi)
        if not lo < mid < hi:  # lo and hi are neighbouring floats: as fine as it gets
            break
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
    resolution: float = 1e-4,
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
    resolution : float
        Bisection width of the boundaries [g]; a width below the spacing of floating-point
        numbers ends with the boundary between two neighbouring floats.

    Returns
    -------
    DomainSlice
        Contiguous intervals from the first to the last grid amplitude; a boundary lies at the
        middle of its last bracket.

    Raises
    ------
    ValueError
        If ``amplitudes`` is not increasing with at least two values, or ``resolution <= 0``.
    RuntimeError
        If new classes keep appearing inside an edge (more than 60 nested bisections).

    Examples
    --------
    A classifier with one class change, at 0.3:

    >>> s = domain_slice(lambda a: ("collapse", 1) if a >= 0.3 else ("recovery", 0),
    ...                  [0.1, 0.2, 0.4, 0.5], resolution=1e-3)
    >>> [(iv.status, round(iv.start, 3)) for iv in s.intervals]
    [('recovery', 0.1), ('collapse', 0.3)]
    >>> abs(s.failure_acceleration_g - 0.3) <= 0.5e-3
    True
    """
    grid = np.asarray(amplitudes, dtype=float)
    if grid.ndim != 1 or grid.size < 2 or np.any(np.diff(grid) <= 0):
        raise ValueError("amplitudes must be an increasing sequence of at least two values [g]")
    if not (resolution > 0):
        raise ValueError(f"resolution must be > 0 [g], got {resolution!r}")
    keys = [_key(classify(a)) for a in grid]
    starts: list[tuple[float, OutcomeKey]] = [(float(grid[0]), keys[0])]
    for i in range(grid.size - 1):
        if keys[i] != keys[i + 1]:
            starts += _refine(classify, grid[i], keys[i], grid[i + 1], keys[i + 1], resolution)
    intervals = []
    for j, (start, key) in enumerate(starts):
        end = starts[j + 1][0] if j + 1 < len(starts) else float(grid[-1])
        intervals.append(Interval(float(start), float(end), key[0], key[1]))
    return DomainSlice(float(duration), tuple(intervals), float(resolution))


# ---------------------------------------------------------------------------------------------
# The failure domain of an arch, with the compiled engine
# ---------------------------------------------------------------------------------------------

EXTENSION_BLOCK = 128
"""Amplitudes analysed at a time (one compiled call) while a scan is extended."""

PULSE_SIGNS = {"l": -1.0, "r": 1.0}
"""Sign of the first pulse for each direction: ``"l"`` is ``-a g`` (opens Mech-l), ``"r"`` +a g."""


@dataclass(frozen=True, eq=False)
class FailureDomain:
    """Outcome regions of one arch over (pulse duration, amplitude) [paper, Fig. 16].

    Attributes
    ----------
    slices : tuple of DomainSlice
        One per pulse duration, in the given order.
    direction : str
        ``"l"`` (first pulse ``-a g``, Mech-l) or ``"r"`` (``+a g``, Mech-r).
    limit_multiplier : float
        Limit-analysis load multiplier k of the mechanism the pulse opens (k_l or k_r) [-]:
        below ``a = k`` the arch moves rigidly with the ground (the dashed line of Fig. 16).
    load_multipliers : tuple of float
        ``(k_l, k_r)`` of the arch [-].
    restitution : tuple of float
        ``(c_lr, c_rl)`` used at the impacts [-].
    motion : str
        Pulse shape (name in :data:`archquake.ground_motion.GROUND_MOTIONS`).
    extend_to_g : float or None
        Cap [g] up to which a scan was extended to find the collapse in the first half cycle
        (None: the scan was the grid alone).
    """

    slices: tuple[DomainSlice, ...]
    direction: str
    limit_multiplier: float
    load_multipliers: tuple[float, float]
    restitution: tuple[float, float]
    motion: str = "oppenheim"
    extend_to_g: float | None = None

    @property
    def durations(self) -> np.ndarray:
        """Pulse durations t_p [s]."""
        return np.array([s.duration for s in self.slices])

    @property
    def failure_accelerations_g(self) -> np.ndarray:
        """Lowest collapsing amplitude per duration [g] (the failure curve; nan: none)."""
        return np.array([s.failure_acceleration_g for s in self.slices])

    @property
    def first_half_cycle_accelerations_g(self) -> np.ndarray:
        """Lowest amplitude collapsing in the first half cycle per duration [g] (Oppenheim's
        curve; nan: none in the scanned range)."""
        return np.array([s.first_half_cycle_acceleration_g for s in self.slices])

    def slice(self, duration: float) -> DomainSlice:
        """The slice of one pulse duration.

        Parameters
        ----------
        duration : float
            Pulse duration t_p [s], one of :attr:`durations` (to 1e-9 s).

        Returns
        -------
        DomainSlice

        Raises
        ------
        ValueError
            If ``duration`` is not one of the domain's.
        """
        for s in self.slices:
            if abs(s.duration - duration) <= 1e-9:
                return s
        raise ValueError(f"duration {duration!r} s is not one of the domain's durations "
                         f"{self.durations.tolist()}")

    def to_list(self) -> list[dict]:
        """The domain as JSON-ready data.

        Returns
        -------
        list of dict
            :meth:`DomainSlice.to_dict` of every slice (durations in s, amplitudes in g).
        """
        return [s.to_dict() for s in self.slices]


def check_durations(durations) -> np.ndarray:
    d = np.atleast_1d(np.asarray(durations, dtype=float))
    if d.ndim != 1 or d.size == 0:
        raise ValueError("durations must be a non-empty sequence of pulse durations t_p [s]")
    if not np.all(np.isfinite(d)) or np.any(d <= 0):
        raise ValueError(f"durations must be finite and > 0 [s], got {d.tolist()}")
    return d


def check_amplitudes(amplitudes_g) -> np.ndarray:
    a = np.atleast_1d(np.asarray(amplitudes_g, dtype=float))
    if a.ndim != 1 or a.size < 2 or not np.all(np.isfinite(a)) or np.any(np.diff(a) <= 0):
        raise ValueError("amplitudes must be an increasing sequence of at least two finite "
                         "values [g]")
    if a[0] < 0:
        raise ValueError(f"amplitudes must be >= 0 [g] (the direction gives the sign), got "
                         f"{a[0]!r}")
    if a[-1] > MAX_ACCELERATION_G:
        raise ValueError(f"amplitudes must be at most {MAX_ACCELERATION_G:g} g, got "
                         f"{float(a[-1])!r}")
    return a


def check_direction(direction: str) -> str:
    """Validate a pulse direction, ``"l"`` or ``"r"``.

    Parameters
    ----------
    direction : str
        ``"l"`` (first pulse ``-a g``, opens Mech-l) or ``"r"`` (``+a g``, opens Mech-r).

    Returns
    -------
    str
        ``direction``.

    Raises
    ------
    ValueError
        For any other value.
    """
    if direction not in PULSE_SIGNS:
        raise ValueError(f"direction must be 'l' (first pulse -a g) or 'r' (+a g), got "
                         f"{direction!r}")
    return direction


def inclusive_range(start: float, stop: float, step: float) -> np.ndarray:
    """``start, start + step, ...`` up to ``stop`` included (when within ``step/2``).

    The values are rounded to 12 decimals so that e.g. ``inclusive_range(0.2, 1.0, 0.01)`` gives
    exactly the decimal grid 0.20, 0.21, ..., 1.00 (as floats).

    Parameters
    ----------
    start, stop : float
        First value and last value (included if ``start + k step`` is within ``step/2`` of it).
    step : float
        Spacing, > 0.

    Returns
    -------
    ndarray
        The values.

    Raises
    ------
    ValueError
        For a non-finite value, a step <= 0, ``stop < start`` or more than
        :data:`archquake.defaults.MAX_GRID_POINTS` values.
    """
    for name, value in (("start", start), ("stop", stop), ("step", step)):
        if not math.isfinite(value):
            raise ValueError(f"range {name} must be a finite number, got {value!r}")
    if not step > 0:
        raise ValueError(f"range step must be > 0, got {step!r}")
    if stop < start:
        raise ValueError(f"range stop must be >= start, got {start!r}:{stop!r}")
    count = math.floor((stop - start) / step + 0.5) + 1
    if count > MAX_GRID_POINTS:
        raise ValueError(f"the range {start:g}:{stop:g}:{step:g} has {count} values, more than "
                         f"the {MAX_GRID_POINTS} of the largest grid (MAX_GRID_POINTS)")
    return np.round(start + step * np.arange(count), 12)


def domain_of(dynamics, durations=None, amplitudes_g=None, *, direction: str = "l",
              resolution: float = DEFAULT_RESOLUTION_G, motion: str = "oppenheim",
              extend_to_g: float | None = DEFAULT_EXTEND_TO_G) -> FailureDomain:
    """Failure domain of an arch's dynamics over (pulse duration, amplitude) [paper, Fig. 16].

    What :meth:`archquake.fourlink.dynamics.ArchDynamics.failure_domain` runs; with its defaults it
    is ``archquake domain`` with its defaults. For every duration the amplitudes are scanned on
    ``amplitudes_g`` (one compiled call for the whole grid) and every change of outcome class
    (rest, recovery, collapse in half cycle h: the regions of Fig. 16 of [1]_) is bisected to
    ``resolution`` (:func:`domain_slice`).

    Parameters
    ----------
    dynamics : ArchDynamics
        The arch, its mechanisms, restitution and tables.
    durations : sequence of float, optional
        Pulse durations t_p [s] (default :data:`archquake.defaults.DOMAIN_DURATIONS`).
    amplitudes_g : sequence of float, optional
        Increasing scan grid of amplitudes a >= 0 [g] (default
        :data:`archquake.defaults.DOMAIN_AMPLITUDES_G`).
    direction : {"l", "r"}
        ``"l"``: the first pulse is ``-a g`` and opens Mech-l; ``"r"``: ``+a g``, Mech-r.
    resolution : float
        Bisection width of every boundary [g].
    motion : str
        Pulse shape, a name of :data:`archquake.ground_motion.ANALYTIC_GROUND_MOTIONS`; default
        Oppenheim's pulse: ``-a g`` (direction ``"l"``) for ``t_p``, then ``+a g/2`` for
        ``2 t_p`` [paper, Sect. 5.3.1].
    extend_to_g : float or None
        A duration whose grid holds no collapse in the first half cycle is scanned further, at
        the grid's last spacing, until that collapse is found or the amplitude reaches this cap
        [g]; the slice then covers the extended range, and a boundary beyond the cap is reported
        as nan. None scans the grid alone.

    Returns
    -------
    FailureDomain

    Raises
    ------
    ValueError
        For an invalid direction, durations, amplitudes (increasing, >= 0, at most
        :data:`~archquake.defaults.MAX_ACCELERATION_G`), resolution or ``extend_to_g``, or a scan
        of more than :data:`~archquake.defaults.MAX_GRID_POINTS` analyses.

    References
    ----------
    .. [1] The paper, Sect. 5.3.3 and Fig. 16.
    """
    from ..status import Status

    sign = PULSE_SIGNS[check_direction(direction)]
    d = check_durations(inclusive_range(*DOMAIN_DURATIONS) if durations is None else durations)
    a = check_amplitudes(inclusive_range(*DOMAIN_AMPLITUDES_G) if amplitudes_g is None
                          else amplitudes_g)
    if not (resolution > 0):
        raise ValueError(f"resolution must be > 0 [g], got {resolution!r}")
    if extend_to_g is not None and extend_to_g <= a[-1]:
        extend_to_g = None  # the grid already reaches the cap
    if extend_to_g is not None and not (math.isfinite(extend_to_g)
                                        and extend_to_g <= MAX_ACCELERATION_G):
        raise ValueError(f"extend_to_g must be a finite amplitude of at most "
                         f"{MAX_ACCELERATION_G:g} g, got {extend_to_g!r}")
    _check_scan_size(d.size, a, extend_to_g)

    def run(dur, amp):
        return dynamics.outcomes(dur, sign * np.asarray(amp, dtype=float), motion)

    scan = run(d[:, None], a[None, :])
    slices = []
    for i, tp in enumerate(d):
        grid, status, half_cycle = a, scan["status"][i], scan["half_cycle"][i]
        if extend_to_g is not None:
            grid, status, half_cycle = _extend(lambda amp, tp=tp: run(tp, amp), grid, status,
                                               half_cycle, extend_to_g)
        known = {float(x): (Status(int(st)).label, int(hc)) for x, st, hc in
                 zip(grid, status, half_cycle, strict=True)}

        def classify(amplitude, tp=tp, known=known):
            key = known.get(float(amplitude))
            if key is None:
                out = run(tp, float(amplitude))
                key = (Status(int(out["status"])).label, int(out["half_cycle"]))
            return key

        slices.append(domain_slice(classify, grid, duration=float(tp), resolution=resolution))
    k = dynamics.load_multipliers
    limit_k = k[0] if direction == "l" else k[1]
    return FailureDomain(tuple(slices), direction, limit_k, k, tuple(dynamics.restitution),
                         motion, None if extend_to_g is None else float(extend_to_g))


def _check_scan_size(durations: int, amplitudes: np.ndarray, extend_to_g: float | None) -> None:
    """Refuse a scan of more than :data:`archquake.defaults.MAX_GRID_POINTS` analyses (counting
    the largest possible extension)."""
    extension = 0
    if extend_to_g is not None:
        extension = math.ceil((extend_to_g - amplitudes[-1]) / (amplitudes[-1] - amplitudes[-2]))
    points = durations * (amplitudes.size + extension)
    if points > MAX_GRID_POINTS:
        more = "" if not extension else f" + up to {extension} beyond it up to {extend_to_g:g} g"
        raise ValueError(f"the scan of {durations} durations x ({amplitudes.size} amplitudes"
                         f"{more}) = {points} analyses is too large: at most {MAX_GRID_POINTS} "
                         f"(MAX_GRID_POINTS, about a minute); use fewer durations or a coarser "
                         f"grid")


def _extend(run, grid, status, half_cycle, cap):
    """The scan of one duration continued beyond ``grid`` at its last spacing, a block of
    :data:`EXTENSION_BLOCK` amplitudes at a time, until the first collapse in the first half
    cycle or the amplitude ``cap`` [g] (included as the last point)."""
    from ..status import Status

    def first_half(st, hc):
        return bool(np.any((st == Status.COLLAPSE) & (hc == 1)))

    step = float(grid[-1] - grid[-2])
    parts = [(grid, np.asarray(status), np.asarray(half_cycle))]
    last = float(grid[-1])
    while not first_half(*parts[-1][1:]) and last < cap:
        block = np.round(last + step * np.arange(1, EXTENSION_BLOCK + 1), 12)
        block = block[block < cap]
        block = np.append(block, cap) if block.size < EXTENSION_BLOCK else block
        out = run(block)
        parts.append((block, np.asarray(out["status"]), np.asarray(out["half_cycle"])))
        last = float(block[-1])
    return tuple(np.concatenate([p[j] for p in parts]) for j in range(3))
