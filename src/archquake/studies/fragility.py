r"""Fragility of irregular arches [paper, Sect. 5.3.3, eq. (9), Figs. 17–21].

The estimated probability of failure at a pulse duration :math:`t_p` [s] and amplitude
:math:`a` [g] is Eq. (9) in [1]_,

.. math::

    P_F(t_p, a) = \frac{h_f(t_p, a)}{h},

where :math:`h` is the number of sampled irregular arches and :math:`h_f \le h` those that
collapse. For the nominal arch alone it is the step of Eq. (10) in [1]_,

.. math::

    P_F(t_p, a) = \begin{cases} 0 & a < \bar a(t_p), \\ 1 & a \ge \bar a(t_p), \end{cases}

with :math:`\bar a(t_p)` its failure acceleration (point Q of Fig. 16 of [1]_,
:attr:`FragilityResult.nominal_failure_acceleration_g`).

Two fits of a fragility curve are provided: the paper's fifth-degree polynomial (least squares,
the dashed curves of Figs. 17-20 of [1]_), and the lognormal fragility function

.. math::

    P_F(a) = \Phi\left(\frac{\ln(a/\theta)}{\beta}\right)

with median :math:`\theta` [g] and dispersion :math:`\beta` [-], fitted by maximum likelihood to
the binomial counts of the grid (Eq. (11) in [2]_, :func:`fit_lognormal`), the standard form in
earthquake engineering. Under a pulse :math:`P_F(a)` need not be monotone: above the failure
accelerations a band of amplitudes lets arches recover again (the last phase of the pulse brings
them back, README). A lognormal CDF cannot follow that, so it is fitted to the rising part of the
data, the amplitudes up to the first grid point where :math:`P_F` takes its largest value
(:func:`rising_part`, recorded with the fit); the polynomial, as in the paper, is fitted to the
whole grid.

The study [paper, Sect. 5.3.3]
------------------------------
:func:`run_fragility` draws h irregular arches around a nominal one [eq. (1)], runs for each
the pulse in both directions over the whole (t_p x a) grid (one compiled call per direction),
and counts an arch as failed at (t_p, a) when it collapses in either direction (the paper
analyses both directions and does not say how they are combined; "either" is the conservative
reading, and the per-direction probabilities are kept too). Beside it, the limit analysis of s
arches gives the empirical CDF of k~ = min(k~_l, k~_r) (the blue curves of Figs. 17-20), and the
nominal arch gives its failure acceleration per duration (point Q of Fig. 16, the step fragility
of eq. (10)) and its k.

Arch ``i`` of both samples is drawn by :func:`archquake.geometry.irregular_arch` from
``SeedSequence(seed, spawn_key=(i,))``, i.e. it is arch ``i`` of
``irregular_sample(nominal, epsilon, sample_size, seed)`` and of ``limit_sample(...)``: the first
h arches of the limit sample are the arches of the dynamic study. The study runs through
:func:`archquake.execution.run_study` (chunks of arches, serial / local processes / Dask, resumable
checkpoints); the results do not depend on how it is run.

Arches that cannot be analysed: with a large epsilon (or a thin nominal arch) a drawn arch may
not be an arch (neighbouring voussoirs no longer touch) or may not stand under its own weight.
Such arches are excluded, not allowed to stop the study: they are counted and named by reason
(:data:`EXCLUSIONS`), index and seed in the summary and the text output, and left out of h, so
P_F is the probability of failure of the drawn arches that stand. Any other error names the
arch that raised it.

Restitution: by default ``"computed"`` (:data:`archquake.defaults.DEFAULT_RESTITUTION`, as every
analysis of the package), each arch its own pair (c_lr, c_rl); ``"nominal"`` applies the
coefficients computed for the nominal arch to every irregular arch, which is the paper's practice
(it applies its nominal c_v to the random arches); ``"paper"`` imposes 0.875.

References
----------
.. [1] The paper, Sect. 5.3.3, Eqs. (9)-(10), Figs. 16-21.
.. [2] Baker, J. W. (2015). Efficient analytical fragility function fitting using dynamic
   structural analysis. Earthquake Spectra 31(1), 579-599.
"""

from __future__ import annotations

import functools
import json
import math
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
from scipy import optimize, stats

from ..defaults import (
    DEFAULT_EPSILON,
    DEFAULT_RESTITUTION,
    DEFAULT_SAMPLE_LIMIT_METHOD,
    DEFAULT_SEED,
    LIMIT_METHODS,
    LIMIT_SAMPLE_SIZE,
    MAX_ACCELERATION_G,
    MAX_GRID_POINTS,
    MAX_LIMIT_SAMPLES,
    MAX_SAMPLES,
    MAX_STUDY_ANALYSES,
    STUDY_AMPLITUDES_G,
    STUDY_DURATIONS,
    STUDY_SAMPLE_SIZE,
)
from ..geometry import BlockArch, arch_from_dict, irregular_arch
from .failure_domain import (
    PULSE_SIGNS,
    FailureDomain,
    inclusive_range,
)


def probability_of_failure(failed: np.ndarray) -> np.ndarray:
    r"""The estimated probability of failure of Eq. (9) in [1]_,

    .. math::

        P_F = \frac{h_f}{h},

    the fraction of the :math:`h` arches (first axis) that fail.

    Parameters
    ----------
    failed : array_like of bool, shape (h, ...)
        Failure of every arch (first axis) at every point of the rest of the shape.

    Returns
    -------
    ndarray, shape (...)
        :math:`P_F` [-].

    Raises
    ------
    ValueError
        If ``failed`` has no arch.

    References
    ----------
    .. [1] The paper, Sect. 5.3.3, Eq. (9).

    Examples
    --------
    >>> probability_of_failure([[False, True], [True, True], [False, True], [False, False]])
    array([0.25, 0.75])
    """
    failed = np.asarray(failed, dtype=bool)
    if failed.ndim < 1 or failed.shape[0] == 0:
        raise ValueError("failed must have at least one arch (first axis)")
    return failed.mean(axis=0)


@dataclass(frozen=True)
class LognormalFragility:
    r"""Lognormal fragility function [1]_:

    .. math::

        P_F(a) = \Phi\left(\frac{\ln(a/\theta)}{\beta}\right),

    :math:`\Phi` the standard normal CDF. Calling it evaluates :math:`P_F` [-] at amplitudes
    :math:`a` (0 for :math:`a \le 0`).

    Attributes
    ----------
    median : float
        :math:`\theta`: the amplitude with 50 % probability of failure [g] (or the unit of the
        intensity measure it was fitted to, :mod:`archquake.studies.record_fragility`).
    dispersion : float
        :math:`\beta`: the logarithmic standard deviation [-].

    References
    ----------
    .. [1] Baker, J. W. (2015). Efficient analytical fragility function fitting using dynamic
       structural analysis. Earthquake Spectra 31(1), 579-599.
    """

    median: float
    dispersion: float

    def __call__(self, amplitude) -> np.ndarray:
        a = np.asarray(amplitude, dtype=float)
        with np.errstate(divide="ignore"):
            z = np.log(np.where(a > 0, a, np.nan) / self.median) / self.dispersion
        return np.where(a > 0, stats.norm.cdf(z), 0.0)


def fit_lognormal(amplitudes, trials, failures) -> LognormalFragility:
    r"""Maximum-likelihood lognormal fragility from binomial counts.

    With :math:`z_j` collapses in :math:`n_j` analyses at amplitude :math:`a_j`, the counts are
    binomial with probability :math:`P(a_j) = \Phi(\ln(a_j/\theta)/\beta)`, and the fit
    maximises the log-likelihood (Eq. (11) in [1]_, without its constant binomial coefficients)

    .. math::

        \{\hat\theta, \hat\beta\} = \arg\max_{\theta, \beta} \sum_j \Bigl[z_j \ln P(a_j)
        + (n_j - z_j) \ln\bigl(1 - P(a_j)\bigr)\Bigr].

    It is solved by Nelder-Mead in :math:`(\ln\theta, \ln\beta)` from the amplitude nearest
    50 % failures and :math:`\beta = 0.3`. Separated data (every survival at an amplitude no
    higher than every failure) have no maximum: the fit then tends to a step, and its
    dispersion is only as small as the optimizer's tolerances leave it
    (:func:`archquake.studies.record_fragility.separated` tells such data).

    Parameters
    ----------
    amplitudes : array_like of float
        Amplitudes :math:`a_j` > 0 [g] (or the unit of the intensity measure), 1-D, at least 2.
    trials : int or array_like of int
        Number of analyses :math:`n_j` at each amplitude (one number: the same at every one).
    failures : array_like of int
        Number of collapses :math:`z_j` at each amplitude, :math:`0 \le z_j \le n_j`.

    Returns
    -------
    LognormalFragility
        :math:`\hat\theta` [unit of ``amplitudes``] and :math:`\hat\beta` [-].

    Raises
    ------
    ValueError
        If the arrays do not match, an amplitude is not finite and > 0, a count is out of range,
        or the data hold no failure or no survival (no maximum exists).

    See Also
    --------
    archquake.studies.record_fragility.lognormal_fit : the same fit, None where no maximum exists.

    References
    ----------
    .. [1] Baker, J. W. (2015). Efficient analytical fragility function fitting using dynamic
       structural analysis. Earthquake Spectra 31(1), 579-599.
    """
    a = np.asarray(amplitudes, dtype=float)
    n = np.broadcast_to(np.asarray(trials, dtype=float), a.shape)
    z = np.asarray(failures, dtype=float)
    if a.shape != z.shape or a.ndim != 1 or a.size < 2:
        raise ValueError("amplitudes and failures must be 1-D arrays of the same length (>= 2)")
    if np.any(a <= 0) or not np.all(np.isfinite(a)):
        raise ValueError("amplitudes must be finite and > 0 [g] for a lognormal fit")
    if np.any(z < 0) or np.any(z > n):
        raise ValueError("failures must be between 0 and the number of trials")
    if z.sum() == 0 or z.sum() == n.sum():
        raise ValueError("a lognormal fit needs both failures and survivals in the data")
    x = np.log(a)

    def nll(p):
        mu, log_beta = p
        beta = math.exp(log_beta)
        s = (x - mu) / beta
        return -(z * stats.norm.logcdf(s) + (n - z) * stats.norm.logsf(s)).sum()

    # start from the amplitude nearest 50 % and a typical dispersion
    frac = z / n
    mu0 = x[np.argmin(np.abs(frac - 0.5))]
    res = optimize.minimize(nll, [mu0, math.log(0.3)], method="Nelder-Mead",
                            options={"xatol": 1e-10, "fatol": 1e-12, "maxiter": 4000})
    mu, log_beta = res.x
    return LognormalFragility(float(math.exp(mu)), float(math.exp(log_beta)))


def rising_part(probability) -> int:
    """Number of leading grid points up to and including the first point where ``probability``
    takes its largest value: the part of a fragility curve a monotone (lognormal) model can
    describe.

    A local maximum below the largest value does not end the rising part (a dip on the way up
    is kept in the data of the fit).

    Parameters
    ----------
    probability : array_like, shape (n,)
        P_F [-] on an increasing amplitude grid.

    Returns
    -------
    int
        In ``1 .. n``.

    Raises
    ------
    ValueError
        If ``probability`` is not a non-empty 1-D array.

    Examples
    --------
    >>> rising_part([0.0, 0.5, 0.25, 1.0, 1.0, 0.5])
    4
    """
    p = np.asarray(probability, dtype=float)
    if p.ndim != 1 or p.size == 0:
        raise ValueError("probability must be a non-empty 1-D array")
    return int(np.argmax(p)) + 1


def fit_polynomial(amplitudes, probabilities, degree: int = 5) -> np.polynomial.Polynomial:
    """Least-squares polynomial of ``degree`` (the paper: 5) through (a [g], P_F) points.

    The paper fits such a polynomial to each fragility curve (the dashed curves of Figs. 17-20).
    Evaluate it with :func:`evaluate_polynomial_fit`, which clips to [0, 1].

    Parameters
    ----------
    amplitudes : array_like
        Amplitudes [g].
    probabilities : array_like
        P_F [-] at ``amplitudes``.
    degree : int
        Degree of the polynomial.

    Returns
    -------
    numpy.polynomial.Polynomial
        The fit (in the scaled variable of :meth:`numpy.polynomial.Polynomial.fit`; ``convert()``
        gives the coefficients in powers of the amplitude [g]).

    Raises
    ------
    ValueError
        If the arrays differ in shape or hold no more than ``degree`` points.
    """
    a = np.asarray(amplitudes, dtype=float)
    p = np.asarray(probabilities, dtype=float)
    if a.shape != p.shape or a.size <= degree:
        raise ValueError(f"a degree-{degree} fit needs more than {degree} points, got {a.size}")
    return np.polynomial.Polynomial.fit(a, p, degree)


def evaluate_polynomial_fit(poly: np.polynomial.Polynomial, amplitude) -> np.ndarray:
    """The polynomial fit clipped to probabilities in [0, 1].

    Parameters
    ----------
    poly : numpy.polynomial.Polynomial
        A fit of :func:`fit_polynomial`.
    amplitude : float or array_like
        Amplitudes [g].

    Returns
    -------
    ndarray
        P_F [-], in [0, 1].
    """
    return np.clip(poly(np.asarray(amplitude, dtype=float)), 0.0, 1.0)


# ---------------------------------------------------------------------------------------------
# The study
# ---------------------------------------------------------------------------------------------

DEFAULT_DURATIONS = STUDY_DURATIONS
"""Pulse durations t_p of the paper's fragility curves [s] (Figs. 17-20)."""
DEFAULT_AMPLITUDES_G = tuple(inclusive_range(*STUDY_AMPLITUDES_G).tolist())
"""Amplitude grid [g]: steps of 0.01 g as in the paper; the range (not stated in the paper) covers
the nominal failure accelerations of Fig. 16 with margin below (down to k~ of weak arches)."""
BELOW_NOMINAL_RTOL = 1e-9
"""Relative margin by which k~ of an irregular arch must lie below the nominal k to count as
below it [-]: the static and kinematic limit analyses of one arch agree to about 1e-9
(:data:`archquake.limit_analysis.AGREEMENT_TOLERANCE`), so a smaller difference is round-off
(with epsilon = 0 every drawn arch is the nominal one, and a strict ``<`` counted all of them)."""
POLYNOMIAL_DEGREE = 5
"""Degree of the paper's polynomial fit of a fragility curve."""


def nominal_dict(arch: BlockArch) -> dict:
    return arch.to_dict()


def nominal_from_dict(data: dict) -> BlockArch:
    return arch_from_dict(data)


def default_nominal() -> BlockArch:
    from ..reference_arches import oppenheim

    return oppenheim()


def positive_int(name: str, value: Any, minimum: int = 1, maximum: int | None = None) -> int:
    if (isinstance(value, bool) or not isinstance(value, int | np.integer) or value < minimum
            or (maximum is not None and value > maximum)):
        accepted = f">= {minimum}" if maximum is None else f"in [{minimum}, {maximum}]"
        raise ValueError(f"{name} must be an integer {accepted}, got {value!r}")
    return int(value)


@dataclass(frozen=True, eq=False)
class FragilitySettings:
    """Settings of a fragility study [paper, Sect. 5.3.3].

    Parameters
    ----------
    nominal : CircularArch or ShapedArch
        Nominal arch (default: Oppenheim's arch); any arch with a centreline, around which the
        irregular arches are drawn (eq. (1) and its generalisation,
        :func:`~archquake.geometry.irregular_arch`).
    sample_size : int
        Number h of irregular arches analysed dynamically (the paper: 40), at most
        :data:`~archquake.defaults.MAX_SAMPLES`; with the grid, at most
        :data:`~archquake.defaults.MAX_STUDY_ANALYSES` analyses in all.
    epsilon : float
        epsilon of the irregular draw [eq. (1)], in [0, 1) (the paper: 0.10).
    durations : tuple of float
        Pulse durations t_p [s] (the paper: 0.4, 0.5, 0.6, 0.7).
    amplitudes_g : tuple of float
        Increasing grid of pulse amplitudes a [g] (the paper: steps of 0.01 g); durations x
        amplitudes at most :data:`~archquake.defaults.MAX_GRID_POINTS`.
    seed : int
        Root seed (>= 0); arch i uses ``SeedSequence(seed, spawn_key=(i,))``.
    restitution : str or float
        Restitution model (:func:`archquake.fourlink.impact.check_restitution_model`; default
        ``"computed"``, each arch its own; ``"nominal"`` is the paper's practice, see the module
        docstring).
    limit_sample_size : int
        Number s of arches of the limit-analysis CDF of k~ (the paper: 1000), at most
        :data:`~archquake.defaults.MAX_LIMIT_SAMPLES`.
    limit_method : {"kinematic", "static"}
        Limit-analysis method of that sample (both give the same k~ to round-off; on a sample
        the kinematic enumeration is about ten times as fast).
    motion : str
        Pulse shape, a name of :data:`archquake.ground_motion.ANALYTIC_GROUND_MOTIONS` (default
        Oppenheim's pulse).

    Raises
    ------
    ValueError
        For a setting out of its range (the message names it), or a study larger than
        :data:`~archquake.defaults.MAX_STUDY_ANALYSES` analyses.
    """

    nominal: BlockArch = field(default_factory=default_nominal)
    sample_size: int = STUDY_SAMPLE_SIZE
    epsilon: float = DEFAULT_EPSILON
    durations: tuple[float, ...] = DEFAULT_DURATIONS
    amplitudes_g: tuple[float, ...] = DEFAULT_AMPLITUDES_G
    seed: int = DEFAULT_SEED
    restitution: str | float = DEFAULT_RESTITUTION
    limit_sample_size: int = LIMIT_SAMPLE_SIZE
    limit_method: str = DEFAULT_SAMPLE_LIMIT_METHOD
    motion: str = "oppenheim"

    def __post_init__(self) -> None:
        from ..fourlink.impact import check_restitution_model
        from ..ground_motion import ANALYTIC_GROUND_MOTIONS

        if not isinstance(self.nominal, BlockArch):
            raise ValueError(f"nominal must be an arch (CircularArch or ShapedArch), got "
                             f"{type(self.nominal).__name__}")
        if not hasattr(self.nominal, "perturbed"):
            raise ValueError(f"nominal must be an arch with a centreline to draw irregular "
                             f"arches around (CircularArch or ShapedArch), got "
                             f"{type(self.nominal).__name__}")
        positive_int("sample_size", self.sample_size, maximum=MAX_SAMPLES)
        positive_int("limit_sample_size", self.limit_sample_size, maximum=MAX_LIMIT_SAMPLES)
        positive_int("seed", self.seed, minimum=0)
        try:
            eps = float(self.epsilon)
        except (TypeError, ValueError):
            eps = math.nan
        if not 0.0 <= eps < 1.0:
            raise ValueError(f"epsilon must be in [0, 1), got {self.epsilon!r}")
        d = np.atleast_1d(np.asarray(self.durations, dtype=float))
        if d.ndim != 1 or d.size == 0 or not np.all(np.isfinite(d)) or np.any(d <= 0):
            raise ValueError(f"durations must be a non-empty list of pulse durations > 0 [s], "
                             f"got {np.ravel(d).tolist()}")
        if np.unique(d).size != d.size:
            raise ValueError(f"durations must be distinct, got {d.tolist()}")
        a = np.atleast_1d(np.asarray(self.amplitudes_g, dtype=float))
        if (a.ndim != 1 or a.size < 2 or not np.all(np.isfinite(a)) or np.any(a <= 0)
                or np.any(np.diff(a) <= 0)):
            raise ValueError("amplitudes_g must be an increasing list of at least two amplitudes "
                             "> 0 [g]")
        if a[-1] > MAX_ACCELERATION_G:
            raise ValueError(f"amplitudes_g must be at most {MAX_ACCELERATION_G:g} g, got "
                             f"{float(a[-1])!r}")
        if d.size * a.size > MAX_GRID_POINTS:
            raise ValueError(f"durations x amplitudes = {d.size} x {a.size} = {d.size * a.size} "
                             f"analyses per arch and direction, at most {MAX_GRID_POINTS} "
                             f"(MAX_GRID_POINTS)")
        analyses = 2 * int(self.sample_size) * d.size * a.size
        if analyses > MAX_STUDY_ANALYSES:
            raise ValueError(f"2 directions x {self.sample_size} samples x {d.size} durations x "
                             f"{a.size} amplitudes = {analyses} analyses, at most "
                             f"{MAX_STUDY_ANALYSES} in one study (MAX_STUDY_ANALYSES): use "
                             f"fewer arches or a coarser grid, or run several studies with "
                             f"different seeds")
        object.__setattr__(self, "restitution", check_restitution_model(self.restitution))
        if self.limit_method not in LIMIT_METHODS:
            raise ValueError(f"limit_method must be one of {LIMIT_METHODS}, got "
                             f"{self.limit_method!r}")
        if self.motion not in ANALYTIC_GROUND_MOTIONS:
            raise ValueError(f"motion must be one of {ANALYTIC_GROUND_MOTIONS}, got "
                             f"{self.motion!r}")
        object.__setattr__(self, "sample_size", int(self.sample_size))
        object.__setattr__(self, "limit_sample_size", int(self.limit_sample_size))
        object.__setattr__(self, "seed", int(self.seed))
        object.__setattr__(self, "epsilon", eps)
        object.__setattr__(self, "durations", tuple(float(x) for x in d))
        object.__setattr__(self, "amplitudes_g", tuple(float(x) for x in a))

    def to_dict(self) -> dict:
        """The settings as JSON-ready data, as stored with the results.

        Returns
        -------
        dict
            Every field, the nominal arch as :meth:`archquake.geometry.CircularArch.to_dict`.
        """
        return {
            "nominal": nominal_dict(self.nominal),
            "sample_size": self.sample_size,
            "epsilon": self.epsilon,
            "durations": list(self.durations),
            "amplitudes_g": list(self.amplitudes_g),
            "seed": self.seed,
            "restitution": self.restitution,
            "limit_sample_size": self.limit_sample_size,
            "limit_method": self.limit_method,
            "motion": self.motion,
        }

    @classmethod
    def from_dict(cls, data: dict) -> FragilitySettings:
        """Inverse of :meth:`to_dict` (the settings are validated again).

        Parameters
        ----------
        data : dict
            As :meth:`to_dict` writes it.

        Returns
        -------
        FragilitySettings
        """
        return cls(nominal=nominal_from_dict(data["nominal"]), sample_size=data["sample_size"],
                   epsilon=data.get("epsilon", data.get("tolerance")),
                   durations=tuple(data["durations"]),
                   amplitudes_g=tuple(data["amplitudes_g"]), seed=data["seed"],
                   restitution=data["restitution"], limit_sample_size=data["limit_sample_size"],
                   limit_method=data["limit_method"], motion=data["motion"])

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, FragilitySettings):
            return NotImplemented
        return self.to_dict() == other.to_dict()

    __hash__ = None  # mutable-free but holds arrays: compare by value, do not hash


def chunk_arches(chunk, nominal: BlockArch, epsilon: float) -> list[BlockArch]:
    """The irregular arches of the items of ``chunk``, drawn from their own seed sequences.

    Arch ``i`` is ``irregular_arch(nominal, epsilon, default_rng(SeedSequence(seed,
    spawn_key=(i,))))``: the same as ``irregular_sample(nominal, epsilon, count, seed)[i]``
    (eq. (1) of the paper).

    Parameters
    ----------
    chunk : archquake.execution.Chunk
        The items (arch indices) and the root seed.
    nominal : CircularArch
        The nominal arch.
    epsilon : float
        epsilon of eq. (1) [-], in [0, 1).

    Returns
    -------
    list of CircularArch
        One arch per item, in item order.
    """
    return [irregular_arch(nominal, epsilon, rng) for rng in chunk.generators()]


def arch_outcomes(arch: BlockArch, durations, amplitudes_g, *, restitution=DEFAULT_RESTITUTION,
                  nominal=None, motion: str = "oppenheim") -> dict[str, np.ndarray]:
    """Outcomes of one arch over the (duration x amplitude) grid, for both pulse directions.

    The arch's :class:`~archquake.fourlink.dynamics.ArchDynamics`, then one compiled call
    (:meth:`~archquake.fourlink.dynamics.ArchDynamics.outcomes`) per direction. Rows are ordered by
    direction (``"l"`` then ``"r"``), duration, amplitude.

    Parameters
    ----------
    arch : BlockArch
        The arch.
    durations : sequence of float
        Pulse durations t_p [s].
    amplitudes_g : sequence of float
        Pulse amplitudes a > 0 [g]; direction ``"l"`` applies ``-a g`` first, ``"r"`` ``+a g``.
    restitution : str or float
        Restitution model (:func:`archquake.fourlink.impact.check_restitution_model`).
    nominal : BlockArch or ArchDynamics, optional
        The nominal arch, for ``restitution="nominal"``.
    motion : str
        Pulse shape (:data:`archquake.ground_motion.ANALYTIC_GROUND_MOTIONS`).

    Returns
    -------
    dict of ndarray
        Columns ``direction``, ``duration`` [s], ``amplitude_g`` [g], ``status``,
        ``half_cycle``, ``impacts``, ``collapse_time`` [s], ``k_l``, ``k_r``, ``c_lr``,
        ``c_rl`` [-] (2 x durations x amplitudes rows); ``status`` holds the integer codes of
        :class:`archquake.status.Status`.

    Raises
    ------
    ValueError
        If the arch cannot be analysed (:meth:`archquake.fourlink.dynamics.ArchDynamics.from_arch`).
    """
    from ..fourlink.dynamics import ArchDynamics

    dynamics = ArchDynamics.from_arch(arch, restitution, nominal)
    d = np.asarray(durations, dtype=float)
    a = np.asarray(amplitudes_g, dtype=float)
    grid_d, grid_a = np.meshgrid(d, a, indexing="ij")
    parts = []
    for direction, sign in PULSE_SIGNS.items():
        out = dynamics.outcomes(grid_d, sign * grid_a, motion)
        parts.append({"direction": np.full(grid_d.size, direction),
                      "duration": grid_d.ravel(), "amplitude_g": grid_a.ravel(),
                      **{name: out[name].ravel() for name in
                         ("status", "half_cycle", "impacts", "collapse_time")}})
    columns = {name: np.concatenate([p[name] for p in parts]) for name in parts[0]}
    rows = columns["duration"].size
    values = (*dynamics.load_multipliers, *dynamics.restitution)
    for name, value in zip(("k_l", "k_r", "c_lr", "c_rl"), values, strict=True):
        columns[name] = np.full(rows, float(value))
    return columns


@functools.lru_cache(maxsize=4)
def _nominal_dynamics(nominal_json: str):
    """The nominal arch's :class:`~archquake.fourlink.FourLinkModel`, built once per process
    and nominal arch.

    Every chunk of a study needs its mechanisms for ``restitution="nominal"``; rebuilding them
    (limit analysis and linkage) in every chunk cost about a tenth of the chunk. They are frozen
    values, so sharing them between chunks changes no result.
    """
    from ..fourlink.dynamics import ArchDynamics

    return ArchDynamics.from_arch(nominal_from_dict(json.loads(nominal_json)))


STATUS_EXCLUDED = -1
"""``status`` of the rows of an excluded arch (not analysed; see :data:`EXCLUSIONS`)."""

EXCLUSIONS = {
    "not an arch": "the draw of eq. (1) separates neighbouring voussoirs (their radial "
                   "extents no longer overlap) or makes a voussoir thicker than its diameter",
    "cannot stand": "no line of thrust fits inside the arch under its own weight: it falls "
                    "without any ground motion, so it has no activation threshold",
    "not analysable": "the arch stands but its collapse mechanism is not the four-link "
                      "mechanism of the dynamics (e.g. a joint that opens over its whole depth, "
                      "or no mechanism in one direction)",
}
"""Why an irregular arch of a study is excluded (not analysed), by the name recorded in the
``excluded`` column of the study table ("" for an analysed arch). Excluded arches are counted
and named (index, seed) in the summary and the text output, and left out of h: P_F is the
probability of failure of the arches that stand (conditional on the draw being a standing
arch). An arch that cannot stand would fail at every amplitude; counting those as failures
instead would raise P_F by at most (their number) / h everywhere. An arch that never collapses
(a line of thrust for every k) is analysed, not excluded: it stays at rest at every amplitude,
with k~ = inf."""


def _draw(nominal: BlockArch, epsilon: float, rng) -> tuple[BlockArch | None, str]:
    """``(arch, "")``, or ``(None, "not an arch")`` when the draw of eq. (1) is no arch."""
    try:
        return irregular_arch(nominal, epsilon, rng), ""
    except ValueError:
        return None, "not an arch"


def _rows_without_motion(durations, amplitudes_g, status: int, k: float) -> dict[str, np.ndarray]:
    """The rows of :func:`arch_outcomes` for an arch that is not set in motion (status 0, an
    arch that never collapses, k = inf) or not analysed (:data:`STATUS_EXCLUDED`, k = nan)."""
    d, a = np.meshgrid(np.asarray(durations, float), np.asarray(amplitudes_g, float),
                       indexing="ij")
    n = d.size
    columns = {"direction": np.repeat(np.array(list(PULSE_SIGNS)), n),
               "duration": np.tile(d.ravel(), 2), "amplitude_g": np.tile(a.ravel(), 2),
               "status": np.full(2 * n, status, dtype=np.int8),
               "half_cycle": np.zeros(2 * n, dtype=np.int16),
               "impacts": np.zeros(2 * n, dtype=np.int32),
               "collapse_time": np.full(2 * n, np.nan)}
    for name in ("k_l", "k_r"):
        columns[name] = np.full(2 * n, k)
    for name in ("c_lr", "c_rl"):
        columns[name] = np.full(2 * n, np.nan)
    return columns


def _analyse(arch: BlockArch | None, why: str, settings: FragilitySettings,
             nominal) -> tuple[dict[str, np.ndarray], str]:
    """Rows of one drawn arch and why it is excluded ("" if it is analysed)."""
    from ..errors import CannotStandError, NeverCollapsesError
    from ..limit_analysis import load_multipliers

    if arch is not None:
        try:
            return arch_outcomes(arch, settings.durations, settings.amplitudes_g,
                                 restitution=settings.restitution, nominal=nominal,
                                 motion=settings.motion), ""
        except CannotStandError:
            why = "cannot stand"
        except NeverCollapsesError:
            if np.all(np.isinf(load_multipliers(arch))):
                return _rows_without_motion(settings.durations, settings.amplitudes_g, 0,
                                            math.inf), ""
            why = "not analysable"
        except ValueError:
            why = "not analysable"
    return _rows_without_motion(settings.durations, settings.amplitudes_g, STATUS_EXCLUDED,
                                math.nan), why


def fragility_task(chunk) -> dict[str, np.ndarray]:
    """Study task (:func:`archquake.execution.run_study`): the arches of one chunk.

    ``chunk.settings`` is :meth:`FragilitySettings.to_dict`; every item is one irregular arch
    (:func:`chunk_arches`), analysed by :func:`arch_outcomes`. An arch that cannot be analysed
    is excluded (:data:`EXCLUSIONS`; its rows then have status :data:`STATUS_EXCLUDED`); any
    other error stops the study with a message that names the arch (index and seed).

    Parameters
    ----------
    chunk : archquake.execution.Chunk
        The arches of the chunk.

    Returns
    -------
    dict of ndarray
        The tidy rows: the column ``arch`` (item index) first, the columns of
        :func:`arch_outcomes`, and ``excluded`` last: why the arch was not analysed, "" if it
        was.

    Raises
    ------
    archquake.errors.StudyError
        For an error of an arch other than the exclusions, naming the arch.
    """
    from ..errors import StudyError

    settings = FragilitySettings.from_dict(chunk.settings)
    nominal = None
    if settings.restitution == "nominal":
        nominal = _nominal_dynamics(json.dumps(chunk.settings["nominal"], sort_keys=True))
    parts = []
    for item, rng in zip(chunk.items, chunk.generators(), strict=True):
        arch, why = _draw(settings.nominal, settings.epsilon, rng)
        try:
            columns, why = _analyse(arch, why, settings, nominal)
        except Exception as exc:
            raise StudyError(f"irregular arch {item} (SeedSequence({chunk.seed}, spawn_key="
                             f"({item},))) stopped the study: {type(exc).__name__}: "
                             f"{exc}") from exc
        n = columns["duration"].size
        parts.append({"arch": np.full(n, item, dtype=np.int64), **columns,
                      "excluded": np.full(n, why, dtype="<U16")})
    return {name: np.concatenate([p[name] for p in parts]) for name in parts[0]}


def limit_task(chunk) -> dict[str, np.ndarray]:
    """Study task: k~_l and k~_r of the irregular arches of one chunk.

    ``chunk.settings`` holds ``nominal``, ``epsilon`` and ``limit_method``; the arches are those
    of :func:`chunk_arches`, hence the values are those of
    :func:`archquake.limit_analysis.limit_sample` with the same seed. An arch that is not an
    arch or cannot stand has k~ = nan and its reason in the column ``excluded``
    (:data:`EXCLUSIONS`); one that never collapses has k~ = inf.

    Parameters
    ----------
    chunk : archquake.execution.Chunk
        The arches of the chunk.

    Returns
    -------
    dict of ndarray
        Columns ``arch`` (item index), ``k_l``, ``k_r`` [-] and ``excluded``.
    """
    from ..limit_analysis import load_multipliers_of

    nominal = nominal_from_dict(chunk.settings["nominal"])
    draws = [_draw(nominal, chunk.settings["epsilon"], rng) for rng in chunk.generators()]
    arches = [arch for arch, _ in draws if arch is not None]
    k = np.full((len(draws), 2), np.nan)
    drawn = np.array([arch is not None for arch, _ in draws])
    if arches:
        k[drawn] = load_multipliers_of(arches, chunk.settings["limit_method"]).reshape(-1, 2)
    why = np.array([why for _, why in draws], dtype="<U16")
    # static: nan when no thrust line exists; kinematic: a negative self-weight multiplier
    cannot_stand = drawn & np.any(np.isnan(k) | (k < 0.0), axis=1)
    why[cannot_stand] = "cannot stand"
    k[why != ""] = np.nan
    return {"arch": chunk.items, "k_l": k[:, 0], "k_r": k[:, 1], "excluded": why}


@dataclass(frozen=True, eq=False)
class FragilityResult:
    """Result of :func:`run_fragility`.

    Attributes
    ----------
    settings : FragilitySettings
        The settings of the study.
    table : pandas.DataFrame
        Tidy table, one row per analysis, ordered by arch, direction, duration and amplitude:
        ``arch`` (item index), ``direction`` (``"l"``, ``"r"``), ``duration`` [s],
        ``amplitude_g`` [g], ``status`` (the codes of :class:`archquake.status.Status`: 0 rest,
        1 recovery, 2 collapse; :data:`STATUS_EXCLUDED` for an excluded arch),
        ``half_cycle``, ``impacts``, ``collapse_time`` [s], ``k_l``, ``k_r``, ``c_lr``,
        ``c_rl`` [-] and ``excluded`` (:data:`EXCLUSIONS`, "" for an analysed arch).
    durations : ndarray, shape (d,)
        Pulse durations t_p [s].
    amplitudes_g : ndarray, shape (a,)
        Amplitudes [g].
    failures, failures_l, failures_r : ndarray of int, shape (d, a)
        Number h_f of arches that collapse in either direction, in direction l, in direction r.
    probability, probability_l, probability_r : ndarray, shape (d, a)
        P_F = h_f / h [-] (eq. (9) of the paper), h the :attr:`analysed` arches.
    polynomial_fits : tuple of numpy.polynomial.Polynomial
        Quintic least-squares fit of P_F(a) per duration (the paper's dashed curves).
    lognormal_fits : tuple of LognormalFragility or None
        Maximum-likelihood lognormal fragility per duration (:func:`fit_lognormal`), fitted to
        the amplitudes up to the first one where P_F takes its largest value
        (:func:`rising_part`); None when no arch, or every arch, fails there, or fewer than two
        amplitudes are left.
    lognormal_upper : ndarray, shape (d,)
        Largest amplitude of the data of each lognormal fit [g].
    limit_sample : archquake.limit_analysis.LimitSample
        k~_l, k~_r of the s arches of the limit analysis.
    nominal_failure_acceleration_g : ndarray, shape (d,)
        Lowest amplitude at which the nominal arch collapses (either direction) [g] (point Q of
        Fig. 16, the threshold of the step fragility of eq. (10)), bisected to the study's
        ``nominal_resolution_g``; nan if it does not collapse in the grid.
    nominal_load_multiplier : float
        k = min(k_l, k_r) of the nominal arch [-].
    nominal_domains : tuple of FailureDomain
        The nominal arch's failure domain over the study grid, directions l and r.
    metadata : dict
        Settings, seed, version, timings of the study (from
        :func:`archquake.execution.run_study`).
    excluded : dict of int to str
        The irregular arches of the dynamic study that were not analysed, by index, with the
        reason (a key of :data:`EXCLUSIONS`); they are left out of h, so ``failures`` and the
        probabilities count the :attr:`analysed` arches only.
    """

    settings: FragilitySettings
    table: pd.DataFrame = field(repr=False)
    durations: np.ndarray
    amplitudes_g: np.ndarray = field(repr=False)
    failures: np.ndarray = field(repr=False)
    failures_l: np.ndarray = field(repr=False)
    failures_r: np.ndarray = field(repr=False)
    probability: np.ndarray = field(repr=False)
    probability_l: np.ndarray = field(repr=False)
    probability_r: np.ndarray = field(repr=False)
    polynomial_fits: tuple = field(repr=False)
    lognormal_fits: tuple
    lognormal_upper: np.ndarray = field(repr=False)
    limit_sample: Any = field(repr=False)
    nominal_failure_acceleration_g: np.ndarray
    nominal_load_multiplier: float
    nominal_domains: tuple[FailureDomain, FailureDomain] = field(repr=False)
    metadata: dict = field(repr=False, default_factory=dict)
    excluded: dict = field(default_factory=dict)

    @property
    def analysed(self) -> int:
        """Number of irregular arches analysed, the h of P_F = h_f / h (drawn minus excluded)."""
        return self.settings.sample_size - len(self.excluded)

    @property
    def limit_load_multipliers(self) -> np.ndarray:
        """k~ = min(k~_l, k~_r) of the s arches of the limit analysis [-]."""
        return self.limit_sample.load_multiplier

    def duration_index(self, duration: float) -> int:
        """Index of a pulse duration in :attr:`durations`.

        Parameters
        ----------
        duration : float
            Pulse duration t_p [s] (to 1e-9 s).

        Returns
        -------
        int

        Raises
        ------
        ValueError
            If it is not one of the study's durations.
        """
        hits = np.flatnonzero(np.abs(self.durations - duration) <= 1e-9)
        if hits.size == 0:
            raise ValueError(f"duration {duration!r} s is not one of the study's durations "
                             f"{self.durations.tolist()}")
        return int(hits[0])

    def probability_below_nominal(self) -> np.ndarray:
        """P_F at the largest grid amplitude below the nominal failure acceleration, per
        duration: where the step of eq. (10) says P_F = 0.

        Returns
        -------
        ndarray, shape (d,)
            P_F [-] (nan where there is no such amplitude).
        """
        out = np.full(self.durations.size, np.nan)
        for i, q in enumerate(self.nominal_failure_acceleration_g):
            below = np.flatnonzero(self.amplitudes_g < q) if math.isfinite(q) else np.array([])
            if below.size:
                out[i] = self.probability[i, below[-1]]
        return out

    def lowest_failure_acceleration_g(self) -> np.ndarray:
        """Lowest grid amplitude at which some irregular arch fails, per duration.

        Returns
        -------
        ndarray, shape (d,)
            Amplitude [g] (nan where no arch fails).
        """
        out = np.full(self.durations.size, np.nan)
        for i in range(self.durations.size):
            hit = np.flatnonzero(self.failures[i] > 0)
            if hit.size:
                out[i] = self.amplitudes_g[hit[0]]
        return out

    def curves(self) -> pd.DataFrame:
        """Fragility curves as a table: one row per (duration, amplitude) with h_f, P_F (both
        directions and each), the quintic and lognormal fits and the nominal step of eq. (10).

        Returns
        -------
        pandas.DataFrame
            Columns ``duration`` [s], ``amplitude_g`` [g], ``failures``, ``failures_l``,
            ``failures_r``, ``probability``, ``probability_l``, ``probability_r``,
            ``polynomial_fit``, ``lognormal_fit`` (nan without a fit) and ``nominal_step``
            (1 at and above the nominal failure acceleration, else 0) [-].
        """
        d, a = np.meshgrid(self.durations, self.amplitudes_g, indexing="ij")
        poly = np.vstack([evaluate_polynomial_fit(p, self.amplitudes_g)
                          for p in self.polynomial_fits])
        logn = np.vstack([f(self.amplitudes_g) if f is not None
                          else np.full(self.amplitudes_g.size, np.nan)
                          for f in self.lognormal_fits])
        step = (a >= self.nominal_failure_acceleration_g[:, None]).astype(float)
        return pd.DataFrame({
            "duration": d.ravel(), "amplitude_g": a.ravel(),
            "failures": self.failures.ravel(), "failures_l": self.failures_l.ravel(),
            "failures_r": self.failures_r.ravel(),
            "probability": self.probability.ravel(),
            "probability_l": self.probability_l.ravel(),
            "probability_r": self.probability_r.ravel(),
            "polynomial_fit": poly.ravel(), "lognormal_fit": logn.ravel(),
            "nominal_step": step.ravel(),
        })

    def summary(self) -> dict:
        """JSON-ready summary: per duration the nominal failure acceleration, P_F below it,
        the fits; ``arches``: how many were drawn and analysed, and the excluded ones by reason
        (:data:`EXCLUSIONS`); the k~ statistics of the limit sample over its arches that are
        not excluded (``count``; ``excluded``; ``never_collapse``: k~ = inf, left out of the
        mean, std, min and max; ``fraction_below_nominal``: the fraction with
        ``k~ < k (1 - BELOW_NOMINAL_RTOL)``).

        Returns
        -------
        dict
            JSON-ready (accelerations in g, non-finite numbers as None).
        """
        k = self.limit_load_multipliers
        counted = k[~np.isnan(k)]  # excluded arches have k~ = nan; inf: never collapses
        finite = counted[np.isfinite(counted)]
        below = self.probability_below_nominal()
        lowest = self.lowest_failure_acceleration_g()
        per_duration = []
        for i, tp in enumerate(self.durations):
            lognormal = self.lognormal_fits[i]
            q = float(self.nominal_failure_acceleration_g[i])
            per_duration.append({
                "duration": float(tp),
                "nominal_failure_acceleration": _json_number(q),
                "probability_below_nominal": _json_number(below[i]),
                "lowest_failure_acceleration": _json_number(lowest[i]),
                "polynomial_coefficients": self.polynomial_fits[i].convert().coef.tolist(),
                "lognormal_median": None if lognormal is None else lognormal.median,
                "lognormal_fitted_up_to": float(self.lognormal_upper[i]),
                "lognormal_dispersion": None if lognormal is None else lognormal.dispersion,
                "lognormal_at_nominal": (None if lognormal is None or not math.isfinite(q)
                                         else float(lognormal(q))),
            })
        def stat(function, values):
            return _json_number(float(function(values))) if values.size else None

        reasons = sorted(set(self.excluded.values()), key=list(EXCLUSIONS).index)
        return {
            "settings": self.settings.to_dict(),
            "seed": self.settings.seed,
            "nominal_load_multiplier": self.nominal_load_multiplier,
            "nominal_restitution": list(self.nominal_domains[0].restitution),
            "arches": {
                "drawn": self.settings.sample_size, "analysed": self.analysed,
                "excluded": {why: sorted(i for i, w in self.excluded.items() if w == why)
                             for why in reasons},
            },
            "limit_sample": {
                "count": int(counted.size), "excluded": int(k.size - counted.size),
                "never_collapse": int(counted.size - finite.size),
                "method": self.settings.limit_method,
                "mean": stat(np.mean, finite),
                "std": float(np.std(finite, ddof=1)) if finite.size > 1 else 0.0,
                "min": stat(np.min, finite), "max": stat(np.max, finite),
                "fraction_below_nominal": stat(np.mean, counted < self.nominal_load_multiplier
                                               * (1.0 - BELOW_NOMINAL_RTOL)),
                "below_nominal_rtol": BELOW_NOMINAL_RTOL,
            },
            "durations": per_duration,
        }


def _json_number(x: float):
    return None if not math.isfinite(x) else float(x)


def _study_arrays(table: pd.DataFrame, settings: FragilitySettings):
    """``status[arch, direction, duration, amplitude]`` from the tidy table (order checked)."""
    h, nd, na = settings.sample_size, len(settings.durations), len(settings.amplitudes_g)
    expected = h * 2 * nd * na
    if len(table) != expected:
        raise ValueError(f"the study table has {len(table)} rows, expected {expected}")
    shape = (h, 2, nd, na)
    arch = table["arch"].to_numpy().reshape(shape)
    direction = table["direction"].to_numpy().astype(str).reshape(shape)
    duration = table["duration"].to_numpy().reshape(shape)
    amplitude = table["amplitude_g"].to_numpy().reshape(shape)
    if (np.any(arch != np.arange(h)[:, None, None, None])
            or np.any(direction != np.array(list(PULSE_SIGNS))[None, :, None, None])
            or np.any(duration != np.asarray(settings.durations)[None, None, :, None])
            or np.any(amplitude != np.asarray(settings.amplitudes_g)[None, None, None, :])):
        raise ValueError("the study table is not ordered by arch, direction, duration, "
                         "amplitude as the fragility task writes it")
    return table["status"].to_numpy().reshape(shape)


def fragility_curves(settings: FragilitySettings, table: pd.DataFrame, limit_sample,
                     nominal_domains, metadata: dict | None = None) -> FragilityResult:
    """Assemble a :class:`FragilityResult` from the study table, the limit sample and the
    nominal arch's failure domains (both directions).

    P_F of eq. (9) of the paper counts an arch as failed where it collapses in either direction,
    over the arches that are not excluded; the fits are :func:`fit_polynomial` (whole grid) and
    :func:`fit_lognormal` (rising part).

    Parameters
    ----------
    settings : FragilitySettings
        The settings of the study.
    table : pandas.DataFrame
        The tidy table of :func:`fragility_task` rows, in its order.
    limit_sample : archquake.limit_analysis.LimitSample
        k~_l, k~_r of the limit-analysis sample.
    nominal_domains : (FailureDomain, FailureDomain)
        The nominal arch's failure domains, directions l and r, over the study grid.
    metadata : dict, optional
        Metadata of the study.

    Returns
    -------
    FragilityResult

    Raises
    ------
    ValueError
        If the table does not match the settings, or every arch was excluded.
    """
    from ..status import Status

    excluded = excluded_arches(table)
    keep = np.array([i not in excluded for i in range(settings.sample_size)])
    if not keep.any():
        counts = ", ".join(f"{why}: {n}" for why, n in
                           pd.Series(list(excluded.values())).value_counts().items())
        raise ValueError(f"every one of the {settings.sample_size} irregular arches was excluded "
                         f"({counts}): no probability of failure can be estimated; use a "
                         f"smaller epsilon (epsilon = {settings.epsilon:g}) or a thicker "
                         f"nominal arch")
    collapsed = _study_arrays(table, settings)[keep] == Status.COLLAPSE
    failed_l, failed_r = collapsed[:, 0], collapsed[:, 1]
    failed = failed_l | failed_r
    a = np.asarray(settings.amplitudes_g)
    h = int(keep.sum())
    polynomial_fits, lognormal_fits, lognormal_upper = [], [], []
    probability = probability_of_failure(failed)
    for i in range(len(settings.durations)):
        degree = min(POLYNOMIAL_DEGREE, a.size - 1)
        polynomial_fits.append(fit_polynomial(a, probability[i], degree))
        z = failed[:, i].sum(axis=0)
        end = rising_part(probability[i])
        lognormal_upper.append(a[end - 1])
        lognormal_fits.append(fit_lognormal(a[:end], h, z[:end])
                              if end >= 2 and 0 < z[:end].sum() < h * end else None)
    q = np.fmin(nominal_domains[0].failure_accelerations_g,
                nominal_domains[1].failure_accelerations_g)
    k_nominal = min(nominal_domains[0].load_multipliers)
    return FragilityResult(
        settings=settings, table=table, durations=np.asarray(settings.durations), amplitudes_g=a,
        failures=failed.sum(axis=0), failures_l=failed_l.sum(axis=0),
        failures_r=failed_r.sum(axis=0), probability=probability,
        probability_l=probability_of_failure(failed_l),
        probability_r=probability_of_failure(failed_r),
        polynomial_fits=tuple(polynomial_fits), lognormal_fits=tuple(lognormal_fits),
        lognormal_upper=np.asarray(lognormal_upper),
        limit_sample=limit_sample, nominal_failure_acceleration_g=q,
        nominal_load_multiplier=float(k_nominal), nominal_domains=tuple(nominal_domains),
        metadata=dict(metadata or {}), excluded=excluded)


def excluded_arches(table: pd.DataFrame) -> dict[int, str]:
    """The excluded arches of a study table (column ``excluded``, :data:`EXCLUSIONS`).

    Parameters
    ----------
    table : pandas.DataFrame
        A study table (:func:`fragility_task` rows).

    Returns
    -------
    dict of int to str
        ``{arch: reason}``; empty for a table without that column.
    """
    if "excluded" not in table.columns:
        return {}
    why = table["excluded"].fillna("").astype(str)  # "" reads back from CSV as missing
    rows = table.loc[why != "", "arch"]
    return {int(i): str(w) for i, w in zip(rows, why[why != ""], strict=True)}


def warm_up() -> None:
    """Load everything a fragility study runs (compiled engine, limit analysis) in this process
    by running a two-arch study of two analyses each, serially.

    The compiled functions are cached on disk, so this costs loading them (a fraction of a
    second), not compiling them, unless the cache is cold. Use it as the ``warm_up`` of
    :func:`archquake.execution.process_pool`, or on Dask workers with ``client.run``.
    """
    tiny = FragilitySettings(sample_size=2, durations=(0.4,), amplitudes_g=(0.3, 0.6),
                             limit_sample_size=2)
    run_fragility(tiny, backend="serial", progress=False)


def _nominal_domains(settings: FragilitySettings, resolution_g: float) -> tuple:
    """The nominal arch's failure domains over the study grid, directions l and r (point Q of
    Fig. 16 per duration), to ``resolution_g`` [g]."""
    from ..fourlink.dynamics import ArchDynamics

    dynamics = ArchDynamics.from_arch(settings.nominal, settings.restitution)
    return tuple(dynamics.failure_domain(settings.durations, settings.amplitudes_g,
                                         direction=direction, resolution=resolution_g,
                                         motion=settings.motion, extend_to_g=None)
                 for direction in PULSE_SIGNS)


def _check_nominal(nominal: BlockArch) -> None:
    """Refuse, before any study, a nominal arch whose limit analysis fails (e.g. it cannot
    stand under its own weight): its failure domains would fail only after the study."""
    from ..limit_analysis import both_directions

    try:
        both_directions(nominal)
    except ValueError as exc:
        raise ValueError(f"the nominal arch cannot be analysed: {exc}") from exc


LIMIT_DIRECTORY = "limit_sample"
"""Subdirectory of a fragility study directory holding the limit-analysis sample (its own study)."""
CURVES_CSV = "curves.csv"
"""File of the fragility curves (:meth:`FragilityResult.curves`) in a study directory."""


def run_fragility(
    settings: FragilitySettings,
    out_dir: str | os.PathLike | None = None,
    *,
    backend: str | None = None,
    workers: int | None = None,
    scheduler: Any = None,
    pool: Any = None,
    resume: bool = False,
    progress: bool = True,
    chunk_size: int = 2,
    limit_chunk_size: int = 50,
    nominal_resolution_g: float = 1e-4,
) -> FragilityResult:
    """Fragility study of irregular arches [paper, Sect. 5.3.3, eq. (9), Figs. 17-21].

    Parameters
    ----------
    settings : FragilitySettings
        What to compute.
    out_dir : str or os.PathLike, optional
        Study directory (must be new or empty unless ``resume``). Written there: ``study.json``
        and ``chunks/`` (checkpoints), ``results.parquet`` and ``results.csv`` (the tidy table),
        ``curves.csv`` (:meth:`FragilityResult.curves`), ``summary.json`` (metadata: settings,
        seed, ``archquake_version``, timings; and :meth:`FragilityResult.summary`), and the
        limit-analysis sample as its own study in ``limit_sample/``.
    backend : {"serial", "processes", "dask"}, optional
        How to run the chunks (:func:`archquake.execution.run_study`); default
        :func:`archquake.execution.default_backend` (``"dask"`` with a scheduler,
        ``"processes"`` with ``workers`` or ``pool``, else in this process, as the command line
        and the report). Both studies share one process pool / Dask cluster.
    workers : int, optional
        Local processes (default: the number of CPUs).
    scheduler : str or distributed.Client, optional
        Dask scheduler address ``tcp://HOST:PORT`` or a client.
    pool : concurrent.futures.Executor, optional
        Running worker processes (:func:`archquake.execution.process_pool`) for backend
        ``"processes"``, to run several studies on the same warm workers; ``workers`` is then
        ignored. The caller keeps ownership of the pool.
    resume : bool
        Continue the study saved in ``out_dir`` (same settings required).
    progress : bool
        Progress bars on stderr.
    chunk_size, limit_chunk_size : int
        Arches per chunk of the dynamic study and of the limit sample (recorded; a resumed study
        must use the same).
    nominal_resolution_g : float
        Bisection width of the nominal failure acceleration [g].

    Returns
    -------
    FragilityResult

    Raises
    ------
    ValueError
        For invalid settings or execution options, a nominal arch that cannot be analysed, an
        output directory that is not empty (without ``resume``) or holds another study.
    archquake.errors.StudyError
        If an irregular arch fails for a reason other than the exclusions (naming it), or the
        Dask cluster can no longer finish the study (:func:`archquake.execution.run_study`).
    """
    from ..execution import StudyPlan, default_backend, process_pool, run_study
    from ..limit_analysis import LimitSample
    from ..results_io import atomic_path, save_study

    if not isinstance(settings, FragilitySettings):
        raise ValueError(f"settings must be FragilitySettings, got {type(settings).__name__}")
    _check_nominal(settings.nominal)
    plan = StudyPlan(settings.to_dict(), settings.seed, settings.sample_size,
                     positive_int("chunk_size", chunk_size))
    limit_settings = {"nominal": nominal_dict(settings.nominal),
                      "epsilon": settings.epsilon, "limit_method": settings.limit_method}
    limit_plan = StudyPlan(limit_settings, settings.seed, settings.limit_sample_size,
                           positive_int("limit_chunk_size", limit_chunk_size))
    backend = default_backend(backend, workers, scheduler, pool)
    out = None if out_dir is None else Path(out_dir)
    limit_dir = None if out is None else out / LIMIT_DIRECTORY
    options = {"backend": backend, "resume": resume, "progress": progress}

    def studies(**run):
        # with local processes, one worker computes the nominal arch's failure domains while
        # the others start on the chunks (it would otherwise be serial work after them)
        running = run.get("pool")
        nominal = (None if running is None
                   else running.submit(_nominal_domains, settings, nominal_resolution_g))
        table = run_study(fragility_task, plan, out, **options, **run)
        limit_table = run_study(limit_task, limit_plan, limit_dir, **options, **run)
        domains = (_nominal_domains(settings, nominal_resolution_g) if nominal is None
                   else nominal.result())
        return table, limit_table, domains

    if backend == "processes":
        if workers is not None:
            positive_int("workers", workers)
        if scheduler is not None:
            raise ValueError(f"scheduler is only used by backend 'dask', not {backend!r}")
        if pool is not None:
            table, limit_table, domains = studies(pool=pool)
        else:
            with process_pool(workers) as own_pool:  # an exception terminates its workers
                table, limit_table, domains = studies(pool=own_pool)
    else:
        if pool is not None:
            raise ValueError(f"pool is only used by backend 'processes', not {backend!r}")
        table, limit_table, domains = studies(workers=workers, scheduler=scheduler)

    limit = LimitSample(limit_table["k_l"].to_numpy(), limit_table["k_r"].to_numpy(),
                        settings.epsilon, settings.seed, settings.limit_method)
    metadata = dict(table.attrs.get("study", {}))
    result = fragility_curves(settings, table, limit, domains, metadata)
    if out is not None:
        with atomic_path(out / CURVES_CSV) as tmp:
            result.curves().to_csv(tmp, index=False)
        save_study(out, table, metadata=metadata, summary=result.summary())
    return result


def load_fragility(out_dir: str | os.PathLike, *,
                   nominal_resolution_g: float = 1e-4) -> FragilityResult:
    """Reload a finished fragility study (:func:`run_fragility` with ``out_dir``) as a
    :class:`FragilityResult`.

    The tidy table, the settings and the limit-analysis sample are read from the directory; the
    fits are refitted from the table and the nominal arch's failure domains (a fraction of a
    second) recomputed, so the curves equal those of the original run.

    Parameters
    ----------
    out_dir : str or os.PathLike
        The study directory.
    nominal_resolution_g : float
        Bisection width of the nominal failure acceleration [g] (that of the original run, to
        reproduce it).

    Returns
    -------
    FragilityResult

    Raises
    ------
    ValueError
        If the directory holds no complete study (e.g. an interrupted one: continue it with
        ``resume=True``), or its files do not belong together.
    """
    from ..limit_analysis import LimitSample
    from ..results_io import load_study

    out = Path(out_dir)
    stored = load_study(out)
    try:
        settings = FragilitySettings.from_dict(stored.summary["settings"])
    except (KeyError, TypeError) as exc:
        raise ValueError(f"{out} does not hold a fragility study (no settings in its "
                         f"summary)") from exc
    limit_table = load_study(out / LIMIT_DIRECTORY).table
    if len(limit_table) != settings.limit_sample_size:
        raise ValueError(f"{out / LIMIT_DIRECTORY} has {len(limit_table)} arches, the study's "
                         f"settings say {settings.limit_sample_size}")
    limit = LimitSample(limit_table["k_l"].to_numpy(), limit_table["k_r"].to_numpy(),
                        settings.epsilon, settings.seed, settings.limit_method)
    domains = _nominal_domains(settings, nominal_resolution_g)
    return fragility_curves(settings, stored.table, limit, domains, stored.metadata)
