"""``archquake risk``: the annual frequency of collapse of a structure at a site, its fragility
convolved with the site's hazard curve; :func:`archquake.site.risk.risk`."""

from __future__ import annotations

import argparse

from ..ranges import number
from . import options
from .output import print_json

TAIL_WARNING_SHARE = 0.10
"""Share of lambda_c from the extrapolated tail [-] above which the text output warns."""

DESCRIPTION = (
    "Mean annual frequency of collapse lambda_c = integral of P(collapse | IM = x) |d lambda(x)| "
    "[1/yr] of a structure at a site, its probability in --years years, 1 - exp(-lambda_c T) "
    "(Poisson), and its return period 1/lambda_c [yr]. The fragility comes from a study folder "
    "(archquake record-fragility --out DIR, or the NRML files of archquake assess --out DIR), "
    "an OpenQuake NRML fragility model, or --median and --dispersion of a lognormal; the "
    "hazard curve from an OpenQuake export (probabilities of exceedance in its investigation "
    "time, converted to annual frequencies as -ln(1 - poe) / T), a two-column CSV (IM [g], "
    "annual frequency of exceedance [1/yr]) or the NTC 2018 national-grid parameters of a site "
    "(TR, ag, F0, Tc*: annual frequency 1/TR at the spectrum's ordinate, ag S for PGA). The "
    "curve is interpolated log-log between its levels, held below its first level and "
    "continued beyond its last with the power law of its last two levels; the tail's share of "
    "lambda_c is reported. Intensities in g: PGA or "
    "SA(T).")


def configure(parser: argparse.ArgumentParser) -> None:
    """The options of ``archquake risk``."""
    parser.description = DESCRIPTION
    fragility = parser.add_argument_group("fragility (--fragility, or --median and "
                                          "--dispersion)")
    fragility.add_argument("--fragility", metavar="STUDY_DIR|NRML.xml",
                           help="a record fragility study folder, an assessment folder or an "
                                "OpenQuake NRML fragility model")
    fragility.add_argument("--median", type=number, metavar="G",
                           help="median of a lognormal fragility [g]")
    fragility.add_argument("--dispersion", type=number, metavar="BETA",
                           help="dispersion (logarithmic standard deviation) of a lognormal "
                                "fragility [-]")
    fragility.add_argument("--fit", choices=("lognormal", "empirical"), default="lognormal",
                           help="of a study: its lognormal fit, or the stripes' probabilities "
                                "interpolated linearly, 0 below the first stripe and the last "
                                "held above (default: %(default)s)")
    fragility.add_argument("--limit-state", metavar="NAME",
                           help="the NRML limit state taken for collapse (default: the one "
                                "named collapse or complete, else the last)")
    fragility.add_argument("--taxonomy", metavar="ID",
                           help="the NRML fragilityFunction id (default: the first, for "
                                "archquake's files the irregular arches' total fit)")
    hazard = parser.add_argument_group("hazard")
    hazard.add_argument("--hazard", required=True, metavar="FILE",
                        help="the site's hazard curve")
    hazard.add_argument("--hazard-format", choices=("openquake", "csv", "ntc"),
                        help="default: recognised from the content (an OpenQuake export starts "
                             "with a comment naming investigation_time, or lon,lat; a "
                             "national-grid site's header names TR, ag, F0, Tc*)")
    hazard.add_argument("--soil", choices=tuple("ABCDE"),
                        help="of a national-grid site (ntc): the soil category of NTC 2018 "
                             "Table 3.2.IV, PGA = ag S (default: rock, the grid's ag)")
    hazard.add_argument("--topography", choices=("T1", "T2", "T3", "T4"), default="T1",
                        help="of a national-grid site with --soil: NTC 2018 Table 3.2.V "
                             "(default: %(default)s)")
    hazard.add_argument("--site-index", type=int, metavar="N",
                        help="the site (row, from 0) of an OpenQuake file of several sites")
    parser.add_argument("--im", metavar="NAME",
                        help="intensity measure, PGA or SA(T) in g: required for a CSV "
                             "hazard without a header naming it and for --median; else it "
                             "must be the files'")
    parser.add_argument("--years", type=number, default=50.0, metavar="T",
                        help="time for the probability of collapse [yr] (default: %(default)s, "
                             "the nominal life of ordinary buildings, NTC 2018 2.4.1)")
    options.add_json_option(parser, "machine-readable output (RiskResult.to_dict)")


def _fragility(args: argparse.Namespace):
    from ..site.fragility_models import LognormalCollapseFragility, StudyFragility, read_fragility

    lognormal = [name for name in ("--median", "--dispersion")
                 if getattr(args, name[2:]) is not None]
    if args.fragility is not None:
        if lognormal:
            raise ValueError(f"give --fragility or --median and --dispersion, not both "
                             f"({', '.join(lognormal)} given)")
        return read_fragility(args.fragility, fit=args.fit, im=args.im,
                              limit_state=args.limit_state, function_id=args.taxonomy)
    if len(lognormal) != 2:
        raise ValueError("give --fragility, or both --median and --dispersion")
    if args.im is None:
        raise ValueError("--median and --dispersion need --im (PGA or SA(T)): the intensity "
                         "measure of the fragility")
    for option, value in (("--median", args.median), ("--dispersion", args.dispersion)):
        if not value > 0:
            raise ValueError(f"{option} must be > 0, got {value!r}")
    return StudyFragility(LognormalCollapseFragility(
        args.median, args.dispersion, im=args.im, source="--median and --dispersion"))


def run(args: argparse.Namespace) -> int:
    """The risk of collapse of the fragility at the site of the hazard curve."""
    from ..site.hazard import hazard_format, read_hazard_curve
    from ..site.risk import risk

    if not args.years > 0:
        raise ValueError(f"--years must be > 0, got {args.years!r}")
    if args.site_index is not None and args.site_index < 0:
        raise ValueError(f"--site-index must be >= 0, got {args.site_index}")
    study = _fragility(args)
    fmt = args.hazard_format or hazard_format(args.hazard)
    # a national-grid site gives the hazard of any ordinate of its spectrum: the fragility's
    im = args.im if fmt != "ntc" or args.im is not None else study.fragility.im
    hazard = read_hazard_curve(args.hazard, format=fmt, im=im, site_index=args.site_index,
                               soil=args.soil, topography=args.topography)
    result = risk(study.fragility, hazard, years=args.years, upper=study.upper)
    if args.json:
        print_json({**result.to_dict(), "hazard": hazard.to_dict(),
                    "undecided_pairs": study.undecided})
        return 0
    f = study.fragility
    print(f"fragility: {f.describe()} [{f.im}]")
    print(f"  from {f.source}")
    print(f"hazard: {hazard.source}")
    print(f"  {hazard.levels.size} levels {hazard.levels[0]:g} to {hazard.levels[-1]:g} g, "
          f"annual frequency of exceedance {hazard.frequencies[0]:.4g} to "
          f"{hazard.frequencies[-1]:.4g} 1/yr; tail beyond the last level: power law of "
          f"slope {hazard.tail_slope:.3g}")
    for note in hazard.notes:
        print(f"  note: {note}")
    print(f"annual frequency of collapse lambda_c = {result.annual_frequency:.4g} 1/yr "
          f"(integration error {result.integration_error:.1g} 1/yr)")
    print(f"probability of collapse in {result.years:g} years = {result.probability:.4g} "
          f"({100 * result.probability:.3g} %)")
    print(f"return period of collapse = {result.return_period:.4g} yr")
    if result.annual_frequency_upper is not None:
        print(f"with the {study.undecided} undecided arch-record pairs counted as collapses: "
              f"lambda_c <= {result.annual_frequency_upper:.4g} 1/yr, probability in "
              f"{result.years:g} years <= {result.probability_upper:.4g}")
    print(f"share of lambda_c from the tail beyond {hazard.levels[-1]:g} g: "
          f"{100 * result.tail_share:.3g} %")
    if result.tail_share > TAIL_WARNING_SHARE:
        print(f"WARNING: {100 * result.tail_share:.0f} % of lambda_c comes from beyond the "
              f"hazard curve's last level, where it is the power law of its last two levels: "
              f"the result rests on that extrapolation (a curve to higher intensities would "
              f"settle it)")
    if result.fragility_at_first_level > 0:
        print(f"P(collapse) at the first level {hazard.levels[0]:g} g is "
              f"{result.fragility_at_first_level:.3g}: below it the hazard is held at its "
              f"first frequency; continued with its first slope it would add "
              f"{result.below_first_level:.3g} 1/yr")
    return 0
