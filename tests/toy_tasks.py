"""Toy study tasks for the execution tests and benchmarks (no physics).

Module-level functions, so that they pickle by reference into worker processes; the tests folder
is on ``sys.path`` of the test session and of the processes it spawns.
"""

import os
import time

import numpy as np


def random_task(chunk):
    """``settings["draws"]`` standard normal draws per item from the item's own generator.

    Optional ``settings["sleep"]`` [s] per chunk and ``settings["log"]``: a file to which the
    chunk index is appended when the chunk finishes (to see which chunks were computed).
    """
    draws = chunk.settings["draws"]
    rows = {"item": [], "draw": [], "value": [], "label": []}
    for item, rng in zip(chunk.items, chunk.generators(), strict=True):
        rows["item"].append(np.full(draws, item))
        rows["draw"].append(np.arange(draws))
        rows["value"].append(rng.standard_normal(draws))
        rows["label"].append(np.full(draws, f"arch-{item}"))
    time.sleep(chunk.settings.get("sleep", 0.0))
    log = chunk.settings.get("log")
    if log:
        with open(log, "a") as f:
            f.write(f"{chunk.index}\n")
            f.flush()
            os.fsync(f.fileno())
    return {name: np.concatenate(parts) for name, parts in rows.items()}


def trivial_task(chunk):
    """One row per item, no work: measures the overhead per chunk."""
    return {"item": chunk.items}


def busy_task(chunk):
    """CPU-bound: ``settings["work"]`` float operations of pure numpy per item, one row each."""
    n = chunk.settings["work"]
    out = []
    for rng in chunk.generators():
        x = rng.random(1000)
        for _ in range(n // 1000):
            x = np.sqrt(x * x + 0.5)
        out.append(x.sum())
    return {"item": chunk.items, "value": np.array(out)}


def echo_task(chunk):
    """Returns ``settings["results"][chunk.index]`` as it is (to test result validation)."""
    return chunk.settings["results"][chunk.index]


def failing_task(chunk):
    """Raises in chunk 1."""
    if chunk.index == 1:
        raise RuntimeError("chunk 1 failed")
    return {"item": chunk.items}


def threads_task(chunk):
    """The thread caps seen by the process that evaluates the chunk."""
    import numba

    return {"numba_env": [int(os.environ.get("NUMBA_NUM_THREADS", -1))],
            "omp_env": [int(os.environ.get("OMP_NUM_THREADS", -1))],
            "numba_threads": [numba.get_num_threads()]}


def pid_and_sleep(seconds):
    """This process's id, after a progress bar of ``seconds`` seconds (tqdm's lock made)."""
    from tqdm.auto import tqdm

    for _ in tqdm(range(max(1, int(seconds * 10))), disable=False, leave=False):
        time.sleep(0.1)
    return os.getpid()


def report_pid(path):
    """Write this process's id to ``path``, then sleep a minute (a worker that is never done)."""
    from tqdm.auto import tqdm

    with open(path, "w") as f:
        f.write(str(os.getpid()))
    for _ in tqdm(range(600), leave=False):
        time.sleep(0.1)
