"""
Response to Oppenheim's pulse
=============================

Oppenheim's arch under Oppenheim's pulse at -1 g: Fig. 15 of the paper.

Run:  ``python examples/pulse_response.py [--quick] [--out DIR] [--restitution C_V]``

For t_p = 0.44, 0.27 and 0.20 s the paper finds: collapse in the first half cycle, collapse in
the second half cycle after one impact, and recovery (with c_v = 0.875). The script prints our
outcomes and writes the three time histories to DIR/pulse_response.png.
"""

import argparse
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from archquake import GRAVITY, FourLinkModel, oppenheim  # noqa: E402
from archquake.ground_motion import oppenheim_pulse  # noqa: E402
from archquake.plotting import plot_pulse_response  # noqa: E402
from archquake.reference_arches import paper_values  # noqa: E402


def main(argv=None):
    parser = argparse.ArgumentParser(
        description="Oppenheim's arch under Oppenheim's pulse at -1 g (Fig. 15 of the paper).")
    parser.add_argument("--quick", action="store_true", help="shorter records")
    parser.add_argument("--out", default=".", help="directory of the figure")
    parser.add_argument("--restitution", type=float, default=0.875,
                        help="coefficient of restitution c_v (default: the paper's 0.875)")
    args = parser.parse_args(argv)

    dynamics = FourLinkModel.from_arch(oppenheim(), args.restitution)
    cases = paper_values()["dynamics"]["NA"]["pulse_cases"]
    fig, axes = plt.subplots(1, len(cases), figsize=(16, 5.5), constrained_layout=True)
    for ax, (duration, amplitude, status, half_cycle) in zip(axes, cases, strict=True):
        motion = oppenheim_pulse(amplitude * GRAVITY, duration)
        history = dynamics.simulate(motion, t_end=2.0 if args.quick else 3.5)
        out = history.outcome
        print(f"t_p = {duration:.2f} s: {out.status} (half cycle {out.half_cycle}); "
              f"paper: {status} (half cycle {half_cycle})")
        label = f"NA, t_p = {duration:.2f} s, c_v = {args.restitution:g}: {out.status}"
        plot_pulse_response(history, ax, labels=[label], phi_limit=0.3)
    path = Path(args.out) / "pulse_response.png"
    fig.savefig(path, dpi=110)
    print(f"figure written to {path}")


if __name__ == "__main__":
    main()
