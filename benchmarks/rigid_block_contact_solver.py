"""What the contact problem costs: the active-set method beside Lemke's algorithm, by the number
of voussoirs.

    python benchmarks/rigid_block_contact_solver.py [--voussoirs 7 15 30 50] [--t-end 0.6]

Oppenheim's geometry (R = 10 m, 157.5 degrees, t = 1.5 m) cut into n voussoirs, under the
command line's default pulse (Oppenheim's, -1 g, t_p = 0.27 s). For every n, in one run:

1. the whole analysis with the defaults (``archquake rigid-blocks --voussoirs n``): its outcome,
   the steps the active-set method left to Lemke's algorithm, the steps left unsolved (there
   must be none) and its CPU time;
2. the first ``--t-end`` seconds of the same motion recorded twice with every step at h: with
   the default solver (the active-set method, Lemke's algorithm where it gives up) and with
   Lemke's algorithm at every step (``BlockSettings(active_set_solves=0)``): the CPU time per
   step of each, their ratio, and the largest difference of the block rotations between the
   two (round-off where both solve the same problem).

The first figure is what a user waits for; the second what a step of the fallback costs
against a step of the active-set method on the same states.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))

import numpy as np  # noqa: E402

from archquake.geometry import GRAVITY  # noqa: E402
from archquake.geometry.spec import StructureSpec  # noqa: E402
from archquake.ground_motion import oppenheim_pulse  # noqa: E402
from archquake.rigid_blocks import BlockSettings, block_outcome, simulate_blocks  # noqa: E402


def cpu(call):
    start = time.process_time()
    result = call()
    return result, time.process_time() - start


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--voussoirs", type=int, nargs="+", default=[7, 15, 30, 50])
    parser.add_argument("--t-end", type=float, default=0.6)
    args = parser.parse_args(argv)
    pulse = oppenheim_pulse(-1.0 * GRAVITY, 0.27)
    warm = StructureSpec(voussoirs=15).nominal()
    block_outcome(warm, pulse)  # every function compiled (cached after the first run)
    simulate_blocks(warm, pulse, BlockSettings(active_set_solves=0, coarse_factor=1), t_end=0.01)
    print("Rigid blocks, Oppenheim's arch in n voussoirs, Oppenheim's pulse -1 g, t_p = 0.27 s; "
          "CPU times, one core")
    print(f"  {'n':>3} {'outcome':>9} {'Lemke steps':>11} {'unsolved':>8} {'analysis [s]':>12}"
          f" | {'default [ms/step]':>17} {'Lemke [ms/step]':>15} {'ratio':>6}"
          f" {'max |d rotation| [rad]':>22}")
    status = 0
    for n in args.voussoirs:
        arch = StructureSpec(voussoirs=n).nominal()
        outcome, seconds = cpu(lambda arch=arch: block_outcome(arch, pulse))
        runs = []
        for solves in (BlockSettings().active_set_solves, 0):
            settings = BlockSettings(active_set_solves=solves, coarse_factor=1)
            history, spent = cpu(lambda arch=arch, settings=settings: simulate_blocks(
                arch, pulse, settings, t_end=args.t_end, record_every=10))
            runs.append((history, spent / history.outcome.steps))
        (fast, fast_step), (slow, slow_step) = runs
        rows = min(len(fast.times), len(slow.times))
        gap = float(np.abs(fast.rotations[:rows] - slow.rotations[:rows]).max())
        print(f"  {n:>3} {outcome.status.label:>9} {outcome.fallback_steps:>11d}"
              f" {outcome.unconverged_steps:>8d} {seconds:>12.2f} | {1e3 * fast_step:>17.4f}"
              f" {1e3 * slow_step:>15.4f} {slow_step / fast_step:>6.0f} {gap:>22.2e}",
              flush=True)
        status = 1 if outcome.unconverged_steps or not outcome.decided else status
    return status


if __name__ == "__main__":
    sys.exit(main())
