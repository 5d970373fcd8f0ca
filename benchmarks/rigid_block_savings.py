"""Where the steps of a rigid-block analysis of Oppenheim's pulse go, and what the skips at rest
save: the time per analysis with them and without, side by side.

    python benchmarks/rigid_block_savings.py [--repeat 3] [--step-g 0.02] [--durations 0.4,...]

Over the paper's grid of Oppenheim's pulse [Sect. 5.3.3] on the paper's arch (Oppenheim's, 7
voussoirs, 1 ms steps, coarse steps of 2 ms): t_p = 0.4-0.7 s x 0.20-0.80 g (by ``--step-g``),
every pulse analysed by ``block_outcome`` with the skips at rest (``BlockSettings()``, the
default: :func:`archquake.rigid_blocks.solver.steady_steps`) and without them
(``skip_rest=False``, every step taken), interleaved, ``--repeat`` times each; the median of each
[ms], their ratio, whether the outcomes (status, collapse and decision times, steps) are the
same, and the steps solved (one contact problem each) by phase
(:func:`archquake.rigid_blocks.dynamics.outcome_with_phases`): ``still`` during the pulse before
the arch moves, ``pulse`` during the pulse after that, ``free`` after the pulse while the arch
moves, ``window`` the window of rest that decides. Then the bound on any earlier decision of
the recoveries: the steps and time per analysis if every recovery were decided at the end of the
pulse (its ``free`` and ``window`` steps not solved), and every collapse as well, at the
measured time per step solved.
JIT compilation excluded; one core.

``--records [SUITE]`` times the skips under records instead: every ``--every``-th record of a
built-in suite (default ``fema-p695-far-field``, every 4th) scaled to the PGA ``--levels``
(default 0.3, 0.45, 0.7, 1.0, 1.5 g) on the same arch, with the skips (at rest under a
constant piece, after the excitation, and under the varying record:
:func:`archquake.rigid_blocks.solver.held_steps`) and without, interleaved: the mean time per
analysis [ms], the ratio, the steps solved, and whether the outcomes (status, collapse and
decision times, steps) are the same. A record whose outcome differs is run again without the
skips under the record scaled by 1 + 1e-15, 1 - 1e-15, 1 + 1e-14 and 1 - 1e-14 (round-offs of
the input): where that changes its outcome too, the rocking is chaotic and the difference is
round-off amplified, not the skip's.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))

from archquake import oppenheim  # noqa: E402
from archquake.geometry import GRAVITY  # noqa: E402
from archquake.ground_motion import oppenheim_pulse  # noqa: E402
from archquake.rigid_blocks import BlockSettings, block_outcome  # noqa: E402
from archquake.rigid_blocks.dynamics import PHASES, outcome_with_phases  # noqa: E402

SKIP, FULL = BlockSettings(), BlockSettings(skip_rest=False)
ROUND_OFF_FACTORS = (1e-15, -1e-15, 1e-14, -1e-14)


def timed(arch, motion, settings) -> float:
    start = time.perf_counter()
    block_outcome(arch, motion, settings)
    return time.perf_counter() - start


def same(a, b) -> bool:
    return (a.status == b.status and a.decision_time == b.decision_time and a.steps == b.steps
            and (a.collapse_time == b.collapse_time
                 or (np.isnan(a.collapse_time) and np.isnan(b.collapse_time))))


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--step-g", type=float, default=0.02)
    parser.add_argument("--durations", default="0.4,0.5,0.6,0.7")
    parser.add_argument("--records", nargs="?", const="fema-p695-far-field", default=None)
    parser.add_argument("--levels", default="0.3,0.45,0.7,1.0,1.5")
    parser.add_argument("--every", type=int, default=4)
    args = parser.parse_args(argv)
    if args.records:
        return records(args)
    arch = oppenheim()
    durations = [float(x) for x in args.durations.split(",")]
    amplitudes = np.round(np.arange(0.2, 0.8 + 1e-9, args.step_g), 10)
    for settings in (SKIP, FULL):  # JIT (cached after the first run)
        block_outcome(arch, oppenheim_pulse(-0.5 * GRAVITY, 0.5), settings)

    print(f"Oppenheim's arch, Oppenheim's pulse, t_p = {args.durations} s x "
          f"{amplitudes[0]:g}-{amplitudes[-1]:g} g by {args.step_g:g} g, median of "
          f"{args.repeat} interleaved runs [ms per analysis]")
    print(f"  {'t_p':>4} {'n':>3} {'skips':>7} {'none':>7} {'ratio':>6} {'same':>5}   "
          + " ".join(f"{p:>7}" for p in PHASES) + "   (steps solved per analysis, with the "
          "skips | without)")
    rows = []
    for tp in durations:
        per = []
        for a in amplitudes:
            motion = oppenheim_pulse(-a * GRAVITY, tp)
            with_skip, phases = outcome_with_phases(arch, motion, SKIP)
            without, every = outcome_with_phases(arch, motion, FULL)
            t_skip, t_full = [], []
            for _ in range(args.repeat):  # interleaved
                t_skip.append(timed(arch, motion, SKIP))
                t_full.append(timed(arch, motion, FULL))
            per.append({"tp": tp, "a": a, "status": with_skip.status.label,
                        "skip": statistics.median(t_skip), "full": statistics.median(t_full),
                        "same": same(with_skip, without),
                        "phases": np.array([phases[p] for p in PHASES]),
                        "every": np.array([every[p] for p in PHASES])})
        rows += per
        skip = np.mean([r["skip"] for r in per])
        full = np.mean([r["full"] for r in per])
        phases = np.mean([r["phases"] for r in per], axis=0)
        every = np.mean([r["every"] for r in per], axis=0)
        print(f"  {tp:>4g} {len(per):>3} {1e3 * skip:>7.2f} {1e3 * full:>7.2f} "
              f"{full / skip:>6.2f} {sum(r['same'] for r in per):>5}   "
              + " ".join(f"{p:>7.0f}" for p in phases) + "  | "
              + " ".join(f"{p:.0f}" for p in every))
    skip = np.array([r["skip"] for r in rows])
    full = np.array([r["full"] for r in rows])
    phases = np.array([r["phases"] for r in rows])
    solved = phases.sum(axis=1)
    per_step = skip.sum() / solved.sum()
    counts = {s: sum(r["status"] == s for r in rows) for s in ("rest", "recovery", "collapse")}
    print(f"  all  {len(rows)} ({', '.join(f'{n} {s}' for s, n in counts.items())}): mean "
          f"{1e3 * skip.mean():.2f} ms with the skips, {1e3 * full.mean():.2f} ms without "
          f"(ratio of the sums {full.sum() / skip.sum():.2f}; medians {1e3 * np.median(skip):.2f}"
          f" and {1e3 * np.median(full):.2f} ms); outcomes the same in "
          f"{sum(r['same'] for r in rows)} of {len(rows)}")
    share = phases.sum(axis=0) / solved.sum()
    print("  steps solved by phase, share of all: "
          + ", ".join(f"{p} {100 * s:.1f} %" for p, s in zip(PHASES, share, strict=True))
          + f"; {1e6 * per_step:.2f} us per step solved")
    recovery = np.array([r["status"] == "recovery" for r in rows])
    ideal = solved - np.where(recovery, phases[:, 2] + phases[:, 3], 0)
    print(f"  bound on an earlier decision of the recoveries (each decided at the end of the "
          f"pulse): {ideal.mean():.0f} steps solved per analysis instead of "
          f"{solved.mean():.0f}, about {1e3 * per_step * ideal.mean():.2f} ms per analysis at "
          f"{1e6 * per_step:.2f} us per step; the pulse phase alone {phases[:, 1].mean():.0f} "
          f"steps, {1e3 * per_step * phases[:, 1].mean():.2f} ms")
    collapse = np.array([r["status"] == "collapse" for r in rows])
    both = ideal - np.where(collapse, phases[:, 2], 0)
    print(f"  and if every collapse were decided at the end of the pulse too (which would change "
          f"the collapse times that studies record): {both.mean():.0f} steps, about "
          f"{1e3 * per_step * both.mean():.2f} ms per analysis")
    return 0


def records(args) -> int:
    """The skips under records (``--records``)."""
    from archquake.ground_motion.fema_p695 import builtin_suite

    arch = oppenheim()
    levels = [float(x) for x in args.levels.split(",")]
    block_outcome(arch, builtin_suite(args.records, im="pga", level=0.5)[0].motion, SKIP)
    block_outcome(arch, builtin_suite(args.records, im="pga", level=0.5)[0].motion, FULL)
    print(f"Oppenheim's arch under every {args.every}th record of {args.records} scaled to PGA "
          f"{args.levels} g, median of {args.repeat} interleaved runs [ms per analysis]")
    print(f"  {'PGA g':>6} {'n':>3} {'skips':>8} {'none':>8} {'ratio':>6} {'same':>5} "
          f"{'solved (skips | none)':>24}")
    total_skip = total_full = 0.0
    count = same_count = 0
    differing = []
    for level in levels:
        suite = builtin_suite(args.records, im="pga", level=level)[::args.every]
        t_skip = t_full = 0.0
        solved_skip = solved_full = same_here = 0
        for rec in suite:
            motion = rec.motion
            a, phases = outcome_with_phases(arch, motion, SKIP)
            b, every = outcome_with_phases(arch, motion, FULL)
            ts, tf = [], []
            for _ in range(args.repeat):
                ts.append(timed(arch, motion, SKIP))
                tf.append(timed(arch, motion, FULL))
            t_skip += statistics.median(ts)
            t_full += statistics.median(tf)
            solved_skip += sum(phases.values())
            solved_full += sum(every.values())
            if same(a, b):
                same_here += 1
            else:
                differing.append((level, rec.name, motion, a, b))
        n = len(suite)
        print(f"  {level:>6g} {n:>3} {1e3 * t_skip / n:>8.2f} {1e3 * t_full / n:>8.2f} "
              f"{t_full / t_skip:>6.2f} {same_here:>5} {solved_skip / n:>11.0f} | "
              f"{solved_full / n:.0f}")
        total_skip += t_skip
        total_full += t_full
        count += n
        same_count += same_here
    print(f"  all {count}: mean {1e3 * total_skip / count:.2f} ms with the skips, "
          f"{1e3 * total_full / count:.2f} ms without (ratio {total_full / total_skip:.2f}); "
          f"outcomes the same in {same_count} of {count}")
    for level, name, motion, a, b in differing:
        perturbed = [block_outcome(arch, motion.scaled(1.0 + f), FULL)
                     for f in ROUND_OFF_FACTORS]
        why = ("chaotic: round-off decides" if any(not same(b, c) for c in perturbed)
               else "not explained by round-off")
        print(f"  differs: {name} at {level:g} g: {a.status.label} at {a.decision_time:.3f} s "
              f"with the skips, {b.status.label} at {b.decision_time:.3f} s without; without "
              f"and under the record scaled by 1 + " + ", ".join(f"{f:g}" for f in
                                                              ROUND_OFF_FACTORS) + ": "
              + ", ".join(f"{c.status.label} at {c.decision_time:.3f} s" for c in perturbed)
              + f" ({why})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
