"""The steps skipped at rest (:func:`archquake.rigid_blocks.solver.steady_steps`): a structure at
rest under a constant piece of a pulse is in static equilibrium, so the solver jumps to the
piece's end. Checked against the same motion without its rest (a rigid block at rest is in its
undeformed configuration whatever held it there: the motion after the rest is the same, shifted
in time, to round-off) and against the decision step that the outcome criteria give in closed
form, for far fewer linear solves.
"""

import numpy as np
import pytest

from archquake import oppenheim
from archquake.geometry import GRAVITY
from archquake.ground_motion import STEP, GroundMotion, oppenheim_pulse
from archquake.rigid_blocks import BlockSettings, block_outcome, rectangular_block, simulate_blocks

WIDTH, HEIGHT = 0.4, 2.0
K = WIDTH / HEIGHT  # the block starts to rock at k g
SETTINGS = BlockSettings(time_step=0.001)


def rest_decision(excitation_end, h=0.001, window=100, coarse=2):
    """When rest is decided [s]: ``window`` steps of rest counted from the first step that
    starts at or after the end of the excitation (t_k = k h >= t_exc, as the solver tests it),
    the step that ends there counting the steps h it spans: ``coarse`` (the default
    coarse_factor) if it ends on the grid of coarse steps (a multiple of ``coarse`` steps, as
    every coarse step at rest does), else one. E.g. t_exc = 0.3 s at h = 1 ms, coarse 2: the
    step 0.298-0.300 s counts 2, every later one 2, so the count reaches 100 at 0.398 s."""
    first = next(k for k in range(10**6) if k * h >= excitation_end)
    counted = coarse if first % coarse == 0 else 1
    return (first + window - counted) * h


def step_motion(pieces):
    """A piecewise-constant motion from ``(duration [s], acceleration [g])`` pieces."""
    times, values = [0.0], []
    for duration, accel in pieces:
        times.append(times[-1] + duration)
        values.append(accel * GRAVITY)
    return GroundMotion(STEP, times, values, name="pieces")


@pytest.fixture(scope="module")
def block():
    return rectangular_block(WIDTH, HEIGHT)


@pytest.mark.parametrize("coarse_factor, agree", [(1, 1e-9), (2, 1e-6)])
def test_rest_then_rocking_is_the_rocking_without_the_rest(block, coarse_factor, agree):
    """Every step at h: the histories agree to round-off. Coarse steps: round-off may tip the
    choice of a step's length (coarse, or again at h) near an event, which moves the rocking
    by more than round-off (1e-7 rad over 2 s here), not its outcome."""
    settings = BlockSettings(time_step=0.001, coarse_factor=coarse_factor)
    rest, rocking = (0.3, 0.5 * K), (0.25, 1.6 * K)  # at rest 0.3 s, then the block rocks
    after_rest = simulate_blocks(block, step_motion([rest, rocking]), settings, record_every=1)
    direct = simulate_blocks(block, step_motion([rocking]), settings, record_every=1)
    start = int(np.searchsorted(after_rest.times, 0.3 - 1e-9))  # the records of the rest
    assert after_rest.outcome.status == direct.outcome.status
    assert direct.outcome.max_rotation > 0.01  # it rocked
    # over the pulse and the first rocking the histories agree to round-off (1e-11 rad); the
    # impacts of the long tail to rest amplify it (1e-6 rad after 5 s, a few ms on the
    # decision after 8 s of rocking), as any round-off
    n = 2000 // coarse_factor
    assert np.allclose(after_rest.times[start:start + n], direct.times[:n] + 0.3, atol=1e-12)
    assert np.abs(after_rest.rotations[start:start + n] - direct.rotations[:n]).max() < agree
    assert np.abs(after_rest.rotations[:start]).max() < 1e-12
    assert after_rest.outcome.decision_time == pytest.approx(direct.outcome.decision_time + 0.3,
                                                             abs=0.01)
    # the rest cost no contact problem but its first steps
    solves = [o.mean_iterations * o.steps for o in (after_rest.outcome, direct.outcome)]
    assert solves[0] < solves[1] + 10


@pytest.mark.parametrize("amplitude", [0.2, 0.3])
def test_oppenheims_arch_at_rest_decides_when_the_window_ends(amplitude):
    """Below the activation (k = 0.37) in both directions of Oppenheim's pulse: rest, decided
    after the excitation (3 t_p) and the window of rest (0.1 s), in a few dozen solves."""
    arch = oppenheim()
    tp = 0.4
    outcome = block_outcome(arch, oppenheim_pulse(-amplitude * GRAVITY, tp))
    assert outcome.status.label == "rest"
    assert outcome.decision_time == pytest.approx(rest_decision(3 * tp), abs=1e-12)
    assert outcome.max_rotation < 1e-9
    assert outcome.mean_iterations * outcome.steps < 50  # of 1300 steps


def test_a_record_of_the_rest_is_written_at_every_stride(block):
    motion = step_motion([(0.3, 0.5 * K)])
    history = simulate_blocks(block, motion, SETTINGS, record_every=10, t_end=0.5)
    assert np.allclose(np.diff(history.times), 0.01)
    assert history.times[-1] == pytest.approx(0.49)
    assert np.abs(history.rotations).max() < 1e-12
    assert history.outcome.decision_time == pytest.approx(rest_decision(0.3), abs=1e-12)
