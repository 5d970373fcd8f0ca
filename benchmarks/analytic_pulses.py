"""Smooth pulses in the compiled engine: exact evaluation against a piecewise-linear table.

The smooth pulses (Ricker wavelets, cycloidal, Mavroeidis-Papageorgiou) are compiled kinds that
the engine evaluates exactly, with breakpoints only at their start and end. The alternative is to
tabulate them finely as a LINEAR record, which forces a step at every sample and adds the
interpolation error. For each pulse, on Oppenheim's arch over a grid of amplitudes and periods,
this prints the time per analysis of both and how far the table's outcomes are from the exact
ones (status disagreements, largest relative difference of the largest rotation).

    python benchmarks/analytic_pulses.py [--cases 40]
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))

from archquake import FourLinkModel, oppenheim  # noqa: E402
from archquake.fourlink.time_history import simulate  # noqa: E402
from archquake.geometry import GRAVITY  # noqa: E402
from archquake.ground_motion import ground_motion  # noqa: E402

PULSES = ("ricker", "ricker-antisymmetric", "cycloidal-b", "mavroeidis-papageorgiou")
SAMPLES_PER_PERIOD = (256, 1024, 4096)


def run(tables, motions):
    start = time.perf_counter()
    out = [simulate(tables, m, (0.9, 0.9), record=False) for m in motions]
    return out, (time.perf_counter() - start) / len(motions)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", type=int, default=40, help="analyses per pulse and method")
    args = parser.parse_args(argv)
    tables = FourLinkModel.from_arch(oppenheim()).tables
    rng = np.random.default_rng(0)
    amplitudes = -rng.uniform(0.4, 2.0, args.cases) * GRAVITY
    periods = rng.uniform(0.2, 1.0, args.cases)
    run(tables, [ground_motion("ricker", -GRAVITY, 0.3)])  # warm up the compiled engine
    run(tables, [ground_motion("ricker", -GRAVITY, 0.3).tabulated(0.01)])
    print(f"{args.cases} analyses per pulse on Oppenheim's arch, c = 0.9, amplitudes 0.4-2.0 g,"
          " periods 0.2-1.0 s")
    print(f"{'pulse':24s} {'method':14s} {'ms/analysis':>11s} {'x exact':>8s} "
          f"{'status diff':>11s} {'max |dphi|/phi':>14s}")
    for name in PULSES:
        exact_motions = [ground_motion(name, a, t) for a, t in zip(amplitudes, periods,
                                                                    strict=True)]
        exact, t_exact = run(tables, exact_motions)
        print(f"{name:24s} {'exact':14s} {1e3 * t_exact:11.3f} {1.0:8.1f} {'-':>11s} "
              f"{'-':>14s}")
        for n in SAMPLES_PER_PERIOD:
            tabled, t_table = run(tables, [m.tabulated(m.params[1] / n) for m in exact_motions])
            status = sum(a.status != b.status for a, b in zip(exact, tabled, strict=True))
            moved = [abs(a.max_phi - b.max_phi) / a.max_phi
                     for a, b in zip(exact, tabled, strict=True)
                     if a.status == b.status and a.max_phi > 0]
            print(f"{'':24s} {f'table T/{n}':14s} {1e3 * t_table:11.3f} "
                  f"{t_table / t_exact:8.1f} {status:11d} {max(moved, default=0.0):14.2e}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
