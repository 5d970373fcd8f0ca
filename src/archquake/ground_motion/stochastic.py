"""A seeded stochastic ground-motion model: Rezaeian & Der Kiureghian's site-based model.

The acceleration is a modulated, filtered white noise [1]_, [2]_:

.. math::
    \\ddot x_g(t) = q(t) \\, \\frac{\\sum_{t_i \\le t} h(t - t_i; \\omega_f(t_i), \\zeta_f) u_i}
                              {\\sqrt{\\sum_{t_i \\le t} h^2(t - t_i; \\omega_f(t_i), \\zeta_f)}},
    \\qquad h(\\tau; \\omega, \\zeta) = \\frac{\\omega}{\\sqrt{1 - \\zeta^2}}
                                     e^{-\\zeta \\omega \\tau}
                                     \\sin\\left(\\omega \\sqrt{1 - \\zeta^2} \\tau\\right)

(eq. (5) of [2]_), with ``u_i`` independent standard normal numbers at ``t_i = i dt``, so the
filtered process has unit variance at every t and the modulation alone sets the intensity:

- the gamma-type modulating function ``q(t) = alpha_1 t^(alpha_2 - 1) exp(-alpha_3 t)`` whose
  parameters follow from the expected Arias intensity, the significant duration D5-95 and the
  time t_mid at which 45 % of the expected Arias intensity is reached (the expected cumulative
  Arias intensity is a regularised incomplete gamma function of ``2 alpha_3 t`` of shape
  ``2 alpha_2 - 1``; :func:`modulation_parameters`);
- the filter frequency varying linearly in time, ``omega_f(t) = 2 pi (f_mid + f' (t - t_mid))``,
  and a constant filter damping ``zeta_f`` (as in the model fitted in [2]_);
- a high-pass post-processing (eq. (8) of [2]_): the acceleration is replaced by ``u''`` of the
  critically damped oscillator ``u'' + 2 omega_c u' + omega_c^2 u = xg''(t)``, which brings the
  ground velocity and displacement back toward zero. It removes little energy from a motion of
  several hertz (the expected Arias intensity is that of the unfiltered process).

The impulse responses are summed over a window beyond which ``exp(-zeta_f omega_f tau) < 1e-9``;
the result is a ``LINEAR`` record sampled every ``dt``. Randomness comes only from the ``rng``
argument; :func:`stochastic_suite` draws motion i from ``SeedSequence(seed, spawn_key=(i,))``, so
a motion does not depend on the size of the suite.

References
----------
.. [1] Rezaeian, S. and Der Kiureghian, A. (2008). A stochastic ground motion model with
   separable temporal and spectral nonstationarities. Earthquake Engineering and Structural
   Dynamics 37(13), 1565-1584.
.. [2] Rezaeian, S. and Der Kiureghian, A. (2010). Simulation of synthetic ground motions for
   specified earthquake and site characteristics. Earthquake Engineering and Structural
   Dynamics 39(10), 1155-1180.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from ..constants import GRAVITY
from ..defaults import MAX_RECORD_SAMPLES
from .core import LINEAR, GroundMotion, check_number
from .intensity import nigam_jennings

DEFAULT_PARAMETERS = {
    "arias_intensity": 0.5,
    "significant_duration": 17.0,
    "midpoint_time": 12.0,
    "filter_frequency": 5.0,
    "filter_frequency_rate": -0.1,
    "filter_damping": 0.2,
}
"""Defaults of :func:`stochastic_motion`: a moderate far-field motion, of the order of the sample
means of the parameters Rezaeian & Der Kiureghian (2010) fitted to recorded motions (Arias
intensity [m/s], D5-95 [s], t_mid [s], f_mid [Hz], f' [Hz/s], zeta_f [-])."""


def _quantile_times(shape: float) -> tuple[float, float, float]:
    """``2 alpha_3 t`` at 5 %, 45 % and 95 % of the gamma-shaped Husid function."""
    from scipy import special  # here, not at the top: the command line imports this module

    return tuple(float(special.gammaincinv(shape, q)) for q in (0.05, 0.45, 0.95))


def _duration_ratio(shape: float) -> float:
    x05, x45, x95 = _quantile_times(shape)
    return (x95 - x05) / x45


def modulation_parameters(arias_intensity: float, significant_duration: float,
                          midpoint_time: float) -> tuple[float, float, float]:
    """``(alpha_1, alpha_2, alpha_3)`` of the modulating function
    ``q(t) = alpha_1 t^(alpha_2 - 1) exp(-alpha_3 t)`` [1]_.

    With ``k = 2 alpha_2 - 1`` the expected cumulative Arias intensity is
    ``I_a P(k, 2 alpha_3 t)`` (P the regularised lower incomplete gamma function), so
    ``D5-95 / t_mid`` fixes ``k`` (solved here), ``t_mid`` then ``alpha_3`` and the Arias intensity
    ``alpha_1`` ([1]_):

    .. math::
        \\alpha_1^2 = \\frac{2 g}{\\pi} I_a \\frac{(2 \\alpha_3)^{k}}{\\Gamma(k)}

    Parameters
    ----------
    arias_intensity : float
        Expected Arias intensity I_a [m/s], > 0.
    significant_duration : float
        D5-95 [s], > 0.
    midpoint_time : float
        t_mid [s]: time at 45 % of the expected Arias intensity, > 0.

    Returns
    -------
    alpha_1, alpha_2, alpha_3 : float
        The parameters of ``q`` [m/s^(alpha_2 + 1)], [-], [1/s].

    Raises
    ------
    ValueError
        If ``significant_duration / midpoint_time`` is not below 4.925 (the ratio of an
        exponential modulation, ``alpha_2 = 1``): the modulation would be infinite at ``t = 0``.

    References
    ----------
    .. [1] Rezaeian, S. and Der Kiureghian, A. (2010). Simulation of synthetic ground motions
       for specified earthquake and site characteristics. Earthquake Engineering and
       Structural Dynamics 39(10), 1155-1180.
    """
    from scipy import special
    from scipy.optimize import brentq

    ia = check_number("arias_intensity", arias_intensity, "m/s")
    d = check_number("significant_duration", significant_duration, "s")
    tmid = check_number("midpoint_time", midpoint_time, "s")
    ratio = d / tmid
    limit = _duration_ratio(1.0)
    if ratio >= limit:
        raise ValueError(f"significant_duration / midpoint_time must be < {limit:.4f} (the "
                         f"modulation would be infinite at t = 0), got {d:g} s / {tmid:g} s = "
                         f"{ratio:.4g}")
    shape = brentq(lambda k: _duration_ratio(k) - ratio, 1.0, 1e5, xtol=1e-13, rtol=1e-14)
    alpha3 = _quantile_times(shape)[1] / (2.0 * tmid)
    alpha2 = (shape + 1.0) / 2.0
    log_a1_sq = (math.log(2.0 * GRAVITY / math.pi * ia) + shape * math.log(2.0 * alpha3)
                 - special.gammaln(shape))
    return math.exp(0.5 * log_a1_sq), alpha2, alpha3


def modulating_function(t, alphas) -> np.ndarray:
    """``q(t) = alpha_1 t^(alpha_2 - 1) exp(-alpha_3 t)`` [m/s^2] at times ``t`` [s] (0 for
    ``t <= 0``)."""
    a1, a2, a3 = alphas
    t = np.asarray(t, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        q = a1 * np.exp((a2 - 1.0) * np.log(t) - a3 * t)
    return np.where(t > 0.0, q, 0.0)


def expected_husid_time(fraction: float, alphas) -> float:
    """Time [s] at which the expected cumulative Arias intensity reaches ``fraction``."""
    from scipy import special

    _, a2, a3 = alphas
    return float(special.gammaincinv(2.0 * a2 - 1.0, fraction)) / (2.0 * a3)


@numba.njit(cache=True)
def _filtered_noise(u, omega, zeta, dt, window):
    """Unit-variance filtered noise: sum_i h(t_j - t_i; omega_i) u_i / sqrt(sum_i h^2)."""
    n = u.size
    num = np.zeros(n)
    var = np.zeros(n)
    sq = math.sqrt(1.0 - zeta * zeta)
    for i in range(n):
        w = omega[i]
        scale = w / sq
        decay = math.exp(-zeta * w * dt)
        rot_c, rot_s = math.cos(w * sq * dt), math.sin(w * sq * dt)
        # z_k = decay^k exp(i w_d k dt), advanced by one complex multiplication per sample
        zr, zi = decay * rot_c, decay * rot_s
        stop = min(n, i + window)
        for j in range(i + 1, stop):
            hv = scale * zi
            num[j] += hv * u[i]
            var[j] += hv * hv
            zr, zi = decay * (zr * rot_c - zi * rot_s), decay * (zr * rot_s + zi * rot_c)
    out = np.zeros(n)
    for j in range(n):
        if var[j] > 0.0:
            out[j] = num[j] / math.sqrt(var[j])
    return out


@numba.njit(cache=True)
def _high_pass_run(x, dt, corner):
    a, b, c, d, a2, b2, c2, d2 = nigam_jennings(dt, corner, 1.0)
    u = 0.0
    v = 0.0
    out = np.empty(x.size)
    for k in range(x.size):
        out[k] = x[k] - 2.0 * corner * v - corner * corner * u
        if k + 1 < x.size:
            u, v = (a * u + b * v + c * x[k] + d * x[k + 1],
                    a2 * u + b2 * v + c2 * x[k] + d2 * x[k + 1])
    return out


def high_pass(acceleration, corner: float, dt: float) -> np.ndarray:
    """``u''`` of the critically damped oscillator ``u'' + 2 w_c u' + w_c^2 u = a(t)`` from rest
    (eq. (8) of Rezaeian & Der Kiureghian 2010), for ``a`` sampled every ``dt`` [s] and linear
    in between (the exact steps of :mod:`~archquake.ground_motion.intensity`, with damping
    ratio 1).

    Parameters
    ----------
    acceleration : array of float
        ``a(t_i)`` [m/s^2].
    corner : float
        omega_c [rad/s], > 0.
    dt : float
        Time step [s].
    """
    return _high_pass_run(np.ascontiguousarray(acceleration, dtype=float), float(dt),
                          float(corner))


def _generator(rng) -> np.random.Generator:
    if isinstance(rng, np.random.Generator):
        return rng
    if rng is None or isinstance(rng, (int, np.integer, np.random.SeedSequence)):
        if isinstance(rng, (int, np.integer)) and int(rng) < 0:
            raise ValueError(f"rng seed must be >= 0, got {rng!r}")
        return np.random.default_rng(rng)
    raise ValueError(f"rng must be a seed (int >= 0), a SeedSequence or a numpy Generator, "
                     f"got {rng!r}")


def stochastic_motion(arias_intensity: float = DEFAULT_PARAMETERS["arias_intensity"],
                      significant_duration: float = DEFAULT_PARAMETERS["significant_duration"],
                      midpoint_time: float = DEFAULT_PARAMETERS["midpoint_time"],
                      filter_frequency: float = DEFAULT_PARAMETERS["filter_frequency"],
                      filter_frequency_rate: float = DEFAULT_PARAMETERS["filter_frequency_rate"],
                      filter_damping: float = DEFAULT_PARAMETERS["filter_damping"], *,
                      high_pass_frequency: float | None = 0.1, dt: float = 0.01,
                      duration: float | None = None, rng=None,
                      name: str | None = None) -> GroundMotion:
    """One synthetic accelerogram of the Rezaeian-Der Kiureghian model (module docstring).

    Parameters
    ----------
    arias_intensity : float
        Expected Arias intensity I_a [m/s].
    significant_duration : float
        Expected significant duration D5-95 [s].
    midpoint_time : float
        t_mid [s]: time at 45 % of the expected Arias intensity.
    filter_frequency : float
        Filter frequency f_mid = omega_mid / (2 pi) at t_mid [Hz], > 0.
    filter_frequency_rate : float
        Rate f' of the filter frequency [Hz/s] (negative: the motion's frequency content
        falls with time); the filter frequency must stay > 0 over the motion.
    filter_damping : float
        Filter damping ratio zeta_f in (0, 1) [-].
    high_pass_frequency : float or None
        Corner f_c = omega_c / (2 pi) of the high-pass post-processing [Hz]; None for none.
    dt : float
        Time step of the record [s].
    duration : float, optional
        Length of the record [s]; default: the time at which the expected cumulative Arias
        intensity reaches 99.9 %.
    rng : int, SeedSequence or numpy Generator, optional
        Source of the white noise; the same seed gives the same motion.
    name : str, optional
        Name of the motion (default: the model and the seed).

    Returns
    -------
    GroundMotion
        ``LINEAR``, accelerations [m/s^2] at ``t_i = i dt``.
    """
    alphas = modulation_parameters(arias_intensity, significant_duration, midpoint_time)
    f_mid = check_number("filter_frequency", filter_frequency, "Hz")
    rate = check_number("filter_frequency_rate", filter_frequency_rate, "Hz/s", positive=False)
    zeta = check_number("filter_damping", filter_damping, "-")
    if zeta >= 1.0:
        raise ValueError(f"filter_damping must be in (0, 1) [-], got {filter_damping!r}")
    dt = check_number("dt", dt, "s")
    if duration is None:
        duration = expected_husid_time(0.999, alphas)
    duration = check_number("duration", duration, "s")
    if duration / dt >= MAX_RECORD_SAMPLES:
        raise ValueError(f"duration / dt = {duration:g} s / {dt:g} s gives {duration / dt:.3g} "
                         f"samples, more than {MAX_RECORD_SAMPLES} (MAX_RECORD_SAMPLES)")
    n = int(math.floor(duration / dt + 1e-9)) + 1
    if n < 3:
        raise ValueError(f"duration must hold at least 3 steps of dt = {dt:g} s, got "
                         f"{duration:g} s")
    t = dt * np.arange(n)
    tmid = float(midpoint_time)
    frequency = f_mid + rate * (t - tmid)
    if np.min(frequency) <= 0.0:
        raise ValueError(f"the filter frequency f_mid + f' (t - t_mid) must stay > 0 [Hz] over "
                         f"the motion; it reaches {np.min(frequency):.3g} Hz (f_mid = {f_mid:g} "
                         f"Hz, f' = {rate:g} Hz/s, duration {duration:g} s)")
    if 1.0 / (2.0 * np.max(frequency)) < 2.0 * dt:
        raise ValueError(f"dt = {dt:g} s is too coarse for a filter frequency of "
                         f"{np.max(frequency):.3g} Hz (need at least 4 samples per period)")
    omega = 2.0 * math.pi * frequency
    window = int(math.ceil(-math.log(1e-9) / (zeta * float(np.min(omega)) * dt))) + 1
    seed_text = f" seed {rng}" if isinstance(rng, (int, np.integer)) else ""
    generator = _generator(rng)
    u = generator.standard_normal(n)
    noise = _filtered_noise(u, omega, zeta, dt, min(window, n))
    acc = modulating_function(t, alphas) * noise
    if high_pass_frequency is not None:
        wc = 2.0 * math.pi * check_number("high_pass_frequency", high_pass_frequency, "Hz")
        acc = high_pass(acc, wc, dt)
    return GroundMotion(LINEAR, t, acc, name=name or f"stochastic motion (Rezaeian & Der "
                                                     f"Kiureghian){seed_text}")


def stochastic_suite(n: int, *args, seed: int = 0, **kwargs) -> list[GroundMotion]:
    """``n`` motions of :func:`stochastic_motion` (same arguments), motion ``i`` drawn from
    ``SeedSequence(seed, spawn_key=(i,))`` and named ``stochastic-<i>``: motion ``i`` is the same
    whatever ``n``.

    Parameters
    ----------
    n : int
        Number of motions, >= 1.
    seed : int
        Root seed, >= 0.
    """
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
        raise ValueError(f"n must be a whole number >= 1, got {n!r}")
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
        raise ValueError(f"seed must be a whole number >= 0, got {seed!r}")
    if "rng" in kwargs:
        raise ValueError("stochastic_suite draws its own streams from seed; do not pass rng")
    width = max(3, len(str(n - 1)))
    return [stochastic_motion(*args, rng=np.random.SeedSequence(int(seed), spawn_key=(i,)),
                              name=f"stochastic-{i:0{width}d}", **kwargs) for i in range(n)]
