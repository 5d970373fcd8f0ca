"""Speed of the rigid-block model, beside LMGC90 and beside the four-link model's answers.

    python benchmarks/rigid_blocks_speed.py [--repeat 5] [--workers 2] [--lmgc90-python PY]
                                            [--lmgc90-runs 3] [--no-curve] [--no-four-link]
                                            [--no-sweep]

1. One analysis of Oppenheim's arch under Oppenheim's pulse (-0.5 g, t_p = 0.5 s): 4.5 s of
   motion at a 1 ms step, recorded (``simulate_blocks(t_end=4.5)``), and the outcome alone
   (``block_outcome``, which stops when the collapse is certain); then a recovery that is
   decided only after about 5 s (-0.6 g, t_p = 0.3 s). Median wall time of ``--repeat`` runs,
   JIT compilation excluded.
2. The cost of one analysis as the studies pay it (``block_outcome`` in-process, JIT excluded):
   Oppenheim's pulse t_p = 0.4 s, -0.6 g (a collapse, certain at about 2.6 s), median of
   ``--repeat`` runs; and a sweep of 78 pulses, t_p = 0.2 .. 0.7 s by 0.1 s x 0.3 .. 1.5 g by
   0.1 g (rest, recovery and collapse), once each: mean and median time per analysis.
3. The same 4.5 s in LMGC90 (3D, the compas_lmgc90 wheel: voussoirs as 1 m deep prisms with
   flat intrados and extrados between the joint corners, two support blocks driven with the
   ground velocity, IQS_CLB friction 0.8, theta = 1/2, 1 ms) when an interpreter that has it
   is given (``--lmgc90-python``) or this one has it; it is not a dependency of archquake.
   A separate environment works:
       python -m venv lmgc && lmgc/bin/pip install --no-deps compas_lmgc90
       lmgc/bin/pip install "compas>=2" numpy
   Without it the reference figure stated for this analysis (a median of 15 s) is printed as
   stated, not measured.
4. The failure curve of Oppenheim's arch at t_p = 0.2 .. 0.7 s (scan 0.10 .. 3.00 g by 0.05 g,
   boundaries bisected to 0.005 g) on ``--workers`` processes, beside the four-link model's
   failure accelerations with the computed and the paper's restitution (0.001 g).
"""

from __future__ import annotations

import argparse
import importlib.util
import json
import math
import statistics
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))

from archquake import oppenheim  # noqa: E402
from archquake.geometry import GRAVITY, CircularArch  # noqa: E402
from archquake.ground_motion import oppenheim_pulse  # noqa: E402
from archquake.rigid_blocks import (  # noqa: E402
    BlockSettings,
    RigidBlockModel,  # noqa: E402
    block_outcome,
    simulate_blocks,
)
from archquake.studies.failure_domain import domain_of  # noqa: E402

STATED_LMGC90_SECONDS = 15.0
"""The reference time stated for this analysis in LMGC90 on this machine (median) [s]."""

DURATIONS = (0.2, 0.3, 0.4, 0.5, 0.6, 0.7)
SWEEP_DURATIONS = np.round(np.arange(0.2, 0.71, 0.1), 10)
SWEEP_AMPLITUDES_G = np.round(np.arange(0.3, 1.51, 0.1), 10)
SIMULATED = 4.5
TIME_STEP = 1e-3

LMGC90_RUNNER = r'''
import json, sys, time
import numpy as np
from compas_lmgc90.solver import Solver
spec = json.loads(sys.stdin.read())
depth = spec["depth"]

def prism(quad):
    n = len(quad)
    vertices = [[x, 0.0, z] for x, z in quad] + [[x, depth, z] for x, z in quad]
    faces = [list(range(n)), list(range(2 * n - 1, n - 1, -1))]
    faces += [[i, n + i, n + (i + 1) % n, (i + 1) % n] for i in range(n)]
    return {"vertices": vertices, "faces": faces}

solver = Solver(dt=spec["dt"], theta=0.5, density=spec["density"])
solver.geometry_from_v_f([prism(q) for q in spec["blocks"] + spec["supports"]])
nb = len(spec["blocks"])
table = np.vstack((spec["velocity_times"], spec["velocity"]))
for k in range(len(spec["supports"])):
    solver.apply_velocity(nb + k, "Vx", table)
    for component in ("Vy", "Vz", "Rx", "Ry", "Rz"):
        solver.apply_velocity(nb + k, component, 0.0)
solver.contact_law("IQS_CLB", spec["friction"], alert=spec["alert"])
solver.preprocess()
crown = spec["crown"]
z0 = float(np.array(solver.init_coor[crown])[2])
start = time.perf_counter()
drops = []
for _ in range(spec["steps"] // spec["every"]):
    solver.run(nb_steps=spec["every"])
    drops.append(z0 - float(np.array(solver.last_result.bodies[crown])[2]))
print(json.dumps({"seconds": time.perf_counter() - start, "crown_drop": drops}))
'''


def _median_time(function, repeat: int) -> tuple[float, object]:
    times, result = [], None
    for _ in range(repeat):
        start = time.perf_counter()
        result = function()
        times.append(time.perf_counter() - start)
    return statistics.median(times), result


def _ccw(quad) -> list[list[float]]:
    q = np.asarray(quad, dtype=float)
    area = 0.5 * np.sum(q[:, 0] * np.roll(q[:, 1], -1) - np.roll(q[:, 0], -1) * q[:, 1])
    return (q if area > 0 else q[::-1]).tolist()


def lmgc90_spec(arch: CircularArch, amplitude: float, duration: float) -> dict:
    """The analysis for LMGC90: voussoirs between their joint corners, support blocks behind
    the springing joints, both supports driven with the ground velocity [SI units]."""
    inner, outer = arch.joint_extents()
    beta = arch.joint_angles
    p_in, p_out = CircularArch.point(inner, beta), CircularArch.point(outer, beta)
    blocks = [_ccw([p_in[i + 1], p_in[i], p_out[i], p_out[i + 1]])
              for i in range(arch.n_voussoirs)]
    supports = []
    for j, sign in ((0, 1.0), (arch.n_voussoirs, -1.0)):
        into_arch = sign * np.array([math.sin(beta[j]), math.cos(beta[j])])
        supports.append(_ccw([p_in[j], p_out[j], p_out[j] - 1.5 * into_arch,
                              p_in[j] - 1.5 * into_arch]))
    # ground velocity of Oppenheim's pulse: a for t_p, -a/2 for 2 t_p (zero net velocity)
    return {"blocks": blocks, "supports": supports, "depth": 1.0, "dt": TIME_STEP,
            "density": arch.density, "velocity_times": [0.0, duration, 3 * duration,
                                                        SIMULATED + 1.0],
            "velocity": [0.0, amplitude * duration, 0.0, 0.0], "friction": 0.8,
            "alert": 1e-2, "crown": arch.n_voussoirs // 2,
            "steps": int(round(SIMULATED / TIME_STEP)), "every": 100}


def lmgc90_python(option: str | None) -> str | None:
    if option:
        return option
    return sys.executable if importlib.util.find_spec("compas_lmgc90") else None


def run_lmgc90(python: str, spec: dict) -> dict:
    out = subprocess.run([python, "-c", LMGC90_RUNNER], input=json.dumps(spec),
                         capture_output=True, text=True, check=True, timeout=600)
    return json.loads(out.stdout.strip().splitlines()[-1])


def per_analysis(arch, repeat: int, sweep: bool = True) -> None:
    """Print the time of one analysis (t_p = 0.4 s, -0.6 g) and of a sweep of pulses."""
    pulse = oppenheim_pulse(-0.6 * GRAVITY, 0.4)
    one, outcome = _median_time(lambda: block_outcome(arch, pulse), repeat)
    print(f"  -0.6 g, t_p = 0.4 s, outcome only ({outcome.status}, certain at "
          f"{outcome.decision_time:.3f} s, {outcome.steps} steps of h): {1e3 * one:7.2f} ms per "
          f"analysis  ({1e6 * one / outcome.steps:.2f} us per step of h)")
    uniform = BlockSettings(coarse_factor=1)
    every, same = _median_time(lambda: block_outcome(arch, pulse, uniform), repeat)
    print(f"  same, every step at h (coarse_factor 1; {same.status}, certain at "
          f"{same.decision_time:.3f} s): {1e3 * every:7.2f} ms per analysis; the default's "
          f"coarse steps {every / one:.2f}x faster")
    if not sweep:
        return
    times, counts = [], {}
    for tp in SWEEP_DURATIONS:
        for a in SWEEP_AMPLITUDES_G:
            motion = oppenheim_pulse(-a * GRAVITY, float(tp))
            start = time.perf_counter()
            result = block_outcome(arch, motion)
            times.append(time.perf_counter() - start)
            counts[result.status.label] = counts.get(result.status.label, 0) + 1
    times = np.array(times)
    print(f"  sweep t_p = {SWEEP_DURATIONS[0]:g} .. {SWEEP_DURATIONS[-1]:g} s x "
          f"{SWEEP_AMPLITUDES_G[0]:g} .. {SWEEP_AMPLITUDES_G[-1]:g} g ({times.size} analyses: "
          + ", ".join(f"{n} {k}" for k, n in sorted(counts.items()))
          + f"): mean {1e3 * times.mean():.2f} ms, median {1e3 * np.median(times):.2f} ms per "
          f"analysis")


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--lmgc90-python", default=None, metavar="PY",
                        help="an interpreter with compas_lmgc90 installed")
    parser.add_argument("--lmgc90-runs", type=int, default=3)
    parser.add_argument("--no-curve", action="store_true", help="skip the failure curve")
    parser.add_argument("--no-four-link", action="store_true",
                        help="skip the four-link failure accelerations")
    parser.add_argument("--no-sweep", action="store_true",
                        help="skip the sweep of 78 pulses")
    args = parser.parse_args(argv)

    arch = oppenheim()
    amplitude, duration = -0.5 * GRAVITY, 0.5
    pulse = oppenheim_pulse(amplitude, duration)
    block_outcome(arch, pulse)  # JIT (cached after the first run)
    simulate_blocks(arch, pulse, t_end=0.01)

    print("Rigid-block model of Oppenheim's arch (7 voussoirs, 16 contacts), 1 ms step, one core")
    recorded, history = _median_time(
        lambda: simulate_blocks(arch, pulse, t_end=SIMULATED), args.repeat)
    steps = history.times.size
    print(f"  -0.5 g, t_p = 0.5 s, {SIMULATED:g} s recorded ({steps} steps): "
          f"{1e3 * recorded:7.1f} ms  ({1e6 * recorded / steps:.1f} us per step; outcome "
          f"{history.outcome.status}, certain at t = {history.outcome.collapse_time:.3f} s)")
    alone, outcome = _median_time(lambda: block_outcome(arch, pulse), args.repeat)
    print(f"  same, outcome only (stops when certain, {outcome.steps} steps): "
          f"{1e3 * alone:7.1f} ms")
    slow_pulse = oppenheim_pulse(-0.6 * GRAVITY, 0.3)
    slow, slow_outcome = _median_time(lambda: block_outcome(arch, slow_pulse), args.repeat)
    print(f"  -0.6 g, t_p = 0.3 s, outcome only ({slow_outcome.status} decided at "
          f"{slow_outcome.decision_time:.2f} s, {slow_outcome.steps} steps): "
          f"{1e3 * slow:7.1f} ms  (target <= 150 ms)")

    per_analysis(arch, args.repeat, sweep=not args.no_sweep)

    python = lmgc90_python(args.lmgc90_python)
    if python is None:
        print(f"  LMGC90: compas_lmgc90 is not installed here (see --lmgc90-python); the "
              f"reference stated for this analysis is {STATED_LMGC90_SECONDS:g} s (median, "
              f"stated, not measured): {STATED_LMGC90_SECONDS / recorded:,.0f} x the recorded "
              "run above")
    else:
        spec = lmgc90_spec(arch, amplitude, duration)
        runs = [run_lmgc90(python, spec) for _ in range(args.lmgc90_runs)]
        seconds = statistics.median(r["seconds"] for r in runs)
        drops = np.array(runs[0]["crown_drop"])
        times = spec["every"] * TIME_STEP * np.arange(1, drops.size + 1)
        ours = np.interp(times, history.times, history.crown_drop)
        print(f"  LMGC90 (3D, compas_lmgc90), same {SIMULATED:g} s, median of {len(runs)}: "
              f"{seconds:.2f} s = {seconds / recorded:,.0f} x the rigid-block model")
        print("    crown drop [m]   t [s]: " + "  ".join(f"{t:5.1f}" for t in times[4::5]))
        print("                   LMGC90: " + "  ".join(f"{d:5.2f}" for d in drops[4::5]))
        print("              rigid block: " + "  ".join(f"{d:5.2f}" for d in ours[4::5]))

    if args.no_curve:
        return 0
    print(f"\nFailure curve of Oppenheim's arch, t_p = {', '.join(map(str, DURATIONS))} s "
          f"(0.10 .. 3.00 g by 0.05 g, bisected to 0.005 g), {args.workers} workers:")
    from archquake.rigid_blocks.model import warm_up

    warm_up()
    start = time.perf_counter()
    curve = domain_of(RigidBlockModel(arch), DURATIONS, np.round(np.arange(0.10, 3.001, 0.05), 12),
                      resolution_g=0.005, extend_to_g=None, workers=args.workers)
    elapsed = time.perf_counter() - start
    print(f"  {elapsed:.1f} s wall (target <= 120 s), including starting the workers")
    four_link = {}
    if not args.no_four_link:
        from archquake import FourLinkModel
        from archquake.studies.failure_domain import inclusive_range

        for restitution in ("computed", "paper"):
            domain = domain_of(FourLinkModel.from_arch(arch, restitution),
                DURATIONS, inclusive_range(0.3, 3.0, 0.01), resolution_g=1e-3, extend_to_g=None)
            four_link[restitution] = domain.failure_accelerations_g
    print(f"  {'t_p [s]':>8} {'rigid blocks [g]':>17} {'recovery above':>16}"
          + "".join(f" {'four-link ' + r + ' [g]':>24}" for r in four_link))
    bands = [curve.slice(tp).recovery_above_g for tp in curve.durations]
    for i, tp in enumerate(curve.durations):
        blocks = curve.failure_accelerations_g[i]
        text = "-" if not bands[i] else ", ".join(f"{a:.3f}-{b:.3f}" for a, b in bands[i])
        row = f"  {tp:>8.2f} {blocks:>17.3f} {text:>16}"
        for values in four_link.values():
            other = values[i]
            ratio = "" if math.isnan(other) or math.isnan(blocks) else (
                f" ({100 * (other / blocks - 1):+.1f} %)")
            row += f" {other:>14.3f}{ratio:>10}"
        print(row)
    print("  (nan: no collapse up to 3 g; the percentage is four-link vs rigid blocks, as "
          "archquake compare prints it)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
