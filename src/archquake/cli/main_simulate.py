"""``archquake simulate``: one time history of the four-link model (paper Sect. 5.3, Fig. 15);
:meth:`archquake.fourlink.FourLinkModel.simulate`."""

from __future__ import annotations

import argparse
import math

from ..ranges import number
from . import options
from .output import print_json

DESCRIPTION = (
    "Time history of the four-link mechanism with impacts under a ground motion: outcome rest "
    "(never activated) / recovery / collapse, the half cycle of collapse (1 = first, no "
    "impact), the number of impacts of the recorded motion (and of those before the outcome "
    "was decided), the collapse time [s] (last crossing of theta_cr, the point of no return), "
    "the largest rotation phi [rad] and when the arch comes to rest.")

FREE_VIBRATION_TIME = 10.0
"""Length of a free vibration (``--phi0``) unless ``--t-end`` is given [s]."""


def configure(parser: argparse.ArgumentParser) -> None:
    """The options of ``archquake simulate``."""
    parser.description = DESCRIPTION
    options.add_arch_options(parser)
    options.add_restitution_option(parser)
    options.add_motion_options(parser)
    parser.add_argument("--phi0", type=number, default=None,
                        help="free vibration instead: release Mech-l from rest at phi0 [rad]")
    parser.add_argument("--t-end", type=number, default=None,
                        help="end of the record [s] (default: a few seconds after the outcome "
                             f"is decided; {FREE_VIBRATION_TIME:g} s with --phi0)")
    parser.add_argument("--output", metavar="history.csv",
                        help="write the time history (t [s], phi [rad, + Mech-l, - Mech-r], "
                             "theta_dot [rad/s], mechanism)")
    options.add_plot_option(parser, "plot the response")
    options.add_json_option(parser)


def run(args: argparse.Namespace) -> int:
    """The time history of the arch of the options under the motion of the options."""
    if args.phi0 is not None:
        motion = options.given(args, "motion", "amplitude", "duration", "cycles", "param",
                               "record", "suite", "scale_to", "reverse")
        if motion:
            raise ValueError(f"--phi0 (free vibration on a still ground) cannot be combined "
                             f"with the ground motion options {', '.join(motion)}")
    dynamics = options.structure_model(args, options.model_spec_from_args(args, "four-link"))
    coefficients = dynamics.restitution
    if args.phi0 is not None:
        history = dynamics.free_vibration(
            args.phi0, t_end=args.t_end if args.t_end is not None else FREE_VIBRATION_TIME)
    else:
        history = dynamics.simulate(options.motion_from_args(args), t_end=args.t_end)
    o = history.outcome
    rest_time = history.rest_time
    result = {"outcome": o.status.label, "half_cycle": o.half_cycle, "impacts": history.impacts,
              "impacts_before_decision": o.impacts,
              "collapse_time": None if math.isnan(o.collapse_time) else o.collapse_time,
              "max_phi": o.max_phi,
              "at_rest_from": None if math.isnan(rest_time) else rest_time}
    if args.output:
        from ..results_io import write_history_csv
        from .output import written_table

        written_table(lambda: write_history_csv(history, args.output), args.output,
                      "time history")
    if args.plot:
        from .output import pyplot, save_figure

        pyplot()
        from ..plotting import plot_free_vibration, plot_pulse_response

        if args.phi0 is not None:
            ax = plot_free_vibration(history)
        else:
            _, ax = plot_pulse_response(history, phi_limit=min(1.0, 1.5 * o.max_phi + 0.02))
        save_figure(ax.figure, args.plot, dpi=120, bbox_inches="tight")
    if args.json:
        print_json(result)
        return 0
    text = {"rest": "the arch is never activated (rests on the ground)",
            "recovery": f"the arch recovers: {history.impacts} impact(s) ({o.impacts} before "
                        f"the end of the excitation), " + (
                            f"at rest from t = {rest_time:.4f} s" if not math.isnan(rest_time)
                            else f"still rocking at the end of the record, t = "
                                 f"{history.t[-1]:.4f} s (--t-end)"),
            "collapse": f"the arch collapses in half cycle {o.half_cycle} "
                        f"({o.impacts} impact(s) before), " + (
                            f"point of no return at t = {o.collapse_time:.4f} s"
                            if not math.isnan(o.collapse_time) else
                            "released beyond its point of no return (the critical angle): "
                            "it falls from t = 0")}[o.status.label]
    print(f"{history.ground_motion.name}; c_v = {coefficients[0]:.4f} (l->r), "
          f"{coefficients[1]:.4f} (r->l)")
    print(f"{text}; largest rotation phi = {o.max_phi:.4f} rad")
    return 0
