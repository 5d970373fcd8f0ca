r"""Fragility statistics: the probability of failure, lognormal fits, bootstrap bands,
dispersions, the paper's polynomial fit and the empirical CDF.

Counts
    :func:`probability_of_failure`: :math:`P_F = h_f / h` of eq. (9) of the paper [1]_.
The lognormal fragility function
    :class:`LognormalFragility`, :math:`P(x) = \Phi(\ln(x/\theta)/\beta)`, fitted by maximum
    likelihood to binomial counts (:math:`z_j` failures of :math:`n_j` trials at each amplitude
    or stripe :math:`x_j`, Eq. (11) in [2]_): the log-likelihood

    .. math::

        \ell(\theta, \beta) = \sum_j \Bigl[z_j \ln P(x_j)
        + (n_j - z_j) \ln\bigl(1 - P(x_j)\bigr)\Bigr]

    is written once (:func:`log_likelihood`, in the probit form
    :math:`\eta_j = (\ln x_j - \ln\theta)/\beta`). :func:`fit_lognormal` maximises it for one
    set of counts, :func:`fit_lognormal_or_none` too but gives None where no maximum exists
    (:func:`separated`), :func:`probit_newton` for many sets at once (the bootstrap, the
    per-record fits), :func:`rising_part` chooses the part of a non-monotone pulse fragility
    curve a lognormal CDF can describe.
Variability
    :func:`bootstrap_lognormal` (percentile bootstrap band, ch. 13 of [3]_),
    :func:`common_dispersion_fit` (one median per record, one common dispersion: the
    arch-to-arch or geometric dispersion), :func:`dispersions` (record-to-record, geometric and
    total, and the square-root sum of squares of the first two).
The paper's curves
    :func:`fit_polynomial` and :func:`evaluate_polynomial_fit` (the quintic least-squares fit of
    Figs. 17-20 of [1]_), :func:`empirical_cdf` (the CDF of the limit-analysis sample, the blue
    curves of Figs. 17-20).

The module depends on numpy and scipy only: both fragility studies
(:mod:`archquake.studies.fragility`, :mod:`archquake.studies.record_fragility`) import it, and
any result can be refitted without them.

References
----------
.. [1] The paper, Sect. 5.3.3, Eq. (9), Figs. 17-21.
.. [2] Baker, J. W. (2015). Efficient analytical fragility function fitting using dynamic
   structural analysis. Earthquake Spectra 31(1), 579-599.
.. [3] Efron, B. and Tibshirani, R. J. (1993). An Introduction to the Bootstrap. Chapman & Hall,
   ch. 13 (percentile intervals).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import optimize, special

BAND_POINTS = 200
"""IM values (log-spaced over the levels) at which a bootstrap band is evaluated."""


def probability_of_failure(failed: np.ndarray) -> np.ndarray:
    r"""The estimated probability of failure of Eq. (9) in [1]_,

    .. math::

        P_F = \frac{h_f}{h},

    the fraction of the :math:`h` arches (first axis) that fail.

    Parameters
    ----------
    failed : array_like of bool, shape (h, ...)
        Failure of every arch (first axis) at every point of the rest of the shape.

    Returns
    -------
    ndarray, shape (...)
        :math:`P_F` [-].

    Raises
    ------
    ValueError
        If ``failed`` has no arch.

    References
    ----------
    .. [1] The paper, Sect. 5.3.3, Eq. (9).

    Examples
    --------
    >>> probability_of_failure([[False, True], [True, True], [False, True], [False, False]])
    array([0.25, 0.75])
    """
    failed = np.asarray(failed, dtype=bool)
    if failed.ndim < 1 or failed.shape[0] == 0:
        raise ValueError("failed must have at least one arch (first axis)")
    return failed.mean(axis=0)


@dataclass(frozen=True)
class LognormalFragility:
    r"""Lognormal fragility function [1]_:

    .. math::

        P_F(a) = \Phi\left(\frac{\ln(a/\theta)}{\beta}\right),

    :math:`\Phi` the standard normal CDF. Calling it evaluates :math:`P_F` [-] at amplitudes
    :math:`a` (0 for :math:`a \le 0`).

    Attributes
    ----------
    median : float
        :math:`\theta`: the amplitude with 50 % probability of failure [g] (or the unit of the
        intensity measure it was fitted to, :mod:`archquake.studies.record_fragility`).
    dispersion : float
        :math:`\beta`: the logarithmic standard deviation [-].

    References
    ----------
    .. [1] Baker, J. W. (2015). Efficient analytical fragility function fitting using dynamic
       structural analysis. Earthquake Spectra 31(1), 579-599.
    """

    median: float
    dispersion: float

    def __call__(self, amplitude) -> np.ndarray:
        a = np.asarray(amplitude, dtype=float)
        with np.errstate(divide="ignore"):
            z = np.log(np.where(a > 0, a, np.nan) / self.median) / self.dispersion
        return np.where(a > 0, special.ndtr(z), 0.0)


def log_likelihood(eta, trials, failures) -> np.ndarray:
    r"""Binomial log-likelihood of lognormal (probit) fragility counts: the one definition that
    every fit of the module maximises.

    With :math:`\eta_j = (\ln x_j - \ln\theta)/\beta` at each amplitude or stripe
    :math:`x_j`, :math:`P(x_j) = \Phi(\eta_j)` and :math:`1 - P(x_j) = \Phi(-\eta_j)`, so
    (Eq. (11) in [1]_ without its constant binomial coefficients)

    .. math::

        \ell = \sum_j z_j \ln\Phi(\eta_j) + (n_j - z_j) \ln\Phi(-\eta_j),

    with :math:`\ln\Phi` evaluated by :func:`scipy.special.log_ndtr` (accurate far in the
    tails).

    Parameters
    ----------
    eta : array_like, shape (..., L)
        :math:`\eta_j` [-] for every set of counts (leading axes) and stripe.
    trials : int or array_like
        :math:`n_j`, broadcastable to ``eta``.
    failures : array_like
        :math:`z_j`, broadcastable to ``eta``.

    Returns
    -------
    ndarray, shape (...)
        :math:`\ell` [-] (a 0-d array for one set).

    References
    ----------
    .. [1] Baker, J. W. (2015). Efficient analytical fragility function fitting using dynamic
       structural analysis. Earthquake Spectra 31(1), 579-599.

    Examples
    --------
    One stripe of 4 trials with 1 failure at the median (:math:`\eta = 0`): :math:`4 \ln 0.5`.

    >>> float(log_likelihood([0.0], 4, [1]))  # doctest: +ELLIPSIS
    -2.7725887...
    """
    eta = np.asarray(eta, dtype=float)
    n = np.asarray(trials, dtype=float)
    z = np.asarray(failures, dtype=float)
    return np.sum(z * special.log_ndtr(eta) + (n - z) * special.log_ndtr(-eta), axis=-1)


def fit_lognormal(amplitudes, trials, failures) -> LognormalFragility:
    r"""Maximum-likelihood lognormal fragility from binomial counts.

    With :math:`z_j` collapses in :math:`n_j` analyses at amplitude :math:`a_j`, the counts are
    binomial with probability :math:`P(a_j) = \Phi(\ln(a_j/\theta)/\beta)`, and the fit
    maximises the log-likelihood (Eq. (11) in [1]_, without its constant binomial coefficients)

    .. math::

        \{\hat\theta, \hat\beta\} = \arg\max_{\theta, \beta} \sum_j \Bigl[z_j \ln P(a_j)
        + (n_j - z_j) \ln\bigl(1 - P(a_j)\bigr)\Bigr].

    It is solved by Nelder-Mead in :math:`(\ln\theta, \ln\beta)` on :func:`log_likelihood`,
    from the amplitude nearest 50 % failures and :math:`\beta = 0.3`. Separated data (every
    survival at an amplitude no higher than every failure) have no maximum: the fit then tends
    to a step, and its dispersion is only as small as the optimizer's tolerances leave it
    (:func:`separated` tells such data; :func:`fit_lognormal_or_none` gives None for them).
    Where both exist, the fit agrees with :func:`probit_newton` to about 1e-8 (relative).

    Parameters
    ----------
    amplitudes : array_like of float
        Amplitudes :math:`a_j` > 0 [g] (or the unit of the intensity measure), 1-D, at least 2.
    trials : int or array_like of int
        Number of analyses :math:`n_j` at each amplitude (one number: the same at every one).
    failures : array_like of int
        Number of collapses :math:`z_j` at each amplitude, :math:`0 \le z_j \le n_j`.

    Returns
    -------
    LognormalFragility
        :math:`\hat\theta` [unit of ``amplitudes``] and :math:`\hat\beta` [-].

    Raises
    ------
    ValueError
        If the arrays do not match, an amplitude is not finite and > 0, a count is out of range,
        or the data hold no failure or no survival (no maximum exists).

    See Also
    --------
    fit_lognormal_or_none : the same fit, None where no maximum exists.

    References
    ----------
    .. [1] Baker, J. W. (2015). Efficient analytical fragility function fitting using dynamic
       structural analysis. Earthquake Spectra 31(1), 579-599.
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
        return -log_likelihood((x - mu) / math.exp(log_beta), n, z)

    # start from the amplitude nearest 50 % and a typical dispersion
    frac = z / n
    mu0 = x[np.argmin(np.abs(frac - 0.5))]
    res = optimize.minimize(nll, [mu0, math.log(0.3)], method="Nelder-Mead",
                            options={"xatol": 1e-10, "fatol": 1e-12, "maxiter": 4000})
    mu, log_beta = res.x
    return LognormalFragility(float(math.exp(mu)), float(math.exp(log_beta)))


def rising_part(probability) -> int:
    """Number of leading grid points up to and including the first point where ``probability``
    takes its largest value: the part of a fragility curve a monotone (lognormal) model can
    describe.

    A local maximum below the largest value does not end the rising part (a dip on the way up
    is kept in the data of the fit).

    Parameters
    ----------
    probability : array_like, shape (n,)
        P_F [-] on an increasing amplitude grid.

    Returns
    -------
    int
        In ``1 .. n``.

    Raises
    ------
    ValueError
        If ``probability`` is not a non-empty 1-D array.

    Examples
    --------
    >>> rising_part([0.0, 0.5, 0.25, 1.0, 1.0, 0.5])
    4
    """
    p = np.asarray(probability, dtype=float)
    if p.ndim != 1 or p.size == 0:
        raise ValueError("probability must be a non-empty 1-D array")
    return int(np.argmax(p)) + 1


def fit_polynomial(amplitudes, probabilities, degree: int = 5) -> np.polynomial.Polynomial:
    """Least-squares polynomial of ``degree`` (the paper: 5) through (a [g], P_F) points.

    The paper fits such a polynomial to each fragility curve (the dashed curves of Figs. 17-20).
    Evaluate it with :func:`evaluate_polynomial_fit`, which clips to [0, 1].

    Parameters
    ----------
    amplitudes : array_like
        Amplitudes [g].
    probabilities : array_like
        P_F [-] at ``amplitudes``.
    degree : int
        Degree of the polynomial.

    Returns
    -------
    numpy.polynomial.Polynomial
        The fit (in the scaled variable of :meth:`numpy.polynomial.Polynomial.fit`; ``convert()``
        gives the coefficients in powers of the amplitude [g]).

    Raises
    ------
    ValueError
        If the arrays differ in shape or hold no more than ``degree`` points.
    """
    a = np.asarray(amplitudes, dtype=float)
    p = np.asarray(probabilities, dtype=float)
    if a.shape != p.shape or a.size <= degree:
        raise ValueError(f"a degree-{degree} fit needs more than {degree} points, got {a.size}")
    return np.polynomial.Polynomial.fit(a, p, degree)


def evaluate_polynomial_fit(poly: np.polynomial.Polynomial, amplitude) -> np.ndarray:
    """The polynomial fit clipped to probabilities in [0, 1].

    Parameters
    ----------
    poly : numpy.polynomial.Polynomial
        A fit of :func:`fit_polynomial`.
    amplitude : float or array_like
        Amplitudes [g].

    Returns
    -------
    ndarray
        P_F [-], in [0, 1].
    """
    return np.clip(poly(np.asarray(amplitude, dtype=float)), 0.0, 1.0)


def separated(levels, trials, failures) -> bool:
    """Whether binomial stripe counts admit no maximum-likelihood lognormal fit.

    True if there is no failure or no survival, or if every survival lies at a level no higher
    than every failure (complete or quasi-complete separation: the likelihood grows without
    bound as the fit tends to a step, beta -> 0).

    Parameters
    ----------
    levels : array_like, shape (L,)
        Stripe levels [the IM's unit].
    trials : int or array_like
        Trials ``n_j`` per stripe.
    failures : array_like, shape (L,)
        Failures ``z_j`` per stripe.

    Returns
    -------
    bool

    Examples
    --------
    Survivals above a failure leave a maximum; a single mixed level between all survivals and
    all failures does not (quasi-complete separation):

    >>> separated([0.1, 0.2, 0.3], 10, [0, 4, 8]), separated([0.1, 0.2, 0.3], 10, [0, 4, 10])
    (False, True)
    """
    x = np.asarray(levels, dtype=float)
    n = np.broadcast_to(np.asarray(trials, dtype=float), x.shape)
    z = np.asarray(failures, dtype=float)
    fails, survives = z > 0, z < n
    if not np.any(fails) or not np.any(survives):
        return True
    return bool(np.max(x[survives]) <= np.min(x[fails]))


def fit_lognormal_or_none(levels, trials, failures) -> LognormalFragility | None:
    """Maximum-likelihood lognormal fragility of stripe counts, or None when none exists.

    Parameters
    ----------
    levels : array_like, shape (L,)
        Stripe levels [the IM's unit].
    trials : int or array_like
        Trials ``n_j`` per stripe.
    failures : array_like, shape (L,)
        Failures ``z_j`` per stripe.

    Returns
    -------
    LognormalFragility or None
        :func:`fit_lognormal`; None for fewer than two levels or separated counts
        (:func:`separated`).
    """
    if np.asarray(levels).size < 2 or separated(levels, trials, failures):
        return None
    return fit_lognormal(levels, trials, failures)


def _inverse_mills(t):
    """``phi(t) / Phi(t)`` [-], stable for large negative t."""
    return np.exp(-0.5 * t * t - 0.5 * math.log(2.0 * math.pi) - special.log_ndtr(t))


def probit_newton(log_levels, trials, failures, *, slope=None, start=(0.0, 1.0),
                  iterations: int = 60, tolerance: float = 1e-12):
    r"""Maximum likelihood of ``P = Phi(a + b ln x)`` for many sets of stripe counts at once.

    The lognormal fragility function is this probit model with :math:`b = 1/\beta` and
    :math:`a = -\ln(\theta)/\beta`; its log-likelihood

    .. math::

        \ell(a, b) = \sum_j z_j \ln\Phi(\eta_j) + (n_j - z_j) \ln\Phi(-\eta_j),
        \qquad \eta_j = a + b \ln x_j,

    is concave in :math:`(a, b)`, so Newton's method with step halving converges from any start
    when the maximum exists. Its score and (negative) Hessian come from
    :math:`\partial\ell/\partial\eta_j = z_j \lambda(\eta_j) - (n_j - z_j) \lambda(-\eta_j)`,
    :math:`\lambda = \varphi/\Phi` the inverse Mills ratio. Used where many fits are needed at
    once (bootstrap resamples, the records of :func:`common_dispersion_fit`); a single fit is
    :func:`fit_lognormal`.

    Parameters
    ----------
    log_levels : array, shape (L,)
        ``ln x_j`` [ln of the IM's unit].
    trials : array, broadcastable to ``failures``
        Trials ``n_j`` per stripe.
    failures : array, shape (..., L)
        Failures ``z_j`` per stripe, for every set.
    slope : float, optional
        If given, ``b`` is held at this value and only ``a`` is fitted.
    start : (float, float) or arrays
        Starting ``(a, b)``.
    iterations : int
        Largest number of Newton steps.
    tolerance : float
        Convergence: the largest Newton step [-].

    Returns
    -------
    a, b : ndarray, shape (...)
        The estimates [-] and [1/ln of the IM's unit] (nan for a set that did not converge).
    """
    u = np.asarray(log_levels, dtype=float)
    z = np.asarray(failures, dtype=float)
    n = np.broadcast_to(np.asarray(trials, dtype=float), z.shape)
    batch = z.shape[:-1]
    a = np.broadcast_to(np.asarray(start[0], dtype=float), batch).copy()
    b = np.broadcast_to(np.asarray(start[1] if slope is None else slope, dtype=float),
                        batch).copy()
    converged = np.zeros(batch, dtype=bool)

    def loglik(a_, b_):
        return log_likelihood(a_[..., None] + b_[..., None] * u, n, z)

    current = loglik(a, b)
    for _ in range(iterations):
        eta = a[..., None] + b[..., None] * u
        lam_p, lam_m = _inverse_mills(eta), _inverse_mills(-eta)
        score = z * lam_p - (n - z) * lam_m  # d loglik / d eta
        weight = z * lam_p * (eta + lam_p) + (n - z) * lam_m * (lam_m - eta)  # -d2/deta2 > 0
        g_a, h_aa = score.sum(-1), weight.sum(-1)
        if slope is None:
            g_b, h_ab, h_bb = (score * u).sum(-1), (weight * u).sum(-1), (weight * u * u).sum(-1)
            det = h_aa * h_bb - h_ab * h_ab
            with np.errstate(divide="ignore", invalid="ignore"):
                d_a = (h_bb * g_a - h_ab * g_b) / det
                d_b = (h_aa * g_b - h_ab * g_a) / det
        else:
            with np.errstate(divide="ignore", invalid="ignore"):
                d_a = g_a / h_aa
            d_b = np.zeros(batch)
        d_a = np.where(converged, 0.0, d_a)
        d_b = np.where(converged, 0.0, d_b)
        step = np.ones(batch)
        for _ in range(30):  # halve the step until the likelihood does not decrease
            trial = loglik(a + step * d_a, b + step * d_b)
            ok = np.isfinite(trial) & (trial >= current - 1e-12 * np.abs(current))
            if np.all(ok | converged):
                break
            step = np.where(ok | converged, step, 0.5 * step)
        a, b = a + step * d_a, b + step * d_b
        current = loglik(a, b)
        converged |= np.maximum(np.abs(step * d_a), np.abs(step * d_b)) <= tolerance * (
            1.0 + np.abs(a) + np.abs(b))
        if np.all(converged):
            break
    bad = ~converged | ~np.isfinite(a) | ~np.isfinite(b)
    return np.where(bad, np.nan, a), np.where(bad, np.nan, b)


@dataclass(frozen=True)
class BootstrapBand:
    """Percentile bootstrap of a lognormal fragility fit.

    Attributes
    ----------
    x : ndarray
        IM values of the band [the IM's unit].
    lower, upper : ndarray
        Band limits of P(collapse | IM = x) [-].
    median_interval, dispersion_interval : (float, float)
        Percentile intervals of theta [the IM's unit] and beta [-].
    resamples : int
        Resamples drawn.
    degenerate : int
        Resamples without a maximum-likelihood fit (left out).
    confidence : float
        Confidence level [-].
    """

    x: np.ndarray
    lower: np.ndarray
    upper: np.ndarray
    median_interval: tuple[float, float]
    dispersion_interval: tuple[float, float]
    resamples: int
    degenerate: int
    confidence: float

    def to_dict(self) -> dict:
        """The band's numbers as JSON-ready data.

        Returns
        -------
        dict
            ``resamples``, ``degenerate``, ``confidence``, ``median_interval`` [the IM's unit]
            and ``dispersion_interval`` [-] (the band itself is in
            :meth:`RecordFragilityResult.curves`).
        """
        return {"resamples": self.resamples, "degenerate": self.degenerate,
                "confidence": self.confidence, "median_interval": list(self.median_interval),
                "dispersion_interval": list(self.dispersion_interval)}


def bootstrap_lognormal(levels, failed, fit: LognormalFragility, *, resamples: int,
                        confidence: float, rng, x=None) -> BootstrapBand | None:
    r"""Confidence band of a lognormal fit by resampling the units of ``failed`` with replacement.

    Every leading axis of ``failed`` (arches, records) is resampled with replacement (drawn as
    multinomial multiplicities of its units), the counts :math:`z^{*b}_j` of resample :math:`b`
    rebuilt from the resampled units and refitted by maximum likelihood
    (:func:`probit_newton`, started from ``fit``); the band is the percentile interval (ch. 13
    of [1]_) of the refitted curves at every IM value :math:`x`,

    .. math::

        \Bigl[q_{\alpha/2}\{P^{*b}(x)\},\; q_{1-\alpha/2}\{P^{*b}(x)\}\Bigr], \qquad
        \alpha = 1 - \text{confidence},

    and the intervals of :math:`\theta` and :math:`\beta` are the same percentiles of their
    refitted values. Resamples whose counts are separated (:func:`separated`) or whose fit does
    not converge are left out and counted.

    Parameters
    ----------
    levels : array, shape (L,)
        Stripe levels [the IM's unit].
    failed : bool array, shape (units..., L)
        Failure of every unit at every level; every leading axis is resampled independently
        (e.g. ``(arches, records, L)``: arches and records).
    fit : LognormalFragility
        The fit to all data (start of every refit).
    resamples : int
        Number of resamples :math:`B`.
    confidence : float
        Central fraction of the refitted curves the band holds [-], in (0, 1).
    rng : numpy.random.Generator
        Source of the resampling.
    x : array, optional
        IM values of the band [the IM's unit] (default: :data:`BAND_POINTS` log-spaced over
        the levels).

    Returns
    -------
    BootstrapBand or None
        None if no resample has a fit.

    References
    ----------
    .. [1] Efron, B. and Tibshirani, R. J. (1993). An Introduction to the Bootstrap. Chapman &
       Hall, ch. 13 (percentile intervals).
    """
    y = np.asarray(failed, dtype=float)
    levels = np.asarray(levels, dtype=float)
    unit_axes = y.shape[:-1]
    counts = y
    weights = [rng.multinomial(size, np.full(size, 1.0 / size), size=resamples)
               for size in unit_axes]
    # z[b, j] = sum over units of (product of the units' multiplicities) * y[units, j]
    z = np.tensordot(weights[0], counts, axes=(1, 0))  # (B, rest..., L)
    for w in weights[1:]:
        z = np.einsum("bk...,bk->b...", z, w)
    trials = float(np.prod(unit_axes))
    u = np.log(levels)
    good = np.array([not separated(levels, trials, zb) for zb in z])
    a = np.full(resamples, np.nan)
    b = np.full(resamples, np.nan)
    if np.any(good):
        start = (-math.log(fit.median) / fit.dispersion, 1.0 / fit.dispersion)
        a[good], b[good] = probit_newton(u, trials, z[good], start=start)
    ok = np.isfinite(a) & np.isfinite(b) & (b > 0)
    if not np.any(ok):
        return None
    beta = 1.0 / b[ok]
    theta = np.exp(-a[ok] * beta)
    if x is None:
        x = np.geomspace(levels[0], levels[-1], BAND_POINTS)
    curves = special.ndtr(np.log(x[None, :] / theta[:, None]) / beta[:, None])
    tail = 50.0 * (1.0 - confidence)
    lower, upper = np.percentile(curves, [tail, 100.0 - tail], axis=0)
    return BootstrapBand(
        x=np.asarray(x, dtype=float), lower=lower, upper=upper,
        median_interval=tuple(float(v) for v in np.percentile(theta, [tail, 100.0 - tail])),
        dispersion_interval=tuple(float(v) for v in np.percentile(beta, [tail, 100.0 - tail])),
        resamples=int(resamples), degenerate=int(resamples - ok.sum()),
        confidence=float(confidence))


@dataclass(frozen=True)
class CommonDispersionFit:
    """Lognormal fragility per record with one common dispersion (:func:`common_dispersion_fit`).

    Attributes
    ----------
    dispersion : float
        The common dispersion beta_G [-].
    medians : ndarray
        Median theta_r of every record used [the IM's unit].
    records : ndarray of int
        Indices of the records used.
    """

    dispersion: float
    medians: np.ndarray
    records: np.ndarray


def common_dispersion_fit(levels, trials, failures) -> CommonDispersionFit | None:
    r"""Joint maximum-likelihood fit of :math:`P_r(x) = \Phi(\ln(x/\theta_r)/\beta)`: one median
    per set of counts (row of ``failures``) and one common dispersion.

    .. math::

        \hat\beta = \arg\max_\beta \max_{\theta_1 \dots \theta_R} \sum_r \sum_j
        \Bigl[z_{rj} \ln P_r(x_j) + (n_{rj} - z_{rj}) \ln\bigl(1 - P_r(x_j)\bigr)\Bigr]:

    the profile likelihood of :math:`\beta`, maximised by a bounded scalar search on
    :math:`\ln\beta \in [\ln 10^{-3}, \ln 10]`, each :math:`\theta_r` at given :math:`\beta` by
    Newton's method (:func:`probit_newton` with the slope held). It is the multiple-stripe fit
    of [1]_ with the records as groups. Rows with no failure or no survival are left out (they
    hold no information on :math:`\beta`).

    Parameters
    ----------
    levels : array, shape (L,)
        Stripe levels [the IM's unit].
    trials : int or array
        Trials :math:`n_{rj}` per stripe (e.g. the number of arches).
    failures : array, shape (R, L)
        Failures :math:`z_{rj}` per row and stripe.

    Returns
    -------
    CommonDispersionFit or None
        None if no row has both failures and survivals, or if every used row is a step
        (:func:`separated`), for which beta -> 0.

    References
    ----------
    .. [1] Baker, J. W. (2015). Efficient analytical fragility function fitting using dynamic
       structural analysis. Earthquake Spectra 31(1), 579-599.
    """
    u = np.log(np.asarray(levels, dtype=float))
    z = np.asarray(failures, dtype=float)
    n = np.broadcast_to(np.asarray(trials, dtype=float), z.shape)
    used = np.flatnonzero((z.sum(-1) > 0) & (z.sum(-1) < n.sum(-1)))
    if used.size == 0 or u.size < 2:
        return None
    z, n = z[used], n[used]
    if all(separated(np.exp(u), n[i], z[i]) for i in range(used.size)):
        return None
    centre = np.array([u[np.argmin(np.abs(zi / ni - 0.5))] for zi, ni in zip(z, n, strict=True)])

    def intercepts(beta):
        a, _ = probit_newton(u, n, z, slope=1.0 / beta, start=(-centre / beta, 1.0 / beta))
        return a

    def negative(log_beta):
        beta = math.exp(log_beta)
        a = intercepts(beta)
        if not np.all(np.isfinite(a)):
            return np.inf
        return -float(np.sum(log_likelihood(a[:, None] + u[None, :] / beta, n, z)))

    res = optimize.minimize_scalar(negative, bounds=(math.log(1e-3), math.log(10.0)),
                                   method="bounded", options={"xatol": 1e-9})
    beta = math.exp(res.x)
    a = intercepts(beta)
    return CommonDispersionFit(float(beta), np.exp(-a * beta), used)


DISPERSIONS = {
    "record_to_record": "dispersion of the lognormal fit to the nominal arch's stripes (one "
                        "geometry, the records vary)",
    "geometric": "common dispersion of lognormal fits with one median per record to the "
                 "irregular arches' stripes (the records fixed, the geometry varies)",
    "total": "dispersion of the lognormal fit to all arch-record pairs pooled",
    "srss": "sqrt(record_to_record^2 + geometric^2), for comparison with total",
}
"""The dispersions of a record-based study (:func:`dispersions`), in words."""


def dispersions(record_to_record: float | None, geometric: float | None,
                total: float | None) -> dict:
    r"""The three dispersions of a record-based fragility study and the square-root sum of
    squares of the first two.

    If the record-to-record and the arch-to-arch (geometric) variability were independent
    lognormal factors of the collapse level, the total dispersion would be

    .. math::

        \beta \approx \sqrt{\beta_{RTR}^2 + \beta_G^2},

    reported as ``srss`` beside the fitted total for comparison.

    Parameters
    ----------
    record_to_record : float or None
        :math:`\beta_{RTR}` [-]: the fit to one geometry's stripes (None: no fit).
    geometric : float or None
        :math:`\beta_G` [-]: :func:`common_dispersion_fit` (None: no estimate).
    total : float or None
        :math:`\beta` [-]: the fit to every arch-record pair pooled (None: no fit).

    Returns
    -------
    dict
        ``record_to_record``, ``geometric``, ``total`` and ``srss`` [-] (None where an input
        is None); their meanings are :data:`DISPERSIONS`.

    Examples
    --------
    >>> dispersions(0.3, 0.4, 0.45)["srss"]
    0.5
    """
    srss = None if record_to_record is None or geometric is None else math.hypot(
        record_to_record, geometric)
    return {"record_to_record": record_to_record, "geometric": geometric, "total": total,
            "srss": srss}


def empirical_cdf(values) -> tuple[np.ndarray, np.ndarray]:
    r"""Empirical cumulative distribution: sorted values and probabilities ``i / s``, i = 1..s.

    Parameters
    ----------
    values : array_like of float
        The sample (any shape; flattened), finite.

    Returns
    -------
    x : ndarray, shape (s,)
        The sorted values.
    p : ndarray, shape (s,)
        :math:`P(X \le x_i) = i / s` [-].
    """
    x = np.sort(np.asarray(values, dtype=float).ravel())
    if x.size == 0:
        raise ValueError("values must contain at least one number")
    if not np.all(np.isfinite(x)):
        raise ValueError("values must be finite numbers")
    return x, np.arange(1, x.size + 1) / x.size


__all__ = [
    "BAND_POINTS", "DISPERSIONS", "BootstrapBand", "CommonDispersionFit", "LognormalFragility",
    "bootstrap_lognormal", "common_dispersion_fit", "dispersions", "empirical_cdf",
    "evaluate_polynomial_fit", "fit_lognormal", "fit_lognormal_or_none", "fit_polynomial",
    "log_likelihood", "probability_of_failure", "probit_newton", "rising_part", "separated",
]
