"""Brute-force maximum likelihood of a lognormal fragility function (for the fit tests): the
binomial likelihood written here with scipy.stats, evaluated on a grid of (median, dispersion)."""

import numpy as np
from scipy import stats


def grid_mle(levels, trials, failures, medians, dispersions):
    """The best node of the binomial log-likelihood on a (median, dispersion) grid."""
    x = np.log(np.asarray(levels, float))
    m, b = np.meshgrid(np.log(medians), dispersions, indexing="ij")
    s = (x[None, None, :] - m[..., None]) / b[..., None]
    n = np.broadcast_to(trials, x.shape)
    ll = (failures * stats.norm.logcdf(s) + (n - failures) * stats.norm.logsf(s)).sum(-1)
    i, j = np.unravel_index(np.argmax(ll), ll.shape)
    return medians[i], dispersions[j]
