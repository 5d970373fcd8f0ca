"""
Both models on an arch on piers
===============================

Oppenheim's arch on piers 3 m wide and 6 m high, under Oppenheim's pulse: its collapse
mechanism runs through a pier, and the two dynamic models of the package part further than on
fixed springings.

Run:  ``python examples/failure_curves_on_piers.py [--quick] [--out DIR]``

Prints the limit analysis (k and the hinges, one of them at a pier's outer toe), the failure
acceleration per pulse duration by the rigid-block model and by the four-link model with the
paper's c_v and the computed one (the paper's link rule does not apply: the pier and the first
voussoir are at rest before the impact, so it gives c_v = 0), beside the same numbers on fixed
springings; and writes DIR/failure_curves_on_piers.png: the mechanism through the pier, the
failure domain of the four-link model with the rigid blocks' failure curve and, hatched, where
the two disagree.
"""

import argparse
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from archquake import model_for, oppenheim  # noqa: E402
from archquake.geometry import arch_on_piers  # noqa: E402
from archquake.limit_analysis import both_directions  # noqa: E402
from archquake.plotting import (  # noqa: E402
    plot_disagreement,
    plot_failure_domain,
    plot_limit_analysis,
)
from archquake.reference_arches import paper_values  # noqa: E402
from archquake.studies.comparison import domain_disagreement  # noqa: E402
from archquake.studies.failure_domain import domain_of, inclusive_range  # noqa: E402

WIDTH, HEIGHT = 3.0, 6.0  # the piers [m]


def failure_curves(structure, durations, grid, resolution_g):
    """The failure domains of both models (the four-link model with the paper's c_v, and the
    computed one) and of the rigid blocks, on one scan."""
    four_link = {c: domain_of(model_for(structure, restitution=c), durations, grid,
                              resolution_g=resolution_g, extend_to_g=None)
                 for c in ("paper", "computed")}
    rigid = domain_of(model_for(structure, "rigid-blocks"), durations, grid,
                      resolution_g=resolution_g, extend_to_g=None)
    return four_link, rigid


def main(argv=None):
    parser = argparse.ArgumentParser(description="Both models on Oppenheim's arch on piers.")
    parser.add_argument("--quick", action="store_true", help="three durations, 0.02 g")
    parser.add_argument("--out", default=".", help="directory of the figure")
    args = parser.parse_args(argv)
    durations = [0.3, 0.5, 0.7] if args.quick else [0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 1.0]
    resolution_g = 0.02 if args.quick else 0.005
    grid = inclusive_range(0.05, 1.2, 0.05)

    paper = paper_values()["table1"]["NA"]["load_multiplier"]
    fixed = oppenheim()
    structure = arch_on_piers(fixed, WIDTH, HEIGHT)
    mech_l = both_directions(structure)[0]
    print(f"Oppenheim's arch (paper, Table 1: k = {paper:.2f}) on piers {WIDTH:g} m x "
          f"{HEIGHT:g} m: k = {mech_l.load_multiplier:.4f}, hinges at "
          + ", ".join(structure.joint_name(h.joint) for h in mech_l.hinges))
    rows = {}
    for name, s in (("on piers", structure), ("fixed springings", fixed)):
        rows[name] = failure_curves(s, durations, grid, resolution_g)
    print(f"{'t_p [s]':>7}  {'':<17}{'rigid blocks':>13} {'four-link paper':>16} "
          f"{'four-link computed':>19}  [g]")
    for name, (four_link, rigid) in rows.items():
        for i, tp in enumerate(durations):
            cells = [rigid.failure_accelerations_g[i],
                     four_link["paper"].failure_accelerations_g[i],
                     four_link["computed"].failure_accelerations_g[i]]
            text = [f"{c:.3f}" if c == c else f"> {grid[-1]:g}" for c in cells]  # nan: none
            print(f"{tp:>7.2f}  {name:<17}" + "".join(f"{c:>{w}}" for c, w in
                                                        zip(text, (13, 17, 20), strict=True)))

    four_link, rigid = rows["on piers"]
    fig, (left, right) = plt.subplots(1, 2, figsize=(14, 5.4), constrained_layout=True)
    plot_limit_analysis(mech_l, left)
    left.set_title(f"Mech-l on piers {WIDTH:g} m x {HEIGHT:g} m: k = "
                   f"{mech_l.load_multiplier:.3f} (fixed springings: {paper:.2f})")
    plot_failure_domain(four_link["paper"], right)
    right.plot(rigid.durations, rigid.failure_accelerations_g, "-s", color="tab:red",
               markersize=4, label="rigid-block model: failure curve")
    plot_disagreement(domain_disagreement(four_link["paper"], rigid), right)
    right.set_title("On piers: the four-link model (shaded, paper's c$_v$) and the rigid "
                    "blocks (red)", fontsize=10)
    path = Path(args.out) / "failure_curves_on_piers.png"
    fig.savefig(path, dpi=100)
    print(f"figure written to {path}")


if __name__ == "__main__":
    main()
