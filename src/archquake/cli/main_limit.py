"""``archquake limit``: load multipliers, hinges and thrust lines (paper Sect. 3, Table 1);
:func:`archquake.limit_analysis.both_directions`."""

from __future__ import annotations

import argparse
import math

from ..defaults import DEFAULT_LIMIT_METHOD, DEFAULT_SEED, LIMIT_METHODS
from . import options
from .output import print_json

DESCRIPTION = (
    "Limit analysis of the arch under its weight and horizontal forces k m_i g (Heyman: no "
    "tension, infinite compressive strength, no sliding). Mech-l: forces left -> right; Mech-r: "
    "the mirrored arch, hinges reported in the mirrored frame (as Table 1 of the paper). Motion "
    "starts when the ground acceleration reaches k g.")


def configure(parser: argparse.ArgumentParser) -> None:
    """The options of ``archquake limit``."""
    parser.description = DESCRIPTION
    options.add_arch_options(parser)
    parser.add_argument("--method", choices=LIMIT_METHODS, default=DEFAULT_LIMIT_METHOD,
                        help="static: linear program (HiGHS); kinematic: enumeration of the "
                             "mechanisms (default: %(default)s)")
    parser.add_argument("--min-pier-width", action="store_true",
                        help="print the narrowest equal rectangular piers on which the arch "
                             "(with its fill) stands under its own weight instead: give their "
                             "height as --piers ,HEIGHT[,COURSES], the width left blank")
    parser.add_argument("--friction", type=options.number, default=None, metavar="MU",
                        help="Coulomb friction coefficient of every interface, >= 0: the joints "
                             "may slide as well as rock; both directions under the associative "
                             "flow rule (the classical linear program) and the non-associative "
                             "one (slip without opening, by iterated linear programs), with the "
                             "interfaces that rock and slide (default: none, nothing slides)")
    parser.add_argument("--arbiter", action="store_true",
                        help="with --friction: also find the multiplier of the rigid-block model "
                             "(Coulomb friction without dilatancy) under a slowly growing "
                             "horizontal acceleration, a tilting-table test, to arbitrate between "
                             "the two laws (a second or so for an arch)")
    parser.add_argument("--samples", type=int, default=None, metavar="N",
                        help="with --epsilon: the distribution of k over N irregular structures "
                             "instead (member i drawn from child i of the seed, as the studies "
                             "draw their arches; a bridge's spans one after the other): its "
                             "quantiles, and with --plot its distribution beside the nominal k")
    options.add_plot_option(parser, "write a figure of both mechanisms (arch, hinges, line of "
                                    "thrust; with --friction, every law's mechanism)")
    options.add_progress_option(parser)
    options.add_json_option(parser)


def run(args: argparse.Namespace) -> int:
    """Limit analysis of the arch of the options, in both directions."""
    from ..limit_analysis import both_directions

    if args.min_pier_width:
        if args.samples is not None:
            raise ValueError("--min-pier-width finds the piers of the nominal arch: leave out "
                             "--samples")
        return _min_pier_width(args)
    if args.samples is not None:
        return _samples(args)
    arch = options.arch_from_args(args, assembly=True, spans=True)
    if args.friction is not None or hasattr(arch, "interfaces"):
        return _with_friction(args, arch)
    if args.arbiter:
        raise ValueError("--arbiter compares the friction laws: give --friction MU")
    with options.analysing(args):
        results = both_directions(arch, method=args.method)
    k_l, k_r = (r.load_multiplier for r in results)
    if args.plot:
        _plot(args, results)
    if args.json:
        mechanisms = {}
        for r in results:
            entry = {"hinges": [{"joint": h.joint, "face": h.face, "beta": h.beta(r.arch)}
                                for h in r.hinges]}
            if hasattr(r.arch, "joint_name"):  # a structure: where each hinge is
                for hinge, item in zip(r.hinges, entry["hinges"], strict=True):
                    item["where"] = r.arch.joint_name(hinge.joint)
            if r.separation is not None:
                entry["separation"] = r.separation
            mechanisms[r.direction] = entry
        print_json({"k": min(k_l, k_r), "k_l": k_l, "k_r": k_r, "mechanisms": mechanisms})
        return 0
    kind = "irregular arch" if args.epsilon is not None else "arch"
    print(f"Limit analysis ({args.method}) of the {kind}: {describe_arch(arch)}")
    circle = hasattr(arch, "joint_extents")  # the paper's arch: hinge radii, else positions
    where = f"{'r [m]':>8}" if circle else f"{'x [m]':>8} {'y [m]':>8}"
    print(f"{'mechanism':<10} {'k [-]':>8} {'hinge':>6} {'joint':>6} {'face':>9} "
          f"{'beta [rad]':>11} {where}")
    for r in results:
        name = "Mech-l" if r.direction == "l" else "Mech-r"
        labels = "ABCD" if r.is_four_hinge else "12"
        for i, h in enumerate(r.hinges):
            k_text = f"{r.load_multiplier:8.4f}" if i == 0 else " " * 8
            x, y = h.point(r.arch)
            where = f"{h.radius(r.arch):>8.4f}" if circle else f"{x:>8.4f} {y:>8.4f}"
            if hasattr(r.arch, "joint_name"):  # a structure: where each hinge is
                where += f"  {r.arch.joint_name(h.joint)}"
            print(f"{name if i == 0 else '':<10} {k_text} {labels[i]:>6} {h.joint:>6} "
                  f"{h.face:>9} {h.beta(r.arch):>11.4f} {where}")
        if r.separation is not None:
            print(f"{'':<10} {'':>8} {'':>6} {r.separation:>6} {'opens':>9}   (no normal force)")
    print(f"k = min(k_l, k_r) = {min(k_l, k_r):.4f}: the motion starts when the ground "
          f"acceleration reaches {min(k_l, k_r):.4f} g (Mech-r hinges in the mirrored frame)")
    if args.plot:
        print(f"figure written to {args.plot}")
    return 0


MAX_SAMPLES = 100_000
"""Largest ``--samples`` [-]."""


def _k_of(args: argparse.Namespace, structure) -> float:
    """The least k of both directions: the governing friction law's with --friction or for a
    block assembly, else the chain program's (the method of the options)."""
    from ..limit_analysis import both_directions, governing_multiplier

    if args.friction is not None or hasattr(structure, "interfaces"):
        return governing_multiplier(structure, friction=_friction_of(args))
    return min(r.load_multiplier for r in both_directions(structure, method=args.method))


def _samples(args: argparse.Namespace) -> int:
    """``limit --epsilon E --samples N``: k over N irregular structures (arches or bridges)."""
    import numpy as np
    from tqdm.auto import tqdm

    from ..errors import CannotStandError, DescriptionError
    from ..limit_analysis import multiplier_distribution

    if args.epsilon is None:
        raise ValueError("--samples draws irregular structures: give --epsilon")
    if not 1 <= args.samples <= MAX_SAMPLES:
        raise ValueError(f"--samples must be an integer in [1, {MAX_SAMPLES}], got "
                         f"{args.samples}")
    if args.arbiter:
        raise ValueError("--arbiter tests one structure: leave out --samples")
    spec = options.structure_spec(args, spans=True)
    with options.naming_options():
        nominal = spec.nominal()
        members = spec.sample(args.samples)
    if (args.friction is not None or hasattr(nominal, "interfaces")) \
            and args.method != "static":
        raise ValueError("--friction and block assemblies take the static method (the linear "
                         "program): the kinematic enumeration holds for chains of voussoirs "
                         "whose joints do not slide")
    k_nominal = _k_of(args, nominal)
    k = np.full(args.samples, np.nan)
    refused, weak = [], []  # members not built; members that cannot stand (k < 0)
    with options.naming_options():  # each member's refusal names it
        bar = tqdm(total=args.samples, desc="irregular structures", unit="structure",
                   disable=args.no_progress or args.json)
        for i, member in enumerate(members):  # each drawn, built and analysed in turn
            if isinstance(member, DescriptionError):
                refused.append({"member": i, "reason": member.naming(options.FIELD_OPTIONS)})
            else:
                try:
                    k[i] = _k_of(args, member)
                except CannotStandError:
                    weak.append(i)
            bar.update(1)
        bar.close()
    drawn = k[np.isfinite(k)]
    seed = spec.seed if spec.seed is not None else DEFAULT_SEED
    summary = multiplier_distribution(drawn, k_nominal)
    what = "bridges" if (spec.spans or 1) > 1 else "structures"
    if args.plot:
        _plot_sample(args, drawn, k_nominal, f"{what}, epsilon {spec.epsilon:g}, seed {seed}")
    if args.json:
        print_json({"k_nominal": k_nominal, "epsilon": spec.epsilon, "seed": seed,
                    "samples": args.samples, "k": [float(x) if np.isfinite(x) else None
                                                   for x in k],
                    "refused": refused, "cannot_stand": weak,
                    "quantiles": summary.get("quantiles", {}),
                    **{key: summary.get(key) for key in ("mean", "min", "max",
                                                          "below_nominal")}})
        return 0
    print(f"k over {args.samples} irregular {what} (epsilon {spec.epsilon:g}, seed {seed}: "
          f"member i from child i of the seed); nominal k = {k_nominal:.4f}")
    if summary:
        q = summary["quantiles"]
        print(f"  min {summary['min']:.4f}, 5 % {q['0.05']:.4f}, median {q['0.5']:.4f}, mean "
              f"{summary['mean']:.4f}, 95 % {q['0.95']:.4f}, max {summary['max']:.4f}; below "
              f"the nominal: {summary['below_nominal']:.0%}")
    if refused:
        print(f"warning: {len(refused)} of {args.samples} drawn could not be built and are left "
              f"out, so the distribution is of the others (those left out have end voussoirs "
              f"too thick for the seats: wider middle piers keep them); the first: member "
              f"{refused[0]['member']}: {refused[0]['reason']}")
    if weak:
        print(f"warning: {len(weak)} of {args.samples} cannot stand under their own weight "
              f"(k < 0) and are left out of the figures above, all of which they lie below "
              f"(the first: member {weak[0]})")
    if args.plot:
        print(f"figure written to {args.plot}")
    return 0


def _plot_sample(args: argparse.Namespace, k, k_nominal: float, what: str) -> None:
    """The empirical distribution of the sample's k beside the nominal k."""
    from .output import pyplot, save_figure

    pyplot()
    from ..plotting import plot_k_distribution

    ax = plot_k_distribution(k, k_nominal, what)
    ax.figure.set_layout_engine("constrained")
    save_figure(ax.figure, args.plot)


def describe_arch(arch) -> str:
    """One line on the arch: its kind, size and voussoirs (units in brackets); a structure's
    piers and fill too (:func:`archquake.geometry.structure.describe_arch`)."""
    from ..geometry.structure import describe_arch as describe

    return describe(arch)


def _min_pier_width(args: argparse.Namespace) -> int:
    """``limit --min-pier-width --piers ,HEIGHT[,COURSES]``: the narrowest piers that stand."""
    from ..limit_analysis import min_pier_width
    from .output import print_json

    if not args.piers or args.pier_left or args.pier_right:
        raise ValueError("--min-pier-width finds the width of two equal piers: give their "
                         "height as --piers ,HEIGHT[,COURSES] (the width left blank), without "
                         "--pier-left or --pier-right")
    width, height, courses = options.pier_from_option("--piers", args.piers, blank_width=True)
    if width is not None:
        raise ValueError(f"--min-pier-width finds the width: leave it blank in --piers "
                         f",HEIGHT[,COURSES], got {args.piers!r}")
    if args.plot:
        raise ValueError("--min-pier-width cannot be combined with --plot")
    arch = options.arch_from_args(args)
    with options.analysing(args):
        width = min_pier_width(arch, height, courses)
    if args.json:
        print_json({"min_pier_width": width, "height": height, "courses": courses})
    else:
        print(f"narrowest piers on which the arch stands under its own weight: width = "
              f"{width:.6g} m (height {height:g} m, {courses} course"
              f"{'' if courses == 1 else 's'}; {describe_arch(arch)})")
    return 0


def _plot(args: argparse.Namespace, results) -> None:
    from .output import pyplot, save_figure

    plt = pyplot()  # the file-only backend, before the plotting module imports pyplot
    from ..plotting import plot_limit_analysis

    nominal = None
    if args.epsilon is not None:
        nominal = options.nominal_arch_from_args(args)
    fig, axes = plt.subplots(1, 2, figsize=(13, 5.0), constrained_layout=True)
    for ax, r in zip(axes, results, strict=True):
        frame = None if nominal is None else (nominal if r.direction == "l"
                                              else nominal.mirrored())
        plot_limit_analysis(r, ax, nominal=frame)
    save_figure(fig, args.plot)


def _with_friction(args: argparse.Namespace, structure) -> int:
    """``limit --friction MU``: both directions under each friction law."""

    from ..limit_analysis import assembly_limits, governing_law

    if args.method != "static":
        raise ValueError("--friction and block assemblies take the static method (the linear "
                         "program): the kinematic enumeration holds for chains of voussoirs "
                         "whose joints do not slide")
    friction = _friction_of(args)
    with options.analysing(args):
        results = assembly_limits(structure, friction=friction)
    governing = {d: governing_law(laws) for d, laws in results.items()}
    k = min(r.load_multiplier for r in governing.values())
    ramp = None
    if args.arbiter:
        from ..rigid_blocks.ramp import ramp_test

        on = structure.with_friction(args.friction) if hasattr(structure, "interfaces") \
            else structure
        with options.analysing(args):
            ramp = ramp_test(on, friction=args.friction)
    if args.plot:
        _plot_friction(args, results)
    if args.json:
        out = {"friction": args.friction, "k": k if math.isfinite(k) else None,
               **_rings_json(args, structure, results),
               "directions": {d: {law: r.to_dict() for law, r in laws.items()}
                              for d, laws in results.items()}}
        for d, laws in results.items():  # several spans: which move
            for law, r in laws.items():
                moving = _spans_moving(structure, r)
                if moving is not None:
                    out["directions"][d][law]["spans_moving"] = moving
        if ramp is not None:
            out["rigid_blocks_ramp"] = ramp.to_dict()
        print_json(out)
        return 0
    print(f"Limit analysis of {_describe(structure, args)}; " + _friction_text(args))
    print(f"{'direction':<10} {'law':<16} {'k [-]':>8} {'tilt [deg]':>10} {'LPs':>4}  "
          "rock / slide (interfaces)")
    for direction, laws in results.items():
        for law, r in laws.items():
            k_text = f"{r.load_multiplier:8.4f}" if math.isfinite(r.load_multiplier) else \
                f"{'none':>8}"
            tilt = f"{r.tilt:10.2f}" if math.isfinite(r.load_multiplier) else f"{'':>10}"
            note = "" if r.converged else "  (did not converge)"
            print(f"{direction:<10} {law:<16} {k_text} {tilt} {r.iterations:>4}  "
                  f"{_moving(r)}{note}")
            moving = _spans_moving(structure, r)
            if moving is not None:
                print(f"{'':<10} {'':<16} spans that move: {_listed(moving)}")
        if ramp is not None:
            onset = ramp.onset(direction)
            found = math.isfinite(onset.multiplier)
            k_text = f"{onset.multiplier:8.4f}" if found else f"{'none':>8}"
            tilt = f"{onset.tilt:10.2f}" if found else f"{'':>10}"
            print(f"{direction:<10} {'rigid blocks':<16} {k_text} {tilt} {'':>4}  "
                  f"{_listed(onset.rocking_joints)} / {_listed(onset.sliding_joints)}  "
                  f"(ramp, +/- {onset.error:.1e})")
    if {law for laws in results.values() for law in laws} == {"no sliding"}:
        # no friction given, or mu = inf everywhere: the two laws are one
        print(f"k = {k:.4f}: the least of the two directions (Heyman: no sliding)")
    else:
        print(f"k = {k:.4f}: the least of the two directions under the non-associative law "
              "(slip without opening, the physical one; the associative multiplier is the "
              "classical program's, which can overestimate)")
    if ramp is not None:
        low = min((ramp.onset(d) for d in results), key=lambda o: o.multiplier)
        if low.multiplier == 0.0 and k > 0.0:  # the ramp's onset within its error of zero
            print(f"the rigid blocks do not stand: they move under their own weight (onset "
                  f"0 +/- {low.error:.1e} toward {low.direction}), though the linear programs "
                  "find contact forces that hold them; with non-associative friction that is no "
                  "proof of safety: take the rigid blocks' verdict")
        elif low.multiplier < k - 3.0 * low.error - 0.01 * k:
            print(f"the rigid blocks move from {low.multiplier:.4f} toward {low.direction}, "
                  f"{100 * (1 - low.multiplier / k):.0f} % below k: with non-associative "
                  "friction the iteration's multiplier is no bound; take the rigid blocks' "
                  "lower value")
    if args.plot:
        print(f"figure written to {args.plot}")
    return 0


def _friction_of(args: argparse.Namespace):
    """The friction the analysis applies over the assembly's own: ``--friction`` for every
    interface or, with ``--ring-friction`` (already the ring interfaces' in the assembly), for
    the others (a dict by kind: the ring interfaces keep theirs)."""
    if args.friction is None or getattr(args, "ring_friction", None) is None:
        return args.friction
    return {kind: args.friction for kind in ("bed", "head", "foundation")}


def _friction_text(args: argparse.Namespace) -> str:
    ring = getattr(args, "ring_friction", None)
    if ring is None:
        return ("no interface slides (give --friction MU to let them)" if args.friction is None
                else f"friction mu = {args.friction:g} at every interface")
    others = ("the other interfaces do not slide" if args.friction is None
              else f"mu = {args.friction:g} at the other interfaces")
    return f"friction mu = {ring:g} between the rings, {others}"


def _rings_json(args: argparse.Namespace, structure, results) -> dict:
    """For an arch of several rings: the rings, and the rings whose blocks move in each
    direction's mechanism under each law."""
    if getattr(args, "rings", None) is None:
        return {}
    import numpy as np

    from ..geometry.bridge import rings_of

    moving = {}
    for direction, laws in results.items():
        moving[direction] = {}
        for law, r in laws.items():
            speed = np.abs(r.velocities).max(axis=1)
            moves = speed > 1e-6 * max(float(speed.max()), 1e-300)
            moving[direction][law] = rings_of(structure, np.flatnonzero(moves))
    count = len(rings_of(structure, range(structure.n_blocks)))
    return {"ring_friction": args.ring_friction,
            "rings": {"count": count, "bond": args.ring_bond or "aligned",
                      "blocks": [structure.names[i] for i in range(structure.n_blocks)],
                      "moving_rings": moving}}


def _describe(structure, args=None) -> str:
    rings = getattr(args, "rings", None)
    if rings is not None and not any(n.startswith("pier ") for n in structure.names):
        return (f"an arch of {rings} {args.ring_bond or 'aligned'} ring"
                f"{'' if rings == 1 else 's'} ({structure.n_blocks} blocks, "
                f"{structure.interfaces.a.size} interfaces)")
    if hasattr(structure, "interfaces"):
        spans = ""
        if any(name.startswith("span ") for name in structure.names):
            from ..geometry.bridge import spans_of

            n = len(spans_of(structure, range(structure.n_blocks)))
            spans = f"{n} span{'s' if n > 1 else ''} on {n + 1} piers, "
            if rings is not None:
                spans += (f"each an arch of {rings} {args.ring_bond or 'aligned'} rings, ")
        fill = getattr(structure, "fill", None)
        return (f"{spans}a block assembly of {structure.n_blocks} blocks and "
                f"{structure.interfaces.a.size} interfaces"
                + ("" if fill is None else f", under a {fill.describe()}"))
    return describe_arch(structure)


def _spans_moving(structure, result):
    """The spans (from 1, left to right) whose voussoirs move in the mechanism of ``result``,
    for an assembly of several spans (:func:`archquake.geometry.bridge.multi_span`); else
    None."""
    names = getattr(structure, "names", ())
    if not any(name.startswith("span ") for name in names):
        return None
    from ..geometry.bridge import moving_blocks, spans_of

    if not math.isfinite(result.load_multiplier):
        return []
    return spans_of(structure, moving_blocks(result))


def _moving(result) -> str:
    """The interfaces that rock and slide; the chords of ring interfaces (an arch of several
    rings) summed as the length of ring interface that opens and slides."""
    ring = result.contacts.kind == "ring"
    if not ring.any():
        return (f"{_listed(result.interfaces_that('rocks'))} / "
                f"{_listed(result.interfaces_that('slides'))}")
    opens, slides = result.ring_lengths()
    rocks = [i for i in result.interfaces_that("rocks") if not ring[i]]
    other = [i for i in result.interfaces_that("slides") if not ring[i]]
    return (f"{_listed(rocks)} / {_listed(other)}; rings open over "
            f"{opens:.3g} m, slide over {slides:.3g} m")


def _listed(interfaces) -> str:
    """Sorted interface indices, runs of three or more as ``first-last`` ("-" for none)."""
    values = sorted(int(i) for i in interfaces)
    runs, start = [], 0
    for n in range(1, len(values) + 1):
        if n == len(values) or values[n] != values[n - 1] + 1:
            run = values[start:n]
            runs.append(f"{run[0]}-{run[-1]}" if len(run) >= 3 else ",".join(map(str, run)))
            start = n
    return ",".join(runs) or "-"


def _plot_friction(args: argparse.Namespace, results) -> None:
    from .output import pyplot, save_figure

    pyplot()
    from ..plotting import plot_assembly_limits

    save_figure(plot_assembly_limits(results), args.plot)
