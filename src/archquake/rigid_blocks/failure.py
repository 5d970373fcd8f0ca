r"""Failure accelerations of the rigid-block model under pulses (the failure curve of an arch).

For a pulse duration t_p the amplitude axis is scanned on a grid and every change of outcome
(rest, recovery, collapse) is bisected to a resolution
(:func:`archquake.studies.failure_domain.domain_slice`, the search shared with the four-link failure
domains of the paper's Sect. 5.3 [1]_; the outcome here is the rigid-block model's,
:func:`archquake.rigid_blocks.dynamics.block_outcome`). The failure acceleration is the lowest
collapsing amplitude [g],

.. math::

    a_f(t_p) = \min \{\, a \in [a_{lo}, a_{hi}] : \text{the pulse } \mp a\,g
    \text{ of duration } t_p \text{ collapses the structure} \,\}

(to the resolution of the bisection, within the scanned range); the outcome need not be
monotone in the amplitude, so the recovery bands above it are reported too. The curve
:math:`a_f(t_p)` is the rigid-block counterpart of the four-link model's, as in the comparisons
of analytical and discrete models of arches under pulses [2]_.

Direction: ``"l"`` makes the first pulse ``-a g`` (the arch sways toward +x, the four-link
model's Mech-l), ``"r"`` makes it ``+a g``. Amplitudes are given and reported in g, positive.

References
----------
.. [1] The paper, Sect. 5.3 (pulses and failure domains).

.. [2] M. J. DeJong, "Seismic assessment strategies for masonry structures", PhD thesis, MIT
   (2009).
"""

from __future__ import annotations

import math
import sys
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ..constants import GRAVITY
from ..defaults import MAX_BLOCK_GRID_POINTS
from ..ground_motion import ANALYTIC_GROUND_MOTIONS, ground_motion
from ..status import Status
from ..studies.failure_domain import DomainSlice, check_direction, domain_slice, inclusive_range
from .dynamics import BlockSettings, block_outcome, structure_assembly

DEFAULT_AMPLITUDES_G = (0.1, 3.0, 0.05)
"""Default scan of amplitudes ``(start, stop, step)`` [g]."""

DEFAULT_RESOLUTION_G = 0.005
"""Default bisection width of the boundaries [g]."""


@dataclass(frozen=True)
class FailureCurve:
    """Outcome intervals of the rigid-block model per pulse duration.

    Attributes
    ----------
    slices : tuple of DomainSlice
        One per duration: contiguous amplitude intervals [g] with status ``rest``,
        ``recovery``, ``collapse`` or ``undecided`` (an analysis that did not decide, never
        counted as a collapse: :class:`~archquake.rigid_blocks.dynamics.BlockOutcome`; half
        cycle 0: the block model does not count them).
    direction : str
        ``"l"`` (first pulse ``-a g``) or ``"r"`` (``+a g``).
    motion : str
        Pulse shape (a name of :data:`archquake.ground_motion.GROUND_MOTIONS`).
    settings : BlockSettings
        Settings of the rigid-block analyses.
    """

    slices: tuple[DomainSlice, ...]
    direction: str
    motion: str
    settings: BlockSettings

    @property
    def durations(self) -> np.ndarray:
        """Pulse durations t_p [s]."""
        return np.array([s.duration for s in self.slices])

    @property
    def failure_accelerations_g(self) -> np.ndarray:
        """Lowest collapsing amplitude per duration [g] (nan: none in the scanned range)."""
        return np.array([s.failure_acceleration_g for s in self.slices])

    def recovery_bands(self) -> list[list[tuple[float, float]]]:
        """Per duration, the recovery intervals ``(from, to)`` [g] above the failure
        acceleration (amplitudes that collapse less easily than a lower one).

        Returns
        -------
        list of list of (float, float)
            One list per duration, in the order of :attr:`durations` [g].
        """
        return [s.recovery_above_g for s in self.slices]

    def to_list(self) -> list[dict]:
        """JSON-ready list: duration [s], failure acceleration [g] (None: none), recovery
        bands above it [g] and the intervals.

        Returns
        -------
        list of dict
            One per duration, with keys ``duration``, ``failure_acceleration``,
            ``recovery_above`` and ``intervals``.
        """
        out = []
        for s, bands in zip(self.slices, self.recovery_bands(), strict=True):
            failure = s.failure_acceleration_g
            out.append({"duration": s.duration,
                        "failure_acceleration": None if math.isnan(failure) else failure,
                        "recovery_above": [list(b) for b in bands],
                        "intervals": [iv.to_dict() for iv in s.intervals]})
        return out


def _grid(amplitudes_g) -> np.ndarray:
    """The checked scan grid [g]: increasing, >= 0, at least two values (default
    :data:`DEFAULT_AMPLITUDES_G`)."""
    if amplitudes_g is None:
        return inclusive_range(*DEFAULT_AMPLITUDES_G)
    a = np.atleast_1d(np.asarray(amplitudes_g, dtype=float))
    if a.ndim != 1 or a.size < 2 or not np.all(np.isfinite(a)) or np.any(np.diff(a) <= 0):
        raise ValueError("amplitudes_g must be an increasing sequence of at least two finite "
                         "values [g]")
    if a[0] < 0:
        raise ValueError(f"amplitudes_g must be >= 0 [g] (the direction gives the sign), got "
                         f"{a[0]!r}")
    return a


def failure_slice(structure, duration: float, *, direction: str = "l",
                  motion: str = "oppenheim", amplitudes_g=None,
                  resolution: float = DEFAULT_RESOLUTION_G,
                  settings: BlockSettings | None = None) -> DomainSlice:
    """Outcome intervals of the rigid-block model over pulse amplitudes, for one duration.

    Parameters
    ----------
    structure : BlockArch or Assembly
        The structure.
    duration : float
        Pulse duration t_p [s], > 0.
    direction : {"l", "r"}
        Sign of the first pulse: ``"l"`` is ``-a g``, ``"r"`` is ``+a g``.
    motion : str
        Pulse shape, one of :data:`archquake.ground_motion.ANALYTIC_GROUND_MOTIONS`
        (default Oppenheim's pulse ``a, -a/2, 0`` [paper, Sect. 5.3.1]).
    amplitudes_g : sequence of float, optional
        Increasing scan grid of amplitudes >= 0 [g] (default 0.10, 0.15, ..., 3.00).
    resolution : float
        Bisection width of every boundary [g], > 0.
    settings : BlockSettings, optional
        Settings of every analysis (default :class:`BlockSettings`).

    Returns
    -------
    DomainSlice
        Its ``failure_acceleration_g`` is the lowest collapsing amplitude [g]; amplitude 0 is
        rest without an analysis.

    Raises
    ------
    ValueError
        If ``direction`` is not ``"l"`` or ``"r"``, ``motion`` is not an analytic pulse,
        ``duration`` is not a finite number > 0, ``resolution <= 0`` or the grid is not an
        increasing sequence of at least two finite values >= 0 [g].
    """
    sign = -1.0 if check_direction(direction) == "l" else 1.0
    if motion not in ANALYTIC_GROUND_MOTIONS:
        raise ValueError(f"motion must be one of {ANALYTIC_GROUND_MOTIONS}, got {motion!r}")
    if not (isinstance(duration, (int, float)) and math.isfinite(duration) and duration > 0):
        raise ValueError(f"duration must be a finite number > 0 [s], got {duration!r}")
    if not (isinstance(resolution, (int, float)) and resolution > 0):
        raise ValueError(f"resolution must be > 0 [g], got {resolution!r}")
    grid = _grid(amplitudes_g)
    assembly = structure_assembly(structure)

    def classify(amplitude_g: float) -> tuple[str, int]:
        if amplitude_g == 0.0:
            return Status.REST, 0
        pulse = ground_motion(motion, sign * amplitude_g * GRAVITY, float(duration))
        return block_outcome(assembly, pulse, settings).status, 0

    return domain_slice(classify, grid, duration=float(duration), resolution=float(resolution))


def _slice_task(args) -> DomainSlice:
    """:func:`failure_slice` of one ``(structure, duration, kwargs)`` task (a worker's job)."""
    structure, duration, kwargs = args
    return failure_slice(structure, duration, **kwargs)


def warm_up() -> None:
    """Load the compiled rigid-block solver (a worker's start-up): one short analysis of
    Oppenheim's arch under a 0.5 g pulse of 0.05 s."""
    from ..reference_arches import oppenheim

    block_outcome(oppenheim(), ground_motion("oppenheim", -0.5 * GRAVITY, 0.05))


def failure_curve(structure, durations: Sequence[float], *, direction: str = "l",
                  motion: str = "oppenheim", amplitudes_g=None,
                  resolution: float = DEFAULT_RESOLUTION_G, settings: BlockSettings | None = None,
                  workers: int | None = None, progress: bool = False) -> FailureCurve:
    """Failure accelerations of the rigid-block model for several pulse durations.

    Parameters
    ----------
    structure : BlockArch or Assembly
        The structure.
    durations : sequence of float
        Pulse durations t_p [s].
    direction, motion, amplitudes_g, resolution, settings
        As :func:`failure_slice`.
    workers : int, optional
        Local worker processes, one duration per task (default: run here).
    progress : bool
        Show a progress bar over the durations (on stderr).

    Returns
    -------
    FailureCurve

    Raises
    ------
    ValueError
        For bad input (as :func:`failure_slice`; ``durations`` not a non-empty sequence of
        finite numbers > 0 [s], ``workers`` not an integer >= 1), or a scan of more than
        :data:`archquake.defaults.MAX_BLOCK_GRID_POINTS` (duration, amplitude) points.
    """
    d = np.atleast_1d(np.asarray(durations, dtype=float))
    if d.ndim != 1 or d.size == 0 or not np.all(np.isfinite(d)) or np.any(d <= 0):
        raise ValueError(f"durations must be a non-empty sequence of finite numbers > 0 [s], "
                         f"got {np.asarray(durations).tolist()}")
    settings = BlockSettings() if settings is None else settings
    points = d.size * _grid(amplitudes_g).size
    if points > MAX_BLOCK_GRID_POINTS:
        raise ValueError(f"the scan of {d.size} durations x {points // d.size} amplitudes = "
                         f"{points} rigid-block analyses is too large: at most "
                         f"{MAX_BLOCK_GRID_POINTS} (MAX_BLOCK_GRID_POINTS, tens of minutes); use "
                         f"fewer durations or a coarser grid")
    kwargs = {"direction": direction, "motion": motion, "amplitudes_g": amplitudes_g,
              "resolution": resolution, "settings": settings}
    tasks = [(structure_assembly(structure), float(tp), kwargs) for tp in d]
    if workers is not None and (isinstance(workers, bool) or int(workers) != workers
                                or workers < 1):
        raise ValueError(f"workers must be an integer >= 1, got {workers!r}")
    from tqdm.auto import tqdm

    bar = tqdm(total=d.size, desc="rigid blocks", unit="duration", disable=not progress,
               file=sys.stderr)
    with bar:
        if workers is None or workers == 1 or d.size == 1:
            slices = []
            for task in tasks:
                slices.append(_slice_task(task))
                bar.update()
        else:
            from ..execution import process_pool

            with process_pool(min(int(workers), d.size), warm_up=warm_up) as pool:
                slices = []
                for s in pool.map(_slice_task, tasks):
                    slices.append(s)
                    bar.update()
    return FailureCurve(tuple(slices), direction, motion, settings)
