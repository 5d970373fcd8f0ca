"""Command-line interface: ``archquake SUBCOMMAND ...``; each subcommand maps onto one library call.

``main(argv=None)`` returns the exit status, so tests call it directly. Invalid input is reported
as ``archquake: error: ...`` with exit status 2, never as a traceback; warnings as one line
``archquake: warning: ...``. Ctrl-C (and SIGTERM during a study on worker processes) stops with
``archquake: interrupted`` and exit status 128 + the signal number.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import math
import os
import re
import signal
import sys
import warnings

from ._version import __version__
from .defaults import (
    COMPARE_AMPLITUDES_G,
    COMPARE_DURATIONS,
    COMPARE_RESOLUTION_G,
    DEFAULT_EPSILON,
    DEFAULT_EXTEND_TO_G,
    DEFAULT_FRICTION,
    DEFAULT_LIMIT_METHOD,
    DEFAULT_RESOLUTION_G,
    DEFAULT_RESTITUTION,
    DEFAULT_SAMPLE_LIMIT_METHOD,
    DEFAULT_SEED,
    DOMAIN_AMPLITUDES_G,
    DOMAIN_DURATIONS,
    LIMIT_METHODS,
    LIMIT_SAMPLE_SIZE,
    MAX_ACCELERATION_G,
    MAX_CYCLES,
    MAX_GRID_POINTS,
    MAX_LIMIT_SAMPLES,
    MAX_SAMPLES,
    MAX_STUDY_ANALYSES,
    MIN_RESOLUTION_G,
    STUDY_AMPLITUDES_G,
    STUDY_DURATIONS,
    STUDY_SAMPLE_SIZE,
)
from .errors import StudyError
from .geometry import (
    SHAPES,
    VOUSSOIR_FACES,
    BlockArch,
    circular_arch,
    irregular_arch,
    load_arch,
    shaped_arch,
)
from .reference_arches import OPPENHEIM, oppenheim


def _range_text(values: tuple[float, float, float]) -> str:
    """``start:stop:step`` of a range of :mod:`archquake.defaults`, as an option's default."""
    return ":".join(f"{v:g}" for v in values)


def add_geometry_options(parser: argparse.ArgumentParser, *, sample: bool = False) -> None:
    """Options that define the arch, shared by every subcommand that analyses one arch.

    With ``sample=True`` the options describe the nominal arch of a sample of irregular arches:
    ``--tolerance`` (default 0.10) and ``--seed`` (default 0) are those of the whole sample.
    """
    if sample:
        g = parser.add_argument_group("nominal arch geometry (defaults: Oppenheim's arch)")
    else:
        g = parser.add_argument_group("arch geometry (defaults: Oppenheim's arch)")
    g.add_argument("--shape", choices=SHAPES, default=None,
                   help="shape of the centreline (default: circular); every shape but the "
                        "circle is given by --span and --rise, with its springings on y = 0")
    g.add_argument("--span", type=float, default=None,
                   help="span of the centreline [m] (with --rise)")
    g.add_argument("--rise", type=float, default=None,
                   help="rise of the centreline [m] (with --span)")
    g.add_argument("--radius", type=float, default=None,
                   help=f"mean radius R of a circular arch [m] (default: {OPPENHEIM['radius']:g}"
                        " unless --span and --rise are given)")
    g.add_argument("--embrace", type=float, default=None,
                   help="angle of embrace alpha of a circular arch [deg] (default: "
                        f"{math.degrees(OPPENHEIM['embrace']):g})")
    g.add_argument("--thickness", type=float, default=None,
                   help=f"thickness t, normal to the centreline [m] (default: "
                        f"{OPPENHEIM['thickness']:g})")
    g.add_argument("--voussoirs", type=int, default=None,
                   help=f"number of voussoirs n, of equal centreline length (default: "
                        f"{OPPENHEIM['voussoirs']}; even for a pointed arch)")
    g.add_argument("--faces", choices=VOUSSOIR_FACES, default=None,
                   help="voussoir faces: curved (following intrados and extrados) or flat "
                        "(chords between the joint ends) (default: curved)")
    g.add_argument("--geometry", metavar="FILE.json",
                   help="explicit arch, instead of the options above: a JSON file with "
                        "'angles' [rad], 'thicknesses' [m], 'radii' [m] per voussoir (a circular "
                        "arch), or 'blocks' (block polygons [[x, y], ...] [m], left to right, "
                        "optionally 'springings')")
    if sample:
        g.add_argument("--tolerance", type=float, default=DEFAULT_EPSILON, metavar="EPS",
                       help="tolerance epsilon in [0, 1) of the irregular arches drawn around the "
                            "nominal arch (paper eq. 1; default: %(default)s)")
        g.add_argument("--seed", type=int, default=DEFAULT_SEED,
                       help="root seed of the sample: arch i is drawn from "
                            "SeedSequence(seed, spawn_key=(i,)) (default: %(default)s)")
        return
    g.add_argument("--tolerance", type=float, default=None, metavar="EPS",
                   help="draw one irregular arch around the arch above with tolerance epsilon "
                        "in [0, 1) (paper eq. 1)")
    g.add_argument("--seed", type=int, default=None,
                   help="seed of the irregular draw (default: 0)")


CIRCULAR_OPTIONS = {"radius": OPPENHEIM["radius"], "embrace": math.degrees(OPPENHEIM["embrace"]),
                    "thickness": OPPENHEIM["thickness"], "voussoirs": OPPENHEIM["voussoirs"]}
"""The options of a circular arch and their defaults (Oppenheim's arch)."""

SHAPE_OPTIONS = ("shape", "span", "rise", "radius", "embrace", "thickness", "voussoirs", "faces")
"""The options that describe an arch by its shape (``None`` when not given)."""


def _option(args: argparse.Namespace, name: str):
    """The value of a geometry option, or its default (Oppenheim's arch)."""
    value = getattr(args, name)
    return CIRCULAR_OPTIONS[name] if value is None else value


def check_circular_options(args: argparse.Namespace) -> None:
    """Refuse circular-arch options out of range, naming the option in its own unit."""
    from .geometry import RADIUS_RANGE

    radius, embrace = _option(args, "radius"), _option(args, "embrace")
    if not RADIUS_RANGE[0] <= radius <= RADIUS_RANGE[1]:
        raise ValueError(f"--radius must be a finite number in [{RADIUS_RANGE[0]:g}, "
                         f"{RADIUS_RANGE[1]:g}] m, got {radius:g}")
    if not 0 < embrace < 360:
        raise ValueError(f"--embrace must be in (0, 360) degrees, got {embrace:g}")
    thickness = _option(args, "thickness")
    if not 0 < thickness < 2 * radius:
        raise ValueError(f"--thickness must be in (0, 2 x --radius = {2 * radius:g}) m, "
                         f"got {thickness:g}")
    _check_voussoirs(args)


def _check_voussoirs(args: argparse.Namespace) -> int:
    from .geometry import MAX_VOUSSOIRS, MIN_VOUSSOIRS

    voussoirs = _option(args, "voussoirs")
    if not MIN_VOUSSOIRS <= voussoirs <= MAX_VOUSSOIRS:
        raise ValueError(f"--voussoirs must be an integer from {MIN_VOUSSOIRS} to "
                         f"{MAX_VOUSSOIRS}, got {voussoirs}")
    return voussoirs


def _check_shape_options(args: argparse.Namespace) -> tuple[str, dict]:
    """``(shape, keyword arguments of shaped_arch without thickness)`` of the shape options,
    refusing conflicting ones; ``shape`` is None for the paper's circular arch by radius and
    embrace with curved faces (:func:`circular_arch`, centre at the origin)."""
    from .geometry import LENGTH_RANGE

    shape = args.shape or "circular"
    by_size, by_angle = _given(args, "span", "rise"), _given(args, "radius", "embrace")
    article = "an" if shape[0] in "aeiou" else "a"
    if shape != "circular" and by_angle:
        raise ValueError(f"{' and '.join(by_angle)} apply to circular arches only; {article} "
                         f"{shape} arch is given by --span and --rise")
    if by_size and by_angle:
        raise ValueError(f"{', '.join(by_size + by_angle)}: a circular arch is given by --span "
                         "and --rise or by --radius and --embrace, not both")
    if shape != "circular" or by_size:
        if len(by_size) < 2:
            raise ValueError(f"{article} {shape} arch needs --span and --rise [m]")
        for name in ("span", "rise"):
            value = getattr(args, name)
            if not LENGTH_RANGE[0] <= value <= LENGTH_RANGE[1]:
                raise ValueError(f"--{name} must be a finite number in [{LENGTH_RANGE[0]:g}, "
                                 f"{LENGTH_RANGE[1]:g}] m, got {value:g}")
        thickness = _option(args, "thickness")
        if not (math.isfinite(thickness) and thickness > 0):
            raise ValueError(f"--thickness must be a finite number > 0 [m], got {thickness:g}")
        return shape, {"span": args.span, "rise": args.rise, "voussoirs": _check_voussoirs(args),
                       "faces": args.faces or "curved"}
    check_circular_options(args)
    kwargs = {"radius": _option(args, "radius"),
              "embrace": math.radians(_option(args, "embrace")),
              "voussoirs": _option(args, "voussoirs"), "faces": args.faces or "curved"}
    return (None if kwargs["faces"] == "curved" else "circular"), kwargs


def nominal_arch_from_args(args: argparse.Namespace) -> BlockArch:
    """The arch of the geometry options, before any irregular draw."""
    if args.geometry:
        given = _given(args, *SHAPE_OPTIONS)
        if given:
            raise ValueError(f"--geometry gives the whole arch; it cannot be combined with "
                             f"{', '.join(given)}")
        return load_arch(args.geometry)
    shape, kwargs = _check_shape_options(args)
    thickness = _option(args, "thickness")
    if shape is None:
        return circular_arch(kwargs["radius"], kwargs["embrace"], thickness,
                             kwargs["voussoirs"])
    return shaped_arch(shape, thickness=thickness, **kwargs)


def arch_from_args(args: argparse.Namespace) -> BlockArch:
    """The arch described by the geometry options."""
    return arches_from_args(args)[1]


def arches_from_args(args: argparse.Namespace) -> tuple[BlockArch, BlockArch]:
    """``(nominal, arch)``: the arch before and after the optional irregular draw."""
    arch = nominal_arch_from_args(args)
    nominal = arch
    if args.tolerance is not None:
        seed = 0 if args.seed is None else args.seed
        if not 0.0 <= args.tolerance < 1.0:
            raise ValueError(f"--tolerance (epsilon) must be in [0, 1), got {args.tolerance:g}")
        if seed < 0:
            raise ValueError(f"--seed must be an integer >= 0, got {seed}")
        if not hasattr(arch, "perturbed"):
            raise ValueError("--tolerance draws an irregular arch around an arch with a "
                             "centreline; a surveyed arch (--geometry with 'blocks') has none")
        try:
            arch = irregular_arch(arch, args.tolerance, rng=seed)
        except ValueError as exc:
            raise ValueError(f"{_drawn(args)} is not a valid arch: {exc}; the tolerance is too "
                             f"large for this arch") from exc
    elif args.seed is not None:
        raise ValueError("--seed needs --tolerance (the seed of an irregular arch)")
    return nominal, arch


def _drawn(args: argparse.Namespace) -> str:
    return (f"the irregular arch drawn with --tolerance {args.tolerance:g} (seed "
            f"{0 if args.seed is None else args.seed})")


@contextlib.contextmanager
def analysing(args: argparse.Namespace):
    """Name the irregular arch (tolerance and seed) in an error of its analysis."""
    try:
        yield
    except ValueError as exc:
        if getattr(args, "tolerance", None) is None:
            raise
        raise ValueError(f"{_drawn(args)}: {exc}") from exc


RESTITUTION_HELP = (
    "'computed' from the momentum balance of the whole arch, 'link' from the paper's link-wise "
    "rule (Housner's rule for the post-impact springing link), 'blocks' measured on the "
    "rigid-block model of the arch (the kinetic energy its blocks keep at the impact), "
    "'nominal' = the nominal arch's computed value (the paper's practice for irregular arches), "
    "'paper' = 0.875, 'elastic' = 1, or a number in (0, 1]")
"""The restitution models, as the help of every ``--restitution`` option lists them."""


def add_restitution_option(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--restitution", default=DEFAULT_RESTITUTION,
        metavar="computed|link|blocks|nominal|paper|elastic|VALUE",
        help=f"coefficient of restitution c_v at impacts: {RESTITUTION_HELP} "
             f"(default: %(default)s)",
    )


def restitution_model(text: str):
    """The --restitution value, checked
    (:func:`archquake.fourlink.impact.check_restitution_model`)."""
    from .fourlink.impact import check_restitution_model

    try:
        return check_restitution_model(text)
    except ValueError as exc:
        raise ValueError(f"--{exc}") from None


def check_workers(workers: int | None) -> int | None:
    """The ``--workers`` value, checked: None or 1 (run in this process) -> None."""
    cpus = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    most = 4 * (cpus or 1)
    if workers is not None and not 1 <= workers <= most:
        raise ValueError(f"--workers must be an integer in [1, {most}] (4 per CPU of this "
                         f"machine: more processes would only share them, each with its own "
                         f"memory), got {workers}")
    return None if workers in (None, 1) else workers


def dynamics_from_args(args: argparse.Namespace):
    """The :class:`~archquake.fourlink.FourLinkModel` of the arch of the geometry options."""
    from .fourlink.dynamics import ArchDynamics

    nominal, arch = arches_from_args(args)
    model = restitution_model(args.restitution)
    with analysing(args):
        return ArchDynamics.from_arch(arch, model, nominal)


def print_json(obj) -> None:
    print(json.dumps(obj, indent=2))


# Each entry: module-level function(subparsers) that adds one subcommand and sets ``func``.
COMMANDS: list = []


def add_limit(subparsers) -> None:
    """``archquake limit``: load multipliers, hinges and thrust lines (paper Sect. 3, Table 1)."""
    parser = subparsers.add_parser(
        "limit",
        help="limit analysis: horizontal load multipliers k_l, k_r and the collapse hinges",
        description="Limit analysis of the arch under its weight and horizontal forces k m_i g "
                    "(Heyman: no tension, infinite compressive strength, no sliding). Mech-l: "
                    "forces left -> right; Mech-r: the mirrored arch, hinges reported in the "
                    "mirrored frame (as Table 1 of the paper). Motion starts when the ground "
                    "acceleration reaches k g.",
    )
    add_geometry_options(parser)
    parser.add_argument("--method", choices=LIMIT_METHODS, default=DEFAULT_LIMIT_METHOD,
                        help="static: linear program (HiGHS); kinematic: enumeration of the "
                             "mechanisms (default: %(default)s)")
    parser.add_argument("--min-thickness", action="store_true",
                        help="print the minimum thickness under its own weight of the arch of "
                             "the shape options (its centreline and voussoirs kept, the "
                             "thickness scaled) instead, and its ratio to the radius (circular "
                             "arches) or to the span")
    parser.add_argument("--plot", metavar="FILE.png",
                        help="write a figure of both mechanisms (arch, hinges, line of thrust)")
    parser.add_argument("--json", action="store_true", help="machine-readable output")
    parser.set_defaults(func=_run_limit)


def _run_limit(args: argparse.Namespace) -> int:
    from .limit_analysis import both_directions

    if args.min_thickness:
        if (args.geometry or args.tolerance is not None or args.plot
                or args.thickness is not None):
            raise ValueError("--min-thickness applies to an arch of a shape (--shape, --span, "
                             "--rise or --radius, --embrace, and --voussoirs, --faces) whose "
                             "thickness it finds; it cannot be combined with --thickness, "
                             "--geometry, --tolerance or --plot")
        _print_min_thickness(args)
        return 0
    arch = arch_from_args(args)
    with analysing(args):
        results = both_directions(arch, method=args.method)
    k_l, k_r = (r.load_multiplier for r in results)
    if args.plot:
        _plot_limit(args, results)
    if args.json:
        mechanisms = {}
        for r in results:
            entry = {"hinges": [{"joint": h.joint, "face": h.face, "beta": h.beta(r.arch)}
                                for h in r.hinges]}
            if r.separation is not None:
                entry["separation"] = r.separation
            mechanisms[r.direction] = entry
        print_json({"k": min(k_l, k_r), "k_l": k_l, "k_r": k_r, "mechanisms": mechanisms})
        return 0
    kind = "irregular arch" if args.tolerance is not None else "arch"
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
            print(f"{name if i == 0 else '':<10} {k_text} {labels[i]:>6} {h.joint:>6} "
                  f"{h.face:>9} {h.beta(r.arch):>11.4f} {where}")
        if r.separation is not None:
            print(f"{'':<10} {'':>8} {'':>6} {r.separation:>6} {'opens':>9}   (no normal force)")
    print(f"k = min(k_l, k_r) = {min(k_l, k_r):.4f}: the motion starts when the ground "
          f"acceleration reaches {min(k_l, k_r):.4f} g (Mech-r hinges in the mirrored frame)")
    if args.plot:
        print(f"figure written to {args.plot}")
    return 0


def describe_arch(arch: BlockArch) -> str:
    """One line on the arch: its kind, size and voussoirs (units in brackets)."""
    n = arch.n_voussoirs
    if hasattr(arch, "radii"):  # the paper's circular arch
        return (f"n = {n} voussoirs, embrace = {math.degrees(arch.embrace):.4g} deg, mean radius "
                f"= {float(arch.radii.mean()):.4g} m, mean thickness = "
                f"{float(arch.thicknesses.mean()):.4g} m")
    if hasattr(arch, "centreline"):
        return (f"{arch.shape} arch, span = {arch.span:.4g} m, rise = {arch.rise:.4g} m, "
                f"n = {n} voussoirs ({arch.faces} faces), mean thickness = "
                f"{arch.thickness_scale:.4g} m")
    return f"surveyed arch of {n} blocks, mean joint depth = {arch.thickness_scale:.4g} m"


def _print_min_thickness(args: argparse.Namespace) -> None:
    from .limit_analysis import min_thickness, shaped_min_thickness

    if args.geometry:
        raise ValueError("--min-thickness needs an arch of a shape, not --geometry")
    shape, kwargs = _check_shape_options(args)
    if shape is None:
        thickness = min_thickness(kwargs["radius"], kwargs["embrace"], kwargs["voussoirs"])
        scale, of = kwargs["radius"], "radius"
        what = (f"circular arch, R = {kwargs['radius']:g} m, alpha = "
                f"{math.degrees(kwargs['embrace']):g} deg, n = {kwargs['voussoirs']}")
    else:
        thickness = shaped_min_thickness(shape, **kwargs)
        line = shaped_arch(shape, thickness=thickness, **kwargs).centreline
        scale, of = (line.radius, "radius") if shape == "circular" else (line.span, "span")
        what = (f"{shape} arch, span = {line.span:g} m, rise = {line.rise:g} m, n = "
                f"{kwargs['voussoirs']}, {kwargs['faces']} faces")
    if args.json:
        print_json({"min_thickness": thickness, "ratio": thickness / scale, "ratio_of": of})
    else:
        symbol = "R" if of == "radius" else "span"
        print(f"minimum thickness under self-weight: t_min = {thickness:.6g} m "
              f"(t_min/{symbol} = {thickness / scale:.6g}; {what})")


def _pyplot():
    """``matplotlib.pyplot`` on the file-only Agg backend (the command line opens no window)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _check_figure_path(path) -> None:
    """Refuse a figure path that is a directory or has no image extension (before a long run:
    :func:`_save_figure` checks the same)."""
    from pathlib import Path

    from matplotlib.backend_bases import FigureCanvasBase

    formats = FigureCanvasBase.get_supported_filetypes()
    if Path(path).is_dir():
        raise ValueError(f"cannot write the figure {str(path)!r}: it is a directory")
    if Path(path).suffix.lstrip(".").lower() not in formats:
        raise ValueError(f"cannot write the figure {str(path)!r}: give a file name with an "
                         f"extension among {', '.join('.' + f for f in sorted(formats))}")


def _save_figure(fig, path, **savefig_options) -> None:
    """Write ``fig`` to ``path`` (PNG by default) and close it; a bad path is a ValueError."""
    import matplotlib.pyplot as plt

    options = {"dpi": 150, **savefig_options}
    try:
        _check_figure_path(path)
        fig.savefig(path, **options)
    except OSError as exc:
        raise ValueError(f"cannot write the figure {str(path)!r}: {exc.strerror}") from exc
    finally:
        plt.close(fig)


def _plot_limit(args: argparse.Namespace, results) -> None:
    plt = _pyplot()

    from .plotting import plot_limit_analysis

    nominal = None
    if args.tolerance is not None:
        nominal = arch_from_args(argparse.Namespace(**{**vars(args), "tolerance": None,
                                                       "seed": None}))
    fig, axes = plt.subplots(1, 2, figsize=(13, 5.0), constrained_layout=True)
    for ax, r in zip(axes, results, strict=True):
        frame = None if nominal is None else (nominal if r.direction == "l"
                                              else nominal.mirrored())
        plot_limit_analysis(r, ax, nominal=frame)
    _save_figure(fig, args.plot)


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="archquake",
        description="Seismic response of masonry arches with geometrical irregularities: limit "
                    "analysis, four-link rocking dynamics with impacts, failure domains and "
                    "fragility. Units: m, s, rad; angles on the command line in degrees and "
                    "accelerations in g where stated.",
    )
    parser.add_argument("--version", action="version", version=f"archquake {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)
    for add in COMMANDS:
        add(sub)
    return parser


class Terminated(KeyboardInterrupt):
    """SIGTERM, raised like Ctrl-C so that a study stops the same clean way."""


def _raise_terminated(signum, frame):
    raise Terminated()


_NEGATIVE_VALUE = re.compile(r"^-(\d|\.\d|inf|nan)", re.IGNORECASE)


def _attach_negative_values(argv: list[str]) -> list[str]:
    """``--option -1e-3`` as ``--option=-1e-3``: argparse takes a value that starts with a dash
    and is not a plain number (``-1e-3``, ``-1:1:0.5``, ``-inf``) for an option of its own."""
    out: list[str] = []
    i = 0
    while i < len(argv):
        if (argv[i].startswith("--") and "=" not in argv[i] and i + 1 < len(argv)
                and _NEGATIVE_VALUE.match(argv[i + 1])):
            out.append(f"{argv[i]}={argv[i + 1]}")
            i += 2
        else:
            out.append(argv[i])
            i += 1
    return out


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(_attach_negative_values(sys.argv[1:] if argv is None else argv))
    previous = None
    if getattr(args, "workers", None) not in (None, 1):
        # a study on worker processes: SIGTERM stops it like Ctrl-C, which terminates the
        # workers. Elsewhere SIGTERM keeps its default action: a Python handler runs only
        # between bytecodes, so it would wait for a long compiled loop to return.
        with contextlib.suppress(ValueError):  # not the main thread: signals stay as they are
            previous = signal.signal(signal.SIGTERM, _raise_terminated)
    show_warning, warnings.showwarning = warnings.showwarning, _show_warning
    try:
        return int(args.func(args) or 0)
    except KeyboardInterrupt as exc:  # Ctrl-C or SIGTERM: stop without a traceback
        signum = signal.SIGTERM if isinstance(exc, Terminated) else signal.SIGINT
        hint = ""
        if getattr(args, "resume", None) is not None and getattr(args, "out", None):
            hint = (f"; rerun with --resume to continue the study in {args.out} (its finished "
                    "chunks are kept)")
        print(f"archquake: interrupted ({signal.Signals(signum).name}){hint}", file=sys.stderr)
        return 128 + signum
    except (ValueError, StudyError) as exc:
        print(f"archquake: error: {exc}", file=sys.stderr)
        return 2
    except OSError as exc:  # a file or directory given on the command line cannot be used
        where = f": {exc.filename!r}" if exc.filename else ""
        print(f"archquake: error: {exc.strerror or exc}{where}", file=sys.stderr)
        return 2
    finally:
        warnings.showwarning = show_warning
        if previous is not None:
            signal.signal(signal.SIGTERM, previous)


def _show_warning(message, category, filename, lineno, file=None, line=None) -> None:
    """A warning on the command line: one line, like the errors."""
    print(f"archquake: warning: {message}", file=sys.stderr if file is None else file)


COMMANDS.append(add_limit)


def add_mechanism(subparsers) -> None:
    """``archquake mechanism``: the four-link mechanisms (paper Sects. 4.1-4.4, Tables 2-3)."""
    parser = subparsers.add_parser(
        "mechanism",
        help="four-link mechanisms Mech-l and Mech-r: theta_u, links, critical angle, c_v",
        description="Oppenheim's four-link mechanism of the arch for both directions, built on "
                    "the limit-analysis hinges: undisplaced configuration theta_u, theta_BC, "
                    "theta_CD [rad], link lengths AB, BC, CD [m], critical angle theta_cr and "
                    "phi_cr = theta_u - theta_cr [rad], activation acceleration -F/P [g], and "
                    "the coefficients of restitution of the impacts. Mech-r quantities are in "
                    "the mirrored frame.",
    )
    add_geometry_options(parser)
    add_restitution_option(parser)
    parser.add_argument("--json", action="store_true", help="machine-readable output")
    parser.set_defaults(func=_run_mechanism)


def _run_mechanism(args: argparse.Namespace) -> int:
    dynamics = dynamics_from_args(args)
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


COMMANDS.append(add_mechanism)



def add_reproduce(subparsers) -> None:
    """``archquake reproduce``: every table and figure of the paper beside the paper's values."""
    parser = subparsers.add_parser(
        "reproduce",
        help="regenerate every table and figure of the paper into a report (HTML, Markdown, "
             "JSON)",
        description="Run the paper's chain on Oppenheim's arch and on irregular arches "
                    "(epsilon = 0.10): Tables 1-3, the arch and its hinges (Figs. 2, 4), the "
                    "potential energy (6-8), free vibrations (9-14), pulse responses (15), the "
                    "failure domain (16), fragility curves and surface (17-21), each beside the "
                    "paper's values. Writes DIR/report.html (self-contained), DIR/report.md "
                    "with the PNG figures, and DIR/results.json with every number.",
    )
    parser.add_argument("--out", default="report", metavar="DIR",
                        help="output directory (default: %(default)s)")
    parser.add_argument("--quick", action="store_true",
                        help="reduced study for a smoke test (h = 6 arches, s = 100, 0.05 g "
                             "steps, 7 failure-domain durations)")
    parser.add_argument("--seed", type=int, default=None,
                        help="root seed of the irregular arches (default: 2024)")
    parser.add_argument("--restitution", default=None,
                        metavar="computed|link|blocks|nominal|paper|elastic|VALUE",
                        help=f"coefficient of restitution c_v of the paper's results, one value "
                             f"for every arch as in the paper: {RESTITUTION_HELP}; a model "
                             f"gives the value of Oppenheim's arch (default: the paper's 0.875; "
                             f"the computed value is always shown beside it)")
    parser.add_argument("--no-progress", action="store_true", help="no progress bar on stderr")
    parser.set_defaults(func=_run_reproduce)


def _run_reproduce(args: argparse.Namespace) -> int:
    from .paper_reproduction import ReproductionSettings, reproduce

    changes = {}
    if args.seed is not None:
        changes["seed"] = args.seed
    if args.restitution is not None:
        model = restitution_model(args.restitution)
        if isinstance(model, str):  # a model: its value for the nominal arch
            from .fourlink.dynamics import ArchDynamics

            model = ArchDynamics.from_arch(oppenheim(), model).restitution[0]
        changes["restitution"] = model
    settings = (ReproductionSettings.quick_settings(**changes) if args.quick
                else ReproductionSettings(**changes))
    result = reproduce(args.out, settings, progress=not args.no_progress)
    timings = result.results["timings"]
    print(f"report written to {result.directory / 'report.html'} (also report.md, "
          f"results.json and {len(result.figures)} figures) in {timings['total']:.1f} s")
    return 0


COMMANDS.append(add_reproduce)


def parse_values(text: str, name: str) -> list[float]:
    """Values of a list option: comma-separated numbers and ranges ``start:stop:step``.

    A range includes ``stop`` when a step lands within ``step/2`` of it
    (:func:`archquake.studies.failure_domain.inclusive_range`); ``"0.4,0.5"`` and ``"0.2:1.0:0.01"``
    and ``"0.1:0.3:0.1,0.5"`` are valid.
    """
    from .studies.failure_domain import inclusive_range

    values: list[float] = []
    for part in (p.strip() for p in str(text).split(",")):
        if not part:
            continue
        pieces = part.split(":")
        try:
            numbers = [float(x) for x in pieces]
        except ValueError:
            raise ValueError(f"{name}: cannot read {part!r}; give numbers separated by commas "
                             "or a range start:stop:step") from None
        if len(numbers) == 1:
            values.append(numbers[0])
        elif len(numbers) == 3:
            try:
                values.extend(inclusive_range(*numbers).tolist())
            except ValueError as exc:
                raise ValueError(f"{name}: {exc}") from None
        else:
            raise ValueError(f"{name}: a range is start:stop:step, got {part!r}")
    if not values:
        raise ValueError(f"{name} must not be empty")
    if not all(math.isfinite(v) for v in values):
        raise ValueError(f"{name} must be finite numbers, got {values}")
    return values


def _durations(text: str) -> list[float]:
    values = parse_values(text, "--durations")
    bad = [v for v in values if v <= 0]
    if bad:
        raise ValueError(f"--durations must be pulse durations > 0 [s], got {bad}")
    return values


def _amplitudes(text: str) -> list[float]:
    values = parse_values(text, "--amplitudes")
    if len(values) < 2 or any(b <= a for a, b in zip(values, values[1:], strict=False)):
        raise ValueError("--amplitudes must be at least two increasing amplitudes [g]")
    if values[0] < 0:
        raise ValueError(f"--amplitudes must be >= 0 [g] (--direction gives the sign), got "
                         f"{values[0]}")
    return values


def add_domain(subparsers) -> None:
    """``archquake domain``: failure domain over (t_p, a) (paper Sect. 5.3.3, Fig. 16)."""
    parser = subparsers.add_parser(
        "domain",
        help="failure domain of the arch over pulse duration and amplitude (Fig. 16)",
        description="Outcome of Oppenheim's pulse (-a for t_p, +a/2 for 2 t_p, then 0) over a "
                    "grid of durations t_p and amplitudes a: every change of outcome along the "
                    "amplitude (rest, recovery, collapse in half cycle h) is bisected. Prints per "
                    "duration the failure acceleration (lowest collapsing a), the lowest a "
                    "collapsing in the first half cycle (Oppenheim's curve) and the intervals. "
                    "Accelerations in g.",
    )
    add_geometry_options(parser)
    add_restitution_option(parser)
    parser.add_argument("--durations", default=_range_text(DOMAIN_DURATIONS), metavar="LIST",
                        help="pulse durations t_p [s]: comma list and/or ranges start:stop:step "
                             "(stop included) (default: %(default)s)")
    parser.add_argument("--amplitudes", default=_range_text(DOMAIN_AMPLITUDES_G), metavar="LIST",
                        help=f"scan grid of amplitudes a [g], increasing; durations x "
                             f"amplitudes (with the extension) at most {MAX_GRID_POINTS} "
                             f"(default: %(default)s)")
    parser.add_argument("--extend-to", type=float, default=DEFAULT_EXTEND_TO_G, metavar="G",
                        help="where the grid holds no collapse in the first half cycle, scan on "
                             "at its last spacing until that collapse is found, up to this "
                             "amplitude [g]; a boundary beyond it is reported as such; a value "
                             "not above the grid scans the grid alone (default: %(default)s)")
    parser.add_argument("--direction", choices=("l", "r"), default="l",
                        help="l: the first pulse is -a g (opens Mech-l); r: +a g (Mech-r) "
                             "(default: %(default)s)")
    parser.add_argument("--resolution", type=float, default=DEFAULT_RESOLUTION_G, metavar="G",
                        help=f"bisection width of every boundary [g], >= "
                             f"{MIN_RESOLUTION_G:g} (default: %(default)s)")
    parser.add_argument("--plot", metavar="FILE.png", help="write the failure-domain figure")
    parser.add_argument("--json", action="store_true", help="machine-readable output")
    parser.set_defaults(func=_run_domain)


def _run_domain(args: argparse.Namespace) -> int:
    durations = _durations(args.durations)
    amplitudes = _amplitudes(args.amplitudes)
    if not (math.isfinite(args.resolution) and args.resolution >= MIN_RESOLUTION_G):
        raise ValueError(f"--resolution must be >= {MIN_RESOLUTION_G:g} g (the analyses are "
                         f"accurate to about 1e-11: finer boundaries mean nothing), got "
                         f"{args.resolution}")
    if not (math.isfinite(args.extend_to) and args.extend_to <= MAX_ACCELERATION_G):
        raise ValueError(f"--extend-to must be a finite amplitude of at most "
                         f"{MAX_ACCELERATION_G:g} g, got {args.extend_to:g}")
    extend_to = args.extend_to if args.extend_to > amplitudes[-1] else None
    dynamics = dynamics_from_args(args)
    with analysing(args):
        domain = dynamics.failure_domain(durations, amplitudes, direction=args.direction,
                                         resolution=args.resolution, extend_to_g=extend_to)
    if args.plot:
        _pyplot()

        from .plotting import plot_failure_domain

        ax = plot_failure_domain(domain)
        _save_figure(ax.figure, args.plot)
    if args.json:
        print_json(domain.to_list())
        return 0
    c_lr, c_rl = domain.restitution
    print(f"Failure domain, first pulse {'-' if args.direction == 'l' else '+'}a g "
          f"(Mech-{args.direction}); k = {domain.limit_multiplier:.4f}; restitution "
          f"{c_lr:.4f} (l->r), {c_rl:.4f} (r->l); boundaries to {args.resolution:g} g")
    print(f"{'t_p [s]':>8} {'failure [g]':>12} {'1st half [g]':>13}  intervals [g]")
    beyond = []
    for sl in domain.slices:
        parts = []
        for iv in sl.intervals:
            what = (f"collapse h={iv.half_cycle}" if iv.status == "collapse" else iv.status)
            parts.append(f"{iv.start:.3f}-{iv.end:.3f} {what}")
        columns = []
        for value, width in ((sl.failure_acceleration_g, 12),
                             (sl.first_half_cycle_acceleration_g, 13)):
            columns.append(f"{value:>{width}.4f}" if math.isfinite(value)
                           else f"{'> ' + format(sl.scanned_to_g, '.3g'):>{width}}")
        if not math.isfinite(sl.first_half_cycle_acceleration_g):
            beyond.append(sl.duration)
        print(f"{sl.duration:>8.3f} {columns[0]} {columns[1]}  " + "; ".join(parts))
    if beyond:
        print("no collapse in the first half cycle up to the end of the scan at t_p = "
              + ", ".join(f"{d:g}" for d in beyond) + " s: the boundary lies beyond it"
              + ("" if extend_to is None else f" (scan extended up to --extend-to "
                                              f"{extend_to:g} g)"))
    if args.plot:
        print(f"figure written to {args.plot}")
    return 0


COMMANDS.append(add_domain)


def add_fragility(subparsers) -> None:
    """``archquake fragility``: Monte Carlo fragility study (paper Sect. 5.3.3, Figs. 17-21)."""
    parser = subparsers.add_parser(
        "fragility",
        help="fragility curves and surface of irregular arches under Oppenheim's pulse "
             "(Figs. 17-21)",
        description="Draw h irregular arches around the nominal arch (eq. 1), run Oppenheim's "
                    "pulse in both directions over every (t_p, a) of the grid, and estimate "
                    "P_F = h_f/h (eq. 9; an arch fails if it collapses in either direction), "
                    "with quintic and lognormal fits per duration; the CDF of the limit-analysis "
                    "multiplier k~ = min(k~_l, k~_r) of s arches; the nominal arch's failure "
                    "acceleration and k. Default restitution: 'nominal', the nominal arch's "
                    "computed c_v applied to every irregular arch (the paper's practice). "
                    "A drawn arch that is not an arch or cannot stand is excluded, counted and "
                    "named, and left out of h. "
                    "Writes results.parquet/.csv (one row per analysis), curves.csv, "
                    "summary.json and limit_sample/ to --out; checkpoints allow --resume.",
    )
    add_geometry_options(parser, sample=True)
    parser.add_argument("--samples", type=int, default=STUDY_SAMPLE_SIZE,
                        help=f"number h of irregular arches analysed dynamically, at most "
                             f"{MAX_SAMPLES} (default: %(default)s)")
    parser.add_argument("--durations", default=",".join(f"{d:g}" for d in STUDY_DURATIONS),
                        metavar="LIST",
                        help="pulse durations t_p [s] (default: %(default)s)")
    parser.add_argument("--amplitudes", default=_range_text(STUDY_AMPLITUDES_G), metavar="LIST",
                        help=f"amplitudes a [g], increasing; durations x amplitudes at most "
                             f"{MAX_GRID_POINTS}, and 2 x samples x durations x amplitudes at "
                             f"most {MAX_STUDY_ANALYSES} analyses (default: %(default)s)")
    add_restitution_option(parser)
    parser.add_argument("--limit-samples", type=int, default=LIMIT_SAMPLE_SIZE, metavar="S",
                        help=f"number s of arches of the limit-analysis CDF of k~, at most "
                             f"{MAX_LIMIT_SAMPLES} (default: %(default)s)")
    parser.add_argument("--limit-method", choices=LIMIT_METHODS,
                        default=DEFAULT_SAMPLE_LIMIT_METHOD,
                        help="limit-analysis method of that sample (same k~; kinematic is "
                             "faster) (default: %(default)s)")
    parser.add_argument("--out", required=True, metavar="DIR",
                        help="study directory (new or empty, or an interrupted study with "
                             "--resume)")
    run = parser.add_mutually_exclusive_group()
    run.add_argument("--workers", type=int, default=None, metavar="N",
                     help="local worker processes, at most 4 per CPU (default: 1, run in this "
                          "process)")
    run.add_argument("--scheduler", metavar="tcp://HOST:PORT",
                     help="run the chunks on the Dask cluster of this scheduler")
    parser.add_argument("--resume", action="store_true",
                        help="continue the interrupted study in --out (same settings)")
    parser.add_argument("--plot-dir", metavar="DIR",
                        help="write the fragility curves and the surface as PNG files here")
    parser.add_argument("--no-progress", action="store_true", help="no progress bars")
    parser.add_argument("--json", action="store_true",
                        help="print the summary as JSON")
    add_record_fragility_options(parser)
    parser.set_defaults(func=_run_fragility)


def _run_fragility(args: argparse.Namespace) -> int:
    if args.records or args.im or args.levels or args.export_nrml:
        return _run_record_fragility(args)
    from .studies.fragility import CURVES_CSV, LIMIT_DIRECTORY, FragilitySettings, run_fragility

    nominal, _ = arches_from_args(argparse.Namespace(**{**vars(args), "tolerance": None,
                                                        "seed": None}))
    for name, value, most in (("--samples", args.samples, MAX_SAMPLES),
                              ("--limit-samples", args.limit_samples, MAX_LIMIT_SAMPLES)):
        if not 1 <= value <= most:
            raise ValueError(f"{name} must be an integer in [1, {most}], got {value}")
    if args.seed < 0:
        raise ValueError(f"--seed must be an integer >= 0, got {args.seed}")
    if not 0.0 <= args.tolerance < 1.0:
        raise ValueError(f"--tolerance (epsilon) must be in [0, 1), got {args.tolerance}")
    workers = check_workers(args.workers)
    settings = FragilitySettings(
        nominal=nominal, sample_size=args.samples, epsilon=args.tolerance,
        durations=tuple(_durations(args.durations)),
        amplitudes_g=tuple(_amplitudes(args.amplitudes)), seed=args.seed,
        restitution=restitution_model(args.restitution), limit_sample_size=args.limit_samples,
        limit_method=args.limit_method)
    result = run_fragility(settings, args.out, workers=workers, scheduler=args.scheduler,
                           resume=args.resume, progress=not args.no_progress)
    written = []
    if args.plot_dir:
        written = _plot_fragility(result, args.plot_dir)
    summary = result.summary()
    if args.json:
        print_json(summary)
        return 0
    n_analyses = len(result.table)
    c_lr, c_rl = summary["nominal_restitution"]
    print(f"Fragility study: h = {settings.sample_size} irregular arches (epsilon = "
          f"{settings.epsilon:g}, seed {settings.seed}), {len(settings.durations)} durations x "
          f"{len(settings.amplitudes_g)} amplitudes x 2 directions = {n_analyses} analyses; "
          f"restitution {settings.restitution!r} (nominal arch: {c_lr:.4f})")
    print(f"nominal arch: k = {result.nominal_load_multiplier:.4f}")
    arches = summary["arches"]
    if arches["excluded"]:
        listed = "; ".join(f"{why}: {', '.join(map(str, items))}"
                           for why, items in arches["excluded"].items())
        print(f"excluded: {arches['drawn'] - arches['analysed']} of {arches['drawn']} arches "
              f"could not be analysed ({listed}; arch i is drawn from SeedSequence("
              f"{settings.seed}, spawn_key=(i,))); P_F = h_f / h over the h = "
              f"{arches['analysed']} arches analysed")
    print(f"{'t_p [s]':>8} {'Q nominal [g]':>14} {'P_F below Q':>12} {'lowest a_f [g]':>15} "
          f"{'lognormal median [g]':>21} {'beta':>6}")
    for row in summary["durations"]:
        def fmt(x, width, digits=4):
            return f"{'-':>{width}}" if x is None else f"{x:>{width}.{digits}f}"
        print(f"{row['duration']:>8.3f} {fmt(row['nominal_failure_acceleration'], 14)} "
              f"{fmt(row['probability_below_nominal'], 12, 3)} "
              f"{fmt(row['lowest_failure_acceleration'], 15, 2)} "
              f"{fmt(row['lognormal_median'], 21)} {fmt(row['lognormal_dispersion'], 6, 3)}")
    k = summary["limit_sample"]

    def number(x, digits=4):
        return "-" if x is None else f"{x:.{digits}f}"

    others = [f"{k[key]} {what}" for key, what in (("excluded", "excluded"),
                                                     ("never_collapse", "never collapse"))
              if k[key]]
    print(f"k~ = min(k~_l, k~_r) over s = {k['count']} arches ({k['method']}"
          + "".join(f"; {o}" for o in others) + f"): mean {number(k['mean'])}, std "
          f"{number(k['std'])}, min {number(k['min'])}, max {number(k['max'])}; fraction below "
          f"the nominal k (by more than {k['below_nominal_rtol']:g} relative): "
          f"{number(k['fraction_below_nominal'], 3)}")
    print("P_F below Q: fraction of irregular arches that fail at the largest amplitude of "
          "the grid below the nominal failure acceleration Q (where the nominal arch survives)")
    print(f"written to {args.out}: results.parquet, results.csv, {CURVES_CSV}, summary.json, "
          f"{LIMIT_DIRECTORY}/")
    for path in written:
        print(f"figure written to {path}")
    return 0


def _plot_directory(plot_dir):
    """``--plot-dir`` as a Path, created if missing (a ValueError naming the option if not)."""
    from pathlib import Path

    directory = Path(plot_dir)
    try:
        directory.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise ValueError(f"cannot create --plot-dir {plot_dir!r}: {exc.strerror}") from exc
    return directory


def _plot_fragility(result, plot_dir) -> list[str]:

    _pyplot()

    from .plotting import plot_fragility_curve, plot_fragility_surface

    directory = _plot_directory(plot_dir)
    written = []
    for tp in result.durations:
        path = directory / f"fragility_tp{tp:.3f}.png"
        ax = plot_fragility_curve(result, tp)
        _save_figure(ax.figure, path)
        written.append(str(path))
    path = directory / "fragility_surface.png"
    ax = plot_fragility_surface(result)
    _save_figure(ax.figure, path)
    written.append(str(path))
    return written


def add_record_fragility_options(parser: argparse.ArgumentParser) -> None:
    """The options of ``archquake fragility --records``: a multiple-stripe study of a record
    suite (:mod:`archquake.studies.record_fragility`)."""
    parser.set_defaults(pulse_defaults={name: parser.get_default(name) for name in
                                        ("durations", "amplitudes", "limit_samples",
                                         "limit_method")})
    g = parser.add_argument_group(
        "record-based fragility (multiple-stripe analysis)",
        "With --records, every record is scaled to each --levels value of --im and applied in "
        "both polarities to the h irregular arches and to the nominal arch; an arch-record "
        "pair fails if it collapses in either polarity. P(collapse | IM) per stripe, lognormal "
        "fits by maximum likelihood (irregular arches pooled; the nominal arch alone, the "
        "record-to-record dispersion; a common dispersion over records, the geometric one) "
        "with 90%% bootstrap bands over arches and records. --tolerance 0 --samples 1 is the "
        "nominal arch alone. Writes results.parquet/.csv (one row per arch, record, level and "
        "polarity), curves.csv, incremental.csv and summary.json to --out. The pulse options "
        "--durations, --amplitudes, --limit-samples and --limit-method do not apply.")
    g.add_argument("--records", nargs="+", metavar="PATH",
                   help="record files (PEER .AT2, CSV in g, ESM .ASC) and folders of them")
    g.add_argument("--im", metavar="NAME",
                   help="intensity measure of the stripes: pga [g], pgv [m/s], pgd [m], "
                        "arias [m/s] or sa(T) [g] with T the period [s] (default: pga)")
    g.add_argument("--levels", metavar="LIST",
                   help="stripe levels of --im in its unit, increasing and > 0, e.g. "
                        "0.1:1.0:0.05 (required with --records)")
    g.add_argument("--export-nrml", metavar="FILE",
                   help="write the fitted fragility functions (irregular arches, nominal arch) "
                        "as an OpenQuake NRML fragility model, format continuous logncdf")


def _run_record_fragility(args: argparse.Namespace) -> int:
    from .studies.record_fragility import (
        CURVES_CSV,
        INCREMENTAL_CSV,
        RecordFragilitySettings,
        RecordSuite,
        run_record_fragility,
        stripe_measure,
    )

    if not args.records:
        given = [option for option, value in (("--im", args.im), ("--levels", args.levels),
                                              ("--export-nrml", args.export_nrml)) if value]
        raise ValueError(f"{', '.join(given)}: only for a record-based study; give the records "
                         "with --records PATH...")
    pulse_only = [f"--{name.replace('_', '-')}" for name, default in args.pulse_defaults.items()
                  if getattr(args, name) != default]
    if pulse_only:
        raise ValueError(f"{', '.join(pulse_only)}: options of the pulse study, not of a "
                         "record-based one (--records)")
    try:
        im = stripe_measure(args.im or "pga")
    except ValueError as exc:
        raise ValueError(f"--{exc}") from None
    if args.levels is None:
        raise ValueError(f"--levels is required with --records: the stripe levels of {im.name} "
                         f"[{im.unit}], e.g. --levels 0.1:1.0:0.05")
    levels = parse_values(args.levels, "--levels")
    bad = [v for v in levels if v <= 0]
    if bad:
        raise ValueError(f"--levels must be {im.name} values > 0 [{im.unit}] (a record cannot be "
                         f"scaled to 0), got {bad}")
    if any(b <= a for a, b in zip(levels, levels[1:], strict=False)):
        raise ValueError(f"--levels must increase strictly, got {levels}")
    for name, value, minimum in (("--samples", args.samples, 1), ("--seed", args.seed, 0)):
        if value < minimum:
            raise ValueError(f"{name} must be an integer >= {minimum}, got {value}")
    if not 0.0 <= args.tolerance < 1.0:
        raise ValueError(f"--tolerance (epsilon) must be in [0, 1), got {args.tolerance}")
    if args.workers is not None and args.workers < 1:
        raise ValueError(f"--workers must be an integer >= 1, got {args.workers}")
    nominal, _ = arches_from_args(argparse.Namespace(**{**vars(args), "tolerance": None,
                                                        "seed": None}))
    settings = RecordFragilitySettings(
        suite=RecordSuite.from_paths(args.records), levels=tuple(levels), im=im.name,
        nominal=nominal, sample_size=args.samples, epsilon=args.tolerance, seed=args.seed,
        restitution=restitution_model(args.restitution))
    workers = None if args.workers in (None, 1) else args.workers  # 1: in this process
    result = run_record_fragility(settings, args.out, workers=workers,
                                  scheduler=args.scheduler, resume=args.resume,
                                  progress=not args.no_progress)
    written = _plot_record_fragility(result, args.plot_dir) if args.plot_dir else []
    if args.export_nrml:
        try:
            written.append(str(result.export_nrml(args.export_nrml)))
        except OSError as exc:
            raise ValueError(f"cannot write --export-nrml {args.export_nrml!r}: "
                             f"{exc.strerror}") from exc
    summary = result.summary()
    if args.json:
        print_json(summary)
        return 0
    _print_record_fragility(result, summary)
    print(f"written to {args.out}: results.parquet, results.csv, {CURVES_CSV}, "
          f"{INCREMENTAL_CSV}, summary.json")
    for path in written:
        print(f"written {path}")
    return 0


def _print_record_fragility(result, summary: dict) -> None:
    s = result.settings
    unit = s.unit
    analyses = summary["analyses"]
    print(f"Record-based fragility: h = {s.sample_size} irregular arches (epsilon = "
          f"{s.epsilon:g}, seed {s.seed}) and the nominal arch, {len(result.records)} records "
          f"x {result.levels.size} levels of {s.im} [{unit}] x 2 polarities = "
          f"{analyses['total']} analyses ({analyses['at_rest_without_integration']} at rest "
          f"without integration); restitution {s.restitution!r}")
    curves = result.curves()
    print(f"{'level [' + unit + ']':>12} {'P irregular':>12} {'P nominal':>10} "
          f"{'lognormal':>10} {'band':>15}")
    for row in curves.itertuples():
        band = ("-" if not math.isfinite(row.band_lower)
                else f"{row.band_lower:.3f}-{row.band_upper:.3f}")
        fit = "-" if not math.isfinite(row.lognormal_fit) else f"{row.lognormal_fit:.3f}"
        print(f"{row.level:>12.4g} {row.probability:>12.3f} {row.nominal_probability:>10.3f} "
              f"{fit:>10} {band:>15}")

    def describe(fit, band):
        if fit["median"] is None:
            return "no lognormal fit (no collapse, no survival, or a single step)"
        text = f"median {fit['median']:.4g} {unit}, beta {fit['dispersion']:.3f}"
        if band is not None:
            lo, hi = band["median_interval"]
            b_lo, b_hi = band["dispersion_interval"]
            text += (f" ({100 * band['confidence']:.0f}% bootstrap intervals: median "
                     f"{lo:.4g}-{hi:.4g}, beta {b_lo:.3f}-{b_hi:.3f}; {band['resamples']} "
                     f"resamples)")
        return text

    total, nominal = summary["lognormal"], summary["nominal"]["lognormal"]
    print(f"irregular arches, all pairs: {describe(total, total['band'])}")
    print(f"nominal arch: {describe(nominal, nominal['band'])}")
    v = summary["variability"]

    def fmt(x):
        return "-" if x is None else f"{x:.3f}"

    print(f"dispersions: record-to-record {fmt(v['record_to_record'])}, geometric "
          f"{fmt(v['geometric'])}, total {fmt(v['total'])} (srss of the first two "
          f"{fmt(v['srss'])})")
    inc = summary["incremental"]
    print(f"incremental view: {inc['pairs_collapsing']} of {inc['pairs']} arch-record pairs "
          f"collapse at some level; {inc['pairs_recovering_above_first_collapse']} of them "
          "survive again at a level above their lowest collapsing one")


def _plot_record_fragility(result, plot_dir) -> list[str]:
    import re

    _pyplot()

    from .plotting import plot_incremental, plot_record_fragility

    directory = _plot_directory(plot_dir)
    tag = re.sub(r"[^\w.-]", "_", result.settings.im)
    written = []
    for name, plot in (("fragility", plot_record_fragility), ("incremental", plot_incremental)):
        path = directory / f"record_{name}_{tag}.png"
        ax = plot(result)
        _save_figure(ax.figure, path)
        written.append(str(path))
    return written


COMMANDS.append(add_fragility)


def add_motion_options(parser: argparse.ArgumentParser) -> None:
    """Options that define one ground motion (read by :func:`motion_from_args`)."""
    from .ground_motion import ANALYTIC_GROUND_MOTIONS

    m = parser.add_argument_group("ground motion")
    # no argparse defaults (motion_from_args applies them), so that an option given where it
    # does not apply (with --record, with --phi0) can be refused instead of ignored
    m.add_argument("--motion", choices=tuple(ANALYTIC_GROUND_MOTIONS) + ("record", "stochastic"),
                   default=None, metavar="NAME",
                   help="oppenheim (a for t_p then -a/2 for 2 t_p), rectangular, sine, "
                        "harmonic, ricker, ricker-antisymmetric, cycloidal-a, cycloidal-b, "
                        "cycloidal-c, mavroeidis-papageorgiou, record (--record FILE) or "
                        f"stochastic (Rezaeian-Der Kiureghian model) (default: {DEFAULT_MOTION})")
    m.add_argument("--amplitude", type=float, default=None,
                   help=f"signed peak acceleration of a pulse [g], within "
                        f"+-{MAX_ACCELERATION_G:g}; -1 starts Mech-l "
                        f"(default: {DEFAULT_PULSE[0]})")
    m.add_argument("--duration", type=float, default=None,
                   help="time scale of a pulse [s]: its duration t_p (oppenheim, rectangular) "
                        f"or its period (the others) (default: {DEFAULT_PULSE[1]})")
    m.add_argument("--param", action="append", default=[], metavar="NAME=VALUE",
                   help="a parameter of the chosen motion (repeatable): cycles (harmonic), n "
                        "(cycloidal-c), gamma and phase [rad] (mavroeidis-papageorgiou), seed "
                        "and the model parameters of stochastic (arias_intensity [m/s], "
                        "significant_duration [s], midpoint_time [s], filter_frequency [Hz], "
                        "filter_frequency_rate [Hz/s], filter_damping, high_pass_frequency "
                        "[Hz], dt [s], duration [s])")
    m.add_argument("--cycles", type=float, default=None,
                   help=f"cycles of the harmonic motion, at most {MAX_CYCLES} (same as --param "
                        f"cycles=N)")
    m.add_argument("--record", metavar="FILE",
                   help="accelerogram: two-column CSV (time [s], acceleration [g]), PEER NGA "
                        ".AT2 or ESM ASCII (implies --motion record)")
    m.add_argument("--scale-to", type=float, default=None, metavar="PGA",
                   help="scale the record or stochastic motion to this peak ground "
                        "acceleration [g]")
    m.add_argument("--reverse", action="store_true",
                   help="apply the motion with its sign flipped (the other polarity, -xg''(t))")


def add_simulate(subparsers) -> None:
    """``archquake simulate``: one time history (paper Sect. 5.3, Fig. 15)."""
    parser = subparsers.add_parser(
        "simulate",
        help="time history of the rocking arch under a pulse, a record or a stochastic motion",
        description="Time history of the four-link mechanism with impacts under a ground "
                    "motion: outcome rest (never activated) / recovery / collapse, the half "
                    "cycle of collapse (1 = first, no impact), the number of impacts of the "
                    "recorded motion (and of those before the outcome was decided), the "
                    "collapse time [s] (last crossing of theta_cr, the point of no return), the "
                    "largest rotation phi [rad] and when the arch comes to rest.",
    )
    add_geometry_options(parser)
    add_restitution_option(parser)
    add_motion_options(parser)
    parser.add_argument("--phi0", type=float, default=None,
                        help="free vibration instead: release Mech-l from rest at phi0 [rad]")
    parser.add_argument("--t-end", type=float, default=None,
                        help="end of the record [s] (default: a few seconds after the outcome "
                             "is decided)")
    parser.add_argument("--output", metavar="history.csv",
                        help="write the time history (t [s], phi [rad, + Mech-l, - Mech-r], "
                             "theta_dot [rad/s], mechanism)")
    parser.add_argument("--plot", metavar="FILE.png", help="plot the response")
    parser.add_argument("--json", action="store_true", help="machine-readable output")
    parser.set_defaults(func=_run_simulate)


DEFAULT_MOTION = "oppenheim"
"""Ground motion of ``simulate`` when neither ``--motion`` nor ``--record`` is given."""

DEFAULT_PULSE = (-1.0, 0.27)
"""Default ``(amplitude [g], time scale [s])`` of ``simulate``'s pulse: the paper's Fig. 15."""


def _given(args: argparse.Namespace, *names: str) -> list[str]:
    """The options among ``names`` given on the command line (not None, empty or False)."""
    return [f"--{name.replace('_', '-')}" for name in names
            if getattr(args, name) not in (None, [], False)]

STOCHASTIC_PARAMETERS = ("seed", "arias_intensity", "significant_duration", "midpoint_time",
                         "filter_frequency", "filter_frequency_rate", "filter_damping",
                         "high_pass_frequency", "dt", "duration")
"""Parameters of ``--motion stochastic`` (see :func:`archquake.ground_motion.stochastic`)."""


def motion_parameters(args: argparse.Namespace, allowed) -> dict[str, float]:
    """``--param NAME=VALUE`` (and ``--cycles``) as ``{name: value}``, checked against
    ``allowed``."""
    params: dict[str, float] = {}
    if args.cycles is not None:
        if "cycles" not in allowed:
            raise ValueError(f"--cycles applies to --motion harmonic, not {args.motion}")
        params["cycles"] = args.cycles
    for item in args.param:
        name, sep, text = item.partition("=")
        name = name.strip()
        if not sep or not name:
            raise ValueError(f"--param must be NAME=VALUE, got {item!r}")
        if name not in allowed:
            options = ", ".join(allowed) if allowed else "none"
            raise ValueError(f"--param {name} does not apply to --motion {args.motion}; its "
                             f"parameters: {options}")
        try:
            value = float(text)
        except ValueError:
            raise ValueError(f"--param {name}: {text!r} is not a number") from None
        if name in params:
            raise ValueError(f"--param {name} is given twice")
        params[name] = value
    return params


def motion_from_args(args: argparse.Namespace):
    """The ground motion of ``simulate``'s options (reversed with ``--reverse``)."""
    from .geometry import GRAVITY
    from .ground_motion import ground_motion, read_record, scale_to_im, shape_parameters

    def refuse(option, value, what):
        if value is not None:
            raise ValueError(f"{option} applies to an analytic pulse, not to {what}")

    if args.scale_to is not None and not 0 < args.scale_to <= MAX_ACCELERATION_G:
        raise ValueError(f"--scale-to must be in (0, {MAX_ACCELERATION_G:g}] g, got "
                         f"{args.scale_to:g}")
    if args.motion is None and not args.record:
        args.motion = DEFAULT_MOTION
    if args.record or args.motion == "record":
        if not args.record:
            raise ValueError("--motion record needs --record FILE")
        if args.motion not in (None, "record"):
            raise ValueError(f"--record FILE is a recorded motion; it cannot be combined with "
                             f"--motion {args.motion}")
        args.motion = "record"
        refuse("--amplitude", args.amplitude, "a record (use --scale-to PGA)")
        refuse("--duration", args.duration, "a record")
        motion_parameters(args, ())
        motion = read_record(args.record, scale_to=args.scale_to)
    elif args.motion == "stochastic":
        refuse("--amplitude", args.amplitude, "a stochastic motion (use --scale-to PGA)")
        refuse("--duration", args.duration, "a stochastic motion (use --param duration=...)")
        motion = ground_motion("stochastic", **motion_parameters(args, STOCHASTIC_PARAMETERS))
        if args.scale_to is not None:
            motion = scale_to_im(motion, "pga", args.scale_to)
    else:
        if args.scale_to is not None:
            raise ValueError("--scale-to applies to a recorded accelerogram (--record FILE) or "
                             "a stochastic motion; a pulse takes --amplitude")
        amplitude = DEFAULT_PULSE[0] if args.amplitude is None else args.amplitude
        duration = DEFAULT_PULSE[1] if args.duration is None else args.duration
        if not (math.isfinite(amplitude) and abs(amplitude) <= MAX_ACCELERATION_G):
            raise ValueError(f"--amplitude must be a finite acceleration within "
                             f"+-{MAX_ACCELERATION_G:g} g, got {amplitude:g}")
        if not (math.isfinite(duration) and duration > 0):
            raise ValueError(f"--duration must be a finite time > 0 [s], got {duration:g}")
        params = motion_parameters(args, tuple(shape_parameters(args.motion)))
        if "cycles" in params and not 0 < params["cycles"] <= MAX_CYCLES:
            raise ValueError(f"--cycles must be in (0, {MAX_CYCLES}], got {params['cycles']:g}")
        if "n" in params:
            params["n"] = _whole(params["n"], "--param n")
        motion = ground_motion(args.motion, amplitude * GRAVITY, duration, **params)
    return motion.reversed() if args.reverse else motion


def _whole(value: float, option: str) -> int:
    if value != int(value):
        raise ValueError(f"{option} must be a whole number, got {value!r}")
    return int(value)


def _run_simulate(args: argparse.Namespace) -> int:
    import math as _math

    if args.phi0 is not None:
        motion = _given(args, "motion", "amplitude", "duration", "cycles", "param", "record",
                        "scale_to", "reverse")
        if motion:
            raise ValueError(f"--phi0 (free vibration on a still ground) cannot be combined "
                             f"with the ground motion options {', '.join(motion)}")
    dynamics = dynamics_from_args(args)
    coefficients = dynamics.restitution
    if args.phi0 is not None:
        history = dynamics.free_vibration(args.phi0, t_end=args.t_end if args.t_end is not None
                                          else 10.0)
    else:
        history = dynamics.simulate(motion_from_args(args), t_end=args.t_end)
    o = history.outcome
    rest_time = history.rest_time
    result = {"outcome": o.status.label, "half_cycle": o.half_cycle, "impacts": history.impacts,
              "impacts_before_decision": o.impacts,
              "collapse_time": None if _math.isnan(o.collapse_time) else o.collapse_time,
              "max_phi": o.max_phi,
              "at_rest_from": None if _math.isnan(rest_time) else rest_time}
    if args.output:
        import numpy as np

        from .results_io import atomic_path

        table = np.column_stack([history.t, history.phi, np.concatenate(
            [s.theta_dot for s in history.segments])])
        try:
            with atomic_path(args.output) as tmp, open(tmp, "w") as fh:
                fh.write("t_s,phi_rad,theta_dot_rad_s,mechanism\n")
                for (t, phi, thd), mech in zip(table.tolist(), history.mechanism, strict=True):
                    fh.write(f"{t!r},{phi!r},{thd!r},{mech}\n")  # Python floats: exact text
        except OSError as exc:
            raise ValueError(f"cannot write the time history {args.output!r}: "
                             f"{exc.strerror}") from exc
    if args.plot:
        _pyplot()

        from .plotting import plot_free_vibration, plot_pulse_response

        if args.phi0 is not None:
            ax = plot_free_vibration(history)
            fig = ax.figure
        else:
            _, ax = plot_pulse_response(history, phi_limit=min(1.0, 1.5 * o.max_phi + 0.02))
            fig = ax.figure
        _save_figure(fig, args.plot, dpi=120, bbox_inches="tight")
    if args.json:
        print_json(result)
        return 0
    text = {"rest": "the arch is never activated (rests on the ground)",
            "recovery": f"the arch recovers: {history.impacts} impact(s) ({o.impacts} before "
                        f"the end of the excitation), " + (
                            f"at rest from t = {rest_time:.4f} s" if not _math.isnan(rest_time)
                            else f"still rocking at the end of the record, t = "
                                 f"{history.t[-1]:.4f} s (--t-end)"),
            "collapse": f"the arch collapses in half cycle {o.half_cycle} "
                        f"({o.impacts} impact(s) before), point of no return at "
                        f"t = {o.collapse_time:.4f} s"}[o.status.label]
    print(f"{history.ground_motion.name}; c_v = {coefficients[0]:.4f} (l->r), "
          f"{coefficients[1]:.4f} (r->l)")
    print(f"{text}; largest rotation phi = {o.max_phi:.4f} rad")
    return 0


COMMANDS.append(add_simulate)


def add_records(subparsers) -> None:
    """``archquake records``: intensity measures of a suite of recorded accelerograms."""
    parser = subparsers.add_parser(
        "records",
        help="intensity measures (PGA, PGV, PGD, Arias, D5-95, Sa(T)) of recorded accelerograms",
        description="Read recorded accelerograms (PEER NGA .AT2, two-column CSV in g, ESM "
                    "ASCII) and print their intensity measures: pga [g], pgv [m/s], pgd [m] "
                    "(no baseline correction), arias [m/s], d5-95 [s] and sa(T) [g], the "
                    "5%%-damped pseudo-spectral acceleration at period T [s]. A folder stands "
                    "for its files with extension .at2, .csv or .asc; the records are sorted "
                    "by file name.",
    )
    parser.add_argument("paths", nargs="+", metavar="PATH",
                        help="record files and folders of record files")
    parser.add_argument("--im", default="pga,pgv,pgd,arias,d5-95", metavar="LIST",
                        help="comma-separated intensity measures, e.g. pga,pgv,sa(0.5) "
                             "(default: %(default)s)")
    parser.add_argument("--json", action="store_true",
                        help='machine-readable output: [{"record": FILE NAME, IM: value, ...}]')
    parser.set_defaults(func=_run_records)


def _run_records(args: argparse.Namespace) -> int:
    from .ground_motion import parse_intensity_measures, read_suite

    measures = parse_intensity_measures(args.im)
    names = [im.name for im in measures]
    if len(set(names)) != len(names):
        raise ValueError(f"--im names an intensity measure twice: {args.im!r}")
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
    return 0


COMMANDS.append(add_records)


# --- archquake dem: the rigid-block model ------------------------------------------------------

def add_friction_option(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--friction", type=float, default=DEFAULT_FRICTION, metavar="MU",
                        help="Coulomb friction coefficient of the joints of the rigid-block "
                             "model, >= 0 (default: %(default)s)")


def add_dem(subparsers) -> None:
    """``archquake dem``: the rigid-block (contact dynamics) model of the arch."""
    parser = subparsers.add_parser(
        "dem",
        help="rigid-block model of the arch (every voussoir a block, contacts with friction) "
             "under a pulse or a recorded accelerogram",
        description="Every voussoir a rigid block on two supports that move with the ground; "
                    "contacts at both ends of every joint with Coulomb friction and no bounce "
                    "(Moreau-Jean nonsmooth contact dynamics). A second opinion on the "
                    "four-link model, independent of it. Outcome: rest (never moved), recovery "
                    "(back at rest after the excitation) or collapse (a block or the crown "
                    "dropped by a thickness, or too little energy left to return), with the "
                    "collapse time [s], the largest block rotation [rad], crown drop [m] and "
                    "joint slip [m]. Displacements are relative to the ground.",
    )
    add_geometry_options(parser)
    add_motion_options(parser)
    add_friction_option(parser)
    parser.add_argument("--time-step", type=float, default=1e-3, metavar="H",
                        help="time step [s] (default: %(default)s)")
    parser.add_argument("--t-end", type=float, default=None,
                        help="record up to this time [s] (default: until 0.5 s after the "
                             "outcome is decided)")
    parser.add_argument("--output", metavar="history.csv",
                        help="write the time history: t [s], crown drop [m], energies [J/m], "
                             "every block's x, y [m] and rotation [rad], every joint's opening "
                             "and slip [m]")
    parser.add_argument("--plot", metavar="FILE.png",
                        help="plot the blocks (when the collapse is certain, or at their "
                             "largest opening) and the time history")
    parser.add_argument("--animate", metavar="FILE.gif", help="write an animation of the blocks")
    parser.add_argument("--json", action="store_true", help="machine-readable output")
    parser.set_defaults(func=_run_dem)


def _run_dem(args: argparse.Namespace) -> int:
    from .rigid_blocks import BlockSettings, block_outcome, simulate_blocks

    arch = arch_from_args(args)
    motion = motion_from_args(args)
    settings = BlockSettings(friction=args.friction, time_step=args.time_step)
    if args.animate:  # checked before the analysis, which may take a while
        from pathlib import Path

        if Path(args.animate).is_dir():
            raise ValueError(f"cannot write the animation {args.animate!r}: it is a directory")
        if Path(args.animate).suffix.lower() != ".gif":
            raise ValueError(f"cannot write the animation {args.animate!r}: give a file name "
                             f"ending in .gif")
    if args.output or args.plot or args.animate or args.t_end is not None:
        history = simulate_blocks(arch, motion, settings, t_end=args.t_end)
        outcome = history.outcome
        if args.output:
            _write_block_history(history, args.output)
        if args.plot:
            _plot_dem(history, args.plot)
        if args.animate:
            _pyplot()

            from .rigid_blocks.plotting import animate_blocks

            animate_blocks(history, args.animate)
    else:
        outcome = block_outcome(arch, motion, settings)
    if args.json:
        out = outcome.to_dict()
        out = {"outcome": out.pop("status"), **out, "friction": settings.friction,
               "time_step": settings.time_step, "motion": motion.name}
        print_json(out)
        return 0
    why = (f"the contact problem of {outcome.unconverged_steps} steps unsolved"
           if outcome.unconverged_steps else "still moving")
    text = {"rest": "the arch never moves (it moves with the ground)",
            "recovery": "the arch rocks and comes back to rest",
            "collapse": f"the arch collapses (certain at t = {outcome.collapse_time:.3f} s)",
            "undecided": f"undecided: not decided by t = "
                         f"{outcome.steps * settings.time_step:.3f} s ({why})"}
    print(f"Rigid-block model, {motion.name}; friction {settings.friction:g}, time step "
          f"{settings.time_step:g} s")
    print(text[outcome.status.label])
    print(f"largest rotation {outcome.max_rotation:.4f} rad, crown drop "
          f"{outcome.max_crown_drop:.4f} m, slip {outcome.max_slip:.2e} m, joint opening "
          f"{outcome.max_opening:.4f} m; {outcome.steps} steps")
    for option, what in ((args.output, "time history"), (args.plot, "figure"),
                         (args.animate, "animation")):
        if option:
            print(f"{what} written to {option}")
    return 0


def _write_block_history(history, path) -> None:
    import numpy as np

    from .results_io import atomic_path

    nb, nj = history.assembly.n_blocks, history.assembly.n_joints
    columns = {"t_s": history.times, "crown_drop_m": history.crown_drop,
               "kinetic_J_m": history.kinetic_energy, "potential_J_m": history.potential_energy,
               "dissipated_J_m": history.dissipated_energy, "input_J_m": history.input_work}
    for i in range(nb):
        columns[f"x{i}_m"] = history.displacements[:, i, 0]
        columns[f"y{i}_m"] = history.displacements[:, i, 1]
        columns[f"rotation{i}_rad"] = history.rotations[:, i]
    for j in range(nj):
        columns[f"opening{j}_m"] = history.openings[:, j]
        columns[f"slip{j}_m"] = history.slips[:, j]
    table = np.column_stack(list(columns.values()))
    try:
        with atomic_path(path) as tmp, open(tmp, "w") as fh:
            fh.write(",".join(columns) + "\n")
            for row in table:
                fh.write(",".join(repr(float(x)) for x in row) + "\n")
    except OSError as exc:
        raise ValueError(f"cannot write the time history {str(path)!r}: {exc.strerror}") from exc


def _plot_dem(history, path) -> None:
    import numpy as np

    plt = _pyplot()

    from .rigid_blocks.plotting import plot_block_history, plot_blocks

    fig, (left, right) = plt.subplots(1, 2, figsize=(13, 4.5), constrained_layout=True)
    if history.outcome.collapsed:  # when the collapse became certain
        moment = history.outcome.collapse_time
    else:  # the most open state
        moment = float(history.times[int(np.argmax(history.openings.max(axis=1)))])
    plot_blocks(history, moment, left)
    plot_block_history(history, right)
    _save_figure(fig, path)


COMMANDS.append(add_dem)


# --- archquake compare: the two models side by side -------------------------------------------

COMPARE_LABELS = {"rigid_block": "rigid blocks", "computed": "computed", "link": "link",
                  "paper": "paper", "blocks": "blocks"}


def add_compare(subparsers) -> None:
    """``archquake compare``: failure accelerations of the rigid-block and four-link models."""
    parser = subparsers.add_parser(
        "compare",
        help="failure acceleration of the arch per pulse duration in the rigid-block model "
             "beside the four-link model with each restitution model",
        description="How far to trust the four-link model: per duration t_p of Oppenheim's "
                    "pulse (-a for t_p, +a/2 for 2 t_p, then 0), the failure acceleration "
                    "(lowest collapsing amplitude a) and the recovery bands above it, in the "
                    "rigid-block model (every voussoir a block, contacts with friction) and in "
                    "the four-link model with the restitution models computed, link, paper and "
                    "blocks (c_v measured on the rigid blocks). Both models scan the same "
                    "amplitudes, bisect every boundary to the same resolution and are not "
                    "extended beyond the scan. Accelerations in g. The rigid-block analyses "
                    "are the long part (about a second per duration).",
    )
    add_geometry_options(parser)
    parser.add_argument("--durations", default=",".join(f"{d:g}" for d in COMPARE_DURATIONS),
                        metavar="LIST",
                        help="pulse durations t_p [s]: comma list and/or ranges start:stop:step "
                             "(default: %(default)s)")
    parser.add_argument("--amplitudes", default=_range_text(COMPARE_AMPLITUDES_G),
                        metavar="LIST",
                        help="scan grid of amplitudes a [g] of both models, increasing "
                             "(default: %(default)s)")
    parser.add_argument("--resolution", type=float, default=COMPARE_RESOLUTION_G, metavar="G",
                        help="bisection width of every boundary [g], >= 1e-6 (default: "
                             "%(default)s)")
    parser.add_argument("--direction", choices=("l", "r"), default="l",
                        help="l: the first pulse is -a g (opens Mech-l); r: +a g (Mech-r) "
                             "(default: %(default)s)")
    add_friction_option(parser)
    parser.add_argument("--time-step", type=float, default=1e-3, metavar="H",
                        help="time step of the rigid-block model [s] (default: %(default)s)")
    parser.add_argument("--workers", type=int, default=None, metavar="N",
                        help="local worker processes of the rigid-block analyses, one duration "
                             "per task, at most 4 per CPU (default: 1, run in this process)")
    parser.add_argument("--plot", metavar="FILE.png",
                        help="write the failure curves of both models against t_p")
    parser.add_argument("--no-progress", action="store_true", help="no progress bar")
    parser.add_argument("--json", action="store_true",
                        help="machine-readable output: [{duration, rigid_block, four_link: "
                             "{computed, link, paper, blocks}, recovery_above, scanned_to}]")
    parser.set_defaults(func=_run_compare)


MIN_COMPARE_RESOLUTION_G = 1e-6
"""Finest bisection width of ``archquake compare`` [g]: a rigid-block boundary is decided by
time steps of 1 ms, finer widths only cost analyses."""


def _run_compare(args: argparse.Namespace) -> int:
    from .rigid_blocks import BlockSettings
    from .studies.comparison import compare_models

    durations = _durations(args.durations)
    amplitudes = _amplitudes(args.amplitudes)
    if not (math.isfinite(args.resolution) and args.resolution >= MIN_COMPARE_RESOLUTION_G):
        raise ValueError(f"--resolution must be >= {MIN_COMPARE_RESOLUTION_G:g} g, got "
                         f"{args.resolution}")
    if amplitudes[-1] > MAX_ACCELERATION_G:
        raise ValueError(f"--amplitudes must be at most {MAX_ACCELERATION_G:g} g, got "
                         f"{amplitudes[-1]:g}")
    workers = check_workers(args.workers)
    try:
        settings = BlockSettings(friction=args.friction, time_step=args.time_step)
    except ValueError as exc:
        raise ValueError(f"--{str(exc).replace('_', '-')}") from None
    if args.plot:
        _check_figure_path(args.plot)
    arch = arch_from_args(args)
    with analysing(args):
        comparison = compare_models(arch, durations, amplitudes_g=amplitudes,
                                    resolution=args.resolution, direction=args.direction,
                                    settings=settings, workers=workers,
                                    progress=not args.no_progress)
    if args.plot:
        plt = _pyplot()

        from .plotting import plot_model_comparison, plot_model_differences

        fig, (left, right) = plt.subplots(1, 2, figsize=(14.5, 5.6), constrained_layout=True,
                                          width_ratios=(1.2, 1.0))
        plot_model_comparison(comparison, left)
        plot_model_differences(comparison, right)
        _save_figure(fig, args.plot)
    rows = comparison.to_list()
    if args.json:
        print_json(rows)
        return 0
    coefficients = ", ".join(f"{name} {pair[0]:.3f}" for name, pair in
                             comparison.restitution.items())
    print(f"Failure acceleration [g] under Oppenheim's pulse, first pulse "
          f"{'-' if args.direction == 'l' else '+'}a g; k = {comparison.load_multiplier:.4f}")
    print(f"rigid blocks: friction {settings.friction:g}, time step {settings.time_step:g} s; "
          f"four-link c_v: {coefficients}; scan {amplitudes[0]:g}-{amplitudes[-1]:g} g, "
          f"boundaries to {args.resolution:g} g; (+x %): four-link vs rigid blocks")
    names = list(comparison.four_link)
    print(f"{'t_p [s]':>8} {'rigid blocks':>13}" + "".join(f" {n:>15}" for n in names))
    for row in rows:
        top = f"> {row['scanned_to']:.3g}"
        rigid = row["rigid_block"]
        cells = [f"{rigid:>13.3f}" if rigid is not None else f"{top:>13}"]
        for name in names:
            value = row["four_link"][name]
            if value is None:
                cells.append(f"{top:>15}")
            elif rigid is None:
                cells.append(f"{value:>15.3f}")
            else:
                cells.append(f"{value:>7.3f} ({100 * (value / rigid - 1):+4.0f} %)".rjust(15))
        print(f"{row['duration']:>8.3f} " + " ".join(cells))
    bands = []
    for row in rows:
        for name, values in (("rigid blocks", row["recovery_above"]["rigid_block"]),
                             *row["recovery_above"]["four_link"].items()):
            if values:
                text = ", ".join(f"{a:.3f}-{b:.3f}" for a, b in values)
                bands.append(f"  t_p = {row['duration']:g} s, {name}: {text}")
    if bands:
        print("recovery above the failure acceleration [g]:")
        print("\n".join(bands))
    if args.plot:
        print(f"figure written to {args.plot}")
    return 0


COMMANDS.append(add_compare)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
