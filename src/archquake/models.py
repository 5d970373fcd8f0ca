"""The protocol both dynamic models satisfy, and the one place a model is chosen by name.

archquake has two models of the same structure: the paper's four-link model
(:class:`archquake.fourlink.FourLinkModel`: the arch rocks as a four-bar linkage on the hinges
of its limit analysis, impacts by a coefficient of restitution) and the rigid-block model
(:class:`archquake.rigid_blocks.RigidBlockModel`: every block rigid, contacts with Coulomb
friction, any mechanism). Both are built once for one structure and answer the same questions
(:class:`StructuralModel`), so the failure domain, the comparison and the fragility studies
call the protocol and never know which model runs.

``model="four-link"`` or ``model="rigid-blocks"`` (:data:`MODELS`) is resolved here, by
:func:`check_model` and :func:`model_for`.

>>> from archquake import GRAVITY, oppenheim
>>> from archquake.ground_motion import oppenheim_pulse
>>> pulse = oppenheim_pulse(-GRAVITY, 0.44)             # the paper's Fig. 15b
>>> [model_for(oppenheim(), name, restitution="paper").outcome(pulse).status.label
...  for name in MODELS]
['collapse', 'collapse']
"""

from __future__ import annotations

from typing import Any, ClassVar, Protocol, runtime_checkable

from .defaults import DEFAULT_MODEL, DEFAULT_RESTITUTION, MODELS


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
    """

    name: ClassVar[str]

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


__all__ = ["DEFAULT_MODEL", "MODELS", "StructuralModel", "check_model", "model_for"]
