"""The paper's fragility study with the rigid-block model: the ``screened`` search (the default)
against the exhaustive grid, side by side on the same arches, and P_F compared at every
amplitude; and what an analysis costs by its outcome, which bounds what screening can save.

    python benchmarks/rigid_block_fragility.py [--arches 40] [--exhaustive-arches 10]
                                               [--workers 2] [--skip-full] [--time-step H]
                                               [--coarse-factor K]

The paper's study [Sect. 5.3.3]: h = 40 irregular arches (epsilon = 0.10), t_p = 0.4, 0.5, 0.6,
0.7 s, 0.20-0.80 g in 0.01 g steps, both directions: 19,520 grid points. Printed:

1. the full study with the default strategy (the target: <= 30 s on 2 cores), wall and CPU
   time, the analyses it ran and the share of the grid they are;
2. on the first ``--exhaustive-arches`` arches (the same seeds, so the same arches),
   ``screened`` and the exhaustive grid one after the other: their wall times, the ratio, and
   whether the statuses and P_F agree at every amplitude (an exit status of 1 if they do not);
   and the time of one analysis by outcome (rest, collapse during the pulse, which ``screened``
   infers between two analysed points, and recovery, collapse after the pulse, which it must
   analyse), over the paper's grid of the first ``--cost-arches`` arches (4), in this
   process, and the bound that sets on any search whose outcomes equal the exhaustive grid's:
   it must analyse every recovery and collapse after the pulse, so it is at most
   ``1 / (their share of the time)`` times faster, whatever it infers;
3. the four-link study of the same 40 arches, for scale;

and the grid points the rigid blocks left undecided (an exit status of 1 if any).

Every run is warm (a study on a warm pool of workers first) and uses the same pool.
"""

from __future__ import annotations

import argparse
import itertools
import resource
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))

from archquake.defaults import DEFAULT_COARSE_FACTOR  # noqa: E402
from archquake.execution import process_pool  # noqa: E402
from archquake.models import ModelSpec  # noqa: E402
from archquake.rigid_blocks.model import warm_up  # noqa: E402
from archquake.studies.failure_domain import inclusive_range  # noqa: E402
from archquake.studies.fragility import FragilitySettings, run_fragility  # noqa: E402

PAPER = {"durations": (0.4, 0.5, 0.6, 0.7),
         "amplitudes_g": tuple(inclusive_range(0.2, 0.8, 0.01).tolist()),
         "epsilon": 0.10, "seed": 0, "limit_sample_size": 1000}


def _cpu_seconds() -> float:
    own, children = (resource.getrusage(w) for w in (resource.RUSAGE_SELF,
                                                    resource.RUSAGE_CHILDREN))
    return own.ru_utime + own.ru_stime + children.ru_utime + children.ru_stime


def _study(settings, pool):
    """(result, wall seconds); the workers' CPU is not visible to this process while the pool
    lives, so the analyses are counted instead."""
    start = time.perf_counter()
    result = run_fragility(settings, pool=pool, progress=False)
    return result, time.perf_counter() - start


def _undecided(result) -> int:
    """Grid points the rigid blocks left undecided (status -1): none, since the contact problem
    of every step is solved (archquake.rigid_blocks.lemke)."""
    return int((result.table["status"] == -1).sum())


def _analysed(result) -> tuple[int, int]:
    table = result.table
    return int(table["analysed"].sum()), len(table)


def _cost_by_outcome(blocks, arches: int) -> None:
    """Time of one analysis by outcome class over the paper's grid of the first ``arches``
    arches (this process), and the bound it sets on any search equal to the exhaustive grid."""
    from archquake.studies.strategies import excitation_end

    settings = FragilitySettings(**PAPER, sample_size=arches, model=blocks)
    cost: dict[str, list] = {}
    models = [settings.sample.member(item, settings.model).model for item in range(arches)]
    for model, tp in itertools.product(models, settings.durations):
        end = excitation_end("oppenheim", tp)
        for sign in (-1.0, 1.0):
            for a in settings.amplitudes_g:
                t0 = time.perf_counter()
                out = model.outcomes(tp, np.array([sign * a]))
                dt = time.perf_counter() - t0
                status = int(out["status"][0])
                name = {0: "rest (inferred)", 1: "recovery", -1: "undecided"}.get(status) or (
                    "collapse in pulse (inferred)" if out["collapse_time"][0] <= end
                    else "collapse after pulse")
                cost.setdefault(name, []).append(dt)
    total = sum(sum(v) for v in cost.values())
    print(f"\nOne analysis by outcome, the paper's grid of the first {arches} arches "
          f"({sum(map(len, cost.values()))} analyses, {total:.1f} s in this process):")
    for name, times in sorted(cost.items()):
        print(f"  {name:<30} {len(times):4d} analyses, {np.mean(times) * 1e3:5.2f} ms each, "
              f"{sum(times) / total:4.0%} of the time")
    # a search equal to the exhaustive grid analyses every recovery and collapse after the
    # pulse (the isolated outcomes narrower than a grid step lie among them,
    # studies.strategies): even with every other outcome inferred for nothing, it saves at
    # most the time of those others
    inferable = sum(sum(v) for k, v in cost.items() if k.endswith("(inferred)"))
    print(f"  bound on any search equal to the exhaustive grid: at most "
          f"{total / (total - inferable):.2f}x faster than it (every rest and collapse in the "
          f"pulse inferred at no cost; the other {1 - inferable / total:.0%} of the time "
          f"analysed)")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--arches", type=int, default=40, help="h of the full study (40)")
    parser.add_argument("--exhaustive-arches", type=int, default=10,
                        help="arches of the side-by-side comparison with the exhaustive grid")
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--cost-arches", type=int, default=4,
                        help="arches over which an analysis is timed by its outcome (4)")
    parser.add_argument("--skip-full", action="store_true", help="only the side-by-side part")
    parser.add_argument("--time-step", type=float, default=None,
                        help="the rigid-block model's time step [s] (default: that of the "
                             "nominal arch, 1 ms for Oppenheim's; "
                             "benchmarks/rigid_block_time_step.py shows what it changes)")
    parser.add_argument("--coarse-factor", type=int, default=None,
                        help="steps of the time step taken as one while no contact changes "
                             "(BlockSettings.coarse_factor; default 2; 1: every step at the "
                             "time step, twice the time)")
    args = parser.parse_args(argv)
    blocks = ModelSpec("rigid-blocks", time_step=args.time_step,
                       coarse_factor=(DEFAULT_COARSE_FACTOR if args.coarse_factor is None
                                      else args.coarse_factor))

    status = 0
    with process_pool(args.workers, warm_up=warm_up) as pool:
        tiny = FragilitySettings(**{**PAPER, "durations": (0.4,), "amplitudes_g": (0.3, 0.6),
                                    "limit_sample_size": 2}, sample_size=2, model=blocks)
        _study(tiny, pool)  # every worker compiled and warm

        if not args.skip_full:
            settings = FragilitySettings(**PAPER, sample_size=args.arches, model=blocks)
            result, wall = _study(settings, pool)
            done, grid = _analysed(result)
            print(f"Full study, rigid blocks (h = {settings.model.time_step * 1e3:g} ms, coarse "
                  f"factor {settings.model.coarse_factor}), search {settings.search!r} (stride "
                  f"{settings.stride}): {args.arches} arches x {len(PAPER['durations'])} "
                  f"durations x {len(PAPER['amplitudes_g'])} amplitudes x 2 directions = "
                  f"{grid} grid points")
            print(f"  {wall:.1f} s wall on {args.workers} workers (target <= 30 s); "
                  f"{done} analyses ({done / grid:.0%} of the grid), "
                  f"{wall * args.workers / max(done, 1) * 1e3:.1f} ms of worker time each")
            print(f"  P_F at t_p = 0.4 s: {np.round(result.probability[0, ::6], 3).tolist()}")
            print(f"  undecided grid points: {_undecided(result)}")
            status = 1 if _undecided(result) else status

        n = args.exhaustive_arches
        default = FragilitySettings(**PAPER, sample_size=n, model=blocks, search="screened")
        exhaustive = FragilitySettings(**PAPER, sample_size=n, model=blocks,
                                       search="exhaustive")
        fast, fast_wall = _study(default, pool)
        full, full_wall = _study(exhaustive, pool)
        fast_done, grid = _analysed(fast)
        print(f"\nSide by side on the first {n} arches ({grid} grid points):")
        print(f"  {default.search:>10}: {fast_wall:6.1f} s wall, {fast_done} analyses")
        print(f"  {'exhaustive':>10}: {full_wall:6.1f} s wall, {grid} analyses")
        print(f"  ratio exhaustive / {default.search}: {full_wall / fast_wall:.2f} (wall), "
              f"{grid / fast_done:.2f} (analyses)")
        same_status = np.array_equal(fast.table["status"], full.table["status"])
        same_pf = np.array_equal(fast.probability, full.probability)
        print(f"  statuses equal at every grid point: {same_status}; P_F equal at every "
              f"amplitude: {same_pf}; undecided grid points: {_undecided(fast)} and "
              f"{_undecided(full)}")
        status = 1 if _undecided(fast) + _undecided(full) else status
        quick = FragilitySettings(**PAPER, sample_size=n, model=blocks,
                                  search="bisection")
        rough, rough_wall = _study(quick, pool)
        rough_done, _ = _analysed(rough)
        wrong = int((rough.table["status"] != full.table["status"]).sum())
        print(f"  {'bisection':>10}: {rough_wall:6.1f} s wall, {rough_done} analyses, "
              f"{full_wall / rough_wall:.2f}x faster than exhaustive; {wrong} grid points "
              f"differ, largest |P_F difference| "
              f"{np.abs(rough.probability - full.probability).max():.3f} (isolated outcomes "
              f"narrower than the stride, studies.strategies)")
        if not (same_status and same_pf):
            wrong = int((fast.table["status"] != full.table["status"]).sum())
            print(f"  DIFFERENT: {wrong} grid points; largest |P_F difference| "
                  f"{np.abs(fast.probability - full.probability).max():.3f}")
            status = 1

        _cost_by_outcome(blocks, args.cost_arches)
        four_link = FragilitySettings(**PAPER, sample_size=args.arches)
        _, fl_wall = _study(four_link, pool)
        print(f"\nThe four-link study of the same {args.arches} arches: {fl_wall:.1f} s wall "
              f"(limit sample of {PAPER['limit_sample_size']} arches included)")
    print(f"\nCPU time of this process and its workers: {_cpu_seconds():.0f} s")
    return status


if __name__ == "__main__":
    raise SystemExit(main())
