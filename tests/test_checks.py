"""archquake.checks: the one integer check and the one "finite float or None" of the package."""

import math

import numpy as np
import pytest

from archquake.checks import check_integer, json_float


@pytest.mark.parametrize("value, expected", [(3, 3), (np.int64(7), 7), (np.uint8(1), 1)])
def test_integers_are_accepted_as_int(value, expected):
    out = check_integer("count", value)
    assert out == expected and type(out) is int


@pytest.mark.parametrize("value, message", [
    (0, "count must be an integer >= 1, got 0"),
    (True, "count must be an integer >= 1, got True"),
    (2.0, "count must be an integer >= 1, got 2.0"),
    ("3", "count must be an integer >= 1, got '3'"),
    (11, r"count must be an integer in \[1, 10\], got 11"),
])
def test_other_values_are_refused_naming_the_parameter(value, message):
    with pytest.raises(ValueError, match=message):
        check_integer("count", value, maximum=10 if value == 11 else None)


def test_json_float_keeps_finite_numbers_only():
    assert json_float(np.float64(0.1)) == 0.1 and type(json_float(np.float64(0.1))) is float
    assert json_float(np.int64(2)) == 2.0
    for missing in (None, math.nan, np.nan, math.inf, -np.inf):
        assert json_float(missing) is None


@pytest.mark.parametrize("digits", [4301, 5000, 20_000])
def test_json_loads_refuses_an_overlong_integer_in_its_own_words(digits):
    from archquake.checks import json_loads

    with pytest.raises(ValueError) as refused:
        json_loads('{"n": -' + "9" * digits + "}")
    assert str(refused.value) == f"an integer of {digits} digits is too long to be read"
    assert json_loads('{"n": -' + "9" * 4300 + "}")["n"] == -(10**4300 - 1)  # 4300: read
