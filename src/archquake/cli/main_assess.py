"""``archquake assess``: the paper's method and both models applied to one structure, against
real records, in one report; :func:`archquake.report.assess.assess`."""

from __future__ import annotations

import argparse
import shlex

from ..ranges import number
from . import options

DESCRIPTION = (
    "Assess one structure (default: Oppenheim's arch): the limit analysis both ways, its hinges "
    "and geometric safety factor (or the verdict that it cannot stand, with the reason); the "
    "four-link mechanisms, critical rotations and restitution; the failure domain under pulses "
    "with the four-link and rigid-block models and where they disagree; the effect of "
    "irregularity (--epsilon); and the record-based fragility against real records (the FEMA "
    "P695 pulse-like near-field set when the records extra is installed) in PGA, PGV and "
    "Sa(T), with OpenQuake NRML files. Writes --out/report.html (self-contained; the summary on "
    "its first screen), report.md with the figures, results.json, and each study in its own "
    "subdirectory: --resume continues an interrupted assessment. Where the two models disagree "
    "under pulses, the studies of irregular arches and records run again with the rigid-block "
    "model and the summary's numbers are its own (the four-link ones beside them, marked not "
    "used). About a minute on two processors where the models agree (two with --sa-period), up "
    "to ten where they disagree; --quick under a minute.")


def configure(parser: argparse.ArgumentParser) -> None:
    """The options of ``archquake assess``."""
    parser.description = DESCRIPTION
    options.add_nominal_arch_options(parser)
    options.add_restitution_option(parser)
    options.add_rigid_block_options(parser, time_step=False)
    group = parser.add_argument_group(
        "records (default: the FEMA P695 pulse-like near-field records if installed, else "
        "synthetic ones, with a note)")
    exclusive = group.add_mutually_exclusive_group()
    exclusive.add_argument("--records", nargs="+", metavar="PATH",
                           help="record files (PEER .AT2, CSV in g, ESM .ASC) and folders of "
                                "them")
    options.add_suite_option(exclusive)
    group.add_argument("--sa-period", type=number, default=None, metavar="T",
                       help="also the fragility in Sa(T), the 5%%-damped spectral "
                            "acceleration at period T [s]")
    options.add_site_options(parser)
    code = parser.add_argument_group("the code check at the site (with --site or --code)")
    code.add_argument("--knowledge-level", default=None, metavar="LC1|LC2|LC3",
                      help="knowledge level of the structure: its confidence factor FC "
                           "(Circolare 2019 §C8.5.4: LC1 1.35, LC2 1.20, LC3 1.00; default "
                           "LC1)")
    code.add_argument("--confidence-factor", type=number, default=None, metavar="FC",
                      help="the confidence factor FC itself, in [1, 2]")
    parser.add_argument("--quick", action="store_true",
                        help="reduced sizes for a smoke test (under a minute), not an assessment")
    parser.add_argument("--resume", action="store_true",
                        help="continue the interrupted assessment in --out (same structure, "
                             "records and settings)")
    parser.add_argument("--out", default="assessment", metavar="DIR",
                        help="output directory, new or empty (default: %(default)s)")
    options.add_progress_option(parser)


def run(args: argparse.Namespace) -> int:
    """Assess the structure of the options into ``--out``."""
    from ..report.assess import AssessmentSettings, assess

    if options.describes_assembly(args):
        with options.naming_options():
            description = options.structure_spec(args, draw=False, spans=True)
            structure = description.nominal()
        if hasattr(structure, "interfaces"):
            return _assembly(args, structure, description)
    structure = options.nominal_arch_from_args(args)
    changes = {"epsilon": args.epsilon, "seed": args.seed, "restitution": args.restitution,
               "friction": args.friction, "sa_period": args.sa_period}
    settings = (AssessmentSettings.quick_settings(**changes) if args.quick
                else AssessmentSettings(**changes))
    records = options.suite_from_args(args)
    result = assess(structure, records=records, out_dir=args.out,
                    progress=not args.no_progress, resume=args.resume, settings=settings,
                    command=_command(args), site=_site(args))
    return _print(result)


def _site(args: argparse.Namespace):
    """The site of the site options, or None; its options without a site are refused."""
    if args.site is not None or args.code is not None:
        return options.site_spec(args)
    if options.given(args, "knowledge_level", "confidence_factor", *sorted(
            {n for names in options.CODE_OPTIONS.values() for n in names})):
        raise ValueError("the site's options need --site FILE or --code (a site to check the "
                         "structure at)")
    return None


def _command(args: argparse.Namespace) -> str | None:
    """The command line that ran the assessment, for the report."""
    if getattr(args, "argv", None) is None:
        return None
    return shlex.join(["archquake", *args.argv])


def _print(result) -> int:
    """The verdict, the site's and where the report is."""
    total = result.results["timings"]["total"]
    figures = sum(f.endswith(".png") for f in result.files)
    nrml = sum(f.endswith(".xml") for f in result.files)
    print(result.verdict)
    if result.results.get("site"):
        from ..report.assess.site import verdict_text

        print(verdict_text(result.results["site"]))
    print(f"report written to {result.directory / 'report.html'} (also report.md, "
          f"results.json, {figures} figure{'s' if figures != 1 else ''}"
          + (f", {nrml} NRML file{'s' if nrml != 1 else ''}" if nrml else "")
          + f") in {total:.1f} s")
    return 0


def _assembly(args: argparse.Namespace, structure, description) -> int:
    """``assess`` of a block assembly (:mod:`archquake.report.assess.assembly`); of several
    spans of one arch, with the limit analysis of its irregular bridges."""
    from ..defaults import DEFAULT_EPSILON, DEFAULT_SEED
    from ..report.assess import AssessmentSettings, assess
    from ..report.assess.assessment import bridge_description

    bridge = bridge_description(description)
    refused = options.given(args, "records", "suite", "sa_period")
    if bridge is None:  # the sample's defaults are no request
        refused += [o for o, given in (("--epsilon", args.epsilon != DEFAULT_EPSILON),
                                       ("--seed", args.seed != DEFAULT_SEED)) if given]
    if refused:
        raise ValueError(f"{', '.join(refused)}: the assessment of a block assembly (several "
                         "spans, rings, a drawing) runs no record study, and draws irregular "
                         "structures only of several spans of one arch")
    settings = (AssessmentSettings.quick_settings if args.quick else AssessmentSettings)(
        friction=args.friction, epsilon=args.epsilon, seed=args.seed)
    own = getattr(structure, "friction", None)
    if isinstance(own, dict):
        # the rings' own friction given (--ring-friction), the other interfaces' none (they
        # do not slide): --friction is theirs, as the rigid blocks' at every other joint
        structure = structure.with_friction(
            {**own, **{kind: args.friction for kind in own if kind != "ring"}})
    result = assess(structure, out_dir=args.out, progress=not args.no_progress,
                    resume=args.resume, settings=settings, command=_command(args),
                    site=_site(args), description=bridge)
    return _print(result)
