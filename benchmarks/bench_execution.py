"""Overhead per chunk of each execution backend, and speed-up of 2 workers over 1.

Run: ``python benchmarks/bench_execution.py`` (a few tens of seconds). Uses the toy tasks of the
test suite (no physics): ``trivial_task`` (one row per item, no work) for the overhead and
``busy_task`` (pure numpy arithmetic) for the speed-up.
"""

import logging
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT / "src"), str(ROOT / "tests")]

from distributed import LocalCluster  # noqa: E402

import toy_tasks  # noqa: E402
from archquake.execution import StudyPlan, run_study  # noqa: E402


def timed(task, plan, checkpoint=False, **options):
    t0 = time.perf_counter()
    if checkpoint:
        with tempfile.TemporaryDirectory() as tmp:
            run_study(task, plan, Path(tmp) / "study", progress=False, **options)
    else:
        run_study(task, plan, progress=False, **options)
    return time.perf_counter() - t0


def overhead(label, n_chunks=400, **options):
    """(T(n chunks) - T(1 chunk)) / (n - 1): the cost per chunk beyond start-up."""
    one = min(timed(toy_tasks.trivial_task, StudyPlan({}, 0, 1, 1), **options) for _ in range(2))
    many = timed(toy_tasks.trivial_task, StudyPlan({}, 0, n_chunks, 1), **options)
    per_chunk = (many - one) / (n_chunks - 1)
    print(f"{label:42s} start-up {one:6.3f} s   per chunk {1e3 * per_chunk:7.3f} ms")


def speedup(label, one, two, work=100_000_000, n_items=8, repeats=3):
    """Wall time with one worker over wall time with two (start-up included).

    Each time is the best of ``repeats`` runs, to filter out other load on the machine.
    """
    plan = StudyPlan({"work": work}, 0, n_items, 1)
    t1 = min(timed(toy_tasks.busy_task, plan, **one) for _ in range(repeats))
    t2 = min(timed(toy_tasks.busy_task, plan, **two) for _ in range(repeats))
    load = open("/proc/loadavg").read().split()[0] if Path("/proc/loadavg").exists() else "?"
    print(f"{label:42s} 1 worker {t1:6.2f} s   2 workers {t2:6.2f} s   speed-up {t1 / t2:4.2f}"
          f"   (load average {load})")


if __name__ == "__main__":
    print("overhead per chunk, trivial task (chunk_size=1, 400 chunks)")
    overhead("serial", backend="serial")
    overhead("serial + checkpoints", backend="serial", checkpoint=True)
    overhead("processes(2)", backend="processes", workers=2)
    overhead("processes(2) + checkpoints", backend="processes", workers=2, checkpoint=True)
    opts = dict(host="127.0.0.1", dashboard_address=":0", silence_logs=logging.ERROR,
                threads_per_worker=1)
    with LocalCluster(n_workers=2, processes=True, **opts) as cluster:
        overhead("dask LocalCluster(2 processes)", scheduler=cluster.scheduler_address)
        overhead("dask LocalCluster(2 processes) + checkpoints",
                 scheduler=cluster.scheduler_address, checkpoint=True)
    serial_chunk = timed(toy_tasks.busy_task, StudyPlan({"work": 100_000_000}, 0, 1, 1),
                         backend="serial")
    print(f"\nspeed-up, CPU-bound task (8 chunks of ~{serial_chunk:.2f} s each)")
    speedup("processes", dict(backend="processes", workers=1),
            dict(backend="processes", workers=2))
    with LocalCluster(n_workers=1, processes=True, **opts) as c1, \
            LocalCluster(n_workers=2, processes=True, **opts) as c2:
        speedup("dask LocalCluster", dict(scheduler=c1.scheduler_address),
                dict(scheduler=c2.scheduler_address))
    speedup("serial vs processes(2)", dict(backend="serial"),
            dict(backend="processes", workers=2))
