"""``archquake record-fragility``: a multiple-stripe study of a suite of records;
:func:`archquake.studies.record_fragility.run_record_fragility`."""

from __future__ import annotations

import argparse
import math

from ..defaults import DEFAULT_IM
from ..ranges import parse_values
from . import options
from .output import print_json

DESCRIPTION = (
    "Every record is scaled to each --levels value of --im and applied in both polarities to "
    "the h irregular arches and to the nominal arch; an arch-record pair fails if it collapses "
    "in either polarity. P(collapse | IM) per stripe, lognormal fits by maximum likelihood "
    "(irregular arches pooled; the nominal arch alone, the record-to-record dispersion; a common "
    "dispersion over records, the geometric one) with 90% bootstrap bands over arches and "
    "records. --epsilon 0 --samples 1 is the nominal arch alone. With --spans (the rigid "
    "blocks alone): irregular bridges, one irregular arch a span. Writes results.parquet/.csv "
    "(one row per arch, record, level and polarity), curves.csv, incremental.csv and "
    "summary.json to --out.")


def add_record_options(parser: argparse.ArgumentParser) -> None:
    """``--records`` or ``--suite``, ``--im``, ``--levels`` and ``--export-nrml``."""
    group = parser.add_argument_group("records and stripes")
    group.add_argument("--records", nargs="+", metavar="PATH",
                       help="record files (PEER .AT2, CSV in g, ESM .ASC) and folders of them")
    options.add_suite_option(group)
    group.add_argument("--im", metavar="NAME",
                       help="intensity measure of the stripes: pga [g], pgv [m/s], pgd [m], "
                            f"arias [m/s] or sa(T) [g] with T the period [s] (default: "
                            f"{DEFAULT_IM})")
    group.add_argument("--levels", metavar="LIST",
                       help="stripe levels of --im in its unit, increasing and > 0, e.g. "
                            "0.1:1.0:0.05 (required with --records)")
    group.add_argument("--export-nrml", metavar="FILE",
                       help="write the fitted fragility functions (irregular arches, nominal "
                            "arch) as an OpenQuake NRML fragility model, format continuous "
                            "logncdf")


def configure(parser: argparse.ArgumentParser) -> None:
    """The options of ``archquake record-fragility``."""
    parser.description = DESCRIPTION
    options.add_nominal_arch_options(parser)
    options.add_samples_option(parser)
    options.add_model_options(parser)
    options.add_restitution_option(parser, of_a_model=True)
    options.add_rigid_block_options(parser, of_a_model=True)
    add_record_options(parser)
    options.add_model_check_option(parser)
    options.add_study_output_options(parser)


def run(args: argparse.Namespace) -> int:
    """The record-based study of the options."""
    from ..studies.record_fragility import (
        CURVES_CSV,
        INCREMENTAL_CSV,
        RecordFragilitySettings,
        run_record_fragility,
        stripe_measure,
    )

    im = stripe_measure(args.im or DEFAULT_IM)
    if not args.records and not args.suite:
        raise ValueError("give the records: --records PATH... or --suite NAME")
    if args.levels is None:
        given = "--suite" if args.suite else "--records"
        raise ValueError(f"--levels is required with {given}: the stripe levels of {im.name} "
                         f"[{im.unit}], e.g. --levels 0.1:1.0:0.05")
    suite = options.suite_from_args(args)
    structure = options.sampled_structure_from_args(args)
    settings = RecordFragilitySettings(
        suite=suite,
        levels=tuple(parse_values(args.levels, "--levels")), im=im.name,
        **structure, sample_size=args.samples,
        epsilon=args.epsilon, seed=args.seed,
        model=options.structure_model_spec(args, "description" in structure),
        search=args.search, stride=args.stride)
    result = run_record_fragility(settings, args.out, workers=args.workers,
                                  scheduler=args.scheduler, resume=args.resume,
                                  progress=not args.no_progress)
    written = _plot(result, args.plot_dir) if args.plot_dir else []
    if args.export_nrml:
        try:
            written.append(str(result.export_nrml(args.export_nrml)))
        except OSError as exc:
            raise ValueError(f"cannot write --export-nrml {args.export_nrml!r}: "
                             f"{exc.strerror}") from exc
    summary = result.summary()
    check = None
    if settings.model.name == "four-link":  # the nominal arch's four-link model, checked
        from ..studies.comparison import PROBE_REFERENCE_DURATIONS


        def four_link():
            return settings.model.build(settings.nominal, settings.nominal)

        check = options.model_check(args, settings.nominal, four_link,
                                    PROBE_REFERENCE_DURATIONS)
        summary["model_check"] = {"skipped": check["skipped"], "probe": check["probe"]}
    if args.json:
        print_json(summary)
        return 0
    for line in (check or {}).get("lines", ()):
        print(f"warning: nominal arch under Oppenheim's pulse: {line}")
    _print(result, summary)
    print(f"written to {args.out}: results.parquet, results.csv, {CURVES_CSV}, "
          f"{INCREMENTAL_CSV}, summary.json")
    for path in written:
        print(f"written {path}")
    return 0


def _print(result, summary: dict) -> None:
    from ..studies.undecided import undecided_warning

    s = result.settings
    unit = s.unit
    analyses = summary["analyses"]
    undecided = summary["undecided"]
    warning = undecided_warning(undecided["analyses"] + undecided["nominal_analyses"],
                                undecided["of"] + undecided["nominal_of"])
    caveat = summary["search"]["caveat"]
    if caveat:
        print(f"warning: {caveat}")
    if warning:
        print(warning)
    kind, kinds = s.member_nouns
    print(f"Record-based fragility: h = {s.sample_size} irregular {kinds} (epsilon = "
          f"{s.epsilon:g}, seed {s.seed}) and the nominal {kind}, {len(result.records)} records "
          f"x {result.levels.size} levels of {s.im} [{unit}] x 2 polarities = "
          f"{analyses['total']} analyses ({analyses['at_rest_without_integration']} at rest "
          f"without integration); {s.model.settings_text()}")
    curves = result.curves()
    print(f"{'level [' + unit + ']':>12} {'P irregular':>12} {'P nominal':>10} "
          f"{'lognormal':>10} {'band':>15}")

    def bounded(lower, upper, width):  # a probability, or its bounds with undecided analyses
        text = f"{lower:.3f}" if upper == lower else f"{lower:.3f}-{upper:.3f}"
        return f"{text:>{width}}"

    for row in curves.itertuples():
        band = ("-" if not math.isfinite(row.band_lower)
                else f"{row.band_lower:.3f}-{row.band_upper:.3f}")
        fit = "-" if not math.isfinite(row.lognormal_fit) else f"{row.lognormal_fit:.3f}"
        print(f"{row.level:>12.4g} {bounded(row.probability, row.probability_upper, 12)} "
              f"{bounded(row.nominal_probability, row.nominal_probability_upper, 10)} "
              f"{fit:>10} {band:>15}")
    print(f"undecided: {undecided['analyses']} of {undecided['of']} analyses of the irregular "
          f"{kinds}, {undecided['nominal_analyses']} of {undecided['nominal_of']} of the "
          f"nominal {kind}")
    if undecided["analyses"] or undecided["nominal_analyses"]:
        print("a-b: P with the pairs whose failure is undecided counted as survivals (a, the "
              "lower bound; the fits and bands too) and as collapses (b, the upper bound)")

    def describe(fit, band):
        if fit["median"] is None:
            return "no lognormal fit (no collapse, no survival, or a single step)"
        text = f"median {fit['median']:.4g} {unit}, beta {fit['dispersion']:.3f}"
        if band is not None:
            lo, hi = band["median_interval"]
            b_lo, b_hi = band["dispersion_interval"]
            text += (f" ({100 * band['confidence']:.0f}% bootstrap intervals: median "
                     f"{lo:.4g}-{hi:.4g}, beta {b_lo:.3f}-{b_hi:.3f}; {band['resamples']} "
                     f"resamples)")
        return text

    total, nominal = summary["lognormal"], summary["nominal"]["lognormal"]
    print(f"irregular {kinds}, all pairs: {describe(total, total['band'])}")
    print(f"nominal {kind}: {describe(nominal, nominal['band'])}")
    v = summary["variability"]

    def fmt(x):
        return "-" if x is None else f"{x:.3f}"

    print(f"dispersions: record-to-record {fmt(v['record_to_record'])}, geometric "
          f"{fmt(v['geometric'])}, total {fmt(v['total'])} (srss of the first two "
          f"{fmt(v['srss'])})")
    inc = summary["incremental"]
    print(f"incremental view: {inc['pairs_collapsing']} of {inc['pairs']} arch-record pairs "
          f"collapse at some level; {inc['pairs_recovering_above_first_collapse']} of them "
          "survive again at a level above their lowest collapsing one")


def _plot(result, plot_dir) -> list[str]:
    import re

    from .output import plot_directory, pyplot, save_figure

    pyplot()
    from ..plotting import plot_incremental, plot_record_fragility

    directory = plot_directory(plot_dir)
    tag = re.sub(r"[^\w.-]", "_", result.settings.im)
    written = []
    for name, plot in (("fragility", plot_record_fragility), ("incremental", plot_incremental)):
        path = directory / f"record_{name}_{tag}.png"
        ax = plot(result)
        save_figure(ax.figure, path)
        written.append(str(path))
    return written
