"""A three-span bridge of two-ring arches under fill: the cost of its limit analysis and of its
rigid-block model, against the same bridge without fill, interleaved.

    python benchmarks/bridge.py [--repeats 5] [--window 0.05] [--full]

The bridge: three semicircular arches of mean radius 5 m and thickness 0.6 m, each two rings
in staggered bond (8 voussoirs in the intrados ring, 7 and two halves in the extrados one, one
chord per face or two where a joint of the other ring meets it), on end piers 1.5 m wide and
middle piers 2 m wide, 4 m high, of three courses: 63 blocks. Fill 0.5 m over the crowns,
1800 kg/m^3; ring interfaces with friction 0.6, the others do not slide.

- limit analysis: ``assembly_limit`` in both directions (associative), median of the repeats;
- rigid blocks: ``simulate_blocks`` under a sine pulse of 0.03 g and 0.5 s for the first
  ``--window`` seconds (per-step cost, JIT excluded), median of the repeats, and the filled
  bridge with its contact problems in the blocks' velocities against the impulses
  (``BlockSettings.unknowns``); with ``--full``,
  also one whole pulse analysis (``block_outcome``, to its decided outcome) of the filled bridge.

The fill adds no unknowns to either model (it rides on its blocks), so the ratios measure that
it costs nothing; the absolute figures are those of the user guide's page "Bridges".

Measured (2 shared cores, ``--repeats 1``; its rings are one chord a face, so the rigid blocks'
arcs change nothing here): limit analysis 0.075 s filled, 0.067 s bare (ratio 1.12; k = 0.0583 and
0.0499); rigid blocks 98.7 ms a step filled, 28.9 ms bare (ratio 3.4, 61 steps); the filled
bridge's contact problems in the blocks' velocities (its default) 107 ms a step with 7 steps solved
by Lemke's algorithm, in the impulses 185 ms and 14 (ratio 1.72). The whole pulse analysis of the
filled bridge (``--full``): rest after 720 steps, 81 s (203 s before the velocities; 384 of its
steps by Lemke's algorithm, where the active-set method cycles). The limit analysis is well within
0.2 s; the rigid blocks are far from 1 s: the steps that fall back to Lemke's dense tableau
dominate.
"""

from __future__ import annotations

import argparse
import math
import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))

from archquake.geometry import GRAVITY, Fill, Pier, multi_ring  # noqa: E402
from archquake.geometry.bridge import multi_span  # noqa: E402
from archquake.ground_motion import sine_pulse  # noqa: E402
from archquake.limit_analysis import assembly_limit  # noqa: E402
from archquake.rigid_blocks import (  # noqa: E402
    BlockSettings,
    block_outcome,
    from_block_assembly,
    simulate_blocks,
)


def bridge(fill: bool):
    """The benchmark's bridge, with or without its fill."""
    ring = multi_ring(5.0, math.pi, 0.6, rings=2, voussoirs=8, bond="staggered",
                      arc_error=0.5, ring_friction=0.6)
    return multi_span(ring, 3, end_piers=(Pier(1.5, 4.0, 3),) * 2,
                      middle_pier=Pier(2.0, 4.0, 3),
                      fill=Fill(0.5, 1800.0) if fill else None)


def timed(function) -> tuple[float, object]:
    start = time.perf_counter()
    out = function()
    return time.perf_counter() - start, out


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--window", type=float, default=0.05,
                        help="time simulated under the pulse per repeat [s]")
    parser.add_argument("--full", action="store_true",
                        help="also one whole pulse analysis of the filled bridge")
    args = parser.parse_args(argv)
    filled, bare = bridge(True), bridge(False)
    print(f"{filled.n_blocks} blocks, {filled.interfaces.n_interfaces} interfaces, fill "
          f"{filled.fill_weight / 1e3:.1f} kN/m on {filled.carriers.size} blocks")
    limit = {"filled": [], "bare": []}
    for _ in range(args.repeats):  # interleaved
        for name, b in (("filled", filled), ("bare", bare)):
            limit[name].append(timed(lambda b=b: [assembly_limit(b, d) for d in ("+x", "-x")]))
    k = {name: min(r.load_multiplier for r in runs[0][1]) for name, runs in limit.items()}
    t = {name: statistics.median(x for x, _ in runs) for name, runs in limit.items()}
    print(f"limit analysis, both directions: filled {t['filled']:.3f} s (k = {k['filled']:.4f})"
          f", bare {t['bare']:.3f} s (k = {k['bare']:.4f}); ratio {t['filled'] / t['bare']:.2f}")
    blocks = {"filled": from_block_assembly(filled), "bare": from_block_assembly(bare)}
    pulse = sine_pulse(0.03 * GRAVITY, 0.5)
    for b in blocks.values():  # compile
        simulate_blocks(b, pulse, t_end=0.002, record_every=10**6)
    steps, rate = {}, {"filled": [], "bare": []}
    for _ in range(args.repeats):
        for name, b in blocks.items():
            dt, h = timed(lambda b=b: simulate_blocks(b, pulse, t_end=args.window,
                                                      record_every=10**6))
            rate[name].append(dt / h.outcome.steps)
            steps[name] = h.outcome.steps
    r = {name: statistics.median(v) for name, v in rate.items()}
    print(f"rigid blocks, {args.window:g} s of the pulse ({steps['filled']} steps): filled "
          f"{1e3 * r['filled']:.1f} ms/step, bare {1e3 * r['bare']:.1f} ms/step; ratio "
          f"{r['filled'] / r['bare']:.2f}")
    impulses = BlockSettings(unknowns="impulses")
    runs = {}
    for _ in range(args.repeats):  # the filled bridge's contact problems in either unknowns
        for name, settings in (("velocities", None), ("impulses", impulses)):
            dt, h = timed(lambda s=settings: simulate_blocks(
                blocks["filled"], pulse, s, t_end=args.window, record_every=10**6))
            runs.setdefault(name, []).append((dt / h.outcome.steps, h.outcome.fallback_steps))
    cost = {name: statistics.median(x for x, _ in v) for name, v in runs.items()}
    print(f"filled, the contact problems in the blocks' velocities (the default here) "
          f"{1e3 * cost['velocities']:.1f} ms/step, {runs['velocities'][0][1]} steps by "
          f"Lemke's algorithm; in the impulses {1e3 * cost['impulses']:.1f} ms/step, "
          f"{runs['impulses'][0][1]}; ratio {cost['impulses'] / cost['velocities']:.2f}")
    if args.full:
        dt, outcome = timed(lambda: block_outcome(blocks["filled"], pulse))
        print(f"whole pulse analysis of the filled bridge: {outcome.status.label} after "
              f"{outcome.steps} steps, {dt:.1f} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
