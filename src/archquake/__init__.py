"""archquake: seismic response of masonry arches with geometrical irregularities.

The chain of the paper "Dynamic response of masonry arch with geometrical irregularities
subjected to a pulse-type ground motion": geometry -> limit analysis -> four-link mechanism ->
impacts -> time histories -> failure domains and fragility, and a second model of the same
structure, every block rigid with Coulomb friction (:mod:`archquake.rigid_blocks`). Both models
satisfy one protocol (:mod:`archquake.models`); :func:`model_for` builds either by name::

    from archquake import GRAVITY, model_for, oppenheim, oppenheim_pulse

    four_link = model_for(oppenheim(), "four-link", restitution="paper")
    history = four_link.simulate(oppenheim_pulse(-GRAVITY, 0.27))   # the paper's Fig. 15
    blocks = model_for(oppenheim(), "rigid-blocks")
    outcome = blocks.outcome(oppenheim_pulse(-GRAVITY, 0.27))

The names below are imported on first use (PEP 562), so that ``import archquake`` stays cheap.
"""

from ._version import __version__
from .constants import GRAVITY

# name -> module that defines it (imported on first use)
_LAZY = {
    "FourLinkModel": "fourlink.model",
    "RigidBlockModel": "rigid_blocks.model",
    "StructuralModel": "models",
    "MODELS": "models",
    "ModelSpec": "models",
    "model_for": "models",
    "BlockArch": "geometry",
    "CircularArch": "geometry",
    "circular_arch": "geometry",
    "irregular_arch": "geometry",
    "load_arch": "geometry",
    "shaped_arch": "geometry",
    "surveyed_arch": "geometry",
    "oppenheim": "reference_arches",
    "oppenheim_pulse": "ground_motion",
    "Status": "status",
}


def __getattr__(name: str):
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module 'archquake' has no attribute {name!r}")
    from importlib import import_module

    value = getattr(import_module(f".{module}", __name__), name)
    globals()[name] = value
    return value


def __dir__():
    return sorted([*globals(), *_LAZY])


__all__ = ["GRAVITY", "MODELS", "BlockArch", "CircularArch", "FourLinkModel", "ModelSpec",
           "RigidBlockModel", "Status", "StructuralModel", "circular_arch", "irregular_arch",
           "load_arch", "model_for", "oppenheim", "oppenheim_pulse", "shaped_arch",
           "surveyed_arch", "__version__"]
