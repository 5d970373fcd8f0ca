r"""Analyses a model left undecided: counted, bounded and said, never taken for an outcome.

The rigid-block model can end an analysis undecided (:attr:`archquake.status.Status.UNDECIDED`,
-1; :attr:`archquake.rigid_blocks.BlockOutcome.decided` False): its contact solver gave up, or
the structure was still moving when the run ended. Such an analysis is neither a collapse nor
a survival, and every study keeps it apart:

- it is counted (:func:`undecided_count`) and the count is reported with every study result
  (text, JSON, the study's ``summary.json``, the report), 0 included;
- a probability of failure is given as two bounds: the point estimate of the package's
  convention counts an undecided analysis as a survival (the lower bound,
  :math:`P_F^- = h_f / h`), the upper bound as a collapse
  (:math:`P_F^+ = (h_f + h_u) / h`, with :math:`h_u` the trials that are undecided and did not
  collapse otherwise); the true :math:`P_F` lies between them (:func:`probability_bounds`).
  Without undecided analyses both are the same number;
- a failure domain reports its undecided bands of amplitudes, and a failure acceleration above
  one only as bounded by it
  (:attr:`archquake.studies.failure_domain.DomainSlice.failure_undecided_from_g`);
- a study whose fraction of undecided analyses exceeds :data:`UNDECIDED_WARNING_FRACTION` says
  so on the first line of its text output (:func:`undecided_warning`).

The fits of the fragility studies (lognormal, polynomial) are made to the point estimate, with
the undecided analyses counted as survivals, as the lower bound is; the bounds say how far
that may be from the truth.
"""

from __future__ import annotations

import numpy as np

from ..status import Status

UNDECIDED_WARNING_FRACTION = 0.01
"""Fraction of a study's analyses left undecided [-] above which its text output warns on its
first line (1 %: the failure probabilities and accelerations may then be far from the
model's)."""


def undecided_count(status) -> int:
    """Number of undecided analyses among status codes.

    Parameters
    ----------
    status : array_like of int
        :class:`archquake.status.Status` codes (other codes, e.g. of excluded arches, are not
        counted).

    Returns
    -------
    int
    """
    return int(np.count_nonzero(np.asarray(status) == int(Status.UNDECIDED)))


def probability_bounds(collapsed, undecided, axis) -> tuple[np.ndarray, np.ndarray]:
    r"""Lower and upper bounds of a probability of failure with undecided trials.

    A trial fails where it collapses; an undecided trial that does not collapse counts as a
    survival in the lower bound :math:`P_F^-` (the point estimate of the studies) and as a
    collapse in the upper bound :math:`P_F^+` (module docstring).

    Parameters
    ----------
    collapsed, undecided : bool array_like
        Whether each trial collapsed and whether it was undecided (of the same shape).
    axis : int or tuple of int
        Axes of the trials (averaged over).

    Returns
    -------
    lower, upper : ndarray
        :math:`P_F^-` and :math:`P_F^+` [-].
    """
    collapsed = np.asarray(collapsed, dtype=bool)
    either = collapsed | np.asarray(undecided, dtype=bool)
    return collapsed.mean(axis=axis), either.mean(axis=axis)


def undecided_summary(count: int, total: int) -> dict:
    """JSON-ready count of a study's undecided analyses.

    Parameters
    ----------
    count : int
        Undecided analyses [-].
    total : int
        Analyses of the study [-].

    Returns
    -------
    dict
        ``analyses`` (the count), ``of`` (the total), ``fraction`` [-] and
        ``warning_fraction`` (:data:`UNDECIDED_WARNING_FRACTION`).
    """
    return {"analyses": int(count), "of": int(total),
            "fraction": float(count) / total if total else 0.0,
            "warning_fraction": UNDECIDED_WARNING_FRACTION}


def undecided_warning(count: int, total: int, what: str = "analyses") -> str | None:
    """The first line of a study's text output when too many of its analyses are undecided.

    Parameters
    ----------
    count : int
        Undecided analyses [-].
    total : int
        Analyses of the study [-].
    what : str
        What was counted (``"analyses"``; ``"rigid-block analyses"``).

    Returns
    -------
    str or None
        ``"WARNING: ..."`` when ``count / total`` exceeds :data:`UNDECIDED_WARNING_FRACTION`,
        else None.

    Examples
    --------
    >>> undecided_warning(3, 100).startswith("WARNING: 3 of 100 analyses (3.0 %) were left")
    True
    >>> undecided_warning(1, 100) is None
    True
    """
    if not total or count / total <= UNDECIDED_WARNING_FRACTION:
        return None
    return (f"WARNING: {count} of {total} {what} ({100 * count / total:.1f} %) were left "
            f"undecided (more than {100 * UNDECIDED_WARNING_FRACTION:g} %): the results are "
            f"bounded by them, not decided")


def bands_text(bands) -> str:
    """Amplitude bands ``[(from, to), ...]`` [g] as text (``"0.520-0.610, 0.700-0.705"``)."""
    return ", ".join(f"{a:.3f}-{b:.3f}" for a, b in bands)


__all__ = ["UNDECIDED_WARNING_FRACTION", "bands_text", "probability_bounds", "undecided_count",
           "undecided_summary", "undecided_warning"]
