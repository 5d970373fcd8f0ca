"""The figures of the paper's report, each drawn from values.

Every function takes what a part returned (:mod:`archquake.report.paper.parts`) and returns a
:class:`matplotlib.figure.Figure`; its caption is written by
:mod:`archquake.report.paper.text` and :func:`archquake.report.render.save` writes it beside the
report. The axes are drawn by :mod:`archquake.plotting`, so a figure of the report is the figure
a user draws with the library. matplotlib is imported when a figure is drawn.
"""

from __future__ import annotations

from ...constants import GRAVITY
from ..formatting import outcome_text
from .settings import ARCH_COLOURS, ARCH_NAMES, PULSE_RECORD_TIME
from .text import restitution_label


def plot_history(history, ax, name: str, phi_limit: float):
    """One arch's rotation history in its colour, its outcome in the legend.

    Parameters
    ----------
    history : TimeHistory
    ax : matplotlib.axes.Axes
    name : str
        The arch (:data:`~archquake.report.paper.settings.ARCH_NAMES`).
    phi_limit : float
        Limit of the rotation axis [rad].

    Returns
    -------
    matplotlib.axes.Axes
    """
    from ...plotting import plot_rotation_history

    out = history.outcome
    text = outcome_text(out.status.label, out.half_cycle)
    plot_rotation_history(history, ax, label=f"{name}: {text}", color=ARCH_COLOURS[name],
                          linewidth=1.2)
    ax.set_ylim(-phi_limit, phi_limit)
    ax.set_ylabel(r"$\phi$ (Mech-l), $-\phi'$ (Mech-r) [rad]")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="upper right", fontsize=8)
    return ax


def nominal_arch(arches, table1: dict):
    """The nominal arch's hinges and thrust line, Mech-l (the paper's Fig. 2).

    Parameters
    ----------
    arches : Arches
    table1 : dict
        :func:`archquake.report.paper.parts.limit_table`.

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt

    from ...plotting import plot_limit_analysis

    fig, ax = plt.subplots(figsize=(7.0, 4.6), constrained_layout=True)
    plot_limit_analysis(arches.nominal.limit[0], ax)
    ax.set_title(f"Oppenheim's arch NA, Mech-l: k = {table1['NA']['k']:.4f}")
    return fig


def irregular_arches(arches):
    """The irregular arches' hinges and thrust lines over the nominal arch, both mechanisms
    (the paper's Fig. 4).

    Parameters
    ----------
    arches : Arches

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt

    from ...plotting import plot_limit_analysis

    fig, axes = plt.subplots(2, 2, figsize=(12.0, 8.6), constrained_layout=True)
    nominal = arches.arch("NA")
    for row, name in enumerate(("RA-1", "RA-2")):
        for col, res in enumerate(arches.models[name].limit):
            frame = nominal if res.direction == "l" else nominal.mirrored()
            plot_limit_analysis(res, axes[row, col], nominal=frame)
            mech = "Mech-l" if res.direction == "l" else "Mech-r (mirrored arch)"
            axes[row, col].set_title(f"{name}, {mech}: k~ = {res.load_multiplier:.4f}")
    return fig


def potential_energy(arches):
    """The potential energy of both mechanisms of the three arches (the paper's Figs. 6-8).

    Parameters
    ----------
    arches : Arches

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt

    from ...plotting import plot_potential_energy

    fig, axes = plt.subplots(1, 3, figsize=(14.0, 4.2), constrained_layout=True)
    for ax, name in zip(axes, ARCH_NAMES, strict=True):
        mechs = arches.models[name].mechanisms
        phi_max = 1.6 * max(m.phi_cr for m in mechs)
        for mech, colour in zip(mechs, ("tab:blue", "tab:orange"), strict=True):
            label = ("Mech-l" if mech.direction == "l" else "Mech-r")
            plot_potential_energy(mech, ax, label=label, color=colour, phi_max=phi_max)
        fig_no = {"NA": "Fig. 6", "RA-1": "Fig. 7", "RA-2": "Fig. 8"}[name]
        ax.set_title(f"{name} ({fig_no} of the paper)")
    return fig


def free_vibration(free, case: str):
    """Free vibrations of the three arches with one coefficient of restitution (the paper's
    Figs. 9-14).

    Parameters
    ----------
    free : FreeVibrations
    case : str
        ``"elastic"``, ``"paper"`` or ``"computed"``.

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt

    pair = free.summary[case]["restitution"]
    fig, axes = plt.subplots(3, 1, figsize=(9.0, 8.0), sharex=True, constrained_layout=True)
    for ax, name in zip(axes, ARCH_NAMES, strict=True):
        plot_history(free.histories[case][name], ax, name, 0.03)
        ax.set_title(rf"{name}: free vibration from $\phi_0$ = 0.02 rad, $c_v$ = {pair[0]:.3f}",
                     fontsize=10)
        if ax is not axes[-1]:
            ax.set_xlabel("")
    return fig


def pulse_response(pulses, case: str):
    """The ground acceleration of the paper's three pulses and the response of the three arches
    to each, with one coefficient of restitution (the paper's Fig. 15).

    Parameters
    ----------
    pulses : PulseResponses
    case : str
        ``"paper"`` or ``"computed"``.

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt

    from ...ground_motion import oppenheim_pulse
    from ...plotting import plot_ground_motion

    entry = pulses.summary[case]
    rows = entry["cases"]
    fig, axes = plt.subplots(len(rows) + 1, 1, figsize=(9.0, 10.5), sharex=True,
                             constrained_layout=True)
    for row, colour in zip(rows, ("0.1", "tab:purple", "tab:brown"), strict=True):
        plot_ground_motion(oppenheim_pulse(row["amplitude"] * GRAVITY, row["duration"]),
                           axes[0], t_end=PULSE_RECORD_TIME, color=colour,
                           label=f"$t_p$ = {row['duration']:.2f} s")
    axes[0].set_title(r"(a) ground acceleration: Oppenheim's pulse, $\ddot{x}_g/g = -1$ for $t_p$, "
                      r"then $+1/2$ for $2 t_p$", fontsize=10)
    axes[0].set_xlabel("")
    for ax, row, letter in zip(axes[1:], rows, "bcd", strict=True):
        for name in ARCH_NAMES:
            plot_history(pulses.histories[case][(name, row["duration"])], ax, name, 0.35)
        ax.set_title(rf"({letter}) $t_p$ = {row['duration']:.2f} s, "
                     f"{restitution_label(case, entry['restitution'])}", fontsize=10)
        if ax is not axes[-1]:
            ax.set_xlabel("")
    return fig


def failure_domain(domain, point=None):
    """A failure domain, with a point marked on it (the paper's Fig. 16 with its point Q).

    Parameters
    ----------
    domain : FailureDomain
        :func:`archquake.studies.failure_domain.domain_of`.
    point : (float, float, str), optional
        ``(t_p [s], amplitude [g], name)`` of a point to mark.

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt

    from ...plotting import plot_failure_domain

    fig, ax = plt.subplots(figsize=(8.0, 5.6), constrained_layout=True)
    plot_failure_domain(domain, ax)
    if point is not None:
        duration, amplitude, name = point
        ax.plot([duration], [amplitude], "s", color="black", markersize=7, zorder=6)
        ax.annotate(f"{name} ({duration:.2f} s, {amplitude:.2f} g)", (duration, amplitude),
                    textcoords="offset points", xytext=(8, 8), fontsize=9, fontweight="bold")
    return fig


def fragility_curve(result, duration: float):
    """The fragility curve of the irregular arches at one duration (the paper's Figs. 17-20).

    Parameters
    ----------
    result : FragilityResult
    duration : float
        Pulse duration t_p [s].

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt

    from ...plotting import plot_fragility_curve

    fig, ax = plt.subplots(figsize=(7.5, 6.2), constrained_layout=True)
    plot_fragility_curve(result, duration, ax)
    return fig


def fragility_surface(result):
    """The fragility surface of the irregular arches and the nominal arch's step surface (the
    paper's Fig. 21).

    Parameters
    ----------
    result : FragilityResult

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt

    from ...plotting import plot_fragility_surface

    fig = plt.figure(figsize=(8.5, 6.4), constrained_layout=True)
    ax = fig.add_subplot(projection="3d")
    plot_fragility_surface(result, ax)
    return fig


def model_comparison(comparison):
    """The failure accelerations of the rigid-block and four-link models (left) and their
    relative differences (right).

    Parameters
    ----------
    comparison : ModelComparison

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt

    from ...plotting import plot_model_comparison, plot_model_differences

    fig, (left, right) = plt.subplots(1, 2, figsize=(14.5, 5.6), constrained_layout=True,
                                      width_ratios=(1.2, 1.0))
    plot_model_comparison(comparison, left)
    plot_model_differences(comparison, right)
    return fig


def record_fragility(results: dict):
    """The record-based fragility, one panel per intensity measure.

    Parameters
    ----------
    results : dict
        By intensity measure: the study's result
        (:attr:`archquake.report.paper.parts.RecordFragilityPart.results`).

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt

    from ...plotting import plot_record_fragility

    fig, axes = plt.subplots(1, len(results), figsize=(13.0, 5.2), constrained_layout=True,
                             squeeze=False)
    for ax, (im, result) in zip(axes[0], results.items(), strict=True):
        plot_record_fragility(result, ax)
        ax.set_title(f"Record-based fragility in {im.upper()}, $\\varepsilon$ = "
                     f"{result.settings.epsilon:g}")
    return fig



def two_model_domain(part):
    """The four-link failure domain (the paper's c_v) with the rigid-block failure curve over it
    and, hatched, where the two models disagree on collapse.

    Parameters
    ----------
    part : TwoModelsPart

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt

    from ...plotting import plot_disagreement, plot_failure_domain

    fig, ax = plt.subplots(figsize=(8.0, 5.6), constrained_layout=True)
    plot_failure_domain(part.four_link_domain, ax)
    domain = part.rigid_domain
    ax.plot(domain.durations, domain.failure_accelerations_g, "-s", color="tab:red",
            markersize=4, linewidth=1.6, label="rigid-block model: failure curve", zorder=5)
    handles, _ = ax.get_legend_handles_labels()
    ax.legend(handles=handles, loc="upper right", fontsize=7, framealpha=0.9)
    plot_disagreement(part.disagreement, ax)
    ax.set_title("Failure domain by both models: the four-link model (shaded) and the rigid "
                 "blocks (red)", fontsize=10)
    return fig


def two_model_fragility(summary: dict):
    """P_F against the amplitude per pulse duration by both models on the same arches, the
    four-link P_F of the whole sample, and the multi-fidelity estimate of the rigid blocks' P_F
    of the whole sample.

    Parameters
    ----------
    summary : dict
        ``two_models["fragility"]`` of ``results.json``.

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt
    import numpy as np

    durations = summary["durations"]
    a = np.asarray(summary["amplitudes_g"])
    fig, axes = plt.subplots(1, len(durations), figsize=(3.6 * len(durations), 3.9),
                             sharey=True, constrained_layout=True, squeeze=False)
    for i, (ax, tp) in enumerate(zip(axes[0], durations, strict=True)):
        ax.step(a, np.asarray(summary["rigid_blocks"])[i], where="mid", color="tab:red",
                linewidth=1.6, label=f"rigid blocks ({summary['arches_both']} arches)")
        ax.step(a, np.asarray(summary["four_link_same_arches"])[i], where="mid",
                color="black", linewidth=1.2, label="four-link, the same arches")
        ax.plot(a, np.asarray(summary["four_link_all"])[i], ":", color="0.4", linewidth=1.2,
                label=f"four-link, all {summary['arches_four_link']} arches")
        ax.plot(a, np.asarray(summary["multifidelity"])[i], "--", color="tab:red",
                linewidth=1.2, label="rigid blocks, multi-fidelity estimate (all arches)")
        ax.set_title(f"t$_p$ = {tp:.2f} s", fontsize=10)
        ax.set_xlabel("pulse amplitude [g]")
        ax.grid(True, alpha=0.3)
    axes[0][0].set_ylabel("P$_F$")
    axes[0][0].set_ylim(-0.03, 1.03)
    axes[0][-1].legend(loc="lower right", fontsize=7, framealpha=0.9)
    return fig


__all__ = ["failure_domain", "fragility_curve", "fragility_surface", "free_vibration",
           "irregular_arches", "model_comparison", "nominal_arch", "plot_history",
           "potential_energy", "pulse_response", "record_fragility", "two_model_domain",
           "two_model_fragility"]
