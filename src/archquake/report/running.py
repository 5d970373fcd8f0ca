"""How a report runs: its steps timed under a progress bar, its long tasks on a second process.

:class:`Steps` times every step of a report (the run-time table) and shows a progress bar over
them. A report has parts that wait on one another (the four-link chain of the paper) and long tasks
that need nothing of them (the rigid-block failure curve, the record-based fragility). On a
machine with two processors or more, :class:`Background` starts one worker process and gives it
those tasks, so that they cost a CPU instead of the report's time; on one processor a task runs
here, when its result is first asked for. A long study of independent chunks
(:meth:`Background.study`) starts on the worker and is shared with this process once its own
steps are done (:class:`SharedChunks`): whichever is free takes the next chunk, so that neither
waits for the other at the end (measured on ``archquake reproduce``: the rigid-block fragility
study's 9 s of chunks, which the report waited for alone, end 5 s sooner). Either way a task's
result comes back as a :class:`TaskRun`: the value, its run time and where it ran.

>>> background = Background()            # no worker process: tasks run when asked
>>> run = background.submit(sum, (1, 2, 3)).result()
>>> run.result, run.ran_on
(6, 'this process')
"""

from __future__ import annotations

import contextlib
import os
import queue
import sys
import threading
import time
from collections.abc import Callable, Iterator
from concurrent.futures import Executor, Future
from dataclasses import dataclass
from typing import Any

HERE = "this process"
"""Where a task ran, when it ran in the report's own process."""

SECOND_PROCESS = "a second process"
"""Where a task ran, when it ran on the worker process."""

BOTH_PROCESSES = "a second process, then both"
"""Where a study ran whose chunks the worker process took from its start and this process too
once its own steps were done (:meth:`Background.study`)."""


class Steps:
    """The steps of a report, each timed, under a progress bar.

    Parameters
    ----------
    total : int
        How many steps there are (the bar's length).
    progress : bool
        Show the progress bar (on stderr).
    desc : str
        The bar's label.

    Attributes
    ----------
    timings : dict of str to float
        Wall time of every step run so far [s], in order.

    Examples
    --------
    >>> steps = Steps(2, progress=False)
    >>> with steps("one"):
    ...     pass
    >>> list(steps.timings)
    ['one']
    >>> steps.close()
    """

    def __init__(self, total: int, progress: bool = True, desc: str = "report"):
        from tqdm.auto import tqdm

        self.timings: dict[str, float] = {}
        self._bar = tqdm(total=total, desc=desc, unit="part", disable=not progress,
                         file=sys.stderr)

    @contextlib.contextmanager
    def __call__(self, name: str) -> Iterator[None]:
        """Time the ``with`` block as the step ``name``."""
        self._bar.set_postfix_str(name)
        t0 = time.perf_counter()
        yield
        self.timings[name] = time.perf_counter() - t0
        self._bar.update()

    def close(self) -> None:
        """Close the progress bar."""
        self._bar.close()


@dataclass(frozen=True)
class TaskRun:
    """A task's result and what it cost.

    Attributes
    ----------
    result : object
        What the task returned.
    seconds : float
        Run time of the task itself [s].
    wall_seconds : float
        From its submission to its end [s] (its waiting included).
    ran_on : str
        :data:`HERE` or :data:`SECOND_PROCESS`.
    """

    result: Any
    seconds: float
    wall_seconds: float
    ran_on: str

    def describe(self) -> dict:
        """JSON-ready ``{"ran on", "seconds", "wall_seconds"}`` (the run-time table of a report).

        Returns
        -------
        dict
        """
        return {"ran on": self.ran_on, "seconds": self.seconds, "wall_seconds": self.wall_seconds}


def timed(function: Callable, *args) -> tuple[Any, float]:
    """``(function(*args), its run time [s])`` (what a worker runs for a task).

    Parameters
    ----------
    function : callable
        A picklable function (module level).
    *args
        Its arguments.

    Returns
    -------
    (object, float)
    """
    t0 = time.perf_counter()
    result = function(*args)
    return result, time.perf_counter() - t0


def run_here(function: Callable, *args) -> TaskRun:
    """Run a task in this process.

    Parameters
    ----------
    function : callable
        The task.
    *args
        Its arguments.

    Returns
    -------
    TaskRun
    """
    result, seconds = timed(function, *args)
    return TaskRun(result, seconds, seconds, HERE)


class Task:
    """A submitted task: on the worker process, or deferred until :meth:`Task.result` runs it
    here."""

    def __init__(self, function: Callable, args: tuple, pool=None):
        self._function, self._args = function, args
        self._future = None
        self._submitted = time.perf_counter()
        self._done: float | None = None
        self._run: TaskRun | None = None
        if pool is not None:
            self._future = pool.submit(timed, function, *args)
            self._future.add_done_callback(self._finished)

    def _finished(self, _future) -> None:
        if self._done is None:
            self._done = time.perf_counter()

    @classmethod
    def run_now(cls, function: Callable, *args) -> Task:
        """``function(*args)`` run here and now (:func:`run_here`), as a :class:`Task` whose
        :meth:`result` is that run."""
        task = cls(function, args)
        task._run = run_here(function, *args)
        return task

    @property
    def done(self) -> bool:
        """Whether the task's result is there (the worker finished it, or it ran here)."""
        return self._run is not None or (self._future is not None and self._future.done())

    def result(self) -> TaskRun:
        """The task's :class:`TaskRun` (waiting for the worker, or running the task here).

        Returns
        -------
        TaskRun
        """
        if self._run is None:
            if self._future is None:
                self._run = run_here(self._function, *self._args)
            else:
                result, seconds = self._future.result()
                done = time.perf_counter() if self._done is None else self._done
                self._run = TaskRun(result, seconds, done - self._submitted, SECOND_PROCESS)
        return self._run


class SharedChunks(Executor):
    """An executor whose tasks (a study's chunks) the worker process takes one at a time from
    the start, and this process too from :meth:`SharedChunks.help` on: whichever is free takes the
    next one.

    A study's chunks are independent and their results do not depend on where they run (the
    same compiled code on the same machine), so a study that the worker would finish alone
    while this process waits is shared between the two instead.

    Parameters
    ----------
    pool : concurrent.futures.Executor
        The worker process (:class:`Background`'s pool).
    """

    def __init__(self, pool):
        self._pool = pool
        self._queue: queue.SimpleQueue = queue.SimpleQueue()
        self._forwarder = threading.Thread(target=self._forward, daemon=True)
        self._forwarder.start()

    def submit(self, fn, /, *args, **kwargs) -> Future:
        """Queue ``fn(*args, **kwargs)`` for whichever side is free first.

        Returns
        -------
        concurrent.futures.Future
        """
        future: Future = Future()
        self._queue.put((future, fn, args, kwargs))
        return future

    @staticmethod
    def _settle(item, run: Callable, here: bool) -> None:
        """Run a queued task by ``run(fn, args, kwargs)`` and set its future (unless it was
        cancelled); an exception goes to the future, and where the task ran ``here`` (this
        process's own thread), a Ctrl-C is raised again, so that this process stops at once."""
        future, fn, args, kwargs = item
        if not future.set_running_or_notify_cancel():
            return
        try:
            future.set_result(run(fn, args, kwargs))
        except BaseException as exc:
            future.set_exception(exc)
            if here and not isinstance(exc, Exception):
                raise

    def _forward(self) -> None:
        while (item := self._queue.get()) is not None:
            self._settle(item, lambda fn, args, kwargs: self._pool.submit(
                fn, *args, **kwargs).result(), here=False)

    def help(self, until: Future) -> None:
        """Run queued tasks in this process until ``until`` is done.

        Parameters
        ----------
        until : concurrent.futures.Future
            The study whose chunks these are.
        """
        while not until.done():
            try:
                item = self._queue.get(timeout=0.02)
            except queue.Empty:
                continue
            if item is None:  # shut down meanwhile
                self._queue.put(None)
                return
            self._settle(item, lambda fn, args, kwargs: fn(*args, **kwargs), here=True)

    def shutdown(self, wait: bool = True, *, cancel_futures: bool = False) -> None:
        """Stop taking tasks to the worker (after those queued before); with ``wait``, until the
        last one it took is done."""
        self._queue.put(None)
        if wait:
            self._forwarder.join()


class StudyTask:
    """A study started on :class:`SharedChunks` (:meth:`Background.study`): its driver runs on
    a thread of this process, its chunks on the worker process, and here from
    :meth:`StudyTask.result` on."""

    def __init__(self, function: Callable, args: tuple, pool, after: Task | None):
        self._shared = SharedChunks(pool)
        self._submitted = time.perf_counter()
        self._future: Future = Future()

        def drive():
            try:
                if after is not None:
                    after.result()
                self._future.set_result(timed(function, *args, self._shared))
            except BaseException as exc:  # noqa: BLE001 - raised again by result()
                self._future.set_exception(exc)

        threading.Thread(target=drive, daemon=True).start()

    @property
    def done(self) -> bool:
        """Whether the study has finished."""
        return self._future.done()

    def result(self) -> TaskRun:
        """Help with the study's chunks until it ends; its :class:`TaskRun`.

        Returns
        -------
        TaskRun
        """
        self._shared.help(self._future)
        self._shared.shutdown(wait=False)
        result, seconds = self._future.result()
        return TaskRun(result, seconds, time.perf_counter() - self._submitted, BOTH_PROCESSES)


class Background:
    """One worker process for a report's long independent tasks (or none: tasks run here).

    Parameters
    ----------
    pool : WorkerPool, optional
        The worker (:func:`archquake.execution.process_pool`); None runs every task here.
        :meth:`start` makes one when the machine has a second processor.
    """

    def __init__(self, pool=None):
        self._pool = pool

    @property
    def parallel(self) -> bool:
        """Whether tasks run on a second process."""
        return self._pool is not None

    @classmethod
    @contextlib.contextmanager
    def start(cls, warm_up: Callable[[], Any] | None = None) -> Iterator[Background]:
        """A :class:`Background` with one worker process on a machine with two processors or
        more, without one on a single processor; the worker ends with the ``with`` block.

        Parameters
        ----------
        warm_up : callable, optional
            Picklable function the worker runs as it starts (e.g. loading a compiled solver).

        Yields
        ------
        Background
        """
        if (os.cpu_count() or 1) < 2:
            yield cls()
            return
        from ..execution import process_pool

        with process_pool(1, warm_up=warm_up) as pool:
            yield cls(pool)

    def submit(self, function: Callable, *args) -> Task:
        """Give the worker ``function(*args)`` (a picklable function and arguments).

        Parameters
        ----------
        function : callable
            The task, a module-level function.
        *args
            Its arguments.

        Returns
        -------
        Task
            Its handle; without a worker the task runs when :meth:`Task.result` is called.
        """
        return Task(function, args, self._pool)

    def study(self, function: Callable, *args, after: Task | None = None) -> Task | StudyTask:
        """Start ``function(*args, pool)``, a study that runs its chunks on ``pool``: on the
        worker from now on, and on this process as well once :meth:`StudyTask.result` is
        called, so that neither waits for the other at the end. Without a worker it runs here
        when its result is asked for, with ``pool=None``.

        Parameters
        ----------
        function : callable
            The study: ``function(*args, pool)`` where ``pool`` is an executor of its chunks
            (or None).
        *args
            Its arguments.
        after : Task, optional
            A task on the worker to wait for before the study starts (one that compiles what
            the study runs, so that this process loads it instead of compiling it again).

        Returns
        -------
        Task or StudyTask
        """
        if self._pool is None:
            return Task(function, (*args, None))
        return StudyTask(function, args, self._pool, after)


__all__ = ["BOTH_PROCESSES", "HERE", "SECOND_PROCESS", "Background", "SharedChunks", "Steps",
           "StudyTask", "Task", "TaskRun", "run_here", "timed"]
