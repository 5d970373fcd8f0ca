"""The fragility study of irregular bridges (``archquake fragility --model rigid-blocks
--spans N``): in one process, as the study ran when its cost was estimated as an arch's, against
the workers it now takes, interleaved, with equal tables checked.

    python benchmarks/bridge_fragility.py [--samples 8] [--repeats 1] [--workers 2]

The study: three spans of Oppenheim's arch on piers 3.2 m wide and 6 m high, ``--samples``
irregular bridges (epsilon 0.1, seed 0), Oppenheim's pulse of 0.5 s at 0.10-0.40 g in 0.01 g
steps, a limit sample of 200 bridges; the default (screened) search. It prints the study's
estimate of its own serial cost (``_serial_seconds``: by the blocks of the bridge, a step of
the rigid blocks costing time linear in them), whether that estimate gives it workers, and the
wall time of each way with their ratio.

Measured as the command (``archquake fragility``, 20 bridges, 2 shared cores): 81 s in one
process, 53 s on two workers, the same table. The estimate is a lower bound, 27 s for the 20
bridges (their serial cost is about 80 s), but above what a pool of fresh workers costs; an
arch's estimate of the same grid, 5.4 s, ran the bridges in one process.
This script, ``--samples 8``: one process 49.1 s, 2 workers 27.2 s, ratio 0.55, tables equal
(estimate 18.5 s, an arch study's 2.4 s).
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))

import numpy as np  # noqa: E402

from archquake.geometry.spec import StructureSpec  # noqa: E402
from archquake.studies.fragility import (  # noqa: E402
    FragilitySettings,
    _serial_seconds,
    run_fragility,
)
from archquake.studies.strategies import workers_that_pay  # noqa: E402


def settings(samples: int) -> FragilitySettings:
    """The benchmark's study."""
    return FragilitySettings(description=StructureSpec(spans=3, piers="3.2,6"),
                             model="rigid-blocks", sample_size=samples, durations=(0.5,),
                             amplitudes_g=tuple(np.round(np.arange(0.10, 0.401, 0.01), 2)),
                             limit_sample_size=200)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--samples", type=int, default=8)
    parser.add_argument("--repeats", type=int, default=1)
    parser.add_argument("--workers", type=int, default=2)
    args = parser.parse_args(argv)
    study = settings(args.samples)
    arch = FragilitySettings(model="rigid-blocks", sample_size=args.samples, durations=(0.5,),
                             amplitudes_g=study.amplitudes_g, limit_sample_size=200)
    estimate = _serial_seconds(study)
    print(f"{args.samples} bridges of {study.nominal.n_blocks} blocks x "
          f"{len(study.amplitudes_g)} amplitudes x 2 directions; estimated serial cost "
          f"{estimate:.1f} s (an arch study of the same grid: {_serial_seconds(arch):.1f} s); "
          f"workers given: {workers_that_pay(estimate, args.workers)}")
    run_fragility(settings(1), backend="serial", progress=False)  # compiled code loaded
    times = {"one process": [], "workers": []}
    tables = {}
    for _ in range(args.repeats):  # interleaved
        for name, options in (("one process", {"backend": "serial"}),
                              ("workers", {"workers": args.workers})):
            start = time.perf_counter()
            result = run_fragility(study, progress=False, **options)
            times[name].append(time.perf_counter() - start)
            tables[name] = result.table
    columns = ["arch", "direction", "duration", "amplitude_g", "status", "analysed"]
    same = tables["one process"][columns].equals(tables["workers"][columns])
    t = {name: statistics.median(v) for name, v in times.items()}
    print(f"one process {t['one process']:.1f} s, {args.workers} workers {t['workers']:.1f} s; "
          f"ratio {t['workers'] / t['one process']:.2f}; tables equal: {same}")
    return 0 if same else 1


if __name__ == "__main__":
    raise SystemExit(main())
