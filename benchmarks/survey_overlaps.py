"""Reading a surveyed arch of many blocks: the overlap check by a sweep over the blocks' boxes
against the pairwise check it replaced, and the whole survey, for 500 to 10 000 blocks.

    python benchmarks/survey_overlaps.py [--largest-pairwise N]

The blocks are the voussoirs of a circular arch of embrace 0.9 pi (their faces as chords, and
sampled at 24 points for the largest case). The pairwise check is quadratic; it runs only up to
``--largest-pairwise`` blocks (default 1000: 2 000 took 69 s before).
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT / "src"), str(ROOT / "tests" / "geometry")]

from survey_reference import check_overlaps_pairwise  # noqa: E402

from archquake.geometry import circular_arch, surveyed_arch  # noqa: E402
from archquake.geometry.overlaps import first_overlap  # noqa: E402
from archquake.geometry.survey import SURVEY_TOLERANCE  # noqa: E402


def blocks_of(n: int, points: int = 4):
    arch = circular_arch(10.0, 0.9 * math.pi, 1.5, n)
    return [arch.outline(i, points)[:-1] for i in range(n)]


def seconds(function) -> float:
    start = time.perf_counter()
    function()
    return time.perf_counter() - start


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--largest-pairwise", type=int, default=1000)
    args = parser.parse_args()
    first_overlap(blocks_of(8), 1e-9)  # compile (or load the cache) outside the timings
    print(f"{'blocks':>7} {'points':>6} {'sweep [s]':>10} {'pairwise [s]':>13} "
          f"{'whole survey [s]':>17}")
    for n, points in ((500, 4), (1000, 4), (2000, 4), (10000, 4), (10000, 24)):
        blocks = blocks_of(n, points)
        tol = SURVEY_TOLERANCE * 20.0
        sweep = seconds(lambda b=blocks, t=tol: first_overlap(b, t))
        pairwise = (f"{seconds(lambda b=blocks, t=tol: check_overlaps_pairwise(b, t)):>13.2f}"
                    if n <= args.largest_pairwise else f"{'-':>13}")
        whole = seconds(lambda b=blocks: surveyed_arch(b))
        print(f"{n:>7} {points:>6} {sweep:>10.2f} {pairwise} {whole:>17.2f}")


if __name__ == "__main__":
    main()
