r"""Outcomes of one structure under one record at many levels, both polarities.

The four-link model runs every level and both polarities of a record as one compiled call
(:func:`record_outcomes`); a model whose analyses are single (the rigid blocks) is searched along
the levels (:func:`searched_record_outcomes`, :mod:`archquake.studies.strategies`). Both are the
analyses of the record-based fragility (:mod:`archquake.studies.record_fragility`), which
re-exports them.
"""

from __future__ import annotations

import numpy as np

from ..defaults import REST_MARGIN

POLARITIES = (1, -1)
"""Polarities of a record: +1 as recorded, -1 reversed (``GroundMotion.reversed()``)."""



def record_outcomes(dynamics, motion, factors) -> dict[str, np.ndarray]:
    """Outcomes of one arch under one record scaled by each of ``factors``, in one call of a
    model whose grid is one call (:meth:`archquake.fourlink.FourLinkModel.scaled_record_outcomes`:
    an analysis whose scaled record stays strictly inside the activation accelerations, with
    the relative margin :data:`REST_MARGIN`, is at rest without being integrated).

    Parameters
    ----------
    dynamics : StructuralModel
        The arch's model, one whose grid is one call (``grid_in_one_call``).
    motion : GroundMotion
        A ``LINEAR`` record [m/s^2].
    factors : array_like of float
        Signed scale factors [-]; a negative factor applies the reversed record.

    Returns
    -------
    dict of ndarray
        ``status`` (0 rest, 1 recovery, 2 collapse), ``half_cycle``, ``impacts``,
        ``collapse_time`` [s], ``max_phi`` [rad] and ``integrated`` (False where the scaled
        record stays below the activation acceleration: rest, not integrated), one per factor.

    Raises
    ------
    ValueError
        If ``motion`` is not piecewise linear, or as the model's method.
    """
    return dynamics.scaled_record_outcomes(motion, factors)


def searched_record_outcomes(model, motion, factors, *, search: str = "screened",
                             stride: int = 4, screen=None) -> dict[str, np.ndarray]:
    """Outcomes of one arch under one record at increasing scale factors, both polarities,
    by a search strategy along the levels (:func:`archquake.studies.strategies.search_grid`).

    For a model whose analyses are single (the rigid blocks): each polarity's line of levels is
    scanned coarsely and every change bisected; with ``"screened"`` every stretch between two
    analysed levels that are not both at rest is analysed level by level, and the screening
    model's changes refine the coarse scan. Under a record only rest is smooth in the level
    (:func:`~archquake.studies.strategies.smooth_outcomes` with no end of excitation). A
    collapse during a record is not, unlike one during a pulse (measured on the nominal and one
    irregular arch under the 28 near-field pulse records at 0.2-2.0 g: taking collapses during
    the record as smooth inferred 2 of 1,120 outcomes wrongly).

    Parameters
    ----------
    model : StructuralModel
        The arch's model.
    motion : GroundMotion
        The record [m/s^2].
    factors : array_like of float
        Increasing scale factors of the levels, > 0 [-].
    search : {"exhaustive", "bisection", "screened"}
        The strategy.
    stride : int
        Levels between coarse points [-].
    screen : StructuralModel, optional
        The screening model (the four-link model of the same arch), for ``"screened"``.

    Returns
    -------
    dict of ndarray
        As :func:`record_outcomes`, one per (level, polarity) in that order (polarities of
        :data:`POLARITIES`); ``integrated`` is False where the outcome was inferred; ``impacts``
        -1, ``max_phi`` nan and ``half_cycle`` 0 for a model that does not count them.
    """
    from .strategies import search_grid, smooth_outcomes

    f = np.asarray(factors, dtype=float).ravel()
    n = f.size * len(POLARITIES)
    out = {"status": np.zeros(n, dtype=np.int8), "half_cycle": np.zeros(n, dtype=np.int16),
           "impacts": np.full(n, -1, dtype=np.int32), "collapse_time": np.full(n, np.nan),
           "max_phi": np.full(n, np.nan), "integrated": np.zeros(n, dtype=bool)}
    for j, polarity in enumerate(POLARITIES):
        rows = np.arange(f.size) * len(POLARITIES) + j
        screen_keys = None
        if search == "screened" and screen is not None:
            screen_keys = record_outcomes(screen, motion, polarity * f)["status"].astype(
                np.int64)

        def classify(indices, polarity=polarity, rows=rows):
            status = np.empty(len(indices), dtype=np.int64)
            time = np.full(len(indices), np.nan)
            for m, i in enumerate(indices):
                outcome = model.outcome(motion.scaled(polarity * f[i]))
                status[m], time[m] = int(outcome.status), outcome.collapse_time
            out["collapse_time"][rows[indices]] = time
            return status, smooth_outcomes({"status": status}, None)  # only rest

        keys, analysed = search_grid(classify, f.size, search=search, stride=stride,
                                     screen=screen_keys)
        out["status"][rows] = keys
        out["integrated"][rows] = analysed
        out["collapse_time"][rows[~analysed]] = np.nan
    return out


__all__ = ["POLARITIES", "REST_MARGIN", "record_outcomes", "searched_record_outcomes"]
