r"""The annual risk of collapse: a fragility convolved with a site's hazard curve.

The mean annual frequency of collapse [1]_ [2]_

.. math::

    \lambda_c = \int_0^\infty P(C \mid IM = x)\, \left|\mathrm{d}\lambda(x)\right|
              = \int P_f(e^u)\, k(u)\, \lambda(e^u)\, \mathrm{d}u,
    \qquad k(u) = -\frac{\mathrm{d}\ln\lambda}{\mathrm{d}u},\ u = \ln x,

its probability in :math:`T` years :math:`P_T = 1 - e^{-\lambda_c T}` (Poisson occurrence)
and the return period :math:`1/\lambda_c`. The hazard :math:`\lambda(x)` is the
:class:`~archquake.site.hazard.HazardCurve`'s: log-log between levels, so :math:`k` is the
constant slope of each interval; held below the first level (:math:`k = 0`: what the fragility
adds below the first level is left out, and estimated apart, see :class:`RiskResult`); a power
law of the last interval's slope beyond the last level (the tail, whose share of
:math:`\lambda_c` is reported).

The integral is taken in :math:`u = \ln x` by composite Simpson's rule on every interval
between the hazard's levels (and a discrete fragility's), where the integrand is smooth, from
the first hazard level (or where the fragility rises above 1e-15) to the intensity beyond
which both the fragility is constant and the hazard a power law; from there on it is exact:
:math:`P_f(x_t)\,\lambda(x_t)`. The grid is refined (doubled) until two successive results
agree to 1e-9; the difference of the last two is the reported integration error.

References
----------
.. [1] Cornell, C. A., Jalayer, F., Hamburger, R. O. and Foutch, D. A. (2002). Probabilistic
   basis for 2000 SAC Federal Emergency Management Agency steel moment frame guidelines.
   Journal of Structural Engineering 128(4), 526-533 (Eq. 9: for
   :math:`\lambda(x) = k_0 x^{-k}` and a lognormal fragility,
   :math:`\lambda_c = k_0\,\theta^{-k} e^{k^2\beta^2/2}`).
.. [2] Eads, L., Miranda, E., Krawinkler, H. and Lignos, D. G. (2013). An efficient method for
   estimating the collapse risk of structures in seismic regions. Earthquake Engineering and
   Structural Dynamics 42(1), 25-41 (Eq. 1).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .hazard import HazardCurve

__all__ = ["RiskResult", "collapse_frequency", "risk", "RISK_RTOL"]

RISK_RTOL = 1e-9
"""Relative agreement of two successive grids at which the integral stops refining [-]."""

_START_DENSITY = 32
"""Simpson intervals per unit of ln(IM) of the first grid."""
_MAX_DENSITY = 32 * 2**9
_INSIDE = 1e-12
"""Relative nudge [-] that evaluates a segment's end nodes inside it (one-sided values at the
hazard's and a discrete fragility's levels)."""


def _flat_from(fragility) -> float:
    """ln of the intensity [g] beyond which the fragility is constant (to 1e-17)."""
    if hasattr(fragility, "levels"):
        return math.log(float(fragility.levels[-1]))
    return math.log(fragility.median) + 8.5 * fragility.dispersion


def _simpson(fragility, hazard: HazardCurve, edges: np.ndarray, slopes: np.ndarray,
             density: int) -> tuple[float, np.ndarray]:
    """Composite Simpson of P_f k lambda du over consecutive ``edges`` (slope of each
    segment ``slopes``), ``density`` intervals per unit of u (even per segment); the
    integral and the contribution of each segment."""
    lengths = np.diff(edges)
    m = np.maximum(2, 2 * np.ceil(lengths * density / 2.0)).astype(np.int64)
    seg = np.repeat(np.arange(lengths.size), m + 1)
    j = np.arange(seg.size) - np.repeat(np.concatenate(([0], np.cumsum(m + 1)[:-1])), m + 1)
    t = j / m[seg]
    t = np.clip(t, _INSIDE, 1.0 - _INSIDE)
    u = edges[seg] + lengths[seg] * t
    x = np.exp(u)
    g = fragility(x) * slopes[seg] * hazard.frequency(x)
    w = np.where((j == 0) | (j == m[seg]), 1.0, np.where(j % 2 == 1, 4.0, 2.0))
    h = lengths[seg] / m[seg]
    parts = np.bincount(seg, weights=w * g * h / 3.0, minlength=lengths.size)
    return float(parts.sum()), parts


def collapse_frequency(fragility, hazard: HazardCurve) -> dict:
    r"""The integral :math:`\lambda_c` [1/yr] and what it is made of (module docstring).

    Parameters
    ----------
    fragility : LognormalCollapseFragility or DiscreteCollapseFragility
        (:mod:`archquake.site.fragility_models`), in the hazard's intensity measure.
    hazard : HazardCurve

    Returns
    -------
    dict
        ``annual_frequency`` [1/yr], ``integration_error`` [1/yr] (difference of the last two
        grids), ``tail`` [1/yr] (the part beyond the last hazard level), ``intervals`` (the
        Simpson intervals of the last grid), ``fragility_at_first_level`` [-] and
        ``below_first_level`` [1/yr]: what the fragility would add below the first level were
        the hazard curve to continue there with the slope of its first interval (it is held
        instead, so this is left out of ``annual_frequency``).
    """
    levels = np.log(hazard.levels)
    top = max(levels[-1], _flat_from(fragility))
    start = max(levels[0], math.log(fragility.lowest))
    slopes_h = hazard.slopes
    remainder = float(fragility(math.exp(top)) * hazard.frequency(math.exp(top)))
    result = {"fragility_at_first_level": float(fragility(hazard.levels[0]))}
    if start >= top:
        total, tail, err, intervals = 0.0, 0.0, 0.0, 0
    else:
        inner = [levels[(levels > start) & (levels < top)]]
        if hasattr(fragility, "levels"):
            lv = np.log(fragility.levels)
            inner.append(lv[(lv > start) & (lv < top)])
        edges = np.unique(np.concatenate([[start, top], *inner]))
        mids = 0.5 * (edges[:-1] + edges[1:])
        index = np.clip(np.searchsorted(levels, mids) - 1, 0, slopes_h.size - 1)
        slopes = np.where(mids > levels[-1], hazard.tail_slope, slopes_h[index])
        density = _START_DENSITY
        previous, _ = _simpson(fragility, hazard, edges, slopes, density)
        while True:
            density *= 2
            total, parts = _simpson(fragility, hazard, edges, slopes, density)
            err = abs(total - previous)
            if err <= RISK_RTOL * abs(total) or density >= _MAX_DENSITY:
                break
            previous = total
        tail = float(parts[mids > levels[-1]].sum())
        intervals = int(np.maximum(2, 2 * np.ceil(np.diff(edges) * density / 2)).sum())
    # below the first level, the power law of the first interval (a diagnostic only)
    below = 0.0
    low = math.log(fragility.lowest)
    if low < levels[0]:
        k1, lam1 = float(slopes_h[0]), float(hazard.frequencies[0])
        u = np.linspace(low, levels[0], 2001)
        g = fragility(np.exp(u)) * k1 * lam1 * np.exp(-k1 * (u - levels[0]))
        below = float(np.sum((g[1:] + g[:-1]) * np.diff(u)) / 2.0)  # trapezoids
    result.update(annual_frequency=total + remainder, integration_error=err,
                  tail=tail + remainder, intervals=intervals,
                  below_first_level=below)
    return result


@dataclass(frozen=True)
class RiskResult:
    r"""The risk of collapse of a structure at a site (:func:`risk`).

    Attributes
    ----------
    annual_frequency : float
        :math:`\lambda_c`, mean annual frequency of collapse [1/yr].
    years : float
        :math:`T` [yr].
    probability : float
        :math:`1 - e^{-\lambda_c T}`, probability of collapse in T years [-].
    return_period : float
        :math:`1/\lambda_c` [yr] (inf when :math:`\lambda_c = 0`).
    integration_error : float
        Estimated error of :math:`\lambda_c` [1/yr].
    tail_share : float
        Share of :math:`\lambda_c` from beyond the hazard curve's last level (the power-law
        tail) [-].
    fragility_at_first_level : float
        :math:`P_f` at the hazard's first level [-]: what the fragility holds below the curve.
    below_first_level : float
        What :math:`\lambda_c` would gain were the hazard curve continued below its first
        level with its first slope [1/yr]; not included (the curve is held there).
    im : str
        The intensity measure.
    fragility : dict
        The fragility's ``to_dict()``.
    hazard_source : str
        The hazard curve's ``source``.
    annual_frequency_upper : float or None
        :math:`\lambda_c` with the upper-bound fragility (undecided analyses as collapses)
        [1/yr]; None without one.
    probability_upper : float or None
        Its probability in T years [-].
    """

    annual_frequency: float
    years: float
    probability: float
    return_period: float
    integration_error: float
    tail_share: float
    fragility_at_first_level: float
    below_first_level: float
    im: str
    fragility: dict
    hazard_source: str
    annual_frequency_upper: float | None = None
    probability_upper: float | None = None

    def to_dict(self) -> dict:
        """JSON-ready: the attributes, and ``units``."""
        return {
            "im": self.im,
            "annual_frequency": self.annual_frequency,
            "years": self.years,
            "probability": self.probability,
            "return_period": self.return_period,
            "annual_frequency_upper": self.annual_frequency_upper,
            "probability_upper": self.probability_upper,
            "integration_error": self.integration_error,
            "tail_share": self.tail_share,
            "fragility_at_first_level": self.fragility_at_first_level,
            "below_first_level": self.below_first_level,
            "fragility": self.fragility,
            "hazard_source": self.hazard_source,
            "units": {"annual_frequency": "1/yr", "years": "yr", "probability": "-",
                      "return_period": "yr", "integration_error": "1/yr",
                      "below_first_level": "1/yr", "im": "g"},
        }


def _probability(annual_frequency: float, years: float) -> float:
    return float(-math.expm1(-annual_frequency * years))


def risk(fragility, hazard: HazardCurve, *, years: float = 50.0,
         upper=None) -> RiskResult:
    r"""Mean annual frequency of collapse, its probability in ``years`` and return period.

    Parameters
    ----------
    fragility : LognormalCollapseFragility or DiscreteCollapseFragility
        :math:`P(C \mid IM)` (:mod:`archquake.site.fragility_models`).
    hazard : HazardCurve
        The site's hazard curve, in the fragility's intensity measure.
    years : float
        T > 0 [yr] (default 50, the nominal life of ordinary buildings in NTC 2018 2.4.1).
    upper : fragility, optional
        The upper-bound fragility of a study with undecided analyses
        (:attr:`~archquake.site.fragility_models.StudyFragility.upper`).

    Returns
    -------
    RiskResult

    Raises
    ------
    ValueError
        If the fragility's and the hazard's intensity measures differ (naming both), or
        ``years`` is not > 0.

    Examples
    --------
    >>> from archquake.site.fragility_models import LognormalCollapseFragility
    >>> hazard = HazardCurve([0.01, 10.0], [1e-2 * 0.01**-2, 1e-2 * 10.0**-2], im="PGA")
    >>> r = risk(LognormalCollapseFragility(0.5, 0.4), hazard)
    >>> round(r.annual_frequency / (1e-2 * 0.5**-2 * math.exp(2**2 * 0.4**2 / 2)), 6)
    1.0
    """
    years = float(years)
    if not (math.isfinite(years) and years > 0):
        raise ValueError(f"years must be > 0, got {years!r}")
    for f in (fragility, upper):
        if f is not None and f.im != hazard.im:
            raise ValueError(f"the fragility is in {f.im} but the hazard curve in "
                             f"{hazard.im}: they must be in the same intensity measure")
    parts = collapse_frequency(fragility, hazard)
    lam = parts["annual_frequency"]
    lam_upper = prob_upper = None
    if upper is not None:
        lam_upper = collapse_frequency(upper, hazard)["annual_frequency"]
        prob_upper = _probability(lam_upper, years)
    return RiskResult(
        annual_frequency=lam, years=years, probability=_probability(lam, years),
        return_period=1.0 / lam if lam > 0 else math.inf,
        integration_error=parts["integration_error"],
        tail_share=parts["tail"] / lam if lam > 0 else 0.0,
        fragility_at_first_level=parts["fragility_at_first_level"],
        below_first_level=parts["below_first_level"], im=hazard.im,
        fragility=fragility.to_dict(), hazard_source=hazard.source,
        annual_frequency_upper=lam_upper, probability_upper=prob_upper)
