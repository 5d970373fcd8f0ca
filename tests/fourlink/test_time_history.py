"""Tests of the time-history API (simulate, free_vibration) and of its plots."""

import math

import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")

from archquake.fourlink import engine  # noqa: E402
from archquake.fourlink.time_history import (  # noqa: E402
    DEFAULT_EXTRA_TIME,
    Outcome,
    TimeHistory,
    free_vibration,
    simulate,
)
from archquake.geometry import GRAVITY  # noqa: E402
from archquake.ground_motion import oppenheim_pulse, rectangular_pulse  # noqa: E402
from archquake.status import Status  # noqa: E402
from rocking_block import RockingBlock, block_pair  # noqa: E402


@pytest.fixture(scope="module")
def tables():
    return tuple(engine.tabulate(m) for m in block_pair())


def test_free_vibration_alternates_mechanisms_with_signed_phi(tables):
    block = RockingBlock()
    history = free_vibration(tables, (1.0, 1.0), 0.1, t_end=6.0)
    assert isinstance(history, TimeHistory)
    outcome = history.outcome
    assert (outcome.status, outcome.half_cycle, outcome.impacts) == (Status.RECOVERY, 0, 0)
    assert outcome.max_phi == pytest.approx(0.1, rel=1e-12)
    # phi starts at +phi0 in Mech-l; mechanisms alternate at every impact
    assert history.phi[0] == pytest.approx(0.1)
    names = [s.mechanism for s in history.segments]
    assert names[:4] == ["l", "r", "l", "r"]
    for seg in history.segments:
        assert np.all(seg.phi >= -1e-12)
        assert np.all(seg.theta <= block.theta_u + 1e-12)
    signed = history.phi
    t = history.t
    assert np.all(np.diff(t) >= 0)
    in_r = history.mechanism == "r"
    assert np.all(signed[in_r] <= 1e-12) and np.all(signed[~in_r] >= -1e-12)
    # symmetric block, c = 1: the amplitude in either direction stays phi0 (Fig. 9)
    assert np.max(signed) == pytest.approx(0.1, rel=1e-8)
    assert np.min(signed) == pytest.approx(-0.1, rel=1e-8)


def test_pulse_below_activation_leaves_arch_at_rest(tables):
    block = RockingBlock()
    motion = rectangular_pulse(-0.99 * block.activation_g * GRAVITY, 0.5)
    history = simulate(tables, motion, (0.9, 0.9))
    outcome = history.outcome
    assert outcome == Outcome(Status.REST, 0, 0, outcome.collapse_time, 0.0, outcome.steps)
    assert math.isnan(history.outcome.collapse_time)
    assert all(s.mechanism == "rest" for s in history.segments)
    assert history.t[-1] == pytest.approx(0.5 + DEFAULT_EXTRA_TIME)


def test_collapse_time_is_last_outward_crossing(tables):
    history = simulate(tables, oppenheim_pulse(-0.5 * GRAVITY, 0.6), (0.85, 0.85))
    outcome = history.outcome
    assert outcome.status is Status.COLLAPSE and outcome.half_cycle == 2
    assert outcome.collapse_time in history.crossing_times
    # after the point of no return theta stays below theta_cr until the kinematic limit
    last = history.segments[-1]
    after = last.t > outcome.collapse_time
    assert np.all(last.theta[after] < RockingBlock().theta_cr)
    assert last.theta[-1] == pytest.approx(tables[1].theta_lo)


def test_outcome_only_path_returns_outcome(tables):
    outcome = simulate(tables, oppenheim_pulse(-0.5 * GRAVITY, 0.6), (0.85, 0.85),
                       record=False)
    assert isinstance(outcome, Outcome) and outcome.collapsed


def test_plots(tmp_path, tables):
    import matplotlib.pyplot as plt

    from archquake import plotting

    history = free_vibration(tables, (0.875, 0.875), 0.1, t_end=8.0)
    ax = plotting.plot_free_vibration(history)
    assert ax.get_lines()
    ax.figure.savefig(tmp_path / "free.png")
    histories = [simulate(tables, oppenheim_pulse(a * GRAVITY, 0.6), (0.85, 0.85), t_end=5.0)
                 for a in (-0.45, -0.4)]
    ax_ground, ax_resp = plotting.plot_pulse_response(histories, labels=["a", "b"],
                                                      phi_limit=0.5)
    assert ax_ground.get_lines() and ax_resp.get_lines()
    ax_resp.figure.savefig(tmp_path / "pulse.png")
    plt.close("all")
