"""A study shared between the worker and this process (:meth:`Background.study`): every chunk
runs once, on either, with the results of a study run in one place; errors come back."""

from __future__ import annotations

import threading
import time
from concurrent.futures import ThreadPoolExecutor

import pytest

from archquake.report.running import BOTH_PROCESSES, HERE, Background, SharedChunks


def _square(x):
    time.sleep(0.02)
    if x < 0:
        raise ValueError(f"chunk {x} failed")
    return x * x, threading.get_ident()


def _study(n, pool):
    """A toy study: n chunks on ``pool`` (or here), their results in order."""
    if pool is None:
        return [_square(x) for x in range(n)]
    futures = [pool.submit(_square, x) for x in range(n)]
    return [f.result() for f in futures]


def test_a_shared_study_runs_every_chunk_once_on_both_sides():
    with ThreadPoolExecutor(1) as worker:  # stands in for the worker process
        task = Background(worker).study(_study, 40)
        time.sleep(0.1)  # this process is busy with its own steps meanwhile
        run = task.result()
    values = [v for v, _ in run.result]
    assert values == [x * x for x in range(40)]  # as the study run in one place
    assert [v for v, _ in _study(40, None)] == values
    ran_on = {who for _, who in run.result}
    assert threading.get_ident() in ran_on and len(ran_on) == 2  # both took chunks
    assert run.ran_on == BOTH_PROCESSES and task.done
    assert 0 < run.seconds <= run.wall_seconds


def test_a_shared_study_waits_for_the_task_it_comes_after():
    with ThreadPoolExecutor(1) as worker:
        background = Background(worker)
        first = background.submit(time.sleep, 0.2)
        start = time.perf_counter()
        run = background.study(_study, 2, after=first).result()
    assert first.done and run.seconds < time.perf_counter() - start - 0.15


def test_a_failing_chunk_fails_the_study():
    def study(pool):
        return [f.result() for f in [pool.submit(_square, x) for x in (1, -1, 2)]]

    with ThreadPoolExecutor(1) as worker:
        task = Background(worker).study(study)
        with pytest.raises(ValueError, match="chunk -1 failed"):
            task.result()


def test_a_cancelled_chunk_is_not_run():
    with ThreadPoolExecutor(1) as worker:
        shared = SharedChunks(worker)
        blocker = shared.submit(time.sleep, 0.1)
        later = shared.submit(_square, 3)
        assert later.cancel()
        blocker.result()
        shared.shutdown()
    assert later.cancelled()


def test_without_a_worker_the_study_runs_here_when_asked():
    task = Background().study(_study, 3)
    assert not task.done
    run = task.result()
    assert [v for v, _ in run.result] == [0, 1, 4] and run.ran_on == HERE


def test_ctrl_c_in_a_chunk_run_here_stops_this_process_at_once():
    def study(pool):
        return [f.result() for f in [pool.submit(_interrupted) for _ in range(3)]]

    with ThreadPoolExecutor(1) as worker:
        task = Background(worker).study(study)
        with pytest.raises(KeyboardInterrupt):
            task.result()


def _interrupted():
    time.sleep(0.05)
    raise KeyboardInterrupt
