"""The parts of an assessment of one structure under its own weight and under pulses: each a
function of the structure, the settings and the values it needs, returning values.

A part's value holds what its figures draw (limit analyses, models, failure domains, the
studies' results) and its ``summary``: the JSON-ready numbers of ``results.json``, computed here
by the library's own calls, so that a test can recompute any of them with the single call
(:func:`archquake.limit_analysis.both_directions`,
:func:`archquake.studies.failure_domain.domain_of`,
:func:`archquake.studies.fragility.run_fragility`):

- :func:`limit_part`: does the structure stand, its load multipliers and hinges both ways (its
  geometric safety factor is :func:`archquake.limit_analysis.geometric_safety_factor`);
- :func:`four_link_part`: the four-link model, its mechanisms and the restitution of every rule;
- :func:`pulse_grid`, :func:`four_link_domains`, :func:`rigid_block_domain`,
  :func:`pulse_part`: the failure domains under pulses of both models, and where they disagree;
- :func:`trusted_model`: which model the first screen's numbers come from (the rigid-block
  model where the two disagree);
- :func:`irregularity_part`: the k~ sample and the fragility under pulses of the irregular
  arches (:func:`fragility_amplitudes` chooses the amplitudes).

The record-based fragility is in :mod:`archquake.report.assess.records`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...checks import json_float
from .settings import AGREEMENT_BAND, AssessmentSettings

DIRECTIONS = ("l", "r")
"""The two directions of a mechanism: Mech-l (forces left to right) and Mech-r."""


# ------------------------------------------------------------------------------ limit analysis
@dataclass(frozen=True, eq=False)
class LimitPart:
    """Whether the structure stands, and its limit analyses both ways.

    Attributes
    ----------
    analyses : (LimitAnalysis, LimitAnalysis) or None
        Mech-l and Mech-r (:func:`archquake.limit_analysis.both_directions`); None when the
        structure cannot stand or never collapses.
    summary : dict
        ``verdict`` (``stands``, ``part``, ``reason``, ``margin``, ``collapses``) and, when it
        collapses, ``k_l``, ``k_r``, ``k`` [-], ``governing`` (the direction of the smaller
        multiplier; Mech-l when they are equal to round-off, as for a symmetric structure) and
        the hinges of both mechanisms in the structure's own frame.
    """

    analyses: tuple | None
    summary: dict

    @property
    def collapses(self) -> bool:
        """Whether a horizontal acceleration collapses the structure (it stands, and k is
        finite)."""
        return self.analyses is not None


def joint_name(structure, joint: int) -> str:
    """What a joint is, in words: a :class:`~archquake.geometry.Structure`'s own name for it
    (``"left pier base"``, ``"arch joint 3"``), else ``"left springing"``, ``"joint 3"``,
    ``"right springing"``.

    Parameters
    ----------
    structure : BlockArch
    joint : int
        Joint index, 0 .. n (left to right).

    Returns
    -------
    str
    """
    if hasattr(structure, "joint_name"):
        return structure.joint_name(joint)
    if joint == 0:
        return "left springing"
    if joint == structure.n_voussoirs:
        return "right springing"
    return f"joint {joint}"


def hinges_in_own_frame(structure, analysis) -> list[dict]:
    """The hinges of a limit analysis in the structure's own frame (Mech-r mirrored back).

    Parameters
    ----------
    structure : BlockArch
        The structure as given.
    analysis : LimitAnalysis
        One direction's analysis (Mech-r's is of the mirrored structure).

    Returns
    -------
    list of dict
        Per hinge, left to right as the mechanism names them (A, B, C, D): ``label``, ``joint``
        (in the structure's numbering), ``where`` (:func:`joint_name`), ``face``, ``x``, ``y``
        [m] and ``beta`` [rad] (the progressive angle in the analysed frame, as Table 1 of the
        paper gives it).
    """
    n = structure.n_voussoirs
    labels = "ABCD" if analysis.is_four_hinge else [f"H{i + 1}" for i in
                                                       range(len(analysis.hinges))]
    out = []
    for label, hinge, (x, y), beta in zip(labels, analysis.hinges, analysis.hinge_points,
                                          analysis.hinge_angles, strict=True):
        joint = hinge.joint if analysis.direction == "l" else n - hinge.joint
        out.append({"label": label, "joint": int(joint), "where": joint_name(structure, joint),
                    "face": hinge.face, "x": float(x if analysis.direction == "l" else -x),
                    "y": float(y), "beta": float(beta)})
    return out


def limit_part(structure) -> LimitPart:
    """Does the structure stand under its own weight, and at what horizontal acceleration does
    it start to move, with which hinges, each way [paper, Sect. 3]?

    Parameters
    ----------
    structure : BlockArch
        An arch (circular, shaped or surveyed) or a
        :class:`~archquake.geometry.Structure` on piers or under fill.

    Returns
    -------
    LimitPart
        The verdict of :func:`archquake.limit_analysis.standing`; when it stands, the analyses
        of :func:`archquake.limit_analysis.both_directions` (static method).
    """
    from ...errors import CannotStandError, NeverCollapsesError
    from ...limit_analysis import both_directions, standing

    verdict = standing(structure)
    summary = {"verdict": {"stands": verdict.stands, "part": verdict.part,
                           "reason": verdict.reason, "margin": json_float(verdict.margin),
                           "collapses": False}}
    if not verdict.stands:
        return LimitPart(None, summary)
    try:
        analyses = both_directions(structure)
    except CannotStandError as exc:
        summary["verdict"].update(stands=False, part=verdict.part or "arch", reason=str(exc))
        return LimitPart(None, summary)
    except NeverCollapsesError as exc:
        summary["verdict"]["reason"] = (f"it stands, and no horizontal acceleration collapses "
                                        f"it: {exc}")
        return LimitPart(None, summary)
    k_l, k_r = (float(a.load_multiplier) for a in analyses)
    summary["verdict"]["collapses"] = True
    summary.update({
        "method": analyses[0].method, "k_l": k_l, "k_r": k_r, "k": min(k_l, k_r),
        "governing": "l" if k_l <= k_r * (1.0 + 1e-9) else "r",
        "mechanisms": {a.direction: {"hinges": hinges_in_own_frame(structure, a),
                                     "four_hinge": a.is_four_hinge,
                                     "separation": a.separation}
                       for a in analyses},
    })
    return LimitPart(tuple(analyses), summary)


def sliding_part(structure, friction: float) -> dict | None:
    """Sliding as well as rocking: the collapse multiplier each way with Coulomb friction
    ``friction`` [-] at every joint (the rigid-block model's), under the associative and the
    non-associative law (:func:`archquake.limit_analysis.assembly_limits`), and the rigid-block
    model's own under a slow ramp (:func:`archquake.rigid_blocks.ramp.ramp_test`), the arbiter.

    Returns
    -------
    dict or None
        ``friction`` and, by direction (``"l"``: forces toward +x, ``"r"``: toward -x, as the
        mechanisms), each law's ``k``, ``rocking`` and ``sliding`` joints; None when the
        structure cannot be analysed so (a fill's passive reaction, or it cannot stand with
        this friction).
    """
    from ...errors import CannotStandError
    from ...limit_analysis import assembly_limits
    from ...rigid_blocks.ramp import ramp_test

    try:
        limits = assembly_limits(structure, friction=friction)
        ramp = ramp_test(structure, friction=friction)
    except (CannotStandError, ValueError):
        return None
    out = {"friction": friction, "directions": {}}
    for name, direction in (("l", "+x"), ("r", "-x")):
        laws = {law: {"k": json_float(r.load_multiplier),
                      "rocking": r.interfaces_that("rocks"),
                      "sliding": r.interfaces_that("slides"), "converged": r.converged}
                for law, r in limits[direction].items()}
        onset = ramp.onset(direction)
        laws["rigid blocks (ramp)"] = {"k": json_float(onset.multiplier),
                                       "error": json_float(onset.error),
                                       "rocking": list(onset.rocking_joints),
                                       "sliding": list(onset.sliding_joints), "converged": True}
        out["directions"][name] = laws
    return out


# ------------------------------------------------------------------------------ four links
@dataclass(frozen=True, eq=False)
class FourLinkPart:
    """The four-link model of the structure [paper, Sect. 4].

    Attributes
    ----------
    model : FourLinkModel or None
        With the settings' restitution; None when the model does not apply (``summary``
        says why).
    summary : dict
        ``applies``, ``reason``; the ``mechanisms`` by direction (link angles and lengths,
        critical angles, activation), the ``restitution`` ``(c_lr, c_rl)`` of every rule and
        ``used`` (the settings' rule and its pair).
    """

    model: object
    summary: dict


RESTITUTION_RULES = ("computed", "link", "measured", "paper", "elastic")
"""The restitution rules an assessment reports
(:data:`archquake.fourlink.impact.RESTITUTION_MODELS`; ``"nominal"`` is ``"computed"`` for the
structure itself)."""


def four_link_part(structure, settings: AssessmentSettings) -> FourLinkPart:
    """The four-link mechanisms of the structure both ways, their critical rotations and the
    coefficient of restitution of every rule [paper, Sects. 4.1-4.4, Tables 2-3].

    Parameters
    ----------
    structure : BlockArch
    settings : AssessmentSettings
        ``restitution``: the rule of the model the assessment runs.

    Returns
    -------
    FourLinkPart
    """
    try:
        model = settings.model_spec("four-link").build(structure)
    except ValueError as exc:
        return FourLinkPart(None, {"applies": False, "reason": str(exc)})
    mechanisms = {}
    for mech in model.mechanisms:
        mechanisms[mech.direction] = {
            "theta_u": mech.theta_u, "theta_bc_u": mech.theta_bc_u, "theta_cd_u": mech.theta_cd_u,
            "ab": mech.ab, "bc": mech.bc, "cd": mech.cd, "theta_cr": mech.theta_cr,
            "phi_cr": mech.phi_cr, "ratio": mech.theta_cr / mech.theta_u,
            "theta_limit": mech.theta_limit, "activation": mech.activation_g}
    rules = {}
    for rule in RESTITUTION_RULES:
        try:
            rules[rule] = [float(c) for c in model.with_restitution(rule).restitution]
        except ValueError as exc:  # e.g. the rigid blocks do not close as the mechanism
            rules[rule] = {"error": str(exc)}
    return FourLinkPart(model, {
        "applies": True, "reason": "", "mechanisms": mechanisms, "restitution": rules,
        "used": {"rule": settings.restitution, "pair": [float(c) for c in model.restitution]}})


# ------------------------------------------------------------------------------ pulses
def pulse_grid(k: float, settings: AssessmentSettings) -> np.ndarray:
    """The amplitudes [g] both models scan in the failure domains: from half the activation
    multiplier k to the larger of 3 g and 8 k, ``settings.amplitude_points`` of them, evenly
    spaced and rounded to 1e-4 g.

    Parameters
    ----------
    k : float
        k = min(k_l, k_r) of the structure [-].
    settings : AssessmentSettings

    Returns
    -------
    ndarray
    """
    start = max(0.01, math.floor(50.0 * k) / 100.0)
    top = max(3.0, math.ceil(16.0 * k) / 2.0)
    return np.round(np.linspace(start, top, settings.amplitude_points), 4)


def four_link_domains(model, durations, amplitudes_g, resolution_g: float) -> dict:
    """The four-link model's failure domains under Oppenheim's pulse, both ways, on the scan of
    the assessment (:func:`archquake.studies.failure_domain.domain_of`, no extension beyond the
    scan, so both models cover the same range).

    Parameters
    ----------
    model : FourLinkModel
    durations : sequence of float
        Pulse durations t_p [s].
    amplitudes_g : array_like
        The scan [g] (:func:`pulse_grid`).
    resolution_g : float
        Bisection width of every boundary [g].

    Returns
    -------
    dict of str to FailureDomain
        By direction, ``"l"`` and ``"r"``.
    """
    from ...studies.failure_domain import domain_of

    return {d: domain_of(model, durations, amplitudes_g, direction=d, resolution_g=resolution_g,
                         extend_to_g=None) for d in DIRECTIONS}


def rigid_block_domain(structure, durations, amplitudes_g, direction: str, resolution_g: float,
                       friction: float):
    """The rigid-block model's failure domain under Oppenheim's pulse, one way, on the scan of
    the assessment (a task for the second process: module level, picklable arguments).

    Parameters
    ----------
    structure : BlockArch
    durations : sequence of float
        Pulse durations t_p [s].
    amplitudes_g : array_like
        The scan [g] (:func:`pulse_grid`).
    direction : {"l", "r"}
        The direction of the first pulse.
    resolution_g : float
        Bisection width of every boundary [g].
    friction : float
        Coulomb friction coefficient of the joints [-].

    Returns
    -------
    FailureDomain
        :func:`archquake.studies.failure_domain.domain_of` of the
        :class:`~archquake.rigid_blocks.RigidBlockModel` (its default search: screened by the
        four-link model).
    """
    from ...models import ModelSpec
    from ...studies.failure_domain import domain_of

    model = ModelSpec("rigid-blocks", friction=friction).build(structure)
    return domain_of(model, durations, amplitudes_g, direction=direction,
                     resolution_g=resolution_g, extend_to_g=None)


@dataclass(frozen=True, eq=False)
class PulsePart:
    """Both models' failure domains under Oppenheim's pulse, and where they disagree.

    Attributes
    ----------
    four_link : dict of str to FailureDomain or None
        The four-link model's domains by direction (None when it does not apply).
    rigid_blocks : FailureDomain
        The rigid-block model's, in the governing direction.
    disagreement : Disagreement or None
        :func:`archquake.studies.comparison.domain_disagreement` (four-link first) in the
        governing direction.
    significant : Disagreement or None
        The pieces of ``disagreement`` wider than twice the bisection width (narrower ones lie
        within the uncertainty of the two boundaries): what the report hatches.
    summary : dict
        The scan, both domains (:meth:`~archquake.studies.failure_domain.FailureDomain.to_list`),
        the rows per duration, the disagreement and how far the models agree.
    """

    four_link: dict | None
    rigid_blocks: object
    disagreement: object
    significant: object
    summary: dict


def significant_disagreement(disagreement, width_g: float):
    """The pieces of a disagreement wider than ``width_g`` [g].

    Parameters
    ----------
    disagreement : Disagreement
        :func:`archquake.studies.comparison.domain_disagreement`.
    width_g : float
        Narrowest piece kept [g].

    Returns
    -------
    Disagreement
    """
    from ...studies.comparison import Disagreement

    return Disagreement(disagreement.durations,
                        tuple(tuple(iv for iv in piece if iv[1] - iv[0] > width_g)
                              for piece in disagreement.intervals), disagreement.names)


def agreement(rows: list[dict]) -> dict:
    """How far the two models' failure accelerations agree, from the rows of
    :func:`pulse_part`.

    Parameters
    ----------
    rows : list of dict
        Per duration ``four_link``, ``rigid_blocks`` [g] (None: no collapse in the scan) and
        ``difference`` (four-link over rigid blocks, minus 1).

    Returns
    -------
    dict
        ``band`` (:data:`~archquake.defaults.AGREEMENT_BAND`), ``within``
        (durations whose failure accelerations agree within it), ``compared`` (durations where
        both collapse in the scan), ``largest`` (``{"difference", "duration"}`` of the largest
        difference, or None), ``median_abs`` (median of the absolute differences), ``from``
        (the shortest duration from which on every duration agrees, or None) and ``only``
        (durations where one model collapses in the scan and the other does not, by model).
    """
    compared = [r for r in rows if r["difference"] is not None]
    within = [r["duration"] for r in compared if abs(r["difference"]) <= AGREEMENT_BAND]
    start = None
    for r in sorted(rows, key=lambda r: -r["duration"]):
        if r["difference"] is None or abs(r["difference"]) > AGREEMENT_BAND:
            break
        start = r["duration"]
    largest = max(compared, key=lambda r: abs(r["difference"]), default=None)
    return {
        "band": AGREEMENT_BAND, "within": within, "compared": [r["duration"] for r in compared],
        "largest": None if largest is None else {"difference": largest["difference"],
                                                 "duration": largest["duration"]},
        "median_abs": (float(np.median([abs(r["difference"]) for r in compared]))
                       if compared else None),
        "from": start,
        "only": {"four-link": [r["duration"] for r in rows if r["rigid_blocks"] is None
                               and r["four_link"] is not None],
                 "rigid-blocks": [r["duration"] for r in rows if r["four_link"] is None
                                  and r["rigid_blocks"] is not None]},
    }


def trusted_model(pulses: dict, four_link_applies: bool) -> dict:
    """Which model the first screen's capacities, fragilities and checks come from: the
    four-link model where the two models' failure accelerations under Oppenheim's pulse agree
    within :data:`~archquake.defaults.AGREEMENT_BAND` at every duration of the scan, else the
    rigid-block model.

    The two agree at a duration where both collapse in the scan and ``|difference| <= band``
    (:func:`agreement`), or where neither does. A duration where only one collapses, or where
    the rigid blocks left an undecided band below their lowest decided collapse (no difference
    is then known, :mod:`archquake.studies.undecided`), is no agreement. Where they disagree
    the rigid-block model is used: every block rigid, any mechanism, sliding with Coulomb
    friction, within 1 % of the discrete-element code LMGC90 on fixed supports (0.4 % on
    piers), where the four-link model keeps the four hinges of the limit analysis.

    Parameters
    ----------
    pulses : dict
        :attr:`PulsePart.summary`.
    four_link_applies : bool
        Whether the four-link model describes the structure (else only the rigid-block model
        does).

    Returns
    -------
    dict
        ``model`` (``"four-link"`` or ``"rigid-blocks"``), ``agree`` (bool), ``disagreeing``
        (the durations where they do not agree [s]) and ``reason`` (in words).
    """
    if not four_link_applies or "agreement" not in pulses:
        return {"model": "rigid-blocks", "agree": False, "disagreeing": [],
                "reason": "the four-link model does not apply to this structure"}
    band = pulses["agreement"]["band"]
    disagreeing = []
    for row in pulses["rows"]:
        neither = (row["four_link"] is None and row["rigid_blocks"] is None
                   and row.get("rigid_blocks_undecided_from") is None)
        within = row["difference"] is not None and abs(row["difference"]) <= band
        if not (neither or within):
            disagreeing.append(row["duration"])
    if not disagreeing:
        return {"model": "four-link", "agree": True, "disagreeing": [],
                "reason": (f"the two models' failure accelerations under Oppenheim's pulse "
                           f"agree within {100 * band:g} % at every duration")}
    return {"model": "rigid-blocks", "agree": False, "disagreeing": disagreeing,
            "reason": (f"the two models' failure accelerations under Oppenheim's pulse do not "
                       f"agree within {100 * band:g} % at {len(disagreeing)} of the "
                       f"{len(pulses['rows'])} durations")}


def pulse_part(four_link: dict | None, rigid_blocks, governing: str,
               amplitudes_g) -> PulsePart:
    """Both models' failure domains side by side, per duration, with their disagreement.

    A row keeps the rigid-block model's undecided analyses (``rigid_blocks_undecided``), bands
    (``rigid_blocks_undecided_bands`` [g]) and, where a band lies below its lowest decided
    collapse, ``rigid_blocks_undecided_from`` [g]: its failure acceleration then lies between
    that and ``rigid_blocks``, and no ``difference`` is given
    (:mod:`archquake.studies.undecided`).

    Parameters
    ----------
    four_link : dict of str to FailureDomain or None
        :func:`four_link_domains` (None when the four-link model does not apply).
    rigid_blocks : FailureDomain
        :func:`rigid_block_domain` in the governing direction.
    governing : {"l", "r"}
        The direction of the smaller load multiplier.
    amplitudes_g : array_like
        The scan [g].

    Returns
    -------
    PulsePart
    """
    from ...studies.comparison import domain_disagreement

    rows = []
    fl = None if four_link is None else four_link[governing]
    for i, s in enumerate(rigid_blocks.slices):
        rb = json_float(s.failure_acceleration_g)
        low = json_float(s.failure_undecided_from_g)  # not None: rb is not decided
        row = {"duration": s.duration, "rigid_blocks": rb, "four_link": None,
               "four_link_first_half_cycle": None, "difference": None,
               "rigid_blocks_analyses": (int(rigid_blocks.analyses[i])
                                         if rigid_blocks.analyses else None),
               "rigid_blocks_undecided": (int(rigid_blocks.undecided[i])
                                          if rigid_blocks.undecided else 0),
               "rigid_blocks_undecided_bands": [list(b) for b in s.undecided_bands_g],
               "rigid_blocks_undecided_from": low}
        if fl is not None:
            other = fl.slices[i]
            a = json_float(other.failure_acceleration_g)
            row.update(four_link=a, four_link_first_half_cycle=json_float(
                other.first_half_cycle_acceleration_g),
                difference=(None if a is None or rb is None or low is not None
                            else a / rb - 1.0))
            row["four_link_other_direction"] = json_float(
                four_link["r" if governing == "l" else "l"].slices[i].failure_acceleration_g)
        rows.append(row)
    disagreement = significant = None
    resolution_g = rigid_blocks.slices[0].resolution_g
    if fl is not None:
        disagreement = domain_disagreement(fl, rigid_blocks)
        significant = significant_disagreement(disagreement, 2.0 * resolution_g)
    summary = {
        "direction": governing, "amplitudes_g": [float(a) for a in amplitudes_g],
        "resolution_g": rigid_blocks.slices[0].resolution_g,
        "durations": [s.duration for s in rigid_blocks.slices],
        "rigid_blocks": {"domain": rigid_blocks.to_list(), "model": rigid_blocks.model,
                         "search": rigid_blocks.search,
                         "analyses": int(sum(rigid_blocks.analyses)),
                         "undecided": rigid_blocks.undecided_analyses},
        "rows": rows,
    }
    if fl is not None:
        summary["four_link"] = {d: {"domain": dom.to_list(), "model": dom.model,
                                    "restitution": [json_float(c) for c in dom.restitution]}
                                for d, dom in four_link.items()}
        summary["disagreement"] = disagreement.to_list()
        summary["disagreement_width_g"] = [float(w) for w in disagreement.width_g()]
        summary["disagreement_shown_above_g"] = 2.0 * resolution_g
        summary["agreement"] = agreement(rows)
        summary["agreement"]["disagreeing"] = [
            float(d) for d, w in zip(significant.durations, significant.width_g(), strict=True)
            if w > 0.0]
    return PulsePart(four_link, rigid_blocks, disagreement, significant, summary)


# ------------------------------------------------------------------------------ irregularity
def has_centreline(structure) -> bool:
    """Whether irregular arches can be drawn around the structure (its arch has a centreline:
    a circular or shaped arch, not a surveyed one)."""
    arch = getattr(structure, "arch", structure)
    return getattr(arch, "perturbed", None) is not None


def fragility_amplitudes(failure_accelerations, k: float, settings: AssessmentSettings
                         ) -> tuple[float, ...]:
    """The amplitudes [g] of the fragility under pulses: ``fragility_amplitude_points`` of them
    from half the smallest to 1.5 times the largest failure acceleration of the structure at the
    fragility's durations (from k/2 to 3 g, or 8 k, without any), rounded to 1e-4 g.

    Parameters
    ----------
    failure_accelerations : array_like
        The structure's failure accelerations at the fragility's durations [g] (nan: none).
    k : float
        Its load multiplier [-].
    settings : AssessmentSettings

    Returns
    -------
    tuple of float
    """
    fa = np.asarray(failure_accelerations, dtype=float)
    fa = fa[np.isfinite(fa)]
    if fa.size:
        lo, hi = 0.5 * float(fa.min()), 1.5 * float(fa.max())
    else:
        lo, hi = 0.5 * k, max(3.0, 8.0 * k)
    values = np.round(np.linspace(lo, hi, settings.fragility_amplitude_points), 4)
    return tuple(float(v) for v in np.unique(values))


@dataclass(frozen=True, eq=False)
class IrregularityPart:
    """The irregular arches under pulses: the sample of k~ and the fragility curves.

    Attributes
    ----------
    result : FragilityResult
        :func:`archquake.studies.fragility.run_fragility`.
    summary : dict
        The study's summary (:meth:`~archquake.studies.fragility.FragilityResult.summary`)
        and the quantiles of k~.
    """

    result: object
    summary: dict


def irregularity_part(structure, settings: AssessmentSettings, durations, amplitudes_g,
                      directory=None, resume: bool = False, model: str = "four-link",
                      pool=None) -> IrregularityPart:
    """The fragility of irregular arches drawn around the structure under Oppenheim's pulse
    [paper, Sect. 5.3.3, eq. (9)] and the limit-analysis sample of k~, with the model ``model``.

    Parameters
    ----------
    structure : BlockArch
        The nominal structure (its arch with a centreline: :func:`has_centreline`).
    settings : AssessmentSettings
        epsilon, seed, restitution, h and s.
    durations : sequence of float
        Pulse durations t_p [s].
    amplitudes_g : sequence of float
        Amplitudes [g] (:func:`fragility_amplitudes`).
    directory : str or Path, optional
        The study's directory (resumable).
    resume : bool
        Continue the study saved in ``directory``, if one was started there
        (:func:`archquake.execution.resumable_study`).
    model : {"four-link", "rigid-blocks"}
        The model of every arch (:meth:`AssessmentSettings.model_spec`): h is
        ``fragility_sample_size`` with the four-link model, ``rigid_block_fragility_sample_size``
        with the rigid blocks.
    pool : WorkerPool, optional
        Worker processes to run the study on (:func:`archquake.execution.process_pool`);
        None: in this process. The results do not depend on it.

    Returns
    -------
    IrregularityPart
        Its summary with ``model``: the name of the model.
    """
    from ...execution import resumable_study
    from ...studies.fragility import FragilitySettings, run_fragility

    spec = settings.model_spec(model)
    study = FragilitySettings(
        nominal=structure, sample_size=(settings.fragility_sample_size if spec.grid_in_one_call
                                        else settings.rigid_block_fragility_sample_size),
        epsilon=settings.epsilon, durations=tuple(durations), amplitudes_g=tuple(amplitudes_g),
        seed=settings.seed, model=spec,
        limit_sample_size=settings.limit_sample_size)
    resume = resume and resumable_study(directory) is not None  # only where it was started
    result = run_fragility(study, directory, resume=resume, progress=False,
                           **({"backend": "serial"} if pool is None else {"pool": pool}))
    summary = result.summary()
    summary["model"] = study.model.name
    k = result.limit_load_multipliers
    finite = k[np.isfinite(k)]
    summary["limit_sample"]["quantiles"] = (
        {f"{q:g}": float(np.quantile(finite, q)) for q in (0.05, 0.5, 0.95)}
        if finite.size else None)
    summary["analysed"] = result.analysed
    return IrregularityPart(result, summary)


__all__ = ["DIRECTIONS", "RESTITUTION_RULES", "FourLinkPart", "IrregularityPart", "LimitPart",
           "PulsePart", "agreement", "four_link_domains", "four_link_part", "fragility_amplitudes",
           "has_centreline", "hinges_in_own_frame", "irregularity_part", "joint_name",
           "limit_part", "pulse_grid", "pulse_part", "rigid_block_domain",
           "significant_disagreement", "trusted_model"]
