"""Value equality for frozen dataclasses that hold numpy arrays.

A frozen dataclass compares and hashes the tuple of its fields, which fails for arrays
(``bool(array == array)`` is ambiguous, arrays are unhashable). archquake decides per class:

- *values* that describe an input (an :class:`~archquake.geometry.CircularArch`, a
  :class:`~archquake.ground_motion.GroundMotion`) compare equal when every field is equal, arrays
  element by element, and hash accordingly (their arrays are read-only), so they can key a cache
  or a dict;
- *results* computed from them (limit analyses, mechanisms, tables, time histories) compare by
  identity (``eq=False``): two results are compared by the numbers a caller cares about, with
  the tolerance the caller chooses.
"""

from __future__ import annotations

from dataclasses import fields

import numpy as np


def _same(a, b) -> bool:
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        return (isinstance(a, np.ndarray) and isinstance(b, np.ndarray) and a.shape == b.shape
                and a.dtype == b.dtype and bool(np.array_equal(a, b)))
    return bool(a == b)


def _key(value):
    if isinstance(value, np.ndarray):
        return (value.shape, value.dtype.str, value.tobytes())
    return value


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
