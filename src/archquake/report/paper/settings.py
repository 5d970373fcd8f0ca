"""Settings of the paper's reproduction and the fixed choices of its report.

:class:`ReproductionSettings` is what :func:`archquake.report.reproduce` runs (the defaults are the
paper's study, :meth:`ReproductionSettings.quick_settings` a reduced one); the constants below
are the report's fixed choices: the paper's arches and their colours, the stripes of the
record-based fragility, and the differences called agreement.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field

from ...defaults import AGREEMENT_BAND, COMPARE_DURATIONS, COMPARE_RESOLUTION_G, REPORT_SEED
from ...fourlink.impact import PAPER_RESTITUTION
from ...geometry import check_epsilon

ARCH_NAMES = ("NA", "RA-1", "RA-2")
"""The paper's three arches: the nominal one and two irregular ones [paper, Sect. 3]."""

ARCH_COLOURS = {"NA": "tab:blue", "RA-1": "tab:red", "RA-2": "tab:green"}
"""Colours of the arches in Fig. 15 of the paper: NA blue, RA-1 red, RA-2 green."""

RECORD_LEVELS = {"pga": (0.4, 0.6, 0.8, 1.0, 1.2, 1.4, 1.6, 1.8, 2.0),
                 "pgv": (0.8, 1.2, 1.6, 2.0, 2.4, 2.8, 3.2, 3.6, 4.0)}
"""Stripes of the report's record-based fragility: every other level of
:data:`archquake.studies.record_fragility.DEFAULT_LEVELS` from just above the activation of the
arch."""

PHI_TOLERANCE = 5e-4
"""Largest difference [rad] (or [-] for ratios, [m] / 100 for lengths) called agreement with a
value the paper prints to four decimals (its last digit, plus rounding of the inputs)."""

Q_TOLERANCE_G = 0.01
"""Largest difference [g] called agreement with the paper's point Q, which it reads off its
failure curve to two decimals."""

PULSE_RECORD_TIME = 3.5
"""Length of the records of the pulse responses of Fig. 15 [s]."""


def _durations(start: float, stop: float, step: float) -> tuple[float, ...]:
    count = int(round((stop - start) / step)) + 1
    return tuple(round(start + i * step, 6) for i in range(count))


@dataclass(frozen=True, eq=False)
class ReproductionSettings:
    """Settings of a reproduction; the defaults are the paper's study (Sects. 5.2-5.4).

    Attributes
    ----------
    epsilon : float
        epsilon of the irregular arches [-] (paper: 0.10).
    seed : int
        Root seed of every irregular arch: RA-1 and RA-2 are arches 0 and 1 of the sample, the
        fragility sample is arches 0 .. h-1, the limit-analysis sample arches 0 .. s-1.
    fragility_sample_size : int
        h, irregular arches of the fragility study (paper: 40).
    limit_sample_size : int
        s, irregular arches of the limit-analysis CDF of k~ (paper: 1000).
    amplitude_min_g, amplitude_max_g : float
        Smallest and largest pulse amplitude of the fragility study [g] (the paper does not
        say; 0.2-0.8 g spans the rise of every curve at epsilon = 0.10 and t_p = 0.4-0.7 s).
    amplitude_step_g : float
        Step of the pulse amplitude in the fragility study [g] (paper: 0.01).
    fragility_durations : tuple of float
        Pulse durations t_p of Figs. 17-20 [s] (paper: 0.4, 0.5, 0.6, 0.7).
    domain_durations : tuple of float
        Pulse durations of the failure domain, Fig. 16 [s].
    domain_amplitude_step_g : float
        Scan step of the failure domain [g]; every boundary is then bisected.
    domain_amplitude_max_g : float
        Top of the failure domain [g].
    domain_resolution_g : float
        Bisection width of the failure-domain boundaries [g].
    restitution : float
        Coefficient of restitution c_v of the paper's dynamic results [-] (paper: 0.875).
    free_vibration_time : float
        Length of the free-vibration records [s].
    comparison_durations : tuple of float
        Pulse durations of the comparison of the rigid-block and four-link models [s].
    comparison_amplitude_step_g, comparison_amplitude_max_g : float
        Step and top of the comparison's amplitude scan, from 0.3 g [g].
    comparison_resolution_g : float
        Bisection width of the comparison's boundaries [g].
    record_count : int
        Records of the synthetic suite of the record-based fragility.
    record_sample_size : int
        Irregular arches h of the record-based fragility (plus the nominal arch).
    record_levels_pga, record_levels_pgv : tuple of float
        Stripe levels of the record-based fragility, PGA [g] and PGV [m/s].
    record_bootstrap : int
        Bootstrap resamples of the record-based fragility's bands.
    rigid_fragility_sample_size : int
        Arches of the fragility study with the rigid-block model (the first of the four-link
        study's sample, whose fragility grid it shares): a reduced h, the rigid-block analyses
        being about a thousand times as costly.
    quick : bool
        Reduced sizes for a smoke test (recorded in the report).
    """

    epsilon: float = 0.10
    seed: int = REPORT_SEED
    fragility_sample_size: int = 40
    limit_sample_size: int = 1000
    amplitude_min_g: float = 0.20
    amplitude_max_g: float = 0.80
    amplitude_step_g: float = 0.01
    fragility_durations: tuple[float, ...] = (0.4, 0.5, 0.6, 0.7)
    domain_durations: tuple[float, ...] = field(default_factory=lambda: _durations(0.1, 1.0, 0.05))
    domain_amplitude_step_g: float = 0.05
    domain_amplitude_max_g: float = 3.0
    domain_resolution_g: float = 1e-3
    restitution: float = PAPER_RESTITUTION
    free_vibration_time: float = 5.0
    comparison_durations: tuple[float, ...] = COMPARE_DURATIONS
    comparison_amplitude_step_g: float = 0.1
    comparison_amplitude_max_g: float = 3.0
    comparison_resolution_g: float = COMPARE_RESOLUTION_G
    record_count: int = 8
    record_sample_size: int = 8
    record_levels_pga: tuple[float, ...] = RECORD_LEVELS["pga"]
    record_levels_pgv: tuple[float, ...] = RECORD_LEVELS["pgv"]
    record_bootstrap: int = 200
    rigid_fragility_sample_size: int = 8
    quick: bool = False

    def __post_init__(self):
        check_epsilon(self.epsilon)
        for name in ("fragility_sample_size", "limit_sample_size", "record_count",
                     "record_sample_size", "rigid_fragility_sample_size"):
            value = getattr(self, name)
            if isinstance(value, bool) or not float(value).is_integer() or value < 2:
                raise ValueError(f"{name} must be an integer >= 2, got {value!r}")
        if (isinstance(self.record_bootstrap, bool)
                or not float(self.record_bootstrap).is_integer() or self.record_bootstrap < 10):
            raise ValueError(f"record_bootstrap must be an integer >= 10, got "
                             f"{self.record_bootstrap!r}")
        if isinstance(self.seed, bool) or not float(self.seed).is_integer() or self.seed < 0:
            raise ValueError(f"seed must be an integer >= 0, got {self.seed!r}")
        for name in ("amplitude_min_g", "amplitude_step_g", "amplitude_max_g",
                     "domain_amplitude_step_g", "domain_amplitude_max_g", "domain_resolution_g",
                     "free_vibration_time", "comparison_amplitude_step_g",
                     "comparison_amplitude_max_g", "comparison_resolution_g"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value > 0):
                raise ValueError(f"{name} must be a finite number > 0, got {value!r}")
        if self.amplitude_max_g - self.amplitude_min_g < 6 * self.amplitude_step_g:
            raise ValueError("amplitude_min_g to amplitude_max_g must span at least 6 amplitude "
                             "steps [g] (the fifth-degree fit needs them)")
        if not (0.0 < self.restitution <= 1.0):
            raise ValueError(f"restitution must be in (0, 1], got {self.restitution!r}")
        for name in ("fragility_durations", "domain_durations", "comparison_durations"):
            values = tuple(float(x) for x in getattr(self, name))
            if not values or any(not (math.isfinite(x) and x > 0) for x in values):
                raise ValueError(f"{name} must be pulse durations > 0 [s], got {values!r}")
            object.__setattr__(self, name, values)
        if self.comparison_amplitude_max_g < 0.3 + 2 * self.comparison_amplitude_step_g:
            raise ValueError("comparison_amplitude_max_g must lie at least two steps above the "
                             "start of the comparison's scan, 0.3 g")
        for name in ("record_levels_pga", "record_levels_pgv"):
            values = tuple(float(x) for x in getattr(self, name))
            if len(values) < 2 or any(not (math.isfinite(x) and x > 0) for x in values) or any(
                    b <= a for a, b in zip(values, values[1:], strict=False)):
                raise ValueError(f"{name} must be at least two increasing levels > 0, got "
                                 f"{values!r}")
            object.__setattr__(self, name, values)

    @classmethod
    def quick_settings(cls, **changes) -> ReproductionSettings:
        """Reduced sizes for a smoke test: h = 6, s = 100, 0.05 g steps, 7 domain durations,
        2 comparison durations, 4 records x 4 arches."""
        base = {"fragility_sample_size": 6, "limit_sample_size": 100, "amplitude_step_g": 0.05,
                "domain_durations": (0.1, 0.2, 0.3, 0.4, 0.6, 0.8, 1.0),
                "domain_amplitude_step_g": 0.1, "domain_resolution_g": 5e-3,
                "comparison_durations": (0.3, 0.7), "comparison_resolution_g": 0.01,
                "record_count": 4, "record_sample_size": 4, "record_bootstrap": 50,
                "rigid_fragility_sample_size": 2, "quick": True}
        return cls(**{**base, **changes})

    def to_dict(self) -> dict:
        """Every setting by name (what ``results.json`` records)."""
        return asdict(self)


__all__ = ["AGREEMENT_BAND", "ARCH_COLOURS", "ARCH_NAMES", "PHI_TOLERANCE", "PULSE_RECORD_TIME",
           "Q_TOLERANCE_G", "RECORD_LEVELS", "ReproductionSettings"]
