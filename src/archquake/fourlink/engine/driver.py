"""The event-driven driver: one analysis, from rest (or a given state) to its outcome.

The driver loop of :func:`integrate` follows scipy's ``solve_ivp``: take a step with error control
(Sect. II.4 of [1]_), look for events inside it on its dense output (Sect. II.6 of [1]_), locate
them [2]_, handle them (the rules of Sects. 4.4 and 5.3 of [3]_), record. Its parts are
the small compiled helpers of this module and of :mod:`~archquake.fourlink.engine.stepper` (the
step), :mod:`~archquake.fourlink.engine.rules` (activation, impact, decision) and
:mod:`~archquake.fourlink.engine.tables`. How each is compiled was chosen by measurement:

- helpers called at one place are inlined into the driver (``inline="always"``: numba copies
  their code there, so a call costs nothing at run time and compiles about as the code would);
  those of every step take scalars only: an array handed to an inlined helper is counted as a
  new reference (two atomic operations per array and call), which cost 20 % of an analysis;
- the step, its dense output and the other leaves that take arrays are compiled on their own,
  without reference counting (``_nrt=False``: they allocate nothing), with a declared signature
  when they are called with literal constants (one compilation for every call site).

One loop of the driver::

    1. decide      the excitation is over: the outcome follows from the state (energy rules)
    2. stop?       decided and followed long enough, the end, a contradiction, the step limit
    3. at rest     wait for the ground to activate a mechanism
    4. step        one Dormand-Prince step of the moving mechanism, with error control
    5. events      on the step's dense output, split at a turning point (theta monotonic on each
                   part): crossings of theta_cr, then the impact at theta_u or the kinematic limit
    6. accept      no terminal event: the step's end is the new state
    7. locate      a terminal event, to round-off, on the integrator's own solution
    8. handle      kinematic limit: collapse (the end); impact: the other mechanism takes over

One driver serves the outcome-only path (``follow = 0``: it stops as soon as the outcome, with the
collapse time, is known) and the recording path used for time histories (``record``, and the
motion is followed after the decision). Followed after the decision, the motion checks the
decision (record mode checks itself): a recovery whose free motion passes ``theta_cr`` away from
``theta_u`` or reaches the kinematic limit, a collapse that has an impact more than decided or
comes to rest, or a collapse in another half cycle than decided, is a contradiction; the driver
stops there and returns its code in ``out[OUT_CONTRADICTION]`` (:data:`~.codes.CONTRADICTIONS`),
which the Python wrappers turn into a ``RuntimeError`` naming the case.

References
----------
.. [1] Hairer, E., Norsett, S. P. and Wanner, G. (1993). Solving Ordinary Differential
   Equations I: Nonstiff Problems, 2nd ed. Springer, Sects. II.4-II.6.
.. [2] Shampine, L. F. and Thompson, S. (2000). Event location for ordinary differential
   equations. Computers and Mathematics with Applications 39(5-6), 43-54.
.. [3] The paper, Sects. 4.3-4.4 (Eqs. (6)-(8)) and 5.3.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from ...ground_motion import (
    ANALYTIC_KINDS,
    HARMONIC,
    LINEAR,
    STEP,
    analytic_duration,
    evaluate,
)
from ._types import F8, F8_2D, I8
from .codes import (
    AGREES,
    COLLAPSE_COMES_BACK,
    COLLAPSE_ELSEWHERE,
    CONTRADICTIONS,
    DEFAULT_ATOL,
    DEFAULT_MAX_STEP,
    DEFAULT_MAX_STEPS,
    DEFAULT_REST_VELOCITY,
    DEFAULT_RTOL,
    OUT_COLLAPSE_TIME,
    OUT_CONTRADICTION,
    OUT_CONTRADICTION_TIME,
    OUT_DECISION_TIME,
    OUT_HALF_CYCLE,
    OUT_IMPACTS,
    OUT_MAX_PHI,
    OUT_SIZE,
    OUT_STATUS,
    OUT_STEPS,
    OUT_TRUNCATED,
    RECOVERY_GOES_OVER,
    REST_STATE,
    STATUS_COLLAPSE,
    STATUS_RECOVERY,
    STATUS_REST,
    UNDECIDED,
)
from .rules import decide_outcome, find_activation, impact_rule, rest_coefficients
from .stepper import (
    dense_coefficients,
    dense_root,
    dense_value,
    dop853_step,
    initial_step,
    motion_rhs,
)
from .tables import MechanismTable, pack_pair

EVENT_NONE, EVENT_IMPACT, EVENT_LIMIT = 0, 1, 2
"""Terminal events of a step: none, impact at ``theta_u``, kinematic limit ``theta_lo``."""

_SIG_PUSH = F8_2D(F8_2D, I8, F8, F8, F8, F8, F8)


# ---------------------------------------------------------------------------------------------
# Record
# ---------------------------------------------------------------------------------------------


@numba.njit(_SIG_PUSH, cache=True)
def _push(buf, n, v0, v1, v2, v3, v4):
    """Write row ``n`` of a record buffer (its first ``buf.shape[1]`` values), growing it.

    Every argument is given, and the signature is declared (see
    :mod:`~archquake.fourlink.engine._types`); the rows are copied by a loop: a slice assignment
    brings numba's shape-mismatch error
    formatting, seconds of compilation."""
    if n >= buf.shape[0]:
        new = np.empty((2 * buf.shape[0], buf.shape[1]))
        for i in range(n):
            for j in range(buf.shape[1]):
                new[i, j] = buf[i, j]
        buf = new
    vals = (float(v0), float(v1), float(v2), float(v3), float(v4))
    for j in range(buf.shape[1]):
        buf[n, j] = vals[j]
    return buf


@numba.njit(cache=True, inline="always")
def _record_samples(rec, nrec, next_sample, t_until, t, hh, th, thd, m, seg, record_dt, Fd):
    """Record the dense output of the step from ``t`` (size ``hh``) [s] every ``record_dt`` [s]
    up to ``t_until`` [s]; rows ``(t, theta, theta', state, segment)``.

    Returns ``(rec, nrec, next_sample)``."""
    while next_sample < t_until:
        xq = (next_sample - t) / hh
        rec = _push(rec, nrec, next_sample, dense_value(xq, 0, th, Fd),
                    dense_value(xq, 1, thd, Fd), m, seg)
        nrec += 1
        next_sample += record_dt
    return rec, nrec, next_sample


# ---------------------------------------------------------------------------------------------
# Parts of the driver loop
# ---------------------------------------------------------------------------------------------


@numba.njit(cache=True, inline="always")
def _next_breakpoint(bps, ib, t):
    """Index of the first breakpoint of the ground motion after ``t`` [s], from ``ib`` on."""
    while ib < bps.size and bps[ib] <= t:
        ib += 1
    return ib


@numba.njit(cache=True, inline="always")
def _decision_after_excitation(m, th, thd, activated, impacts, last_out, max_phi, tab, c_lr,
                               c_rl):
    """The outcome decided when the excitation is over, from the state of the arch: at rest
    (recovery if it ever moved, else rest) or moving (:func:`~.rules.decide_outcome`).

    Returns ``(status, half_cycle, decided_impacts, collapse_time, max_phi, pending)``:
    ``pending`` when a collapse is decided but its point of no return (the crossing of
    ``theta_cr`` away from ``theta_u``) is still ahead, ``collapse_time`` [s] the crossing
    already passed if not; ``max_phi`` [rad] the largest rotation to come."""
    scal = tab[0]
    if m == REST_STATE:
        status = STATUS_RECOVERY if activated else STATUS_REST
        return status, 0, impacts, np.nan, max_phi, False
    status, extra, peak, known = decide_outcome(m, th, thd, tab, c_lr, c_rl)
    if status != STATUS_COLLAPSE:
        return status, 0, impacts, np.nan, max(max_phi, peak), False
    half_cycle = impacts + 1 + extra  # the collapse comes after `extra` more impacts
    m_collapse = m if extra % 2 == 0 else 1 - m
    max_phi = scal[m_collapse, 0] - scal[m_collapse, 2]
    if known:
        return status, half_cycle, half_cycle - 1, last_out, max_phi, False
    return status, half_cycle, half_cycle - 1, np.nan, max_phi, True


@numba.njit(cache=True, inline="always")
def _wait_at_rest(t, duration, t_end, rest, kind, params, times, values, bps):
    """At rest from ``t`` [s]: the first instant at which the ground activates a mechanism,
    and which one (``REST_STATE`` if none before the end of the excitation: the ground is
    then still for ever, and the arch rests until ``t_end``)."""
    if t < duration:
        return find_activation(t, min(duration, t_end), rest, kind, params, times, values, bps)
    return t_end, REST_STATE


@numba.njit(cache=True, inline="always")
def _step_size(t, h, t_stop, bnext, max_step):
    """Size of the next attempt from ``t`` [s]: ``h`` [s], at most ``max_step`` [s], shortened to
    land on ``t_stop`` [s] if it would pass it. A step that lands on the breakpoint ``bnext``
    [s] of the ground motion evaluates the ground at its end on the step's side of it: times
    from ``tcap`` on are read as ``tcap_left`` (just before the breakpoint).

    Returns ``(hh, landing, tcap, tcap_left)``."""
    hh = min(h, max_step)
    landing = t + hh >= t_stop
    if landing:
        hh = t_stop - t
    if landing and t_stop == bnext:
        return hh, landing, bnext, bnext * (1.0 - 2.0 ** -52) if bnext > 0.0 else bnext
    return hh, landing, np.inf, np.inf


@numba.njit(cache=True, inline="always")
def _error_control(err, hh, h, landing, rejected):
    """Accept the step of size ``hh`` [s] if its error norm ``err`` is below 1, and choose the
    next size (Hairer, Norsett & Wanner, Sect. II.4, with the exponent 1/8 of DOP853): at most
    10 times larger, not larger after a rejection, at most 5 times smaller; a step shortened to
    land on a breakpoint leaves the size ``h`` [s] as it was.

    Returns ``(accepted, next size [s])``."""
    if err < 1.0:
        fac = 10.0 if err == 0.0 else min(10.0, 0.9 * err ** (-1.0 / 8.0))
        if rejected:
            fac = min(1.0, fac)
        if not landing or hh >= h:
            h = hh * fac
        return True, h
    return False, hh * max(0.2, 0.9 * err ** (-1.0 / 8.0))


@numba.njit(cache=True, inline="always")
def _may_hold_event(th, n0, thd, n1, th_u, th_cr, th_lo):
    """Whether a step from ``theta = th`` to ``n0`` [rad] may hold an event: it ends above
    ``theta_u`` or below ``theta_lo``, ``theta_cr`` is not strictly on one side of it, or
    ``theta'`` changes sign (a turning point). Otherwise theta is monotonic on the step and no
    event is in it: the dense output is not needed."""
    return (n0 > th_u or n0 < th_lo or (th - th_cr) * (n0 - th_cr) <= 0.0
            or (thd > 0.0) != (n1 > 0.0))


@numba.njit(cache=True, inline="always")
def _turning_point(thd, f1, n1, Fd):
    """Fraction of the step [-] at which ``theta'`` changes sign, from ``thd`` at its start to
    ``n1`` at its end [rad/s] (``phi`` has a local extremum there), 2.0 if it does not.

    A motion that starts from rest (``thd = 0``, from an activation) moves first with the sign
    of ``theta'' = f1`` [rad/s^2]; its turning point is looked for from a small fraction of the
    step on (``theta'`` vanishes at the start itself), so that an arch that opens and closes
    again within its first step has its impact after the start, not at it."""
    x0 = 0.0
    s0 = thd
    if thd == 0.0:
        x0 = 1e-9
        s0 = f1
    if s0 != 0.0 and n1 != 0.0 and (s0 > 0.0) != (n1 > 0.0):
        return dense_root(x0, 1.0, 1, thd, Fd, 0.0)
    return 2.0


@numba.njit(cache=True, inline="always")
def _crossing(xa, xb, ga, gb, level, th, Fd):
    """Fraction of the step [-] in ``[xa, xb]``, on which theta goes monotonically from ``ga``
    to ``gb`` [rad], at which it crosses ``level`` [rad]; -1.0 if it does not."""
    if (ga - level) * (gb - level) < 0.0 or (gb == level and ga != level):
        return dense_root(xa, xb, 0, th, Fd, level)
    return -1.0


@numba.njit(cache=True, inline="always")
def _terminal_event(xa, xb, ga, gb, th_u, th_lo, th, Fd):
    """The event that ends the motion of the mechanism on the part ``[xa, xb]`` of the step on
    which theta goes monotonically from ``ga`` to ``gb`` [rad]: theta rises through
    ``theta_u`` (impact) or falls through ``theta_lo`` (kinematic limit).

    Returns ``(event, fraction of the step)``, ``(EVENT_NONE, 1.0)`` if none."""
    if gb > th_u and ga <= th_u:
        return EVENT_IMPACT, dense_root(xa, xb, 0, th, Fd, th_u)
    if gb < th_lo and ga >= th_lo:
        return EVENT_LIMIT, dense_root(xa, xb, 0, th, Fd, th_lo)
    return EVENT_NONE, 1.0


@numba.njit(cache=True, inline="always")
def _locate_event(t, th, thd, f0, f1, x_event, xa, xb, hh, level, m, tab, xg_step, tcap,
                  tcap_left, kind, params, times, values, rtol, atol, K, Fd):
    """The event at fraction ``x_event`` of the step (found on the dense output, on the part
    ``[xa, xb]`` of the step where theta is monotonic) polished on the integrator's own
    solution: steps from ``t`` to the event time, corrected by Newton (``theta'`` is the slope),
    until theta hits ``level`` [rad] to round-off. Newton stays on the part: a motion that
    leaves ``theta_u`` and comes back within one step has two roots, its start and its return.

    Returns ``(h_event, theta'_event)``: the time from ``t`` [s] and ``theta'`` [rad/s]."""
    h_ev = x_event * hh
    thd_ev = dense_value(x_event, 1, thd, Fd)
    for _ in range(4):
        p0, p1, _nf, _err = dop853_step(t, th, thd, f0, f1, h_ev, m, tab, xg_step, tcap, tcap_left,
                                  kind, params, times, values, rtol, atol, K)
        thd_ev = p1
        if p1 == 0.0 or abs(p0 - level) <= 4e-16 * max(1.0, abs(level)):
            break
        h_new = h_ev - (p0 - level) / p1
        if not (xa * hh < h_new <= xb * hh):
            break
        h_ev = h_new
    return h_ev, thd_ev


@numba.njit(cache=True, inline="always")
def _outcome_vector(status, half_cycle, decided_impacts, collapse_time, max_phi, decision_time,
                    steps, truncated, contradiction, contradiction_time):
    """The outcome vector (indices ``OUT_*`` of :mod:`~archquake.fourlink.engine.codes`)."""
    out = np.full(OUT_SIZE, np.nan)
    collapse = status == STATUS_COLLAPSE
    out[OUT_STATUS] = status
    out[OUT_HALF_CYCLE] = half_cycle if collapse else 0
    out[OUT_IMPACTS] = decided_impacts
    out[OUT_COLLAPSE_TIME] = collapse_time if collapse else np.nan
    out[OUT_MAX_PHI] = max_phi
    out[OUT_DECISION_TIME] = decision_time
    out[OUT_STEPS] = steps
    out[OUT_TRUNCATED] = 1.0 if truncated else 0.0
    out[OUT_CONTRADICTION] = contradiction
    out[OUT_CONTRADICTION_TIME] = contradiction_time
    return out


# ---------------------------------------------------------------------------------------------
# The driver
# ---------------------------------------------------------------------------------------------


@numba.njit(cache=True)
def integrate(tab, c_lr, c_rl, kind, params, times, values, bps, duration, t_start, t_end, mech0,
         theta0, thetadot0, rtol, atol, rest_velocity, max_step, max_steps, record, record_dt,
         follow):
    """Integrate one analysis; see the module docstring for the loop and
    :mod:`~archquake.fourlink.engine.rules` for the rules.

    ``(kind, params, times, values)`` is the ground motion (:func:`compiled_motion`), ``bps``
    its breakpoints and ``duration`` [s] its end; the arch starts at ``t_start`` [s] in state
    ``mech0`` (``REST_STATE`` or a mechanism at ``theta0`` [rad], ``thetadot0`` [rad/s]); the
    analysis ends at ``t_end`` [s] at the latest, and ``follow`` [s] after the decision (``0``:
    at the decision, once the collapse time is known; ``inf``: at ``t_end``).

    Returns ``(out, rec, imp, crs)``: ``out`` the outcome vector (``OUT_*`` indices); with
    ``record``, ``rec`` rows ``(t, theta, theta', state, segment)``, ``imp`` rows ``(t, mechanism
    before, theta' before, theta' after)`` and ``crs`` rows ``(t, mechanism, +1 outward / -1
    inward)`` of the crossings of ``theta_cr`` (every ``record_dt`` [s] and at every event),
    else empty arrays.
    """
    scal = tab[0]
    rest = rest_coefficients(tab)  # theta'' from rest at theta_u: the activation test
    K = np.empty((16, 2))  # stages of the last step
    Fd = np.empty((7, 2))  # its dense output
    cap = 256 if record else 1
    rec, imp, crs = np.empty((cap, 5)), np.empty((cap, 4)), np.empty((cap, 3))
    nrec = nimp = ncrs = 0

    # the state: time, mechanism (or rest), theta, theta'; and the integrator's
    t, m, th, thd = t_start, mech0, theta0, thetadot0
    h = min(1e-3, max_step)  # size of the next step
    fresh = True  # a motion starts: estimate its first step
    fsal = False  # theta'' at the state known from the last stage of the last step
    f1 = 0.0  # theta'' at the state
    ib = _next_breakpoint(bps, 0, t)  # next breakpoint of the ground motion
    steps = impacts = seg = 0  # seg: segment of the record (between events)
    activated = m >= 0
    # the outcome
    status = UNDECIDED
    half_cycle = decided_impacts = 0
    collapse_time = decision_time = np.nan
    pending = False  # collapse decided, its point of no return still ahead
    last_out = np.nan  # last crossing of theta_cr away from theta_u
    max_phi = scal[m, 0] - th if m >= 0 else 0.0
    truncated = False
    contradiction = AGREES
    contradiction_time = np.nan
    next_sample = t + record_dt
    if record:
        rec = _push(rec, 0, t, th if m >= 0 else np.nan, thd, m, seg)
        nrec = 1

    while True:
        # -------- 1. the excitation is over: decide the outcome from the state
        if status == UNDECIDED and t >= duration:
            status, half_cycle, decided_impacts, collapse_time, max_phi, pending = (
                _decision_after_excitation(m, th, thd, activated, impacts, last_out, max_phi,
                                           tab, c_lr, c_rl))
            decision_time = t
        # -------- 2. stop
        if status != UNDECIDED and not pending and t >= decision_time + follow:
            break
        if t >= t_end or contradiction != AGREES:
            break
        if steps >= max_steps:
            truncated = True
            break

        # -------- 3. at rest: wait for the ground to activate a mechanism
        if m == REST_STATE:
            t, m = _wait_at_rest(t, duration, t_end, rest, kind, params, times, values, bps)
            steps += 1
            if record:
                rec = _push(rec, nrec, t, np.nan, 0.0, REST_STATE, seg)
                nrec += 1
            ib = _next_breakpoint(bps, ib, t)
            if m != REST_STATE:  # a mechanism starts from theta_u
                th, thd = scal[m, 0], 0.0
                activated = fresh = True
                fsal = False
                seg += 1
                if record:
                    rec = _push(rec, nrec, t, th, thd, m, seg)
                    nrec += 1
                    next_sample = t + record_dt
            continue

        # -------- 4. one step of the moving mechanism, with error control
        th_u, th_cr, th_lo = scal[m, 0], scal[m, 1], scal[m, 2]
        bnext = bps[ib] if ib < bps.size else np.inf
        t_stop = min(bnext, t_end)
        xg_step = evaluate(t, kind, params, times, values) if kind == STEP else np.nan
        f0 = thd
        if not fsal:
            f1 = motion_rhs(t, th, thd, m, tab, xg_step, np.inf, np.inf, kind, params, times,
                            values)
        if fresh:
            h = initial_step(t, th, thd, f1, m, tab, xg_step, kind, params, times, values, rtol,
                              atol, max_step)
            fresh = False
        rejected = False
        while True:  # attempts, until the local error is accepted
            hh, landing, tcap, tcap_left = _step_size(t, h, t_stop, bnext, max_step)
            n0, n1, nf, err = dop853_step(t, th, thd, f0, f1, hh, m, tab, xg_step, tcap, tcap_left,
                                    kind, params, times, values, rtol, atol, K)
            steps += 1
            accepted, h = _error_control(err, hh, h, landing, rejected)
            if accepted or steps >= max_steps:
                break
            rejected = True

        # -------- 5. events in the step, on its dense output
        event, x_event = EVENT_NONE, 1.0
        xa, xb = 0.0, 1.0  # the part of the step that holds the event
        if record or _may_hold_event(th, n0, thd, n1, th_u, th_cr, th_lo):
            dense_coefficients(t, th, thd, n0, n1, hh, m, tab, xg_step, tcap, tcap_left, kind,
                               params, times, values, K, Fd)
            x_turn = _turning_point(thd, f1, n1, Fd)
            for part in range(2):  # theta is monotonic on [0, x_turn] and on [x_turn, 1]
                if part == 1 and x_turn >= 1.0:
                    break
                xa, xb = (0.0, min(x_turn, 1.0)) if part == 0 else (x_turn, 1.0)
                ga = th if xa == 0.0 else dense_value(xa, 0, th, Fd)
                gb = n0 if xb == 1.0 else dense_value(xb, 0, th, Fd)
                if part == 0 and x_turn < 1.0 and status == UNDECIDED:
                    max_phi = max(max_phi, th_u - gb)  # phi at a local extremum
                # a crossing of theta_cr precedes an impact or the limit on the same part
                x_cross = _crossing(xa, xb, ga, gb, th_cr, th, Fd)
                if x_cross >= 0.0:
                    tc = t + x_cross * hh
                    outward = gb < ga
                    if outward:
                        last_out = tc
                        if pending:  # the point of no return of a decided collapse
                            collapse_time, pending = tc, False
                        if status == STATUS_RECOVERY and contradiction == AGREES:
                            contradiction, contradiction_time = RECOVERY_GOES_OVER, tc
                    if record:
                        crs = _push(crs, ncrs, tc, m, 1.0 if outward else -1.0, 0.0, 0.0)
                        ncrs += 1
                event, x_event = _terminal_event(xa, xb, ga, gb, th_u, th_lo, th, Fd)
                if event != EVENT_NONE:
                    break
            if record:
                rec, nrec, next_sample = _record_samples(rec, nrec, next_sample,
                                                         t + x_event * hh, t, hh, th, thd, m,
                                                         seg, record_dt, Fd)

        # -------- 6. no terminal event: accept the step
        if event == EVENT_NONE:
            t = t_stop if landing else t + hh
            th, thd, f1 = n0, n1, nf
            # the last stage is theta'' at the new point, unless the ground changes there
            fsal = not (landing and t_stop == bnext)
            if status == UNDECIDED:
                max_phi = max(max_phi, th_u - th)
            if landing:  # on a breakpoint (else t is before the next one)
                ib = _next_breakpoint(bps, ib, t)
            if record:
                rec = _push(rec, nrec, t, th, thd, m, seg)
                nrec += 1
            continue

        # -------- 7. locate the event to round-off
        level = th_u if event == EVENT_IMPACT else th_lo
        h_ev, thd_ev = _locate_event(t, th, thd, f0, f1, x_event, xa, xb, hh, level, m, tab,
                                     xg_step, tcap, tcap_left, kind, params, times, values, rtol,
                                     atol, K, Fd)
        t = t + h_ev
        if record:
            rec = _push(rec, nrec, t, level, thd_ev, m, seg)
            nrec += 1

        # -------- 8. handle it
        if event == EVENT_LIMIT:  # the kinematic limit: collapse, the end of the analysis
            th, thd = th_lo, thd_ev
            if status == UNDECIDED:  # during the excitation: in this half cycle
                status, half_cycle, decided_impacts = STATUS_COLLAPSE, impacts + 1, impacts
                decision_time, collapse_time, max_phi = t, last_out, th_u - th_lo
            elif status == STATUS_RECOVERY and contradiction == AGREES:
                contradiction, contradiction_time = RECOVERY_GOES_OVER, t
            elif impacts != half_cycle - 1 and contradiction == AGREES:
                contradiction, contradiction_time = COLLAPSE_ELSEWHERE, t
            pending = False
            break
        # impact at theta_u: the other mechanism takes over (or the arch comes to rest); the
        # arch arrives with theta' >= 0 (a turning point just before it may leave -0 or so)
        thd_ev = max(thd_ev, 0.0)
        m_before = m
        m, th, thd, thd_after = impact_rule(m, thd_ev, t, c_lr, c_rl, rest_velocity, scal, rest,
                                        kind, params, times, values)
        impacts += 1
        seg += 1
        fsal = False
        ib = _next_breakpoint(bps, ib, t)
        if status == STATUS_COLLAPSE and (impacts > half_cycle - 1 or m == REST_STATE):
            contradiction, contradiction_time = COLLAPSE_COMES_BACK, t
        if record:
            imp = _push(imp, nimp, t, m_before, thd_ev, thd_after, 0.0)
            nimp += 1
            rec = _push(rec, nrec, t, th, thd, m, seg)
            nrec += 1

    out = _outcome_vector(status, half_cycle, decided_impacts, collapse_time, max_phi,
                          decision_time, steps, truncated, contradiction, contradiction_time)
    return out, rec[:nrec], imp[:nimp], crs[:ncrs]


@numba.njit(cache=True)
def _grid(tab, c_lr, c_rl, kind, params0, times0, values0, amplitudes, durations, rtol, atol,
          rest_velocity, max_step, max_steps, rest_state, record, follow):
    """Outcomes of a scaled template motion for many (amplitude, duration) pairs.

    ``rest_state`` (:data:`~.codes.REST_STATE`) and ``record`` (False) are arguments, not
    constants written here: numba would compile ``integrate`` (and every function it calls) once
    more
    for the literal values of constants, beside the compilation for the calls from Python."""
    n = amplitudes.size
    status = np.empty(n, dtype=np.int8)
    half_cycle = np.empty(n, dtype=np.int16)
    impacts = np.empty(n, dtype=np.int32)
    collapse_time = np.empty(n)
    max_phi = np.empty(n)
    steps = np.empty(n, dtype=np.int64)
    contradiction = np.empty(n, dtype=np.int8)
    params = params0.copy()
    for q in range(n):
        a = amplitudes[q]
        tp = durations[q]
        times = times0 * tp
        values = values0 * a
        if kind >= HARMONIC:  # analytic: params[0] scales the acceleration, params[1] time
            params[0] = params0[0] * a
            params[1] = params0[1] * tp
            duration = analytic_duration(kind, params)
            bps = np.array([0.0, duration])
        else:
            duration = times[times.size - 1]
            bps = times
        out, _, _, _ = integrate(tab, c_lr, c_rl, kind, params, times, values, bps, duration, 0.0,
                            np.inf, rest_state, 0.0, 0.0, rtol, atol, rest_velocity, max_step,
                            max_steps, record, 1.0, follow)
        status[q] = int(out[OUT_STATUS])
        half_cycle[q] = int(out[OUT_HALF_CYCLE])
        impacts[q] = int(out[OUT_IMPACTS])
        collapse_time[q] = out[OUT_COLLAPSE_TIME]
        max_phi[q] = out[OUT_MAX_PHI]
        steps[q] = int(out[OUT_STEPS])
        contradiction[q] = int(out[OUT_CONTRADICTION])
    return status, half_cycle, impacts, collapse_time, max_phi, steps, contradiction


# ---------------------------------------------------------------------------------------------
# Python entry points
# ---------------------------------------------------------------------------------------------


def check_restitution(c_lr, c_rl) -> tuple[float, float]:
    r"""Validate the coefficients of restitution: finite, > 0, and ``c_lr c_rl <= 1``.

    A single coefficient may exceed 1: for an irregular arch the computed :math:`c_v` (Eq. (8)
    in [1]_) is a ratio of the rates of two different coordinates (:math:`\theta` of Mech-l and
    :math:`\theta'` of Mech-r), not of one speed. What an impact may not do is create energy.
    The kinetic energy ratio of one impact, :math:`c^2 M_{to}(\theta_u) / M_{from}(\theta_u)`,
    is at most 1 for the computed coefficients (Cauchy-Schwarz, see
    :mod:`archquake.fourlink.impact`), and over a pair of impacts (l -> r -> l) the masses cancel,

    .. math::

        \frac{K''}{K} = c_{lr}^2 \frac{M_r}{M_l}\; c_{rl}^2 \frac{M_l}{M_r}
        = (c_{lr} c_{rl})^2 \le 1:

    the outcome decision after the excitation relies on that product being at most 1
    (:mod:`archquake.fourlink.engine.rules`).

    Parameters
    ----------
    c_lr, c_rl : float
        Coefficients of restitution of the impacts Mech-l -> Mech-r and Mech-r -> Mech-l [-].

    Returns
    -------
    (float, float)
        ``(c_lr, c_rl)`` as floats.

    Raises
    ------
    ValueError
        If a coefficient is not a finite number > 0, or if ``c_lr c_rl > 1`` (beyond a
        round-off of 1e-12).

    References
    ----------
    .. [1] The paper, Sect. 4.4, Eq. (8).
    """
    out = []
    for name, c in (("c_lr", c_lr), ("c_rl", c_rl)):
        try:
            c = float(c)
        except (TypeError, ValueError) as exc:
            raise ValueError(f"restitution {name} must be a finite number > 0, got {c!r}") from exc
        if not (math.isfinite(c) and c > 0.0):
            raise ValueError(f"restitution {name} must be a finite number > 0, got {c!r}")
        out.append(c)
    if out[0] * out[1] > 1.0 + 1e-12:
        raise ValueError(f"restitution c_lr * c_rl must be <= 1 (no energy gained over a pair of "
                         f"impacts), got {out[0]!r} * {out[1]!r} = {out[0] * out[1]!r}")
    return out[0], out[1]


def compiled_motion(motion):
    """A ground motion in the form the compiled driver takes.

    The arrays are writable copies: the motion's own arrays are read-only, and numba compiles a
    function again for read-only arrays; the grids of :func:`outcomes_grid` are writable.

    Parameters
    ----------
    motion : GroundMotion
        The ground motion.

    Returns
    -------
    kind : int
        Kind of the motion (``STEP``, ``LINEAR`` or an analytic kind of
        :mod:`archquake.ground_motion`).
    params : ndarray
        Parameters of an analytic motion (its amplitude [m/s^2] and time scale [s] first).
    times : ndarray
        Sample times of a table motion [s].
    values : ndarray
        Accelerations at ``times`` [m/s^2].
    breakpoints : ndarray
        Times [s] at which the acceleration or its slope may jump, sorted, from 0 to
        ``duration``; a step never crosses one.
    duration : float
        Time [s] from which the ground acceleration is zero for ever.
    """
    kind, params, times, values = motion.compiled()
    params, times, values, bps = (np.array(x, dtype=float) for x in
                                  (params, times, values, motion.breakpoints))
    return int(kind), params, times, values, bps, float(motion.duration)


def contradiction_message(code: int) -> str:
    """What the continuation did, for a nonzero ``out[OUT_CONTRADICTION]``.

    Parameters
    ----------
    code : int
        A code of :data:`~archquake.fourlink.engine.codes.CONTRADICTIONS`.

    Returns
    -------
    str
        Its description (an unknown code is named as such).
    """
    return CONTRADICTIONS.get(int(code), f"unknown contradiction code {code!r}")


def outcomes_grid(table_l: MechanismTable, table_r: MechanismTable, c_lr: float, c_rl: float,
                  durations, amplitudes, motion="oppenheim", *,
                  rtol: float = DEFAULT_RTOL, atol: float = DEFAULT_ATOL,
                  rest_velocity: float = DEFAULT_REST_VELOCITY,
                  max_step: float = DEFAULT_MAX_STEP,
                  continuation: float = 0.0) -> dict[str, np.ndarray]:
    """Outcomes of one arch under many pulses, in one compiled call.

    Every case ``q`` is the template motion scaled to ``amplitudes[q]`` and ``durations[q]``,
    applied to the arch at rest from ``t = 0``, and integrated until its outcome is decided
    (:mod:`~archquake.fourlink.engine.driver`; the rules of
    :mod:`~archquake.fourlink.engine.rules`).

    Parameters
    ----------
    table_l, table_r : MechanismTable
        Tables of Mech-l and Mech-r of the arch (:func:`~archquake.fourlink.engine.tabulate`).
    c_lr, c_rl : float
        Coefficients of restitution of the impacts Mech-l -> Mech-r and Mech-r -> Mech-l [-].
    durations : array_like
        Pulse durations t_p [s] (the time scale of the template: the duration of a pulse, the
        period of a wavelet; ``1`` keeps a record's own time), each > 0.
    amplitudes : array_like
        Signed ground accelerations of the pulse [m/s^2] (``-GRAVITY`` is the paper's -1 g);
        broadcast against ``durations``. For a template record, its scale factor [-].
    motion : str or GroundMotion
        Name of the pulse shape in :data:`archquake.ground_motion.GROUND_MOTIONS` (every analytic
        shape of the registry is ``amplitude * shape(t / duration)``, which is how the cases are
        built), or a template GroundMotion of unit amplitude and unit duration, scaled the same
        way (its times by the duration, its accelerations by the amplitude).
    rtol, atol : float
        Tolerances of the local error of a step [-], [rad and rad/s].
    rest_velocity : float
        Speed after an impact below which the arch comes to rest [rad/s].
    max_step : float
        Largest step [s].
    continuation : float
        Time [s] the motion is followed after the outcome is decided, to check the decision
        against it (0: not checked). A continuation that contradicts the decision raises
        ``RuntimeError``.

    Returns
    -------
    dict of ndarray
        ``status`` (the codes of :class:`archquake.status.Status`: 0 rest, 1 recovery, 2
        collapse), ``half_cycle``, ``impacts``, ``collapse_time`` [s], ``max_phi`` [rad] and
        ``steps`` (integration steps of the analysis), each of the broadcast shape.

    Raises
    ------
    ValueError
        If a coefficient of restitution is invalid (:func:`check_restitution`), a duration is
        not finite and > 0, an amplitude is not finite, ``continuation < 0``, or ``motion`` is
        not a known name or a motion the compiled engine can evaluate.
    RuntimeError
        If an analysis stops before its outcome is decided (the safety limit on the number of
        steps), or if ``continuation > 0`` and the motion after a decision contradicts it.
    """
    from ...ground_motion import GroundMotion, ground_motion

    c_lr, c_rl = check_restitution(c_lr, c_rl)
    durations, amplitudes = np.broadcast_arrays(np.asarray(durations, dtype=float),
                                                np.asarray(amplitudes, dtype=float))
    shape = durations.shape
    if np.any(~np.isfinite(durations)) or np.any(durations <= 0):
        raise ValueError("durations must be finite numbers > 0 [s]")
    if np.any(~np.isfinite(amplitudes)):
        raise ValueError("amplitudes must be finite numbers [m/s^2]")
    if not (continuation >= 0.0):
        raise ValueError(f"continuation must be a time >= 0 [s], got {continuation!r}")
    template = motion if isinstance(motion, GroundMotion) else ground_motion(motion, 1.0, 1.0)
    kind, params, times, values = (np.asarray(x) if i else x
                                   for i, x in enumerate(template.compiled()))
    if kind not in (STEP, LINEAR) + ANALYTIC_KINDS:
        raise ValueError(f"unsupported ground motion kind {kind!r}")
    res = _grid(pack_pair(table_l, table_r), c_lr, c_rl, int(kind),
                np.ascontiguousarray(params, dtype=float), np.ascontiguousarray(times, float),
                np.ascontiguousarray(values, float), np.ascontiguousarray(amplitudes.ravel()),
                np.ascontiguousarray(durations.ravel()), rtol, atol, rest_velocity, max_step,
                DEFAULT_MAX_STEPS, REST_STATE, False, float(continuation))
    *res, contradiction = res

    def case(q):
        return (f"duration {durations.ravel()[q]!r} s, amplitude {amplitudes.ravel()[q]!r} "
                f"m/s^2 ({template.name or motion!r}), c_lr {c_lr!r}, c_rl {c_rl!r}")

    undecided = np.flatnonzero(res[0] == UNDECIDED)
    if undecided.size:
        raise RuntimeError(f"{undecided.size} of {res[0].size} analyses "
                           f"stopped before their outcome was decided ({DEFAULT_MAX_STEPS} "
                           f"steps); the first: {case(int(undecided[0]))}")
    bad = np.flatnonzero(contradiction)
    if bad.size:
        q = int(bad[0])
        raise RuntimeError(f"{bad.size} of {contradiction.size} analyses contradict their "
                           f"decided outcome; the first, {case(q)}: "
                           f"{contradiction_message(contradiction[q])}")
    names = ("status", "half_cycle", "impacts", "collapse_time", "max_phi", "steps")
    return {k: v.reshape(shape) for k, v in zip(names, res, strict=True)}
