"""Figures and animations of rigid-block analyses.

A leaf module: nothing in archquake's physics imports it. Every plot function takes ``ax=None``
(a new figure when None) and returns the axes; :func:`animate_blocks` writes a GIF with
matplotlib's ``PillowWriter`` (Pillow comes with matplotlib). The blocks are drawn in the frame
of the ground, in which the supports do not move.
"""

from __future__ import annotations

import warnings
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.collections import PolyCollection

from .dynamics import BlockHistory


def _axes(ax, size=(7.0, 4.5)):
    """``ax``, or the axes of a new figure of ``size`` [in] when None."""
    if ax is None:
        _, ax = plt.subplots(figsize=size)
    return ax


def _record(history: BlockHistory, time: float | None) -> int:
    """Index of the record nearest to ``time`` [s] (the last for None)."""
    if history.times.size == 0:
        raise ValueError("the history holds no records")
    if time is None:
        return history.times.size - 1
    return int(np.argmin(np.abs(history.times - time)))


def _limits(history: BlockHistory) -> tuple[tuple[float, float], tuple[float, float]]:
    """x and y limits [m] around the undeformed outlines, with margins (more below)."""
    points = np.vstack(history.assembly.outlines)
    span = np.ptp(points, axis=0)
    lo = points.min(axis=0) - 0.08 * span
    hi = points.max(axis=0) + 0.08 * span
    return (float(lo[0]), float(hi[0])), (float(lo[1] - 0.1 * span[1]), float(hi[1]))


def _supports(history: BlockHistory, ax) -> None:
    """The joints against the ground, drawn as thick grey segments."""
    asm = history.assembly
    for j in range(asm.n_joints):
        if -1 in asm.joint_bodies[j]:
            p = asm.joint_points[j]
            ax.plot(p[:, 0], p[:, 1], color="0.35", linewidth=4, solid_capstyle="butt")


def plot_blocks(history: BlockHistory, time: float | None = None, ax=None, *,
                undeformed: bool = True, color="tab:orange"):
    """The blocks at ``time`` [s] (the record nearest to it; default: the last record).

    Parameters
    ----------
    history : BlockHistory
        A recorded analysis (:func:`archquake.rigid_blocks.simulate_blocks`).
    time : float, optional
        Time [s].
    ax : matplotlib Axes, optional
        Axes to draw in (default: a new figure).
    undeformed : bool
        Also draw the undeformed outlines (thin grey).
    color : color
        Face colour of the blocks.

    Returns
    -------
    matplotlib Axes
        The axes, in the frame of the ground [m], equal aspect.

    Raises
    ------
    ValueError
        If the history holds no records.
    """
    ax = _axes(ax)
    k = _record(history, time)
    if undeformed:
        for outline in history.assembly.outlines:
            ax.plot(outline[:, 0], outline[:, 1], color="0.6", linewidth=0.6)
    polys = PolyCollection(history.outlines(k), facecolors=color, edgecolors="black",
                           linewidths=0.8, alpha=0.9)
    ax.add_collection(polys)
    _supports(history, ax)
    (x0, x1), (y0, y1) = _limits(history)
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m] (frame of the ground)")
    ax.set_ylabel("y [m]")
    ax.set_title(f"t = {history.times[k]:.3f} s")
    return ax


def plot_block_history(history: BlockHistory, ax=None):
    """Crown drop, largest joint opening and largest slip [m] against time [s], with the
    largest block rotation [rad] on a second axis and the decision time marked.

    Parameters
    ----------
    history : BlockHistory
        A recorded analysis.
    ax : matplotlib Axes, optional
        Axes to draw in (default: a new figure).

    Returns
    -------
    matplotlib Axes
        The axes of the displacements (the rotation is on their twin).
    """
    ax = _axes(ax)
    t = history.times
    ax.plot(t, history.crown_drop, label="crown drop [m]", color="tab:blue")
    ax.plot(t, history.openings.max(axis=1), label="largest joint opening [m]",
            color="tab:orange")
    ax.plot(t, np.abs(history.slips).max(axis=1), label="largest slip [m]", color="tab:green")
    ax.set_xlabel("t [s]")
    ax.set_ylabel("displacement [m]")
    twin = ax.twinx()
    twin.plot(t, np.abs(history.rotations).max(axis=1), color="0.3", linestyle="--",
              label="largest rotation [rad]")
    twin.set_ylabel("largest block rotation [rad]")
    outcome = history.outcome
    if np.isfinite(outcome.decision_time):
        ax.axvline(outcome.decision_time, color="black", linewidth=0.8, linestyle=":")
    lines = ax.get_lines()[:3] + twin.get_lines()
    ax.legend(lines, [line.get_label() for line in lines], loc="upper left", fontsize=8)
    ax.set_title(f"{history.motion_name}: {outcome.status.label}")
    return ax


def plot_block_energy(history: BlockHistory, ax=None):
    """Kinetic, potential and dissipated energy and the input work [J/m] against time [s].

    Parameters
    ----------
    history : BlockHistory
        A recorded analysis (energies: module docstring of
        :mod:`archquake.rigid_blocks.solver`).
    ax : matplotlib Axes, optional
        Axes to draw in (default: a new figure).

    Returns
    -------
    matplotlib Axes
    """
    ax = _axes(ax)
    t = history.times
    for values, label in ((history.kinetic_energy, "kinetic"),
                          (history.potential_energy, "potential"),
                          (history.dissipated_energy, "dissipated by the contacts"),
                          (history.input_work, "work of the ground motion")):
        ax.plot(t, values, label=label)
    ax.set_xlabel("t [s]")
    ax.set_ylabel("energy per unit depth [J/m]")
    ax.legend(fontsize=8)
    return ax


MAX_ANIMATION_FRAMES = 600
"""Most frames of an animation of the blocks (30 s at 20 frames per second, a minute or so to
draw): a longer history is played faster, so a record of minutes does not take hours."""


def animate_blocks(history: BlockHistory, path, *, fps: int = 20, speed: float = 1.0,
                   dpi: int = 80, max_frames: int = MAX_ANIMATION_FRAMES) -> Path:
    """Write an animated GIF of the blocks moving [real time / ``speed``].

    At most ``max_frames`` frames are drawn: a history that would need more at ``speed`` is
    played faster, with a warning that says how fast.

    Parameters
    ----------
    history : BlockHistory
        A recorded analysis.
    path : str or Path
        The GIF file.
    fps : int
        Frames per second of the animation [1/s] (1 .. 60).
    speed : float
        Simulated seconds per second of animation [-] (> 0); the frames are the records
        nearest to every ``speed / fps`` seconds.
    dpi : int
        Resolution of the frames [dots per inch].
    max_frames : int
        Most frames drawn (:data:`MAX_ANIMATION_FRAMES`).

    Returns
    -------
    Path
        The file written.

    Raises
    ------
    ValueError
        If ``fps`` or ``speed`` is out of range, the history holds no records, or the file
        cannot be written.
    """
    from matplotlib.animation import FuncAnimation, PillowWriter

    if isinstance(fps, bool) or int(fps) != fps or not 1 <= fps <= 60:
        raise ValueError(f"fps must be an integer in 1 .. 60, got {fps!r}")
    if not (np.isfinite(speed) and speed > 0):
        raise ValueError(f"speed must be > 0 (simulated seconds per second), got {speed!r}")
    if history.times.size == 0:
        raise ValueError("the history holds no records")
    if isinstance(max_frames, bool) or int(max_frames) != max_frames or max_frames < 2:
        raise ValueError(f"max_frames must be an integer >= 2, got {max_frames!r}")
    t = history.times
    span = float(t[-1] - t[0])
    fastest = span * fps / (max_frames - 1)  # the speed that draws max_frames frames
    if fastest > speed:
        warnings.warn(f"the animation of {span:.4g} s plays at {fastest:.3g} times real time "
                      f"(at most {max_frames} frames at {int(fps)} per second)", stacklevel=2)
        speed = fastest
    frames = np.searchsorted(t, np.arange(t[0], t[-1] + 1e-12, speed / fps)[:max_frames])
    frames = np.unique(np.clip(frames, 0, t.size - 1))
    fig, ax = plt.subplots(figsize=(6.4, 4.0))
    plot_blocks(history, t[0], ax)
    polys = ax.collections[0]
    title = ax.set_title("")

    def draw(k):
        polys.set_verts(history.outlines(int(k)))
        title.set_text(f"{history.motion_name}   t = {t[int(k)]:.2f} s")
        return polys, title

    path = Path(path)
    try:
        FuncAnimation(fig, draw, frames=frames, blit=False).save(
            path, writer=PillowWriter(fps=int(fps)), dpi=dpi)
    except OSError as exc:
        raise ValueError(f"cannot write the animation {str(path)!r}: {exc.strerror}") from exc
    finally:
        plt.close(fig)
    return path
