r"""A general 2D block assembly: rigid blocks given as polygons, interfaces found from the geometry.

A :class:`BlockAssembly` is any planar set of rigid blocks (per unit depth) resting on fixed
supports (the ground): a wall of any bond, a portal, an arch on piers, a drawing
(:func:`archquake.geometry.dxf.read_dxf`). It holds

- ``polygons``: every block's outline, counter-clockwise [m] (given in either sense);
- ``density``: every block's density [kg/m^3];
- ``supports``: polygons of fixed bodies [m]; when none are given the ground is the lowest
  horizontal line of the blocks (below);
- ``friction``: None (nothing slides, Heyman's hypothesis [2]_), one Coulomb coefficient, or
  one per interface kind [-];

and derives the mass properties (:attr:`BlockAssembly.mass`, :attr:`~BlockAssembly.centroid`,
:attr:`~BlockAssembly.inertia`) by the polygon formulas [1]_, per unit depth with density
:math:`\rho`, from the edges :math:`(x_k, y_k) \to (x_{k+1}, y_{k+1})` about the first vertex,
:math:`c_k = x_k y_{k+1} - x_{k+1} y_k`:

.. math::

    A = \tfrac12 \sum_k c_k, \qquad
    A\,\bar x = \tfrac16 \sum_k c_k (x_k + x_{k+1}), \qquad
    J_O = \tfrac1{12} \sum_k c_k (x_k^2 + x_k x_{k+1} + x_{k+1}^2 + y_k^2 + y_k y_{k+1}
    + y_{k+1}^2),

mass :math:`\rho A` [kg/m], polar moment about the centroid :math:`\rho\,(J_O - A\,|\bar
x|^2)` [kg m].

**Interfaces** (:class:`Interfaces`) are found from the geometry: two edges of different bodies
that lie on one line (the shorter's ends within ``tolerance`` [m] of the longer's line), run in
opposite senses (as the edges of two counter-clockwise polygons that touch from outside do) and
overlap over more than ``tolerance`` give one interface, their overlap. A long bed edge under a
course of running bond touches several blocks, so it gives several interfaces; a head joint of
one course meets the middle of a bed joint of the next, so partial overlaps count. Collinear
contiguous pieces between the same two bodies (a face drawn with extra vertices) merge into one.
The normal points from body ``a`` into body ``b`` (``a`` the lower block index, or
:data:`GROUND` for a support), and the tangent ``(p1 - p0) / |p1 - p0|`` is the normal turned
by +90 degrees: the joint convention of :class:`archquake.rigid_blocks.assembly.Assembly`.
Kinds: ``"foundation"`` with a support; otherwise ``"bed"`` when the normal is within 45 degrees
of vertical (45 exactly included), ``"head"`` beyond; ``kinds`` overrides them body pair by body
pair (``"ring"`` is only ever given so, by a builder).

**The ground.** Explicit ``supports`` are fixed polygons; a block edge on a support's edge is a
foundation interface. With no supports the ground is the line :math:`y = \min y` of all blocks:
every block edge on it (both ends within ``tolerance``) rests on the ground along its length.

**Cost.** Candidate pairs of bodies come from a sort-and-sweep of their bounding boxes (widened
by ``tolerance``) along the axis on which fewer boxes overlap, :math:`O(n \log n + P)` for
:math:`P` pairs of boxes overlapping along that axis (a few per block in a wall); every edge of
a candidate pair is then tested against every edge of the other, vectorised. A running-bond wall
of 1 000 blocks takes about 0.1 s (``tests/geometry/test_assembly.py`` bounds it at 1 s).

**Refusals** (a ValueError naming the blocks, by index and, for a drawing, by the entity's
handle and layer): a polygon with fewer than three distinct vertices, a non-finite coordinate,
crossing edges or no area; blocks whose interiors overlap by more than ``tolerance`` (or a block
and a support); a block touching nothing; a group of blocks not connected to the ground; an
assembly that rests on nothing. The overlap test takes convex pieces: a convex block of at most
:data:`PIECE_VERTICES` vertices is one piece, any other block is cut into triangles (a fan for
a convex one, ear clipping otherwise). Two pieces of different bodies overlap when the
separating-axis test finds no axis among their edge normals along which they are apart: their
penetration, the least overlap of their projections, is more than ``tolerance``. For convex
blocks this is their exact penetration; for a non-convex one the penetration of its triangles is
a lower bound of the block's, so nothing that does not overlap is refused (an L-shaped block
holds a block in its notch) and an overlap is found once two triangles interpenetrate by more
than the tolerance.

References
----------
.. [1] Steger, C. (1996). On the calculation of arbitrary moments of polygons. Technical
   report FGBV-96-05, Technische Universitaet Muenchen.
.. [2] Heyman, J. (1966). The stone skeleton. Int. J. Solids Struct. 2, 249-279 (no sliding:
   infinite friction).

Examples
--------
A running-bond wall of three courses of two blocks on the ground:

>>> w = wall(3, 2, 0.4, 0.2)
>>> w.n_blocks, sorted(w.interfaces.kind.tolist()).count("bed")
(7, 8)
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .._equality import frozen_value
from ..constants import DEFAULT_DENSITY, GRAVITY
from .blocks import BlockArch, check_json_numbers, polygon_vertices
from .mass import polygon_mass_properties

GROUND = -1
"""Body index of the ground (every support) [-]; always an interface's ``a``."""

INTERFACE_KINDS = ("bed", "head", "ring", "foundation")
"""The kinds of interface, each of which may take its own friction coefficient."""

DEFAULT_TOLERANCE = 1e-6
"""Default contact tolerance as a fraction of the assembly's size (the larger extent of its
blocks) [-]: edges closer than it are in contact, overlaps smaller than it are ignored."""

BED_ANGLE = 45.0
"""Largest angle [deg] between an interface's normal and the vertical for a "bed" interface."""

_COLLINEAR = 1e-12
"""Relative cross product below which three consecutive vertices are taken to be collinear
when a polygon is cut into triangles [-]."""


def _frozen(array, dtype=float) -> np.ndarray:
    arr = np.array(array, dtype=dtype, copy=True)
    arr.setflags(write=False)
    return arr


def _cross(a, b):
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


@dataclass(frozen=True, eq=False)
class Interfaces:
    """The interfaces of an assembly, one row per straight contact segment.

    Parameters
    ----------
    a, b : array of int, shape (ni,)
        The two bodies: ``a`` a block index or :data:`GROUND`, ``b`` a block index.
    p0, p1 : array of float, shape (ni, 2)
        Ends of every interface [m].
    normal : array of float, shape (ni, 2)
        Unit normal from body ``a`` into body ``b`` [-]; ``(p1 - p0) / |p1 - p0|`` is it turned
        by +90 degrees.
    kind : array of str, shape (ni,)
        One of :data:`INTERFACE_KINDS`.
    friction : array of float, shape (ni,)
        Coulomb coefficient [-]; ``inf`` when the interface cannot slide (Heyman's hypothesis).
    """

    a: np.ndarray
    b: np.ndarray
    p0: np.ndarray
    p1: np.ndarray
    normal: np.ndarray
    kind: np.ndarray
    friction: np.ndarray

    def __post_init__(self):
        for name in ("a", "b"):
            object.__setattr__(self, name, _frozen(getattr(self, name), np.int64))
        for name in ("p0", "p1", "normal", "friction"):
            object.__setattr__(self, name, _frozen(getattr(self, name)))
        object.__setattr__(self, "kind", _frozen(self.kind, object).astype(str))
        self.kind.setflags(write=False)

    @property
    def n_interfaces(self) -> int:
        """Number of interfaces ni [-]."""
        return int(self.a.size)

    @property
    def length(self) -> np.ndarray:
        """Length of every interface [m], shape (ni,)."""
        return np.hypot(*(self.p1 - self.p0).T)

    @property
    def tangent(self) -> np.ndarray:
        """Unit tangent ``(p1 - p0) / |p1 - p0|`` of every interface [-], shape (ni, 2)."""
        return (self.p1 - self.p0) / self.length[:, None]

    def __len__(self) -> int:
        return self.n_interfaces


# ---------------------------------------------------------------------------------- validation
def _polygon(name: str, vertices) -> np.ndarray:
    """``vertices`` as a (k, 2) float array, repeated vertices dropped, or a ValueError."""
    return polygon_vertices(name, vertices)


def _signed_area(v: np.ndarray) -> float:
    return 0.5 * float(np.sum(_cross(v, np.roll(v, -1, axis=0))))


def _packed(polygons) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """``(vertices (K, 2), first (n,), count (n,), previous (K,), next (K,))`` of polygons
    stored one after the other: the index of each vertex's neighbours in its own polygon."""
    count = np.array([len(p) for p in polygons])
    first = np.concatenate(([0], np.cumsum(count)[:-1]))
    v = np.vstack(polygons)
    nxt = np.arange(len(v)) + 1
    nxt[first + count - 1] = first
    prev = np.arange(len(v)) - 1
    prev[first] = first + count - 1
    return v, first, count, prev, nxt


def _check_polygons(polygons, names: list[str]) -> tuple[np.ndarray, ...]:
    """The polygons as counter-clockwise arrays, or a ValueError naming the one that is not a
    simple polygon of positive area."""
    from .overlaps import self_intersections

    out = [_polygon(names[i], p) for i, p in enumerate(polygons)]
    if not out:
        return ()
    crossing = self_intersections(out, 1e-12)
    bad = np.flatnonzero(crossing[:, 0] >= 0)
    if bad.size:
        i = int(bad[0])
        raise ValueError(f"{names[i]} is not a simple polygon: its edges {crossing[i, 0]} "
                         f"and {crossing[i, 1]} cross or touch")
    v, first, _, _, nxt = _packed(out)
    size = (np.maximum.reduceat(v, first) - np.minimum.reduceat(v, first)).max(axis=1)
    p = v - np.repeat(v[first], [len(o) for o in out], axis=0)
    area = np.add.reduceat(_cross(p, p[nxt]), first) / 2.0
    bad = np.flatnonzero(~(np.abs(area) > 1e-12 * size * size))
    if bad.size:
        raise ValueError(f"{names[int(bad[0])]} encloses no area")
    for i in np.flatnonzero(area < 0):
        out[i] = out[i][::-1].copy()
    for o in out:
        o.setflags(write=False)
    return tuple(out)


def _check_friction(friction):
    """``friction`` as None, a float or a dict kind -> float, or a ValueError."""
    def coefficient(name, value, infinite=False):
        if isinstance(value, bool) or not isinstance(value, int | float | np.floating) or not (
                (math.isfinite(value) or (infinite and value == math.inf)) and value >= 0):
            raise ValueError(f"{name} must be a finite Coulomb coefficient >= 0 [-]"
                             f"{' (or inf: that kind does not slide)' if infinite else ''}, "
                             f"got {value!r}")
        return float(value)

    if friction is None:
        return None
    if isinstance(friction, dict):
        allowed = (*INTERFACE_KINDS, "default")
        unknown = sorted(str(k) for k in friction if k not in allowed)
        if unknown:
            raise ValueError(f"friction has unknown interface kind(s) {unknown}; allowed: "
                             f"{list(allowed)}")
        return {str(k): coefficient(f"friction[{k!r}]", v, True)
                for k, v in sorted(friction.items())}
    return coefficient("friction", friction)


def _check_kinds(kinds, n_blocks: int) -> tuple:
    """``kinds`` (a mapping (a, b) -> kind, or pairs ``(a, b, kind)``) as a sorted tuple of
    ``(min, max, kind)``, or a ValueError."""
    items = kinds.items() if isinstance(kinds, dict) else [((k[0], k[1]), k[2]) for k in kinds]
    out = {}
    for (a, b), kind in items:
        a, b = int(a), int(b)
        if kind not in INTERFACE_KINDS:
            raise ValueError(f"kinds[({a}, {b})] must be one of {list(INTERFACE_KINDS)}, got "
                             f"{kind!r}")
        if a == b or not (GROUND <= a < n_blocks and GROUND <= b < n_blocks):
            raise ValueError(f"kinds: ({a}, {b}) must pair two different bodies among "
                             f"{GROUND} (ground) .. {n_blocks - 1}")
        out[(min(a, b), max(a, b))] = str(kind)
    return tuple((a, b, k) for (a, b), k in sorted(out.items()))


# ---------------------------------------------------------------------------------- geometry
def _candidate_pairs(lo: np.ndarray, hi: np.ndarray, tol: float) -> tuple[np.ndarray, np.ndarray]:
    """Pairs ``(i, j)``, ``i < j``, of boxes ``[lo, hi]`` (n, 2) that overlap within ``tol``:
    sort and sweep along the axis on which fewer boxes overlap."""
    n = len(lo)
    best = None
    for axis in (0, 1):
        order = np.argsort(lo[:, axis], kind="stable")
        ends = np.searchsorted(lo[order, axis], hi[order, axis] + tol, side="right")
        count = np.maximum(ends - np.arange(n) - 1, 0)
        if best is None or count.sum() < best[2].sum():
            best = (axis, order, count)
    _, order, count = best
    total = int(count.sum())
    first = np.repeat(np.arange(n), count)
    second = first + 1 + np.arange(total) - np.repeat(np.cumsum(count) - count, count)
    i, j = order[first], order[second]
    keep = np.all((lo[i] <= hi[j] + tol) & (lo[j] <= hi[i] + tol), axis=1)
    i, j = i[keep], j[keep]
    return np.minimum(i, j), np.maximum(i, j)


def _products(ca: np.ndarray, cb: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """For pairs with ``ca`` and ``cb`` items: (pair, index in a, index in b) of every
    combination."""
    total = ca * cb
    pair = np.repeat(np.arange(ca.size), total)
    local = np.arange(int(total.sum())) - np.repeat(np.cumsum(total) - total, total)
    return pair, local // cb[pair], local % cb[pair]


def _ear_clipping(v: np.ndarray) -> np.ndarray:
    """Triangles (k - 2, 3, 2) covering the simple counter-clockwise polygon ``v`` (ear
    clipping, collinear vertices dropped first), O(k^2)."""
    size = float(np.ptp(v, axis=0).max())
    eps = _COLLINEAR * size * size
    turn = _cross(v - np.roll(v, 1, axis=0), np.roll(v, -1, axis=0) - v)
    v = v[np.abs(turn) > eps]
    idx = list(range(len(v)))
    triangles = []
    while len(idx) > 3:
        for m in range(len(idx)):
            i0, i1, i2 = idx[m - 1], idx[m], idx[(m + 1) % len(idx)]
            a, b, c = v[i0], v[i1], v[i2]
            if _cross(b - a, c - b) <= eps:
                continue  # a reflex (or flat) corner is no ear
            others = v[[k for k in idx if k not in (i0, i1, i2)]]
            inside = ((_cross(b - a, others - a) >= -eps) & (_cross(c - b, others - b) >= -eps)
                      & (_cross(a - c, others - c) >= -eps))
            if inside.any():
                continue
            triangles.append((a, b, c))
            del idx[m]
            break
        else:  # pragma: no cover - a simple polygon always has an ear
            raise ValueError("a polygon could not be cut into triangles")
    triangles.append(tuple(v[idx]))
    return np.array(triangles, dtype=float)


PIECE_VERTICES = 8
"""Most vertices of a convex block tested for overlap as one piece; a convex block of more, and
a non-convex block, is cut into triangles [-]."""


def _convex_pieces(polygons) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Convex pieces covering every counter-clockwise polygon: ``(pieces (T, K, 2), vertices
    of each piece (T,), pieces of each polygon (n,))``, each piece padded to K =
    :data:`PIECE_VERTICES` by repeating its last vertex. A convex polygon of at most K vertices
    is one piece (its exact overlap), a larger convex one a fan of triangles, a non-convex one
    the triangles of ear clipping."""
    v, first, count, prev, nxt = _packed(polygons)
    size = (np.maximum.reduceat(v, first) - np.minimum.reduceat(v, first)).max(axis=1)
    owner = np.repeat(np.arange(count.size), count)
    turn = _cross(v - v[prev], v[nxt] - v)
    convex = np.minimum.reduceat(turn / (size[owner] ** 2), first) >= -_COLLINEAR
    k = PIECE_VERTICES
    whole = convex & (count <= k)
    per = np.ones(count.size, dtype=int)
    cut = {}
    for i in np.flatnonzero(~whole):
        if convex[i]:
            m = np.arange(1, count[i] - 1)
            poly = polygons[i]
            tri = np.stack((np.broadcast_to(poly[0], (m.size, 2)), poly[m], poly[m + 1]), axis=1)
        else:
            tri = _ear_clipping(polygons[i])
        cut[int(i)] = np.concatenate((tri, np.repeat(tri[:, 2:], k - 3, axis=1)), axis=1)
        per[i] = len(tri)
    start = np.concatenate(([0], np.cumsum(per)[:-1]))
    pieces = np.empty((int(per.sum()), k, 2))
    vertices = np.full(int(per.sum()), 3)
    rows = start[whole]  # the whole convex polygons, vectorised
    col = np.minimum(np.arange(k)[None, :], count[whole, None] - 1)
    pieces[rows] = v[first[whole, None] + col]
    vertices[rows] = count[whole]
    for i, tri in cut.items():
        pieces[start[i]:start[i] + per[i]] = tri
    return pieces, vertices, per


def _penetration(pa: np.ndarray, na: np.ndarray, pb: np.ndarray, nb: np.ndarray) -> np.ndarray:
    """Separating-axis penetration of pairs of convex pieces ``pa``, ``pb`` (m, K, 2) of ``na``,
    ``nb`` vertices [m]: the least, over their edge normals, of the overlap of their projections
    (<= 0: apart or touching)."""
    col = np.arange(pa.shape[1])[None, :]

    def axes_of(p, n):
        nxt = np.where(col + 1 < n[:, None], col + 1, 0)
        edge = np.take_along_axis(p, nxt[..., None], axis=1) - p
        axis = np.stack((edge[..., 1], -edge[..., 0]), axis=-1)
        axis /= np.maximum(np.hypot(axis[..., 0], axis[..., 1]), 1e-300)[..., None]
        return axis, col < n[:, None]

    (aa, va), (ab, vb) = axes_of(pa, na), axes_of(pb, nb)
    axes, valid = np.concatenate((aa, ab), axis=1), np.concatenate((va, vb), axis=1)
    proj_a = np.einsum("mvd,mad->mav", pa, axes)
    proj_b = np.einsum("mvd,mad->mav", pb, axes)
    overlap = (np.minimum(proj_a.max(-1), proj_b.max(-1))
               - np.maximum(proj_a.min(-1), proj_b.min(-1)))
    return np.where(valid, overlap, np.inf).min(axis=1)


@dataclass(frozen=True)
class _Edges:
    """Every edge of every body (blocks, then supports): start, end, owner."""

    start: np.ndarray
    end: np.ndarray
    owner: np.ndarray
    first: np.ndarray
    count: np.ndarray

    @classmethod
    def of(cls, polygons) -> _Edges:
        v, first, counts, _, nxt = _packed(polygons)
        return cls(v, v[nxt], np.repeat(np.arange(counts.size), counts), first, counts)


def _contacts(edges: _Edges, a: np.ndarray, b: np.ndarray, tol: float):
    """Overlap segments of the edges of bodies ``a`` and ``b`` (paired arrays): returns
    ``(a, b, p, q, normal from a into b)`` per contact."""
    pair, ka, kb = _products(edges.count[a], edges.count[b])
    ia, ib = edges.first[a][pair] + ka, edges.first[b][pair] + kb
    pa, qa, pb, qb = edges.start[ia], edges.end[ia], edges.start[ib], edges.end[ib]
    la, lb = np.hypot(*(qa - pa).T), np.hypot(*(qb - pb).T)
    ta, tb = (qa - pa) / la[:, None], (qb - pb) / lb[:, None]
    opposite = np.einsum("ij,ij->i", ta, tb) < 0
    a_longer = la >= lb
    rp = np.where(a_longer[:, None], pa, pb)
    rt = np.where(a_longer[:, None], ta, tb)
    rl = np.where(a_longer, la, lb)
    op = np.where(a_longer[:, None], pb, pa)
    oq = np.where(a_longer[:, None], qb, qa)
    on_line = (np.abs(_cross(rt, op - rp)) <= tol) & (np.abs(_cross(rt, oq - rp)) <= tol)
    s0, s1 = np.einsum("ij,ij->i", op - rp, rt), np.einsum("ij,ij->i", oq - rp, rt)
    lo = np.maximum(np.minimum(s0, s1), 0.0)
    hi = np.minimum(np.maximum(s0, s1), rl)
    hit = np.flatnonzero(opposite & on_line & (hi - lo > tol))
    rp, rt, lo, hi = rp[hit], rt[hit], lo[hit], hi[hit]
    outward = np.column_stack((rt[:, 1], -rt[:, 0]))  # of the longer edge's body
    normal = np.where(a_longer[hit][:, None], outward, -outward)
    return (a[pair[hit]], b[pair[hit]], rp + lo[:, None] * rt, rp + hi[:, None] * rt, normal)


def _merge(a, b, p, q, normal, tol: float):
    """Merge collinear contiguous contact pieces between the same two bodies (one face drawn
    with extra vertices) into one; pieces apart by more than ``tol`` [m] stay apart."""
    if a.size < 2:
        return a, b, p, q, normal
    order = np.lexsort((b, a))
    a, b, p, q, normal = a[order], b[order], p[order], q[order], normal[order]
    start = np.concatenate(([True], (np.diff(a) != 0) | (np.diff(b) != 0)))
    group = np.cumsum(start) - 1
    single = np.bincount(group)[group] == 1
    out = [(a[single], b[single], p[single], q[single], normal[single])]
    for g in np.unique(group[~single]):
        remaining = list(np.flatnonzero(group == g))
        while remaining:
            head = remaining[0]
            n = normal[head]
            t = np.array([-n[1], n[0]])
            same = [k for k in remaining
                    if normal[k] @ n > 1 - 1e-9 and abs((p[k] - p[head]) @ n) <= tol]
            remaining = [k for k in remaining if k not in same]
            spans = sorted(sorted(((p[k] - p[head]) @ t, (q[k] - p[head]) @ t)) for k in same)
            merged = [list(spans[0])]
            for s, e in spans[1:]:
                if s <= merged[-1][1] + tol:
                    merged[-1][1] = max(merged[-1][1], e)
                else:
                    merged.append([s, e])
            m = len(merged)
            spans = np.array(merged)
            out.append((np.full(m, a[head]), np.full(m, b[head]),
                        p[head] + spans[:, :1] * t, p[head] + spans[:, 1:] * t,
                        np.tile(n, (m, 1))))
    return tuple(np.concatenate([o[k] for o in out]) for k in range(5))


# ---------------------------------------------------------------------------------- assembly
@dataclass(frozen=True, eq=False)
class BlockAssembly:
    r"""Rigid blocks given as polygons on fixed supports, interfaces found from the geometry (see
    the module). Per unit depth, SI units.

    Parameters
    ----------
    polygons : sequence of array_like (k_i, 2)
        Every block's outline [m]: at least three distinct vertices, finite, a simple polygon of
        positive area, in either sense (stored counter-clockwise; a repeated first vertex at the
        end is dropped).
    density : float or array_like (nb,), default 2000
        Density of every block [kg/m^3], finite and > 0.
    supports : sequence of array_like (k, 2), default ()
        Polygons of fixed bodies (the ground) [m], the same rules; none: the ground is the line
        ``y = min y`` of the blocks.
    friction : None, float or dict, default None
        Coulomb coefficient of the interfaces [-]: None (nothing slides: ``inf``), one value
        >= 0 for every interface, or a dict interface kind -> value (keys among
        :data:`INTERFACE_KINDS` and ``"default"`` for the kinds not listed; a kind present in
        the assembly and missing from the dict is an error naming it; a value ``inf``: that
        kind does not slide).
    tolerance : float, optional
        Contact tolerance [m], finite and > 0: edges closer than it to one line are in contact,
        overlaps and gaps smaller than it are ignored. Default :data:`DEFAULT_TOLERANCE` (1e-6)
        times the assembly's size (the larger extent of its blocks).
    kinds : dict (a, b) -> str, or sequence of (a, b, kind), default ()
        The kind of the interfaces between bodies ``a`` and ``b`` (block indices, or
        :data:`GROUND`), overriding the kind found from the geometry; stored as sorted
        ``(min, max, kind)`` triples.
    names : sequence of str, default ()
        How each block is named in error messages besides its index (e.g. a drawing's entity
        handle and layer); not compared.
    support_names : sequence of str, default ()
        The same for the supports.

    Raises
    ------
    ValueError
        Naming the block (see the module's refusals), or the parameter out of its range.

    Examples
    --------
    Housner's block, 0.2 m x 1 m, on the ground:

    >>> block = block_on_ground(0.2, 1.0)
    >>> float(block.mass[0]), round(float(block.inertia[0]), 9)  # 2000 * 0.2, 400 (0.04 + 1) / 12
    (400.0, 34.666666667)
    >>> block.interfaces.kind.tolist(), block.interfaces.p0.tolist()
    (['foundation'], [[0.1, 0.0]])
    """

    polygons: tuple
    density: np.ndarray | float = DEFAULT_DENSITY
    supports: tuple = ()
    friction: float | dict | None = None
    tolerance: float | None = None
    kinds: tuple = ()
    names: tuple = field(default=(), compare=False)
    support_names: tuple = field(default=(), compare=False)
    _cache: dict = field(default_factory=dict, init=False, repr=False, compare=False, hash=False)

    def __post_init__(self):
        try:
            polygons = list(self.polygons)
            supports = list(self.supports)
        except TypeError as exc:
            raise ValueError("polygons and supports must be sequences of polygons "
                             "[[x, y], ...] [m]") from exc
        if not polygons:
            raise ValueError("an assembly needs at least one block (polygons is empty)")
        nb = len(polygons)
        names = tuple(str(n) for n in self.names)
        if names and len(names) != nb:
            raise ValueError(f"names must name the {nb} blocks, got {len(names)}")
        support_names = tuple(str(n) for n in self.support_names)
        if support_names and len(support_names) != len(supports):
            raise ValueError(f"support_names must name the {len(supports)} supports, got "
                             f"{len(support_names)}")
        object.__setattr__(self, "names", names)
        object.__setattr__(self, "support_names", support_names)
        polygons = _check_polygons(polygons, [self.block_name(i) for i in range(nb)])
        supports = _check_polygons(supports, [self._support_name(k) for k in
                                              range(len(supports))])
        object.__setattr__(self, "polygons", polygons)
        object.__setattr__(self, "supports", supports)
        density = np.array(self.density, dtype=float) if not isinstance(self.density, bool) \
            else np.array(math.nan)
        if density.ndim == 0:
            density = np.full(nb, float(density))
        if density.shape != (nb,) or not np.all(np.isfinite(density)) or np.any(density <= 0):
            raise ValueError(f"density must be a finite number > 0 [kg/m^3], or {nb} of them "
                             f"(one per block), got {np.asarray(self.density).tolist()!r}")
        density.setflags(write=False)
        object.__setattr__(self, "density", density)
        everything = np.vstack(polygons)
        size = float(np.ptp(everything, axis=0).max())
        if self.tolerance is None:
            tolerance = DEFAULT_TOLERANCE * size
        else:
            tolerance = self.tolerance
            if isinstance(tolerance, bool) or not isinstance(tolerance, int | float) or not (
                    math.isfinite(tolerance) and 0 < tolerance < 0.01 * size):
                raise ValueError(f"tolerance must be a distance [m] > 0 and below a hundredth of "
                                 f"the assembly's size ({0.01 * size:.6g} m), got {tolerance!r}")
        object.__setattr__(self, "tolerance", float(tolerance))
        object.__setattr__(self, "kinds", _check_kinds(self.kinds, nb))
        object.__setattr__(self, "friction", _check_friction(self.friction))
        area, mass, centroid, inertia = polygon_mass_properties(polygons, density)
        for name, value in (("area", area), ("mass", mass), ("centroid", centroid),
                            ("inertia", inertia)):
            value.setflags(write=False)
            self._cache[name] = value
        self._cache["size"] = size
        self._cache["geometry"] = self._find_interfaces()
        self._cache["interfaces"] = self._with_friction_values(self.friction)

    # ------------------------------------------------------------------ names
    def block_name(self, i: int) -> str:
        """How block ``i`` is named in messages: ``"block i"`` and, for a drawing, its entity
        (``"block 3 (handle 2F, layer WALL)"``)."""
        if self.names and 0 <= i < len(self.names):
            return f"block {i} ({self.names[i]})"
        return f"block {i}"

    def _support_name(self, k: int) -> str:
        if self.support_names and 0 <= k < len(self.support_names):
            return f"support {k} ({self.support_names[k]})"
        return f"support {k}"

    def _body_name(self, body: int) -> str:
        nb = len(self.polygons)
        return self.block_name(body) if body < nb else self._support_name(body - nb)

    # ------------------------------------------------------------------ derived
    @property
    def n_blocks(self) -> int:
        """Number of blocks nb [-]."""
        return len(self.polygons)

    @property
    def size(self) -> float:
        """Larger extent of the blocks [m]."""
        return self._cache["size"]

    @property
    def area(self) -> np.ndarray:
        """Area of every block [m^2], shape (nb,)."""
        return self._cache["area"]

    @property
    def mass(self) -> np.ndarray:
        """Mass of every block per unit depth [kg/m], shape (nb,)."""
        return self._cache["mass"]

    @property
    def centroid(self) -> np.ndarray:
        """Centroid of every block [m], shape (nb, 2)."""
        return self._cache["centroid"]

    @property
    def inertia(self) -> np.ndarray:
        """Polar moment of inertia of every block about its centroid, per unit depth [kg m],
        shape (nb,)."""
        return self._cache["inertia"]

    @property
    def weight(self) -> np.ndarray:
        """Weight of every block per unit depth, ``mass * g`` [N/m], shape (nb,)."""
        return self.mass * GRAVITY

    @property
    def interfaces(self) -> Interfaces:
        """The interfaces found from the geometry (see the module)."""
        return self._cache["interfaces"]

    # ------------------------------------------------------------------ interfaces
    def _find_interfaces(self):
        nb, tol = self.n_blocks, self.tolerance
        bodies = (*self.polygons, *self.supports)
        lo = np.array([p.min(axis=0) for p in bodies])
        hi = np.array([p.max(axis=0) for p in bodies])
        i, j = _candidate_pairs(lo, hi, tol)
        keep = i < nb  # two supports never make an interface
        i, j = i[keep], j[keep]
        self._check_overlaps(bodies, i, j)
        edges = _Edges.of(bodies)
        a, b, p, q, normal = _contacts(edges, i, j, tol)
        support = b >= nb  # the support is the higher index: it becomes a = GROUND
        a, b = np.where(support, GROUND, a), np.where(support, a, b)
        normal = np.where(support[:, None], -normal, normal)
        if not self.supports:
            a, b, p, q, normal = self._ground_line(edges, a, b, p, q, normal)
        a, b, p, q, normal = _merge(a, b, p, q, normal, tol)
        tangent = np.column_stack((-normal[:, 1], normal[:, 0]))
        flip = np.einsum("ij,ij->i", q - p, tangent) < 0
        p, q = np.where(flip[:, None], q, p), np.where(flip[:, None], p, q)
        order = np.lexsort((p[:, 0], p[:, 1], b, a))
        a, b, p, q, normal = a[order], b[order], p[order], q[order], normal[order]
        kind = np.where(a == GROUND, "foundation",
                        np.where(np.abs(normal[:, 1]) >= math.cos(math.radians(BED_ANGLE))
                                 - 1e-12, "bed", "head")).astype(object)
        for ka, kb, value in self.kinds:
            kind[(a == ka) & (b == kb)] = value
        self._check_connected(a, b)
        return a, b, p, q, normal, kind.astype(str)

    def _ground_line(self, edges: _Edges, a, b, p, q, normal):
        """Add the block edges on ``y = min y`` as foundation interfaces (no supports given)."""
        tol = self.tolerance
        bottom = float(np.vstack(self.polygons)[:, 1].min())
        on = np.flatnonzero((np.abs(edges.start[:, 1] - bottom) <= tol)
                            & (np.abs(edges.end[:, 1] - bottom) <= tol)
                            & (np.abs(edges.end[:, 0] - edges.start[:, 0]) > tol))
        n = on.size
        return (np.concatenate((a, np.full(n, GROUND))), np.concatenate((b, edges.owner[on])),
                np.concatenate((p, edges.start[on])), np.concatenate((q, edges.end[on])),
                np.concatenate((normal, np.tile([0.0, 1.0], (n, 1)))))

    def _check_overlaps(self, bodies, i: np.ndarray, j: np.ndarray) -> None:
        """Refuse a candidate pair of bodies whose interiors overlap by more than the
        tolerance (separating axes over their triangles, see the module)."""
        if i.size == 0:
            return
        every, vertices, counts = _convex_pieces(bodies)
        first = np.concatenate(([0], np.cumsum(counts)[:-1]))
        pair, ka, kb = _products(counts[i], counts[j])
        x, y = first[i][pair] + ka, first[j][pair] + kb
        # the penetration of two convex pieces is the least overlap of their projections over
        # every direction, so at most that along x or y: pieces whose bounding boxes overlap by
        # no more than the tolerance cannot be refused, and need no separating axes
        low, high = every.min(axis=1), every.max(axis=1)
        boxes = np.minimum(high[x], high[y]) - np.maximum(low[x], low[y])
        near = np.flatnonzero((boxes > self.tolerance).all(axis=1))
        pair, x, y = pair[near], x[near], y[near]
        depth = _penetration(every[x], vertices[x], every[y], vertices[y])
        bad = np.flatnonzero(depth > self.tolerance)
        if bad.size:
            k = bad[np.lexsort((j[pair[bad]], i[pair[bad]]))[0]]
            x, y = int(i[pair[k]]), int(j[pair[k]])
            raise ValueError(f"{self._body_name(x)} and {self._body_name(y)} overlap (by at "
                             f"least {depth[k]:.3g} m, more than the tolerance "
                             f"{self.tolerance:.3g} m)")

    def _check_connected(self, a: np.ndarray, b: np.ndarray) -> None:
        """Refuse a block touching nothing, an assembly on nothing, a floating cluster."""
        from scipy.sparse import coo_matrix
        from scipy.sparse.csgraph import connected_components

        nb = self.n_blocks
        if not np.any(a == GROUND):
            where = ("no block edge lies on a support" if self.supports else
                     "no block edge lies on the lowest line y = "
                     f"{float(np.vstack(self.polygons)[:, 1].min()):.6g} m (give supports)")
            raise ValueError(f"the assembly rests on nothing: {where}")
        touched = np.zeros(nb, dtype=bool)
        touched[b] = True
        touched[a[a >= 0]] = True
        if not touched.all():
            lonely = np.flatnonzero(~touched)
            raise ValueError(f"{', '.join(self.block_name(int(k)) for k in lonely[:10])} "
                             f"touch{'es' if lonely.size == 1 else ''} nothing: every block must "
                             f"share an edge with another block or a support (within the "
                             f"tolerance {self.tolerance:.3g} m)")
        node = np.where(a == GROUND, nb, a)
        graph = coo_matrix((np.ones(a.size), (node, b)), shape=(nb + 1, nb + 1))
        _, label = connected_components(graph, directed=False)
        floating = np.flatnonzero(label[:nb] != label[nb])
        if floating.size:
            listed = ", ".join(self.block_name(int(k)) for k in floating[:10])
            more = f" and {floating.size - 10} more" if floating.size > 10 else ""
            raise ValueError(f"blocks not connected to the ground (a floating group): {listed}"
                             f"{more}")

    def _with_friction_values(self, friction) -> Interfaces:
        a, b, p, q, normal, kind = self._cache["geometry"]
        if friction is None:
            values = np.full(a.size, math.inf)
        elif isinstance(friction, dict):
            missing = sorted(set(kind.tolist()) - set(friction))
            if missing and "default" not in friction:
                raise ValueError(f"friction gives no coefficient for the interface kind(s) "
                                 f"{missing} of this assembly; give them or a 'default'")
            values = np.array([friction.get(k, friction.get("default", math.nan))
                               for k in kind.tolist()], dtype=float)
        else:
            values = np.full(a.size, float(friction))
        return Interfaces(a, b, p, q, normal, kind, values)

    def with_friction(self, friction) -> BlockAssembly:
        """A copy with another ``friction`` (None, a float or a dict kind -> value, see the
        class), sharing the geometry (the interfaces are not searched again)."""
        friction = _check_friction(friction)
        interfaces = self._with_friction_values(friction)
        other = object.__new__(BlockAssembly)
        for f in ("polygons", "density", "supports", "tolerance", "kinds", "names",
                  "support_names"):
            object.__setattr__(other, f, getattr(self, f))
        object.__setattr__(other, "friction", friction)
        object.__setattr__(other, "_cache", {**self._cache, "interfaces": interfaces})
        return other

    # ------------------------------------------------------------------ values
    def to_dict(self) -> dict:
        """``{"blocks", "supports", "density", "friction", "tolerance"}`` (and ``"kinds"``
        when set) [m, kg/m^3], as read by :meth:`from_dict`; density one number when every
        block has the same."""
        density = self.density
        out = {"blocks": [p.tolist() for p in self.polygons],
               "supports": [p.tolist() for p in self.supports],
               "density": float(density[0]) if np.all(density == density[0]) else
               density.tolist(),
               "friction": dict(self.friction) if isinstance(self.friction, dict)
               else self.friction,
               "tolerance": self.tolerance}
        if self.kinds:
            out["kinds"] = [list(k) for k in self.kinds]
        return out

    @classmethod
    def from_dict(cls, data: dict, *, density: float = DEFAULT_DENSITY) -> BlockAssembly:
        """The assembly of a mapping ``{"blocks": [[[x, y], ...], ...], "supports": [...]
        (optional), "density": number or list (optional), "friction": null, number or
        {kind: number} (optional), "tolerance": number [m] (optional), "kinds": [[a, b, kind],
        ...] (optional)}``.

        Parameters
        ----------
        data : dict
            The description.
        density : float, default 2000
            Density [kg/m^3] when ``data`` gives none.
        """
        allowed = {"blocks", "supports", "density", "friction", "tolerance", "kinds"}
        if not isinstance(data, dict):
            raise ValueError(f"a block assembly must be a JSON object, got {type(data).__name__}")
        unknown = sorted(str(k) for k in set(data) - allowed)
        if unknown:
            raise ValueError(f"a block assembly has unknown key(s) {unknown}; allowed: "
                             f"{sorted(allowed)}")
        if not isinstance(data.get("blocks"), list):
            raise ValueError("a block assembly needs 'blocks': a list of polygons [[x, y], ...]")
        check_json_numbers("blocks", data["blocks"], 3)
        supports = data.get("supports") or []
        check_json_numbers("supports", supports, 3)
        for key in ("density", "tolerance"):
            if data.get(key) is not None:
                value = data[key]
                check_json_numbers(key, value, 1 if isinstance(value, list) else 0)
        friction = data.get("friction")
        if isinstance(friction, dict):
            for key, value in friction.items():
                check_json_numbers(f"friction[{key!r}]", value, 0)
        elif friction is not None:
            check_json_numbers("friction", friction, 0)
        kinds = data.get("kinds") or []
        if not isinstance(kinds, list) or not all(
                isinstance(k, list) and len(k) == 3 and all(
                    isinstance(x, int) and not isinstance(x, bool) for x in k[:2])
                for k in kinds):
            raise ValueError("kinds must be a list of [a, b, kind] (two body indices, -1 the "
                             "ground, and an interface kind)")
        return cls(tuple(data["blocks"]), data.get("density", density), tuple(supports),
                   friction, data.get("tolerance"), tuple(tuple(k) for k in kinds))

    def __repr__(self) -> str:
        return (f"BlockAssembly({self.n_blocks} blocks, {len(self.supports)} supports, "
                f"{self.interfaces.n_interfaces} interfaces, friction={self.friction!r}, "
                f"tolerance={self.tolerance:.3g} m)")

    def __eq__(self, other):
        if other.__class__ is not self.__class__:
            return NotImplemented
        return frozen_value(self.to_dict()) == frozen_value(other.to_dict())

    def __hash__(self):
        return hash(("BlockAssembly", frozen_value(self.to_dict())))


# ---------------------------------------------------------------------------------- builders
def _positive(name: str, value) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float) or not (
            math.isfinite(value) and value > 0):
        raise ValueError(f"{name} must be a finite number > 0, got {value!r}")
    return float(value)


def _count(name: str, value, low: int = 1) -> int:
    if isinstance(value, bool) or not isinstance(value, int | np.integer) or value < low:
        raise ValueError(f"{name} must be an integer >= {low}, got {value!r}")
    return int(value)


def _rectangle(x0: float, y0: float, x1: float, y1: float) -> np.ndarray:
    return np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]])


def block_on_ground(width: float, height: float, *, density: float = DEFAULT_DENSITY,
                    friction=None) -> BlockAssembly:
    """One ``width`` x ``height`` block [m] standing on the ground, its base from
    ``(-width/2, 0)`` to ``(width/2, 0)`` (Housner's block).

    Parameters
    ----------
    width, height : float
        Size of the block [m], > 0.
    density : float, default 2000
        [kg/m^3].
    friction : None, float or dict
        See :class:`BlockAssembly`.
    """
    b, h = _positive("width", width), _positive("height", height)
    return BlockAssembly((_rectangle(-b / 2, 0.0, b / 2, h),), density, friction=friction)


def stack(n: int, width: float, height: float, *, density: float = DEFAULT_DENSITY,
          friction=None) -> BlockAssembly:
    """``n`` equal blocks ``width`` x ``height`` [m] stacked on the ground, centred on x = 0,
    block 0 at the bottom: ``n - 1`` bed interfaces and one foundation.

    Parameters
    ----------
    n : int
        Number of blocks, >= 1.
    width, height : float
        Size of each block [m], > 0.
    density : float, default 2000
        [kg/m^3].
    friction : None, float or dict
        See :class:`BlockAssembly`.
    """
    n = _count("n", n)
    b, h = _positive("width", width), _positive("height", height)
    return BlockAssembly(tuple(_rectangle(-b / 2, k * h, b / 2, (k + 1) * h) for k in range(n)),
                         density, friction=friction)


BONDS = ("running", "stack")
"""The bonds :func:`wall` builds."""


def wall(courses: int, blocks_per_course: int, block_width: float, block_height: float, *,
         bond: str = "running", density: float = DEFAULT_DENSITY,
         friction=None) -> BlockAssembly:
    """A rectangular wall of ``courses`` courses on the ground, from x = 0 to
    ``blocks_per_course * block_width`` [m], course 0 at the bottom.

    ``bond="stack"``: every course ``blocks_per_course`` full blocks, head joints aligned.
    ``bond="running"``: the even courses (0, 2, ...) ``blocks_per_course`` full blocks, the odd
    courses offset by half a block: a half block at each end and ``blocks_per_course - 1`` full
    blocks between, so the wall stays rectangular. Blocks are numbered course by course, left to
    right.

    Parameters
    ----------
    courses : int
        Number of courses, >= 1.
    blocks_per_course : int
        Full blocks in a course, >= 1.
    block_width, block_height : float
        Size of a full block [m], > 0.
    bond : {"running", "stack"}
        See above.
    density : float, default 2000
        [kg/m^3].
    friction : None, float or dict
        See :class:`BlockAssembly`.
    """
    courses, per = _count("courses", courses), _count("blocks_per_course", blocks_per_course)
    w, h = _positive("block_width", block_width), _positive("block_height", block_height)
    if bond not in BONDS:
        raise ValueError(f"bond must be one of {list(BONDS)}, got {bond!r}")
    length = per * w
    polygons = []
    for c in range(courses):
        if bond == "running" and c % 2 == 1:
            cuts = np.concatenate(([0.0], w / 2 + w * np.arange(per), [length]))
        else:
            cuts = w * np.arange(per + 1)
        cuts[-1] = length
        polygons += [_rectangle(cuts[k], c * h, cuts[k + 1], (c + 1) * h)
                     for k in range(cuts.size - 1)]
    return BlockAssembly(tuple(polygons), density, friction=friction)


def portal(pier_width: float, pier_height: float, opening: float, lintel_height: float, *,
           pier_courses: int = 1, density: float = DEFAULT_DENSITY,
           friction=None) -> BlockAssembly:
    """A portal frame on the ground: two piers of ``pier_courses`` stacked blocks each
    ``pier_width`` wide, ``opening`` apart, and one lintel block spanning them, from the left
    pier's outer face (x = 0) to the right one's.

    Blocks: the left pier's courses bottom to top, the right pier's, then the lintel.

    Parameters
    ----------
    pier_width, pier_height : float
        Width and height of each pier [m], > 0.
    opening : float
        Clear span between the piers [m], > 0.
    lintel_height : float
        Depth of the lintel [m], > 0.
    pier_courses : int, default 1
        Blocks in each pier, >= 1.
    density : float, default 2000
        [kg/m^3].
    friction : None, float or dict
        See :class:`BlockAssembly`.
    """
    b, hp = _positive("pier_width", pier_width), _positive("pier_height", pier_height)
    span, hl = _positive("opening", opening), _positive("lintel_height", lintel_height)
    n = _count("pier_courses", pier_courses)
    course = hp / n
    polygons = []
    for x0 in (0.0, b + span):
        polygons += [_rectangle(x0, k * course, x0 + b, hp if k == n - 1 else (k + 1) * course)
                     for k in range(n)]
    polygons.append(_rectangle(0.0, hp, 2 * b + span, hp + hl))
    return BlockAssembly(tuple(polygons), density, friction=friction)


ARC_POINTS = 24
"""Points on each curved face of a voussoir when :func:`from_arch` draws it as a polygon."""


def from_arch(arch: BlockArch, *, points: int = ARC_POINTS, friction=None) -> BlockAssembly:
    r"""Any :class:`~archquake.geometry.BlockArch` (an arch of any shape, surveyed, or on piers)
    as a block assembly.

    It reads the arch only through the contract every arch keeps (as
    :func:`archquake.rigid_blocks.assembly.from_arch` does): block ``i``'s polygon is the arch's
    outline :meth:`~archquake.geometry.BlockArch.outline` (``points`` points on each curved
    face), and each springing joint (joint 0 and joint n: an arch's springings or its piers'
    bases) rests on a support, a square on the joint on its far side. Every joint between two
    blocks -- a voussoir joint, a pier course -- is a ``"bed"`` interface (the ``kinds``
    override), the two springings ``"foundation"``, so the assembly has the arch's ``n + 1``
    joints as its interfaces, with the same ends and normals.

    Curved faces become chords: with :math:`\Delta` the angle a chord subtends, a circular
    voussoir's area is :math:`\sin\Delta/\Delta \approx 1 - \Delta^2/6` of the exact one (for
    Oppenheim's arch, 24 points on a voussoir of 22.5 degrees: 4.9e-5 less).

    Parameters
    ----------
    arch : BlockArch
        The arch; carrying no fill (a fill is no block: it is refused).
    points : int, default 24
        Points on each curved face of a voussoir, >= 2.
    friction : None, float or dict
        See :class:`BlockAssembly`.

    Raises
    ------
    ValueError
        If ``arch`` is not a BlockArch or carries fill.
    """
    if not isinstance(arch, BlockArch):
        raise ValueError(f"arch must be a BlockArch, got {type(arch).__name__}")
    if getattr(arch, "fill", None) is not None:
        raise ValueError("from_arch takes an arch without fill: the fill is no rigid block of "
                         "the assembly (its weight rides on the voussoirs only in the arch "
                         "models)")
    points = _count("points", points, 2)
    n = arch.n_voussoirs
    polygons = tuple(np.asarray(arch.outline(i, points), dtype=float)[:-1] for i in range(n))
    joints, normals = arch.joints, arch.joint_normals
    supports = []
    for j, side in ((0, -1.0), (n, 1.0)):
        p_in, p_out = joints[j]
        d = side * float(np.hypot(*(p_out - p_in))) * normals[j]
        supports.append(np.array([p_in, p_out, p_out + d, p_in + d]))
    kinds = tuple((i, i + 1, "bed") for i in range(n - 1))
    return BlockAssembly(polygons, arch.density, tuple(supports), friction, kinds=kinds)


__all__ = ["ARC_POINTS", "BED_ANGLE", "BONDS", "DEFAULT_TOLERANCE", "GROUND", "INTERFACE_KINDS",
           "BlockAssembly", "Interfaces", "block_on_ground", "from_arch",
           "portal", "stack", "wall"]
