"""Time the paper's fragility study [Sect. 5.3.3]: h = 40 arches, t_p in {0.4, 0.5, 0.6, 0.7} s,
0.20-1.00 g in 0.01 g steps, both directions (25,920 analyses), plus s = 1000 limit analyses.

    python benchmarks/fragility_study.py [--large 400] [--no-large] [--seed 0]

Prints where the time goes (limit analysis, tables, integration; steps per analysis), the wall
time with 1 worker (in this process), with warm pools of 1 and of 2 local worker processes
(measured side by side: the 2-worker speed-up), with 2 fresh local processes (start-up included)
and with a warm Dask LocalCluster of 2 single-threaded worker processes, the concurrency of
the machine itself (the same compiled work in 1 and in 2 simultaneous processes), peak memory, and
the cost of 10x more arches. JIT compilation is excluded: everything is warmed up first (the
compiled functions are cached on disk, cache=True).
"""

from __future__ import annotations

import argparse
import multiprocessing
import os
import resource
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))

from archquake import FourLinkModel, oppenheim  # noqa: E402
from archquake.execution import process_pool  # noqa: E402
from archquake.fourlink import engine  # noqa: E402
from archquake.fourlink.engine.driver import integrate  # noqa: E402
from archquake.fourlink.mechanism import mechanisms  # noqa: E402
from archquake.geometry import GRAVITY, irregular_sample  # noqa: E402
from archquake.ground_motion import oppenheim_pulse  # noqa: E402
from archquake.limit_analysis import both_directions, limit_sample  # noqa: E402
from archquake.studies.failure_domain import inclusive_range  # noqa: E402
from archquake.studies.fragility import FragilitySettings, run_fragility, warm_up  # noqa: E402


def _grid_seconds(repeat: int = 3) -> float:
    """Seconds of one arch's full grid (both directions) with the compiled engine, best of
    ``repeat``."""
    arch = irregular_sample(oppenheim(), 0.1, 1, 0)[0]
    dynamics = FourLinkModel.from_arch(arch, 0.645)
    (tl, tr), (c_lr, c_rl) = dynamics.tables, dynamics.restitution
    d, a = np.meshgrid([0.4, 0.5, 0.6, 0.7], inclusive_range(0.2, 1.0, 0.01), indexing="ij")
    best = np.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        for sign in (-1.0, 1.0):
            engine.outcomes_grid(tl, tr, c_lr, c_rl, d, sign * GRAVITY * a)
        best = min(best, time.perf_counter() - t0)
    return best


def _concurrency_worker(repeat: int) -> float:
    """Seconds of ``repeat`` grids of one arch, run back to back (about half a second)."""
    _grid_seconds(1)  # warm
    t0 = time.perf_counter()
    for _ in range(repeat):
        _grid_seconds(1)
    return time.perf_counter() - t0


def breakdown(settings: FragilitySettings) -> None:
    """Where the time of the dynamic study goes, per arch, in this process: the stages of
    :meth:`FourLinkModel.from_arch`, timed one by one, then the compiled grid."""
    arches = irregular_sample(settings.nominal, settings.epsilon, 10, settings.seed)
    nominal_pair = mechanisms(settings.nominal)
    times = {"limit analysis (hinges, k)": 0.0, "mechanisms + restitution": 0.0,
             "tables (polynomial pieces)": 0.0, "integration (2 x outcomes_grid)": 0.0}
    d, a = np.meshgrid(settings.durations, settings.amplitudes_g, indexing="ij")
    for arch in arches:
        t0 = time.perf_counter()
        limit = both_directions(arch)
        t1 = time.perf_counter()
        pair = mechanisms(arch, limit=limit)
        from archquake.fourlink.impact import restitution

        c = restitution("nominal", *pair, nominal=nominal_pair)
        t2 = time.perf_counter()
        tables = [engine.tabulate(m) for m in pair]
        t3 = time.perf_counter()
        for sign in (-1.0, 1.0):
            engine.outcomes_grid(*tables, *c, d, sign * GRAVITY * a)
        t4 = time.perf_counter()
        for key, dt in zip(times, (t1 - t0, t2 - t1, t3 - t2, t4 - t3), strict=True):
            times[key] += dt
    n = len(arches)
    print(f"per arch (mean of {n}):")
    total = sum(times.values())
    for key, value in times.items():
        print(f"  {key:<34} {1e3 * value / n:7.1f} ms  ({100 * value / total:4.1f} %)")
    analyses = 2 * d.size
    print(f"  => {1e6 * times['integration (2 x outcomes_grid)'] / (n * analyses):.0f} us per "
          f"analysis ({analyses} analyses per arch)")
    # steps per analysis and the instant the outcome is decided (no integration after it)
    dynamics = FourLinkModel.from_arch(arches[0], "nominal", settings.nominal)
    (tl, tr), (c_lr, c_rl) = dynamics.tables, dynamics.restitution
    tab = engine.pack_pair(tl, tr)
    steps, after = [], []
    for tp in settings.durations:
        for amp in settings.amplitudes_g[::5]:
            motion = engine.compiled_motion(oppenheim_pulse(-amp * GRAVITY, tp))
            out, *_ = integrate(tab, c_lr, c_rl, *motion, 0.0, np.inf, engine.REST_STATE, 0.0, 0.0,
                           engine.DEFAULT_RTOL, engine.DEFAULT_ATOL,
                           engine.DEFAULT_REST_VELOCITY, engine.DEFAULT_MAX_STEP,
                           engine.DEFAULT_MAX_STEPS, False, 1.0, 0.0)
            steps.append(out[engine.OUT_STEPS])
            after.append(out[engine.OUT_DECISION_TIME] - 3.0 * tp)
    steps = np.array(steps)
    print(f"  steps per analysis: median {np.median(steps):.0f}, max {steps.max():.0f}; outcome "
          f"decided at the end of the pulse (3 t_p) in {np.mean(np.abs(after) < 1e-12):.0%} of "
          f"the cases, at most {max(after):.3f} s after it (energy test, eq. 3)")
    t0 = time.perf_counter()
    limit_sample(settings.nominal, settings.epsilon, 200, settings.seed, "kinematic")
    t_kin = (time.perf_counter() - t0) / 200
    t0 = time.perf_counter()
    limit_sample(settings.nominal, settings.epsilon, 200, settings.seed, "static")
    t_sta = (time.perf_counter() - t0) / 200
    print(f"limit sample: {1e3 * t_kin:.1f} ms per arch (kinematic, used), {1e3 * t_sta:.1f} ms "
          f"(static LP) -> s = {settings.limit_sample_size}: "
          f"{t_kin * settings.limit_sample_size:.1f} s")


def timed(settings, label, **run):
    t0 = time.perf_counter()
    result = run_fragility(settings, progress=False, **run)
    wall = time.perf_counter() - t0
    task = result.metadata["timings"]["task_seconds"]
    print(f"{label:<44} {wall:7.2f} s wall   (dynamic study: {task:6.2f} s inside the task)")
    return wall, result


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--large", type=int, default=400, help="h of the scaling run")
    parser.add_argument("--no-large", action="store_true", help="skip the scaling run")
    args = parser.parse_args(argv)

    settings = FragilitySettings(seed=args.seed)
    print(f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} CPUs (other work on the "
          "machine slows the parallel runs)")
    n = settings.sample_size * 2 * len(settings.durations) * len(settings.amplitudes_g)
    print(f"paper's study: h = {settings.sample_size}, t_p = {settings.durations}, "
          f"{len(settings.amplitudes_g)} amplitudes, 2 directions = {n} analyses; "
          f"s = {settings.limit_sample_size} limit analyses; restitution {settings.restitution!r}")
    warm_up()  # JIT caches, imports
    breakdown(settings)

    print("\nmachine: the same compiled work (one arch's grid) alone and in 2 simultaneous "
          "processes")
    repeat = 25
    alone = _concurrency_worker(repeat)
    with multiprocessing.get_context("spawn").Pool(2) as pool:
        pool.map(_concurrency_worker, [1, 1], chunksize=1)  # start and warm both workers
        both = pool.map(_concurrency_worker, [repeat, repeat], chunksize=1)
    ideal = 2 * alone / max(both)
    print(f"  {repeat} grids: alone {alone:.2f} s, 2 processes at once {both[0]:.2f} / "
          f"{both[1]:.2f} s -> the best 2-worker speed-up this machine gives now is about "
          f"{ideal:.2f}x (load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} CPUs)")

    print()
    serial, result = timed(settings, "1 worker (this process)", backend="serial")
    pooled = {}
    for n_workers in (1, 2):
        with process_pool(n_workers, warm_up=warm_up) as pool:
            list(pool.map(time.sleep, [0.5] * n_workers))  # start (and warm) every worker
            best = np.inf
            for _ in range(2):
                wall, pool_result = timed(settings, f"{n_workers} warm local process(es)",
                                          pool=pool)
                best = min(best, wall)
                assert pool_result.table.equals(result.table)
            pooled[n_workers] = best
    cold, _ = timed(settings, "2 workers, fresh local processes", backend="processes",
                    workers=2)
    from distributed import Client, LocalCluster

    # one thread per worker for numba and BLAS too, as the local process pool does
    single = {name: "1" for name in ("NUMBA_NUM_THREADS", "OMP_NUM_THREADS",
                                      "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")}
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, env=single,
                      dashboard_address=None) as cluster, Client(cluster) as client:
        client.run(warm_up)  # on every worker
        warm, warm_result = timed(settings, "2 workers, warm Dask LocalCluster",
                                  backend="dask", scheduler=client)
    assert warm_result.table.equals(result.table)
    print(f"2-worker speed-up: {pooled[1] / pooled[2]:.2f}x (2 vs 1 warm local processes, best "
          f"of 2 each), {serial / pooled[2]:.2f}x against this process, {serial / warm:.2f}x "
          f"on warm Dask workers, {serial / cold:.2f}x including the start of the processes")
    self_kb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    children_kb = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    print(f"peak memory (max RSS): this process {self_kb / 1024:.0f} MiB, largest child "
          f"{children_kb / 1024:.0f} MiB")
    q = result.nominal_failure_acceleration_g
    print(f"nominal failure acceleration Q [g]: {np.round(q, 4).tolist()}; P_F just below Q: "
          f"{result.probability_below_nominal().tolist()}")

    if not args.no_large:
        large = FragilitySettings(sample_size=args.large, seed=args.seed)
        wall, big = timed(large, f"h = {args.large}, 1 worker (this process)", backend="serial")
        per_small = result.metadata["timings"]["task_seconds"] / settings.sample_size
        per_large = big.metadata["timings"]["task_seconds"] / large.sample_size
        print(f"dynamic study per arch: {1e3 * per_small:.1f} ms (h = {settings.sample_size}), "
              f"{1e3 * per_large:.1f} ms (h = {large.sample_size}): cost linear in h "
              f"(ratio {per_large / per_small:.2f})")
        with process_pool(2, warm_up=warm_up) as pool:
            list(pool.map(time.sleep, [0.5, 0.5]))
            wall2, big2 = timed(large, f"h = {args.large}, 2 warm local processes", pool=pool)
        assert big2.table.equals(big.table)
        print(f"2-worker speed-up at h = {args.large}: {wall / wall2:.2f}x")
    return 0


if __name__ == "__main__":
    sys.exit(main())
