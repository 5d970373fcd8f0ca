"""Time a fragility study on a pointed arch beside the same study on Oppenheim's circular arch.

    python benchmarks/shapes_fragility.py [--samples 40] [--limit-samples 1000] [--repeat 2]

Both studies have the paper's settings (eq. (1) with epsilon = 0.10, t_p in {0.4, 0.5, 0.6,
0.7} s, 0.20-1.00 g in 0.01 g steps, both directions, s limit analyses), serial in this process
after a warm-up (JIT compilation excluded). The circular arch is Oppenheim's (closed-form
annular sectors, 7 voussoirs); the pointed arch is the equilateral arch of the same span and
thickness in 8 voussoirs (a ShapedArch: blocks built from its centreline, mass properties by
Green's theorem), so the figures compare the geometry of a general arch with the paper's closed
forms. Target: the pointed study within 2x the circular one. Printed: the wall times of the whole
study and of its parts (geometry of the irregular arches, limit-analysis sample), best of
``--repeat``, and their ratios; a third row, Oppenheim's arch in 8 voussoirs, separates what the
number of voussoirs costs (the kinematic enumeration grows as n^4) from what the general
geometry costs. The pointed arch's k is lower, so more of the grid's pulses set it moving.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))

from archquake import circular_arch, oppenheim  # noqa: E402
from archquake.geometry import irregular_sample, shaped_arch  # noqa: E402
from archquake.limit_analysis import limit_sample  # noqa: E402
from archquake.reference_arches import OPPENHEIM  # noqa: E402
from archquake.studies.fragility import FragilitySettings, run_fragility, warm_up  # noqa: E402


def pointed_arch():
    """The equilateral pointed arch of Oppenheim's span and thickness, 8 voussoirs."""
    span = 2 * OPPENHEIM["radius"] * math.sin(OPPENHEIM["embrace"] / 2)
    return shaped_arch("pointed", span=span, rise=span * math.sqrt(3) / 2,
                       thickness=OPPENHEIM["thickness"], voussoirs=8)


def best(repeat: int, call) -> float:
    """Best wall time of ``repeat`` calls [s]."""
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        call()
        times.append(time.perf_counter() - start)
    return min(times)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--samples", type=int, default=40, help="h (default: %(default)s)")
    parser.add_argument("--limit-samples", type=int, default=1000,
                        help="s (default: %(default)s)")
    parser.add_argument("--repeat", type=int, default=2, help="best of (default: %(default)s)")
    args = parser.parse_args(argv)
    warm_up()
    arches = {"circular (Oppenheim, n = 7)": oppenheim(),
              "pointed (equilateral, n = 8)": pointed_arch(),
              "circular (Oppenheim's, n = 8)": circular_arch(
                  OPPENHEIM["radius"], OPPENHEIM["embrace"], OPPENHEIM["thickness"], 8)}
    rows = {}
    for name, nominal in arches.items():
        settings = FragilitySettings(nominal=nominal, sample_size=args.samples,
                                     limit_sample_size=args.limit_samples)
        run_fragility(FragilitySettings(nominal=nominal, sample_size=2, limit_sample_size=4,
                                        durations=(0.4,)), progress=False, backend="serial")
        whole = best(args.repeat, lambda s=settings: run_fragility(s, progress=False,
                                                                   backend="serial"))
        geometry = best(args.repeat, lambda n=nominal: [
            a.masses for a in irregular_sample(n, 0.10, args.limit_samples, seed=0)])
        limit = best(args.repeat, lambda n=nominal: limit_sample(n, 0.10, args.limit_samples,
                                                                 seed=0, method="kinematic"))
        result = run_fragility(settings, progress=False, backend="serial")
        rows[name] = (whole, geometry, limit, result.nominal_load_multiplier)
    print(f"fragility study, h = {args.samples}, s = {args.limit_samples}, 4 durations x 81 "
          f"amplitudes x 2 directions, serial, best of {args.repeat}")
    print(f"{'nominal arch':<30} {'k':>7} {'study [s]':>10} {'geometry of s arches [s]':>25} "
          f"{'limit sample [s]':>17}")
    for name, (whole, geometry, limit, k) in rows.items():
        print(f"{name:<30} {k:7.4f} {whole:10.2f} {geometry:25.2f} {limit:17.2f}")
    (c_whole, c_geo, c_lim, _), (p_whole, p_geo, p_lim, _), _ = rows.values()
    ratio = p_whole / c_whole
    print(f"{'pointed / circular':<30} {'':>7} {ratio:10.2f} {p_geo / c_geo:25.2f} "
          f"{p_lim / c_lim:17.2f}")
    print(f"target: the pointed study within 2x the circular one: "
          f"{'met' if ratio <= 2.0 else 'NOT met'} ({ratio:.2f}x)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
