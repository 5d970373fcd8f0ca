"""Intensity measures against closed forms (pulses, a step, a harmonic excitation of a damped
oscillator) and against second methods written here (scipy quadrature, solve_ivp, expm)."""

import math
from pathlib import Path

import numpy as np
import pytest
from scipy import integrate
from scipy.linalg import expm

from archquake.geometry import GRAVITY
from archquake.ground_motion import (
    LINEAR,
    GroundMotion,
    harmonic,
    oppenheim_pulse,
    read_record,
    rectangular_pulse,
    ricker_wavelet,
)
from archquake.ground_motion.intensity import (
    INTENSITY_MEASURES,
    arias_intensity,
    intensity_measure,
    intensity_measures,
    nigam_jennings,
    parse_intensity_measures,
    peak_ground_displacement,
    peak_ground_velocity,
    pseudo_spectral_acceleration,
    scale_to_im,
    significant_duration,
)

DATA = Path(__file__).parents[1] / "data"
ZETA = 0.05


# --- peaks, Arias, duration of pulses in closed form -----------------------------------------

def test_oppenheim_pulse_closed_forms():
    a, tp = -2.0, 0.3
    g = oppenheim_pulse(a, tp)
    assert peak_ground_velocity(g) == pytest.approx(abs(a) * tp, rel=1e-14)
    # velocity a tp at t_p falls linearly to 0 at 3 t_p: displacement 1.5 a tp^2, then still
    assert peak_ground_displacement(g) == pytest.approx(1.5 * abs(a) * tp ** 2, rel=1e-14)
    assert arias_intensity(g) == pytest.approx(math.pi / (2 * GRAVITY) * 1.5 * a * a * tp)
    # 5 % of 1.5 a^2 tp at 0.075 tp; 95 % at tp + (1.425 - 1) a^2 tp / (a^2/4) = 2.7 tp
    assert significant_duration(g) == pytest.approx(2.625 * tp, rel=1e-12)


def test_ricker_closed_forms():
    a, T = 3.0, 0.4
    g = ricker_wavelet(a, T)
    assert peak_ground_velocity(g) == pytest.approx(a * T / (math.pi * math.sqrt(2))
                                                    * math.exp(-0.5), rel=1e-6)
    assert peak_ground_displacement(g) == pytest.approx(a * T ** 2 / (2 * math.pi ** 2),
                                                        rel=1e-6)
    # int (1 - 2x^2)^2 exp(-2x^2) dx = (3/4) sqrt(pi/2), dt = T/pi dx
    arias = math.pi / (2 * GRAVITY) * a * a * T / math.pi * 0.75 * math.sqrt(math.pi / 2)
    assert arias_intensity(g) == pytest.approx(arias, rel=1e-6)
    assert intensity_measure("pga")(g) == pytest.approx(a / GRAVITY, rel=1e-15)


def test_harmonic_closed_forms():
    a, T, n = 1.5, 0.25, 6
    g = harmonic(a, T, cycles=n)
    assert arias_intensity(g) == pytest.approx(math.pi / (2 * GRAVITY) * a * a * n * T / 2,
                                               rel=1e-6)
    assert peak_ground_velocity(g) == pytest.approx(a * T / math.pi, rel=1e-6)
    # x = (a T / 2 pi) t - (a T^2 / 4 pi^2) sin(2 pi t / T): largest at the end
    assert peak_ground_displacement(g) == pytest.approx(a * T * n * T / (2 * math.pi), rel=1e-6)


def linear_record(times, values):
    return GroundMotion(LINEAR, times, values, name="test record")


def test_peaks_inside_segments_of_a_linear_record_are_exact():
    """Extrema of velocity and displacement between samples, against dense quadrature."""
    g = linear_record([0.0, 0.4, 0.7, 1.5, 1.6, 2.5], [0.0, 2.0, -3.0, 1.0, 2.5, -1.0])
    t = np.linspace(0.0, g.duration, 200001)
    v = integrate.cumulative_trapezoid(g.acceleration(t), t, initial=0.0)
    d = integrate.cumulative_trapezoid(v, t, initial=0.0)
    assert peak_ground_velocity(g) == pytest.approx(np.max(np.abs(v)), rel=1e-9)
    assert peak_ground_displacement(g) == pytest.approx(np.max(np.abs(d)), rel=1e-9)
    i_v, i_d = np.argmax(np.abs(v)), np.argmax(np.abs(d))
    assert not np.isclose(t[i_v], g.times).any()  # the peaks are really between samples
    assert not np.isclose(t[i_d], g.times).any()


def test_arias_and_duration_of_a_record_against_quadrature():
    g = read_record(DATA / "decaying_sine.AT2")
    quad = sum(integrate.quad(lambda s: g.acceleration(s) ** 2, a, b)[0]
               for a, b in zip(g.times[:-1], g.times[1:], strict=True))
    assert arias_intensity(g) == pytest.approx(math.pi / (2 * GRAVITY) * quad, rel=1e-12)
    t = np.linspace(0.0, g.duration, 400001)
    husid = integrate.cumulative_trapezoid(g.acceleration(t) ** 2, t, initial=0.0)
    husid /= husid[-1]
    d = np.interp(0.95, husid, t) - np.interp(0.05, husid, t)
    assert significant_duration(g) == pytest.approx(d, abs=1e-6)


# --- spectral acceleration -------------------------------------------------------------------

@pytest.mark.parametrize("zeta", [ZETA, 1.0])
def test_step_coefficients_equal_the_matrix_exponential(zeta):
    """Nigam-Jennings' closed form (and its series branch, with scaling and squaring for long
    critically damped steps) against scipy's expm."""
    for period in (0.02, 0.3, 4.0, 60.0):
        w = 2 * math.pi / period
        for h in (1e-4, 3e-3, 0.01, 0.05):
            m = np.zeros((4, 4))
            m[0, 1], m[1, 0], m[1, 1], m[1, 2], m[2, 3] = 1, -w * w, -2 * zeta * w, 1, 1
            e = expm(m * h)
            expected = [e[0, 0], e[0, 1], e[0, 2] - e[0, 3] / h, e[0, 3] / h,
                        e[1, 0], e[1, 1], e[1, 2] - e[1, 3] / h, e[1, 3] / h]
            assert np.array(nigam_jennings(h, w, zeta)) == pytest.approx(
                expected, rel=1e-10, abs=1e-14 * max(1.0, 1 / w ** 2)), (period, h)


@pytest.mark.parametrize("period", [0.05, 0.2, 1.0])
def test_sa_of_a_step_is_the_overshoot_of_a_damped_oscillator(period):
    a0 = 2.0
    g = rectangular_pulse(a0, 40 * period)  # a step held for many periods
    wd_ratio = math.sqrt(1 - ZETA ** 2)
    # u = -(a0/w^2)(1 - exp(-z w t)(cos wd t + z/sqrt(1-z^2) sin wd t)), largest at t = pi/wd
    expected = a0 * (1 + math.exp(-ZETA * math.pi / wd_ratio))
    assert pseudo_spectral_acceleration(g, period) == pytest.approx(expected, rel=1e-7)


def harmonic_response(t, amplitude, forcing_period, period, duration):
    """Exact relative displacement of the 5 %-damped oscillator under
    -amplitude sin(W t), 0 <= t < duration, from rest; free vibration afterwards."""
    w, W, z = 2 * math.pi / period, 2 * math.pi / forcing_period, ZETA
    wd = w * math.sqrt(1 - z * z)
    # particular solution of u'' + 2 z w u' + w^2 u = -A sin W t:  P sin W t + Q cos W t
    det = (w * w - W * W) ** 2 + (2 * z * w * W) ** 2
    P = -amplitude * (w * w - W * W) / det
    Q = amplitude * 2 * z * w * W / det
    c1 = -Q  # u(0) = 0
    c2 = -(P * W - z * w * c1) / wd  # u'(0) = 0

    def forced(s):
        return (P * np.sin(W * s) + Q * np.cos(W * s)
                + np.exp(-z * w * s) * (c1 * np.cos(wd * s) + c2 * np.sin(wd * s)))

    def forced_rate(s):
        return (P * W * np.cos(W * s) - Q * W * np.sin(W * s) + np.exp(-z * w * s)
                * ((-z * w * c1 + wd * c2) * np.cos(wd * s) + (-z * w * c2 - wd * c1)
                   * np.sin(wd * s)))

    u_end, v_end = forced(duration), forced_rate(duration)
    tau = t - duration
    free = np.exp(-z * w * tau) * (u_end * np.cos(wd * tau)
                                   + (v_end + z * w * u_end) / wd * np.sin(wd * tau))
    return np.where(t < duration, forced(t), free)


@pytest.mark.parametrize("period, forcing_period", [(0.5, 0.5), (0.2, 0.45), (1.0, 0.3)])
def test_sa_of_a_harmonic_excitation_matches_the_exact_response(period, forcing_period):
    amplitude, cycles = 1.2, 12
    g = harmonic(amplitude, forcing_period, cycles=cycles)
    duration = cycles * forcing_period
    t = np.linspace(0.0, duration + 2 * period, 2_000_001)
    u = harmonic_response(t, amplitude, forcing_period, period, duration)
    expected = (2 * math.pi / period) ** 2 * np.max(np.abs(u))
    # the pulse is sampled at 4096 points per period for the IMs: ~1e-7 relative
    assert pseudo_spectral_acceleration(g, period) == pytest.approx(expected, rel=2e-6)


@pytest.mark.parametrize("period", [0.1, 0.5, 2.0])
def test_sa_of_a_record_matches_solve_ivp(period):
    g = read_record(DATA / "decaying_sine.AT2")
    w = 2 * math.pi / period

    def rhs(t, y):
        return [y[1], -g.acceleration(t) - 2 * ZETA * w * y[1] - w * w * y[0]]

    end = g.duration + 2 * period
    sol = integrate.solve_ivp(rhs, (0.0, end), [0.0, 0.0], method="DOP853", rtol=1e-11,
                              atol=1e-14, dense_output=True,
                              max_step=float(np.min(np.diff(g.times))))
    t = np.linspace(0.0, end, 400001)
    expected = w * w * np.max(np.abs(sol.sol(t)[0]))
    assert pseudo_spectral_acceleration(g, period) == pytest.approx(expected, rel=1e-6)


def test_sa_of_a_stiff_oscillator_is_the_pga():
    g = read_record(DATA / "decaying_sine.AT2")
    assert intensity_measure("sa(0.002)")(g) == pytest.approx(intensity_measure("pga")(g),
                                                               rel=1e-3)


# --- names, homogeneity, scaling -------------------------------------------------------------

def test_names_parse_and_unknown_names_list_the_options():
    ims = parse_intensity_measures("PGA, pgv,sa( 0.5 ),d5-95")
    assert [im.name for im in ims] == ["pga", "pgv", "sa(0.5)", "d5-95"]
    assert [im.unit for im in ims] == ["g", "m/s", "g", "s"]
    assert set(INTENSITY_MEASURES) == {"pga", "pgv", "pgd", "arias", "d5-95"}
    with pytest.raises(ValueError, match=r"unknown intensity measure 'pgq'.*pga, pgv.*sa\(T\)"):
        intensity_measure("pgq")
    for bad in ("sa(0)", "sa(-1)", "sa(x)", "sa(inf)"):
        with pytest.raises(ValueError, match=r"period T of sa\(T\) must be a number > 0"):
            intensity_measure(bad)
    with pytest.raises(ValueError, match="no intensity measure"):
        parse_intensity_measures(" , ")


NAMES = ["pga", "pgv", "pgd", "arias", "d5-95", "sa(0.3)"]


@pytest.mark.parametrize("factor", [2.5, -0.4])
def test_intensity_measures_are_homogeneous_in_the_amplitude(factor):
    for g in (read_record(DATA / "decaying_sine.csv"), ricker_wavelet(2.0, 0.5)):
        base = intensity_measures(g, NAMES)
        scaled = intensity_measures(g.scaled(factor), NAMES)
        for name in NAMES:
            exponent = intensity_measure(name).exponent
            assert scaled[name] == pytest.approx(abs(factor) ** exponent * base[name],
                                                 rel=1e-9), name


@pytest.mark.parametrize("name, level", [("pga", 0.35), ("pgv", 0.2), ("pgd", 0.05),
                                         ("arias", 0.8), ("sa(0.5)", 0.6)])
def test_scale_to_im_reaches_the_level(name, level):
    g = read_record(DATA / "decaying_sine.AT2")
    s = scale_to_im(g, name, level)
    assert intensity_measure(name)(s) == pytest.approx(level, rel=1e-12)
    assert s.name.startswith("record decaying_sine.AT2 x ")


def test_scale_to_im_refuses_duration_zero_motions_and_bad_levels():
    g = read_record(DATA / "decaying_sine.AT2")
    with pytest.raises(ValueError, match="d5-95.*does not change"):
        scale_to_im(g, "d5-95", 10.0)
    with pytest.raises(ValueError, match=r"level must be a finite number > 0 \[g\]"):
        scale_to_im(g, "pga", -0.1)
    still = linear_record([0.0, 1.0], [0.0, 0.0])
    with pytest.raises(ValueError, match="cannot be scaled"):
        scale_to_im(still, "pgv", 0.1)
    with pytest.raises(ValueError, match="zero everywhere"):
        significant_duration(still)
