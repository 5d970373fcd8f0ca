"""``archquake fragility``: Monte Carlo fragility study under pulses (paper Sect. 5.3.3, Figs.
17-21); :func:`archquake.studies.fragility.run_fragility`. The study under recorded
accelerograms is ``archquake record-fragility`` (:mod:`archquake.cli.main_record_fragility`).
"""

from __future__ import annotations

import argparse

from ..defaults import (
    DEFAULT_RESTITUTION,
    DEFAULT_SAMPLE_LIMIT_METHOD,
    LIMIT_METHODS,
    LIMIT_SAMPLE_SIZE,
    MAX_GRID_POINTS,
    MAX_LIMIT_SAMPLES,
    MAX_STUDY_ANALYSES,
    STUDY_AMPLITUDES_G,
    STUDY_DURATIONS,
)
from ..ranges import parse_values, range_text
from . import options
from .output import print_json

DESCRIPTION = (
    "Draw h irregular arches around the nominal arch (eq. 1), run Oppenheim's pulse in both "
    "directions over every (t_p, a) of the grid, and estimate P_F = h_f/h (eq. 9; an arch fails "
    "if it collapses in either direction), with quintic and lognormal fits per duration; the "
    "CDF of the limit-analysis multiplier k~ = min(k~_l, k~_r) of s arches; the nominal arch's "
    f"failure acceleration and k. Default restitution: '{DEFAULT_RESTITUTION}', each arch's "
    "own c_v from its momentum balance; --restitution nominal applies the nominal arch's "
    "computed c_v to every irregular arch (the paper's practice). A drawn arch that is not an "
    "arch or cannot stand is excluded, counted and named, and left out of h. With --spans "
    "(the rigid blocks alone): irregular bridges, one irregular arch a span, those whose piers "
    "cannot seat the draws excluded as 'not seated'. Writes "
    "results.parquet/.csv (one row per analysis), curves.csv, summary.json and limit_sample/ to "
    "--out; checkpoints allow --resume.")

def configure(parser: argparse.ArgumentParser) -> None:
    """The options of ``archquake fragility``."""
    parser.description = DESCRIPTION
    options.add_nominal_arch_options(parser)
    options.add_samples_option(parser)
    parser.add_argument("--durations", default=",".join(f"{d:g}" for d in STUDY_DURATIONS),
                        metavar="LIST",
                        help="pulse durations t_p [s] (default: %(default)s)")
    parser.add_argument("--amplitudes", default=range_text(STUDY_AMPLITUDES_G),
                        metavar="LIST",
                        help=f"amplitudes a [g], increasing; durations x amplitudes at most "
                             f"{MAX_GRID_POINTS}, and 2 x samples x durations x amplitudes at "
                             f"most {MAX_STUDY_ANALYSES} analyses (default: %(default)s)")
    options.add_model_options(parser)
    options.add_restitution_option(parser, of_a_model=True)
    options.add_rigid_block_options(parser, of_a_model=True)
    parser.add_argument("--limit-samples", type=int, default=LIMIT_SAMPLE_SIZE, metavar="S",
                        help=f"number s of arches of the limit-analysis CDF of k~, at most "
                             f"{MAX_LIMIT_SAMPLES} (default: %(default)s)")
    parser.add_argument("--limit-method", choices=LIMIT_METHODS,
                        default=DEFAULT_SAMPLE_LIMIT_METHOD,
                        help="limit-analysis method of that sample (same k~; kinematic is "
                             "faster) (default: %(default)s)")
    options.add_model_check_option(parser)
    options.add_study_output_options(parser)


def run(args: argparse.Namespace) -> int:
    """The pulse study of the options."""
    from ..studies.fragility import CURVES_CSV, LIMIT_DIRECTORY, FragilitySettings, run_fragility

    structure = options.sampled_structure_from_args(args)
    settings = FragilitySettings(
        **structure, sample_size=args.samples,
        epsilon=args.epsilon,
        durations=tuple(parse_values(args.durations, "--durations")),
        amplitudes_g=tuple(parse_values(args.amplitudes, "--amplitudes")),
        seed=args.seed, limit_sample_size=args.limit_samples,
        limit_method=args.limit_method,
        model=options.structure_model_spec(args, "description" in structure),
        search=args.search, stride=args.stride)
    result = run_fragility(settings, args.out, workers=args.workers, scheduler=args.scheduler,
                           resume=args.resume, progress=not args.no_progress)
    written = []
    if args.plot_dir:
        written = _plot(result, args.plot_dir)
    summary = result.summary()
    check = None
    if settings.model.name == "four-link":  # the nominal arch's four-link numbers, checked
        def four_link():
            return settings.model.build(settings.nominal, settings.nominal)

        check = options.model_check(args, settings.nominal, four_link, settings.durations)
        summary["model_check"] = {"skipped": check["skipped"], "probe": check["probe"]}
    if args.json:
        print_json(summary)
        return 0
    n_analyses = len(result.table)
    c_lr, c_rl = summary["nominal_restitution"]
    if settings.model.grid_in_one_call:
        model = f"{settings.model.settings_text()} (nominal arch: {c_lr:.4f})"
    else:
        analysed = int(result.table["analysed"].sum())
        model = (f"{settings.model.settings_text()}, search {settings.search!r}: {analysed} "
                 f"analysed, the others inferred")
    from ..studies.undecided import undecided_warning

    undecided = summary["undecided"]
    warning = undecided_warning(undecided["analyses"] + undecided["nominal_analyses"],
                                undecided["of"] + sum(sum(d.analyses)
                                                      for d in result.nominal_domains))
    if warning:
        print(warning)
    for line in (check or {}).get("lines", ()):
        print(f"warning: nominal arch: {line}")
    one, kind = settings.member_nouns
    print(f"Fragility study: h = {settings.sample_size} irregular {kind} (epsilon = "
          f"{settings.epsilon:g}, seed {settings.seed}), {len(settings.durations)} durations x "
          f"{len(settings.amplitudes_g)} amplitudes x 2 directions = {n_analyses} analyses; "
          f"{model}")
    if summary["search"]["caveat"]:
        print(f"warning: {summary['search']['caveat']}")
    print(f"nominal {one}: k = {result.nominal_load_multiplier:.4f}")
    arches = summary["arches"]
    if arches["excluded"]:
        listed = "; ".join(f"{why}: {', '.join(map(str, items))}"
                           for why, items in arches["excluded"].items())
        print(f"excluded: {arches['drawn'] - arches['analysed']} of {arches['drawn']} {kind} "
              f"could not be analysed ({listed}; member i is drawn from SeedSequence("
              f"{settings.seed}, spawn_key=(i,))); P_F = h_f / h over the h = "
              f"{arches['analysed']} {kind} analysed")
    print(f"{'t_p [s]':>8} {'Q nominal [g]':>14} {'P_F below Q':>12} {'lowest a_f [g]':>15} "
          f"{'lognormal median [g]':>21} {'beta':>6}")

    def fmt(x, width, digits=4):
        return f"{'-':>{width}}" if x is None else f"{x:>{width}.{digits}f}"

    def nominal(row, width):
        if "nominal_failure_undecided_from" in row:  # an undecided band below it
            high = row["nominal_failure_acceleration"]
            return (f"{row['nominal_failure_undecided_from']:.3f}.."
                    + ("" if high is None else f"{high:.3f}")).rjust(width)
        if row.get("nominal_failure_acceleration_bound") == "upper":  # collapse from the start
            return f"<= {row['nominal_failure_acceleration']:.4f}".rjust(width)
        return fmt(row["nominal_failure_acceleration"], width)

    def below(row, width):
        if "probability_below_nominal_upper" in row:  # bounded by undecided arches
            return (f"{row['probability_below_nominal']:.3f}-"
                    f"{row['probability_below_nominal_upper']:.3f}").rjust(width)
        return fmt(row["probability_below_nominal"], width, 3)

    for row in summary["durations"]:
        print(f"{row['duration']:>8.3f} {nominal(row, 14)} {below(row, 12)} "
              f"{fmt(row['lowest_failure_acceleration'], 15, 2)} "
              f"{fmt(row['lognormal_median'], 21)} {fmt(row['lognormal_dispersion'], 6, 3)}"
              + options.model_check_note(check, row["duration"]))
    k = summary["limit_sample"]

    def number(x, digits=4):
        return "-" if x is None else f"{x:.{digits}f}"

    others = [f"{k[key]} {what}" for key, what in (("excluded", "excluded"),
                                                     ("never_collapse", "never collapse"))
              if k[key]]
    print(f"k~ = min(k~_l, k~_r) over s = {k['count']} {kind} ({k['method']}"
          + "".join(f"; {o}" for o in others) + f"): mean {number(k['mean'])}, std "
          f"{number(k['std'])}, min {number(k['min'])}, max {number(k['max'])}; fraction below "
          f"the nominal k (by more than {k['below_nominal_rtol']:g} relative): "
          f"{number(k['fraction_below_nominal'], 3)}")
    print(f"P_F below Q: fraction of irregular {kind} that fail at the largest amplitude of "
          f"the grid below the nominal failure acceleration Q (where the nominal {one} "
          "survives)")
    _print_undecided(summary, undecided, (one, kind))
    print(f"written to {args.out}: results.parquet, results.csv, {CURVES_CSV}, summary.json, "
          f"{LIMIT_DIRECTORY}/")
    for path in written:
        print(f"figure written to {path}")
    return 0


def _print_undecided(summary: dict, undecided: dict, kind=("arch", "arches")) -> None:
    """The count of undecided analyses and, where there are any, the bounds of P_F they leave
    (:mod:`archquake.studies.undecided`); ``kind`` names a member, one and several
    (``("bridge", "bridges")`` for a study of bridges)."""
    print(f"undecided: {undecided['analyses']} of {undecided['of']} analyses of the irregular "
          f"{kind[1]}, {undecided['nominal_analyses']} of the nominal {kind[0]}'s failure "
          "domains")
    gaps = [(row["duration"], row["undecided"], row["probability_upper_largest_gap"])
            for row in summary["durations"] if row["undecided"]]
    if gaps:
        print("P_F counts an arch whose failure is undecided as a survival (the lower bound; "
              "the fits too); as a failure it is the upper bound (curves.csv: "
              "probability_upper): " + "; ".join(
                  f"t_p = {d:g} s: {n} arch-amplitude points undecided, bounds up to "
                  f"{gap:.3f} apart" for d, n, gap in gaps))
    if any("nominal_failure_undecided_from" in row for row in summary["durations"]):
        print("a..b: the nominal arch is undecided from a below its lowest decided collapse b: "
              "Q lies between a and b")


def _plot(result, plot_dir) -> list[str]:
    from .output import plot_directory, pyplot, save_figure

    pyplot()
    from ..plotting import plot_fragility_curve, plot_fragility_surface

    directory = plot_directory(plot_dir)
    written = []
    for tp in result.durations:
        path = directory / f"fragility_tp{tp:.3f}.png"
        ax = plot_fragility_curve(result, tp)
        save_figure(ax.figure, path)
        written.append(str(path))
    path = directory / "fragility_surface.png"
    ax = plot_fragility_surface(result)
    save_figure(ax.figure, path)
    written.append(str(path))
    return written
