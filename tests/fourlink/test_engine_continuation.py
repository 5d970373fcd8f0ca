"""The outcome decided when the excitation ends agrees with the motion that follows it.

The engine decides recovery or collapse from the energy of the state at the end of the
excitation (archquake.fourlink.engine.rules), without integrating further. Followed on, the motion
must agree: a recovery never passes theta_cr away from theta_u nor reaches the kinematic limit, and
never rotates more than the decided largest rotation; a collapse has exactly the impacts decided
before it reaches the kinematic limit and never comes to rest. The engine checks this itself when
it follows the motion (outcomes_grid(continuation=...), and every recorded time history), and
raises RuntimeError on a contradiction.
"""

import dataclasses
import math

import numpy as np
import pytest

from archquake import irregular_arch, oppenheim
from archquake.fourlink import engine
from archquake.fourlink.impact import restitution
from archquake.fourlink.mechanism import mechanisms
from archquake.fourlink.time_history import simulate
from archquake.geometry import GRAVITY
from archquake.ground_motion import ground_motion, harmonic, oppenheim_pulse
from archquake.status import Status

SHAPES = {
    "oppenheim": "oppenheim",
    "rectangular": "rectangular",
    "sine": "sine",
    # three cycles of a sine (one cycle is the "sine" pulse): long excitations, many impacts
    "harmonic": harmonic(1.0, 1.0, cycles=3),
}
RESTITUTION = ((0.55, 0.55), (0.7, 0.7), (0.875, 0.875), (1.0, 1.0))
"""Equal coefficients ``(c_lr, c_rl)``; every arch also gets its computed pair (impact.py),
unequal and for the irregular arches sometimes one above 1 (e.g. 1.24 and 0.49)."""
CONTINUATION = 5.0  # [s] followed after every decision
ARCHES = {"NA": None, "seed0": 0, "seed1": 1, "seed2": 2, "seed3": 3}


@pytest.fixture(scope="module")
def arches():
    """``name -> (tables of Mech-l and Mech-r, computed (c_lr, c_rl))``."""
    nominal = oppenheim()
    out = {}
    for name, seed in ARCHES.items():
        arch = nominal if seed is None else irregular_arch(nominal, 0.1, rng=seed)
        pair = mechanisms(arch)
        out[name] = (tuple(engine.tabulate(m) for m in pair), restitution("computed", *pair))
    return out


@pytest.fixture(scope="module")
def arch_tables(arches):
    return {name: tables for name, (tables, _) in arches.items()}


def _pulses(rng, tables, n):
    """Durations [s] and signed amplitudes [m/s^2] from just above the activation of the arch
    to well beyond its failure curve, both directions."""
    k = max(t.activation_g for t in tables)
    durations = rng.uniform(0.1, 1.0, n)
    amplitudes_g = k * (1.0 + rng.uniform(0.0, 1.5, n) * (1.0 + 0.3 / durations))
    return durations, rng.choice([-1.0, 1.0], n) * amplitudes_g * GRAVITY


def _sweep(arches, per_case: int, seed: int) -> dict:
    """Every arch x shape x restitution, ``per_case`` pulses each, followed after the decision
    (outcomes_grid raises RuntimeError on a contradiction or an undecided analysis)."""
    rng = np.random.default_rng(seed)
    classes = {}
    analyses = 0
    for tables, computed in arches.values():
        for motion in SHAPES.values():
            for c_lr, c_rl in (*RESTITUTION, computed):
                durations, amplitudes = _pulses(rng, tables, per_case)
                res = engine.outcomes_grid(*tables, c_lr, c_rl, durations, amplitudes, motion,
                                           continuation=CONTINUATION)
                analyses += durations.size
                for st, hc in zip(res["status"], res["half_cycle"], strict=True):
                    key = (Status(int(st)), int(hc))
                    classes[key] = classes.get(key, 0) + 1
    return {"analyses": analyses, "classes": classes}


def _check_sweep(result, at_least):
    assert result["analyses"] >= at_least
    classes = result["classes"]
    # a sweep that exercises every decision: recoveries, and collapses in the first half cycle,
    # after one impact (the arrival into the other mechanism) and after two (back into the first)
    assert classes.get((Status.RECOVERY, 0), 0) > 0.2 * result["analyses"]
    for half_cycle in (1, 2, 3):
        assert classes.get((Status.COLLAPSE, half_cycle), 0) > 0, classes


def test_decision_agrees_with_continuation_sweep(arches):
    """12,800 analyses (5 arches x 4 shapes x 5 pairs of c_v x 128 pulses), each followed 5 s
    after its decision: no contradiction, every analysis decided."""
    _check_sweep(_sweep(arches, per_case=128, seed=2024), at_least=12_800)


@pytest.mark.slow
def test_decision_agrees_with_continuation_large_sweep(arches):
    """Ten times the default sweep (128,000 analyses), other pulses."""
    _check_sweep(_sweep(arches, per_case=1280, seed=7), at_least=128_000)


def test_recovery_never_rotates_more_than_decided(arch_tables):
    """The recorded motion after a recovery decision stays within the decided largest rotation
    (the energy rule's turning points, found by root finding on the tabulated V)."""
    rng = np.random.default_rng(11)
    checked = 0
    for name in ("NA", "seed1"):
        tables = arch_tables[name]
        for c in (0.7, 1.0):
            durations, amplitudes = _pulses(rng, tables, 40)
            for tp, a in zip(durations, amplitudes, strict=True):
                motion = oppenheim_pulse(a, tp)
                history = simulate(tables, motion, (c, c), t_end=motion.duration + 6.0)
                outcome = history.outcome
                if outcome.status is not Status.RECOVERY:
                    continue
                after = [s for s in history.segments if s.mechanism != "rest"
                         and s.t[-1] > motion.duration]
                if not after:
                    continue
                phi = max(float(np.max(s.phi[s.t >= motion.duration])) for s in after
                          if np.any(s.t >= motion.duration))
                assert phi <= outcome.max_phi + 1e-9, (name, c, tp, a)
                # and max_phi is a rotation the arch reaches (the record samples every 2 ms)
                recorded = float(np.max(np.abs(history.phi)))
                assert recorded == pytest.approx(outcome.max_phi, rel=1e-2), (name, c, tp, a)
                checked += 1
    assert checked >= 20


def test_a_wrong_decision_is_caught(arch_tables):
    """Tables whose theta_cr is put halfway between theta_u and the true one: the energy rule
    then compares with a barrier V(theta_cr) lower than the true maximum of V and decides
    collapse where the arch, integrated, turns back and comes home. The recorded path and a
    followed grid must refuse it, not pass it silently."""
    true = arch_tables["NA"]
    fake = tuple(dataclasses.replace(t, theta_cr=0.5 * (t.theta_u + t.theta_cr)) for t in true)
    c = 0.875
    amplitudes = -np.linspace(0.3, 1.2, 46) * GRAVITY
    found = None
    for a in amplitudes:
        motion = oppenheim_pulse(a, 0.3)
        wrong = simulate(fake, motion, (c, c), record=False)
        right = simulate(true, motion, (c, c), record=False)
        if wrong.status is Status.COLLAPSE and right.status is Status.RECOVERY:
            found = motion
            break
    assert found is not None, "no pulse separates the two barriers"
    with pytest.raises(RuntimeError, match="contradicts"):
        simulate(fake, found, (c, c))
    with pytest.raises(RuntimeError, match="contradict"):
        engine.outcomes_grid(*fake, c, c, [0.3], [found.values[0]], continuation=CONTINUATION)
    # the true tables: the same pulse passes both checks
    assert simulate(true, found, (c, c)).outcome.status is Status.RECOVERY
    engine.outcomes_grid(*true, c, c, [0.3], [found.values[0]], continuation=CONTINUATION)


def _opening_estimate(table, motion, sign):
    """Order of magnitude of the rotation [rad] of a mechanism whose activation threshold the
    ground exceeds by at most ``excess`` [m/s^2] during ``w`` [s] in all:
    ``max(P/M) excess w^2 / 2`` (from a fine sampling of the motion; ``sign`` +1 for Mech-r,
    which the positive ground acceleration opens, -1 for Mech-l)."""
    t = np.linspace(0.0, motion.duration, 200_001)
    excess = sign * motion.acceleration(t) - table.activation_g * GRAVITY
    window = (np.count_nonzero(excess > 0) + 2) * (t[1] - t[0])
    theta = np.linspace(table.theta_lo, table.theta_u, 10_001)
    p_over_m = np.max(np.abs(table.functions(theta)[0]))
    return 0.5 * p_over_m * max(float(np.max(excess)), 0.0) * window**2


def test_barely_activating_pulses_are_decided(arch_tables):
    """Two analyses that ran to the safety limit of 2,000,000 steps (undecided) before the
    activation test was made the sign of the engine's own theta'' and the location of an
    impact was kept on the rising part of its step:

    - a one-cycle sine 0.07 % above the activation of NA (the arch was activated with
      theta'' = +0, closed again at the same instant, and so on for ever): it recovers, and its
      rotation is of the order that the tiny excess of the ground over its threshold allows;
    - three cycles at 0.1 % above the activation of Mech-r of an irregular arch with c_v = 1
      (chatter of zero-time impacts): it recovers, and its recorded motion never reaches
      theta_cr.
    """
    tables = arch_tables["NA"]
    motion = ground_motion("sine", 0.3702593038435492 * GRAVITY, 0.21952416435785937)
    out = simulate(tables, motion, (0.55, 0.55), record=False)
    assert out.status is Status.RECOVERY and out.steps < 10_000
    estimate = max(_opening_estimate(tables[1], motion, 1.0),
                   _opening_estimate(tables[0], motion, -1.0))
    assert 0.0 < out.max_phi < 10.0 * estimate

    arch = irregular_arch(oppenheim(), 0.1, rng=7)
    tables = tuple(engine.tabulate(m) for m in mechanisms(arch))
    motion = harmonic(0.36741915616188686 * GRAVITY, 0.31692108529709206, cycles=3)
    out = simulate(tables, motion, (1.0, 1.0), record=False)
    assert out.status is Status.RECOVERY and out.steps < 100_000
    history = simulate(tables, motion, (1.0, 1.0))  # followed 4 s after the decision
    phi_cr = {"l": tables[0].theta_u - tables[0].theta_cr,
              "r": tables[1].theta_u - tables[1].theta_cr}
    for segment in history.segments:
        if segment.mechanism != "rest":
            assert np.all(segment.phi < phi_cr[segment.mechanism])
    assert math.isnan(out.collapse_time)
