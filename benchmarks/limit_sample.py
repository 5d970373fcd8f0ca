"""Time the limit analysis of s irregular Oppenheim arches in both directions, by both methods.

    python benchmarks/limit_sample.py [--samples 1000] [--epsilon 0.1] [--seed 0] [--plot FILE]

Prints the wall time of each method, their largest disagreement, and the statistics of
k~ = min(k~_l, k~_r) [paper, Figs. 17-20, blue curve].
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))

from archquake import oppenheim  # noqa: E402
from archquake.limit_analysis import limit_analysis, limit_sample  # noqa: E402


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--samples", type=int, default=1000)
    parser.add_argument("--epsilon", type=float, default=0.10)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--plot", help="write the empirical CDF of k~ to this PNG")
    args = parser.parse_args(argv)

    nominal = oppenheim()
    k_nominal = limit_analysis(nominal).load_multiplier
    samples = {}
    for method in ("static", "kinematic"):
        start = time.perf_counter()
        samples[method] = limit_sample(nominal, args.epsilon, args.samples, args.seed, method)
        elapsed = time.perf_counter() - start
        print(f"{method:>9}: s = {args.samples} arches x 2 directions in {elapsed:6.2f} s "
              f"({1e3 * elapsed / (2 * max(args.samples, 1)):.2f} ms per analysis)")
    static, kinematic = samples["static"], samples["kinematic"]
    diff = max(np.max(np.abs(static.load_multiplier_l - kinematic.load_multiplier_l)),
               np.max(np.abs(static.load_multiplier_r - kinematic.load_multiplier_r)))
    print(f"largest |k_static - k_kinematic| = {diff:.2e}")
    k = static.load_multiplier
    print(f"nominal k = {k_nominal:.4f}; k~ = min(k~_l, k~_r) over {k.size} arches "
          f"(epsilon = {args.epsilon}, seed = {args.seed}):")
    print(f"  mean {k.mean():.4f}  std {k.std(ddof=1):.4f}  min {k.min():.4f}  "
          f"max {k.max():.4f}  median {np.median(k):.4f}")
    print(f"  fraction below the nominal k: {np.mean(k < k_nominal):.3f}")
    for name, values in (("k~_l", static.load_multiplier_l), ("k~_r", static.load_multiplier_r)):
        print(f"  {name}: mean {values.mean():.4f}  std {values.std(ddof=1):.4f}")
    if args.plot:
        import matplotlib

        matplotlib.use("Agg")
        from archquake.plotting import plot_load_multiplier_cdf

        ax = plot_load_multiplier_cdf(k, nominal_k=k_nominal)
        ax.set_title(f"Limit analysis of {k.size} irregular Oppenheim arches "
                     f"(epsilon = {args.epsilon})")
        ax.figure.savefig(args.plot, dpi=150, bbox_inches="tight")
        print(f"figure written to {args.plot}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
