"""Every table and figure of the paper, regenerated beside the paper's values.

:func:`reproduce` runs the whole chain of the paper on its nominal arch (Oppenheim's arch, "NA")
and on irregular arches drawn with epsilon = 0.10, and writes a report:

- ``report.html``: self-contained (figures embedded as base64 PNG), opens offline;
- ``report.md`` with the PNG files beside it;
- ``results.json``: every number of the report, the settings, the environment and the run times.

Beyond the paper, two sections: how far to trust the four-link model (its failure curve beside
the rigid-block model's, :mod:`comparison`; the rigid-block curve runs on a second process while
the other parts run, so that its compilation and analyses cost a CPU, not the report's time) and
the record-based fragility of the arch and its irregular sample in PGA and PGV
(:mod:`record_fragility`, at a reduced size).

This module only orchestrates: every number comes from the library (:mod:`limit_analysis`,
:mod:`mechanism`, :mod:`impact`, :mod:`time_history`, :mod:`engine`, :mod:`failure_domain`,
:mod:`fragility`, :mod:`comparison`, :mod:`record_fragility`), every figure from
:mod:`plotting`, every published number from
``archquake/data/paper_values.toml`` (:func:`archquake.reference_arches.paper_values`). A
statement of agreement in a caption is computed from the results, never written by hand.
"""

from __future__ import annotations

import base64
import contextlib
import functools
import html
import math
import os
import platform
import sys
import time
from dataclasses import asdict, dataclass, field
from pathlib import Path

import numpy as np

from ._version import __version__
from .defaults import COMPARE_DURATIONS, COMPARE_RESOLUTION_G
from .fourlink.impact import PAPER_RESTITUTION, restitution
from .geometry import GRAVITY
from .reference_arches import oppenheim, paper_values

ARCH_NAMES = ("NA", "RA-1", "RA-2")
"""The paper's three arches: the nominal one and two irregular ones [paper, Sect. 3]."""

ARCH_COLOURS = {"NA": "tab:blue", "RA-1": "tab:red", "RA-2": "tab:green"}
"""Colours of the arches in Fig. 15 of the paper: NA blue, RA-1 red, RA-2 green."""

RECORD_LEVELS = {"pga": (0.4, 0.6, 0.8, 1.0, 1.2, 1.4, 1.6, 1.8, 2.0),
                 "pgv": (0.8, 1.2, 1.6, 2.0, 2.4, 2.8, 3.2, 3.6, 4.0)}
"""Stripes of the report's record-based fragility: every other level of
:data:`archquake.studies.record_fragility.DEFAULT_LEVELS` from just above the activation of the
arch."""

AGREEMENT_BAND = 0.05
"""Relative difference [-] called agreement of the two models' failure accelerations."""

PHI_TOLERANCE = 5e-4
"""Largest difference [rad] (or [-] for ratios, [m] / 100 for lengths) called agreement with a
value the paper prints to four decimals (its last digit, plus rounding of the inputs)."""


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
    quick : bool
        Reduced sizes for a smoke test (recorded in the report).
    """

    epsilon: float = 0.10
    seed: int = 2024
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
    quick: bool = False

    def __post_init__(self):
        if not (0.0 <= self.epsilon < 1.0):
            raise ValueError(f"epsilon must be in [0, 1), got {self.epsilon!r}")
        for name in ("fragility_sample_size", "limit_sample_size", "record_count",
                     "record_sample_size"):
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
                "quick": True}
        return cls(**{**base, **changes})

    def to_dict(self) -> dict:
        return asdict(self)


# ------------------------------------------------------------------------------ helpers
@functools.lru_cache(maxsize=1)
def _paper_values() -> dict:
    return paper_values()


def _paper_q() -> float:
    """The paper's point Q: failure acceleration of the nominal arch at t_p = 0.40 s [g]."""
    return float(_paper_values()["dynamics"]["NA"]["failure_acceleration_tp040"])


def _oppenheim_text() -> str:
    a = _paper_values()["oppenheim"]
    return (f"R = {a['radius']:g} m, alpha = {a['embrace_deg']:g} deg, t = {a['thickness']:g} m, "
            f"n = {a['voussoirs']}")


def _agree(ok: bool) -> str:
    return "agrees" if ok else "differs"


def _outcome_dict(outcome) -> dict:
    return {"status": outcome.status.label, "half_cycle": outcome.half_cycle,
            "impacts": outcome.impacts, "collapse_time": outcome.collapse_time,
            "max_phi": outcome.max_phi}


def _outcome_text(status: str, half_cycle: int) -> str:
    if status == "collapse":
        return f"collapse in half cycle {half_cycle}"
    return status


@dataclass
class _Arches:
    """The three arches with their dynamics (:class:`~archquake.fourlink.FourLinkModel`: limit
    analyses, mechanisms, tables) and views of their parts."""

    arches: dict
    dynamics: dict = field(default_factory=dict)
    limit: dict = field(default_factory=dict)
    mechanisms: dict = field(default_factory=dict)
    tables: dict = field(default_factory=dict)
    """Engine tables of each arch's (Mech-l, Mech-r), built once for all its time histories."""


def _restitution_cases(settings: ReproductionSettings, nominal_mechanisms) -> dict:
    """The two coefficients of restitution of the report: the paper's and the computed one."""
    computed = restitution("computed", *nominal_mechanisms)
    return {"paper": (settings.restitution, settings.restitution),
            "computed": (float(computed[0]), float(computed[1]))}


def _label(case: str, pair) -> str:
    name = "paper's" if case == "paper" else "computed"
    return f"c_v = {pair[0]:.3f} ({name})"


# ------------------------------------------------------------------------------ parts
def _part_limit(settings: ReproductionSettings, paper: dict) -> tuple[_Arches, dict]:
    from .fourlink.dynamics import ArchDynamics
    from .studies.arch_sample import ArchSample

    nominal = oppenheim()
    ra = ArchSample(nominal, settings.epsilon, settings.seed).arches(2)  # the studies' arches 0, 1
    state = _Arches({"NA": nominal, "RA-1": ra[0], "RA-2": ra[1]})
    table = {}
    for name, arch in state.arches.items():
        dynamics = ArchDynamics.from_arch(arch)  # limit analyses, mechanisms, tables
        state.dynamics[name] = dynamics
        la_l, la_r = state.limit[name] = dynamics.limit
        table[name] = {
            "k_l": la_l.load_multiplier, "k_r": la_r.load_multiplier,
            "k": min(la_l.load_multiplier, la_r.load_multiplier),
            "beta_l": la_l.hinge_angles.tolist(), "beta_r": la_r.hinge_angles.tolist(),
            "joints_l": [h.joint for h in la_l.hinges], "joints_r": [h.joint for h in la_r.hinges],
            "faces_l": [h.face for h in la_l.hinges], "faces_r": [h.face for h in la_r.hinges],
        }
    ref = paper["table1"]["NA"]
    ours = table["NA"]
    table["NA"]["paper"] = {"k": ref["load_multiplier"], "beta": ref["beta"],
                            "joints": ref["joints"], "faces": ref["faces"]}
    table["NA"]["difference"] = {
        "k": ours["k"] - ref["load_multiplier"],
        "beta": (np.array(ours["beta_l"]) - np.array(ref["beta"])).tolist(),
    }
    table["NA"]["agrees"] = bool(
        abs(ours["k"] - ref["load_multiplier"]) < PHI_TOLERANCE
        and np.max(np.abs(np.array(ours["beta_l"]) - ref["beta"])) < PHI_TOLERANCE
        and ours["joints_l"] == ref["joints"] and ours["faces_l"] == ref["faces"])
    for name, key in (("RA-1", "RA1"), ("RA-2", "RA2")):
        table[name]["paper_printed"] = paper["table1"][key]
        table[name]["paper_text"] = {"k_l": paper["text"]["RA"][f"{key.lower()}_k_l"],
                                     "k_r": paper["text"]["RA"][f"{key.lower()}_k_r"]}
    return state, table


def _part_mechanisms(state: _Arches, paper: dict) -> tuple[dict, dict]:
    table2, table3 = {}, {}
    for name in state.arches:
        pair = state.mechanisms[name] = state.dynamics[name].mechanisms
        state.tables[name] = state.dynamics[name].tables
        table2[name], table3[name] = {}, {}
        for mech in pair:
            d = mech.direction
            table2[name][d] = {"theta_u": mech.theta_u, "theta_bc_u": mech.theta_bc_u,
                               "theta_cd_u": mech.theta_cd_u, "ab": mech.ab, "bc": mech.bc,
                               "cd": mech.cd, "activation": mech.activation_g}
            table3[name][d] = {"theta_cr": mech.theta_cr, "phi_cr": mech.phi_cr,
                               "ratio": mech.theta_cr / mech.theta_u,
                               "theta_limit": mech.theta_limit}
    ref2, ref3 = paper["table2"]["NA"], paper["table3"]["NA"]
    diff2 = {key: table2["NA"]["l"][key] - ref2[key] for key in ref2}
    table2["NA"]["paper"], table2["NA"]["difference"] = ref2, diff2
    table2["NA"]["agrees"] = bool(all(
        abs(v) < (0.005 if key in ("ab", "bc", "cd") else PHI_TOLERANCE)
        for key, v in diff2.items()))
    diff3 = {key: table3["NA"]["l"][key] - ref3[key] for key in ref3}
    table3["NA"]["paper"], table3["NA"]["difference"] = ref3, diff3
    table3["NA"]["agrees"] = bool(all(
        abs(v) < (0.0005 if key == "ratio" else PHI_TOLERANCE) for key, v in diff3.items()))
    for name, key in (("RA-1", "RA1"), ("RA-2", "RA2")):
        table2[name]["paper"] = paper["table2"][key]
        table3[name]["paper"] = paper["table3"][key]
    return table2, table3


def _half_cycle_peaks(history) -> list[tuple[str, float]]:
    """Largest phi [rad] of every complete half cycle of motion (Mech-l or Mech-r segment).

    A half cycle is complete when it ends at an impact; the last one, cut by the end of the
    record, is left out, and so are half cycles below 1e-6 rad (the arch is then at rest to
    the resolution of the integration).
    """
    moving = [s for s in history.segments if s.mechanism in ("l", "r") and s.phi.size]
    impacts = np.asarray(history.impact_times)
    complete = [s for s in moving if np.any(np.abs(impacts - s.t[-1]) < 1e-9)]
    peaks = [(s.mechanism, float(np.max(s.phi))) for s in complete]
    return [(m, p) for m, p in peaks if p > 1e-6]


def _part_free_vibrations(settings: ReproductionSettings, state: _Arches, paper: dict,
                          cases: dict) -> tuple[dict, dict]:
    from .fourlink.time_history import free_vibration

    phi0 = paper["dynamics"]["NA"]["free_vibration_phi0"]
    histories, summary = {}, {}
    for case, pair in (("elastic", (1.0, 1.0)), *cases.items()):
        histories[case], summary[case] = {}, {"restitution": list(pair)}
        for name in ARCH_NAMES:
            history = free_vibration(state.tables[name], pair, phi0,
                                     t_end=settings.free_vibration_time)
            peaks = _half_cycle_peaks(history)
            histories[case][name] = history
            by_dir = {d: [p for m, p in peaks if m == d] for d in ("l", "r")}
            if case == "elastic":  # paper: amplitude different, but constant, in each direction
                ok = all(np.ptp(v) < 1e-3 * max(v) for v in by_dir.values() if len(v) > 1)
            else:  # paper: the amplitude in each direction decreases with time
                ok = all(np.all(np.diff(v) < 0) for v in by_dir.values() if len(v) > 1)
            summary[case][name] = {
                "peaks_l": by_dir["l"], "peaks_r": by_dir["r"],
                "impacts": int(history.impact_times.size), "outcome": history.outcome.status.label,
                "agrees": bool(ok and not history.outcome.collapsed),
            }
    return histories, summary


def _part_pulses(settings: ReproductionSettings, state: _Arches, paper: dict,
                 cases: dict) -> tuple[dict, dict]:
    from .fourlink.time_history import simulate
    from .ground_motion import oppenheim_pulse

    expected = {"NA": paper["dynamics"]["NA"]["pulse_cases"],
                "RA-1": paper["dynamics"]["RA"]["ra1_pulse_cases"],
                "RA-2": paper["dynamics"]["RA"]["ra2_pulse_cases"]}
    histories, summary = {}, {}
    for case, pair in cases.items():
        histories[case], summary[case] = {}, {"restitution": list(pair), "cases": []}
        for duration, amplitude, *_ in expected["NA"]:
            motion = oppenheim_pulse(amplitude * GRAVITY, duration)
            row = {"duration": duration, "amplitude": amplitude}
            for name in ARCH_NAMES:
                history = simulate(state.tables[name], motion, pair, t_end=3.5)
                histories[case][(name, duration)] = history
                ref = next(r for r in expected[name] if r[0] == duration)
                out = _outcome_dict(history.outcome)
                out["paper"] = {"status": ref[2], "half_cycle": ref[3]}
                out["agrees"] = bool(out["status"] == ref[2] and out["half_cycle"] == ref[3])
                row[name] = out
            summary[case]["cases"].append(row)
        summary[case]["nominal_agrees"] = all(r["NA"]["agrees"] for r in summary[case]["cases"])
    return histories, summary


def _domain_grid(settings: ReproductionSettings) -> np.ndarray:
    """Amplitudes [g] scanned by the failure domain: from below k (no motion) to the top."""
    from .studies.failure_domain import inclusive_range

    return inclusive_range(0.30, settings.domain_amplitude_max_g, settings.domain_amplitude_step_g)


def _part_failure_domain(settings: ReproductionSettings, state: _Arches, cases: dict) -> dict:
    """Failure domain of the nominal arch over (t_p, xg''/g) [paper, Fig. 16] and point Q."""
    from .fourlink.dynamics import ArchDynamics
    from .studies.failure_domain import domain_of

    nominal = state.arches["NA"]
    pair = cases["paper"]
    grid = _domain_grid(settings)
    domain = domain_of(ArchDynamics.from_arch(nominal, pair[0]),
        settings.domain_durations, grid, resolution=settings.domain_resolution_g,
        extend_to_g=None)
    q = {}
    for case, p in cases.items():  # point Q, to 1e-4 g, with both coefficients of restitution
        part = domain_of(ArchDynamics.from_arch(nominal, p[0]),
            (0.4,), grid, resolution=1e-4, extend_to_g=None)
        q[case] = part.slices[0].failure_acceleration_g
    return {"domain": domain, "activation": domain.limit_multiplier, "restitution": list(pair),
            "q_tp040": q}


def _part_fragility(settings: ReproductionSettings, cases: dict, progress: bool) -> dict:
    """Fragility curves, surface and the k~ sample [paper, eq. (9), Figs. 17-21]."""
    from .execution import default_backend
    from .studies.failure_domain import inclusive_range
    from .studies.fragility import FragilitySettings, run_fragility

    study = FragilitySettings(
        sample_size=settings.fragility_sample_size, epsilon=settings.epsilon,
        durations=settings.fragility_durations,
        amplitudes_g=tuple(inclusive_range(settings.amplitude_min_g, settings.amplitude_max_g,
                                           settings.amplitude_step_g).tolist()),
        seed=settings.seed, restitution=cases["paper"][0],
        limit_sample_size=settings.limit_sample_size)
    result = run_fragility(study, progress=progress)  # the defaults of the command line
    return {"result": result, "summary": result.summary(), "backend": default_backend()}


def _comparison_grid(settings: ReproductionSettings) -> np.ndarray:
    """Amplitudes [g] scanned by both models in the comparison: from below k to the top."""
    from .studies.failure_domain import inclusive_range

    return inclusive_range(0.30, settings.comparison_amplitude_max_g,
                           settings.comparison_amplitude_step_g)


def _rigid_block_curve(arch, durations, grid, resolution) -> tuple:
    """The rigid-block failure curve of the comparison and its run time [s] (a worker's task;
    the same call :func:`archquake.studies.comparison.compare_models` makes)."""
    from .rigid_blocks import RigidBlockModel
    from .studies.failure_domain import domain_of

    t0 = time.perf_counter()
    curve = domain_of(RigidBlockModel(arch), durations, grid, resolution=resolution,
                      extend_to_g=None)
    return curve, time.perf_counter() - t0


def _record_studies(settings: ReproductionSettings) -> tuple:
    """The record-based fragility studies of the report and their run time [s] (a worker's
    task): :func:`archquake.studies.record_fragility.oppenheim_record_fragility` in PGA and PGV."""
    from .studies.record_fragility import oppenheim_record_fragility

    t0 = time.perf_counter()
    results = oppenheim_record_fragility(
        ("pga", "pgv"), records=settings.record_count, sample_size=settings.record_sample_size,
        epsilon=settings.epsilon, seed=settings.seed, suite_seed=settings.seed,
        levels={"pga": settings.record_levels_pga, "pgv": settings.record_levels_pgv},
        bootstrap=settings.record_bootstrap)
    return results, time.perf_counter() - t0


def _submit(pool, function, *args) -> dict:
    job = {"submitted": time.perf_counter()}
    job["future"] = pool.submit(function, *args)
    job["future"].add_done_callback(lambda _: job.setdefault("done", time.perf_counter()))
    return job


def _collect(job: dict | None, function, *args) -> tuple:
    """``(result, seconds of the task, wall seconds from submission to end, where it ran)``:
    from the background ``job``, or ``function(*args)`` run here when there is none."""
    if job is None:
        result, seconds = function(*args)
        return result, seconds, seconds, "this process"
    result, seconds = job["future"].result()
    wall = job.get("done", time.perf_counter()) - job["submitted"]
    return result, seconds, wall, "a second process"


def _start_background(settings: ReproductionSettings, stack) -> dict:
    """Start a second process that compiles the rigid-block solver and runs the rigid-block
    curve beside the paper's parts, so that they take a second CPU instead of the report's
    time (:func:`_submit_records` gives it the record studies later). Nothing on a single CPU
    (the parts then run them here)."""
    if (os.cpu_count() or 1) < 2:
        return {}
    from .execution import process_pool
    from .rigid_blocks.model import warm_up

    pool = stack.enter_context(process_pool(1, warm_up=warm_up))
    return {"pool": pool,
            "comparison": _submit(pool, _rigid_block_curve, oppenheim(),
                                  settings.comparison_durations, _comparison_grid(settings),
                                  settings.comparison_resolution_g)}


def _submit_records(settings: ReproductionSettings, background: dict) -> None:
    """Give the second process the record studies, once the four-link engine is compiled and
    cached here (after the failure domain): it then loads the engine instead of compiling it
    a second time."""
    if "pool" in background:
        background["records"] = _submit(background["pool"], _record_studies, settings)


def _part_comparison(settings: ReproductionSettings, state: _Arches, background: dict) -> dict:
    """The rigid-block model beside the four-link model (:func:`compare_models`)."""
    from .studies.comparison import compare_models

    curve, seconds, wall, backend = _collect(
        background.get("comparison"), _rigid_block_curve, state.arches["NA"],
        settings.comparison_durations, _comparison_grid(settings),
        settings.comparison_resolution_g)
    comparison = compare_models(state.arches["NA"], settings.comparison_durations,
                                amplitudes_g=_comparison_grid(settings),
                                resolution=settings.comparison_resolution_g,
                                dynamics=state.dynamics["NA"], rigid_block=curve)
    # how the blocks move on after the closing impact of Mech-l (archquake.fourlink.impact,
    # "blocks")
    from .rigid_blocks.impacts import closing_impact

    mech_l, mech_r = state.dynamics["NA"].mechanisms
    u_l, u_r = (np.column_stack(m.mode_shape()) for m in (mech_l, mech_r))
    impact = closing_impact(state.arches["NA"], u_l, comparison.settings)
    rotation = np.concatenate(([0.0], impact.velocities_after[:, 2], [0.0]))
    hinges = np.flatnonzero(np.abs(np.diff(rotation)) > 1e-3 * np.abs(rotation).max())
    half_cycles = {}
    for name, domain in comparison.four_link.items():
        half_cycles[name] = [next((iv.half_cycle for iv in s.intervals
                                   if iv.status == "collapse"), None) for s in domain.slices]
    block_settings = comparison.settings
    return {"comparison": comparison, "summary": {
        "rows": comparison.to_list(), "restitution": comparison.restitution,
        "load_multiplier": comparison.load_multiplier,
        "scan_g": [float(comparison.amplitudes_g[0]), float(comparison.amplitudes_g[-1]),
                   settings.comparison_amplitude_step_g],
        "resolution_g": comparison.resolution, "friction": block_settings.friction,
        "time_step": block_settings.time_step, "half_cycle_at_failure": half_cycles,
        "impact": {"energy_ratio": impact.energy_ratio, "mech_r_share": impact.mode_share(u_r),
                   "hinges": hinges.tolist()},
        "backend": backend, "rigid_block_seconds": seconds},
        "run": {"ran on": backend, "seconds": seconds, "wall_seconds": wall}}


def _part_record_fragility(settings: ReproductionSettings, background: dict) -> dict:
    """Record-based fragility of the nominal arch and its irregular sample in PGA and PGV
    (:func:`_record_studies`)."""
    results, seconds, wall, backend = _collect(background.get("records"), _record_studies,
                                               settings)
    summaries = {}
    for im, result in results.items():
        summary = result.summary()
        variability = summary["variability"]
        summaries[im] = {
            "unit": summary["im_unit"], "levels": summary["levels"],
            "records": len(result.records), "sample_size": result.settings.sample_size,
            "restitution": result.settings.restitution,
            "probability": summary["probability"],
            "nominal_probability": summary["nominal"]["probability"],
            "lognormal": {k: summary["lognormal"][k] for k in ("median", "dispersion")},
            "nominal_lognormal": {k: summary["nominal"]["lognormal"][k]
                                  for k in ("median", "dispersion")},
            **{k: variability[k] for k in ("record_to_record", "geometric", "total", "srss")},
            "analyses": summary["analyses"],
        }
    run = {"ran on": backend, "seconds": seconds, "wall_seconds": wall}
    return {"results": results, "summary": summaries, "run": run}


# ------------------------------------------------------------------------------ figures
def _save(fig, out: Path, name: str) -> str:
    path = out / name
    fig.savefig(path, dpi=110)
    import matplotlib.pyplot as plt

    plt.close(fig)
    return name


def _fig_limit(out: Path, state: _Arches, table1: dict) -> list[dict]:
    import matplotlib.pyplot as plt

    from .plotting import plot_limit_analysis

    figures = []
    fig, ax = plt.subplots(figsize=(7.0, 4.6), constrained_layout=True)
    plot_limit_analysis(state.limit["NA"][0], ax)
    ax.set_title(f"Oppenheim's arch NA, Mech-l: k = {table1['NA']['k']:.4f}")
    paper_k = table1["NA"]["paper"]["k"]
    figures.append({
        "file": _save(fig, out, "fig02_nominal_arch.png"), "paper_figure": "Fig. 2",
        "agrees": table1["NA"]["agrees"],
        "caption": (f"Collapse hinges and thrust line of Oppenheim's arch NA. The paper's Fig. 2 "
                    f"shows hinges A, B, C, D at joints {table1['NA']['paper']['joints']} "
                    f"(intrados, extrados, intrados, extrados) and k = {paper_k:.4f}; ours: "
                    f"joints {table1['NA']['joints_l']}, k = {table1['NA']['k']:.4f} - "
                    f"{_agree(table1['NA']['agrees'])}."),
    })
    fig, axes = plt.subplots(2, 2, figsize=(12.0, 8.6), constrained_layout=True)
    nominal = state.arches["NA"]
    for row, name in enumerate(("RA-1", "RA-2")):
        for col, res in enumerate(state.limit[name]):
            frame = nominal if res.direction == "l" else nominal.mirrored()
            plot_limit_analysis(res, axes[row, col], nominal=frame)
            mech = "Mech-l" if res.direction == "l" else "Mech-r (mirrored arch)"
            axes[row, col].set_title(f"{name}, {mech}: k~ = {res.load_multiplier:.4f}")
    figures.append({
        "file": _save(fig, out, "fig04_irregular_arches.png"), "paper_figure": "Fig. 4",
        "agrees": None,
        "caption": ("Collapse hinges and thrust lines of the irregular arches RA-1 and RA-2 "
                    "(black) over the nominal arch (red); Mech-r on the mirrored arch. The paper's "
                    "Fig. 4 shows the same for its own two random arches, whose geometry is not "
                    "given: these are two arches drawn with the report's seed, so only the kind "
                    "of result is comparable (hinges move away from the nominal joints, k~_l "
                    "differs from k~_r)."),
    })
    return figures


def _fig_energy(out: Path, state: _Arches, table3: dict) -> dict:
    import matplotlib.pyplot as plt

    from .plotting import plot_potential_energy

    fig, axes = plt.subplots(1, 3, figsize=(14.0, 4.2), constrained_layout=True)
    for ax, name in zip(axes, ARCH_NAMES, strict=True):
        mechs = state.mechanisms[name]
        phi_max = 1.6 * max(m.phi_cr for m in mechs)
        for mech, colour in zip(mechs, ("tab:blue", "tab:orange"), strict=True):
            label = ("Mech-l" if mech.direction == "l" else "Mech-r")
            plot_potential_energy(mech, ax, label=label, color=colour, phi_max=phi_max)
        fig_no = {"NA": "Fig. 6", "RA-1": "Fig. 7", "RA-2": "Fig. 8"}[name]
        ax.set_title(f"{name} ({fig_no} of the paper)")
    ours, ref = table3["NA"]["l"]["phi_cr"], table3["NA"]["paper"]["phi_cr"]
    return {
        "file": _save(fig, out, "fig06_08_potential_energy.png"), "paper_figure": "Figs. 6-8",
        "agrees": table3["NA"]["agrees"],
        "caption": (f"Potential energy V(phi) - V(0) of the four-link mechanisms (eq. 3). The "
                    f"paper's Fig. 6 has its maximum at phi_cr = {ref:.4f} rad for NA; ours at "
                    f"{ours:.4f} rad - {_agree(table3['NA']['agrees'])}. Figs. 7-8 show the "
                    f"paper's random arches (phi_cr 0.1765/0.1545 and 0.1723/0.0627 rad); ours "
                    f"are other draws: phi_cr = {table3['RA-1']['l']['phi_cr']:.4f}/"
                    f"{table3['RA-1']['r']['phi_cr']:.4f} (RA-1) and "
                    f"{table3['RA-2']['l']['phi_cr']:.4f}/{table3['RA-2']['r']['phi_cr']:.4f} "
                    f"rad (RA-2), Mech-l/Mech-r."),
    }


def _fig_free(out: Path, histories: dict, summary: dict, case: str, pair) -> dict:
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(3, 1, figsize=(9.0, 8.0), sharex=True, constrained_layout=True)
    for ax, name in zip(axes, ARCH_NAMES, strict=True):
        _plot_history(histories[case][name], ax, name, 0.03)
        ax.set_title(rf"{name}: free vibration from $\phi_0$ = 0.02 rad, $c_v$ = {pair[0]:.3f}",
                     fontsize=10)
        if ax is not axes[-1]:
            ax.set_xlabel("")
    ok = all(summary[case][n]["agrees"] for n in ARCH_NAMES)
    if case == "elastic":
        file, figs = "fig09_11_free_vibration_elastic.png", "Figs. 9-11"
        claim = ("with c_v = 1 the amplitude of the oscillation differs between the "
                 "directions but stays constant in each")
    else:
        file = f"fig12_14_free_vibration_{case}.png"
        figs = "Figs. 12-14"
        claim = (f"with c_v < 1 (the paper uses 0.875; here {_label(case, pair)}) the amplitude "
                 "in each direction decreases with time")
    return {"file": _save(fig, out, file), "paper_figure": figs, "agrees": ok,
            "caption": (f"Free vibrations of NA, RA-1 and RA-2 released at phi0 = 0.02 rad with "
                        f"zero velocity (+phi in Mech-l, -phi' in Mech-r). Paper ({figs}): "
                        f"{claim}. Ours: {_agree(ok)} for all three arches.")}


def _plot_history(history, ax, name: str, phi_limit: float):
    from .plotting import plot_rotation_history

    out = history.outcome
    text = _outcome_text(out.status.label, out.half_cycle)
    plot_rotation_history(history, ax, label=f"{name}: {text}", color=ARCH_COLOURS[name],
                          linewidth=1.2)
    ax.set_ylim(-phi_limit, phi_limit)
    ax.set_ylabel(r"$\phi$ (Mech-l), $-\phi'$ (Mech-r) [rad]")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="upper right", fontsize=8)


def _fig_pulse(out: Path, histories: dict, summary: dict, case: str, pair) -> dict:
    import matplotlib.pyplot as plt

    from .ground_motion import oppenheim_pulse
    from .plotting import plot_ground_motion

    rows = summary[case]["cases"]
    fig, axes = plt.subplots(len(rows) + 1, 1, figsize=(9.0, 10.5), sharex=True,
                             constrained_layout=True)
    for row, colour in zip(rows, ("0.1", "tab:purple", "tab:brown"), strict=True):
        plot_ground_motion(oppenheim_pulse(row["amplitude"] * GRAVITY, row["duration"]),
                           axes[0], t_end=3.5, color=colour,
                           label=f"$t_p$ = {row['duration']:.2f} s")
    axes[0].set_title(r"(a) ground acceleration: Oppenheim's pulse, $\ddot{x}_g/g = -1$ for $t_p$, "
                      r"then $+1/2$ for $2 t_p$", fontsize=10)
    axes[0].set_xlabel("")
    for ax, row, letter in zip(axes[1:], rows, "bcd", strict=True):
        for name in ARCH_NAMES:
            _plot_history(histories[case][(name, row["duration"])], ax, name, 0.35)
        ax.set_title(rf"({letter}) $t_p$ = {row['duration']:.2f} s, {_label(case, pair)}",
                     fontsize=10)
        if ax is not axes[-1]:
            ax.set_xlabel("")
    parts = []
    for row in rows:
        na = row["NA"]
        parts.append(f"t_p = {row['duration']:.2f} s: paper {_outcome_text(**na['paper'])}, ours "
                     f"{_outcome_text(na['status'], na['half_cycle'])} ({_agree(na['agrees'])})")
    ok = summary[case]["nominal_agrees"]
    return {"file": _save(fig, out, f"fig15_pulse_response_{case}.png"),
            "paper_figure": "Fig. 15", "agrees": ok,
            "caption": ("Response to Oppenheim's pulse xg''/g = -1 (a) of NA (blue), RA-1 (red) "
                        f"and RA-2 (green), {_label(case, pair)}; open circles mark impacts, a "
                        "dotted line the point of no return of a collapse, after which phi grows "
                        "to the kinematic limit. "
                        "Nominal arch - " + "; ".join(parts) + f". Overall: {_agree(ok)}.")}


def _fig_failure_domain(out: Path, domain: dict) -> dict:
    import matplotlib.pyplot as plt

    from .plotting import plot_failure_domain

    fig, ax = plt.subplots(figsize=(8.0, 5.6), constrained_layout=True)
    plot_failure_domain(domain["domain"], ax)
    q = domain["q_tp040"]["paper"]
    ax.plot([0.4], [q], "s", color="black", markersize=7, zorder=6)
    ax.annotate(f"Q (0.40 s, {q:.2f} g)", (0.4, q), textcoords="offset points", xytext=(8, 8),
                fontsize=9, fontweight="bold")
    paper_q = _paper_q()
    ok = abs(q - paper_q) < 0.01
    return {"file": _save(fig, out, "fig16_failure_domain.png"), "paper_figure": "Fig. 16",
            "agrees": ok,
            "caption": ("Failure domain of Oppenheim's arch (epsilon = 0) under Oppenheim's pulse "
                        "of duration t_p and amplitude xg''/g, c_v = "
                        f"{domain['restitution'][0]:.3f}: recovery, collapse after impacts "
                        "(second half cycle or later), collapse in the first half cycle; "
                        f"dashed: k = {domain['activation']:.4f}, below which the arch does not "
                        "move. At short durations the outcome is not monotone in the amplitude "
                        "(bands of recovery inside the collapse region). The paper reads "
                        f"Q = (0.40 s, {paper_q:.2f} g) off its failure curve; ours {q:.3f} g - "
                        f"{_agree(ok)}.")}


def _fig_fragility(out: Path, frag: dict) -> list[dict]:
    import matplotlib.pyplot as plt

    from .plotting import plot_fragility_curve

    result, summary = frag["result"], frag["summary"]
    figures = []
    for j, entry in enumerate(summary["durations"]):
        duration = entry["duration"]
        fig, ax = plt.subplots(figsize=(7.5, 6.2), constrained_layout=True)
        plot_fragility_curve(result, duration, ax)
        q = entry["nominal_failure_acceleration"]
        below = entry["probability_below_nominal"]
        ok = below is not None and below > 0.0
        paper_q = f" (the paper: {_paper_q():.2f} g)" if abs(duration - 0.4) < 1e-9 else ""
        number = 17 + j
        fig_name = f"Fig. {number}" if number <= 20 else "(no figure in the paper)"
        figures.append({
            "file": _save(fig, out, f"fig{number}_fragility_tp{duration:.2f}.png"),
            "paper_figure": fig_name, "agrees": ok,
            "caption": (f"Fragility curve at t_p = {duration:.2f} s: P_F = h_f/h (eq. 9) of "
                        f"h = {result.settings.sample_size} irregular arches, an arch failing when "
                        "it collapses under the pulse in either direction, with the paper's "
                        "fifth-degree polynomial and a lognormal fit; blue: CDF of "
                        "k~ = min(k~_l, k~_r) of "
                        f"s = {result.limit_load_multipliers.size} arches by limit analysis; "
                        "vertical lines: the nominal arch's k (blue) and failure acceleration "
                        f"{_f(q, 3)} g{paper_q} (black). The paper's point: irregular arches "
                        "may fail below the nominal failure acceleration (P_F > 0 left of the "
                        f"black line, where eq. 10 gives 0); ours: P_F = {_f(below, 3)} at the "
                        f"last step below it - {_agree(ok)}."),
        })
    return figures


def _fig_surface(out: Path, frag: dict) -> dict:
    import matplotlib.pyplot as plt

    from .plotting import plot_fragility_surface

    result, summary = frag["result"], frag["summary"]
    fig = plt.figure(figsize=(8.5, 6.4), constrained_layout=True)
    ax = fig.add_subplot(projection="3d")
    plot_fragility_surface(result, ax)
    below = [e for e in summary["durations"]
             if e["probability_below_nominal"] is not None and e["probability_below_nominal"] > 0]
    ok = len(below) > 0
    where = ", ".join(f"{e['duration']:.2f} s" for e in below) or "none"
    return {"file": _save(fig, out, "fig21_fragility_surface.png"), "paper_figure": "Fig. 21",
            "agrees": ok,
            "caption": ("Fragility surface P_F(t_p, xg''/g) of the irregular arches (epsilon = "
                        f"{result.settings.epsilon:.2f}), plane facets between the fragility "
                        "curves as in the paper, with the nominal arch's step surface (eq. 10, "
                        "the paper's 'cylinder'). The paper's point: part of the surface lies at "
                        "lower accelerations than the cylinder, where the nominal arch predicts "
                        f"P_F = 0; ours: P_F > 0 below the nominal failure acceleration at "
                        f"t_p = {where} - {_agree(ok)}.")}


def _fig_comparison(out: Path, comparison, summary: dict) -> dict:
    import matplotlib.pyplot as plt

    from .plotting import plot_model_comparison, plot_model_differences

    fig, (left, right) = plt.subplots(1, 2, figsize=(14.5, 5.6), constrained_layout=True,
                                      width_ratios=(1.2, 1.0))
    plot_model_comparison(comparison, left)
    plot_model_differences(comparison, right)
    stats = _comparison_stats(summary)
    long = [d for d in stats["durations"] if d >= 0.7 - 1e-9]
    ok = bool(long) and all(stats["within_band"][d] for d in long)
    return {"file": _save(fig, out, "comparison_rigid_blocks.png"),
            "paper_figure": "Rigid blocks beside four links", "agrees": ok,
            "caption": ("Failure acceleration of Oppenheim's arch under Oppenheim's pulse in the "
                        "rigid-block model (black) and in the four-link model with each "
                        "restitution model (left), and their relative difference (right). "
                        "For long pulses (t_p >= 0.7 s) the two models should agree within 5 %: "
                        + ("they do" if ok else "they do not") + " - " + _agree(ok) + ".")}


def _fig_record_fragility(out: Path, record: dict) -> dict:
    import matplotlib.pyplot as plt

    from .plotting import plot_record_fragility

    fig, axes = plt.subplots(1, 2, figsize=(13.0, 5.2), constrained_layout=True)
    for ax, (im, result) in zip(axes, record["results"].items(), strict=True):
        plot_record_fragility(result, ax)
        ax.set_title(f"Record-based fragility in {im.upper()}, $\\varepsilon$ = "
                     f"{result.settings.epsilon:g}")
    parts = []
    for im, entry in record["summary"].items():
        fit = entry["lognormal"]
        parts.append(f"{im.upper()}: median {_f(fit['median'], 3)} {entry['unit']}, "
                     f"dispersion {_f(fit['dispersion'], 3)}")
    first = next(iter(record["summary"].values()))
    return {"file": _save(fig, out, "record_fragility.png"),
            "paper_figure": "Record-based fragility", "agrees": None,
            "caption": (f"P(collapse | IM) of {first['sample_size']} irregular arches under "
                        f"{first['records']} synthetic records in both polarities (black dots: "
                        "the stripes; line: lognormal fit by maximum likelihood, grey its 90 % "
                        "bootstrap band) and of the nominal arch (blue squares, dashed fit): "
                        + "; ".join(parts) + ". The paper has no such figure (its conclusion "
                        "names earthquake excitation as further work).")}


# ------------------------------------------------------------------------------ report text
def _f(x, digits: int = 4) -> str:
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "-"
    return f"{x:.{digits}f}"


def _signed(x, digits: int = 4) -> str:
    return "-" if x is None else f"{x:+.{digits}f}"


def _table1_rows(table1: dict) -> list[list[str]]:
    na = table1["NA"]
    rows = [["NA, Mech-l", "k", _f(na["paper"]["k"]), _f(na["k_l"]),
             _signed(na["difference"]["k"])]]
    for label, ref, ours, diff in zip("ABCD", na["paper"]["beta"], na["beta_l"],
                                      na["difference"]["beta"], strict=True):
        rows.append(["NA, Mech-l", f"beta_{label} [rad]", _f(ref), _f(ours), _signed(diff)])
    rows.append(["NA, Mech-r", "k", _f(na["paper"]["k"]), _f(na["k_r"]),
                 _signed(na["k_r"] - na["paper"]["k"])])
    for name in ("RA-1", "RA-2"):
        ra = table1[name]
        printed, text = ra["paper_printed"], ra["paper_text"]
        for d in ("l", "r"):
            mech = "Mech-l" if d == "l" else "Mech-r"
            rows.append([f"{name}, {mech}", "k~",
                         f"{_f(printed['load_multiplier_' + d])} (text {_f(text['k_' + d])})",
                         _f(ra["k_" + d]), "other arch"])
            rows.append([f"{name}, {mech}", "beta A, B, C, D [rad]",
                         ", ".join(_f(b) for b in printed["beta_" + d]),
                         ", ".join(_f(b) for b in ra["beta_" + d]), "other arch"])
    return rows


_TABLE2_KEYS = (("theta_u", "theta_u [rad]"), ("theta_bc_u", "theta_BC(theta_u) [rad]"),
                ("theta_cd_u", "theta_CD(theta_u) [rad]"), ("ab", "AB [m]"), ("bc", "BC [m]"),
                ("cd", "CD [m]"))


def _table2_rows(table2: dict) -> list[list[str]]:
    rows = []
    na = table2["NA"]
    for key, label in _TABLE2_KEYS:
        rows.append([label, _f(na["paper"][key]), _f(na["l"][key]), _f(na["r"][key]),
                     _signed(na["difference"][key]),
                     _f(table2["RA-1"]["paper"][key]), _f(table2["RA-1"]["l"][key]),
                     _f(table2["RA-2"]["paper"][key]), _f(table2["RA-2"]["l"][key])])
    rows.append(["theta'_u (Mech-r) [rad]", _f(na["paper"]["theta_u"]), "-", _f(na["r"]["theta_u"]),
                 _signed(na["r"]["theta_u"] - na["paper"]["theta_u"]),
                 _f(table2["RA-1"]["paper"]["theta_u_r"]), _f(table2["RA-1"]["r"]["theta_u"]),
                 _f(table2["RA-2"]["paper"]["theta_u_r"]), _f(table2["RA-2"]["r"]["theta_u"])])
    return rows


def _table3_rows(table3: dict) -> list[list[str]]:
    na = table3["NA"]
    rows = [["NA, Mech-l", _f(na["paper"]["theta_cr"]), _f(na["l"]["theta_cr"]),
             _f(na["paper"]["phi_cr"]), _f(na["l"]["phi_cr"]), _f(na["paper"]["ratio"], 3),
             _f(na["l"]["ratio"], 3), _signed(na["difference"]["ratio"], 4)],
            ["NA, Mech-r", _f(na["paper"]["theta_cr"]), _f(na["r"]["theta_cr"]),
             _f(na["paper"]["phi_cr"]), _f(na["r"]["phi_cr"]), _f(na["paper"]["ratio"], 3),
             _f(na["r"]["ratio"], 3), _signed(na["r"]["ratio"] - na["paper"]["ratio"], 4)]]
    for name in ("RA-1", "RA-2"):
        ref = table3[name]["paper"]
        for d in ("l", "r"):
            ours = table3[name][d]
            rows.append([f"{name}, {'Mech-l' if d == 'l' else 'Mech-r'}",
                         _f(ref["theta_cr_" + d]), _f(ours["theta_cr"]), _f(ref["phi_cr_" + d]),
                         _f(ours["phi_cr"]), _f(ref["ratio_" + d], 3), _f(ours["ratio"], 3),
                         "other arch"])
    return rows


def _agreement_rows(results: dict) -> list[list[str]]:
    t1, t2, t3 = results["table1"]["NA"], results["table2"]["NA"], results["table3"]["NA"]
    rows = [["k (Table 1)", _f(t1["paper"]["k"]), _f(t1["k"]), _signed(t1["difference"]["k"])]]
    for label, ref, ours in zip("ABCD", t1["paper"]["beta"], t1["beta_l"], strict=True):
        rows.append([f"beta_{label} [rad] (Table 1)", _f(ref), _f(ours), _signed(ours - ref)])
    for key, label in _TABLE2_KEYS:
        rows.append([f"{label} (Table 2)", _f(t2["paper"][key]), _f(t2["l"][key]),
                     _signed(t2["difference"][key])])
    for key, label, digits in (("theta_cr", "theta_cr [rad]", 4), ("phi_cr", "phi_cr [rad]", 4),
                               ("ratio", "theta_cr/theta_u", 3)):
        rows.append([f"{label} (Table 3, Sect. 4.2)", _f(t3["paper"][key], digits),
                     _f(t3["l"][key], digits), _signed(t3["difference"][key], 4)])
    pulses = results["pulse"]["paper"]
    for row in pulses["cases"]:
        na = row["NA"]
        rows.append([f"Fig. 15, NA, t_p = {row['duration']:.2f} s, c_v = "
                     f"{pulses['restitution'][0]:.3f}", _outcome_text(**na["paper"]),
                     _outcome_text(na["status"], na["half_cycle"]), _agree(na["agrees"])])
    if "failure_domain" in results:
        q = results["failure_domain"]["q_tp040"]["paper"]
        rows.append([f"Q: failure acceleration at t_p = 0.40 s [g], c_v = "
                     f"{pulses['restitution'][0]:.3f}", _f(_paper_q(), 2), _f(q, 3),
                     _signed(q - _paper_q(), 3)])
    return rows


def _restitution_rows(results: dict) -> list[list[str]]:
    rows = []
    for case in ("paper", "computed"):
        pulses = results["pulse"][case]
        label = _label(case, pulses["restitution"])
        for row in pulses["cases"]:
            na = row["NA"]
            rows.append([label, f"Fig. 15, t_p = {row['duration']:.2f} s",
                         _outcome_text(**na["paper"]),
                         _outcome_text(na["status"], na["half_cycle"]), _agree(na["agrees"])])
        if "failure_domain" in results:
            q = results["failure_domain"]["q_tp040"][case]
            rows.append([label, "Q at t_p = 0.40 s [g]", _f(_paper_q(), 2), _f(q, 3),
                         _agree(abs(q - _paper_q()) < 0.01)])
    return rows


def _notes(results: dict) -> list[str]:
    c = results["restitution"]["computed"][0]
    lk = results["restitution"]["link"][0]
    s = results["settings"]
    return [
        "1. Coefficient of restitution. The paper uses c_v = 0.875 for Oppenheim's arch, "
        "quoting De Lorenzis et al. (2007). Three models give three numbers. 'computed' (the "
        "package's default): the momentum balance of the whole arch through the impact, with "
        "impulses at the closing joints and at the hinges of the post-impact mechanism, gives "
        f"c_v = {c:.4f} for this 7-voussoir arch (about 0.73 in the limit of many voussoirs), "
        "and the kinetic energy never grows at an impact. 'link': the paper's own rule read "
        "link by link as Housner does for a block (the post-impact springing link turns about "
        "the opposite face of the same springing joint, its angular momentum conserved, the "
        f"impulse at its other hinge neglected) gives c_v = {lk:.4f} with the annular-sector "
        "voussoirs of this arch and 0.875 with flat-faced voussoirs: that is the paper's "
        "number. It is not a consistent momentum balance: the neglected impulse is what sets "
        "the other links moving, their momentum is left out, and the rate of one link is taken "
        "for the rate of the mechanism's coordinate. 'paper': 0.875 imposed. This report uses "
        "the paper's 0.875 for every figure that reproduces the paper and shows the computed "
        "value beside it (Figs. 12-15, point Q). With the computed value the irregular arches "
        "take the nominal arch's value, as the paper applies one value to all arches. The table "
        "below gives the outcomes with both.",
        "2. Table 1 swaps the k~ values of RA-1 and RA-2 relative to the text of Sect. 3 (text: "
        "RA-1 k~_l = 0.4111, k~_r = 0.3104; RA-2 k~_l = 0.3946, k~_r = 0.3501). The geometry of "
        "RA-1 and RA-2 is not given in the paper, so they cannot be regenerated: this report "
        "draws two irregular arches of the same kind (epsilon = 0.10) from a fixed seed and "
        "shows the paper's rows beside them for scale only.",
        "3. Table 2's Mech-r rows have missing and shifted cells; for NA, Mech-r equals Mech-l by "
        "symmetry (ours: identical to round-off), and only theta'_u of RA-1 and RA-2 is legible.",
        "4. 'Mech-1' in the paper's text and captions is Mech-l (left).",
        "5. Not stated by the paper, chosen here: g = 9.81 m/s^2; density 2000 kg/m^3 (it cancels "
        "from every result); the sum of the voussoir angles of an irregular arch is kept equal "
        "to the nominal embrace by rescaling the drawn angles; the amplitude range of the "
        f"fragility scan ({s['amplitude_min_g']:.2f} to {s['amplitude_max_g']:.2f} g, which spans "
        f"the "
        "rise of every curve); the seed of the irregular arches; an irregular arch 'fails' "
        "when it collapses under the pulse in either direction (the paper analyses both and "
        "counts arches, h_f <= h); the collapse test ('ever-increasing phi') is the energy "
        "criterion of archquake.fourlink.engine: after the excitation an arch moving away from "
        "theta_u "
        "with more energy than V(theta_cr), or beyond theta_cr and not returning, collapses; "
        "during the excitation, reaching the kinematic limit of the linkage is collapse.",
    ]


def _comparison_stats(summary: dict) -> dict:
    """What the comparison's paragraph says, computed from its rows: relative differences per
    model and duration (None: no failure in the scan), from which duration on each model stays
    within :data:`AGREEMENT_BAND`, and the largest differences."""
    rows = sorted(summary["rows"], key=lambda r: r["duration"])
    names = list(summary["restitution"])
    durations = [r["duration"] for r in rows]
    diff = {name: {} for name in names}
    for r in rows:
        for name in names:
            a, b = r["four_link"][name], r["rigid_block"]
            diff[name][r["duration"]] = None if a is None or b is None else a / b - 1.0
    within = {name: {d: v is not None and abs(v) <= AGREEMENT_BAND for d, v in diff[name].items()}
              for name in names}
    agree_from = {}
    for name in names:
        start = None
        for d in reversed(durations):
            if not within[name][d]:
                break
            start = d
        agree_from[name] = start
    all_from = (None if any(v is None for v in agree_from.values())
                else max(agree_from.values()))
    within_band = {d: all(within[name][d] for name in names) for d in durations}

    def largest(ds):
        pairs = [(abs(diff[n][d]), n, d) for n in names for d in ds if diff[n][d] is not None]
        return max(pairs) if pairs else None

    long = [d for d in durations if all_from is not None and d >= all_from]
    short = [d for d in durations if all_from is None or d < all_from]
    return {"names": names, "durations": durations, "rows": rows, "difference": diff,
            "agree_from": agree_from, "all_from": all_from, "within_band": within_band,
            "largest_long": largest(long), "largest_short": largest(short), "short": short}


def _percent(x) -> str:
    return "-" if x is None else f"{100 * x:+.1f} %"


def _comparison_text(summary: dict) -> list[str]:
    """The paragraphs of the comparison section, every number from ``summary``."""
    st = _comparison_stats(summary)
    k = summary["load_multiplier"]
    c = summary["restitution"]
    top = summary["scan_g"][1]
    names, diff, rows = st["names"], st["difference"], st["rows"]
    models = ", ".join(f"{n} (c_v = {c[n][0]:.3f})" for n in names)
    text = [(f"The same arch in the package's two models: the four-link model of the paper "
             f"(one degree of freedom, the hinges of the limit analysis, impacts by a "
             f"coefficient of restitution c_v) with each restitution model - {models} - and "
             f"the rigid-block model (every voussoir a block, unilateral contacts with Coulomb "
             f"friction mu = {summary['friction']:g} at both ends of every joint, Newton "
             f"impacts with restitution 0, time step {1000 * summary['time_step']:g} ms; "
             f"'blocks' is the c_v measured on its impacts). Failure acceleration: the lowest "
             f"amplitude of Oppenheim's pulse that collapses the arch, both models on the same "
             f"scan ({summary['scan_g'][0]:g}-{top:g} g in {summary['scan_g'][2]:g} g steps) "
             f"with every boundary bisected to {summary['resolution_g']:g} g; the same numbers "
             f"as `archquake compare`.")]
    if st["all_from"] is not None:
        size, name, d = st["largest_long"]
        early = [f"{n} from {st['agree_from'][n]:.2f} s" for n in names
                 if st["agree_from"][n] < st["all_from"]]
        longest = rows[-1]
        a = longest["rigid_block"]
        text.append(
            f"Long pulses agree. From t_p = {st['all_from']:.2f} s on, the four-link failure "
            f"acceleration is within {100 * AGREEMENT_BAND:g} % of the rigid-block one with "
            f"every restitution model (largest: {name}, {_percent(diff[name][d])} at "
            f"{d:.2f} s)" + (f"; {', '.join(early)}" if early else "") + ". Both models "
            f"then fail close to the static load multiplier k = {k:.3f}, which they share (the "
            f"rigid blocks start to move within 1 % of k, a tested property): at t_p = "
            f"{longest['duration']:.2f} s the rigid blocks fail at {a:.3f} g, "
            f"{100 * (a / k - 1):.1f} % above k, and the impact law, which decides the rest, "
            f"moves the answer little.")
    else:
        text.append(f"No duration of the comparison has every restitution model within "
                    f"{100 * AGREEMENT_BAND:g} % of the rigid-block model.")
    if st["short"]:
        first = rows[0]
        parts = []
        for n in names:
            v = first["four_link"][n]
            parts.append(f"{v:.3f} g ({n}, {_percent(diff[n][first['duration']])})"
                         if v is not None else f"more than {top:g} g ({n})")
        rb = first["rigid_block"]
        rb_text = f"{rb:.3f} g" if rb is not None else f"more than {top:g} g"
        largest = st["largest_short"]
        impact = summary["impact"]
        by_duration = {n: dict(zip([r["duration"] for r in summary["rows"]],
                                   summary["half_cycle_at_failure"][n], strict=True))
                       for n in names}
        after_impact = [n for n in names
                        if all((by_duration[n][d] or 0) >= 2 for d in st["short"])]
        first_swing = [n for n in names if n not in after_impact]
        blocks = ""
        if "blocks" in names:
            close = [d for d in st["short"] if diff["blocks"][d] is not None]
            if close:
                worst = max(abs(diff["blocks"][d]) for d in close)
                blocks = (f" With the c_v measured on the blocks ({c['blocks'][0]:.3f}) the "
                          f"four-link model comes within {100 * worst:.1f} % of the rigid "
                          f"blocks at t_p = {', '.join(f'{d:g}' for d in close)} s")
                missing = [d for d in st["short"] if diff["blocks"][d] is None]
                blocks += (f", but not at {', '.join(f'{d:g}' for d in missing)} s."
                           if missing else ".")
        text.append(
            f"Short pulses differ. At t_p = {first['duration']:.2f} s the rigid blocks fail at "
            f"{rb_text}, the four-link model at " + ", ".join(parts)
            + (f"; the largest difference below {st['all_from']:.2f} s is "
               f"{_percent(diff[largest[1]][largest[2]])} ({largest[1]}, t_p = "
               f"{largest[2]:.2f} s)" if largest and st["all_from"] is not None else "")
            + ". A short pulse must be several times k to overturn the arch. At the failure "
              "acceleration of the four-link model the arch collapses after an impact (half "
              "cycle 2 or later) with " + (", ".join(after_impact) or "no model")
            + ("; with " + ", ".join(first_swing) + " it survives the impacts at some short "
               "durations, and falls only in its first swing, at a far higher amplitude (or "
               "beyond the scan)"
               if first_swing else "")
            + ". So the energy an impact leaves decides, and the four-link answer depends "
              "strongly on c_v. The rigid "
              f"blocks do not move on in a four-link mechanism after an impact: at the closing "
              f"of Mech-l they keep {100 * impact['energy_ratio']:.0f} % of the kinetic "
              f"energy, of which {100 * (1 - impact['mech_r_share']):.0f} % moves outside "
              f"Mech-r, with hinges at joints {', '.join(map(str, impact['hinges']))} "
              f"(archquake.fourlink.impact, model 'blocks'), so no single c_v reproduces them."
            + blocks)
    bands_fl = sorted({r["duration"] for r in rows for v in r["recovery_above"]["four_link"]
                       .values() if v})
    bands_rb = [r["duration"] for r in rows if r["recovery_above"]["rigid_block"]]
    text.append(
        f"Above its failure acceleration the four-link model recovers again in a band at "
        f"{len(bands_fl)} of the {len(rows)} durations (between its collapse after an impact and "
        f"its collapse in the first half cycle, as in Fig. 16), the rigid-block model at "
        f"{len(bands_rb)}" + (f" ({', '.join(f'{d:g}' for d in bands_rb)} s)" if bands_rb
                              else "") + f" (on this scan: a band narrower than "
        f"{summary['scan_g'][2]:g} g can be missed). Cost: the rigid-block curve ran on "
        f"{summary['backend']}" + (" beside the paper's parts" if summary["backend"] !=
                                   "this process" else "")
        + f" ({summary['rigid_block_seconds']:.1f} s of analyses, after the compilation of "
          f"its solver); the four-link curves take well under a second.")
    return text


def _comparison_rows(summary: dict) -> list[list[str]]:
    st = _comparison_stats(summary)
    top = summary["scan_g"][1]
    out = []
    for r in st["rows"]:
        rb = r["rigid_block"]
        cells = [f"{r['duration']:.2f}", _f(rb, 3) if rb is not None else f"> {top:g}"]
        for n in st["names"]:
            v = r["four_link"][n]
            cells.append(f"> {top:g}" if v is None else
                         f"{v:.3f}" + ("" if rb is None else f" ({_percent(v / rb - 1)})"))
        bands = [("rigid blocks", r["recovery_above"]["rigid_block"]),
                 *r["recovery_above"]["four_link"].items()]
        cells.append("; ".join(f"{n} " + ", ".join(f"{a:.2f}-{b:.2f}" for a, b in v)
                               for n, v in bands if v) or "-")
        out.append(cells)
    return out


def _record_rows(record: dict) -> list[list[str]]:
    rows = []
    for im, e in record.items():
        rows.append([f"{im.upper()} [{e['unit']}]", _f(e["lognormal"]["median"], 3),
                     _f(e["total"], 3), _f(e["nominal_lognormal"]["median"], 3),
                     _f(e["record_to_record"], 3), _f(e["geometric"], 3), _f(e["srss"], 3)])
    return rows


def _record_text(record: dict, settings: dict) -> str:
    pga, pgv = record["pga"], record["pgv"]
    analyses = sum(e["analyses"]["total"] for e in record.values())
    integrated = sum(e["analyses"]["integrated"] for e in record.values())
    return (
        f"The paper's conclusion names earthquake excitation as further work: the fragility of "
        f"Oppenheim's arch and of {pga['sample_size']} irregular arches (epsilon = "
        f"{settings['epsilon']:.2f}, seed {settings['seed']}, arches 0-"
        f"{pga['sample_size'] - 1} of the fragility sample) against {pga['records']} synthetic "
        f"ground motions (archquake.studies.record_fragility.STOCHASTIC_SUITE, a modulated, "
        f"filtered "
        f"white noise, seed {settings['seed']}), each scaled to {len(pga['levels'])} levels of "
        f"PGA ({pga['levels'][0]:g}-{pga['levels'][-1]:g} g) and of PGV "
        f"({pgv['levels'][0]:g}-{pgv['levels'][-1]:g} m/s) and applied in both polarities "
        f"(multiple-stripe analysis; an arch-record pair fails if it collapses in either), "
        f"restitution '{pga['restitution']}': {analyses} analyses, {integrated} of them "
        f"integrated (the others never reach the arch's activation). Lognormal fragility "
        f"functions fitted by maximum likelihood on the stripes (Baker 2015); dispersions: "
        f"record-to-record (the nominal arch's fit), geometric (a common dispersion of "
        f"per-record fits to the irregular arches) and total (all pairs pooled), with "
        f"sqrt(rtr^2 + geo^2) beside the total for comparison; bands: "
        f"{settings['record_bootstrap']} bootstrap resamples. The sizes are reduced to fit the "
        f"report's time budget (the full study is 40 arches x 20 records x 20 levels: "
        f"`archquake fragility --records ...` or examples/record_fragility.py --full). "
        + " ".join(_weaker(im, e) for im, e in record.items()))


def _weaker(im: str, entry: dict) -> str:
    """How much lower the irregular arches' median is than the nominal arch's (the paper's
    point for pulses, Sect. 5.3.3, seen here with records)."""
    ours, nominal = entry["lognormal"]["median"], entry["nominal_lognormal"]["median"]
    if ours is None or nominal is None:
        return f"{im.upper()}: no lognormal fit for both."
    return (f"In {im.upper()} the median of the irregular arches is {ours:.3f} {entry['unit']}, "
            f"{100 * abs(1 - ours / nominal):.0f} % {'below' if ours < nominal else 'above'} "
            f"the nominal arch's {nominal:.3f} "
            f"{entry['unit']}.")


def _environment() -> dict:
    import matplotlib
    import numba
    import scipy

    return {"archquake": __version__, "python": sys.version.split()[0],
            "platform": platform.platform(), "numpy": np.__version__, "scipy": scipy.__version__,
            "numba": numba.__version__, "matplotlib": matplotlib.__version__,
            "processors": __import__("os").cpu_count()}


def _sections(results: dict, figures: dict) -> list[tuple[str, list]]:
    s = results["settings"]
    intro = [
        ("p", "The paper: 'Dynamic response of masonry arch with geometrical irregularities "
              "subjected to a pulse-type ground motion'. Nominal arch: Oppenheim's arch NA "
              f"({_oppenheim_text()}). Irregular arches: epsilon "
              f"epsilon = {s['epsilon']:.2f}, seed {s['seed']}. Coefficient of restitution of "
              f"the paper's dynamic results: c_v = {s['restitution']:.3f}."
              + (" QUICK RUN: reduced sample sizes, not the paper's study."
                 if s["quick"] else "")),
        ("table", ["quantity (nominal arch)", "paper", "ours", "difference"],
         _agreement_rows(results)),
    ]
    sections = [("Agreement with the paper", intro)]
    sections.append(("Table 1: activation (limit analysis)", [
        ("p", "Horizontal load multipliers and progressive angles of the collapse hinges (Mech-r "
              "in the mirrored frame, as in the paper). RA-1 and RA-2 are our own draws; the "
              "paper's rows are given beside them for scale (Table 1 as printed, the text's k~ in "
              "brackets)."),
        ("table", ["arch, mechanism", "quantity", "paper", "ours", "difference"],
         _table1_rows(results["table1"])),
        ("figure", figures["fig02"]), ("figure", figures["fig04"]),
    ]))
    sections.append(("Table 2: four-link mechanisms", [
        ("table", ["quantity", "paper NA", "ours NA Mech-l", "ours NA Mech-r", "difference NA",
                   "paper RA-1", "ours RA-1", "paper RA-2", "ours RA-2"],
         _table2_rows(results["table2"])),
    ]))
    sections.append(("Table 3: critical angles and potential energy", [
        ("table", ["arch, mechanism", "theta_cr paper", "theta_cr ours", "phi_cr paper",
                   "phi_cr ours", "theta_cr/theta_u paper", "ours", "difference"],
         _table3_rows(results["table3"])),
        ("figure", figures["fig06"]),
    ]))
    sections.append(("Free vibrations (Figs. 9-14)", [
        ("figure", figures["fig09"]), ("figure", figures["fig12_paper"]),
        ("figure", figures["fig12_computed"]),
    ]))
    sections.append(("Pulse responses (Fig. 15)", [
        ("figure", figures["fig15_paper"]), ("figure", figures["fig15_computed"]),
    ]))
    if "fig16" in figures:
        sections.append(("Failure domain (Fig. 16)", [("figure", figures["fig16"])]))
    if "fragility" in results:
        ls = results["limit_sample"]
        frag_blocks = [
            ("p", f"Limit-analysis sample: s = {ls['count']} arches, k~ = min(k~_l, k~_r): mean "
                  f"{ls['mean']:.4f}, standard deviation {ls['std']:.4f}, range "
                  f"[{ls['min']:.4f}, {ls['max']:.4f}]; {100 * ls['fraction_below_nominal']:.1f} "
                  "% of the arches start moving below the nominal k = "
                  f"{_paper_values()['table1']['NA']['load_multiplier']:.2f}. Dynamic sample: h = "
                  f"{results['fragility']['arches']} arches, amplitude step "
                  f"{s['amplitude_step_g']:.2f} g."),
            ("table", ["t_p [s]", "nominal failure acceleration [g]", "lognormal median [g]",
                       "lognormal dispersion", "P_F just below the nominal failure acceleration"],
             [[f"{c['duration']:.2f}", _f(c["nominal_failure_acceleration"], 3),
               _f(c["lognormal_median"], 3), _f(c["lognormal_dispersion"], 3),
               _f(c["probability_below_nominal"], 3)]
              for c in results["fragility"]["curves"]]),
        ]
        frag_blocks += [("figure", f) for f in figures["fragility"]]
        frag_blocks.append(("figure", figures["fig21"]))
        sections.append(("Fragility curves and surface (Figs. 17-21)", frag_blocks))
    if "comparison" in results:
        c = results["comparison"]
        header = ["t_p [s]", "rigid blocks [g]"] + [
            f"four-link, {n} c_v = {pair[0]:.3f} [g]" for n, pair in c["restitution"].items()
        ] + ["recovery above the failure acceleration [g]"]
        blocks = [("p", t) for t in _comparison_text(c)]
        blocks += [("table", header, _comparison_rows(c)), ("figure", figures["comparison"])]
        sections.append(("How far to trust the four-link model", blocks))
    if "record_fragility" in results:
        sections.append(("Record-based fragility (PGA, PGV)", [
            ("p", _record_text(results["record_fragility"], s)),
            ("table", ["IM [unit]", "median, irregular arches", "total dispersion",
                       "median, nominal arch", "record-to-record dispersion",
                       "geometric dispersion", "sqrt(rtr^2 + geo^2)"],
             _record_rows(results["record_fragility"])),
            ("figure", figures["record_fragility"]),
        ]))
    notes = [("p", n) for n in _notes(results)]
    notes.append(("table", ["c_v", "case", "paper", "ours", "verdict"],
                  _restitution_rows(results)))
    sections.append(("Where the paper is wrong or silent, and the choices made", notes))
    env = results["environment"]
    runtime = [("table", ["part", "wall time [s]"],
                [[k, f"{v:.2f}"] for k, v in results["timings"].items() if k != "report"])]
    if results.get("background"):
        runtime.append(("p", "Run beside the parts above (a part waits for its result):"))
        runtime.append(("table", ["task", "ran on", "analyses [s]",
                                  "from submission to result [s]"],
                        [[k, v["ran on"], f"{v['seconds']:.2f}", f"{v['wall_seconds']:.2f}"]
                         for k, v in results["background"].items()]))
    sections.append(("Runtime and environment", [
        *runtime,
        ("p", ", ".join(f"{k} {v}" for k, v in env.items()) + f"; seed {s['seed']}."),
        ("p", "Settings: " + ", ".join(f"{k} = {v}" for k, v in s.items()) + "."),
    ]))
    if results.get("missing"):
        sections.append(("Not reproduced", [("p", m) for m in results["missing"]]))
    return sections


def _html_table(header, rows) -> str:
    head = "".join(f"<th>{html.escape(h)}</th>" for h in header)
    body = "".join("<tr>" + "".join(f"<td>{html.escape(str(c))}</td>" for c in row) + "</tr>"
                   for row in rows)
    return f"<table><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>"


_CSS = ("body{font-family:sans-serif;max-width:1100px;margin:2em auto;line-height:1.4}"
        "table{border-collapse:collapse;margin:1em 0;font-size:0.9em}"
        "td,th{border:1px solid #bbb;padding:3px 8px;text-align:left}"
        "th{background:#eee}figure{margin:1.5em 0}img{max-width:100%}"
        "figcaption{font-size:0.92em;color:#333}.agrees{color:#070}.differs{color:#b00}")


def _verdict(figure: dict) -> str:
    if figure["agrees"] is None:
        return "no comparison"
    return "agrees" if figure["agrees"] else "differs"


def _write_html(path: Path, out: Path, sections) -> None:
    parts = ["<!DOCTYPE html><html><head><meta charset='utf-8'><title>archquake: the paper, "
             f"regenerated</title><style>{_CSS}</style></head><body>",
             "<h1>The paper, regenerated</h1>"]
    for title, blocks in sections:
        parts.append(f"<h2>{html.escape(title)}</h2>")
        for kind, *content in blocks:
            if kind == "p":
                parts.append(f"<p>{html.escape(content[0])}</p>")
            elif kind == "table":
                parts.append(_html_table(*content))
            else:
                fig = content[0]
                data = base64.b64encode((out / fig["file"]).read_bytes()).decode("ascii")
                verdict = _verdict(fig)
                parts.append(
                    f"<figure><img alt='{html.escape(fig['paper_figure'])}' "
                    f"src='data:image/png;base64,{data}'><figcaption><b>{fig['paper_figure']}"
                    f"</b> (<span class='{verdict.split()[0]}'>{verdict}</span>). "
                    f"{html.escape(fig['caption'])}</figcaption></figure>")
    parts.append("</body></html>")
    path.write_text("\n".join(parts), encoding="utf-8")


def _md_table(header, rows) -> str:
    def cell(c):
        return str(c).replace("|", "\\|")

    lines = ["| " + " | ".join(cell(h) for h in header) + " |",
             "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(cell(c) for c in row) + " |" for row in rows]
    return "\n".join(lines)


def _write_markdown(path: Path, sections) -> None:
    parts = ["# The paper, regenerated", ""]
    for title, blocks in sections:
        parts += [f"## {title}", ""]
        for kind, *content in blocks:
            if kind == "p":
                parts += [content[0], ""]
            elif kind == "table":
                parts += [_md_table(*content), ""]
            else:
                fig = content[0]
                parts += [f"![{fig['paper_figure']}]({fig['file']})", "",
                          f"**{fig['paper_figure']}** ({_verdict(fig)}). {fig['caption']}", ""]
    path.write_text("\n".join(parts), encoding="utf-8")


# ------------------------------------------------------------------------------ driver
def _jsonable(obj):
    """Plain JSON values: arrays to lists, NaN to None, tuple keys to strings."""
    if isinstance(obj, dict):
        return {str(k): _jsonable(v) for k, v in obj.items()}
    if isinstance(obj, list | tuple):
        return [_jsonable(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return _jsonable(obj.tolist())
    if isinstance(obj, np.generic):
        return _jsonable(obj.item())
    if isinstance(obj, float) and not math.isfinite(obj):
        return None
    return obj


@dataclass(frozen=True)
class Reproduction:
    """Result of :func:`reproduce`.

    Attributes
    ----------
    results : dict
        Every number of the report (also written to ``results.json``).
    directory : Path
        Where ``report.html``, ``report.md``, ``results.json`` and the figures are.
    figures : tuple of str
        File names of the figures (PNG) in ``directory``.
    """

    results: dict
    directory: Path
    figures: tuple[str, ...]


def reproduce(out_dir, settings: ReproductionSettings | None = None, *,
              progress: bool = True) -> Reproduction:
    """Regenerate every table and figure of the paper and write the report into ``out_dir``.

    Parameters
    ----------
    out_dir : str or Path
        Output directory (created if needed); existing report files are overwritten.
    settings : ReproductionSettings, optional
        Default: the paper's study (h = 40, s = 1000, 0.01 g steps).
    progress : bool
        Show a progress bar over the parts on stderr.

    Returns
    -------
    Reproduction
    """
    import matplotlib

    matplotlib.use("Agg")
    from tqdm.auto import tqdm

    from .results_io import write_json

    settings = ReproductionSettings() if settings is None else settings
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    paper = paper_values()
    results: dict = {"settings": settings.to_dict(), "environment": _environment(),
                     "timings": {}, "background": {}, "missing": []}
    store: dict = {}
    figures: dict = {}
    started = time.perf_counter()

    def part_limit():
        store["state"], results["table1"] = _part_limit(settings, paper)

    def part_mechanisms():
        results["table2"], results["table3"] = _part_mechanisms(store["state"], paper)
        store["cases"] = _restitution_cases(settings, store["state"].mechanisms["NA"])
        results["restitution"] = {k: list(v) for k, v in store["cases"].items()}
        results["restitution"]["link"] = list(restitution("link",
                                                          *store["state"].mechanisms["NA"]))

    def part_free():
        store["free"], results["free_vibration"] = _part_free_vibrations(
            settings, store["state"], paper, store["cases"])

    def part_pulses():
        store["pulse"], results["pulse"] = _part_pulses(settings, store["state"], paper,
                                                        store["cases"])

    def part_domain():
        store["domain"] = _part_failure_domain(settings, store["state"], store["cases"])
        d = store["domain"]
        results["failure_domain"] = {
            "activation": d["activation"], "restitution": d["restitution"],
            "q_tp040": d["q_tp040"], "slices": d["domain"].to_list()}
        _submit_records(settings, background)

    def part_fragility():
        store["fragility"] = _part_fragility(settings, store["cases"], progress)
        summary = store["fragility"]["summary"]
        result = store["fragility"]["result"]
        results["limit_sample"] = summary["limit_sample"]
        results["fragility"] = {
            "arches": result.settings.sample_size, "restitution": list(store["cases"]["paper"]),
            "backend": store["fragility"]["backend"],
            "durations": result.durations, "amplitudes_g": result.amplitudes_g,
            "failures": result.failures, "failures_l": result.failures_l,
            "failures_r": result.failures_r, "probability": result.probability,
            "curves": summary["durations"]}

    def part_records():
        store["records"] = _part_record_fragility(settings, background)
        results["record_fragility"] = store["records"]["summary"]
        results["background"]["record studies"] = store["records"]["run"]
        figures["record_fragility"] = _fig_record_fragility(out, store["records"])

    def part_comparison():
        store["comparison"] = _part_comparison(settings, store["state"], background)
        results["comparison"] = store["comparison"]["summary"]
        results["background"]["rigid-block curve"] = store["comparison"]["run"]
        figures["comparison"] = _fig_comparison(out, store["comparison"]["comparison"],
                                                results["comparison"])

    def part_figures():
        state, cases = store["state"], store["cases"]
        fig2, fig4 = _fig_limit(out, state, results["table1"])
        figures.update(fig02=fig2, fig04=fig4)
        figures["fig06"] = _fig_energy(out, state, results["table3"])
        figures["fig09"] = _fig_free(out, store["free"], results["free_vibration"], "elastic",
                                     (1.0, 1.0))
        for case, pair in cases.items():
            figures[f"fig12_{case}"] = _fig_free(out, store["free"], results["free_vibration"],
                                                 case, pair)
            figures[f"fig15_{case}"] = _fig_pulse(out, store["pulse"], results["pulse"], case,
                                                  pair)
        figures["fig16"] = _fig_failure_domain(out, store["domain"])
        figures["fragility"] = _fig_fragility(out, store["fragility"])
        figures["fig21"] = _fig_surface(out, store["fragility"])

    parts = [("limit analysis (Table 1)", part_limit),
             ("four-link mechanisms (Tables 2-3)", part_mechanisms),
             ("free vibrations (Figs. 9-14)", part_free),
             ("pulse responses (Fig. 15)", part_pulses),
             ("failure domain (Fig. 16)", part_domain),
             ("fragility and k~ sample (Figs. 17-21)", part_fragility),
             ("figures", part_figures),
             ("rigid blocks beside four links", part_comparison),
             ("record-based fragility", part_records)]
    with contextlib.ExitStack() as stack:
        # the rigid-block curve and the record studies run on a second CPU meanwhile
        background = _start_background(settings, stack)
        bar = tqdm(parts, desc="reproduce", unit="part", disable=not progress, file=sys.stderr)
        for name, run in bar:
            bar.set_postfix_str(name)
            t0 = time.perf_counter()
            run()
            results["timings"][name] = time.perf_counter() - t0
    t0 = time.perf_counter()
    results["figures"] = _flat_figures(figures)
    results["timings"]["report"] = 0.0
    results["timings"]["total"] = time.perf_counter() - started
    results = _jsonable(results)
    sections = _sections(results, figures)
    _write_html(out / "report.html", out, sections)
    _write_markdown(out / "report.md", sections)
    results["timings"]["report"] = time.perf_counter() - t0
    results["timings"]["total"] = time.perf_counter() - started
    write_json(out / "results.json", results)
    bar.close()
    names = tuple(f["file"] for f in _flat_figures(figures).values())
    return Reproduction(results, out, names)


def _flat_figures(figures: dict) -> dict:
    flat = {}
    for value in figures.values():
        if isinstance(value, list):
            for f in value:
                flat[Path(f["file"]).stem] = f
        else:
            flat[Path(value["file"]).stem] = value
    return flat
