"""The geometric safety factor (Heyman's): the thickness, or the piers' width, over the least on
which the structure stands, found here independently by bisection on the kinematic method's
collapse multiplier (k >= 0: it stands), not on the static margin that the library's roots use."""

import math

import pytest

from archquake.errors import CannotStandError
from archquake.geometry import (
    Pier,
    Structure,
    arch_on_piers,
    circular_arch,
    irregular_arch,
    shaped_arch,
)
from archquake.limit_analysis import GeometricSafetyFactor, geometric_safety_factor, limit_analysis


def stands(structure) -> bool:
    """Whether every collapse mechanism needs a push (k >= 0) both ways: the kinematic method."""
    try:
        return all(limit_analysis(structure, d, "kinematic").load_multiplier >= 0.0
                   for d in ("l", "r"))
    except CannotStandError:
        return False


def least(structure_of, lo: float, hi: float, rtol: float = 1e-6) -> float:
    """The least size in (lo, hi] for which ``structure_of(size)`` stands, by bisection."""
    assert not stands(structure_of(lo)) and stands(structure_of(hi))
    while hi - lo > rtol * hi:
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if stands(structure_of(mid)) else (mid, hi)
    return hi


def test_circular_arch_thickness_over_the_least_that_stands():
    embrace, n, t = math.pi, 10, 0.15
    sf = geometric_safety_factor(circular_arch(1.0, embrace, t, n))
    t_min = least(lambda t: circular_arch(1.0, embrace, t, n), 0.05, 0.15)
    assert sf.kind == "thickness" and sf.value == t and sf.thickness is None
    assert sf.minimum == pytest.approx(t_min, rel=1e-5)
    assert sf.factor == pytest.approx(t / t_min, rel=1e-5)
    assert 0.10 < sf.minimum < 0.11  # Milankovitch's 0.1075 R, for 10 voussoirs a little below


def test_shaped_arch_thickness_over_the_least_that_stands():
    def arch_of(t):
        return shaped_arch("pointed", span=10.0, rise=7.0, thickness=t, voussoirs=12)

    sf = geometric_safety_factor(arch_of(0.6))
    t_min = least(arch_of, 0.05, 0.6)
    assert sf.kind == "thickness" and "pointed arch" in sf.note
    assert sf.factor == pytest.approx(0.6 / t_min, rel=1e-5)


def test_arch_on_piers_pier_width_over_the_narrowest_that_stands(nominal):
    width, height = 3.5, 6.0
    sf = geometric_safety_factor(arch_on_piers(nominal, width, height))
    b_min = least(lambda b: arch_on_piers(nominal, b, height), 2.0, width)
    assert sf.kind == "pier width" and sf.value == width
    assert sf.factor == pytest.approx(width / b_min, rel=1e-5)
    # the bare arch's factor beside it, as for the arch alone
    assert sf.thickness == geometric_safety_factor(nominal)


def test_not_defined_is_a_value_that_says_why(nominal):
    uneven = geometric_safety_factor(Structure(nominal, Pier(3.0, 6.0), Pier(4.0, 6.0)))
    assert uneven.kind is None and uneven.factor is None and "two equal" in uneven.note
    assert uneven.thickness.kind == "thickness"
    irregular = irregular_arch(nominal, 0.1, 1)
    sf = geometric_safety_factor(irregular)
    assert sf == GeometricSafetyFactor(None, None, None, None, sf.note)
    assert "no thickness to scale" in sf.note


def test_to_dict_keys_and_values(nominal):
    sf = geometric_safety_factor(arch_on_piers(nominal, 3.5, 6.0))
    data = sf.to_dict()
    assert list(data) == ["kind", "value", "minimum", "factor", "thickness", "note"]
    assert data["factor"] == sf.factor and data["thickness"] == sf.thickness.to_dict()
    assert list(data["thickness"]) == ["kind", "value", "minimum", "factor", "note"]
