"""Time a multiple-stripe study: 40 irregular arches x 20 records x 20 PGA levels x 2
polarities (32,000 analyses of 20-s records at 0.01 s), plus the nominal arch.

    python benchmarks/record_fragility.py [--arches 40] [--records 20] [--levels 20]
                                          [--workers 2] [--no-breakdown]

The records are synthetic (Rezaeian & Der Kiureghian, 1.5 Hz at mid-record, D5-95 = 10 s), so no
files are needed. Printed: where the time of one arch goes (building its dynamics; analyses at
rest without integration; integrated analyses, split into the time the arch spends at rest
waiting for the ground to activate it and the time it moves), the wall time of the whole study
on a warm pool of worker processes, its size-scaling (the same study with half the arches), the
peak memory of this process and of the workers, and the target: <= 60 s wall on 2 cores, < 1 GB.
JIT compilation is excluded (the compiled engine is cached on disk and warmed up first).
"""

from __future__ import annotations

import argparse
import os
import resource
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))

from archquake import (
    GRAVITY,  # noqa: E402
    FourLinkModel,  # noqa: E402
)
from archquake.execution import process_pool  # noqa: E402
from archquake.fourlink.engine import outcomes_grid  # noqa: E402
from archquake.fourlink.time_history import simulate  # noqa: E402
from archquake.geometry import irregular_sample  # noqa: E402
from archquake.ground_motion import RecordSuite, scale_factors  # noqa: E402
from archquake.studies.record_fragility import (  # noqa: E402
    STOCHASTIC_SUITE,
    RecordFragilitySettings,
    record_outcomes,
    run_record_fragility,
    warm_up,
)

SUITE = STOCHASTIC_SUITE


def settings_of(arches: int, records: int, levels: int) -> RecordFragilitySettings:
    suite = RecordSuite.from_stochastic(records, seed=0, **SUITE)
    grid = tuple(np.round(0.1 * np.arange(1, levels + 1), 10))  # 0.1 .. 2.0 g
    return RecordFragilitySettings(suite=suite, levels=grid, im="pga", sample_size=arches)


def breakdown(settings: RecordFragilitySettings, n_arches: int = 3) -> None:
    """Where the time of an arch goes, in this process."""
    motions = settings.suite.motions()
    im = np.array([m.peak / GRAVITY for m in motions])
    factors = scale_factors(im, settings.levels, 1.0)
    arches = irregular_sample(settings.nominal, settings.epsilon, n_arches, settings.seed)
    t_build = t_all = 0.0
    n_total = n_run = 0
    per_level = np.zeros(len(settings.levels))
    rest_seconds = moving_seconds = 0.0
    samples = motions[0].times.size
    for arch in arches:
        t0 = time.perf_counter()
        dynamics = FourLinkModel.from_arch(arch, settings.restitution, settings.nominal)
        t_build += time.perf_counter() - t0
        for r, motion in enumerate(motions):
            signed = (factors[r][:, None] * np.array([1.0, -1.0])).ravel()
            t0 = time.perf_counter()
            out = record_outcomes(dynamics, motion, signed)
            t_all += time.perf_counter() - t0
            n_total += signed.size
            n_run += int(out["integrated"].sum())
            for j in range(len(settings.levels)):  # per-level cost, one analysis at a time
                t0 = time.perf_counter()
                outcomes_grid(*dynamics.tables, *dynamics.restitution, np.ones(2),
                              signed[2 * j:2 * j + 2], motion)
                per_level[j] += time.perf_counter() - t0
    # the cost of one sample at rest: a record just below activation, integrated anyway
    dynamics = FourLinkModel.from_arch(settings.nominal, settings.restitution, settings.nominal)
    motion = motions[0]
    quiet = 0.999 * dynamics.tables[1].activation_g * GRAVITY / np.max(np.abs(motion.values))
    outcomes_grid(*dynamics.tables, *dynamics.restitution, [1.0], [quiet], motion)
    t0 = time.perf_counter()
    for _ in range(50):
        outcomes_grid(*dynamics.tables, *dynamics.restitution, [1.0], [quiet], motion)
    per_rest_sample = (time.perf_counter() - t0) / 50 / samples
    # how long the arch rests and moves during integrated analyses (recorded histories)
    count = 0
    for r, motion in enumerate(motions[:5]):
        for j in range(4, len(settings.levels), 3):
            f = factors[r][j]
            h = simulate(dynamics.tables, motion.scaled(f), dynamics.restitution, t_end=20.0)
            for s in h.segments:
                span = min(s.t[-1], 20.0) - min(s.t[0], 20.0)
                if s.mechanism == "rest":
                    rest_seconds += span
                else:
                    moving_seconds += span
            count += 1
    rest_share = rest_seconds / (rest_seconds + moving_seconds)
    per_analysis = t_all / n_total
    print(f"one arch: {len(motions)} records x {len(settings.levels)} levels x 2 polarities = "
          f"{n_total // n_arches} analyses of {motions[0].duration:g}-s records "
          f"({samples} samples)")
    print(f"  arch dynamics (limit analysis, mechanisms, restitution, tables): "
          f"{1e3 * t_build / n_arches:.1f} ms per arch")
    print(f"  analyses: {per_analysis * 1e3:.2f} ms each on average; "
          f"{n_total - n_run} of {n_total} at rest without integration "
          f"({100 * (n_total - n_run) / n_total:.0f} %), the rest "
          f"{t_all / max(n_run, 1) * 1e3:.2f} ms each")
    costs = ", ".join(f"{x:g}: {1e3 * c / (2 * len(motions) * n_arches):.1f}"
                      for x, c in zip(settings.levels, per_level, strict=True))
    print(f"  ms per analysis by level [g] -> {costs}")
    print(f"  at rest, the engine scans the record for the activation instant at "
          f"{per_rest_sample * 1e9:.0f} ns per sample ({per_rest_sample * samples * 1e3:.2f} ms "
          f"for a whole {motions[0].duration:g}-s record)")
    print(f"  in {count} integrated analyses of the nominal arch (levels 0.5-2.0 g) the arch "
          f"rests {100 * rest_share:.0f} % of the record's time and moves "
          f"{100 * (1 - rest_share):.0f} %: about "
          f"{rest_share * per_rest_sample * samples * 1e3:.2f} ms of an analysis waiting at rest, "
          f"the rest of it moving (DOP853 steps, one at least per sample)")


class MemorySampler:
    """Peak memory of this process and its children, sampled every 0.2 s from /proc (Linux):
    the sum of their resident sets (RSS, which counts a shared library once per process) and
    of their proportional sets (PSS, which shares it out: the physical memory they use)."""

    def __init__(self):
        import threading

        self.peak_rss = self.peak_pss = 0.0
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)

    def _pids(self):
        me = os.getpid()
        pids = [me]
        for entry in Path("/proc").iterdir():
            if entry.name.isdigit():
                try:
                    stat = (entry / "stat").read_text()
                except OSError:
                    continue
                if int(stat.rsplit(")", 1)[1].split()[1]) == me:
                    pids.append(int(entry.name))
        return pids

    def _run(self):
        while not self._stop.is_set():
            rss = pss = 0.0
            for pid in self._pids():
                try:
                    text = Path(f"/proc/{pid}/smaps_rollup").read_text()
                except OSError:
                    continue
                fields = dict(line.split(":", 1) for line in text.splitlines()[1:])
                rss += int(fields["Rss"].split()[0]) / 1024
                pss += int(fields["Pss"].split()[0]) / 1024
            self.peak_rss, self.peak_pss = max(self.peak_rss, rss), max(self.peak_pss, pss)
            self._stop.wait(0.2)

    def __enter__(self):
        self._thread.start()
        return self

    def __exit__(self, *exc):
        self._stop.set()
        self._thread.join()


def _children_cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def timed_study(settings: RecordFragilitySettings, workers: int):
    """``(wall seconds of the study, CPU seconds of its workers, result)`` on a fresh pool of
    warm workers (started, and the engine loaded, before the clock starts)."""
    before = _children_cpu()
    with process_pool(workers, warm_up=warm_up) as pool:
        list(pool.map(time.sleep, [0.5] * workers))  # start (and warm) every worker
        t0 = time.perf_counter()
        result = run_record_fragility(settings, pool=pool, progress=False, backend="processes")
        wall = time.perf_counter() - t0
    return wall, _children_cpu() - before, result


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--arches", type=int, default=40)
    parser.add_argument("--records", type=int, default=20)
    parser.add_argument("--levels", type=int, default=20)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--no-breakdown", action="store_true")
    args = parser.parse_args(argv)
    settings = settings_of(args.arches, args.records, args.levels)
    warm_up()
    if not args.no_breakdown:
        breakdown(settings)
    load = os.getloadavg()[0]
    before = _children_cpu()
    with process_pool(args.workers, warm_up=warm_up) as pool:
        list(pool.map(time.sleep, [0.5] * args.workers))
    start_cpu = (_children_cpu() - before) / args.workers
    half = settings_of(max(1, args.arches // 2), args.records, args.levels)
    t_half, cpu_half, _ = timed_study(half, args.workers)
    with MemorySampler() as memory:
        t_full, cpu_full, result = timed_study(settings, args.workers)
    analyses = (args.arches + 1) * args.records * args.levels * 2
    summary = result.summary()
    print(f"study: ({args.arches} irregular + 1 nominal) arches x {args.records} records x "
          f"{args.levels} levels x 2 polarities = {analyses} analyses "
          f"({summary['analyses']['at_rest_without_integration']} at rest without integration)")
    print(f"  machine load before the studies (1-min load average): {load:.2f} on "
          f"{os.cpu_count()} CPUs")
    study_cpu = cpu_full - args.workers * start_cpu
    print(f"  wall time on {args.workers} warm worker processes: {t_full:6.1f} s; the workers' "
          f"CPU time {study_cpu:.1f} s ({1e3 * study_cpu / analyses:.2f} ms per analysis; "
          f"start-up and warm-up of {start_cpu:.1f} s per worker left out), i.e. "
          f"{study_cpu / args.workers:.1f} s wall on {args.workers} idle cores; target <= 60 s "
          f"for 40 x 20 x 20 x 2")
    print(f"  half the arches ({half.sample_size}): {t_half:6.1f} s wall, "
          f"{cpu_half - args.workers * start_cpu:.1f} s CPU -> full / half = "
          f"{t_full / t_half:.2f} wall, {study_cpu / (cpu_half - args.workers * start_cpu):.2f} "
          f"CPU (linear: {(args.arches + 1) / (half.sample_size + 1):.2f})")
    own = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    children = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
    print(f"  peak memory of the study, this process and its {args.workers} workers together: "
          f"{memory.peak_pss:.0f} MB proportional (PSS: physical memory), "
          f"{memory.peak_rss:.0f} MB resident (RSS: shared libraries counted in each process); "
          f"largest RSS of one process {max(own, children):.0f} MB (target < 1024 MB)")
    fit = result.lognormal
    print(f"  result: P(collapse | pga) from {result.probability.min():.2f} to "
          f"{result.probability.max():.2f}; lognormal median {fit.median:.3f} g, "
          f"beta {fit.dispersion:.3f}")


if __name__ == "__main__":
    main()
