r"""Records compatible with a site's elastic spectrum: selected from a suite and scaled.

A time-history analysis under the Italian code uses records whose mean spectrum matches the
site's elastic spectrum (NTC 2018 §3.2.3.6 [1]_): the mean of the 5 %-damped spectra of the
scaled records may fall below the target by no more than 10 % and exceed it by no more than
30 % anywhere in the period range, by default 0.15-2.0 s (the larger of 0.15-2.0 s and
0.15 s-2T for the ultimate limit states, T the structure's elastic period). A rocking arch has
no elastic period: its response is rigid until the ground acceleration reaches the activation
acceleration, then its period of rocking grows with the amplitude. So the range is the code's
default, 0.15-2.0 s, and the user may widen it. Eurocode 8 (EN 1998-1 §3.2.3.1.2(4) [2]_) is
the option ``rule="ec8"``: no upper tolerance, but the mean peak ground acceleration of the
records must not be smaller than the site's (``target.pga``, a_g S), and the range is the
user's (0.2 T_1-2 T_1 in the code).

With the target spectrum :math:`S_e(T)` [g] and the 5 %-damped pseudo-spectral accelerations
:math:`S_{a,i}(T)` [g] of the candidate records on a grid of periods :math:`T_k` (log-spaced
over the range, the ends included, and the target's corner periods inside it, where the ratio
of a smooth mean to a code spectrum has its extremes), the selection is

1. *each record alone*: the factor that matches the target in the least-squares sense of the
   logarithms over the grid, clipped to ``factor_range``,

   .. math:: \ln f_i = \frac{1}{K} \sum_k \bigl(\ln S_e(T_k) - \ln S_{a,i}(T_k)\bigr);

2. *the subset*: of ``count`` records (default 7), at most one component per recorded event
   when the suite says which components belong together (the built-in suites), chosen greedily
   (each step adds the record that makes the best subset so far) and then improved by swaps
   (one member for one non-member, the best swap first, until none improves); a subset is
   ranked by how far its mean spectrum
   :math:`\bar S(T) = \frac{1}{n} \sum_{i \in A} f_i S_{a,i}(T)` leaves the tolerance band
   after step 3 (0 for a compatible subset), then by its misfit, the root mean square of
   :math:`\ln(\bar S / S_e)` about its mean over the grid (how far the mean's *shape* is from
   the target's);
3. *one common factor* :math:`c` for the subset, which centres the ratio
   :math:`\bar S / S_e` in the band in the logarithmic sense (NTC:
   :math:`c = \sqrt{(0.9 \cdot 1.3) / (r_{min} r_{max})}`; EC8: the smallest factor that puts
   the mean on or above the target and its PGA on or above the site's), kept such that every
   :math:`c f_i` stays within ``factor_range``.

A subset is compatible if the ratio of its mean to the target stays within the band at every
grid period; with an upper tolerance that is possible only if
:math:`r_{max} / r_{min} \le 1.3 / 0.9`. A suite with no compatible subset gives a selection
with ``compatible`` False that says by how much and where its best subset fails
(:attr:`CompatibleSelection.problems`), never a silent pass.

The code also asks that the records be representative of the site's seismicity (source,
magnitude, distance, soil): that choice of the suite is the user's and is not checked here.

References
----------
.. [1] Ministero delle Infrastrutture e dei Trasporti (2018). Aggiornamento delle «Norme
   tecniche per le costruzioni» (NTC 2018), D.M. 17 gennaio 2018, §3.2.3.6 (Impiego di storie
   temporali del moto del terreno) and §7.3.5 (Risposte alle diverse componenti ...: at least
   three records; with at least seven, the mean of the effects).
.. [2] CEN (2004). EN 1998-1:2004, Eurocode 8: Design of structures for earthquake resistance,
   Part 1, §3.2.3.1.2 (Recorded or simulated accelerograms).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..checks import check_integer, json_float
from ..constants import GRAVITY
from ..defaults import COMPATIBILITY_RULES as COMPATIBILITY_RULE_NAMES
from ..defaults import DEFAULT_FACTOR_RANGE, DEFAULT_PERIOD_RANGE, DEFAULT_RECORD_COUNT
from ..ground_motion.core import GroundMotion
from ..ground_motion.intensity import SA_DAMPING, pseudo_spectral_acceleration


@dataclass(frozen=True)
class CompatibilityRule:
    """How a code says a mean spectrum matches the target.

    Attributes
    ----------
    name : str
        Key of :data:`COMPATIBILITY_RULES`.
    lower_tolerance : float
        How far the mean may fall below the target, as a fraction of it [-].
    upper_tolerance : float
        How far the mean may exceed the target, as a fraction of it [-]; inf for no limit.
    mean_pga : bool
        Whether the mean peak ground acceleration must be at least the target's ``pga``.
    clause : str
        Where the rule is written.
    """

    name: str
    lower_tolerance: float
    upper_tolerance: float
    mean_pga: bool
    clause: str

    @property
    def lower(self) -> float:
        """Lowest ratio of the mean to the target allowed [-] (0.9)."""
        return 1.0 - self.lower_tolerance

    @property
    def upper(self) -> float:
        """Highest ratio of the mean to the target allowed [-] (1.3, or inf)."""
        return 1.0 + self.upper_tolerance


COMPATIBILITY_RULES = {rule.name: rule for rule in (
    CompatibilityRule("ntc2018", 0.10, 0.30, False, "NTC 2018 §3.2.3.6"),
    CompatibilityRule("ec8", 0.10, math.inf, True, "EN 1998-1 §3.2.3.1.2(4)"),
)}
"""The compatibility rules by name: NTC 2018 (the mean within -10 %/+30 % of the target) and
Eurocode 8 (the mean not below 90 % of the target, its mean PGA not below the site's)."""

DEFAULT_RULE = COMPATIBILITY_RULE_NAMES[0]
"""The rule of a selection unless told (:data:`COMPATIBILITY_RULES`)."""
DEFAULT_COUNT = DEFAULT_RECORD_COUNT
"""Records of a selection unless told (:data:`archquake.defaults.DEFAULT_RECORD_COUNT`)."""
MIN_COUNT = 3
"""Fewest records the code accepts for a time-history analysis (NTC 2018 §7.3.5)."""
DEFAULT_PERIODS = 100
"""Periods of the grid on which the spectra are compared unless told [-] (log-spaced over the
range: neighbours 3 % apart over 0.15-2.0 s)."""
SWAP_PASSES = 200
"""Most swaps of the improvement phase [-] (each one strictly improves the subset's rank, so
the phase ends long before in practice)."""


def check_rule(rule: str) -> CompatibilityRule:
    """The :class:`CompatibilityRule` named ``rule``; an unknown name lists the options."""
    if not isinstance(rule, str) or rule not in COMPATIBILITY_RULES:
        raise ValueError(f"rule must be one of {', '.join(map(repr, COMPATIBILITY_RULES))}, "
                         f"got {rule!r}")
    return COMPATIBILITY_RULES[rule]


def check_count(count) -> int:
    """A number of records, checked: an integer >= :data:`MIN_COUNT` (NTC 2018 §7.3.5)."""
    try:
        return check_integer("count", count, minimum=MIN_COUNT)
    except ValueError as exc:
        raise ValueError(f"{exc} (NTC 2018 §7.3.5: a time-history analysis takes at least "
                         f"{MIN_COUNT} records)") from None


def _check_pair(name: str, value, unit: str) -> tuple[float, float]:
    try:
        low, high = (float(v) for v in value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be two numbers (low, high) [{unit}], got {value!r}") \
            from None
    if not (math.isfinite(low) and math.isfinite(high) and 0.0 < low < high):
        raise ValueError(f"{name} must be two finite numbers 0 < low < high [{unit}], got "
                         f"{value!r}")
    return low, high


def response_spectra(motions, periods, damping: float = SA_DAMPING) -> np.ndarray:
    """5 %-damped pseudo-spectral accelerations of every motion at every period [g].

    Each value is :func:`archquake.ground_motion.intensity.pseudo_spectral_acceleration` (the
    exact Nigam-Jennings recursion), divided by g.

    Parameters
    ----------
    motions : sequence of GroundMotion
        The ground motions [m/s^2].
    periods : array_like, shape (K,)
        Oscillator periods, each > 0 [s].
    damping : float
        Damping ratio of the oscillator [-].

    Returns
    -------
    ndarray, shape (R, K)
        ``Sa`` of motion ``r`` at period ``k`` [g].
    """
    periods = np.asarray(periods, dtype=float).ravel()
    out = np.empty((len(motions), periods.size))
    for r, motion in enumerate(motions):
        for k, period in enumerate(periods):
            out[r, k] = pseudo_spectral_acceleration(motion, period, damping) / GRAVITY
    return out


def usable_periods(motion: GroundMotion, metadata: dict | None = None) -> tuple[float, float]:
    """The periods a record's spectrum can speak for [s]: from twice its longest sample spacing
    (the Nyquist period of the samples; 0 for an analytic motion) to the shorter of its
    duration and the inverse of its lowest usable frequency (``lowest_usable_frequency`` [Hz]
    of its metadata, where given: the high-pass filter of its processing removed the longer
    periods).

    Parameters
    ----------
    motion : GroundMotion
        The record.
    metadata : dict, optional
        What is known of it (:attr:`archquake.ground_motion.RecordSuite.metadata`).

    Returns
    -------
    (float, float)
        Shortest and longest usable period [s].
    """
    shortest = 0.0 if motion.is_analytic else 2.0 * float(np.max(np.diff(motion.times)))
    longest = float(motion.duration)
    frequency = (metadata or {}).get("lowest_usable_frequency")
    if frequency is not None and float(frequency) > 0.0:
        longest = min(longest, 1.0 / float(frequency))
    return shortest, longest


CORNER_PERIODS = ("t_b", "t_c", "t_d")
"""Attributes of a code spectrum that hold its corner periods [s] (where its branches meet:
:class:`archquake.site.spectra.ElasticSpectrum`)."""


def comparison_periods(target, t_min: float, t_max: float, periods: int) -> np.ndarray:
    """The periods at which the spectra are compared [s]: ``periods`` log-spaced over
    ``[t_min, t_max]``, ends included, and the target's corner periods inside the range
    (:data:`CORNER_PERIODS`, where a code spectrum has a kink and the ratio of a smooth mean to
    it an extreme).

    Returns
    -------
    ndarray
        Increasing periods [s].
    """
    grid = np.geomspace(t_min, t_max, periods)
    corners = [float(c) for name in CORNER_PERIODS
               if isinstance(c := getattr(target, name, None), int | float)
               and t_min < c < t_max]
    return np.unique(np.concatenate([grid, corners]))


def _candidates(records) -> tuple[list[GroundMotion], list[dict]]:
    """The motions and their metadata of a suite, a list of built-in records or of motions."""
    from ..ground_motion.suites import RecordSuite

    if isinstance(records, RecordSuite):
        return records.motions(cached=True), [dict(m) for m in records.metadata]
    try:
        items = list(records)
    except TypeError:
        raise ValueError(f"records must be a RecordSuite or a sequence of ground motions, got "
                         f"{type(records).__name__}") from None
    motions, metadata = [], []
    for item in items:
        if isinstance(item, GroundMotion):
            motions.append(item)
            metadata.append({"name": item.name})
        elif isinstance(getattr(item, "motion", None), GroundMotion):  # a built-in record
            motions.append(item.motion)
            metadata.append(item.to_dict())
        else:
            raise ValueError(f"records must be a RecordSuite or a sequence of ground motions, "
                             f"got an item of type {type(item).__name__}")
    return motions, metadata


def _target_values(target, periods: np.ndarray) -> np.ndarray:
    damping = getattr(target, "damping", None)
    if damping is not None and not (math.isclose(damping, 5.0) or math.isclose(damping, 0.05)):
        raise ValueError(f"target must be the 5 %-damped elastic spectrum (the records' spectra "
                         f"are 5 %-damped, NTC 2018 §3.2.3.6), got damping {damping!r}")
    try:
        values = np.asarray(target.acceleration(periods), dtype=float)
    except AttributeError:
        raise ValueError(f"target must have acceleration(periods) -> Se [g], got "
                         f"{type(target).__name__}") from None
    if values.shape != periods.shape or not np.all(np.isfinite(values) & (values > 0.0)):
        raise ValueError("target.acceleration(periods) must give one finite value > 0 [g] per "
                         "period of the range")
    return values


@dataclass(frozen=True)
class _Problem:
    """Spectra, target and rule of one selection problem, and how a subset is ranked."""

    spectra: np.ndarray  # (N, K) the candidates' spectra scaled by their own factors [g]
    factors: np.ndarray  # (N,) their own factors [-]
    pga: np.ndarray  # (N,) their peak ground accelerations so scaled [g]
    target: np.ndarray  # (K,) [g]
    target_pga: float  # [g] (nan unless the rule needs it)
    rule: CompatibilityRule
    factor_range: tuple[float, float]

    def common(self, mean: np.ndarray, pga: np.ndarray, f_min: np.ndarray, f_max: np.ndarray):
        """For subsets with mean spectra ``mean`` (B, K), mean PGA ``pga`` (B,) and factors in
        ``[f_min, f_max]`` (B,): the common factor (B,), the violation (B,) [log units], the
        misfit (B,) and whether the factor range held the common factor (B,)."""
        log_ratio = np.log(mean / self.target)
        lo, hi = np.min(log_ratio, axis=1), np.max(log_ratio, axis=1)
        rule = self.rule
        if math.isinf(rule.upper):
            wanted = -lo  # the mean on or above the target ...
            if rule.mean_pga:  # ... and its PGA on or above the site's
                wanted = np.maximum(wanted, math.log(self.target_pga) - np.log(pga))
        else:
            wanted = 0.5 * (math.log(rule.lower) + math.log(rule.upper)) - 0.5 * (lo + hi)
        least = math.log(self.factor_range[0]) - np.log(f_min)
        most = math.log(self.factor_range[1]) - np.log(f_max)
        log_c = np.clip(wanted, least, most)
        violation = (np.maximum(0.0, math.log(rule.lower) - (lo + log_c))
                     + np.maximum(0.0, (hi + log_c) - math.log(rule.upper)))
        if rule.mean_pga:
            violation = violation + np.maximum(0.0, math.log(self.target_pga)
                                               - (np.log(pga) + log_c))
        misfit = np.sqrt(np.mean((log_ratio - np.mean(log_ratio, axis=1, keepdims=True)) ** 2,
                                 axis=1))
        return np.exp(log_c), violation, misfit, log_c != wanted

    def rank(self, mean, pga, f_min, f_max) -> np.ndarray:
        """Rank of subsets (smaller is better): every compatible subset before any other; among
        compatible ones by misfit, among the others by violation."""
        _, violation, misfit, _ = self.common(mean, pga, f_min, f_max)
        return np.where(violation > 0.0, 1e3 * (1.0 + violation), 0.0) + misfit


def _search(problem: _Problem, count: int, groups: np.ndarray) -> list[int]:
    """The subset of ``count`` candidates: greedy, then the best single swap until none
    improves (module docstring, step 2)."""
    x, f, pga = problem.spectra, problem.factors, problem.pga
    n_cand = x.shape[0]
    chosen: list[int] = []
    for size in range(1, count + 1):
        free = np.array([j for j in range(n_cand) if j not in chosen
                         and groups[j] not in {groups[i] for i in chosen}])
        mean = (x[chosen].sum(axis=0) + x[free]) / size
        mean_pga = (pga[chosen].sum() + pga[free]) / size
        f_min = np.minimum(f[chosen].min(initial=np.inf), f[free])
        f_max = np.maximum(f[chosen].max(initial=-np.inf), f[free])
        chosen.append(int(free[np.argmin(problem.rank(mean, mean_pga, f_min, f_max))]))
    total, total_pga = x[chosen].sum(axis=0), pga[chosen].sum()
    best = float(problem.rank(total[None] / count, np.array([total_pga / count]),
                              f[chosen].min(keepdims=True), f[chosen].max(keepdims=True))[0])
    for _ in range(SWAP_PASSES):
        move = None
        for p, out in enumerate(chosen):
            others = chosen[:p] + chosen[p + 1:]
            used = {groups[i] for i in others}
            free = np.array([j for j in range(n_cand) if j not in chosen
                             and groups[j] not in used], dtype=int)
            if free.size == 0:
                continue
            mean = (total - x[out] + x[free]) / count
            mean_pga = (total_pga - pga[out] + pga[free]) / count
            f_min = np.minimum(f[others].min(initial=np.inf), f[free])
            f_max = np.maximum(f[others].max(initial=-np.inf), f[free])
            ranks = problem.rank(mean, mean_pga, f_min, f_max)
            j = int(np.argmin(ranks))
            if ranks[j] < best - 1e-12 and (move is None or ranks[j] < move[0]):
                move = (float(ranks[j]), p, int(free[j]))
        if move is None:
            break
        best, p, j = move
        total = total - x[chosen[p]] + x[j]
        total_pga = total_pga - pga[chosen[p]] + pga[j]
        chosen[p] = j
    return sorted(chosen)


@dataclass(frozen=True, eq=False)
class CompatibleSelection:
    """Records selected from a suite and scaled so that their mean spectrum matches a target
    (:func:`select_compatible_records`).

    Attributes
    ----------
    records : tuple of str
        Names of the selected records, in suite order.
    motions : tuple of GroundMotion
        The selected records as recorded [m/s^2] (:meth:`scaled_motions` scales them).
    factors : ndarray, shape (n,)
        Scale factor of each record [-]: its own factor times the common factor.
    own_factors : ndarray, shape (n,)
        Each record's own least-squares factor, clipped to ``factor_range`` [-].
    common_factor : float
        The factor applied to the whole subset [-].
    periods : ndarray, shape (K,)
        The periods of the comparison [s].
    spectra : ndarray, shape (n, K)
        Spectra of the scaled records [g].
    mean_spectrum : ndarray, shape (K,)
        Their mean [g].
    target : ndarray, shape (K,)
        The target spectrum [g].
    lower_bound, upper_bound : ndarray, shape (K,)
        The band the mean must stay in [g] (``upper_bound`` inf without an upper tolerance).
    rule : CompatibilityRule
        The rule of the band.
    period_range : (float, float)
        The range of the comparison [s].
    factor_range : (float, float)
        The range every scale factor is kept in [-].
    target_pga : float
        The target's peak ground acceleration [g] (nan if it does not say).
    mean_pga : float
        Mean peak ground acceleration of the scaled records [g].
    misfit : float
        Root mean square of ``ln(mean / target)`` about its mean over the grid [-].
    candidates : int
        Records the selection was made from (after those left out) [-].
    excluded : tuple of (str, str)
        Records left out, and why (their usable periods do not cover the range).
    metadata : tuple of dict
        What is known of each selected record.
    factor_limited : bool
        Whether the factor range held the common factor short of the one wanted.
    """

    records: tuple[str, ...]
    motions: tuple[GroundMotion, ...]
    factors: np.ndarray
    own_factors: np.ndarray
    common_factor: float
    periods: np.ndarray
    spectra: np.ndarray
    mean_spectrum: np.ndarray
    target: np.ndarray
    lower_bound: np.ndarray
    upper_bound: np.ndarray
    rule: CompatibilityRule
    period_range: tuple[float, float]
    factor_range: tuple[float, float]
    target_pga: float
    mean_pga: float
    misfit: float
    candidates: int
    excluded: tuple[tuple[str, str], ...]
    metadata: tuple[dict, ...]
    factor_limited: bool = False

    @property
    def count(self) -> int:
        """Number of records [-]."""
        return len(self.records)

    @property
    def ratio(self) -> np.ndarray:
        """Ratio of the mean spectrum to the target at every period [-]."""
        return self.mean_spectrum / self.target

    @property
    def min_ratio(self) -> float:
        """Smallest ratio of the mean to the target over the range [-]."""
        return float(np.min(self.ratio))

    @property
    def max_ratio(self) -> float:
        """Largest ratio of the mean to the target over the range [-]."""
        return float(np.max(self.ratio))

    @property
    def min_ratio_period(self) -> float:
        """Period of the smallest ratio [s]."""
        return float(self.periods[int(np.argmin(self.ratio))])

    @property
    def max_ratio_period(self) -> float:
        """Period of the largest ratio [s]."""
        return float(self.periods[int(np.argmax(self.ratio))])

    @property
    def problems(self) -> tuple[str, ...]:
        """Why the selection is not compatible, one sentence per breach (empty if it is)."""
        out = []
        rule = self.rule
        if self.min_ratio < rule.lower:
            out.append(f"the mean spectrum falls to {self.min_ratio:.3f} of the target at "
                       f"T = {self.min_ratio_period:.3g} s, below the {rule.lower:.2f} "
                       f"allowed ({rule.clause})")
        if self.max_ratio > rule.upper:
            out.append(f"the mean spectrum rises to {self.max_ratio:.3f} of the target at "
                       f"T = {self.max_ratio_period:.3g} s, above the {rule.upper:.2f} "
                       f"allowed ({rule.clause})")
        if rule.mean_pga and self.mean_pga < self.target_pga:
            out.append(f"the mean PGA {self.mean_pga:.3f} g is below the site's "
                       f"{self.target_pga:.3f} g ({rule.clause})")
        if out and not math.isinf(rule.upper) and (
                self.max_ratio / self.min_ratio > rule.upper / rule.lower):
            out.append(f"no common factor can fix it: the mean's ratio to the target spans "
                       f"{self.max_ratio / self.min_ratio:.3f}, more than the "
                       f"{rule.upper / rule.lower:.3f} of the band")
        if out and self.factor_limited:
            out.append(f"the common factor is held by the factor range "
                       f"[{self.factor_range[0]:g}, {self.factor_range[1]:g}] (a record's "
                       f"factor is at its end)")
        return tuple(out)

    @property
    def compatible(self) -> bool:
        """Whether the mean spectrum stays within the band at every period of the grid (and, for
        a rule that asks it, the mean PGA reaches the site's)."""
        return not self.problems

    @property
    def effect_rule(self) -> str:
        """How the code combines the effects of the records (NTC 2018 §7.3.5): ``"mean"`` with
        seven or more, ``"most unfavourable"`` with three to six."""
        return effect_rule(self.count)

    def scaled_motions(self) -> tuple[GroundMotion, ...]:
        """The selected records, each scaled by its factor [m/s^2], under their names."""
        return tuple(m.scaled(float(f)).renamed(m.name)
                     for m, f in zip(self.motions, self.factors, strict=True))

    def summary(self) -> str:
        """The selection in a few lines of text."""
        rule = self.rule
        upper = "no upper limit" if math.isinf(rule.upper) else f"{rule.upper:.2f}"
        head = (f"{self.count} of {self.candidates} records, {rule.clause}: mean/target over "
                f"{self.period_range[0]:g}-{self.period_range[1]:g} s between "
                f"{self.min_ratio:.3f} (T = {self.min_ratio_period:.3g} s) and "
                f"{self.max_ratio:.3f} (T = {self.max_ratio_period:.3g} s); allowed "
                f"{rule.lower:.2f} to {upper}")
        verdict = ("compatible" if self.compatible
                   else "NOT compatible: " + "; ".join(self.problems))
        return f"{head}\n{verdict}"

    def to_dict(self) -> dict:
        """JSON-ready data: the rule, the range, the records with their factors, the periods,
        the mean, target and band, the ratios and the verdict (inf as None)."""
        def floats(values):
            return [json_float(v) for v in np.asarray(values, dtype=float)]

        return {
            "rule": self.rule.name, "clause": self.rule.clause,
            "lower_tolerance": self.rule.lower_tolerance,
            "upper_tolerance": json_float(self.rule.upper_tolerance),
            "period_range": list(self.period_range), "factor_range": list(self.factor_range),
            "count": self.count, "candidates": self.candidates,
            "effect_rule": self.effect_rule,
            "records": [{"name": name, "factor": float(f), "own_factor": float(g),
                         "metadata": meta}
                        for name, f, g, meta in zip(self.records, self.factors,
                                                    self.own_factors, self.metadata,
                                                    strict=True)],
            "common_factor": self.common_factor,
            "excluded": [{"name": n, "reason": why} for n, why in self.excluded],
            "periods": floats(self.periods), "mean_spectrum": floats(self.mean_spectrum),
            "target": floats(self.target), "lower_bound": floats(self.lower_bound),
            "upper_bound": floats(self.upper_bound),
            "min_ratio": self.min_ratio, "min_ratio_period": self.min_ratio_period,
            "max_ratio": self.max_ratio, "max_ratio_period": self.max_ratio_period,
            "target_pga": json_float(self.target_pga), "mean_pga": self.mean_pga,
            "misfit": self.misfit, "compatible": self.compatible,
            "problems": list(self.problems),
        }


def effect_rule(count: int) -> str:
    """How the code combines the effects of ``count`` records (NTC 2018 §7.3.5): ``"mean"``
    with seven or more, ``"most unfavourable"`` with three to six.

    Raises
    ------
    ValueError
        For fewer than :data:`MIN_COUNT` records.
    """
    count = check_count(count)
    return "mean" if count >= 7 else "most unfavourable"


def select_compatible_records(records, target, *, count: int = DEFAULT_COUNT,
                              period_range=DEFAULT_PERIOD_RANGE, rule: str = DEFAULT_RULE,
                              factor_range=DEFAULT_FACTOR_RANGE, periods: int = DEFAULT_PERIODS,
                              one_per_event: bool = True) -> CompatibleSelection:
    """Records of a suite selected and scaled so that their mean spectrum matches ``target``
    (module docstring: own factors, greedy subset improved by swaps, common factor).

    Parameters
    ----------
    records : RecordSuite or sequence of GroundMotion or of built-in records
        The candidates (:class:`archquake.ground_motion.RecordSuite`, the list of
        :func:`archquake.ground_motion.builtin_suite`, or ground motions [m/s^2]).
    target : object
        The site's 5 %-damped elastic spectrum: ``target.acceleration(periods)`` gives
        ``Se`` [g] for an array of periods [s]; ``target.pga`` [g] (a_g S) is needed by
        ``rule="ec8"`` and reported otherwise.
    count : int
        Records to select [-], >= 3 (NTC 2018 §7.3.5; default 7, so the effects are the mean).
    period_range : (float, float)
        Periods over which the mean must match [s] (default 0.15-2.0 s, the code's range; a
        rocking arch has no elastic period to widen it to 2T).
    rule : {"ntc2018", "ec8"}
        The compatibility rule (:data:`COMPATIBILITY_RULES`).
    factor_range : (float, float)
        Range of every record's scale factor [-] (default 0.5-4).
    periods : int
        Periods of the log-spaced comparison grid, ends included [-], >= 2; the target's
        corner periods inside the range are added (:func:`comparison_periods`).
    one_per_event : bool
        At most one component of a recorded event (``record_number`` of a built-in suite's
        metadata); records without it are each their own event.

    Returns
    -------
    CompatibleSelection
        With ``compatible`` False, and what fails in ``problems``, if no subset found is.

    Raises
    ------
    ValueError
        For ``count`` < 3, more records asked than the suite has (events, with
        ``one_per_event``) whose usable periods cover the range, a range or factor range that
        is not ``0 < low < high``, an unknown rule, or a target that gives no positive
        spectrum.
    """
    rule_ = check_rule(rule)
    count = check_count(count)
    t_min, t_max = _check_pair("period_range", period_range, "s")
    factor_range = _check_pair("factor_range", factor_range, "-")
    if not factor_range[0] <= 1.0 <= factor_range[1]:
        raise ValueError(f"factor_range must contain 1 (a record as recorded), got "
                         f"{factor_range}")
    n_periods = check_integer("periods", periods, minimum=2)
    motions, metadata = _candidates(records)
    if not motions:
        raise ValueError("records must hold at least one ground motion, got none")
    grid = comparison_periods(target, t_min, t_max, n_periods)
    usable, excluded, limits = [], [], []
    for i, (motion, meta) in enumerate(zip(motions, metadata, strict=True)):
        shortest, longest = usable_periods(motion, meta)
        limits.append((shortest, longest))
        if shortest <= t_min and t_max <= longest:
            usable.append(i)
        else:
            excluded.append((motion.name, f"usable periods {shortest:.3g}-{longest:.3g} s do "
                                          f"not cover {t_min:g}-{t_max:g} s"))
    events = [meta.get("record_number", f"#{i}") if one_per_event else f"#{i}"
              for i, meta in enumerate(metadata)]
    available = len({events[i] for i in usable})
    if not usable:
        longest = max(lim[1] for lim in limits)
        shortest = min(lim[0] for lim in limits)
        raise ValueError(
            f"period_range: {t_min:g}-{t_max:g} s, no record's usable periods cover it (they "
            f"reach from {shortest:.3g} s up to {longest:.3g} s at most; the shortest usable "
            f"period is twice the sample spacing, the longest the record's duration or the "
            f"inverse of its lowest usable frequency)")
    if available < count:
        what = "events" if one_per_event and any("record_number" in m for m in metadata) \
            else "records"
        longest = max((lim[1] for lim in limits), default=0.0)
        shortest = min((lim[0] for lim in limits), default=0.0)
        raise ValueError(
            f"count must be at most the {available} {what} whose usable periods cover the "
            f"period_range {t_min:g}-{t_max:g} s, got {count} (of {len(motions)} records; "
            f"their usable periods reach from {shortest:.3g} s up to {longest:.3g} s at most)")

    target_values = _target_values(target, grid)
    try:
        target_pga = float(getattr(target, "pga", math.nan))
    except ValueError:  # a table that does not reach T = 0 has no PGA
        target_pga = math.nan
    if rule_.mean_pga and not (math.isfinite(target_pga) and target_pga > 0.0):
        raise ValueError(f"target.pga must be a number > 0 [g] for rule {rule_.name!r} (the "
                         f"mean PGA is compared with it), got {target_pga!r}")

    spectra = response_spectra([motions[i] for i in usable], grid)
    if not np.all(spectra > 0.0):
        bad = [motions[usable[r]].name for r in np.nonzero(~np.all(spectra > 0.0, axis=1))[0]]
        raise ValueError(f"records with a zero spectrum in the period range cannot be scaled "
                         f"to a target: {bad}")
    own = np.exp(np.mean(np.log(target_values) - np.log(spectra), axis=1))
    own = np.clip(own, *factor_range)
    pga = np.array([motions[i].peak / GRAVITY for i in usable]) * own
    problem = _Problem(spectra * own[:, None], own, pga, target_values, target_pga, rule_,
                       factor_range)
    chosen = _search(problem, count, np.array([str(events[i]) for i in usable]))

    mean = problem.spectra[chosen].mean(axis=0)
    common, _, misfit, limited = problem.common(mean[None], np.array([pga[chosen].mean()]),
                                       own[chosen].min(keepdims=True),
                                       own[chosen].max(keepdims=True))
    c = float(common[0])
    factors = own[chosen] * c
    scaled = spectra[chosen] * factors[:, None]
    picked = [usable[i] for i in chosen]
    return CompatibleSelection(
        records=tuple(motions[i].name for i in picked),
        motions=tuple(motions[i] for i in picked),
        factors=factors, own_factors=own[chosen], common_factor=c, periods=grid,
        spectra=scaled, mean_spectrum=scaled.mean(axis=0), target=target_values,
        lower_bound=rule_.lower * target_values, upper_bound=rule_.upper * target_values,
        rule=rule_, period_range=(t_min, t_max), factor_range=factor_range,
        target_pga=target_pga, mean_pga=float(np.mean(pga[chosen]) * c),
        misfit=float(misfit[0]), candidates=len(usable), excluded=tuple(excluded),
        metadata=tuple(metadata[i] for i in picked), factor_limited=bool(limited[0]))


__all__ = ["COMPATIBILITY_RULES", "CORNER_PERIODS", "DEFAULT_COUNT", "DEFAULT_FACTOR_RANGE",
           "DEFAULT_PERIODS", "DEFAULT_PERIOD_RANGE", "DEFAULT_RULE", "MIN_COUNT",
           "CompatibilityRule", "CompatibleSelection", "check_count", "check_rule",
           "comparison_periods", "effect_rule", "response_spectra", "select_compatible_records",
           "usable_periods"]
