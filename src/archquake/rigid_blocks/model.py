"""The rigid-block model of one structure, behind the protocol both models satisfy.

:class:`RigidBlockModel` holds a structure (any :class:`~archquake.geometry.BlockArch`, or an
:class:`~archquake.rigid_blocks.assembly.Assembly`) and the :class:`BlockSettings` of its
analyses, and answers as :class:`archquake.fourlink.FourLinkModel` does: an outcome
(:meth:`RigidBlockModel.outcome`), a time history (:meth:`RigidBlockModel.simulate`) and a grid
of pulses (:meth:`RigidBlockModel.outcomes`), so that a study written against
:class:`archquake.models.StructuralModel` runs either model. It imports nothing of the four-link
model.

>>> from archquake import GRAVITY, oppenheim
>>> from archquake.ground_motion import oppenheim_pulse
>>> model = RigidBlockModel(oppenheim())
>>> model.outcome(oppenheim_pulse(-0.3 * GRAVITY, 0.4)).status.label
'rest'
"""

from __future__ import annotations

from dataclasses import dataclass, field, fields
from typing import ClassVar

import numpy as np

from ..checks import pulse_grid
from ..constants import GRAVITY
from ..status import Status
from .assembly import Assembly
from .dynamics import (
    BlockOutcome,
    BlockSettings,
    block_outcome,
    check_time_step,
    resolved_settings,
    simulate_blocks,
    structure_assembly,
    study_time_step,
)


@dataclass(frozen=True, eq=False)
class RigidBlockModel:
    """The rigid-block model of a structure: every block rigid, contacts with Coulomb friction
    (:mod:`archquake.rigid_blocks`).

    Parameters
    ----------
    structure : BlockArch or Assembly
        The structure; an arch is converted to its :class:`Assembly` once, here (and cached on
        the arch, so that another model of the same arch shares it).
    settings : BlockSettings
        Settings of every analysis (friction, time step, outcome criteria); without a time
        step, the model takes that of the structure
        (:func:`~archquake.rigid_blocks.dynamics.structure_time_step`) and states it here.

    Attributes
    ----------
    assembly : Assembly
        The blocks and joints of the structure, built once: every analysis of the model runs on
        it, and a caller that needs the blocks asks the model for them.

    Raises
    ------
    ValueError
        If ``structure`` is neither an arch nor an Assembly, has more blocks than
        :data:`~archquake.rigid_blocks.dynamics.MAX_BLOCKS`, or ``settings`` is not a
        :class:`BlockSettings`.
    """

    structure: object
    settings: BlockSettings = field(default_factory=BlockSettings)
    assembly: Assembly = field(init=False, repr=False, compare=False)
    _cache: dict = field(default_factory=dict, init=False, repr=False, compare=False)

    name: ClassVar[str] = "rigid-blocks"
    """The model's name (:data:`archquake.models.MODELS`)."""
    grid_in_one_call: ClassVar[bool] = False
    """Every analysis is its own call: a study searches its grid."""
    counts_half_cycles: ClassVar[bool] = False
    """An outcome does not say in which half cycle the structure collapses."""
    checks_standing: ClassVar[bool] = True
    """A study checks that an arch stands before it builds the model (:meth:`check_stands`)."""

    def __post_init__(self):
        if not isinstance(self.settings, BlockSettings):
            raise ValueError(f"settings must be a BlockSettings, got "
                             f"{type(self.settings).__name__}")
        assembly = structure_assembly(self.structure)  # checks the type, converts once
        object.__setattr__(self, "assembly", assembly)
        # the step chosen from the structure unless given: the model states the one it uses
        object.__setattr__(self, "settings", resolved_settings(self.settings, assembly))

    @property
    def load_multipliers(self) -> tuple[float, float]:
        """``(k_l, k_r)``: the limit analysis' load multipliers of the structure [-] (the
        accelerations, in g, at which it starts to move toward +x and -x; the rigid-block
        model starts to move there too, within its friction): Heyman's for an arch, and for
        a block assembly (several spans, rings, a drawing) the static program of
        :func:`archquake.limit_analysis.assembly_limit` with its interfaces' own friction
        (those without any do not slide)."""
        cache = self._cache
        if "load_multipliers" not in cache:
            from ..limit_analysis import load_multipliers

            if isinstance(self.structure, Assembly):
                raise ValueError("the load multipliers need an arch (a BlockArch), not an "
                                 "Assembly")
            if hasattr(self.structure, "interfaces"):  # a BlockAssembly: its own friction
                from ..limit_analysis import assembly_multipliers

                cache["load_multipliers"] = assembly_multipliers(self.structure)
            else:
                cache["load_multipliers"] = tuple(float(k) for k in
                                                  load_multipliers(self.structure))
        return cache["load_multipliers"]

    def check_motion(self, motion) -> float:
        """Refuse a ground motion that the model's time step cannot resolve on its blocks
        (:func:`~archquake.rigid_blocks.dynamics.check_time_step` with the thickness of
        :attr:`assembly`), before any analysis.

        Parameters
        ----------
        motion : GroundMotion
            Horizontal ground acceleration [m/s^2].

        Returns
        -------
        float
            The longest step allowed [s].

        Raises
        ------
        ValueError
            Naming ``time_step``, the longest step allowed and why.
        """
        return check_time_step(self.settings.time_step, motion, self.assembly.thickness)

    @staticmethod
    def study_time_step(time_step: float | None, structure) -> float:
        """The time step of a study of ``structure`` [s]: ``time_step`` if given, else the one
        chosen from the structure (:func:`~archquake.rigid_blocks.dynamics.study_time_step`),
        what a study records before any model is built.

        Parameters
        ----------
        time_step : float or None
            The step given [s].
        structure : BlockArch or Assembly
            The (nominal) structure.

        Returns
        -------
        float
        """
        return study_time_step(time_step, structure)

    def check_stands(self) -> None:
        """Refuse, before any dynamics, an arch that cannot stand under its own weight with its
        friction (:func:`archquake.limit_analysis.standing_with_friction`): every amplitude
        would collapse it, and the lowest one scanned is no failure acceleration. An
        :class:`Assembly` is not checked.

        Raises
        ------
        archquake.errors.CannotStandError
            With the reason of the verdict.
        """
        from ..errors import CannotStandError
        from ..geometry import BlockArch
        from ..limit_analysis import standing_with_friction

        if not isinstance(self.structure, BlockArch):
            return
        verdict = standing_with_friction(self.structure, self.settings.friction)
        if not verdict.stands:
            raise CannotStandError(verdict.reason)

    def describe(self) -> dict:
        """JSON-ready name and settings of the model (what results record of it).

        Returns
        -------
        dict
            ``model`` (``"rigid-blocks"``) and every field of :class:`BlockSettings`.
        """
        return {"model": self.name,
                **{f.name: getattr(self.settings, f.name) for f in fields(self.settings)}}

    def outcome(self, motion) -> BlockOutcome:
        """Outcome under ``motion`` (:func:`~archquake.rigid_blocks.dynamics.block_outcome`).

        Parameters
        ----------
        motion : GroundMotion or None
            Horizontal ground acceleration [m/s^2]; None for a still ground.

        Returns
        -------
        BlockOutcome
        """
        return block_outcome(self.assembly, motion, self.settings)

    def simulate(self, motion, **options):
        """Time history under ``motion`` (:func:`~archquake.rigid_blocks.dynamics.simulate_blocks`).

        Parameters
        ----------
        motion : GroundMotion or None
            Horizontal ground acceleration [m/s^2]; None for a still ground.
        **options
            ``initial``, ``record_every``, ``t_end``, ``tail`` of :func:`simulate_blocks`.

        Returns
        -------
        BlockHistory
        """
        return simulate_blocks(self.assembly, motion, self.settings, **options)

    def outcomes(self, durations, amplitudes_g, motion: str = "oppenheim") -> dict:
        """Outcomes of a grid of pulses, one analysis each (amplitude 0 is rest, unanalysed).

        Parameters
        ----------
        durations : array_like
            Pulse durations t_p [s].
        amplitudes_g : array_like
            Signed amplitudes of the first pulse [g]; broadcast against ``durations``.
        motion : str
            Pulse shape, a name of :data:`archquake.ground_motion.ANALYTIC_GROUND_MOTIONS`.

        Returns
        -------
        dict of ndarray
            ``status`` (:class:`archquake.status.Status` codes, -1 for an analysis left
            undecided), ``half_cycle`` (0: the rigid-block model does not count half cycles)
            and ``collapse_time`` (when the collapse became certain [s], nan without one), of
            the broadcast shape.
        """
        from ..ground_motion import ground_motion

        d, a = pulse_grid(durations, amplitudes_g)
        status = np.full(d.shape, int(Status.REST), dtype=np.int64)
        collapse_time = np.full(d.shape, np.nan)
        for index in np.ndindex(d.shape):
            if a[index] != 0.0:
                pulse = ground_motion(motion, float(a[index]) * GRAVITY, float(d[index]))
                outcome = self.outcome(pulse)
                status[index], collapse_time[index] = int(outcome.status), outcome.collapse_time
        return {"status": status, "half_cycle": np.zeros(d.shape, dtype=np.int64),
                "collapse_time": collapse_time}


def warm_up() -> None:
    """Load the compiled rigid-block solver in this process (a worker pool's ``warm_up``): one
    short analysis of Oppenheim's arch under a 0.5 g pulse of 0.05 s."""
    from ..ground_motion import ground_motion
    from ..reference_arches import oppenheim

    block_outcome(oppenheim(), ground_motion("oppenheim", -0.5 * GRAVITY, 0.05))


def engines() -> list[tuple[str, object]]:
    """The compiled engine of the rigid-block model, ``[(name, entry point)]``
    (:mod:`archquake.compiled`): the solver's driver, whose compilation compiles the rest."""
    from ..compiled import RIGID_BLOCKS
    from .solver import run

    return [(RIGID_BLOCKS, run)]


warm_up.engines = engines  # what a pool warmed up by it compiles (archquake.compiled)


__all__ = ["RigidBlockModel", "engines", "warm_up"]
