"""The page's long computations as jobs: one worker process each, polled for progress,
cancelled by terminating it.

A job runs a task of :data:`archquake.app.tasks.TASKS` in a process of its own, so a long
computation (compiled code that holds the interpreter's lock for seconds) never stalls the
server, and cancelling it is ending its process. The processes are forked from a fork server
that has imported the library once (:mod:`multiprocessing`'s ``"forkserver"`` start method,
preloading :mod:`archquake.app.worker`), so a job starts in milliseconds, not in the second or
two an interpreter takes to import numpy, scipy, numba and matplotlib.

What crosses between the server and a worker is JSON text (the task's description in, the
progress and the result out), never a pickled object of the user's.
"""

from __future__ import annotations

import json
import multiprocessing
import os
import secrets
import signal
import threading
import time
from collections import OrderedDict

MAX_RUNNING = 3
"""Jobs running at once; one more is refused until one ends (the machine's cores are shared)."""

KEEP_FINISHED = 8
"""Finished jobs kept for the page to read, with their results and files (the oldest are
forgotten first, their files deleted): an animation of many blocks is megabytes, an assessment
report some."""


class BusyError(RuntimeError):
    """As many jobs as :data:`MAX_RUNNING` are running: the page is asked to wait or cancel."""


def context():
    """The multiprocessing context of the workers: forked from a fork server that preloads
    :mod:`archquake.app.worker`."""
    ctx = multiprocessing.get_context("forkserver")
    ctx.set_forkserver_preload(["archquake.app.worker"])
    return ctx


def start_fork_server() -> None:
    """Start the fork server now (it imports the library, a second or two), so that the first
    job does not wait for it."""
    from multiprocessing import forkserver

    context()
    forkserver.ensure_running()


def run_worker(connection, kind: str, text: str) -> None:
    """The target of a worker process: :func:`archquake.app.worker.main` (imported here, in the
    worker, where the fork server has imported it already)."""
    from .worker import main

    main(connection, kind, text)


class Job:
    """One task in its worker process (see :class:`Jobs`)."""

    def __init__(self, ctx, kind: str, spec: dict):
        self.id = secrets.token_hex(8)
        self.kind = kind
        self.state = "running"
        self.progress = {"done": 0, "total": 1, "text": "starting"}
        self.result = None
        self.error = None
        self.started = time.monotonic()
        self.ended = None
        self._lock = threading.Lock()
        self._reader, writer = ctx.Pipe(duplex=False)
        text = json.dumps({**spec, "job": self.id})
        # not a daemon: a task may start processes of its own (the report does), which a
        # daemon may not; the worker leads a process group, which cancel() ends as a whole
        self.process = ctx.Process(target=run_worker, args=(writer, kind, text), daemon=False,
                                   name=f"archquake-app-{kind}-{self.id}")
        self.process.start()
        writer.close()  # the worker's end: closed here so that its exit is seen as EOF

    def poll(self) -> None:
        """Read what the worker has said; a worker that ended without a result has failed."""
        with self._lock:
            if self.state != "running":
                return
            try:
                while self._reader.poll():
                    self._message(json.loads(self._reader.recv_bytes()))
                    if self.state != "running":
                        break
            except (EOFError, OSError):
                pass
            if self.state == "running" and not self.process.is_alive():
                self.process.join()
                self._finish("failed", error=f"the worker process ended without a result (exit "
                                             f"code {self.process.exitcode})")

    def _message(self, message: dict) -> None:
        if "progress" in message:
            done, total, text = message["progress"]
            self.progress = {"done": done, "total": total, "text": text}
        elif "result" in message:
            self.result = message["result"]
            self.progress = {**self.progress, "done": self.progress["total"], "text": "done"}
            self._finish("done")
        elif "error" in message:
            self._finish("failed", error=message["error"])

    def _finish(self, state: str, error: str | None = None) -> None:
        self.state = state
        self.error = error
        self.ended = time.monotonic()
        self._reader.close()
        self.process.join(timeout=5)

    def cancel(self) -> None:
        """End the worker process and the processes it started (a job already finished is left
        as it is)."""
        self.poll()
        with self._lock:
            if self.state != "running":
                return
            self._signal(signal.SIGTERM)
            self.process.join(timeout=5)
            if self.process.is_alive():
                self._signal(signal.SIGKILL)
                self.process.join(timeout=5)
            self._finish("cancelled")

    def _signal(self, number: int) -> None:
        """Send a signal to the worker's process group (the worker and its children), or to
        the worker alone before it has made its group."""
        pid = self.process.pid
        try:
            if os.getpgid(pid) == pid:
                os.killpg(pid, number)
                return
        except (ProcessLookupError, PermissionError):
            pass
        try:
            os.kill(pid, number)
        except ProcessLookupError:
            pass

    def status(self, result: bool = True) -> dict:
        """JSON-ready state of the job: ``id``, ``kind``, ``state`` (``running``, ``done``,
        ``failed``, ``cancelled``), ``progress`` (``done``, ``total``, ``text``), ``elapsed``
        [s], and ``result`` or ``error`` once finished."""
        self.poll()
        end = self.ended if self.ended is not None else time.monotonic()
        out = {"id": self.id, "kind": self.kind, "state": self.state,
               "progress": self.progress, "elapsed": round(end - self.started, 3)}
        if self.error is not None:
            out["error"] = self.error
        if result and self.result is not None:
            out["result"] = self.result
        return out


class Jobs:
    """The jobs of one server.

    Parameters
    ----------
    max_running : int
        Jobs running at once (:data:`MAX_RUNNING`).
    keep : int
        Finished jobs kept (:data:`KEEP_FINISHED`).
    forget : callable, optional
        ``forget(job_id)``, called for each job forgotten (to delete the files it wrote).
    """

    def __init__(self, max_running: int = MAX_RUNNING, keep: int = KEEP_FINISHED,
                 forget=None):
        self.max_running = max_running
        self.keep = keep
        self.forget = forget
        self._jobs: OrderedDict[str, Job] = OrderedDict()
        self._lock = threading.Lock()
        self._context = context()

    def start(self, kind: str, spec: dict) -> Job:
        """Start a task of :data:`archquake.app.tasks.TASKS` on ``spec`` in a new worker.

        Raises
        ------
        BusyError
            When :attr:`max_running` jobs are running.
        """
        with self._lock:
            running = [job for job in self._jobs.values() if job.state == "running"]
            for job in running:
                job.poll()
            running = [job for job in running if job.state == "running"]
            if len(running) >= self.max_running:
                raise BusyError(f"{len(running)} computations are running, the most this page "
                                f"runs at once: wait for one to end or cancel it")
            job = Job(self._context, kind, spec)
            self._jobs[job.id] = job
            finished = [i for i, j in self._jobs.items() if j.state != "running"]
            forgotten = finished[:max(0, len(finished) - self.keep)]
            for old in forgotten:
                del self._jobs[old]
        for old in forgotten:
            if self.forget is not None:
                self.forget(old)
        return job

    def get(self, job_id: str) -> Job:
        """The job of an id.

        Raises
        ------
        KeyError
            For an id the server does not know (or no longer keeps).
        """
        with self._lock:
            return self._jobs[job_id]

    def shutdown(self) -> None:
        """Cancel every running job."""
        with self._lock:
            jobs = list(self._jobs.values())
        for job in jobs:
            job.cancel()


__all__ = ["KEEP_FINISHED", "MAX_RUNNING", "BusyError", "Job", "Jobs", "context",
           "run_worker", "start_fork_server"]
