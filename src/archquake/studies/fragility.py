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
the binomial counts of the grid (Eq. (11) in [2]_, :func:`archquake.studies.fits.fit_lognormal`),
the standard form in earthquake engineering (the statistics live in
:mod:`archquake.studies.fits`). Under a pulse :math:`P_F(a)` need not be monotone: above the failure
accelerations a band of amplitudes lets arches recover again (the last phase of the pulse brings
them back, README). A lognormal CDF cannot follow that, so it is fitted to the rising part of the
data, the amplitudes up to the first grid point where :math:`P_F` takes its largest value
(:func:`~archquake.studies.fits.rising_part`, recorded with the fit); the polynomial, as in the
paper, is fitted to the whole grid.

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

Arch ``i`` of both samples is arch ``i`` of the study's
:class:`~archquake.studies.arch_sample.ArchSample` (drawn by
:func:`archquake.geometry.irregular_arch` from ``SeedSequence(seed, spawn_key=(i,))``), i.e. arch
``i`` of ``irregular_sample(nominal, epsilon, sample_size, seed)`` and of ``limit_sample(...)``:
the first h arches of the limit sample are the arches of the dynamic study, and of the
record-based study with the same seed. The study runs through
:func:`archquake.execution.run_study` (chunks of arches, serial / local processes / Dask,
resumable checkpoints); the results do not depend on how it is run.

Arches that cannot be analysed follow the one rule of :mod:`archquake.studies.arch_sample`: with a
large epsilon (or a thin nominal arch) a drawn arch may not be an arch, may not stand under its own
weight, or may not have a four-link mechanism. Such arches are excluded, not allowed to stop the
study: they are counted and named by reason (:data:`~archquake.studies.arch_sample.EXCLUSIONS`),
index and seed in the summary and the text output, and left out of h, so P_F is the probability of
failure of the drawn arches that stand. Any other error names the arch that raised it.

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

import math
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from .._equality import frozen_value
from ..checks import check_integer, json_float
from ..defaults import (
    DEFAULT_EPSILON,
    DEFAULT_SAMPLE_LIMIT_METHOD,
    DEFAULT_SEARCH,
    DEFAULT_SEED,
    LIMIT_METHODS,
    LIMIT_SAMPLE_SIZE,
    MAX_ACCELERATION_G,
    MAX_GRID_POINTS,
    MAX_LIMIT_SAMPLES,
    MAX_PULSE_DURATION,
    MAX_SAMPLES,
    MAX_STUDY_ANALYSES,
    STUDY_AMPLITUDES_G,
    STUDY_DURATIONS,
    STUDY_SAMPLE_SIZE,
)
from ..geometry import GRAVITY, BlockArch
from ..models import DEFAULT_MODEL, ModelSpec, model_spec
from ..reference_arches import oppenheim
from .arch_sample import (
    STATUS_EXCLUDED,
    StudySample,
    check_analysed,
    check_nominal,
    excluded_arches,
    exclusion_summary,
    nominal_model,
    sample_of,
    study_error,
)
from .failure_domain import (
    PULSE_SIGNS,
    FailureDomain,
    domain_of,
    inclusive_range,
)
from .fits import (
    evaluate_polynomial_fit,
    fit_lognormal,
    fit_polynomial,
    probability_of_failure,
    rising_part,
)
from .strategies import DEFAULT_STRIDE, study_seconds, workers_that_pay
from .undecided import undecided_count, undecided_summary

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


@dataclass(frozen=True, eq=False)
class FragilitySettings(StudySample):
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
    limit_sample_size : int
        Number s of arches of the limit-analysis CDF of k~ (the paper: 1000), at most
        :data:`~archquake.defaults.MAX_LIMIT_SAMPLES`.
    limit_method : {"kinematic", "static"}
        Limit-analysis method of that sample (both give the same k~ to round-off; on a sample
        the kinematic enumeration is about ten times as fast).
    motion : str
        Pulse shape, a name of :data:`archquake.ground_motion.ANALYTIC_GROUND_MOTIONS` (default
        Oppenheim's pulse).
    model : ModelSpec or str
        The dynamic model of every arch and its settings (:class:`archquake.models.ModelSpec`;
        a name stands for its spec with the default settings; default the paper's four-link
        model, restitution ``"computed"``, each arch its own: ``"nominal"`` is the paper's
        practice, see the module docstring). Recorded resolved for the nominal arch
        (:meth:`~archquake.models.ModelSpec.resolved`: the rigid blocks' time step chosen from
        it unless given, 1 ms for Oppenheim's arch; how the study's outcomes depend on it:
        :func:`archquake.rigid_blocks.dynamics.structure_time_step` and the user guide, "What a
        rigid-block study costs").
    search : {"exhaustive", "bisection", "screened"}, optional
        How each arch's amplitude lines are searched (:mod:`archquake.studies.strategies`;
        default :data:`archquake.defaults.DEFAULT_SEARCH` of the model).
    stride : int, optional
        Grid steps between the coarse points of ``bisection`` and ``screened`` [-] (default
        :data:`archquake.defaults.DEFAULT_STRIDE`).
    description : StructureSpec, optional
        A bridge of several spans of one arch
        (:attr:`~archquake.geometry.StructureSpec.bridge_of_arches`, without ``epsilon`` and
        ``seed``), instead of ``nominal``: its members put one irregular arch on every span
        (:class:`~archquake.studies.arch_sample.BridgeSample`), analysed by the rigid blocks
        (the only model of a bridge), whose search has no four-link screen; the nominal
        structure is the bridge the description builds, and ``limit_method`` is ``"static"``
        (the assembly's program, :func:`~archquake.limit_analysis.assembly_multipliers`).

    Raises
    ------
    ValueError
        For a setting out of its range (the message names it), or a study larger than
        :data:`~archquake.defaults.MAX_STUDY_ANALYSES` analyses.
    """

    nominal: BlockArch = field(default_factory=oppenheim)
    sample_size: int = STUDY_SAMPLE_SIZE
    epsilon: float = DEFAULT_EPSILON
    durations: tuple[float, ...] = DEFAULT_DURATIONS
    amplitudes_g: tuple[float, ...] = DEFAULT_AMPLITUDES_G
    seed: int = DEFAULT_SEED
    limit_sample_size: int = LIMIT_SAMPLE_SIZE
    limit_method: str = DEFAULT_SAMPLE_LIMIT_METHOD
    motion: str = "oppenheim"
    model: ModelSpec | str = DEFAULT_MODEL
    search: str | None = None
    stride: int | None = None
    description: Any = None

    def __post_init__(self) -> None:
        from ..ground_motion import ANALYTIC_GROUND_MOTIONS
        from .strategies import check_search, check_stride

        self._take_description()
        if self.description is not None:  # an assembly has one limit analysis, the static one
            object.__setattr__(self, "limit_method", "static")
        # resolved for the nominal structure (its time step), then recorded
        object.__setattr__(self, "model", model_spec(self.model).resolved(self.nominal))
        object.__setattr__(self, "search", check_search(
            self.model.default_search if self.search is None else self.search))
        object.__setattr__(self, "stride", check_stride(
            DEFAULT_STRIDE if self.stride is None else self.stride))
        sample = self.sample  # checks nominal, epsilon, seed
        check_integer("sample_size", self.sample_size, maximum=MAX_SAMPLES)
        check_integer("limit_sample_size", self.limit_sample_size, maximum=MAX_LIMIT_SAMPLES)
        d = np.atleast_1d(np.asarray(self.durations, dtype=float))
        if (d.ndim != 1 or d.size == 0 or not np.all(np.isfinite(d)) or np.any(d <= 0)
                or np.any(d > MAX_PULSE_DURATION)):
            bad = [v for v in np.ravel(d).tolist() if not 0 < v <= MAX_PULSE_DURATION]
            raise ValueError(f"durations must be a non-empty list of pulse durations in (0, "
                             f"{MAX_PULSE_DURATION:g}] s (MAX_PULSE_DURATION), got "
                             f"{bad[:5] if bad else np.ravel(d).tolist()[:5]}")
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
        if self.limit_method not in LIMIT_METHODS:
            raise ValueError(f"limit_method must be one of {LIMIT_METHODS}, got "
                             f"{self.limit_method!r}")
        if self.motion not in ANALYTIC_GROUND_MOTIONS:
            raise ValueError(f"motion must be one of {ANALYTIC_GROUND_MOTIONS}, got "
                             f"{self.motion!r}")
        object.__setattr__(self, "sample_size", int(self.sample_size))
        object.__setattr__(self, "limit_sample_size", int(self.limit_sample_size))
        object.__setattr__(self, "seed", sample.seed)
        object.__setattr__(self, "epsilon", sample.epsilon)
        object.__setattr__(self, "durations", tuple(float(x) for x in d))
        object.__setattr__(self, "amplitudes_g", tuple(float(x) for x in a))
        self._check_motion(float(d.min()))

    def _check_motion(self, shortest: float) -> None:
        """Refuse, before any analysis, a model that cannot resolve the shortest pulse on the
        nominal arch (:meth:`archquake.models.ModelSpec.check_motion`: the rigid blocks' time
        step; an irregular arch thinner than the nominal one by epsilon may still refuse a step
        at the limit when it is analysed)."""
        from ..ground_motion import ground_motion

        self.model.check_motion(self.nominal, ground_motion(self.motion, GRAVITY, shortest))

    @property
    def screening(self) -> ModelSpec | None:
        """The model that screens every arch's search (``screened`` with a model that needs
        one, the four-link model, default restitution; a bridge has none), or None."""
        if self.search != "screened" or self.description is not None:
            return None
        return self.model.screening()

    def to_sample_dict(self) -> dict:
        """What draws the study's sample (:func:`sample_of`): the nominal arch (or the
        bridge's description) and epsilon."""
        return {**self.structure_dict(), "epsilon": self.epsilon}

    def to_dict(self) -> dict:
        """The settings as JSON-ready data, as stored with the results.

        Returns
        -------
        dict
            Every field, the nominal arch as :meth:`archquake.geometry.CircularArch.to_dict`
            (for a bridge, its ``description`` as
            :meth:`archquake.geometry.StructureSpec.to_dict` instead).
        """
        model = self.model.to_dict()  # its keys stored flat, as before the spec
        return {
            **self.structure_dict(),
            "sample_size": self.sample_size,
            "epsilon": self.epsilon,
            "durations": list(self.durations),
            "amplitudes_g": list(self.amplitudes_g),
            "seed": self.seed,
            "restitution": model.pop("restitution"),
            "limit_sample_size": self.limit_sample_size,
            "limit_method": self.limit_method,
            "motion": self.motion,
            "model": model.pop("model"),
            "search": self.search,
            "stride": self.stride,
            **model,
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
        return cls(**cls.structure_of(data), sample_size=data["sample_size"],
                   epsilon=data.get("epsilon", data.get("tolerance")),
                   durations=tuple(data["durations"]),
                   amplitudes_g=tuple(data["amplitudes_g"]), seed=data["seed"],
                   limit_sample_size=data["limit_sample_size"],
                   limit_method=data["limit_method"], motion=data["motion"],
                   model=ModelSpec.from_dict(data), search=data.get("search"),
                   stride=data.get("stride", DEFAULT_STRIDE))

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, FragilitySettings):
            return NotImplemented
        return self.to_dict() == other.to_dict()

    def __hash__(self) -> int:
        # frozen, and every field an immutable value: hashed as it compares, by its to_dict
        return hash(("FragilitySettings", frozen_value(self.to_dict())))


def model_outcomes(model, durations, amplitudes_g, *, motion: str = "oppenheim",
                   search: str | None = None, stride: int = DEFAULT_STRIDE, screen=None
                   ) -> dict[str, np.ndarray]:
    """Outcomes of one arch's model over the (duration x amplitude) grid, for both pulse
    directions.

    The four-link model's whole grid is one compiled call per direction
    (:meth:`~archquake.fourlink.FourLinkModel.outcomes`); the rigid-block model's amplitude
    lines are searched by ``search`` (:func:`archquake.studies.strategies.pulse_grid_outcomes`).
    Rows are ordered by direction (``"l"`` then ``"r"``), duration, amplitude.

    Parameters
    ----------
    model : StructuralModel
        The arch's model (:func:`archquake.models.model_for`).
    durations : sequence of float
        Pulse durations t_p [s].
    amplitudes_g : sequence of float
        Pulse amplitudes a > 0 [g]; direction ``"l"`` applies ``-a g`` first, ``"r"`` ``+a g``.
    motion : str
        Pulse shape (:data:`archquake.ground_motion.ANALYTIC_GROUND_MOTIONS`).
    search : {"exhaustive", "bisection", "screened"}, optional
        Search strategy (default :data:`archquake.defaults.DEFAULT_SEARCH` of the model).
    stride : int
        Coarse stride of the faster strategies [grid steps].
    screen : StructuralModel, optional
        The screening model of ``"screened"`` (the four-link model of the same arch).

    Returns
    -------
    dict of ndarray
        Columns ``direction``, ``duration`` [s], ``amplitude_g`` [g], ``status``,
        ``half_cycle``, ``impacts`` (-1 where the model does not count them or the outcome was
        inferred), ``collapse_time`` [s] (nan where inferred), ``analysed`` (False where the
        outcome was inferred from analysed neighbours), ``k_l``, ``k_r``, ``c_lr``, ``c_rl``
        [-] (nan for a model without restitution) (2 x durations x amplitudes rows);
        ``status`` holds the integer codes of :class:`archquake.status.Status`.
    """
    search = DEFAULT_SEARCH[model.name] if search is None else search
    if not (model.grid_in_one_call and search == "exhaustive"):
        return _searched_outcomes(model, durations, amplitudes_g, motion, search, stride,
                                  screen)
    d = np.asarray(durations, dtype=float)
    a = np.asarray(amplitudes_g, dtype=float)
    grid_d, grid_a = np.meshgrid(d, a, indexing="ij")
    parts = []
    for direction, sign in PULSE_SIGNS.items():
        out = model.outcomes(grid_d, sign * grid_a, motion)
        parts.append({"direction": np.full(grid_d.size, direction),
                      "duration": grid_d.ravel(), "amplitude_g": grid_a.ravel(),
                      **{name: out[name].ravel() for name in
                         ("status", "half_cycle", "impacts", "collapse_time")},
                      "analysed": np.ones(grid_d.size, dtype=bool)})
    columns = {name: np.concatenate([p[name] for p in parts]) for name in parts[0]}
    rows = columns["duration"].size
    values = (*model.load_multipliers, *model.restitution)
    for name, value in zip(("k_l", "k_r", "c_lr", "c_rl"), values, strict=True):
        columns[name] = np.full(rows, float(value))
    return columns


def _searched_outcomes(model, durations, amplitudes_g, motion, search, stride, screen):
    """:func:`model_outcomes` by a search strategy (one analysis per point analysed)."""
    from .strategies import pulse_grid_outcomes

    out = pulse_grid_outcomes(model, durations, amplitudes_g, motion=motion, search=search,
                              stride=stride, screen=screen)
    rows = out["duration"].size
    columns = {name: out[name] for name in ("direction", "duration", "amplitude_g")}
    columns |= {"status": out["status"], "half_cycle": out["half_cycle"],
                "impacts": np.full(rows, -1, dtype=np.int64),
                "collapse_time": np.full(rows, np.nan), "analysed": out["analysed"]}
    values = (*model.load_multipliers, *getattr(model, "restitution", (np.nan, np.nan)))
    for name, value in zip(("k_l", "k_r", "c_lr", "c_rl"), values, strict=True):
        columns[name] = np.full(rows, float(value))
    return columns


def _rows_without_motion(durations, amplitudes_g, status: int, k: float) -> dict[str, np.ndarray]:
    """The rows of :func:`model_outcomes` for an arch that is not set in motion (status 0, an
    arch that never collapses, k = inf) or not analysed
    (:data:`~archquake.studies.arch_sample.STATUS_EXCLUDED`, k = nan)."""
    d, a = np.meshgrid(np.asarray(durations, float), np.asarray(amplitudes_g, float),
                       indexing="ij")
    n = d.size
    columns = {"direction": np.repeat(np.array(list(PULSE_SIGNS)), n),
               "duration": np.tile(d.ravel(), 2), "amplitude_g": np.tile(a.ravel(), 2),
               "status": np.full(2 * n, status, dtype=np.int8),
               "half_cycle": np.zeros(2 * n, dtype=np.int16),
               "impacts": np.zeros(2 * n, dtype=np.int32),
               "collapse_time": np.full(2 * n, np.nan),
               "analysed": np.zeros(2 * n, dtype=bool)}
    for name in ("k_l", "k_r"):
        columns[name] = np.full(2 * n, k)
    for name in ("c_lr", "c_rl"):
        columns[name] = np.full(2 * n, np.nan)
    return columns


def fragility_task(chunk) -> dict[str, np.ndarray]:
    """Study task (:func:`archquake.execution.run_study`): the arches of one chunk.

    ``chunk.settings`` is :meth:`FragilitySettings.to_dict`; every item is one irregular arch
    of :attr:`FragilitySettings.sample`, analysed by :func:`model_outcomes`. An arch that cannot
    be analysed is excluded (:data:`~archquake.studies.arch_sample.EXCLUSIONS`; its rows then
    have status :data:`~archquake.studies.arch_sample.STATUS_EXCLUDED`); any other error stops
    the study with a message that names the arch (index and seed).

    Parameters
    ----------
    chunk : archquake.execution.Chunk
        The arches of the chunk.

    Returns
    -------
    dict of ndarray
        The tidy rows: the column ``arch`` (item index) first, the columns of
        :func:`model_outcomes`, and ``excluded`` last: why the arch was not analysed, "" if it
        was.

    Raises
    ------
    archquake.errors.StudyError
        For an error of an arch other than the exclusions, naming the arch.
    """
    settings = FragilitySettings.from_dict(chunk.settings)
    sample = settings.sample
    grid = (settings.durations, settings.amplitudes_g)
    parts = []
    for item in chunk.items:
        try:
            member = sample.member(item, settings.model)
            if member.model is not None:
                screen = None
                if settings.screening is not None:
                    screen = sample.member(item, settings.screening).model  # where it has one
                columns = model_outcomes(member.model, *grid, motion=settings.motion,
                                         search=settings.search, stride=settings.stride,
                                         screen=screen)
            elif member.never_collapses:
                columns = _rows_without_motion(*grid, 0, math.inf)
            else:
                columns = _rows_without_motion(*grid, STATUS_EXCLUDED, math.nan)
        except Exception as exc:
            raise study_error(sample.label(item), exc) from exc
        n = columns["duration"].size
        parts.append({"arch": np.full(n, item, dtype=np.int64), **columns,
                      "excluded": np.full(n, member.excluded, dtype="<U16")})
    return {name: np.concatenate([p[name] for p in parts]) for name in parts[0]}


def limit_task(chunk) -> dict[str, np.ndarray]:
    """Study task: k~_l and k~_r of the irregular arches of one chunk.

    ``chunk.settings`` holds ``nominal``, ``epsilon`` and ``limit_method``; the arches are those
    of the study's :class:`~archquake.studies.arch_sample.ArchSample` with the chunk's seed,
    hence the values are those of :func:`archquake.limit_analysis.limit_sample` with the same
    seed (:meth:`~archquake.studies.arch_sample.ArchSample.load_multipliers`). An arch that is
    not an arch or cannot stand has k~ = nan and its reason in the column ``excluded``
    (:data:`~archquake.studies.arch_sample.EXCLUSIONS`); one that never collapses has k~ = inf.

    Parameters
    ----------
    chunk : archquake.execution.Chunk
        The arches of the chunk.

    Returns
    -------
    dict of ndarray
        Columns ``arch`` (item index), ``k_l``, ``k_r`` [-] and ``excluded``.
    """
    sample = sample_of(chunk.settings, chunk.seed)
    k, why = sample.load_multipliers(chunk.items, chunk.settings["limit_method"])
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
        1 recovery, 2 collapse; :data:`~archquake.studies.arch_sample.STATUS_EXCLUDED` for an
        excluded arch), ``half_cycle``, ``impacts``, ``collapse_time`` [s], ``k_l``, ``k_r``,
        ``c_lr``, ``c_rl`` [-] and ``excluded``
        (:data:`~archquake.studies.arch_sample.EXCLUSIONS`, "" for an analysed arch).
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
        Maximum-likelihood lognormal fragility per duration
        (:func:`~archquake.studies.fits.fit_lognormal`), fitted to the amplitudes up to the
        first one where P_F takes its largest value
        (:func:`~archquake.studies.fits.rising_part`); None when no arch, or every arch, fails
        there, or fewer than two amplitudes are left.
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
        reason (a key of :data:`~archquake.studies.arch_sample.EXCLUSIONS`); they are left out
        of h, so ``failures`` and the probabilities count the :attr:`analysed` arches only.
    undecided : ndarray of int, shape (d, a)
        Number h_u of analysed arches whose failure the model left undecided: an analysis
        undecided in a direction (:attr:`archquake.status.Status.UNDECIDED`, the rigid-block
        model's) and a collapse in neither. :attr:`probability` counts them as survivals (the
        lower bound of P_F), :attr:`probability_upper` as failures; the fits are made to
        :attr:`probability` (:mod:`archquake.studies.undecided`). None: zero everywhere.
    undecided_analyses : int
        Rows of the table of the analysed arches whose status is undecided [-] (analysed, or
        inferred between two undecided analyses by the ``bisection`` search,
        :mod:`archquake.studies.strategies`).
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
    undecided: np.ndarray | None = field(repr=False, default=None)
    undecided_analyses: int = 0

    def __post_init__(self) -> None:
        if self.undecided is None:
            object.__setattr__(self, "undecided", np.zeros_like(self.failures))

    @property
    def analysed(self) -> int:
        """Number of irregular arches analysed, the h of P_F = h_f / h (drawn minus excluded)."""
        return self.settings.sample_size - len(self.excluded)

    @property
    def analyses(self) -> int:
        """Analyses of the analysed arches (both directions, the whole grid) [-]."""
        return 2 * self.analysed * self.failures.size

    @property
    def probability_upper(self) -> np.ndarray:
        """Upper bound of P_F, shape (d, a) [-]: the arches whose failure is undecided
        (:attr:`undecided`) counted as failed, ``(h_f + h_u) / h``; equal to
        :attr:`probability` (the lower bound) where no analysis was left undecided."""
        return (self.failures + self.undecided) / self.analysed

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

    def nominal_failure_bound(self, i: int) -> str | None:
        """Whether the nominal failure acceleration of duration ``i`` is a bound
        (:attr:`archquake.studies.failure_domain.DomainSlice.failure_acceleration_bound` of the
        direction that gives it): ``"upper"`` when the nominal arch collapses at the lowest
        amplitude scanned, ``"lower"`` when at none, None when bracketed."""
        q = float(self.nominal_failure_acceleration_g[i])
        if not math.isfinite(q):
            return "lower"
        slices = [domain.slices[i] for domain in self.nominal_domains]
        return ("upper" if any(s.failure_acceleration_g == q
                               and s.failure_acceleration_bound == "upper" for s in slices)
                else None)

    def nominal_failure_undecided_from(self, i: int) -> float:
        """Lowest amplitude [g] of an undecided band of the nominal arch below its failure
        acceleration of duration ``i`` (in either direction;
        :attr:`archquake.studies.failure_domain.DomainSlice.failure_undecided_from_g`): the
        nominal failure acceleration then lies between it and
        :attr:`nominal_failure_acceleration_g`. nan when none (the value is decided)."""
        q = float(self.nominal_failure_acceleration_g[i])
        lows = []
        for domain in self.nominal_domains:
            s = domain.slices[i]
            low = s.failure_undecided_from_g
            lows.append(low if math.isfinite(low) else s.failure_acceleration_g)
        lows = [x for x in lows if math.isfinite(x)]
        low = min(lows) if lows else math.nan
        return low if math.isfinite(low) and (math.isnan(q) or low < q) else math.nan

    @property
    def nominal_undecided_analyses(self) -> int:
        """Analyses of the nominal arch's failure domains left undecided [-]."""
        return sum(getattr(d, "undecided_analyses", 0) for d in self.nominal_domains)

    def probability_below_nominal(self, upper: bool = False) -> np.ndarray:
        """P_F at the largest grid amplitude below the nominal failure acceleration, per
        duration: where the step of eq. (10) says P_F = 0.

        Parameters
        ----------
        upper : bool
            The upper bound of P_F (:attr:`probability_upper`) instead of P_F.

        Returns
        -------
        ndarray, shape (d,)
            P_F [-] (nan where there is no such amplitude).
        """
        probability = self.probability_upper if upper else self.probability
        out = np.full(self.durations.size, np.nan)
        for i, q in enumerate(self.nominal_failure_acceleration_g):
            below = np.flatnonzero(self.amplitudes_g < q) if math.isfinite(q) else np.array([])
            if below.size:
                out[i] = probability[i, below[-1]]
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
            ``polynomial_fit``, ``lognormal_fit`` (nan without a fit), ``nominal_step``
            (1 at and above the nominal failure acceleration, else 0) [-], ``undecided``
            (h_u, :attr:`undecided`) and ``probability_upper`` (:attr:`probability_upper`:
            ``probability`` is its lower bound) [-].
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
            "undecided": self.undecided.ravel(),
            "probability_upper": self.probability_upper.ravel(),
        })

    def summary(self) -> dict:
        """JSON-ready summary: per duration the nominal failure acceleration, P_F below it,
        the fits, and ``undecided`` (the arch-amplitude points whose failure is undecided, 0
        when every analysis decided; only then, the upper bounds
        ``probability_upper_largest_gap`` (the largest difference of the bounds of P_F over the
        amplitudes), ``probability_below_nominal_upper`` and, for an undecided band of the
        nominal arch below its failure acceleration, ``nominal_failure_undecided_from`` [g]);
        ``undecided``: the count of undecided analyses of the irregular arches and of the
        nominal arch (:func:`archquake.studies.undecided.undecided_summary`, ``nominal_analyses``);
        ``arches``: how many were drawn and analysed, and the excluded ones by reason
        (:data:`~archquake.studies.arch_sample.EXCLUSIONS`); the k~ statistics of the limit
        sample over its arches that are not excluded (``count``; ``excluded``;
        ``never_collapse``: k~ = inf, left out of the mean, std, min and max;
        ``fraction_below_nominal``: the fraction with ``k~ < k (1 - BELOW_NOMINAL_RTOL)``).

        Returns
        -------
        dict
            JSON-ready (accelerations in g, non-finite numbers as None).
        """
        k = self.limit_load_multipliers
        counted = k[~np.isnan(k)]  # excluded arches have k~ = nan; inf: never collapses
        finite = counted[np.isfinite(counted)]
        below = self.probability_below_nominal()
        below_upper = self.probability_below_nominal(upper=True)
        lowest = self.lowest_failure_acceleration_g()
        per_duration = []
        for i, tp in enumerate(self.durations):
            lognormal = self.lognormal_fits[i]
            q = float(self.nominal_failure_acceleration_g[i])
            per_duration.append({
                "duration": float(tp),
                "nominal_failure_acceleration": json_float(q),
                "probability_below_nominal": json_float(below[i]),
                "lowest_failure_acceleration": json_float(lowest[i]),
                "polynomial_coefficients": self.polynomial_fits[i].convert().coef.tolist(),
                "lognormal_median": None if lognormal is None else lognormal.median,
                "lognormal_fitted_up_to": float(self.lognormal_upper[i]),
                "lognormal_dispersion": None if lognormal is None else lognormal.dispersion,
                "lognormal_at_nominal": (None if lognormal is None or not math.isfinite(q)
                                         else float(lognormal(q))),
                **({"nominal_failure_acceleration_bound": "upper"}
                   if self.nominal_failure_bound(i) == "upper" else {}),
                "undecided": int(self.undecided[i].sum()),
                **self._undecided_bounds(i, below[i], below_upper[i]),
            })
        def stat(function, values):
            return json_float(float(function(values))) if values.size else None

        return {
            "settings": self.settings.to_dict(),
            "seed": self.settings.seed,
            "nominal_load_multiplier": self.nominal_load_multiplier,
            "nominal_restitution": [json_float(c) for c in self.nominal_domains[0].restitution],
            "arches": exclusion_summary(self.settings.sample_size, self.excluded),
            "undecided": {**undecided_summary(self.undecided_analyses, self.analyses),
                          "nominal_analyses": self.nominal_undecided_analyses},
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
            "search": self.search_summary(),
        }

    def search_summary(self) -> dict:
        """How the study searched its grid: ``strategy`` and ``stride``, the ``grid_points``
        of the irregular arches analysed dynamically (the arches excluded, and those that
        never collapse, have no search) and of the nominal arch's failure domains
        (``nominal_grid_points``), the points of each whose outcome was inferred without an
        analysis (``not_analysed``, ``nominal_not_analysed``) and, for ``bisection``, the
        ``caveat`` every output of the study says
        (:func:`archquake.studies.strategies.search_caveat`; None otherwise).

        Returns
        -------
        dict
        """
        from .strategies import search_caveat

        table = self.table
        searched = ((table["excluded"].to_numpy() == "")
                    & np.isfinite(table["k_l"].to_numpy(dtype=float)))
        points = int(searched.sum())
        skipped = int(np.count_nonzero(~table["analysed"].to_numpy(dtype=bool)[searched]))
        nominal_points = sum(sum(d.scan_points) for d in self.nominal_domains)
        nominal_skipped = sum(sum(d.not_analysed) for d in self.nominal_domains)
        s = self.settings
        return {"strategy": s.search, "stride": s.stride, "grid_points": points,
                "not_analysed": skipped, "nominal_grid_points": int(nominal_points),
                "nominal_not_analysed": int(nominal_skipped),
                "caveat": search_caveat(s.search, skipped + nominal_skipped,
                                        points + nominal_points, s.stride)}


    def _undecided_bounds(self, i: int, below: float, below_upper: float) -> dict:
        """The keys of duration ``i`` of :meth:`summary` that only undecided analyses add."""
        out = {}
        if self.undecided[i].any():
            out["probability_upper_largest_gap"] = float(
                np.max(self.probability_upper[i] - self.probability[i]))
        if below_upper != below and math.isfinite(below_upper):
            out["probability_below_nominal_upper"] = float(below_upper)
        low = self.nominal_failure_undecided_from(i)
        if math.isfinite(low):
            out["nominal_failure_undecided_from"] = low
        return out


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
    over the arches that are not excluded; an arch whose analyses are undecided in a direction
    and collapse in neither counts as a survival in P_F (the lower bound) and as a failure in
    :attr:`FragilityResult.probability_upper` (:mod:`archquake.studies.undecided`). The fits
    are :func:`~archquake.studies.fits.fit_polynomial` (whole grid) and
    :func:`~archquake.studies.fits.fit_lognormal` (rising part), both of P_F, the lower bound.

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
    check_analysed(settings.sample_size, excluded, settings.epsilon)
    keep = np.array([i not in excluded for i in range(settings.sample_size)])
    status = _study_arrays(table, settings)[keep]
    collapsed = status == Status.COLLAPSE
    failed_l, failed_r = collapsed[:, 0], collapsed[:, 1]
    failed = failed_l | failed_r
    undecided = (status == Status.UNDECIDED).any(axis=1) & ~failed  # failure not decided
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
        metadata=dict(metadata or {}), excluded=excluded, undecided=undecided.sum(axis=0),
        undecided_analyses=undecided_count(status))


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


def _engines():
    """What a pool warmed up by :func:`warm_up` compiles: the four-link engine."""
    from ..models import ModelSpec

    return ModelSpec("four-link").engines()


warm_up.engines = _engines  # (archquake.compiled)


LIMIT_ANALYSIS_SECONDS = 1e-3
"""Time of the kinematic limit analysis of one arch of the limit sample [s] (measured: 1,000
arches in about a second)."""

BRIDGE_LIMIT_SECONDS = 0.06
"""Time of the limit analysis of one irregular bridge of the limit sample [s] (measured: 200
bridges of three spans in 12 s, each built and its overlaps checked)."""

FORK_PAYS_SECONDS = 0.2
"""Estimated time of a limit sample [s] from which a study run in this process gives it to a
forked worker (:func:`archquake.execution.forked_pool`), when more than one worker was asked
for: forking takes about 10 ms, and the sample's result a few more to come back."""


def _serial_seconds(settings: FragilitySettings) -> float:
    """Estimated time of a study in one process [s]: its arches and analyses
    (:func:`archquake.studies.strategies.study_seconds`), the nominal arch's, and the limit
    sample."""
    grid = 2 * len(settings.durations) * len(settings.amplitudes_g)
    arches = settings.sample_size + 1
    blocks = None if settings.description is None else settings.nominal.n_blocks
    limit = LIMIT_ANALYSIS_SECONDS if blocks is None else BRIDGE_LIMIT_SECONDS
    return (study_seconds(settings.model.name, "pulse", arches, arches * grid, blocks)
            + settings.limit_sample_size * limit)


def _nominal_domains(settings: FragilitySettings, resolution_g: float | None) -> tuple:
    """The nominal arch's failure domains over the study grid, directions l and r (point Q of
    Fig. 16 per duration), to ``resolution_g`` [g] (default
    :attr:`archquake.models.ModelSpec.nominal_resolution_g` of the model)."""
    if resolution_g is None:
        resolution_g = settings.model.nominal_resolution_g
    model = nominal_model(settings.nominal_structure, settings.model)
    return tuple(domain_of(model, settings.durations, settings.amplitudes_g,
                           direction=direction, resolution_g=resolution_g,
                           motion=settings.motion, extend_to_g=None, search=settings.search,
                           stride=settings.stride)
                 for direction in PULSE_SIGNS)


def _limit_study(plan, out, options: dict):
    """The limit-analysis sample of a study, in a forked worker (:func:`run_fragility`)."""
    from ..execution import run_study

    return run_study(limit_task, plan, out, **options)


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
    chunk_size: int | None = None,
    limit_chunk_size: int = 50,
    nominal_resolution_g: float | None = None,
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
        Local processes (default: the number of CPUs). Without an explicit ``backend``, a
        study whose estimated work (:func:`_serial_seconds`) is shorter than what the workers
        would save once started (:func:`archquake.studies.strategies.pool_pays`) runs in this
        process instead (the four-link model's paper-sized study: about 3 s of work, 6 s
        in this process against 14 s on two fresh workers); its metadata say ``"serial"``.
        With two workers or more asked for, such a study gives its limit sample, when it is
        estimated at :data:`FORK_PAYS_SECONDS` or more, to one worker forked from this process
        (:func:`archquake.execution.forked_pool`, Linux only), which computes it while the
        arches run here (the paper's four-link study as a command: 2.97 s against 3.37 s).
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
        Arches per chunk of the dynamic study (default
        :attr:`archquake.models.ModelSpec.chunk_size`: 2 with the four-link model, 1 with the
        rigid blocks, whose arch takes seconds) and of the limit sample (recorded; a resumed
        study must use the same).
    nominal_resolution_g : float, optional
        Bisection width of the nominal failure acceleration [g] (default
        :attr:`archquake.models.ModelSpec.nominal_resolution_g` of the model).

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
    from ..compiled import announce_all
    from ..execution import StudyPlan, default_backend, forked_pool, process_pool, run_study
    from ..limit_analysis import LimitSample
    from ..results_io import atomic_path, save_study

    if not isinstance(settings, FragilitySettings):
        raise ValueError(f"settings must be FragilitySettings, got {type(settings).__name__}")
    check_nominal(settings.nominal_structure, settings.model)
    announce_all(settings.engines())  # compiled here or by workers: said here, once
    if chunk_size is None:
        chunk_size = settings.model.chunk_size
    plan = StudyPlan(settings.to_dict(), settings.seed, settings.sample_size,
                     check_integer("chunk_size", chunk_size))
    limit_settings = {**settings.to_sample_dict(), "limit_method": settings.limit_method}
    limit_plan = StudyPlan(limit_settings, settings.seed, settings.limit_sample_size,
                           check_integer("limit_chunk_size", limit_chunk_size))
    asked = workers
    workers = workers_that_pay(_serial_seconds(settings), workers, backend=backend,
                               scheduler=scheduler, pool=pool)
    # a study run here because fresh workers would not pay: a forked one takes the limit
    # sample while this process runs the arches (and pays from a fraction of a second of it)
    fork_limit = (backend is None and workers is None and asked is not None and asked >= 2
                  and settings.limit_sample_size * LIMIT_ANALYSIS_SECONDS >= FORK_PAYS_SECONDS)
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
        helper = forked_pool() if fork_limit else None  # fork_limit: no pool here
        if helper is None:
            table = run_study(fragility_task, plan, out, **options, **run,
                              save=False)  # saved below, with the summary
            limit_table = run_study(limit_task, limit_plan, limit_dir, **options, **run)
        else:
            with helper:  # an exception here terminates the forked worker
                limit = helper.submit(_limit_study, limit_plan, limit_dir,
                                      {**options, "progress": False, **run})
                table = run_study(fragility_task, plan, out, **options, **run, save=False)
                limit_table = limit.result()
        domains = (_nominal_domains(settings, nominal_resolution_g) if nominal is None
                   else nominal.result())
        return table, limit_table, domains

    if backend == "processes":
        if workers is not None:
            check_integer("workers", workers)
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
                   nominal_resolution_g: float | None = None) -> FragilityResult:
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
