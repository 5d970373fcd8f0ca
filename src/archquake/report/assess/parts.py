"""The parts of an assessment of one structure: each a function of the structure, the settings
and the values it needs, returning values.

A part's value holds what its figures draw (limit analyses, models, failure domains, the
studies' results) and its ``summary``: the JSON-ready numbers of ``results.json``, computed here
by the library's own calls, so that a test can recompute any of them with the single call
(:func:`archquake.limit_analysis.both_directions`,
:func:`archquake.studies.failure_domain.domain_of`,
:func:`archquake.studies.fragility.run_fragility`,
:func:`archquake.studies.record_fragility.run_record_fragility`):

- :func:`limit_part`: does the structure stand, its load multipliers and hinges both ways;
- :func:`four_link_part`: the four-link model, its mechanisms and the restitution of every rule;
- :func:`pulse_grid`, :func:`four_link_domains`, :func:`rigid_block_domain`,
  :func:`pulse_part`: the failure domains under pulses of both models, and where they disagree;
- :func:`irregularity_part`: the k~ sample and the fragility under pulses of the irregular
  arches (:func:`fragility_amplitudes` chooses the amplitudes);
- :func:`select_records`, :func:`record_study`,
  :func:`record_summary`, :func:`export_nrml`, :func:`record_check`: the record-based
  fragility (multiple-stripe analysis) in each intensity measure, with its OpenQuake NRML file,
  and the rigid blocks' check under the records (:func:`structure_stripes` for a structure
  without irregular arches around it).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .settings import AGREEMENT_BAND, AssessmentSettings

DIRECTIONS = ("l", "r")
"""The two directions of a mechanism: Mech-l (forces left to right) and Mech-r."""


def _json_float(x):
    x = float(x)
    return x if math.isfinite(x) else None


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
                           "reason": verdict.reason, "margin": _json_float(verdict.margin),
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


RESTITUTION_RULES = ("computed", "link", "rigid-blocks", "paper", "elastic")
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
    from ...fourlink import FourLinkModel

    try:
        model = FourLinkModel.from_arch(structure, settings.restitution)
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


def four_link_domains(model, durations, amplitudes_g, resolution: float) -> dict:
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
    resolution : float
        Bisection width of every boundary [g].

    Returns
    -------
    dict of str to FailureDomain
        By direction, ``"l"`` and ``"r"``.
    """
    from ...studies.failure_domain import domain_of

    return {d: domain_of(model, durations, amplitudes_g, direction=d, resolution=resolution,
                         extend_to_g=None) for d in DIRECTIONS}


def rigid_block_domain(structure, durations, amplitudes_g, direction: str, resolution: float,
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
    resolution : float
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
    from ...rigid_blocks import BlockSettings, RigidBlockModel
    from ...studies.failure_domain import domain_of

    model = RigidBlockModel(structure, BlockSettings(friction=friction))
    return domain_of(model, durations, amplitudes_g, direction=direction,
                     resolution=resolution, extend_to_g=None)


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
        ``band`` (:data:`~archquake.report.assess.settings.AGREEMENT_BAND`), ``within``
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


def pulse_part(four_link: dict | None, rigid_blocks, governing: str,
               amplitudes_g) -> PulsePart:
    """Both models' failure domains side by side, per duration, with their disagreement.

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
        rb = _json_float(s.failure_acceleration_g)
        row = {"duration": s.duration, "rigid_blocks": rb, "four_link": None,
               "four_link_first_half_cycle": None, "difference": None,
               "rigid_blocks_analyses": (int(rigid_blocks.analyses[i])
                                         if rigid_blocks.analyses else None)}
        if fl is not None:
            other = fl.slices[i]
            a = _json_float(other.failure_acceleration_g)
            row.update(four_link=a, four_link_first_half_cycle=_json_float(
                other.first_half_cycle_acceleration_g),
                difference=None if a is None or rb is None else a / rb - 1.0)
            row["four_link_other_direction"] = _json_float(
                four_link["r" if governing == "l" else "l"].slices[i].failure_acceleration_g)
        rows.append(row)
    disagreement = significant = None
    resolution = rigid_blocks.slices[0].resolution
    if fl is not None:
        disagreement = domain_disagreement(fl, rigid_blocks)
        significant = significant_disagreement(disagreement, 2.0 * resolution)
    summary = {
        "direction": governing, "amplitudes_g": [float(a) for a in amplitudes_g],
        "resolution_g": rigid_blocks.slices[0].resolution,
        "durations": [s.duration for s in rigid_blocks.slices],
        "rigid_blocks": {"domain": rigid_blocks.to_list(), "model": rigid_blocks.model,
                         "search": rigid_blocks.search,
                         "analyses": int(sum(rigid_blocks.analyses))},
        "rows": rows,
    }
    if fl is not None:
        summary["four_link"] = {d: {"domain": dom.to_list(), "model": dom.model,
                                    "restitution": [_json_float(c) for c in dom.restitution]}
                                for d, dom in four_link.items()}
        summary["disagreement"] = disagreement.to_list()
        summary["disagreement_width_g"] = [float(w) for w in disagreement.width_g()]
        summary["disagreement_shown_above_g"] = 2.0 * resolution
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
                      directory=None, resume: bool = False) -> IrregularityPart:
    """The fragility of irregular arches drawn around the structure under Oppenheim's pulse
    [paper, Sect. 5.3.3, eq. (9)] and the limit-analysis sample of k~, with the four-link model.

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
        Continue the study saved in ``directory``.

    Returns
    -------
    IrregularityPart
    """
    from ...studies.fragility import FragilitySettings, run_fragility

    study = FragilitySettings(
        nominal=structure, sample_size=settings.fragility_sample_size,
        epsilon=settings.epsilon, durations=tuple(durations), amplitudes_g=tuple(amplitudes_g),
        seed=settings.seed, restitution=settings.restitution,
        limit_sample_size=settings.limit_sample_size)
    result = run_fragility(study, directory, resume=_resumable(directory, resume),
                           progress=False, backend="serial")
    summary = result.summary()
    k = result.limit_load_multipliers
    finite = k[np.isfinite(k)]
    summary["limit_sample"]["quantiles"] = (
        {f"{q:g}": float(np.quantile(finite, q)) for q in (0.05, 0.5, 0.95)}
        if finite.size else None)
    summary["analysed"] = result.analysed
    return IrregularityPart(result, summary)


def _resumable(directory, resume: bool) -> bool:
    """Resume a study only where one was started."""
    return bool(resume and directory is not None
                and (Path(directory) / "study.json").is_file())


# ------------------------------------------------------------------------------ records
def select_records(suite, count: int | None):
    """The first ``count`` ground motions of a suite (all when None or the suite is not larger).

    A built-in suite keeps its fault-normal components (component ``"a"``, which carries the
    pulse of a near-field record) first, in suite order, then the others; files the first by
    name; a stochastic suite its first ``count`` motions.

    Parameters
    ----------
    suite : RecordSuite
    count : int or None

    Returns
    -------
    RecordSuite
    """
    from ...ground_motion.suites import RecordSuite

    if count is None or count >= len(suite):
        return suite
    if suite.kind == "builtin":
        meta = suite.metadata
        order = ([m["name"] for m in meta if m.get("component") == "a"]
                 + [m["name"] for m in meta if m.get("component") != "a"])
        spec = suite.builtin
        return RecordSuite.from_builtin(spec["name"], spec["scaling"], records=order[:count])
    if suite.kind == "files":
        return RecordSuite(files=suite.files[:count])
    spec = suite.stochastic
    return RecordSuite.from_stochastic(count, spec["seed"], **spec["parameters"])


def record_study(structure, suite, im: str, levels, settings: AssessmentSettings,
                 directory=None, resume: bool = False):
    """One record-based fragility (multiple-stripe analysis) of the structure and its irregular
    arches, with the four-link model
    (:func:`archquake.studies.record_fragility.run_record_fragility`).

    Parameters
    ----------
    structure : BlockArch
    suite : RecordSuite
    im : str
        The intensity measure of the stripes.
    levels : sequence of float
        The stripes [the IM's unit] (:func:`archquake.studies.stripes.stripe_levels`).
    settings : AssessmentSettings
        epsilon, seed, restitution, h, bootstrap.
    directory : str or Path, optional
        The study's directory (resumable).
    resume : bool
        Continue the study saved in ``directory``.

    Returns
    -------
    RecordFragilityResult
    """
    from ...studies.record_fragility import RecordFragilitySettings, run_record_fragility

    study = RecordFragilitySettings(
        suite=suite, levels=tuple(levels), im=im, nominal=structure,
        sample_size=settings.record_sample_size, epsilon=settings.epsilon, seed=settings.seed,
        restitution=settings.restitution, bootstrap=settings.bootstrap)
    return run_record_fragility(study, directory, resume=_resumable(directory, resume),
                                progress=False, backend="serial")


CHECK_RECORDS = 14
"""Ground motions of the rigid blocks' check under the records: the first of the suite in the
order of :func:`select_records` (of a FEMA P695 near-field set, its 14 fault-normal components,
which carry the pulses). A rigid-block analysis of a record costs about a thousand four-link
ones."""


def rigid_block_record_outcomes(structure, suite: dict, level_pga: float,
                                friction: float) -> list[list[int]]:
    """The rigid-block model's outcome under every record of a suite scaled to one PGA, in both
    polarities (a task for the second process: module level, picklable arguments).

    Parameters
    ----------
    structure : BlockArch
    suite : dict
        :meth:`archquake.ground_motion.RecordSuite.to_dict`.
    level_pga : float
        The PGA every record is scaled to [g].
    friction : float
        Coulomb friction coefficient of the joints [-].

    Returns
    -------
    list of [int, int]
        Per record, the status code (:class:`archquake.status.Status`: 0 rest, 1 recovery,
        2 collapse) as recorded and reversed.
    """
    from ...ground_motion.suites import RecordSuite
    from ...rigid_blocks import BlockSettings, RigidBlockModel

    records = RecordSuite.from_dict(suite)
    model = RigidBlockModel(structure, BlockSettings(friction=friction))
    out = []
    for motion, pga in zip(records.motions(cached=True), records.intensities("pga"),
                           strict=True):
        factor = level_pga / float(pga)
        out.append([int(model.outcome(motion.scaled(sign * factor)).status)
                    for sign in (1.0, -1.0)])
    return out


def record_check(model, suite, level_pga: float, rigid_blocks: list) -> dict:
    """Both models under every record of the suite scaled to one PGA, in both polarities: on
    how many of them they agree about collapse.

    Parameters
    ----------
    model : FourLinkModel
        The structure's four-link model.
    suite : RecordSuite
    level_pga : float
        The PGA every record is scaled to [g]
        (:func:`archquake.studies.stripes.median_collapse_pga`).
    rigid_blocks : list of [int, int]
        :func:`rigid_block_record_outcomes` at the same level.

    Returns
    -------
    dict
        ``level_pga`` [g], ``pairs`` (records x 2), the counts ``both``, ``neither``,
        ``four_link_only`` and ``rigid_blocks_only`` (collapse), ``agree`` (the fraction of
        pairs where the two agree) and ``by_record`` (``name``, the status codes of both
        models as recorded and reversed).
    """
    from ...studies.record_fragility import record_outcomes

    rows, counts = [], {"both": 0, "neither": 0, "four_link_only": 0, "rigid_blocks_only": 0}
    for motion, pga, rb, name in zip(suite.motions(cached=True), suite.intensities("pga"),
                                     rigid_blocks, suite.names, strict=True):
        factor = level_pga / float(pga)
        fl = [int(v) for v in record_outcomes(model, motion, [factor, -factor])["status"]]
        for a, b in zip(fl, rb, strict=True):
            key = {(True, True): "both", (False, False): "neither",
                   (True, False): "four_link_only", (False, True): "rigid_blocks_only"}[
                (a == 2, b == 2)]
            counts[key] += 1
        rows.append({"name": name, "four_link": fl, "rigid_blocks": [int(v) for v in rb]})
    pairs = 2 * len(rows)
    return {"level_pga": level_pga, "pairs": pairs, **counts,
            "agree": (counts["both"] + counts["neither"]) / pairs, "by_record": rows}


def file_stem(im: str) -> str:
    """An intensity measure's name as part of a file name: ``sa(0.5)`` -> ``sa_0.5``."""
    return im.replace("(", "_").replace(")", "")


def record_summary(result, nrml: str | None, nrml_note: str) -> dict:
    """What ``results.json`` records of one record-based fragility.

    Parameters
    ----------
    result : RecordFragilityResult
    nrml : str or None
        File name of its NRML export (None: none written).
    nrml_note : str
        Why there is none, or ``""``.

    Returns
    -------
    dict
        ``unit``, ``levels``, ``probability``, ``nominal_probability``, ``lognormal`` and
        ``nominal_lognormal`` (``median`` [unit], ``dispersion`` [-]), the dispersions
        (``record_to_record``, ``geometric``, ``total``, ``srss``), ``analyses``, ``arches``,
        the nominal structure's lowest collapsing level by record (``first_collapse``), and
        ``nrml``.
    """
    summary = result.summary()
    variability = summary["variability"]
    incremental = result.incremental()
    nominal = incremental[incremental["arch"] == -1]
    first = {str(r): _json_float(v) for r, v in zip(nominal["record"], nominal["first_collapse"],
                                                     strict=True)}
    return {
        "im": summary["im"], "unit": summary["im_unit"], "levels": summary["levels"],
        "records": len(result.records), "sample_size": result.settings.sample_size,
        "analysed": result.analysed, "arches": summary["arches"],
        "probability": summary["probability"],
        "nominal_probability": summary["nominal"]["probability"],
        "lognormal": {k: summary["lognormal"][k] for k in ("median", "dispersion")},
        "nominal_lognormal": {k: summary["nominal"]["lognormal"][k]
                              for k in ("median", "dispersion")},
        **{k: variability[k] for k in ("record_to_record", "geometric", "total", "srss")},
        "analyses": summary["analyses"], "first_collapse": first,
        "nrml": nrml, "nrml_note": nrml_note,
    }


@dataclass(frozen=True, eq=False)
class StructureStripes:
    """The record-based fragility of the structure alone (multiple-stripe analysis), for a
    structure around which no irregular arches are drawn (a surveyed arch): the record-to-record
    part of :func:`archquake.studies.record_fragility.run_record_fragility`, the same counts,
    fit and bootstrap band as that study's nominal arch.

    Attributes
    ----------
    im : str
        The intensity measure.
    unit : str
        Its unit.
    levels : ndarray, shape (L,)
        The stripes [unit].
    records : tuple of str
        The records, in suite order.
    collapsed : bool ndarray, shape (R, L, 2)
        Collapse under every record, level and polarity (as recorded, reversed).
    integrated : int
        Analyses integrated (the others never reach the activation: at rest).
    lognormal : LognormalFragility or None
        The maximum-likelihood fit (:func:`archquake.studies.fits.lognormal_fit`).
    band : BootstrapBand or None
        Its bootstrap band over the records.
    """

    im: str
    unit: str
    levels: np.ndarray
    records: tuple
    collapsed: np.ndarray
    integrated: int
    lognormal: object
    band: object

    @property
    def failed(self) -> np.ndarray:
        """Collapse in either polarity, shape (R, L)."""
        return self.collapsed.any(axis=-1)

    @property
    def probability(self) -> np.ndarray:
        """The fraction of the records that collapse the structure at each level [-]."""
        return self.failed.mean(axis=0)


def structure_stripes(model, suite, im: str, levels, *, bootstrap: int, seed: int):
    """The record-based fragility of the structure alone: every record of the suite scaled to
    each level and applied in both polarities
    (:func:`archquake.studies.record_fragility.record_outcomes`), a pair failing if it
    collapses in either; the lognormal fit by maximum likelihood and its bootstrap band over
    the records, on the random stream the record-based study gives its nominal arch (so the
    numbers are that study's for the same structure).

    Parameters
    ----------
    model : FourLinkModel
        The structure's model.
    suite : RecordSuite
    im : str
        The intensity measure of the stripes.
    levels : sequence of float
        The stripes [the IM's unit].
    bootstrap : int
        Bootstrap resamples.
    seed : int
        Root seed of the bootstrap.

    Returns
    -------
    StructureStripes
    """
    from ...ground_motion.suites import stripe_measure
    from ...studies.fits import bootstrap_lognormal, lognormal_fit
    from ...studies.record_fragility import BOOTSTRAP_KEY, DEFAULT_CONFIDENCE, record_outcomes

    measure = stripe_measure(im)
    x = np.asarray(levels, dtype=float)
    factors = suite.scale_factors(measure.name, x)
    collapsed = np.zeros((len(suite), x.size, 2), dtype=bool)
    integrated = 0
    for r, motion in enumerate(suite.motions(cached=True)):
        out = record_outcomes(model, motion, np.concatenate([factors[r], -factors[r]]))
        collapsed[r] = (out["status"].reshape(2, -1) == 2).T
        integrated += int(out["integrated"].sum())
    failed = collapsed.any(axis=-1)
    fit = lognormal_fit(x, failed.shape[0], failed.sum(axis=0))
    band = None
    if fit is not None:
        stream = np.random.default_rng(
            np.random.SeedSequence(seed, spawn_key=(BOOTSTRAP_KEY,)).spawn(2)[1])
        band = bootstrap_lognormal(x, failed, fit, resamples=bootstrap,
                                   confidence=DEFAULT_CONFIDENCE, rng=stream)
    return StructureStripes(measure.name, measure.unit, x, tuple(suite.names), collapsed,
                            integrated, fit, band)


def structure_stripes_summary(stripes: StructureStripes, nrml: str | None,
                              nrml_note: str) -> dict:
    """What ``results.json`` records of :func:`structure_stripes`, with the keys of
    :func:`record_summary` (the irregular arches' fits and dispersions None).

    Parameters
    ----------
    stripes : StructureStripes
    nrml : str or None
        File name of its NRML export.
    nrml_note : str
        Why there is none, or ``""``.

    Returns
    -------
    dict
    """
    failed = stripes.failed
    fit = stripes.lognormal
    first = {}
    for name, row in zip(stripes.records, failed, strict=True):
        first[name] = float(stripes.levels[np.argmax(row)]) if row.any() else None
    rtr = None if fit is None else float(fit.dispersion)
    return {
        "im": stripes.im, "unit": stripes.unit, "levels": stripes.levels.tolist(),
        "records": len(stripes.records), "sample_size": 0, "analysed": 0, "arches": None,
        "structure_only": True, "probability": None,
        "nominal_probability": stripes.probability.tolist(),
        "lognormal": {"median": None, "dispersion": None},
        "nominal_lognormal": {"median": None if fit is None else float(fit.median),
                              "dispersion": rtr},
        "record_to_record": rtr, "geometric": None, "total": None, "srss": None,
        "analyses": {"total": int(stripes.collapsed.size),
                     "integrated": stripes.integrated,
                     "at_rest_without_integration": int(stripes.collapsed.size)
                     - stripes.integrated},
        "first_collapse": first, "nrml": nrml, "nrml_note": nrml_note,
    }


def export_structure_nrml(stripes: StructureStripes, directory) -> tuple[str | None, str]:
    """Write the fit of :func:`structure_stripes` as an OpenQuake NRML fragility model
    (:func:`archquake.results_io.write_fragility_nrml`, id ``masonry-arch-nominal``).

    Parameters
    ----------
    stripes : StructureStripes
    directory : str or Path

    Returns
    -------
    (str or None, str)
        The file's name, or None and why no file was written.
    """
    from ..._version import __version__
    from ...results_io import write_fragility_nrml

    if stripes.lognormal is None:
        return None, ("no fragility function to export: the stripes admit no lognormal fit (no "
                      "collapse, no survival, or a single step between two levels)")
    name = f"fragility_{file_stem(stripes.im)}.xml"
    x = stripes.levels
    write_fragility_nrml(
        Path(directory) / name,
        [("masonry-arch-nominal", stripes.lognormal.median, stripes.lognormal.dispersion)],
        im=stripes.im, min_iml=float(x[0]), max_iml=float(x[-1]),
        description=f"archquake {__version__}: collapse of a masonry arch, lognormal fit by "
                    f"maximum likelihood to multiple stripes of {stripes.im} ({x[0]:g} to "
                    f"{x[-1]:g} {stripes.unit}), {len(stripes.records)} records x 2 "
                    f"polarities; the structure alone")
    return name, ""


def export_nrml(result, directory, im: str) -> tuple[str | None, str]:
    """Write a record-based fragility's lognormal fits as an OpenQuake NRML fragility model
    (:meth:`~archquake.studies.record_fragility.RecordFragilityResult.export_nrml`) beside the
    report.

    Parameters
    ----------
    result : RecordFragilityResult
    directory : str or Path
    im : str

    Returns
    -------
    (str or None, str)
        The file's name, or None and why no file was written.
    """
    name = f"fragility_{file_stem(im)}.xml"
    try:
        result.export_nrml(Path(directory) / name, taxonomy="masonry-arch")
    except ValueError as exc:
        return None, str(exc)
    return name, ""


__all__ = ["CHECK_RECORDS", "DIRECTIONS", "RESTITUTION_RULES", "FourLinkPart", "IrregularityPart",
           "LimitPart", "PulsePart", "StructureStripes", "agreement", "export_nrml",
           "export_structure_nrml", "file_stem", "four_link_domains", "four_link_part",
           "fragility_amplitudes", "has_centreline", "hinges_in_own_frame", "irregularity_part",
           "joint_name", "limit_part", "pulse_grid", "pulse_part", "record_check", "record_study",
           "record_summary", "rigid_block_domain", "rigid_block_record_outcomes", "select_records",
           "significant_disagreement", "structure_stripes", "structure_stripes_summary"]
