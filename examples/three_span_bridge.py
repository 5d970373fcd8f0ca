"""
A three-span bridge under fill, and an arch of two rings
========================================================

Oppenheim's arch three times in a row on four piers 3 m wide and 6 m high, under 0.5 m of fill
(1600 kg/m^3) that runs across the piers; then the same arch in two rings of brickwork.

Run:  ``python examples/three_span_bridge.py [--quick] [--out DIR]``

Prints the horizontal load multiplier k of the single arch (the paper's 0.37 on fixed
springings), of the single arch on its piers under the fill (the chain program) and of the
bridge (the program of its block assembly; one span of it is the single arch to 1e-12), the
spans that move and the weight of the fill; runs the rigid-block model of the bridge under two
sine pulses of 0.5 s (below and above k: the blocks stay at rest, then rock and recover); and
the multiplier of the arch in two rings, aligned and staggered, whose interfaces slide at
friction 0.6. Writes the bridge's mechanism with its fill columns, the rigid blocks at their
largest opening and the mechanism of the two rings to DIR/three_span_bridge.png.
"""

import argparse
import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from archquake import oppenheim  # noqa: E402
from archquake.geometry import GRAVITY, Fill, Pier, arch_on_piers, multi_ring  # noqa: E402
from archquake.geometry.bridge import moving_blocks, multi_span, spans_of  # noqa: E402
from archquake.ground_motion import sine_pulse  # noqa: E402
from archquake.limit_analysis import assembly_limit, load_multipliers  # noqa: E402
from archquake.plotting import plot_assembly_limit  # noqa: E402
from archquake.reference_arches import paper_values  # noqa: E402
from archquake.rigid_blocks import from_block_assembly, simulate_blocks  # noqa: E402
from archquake.rigid_blocks.plotting import plot_blocks  # noqa: E402

PIER = Pier(3.0, 6.0)  # every pier: 3 m wide, 6 m high [m]
FILL = Fill(0.5, 1600.0)  # 0.5 m over the crowns, 1600 kg/m^3, moving with its blocks


def main(argv=None):
    parser = argparse.ArgumentParser(description="A three-span bridge under fill.")
    parser.add_argument("--quick", action="store_true", help="(no effect: already fast)")
    parser.add_argument("--out", default=".", help="directory of the figure")
    args = parser.parse_args(argv)

    arch = oppenheim()
    paper = paper_values()["table1"]["NA"]["load_multiplier"]
    single = min(load_multipliers(arch_on_piers(arch, PIER.width, PIER.height, fill=FILL)))
    bridge = multi_span(arch, 3, end_piers=(PIER, PIER), middle_pier=PIER, fill=FILL)
    results = {d: assembly_limit(bridge, d) for d in ("+x", "-x")}
    k = min(r.load_multiplier for r in results.values())
    print(f"Oppenheim's arch on fixed springings: k = {min(load_multipliers(arch)):.4f} "
          f"(paper, Table 1: {paper:.2f})")
    print(f"on piers {PIER.width:g} m x {PIER.height:g} m under {FILL.cover:g} m of fill: "
          f"k = {single:.4f} (chain program)")
    print(f"three spans on four piers under the same fill ({bridge.n_blocks} blocks, fill "
          f"{bridge.fill_weight / 1e3:.0f} kN/m over the spans and the two middle piers):")
    for d, r in results.items():
        print(f"  load {d}: k = {r.load_multiplier:.4f}, spans that move: "
              f"{spans_of(bridge, moving_blocks(r))}")

    blocks = from_block_assembly(bridge)  # the fill rides on its blocks as mass
    histories = {}
    for factor in (0.5, 2.5):
        pulse = sine_pulse(factor * k * GRAVITY, 0.5)
        histories[factor] = simulate_blocks(blocks, pulse, record_every=10)
        o = histories[factor].outcome
        print(f"rigid blocks, sine pulse {factor * k:.3f} g, 0.5 s: {o.status.label} "
              f"(largest rotation {o.max_rotation:.2e} rad, {o.steps} steps)")

    rings = {}
    for bond in ("aligned", "staggered"):
        two = multi_ring(10.0, math.radians(157.5), 1.5, rings=2, voussoirs=7, bond=bond,
                         ring_friction=0.6)
        rings[bond] = assembly_limit(two)
        print(f"Oppenheim's arch in two {bond} rings, ring friction 0.6: k = "
              f"{rings[bond].load_multiplier:.4f}")

    fig, axes = plt.subplots(3, 1, figsize=(12, 12), constrained_layout=True)
    plot_assembly_limit(results["+x"], axes[0])
    for outline in bridge.outlines:
        axes[0].fill(outline[:, 0], outline[:, 1], color="tan", alpha=0.35, linewidth=0)
    axes[0].set_title(f"three spans under fill, load toward +x: k = "
                      f"{results['+x'].load_multiplier:.4f} (one span on its piers: "
                      f"{single:.4f})")
    history = histories[2.5]
    moment = float(history.times[int(history.openings.max(axis=1).argmax())])
    plot_blocks(history, moment, axes[1])
    axes[1].set_title(f"rigid blocks at their largest opening (t = {moment:.2f} s), pulse "
                      f"{2.5 * k:.3f} g")
    plot_assembly_limit(rings["staggered"], axes[2])
    axes[2].set_title(f"two staggered rings sliding at friction 0.6: k = "
                      f"{rings['staggered'].load_multiplier:.4f}")
    path = Path(args.out) / "three_span_bridge.png"
    fig.savefig(path, dpi=100)
    print(f"figure written to {path}")


if __name__ == "__main__":
    main()
