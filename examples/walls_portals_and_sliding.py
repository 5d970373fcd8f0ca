"""
Walls, portals and sliding
==========================

A portal and a wall drawn in CAD, analysed with Coulomb friction at their joints.

Run:  ``python examples/walls_portals_and_sliding.py [--quick] [--out DIR]``

Draws a portal (two piers of four courses, 0.5 m x 2 m, 1.2 m apart, under a lintel 0.3 m deep)
and a wall in running bond (six courses of eight blocks 0.4 m x 0.2 m) as DXF drawings, reads
them back as block assemblies and prints, both ways, the collapse multiplier k without sliding
and with friction 0.2 under the associative and the non-associative law, with the interfaces
that rock and slide; then Oppenheim's arch with friction 0.35 beside the paper's k. Writes the
portal's and the wall's mechanisms with friction to DIR/walls_portals_and_sliding.png.
"""

import argparse
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from archquake import oppenheim  # noqa: E402
from archquake.geometry import read_dxf, write_dxf  # noqa: E402
from archquake.geometry.assembly import portal, wall  # noqa: E402
from archquake.limit_analysis import assembly_limits  # noqa: E402
from archquake.plotting import plot_assembly_limit  # noqa: E402
from archquake.reference_arches import paper_values  # noqa: E402

FRICTION = 0.2
ARCH_FRICTION = 0.35  # Oppenheim's arch cannot stand with 0.2 (its springings slide)


def report(name, structure):
    """Print both directions under every law; the non-associative +x result."""
    laws = {"no sliding": assembly_limits(structure)}
    laws.update({"with friction": assembly_limits(structure, friction=FRICTION)})
    for direction in ("+x", "-x"):
        for results in laws.values():
            for law, r in results[direction].items():
                print(f"{name:<10} {direction:<3} {law:<16} {r.load_multiplier:7.4f} "
                      f"{r.tilt:7.2f}  rock {r.interfaces_that('rocks') or '-'}, "
                      f"slide {r.interfaces_that('slides') or '-'}"
                      + ("" if r.converged else " (not converged)"))
    return laws["with friction"]["+x"]["non-associative"]


def main(argv=None):
    parser = argparse.ArgumentParser(description="Walls, portals and sliding.")
    parser.add_argument("--quick", action="store_true", help="(no effect: already fast)")
    parser.add_argument("--out", default=".", help="directory of the drawings and the figure")
    args = parser.parse_args(argv)
    out = Path(args.out)

    drawings = {"portal": portal(0.5, 2.0, 1.2, 0.3, pier_courses=4),
                "wall": wall(6, 8, 0.4, 0.2)}
    print(f"{'structure':<10} {'dir':<3} {'law':<16} {'k [-]':>7} {'tilt':>7}  interfaces")
    shown = []
    for name, assembly in drawings.items():
        path = out / f"{name}.dxf"
        write_dxf(assembly, path)
        shown.append(report(name, read_dxf(path)))
    paper = paper_values()["table1"]["NA"]["load_multiplier"]
    arch = assembly_limits(oppenheim(), friction=ARCH_FRICTION)["+x"]["non-associative"]
    print(f"Oppenheim's arch with friction {ARCH_FRICTION:g}: k = {arch.load_multiplier:.4f} "
          f"(paper, Table 1, without sliding: {paper:.2f}); sliding at joint(s) "
          f"{arch.interfaces_that('slides')}")

    fig, axes = plt.subplots(1, 2, figsize=(13, 5), constrained_layout=True)
    for ax, result in zip(axes, shown, strict=True):
        plot_assembly_limit(result, ax)
    path = out / "walls_portals_and_sliding.png"
    fig.savefig(path, dpi=110)
    print(f"figure written to {path}")


if __name__ == "__main__":
    main()
