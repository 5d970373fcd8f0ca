"""
Ground motions beside the paper's pulse
=======================================

Ricker, cycloidal and Mavroeidis-Papageorgiou pulses and a stochastic record, their intensity
measures and the response of Oppenheim's arch.

Run:  ``python examples/ground_motions.py [--quick] [--out DIR]``

The paper analyses Oppenheim's pulse only; its conclusion asks for other excitations. Every motion
here is built from the registry, needs no file, and is scaled to a peak ground acceleration of
0.6 g (the paper's pulse is shown at its own -1 g); the script prints PGA, PGV and Sa(0.5 s) and
the outcome for Oppenheim's arch, and plots the accelerations to DIR/ground_motions.png.
"""

import argparse
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from archquake import GRAVITY, FourLinkModel, oppenheim  # noqa: E402
from archquake.ground_motion import ground_motion, intensity_measures, scale_to_im  # noqa: E402
from archquake.plotting import plot_ground_motion  # noqa: E402


def motions(quick: bool):
    a = -0.6 * GRAVITY
    stochastic = ground_motion("stochastic", seed=0, significant_duration=6.0 if quick else 17.0,
                               midpoint_time=4.0 if quick else 12.0)
    return [
        ("the paper's pulse", ground_motion("oppenheim", -GRAVITY, 0.27)),
        ("Ricker", ground_motion("ricker", a, 0.5)),
        ("antisymmetric Ricker", ground_motion("ricker-antisymmetric", a, 0.5)),
        ("cycloidal A", ground_motion("cycloidal-a", a, 0.5)),
        ("cycloidal B", ground_motion("cycloidal-b", a, 0.5)),
        ("cycloidal C2", ground_motion("cycloidal-c", a, 0.5, n=2)),
        ("Mavroeidis-Papageorgiou", ground_motion("mavroeidis-papageorgiou", a, 0.5, gamma=2.5,
                                                  phase=1.0)),
        ("stochastic", scale_to_im(stochastic, "pga", 0.6)),
    ]


def main(argv=None):
    parser = argparse.ArgumentParser(
        description="Ground motions beside the paper's pulse, their IMs and the arch's outcome.")
    parser.add_argument("--quick", action="store_true", help="a shorter stochastic record")
    parser.add_argument("--out", default=".", help="directory of the figure")
    args = parser.parse_args(argv)

    dynamics = FourLinkModel.from_arch(oppenheim())  # computed restitution (the default)
    cases = motions(args.quick)
    fig, axes = plt.subplots(4, 2, figsize=(12, 10), constrained_layout=True)
    print(f"{'motion':26s} {'PGA [g]':>8s} {'PGV [m/s]':>10s} {'Sa(0.5) [g]':>12s}  outcome")
    for ax, (label, motion) in zip(axes.ravel(), cases, strict=True):
        ims = intensity_measures(motion, "pga,pgv,sa(0.5)")
        outcome = dynamics.outcome(motion)
        print(f"{label:26s} {ims['pga']:8.3f} {ims['pgv']:10.3f} {ims['sa(0.5)']:12.3f}  "
              f"{outcome.status}")
        plot_ground_motion(motion, ax, label=f"{label}: {outcome.status}")
    path = Path(args.out) / "ground_motions.png"
    fig.savefig(path, dpi=100)
    print(f"figure written to {path}")


if __name__ == "__main__":
    main()
