"""Figures. Every function takes ``ax=None`` (a new figure when None) and returns the axes.

This is a leaf module: nothing in archquake's physics imports it. It uses ``matplotlib.pyplot``
with whatever backend is active; the command line selects the non-interactive ``Agg`` backend
before importing it.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from .geometry import BlockArch
from .limit_analysis import LimitAnalysis
from .studies.fits import empirical_cdf

HINGE_LABELS = ("A", "B", "C", "D")
_MECHANISM_NAMES = {"l": "Mech-l", "r": "Mech-r"}


def _axes(ax):
    if ax is None:
        _, ax = plt.subplots(figsize=(7.0, 4.5))
    return ax


FILL_COLOUR = "#e8d9b5"
"""Colour of the fill over an arch."""


def _members(settings) -> tuple[str, str]:
    """How a figure names one member of a study's sample and several
    (:attr:`archquake.studies.arch_sample.StudySample.member_nouns`)."""
    return getattr(settings, "member_nouns", ("arch", "arches"))


def plot_arch(arch: BlockArch, ax=None, *, label: str | None = None, fill: bool = True,
              **style):
    """Outline of every block of ``arch`` [m], in its own frame; its fill and the ground under
    its piers, if it has them (:class:`~archquake.geometry.Structure`).

    Parameters
    ----------
    arch : BlockArch
        The arch (of any shape), or a structure: an arch on piers, with fill.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; a new figure when None.
    label : str, optional
        Legend label (given to the first voussoir only).
    fill : bool, default True
        Draw the fill columns (shaded, one per voussoir) and the fill's level surface.
    **style
        Line properties (default: black, 1 pt).

    Returns
    -------
    matplotlib.axes.Axes
        The axes drawn on.
    """
    ax = _axes(ax)
    style = {"color": "black", "linewidth": 1.0, **style}
    columns = getattr(arch, "fill_columns", None)
    if fill and columns is not None:
        for k, outline in enumerate(columns.outlines):
            ax.fill(outline[:, 0], outline[:, 1], facecolor=FILL_COLOUR, edgecolor="#c9b78f",
                    linewidth=0.5, zorder=0, label="fill" if k == 0 else None)
    for i in range(arch.n_voussoirs):
        outline = arch.outline(i)
        ax.plot(outline[:, 0], outline[:, 1], label=label if i == 0 else None, **style)
    for j, side in ((0, getattr(arch, "left", None)), (-1, getattr(arch, "right", None))):
        if side is not None:  # the ground under a pier
            base = arch.joints[j]
            width = float(abs(base[1, 0] - base[0, 0]))
            x = np.sort(base[:, 0]) + np.array([-0.3, 0.3]) * width
            ax.plot(x, base[:, 1], color="#7a5c3a", linewidth=2.5, solid_capstyle="butt",
                    zorder=0)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    return ax


def plot_limit_analysis(result: LimitAnalysis, ax=None, *, nominal: BlockArch | None = None):
    """Arch, line of thrust and hinges at collapse [paper, Figs. 2 and 4].

    The funicular polygon (line of action of the resultant inside each voussoir) is drawn in
    blue with the pressure points on the joints as dots; the hinges are labelled A, B, C, D.
    ``nominal`` (drawn in red beneath) shows an irregular arch against its nominal one, as in
    Fig. 4 of the paper; for Mech-r give the nominal arch in the same (mirrored) frame.

    Parameters
    ----------
    result : archquake.limit_analysis.LimitAnalysis
        The limit analysis of one direction; drawn in its own frame (mirrored for Mech-r).
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; a new figure when None.
    nominal : BlockArch, optional
        The nominal arch, drawn beneath in red [m].

    Returns
    -------
    matplotlib.axes.Axes
        The axes drawn on.
    """
    ax = _axes(ax)
    if nominal is not None:
        plot_arch(nominal, ax, color="tab:red", linewidth=0.9, label="nominal arch")
        plot_arch(result.arch, ax, color="black", label="irregular arch")
    else:
        plot_arch(result.arch, ax, color="black", label="arch")
    funicular = result.funicular()
    ax.plot(funicular[:, 0], funicular[:, 1], color="tab:blue", linewidth=1.4,
            label="line of action of the resultant")
    pts = result.thrust_line.points
    ax.plot(pts[:, 0], pts[:, 1], "o", color="tab:blue", markersize=3.5,
            label="pressure points on the joints")
    hinges = result.hinge_points
    ax.plot(hinges[:, 0], hinges[:, 1], "o", color="tab:orange", markeredgecolor="black",
            markersize=8, zorder=5, label="hinges")
    labels = HINGE_LABELS if result.is_four_hinge else tuple(
        f"H{i + 1}" for i in range(len(result.hinges)))
    span = float(np.ptp(result.arch.centroids[:, 0])) or 1.0
    for (x, y), hinge, text in zip(hinges, result.hinges, labels, strict=False):
        outward = result.arch.joint_directions[hinge.joint]  # intrados -> extrados end
        sign = 1.0 if hinge.face == "extrados" else -1.0
        offset = 0.045 * span * sign * outward
        ax.annotate(text, (x, y), (x + offset[0], y + offset[1]), ha="center", va="center",
                    fontsize=11, fontweight="bold")
    ax.annotate("", xy=(0.16, 0.93), xytext=(0.03, 0.93), xycoords="axes fraction",
                arrowprops={"arrowstyle": "-|>", "color": "tab:green", "linewidth": 1.5})
    fill = getattr(result.arch, "fill", None)
    ax.text(0.03, 0.86, "horizontal forces k m$_i$ g" + (
        "" if fill is None else f" (fill inertia: {fill.inertia})"),
        transform=ax.transAxes, fontsize=8, color="tab:green")
    name = _MECHANISM_NAMES[result.direction]
    if result.direction == "r":
        name += " (mirrored arch)"
    ax.set_title(f"{name}: k = {result.load_multiplier:.4f}")
    ax.legend(loc="lower center", fontsize=8, frameon=False, ncol=2)
    heights = np.concatenate([result.arch.outline(i)[:, 1]
                              for i in range(result.arch.n_voussoirs)])
    columns = getattr(result.arch, "fill_columns", None)
    low, top = min(0.0, float(heights.min())), float(heights.max())
    room = 0.12
    if columns is not None:  # the fill's surface, and room above it for the forces' label
        top, room = max(top, columns.level), 0.35
    ax.set_ylim(low - 0.45 * (top - low), top + room * (top - low))
    return ax


def plot_load_multiplier_cdf(k_values, ax=None, *, nominal_k: float | None = None,
                             label: str = "limit analysis, irregular arches"):
    """Empirical cumulative distribution of the load multiplier k~ [paper, Figs. 17-20, blue].

    Parameters
    ----------
    k_values : array of float
        Load multipliers k~ = min(k~_l, k~_r) of the sampled arches [-].
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; a new figure when None.
    nominal_k : float, optional
        k of the nominal arch, drawn as a vertical line.
    label : str
        Legend label of the curve.

    Returns
    -------
    matplotlib.axes.Axes
        The axes drawn on.
    """
    ax = _axes(ax)
    x, p = empirical_cdf(k_values)
    ax.step(x, p, where="post", color="tab:blue", label=f"{label} (s = {x.size})")
    if nominal_k is not None:
        ax.axvline(nominal_k, color="tab:blue", linestyle="-.", linewidth=1.0,
                   label=f"nominal arch, k = {nominal_k:.4f}")
    ax.set_xlabel("horizontal load multiplier k~ = a/g [-]")
    ax.set_ylabel("cumulative probability [-]")
    ax.set_ylim(0.0, 1.02)
    ax.grid(True, alpha=0.3)
    ax.legend(loc="upper left", fontsize=8)
    return ax


# ------------------------------------------------------------------ failure domain, fragility
DOMAIN_COLOURS = {
    "rest": "#eeeeee",
    "recovery": "#d5ecd4",
    "collapse_impacts": "#fbd9a6",
    "collapse_first": "#f3a6a6",
    "undecided": "#c8b4e0",
}
DOMAIN_LABELS = {
    "rest": "no motion (a < k)",
    "recovery": "(1) recovery",
    "collapse_impacts": "(2) collapse after impacts",
    "collapse_first": "(3) collapse in the first half cycle",
    "undecided": "undecided (the model gave no outcome)",
}


def _region(status: str, half_cycle: int) -> str:
    if status == "collapse":
        return "collapse_first" if half_cycle == 1 else "collapse_impacts"
    return status


def _cell_edges(values: np.ndarray) -> np.ndarray:
    """Edges of cells centred on sorted ``values`` (half-way between neighbours)."""
    if values.size == 1:
        return np.array([values[0] * 0.95, values[0] * 1.05])
    mid = 0.5 * (values[1:] + values[:-1])
    return np.concatenate([[values[0] - (mid[0] - values[0])], mid,
                           [values[-1] + (values[-1] - mid[-1])]])


def plot_failure_domain(domain, ax=None):
    """Failure domain over (pulse duration, amplitude) [paper, Fig. 16].

    The regions are shaded (no motion, recovery, collapse after impacts, collapse in the first
    half cycle, and the amplitudes a model left undecided); the boundary of collapse in the
    first half cycle (Oppenheim's curve) is drawn with asterisks, the failure curve (lowest
    collapsing amplitude) with dots (an open triangle pointing down where the lowest amplitude
    scanned already collapses: an upper bound), and the
    limit-analysis multiplier k as a horizontal dashed line.

    Parameters
    ----------
    domain : archquake.studies.failure_domain.FailureDomain
        The domain (:func:`archquake.studies.failure_domain.domain_of`).
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; a new figure when None.

    Returns
    -------
    matplotlib.axes.Axes
        The axes drawn on.
    """
    from matplotlib.collections import PolyCollection
    from matplotlib.patches import Patch

    ax = _axes(ax)
    order = np.argsort(domain.durations)
    durations = domain.durations[order]
    slices = [domain.slices[i] for i in order]
    edges = _cell_edges(durations)
    polygons = {key: [] for key in DOMAIN_COLOURS}
    for x0, x1, s in zip(edges[:-1], edges[1:], slices, strict=True):
        for iv in s.intervals:
            polygons[_region(iv.status, iv.half_cycle)].append(
                [(x0, iv.start), (x1, iv.start), (x1, iv.end), (x0, iv.end)])
    handles = []
    for key, polys in polygons.items():
        if polys:
            ax.add_collection(PolyCollection(polys, facecolors=DOMAIN_COLOURS[key],
                                             edgecolors="none", zorder=0))
            handles.append(Patch(facecolor=DOMAIN_COLOURS[key], label=DOMAIN_LABELS[key]))
    first = domain.first_half_cycle_accelerations_g[order]
    failure = domain.failure_accelerations_g[order]
    (curve_first,) = ax.plot(durations, first, "-*", color="black", markersize=7,
                             linewidth=1.2, label="collapse in the first half cycle "
                                                  "(Oppenheim's curve)")
    (curve_failure,) = ax.plot(durations, failure, "-o", color="black", markersize=3.5,
                               linewidth=1.2, label="failure curve (lowest collapsing amplitude)")
    upper = np.array([s.failure_acceleration_bound == "upper" for s in slices])
    bounds = []
    if np.any(upper):  # collapse from the lowest amplitude scanned: at most there
        bounds = ax.plot(durations[upper], failure[upper], "v", color="black",
                         markerfacecolor="white", markersize=9, zorder=5,
                         label="collapse from the lowest amplitude scanned (an upper bound)")
    k = domain.limit_multiplier
    line_k = ax.axhline(k, color="black", linestyle="--", linewidth=1.2,
                        label=f"limit analysis, k = {k:.3f}")
    low = min(s.intervals[0].start for s in slices)
    high = max(s.intervals[-1].end for s in slices)
    ax.set_xlim(edges[0], edges[-1])
    ax.set_ylim(low, high)
    ax.set_xlabel("pulse duration t$_p$ [s]")
    ax.set_ylabel("pulse amplitude |$\\ddot{x}_g$| [g]")
    name = _MECHANISM_NAMES[domain.direction]
    sign = "-" if domain.direction == "l" else "+"
    c_lr, c_rl = domain.restitution
    c_text = f"{c_lr:.3f}" if abs(c_lr - c_rl) < 5e-4 else f"{c_lr:.3f} / {c_rl:.3f}"
    ax.set_title(f"Failure domain: first pulse {sign}a g ({name}), c$_v$ = {c_text}")
    ax.legend(handles=[curve_first, curve_failure, *bounds, line_k] + handles, loc="upper right",
              fontsize=8, framealpha=0.9)
    return ax


def plot_fragility_curve(result, duration: float, ax=None):
    """Fragility curve at one pulse duration [paper, Figs. 17-20].

    Black dots: P_F = h_f/h of the irregular arches [eq. (9)] (open purple triangles: its upper
    bound, where arches are undecided, :mod:`archquake.studies.undecided`); black dashed: the
    quintic fit;
    grey: the lognormal (maximum-likelihood) fit; blue: the empirical CDF of the limit-analysis
    multiplier k~ = min(k~_l, k~_r) of s arches; vertical lines: the nominal arch's failure
    acceleration (black dash-dot, the step of eq. (10)) and its k (blue).

    Parameters
    ----------
    result : archquake.studies.fragility.FragilityResult
    duration : float
        Pulse duration t_p [s], one of the study's.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; a new figure when None.

    Returns
    -------
    matplotlib.axes.Axes
        The axes drawn on.
    """
    from .studies.fits import evaluate_polynomial_fit

    if ax is None:
        _, ax = plt.subplots(figsize=(7.5, 6.2), constrained_layout=True)
    i = result.duration_index(duration)
    a = result.amplitudes_g
    settings = result.settings
    noun, _ = _members(settings)
    # excluded arches (k~ = nan) are not counted; those that never collapse (k~ = inf) are,
    # so the CDF then stays below 1
    k_values = result.limit_load_multipliers[~np.isnan(result.limit_load_multipliers)]
    k_sorted = np.sort(k_values[np.isfinite(k_values)])
    k_prob = np.arange(1, k_sorted.size + 1) / max(k_values.size, 1)
    x_low = min(float(a[0]), float(k_sorted[0]) if k_sorted.size else float(a[0]))
    fine = np.linspace(a[0], a[-1], 400)
    ax.step(np.concatenate([[x_low], k_sorted]), np.concatenate([[0.0], k_prob]), where="post",
            color="tab:blue", linewidth=1.3,
            label=f"limit analysis: CDF of k~ (s = {k_values.size})")
    ax.axvline(result.nominal_load_multiplier, color="tab:blue", linewidth=1.2,
               label=f"nominal {noun}, limit analysis k = {result.nominal_load_multiplier:.3f}")
    ax.plot(fine, evaluate_polynomial_fit(result.polynomial_fits[i], fine), "--", color="black",
            linewidth=1.3, label="fifth-degree polynomial fit")
    lognormal = result.lognormal_fits[i]
    if lognormal is not None:
        ax.plot(fine, lognormal(fine), "-", color="0.55", linewidth=1.3,
                label=f"lognormal fit to {result.lognormal_upper[i]:.2f} g (median "
                      f"{lognormal.median:.3f} g, beta {lognormal.dispersion:.3f})")
    ax.plot(a, result.probability[i], "o", color="black", markersize=3.5,
            label=f"P$_F$ = h$_f$/h, h = {result.analysed}"
                  + (f" ({len(result.excluded)} excluded)" if result.excluded else ""))
    upper = getattr(result, "probability_upper", result.probability)[i]
    if np.any(upper != result.probability[i]):  # undecided arches: P_F lies between the two
        ax.plot(a, upper, "^", color="tab:purple", markerfacecolor="none", markersize=4.5,
                label="upper bound of P$_F$: undecided arches as failed")
    q = float(result.nominal_failure_acceleration_g[i])
    if np.isfinite(q):
        ax.axvline(q, color="black", linestyle="-.", linewidth=1.2,
                   label=f"nominal {noun}, failure acceleration {q:.3f} g")
    ax.set_xlim(x_low - 0.02, float(a[-1]) + 0.02)
    ax.set_ylim(-0.02, 1.04)
    ax.set_xlabel("pulse amplitude |$\\ddot{x}_g$| [g]; load multiplier k~ [-]")
    ax.set_ylabel("probability of failure P$_F$; cumulative probability [-]")
    ax.set_title(f"Fragility curve, t$_p$ = {result.durations[i]:.2f} s, "
                 f"$\\varepsilon$ = {settings.epsilon:g}")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=2, fontsize=7.5,
              frameon=False)
    return ax


def plot_fragility_surface(result, ax=None):
    """Fragility surface P_F(t_p, a) of the irregular arches [paper, Fig. 21].

    The fragility curves are joined by plane facets over (amplitude, duration); the nominal
    arch's step surface (eq. (10): P_F = 0 below its failure acceleration, 1 from it on) is drawn
    as a translucent grey wall with its top edge.

    Parameters
    ----------
    result : archquake.studies.fragility.FragilityResult
    ax : matplotlib 3-D Axes, optional
        Created with ``projection="3d"`` when None.

    Returns
    -------
    matplotlib.axes.Axes
        The axes drawn on.
    """
    if ax is None:
        fig = plt.figure(figsize=(8.0, 6.0))
        ax = fig.add_subplot(projection="3d")
    a, d = np.meshgrid(result.amplitudes_g, result.durations)
    ax.plot_surface(a, d, result.probability, cmap="viridis", vmin=0.0, vmax=1.0,
                    edgecolor="none", linewidth=0, alpha=0.85, rstride=1, cstride=1)
    for i, tp in enumerate(result.durations):
        ax.plot(result.amplitudes_g, np.full(result.amplitudes_g.size, tp), result.probability[i],
                color="black", linewidth=0.8)
    q = result.nominal_failure_acceleration_g
    ok = np.isfinite(q)
    if np.count_nonzero(ok) >= 1:
        qd, dd = q[ok], result.durations[ok]
        wall_a = np.vstack([qd, qd])
        wall_d = np.vstack([dd, dd])
        wall_p = np.vstack([np.zeros(qd.size), np.ones(qd.size)])
        if qd.size >= 2:
            ax.plot_surface(wall_a, wall_d, wall_p, color="0.5", alpha=0.35, linewidth=0)
        ax.plot(qd, dd, np.ones(qd.size), color="red", linewidth=1.8,
                label=f"nominal {_members(result.settings)[0]} (eq. 10): P$_F$ steps 0 -> 1 at "
                      "its failure acceleration")
        ax.plot(qd, dd, np.zeros(qd.size), color="red", linewidth=1.0, linestyle="--")
        for x, y in zip(qd, dd, strict=True):
            ax.plot([x, x], [y, y], [0.0, 1.0], color="red", linewidth=0.8)
        ax.legend(loc="upper left", fontsize=8)
    ax.set_xlabel("amplitude |$\\ddot{x}_g$| [g]")
    ax.set_ylabel("pulse duration t$_p$ [s]")
    ax.set_zlabel("P$_F$ [-]")
    ax.set_zlim(0.0, 1.0)
    ax.set_title(f"Fragility surface, $\\varepsilon$ = {result.settings.epsilon:g}, "
                 f"h = {result.settings.sample_size}")
    ax.view_init(elev=25, azim=-125)
    return ax


# --- dynamics


def plot_rotation_history(history, ax=None, *, label: str | None = None, mark_impacts=True,
                          **style):
    """Rotation phi(t) of a time history [rad], Mech-l positive and Mech-r negative
    (Figs. 9-15 of the paper), impacts marked.

    Parameters
    ----------
    history : archquake.fourlink.time_history.TimeHistory
        A recorded time history.
    ax : matplotlib axes, optional
    label : str, optional
        Legend label.
    mark_impacts : bool
        Mark every impact on the time axis.
    **style
        Passed to ``ax.plot``.

    Returns
    -------
    matplotlib.axes.Axes
        The axes drawn on.
    """
    ax = _axes(ax)
    line = None
    for seg in history.segments:
        sign = -1.0 if seg.mechanism == "r" else 1.0
        kwargs = dict(style)
        if line is not None:
            kwargs["color"] = line.get_color()
        (line,) = ax.plot(seg.t, sign * seg.phi, label=label if line is None else None,
                          **kwargs)
    if mark_impacts and history.impact_times.size:
        ax.plot(history.impact_times, np.zeros_like(history.impact_times), "o", ms=3.5,
                mfc="none", color=line.get_color() if line is not None else "k")
    outcome = history.outcome
    if outcome.collapsed and np.isfinite(outcome.collapse_time):
        ax.axvline(outcome.collapse_time, ls=":", lw=0.8,
                   color=line.get_color() if line is not None else "k")
    ax.axhline(0.0, color="0.6", lw=0.6)
    ax.set_xlabel("time t [s]")
    ax.set_ylabel(r"$\phi$ (Mech-l $+$, Mech-r $-$) [rad]")
    if label is not None:
        ax.legend()
    return ax


def plot_free_vibration(history, ax=None, **style):
    """Free vibration phi(t) (Figs. 9-14 of the paper); see :func:`plot_rotation_history`."""
    ax = plot_rotation_history(history, ax, **style)
    ax.set_title("free vibration")
    return ax


def plot_pulse_response(histories, ax=None, *, labels=None, phi_limit: float | None = None):
    """Response phi(t) to a ground motion with the acceleration in a panel above (Fig. 15).

    Parameters
    ----------
    histories : TimeHistory or sequence of TimeHistory
        Time histories under the same ground motion (e.g. several arches).
    ax : matplotlib axes, optional
        Axes of the response; the ground-motion panel is added above it.
    labels : sequence of str, optional
        Legend labels.
    phi_limit : float, optional
        Clip the vertical axis at +-phi_limit [rad] (collapsing histories run to the limit).

    Returns
    -------
    (ax_ground, ax_response)
    """
    from mpl_toolkits.axes_grid1 import make_axes_locatable

    if not isinstance(histories, list | tuple):
        histories = [histories]
    labels = labels or [None] * len(histories)
    if ax is None:
        _, ax = plt.subplots(figsize=(7.0, 5.5))
    divider = make_axes_locatable(ax)
    ax_ground = divider.append_axes("top", size="35%", pad=0.15, sharex=ax)
    t_max = max(float(h.t[-1]) for h in histories)
    motion = histories[0].ground_motion
    t = np.linspace(0.0, t_max, 4001)
    t = np.unique(np.concatenate([t, motion.breakpoints[motion.breakpoints <= t_max],
                                  np.nextafter(motion.breakpoints, -np.inf)]))
    t = t[(t >= 0) & (t <= t_max)]
    ax_ground.plot(t, motion.acceleration(t) / 9.81, color="k", lw=1.0)
    ax_ground.axhline(0.0, color="0.6", lw=0.6)
    ax_ground.set_ylabel(r"$\ddot{x}_g$ [g]")
    ax_ground.tick_params(labelbottom=False)
    ax_ground.set_title(motion.name)
    for history, label in zip(histories, labels, strict=True):
        plot_rotation_history(history, ax, label=label)
    if phi_limit is not None:
        ax.set_ylim(-phi_limit, phi_limit)
    return ax_ground, ax


# --- energy and ground motion


def plot_potential_energy(mechanism, ax=None, *, label: str | None = None, color=None,
                          phi_max: float | None = None):
    """Potential energy ``V(phi) - V(0)`` of a four-link mechanism [paper, eq. (3), Figs. 6-8].

    ``phi = theta_u - theta`` [rad] from the undisplaced configuration (0) to ``phi_max``
    (default: the kinematic limit ``theta_u - theta_limit``). The maximum at ``phi_cr`` (eq. (4))
    is marked with a dot and a dotted vertical line.

    Parameters
    ----------
    mechanism : FourLinkMechanism
        Mech-l or Mech-r of an arch.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; a new figure when None.
    label : str, optional
        Legend label (default: the mechanism's name).
    color : optional
        Line colour.
    phi_max : float, optional
        Right end of the phi axis [rad].

    Returns
    -------
    matplotlib.axes.Axes
        The axes drawn on.
    """
    ax = _axes(ax)
    name = _MECHANISM_NAMES[mechanism.direction]
    limit = mechanism.theta_u - mechanism.theta_limit
    end = limit if phi_max is None else min(float(phi_max), limit)
    phi = np.linspace(0.0, end, 400)
    v0 = float(mechanism.potential_energy(mechanism.theta_u))
    energy = (mechanism.potential_energy(mechanism.theta_u - phi) - v0) / 1e3
    line, = ax.plot(phi, energy, color=color, label=label or name)
    v_cr = (float(mechanism.potential_energy(mechanism.theta_cr)) - v0) / 1e3
    ax.plot([mechanism.phi_cr], [v_cr], "o", color=line.get_color(), markersize=5)
    ax.axvline(mechanism.phi_cr, color=line.get_color(), linestyle=":", linewidth=1.0)
    ax.annotate(f"$\\phi_{{cr}}$ = {mechanism.phi_cr:.4f}", (mechanism.phi_cr, v_cr),
                textcoords="offset points", xytext=(4, 6), fontsize=8, color=line.get_color())
    ax.set_xlabel(r"$\phi = \theta_u - \theta$ [rad]")
    ax.set_ylabel(r"$V(\phi) - V(0)$ [kJ/m]")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="best", fontsize=8)
    return ax


def plot_ground_motion(motion, ax=None, *, t_end: float | None = None, label: str | None = None,
                       color=None):
    """Ground acceleration ``xg''/g`` of a ground motion against time [Fig. 15a].

    Parameters
    ----------
    motion : GroundMotion
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; a new figure when None.
    t_end : float, optional
        End of the time axis [s] (default: 1.2 times the duration of the motion).
    label : str, optional
        Legend label (default: the motion's name).
    color : optional
        Line colour.

    Returns
    -------
    matplotlib.axes.Axes
        The axes drawn on.
    """
    from .geometry import GRAVITY

    ax = _axes(ax)
    end = 1.2 * motion.duration if t_end is None else float(t_end)
    breaks = motion.breakpoints
    t = np.union1d(np.linspace(0.0, end, 1500), np.concatenate([breaks, breaks - 1e-9]))
    t = t[(t >= 0.0) & (t <= end)]
    ax.plot(t, motion.acceleration(t) / GRAVITY, color=color, linewidth=1.2,
            label=label or motion.name)
    ax.axhline(0.0, color="0.4", linewidth=0.6)
    ax.set_xlabel("time t [s]")
    ax.set_ylabel(r"$\ddot{x}_g / g$ [-]")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="upper right", fontsize=8)
    return ax


def plot_record_fragility(result, ax=None, *, nominal: bool = True):
    """Record-based fragility curve in the intensity measure: the stripes' fractions, the
    lognormal fit and its bootstrap band (:mod:`archquake.studies.record_fragility`).

    Black dots: P(collapse | IM = x) of the irregular arch-record pairs at each stripe; black
    line: the total lognormal fit (all pairs pooled) with its bootstrap band (grey); blue squares
    and dashed line: the nominal arch's fraction of collapsing records and its
    (record-to-record) fit, with its band.

    Parameters
    ----------
    result : archquake.studies.record_fragility.RecordFragilityResult
    ax : matplotlib Axes, optional
    nominal : bool
        Draw the nominal arch too.
    """
    if ax is None:
        _, ax = plt.subplots(figsize=(7.5, 5.6), constrained_layout=True)
    settings = result.settings
    x = result.levels
    fine = np.geomspace(x[0], x[-1], 300)
    unit = settings.unit
    if result.band is not None:
        ax.fill_between(result.band.x, result.band.lower, result.band.upper, color="0.8",
                        linewidth=0, label=f"{100 * result.band.confidence:.0f} % bootstrap band "
                                           f"({result.band.resamples} resamples)")
    if result.lognormal is not None:
        fit = result.lognormal
        ax.plot(fine, fit(fine), "-", color="black", linewidth=1.4,
                label=f"lognormal fit: median {fit.median:.3g} {unit}, "
                      f"$\\beta$ = {fit.dispersion:.3f}")
    one, many = _members(settings)
    ax.plot(x, result.probability, "o", color="black", markersize=4,
            label=f"irregular {many}: {result.analysed} {many} x {len(result.records)} "
                  f"records")
    if nominal:
        if result.nominal_band is not None:
            band = result.nominal_band
            ax.fill_between(band.x, band.lower, band.upper, color="tab:blue", alpha=0.15,
                            linewidth=0)
        if result.nominal_lognormal is not None:
            fit = result.nominal_lognormal
            ax.plot(fine, fit(fine), "--", color="tab:blue", linewidth=1.3,
                    label=f"nominal {one} fit: median {fit.median:.3g} {unit}, "
                          f"$\\beta$ = {fit.dispersion:.3f}")
        ax.plot(x, result.nominal_probability, "s", color="tab:blue", markersize=3.5,
                markerfacecolor="none", label=f"nominal {one}: fraction of records")
    ax.set_xlim(0.0, float(x[-1]) * 1.03)
    ax.set_ylim(-0.02, 1.04)
    ax.set_xlabel(f"{settings.im} [{unit}]")
    ax.set_ylabel("P(collapse | IM) [-]")
    ax.set_title(f"Record-based fragility, $\\varepsilon$ = {settings.epsilon:g}")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="lower right", fontsize=7.5)
    return ax


def plot_incremental(result, ax=None, *, arch: int | None = None):
    """The incremental view: for every arch-record pair, the levels that collapse it.

    One row per pair (sorted by its lowest collapsing level), one column per stripe level:
    black where the pair collapses (either polarity), orange where the arch survives again at a
    level above its lowest collapsing level, white where it survives below it.

    Parameters
    ----------
    result : archquake.studies.record_fragility.RecordFragilityResult
    ax : matplotlib Axes, optional
    arch : int, optional
        Only this arch (-1: the nominal arch); default every irregular arch.
    """
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch

    if ax is None:
        _, ax = plt.subplots(figsize=(7.5, 5.6), constrained_layout=True)
    one, many = _members(result.settings)
    if arch is None:
        failed = result.failed.reshape(-1, result.levels.size)
        what = f"{result.analysed} {many} x {len(result.records)} records"
    elif arch == -1:
        failed = result.nominal_failed
        what = f"nominal {one}, {len(result.records)} records"
    else:
        failed = result.arch_failed(arch)
        what = f"{one} {arch}, {len(result.records)} records"
    n_levels = result.levels.size
    first = np.where(failed.any(axis=1), np.argmax(failed, axis=1), n_levels)
    order = np.lexsort((-failed.sum(axis=1), first))
    failed, first = failed[order], first[order]
    above = np.arange(n_levels)[None, :] > first[:, None]
    code = np.where(failed, 2, np.where(above, 1, 0))
    x = result.levels
    edges = np.concatenate([[x[0] - 0.5 * (x[1] - x[0]) if x.size > 1 else 0.5 * x[0]],
                            0.5 * (x[1:] + x[:-1]),
                            [x[-1] + 0.5 * (x[-1] - x[-2]) if x.size > 1 else 1.5 * x[0]]])
    cmap = ListedColormap(["white", "tab:orange", "black"])
    ax.pcolormesh(edges, np.arange(code.shape[0] + 1), code, cmap=cmap, vmin=-0.5, vmax=2.5)
    ax.set_xlabel(f"{result.settings.im} [{result.settings.unit}]")
    ax.set_ylabel(f"{one}-record pair (sorted by lowest collapsing level)")
    recovering = int(np.sum((code == 1).any(axis=1)))
    ax.set_title(f"Incremental view, {what}: {recovering} of {code.shape[0]} pairs survive "
                 "above a collapse", fontsize=9)
    ax.legend(handles=[Patch(color="black", label="collapse"),
                       Patch(color="tab:orange", label="survives above its lowest collapse"),
                       Patch(facecolor="white", edgecolor="0.5", label="survives")],
              loc="upper left", fontsize=7.5)
    return ax


COMPARISON_COLOURS = {"computed": "tab:blue", "link": "tab:orange", "paper": "tab:green",
                      "measured": "tab:red", "nominal": "tab:purple",
                      "elastic": "tab:brown"}
"""Colour of the four-link model's curve for each restitution model."""


def plot_model_comparison(comparison, ax=None):
    """Failure acceleration against pulse duration in the rigid-block and four-link models.

    Black squares: the rigid-block model; coloured lines: the four-link model with each
    restitution model; vertical bars at a duration: the recovery bands above a failure
    acceleration (amplitudes at which the arch survives although a lower one collapses it),
    grey for the rigid-block model, coloured (slightly offset) for the four-link model; open
    triangles at the top of the scan: no collapse in the scan; open triangles pointing down:
    collapse from the lowest amplitude scanned (an upper bound); dashed: the limit-analysis k,
    below which neither model moves.

    Parameters
    ----------
    comparison : archquake.studies.comparison.ModelComparison
        The comparison (:func:`archquake.studies.comparison.compare_models`).
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; a new figure when None.

    Returns
    -------
    matplotlib.axes.Axes
        The axes drawn on.
    """
    if ax is None:
        _, ax = plt.subplots(figsize=(8.0, 5.4), constrained_layout=True)
    durations = comparison.durations
    order = np.argsort(durations)
    x = durations[order]
    top = float(comparison.amplitudes_g[-1])
    span = float(np.ptp(x)) if x.size > 1 else 1.0
    curves = [("rigid_block", "rigid-block model", comparison.rigid_block.slices, "black")]
    any_upper = False
    for name, domain in comparison.four_link.items():
        c_lr, c_rl = domain.restitution
        c_text = f"{c_lr:.3f}" if abs(c_lr - c_rl) < 5e-4 else f"{c_lr:.3f}/{c_rl:.3f}"
        curves.append((name, f"four-link, c$_v$ = {c_text} ({name})", domain.slices,
                       COMPARISON_COLOURS.get(name, None)))
    for j, (name, label, slices, colour) in enumerate(curves):
        slices = [slices[i] for i in order]
        failure = np.array([s.failure_acceleration_g for s in slices])
        rigid = name == "rigid_block"
        (line,) = ax.plot(x, failure, "-s" if rigid else "-o", color=colour,
                          linewidth=2.2 if rigid else 1.2, markersize=6 if rigid else 3.5,
                          label=label, zorder=4 if rigid else 3)
        colour = line.get_color()
        shift = 0.0 if rigid else 0.008 * span * j
        beyond = np.isnan(failure)
        if np.any(beyond):
            ax.plot(x[beyond] + shift, np.full(beyond.sum(), top), "^", color=colour,
                    markerfacecolor="none", markersize=8, zorder=5)
        upper = np.array([s.failure_acceleration_bound == "upper" for s in slices])
        if np.any(upper):
            any_upper = True
            ax.plot(x[upper] + shift, failure[upper], "v", color=colour,
                    markerfacecolor="none", markersize=8, zorder=5)
        for xi, s in zip(x, slices, strict=True):
            for lo, hi in s.recovery_above_g:
                ax.plot([xi + shift, xi + shift], [lo, hi], "-", color="0.55" if rigid else colour,
                        linewidth=5 if rigid else 2, alpha=0.8, solid_capstyle="butt", zorder=2)
    k = comparison.load_multiplier
    ax.axhline(k, color="black", linestyle="--", linewidth=1.0,
               label=f"limit analysis, k = {k:.3f}")
    ax.plot([], [], "^", color="0.3", markerfacecolor="none", label="no collapse up to the "
                                                                      "top of the scan")
    if any_upper:
        ax.plot([], [], "v", color="0.3", markerfacecolor="none", label="collapse from the "
                "lowest amplitude scanned (an upper bound)")
    ax.plot([], [], "-", color="0.55", linewidth=5, label="recovery above the failure "
                                                          "acceleration")
    ax.set_yscale("log")
    ax.set_ylim(float(comparison.amplitudes_g[0]), top * 1.08)
    ticks = [t for t in (0.3, 0.4, 0.5, 0.7, 1.0, 1.5, 2.0, 3.0, 5.0, 10.0)
             if comparison.amplitudes_g[0] <= t <= top * 1.08]
    ax.set_yticks(ticks, [f"{t:g}" for t in ticks])
    ax.minorticks_off()
    ax.set_xlabel("pulse duration t$_p$ [s]")
    ax.set_ylabel("failure acceleration |$\\ddot{x}_g$|/g [-]")
    friction = comparison.settings.friction
    ax.set_title(f"Rigid-block and four-link models: failure curves (friction {friction:g})")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="upper right", fontsize=8, framealpha=0.9)
    return ax


def plot_model_differences(comparison, ax=None):
    """Relative difference of the four-link failure acceleration from the rigid-block one,
    ``a_four_link / a_rigid_block - 1`` [%], against pulse duration, one line per restitution
    model; the grey band is +-5 %.

    Parameters
    ----------
    comparison : archquake.studies.comparison.ModelComparison
        The comparison (:func:`archquake.studies.comparison.compare_models`).
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; a new figure when None.

    Returns
    -------
    matplotlib.axes.Axes
        The axes drawn on.
    """
    if ax is None:
        _, ax = plt.subplots(figsize=(7.0, 5.4), constrained_layout=True)
    order = np.argsort(comparison.durations)
    x = comparison.durations[order]
    ax.axhspan(-5.0, 5.0, color="0.88", zorder=0, label="$\\pm$5 %")
    ax.axhline(0.0, color="black", linewidth=1.0)
    for name, difference in comparison.relative_differences().items():
        c_lr = comparison.four_link[name].restitution[0]
        ax.plot(x, 100.0 * difference[order], "-o", color=COMPARISON_COLOURS.get(name),
                markersize=3.5, linewidth=1.2, label=f"{name}, c$_v$ = {c_lr:.3f}")
    ax.set_xlabel("pulse duration t$_p$ [s]")
    ax.set_ylabel("four-link / rigid-block failure acceleration - 1 [%]")
    ax.set_title("Difference from the rigid-block model (none: no failure in the scan)")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="best", fontsize=8, framealpha=0.9)
    return ax


def plot_disagreement(disagreement, ax=None):
    """Hatch where two failure domains disagree on collapse (over a failure-domain figure).

    Drawn over :func:`plot_failure_domain` of the first domain, it shows where in
    (pulse duration, amplitude) the second model -- the rigid blocks, for the four-link
    model's domain -- collapses and the first does not (``\\\\``, red) or the reverse (``//``,
    blue): the four-link model's error as the rigid-block model estimates it.

    Parameters
    ----------
    disagreement : archquake.studies.comparison.Disagreement
        :func:`archquake.studies.comparison.domain_disagreement` of two domains.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; a new figure when None.

    Returns
    -------
    matplotlib.axes.Axes
        The axes drawn on.
    """
    from matplotlib.patches import Patch, Rectangle

    ax = _axes(ax)
    durations = np.asarray(disagreement.durations, dtype=float)
    order = np.argsort(durations)
    edges = _cell_edges(durations[order])
    first, second = disagreement.names
    style = {"second only": ("\\\\\\\\", "#b2182b", f"{second} collapses, {first} does not"),
             "first only": ("////", "#2166ac", f"{first} collapses, {second} does not")}
    used = set()
    for x0, x1, i in zip(edges[:-1], edges[1:], order, strict=True):
        for lo, hi, which in disagreement.intervals[i]:
            hatch, colour, _ = style[which]
            ax.add_patch(Rectangle((x0, lo), x1 - x0, hi - lo, fill=False, hatch=hatch,
                                   edgecolor=colour, linewidth=0.0, zorder=1))
            used.add(which)
    handles = [Patch(facecolor="none", hatch=style[w][0], edgecolor=style[w][1],
                     label=style[w][2]) for w in ("second only", "first only") if w in used]
    if handles:
        previous = ax.get_legend()
        extra = list(previous.legend_handles) if previous is not None else []
        ax.legend(handles=extra + handles, loc="upper right", fontsize=7, framealpha=0.9)
    return ax


def plot_capacity_curve(check, ax=None):
    r"""The capacity curves of a local-mechanism check (Circolare 2019 §C8.7.1.2.2): spectral
    acceleration :math:`a^*` [g] against spectral displacement :math:`d^*` [m] in each
    direction (one curve when they coincide), with every limit state's displacement capacity
    :math:`d_u^*` (open marker on the curve) and demand :math:`S_{De}(T_s)` (filled marker on
    the axis), and the linear check's
    :math:`a_0^*` against its demand.

    Parameters
    ----------
    check : LocalMechanismCheck
        :func:`archquake.site.local_mechanism.check_local_mechanism`.
    ax : matplotlib.axes.Axes, optional

    Returns
    -------
    matplotlib.axes.Axes
    """
    ax = _axes(ax)
    g = 9.81
    colours = {"l": "C0", "r": "C1"}
    styles = {"SLV": "o", "SLC": "s"}
    curves = list(check.curves)
    same = (len(curves) == 2 and curves[0].spectral_displacement.shape
            == curves[1].spectral_displacement.shape
            and np.allclose(curves[0].spectral_displacement, curves[1].spectral_displacement)
            and np.allclose(curves[0].spectral_acceleration, curves[1].spectral_acceleration))
    if same:  # a symmetric structure: one curve for both
        curves = curves[:1]
    for curve in curves:
        colour = colours[curve.direction]
        name = "Mech-l = Mech-r" if same else _MECHANISM_NAMES[curve.direction]
        ax.plot(curve.spectral_displacement, curve.spectral_acceleration / g, color=colour,
                label=f"{name}: capacity, $d_0^*$ = {curve.d0:.3f} m")
        for c in check.nonlinear:
            if c.direction != curve.direction:
                continue
            a_u = float(curve.acceleration_at(c.ultimate_displacement)) / g
            ax.plot(c.ultimate_displacement, a_u, styles[c.limit_state], color=colour,
                    markerfacecolor="white",
                    label=f"{c.limit_state}: capacity $d_u^*$ = {c.ultimate_displacement:.3f} m")
            ax.plot(c.demand, 0.0, styles[c.limit_state], color=colour, clip_on=False,
                    label=f"{c.limit_state}: demand $S_{{De}}(T_s)$ = {c.demand:.3f} m "
                          f"($T_s$ = {c.secant_period:.2f} s)")
    for c in check.linear:
        if c.direction == "l" or not check.curves:
            ax.axhline(c.demand, color="0.4", ls="--", lw=1,
                       label=f"linear {c.limit_state} demand $a_g S/q$ = {c.demand:.3f} g "
                             f"(capacity $a_0^*$ = {c.capacity:.3f} g)")
    ax.set_xlabel("spectral displacement $d^*$ [m]")
    ax.set_ylabel("spectral acceleration $a^*$ [g]")
    ax.set_xlim(left=0.0)
    ax.set_ylim(bottom=0.0)
    ax.set_title("Capacity curve of the mechanism (Circolare 2019 §C8.7.1.2.2)", fontsize=10)
    ax.legend(fontsize=7)
    return ax


_STATE_STYLE = {
    "rocks": ("tab:red", "rocks (a hinge at its closed end)"),
    "slides": ("tab:blue", "slides"),
    "rocks and slides": ("tab:purple", "rocks and slides"),
    "separates": ("tab:orange", "separates"),
}


def plot_k_distribution(k, k_nominal: float, what: str, ax=None):
    """The empirical distribution of the load multipliers ``k`` of irregular structures beside
    the nominal one's (``archquake limit --samples``, the assessment of a bridge).

    Parameters
    ----------
    k : array_like
        The multipliers of the structures drawn [-].
    k_nominal : float
        The nominal structure's [-].
    what : str
        What was drawn, for the legend (``"bridges, epsilon 0.1, seed 0"``).
    ax : matplotlib Axes, optional

    Returns
    -------
    matplotlib.axes.Axes
    """
    from .studies.fits import empirical_cdf

    ax = _axes(ax)
    k = np.asarray(k, dtype=float)
    if k.size:
        x, p = empirical_cdf(k)
        ax.step(x, p, where="post", label=f"{k.size} irregular {what}")
    ax.axvline(k_nominal, color="k", linestyle="--", label=f"nominal, k = {k_nominal:.4f}")
    ax.set_xlabel("load multiplier k [-]")
    ax.set_ylabel("fraction with a lower k [-]")
    ax.set_ylim(0, 1)
    ax.legend(loc="upper left")
    return ax


def plot_assembly_limits(results):
    """Every direction's and friction law's collapse of an assembly, one panel each: the
    directions side by side, the laws one row each (:func:`plot_assembly_limit`).

    Parameters
    ----------
    results : dict
        Direction -> law -> AssemblyLimit (:func:`archquake.limit_analysis.assembly_limits`).

    Returns
    -------
    matplotlib.figure.Figure
        The figure drawn.
    """
    laws = list(next(iter(results.values())))
    fig, axes = plt.subplots(len(laws), len(results), figsize=(6.5 * len(results),
                             4.6 * len(laws)), constrained_layout=True, squeeze=False)
    for column, laws_of in enumerate(results.values()):
        for row, law in enumerate(laws):
            plot_assembly_limit(laws_of[law], axes[row, column])
    return fig


def plot_assembly_limit(result, ax=None, *, displacement: float | None = None):
    """An assembly at collapse: its blocks, the mechanism and the state of every interface.

    The blocks are drawn in grey, the mechanism's displaced blocks (the collapse velocities
    times ``displacement``) in red outline, the interfaces that move in colour (red: rock, the
    hinge as a dot at the end that stays closed; blue: slide; purple: both; orange: separate),
    the pressure points of the loaded interfaces as black dots, the line of thrust through them
    (:meth:`~archquake.limit_analysis.AssemblyLimit.thrust_line`) and the ground as a thick
    line under the foundation interfaces.

    Parameters
    ----------
    result : AssemblyLimit
        One direction's collapse (:func:`archquake.limit_analysis.assembly_limit`).
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; a new figure when None.
    displacement : float, optional
        Largest displacement of a block corner in the drawn mechanism [m] (default 6 % of the
        assembly's size).

    Returns
    -------
    matplotlib.axes.Axes
        The axes drawn on.
    """
    from matplotlib.patches import Polygon

    ax = _axes(ax)
    c = result.contacts
    corners = np.concatenate([np.asarray(o, dtype=float) for o in c.outlines])
    size = float(max(np.ptp(corners[:, 0]), np.ptp(corners[:, 1]))) or 1.0
    scale = 0.06 * size if displacement is None else float(displacement)
    for j, outline in enumerate(c.outlines):
        outline = np.asarray(outline, dtype=float)
        ax.add_patch(Polygon(outline, closed=True, facecolor="0.88", edgecolor="0.35",
                             linewidth=0.7))
        moved = outline + scale * result.velocity_at(j, outline)
        if np.max(np.abs(moved - outline)) > 1e-3 * scale:
            ax.add_patch(Polygon(moved, closed=True, fill=False, edgecolor="tab:red",
                                 linewidth=0.8, linestyle="--"))
    ground = (c.a < 0) | (c.b < 0)
    for p0, p1 in zip(c.p0[ground], c.p1[ground], strict=True):
        ax.plot([p0[0], p1[0]], [p0[1], p1[1]], color="black", linewidth=3, zorder=3)
    seen = set()
    for i, state in enumerate(result.state):
        if state == "closed":
            continue
        colour, label = _STATE_STYLE[state]
        ax.plot([c.p0[i, 0], c.p1[i, 0]], [c.p0[i, 1], c.p1[i, 1]], color=colour, linewidth=2.5,
                zorder=4, label=None if state in seen else label)
        seen.add(state)
        if "rocks" in state:
            hinge = c.p0[i] if result.opening[i, 0] < result.opening[i, 1] else c.p1[i]
            ax.plot(*hinge, "o", color=colour, markeredgecolor="black", markersize=7, zorder=5)
    loaded = np.isfinite(result.pressure[:, 0]) & (result.normal > 1e-9 * np.max(result.normal))
    segments, _ = result.thrust_line()
    if segments.size:
        from matplotlib.collections import LineCollection

        ax.add_collection(LineCollection(segments, colors="black", linewidths=0.9, zorder=5,
                                         label="thrust line"))
    ax.plot(result.pressure[loaded, 0], result.pressure[loaded, 1], ".", color="black",
            markersize=4, zorder=5, label="pressure points")
    arrow = "-|>"
    x0, x1 = (0.03, 0.16) if result.direction == "+x" else (0.16, 0.03)
    ax.annotate("", xy=(x1, 0.93), xytext=(x0, 0.93), xycoords="axes fraction",
                arrowprops={"arrowstyle": arrow, "color": "tab:green", "linewidth": 1.5})
    ax.text(0.03, 0.86, "horizontal forces k W", transform=ax.transAxes, fontsize=8,
            color="tab:green")
    k = result.load_multiplier
    title = (f"{result.direction}, {result.law}: k = {k:.4f} (tilt {result.tilt:.2f} deg)"
             if np.isfinite(k) else f"{result.direction}, {result.law}: no collapse")
    if not result.converged:
        title += ", not converged"
    ax.set_title(title, fontsize=10)
    ax.set_aspect("equal")
    pad = 0.08 * size
    ax.set_xlim(corners[:, 0].min() - pad, corners[:, 0].max() + pad)
    ax.set_ylim(corners[:, 1].min() - pad, corners[:, 1].max() + 2.5 * pad)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.legend(loc="lower center", fontsize=8, frameon=False, ncol=3,
              bbox_to_anchor=(0.5, -0.02))
    return ax
