"""Every table and figure of the paper, regenerated beside the paper's values.

:func:`reproduce` runs the whole chain of the paper on its nominal arch (Oppenheim's arch, "NA")
and on irregular arches drawn with epsilon = 0.10, and writes a report:

- ``report.html``: self-contained (figures embedded as base64 PNG), opens offline;
- ``report.md`` with the PNG files beside it;
- ``results.json``: every number of the report, the settings, the environment and the run times.

Beyond the paper, two sections: how far to trust the four-link model (its failure curve beside
the rigid-block model's, :mod:`archquake.studies.comparison`; the rigid-block curve runs on a
second process while the other parts run, so that its compilation and analyses cost a CPU, not
the report's time, and so does the rigid-block fragility study, whose chunks this process shares
once its own parts are done: :meth:`archquake.report.running.Background.study`) and the
record-based fragility of the arch and its irregular sample in PGA and PGV
(:mod:`archquake.studies.record_fragility`, at a reduced size).

This module only orchestrates: the parts compute (:mod:`archquake.report.paper.parts`), the figures
are drawn from their values (:mod:`archquake.report.paper.figures`), the words written from them
(:mod:`archquake.report.paper.text`) and the files rendered (:mod:`archquake.report.render`). Every
published number comes from ``archquake/data/paper_values.toml``
(:func:`archquake.reference_arches.paper_values`); a statement of agreement in a caption is
computed from the results, never written by hand.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from pathlib import Path

from ...reference_arches import oppenheim, paper_values
from ..render import (
    Document,
    Figure,
    Paragraph,
    Section,
    Table,
    environment,
    jsonable,
    save,
    write_html,
    write_markdown,
)
from ..running import Background, Steps, Task
from . import figures as draw
from . import parts, text
from .settings import ReproductionSettings

STEPS = ("limit analysis (Table 1)", "four-link mechanisms (Tables 2-3)",
         "free vibrations (Figs. 9-14)", "pulse responses (Fig. 15)", "failure domain (Fig. 16)",
         "fragility and k~ sample (Figs. 17-21)", "figures", "rigid blocks beside four links",
         "both models in the paper's study", "record-based fragility")
"""The steps of the reproduction, in the order they run (the rows of the report's run-time
table)."""

TITLE = "archquake: the paper, regenerated"
"""The title of the report's page."""

HEADING = "The paper, regenerated"
"""The heading of the report."""


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


# ------------------------------------------------------------------------------ figures
def _figure(directory: Path, name: str, figure, label: str, caption: str, agrees) -> Figure:
    return Figure(save(figure, directory, name), label, caption, agrees)


def paper_figures(directory, arches: parts.Arches, table1: dict, table3: dict,
                  free: parts.FreeVibrations, pulses: parts.PulseResponses,
                  domain: parts.FailureDomainPart, fragility: parts.FragilityPart) -> dict:
    """Draw and write the figures of the paper's parts (Figs. 2-21), each with its caption and
    verdict.

    Parameters
    ----------
    directory : str or Path
        Where the PNG files go.
    arches, table1, table3, free, pulses, domain, fragility
        The values of the parts (:mod:`archquake.report.paper.parts`).

    Returns
    -------
    dict
        :class:`~archquake.report.render.Figure` by key (``fig02`` ... ``fig21``;
        ``fragility``: the list of Figs. 17-20).
    """
    out = Path(directory)
    figures = {
        "fig02": _figure(out, "fig02_nominal_arch.png", draw.nominal_arch(arches, table1),
                         "Fig. 2", text.nominal_arch_caption(table1), table1["NA"]["agrees"]),
        "fig04": _figure(out, "fig04_irregular_arches.png", draw.irregular_arches(arches),
                         "Fig. 4", text.IRREGULAR_ARCHES_CAPTION, None),
        "fig06": _figure(out, "fig06_08_potential_energy.png", draw.potential_energy(arches),
                         "Figs. 6-8", text.potential_energy_caption(table3),
                         table3["NA"]["agrees"]),
    }
    for case in ("elastic", *pulses.summary):
        pair, ok = free.summary[case]["restitution"], free.agrees(case)
        key, name = (("fig09", "fig09_11_free_vibration_elastic.png") if case == "elastic"
                     else (f"fig12_{case}", f"fig12_14_free_vibration_{case}.png"))
        figures[key] = _figure(out, name, draw.free_vibration(free, case),
                               text.free_vibration_figures(case),
                               text.free_vibration_caption(case, pair, ok), ok)
        if case != "elastic":
            figures[f"fig15_{case}"] = _figure(
                out, f"fig15_pulse_response_{case}.png", draw.pulse_response(pulses, case),
                "Fig. 15", text.pulse_response_caption(pulses.summary, case),
                pulses.summary[case]["nominal_agrees"])
    q = domain.summary["q_tp040"]["paper"]
    figures["fig16"] = _figure(out, "fig16_failure_domain.png",
                               draw.failure_domain(domain.domain, (0.4, q, "Q")), "Fig. 16",
                               text.failure_domain_caption(domain.summary), parts.q_agrees(q))
    curves = []
    for j, curve in enumerate(fragility.curves):
        number = 17 + j
        duration = curve["duration"]
        curves.append(_figure(
            out, f"fig{number}_fragility_tp{duration:.2f}.png",
            draw.fragility_curve(fragility.result, duration),
            f"Fig. {number}" if number <= 20 else "(no figure in the paper)",
            text.fragility_curve_caption(fragility.result, curve), parts.below_nominal(curve)))
    figures["fragility"] = curves
    figures["fig21"] = _figure(out, "fig21_fragility_surface.png",
                               draw.fragility_surface(fragility.result), "Fig. 21",
                               text.fragility_surface_caption(fragility.result, fragility.curves),
                               any(parts.below_nominal(c) for c in fragility.curves))
    return figures


def comparison_figure(directory, comparison: parts.ComparisonPart) -> Figure:
    """Draw and write the figure of the two models side by side, with its caption and verdict.

    Parameters
    ----------
    directory : str or Path
    comparison : ComparisonPart

    Returns
    -------
    Figure
    """
    ok = parts.long_pulses_agree(comparison.summary)
    return _figure(Path(directory), "comparison_rigid_blocks.png",
                   draw.model_comparison(comparison.comparison), "Rigid blocks beside four links",
                   text.comparison_caption(ok), ok)


def two_models_figures(directory, both: parts.TwoModelsPart) -> dict:
    """Draw and write the failure domain and the fragility curves by both models, with their
    captions.

    Parameters
    ----------
    directory : str or Path
    both : TwoModelsPart

    Returns
    -------
    dict
        ``two_models_domain`` and ``two_models_fragility``
        (:class:`~archquake.report.render.Figure`).
    """
    out = Path(directory)
    return {
        "two_models_domain": _figure(out, "fig16_failure_domain_both_models.png",
                                     draw.two_model_domain(both), "Fig. 16, both models",
                                     text.two_models_domain_caption(both.summary), None),
        "two_models_fragility": _figure(out, "fig17_20_fragility_both_models.png",
                                        draw.two_model_fragility(both.summary["fragility"]),
                                        "Figs. 17-20, both models",
                                        text.two_models_fragility_caption(both.summary), None),
    }


def record_fragility_figure(directory, record: parts.RecordFragilityPart) -> Figure:
    """Draw and write the figure of the record-based fragility, with its caption.

    Parameters
    ----------
    directory : str or Path
    record : RecordFragilityPart

    Returns
    -------
    Figure
    """
    return _figure(Path(directory), "record_fragility.png", draw.record_fragility(record.results),
                   "Record-based fragility", text.record_fragility_caption(record.summary), None)


def flat_figures(figures: dict) -> dict:
    """The figures by file stem, lists unrolled, in order.

    Parameters
    ----------
    figures : dict
        :class:`~archquake.report.render.Figure` or lists of them, by key.

    Returns
    -------
    dict of str to Figure
    """
    flat = {}
    for value in figures.values():
        for figure in value if isinstance(value, list) else [value]:
            flat[figure.stem] = figure
    return flat


def figure_record(figure: Figure) -> dict:
    """What ``results.json`` records of a figure: ``file``, ``paper_figure``, ``agrees``,
    ``caption``.

    Parameters
    ----------
    figure : Figure

    Returns
    -------
    dict
    """
    return {"file": figure.file, "paper_figure": figure.label, "agrees": figure.agrees,
            "caption": figure.caption}


# ------------------------------------------------------------------------------ sections
def sections(results: dict, figures: dict, paper: dict) -> list[Section]:
    """The sections of the report, from the results (their JSON form) and the figures.

    Parameters
    ----------
    results : dict
        Every number of the report (``results.json``).
    figures : dict
        The figures by key (:func:`paper_figures` and the two of the extensions).
    paper : dict
        The paper's values.

    Returns
    -------
    list of Section
    """
    s = results["settings"]
    out = [Section("Agreement with the paper", [
        Paragraph(text.introduction(s, paper)),
        Table(["quantity (nominal arch)", "paper", "ours", "difference"],
              text.agreement_rows(results)),
    ])]
    out.append(Section("Table 1: activation (limit analysis)", [
        Paragraph(text.TABLE1_TEXT),
        Table(["arch, mechanism", "quantity", "paper", "ours", "difference"],
              text.table1_rows(results["table1"])),
        figures["fig02"], figures["fig04"],
    ]))
    out.append(Section("Table 2: four-link mechanisms", [
        Table(["quantity", "paper NA", "ours NA Mech-l", "ours NA Mech-r", "difference NA",
               "paper RA-1", "ours RA-1", "paper RA-2", "ours RA-2"],
              text.table2_rows(results["table2"])),
    ]))
    out.append(Section("Table 3: critical angles and potential energy", [
        Table(["arch, mechanism", "theta_cr paper", "theta_cr ours", "phi_cr paper",
               "phi_cr ours", "theta_cr/theta_u paper", "ours", "difference"],
              text.table3_rows(results["table3"])),
        figures["fig06"],
    ]))
    out.append(Section("Free vibrations (Figs. 9-14)", [
        figures["fig09"], figures["fig12_paper"], figures["fig12_computed"],
    ]))
    out.append(Section("Pulse responses (Fig. 15)", [
        figures["fig15_paper"], figures["fig15_computed"],
    ]))
    if "fig16" in figures:
        out.append(Section("Failure domain (Fig. 16)", [figures["fig16"]]))
    if "fragility" in results:
        out.append(Section("Fragility curves and surface (Figs. 17-21)", [
            Paragraph(text.limit_sample_text(results, paper)),
            Table(["t_p [s]", "nominal failure acceleration [g]", "lognormal median [g]",
                   "lognormal dispersion", "P_F just below the nominal failure acceleration"],
                  text.fragility_rows(results["fragility"]["curves"])),
            *figures["fragility"], figures["fig21"],
        ]))
    if "comparison" in results:
        c = results["comparison"]
        header = ["t_p [s]", "rigid blocks [g]"] + [
            f"four-link, {n} c_v = {pair[0]:.3f} [g]" for n, pair in c["restitution"].items()
        ] + ["recovery above the failure acceleration [g]"]
        out.append(Section("How far to trust the four-link model", [
            *(Paragraph(t) for t in text.comparison_text(c)),
            Table(header, text.comparison_rows(c)), figures["comparison"],
        ]))
    if "two_models" in results:
        out.append(Section("Both models in the paper's study (Figs. 16-20)", [
            *(Paragraph(t) for t in text.two_models_text(results["two_models"],
                                                          s["comparison_resolution_g"])),
            figures["two_models_domain"], figures["two_models_fragility"],
        ]))
    if "record_fragility" in results:
        out.append(Section("Record-based fragility (PGA, PGV)", [
            Paragraph(text.record_text(results["record_fragility"], s)),
            Table(["IM [unit]", "median, irregular arches", "total dispersion",
                   "median, nominal arch", "record-to-record dispersion",
                   "geometric dispersion", "sqrt(rtr^2 + geo^2)"],
                  text.record_rows(results["record_fragility"])),
            figures["record_fragility"],
        ]))
    out.append(Section("Where the paper is wrong or silent, and the choices made", [
        *(Paragraph(n) for n in text.notes(results)),
        Table(["c_v", "case", "paper", "ours", "verdict"], text.restitution_rows(results)),
    ]))
    out.append(Section("Runtime and environment", text.run_info(results)))
    if results.get("missing"):
        out.append(Section("Not reproduced", [Paragraph(m) for m in results["missing"]]))
    return out


# ------------------------------------------------------------------------------ driver
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
    from ...models import model_for
    from ...results_io import write_json
    from ...rigid_blocks.model import warm_up

    settings = ReproductionSettings() if settings is None else settings
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    paper = paper_values()
    env = environment()
    started = time.perf_counter()
    nominal = oppenheim()
    steps = Steps(len(STEPS), progress, desc="reproduce")
    # the rigid-block curve and the record studies run on a second CPU meanwhile
    with Background.start(warm_up) as background:
        blocks = model_for(nominal, "rigid-blocks")
        curve = background.submit(parts.rigid_block_curve, blocks, settings)
        # its chunks on the second CPU, and on this one too once its own parts are done
        rigid_fragility = background.study(parts.rigid_block_fragility, settings, after=curve)
        with steps("limit analysis (Table 1)"):
            arches = parts.paper_arches(settings, nominal)
            table1 = parts.limit_table(arches, paper)
        with steps("four-link mechanisms (Tables 2-3)"):
            table2, table3 = parts.mechanism_tables(arches, paper)
            cases = parts.restitution_cases(settings, arches)
            restitution = parts.restitution_summary(arches, cases)
        with steps("free vibrations (Figs. 9-14)"):
            free = parts.free_vibrations(settings, arches, cases, paper)
        with steps("pulse responses (Fig. 15)"):
            pulses = parts.pulse_responses(cases, paper)
        with steps("failure domain (Fig. 16)"):
            domain = parts.failure_domain(settings, arches, cases)
            # the four-link engine is compiled and cached by now: the second process loads it
            # instead of compiling it a second time; while it is still compiling the rigid
            # blocks (a cold cache), this process runs the record studies (four links)
            # meanwhile, instead of waiting for them after the rigid blocks' work
            records = (Task.run_now(parts.record_studies, settings)
                       if background.parallel and not curve.done
                       else background.submit(parts.record_studies, settings))
        with steps("fragility and k~ sample (Figs. 17-21)"):
            fragility = parts.fragility(settings, cases, progress)
        with steps("figures"):
            figures = paper_figures(out, arches, table1, table3, free, pulses, domain, fragility)
        with steps("rigid blocks beside four links"):
            comparison = parts.model_comparison(settings, arches.nominal, blocks, curve.result())
            comparison_fig = comparison_figure(out, comparison)
        with steps("both models in the paper's study"):
            both = parts.two_models(settings, arches, cases, comparison, fragility,
                                    rigid_fragility.result())
            both_figs = two_models_figures(out, both)
        with steps("record-based fragility"):
            record = parts.record_fragility(settings, records.result())
            record_fig = record_fragility_figure(out, record)
    figures = {**figures, "comparison": comparison_fig, "record_fragility": record_fig,
               **both_figs}
    t0 = time.perf_counter()
    flat = flat_figures(figures)
    timings = {**steps.timings, "report": 0.0, "total": time.perf_counter() - started}
    results = jsonable({
        "settings": settings.to_dict(), "environment": env, "timings": timings,
        "background": {"rigid-block curve": comparison.run, "record studies": record.run,
                       "rigid-block fragility": both.run},
        "missing": [], "table1": table1, "table2": table2, "table3": table3,
        "restitution": restitution, "free_vibration": free.summary, "pulse": pulses.summary,
        "failure_domain": domain.summary, "limit_sample": fragility.limit_sample,
        "fragility": fragility.summary, "comparison": comparison.summary,
        "two_models": both.summary,
        "record_fragility": record.summary,
        "figures": {stem: figure_record(f) for stem, f in flat.items()}})
    document = Document(TITLE, HEADING, sections(results, figures, paper))
    write_html(out / "report.html", document, out)
    write_markdown(out / "report.md", document)
    results["timings"]["report"] = time.perf_counter() - t0
    results["timings"]["total"] = time.perf_counter() - started
    write_json(out / "results.json", results)
    steps.close()
    return Reproduction(results, out, tuple(f.file for f in flat.values()))


__all__ = ["HEADING", "STEPS", "TITLE", "Reproduction", "comparison_figure", "figure_record",
           "flat_figures", "paper_figures", "record_fragility_figure", "reproduce", "sections",
           "two_models_figures"]
