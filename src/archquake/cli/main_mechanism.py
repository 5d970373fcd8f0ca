"""``archquake mechanism``: the four-link mechanisms (paper Sects. 4.1-4.4, Tables 2-3);
:meth:`archquake.fourlink.FourLinkModel.from_arch`."""

from __future__ import annotations

import argparse

from . import options
from .output import print_json

DESCRIPTION = (
    "Oppenheim's four-link mechanism of the arch for both directions, built on the "
    "limit-analysis hinges: undisplaced configuration theta_u, theta_BC, theta_CD [rad], link "
    "lengths AB, BC, CD [m], critical angle theta_cr and phi_cr = theta_u - theta_cr [rad], "
    "activation acceleration -F/P [g], and the coefficients of restitution of the impacts. "
    "Mech-r quantities are in the mirrored frame.")


def configure(parser: argparse.ArgumentParser) -> None:
    """The options of ``archquake mechanism``."""
    parser.description = DESCRIPTION
    options.add_arch_options(parser)
    options.add_restitution_option(parser)
    options.add_json_option(parser)


def run(args: argparse.Namespace) -> int:
    """The mechanisms and restitution of the arch of the options."""
    dynamics = options.structure_model(args, options.model_spec_from_args(args, "four-link"))
    mech_l, mech_r = dynamics.mechanisms
    c_lr, c_rl = dynamics.restitution
    out = {}
    for m in (mech_l, mech_r):
        out[m.direction] = {
            "theta_u": m.theta_u, "theta_bc_u": m.theta_bc_u, "theta_cd_u": m.theta_cd_u,
            "ab": m.ab, "bc": m.bc, "cd": m.cd, "theta_cr": m.theta_cr, "phi_cr": m.phi_cr,
            "activation": m.activation_g,
        }
    out["restitution"] = {"l_to_r": c_lr, "r_to_l": c_rl}
    if args.json:
        print_json(out)
        return 0
    rows = [("theta_u", "rad"), ("theta_bc_u", "rad"), ("theta_cd_u", "rad"), ("ab", "m"),
            ("bc", "m"), ("cd", "m"), ("theta_cr", "rad"), ("phi_cr", "rad"),
            ("activation", "g")]
    print(f"{'quantity':<12}{'Mech-l':>12}{'Mech-r':>12}  unit")
    for key, unit in rows:
        print(f"{key:<12}{out['l'][key]:>12.4f}{out['r'][key]:>12.4f}  {unit}")
    ratio_l, ratio_r = (m.theta_cr / m.theta_u for m in (mech_l, mech_r))
    print(f"{'theta_cr/u':<12}{ratio_l:>12.4f}{ratio_r:>12.4f}  -")
    print(f"restitution c_v: Mech-l -> Mech-r {c_lr:.4f}, Mech-r -> Mech-l {c_rl:.4f}")
    return 0
