"""Coarse steps (``BlockSettings.coarse_factor``): steps of k h while no contact starts or stops
carrying an impulse, the step taken again at h where one does. Checked against the same model
at a step four times finer (an independent discretisation of the same equations), against the
energy balance, and against recording."""

import numpy as np
import pytest

from archquake import GRAVITY, oppenheim
from archquake.ground_motion import oppenheim_pulse
from archquake.rigid_blocks import BlockSettings, RigidBlockModel, block_outcome, simulate_blocks
from archquake.studies.failure_domain import domain_of

COARSE = BlockSettings(coarse_factor=2)  # the default: 2 ms between the events, 1 ms at them


@pytest.mark.parametrize("duration", [0.4, 0.5])
def test_coarse_steps_find_the_failure_acceleration_of_a_four_times_finer_step(duration):
    """The paper's pulse durations: the failure acceleration of Oppenheim's arch, bisected to
    0.001 g, at coarse steps of 2 ms (1 ms at the events) is that of uniform steps of 0.25 ms
    within 0.002 g (``benchmarks/rigid_block_time_step.py``: 0.5559 and 0.4395 g for both)."""
    found = {}
    for name, settings in (("coarse", COARSE), ("fine", BlockSettings(time_step=2.5e-4))):
        model = RigidBlockModel(oppenheim(), settings)
        domain = domain_of(model, (duration,), (0.3, 0.4, 0.5, 0.6, 0.7), resolution_g=0.001,
                           workers=1)
        found[name] = domain.slices[0].failure_acceleration_g
    assert found["coarse"] == pytest.approx(found["fine"], abs=0.002)


def test_coarse_steps_halve_the_contact_problems_of_a_rocking_arch():
    """Oppenheim's pulse (0.6 g, 0.4 s): the same outcome at about half the contact problems
    (the solves counted by the outcome, not timed)."""
    motion = oppenheim_pulse(-0.6 * GRAVITY, 0.4)
    uniform = block_outcome(oppenheim(), motion, BlockSettings(coarse_factor=1))
    coarse = block_outcome(oppenheim(), motion, COARSE)
    assert uniform.status == coarse.status
    assert coarse.decision_time == pytest.approx(uniform.decision_time, abs=0.05)
    solves = [o.mean_iterations * o.steps for o in (uniform, coarse)]
    assert solves[1] < 0.7 * solves[0]


def test_a_rocking_arch_takes_both_step_lengths():
    """The arch after a pulse (the energy balance of the same run at either coarse factor:
    ``test_arch_energy_after_the_pulse``): the records of every step lie 1 and 2 ms apart."""
    history = simulate_blocks(oppenheim(), oppenheim_pulse(-0.6 * GRAVITY, 0.3), COARSE,
                              tail=0.5)
    spacing = np.unique(np.round(np.diff(history.times), 9))
    assert set(spacing) == {0.001, 0.002}


@pytest.mark.parametrize("amplitude, duration", [(0.6, 0.4), (0.6, 0.3), (0.2, 0.4)])
def test_recording_does_not_change_a_coarse_outcome(amplitude, duration):
    """A collapse, a recovery and a rest: recorded at every 5th step or not, the same steps,
    so the same outcome to the last bit."""
    motion = oppenheim_pulse(-amplitude * GRAVITY, duration)
    alone = block_outcome(oppenheim(), motion, COARSE)
    recorded = simulate_blocks(oppenheim(), motion, COARSE, record_every=5).outcome
    assert recorded == alone


def test_a_coarse_step_is_never_longer_than_the_motion_allows():
    """Under Oppenheim's pulse of 0.27 s at -1 g (which collapses the arch) a step may be at most
    7.8 ms (check_time_step); a coarse factor of 1000 would average the whole pulse away in
    one step, and 8 (8 ms) already turned the collapse into a recovery. The coarse factor is
    held to the longest step allowed: 7 here, whatever is asked above it."""
    from archquake.rigid_blocks.dynamics import check_time_step

    motion = oppenheim_pulse(-GRAVITY, 0.27)
    longest = check_time_step(1e-3, motion, 1.5)  # Oppenheim's arch, 1.5 m thick
    assert 7e-3 <= longest < 8e-3
    allowed = block_outcome(oppenheim(), motion, BlockSettings(coarse_factor=7))
    for asked in (8, 1000):
        assert block_outcome(oppenheim(), motion, BlockSettings(coarse_factor=asked)) == allowed
    assert allowed.status.label == "collapse"
    assert block_outcome(oppenheim(), motion, BlockSettings(coarse_factor=1)).collapsed


@pytest.mark.parametrize("value", [0, -2, 1.5, True, "2"])
def test_coarse_factor_must_be_a_whole_number_of_steps(value):
    with pytest.raises(ValueError,
                       match=r"coarse_factor must be (an integer in \[1, 1000\]|a number)"):
        BlockSettings(coarse_factor=value)


def test_a_free_rocking_block_at_coarse_steps_is_as_accurate_as_every_step_at_twice_h():
    """Where the motion between impacts dominates, coarse steps cost what they save: a block
    (0.4 m x 2 m) released at half its slenderness rocks freely for 3 s; the energy rises above
    its running minimum (the lag of the contact Jacobians, first order in the step: ``solver``,
    "Energy") and the first two impact times miss Housner's ODE as with every step at 2 h, not
    h (measured: rises 3.0e-3 of E(0) at both; RMS errors of the impact times over 9 release
    angles 0.27 and 5.9 ms, against 0.29 and 6.7 ms at 2 ms and 0.15 and 3.0 ms at 1 ms).
    Every impact itself is taken at h."""
    from test_rigid_blocks_block import ALPHA, HEIGHT, WIDTH, crossings, rocking, tilted

    from archquake.rigid_blocks.assembly import rectangular_block

    block = rectangular_block(WIDTH, HEIGHT)
    found = {}
    for name, settings in (("coarse", COARSE),
                           ("2h", BlockSettings(time_step=2e-3, coarse_factor=1))):
        history = simulate_blocks(block, None, settings, initial=tilted(0.5 * ALPHA), t_end=3.0)
        energy = history.total_energy
        rise = float((energy - np.minimum.accumulate(energy)).max()) / energy[0]
        errors = []
        for theta0 in np.linspace(0.4, 0.6, 5) * ALPHA:
            impacts = rocking(lambda t: 0.0, theta0, 3.0)[1][:2]
            run = simulate_blocks(block, None, settings, initial=tilted(theta0),
                                  t_end=impacts[1] + 0.05)
            errors.append(crossings(run, 2) - impacts)
        found[name] = (rise, *np.sqrt(np.mean(np.square(errors), axis=0)))
    for coarse, doubled in zip(found["coarse"], found["2h"], strict=True):
        assert coarse <= 1.05 * doubled
