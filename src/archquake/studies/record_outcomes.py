r"""Outcomes of one structure under one record at many levels, both polarities.

The four-link model runs every level and both polarities of a record as one compiled call
(:func:`record_outcomes`); a model whose analyses are single (the rigid blocks) is searched along
the levels (:func:`searched_record_outcomes`, :mod:`archquake.studies.strategies`). Both are the
analyses of the record-based fragility (:mod:`archquake.studies.record_fragility`), which
re-exports them.
"""

from __future__ import annotations

import numpy as np

from ..constants import GRAVITY

POLARITIES = (1, -1)
"""Polarities of a record: +1 as recorded, -1 reversed (``GroundMotion.reversed()``)."""
REST_MARGIN = 1e-12
"""Relative margin [-] below the activation acceleration within which an analysis is integrated
rather than declared at rest (round-off of the interpolation between samples)."""



def record_outcomes(dynamics, motion, factors) -> dict[str, np.ndarray]:
    """Outcomes of one arch under one record scaled by each of ``factors``.

    An analysis whose scaled record stays strictly inside the activation accelerations
    (``-k_l g < s xg'' < k_r g`` at every sample, eq. (2) of the paper, with the relative margin
    :data:`REST_MARGIN`) is at rest without being integrated: the record is piecewise linear, so
    its extremes are samples, and the engine would decide the same.

    Parameters
    ----------
    dynamics : FourLinkModel
        The arch's four-link model (:class:`~archquake.fourlink.FourLinkModel`).
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
        If ``motion`` is not piecewise linear, or as
        :func:`archquake.fourlink.engine.outcomes_grid`.
    RuntimeError
        As :func:`archquake.fourlink.engine.outcomes_grid`.
    """
    from ..fourlink.engine import outcomes_grid
    from ..ground_motion import LINEAR

    if motion.kind != LINEAR:
        raise ValueError(f"record_outcomes takes a piecewise-linear record, got kind "
                         f"{motion.kind} ({motion.name!r})")
    table_l, table_r = dynamics.tables
    c_lr, c_rl = dynamics.restitution
    s = np.asarray(factors, dtype=float).ravel()
    v_max, v_min = float(np.max(motion.values)), float(np.min(motion.values))
    # rounding is monotone: max(v * s) is v_max * s for s > 0 and v_min * s for s < 0
    high = np.where(s > 0, s * v_max, s * v_min)
    low = np.where(s > 0, s * v_min, s * v_max)
    threshold_r = table_r.activation_g * GRAVITY  # Mech-r opens when xg'' > k_r g
    threshold_l = -table_l.activation_g * GRAVITY  # Mech-l opens when xg'' < -k_l g
    run = ~((high < threshold_r * (1.0 - REST_MARGIN)) & (low > threshold_l * (1.0 - REST_MARGIN)))
    out = {"status": np.zeros(s.size, dtype=np.int8),
           "half_cycle": np.zeros(s.size, dtype=np.int16),
           "impacts": np.zeros(s.size, dtype=np.int32),
           "collapse_time": np.full(s.size, np.nan), "max_phi": np.zeros(s.size),
           "integrated": run}
    if np.any(run):
        signed = s[run]
        grid = outcomes_grid(table_l, table_r, c_lr, c_rl, np.ones(signed.size), signed, motion)
        for name in ("status", "half_cycle", "impacts", "collapse_time", "max_phi"):
            out[name][run] = grid[name]
    return out



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
