"""Analytic pulses (Ricker, cycloidal, Mavroeidis-Papageorgiou, harmonic) against their closed
forms, written here independently of archquake's compiled evaluation, and in the engine."""

import math

import numpy as np
import pytest
from numpy.polynomial import hermite_e
from scipy import integrate

from archquake import oppenheim
from archquake.fourlink import engine
from archquake.fourlink.mechanism import mechanisms
from archquake.fourlink.time_history import simulate
from archquake.geometry import GRAVITY
from archquake.ground_motion import (
    ANALYTIC_GROUND_MOTIONS,
    GROUND_MOTIONS,
    HARMONIC,
    LINEAR,
    antisymmetric_ricker_wavelet,
    cycloidal_phase,
    cycloidal_pulse,
    ground_motion,
    harmonic,
    mavroeidis_papageorgiou_pulse,
    oppenheim_pulse,
    ricker_wavelet,
    sine_pulse,
)


def integrals(motion, t):
    """Ground velocity and displacement at the times ``t`` (sorted) by adaptive quadrature."""
    edges = np.concatenate(([0.0], t))
    dv = [integrate.quad(motion.acceleration, a, b, epsabs=1e-13, epsrel=1e-12, limit=200)[0]
          for a, b in zip(edges[:-1], edges[1:], strict=True)]
    v = np.cumsum(dv)
    vel = np.concatenate(([0.0], v))
    # displacement: integral of the velocity, by the trapezoid-free route d = int (t - s) a(s) ds
    d = [integrate.quad(lambda s, T=T: (T - s) * motion.acceleration(s), 0.0, T, epsabs=1e-13,
                        epsrel=1e-12, limit=400)[0] for T in t]
    return vel[1:], np.array(d)


def same(g, h):
    return (g.kind == h.kind and g.name == h.name and np.array_equal(g.params, h.params)
            and np.array_equal(g.times, h.times) and np.array_equal(g.values, h.values))


def fourier_peak_frequency(motion, dt=1e-3, pad=2 ** 20):
    t = np.arange(0.0, motion.duration, dt)
    spectrum = np.abs(np.fft.rfft(motion.acceleration(t), n=pad))
    return np.fft.rfftfreq(pad, dt)[np.argmax(spectrum)]


# --- Ricker wavelets -------------------------------------------------------------------------

def test_symmetric_ricker_closed_form_velocity_and_displacement():
    a_p, T = -3.0, 0.4
    g = ricker_wavelet(a_p, T)
    t0 = 2.0 * T
    assert g.duration == pytest.approx(4 * T)
    t = np.linspace(0.0, g.duration, 41)[1:-1]
    x2 = (math.pi * (t - t0) / T) ** 2
    assert g.acceleration(t) == pytest.approx(a_p * (1 - 2 * x2) * np.exp(-x2), abs=1e-14)
    v, d = integrals(g, t)
    assert v == pytest.approx(a_p * (t - t0) * np.exp(-x2), abs=1e-11)
    # d(t) = a_p T^2 / (2 pi^2) (exp(-x0^2) - exp(-x^2)), x0 = 2 pi at t = 0
    d_exact = a_p * T ** 2 / (2 * math.pi ** 2) * (math.exp(-4 * math.pi ** 2) - np.exp(-x2))
    assert d == pytest.approx(d_exact, abs=1e-11)
    assert g.peak == abs(a_p)


@pytest.mark.parametrize("factory", [ricker_wavelet, antisymmetric_ricker_wavelet])
def test_ricker_fourier_amplitude_peaks_at_one_over_period(factory):
    g = factory(1.0, 0.5)
    assert fourier_peak_frequency(g) == pytest.approx(2.0, abs=2e-3)


def test_antisymmetric_ricker_is_the_normalised_third_derivative_of_a_gaussian():
    a_p, T = 2.0, 0.3
    g = antisymmetric_ricker_wavelet(a_p, T)
    t = np.linspace(0.0, g.duration, 3001)[:-1]
    x = 2 * math.pi * (t - 2.5 * T) / (math.sqrt(3) * T)
    shape = hermite_e.hermeval(x, [0, 0, 0, 1]) * np.exp(-x ** 2 / 2)  # He3 = x^3 - 3x
    dense = np.linspace(-4, 4, 800001)
    beta = np.max(np.abs(hermite_e.hermeval(dense, [0, 0, 0, 1]) * np.exp(-dense ** 2 / 2)))
    assert beta == pytest.approx(1.3801, abs=1e-4)  # the published normalisation
    assert g.acceleration(t) == pytest.approx(a_p / beta * shape, abs=1e-9)
    i = np.argmax(np.abs(g.acceleration(t)))
    assert g.acceleration(t[i]) == pytest.approx(a_p, rel=1e-5) and t[i] < 2.5 * T
    assert g.peak == pytest.approx(a_p)
    v, d = integrals(g, np.array([g.duration]))
    assert v[0] == pytest.approx(0.0, abs=1e-12) and d[0] == pytest.approx(0.0, abs=1e-12)


# --- cycloidal pulses ------------------------------------------------------------------------

def test_cycloidal_phases_match_zhang_and_makris():
    assert cycloidal_phase(1) / math.pi == pytest.approx(0.0697, abs=5e-5)
    assert cycloidal_phase(2) / math.pi == pytest.approx(0.0410, abs=5e-5)


def test_cycloidal_type_a_is_a_fling_with_closed_form_velocity_and_displacement():
    a_p, T = 2.0, 0.6
    w = 2 * math.pi / T
    g = cycloidal_pulse(a_p, T, "A")
    t = np.linspace(0.0, T, 13)[1:]
    assert g.acceleration(t[:-1]) == pytest.approx(a_p * np.sin(w * t[:-1]), abs=1e-14)
    v, d = integrals(g, t)
    assert v == pytest.approx(a_p / w * (1 - np.cos(w * t)), abs=1e-12)
    assert d == pytest.approx(a_p / w * t - a_p / w ** 2 * np.sin(w * t), abs=1e-12)
    assert d[-1] == pytest.approx(a_p * T ** 2 / (2 * math.pi))  # permanent displacement
    assert same(g, ground_motion("cycloidal-a", a_p, T)) and g.acceleration(T) == 0.0


def test_cycloidal_type_b_returns_to_rest_in_place():
    a_p, T = -1.5, 0.5
    w = 2 * math.pi / T
    g = cycloidal_pulse(a_p, T, "B")
    t = np.linspace(0.0, T, 11)[1:]
    assert g.acceleration(0.0) == a_p  # the acceleration jumps at the start
    assert g.acceleration(t[:-1]) == pytest.approx(a_p * np.cos(w * t[:-1]), abs=1e-14)
    v, d = integrals(g, t)
    assert v == pytest.approx(a_p / w * np.sin(w * t), abs=1e-12)
    assert d == pytest.approx(a_p / w ** 2 * (1 - np.cos(w * t)), abs=1e-12)


@pytest.mark.parametrize("n", [1, 2, 3])
def test_cycloidal_type_cn_ends_at_rest_where_it_started(n):
    a_p, T = 1.0, 0.4
    g = cycloidal_pulse(a_p, T, "C", n)
    phi = cycloidal_phase(n)
    assert g.duration == pytest.approx((n + 0.5 - phi / math.pi) * T)
    t = np.linspace(0.0, g.duration, 9)[1:-1]
    assert g.acceleration(t) == pytest.approx(a_p * np.cos(2 * math.pi * t / T + phi), abs=1e-14)
    v, d = integrals(g, np.array([g.duration]))
    assert v[0] == pytest.approx(0.0, abs=1e-12) and d[0] == pytest.approx(0.0, abs=1e-12)
    assert same(g, ground_motion("cycloidal-c", a_p, T, n=n))


@pytest.mark.parametrize("kwargs, message", [
    ({"pulse_type": "D"}, "pulse_type"), ({"pulse_type": "C", "n": 0}, "whole number >= 1"),
    ({"pulse_type": "C", "n": 1.5}, "whole number"), ({"pulse_type": "A", "n": 2}, "type-C_n"),
])
def test_bad_cycloidal_parameters(kwargs, message):
    with pytest.raises(ValueError, match=message):
        cycloidal_pulse(1.0, 0.5, **kwargs)


# --- Mavroeidis-Papageorgiou -----------------------------------------------------------------

@pytest.mark.parametrize("gamma, nu", [(1.5, 0.0), (2.0, math.pi / 2), (3.0, 1.0)])
def test_mavroeidis_papageorgiou_velocity_matches_the_published_velocity_pulse(gamma, nu):
    amplitude, T = -2.0, 0.8
    g = mavroeidis_papageorgiou_pulse(amplitude, T, gamma, nu)
    f_p, t0 = 1 / T, gamma * T / 2
    A = g.params[0] * T / math.pi  # the paper's velocity amplitude
    t = np.linspace(0.0, g.duration, 17)[1:]
    v_paper = A / 2 * (1 + np.cos(2 * math.pi * f_p * (t - t0) / gamma)) * np.cos(
        2 * math.pi * f_p * (t - t0) + nu)
    v, _ = integrals(g, t)
    assert v == pytest.approx(v_paper, abs=1e-11 * abs(A) + 1e-13)
    dense = np.linspace(0.0, g.duration, 400001)
    assert np.max(np.abs(g.acceleration(dense))) == pytest.approx(abs(amplitude), rel=1e-9)
    assert g.peak == pytest.approx(abs(amplitude), rel=1e-12)
    assert g.acceleration(np.array([0.0, g.duration - 1e-12])) == pytest.approx([0, 0], abs=1e-9)


def test_mavroeidis_papageorgiou_bad_gamma():
    with pytest.raises(ValueError, match="gamma must be > 1"):
        mavroeidis_papageorgiou_pulse(1.0, 0.5, gamma=1.0)


# --- harmonic, registry, scaling -------------------------------------------------------------

def test_harmonic_takes_a_period_and_cycles():
    h = harmonic(amplitude=1.0, period=0.2, cycles=3)
    assert h.duration == pytest.approx(0.6) and h.kind == HARMONIC
    assert same(h, ground_motion("harmonic", 1.0, 0.2, cycles=3))
    assert sine_pulse(1.0, 0.2).acceleration(0.05) == pytest.approx(1.0)


def test_every_analytic_motion_is_amplitude_times_a_shape_of_t_over_its_time_scale():
    for name in ANALYTIC_GROUND_MOTIONS:
        unit = ground_motion(name, 1.0, 1.0)
        g = ground_motion(name, -2.5, 0.3)
        t = np.linspace(0.0, g.duration * 1.1, 57)
        assert g.acceleration(t) == pytest.approx(-2.5 * unit.acceleration(t / 0.3),
                                                  abs=1e-12), name
        assert g.duration == pytest.approx(0.3 * unit.duration), name
        assert g.peak == pytest.approx(2.5 * unit.peak), name
        assert g.reversed().acceleration(t) == pytest.approx(-g.acceleration(t)), name
        assert g.scaled(2.0).acceleration(t) == pytest.approx(2 * g.acceleration(t)), name
    assert set(ANALYTIC_GROUND_MOTIONS) < set(GROUND_MOTIONS)


def test_tabulated_pulse_interpolates_the_exact_pulse():
    g = mavroeidis_papageorgiou_pulse(3.0, 0.5, 2.5, 0.7)
    table = g.tabulated(1e-3)
    assert table.kind == LINEAR and table.duration == pytest.approx(g.duration)
    t = np.linspace(0.0, g.duration, 777)
    # linear interpolation error <= h^2/8 max|a''|, |a''| <= (2 pi / T)^2 (1 + 1/gamma)^2 |a|
    bound = 1e-6 / 8 * (2 * math.pi / 0.5 * 1.4) ** 2 * 3.0 * 1.5
    assert np.max(np.abs(table.acceleration(t) - g.acceleration(t))) < bound


# --- in the engine ---------------------------------------------------------------------------

@pytest.fixture(scope="module")
def arch_tables():
    mech_l, mech_r = mechanisms(oppenheim())
    return engine.tabulate(mech_l), engine.tabulate(mech_r)


@pytest.mark.parametrize("name", ["ricker", "ricker-antisymmetric", "cycloidal-b",
                                  "mavroeidis-papageorgiou"])
def test_pulse_grid_scales_the_template_as_the_factory_does(arch_tables, name):
    durations = np.array([0.2, 0.35, 0.5])
    amplitudes = np.array([-0.6, -0.9, 0.8]) * GRAVITY
    grid = engine.outcomes_grid(*arch_tables, 0.9, 0.9, durations, amplitudes, motion=name)
    for i, (tp, a) in enumerate(zip(durations, amplitudes, strict=True)):
        o = simulate(arch_tables, ground_motion(name, a, tp), (0.9, 0.9), record=False)
        assert grid["status"][i] == int(o.status)
        assert grid["max_phi"][i] == pytest.approx(o.max_phi, rel=1e-9, abs=1e-12)


def test_exact_pulse_and_its_fine_table_give_the_same_response(arch_tables):
    g = mavroeidis_papageorgiou_pulse(-1.6 * GRAVITY, 0.8, 2.0, 0.5)
    exact = simulate(arch_tables, g, (0.9, 0.9), record=False)
    table = simulate(arch_tables, g.tabulated(0.8 / 4096), (0.9, 0.9), record=False)
    assert exact.status == table.status and exact.impacts == table.impacts
    assert exact.max_phi > 0.01
    assert table.max_phi == pytest.approx(exact.max_phi, rel=1e-5)


@pytest.mark.parametrize("build", [lambda t: oppenheim_pulse(-GRAVITY, t),
                                   lambda t: harmonic(GRAVITY, t, cycles=2)])
def test_a_pulse_of_centuries_is_refused_naming_its_parameter(build):
    """Hardening (found by the fuzzer): a duration of 6e307 s overflowed the pulse's end to
    infinity and was refused as "ground motion times must be finite numbers"."""
    with pytest.raises(ValueError, match=r"(duration|period) must be at most 60 .*"
                                         r"MAX_PULSE_DURATION"):
        build(5.99e307)
    assert build(60.0).duration >= 60.0
