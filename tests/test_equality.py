"""Equality and hashing of the package's values and results, decided per class on purpose."""

import numpy as np
import pytest

from archquake import irregular_arch, oppenheim
from archquake.fourlink import engine
from archquake.fourlink.mechanism import mechanisms
from archquake.fourlink.time_history import simulate
from archquake.geometry import CircularArch
from archquake.ground_motion import GroundMotion, harmonic, oppenheim_pulse
from archquake.limit_analysis import both_directions, limit_sample


def test_arches_equal_by_value_and_hash_alike():
    a, b = oppenheim(), oppenheim()
    assert a == b and hash(a) == hash(b)
    assert len({a, b}) == 1
    irregular = irregular_arch(a, 0.1, rng=3)
    assert irregular != a and irregular == irregular_arch(a, 0.1, rng=3)
    assert a != CircularArch(a.angles, a.thicknesses, a.radii, a.start_angle, 2 * a.density)
    assert a != "an arch"


def test_ground_motions_equal_by_value_and_hash_alike():
    p = oppenheim_pulse(-9.81, 0.27)
    assert p == oppenheim_pulse(-9.81, 0.27) and hash(p) == hash(oppenheim_pulse(-9.81, 0.27))
    assert p != oppenheim_pulse(-9.81, 0.28)
    assert p != p.scaled(2.0)
    assert {p: 1}[oppenheim_pulse(-9.81, 0.27)] == 1
    assert harmonic(1.0, 0.5, 2) != p
    table = GroundMotion(p.kind, p.times, p.values, p.params, "other name")
    assert table != p  # the name is part of the value


def test_results_compare_by_identity():
    arch = oppenheim()
    la_l, la_r = both_directions(arch)
    again_l, _ = both_directions(arch)
    assert la_l == la_l and la_l != again_l
    assert len({la_l, again_l, la_r}) == 3
    mech_l, mech_r = mechanisms(arch)
    table = engine.tabulate(mech_l)
    assert table == table and table != engine.tabulate(mech_l)
    history = simulate((mech_l, mech_r), oppenheim_pulse(-9.81, 0.27), (0.875, 0.875))
    assert history == history and hash(history) == hash(history)
    assert history != simulate((mech_l, mech_r), oppenheim_pulse(-9.81, 0.27), (0.875, 0.875))
    sample = limit_sample(arch, 0.1, 3, seed=0)
    assert sample == sample and {sample}


@pytest.mark.parametrize("value", [oppenheim(), oppenheim_pulse(-9.81, 0.27)])
def test_value_hash_does_not_depend_on_array_identity(value):
    copy = type(value)(**{name: (np.array(getattr(value, name))
                                 if isinstance(getattr(value, name), np.ndarray)
                                 else getattr(value, name))
                          for name in value.__dataclass_fields__ if not name.startswith("_")})
    assert copy == value and hash(copy) == hash(value)



def test_an_arch_round_trips_through_its_dict():
    """to_dict is complete: start angle and density included (an asymmetric irregular arch and
    a denser arch come back equal)."""
    for arch in (irregular_arch(oppenheim(), 0.1, rng=7), oppenheim(density=2400.0)):
        assert CircularArch.from_dict(arch.to_dict()) == arch
