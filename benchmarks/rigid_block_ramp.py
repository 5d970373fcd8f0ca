"""Convergence of the rigid blocks' ramp (tilt) test with its rate, beside the exact multipliers.

    python benchmarks/rigid_block_ramp.py [--rates 0.8,0.4,0.2,0.1,0.05,0.025,0.0125,0.00625]

For each case and rate (the growth of the multiplier per second [1/s]) ``ramp_test`` in the +x
direction prints: the multiplier at the first threshold crossing (the onset as read directly,
behind it by the ramp's lag), the extrapolated onset ``k``, its stated error, the actual error
against the exact value and the wall time (JIT compilation excluded). The cases and their exact
values:

- Housner's block 0.4 m x 1 m with friction 2 (rocking): ``b/h = 0.4``;
- the same block with friction 0.3 (sliding): ``mu = 0.3``;
- Oppenheim's arch with friction 0.8 (four hinges): the limit analysis's ``k_l``
  (``archquake.limit_analysis.load_multipliers``, 0.3700).

What it shows: the lag of the first crossing falls as ``rate^(2/3)``, the extrapolated onset is
within its stated error of the exact value at every rate, and its error falls with the rate to
the stated ``r h`` floor (5e-5 at the default 0.05 /s for the arch).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))

from archquake import oppenheim  # noqa: E402
from archquake.limit_analysis import load_multipliers  # noqa: E402
from archquake.rigid_blocks import rectangular_block  # noqa: E402
from archquake.rigid_blocks.ramp import ramp_test  # noqa: E402

RATES = "0.8,0.4,0.2,0.1,0.05,0.025,0.0125,0.00625"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rates", default=RATES, help=f"rates [1/s] (default {RATES})")
    args = parser.parse_args(argv)
    rates = [float(r) for r in args.rates.split(",")]
    arch = oppenheim()
    cases = [("block 0.4 x 1 m, mu 2 (rocks)", rectangular_block(0.4, 1.0), 2.0, 0.4),
             ("block 0.4 x 1 m, mu 0.3 (slides)", rectangular_block(0.4, 1.0), 0.3, 0.3),
             ("Oppenheim's arch, mu 0.8", arch, 0.8, load_multipliers(arch)[0])]
    ramp_test(rectangular_block(0.4, 1.0), friction=2.0, rate=1.0, directions="+x")  # JIT
    for name, structure, friction, exact in cases:
        print(f"\n{name}: exact k = {exact:.6f}")
        print(f"{'rate [1/s]':>10} {'k first':>9} {'k onset':>9} {'stated':>8} {'|error|':>8} "
              f"{'mode':>8} {'wall [s]':>8}")
        for rate in rates:
            start = time.perf_counter()
            onset = ramp_test(structure, friction=friction, rate=rate,
                              directions="+x").onset("+x")
            wall = time.perf_counter() - start
            print(f"{rate:10.5g} {onset.crossings[0]:9.6f} {onset.multiplier:9.6f} "
                  f"{onset.error:8.1e} {abs(onset.multiplier - exact):8.1e} {onset.mode:>8} "
                  f"{wall:8.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
