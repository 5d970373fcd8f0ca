"""Limit analysis with friction at the joints: the static verdict on an arch of rigid blocks
that may slide, checked against the rigid-block model on a still ground (a second method)."""

import math

import pytest

from archquake import oppenheim
from archquake.ground_motion import oppenheim_pulse
from archquake.limit_analysis import friction_margin, self_weight_margin, standing_with_friction
from archquake.rigid_blocks import BlockSettings, RigidBlockModel


def _lowest_friction(arch) -> float:
    """The friction at which the arch starts to stand, by bisection of the LP's verdict."""
    lo, hi = 0.0, 1.0
    while hi - lo > 1e-4:
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if friction_margin(arch, mid) >= 0 else (mid, hi)
    return 0.5 * (lo + hi)


def test_friction_threshold_matches_the_rigid_block_model_on_a_still_ground():
    """Just below the threshold the rigid blocks slide down and collapse on a still ground;
    just above it they stay at rest (slip of 1e-10 m)."""
    arch = oppenheim()
    mu = _lowest_friction(arch)
    assert 0.15 < mu < 0.3
    still = oppenheim_pulse(0.0, 0.4)
    below = RigidBlockModel(arch, BlockSettings(friction=mu - 0.01)).outcome(still)
    above = RigidBlockModel(arch, BlockSettings(friction=mu + 0.01)).outcome(still)
    assert below.status.label == "collapse"
    assert above.status.label == "rest" and above.max_slip < 1e-6


def test_with_ample_friction_the_margin_is_that_of_no_sliding():
    """Friction large enough never binds: the margin equals the self-weight margin of the
    no-sliding limit analysis."""
    arch = oppenheim()
    assert friction_margin(arch, 10.0) == pytest.approx(self_weight_margin(arch), rel=1e-6)


def test_standing_with_friction_says_what_fails():
    arch = oppenheim()
    assert standing_with_friction(arch, 0.8).stands
    verdict = standing_with_friction(arch, 0.0)
    assert not verdict.stands and verdict.part == "joints"
    assert verdict.margin == -math.inf
    assert "with friction 0 at its joints the arch cannot stand" in verdict.reason


def test_friction_must_be_a_number_at_least_zero():
    with pytest.raises(ValueError, match="friction must be a finite number >= 0"):
        friction_margin(oppenheim(), -0.1)


def test_threshold_is_one_crossing():
    """The verdict changes once: the margin is -inf below the threshold and non-negative above."""
    arch = oppenheim()
    mu = _lowest_friction(arch)
    margins = [friction_margin(arch, f) for f in (0.5 * mu, 0.95 * mu, 1.05 * mu, 2 * mu)]
    assert margins[:2] == [-math.inf, -math.inf] and min(margins[2:]) >= 0
