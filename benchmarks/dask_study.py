"""A large four-link fragility study on a local Dask cluster whose scheduler and workers are
separate processes (as on a real cluster), beside the serial run of the same study.

Run: ``python benchmarks/dask_study.py`` (100,000 arches: measured on two processors, 1,183 s
on the cluster, 84.5 arches/s or 42.3 per worker, against 2,083 s serially, 48.0 arches/s, a
speed-up of 1.76, the tables equal; about an hour in all), ``--quick``
(10,000 arches) or ``--arches N``. It starts ``dask scheduler`` and ``dask worker ADDRESS
--nworkers 2 --nthreads 1`` as subprocesses, runs
:func:`archquake.studies.fragility.run_fragility` of Oppenheim's arch (epsilon 0.10, seed 1, one
pulse duration and two amplitudes: the cheapest four-link study, four analyses an arch) with
``scheduler=ADDRESS``, then the same study serially, prints the throughput of each (arches/s,
and per Dask worker), and checks that the two tables are equal, value for value. The repeated
runs alternate Dask and serial (``--repeats``) and the ratio is the medians'.
"""

from __future__ import annotations

import argparse
import os
import re
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "src"))

from archquake import oppenheim  # noqa: E402
from archquake.studies.fragility import FragilitySettings, run_fragility  # noqa: E402

WORKERS = 2
"""Dask worker processes (one thread each: the analyses hold the GIL)."""


def dask_command(name: str) -> list[str]:
    """The ``dask`` command of this Python's environment."""
    found = Path(sys.executable).with_name("dask")
    return [str(found) if found.exists() else shutil.which("dask") or "dask", name]


def start_cluster() -> tuple[str, list[subprocess.Popen]]:
    """Start ``dask scheduler`` and ``dask worker`` as subprocesses; return the scheduler's
    address and the processes (the workers are ready when this returns)."""
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(
        [str(ROOT / "src"), os.environ.get("PYTHONPATH", "")])}
    scheduler = subprocess.Popen(
        [*dask_command("scheduler"), "--host", "127.0.0.1", "--port", "0",
         "--dashboard-address", ":0", "--no-show"],
        stderr=subprocess.PIPE, text=True, env=env, start_new_session=True)
    address = None
    t0 = time.time()
    while address is None and time.time() - t0 < 60:
        line = scheduler.stderr.readline()
        match = re.search(r"Scheduler at:\s+(tcp://\S+)", line)
        if match:
            address = match.group(1)
    if address is None:
        scheduler.kill()
        raise SystemExit("the dask scheduler did not start")
    worker = subprocess.Popen(
        [*dask_command("worker"), address, "--nworkers", str(WORKERS), "--nthreads", "1",
         "--no-dashboard"],
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env, start_new_session=True)
    from distributed import Client

    with Client(address, timeout=30, set_as_default=False) as client:
        client.wait_for_workers(WORKERS, timeout=120)
    # keep draining the scheduler's log so that it never blocks on a full pipe
    import threading

    threading.Thread(target=lambda: [None for _ in scheduler.stderr], daemon=True).start()
    return address, [worker, scheduler]


def stop_cluster(processes: list[subprocess.Popen]) -> None:
    """Stop the processes this script started (their own process groups)."""
    for p in processes:
        if p.poll() is None:
            os.killpg(p.pid, signal.SIGTERM)
    for p in processes:
        try:
            p.wait(timeout=20)
        except subprocess.TimeoutExpired:
            os.killpg(p.pid, signal.SIGKILL)


def study(arches: int) -> FragilitySettings:
    """The study: ``arches`` irregular Oppenheim arches under one pulse duration (t_p = 0.5 s)
    at 0.40 g and 0.45 g."""
    return FragilitySettings(nominal=oppenheim(), sample_size=arches, epsilon=0.10,
                             durations=(0.5,), amplitudes_g=(0.40, 0.45), seed=1,
                             limit_sample_size=1)


def timed_run(settings: FragilitySettings, chunk_size: int, **options):
    t0 = time.perf_counter()
    result = run_fragility(settings, progress=False, chunk_size=chunk_size, **options)
    return result, time.perf_counter() - t0


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--arches", type=int, default=100_000)
    parser.add_argument("--quick", action="store_true", help="10,000 arches")
    parser.add_argument("--repeats", type=int, default=1)
    parser.add_argument("--chunk-size", type=int, default=None,
                        help="arches a chunk (default: arches / 40, at least 10)")
    args = parser.parse_args(argv)
    arches = 10_000 if args.quick else args.arches
    chunk = args.chunk_size or max(10, arches // 40)
    settings = study(arches)
    run_fragility(study(4), progress=False, backend="serial")  # compile/load numba here
    address, processes = start_cluster()
    print(f"cluster: scheduler {address}, {WORKERS} worker processes x 1 thread; "
          f"{arches} arches, chunks of {chunk}; load average "
          f"{open('/proc/loadavg').read().split()[0]}")
    try:
        # the workers load the compiled functions (numba's cache) on their first arches
        run_fragility(study(4 * WORKERS), progress=False, chunk_size=1, backend="dask",
                      scheduler=address)
        serial_times, dask_times = [], []
        for _ in range(args.repeats):
            dask_result, t_dask = timed_run(settings, chunk, backend="dask", scheduler=address)
            serial_result, t_serial = timed_run(settings, chunk, backend="serial")
            dask_times.append(t_dask)
            serial_times.append(t_serial)
            import pandas as pd

            pd.testing.assert_frame_equal(dask_result.table, serial_result.table)
            assert np.array_equal(dask_result.probability, serial_result.probability,
                                  equal_nan=True)
    finally:
        stop_cluster(processes)
    ts, td = float(np.median(serial_times)), float(np.median(dask_times))
    print(f"serial          {ts:8.1f} s   {arches / ts:8.1f} arches/s")
    print(f"dask ({WORKERS} workers) {td:8.1f} s   {arches / td:8.1f} arches/s   "
          f"{arches / td / WORKERS:8.1f} arches/s per worker")
    print(f"speed-up dask / serial: {ts / td:.2f} (median of {args.repeats}); results equal "
          f"(table and P_F), analysed {serial_result.analysed} of {arches}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
