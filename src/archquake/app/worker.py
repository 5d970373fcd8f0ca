"""The body of a worker process (:mod:`archquake.app.jobs`): run one task, say how far it is,
send its result, as JSON.

The fork server imports this module before it forks any worker, so everything a task needs is
imported here once -- numpy, scipy, matplotlib on its file-only backend, the library's modules
that the tasks call -- and numba's compiled functions are loaded from their cache by one small
analysis of each kind (:func:`warm_up`, a second or two, once): every worker forked from the
server has them.
"""

from __future__ import annotations

import json
import os
import signal
import sys
import threading
import traceback

import matplotlib
import tqdm.std

matplotlib.use("Agg")

import matplotlib.pyplot  # noqa: E402, F401  (imported once, in the fork server)

from ..fourlink import FourLinkModel  # noqa: E402, F401
from ..plotting import plot_failure_domain  # noqa: E402, F401
from ..rigid_blocks import RigidBlockModel  # noqa: E402, F401
from ..studies.comparison import domain_disagreement  # noqa: E402, F401
from ..studies.failure_domain import domain_of  # noqa: E402, F401
from .tasks import TASKS  # noqa: E402
from .views import json_ready  # noqa: E402

# The progress bars of the library's studies take a lock shared between processes (a
# semaphore) unless given one: a worker ended while it holds one (a job cancelled, the server
# stopped) leaves the semaphore behind, which the resource tracker reports as leaked when the
# server stops. A worker's bars are its own: a lock of its threads is enough.
tqdm.std.tqdm.set_lock(threading.RLock())


def warm_up() -> None:
    """Run one small analysis of each kind the tasks run (time histories, outcomes and grids of
    both models, a limit analysis), so that their compiled functions are loaded."""
    from ..geometry import GRAVITY, circular_arch
    from ..ground_motion import oppenheim_pulse
    from ..rigid_blocks import BlockSettings

    arch = circular_arch(10.0, 2.75, 1.5, 5)
    pulse = oppenheim_pulse(-GRAVITY, 0.2)
    four_link = FourLinkModel.from_arch(arch)
    four_link.simulate(pulse)
    four_link.outcome(pulse)
    four_link.outcomes([0.2], [-1.0])
    blocks = RigidBlockModel(arch, BlockSettings(settle_time=0.5))
    blocks.simulate(pulse, record_every=40)
    blocks.outcome(pulse)


try:
    warm_up()
except Exception as exc:  # a worker then loads what it needs itself
    print(f"archquake app: warning: warm-up of the workers failed: {exc}", file=sys.stderr)


def main(connection, kind: str, text: str) -> None:
    """Run the task ``kind`` on the JSON description ``text``, writing to ``connection``
    ``{"progress": [done, total, text]}`` as it goes and then ``{"result": ...}`` or
    ``{"error": message}``.

    A :class:`ValueError` is bad input: its message is the answer (naming the field, as the
    library does). Anything else is a failure of the program: its message is the answer and its
    traceback goes to the server's standard error.
    """
    os.setsid()  # a process group of its own: cancelling the job ends it with its children
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C stops the server, which ends us

    def send(message: dict) -> None:
        connection.send_bytes(json.dumps(json_ready(message), allow_nan=False).encode())

    def report(done: int, total: int, what: str) -> None:
        send({"progress": [int(done), int(total), str(what)]})

    try:
        send({"result": TASKS[kind](json.loads(text), report)})
    except ValueError as exc:
        send({"error": str(exc)})
    except Exception as exc:  # a failure of the program, not of the input
        traceback.print_exc(file=sys.stderr)
        send({"error": f"{type(exc).__name__}: {exc}"})
    finally:
        connection.close()


__all__ = ["main"]
