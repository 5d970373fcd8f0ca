import numpy as np
import pytest
from scipy import stats

from archquake.limit_analysis import empirical_cdf
from archquake.studies.fragility import (
    LognormalFragility,
    evaluate_polynomial_fit,
    fit_lognormal,
    fit_polynomial,
    probability_of_failure,
    rising_part,
)


def test_probability_of_failure_is_fraction_of_failed_arches():
    failed = np.array([[1, 0, 1], [1, 1, 0], [0, 0, 1], [1, 0, 1]], dtype=bool)
    assert probability_of_failure(failed) == pytest.approx([0.75, 0.25, 0.75])


def test_lognormal_mle_recovers_parameters_from_exact_expected_counts():
    a = np.linspace(0.2, 1.2, 41)
    truth = LognormalFragility(median=0.55, dispersion=0.22)
    n = np.full(a.size, 10**6)
    z = np.round(truth(a) * n)
    fit = fit_lognormal(a, n, z)
    assert fit.median == pytest.approx(0.55, rel=1e-4)
    assert fit.dispersion == pytest.approx(0.22, rel=1e-3)


def test_lognormal_mle_matches_probit_glm_on_random_data():
    # independent check: the MLE is a probit regression on ln(a); solve its score equations
    rng = np.random.default_rng(5)
    a = np.linspace(0.3, 0.9, 25)
    n = np.full(a.size, 40)
    z = rng.binomial(n, stats.norm.cdf(np.log(a / 0.6) / 0.25))
    fit = fit_lognormal(a, n, z)
    x = np.log(a)
    b1, b0 = 1 / fit.dispersion, -np.log(fit.median) / fit.dispersion
    s = b0 + b1 * x
    w = stats.norm.pdf(s) * (z - n * stats.norm.cdf(s)) / (stats.norm.cdf(s) * stats.norm.sf(s))
    assert abs(w.sum()) < 1e-3 and abs((w * x).sum()) < 1e-3


def test_quintic_fit_reproduces_a_quintic():
    a = np.linspace(0.2, 1.0, 81)
    p = 0.5 + 0.3 * (a - 0.6) - 2 * (a - 0.6) ** 3 + 5 * (a - 0.6) ** 5
    poly = fit_polynomial(a, p)
    assert poly(a) == pytest.approx(p, abs=1e-10)
    line = np.polynomial.Polynomial([-1.0, 3.0])  # -1 at a = 0, 2 at a = 1
    assert evaluate_polynomial_fit(line, [0.0, 0.5, 1.0]).tolist() == [0.0, 0.5, 1.0]


def test_empirical_cdf():
    v, p = empirical_cdf([0.3, 0.1, 0.2])
    assert v.tolist() == [0.1, 0.2, 0.3]
    assert p.tolist() == pytest.approx([1 / 3, 2 / 3, 1])


def test_bad_fit_input():
    with pytest.raises(ValueError, match="both failures and survivals"):
        fit_lognormal([0.1, 0.2], [5, 5], [0, 0])
    with pytest.raises(ValueError, match="> 0"):
        fit_lognormal([0.0, 0.2], [5, 5], [1, 2])
    with pytest.raises(ValueError, match="more than 5 points"):
        fit_polynomial([0.1, 0.2], [0, 1])


def test_rising_part_ends_at_the_first_maximum():
    # a pulse's fragility rises, holds, dips in the recovery band and rises again
    p = np.array([0.0, 0.1, 0.6, 0.95, 0.95, 0.7, 0.5, 0.9, 0.95])
    assert rising_part(p) == 4
    assert rising_part(np.array([0.0, 0.5, 1.0])) == 3
    with pytest.raises(ValueError):
        rising_part(np.array([]))
