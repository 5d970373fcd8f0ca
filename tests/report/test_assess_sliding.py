"""The assessment's table of sliding as well as rocking: both friction laws and the rigid
blocks' ramp, against the frictionless chain program and each other."""

import pytest

import archquake
from archquake.limit_analysis import load_multipliers
from archquake.report.assess import parts, text


def test_with_the_models_friction_nothing_slides_and_all_three_are_heymans():
    arch = archquake.oppenheim()
    k_l, k_r = load_multipliers(arch)
    sliding = parts.sliding_part(arch, 0.8)
    for d, k in (("l", k_l), ("r", k_r)):
        laws = sliding["directions"][d]
        assert set(laws) == {"associative", "non-associative", "rigid blocks (ramp)"}
        for entry in laws.values():
            assert entry["k"] == pytest.approx(k, abs=1e-4)
            assert entry["sliding"] == [] and len(entry["rocking"]) == 4
    rows = text.sliding_rows(sliding)
    assert [r[0] for r in rows] == ["Mech-l", "", "", "Mech-r", "", ""]


def test_low_friction_lowers_every_law_alike_here():
    # mu = 0.35: a springing slides beside three hinges; the ramp (an independent model) agrees
    sliding = parts.sliding_part(archquake.oppenheim(), 0.35)
    laws = sliding["directions"]["l"]
    ramp = laws["rigid blocks (ramp)"]
    assert laws["non-associative"]["k"] == pytest.approx(ramp["k"], abs=ramp["error"] + 1e-6)
    assert laws["non-associative"]["sliding"] == ramp["sliding"] == [7]


def test_a_structure_that_cannot_stand_with_the_friction_has_no_table():
    assert parts.sliding_part(archquake.oppenheim(), 0.1) is None
