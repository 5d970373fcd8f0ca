r"""The four-link model beside the rigid-block model: how far to trust the four-link model.

The same arch under the same pulses, in the package's two models:

- the four-link model [paper, Sects. 4-5] (:class:`archquake.fourlink.dynamics.ArchDynamics`): one
degree
  of freedom, the hinges of the limit analysis, impacts by a coefficient of restitution chosen by
  a rule (:data:`archquake.fourlink.impact.RESTITUTION_MODELS`);
- the rigid-block model (:mod:`archquake.rigid_blocks`): every voussoir a block, unilateral
  contacts with Coulomb friction at both ends of every joint, Newton impacts with restitution 0;
  any mechanism may form and change, blocks may slide.

:func:`compare_models` computes, per pulse duration t_p, the failure acceleration (the lowest
collapsing amplitude, and the recovery bands above it) of the rigid-block model
(:func:`archquake.rigid_blocks.failure.failure_curve`) and of the four-link model with each
restitution model (:meth:`archquake.fourlink.dynamics.ArchDynamics.failure_domain`), on the same
amplitude scan bisected to the same resolution, and with no extension of the scan (a failure
acceleration above the scan is reported as none, for either model).

For Oppenheim's arch under Oppenheim's pulse (``archquake compare``; the numbers are in the
README and the report) the two models agree for long pulses, where the arch falls in its first
swing, and differ for short ones, where it collapses only after impacts and the energy an impact
leaves decides: there the four-link answer depends strongly on its coefficient of restitution,
and the rigid blocks do not move on in a four-link mechanism after an impact
(:mod:`archquake.fourlink.impact`, model ``"blocks"``).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, replace

import numpy as np

from ..defaults import (
    COMPARE_AMPLITUDES_G,
    COMPARE_DURATIONS,
    COMPARE_RESOLUTION_G,
    COMPARE_RESTITUTIONS,
)
from ..geometry import BlockArch


@dataclass(frozen=True, eq=False)
class ModelComparison:
    """Failure accelerations of the rigid-block and four-link models, duration by duration.

    Attributes
    ----------
    arch : BlockArch
        The arch.
    rigid_block : FailureCurve
        The rigid-block model's outcome intervals per duration.
    four_link : dict
        ``{restitution model: FailureDomain}`` of the four-link model, in the order given.
    amplitudes_g : ndarray
        The amplitude scan of both models [g].
    resolution : float
        Bisection width of every boundary of both models [g].
    """

    arch: BlockArch
    rigid_block: object
    four_link: dict
    amplitudes_g: np.ndarray
    resolution: float

    @property
    def durations(self) -> np.ndarray:
        """Pulse durations t_p [s]."""
        return self.rigid_block.durations

    @property
    def restitution(self) -> dict[str, tuple[float, float]]:
        """``{model: (c_lr, c_rl)}``: the coefficients of restitution of the four-link runs [-]."""
        return {name: tuple(domain.restitution) for name, domain in self.four_link.items()}

    @property
    def load_multiplier(self) -> float:
        """k of the mechanism the pulse opens [-]: no model moves below ``a = k``."""
        return next(iter(self.four_link.values())).limit_multiplier

    def failure_accelerations_g(self) -> dict[str, np.ndarray]:
        """``{"rigid_block": ..., <restitution model>: ...}``: the lowest collapsing amplitude
        per duration [g] (nan: none in the scan)."""
        out = {"rigid_block": self.rigid_block.failure_accelerations_g}
        for name, domain in self.four_link.items():
            out[name] = domain.failure_accelerations_g
        return out

    def relative_differences(self) -> dict[str, np.ndarray]:
        """``{restitution model: (a_four_link - a_rigid_block) / a_rigid_block}`` per duration
        [-] (nan where either has no failure in the scan)."""
        rigid = self.rigid_block.failure_accelerations_g
        return {name: domain.failure_accelerations_g / rigid - 1.0
                for name, domain in self.four_link.items()}

    def to_list(self) -> list[dict]:
        """JSON-ready list, one entry per duration: ``duration`` [s], ``rigid_block`` and
        ``four_link`` (``{model: ...}``) failure accelerations [g] (None: none in the scan, see
        ``scanned_to``), the recovery bands above them ``recovery_above`` (``{"rigid_block":
        [[from, to], ...], "four_link": {model: [...]}}`` [g]) and ``scanned_to`` [g]."""
        out = []
        for i, rb in enumerate(self.rigid_block.slices):
            fl = {name: domain.slices[i] for name, domain in self.four_link.items()}
            out.append({
                "duration": rb.duration,
                "rigid_block": _json(rb.failure_acceleration_g),
                "four_link": {name: _json(s.failure_acceleration_g) for name, s in fl.items()},
                "recovery_above": {
                    "rigid_block": [list(b) for b in rb.recovery_above_g],
                    "four_link": {name: [list(b) for b in s.recovery_above_g]
                                  for name, s in fl.items()}},
                "scanned_to": rb.scanned_to_g,
            })
        return out


def _json(x: float):
    return None if math.isnan(x) else float(x)


def _scan(amplitudes_g) -> np.ndarray:
    from .failure_domain import check_amplitudes, inclusive_range

    if amplitudes_g is None:
        return inclusive_range(*COMPARE_AMPLITUDES_G)
    return check_amplitudes(amplitudes_g)


def _four_link(dynamics, model: str, settings):
    """``dynamics`` with restitution ``model``; ``"rigid-blocks"`` (or its former name
    ``"blocks"``) measured with the rigid-block model's ``settings`` (its friction and time step)
    when they are not the defaults."""
    from ..fourlink.impact import canonical_restitution_model
    from ..rigid_blocks import BlockSettings

    if (canonical_restitution_model(model) == "rigid-blocks" and settings is not None
            and settings != BlockSettings()):
        from ..fourlink.impact import blocks_restitution

        mech_l, mech_r = dynamics.mechanisms
        pair = (blocks_restitution(mech_l, mech_r, settings),
                blocks_restitution(mech_r, mech_l, settings))
        return replace(dynamics, restitution=pair, restitution_model=model)
    return dynamics.with_restitution(model)


def _check_curve(curve, durations, direction, motion, settings, resolution, grid) -> None:
    from ..rigid_blocks import BlockSettings
    from ..rigid_blocks.failure import FailureCurve

    if not isinstance(curve, FailureCurve):
        raise ValueError(f"rigid_block must be a FailureCurve, got {type(curve).__name__}")
    same = (curve.durations.shape == durations.shape
            and np.allclose(curve.durations, durations, rtol=0, atol=1e-12)
            and curve.direction == direction and curve.motion == motion
            and curve.settings == (BlockSettings() if settings is None else settings)
            and all(s.resolution == resolution and s.intervals[0].start == grid[0]
                    and s.scanned_to_g == grid[-1] for s in curve.slices))
    if not same:
        raise ValueError("rigid_block must be the failure curve of the same durations, "
                         "direction, motion, settings, amplitude scan and resolution")


def compare_models(arch: BlockArch, durations: Sequence[float] | None = None, *,
                   restitutions: Sequence[str] = COMPARE_RESTITUTIONS, amplitudes_g=None,
                   resolution: float = COMPARE_RESOLUTION_G, direction: str = "l",
                   motion: str = "oppenheim", settings=None, workers: int | None = None,
                   progress: bool = False, dynamics=None, rigid_block=None) -> ModelComparison:
    """Failure accelerations of the rigid-block and four-link models of ``arch`` under pulses.

    Parameters
    ----------
    arch : BlockArch
        The arch.
    durations : sequence of float, optional
        Pulse durations t_p [s] (default :data:`archquake.defaults.COMPARE_DURATIONS`).
    restitutions : sequence of str
        Restitution models of the four-link runs (default computed, link, paper, blocks).
    amplitudes_g : sequence of float, optional
        Increasing amplitude scan of both models [g] (default
        :data:`archquake.defaults.COMPARE_AMPLITUDES_G`, 0.3-3.0 g in 0.1 g steps).
    resolution : float
        Bisection width of every boundary of both models [g].
    direction : {"l", "r"}
        ``"l"``: the first pulse is ``-a g`` (opens Mech-l); ``"r"``: ``+a g``.
    motion : str
        Pulse shape (a name of :data:`archquake.ground_motion.ANALYTIC_GROUND_MOTIONS`; default
        Oppenheim's pulse).
    settings : archquake.rigid_blocks.BlockSettings, optional
        Friction, time step and outcome criteria of the rigid-block model (also those of the
        ``"blocks"`` restitution).
    workers : int, optional
        Local worker processes of the rigid-block curve, one duration per task.
    progress : bool
        Progress bar over the rigid-block durations (the long part).
    dynamics : ArchDynamics, optional
        The arch's four-link dynamics, if already built.
    rigid_block : FailureCurve, optional
        The rigid-block curve, if already computed (e.g. on another process) with the same
        durations, direction, motion, settings, scan and resolution (checked).

    Returns
    -------
    ModelComparison
    """
    from ..fourlink.dynamics import ArchDynamics
    from ..fourlink.impact import check_restitution_model
    from ..rigid_blocks.failure import failure_curve
    from .failure_domain import check_direction, check_durations

    if not isinstance(arch, BlockArch):
        raise ValueError(f"arch must be a BlockArch, got {type(arch).__name__}")
    d = check_durations(COMPARE_DURATIONS if durations is None else durations)
    grid = _scan(amplitudes_g)
    check_direction(direction)
    if not (isinstance(resolution, (int, float)) and math.isfinite(resolution)
            and resolution > 0):
        raise ValueError(f"resolution must be a finite number > 0 [g], got {resolution!r}")
    names = tuple(restitutions)
    if not names:
        raise ValueError("restitutions must name at least one restitution model")
    for name in names:
        if not isinstance(name, str):
            raise ValueError(f"restitutions must be names of restitution models, got {name!r}")
        check_restitution_model(name)
    if dynamics is None:
        dynamics = ArchDynamics.from_arch(arch)
    elif not isinstance(dynamics, ArchDynamics) or dynamics.arch is not arch:
        raise ValueError("dynamics must be the ArchDynamics of arch")
    if rigid_block is None:
        rigid_block = failure_curve(arch, d, direction=direction, motion=motion,
                                    amplitudes_g=grid, resolution=float(resolution),
                                    settings=settings, workers=workers, progress=progress)
    else:
        _check_curve(rigid_block, d, direction, motion, settings, float(resolution), grid)
    four_link = {}
    for name in names:
        four_link[name] = _four_link(dynamics, name, settings).failure_domain(
            d, grid, direction=direction, resolution=float(resolution), extend_to_g=None,
            motion=motion)
    return ModelComparison(arch, rigid_block, four_link, grid, float(resolution))


__all__ = ["ModelComparison", "compare_models"]
