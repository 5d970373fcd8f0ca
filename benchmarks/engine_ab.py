"""The engine of this tree against the engine of another tree, side by side (A/B).

Each measurement runs in a fresh process that imports ``archquake`` from one tree's ``src``
(compilation and tables excluded from the timing), alternating between the two trees for
``--rounds`` rounds, so that both see the same load of a shared, noisy machine; the CPU time of
the process (``time.process_time``) is measured, and the medians are compared:

- grid path: :func:`archquake.fourlink.engine.outcomes_grid` on ``--grid`` Oppenheim pulses around
the
  failure curve of Oppenheim's arch (outcome only: the path of failure domains and fragility
  studies), and on a quarter as many one-cycle sine pulses at least 9 % above the activation (a
  ground acceleration evaluated at every stage of a step);
- recording path: :func:`archquake.fourlink.time_history.simulate` with its record (the time history
  of a pulse response, followed after the decision) on ``--records`` pulses.

Run:  python benchmarks/engine_ab.py --baseline /path/to/other/tree/src [--rounds 7]
(the candidate is this tree unless ``--candidate`` names another ``src``; without
``--baseline`` the tree is compared with itself: the noise of the measurement).
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

MEASURE = r"""
import json, sys, time
import numpy as np
from archquake import oppenheim
from archquake.fourlink import engine
from archquake.geometry import GRAVITY
from archquake.ground_motion import oppenheim_pulse
from archquake.fourlink.mechanism import mechanisms
from archquake.fourlink.time_history import simulate

n_grid, n_records = int(sys.argv[1]), int(sys.argv[2])
tables = [engine.tabulate(m) for m in mechanisms(oppenheim())]
c = 0.875
rng = np.random.default_rng(20240601)

def cases(n):
    durations = rng.uniform(0.2, 0.7, n)
    return durations, -(0.37 + 0.05 / durations) * rng.uniform(0.6, 1.4, n) * GRAVITY

# compile (or load from the cache) both paths first
engine.outcomes_grid(*tables, c, c, [0.3], [-GRAVITY])
simulate(tables, oppenheim_pulse(-GRAVITY, 0.3), (c, c))
d, a = cases(n_grid)
t0 = time.process_time()
engine.outcomes_grid(*tables, c, c, d, a)
grid = (time.process_time() - t0) / n_grid
engine.outcomes_grid(*tables, c, c, [0.3], [-GRAVITY], "sine")
# sine pulses well above the activation (at its edge main's engine could run 2,000,000 steps)
d = rng.uniform(0.2, 0.7, n_grid // 4)
a = -(0.45 + 0.1 / d) * rng.uniform(0.9, 1.5, d.size) * GRAVITY
t0 = time.process_time()
engine.outcomes_grid(*tables, c, c, d, a, "sine")
sine = (time.process_time() - t0) / d.size
d, a = cases(n_records)
motions = [oppenheim_pulse(a[q], d[q]) for q in range(n_records)]
t0 = time.process_time()
for motion in motions:
    simulate(tables, motion, (c, c))
record = (time.process_time() - t0) / n_records
print(json.dumps({"grid": grid, "sine": sine, "record": record}))
"""


def measure(src: Path, n_grid: int, n_records: int) -> dict:
    """One measurement in a fresh process importing ``archquake`` from ``src``."""
    out = subprocess.run([sys.executable, "-c", MEASURE, str(n_grid), str(n_records)],
                         capture_output=True, text=True, check=True,
                         env={**os.environ, "PYTHONPATH": str(src)})
    return json.loads(out.stdout.splitlines()[-1])


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--baseline", type=Path, default=ROOT / "src",
                        help="src directory of the other tree (default: this tree's)")
    parser.add_argument("--candidate", type=Path, default=ROOT / "src",
                        help="src directory of the tree measured against it (default: this "
                             "tree's)")
    parser.add_argument("--rounds", type=int, default=7)
    parser.add_argument("--grid", type=int, default=20000, help="analyses of the grid path")
    parser.add_argument("--records", type=int, default=60, help="analyses of the record path")
    args = parser.parse_args(argv)
    trees = {"baseline": args.baseline.resolve(), "candidate": args.candidate.resolve()}
    for src in trees.values():
        if not (src / "archquake").is_dir():
            parser.error(f"no archquake package in {src}")
    results = {name: [] for name in trees}
    for r in range(args.rounds):
        order = list(trees) if r % 2 == 0 else list(trees)[::-1]
        for name in order:
            results[name].append(measure(trees[name], args.grid, args.records))
        print(f"round {r + 1}: " + "; ".join(
            f"{name} grid {results[name][-1]['grid'] * 1e6:6.2f} us, sine "
            f"{results[name][-1]['sine'] * 1e6:6.2f} us, record "
            f"{results[name][-1]['record'] * 1e3:6.3f} ms" for name in trees), flush=True)
    keys = ("grid", "sine", "record")
    med = {name: {k: statistics.median(x[k] for x in results[name]) for k in keys}
           for name in trees}
    print(f"\nmedians over {args.rounds} rounds (CPU time per analysis):")
    print(f"{'':12} {'grid path [us]':>16} {'sine grid [us]':>16} {'record path [ms]':>18}")
    for name in trees:
        print(f"{name:12} {med[name]['grid'] * 1e6:16.2f} {med[name]['sine'] * 1e6:16.2f} "
              f"{med[name]['record'] * 1e3:18.3f}")
    ratio = {k: med["candidate"][k] / med["baseline"][k] for k in keys}
    print(f"{'ratio':12} {ratio['grid']:16.3f} {ratio['sine']:16.3f} {ratio['record']:18.3f}  "
          f"(candidate / baseline)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
