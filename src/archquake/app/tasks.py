"""The page's long computations, each run in a worker process of its own (:mod:`.jobs`).

A task is a function ``task(spec, report) -> dict``: ``spec`` is the JSON description the page
sent (uploaded files already resolved to their paths, :meth:`archquake.app.inputs.Uploads.
resolve`, and ``workdir`` the server's temporary folder, the only place a task writes),
``report(done, total, text)`` tells the page how far it is, and the result is JSON-ready.
:data:`TASKS` holds them by name.

- :func:`simulate`: the time histories of both models under one ground motion, as the page
  animates them;
- :func:`failure_domain`: the failure domain of both models over (pulse duration, amplitude),
  one duration at a time so that the progress is seen, and where they disagree;
- :func:`assessment`: the assessment report of the structure, zipped for download.
"""

from __future__ import annotations

import base64
import io
import math
import shutil
import zipfile
from dataclasses import replace
from pathlib import Path

from . import views
from .inputs import (
    ASSEMBLY_UNAVAILABLE,
    LIMITS,
    is_assembly,
    motion_and_warnings,
    structure_from_spec,
)

DOMAIN_DEFAULTS = {"durations": "0.1:1.0:0.1", "amplitudes": "0.05:1.5:0.05",
                   "direction": "l", "motion": "oppenheim", "resolution": 0.01,
                   "extend_to": 3.0}
"""The page's failure domain unless told otherwise: a coarser grid than ``archquake domain``'s
(10 durations [s], 30 amplitudes [g], boundaries to 0.01 g, scans extended to 3 g), so that the
rigid blocks' domain takes seconds, not minutes."""


def model_settings(spec: dict) -> dict:
    """The page's settings of both models, checked: ``{name: ModelSpec}``
    (:class:`archquake.models.ModelSpec`, with the page's restitution and friction) for every
    model of :data:`archquake.models.MODELS`.

    Raises
    ------
    ValueError
        Naming ``restitution`` or ``friction``.
    """
    from ..defaults import DEFAULT_FRICTION, DEFAULT_RESTITUTION
    from ..models import MODELS, ModelSpec

    settings = spec.get("models") or {}
    if not isinstance(settings, dict):
        raise ValueError("models must be a JSON object {restitution, friction}")
    restitution = settings.get("restitution") or DEFAULT_RESTITUTION
    try:
        restitution = float(restitution)
    except (TypeError, ValueError):
        pass
    friction = settings.get("friction")
    try:
        friction = DEFAULT_FRICTION if friction in (None, "") else float(friction)
    except (TypeError, ValueError):
        raise ValueError(f"friction must be a number >= 0, got {friction!r}") from None
    checked = ModelSpec(restitution=restitution, friction=friction)
    return {name: replace(checked, name=name) for name in MODELS}


def models_of(spec: dict, structure, nominal) -> dict:
    """Both models of the structure with the page's settings (:func:`model_settings`):
    ``{name: model, or the message why it cannot be built}``; a block assembly (several spans
    or rings) has the rigid blocks only (the four-link model is one chain's,
    :data:`~archquake.app.inputs.ASSEMBLY_UNAVAILABLE`)."""
    out = {}
    for name, model in model_settings(spec).items():
        if name == "four-link" and is_assembly(structure):
            out[name] = ASSEMBLY_UNAVAILABLE["four-link"]
            continue
        try:
            out[name] = model.build(structure, nominal)
        except ValueError as exc:  # cannot stand, not a four-link mechanism, ...
            out[name] = f"{exc}"
    return out


def simulate(spec: dict, report) -> dict:
    """Time histories of both models of the structure under the ground motion of ``spec``.

    Parameters
    ----------
    spec : dict
        ``structure`` and ``motion`` (:mod:`archquake.app.inputs`), ``models`` (``restitution``,
        ``friction``).
    report : callable
        ``report(done, total, text)``.

    Returns
    -------
    dict
        ``structure`` (:func:`~archquake.app.views.structure_view`), ``motion``
        (:func:`~archquake.app.views.motion_view`), ``warnings`` about the motion (a record's
        implausible peak, :func:`~archquake.app.inputs.motion_and_warnings`), ``times`` of the
        frames [s] and their
        rate ``fps`` [1/s] (:func:`~archquake.app.views.frame_rate`), and per model
        (``"four-link"``, ``"rigid-blocks"``) its view (:func:`~archquake.app.views.four_link_view`,
        :func:`~archquake.app.views.rigid_block_view`) or ``{"error": message}`` (the
        four-link model's for a block assembly: several spans or rings are the rigid
        blocks' only).
    """
    nominal, structure = structure_from_spec(spec.get("structure") or {})
    motion, said = motion_and_warnings(spec.get("motion") or {})
    models = models_of(spec, structure, nominal)
    histories = {}
    out = {"structure": views.structure_view(structure), "motion": views.motion_view(motion),
           "warnings": said}
    for k, (name, model) in enumerate(models.items()):
        report(k, 2, f"{name} model")
        if isinstance(model, str):
            out[name] = {"error": model}
            continue
        try:
            if name == "four-link":
                histories[name] = (model, model.simulate(motion))
            else:
                every = max(1, round(1.0 / (views.FRAME_RATE * model.settings.time_step)))
                histories[name] = (model, model.simulate(motion, record_every=every))
        except (ValueError, RuntimeError) as exc:
            out[name] = {"error": f"{exc}"}
    ends = [float(h.t[-1]) if name == "four-link" else float(h.times[-1])
            for name, (_, h) in histories.items()]
    blocks = structure.n_blocks if is_assembly(structure) else structure.n_voussoirs
    rate = views.frame_rate(views.animation_end(*ends), blocks)
    times = views.frame_times(*ends, rate=rate)
    out["fps"], out["times"] = rate, views.rounded(times, 4)
    for name, (model, history) in histories.items():
        out[name] = (views.four_link_view(model, history, times) if name == "four-link"
                     else views.rigid_block_view(history, times))
    report(2, 2, "done")
    return out


def _domain_settings(spec: dict) -> dict:
    from ..ground_motion import ANALYTIC_GROUND_MOTIONS
    from ..ranges import parse_values

    domain = spec.get("domain") or {}
    if not isinstance(domain, dict):
        raise ValueError(f"domain must be a JSON object of {', '.join(DOMAIN_DEFAULTS)}, got "
                         f"{type(domain).__name__}")
    given = {**DOMAIN_DEFAULTS, **{k: v for k, v in domain.items() if v not in (None, "")}}
    unknown = sorted(set(given) - set(DOMAIN_DEFAULTS))
    if unknown:
        raise ValueError(f"unknown failure-domain field(s) {unknown}; known: "
                         f"{list(DOMAIN_DEFAULTS)}")
    durations = parse_values(given["durations"], "durations")
    amplitudes = parse_values(given["amplitudes"], "amplitudes")
    for name, values in (("durations", durations), ("amplitudes", amplitudes)):
        most = LIMITS[f"domain_{name}"]
        if len(values) > most:
            raise ValueError(f"{name} has {len(values)} values; this page takes at most "
                             f"{most}")
    if given["direction"] not in ("l", "r"):
        raise ValueError(f"direction must be l or r, got {given['direction']!r}")
    if given["motion"] not in ANALYTIC_GROUND_MOTIONS:
        raise ValueError(f"motion must be one of {', '.join(ANALYTIC_GROUND_MOTIONS)}, got "
                         f"{given['motion']!r}")
    resolution, extend = (_domain_number(given, name) for name in ("resolution", "extend_to"))
    if not (math.isfinite(resolution) and 1e-4 <= resolution <= 0.5):
        raise ValueError(f"resolution must be in [0.0001, 0.5] g, got {given['resolution']}")
    if not (math.isfinite(extend) and 0 <= extend <= LIMITS["amplitude_g"]):
        raise ValueError(f"extend_to must be in [0, {LIMITS['amplitude_g']:g}] g, got "
                         f"{given['extend_to']}")
    return {"durations": durations, "amplitudes": amplitudes, "direction": given["direction"],
            "motion": given["motion"], "resolution": resolution,
            "extend_to": extend if extend > amplitudes[-1] else None}


def _domain_number(given: dict, name: str) -> float:
    """The number of a failure-domain field, read as the command line reads its options."""
    from ..ranges import number

    value = given[name]
    if not isinstance(value, bool) and isinstance(value, (int, float, str)):
        try:
            return number(value)
        except ValueError:
            pass
    raise ValueError(f"{name} must be a number [g], got {value!r}")


def check_domain(spec: dict) -> dict:
    """The failure-domain settings of ``spec``, checked (before a worker is started).

    Returns
    -------
    dict
        ``durations`` [s], ``amplitudes`` [g] (lists), ``direction``, ``motion``,
        ``resolution`` [g] and ``extend_to`` [g] or None.

    Raises
    ------
    ValueError
        Naming the option of ``archquake domain`` that is wrong, or a page limit.
    """
    return _domain_settings(spec)


def failure_domain(spec: dict, report) -> dict:
    """Failure domains of both models of the structure, and where they disagree.

    :func:`archquake.studies.failure_domain.domain_of` runs one pulse duration at a time
    (reporting each), and the slices of each model are put together into one domain.

    Parameters
    ----------
    spec : dict
        ``structure``, ``models`` and ``domain`` (``durations``, ``amplitudes`` as
        ``archquake domain`` takes them, ``direction``, ``motion``, ``resolution``,
        ``extend_to``; :data:`DOMAIN_DEFAULTS`).
    report : callable
        ``report(done, total, text)``.

    Returns
    -------
    dict
        ``figure`` (a PNG as a data URL: the four-link domain with the disagreement hatched,
        beside the rigid blocks'), per model its ``failure`` curve (``durations`` [s],
        ``failure_g`` and ``first_half_cycle_g`` [g], None where none was found) or its
        ``error``, ``disagreement`` (:meth:`~archquake.studies.comparison.Disagreement.
        to_list`) and ``model_check`` (``rows``: per duration both failure accelerations, their
        difference and whether it is beyond the agreement band,
        :func:`~archquake.studies.comparison.agreement_rows`; ``messages``: what to say beside
        the four-link numbers).
    """
    from ..defaults import AGREEMENT_BAND
    from ..studies.comparison import AgreementProbe, agreement_rows, domain_disagreement
    from ..studies.failure_domain import domain_of

    settings = _domain_settings(spec)
    nominal, structure = structure_from_spec(spec.get("structure") or {})
    models = models_of(spec, structure, nominal)  # an assembly's: the rigid blocks alone
    durations = settings["durations"]
    total = len(durations) * len(models)
    domains, out = {}, {}
    done = 0
    for name, model in models.items():
        if isinstance(model, str):
            out[name] = {"error": model}
            done += len(durations)
            continue
        slices, analyses, undecided, first = [], [], [], None
        for duration in durations:
            report(done, total, f"{name} model: t_p = {duration:g} s")
            piece = domain_of(model, [duration], settings["amplitudes"],
                              direction=settings["direction"], motion=settings["motion"],
                              resolution_g=settings["resolution"],
                              extend_to_g=settings["extend_to"])
            first = first or piece
            slices += piece.slices
            analyses += piece.analyses
            undecided += piece.undecided
            done += 1
        domain = replace(first, slices=tuple(slices), analyses=tuple(analyses),
                         undecided=tuple(undecided))
        domains[name] = domain
        out[name] = {"failure": {
            "durations": [float(d) for d in domain.durations],
            "failure_g": [views.finite(x) for x in domain.failure_accelerations_g],
            "first_half_cycle_g": [views.finite(x)
                                   for x in domain.first_half_cycle_accelerations_g],
            # the failure lies between this and failure_g where a band is undecided below it
            "undecided_from_g": [views.finite(s.failure_undecided_from_g)
                                 for s in domain.slices]},
            "analyses": int(sum(analyses)), "undecided": int(sum(undecided))}
    report(total, total, "figure")
    disagreement = None
    if len(domains) == 2:
        disagreement = domain_disagreement(domains["four-link"], domains["rigid-blocks"])
        out["disagreement"] = disagreement.to_list()
        # beside each four-link failure acceleration: the trusted rigid blocks' where they
        # disagree beyond the agreement band (archquake domain prints the same)
        rows = agreement_rows(domains["four-link"], domains["rigid-blocks"])
        out["model_check"] = {"rows": [r.to_dict() for r in rows],
                              "messages": AgreementProbe(
                                  rows, AGREEMENT_BAND, float(settings["resolution"]), (),
                                  on_piers=getattr(structure, "left", None) is not None
                                  or getattr(structure, "right", None) is not None).messages()}
    out["figure"] = _domain_figure(domains, disagreement, models) if domains else None
    return out


def _domain_figure(domains: dict, disagreement, models: dict) -> str:
    """The domains as one PNG figure, a data URL."""
    from .views import pyplot

    plt = pyplot()
    from ..plotting import plot_disagreement, plot_failure_domain

    fig, axes = plt.subplots(1, len(domains), figsize=(6.2 * len(domains), 4.6),
                             constrained_layout=True, squeeze=False)
    for ax, (name, domain) in zip(axes[0], domains.items(), strict=True):
        plot_failure_domain(domain, ax)
        if name == "four-link" and disagreement is not None:
            plot_disagreement(disagreement, ax)
        sign = "-" if domain.direction == "l" else "+"
        c_lr, c_rl = domain.restitution
        c_text = f"{c_lr:.3f}" if abs(c_lr - c_rl) < 5e-4 else f"{c_lr:.3f} / {c_rl:.3f}"
        settings = (f"c$_v$ = {c_text}" if name == "four-link"
                    else f"friction $\\mu$ = {models[name].settings.friction:g}")
        ax.set_title(f"{name} model: first pulse {sign}a g (Mech-{domain.direction}), "
                     f"{settings}", fontsize=10)
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", dpi=90)
    plt.close(fig)
    return "data:image/png;base64," + base64.b64encode(buffer.getvalue()).decode("ascii")


def assessment(spec: dict, report) -> dict:
    """The assessment report of the structure, zipped in the server's temporary folder.

    Parameters
    ----------
    spec : dict
        ``structure``; ``workdir`` (the server's temporary folder) and ``job`` (the job's id,
        which names the files).
    report : callable
        ``report(done, total, text)``.

    Returns
    -------
    dict
        ``file``: the name of the zip file in ``workdir`` (the server offers it for download
        while it keeps the job; the folder the report was written in is deleted once zipped),
        ``verdict`` and ``files`` of the report.
    """
    fields = spec.get("structure") or {}
    _, structure = structure_from_spec(fields)
    workdir = Path(spec["workdir"])
    name = f"assessment-{spec['job']}"
    report(0, 1, "assessment report (a few minutes)")
    summary = assessment_report(structure, workdir / name, _description(fields))
    archive = workdir / f"{name}.zip"
    with zipfile.ZipFile(archive, "w", zipfile.ZIP_DEFLATED) as zf:
        for path in sorted((workdir / name).rglob("*")):
            if path.is_file():
                zf.write(path, Path(name) / path.relative_to(workdir / name))
    shutil.rmtree(workdir / name)  # the zip holds it: the server's folder keeps one copy
    report(1, 1, "done")
    return {"file": archive.name, **summary}


def _description(fields: dict):
    """The description of a bridge of several spans of one arch whose irregular bridges its
    assessment draws (:func:`archquake.report.assess.assessment.bridge_description`), else
    None (as for an uploaded geometry file, which the structure resolves)."""
    if fields.get("geometry"):
        return None
    from ..geometry import StructureSpec
    from ..report.assess.assessment import bridge_description

    return bridge_description(StructureSpec.from_dict(
        {k: v for k, v in fields.items() if k not in ("epsilon", "seed")}))


def assessment_report(structure, out_dir: Path, description=None) -> dict:
    """Run :func:`archquake.report.assess.assess` on ``structure`` into ``out_dir`` with its
    quick sizes: the page's button is a first look; ``archquake assess`` runs the full one
    (with ``description``, a bridge's, its irregular bridges too).

    Returns
    -------
    dict
        ``verdict`` (the report's verdict in words) and ``files`` (the names written).
    """
    from ..report.assess import assess

    result = assess(structure, quick=True, out_dir=out_dir, progress=False,
                    description=description)
    return {"verdict": str(result.verdict), "files": [Path(f).name for f in result.files]}


TASKS = {"simulate": simulate, "domain": failure_domain, "assess": assessment}
"""The tasks by name."""


__all__ = ["DOMAIN_DEFAULTS", "TASKS", "assessment", "assessment_report", "check_domain",
           "failure_domain", "model_settings", "models_of", "simulate"]
