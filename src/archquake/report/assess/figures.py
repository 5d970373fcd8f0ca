"""The figures of an assessment, each drawn from the values of its parts
(:mod:`archquake.report.assess.parts`, :mod:`archquake.report.assess.records`).

Every function returns a :class:`matplotlib.figure.Figure`; its caption is written by
:mod:`archquake.report.assess.text` and :func:`archquake.report.render.save` writes it beside the
report. The axes are drawn by :mod:`archquake.plotting`, so a figure of the report is the
figure a user draws with the library. matplotlib is imported when a figure is drawn.
"""

from __future__ import annotations

import numpy as np


def _own_frame(ax) -> None:
    """Show a Mech-r drawing (of the mirrored structure) in the structure's own frame: the x
    axis reversed and its ticks labelled with the structure's own coordinates, and the arrow of
    the horizontal forces turned to point right to left."""
    from matplotlib.text import Annotation
    from matplotlib.ticker import FuncFormatter

    ax.invert_xaxis()
    ax.xaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{-v + 0.0:g}"))
    for artist in list(ax.texts):
        if isinstance(artist, Annotation) and artist.arrow_patch is not None:
            props = dict(artist.arrowprops)
            (x0, y), (x1, _) = artist.xyann, artist.xy
            artist.remove()
            ax.annotate("", xy=(1.0 - x1, y), xytext=(1.0 - x0, y), xycoords="axes fraction",
                        arrowprops=props)
        elif not isinstance(artist, Annotation) and "horizontal forces" in artist.get_text():
            artist.set_position((0.97, artist.get_position()[1]))
            artist.set_horizontalalignment("right")


def structure_figure(structure, analyses=None, *, title: str = ""):
    """The structure drawn to scale; with its limit analyses, the line of thrust at activation
    and the hinges of both mechanisms, each in the structure's own frame.

    Parameters
    ----------
    structure : BlockArch
        The structure.
    analyses : (LimitAnalysis, LimitAnalysis), optional
        Mech-l and Mech-r (:attr:`archquake.report.assess.parts.LimitPart.analyses`); None
        draws the structure alone (one that cannot stand).
    title : str
        Title of a drawing of the structure alone.

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt

    from ...plotting import plot_arch, plot_limit_analysis

    if analyses is None:
        fig, ax = plt.subplots(figsize=(7.5, 5.0), constrained_layout=True)
        plot_arch(structure, ax, label="the structure")
        ax.set_title(title)
        ax.legend(loc="lower center", fontsize=8, frameon=False)
        return fig
    fig, axes = plt.subplots(1, 2, figsize=(13.0, 5.2), constrained_layout=True)
    for ax, analysis in zip(axes, analyses, strict=True):
        plot_limit_analysis(analysis, ax)
        k = analysis.load_multiplier
        if analysis.direction == "r":
            _own_frame(ax)
            ax.set_title(f"Mech-r (forces right to left): k$_r$ = {k:.4f}")
        else:
            ax.set_title(f"Mech-l (forces left to right): k$_l$ = {k:.4f}")
    return fig


def mechanisms_figure(model):
    """The potential energy of both four-link mechanisms against their rotation, with the
    critical rotation phi_cr marked [paper, eq. (3), Figs. 6-8].

    Parameters
    ----------
    model : FourLinkModel

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt

    from ...plotting import plot_potential_energy

    fig, ax = plt.subplots(figsize=(7.5, 4.4), constrained_layout=True)
    phi_max = 1.6 * max(m.phi_cr for m in model.mechanisms)
    for mech, colour in zip(model.mechanisms, ("tab:blue", "tab:orange"), strict=True):
        plot_potential_energy(mech, ax, color=colour, phi_max=phi_max,
                              label="Mech-l" if mech.direction == "l" else "Mech-r")
    ax.set_title("Potential energy of the four-link mechanisms")
    return fig


def domain_figure(pulses):
    """The failure domain under Oppenheim's pulse: the four-link model's regions (shaded), the
    rigid-block model's failure curve (squares) and where the two disagree on collapse
    (hatched).

    Parameters
    ----------
    pulses : PulsePart
        :func:`archquake.report.assess.parts.pulse_part`.

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt

    from ...plotting import plot_disagreement, plot_failure_domain

    fig, ax = plt.subplots(figsize=(9.0, 6.0), constrained_layout=True)
    governing = pulses.summary["direction"]
    rigid = pulses.rigid_blocks
    shaded = rigid if pulses.four_link is None else pulses.four_link[governing]
    plot_failure_domain(shaded, ax)
    handles = list(ax.get_legend().legend_handles)
    if pulses.four_link is not None:
        (line,) = ax.plot(rigid.durations, rigid.failure_accelerations_g, "--s", color="tab:red",
                          markersize=5, linewidth=1.2,
                          label="rigid blocks: failure curve")
        handles.insert(2, line)
        ax.legend(handles=handles, loc="upper right", fontsize=7.5, framealpha=0.9)
        plot_disagreement(pulses.significant, ax)
        model = "four-link model (shaded)"
    else:
        model = "rigid-block model"
    sign = "-" if governing == "l" else "+"
    ax.set_title(f"Failure domain, {model}, first pulse {sign}a g", fontsize=10)
    low, high = ax.get_ylim()
    if high > 20.0 * low > 0.0:  # the failure curves near k would be a line at the bottom
        from matplotlib.ticker import FixedLocator, NullFormatter, ScalarFormatter

        ax.set_yscale("log")
        ax.set_ylim(low, high)
        ticks = [t for t in (0.02, 0.05, 0.1, 0.2, 0.5, 1.0, 2.0, 5.0, 10.0, 20.0)
                 if low <= t <= high]
        ax.yaxis.set_major_locator(FixedLocator(ticks))
        ax.yaxis.set_major_formatter(ScalarFormatter())
        ax.yaxis.set_minor_formatter(NullFormatter())
        ax.set_ylabel("pulse amplitude |$\\ddot{x}_g$| [g] (logarithmic)")
    return fig


def irregularity_figure(irregularity, durations=None):
    """The fragility curves of the irregular arches under Oppenheim's pulse, with the CDF of
    k~ of the limit-analysis sample, at the first and the last duration of the study
    [paper, Figs. 17-20].

    Parameters
    ----------
    irregularity : IrregularityPart
        :func:`archquake.report.assess.parts.irregularity_part`.
    durations : sequence of float, optional
        The durations drawn (default: the study's first and last).

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt

    from ...plotting import plot_fragility_curve

    result = irregularity.result
    if durations is None:
        d = result.durations
        durations = [float(d[0])] if d.size == 1 else [float(d[0]), float(d[-1])]
    fig, axes = plt.subplots(1, len(durations), figsize=(6.6 * len(durations), 6.4),
                             constrained_layout=True, squeeze=False)
    for ax, duration in zip(axes[0], durations, strict=True):
        plot_fragility_curve(result, duration, ax)
    return fig


def record_figure(results: dict):
    """The record-based fragility in every intensity measure, one panel each.

    Parameters
    ----------
    results : dict
        By intensity measure: a
        :class:`~archquake.studies.record_fragility.RecordFragilityResult` (or a
        :class:`~archquake.report.assess.records.StructureStripes`).

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt

    from ...plotting import plot_record_fragility
    from .records import StructureStripes
    from .text import im_label

    n = len(results)
    fig, axes = plt.subplots(1, n, figsize=(5.6 * n, 5.0), constrained_layout=True,
                             squeeze=False)
    for ax, (im, result) in zip(axes[0], results.items(), strict=True):
        if isinstance(result, StructureStripes):
            structure_stripes_axes(result, ax)
            ax.set_title(f"{im_label(im)}, the structure", fontsize=10)
            continue
        plot_record_fragility(result, ax)
        ax.set_title(f"{im_label(im)}, $\\varepsilon$ = {result.settings.epsilon:g}",
                     fontsize=10)
    return fig


def structure_stripes_axes(stripes, ax):
    """The record-based fragility of the structure alone on ``ax``: the fraction of the records
    that collapse it at each stripe, the lognormal fit and its bootstrap band.

    Parameters
    ----------
    stripes : StructureStripes
        :func:`archquake.report.assess.records.structure_stripes`.
    ax : matplotlib.axes.Axes

    Returns
    -------
    matplotlib.axes.Axes
    """
    x = stripes.levels
    if stripes.band is not None:
        band = stripes.band
        ax.fill_between(band.x, band.lower, band.upper, color="tab:blue", alpha=0.15,
                        linewidth=0, label=f"{100 * band.confidence:.0f} % bootstrap band "
                                           f"({band.resamples} resamples)")
    if stripes.lognormal is not None:
        fit = stripes.lognormal
        fine = np.geomspace(x[0], x[-1], 300)
        ax.plot(fine, fit(fine), "--", color="tab:blue", linewidth=1.3,
                label=f"lognormal fit: median {fit.median:.3g} {stripes.unit}, "
                      f"$\\beta$ = {fit.dispersion:.3f}")
    ax.plot(x, stripes.probability, "s", color="tab:blue", markersize=4,
            markerfacecolor="none", label=f"fraction of {len(stripes.records)} records")
    ax.set_xlim(0.0, float(x[-1]) * 1.03)
    ax.set_ylim(-0.02, 1.04)
    ax.set_xlabel(f"{stripes.im} [{stripes.unit}]")
    ax.set_ylabel("P(collapse | IM) [-]")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="lower right", fontsize=7.5)
    return ax


def records_figure(names, pga_g, first_pga_g, k: float):
    """The records' PGA as recorded and the PGA at which each first collapses the structure
    (the four-link model, either polarity), sorted.

    Parameters
    ----------
    names : sequence of str
        The records.
    pga_g : array_like
        Their PGA as recorded [g].
    first_pga_g : array_like
        The lowest PGA that collapses the structure [g] (nan: none on the pilot's grid).
    k : float
        The structure's load multiplier [-] (the PGA below which it does not move).

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt

    first = np.asarray(first_pga_g, dtype=float)
    order = np.argsort(np.where(np.isfinite(first), first, np.inf))
    fig, ax = plt.subplots(figsize=(9.0, 0.5 + 0.22 * len(names)), constrained_layout=True)
    y = np.arange(len(names))
    ax.barh(y, first[order], color="tab:red", alpha=0.5,
            label="PGA that first collapses the structure")
    ax.plot(np.asarray(pga_g)[order], y, "k|", markersize=9, label="PGA as recorded")
    ax.axvline(k, color="black", linestyle="--", linewidth=1.0, label=f"k = {k:.3f}")
    ax.set_yticks(y, [names[i] for i in order], fontsize=7)
    ax.invert_yaxis()
    ax.set_xlabel("PGA [g]")
    ax.grid(True, axis="x", alpha=0.3)
    ax.legend(loc="lower right", fontsize=8)
    return fig


__all__ = ["domain_figure", "irregularity_figure", "mechanisms_figure", "record_figure",
           "records_figure", "structure_figure", "structure_stripes_axes"]


def site_figure(check):
    """The code check at the site: the capacity curve of the mechanism with the displacement
    capacities and demands (:func:`archquake.plotting.plot_capacity_curve`).

    Parameters
    ----------
    check : LocalMechanismCheck

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt

    from ...plotting import plot_capacity_curve

    fig, ax = plt.subplots(figsize=(8.0, 5.0), constrained_layout=True)
    plot_capacity_curve(check, ax)
    return fig
