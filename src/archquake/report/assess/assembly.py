"""The assessment of a block assembly: several spans on shared piers, an arch of several rings,
a drawing (``archquake assess --spans N`` or ``--rings N``;
:func:`~archquake.report.assess.assess` with a block assembly).

What the assessment of one chain of voussoirs does (:mod:`archquake.report.assess.assessment`)
rests on the four-link model of that chain and on thousands of analyses; an assembly has
neither: its collapse may be a mechanism of one span among several, or rings that separate or
slide, and the rigid-block model is its only dynamic model. Its report therefore holds:

1. the limit analysis both ways, with the friction the rigid-block model gives its joints (the
   assessment's ``friction`` at every interface of an assembly that gives none, else the
   assembly's own) under both friction laws, the
   non-associative one governing, and Heyman's (nothing slides) beside it; which span and which
   ring moves first, and how (interfaces that rock, slide, rings that open or slide), on the
   first screen and in the figure (:func:`archquake.plotting.plot_assembly_limit`);
2. the rigid-block model's check of that collapse multiplier: a horizontal acceleration
   :data:`ACTIVATION_MARGIN` below it (held for :data:`ACTIVATION_DURATION` times the time
   scale of the structure) must leave the blocks at rest, one as far above it must set them
   moving (the model's own test: a structure that never opens or slips a joint by more than
   ``moved_opening`` of its length scale, 1e-5, is at rest); and, where its estimated cost is within
   :data:`DOMAIN_BUDGET`, the rigid-block failure domain under Oppenheim's pulse on the
   durations and scan of the assessment's settings (below k the blocks must not move);
3. at a site (``site``), the code check of the mechanism by the linear route of Circolare 2019
   §C8.7.1.2.1 (:func:`archquake.site.local_mechanism.check_local_mechanism`, whose
   participating mass comes from the assembly's collapse velocities), and the code's dynamic
   route (NTC 2018 §7.3.5: the records compatible with the site's spectrum, each through the
   rigid-block model, :func:`archquake.site.dynamic_check.run_dynamic_check`) where its
   estimated cost is within :data:`DYNAMIC_BUDGET`;

4. where its estimated cost is within :data:`RECORD_BUDGET`, the record-based collapse
   fragility in PGA of the structure with the rigid-block model (:func:`record_part`), and at a
   site with a hazard curve, the annual risk of collapse from it (:func:`assembly_risk`);

and, for a bridge described as several spans of one arch (``description``), the collapse
multiplier of :data:`IRREGULAR_BRIDGES` irregular bridges around it (:func:`irregular_part`);
and says what it leaves out and why: the fragility under pulses and the rigid blocks of
irregular structures (each needs thousands of rigid-block analyses, up to a minute each on
these structures).
"""

from __future__ import annotations

import math
import time

from ...constants import GRAVITY
from ..render import Bullets, Paragraph, Section, Table

ACTIVATION_MARGIN = 0.1
"""The rigid-block check loads the structure at (1 -/+ this) times its collapse multiplier
[-]."""

ACTIVATION_DURATION = 0.3
"""How long each load of the check is held, times the structure's time scale
(:func:`~archquake.report.assess.settings.time_scale`; 0.3 s for Oppenheim's arch) [s]."""

DOMAIN_BUDGET = 300.0
"""The rigid-block failure domain under pulses is computed when its estimated cost is at most
this [s]: :data:`DOMAIN_ANALYSES` analyses a duration, each as long as the longer run of the
rigid-block check (whose held load lasts about as long as a pulse and the motion after it)."""

DYNAMIC_BUDGET = 300.0
"""The code's dynamic route is run when its estimated cost is at most this [s]: the number of
its records times the wall time of one rigid-block analysis under the first of them."""

RECORD_BUDGET = 300.0
"""The record-based fragility is computed when its estimated cost is at most this [s]
(:func:`record_part`)."""

RECORD_LEVELS = 10
"""Levels a record and polarity is expected to be run at before it collapses the structure,
for the cost estimate of the record-based fragility [-] (the pilot's grid rises by 15 % a
level; measured on three spans of Oppenheim's arch: the six records of a quick assessment
collapse them at 2.7-4.8 k g, after 8-12 levels)."""

IRREGULAR_BRIDGES = 100
"""Irregular bridges whose collapse multiplier the assessment of a bridge draws
(:func:`irregular_part`; 20 in a quick assessment) [-]: about 0.1 s each with friction, both
directions, the non-associative iteration."""

QUICK_IRREGULAR_BRIDGES = 20
"""The same in a quick assessment [-]."""

DOMAIN_ANALYSES = 25
"""Analyses a duration of the failure domain's scan and bisections, for its cost estimate [-]
(measured: 19 durations of three spans took 470 analyses)."""

LEFT_OUT = (
    "the four-link model: the structure is not one chain of voussoirs between two springings, "
    "so its mechanism is not a four-hinge mechanism of one chain; the rigid-block model is its "
    "dynamic model",
    "the fragility under pulses and the rigid blocks of irregular structures: each needs "
    "thousands of rigid-block analyses; run one with archquake rigid-blocks and the same "
    "structure options (--amplitude/--duration for a pulse, --record FILE for a record); the "
    "limit analysis of irregular bridges is drawn where the structure is a description of "
    "several spans of one arch (not rings or a drawing), and their fragility under pulses is "
    "archquake fragility --model rigid-blocks with the same structure options",
    "at a site, the nonlinear route of the code check (its capacity curve needs a four-link "
    "chain)",
)
"""What the assessment of an assembly does not do, and why (the report lists it)."""


def _friction(structure, friction: float):
    """The interfaces' Coulomb coefficients as the rigid-block model sees them
    (:func:`~archquake.rigid_blocks.from_block_assembly`): ``friction`` at every interface of
    an assembly that gives none, else the assembly's own (an infinite one: the interface does
    not slide)."""
    from ...limit_analysis.assembly import contacts_of

    contacts = contacts_of(structure)
    if getattr(structure, "friction", None) is None:
        return contacts.with_friction(friction)
    return contacts


def _names(structure, blocks) -> dict:
    """The spans and rings of ``blocks`` (block indices)."""
    from ...geometry.bridge import rings_of, spans_of

    return {"spans": spans_of(structure, blocks), "rings": rings_of(structure, blocks)}


def _how(result) -> dict:
    """How a collapse moves: the interfaces that rock, slide, separate, and the length of ring
    interface that opens and slides [m]."""
    ring = result.contacts.kind == "ring"
    opens, slides = result.ring_lengths()
    return {"rocking": [i for i in result.interfaces_that("rocks") if not ring[i]],
            "sliding": [i for i in result.interfaces_that("slides") if not ring[i]],
            "ring_opens_m": opens, "ring_slides_m": slides}


def _entry(structure, result) -> dict:
    from ...geometry.bridge import moving_blocks

    k = result.load_multiplier
    moving = moving_blocks(result)
    return {"direction": result.direction, "law": result.law,
            "k": k if math.isfinite(k) else None,
            "tilt_deg": result.tilt if math.isfinite(k) else None,
            "converged": result.converged, "moving_blocks": moving,
            **_names(structure, moving), **_how(result)}


def limit_part(structure, friction: float) -> tuple[dict, dict, tuple]:
    """The limit analysis of the assessment (module docstring, 1).

    Returns
    -------
    summary : dict
        JSON-ready: ``laws`` (direction -> law -> entry), ``governing`` (the entries of the
        governing law of each direction), ``heyman`` (k of each direction, nothing sliding),
        ``k``, ``direction``.
    results : dict
        Direction -> law -> AssemblyLimit (for the figure).
    governing : (AssemblyLimit, AssemblyLimit)
        Toward +x and -x.
    """
    from ...limit_analysis import assembly_limits, governing_law
    from ...site.local_mechanism import assembly_directions

    contacts = _friction(structure, friction)
    results = assembly_limits(contacts)  # the non-associative iteration once
    governing = tuple(governing_law(laws) for laws in results.values())
    heyman = assembly_directions(contacts.with_friction(math.inf))
    first = min(governing, key=lambda r: r.load_multiplier)
    summary = {"laws": {d: {law: _entry(structure, r) for law, r in laws.items()}
                        for d, laws in results.items()},
               "governing": [_entry(structure, r) for r in governing],
               "heyman": {r.direction: r.load_multiplier for r in heyman},
               "k": first.load_multiplier, "direction": first.direction}
    return summary, results, governing


def irregular_part(description, k_nominal: float, settings) -> dict:
    """The collapse multiplier of irregular bridges around the description's
    (:meth:`~archquake.geometry.StructureSpec.sample` with the assessment's epsilon and seed:
    every span its own irregular arch, bridge ``i`` from child ``i`` of the seed), under the
    governing friction law (:func:`~archquake.limit_analysis.governing_multiplier`, with the
    friction of :func:`limit_part`).

    Returns
    -------
    dict
        JSON-ready: ``epsilon``, ``seed``, ``size``, every bridge's ``k`` (None for one whose
        piers cannot seat its springings, and for one that cannot stand), ``refused`` (the
        first's indices) and ``refusal`` (the first's reason), ``cannot_stand`` (the second's
        indices), ``min``, ``max``, ``mean``, ``quantiles`` (0.05, 0.5, 0.95),
        ``below_nominal`` (the fraction below ``k_nominal``), ``k_nominal`` and ``seconds``.
    """
    from dataclasses import replace

    from ...errors import CannotStandError, DescriptionError
    from ...limit_analysis import governing_multiplier, multiplier_distribution

    t0 = time.perf_counter()
    size = QUICK_IRREGULAR_BRIDGES if settings.quick else IRREGULAR_BRIDGES
    spec = replace(description, epsilon=settings.epsilon, seed=settings.seed)
    k, refused, refusal, weak = [], [], None, []
    for i, member in enumerate(spec.sample(size)):
        if isinstance(member, DescriptionError):
            k.append(None)
            refused.append(i)
            refusal = refusal or str(member)
            continue
        try:
            k.append(governing_multiplier(_friction(member, settings.friction)))
        except CannotStandError:  # weaker than every other: said, not hidden
            k.append(None)
            weak.append(i)
    return {"epsilon": settings.epsilon, "seed": settings.seed, "size": size, "k": k,
            "refused": refused, "refusal": refusal, "cannot_stand": weak,
            "k_nominal": k_nominal,
            **multiplier_distribution([x for x in k if x is not None], k_nominal),
            "seconds": time.perf_counter() - t0}


def irregular_text(results: dict) -> str:
    """What the irregular bridges' multipliers say (:func:`irregular_part`)."""
    r = results["irregular"]
    text = (f"The collapse multiplier of {r['size']} irregular bridges drawn around this one "
            f"(epsilon {r['epsilon']:g} of the paper's eq. (1), seed {r['seed']}: every span "
            f"its own irregular arch, bridge i from child i of the seed), under the governing "
            f"friction law: ")
    if "quantiles" in r:
        q = r["quantiles"]
        text += (f"from {r['min']:.4f} to {r['max']:.4f}, 5 % {q['0.05']:.4f}, median "
                 f"{q['0.5']:.4f}, 95 % {q['0.95']:.4f}, against the nominal "
                 f"{r['k_nominal']:.4f} ({r['below_nominal']:.0%} of them below it).")
    else:
        text += "none could be built."
    if r.get("cannot_stand"):
        text += (f" WARNING: {len(r['cannot_stand'])} of {r['size']} cannot stand under their "
                 f"own weight and are left out of these figures, all of which they lie below.")
    if r["refused"]:
        text += (f" WARNING: {len(r['refused'])} of {r['size']} could not be built and are left "
                 f"out, so the distribution is of the others (their end voussoirs are too thick "
                 f"for the seats of the middle piers); the first: {r['refusal']}")
    return text


def activation_part(structure, k: float, direction: str, friction: float) -> dict:
    """The rigid-block model's check of the collapse multiplier ``k`` toward ``direction``
    (module docstring, 2).

    Returns
    -------
    dict
        JSON-ready: the duration [s], the threshold [m] and, below and above ``k``, the
        factor, the acceleration [g], the outcome, the largest opening and slip [m], whether
        the blocks moved, the time steps and those left to Lemke's algorithm, and the seconds
        it took; where the check fails, ``ramp``: the rigid blocks' own collapse multiplier
        toward ``direction`` by the ramp test (:func:`archquake.rigid_blocks.ramp.ramp_test`;
        its ``multiplier``, ``error``, ``crossings`` and ``seconds``).
    """
    from ...ground_motion.pulses import rectangular_pulse
    from ...rigid_blocks import BlockSettings, RigidBlockModel
    from .settings import time_scale

    model = RigidBlockModel(structure, BlockSettings(friction=friction))
    duration = round(ACTIVATION_DURATION * time_scale(structure), 3)
    threshold = model.settings.moved_opening * model.assembly.thickness
    sign = 1.0 if direction == "+x" else -1.0
    runs = []
    for factor in (1.0 - ACTIVATION_MARGIN, 1.0 + ACTIVATION_MARGIN):
        t0 = time.perf_counter()
        # a ground acceleration -a loads every block with +a m toward +x
        outcome = model.outcome(rectangular_pulse(-sign * factor * k * GRAVITY, duration))
        runs.append({"factor": factor, "acceleration_g": factor * k,
                     "status": outcome.status.label, "max_opening_m": outcome.max_opening,
                     "max_slip_m": outcome.max_slip,
                     "moves": outcome.status.label != "rest",
                     "decided": outcome.decided, "steps": outcome.steps,
                     "lemke_steps": outcome.fallback_steps,
                     "seconds": time.perf_counter() - t0})
    below, above = runs
    out = {"direction": direction, "k": k, "duration_s": duration, "threshold_m": threshold,
           "friction": friction, "time_step_s": model.settings.time_step, "runs": runs,
           "agrees": (not below["moves"]) and above["moves"]}
    if not out["agrees"]:  # the rigid blocks' own collapse multiplier, by the ramp test
        from ...rigid_blocks.ramp import ramp_test

        t0 = time.perf_counter()
        onset = ramp_test(structure, friction=friction, directions=(direction,)).onset(
            direction)
        out["ramp"] = {"multiplier": onset.multiplier if onset.found else None,
                       "error": onset.error if onset.found else None,
                       "crossings": list(onset.crossings),
                       "seconds": time.perf_counter() - t0}
    return out


def domain_part(structure, k: float, direction: str, settings, activation: dict):
    """The rigid-block failure domain under Oppenheim's pulse toward ``direction`` on the
    assessment's durations and scan, when its estimated cost is within :data:`DOMAIN_BUDGET`
    (module docstring, 2).

    Returns
    -------
    summary : dict
        JSON-ready: ``estimate_s``; either ``skipped`` (why) or the domain's rows (duration,
        the amplitude where the blocks first move and the lowest that collapses [g]), its
        ``domain`` (:meth:`~archquake.studies.failure_domain.FailureDomain.to_dict`) and
        ``seconds``.
    domain : FailureDomain or None
    """
    from .parts import pulse_grid, rigid_block_domain

    durations = settings.pulse_durations(structure)
    per_run = max(r["seconds"] for r in activation["runs"])
    estimate = len(durations) * DOMAIN_ANALYSES * per_run
    out = {"estimate_s": estimate, "durations": list(durations)}
    if estimate > DOMAIN_BUDGET:
        out["skipped"] = (f"its {len(durations)} pulse durations would take about "
                          f"{estimate / 60:.0f} minutes of rigid-block analyses (an analysis of "
                          f"this structure about {per_run:.1f} s; the budget is "
                          f"{DOMAIN_BUDGET / 60:.0f} minutes)")
        return out, None
    t0 = time.perf_counter()
    grid = pulse_grid(k, settings)
    domain = rigid_block_domain(structure, durations, grid, "l" if direction == "+x" else "r",
                                settings.domain_resolution_g, settings.friction)
    rows = []
    for sl in domain.slices:
        first = next((iv.start for iv in sl.intervals if iv.status != "rest"), math.nan)
        rows.append({"duration": sl.duration, "moves_from_g": first,
                     "collapse_from_g": sl.failure_acceleration_g,
                     "bound": sl.failure_acceleration_bound,
                     "undecided": [list(b) for b in sl.undecided_bands_g]})
    out.update(rows=rows, domain=domain.to_dict(), seconds=time.perf_counter() - t0,
               resolution_g=settings.domain_resolution_g, direction=direction)
    return out, domain


def record_part(structure, k: float, suite, friction: float) -> dict:
    r"""The record-based collapse fragility in PGA of the structure with the rigid-block model
    (module docstring, 4), where its estimated cost is within :data:`RECORD_BUDGET`.

    Every record of ``suite`` is scaled up the PGA levels of the pilot of a record study
    (:func:`archquake.studies.stripes.record_pilot`: 25 levels geometric from ``k g`` to
    ``30 k g``), both polarities, until it collapses the structure: its collapse PGA is the
    first level that does. The stripes follow: at level :math:`x_j` the
    records whose collapse PGA is at most :math:`x_j` fail, and the lognormal fragility is their
    maximum-likelihood fit (:func:`~archquake.studies.fits.fit_lognormal_or_none`), a
    record-to-record fragility of the nominal structure (no irregular draws). A run left
    undecided counts as a collapse (the fragility is then an upper bound; their number is
    given). The cost estimate: the records times two polarities times
    :data:`RECORD_LEVELS` levels, each as long as one analysis of the first record at ``k g``.

    Returns
    -------
    dict
        JSON-ready: ``estimate_s``; either ``skipped`` (why) or ``levels_g``, per record its
        ``name``, ``pga_g`` and ``collapse_pga_g`` (None: none on the grid) and its analyses,
        ``failures`` per level, ``lognormal`` (``median`` [g], ``dispersion``; None where the
        counts do not separate into a fit), ``undecided`` runs, ``analyses`` and ``seconds``.
    """
    import numpy as np

    from ...models import ModelSpec
    from ...studies.fits import fit_lognormal_or_none
    from ...studies.stripes import pilot_levels, record_pilot

    spec = ModelSpec("rigid-blocks", friction=friction).resolved(structure)
    model = spec.build(structure)
    motions = suite.motions(cached=True)
    pga = suite.intensities("pga")
    levels = pilot_levels(k)
    for motion, value in zip(motions, pga, strict=True):
        spec.check_motion(structure, motion.scaled(levels[-1] / value))
    t0 = time.perf_counter()
    model.outcome(motions[0].scaled(levels[0] / pga[0]))
    estimate = len(motions) * 2 * RECORD_LEVELS * (time.perf_counter() - t0)
    out = {"estimate_s": estimate}
    if estimate > RECORD_BUDGET:
        out["skipped"] = (f"its {len(motions)} records would take about {estimate / 60:.0f} "
                          f"minutes of rigid-block analyses (the budget is "
                          f"{RECORD_BUDGET / 60:.0f} minutes)")
        return out
    t0 = time.perf_counter()
    pilot = record_pilot(model, suite, k)
    records = [{"name": motion.name, "pga_g": value,
                "collapse_pga_g": None if first is None else first * value, "analyses": runs}
               for motion, value, first, runs in zip(motions, pilot["pga"],
                                                     pilot["first_factor"],
                                                     pilot["analyses"], strict=True)]
    capacity = np.array([math.inf if r["collapse_pga_g"] is None else r["collapse_pga_g"]
                         for r in records])
    failures = np.array([int(np.sum(capacity <= x * (1 + 1e-12))) for x in levels])
    fit = fit_lognormal_or_none(levels, len(records), failures)
    out.update(levels_g=levels.tolist(), records=records, failures=failures.tolist(),
               lognormal=None if fit is None else {"median": fit.median,
                                                   "dispersion": fit.dispersion},
               undecided=pilot["undecided"], analyses=sum(pilot["analyses"]),
               seconds=time.perf_counter() - t0)
    return out


def assembly_risk(site, records: dict) -> dict:
    """The annual frequency of collapse at ``site`` from its hazard curve in PGA and the
    record-based fragility of :func:`record_part` (:func:`archquake.site.risk.risk`), or
    ``skipped`` (why)."""
    from ...site.fragility_models import LognormalCollapseFragility
    from ...site.risk import risk
    from .site import RISK_YEARS

    hazard = site.hazard_curve("PGA")
    if hazard is None:
        return {"skipped": "the site is given by one spectrum, not its hazard curve: give its "
                           "national-grid table (--site FILE) for the risk"}
    fit = (records or {}).get("lognormal")
    if not fit:
        return {"skipped": "no lognormal fragility in PGA from the record-based study of the "
                           "rigid-block model" + (f" ({records['skipped']})"
                                                  if "skipped" in (records or {}) else "")}
    fragility = LognormalCollapseFragility(
        float(fit["median"]), float(fit["dispersion"]), "PGA",
        source="the record-based fragility of the structure (rigid-blocks model)")
    return {**risk(fragility, hazard, years=RISK_YEARS).to_dict(), "model": "rigid-blocks"}


def dynamic_part(structure, site, suite, friction: float, progress: bool = True) -> dict:
    """The code's dynamic route at the site with the rigid-block model (module docstring, 3),
    where its estimated cost is within :data:`DYNAMIC_BUDGET`.

    Parameters
    ----------
    structure : BlockAssembly
    site : SiteSpec
    suite : RecordSuite
        The records from which the compatible ones are selected.
    friction : float
        Coulomb coefficient of the interfaces that give none [-].
    progress : bool

    Returns
    -------
    dict
        JSON-ready: as the arch's dynamic route (``limit_state``, the selection, the runs and
        the verdicts), or ``skipped`` (why), with ``estimate_s`` where it was estimated.
    """
    from ...models import ModelSpec
    from ...site.dynamic_check import run_dynamic_check
    from .site import dynamic_selection

    action, selection, skipped = dynamic_selection(site, site.actions(), suite)
    if skipped is not None:
        return skipped
    spec = ModelSpec("rigid-blocks", friction=friction).resolved(structure)
    model = spec.build(structure)
    motions = selection.scaled_motions()
    for motion in motions:
        spec.check_motion(structure, motion)
    t0 = time.perf_counter()
    model.outcome(motions[0])
    estimate = len(motions) * (time.perf_counter() - t0)
    if estimate > DYNAMIC_BUDGET:
        return {"skipped": f"its {len(motions)} records would take about {estimate / 60:.0f} "
                           f"minutes of rigid-block analyses (the budget is "
                           f"{DYNAMIC_BUDGET / 60:.0f} minutes)", "estimate_s": estimate}
    t0 = time.perf_counter()
    dynamic = run_dynamic_check(structure, selection, models=(spec,), progress=progress)
    return {"limit_state": action.limit_state, **dynamic.to_dict(), "estimate_s": estimate,
            "seconds": time.perf_counter() - t0}


# ------------------------------------------------------------------------------ words
def _listed(values, what: str) -> str:
    values = list(values)
    if not values:
        return ""
    return f"{what}{'s' if len(values) > 1 else ''} {', '.join(str(v) for v in values)}"


def mechanism_words(entry: dict) -> str:
    """Which span and ring move in a collapse, and how, in words."""
    where = [w for w in (_listed(entry["spans"], "span"),
                         _listed([r + 1 for r in entry["rings"]], "ring")) if w]
    how = []
    if entry["rocking"]:
        how.append(f"{len(entry['rocking'])} interface{'s' if len(entry['rocking']) > 1 else ''}"
                   " rock")
    if entry["sliding"]:
        how.append(f"{len(entry['sliding'])} interface{'s' if len(entry['sliding']) > 1 else ''}"
                   " slide")
    if entry["ring_opens_m"] > 0:
        how.append(f"the rings separate over {entry['ring_opens_m']:.2f} m")
    if entry["ring_slides_m"] > 0:
        how.append(f"the rings slide on each other over {entry['ring_slides_m']:.2f} m")
    blocks = len(entry["moving_blocks"])
    text = (" and ".join(where) + ": " if where else "") + (
        f"{blocks} block{'s' if blocks != 1 else ''} move")
    return text + (f" ({'; '.join(how)})" if how else "")


def verdict_text(results: dict) -> str:
    """The first screen's verdict."""
    limit = results["limit"]
    if limit is None:
        return f"VERDICT: CANNOT STAND. {results['cannot_stand']}"
    k = limit["k"]
    entry = next(e for e in limit["governing"] if e["direction"] == limit["direction"])
    other = next(e for e in limit["governing"] if e["direction"] != limit["direction"])
    text = (f"VERDICT: STANDS. It starts to collapse under a horizontal acceleration of "
            f"{k:.4f} g toward {limit['direction']} ({entry['law']}; {other['k']:.4f} g "
            f"toward {other['direction']}). What fails first: {mechanism_words(entry)}.")
    act = results.get("rigid_blocks")
    if act:
        below, above = act["runs"]
        if act["agrees"]:
            text += (f" The rigid-block model agrees: at rest under {below['acceleration_g']:.4f}"
                     f" g, moving under {above['acceleration_g']:.4f} g.")
        else:
            text += (f" The rigid-block model does NOT confirm it: under "
                     f"{below['acceleration_g']:.4f} g its blocks "
                     f"{'move' if below['moves'] else 'stay at rest'}, under "
                     f"{above['acceleration_g']:.4f} g they "
                     f"{'move' if above['moves'] else 'stay at rest'} (section 2).")
            ramp = act.get("ramp") or {}
            if ramp.get("multiplier") is not None:
                text += (f" Its ramp test finds them moving from {ramp['multiplier']:.4f} g "
                         f"(+/- {ramp['error']:.4f}) toward {act['direction']}: "
                         + ("below k, and with non-associative friction the limit analysis's "
                            "multiplier is no bound, so take this lower value."
                            if ramp["multiplier"] < k else "above k."))
    irregular = results.get("irregular") or {}
    if "quantiles" in irregular:
        text += (f" Of {irregular['size'] - len(irregular['refused'])} irregular bridges "
                 f"around it (epsilon {irregular['epsilon']:g}), 5 % start to collapse below "
                 f"{irregular['quantiles']['0.05']:.4f} g, half below "
                 f"{irregular['quantiles']['0.5']:.4f} g (section 1b).")
    rows = (results.get("domain") or {}).get("rows")
    if rows:
        text += (f" Under Oppenheim's pulse (rigid blocks) it collapses from "
                 f"{_g(rows[-1]['collapse_from_g'])} g at t_p = {rows[-1]['duration']:g} s and "
                 f"from {_g(rows[0]['collapse_from_g'])} g at t_p = {rows[0]['duration']:g} s.")
    fit = (results.get("records") or {}).get("lognormal")
    if fit:
        rec = results["records"]
        text += (f" Under {len(rec['records'])} records (rigid blocks) its collapse PGA has a "
                 f"median of {fit['median']:.3f} g (dispersion {fit['dispersion']:.2f}).")
    return text


def record_text(results: dict) -> str:
    """The record-based fragility in words."""
    r = results["records"]
    note = f" {r['records_note']}" if r.get("records_note") else ""
    if "skipped" in r:
        return f"The record-based fragility was not computed: {r['skipped']}.{note}"
    fit = r["lognormal"]
    k = results["limit"]["k"]
    fitted = (f"The lognormal fit of these stripes (maximum likelihood): median "
              f"{fit['median']:.3f} g, dispersion {fit['dispersion']:.2f} (record to record "
              f"only: the nominal structure, no irregular draws)." if fit else
              "The stripes do not separate into a lognormal fit (every record collapses the "
              "structure at one level, or none does).")
    undecided = (f" {r['undecided']} runs were left undecided and count as collapses: the "
                 "fragility is an upper bound." if r["undecided"] else " No run was left "
                 "undecided.")
    return (f"The record-based collapse fragility in PGA with the rigid-block model: every "
            f"record scaled up the pilot's {len(r['levels_g'])} PGA levels from k g = "
            f"{k:.4f} g to 30 k g (15 % apart), both polarities, until it collapses the "
            f"structure ({r['analyses']} analyses in {r['seconds']:.0f} s). A record's collapse "
            f"PGA is the first level that collapses it; at each level the records that "
            f"collapsed at or below it count as failures. {fitted}{undecided}{note}")


def record_rows(results: dict) -> list[list[str]]:
    """One row per record: name, its PGA, its collapse PGA, analyses."""
    return [[r["name"], f"{r['pga_g']:.3f}",
             "beyond 30 k g" if r["collapse_pga_g"] is None else f"{r['collapse_pga_g']:.3f}",
             str(r["analyses"])] for r in results["records"]["records"]]


def limit_rows(results: dict) -> list[list[str]]:
    """One row per direction and law."""
    rows = []
    for direction, laws in results["limit"]["laws"].items():
        for law, e in laws.items():
            rows.append([direction, law, "-" if e["k"] is None else f"{e['k']:.4f}",
                         "-" if e["tilt_deg"] is None else f"{e['tilt_deg']:.2f}",
                         mechanism_words(e), "yes" if e["converged"] else "NO"])
        rows.append([direction, "Heyman (nothing slides)",
                     f"{results['limit']['heyman'][direction]:.4f}", "", "", ""])
    return rows


def _g(value) -> str:
    return "-" if value is None or not math.isfinite(value) else f"{value:.3f}"


def domain_rows(results: dict) -> list[list[str]]:
    """One row per pulse duration of the rigid-block failure domain."""
    return [[f"{r['duration']:g}", _g(r["moves_from_g"]),
             _g(r["collapse_from_g"]) + (" (beyond the scan)" if r["bound"] == "lower" else
                                         " (at most)" if r["bound"] == "upper" else ""),
             ", ".join(f"{a:.3f}-{b:.3f}" for a, b in r["undecided"]) or "none"]
            for r in results["domain"]["rows"]]


def domain_text(results: dict) -> str:
    d = results["domain"]
    if "skipped" in d:
        return (f"The rigid-block failure domain under Oppenheim's pulse was not computed: "
                f"{d['skipped']}.")
    rows = d["rows"]
    return (f"The rigid-block model's failure domain under Oppenheim's pulse (a pulse of "
            f"amplitude a for t_p pushing toward {d['direction']}, then half of it back for "
            f"2 t_p), each boundary bisected to {d['resolution_g']:g} g, in "
            f"{d['seconds']:.0f} s: from t_p = {rows[0]['duration']:g} s to "
            f"{rows[-1]['duration']:g} s the lowest amplitude that collapses the structure "
            f"falls from {_g(rows[0]['collapse_from_g'])} g to "
            f"{_g(rows[-1]['collapse_from_g'])} g. Below the collapse multiplier k = "
            f"{results['limit']['k']:.4f} the blocks must not move at any duration: they first "
            f"move at {min(r['moves_from_g'] for r in rows):.3f}-"
            f"{max(r['moves_from_g'] for r in rows):.3f} g (each boundary to "
            f"{d['resolution_g']:g} g).")


def activation_rows(results: dict) -> list[list[str]]:
    act = results["rigid_blocks"]
    return [[f"{r['factor']:.2f} k = {r['acceleration_g']:.4f} g", r["status"],
             f"{r['max_opening_m']:.3g}", f"{r['max_slip_m']:.3g}",
             "moves" if r["moves"] else "at rest", f"{r['steps']}", f"{r['lemke_steps']}",
             f"{r['seconds']:.1f}"] for r in act["runs"]]


def activation_text(results: dict) -> str:
    act = results["rigid_blocks"]
    return (f"The rigid-block model (every block rigid, Coulomb friction {act['friction']:g} "
            f"where the structure gives none, time step {act['time_step_s']:.3g} s) "
            f"under a horizontal ground acceleration held for {act['duration_s']:g} s, "
            f"{100 * ACTIVATION_MARGIN:g} % below and above the collapse multiplier toward "
            f"{act['direction']}: below it the blocks must stay at rest, above it they must "
            f"move (the model's outcome: at rest when no joint ever opens or slips by more "
            f"than {act['threshold_m']:.3g} m, 1e-5 of the structure's length scale). Steps "
            "left to Lemke's algorithm are those where the active-set method of the contact "
            "problem did not settle: they are decided exactly, at a higher cost."
            + _ramp_words(act))


def _ramp_words(act: dict) -> str:
    ramp = act.get("ramp")
    if not ramp:
        return ""
    if ramp["multiplier"] is None:
        return " The check failed, and the ramp test found no onset of motion up to 2 g."
    crossings = ", ".join(f"{c:.4f}" for c in ramp["crossings"])
    return (f" The check failed, so the ramp test (a horizontal load growing at 0.05 g/s, "
            f"archquake.rigid_blocks.ramp.ramp_test) found the rigid blocks' own "
            f"collapse multiplier: {ramp['multiplier']:.4f} +/- {ramp['error']:.4f}, "
            f"extrapolated from the multipliers where the largest opening or slip crossed "
            f"three thresholds ({crossings}) in {ramp['seconds']:.1f} s.")


# ------------------------------------------------------------------------------ driver
def assembly_name(structure) -> str:
    """A short name of an assembly: its spans and rings (read from the blocks' names), fill,
    and blocks."""
    from ...geometry.bridge import rings_of, spans_of

    every = range(structure.n_blocks)
    spans, rings = len(spans_of(structure, every)), len(rings_of(structure, every))
    parts = []
    if spans:
        parts.append(f"{spans} span{'s' if spans > 1 else ''} on {spans + 1} piers")
    if rings:
        parts.append(f"arches of {rings} ring{'s' if rings > 1 else ''}" if spans
                     else f"an arch of {rings} ring{'s' if rings > 1 else ''}")
    if getattr(structure, "fill", None) is not None:
        parts.append("under fill")
    name = ", ".join(parts) if parts else "a block assembly"
    return f"{name} ({structure.n_blocks} blocks)"



def sections(results: dict, figures: dict) -> list[Section]:
    """The sections of the report of an assembly, from its ``results.json`` and figures; the
    summary first."""
    from . import site as site_words

    stands = results["limit"] is not None
    summary = [Paragraph(verdict_text(results), "verdict" if stands else "verdict cannot")]
    if results.get("site"):
        summary.append(Paragraph(site_words.verdict_text(results["site"]), "verdict"))
    if results["settings"].get("quick"):
        summary.append(Paragraph("QUICK RUN: the settings of a smoke test (they change none of "
                                 "an assembly's parts).", "note"))
    summary.append(Paragraph("This assessment of a block assembly leaves out, and why:",
                             "note"))
    summary.append(Bullets(results["left_out"]))
    out = [Section("Summary", summary)]
    s = results["structure"]
    blocks = [Paragraph(f"The structure: {s['name']}, {s['interfaces']} "
                        "interfaces. Limit analysis of the block assembly (the static linear "
                        "program; non-associative friction by Gilbert et al.'s iteration), "
                        "with the friction the rigid-block model gives the interfaces: "
                        f"{results['settings']['friction']:g} at every interface where the "
                        "structure gives none, else its own (infinite: the interface does not "
                        "slide).")]
    if stands:
        blocks.append(Table(["direction", "law", "k [-]", "tilt [deg]", "what moves",
                             "converged"], limit_rows(results)))
        blocks.append(figures["collapse"])
    else:
        blocks.append(Paragraph(results["cannot_stand"]))
    out.append(Section("1. The structure and its collapse", blocks))
    if results.get("irregular"):
        blocks = [Paragraph(irregular_text(results))]
        if "irregular" in figures:
            blocks.append(figures["irregular"])
        out.append(Section("1b. Irregular bridges: how much k depends on the irregularity",
                           blocks))
    if results.get("rigid_blocks"):
        out.append(Section("2. The rigid-block model's check of the collapse", [
            Paragraph(activation_text(results)),
            Table(["horizontal acceleration", "outcome", "largest opening [m]",
                   "largest slip [m]", "the blocks", "steps", "by Lemke", "wall time [s]"],
                  activation_rows(results))]))
    if results.get("domain"):
        blocks = [Paragraph(domain_text(results))]
        if "rows" in results["domain"]:
            blocks += [Table(["t_p [s]", "the blocks move from [g]", "collapse from [g]",
                              "undecided [g]"], domain_rows(results)), figures["domain"]]
        out.append(Section("3. Failure domain under pulses (rigid blocks)", blocks))
    if results.get("records"):
        blocks = [Paragraph(record_text(results))]
        if "records" in results["records"]:
            blocks.append(Table(["record", "its PGA [g]", "collapses from PGA [g]",
                                 "analyses"], record_rows(results)))
            if "records" in figures:
                blocks.append(figures["records"])
        out.append(Section("3b. Record-based fragility (rigid blocks)", blocks))
    if results.get("site"):
        site = results["site"]
        out.append(Section("4. Is it safe here? The code check at the site", [
            Paragraph(site_words.check_text(site)),
            Table(["limit state", "route", "mechanism", "capacity", "demand",
                   "capacity / demand", "verdict", "holds up to a_g"],
                  site_words.check_rows(site)),
            Paragraph(site_words.dynamic_text(site)), Paragraph(site_words.risk_text(site))]))
    env = results["environment"]
    out.append(Section("Run, versions and settings", [
        Table(["part", "wall time [s]"], [[k, f"{v:.2f}"] for k, v in
                                          results["timings"].items()]),
        Paragraph("Versions: " + ", ".join(f"{k} {v}" for k, v in env.items()) + "."),
        Paragraph("To regenerate this report:"),
        Bullets([results["command"]["regenerate"]])]))
    return out


__all__ = ["ACTIVATION_DURATION", "ACTIVATION_MARGIN", "LEFT_OUT",
           "DOMAIN_ANALYSES", "DOMAIN_BUDGET", "DYNAMIC_BUDGET", "RECORD_BUDGET", "RECORD_LEVELS",
           "IRREGULAR_BRIDGES", "QUICK_IRREGULAR_BRIDGES",
           "activation_part", "assembly_name", "assembly_risk", "domain_part", "dynamic_part",
           "irregular_part", "irregular_text", "record_part",
           "limit_part", "mechanism_words", "record_rows", "record_text", "sections",
           "verdict_text"]
