r"""Arches of several rings: brick arches whose rings can separate.

A multi-ring brick arch (most British brick road and rail bridges) is built as concentric
rings of bricks on edge, bonded to each other only by the mortar of the collar joints between
them: the rings can separate, and a ring that separates from its neighbours carries the load
alone, with a smaller depth. Melbourne and Gilbert [1]_ found that failure (ring separation)
in their full-scale tests, and LimitState:RING [2]_ models the ring interfaces as contacts
that can open and slide. :func:`multi_ring` builds such an arch as a
:class:`~archquake.geometry.BlockAssembly`.

**Geometry.** A circular arch of mean radius :math:`R`, embrace :math:`\alpha` and total
thickness :math:`t` (:func:`~archquake.geometry.circular_arch`'s frame: centre at the origin,
the point at radius :math:`r` on the radial line of progressive angle :math:`\beta` at
:math:`(-r\cos\beta, r\sin\beta)`, :math:`\beta_0 = (\pi - \alpha)/2`) is cut by the circles
:math:`r_0 = R - t/2 < r_1 < \dots < r_N = R + t/2` into :math:`N` rings (ring 0 the
intrados ring), of equal thickness or of the thicknesses given. Every ring is cut by radial
joints into voussoirs, each its own block:

- ``bond="aligned"``: every ring has ``voussoirs`` voussoirs of equal angle
  :math:`\alpha/n`, the joints of all rings on the same radial lines;
- ``bond="staggered"``: the even rings (0, 2, ...) as aligned, the odd rings offset by half a
  voussoir: a half voussoir at each springing and :math:`n - 1` full ones between (the
  running bond of :func:`~archquake.geometry.assembly.wall` bent round), so every ring starts
  and ends on the springing line and no joint runs through two adjacent rings.

**Other centrelines.** Given ``shape``, ``span`` and ``rise`` instead, the arch is built on a
smooth centreline of :mod:`~archquake.geometry.centrelines` in its frame (springings at
:math:`(\mp S/2, 0)`): the ring boundaries are the offset curves of the centreline at
:math:`-t/2 < d_1 < \dots < t/2`, the joints normal to it at equal arc lengths (those of
:func:`~archquake.geometry.shaped_arch`; a staggered ring offset by half of one), and the
chords between two joint ends are the fewest equal steps of arc length (from the largest
curvature between them, doubled until the sagitta, measured at the middle of each chord's arc,
is at most ``arc_error``). A pointed arch is refused: its crown is a corner.

**Faces as chords.** Every circle :math:`r_m` (intrados, extrados and the ring interfaces) is
drawn as chords through one set of points: every joint end on it (of the ring inside and the
ring outside), and between two consecutive joint ends the fewest equal chords whose sagitta
:math:`r_m (1 - \cos(\Delta/2))` (the largest distance of a chord subtending :math:`\Delta`
from its arc) is at most ``arc_error``. Both rings of an interface use the same points, so
their faces are collinear, overlapping edges, found as interfaces by
:class:`~archquake.geometry.BlockAssembly`: one interface per chord. A chord polygon's area is
smaller than the sector's by the segments cut off, :math:`r^2(\Delta - \sin\Delta)/2
\approx r^2\Delta^3/12` each, so the weights converge as :math:`O(\text{arc\_error})`.

**Interfaces.** Kinds (the ``kinds`` override): between two rings ``"ring"``, between two
voussoirs of a ring ``"bed"``, on the springings ``"foundation"``. The arch stands on fixed
springings, as :func:`~archquake.geometry.assembly.from_arch` builds them: a square support on
each springing line, on its far side, on which every ring rests.

**Friction.** ``friction`` is the Coulomb coefficient of the bed and foundation interfaces,
``ring_friction`` that of the ring interfaces (each ``None``: they do not slide). The ring
interfaces carry no tension: a cohesion of the mortar of the collar joints (LimitState:RING's
optional one) is not modelled; a cohesive interface would need a tensile strength in the
program of :mod:`archquake.limit_analysis.assembly`, which has none.

References
----------
.. [1] Melbourne, C. and Gilbert, M. (1995). The behaviour of multiring brickwork arch
   bridges. The Structural Engineer 73(3), 39-47.
.. [2] LimitState Ltd. LimitState:RING, masonry arch bridge analysis software (multi-ring
   arches with ring interfaces that can separate and slide; Gilbert, M. (2007). Limit analysis
   applied to masonry arch bridges: state-of-the-art and recent developments. Proc. ARCH'07,
   Madeira, 13-28).

Examples
--------
Oppenheim's arch in two rings, staggered: seven voussoirs in the intrados ring, six and two
halves in the extrados one, and a ring interface of chords over the whole embrace:

>>> import math
>>> arch = multi_ring(10.0, math.radians(157.5), 1.5, rings=2, voussoirs=7, bond="staggered")
>>> arch.n_blocks, sorted(set(arch.interfaces.kind.tolist()))
(15, ['bed', 'foundation', 'ring'])
"""

from __future__ import annotations

import math

import numpy as np

from .. import defaults
from ..constants import DEFAULT_DENSITY
from .assembly import BlockAssembly

RING_BONDS = defaults.RING_BONDS
"""The bonds of the rings :func:`multi_ring` builds (:data:`archquake.defaults.RING_BONDS`)."""

ARC_ERROR = 1e-3
"""Default largest sagitta of a chord as a fraction of the arch's thickness [-]."""

MAX_CHORDS = 100_000
"""Most chords over all the circles of one arch [-] (an ``arc_error`` far below the size of
the arch would build an assembly too large to analyse)."""


def _positive(name: str, value) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float | np.floating) or not (
            math.isfinite(value) and value > 0):
        raise ValueError(f"{name} must be a finite number > 0, got {value!r}")
    return float(value)


def _ring_radii(radius: float, thickness: float, rings, thicknesses) -> np.ndarray:
    """The radii r_0 < ... < r_N of the ring boundaries [m]."""
    if (rings is None) == (thicknesses is None):
        raise ValueError("give either rings (the number of rings of equal thickness) or "
                         "thicknesses (one per ring, inside out), not both and not neither")
    if thicknesses is None:
        if isinstance(rings, bool) or not isinstance(rings, int | np.integer) or rings < 1:
            raise ValueError(f"rings must be an integer >= 1, got {rings!r}")
        parts = np.full(int(rings), thickness / int(rings))
    else:
        if isinstance(thicknesses, str) or not hasattr(thicknesses, "__len__"):
            raise ValueError(f"thicknesses must be a list of ring thicknesses [m], got "
                             f"{thicknesses!r}")
        parts = np.array([_positive(f"thicknesses[{i}]", v) for i, v in enumerate(thicknesses)])
        if parts.size < 1:
            raise ValueError("thicknesses must list at least one ring thickness [m]")
        if not math.isclose(float(parts.sum()), thickness, rel_tol=1e-9):
            raise ValueError(f"thicknesses must add up to the thickness {thickness:g} m, got "
                             f"{float(parts.sum()):g} m")
    inner = radius - thickness / 2
    radii = inner + np.concatenate(([0.0], np.cumsum(parts)))
    radii[-1] = radius + thickness / 2
    return radii


def _ring_joints(start: float, embrace: float, voussoirs: int, rings: int,
                 bond: str) -> list[np.ndarray]:
    """The joint angles [rad] of every ring, springing to springing."""
    full = start + embrace * np.arange(voussoirs + 1) / voussoirs
    if bond == "aligned":
        return [full] * rings
    half = start + embrace * (0.5 + np.arange(voussoirs)) / voussoirs
    shifted = np.concatenate(([start], half, [start + embrace]))
    return [full if m % 2 == 0 else shifted for m in range(rings)]


def _circle_points(radius: float, joints: np.ndarray, arc_error: float) -> np.ndarray:
    """Angles [rad] of the chord ends on the circle ``radius``: the joint angles ``joints``
    (sorted, unique) and between each two the fewest equal chords of sagitta <= arc_error."""
    largest = 2.0 * math.acos(max(1.0 - arc_error / radius, -1.0))
    gaps = np.diff(joints)
    pieces = np.maximum(np.ceil(gaps / largest - 1e-12).astype(int), 1)
    out = [joints[:1]]
    for a, gap, m in zip(joints[:-1], gaps, pieces, strict=True):
        out.append(a + gap * np.arange(1, m + 1) / m)
    points = np.concatenate(out)
    points[np.cumsum(np.concatenate(([0], pieces)))] = joints  # joint ends exactly
    return points


def multi_ring(radius: float | None = None, embrace: float | None = None,
               thickness: float | None = None, *, shape: str | None = None,
               span: float | None = None, rise: float | None = None, rings: int | None = None,
               thicknesses=None, voussoirs: int = 7, bond: str = "aligned", friction=None,
               ring_friction=None, arc_error: float | None = None,
               density: float = DEFAULT_DENSITY) -> BlockAssembly:
    r"""A circular arch of several concentric rings that can separate, as a block assembly.

    See the module for the geometry, the chords and the interfaces. Blocks are numbered ring
    by ring from the intrados, each ring left to right.

    Parameters
    ----------
    radius : float
        Mean radius :math:`R` of a circular arch [m], > thickness / 2 (or give ``shape``,
        ``span`` and ``rise``).
    embrace : float
        Angle of embrace :math:`\alpha` of a circular arch [rad], in (0, 2 pi).
    thickness : float
        Total thickness :math:`t` of the arch, all rings, normal to the centreline [m], > 0.
    shape : str, optional
        Instead of ``radius`` and ``embrace``: a smooth centreline of
        :mod:`~archquake.geometry.centrelines` (``"circular"``, ``"elliptical"``,
        ``"parabolic"``, ``"catenary"``, ``"three-centred"``; not ``"pointed"``, whose crown
        corner the rings' offset curves cannot follow as chords) of ``span`` and ``rise`` [m],
        in its frame (springings at :math:`(\mp S/2, 0)`): the rings are its offset curves,
        the joints normal to it at equal arc lengths (as
        :func:`~archquake.geometry.shaped_arch` cuts them), every chord's sagitta measured at
        the middle of its arc.
    span, rise : float, optional
        Span and rise of the centreline [m], with ``shape``.
    rings : int, optional
        Number of rings of equal thickness :math:`t/N`, >= 1 (or give ``thicknesses``).
    thicknesses : sequence of float, optional
        Thickness of every ring from the intrados out [m], each > 0, adding up to
        ``thickness``.
    voussoirs : int, default 7
        Voussoirs of every ring (of the aligned rings; a staggered odd ring has ``voussoirs -
        1`` and two halves), >= 1.
    bond : {"aligned", "staggered"}
        Joints of adjacent rings on the same radial lines, or offset by half a voussoir.
    friction : None, float or dict, optional
        Coulomb coefficient of the bed and foundation interfaces [-] (None: they do not slide;
        a dict by kind as :class:`~archquake.geometry.BlockAssembly` takes it).
    ring_friction : float, optional
        Coulomb coefficient of the ring interfaces [-], >= 0 (None: they do not slide; with a
        dict ``friction`` its ``"ring"`` entry may give it instead).
    arc_error : float, optional
        Largest sagitta of a chord drawing a circle [m], > 0 (default :data:`ARC_ERROR` times
        ``thickness``).
    density : float, default 2000
        Density of the masonry [kg/m^3].

    Returns
    -------
    BlockAssembly
        The arch on its two springing supports, with ``kinds`` naming the ring interfaces and
        ``names`` every block (``"ring 1, voussoir 3"``: ring 0 the intrados ring, voussoirs
        from the left).

    Raises
    ------
    ValueError
        Naming the parameter out of its range.

    References
    ----------
    .. [1] Melbourne and Gilbert (1995), see the module.
    """
    if shape is not None or span is not None or rise is not None:
        if radius is not None or embrace is not None:
            raise ValueError("give radius and embrace (a circular arch) or shape, span and "
                             "rise, not both")
        return _on_centreline(shape or "circular", span, rise, thickness, rings=rings,
                              thicknesses=thicknesses, voussoirs=voussoirs, bond=bond,
                              friction=friction, ring_friction=ring_friction,
                              arc_error=arc_error, density=density)
    radius = _positive("radius", radius)
    thickness = _positive("thickness", thickness)
    embrace = _positive("embrace", embrace)
    if not embrace < 2 * math.pi:
        raise ValueError(f"embrace must be in (0, 2 pi) rad, got {embrace!r}")
    if not thickness < 2 * radius:
        raise ValueError(f"thickness must be below twice the radius ({2 * radius:g} m), got "
                         f"{thickness!r}")
    _check_voussoirs_and_bond(voussoirs, bond)
    radii = _ring_radii(radius, thickness, rings, thicknesses)
    n_rings = radii.size - 1
    arc_error = ARC_ERROR * thickness if arc_error is None else _positive("arc_error",
                                                                          arc_error)
    if not arc_error < radii[0]:
        raise ValueError(f"arc_error must be below the intrados radius ({radii[0]:g} m), got "
                         f"{arc_error!r}")
    start = (math.pi - embrace) / 2
    joints = _ring_joints(start, embrace, int(voussoirs), n_rings, bond)
    chords = sum(math.ceil(embrace / (2.0 * math.acos(1.0 - arc_error / r))) for r in radii)
    if chords > MAX_CHORDS:
        raise ValueError(f"arc_error must be larger: {arc_error:g} m draws the circles with "
                         f"about {chords} chords, more than {MAX_CHORDS}")
    circles = []
    for m, r in enumerate(radii):
        near = [joints[k] for k in (m - 1, m) if 0 <= k < n_rings]
        circles.append(_circle_points(float(r), np.unique(np.concatenate(near)), arc_error))

    def arc(m, b0, b1):
        beta = circles[m]
        beta = beta[(beta >= b0 - 1e-12) & (beta <= b1 + 1e-12)]
        r = radii[m]
        return np.column_stack((-r * np.cos(beta), r * np.sin(beta)))

    polygons, names, kinds = _blocks(joints, arc)
    supports = []
    for beta, side in ((start, -1.0), (start + embrace, 1.0)):
        p_in = np.array([-radii[0] * math.cos(beta), radii[0] * math.sin(beta)])
        p_out = np.array([-radii[-1] * math.cos(beta), radii[-1] * math.sin(beta)])
        # the joint normal (toward increasing beta) is (sin beta, cos beta); the support lies
        # beyond the springing, away from the arch
        d = side * thickness * np.array([math.sin(beta), math.cos(beta)])
        supports.append(np.array([p_in, p_out, p_out + d, p_in + d]))
    return BlockAssembly(tuple(polygons), density, tuple(supports),
                         ring_friction_of(friction, ring_friction), kinds=tuple(kinds),
                         names=tuple(names))


def _check_voussoirs_and_bond(voussoirs, bond) -> None:
    if isinstance(voussoirs, bool) or not isinstance(voussoirs, int | np.integer) \
            or voussoirs < 1:
        raise ValueError(f"voussoirs must be an integer >= 1, got {voussoirs!r}")
    if bond not in RING_BONDS:
        raise ValueError(f"bond must be one of {list(RING_BONDS)}, got {bond!r}")


def _blocks(joints, arc):
    """Every ring's voussoirs between its joint stations ``joints[m]`` (angles or arc lengths),
    each bounded by ``arc(m, a, b)`` inside and ``arc(m + 1, a, b)`` outside: ``(polygons,
    names, kinds)``."""
    polygons, ring_of, span, names = [], [], [], []
    for m in range(len(joints)):
        for i, (b0, b1) in enumerate(zip(joints[m][:-1], joints[m][1:], strict=True)):
            polygons.append(np.vstack((arc(m, b0, b1), arc(m + 1, b0, b1)[::-1])))
            ring_of.append(m)
            span.append((b0, b1))
            names.append(f"ring {m}, voussoir {i}")
    ring_of, span = np.array(ring_of), np.array(span)
    tol = 1e-12 * max(1.0, float(np.abs(span).max()))
    kinds = []
    for i in range(len(polygons)):
        for j in np.flatnonzero(ring_of == ring_of[i] + 1):
            if min(span[i, 1], span[j, 1]) - max(span[i, 0], span[j, 0]) > tol:
                kinds.append((i, int(j), "ring"))
        if i + 1 < len(polygons) and ring_of[i + 1] == ring_of[i]:
            kinds.append((i, i + 1, "bed"))
    return polygons, names, kinds


def _offset(curve, s: np.ndarray, offset: float) -> np.ndarray:
    """Points of the offset curve of ``curve`` at ``offset`` [m] at arc lengths ``s``."""
    index, u = curve.stations(s)
    out = np.empty((s.size, 2))
    for i, part in enumerate(curve.parts):
        here = index == i
        if here.any():
            out[here] = part.offset_point(u[here], offset)
    return out


def _offset_stations(curve, offset: float, joints: np.ndarray, arc_error: float) -> np.ndarray:
    """Arc lengths [m] of the chord ends on the offset curve at ``offset``: the joint stations
    and between each two the fewest equal steps (doubled until the sagitta, measured at the
    middle of every chord's arc, is at most ``arc_error``)."""
    out = [joints[:1]]
    for a, b in zip(joints[:-1], joints[1:], strict=True):
        kappa = curve.max_curvature(curve.locate(a, "right"), curve.locate(b, "left"))
        rho = math.inf if kappa == 0 else 1.0 / kappa + offset
        turn = 2.0 * math.acos(max(1.0 - arc_error / rho, -1.0)) if math.isfinite(rho) else \
            math.inf
        m = max(1, math.ceil((b - a) * kappa / turn - 1e-12)) if kappa > 0 else 1
        while True:
            s = a + (b - a) * np.arange(m + 1) / m
            p = _offset(curve, s, offset)
            mid = _offset(curve, 0.5 * (s[:-1] + s[1:]), offset)
            chord = p[1:] - p[:-1]
            gap = np.abs(chord[:, 0] * (mid[:, 1] - p[:-1, 1]) - chord[:, 1] * (
                mid[:, 0] - p[:-1, 0])) / np.hypot(*chord.T)
            if gap.max() <= arc_error or m > MAX_CHORDS:
                break
            m *= 2
        s[0], s[-1] = a, b
        out.append(s[1:])
    return np.concatenate(out)


def _on_centreline(shape, span, rise, thickness, *, rings, thicknesses, voussoirs, bond,
                   friction, ring_friction, arc_error, density) -> BlockAssembly:
    """:func:`multi_ring` on a smooth centreline of a shape (see its ``shape``)."""
    from .centrelines import centreline

    if shape == "pointed":
        raise ValueError("shape must be a smooth centreline: a pointed arch's crown is a "
                         "corner, which the rings' offset curves cannot follow; give another "
                         "shape")
    thickness = _positive("thickness", thickness)
    _check_voussoirs_and_bond(voussoirs, bond)
    curve = centreline(shape, span, rise)
    if curve.corners:
        raise ValueError(f"shape must be a smooth centreline; a {shape} one has corners")
    least = min(curve.min_radius_of_curvature(a, b) for a, b in curve.segments)
    if not thickness < 2 * least:
        raise ValueError(f"thickness must be below twice the smallest radius of curvature of "
                         f"the centreline ({2 * least:g} m), got {thickness!r}")
    offsets = _ring_radii(0.0, thickness, rings, thicknesses)  # -t/2 .. t/2
    n_rings = offsets.size - 1
    arc_error = ARC_ERROR * thickness if arc_error is None else _positive("arc_error",
                                                                          arc_error)
    length = curve.length
    joints = _ring_joints(0.0, length, int(voussoirs), n_rings, bond)
    rough = sum(length / (2.0 * math.sqrt(2.0 * arc_error * (least + o))) for o in offsets
                if least + o > 0)
    if rough > MAX_CHORDS:
        raise ValueError(f"arc_error must be larger: {arc_error:g} m draws the offset curves "
                         f"with about {int(rough)} chords, more than {MAX_CHORDS}")
    stations = []
    for m, o in enumerate(offsets):
        near = [joints[k] for k in (m - 1, m) if 0 <= k < n_rings]
        stations.append(_offset_stations(curve, float(o), np.unique(np.concatenate(near)),
                                         arc_error))
    tol = 1e-12 * length

    def arc(m, a, b):
        s = stations[m]
        return _offset(curve, s[(s >= a - tol) & (s <= b + tol)], float(offsets[m]))

    polygons, names, kinds = _blocks(joints, arc)
    supports = []
    for s, side in ((0.0, -1.0), (length, 1.0)):
        p_in, p_out = _offset(curve, np.array([s, s]), 0.0) + np.outer(
            offsets[[0, -1]], curve.normal(s, "right" if side < 0 else "left"))
        d = side * thickness * curve.tangent(s, "right" if side < 0 else "left")
        supports.append(np.array([p_in, p_out, p_out + d, p_in + d]))
    return BlockAssembly(tuple(polygons), density, tuple(supports),
                         ring_friction_of(friction, ring_friction), kinds=tuple(kinds),
                         names=tuple(names))


def ring_friction_of(friction, ring_friction):
    """The ``friction`` of a :class:`~archquake.geometry.BlockAssembly` of rings from the
    coefficient of the bed and foundation interfaces (``friction``: None, a number or a dict
    by kind) and of the ring interfaces (``ring_friction``: None or a number) [-]: None when
    neither is given (nothing slides); an interface kind given no coefficient does not slide
    (``inf``)."""
    if ring_friction is None:
        return friction
    if isinstance(ring_friction, bool) or not isinstance(ring_friction, int | float | np.floating) \
            or not ring_friction >= 0:
        raise ValueError(f"ring_friction must be a Coulomb coefficient >= 0 [-], got "
                         f"{ring_friction!r}")
    if isinstance(friction, dict):
        return {**friction, "ring": float(ring_friction)}
    other = math.inf if friction is None else friction
    return {"bed": other, "foundation": other, "ring": float(ring_friction)}


__all__ = ["ARC_ERROR", "MAX_CHORDS", "RING_BONDS", "multi_ring", "ring_friction_of"]
