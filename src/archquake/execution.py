"""Running large studies: chunking, seeding, checkpoint/resume, progress, processes or Dask.

Nothing here knows any physics. A study is

- a :class:`StudyPlan`: JSON-serialisable ``settings``, a ``seed``, a number of items (e.g. one
  item = one sampled irregular arch) and a chunk size; the items ``0 .. n_items-1`` are split into
  consecutive chunks of ``chunk_size`` items (the last one may be shorter);
- a *task*: a module-level (hence picklable) function ``task(chunk: Chunk) -> dict[str, array]``
  that evaluates one :class:`Chunk` and returns the columns of a tidy table (one row per
  analysis, any number of rows per item, every column one-dimensional and of equal length).

:func:`run_study` evaluates every chunk with one of the :data:`BACKENDS` and returns the rows of
all chunks, in chunk (hence item) order, as one :class:`pandas.DataFrame`.

Random numbers
--------------
Item ``i`` draws its random numbers from its own :class:`numpy.random.SeedSequence` [1]_,
``SeedSequence(seed, spawn_key=(i,))``, which is the very same sequence as
``SeedSequence(seed).spawn(n_items)[i]`` (the ``i``-th child of the root sequence): same entropy,
same spawn key, same generated state. A task must draw item ``i``'s numbers only from
``chunk.generators()[i - chunk.start]`` (or ``chunk.seed_sequences()``). Item ``i``'s stream
therefore depends on the seed and on ``i`` only -- not on the chunk size, the backend, the number
of workers, the order in which chunks finish or whether the study was resumed -- so the results
are identical in all these cases.

Checkpoints
-----------
With an output directory ``DIR``, :func:`run_study` writes ``DIR/study.json`` (settings, seed,
chunking, task name and ``archquake_version``) before computing anything, and saves each finished
chunk as ``DIR/chunks/chunk-000123.npz`` as soon as it arrives (atomically: a temporary file in
the same directory renamed over the target, see :func:`archquake.results_io.atomic_path`). The
chunk files are written by the calling process, so Dask workers need no shared file system. At
the end, the tidy table and the JSON summary are saved with
:func:`archquake.results_io.save_study`. ``resume=True`` reloads the finished chunks of an
interrupted study and computes only the missing ones; :func:`resumable_study` says which study a
directory holds for a resume (the one reading of a study directory that :func:`run_study` and
the studies and reports that call it share).

Threads
-------
The ``"processes"`` backend starts fresh interpreters (``"spawn"`` context: no state, locks or
threads -- numba's or BLAS's -- are inherited through ``fork``) and caps the threads of every
worker (``NUMBA_NUM_THREADS``, ``OMP_NUM_THREADS``, ... set to ``cpu_count // workers``, at
least 1) so that parallel workers do not oversubscribe the cores. The variables take effect for
libraries a worker imports after start-up (numba's cap is also applied at run time); a value
already set in the environment is kept. Dask workers are started by the cluster: for CPU-bound
tasks that hold the GIL, start them with one thread each (``dask worker ADDRESS --nworkers N
--nthreads 1``).

The task function and this package must be importable where the task runs (the worker
processes, or every Dask worker): the task is pickled by reference (module and name).

References
----------
.. [1] NumPy documentation, "Parallel Random Number Generation" (:mod:`numpy.random`):
   independent streams from ``SeedSequence.spawn``.
"""

from __future__ import annotations

import contextlib
import copy
import datetime
import json
import math
import os
import re
import signal
import sys
import time
import warnings
from collections.abc import Callable, Iterator, Mapping
from concurrent.futures import ProcessPoolExecutor
from contextlib import suppress
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
from tqdm.auto import tqdm

from ._version import __version__
from .defaults import DEFAULT_BACKEND
from .errors import StudyError, StudyWarning
from .results_io import atomic_path, read_json, save_study, to_json_text, write_json

BACKENDS = ("serial", "processes", "dask")
"""Names accepted by ``run_study(backend=...)``."""

SCHEDULER_TIMEOUT = 5.0
"""Time allowed to connect to a Dask scheduler before giving up [s]."""

DASK_WORKER_TIMEOUT = 60.0
"""Longest time a study waits while its Dask cluster has no worker (all died or none started)
before it stops with a :class:`~archquake.errors.StudyError` [s]; finished chunks stay saved."""

STUDY_JSON = "study.json"
CHUNK_DIR = "chunks"
STUDY_FORMAT = "archquake-study"
STUDY_FORMAT_VERSION = 1

_THREAD_VARIABLES = ("NUMBA_NUM_THREADS", "OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS",
                     "MKL_NUM_THREADS")
_SCHEDULER_ADDRESS = re.compile(r"^(tcp|tls)://(\[[0-9A-Fa-f:.]+\]|[A-Za-z0-9_.-]+):(\d{1,5})$")
_RESERVED_PREFIX = "__"

Task = Callable[["Chunk"], Mapping[str, Any]]


# --------------------------------------------------------------------------------------------
# Plan and chunks
# --------------------------------------------------------------------------------------------


def item_seed_sequence(seed: int, item: int) -> np.random.SeedSequence:
    """Seed sequence of item ``item`` of a study with root seed ``seed``.

    ``SeedSequence(seed, spawn_key=(item,))``, identical to
    ``SeedSequence(seed).spawn(n)[item]`` for any ``n > item``.

    Parameters
    ----------
    seed : int
        Root seed of the study, ``>= 0``.
    item : int
        Item index, ``>= 0``.

    Returns
    -------
    numpy.random.SeedSequence

    Examples
    --------
    >>> child = np.random.SeedSequence(7).spawn(3)[2]
    >>> item_seed_sequence(7, 2).generate_state(4).tolist() == child.generate_state(4).tolist()
    True
    """
    return np.random.SeedSequence(seed, spawn_key=(item,))


def _check_count(name: str, value: Any, minimum: int = 1) -> int:
    if isinstance(value, bool) or not isinstance(value, int | np.integer):
        raise ValueError(f"{name} must be an integer >= {minimum}, got {value!r}")
    if value < minimum:
        raise ValueError(f"{name} must be an integer >= {minimum}, got {value}")
    return int(value)


def _normalise_settings(settings: Any) -> dict:
    if not isinstance(settings, Mapping):
        raise ValueError(f"settings must be a mapping (dict), got {type(settings).__name__}")
    bad = [k for k in settings if not isinstance(k, str)]
    if bad:
        raise ValueError(f"settings keys must be strings, got {bad!r}")
    try:
        # The JSON round trip gives the exact form that study.json stores (tuples -> lists,
        # numpy scalars -> numbers), so a resumed study compares like with like.
        return json.loads(to_json_text(dict(settings)))
    except (TypeError, ValueError) as exc:
        raise ValueError(f"settings must be JSON-serialisable: {exc}") from exc


@dataclass(frozen=True)
class Chunk:
    """Consecutive items ``start .. stop-1`` of a study, evaluated by one task call.

    Attributes
    ----------
    index : int
        Chunk number, ``0 .. n_chunks-1``.
    start, stop : int
        First item and one past the last item.
    seed : int
        Root seed of the study.
    settings : dict
        Settings of the study (JSON-serialisable).
    """

    index: int
    start: int
    stop: int
    seed: int
    settings: dict = field(repr=False)

    def __len__(self) -> int:
        return self.stop - self.start

    @property
    def items(self) -> np.ndarray:
        """Item indices ``start .. stop-1`` (int64)."""
        return np.arange(self.start, self.stop, dtype=np.int64)

    def seed_sequences(self) -> list[np.random.SeedSequence]:
        """Seed sequence of each item of the chunk.

        Returns
        -------
        list of numpy.random.SeedSequence
            :func:`item_seed_sequence` of items ``start .. stop-1``.
        """
        return [item_seed_sequence(self.seed, i) for i in range(self.start, self.stop)]

    def generators(self) -> list[np.random.Generator]:
        """A fresh random generator for each item of the chunk.

        Returns
        -------
        list of numpy.random.Generator
            PCG64 generators seeded by :meth:`seed_sequences`.
        """
        return [np.random.default_rng(s) for s in self.seed_sequences()]


@dataclass(frozen=True)
class StudyPlan:
    """What a study computes and how it is split into chunks.

    Parameters
    ----------
    settings : mapping
        JSON-serialisable settings passed to the task in every chunk (stored normalised through
        JSON: tuples become lists, numpy scalars numbers).
    seed : int
        Root seed, ``>= 0``; item ``i`` uses ``SeedSequence(seed, spawn_key=(i,))``.
    n_items : int
        Number of items, ``>= 1``.
    chunk_size : int
        Items per chunk, ``>= 1`` (the last chunk may be shorter).

    Raises
    ------
    ValueError
        If a count is not a positive integer, the seed is negative or settings are not
        JSON-serialisable.
    """

    settings: dict
    seed: int
    n_items: int
    chunk_size: int

    def __post_init__(self) -> None:
        object.__setattr__(self, "settings", _normalise_settings(self.settings))
        object.__setattr__(self, "seed", _check_count("seed", self.seed, minimum=0))
        object.__setattr__(self, "n_items", _check_count("n_items", self.n_items))
        object.__setattr__(self, "chunk_size", _check_count("chunk_size", self.chunk_size))

    @property
    def n_chunks(self) -> int:
        """Number of chunks, ``ceil(n_items / chunk_size)``."""
        return math.ceil(self.n_items / self.chunk_size)

    def chunk(self, index: int) -> Chunk:
        """Chunk number ``index``.

        Parameters
        ----------
        index : int
            ``0 <= index < n_chunks``.

        Returns
        -------
        Chunk
            Its items, the seed and its own copy of the settings.

        Raises
        ------
        ValueError
            If ``index`` is not an integer in range.
        """
        if isinstance(index, bool) or not isinstance(index, int | np.integer) \
                or not 0 <= index < self.n_chunks:
            raise ValueError(f"chunk index must be an integer in [0, {self.n_chunks}), "
                             f"got {index!r}")
        start = int(index) * self.chunk_size
        # each chunk gets its own copy of the settings: a task that modifies them cannot affect
        # other chunks, whichever backend runs it
        return Chunk(index=int(index), start=start,
                     stop=min(start + self.chunk_size, self.n_items),
                     seed=self.seed, settings=copy.deepcopy(self.settings))

    def chunks(self) -> Iterator[Chunk]:
        """All chunks in order.

        Returns
        -------
        iterator of Chunk
        """
        return (self.chunk(i) for i in range(self.n_chunks))

    def describe(self) -> dict:
        """The plan as a JSON-serialisable dictionary (what ``study.json`` records).

        Returns
        -------
        dict
            ``settings``, ``seed``, ``n_items``, ``chunk_size`` and ``n_chunks``.
        """
        return {"settings": self.settings, "seed": self.seed, "n_items": self.n_items,
                "chunk_size": self.chunk_size, "n_chunks": self.n_chunks}


# --------------------------------------------------------------------------------------------
# Evaluating one chunk (runs in the workers)
# --------------------------------------------------------------------------------------------


def _columns_of(result: Any, chunk_index: int) -> dict[str, np.ndarray]:
    """Validated columns of a task result: 1-D, equal lengths, no Python objects."""
    where = f"the task's result for chunk {chunk_index}"
    if not isinstance(result, Mapping) or not result:
        raise ValueError(f"{where} must be a non-empty dict of columns (name -> 1-D array), "
                         f"got {type(result).__name__}")
    columns = {}
    for name, values in result.items():
        if not isinstance(name, str) or name.startswith(_RESERVED_PREFIX):
            raise ValueError(f"{where}: column names must be strings not starting with "
                             f"{_RESERVED_PREFIX!r}, got {name!r}")
        array = np.asarray(values)
        if array.ndim != 1:
            raise ValueError(f"{where}: column {name!r} must be one-dimensional, "
                             f"got shape {array.shape}")
        if array.dtype.kind in "OV":
            raise ValueError(f"{where}: column {name!r} has dtype {array.dtype}; use numbers, "
                             "booleans or fixed-width strings (np.asarray(values, dtype=str))")
        columns[name] = array
    lengths = {name: len(a) for name, a in columns.items()}
    if len(set(lengths.values())) > 1:
        raise ValueError(f"{where}: columns must have equal lengths, got {lengths}")
    return columns


def _run_chunk(chunk: Chunk, task: Task) -> tuple[int, dict[str, np.ndarray], float]:
    """Evaluate ``task(chunk)``; return the chunk index, its columns and the time taken [s]."""
    t0 = time.perf_counter()
    columns = _columns_of(task(chunk), chunk.index)
    return chunk.index, columns, time.perf_counter() - t0


PARENT_CHECK_INTERVAL = 0.5
"""How often a worker process checks that the process that started it is alive [s]."""


def die_with_parent(parent: int, interval: float = PARENT_CHECK_INTERVAL) -> None:
    """End this process when its parent ``parent`` (a process id) is gone.

    A worker whose parent was killed (``kill -9``, an out-of-memory kill, a SIGTERM with the
    default action) would otherwise run its chunk to the end, then wait for work forever,
    keeping the resource tracker alive with it. On Linux the kernel sends SIGKILL at the
    parent's death (``prctl(PR_SET_PDEATHSIG)``, when the ``prctl`` call is available); a
    daemon thread also polls :func:`os.getppid` every ``interval`` seconds, which works on
    every POSIX system (an orphan is adopted by another process) and whatever thread of the
    parent started this one.

    Parameters
    ----------
    parent : int
        Process id of the parent, as the parent saw itself (:func:`os.getpid`).
    interval : float
        Seconds between two checks.
    """
    import threading

    if sys.platform.startswith("linux"):
        with suppress(Exception):  # no libc, no prctl: the thread below still watches
            import ctypes

            libc = ctypes.CDLL(None, use_errno=True)
            libc.prctl(1, signal.SIGKILL, 0, 0, 0)  # PR_SET_PDEATHSIG = 1
    if os.getppid() != parent:  # the parent died before the watch began
        os._exit(1)

    def watch() -> None:
        while os.getppid() == parent:
            time.sleep(interval)
        os._exit(1)

    threading.Thread(target=watch, name="archquake-parent-watch", daemon=True).start()


def _limit_threads(threads: int, warm_up: Callable[[], Any] | None = None,
                   parent: int | None = None) -> None:
    """Process-pool initializer: end with the parent ``parent`` (:func:`die_with_parent`), cap
    the threads of numba and BLAS in a worker process, then run ``warm_up`` (if given) once.

    A worker ignores SIGINT: Ctrl-C in a terminal signals the whole process group, and the
    process that owns the pool stops the workers itself (:meth:`WorkerPool.terminate_workers`)
    instead of each worker printing a KeyboardInterrupt traceback; SIGTERM takes its default
    action (ends it), also in a worker forked from a command that handles SIGTERM. Its
    progress bars (tqdm) lock with a thread lock, not tqdm's default multiprocessing one: a
    worker terminated with a semaphore of its own registered would leave the resource tracker
    to warn of it ("leaked semaphore objects") at the end of the command.
    """
    import threading

    if parent is not None:
        die_with_parent(parent)
    tqdm.set_lock(threading.RLock())
    with suppress(ValueError):  # not the main thread of the worker: leave signals alone
        signal.signal(signal.SIGINT, signal.SIG_IGN)
        # a forked worker inherits the command's SIGTERM handler, which raises an exception
        # that the pool's loop would catch: SIGTERM must end it (terminate_workers)
        signal.signal(signal.SIGTERM, signal.SIG_DFL)
    numba_imported = "numba" in sys.modules  # e.g. by the parent's __main__, re-imported here
    for name in _THREAD_VARIABLES:
        # numba reads NUMBA_NUM_THREADS again at every compilation and refuses a value that
        # differs from the one it started with; once imported, it keeps its own (archquake's
        # compiled code is not multi-threaded, so only BLAS's threads matter then)
        if not (numba_imported and name == "NUMBA_NUM_THREADS"):
            os.environ.setdefault(name, str(threads))
    if warm_up is not None:
        warm_up()


# --------------------------------------------------------------------------------------------
# Backends: each yields (chunk index, columns, seconds) as chunks finish, in any order
# --------------------------------------------------------------------------------------------


def _serial(task: Task, chunks: list[Chunk], workers: int | None,
            client: Any) -> Iterator[tuple[int, dict, float]]:
    for chunk in chunks:
        yield _run_chunk(chunk, task)


class WorkerPool(ProcessPoolExecutor):
    """A :class:`concurrent.futures.ProcessPoolExecutor` that stops its workers when it is left
    by an exception.

    Leaving ``with WorkerPool(...)`` normally waits for the submitted work, as the base class
    does; leaving it by an exception (a failed chunk, Ctrl-C, SIGTERM turned into an
    exception) terminates the worker processes at once, so none is left running the abandoned
    work, or orphaned if this process then exits.
    """

    def terminate_workers(self, timeout: float = 5.0) -> None:
        """Cancel the queued work and terminate the worker processes, waiting for them to exit.

        Parameters
        ----------
        timeout : float
            Time [s] the processes are given to exit after SIGTERM, all together, before they
            are killed (SIGKILL).
        """
        # The pool's table of processes, read only after the shutdown: a submission in flight
        # starts its worker holding the pool's lock, and the shutdown waits for that lock, so
        # the table is complete once it returns (a list read before it would miss a worker
        # started meanwhile, which would survive). The shutdown drops the pool's reference to
        # the table, not the table.
        table = getattr(self, "_processes", None)
        table = {} if table is None else table  # the table itself, even empty: not a copy
        self.shutdown(wait=False, cancel_futures=True)
        with self._shutdown_lock:
            processes = list(table.values())
        for process in processes:
            with suppress(ValueError, ProcessLookupError):
                process.terminate()
        deadline = time.monotonic() + timeout
        for process in processes:
            with suppress(ValueError):
                process.join(max(0.0, deadline - time.monotonic()))
                if process.is_alive():
                    process.kill()
                    process.join(1.0)

    def __exit__(self, exc_type, exc_val, exc_tb):
        if exc_type is not None:
            self.terminate_workers()
        return super().__exit__(exc_type, exc_val, exc_tb)


def process_pool(workers: int | None = None, *,
                 warm_up: Callable[[], Any] | None = None) -> WorkerPool:
    """A pool of fresh local worker processes, as the ``"processes"`` backend starts them.

    ``"spawn"`` context and threads capped per worker (module docstring); the workers ignore
    SIGINT. Give it to :func:`run_study` as ``pool=`` to run several studies on the same (warm)
    workers: starting a process and importing numpy, scipy and numba in it takes seconds, often
    more than a small study. The caller owns the pool: use it as a context manager (an
    exception inside terminates the workers, :class:`WorkerPool`) or call ``shutdown()``.

    Parameters
    ----------
    workers : int, optional
        Number of processes (default ``os.cpu_count()``).
    warm_up : callable, optional
        Picklable function run once in every worker as it starts (e.g.
        :func:`archquake.studies.fragility.warm_up`, which loads the compiled engine), so that the
        first chunks of a study do not pay for it.

    Returns
    -------
    WorkerPool

    Raises
    ------
    ValueError
        If ``workers`` is not an integer >= 1.
    """
    n = _check_count("workers", workers) if workers is not None else (os.cpu_count() or 1)
    return _worker_pool(n, "spawn", warm_up)


def _worker_pool(n: int, start_method: str, warm_up: Callable[[], Any] | None) -> WorkerPool:
    """``n`` worker processes started by ``start_method``, with :func:`_limit_threads` as
    their initializer (:func:`process_pool`, :func:`forked_pool`)."""
    import multiprocessing

    from .compiled import announce_for_workers

    announce_for_workers(warm_up)  # its workers compile an engine: said here, once
    threads = max(1, (os.cpu_count() or 1) // n)
    return WorkerPool(max_workers=n, mp_context=multiprocessing.get_context(start_method),
                      initializer=_limit_threads, initargs=(threads, warm_up, os.getpid()))


def forked_pool() -> WorkerPool | None:
    """One worker process forked from this one, or None where processes cannot be forked
    (only Linux forks them here: elsewhere a fork of a process with numba and BLAS loaded is
    not safe).

    A forked worker starts with this process's modules imported and its compiled code
    loaded, in milliseconds where a fresh one (:func:`process_pool`) takes a second or two:
    it pays for work of a fraction of a second that this process would otherwise do after
    its own, such as the limit-analysis sample of a fragility study run here
    (:func:`archquake.studies.fragility.run_fragility`). Fork it before this process starts
    threads of its own (progress bars): a fork copies only the thread that forks. Like
    :func:`process_pool`'s workers it ignores SIGINT and ends with this process.

    Returns
    -------
    WorkerPool or None
    """
    if not sys.platform.startswith("linux"):
        return None
    return _worker_pool(1, "fork", None)


def _processes(task: Task, chunks: list[Chunk], workers: int,
               pool: Any) -> Iterator[tuple[int, dict, float]]:
    from concurrent.futures import FIRST_COMPLETED, wait

    executor = process_pool(min(workers, len(chunks))) if pool is None else pool
    pending = set()
    try:
        pending = {executor.submit(_run_chunk, chunk, task) for chunk in chunks}
        while pending:
            done, pending = wait(pending, return_when=FIRST_COMPLETED)
            for future in done:
                yield future.result()
    except BaseException:  # stopped early (interrupted, a chunk failed, closed by the caller)
        if pool is None:  # the running chunks are abandoned: stop their workers now
            executor.terminate_workers()
        raise
    finally:
        if pool is None:
            executor.shutdown(wait=True, cancel_futures=True)
        else:  # a pool owned by the caller stays open; drop what this study still queued
            for future in pending:
                future.cancel()


@contextlib.contextmanager
def _quiet_loggers(prefixes: tuple[str, ...]):
    """Disable the loggers whose names start with one of ``prefixes`` in the block (restored
    after it)."""
    import logging

    names = [name for name in list(logging.root.manager.loggerDict)
             if name.split(".")[0] in prefixes]
    loggers = [logging.getLogger(name) for name in names]
    before = [logger.disabled for logger in loggers]
    for logger in loggers:
        logger.disabled = True
    try:
        yield
    finally:
        for logger, disabled in zip(loggers, before, strict=True):
            logger.disabled = disabled


def _dask_client(scheduler: Any):
    """A connected ``distributed.Client`` and whether this module owns (must close) it."""
    try:
        import distributed
    except ImportError as exc:  # pragma: no cover - depends on the installation
        raise ValueError("backend 'dask' needs dask.distributed: pip install "
                         "'archquake[cluster]'") from exc
    if isinstance(scheduler, distributed.Client):
        return scheduler, False
    try:
        _probe_scheduler(scheduler, SCHEDULER_TIMEOUT)
        client = distributed.Client(scheduler, timeout=SCHEDULER_TIMEOUT, set_as_default=False)
    except Exception as exc:
        raise ValueError(f"could not connect to the Dask scheduler at {scheduler} within "
                         f"{SCHEDULER_TIMEOUT:g} s: is a dask scheduler running there and "
                         f"reachable? ({type(exc).__name__}: {exc})") from exc
    return client, True


def _probe_scheduler(address: str, timeout: float) -> None:
    """Open and close one Dask connection (with handshake) to ``address``, or raise.

    Done before creating a ``Client``: a ``Client`` that fails to connect blocks for a further
    10 s when it is garbage collected. The probe runs its own event loop in a helper thread, so it
    also works where a loop is already running (e.g. a notebook).
    """
    import asyncio
    from concurrent.futures import ThreadPoolExecutor

    from distributed.comm import connect

    async def probe() -> None:
        comm = await connect(address, timeout=timeout)
        await comm.close()

    with ThreadPoolExecutor(max_workers=1) as pool:
        pool.submit(asyncio.run, probe()).result()


def _dask(task: Task, chunks: list[Chunk], workers: int | None,
          client: Any) -> Iterator[tuple[int, dict, float]]:
    """Run the chunks on a Dask cluster; a cluster that can no longer finish them is a
    :class:`StudyError` (scheduler lost, no worker for :data:`DASK_WORKER_TIMEOUT`, a chunk
    that killed the workers that ran it), not an endless wait or a Dask traceback."""
    import distributed
    import distributed.comm

    address = getattr(getattr(client, "scheduler", None), "address", None) or "?"
    futures = []
    returned = 0
    try:
        futures = client.map(_run_chunk, chunks, task=task, pure=False)
        chunk_of = {future.key: chunk for future, chunk in zip(futures, chunks, strict=True)}
        finished = distributed.as_completed(futures, loop=client.loop, raise_errors=False)
        without_workers_since = None
        next_check = time.monotonic()
        while not finished.is_empty():
            for future in finished.next_batch(block=False):
                unfinished = f"{len(futures) - returned} of {len(futures)}"
                yield _dask_result(future, chunk_of[future.key], address, unfinished)
                returned += 1
                future.release()
            if finished.has_ready():
                continue
            now = time.monotonic()
            if now >= next_check:  # is the cluster still able to finish the study?
                next_check = now + 0.5
                unfinished = f"{len(futures) - returned} of {len(futures)}"
                if client.status not in ("running", "connecting"):
                    raise _scheduler_lost(address, unfinished)
                if _dask_worker_count(client) == 0:
                    without_workers_since = without_workers_since or now
                    if now - without_workers_since >= DASK_WORKER_TIMEOUT:
                        raise StudyError(
                            f"the Dask cluster at {address} has had no worker for "
                            f"{DASK_WORKER_TIMEOUT:g} s, with {unfinished} chunks "
                            f"unfinished: start workers (dask worker "
                            f"{address}) and resume the study")
                else:
                    without_workers_since = None
            time.sleep(0.02)
    except (ConnectionError, distributed.comm.CommClosedError) as exc:
        # the scheduler went away between two of the checks above (a reset connection while
        # fetching a result or polling): the same lost cluster, said the same way
        unfinished = f"{len(futures) - returned} of {len(futures)}" if futures else "all"
        raise _scheduler_lost(address, unfinished) from exc
    finally:
        with suppress(Exception):  # the cluster may be gone
            client.cancel([f for f in futures if not f.done()])


def _dask_worker_count(client: Any) -> int | None:
    """Number of workers the scheduler knows (None if it cannot be asked)."""
    try:
        info = client.scheduler_info(n_workers=0)
    except Exception:
        return None
    count = info.get("n_workers", None) if hasattr(info, "get") else None
    return None if count is None else int(count)


def _scheduler_lost(address: str, unfinished: str) -> StudyError:
    return StudyError(f"lost the connection to the Dask scheduler at {address}, with "
                      f"{unfinished} chunks unfinished: was it stopped? Restart the cluster and "
                      f"resume the study")


def _dask_result(future: Any, chunk: Chunk, address: str, unfinished: str):
    """``(index, columns, seconds)`` of a finished Dask future, or the reason it has none."""
    import distributed

    if future.status == "cancelled":
        raise _scheduler_lost(address, unfinished)
    if future.status == "error":
        exc = future.exception()
        if isinstance(exc, distributed.KilledWorker):
            raise StudyError(
                f"chunk {chunk.index} (items {chunk.start}..{chunk.stop - 1}) was lost with "
                f"every Dask worker that ran it ({exc}); a worker may have run out of memory. "
                f"Fix the cause and resume the study")
    return future.result()  # the task's own exception, if any, propagates unchanged


_RUNNERS = {"serial": _serial, "processes": _processes, "dask": _dask}


def default_backend(backend: str | None = None, workers: Any = None, scheduler: Any = None,
                    pool: Any = None) -> str:
    """The backend of a study: ``backend`` if given, else ``"dask"`` with a scheduler,
    ``"processes"`` with workers or a pool, else :data:`archquake.defaults.DEFAULT_BACKEND` (in
    this process) -- the one rule of the Python API, the command line and the report.

    Parameters
    ----------
    backend : str, optional
        An explicit choice, returned as it is (:func:`run_study` validates it).
    workers, scheduler, pool : optional
        The other execution options of :func:`run_study`; only whether they are given counts.

    Returns
    -------
    str
        ``backend``, ``"dask"``, ``"processes"`` or the default.
    """
    if backend is not None:
        return backend
    if scheduler is not None:
        return "dask"
    if workers is not None or pool is not None:
        return "processes"
    return DEFAULT_BACKEND


def _check_execution(backend: str | None, workers: Any, scheduler: Any,
                     pool: Any = None) -> tuple[str, int | None]:
    backend = default_backend(backend, workers, scheduler, pool)
    if backend not in BACKENDS:
        raise ValueError(f"unknown backend {backend!r}; choose one of {', '.join(BACKENDS)}")
    if pool is not None:
        if backend != "processes":
            raise ValueError(f"pool is only used by backend 'processes', not {backend!r}")
        if not hasattr(pool, "submit"):
            raise ValueError(f"pool must be a concurrent.futures executor (process_pool()), "
                             f"got {type(pool).__name__}")
        if workers is not None:
            raise ValueError("workers must be None when a pool is given (the pool decides)")
        workers = getattr(pool, "_max_workers", None)
        if scheduler is not None:
            raise ValueError(f"scheduler is only used by backend 'dask', not {backend!r}")
        return backend, workers
    if workers is not None:
        workers = _check_count("workers", workers)
    if backend == "processes" and workers is None:
        workers = os.cpu_count() or 1
    if backend == "serial" and workers not in (None, 1):
        raise ValueError(f"backend 'serial' runs one worker; got workers={workers}")
    if backend == "dask":
        if workers is not None:
            raise ValueError("workers must be None with backend 'dask': the Dask cluster decides "
                             "how many workers run")
        if scheduler is None:
            raise ValueError("backend 'dask' needs scheduler='tcp://HOST:PORT' (the address of a "
                             "running dask scheduler) or a distributed.Client")
        if isinstance(scheduler, str):
            match = _SCHEDULER_ADDRESS.match(scheduler)
            if match is None or not 1 <= int(match.group(3)) <= 65535:
                raise ValueError(f"scheduler must be an address 'tcp://HOST:PORT' (PORT in "
                                 f"1..65535), got {scheduler!r}")
        elif not hasattr(scheduler, "submit"):
            raise ValueError(f"scheduler must be an address 'tcp://HOST:PORT' or a "
                             f"distributed.Client, got {type(scheduler).__name__}")
    elif scheduler is not None:
        raise ValueError(f"scheduler is only used by backend 'dask', not {backend!r}")
    return backend, workers


# --------------------------------------------------------------------------------------------
# Checkpoint directory
# --------------------------------------------------------------------------------------------


def task_name(task: Callable) -> str:
    """``module.qualname`` of a task (recorded in ``study.json`` and checked on resume).

    Parameters
    ----------
    task : callable
        A task function, or a :func:`functools.partial` of one (named after the function).

    Returns
    -------
    str
    """
    func = getattr(task, "func", task)  # functools.partial
    return f"{getattr(func, '__module__', '?')}.{getattr(func, '__qualname__', repr(func))}"


def chunk_path(out_dir: str | os.PathLike, index: int) -> Path:
    """Path of the checkpoint file of chunk ``index``: ``DIR/chunks/chunk-000123.npz``.

    Parameters
    ----------
    out_dir : str or os.PathLike
        The study directory ``DIR``.
    index : int
        Chunk number.

    Returns
    -------
    pathlib.Path
    """
    return Path(out_dir) / CHUNK_DIR / f"chunk-{index:06d}.npz"


def _save_chunk(out_dir: Path, chunk: Chunk, columns: dict[str, np.ndarray],
                seconds: float) -> None:
    with atomic_path(chunk_path(out_dir, chunk.index)) as tmp, open(tmp, "wb") as f:
        np.savez(f, __chunk__=np.array([chunk.index, chunk.start, chunk.stop]),
                 __seconds__=np.array(seconds), **columns)


def _load_chunk(out_dir: Path, chunk: Chunk) -> tuple[dict[str, np.ndarray], float]:
    """The columns and the time of a saved chunk; a ValueError naming the file if it cannot be
    read (damaged, not a chunk file, or another chunk's)."""
    path = chunk_path(out_dir, chunk.index)
    try:
        with np.load(path, allow_pickle=False) as data:
            stored = data["__chunk__"].tolist()
            if stored != [chunk.index, chunk.start, chunk.stop]:
                raise ValueError(f"it holds chunk (index, start, stop) = {stored}, not "
                                 f"{[chunk.index, chunk.start, chunk.stop]}")
            seconds = float(data["__seconds__"])
            columns = {k: data[k] for k in data.files if not k.startswith(_RESERVED_PREFIX)}
    except Exception as exc:  # BadZipFile, EOFError, KeyError, refused pickles, ...
        raise ValueError(f"{path} cannot be read ({type(exc).__name__}: {exc})") from exc
    return columns, seconds


PLAN_WORDS = {"task": "the kind of study (task)", "seed": "the seed",
              "n_items": "the number of items the study analyses (n_items: its arches)",
              "chunk_size": "the items per chunk (chunk_size: the model's default, or the one "
                            "given to the study)",
              "archquake_version": "the version of archquake"}
"""What a study's record holds beside its settings, in words (:func:`_difference`)."""


def _difference(stored: Mapping, expected: Mapping) -> str | None:
    """Description of the first recorded setting that differs, or None: the kind of study,
    its settings by name (``setting 'sample_size' differs``, which the command line says as
    its option), then what the study derives from them (:data:`PLAN_WORDS`), in words."""
    if stored.get("task") != expected["task"]:
        return (f"{PLAN_WORDS['task']} differs: the directory has {stored.get('task')!r}, this "
                f"study is {expected['task']!r}")
    difference = _settings_difference(stored.get("settings", {}), expected["settings"])
    if difference is not None:
        return difference
    for key in ("seed", "n_items", "chunk_size", "archquake_version"):
        if stored.get(key) != expected[key]:
            return (f"{PLAN_WORDS[key]} differs: the directory has {stored.get(key)!r}, this "
                    f"study has {expected[key]!r}")
    return None


def _settings_difference(old: Mapping, new: Mapping) -> str | None:
    """The first setting by name that ``new`` lacks, adds or changes, or None."""
    for key in sorted(set(old) | set(new)):
        if key not in old:
            return f"setting {key!r} is new (the directory has no such setting)"
        if key not in new:
            return f"setting {key!r} is missing (the directory has {key}={old[key]!r})"
        if old[key] != new[key]:
            return (f"setting {key!r} differs: the directory has {old[key]!r}, this study has "
                    f"{new[key]!r}")
    return None


@dataclass(frozen=True)
class SavedStudy:
    """A study started in a directory, as a run with ``resume=True`` finds it
    (:func:`resumable_study`).

    Attributes
    ----------
    directory : Path
        The study directory.
    record : dict
        What its ``study.json`` records (the plan's :meth:`StudyPlan.describe`, the task's name
        and the version of archquake): a run continues the study only if it records the same.
    """

    directory: Path
    record: dict

    def chunk_columns(self) -> frozenset[str] | None:
        """Names of the columns of the saved chunks (those of the first one, in index order).

        Returns
        -------
        frozenset of str or None
            None where no chunk is saved yet, or the first one cannot be read (a run computes a
            damaged chunk again, with a warning).
        """
        saved = sorted((self.directory / CHUNK_DIR).glob("chunk-*.npz"))
        if not saved:
            return None
        try:
            with np.load(saved[0], allow_pickle=False) as data:
                return frozenset(k for k in data.files if not k.startswith(_RESERVED_PREFIX))
        except Exception:  # BadZipFile, EOFError, ...: recomputed by the run
            return None


def resumable_study(out_dir: str | os.PathLike | None) -> SavedStudy | None:
    """The study that :func:`run_study` continues in ``out_dir`` with ``resume=True``.

    The one reading of a study directory for a resume: :func:`run_study` checks with it that
    the directory holds the same study before it reuses a chunk, and a caller that must know
    more before it starts asks it too (a record-based study compares its record files with
    the stored ones; a report resumes a study only where one was started).

    Parameters
    ----------
    out_dir : str, os.PathLike or None
        The study directory (None: no directory, so nothing to resume).

    Returns
    -------
    SavedStudy or None
        The study started there, or None where none was (no ``study.json``: no directory, an
        empty one, or one that holds something else).

    Raises
    ------
    ValueError
        If ``study.json`` cannot be read or holds no study's record, naming the file and the
        way out.

    Examples
    --------
    >>> import tempfile
    >>> from archquake.execution import StudyPlan, resumable_study, run_study
    >>> def one_task(chunk):
    ...     return {"item": chunk.items}
    >>> with tempfile.TemporaryDirectory() as out:
    ...     before = resumable_study(out)
    ...     plan = StudyPlan({"n": 1}, seed=1, n_items=2, chunk_size=1)
    ...     _ = run_study(one_task, plan, out, backend="serial", progress=False)
    ...     saved = resumable_study(out)
    ...     before, saved.record["settings"], sorted(saved.chunk_columns())
    (None, {'n': 1}, ['item'])
    """
    if out_dir is None:
        return None
    out_dir = Path(out_dir)
    study_json = out_dir / STUDY_JSON
    if not study_json.is_file():
        return None
    try:
        stored = read_json(study_json)
        if not isinstance(stored, dict):
            raise ValueError(f"{study_json} holds a JSON {type(stored).__name__}, not the "
                             "record of a study")
    except ValueError as exc:
        raise ValueError(f"cannot resume: {exc}; it records what the study computes, so the "
                         f"saved chunks cannot be checked without it: restore it, or delete "
                         f"{out_dir} to start again") from exc
    return SavedStudy(out_dir, stored)


def _prepare_directory(out_dir: Path, record: dict, resume: bool) -> None:
    """Create the study directory or check that it continues the same study."""
    study_json = out_dir / STUDY_JSON
    if out_dir.exists() and not out_dir.is_dir():
        raise ValueError(f"out_dir {out_dir} exists and is not a directory")
    non_empty = out_dir.is_dir() and any(out_dir.iterdir())
    if non_empty and not resume:
        raise ValueError(f"out_dir {out_dir} exists and is not empty; pass resume=True "
                         "(--resume) to continue the study saved there, or choose another "
                         "directory")
    if non_empty:
        saved = resumable_study(out_dir)
        if saved is None:
            raise ValueError(f"cannot resume: {out_dir} is not empty but holds no {STUDY_JSON}; "
                             "choose another directory")
        difference = _difference(saved.record, record)
        if difference is not None:
            raise ValueError(f"cannot resume the study in {out_dir}: {difference}; use the same "
                             "settings or another directory")
        for leftover in (out_dir / CHUNK_DIR).glob(".*.tmp"):  # from an interrupted write
            with suppress(FileNotFoundError):
                leftover.unlink()
    (out_dir / CHUNK_DIR).mkdir(parents=True, exist_ok=True)
    if not study_json.is_file():
        write_json(study_json, record)


# --------------------------------------------------------------------------------------------
# Driver
# --------------------------------------------------------------------------------------------


def _concatenate(results: dict[int, dict[str, np.ndarray]], n_chunks: int) -> pd.DataFrame:
    names = list(results[0])
    for index in range(n_chunks):
        if list(results[index]) != names:
            raise ValueError(f"chunk {index} returned columns {list(results[index])}, chunk 0 "
                             f"returned {names}: every chunk must return the same columns")
    return pd.DataFrame({name: np.concatenate([results[i][name] for i in range(n_chunks)])
                         for name in names})


def run_study(
    task: Task,
    plan: StudyPlan,
    out_dir: str | os.PathLike | None = None,
    *,
    backend: str | None = None,
    workers: int | None = None,
    scheduler: Any = None,
    resume: bool = False,
    progress: bool = True,
    pool: Any = None,
    save: bool = True,
) -> pd.DataFrame:
    """Evaluate every chunk of a study and return all rows as one tidy table.

    Parameters
    ----------
    task : callable
        Module-level function ``task(chunk) -> dict[str, array]`` (picklable by reference for the
        ``"processes"`` and ``"dask"`` backends). It receives a :class:`Chunk` and returns the
        columns of its rows: one-dimensional arrays of equal length, with numbers, booleans or
        fixed-width strings; every chunk must return the same column names (not starting with
        ``"__"``, which is reserved for the checkpoint files). It must draw item
        ``i``'s random numbers only from ``chunk.generators()`` / ``chunk.seed_sequences()``.
    plan : StudyPlan
        Settings, seed, number of items and chunk size.
    out_dir : str or os.PathLike, optional
        Study directory for checkpoints (``study.json``, ``chunks/``) and, at the end, the
        results (``results.parquet``, ``results.csv``, ``summary.json``; see
        :func:`archquake.results_io.save_study`). It must not exist or be empty unless
        ``resume=True``. Default: nothing is written.
    backend : {"serial", "processes", "dask"}, optional
        ``"serial"``: in this process. ``"processes"``: a pool of ``workers`` fresh local
        processes (``concurrent.futures.ProcessPoolExecutor``, ``"spawn"`` context).
        ``"dask"``: the workers of the Dask cluster at ``scheduler``. Default:
        :func:`default_backend` (``"dask"`` with a scheduler, ``"processes"`` with workers or a
        pool, else ``"serial"``).
    workers : int, optional
        Number of local processes (``"processes"``; default ``os.cpu_count()``); must be None or
        1 with ``"serial"`` and None with ``"dask"``.
    scheduler : str or distributed.Client, optional
        Address ``"tcp://HOST:PORT"`` of a running Dask scheduler (connection attempt limited to
        :data:`SCHEDULER_TIMEOUT` seconds), or a connected ``distributed.Client`` (left open).
    resume : bool, optional
        Continue the study saved in ``out_dir``: finished chunks are loaded, not recomputed.
        The directory must hold the same task, settings, seed, number of items, chunk size and
        ``archquake_version``. An empty or missing ``out_dir`` simply starts the study.
    progress : bool, optional
        Show a progress bar over chunks on stderr (advancing as chunks finish).
    pool : concurrent.futures.Executor, optional
        With backend ``"processes"``: run the chunks on this existing pool (from
        :func:`process_pool`; left open) instead of starting one; ``workers`` must then be None.
    save : bool, optional
        Write the results to ``out_dir`` at the end (default); False leaves that to the
        caller, who saves the table with more (a study's summary) and would otherwise write
        the same table twice. The checkpoints are written either way.

    Returns
    -------
    pandas.DataFrame
        The rows of all chunks in chunk (hence item) order, with a fresh ``RangeIndex``.
        ``table.attrs["study"]`` holds the metadata: settings, seed, chunking, task,
        ``archquake_version``, backend, workers and ``timings`` (``wall_seconds``: this call;
        ``task_seconds``: summed time inside the task over all chunks, including resumed ones;
        ``chunks_computed`` / ``chunks_resumed``).

    Raises
    ------
    ValueError
        Invalid plan, backend, workers or scheduler; an unreachable scheduler; an output
        directory that is not empty (without ``resume``) or that holds a different study (the
        message names the setting that differs); a task result that is not a valid table.
        An exception raised by the task propagates unchanged; chunks finished before it stay
        saved, so the study can be resumed once the cause is fixed.
    archquake.errors.StudyError
        The Dask cluster can no longer finish the study: the connection to its scheduler is
        lost, it has had no worker for :data:`DASK_WORKER_TIMEOUT` seconds, or a chunk was
        lost with every worker that ran it. The message names the cause and the unfinished
        chunks; finished chunks stay saved, so the study can be resumed.
    KeyboardInterrupt
        Ctrl-C (the command line also turns SIGTERM into it): the workers of a pool started
        here are terminated at once; finished chunks stay saved.

    Notes
    -----
    The results do not depend on the backend, the number of workers, the chunk completion order
    or interruptions and resumption: every item has its own seed sequence
    (:func:`item_seed_sequence`) and the rows are assembled in chunk order.

    Examples
    --------
    A task, defined in an importable module so that worker processes can load it:

    >>> def draw_task(chunk):
    ...     values = [rng.uniform(0.0, chunk.settings["high"]) for rng in chunk.generators()]
    ...     return {"item": chunk.items, "value": np.array(values)}
    >>> plan = StudyPlan({"high": 2.0}, seed=1, n_items=10, chunk_size=4)
    >>> table = run_study(draw_task, plan, backend="serial", progress=False)
    >>> len(table), table.attrs["study"]["n_chunks"]
    (10, 3)

    The same study on 4 local processes, saved in (and resumable from) ``out``:
    ``run_study(draw_task, plan, "out", workers=4)``; on a Dask cluster:
    ``run_study(draw_task, plan, "out", scheduler="tcp://10.0.0.5:8786")``.
    """
    if not isinstance(plan, StudyPlan):
        raise ValueError(f"plan must be a StudyPlan, got {type(plan).__name__}")
    if not callable(task):
        raise ValueError(f"task must be a callable task(chunk) -> dict, got {task!r}")
    backend, workers = _check_execution(backend, workers, scheduler, pool)
    if resume and out_dir is None:
        raise ValueError("resume=True needs out_dir, the directory of the study to continue")

    started = time.perf_counter()
    client, owned = _dask_client(scheduler) if backend == "dask" else (None, False)
    failed = True
    try:
        table = _run(task, plan, out_dir, backend, workers, client, resume, progress, started,
                     pool, save)
        failed = False
        return table
    finally:
        if owned:
            # after a lost cluster, closing the client logs distributed's own tracebacks
            # (its reconnection, cancelled) before our message: ours says it all
            with _quiet_loggers(("distributed", "tornado") if failed else ()):
                client.close()


def _run(task: Task, plan: StudyPlan, out_dir: str | os.PathLike | None, backend: str,
         workers: int | None, client: Any, resume: bool, progress: bool,
         started: float, pool: Any = None, save: bool = True) -> pd.DataFrame:
    """:func:`run_study` once the options are checked and a Dask client (if any) connected."""
    if client is not None:
        workers = len(client.nthreads())  # record the size of the cluster
    record = {"format": STUDY_FORMAT, "format_version": STUDY_FORMAT_VERSION,
              "archquake_version": __version__, "task": task_name(task), **plan.describe(),
              "created": datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds")}
    results: dict[int, dict[str, np.ndarray]] = {}
    seconds: dict[int, float] = {}
    if out_dir is not None:
        out_dir = Path(out_dir)
        _prepare_directory(out_dir, record, resume)
        record = read_json(out_dir / STUDY_JSON)  # keeps the original creation time on resume
        for chunk in plan.chunks():
            if chunk_path(out_dir, chunk.index).is_file():
                try:
                    results[chunk.index], seconds[chunk.index] = _load_chunk(out_dir, chunk)
                except ValueError as exc:  # chunks are deterministic: computing it again is safe
                    warnings.warn(f"{exc}; the chunk is recomputed", StudyWarning, stacklevel=3)
    resumed = len(results)
    todo = [chunk for chunk in plan.chunks() if chunk.index not in results]

    with tqdm(total=plan.n_chunks, initial=resumed, unit="chunk", desc="study",
              file=sys.stderr, disable=not progress, dynamic_ncols=True) as bar:
        if todo:
            finished = _RUNNERS[backend](task, todo, workers,
                                         pool if backend == "processes" else client)
            try:
                for index, columns, elapsed in finished:
                    if out_dir is not None:
                        _save_chunk(out_dir, plan.chunk(index), columns, elapsed)
                    results[index], seconds[index] = columns, elapsed
                    bar.update(1)
            except StudyError as exc:
                where = ("" if out_dir is None else
                         f" ({len(results)} finished chunks are saved in {out_dir}; resume "
                         f"with resume=True, --resume on the command line)")
                raise StudyError(f"{exc}{where}") from exc
            finally:
                finished.close()  # cancels what is still queued if we stop early

    table = _concatenate(results, plan.n_chunks)
    metadata = {key: value for key, value in record.items()
                if key not in ("format", "format_version")}
    metadata.update(backend=backend, workers=workers, timings={
        "wall_seconds": time.perf_counter() - started,
        "task_seconds": float(sum(seconds.values())),
        "chunks_computed": len(todo),
        "chunks_resumed": resumed,
    })
    table.attrs["study"] = metadata
    if out_dir is not None and save:
        save_study(out_dir, table, metadata=metadata)
    return table

