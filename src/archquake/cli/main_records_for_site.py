"""``archquake records-for-site``: records selected and scaled to be compatible with a site's
elastic spectrum and, with ``--run``, the structure under them by both models and the code's
verdict; :func:`archquake.site.compatible_records.select_compatible_records` and
:func:`archquake.site.dynamic_check.run_dynamic_check`."""

from __future__ import annotations

import argparse
import math

from . import options
from .output import print_json

DESCRIPTION = (
    "Select records from a suite and scale them so that the mean of their 5%-damped spectra "
    "matches the site's elastic spectrum (NTC 2018 §3.2.3.6: nowhere more than 10% below nor "
    "30% above it over the period range): each record scaled to the spectrum alone (least "
    "squares of the logarithms), the subset chosen greedily and improved by swaps, one common "
    "factor centring the mean in the band. With --run, every scaled record is applied to the "
    "structure by the rigid-block model (its verdict is stated) and the four-link model beside "
    "it: the check fails if any record collapses the structure (the mean of the effects, with "
    "7 records or more, or the most unfavourable one, is unbounded, NTC 2018 §7.3.5), is "
    "undecided if a run is, and passes otherwise. A suite of which no subset is found "
    "compatible is shown, then refused (exit status 2).")


def configure(parser: argparse.ArgumentParser) -> None:
    """The options of ``archquake records-for-site``."""
    parser.description = DESCRIPTION
    options.add_site_options(parser)
    options.add_dynamic_route_options(parser)
    group = parser.add_argument_group("the dynamic check")
    group.add_argument("--run", action="store_true",
                       help="apply every selected record to the structure by both models and "
                            "give the code's verdict")
    group.add_argument("--both-polarities", action="store_true",
                       help="apply every record also reversed (a record's effect is then the "
                            "less favourable of the two)")
    options.add_arch_options(parser)
    options.add_restitution_option(parser)
    options.add_rigid_block_options(parser)
    options.add_progress_option(parser)
    options.add_json_option(parser, "print the selection (and with --run the runs and the "
                                    "verdicts) as JSON")


def run(args: argparse.Namespace) -> int:
    """The selection of the options, and with ``--run`` the dynamic check."""
    way = options.site_way(args)
    try:
        target, _ = options.site_spectrum(args, way)
    except ValueError as exc:
        raise options.site_option_message(exc) from None
    if args.run:  # refuse a bad structure or model setting before the selection
        arch = options.arch_from_args(args)
        specs = (options.model_spec_from_args(args, "rigid-blocks", both=True),
                 options.model_spec_from_args(args, "four-link", both=True))
    selection = options.compatible_selection_from_args(args, target, way)
    if not selection.compatible:  # the selection shown, then why it cannot serve
        if args.json:
            print_json({"selection": selection.to_dict(), "target_spectrum": target.to_dict()})
        else:
            _print_selection(selection, target)
        raise ValueError("records: no subset of the candidates found is compatible with the "
                         "site's spectrum" + (", so the dynamic check is not run" if args.run
                                              else "") + ": " + "; ".join(selection.problems))
    check = None
    if args.run:
        from ..site.dynamic_check import run_dynamic_check

        with options.analysing(args):
            check = run_dynamic_check(arch, selection, specs,
                                      polarities=(1, -1) if args.both_polarities else (1,),
                                      progress=not args.no_progress)
    if args.json:
        out = check.to_dict() if check is not None else {"selection": selection.to_dict()}
        out["target_spectrum"] = target.to_dict()
        print_json(out)
        return 0
    _print_selection(selection, target)
    if check is not None:
        _print_check(check)
    return 0


def _print_selection(selection, target) -> None:
    """The selection as a table and its verdict of compatibility."""
    print(f"Target: {getattr(target, 'code', 'spectrum')}, PGA {selection.target_pga:.4g} g")
    width = max(len("record"), *(len(r) for r in selection.records))
    print(f"{'record'.ljust(width)}  factor")
    for name, factor in zip(selection.records, selection.factors, strict=True):
        print(f"{name.ljust(width)}  {factor:6.3f}")
    print(selection.summary())
    if selection.excluded:
        print(f"{len(selection.excluded)} records left out: their usable periods do not cover "
              f"the range")


def _print_check(check) -> None:
    """Every run and the verdicts."""
    from ..site.dynamic_check import PEAK_RESPONSE

    print()
    width = max(len("record"), *(len(r.record) for r in check.runs))
    print(f"{'model':<12}  {'record'.ljust(width)}  pol  {'outcome':<9}  peak [rad]")
    for r in check.runs:
        peak = "-" if math.isnan(r.peak_response) else f"{r.peak_response:.3e}"
        print(f"{r.model:<12}  {r.record.ljust(width)}  {r.polarity:+d}   {r.status.label:<9}  "
              f"{peak}")
    for spec in check.models:
        print(f"{spec.name}: {spec.settings_text()}; peak = "
              f"{PEAK_RESPONSE[spec.name][1]}")
    for v in check.verdicts:
        stated = " (the verdict stated)" if v is check.verdict else ""
        print(f"{v.model}: {v.verdict.upper()}{stated}: {v.reason}")
