"""``archquake reproduce``: every table and figure of the paper beside the paper's values;
:func:`archquake.report.reproduce`."""

from __future__ import annotations

import argparse

from ..defaults import REPORT_SEED
from . import options

DESCRIPTION = (
    "Run the paper's chain on Oppenheim's arch and on irregular arches (epsilon = 0.10): Tables "
    "1-3, the arch and its hinges (Figs. 2, 4), the potential energy (6-8), free vibrations "
    "(9-14), pulse responses (15), the failure domain (16), fragility curves and surface "
    "(17-21), each beside the paper's values. Writes DIR/report.html (self-contained), "
    "DIR/report.md with the PNG figures, and DIR/results.json with every number.")

STARTS_PROCESSES = True
"""The report runs its long tasks on a second process (on a machine with two processors):
SIGTERM stops it like Ctrl-C, so that process is stopped too and its queues are released
(:func:`archquake.cli._signals.sigterm_as_interrupt`)."""


def configure(parser: argparse.ArgumentParser) -> None:
    """The options of ``archquake reproduce``."""
    parser.description = DESCRIPTION
    parser.add_argument("--out", default="report", metavar="DIR",
                        help="output directory (default: %(default)s)")
    parser.add_argument("--quick", action="store_true",
                        help="reduced study for a smoke test (h = 6 arches, s = 100, 0.05 g "
                             "steps, 7 failure-domain durations)")
    parser.add_argument("--seed", type=int, default=None,
                        help=f"root seed of the irregular arches (default: {REPORT_SEED})")
    parser.add_argument("--restitution", default=None, metavar=options.RESTITUTION_METAVAR,
                        help=f"coefficient of restitution c_v of the paper's results, one value "
                             f"for every arch as in the paper: {options.RESTITUTION_HELP}; a "
                             f"model gives the value of Oppenheim's arch (default: the paper's "
                             f"0.875; the computed value is always shown beside it)")
    options.add_progress_option(parser)


def run(args: argparse.Namespace) -> int:
    """Reproduce the paper into ``--out``."""
    from ..report import ReproductionSettings, reproduce

    changes = {}
    if args.seed is not None:
        changes["seed"] = args.seed
    if args.restitution is not None:
        from ..models import ModelSpec

        spec = ModelSpec(restitution=args.restitution)
        model = spec.restitution
        if isinstance(model, str):  # a model: its value for the nominal arch
            from ..reference_arches import oppenheim

            model = spec.build(oppenheim()).restitution[0]
        changes["restitution"] = model
    settings = (ReproductionSettings.quick_settings(**changes) if args.quick
                else ReproductionSettings(**changes))
    result = reproduce(args.out, settings, progress=not args.no_progress)
    timings = result.results["timings"]
    print(f"report written to {result.directory / 'report.html'} (also report.md, "
          f"results.json and {len(result.figures)} figures) in {timings['total']:.1f} s")
    return 0
