"""The rigid-block model's default time step is chosen from the structure: rigid blocks under
gravity have no length scale of their own, so an arch k times smaller, under pulses sqrt(k)
times shorter, moves as the large one does at a step sqrt(k) times shorter, and with its own
default step it reproduces the large arch's analyses."""

import math

import pytest

from archquake import GRAVITY, oppenheim
from archquake.defaults import DEFAULT_TIME_STEP, REFERENCE_THICKNESS
from archquake.geometry.arch import circular_arch
from archquake.ground_motion import oppenheim_pulse
from archquake.rigid_blocks import BlockSettings, RigidBlockModel, block_outcome, simulate_blocks
from archquake.rigid_blocks.dynamics import structure_time_step
from archquake.studies.fragility import FragilitySettings

SMALL = circular_arch(2.5, math.radians(157.5), 0.375, 7)  # Oppenheim's arch, 4 times smaller


def test_the_step_scales_with_the_square_root_of_the_thickness():
    assert structure_time_step(REFERENCE_THICKNESS) == DEFAULT_TIME_STEP
    assert RigidBlockModel(oppenheim()).settings.time_step == DEFAULT_TIME_STEP  # exactly 1 ms
    assert RigidBlockModel(SMALL).settings.time_step == pytest.approx(DEFAULT_TIME_STEP / 2)
    assert structure_time_step(0.4) == pytest.approx(1e-3 * math.sqrt(0.4 / 1.5), rel=1e-15)
    # a step given is kept; the study's step is that of its nominal arch (Oppenheim's: 1 ms)
    assert RigidBlockModel(SMALL, BlockSettings(time_step=0.002)).settings.time_step == 0.002
    assert FragilitySettings().model.time_step == DEFAULT_TIME_STEP
    assert FragilitySettings(nominal=SMALL).model.time_step == pytest.approx(DEFAULT_TIME_STEP / 2)
    history = simulate_blocks(SMALL, oppenheim_pulse(-0.3 * GRAVITY, 0.2), t_end=0.01)
    assert history.settings.time_step == pytest.approx(5e-4)  # the history states the step


def test_the_model_holds_its_blocks_and_checks_a_motion_on_them():
    """The model builds the assembly of its arch once (shared with another model of the same
    arch), runs on it, and refuses a step its blocks cannot follow: the contact law's
    0.02 sqrt(t/g) with t = 0.375 m (3.91 ms) for the small arch, twice that for the large."""
    from archquake.rigid_blocks import from_arch

    model = RigidBlockModel(SMALL, BlockSettings(time_step=0.005))
    assert model.assembly is RigidBlockModel(SMALL).assembly
    assert model.assembly.thickness == pytest.approx(from_arch(SMALL).thickness, rel=1e-15)
    assert RigidBlockModel(model.assembly).settings.time_step == pytest.approx(5e-4)
    with pytest.raises(ValueError, match=r"time_step must be at most 0.00391 s .* 0.375 m thick"):
        model.check_motion(oppenheim_pulse(-GRAVITY, 1.0))
    longest = RigidBlockModel(oppenheim()).check_motion(oppenheim_pulse(-GRAVITY, 1.0))
    assert longest == pytest.approx(0.02 * math.sqrt(1.5 / GRAVITY), rel=1e-12)


@pytest.mark.parametrize("duration, amplitude", [(0.4, 0.6), (0.5, 0.45), (0.3, 0.9),
                                                 (0.4, 0.5), (0.5, 0.3)])
def test_a_smaller_arch_at_its_own_step_moves_as_the_large_one(duration, amplitude):
    """Collapses (at the same step number, so at half the time), a recovery and a rest: the
    same outcome and the same largest rotation, to round-off. (The windows of rest are fixed
    times, not scaled: a recovery is decided a few steps apart.)"""
    large = block_outcome(oppenheim(), oppenheim_pulse(-amplitude * GRAVITY, duration))
    small = block_outcome(SMALL, oppenheim_pulse(-amplitude * GRAVITY, duration / 2))
    assert small.status == large.status
    assert small.max_rotation == pytest.approx(large.max_rotation, rel=1e-9, abs=1e-12)
    if large.status.label == "collapse":
        assert small.steps == large.steps
        assert 2 * small.collapse_time == pytest.approx(large.collapse_time, rel=1e-12)
    # at the large arch's step the small one is resolved as the large one at twice its step
    coarse = block_outcome(SMALL, oppenheim_pulse(-amplitude * GRAVITY, duration / 2),
                           BlockSettings(time_step=DEFAULT_TIME_STEP))
    doubled = block_outcome(oppenheim(), oppenheim_pulse(-amplitude * GRAVITY, duration),
                            BlockSettings(time_step=2 * DEFAULT_TIME_STEP))
    assert coarse.status == doubled.status
    # (a rest turns by round-off only, 1e-10 rad, which the steps chosen may change)
    assert coarse.max_rotation == pytest.approx(doubled.max_rotation, rel=1e-9, abs=1e-9)
