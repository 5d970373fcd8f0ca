"""Arches of several rings: k against arc_error (one ring against the chain program), k by
rings, bond and ring friction for Oppenheim's arch, and the cost of three rings of 20 voussoirs;
with ``--rigid-blocks``, the rigid-block model's failure acceleration of two rings under
Oppenheim's pulse against arc_error, with its cost and the steps left to Lemke's algorithm.

    python benchmarks/ring_arches.py [--quick] [--rigid-blocks]

The tables of the user guide's page "Bridges: several rings". ``--quick`` skips the
non-associative iterations (about a minute of the two); ``--rigid-blocks`` takes a few minutes.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT / "src")]

from archquake.geometry import circular_arch, multi_ring  # noqa: E402
from archquake.limit_analysis import load_multipliers  # noqa: E402
from archquake.limit_analysis.assembly import assembly_limit  # noqa: E402

ALPHA = math.radians(157.5)


def convergence() -> None:
    k_chain = load_multipliers(circular_arch(10.0, ALPHA, 1.5, 7), "static")[0]
    print(f"one ring of Oppenheim's arch against the chain program (k = {k_chain:.6f})")
    print(f"{'arc_error [mm]':>15} {'vertices/block':>15} {'k [-]':>10} {'k - chain':>10}")
    for e in (1.5e-2, 1.5e-3, 1.5e-4, 1.5e-5):
        arch = multi_ring(10.0, ALPHA, 1.5, rings=1, voussoirs=7, arc_error=e)
        k = assembly_limit(arch).load_multiplier
        print(f"{e * 1e3:15.3g} {len(arch.polygons[0]):15d} {k:10.6f} {k - k_chain:10.2e}")


def by_friction(quick: bool) -> None:
    print("\nOppenheim's arch, 7 voussoirs per ring: k associative / non-associative "
          "(* not converged)")
    mus = (None, 0.8, 0.6, 0.4, 0.3)
    print(f"{'rings':<6}{'bond':<11}" + "".join(f"{'none' if m is None else m:>18}"
                                                  for m in mus))
    for rings, bond in ((2, "aligned"), (2, "staggered"), (3, "aligned"), (3, "staggered")):
        row = []
        for mu in mus:
            arch = multi_ring(10.0, ALPHA, 1.5, rings=rings, voussoirs=7, bond=bond,
                              ring_friction=mu)
            k = assembly_limit(arch).load_multiplier
            text = f"{k:.4f}"
            if mu is not None and not quick:
                r = assembly_limit(arch, law="non-associative")
                text += f"/{r.load_multiplier:.4f}{'' if r.converged else '*'}"
            row.append(text)
        print(f"{rings:<6}{bond:<11}" + "".join(f"{t:>18}" for t in row))


def cost(quick: bool) -> None:
    print("\nthree staggered rings of 20 voussoirs, ring friction 0.5")
    for e in (None, 1.5e-4):
        t0 = time.perf_counter()
        arch = multi_ring(10.0, ALPHA, 1.5, rings=3, voussoirs=20, bond="staggered",
                          ring_friction=0.5, arc_error=e)
        t1 = time.perf_counter()
        k = assembly_limit(arch).load_multiplier
        t2 = time.perf_counter()
        text = (f"arc_error {'default' if e is None else f'{e * 1e3:g} mm'}: "
                f"{arch.n_blocks} blocks, {arch.interfaces.n_interfaces} interfaces, built in "
                f"{t1 - t0:.2f} s; associative k = {k:.4f} in {t2 - t1:.3f} s")
        if not quick:
            r = assembly_limit(arch, law="non-associative")
            text += (f"; non-associative {r.load_multiplier:.4f} in {time.perf_counter() - t2:.1f}"
                     f" s ({r.iterations} programs, converged: {r.converged})")
        print(text)


def rigid_blocks() -> None:
    """The failure acceleration of two aligned rings of Oppenheim's arch (friction 0.8 at
    every joint) under Oppenheim's pulse, by bisection to 0.01 g, against arc_error: with the
    ring interfaces as arcs (the default, one curved joint a pair of voussoirs) and as their
    chords (``from_block_assembly(arcs=False)``), side by side."""
    from archquake.constants import GRAVITY
    from archquake.ground_motion import oppenheim_pulse
    from archquake.rigid_blocks import BlockSettings, RigidBlockModel, from_block_assembly

    durations = (0.2, 0.5)
    print("\ntwo aligned rings of Oppenheim's arch, friction 0.8 at every joint: the rigid-block "
          "failure acceleration [g] under Oppenheim's pulse (bisection to 0.01 g), the ring "
          "interfaces as arcs and as chords")
    print(f"{'arc_error/t':>12} {'interfaces':>10} {'joints':>6}" + "".join(
        f"{f't_p = {tp:g} s':>14} {'Lemke/steps':>13} {'time [s]':>9}" for tp in durations))
    for fraction in (0.05, 0.02, 0.01, 0.005, 0.002, 0.001):
        arch = multi_ring(10.0, ALPHA, 1.5, rings=2, voussoirs=7, arc_error=fraction * 1.5)
        for arcs in (True, False):
            assembly = from_block_assembly(arch, arcs=arcs)
            model = RigidBlockModel(assembly, BlockSettings(friction=0.8))
            row = (f"{fraction:12g} {arch.interfaces.n_interfaces:10d} "
                   f"{assembly.n_joints:6d}")
            for tp in durations:
                lo, hi, lemke, steps = 0.2, 1.5, 0, 0
                t0 = time.perf_counter()
                while hi - lo > 0.01:
                    mid = 0.5 * (lo + hi)
                    outcome = model.outcome(oppenheim_pulse(-mid * GRAVITY, tp))
                    lemke, steps = lemke + outcome.fallback_steps, steps + outcome.steps
                    lo, hi = (lo, mid) if outcome.collapsed else (mid, hi)
                row += (f"{0.5 * (lo + hi):14.3f} {f'{lemke}/{steps}':>13} "
                        f"{time.perf_counter() - t0:9.1f}")
            print(row + ("  arcs" if arcs else "  chords"), flush=True)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true",
                        help="the associative program only")
    parser.add_argument("--rigid-blocks", action="store_true",
                        help="also the rigid-block failure acceleration against arc_error")
    args = parser.parse_args(argv)
    convergence()
    by_friction(args.quick)
    cost(args.quick)
    if args.rigid_blocks:
        rigid_blocks()
    return 0


if __name__ == "__main__":
    sys.exit(main())
