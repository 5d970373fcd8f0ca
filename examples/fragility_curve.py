"""
Fragility curve of irregular arches
===================================

Irregular Oppenheim's arches under Oppenheim's pulse of t_p = 0.40 s: Fig. 17 of the paper.

Run:  ``python examples/fragility_curve.py [--quick] [--out DIR]``

h irregular arches (epsilon = 0.10; paper: h = 40) are hit by Oppenheim's pulse of increasing
amplitude (steps of 0.01 g) in both directions; P_F = h_f / h (eq. 9) is compared with the
nominal arch's failure acceleration (the paper's point Q, 0.49 g) and with the cumulative
distribution of the limit-analysis multiplier k~ of s arches (paper: s = 1000).
"""

import argparse
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import numpy as np  # noqa: E402

from archquake import FourLinkModel, Status, oppenheim  # noqa: E402
from archquake.geometry import irregular_sample  # noqa: E402
from archquake.limit_analysis import limit_sample  # noqa: E402
from archquake.plotting import plot_load_multiplier_cdf  # noqa: E402
from archquake.studies.fits import fit_lognormal, probability_of_failure  # noqa: E402

DURATION = 0.40  # t_p [s]
RESTITUTION = 0.875  # the paper's c_v


def failures(arch, amplitudes):
    """Whether ``arch`` collapses under the pulse of each amplitude [g], in either direction."""
    dynamics = FourLinkModel.from_arch(arch, RESTITUTION)
    failed = np.zeros(amplitudes.size, dtype=bool)
    for sign in (-1.0, 1.0):
        res = dynamics.outcomes(DURATION, sign * amplitudes)  # one compiled call
        failed |= res["status"] == Status.COLLAPSE
    return failed


def main(argv=None):
    parser = argparse.ArgumentParser(
        description="Fragility of irregular arches at t_p = 0.40 s (Fig. 17 of the paper).")
    parser.add_argument("--quick", action="store_true", help="h = 6, s = 50, 0.02 g steps")
    parser.add_argument("--out", default=".", help="directory of the figure")
    args = parser.parse_args(argv)
    h, s, step = (6, 50, 0.02) if args.quick else (40, 1000, 0.01)

    amplitudes = np.round(np.arange(step, 1.0 + 1e-9, step), 10)
    arches = irregular_sample(oppenheim(), 0.10, h, seed=2024)
    p_f = probability_of_failure(np.array([failures(a, amplitudes) for a in arches]))
    nominal = failures(oppenheim(), amplitudes)
    q = amplitudes[np.argmax(nominal)]
    fit = fit_lognormal(amplitudes, h, np.round(p_f * h))
    print(f"nominal arch fails from {q:.2f} g (paper: 0.49 g); irregular arches: median "
          f"{fit.median:.3f} g, P_F below {q:.2f} g up to {p_f[amplitudes < q].max():.3f}")

    ax = plot_load_multiplier_cdf(limit_sample(oppenheim(), 0.10, s, seed=2024).load_multiplier,
                                  nominal_k=0.37)
    ax.plot(amplitudes, p_f, "o", color="black", markersize=3, label=f"$P_F$ (h = {h})")
    ax.plot(amplitudes, fit(amplitudes), "--", color="black", label="lognormal fit")
    ax.axvline(q, color="black", linestyle="-.", label=f"nominal arch fails at {q:.2f} g")
    ax.set_xlabel(r"pulse amplitude $|\ddot{x}_g|/g$ [-]")
    ax.set_title(f"Fragility at $t_p$ = {DURATION:.2f} s (Fig. 17)")
    ax.legend(loc="lower right", fontsize=8)
    path = Path(args.out) / "fragility_curve.png"
    ax.figure.savefig(path, dpi=110)
    print(f"figure written to {path}")


if __name__ == "__main__":
    main()
