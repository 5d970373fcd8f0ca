"""``archquake app``: the interactive page, served on this machine (:mod:`archquake.app`)."""

from __future__ import annotations

import argparse
import sys

DESCRIPTION = (
    "Start the interactive page: change the structure (shape, span, rise, thickness, voussoirs, "
    "faces, piers, fill, or a geometry file) and see its blocks, thrust lines, hinges and load "
    "multipliers k_l, k_r at once; shake it with a pulse or a record and watch both models "
    "(four-link and rigid blocks) side by side; compute its failure domain with both models in "
    "the background. Served on loopback only by default; stop with Ctrl-C. Needs the optional "
    'dependencies: pip install "archquake[app]".')

DEFAULT_HOST = "127.0.0.1"
DEFAULT_PORT = 8050


def configure(parser: argparse.ArgumentParser) -> None:
    """The options of ``archquake app``."""
    parser.description = DESCRIPTION
    parser.add_argument("--port", type=int, default=DEFAULT_PORT,
                        help="TCP port, in [0, 65535]; 0 picks a free one (default: "
                             "%(default)s)")
    parser.add_argument("--host", default=DEFAULT_HOST,
                        help="address to listen on (default: %(default)s, this machine only, "
                             "as is any 127.x.y.z, ::1 or localhost; another address, e.g. "
                             "0.0.0.0 for every interface, serves the page to the network, "
                             "which has no authentication; an empty one is refused)")
    parser.add_argument("--no-browser", action="store_true",
                        help="print the page's address instead of opening it in the browser")


def run(args: argparse.Namespace) -> int:
    """Serve the page until interrupted."""
    if not 0 <= args.port <= 65535:
        raise ValueError(f"--port must be an integer in [0, 65535], got {args.port}")
    from ..app import missing_dependencies

    missing = missing_dependencies()
    if missing:
        raise ValueError(f"archquake app needs {', '.join(missing)}: pip install "
                         f"\"archquake[app]\" (or pip install {' '.join(missing)})")
    from ..app.server import serve

    return serve(args.host, args.port, open_browser=not args.no_browser, log=sys.stderr)
