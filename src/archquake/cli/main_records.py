"""``archquake records``: intensity measures of a suite of recorded accelerograms;
:func:`archquake.ground_motion.read_suite` and
:func:`archquake.ground_motion.parse_intensity_measures`."""

from __future__ import annotations

import argparse

from ..defaults import DEFAULT_INTENSITY_MEASURES
from . import options
from .output import print_json

DESCRIPTION = (
    "Read recorded accelerograms (PEER NGA .AT2, two-column CSV in g, ESM ASCII) and print "
    "their intensity measures: pga [g], pgv [m/s], pgd [m] (no baseline correction), arias "
    "[m/s], d5-95 [s] and sa(T) [g], the 5%-damped pseudo-spectral acceleration at period T "
    "[s]. A folder stands for its files with extension .at2, .csv or .asc; the records are "
    "sorted by file name.")


def configure(parser: argparse.ArgumentParser) -> None:
    """The options of ``archquake records``."""
    parser.description = DESCRIPTION
    parser.add_argument("paths", nargs="*", metavar="PATH",
                        help="record files and folders of record files")
    options.add_suite_option(parser, "instead of files (--json adds each record's metadata)")
    parser.add_argument("--im", default=DEFAULT_INTENSITY_MEASURES, metavar="LIST",
                        help="comma-separated intensity measures, e.g. pga,pgv,sa(0.5) "
                             "(default: %(default)s)")
    options.add_json_option(
        parser, 'machine-readable output: [{"record": FILE NAME, IM: value, ...}]')


def run(args: argparse.Namespace) -> int:
    """The intensity measures of the records of the paths."""
    from ..ground_motion import parse_intensity_measures, read_suite

    measures = parse_intensity_measures(args.im)
    names = [im.name for im in measures]
    if len(set(names)) != len(names):
        raise ValueError(f"--im names an intensity measure twice: {args.im!r}")
    if args.suite is not None:
        if args.paths:
            raise ValueError("records: give --suite or record files, not both")
        rows = _builtin_suite_rows(args.suite, measures)
    elif not args.paths:
        raise ValueError("records: give record files and folders, or --suite NAME")
    else:
        rows = []
        for motion in read_suite(args.paths):
            row = {"record": motion.name}
            row.update({im.name: im(motion) for im in measures})
            rows.append(row)
    if args.json:
        print_json(rows)
        return 0
    header = ["record"] + [f"{im.name} [{im.unit}]" for im in measures]
    table = [[row["record"]] + [f"{row[im.name]:.5g}" for im in measures] for row in rows]
    widths = [max(len(line[j]) for line in [header, *table]) for j in range(len(header))]
    for line in [header, *table]:
        cells = [line[0].ljust(widths[0])] + [c.rjust(w) for c, w in zip(line[1:], widths[1:],
                                                                       strict=True)]
        print("  ".join(cells).rstrip())
    if args.suite is not None:  # a built-in suite lists every horizontal component
        events = len({row["record_number"] for row in rows})
        print(f"{args.suite}: {events} records, {len(rows)} horizontal components "
              f"(record_number and component in --json)")
    return 0


def _builtin_suite_rows(name: str, measures) -> list[dict]:
    """Rows of ``archquake records --suite NAME``: each ground motion of a built-in suite with
    its intensity measures, then its metadata (the ground motion's name is ``record``)."""
    from ..ground_motion import builtin_suite

    try:
        records = builtin_suite(name)
    except ImportError as exc:
        raise ValueError(f"--suite {name}: {exc}") from None
    except ValueError as exc:
        raise ValueError(f"--suite: {exc}") from None
    rows = []
    for r in records:
        row = {"record": r.name}
        row.update({im.name: im(r.motion) for im in measures})
        row.update({key: value for key, value in r.metadata.to_dict().items() if key != "name"})
        rows.append(row)
    return rows
