"""Lists of values written as text: comma-separated numbers and ranges ``start:stop:step``.

The command line's list options (``--amplitudes 0.2:0.8:0.01``, ``--durations 0.1,0.5``,
``--levels``) and the page's fields of the same names are read here, so both take the same text
and refuse it with the same message, which names what was read (the option, or the field).
:func:`inclusive_range` is the grid of one range, also the default grids of the studies
(:mod:`archquake.defaults`). :func:`number` and :func:`number_field` read one number, for the
command line and for the descriptions' fields. The module imports numpy only to make a grid, so
that the command line shows its defaults (:func:`range_text`) without it.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from .defaults import MAX_GRID_POINTS
from .errors import DescriptionError

if TYPE_CHECKING:
    import numpy as np

RANGE_TOLERANCE = 1e-9
"""How close [fraction of the step] the last step of :func:`inclusive_range` must land on the
stop to be the stop."""


def number(text) -> float:
    """A number written as text, read as a person reads it: ``float(text)``, but ``_`` refused.

    Python reads ``"3_0"`` as 30 and ``"1_000"`` as 1000 (digit grouping); on a command line or
    in a form such a value is a typo, and a pier 30 m wide instead of 3 m is a silently wrong
    answer. Every number the command line, the page and the descriptions read as text goes
    through here (argparse's message then reads ``invalid number value: '3_0'``).

    Parameters
    ----------
    text : str or float
        The text of a number (or a number, returned as a float).

    Returns
    -------
    float

    Raises
    ------
    ValueError
        If ``text`` is not the text of a number, or holds ``_``.

    Examples
    --------
    >>> number(" 2.5 ")
    2.5
    >>> number("3_0")
    Traceback (most recent call last):
    ...
    ValueError: '3_0' is not a number (a '_' in it)
    """
    if isinstance(text, str) and "_" in text:
        raise ValueError(f"{text!r} is not a number (a '_' in it)")
    return float(text)


def number_field(name: str, value) -> float:
    """``value`` of the field ``name`` as a float: a number or the text of one (its range is
    checked where it is used); a :class:`~archquake.errors.DescriptionError` naming the field
    otherwise."""
    if isinstance(value, int | float) and not isinstance(value, bool):
        return float(value)
    if isinstance(value, str):
        try:
            return number(value)
        except ValueError:
            pass
    raise DescriptionError(f"{{{name}}} must be a number, got "
                           f"{DescriptionError.literal(repr(value))}")


def inclusive_range(start: float, stop: float, step: float) -> np.ndarray:
    """``start, start + step, ...`` up to ``stop``, never beyond it; ``stop`` included when a
    step lands on it within :data:`RANGE_TOLERANCE` of the step.

    The values are rounded to 12 decimals so that e.g. ``inclusive_range(0.2, 1.0, 0.01)`` gives
    exactly the decimal grid 0.20, 0.21, ..., 1.00 (as floats); ``inclusive_range(0.2, 1.0,
    0.3)`` is 0.2, 0.5, 0.8 (the next step, 1.1, would pass the stop).

    Parameters
    ----------
    start, stop : float
        First value and the value not to pass (the last one if ``start + k step`` lands on it).
    step : float
        Spacing, > 0.

    Returns
    -------
    ndarray
        The values.

    Raises
    ------
    ValueError
        For a non-finite value, a step <= 0, ``stop < start`` or more than
        :data:`archquake.defaults.MAX_GRID_POINTS` values.

    Examples
    --------
    >>> inclusive_range(0.2, 1.0, 0.3).tolist()
    [0.2, 0.5, 0.8]
    >>> inclusive_range(0.3, 0.5, 0.1).tolist()
    [0.3, 0.4, 0.5]
    """
    for name, value in (("start", start), ("stop", stop), ("step", step)):
        if not math.isfinite(value):
            raise ValueError(f"range {name} must be a finite number, got {value!r}")
    if not step > 0:
        raise ValueError(f"range step must be > 0, got {step!r}")
    if stop < start:
        raise ValueError(f"range stop must be >= start, got {start!r}:{stop!r}")
    steps = (stop - start) / step
    if steps + 1 > MAX_GRID_POINTS:
        raise ValueError(f"the range {start:g}:{stop:g}:{step:g} has {math.floor(steps) + 1} "
                         f"values, more than the {MAX_GRID_POINTS} of the largest grid "
                         f"(MAX_GRID_POINTS)")
    import numpy as np

    count = math.floor(steps + RANGE_TOLERANCE) + 1
    values = np.round(start + step * np.arange(count), 12)
    if abs(values[-1] - stop) <= RANGE_TOLERANCE * step:
        values[-1] = stop  # the stop itself, not a neighbour of it in the last bits
    return np.minimum(values, stop)


def parse_values(text: str, name: str) -> list[float]:
    """The values of a list written as text: comma-separated numbers and ranges
    ``start:stop:step``.

    A range never passes ``stop`` and includes it when a step lands on it
    (:func:`inclusive_range`); ``"0.4,0.5"`` and ``"0.2:1.0:0.01"`` and ``"0.1:0.3:0.1,0.5"``
    are valid.

    Parameters
    ----------
    text : str
        The list (any object, read as its text).
    name : str
        What the list is, for the messages: the option (``--amplitudes``) or the field
        (``amplitudes``) that gave it.

    Returns
    -------
    list of float
        The values, in the order written.

    Raises
    ------
    ValueError
        Naming ``name``: for a part that is neither a number nor a range, a bad range, no
        value at all or a value that is not finite.

    Examples
    --------
    >>> parse_values("0.1:0.3:0.1, 0.5", "durations")
    [0.1, 0.2, 0.3, 0.5]
    >>> parse_values("0.1:0.3", "--durations")
    Traceback (most recent call last):
    ...
    ValueError: --durations: a range is start:stop:step, got '0.1:0.3'
    """
    values: list[float] = []
    for part in (p.strip() for p in str(text).split(",")):
        if not part:
            continue
        pieces = part.split(":")
        try:
            numbers = [number(x) for x in pieces]
        except ValueError:
            raise ValueError(f"{name}: cannot read {part!r}; give numbers separated by commas "
                             "or a range start:stop:step") from None
        if len(numbers) == 1:
            values.append(numbers[0])
        elif len(numbers) == 3:
            try:
                values.extend(inclusive_range(*numbers).tolist())
            except ValueError as exc:
                raise ValueError(f"{name}: {exc}") from None
        else:
            raise ValueError(f"{name}: a range is start:stop:step, got {part!r}")
    if not values:
        raise ValueError(f"{name} must not be empty")
    if not all(math.isfinite(v) for v in values):
        raise ValueError(f"{name} must be finite numbers, got {values}")
    return values


def range_text(values: tuple[float, float, float]) -> str:
    """``start:stop:step`` of a range (of :mod:`archquake.defaults`), as a default is shown.

    Examples
    --------
    >>> range_text((0.2, 1.0, 0.01))
    '0.2:1:0.01'
    """
    return ":".join(f"{v:g}" for v in values)


__all__ = ["RANGE_TOLERANCE", "inclusive_range", "number", "number_field", "parse_values",
           "range_text"]
