r"""Surveyed arches: blocks given as polygons, joints found where neighbours touch.

A surveyed arch is a JSON object (or the same dict in Python)::

    {"blocks": [[[x, y], [x, y], ...], ...],
     "springings": [[[x, y], [x, y]], [[x, y], [x, y]]]}

- ``blocks``: one polygon per block [m], the blocks left to right (listed right to left, they
  are reversed, with a warning: the order names the hinges and the direction of each impact);
  the vertices of a polygon in order, either sense, not repeated at the end (a repeated first
  vertex is dropped). Curved faces are given by sampling them finely; mass properties are those
  of the polygons, exact.
- Joints: the joint between consecutive blocks is the segment along which their boundaries
  overlap: an edge of one lying on an edge of the other (to :data:`SURVEY_TOLERANCE` of the
  arch's size), or several collinear such edges, merged. Two blocks that do not touch along a
  segment, or touch along two separate ones, are an error; so are blocks that overlap,
  non-neighbours that touch along a segment, a self-intersecting polygon, and fewer than four
  blocks (a four-hinge mechanism needs them).
- ``springings`` (optional): the joints of the first and last block with the supports, each a
  segment ``[[x, y], [x, y]]`` that lies on the boundary of its block. When absent, the
  springing joint of the first block is the straight edge of its boundary (collinear
  consecutive edges merged into one) whose outward normal points most nearly away from the
  second block -- along the vector from the second block's centroid to the first's -- and
  that is not its joint with the second block; likewise for the last block. That edge must
  face away within 60 degrees; otherwise give ``springings``.

Joint ends are ordered as everywhere in archquake (:mod:`archquake.geometry.blocks`): the normal
of joint ``j`` points from block ``j-1`` into block ``j`` and the extrados end lies to the left
of it.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field

import numpy as np

from .._equality import value_equality
from ..constants import DEFAULT_DENSITY
from .blocks import (
    MAX_VOUSSOIRS,
    MIN_VOUSSOIRS,
    BlockArch,
    check_density,
    check_json_numbers,
    polygon_vertices,
)
from .mass import Segment, polygon_properties

SURVEY_TOLERANCE = 1e-9
"""Default contact tolerance of a survey: the distance, as a fraction of the arch's size, within
which two edges of neighbouring blocks are taken to lie on one another, and below which a gap or
an overlap is ignored [-]. A survey measured to a millimetre on an arch of 10 m needs 1e-4: give
it as ``tolerance`` (:func:`surveyed_arch`, the file's ``"tolerance"``), within
:data:`SURVEY_TOLERANCE_RANGE`."""

SURVEY_TOLERANCE_RANGE = (1e-12, 1e-2)
"""Accepted contact tolerances of a survey, as fractions of the arch's size [-]: from the
round-off of its coordinates to a gap of a hundredth of the arch, beyond which the blocks are
not in contact."""


def check_survey_tolerance(tolerance) -> float:
    """``tolerance`` as a float in :data:`SURVEY_TOLERANCE_RANGE`, or a ValueError naming it."""
    low, high = SURVEY_TOLERANCE_RANGE
    try:
        value = float(tolerance)
    except (TypeError, ValueError):
        value = math.nan
    if isinstance(tolerance, bool) or not low <= value <= high:
        raise ValueError(f"tolerance must be a number in [{low:g}, {high:g}] (a fraction of the "
                         f"arch's size), got {tolerance!r}")
    return value

SPRINGING_ANGLE = 60.0
"""Largest angle [deg] between the outward normal of a springing joint found from the geometry
and the direction away from the neighbouring block."""


def _cross(a, b):
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


MAX_SURVEY_COORDINATE = 1e7
"""Largest magnitude of a surveyed coordinate [m]: a projected coordinate (UTM northings reach
1e7 m) fits; beyond it the areas and masses lose their digits or overflow."""


def _bounded(name: str, v: np.ndarray) -> None:
    if np.any(np.abs(v) > MAX_SURVEY_COORDINATE):
        value = float(v.flat[int(np.argmax(np.abs(v)))])
        raise ValueError(f"{name} has the coordinate {value:.6g} m, too large: coordinates must "
                         f"be within +-{MAX_SURVEY_COORDINATE:g} m (MAX_SURVEY_COORDINATE); are "
                         "they in metres?")


def _polygon(name: str, vertices) -> np.ndarray:
    return polygon_vertices(name, vertices, _bounded)


def _signed_area(v: np.ndarray) -> float:
    return 0.5 * float(np.sum(_cross(v, np.roll(v, -1, axis=0))))


def _edges(v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    return v, np.roll(v, -1, axis=0)


def _orient(a, b, c):
    return _cross(b - a, c - a)


def _segments_meet(a, b, c, d, tol: float) -> np.ndarray:
    """Whether segments a-b meet segments c-d (arrays (m, 2), paired row by row): they cross,
    or an end of one lies within ``tol`` [m] of the other."""
    def on_segment(p, q, r):
        """r within tol of segment p-q."""
        e = q - p
        ll = np.maximum(np.sum(e * e, axis=-1), 1e-300)
        t = np.clip(np.sum((r - p) * e, axis=-1) / ll, 0.0, 1.0)
        return np.hypot(*np.moveaxis(r - (p + t[..., None] * e), -1, 0)) <= tol

    la = np.maximum(np.hypot(*(b - a).T), 1e-300)
    lc = np.maximum(np.hypot(*(d - c).T), 1e-300)
    o1, o2 = _orient(a, b, c) / la, _orient(a, b, d) / la
    o3, o4 = _orient(c, d, a) / lc, _orient(c, d, b) / lc
    crossing = (((o1 > tol) & (o2 < -tol)) | ((o1 < -tol) & (o2 > tol))) & (
        ((o3 > tol) & (o4 < -tol)) | ((o3 < -tol) & (o4 > tol)))
    return (crossing | on_segment(a, b, c) | on_segment(a, b, d)
            | on_segment(c, d, a) | on_segment(c, d, b))


def _box_pairs(pa, qa, pb, qb, tol: float):
    """Index pairs (i, j) of segments whose bounding boxes overlap (within ``tol`` [m])."""
    lo_a, hi_a = np.minimum(pa, qa) - tol, np.maximum(pa, qa) + tol
    lo_b, hi_b = np.minimum(pb, qb), np.maximum(pb, qb)
    order = np.argsort(lo_b[:, 0])
    starts = np.searchsorted(lo_b[order, 0], hi_a[:, 0], side="right")
    rows, cols = [], []
    for i in range(len(pa)):
        cand = order[:starts[i]]
        ok = cand[(hi_b[cand, 0] >= lo_a[i, 0]) & (lo_b[cand, 1] <= hi_a[i, 1])
                  & (hi_b[cand, 1] >= lo_a[i, 1])]
        rows.append(np.full(ok.size, i))
        cols.append(ok)
    return np.concatenate(rows).astype(np.int64), np.concatenate(cols).astype(np.int64)


def _self_intersection(v: np.ndarray, tol: float) -> tuple[int, int] | None:
    """A pair of non-adjacent edges of polygon ``v`` that cross or touch (within ``tol`` [m]),
    else None."""
    p, q = _edges(v)
    k = len(v)
    i, j = _box_pairs(p, q, p, q, tol)
    keep = (j >= i + 2) & ~((i == 0) & (j == k - 1))
    i, j = i[keep], j[keep]
    hit = np.flatnonzero(_segments_meet(p[i], q[i], p[j], q[j], tol))
    return (int(i[hit[0]]), int(j[hit[0]])) if hit.size else None


def _crossing(pa, qa, pb, qb, tol) -> bool:
    """True when an edge of polygon a properly crosses an edge of polygon b (an intersection
    point interior to both, farther than ``tol`` [m] from their ends and lines)."""
    i, j = _box_pairs(pa, qa, pb, qb, tol)
    a, b, c, d = pa[i], qa[i], pb[j], qb[j]
    la = np.maximum(np.hypot(*(b - a).T), 1e-300)
    lc = np.maximum(np.hypot(*(d - c).T), 1e-300)
    o1, o2 = _orient(a, b, c) / la, _orient(a, b, d) / la
    o3, o4 = _orient(c, d, a) / lc, _orient(c, d, b) / lc
    return bool(np.any((((o1 > tol) & (o2 < -tol)) | ((o1 < -tol) & (o2 > tol)))
                       & (((o3 > tol) & (o4 < -tol)) | ((o3 < -tol) & (o4 > tol)))))


def _inside(points: np.ndarray, polygon: np.ndarray, tol: float) -> np.ndarray:
    """Points strictly inside ``polygon`` (farther than ``tol`` [m] from its boundary)."""
    p, q = _edges(polygon)
    x, y = points[:, 0][:, None], points[:, 1][:, None]
    cond = (p[:, 1] > y) != (q[:, 1] > y)
    with np.errstate(divide="ignore", invalid="ignore"):
        xc = p[:, 0] + (y - p[:, 1]) * (q[:, 0] - p[:, 0]) / (q[:, 1] - p[:, 1])
    inside = np.sum(cond & (x < xc), axis=1) % 2 == 1
    for k in np.flatnonzero(inside):  # farther than tol from every edge?
        e = q - p
        t = np.clip(((points[k] - p) * e).sum(-1) / np.maximum((e * e).sum(-1), 1e-300), 0, 1)
        inside[k] = np.min(np.hypot(*(points[k] - p - t[:, None] * e).T)) > tol
    return inside


def _contacts(va: np.ndarray, vb: np.ndarray, tol: float) -> list[tuple[np.ndarray, np.ndarray]]:
    """Segments of positive length along which the boundaries of polygons a and b overlap: for
    every edge of a, its overlap with every edge of b that lies on it (both ends within ``tol``
    [m] of its line). Returns ``(p, q)`` pairs."""
    return _segment_contacts(*_edges(va), *_edges(vb), tol)


def _segment_contacts(pa, qa, pb, qb, tol: float) -> list[tuple[np.ndarray, np.ndarray]]:
    length = np.hypot(*(qa - pa).T)
    t = (qa - pa) / length[:, None]
    normal = np.column_stack((-t[:, 1], t[:, 0]))
    dc = normal[:, 0:1] * (pb[None, :, 0] - pa[:, 0:1]) + normal[:, 1:2] * (
        pb[None, :, 1] - pa[:, 1:2])
    i, j = np.nonzero(np.abs(dc) <= tol)  # few candidates: test only those
    dd = np.einsum("ij,ij->i", qb[j] - pa[i], normal[i])
    sc = np.einsum("ij,ij->i", pb[j] - pa[i], t[i])
    sd = np.einsum("ij,ij->i", qb[j] - pa[i], t[i])
    lo = np.maximum(np.minimum(sc, sd), 0.0)
    hi = np.minimum(np.maximum(sc, sd), length[i])
    keep = np.flatnonzero((np.abs(dd) <= tol) & (hi - lo > tol))
    return [(pa[i[k]] + lo[k] * t[i[k]], pa[i[k]] + hi[k] * t[i[k]]) for k in keep]


def _merge(segments, tol: float) -> tuple[np.ndarray, np.ndarray] | None:
    """One segment covering collinear contiguous ``segments``, or None if they are not one."""
    p0, q0 = segments[0]
    t = (q0 - p0) / np.hypot(*(q0 - p0))
    normal = np.array([-t[1], t[0]])
    spans = []
    for p, q in segments:
        if abs((p - p0) @ normal) > tol or abs((q - p0) @ normal) > tol:
            return None
        spans.append(sorted(((p - p0) @ t, (q - p0) @ t)))
    spans.sort()
    reach = spans[0][1]
    for lo, hi in spans[1:]:
        if lo > reach + tol:
            return None
        reach = max(reach, hi)
    return p0 + spans[0][0] * t, p0 + reach * t


def _boundary_path(v: np.ndarray, start, end, tol: float) -> np.ndarray:
    """The points of the boundary of the counterclockwise polygon ``v`` from the boundary point
    ``start`` to the boundary point ``end``, counterclockwise [m]."""
    p, q = _edges(v)

    def locate(point) -> tuple[int, float]:
        e = q - p
        ll = np.maximum(np.sum(e * e, axis=1), 1e-300)
        t = np.clip(np.sum((point - p) * e, axis=1) / ll, 0.0, 1.0)
        dist = np.hypot(*(point - p - t[:, None] * e).T)
        k = int(np.argmin(dist))
        if dist[k] > tol:
            raise ValueError("a joint end does not lie on its block's boundary")
        return k, float(t[k])

    (ks, ts), (ke, te) = locate(np.asarray(start)), locate(np.asarray(end))
    points = [np.asarray(start, dtype=float)]
    if not (ke == ks and te >= ts):
        k = ks
        while True:
            k = (k + 1) % len(v)
            points.append(v[k])
            if k == ke:
                break
    points.append(np.asarray(end, dtype=float))
    out = [points[0]]
    for point in points[1:]:
        if np.hypot(*(point - out[-1])) > tol:
            out.append(point)
    return np.array(out)


def _straight_edges(v: np.ndarray) -> list[tuple[np.ndarray, np.ndarray]]:
    """The polygon's edges with collinear consecutive edges merged (angle below 1e-9 rad)."""
    p, q = _edges(v)
    d = q - p
    angle = np.arctan2(d[:, 1], d[:, 0])
    turn = np.abs((np.diff(np.concatenate((angle, angle[:1]))) + math.pi) % (2 * math.pi)
                  - math.pi)
    breaks = np.flatnonzero(turn > 1e-9)  # edge i and i+1 are not collinear
    if breaks.size == 0:
        return [(p[0], q[-1])]
    out = []
    starts = (breaks + 1) % len(v)
    for k, start in enumerate(starts):
        end = breaks[(k + 1) % len(breaks)]
        out.append((p[start], q[end]))
    return out


@value_equality
@dataclass(frozen=True)
class SurveyedArch(BlockArch):
    """An arch given block by block as polygons (a survey); see the module's rules.

    Build it with :func:`surveyed_arch` or :meth:`from_dict`.

    Parameters
    ----------
    vertices : array of float, shape (K, 2)
        The vertices of all blocks, block after block, each polygon counterclockwise [m].
    counts : array of int, shape (n,)
        Number of vertices of every block.
    springings : array of float, shape (2, 2, 2)
        The left and right springing joints, each as two points [m].
    density : float, default 2000
        Density of the masonry [kg/m^3].
    tolerance : float, default :data:`SURVEY_TOLERANCE`
        Contact tolerance, a fraction of the arch's size [-] (:data:`SURVEY_TOLERANCE`).
    """

    vertices: np.ndarray
    counts: np.ndarray
    springings: np.ndarray
    density: float = DEFAULT_DENSITY
    tolerance: float = SURVEY_TOLERANCE
    _cache: dict = field(default_factory=dict, init=False, repr=False, compare=False, hash=False)

    def __post_init__(self):
        vertices = np.array(self.vertices, dtype=float)
        counts = np.array(self.counts, dtype=np.int64)
        springings = np.array(self.springings, dtype=float)
        if vertices.ndim != 2 or vertices.shape[1] != 2 or counts.ndim != 1 or (
                counts.sum() != len(vertices)) or np.any(counts < 3):
            raise ValueError("vertices (K, 2) and counts (n,) >= 3 must describe the blocks")
        if springings.shape != (2, 2, 2) or not np.all(np.isfinite(springings)):
            raise ValueError("springings must be two segments [[x, y], [x, y]] [m]")
        density = check_density(self.density)
        for name, arr in (("vertices", vertices), ("counts", counts),
                          ("springings", springings)):
            arr.setflags(write=False)
            object.__setattr__(self, name, arr)
        object.__setattr__(self, "density", density)
        object.__setattr__(self, "tolerance", check_survey_tolerance(self.tolerance))
        self._cache["starts"] = np.concatenate(([0], np.cumsum(counts)))
        self._cache["size"] = float(np.ptp(vertices, axis=0).max())
        self._cache["joints"] = self._find_joints()

    # ------------------------------------------------------------------ blocks
    @property
    def n_voussoirs(self) -> int:
        """Number of blocks n [-]."""
        return int(self.counts.size)

    @property
    def thickness_scale(self) -> float:
        """The median depth of the joints [m]: a voussoir's thickness, as a built arch gives
        its own, even where the survey holds piers (whose wider bed joints would raise a mean:
        the survey of an arch on piers 3 m wide took a time step 15 % longer than the same
        structure built)."""
        return float(np.median(self.joint_lengths))

    def polygon(self, i: int) -> np.ndarray:
        """Vertices of block ``i``, counterclockwise [m], shape (k_i, 2)."""
        starts = self._cache["starts"]
        return self.vertices[int(starts[i]):int(starts[i + 1])]

    @property
    def size(self) -> float:
        """Largest extent of the arch [m]."""
        return self._cache["size"]

    @property
    def contact_distance(self) -> float:
        """The contact tolerance as a distance: :attr:`tolerance` times :attr:`size` [m]."""
        return self.tolerance * self.size

    def outline(self, i: int, points: int = 24) -> np.ndarray:
        """Closed outline of block ``i`` [m] (its polygon, first vertex repeated)."""
        v = self.polygon(i)
        return np.vstack((v, v[:1]))

    def extrados(self, i: int) -> list:
        """The extrados of block ``i`` as segments (:class:`~archquake.geometry.mass.Segment`),
        from its left end to its right end [m]: the part of its boundary between the extrados
        ends of its two joints that does not hold its intrados."""
        v = self.polygon(i)
        start, end = self.joints[i + 1, 1], self.joints[i, 1]
        path = _boundary_path(v, start, end, self.contact_distance)[::-1]
        return [Segment(path[k], path[k + 1]) for k in range(len(path) - 1)]

    def _mass_properties(self):
        props = [polygon_properties(self.polygon(i), self.density, name=f"block {i}")
                 for i in range(self.n_voussoirs)]
        return (np.array([p[0] for p in props]), np.array([p[1] for p in props]),
                np.array([p[2] for p in props]))

    # ------------------------------------------------------------------ joints
    def _find_joints(self) -> np.ndarray:
        n = self.n_voussoirs
        tol = self.contact_distance
        joints = np.empty((n + 1, 2, 2))
        normals = np.empty((n + 1, 2))
        for j in range(1, n):
            contacts = _contacts(self.polygon(j - 1), self.polygon(j), tol)
            if not contacts:
                gap = _distance(self.polygon(j - 1), self.polygon(j))
                raise ValueError(
                    f"blocks {j - 1} and {j} do not touch along a segment: consecutive blocks "
                    f"must share an edge (their joint); they are {gap:.3g} m apart at their "
                    f"closest, the contact tolerance is {tol:.3g} m ({self.tolerance:g} of the "
                    f"arch's size {self.size:.4g} m; a larger 'tolerance' accepts a wider gap)")
            merged = _merge(contacts, tol)
            if merged is None:
                raise ValueError(f"blocks {j - 1} and {j} touch along more than one segment")
            p, q = merged
            t = (q - p) / np.hypot(*(q - p))
            # block j-1 is counterclockwise: on its edge p -> q (its own direction) the outward
            # normal is the tangent turned by -90 degrees; find the edge's sense in block j-1
            outward = self._outward_normal(j - 1, p, q)
            normals[j] = outward
            joints[j] = (p, q) if t @ np.array([-outward[1], outward[0]]) > 0 else (q, p)
        for side, block, sign in ((0, 0, -1.0), (1, n - 1, 1.0)):
            p, q = self.springings[side]
            outward = self._outward_normal(block, p, q, springing=side)
            normal = sign * outward
            j = 0 if side == 0 else n
            normals[j] = normal
            t = q - p
            joints[j] = (p, q) if t @ np.array([-normal[1], normal[0]]) > 0 else (q, p)
        return joints

    def _outward_normal(self, block: int, p, q, springing: int | None = None) -> np.ndarray:
        """Outward unit normal of block ``block`` along the segment p-q of its boundary."""
        tol = self.contact_distance
        v = self.polygon(block)
        a, b = _edges(v)
        mid = 0.5 * (np.asarray(p) + np.asarray(q))
        t = (np.asarray(q) - np.asarray(p)) / np.hypot(*(np.asarray(q) - np.asarray(p)))
        for k in range(len(v)):
            e = b[k] - a[k]
            length = float(np.hypot(*e))
            u = e / length
            normal = np.array([u[1], -u[0]])  # outward for a counterclockwise polygon
            if abs(abs(u @ t) - 1.0) > 1e-9 or abs((mid - a[k]) @ normal) > tol:
                continue
            s = (mid - a[k]) @ u
            if -tol <= s <= length + tol:
                return normal
        what = (f"springings[{springing}] does not lie on the boundary of block {block}"
                if springing is not None else f"a joint does not lie on block {block}")
        raise ValueError(what)

    def _joints(self) -> np.ndarray:
        return self._cache["joints"]

    # ------------------------------------------------------------------ the contract
    def mirrored(self) -> SurveyedArch:
        """The arch mirrored about x = 0 (blocks in reverse order, springings swapped)."""
        flip = np.array([-1.0, 1.0])
        blocks = [(self.polygon(i) * flip)[::-1] for i in range(self.n_voussoirs)][::-1]
        springings = (self.springings * flip)[::-1]
        return SurveyedArch(np.vstack(blocks), self.counts[::-1].copy(), springings,
                            self.density, self.tolerance)

    def to_dict(self) -> dict:
        """``{"blocks": [...], "springings": [...], "density": ...}`` [m, kg/m^3], as read by
        :meth:`from_dict`."""
        out = {"blocks": [self.polygon(i).tolist() for i in range(self.n_voussoirs)],
               "springings": self.springings.tolist(), "density": self.density}
        if self.tolerance != SURVEY_TOLERANCE:
            out["tolerance"] = self.tolerance
        return out

    @classmethod
    def from_dict(cls, data: dict, *, density: float = DEFAULT_DENSITY) -> SurveyedArch:
        """The arch of a mapping ``{"blocks": ..., "springings": ... (optional), "density":
        ... (optional), "tolerance": ... (optional)}`` (see the module's rules)."""
        unknown = sorted(set(data) - {"blocks", "springings", "density", "tolerance"})
        if unknown:
            raise ValueError(f"a surveyed arch has unknown key(s) {unknown}; allowed: 'blocks', "
                             "'springings', 'density', 'tolerance'")
        if not isinstance(data.get("blocks"), list):
            raise ValueError("a surveyed arch needs 'blocks': a list of polygons [[x, y], ...]")
        check_json_numbers("blocks", data["blocks"], 3)
        if data.get("springings") is not None:
            check_json_numbers("springings", data["springings"], 3)
        for key in ("density", "tolerance"):
            if key in data:
                check_json_numbers(key, data[key], 0)
        return surveyed_arch(data["blocks"], data.get("springings"),
                             density=data.get("density", density),
                             tolerance=data.get("tolerance", SURVEY_TOLERANCE))


def surveyed_arch(blocks, springings=None, *, density: float = DEFAULT_DENSITY,
                  tolerance: float = SURVEY_TOLERANCE) -> SurveyedArch:
    """An arch from its block polygons [m], left to right (see :mod:`survey <.survey>` rules).

    Parameters
    ----------
    blocks : sequence of array_like (k_i, 2)
        One polygon per block [m], vertices in order (either sense), left to right; blocks
        listed right to left (the first block's centroid to the right of the last's) are taken
        in the reverse order, with a warning.
    springings : array_like (2, 2, 2), optional
        The left and right springing joints, each two points [m]; found from the geometry when
        not given.
    density : float, default 2000
        Density of the masonry [kg/m^3].
    tolerance : float, default :data:`SURVEY_TOLERANCE`
        Contact tolerance, a fraction of the arch's size [-]: edges of neighbours closer than
        it touch; gaps and overlaps below it are ignored.

    Returns
    -------
    SurveyedArch

    Raises
    ------
    ValueError
        Naming the block: a polygon with fewer than three vertices, no area or crossing edges;
        blocks that overlap; consecutive blocks that do not share an edge; fewer than four
        blocks; a springing that does not lie on its block.
    """
    try:
        blocks = list(blocks)
    except TypeError as exc:
        raise ValueError("blocks must be a list of polygons [[x, y], ...]") from exc
    if len(blocks) < MIN_VOUSSOIRS:
        raise ValueError(f"a surveyed arch needs at least {MIN_VOUSSOIRS} blocks for a "
                         f"four-hinge mechanism, got {len(blocks)}")
    if len(blocks) > MAX_VOUSSOIRS:
        raise ValueError(f"a surveyed arch has at most {MAX_VOUSSOIRS} blocks (MAX_VOUSSOIRS), "
                         f"got {len(blocks)}")
    from .overlaps import self_intersections

    polygons = [_polygon(f"block {i}", block) for i, block in enumerate(blocks)]
    crossing = self_intersections(polygons, 1e-12)
    for i, v in enumerate(polygons):
        if crossing[i, 0] >= 0:
            raise ValueError(f"block {i} is not a simple polygon: its edges {crossing[i, 0]} "
                             f"and {crossing[i, 1]} cross or touch")
        size = float(np.ptp(v, axis=0).max())
        area = _signed_area(v)
        if not abs(area) > 1e-12 * size * size:
            raise ValueError(f"block {i} encloses no area")
        if area < 0:
            polygons[i] = v[::-1].copy()
    first, last = _centroid(polygons[0])[0], _centroid(polygons[-1])[0]
    if first > last:  # listed right to left: the hinges and impacts would be mislabelled
        warnings.warn(f"the blocks are listed right to left (the first block's centroid at x = "
                      f"{first:.6g} m, the last's at x = {last:.6g} m); they are taken in the "
                      "reverse order, left to right", stacklevel=2)
        polygons = polygons[::-1]
        if springings is not None:
            try:
                springings = list(springings)[::-1]
            except TypeError as exc:
                raise ValueError("springings must be [[[x, y], [x, y]], [[x, y], [x, y]]] "
                                 "[m]") from exc
    tolerance = check_survey_tolerance(tolerance)
    everything = np.vstack(polygons)
    tol = tolerance * float(np.ptp(everything, axis=0).max())
    _check_overlaps(polygons, tol)
    if springings is None:
        springings = [_find_springing(polygons, 0, 1, tol),
                      _find_springing(polygons, len(polygons) - 1, len(polygons) - 2, tol)]
    else:
        try:
            springings = np.array(springings, dtype=float)
        except (TypeError, ValueError) as exc:
            raise ValueError("springings must be [[[x, y], [x, y]], [[x, y], [x, y]]] [m]") from exc
        if springings.shape != (2, 2, 2):
            raise ValueError(f"springings must be two segments [[x, y], [x, y]] [m], got shape "
                             f"{springings.shape}")
    return SurveyedArch(everything, [len(v) for v in polygons], springings, density, tolerance)


def _check_overlaps(polygons: list[np.ndarray], tol: float) -> None:
    """Refuse blocks that overlap, or touch along a segment without being neighbours (a sweep
    over their boxes: :func:`archquake.geometry.overlaps.first_overlap`)."""
    from .overlaps import TOUCHING, first_overlap

    found = first_overlap(polygons, tol)
    if found is None:
        return
    a, b, kind = found
    if kind == TOUCHING:
        raise ValueError(f"blocks {a} and {b} touch along a segment but are not neighbours: "
                         "list the blocks left to right")
    raise ValueError(f"blocks {a} and {b} overlap")


def _distance(va: np.ndarray, vb: np.ndarray) -> float:
    """Smallest distance between the boundaries of polygons a and b [m] (0 if they cross)."""
    def to_edges(points, v):
        p, q = _edges(v)
        e = q - p
        ll = np.maximum(np.sum(e * e, axis=1), 1e-300)
        t = np.clip(np.einsum("kij,ij->ki", points[:, None, :] - p[None], e) / ll, 0.0, 1.0)
        d = points[:, None, :] - p[None] - t[..., None] * e[None]
        return float(np.min(np.hypot(d[..., 0], d[..., 1])))

    return min(to_edges(va, vb), to_edges(vb, va))


def _centroid(v: np.ndarray) -> np.ndarray:
    return polygon_properties(v, 1.0)[1]


def _overlap(p, q, joint, tol: float) -> bool:
    """Whether segment p-q overlaps the segment ``joint`` along a common line."""
    return bool(_segment_contacts(np.array([p]), np.array([q]), np.array([joint[0]]),
                                  np.array([joint[1]]), tol))


def _find_springing(polygons, block: int, neighbour: int, tol: float) -> np.ndarray:
    """The straight edge of ``block`` that faces away from ``neighbour`` (see the module)."""
    v = polygons[block]
    away = _centroid(v) - _centroid(polygons[neighbour])
    away /= np.hypot(*away)
    contacts = _contacts(v, polygons[neighbour], tol)
    joint = _merge(contacts, tol) if contacts else None
    best, score = None, -2.0
    for p, q in _straight_edges(v):
        d = q - p
        length = float(np.hypot(*d))
        if length <= tol or (joint is not None and _overlap(p, q, joint, tol)):
            continue
        value = float(np.array([d[1], -d[0]]) @ away) / length
        if value > score:
            best, score = (p, q), value
    if best is None or score < math.cos(math.radians(SPRINGING_ANGLE)):
        raise ValueError(
            f"cannot find the springing joint of block {block}: no straight edge of it faces "
            f"away from block {neighbour} within {SPRINGING_ANGLE:g} degrees; give "
            "'springings'")
    return np.array(best)
