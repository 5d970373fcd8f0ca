"""The compiled engine against a straightforward scipy implementation of the same rules.

The baseline is what a user would write: ``solve_ivp(method="DOP853", rtol=1e-9)`` with a Python
right-hand side calling the mechanism's exact ``coefficients`` at every evaluation, terminal
events for the impact and the kinematic limit, one ``solve_ivp`` call per interval of the
piecewise-constant pulse (or of the piecewise-linear record, between two samples), and the
decision rules of :mod:`archquake.fourlink.engine` (energy test once the excitation is over). It is
an independent second implementation, used by the tests on a few cases and by
``benchmarks/record_vs_solve_ivp.py`` on records.

Run:  python benchmarks/engine_vs_solve_ivp.py [--analyses 600] [--block]
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "src"))

from archquake.fourlink import engine  # noqa: E402
from archquake.geometry import GRAVITY  # noqa: E402
from archquake.ground_motion import LINEAR, STEP, oppenheim_pulse  # noqa: E402

LIMIT_MARGIN = 1e-6  # as engine.tabulate
BASELINE_TOL = {"rtol": 1e-9, "atol": 1e-12}  # solve_ivp's tolerances below
IMPACT_OFFSET = 1e-12  # [rad]
MAX_EVENTS = 2_000


def baseline_outcome(mech_l, mech_r, c_lr, c_rl, motion, *, rtol=1e-9, atol=1e-12,
                     rest_velocity=engine.DEFAULT_REST_VELOCITY, impact_offset=IMPACT_OFFSET):
    """``(status, half_cycle, impacts, collapse_time)`` with scipy, for a STEP (pulse) or
    LINEAR (record) ground motion."""
    if motion.kind not in (STEP, LINEAR):
        raise ValueError("the baseline handles piecewise-constant and piecewise-linear ground "
                         "motions only")
    mechs = (mech_l, mech_r)
    sign = (1.0, -1.0)
    c_of = (c_lr, c_rl)
    lo = [m.theta_limit + LIMIT_MARGIN for m in mechs]
    times, values = motion.times, motion.values
    act = []
    for k, m in enumerate(mechs):
        _, _, f, p = m.coefficients(m.theta_u)
        act.append(float(f * GRAVITY / p) if k == 0 else float(-f * GRAVITY / p))

    def accel(t):
        if motion.kind == LINEAR:
            return float(np.interp(t, times, values, left=0.0, right=0.0))
        if t < times[0] or t >= times[-1]:
            return 0.0
        return float(values[np.searchsorted(times, t, side="right") - 1])

    def activated(xg):
        return 0 if xg < act[0] else (1 if xg > act[1] else -1)

    def ground_on(t_a, t_b):
        """The ground acceleration on [t_a, t_b) as a function of t (a line for a record)."""
        a0 = accel(t_a)
        if motion.kind == STEP:
            return lambda t: a0
        a1 = float(np.interp(t_b, times, values, left=0.0, right=0.0))
        return lambda t: a0 + (a1 - a0) * (t - t_a) / (t_b - t_a)

    def activation(t0, t_b, ground):
        """First ``(t, mechanism)`` in [t0, t_b) at which the ground opens a mechanism."""
        if motion.kind == STEP:
            return t0, activated(ground(t0))
        g0, g1 = ground(t0), ground(t_b)
        if activated(g0) >= 0:
            return t0, activated(g0)
        first = (t_b, -1)
        for k, level in enumerate(act):
            if (g1 - level) * (g0 - level) < 0.0:
                t_cross = t0 + (level - g0) / (g1 - g0) * (t_b - t0)
                first = min(first, (t_cross, k))
        return first

    state = {"m": -1, "th": 0.0, "thd": 0.0, "t": 0.0, "impacts": 0, "activated": False,
             "last_out": math.nan}

    def integrate(t0, t1, xg, stop_at_outward=False):
        """Move mechanism m from t0 to t1 under the ground acceleration xg(t); returns the
        terminal event."""
        m = state["m"]
        mech = mechs[m]

        def rhs(t, y):
            mm, ll, ff, pp = mech.coefficients(y[0])
            return [y[1], (sign[m] * pp * xg(t) - ff * GRAVITY - ll * y[1] ** 2) / mm]

        def impact(t, y):
            # the level sits a hair above theta_u: a start exactly at theta_u (after an impact
            # or an activation) must not count as an impact at once
            return y[0] - mech.theta_u - impact_offset
        impact.terminal, impact.direction = True, 1.0

        def limit(t, y):
            return y[0] - lo[m]
        limit.terminal, limit.direction = True, -1.0

        def critical(t, y):
            return y[0] - mech.theta_cr
        critical.terminal, critical.direction = stop_at_outward, -1.0

        y0 = [state["th"], state["thd"]]
        # start exactly at theta_u after an impact or activation: nudge the impact event
        sol = solve_ivp(rhs, (t0, t1), y0, method="DOP853", rtol=rtol, atol=atol,
                        events=(impact, limit, critical))
        if sol.t_events[2].size:
            state["last_out"] = float(sol.t_events[2][-1])
        state["t"] = float(sol.t[-1])
        state["th"], state["thd"] = float(sol.y[0, -1]), float(sol.y[1, -1])
        if sol.status == 1:
            if sol.t_events[0].size:
                state["t"] = float(sol.t_events[0][0])
                state["thd"] = float(sol.y_events[0][0][1])
                return "impact"
            if sol.t_events[1].size:
                return "limit"
            if sol.t_events[2].size:
                return "outward"
        return None

    def do_impact():
        m = state["m"]
        new_thd = -c_of[m] * state["thd"]
        state["impacts"] += 1
        state["m"] = 1 - m
        state["th"] = mechs[1 - m].theta_u
        state["thd"] = new_thd
        if abs(new_thd) < rest_velocity and activated(accel(state["t"])) != 1 - m:
            state["m"] = -1
            state["thd"] = 0.0

    breakpoints = list(np.unique(np.concatenate(([0.0], times))))
    # ---- during the excitation
    for t_a, t_b in zip(breakpoints[:-1], breakpoints[1:], strict=True):
        xg = ground_on(t_a, t_b)
        state["t"] = t_a
        for _ in range(MAX_EVENTS):
            if state["t"] >= t_b:
                break
            if state["m"] < 0:
                t_act, m_act = activation(state["t"], t_b, xg)
                if m_act < 0:
                    break
                state.update(m=m_act, th=mechs[m_act].theta_u, thd=0.0, activated=True,
                             t=t_act)
            event = integrate(state["t"], t_b, xg)
            if event == "impact":
                do_impact()
            elif event == "limit":
                return 2, state["impacts"] + 1, state["impacts"], state["last_out"]
        else:
            raise RuntimeError(f"more than {MAX_EVENTS} events in one pulse interval")
    # ---- decision after the excitation (energy, as in the engine)
    if state["m"] < 0:
        return (1 if state["activated"] else 0), 0, state["impacts"], math.nan
    m = state["m"]
    mech, other = mechs[m], mechs[1 - m]
    th, thd = state["th"], state["thd"]
    mm = mech.coefficients(th)[0]
    energy = 0.5 * mm * thd * thd + mech.potential_energy(th)
    v_cr = mech.potential_energy(mech.theta_cr)
    collapse_extra = None
    if th <= mech.theta_cr:
        if thd <= 0.0 or energy <= v_cr:
            return 2, state["impacts"] + 1, state["impacts"], state["last_out"]
    elif thd < 0.0 and energy > v_cr:
        collapse_extra = 0
    if collapse_extra is None:
        kinetic = energy - mech.potential_energy(mech.theta_u)
        m_u = mech.coefficients(mech.theta_u)[0]
        m_new = other.coefficients(other.theta_u)[0]
        kinetic_new = c_of[m] ** 2 * m_new / m_u * kinetic
        barrier = other.potential_energy(other.theta_cr) - other.potential_energy(other.theta_u)
        if kinetic_new > barrier:
            collapse_extra = 1
        else:  # back into this mechanism after the second impact, against its own barrier
            kinetic_back = c_of[1 - m] ** 2 * m_u / m_new * kinetic_new
            own = v_cr - mech.potential_energy(mech.theta_u)
            if kinetic_back <= own:
                return 1, 0, state["impacts"], math.nan
            collapse_extra = 2
    half_cycle = state["impacts"] + 1 + collapse_extra
    # ---- time of the point of no return: integrate the free motion to the outward crossing
    t = state["t"]
    for _ in range(10):
        event = integrate(t, t + 100.0, lambda _: 0.0, stop_at_outward=True)
        t = state["t"]
        if event == "impact":
            do_impact()
            continue
        break
    return 2, half_cycle, half_cycle - 1, state["last_out"]


def engine_case_arrays(table_l, table_r):
    return engine.pack_pair(table_l, table_r)


def _cases(rng, n, nominal_failure):
    durations = rng.uniform(0.2, 0.7, n)
    # amplitudes around the failure curve (in g): +-40 % of a rough failure acceleration
    amps = -nominal_failure(durations) * rng.uniform(0.6, 1.4, n)
    return durations, amps


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--analyses", type=int, default=600)
    parser.add_argument("--arches", type=int, default=6, help="irregular arches besides NA")
    parser.add_argument("--block", action="store_true", help="rocking-block stand-in instead")
    parser.add_argument("--restitution", type=float, default=0.875)
    args = parser.parse_args(argv)
    rng = np.random.default_rng(20240601)
    c = args.restitution

    if args.block:
        sys.path.insert(0, str(ROOT / "tests"))
        from rocking_block import block_pair
        pairs = [block_pair()]
        def failure(tp):
            return 0.36 + 0.12 / tp
    else:
        from archquake import FourLinkModel, irregular_arch, oppenheim
        nominal = oppenheim()
        arches = [nominal] + [irregular_arch(nominal, 0.1, rng=s) for s in range(args.arches)]
        pairs = [FourLinkModel.from_arch(a).mechanisms for a in arches]
        def failure(tp):
            return 0.37 + 0.05 / tp
    tables = [(engine.tabulate(a), engine.tabulate(b)) for a, b in pairs]
    per_arch = int(math.ceil(args.analyses / len(pairs)))
    # compile (excluded from the timing)
    engine.outcomes_grid(*tables[0], c, c, [0.3], [-GRAVITY])

    n_total = 0
    t_engine = t_engine_same = t_base = 0.0
    same_tol_mismatch = 0
    mismatches = []
    failed = []
    base_times = []
    same_status = 0
    for (ml, mr), (tl, tr) in zip(pairs, tables, strict=True):
        durations, amps_g = _cases(rng, per_arch, failure)
        t0 = time.perf_counter()
        res = engine.outcomes_grid(tl, tr, c, c, durations, amps_g * GRAVITY)
        t_engine += time.perf_counter() - t0
        t0 = time.perf_counter()
        same_tol = engine.outcomes_grid(tl, tr, c, c, durations, amps_g * GRAVITY, **BASELINE_TOL)
        t_engine_same += time.perf_counter() - t0
        same_tol_mismatch += int(np.sum(
            (same_tol["status"] != res["status"]) | (same_tol["half_cycle"] != res["half_cycle"])
            | (same_tol["impacts"] != res["impacts"])))
        for q in range(per_arch):
            motion = oppenheim_pulse(amps_g[q] * GRAVITY, durations[q])
            t0 = time.perf_counter()
            try:
                base = baseline_outcome(ml, mr, c, c, motion)
            except RuntimeError:
                base = (-1, -1, -1, math.nan)  # the baseline chattered without end
            base_times.append(time.perf_counter() - t0)
            t_base += base_times[-1]
            if base[0] < 0:
                failed.append((durations[q], amps_g[q]))
                continue
            if (int(res["status"][q]), int(res["half_cycle"][q])) == base[:2]:
                same_status += 1
            eng = (int(res["status"][q]), int(res["half_cycle"][q]), int(res["impacts"][q]))
            if eng != base[:3]:
                mismatches.append((durations[q], amps_g[q], eng, base[:3]))
        n_total += per_arch
    # also time the engine per analysis on a larger grid for a steady figure
    tl, tr = tables[0]
    big_d, big_a = _cases(rng, 20000, failure)
    t0 = time.perf_counter()
    engine.outcomes_grid(tl, tr, c, c, big_d, big_a * GRAVITY)
    t_big = (time.perf_counter() - t0) / big_d.size
    t0 = time.perf_counter()
    engine.outcomes_grid(tl, tr, c, c, big_d, big_a * GRAVITY, **BASELINE_TOL)
    t_big_same = (time.perf_counter() - t0) / big_d.size

    per_engine = t_engine / n_total
    per_base = t_base / n_total
    print(f"model: {'rocking block' if args.block else 'Oppenheim arch + irregular arches'}, "
          f"{len(pairs)} arch(es), c = {c}")
    print(f"analyses compared           : {n_total}")
    finished = n_total - len(failed)
    print(f"identical (status, half cycle, impacts), baseline finished: "
          f"{finished - len(mismatches)} / {finished}")
    print(f"identical (status, half cycle), baseline finished: {same_status} / "
          f"{n_total - len(failed)}; baseline did not finish: {len(failed)}")
    for d, a, e, b in mismatches:
        print(f"  mismatch t_p = {d:.4f} s, a = {a:+.4f} g: engine {e}, solve_ivp {b}")
    median_base = float(np.median(base_times))
    print(f"solve_ivp (DOP853, Python)  : {per_base * 1e3:9.3f} ms per analysis "
          f"(median {median_base * 1e3:.3f} ms)")
    per_same = t_engine_same / n_total
    print(f"engine (outcomes_grid), its default rtol {engine.DEFAULT_RTOL:g}: "
          f"{per_engine * 1e6:6.2f} us per analysis ({t_big * 1e6:.2f} us on a grid of "
          f"{big_d.size}) -> {per_base / per_engine:5.0f} x "
          f"({per_base / t_big:.0f} x on the large grid)")
    print(f"engine at the baseline's rtol {BASELINE_TOL['rtol']:g}: "
          f"{per_same * 1e6:6.2f} us per analysis ({t_big_same * 1e6:.2f} us on the large grid) "
          f"-> {per_base / per_same:5.0f} x ({per_base / t_big_same:.0f} x on the large grid); "
          f"outcomes different from the default tolerance: {same_tol_mismatch} / {n_total}")
    print(f"median baseline / mean engine: {median_base / per_engine:.0f} x (default), "
          f"{median_base / per_same:.0f} x (same tolerance)")

if __name__ == "__main__":
    main()
