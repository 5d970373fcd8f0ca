"""Checks and conversions of plain values that every part of the package shares.

:func:`check_integer`
    an integer setting (a count, a seed) in its range, or a ``ValueError`` naming it;
:func:`json_float`
    a number as JSON holds it: a finite float, or ``None`` for nan and infinities (strict JSON
    has no such numbers, and a summary's reader should not meet ``NaN`` where a number is
    missing).

The module imports nothing of the package, so any module may import it (geometry, ground motions,
studies and result files alike).
"""

from __future__ import annotations

import math
import numbers
from typing import Any


def check_integer(name: str, value: Any, minimum: int = 1, maximum: int | None = None) -> int:
    """``value`` as an ``int`` in ``[minimum, maximum]``, or a ``ValueError`` naming ``name``.

    Parameters
    ----------
    name : str
        The parameter's name, for the message.
    value : int
        The value: a Python or numpy integer (not a bool, not a float).
    minimum : int
        Smallest accepted value.
    maximum : int, optional
        Largest accepted value (default: no bound).

    Returns
    -------
    int

    Raises
    ------
    ValueError
        ``"<name> must be an integer >= <minimum>, got <value>"`` (or ``in [<minimum>,
        <maximum>]``).

    Examples
    --------
    >>> check_integer("sample_size", 40, maximum=100)
    40
    >>> check_integer("seed", -1, minimum=0)
    Traceback (most recent call last):
    ...
    ValueError: seed must be an integer >= 0, got -1
    """
    if (isinstance(value, bool) or not isinstance(value, numbers.Integral) or value < minimum
            or (maximum is not None and value > maximum)):
        accepted = f">= {minimum}" if maximum is None else f"in [{minimum}, {maximum}]"
        raise ValueError(f"{name} must be an integer {accepted}, got {value!r}")
    return int(value)


def json_float(value: Any) -> float | None:
    """A number as a JSON summary holds it: a finite ``float``, or ``None``.

    Parameters
    ----------
    value : float, numpy scalar or None
        The number.

    Returns
    -------
    float or None
        ``float(value)`` if it is finite; ``None`` for ``None``, nan and infinities.

    Examples
    --------
    >>> json_float(0.25), json_float(float("nan")), json_float(float("inf")), json_float(None)
    (0.25, None, None, None)
    """
    if value is None:
        return None
    x = float(value)
    return x if math.isfinite(x) else None


__all__ = ["check_integer", "json_float"]
