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

(:func:`archquake.studies.fragility.fit_lognormal`; none exists for separated counts,
:func:`separated`). Three dispersions are reported:

record-to-record, :math:`\beta_{RTR}`
    the fit to the nominal arch's stripes (``n_j = R`` records): how the collapse level of one
    geometry varies from record to record.
geometric, :math:`\beta_G`
    the irregular arches' spread for the same records: the joint maximum-likelihood fit of
    :math:`P_r(x) = \Phi(\ln(x/\theta_r)/\beta_G)` with one median :math:`\theta_r` per record
    and one common dispersion, to the counts ``z_{r,j} = sum_a y[a, r, j]`` of ``n = h`` arches
    (:func:`common_dispersion_fit`). Records that collapse no arch, or every arch, at every level
    carry no information on it and are left out. It also absorbs the non-monotone response of a
    record (an arch that recovers at a level above one that collapses it). With
    :math:`\varepsilon = 0` every arch is the nominal one and :math:`\beta_G = 0` by definition.
total, :math:`\beta`
    everything pooled: the fit to ``z_j`` of all ``h R`` arch-record pairs; its median and
    dispersion are *the* fragility function of the study (``"lognormal"`` in the summary). If
    the two sources were independent lognormal factors of the collapse level,
    :math:`\beta^2 \approx \beta_{RTR}^2 + \beta_G^2` (reported as ``"srss"`` beside it).

The confidence band of a fit is a percentile bootstrap (ch. 13 of [2]_): the arches and the
records are resampled with replacement (both, for the sample; the records, for the nominal
arch), the counts rebuilt from the resampled pairs and refitted (:func:`bootstrap_lognormal`;
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
arch, the ``h`` irregular arches first (arch ``i`` drawn from ``SeedSequence(seed,
spawn_key=(i,))``, i.e. arch ``i`` of :func:`archquake.geometry.irregular_sample` and of the pulse
study), then the nominal arch (``arch = -1`` in the table). Chunks of arches run serially, on local
processes or on Dask, are checkpointed and resumable, and the results do not depend on how they
were run. The workers read the records from their files (so on a Dask cluster the files must be at
the same paths on every worker); the settings hold each file's name and SHA-256 digest, a worker
refuses a file whose content changed, and a resume with changed files is refused.

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

import functools
import hashlib
import json
import math
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from ..defaults import DEFAULT_RESTITUTION
from ..fourlink.dynamics import ArchDynamics
from ..geometry import GRAVITY, BlockArch, irregular_arch
from .fragility import (
    LognormalFragility,
    default_nominal,
    fit_lognormal,
    nominal_dict,
    nominal_from_dict,
    positive_int,
)

NOMINAL_ARCH = -1
"""Value of the ``arch`` column for the nominal arch (the irregular arches are 0 .. h-1)."""
POLARITIES = (1, -1)
"""Polarities of a record: +1 as recorded, -1 reversed (``GroundMotion.reversed()``)."""
DEFAULT_BOOTSTRAP = 1000
"""Default number of bootstrap resamples of a confidence band."""
DEFAULT_CONFIDENCE = 0.90
"""Default confidence level of a bootstrap band (the central 90 %: 5th to 95th percentile)."""
BOOTSTRAP_KEY = 2**32
"""Spawn key of the bootstrap's random stream, ``SeedSequence(seed, spawn_key=(BOOTSTRAP_KEY,))``:
far beyond any arch index, so it is independent of every arch's stream."""
REST_MARGIN = 1e-12
"""Relative margin [-] below the activation acceleration within which an analysis is integrated
rather than declared at rest (round-off of the interpolation between samples)."""
BAND_POINTS = 200
"""IM values (log-spaced over the levels) at which a band is evaluated."""

CURVES_CSV = "curves.csv"
"""File of the stripes and fits (:meth:`RecordFragilityResult.curves`) in a study directory."""
INCREMENTAL_CSV = "incremental.csv"
"""File of the incremental view (:meth:`RecordFragilityResult.incremental`)."""


# ---------------------------------------------------------------------------------------------
# The record suite of a study
# ---------------------------------------------------------------------------------------------


def file_digest(path: str | os.PathLike) -> str:
    """SHA-256 digest of a file's content.

    Parameters
    ----------
    path : str or os.PathLike
        The file.

    Returns
    -------
    str
        The digest in hexadecimal (64 characters).

    Raises
    ------
    OSError
        If the file cannot be read.
    """
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


@dataclass(frozen=True)
class RecordFile:
    """One record file of a suite.

    Attributes
    ----------
    name : str
        The record's name (its file name), as in the table.
    path : str
        Absolute path of the file.
    file_format : str
        Key of :data:`archquake.ground_motion.RECORD_FORMATS`.
    sha256 : str
        SHA-256 digest of the file's content.
    """

    name: str
    path: str
    file_format: str
    sha256: str


@dataclass(frozen=True, eq=False)
class RecordSuite:
    """Where the records of a study come from: files, or the seeded stochastic model.

    Build it with :meth:`from_paths` or :meth:`from_stochastic`; a study stores it in its settings
    (:meth:`to_dict`) and every worker rebuilds the motions from it (:meth:`motions`).

    Attributes
    ----------
    files : tuple of RecordFile
        The record files, sorted by name (empty for a stochastic suite).
    stochastic : dict or None
        ``{"count": n, "seed": s, "parameters": {...}}`` of
        :func:`archquake.ground_motion.stochastic_suite` (None for files).
    """

    files: tuple[RecordFile, ...] = ()
    stochastic: dict | None = None

    def __post_init__(self) -> None:
        if bool(self.files) == (self.stochastic is not None):
            raise ValueError("a record suite is either files or a stochastic suite (one of them)")

    @classmethod
    def from_paths(cls, paths) -> RecordSuite:
        """The records of folders and files, as :func:`archquake.ground_motion.read_suite` reads
        them (a folder stands for its files with a record extension; sorted by file name).

        Every file is read once here, so a bad file is reported (naming it) before a study starts.

        Parameters
        ----------
        paths : str, os.PathLike or sequence of them
            Record files and folders (:func:`archquake.ground_motion.read_suite`).

        Returns
        -------
        RecordSuite

        Raises
        ------
        ValueError
            If a file cannot be read as a record (the message names it), or there is none.
        """
        from ..ground_motion import read_suite
        from ..ground_motion.records import record_format, suite_files

        motions = read_suite(paths)  # validates every file; names and order of the suite
        found = {}
        for path, fmt in suite_files(paths):
            found.setdefault(path.name, (path, fmt))
        files = []
        for motion in motions:
            path, fmt = found[motion.name]
            files.append(RecordFile(motion.name, str(path.resolve()), fmt or record_format(path),
                                    file_digest(path)))
        return cls(files=tuple(files))

    @classmethod
    def from_stochastic(cls, count: int, seed: int = 0, **parameters) -> RecordSuite:
        """``count`` motions of :func:`archquake.ground_motion.stochastic_suite`; no files are
        needed.

        Parameters
        ----------
        count : int
            Number of motions, >= 1.
        seed : int
            Seed of the suite, >= 0.
        **parameters
            Model parameters [SI units, see :func:`~archquake.ground_motion.stochastic_motion`]
            (checked here by drawing one motion).

        Returns
        -------
        RecordSuite

        Raises
        ------
        ValueError
            For an invalid count, seed or parameter.
        """
        from ..ground_motion import stochastic_suite

        positive_int("count", count)
        positive_int("seed", seed, minimum=0)
        spec = {"count": int(count), "seed": int(seed),
                "parameters": json.loads(json.dumps(parameters))}
        stochastic_suite(1, seed=spec["seed"], **spec["parameters"])  # check the parameters now
        return cls(stochastic=spec)

    @property
    def kind(self) -> str:
        """``"files"`` or ``"stochastic"``."""
        return "files" if self.files else "stochastic"

    @property
    def names(self) -> tuple[str, ...]:
        """Names of the records, in suite order."""
        if self.files:
            return tuple(f.name for f in self.files)
        count = self.stochastic["count"]
        width = max(3, len(str(count - 1)))
        return tuple(f"stochastic-{i:0{width}d}" for i in range(count))

    def __len__(self) -> int:
        return len(self.files) if self.files else int(self.stochastic["count"])

    def motions(self) -> list:
        """The ground motions of the suite.

        Returns
        -------
        list of GroundMotion
            ``LINEAR`` motions [m/s^2], named as :attr:`names`.

        Raises
        ------
        ValueError
            If a file is missing or its content no longer has the recorded digest.
        """
        from ..ground_motion import read_record, stochastic_suite

        if self.stochastic is not None:
            spec = self.stochastic
            return stochastic_suite(spec["count"], seed=spec["seed"], **spec["parameters"])
        motions = []
        for f in self.files:
            try:
                digest = file_digest(f.path)
            except OSError as exc:
                raise ValueError(f"record file '{f.path}' of the study cannot be read: "
                                 f"{exc.strerror}") from exc
            if digest != f.sha256:
                raise ValueError(f"record file '{f.path}' has changed since the study was set up "
                                 f"(sha256 {digest[:12]}... instead of {f.sha256[:12]}...)")
            motions.append(read_record(f.path, file_format=f.file_format).renamed(f.name))
        return motions

    def to_dict(self) -> dict:
        """The suite as JSON-ready data (what a study's settings store).

        Returns
        -------
        dict
            ``{"kind": "files", "records": [{name, path, format, sha256}, ...]}`` or
            ``{"kind": "stochastic", "count", "seed", "parameters"}``.
        """
        if self.stochastic is not None:
            return {"kind": "stochastic", **self.stochastic}
        return {"kind": "files", "records": [
            {"name": f.name, "path": f.path, "format": f.file_format, "sha256": f.sha256}
            for f in self.files]}

    @classmethod
    def from_dict(cls, data: dict) -> RecordSuite:
        """Inverse of :meth:`to_dict`.

        Parameters
        ----------
        data : dict
            As :meth:`to_dict` writes it.

        Returns
        -------
        RecordSuite
        """
        if data.get("kind") == "stochastic":
            return cls(stochastic={"count": data["count"], "seed": data["seed"],
                                   "parameters": dict(data["parameters"])})
        return cls(files=tuple(RecordFile(r["name"], r["path"], r["format"], r["sha256"])
                               for r in data["records"]))

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, RecordSuite):
            return NotImplemented
        return self.to_dict() == other.to_dict()

    __hash__ = None


def stripe_measure(name: str):
    """The :class:`~archquake.ground_motion.IntensityMeasure` of a stripe: one that scales with
    the record.

    Parameters
    ----------
    name : str
        ``pga``, ``pgv``, ``pgd``, ``arias`` or ``sa(T)`` (T the period [s]).

    Returns
    -------
    IntensityMeasure

    Raises
    ------
    ValueError
        For an unknown name, or a measure that does not change when a record is scaled
        (``d5-95``); the message names ``im``.
    """
    from ..ground_motion import intensity_measure

    try:
        im = intensity_measure(name)
    except ValueError as exc:
        raise ValueError(f"im: {exc}") from None
    if im.exponent == 0.0:
        raise ValueError(f"im {im.name!r} ({im.description}) cannot define stripes: it does not "
                         "change when a record is scaled; choose pga, pgv, pgd, arias or sa(T)")
    return im


# ---------------------------------------------------------------------------------------------
# Settings
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class RecordFragilitySettings:
    """Settings of a multiple-stripe study (module docstring).

    Parameters
    ----------
    suite : RecordSuite
        The records.
    levels : tuple of float
        Increasing stripe levels of the intensity measure, each > 0 [the IM's unit: g for pga and
        sa(T), m/s for pgv and arias, m for pgd].
    im : str
        Intensity measure of the stripes (:func:`stripe_measure`).
    nominal : CircularArch or ShapedArch
        Nominal arch (default: Oppenheim's arch).
    sample_size : int
        Number h of irregular arches (default 40).
    epsilon : float
        epsilon of the irregular draw [eq. (1)], in [0, 1) (default 0.10); 0 makes every arch
        the nominal one.
    seed : int
        Root seed (>= 0) of the arches and of the bootstrap.
    restitution : str or float
        Restitution model (:func:`archquake.fourlink.impact.check_restitution_model`; default
        ``"computed"``, :data:`archquake.defaults.DEFAULT_RESTITUTION`, as in
        :class:`archquake.studies.fragility.FragilitySettings`).
    bootstrap : int
        Number of bootstrap resamples of the confidence bands (>= 10).
    confidence : float
        Confidence level of the bands [-], in (0, 1).

    Raises
    ------
    ValueError
        For a setting out of its range (the message names it).
    """

    suite: RecordSuite
    levels: tuple[float, ...]
    im: str = "pga"
    nominal: BlockArch = field(default_factory=default_nominal)
    sample_size: int = 40
    epsilon: float = 0.10
    seed: int = 0
    restitution: str | float = DEFAULT_RESTITUTION
    bootstrap: int = DEFAULT_BOOTSTRAP
    confidence: float = DEFAULT_CONFIDENCE

    def __post_init__(self) -> None:
        from .fragility import FragilitySettings

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
        positive_int("bootstrap", self.bootstrap, minimum=10)
        if not (isinstance(self.confidence, int | float) and 0.0 < self.confidence < 1.0):
            raise ValueError(f"confidence must be in (0, 1), got {self.confidence!r}")
        # the arch, sample and restitution rules of the pulse study
        FragilitySettings(nominal=self.nominal, sample_size=self.sample_size,
                          epsilon=self.epsilon, seed=self.seed,
                          restitution=self.restitution, limit_sample_size=1)
        object.__setattr__(self, "im", im.name)
        object.__setattr__(self, "levels", tuple(float(v) for v in x))
        object.__setattr__(self, "sample_size", int(self.sample_size))
        object.__setattr__(self, "seed", int(self.seed))
        object.__setattr__(self, "epsilon", float(self.epsilon))
        object.__setattr__(self, "bootstrap", int(self.bootstrap))
        object.__setattr__(self, "confidence", float(self.confidence))
        if not isinstance(self.restitution, str):
            object.__setattr__(self, "restitution", float(self.restitution))

    @property
    def unit(self) -> str:
        """Unit of the IM and of the levels."""
        return stripe_measure(self.im).unit

    def to_dict(self) -> dict:
        """The settings as JSON-ready data, as stored with the results.

        Returns
        -------
        dict
            Every field (the suite by :meth:`RecordSuite.to_dict`, the nominal arch by
            :meth:`archquake.geometry.CircularArch.to_dict`) and ``im_unit``.
        """
        return {
            "suite": self.suite.to_dict(),
            "im": self.im,
            "im_unit": self.unit,
            "levels": list(self.levels),
            "nominal": nominal_dict(self.nominal),
            "sample_size": self.sample_size,
            "epsilon": self.epsilon,
            "seed": self.seed,
            "restitution": self.restitution,
            "bootstrap": self.bootstrap,
            "confidence": self.confidence,
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
                   im=data["im"], nominal=nominal_from_dict(data["nominal"]),
                   sample_size=data["sample_size"],
                   epsilon=data.get("epsilon", data.get("tolerance")),
                   seed=data["seed"],
                   restitution=data["restitution"], bootstrap=data["bootstrap"],
                   confidence=data["confidence"])

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, RecordFragilitySettings):
            return NotImplemented
        return self.to_dict() == other.to_dict()

    __hash__ = None


# ---------------------------------------------------------------------------------------------
# One arch under one record: every level, both polarities, one compiled call
# ---------------------------------------------------------------------------------------------


def scale_factors(im_values, levels, exponent: float) -> np.ndarray:
    r"""Factors that scale each record to each level, as
    :func:`archquake.ground_motion.scale_to_im` does.

    An intensity measure of exponent :math:`p` scales as :math:`IM(s\,\ddot x_g) = s^p\,
    IM(\ddot x_g)` (:math:`p = 1` for PGA, PGV, PGD and SA, 2 for the Arias intensity), so the
    factor that brings record :math:`r` to level :math:`x_j` is

    .. math::

        s_{rj} = \left(\frac{x_j}{IM_r}\right)^{1/p}.

    Parameters
    ----------
    im_values : array_like, shape (R,)
        The intensity measure of every record [the IM's unit].
    levels : array_like, shape (L,)
        Stripe levels [the IM's unit].
    exponent : float
        :math:`p` [-].

    Returns
    -------
    ndarray, shape (R, L)
        :math:`s_{rj}` [-].

    Examples
    --------
    >>> scale_factors([0.2, 0.5], [0.1, 1.0], 1.0)
    array([[0.5, 5. ],
           [0.2, 2. ]])
    """
    im_values = np.asarray(im_values, dtype=float)
    levels = np.asarray(levels, dtype=float)
    return (levels[None, :] / im_values[:, None]) ** (1.0 / exponent)


def record_outcomes(dynamics, motion, factors) -> dict[str, np.ndarray]:
    """Outcomes of one arch under one record scaled by each of ``factors``.

    An analysis whose scaled record stays strictly inside the activation accelerations
    (``-k_l g < s xg'' < k_r g`` at every sample, eq. (2) of the paper, with the relative margin
    :data:`REST_MARGIN`) is at rest without being integrated: the record is piecewise linear, so
    its extremes are samples, and the engine would decide the same.

    Parameters
    ----------
    dynamics : ArchDynamics
        The arch's :class:`~archquake.fourlink.dynamics.ArchDynamics`.
    motion : GroundMotion
        A ``LINEAR`` record [m/s^2].
    factors : array_like of float
        Signed scale factors [-]; a negative factor applies the reversed record.

    Returns
    -------
    dict of ndarray
        ``status`` (0 rest, 1 recovery, 2 collapse), ``half_cycle``, ``impacts``,
        ``collapse_time`` [s], ``max_phi`` [rad] and ``integrated`` (False where the scaled
        record stays below the activation acceleration: rest, not integrated), one per factor.

    Raises
    ------
    ValueError
        If ``motion`` is not piecewise linear, or as
        :func:`archquake.fourlink.engine.outcomes_grid`.
    RuntimeError
        As :func:`archquake.fourlink.engine.outcomes_grid`.
    """
    from ..fourlink.engine import outcomes_grid
    from ..ground_motion import LINEAR

    if motion.kind != LINEAR:
        raise ValueError(f"record_outcomes takes a piecewise-linear record, got kind "
                         f"{motion.kind} ({motion.name!r})")
    table_l, table_r = dynamics.tables
    c_lr, c_rl = dynamics.restitution
    s = np.asarray(factors, dtype=float).ravel()
    v_max, v_min = float(np.max(motion.values)), float(np.min(motion.values))
    # rounding is monotone: max(v * s) is v_max * s for s > 0 and v_min * s for s < 0
    high = np.where(s > 0, s * v_max, s * v_min)
    low = np.where(s > 0, s * v_min, s * v_max)
    threshold_r = table_r.activation_g * GRAVITY  # Mech-r opens when xg'' > k_r g
    threshold_l = -table_l.activation_g * GRAVITY  # Mech-l opens when xg'' < -k_l g
    run = ~((high < threshold_r * (1.0 - REST_MARGIN)) & (low > threshold_l * (1.0 - REST_MARGIN)))
    out = {"status": np.zeros(s.size, dtype=np.int8),
           "half_cycle": np.zeros(s.size, dtype=np.int16),
           "impacts": np.zeros(s.size, dtype=np.int32),
           "collapse_time": np.full(s.size, np.nan), "max_phi": np.zeros(s.size),
           "integrated": run}
    if np.any(run):
        signed = s[run]
        grid = outcomes_grid(table_l, table_r, c_lr, c_rl, np.ones(signed.size), signed, motion)
        for name in ("status", "half_cycle", "impacts", "collapse_time", "max_phi"):
            out[name][run] = grid[name]
    return out


# ---------------------------------------------------------------------------------------------
# The study task (runs in the workers)
# ---------------------------------------------------------------------------------------------


@functools.lru_cache(maxsize=2)
def _suite_motions(suite_json: str) -> tuple:
    """The suite's motions, read once per process and suite."""
    return tuple(RecordSuite.from_dict(json.loads(suite_json)).motions())


@functools.lru_cache(maxsize=4)
def _suite_im_values(suite_json: str, im_name: str) -> np.ndarray:
    """The intensity measure of every record of the suite [the IM's unit]."""
    im = stripe_measure(im_name)
    values = np.array([im(m) for m in _suite_motions(suite_json)])
    bad = [m.name for m, v in zip(_suite_motions(suite_json), values, strict=True) if not v > 0]
    if bad:
        raise ValueError(f"records with {im.name} = 0 cannot be scaled to a level: {bad}")
    return values


def record_fragility_task(chunk) -> dict[str, np.ndarray]:
    """Study task (:func:`archquake.execution.run_study`): the arches of one chunk.

    ``chunk.settings`` is :meth:`RecordFragilitySettings.to_dict`; item ``i < h`` is irregular
    arch ``i`` (drawn from ``chunk.generators()``), item ``h`` the nominal arch.

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
        If an arch cannot be analysed (naming it; unlike the pulse study, no arch is
        excluded), or a record file changed.
    """
    settings = RecordFragilitySettings.from_dict(chunk.settings)
    suite_json = json.dumps(chunk.settings["suite"], sort_keys=True)
    motions = _suite_motions(suite_json)
    im = stripe_measure(settings.im)
    factors = scale_factors(_suite_im_values(suite_json, settings.im), settings.levels,
                            im.exponent)
    levels = np.asarray(settings.levels)
    n_levels = levels.size
    polarity = np.tile(np.array(POLARITIES, dtype=np.int8), n_levels)
    parts = []
    for item, rng in zip(chunk.items, chunk.generators(), strict=True):
        if item < settings.sample_size:
            arch, arch_id = irregular_arch(settings.nominal, settings.epsilon, rng), int(item)
        else:
            arch, arch_id = settings.nominal, NOMINAL_ARCH
        try:
            dynamics = ArchDynamics.from_arch(arch, settings.restitution, settings.nominal)
        except ValueError as exc:
            raise ValueError(f"arch {arch_id} (seed {chunk.seed}) cannot be analysed: "
                             f"{exc}") from exc
        k_l, k_r = dynamics.load_multipliers
        c_lr, c_rl = dynamics.restitution
        for r, motion in enumerate(motions):
            signed = (factors[r][:, None] * np.array(POLARITIES, dtype=float)[None, :]).ravel()
            out = record_outcomes(dynamics, motion, signed)
            n = signed.size
            parts.append({
                "arch": np.full(n, arch_id, dtype=np.int64),
                "record": np.full(n, motion.name),
                "level": np.repeat(levels, len(POLARITIES)),
                "polarity": polarity,
                "scale_factor": np.abs(signed),
                **out,
                "k_l": np.full(n, k_l), "k_r": np.full(n, k_r),
                "c_lr": np.full(n, c_lr), "c_rl": np.full(n, c_rl),
            })
    columns = {name: np.concatenate([p[name] for p in parts]) for name in parts[0]}
    width = max(len(name) for name in columns["record"])
    columns["record"] = columns["record"].astype(f"<U{width}")
    return columns


# ---------------------------------------------------------------------------------------------
# Fits
# ---------------------------------------------------------------------------------------------


def separated(levels, trials, failures) -> bool:
    """Whether binomial stripe counts admit no maximum-likelihood lognormal fit.

    True if there is no failure or no survival, or if every survival lies at a level no higher
    than every failure (complete or quasi-complete separation: the likelihood grows without
    bound as the fit tends to a step, beta -> 0).

    Parameters
    ----------
    levels : array_like, shape (L,)
        Stripe levels [the IM's unit].
    trials : int or array_like
        Trials ``n_j`` per stripe.
    failures : array_like, shape (L,)
        Failures ``z_j`` per stripe.

    Returns
    -------
    bool

    Examples
    --------
    Survivals above a failure leave a maximum; a single mixed level between all survivals and
    all failures does not (quasi-complete separation):

    >>> separated([0.1, 0.2, 0.3], 10, [0, 4, 8]), separated([0.1, 0.2, 0.3], 10, [0, 4, 10])
    (False, True)
    """
    x = np.asarray(levels, dtype=float)
    n = np.broadcast_to(np.asarray(trials, dtype=float), x.shape)
    z = np.asarray(failures, dtype=float)
    fails, survives = z > 0, z < n
    if not np.any(fails) or not np.any(survives):
        return True
    return bool(np.max(x[survives]) <= np.min(x[fails]))


def lognormal_fit(levels, trials, failures) -> LognormalFragility | None:
    """Maximum-likelihood lognormal fragility of stripe counts, or None when none exists.

    Parameters
    ----------
    levels : array_like, shape (L,)
        Stripe levels [the IM's unit].
    trials : int or array_like
        Trials ``n_j`` per stripe.
    failures : array_like, shape (L,)
        Failures ``z_j`` per stripe.

    Returns
    -------
    LognormalFragility or None
        :func:`archquake.studies.fragility.fit_lognormal`; None for fewer than two levels or
        separated counts (:func:`separated`).
    """
    if np.asarray(levels).size < 2 or separated(levels, trials, failures):
        return None
    return fit_lognormal(levels, trials, failures)


def _inverse_mills(t):
    """``phi(t) / Phi(t)`` [-], stable for large negative t."""
    from scipy import special

    return np.exp(-0.5 * t * t - 0.5 * math.log(2.0 * math.pi) - special.log_ndtr(t))


def _probit_log_likelihood(eta, n, z):
    from scipy import special

    return np.sum(z * special.log_ndtr(eta) + (n - z) * special.log_ndtr(-eta), axis=-1)


def probit_newton(log_levels, trials, failures, *, slope=None, start=(0.0, 1.0),
                  iterations: int = 60, tolerance: float = 1e-12):
    r"""Maximum likelihood of ``P = Phi(a + b ln x)`` for many sets of stripe counts at once.

    The lognormal fragility function is this probit model with :math:`b = 1/\beta` and
    :math:`a = -\ln(\theta)/\beta`; its log-likelihood

    .. math::

        \ell(a, b) = \sum_j z_j \ln\Phi(\eta_j) + (n_j - z_j) \ln\Phi(-\eta_j),
        \qquad \eta_j = a + b \ln x_j,

    is concave in :math:`(a, b)`, so Newton's method with step halving converges from any start
    when the maximum exists. Its score and (negative) Hessian come from
    :math:`\partial\ell/\partial\eta_j = z_j \lambda(\eta_j) - (n_j - z_j) \lambda(-\eta_j)`,
    :math:`\lambda = \varphi/\Phi` the inverse Mills ratio. Used where many fits are needed at
    once (bootstrap resamples, the records of :func:`common_dispersion_fit`); a single fit is
    :func:`archquake.studies.fragility.fit_lognormal`.

    Parameters
    ----------
    log_levels : array, shape (L,)
        ``ln x_j`` [ln of the IM's unit].
    trials : array, broadcastable to ``failures``
        Trials ``n_j`` per stripe.
    failures : array, shape (..., L)
        Failures ``z_j`` per stripe, for every set.
    slope : float, optional
        If given, ``b`` is held at this value and only ``a`` is fitted.
    start : (float, float) or arrays
        Starting ``(a, b)``.
    iterations : int
        Largest number of Newton steps.
    tolerance : float
        Convergence: the largest Newton step [-].

    Returns
    -------
    a, b : ndarray, shape (...)
        The estimates [-] and [1/ln of the IM's unit] (nan for a set that did not converge).
    """
    u = np.asarray(log_levels, dtype=float)
    z = np.asarray(failures, dtype=float)
    n = np.broadcast_to(np.asarray(trials, dtype=float), z.shape)
    batch = z.shape[:-1]
    a = np.broadcast_to(np.asarray(start[0], dtype=float), batch).copy()
    b = np.broadcast_to(np.asarray(start[1] if slope is None else slope, dtype=float),
                        batch).copy()
    converged = np.zeros(batch, dtype=bool)

    def loglik(a_, b_):
        return _probit_log_likelihood(a_[..., None] + b_[..., None] * u, n, z)

    current = loglik(a, b)
    for _ in range(iterations):
        eta = a[..., None] + b[..., None] * u
        lam_p, lam_m = _inverse_mills(eta), _inverse_mills(-eta)
        score = z * lam_p - (n - z) * lam_m  # d loglik / d eta
        weight = z * lam_p * (eta + lam_p) + (n - z) * lam_m * (lam_m - eta)  # -d2/deta2 > 0
        g_a, h_aa = score.sum(-1), weight.sum(-1)
        if slope is None:
            g_b, h_ab, h_bb = (score * u).sum(-1), (weight * u).sum(-1), (weight * u * u).sum(-1)
            det = h_aa * h_bb - h_ab * h_ab
            with np.errstate(divide="ignore", invalid="ignore"):
                d_a = (h_bb * g_a - h_ab * g_b) / det
                d_b = (h_aa * g_b - h_ab * g_a) / det
        else:
            with np.errstate(divide="ignore", invalid="ignore"):
                d_a = g_a / h_aa
            d_b = np.zeros(batch)
        d_a = np.where(converged, 0.0, d_a)
        d_b = np.where(converged, 0.0, d_b)
        step = np.ones(batch)
        for _ in range(30):  # halve the step until the likelihood does not decrease
            trial = loglik(a + step * d_a, b + step * d_b)
            ok = np.isfinite(trial) & (trial >= current - 1e-12 * np.abs(current))
            if np.all(ok | converged):
                break
            step = np.where(ok | converged, step, 0.5 * step)
        a, b = a + step * d_a, b + step * d_b
        current = loglik(a, b)
        converged |= np.maximum(np.abs(step * d_a), np.abs(step * d_b)) <= tolerance * (
            1.0 + np.abs(a) + np.abs(b))
        if np.all(converged):
            break
    bad = ~converged | ~np.isfinite(a) | ~np.isfinite(b)
    return np.where(bad, np.nan, a), np.where(bad, np.nan, b)


@dataclass(frozen=True)
class BootstrapBand:
    """Percentile bootstrap of a lognormal fragility fit.

    Attributes
    ----------
    x : ndarray
        IM values of the band [the IM's unit].
    lower, upper : ndarray
        Band limits of P(collapse | IM = x) [-].
    median_interval, dispersion_interval : (float, float)
        Percentile intervals of theta [the IM's unit] and beta [-].
    resamples : int
        Resamples drawn.
    degenerate : int
        Resamples without a maximum-likelihood fit (left out).
    confidence : float
        Confidence level [-].
    """

    x: np.ndarray
    lower: np.ndarray
    upper: np.ndarray
    median_interval: tuple[float, float]
    dispersion_interval: tuple[float, float]
    resamples: int
    degenerate: int
    confidence: float

    def to_dict(self) -> dict:
        """The band's numbers as JSON-ready data.

        Returns
        -------
        dict
            ``resamples``, ``degenerate``, ``confidence``, ``median_interval`` [the IM's unit]
            and ``dispersion_interval`` [-] (the band itself is in
            :meth:`RecordFragilityResult.curves`).
        """
        return {"resamples": self.resamples, "degenerate": self.degenerate,
                "confidence": self.confidence, "median_interval": list(self.median_interval),
                "dispersion_interval": list(self.dispersion_interval)}


def bootstrap_lognormal(levels, failed, fit: LognormalFragility, *, resamples: int,
                        confidence: float, rng, x=None) -> BootstrapBand | None:
    r"""Confidence band of a lognormal fit by resampling the units of ``failed`` with replacement.

    Every leading axis of ``failed`` (arches, records) is resampled with replacement (drawn as
    multinomial multiplicities of its units), the counts :math:`z^{*b}_j` of resample :math:`b`
    rebuilt from the resampled units and refitted by maximum likelihood
    (:func:`probit_newton`, started from ``fit``); the band is the percentile interval (ch. 13
    of [1]_) of the refitted curves at every IM value :math:`x`,

    .. math::

        \Bigl[q_{\alpha/2}\{P^{*b}(x)\},\; q_{1-\alpha/2}\{P^{*b}(x)\}\Bigr], \qquad
        \alpha = 1 - \text{confidence},

    and the intervals of :math:`\theta` and :math:`\beta` are the same percentiles of their
    refitted values. Resamples whose counts are separated (:func:`separated`) or whose fit does
    not converge are left out and counted.

    Parameters
    ----------
    levels : array, shape (L,)
        Stripe levels [the IM's unit].
    failed : bool array, shape (units..., L)
        Failure of every unit at every level; every leading axis is resampled independently
        (e.g. ``(arches, records, L)``: arches and records).
    fit : LognormalFragility
        The fit to all data (start of every refit).
    resamples : int
        Number of resamples :math:`B`.
    confidence : float
        Central fraction of the refitted curves the band holds [-], in (0, 1).
    rng : numpy.random.Generator
        Source of the resampling.
    x : array, optional
        IM values of the band [the IM's unit] (default: :data:`BAND_POINTS` log-spaced over
        the levels).

    Returns
    -------
    BootstrapBand or None
        None if no resample has a fit.

    References
    ----------
    .. [1] Efron, B. and Tibshirani, R. J. (1993). An Introduction to the Bootstrap. Chapman &
       Hall, ch. 13 (percentile intervals).
    """
    from scipy import stats

    y = np.asarray(failed, dtype=float)
    levels = np.asarray(levels, dtype=float)
    unit_axes = y.shape[:-1]
    counts = y
    weights = [rng.multinomial(size, np.full(size, 1.0 / size), size=resamples)
               for size in unit_axes]
    # z[b, j] = sum over units of (product of the units' multiplicities) * y[units, j]
    z = np.tensordot(weights[0], counts, axes=(1, 0))  # (B, rest..., L)
    for w in weights[1:]:
        z = np.einsum("bk...,bk->b...", z, w)
    trials = float(np.prod(unit_axes))
    u = np.log(levels)
    good = np.array([not separated(levels, trials, zb) for zb in z])
    a = np.full(resamples, np.nan)
    b = np.full(resamples, np.nan)
    if np.any(good):
        start = (-math.log(fit.median) / fit.dispersion, 1.0 / fit.dispersion)
        a[good], b[good] = probit_newton(u, trials, z[good], start=start)
    ok = np.isfinite(a) & np.isfinite(b) & (b > 0)
    if not np.any(ok):
        return None
    beta = 1.0 / b[ok]
    theta = np.exp(-a[ok] * beta)
    if x is None:
        x = np.geomspace(levels[0], levels[-1], BAND_POINTS)
    curves = stats.norm.cdf(np.log(x[None, :] / theta[:, None]) / beta[:, None])
    tail = 50.0 * (1.0 - confidence)
    lower, upper = np.percentile(curves, [tail, 100.0 - tail], axis=0)
    return BootstrapBand(
        x=np.asarray(x, dtype=float), lower=lower, upper=upper,
        median_interval=tuple(float(v) for v in np.percentile(theta, [tail, 100.0 - tail])),
        dispersion_interval=tuple(float(v) for v in np.percentile(beta, [tail, 100.0 - tail])),
        resamples=int(resamples), degenerate=int(resamples - ok.sum()),
        confidence=float(confidence))


@dataclass(frozen=True)
class CommonDispersionFit:
    """Lognormal fragility per record with one common dispersion (:func:`common_dispersion_fit`).

    Attributes
    ----------
    dispersion : float
        The common dispersion beta_G [-].
    medians : ndarray
        Median theta_r of every record used [the IM's unit].
    records : ndarray of int
        Indices of the records used.
    """

    dispersion: float
    medians: np.ndarray
    records: np.ndarray


def common_dispersion_fit(levels, trials, failures) -> CommonDispersionFit | None:
    r"""Joint maximum-likelihood fit of :math:`P_r(x) = \Phi(\ln(x/\theta_r)/\beta)`: one median
    per set of counts (row of ``failures``) and one common dispersion.

    .. math::

        \hat\beta = \arg\max_\beta \max_{\theta_1 \dots \theta_R} \sum_r \sum_j
        \Bigl[z_{rj} \ln P_r(x_j) + (n_{rj} - z_{rj}) \ln\bigl(1 - P_r(x_j)\bigr)\Bigr]:

    the profile likelihood of :math:`\beta`, maximised by a bounded scalar search on
    :math:`\ln\beta \in [\ln 10^{-3}, \ln 10]`, each :math:`\theta_r` at given :math:`\beta` by
    Newton's method (:func:`probit_newton` with the slope held). It is the multiple-stripe fit
    of [1]_ with the records as groups. Rows with no failure or no survival are left out (they
    hold no information on :math:`\beta`).

    Parameters
    ----------
    levels : array, shape (L,)
        Stripe levels [the IM's unit].
    trials : int or array
        Trials :math:`n_{rj}` per stripe (e.g. the number of arches).
    failures : array, shape (R, L)
        Failures :math:`z_{rj}` per row and stripe.

    Returns
    -------
    CommonDispersionFit or None
        None if no row has both failures and survivals, or if every used row is a step
        (:func:`separated`), for which beta -> 0.

    References
    ----------
    .. [1] Baker, J. W. (2015). Efficient analytical fragility function fitting using dynamic
       structural analysis. Earthquake Spectra 31(1), 579-599.
    """
    from scipy import optimize

    u = np.log(np.asarray(levels, dtype=float))
    z = np.asarray(failures, dtype=float)
    n = np.broadcast_to(np.asarray(trials, dtype=float), z.shape)
    used = np.flatnonzero((z.sum(-1) > 0) & (z.sum(-1) < n.sum(-1)))
    if used.size == 0 or u.size < 2:
        return None
    z, n = z[used], n[used]
    if all(separated(np.exp(u), n[i], z[i]) for i in range(used.size)):
        return None
    centre = np.array([u[np.argmin(np.abs(zi / ni - 0.5))] for zi, ni in zip(z, n, strict=True)])

    def intercepts(beta):
        a, _ = probit_newton(u, n, z, slope=1.0 / beta, start=(-centre / beta, 1.0 / beta))
        return a

    def negative(log_beta):
        beta = math.exp(log_beta)
        a = intercepts(beta)
        if not np.all(np.isfinite(a)):
            return np.inf
        return -float(np.sum(_probit_log_likelihood(a[:, None] + u[None, :] / beta, n, z)))

    res = optimize.minimize_scalar(negative, bounds=(math.log(1e-3), math.log(10.0)),
                                   method="bounded", options={"xatol": 1e-9})
    beta = math.exp(res.x)
    a = intercepts(beta)
    return CommonDispersionFit(float(beta), np.exp(-a * beta), used)


# ---------------------------------------------------------------------------------------------
# The result
# ---------------------------------------------------------------------------------------------


def _json_number(x) -> float | None:
    return None if x is None or not math.isfinite(float(x)) else float(x)


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
        without integrating), ``k_l``, ``k_r``, ``c_lr``, ``c_rl`` [-].
    records : tuple of str
        Record names, in suite order.
    levels : ndarray, shape (L,)
        Stripe levels [IM unit].
    collapsed : bool ndarray, shape (h, R, L, 2)
        Collapse of every irregular arch, record, level and polarity (as recorded, reversed).
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

    # ------------------------------------------------------------------ stripes
    @property
    def failed(self) -> np.ndarray:
        """Failure of every irregular arch-record pair at every level (either polarity),
        shape (h, R, L)."""
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
        geo = self.geometric_dispersion
        total = None if self.lognormal is None else self.lognormal.dispersion
        srss = None if rtr is None or geo is None else math.hypot(rtr, geo)
        return {
            "record_to_record": rtr, "geometric": geo, "total": total, "srss": srss,
            "geometric_records_used": (0 if self.geometric is None
                                       else int(self.geometric.records.size)),
            "definitions": {
                "record_to_record": "dispersion of the lognormal fit to the nominal arch's "
                                    "stripes (one geometry, the records vary)",
                "geometric": "common dispersion of lognormal fits with one median per record to "
                             "the irregular arches' stripes (the records fixed, the geometry "
                             "varies)",
                "total": "dispersion of the lognormal fit to all arch-record pairs pooled",
                "srss": "sqrt(record_to_record^2 + geometric^2), for comparison with total",
            },
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
        blocks = [(a, self.failed[a]) for a in range(self.failed.shape[0])]
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
            ``nominal_records``, ``nominal_failures``, ``nominal_probability`` and
            ``nominal_lognormal_fit`` [-]; nan where a fit or band does not exist.
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
        })

    def export_nrml(self, path: str | os.PathLike, *, taxonomy: str = "masonry-arch") -> Path:
        """Write the fitted fragility functions as an OpenQuake NRML fragility model
        (:func:`archquake.results_io.write_fragility_nrml`), limit state ``collapse``, in the
        study's intensity measure (OpenQuake's units): ``taxonomy`` is the total fit of the
        irregular arches, ``taxonomy + "-nominal"`` the nominal arch's fit.

        Parameters
        ----------
        path : str or os.PathLike
            The XML file.
        taxonomy : str
            Id of the total fit (OpenQuake's taxonomy).

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
        description = (f"archquake {__version__}: collapse of masonry arches, lognormal fits by "
                       f"maximum likelihood to multiple stripes of {s.im} "
                       f"({self.levels[0]:g} to {self.levels[-1]:g} {s.unit}), "
                       f"{len(self.records)} records x 2 polarities; '{taxonomy}': "
                       f"{s.sample_size} irregular arches (epsilon {s.epsilon:g}, seed "
                       f"{s.seed}); "
                       f"'{taxonomy}-nominal': the nominal arch")
        return write_fragility_nrml(path, functions, im=s.im, min_iml=float(self.levels[0]),
                                    max_iml=float(self.levels[-1]), description=description)

    def summary(self) -> dict:
        """JSON-ready summary: IM, levels, stripes, fits, bands, variability, incremental view.

        Returns
        -------
        dict
            What ``summary.json`` of the study holds under ``summary`` (levels in the IM's
            unit, probabilities and dispersions [-]).
        """
        incremental = self.incremental()
        sample = incremental[incremental["arch"] != NOMINAL_ARCH]
        total = _fit_dict(self.lognormal)
        total["band"] = None if self.band is None else self.band.to_dict()
        nominal = _fit_dict(self.nominal_lognormal)
        nominal["band"] = None if self.nominal_band is None else self.nominal_band.to_dict()
        integrated = self.table["integrated"].to_numpy()
        return {
            "im": self.settings.im,
            "im_unit": self.settings.unit,
            "levels": self.levels.tolist(),
            "records": list(self.records),
            "sample_size": self.settings.sample_size,
            "trials": self.trials,
            "failures": self.failures.tolist(),
            "probability": self.probability.tolist(),
            "probability_as_recorded": self.probability_of_polarity(1).tolist(),
            "probability_reversed": self.probability_of_polarity(-1).tolist(),
            "lognormal": total,
            "nominal": {"probability": self.nominal_probability.tolist(), "lognormal": nominal},
            "variability": self.variability(),
            "incremental": {
                "pairs": int(len(sample)),
                "pairs_collapsing": int(np.isfinite(sample["first_collapse"]).sum()),
                "pairs_recovering_above_first_collapse": int((sample["recoveries_above"] > 0)
                                                             .sum()),
            },
            "analyses": {"total": int(integrated.size), "integrated": int(integrated.sum()),
                         "at_rest_without_integration": int((~integrated).sum())},
            "settings": self.settings.to_dict(),
            "seed": self.settings.seed,
        }


def _study_arrays(table: pd.DataFrame, settings: RecordFragilitySettings):
    """``collapsed[arch, record, level, polarity]`` (irregular arches, then the nominal one)."""
    from ..fourlink.engine import STATUS_COLLAPSE

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
    return table["status"].to_numpy().reshape(shape) == STATUS_COLLAPSE


def record_fragility_result(settings: RecordFragilitySettings, table: pd.DataFrame,
                            metadata: dict | None = None) -> RecordFragilityResult:
    """Assemble a :class:`RecordFragilityResult` (stripes, fits, bands) from the study table.

    The bootstrap draws from ``SeedSequence(settings.seed, spawn_key=(BOOTSTRAP_KEY,))`` (one
    child stream for the total band, one for the nominal band), so the same table gives the
    same bands.

    Parameters
    ----------
    settings : RecordFragilitySettings
        The settings of the study.
    table : pandas.DataFrame
        The rows of :func:`record_fragility_task`, in its order.
    metadata : dict, optional
        Metadata of the study.

    Returns
    -------
    RecordFragilityResult

    Raises
    ------
    ValueError
        If the table does not match the settings.
    """
    collapsed = _study_arrays(table, settings)
    sample, nominal = collapsed[:-1], collapsed[-1]
    levels = np.asarray(settings.levels)
    failed = sample.any(axis=-1)
    nominal_failed = nominal.any(axis=-1)
    h, r = failed.shape[:2]
    total = lognormal_fit(levels, h * r, failed.sum(axis=(0, 1)))
    nominal_fit = lognormal_fit(levels, r, nominal_failed.sum(axis=0))
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
        metadata=dict(metadata or {}))


# ---------------------------------------------------------------------------------------------
# Running, saving, loading
# ---------------------------------------------------------------------------------------------


def warm_up() -> None:
    """Load the compiled engine in this process (a pool's ``warm_up``): one arch, one short
    record, two levels."""
    from ..ground_motion import stochastic_motion

    motion = stochastic_motion(0.5, 2.0, 1.0, 2.0, 0.0, 0.2, duration=2.0, rng=0)
    dynamics = ArchDynamics.from_arch(default_nominal(), "nominal", default_nominal())
    record_outcomes(dynamics, motion, [0.5, -3.0])


def _check_resume(out: Path, settings: RecordFragilitySettings) -> None:
    """Refuse to resume a study whose record files differ from the stored ones, naming them."""
    from ..execution import STUDY_JSON
    from ..results_io import read_json

    study = out / STUDY_JSON
    if not study.is_file():
        return
    stored = read_json(study).get("settings", {}).get("suite")
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
        Local processes (default: the number of CPUs).
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
        (IM = 0), changed record files on resume, an arch that cannot be analysed, or an output
        directory that is not empty (without ``resume``) or holds another study.
    archquake.errors.StudyError
        If the Dask cluster can no longer finish the study
        (:func:`archquake.execution.run_study`).
    """
    from ..execution import StudyPlan, run_study
    from ..results_io import atomic_path, save_study, write_csv

    if not isinstance(settings, RecordFragilitySettings):
        raise ValueError(f"settings must be RecordFragilitySettings, got "
                         f"{type(settings).__name__}")
    # read every record and its IM here, so that a bad file stops the study before it starts
    suite_json = json.dumps(settings.suite.to_dict(), sort_keys=True)
    _suite_im_values(suite_json, settings.im)
    out = None if out_dir is None else Path(out_dir)
    if resume and out is not None:
        _check_resume(out, settings)
    plan = StudyPlan(settings.to_dict(), settings.seed, settings.sample_size + 1,
                     positive_int("chunk_size", chunk_size))
    table = run_study(record_fragility_task, plan, out, backend=backend, workers=workers,
                      scheduler=scheduler, pool=pool, resume=resume, progress=progress)
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
    "BOOTSTRAP_KEY", "DEFAULT_BOOTSTRAP", "DEFAULT_CONFIDENCE", "DEFAULT_LEVELS", "NOMINAL_ARCH",
    "POLARITIES", "STOCHASTIC_SUITE", "oppenheim_record_fragility",
    "REST_MARGIN", "BootstrapBand", "CommonDispersionFit", "RecordFile",
    "RecordFragilityResult", "RecordFragilitySettings", "RecordSuite", "bootstrap_lognormal",
    "common_dispersion_fit", "file_digest", "load_record_fragility", "lognormal_fit",
    "probit_newton", "record_fragility_result", "record_fragility_task", "record_outcomes",
    "run_record_fragility", "scale_factors", "separated", "stripe_measure", "warm_up",
]
