"""Fragility statistics (archquake.studies.fits): P_F, the lognormal likelihood and its two
solvers, bootstrap bands, dispersions, the paper's polynomial and the empirical CDF, each against
an independent value (a closed form, a brute-force grid, another optimizer, hand-drawn resamples).
"""

import math

import numpy as np
import pytest
from scipy import optimize, special, stats

from archquake.studies.fits import (
    DISPERSIONS,
    LognormalFragility,
    bootstrap_lognormal,
    common_dispersion_fit,
    dispersions,
    empirical_cdf,
    evaluate_polynomial_fit,
    fit_lognormal,
    fit_lognormal_or_none,
    fit_polynomial,
    log_likelihood,
    probability_of_failure,
    probit_newton,
    rising_part,
    separated,
)
from likelihood_grid import grid_mle


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
    x, p = empirical_cdf([0.3, 0.1, 0.2, 0.4])
    assert x.tolist() == [0.1, 0.2, 0.3, 0.4] and p.tolist() == [0.25, 0.5, 0.75, 1.0]
    for bad in ([], [0.1, float("nan")]):
        with pytest.raises(ValueError, match="values"):
            empirical_cdf(bad)


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


# --------------------------------------------------------------------------------------------
# fits
# --------------------------------------------------------------------------------------------


def test_lognormal_fits_are_the_maximum_of_a_likelihood_grid():
    rng = np.random.default_rng(11)
    levels = np.linspace(0.2, 1.6, 15)
    trials = 60
    failures = rng.binomial(trials, stats.norm.cdf(np.log(levels / 0.7) / 0.45))
    medians, dispersions = np.linspace(0.5, 0.9, 401), np.linspace(0.25, 0.7, 451)
    grid_median, grid_beta = grid_mle(levels, trials, failures, medians, dispersions)
    fit = fit_lognormal(levels, trials, failures)  # the study's fit
    assert fit.median == pytest.approx(grid_median, abs=1e-3)
    assert fit.dispersion == pytest.approx(grid_beta, abs=1e-3)
    a, b = probit_newton(np.log(levels), trials, failures[None, :])  # the bootstrap's refit
    assert 1 / b[0] == pytest.approx(fit.dispersion, rel=1e-7)
    assert math.exp(-a[0] / b[0]) == pytest.approx(fit.median, rel=1e-7)


def test_separated_stripes_have_no_fit():
    levels = [0.2, 0.4, 0.6, 0.8]
    assert separated(levels, 10, [0, 0, 10, 10])  # a step
    assert separated(levels, 10, [0, 0, 4, 10])  # quasi-complete: one mixed stripe
    assert separated(levels, 10, [0, 0, 0, 0]) and separated(levels, 10, [10] * 4)
    assert not separated(levels, 10, [0, 3, 4, 10])
    assert not separated(levels, 10, [0, 10, 0, 10])  # non-monotone: a finite maximum exists


def test_geometric_dispersion_is_the_maximum_of_a_profile_likelihood_grid():
    """Two records, one median each and a common dispersion: brute force over a grid of all
    three parameters (separable: for each dispersion, the best median of each record)."""
    rng = np.random.default_rng(3)
    levels = np.linspace(0.3, 2.0, 12)
    truth = [(0.7, 0.3), (1.2, 0.3)]
    failures = np.array([rng.binomial(40, stats.norm.cdf(np.log(levels / m) / b))
                         for m, b in truth])
    fit = common_dispersion_fit(levels, 40, failures)
    medians, dispersions = np.geomspace(0.4, 2.0, 801), np.linspace(0.1, 0.6, 251)
    x = np.log(levels)
    s = (x[None, None, :] - np.log(medians)[:, None, None]) / dispersions[None, :, None]
    log_p, log_q = special.log_ndtr(s), special.log_ndtr(-s)
    best = 0.0
    for z in failures:
        ll = (z * log_p + (40 - z) * log_q).sum(-1)
        best = best + ll.max(axis=0)  # best median of this record, for every dispersion
    assert fit.dispersion == pytest.approx(dispersions[np.argmax(best)], abs=2e-3)
    for r, z in enumerate(failures):
        beta = dispersions[np.argmax(best)]
        sr = (x[None, :] - np.log(medians)[:, None]) / beta
        ll = (z * stats.norm.logcdf(sr) + (40 - z) * stats.norm.logsf(sr)).sum(-1)
        assert fit.medians[r] == pytest.approx(medians[np.argmax(ll)], rel=5e-3)


def test_geometric_dispersion_recovers_the_spread_of_simulated_arches():
    """Arches whose collapse level is lognormal around a median per record: the common
    dispersion of the fit is that spread."""
    rng = np.random.default_rng(8)
    levels = np.geomspace(0.3, 3.0, 20)
    record_medians = np.array([0.6, 0.9, 1.3, 1.8])
    capacity = record_medians[None, :] * np.exp(0.25 * rng.standard_normal((2000, 4)))
    failed = levels[None, None, :] >= capacity[..., None]
    fit = common_dispersion_fit(levels, 2000, failed.sum(axis=0))
    assert fit.dispersion == pytest.approx(0.25, rel=0.05)
    assert fit.medians == pytest.approx(record_medians, rel=0.03)


def _synthetic_failed(arches, records, rng):
    """Collapse of (arch, record) pairs: the collapse level is lognormal (median 0.8 g,
    dispersion 0.3 from the record, 0.2 from the arch)."""
    levels = np.geomspace(0.3, 2.0, 12)
    capacity = 0.8 * np.exp(0.3 * rng.standard_normal(records)[None, :]
                            + 0.2 * rng.standard_normal((arches, records)))
    return levels, levels[None, None, :] >= capacity[..., None]


def test_bootstrap_band_holds_the_fit_and_narrows_with_more_data():
    widths = []
    for arches, records in ((8, 8), (40, 40)):
        levels, failed = _synthetic_failed(arches, records, np.random.default_rng(1))
        fit = fit_lognormal(levels, arches * records, failed.sum(axis=(0, 1)))
        band = bootstrap_lognormal(levels, failed, fit, resamples=400, confidence=0.9,
                                   rng=np.random.default_rng(2))
        curve = fit(band.x)
        assert np.all(band.lower <= curve + 1e-9) and np.all(curve <= band.upper + 1e-9)
        lo, hi = band.median_interval
        assert lo <= fit.median <= hi
        widths.append((np.mean(band.upper - band.lower), hi - lo))
        again = bootstrap_lognormal(levels, failed, fit, resamples=400, confidence=0.9,
                                    rng=np.random.default_rng(2))
        assert np.array_equal(again.lower, band.lower)  # seeded
    # 5 times the records and arches: about half the width (the records dominate)
    assert widths[1][0] < 0.7 * widths[0][0] and widths[1][1] < 0.7 * widths[0][1]


def test_bootstrap_counts_are_those_of_the_resampled_pairs():
    """The counts of a resample are rebuilt from the resampled arches and records: with one
    resample drawn by hand, the refit equals fit_lognormal of those counts."""
    levels, failed = _synthetic_failed(6, 5, np.random.default_rng(4))
    fit = fit_lognormal(levels, 30, failed.sum(axis=(0, 1)))
    rng = np.random.default_rng(9)
    band = bootstrap_lognormal(levels, failed, fit, resamples=10, confidence=0.9, rng=rng,
                               x=np.array([fit.median]))
    rng = np.random.default_rng(9)
    w_arch = rng.multinomial(6, np.full(6, 1 / 6), size=10)
    w_rec = rng.multinomial(5, np.full(5, 1 / 5), size=10)
    refits = []
    for b in range(10):
        arches = np.repeat(np.arange(6), w_arch[b])
        records = np.repeat(np.arange(5), w_rec[b])
        z = failed[arches][:, records].sum(axis=(0, 1))
        if not separated(levels, 30, z):
            refits.append(fit_lognormal(levels, 30, z)(fit.median))
    lo, hi = np.percentile(refits, [5, 95])
    assert band.lower[0] == pytest.approx(lo, abs=1e-6)
    assert band.upper[0] == pytest.approx(hi, abs=1e-6)


# --------------------------------------------------------------------------------------------
# one likelihood, two solvers: against a closed form and an independent optimizer
# --------------------------------------------------------------------------------------------


def _newton(levels, trials, failures):
    """The Newton solver (probit_newton) as (median, dispersion)."""
    a, b = probit_newton(np.log(levels), trials, np.asarray(failures, float)[None, :])
    return math.exp(-a[0] / b[0]), 1.0 / b[0]


def _independent_mle(levels, trials, failures, start):
    """The binomial likelihood written with scipy.stats.binom (constants included), maximised
    by BFGS in (ln median, ln dispersion) from ``start``."""
    x, n, z = np.log(levels), np.broadcast_to(trials, np.shape(levels)), np.asarray(failures)

    def negative(p):
        prob = stats.norm.cdf((x - p[0]) / math.exp(p[1]))
        return -stats.binom.logpmf(z, n, np.clip(prob, 1e-300, 1 - 1e-16)).sum()

    res = optimize.minimize(negative, [math.log(start[0]), math.log(start[1])], method="BFGS",
                            options={"gtol": 1e-10})
    return math.exp(res.x[0]), math.exp(res.x[1])


@pytest.mark.parametrize("z", [(5, 15), (4, 18), (1, 11)])
def test_two_stripes_are_fitted_exactly_the_closed_form(z):
    """With two stripes a lognormal CDF can pass through both fractions p_j = z_j / n, and that
    is the maximum: beta = ln(x_2/x_1) / (Phi^-1(p_2) - Phi^-1(p_1)),
    theta = x_1 exp(-beta Phi^-1(p_1))."""
    x, n = np.array([0.4, 0.8]), 20
    q1, q2 = stats.norm.ppf(np.array(z) / n)
    beta = math.log(x[1] / x[0]) / (q2 - q1)
    theta = x[0] * math.exp(-beta * q1)
    for median, dispersion in (_newton(x, n, z), astuple(fit_lognormal(x, n, z)),
                               astuple(fit_lognormal_or_none(x, n, z))):
        assert median == pytest.approx(theta, rel=1e-7)
        assert dispersion == pytest.approx(beta, rel=1e-7)


def astuple(fit):
    return fit.median, fit.dispersion


# the rising parts of the pulse study of `archquake reproduce --quick` at t_p = 0.6 and 0.7 s
# (h = 6 arches), and random stripes
PULSE_QUICK = np.array([0.2, 0.25, 0.3, 0.35, 0.4, 0.45])
CASES = {
    "pulse t_p 0.6": (PULSE_QUICK, 6, [0, 0, 0, 3, 5, 6]),
    "pulse t_p 0.7": (PULSE_QUICK, 6, [0, 0, 0, 4, 5, 6]),
    "random stripes": (np.linspace(0.3, 0.9, 25), 40, np.random.default_rng(5).binomial(
        40, stats.norm.cdf(np.log(np.linspace(0.3, 0.9, 25) / 0.6) / 0.25))),
}


@pytest.mark.parametrize("case", list(CASES))
def test_both_solvers_find_the_maximum_of_an_independent_likelihood(case):
    """Nelder-Mead (fit_lognormal) and Newton (probit_newton) maximise the same likelihood:
    they agree to 1e-7 and with BFGS on scipy.stats.binom's likelihood to 1e-6 (BFGS stops
    on the gradient, less tightly)."""
    levels, n, z = CASES[case]
    assert not separated(levels, n, z)
    nelder_mead = astuple(fit_lognormal(levels, n, z))
    newton = _newton(levels, n, z)
    assert newton == pytest.approx(nelder_mead, rel=1e-7)
    independent = _independent_mle(levels, n, z, start=(float(np.median(levels)), 0.5))
    assert newton == pytest.approx(independent, rel=1e-6)
    # the score of the likelihood vanishes at Newton's estimate (probit form, eta = a + b ln x)
    b = 1 / newton[1]
    a = -math.log(newton[0]) * b
    eta = a + b * np.log(levels)
    lam_p = np.exp(stats.norm.logpdf(eta) - special.log_ndtr(eta))
    lam_m = np.exp(stats.norm.logpdf(eta) - special.log_ndtr(-eta))
    score = z * lam_p - (n - np.asarray(z)) * lam_m
    assert abs(score.sum()) < 1e-8 and abs((score * np.log(levels)).sum()) < 1e-8


def test_separated_counts_have_no_maximum():
    """Every survival at or below every failure (the quick pulse study at t_p = 0.4 s): the
    likelihood grows without bound as the fit tends to a step. Newton says so (nan),
    fit_lognormal_or_none gives None, and fit_lognormal stops at a near-step where the optimizer's
    tolerances leave it (the reason the two solvers are both kept, see the module)."""
    z = [0, 0, 0, 0, 2, 6]
    assert separated(PULSE_QUICK, 6, z)
    with np.errstate(invalid="ignore"):
        assert all(math.isnan(v) for v in _newton(PULSE_QUICK, 6, z))
    assert fit_lognormal_or_none(PULSE_QUICK, 6, z) is None
    step = fit_lognormal(PULSE_QUICK, 6, z)
    assert step.dispersion < 0.05 and 0.40 <= step.median <= 0.45
    # a steeper curve through the same P at the mixed stripe (0.40 g) is more likely still
    eta_mixed = math.log(0.40 / step.median) / step.dispersion
    steeper = step.dispersion / 2
    better = LognormalFragility(0.40 * math.exp(-eta_mixed * steeper), steeper)
    eta = [np.log(PULSE_QUICK / f.median) / f.dispersion for f in (step, better)]
    assert log_likelihood(eta[1], 6, z) > log_likelihood(eta[0], 6, z)


def test_log_likelihood_is_the_binomial_one():
    """log_likelihood + the binomial coefficients = scipy.stats.binom.logpmf summed."""
    rng = np.random.default_rng(2)
    eta = rng.normal(size=(3, 7))
    n = rng.integers(1, 30, size=7)
    z = rng.integers(0, n + 1)
    p = stats.norm.cdf(eta)
    expected = stats.binom.logpmf(z, n, p).sum(-1) - np.log(special.comb(n, z)).sum()
    assert log_likelihood(eta, n, z) == pytest.approx(expected, rel=1e-12)


def test_dispersions_and_their_square_root_sum_of_squares():
    assert dispersions(0.3, 0.4, 0.45) == {"record_to_record": 0.3, "geometric": 0.4,
                                           "total": 0.45, "srss": pytest.approx(0.5)}
    assert dispersions(None, 0.4, 0.45)["srss"] is None
    assert dispersions(0.3, None, None) == {"record_to_record": 0.3, "geometric": None,
                                            "total": None, "srss": None}
    assert set(DISPERSIONS) == {"record_to_record", "geometric", "total", "srss"}
