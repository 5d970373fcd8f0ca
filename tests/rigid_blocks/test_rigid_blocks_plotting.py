"""Figures of the rigid-block model: the drawn blocks are the computed ones."""

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from archquake.geometry import GRAVITY  # noqa: E402
from archquake.ground_motion import oppenheim_pulse  # noqa: E402
from archquake.rigid_blocks import simulate_blocks  # noqa: E402
from archquake.rigid_blocks.plotting import (  # noqa: E402
    animate_blocks,
    plot_block_energy,
    plot_block_history,
    plot_blocks,
)


def polygon_centroid(points):
    x, y = points[:-1, 0], points[:-1, 1]
    xn, yn = np.roll(x, -1), np.roll(y, -1)
    cross = x * yn - xn * y
    area = cross.sum() / 2
    return np.array([((x + xn) * cross).sum(), ((y + yn) * cross).sum()]) / (6 * area)


@pytest.fixture(scope="module")
def history(nominal):
    return simulate_blocks(nominal, oppenheim_pulse(-0.6 * GRAVITY, 0.5), record_every=10)


def test_drawn_blocks_are_the_moved_voussoirs(history, nominal):
    """Each drawn polygon is its voussoir's outline moved rigidly: its area centroid is the
    voussoir's centroid (annular-sector formula of the geometry, to the outline's chords)
    plus the computed displacement, and its size is unchanged."""
    ax = plot_blocks(history, history.outcome.collapse_time)
    k = int(np.argmin(np.abs(history.times - history.outcome.collapse_time)))
    drawn = ax.collections[0].get_paths()
    assert len(drawn) == nominal.n_voussoirs
    for i, path in enumerate(drawn):
        moved = path.vertices
        expected = nominal.centroids[i] + history.displacements[k, i]
        np.testing.assert_allclose(polygon_centroid(moved), expected, atol=2e-3)
        original = nominal.outline(i)
        assert np.ptp(np.linalg.norm(moved[:-1] - moved[0], axis=1)) == pytest.approx(
            np.ptp(np.linalg.norm(original[:-1] - original[0], axis=1)), rel=1e-9)
    plt.close(ax.figure)


def test_history_and_energy_plots_return_their_axes(history):
    for plot in (plot_block_history, plot_block_energy):
        fig, ax = plt.subplots()
        assert plot(history, ax) is ax
        assert len(ax.get_lines()) >= 3
        plt.close(fig)


def test_animation_options_are_checked(history, tmp_path):
    with pytest.raises(ValueError, match="fps"):
        animate_blocks(history, tmp_path / "a.gif", fps=0)
    with pytest.raises(ValueError, match="speed"):
        animate_blocks(history, tmp_path / "a.gif", speed=-1.0)
    path = animate_blocks(history, tmp_path / "a.gif", fps=4, speed=4.0, dpi=40)
    assert path.read_bytes()[:6] == b"GIF89a"


def test_a_long_history_is_animated_in_at_most_max_frames(history, tmp_path):
    """A history that would need more frames than the cap at real time is played faster, with
    a warning that says how fast: the frames of the GIF are the cap (a 700 s record took
    hours to draw)."""
    from PIL import Image

    span = float(history.times[-1] - history.times[0])
    with pytest.warns(UserWarning, match=r"plays at .* times real time \(at most 6 frames"):
        path = animate_blocks(history, tmp_path / "a.gif", fps=20, dpi=20, max_frames=6)
    with Image.open(path) as gif:
        assert gif.n_frames == 6
    assert span * 20 > 6  # real time would have needed more
