"""Worker processes end with the process that started them, however it ends: a clean stop
leaves no leaked semaphore, a ``kill -9`` of the parent no orphan, and a worker started while
the pool is being stopped is stopped too."""

import os
import signal
import subprocess
import sys
import textwrap
import threading
import time
from pathlib import Path

import pytest

from archquake.execution import WorkerPool, _limit_threads, process_pool

pytestmark = pytest.mark.skipif(not Path("/proc/self/stat").exists(),
                                reason="lists processes through /proc (Linux)")
TESTS = Path(__file__).parent
SRC = TESTS.parent / "src"
ENV = {**os.environ, "PYTHONPATH": os.pathsep.join([str(SRC), str(TESTS)])}


def _alive(pid: int) -> bool:
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except OSError:
        return False
    return state != "Z"


def _wait_gone(pid: int, seconds: float) -> bool:
    deadline = time.monotonic() + seconds
    while _alive(pid):
        if time.monotonic() > deadline:
            return False
        time.sleep(0.05)
    return True


PARENT = textwrap.dedent("""
    import sys, time
    from archquake.execution import process_pool
    from toy_tasks import report_pid

    pool = process_pool(1)
    pool.submit(report_pid, sys.argv[1])
    time.sleep(120)
""")


def test_a_worker_dies_with_its_parent_killed(tmp_path):
    """kill -9 of the process that owns the pool: its worker (and the resource tracker) end
    within a second or so; they used to run on for minutes."""
    pid_file = tmp_path / "worker.pid"
    parent = subprocess.Popen([sys.executable, "-c", PARENT, str(pid_file)], env=ENV,
                              start_new_session=True)
    try:
        deadline = time.monotonic() + 60
        while not pid_file.exists() or not pid_file.read_text():
            assert parent.poll() is None and time.monotonic() < deadline, "no worker started"
            time.sleep(0.05)
        worker = int(pid_file.read_text())
        assert _alive(worker)
        os.kill(parent.pid, signal.SIGKILL)
        parent.wait()
        assert _wait_gone(worker, 10), "the worker survived its parent"
    finally:
        with_group = [p for p in Path("/proc").glob("[0-9]*/stat") if _group(p) == parent.pid]
        if with_group:
            os.killpg(parent.pid, signal.SIGKILL)


def _group(stat: Path) -> int | None:
    try:
        return int(stat.read_text().rsplit(")", 1)[1].split()[2])
    except (OSError, ValueError, IndexError):
        return None


INTERRUPTED = textwrap.dedent("""
    import sys, time
    from archquake.execution import process_pool
    from toy_tasks import report_pid

    with process_pool(1) as pool:
        pool.submit(report_pid, sys.argv[1])
        from pathlib import Path
        while not Path(sys.argv[1]).exists():
            time.sleep(0.05)
        time.sleep(0.5)  # the worker is inside its progress bar
        raise KeyboardInterrupt
""")


def test_an_interrupted_pool_leaks_no_semaphore(tmp_path):
    """Ctrl-C with a worker inside a progress bar: no "leaked semaphore" warning from the
    resource tracker (tqdm's multiprocessing lock, registered by the terminated worker)."""
    pid_file = tmp_path / "worker.pid"
    run = subprocess.run([sys.executable, "-c", INTERRUPTED, str(pid_file)], env=ENV,
                         capture_output=True, text=True, timeout=120)
    assert "KeyboardInterrupt" in run.stderr
    assert "leaked" not in run.stderr, run.stderr
    assert _wait_gone(int(pid_file.read_text()), 10)


class _SlowSpawn(WorkerPool):
    """A pool whose worker starts slowly, holding the pool's lock as the base class does."""

    entered = None

    def _spawn_process(self):
        self.entered.set()
        time.sleep(0.5)
        super()._spawn_process()


def test_a_worker_started_while_the_pool_stops_is_stopped_too():
    """terminate_workers while a submission from another thread is starting a worker: the
    worker is in the list of processes stopped (it was read before the shutdown, and missed)."""
    import multiprocessing

    pool = _SlowSpawn(max_workers=1, mp_context=multiprocessing.get_context("spawn"),
                      initializer=_limit_threads, initargs=(1, None, os.getpid()))
    pool.entered = threading.Event()
    table = pool._processes
    submitter = threading.Thread(target=pool.submit, args=(time.sleep, 30))
    submitter.start()
    assert pool.entered.wait(10)
    pool.terminate_workers(timeout=10)
    submitter.join(10)
    started = list(table.values())
    assert len(started) == 1
    # stopped by terminate_workers' signal (a worker it missed would end on the pool's sentinel,
    # exit code 0). The pool's manager thread reaps the worker too: until it has stored the exit
    # code, this thread's waitpid finds no child and the process reads as alive, so wait for it.
    deadline = time.monotonic() + 10
    while started[0].exitcode is None and time.monotonic() < deadline:
        time.sleep(0.05)
    assert started[0].exitcode in (-signal.SIGTERM, -signal.SIGKILL), started[0].exitcode


def test_process_pool_workers_know_their_parent():
    with process_pool(1) as pool:
        assert pool.submit(os.getppid).result(timeout=120) == os.getpid()
