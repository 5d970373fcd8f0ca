"""``archquake compare``: failure accelerations of the rigid-block and four-link models side by
side; :func:`archquake.studies.comparison.compare_models`."""

from __future__ import annotations

import argparse
import math

from ..defaults import (
    COMPARE_AMPLITUDES_G,
    COMPARE_DURATIONS,
    COMPARE_RESOLUTION_G,
    MIN_COMPARE_RESOLUTION_G,
)
from ..ranges import number, parse_values, range_text
from . import options
from .output import print_json

DESCRIPTION = (
    "How far to trust the four-link model: per duration t_p of Oppenheim's pulse (-a for t_p, "
    "+a/2 for 2 t_p, then 0), the failure acceleration (lowest collapsing amplitude a) and the "
    "recovery bands above it, in the rigid-block model (every voussoir a block, contacts with "
    "friction) and in the four-link model with the restitution models computed, link, paper "
    "and measured (c_v measured on the rigid blocks). Both models scan the same amplitudes, "
    "bisect every boundary to the same resolution and are not extended beyond the scan. "
    "Accelerations in g. The rigid-block analyses are the long part (about a second per "
    "duration).")


def configure(parser: argparse.ArgumentParser) -> None:
    """The options of ``archquake compare``."""
    parser.description = DESCRIPTION
    options.add_arch_options(parser)
    parser.add_argument("--durations", default=",".join(f"{d:g}" for d in COMPARE_DURATIONS),
                        metavar="LIST",
                        help="pulse durations t_p [s]: comma list and/or ranges start:stop:step "
                             "(default: %(default)s)")
    parser.add_argument("--amplitudes", default=range_text(COMPARE_AMPLITUDES_G),
                        metavar="LIST",
                        help="scan grid of amplitudes a [g] of both models, increasing "
                             "(default: %(default)s)")
    parser.add_argument("--resolution", type=number, default=COMPARE_RESOLUTION_G, metavar="G",
                        help=f"bisection width of every boundary [g], >= "
                             f"{MIN_COMPARE_RESOLUTION_G:g} (default: %(default)s)")
    parser.add_argument("--direction", choices=("l", "r"), default="l",
                        help="l: the first pulse is -a g (opens Mech-l); r: +a g (Mech-r) "
                             "(default: %(default)s)")
    options.add_rigid_block_options(parser)
    options.add_search_options(parser.add_argument_group("search of the rigid-block scan"))
    options.add_workers_option(parser, help="local worker processes of the rigid-block "
                                            "analyses, one duration per task, at most 4 per CPU "
                                            "(default: 1, run in this process)")
    options.add_plot_option(parser, "write the failure curves of both models against t_p")
    options.add_progress_option(parser, "no progress bar")
    options.add_json_option(parser, "machine-readable output: [{duration, rigid_block, "
                                    "four_link: {computed, link, paper, measured}, "
                                    "recovery_above, scanned_to, undecided, "
                                    "undecided_analyses}]")


def run(args: argparse.Namespace) -> int:
    """The comparison of the two models of the arch of the options."""
    from ..studies.comparison import compare_models

    durations = parse_values(args.durations, "--durations")
    amplitudes = parse_values(args.amplitudes, "--amplitudes")
    if not (math.isfinite(args.resolution) and args.resolution >= MIN_COMPARE_RESOLUTION_G):
        # the library takes any width > 0; finer than this only costs rigid-block analyses
        raise ValueError(f"--resolution must be >= {MIN_COMPARE_RESOLUTION_G:g} g, got "
                         f"{args.resolution}")
    settings = options.model_spec_from_args(args, "rigid-blocks").block_settings
    if args.plot:
        from .output import check_figure_path

        check_figure_path(args.plot)
    arch = options.arch_from_args(args)
    with options.analysing(args):
        comparison = compare_models(arch, durations, amplitudes_g=amplitudes,
                                    resolution_g=args.resolution, direction=args.direction,
                                    settings=settings, workers=args.workers,
                                    progress=not args.no_progress, search=args.search,
                                    stride=args.stride)
    if args.plot:
        from .output import pyplot, save_figure

        plt = pyplot()
        from ..plotting import plot_model_comparison, plot_model_differences

        fig, (left, right) = plt.subplots(1, 2, figsize=(14.5, 5.6), constrained_layout=True,
                                          width_ratios=(1.2, 1.0))
        plot_model_comparison(comparison, left)
        plot_model_differences(comparison, right)
        save_figure(fig, args.plot)
    rows = comparison.to_list()
    from ..defaults import AGREEMENT_BAND, DEFAULT_STRIDE

    differences = comparison.relative_differences()
    for i, row in enumerate(rows):  # where the four-link value is not to be trusted
        row["agreement_band"] = AGREEMENT_BAND
        row["beyond_band"] = {name: bool(abs(d[i]) > AGREEMENT_BAND)
                              for name, d in differences.items() if math.isfinite(d[i])}
    from ..studies.strategies import search_caveat

    blocks = comparison.rigid_block  # the searched scan; the four-link one is exhaustive
    stride = DEFAULT_STRIDE if args.stride is None else args.stride
    if args.json:
        if blocks.search == "bisection" and blocks.not_analysed:  # what it may have missed
            for row, skipped, points in zip(rows, blocks.not_analysed, blocks.scan_points,
                                            strict=True):
                row.update(search=blocks.search, not_analysed=skipped, scan_points=points,
                           caveat="rigid blocks: " + search_caveat(blocks.search, skipped,
                                                                   points, stride))
        print_json(rows)
        return 0
    caveat = search_caveat(blocks.search, sum(blocks.not_analysed), sum(blocks.scan_points),
                           stride)
    if caveat:
        print(f"warning: rigid blocks: {caveat}")
    from ..studies.undecided import bands_text, undecided_warning

    warning = undecided_warning(comparison.undecided_analyses,
                                sum(comparison.rigid_block.analyses), "rigid-block analyses")
    if warning:
        print(warning)
    coefficients = ", ".join(f"{name} {pair[0]:.3f}" for name, pair in
                             comparison.restitution.items())
    print(f"Failure acceleration [g] under Oppenheim's pulse, first pulse "
          f"{'-' if args.direction == 'l' else '+'}a g; k = {comparison.load_multiplier:.4f}")
    settings = comparison.settings  # its time step chosen from the structure unless given
    print(f"rigid blocks: friction {settings.friction:g}, time step {settings.time_step:g} s "
          f"(coarse factor {settings.coarse_factor}); "
          f"four-link c_v: {coefficients}; scan {amplitudes[0]:g}-{amplitudes[-1]:g} g, "
          f"boundaries to {args.resolution:g} g; (+x %): four-link vs rigid blocks")
    names = list(comparison.four_link)
    print(f"{'t_p [s]':>8} {'rigid blocks':>13}" + "".join(f" {n:>15}" for n in names))
    upper = []
    for row in rows:
        top = f"> {row['scanned_to']:.3g}"
        bounds = row.get("failure_acceleration_bound", {})
        rigid = row["rigid_block"]
        low = row.get("failure_undecided_from", {}).get("rigid_block")
        if bounds:
            upper.append(row["duration"])
        if low is not None:  # undecided below the lowest decided collapse: a range
            cells = [(f"{low:.3f}.." + ("" if rigid is None else f"{rigid:.3f}")).rjust(13)]
            rigid = None  # no difference to a failure acceleration that is not decided
        elif rigid is None:
            cells = [f"{top:>13}"]
        else:
            cells = [(f"<= {rigid:.3f}" if "rigid_block" in bounds else f"{rigid:.3f}")
                     .rjust(13)]
        for name in names:
            value = row["four_link"][name]
            if value is None:
                cells.append(f"{top:>15}")
            elif name in bounds:
                cells.append(f"<= {value:.3f}".rjust(15))
            elif rigid is None or "rigid_block" in bounds:
                cells.append(f"{value:>15.3f}")
            else:
                flag = "!" if row["beyond_band"].get(name) else " "
                cells.append(f"{value:>7.3f} ({100 * (value / rigid - 1):+4.0f} %){flag}"
                             .rjust(15))
        print(f"{row['duration']:>8.3f} " + " ".join(cells))
    if any(any(row["beyond_band"].values()) for row in rows):
        print(f"!: the four-link value is off by more than {100 * AGREEMENT_BAND:g} %: the "
              f"rigid-block model is the trusted one (it agrees with LMGC90 to 1 % on fixed "
              f"supports, 0.4 % on piers)")
    if upper:
        print("<=: collapse from the lowest amplitude scanned at t_p = "
              + ", ".join(f"{d:g}" for d in upper) + " s: the failure acceleration is at "
              "most it (start --amplitudes lower)")
    bands = []
    for row in rows:
        for name, values in (("rigid blocks", row["recovery_above"]["rigid_block"]),
                             *row["recovery_above"]["four_link"].items()):
            if values:
                text = ", ".join(f"{a:.3f}-{b:.3f}" for a, b in values)
                bands.append(f"  t_p = {row['duration']:g} s, {name}: {text}")
    if bands:
        print("recovery above the failure acceleration [g]:")
        print("\n".join(bands))
    print(f"rigid blocks undecided: {comparison.undecided_analyses} of "
          f"{sum(comparison.rigid_block.analyses)} analyses")
    for row in rows:
        if row["undecided"]["rigid_block"]:
            print(f"  t_p = {row['duration']:g} s: {row['undecided_analyses']['rigid_block']} "
                  f"undecided, bands {bands_text(row['undecided']['rigid_block'])} g")
    if any("failure_undecided_from" in row for row in rows):
        print("a..b: the rigid blocks are undecided from a below their lowest decided collapse "
              "b: the failure acceleration lies between a and b (a..: at least a), and is not "
              "compared")
    for name, why in comparison.skipped.items():
        print(f"restitution {name!r} left out: {why}")
    if args.plot:
        print(f"figure written to {args.plot}")
    return 0
