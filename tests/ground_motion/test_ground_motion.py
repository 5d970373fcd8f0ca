import math

import numpy as np
import pytest
from scipy import integrate

from archquake.geometry import GRAVITY
from archquake.ground_motion import (
    GROUND_MOTIONS,
    ground_motion,
    harmonic,
    oppenheim_pulse,
    rectangular_pulse,
    sine_pulse,
    still_ground,
)


def test_oppenheim_pulse_shape_matches_paper():
    g = oppenheim_pulse(-GRAVITY, 0.27)
    t = np.array([0.0, 0.1, 0.2699, 0.27, 0.5, 0.8099, 0.81, 2.0])
    expected = [-GRAVITY, -GRAVITY, -GRAVITY, GRAVITY / 2, GRAVITY / 2, GRAVITY / 2, 0, 0]
    assert g.acceleration(t) == pytest.approx(expected)
    assert g.duration == pytest.approx(0.81)
    assert g.breakpoints.tolist() == pytest.approx([0, 0.27, 0.81])


def test_oppenheim_pulse_has_zero_net_ground_velocity():
    g = oppenheim_pulse(3.0, 0.4)
    v = sum(integrate.quad(g.acceleration, a, b)[0] for a, b in [(0, 0.4), (0.4, 1.2)])
    assert v == pytest.approx(0.0, abs=1e-12)


def test_sine_pulse_and_harmonic_closed_form():
    g = sine_pulse(2.0, 0.5)
    t = np.linspace(0, 0.49, 50)
    assert g.acceleration(t) == pytest.approx(2.0 * np.sin(2 * np.pi * t / 0.5))
    assert g.acceleration(0.5) == 0.0
    h = harmonic(1.0, 0.2, cycles=3)
    assert h.duration == pytest.approx(0.6)
    assert h.acceleration(0.25) == pytest.approx(math.sin(2 * math.pi * 0.25 / 0.2))
    assert h.peak == 1.0


def test_rectangular_and_scaling():
    g = rectangular_pulse(1.5, 0.3).scaled(2.0)
    assert g.acceleration([0.1, 0.31]) == pytest.approx([3.0, 0.0])
    assert g.peak == 3.0


def test_still_ground_is_still():
    assert still_ground().acceleration([0.0, 1.0, 10.0]) == pytest.approx([0, 0, 0])


def test_registry_lists_options_for_unknown_name():
    assert set(GROUND_MOTIONS) >= {"oppenheim", "rectangular", "sine", "harmonic"}
    with pytest.raises(ValueError, match="oppenheim"):
        ground_motion("tsunami", 1.0, 1.0)


@pytest.mark.parametrize("amplitude, duration", [(1.0, 0.0), (1.0, -1), (float("nan"), 1.0),
                                                 ("a", 1.0)])
def test_bad_pulse_input(amplitude, duration):
    with pytest.raises(ValueError, match="amplitude|duration"):
        oppenheim_pulse(amplitude, duration)
