"""Codes and defaults of the compiled engine: states, outcome codes, the outcome vector.

Plain integers and floats (the compiled code reads them as constants); the outcome codes are the
values of :class:`archquake.status.Status`.
"""

from __future__ import annotations

from ...status import Status

# --- state of the arch while integrating
REST_STATE = -1
"""The arch moves rigidly with the ground (no mechanism active)."""
MECH_L = 0
"""Mech-l moving; also the index of Mech-l in a packed pair of tables."""
MECH_R = 1
"""Mech-r moving; also the index of Mech-r in a packed pair of tables."""

# --- outcome codes (Status as plain integers for the compiled code)
UNDECIDED = int(Status.UNDECIDED)
"""The outcome is not decided yet (:attr:`Status.UNDECIDED`)."""
STATUS_REST = int(Status.REST)
"""Code of :attr:`Status.REST`."""
STATUS_RECOVERY = int(Status.RECOVERY)
"""Code of :attr:`Status.RECOVERY`."""
STATUS_COLLAPSE = int(Status.COLLAPSE)
"""Code of :attr:`Status.COLLAPSE`."""
STATUS_NAMES = {int(s): s.label for s in (Status.REST, Status.RECOVERY, Status.COLLAPSE)}
"""Code -> label (``"rest"``, ``"recovery"``, ``"collapse"``)."""

# --- check of the continuation after the decision (record mode): OUT_CONTRADICTION
AGREES = 0
"""The continuation agrees with the decision (or there was nothing to check)."""
RECOVERY_GOES_OVER = 1
"""Recovery decided, but the free motion crossed ``theta_cr`` away from ``theta_u`` or reached
the kinematic limit."""
COLLAPSE_COMES_BACK = 2
"""Collapse decided, but the motion had more impacts than decided or came to rest."""
COLLAPSE_ELSEWHERE = 3
"""Collapse decided in one half cycle, but the kinematic limit was reached in another one."""
CONTRADICTIONS = {
    RECOVERY_GOES_OVER: "recovery was decided, but the free motion afterwards passed theta_cr "
                        "away from theta_u (or reached the kinematic limit)",
    COLLAPSE_COMES_BACK: "collapse was decided, but the motion afterwards had more impacts "
                         "than decided (or came to rest)",
    COLLAPSE_ELSEWHERE: "collapse was decided in one half cycle, but the kinematic limit was "
                        "reached in another one",
}
"""Code of ``OUT_CONTRADICTION`` -> what the continuation did."""

# --- outcome vector returned by the compiled driver: indices
OUT_STATUS = 0
"""Status code."""
OUT_HALF_CYCLE = 1
"""Half cycle of the collapse (1 = before any impact), 0 if none."""
OUT_IMPACTS = 2
"""Impacts before the decision (for a collapse, half cycle - 1)."""
OUT_COLLAPSE_TIME = 3
"""Last crossing of ``theta_cr`` away from ``theta_u`` before the collapse [s], else nan."""
OUT_MAX_PHI = 4
"""Largest ``phi = theta_u - theta`` [rad], reached before the decision or, for a recovery, still
to come after it (from the energy, :mod:`~archquake.fourlink.engine.rules`); for a collapse
``theta_u - theta_lo`` of the collapsing mechanism (its kinematic limit)."""
OUT_DECISION_TIME = 5
"""Time [s] at which the outcome was decided: the kinematic limit reached during the excitation,
or the end of the excitation (steps end on it: it is the last breakpoint of the motion)."""
OUT_STEPS = 6
"""Integration steps (attempted, rejected ones included) and waits at rest."""
OUT_TRUNCATED = 7
"""1.0 if the analysis stopped at the limit on the number of steps."""
OUT_CONTRADICTION = 8
"""Code of the check of the continuation (:data:`AGREES` ...)."""
OUT_CONTRADICTION_TIME = 9
"""Time [s] of the contradiction, nan if none."""
OUT_SIZE = 10
"""Length of the outcome vector."""

# --- defaults
DEFAULT_RTOL = 1e-11
"""Relative tolerance of the local error of a step [-]."""
DEFAULT_ATOL = 1e-13
"""Absolute tolerance of the local error of a step [rad, rad/s]."""
DEFAULT_REST_VELOCITY = 1e-6
"""Speed below which an arch that has just impacted, and is not pushed open, is at rest [rad/s]."""
DEFAULT_MAX_STEP = 0.25
"""Largest step [s] (keeps two roots of an event function from hiding inside one step)."""
DEFAULT_MAX_STEPS = 2_000_000
"""Safety limit on the number of steps of one analysis [-] (:data:`OUT_STEPS`)."""
