r"""Record-based fragility of irregular arches: multiple-stripe analysis [1]_.

Every record of a suite is scaled to each level :math:`x_j` of an intensity measure (IM, e.g.
PGA [g]) and applied in both polarities (as recorded, and with its sign flipped) to every arch of
the irregular sample drawn around a nominal arch [paper, eq. (1)], and to the nominal arch
itself. An arch-record pair *fails* at :math:`x_j` if the arch collapses in either polarity (the
conservative reading, as in the pulse study of :mod:`archquake.studies.fragility`); the per-polarity
outcomes are kept in the table. With :math:`y_{a r j} \in \{0, 1\}` the failure of arch
:math:`a` under record :math:`r` at level :math:`x_j` (:math:`h` arches, :math:`R` records), the
stripe of :math:`x_j` has :math:`n_j = h R` trials and
:math:`z_j = \sum_{a, r} y_{a r j}` failures, and (the record-based counterpart of the paper's
:math:`P_F = h_f / h`, eq. (9))

.. math::

    P(\mathrm{collapse} \mid IM = x_j) \approx \frac{z_j}{n_j}.

Fits and variability
--------------------
Each fragility function is the lognormal CDF :math:`P(x) = \Phi(\ln(x/\theta)/\beta)` with
median :math:`\theta` (in the IM's unit) and dispersion :math:`\beta` [-], fitted by maximum
likelihood on the binomial counts per stripe (Eq. (11) in [1]_):

.. math::

    \{\hat\theta, \hat\beta\} = \arg\max_{\theta, \beta} \sum_j \Bigl[z_j \ln P(x_j)
    + (n_j - z_j) \ln\bigl(1 - P(x_j)\bigr)\Bigr]

(:func:`archquake.studies.fits.fit_lognormal_or_none`; none exists for separated counts,
:func:`archquake.studies.fits.separated`). Three dispersions are reported
(:func:`archquake.studies.fits.dispersions`):

record-to-record, :math:`\beta_{RTR}`
    the fit to the nominal arch's stripes (``n_j = R`` records): how the collapse level of one
    geometry varies from record to record.
geometric, :math:`\beta_G`
    the irregular arches' spread for the same records: the joint maximum-likelihood fit of
    :math:`P_r(x) = \Phi(\ln(x/\theta_r)/\beta_G)` with one median :math:`\theta_r` per record
    and one common dispersion, to the counts ``z_{r,j} = sum_a y[a, r, j]`` of ``n = h`` arches
    (:func:`archquake.studies.fits.common_dispersion_fit`). Records that collapse no arch, or
    every arch, at every level carry no information on it and are left out. It also absorbs
    the non-monotone response of a record (an arch that recovers at a level above one that
    collapses it). With
    :math:`\varepsilon = 0` every arch is the nominal one and :math:`\beta_G = 0` by definition.
total, :math:`\beta`
    everything pooled: the fit to ``z_j`` of all ``h R`` arch-record pairs; its median and
    dispersion are *the* fragility function of the study (``"lognormal"`` in the summary). If
    the two sources were independent lognormal factors of the collapse level,
    :math:`\beta^2 \approx \beta_{RTR}^2 + \beta_G^2` (reported as ``"srss"`` beside it).

The confidence band of a fit is a percentile bootstrap (ch. 13 of [2]_): the arches and the
records are resampled with replacement (both, for the sample; the records, for the nominal
arch), the counts rebuilt from the resampled pairs and refitted
(:func:`archquake.studies.fits.bootstrap_lognormal`;
:math:`B` = ``bootstrap`` resamples, 1000 by default, from
``SeedSequence(seed, spawn_key=(BOOTSTRAP_KEY,))``); with :math:`\alpha = 1 -` ``confidence``,
the band at every IM value :math:`x` is

.. math::

    \Bigl[\, q_{\alpha/2}\bigl\{P^{*b}(x)\bigr\}_{b=1}^{B},\;
    q_{1-\alpha/2}\bigl\{P^{*b}(x)\bigr\}_{b=1}^{B} \Bigr],

:math:`q_p` the empirical :math:`p`-quantile of the refitted curves :math:`P^{*b}` (the central
90 % by default). A resample whose counts admit no maximum-likelihood fit (no failure, no
survival, or failures and survivals separated by one level: a step) is counted and left out.

The incremental view
--------------------
For every arch and record, the lowest level that collapses the pair and the levels above it at
which the arch survives again (the record's outcome is not monotone in its scale, like a pulse's
in the paper's Fig. 16): :meth:`RecordFragilityResult.incremental`.

Execution
---------
:func:`run_record_fragility` runs through :func:`archquake.execution.run_study`: one item per
arch, the ``h`` irregular arches first (arch ``i`` of the study's
:class:`~archquake.studies.arch_sample.ArchSample`, drawn from ``SeedSequence(seed,
spawn_key=(i,))``, i.e. arch ``i`` of :func:`archquake.geometry.irregular_sample` and of the pulse
study), then the nominal arch (``arch = -1`` in the table). Chunks of arches run serially, on local
processes or on Dask, are checkpointed and resumable, and the results do not depend on how they
were run. The workers read the records from their files (so on a Dask cluster the files must be at
the same paths on every worker); the settings hold the suite
(:class:`~archquake.ground_motion.RecordSuite`: each file's name and SHA-256 digest), a worker
refuses a file whose content changed, and a resume with changed files is refused.

An irregular arch that cannot be analysed (it is not an arch, cannot stand, or has no four-link
mechanism) is excluded as in the pulse study, by the one rule of
:mod:`archquake.studies.arch_sample`: its rows carry ``status``
:data:`~archquake.studies.arch_sample.STATUS_EXCLUDED` and the reason in the column ``excluded``,
the summary names it (``arches``), and the stripes count the ``h`` analysed arches only
(:attr:`RecordFragilityResult.analysed`); a study whose every irregular arch is excluded is an
error. An arch that never collapses is analysed: it stays at rest at every level. The nominal arch
must be analysable (checked before the study starts).

For each arch and record, all levels and both polarities are one compiled call
(:func:`archquake.fourlink.engine.outcomes_grid` with the record as template). An analysis whose
scaled record never reaches the arch's activation acceleration (eq. (2): ``xg'' < -k_l g`` or
``xg'' > k_r g``) is not integrated: the arch stays at rest, exactly as the engine would decide
(the record is piecewise linear, so its extremes are samples; a relative margin of
:data:`REST_MARGIN` keeps round-off out of it). Levels above an arch's collapse level are *not*
skipped: collapse is not monotone in the level.

References
----------
.. [1] Baker, J. W. (2015). Efficient analytical fragility function fitting using dynamic
   structural analysis. Earthquake Spectra 31(1), 579-599.
.. [2] Efron, B. and Tibshirani, R. J. (1993). An Introduction to the Bootstrap. Chapman & Hall,
   ch. 13 (percentile intervals).
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
from ..checks import check_integer
from ..defaults import (
    DEFAULT_EPSILON,
    DEFAULT_IM,
    DEFAULT_LEVEL_STRIDE,
    DEFAULT_SEED,
    MAX_SAMPLES,
    RECORD_STUDY_SEARCH,
    STUDY_SAMPLE_SIZE,
)
from ..geometry import BlockArch
from ..ground_motion.suites import RecordSuite, stripe_measure
from ..models import DEFAULT_MODEL, ModelSpec, model_spec
from ..reference_arches import oppenheim
from ..status import Status
from .arch_sample import (
    STATUS_EXCLUDED,
    StudySample,
    check_analysed,
    check_nominal,
    excluded_arches,
    exclusion_summary,
    nominal_model,
    study_error,
)
from .fits import (
    DISPERSIONS,
    BootstrapBand,
    CommonDispersionFit,
    LognormalFragility,
    bootstrap_lognormal,
    common_dispersion_fit,
    dispersions,
    fit_lognormal_or_none,
)
from .record_outcomes import POLARITIES, REST_MARGIN, record_outcomes, searched_record_outcomes
from .undecided import undecided_summary

NOMINAL_ARCH = -1
"""Value of the ``arch`` column for the nominal arch (the irregular arches are 0 .. h-1)."""
DEFAULT_BOOTSTRAP = 1000
"""Default number of bootstrap resamples of a confidence band."""
DEFAULT_CONFIDENCE = 0.90
"""Default confidence level of a bootstrap band (the central 90 %: 5th to 95th percentile)."""
BOOTSTRAP_KEY = 2**32
"""Spawn key of the bootstrap's random stream, ``SeedSequence(seed, spawn_key=(BOOTSTRAP_KEY,))``:
far beyond any arch index, so it is independent of every arch's stream."""

CURVES_CSV = "curves.csv"
"""File of the stripes and fits (:meth:`RecordFragilityResult.curves`) in a study directory."""
INCREMENTAL_CSV = "incremental.csv"
"""File of the incremental view (:meth:`RecordFragilityResult.incremental`)."""


# ---------------------------------------------------------------------------------------------
# Settings
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class RecordFragilitySettings(StudySample):
    """Settings of a multiple-stripe study (module docstring).

    Parameters
    ----------
    suite : RecordSuite
        The records (:class:`archquake.ground_motion.RecordSuite`).
    levels : tuple of float
        Increasing stripe levels of the intensity measure, each > 0 [the IM's unit: g for pga and
        sa(T), m/s for pgv and arias, m for pgd].
    im : str
        Intensity measure of the stripes (:func:`archquake.ground_motion.stripe_measure`).
    nominal : CircularArch or ShapedArch
        Nominal arch (default: Oppenheim's arch); any arch with a centreline to draw irregular
        arches around.
    sample_size : int
        Number h of irregular arches (default 40), at most
        :data:`~archquake.defaults.MAX_SAMPLES`.
    epsilon : float
        epsilon of the irregular draw [eq. (1)], in [0, 1) (default 0.10); 0 makes every arch
        the nominal one.
    seed : int
        Root seed (>= 0) of the arches (arch i uses ``SeedSequence(seed, spawn_key=(i,))``, as
        in :class:`archquake.studies.fragility.FragilitySettings`) and of the bootstrap.
    bootstrap : int
        Number of bootstrap resamples of the confidence bands (>= 10).
    confidence : float
        Confidence level of the bands [-], in (0, 1).
    model : ModelSpec or str
        The dynamic model of every arch and its settings (:class:`archquake.models.ModelSpec`,
        as in :class:`~archquake.studies.fragility.FragilitySettings`; a name stands for its
        spec with the default settings; default the four-link model, restitution
        ``"computed"``). Recorded resolved for the nominal arch (the rigid blocks' time step
        chosen from it unless given; at most the records' sample spacing).
    search : {"exhaustive", "bisection", "screened"}, optional
        How each (arch, record, polarity) line of levels is searched
        (:mod:`archquake.studies.strategies`; default
        :data:`archquake.defaults.RECORD_STUDY_SEARCH` of the model: every level).
    stride : int, optional
        Levels between the coarse points of ``bisection`` and ``screened`` [-] (default
        :data:`archquake.defaults.DEFAULT_LEVEL_STRIDE`).
    description : StructureSpec, optional
        A bridge of several spans of one arch, instead of ``nominal``, as in
        :class:`~archquake.studies.fragility.FragilitySettings`: its members put one irregular
        arch on every span (:class:`~archquake.studies.arch_sample.BridgeSample`), analysed by
        the rigid blocks alone, without a four-link screen.

    Raises
    ------
    ValueError
        For a setting out of its range (the message names it).
    """

    suite: RecordSuite
    levels: tuple[float, ...]
    im: str = DEFAULT_IM
    nominal: BlockArch = field(default_factory=oppenheim)
    sample_size: int = STUDY_SAMPLE_SIZE
    epsilon: float = DEFAULT_EPSILON
    seed: int = DEFAULT_SEED
    bootstrap: int = DEFAULT_BOOTSTRAP
    confidence: float = DEFAULT_CONFIDENCE
    model: ModelSpec | str = DEFAULT_MODEL
    search: str | None = None
    stride: int | None = None
    description: Any = None

    def __post_init__(self) -> None:
        from .strategies import check_search, check_stride

        self._take_description()
        # resolved for the nominal structure (its time step), then recorded
        object.__setattr__(self, "model", model_spec(self.model).resolved(self.nominal))
        object.__setattr__(self, "search", check_search(
            RECORD_STUDY_SEARCH[self.model.name] if self.search is None else self.search))
        object.__setattr__(self, "stride", check_stride(
            DEFAULT_LEVEL_STRIDE if self.stride is None else self.stride))

        if not isinstance(self.suite, RecordSuite):
            raise ValueError(f"suite must be a RecordSuite, got {type(self.suite).__name__}")
        im = stripe_measure(self.im)
        try:
            x = np.atleast_1d(np.asarray(self.levels, dtype=float))
        except (TypeError, ValueError):
            raise ValueError(f"levels must be numbers [{im.unit}], got {self.levels!r}") from None
        if x.ndim != 1 or x.size == 0:
            raise ValueError(f"levels must be a non-empty list of {im.name} levels [{im.unit}]")
        if not np.all(np.isfinite(x)) or np.any(x <= 0):
            bad = [v for v in x.tolist() if not (math.isfinite(v) and v > 0)]
            raise ValueError(f"levels must be {im.name} values > 0 [{im.unit}] (a record cannot "
                             f"be scaled to 0), got {bad}")
        if np.any(np.diff(x) <= 0):
            raise ValueError(f"levels must increase strictly, got {x.tolist()}")
        check_integer("bootstrap", self.bootstrap, minimum=10)
        if not (isinstance(self.confidence, int | float) and 0.0 < self.confidence < 1.0):
            raise ValueError(f"confidence must be in (0, 1), got {self.confidence!r}")
        sample = self.sample  # checks nominal, epsilon, seed
        check_integer("sample_size", self.sample_size, maximum=MAX_SAMPLES)
        object.__setattr__(self, "im", im.name)
        object.__setattr__(self, "levels", tuple(float(v) for v in x))
        object.__setattr__(self, "sample_size", int(self.sample_size))
        object.__setattr__(self, "seed", sample.seed)
        object.__setattr__(self, "epsilon", sample.epsilon)
        object.__setattr__(self, "bootstrap", int(self.bootstrap))
        object.__setattr__(self, "confidence", float(self.confidence))

    @property
    def screening(self) -> ModelSpec | None:
        """The four-link model of the study's restitution that screens a model that needs one
        (a bridge has none), or None."""
        if self.description is not None:
            return None
        return self.model.screening(self.model.restitution)

    @property
    def unit(self) -> str:
        """Unit of the IM and of the levels."""
        return stripe_measure(self.im).unit

    def to_dict(self) -> dict:
        """The settings as JSON-ready data, as stored with the results.

        Returns
        -------
        dict
            Every field (the suite by :meth:`archquake.ground_motion.RecordSuite.to_dict`, the
            nominal arch by :meth:`archquake.geometry.CircularArch.to_dict`) and ``im_unit``.
        """
        model = self.model.to_dict()  # its keys stored flat, as before the spec
        return {
            "suite": self.suite.to_dict(),
            "im": self.im,
            "im_unit": self.unit,
            "levels": list(self.levels),
            **self.structure_dict(),
            "sample_size": self.sample_size,
            "epsilon": self.epsilon,
            "seed": self.seed,
            "restitution": model.pop("restitution"),
            "bootstrap": self.bootstrap,
            "confidence": self.confidence,
            "model": model.pop("model"),
            "search": self.search,
            "stride": self.stride,
            **model,
        }

    @classmethod
    def from_dict(cls, data: dict) -> RecordFragilitySettings:
        """Inverse of :meth:`to_dict` (the settings are validated again).

        Parameters
        ----------
        data : dict
            As :meth:`to_dict` writes it.

        Returns
        -------
        RecordFragilitySettings
        """
        return cls(suite=RecordSuite.from_dict(data["suite"]), levels=tuple(data["levels"]),
                   im=data["im"], **cls.structure_of(data),
                   sample_size=data["sample_size"],
                   epsilon=data.get("epsilon", data.get("tolerance")),
                   seed=data["seed"], bootstrap=data["bootstrap"],
                   confidence=data["confidence"], model=ModelSpec.from_dict(data),
                   search=data.get("search"),
                   stride=data.get("stride", DEFAULT_LEVEL_STRIDE))

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, RecordFragilitySettings):
            return NotImplemented
        return self.to_dict() == other.to_dict()

    def __hash__(self) -> int:
        # frozen, and every field an immutable value: hashed as it compares, by its to_dict
        return hash(("RecordFragilitySettings", frozen_value(self.to_dict())))


# ---------------------------------------------------------------------------------------------
# The study task (runs in the workers)
# ---------------------------------------------------------------------------------------------


def _outcomes_without_motion(n: int, status: int) -> dict[str, np.ndarray]:
    """The columns of :func:`record_outcomes` for ``n`` analyses of an arch that is not set in
    motion (status 0: it never collapses) or not analysed
    (:data:`~archquake.studies.arch_sample.STATUS_EXCLUDED`)."""
    return {"status": np.full(n, status, dtype=np.int8),
            "half_cycle": np.zeros(n, dtype=np.int16), "impacts": np.zeros(n, dtype=np.int32),
            "collapse_time": np.full(n, np.nan),
            "max_phi": np.zeros(n) if status == 0 else np.full(n, np.nan),
            "integrated": np.zeros(n, dtype=bool)}


def record_fragility_task(chunk) -> dict[str, np.ndarray]:
    """Study task (:func:`archquake.execution.run_study`): the arches of one chunk.

    ``chunk.settings`` is :meth:`RecordFragilitySettings.to_dict`; item ``i < h`` is arch ``i``
    of :attr:`RecordFragilitySettings.sample`, item ``h`` the nominal arch. An irregular arch
    that cannot be analysed is excluded (:mod:`archquake.studies.arch_sample`: its rows have
    status :data:`~archquake.studies.arch_sample.STATUS_EXCLUDED` and the reason in the column
    ``excluded``); one that never collapses is at rest at every level.

    Parameters
    ----------
    chunk : archquake.execution.Chunk
        The arches of the chunk.

    Returns
    -------
    dict of ndarray
        One row per arch, record, level and polarity (in that order), with the columns of
        :attr:`RecordFragilityResult.table`.

    Raises
    ------
    ValueError
        If a record file changed.
    archquake.errors.StudyError
        For an error of an arch other than the exclusions, naming the arch.
    """
    settings = RecordFragilitySettings.from_dict(chunk.settings)
    sample = settings.sample
    motions = settings.suite.motions(cached=True)
    factors = settings.suite.scale_factors(settings.im, settings.levels)
    levels = np.asarray(settings.levels)
    polarity = np.tile(np.array(POLARITIES, dtype=np.int8), levels.size)
    parts = []
    for item in chunk.items:
        if item < settings.sample_size:
            arch_id, label = int(item), sample.label(item)
        else:
            arch_id, label = NOMINAL_ARCH, "the nominal arch"
        try:
            screen = None
            screening = settings.screening
            if arch_id == NOMINAL_ARCH:
                excluded = ""
                if screening is None:
                    model = nominal_model(settings.nominal_structure, settings.model)
                    k = model.load_multipliers
                else:
                    screen = nominal_model(settings.nominal, screening)
                    k = screen.load_multipliers
                    model = settings.model.build(settings.nominal)
            else:
                member = sample.member(item, settings.model)
                model, excluded = member.model, member.excluded
                k = member.load_multipliers
                if model is not None and screening is not None:
                    screen = sample.member(item, screening).model
            c = getattr(model, "restitution", (math.nan, math.nan))
            searched = not settings.model.grid_in_one_call or settings.search != "exhaustive"
            for r, motion in enumerate(motions):
                signed = (factors[r][:, None] * np.array(POLARITIES, dtype=float)[None, :]).ravel()
                n = signed.size
                if model is not None and searched:
                    out = searched_record_outcomes(model, motion, factors[r],
                                                   search=settings.search,
                                                   stride=settings.stride, screen=screen)
                elif model is not None:
                    out = record_outcomes(model, motion, signed)
                else:
                    out = _outcomes_without_motion(n, STATUS_EXCLUDED if excluded else 0)
                parts.append({
                    "arch": np.full(n, arch_id, dtype=np.int64),
                    "record": np.full(n, motion.name),
                    "level": np.repeat(levels, len(POLARITIES)),
                    "polarity": polarity,
                    "scale_factor": np.abs(signed),
                    **out,
                    "k_l": np.full(n, float(k[0])), "k_r": np.full(n, float(k[1])),
                    "c_lr": np.full(n, float(c[0])), "c_rl": np.full(n, float(c[1])),
                    "excluded": np.full(n, excluded, dtype="<U16"),
                })
        except Exception as exc:
            raise study_error(label, exc) from exc
    columns = {name: np.concatenate([p[name] for p in parts]) for name in parts[0]}
    width = max(len(name) for name in columns["record"])
    columns["record"] = columns["record"].astype(f"<U{width}")
    return columns


# ---------------------------------------------------------------------------------------------
# The result
# ---------------------------------------------------------------------------------------------


def _fit_dict(fit: LognormalFragility | None) -> dict:
    if fit is None:
        return {"median": None, "dispersion": None}
    return {"median": float(fit.median), "dispersion": float(fit.dispersion)}


@dataclass(frozen=True, eq=False)
class RecordFragilityResult:
    r"""Result of :func:`run_record_fragility`.

    Attributes
    ----------
    settings : RecordFragilitySettings
        The settings of the study.
    table : pandas.DataFrame
        One row per arch, record, level and polarity: ``arch`` (0 .. h-1; -1 the nominal arch),
        ``record``, ``level`` [IM unit], ``polarity`` (+1 as recorded, -1 reversed),
        ``scale_factor`` [-], ``status`` (0 rest, 1 recovery, 2 collapse), ``half_cycle``,
        ``impacts``, ``collapse_time`` [s], ``max_phi`` [rad], ``integrated`` (False: rest
        without integrating, or not analysed), ``k_l``, ``k_r``, ``c_lr``, ``c_rl`` [-] and
        ``excluded`` ("" for an analysed arch, else why it is not:
        :data:`~archquake.studies.arch_sample.EXCLUSIONS`; its ``status`` is then
        :data:`~archquake.studies.arch_sample.STATUS_EXCLUDED`).
    records : tuple of str
        Record names, in suite order.
    levels : ndarray, shape (L,)
        Stripe levels [IM unit].
    collapsed : bool ndarray, shape (h, R, L, 2)
        Collapse of every analysed irregular arch (:attr:`arches`), record, level and polarity
        (as recorded, reversed).
    nominal_collapsed : bool ndarray, shape (R, L, 2)
        The same for the nominal arch.
    lognormal : LognormalFragility or None
        Total fit (all arch-record pairs pooled), dispersion :math:`\beta`; None if the counts
        are separated.
    nominal_lognormal : LognormalFragility or None
        Record-to-record fit (the nominal arch), dispersion :math:`\beta_{RTR}`.
    geometric : CommonDispersionFit or None
        Geometric fit (common dispersion :math:`\beta_G`, a median per record); None with
        epsilon = 0 or when it has no estimate.
    band, nominal_band : BootstrapBand or None
        Bootstrap bands of the total and nominal fits.
    metadata : dict
        Settings, seed, version, timings of the study.
    excluded : dict of int to str
        The irregular arches that were not analysed, by index, with the reason (a key of
        :data:`~archquake.studies.arch_sample.EXCLUSIONS`); they are left out of h, so the
        stripes count the :attr:`analysed` arches only.
    undecided : bool ndarray, shape (h, R, L, 2)
        Analyses the model left undecided (:attr:`archquake.status.Status.UNDECIDED`, the
        rigid-block model's), as :attr:`collapsed`. A pair undecided in a polarity and collapsing
        in neither is a survival in :attr:`probability`, the fits and the bands (the lower
        bound of P_F) and a failure in :attr:`probability_upper`
        (:mod:`archquake.studies.undecided`). None: none undecided.
    nominal_undecided : bool ndarray, shape (R, L, 2)
        The same for the nominal arch.
    """

    settings: RecordFragilitySettings
    table: pd.DataFrame = field(repr=False)
    records: tuple[str, ...] = field(repr=False)
    levels: np.ndarray = field(repr=False)
    collapsed: np.ndarray = field(repr=False)
    nominal_collapsed: np.ndarray = field(repr=False)
    lognormal: LognormalFragility | None
    nominal_lognormal: LognormalFragility | None
    geometric: CommonDispersionFit | None = field(repr=False)
    band: BootstrapBand | None = field(repr=False)
    nominal_band: BootstrapBand | None = field(repr=False)
    metadata: dict = field(repr=False, default_factory=dict)
    excluded: dict = field(default_factory=dict)
    undecided: np.ndarray | None = field(repr=False, default=None)
    nominal_undecided: np.ndarray | None = field(repr=False, default=None)

    def __post_init__(self) -> None:
        if self.undecided is None:
            object.__setattr__(self, "undecided", np.zeros_like(self.collapsed))
        if self.nominal_undecided is None:
            object.__setattr__(self, "nominal_undecided", np.zeros_like(self.nominal_collapsed))

    # ------------------------------------------------------------------ undecided
    @property
    def undecided_pairs(self) -> np.ndarray:
        """Analysed irregular arch-record pairs per stripe whose failure is undecided
        (undecided in a polarity, collapsing in neither), shape (L,)."""
        return (self.undecided.any(axis=-1) & ~self.failed).sum(axis=(0, 1))

    @property
    def probability_upper(self) -> np.ndarray:
        """Upper bound of P(collapse | IM = x_j) of the irregular arches, shape (L,) [-]: the
        pairs whose failure is undecided counted as failures; :attr:`probability` is the lower
        bound (:mod:`archquake.studies.undecided`)."""
        return (self.failures + self.undecided_pairs) / self.trials

    @property
    def nominal_probability_upper(self) -> np.ndarray:
        """Upper bound of :attr:`nominal_probability` [-], as :attr:`probability_upper`."""
        undecided = self.nominal_undecided.any(axis=-1) & ~self.nominal_failed
        return (self.nominal_failed | undecided).mean(axis=0)

    def undecided_summary(self) -> dict:
        """The count of undecided analyses, JSON-ready
        (:func:`archquake.studies.undecided.undecided_summary` of the irregular arches, and
        ``nominal_analyses``: of the nominal arch, out of ``nominal_of``)."""
        return {**undecided_summary(int(self.undecided.sum()), int(self.collapsed.size)),
                "nominal_analyses": int(self.nominal_undecided.sum()),
                "nominal_of": int(self.nominal_collapsed.size)}

    # ------------------------------------------------------------------ arches
    @property
    def analysed(self) -> int:
        """Number h of irregular arches analysed (drawn minus excluded)."""
        return self.settings.sample_size - len(self.excluded)

    @property
    def arches(self) -> np.ndarray:
        """Indices of the analysed irregular arches: the arch of each row of :attr:`collapsed`
        and :attr:`failed`."""
        return np.array([i for i in range(self.settings.sample_size) if i not in self.excluded],
                        dtype=np.int64)

    def arch_failed(self, arch: int) -> np.ndarray:
        """Failure of one arch under every record at every level (either polarity).

        Parameters
        ----------
        arch : int
            Index of an analysed irregular arch, or :data:`NOMINAL_ARCH` (-1).

        Returns
        -------
        bool ndarray, shape (R, L)

        Raises
        ------
        ValueError
            For an excluded arch or an index that is not in the study.
        """
        if arch == NOMINAL_ARCH:
            return self.nominal_failed
        if arch in self.excluded:
            raise ValueError(f"arch {arch} was excluded ({self.excluded[arch]}): it has no "
                             f"outcomes")
        rows = np.flatnonzero(self.arches == arch)
        if rows.size == 0:
            raise ValueError(f"arch must be {NOMINAL_ARCH} (the nominal arch) or an irregular "
                             f"arch in [0, {self.settings.sample_size}), got {arch!r}")
        return self.failed[rows[0]]

    # ------------------------------------------------------------------ stripes
    @property
    def failed(self) -> np.ndarray:
        """Failure of every analysed irregular arch-record pair at every level (either
        polarity), shape (h, R, L)."""
        return self.collapsed.any(axis=-1)

    @property
    def nominal_failed(self) -> np.ndarray:
        """Failure of the nominal arch under every record at every level, shape (R, L)."""
        return self.nominal_collapsed.any(axis=-1)

    @property
    def trials(self) -> int:
        """Arch-record pairs per stripe, h R."""
        return int(self.collapsed.shape[0] * self.collapsed.shape[1])

    @property
    def failures(self) -> np.ndarray:
        """Failing arch-record pairs per stripe, shape (L,)."""
        return self.failed.sum(axis=(0, 1))

    @property
    def probability(self) -> np.ndarray:
        """P(collapse | IM = x_j) of the irregular arches, shape (L,) [-]."""
        return self.failures / self.trials

    def probability_of_polarity(self, polarity: int) -> np.ndarray:
        """P(collapse | IM = x_j) [-] of the irregular arches with the records in one polarity
        only, shape (L,).

        Parameters
        ----------
        polarity : {1, -1}
            +1 as recorded, -1 reversed.

        Returns
        -------
        ndarray

        Raises
        ------
        ValueError
            For another polarity.
        """
        k = POLARITIES.index(polarity)
        return self.collapsed[..., k].mean(axis=(0, 1))

    @property
    def nominal_probability(self) -> np.ndarray:
        """Fraction of the records that collapse the nominal arch at each level [-]."""
        return self.nominal_failed.mean(axis=0)

    # ------------------------------------------------------------------ variability
    @property
    def geometric_dispersion(self) -> float | None:
        """beta_G [-] (0 when every arch is the nominal one; None when it has no estimate)."""
        if self.settings.epsilon == 0.0:
            return 0.0
        return None if self.geometric is None else self.geometric.dispersion

    def variability(self) -> dict:
        r"""The three dispersions [-] (module docstring) and their square-root sum of squares.

        Returns
        -------
        dict
            ``record_to_record`` (:math:`\beta_{RTR}`), ``geometric`` (:math:`\beta_G`),
            ``total`` (:math:`\beta`), ``srss``
            (:math:`\sqrt{\beta_{RTR}^2 + \beta_G^2}`, to compare with the total), each None
            without an estimate; ``geometric_records_used`` and the ``definitions`` in words.
        """
        rtr = None if self.nominal_lognormal is None else self.nominal_lognormal.dispersion
        total = None if self.lognormal is None else self.lognormal.dispersion
        return {
            **dispersions(rtr, self.geometric_dispersion, total),
            "geometric_records_used": (0 if self.geometric is None
                                       else int(self.geometric.records.size)),
            "definitions": dict(DISPERSIONS),
        }

    # ------------------------------------------------------------------ views
    def incremental(self) -> pd.DataFrame:
        """For every arch and record: the lowest level that collapses the pair (either polarity)
        and the levels above it at which the arch survives again.

        Returns
        -------
        pandas.DataFrame
            ``arch`` (-1: nominal), ``record``, ``first_collapse`` [IM unit] (nan: none),
            ``recoveries_above`` (count), ``recovery_levels`` (space-separated levels).
        """
        rows = []
        blocks = [(int(a), self.failed[row]) for row, a in enumerate(self.arches)]
        blocks.append((NOMINAL_ARCH, self.nominal_failed))
        for arch, failed in blocks:
            for r, name in enumerate(self.records):
                hit = np.flatnonzero(failed[r])
                first = math.nan
                recovered = np.zeros(0)
                if hit.size:
                    first = float(self.levels[hit[0]])
                    above = np.arange(hit[0] + 1, self.levels.size)
                    recovered = self.levels[above[~failed[r, above]]]
                rows.append({"arch": arch, "record": name, "first_collapse": first,
                             "recoveries_above": int(recovered.size),
                             "recovery_levels": " ".join(f"{v:g}" for v in recovered)})
        return pd.DataFrame(rows)

    def curves(self) -> pd.DataFrame:
        """The stripes and fits as a table, one row per level.

        Returns
        -------
        pandas.DataFrame
            ``level`` [the IM's unit], ``trials``, ``failures``, ``probability``,
            ``probability_as_recorded``, ``probability_reversed``, ``lognormal_fit``,
            ``band_lower``, ``band_upper`` (the bootstrap band, interpolated in ``ln x``),
            ``nominal_records``, ``nominal_failures``, ``nominal_probability``,
            ``nominal_lognormal_fit``, ``undecided`` (:attr:`undecided_pairs`),
            ``probability_upper`` and ``nominal_probability_upper`` (the upper bounds of P_F
            with undecided analyses; the probabilities are the lower bounds) [-]; nan where a
            fit or band does not exist.
        """
        x = self.levels

        def fitted(fit):
            return np.full(x.size, np.nan) if fit is None else fit(x)

        def band(b, which):
            if b is None:
                return np.full(x.size, np.nan)
            return np.interp(np.log(x), np.log(b.x), getattr(b, which))

        return pd.DataFrame({
            "level": x, "trials": self.trials, "failures": self.failures,
            "probability": self.probability,
            "probability_as_recorded": self.probability_of_polarity(1),
            "probability_reversed": self.probability_of_polarity(-1),
            "lognormal_fit": fitted(self.lognormal),
            "band_lower": band(self.band, "lower"), "band_upper": band(self.band, "upper"),
            "nominal_records": len(self.records),
            "nominal_failures": self.nominal_failed.sum(axis=0),
            "nominal_probability": self.nominal_probability,
            "nominal_lognormal_fit": fitted(self.nominal_lognormal),
            "undecided": self.undecided_pairs,
            "probability_upper": self.probability_upper,
            "nominal_probability_upper": self.nominal_probability_upper,
        })

    def export_nrml(self, path: str | os.PathLike, *, taxonomy: str | None = None) -> Path:
        """Write the fitted fragility functions as an OpenQuake NRML fragility model
        (:func:`archquake.results_io.write_fragility_nrml`), limit state ``collapse``, in the
        study's intensity measure (OpenQuake's units): ``taxonomy`` is the total fit of the
        irregular arches, ``taxonomy + "-nominal"`` the nominal arch's fit.

        Parameters
        ----------
        path : str or os.PathLike
            The XML file.
        taxonomy : str, optional
            Id of the total fit (OpenQuake's taxonomy; default ``"masonry-arch"``, or
            ``"masonry-bridge"`` for a study of bridges).

        Returns
        -------
        pathlib.Path
            ``path``.

        Raises
        ------
        ValueError
            If neither fit exists, or the IM has no OpenQuake counterpart.
        """
        from .._version import __version__
        from ..results_io import write_fragility_nrml

        one, many = self.settings.member_nouns
        taxonomy = f"masonry-{one}" if taxonomy is None else taxonomy
        functions = []
        if self.lognormal is not None:
            functions.append((taxonomy, self.lognormal.median, self.lognormal.dispersion))
        if self.nominal_lognormal is not None:
            functions.append((f"{taxonomy}-nominal", self.nominal_lognormal.median,
                              self.nominal_lognormal.dispersion))
        if not functions:
            raise ValueError("no fragility function to export: the stripes admit no lognormal "
                             "fit (no collapse, no survival, or a single step between two "
                             "levels); widen or refine the levels")
        s = self.settings
        description = (f"archquake {__version__}: collapse of masonry {many}, lognormal fits by "
                       f"maximum likelihood to multiple stripes of {s.im} "
                       f"({self.levels[0]:g} to {self.levels[-1]:g} {s.unit}), "
                       f"{len(self.records)} records x 2 polarities; '{taxonomy}': "
                       f"{self.analysed} irregular {many} (epsilon {s.epsilon:g}, seed "
                       f"{s.seed}); "
                       f"'{taxonomy}-nominal': the nominal {one}")
        caveat = self.search_summary()["caveat"]
        if caveat:  # the curves may miss collapses the search did not analyse
            description += f"; {caveat}"
        return write_fragility_nrml(path, functions, im=s.im, min_iml=float(self.levels[0]),
                                    max_iml=float(self.levels[-1]), description=description)

    def summary(self) -> dict:
        """JSON-ready summary: IM, levels, stripes, fits, bands, variability, incremental view,
        the arches drawn, analysed and excluded (``arches``, by reason:
        :data:`~archquake.studies.arch_sample.EXCLUSIONS`), and the undecided analyses
        (``undecided``: :meth:`undecided_summary`; ``probability_upper``, of the irregular and
        of the nominal arch: the upper bounds of the probabilities, equal to them when none is
        undecided).

        Returns
        -------
        dict
            What ``summary.json`` of the study holds under ``summary`` (levels in the IM's
            unit, probabilities and dispersions [-]); ``analyses`` counts the analyses of the
            analysed arches (the nominal one included).
        """
        incremental = self.incremental()
        sample = incremental[incremental["arch"] != NOMINAL_ARCH]
        total = _fit_dict(self.lognormal)
        total["band"] = None if self.band is None else self.band.to_dict()
        nominal = _fit_dict(self.nominal_lognormal)
        nominal["band"] = None if self.nominal_band is None else self.nominal_band.to_dict()
        analysed = ~self.table["arch"].isin(list(self.excluded)).to_numpy()
        integrated = self.table["integrated"].to_numpy()[analysed]
        return {
            "im": self.settings.im,
            "im_unit": self.settings.unit,
            "levels": self.levels.tolist(),
            "records": list(self.records),
            "sample_size": self.settings.sample_size,
            "arches": exclusion_summary(self.settings.sample_size, self.excluded),
            "trials": self.trials,
            "failures": self.failures.tolist(),
            "probability": self.probability.tolist(),
            "probability_as_recorded": self.probability_of_polarity(1).tolist(),
            "probability_reversed": self.probability_of_polarity(-1).tolist(),
            "probability_upper": self.probability_upper.tolist(),
            "undecided": self.undecided_summary(),
            "lognormal": total,
            "nominal": {"probability": self.nominal_probability.tolist(),
                        "probability_upper": self.nominal_probability_upper.tolist(),
                        "lognormal": nominal},
            "variability": self.variability(),
            "incremental": {
                "pairs": int(len(sample)),
                "pairs_collapsing": int(np.isfinite(sample["first_collapse"]).sum()),
                "pairs_recovering_above_first_collapse": int((sample["recoveries_above"] > 0)
                                                             .sum()),
            },
            "analyses": {"total": int(integrated.size), "integrated": int(integrated.sum()),
                         "at_rest_without_integration": int((~integrated).sum())},
            "search": self.search_summary(),
            "settings": self.settings.to_dict(),
            "seed": self.settings.seed,
        }

    def search_summary(self) -> dict:
        """How the study searched its lines of levels: ``strategy`` and ``stride``, the
        ``grid_points`` (arch, record, level, polarity) of the arches analysed dynamically
        (the nominal one included; the arches excluded, and those that never collapse, have
        no search), of them ``not_analysed``: those whose outcome a search inferred without
        integrating (0 for a study that integrates every level), and, for ``bisection``, the
        ``caveat`` every output of the study says
        (:func:`archquake.studies.strategies.search_caveat`; None otherwise).

        Returns
        -------
        dict
        """
        from .strategies import search_caveat

        s, table = self.settings, self.table
        searched = ((table["excluded"].to_numpy() == "")
                    & np.isfinite(table["k_l"].to_numpy(dtype=float)))
        points = int(searched.sum())
        skipped = 0
        if not (s.model.grid_in_one_call and s.search == "exhaustive"):
            skipped = int(np.count_nonzero(~table["integrated"].to_numpy(dtype=bool)[searched]))
        return {"strategy": s.search, "stride": s.stride, "grid_points": points,
                "not_analysed": skipped,
                "caveat": search_caveat(s.search, skipped, points, s.stride)}


def _study_arrays(table: pd.DataFrame, settings: RecordFragilitySettings):
    """``status[arch, record, level, polarity]`` (irregular arches, then the nominal one)."""
    h, r, n_levels = settings.sample_size, len(settings.suite), len(settings.levels)
    shape = (h + 1, r, n_levels, len(POLARITIES))
    expected = math.prod(shape)
    if len(table) != expected:
        raise ValueError(f"the study table has {len(table)} rows, expected {expected}")
    arch = table["arch"].to_numpy().reshape(shape)
    record = table["record"].to_numpy().astype(str).reshape(shape)
    level = table["level"].to_numpy().reshape(shape)
    polarity = table["polarity"].to_numpy().reshape(shape)
    arch_ids = np.append(np.arange(h), NOMINAL_ARCH)
    if (np.any(arch != arch_ids[:, None, None, None])
            or np.any(record != np.array(settings.suite.names)[None, :, None, None])
            or np.any(level != np.asarray(settings.levels)[None, None, :, None])
            or np.any(polarity != np.array(POLARITIES)[None, None, None, :])):
        raise ValueError("the study table is not ordered by arch, record, level, polarity as the "
                         "record fragility task writes it")
    return table["status"].to_numpy().reshape(shape)


def record_fragility_result(settings: RecordFragilitySettings, table: pd.DataFrame,
                            metadata: dict | None = None) -> RecordFragilityResult:
    """Assemble a :class:`RecordFragilityResult` (stripes, fits, bands) from the study table.

    The bootstrap draws from ``SeedSequence(settings.seed, spawn_key=(BOOTSTRAP_KEY,))`` (one
    child stream for the total band, one for the nominal band), so the same table gives the
    same bands. The excluded irregular arches (column ``excluded``) are left out of the stripes.
    A pair whose analyses are undecided (and collapse in neither polarity) counts as a survival
    in the stripes and the fits (the lower bound of P_F) and as a failure in
    :attr:`RecordFragilityResult.probability_upper` (:mod:`archquake.studies.undecided`).

    Parameters
    ----------
    settings : RecordFragilitySettings
        The settings of the study.
    table : pandas.DataFrame
        The rows of :func:`record_fragility_task`, in its order (a table written before the
        column ``excluded`` existed has no excluded arch).
    metadata : dict, optional
        Metadata of the study.

    Returns
    -------
    RecordFragilityResult

    Raises
    ------
    ValueError
        If the table does not match the settings, or every irregular arch was excluded.
    """
    status = _study_arrays(table, settings)
    excluded = excluded_arches(table)
    check_analysed(settings.sample_size, excluded, settings.epsilon)
    keep = np.array([i not in excluded for i in range(settings.sample_size)], dtype=bool)
    collapsed, undecided = status == Status.COLLAPSE, status == Status.UNDECIDED
    sample, nominal = collapsed[:-1][keep], collapsed[-1]
    levels = np.asarray(settings.levels)
    failed = sample.any(axis=-1)
    nominal_failed = nominal.any(axis=-1)
    h, r = failed.shape[:2]
    total = fit_lognormal_or_none(levels, h * r, failed.sum(axis=(0, 1)))
    nominal_fit = fit_lognormal_or_none(levels, r, nominal_failed.sum(axis=0))
    geometric = None
    if settings.epsilon > 0.0:
        geometric = common_dispersion_fit(levels, h, failed.sum(axis=0))
    root = np.random.SeedSequence(settings.seed, spawn_key=(BOOTSTRAP_KEY,))
    total_stream, nominal_stream = (np.random.default_rng(s) for s in root.spawn(2))
    options = {"resamples": settings.bootstrap, "confidence": settings.confidence}
    band = None if total is None else bootstrap_lognormal(levels, failed, total,
                                                          rng=total_stream, **options)
    nominal_band = None if nominal_fit is None else bootstrap_lognormal(
        levels, nominal_failed, nominal_fit, rng=nominal_stream, **options)
    return RecordFragilityResult(
        settings=settings, table=table, records=settings.suite.names, levels=levels,
        collapsed=sample, nominal_collapsed=nominal, lognormal=total,
        nominal_lognormal=nominal_fit, geometric=geometric, band=band, nominal_band=nominal_band,
        metadata=dict(metadata or {}), excluded=excluded, undecided=undecided[:-1][keep],
        nominal_undecided=undecided[-1])



# ---------------------------------------------------------------------------------------------
# Running, saving, loading
# ---------------------------------------------------------------------------------------------


def warm_up() -> None:
    """Load the compiled engine in this process (a pool's ``warm_up``): one arch, one short
    record, two levels."""
    from ..ground_motion import stochastic_motion

    motion = stochastic_motion(0.5, 2.0, 1.0, 2.0, 0.0, 0.2, duration=2.0, rng=0)
    record_outcomes(nominal_model(oppenheim()), motion, [0.5, -3.0])


def _engines():
    """What a pool warmed up by :func:`warm_up` compiles: the four-link engine."""
    from ..models import ModelSpec

    return ModelSpec("four-link").engines()


warm_up.engines = _engines  # (archquake.compiled)


def _check_resume(out: Path, settings: RecordFragilitySettings) -> None:
    """Refuse to resume a study whose record files differ from the stored ones, naming them,
    or whose saved chunks have no column ``excluded`` (written before arches could be
    excluded: they cannot be joined with new chunks)."""
    from ..execution import CHUNK_DIR, resumable_study

    saved = resumable_study(out)
    if saved is None:  # no study started there: nothing to compare
        return
    columns = saved.chunk_columns()  # None: no chunk yet, or a damaged one run_study recomputes
    if columns is not None and "excluded" not in columns:
        raise ValueError(f"cannot resume the study in {out}: its saved chunks were written "
                         f"by an earlier version of archquake, whose table has no column "
                         f"'excluded'; start the study again in another directory (or "
                         f"delete {out / CHUNK_DIR})")
    stored = saved.record.get("settings", {}).get("suite")
    if not isinstance(stored, dict):
        return
    new = settings.suite.to_dict()
    if stored.get("kind") != new["kind"]:
        raise ValueError(f"cannot resume the study in {out}: it was run on a {stored.get('kind')} "
                         f"suite, this one is a {new['kind']} suite")
    if new["kind"] != "files":
        return
    old_names = [r["name"] for r in stored["records"]]
    new_names = [r["name"] for r in new["records"]]
    if old_names != new_names:
        missing = sorted(set(old_names) - set(new_names))
        extra = sorted(set(new_names) - set(old_names))
        raise ValueError(f"cannot resume the study in {out}: its records were {old_names}; "
                         f"missing now: {missing}, new: {extra}")
    for old, cur in zip(stored["records"], new["records"], strict=True):
        if old["sha256"] != cur["sha256"]:
            raise ValueError(f"cannot resume the study in {out}: record file '{cur['path']}' has "
                             f"changed since the study started (sha256 {cur['sha256'][:12]}... "
                             f"instead of {old['sha256'][:12]}...); restore it or start a new "
                             f"study in another directory")
        if old["path"] != cur["path"]:
            raise ValueError(f"cannot resume the study in {out}: record {cur['name']!r} was read "
                             f"from '{old['path']}', now from '{cur['path']}'")


def run_record_fragility(
    settings: RecordFragilitySettings,
    out_dir: str | os.PathLike | None = None,
    *,
    backend: str | None = None,
    workers: int | None = None,
    scheduler: Any = None,
    pool: Any = None,
    resume: bool = False,
    progress: bool = True,
    chunk_size: int = 1,
) -> RecordFragilityResult:
    """Multiple-stripe fragility study of irregular arches under a record suite (module
    docstring).

    Parameters
    ----------
    settings : RecordFragilitySettings
        What to compute.
    out_dir : str or os.PathLike, optional
        Study directory (new or empty unless ``resume``): ``study.json`` and ``chunks/``
        (checkpoints), ``results.parquet`` / ``results.csv`` (the table), ``curves.csv``,
        ``incremental.csv`` and ``summary.json`` (metadata and
        :meth:`RecordFragilityResult.summary`).
    backend : {"serial", "processes", "dask"}, optional
        How the chunks run (:func:`archquake.execution.run_study`); default
        :func:`archquake.execution.default_backend`.
    workers : int, optional
        Local processes (default: the number of CPUs). Without an explicit ``backend``, a
        study whose estimated work is shorter than what the workers would save once started
        runs in this process instead (:func:`archquake.studies.strategies.pool_pays`); its
        metadata say ``"serial"``.
    scheduler : str or distributed.Client, optional
        Dask scheduler address ``tcp://HOST:PORT`` or a client.
    pool : concurrent.futures.Executor, optional
        Running worker processes (:func:`archquake.execution.process_pool`) for ``"processes"``.
    resume : bool
        Continue the study saved in ``out_dir`` (same settings and record files required).
    progress : bool
        Progress bar on stderr.
    chunk_size : int
        Arches per chunk.

    Returns
    -------
    RecordFragilityResult

    Raises
    ------
    ValueError
        For invalid settings or execution options, a record that cannot be read or scaled
        (IM = 0), changed record files on resume, a nominal arch that cannot be analysed, every
        irregular arch excluded, or an output directory that is not empty (without ``resume``)
        or holds another study.
    archquake.errors.StudyError
        If an arch fails for a reason other than the exclusions (naming it), or the Dask
        cluster can no longer finish the study (:func:`archquake.execution.run_study`).
    """
    from ..compiled import announce_all
    from ..execution import StudyPlan, run_study
    from ..results_io import atomic_path, save_study, write_csv
    from .strategies import study_seconds, workers_that_pay

    if not isinstance(settings, RecordFragilitySettings):
        raise ValueError(f"settings must be RecordFragilitySettings, got "
                         f"{type(settings).__name__}")
    # read every record and its IM here, so that a bad file or a level that would scale a
    # record beyond any acceleration analysed stops the study before it starts
    settings.suite.scale_factors(settings.im, settings.levels)
    check_nominal(settings.nominal_structure, settings.model)
    announce_all(settings.engines())  # compiled here or by workers: said here, once
    for motion in settings.suite.motions(cached=True):  # a step that cannot follow a record
        settings.model.check_motion(settings.nominal, motion)  # refused before any analysis
    out = None if out_dir is None else Path(out_dir)
    if resume and out is not None:
        _check_resume(out, settings)
    plan = StudyPlan(settings.to_dict(), settings.seed, settings.sample_size + 1,
                     check_integer("chunk_size", chunk_size))
    arches = settings.sample_size + 1  # and the nominal arch
    analyses = arches * len(settings.suite) * len(settings.levels) * 2
    blocks = None if settings.description is None else settings.nominal.n_blocks
    workers = workers_that_pay(study_seconds(settings.model.name, "record", arches, analyses,
                                             blocks),
                               workers, backend=backend, scheduler=scheduler, pool=pool)
    table = run_study(record_fragility_task, plan, out, backend=backend, workers=workers,
                      scheduler=scheduler, pool=pool, resume=resume, progress=progress,
                      save=False)  # saved below, with the summary
    metadata = dict(table.attrs.get("study", {}))
    result = record_fragility_result(settings, table, metadata)
    if out is not None:
        with atomic_path(out / CURVES_CSV) as tmp:
            result.curves().to_csv(tmp, index=False)
        write_csv(out / INCREMENTAL_CSV, result.incremental())  # record names: never formulas
        save_study(out, table, metadata=metadata, summary=result.summary())
    return result


def load_record_fragility(out_dir: str | os.PathLike) -> RecordFragilityResult:
    """Reload a finished study (:func:`run_record_fragility` with ``out_dir``); the fits and
    bands are recomputed from the table (same seed, so the same numbers).

    Parameters
    ----------
    out_dir : str or os.PathLike
        The study directory.

    Returns
    -------
    RecordFragilityResult

    Raises
    ------
    ValueError
        If the directory holds no complete study, or not a record fragility study.
    """
    from ..results_io import load_study

    out = Path(out_dir)
    stored = load_study(out)
    try:
        settings = RecordFragilitySettings.from_dict(stored.summary["settings"])
    except (KeyError, TypeError) as exc:
        raise ValueError(f"{out} does not hold a record fragility study (no settings in its "
                         f"summary)") from exc
    return record_fragility_result(settings, stored.table, stored.metadata)


# ---------------------------------------------------------------------------------------------
# Oppenheim's arch against a synthetic suite (for the report and the gallery)
# ---------------------------------------------------------------------------------------------

STOCHASTIC_SUITE = {"significant_duration": 10.0, "midpoint_time": 6.0, "filter_frequency": 1.5,
                    "filter_frequency_rate": -0.05, "duration": 20.0}
"""Parameters of :func:`archquake.ground_motion.stochastic_suite` of the default synthetic suite:
20-s records at 0.01 s, D5-95 = 10 s, 1.5 Hz at mid-record falling by 0.05 Hz/s (a soft-site
or near-fault content; Oppenheim's arch, R = 10 m, hardly moves under the default 5 Hz motions
of the model). The records are scaled to each stripe, so their Arias intensity does not matter."""

DEFAULT_LEVELS = {"pga": tuple(np.round(0.1 * np.arange(1, 21), 10)),
                  "pgv": tuple(np.round(0.2 * np.arange(1, 21), 10))}
"""Stripe levels of :func:`oppenheim_record_fragility`: PGA 0.1-2.0 g and PGV 0.2-4.0 m/s in
20 steps, from below the activation of the arch (k = 0.37) to most records collapsing it."""


def oppenheim_record_fragility(ims=("pga", "pgv"), *, records: int = 20, sample_size: int = 40,
                               epsilon: float = 0.10, seed: int = 0, levels=None,
                               suite_seed: int = 0, suite_parameters=None,
                               bootstrap: int = DEFAULT_BOOTSTRAP, backend: str = "serial",
                               workers: int | None = None, pool: Any = None,
                               out_dir: str | os.PathLike | None = None,
                               progress: bool = False) -> dict[str, RecordFragilityResult]:
    """Record-based fragility of Oppenheim's arch and of its irregular sample, against a seeded
    synthetic suite (no files needed), in each intensity measure of ``ims``.

    Parameters
    ----------
    ims : sequence of str
        Intensity measures of the stripes (default PGA [g] and PGV [m/s]).
    records : int
        Records of the suite (:data:`STOCHASTIC_SUITE`, ``stochastic_suite(records,
        seed=suite_seed)``).
    sample_size, epsilon, seed : int, float, int
        h irregular arches drawn with epsilon ``epsilon`` [eq. (1)] from ``seed``.
    levels : dict, optional
        ``{im: levels}`` [the IM's unit]; default :data:`DEFAULT_LEVELS` (an IM without default
        needs its levels here).
    suite_seed : int
        Seed of the synthetic suite.
    suite_parameters : dict, optional
        Parameters of the suite replacing :data:`STOCHASTIC_SUITE`.
    bootstrap : int
        Bootstrap resamples of the bands.
    backend, workers, pool
        How the studies run (:func:`run_record_fragility`); with ``"processes"`` and no pool,
        one pool of warm workers serves every IM.
    out_dir : str or os.PathLike, optional
        If given, each study is saved in ``out_dir/<im>`` (``sa(T)`` as ``sa_T``).
    progress : bool
        Progress bars.

    Returns
    -------
    dict
        ``{im: RecordFragilityResult}``.

    Raises
    ------
    ValueError
        For an invalid setting, or an IM without default levels and none given.
    """
    from ..execution import process_pool

    suite = RecordSuite.from_stochastic(records, seed=suite_seed,
                                        **(suite_parameters or STOCHASTIC_SUITE))
    levels = {**DEFAULT_LEVELS, **(levels or {})}
    settings = {}
    for name in ims:
        im = stripe_measure(name)
        if im.name not in levels:
            raise ValueError(f"no default levels for {im.name!r}: give levels={{{im.name!r}: "
                             f"[...]}} [{im.unit}]")
        settings[im.name] = RecordFragilitySettings(
            suite=suite, levels=tuple(levels[im.name]), im=im.name, sample_size=sample_size,
            epsilon=epsilon, seed=seed, bootstrap=bootstrap)

    def run_all(**options):
        results = {}
        for name, s in settings.items():
            out = None if out_dir is None else Path(out_dir) / name.replace("(", "_").rstrip(")")
            results[name] = run_record_fragility(s, out, progress=progress, **options)
        return results

    if backend == "processes" and pool is None:
        with process_pool(workers, warm_up=warm_up) as own:
            return run_all(backend="processes", pool=own)
    return run_all(backend=backend, workers=workers, pool=pool)


__all__ = [
    "BOOTSTRAP_KEY", "CURVES_CSV", "DEFAULT_BOOTSTRAP", "DEFAULT_CONFIDENCE", "DEFAULT_LEVELS",
    "INCREMENTAL_CSV", "NOMINAL_ARCH", "POLARITIES", "REST_MARGIN", "STOCHASTIC_SUITE",
    "RecordFragilityResult", "RecordFragilitySettings", "RecordSuite", "load_record_fragility",
    "oppenheim_record_fragility", "record_fragility_result", "record_fragility_task",
    "record_outcomes", "run_record_fragility", "searched_record_outcomes", "stripe_measure",
    "warm_up",
]
