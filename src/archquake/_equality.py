"""Value equality for frozen dataclasses that hold numpy arrays.

A frozen dataclass compares and hashes the tuple of its fields, which fails for arrays
(``bool(array == array)`` is ambiguous, arrays are unhashable). archquake decides per class:

- *values* that describe an input (an :class:`~archquake.geometry.CircularArch`, a
  :class:`~archquake.ground_motion.GroundMotion`) compare equal when every field is equal, arrays
  element by element, and hash accordingly (their arrays are read-only), so they can key a cache
  or a dict; a number that is nan equals nan (an outcome's ``collapse_time`` is nan when there is
  no collapse: two identical runs are equal);
- *results* computed from them (limit analyses, mechanisms, tables, time histories) compare by
  identity (``eq=False``): two results are compared by the numbers a caller cares about, with
  the tolerance the caller chooses.
"""

from __future__ import annotations

import math
from dataclasses import fields

import numpy as np

_NAN = ("nan",)
"""What a nan hashes as (``hash(float("nan"))`` differs between two nan objects)."""


def _same(a, b) -> bool:
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        return (isinstance(a, np.ndarray) and isinstance(b, np.ndarray) and a.shape == b.shape
                and a.dtype == b.dtype
                and bool(np.array_equal(a, b, equal_nan=a.dtype.kind in "fc")))
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return True
    return bool(a == b)


def _key(value):
    if isinstance(value, np.ndarray):
        return (value.shape, value.dtype.str, value.tobytes())
    if isinstance(value, float) and math.isnan(value):
        return _NAN
    return value


def frozen_value(value):
    """A hashable image of JSON-like data (dicts, lists, numbers, strings) that is equal for
    equal data: dicts as sorted tuples of items, lists as tuples, nan as one value. For the
    ``__hash__`` of a value that compares by its ``to_dict()``.

    Examples
    --------
    >>> frozen_value({"b": [1, 2.0], "a": None}) == frozen_value({"a": None, "b": [1.0, 2]})
    True
    """
    if isinstance(value, dict):
        return tuple(sorted((str(k), frozen_value(v)) for k, v in value.items()))
    if isinstance(value, list | tuple):
        return tuple(frozen_value(v) for v in value)
    return _key(value)


def value_equality(cls):
    """Class decorator: ``==`` and ``hash`` by the values of the compared fields, arrays
    element by element. Apply it above ``@dataclass(frozen=True)``."""
    names = tuple(f.name for f in fields(cls) if f.compare)

    def __eq__(self, other):
        if other.__class__ is not self.__class__:
            return NotImplemented
        return all(_same(getattr(self, n), getattr(other, n)) for n in names)

    def __hash__(self):
        return hash((cls.__qualname__, *(_key(getattr(self, n)) for n in names)))

    cls.__eq__ = __eq__
    cls.__hash__ = __hash__
    return cls
