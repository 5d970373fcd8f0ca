"""The stochastic ground-motion model: reproducible from its seed, independent streams per
motion, and its expected Arias intensity and D5-95 reached in the mean over many draws."""

import math

import numpy as np
import pytest
from scipy import integrate, signal

from archquake.geometry import GRAVITY
from archquake.ground_motion import LINEAR, GroundMotion
from archquake.ground_motion.intensity import arias_intensity, husid_time, significant_duration
from archquake.ground_motion.stochastic import (
    high_pass,
    modulating_function,
    modulation_parameters,
    stochastic_motion,
    stochastic_suite,
)

TARGET = {"arias_intensity": 0.3, "significant_duration": 5.0, "midpoint_time": 4.0}
MODEL = dict(TARGET, filter_frequency=5.0, filter_frequency_rate=-0.1, filter_damping=0.2)
DRAWS = 200


def test_modulating_function_has_the_target_arias_intensity_and_duration():
    """The solved (alpha_1, alpha_2, alpha_3) against quadrature of q(t)^2."""
    alphas = modulation_parameters(**TARGET)
    q2 = lambda t: modulating_function(t, alphas) ** 2  # noqa: E731
    total = integrate.quad(q2, 0, np.inf, limit=200)[0]
    assert math.pi / (2 * GRAVITY) * total == pytest.approx(0.3, rel=1e-9)

    def when(fraction):
        from scipy.optimize import brentq
        return brentq(lambda t: integrate.quad(q2, 0, t, limit=200)[0] - fraction * total,
                      1e-6, 100.0, xtol=1e-12)

    assert when(0.45) == pytest.approx(4.0, rel=1e-8)
    assert when(0.95) - when(0.05) == pytest.approx(5.0, rel=1e-8)


def test_same_seed_same_motion_and_other_seeds_differ():
    a = stochastic_motion(**MODEL, rng=11)
    b = stochastic_motion(**MODEL, rng=11)
    c = stochastic_motion(**MODEL, rng=12)
    assert a.kind == LINEAR and np.array_equal(a.values, b.values)
    assert not np.allclose(a.values, c.values)
    assert a.times[1] == pytest.approx(0.01) and a.name.endswith("seed 11")
    g = stochastic_motion(**MODEL, rng=np.random.default_rng(11))
    assert np.array_equal(g.values, a.values)


def test_suite_member_does_not_depend_on_the_suite_size():
    small = stochastic_suite(2, **MODEL, seed=5)
    large = stochastic_suite(4, **MODEL, seed=5)
    for i in range(2):
        assert np.array_equal(small[i].values, large[i].values)
    assert [g.name for g in large] == ["stochastic-000", "stochastic-001", "stochastic-002",
                                       "stochastic-003"]
    seq = np.random.SeedSequence(5, spawn_key=(3,))
    assert np.array_equal(large[3].values, stochastic_motion(**MODEL, rng=seq).values)
    assert len({g.values.tobytes() for g in large}) == 4


@pytest.fixture(scope="module")
def draws():
    return (stochastic_suite(DRAWS, **MODEL, seed=2024, high_pass_frequency=None),
            stochastic_suite(DRAWS, **MODEL, seed=2024))


def test_expected_arias_intensity_is_reached_in_the_mean(draws):
    """The model sets E[xg''(t_i)^2] = q(t_i)^2, so the Arias intensity of the samples,
    pi/(2g) sum a_i^2 dt, has the target as its expectation (up to the sum standing for the
    integral, < 0.1 % here). Tolerance: 4 standard errors of the mean of 200 draws (about 1.4 %
    each), i.e. a correct model fails with probability 6e-5."""
    raw, _ = draws
    values = np.array([math.pi / (2 * GRAVITY) * np.sum(g.values ** 2) * 0.01 for g in raw])
    se = values.std(ddof=1) / math.sqrt(DRAWS)
    assert abs(values.mean() - 0.3) < 4 * se
    assert se / 0.3 < 0.02


def test_expected_husid_function_gives_the_target_duration_and_midpoint(draws):
    """D5-95 and t_mid are those of the expected Husid function; the ensemble mean of
    a(t_i)^2 over 200 draws estimates it. Tolerance 3 %: the ensemble mean still fluctuates by
    about 1 % in these times (seen over seeds), and a wrong shape of q would move them by far
    more."""
    raw, _ = draws
    mean_square = np.mean([g.values ** 2 for g in raw], axis=0)
    ensemble = GroundMotion(LINEAR, raw[0].times, np.sqrt(mean_square))
    assert significant_duration(ensemble) == pytest.approx(5.0, rel=0.03)
    assert husid_time(ensemble, 0.45) == pytest.approx(4.0, rel=0.03)


def test_high_pass_removes_little_energy_and_brings_the_ground_back(draws):
    raw, filtered = draws
    ratio = np.array([arias_intensity(f) / arias_intensity(r)
                      for r, f in zip(raw, filtered, strict=True)])
    assert 0.97 < ratio.mean() < 1.0  # measured about 0.99 for a 5-Hz motion, 0.1-Hz corner
    # ground velocity at the end: the high-passed record stops (nearly) at rest
    def end_velocity(g):
        return abs(np.sum(np.diff(g.times) * (g.values[1:] + g.values[:-1]) / 2))

    assert np.median([end_velocity(f) for f in filtered]) < 0.2 * np.median(
        [end_velocity(r) for r in raw])


def test_high_pass_matches_scipy_lsim():
    x = np.random.default_rng(0).standard_normal(400)
    t = 0.01 * np.arange(400)
    wc = 2 * math.pi * 0.5
    system = signal.StateSpace([[0.0, 1.0], [-wc * wc, -2.0 * wc]], [[0.0], [1.0]],
                               [[-wc * wc, -2.0 * wc]], [[1.0]])
    _, expected, _ = signal.lsim(system, x, t)
    assert high_pass(x, wc, 0.01) == pytest.approx(expected, abs=1e-12)


def test_default_motion_needs_no_file():
    g = stochastic_motion(rng=0)
    assert g.duration > 30 and np.all(np.isfinite(g.values)) and g.peak > 0


@pytest.mark.parametrize("kwargs, message", [
    ({"significant_duration": 30.0}, r"must be < 4\.925"),
    ({"filter_frequency_rate": -1.0}, "filter frequency .* must stay > 0"),
    ({"filter_damping": 1.0}, r"filter_damping must be in \(0, 1\)"),
    ({"dt": 0.2}, "too coarse"),
    ({"arias_intensity": -1}, "arias_intensity"),
    ({"rng": -3}, "seed must be >= 0"),
    ({"rng": "x"}, "rng must be"),
])
def test_bad_model_parameters(kwargs, message):
    with pytest.raises(ValueError, match=message):
        stochastic_motion(**{**MODEL, **kwargs})


def test_bad_suite_arguments():
    with pytest.raises(ValueError, match="n must be"):
        stochastic_suite(0, **MODEL)
    with pytest.raises(ValueError, match="do not pass rng"):
        stochastic_suite(2, **MODEL, rng=3)


def test_registered_by_name_with_a_seed():
    from archquake.ground_motion import ground_motion

    g = ground_motion("stochastic", seed=4, **MODEL)
    assert np.array_equal(g.values, stochastic_motion(**MODEL, rng=4).values)
    with pytest.raises(ValueError, match="seed must be a whole number"):
        ground_motion("stochastic", seed=1.5)
