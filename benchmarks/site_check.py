"""The cost of the code check of a mechanism (Circolare 2019 §C8.7.1): the library call and the
whole command, for arches of 7 to 40 voussoirs and an arch on piers.

The check is a limit analysis both ways, two capacity curves on the four-link mechanism's
exact kinematics (a scan of 2,001 points for the critical angle, then 201 points) and a root
search of the PGA capacity per check ("rest": the share of the check beyond its limit
analysis). Target: <= 2 s for a 10-voussoir arch as a whole command
(``archquake check``, a fresh Python process: imports included).

    python benchmarks/site_check.py [--repeat 3]
"""

from __future__ import annotations

import argparse
import math
import subprocess
import sys
import time
from pathlib import Path

SRC = Path(__file__).resolve().parents[1] / "src"
sys.path.insert(0, str(SRC))

from archquake.geometry import arch_on_piers, circular_arch  # noqa: E402
from archquake.limit_analysis import both_directions  # noqa: E402
from archquake.site.local_mechanism import SiteAction, check_local_mechanism  # noqa: E402
from archquake.site.spectra import ntc2018_spectrum  # noqa: E402

EMBRACE = math.radians(157.5)
SITE = ("--code", "ntc2018", "--ag", "0.25", "--f0", "2.4", "--tc-star", "0.3", "--soil", "C")


def _best(function, repeat: int) -> float:
    best = float("inf")
    for _ in range(repeat):
        start = time.perf_counter()
        function()
        best = min(best, time.perf_counter() - start)
    return best


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3, help="runs of each case (best kept)")
    args = parser.parse_args(argv)
    actions = [SiteAction.of(s, ntc2018_spectrum(ag, 2.4, 0.3, "C"))
               for s, ag in (("SLV", 0.25), ("SLC", 0.32))]
    both_directions(circular_arch(10.0, EMBRACE, 1.5, 7))  # compile the kinematic method
    print(f"{'structure':<28} {'limit analysis [s]':>19} {'check [s]':>10} {'rest':>6}")
    cases = [(f"circular, {n} voussoirs", circular_arch(10.0, EMBRACE, 1.5, n))
             for n in (7, 10, 20, 40)]
    cases.append(("on piers 3 x 6 m, 2 courses", arch_on_piers(circular_arch(10.0, EMBRACE, 1.5, 7),
                                                               3.0, 6.0, 2)))
    for name, structure in cases:
        limit_time = _best(lambda s=structure: both_directions(s), args.repeat)
        check_time = _best(lambda s=structure: check_local_mechanism(s, actions),
                           args.repeat)
        print(f"{name:<28} {limit_time:>19.3f} {check_time:>10.3f} "
              f"{1 - limit_time / check_time:>6.0%}")
    command = [sys.executable, "-m", "archquake", "check", *SITE, "--voussoirs", "10"]
    env = {"PYTHONPATH": str(SRC), "PATH": "/usr/bin:/bin"}
    whole = _best(lambda: subprocess.run(command, check=True, capture_output=True, env=env),
                  args.repeat)
    print(f"whole command, 10 voussoirs ({' '.join(command[2:])}): {whole:.2f} s "
          f"(target <= 2 s)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
