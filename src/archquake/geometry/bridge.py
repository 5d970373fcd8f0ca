r"""Bridges and arcades: several equal arches in a row on shared piers, as one block assembly.

The bridge is rigid blocks on piers, as Gilbert and Melbourne analyse it [1]_.

:func:`multi_span` puts ``spans`` copies of one arch (any :class:`~archquake.geometry.BlockArch`:
circular, of any shape, surveyed) side by side on ``spans + 1`` piers:

- **End piers** are those of an arch on piers (:class:`~archquake.geometry.Structure`,
  :mod:`archquake.geometry.piers`): under the first arch's left springing and the last arch's
  right one, their width measured outward from the intrados springing point; None leaves a
  fixed springing (a support on the springing joint).
- **Intermediate piers** (:func:`~archquake.geometry.piers.middle_pier_blocks`) carry the right
  springing of one arch and the left springing of the next: their faces are the verticals
  through the two intrados springing points, so the arches stand ``middle_pier.width`` apart
  (from one intrados springing point to the next) and the clear span between two piers is the
  arch's intrados chord; the top follows both springing joints and is level between their
  extrados ends. A pier narrower than its two seats (the extrados ends would cross) is refused
  with the width it needs.
- **Courses**: every pier is a stack of ``courses`` blocks of equal height; the top course
  carries the seats.

Arch :math:`k` (0-based) is the given arch translated by :math:`k\,(c + W)` along x, with
:math:`c` the horizontal distance between its two intrados springing points and :math:`W` the
intermediate pier's width.

**Blocks**, left to right: the left end pier's courses from the ground up, then for each span
its voussoirs (left to right) followed by the next pier's courses (an intermediate pier's from
the ground up, the right end pier's from the top down). With one span these are exactly the
blocks of :func:`~archquake.geometry.assembly.from_arch` of the arch on its two end piers, in the
same order, with the same supports. Every block is named (``"span 2 voussoir 3"``, ``"pier 1
course 2"``, spans and piers counted from 1 and 0 left to right, voussoirs and courses from 1):
:func:`spans_of` reads the names back.

**Supports**: a square under every pier's base (and on a fixed springing's joint), as
:func:`~archquake.geometry.assembly.from_arch` puts them.

**Interface kinds** (without friction none slides, Heyman's hypothesis [2]_): voussoir joints
``"bed"``, pier courses on each other ``"bed"``, the
arches' springings on the piers ``"bed"``, the piers' bases (and fixed springings)
``"foundation"``.

**Fill** (``fill``, a :class:`~archquake.geometry.Fill`): one level
surface over the whole bridge, :math:`d` (the cover) above the arches' crown. Over every span
it is the single arch's fill, column by column over the voussoirs
(:func:`~archquake.geometry.fill.fill_columns`, the same columns as an arch on piers under that
fill, moved span by span); over every intermediate pier, the spandrel fill between the two
arches is one more column, the rectangle from the pier's level top between the two extrados
springing points up to the surface, carried by the pier's top course. Beyond the end
springings the fill rests on the abutments and is ignored, as for one arch. A block and its
column are one body (:class:`FilledAssembly`): their weight acts through their centroid, the
horizontal load as the fill's inertia model says, so the limit analysis of one span under fill
is that of the arch on piers under fill, and the rigid-block model carries the fill as mass.
A passive reaction of the fill acts on every span's voussoirs as on the single arch's, each
toward the middle of its own span (:mod:`~archquake.geometry.fill`); the spandrel columns over
the piers offer none, and the dynamic models none at all
(:func:`~archquake.geometry.fill.check_dynamic_fill`).

**Arches of several rings** (:func:`~archquake.geometry.multi_ring`) span the same way: every
ring rests on the seat of its springing, and the fill lies on the top faces of the extrados
ring's blocks.

References
----------
.. [1] Gilbert, M. and Melbourne, C. (1994). Rigid-block analysis of masonry structures. The
   Structural Engineer 72(21), 356-361 (multi-span bridges as rigid blocks on piers).
.. [2] Heyman, J. (1966). The stone skeleton. Int. J. Solids Struct. 2, 249-279 (no tension,
   no sliding: the interfaces' default).

Examples
--------
Three spans of an 8-voussoir arch on piers of three courses:

>>> from archquake.geometry import Pier, shaped_arch
>>> arch = shaped_arch("circular", span=4.0, rise=2.0, thickness=0.4, voussoirs=8)
>>> bridge = multi_span(arch, 3, end_piers=(Pier(1.5, 3.0, 3),) * 2,
...                     middle_pier=Pier(1.5, 3.0, 3))
>>> bridge.n_blocks  # 3 x 8 voussoirs and 4 x 3 courses
36
>>> spans_of(bridge, [3, 12, 14])  # a voussoir of span 1, a pier course, one of span 2
[1, 2]
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field, replace

import numpy as np

from ..constants import GRAVITY
from .assembly import ARC_POINTS, GROUND, BlockAssembly
from .blocks import BlockArch, frozen_array
from .fill import Fill, carry_fill, fill_columns, fill_horizontal_loads
from .loads import BlockLoads
from .mass import Segment, polygon_mass_properties
from .piers import Pier, middle_pier_blocks, pier_blocks
from .structure import Structure

MAX_SPANS = 100
"""Most spans of :func:`multi_span` [-]."""

_SPAN_NAME = re.compile(r"span (\d+) ")
_RING_NAME = re.compile(r"(?:span \d+ )?ring (\d+),")
_FLIP = np.array([-1.0, 1.0])


def _check_spans(spans) -> int:
    if isinstance(spans, bool) or not isinstance(spans, int | np.integer) or not (
            1 <= spans <= MAX_SPANS):
        raise ValueError(f"spans must be an integer in [1, {MAX_SPANS}], got {spans!r}")
    return int(spans)


def _support(p_in: np.ndarray, p_out: np.ndarray, normal: np.ndarray, side: float) -> np.ndarray:
    """The square on a joint on its far side (``side`` -1 before the chain, +1 after it), as
    :func:`~archquake.geometry.assembly.from_arch` puts it."""
    d = side * float(np.hypot(*(p_out - p_in))) * normal
    return np.array([p_in, p_out, p_out + d, p_in + d])


@dataclass(frozen=True, eq=False)
class FilledAssembly:
    r"""A block assembly under a level fill: the masonry blocks, and the fill columns some of
    them carry (:func:`multi_span` with ``fill``; the model of :mod:`archquake.geometry.fill`).

    Every carrying block and its column are one rigid body (mass, centroid and moment of
    inertia by :func:`~archquake.geometry.fill.carry_fill`); its loads for the limit analysis
    (:attr:`loads`) are the weight of both through their centroid and the horizontal load the
    fill's inertia model gives (:func:`~archquake.geometry.fill.fill_horizontal_loads`). The
    assembly reads as a :class:`~archquake.geometry.BlockAssembly` (``polygons``,
    ``interfaces``, ``friction``, ``names``, ...), with the fill's mass in ``mass``,
    ``centroid`` and ``inertia``: the rigid-block model carries it so (the ``"centroid"``
    model).

    Attributes
    ----------
    blocks : BlockAssembly
        The masonry.
    fill : Fill
        The fill.
    fill_masses : array of float, shape (nb,)
        Mass of the column every block carries [kg/m] (0: none).
    fill_centroids : array of float, shape (nb, 2)
        Its centroid [m].
    fill_inertias : array of float, shape (nb,)
        Its polar moment of inertia about its centroid [kg m].
    extrados_y : array of float, shape (nb,)
        Height of the block's top below the column's centroid [m] (the ``"extrados"`` model's
        line).
    carriers : array of int
        The blocks that carry a column.
    level : float
        Height of the fill's surface [m].
    outlines : tuple of arrays
        Closed outline of every column [m], for drawing (one per carrier, in its order).
    passive, passive_y, passive_sign : array of float, shape (nb,)
        The fill's passive reaction on every block (:class:`~archquake.geometry.loads.BlockLoads`;
        none by default): the largest [N/m], the ordinate of its line [m], its direction (+1
        toward +x, -1 toward -x, 0 none).
    """

    blocks: BlockAssembly
    fill: Fill
    fill_masses: np.ndarray
    fill_centroids: np.ndarray
    fill_inertias: np.ndarray
    extrados_y: np.ndarray
    carriers: np.ndarray
    level: float
    outlines: tuple
    passive: np.ndarray | None = None
    passive_y: np.ndarray | None = None
    passive_sign: np.ndarray | None = None
    _cache: dict = field(default_factory=dict, init=False, repr=False, compare=False)

    def __post_init__(self):
        b = self.blocks
        mass, centroid, inertia = (np.array(v, dtype=float) for v in (b.mass, b.centroid,
                                                                       b.inertia))
        horizontal, horizontal_y = mass * GRAVITY, centroid[:, 1].copy()
        c = np.asarray(self.carriers, dtype=np.int64)
        m, g, j = carry_fill(mass[c], centroid[c], inertia[c], self.fill_masses[c],
                             self.fill_centroids[c], self.fill_inertias[c])
        horizontal[c], horizontal_y[c] = fill_horizontal_loads(
            mass[c], centroid[c], self.fill_masses[c], self.fill_centroids[c],
            self.extrados_y[c], self.fill.inertia)
        mass[c], centroid[c], inertia[c] = m, g, j
        for name, value in (("mass", mass), ("centroid", centroid), ("inertia", inertia)):
            value.setflags(write=False)
            self._cache[name] = value
        self._cache["loads"] = BlockLoads(mass * GRAVITY, centroid[:, 0], horizontal,
                                          horizontal_y, self.passive, self.passive_y,
                                          self.passive_sign)

    _MASONRY = ("polygons", "supports", "density", "friction", "tolerance", "kinds", "names",
                "n_blocks", "size", "interfaces", "block_name")
    """What the assembly reads of its masonry, as a :class:`~archquake.geometry.BlockAssembly`
    gives it (the fill is no block: the interfaces are the masonry's)."""

    def __getattr__(self, name: str):
        if name in FilledAssembly._MASONRY:
            return getattr(self.blocks, name)
        raise AttributeError(f"{type(self).__name__!r} object has no attribute {name!r}")

    # block and column together
    @property
    def mass(self) -> np.ndarray:
        """Mass of every block with the column it carries [kg/m], shape (nb,)."""
        return self._cache["mass"]

    @property
    def centroid(self) -> np.ndarray:
        """Centroid of every block with its column [m], shape (nb, 2)."""
        return self._cache["centroid"]

    @property
    def inertia(self) -> np.ndarray:
        """Polar moment of inertia of every block with its column about their centroid
        [kg m], shape (nb,)."""
        return self._cache["inertia"]

    @property
    def weight(self) -> np.ndarray:
        """Weight of every block with its column [N/m], shape (nb,)."""
        return self.mass * GRAVITY

    @property
    def loads(self) -> BlockLoads:
        """Loads of the limit analysis: weights through the centroids of block and column,
        horizontal loads as the fill's inertia model says (see the class)."""
        return self._cache["loads"]

    @property
    def fill_weight(self) -> float:
        """Weight of all the fill the blocks carry [N/m]."""
        return float(np.sum(self.fill_masses)) * GRAVITY

    def with_friction(self, friction) -> FilledAssembly:
        """The same assembly and fill with another friction of the masonry's interfaces."""
        return replace(self, blocks=self.blocks.with_friction(friction))

    def describe(self) -> str:
        """One line: blocks and fill."""
        return (f"{self.n_blocks} blocks carrying {self.carriers.size} fill columns; "
                f"{self.fill.describe()}")


@dataclass(frozen=True)
class _Span:
    """What :func:`multi_span` reads of the arch of one span (in the arch's own frame)."""

    voussoirs: list       # polygons, counter-clockwise [m]
    names: list           # every voussoir's name
    kinds: list           # (i, j, kind) between voussoirs, local indices
    left: np.ndarray      # left springing joint (intrados end, extrados end) [m]
    right: np.ndarray     # right springing joint [m]
    on_left: list         # voussoirs resting on the left springing
    on_right: list        # and on the right one
    friction: object      # the arch's own friction (a ring arch's), or None
    extrados: object      # what fill_columns reads: n_voussoirs, extrados(i), joints
    carriers: list        # the voussoirs under fill (local indices, extrados order)


class _FreeFaces:
    """The top faces of the extrados ring's blocks of an arch of several rings, as
    :func:`~archquake.geometry.fill.fill_columns` reads an arch: ``n_voussoirs``,
    ``extrados(i)`` (chords, left to right) and ``joints`` (the two springing joints)."""

    def __init__(self, faces: list, left: np.ndarray, right: np.ndarray):
        self._faces = faces
        self.n_voussoirs = len(faces)
        self.joints = np.array([left, right], dtype=float)

    def extrados(self, i: int) -> list:
        return self._faces[i]


def _free_chain(polygon: np.ndarray, p0: np.ndarray, p1: np.ndarray, tol: float) -> list:
    """The edges of ``polygon`` on no interface (segments ``p0``-``p1``), as Segments left to
    right: a ring arch's extrados face of a block of its outer ring."""
    start, end = polygon, np.roll(polygon, -1, axis=0)
    mid = 0.5 * (start + end)
    d = p1 - p0
    length2 = np.maximum(np.sum(d * d, axis=1), 1e-300)
    t = np.clip(np.einsum("kmi,mi->km", mid[:, None, :] - p0[None], d) / length2, 0.0, 1.0)
    near = p0[None] + t[..., None] * d[None]
    free = np.hypot(*(mid[:, None, :] - near).transpose(2, 0, 1)).min(axis=1) > tol
    firsts = np.flatnonzero(free & ~np.roll(free, 1))
    if firsts.size == 0:
        raise ValueError("a block of the outer ring has no free top face to carry fill")
    chains = []
    for first in firsts:  # the runs of free edges; the extrados is the highest (one ring: the
        run = [int(first)]  # intrados is free too)
        while free[(run[-1] + 1) % len(free)] and len(run) < len(free):
            run.append((run[-1] + 1) % len(free))
        chains.append(run)
    order = max(chains, key=lambda run: float(np.mean(mid[run, 1])))
    # a counter-clockwise outline runs along its top from right to left
    return [Segment(tuple(end[e]), tuple(start[e])) for e in reversed(order)]


def _span_of(arch, points: int) -> _Span:
    """The voussoirs, springings and extrados of the arch of a span."""
    if isinstance(arch, BlockArch):
        n = arch.n_voussoirs
        return _Span([np.asarray(arch.outline(i, points), dtype=float)[:-1] for i in range(n)],
                     [f"voussoir {i + 1}" for i in range(n)],
                     [(i, i + 1, "bed") for i in range(n - 1)],
                     np.asarray(arch.joints[0], dtype=float),
                     np.asarray(arch.joints[-1], dtype=float), [0], [n - 1], None, arch,
                     list(range(n)))
    faces = arch.interfaces
    if len(arch.supports) != 2 or not arch.names:
        raise ValueError("arch must be a BlockArch or an arch of several rings (multi_ring): "
                         "named blocks on two springing supports")
    ground = np.flatnonzero(faces.a == GROUND)
    middle = float(np.mean(np.concatenate((faces.p0[ground, 0], faces.p1[ground, 0]))))
    at_left = faces.p0[ground, 0] < middle
    left = _springing(faces.p0[ground[at_left]], faces.p1[ground[at_left]], inward=1.0)
    right = _springing(faces.p0[ground[~at_left]], faces.p1[ground[~at_left]], inward=-1.0)
    rings = [int(_RING_NAME.match(name).group(1)) for name in arch.names]
    outer = [i for i, r in enumerate(rings) if r == max(rings)]
    tol = arch.tolerance
    chains = []
    for i in outer:
        mine = (faces.a == i) | (faces.b == i)
        chains.append(_free_chain(arch.polygons[i], faces.p0[mine], faces.p1[mine], tol))
    order = np.argsort([c[0].start[0] for c in chains], kind="stable")
    return _Span([np.asarray(p, dtype=float) for p in arch.polygons], list(arch.names),
                 [tuple(k) for k in arch.kinds],
                 left, right, sorted({int(b) for b in faces.b[ground[at_left]]}),
                 sorted({int(b) for b in faces.b[ground[~at_left]]}), arch.friction,
                 _FreeFaces([chains[k] for k in order], left, right),
                 [outer[k] for k in order])


def _springing(p0: np.ndarray, p1: np.ndarray, inward: float) -> np.ndarray:
    """The springing joint (intrados end, extrados end) [m] that the foundation interfaces
    ``p0``-``p1`` of one springing cover: its two farthest points, the intrados end the one
    toward midspan (``inward`` +1: toward +x, the left springing)."""
    points = np.concatenate((p0, p1))
    gap = np.hypot(*(points[:, None, :] - points[None, :, :]).transpose(2, 0, 1))
    i, j = np.unravel_index(int(np.argmax(gap)), gap.shape)
    a, b = points[i], points[j]
    return np.array([a, b] if inward * (a[0] - b[0]) > 0 else [b, a])


def _normal(joint: np.ndarray) -> np.ndarray:
    """The unit normal of a joint whose tangent (intrados end to extrados end) it is turned by
    +90 degrees."""
    t = (joint[1] - joint[0]) / float(np.hypot(*(joint[1] - joint[0])))
    return np.array([t[1], -t[0]])


def multi_span(arch, spans: int, *, end_piers=(None, None),
               middle_pier: Pier | None = None, friction=None, fill: Fill | None = None,
               points: int = ARC_POINTS):
    r"""``spans`` arches in a row on ``spans + 1`` piers, as a block assembly (see the
    module), under a fill if given.

    Parameters
    ----------
    arch : BlockArch, BlockAssembly or sequence of BlockArch
        The arch of every span, on fixed springings and without fill: a
        :class:`~archquake.geometry.BlockArch` (circular, shaped or surveyed) or an arch of
        several rings (:func:`~archquake.geometry.multi_ring`); its density is the masonry's,
        piers included [kg/m^3]. Or one BlockArch a span, left to right, of one density (the
        irregular arches of a bridge, :meth:`~archquake.geometry.StructureSpec.arches`): each
        intermediate pier carries the right springing of the arch on its left and the left
        springing of the one on its right, ``width`` apart, so every arch after the first is
        moved, horizontally and vertically, to bring its left intrados springing point there;
        the fill's surface lies ``cover`` above the highest crown.
    spans : int
        Number of arches, in [1, :data:`MAX_SPANS`].
    end_piers : (Pier or None, Pier or None), default (None, None)
        The piers under the first arch's left springing and the last arch's right one, as
        :class:`~archquake.geometry.Structure` puts them; None: a fixed springing.
    middle_pier : Pier, optional
        The intermediate piers (rectangular): ``width`` the distance between the two intrados
        springing points each carries [m], ``height`` from the ground up to them [m], its
        courses. Needed with two spans or more.
    friction : None, float or dict
        Coulomb coefficient of the interfaces [-] (:class:`~archquake.geometry.BlockAssembly`);
        None: a ring arch's own (its ring interfaces'), else none slides.
    fill : Fill, optional
        A level fill over the whole bridge (see the module), with its passive reaction if it
        has one.
    points : int, default 24
        Points on each curved face of a voussoir (:func:`~archquake.geometry.assembly.from_arch`).

    Returns
    -------
    BlockAssembly or FilledAssembly
        Named blocks (``"pier 0 course 1"``, ``"span 1 voussoir 1"``, ``"span 2 ring 1,
        voussoir 3"``, ...); with ``fill`` a :class:`FilledAssembly`.

    Raises
    ------
    ValueError
        Naming the parameter: an arch that is not a BlockArch or an arch of rings, is on piers
        already or carries fill; spans out of range; end piers not a pair of Pier or None, or
        one that does not fit its springing; no intermediate pier with two spans or more, or one
        that is not rectangular, whose springings are not at one height, or narrower than its
        two seats (the message gives the width needed); a fill that is not a Fill.
    """
    if isinstance(arch, Structure):
        what = "carries fill" if arch.fill is not None else "is on piers already"
        raise ValueError(f"arch must be an arch on fixed springings: this one {what} (multi_span "
                         "puts the arch on its piers and under the fill of its fill argument)")
    arches = _arches(arch, spans)
    if arches is not None:
        arch = arches[0]
    if not isinstance(arch, BlockArch | BlockAssembly):
        raise ValueError(f"arch must be a BlockArch or an arch of rings (BlockAssembly), got "
                         f"{type(arch).__name__}")
    if fill is not None and not isinstance(fill, Fill):
        raise ValueError(f"fill must be a Fill or None, got {type(fill).__name__}")
    spans = _check_spans(spans)
    try:
        left, right = end_piers
    except (TypeError, ValueError):
        raise ValueError(f"end_piers must be a pair (left, right) of Pier or None, got "
                         f"{end_piers!r}") from None
    for name, pier in (("end_piers[0]", left), ("end_piers[1]", right)):
        if pier is not None and not isinstance(pier, Pier):
            raise ValueError(f"{name} must be a Pier or None, got {type(pier).__name__}")
    if spans > 1 and not isinstance(middle_pier, Pier):
        raise ValueError(f"middle_pier must be a Pier with {spans} spans (the piers between "
                         f"them), got {type(middle_pier).__name__}")
    span = _span_of(arch, points)
    density = arch.density if isinstance(arch, BlockArch) else float(arch.density[0])
    if friction is None:
        friction = span.friction
    if arches is not None:  # one arch a span: the end piers of the first and the last
        first, final = Structure(arches[0], left, None), Structure(arches[-1], None, right)
        n_left, n_right = first.n_left, final.n_right
        left_courses = [first.outline(i)[:-1] for i in range(n_left)]
        last = arches[-1].n_voussoirs
        right_courses = [final.outline(i)[:-1] for i in range(last, last + n_right)]
        first_support = _support(*first.joints[0], first.joint_normals[0], -1.0)
        last_joint, last_normal = final.joints[-1], final.joint_normals[-1]
    elif isinstance(arch, BlockArch):  # the end piers and supports of the arch on piers
        ends = Structure(arch, left, right)
        n_left, n_right = ends.n_left, ends.n_right
        left_courses = [ends.outline(i)[:-1] for i in range(n_left)]
        last = n_left + arch.n_voussoirs
        right_courses = [ends.outline(i)[:-1] for i in range(last, last + n_right)]
        first_support = _support(*ends.joints[0], ends.joint_normals[0], -1.0)
        last_joint, last_normal = ends.joints[-1], ends.joint_normals[-1]
    else:  # the same rules (Structure's) on the springing joints of the ring arch
        left_courses, right_courses = [], []
        first_support, last_joint = arch.supports[0], None
        if left is not None:
            try:
                left_courses, joints = pier_blocks(left, span.left)
            except ValueError as exc:
                raise ValueError(f"left pier: {exc}") from exc
            first_support = _support(*joints[0], _normal(joints[0]), -1.0)
        if right is not None:
            try:
                courses, joints = pier_blocks(right, span.right * _FLIP)
            except ValueError as exc:
                raise ValueError(f"right pier: {exc}") from exc
            right_courses = [(p * _FLIP)[::-1] for p in courses][::-1]
            last_joint = joints[0] * _FLIP
            last_normal = _normal(last_joint)
        n_left, n_right = len(left_courses), len(right_courses)
    each = [span] * spans if arches is None else [_span_of(a, points) for a in arches]
    offsets = [np.zeros(2)]  # every span's move [m]
    middles = []  # every intermediate pier's courses, in place
    if spans > 1:
        pitch = float(span.right[0, 0] - span.left[0, 0]) + middle_pier.width
    for k in range(spans - 1):
        here, after = each[k], each[k + 1]
        if arches is None:  # equal spans: k pitches along, the same pier moved
            offsets.append(np.array([(k + 1) * pitch, 0.0]))
            if k > 0:
                middles.append([p + offsets[k] for p in middles[0]])
                continue
        else:  # the next left intrados springing point `width` beyond this right one
            offsets.append(offsets[k] + here.right[0] - after.left[0]
                           + np.array([middle_pier.width, 0.0]))
        try:
            middles.append(middle_pier_blocks(middle_pier, here.right + offsets[k],
                                              after.left + offsets[k + 1]))
        except ValueError as exc:
            raise ValueError(f"middle_pier: {exc}") from exc

    def moved(polygon: np.ndarray, k: int) -> np.ndarray:
        return polygon if k == 0 else polygon + offsets[k]

    polygons, names, kinds = [], [], []
    starts, middle_tops = [], []

    def add(blocks, labels, chain: bool) -> range:
        """Append blocks; ``chain``: consecutive ones rest on each other (pier courses)."""
        start = len(polygons)
        polygons.extend(blocks)
        names.extend(labels)
        if chain:
            kinds.extend((i, i + 1, "bed") for i in range(start, len(polygons) - 1))
        return range(start, len(polygons))

    pier = add(left_courses, [f"pier 0 course {c + 1}" for c in range(n_left)], True)
    seat = pier[-1] if pier else None  # the block under the next arch's left springing
    for k in range(spans):
        this = each[k]
        here = add([moved(v, k) for v in this.voussoirs],
                   [f"span {k + 1} {name}" for name in this.names], False)
        starts.append(here.start)
        kinds.extend((here.start + i, here.start + j, kind) for i, j, kind in this.kinds)
        if seat is not None:
            kinds.extend((seat, here.start + i, "bed") for i in this.on_left)
        if k < spans - 1:
            middle = middles[k]
            pier = add(middle, [f"pier {k + 1} course {c + 1}" for c in range(len(middle))],
                       True)
            middle_tops.append(pier[-1])
        else:
            pier = add([moved(p, k) for p in right_courses],
                       [f"pier {spans} course {n_right - c}" for c in range(n_right)], True)
        seat = None
        if pier:
            top = pier[-1] if k < spans - 1 else pier[0]  # the right end pier runs top down
            kinds.extend((here.start + i, top, "bed") for i in this.on_right)
            seat = top

    supports = [moved(first_support, 0)]
    for k in range(spans - 1):
        base = middles[k][0]
        x0, x1 = float(base[:, 0].min()), float(base[:, 0].max())
        y = float(base[:, 1].min())
        width = x1 - x0
        supports.append(np.array([(x0, y), (x0, y - width), (x1, y - width), (x1, y)]))
    if last_joint is None:  # a ring arch on a fixed right springing: its own support
        supports.append(moved(arch.supports[1], spans - 1))
    else:
        end = last_joint if spans == 1 else last_joint + offsets[spans - 1]
        supports.append(_support(*end, last_normal, 1.0))
    blocks = BlockAssembly(tuple(polygons), density, tuple(supports), friction,
                           kinds=tuple(kinds), names=tuple(names))
    if fill is None:
        return blocks
    return _filled(blocks, fill, each, starts, middle_tops, offsets)


def _arches(arch, spans) -> list | None:
    """The arches of a bridge given one a span (:func:`multi_span`), checked; None for one
    arch."""
    if not isinstance(arch, list | tuple):
        return None
    arches = list(arch)
    if isinstance(spans, int) and not isinstance(spans, bool) and len(arches) != spans:
        raise ValueError(f"arch: {len(arches)} arches given for {spans} spans (one a span)")
    for i, a in enumerate(arches):
        if isinstance(a, Structure) or not isinstance(a, BlockArch):
            raise ValueError(f"arch[{i}] must be an arch on fixed springings without fill "
                             f"(a BlockArch), got {type(a).__name__}")
    if len({float(a.density) for a in arches}) > 1:
        raise ValueError("arch: the arches of one bridge are of one masonry (one density)")
    return arches


def _filled(blocks: BlockAssembly, fill: Fill, each: list, starts: list, middle_tops: list,
            offsets: list) -> FilledAssembly:
    """The fill over every span's voussoirs (the columns of the span's arch,
    :func:`~archquake.geometry.fill.fill_columns`, moved with it; one level surface, ``cover``
    above the highest crown) and over every intermediate pier (a rectangle from its level top
    between the two extrados springing points up to the fill's surface)."""
    nb = blocks.n_blocks
    columns_of = {}  # by span (equal spans: one)
    for span in each:
        if id(span) not in columns_of:
            columns_of[id(span)] = fill_columns(span.extrados, fill)
    level = max(columns_of[id(span)].level + offset[1]
                for span, offset in zip(each, offsets, strict=True))
    for span, offset in zip(each, offsets, strict=True):
        rise = level - (columns_of[id(span)].level + offset[1])
        if rise != 0.0:  # a lower crown: the fill of this arch with its surface at `level`
            columns_of[id(span)] = fill_columns(span.extrados,
                                                replace(fill, cover=fill.cover + rise))
    mass, centroid, inertia = np.zeros(nb), np.zeros((nb, 2)), np.zeros(nb)
    below = np.zeros(nb)
    passive, passive_y, passive_sign = np.zeros(nb), np.zeros(nb), np.zeros(nb)
    carriers, outlines = [], []
    for k, start in enumerate(starts):
        span, shift = each[k], offsets[k]
        columns = columns_of[id(span)]
        local = np.asarray(span.carriers)
        index = start + local
        mass[index] = columns.masses
        centroid[index] = columns.centroids + shift
        inertia[index] = columns.inertias
        below[index] = columns.extrados_points[:, 1] + shift[1]
        # toward the middle of this span: the single arch's, moved with its voussoirs
        passive[index], passive_sign[index] = columns.passive, columns.passive_sign
        passive_y[index] = columns.passive_y + shift[1]
        carriers.extend(index.tolist())
        outlines.extend(o + shift for o in columns.outlines)
    for k, top in enumerate(middle_tops):
        e_right = each[k].right[1] + offsets[k]
        e_left = each[k + 1].left[1] + offsets[k + 1]
        column = np.array([e_right, e_left, (e_left[0], level), (e_right[0], level)])
        _, m, c, j = polygon_mass_properties([column], np.array([fill.density]))
        mass[top], centroid[top], inertia[top] = m[0], c[0], j[0]
        below[top] = 0.5 * (e_right[1] + e_left[1])
        carriers.append(top)
        outlines.append(np.vstack((column, column[:1])))
    order = np.argsort(carriers, kind="stable")
    index = np.asarray(carriers, dtype=np.int64)[order]
    index.setflags(write=False)
    return FilledAssembly(blocks, fill, frozen_array(mass), frozen_array(centroid),
                          frozen_array(inertia), frozen_array(below), index, level,
                          tuple(outlines[i] for i in order), frozen_array(passive),
                          frozen_array(passive_y), frozen_array(passive_sign))


def spans_of(assembly: BlockAssembly, blocks) -> list[int]:
    """The spans (counted from 1) of the voussoirs among ``blocks`` (block indices) of an
    assembly built by :func:`multi_span` (read from the blocks' names); piers belong to no
    span."""
    return _numbered(assembly, blocks, _SPAN_NAME)


def rings_of(assembly, blocks) -> list[int]:
    """The rings (0 the intrados ring) of the blocks among ``blocks`` (block indices) of an arch
    of several rings (:func:`~archquake.geometry.multi_ring`) or a bridge of them
    (:func:`multi_span`), read from the blocks' names; piers belong to no ring."""
    return _numbered(assembly, blocks, _RING_NAME)


def _numbered(assembly, blocks, pattern: re.Pattern) -> list[int]:
    """The numbers that ``pattern`` reads from the names of ``blocks``, sorted, each once."""
    names = assembly.names
    found = (pattern.match(names[int(i)] if names else "") for i in blocks)
    return sorted({int(match.group(1)) for match in found if match})


def moving_blocks(result, tolerance: float = 1e-6) -> list[int]:
    """The blocks that move in the mechanism of an
    :class:`~archquake.limit_analysis.AssemblyLimit`: a corner's velocity above ``tolerance``
    [m/s] (the fastest corner moves at 1 m/s)."""
    moving = []
    for i, outline in enumerate(result.contacts.outlines):
        speed = np.hypot(*result.velocity_at(i, outline).T)
        if math.isfinite(float(speed.max())) and float(speed.max()) > tolerance:
            moving.append(i)
    return moving


__all__ = ["MAX_SPANS", "FilledAssembly", "moving_blocks", "multi_span", "rings_of",
           "spans_of"]
