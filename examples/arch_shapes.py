"""
Arches of different shapes
==========================

Six arch shapes of the same span, thickness and voussoirs under Oppenheim's pulse: their
collapse load multiplier k, critical angle theta_cr, failure curve and fragility.

Run:  ``python examples/arch_shapes.py [--full] [--out DIR]``

The circular, elliptical, parabolic, catenary and three-centred arches have the span and rise
of Oppenheim's arch (19.6 m and 8.05 m, 1.5 m thick; here in 8 voussoirs); a pointed arch must
rise above half its span, so it is the equilateral one of the same span. For each shape: the
limit analysis (k = min(k_l, k_r)), the four-link mechanism (theta_cr / theta_u), the computed
coefficient of restitution, the failure curve (lowest collapsing amplitude of Oppenheim's pulse
against its duration) and the fragility at t_p = 0.40 s of irregular arches (epsilon = 0.10).
The default size is small, so that the documentation builds it quickly; ``--full`` runs the
study at full size (finer grids, 40 irregular arches a shape).
"""

import argparse
import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from archquake import FourLinkModel, Status, oppenheim  # noqa: E402
from archquake.geometry import SHAPES, irregular_sample, shaped_arch  # noqa: E402
from archquake.limit_analysis import both_directions  # noqa: E402
from archquake.plotting import plot_arch  # noqa: E402
from archquake.reference_arches import OPPENHEIM, paper_values  # noqa: E402
from archquake.studies.failure_domain import domain_of  # noqa: E402
from archquake.studies.fits import fit_lognormal, probability_of_failure  # noqa: E402

RADIUS, EMBRACE = OPPENHEIM["radius"], OPPENHEIM["embrace"]
SPAN = 2 * RADIUS * math.sin(EMBRACE / 2)  # Oppenheim's arch: 19.6 m
RISE = RADIUS * (1 - math.cos(EMBRACE / 2))  # 8.05 m
THICKNESS, VOUSSOIRS = OPPENHEIM["thickness"], 8
DURATION = 0.40  # t_p of the fragility curves [s]
RESTITUTION = "computed"  # each arch's own momentum balance at the impacts


def arch_of(shape):
    """The arch of a shape: Oppenheim's span and rise (the equilateral rise if pointed)."""
    rise = SPAN * math.sqrt(3) / 2 if shape == "pointed" else RISE
    return shaped_arch(shape, span=SPAN, rise=rise, thickness=THICKNESS, voussoirs=VOUSSOIRS)


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
        description="Six arch shapes of the same span: k, theta_cr, failure curve, fragility.")
    parser.add_argument("--full", action="store_true",
                        help="full size: 19 pulse durations, 0.01 g steps, 40 arches a shape")
    parser.add_argument("--quick", action="store_true",
                        help="the default small size (accepted for the documentation build)")
    parser.add_argument("--out", default=".", help="directory of the figure")
    args = parser.parse_args(argv)
    if args.full:
        durations, step, samples = np.round(np.arange(0.1, 1.0001, 0.05), 10), 0.01, 40
    else:
        durations, step, samples = np.array([0.2, 0.4, 0.7, 1.0]), 0.05, 6

    paper_k = paper_values()["table1"]["NA"]["load_multiplier"]
    k_oppenheim = min(r.load_multiplier for r in both_directions(oppenheim()))
    print(f"Oppenheim's arch (circular, 7 voussoirs): k = {k_oppenheim:.4f} (paper: {paper_k})")
    print(f"span {SPAN:.2f} m, rise {RISE:.2f} m (pointed: equilateral, "
          f"{SPAN * math.sqrt(3) / 2:.2f} m), t = {THICKNESS} m, {VOUSSOIRS} voussoirs")
    print(f"{'shape':<14} {'k [-]':>7} {'theta_cr/theta_u':>17} {'c_v':>6} "
          f"{'a_f(0.4 s) [g]':>15} {'median [g]':>11}")

    amplitudes = np.round(np.arange(step, 2.0 + 1e-9, step), 10)
    fig, axes = plt.subplots(2, 2, figsize=(12, 9), constrained_layout=True)
    colours = dict(zip(SHAPES, plt.get_cmap("tab10").colors, strict=False))
    for shape in SHAPES:
        arch = arch_of(shape)
        colour = colours[shape]
        dynamics = FourLinkModel.from_arch(arch, RESTITUTION)
        mech_l = dynamics.mechanisms[0]
        k = dynamics.load_multiplier
        domain = domain_of(dynamics, durations, amplitudes, extend_to_g=6.0)
        curve = domain.failure_accelerations_g
        sample = irregular_sample(arch, 0.10, samples, seed=2024)
        p_f = probability_of_failure(np.array([failures(a, amplitudes) for a in sample]))
        fit = fit_lognormal(amplitudes, samples, np.round(p_f * samples))
        i = int(np.argmin(np.abs(durations - DURATION)))
        print(f"{shape:<14} {k:7.4f} {mech_l.theta_cr / mech_l.theta_u:17.3f} "
              f"{domain.restitution[0]:6.3f} {curve[i]:15.3f} {fit.median:11.3f}")

        plot_arch(arch, axes[0, 0], color=colour, linewidth=0.8, label=shape)
        axes[0, 1].bar(shape, k, color=colour)
        axes[1, 0].plot(durations, curve, "-o", color=colour, markersize=3, label=shape)
        axes[1, 1].plot(amplitudes, p_f, "o", color=colour, markersize=3)
        axes[1, 1].plot(amplitudes, fit(amplitudes), "-", color=colour, label=shape)

    axes[0, 0].legend(fontsize=8, loc="upper right")
    axes[0, 0].set_title(f"the arches (span {SPAN:.1f} m, t = {THICKNESS} m, n = {VOUSSOIRS})")
    axes[0, 1].set_ylabel("load multiplier k = min(k$_l$, k$_r$) [-]")
    axes[0, 1].axhline(paper_k, color="black", linestyle=":", linewidth=1.0,
                       label="Oppenheim's arch, n = 7 (paper)")
    axes[0, 1].legend(fontsize=8)
    axes[0, 1].tick_params(axis="x", labelrotation=30)
    axes[0, 1].set_title("collapse under horizontal forces (limit analysis)")
    axes[1, 0].set_xlabel("pulse duration t$_p$ [s]")
    axes[1, 0].set_ylabel("failure acceleration [g]")
    axes[1, 0].set_title("failure curves under Oppenheim's pulse (computed c$_v$)")
    axes[1, 0].legend(fontsize=8)
    axes[1, 1].set_xlabel(r"pulse amplitude $|\ddot{x}_g|/g$ [-]")
    axes[1, 1].set_ylabel("probability of failure P$_F$ [-]")
    axes[1, 1].set_title(f"fragility at t$_p$ = {DURATION:.2f} s, h = {samples} irregular "
                         "arches (lognormal fits)")
    axes[1, 1].set_xlim(0.0, 1.5)
    axes[1, 1].legend(fontsize=8)
    path = Path(args.out) / "arch_shapes.png"
    fig.savefig(path, dpi=100)
    print(f"figure written to {path}")


if __name__ == "__main__":
    main()
