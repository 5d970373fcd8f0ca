"""The paper's model: the arch as a four-link mechanism that rocks on four hinges.

The chain of the paper [1]_ from an arch to its dynamics: the four-bar linkage
(:mod:`.linkage`), the mechanisms built on the limit analysis' hinges and their potential energy
(:mod:`.mechanism`, eqs. (3)-(4)), Lagrange's equations of motion (:mod:`.equations_of_motion`,
eqs. (5)-(7)), the impacts between Mech-l and Mech-r and their coefficients of restitution
(:mod:`.impact`, eq. (8)), the compiled engine that integrates them (:mod:`.engine`: tables,
DOP853, the driver) and time histories (:mod:`.time_history`). :class:`FourLinkModel`
(:mod:`.model`) is the front door of the model: everything one arch needs, built once. It
satisfies :class:`archquake.models.StructuralModel`, as the rigid-block model
(:mod:`archquake.rigid_blocks`, front door :mod:`archquake.rigid_blocks.model`)
does.

References
----------
.. [1] The paper, Sects. 3-5.
"""

from .model import FourLinkModel

__all__ = ["FourLinkModel"]
