"""The parts of the paper's reproduction: each a function of the settings and of the values it
needs, returning values.

Every arch is built once, as its :class:`~archquake.fourlink.FourLinkModel` (limit analyses,
mechanisms, tables: :func:`paper_arches`); a coefficient of restitution is a variant of it
(:meth:`~archquake.fourlink.FourLinkModel.with_restitution`, which shares the tables:
:class:`RestitutionCase`), and the rigid-block model of the nominal arch is its
:class:`~archquake.rigid_blocks.RigidBlockModel`. A part's value holds what its figures draw
(time histories, the failure domain, the studies' results) and its ``summary``: the JSON-ready
numbers of ``results.json``. So a part can be rerun alone::

    arches = paper_arches(settings)
    cases = restitution_cases(settings, arches)
    pulses = pulse_responses(cases, paper_values())

The numbers come from the library (:mod:`archquake.limit_analysis`,
:mod:`archquake.fourlink`, :mod:`archquake.studies`, :mod:`archquake.rigid_blocks`), the
published ones from ``archquake/data/paper_values.toml``
(:func:`archquake.reference_arches.paper_values`); a verdict of agreement is computed here, from
them, never written by hand.
"""

from __future__ import annotations

import functools
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from ...constants import GRAVITY
from ...reference_arches import oppenheim, paper_values
from ..running import TaskRun, run_here
from .settings import (
    AGREEMENT_BAND,
    ARCH_NAMES,
    PHI_TOLERANCE,
    PULSE_RECORD_TIME,
    Q_TOLERANCE_G,
    ReproductionSettings,
)


# ------------------------------------------------------------------------------ the paper
@functools.lru_cache(maxsize=1)
def _paper() -> dict:
    return paper_values()


def paper_q() -> float:
    """The paper's point Q: failure acceleration of the nominal arch at t_p = 0.40 s [g].

    Returns
    -------
    float
    """
    return float(_paper()["dynamics"]["NA"]["failure_acceleration_tp040"])


def q_agrees(q: float) -> bool:
    """Whether a failure acceleration at t_p = 0.40 s [g] agrees with the paper's point Q
    (within :data:`~archquake.report.paper.settings.Q_TOLERANCE_G`).

    Parameters
    ----------
    q : float
        Failure acceleration [g].

    Returns
    -------
    bool
    """
    return abs(q - paper_q()) < Q_TOLERANCE_G


# ------------------------------------------------------------------------------ arches
@dataclass(frozen=True, eq=False)
class Arches:
    """The paper's three arches, NA, RA-1 and RA-2, each with its four-link model, built once.

    Attributes
    ----------
    models : mapping of str to FourLinkModel
        By name (:data:`~archquake.report.paper.settings.ARCH_NAMES`), with the paper's
        coefficient of restitution (``settings.restitution``).
    """

    models: Mapping

    @property
    def nominal(self):
        """The nominal arch's model (NA, Oppenheim's arch)."""
        return self.models["NA"]

    def arch(self, name: str):
        """The arch named ``name``.

        Parameters
        ----------
        name : str
            ``"NA"``, ``"RA-1"`` or ``"RA-2"``.

        Returns
        -------
        BlockArch
        """
        return self.models[name].arch


def paper_arches(settings: ReproductionSettings, nominal=None) -> Arches:
    """Oppenheim's arch and two irregular arches drawn from it, each with its four-link model.

    RA-1 and RA-2 are arches 0 and 1 of the irregular sample of ``settings.epsilon`` and
    ``settings.seed`` (:func:`archquake.geometry.irregular_sample`): the paper does not give its
    own two.

    Parameters
    ----------
    settings : ReproductionSettings
        The epsilon, seed and coefficient of restitution.
    nominal : CircularArch, optional
        The nominal arch (default :func:`archquake.reference_arches.oppenheim`).

    Returns
    -------
    Arches
    """
    from ...fourlink import FourLinkModel
    from ...geometry import irregular_sample

    nominal = oppenheim() if nominal is None else nominal
    ra = irregular_sample(nominal, settings.epsilon, 2, settings.seed)
    arches = {"NA": nominal, "RA-1": ra[0], "RA-2": ra[1]}
    return Arches({name: FourLinkModel.from_arch(arch, settings.restitution)
                   for name, arch in arches.items()})


def limit_table(arches: Arches, paper: dict) -> dict:
    """Table 1 of the paper: load multipliers and hinges of the three arches, NA beside the
    paper's values [paper, Sect. 3].

    Parameters
    ----------
    arches : Arches
    paper : dict
        The paper's values (:func:`archquake.reference_arches.paper_values`).

    Returns
    -------
    dict
        By arch: ``k_l``, ``k_r``, ``k`` [-], hinge angles ``beta_l``, ``beta_r`` [rad], joints
        and faces; NA also ``paper``, ``difference`` and ``agrees``; RA-1 and RA-2 the paper's
        printed rows and the values of its text.
    """
    table = {}
    for name, model in arches.models.items():
        la_l, la_r = model.limit
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
    return table


def mechanism_tables(arches: Arches, paper: dict) -> tuple[dict, dict]:
    """Tables 2 and 3 of the paper: the four-link mechanisms and their critical angles
    [paper, Sects. 4.1-4.2], NA beside the paper's values.

    Parameters
    ----------
    arches : Arches
    paper : dict
        The paper's values.

    Returns
    -------
    (dict, dict)
        Table 2 and Table 3, by arch and direction (``"l"``, ``"r"``); NA also ``paper``,
        ``difference`` and ``agrees``, RA-1 and RA-2 the paper's rows.
    """
    table2, table3 = {}, {}
    for name, model in arches.models.items():
        table2[name], table3[name] = {}, {}
        for mech in model.mechanisms:
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


# ------------------------------------------------------------------------------ restitution
@dataclass(frozen=True, eq=False)
class RestitutionCase:
    """One coefficient of restitution of the report, applied to the three arches.

    Attributes
    ----------
    name : str
        ``"paper"`` (the paper's c_v, ``settings.restitution``), ``"computed"`` (the nominal
        arch's computed c_v, applied to every arch as the paper applies one value) or
        ``"elastic"`` (c_v = 1).
    pair : (float, float)
        ``(c_lr, c_rl)`` [-] of every arch.
    models : mapping of str to FourLinkModel
        The arches' models with this restitution (variants sharing the tables).
    """

    name: str
    pair: tuple[float, float]
    models: Mapping


def restitution_cases(settings: ReproductionSettings, arches: Arches) -> dict:
    """The two coefficients of restitution of the report: the paper's and the computed one.

    Parameters
    ----------
    settings : ReproductionSettings
        ``restitution``: the paper's c_v.
    arches : Arches

    Returns
    -------
    dict of str to RestitutionCase
        ``"paper"`` and ``"computed"``.
    """
    paper = {name: model.with_restitution(settings.restitution)
             for name, model in arches.models.items()}
    nominal = arches.nominal
    computed = {name: (model.with_restitution("computed") if model is nominal
                       else model.with_restitution("nominal", nominal))
                for name, model in arches.models.items()}
    return {"paper": RestitutionCase("paper", paper["NA"].restitution, paper),
            "computed": RestitutionCase("computed", computed["NA"].restitution, computed)}


def elastic_case(arches: Arches) -> RestitutionCase:
    """The three arches with c_v = 1 (no energy lost at impact; the paper's Figs. 9-11).

    Parameters
    ----------
    arches : Arches

    Returns
    -------
    RestitutionCase
    """
    models = {name: model.with_restitution("elastic") for name, model in arches.models.items()}
    return RestitutionCase("elastic", models["NA"].restitution, models)


def restitution_summary(arches: Arches, cases: dict) -> dict:
    """The coefficients of restitution the report quotes: its cases and the nominal arch's
    link-wise value (the paper's rule, :func:`archquake.fourlink.impact.link_restitution`).

    Parameters
    ----------
    arches : Arches
    cases : dict of str to RestitutionCase

    Returns
    -------
    dict
        ``[c_lr, c_rl]`` by case, and ``"link"``.
    """
    summary = {name: list(case.pair) for name, case in cases.items()}
    summary["link"] = list(arches.nominal.with_restitution("link").restitution)
    return summary


# ------------------------------------------------------------------------------ free vibrations
@dataclass(frozen=True, eq=False)
class FreeVibrations:
    """Free vibrations of the three arches [paper, Sect. 5.2, Figs. 9-14].

    Attributes
    ----------
    histories : dict
        ``histories[case][arch]``: :class:`~archquake.fourlink.time_history.TimeHistory`.
    summary : dict
        ``summary[case]``: ``restitution`` and by arch the peaks of every complete half cycle
        (``peaks_l``, ``peaks_r`` [rad]), ``impacts``, ``outcome`` and ``agrees``.
    """

    histories: dict
    summary: dict

    def agrees(self, case: str) -> bool:
        """Whether all three arches behave as the paper says with the coefficient ``case``.

        Parameters
        ----------
        case : str

        Returns
        -------
        bool
        """
        return all(self.summary[case][n]["agrees"] for n in ARCH_NAMES)


def half_cycle_peaks(history) -> list[tuple[str, float]]:
    """Largest phi [rad] of every complete half cycle of motion (Mech-l or Mech-r segment).

    A half cycle is complete when it ends at an impact; the last one, cut by the end of the
    record, is left out, and so are half cycles below 1e-6 rad (the arch is then at rest to
    the resolution of the integration).

    Parameters
    ----------
    history : TimeHistory

    Returns
    -------
    list of (str, float)
        ``(mechanism, peak phi [rad])`` in order of time.
    """
    moving = [s for s in history.segments if s.mechanism in ("l", "r") and s.phi.size]
    impacts = np.asarray(history.impact_times)
    complete = [s for s in moving if np.any(np.abs(impacts - s.t[-1]) < 1e-9)]
    peaks = [(s.mechanism, float(np.max(s.phi))) for s in complete]
    return [(m, p) for m, p in peaks if p > 1e-6]


def free_vibrations(settings: ReproductionSettings, arches: Arches, cases: dict,
                    paper: dict) -> FreeVibrations:
    """Free vibrations released at the paper's phi0, with c_v = 1 and with each case
    [paper, Sect. 5.2, Figs. 9-14].

    The paper: with c_v = 1 the amplitude differs between the directions but stays constant in
    each; with c_v < 1 it decreases with time.

    Parameters
    ----------
    settings : ReproductionSettings
        ``free_vibration_time``: length of the records [s].
    arches : Arches
    cases : dict of str to RestitutionCase
    paper : dict
        The paper's values (phi0).

    Returns
    -------
    FreeVibrations
    """
    phi0 = paper["dynamics"]["NA"]["free_vibration_phi0"]
    histories, summary = {}, {}
    for case in (elastic_case(arches), *cases.values()):
        histories[case.name], summary[case.name] = {}, {"restitution": list(case.pair)}
        for name in ARCH_NAMES:
            history = case.models[name].free_vibration(phi0, t_end=settings.free_vibration_time)
            peaks = half_cycle_peaks(history)
            histories[case.name][name] = history
            by_dir = {d: [p for m, p in peaks if m == d] for d in ("l", "r")}
            if case.name == "elastic":  # paper: amplitude different, but constant, in each way
                ok = all(np.ptp(v) < 1e-3 * max(v) for v in by_dir.values() if len(v) > 1)
            else:  # paper: the amplitude in each direction decreases with time
                ok = all(np.all(np.diff(v) < 0) for v in by_dir.values() if len(v) > 1)
            summary[case.name][name] = {
                "peaks_l": by_dir["l"], "peaks_r": by_dir["r"],
                "impacts": int(history.impact_times.size), "outcome": history.outcome.status.label,
                "agrees": bool(ok and not history.outcome.collapsed),
            }
    return FreeVibrations(histories, summary)


# ------------------------------------------------------------------------------ pulses
@dataclass(frozen=True, eq=False)
class PulseResponses:
    """Responses to Oppenheim's pulse [paper, Sect. 5.3, Fig. 15].

    Attributes
    ----------
    histories : dict
        ``histories[case][(arch, t_p)]``: time histories.
    summary : dict
        ``summary[case]``: ``restitution``, ``cases`` (per pulse: duration, amplitude and by
        arch the outcome beside the paper's) and ``nominal_agrees``.
    """

    histories: dict
    summary: dict


def _outcome_dict(outcome) -> dict:
    return {"status": outcome.status.label, "half_cycle": outcome.half_cycle,
            "impacts": outcome.impacts, "collapse_time": outcome.collapse_time,
            "max_phi": outcome.max_phi}


def pulse_responses(cases: dict, paper: dict) -> PulseResponses:
    """The paper's three pulses of Fig. 15 on the three arches, with each case.

    Parameters
    ----------
    cases : dict of str to RestitutionCase
    paper : dict
        The paper's values (the pulses and its outcomes).

    Returns
    -------
    PulseResponses
    """
    from ...ground_motion import oppenheim_pulse

    expected = {"NA": paper["dynamics"]["NA"]["pulse_cases"],
                "RA-1": paper["dynamics"]["RA"]["ra1_pulse_cases"],
                "RA-2": paper["dynamics"]["RA"]["ra2_pulse_cases"]}
    histories, summary = {}, {}
    for case in cases.values():
        histories[case.name] = {}
        summary[case.name] = {"restitution": list(case.pair), "cases": []}
        for duration, amplitude, *_ in expected["NA"]:
            motion = oppenheim_pulse(amplitude * GRAVITY, duration)
            row = {"duration": duration, "amplitude": amplitude}
            for name in ARCH_NAMES:
                history = case.models[name].simulate(motion, t_end=PULSE_RECORD_TIME)
                histories[case.name][(name, duration)] = history
                ref = next(r for r in expected[name] if r[0] == duration)
                out = _outcome_dict(history.outcome)
                out["paper"] = {"status": ref[2], "half_cycle": ref[3]}
                out["agrees"] = bool(out["status"] == ref[2] and out["half_cycle"] == ref[3])
                row[name] = out
            summary[case.name]["cases"].append(row)
        summary[case.name]["nominal_agrees"] = all(
            r["NA"]["agrees"] for r in summary[case.name]["cases"])
    return PulseResponses(histories, summary)


# ------------------------------------------------------------------------------ failure domain
@dataclass(frozen=True, eq=False)
class FailureDomainPart:
    """The failure domain of the nominal arch and the point Q [paper, Sect. 5.3.3, Fig. 16].

    Attributes
    ----------
    domain : FailureDomain
        With the paper's coefficient of restitution.
    summary : dict
        ``activation`` (k [-]), ``restitution``, ``q_tp040`` (the failure acceleration at
        t_p = 0.40 s [g] by case) and ``slices``.
    """

    domain: object
    summary: dict


def domain_grid(settings: ReproductionSettings) -> np.ndarray:
    """Amplitudes [g] scanned by the failure domain: from below k (no motion) to the top.

    Parameters
    ----------
    settings : ReproductionSettings

    Returns
    -------
    ndarray
    """
    from ...studies.failure_domain import inclusive_range

    return inclusive_range(0.30, settings.domain_amplitude_max_g, settings.domain_amplitude_step_g)


def failure_domain(settings: ReproductionSettings, arches: Arches,
                   cases: dict) -> FailureDomainPart:
    """Failure domain of the nominal arch over (t_p, xg''/g) with the paper's c_v, and point Q
    to 1e-4 g with each case [paper, Fig. 16].

    Parameters
    ----------
    settings : ReproductionSettings
        The durations, scan and resolution of the domain.
    arches : Arches
    cases : dict of str to RestitutionCase
        ``"paper"`` first.

    Returns
    -------
    FailureDomainPart
    """
    nominal = arches.nominal
    pair = cases["paper"].pair
    grid = domain_grid(settings)
    from ...studies.failure_domain import domain_of

    domain = domain_of(nominal.with_restitution(pair[0]), settings.domain_durations, grid,
                       resolution_g=settings.domain_resolution_g, extend_to_g=None)
    q = {}
    for name, case in cases.items():  # point Q, to 1e-4 g, with both coefficients
        part = domain_of(nominal.with_restitution(case.pair[0]), (0.4,), grid, resolution_g=1e-4,
                         extend_to_g=None)
        q[name] = part.slices[0].failure_acceleration_g
    return FailureDomainPart(domain, {
        "activation": domain.limit_multiplier, "restitution": list(pair), "q_tp040": q,
        "slices": domain.to_list()})


# ------------------------------------------------------------------------------ fragility
@dataclass(frozen=True, eq=False)
class FragilityPart:
    """Fragility curves and surface of the irregular arches and the sample of k~
    [paper, eq. (9), Figs. 17-21].

    Attributes
    ----------
    result : FragilityResult
        The study (:func:`archquake.studies.fragility.run_fragility`).
    curves : list of dict
        Per duration: the nominal failure acceleration, P_F below it, the fits
        (:meth:`archquake.studies.fragility.FragilityResult.summary`).
    limit_sample : dict
        Statistics of k~ over the limit-analysis sample.
    summary : dict
        What ``results.json`` records of the study.
    """

    result: object
    curves: list
    limit_sample: dict
    summary: dict


def below_nominal(curve: dict) -> bool:
    """Whether irregular arches fail below the nominal failure acceleration at one duration (the
    paper's point, Sect. 5.3.3).

    Parameters
    ----------
    curve : dict
        An entry of :attr:`FragilityPart.curves`.

    Returns
    -------
    bool
    """
    below = curve["probability_below_nominal"]
    return below is not None and below > 0.0


def fragility(settings: ReproductionSettings, cases: dict, progress: bool = False
              ) -> FragilityPart:
    """The fragility study of the irregular arches with the paper's c_v (the defaults of the
    command line otherwise).

    Parameters
    ----------
    settings : ReproductionSettings
        Sample sizes, epsilon, seed, durations and amplitudes.
    cases : dict of str to RestitutionCase
        ``"paper"``: the coefficient of restitution.
    progress : bool
        Progress bars of the study on stderr.

    Returns
    -------
    FragilityPart
    """
    from ...execution import default_backend
    from ...models import ModelSpec
    from ...studies.failure_domain import inclusive_range
    from ...studies.fragility import FragilitySettings, run_fragility

    pair = cases["paper"].pair
    study = FragilitySettings(
        sample_size=settings.fragility_sample_size, epsilon=settings.epsilon,
        durations=settings.fragility_durations,
        amplitudes_g=tuple(inclusive_range(settings.amplitude_min_g, settings.amplitude_max_g,
                                           settings.amplitude_step_g).tolist()),
        seed=settings.seed, model=ModelSpec(restitution=pair[0]),
        limit_sample_size=settings.limit_sample_size)
    result = run_fragility(study, progress=progress)
    summary = result.summary()
    return FragilityPart(result, summary["durations"], summary["limit_sample"], {
        "arches": result.settings.sample_size, "restitution": list(pair),
        "backend": default_backend(),
        "durations": result.durations, "amplitudes_g": result.amplitudes_g,
        "failures": result.failures, "failures_l": result.failures_l,
        "failures_r": result.failures_r, "probability": result.probability,
        "curves": summary["durations"]})


# ------------------------------------------------------------------------------ two models
@dataclass(frozen=True, eq=False)
class ComparisonPart:
    """The rigid-block model beside the four-link model of the nominal arch.

    Attributes
    ----------
    comparison : ModelComparison
        :func:`archquake.studies.comparison.compare_models`.
    summary : dict
        What ``results.json`` records: the rows, restitutions, scan, the rigid-block settings,
        the half cycle at failure, the closing impact of the rigid blocks and the cost.
    run : dict
        Where the rigid-block curve ran and what it cost (:meth:`TaskRun.describe`).
    """

    comparison: object
    summary: dict
    run: dict


def comparison_grid(settings: ReproductionSettings) -> np.ndarray:
    """Amplitudes [g] scanned by both models in the comparison: from below k to the top.

    Parameters
    ----------
    settings : ReproductionSettings

    Returns
    -------
    ndarray
    """
    from ...studies.failure_domain import inclusive_range

    return inclusive_range(0.30, settings.comparison_amplitude_max_g,
                           settings.comparison_amplitude_step_g)


def rigid_block_curve(blocks, settings: ReproductionSettings):
    """The rigid-block failure curve of the comparison (a worker's task; the call
    :func:`archquake.studies.comparison.compare_models` makes).

    Parameters
    ----------
    blocks : RigidBlockModel
        The rigid-block model of the nominal arch.
    settings : ReproductionSettings
        The comparison's durations, scan and resolution.

    Returns
    -------
    FailureDomain
        The rigid-block model's failure domain over the comparison's scan (its default search).
    """
    from ...studies.failure_domain import domain_of

    return domain_of(blocks, settings.comparison_durations, comparison_grid(settings),
                     resolution_g=settings.comparison_resolution_g, extend_to_g=None)


def model_comparison(settings: ReproductionSettings, nominal, blocks,
                     curve: TaskRun | None = None) -> ComparisonPart:
    """The rigid-block model beside the four-link model of the nominal arch
    (:func:`archquake.studies.comparison.compare_models`), and how the rigid blocks move on
    after the closing impact of Mech-l (:func:`archquake.rigid_blocks.impacts.closing_impact`).

    Parameters
    ----------
    settings : ReproductionSettings
        The comparison's durations, scan and resolution.
    nominal : FourLinkModel
        The nominal arch's four-link model.
    blocks : RigidBlockModel
        Its rigid-block model (of the same arch).
    curve : TaskRun, optional
        The rigid-block curve (:func:`rigid_block_curve`) if it ran elsewhere; default: run here.

    Returns
    -------
    ComparisonPart
    """
    from ...rigid_blocks.impacts import closing_impact
    from ...studies.comparison import compare_models

    if curve is None:
        curve = run_here(rigid_block_curve, blocks, settings)
    grid = comparison_grid(settings)
    comparison = compare_models(nominal.arch, settings.comparison_durations,
                                amplitudes_g=grid, resolution_g=settings.comparison_resolution_g,
                                settings=blocks.settings, dynamics=nominal,
                                rigid_block=curve.result)
    # how the blocks move on after the closing impact of Mech-l (archquake.fourlink.impact,
    # "measured")
    mech_l, mech_r = nominal.mechanisms
    u_l, u_r = (np.column_stack(m.mode_shape()) for m in (mech_l, mech_r))
    impact = closing_impact(blocks.assembly, u_l, blocks.settings)
    rotation = np.concatenate(([0.0], impact.velocities_after[:, 2], [0.0]))
    hinges = np.flatnonzero(np.abs(np.diff(rotation)) > 1e-3 * np.abs(rotation).max())
    half_cycles = {}
    for name, domain in comparison.four_link.items():
        half_cycles[name] = [next((iv.half_cycle for iv in s.intervals
                                   if iv.status == "collapse"), None) for s in domain.slices]
    block_settings = comparison.settings
    return ComparisonPart(comparison, {
        "rows": comparison.to_list(), "restitution": comparison.restitution,
        "load_multiplier": comparison.load_multiplier,
        "scan_g": [float(comparison.amplitudes_g[0]), float(comparison.amplitudes_g[-1]),
                   settings.comparison_amplitude_step_g],
        "resolution_g": comparison.resolution_g, "friction": block_settings.friction,
        "time_step": block_settings.time_step,
        "coarse_factor": block_settings.coarse_factor, "half_cycle_at_failure": half_cycles,
        "impact": {"energy_ratio": impact.energy_ratio, "mech_r_share": impact.mode_share(u_r),
                   "hinges": hinges.tolist()},
        "backend": curve.ran_on, "rigid_block_seconds": curve.seconds}, curve.describe())


def comparison_statistics(summary: dict) -> dict:
    """What the comparison says, computed from its rows: relative differences per model and
    duration (None: no failure in the scan, or the rigid blocks' is not decided: an undecided
    band below it), from which duration on each model stays within
    :data:`~archquake.defaults.AGREEMENT_BAND`, and the largest differences.

    Parameters
    ----------
    summary : dict
        :attr:`ComparisonPart.summary` (or its JSON form).

    Returns
    -------
    dict
        ``names`` (restitution models), ``durations``, ``rows`` (by duration), ``difference``
        (``[name][t_p]``), ``agree_from`` (by name), ``all_from``, ``within_band`` (by
        duration), ``largest_long``, ``largest_short`` (``(|difference|, name, t_p)``) and
        ``short`` (the durations before ``all_from``).
    """
    rows = sorted(summary["rows"], key=lambda r: r["duration"])
    names = list(summary["restitution"])
    durations = [r["duration"] for r in rows]
    diff = {name: {} for name in names}
    for r in rows:
        for name in names:
            a, b = r["four_link"][name], r["rigid_block"]
            if "failure_undecided_from" in r:  # the rigid blocks' failure is not decided
                b = None
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


def long_pulses_agree(summary: dict) -> bool:
    """Whether the two models agree within the band for every pulse of t_p >= 0.7 s.

    Parameters
    ----------
    summary : dict
        :attr:`ComparisonPart.summary`.

    Returns
    -------
    bool
    """
    stats = comparison_statistics(summary)
    long = [d for d in stats["durations"] if d >= 0.7 - 1e-9]
    return bool(long) and all(stats["within_band"][d] for d in long)


# ------------------------------------------------------------------------------ records
@dataclass(frozen=True, eq=False)
class RecordFragilityPart:
    """Record-based fragility of the nominal arch and its irregular sample in PGA and PGV.

    Attributes
    ----------
    results : dict
        By intensity measure: :class:`~archquake.studies.record_fragility.RecordFragilityResult`.
    summary : dict
        By intensity measure: levels, probabilities, lognormal fits, dispersions, analyses.
    run : dict
        Where the studies ran and what they cost (:meth:`TaskRun.describe`).
    """

    results: dict
    summary: dict
    run: dict


def record_studies(settings: ReproductionSettings) -> dict:
    """The record-based fragility studies of the report (a worker's task):
    :func:`archquake.studies.record_fragility.oppenheim_record_fragility` in PGA and PGV.

    Parameters
    ----------
    settings : ReproductionSettings
        Records, sample size, epsilon, seed, levels and bootstrap.

    Returns
    -------
    dict
        By intensity measure (``"pga"``, ``"pgv"``): the study's result.
    """
    from ...studies.record_fragility import oppenheim_record_fragility

    return oppenheim_record_fragility(
        ("pga", "pgv"), records=settings.record_count, sample_size=settings.record_sample_size,
        epsilon=settings.epsilon, seed=settings.seed, suite_seed=settings.seed,
        levels={"pga": settings.record_levels_pga, "pgv": settings.record_levels_pgv},
        bootstrap=settings.record_bootstrap)


def record_fragility(settings: ReproductionSettings,
                     studies: TaskRun | None = None) -> RecordFragilityPart:
    """Record-based fragility of the nominal arch and its irregular sample in PGA and PGV
    (:func:`record_studies`), summarised.

    Parameters
    ----------
    settings : ReproductionSettings
    studies : TaskRun, optional
        The studies if they ran elsewhere; default: run here.

    Returns
    -------
    RecordFragilityPart
    """
    if studies is None:
        studies = run_here(record_studies, settings)
    summaries = {}
    for im, result in studies.result.items():
        summary = result.summary()
        variability = summary["variability"]
        summaries[im] = {
            "unit": summary["im_unit"], "levels": summary["levels"],
            "records": len(result.records), "sample_size": result.settings.sample_size,
            "restitution": result.settings.model.restitution,
            "probability": summary["probability"],
            "nominal_probability": summary["nominal"]["probability"],
            "lognormal": {k: summary["lognormal"][k] for k in ("median", "dispersion")},
            "nominal_lognormal": {k: summary["nominal"]["lognormal"][k]
                                  for k in ("median", "dispersion")},
            **{k: variability[k] for k in ("record_to_record", "geometric", "total", "srss")},
            "analyses": summary["analyses"],
        }
    return RecordFragilityPart(studies.result, summaries, studies.describe())




# ------------------------------------------------------------------------------ both models
def rigid_block_fragility(settings: ReproductionSettings, pool=None):
    """The fragility study with the rigid-block model: the first
    ``rigid_fragility_sample_size`` arches of the four-link study's sample, on its grid, with the
    default search (:data:`archquake.defaults.DEFAULT_SEARCH`).

    Parameters
    ----------
    settings : ReproductionSettings
    pool : concurrent.futures.Executor, optional
        Where its chunks run (:meth:`archquake.report.running.Background.study`); default: in
        this process.

    Returns
    -------
    FragilityResult
    """
    from ...studies.failure_domain import inclusive_range
    from ...studies.fragility import FragilitySettings, run_fragility

    study = FragilitySettings(
        sample_size=settings.rigid_fragility_sample_size, epsilon=settings.epsilon,
        durations=settings.fragility_durations,
        amplitudes_g=tuple(inclusive_range(settings.amplitude_min_g, settings.amplitude_max_g,
                                           settings.amplitude_step_g).tolist()),
        seed=settings.seed, limit_sample_size=2, model="rigid-blocks")
    return run_fragility(study, backend="serial" if pool is None else "processes", pool=pool,
                         progress=False)


def _failed_arches(result, undecided: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """``(failed[arch, duration, amplitude], analysed[arch])`` of a fragility study: an arch
    fails where it collapses in either direction (with ``undecided``, also where an analysis
    is undecided: the upper bound of P_F)."""
    table = result.table
    h = result.settings.sample_size
    nd, na = len(result.settings.durations), len(result.settings.amplitudes_g)
    status = table["status"].to_numpy().reshape(h, 2, nd, na)
    analysed = (table["excluded"].to_numpy().reshape(h, -1) == "").all(axis=1)
    failing = (status == 2) | (status == -1) if undecided else status == 2
    return np.any(failing, axis=1), analysed


@dataclass(frozen=True, eq=False)
class TwoModelsPart:
    """The paper's failure domain and fragility with both models.

    Attributes
    ----------
    four_link_domain : FailureDomain
        The four-link model (the paper's c_v) over the comparison's durations and scan.
    rigid_domain : FailureDomain
        The rigid-block model over the same (the comparison's rigid-block curve).
    disagreement : Disagreement
        Where they disagree on collapse
        (:func:`archquake.studies.comparison.domain_disagreement`).
    rigid_fragility : FragilityResult
        The rigid-block fragility study.
    summary : dict
        What ``results.json`` records.
    run : dict
        Where the rigid-block study ran and what it cost.
    """

    four_link_domain: object
    rigid_domain: object
    disagreement: object
    rigid_fragility: object
    summary: dict
    run: dict


def two_models(settings: ReproductionSettings, arches: Arches, cases: dict,
               comparison: ComparisonPart, fragility: FragilityPart, rigid: TaskRun
               ) -> TwoModelsPart:
    r"""Fig. 16 and Figs. 17-20 with both models: where they disagree on collapse in (t_p, a),
    and the fragility of the same arches by each, with a multi-fidelity estimate.

    The multi-fidelity estimate of the rigid blocks' P_F over the four-link study's h arches is
    the four-link P_F of all h arches corrected by the mean difference of the two models on the
    m arches both analysed (a control variate with unit coefficient),

    .. math::

        \hat P_F^{RB} = P_F^{FL}(h) + \frac{1}{m}\sum_{i \le m}
        \left(I^{RB}_i - I^{FL}_i\right),

    unbiased for the rigid blocks' P_F of the sample, and more precise than the m rigid-block
    arches alone where the two models' outcomes are correlated.

    Parameters
    ----------
    settings : ReproductionSettings
    arches : Arches
        The nominal arch's four-link model.
    cases : dict of str to RestitutionCase
        ``"paper"``: the coefficient of restitution of the four-link runs.
    comparison : ComparisonPart
        Its rigid-block curve is the rigid-block failure domain.
    fragility : FragilityPart
        The four-link study.
    rigid : TaskRun
        :func:`rigid_block_fragility`, run beside the other parts.

    Returns
    -------
    TwoModelsPart
    """
    from ...studies.comparison import domain_disagreement
    from ...studies.failure_domain import domain_of

    rigid_domain = comparison.comparison.rigid_block
    four_link = arches.nominal.with_restitution(cases["paper"].pair[0])
    four_link_domain = domain_of(four_link, settings.comparison_durations,
                                 comparison_grid(settings),
                                 resolution_g=settings.comparison_resolution_g, extend_to_g=None)
    gap = domain_disagreement(four_link_domain, rigid_domain)
    result = rigid.result
    m = result.settings.sample_size
    fl_failed, fl_analysed = _failed_arches(fragility.result)
    rb_failed, rb_analysed = _failed_arches(result)
    both = fl_analysed[:m] & rb_analysed
    p_fl_all = fl_failed[fl_analysed].mean(axis=0)
    p_fl_same = fl_failed[:m][both].mean(axis=0)
    p_rb_same = rb_failed[both].mean(axis=0)
    p_rb_upper = _failed_arches(result, undecided=True)[0][both].mean(axis=0)
    estimate = np.clip(p_fl_all + (p_rb_same - p_fl_same), 0.0, 1.0)
    difference = p_rb_same - p_fl_same
    worst = np.unravel_index(int(np.argmax(np.abs(difference))), difference.shape)
    table = result.table
    summary = {
        "domain": {"durations": list(gap.durations), "disagreement": gap.to_list(),
                   "width_g": gap.width_g().tolist(),
                   "four_link_failure_g": four_link_domain.failure_accelerations_g.tolist(),
                   "rigid_block_failure_g": rigid_domain.failure_accelerations_g.tolist(),
                   "restitution": list(cases["paper"].pair)},
        "fragility": {
            "arches_rigid_blocks": int(m), "arches_both": int(both.sum()),
            "arches_four_link": int(fl_analysed.sum()),
            "search": result.settings.search,
            "analysed": int(table["analysed"].sum()), "grid_points": len(table),
            "durations": list(result.settings.durations),
            "amplitudes_g": list(result.settings.amplitudes_g),
            "rigid_blocks": p_rb_same, "rigid_blocks_upper": p_rb_upper,
            "undecided": result.summary()["undecided"],
            "four_link_same_arches": p_fl_same,
            "four_link_all": p_fl_all, "multifidelity": estimate,
            "largest_difference": float(difference[worst]),
            "largest_difference_at": {"duration": result.settings.durations[worst[0]],
                                      "amplitude_g": result.settings.amplitudes_g[worst[1]]},
        },
    }
    return TwoModelsPart(four_link_domain, rigid_domain, gap, result, summary,
                         rigid.describe())


__all__ = ["Arches", "ComparisonPart", "FailureDomainPart", "FragilityPart", "FreeVibrations",
           "PulseResponses", "RecordFragilityPart", "RestitutionCase", "TwoModelsPart",
           "below_nominal", "comparison_grid", "comparison_statistics", "domain_grid",
           "elastic_case", "failure_domain", "fragility", "free_vibrations", "half_cycle_peaks",
           "limit_table", "long_pulses_agree", "mechanism_tables", "model_comparison",
           "paper_arches", "paper_q", "pulse_responses", "q_agrees", "record_fragility",
           "record_studies", "restitution_cases", "restitution_summary", "rigid_block_curve",
           "rigid_block_fragility", "two_models"]
