r"""Where the stripes of a record-based fragility go: a pilot over the records, and the levels
chosen from it.

A multiple-stripe analysis (:func:`archquake.studies.record_fragility.run_record_fragility`)
needs its levels :math:`x_j` where the collapses happen: too low and no record collapses the
arch, too high and every record does, and the lognormal fit has nothing to fit. A pilot finds,
for every record :math:`r`, the lowest scale factor :math:`s_r` on a geometric grid of PGA from
:math:`k g` to :math:`30 k g` that collapses the structure in either polarity
(:func:`record_pilot`); the record then collapses it from about :math:`IM_r\, s_r^{p}` on, with
:math:`IM_r` the record's intensity and :math:`p` the measure's exponent
(:attr:`archquake.ground_motion.IntensityMeasure.exponent`). :func:`stripe_levels` spaces the
stripes evenly in logarithm from 0.8 times the lowest of these to 1.25 times the highest,

.. math::

    x_j = x_{\min} \left(\frac{x_{\max}}{x_{\min}}\right)^{j / (L - 1)}, \quad
    x_{\min} = 0.8\, w \min_r IM_r s_r^p, \quad x_{\max} = 1.25 \max_r IM_r s_r^p,

:math:`j = 0 \dots L-1`, with :math:`w \le 1` lowering the first stripe below the collapses of
arches weaker than the structure (its irregular arches). :func:`median_collapse_pga` is the
median over the records of the lowest collapsing PGA: one level at which about half the
records collapse the structure.
"""

from __future__ import annotations

import math

import numpy as np

PILOT_RANGE = (1.0, 30.0, 25)
"""PGA levels of the pilot, in units of k g: ``geomspace(1, 30, 25)`` (from the activation to
thirty times it)."""


def _significant(x: float, digits: int = 4) -> float:
    return float(f"{x:.{digits}g}")


def pilot_levels(k: float) -> np.ndarray:
    """The PGA levels of the pilot [g]: :data:`PILOT_RANGE` times ``k`` (the collapse
    multiplier [-])."""
    return k * np.geomspace(*PILOT_RANGE)


def record_pilot(model, suite, k: float | None = None) -> dict:
    """The lowest scale factor of every record that collapses the structure (either polarity),
    on a geometric grid of PGA from k to 30 k (:data:`PILOT_RANGE`): where the stripes of the
    record-based fragility belong (:func:`stripe_levels`).

    A model whose grid is one call (the four-link model) runs every level; a model whose
    analyses are single (the rigid blocks) is run up the grid, both polarities a level, until
    the first level that collapses the structure: the same answer, without the levels above
    it. There a run left undecided counts as a collapse (the record's first factor is then a
    lower bound on its collapse, never hidden as a survival) and is counted.

    Parameters
    ----------
    model : StructuralModel
        The structure's model.
    suite : RecordSuite
        The records.
    k : float, optional
        The collapse multiplier the grid starts from [-] (default: the least of the model's
        ``load_multipliers``).

    Returns
    -------
    dict
        ``pga_levels`` [g] of the grid, ``pga`` of every record [g], ``first_factor`` [-]
        of every record (None: no collapse on the grid), the ``analyses`` run for every record
        and the runs left ``undecided``. JSON-ready.
    """
    from ..status import Status
    from .record_fragility import record_outcomes

    grid = pilot_levels(min(model.load_multipliers) if k is None else float(k))
    pga = suite.intensities("pga")
    first, analyses, undecided = [], [], 0
    for motion, value in zip(suite.motions(cached=True), pga, strict=True):
        factors = grid / value
        if model.grid_in_one_call:
            out = record_outcomes(model, motion, np.concatenate([factors, -factors]))
            collapsed = (out["status"].reshape(2, -1) == 2).any(axis=0)
            first.append(float(factors[np.argmax(collapsed)]) if collapsed.any() else None)
            analyses.append(2 * factors.size)
            continue
        found, runs = None, 0
        for factor in factors:
            statuses = [model.outcome(motion.scaled(sign * factor)).status
                        for sign in (1.0, -1.0)]
            runs += 2
            undecided += sum(s is Status.UNDECIDED for s in statuses)
            if any(s in (Status.COLLAPSE, Status.UNDECIDED) for s in statuses):
                found = float(factor)
                break
        first.append(found)
        analyses.append(runs)
    return {"pga_levels": grid.tolist(), "pga": [float(v) for v in pga],
            "first_factor": first, "analyses": analyses, "undecided": undecided}


def stripe_levels(pilot: dict, suite, im: str, count: int, weaker: float = 1.0
                  ) -> tuple[float, ...]:
    """The stripes of a record-based fragility in ``im``: ``count`` levels, evenly spaced in
    logarithm, from 0.8 times the smallest level at which a record collapses the structure
    (:func:`record_pilot`), times ``weaker``, to 1.25 times the largest (up to the median top
    of the pilot where a record does not), to four significant digits (module docstring).

    Parameters
    ----------
    pilot : dict
        :func:`record_pilot`.
    suite : RecordSuite
        The records of the pilot.
    im : str
        The intensity measure (:func:`archquake.ground_motion.suites.stripe_measure`).
    count : int
        Number of levels.
    weaker : float
        How much weaker than the structure the weakest irregular arches are [-], in (0, 1]
        (e.g. the 5 % quantile of k~ over k): the lowest stripe is lowered by it, so that it
        lies below their collapses too.

    Returns
    -------
    tuple of float
        Increasing levels [the IM's unit] (fewer than ``count`` should two round to the same
        value).
    """
    from ..ground_motion.suites import stripe_measure

    measure = stripe_measure(im)
    values = suite.intensities(measure.name)
    top = max(pilot["pga_levels"]) / np.asarray(pilot["pga"])
    first = np.array([math.nan if f is None else f for f in pilot["first_factor"]])
    at_first = first ** measure.exponent * values
    at_top = top ** measure.exponent * values
    finite = at_first[np.isfinite(at_first)]
    if finite.size:
        lo, hi = 0.8 * weaker * float(finite.min()), 1.25 * float(finite.max())
        if finite.size < first.size:
            hi = max(hi, float(np.median(at_top)))
    else:
        lo, hi = float(np.median(values * (np.min(pilot["pga_levels"])
                                           / np.asarray(pilot["pga"])) ** measure.exponent)), \
            float(np.median(at_top))
    levels = sorted({_significant(v) for v in np.geomspace(lo, hi, count)})
    return tuple(levels)


def median_collapse_pga(pilot: dict) -> float | None:
    """The median over the records of the lowest PGA that collapses the structure
    (:func:`record_pilot`; a record that does not collapse it on the pilot's grid counts as
    above it), to four significant digits: a level at which about half the records collapse it.

    Parameters
    ----------
    pilot : dict
        :func:`record_pilot`.

    Returns
    -------
    float or None
        The PGA [g] (the lower median of an even count; the highest collapsing PGA when more
        than half the records do not collapse the structure), None if no record collapses it.
    """
    first = np.array([math.inf if f is None else f * a
                      for f, a in zip(pilot["first_factor"], pilot["pga"], strict=True)])
    if not np.any(np.isfinite(first)):
        return None
    level = float(np.quantile(first, 0.5, method="lower"))
    return _significant(level) if math.isfinite(level) else _significant(
        float(np.max(first[np.isfinite(first)])))


__all__ = ["PILOT_RANGE", "median_collapse_pga", "pilot_levels", "record_pilot", "stripe_levels"]
