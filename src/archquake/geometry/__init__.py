r"""Arch geometry: rigid blocks and the joints between them, for an arch of any shape.

The definitions below are a contract: every step of archquake (limit analysis, mechanisms,
impacts, the rigid-block model, plots) reads an arch only through them.

**An arch** is a sequence of ``n`` rigid blocks (voussoirs) between two fixed springings and a
sequence of ``n + 1`` joints (:class:`BlockArch`):

- Voussoirs are numbered left to right ``0 .. n-1``; joints ``0 .. n``; joint 0 is the contact
  of voussoir 0 with the left support, joint ``n`` that of voussoir ``n-1`` with the right
  support; voussoir ``i`` lies between joints ``i`` and ``i+1``.
- Every block is a planar region with exact mass properties per unit depth (out of plane): mass
  [kg/m], centroid [m], polar moment of inertia about the centroid [kg m], for a density
  [kg/m^3] (:mod:`.mass`).
- Every joint is a segment where neighbours touch, given by its *intrados end* and its
  *extrados end* [m]; its normal points along the arch, from voussoir ``j-1`` into voussoir
  ``j``, and the extrados end is the intrados end moved along that normal turned by +90
  degrees. Hinges form at the ends (:class:`Hinge`). A joint's *progressive angle* is the
  direction from its intrados to its extrados end, :math:`(-\cos\beta, \sin\beta)`: for the
  radial joints of a circle it is the paper's progressive angle (Fig. 1a of [1]_).
- Frame: x to the right, y up; units m, rad, kg.

Three kinds of arch keep the contract:

- :class:`CircularArch` (:mod:`.arch`): the paper's circular arch, voussoirs that are annular
  sectors with radial joints, each with its own angle, thickness and mean radius [1]_; in the
  frame of
  the circle's centre O at the origin (the springings of a symmetric arch at
  :math:`y = R\cos\beta_0`). :func:`circular_arch` builds the nominal arch, as in the paper.
- :class:`ShapedArch` (:mod:`.shaped`): any of the shapes of :mod:`.centrelines` (circular,
  pointed, elliptical, parabolic, catenary, three-centred) by the span and rise of its
  centreline, in the frame of its springings (on y = 0, midspan at x = 0): thickness normal to
  the centreline, voussoirs of equal centreline arc length, joints normal to the centreline
  (a vertical crown joint for a pointed arch), faces ``"curved"`` (the intrados and extrados
  offset curves) or ``"flat"`` (chords). :func:`shaped_arch` builds it.
- :class:`SurveyedArch` (:mod:`.survey`): blocks given as polygons, joints found where
  neighbours touch; :func:`surveyed_arch` builds it.

Any of them may stand on piers or buttresses and carry fill: a :class:`Structure`
(:mod:`.structure`) is the chain of the piers' courses (:class:`Pier`, :mod:`.piers`) and the
arch's voussoirs, each voussoir carrying its column of fill (:class:`Fill`, :mod:`.fill`), and
keeps the same contract; :func:`arch_on_piers` builds it. Every block's loads in the limit
analysis are a :class:`BlockLoads` (:mod:`.loads`).

Irregular arches (:func:`irregular_arch`, :func:`irregular_sample`, :mod:`.irregular`) follow the
paper's eq. (1) on a circular :class:`CircularArch` and its generalisation on any
:class:`ShapedArch`. :func:`load_arch` reads a JSON file of any of the three kinds, and
:func:`arch_from_dict` the same description as a dict. A structure described by named values
(a shape, piers, a fill, an irregular draw), as the command line and the page describe one, is a
:class:`StructureSpec` (:mod:`.spec`).

**Any block assembly** -- a wall of any bond, a portal, a drawing, an arch -- is a
:class:`BlockAssembly` (:mod:`.assembly`): blocks as polygons on supports, with the
interfaces between them found from the geometry (:class:`Interfaces`); builders
(:func:`block_on_ground`, :func:`stack`, :func:`wall`, :func:`portal`,
:func:`assembly.from_arch <archquake.geometry.assembly.from_arch>` for any arch) and DXF
drawings (:func:`read_dxf`, :func:`write_dxf`, :mod:`.dxf`) make one. An arch of several
rings that can separate (multi-ring brickwork) is one too: :func:`multi_ring` (:mod:`.rings`).

References
----------
.. [1] The paper, Sect. 2, eq. (1) and Fig. 1.

Examples
--------
Oppenheim's arch and a pointed arch of the same span and rise:

>>> import math
>>> from archquake.geometry import circular_arch, shaped_arch
>>> paper = circular_arch(10.0, math.radians(157.5), 1.5, 7)
>>> span = 2 * 10.0 * math.sin(math.radians(157.5) / 2)
>>> rise = 10.0 * (1 - math.cos(math.radians(157.5) / 2))
>>> round(span, 4), round(rise, 4)
(19.6157, 8.0491)
>>> pointed = shaped_arch("pointed", span=span, rise=1.2 * span / 2, thickness=1.5,
...                       voussoirs=8)
>>> pointed.n_voussoirs, pointed.joints.shape, pointed.is_symmetric()
(8, (9, 2, 2), True)
"""

from ..constants import DEFAULT_DENSITY, GRAVITY
from .arch import RADIUS_RANGE, CircularArch, circular_arch
from .assembly import (
    GROUND,
    INTERFACE_KINDS,
    BlockAssembly,
    Interfaces,
    block_on_ground,
    portal,
    stack,
    wall,
)
from .blocks import (
    FACES,
    LENGTH_RANGE,
    MAX_GEOMETRY_FILE_BYTES,
    MAX_VOUSSOIRS,
    MIN_VOUSSOIRS,
    BlockArch,
    Hinge,
)
from .bridge import multi_span
from .centrelines import CENTRELINES, SHAPES, Centreline, centreline
from .dxf import read_dxf, write_dxf
from .files import arch_from_dict, load_arch
from .fill import DEFAULT_FILL_INERTIA, FILL_INERTIA_MODELS, Fill
from .irregular import check_epsilon, irregular_arch, irregular_sample
from .loads import BlockLoads
from .piers import Pier
from .rings import RING_BONDS, multi_ring
from .shaped import VOUSSOIR_FACES, ShapedArch, shaped_arch
from .spec import StructureSpec
from .structure import Structure, arch_on_piers
from .survey import SurveyedArch, surveyed_arch

__all__ = [
    "CENTRELINES", "DEFAULT_DENSITY", "DEFAULT_FILL_INERTIA",
    "FACES", "FILL_INERTIA_MODELS", "GRAVITY", "GROUND", "INTERFACE_KINDS", "LENGTH_RANGE",
    "MAX_GEOMETRY_FILE_BYTES", "MAX_VOUSSOIRS", "MIN_VOUSSOIRS", "RADIUS_RANGE", "SHAPES",
    "VOUSSOIR_FACES", "BlockArch", "BlockAssembly", "BlockLoads", "Centreline", "CircularArch",
    "Fill", "Hinge", "Interfaces", "Pier", "ShapedArch", "Structure", "StructureSpec",
    "SurveyedArch", "arch_from_dict", "arch_on_piers", "block_on_ground", "centreline",
    "check_epsilon", "circular_arch", "irregular_arch", "irregular_sample", "load_arch",
    "multi_span", "portal", "read_dxf", "shaped_arch", "stack", "surveyed_arch",
    "wall", "write_dxf",
]
__all__ += ["RING_BONDS", "multi_ring"]
