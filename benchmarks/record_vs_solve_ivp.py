"""Record analyses: the compiled engine against a straightforward scipy implementation.

    python benchmarks/record_vs_solve_ivp.py [--arches 3] [--records 5] [--levels 10]
                                             [--workers 2]

The same analyses (default 3 arches x 5 records x 10 PGA levels x 2 polarities = 300) of 20-s
synthetic records sampled at 0.01 s (the suite of ``benchmarks/record_fragility.py``) are run by

- the engine: one compiled call per arch and record over all its levels and polarities
  (:func:`archquake.fourlink.engine.outcomes_grid`, every analysis integrated; and, as the study
  runs it, :func:`archquake.studies.record_fragility.record_outcomes`, which does not integrate
  analyses whose record never reaches the activation acceleration);
- the baseline of ``benchmarks/engine_vs_solve_ivp.py``: ``solve_ivp(method="DOP853")`` with a
  Python right-hand side from the mechanism's exact coefficients, one call per interval between
  two samples of the record, the same decision rules once the record is over. The baseline runs
  on ``--workers`` processes at once; its time is the sum of its analyses' times.

The baseline runs at the engine's accuracy (``rtol = 1e-11``, ``atol = 1e-14``, impact events
located 1e-14 rad from theta_u): between two bursts of shaking an arch often comes to rest
through a geometric sequence of ever smaller rocking cycles, whose last ones are ~1e-12 rad
wide, and at the pulse benchmark's ``rtol = 1e-9, atol = 1e-12`` the baseline counts one or two
impacts more in such a tail (the last impact speeds are off by 20 %), which shifts the half
cycle of a later collapse.

Printed: how many outcomes (status, half cycle, impacts) agree, and the time per analysis of each,
with the ratio (target: identical outcomes, >= 100 x). Times are CPU times (``time.process_time``),
so that other work on the machine does not distort the ratio.
"""

from __future__ import annotations

import argparse
import importlib.util
import multiprocessing
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "src"))

from archquake import (  # noqa: E402
    GRAVITY,
    FourLinkModel,  # noqa: E402
    oppenheim,
)
from archquake.fourlink.engine import outcomes_grid  # noqa: E402
from archquake.geometry import irregular_sample  # noqa: E402
from archquake.ground_motion import stochastic_suite  # noqa: E402
from archquake.studies.record_fragility import (  # noqa: E402
    STOCHASTIC_SUITE,
    record_outcomes,
    warm_up,
)

BASELINE = {"rtol": 1e-11, "atol": 1e-14, "impact_offset": 1e-14}
"""Tolerances of the baseline (module docstring)."""
SUITE = STOCHASTIC_SUITE


def _baseline_module():
    spec = importlib.util.spec_from_file_location("engine_vs_solve_ivp",
                                                  ROOT / "benchmarks" / "engine_vs_solve_ivp.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _arches(n: int):
    nominal = oppenheim()
    return [nominal] + irregular_sample(nominal, 0.10, n - 1, 0)


def _cases(args):
    """Every (arch index, record index, signed scale factor)."""
    suite = stochastic_suite(args.records, seed=0, **SUITE)
    levels = np.linspace(0.4, 2.2, args.levels)  # pga [g]
    cases = []
    for a in range(args.arches):
        for r, motion in enumerate(suite):
            factors = levels / (motion.peak / GRAVITY)
            for f in factors:
                cases += [(a, r, f), (a, r, -f)]
    return suite, cases


def _baseline_chunk(job):
    """Baseline outcomes and times of a list of cases, in a worker process."""
    args, cases = job
    baseline = _baseline_module()
    suite, _ = _cases(args)
    arches = _arches(args.arches)
    dynamics = [FourLinkModel.from_arch(arch, "nominal", arches[0]) for arch in arches]
    pairs = [d.mechanisms for d in dynamics]
    coefficients = [d.restitution for d in dynamics]
    out = []
    for a, r, f in cases:
        motion = suite[r].scaled(f) if f > 0 else suite[r].reversed().scaled(-f)
        t0 = time.process_time()
        try:
            res = baseline.baseline_outcome(*pairs[a], *coefficients[a], motion,
                                            **BASELINE)[:3]
        except RuntimeError:
            res = (-1, -1, -1)
        out.append((res, time.process_time() - t0))
    return out


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--arches", type=int, default=3)
    parser.add_argument("--records", type=int, default=5)
    parser.add_argument("--levels", type=int, default=10)
    parser.add_argument("--workers", type=int, default=2)
    args = parser.parse_args(argv)
    suite, cases = _cases(args)
    arches = _arches(args.arches)
    warm_up()
    dynamics = [FourLinkModel.from_arch(arch, "nominal", arches[0]) for arch in arches]

    # ---- engine: one compiled call per arch and record
    engine_out = {}
    t_engine = t_study = 0.0
    for repeat in range(3):  # best of three
        t_all = t_skip = 0.0
        for a, dyn in enumerate(dynamics):
            for r, motion in enumerate(suite):
                signed = np.array([f for (ca, cr, f) in cases if ca == a and cr == r])
                t0 = time.process_time()
                res = outcomes_grid(*dyn.tables, *dyn.restitution, np.ones(signed.size),
                                    signed, motion)
                t_all += time.process_time() - t0
                t0 = time.process_time()
                record_outcomes(dyn, motion, signed)
                t_skip += time.process_time() - t0
                for q, f in enumerate(signed):
                    engine_out[(a, r, f)] = (int(res["status"][q]), int(res["half_cycle"][q]),
                                             int(res["impacts"][q]))
        t_engine = t_all if repeat == 0 else min(t_engine, t_all)
        t_study = t_skip if repeat == 0 else min(t_study, t_skip)

    # ---- baseline: the cases dealt round-robin to the workers
    jobs = [(args, cases[k::args.workers]) for k in range(args.workers)]
    t0 = time.perf_counter()
    with multiprocessing.get_context("spawn").Pool(args.workers) as pool:
        results = pool.map(_baseline_chunk, jobs)
    wall = time.perf_counter() - t0
    base = {}
    t_base = 0.0
    for (_, part), res in zip(jobs, results, strict=True):
        for case, (outcome, seconds) in zip(part, res, strict=True):
            base[case] = outcome
            t_base += seconds

    n = len(cases)
    finished = [c for c in cases if base[c][0] >= 0]
    same = sum(engine_out[c] == tuple(base[c]) for c in finished)
    same_outcome = sum(engine_out[c][:2] == tuple(base[c][:2]) for c in finished)
    same_status = sum(engine_out[c][0] == base[c][0] for c in finished)
    statuses = np.bincount([engine_out[c][0] for c in cases], minlength=3)
    print(f"analyses: {n} ({args.arches} arches x {args.records} records of "
          f"{suite[0].duration:g} s at {suite[0].times[1]:g} s x {args.levels} PGA levels x 2 "
          f"polarities); engine outcomes: {statuses[0]} rest, {statuses[1]} recovery, "
          f"{statuses[2]} collapse")
    print(f"identical (status, half cycle, impacts): {same} / {len(finished)}; (status, half "
          f"cycle): {same_outcome} / {len(finished)}; status: {same_status} / "
          f"{len(finished)}; baseline did not finish: {n - len(finished)}")
    for c in finished:
        if engine_out[c] != tuple(base[c]):
            print(f"  differs: arch {c[0]}, record {c[1]}, factor {c[2]:+.4f}: engine "
                  f"{engine_out[c]}, solve_ivp {tuple(base[c])}")
    per_base, per_engine, per_study = t_base / n, t_engine / n, t_study / n
    print(f"solve_ivp (DOP853, Python, rtol {BASELINE['rtol']:g}, atol {BASELINE['atol']:g}): "
          f"{per_base * 1e3:9.1f} ms per analysis "
          f"({wall:.0f} s wall on {args.workers} processes)")
    print(f"engine, every analysis integrated: {per_engine * 1e3:9.3f} ms per analysis -> "
          f"{per_base / per_engine:6.0f} x")
    print(f"engine as the study runs it      : {per_study * 1e3:9.3f} ms per analysis -> "
          f"{per_base / per_study:6.0f} x (analyses below activation not integrated)")


if __name__ == "__main__":
    main()
