"""Checks and conversions of plain values that every part of the package shares.

:func:`check_integer`
    an integer setting (a count, a seed) in its range, or a ``ValueError`` naming it;
:func:`json_float`
    a number as JSON holds it: a finite float, or ``None`` for nan and infinities (strict JSON
    has no such numbers, and a summary's reader should not meet ``NaN`` where a number is
    missing);
:func:`json_value`, :func:`json_dumps`
    any value as strict JSON (``null`` for nan and infinities, never ``NaN``): every JSON the
    package writes goes through them;
:func:`pulse_grid`
    the durations and amplitudes of a grid of pulses as arrays, or a ``ValueError`` naming
    the one refused;
:func:`json_loads`
    JSON as the package reads it: a key given twice, ``NaN`` or a nesting too deep for Python
    is a ``ValueError``, never a silent choice or a ``RecursionError`` (nor Python's message
    about an integer too long to convert).

The module imports nothing of the package, so any module may import it (geometry, ground motions,
studies and result files alike).
"""

from __future__ import annotations

import json
import math
import numbers
import os
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


MAX_PULSE_AMPLITUDE_G = 1e300
"""Largest amplitude of a pulse given in g that stays finite in m/s^2 [g] (far beyond any
physical meaning: the command line caps amplitudes at
:data:`~archquake.defaults.MAX_ACCELERATION_G`)."""


def pulse_grid(durations: Any, amplitudes_g: Any):
    """``(durations [s], amplitudes_g [g])`` broadcast against each other as float arrays.

    Raises
    ------
    ValueError
        Naming ``durations`` or ``amplitudes_g``: text, booleans, shapes that do not
        broadcast, a duration not finite and > 0, or an amplitude not finite or beyond
        :data:`MAX_PULSE_AMPLITUDE_G` in magnitude (it would overflow in m/s^2).

    Examples
    --------
    >>> pulse_grid([0.4], [-1e308])
    Traceback (most recent call last):
    ...
    ValueError: amplitudes_g must be finite numbers of magnitude at most 1e+300 [g], got -1e+308
    """
    import numpy as np

    arrays = []
    for name, value in (("durations", durations), ("amplitudes_g", amplitudes_g)):
        array = np.asarray(value)
        if array.dtype.kind not in "iuf":
            raise ValueError(f"{name} must be numbers, got {value!r}")
        arrays.append(array.astype(float))
    try:
        d, a = np.broadcast_arrays(*arrays)
    except ValueError as exc:
        raise ValueError(f"durations {arrays[0].shape} and amplitudes_g {arrays[1].shape} must "
                         f"broadcast against each other") from exc
    bad = ~np.isfinite(d) | (d <= 0)
    if np.any(bad):
        raise ValueError(f"durations must be finite numbers > 0 [s], got {float(d[bad].flat[0])!r}")
    bad = ~(np.abs(a) <= MAX_PULSE_AMPLITUDE_G)
    if np.any(bad):
        raise ValueError(f"amplitudes_g must be finite numbers of magnitude at most "
                         f"{MAX_PULSE_AMPLITUDE_G:g} [g], got {float(a[bad].flat[0])!r}")
    return d, a


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


def json_value(obj: Any) -> Any:
    """``obj`` as plain JSON values: numpy scalars and arrays as numbers and lists, tuples as
    lists, paths as strings, keys as strings, and nan and infinities as ``None``.

    Parameters
    ----------
    obj : object
        Nested dicts, lists, tuples, arrays, numbers, strings, paths.

    Returns
    -------
    object
        What :func:`json.dumps` writes as strict JSON.

    Raises
    ------
    TypeError
        For a value JSON cannot hold (naming its type).

    Examples
    --------
    >>> json_value({"a": (1.5, float("nan")), 2: float("-inf")})
    {'a': [1.5, None], '2': None}
    """
    if isinstance(obj, dict):
        return {str(k): json_value(v) for k, v in obj.items()}
    if isinstance(obj, list | tuple):
        return [json_value(v) for v in obj]
    if obj is None or isinstance(obj, bool | str | int):
        return obj
    if isinstance(obj, float):
        return obj if math.isfinite(obj) else None
    if isinstance(obj, os.PathLike):
        return os.fspath(obj)
    if hasattr(obj, "tolist"):  # numpy scalars and arrays, without importing numpy here
        return json_value(obj.tolist())
    if isinstance(obj, numbers.Real):
        return json_value(float(obj))
    raise TypeError(f"object of type {type(obj).__name__} is not JSON serialisable")


def json_dumps(obj: Any, **kwargs) -> str:
    """Strict JSON text of ``obj`` (:func:`json_value`; ``allow_nan=False``): ``null`` where a
    number is nan or infinite. ``kwargs`` go to :func:`json.dumps` (``indent``,
    ``sort_keys``).

    Examples
    --------
    >>> json_dumps({"collapse_time": float("nan")})
    '{"collapse_time": null}'
    """
    return json.dumps(json_value(obj), allow_nan=False, **kwargs)


def _refuse_duplicate_keys(pairs: list[tuple[str, Any]]) -> dict:
    keys = [key for key, _ in pairs]
    seen: set[str] = set()
    for key in keys:
        if key in seen:
            raise ValueError(f"the key {key!r} is given twice")
        seen.add(key)
    return dict(pairs)


def _read_integer(text: str) -> int:
    try:
        return int(text)
    except ValueError:  # more digits than Python converts (sys.get_int_max_str_digits())
        digits = len(text.lstrip("-"))
        raise ValueError(f"an integer of {digits} digits is too long to be read") from None


def _refuse_constant(name: str):
    raise ValueError(f"{name} is not a JSON number (strict JSON has no {name}); give a finite "
                     "number")


def json_loads(text: str, *, allow_nan: bool = False) -> Any:
    """The value of the JSON ``text``, refusing what :func:`json.loads` would accept silently.

    Parameters
    ----------
    text : str
        The JSON text.
    allow_nan : bool
        Accept ``NaN``, ``Infinity`` and ``-Infinity`` (files written by earlier versions);
        default: refuse them.

    Returns
    -------
    object

    Raises
    ------
    ValueError
        A key given twice in one object (:func:`json.loads` keeps the last), ``NaN`` or
        ``Infinity`` unless ``allow_nan``, a nesting deeper than Python's recursion limit, an
        integer of more digits than Python converts (4300 by default), or text that is not JSON
        (a :class:`json.JSONDecodeError`, a subclass of ValueError).

    Examples
    --------
    >>> json_loads('{"a": 1, "a": 2}')
    Traceback (most recent call last):
    ...
    ValueError: the key 'a' is given twice
    """
    kwargs = {} if allow_nan else {"parse_constant": _refuse_constant}
    try:
        return json.loads(text, object_pairs_hook=_refuse_duplicate_keys, **kwargs)
    except RecursionError:
        raise ValueError("the JSON is nested too deeply to be read") from None
    except json.JSONDecodeError:
        raise
    except ValueError:  # read again, rarely, to say an overlong integer in our own words
        return json.loads(text, object_pairs_hook=_refuse_duplicate_keys,
                          parse_int=_read_integer, **kwargs)


__all__ = ["check_integer", "json_dumps", "json_float", "json_loads", "json_value"]
