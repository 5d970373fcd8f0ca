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
is independent of how the outcome is computed; :func:`domain_of` plugs in a model of the
structure (:class:`archquake.models.StructuralModel`). For the four-link model
(:class:`~archquake.fourlink.FourLinkModel`: its mechanisms, tables and coefficients of
restitution, built once) the whole (duration x amplitude) scan is one compiled call, and only the
bisection steps are single analyses; the rigid-block model
(:class:`~archquake.rigid_blocks.RigidBlockModel`) answers one analysis at a time, and the search
strategy (:mod:`archquake.studies.strategies`) decides which grid points are analysed.
``domain_of(model_for(arch, "four-link"), ...)`` is the way in
(:func:`archquake.models.model_for`).

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

from ..checks import json_float
from ..defaults import (
    DEFAULT_EXTEND_TO_G,
    DEFAULT_RESOLUTION_G,
    DEFAULT_SEARCH,
    DOMAIN_AMPLITUDES_G,
    DOMAIN_DURATIONS,
    MAX_ACCELERATION_G,
    MAX_BLOCK_GRID_POINTS,
    MAX_GRID_POINTS,
    MAX_PULSE_DURATION,
)
from ..models import screening_model
from ..ranges import inclusive_range
from ..status import Status
from .strategies import DEFAULT_STRIDE

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

    @classmethod
    def from_dict(cls, data: dict) -> Interval:
        """Inverse of :meth:`to_dict`.

        Parameters
        ----------
        data : dict
            ``from``, ``to`` [g], ``outcome`` and ``half_cycle``.

        Returns
        -------
        Interval
        """
        return cls(float(data["from"]), float(data["to"]), str(data["outcome"]),
                   int(data["half_cycle"]))


@dataclass(frozen=True)
class DomainSlice:
    """Outcome intervals of one pulse duration.

    Attributes
    ----------
    duration : float
        Pulse duration t_p [s].
    intervals : tuple of Interval
        Ordered, contiguous intervals covering the scanned amplitude range [g].
    resolution_g : float
        Width [g] to which every boundary between intervals was bisected.
    """

    duration: float
    intervals: tuple[Interval, ...]
    resolution_g: float

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
    def failure_acceleration_bound(self) -> str | None:
        """Whether :attr:`failure_acceleration_g` is a bound rather than a value bracketed to
        the resolution: ``"upper"`` when the lowest amplitude scanned already collapses (the
        failure acceleration is at most it: the scan started too high), ``"lower"`` when no
        amplitude of the scan collapses (it is above :attr:`scanned_to_g`), None otherwise."""
        if math.isnan(self.failure_acceleration_g):
            return "lower"
        return "upper" if self.intervals[0].status == "collapse" else None

    @property
    def first_half_cycle_bound(self) -> str | None:
        """:attr:`failure_acceleration_bound` of :attr:`first_half_cycle_acceleration_g`."""
        if math.isnan(self.first_half_cycle_acceleration_g):
            return "lower"
        first = self.intervals[0]
        return "upper" if first.status == "collapse" and first.half_cycle == 1 else None

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

    @property
    def undecided_bands_g(self) -> list[tuple[float, float]]:
        """Intervals ``(from, to)`` [g] whose analyses the model left undecided (empty for a
        model that decides every analysis, as the four-link model does)."""
        return [(iv.start, iv.end) for iv in self.intervals if iv.status == "undecided"]

    @property
    def failure_undecided_from_g(self) -> float:
        """Lowest amplitude [g] of an undecided band below :attr:`failure_acceleration_g`
        (anywhere in the scan when nothing collapses), nan if none.

        The failure acceleration is then not decided: the lowest collapse may lie in the band,
        so the true value is only known to lie between this amplitude and
        :attr:`failure_acceleration_g` (above :attr:`scanned_to_g` when that is nan), and a
        result must say so (:mod:`archquake.studies.undecided`)."""
        failure = self.failure_acceleration_g
        for iv in self.intervals:
            if iv.status == "undecided" and (math.isnan(failure) or iv.start < failure):
                return iv.start
        return math.nan

    def to_dict(self) -> dict:
        """The slice as JSON-ready data.

        Returns
        -------
        dict
            ``duration`` [s], ``failure_acceleration``, ``first_half_cycle_acceleration`` (None
            for nan: no collapse up to ``scanned_to``, a lower bound) and ``scanned_to`` [g],
            and the ``intervals`` (:meth:`Interval.to_dict`); and, only when the lowest
            amplitude scanned already collapses, ``failure_acceleration_bound: "upper"`` (the
            failure acceleration is at most the value given; :attr:`failure_acceleration_bound`).
            Only when the model left some amplitudes undecided: ``undecided`` (the bands,
            ``[[from, to], ...]`` [g]) and, if one lies below the failure acceleration,
            ``failure_undecided_from`` [g] (:attr:`failure_undecided_from_g`: the failure
            acceleration lies between it and ``failure_acceleration``).
        """
        out = {
            "duration": self.duration,
            "failure_acceleration": json_float(self.failure_acceleration_g),
            "first_half_cycle_acceleration": json_float(self.first_half_cycle_acceleration_g),
            "scanned_to": self.scanned_to_g,
            "intervals": [iv.to_dict() for iv in self.intervals],
        }
        if self.failure_acceleration_bound == "upper":
            out["failure_acceleration_bound"] = "upper"
        bands = self.undecided_bands_g
        if bands:
            out["undecided"] = [list(b) for b in bands]
            if not math.isnan(self.failure_undecided_from_g):
                out["failure_undecided_from"] = self.failure_undecided_from_g
        return out


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
    resolution_g: float = 1e-4,
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
    resolution_g : float
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
        If ``amplitudes`` is not increasing with at least two values, or ``resolution_g <= 0``.
    RuntimeError
        If new classes keep appearing inside an edge (more than 60 nested bisections).

    Examples
    --------
    A classifier with one class change, at 0.3:

    >>> s = domain_slice(lambda a: ("collapse", 1) if a >= 0.3 else ("recovery", 0),
    ...                  [0.1, 0.2, 0.4, 0.5], resolution_g=1e-3)
    >>> [(iv.status, round(iv.start, 3)) for iv in s.intervals]
    [('recovery', 0.1), ('collapse', 0.3)]
    >>> abs(s.failure_acceleration_g - 0.3) <= 0.5e-3
    True
    """
    grid = np.asarray(amplitudes, dtype=float)
    if grid.ndim != 1 or grid.size < 2 or np.any(np.diff(grid) <= 0):
        raise ValueError("amplitudes must be an increasing sequence of at least two values [g]")
    if not (resolution_g > 0):
        raise ValueError(f"resolution_g must be > 0 [g], got {resolution_g!r}")
    keys = [_key(classify(a)) for a in grid]
    starts: list[tuple[float, OutcomeKey]] = [(float(grid[0]), keys[0])]
    for i in range(grid.size - 1):
        if keys[i] != keys[i + 1]:
            starts += _refine(classify, grid[i], keys[i], grid[i + 1], keys[i + 1], resolution_g)
    intervals = []
    for j, (start, key) in enumerate(starts):
        end = starts[j + 1][0] if j + 1 < len(starts) else float(grid[-1])
        intervals.append(Interval(float(start), float(end), key[0], key[1]))
    return DomainSlice(float(duration), tuple(intervals), float(resolution_g))


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
        ``(c_lr, c_rl)`` used at the impacts [-] (nan for a model without them).
    motion : str
        Pulse shape (name in :data:`archquake.ground_motion.GROUND_MOTIONS`).
    extend_to_g : float or None
        Cap [g] up to which a scan was extended to find the collapse in the first half cycle
        (None: the scan was the grid alone).
    model : dict or None
        The model that made the domain (:meth:`archquake.models.StructuralModel.describe`:
        ``{"model": name, **settings}``).
    search : str
        The search strategy of the grid (:data:`archquake.studies.strategies.SEARCHES`).
    analyses : tuple of int
        Number of analyses per duration (scan, extension and bisection) [-].
    undecided : tuple of int
        Of these, the analyses the model left undecided, per duration [-] (empty for a domain
        made before they were counted; :mod:`archquake.studies.undecided`).
    not_analysed : tuple of int
        Points of the scan (the grid, and its extension at the grid's last spacing) whose
        outcome the search inferred from their neighbours without analysing them, per duration
        [-] (empty for a domain made before they were counted;
        :func:`archquake.studies.strategies.search_caveat`).
    scan_points : tuple of int
        Points of that scan per duration [-] (analysed or not; empty as ``not_analysed``).
    """

    slices: tuple[DomainSlice, ...]
    direction: str
    limit_multiplier: float
    load_multipliers: tuple[float, float]
    restitution: tuple[float, float]
    motion: str = "oppenheim"
    extend_to_g: float | None = None
    model: dict | None = None
    search: str = "exhaustive"
    analyses: tuple[int, ...] = ()
    undecided: tuple[int, ...] = ()
    not_analysed: tuple[int, ...] = ()
    scan_points: tuple[int, ...] = ()

    @property
    def undecided_analyses(self) -> int:
        """Analyses the model left undecided, over every duration [-]."""
        return int(sum(self.undecided))

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

    def to_dict(self) -> dict:
        """The whole domain as JSON-ready data, from which :meth:`from_dict` rebuilds it: the
        slices of :meth:`to_list`, each with its ``resolution_g`` [g], and every attribute.

        Returns
        -------
        dict
            ``slices``, ``direction``, ``limit_multiplier``, ``load_multipliers`` [-],
            ``restitution`` [-] (None for nan), ``motion``, ``extend_to_g`` [g], ``model``,
            ``search``, ``analyses``, ``undecided``, ``not_analysed`` and ``scan_points``.

        Examples
        --------
        >>> domain = FailureDomain((DomainSlice(0.5, (Interval(0.3, 0.5, "recovery", 0),
        ...     Interval(0.5, 0.8, "collapse", 2)), 1e-3),), "l", 0.3, (0.3, 0.3),
        ...     (math.nan, math.nan))
        >>> FailureDomain.from_dict(domain.to_dict()).slices == domain.slices
        True
        """
        return {
            "slices": [{**s.to_dict(), "resolution_g": s.resolution_g} for s in self.slices],
            "direction": self.direction, "limit_multiplier": self.limit_multiplier,
            "load_multipliers": list(self.load_multipliers),
            "restitution": [json_float(c) for c in self.restitution], "motion": self.motion,
            "extend_to_g": self.extend_to_g, "model": self.model, "search": self.search,
            "analyses": list(self.analyses), "undecided": list(self.undecided),
            "not_analysed": list(self.not_analysed), "scan_points": list(self.scan_points)}

    @classmethod
    def from_dict(cls, data: dict) -> FailureDomain:
        """Inverse of :meth:`to_dict`.

        Parameters
        ----------
        data : dict
            :meth:`to_dict`'s form (the derived numbers of a slice, such as its
            ``failure_acceleration``, are read from its intervals, not from the dict; a domain
            written before undecided analyses were counted has none recorded; a slice's width
            kept under its former key ``resolution`` is read too).

        Returns
        -------
        FailureDomain
        """
        slices = tuple(DomainSlice(s["duration"],
                                   tuple(Interval.from_dict(iv) for iv in s["intervals"]),
                                   s.get("resolution_g", s.get("resolution")))
                       for s in data["slices"])
        restitution = tuple(math.nan if c is None else c for c in data["restitution"])
        return cls(slices, data["direction"], data["limit_multiplier"],
                   tuple(data["load_multipliers"]), restitution, data["motion"],
                   data["extend_to_g"], data["model"], data["search"], tuple(data["analyses"]),
                   tuple(data.get("undecided", ())), tuple(data.get("not_analysed", ())),
                   tuple(data.get("scan_points", ())))


def check_durations(durations) -> np.ndarray:
    d = np.atleast_1d(np.asarray(durations, dtype=float))
    if d.ndim != 1 or d.size == 0:
        raise ValueError("durations must be a non-empty sequence of pulse durations t_p [s]")
    bad = d[~((d > 0) & (d <= MAX_PULSE_DURATION))]  # nan too
    if bad.size:
        shown = ", ".join(f"{v:g}" for v in bad[:5]) + (", ..." if bad.size > 5 else "")
        raise ValueError(f"durations must be pulse durations in (0, {MAX_PULSE_DURATION:g}] s "
                         f"(MAX_PULSE_DURATION), got {shown}")
    return d


def check_amplitudes(amplitudes_g) -> np.ndarray:
    a = np.atleast_1d(np.asarray(amplitudes_g, dtype=float))
    if a.ndim != 1 or a.size < 2 or not np.all(np.isfinite(a)) or np.any(np.diff(a) <= 0):
        raise ValueError("amplitudes must be an increasing sequence of at least two finite "
                         "values [g]")
    if a[0] < 0:
        raise ValueError(f"amplitudes must be >= 0 [g] (the direction gives the sign), got "
                         f"{float(a[0])!r}")
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


def domain_of(model, durations=None, amplitudes_g=None, *, direction: str = "l",
              resolution_g: float = DEFAULT_RESOLUTION_G, motion: str = "oppenheim",
              extend_to_g: float | None = DEFAULT_EXTEND_TO_G, search: str | None = None,
              stride: int = DEFAULT_STRIDE, screen=None, workers: int | None = None,
              progress: bool = False) -> FailureDomain:
    """Failure domain of a model of a structure over (pulse duration, amplitude) [paper, Fig. 16].

    Written against the model protocol (:class:`archquake.models.StructuralModel`): the same
    search for the four-link and the rigid-block model. For every duration the outcome (rest,
    recovery, collapse in half cycle h: the regions of Fig. 16 of [1]_; the rigid-block model
    does not count half cycles) is found at every amplitude of ``amplitudes_g`` by the strategy
    ``search`` (:mod:`archquake.studies.strategies`), and every change of outcome class is then
    bisected to ``resolution_g`` (:func:`domain_slice`). With its defaults and the four-link model
    it is ``archquake domain`` with its defaults.

    Parameters
    ----------
    model : StructuralModel
        The model of the structure: a :class:`~archquake.fourlink.FourLinkModel` (its
        mechanisms, restitution and tables) or a :class:`~archquake.rigid_blocks.RigidBlockModel`.
    durations : sequence of float, optional
        Pulse durations t_p [s] (default :data:`archquake.defaults.DOMAIN_DURATIONS`).
    amplitudes_g : sequence of float, optional
        Increasing scan grid of amplitudes a >= 0 [g] (default
        :data:`archquake.defaults.DOMAIN_AMPLITUDES_G`).
    direction : {"l", "r"}
        ``"l"``: the first pulse is ``-a g`` and opens Mech-l; ``"r"``: ``+a g``, Mech-r.
    resolution_g : float
        Bisection width of every boundary [g].
    motion : str
        Pulse shape, a name of :data:`archquake.ground_motion.ANALYTIC_GROUND_MOTIONS`; default
        Oppenheim's pulse: ``-a g`` (direction ``"l"``) for ``t_p``, then ``+a g/2`` for
        ``2 t_p`` [paper, Sect. 5.3.1].
    extend_to_g : float or None
        A duration whose grid does not hold the outcome sought -- for the four-link model the
        collapse in the first half cycle, for the rigid-block model any collapse -- is scanned
        further, at the grid's last spacing (times ``stride`` for the faster strategies), until
        it is found or the amplitude reaches this cap [g]; the slice then covers the extended
        range, and a boundary beyond the cap is reported as nan. None scans the grid alone.
    search : {"exhaustive", "bisection", "screened"}, optional
        How the grid is scanned (:data:`archquake.defaults.DEFAULT_SEARCH` of the model by
        default: every point for the four-link model, whose whole grid is one compiled call;
        a coarse scan and bisection for the rigid blocks).
    stride : int
        Grid steps between the coarse points of ``bisection`` and ``screened`` [-].
    screen : StructuralModel, optional
        The screening model of ``screened`` (default: the four-link model of the same
        structure with the default restitution, where it has one).
    workers : int, optional
        Local worker processes, one duration per task (models whose analyses are single calls,
        i.e. the rigid blocks); default: run here.
    progress : bool
        Show a progress bar over the durations (on stderr).

    Returns
    -------
    FailureDomain

    Raises
    ------
    ValueError
        For an invalid direction, durations, amplitudes (increasing, >= 0, at most
        :data:`~archquake.defaults.MAX_ACCELERATION_G`), ``resolution_g``, search, ``extend_to_g``
        or ``workers``, or a scan of more than :data:`~archquake.defaults.MAX_GRID_POINTS`
        analyses (:data:`~archquake.defaults.MAX_BLOCK_GRID_POINTS` for the rigid blocks),
        counting those the search makes whatever the outcomes: every grid point, or the coarse
        scan of ``bisection`` and ``screened``, and the extension up to ``extend_to_g`` at the
        search's step.
    archquake.errors.CannotStandError
        For a rigid-block structure that cannot stand under its own weight with its friction
        (:func:`archquake.limit_analysis.standing_with_friction`), before any dynamics.

    References
    ----------
    .. [1] The paper, Sect. 5.3.3 and Fig. 16.
    """
    from .strategies import check_search, check_stride

    name = getattr(model, "name", None)
    if name not in DEFAULT_SEARCH:
        raise ValueError(f"model must be a model of a structure (archquake.models."
                         f"StructuralModel: four-link or rigid-blocks), got "
                         f"{type(model).__name__}")
    if screen is not None and (getattr(screen, "name", None) not in DEFAULT_SEARCH
                               or not callable(getattr(screen, "outcomes", None))):
        raise ValueError(f"screen must be None or a model of a structure (archquake.models."
                         f"StructuralModel), got {screen!r}")
    search = check_search(DEFAULT_SEARCH[name] if search is None else search)
    stride = check_stride(stride)
    sign = PULSE_SIGNS[check_direction(direction)]
    d = check_durations(inclusive_range(*DOMAIN_DURATIONS) if durations is None else durations)
    a = check_amplitudes(inclusive_range(*DOMAIN_AMPLITUDES_G) if amplitudes_g is None
                         else amplitudes_g)
    if not (isinstance(resolution_g, int | float) and math.isfinite(resolution_g)
            and resolution_g > 0):
        raise ValueError(f"resolution_g must be a finite number > 0 [g], got {resolution_g!r}")
    if extend_to_g is not None and extend_to_g <= a[-1]:
        extend_to_g = None  # the grid already reaches the cap
    if extend_to_g is not None and not (math.isfinite(extend_to_g)
                                        and extend_to_g <= MAX_ACCELERATION_G):
        raise ValueError(f"extend_to_g must be a finite amplitude of at most "
                         f"{MAX_ACCELERATION_G:g} g, got {extend_to_g!r}")
    if workers is not None and (isinstance(workers, bool) or int(workers) != workers
                                or workers < 1):
        raise ValueError(f"workers must be an integer >= 1, got {workers!r}")
    single = not model.grid_in_one_call
    _check_scan_size(d.size, a, extend_to_g, MAX_BLOCK_GRID_POINTS if single else
                     MAX_GRID_POINTS, search=search, stride=stride)
    model.check_stands()
    screen_model = screen
    if search == "screened" and screen is None:
        screen_model = screening_model(model)
    job = _SliceJob(model, screen_model, sign, a, float(resolution_g), motion, extend_to_g,
                    search, stride)
    if model.grid_in_one_call and search == "exhaustive":
        job = job.with_scan(model.outcomes(d[:, None], sign * a[None, :], motion))
    slices = _run_slices(job, d, workers if single else None, progress)
    try:
        k = model.load_multipliers
    except ValueError:  # a structure without a limit analysis (a rigid-block Assembly)
        k = (math.nan, math.nan)
    limit_k = k[0] if direction == "l" else k[1]
    restitution = tuple(getattr(model, "restitution", (math.nan, math.nan)))
    return FailureDomain(tuple(s[0] for s in slices), direction, limit_k, k, restitution,
                         motion, None if extend_to_g is None else float(extend_to_g),
                         model.describe(), search, tuple(s[1] for s in slices),
                         tuple(s[2] for s in slices), tuple(s[3] for s in slices),
                         tuple(s[4] for s in slices))


def _encode(status, half_cycle) -> np.ndarray:
    """Integer outcome keys: the status code times 1000, plus the half cycle of a collapse."""
    status = np.asarray(status, dtype=np.int64)
    return status * 1000 + np.where(status == Status.COLLAPSE,
                                    np.asarray(half_cycle, dtype=np.int64), 0)


def _decode(key: int) -> tuple[str, int]:
    return Status(int(key) // 1000).label, int(key) % 1000


@dataclass(frozen=True)
class _SliceJob:
    """What every duration of a domain needs (sent whole to a worker)."""

    model: object
    screen: object
    sign: float
    grid: np.ndarray
    resolution_g: float
    motion: str
    extend_to_g: float | None
    search: str
    stride: int
    scan: dict | None = None  # the four-link model's whole (duration x amplitude) grid

    def with_scan(self, scan: dict) -> _SliceJob:
        return _SliceJob(self.model, self.screen, self.sign, self.grid, self.resolution_g,
                         self.motion, self.extend_to_g, self.search, self.stride, scan)

    def outcome_keys(self, duration: float, amplitudes, smooth: bool = False):
        """Outcome keys at ``amplitudes`` [g] (and, with ``smooth``, which are smooth in the
        amplitude: :func:`archquake.studies.strategies.smooth_outcomes`)."""
        from .strategies import excitation_end, smooth_outcomes

        out = self.model.outcomes(duration, self.sign * np.asarray(amplitudes, dtype=float),
                                  self.motion)
        keys = np.atleast_1d(_encode(out["status"], out["half_cycle"]))
        if not smooth:
            return keys
        return keys, smooth_outcomes(out, excitation_end(self.motion, duration))


def _slice_task(args) -> tuple[DomainSlice, int, int, int, int]:
    """One duration of a domain: ``(slice, number of analyses, of them undecided, points of
    the scan not analysed, points of the scan)`` (a worker's job)."""
    job, index, duration = args
    return _domain_slice_of(job, index, duration)


UNDECIDED_KEY = int(Status.UNDECIDED) * 1000
"""The outcome key (:func:`_encode`) of an undecided analysis."""


def _domain_slice_of(job: _SliceJob, index: int, tp: float
                     ) -> tuple[DomainSlice, int, int, int, int]:
    from .strategies import search_grid

    count = undecided = skipped = points = 0
    if job.scan is not None:  # the whole grid, analysed in one call
        keys = _encode(job.scan["status"][index], job.scan["half_cycle"][index])
        count += keys.size
        undecided += int(np.count_nonzero(keys == UNDECIDED_KEY))
    else:
        screen = None
        if job.search == "screened" and job.screen is not None:
            out = job.screen.outcomes(tp, job.sign * job.grid, job.motion)
            screen = _encode(out["status"], out["half_cycle"])

        def classify_indices(indices):
            return job.outcome_keys(tp, job.grid[indices], smooth=True)

        keys, analysed = search_grid(classify_indices, job.grid.size, search=job.search,
                                     stride=job.stride, screen=screen)
        count += int(analysed.sum())
        skipped += int(analysed.size - analysed.sum())
        undecided += int(np.count_nonzero(keys[analysed] == UNDECIDED_KEY))
    grid = job.grid
    if job.extend_to_g is not None:
        step = 1 if job.search == "exhaustive" else job.stride
        size = grid.size
        grid, keys, extra = _extend(lambda amp: job.outcome_keys(tp, amp), grid, keys,
                                    job.extend_to_g, step, _target(job.model))
        count += extra
        undecided += int(np.count_nonzero(keys[size:] == UNDECIDED_KEY))
        if extra and step > 1:  # the points at the grid's spacing between extension points
            spacing = float(job.grid[-1] - job.grid[-2])
            between = round((float(grid[-1]) - float(job.grid[-1])) / spacing) - extra
            skipped += between
            points += between
    points += grid.size
    known = {float(x): int(key) for x, key in zip(grid, keys, strict=True)}
    analyses = [0, 0]  # bisection steps, of them undecided

    def classify(amplitude, known=known):
        key = known.get(float(amplitude))
        if key is None:
            key = int(job.outcome_keys(tp, [float(amplitude)])[0])
            analyses[0] += 1
            analyses[1] += key == UNDECIDED_KEY
        return _decode(key)

    piece = domain_slice(classify, grid, duration=float(tp), resolution_g=job.resolution_g)
    return piece, count + analyses[0], undecided + analyses[1], skipped, points


def _run_slices(job: _SliceJob, durations: np.ndarray, workers: int | None,
                progress: bool) -> list[tuple[DomainSlice, int, int, int, int]]:
    """Every duration's slice, here or on local worker processes."""
    import sys

    from tqdm.auto import tqdm

    tasks = [(job, i, float(tp)) for i, tp in enumerate(durations)]
    out = []
    with tqdm(total=len(tasks), desc=f"failure domain ({job.model.name})", unit="duration",
              disable=not progress, file=sys.stderr) as bar:
        if workers is None or workers == 1 or len(tasks) == 1:
            for task in tasks:
                out.append(_slice_task(task))
                bar.update()
        else:
            from ..compiled import announce_all
            from ..execution import process_pool
            from ..models import ModelSpec

            # the workers compile the engines of the model and its screen: said here, once
            announce_all([e for m in (job.model, job.screen) if m is not None
                          for e in ModelSpec(m.name).engines()])
            with process_pool(min(int(workers), len(tasks))) as pool:
                for result in pool.map(_slice_task, tasks):
                    out.append(result)
                    bar.update()
    return out


def _target(model) -> Callable[[np.ndarray], bool]:
    """What an extension of the scan looks for: the collapse in the first half cycle (four-link
    model) or any collapse (models that do not count half cycles)."""
    if model.counts_half_cycles:
        return lambda keys: bool(np.any(keys == int(Status.COLLAPSE) * 1000 + 1))
    return lambda keys: bool(np.any(keys // 1000 == int(Status.COLLAPSE)))


def _check_scan_size(durations: int, amplitudes: np.ndarray, extend_to_g: float | None,
                     largest: int = MAX_GRID_POINTS, *, search: str = "exhaustive",
                     stride: int = 1) -> None:
    """Refuse a scan of more than ``largest`` analyses, counting those the search makes
    whatever the outcomes: every grid point (``exhaustive``) or the coarse scan
    (:func:`~archquake.studies.strategies.coarse_indices`; ``bisection`` and ``screened``), and
    the largest possible extension up to ``extend_to_g`` [g] at the search's step (the grid's
    last spacing, times ``stride`` for the coarse searches). The bisection of each change of
    outcome, and the stretches ``screened`` analyses point by point, come on top."""
    from .strategies import coarse_indices

    coarse = search != "exhaustive"
    step = stride if coarse else 1
    scanned = coarse_indices(amplitudes.size, stride).size if coarse else amplitudes.size
    extension = 0
    if extend_to_g is not None:
        spacing = (amplitudes[-1] - amplitudes[-2]) * step
        extension = math.ceil(round((extend_to_g - amplitudes[-1]) / spacing, 9))
    points = durations * (scanned + extension)
    if points > largest:
        what = (f"{amplitudes.size} amplitudes" if not coarse else
                f"{scanned} coarse points of {amplitudes.size} amplitudes, every {stride}")
        more = ("" if not extension else
                f" + up to {extension} beyond it up to {extend_to_g:g} g (extend_to_g, "
                f"--extend-to)")
        name = "MAX_GRID_POINTS" if largest == MAX_GRID_POINTS else "MAX_BLOCK_GRID_POINTS"
        raise ValueError(f"the scan of {durations} durations x ({what}{more}) = {points} "
                         f"analyses is too large: at most {largest} ({name}); use fewer "
                         f"durations, a coarser grid"
                         + (", or a lower --extend-to (the cap of the scan beyond the grid)"
                            if extension else ""))


def _extend(run, grid, keys, cap, stride, found):
    """The scan of one duration continued beyond ``grid`` at its last spacing times ``stride``,
    a block of :data:`EXTENSION_BLOCK` amplitudes at a time (one amplitude at a time for
    ``stride > 1``, whose analyses are single), until ``found(keys)`` or the amplitude ``cap``
    [g] (included as the last point). Returns ``(grid, keys, analyses)``."""
    step = float(grid[-1] - grid[-2]) * stride
    block_size = EXTENSION_BLOCK if stride == 1 else 1
    parts = [(np.asarray(grid, dtype=float), np.asarray(keys, dtype=np.int64))]
    last, count = float(grid[-1]), 0
    while not found(parts[-1][1]) and last < cap:
        block = np.round(last + step * np.arange(1, block_size + 1), 12)
        block = block[block < cap]
        block = np.append(block, cap) if block.size < block_size else block
        out = run(block)
        count += block.size
        parts.append((block, np.asarray(out, dtype=np.int64)))
        last = float(block[-1])
    return (np.concatenate([p[0] for p in parts]), np.concatenate([p[1] for p in parts]),
            count)
