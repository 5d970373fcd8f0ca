"""Fragility of irregular arches [paper, Sect. 5.3.3, eq. (9), Figs. 17–21].

The estimated probability of failure at a pulse duration t_p and amplitude a is

    P_F(t_p, a) = h_f(t_p, a) / h                                             (eq. 9)

where h is the number of sampled irregular arches and h_f those that collapse. Two fits of a
fragility curve are provided: the paper's fifth-degree polynomial, and the lognormal fragility
function ``P_F = Phi(ln(a / median) / dispersion)`` fitted by maximum likelihood to the binomial
counts, the standard form in earthquake engineering.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import optimize, stats


def probability_of_failure(failed: np.ndarray) -> np.ndarray:
    """P_F = h_f / h (eq. 9) from a boolean array ``failed[arch, ...]`` [-]."""
    failed = np.asarray(failed, dtype=bool)
    if failed.ndim < 1 or failed.shape[0] == 0:
        raise ValueError("failed must have at least one arch (first axis)")
    return failed.mean(axis=0)


@dataclass(frozen=True)
class LognormalFragility:
    """Lognormal fragility function ``P_F(a) = Phi(ln(a / median) / dispersion)``.

    Attributes
    ----------
    median : float
        Amplitude with 50 % probability of failure [g].
    dispersion : float
        Logarithmic standard deviation beta [-].
    """

    median: float
    dispersion: float

    def __call__(self, amplitude) -> np.ndarray:
        a = np.asarray(amplitude, dtype=float)
        with np.errstate(divide="ignore"):
            z = np.log(np.where(a > 0, a, np.nan) / self.median) / self.dispersion
        return np.where(a > 0, stats.norm.cdf(z), 0.0)


def fit_lognormal(amplitudes, trials, failures) -> LognormalFragility:
    """Maximum-likelihood lognormal fragility from binomial counts.

    Maximises ``sum_j z_j ln P(a_j) + (n_j - z_j) ln(1 - P(a_j))`` over (median, dispersion).

    Parameters
    ----------
    amplitudes : array of float
        Amplitudes a_j > 0 [g].
    trials : array of int
        Number of analyses n_j at each amplitude.
    failures : array of int
        Number of collapses z_j at each amplitude.
    """
    a = np.asarray(amplitudes, dtype=float)
    n = np.broadcast_to(np.asarray(trials, dtype=float), a.shape)
    z = np.asarray(failures, dtype=float)
    if a.shape != z.shape or a.ndim != 1 or a.size < 2:
        raise ValueError("amplitudes and failures must be 1-D arrays of the same length (>= 2)")
    if np.any(a <= 0) or not np.all(np.isfinite(a)):
        raise ValueError("amplitudes must be finite and > 0 [g] for a lognormal fit")
    if np.any(z < 0) or np.any(z > n):
        raise ValueError("failures must be between 0 and the number of trials")
    if z.sum() == 0 or z.sum() == n.sum():
        raise ValueError("a lognormal fit needs both failures and survivals in the data")
    x = np.log(a)

    def nll(p):
        mu, log_beta = p
        beta = math.exp(log_beta)
        s = (x - mu) / beta
        return -(z * stats.norm.logcdf(s) + (n - z) * stats.norm.logsf(s)).sum()

    # start from the amplitude nearest 50 % and a typical dispersion
    frac = z / n
    mu0 = x[np.argmin(np.abs(frac - 0.5))]
    res = optimize.minimize(nll, [mu0, math.log(0.3)], method="Nelder-Mead",
                            options={"xatol": 1e-10, "fatol": 1e-12, "maxiter": 4000})
    mu, log_beta = res.x
    return LognormalFragility(float(math.exp(mu)), float(math.exp(log_beta)))


def fit_polynomial(amplitudes, probabilities, degree: int = 5) -> np.polynomial.Polynomial:
    """Least-squares polynomial of ``degree`` (the paper: 5) through (a [g], P_F) points.

    Evaluate with :func:`evaluate_polynomial_fit`, which clips to [0, 1].
    """
    a = np.asarray(amplitudes, dtype=float)
    p = np.asarray(probabilities, dtype=float)
    if a.shape != p.shape or a.size <= degree:
        raise ValueError(f"a degree-{degree} fit needs more than {degree} points, got {a.size}")
    return np.polynomial.Polynomial.fit(a, p, degree)


def evaluate_polynomial_fit(poly: np.polynomial.Polynomial, amplitude) -> np.ndarray:
    """The polynomial fit clipped to probabilities in [0, 1]."""
    return np.clip(poly(np.asarray(amplitude, dtype=float)), 0.0, 1.0)


def empirical_cdf(values) -> tuple[np.ndarray, np.ndarray]:
    """Sorted values and their empirical cumulative probabilities i/s, i = 1..s."""
    v = np.sort(np.asarray(values, dtype=float).ravel())
    if v.size == 0:
        raise ValueError("values must not be empty")
    return v, np.arange(1, v.size + 1) / v.size
