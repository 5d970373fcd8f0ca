"""Settings of an assessment of one structure (:func:`archquake.report.assess.assess`) and the
fixed choices of its report.

:class:`AssessmentSettings` holds every choice an assessment makes: the irregularity (epsilon,
seed), the four-link model's restitution, the rigid blocks' friction, the period of Sa(T), and the
sizes of its studies. The defaults keep an assessment of a ten-voussoir arch against a built-in
suite of real records within three minutes on two processors (measured: about one, two with
Sa(T)) where the two models agree; where they disagree, the studies of irregular arches and
records run again with the rigid-block model (``rigid_block_*_sample_size``), and the budget is
ten minutes on two processors for Oppenheim's arch on piers 3 m x 6 m
(``archquake assess --piers 3,6``; measured 162 s on two nearly idle processors, 33 s before
the rigid-block studies; 8.5 min with 4 arches under the records on a machine shared with other
work). :meth:`AssessmentSettings.quick_settings` within a minute (a smoke test,
not an assessment). The pulse durations are the paper's, scaled to the size of the structure
(:func:`time_scale`): rocking is slower, by the square root of the size, in a larger structure.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, replace

import numpy as np

from ...checks import check_integer
from ...defaults import (
    AGREEMENT_BAND,
    DEFAULT_EPSILON,
    DEFAULT_FRICTION,
    DEFAULT_RESTITUTION,
    DEFAULT_SEED,
    MAX_GRID_POINTS,
    MAX_LIMIT_SAMPLES,
    MAX_SAMPLES,
    STUDY_DURATIONS,
)
from ...geometry import check_epsilon

PAPER_DURATIONS = (0.1, 1.0)
"""First and last pulse duration t_p [s] of the paper's failure domain (Fig. 16), for
Oppenheim's arch; an assessment scales them to its structure (:func:`time_scale`)."""

PAPER_FRAGILITY_DURATIONS = STUDY_DURATIONS
"""Pulse durations t_p [s] of the paper's fragility curves (Figs. 17-20), for Oppenheim's arch."""

DEFAULT_SUITE = "fema-p695-near-field-pulse"
"""The records of an assessment unless others are given: FEMA P695's pulse-like near-field
records, the kind of motion the paper studies (a pulse), when the ``records`` extra is installed.
"""

FALLBACK_RECORDS = 20
"""Ground motions of the stochastic suite used when no real records are at hand."""

QUICK = {"duration_count": 4, "amplitude_points": 30, "domain_resolution_g": 2e-2,
         "fragility_sample_size": 8, "limit_sample_size": 100,
         "fragility_amplitude_points": 21, "record_sample_size": 4, "record_levels": 6,
         "record_count": 6, "rigid_block_fragility_sample_size": 2,
         "rigid_block_record_sample_size": 1, "bootstrap": 50,
         "quick": True}
"""The reduced sizes of a quick assessment (:meth:`AssessmentSettings.quick_settings`)."""

def arch_extent(structure) -> float:
    """Horizontal extent of the arch of a structure (its piers left out) [m].

    Parameters
    ----------
    structure : BlockArch or BlockAssembly
        An arch or a :class:`~archquake.geometry.Structure`; or a block assembly: of several
        spans (:func:`~archquake.geometry.bridge.multi_span`), the first span's voussoirs; else
        its voussoirs (an arch of several rings), else all its blocks.

    Returns
    -------
    float
    """
    if not hasattr(structure, "n_voussoirs") and hasattr(structure, "polygons"):
        pairs = list(zip(structure.polygons, structure.names or ("",) * structure.n_blocks,
                         strict=True))
        chosen = ([p for p, name in pairs if name.startswith("span 1 ")]
                  or [p for p, name in pairs if "voussoir" in name]
                  or [p for p, _ in pairs])
        return float(np.ptp(np.concatenate([np.asarray(p, dtype=float)[:, 0]
                                            for p in chosen])))
    arch = getattr(structure, "arch", structure)
    xs = np.concatenate([arch.outline(i, 8)[:, 0] for i in range(arch.n_voussoirs)])
    return float(np.ptp(xs))


def time_scale(structure) -> float:
    r"""Factor [-] that scales the paper's pulse durations to a structure.

    The time of rocking scales with :math:`\sqrt{L/g}`, :math:`L` a size of the structure (the
    frequency parameter of a rocking block, Housner 1963), so the pulse durations that span the
    interesting part of a failure domain do too. With :math:`L` the horizontal extent of the arch
    (:func:`arch_extent`), the factor is :math:`\sqrt{L / L_0}`, :math:`L_0` that of
    Oppenheim's arch: 1 for it, whose durations are then the paper's.

    Parameters
    ----------
    structure : BlockArch

    Returns
    -------
    float

    References
    ----------
    .. [1] Housner, G. W. (1963). The behavior of inverted pendulum structures during
       earthquakes. Bulletin of the Seismological Society of America 53(2), 403-417.
    """
    from ...reference_arches import oppenheim

    return math.sqrt(arch_extent(structure) / arch_extent(oppenheim()))


@dataclass(frozen=True, eq=False)
class AssessmentSettings:
    """Every choice of an assessment.

    Attributes
    ----------
    epsilon : float
        epsilon of the irregular arches drawn around the structure [-], in [0, 1) (the paper's
        eq. (1); 0.10 by default, the paper's).
    seed : int
        Root seed of the irregular arches (and of a synthetic suite), >= 0.
    restitution : str or float
        Restitution model of the four-link model
        (:data:`archquake.fourlink.impact.RESTITUTION_MODELS`, or an imposed c_v in (0, 1]);
        every irregular arch gets its own with ``"computed"``.
    friction : float
        Coulomb friction coefficient of the rigid-block model's joints [-].
    sa_period : float or None
        Period T [s] of the spectral acceleration Sa(T) of a third record-based fragility
        (None: PGA and PGV only).
    durations : tuple of float or None
        Pulse durations t_p [s] of the failure domains of both models; None: ``duration_count``
        durations from the paper's 0.1 s to 1.0 s scaled to the structure (:func:`time_scale`).
    duration_count : int
        Pulse durations of the failure domains when ``durations`` is None, >= 2.
    amplitude_points : int
        Points of the amplitude scan of the failure domains, from just below the activation to
        the top (:func:`archquake.report.assess.parts.pulse_grid`), >= 10.
    domain_resolution_g : float
        Bisection width of every boundary of both models' failure domains [g].
    fragility_sample_size : int
        h, irregular arches of the fragility under pulses (the paper: 40), at most
        :data:`~archquake.defaults.MAX_SAMPLES`.
    limit_sample_size : int
        s, irregular arches of the limit-analysis CDF of k~ (the paper: 1000), at most
        :data:`~archquake.defaults.MAX_LIMIT_SAMPLES`.
    fragility_amplitude_points : int
        Amplitudes of the fragility under pulses, around the structure's failure accelerations,
        >= 8.
    record_sample_size : int
        h, irregular arches of the record-based fragility (beside the structure itself), at
        most :data:`~archquake.defaults.MAX_SAMPLES`.
    rigid_block_fragility_sample_size : int
        h of the rigid-block model's fragility under pulses, run where the two models disagree
        (:func:`archquake.report.assess.parts.trusted_model`): the first arches of the same
        draws (about 1.5 s an arch for Oppenheim's arch on piers, 4 durations x 41 amplitudes
        x 2 directions, on one processor).
    rigid_block_record_sample_size : int
        h of the rigid-block model's record-based fragility, run where the two models
        disagree; fewer than ``record_sample_size``: a rigid-block analysis of a record costs
        about 60 ms (Oppenheim's arch on piers; 160 ms the pointed arch of the user guide),
        thousands of four-link ones. Three arches and the structure are two rounds of one arch
        per process on two processors (four arches would take three).
    record_levels : int
        Stripes of each record-based fragility, >= 4.
    record_count : int or None
        Ground motions of the suite used (None: all); a built-in suite keeps its first
        ``record_count`` fault-normal components, then the others; files the first by name.
    bootstrap : int
        Bootstrap resamples of the record-based fragility's bands, >= 10.
    quick : bool
        The reduced sizes of :meth:`quick_settings` (recorded in the report).

    Raises
    ------
    ValueError
        For a setting out of its range (the message names it).
    """

    epsilon: float = DEFAULT_EPSILON
    seed: int = DEFAULT_SEED
    restitution: str | float = DEFAULT_RESTITUTION
    friction: float = DEFAULT_FRICTION
    sa_period: float | None = None
    durations: tuple[float, ...] | None = None
    duration_count: int = 19
    amplitude_points: int = 60
    domain_resolution_g: float = 5e-3
    fragility_sample_size: int = 40
    limit_sample_size: int = 1000
    fragility_amplitude_points: int = 41
    record_sample_size: int = 10
    rigid_block_fragility_sample_size: int = 40
    rigid_block_record_sample_size: int = 3
    record_levels: int = 10
    record_count: int | None = None
    bootstrap: int = 200
    quick: bool = False

    def __post_init__(self):
        object.__setattr__(self, "epsilon", check_epsilon(self.epsilon))
        object.__setattr__(self, "seed", check_integer("seed", self.seed, minimum=0))
        # the restitution and the friction are checked as the model's settings
        object.__setattr__(self, "restitution", self.model_spec().restitution)
        if self.sa_period is not None:
            if not (isinstance(self.sa_period, int | float) and math.isfinite(self.sa_period)
                    and 0.0 < self.sa_period <= 10.0):
                raise ValueError(f"sa_period must be a period in (0, 10] s, got "
                                 f"{self.sa_period!r}")
            object.__setattr__(self, "sa_period", float(self.sa_period))
        if self.durations is not None:
            d = tuple(float(x) for x in np.atleast_1d(self.durations))
            if len(d) < 2 or any(not (math.isfinite(x) and x > 0) for x in d) or any(
                    b <= a for a, b in zip(d, d[1:], strict=False)):
                raise ValueError(f"durations must be at least two increasing pulse durations "
                                 f"> 0 [s], got {self.durations!r}")
            object.__setattr__(self, "durations", d)
        # the studies' own bounds, checked here so that an assessment refuses them before it
        # writes anything rather than after minutes of its first parts
        for name, least, most in (("duration_count", 2, None), ("amplitude_points", 10, None),
                                  ("fragility_sample_size", 2, MAX_SAMPLES),
                                  ("limit_sample_size", 2, MAX_LIMIT_SAMPLES),
                                  ("fragility_amplitude_points", 8, MAX_GRID_POINTS),
                                  ("record_sample_size", 1, MAX_SAMPLES),
                                  ("rigid_block_fragility_sample_size", 2, MAX_SAMPLES),
                                  ("rigid_block_record_sample_size", 1, MAX_SAMPLES),
                                  ("record_levels", 4, MAX_GRID_POINTS), ("bootstrap", 10, None)):
            object.__setattr__(self, name, check_integer(name, getattr(self, name),
                                                         minimum=least, maximum=most))
        if self.record_count is not None:
            object.__setattr__(self, "record_count",
                               check_integer("record_count", self.record_count, minimum=2))
        if not (isinstance(self.domain_resolution_g, int | float)
                and math.isfinite(self.domain_resolution_g) and self.domain_resolution_g > 0):
            raise ValueError(f"domain_resolution_g must be a finite number > 0 [g], got "
                             f"{self.domain_resolution_g!r}")

    @classmethod
    def quick_settings(cls, **changes) -> AssessmentSettings:
        """The reduced sizes of a quick assessment (:data:`QUICK`): a smoke test within a minute
        (thirty seconds where the two models agree), not an assessment.

        Parameters
        ----------
        **changes
            Settings that replace those of :data:`QUICK` and the defaults.

        Returns
        -------
        AssessmentSettings
        """
        return cls(**{**QUICK, **changes})

    def with_changes(self, **changes) -> AssessmentSettings:
        """These settings with some replaced (validated again)."""
        return replace(self, **changes)

    def intensity_measures(self) -> tuple[str, ...]:
        """The intensity measures of the record-based fragility: ``pga``, ``pgv`` and, with a
        period, ``sa(T)``."""
        out = ("pga", "pgv")
        if self.sa_period is not None:
            from ...ground_motion.suites import stripe_measure

            out += (stripe_measure(f"sa({self.sa_period:g})").name,)
        return out

    def pulse_durations(self, structure) -> tuple[float, ...]:
        """The pulse durations t_p [s] of the failure domains of ``structure``: ``durations``,
        or ``duration_count`` of them from the paper's 0.1 s to 1.0 s scaled by
        :func:`time_scale`, to 0.01 s.

        Parameters
        ----------
        structure : BlockArch

        Returns
        -------
        tuple of float
        """
        if self.durations is not None:
            return self.durations
        scale = time_scale(structure)
        values = np.linspace(*PAPER_DURATIONS, self.duration_count) * scale
        return tuple(sorted({max(0.01, round(float(v), 2)) for v in values}))

    def fragility_durations(self, structure) -> tuple[float, ...]:
        """The pulse durations t_p [s] of the fragility under pulses: the paper's 0.4-0.7 s
        scaled by :func:`time_scale`, to 0.01 s (the quick run: the first and the last).

        Parameters
        ----------
        structure : BlockArch

        Returns
        -------
        tuple of float
        """
        scale = time_scale(structure)
        chosen = PAPER_FRAGILITY_DURATIONS
        if self.quick:
            chosen = (chosen[0], chosen[-1])
        return tuple(sorted({max(0.01, round(t * scale, 2)) for t in chosen}))

    def model_spec(self, name: str = "four-link"):
        """The :class:`~archquake.models.ModelSpec` of model ``name`` with the assessment's
        restitution and friction (every other setting at its default).

        Parameters
        ----------
        name : {"four-link", "rigid-blocks"}
            The model.

        Returns
        -------
        ModelSpec
        """
        from ...models import ModelSpec

        return ModelSpec(name, restitution=self.restitution, friction=self.friction)

    def to_dict(self) -> dict:
        """Every setting by name (what ``results.json`` and ``assessment.json`` record)."""
        out = asdict(self)
        out["durations"] = None if self.durations is None else list(self.durations)
        return out

    @classmethod
    def from_dict(cls, data: dict) -> AssessmentSettings:
        """Inverse of :meth:`to_dict` (a restitution stored under a former name read as the
        current one)."""
        from ...fourlink.impact import stored_restitution_model

        if "restitution" in data:
            data = {**data, "restitution": stored_restitution_model(data["restitution"])}
        return cls(**{k: (tuple(v) if k == "durations" and v is not None else v)
                      for k, v in data.items()})


__all__ = ["AGREEMENT_BAND", "DEFAULT_SUITE", "FALLBACK_RECORDS",
           "PAPER_DURATIONS", "PAPER_FRAGILITY_DURATIONS", "QUICK", "AssessmentSettings",
           "arch_extent", "time_scale"]
