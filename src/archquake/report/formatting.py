"""The formatters of every report: numbers, differences and outcomes in words, as the paper's
report (:mod:`archquake.report.paper`) and the assessment (:mod:`archquake.report.assess`) write
them.

>>> number(0.123456), signed(0.0123, 3), percent(-0.05), number(None)
('0.1235', '+0.012', '-5.0 %', '-')
"""

from __future__ import annotations

import math


def number(x, digits: int = 4) -> str:
    """``x`` to ``digits`` decimals; ``"-"`` for None or nan.

    Parameters
    ----------
    x : float or None
    digits : int

    Returns
    -------
    str
    """
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "-"
    return f"{x:.{digits}f}"


def signed(x, digits: int = 4) -> str:
    """``x`` with its sign to ``digits`` decimals; ``"-"`` for None.

    Parameters
    ----------
    x : float or None
    digits : int

    Returns
    -------
    str
    """
    return "-" if x is None else f"{x:+.{digits}f}"


def percent(x) -> str:
    """A relative difference [-] in percent with its sign; ``"-"`` for None.

    Parameters
    ----------
    x : float or None

    Returns
    -------
    str
    """
    return "-" if x is None else f"{100 * x:+.1f} %"


def agree(ok: bool) -> str:
    """The verdict word: ``"agrees"`` or ``"differs"``.

    Parameters
    ----------
    ok : bool

    Returns
    -------
    str
    """
    return "agrees" if ok else "differs"


def outcome_text(status: str, half_cycle: int) -> str:
    """An outcome in words: ``"collapse in half cycle 2"``, ``"recovery"``, ``"rest"``.

    Parameters
    ----------
    status : str
        The outcome's label (:attr:`archquake.status.Status.label`).
    half_cycle : int
        The half cycle of a collapse.

    Returns
    -------
    str
    """
    if status == "collapse":
        return f"collapse in half cycle {half_cycle}"
    return status


__all__ = ["agree", "number", "outcome_text", "percent", "signed"]
