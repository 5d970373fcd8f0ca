"""A recorded ground motion run over many scale factors in one compiled call.

``engine.outcomes_grid`` takes a template GroundMotion (a record) with ``durations = 1`` and the
scale factors as ``amplitudes``; every outcome must be that of the single analysis of the scaled
record, :func:`archquake.fourlink.time_history.simulate` of ``record.scaled(f)`` (and of
``record.reversed().scaled(f)`` for a negative factor).
"""

import numpy as np
import pytest

from archquake import FourLinkModel
from archquake.fourlink import engine
from archquake.fourlink.time_history import simulate
from archquake.ground_motion import stochastic_motion


@pytest.fixture(scope="module")
def dynamics(nominal):
    dynamics = FourLinkModel.from_arch(nominal, "nominal")
    return dynamics.tables, dynamics.restitution, dynamics.load_multipliers


@pytest.fixture(scope="module")
def short_record():
    """Six seconds of a low-frequency synthetic motion (peak about 1.6 m/s^2 before scaling)."""
    return stochastic_motion(0.05, 4.0, 3.0, 1.0, 0.0, 0.2, duration=6.0, rng=1)


def test_record_grid_equals_single_analyses_of_the_scaled_record(dynamics, short_record):
    (table_l, table_r), (c_lr, c_rl), _ = dynamics
    peak = short_record.peak / 9.81
    factors = np.array([0.3, 0.45, 0.6, 0.8, 1.0, 1.3, 1.6, 2.0]) / peak
    signed = np.concatenate([factors, -factors])
    grid = engine.outcomes_grid(table_l, table_r, c_lr, c_rl, 1.0, signed, short_record)
    expected = []
    for motion in (short_record, short_record.reversed()):
        for f in factors:
            out = simulate((table_l, table_r), motion.scaled(f), (c_lr, c_rl), record=False)
            expected.append((out.status.label, out.half_cycle, out.impacts))
    got = [(engine.STATUS_NAMES[int(s)], int(h), int(i)) for s, h, i in
           zip(grid["status"], grid["half_cycle"], grid["impacts"], strict=True)]
    assert got == expected
    # the grid spans every outcome, so the comparison covers each path of the engine
    assert {g[0] for g in got} == {"rest", "recovery", "collapse"}


@pytest.mark.parametrize("start", [0.0, 0.37], ids=["from t=0", "first sample later"])
def test_activation_after_a_long_quiet_stretch_is_the_linear_crossing(dynamics, start):
    """The activation scan passes over quiet samples without evaluating the motion: the instant
    found after 1500 quiet samples is still the crossing of k_r g on the first segment that
    reaches it (a closed form), and samples a hair inside the threshold do not activate."""
    from archquake.ground_motion import LINEAR, GroundMotion

    (table_l, table_r), (c_lr, c_rl), _ = dynamics
    threshold = table_r.activation_g * 9.81  # Mech-r opens when xg'' > k_r g
    t = start + 0.01 * np.arange(2000)
    quiet = 0.6 * threshold * np.sin(2 * np.pi * t / 0.37)
    for hair in (1 - 1e-13, 1 - 1e-15):  # strictly below: never activates
        values = quiet.copy()
        values[1500] = hair * threshold
        values[1700] = -hair * table_l.activation_g * 9.81
        out = simulate((table_l, table_r), GroundMotion(LINEAR, t, values), (c_lr, c_rl),
                       record=False)
        assert out.status.label == "rest"
    values = quiet.copy()
    values[1499], values[1500] = 0.0, 2.0 * threshold  # crosses half way through the segment
    history = simulate((table_l, table_r), GroundMotion(LINEAR, t, values), (c_lr, c_rl),
                       t_end=t[1500] + 0.01)
    first = next(s for s in history.segments if s.mechanism != "rest")
    assert first.mechanism == "r"
    assert first.t[0] == pytest.approx(0.5 * (t[1499] + t[1500]), abs=1e-12)
