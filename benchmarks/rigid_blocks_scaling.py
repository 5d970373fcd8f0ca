"""Cost of a step of the rigid-block model against the number of blocks.

    python benchmarks/rigid_blocks_scaling.py [--blocks 7 70 700] [--steps 200]

Circular arches of Oppenheim's size (radius 10 m, embrace 157.5 degrees, thickness 1.5 m) cut
into 7, 70 and 700 voussoirs. Two figures per arch, CPU time per step of the compiled driver
(JIT and the conversion of the arch excluded), best of three:

- at rest on a still ground: every contact active and sticking, one linear solve of the contact
  problem per step (2 (n + 1) contacts, 4 (n + 1) impulses): the cost of the band contact
  problem itself, which grows linearly with the number of blocks;
- moving, the first 0.1 s of Oppenheim's pulse -0.6 g, t_p = 0.4 s: the active-set method
  needs more solves per step when many joints open at once (printed beside).

Arches beyond the model's limit (:data:`archquake.rigid_blocks.MAX_BLOCKS`) are run here for
the scaling only: the limit is lifted for this process.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))

from archquake.geometry import GRAVITY, circular_arch  # noqa: E402
from archquake.ground_motion import oppenheim_pulse  # noqa: E402
from archquake.rigid_blocks import dynamics, from_arch, simulate_blocks  # noqa: E402


def per_step(assembly, motion, t_end: float, repeat: int = 3) -> tuple[float, object]:
    """Best CPU time per step [s] of ``simulate_blocks`` to ``t_end``, and its outcome."""
    best, outcome = math.inf, None
    for _ in range(repeat):
        start = time.thread_time()
        history = simulate_blocks(assembly, motion, t_end=t_end, record_every=10**6)
        elapsed = time.thread_time() - start
        outcome = history.outcome
        best = min(best, elapsed / outcome.steps)
    return best, outcome


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--blocks", type=int, nargs="+", default=[7, 70, 700])
    parser.add_argument("--steps", type=int, default=200, help="steps at rest per arch")
    args = parser.parse_args(argv)
    limit = dynamics.MAX_BLOCKS
    dynamics.MAX_BLOCKS = max(max(args.blocks), limit)  # for the scaling only
    pulse = oppenheim_pulse(-0.6 * GRAVITY, 0.4)
    simulate_blocks(from_arch(circular_arch(10.0, math.radians(157.5), 1.5, 7)), None,
                    t_end=0.002)  # JIT (cached after the first run)
    print("Rigid-block model, cost of a step against the number of blocks (1 ms step, one core)")
    print(f"  {'blocks':>6} {'contacts':>8} {'at rest [us/step]':>18} {'per block [us]':>15}"
          f" {'moving [us/step]':>17} {'solves/step':>12}")
    for n in args.blocks:
        assembly = from_arch(circular_arch(10.0, math.radians(157.5), 1.5, n))
        rest, _ = per_step(assembly, None, args.steps * 1e-3)
        moving, outcome = per_step(assembly, pulse, 0.1)
        print(f"  {n:>6} {2 * (n + 1):>8} {1e6 * rest:>18.1f} {1e6 * rest / n:>15.3f}"
              f" {1e6 * moving:>17.1f} {outcome.mean_iterations:>12.1f}")
    print(f"  (lifted here: the model refuses more than {limit} blocks, MAX_BLOCKS)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
