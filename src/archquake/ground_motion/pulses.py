"""Analytic pulses: Oppenheim's pulse, rectangular and sine pulses, harmonic motions, Ricker
wavelets, Makris' cycloidal pulses and the Mavroeidis-Papageorgiou pulse.

Every factory takes the signed ``amplitude`` [m/s^2] and a time scale [s] (a pulse duration or a
period) first, and returns a :class:`~.core.GroundMotion` whose acceleration is
``amplitude * shape(t / time_scale)``; that is how a pulse study (:mod:`archquake.fourlink.engine`)
scans amplitudes and durations with one template. Every pulse starts at ``t = 0`` from a ground at
rest.

The smooth pulses are evaluated exactly by the compiled engine (kinds ``HARMONIC``, ``RICKER``,
``MAVROEIDIS_PAPAGEORGIOU`` of :func:`~.core.evaluate`), with breakpoints only at their start and
end, so the integrator takes steps as long as the response allows; a tabulation as a
piecewise-linear record would force a step at every sample and add its interpolation error
(measured in ``benchmarks/analytic_pulses.py``).
"""

from __future__ import annotations

import math

from ..defaults import MAX_CYCLES, MAX_PULSE_DURATION
from .core import GRAVITY as _G
from .core import (
    HARMONIC,
    MAVROEIDIS_PAPAGEORGIOU,
    RICKER,
    STEP,
    GroundMotion,
    check_number,
)

RICKER_CENTRE = {"symmetric": 2.0, "antisymmetric": 2.5}
"""Centre of the Ricker wavelets, in periods after ``t = 0``; the wavelet is cut to
``[0, 2 centre T_p]``, where its tails are below ``1e-15`` of the peak."""


def _g(a: float) -> str:
    return f"{a / _G:+.3g} g"


_PULSE_TIME = {"at_most": MAX_PULSE_DURATION, "limit_name": "MAX_PULSE_DURATION"}
"""The bound of a pulse's duration or period: a duration of minutes is a unit mistake."""


def oppenheim_pulse(amplitude: float, duration: float) -> GroundMotion:
    """Oppenheim's pulse [paper, Sect. 5.3.1]: ``amplitude`` for ``duration`` t_p, then
    ``-amplitude/2`` for ``2 t_p``, then rest (zero net ground velocity).

    Parameters
    ----------
    amplitude : float
        Signed ground acceleration of the first pulse [m/s^2]; the paper's ``xg'' = -1 g`` is
        ``-GRAVITY``.
    duration : float
        Duration t_p of the first pulse [s].
    """
    a = check_number("amplitude", amplitude, "m/s^2", positive=False)
    tp = check_number("duration", duration, "s", **_PULSE_TIME)
    return GroundMotion(STEP, [0.0, tp, 3.0 * tp], [a, -a / 2.0],
                        name=f"Oppenheim pulse {_g(a)}, t_p = {tp:.3g} s")


def rectangular_pulse(amplitude: float, duration: float) -> GroundMotion:
    """One rectangular pulse: ``amplitude`` [m/s^2] for ``duration`` [s], then rest."""
    a = check_number("amplitude", amplitude, "m/s^2", positive=False)
    tp = check_number("duration", duration, "s", **_PULSE_TIME)
    return GroundMotion(STEP, [0.0, tp], [a], name=f"rectangular pulse {_g(a)}, {tp:.3g} s")


def sine_pulse(amplitude: float, duration: float) -> GroundMotion:
    """One full cycle of ``amplitude sin(2 pi t / duration)`` [m/s^2], then rest.

    Parameters
    ----------
    amplitude : float
        Signed peak ground acceleration [m/s^2].
    duration : float
        Duration of the cycle (its period) [s].
    """
    return harmonic(amplitude, duration, cycles=1, name_prefix="one-cycle sine pulse")


def harmonic(amplitude: float, period: float, cycles: float = 1, *,
             name_prefix: str = "harmonic") -> GroundMotion:
    """``cycles`` cycles of a sine, then rest.

    .. math:: \\ddot x_g(t) = a \\sin(2 \\pi t / T), \\quad 0 \\le t < n T

    Parameters
    ----------
    amplitude : float
        Signed amplitude a [m/s^2].
    period : float
        Period T [s].
    cycles : float
        Number of cycles n > 0 [-] (need not be whole), at most
        :data:`archquake.defaults.MAX_CYCLES`.
    """
    a = check_number("amplitude", amplitude, "m/s^2", positive=False)
    period = check_number("period", period, "s", **_PULSE_TIME)
    cycles = check_number("cycles", cycles, "-")
    if cycles > MAX_CYCLES:
        raise ValueError(f"cycles must be at most {MAX_CYCLES} (MAX_CYCLES), got {cycles:g}")
    return GroundMotion(HARMONIC, params=[a, period, cycles, 0.0],
                        name=f"{name_prefix} {_g(a)}, T = {period:.3g} s")


def ricker_wavelet(amplitude: float, period: float) -> GroundMotion:
    """The symmetric Ricker wavelet ("Mexican hat"), centred at ``t_0 = 2 T_p``.

    .. math::
        \\ddot x_g(t) = a_p \\left(1 - \\frac{2 \\pi^2 (t - t_0)^2}{T_p^2}\\right)
                       \\exp\\left(-\\frac{\\pi^2 (t - t_0)^2}{T_p^2}\\right),
        \\quad 0 \\le t < 2 t_0

    (the second derivative of a Gaussian; eq. (1) of [1], time shifted to start at rest). Its
    Fourier amplitude peaks at the frequency ``1/T_p``; the ground velocity
    ``a_p (t - t_0) exp(-pi^2 (t - t_0)^2 / T_p^2)`` and displacement return to zero.

    Parameters
    ----------
    amplitude : float
        Signed peak ground acceleration a_p [m/s^2] (the value at the centre).
    period : float
        Period T_p of the wavelet [s]: the inverse of its dominant frequency.

    References
    ----------
    .. [1] Vassiliou, M. F. and Makris, N. (2011). Analysis of the rocking response of rigid
       blocks standing free on a seismically isolated base. Earthquake Engineering and
       Structural Dynamics 41(2), 177-196.
    .. [2] Ricker, N. (1943). Further developments in the wavelet theory of seismogram
       structure. Bulletin of the Seismological Society of America 33(3), 197-228.
    """
    a = check_number("amplitude", amplitude, "m/s^2", positive=False)
    period = check_number("period", period, "s", **_PULSE_TIME)
    return GroundMotion(RICKER, params=[a, period, RICKER_CENTRE["symmetric"], 0.0],
                        name=f"symmetric Ricker wavelet {_g(a)}, T_p = {period:.3g} s")


def antisymmetric_ricker_wavelet(amplitude: float, period: float) -> GroundMotion:
    """The antisymmetric Ricker wavelet, centred at ``t_0 = 2.5 T_p``.

    .. math::
        \\ddot x_g(t) = \\frac{a_p}{\\beta} \\left(x^2 - 3\\right) x \\, e^{-x^2/2}, \\quad
        x = \\frac{2 \\pi (t - t_0)}{\\sqrt{3} T_p}, \\quad 0 \\le t < 2 t_0

    (the third derivative of a Gaussian; eq. (2) of [1], time shifted to start at rest), with
    ``beta = sqrt(6 (3 - sqrt 6)) exp(-(3 - sqrt 6)/2) = 1.38012`` its peak, so that the peak
    acceleration is ``|a_p|``; the main lobes are ``+a_p`` just before the centre and ``-a_p``
    just after. Its Fourier amplitude peaks at ``1/T_p``; ground velocity and displacement
    return to zero.

    Parameters
    ----------
    amplitude : float
        Signed peak ground acceleration a_p [m/s^2] (the first main lobe).
    period : float
        Period T_p of the wavelet [s].

    References
    ----------
    .. [1] Vassiliou, M. F. and Makris, N. (2011). Analysis of the rocking response of rigid
       blocks standing free on a seismically isolated base. Earthquake Engineering and
       Structural Dynamics 41(2), 177-196.
    """
    a = check_number("amplitude", amplitude, "m/s^2", positive=False)
    period = check_number("period", period, "s", **_PULSE_TIME)
    return GroundMotion(RICKER, params=[a, period, RICKER_CENTRE["antisymmetric"], 1.0],
                        name=f"antisymmetric Ricker wavelet {_g(a)}, T_p = {period:.3g} s")


def cycloidal_phase(n: int) -> float:
    """Phase phi [rad] of the type-C_n cycloidal pulse: the root in (0, pi/2) of

    .. math:: 2 \\cos\\varphi = \\left((2n + 1)\\pi - 2\\varphi\\right) \\sin\\varphi

    so that the ground displacement returns to zero at the end of the pulse
    (phi = 0.0697 pi for n = 1, 0.0410 pi for n = 2 [2]).
    """
    n = _whole_cycles(n)
    from scipy.optimize import brentq  # here: the command line imports this module

    return brentq(lambda p: 2.0 * math.cos(p) - ((2 * n + 1) * math.pi - 2.0 * p) * math.sin(p),
                  1e-12, math.pi / 2.0, xtol=1e-15)


def _whole_cycles(n) -> int:
    if (isinstance(n, bool) or float(n) != int(float(n)) or int(float(n)) < 1
            or float(n) > MAX_CYCLES):
        raise ValueError(f"n (main cycles of a type-C_n pulse) must be a whole number >= 1, "
                         f"at most {MAX_CYCLES} (MAX_CYCLES), got {n!r}")
    return int(float(n))


def cycloidal_pulse(amplitude: float, period: float, pulse_type: str = "A",
                    n: int = 1) -> GroundMotion:
    """Makris' cycloidal pulses of type A, B and C_n [1, 2].

    .. math::
        \\text{A:}\\; \\ddot x_g = a_p \\sin(\\omega_p t), \\; 0 \\le t < T_p \\qquad
        \\text{B:}\\; \\ddot x_g = a_p \\cos(\\omega_p t), \\; 0 \\le t < T_p

        \\text{C}_n\\text{:}\\; \\ddot x_g = a_p \\cos(\\omega_p t + \\varphi), \\;
        0 \\le t < \\left(n + \\tfrac12 - \\tfrac{\\varphi}{\\pi}\\right) T_p

    with ``omega_p = 2 pi / T_p``. Type A (a one-sine acceleration) gives a one-sided velocity
    pulse ``(a_p/omega_p)(1 - cos omega_p t)`` and a permanent ground displacement
    ``a_p T_p^2 / (2 pi)`` (a fling step, forward motion); type B (a one-cosine acceleration) a
    full-sine velocity pulse ``(a_p/omega_p) sin omega_p t`` and a forward-and-back displacement
    returning to zero; type C_n a velocity of n main cycles,
    ``(a_p/omega_p)(sin(omega_p t + phi) - sin phi)``, with the phase phi of
    :func:`cycloidal_phase` bringing velocity and displacement back to zero at the end.
    Velocity and displacement are continuous; the acceleration of types B and C_n jumps at
    the start and the end.

    Parameters
    ----------
    amplitude : float
        Signed peak ground acceleration a_p [m/s^2] (``a_p = omega_p v_p`` for types B, C_n and
        ``omega_p v_p / 2`` for type A, with v_p the peak ground velocity of [2]).
    period : float
        Pulse period T_p [s].
    pulse_type : {"A", "B", "C"}
        Type of the pulse.
    n : int
        Number of main cycles of a type-C_n pulse (>= 1); type C only.

    References
    ----------
    .. [1] Makris, N. and Roussos, Y. S. (2000). Rocking response of rigid blocks under
       near-source ground motions. Geotechnique 50(3), 243-262.
    .. [2] Zhang, J. and Makris, N. (2001). Rocking response of free-standing blocks under
       cycloidal pulses. Journal of Engineering Mechanics 127(5), 473-483.
    """
    a = check_number("amplitude", amplitude, "m/s^2", positive=False)
    period = check_number("period", period, "s", **_PULSE_TIME)
    kind = str(pulse_type).upper()
    if kind not in ("A", "B", "C"):
        raise ValueError(f"pulse_type must be 'A', 'B' or 'C' (C_n), got {pulse_type!r}")
    if kind != "C" and n != 1:
        raise ValueError(f"n applies to the type-C_n pulse only, got n = {n!r} for type {kind}")
    if kind == "A":  # a sin(w t)
        params, label = [a, period, 1.0, 0.0], "A"
    elif kind == "B":  # a cos(w t) = a sin(w t + pi/2)
        params, label = [a, period, 1.0, math.pi / 2.0], "B"
    else:
        n = _whole_cycles(n)
        phi = cycloidal_phase(n)
        params, label = [a, period, n + 0.5 - phi / math.pi, math.pi / 2.0 + phi], f"C{n}"
    return GroundMotion(HARMONIC, params=params,
                        name=f"cycloidal pulse type {label} {_g(a)}, T_p = {period:.3g} s")


def cycloidal_a(amplitude: float, period: float) -> GroundMotion:
    """Type-A cycloidal pulse: :func:`cycloidal_pulse` ``(amplitude, period, "A")``."""
    return cycloidal_pulse(amplitude, period, "A")


def cycloidal_b(amplitude: float, period: float) -> GroundMotion:
    """Type-B cycloidal pulse: :func:`cycloidal_pulse` ``(amplitude, period, "B")``."""
    return cycloidal_pulse(amplitude, period, "B")


def cycloidal_c(amplitude: float, period: float, n: int = 1) -> GroundMotion:
    """Type-C_n cycloidal pulse: :func:`cycloidal_pulse` ``(amplitude, period, "C", n)``."""
    return cycloidal_pulse(amplitude, period, "C", n)


def mavroeidis_papageorgiou_shape_peak(gamma: float, phase: float) -> float:
    """Peak ``max |S(t)|`` of the Mavroeidis-Papageorgiou acceleration shape ``S`` [-].

    ``S`` is the pulse of :func:`mavroeidis_papageorgiou_pulse` with ``coefficient = 1``.

    Parameters
    ----------
    gamma : float
        Oscillatory character ``gamma`` of the pulse [-].
    phase : float
        Phase ``nu`` of the pulse [rad].

    Returns
    -------
    float
        The peak of ``|S|`` [-].
    """
    template = GroundMotion(MAVROEIDIS_PAPAGEORGIOU, params=[1.0, 1.0, gamma, phase])
    return template.peak


def mavroeidis_papageorgiou_pulse(amplitude: float, period: float, gamma: float = 2.0,
                                  phase: float = 0.0) -> GroundMotion:
    """The Mavroeidis-Papageorgiou (2003) near-fault velocity pulse, by its acceleration.

    Ground velocity and acceleration, eqs. (1) and (2) of [1], with ``f_p = 1/T_p`` and the
    pulse centred at ``t_0 = gamma T_p / 2`` so that it starts at ``t = 0``:

    .. math::
        v(t) = \\frac{A}{2}\\left[1 + \\cos\\left(\\frac{2\\pi f_p (t - t_0)}{\\gamma}\\right)
               \\right] \\cos\\left(2\\pi f_p (t - t_0) + \\nu\\right)

        \\ddot x_g(t) = -\\frac{A \\pi f_p}{\\gamma}\\left[
            \\sin\\left(\\frac{2\\pi f_p (t - t_0)}{\\gamma}\\right)
            \\cos\\left(2\\pi f_p (t - t_0) + \\nu\\right)
            + \\gamma \\sin\\left(2\\pi f_p (t - t_0) + \\nu\\right)
            \\left(1 + \\cos\\left(\\frac{2\\pi f_p (t - t_0)}{\\gamma}\\right)\\right)\\right]

    for ``0 <= t < gamma T_p``, zero otherwise. Velocity and acceleration are zero at both
    ends (continuous); the ground displacement may keep a residual value.

    Parameters
    ----------
    amplitude : float
        Signed peak ground acceleration [m/s^2]: the paper's velocity amplitude A is chosen so
        that ``max |xg''| = |amplitude|``, with the paper's sign for ``amplitude > 0``; then
        ``A = c T_p / pi`` with ``c = amplitude / max|S|``, S the shape for ``A pi f_p = 1``
        (:func:`mavroeidis_papageorgiou_shape_peak`).
    period : float
        Pulse period T_p = 1/f_p [s].
    gamma : float
        gamma > 1 [-]: the oscillatory character (about the number of half cycles).
    phase : float
        nu [rad]: the phase of the amplitude-modulated harmonic (0: symmetric velocity pulse,
        pi/2: antisymmetric).

    References
    ----------
    .. [1] Mavroeidis, G. P. and Papageorgiou, A. S. (2003). A mathematical representation of
       near-fault ground motions. Bulletin of the Seismological Society of America 93(3),
       1099-1131.
    """
    a = check_number("amplitude", amplitude, "m/s^2", positive=False)
    period = check_number("period", period, "s", **_PULSE_TIME)
    gamma = check_number("gamma", gamma, "-")
    phase = check_number("phase", phase, "rad", positive=False)
    if not 1.0 < gamma <= 2 * MAX_CYCLES:
        raise ValueError(f"gamma must be > 1 [-] (Mavroeidis & Papageorgiou 2003) and at most "
                         f"{2 * MAX_CYCLES} (about the number of half cycles), got {gamma!r}")
    coefficient = a / mavroeidis_papageorgiou_shape_peak(gamma, phase)
    return GroundMotion(MAVROEIDIS_PAPAGEORGIOU, params=[coefficient, period, gamma, phase],
                        name=f"Mavroeidis-Papageorgiou pulse {_g(a)}, T_p = {period:.3g} s, "
                             f"gamma = {gamma:.3g}, nu = {phase:.3g} rad")
