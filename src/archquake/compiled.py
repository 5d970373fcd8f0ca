"""Whether a compiled engine is ready on this processor, and the one note a command prints
before it compiles one.

The two engines (the four-link model's integrator, :mod:`archquake.fourlink.engine`, and the
rigid-block solver, :mod:`archquake.rigid_blocks.solver`) are compiled by numba the first time
they run on a processor, and cached on disk (``__pycache__`` beside the modules, or
``NUMBA_CACHE_DIR``): later processes load them in a fraction of a second. The first run after
an installation (or after a change of an engine's source, or on another processor) compiles
them, about 20 s for the four-link engine and 40 s for the rigid-block solver on one core,
with nothing else to show for it: a command that is about to compile one says so first, once,
on stderr (:func:`announce`), so that a first run is not taken for a hung one.

The notes are printed only by the process in which :func:`enable_notes` was called (the
command line's; a program that imports archquake prints nothing), never by its workers: where
workers will compile an engine, the process that starts them announces it
(:func:`announce_all`, :func:`announce_for_workers`). Each model names its engine's entry point
(:func:`archquake.fourlink.model.engines`, :func:`archquake.rigid_blocks.model.engines`,
through :meth:`archquake.models.ModelSpec.engines`), and a study those of its model and its
screen (:meth:`archquake.studies.arch_sample.StudySample.engines`); this module imports neither
model.
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Iterable
from typing import Any

FOUR_LINK, RIGID_BLOCKS = "the four-link engine", "the rigid-block solver"
"""Names of the engines in the notes."""

COMPILE_SECONDS = {FOUR_LINK: 20, RIGID_BLOCKS: 45}
"""About how long each engine takes to compile on one core of a two-core machine [s] (measured
from an empty cache: 42-44 s the rigid-block solver, about 20 s the four-link engine)."""


def is_ready(dispatcher) -> bool:
    """Whether a numba function (``cache=True``) runs without compiling: compiled in this
    process, or in numba's cache on disk for this processor with its current source.

    Reads numba's cache index the way numba does (a stale index, of another version of the
    source, is empty); where that cannot be read (another numba, a function without a cache),
    True: no note is better than a wrong one.

    Parameters
    ----------
    dispatcher : numba.core.registry.CPUDispatcher
        The function.

    Returns
    -------
    bool
    """
    if dispatcher.overloads:
        return True
    try:
        index = dispatcher._cache._cache_file._load_index()
        magic = dispatcher.targetctx.codegen().magic_tuple()
        return any(key[1] == magic for key in index)
    except Exception:  # noqa: BLE001 - a numba whose internals differ: say nothing
        return True


_NOTES: dict[str, Any] = {"enabled": False, "noted": set()}


def enable_notes(enabled: bool = True) -> None:
    """Let :func:`announce` print in this process (False: stop it, and forget what it
    announced)."""
    _NOTES["enabled"] = bool(enabled)
    _NOTES["noted"] = set()


def announce(engine: str, dispatcher, file=None) -> bool:
    """Print, once, that ``engine`` is about to be compiled, if it is not ready
    (:func:`is_ready`) and the notes are enabled (:func:`enable_notes`). Whether it is ready is
    read at the first call for the engine, the later ones return at once: a command may build
    thousands of models.

    Parameters
    ----------
    engine : str
        :data:`FOUR_LINK` or :data:`RIGID_BLOCKS`.
    dispatcher : numba.core.registry.CPUDispatcher
        The engine's entry point, whose compilation compiles the rest.
    file : file, optional
        Where to print (default ``sys.stderr``).

    Returns
    -------
    bool
        Whether the note was printed.
    """
    if not _NOTES["enabled"] or engine in _NOTES["noted"]:
        return False
    _NOTES["noted"].add(engine)  # decided once (reading the cache's index costs 0.2 ms)
    if is_ready(dispatcher):
        return False
    seconds = COMPILE_SECONDS.get(engine)
    about = f" (about {seconds} s)" if seconds else ""
    from tqdm import tqdm  # over a progress bar, not inside it

    tqdm.write(f"archquake: note: compiling {engine} for this processor{about}, once: later "
               f"runs load it", file=sys.stderr if file is None else file)
    return True


def engines_of(warm_up: Callable[[], Any] | None) -> Iterable[tuple[str, Any]]:
    """The ``(engine, dispatcher)`` pairs that a worker's ``warm_up`` compiles: its attribute
    ``engines``, a callable returning them (none without it)."""
    engines = getattr(warm_up, "engines", None)
    return engines() if callable(engines) else ()


def announce_all(engines: Iterable[tuple[str, Any]]) -> None:
    """:func:`announce` every ``(engine, dispatcher)`` pair of ``engines``."""
    for engine, dispatcher in engines:
        announce(engine, dispatcher)


def announce_for_workers(warm_up: Callable[[], Any] | None) -> None:
    """Announce, in the process that starts a pool of workers, the engines that their
    ``warm_up`` will compile (:func:`engines_of`)."""
    announce_all(engines_of(warm_up))


__all__ = ["COMPILE_SECONDS", "FOUR_LINK", "RIGID_BLOCKS", "announce", "announce_all",
           "announce_for_workers", "enable_notes", "engines_of", "is_ready"]
