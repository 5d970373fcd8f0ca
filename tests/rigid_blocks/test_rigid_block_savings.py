"""The steps skipped at rest change nothing of the outcome (``BlockSettings.skip_rest``): the
run that skips them and the run that takes every step (the second method) give the same
status, times of collapse and decision, and steps, over pulses at rest, near the threshold of
motion and of collapse; and the count of the steps solved by phase adds up to the steps taken.
"""

from dataclasses import replace

import numpy as np
import pytest

from archquake import oppenheim
from archquake.geometry import GRAVITY
from archquake.ground_motion import STEP, GroundMotion, oppenheim_pulse, rectangular_pulse
from archquake.rigid_blocks import BlockSettings, rectangular_block
from archquake.rigid_blocks.dynamics import PHASES, outcome_with_phases

DEFAULT = BlockSettings()


def same_outcome(structure, motion, settings=DEFAULT, late=0.0):
    """The outcome with the skips and its phases, and the phases without; ``late``: the
    tolerance of a decision after a long rocking [s] (0: the same step)."""
    skip, phases = outcome_with_phases(structure, motion, settings)
    full, every = outcome_with_phases(structure, motion,
                                      replace(settings, skip_rest=False))
    assert skip.status == full.status
    assert skip.decided == full.decided
    assert skip.closed == full.closed
    if late:
        assert skip.decision_time == pytest.approx(full.decision_time, abs=late)
        return skip, phases, every
    np.testing.assert_equal(skip.collapse_time, full.collapse_time)  # nan == nan
    assert skip.decision_time == full.decision_time
    assert skip.steps == full.steps
    return skip, phases, every


@pytest.mark.parametrize("duration", [0.4, 0.7])
@pytest.mark.parametrize("amplitude_g", [0.30, 0.36, 0.38, 0.40, 0.42, 0.44, 0.54, 0.56])
def test_oppenheims_arch_the_same_with_and_without_the_skips(duration, amplitude_g):
    """Oppenheim's arch starts to rock at 0.37 g; 0.40-0.44 g recover or collapse after the
    pulse, 0.54-0.56 g at t_p = 0.4 s recover or collapse late."""
    arch = oppenheim()
    outcome, phases, every = same_outcome(arch, oppenheim_pulse(-amplitude_g * GRAVITY, duration))
    if outcome.status.label == "rest":  # every solve at rest but a few skipped
        assert sum(phases.values()) < 10 < sum(every.values())


def test_a_block_at_rest_then_rocking_the_same_with_and_without_the_skips():
    """A block 0.4 m x 2 m (k = 0.2) at rest under 0.1 g for 0.3 s, then rocking under 0.32 g:
    the rest skipped to the grid point of coarse steps before 0.3 s, then the same steps. The
    skipped steps' round-off (velocities of 1e-13 m/s) is all that differs; the block's impacts
    over 8 s of rocking amplify it to 1e-10 rad and a few steps of the decision (22 ms), as any
    round-off (``test_rigid_blocks_rest.py``)."""
    block = rectangular_block(0.4, 2.0)
    motion = GroundMotion(STEP, [0.0, 0.3, 0.55], [0.1 * GRAVITY, 0.32 * GRAVITY], name="pieces")
    outcome, phases, _ = same_outcome(block, motion, BlockSettings(time_step=0.001), late=0.05)
    assert outcome.max_rotation > 0.01  # it rocked
    assert phases["still"] < 10  # of 300 steps at rest


@pytest.mark.parametrize("amplitude_g", [0.1, 0.5])
def test_the_steps_by_phase_add_up_to_the_steps_taken(amplitude_g):
    """Every step at h, none skipped: one contact problem per step until the decision, so the
    phases add up to ``steps``; at rest (0.1 g < k = 0.2) the steps during the pulse, 0.2 s /
    1 ms = 200, are all 'still', the rest in the window."""
    block = rectangular_block(0.4, 2.0)
    settings = BlockSettings(time_step=0.001, coarse_factor=1, skip_rest=False)
    outcome, phases = outcome_with_phases(block, rectangular_pulse(amplitude_g * GRAVITY, 0.2),
                                          settings)
    assert tuple(phases) == PHASES
    assert sum(phases.values()) == outcome.steps
    if amplitude_g < 0.2:
        assert outcome.status.label == "rest"
        assert phases["still"] == 200 and phases["pulse"] == phases["free"] == 0
    else:
        assert phases["pulse"] > 0 and phases["free"] > 0


def test_skip_rest_is_a_bool():
    with pytest.raises(ValueError, match="skip_rest"):
        BlockSettings(skip_rest=1)
