"""A structure at rest under a ground motion that varies (a record, a sine) skips the steps in
which it stays at rest (``solver.held_steps``, ``contact_problem.rest_range``), and the outcome
is that of the run that takes every step (the second method): the same status, times of
collapse and decision, and steps. The range of accelerations in which it is held never reaches
past the limit analysis's load multiplier (an independent bound), and the blocks are moved by
the creep the full run's compliance gives them, to round-off.
"""

from dataclasses import replace

import numpy as np
import pytest

from archquake import oppenheim
from archquake.geometry import GRAVITY
from archquake.ground_motion import HARMONIC, LINEAR, GroundMotion
from archquake.ground_motion.fema_p695 import builtin_suite
from archquake.limit_analysis import load_multipliers
from archquake.rigid_blocks import BlockSettings, rectangular_block, simulate_blocks
from archquake.rigid_blocks.dynamics import outcome_with_phases

DEFAULT = BlockSettings()
SUITE = "fema-p695-far-field"


def both(structure, motion, settings=DEFAULT):
    """The outcome with the skips and its phases, and without; the same outcome asserted."""
    skip, phases = outcome_with_phases(structure, motion, settings)
    full, every = outcome_with_phases(structure, motion, replace(settings, skip_rest=False))
    assert skip.status == full.status
    assert skip.decided == full.decided
    assert skip.closed == full.closed
    np.testing.assert_equal(skip.collapse_time, full.collapse_time)  # nan == nan
    assert skip.decision_time == full.decision_time
    assert skip.steps == full.steps
    return skip, sum(phases.values()), sum(every.values())


def record(index, level_g):
    return builtin_suite(SUITE, im="pga", level=level_g)[index].motion


@pytest.mark.parametrize("index", [0, 8, 16])
@pytest.mark.parametrize("level_g", [0.3, 0.7])
def test_oppenheims_arch_under_records_the_same_with_and_without_the_skips(index, level_g):
    """0.3 g stays below k = 0.37 (rest), 0.7 g rocks and recovers: at rest for most of the
    record either way, and most of those steps are skipped."""
    outcome, solved, every = both(oppenheim(), record(index, level_g))
    assert outcome.status.label == ("rest" if level_g < 0.37 else "recovery")
    assert solved < 0.7 * every
    if outcome.status.label == "rest":
        assert solved < 0.05 * every


def test_a_record_that_collapses_the_arch_the_same_with_and_without_the_skips():
    outcome, solved, every = both(oppenheim(), record(36, 1.0))
    assert outcome.status.label == "collapse"
    assert solved < every


def test_held_only_below_the_limit_analysis():
    """A sine of 0.4 k g for 4 s leaves the arch at rest with almost every step skipped, and
    one of 0.98 k g at rest too; one of 1.02 k g sets it rocking (k of the limit analysis, an
    independent bound of the range in which the contact problem holds it). The smallest
    impulses hold the arch with every contact sticking up to 0.17 g; above, some contacts
    slide at rest, at their friction limit, where the range ends within a few steps (a slip
    rate that starts at zero): those steps are solved."""
    arch = oppenheim()
    k = min(load_multipliers(arch))
    for ratio, label in ((0.4, "rest"), (0.98, "rest"), (1.02, "recovery")):
        motion = GroundMotion(HARMONIC, params=[ratio * k * GRAVITY, 1.0, 4.0, 0.0],
                              name="sine")
        outcome, solved, every = both(arch, motion)
        assert outcome.status.label == label
        if ratio < 0.5:
            assert solved < 0.05 * every
        elif label == "rest":
            assert solved < every
        else:
            assert outcome.max_rotation > 1e-5


def test_a_block_held_then_rocking_under_a_tabulated_motion():
    """A block 0.4 m x 2 m (k = 0.2) under a table that rises from 0 to 0.15 g and back
    twice, then to 0.3 g: held through the first two waves (skipped), rocking in the third.
    The contact problem holds it in [-0.16, 0.16] g, not up to k = b/h = 0.2: its smallest
    impulses split the friction force evenly between the two corners, and the corner that
    unloads, N = (m g / 2)(1 - a / (k g)) against T = m a / 2, reaches mu N at
    a = mu k g / (k + mu) = 0.16 g (mu = 0.8), where the active-set method lets it slide, at
    rest; the skip ends there and the steps are taken."""
    block = rectangular_block(0.4, 2.0)
    times = [0.0, 1.0, 2.0, 3.0, 4.0, 4.5, 5.0]
    values = np.array([0.0, 0.15, 0.0, -0.15, 0.0, 0.3, 0.0]) * GRAVITY
    motion = GroundMotion(LINEAR, times, values, name="waves")
    outcome, solved, every = both(block, motion, BlockSettings(time_step=0.001))
    assert outcome.max_rotation > 1e-3
    assert solved < every - 2000  # the 4.27 s held: 2,134 coarse steps of the full run


def test_the_skipped_steps_creep_as_the_full_run_and_carry_its_forces():
    """Under a record at 0.3 g the full run's compliance lets the arch creep (1e-11 m to
    1e-9 m over the record); the skip moves the blocks as those steps would, to round-off, and
    records the forces of the affine path, those of the full run's steps."""
    arch = oppenheim()
    motion = record(0, 0.3)
    end = 10.0
    skip = simulate_blocks(arch, motion, DEFAULT, t_end=end, record_every=10)
    full = simulate_blocks(arch, motion, replace(DEFAULT, skip_rest=False), t_end=end,
                           record_every=10)
    np.testing.assert_array_equal(skip.times, full.times)
    creep = np.abs(full.displacements[-1]).max()
    assert creep > 1e-12
    np.testing.assert_allclose(skip.displacements[-1], full.displacements[-1], rtol=0,
                               atol=1e-6 * creep)
    np.testing.assert_allclose(skip.rotations[-1], full.rotations[-1], rtol=0,
                               atol=1e-6 * np.abs(full.rotations[-1]).max())
    weight = arch.loads.total_weight
    np.testing.assert_allclose(skip.normal_forces, full.normal_forces, rtol=0,
                               atol=1e-6 * weight)
    np.testing.assert_allclose(skip.tangential_forces, full.tangential_forces, rtol=0,
                               atol=1e-6 * weight)


def test_a_bridge_under_a_record_the_same_with_and_without_the_skips():
    """Three spans on piers (25 blocks, k = 0.144) under a record at 0.1 g (at rest) and 0.2 g
    (rocks and recovers): the assembly's contact problem in the impulses' band, skipped alike."""
    from archquake.geometry.spec import StructureSpec

    bridge = StructureSpec(spans=3, piers="3,6").nominal()
    for level_g, label in ((0.1, "rest"), (0.2, "recovery")):
        outcome, solved, every = both(bridge, record(0, level_g), BlockSettings(friction=0.8))
        assert outcome.status.label == label
        assert solved < 0.3 * every
