"""
Limit analysis of Oppenheim's arch
==================================

Table 1 and Figs. 2 and 4 of the paper.

Run:  ``python examples/limit_analysis_of_oppenheim_arch.py [--quick] [--out DIR]``

Prints the horizontal load multiplier k and the hinges A, B, C, D beside the paper's values and
writes the collapse state (hinges and thrust line) of the nominal arch and of one irregular arch
(epsilon = 0.10) to DIR/limit_analysis.png.
"""

import argparse
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from archquake import irregular_arch, oppenheim  # noqa: E402
from archquake.limit_analysis import both_directions  # noqa: E402
from archquake.plotting import plot_limit_analysis  # noqa: E402
from archquake.reference_arches import paper_values  # noqa: E402


def main(argv=None):
    parser = argparse.ArgumentParser(
        description="Limit analysis of Oppenheim's arch (Table 1, Figs. 2 and 4 of the paper).")
    parser.add_argument("--quick", action="store_true", help="(no effect: already fast)")
    parser.add_argument("--out", default=".", help="directory of the figure")
    args = parser.parse_args(argv)

    paper = paper_values()["table1"]["NA"]
    nominal = oppenheim()
    la_l, la_r = both_directions(nominal)
    print(f"k_l = {la_l.load_multiplier:.4f}, k_r = {la_r.load_multiplier:.4f} "
          f"(paper: {paper['load_multiplier']:.4f})")
    for label, hinge, beta, ref in zip("ABCD", la_l.hinges, la_l.hinge_angles, paper["beta"],
                                       strict=True):
        print(f"hinge {label}: joint {hinge.joint} {hinge.face:<9} beta = {beta:.4f} rad "
              f"(paper: {ref:.4f})")

    rough = irregular_arch(nominal, epsilon=0.10, rng=2024)
    rough_l, _ = both_directions(rough)
    fig, axes = plt.subplots(1, 2, figsize=(13, 5), constrained_layout=True)
    plot_limit_analysis(la_l, axes[0])
    axes[0].set_title(f"Oppenheim's arch (Fig. 2): k = {la_l.load_multiplier:.4f}")
    plot_limit_analysis(rough_l, axes[1], nominal=nominal)
    axes[1].set_title(f"irregular arch, epsilon = 0.10 (Fig. 4): k~_l = "
                      f"{rough_l.load_multiplier:.4f}")
    path = Path(args.out) / "limit_analysis.png"
    fig.savefig(path, dpi=110)
    print(f"figure written to {path}")


if __name__ == "__main__":
    main()
