r"""The rules of the rocking arch that are not integration: activation from rest, impacts, and
the outcome once the excitation is over [paper, Sects. 4.2-4.4 and 5.3].

Rest and activation
    At rest the arch moves rigidly with the ground, at :math:`\theta_u` of both mechanisms. A
    mechanism starts when its :math:`\ddot\theta` from rest (:math:`\theta = \theta_u`,
    :math:`\dot\theta = 0`) is negative, i.e. when the ground acceleration :math:`\ddot x_g`
    [m/s^2] opens it (Eq. (2) in [1]_):

    .. math::

        \text{Mech-l: } P\,\ddot x_g - F g < 0 \iff \ddot x_g / g < -k_l, \qquad
        \text{Mech-r: } -P\,\ddot x_g - F g < 0 \iff \ddot x_g / g > k_r,

    with :math:`k = -F(\theta_u)/P(\theta_u)` [-] the activation multiplier of each mechanism
    (its limit-analysis load multiplier, Sect. 3 of [1]_). For a piecewise-linear (recorded)
    ground motion the instant of activation between samples is located.
Impact
    When the moving mechanism closes at :math:`\theta_u` the other one takes over at its own
    :math:`\theta_u` with :math:`\dot\theta^+ = -c\,\dot\theta^-` (Sect. 4.4 and Eq. (8) in
    [1]_; :math:`c = c_{lr}` from Mech-l, :math:`c_{rl}` from Mech-r). If then
    :math:`|\dot\theta^+|` is below ``rest_velocity`` [rad/s] and the ground does not open the
    new mechanism, the arch comes to rest (this ends the geometric sequence of ever shorter
    rocking cycles).
Decision after the excitation
    Once :math:`\ddot x_g = 0` for good, the motion between impacts conserves

    .. math::

        E = \tfrac12 M(\theta)\,\dot\theta^2 + V(\theta)

    (Eq. (6) in [1]_ times :math:`\dot\theta`, with :math:`L = \tfrac12\, dM/d\theta` and
    :math:`dV/d\theta = g F`, Eq. (4) in [1]_), and :math:`V` has its maximum on
    :math:`[\theta_{lo}, \theta_u]` at :math:`\theta_{cr}` (Sect. 4.2 of [1]_). From the state
    :math:`(\theta, \dot\theta)` of the moving mechanism (:func:`decide_outcome`):

    1. *this half cycle*: the arch collapses if it is beyond :math:`\theta_{cr}`
       (:math:`\theta \le \theta_{cr}`) and moving away from :math:`\theta_u`
       (:math:`\dot\theta \le 0`) or unable to come back (:math:`E \le V(\theta_{cr})`), or
       if, short of :math:`\theta_{cr}`, it moves away (:math:`\dot\theta < 0`) with
       :math:`E > V(\theta_{cr})`;
    2. otherwise it returns to :math:`\theta_u` with the kinetic energy
       :math:`K = E - V(\theta_u)`, and after the impact the other mechanism (primed) has

       .. math::

           K' = c^2\, \frac{M'(\theta'_u)}{M(\theta_u)}\, K,

       which collapses it, after one more impact, if :math:`K' > V'(\theta'_{cr}) -
       V'(\theta'_u)`;
    3. otherwise the second impact brings back into the first mechanism
       :math:`K'' = c'^2\, (M(\theta_u)/M'(\theta'_u))\, K'`, checked against its own barrier
       :math:`V(\theta_{cr}) - V(\theta_u)` (the arch may have been on its way back with energy
       above it): collapse after two more impacts if it passes;
    4. surviving both arrivals is recovery: two successive impacts multiply the kinetic energy
       at :math:`\theta_u` by :math:`(c_{lr}^2 M_r/M_l)(c_{rl}^2 M_l/M_r) = (c_{lr}
       c_{rl})^2 \le 1` (:func:`archquake.fourlink.engine.check_restitution` refuses a larger
       product), so every later arrival into either mechanism has no more energy than the first
       checked one, which did not pass the barrier.

    The largest :math:`\varphi = \theta_u - \theta` still to come is the root of
    :math:`V(\theta) = E` (or of its counterpart after an impact) below :math:`\theta_u`.

References
----------
.. [1] The paper, Sect. 3, Eq. (2); Sect. 4.2, Eqs. (3)-(4); Sect. 4.3, Eq. (6); Sect. 4.4,
   Eq. (8); Sect. 5.3.
"""

import math

import numba
import numpy as np

from ...ground_motion import HARMONIC, LINEAR, STEP, evaluate
from .codes import MECH_L, MECH_R, REST_STATE, STATUS_COLLAPSE, STATUS_RECOVERY
from .tables import ROW_M, ROW_V, root_function, table_function, table_rhs


@numba.njit(cache=True, inline="always")
def rest_coefficients(tab):
    """``(P/M, gF/M, L/M)`` of Mech-l and Mech-r at ``theta_u``, shape (2, 3): the coefficients of
    ``theta''`` of a mechanism that starts from rest (:func:`_activated`). Inlined into the
    driver, so that they are the very values its right-hand side computes there."""
    scal, cells, breaks, coefs = tab
    out = np.empty((2, 3))
    for m in range(2):
        a, b, c = table_rhs(scal[m, 0], scal[m, 2], scal[m, 4], cells[m], breaks[m], coefs[m])
        out[m, 0] = a
        out[m, 1] = b
        out[m, 2] = c
    return out


@numba.njit(cache=True)
def _activated(xg, rest):
    """Mechanism activated by the ground acceleration ``xg`` [m/s^2] at rest, or -1: the one
    whose ``theta''`` at ``theta_u`` from rest is negative, ``P xg'' - F g < 0`` for Mech-l and
    ``-P xg'' - F g < 0`` for Mech-r [eq. (2) of the paper; ``xg''/g < -k_l`` and
    ``xg''/g > k_r``]; ``rest`` from :func:`rest_coefficients`.

    The same arithmetic as the first ``theta''`` of the motion that starts (the driver's
    right-hand side at ``theta_u`` with ``theta' = 0``): a comparison with the tabulated
    activation acceleration may differ from it in the last bit, and an arch activated with
    ``theta'' >= 0`` closed again at once, at the same instant, for ever."""
    for m in range(2):  # MECH_L, MECH_R
        sign = 1.0 if m == MECH_L else -1.0
        if sign * rest[m, 0] * xg - rest[m, 1] - rest[m, 2] * 0.0 * 0.0 < 0.0:
            return m
    return -1


@numba.njit(cache=True)
def _activated_at(t, rest, kind, params, times, values):
    """Mechanism the ground activates at time ``t`` [s] (:func:`_activated`), or -1."""
    return _activated(evaluate(t, kind, params, times, values), rest)


ACTIVATION_MARGIN = 1e-12
"""Relative margin [-] inside the activation accelerations within which a sample of a
piecewise-linear motion counts as quiet (:func:`_quiet_segments`): it covers the round-off of
the interpolation between two samples."""


@numba.njit(cache=True, inline="always")
def _quiet_segments(i, t_stop, rest, times, values, bps):
    """For a piecewise-linear motion: the index ``i' >= i`` of the first segment
    ``[bps[i'-1], bps[i']]`` that may activate a mechanism, or that ends after ``t_stop``.

    Between two samples the acceleration is linear, so its extremes on a segment are the two
    samples: a segment whose samples both lie inside the activation accelerations of Mech-l
    and Mech-r (``-k_l g < xg'' < k_r g``, from ``rest`` of :func:`rest_coefficients`) by the
    relative :data:`ACTIVATION_MARGIN` cannot activate either mechanism, and is passed over
    without evaluating the motion (the sample scan of :func:`find_activation` would find nothing on
    it). ``bps`` are ``times``, possibly with ``0`` before them (where the ground is still).
    """
    nb = bps.size
    offset = nb - times.size
    # Mech-l starts where a_l xg'' - b_l < 0, Mech-r where -a_r xg'' - b_r < 0 (_activated)
    a_l, b_l = rest[MECH_L, 0], rest[MECH_L, 1]
    a_r, b_r = rest[MECH_R, 0], rest[MECH_R, 1]
    if (times.size == 0 or times[0] < 0.0 or offset < 0 or offset > 1
            or not (a_l > 0.0 and a_r > 0.0)):
        return i
    lo = (b_l / a_l) * (1.0 - ACTIVATION_MARGIN)
    hi = (-b_r / a_r) * (1.0 - ACTIVATION_MARGIN)
    if not (lo < 0.0 < hi):
        return i
    while i < nb and bps[i] <= t_stop:
        j = i - offset  # sample at bps[i]
        v0 = values[j - 1] if j >= 1 else 0.0
        v1 = values[j] if j >= 0 else 0.0
        if not (lo < v0 < hi and lo < v1 < hi):
            break
        i += 1
    return i


@numba.njit(cache=True)
def find_activation(t, t_stop, rest, kind, params, times, values, bps):
    """First instant in ``[t, t_stop)`` [s] at which the ground activates a mechanism from rest.

    Returns ``(time, mechanism)``, ``(t_stop, -1)`` if none. Piecewise-constant motions are
    checked per interval, piecewise-linear ones per segment (one crossing at most; segments whose
    samples stay inside the activation accelerations are passed over by
    :func:`_quiet_segments`), analytic ones on a sampling at 1/512 of their time scale; a
    crossing is then bracketed to round-off by bisection.
    """
    nb = bps.size
    i = np.searchsorted(bps, t, side="right")  # first breakpoint after t
    ta = t
    while ta < t_stop:
        if kind == LINEAR and i > 0 and ta == bps[i - 1]:
            i = _quiet_segments(i, t_stop, rest, times, values, bps)
            ta = bps[i - 1]
            if ta >= t_stop:
                break
        tb = bps[i] if i < nb else t_stop
        tb = min(tb, t_stop)
        if tb <= ta:
            i += 1
            continue
        m = _activated_at(ta, rest, kind, params, times, values)
        if m >= 0:
            return ta, m
        if kind != STEP:
            nsub = 1
            if kind >= HARMONIC:  # analytic: sampled at 1/512 of its time scale params[1]
                nsub = max(1, int(math.ceil((tb - ta) / (params[1] / 512.0))))
            tl = tb * (1.0 - 2.0 ** -52)
            prev = ta
            for q in range(1, nsub + 1):
                tq = ta + (tb - ta) * q / nsub
                if q == nsub:
                    tq = tl
                if _activated_at(tq, rest, kind, params, times, values) >= 0:
                    lo, hi = prev, tq  # not activated at lo, activated at hi
                    for _ in range(200):
                        mid = 0.5 * (lo + hi)
                        if mid <= lo or mid >= hi:
                            break
                        if _activated_at(mid, rest, kind, params, times, values) >= 0:
                            hi = mid
                        else:
                            lo = mid
                    return hi, _activated_at(hi, rest, kind, params, times, values)
                prev = tq
        ta = tb
        i += 1
    return t_stop, -1


@numba.njit(cache=True)
def decide_outcome(m, th, thd, tab, c_lr, c_rl):
    """Outcome after the end of the excitation, from the state ``(theta [rad], theta' [rad/s])``
    of mechanism ``m`` (see the module docstring).

    Returns ``(status, extra_half_cycles, peak_phi, time_known)``: ``extra_half_cycles`` is 0 if
    a collapse happens in the current half cycle, 1 (2) if after the next (second) impact;
    ``peak_phi`` [rad] the largest phi still to come if the arch recovers; ``time_known``
    whether the point of no return (the crossing of ``theta_cr`` away from ``theta_u``) has
    already been passed.
    """
    scal = tab[0]
    other = 1 - m
    th_u, th_cr = scal[m, 0], scal[m, 1]
    mm = table_function(th, ROW_M, m, tab)
    v = table_function(th, ROW_V, m, tab)
    v_cr = table_function(th_cr, ROW_V, m, tab)
    v_u = table_function(th_u, ROW_V, m, tab)
    energy = 0.5 * mm * thd * thd + v
    peak = 0.0
    if th <= th_cr:
        if thd <= 0.0 or energy <= v_cr:
            return STATUS_COLLAPSE, 0, peak, True
    elif thd < 0.0:
        if energy > v_cr:
            return STATUS_COLLAPSE, 0, peak, False
        peak = th_u - root_function(ROW_V, energy, th_cr, th, m, tab)
    # returns to theta_u, impacts into the other mechanism
    kinetic = max(energy - v_u, 0.0)
    c = c_lr if m == MECH_L else c_rl
    m_u = table_function(th_u, ROW_M, m, tab)
    m_new = table_function(scal[other, 0], ROW_M, other, tab)
    kinetic_new = c * c * m_new / m_u * kinetic
    v_u_new = table_function(scal[other, 0], ROW_V, other, tab)
    barrier = table_function(scal[other, 1], ROW_V, other, tab) - v_u_new
    if kinetic_new > barrier:
        return STATUS_COLLAPSE, 1, peak, False
    th_peak = root_function(ROW_V, v_u_new + kinetic_new, scal[other, 1], scal[other, 0],
                             other, tab)
    peak = max(peak, scal[other, 0] - th_peak)
    # back into this mechanism after the second impact: its own barrier has not been checked
    # yet (the arch may be on its way back with more energy than the barrier); from then on
    # every full cycle multiplies the kinetic energy of an arrival by (c_lr c_rl)^2 <= 1
    c_back = c_rl if m == MECH_L else c_lr
    kinetic_back = c_back * c_back * m_u / m_new * kinetic_new
    if kinetic_back > v_cr - v_u:
        return STATUS_COLLAPSE, 2, peak, False
    th_peak = root_function(ROW_V, v_u + kinetic_back, th_cr, th_u, m, tab)
    peak = max(peak, th_u - th_peak)
    return STATUS_RECOVERY, 0, peak, True


@numba.njit(cache=True, inline="always")
def impact_rule(m, thd, t, c_lr, c_rl, rest_velocity, scal, rest, kind, params, times, values):
    """The impact of mechanism ``m`` arriving at ``theta_u`` with ``theta' = thd`` [rad/s] at
    time ``t`` [s]: the other mechanism takes over with ``theta' = -c thd`` [paper, Sect. 4.4]
    (``c = c_lr`` from Mech-l, ``c_rl`` from Mech-r), or the arch comes to rest if that speed is
    below ``rest_velocity`` [rad/s] and the ground does not push the new mechanism open.

    Returns ``(state, theta, theta', theta' after the impact)``: the state after the impact
    (theta nan and theta' 0 at rest) and the rate ``-c thd`` the impact leaves [rad, rad/s]."""
    c = c_lr if m == MECH_L else c_rl
    new = 1 - m
    thd_after = -c * thd
    if abs(thd_after) < rest_velocity:
        if _activated_at(t, rest, kind, params, times, values) != new:
            return REST_STATE, np.nan, 0.0, thd_after
    return new, scal[new, 0], thd_after, thd_after
