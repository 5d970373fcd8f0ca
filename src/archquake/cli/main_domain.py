"""``archquake domain``: failure domain over (t_p, a) (paper Sect. 5.3.3, Fig. 16) of either
model; :func:`archquake.studies.failure_domain.domain_of`."""

from __future__ import annotations

import argparse
import math

from ..defaults import (
    DEFAULT_EXTEND_TO_G,
    DEFAULT_RESOLUTION_G,
    DEFAULT_STRIDE,
    DOMAIN_AMPLITUDES_G,
    DOMAIN_DURATIONS,
    MAX_BLOCK_GRID_POINTS,
    MAX_GRID_POINTS,
    MIN_RESOLUTION_G,
)
from ..ranges import number, parse_values, range_text
from . import options
from .output import print_json

DESCRIPTION = (
    "Outcome of Oppenheim's pulse (-a for t_p, +a/2 for 2 t_p, then 0) over a grid of "
    "durations t_p and amplitudes a: every change of outcome along the amplitude (rest, "
    "recovery, collapse in half cycle h) is bisected. Prints per duration the failure "
    "acceleration (lowest collapsing a), the lowest a collapsing in the first half cycle "
    "(Oppenheim's curve) and the intervals. Accelerations in g. --model rigid-blocks runs the "
    "rigid-block model instead (it does not count half cycles: the scan is extended until the "
    "first collapse); it alone takes a block assembly (--spans, --rings, a drawing).")


def configure(parser: argparse.ArgumentParser) -> None:
    """The options of ``archquake domain``."""
    parser.description = DESCRIPTION
    options.add_arch_options(parser)
    options.add_model_options(parser)
    options.add_restitution_option(parser, of_a_model=True)
    options.add_rigid_block_options(parser, of_a_model=True)
    options.add_workers_option(parser, help="local worker processes of the rigid-block model, "
                                            "one duration at a time (default: this process)")
    parser.add_argument("--durations", default=range_text(DOMAIN_DURATIONS),
                        metavar="LIST",
                        help="pulse durations t_p [s]: comma list and/or ranges start:stop:step "
                             "(stop included) (default: %(default)s)")
    parser.add_argument("--amplitudes", default=range_text(DOMAIN_AMPLITUDES_G),
                        metavar="LIST",
                        help=f"scan grid of amplitudes a [g], increasing; durations x "
                             f"the amplitudes the search analyses whatever the outcomes (all "
                             f"of them, or the coarse scan of bisection and screened), with "
                             f"the extension up to --extend-to, at most {MAX_GRID_POINTS} "
                             f"({MAX_BLOCK_GRID_POINTS} with the rigid blocks) "
                             f"(default: %(default)s)")
    parser.add_argument("--extend-to", type=number, default=DEFAULT_EXTEND_TO_G, metavar="G",
                        help="where the grid holds no collapse in the first half cycle (the "
                             "rigid blocks: no collapse), scan on at its last spacing (times "
                             "--stride for the faster searches) until it is found, up to this "
                             "amplitude [g]; a boundary beyond it is reported as such; a value "
                             "not above the grid scans the grid alone (default: %(default)s)")
    parser.add_argument("--direction", choices=("l", "r"), default="l",
                        help="l: the first pulse is -a g (opens Mech-l); r: +a g (Mech-r) "
                             "(default: %(default)s)")
    parser.add_argument("--resolution", type=number, default=DEFAULT_RESOLUTION_G, metavar="G",
                        help=f"bisection width of every boundary [g], >= "
                             f"{MIN_RESOLUTION_G:g} (default: %(default)s)")
    options.add_plot_option(parser, "write the failure-domain figure")
    options.add_model_check_option(parser)
    options.add_progress_option(parser)
    options.add_json_option(parser)


def run(args: argparse.Namespace) -> int:
    """The failure domain of the arch of the options."""
    durations = parse_values(args.durations, "--durations")
    amplitudes = parse_values(args.amplitudes, "--amplitudes")
    if not (math.isfinite(args.resolution) and args.resolution >= MIN_RESOLUTION_G):
        # the library takes any width > 0; the command line refuses what means nothing
        raise ValueError(f"--resolution must be >= {MIN_RESOLUTION_G:g} g (the analyses are "
                         f"accurate to about 1e-11: finer boundaries mean nothing), got "
                         f"{args.resolution}")
    from ..studies.failure_domain import domain_of
    from ..studies.strategies import search_caveat

    domain_stride = DEFAULT_STRIDE if args.stride is None else args.stride
    model = _model(args)
    with options.analysing(args):
        domain = domain_of(model, durations, amplitudes, direction=args.direction,
                           resolution_g=args.resolution, extend_to_g=args.extend_to,
                           search=args.search,
                           stride=domain_stride,
                           workers=args.workers,
                           progress=not (args.no_progress or model.grid_in_one_call))
    if args.plot:
        from .output import pyplot, save_figure

        pyplot()
        from ..plotting import plot_failure_domain

        ax = plot_failure_domain(domain)
        save_figure(ax.figure, args.plot)
    check = None
    if model.counts_half_cycles:  # four-link numbers: checked against the rigid blocks
        check = options.model_check(args, model.arch, model, durations)
    caveat = search_caveat(domain.search, sum(domain.not_analysed), sum(domain.scan_points),
                           domain_stride)
    if args.json:
        rows = domain.to_list()
        if caveat:  # bisection: what it inferred without analysing it, and may have missed
            for row, skipped, points in zip(rows, domain.not_analysed, domain.scan_points,
                                            strict=True):
                row.update(search=domain.search, not_analysed=skipped, scan_points=points,
                           caveat=search_caveat(domain.search, skipped, points,
                                                domain_stride))
        if not model.counts_half_cycles:  # the model is said where the output is as before
            for row, sl, undecided in zip(rows, domain.slices, domain.undecided, strict=True):
                row["model"] = model.name
                row["recovery_above"] = [list(b) for b in sl.recovery_above_g]
                row["undecided"] = [list(b) for b in sl.undecided_bands_g]
                row["undecided_analyses"] = undecided
                del row["first_half_cycle_acceleration"]
        if check is not None:
            for row in rows:
                row["model_check"] = options.model_check_of_row(check, row["duration"])
        print_json(rows)
        return 0
    four_link = model.counts_half_cycles  # the table of the paper's Fig. 16
    if check is not None:
        for line in check["lines"]:
            print(f"warning: {line}")
    if four_link:
        c_lr, c_rl = domain.restitution
        what = f"restitution {c_lr:.4f} (l->r), {c_rl:.4f} (r->l)"
    else:
        from ..studies.undecided import undecided_warning

        warning = undecided_warning(domain.undecided_analyses, sum(domain.analyses),
                                    "rigid-block analyses")
        if warning:
            print(warning)
        what = (f"rigid-block model, friction {model.settings.friction:g}, time step "
                f"{model.settings.time_step:g} s (coarse factor {model.settings.coarse_factor}), "
                f"search {domain.search}")
    print(f"Failure domain, first pulse {'-' if args.direction == 'l' else '+'}a g "
          f"(Mech-{args.direction}); k = {domain.limit_multiplier:.4f}; {what}; boundaries to "
          f"{args.resolution:g} g" + (" where the search found them" if caveat else ""))
    if caveat:
        print(f"warning: {caveat}")
    if not four_link:
        return _print_rigid_block_domain(domain, args)
    print(f"{'t_p [s]':>8} {'failure [g]':>12} {'1st half [g]':>13}  intervals [g]")
    beyond = []
    for sl in domain.slices:
        parts = []
        for iv in sl.intervals:
            what = (f"collapse h={iv.half_cycle}" if iv.status == "collapse" else iv.status)
            parts.append(f"{iv.start:.3f}-{iv.end:.3f} {what}")
        columns = [_acceleration(sl, sl.failure_acceleration_g, sl.failure_acceleration_bound,
                                 12),
                   _acceleration(sl, sl.first_half_cycle_acceleration_g,
                                 sl.first_half_cycle_bound, 13)]
        if not math.isfinite(sl.first_half_cycle_acceleration_g):
            beyond.append(sl.duration)
        print(f"{sl.duration:>8.3f} {columns[0]} {columns[1]}  " + "; ".join(parts)
              + options.model_check_note(check, sl.duration))
    _say_upper_bounds(domain)
    if beyond:
        extend_to = domain.extend_to_g
        print("no collapse in the first half cycle up to the end of the scan at t_p = "
              + ", ".join(f"{d:g}" for d in beyond) + " s: the boundary lies beyond it"
              + ("" if extend_to is None else f" (scan extended up to --extend-to "
                                              f"{extend_to:g} g)"))
    if args.plot:
        print(f"figure written to {args.plot}")
    return 0


def _model(args: argparse.Namespace):
    """The model of the options' structure: a block assembly (several spans, rings, a drawing
    of one) only with the rigid blocks, which the four-link model does not describe (they are
    its default, said on stderr)."""
    nominal, structure = options.arches_from_args(args, assembly=True, spans=True)
    spec = options.structure_model_spec(args, hasattr(structure, "interfaces"))
    with options.analysing(args):
        return spec.build(structure, nominal)


def _print_rigid_block_domain(domain, args: argparse.Namespace) -> int:
    """The text output of a rigid-block domain: no half cycles, the recovery bands above the
    failure acceleration, the analyses each duration cost and the undecided ones, and a failure
    acceleration above an undecided band as the range it is known to (``a..b``)."""
    from ..studies.undecided import bands_text

    print(f"{'t_p [s]':>8} {'failure [g]':>12} {'analyses':>9}  intervals [g]")
    for sl, count in zip(domain.slices, domain.analyses, strict=True):
        parts = [f"{iv.start:.3f}-{iv.end:.3f} {iv.status}" for iv in sl.intervals]
        column = _acceleration(sl, sl.failure_acceleration_g, sl.failure_acceleration_bound, 12,
                               sl.failure_undecided_from_g)
        print(f"{sl.duration:>8.3f} {column} {count:>9d}  " + "; ".join(parts))
    _say_upper_bounds(domain)
    total = sum(domain.analyses)
    print(f"undecided: {domain.undecided_analyses} of {total} analyses")
    for sl, undecided in zip(domain.slices, domain.undecided, strict=True):
        if sl.undecided_bands_g:
            print(f"  t_p = {sl.duration:g} s: {undecided} undecided, bands "
                  f"{bands_text(sl.undecided_bands_g)} g" + _between(sl))
    if any(math.isfinite(sl.failure_undecided_from_g) for sl in domain.slices):
        print("a..b: an undecided band starts at a below the lowest decided collapse b: the "
              "failure acceleration lies between a and b (a..: at least a, none decided in "
              "the scan)")
    if args.plot:
        print(f"figure written to {args.plot}")
    return 0


def _between(sl) -> str:
    """What an undecided band below the failure acceleration leaves of it, in words."""
    low = sl.failure_undecided_from_g
    if not math.isfinite(low):
        return ""
    high = sl.failure_acceleration_g
    if math.isnan(high):
        return (f"; no decided collapse up to {sl.scanned_to_g:.3f} g: the failure "
                f"acceleration is at least {low:.3f} g, undecided from there")
    return (f"; the failure acceleration is between {low:.3f} g and {high:.4f} g, undecided "
            f"from {low:.3f} g")


def _acceleration(sl, value: float, bound: str | None, width: int,
                  undecided_from: float = math.nan) -> str:
    """An acceleration of a slice as a column: the value, ``<= value`` when the lowest amplitude
    scanned already collapses (an upper bound), ``> scanned_to`` when none does, ``a..value``
    when an undecided band starting at ``undecided_from = a`` lies below it (``a..`` without a
    collapse)."""
    if math.isfinite(undecided_from):
        text = f"{undecided_from:.3f}.." + ("" if math.isnan(value) else f"{value:.3f}")
        return f"{text:>{width}}"
    if bound == "lower":
        return f"{'> ' + format(sl.scanned_to_g, '.3g'):>{width}}"
    if bound == "upper":
        return f"{'<= ' + format(value, '.4f'):>{width}}"
    return f"{value:>{width}.4f}"


def _say_upper_bounds(domain) -> None:
    """One line for the durations whose failure acceleration is only bounded from above."""
    upper = [s.duration for s in domain.slices if s.failure_acceleration_bound == "upper"]
    if upper:
        print("collapse from the lowest amplitude scanned at t_p = "
              + ", ".join(f"{d:g}" for d in upper) + " s: the failure acceleration is at most "
              "it (start --amplitudes lower)")
