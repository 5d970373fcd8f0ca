"""What the commands write besides the tables of :mod:`archquake.results_io`: JSON on stdout and
figures (matplotlib on its file-only backend, imported only when a figure is asked for)."""

from __future__ import annotations

from pathlib import Path


def print_json(obj) -> None:
    """Print ``obj`` as indented strict JSON (the ``--json`` output of every command): ``null``
    where a number is nan or infinite, never ``NaN`` (:func:`archquake.checks.json_dumps`)."""
    from ..checks import json_dumps

    print(json_dumps(obj, indent=2))


def pyplot():
    """``matplotlib.pyplot`` on the file-only Agg backend (the command line opens no window)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def check_figure_path(path) -> None:
    """Refuse a figure path that is a directory or has no image extension (before a long run:
    :func:`save_figure` checks the same)."""
    from matplotlib.backend_bases import FigureCanvasBase

    formats = FigureCanvasBase.get_supported_filetypes()
    if Path(path).is_dir():
        raise ValueError(f"cannot write the figure {str(path)!r}: it is a directory")
    if Path(path).suffix.lstrip(".").lower() not in formats:
        raise ValueError(f"cannot write the figure {str(path)!r}: give a file name with an "
                         f"extension among {', '.join('.' + f for f in sorted(formats))}")


def save_figure(fig, path, **savefig_options) -> None:
    """Write ``fig`` to ``path`` (150 dpi unless told) and close it; a path that cannot be
    written is a :class:`ValueError` that names it."""
    plt = pyplot()
    options = {"dpi": 150, **savefig_options}
    try:
        check_figure_path(path)
        fig.savefig(path, **options)
    except OSError as exc:
        raise ValueError(f"cannot write the figure {str(path)!r}: {exc.strerror}") from exc
    finally:
        plt.close(fig)


def plot_directory(plot_dir) -> Path:
    """``--plot-dir`` as a Path, created if missing (a ValueError naming the option if not)."""
    directory = Path(plot_dir)
    try:
        directory.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise ValueError(f"cannot create --plot-dir {plot_dir!r}: {exc.strerror}") from exc
    return directory


def written_table(write, path, what: str):
    """Run ``write()``, which writes the file ``path``; an :class:`OSError` becomes a
    :class:`ValueError` naming ``what`` and the file (``cannot write the time history ...``)."""
    try:
        return write()
    except OSError as exc:
        raise ValueError(f"cannot write the {what} {str(path)!r}: {exc.strerror}") from exc
