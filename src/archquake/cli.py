"""Command-line interface: ``archquake SUBCOMMAND ...``; each subcommand maps onto one library call.

``main(argv=None)`` returns the exit status, so tests call it directly. Invalid input is reported
as ``archquake: error: ...`` with exit status 2, never as a traceback.
"""

from __future__ import annotations

import argparse
import json
import math
import sys

from . import __version__
from .geometry import Arch, circular_arch, irregular_arch
from .reference_arches import OPPENHEIM


def add_geometry_options(parser: argparse.ArgumentParser) -> None:
    """Options that define the arch, shared by every subcommand that analyses one arch."""
    g = parser.add_argument_group("arch geometry (defaults: Oppenheim's arch)")
    g.add_argument("--radius", type=float, default=OPPENHEIM["radius"],
                   help="mean radius R [m] (default: %(default)s)")
    g.add_argument("--embrace", type=float, default=math.degrees(OPPENHEIM["embrace"]),
                   help="angle of embrace alpha [deg] (default: %(default)s)")
    g.add_argument("--thickness", type=float, default=OPPENHEIM["thickness"],
                   help="thickness t [m] (default: %(default)s)")
    g.add_argument("--voussoirs", type=int, default=OPPENHEIM["voussoirs"],
                   help="number of voussoirs n (default: %(default)s)")
    g.add_argument("--geometry", metavar="FILE.json",
                   help="explicit arch: JSON with 'angles' [rad], 'thicknesses' [m], 'radii' [m] "
                        "per voussoir (overrides the circular-arch options)")
    g.add_argument("--tolerance", type=float, default=None, metavar="EPS",
                   help="draw one irregular arch around the arch above with tolerance epsilon "
                        "in [0, 1) (paper eq. 1)")
    g.add_argument("--seed", type=int, default=None,
                   help="seed of the irregular draw (default: 0)")


def arch_from_args(args: argparse.Namespace) -> Arch:
    """The arch described by the geometry options."""
    if args.geometry:
        arch = Arch.from_json(args.geometry)
    else:
        arch = circular_arch(args.radius, math.radians(args.embrace), args.thickness,
                             args.voussoirs)
    if args.tolerance is not None:
        arch = irregular_arch(arch, args.tolerance, rng=0 if args.seed is None else args.seed)
    elif args.seed is not None:
        raise ValueError("--seed needs --tolerance (the seed of an irregular arch)")
    return arch


def print_json(obj) -> None:
    print(json.dumps(obj, indent=2))


# Each entry: module-level function(subparsers) that adds one subcommand and sets ``func``.
COMMANDS: list = []


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


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return int(args.func(args) or 0)
    except ValueError as exc:
        print(f"archquake: error: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
