"""
Arches on piers and with fill
=============================

Oppenheim's arch as it rarely stands: on piers instead of fixed springings, and under fill.

Run:  ``python examples/arches_on_piers_and_fill.py [--quick] [--out DIR]``

Prints the horizontal load multiplier k of Oppenheim's arch on fixed springings (the paper's
0.37), on piers 3 m wide and 6 m high (its collapse mechanism runs through a pier: the fourth
hinge is the right pier's outer toe), the narrowest piers 6 m high on which it stands, and
under 0.5 m of fill (1600 kg/m^3) with each model of the fill's inertia, with and without a
passive reaction (phi = 30 deg, a third of it mobilised); then the same fill over the arch on
piers. Writes the collapse mechanisms of the arch on piers and of the filled arch on piers to
DIR/piers_and_fill.png. Every number comes from the static method and is checked against the
kinematic one.
"""

import argparse
import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from archquake import oppenheim  # noqa: E402
from archquake.geometry import Fill, Structure, arch_on_piers  # noqa: E402
from archquake.limit_analysis import both_directions, min_pier_width  # noqa: E402
from archquake.plotting import plot_limit_analysis  # noqa: E402
from archquake.reference_arches import paper_values  # noqa: E402

WIDTH, HEIGHT = 3.0, 6.0  # the piers [m]
COVER, DENSITY = 0.5, 1600.0  # the fill [m], [kg/m^3]
PASSIVE = (math.radians(30.0), 0.33)  # friction angle [rad], mobilisation [-]


def collapse(structure):
    """Mech-l of ``structure`` by the static method, checked against the kinematic method."""
    static = both_directions(structure, "static")[0]
    kinematic = both_directions(structure, "kinematic")[0]
    assert abs(static.load_multiplier - kinematic.load_multiplier) < 1e-9
    return static


def hinges(result):
    return ", ".join(f"{h.joint}{h.face[0]}" for h in result.hinges)


def main(argv=None):
    parser = argparse.ArgumentParser(description="Oppenheim's arch on piers and with fill.")
    parser.add_argument("--quick", action="store_true", help="(no effect: already fast)")
    parser.add_argument("--out", default=".", help="directory of the figure")
    args = parser.parse_args(argv)

    paper = paper_values()["table1"]["NA"]["load_multiplier"]
    arch = oppenheim()
    rows = [("fixed springings", collapse(arch))]
    on_piers = arch_on_piers(arch, WIDTH, HEIGHT)
    rows.append((f"piers {WIDTH:g} m x {HEIGHT:g} m", collapse(on_piers)))
    for inertia in ("none", "centroid", "extrados"):
        for passive in (None, PASSIVE):
            fill = Fill(COVER, DENSITY, inertia, *(passive or (None, None)))
            name = f"fill, inertia {inertia}" + (", passive" if passive else "")
            rows.append((name, collapse(Structure(arch, fill=fill))))
    bridge = arch_on_piers(arch, WIDTH, HEIGHT, fill=Fill(COVER, DENSITY))
    rows.append(("piers and fill (centroid)", collapse(bridge)))

    print(f"Oppenheim's arch (paper, Table 1: k = {paper:.2f})")
    print(f"{'structure':<34} {'k [-]':>7}  hinges (joint, face)")
    for name, result in rows:
        print(f"{name:<34} {result.load_multiplier:7.4f}  {hinges(result)}")
    width = min_pier_width(arch, HEIGHT)
    print(f"narrowest piers {HEIGHT:g} m high on which it stands: {width:.3f} m wide")

    fig, axes = plt.subplots(1, 2, figsize=(13, 5), constrained_layout=True)
    plot_limit_analysis(rows[1][1], axes[0])
    axes[0].set_title(f"on piers {WIDTH:g} m x {HEIGHT:g} m: k = "
                      f"{rows[1][1].load_multiplier:.4f} (fixed: {rows[0][1].load_multiplier:.2f})")
    plot_limit_analysis(rows[-1][1], axes[1])
    axes[1].set_title(f"on the same piers under {COVER:g} m of fill: k = "
                      f"{rows[-1][1].load_multiplier:.4f}")
    path = Path(args.out) / "piers_and_fill.png"
    fig.savefig(path, dpi=110)
    print(f"figure written to {path}")


if __name__ == "__main__":
    main()
