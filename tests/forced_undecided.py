"""A rigid-block model forced to leave chosen analyses undecided (a test stand-in).

:func:`force` replaces the analyses of :class:`archquake.rigid_blocks.RigidBlockModel` (its
``outcomes`` over a grid of pulses and its ``outcome`` under one motion) by a pattern of the
ground acceleration relative to the structure's load multiplier, ``m = |a| / k`` (k of the
mechanism the first pulse opens; the smaller one under a record):

    m < 1: rest;  1 <= m < 1.6: recovery;  1.6 <= m < 1.9: undecided (t_p <= 0.45 s under a
    pulse; recovery above);  1.9 <= m < 2.4: collapse;  2.4 <= m < 2.5: undecided;  m >= 2.5:
    collapse.

So the accounting of the studies is tested without depending on when the solver gives up.
Every call is recorded in ``calls`` (``(duration, signed amplitude [g], status)``; duration nan
under a record), so a test counts the undecided analyses independently of the study.
"""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np

from archquake.constants import GRAVITY
from archquake.status import Status

UNDECIDED_BAND = (1.6, 1.9)
"""The undecided band below the failure, in m = |a| / k."""
COLLAPSE_FROM = 1.9
"""The lowest m that collapses (decided)."""
SECOND_BAND = (2.4, 2.5)
"""An undecided band among the collapses, in m."""
SHORT_PULSE = 0.45
"""Pulses up to this duration [s] have the first undecided band; longer ones recover there."""


def status_of(m: float, duration: float = math.nan) -> Status:
    """The forced outcome at ``m = |a| / k`` under a pulse of ``duration`` [s] (nan: a
    record)."""
    if m < 1.0:
        return Status.REST
    if m < UNDECIDED_BAND[0]:
        return Status.RECOVERY
    if m < COLLAPSE_FROM:
        return (Status.UNDECIDED if math.isnan(duration) or duration <= SHORT_PULSE
                else Status.RECOVERY)
    if SECOND_BAND[0] <= m < SECOND_BAND[1]:
        return Status.UNDECIDED
    return Status.COLLAPSE


def force(monkeypatch) -> list:
    """Replace the rigid-block analyses by the forced pattern; returns the list of calls."""
    from archquake.rigid_blocks import RigidBlockModel

    calls = []

    def multiplier(model, signed_g):
        k_l, k_r = model.load_multipliers
        return k_l if signed_g < 0 else k_r

    def outcomes(self, durations, amplitudes_g, motion="oppenheim"):
        d, a = np.broadcast_arrays(np.asarray(durations, dtype=float),
                                   np.asarray(amplitudes_g, dtype=float))
        status = np.full(d.shape, int(Status.REST), dtype=np.int64)
        for index in np.ndindex(d.shape):
            if a[index] != 0.0:
                tp, amp = float(d[index]), float(a[index])
                code = status_of(abs(amp) / multiplier(self, amp), tp)
                calls.append((tp, amp, code))
                status[index] = int(code)
        return {"status": status, "half_cycle": np.zeros(d.shape, dtype=np.int64),
                "collapse_time": np.full(d.shape, np.nan)}

    def outcome(self, motion):
        pga = float(np.max(np.abs(motion.values))) / GRAVITY
        code = status_of(pga / min(self.load_multipliers))
        calls.append((math.nan, pga, code))
        return SimpleNamespace(status=code, collapse_time=math.nan,
                               collapsed=code is Status.COLLAPSE,
                               decided=code is not Status.UNDECIDED)

    monkeypatch.setattr(RigidBlockModel, "outcomes", outcomes)
    monkeypatch.setattr(RigidBlockModel, "outcome", outcome)
    return calls
