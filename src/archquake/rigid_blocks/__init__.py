"""A second model of the arch: every voussoir a rigid block, contacts with Coulomb friction.

Nonsmooth contact dynamics (Moreau-Jean time stepping, Newton impact law with restitution 0,
projected Gauss-Seidel) of the blocks of an arch on two supports that move with the ground. It
shares with the rest of archquake only the geometry (any :class:`archquake.geometry.BlockArch`,
read by :func:`from_arch`) and the ground motions (:mod:`archquake.ground_motion`), not the
four-link equations of motion, so that it can check them.

:class:`RigidBlockModel` is the model's front door (the protocol of :mod:`archquake.models`);
its failure domain and fragility studies are those of :mod:`archquake.studies`, as for the
four-link model. Modules: :mod:`.assembly` (blocks and joints), :mod:`.model` (the front door),
:mod:`.solver` (the compiled scheme: its driver), by stage of a step :mod:`.contacts` (the
contact geometry), :mod:`.contact_problem` (the impulses of a step; :mod:`.lemke` its fallback)
and :mod:`.band` (the band solvers of its linear systems), :mod:`.dynamics` (analyses, their
outcome criteria and results), :mod:`.impacts` (the impact of a closing structure and its
equivalent coefficient of restitution), :mod:`.plotting` (figures and animations; a leaf,
imported on demand).
"""

from .assembly import (
    GROUND,
    Assembly,
    from_arch,
    from_block_assembly,
    rectangular_block,
)
from .dynamics import (
    MAX_BLOCKS,
    BlockHistory,
    BlockOutcome,
    BlockSettings,
    block_outcome,
    simulate_blocks,
)
from .model import RigidBlockModel

__all__ = [
    "GROUND", "MAX_BLOCKS", "Assembly", "BlockHistory", "BlockOutcome", "BlockSettings",
    "RigidBlockModel", "block_outcome", "from_arch", "from_block_assembly", "rectangular_block",
    "simulate_blocks",
]
