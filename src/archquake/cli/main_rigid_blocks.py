"""``archquake rigid-blocks``: the rigid-block model of the arch under one ground motion;
:func:`archquake.rigid_blocks.block_outcome` and :func:`archquake.rigid_blocks.simulate_blocks`."""

from __future__ import annotations

import argparse

from ..ranges import number
from . import options
from .output import print_json

DESCRIPTION = (
    "Every voussoir a rigid block on two supports that move with the ground; contacts at both "
    "ends of every joint with Coulomb friction and no bounce (Moreau-Jean nonsmooth contact "
    "dynamics). A second opinion on the four-link model, independent of it. Outcome: rest "
    "(never moved), recovery (back at rest after the excitation) or collapse (a block or the "
    "crown dropped by a thickness, or too little energy left to return), with the collapse "
    "time [s], the largest block rotation [rad], crown drop [m] and joint slip [m]. "
    "Displacements are relative to the ground.")


def configure(parser: argparse.ArgumentParser) -> None:
    """The options of ``archquake rigid-blocks``."""
    parser.description = DESCRIPTION
    options.add_arch_options(parser)
    options.add_motion_options(parser)
    options.add_rigid_block_options(parser)
    parser.add_argument("--t-end", type=number, default=None,
                        help="record up to this time [s] (default: until 0.5 s after the "
                             "outcome is decided)")
    parser.add_argument("--output", metavar="history.csv",
                        help="write the time history: t [s], crown drop [m], energies [J/m], "
                             "every block's x, y [m] and rotation [rad], every joint's opening "
                             "and slip [m]")
    options.add_plot_option(parser, "plot the blocks (when the collapse is certain, or at "
                                    "their largest opening) and the time history")
    parser.add_argument("--animate", metavar="FILE.gif", help="write an animation of the blocks")
    options.add_json_option(parser)


def run(args: argparse.Namespace) -> int:
    """The rigid-block analysis of the arch of the options under the motion of the options."""
    spec = options.model_spec_from_args(args, "rigid-blocks")
    arch = options.arch_from_args(args, assembly=True, spans=True)
    motion = options.motion_from_args(args)
    model = spec.build(arch)
    settings = model.settings  # with the time step used
    if args.animate:  # checked before the analysis, which may take a while
        from pathlib import Path

        if Path(args.animate).is_dir():
            raise ValueError(f"cannot write the animation {args.animate!r}: it is a directory")
        if Path(args.animate).suffix.lower() != ".gif":
            raise ValueError(f"cannot write the animation {args.animate!r}: give a file name "
                             f"ending in .gif")
    if args.output or args.plot or args.animate or args.t_end is not None:
        history = model.simulate(motion, t_end=args.t_end)
        outcome = history.outcome
        if args.output:
            from ..results_io import write_block_history_csv
            from .output import written_table

            written_table(lambda: write_block_history_csv(history, args.output), args.output,
                          "time history")
        if args.plot:
            _plot(history, args.plot)
        if args.animate:
            from .output import pyplot

            pyplot()
            from ..rigid_blocks.plotting import animate_blocks

            animate_blocks(history, args.animate)
    else:
        outcome = model.outcome(motion)
    if args.json:
        out = outcome.to_dict()
        out = {"outcome": out.pop("status"), **out, "friction": _friction(arch, settings),
               "time_step": settings.time_step, "motion": motion.name}
        print_json(out)
        return 0
    why = (f"the contact problem of {outcome.unconverged_steps} steps unsolved"
           if outcome.unconverged_steps else "still moving")
    what = "the structure" if hasattr(arch, "interfaces") else "the arch"
    text = {"rest": f"{what} never moves (it moves with the ground)",
            "recovery": f"{what} rocks and comes back to rest",
            "collapse": f"{what} collapses (certain at t = {outcome.collapse_time:.3f} s)",
            "undecided": f"undecided: not decided by t = "
                         f"{outcome.steps * settings.time_step:.3f} s ({why})"}
    friction = _friction(arch, settings)
    friction = (f"{friction:g}" if not isinstance(friction, dict) else ", ".join(
        f"{kind} {'no sliding' if value is None else f'{value:g}'}"
        for kind, value in friction.items()))
    print(f"Rigid-block model, {motion.name}; friction {friction}, time step "
          f"{settings.time_step:g} s (coarse factor {settings.coarse_factor})")
    print(text[outcome.status.label])
    print(f"largest rotation {outcome.max_rotation:.4f} rad, crown drop "
          f"{outcome.max_crown_drop:.4f} m, slip {outcome.max_slip:.2e} m, joint opening "
          f"{outcome.max_opening:.4f} m; {outcome.steps} steps")
    for option, what in ((args.output, "time history"), (args.plot, "figure"),
                         (args.animate, "animation")):
        if option:
            print(f"{what} written to {option}")
    return 0


def _plot(history, path) -> None:
    import numpy as np

    from .output import pyplot, save_figure

    plt = pyplot()
    from ..rigid_blocks.plotting import plot_block_history, plot_blocks

    fig, (left, right) = plt.subplots(1, 2, figsize=(13, 4.5), constrained_layout=True)
    if history.outcome.collapsed:  # when the collapse became certain
        moment = history.outcome.collapse_time
    else:  # the most open state
        moment = float(history.times[int(np.argmax(history.openings.max(axis=1)))])
    plot_blocks(history, moment, left)
    plot_block_history(history, right)
    save_figure(fig, path)


def _friction(structure, settings):
    """The Coulomb coefficient of the joints [-]: the model's, or, for a block assembly that
    gives its own, one per interface kind (None: that kind does not slide)."""
    own = getattr(structure, "friction", None) if hasattr(structure, "interfaces") else None
    if own is None:
        return settings.friction
    import math

    faces = structure.interfaces
    out = {}
    for kind in dict.fromkeys(faces.kind.tolist()):
        values = {float(v) for v in faces.friction[faces.kind == kind]}
        value = values.pop() if len(values) == 1 else None
        out[kind] = None if value is None or math.isinf(value) else value
    return out
