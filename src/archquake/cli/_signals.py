"""Stopping a command: Ctrl-C (SIGINT), and SIGTERM around worker processes.

Ctrl-C stops any command with ``archquake: interrupted (SIGINT)`` and exit status 130. During a
study on worker processes, and in a command that starts a process of its own (``reproduce``),
SIGTERM does the same (128 + 15), which terminates the workers; the study's finished chunks are
kept and ``--resume`` continues it. A worker also ends when its parent dies without stopping it
(``kill -9``): :func:`archquake.execution.die_with_parent`. Elsewhere SIGTERM keeps its
default action: a Python handler runs only between bytecodes, so it would wait for a long
compiled loop to return.
"""

from __future__ import annotations

import contextlib
import signal
import sys


class Terminated(KeyboardInterrupt):
    """SIGTERM, raised like Ctrl-C so that a study stops the same clean way."""


def raise_terminated(signum, frame):
    """The SIGTERM handler around worker processes: raise :class:`Terminated`."""
    raise Terminated()


@contextlib.contextmanager
def sigterm_as_interrupt(on: bool):
    """With ``on`` (a study on worker processes), SIGTERM raises :class:`Terminated` in the
    block; the previous handler is restored after it."""
    previous = None
    if on:
        with contextlib.suppress(ValueError):  # not the main thread: signals stay as they are
            previous = signal.signal(signal.SIGTERM, raise_terminated)
    try:
        yield
    finally:
        if previous is not None:
            signal.signal(signal.SIGTERM, previous)


def interrupted(exc: KeyboardInterrupt, args) -> int:
    """Say that the command was interrupted (and how to resume a study); the exit status,
    128 + the signal number."""
    signum = signal.SIGTERM if isinstance(exc, Terminated) else signal.SIGINT
    hint = ""
    if getattr(args, "resume", None) is not None and getattr(args, "out", None):
        hint = (f"; rerun with --resume to continue the study in {args.out} (its finished "
                "chunks are kept)")
    print(f"archquake: interrupted ({signal.Signals(signum).name}){hint}", file=sys.stderr)
    return 128 + signum
