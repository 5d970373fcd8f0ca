"""The protocol both dynamic models satisfy, and the one place a model is chosen by name.

archquake has two models of the same structure: the paper's four-link model
(:class:`archquake.fourlink.FourLinkModel`: the arch rocks as a four-bar linkage on the hinges
of its limit analysis, impacts by a coefficient of restitution) and the rigid-block model
(:class:`archquake.rigid_blocks.RigidBlockModel`: every block rigid, contacts with Coulomb
friction, any mechanism). Both are built once for one structure and answer the same questions
(:class:`StructuralModel`), so the failure domain, the comparison and the fragility studies
call the protocol and never know which model runs.

``model="four-link"`` or ``model="rigid-blocks"`` (:data:`MODELS`) is resolved here, by
:func:`check_model` and :func:`model_for`; :class:`ModelSpec` is the whole choice (the name and
the settings of both models) as one value, which the studies, the command line, the page and the
reports hold and ask what they need to know of the model.

>>> from archquake import GRAVITY, oppenheim
>>> from archquake.ground_motion import oppenheim_pulse
>>> pulse = oppenheim_pulse(-GRAVITY, 0.44)             # the paper's Fig. 15b
>>> [model_for(oppenheim(), name, restitution="paper").outcome(pulse).status.label
...  for name in MODELS]
['collapse', 'collapse']
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields, replace
from typing import Any, ClassVar, Protocol, runtime_checkable

from .defaults import (
    DEFAULT_COARSE_FACTOR,
    DEFAULT_FRICTION,
    DEFAULT_MODEL,
    DEFAULT_RESTITUTION,
    DEFAULT_SEARCH,
    DEFAULT_TIME_STEP,
    MODELS,
)


@runtime_checkable
class StructuralModel(Protocol):
    """What a dynamic model of one structure offers (both models satisfy it).

    Attributes
    ----------
    name : str
        ``"four-link"`` or ``"rigid-blocks"``.
    structure : BlockArch
        The structure the model describes.
    settings : object
        The model's settings (the restitution of the four-link model, the
        :class:`~archquake.rigid_blocks.BlockSettings` of the rigid blocks).
    load_multipliers : (float, float)
        ``(k_l, k_r)`` [-]: the ground accelerations, in g, that set the structure in motion.
    grid_in_one_call : bool
        Whether :meth:`outcomes` analyses a whole grid in one compiled call (then a study
        analyses every point) rather than one analysis at a time (then a study searches).
    counts_half_cycles : bool
        Whether an outcome says in which half cycle a collapse happens.
    checks_standing : bool
        Whether a study checks that an arch stands before it builds the model (a model that
        refuses such an arch when it is built needs no check).
    """

    name: ClassVar[str]
    grid_in_one_call: ClassVar[bool]
    counts_half_cycles: ClassVar[bool]
    checks_standing: ClassVar[bool]

    @property
    def structure(self) -> Any: ...

    @property
    def settings(self) -> Any: ...

    @property
    def load_multipliers(self) -> tuple[float, float]: ...

    def describe(self) -> dict:
        """JSON-ready ``{"model": name, **settings}``: what a result records of the model."""

    def outcome(self, motion) -> Any:
        """The outcome under a ground motion: a value with ``status`` (a
        :class:`~archquake.status.Status`) and ``collapsed``."""

    def simulate(self, motion, **options) -> Any:
        """The time history under a ground motion (with its ``outcome``)."""

    def outcomes(self, durations, amplitudes_g, motion: str = "oppenheim") -> dict:
        """``status`` codes and ``half_cycle`` of a grid of pulses (signed amplitudes [g])."""

    def check_motion(self, motion) -> float:
        """Refuse a ground motion the model cannot resolve; the longest step allowed [s]."""

    def check_stands(self) -> None:
        """Refuse, before any dynamics, a structure that cannot stand under its own weight
        (:class:`archquake.errors.CannotStandError`)."""


def check_model(model: str) -> str:
    """A model's name, checked (one of :data:`MODELS`).

    Parameters
    ----------
    model : str
        ``"four-link"`` or ``"rigid-blocks"``.

    Returns
    -------
    str

    Raises
    ------
    ValueError
        For any other name; the message lists the models.
    """
    if not isinstance(model, str) or model not in MODELS:
        raise ValueError(f"model must be one of {', '.join(repr(m) for m in MODELS)}, got "
                         f"{model!r}")
    return model


@dataclass(frozen=True)
class ModelSpec:
    """The choice of a model and its settings, one value: what a study, the command line, the
    page and the reports hold of the model they run.

    A study asks the spec, never the name, what to do: :meth:`build` the model of a structure,
    :meth:`resolved` its settings for the nominal structure, :meth:`check_motion` before any
    analysis, and the model's capabilities (:attr:`grid_in_one_call`, :attr:`default_search`,
    :attr:`chunk_size`, :attr:`nominal_resolution_g`, :attr:`checks_standing`,
    :meth:`screening`). A new setting of a model is a new field here, with its line in this
    docstring: :meth:`to_dict` and :meth:`from_dict` store and read every field by its name.

    Parameters
    ----------
    name : {"four-link", "rigid-blocks"}
        The model (:data:`MODELS`; default :data:`archquake.defaults.DEFAULT_MODEL`).
    restitution : str or float
        Restitution model of the four-link model
        (:func:`archquake.fourlink.impact.check_restitution_model`; default ``"computed"``);
        ignored by the rigid blocks.
    friction : float
        Coulomb friction coefficient of the rigid-block model's joints [-], >= 0 (ignored by
        the four-link model).
    time_step : float, optional
        Time step h of the rigid-block model [s] (default: chosen from the structure,
        :func:`archquake.rigid_blocks.dynamics.structure_time_step`; a study records the one
        :meth:`resolved` chooses for its nominal structure).
    coarse_factor : int
        Steps of ``time_step`` the rigid-block model takes as one while no contact starts or
        stops carrying an impulse [-], >= 1 (default 2; 1: every step at ``time_step``;
        :class:`archquake.rigid_blocks.BlockSettings`).

    Raises
    ------
    ValueError
        For an unknown model or a setting out of its range; the message names the setting.

    Examples
    --------
    >>> spec = ModelSpec("rigid-blocks", friction=0.6)
    >>> spec.to_dict()["coarse_factor"], spec.default_search
    (2, 'screened')
    >>> ModelSpec.from_dict(spec.to_dict()) == spec
    True
    """

    name: str = DEFAULT_MODEL
    restitution: str | float = DEFAULT_RESTITUTION
    friction: float = DEFAULT_FRICTION
    time_step: float | None = None
    coarse_factor: int = DEFAULT_COARSE_FACTOR

    STORED_DEFAULTS: ClassVar[dict] = {"model": DEFAULT_MODEL, "friction": DEFAULT_FRICTION,
                                       "time_step": DEFAULT_TIME_STEP, "coarse_factor": 1}
    """What :meth:`from_dict` takes for a key a stored study lacks: the value its results were
    computed with before the setting existed (before coarse steps, every step was at h)."""

    def __post_init__(self) -> None:
        from .fourlink.impact import check_restitution_model

        object.__setattr__(self, "name", check_model(self.name))
        object.__setattr__(self, "restitution", check_restitution_model(self.restitution))
        if self.name != "four-link" or (self.friction, self.time_step, self.coarse_factor) != (
                DEFAULT_FRICTION, None, DEFAULT_COARSE_FACTOR):
            # checks the friction, the time step and the coarse factor; the defaults are valid,
            # so the four-link model with them does not import the rigid blocks (a second of
            # a four-link command's start)
            _ = self.block_settings

    @property
    def model_class(self) -> type:
        """The class of the model (:class:`~archquake.fourlink.FourLinkModel` or
        :class:`~archquake.rigid_blocks.RigidBlockModel`), imported when asked."""
        if self.name == "four-link":
            from .fourlink import FourLinkModel

            return FourLinkModel
        from .rigid_blocks import RigidBlockModel

        return RigidBlockModel

    @property
    def block_settings(self):
        """The rigid-block model's settings (:class:`archquake.rigid_blocks.BlockSettings`)."""
        from .rigid_blocks import BlockSettings

        return BlockSettings(friction=self.friction, time_step=self.time_step,
                             coarse_factor=self.coarse_factor)

    @property
    def grid_in_one_call(self) -> bool:
        """Whether the model analyses a whole grid of pulses, or every level of a record, in
        one compiled call (the four-link model) rather than one analysis at a time."""
        return self.model_class.grid_in_one_call

    @property
    def default_search(self) -> str:
        """How a study searches its lines by default (:data:`archquake.defaults.DEFAULT_SEARCH`
        of the model: every point where the grid is one call, else screened)."""
        return DEFAULT_SEARCH[self.name]

    @property
    def chunk_size(self) -> int:
        """Arches per chunk of a study by default [-]: two where an arch's grid is one call,
        one where an arch is seconds of work (one per chunk balances the workers)."""
        return 2 if self.grid_in_one_call else 1

    @property
    def nominal_resolution_g(self) -> float:
        """Default bisection width of the nominal arch's failure acceleration [g]: 1e-4 g where
        analyses are cheap (one call); a rigid-block analysis costs about a thousand of them,
        and 2e-3 g, a fifth of the paper's 0.01 g step, places the step of eq. (10) on the
        grid."""
        return 1e-4 if self.grid_in_one_call else 2e-3

    @property
    def checks_standing(self) -> bool:
        """Whether a study checks that an arch stands under its own weight before building the
        model (:func:`archquake.studies.arch_sample.analysable_model`)."""
        return self.model_class.checks_standing

    @property
    def needs_nominal(self) -> bool:
        """Whether :meth:`build` takes the nominal arch (the four-link model with
        ``restitution="nominal"``)."""
        return self.name == "four-link" and self.restitution == "nominal"

    def screening(self, restitution=DEFAULT_RESTITUTION) -> ModelSpec | None:
        """The spec of the model that screens this model's searches: the four-link model (its
        grid is one call) with ``restitution``, or None for a model that is its own screen.

        Parameters
        ----------
        restitution : str or float
            Restitution model of the screening model.

        Returns
        -------
        ModelSpec or None
        """
        if self.grid_in_one_call:
            return None
        return ModelSpec("four-link", restitution=restitution)

    def engines(self) -> list[tuple[str, Any]]:
        """The compiled engine of this model, ``[(name, entry point)]``
        (:mod:`archquake.compiled`); a study adds that of its screen
        (:meth:`archquake.studies.arch_sample.StudySample.engines`).

        Returns
        -------
        list of tuple
        """
        if self.grid_in_one_call:
            from .fourlink.model import engines
        else:
            from .rigid_blocks.model import engines
        return engines()

    def resolved(self, structure) -> ModelSpec:
        """The spec with what a structure decides made explicit, as a study records it: the
        time step chosen from ``structure`` unless given
        (:meth:`archquake.rigid_blocks.RigidBlockModel.study_time_step`).

        Parameters
        ----------
        structure : BlockArch or Assembly
            The (nominal) structure.

        Returns
        -------
        ModelSpec
        """
        from .rigid_blocks import RigidBlockModel

        return replace(self, time_step=RigidBlockModel.study_time_step(self.time_step,
                                                                       structure))

    def build(self, structure, nominal=None):
        """The model of ``structure``, built once (:func:`model_for` with this spec).

        Parameters
        ----------
        structure : BlockArch
            The structure (any arch; the rigid-block model takes an Assembly too).
        nominal : BlockArch or FourLinkModel, optional
            The nominal arch, for ``restitution="nominal"`` (:attr:`needs_nominal`).

        Returns
        -------
        StructuralModel
            A :class:`~archquake.fourlink.FourLinkModel` or a
            :class:`~archquake.rigid_blocks.RigidBlockModel`.

        Raises
        ------
        ValueError
            As the model's constructor.
        """
        return model_for(structure, self.name, restitution=self.restitution, nominal=nominal,
                         block_settings=self.block_settings)

    def check_motion(self, structure, motion) -> float:
        """Refuse, before any analysis, a ground motion the model cannot resolve on
        ``structure``: the rigid blocks' time step
        (:meth:`archquake.rigid_blocks.RigidBlockModel.check_motion`); the four-link model
        takes any motion.

        Parameters
        ----------
        structure : BlockArch or Assembly
            The structure.
        motion : GroundMotion
            Horizontal ground acceleration [m/s^2].

        Returns
        -------
        float
            The longest step allowed [s] (inf for a model without a time step).

        Raises
        ------
        ValueError
            Naming ``time_step``, the longest step allowed and why.
        """
        if self.name == "four-link":
            return math.inf
        return self.model_class(structure, self.block_settings).check_motion(motion)

    def settings_text(self) -> str:
        """The settings that matter to the model, as a line of text says them: ``restitution
        'computed'`` for the four-link model, ``rigid-block model (friction 0.8, time step
        0.001 s, coarse factor 2)`` for the rigid blocks.

        Returns
        -------
        str
        """
        if self.name == "four-link":
            return f"restitution {self.restitution!r}"
        time_step = "chosen from the structure" if self.time_step is None else (
            f"{self.time_step:g} s")
        return (f"rigid-block model (friction {self.friction:g}, time step {time_step}, "
                f"coarse factor {self.coarse_factor})")

    def to_dict(self) -> dict:
        """The spec as JSON-ready data: ``model`` (the name) and every setting by its name,
        the flat keys a study stores among its settings.

        Returns
        -------
        dict
        """
        return {("model" if f.name == "name" else f.name): getattr(self, f.name)
                for f in fields(self)}

    @classmethod
    def from_dict(cls, data: dict) -> ModelSpec:
        """Inverse of :meth:`to_dict`, which also reads the settings of a stored study: other
        keys are ignored, a missing one takes :attr:`STORED_DEFAULTS` (or the field's default),
        a former restitution name the current one.

        Parameters
        ----------
        data : dict
            As :meth:`to_dict` writes it, alone or among a study's settings.

        Returns
        -------
        ModelSpec

        Raises
        ------
        ValueError
            As the constructor.
        """
        from .fourlink.impact import stored_restitution_model

        values = {}
        for f in fields(cls):
            key = "model" if f.name == "name" else f.name
            if key in data:
                values[f.name] = data[key]
            elif key in cls.STORED_DEFAULTS:
                values[f.name] = cls.STORED_DEFAULTS[key]
        if "restitution" in values:
            values["restitution"] = stored_restitution_model(values["restitution"])
        return cls(**values)


def model_spec(model=None) -> ModelSpec:
    """A :class:`ModelSpec` from what a caller gives: a spec as it is, a model's name as its
    spec with the default settings, None as the default spec.

    Parameters
    ----------
    model : ModelSpec or str or None
        The spec, or a name of :data:`MODELS`.

    Returns
    -------
    ModelSpec

    Raises
    ------
    ValueError
        For an unknown name or anything else.
    """
    if model is None:
        return ModelSpec()
    if isinstance(model, ModelSpec):
        return model
    if isinstance(model, str):
        return ModelSpec(model)
    raise ValueError(f"model must be a ModelSpec or one of {', '.join(repr(m) for m in MODELS)}, "
                     f"got {type(model).__name__}")


def screening_model(model):
    """The model that screens the searches of ``model`` (a search's coarse scan refined by its
    changes, :mod:`archquake.studies.strategies`): ``model`` itself where its grid is one call,
    else the four-link model of its structure (default restitution), whose grid is; None where
    the structure has none (not an arch, or a collapse that is no four-link mechanism).

    Parameters
    ----------
    model : StructuralModel
        The model searched.

    Returns
    -------
    StructuralModel or None
    """
    if model.grid_in_one_call:
        return model
    from .geometry import BlockArch

    if not isinstance(model.structure, BlockArch):
        return None
    try:
        return ModelSpec("four-link").build(model.structure)
    except ValueError:
        return None


def model_for(structure, model: str = DEFAULT_MODEL, *, restitution=DEFAULT_RESTITUTION,
              nominal=None, block_settings=None):
    """The model named ``model`` of ``structure``, built once.

    Parameters
    ----------
    structure : BlockArch
        The structure (any arch; the rigid-block model takes an Assembly too).
    model : str
        ``"four-link"`` (default) or ``"rigid-blocks"`` (:func:`check_model`).
    restitution : str or float
        The four-link model's restitution model
        (:func:`archquake.fourlink.impact.check_restitution_model`); ignored by the rigid blocks.
    nominal : BlockArch or FourLinkModel, optional
        The nominal arch, for ``restitution="nominal"``.
    block_settings : BlockSettings, optional
        Settings of the rigid-block analyses; ignored by the four-link model.

    Returns
    -------
    StructuralModel
        A :class:`~archquake.fourlink.FourLinkModel` or a
        :class:`~archquake.rigid_blocks.RigidBlockModel`.

    Raises
    ------
    ValueError
        For an unknown model, and as the model's constructor.
    """
    name = check_model(model)
    if name == "four-link":
        from .fourlink import FourLinkModel

        return FourLinkModel.from_arch(structure, restitution, nominal)
    from .rigid_blocks import BlockSettings, RigidBlockModel

    return RigidBlockModel(structure, BlockSettings() if block_settings is None
                           else block_settings)


__all__ = ["DEFAULT_MODEL", "MODELS", "ModelSpec", "StructuralModel", "check_model", "model_for",
           "model_spec", "screening_model"]
