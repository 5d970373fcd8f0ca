"""``archquake check``: the code check of the structure's collapse mechanism at a site (NTC 2018
§8.7.1, Circolare 2019 §C8.7.1); :func:`archquake.site.local_mechanism.check_local_mechanism`."""

from __future__ import annotations

import argparse

from . import options
from .output import print_json

DESCRIPTION = (
    "The seismic code's check of the structure's collapse mechanism at a site, by kinematic "
    "analysis of a local mechanism (NTC 2018 §8.7.1, Circolare 2019 §C8.7.1): alpha0 from the "
    "limit analysis, the participating mass M* and fraction e* (eqs. C8.7.1.2-3), "
    "a0* = alpha0 g / (e* FC) (eq. C8.7.1.4); the linear check at SLV, a0* >= a_g S / q with "
    "q = 2 (§C8.7.1.2.1); the nonlinear check d_u* >= SDe(T_s) at SLV and SLC on the capacity "
    "curve of the mechanism's exact large-displacement kinematics (§C8.7.1.2.2), against the "
    "site's elastic spectra (NTC 2018 §3.2.3.2, or EN 1998-1 §3.2.2.2, or a user's table). "
    "Give the site either as the national-grid parameters at the nine return periods "
    "(--site FILE: SLV and SLC both checked) or as one spectrum (--code ...) of one limit "
    "state (--limit-state, default SLV). Prints the PGA capacity: the site's a_g at which "
    "each check just holds.")


def configure(parser: argparse.ArgumentParser) -> None:
    """The options of ``archquake check``."""
    parser.description = DESCRIPTION
    options.add_arch_options(parser)
    options.add_site_options(parser)
    code = parser.add_argument_group("the check (Circolare 2019 §C8.7.1)")
    code.add_argument("--knowledge-level", default=None, metavar="LC1|LC2|LC3",
                      help="knowledge level of the structure: its confidence factor FC "
                           "(§C8.5.4: LC1 1.35, LC2 1.20, LC3 1.00; default LC1)")
    code.add_argument("--confidence-factor", type=options.number, default=None, metavar="FC",
                      help="the confidence factor FC itself, in [1, 2] (instead of "
                           "--knowledge-level)")
    floor = parser.add_argument_group(
        "a structure standing in a building (floor demand of Circolare 2009 §C8A.4.9-10)")
    floor.add_argument("--elevation", type=options.number, default=None, metavar="Z",
                       help="height Z of the structure's base above the foundation [m]")
    floor.add_argument("--building-height", type=options.number, default=None, metavar="H",
                       help="height H of the building [m]")
    floor.add_argument("--building-period", type=options.number, default=None, metavar="T1",
                       help="the building's first-mode period T1 [s]")
    floor.add_argument("--storeys", type=int, default=None, metavar="N",
                       help="the building's number of storeys N (gamma = 3N/(2N+1))")
    options.add_plot_option(parser, "write a figure of the capacity curves with the "
                                    "displacement capacities and demands")
    options.add_json_option(parser)


def run(args: argparse.Namespace) -> int:
    """The check of the structure of the options at the site of the options."""
    from ..limit_analysis import both_directions
    from ..site.local_mechanism import check_local_mechanism, confidence_factor

    try:
        fc = confidence_factor(args.knowledge_level, args.confidence_factor)
    except ValueError as exc:
        raise ValueError(str(exc).replace("knowledge_level", "--knowledge-level")
                         .replace("the confidence factor", "--confidence-factor")
                         .replace("confidence_factor", "--confidence-factor")) from None
    actions = options.site_actions(args)
    elevation = _elevation(args)
    arch = options.arch_from_args(args)
    with options.analysing(args):
        limit = both_directions(arch)
        check = check_local_mechanism(arch, actions, confidence_factor=fc, limit=limit,
                                      elevation=elevation)
    if args.plot:
        from .output import pyplot, save_figure

        plt = pyplot()  # the file-only backend, before the plotting module imports pyplot
        from ..plotting import plot_capacity_curve

        fig, ax = plt.subplots(figsize=(8.0, 5.0), constrained_layout=True)
        plot_capacity_curve(check, ax)
        save_figure(fig, args.plot)
    if args.json:
        from .main_limit import describe_arch

        print_json({"structure": describe_arch(arch), **check.to_dict()})
        return 0
    _print(check, arch, fc, args)
    return 0


_FLOOR = ("elevation", "building_height", "building_period", "storeys")


def _elevation(args: argparse.Namespace):
    """The structure's place in a building, if given (all four options or none)."""
    from ..site.local_mechanism import Elevation

    given = options.given(args, *_FLOOR)
    if not given:
        return None
    if len(given) < len(_FLOOR):
        missing = [f"--{n.replace('_', '-')}" for n in _FLOOR if getattr(args, n) is None]
        raise ValueError(f"{', '.join(given)} needs {', '.join(missing)} too (a structure in a "
                         "building: its height, the building's height, period and storeys)")
    try:
        return Elevation(args.elevation, args.building_height, args.building_period,
                         args.storeys)
    except ValueError as exc:
        text = str(exc)
        name = text.split(" ", 1)[0]
        options_of = {"height": "--elevation", "building_height": "--building-height",
                      "building_period": "--building-period", "storeys": "--storeys"}
        if name in options_of:
            text = options_of[name] + text[len(name):]
        raise ValueError(text.replace("building_height", "--building-height")) from None


def _capacity(value) -> str:
    return "holds beyond a_g = 1.5 g" if value is None else f"holds up to a_g = {value:.3f} g"


def _print(check, arch, fc: float, args) -> None:
    from .main_limit import describe_arch

    names = {"l": "Mech-l", "r": "Mech-r"}
    print(f"Code check of the collapse mechanism (NTC 2018 §8.7.1, Circolare 2019 §C8.7.1): "
          f"{describe_arch(arch)}")
    for state, action in check.actions.items():
        s = action.spectrum
        print(f"  {state}: {s.code}, a_g = {action.ag:.4f} g, PGA = a_g S = {s.pga:.4f} g")
    print(f"  confidence factor FC = {fc:g}")
    if check.elevation is not None:
        e = check.elevation
        print(f"  in a building: Z = {e.height:g} m of H = {e.building_height:g} m, T1 = "
              f"{e.building_period:g} s, N = {e.storeys}: floor demand of Circolare 2009 "
              f"§C8A.4.9-10 (psi gamma = {e.amplification:.3f}), the larger with the ground's")
    print(f"{'':<8} {'alpha0':>8} {'M* [t/m]':>9} {'e*':>7} {'a0* [g]':>8}")
    for p in check.participations:
        print(f"{names[p.direction]:<8} {p.alpha0:>8.4f} {p.participating_mass / 1e3:>9.2f} "
              f"{p.mass_fraction:>7.4f} {p.spectral_acceleration_g:>8.4f}")
    if check.linear:
        q = check.linear[0].behaviour_factor
        print(f"Linear check (§C8.7.1.2.1), SLV: a0* >= a_g S / q, q = {q:g}")
        for c in check.linear:
            print(f"  {names[c.direction]:<7} a0* = {c.capacity:.4f} g, demand {c.demand:.4f} g,"
                  f" ratio {c.ratio:.2f}: {'holds' if c.passes else 'FAILS'} "
                  f"({_capacity(c.pga_capacity)})")
    if check.nonlinear:
        demand = "SDe(T_s)" if check.elevation is None else "the floor's demand"
        print(f"Nonlinear check (§C8.7.1.2.2): d_u* >= {demand}; d_u* = 0.24 d0* (SLV), "
              "0.40 d0* (SLC); T_s at d_s* = 0.4 d_u*")
        d0 = {c.direction: c.d0 for c in check.curves}
        for c in check.nonlinear:
            print(f"  {c.limit_state} {names[c.direction]:<7} d0* = {d0[c.direction]:.4f} m, "
                  f"d_u* = {c.ultimate_displacement:.4f} m, T_s = {c.secant_period:.3f} s, "
                  f"demand {c.demand:.4f} m, ratio {c.ratio:.2f}: "
                  f"{'holds' if c.passes else 'FAILS'} "
                  f"({_capacity(c.pga_capacity)})")
    for note in check.notes:
        print(f"  note: {note}")
    for state in check.actions:
        verdict = check.holds(state)
        routes = check.routes(state)
        passing = [name for name, cs in routes.items() if all(c.passes for c in cs)]
        why = f" ({' and '.join(passing)} check)" if verdict else ""
        print(f"Verdict {state}: {'HOLDS' if verdict else 'FAILS'}{why}: "
              f"{_capacity(check.pga_capacity(state))}, against the site's a_g = "
              f"{check.actions[state].ag:.4f} g")
