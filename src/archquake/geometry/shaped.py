r"""Arches of any shape by their centreline: stereotomy, faces and exact blocks.

The paper's arch is circular with radial joints [1]_; the same rules of stereotomy give arches
of the other traditional shapes [2]_. A :class:`ShapedArch` is built on a
:class:`~archquake.geometry.centrelines.Centreline` (span and rise of the centreline,
springings at :math:`(\mp S/2, 0)`, crown at :math:`(0, H)`) by these rules:

- **Voussoirs.** Voussoir ``i`` spans the arc length :math:`\ell_i` [m] of the centreline,
  from :math:`s_i` to :math:`s_{i+1} = s_i + \ell_i`; the nominal arch has ``n`` voussoirs of
  equal centreline arc length :math:`L/n`.
- **Thickness.** Voussoir ``i`` has thickness :math:`t_i` [m] measured along the normal of the
  centreline, and its own centreline is shifted by :math:`\delta_i` [m] along the normal
  (toward the extrados if positive; 0 for the nominal arch). Its intrados and extrados are the
  offset curves of the centreline at :math:`\delta_i - t_i/2` and :math:`\delta_i + t_i/2`;
  for a circle of radius R they are circles of radii :math:`R + \delta_i \mp t_i/2`.
- **Joints** are normal to the centreline at every :math:`s_j` (for a circle: radial), the
  springing joints included. At a corner of the centreline (the crown of a pointed arch,
  which then needs an even ``n``) the joint follows the bisector of the two normals: vertical
  for a symmetric arch, so each half of a pointed arch has joints radial to its own centre
  and a vertical crown joint. The contact at a joint is the overlap of the two voussoirs'
  extents along it (a springing joint: its voussoir's own extent), as for the paper's
  irregular arches.
- **Faces.** ``"curved"``: a voussoir is bounded by its two joints and by the arcs of its
  intrados and extrados offset curves between them; ``"flat"``: by the four chords between its
  joint ends (a quadrilateral). Mass properties are exact for circular faces (every part of a
  circular, pointed or three-centred centreline is a circular arc, and so are its offsets), and
  to about 1e-13 relative for the offset curves of ellipses, parabolas and catenaries (Green's
  theorem by Gauss-Legendre quadrature, :mod:`archquake.geometry.mass`).

The thickness must stay below twice the smallest radius of curvature of the centreline, where
the intrados offset curve would fold back on itself.

References
----------
.. [1] The paper, Sect. 2 and Fig. 1: the circular arch with radial joints and its voussoir
   parameters.
.. [2] Heyman, J. (1982). The Masonry Arch. Chichester: Ellis Horwood.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .. import defaults
from .._equality import value_equality
from ..constants import DEFAULT_DENSITY
from .blocks import (
    BlockArch,
    check_density,
    check_json_numbers,
    check_voussoir_count,
    float_array,
    frozen_array,
    real_number,
)
from .centrelines import SHAPES, ArcPart, Centreline, centreline
from .mass import Arc, Curve, Segment, region_properties

VOUSSOIR_FACES: tuple[str, ...] = defaults.VOUSSOIR_FACES
"""Faces of a voussoir: ``"curved"`` (the intrados and extrados offset curves) or ``"flat"``
(the chords between the joint ends)."""


def _reversed(piece):
    if isinstance(piece, Segment):
        return Segment(piece.end, piece.start)
    if isinstance(piece, Arc):
        return Arc(piece.centre, piece.radius, piece.end_angle, piece.start_angle)
    return Curve(piece.path, piece.velocity, piece.end_parameter, piece.start_parameter)


@value_equality
@dataclass(frozen=True)
class ShapedArch(BlockArch):
    r"""An arch of any shape: voussoirs laid along a centreline (see the module's rules).

    Build it with :func:`shaped_arch`; irregular arches around it come from
    :func:`archquake.geometry.irregular_arch`.

    Parameters
    ----------
    centreline : Centreline
        The centreline (shape, span and rise).
    lengths : array of float, shape (n,)
        Centreline arc length :math:`\ell_i` of every voussoir [m], > 0, summing to the length of
        the centreline (to the length of each half for a pointed arch).
    thicknesses : array of float, shape (n,)
        Thickness :math:`t_i` of every voussoir [m], > 0, below twice the centreline's smallest
        radius of curvature over the voussoir.
    offsets : array of float, shape (n,)
        Shift :math:`\delta_i` of every voussoir's own centreline along the normal [m].
    faces : {"curved", "flat"}
        Voussoir faces.
    density : float, default 2000
        Density of the masonry [kg/m^3].
    """

    centreline: Centreline
    lengths: np.ndarray
    thicknesses: np.ndarray
    offsets: np.ndarray
    faces: str = "curved"
    density: float = DEFAULT_DENSITY
    _cache: dict = field(default_factory=dict, init=False, repr=False, compare=False, hash=False)

    def __post_init__(self):
        if not isinstance(self.centreline, Centreline):
            raise ValueError(f"centreline must be a Centreline, got "
                             f"{type(self.centreline).__name__}")
        lengths = float_array("lengths", self.lengths)
        thicknesses = float_array("thicknesses", self.thicknesses)
        offsets = float_array("offsets", self.offsets)
        n = lengths.size
        if thicknesses.size != n or offsets.size != n:
            raise ValueError("lengths, thicknesses and offsets must have the same length (one "
                             f"value per voussoir), got {n}, {thicknesses.size} and {offsets.size}")
        check_voussoir_count(n)
        if self.faces not in VOUSSOIR_FACES:
            raise ValueError(f"faces must be one of {VOUSSOIR_FACES}, got {self.faces!r}")
        if np.any(lengths <= 0):
            raise ValueError(f"lengths must all be > 0 [m], got {lengths.tolist()}")
        if np.any(thicknesses <= 0):
            raise ValueError(f"thicknesses must all be > 0 [m], got {thicknesses.tolist()}")
        density = check_density(self.density)
        for name, arr in (("lengths", lengths), ("thicknesses", thicknesses),
                          ("offsets", offsets)):
            arr.setflags(write=False)
            object.__setattr__(self, name, arr)
        object.__setattr__(self, "density", density)
        self._cache["s"] = self._joint_positions()
        self._check_thickness()
        lo, hi = self._contacts()
        bad = np.flatnonzero(lo >= hi)
        if bad.size:
            j = int(bad[0])
            raise ValueError(
                f"adjacent voussoirs must touch at every joint: at joint {j} the extents of "
                f"voussoirs {j - 1} and {j} along the joint do not overlap")

    # ------------------------------------------------------------------ construction
    def _joint_positions(self) -> np.ndarray:
        """Arc length s_j of every joint [m]; each smooth stretch of the centreline is filled
        by whole voussoirs, its end snapped to the corner."""
        s = np.concatenate(([0.0], np.cumsum(self.lengths)))
        total = self.centreline.length
        tol = 1e-9 * total
        for corner in (*self.centreline.corners, total):
            j = int(np.argmin(np.abs(s - corner)))
            if abs(s[j] - corner) > tol:
                where = "its crown (a corner)" if corner < total else "the right springing"
                raise ValueError(
                    f"the voussoir lengths must reach {where} at a joint: the joints are at "
                    f"{np.round(s, 9).tolist()} m, {where} at {corner:.9g} m (a pointed arch "
                    "needs an even number of voussoirs, half on each side)")
            s[j] = corner
        return s

    @property
    def joint_positions(self) -> np.ndarray:
        """Centreline arc length s_j of every joint j = 0..n from the left springing [m]."""
        return self._cache["s"]

    def _stations(self):
        """``(right, left)``: the part and parameter of every joint's position, on the part to
        its right (where a voussoir starts) and to its left (where one ends)."""
        def compute():
            s = self.joint_positions
            return (self.centreline.stations(s, "right"), self.centreline.stations(s, "left"))
        return self._cached("stations", compute)

    def _station(self, joint: int, side: str) -> tuple[int, float]:
        index, u = self._stations()[0 if side == "right" else 1]
        return int(index[joint]), float(u[joint])

    def _check_thickness(self) -> None:
        for i in range(self.n_voussoirs):
            kappa = self.centreline.max_curvature(self._station(i, "right"),
                                                  self._station(i + 1, "left"))
            rho = math.inf if kappa == 0.0 else 1.0 / kappa
            inner = 0.5 * self.thicknesses[i] - self.offsets[i]
            if inner >= rho:
                raise ValueError(
                    f"thickness must be < 2 x the smallest radius of curvature of the "
                    f"centreline ({2 * rho:.6g} m for voussoir {i}), where the intrados would "
                    f"fold back: voussoir {i} reaches {inner:.6g} m inside the centreline")

    def _joint_lines(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Every joint's line: ``(base (n+1, 2), direction (n+1, 2), corner (n+1,))`` -- its
        point on the centreline [m], its unit direction toward the extrados (the normal; the
        bisector of the two normals at a corner) and whether it is a corner joint."""
        def compute():
            (right, u_right), (left, u_left) = self._stations()
            parts = self.centreline.parts
            base = np.empty((right.size, 2))
            direction = np.empty((right.size, 2))
            for i, part in enumerate(parts):
                here = right == i
                if np.any(here):
                    base[here] = part.point(u_right[here])
                    direction[here] = part.normal(u_right[here])
            corner = np.isin(self.joint_positions, self.centreline.corners)
            for j in np.flatnonzero(corner):
                w = parts[left[j]].normal(u_left[j]) + direction[j]
                direction[j] = w / np.hypot(*w)
            return base, direction, corner
        return self._cached("lines", compute)

    def _end(self, i: int, joint: int, offset: float) -> tuple[float, float]:
        """``(lambda, u)``: where voussoir ``i``'s offset curve at ``offset`` meets its corner
        joint ``joint`` (``i`` or ``i + 1``): the distance along the joint line from the
        centreline [m] and the parameter of the part."""
        base, direction, _ = self._joint_lines()
        index, _ = self._station(joint, "right" if joint == i else "left")
        part = self.centreline.parts[index]
        if not isinstance(part, ArcPart):  # pragma: no cover - corners join arcs only
            raise ValueError("a corner of a centreline must join circular arcs")
        u = part.offset_parameter_on_line(offset, base[joint], direction[joint])
        lam = float((part.offset_point(u, offset) - base[joint]) @ direction[joint])
        return lam, u

    def _extents(self):
        """Own extents of every voussoir along its two joints: ``lam (n, 2 ends, 2 faces)`` [m]
        (the offsets of its faces on a joint normal to the centreline) and the part parameters
        at corner ends ``u (n, 2, 2)`` (nan elsewhere)."""
        def compute():
            faces = np.stack((self.offsets - 0.5 * self.thicknesses,
                              self.offsets + 0.5 * self.thicknesses), axis=1)  # (n, 2)
            lam = np.repeat(faces[:, None, :], 2, axis=1)
            u = np.full(lam.shape, np.nan)
            corner = self._joint_lines()[2]
            for joint in np.flatnonzero(corner):
                for i, end in ((joint - 1, 1), (joint, 0)):
                    if 0 <= i < self.n_voussoirs:
                        for face in range(2):
                            lam[i, end, face], u[i, end, face] = self._end(i, joint,
                                                                           faces[i, face])
            return lam, u
        return self._cached("extents", compute)

    def _contacts(self) -> tuple[np.ndarray, np.ndarray]:
        lam, _ = self._extents()
        lo = np.concatenate(([lam[0, 0, 0]], np.maximum(lam[:-1, 1, 0], lam[1:, 0, 0]),
                             [lam[-1, 1, 0]]))
        hi = np.concatenate(([lam[0, 0, 1]], np.minimum(lam[:-1, 1, 1], lam[1:, 0, 1]),
                             [lam[-1, 1, 1]]))
        return lo, hi

    def _joints(self) -> np.ndarray:
        lo, hi = self._contacts()
        base, w, _ = self._joint_lines()
        return np.stack((base + lo[:, None] * w, base + hi[:, None] * w), axis=1)

    def _corners_of(self, i: int) -> np.ndarray:
        """Own corner points of voussoir i: ``[in_left, in_right, out_right, out_left]`` [m]."""
        lam, _ = self._extents()
        base, w, _ = self._joint_lines()
        return np.array([base[i] + lam[i, 0, 0] * w[i], base[i + 1] + lam[i, 1, 0] * w[i + 1],
                         base[i + 1] + lam[i, 1, 1] * w[i + 1], base[i] + lam[i, 0, 1] * w[i]])

    def boundary(self, i: int) -> list:
        """The boundary of voussoir ``i`` as pieces (counterclockwise): intrados left to right,
        the right joint, extrados right to left, the left joint (:mod:`archquake.geometry.mass`).
        """
        c = self._corners_of(i)
        intrados, extrados = self._face(i, 0), self._face(i, 1)
        return [*intrados, Segment(c[1], c[2]), *[_reversed(p) for p in extrados[::-1]],
                Segment(c[3], c[0])]

    def _face(self, i: int, face: int) -> list:
        """The intrados (``face`` 0) or extrados (1) of voussoir ``i`` as pieces, left to
        right."""
        c = self._corners_of(i)
        if self.faces == "flat":
            return [Segment(c[0], c[1])] if face == 0 else [Segment(c[3], c[2])]
        _, u = self._extents()
        (first, ua), (last, ub) = self._station(i, "right"), self._station(i + 1, "left")
        d = self.offsets[i] + (0.5 if face else -0.5) * self.thicknesses[i]
        start = ua if np.isnan(u[i, 0, face]) else float(u[i, 0, face])
        end = ub if np.isnan(u[i, 1, face]) else float(u[i, 1, face])
        return list(self.centreline.offset_pieces(d, (first, start), (last, end)))

    def extrados(self, i: int) -> list:
        """The extrados of voussoir ``i`` as pieces (:mod:`archquake.geometry.mass`), from its
        left end to its right end [m]: the offset curve (curved faces) or the chord (flat)."""
        return self._face(i, 1)

    def _mass_properties(self):
        try:
            props = [region_properties(self.boundary(i), self.density, name=f"voussoir {i}",
                                       check=False)  # closed by construction
                     for i in range(self.n_voussoirs)]
        except ValueError as exc:  # too thin to have an area, or folded where it turns
            raise ValueError(f"thickness: {exc} (a voussoir of this {self.shape} arch is too "
                             f"thin to have an area in floating point, or so thick where the "
                             f"arch turns that its faces cross)") from exc
        return (np.array([p[0] for p in props]), np.array([p[1] for p in props]),
                np.array([p[2] for p in props]))

    # ------------------------------------------------------------------ the contract
    @property
    def n_voussoirs(self) -> int:
        """Number of voussoirs n [-]."""
        return int(self.lengths.size)

    @property
    def shape(self) -> str:
        """Name of the centreline's shape."""
        return self.centreline.shape

    @property
    def span(self) -> float:
        """Span S of the centreline [m]."""
        return self.centreline.span

    @property
    def rise(self) -> float:
        """Rise H of the centreline [m]."""
        return self.centreline.rise

    @property
    def thickness_scale(self) -> float:
        """Mean thickness of the voussoirs [m]."""
        return float(np.mean(self.thicknesses))

    def outline(self, i: int, points: int = 24) -> np.ndarray:
        """Closed outline polygon of voussoir ``i`` [m] (``points`` per curved face)."""
        parts = []
        for piece in self.boundary(i):
            count = 2 if isinstance(piece, Segment) else max(2, int(points))
            parts.append(piece.points(count)[:-1])
        out = np.vstack(parts)
        return np.vstack((out, out[:1]))

    def mirrored(self) -> ShapedArch:
        """The arch mirrored about x = 0: the same (symmetric) centreline, the voussoirs in
        reverse order. Its joints and mass properties are this arch's, reflected (not
        recomputed)."""
        mirror = object.__new__(ShapedArch)
        for name in ("lengths", "thicknesses", "offsets"):
            arr = getattr(self, name)[::-1].copy()
            arr.setflags(write=False)
            object.__setattr__(mirror, name, arr)
        for name in ("centreline", "faces", "density"):
            object.__setattr__(mirror, name, getattr(self, name))
        flip = np.array([-1.0, 1.0])
        masses, centroids, inertias = self.masses, self.centroids, self.inertias
        cache = {"s": mirror._joint_positions(), "joints": frozen_array(self.joints[::-1] * flip),
                 "mass": (frozen_array(masses[::-1]), frozen_array(centroids[::-1] * flip),
                          frozen_array(inertias[::-1]))}
        object.__setattr__(mirror, "_cache", cache)
        return mirror

    def to_dict(self) -> dict:
        """``{"shape", <the centreline's parameters>, "faces", "lengths", "thicknesses",
        "offsets", "density"}`` (m, rad, kg/m^3), as read by :meth:`from_dict`."""
        return {"shape": self.shape, **dict(self.centreline.parameters), "faces": self.faces,
                "lengths": self.lengths.tolist(), "thicknesses": self.thicknesses.tolist(),
                "offsets": self.offsets.tolist(), "density": self.density}

    @classmethod
    def from_dict(cls, data: dict) -> ShapedArch:
        """The arch of :meth:`to_dict`."""
        keys = {"shape", "faces", "lengths", "thicknesses", "offsets", "density", "span", "rise",
                "radius", "embrace"}
        unknown = sorted(set(data) - keys)
        if unknown:
            raise ValueError(f"a shaped arch has unknown key(s) {unknown}; allowed: "
                             f"{sorted(keys)}")
        missing = [k for k in ("shape", "lengths", "thicknesses", "offsets") if k not in data]
        if missing:
            raise ValueError(f"a shaped arch is missing the key(s) {missing}")
        for key in ("lengths", "thicknesses", "offsets"):
            check_json_numbers(key, data[key], 1)
        for key in ("span", "rise", "radius", "embrace", "density"):
            if key in data:
                check_json_numbers(key, data[key], 0)
        line = centreline(data["shape"], data.get("span"), data.get("rise"),
                              radius=data.get("radius"), embrace=data.get("embrace"))
        return cls(line, data["lengths"], data["thicknesses"], data["offsets"],
                   data.get("faces", "curved"), data.get("density", DEFAULT_DENSITY))

    def perturbed(self, epsilon: float, draws: np.ndarray) -> ShapedArch:
        r"""The irregular arch of eq. (1) of the paper, generalised, for given uniform draws.

        For every voussoir :math:`i`:

        .. math::

            \tilde\ell_i = \ell_i \left(1 + \varepsilon\, \tilde p_{\alpha_i}\right), \qquad
            \tilde t_i = t_i \left(1 + \varepsilon\, \tilde p_{t_i}\right), \qquad
            \tilde\delta_i = \delta_i + \varepsilon\, t_i\, \tilde p_{R_i},

        the lengths then rescaled by a common factor so that they fill each smooth stretch of the
        centreline (the whole of it, or each half of a pointed arch, whose crown joint stays at
        the crown). On a circle of radius R this is the paper's eq. (1):
        :math:`\ell_i = R\alpha_i` and :math:`R + \tilde\delta_i = R_i (1 + \chi \tilde p)`.

        Parameters
        ----------
        epsilon : float
            :math:`\varepsilon` [-].
        draws : ndarray, shape (3, n)
            :math:`\tilde p` in [-1, 1]: row 0 lengths, row 1 thicknesses, row 2 shifts.

        Returns
        -------
        ShapedArch
        """
        eps, p = float(epsilon), np.asarray(draws, dtype=float)
        lengths = self.lengths * (1.0 + eps * p[0])
        s = self.joint_positions
        middle = 0.5 * (s[:-1] + s[1:])
        for start, end in self.centreline.segments:
            inside = (middle > start) & (middle < end)
            lengths[inside] *= (end - start) / lengths[inside].sum()
        thicknesses = self.thicknesses * (1.0 + eps * p[1])
        offsets = self.offsets + eps * self.thicknesses * p[2]
        return ShapedArch(self.centreline, lengths, thicknesses, offsets, self.faces,
                          self.density)


def shaped_arch(shape: str, *, thickness: float, voussoirs: int, span: float | None = None,
                rise: float | None = None, radius: float | None = None,
                embrace: float | None = None, faces: str = "curved",
                density: float = DEFAULT_DENSITY) -> ShapedArch:
    r"""Nominal arch of a shape: ``voussoirs`` equal voussoirs of constant thickness.

    Parameters
    ----------
    shape : str
        One of :data:`~archquake.geometry.centrelines.SHAPES`: ``"circular"``, ``"pointed"``,
        ``"elliptical"``, ``"parabolic"``, ``"catenary"``, ``"three-centred"``.
    thickness : float
        Thickness t normal to the centreline [m].
    voussoirs : int
        Number of voussoirs n [-], >= 4; even for a pointed arch.
    span, rise : float, optional
        Span S and rise H of the centreline [m] (every shape; see
        :mod:`archquake.geometry.centrelines` for the ranges).
    radius, embrace : float, optional
        For a circular arch, instead of span and rise: radius R [m] and embrace
        :math:`\alpha` [rad].
    faces : {"curved", "flat"}
        Voussoir faces.
    density : float, default 2000
        Density [kg/m^3].

    Returns
    -------
    ShapedArch
        Springings at :math:`(\mp S/2, 0)`, crown of the centreline at :math:`(0, H)`.

    Raises
    ------
    ValueError
        For an unknown shape or face, a parameter out of range, or conflicting parameters.

    Examples
    --------
    An equilateral pointed arch of 10 m span, 0.8 m thick, in 10 voussoirs; its crown joint
    (joint 5) is vertical:

    >>> arch = shaped_arch("pointed", span=10.0, rise=10.0 * 3**0.5 / 2, thickness=0.8,
    ...                    voussoirs=10)
    >>> arch.n_voussoirs, arch.is_symmetric(), bool(abs(arch.joint_angles[5] - math.pi / 2) < 1e-12)
    (10, True, True)
    """
    if not isinstance(shape, str) or shape not in SHAPES:
        raise ValueError(f"shape must be one of {SHAPES}, got {shape!r}")
    if faces not in VOUSSOIR_FACES:
        raise ValueError(f"faces must be one of {VOUSSOIR_FACES}, got {faces!r}")
    line = centreline(shape, span, rise, radius=radius, embrace=embrace)
    t = real_number("thickness", thickness, "m")
    if not (math.isfinite(t) and t > 0):
        raise ValueError(f"thickness must be a finite number > 0 [m], got {thickness!r}")
    n = check_voussoir_count(voussoirs)
    segments = line.segments
    if n % len(segments):
        raise ValueError(f"a {shape} arch needs a number of voussoirs divisible by "
                         f"{len(segments)} (a joint at its crown), got {n}")
    per = n // len(segments)
    lengths = np.concatenate([np.full(per, (end - start) / per) for start, end in segments])
    return ShapedArch(line, lengths, np.full(n, t), np.zeros(n), faces, density)
