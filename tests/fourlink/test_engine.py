"""Tests of the compiled engine against closed forms of Housner's rocking block, energy balances,
an independent scipy implementation, and the paper's pulse outcomes (Fig. 15)."""

import importlib.util
import math
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import quad

from archquake import oppenheim
from archquake.fourlink import engine
from archquake.fourlink.engine import stepper, tables
from archquake.fourlink.mechanism import mechanisms
from archquake.fourlink.time_history import free_vibration, simulate
from archquake.geometry import GRAVITY
from archquake.ground_motion import (
    LINEAR,
    GroundMotion,
    oppenheim_pulse,
    rectangular_pulse,
)
from archquake.status import Status
from rocking_block import RockingBlock, block_pair

ROOT = Path(__file__).resolve().parents[2]


def _baseline_module():
    spec = importlib.util.spec_from_file_location(
        "engine_vs_solve_ivp", ROOT / "benchmarks" / "engine_vs_solve_ivp.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def block_tables():
    mech_l, mech_r = block_pair()
    return engine.tabulate(mech_l), engine.tabulate(mech_r)


@pytest.fixture(scope="module")
def nominal_mechanisms():
    return mechanisms(oppenheim())


@pytest.fixture(scope="module")
def nominal_tables(nominal_mechanisms):
    return tuple(engine.tabulate(m) for m in nominal_mechanisms)


def _energy(mech, theta, theta_dot):
    m = mech.coefficients(theta)[0]
    return 0.5 * m * theta_dot**2 + mech.potential_energy(theta)


# ------------------------------------------------------------------------------ tables


@pytest.mark.parametrize("which", ["block", "oppenheim_l", "oppenheim_r"])
def test_table_reproduces_exact_coefficients(which, nominal_mechanisms):
    mech = {"block": RockingBlock(), "oppenheim_l": nominal_mechanisms[0],
            "oppenheim_r": nominal_mechanisms[1]}[which]
    table = engine.tabulate(mech)
    theta = np.random.default_rng(0).uniform(table.theta_lo, table.theta_u, 3000)
    exact = np.vstack([np.broadcast_to(c, theta.shape) for c in mech.coefficients(theta)]
                      + [mech.potential_energy(theta)])
    approx = table.evaluate(theta)
    grid = np.linspace(table.theta_lo, table.theta_u, 5001)
    scale = np.max(np.abs(np.vstack([np.broadcast_to(c, grid.shape)
                                     for c in mech.coefficients(grid)]
                                    + [mech.potential_energy(grid)])), axis=1)
    scale[scale == 0] = 1.0
    error = np.max(np.abs(approx - exact), axis=1) / scale
    assert np.all(error < 1e-11), error
    assert table.activation_g == pytest.approx(mech.activation_g, rel=1e-12)


def test_table_ratios_and_piece_lookup(nominal_mechanisms):
    # the right-hand side uses P/M, gF/M and L/M directly; the piece of any theta is found by
    # equal cells plus a short scan: compare with a search of the breaks
    from archquake import irregular_arch

    for mech in (*nominal_mechanisms, *mechanisms(irregular_arch(oppenheim(), 0.1, rng=5))):
        table = engine.tabulate(mech)
        rng = np.random.default_rng(1)
        theta = np.concatenate([
            rng.uniform(table.theta_lo, table.theta_u, 2000), table.breaks,
            table.theta_lo + (table.theta_u - table.theta_lo) * np.arange(table.n_cells + 1)
            / table.n_cells,
            table.theta_u - np.geomspace(1e-12, 1e-2, 50),
            table.theta_lo + np.geomspace(1e-12, 1e-2, 50)])
        theta = np.clip(theta, table.theta_lo, table.theta_u)
        inv_cell = table.n_cells / (table.theta_u - table.theta_lo)
        found = np.array([tables._piece(x, table.theta_lo, inv_cell, table.cells, table.breaks)
                          for x in theta])
        # Convention: a theta on a break (to round-off) may get the piece on either side, both
        # interpolate the same function there; elsewhere the piece is the one that holds theta.
        slack = 4 * np.finfo(float).eps * (table.theta_u - table.theta_lo)
        left, right = table.breaks[found], table.breaks[found + 1]
        assert np.all((left - slack <= theta) & (theta <= right + slack))
        near_break = np.min(np.abs(theta[:, None] - table.breaks[None, :]), axis=1) <= slack
        expected = np.clip(np.searchsorted(table.breaks, theta, side="right") - 1, 0,
                           table.pieces - 1)
        assert np.array_equal(found[~near_break], expected[~near_break])
        assert np.count_nonzero(near_break) >= table.pieces - 1  # the breaks were tested
        m, l_, f, p = (np.broadcast_to(c, theta.shape) for c in mech.coefficients(theta))
        exact = np.vstack([p / m, GRAVITY * f / m, l_ / m])
        approx = table.functions(theta)[:3]
        scale = np.max(np.abs(exact), axis=1)
        assert np.all(np.max(np.abs(approx - exact), axis=1) / scale < 1e-11)
        rhs = np.array([tables.table_rhs(x, table.theta_lo, inv_cell, table.cells,
                                          table.breaks, table.coefficients) for x in theta]).T
        assert np.allclose(rhs, approx, rtol=1e-13, atol=1e-13 * scale[:, None])


def test_written_out_step_is_the_tableau(nominal_tables):
    """The engine's step and dense output hold the text generated from the DOP853 tableau, and
    that text computes what loops over the tableau compute."""
    from archquake.fourlink.engine import _dop853 as dop

    source = Path(stepper.__file__).read_text()
    begin = source.index(dop.GENERATED_BEGIN)
    end = source.index(dop.GENERATED_END) + len(dop.GENERATED_END) + 1
    assert source[begin:end] == dop.written_out_source()

    tab = engine.pack_pair(*nominal_tables)
    xg = -0.6 * GRAVITY
    none = np.zeros(1)

    def rhs(th, thd):
        return float(stepper.motion_rhs(0.0, th, thd, 0, tab, xg, np.inf, np.inf, 0, none, none,
                                        none))

    y0, y1, h = nominal_tables[0].theta_u - 0.05, -0.4, 0.02
    K = np.zeros((16, 2))
    K[0] = y1, rhs(y0, y1)
    for s in range(1, 16):
        if s == 12:
            continue
        z0 = y0 + h * (dop.A[s, :s] @ K[:s, 0])
        z1 = y1 + h * (dop.A[s, :s] @ K[:s, 1])
        K[s] = z1, rhs(z0, z1)
        if s == 11:  # stage 12 is the end point
            n0, n1 = y0 + h * (dop.B @ K[:12, 0]), y1 + h * (dop.B @ K[:12, 1])
            K[12] = n1, rhs(n0, n1)
    got = np.zeros((16, 2))
    out = stepper.dop853_step(0.0, y0, y1, K[0, 0], K[0, 1], h, 0, tab, xg, np.inf, np.inf, 0, none,
                       none, none, 1e-11, 1e-13, got)
    assert out[0] == pytest.approx(n0, rel=1e-14) and out[1] == pytest.approx(n1, rel=1e-14)
    assert np.allclose(got[:13], K[:13], rtol=1e-13, atol=0)
    sc = 1e-13 + 1e-11 * np.maximum(np.abs([y0, y1]), np.abs([n0, n1]))
    e5, e3 = (dop.E5 @ K[:13]) / sc, (dop.E3 @ K[:13]) / sc
    err = h * (e5 @ e5) / math.sqrt((e5 @ e5 + 0.01 * (e3 @ e3)) * 2.0)
    assert out[3] == pytest.approx(err, rel=1e-3)  # a difference of near-equal sums
    Fd = np.zeros((7, 2))
    stepper.dense_coefficients(0.0, y0, y1, n0, n1, h, 0, tab, xg, np.inf, np.inf, 0, none, none,
                               none, got, Fd)
    dy = np.array([n0 - y0, n1 - y1])
    expected = np.vstack([dy, h * K[0] - dy, 2.0 * dy - h * (K[12] + K[0]),
                          h * (dop.D @ K)])
    assert np.allclose(Fd[:3], expected[:3], rtol=1e-9, atol=1e-16)
    # rows 3-6 are small differences of large sums: compare with the size of their terms
    terms = h * (np.abs(dop.D) @ np.abs(K))
    assert np.all(np.abs(Fd[3:] - expected[3:]) <= 1e-13 * terms.max(axis=0))


# ------------------------------------------------------------------------------ free rocking


def _quarter_period(block, phi0):
    """Exact time from rest at phi0 to the first impact (energy integral by quadrature)."""
    p2 = block.frequency**2
    alpha = block.alpha
    u0 = alpha - phi0  # u = theta - pi/2; u'' = p^2 sin u, u'^2 = 2 p^2 (cos u0 - cos u)

    def integrand(u):  # times the weight (u - u0)^(-1/2)
        # (u - u0) / (cos u0 - cos u) = (x / sin x) / sin((u + u0)/2), x = (u - u0)/2
        x = 0.5 * (u - u0)
        ratio = (x / math.sin(x) if x else 1.0) / math.sin(0.5 * (u + u0))
        return math.sqrt(ratio / (2.0 * p2))

    value, _ = quad(integrand, u0, alpha, weight="alg", wvar=(-0.5, 0.0), epsabs=1e-15,
                    epsrel=1e-13)
    return value


def test_first_impact_matches_energy_quadrature(block_tables):
    block = RockingBlock()
    phi0 = 0.1
    history = free_vibration(block_tables, (1.0, 1.0), phi0, t_end=3.0)
    assert history.impact_times[0] == pytest.approx(_quarter_period(block, phi0), rel=1e-9)


def test_first_impact_matches_housner_linearised_closed_form():
    block = RockingBlock(linearised=True)
    tables = tuple(engine.tabulate(m) for m in block_pair(linearised=True))
    phi0 = 0.1
    history = free_vibration(tables, (1.0, 1.0), phi0, t_end=3.0)
    # Housner (1963): u = u0 cosh(p t) reaches alpha at t = acosh(1 / (1 - phi0/alpha)) / p
    expected = math.acosh(1.0 / (1.0 - phi0 / block.alpha)) / block.frequency
    assert history.impact_times[0] == pytest.approx(expected, rel=1e-9)


def test_energy_conserved_over_twenty_elastic_impacts(block_tables):
    block = RockingBlock()
    phi0 = 0.2
    t1 = _quarter_period(block, phi0)
    history = free_vibration(block_tables, (1.0, 1.0), phi0, t_end=t1 * 42)
    times = history.impact_times
    assert times.size >= 20
    # every impact at theta_u: impacts are exactly one half period (2 t1) apart
    np.testing.assert_allclose(times[:20], t1 * (1 + 2 * np.arange(20)), rtol=1e-9)
    e0 = float(block.potential_energy(block.theta_u - phi0))
    energies = np.concatenate([_energy(block, s.theta, s.theta_dot) for s in history.segments])
    assert np.max(np.abs(energies - e0)) / e0 < 1e-8
    speed = math.sqrt(2 * (e0 - block.potential_energy(block.theta_u))
                      / block.coefficients(block.theta_u)[0])
    np.testing.assert_allclose(history.impact_velocities[:20, 0], speed, rtol=1e-9)


def test_kinetic_energy_ratio_per_impact_is_c_squared(block_tables):
    block = RockingBlock()
    c_lr, c_rl = 0.9, 0.8
    history = free_vibration(block_tables, (c_lr, c_rl), 0.2, t_end=12.0)
    before = history.impact_velocities[:, 0]
    assert before.size >= 6
    m_u = block.coefficients(block.theta_u)[0]
    ke_before = 0.5 * m_u * before**2
    ke_after = 0.5 * m_u * history.impact_velocities[:, 1] ** 2
    c = np.where(np.array(history.impact_mechanisms) == "l", c_lr, c_rl)
    np.testing.assert_allclose(ke_after, c**2 * ke_before, rtol=1e-13)
    # the free motion between impacts conserves energy: next arrival = previous departure
    np.testing.assert_allclose(ke_before[1:], ke_after[:-1], rtol=1e-9, atol=1e-9 * ke_before[0])


def test_arch_comes_to_rest_after_geometric_impacts(block_tables):
    history = free_vibration(block_tables, (0.5, 0.5), 0.05, t_end=20.0)
    assert history.outcome.status is Status.RECOVERY
    assert history.segments[-1].mechanism == "rest"
    assert abs(history.impact_velocities[-1, 1]) < engine.DEFAULT_REST_VELOCITY


# ------------------------------------------------------------------------------ pulses


def test_rectangular_pulse_overturning_amplitude_matches_closed_form():
    """Slender block, linearised: a rectangular pulse of duration t_p overturns the block in the
    first half cycle iff a/g >= alpha / (1 - exp(-p t_p)) (Housner 1963; the energy condition
    |u'| >= p u at the end of the pulse, derived in the test's docstring of RockingBlock)."""
    block = RockingBlock(linearised=True)
    tables = tuple(engine.tabulate(m) for m in block_pair(linearised=True))
    for tp in (0.2, 0.5, 1.0):
        expected = block.alpha / (1.0 - math.exp(-block.frequency * tp))
        above = simulate(tables, rectangular_pulse(-expected * (1 + 1e-7) * GRAVITY, tp),
                         (1.0, 1.0), record=False)
        below = simulate(tables, rectangular_pulse(-expected * (1 - 1e-7) * GRAVITY, tp),
                         (1.0, 1.0), record=False)
        assert (above.status, above.half_cycle) == (Status.COLLAPSE, 1)
        assert below.status is Status.RECOVERY


def test_work_of_ground_balances_energy_and_impact_losses(block_tables):
    block = RockingBlock()
    motion = oppenheim_pulse(-0.5 * GRAVITY, 0.6)
    c = 0.85
    history = simulate(block_tables, motion, (c, c), t_end=12.0, record_dt=1e-3)
    assert history.impact_times.size >= 1
    m_r = block.mass * block.radius
    work = 0.0
    for seg in history.segments:
        if seg.mechanism == "rest":
            continue
        sign = 1.0 if seg.mechanism == "l" else -1.0
        # dE/dt = s P xg'' theta'  (Mech-l s = +1, Mech-r s = -1): with xg'' constant between
        # samples and P = m R sin(theta), the work is s xg'' m R (cos theta_a - cos theta_b)
        xg = motion.acceleration(0.5 * (seg.t[1:] + seg.t[:-1]))
        work += np.sum(sign * xg * m_r * (np.cos(seg.theta[:-1]) - np.cos(seg.theta[1:])))
    m_u = block.coefficients(block.theta_u)[0]
    losses = np.sum(0.5 * m_u * (history.impact_velocities[:, 0] ** 2
                                 - history.impact_velocities[:, 1] ** 2))
    last = history.segments[-1]
    e_end = float(_energy(block, last.theta[-1], last.theta_dot[-1]))
    e_start = float(block.potential_energy(block.theta_u))
    assert e_end - e_start == pytest.approx(work - losses, rel=1e-7, abs=1e-9 * e_start)


def test_activation_instant_located_on_a_linear_record(block_tables):
    block = RockingBlock()
    slope = 5.0  # xg'' = -slope t [m/s^2]
    motion = GroundMotion(LINEAR, [0.0, 2.0], [0.0, -2.0 * slope])
    history = simulate(block_tables, motion, (0.9, 0.9), t_end=1.0)
    first = next(s for s in history.segments if s.mechanism != "rest")
    assert first.mechanism == "l"
    assert first.t[0] == pytest.approx(block.activation_g * GRAVITY / slope, rel=1e-13)


def test_paper_fig15_outcomes_of_oppenheims_arch(paper, nominal_tables):
    c = paper["dynamics"]["NA"]["restitution_paper"]
    for tp, amplitude, status, half_cycle in paper["dynamics"]["NA"]["pulse_cases"]:
        outcome = simulate(nominal_tables, oppenheim_pulse(amplitude * GRAVITY, tp), (c, c),
                           record=False)
        assert (outcome.status.label, outcome.half_cycle) == (status, half_cycle), tp


def test_record_and_outcome_paths_agree(nominal_tables):
    for tp, a in ((0.44, -1.0), (0.27, -1.0), (0.2, -1.0), (0.5, 0.45), (0.3, 0.2)):
        motion = oppenheim_pulse(a * GRAVITY, tp)
        fast = simulate(nominal_tables, motion, (0.875, 0.875), record=False)
        history = simulate(nominal_tables, motion, (0.875, 0.875))
        recorded = history.outcome
        assert (recorded.status, recorded.half_cycle, recorded.impacts) == (
            fast.status, fast.half_cycle, fast.impacts)
        np.testing.assert_equal(recorded.collapse_time, fast.collapse_time)
        np.testing.assert_equal(recorded.max_phi, fast.max_phi)


def test_grid_matches_single_analyses(nominal_tables):
    durations = np.array([0.2, 0.27, 0.44, 0.4, 0.6])
    amplitudes = np.array([-1.0, -1.0, -1.0, 0.49, -0.3]) * GRAVITY
    grid = engine.outcomes_grid(*nominal_tables, 0.875, 0.875, durations, amplitudes)
    for q in range(durations.size):
        single = simulate(nominal_tables, oppenheim_pulse(amplitudes[q], durations[q]),
                          (0.875, 0.875), record=False)
        assert grid["status"][q] == single.status
        assert grid["steps"][q] == single.steps
        assert grid["half_cycle"][q] == single.half_cycle
        assert grid["impacts"][q] == single.impacts
        np.testing.assert_equal(grid["collapse_time"][q], single.collapse_time)


def test_outcomes_unchanged_with_tighter_tolerances(nominal_tables):
    rng = np.random.default_rng(3)
    durations = rng.uniform(0.2, 0.7, 60)
    amplitudes = -(0.37 + 0.05 / durations) * rng.uniform(0.7, 1.3, 60) * GRAVITY
    reference = engine.outcomes_grid(*nominal_tables, 0.875, 0.875, durations, amplitudes)
    for factor in (10.0, 100.0):
        tight = engine.outcomes_grid(
            *nominal_tables, 0.875, 0.875, durations, amplitudes,
            rtol=engine.DEFAULT_RTOL / factor, atol=engine.DEFAULT_ATOL / factor,
            rest_velocity=engine.DEFAULT_REST_VELOCITY / factor,
            max_step=engine.DEFAULT_MAX_STEP / factor)
        for key in ("status", "half_cycle", "impacts"):
            np.testing.assert_array_equal(tight[key], reference[key])
        np.testing.assert_allclose(tight["collapse_time"], reference["collapse_time"],
                                   rtol=1e-7)


def test_engine_matches_scipy_baseline(nominal_mechanisms, nominal_tables):
    baseline = _baseline_module()
    rng = np.random.default_rng(7)
    durations = rng.uniform(0.2, 0.7, 10)
    amplitudes = -(0.37 + 0.05 / durations) * rng.uniform(0.7, 1.3, 10)
    grid = engine.outcomes_grid(*nominal_tables, 0.875, 0.875, durations, amplitudes * GRAVITY)
    for q in range(10):
        motion = oppenheim_pulse(amplitudes[q] * GRAVITY, durations[q])
        status, half_cycle, impacts, time = baseline.baseline_outcome(
            *nominal_mechanisms, 0.875, 0.875, motion)
        assert (grid["status"][q], grid["half_cycle"][q], grid["impacts"][q]) == (
            status, half_cycle, impacts)
        if status == engine.STATUS_COLLAPSE:
            assert grid["collapse_time"][q] == pytest.approx(time, rel=1e-6)


# ------------------------------------------------------------------------------ inputs


def test_invalid_inputs_raise(block_tables):
    with pytest.raises(ValueError, match="t_end"):
        simulate(block_tables, None, (1.0, 1.0), t_end=-1.0, initial=("l", 0.1, 0.0))
    with pytest.raises(ValueError, match="initial mechanism"):
        simulate(block_tables, None, (1.0, 1.0), initial=("x", 0.1, 0.0))
    for c in (0.0, 1.5, -0.2):
        with pytest.raises(ValueError, match="restitution"):
            simulate(block_tables, None, (c, 0.9), initial=("l", 0.1, 0.0))
    with pytest.raises(ValueError, match="phi0"):
        free_vibration(block_tables, (1.0, 1.0), 5.0)
    with pytest.raises(ValueError, match="durations"):
        engine.outcomes_grid(*block_tables, 0.9, 0.9, [-0.1], [-GRAVITY])
    with pytest.raises(ValueError, match="unknown ground motion"):
        engine.outcomes_grid(*block_tables, 0.9, 0.9, [0.1], [-GRAVITY], motion="nope")
    with pytest.raises(ValueError, match=r"\(Mech-l, Mech-r\)"):
        simulate(block_tables[::-1], None, (1.0, 1.0), initial=("l", 0.1, 0.0))
    with pytest.raises(ValueError, match="degree 9"):
        engine.pack_pair(engine.tabulate(block_pair()[0], degree=7), block_tables[1])
