r"""Centrelines of arches: circular, pointed, elliptical, parabolic, catenary, three-centred.

A centreline is a plane curve from the left springing to the right springing, made of smooth
*parts* (circular arcs or analytic curves) joined end to end. Every shape is given by its span
:math:`S` and rise :math:`H` [m] (those of the centreline), in the frame

- x to the right, y up; the springings at :math:`(\mp S/2, 0)`, the crown at :math:`(0, H)`;
  every shape is symmetric about x = 0.

The constructions are the traditional ones of masonry arches [1]_ [2]_. Position along a
centreline is its arc length :math:`s` from the left springing, :math:`0 \le s
\le L`. At every point of a part the unit tangent :math:`\mathbf T` points along the arch
(left to right) and the unit normal :math:`\mathbf N` is :math:`\mathbf T` turned by +90
degrees: it points out of the arch, toward the extrados. Where two parts meet with different
tangents (the crown of a pointed arch) the centreline has a *corner*.

The shapes (:data:`CENTRELINES`):

``circular``
    A circular arc through the springings and the crown: radius
    :math:`R = (S^2/4 + H^2) / (2H)`, centre :math:`(0, H - R)`, embrace
    :math:`\alpha = 2\,\mathrm{atan2}(S/2, R - H)` (any rise > 0: segmental for
    :math:`H < S/2`, a semicircle for :math:`H = S/2`, a horseshoe above). Or given by its radius
    and embrace: :math:`S = 2R\sin(\alpha/2)`, :math:`H = R(1 - \cos(\alpha/2))`.
``pointed``
    Two-centred (Gothic): two circular arcs meeting at the crown, each centred on the springing
    line, the left one at :math:`(c, 0)` and the right one at :math:`(-c, 0)` with
    :math:`c = (H^2 - S^2/4)/S`, radius :math:`R = c + S/2`; rise :math:`H > S/2`
    (:math:`H = S\sqrt3/2` is the equilateral arch, :math:`R = S`).
``elliptical``
    Half an ellipse with semi-axes :math:`S/2` (horizontal) and :math:`H` (vertical), centred
    at the origin: :math:`(-\tfrac S2\cos u, H\sin u)`, :math:`0 \le u \le \pi`; the springings
    are the ends of the horizontal axis.
``parabolic``
    :math:`y = H\,(1 - 4x^2/S^2)`.
``catenary``
    :math:`y = H - a\,(\cosh(x/a) - 1)`, with :math:`a` [m] the root of
    :math:`a(\cosh(S/(2a)) - 1) = H`: the funicular of a load uniform along the curve.
``three-centred``
    The classical basket handle (anse de panier) of three tangent circular arcs that subtend
    equal angles of 60 degrees: side arcs of radius
    :math:`r_1 = (H - S(1 - \sqrt3/2))/(\sqrt3 - 1)` centred on the springing line at
    :math:`(\mp(S/2 - r_1), 0)` (so the springings are vertical), and a crown arc of radius
    :math:`r_2 = S - r_1` centred at :math:`(0, H - r_2)`. It needs
    :math:`S(1 - \sqrt3/2) < H \le S/2` (about :math:`0.134 S < H \le 0.5 S`); at
    :math:`H = S/2` it is the semicircle.

References
----------
.. [1] Heyman, J. (1982). The Masonry Arch. Chichester: Ellis Horwood (arch shapes, the
   catenary as the line of thrust of a uniform arch).
.. [2] Huerta, S. (2004). Arcos, bovedas y cupulas. Geometria y equilibrio en el calculo
   tradicional de estructuras de fabrica. Madrid: Instituto Juan de Herrera (the traditional
   constructions of pointed and basket-handle arches).
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from .. import defaults
from .blocks import check_length, real_number
from .mass import Arc, Curve, Piece

SQRT3 = math.sqrt(3.0)


def _angle(name: str, value) -> float:
    value = real_number(name, value, "rad")
    if not math.isfinite(value) or value <= 0.0:
        raise ValueError(f"{name} must be a finite number > 0 [rad], got {value!r}")
    return value


def _rot90(v):
    v = np.asarray(v, dtype=float)
    return np.stack((-v[..., 1], v[..., 0]), axis=-1)


# ---------------------------------------------------------------------------------- parts
class Part(ABC):
    """A smooth part of a centreline, parametrised by ``u`` increasing from ``u0`` (its left
    end) to ``u1`` (its right end)."""

    u0: float
    u1: float

    @abstractmethod
    def point(self, u) -> np.ndarray:
        """Point(s) of the part at parameter ``u`` [m], shape (..., 2)."""

    @abstractmethod
    def first(self, u) -> np.ndarray:
        """First derivative with respect to ``u`` [m per unit u], shape (..., 2)."""

    @abstractmethod
    def second(self, u) -> np.ndarray:
        """Second derivative with respect to ``u``, shape (..., 2)."""

    @abstractmethod
    def arc_length(self, u) -> np.ndarray:
        """Arc length from ``u0`` to ``u`` [m]."""

    @abstractmethod
    def crown_parameter(self) -> float | None:
        """Parameter of the largest curvature inside the part, if not at an end (else None)."""

    @cached_property
    def length(self) -> float:
        """Arc length of the part [m]."""
        return float(self.arc_length(self.u1))

    def parameters(self, s) -> np.ndarray:
        """Parameters ``u`` at arc lengths ``s`` [m] from the part's left end, clipped to the
        part (Newton's method safeguarded by bisection, to round-off; vectorised)."""
        s = np.clip(np.asarray(s, dtype=float), 0.0, self.length)
        lo = np.full(s.shape, float(self.u0))
        hi = np.full(s.shape, float(self.u1))
        u = lo + (hi - lo) * s / self.length
        for _ in range(100):
            f = self.arc_length(u) - s
            lo = np.where(f <= 0, u, lo)
            hi = np.where(f > 0, u, hi)
            nxt = u - f / np.hypot(*np.moveaxis(self.first(u), -1, 0))
            nxt = np.where((lo <= nxt) & (nxt <= hi), nxt, 0.5 * (lo + hi))
            nxt = np.where(f == 0.0, u, nxt)
            done = np.abs(nxt - u) <= 4e-16 * np.maximum(1.0, np.abs(u))
            u = nxt
            if np.all(done):
                break
        return u

    def parameter(self, s: float) -> float:
        """Parameter ``u`` at arc length ``s`` [m] from the part's left end."""
        return float(self.parameters(np.array([s]))[0])

    def tangent(self, u) -> np.ndarray:
        """Unit tangent (left to right) [-], shape (..., 2)."""
        d = self.first(u)
        return d / np.linalg.norm(d, axis=-1, keepdims=True)

    def normal(self, u) -> np.ndarray:
        """Unit normal toward the extrados (the tangent turned by +90 degrees) [-]."""
        return _rot90(self.tangent(u))

    def curvature(self, u) -> np.ndarray:
        """Signed curvature [1/m]: negative where the part turns clockwise (an arch's)."""
        d1, d2 = self.first(u), self.second(u)
        cross = d1[..., 0] * d2[..., 1] - d1[..., 1] * d2[..., 0]
        return cross / np.linalg.norm(d1, axis=-1) ** 3

    def max_curvature(self, ua: float, ub: float) -> float:
        """Largest absolute curvature on ``[ua, ub]`` [1/m] (every part's curvature is monotone
        on either side of its crown parameter)."""
        candidates = [ua, ub]
        crown = self.crown_parameter()
        if crown is not None and ua < crown < ub:
            candidates.append(crown)
        return float(np.max(np.abs(self.curvature(np.array(candidates)))))

    def offset_point(self, u, offset: float) -> np.ndarray:
        """Point at distance ``offset`` along the normal [m] (toward the extrados if > 0)."""
        return self.point(u) + offset * self.normal(u)

    def offset_piece(self, offset: float, ua: float, ub: float) -> Piece:
        """The offset curve at ``offset`` [m] from ``ua`` to ``ub``, as a boundary piece."""
        offset = float(offset)
        return Curve(_OffsetPath(self, offset, False), _OffsetPath(self, offset, True), ua, ub)


@dataclass(frozen=True)
class _OffsetPath:
    """``u -> C(u) + d N(u)`` or its derivative ``C'(u) (1 - d kappa(u))``."""

    part: Part
    offset: float
    derivative: bool

    def __call__(self, u):
        u = np.asarray(u, dtype=float)
        if self.derivative:
            return self.part.first(u) * (1.0 - self.offset * self.part.curvature(u))[..., None]
        return self.part.offset_point(u, self.offset)


@dataclass(frozen=True)
class ArcPart(Part):
    """A circular arc traversed clockwise (as an arch, left to right over the top).

    The parameter is the arc length from the left end, ``u = R (start_angle - polar angle)``.

    Parameters
    ----------
    centre : (float, float)
        Centre [m].
    radius : float
        Radius R [m].
    start_angle, end_angle : float
        Polar angles of the left and right ends [rad], ``start_angle > end_angle``.
    """

    centre: tuple[float, float]
    radius: float
    start_angle: float
    end_angle: float

    def __post_init__(self):
        object.__setattr__(self, "centre", (float(self.centre[0]), float(self.centre[1])))
        for name in ("radius", "start_angle", "end_angle"):
            object.__setattr__(self, name, float(getattr(self, name)))

    @property
    def u0(self) -> float:
        return 0.0

    @property
    def u1(self) -> float:
        return self.radius * (self.start_angle - self.end_angle)

    def angle(self, u) -> np.ndarray:
        """Polar angle about the centre at parameter ``u`` [rad]."""
        return self.start_angle - np.asarray(u, dtype=float) / self.radius

    def _radial(self, u) -> np.ndarray:
        a = self.angle(u)
        return np.stack((np.cos(a), np.sin(a)), axis=-1)

    def point(self, u):
        return np.asarray(self.centre) + self.radius * self._radial(u)

    def first(self, u):
        return -_rot90(self._radial(u))

    def second(self, u):
        return -self._radial(u) / self.radius

    def arc_length(self, u):
        return np.asarray(u, dtype=float)

    def parameters(self, s):
        return np.clip(np.asarray(s, dtype=float), 0.0, self.u1)

    def crown_parameter(self):
        return None

    def normal(self, u):
        return self._radial(u)

    def curvature(self, u):
        return np.full(np.shape(u), -1.0 / self.radius)

    def max_curvature(self, ua, ub):
        return 1.0 / self.radius

    def offset_piece(self, offset, ua, ub):
        return Arc(self.centre, self.radius + offset, self.start_angle - ua / self.radius,
                   self.start_angle - ub / self.radius)

    def offset_parameter_on_line(self, offset: float, base, direction) -> float:
        """Parameter at which the offset arc at ``offset`` [m] meets the line through ``base``
        along the unit ``direction`` (the intersection nearest to ``base``)."""
        r = self.radius + offset
        p = np.asarray(base, dtype=float) - np.asarray(self.centre)
        w = np.asarray(direction, dtype=float)
        b = p @ w
        disc = b * b - (p @ p - r * r)
        if disc < 0:
            raise ValueError("an offset of the arch misses its crown joint (thickness too large)")
        lam = min((-b - math.sqrt(disc), -b + math.sqrt(disc)), key=abs)
        q = p + lam * w
        return self.radius * (self.start_angle - math.atan2(q[1], q[0]))


@dataclass(frozen=True)
class EllipsePart(Part):
    """Half an ellipse ``(-a cos u, b sin u)``, ``0 <= u <= pi`` [m]."""

    a: float
    b: float

    @property
    def u0(self) -> float:
        return 0.0

    @property
    def u1(self) -> float:
        return math.pi

    def point(self, u):
        u = np.asarray(u, dtype=float)
        return np.stack((-self.a * np.cos(u), self.b * np.sin(u)), axis=-1)

    def first(self, u):
        u = np.asarray(u, dtype=float)
        return np.stack((self.a * np.sin(u), self.b * np.cos(u)), axis=-1)

    def second(self, u):
        u = np.asarray(u, dtype=float)
        return np.stack((self.a * np.cos(u), -self.b * np.sin(u)), axis=-1)

    def arc_length(self, u):
        from scipy.special import ellipeinc

        # |C'| = sqrt(a^2 sin^2 u + b^2 cos^2 u) = b sqrt(1 - m sin^2 u), m = 1 - a^2/b^2
        return self.b * ellipeinc(np.asarray(u, dtype=float), 1.0 - (self.a / self.b) ** 2)

    def crown_parameter(self):
        return 0.5 * math.pi


@dataclass(frozen=True)
class ParabolaPart(Part):
    """The parabola ``y = H (1 - 4 x^2 / S^2)``, parameter ``u = x``."""

    span: float
    rise: float

    @property
    def u0(self) -> float:
        return -0.5 * self.span

    @property
    def u1(self) -> float:
        return 0.5 * self.span

    @property
    def _c(self) -> float:
        return 4.0 * self.rise / self.span**2  # y = H - c x^2

    def point(self, u):
        u = np.asarray(u, dtype=float)
        return np.stack((u, self.rise - self._c * u * u), axis=-1)

    def first(self, u):
        u = np.asarray(u, dtype=float)
        return np.stack((np.ones_like(u), -2.0 * self._c * u), axis=-1)

    def second(self, u):
        u = np.asarray(u, dtype=float)
        return np.stack((np.zeros_like(u), np.full_like(u, -2.0 * self._c)), axis=-1)

    def _primitive(self, x):
        k = 2.0 * self._c
        p = k * np.asarray(x, dtype=float)
        return (p * np.sqrt(1.0 + p * p) + np.arcsinh(p)) / (2.0 * k)

    def arc_length(self, u):
        return self._primitive(u) - self._primitive(self.u0)

    def crown_parameter(self):
        return 0.0


@dataclass(frozen=True)
class CatenaryPart(Part):
    """The catenary ``y = H - a (cosh(x/a) - 1)``, parameter ``u = x``."""

    span: float
    rise: float
    a: float

    @property
    def u0(self) -> float:
        return -0.5 * self.span

    @property
    def u1(self) -> float:
        return 0.5 * self.span

    def point(self, u):
        u = np.asarray(u, dtype=float)
        return np.stack((u, self.rise - self.a * (np.cosh(u / self.a) - 1.0)), axis=-1)

    def first(self, u):
        u = np.asarray(u, dtype=float)
        return np.stack((np.ones_like(u), -np.sinh(u / self.a)), axis=-1)

    def second(self, u):
        u = np.asarray(u, dtype=float)
        return np.stack((np.zeros_like(u), -np.cosh(u / self.a) / self.a), axis=-1)

    def arc_length(self, u):
        return self.a * (np.sinh(np.asarray(u, dtype=float) / self.a)
                         - math.sinh(self.u0 / self.a))

    def parameters(self, s):
        s = np.clip(np.asarray(s, dtype=float), 0.0, self.length)
        return self.a * np.arcsinh(s / self.a + math.sinh(self.u0 / self.a))

    def crown_parameter(self):
        return 0.0


# ---------------------------------------------------------------------------------- centreline
@dataclass(frozen=True)
class Centreline:
    """The centreline of an arch: smooth parts from the left to the right springing.

    Build it with :func:`centreline` (or one of the shape functions of :data:`CENTRELINES`).

    Parameters
    ----------
    shape : str
        Name of the shape (a key of :data:`CENTRELINES`).
    span, rise : float
        Span S and rise H of the centreline [m].
    parts : tuple of Part
        The smooth parts, left to right, each ending where the next begins.
    radius : float or None
        Radius R [m] of a circular centreline (None for other shapes).
    parameters : tuple of (str, float)
        The arguments it was built from, ``(("span", S), ("rise", H))`` or, for a circle given
        by its angle, ``(("radius", R), ("embrace", alpha))`` [m, rad]: building it again from
        them gives the same centreline to the last bit.
    """

    shape: str
    span: float
    rise: float
    parts: tuple[Part, ...]
    radius: float | None = None
    parameters: tuple[tuple[str, float], ...] = ()

    @cached_property
    def part_lengths(self) -> np.ndarray:
        """Arc length of every part [m]."""
        return np.array([p.length for p in self.parts])

    @cached_property
    def part_starts(self) -> np.ndarray:
        """Arc length s at the start of every part, and the total length at the end [m]."""
        return np.concatenate(([0.0], np.cumsum(self.part_lengths)))

    @property
    def length(self) -> float:
        """Arc length L of the centreline from springing to springing [m]."""
        return float(self.part_starts[-1])

    @cached_property
    def corners(self) -> tuple[float, ...]:
        """Arc lengths s of the corners [m] (where the tangent jumps: the crown of a pointed
        arch)."""
        starts = self.part_starts
        out = []
        for i in range(1, len(self.parts)):
            left = self.parts[i - 1].tangent(self.parts[i - 1].u1)
            right = self.parts[i].tangent(self.parts[i].u0)
            if float(left @ right) < 1.0 - 1e-12:
                out.append(float(starts[i]))
        return tuple(out)

    @property
    def segments(self) -> tuple[tuple[float, float], ...]:
        """The smooth stretches between corners, ``(s_start, s_end)`` [m]: the whole
        centreline, or its two halves for a pointed arch."""
        ends = (0.0, *self.corners, self.length)
        return tuple(zip(ends[:-1], ends[1:], strict=True))

    def stations(self, s, side: str = "right") -> tuple[np.ndarray, np.ndarray]:
        """``(part indices, parameters u)`` of arc lengths ``s`` [m] (vectorised); at a junction
        of two parts, the part on ``side`` (``"left"`` or ``"right"``) of it."""
        s = np.atleast_1d(np.asarray(s, dtype=float))
        starts = self.part_starts
        index = np.searchsorted(starts, s, side="right" if side == "right" else "left") - 1
        index = np.clip(index, 0, len(self.parts) - 1)
        u = np.empty(s.shape)
        for i, part in enumerate(self.parts):
            here = index == i
            if np.any(here):
                u[here] = part.parameters(s[here] - starts[i])
        return index, u

    def locate(self, s: float, side: str = "right") -> tuple[int, float]:
        """``(part index, parameter u)`` of arc length ``s`` [m]; at a junction of two parts,
        the part on ``side`` (``"left"`` or ``"right"``) of it."""
        index, u = self.stations(s, side)
        return int(index[0]), float(u[0])

    def point(self, s: float) -> np.ndarray:
        """Point of the centreline at arc length ``s`` [m]."""
        i, u = self.locate(s)
        return self.parts[i].point(u)

    def normal(self, s: float, side: str = "right") -> np.ndarray:
        """Unit normal toward the extrados at arc length ``s`` [-]."""
        i, u = self.locate(s, side)
        return self.parts[i].normal(u)

    def tangent(self, s: float, side: str = "right") -> np.ndarray:
        """Unit tangent (left to right) at arc length ``s`` [-]."""
        i, u = self.locate(s, side)
        return self.parts[i].tangent(u)

    def max_curvature(self, start: tuple[int, float], end: tuple[int, float]) -> float:
        """Largest absolute curvature [1/m] between two stations ``(part, u)`` (left to
        right)."""
        kappa = 0.0
        for i in range(start[0], end[0] + 1):
            part = self.parts[i]
            lo = start[1] if i == start[0] else part.u0
            hi = end[1] if i == end[0] else part.u1
            kappa = max(kappa, part.max_curvature(lo, hi))
        return kappa

    def min_radius_of_curvature(self, s0: float, s1: float) -> float:
        """Smallest radius of curvature of the centreline between arc lengths ``s0 < s1`` [m]."""
        kappa = self.max_curvature(self.locate(s0, "right"), self.locate(s1, "left"))
        return math.inf if kappa == 0.0 else 1.0 / kappa

    def offset_pieces(self, offset: float, start: tuple[int, float],
                      end: tuple[int, float]) -> list[Piece]:
        """The offset curve at ``offset`` [m] between two stations ``(part, u)`` of one smooth
        stretch, as boundary pieces left to right (one per part crossed)."""
        pieces = []
        for i in range(start[0], end[0] + 1):
            part = self.parts[i]
            lo = start[1] if i == start[0] else part.u0
            hi = end[1] if i == end[0] else part.u1
            pieces.append(part.offset_piece(offset, lo, hi))
        return pieces


# ---------------------------------------------------------------------------------- shapes
def _span_rise(span, rise) -> tuple[float, float]:
    return check_length("span", span), check_length("rise", rise)


def circular_centreline(span: float | None = None, rise: float | None = None, *,
                        radius: float | None = None, embrace: float | None = None) -> Centreline:
    r"""Circular centreline by span and rise [m], or by radius [m] and embrace [rad].

    Parameters
    ----------
    span, rise : float, optional
        Span S and rise H [m] (both, or neither).
    radius : float, optional
        Radius R [m] (with ``embrace``, instead of span and rise).
    embrace : float, optional
        Angle of embrace :math:`\alpha` [rad], in :math:`(0, 2\pi)`.

    Returns
    -------
    Centreline
        Springings at :math:`(\mp S/2, 0)`, centre :math:`(0, H - R)`.
    """
    by_size = span is not None or rise is not None
    by_angle = radius is not None or embrace is not None
    if by_size and by_angle:
        raise ValueError("a circular centreline is given by span and rise, or by radius and "
                         "embrace, not both")
    if by_angle:
        if radius is None or embrace is None:
            raise ValueError("a circular centreline by angle needs both radius [m] and embrace "
                             "[rad]")
        radius = check_length("radius", radius)
        embrace = _angle("embrace", embrace)
        if embrace >= 2.0 * math.pi:
            raise ValueError(f"embrace must be in (0, 360) degrees, got "
                             f"{math.degrees(embrace):.6g} degrees")
        span = 2.0 * radius * math.sin(0.5 * embrace)
        rise = radius * (1.0 - math.cos(0.5 * embrace))
        parameters = (("radius", radius), ("embrace", embrace))
    else:
        if span is None or rise is None:
            raise ValueError("a circular centreline needs span and rise [m] (or radius and "
                             "embrace)")
        span, rise = _span_rise(span, rise)
        radius = (0.25 * span * span + rise * rise) / (2.0 * rise)
        embrace = 2.0 * math.atan2(0.5 * span, radius - rise)
        parameters = (("span", span), ("rise", rise))
    centre = (0.0, rise - radius)
    half = 0.5 * embrace
    part = ArcPart(centre, radius, 0.5 * math.pi + half, 0.5 * math.pi - half)
    return Centreline("circular", span, rise, (part,), radius, parameters)


def pointed_centreline(span: float, rise: float) -> Centreline:
    """Two-centred (pointed) centreline: two arcs centred on the springing line, meeting at the
    crown; ``rise > span / 2`` [m]."""
    span, rise = _span_rise(span, rise)
    if not rise > 0.5 * span:
        raise ValueError(f"a pointed arch needs rise > span / 2 = {0.5 * span:g} m, got rise = "
                         f"{rise:g} m")
    c = (rise * rise - 0.25 * span * span) / span
    radius = c + 0.5 * span
    left = ArcPart((c, 0.0), radius, math.pi, math.atan2(rise, -c))
    right = ArcPart((-c, 0.0), radius, math.atan2(rise, c), 0.0)
    return Centreline("pointed", span, rise, (left, right), radius,
                      (("span", span), ("rise", rise)))


def elliptical_centreline(span: float, rise: float) -> Centreline:
    """Half an ellipse with semi-axes ``span / 2`` and ``rise`` [m]."""
    span, rise = _span_rise(span, rise)
    return Centreline("elliptical", span, rise, (EllipsePart(0.5 * span, rise),), None,
                      (("span", span), ("rise", rise)))


def parabolic_centreline(span: float, rise: float) -> Centreline:
    """The parabola ``y = rise (1 - 4 x^2 / span^2)`` [m]."""
    span, rise = _span_rise(span, rise)
    return Centreline("parabolic", span, rise, (ParabolaPart(span, rise),), None,
                      (("span", span), ("rise", rise)))


def catenary_parameter(span: float, rise: float) -> float:
    """The parameter a [m] of the catenary ``y = rise - a (cosh(x/a) - 1)`` through the
    springings ``(-+span/2, 0)``: the root of ``(cosh z - 1) / z = 2 rise / span``,
    ``z = span / (2a)``, by bisection to round-off."""
    target = 2.0 * rise / span
    lo, hi = 0.0, 1.0
    while (math.cosh(hi) - 1.0) / hi < target:
        hi *= 2.0
        if hi > 700.0:
            raise ValueError(f"a catenary of rise/span = {rise / span:g} is beyond range")
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if mid in (lo, hi):
            break
        value = (math.cosh(mid) - 1.0) / mid if mid > 0 else 0.0
        if value < target:
            lo = mid
        else:
            hi = mid
    z = 0.5 * (lo + hi)
    return 0.5 * span / z


def catenary_centreline(span: float, rise: float) -> Centreline:
    """The catenary through the springings and the crown [m]."""
    span, rise = _span_rise(span, rise)
    return Centreline("catenary", span, rise,
                      (CatenaryPart(span, rise, catenary_parameter(span, rise)),), None,
                      (("span", span), ("rise", rise)))


def three_centred_centreline(span: float, rise: float) -> Centreline:
    r"""Basket-handle centreline of three tangent arcs of 60 degrees each [m].

    Side radius :math:`r_1 = (H - S(1 - \sqrt3/2))/(\sqrt3 - 1)`, crown radius
    :math:`r_2 = S - r_1`; needs :math:`S(1 - \sqrt3/2) < H \le S/2`.
    """
    span, rise = _span_rise(span, rise)
    low = span * (1.0 - 0.5 * SQRT3)
    if not (low < rise <= 0.5 * span * (1.0 + 1e-12)):
        raise ValueError(
            f"a three-centred arch (three arcs of 60 degrees) needs span (1 - sqrt(3)/2) = "
            f"{low:.6g} m < rise <= span / 2 = {0.5 * span:g} m, got rise = {rise:g} m")
    r1 = (rise - low) / (SQRT3 - 1.0)
    r2 = span - r1
    third = math.pi / 3.0
    left = ArcPart((-0.5 * span + r1, 0.0), r1, math.pi, 2.0 * third)
    crown = ArcPart((0.0, rise - r2), r2, 2.0 * third, third)
    right = ArcPart((0.5 * span - r1, 0.0), r1, third, 0.0)
    return Centreline("three-centred", span, rise, (left, crown, right), None,
                      (("span", span), ("rise", rise)))


CENTRELINES = {
    "circular": circular_centreline,
    "pointed": pointed_centreline,
    "elliptical": elliptical_centreline,
    "parabolic": parabolic_centreline,
    "catenary": catenary_centreline,
    "three-centred": three_centred_centreline,
}
"""The shapes by name, each ``f(span, rise) -> Centreline`` [m]."""

SHAPES: tuple[str, ...] = defaults.SHAPES
"""Names of the shapes: circular, pointed, elliptical, parabolic, catenary, three-centred (the
keys of :data:`CENTRELINES`; named in :mod:`archquake.defaults`, which the command line reads
without importing the geometry)."""


def centreline(shape: str, span: float | None = None, rise: float | None = None, *,
               radius: float | None = None, embrace: float | None = None) -> Centreline:
    """The centreline of ``shape`` with the given span and rise [m] (a circle also by radius
    and embrace).

    Parameters
    ----------
    shape : str
        One of :data:`SHAPES`.
    span, rise : float
        Span S and rise H of the centreline [m].
    radius, embrace : float, optional
        For a circular centreline, instead of span and rise: radius R [m] and embrace [rad].

    Returns
    -------
    Centreline

    Raises
    ------
    ValueError
        For an unknown shape (the message lists them), a span or rise out of the shape's range,
        or radius and embrace for another shape than a circle.

    Examples
    --------
    >>> line = centreline("pointed", 10.0, 8.0)
    >>> round(line.length, 6), line.corners == (line.length / 2,)
    (19.886136, True)
    """
    if not isinstance(shape, str) or shape not in CENTRELINES:
        raise ValueError(f"shape must be one of {SHAPES}, got {shape!r}")
    if shape == "circular":
        return circular_centreline(span, rise, radius=radius, embrace=embrace)
    if radius is not None or embrace is not None:
        raise ValueError(f"radius and embrace define circular arches only; a {shape!r} arch is "
                         "given by span and rise")
    if span is None or rise is None:
        raise ValueError(f"a {shape!r} arch needs span and rise [m]")
    return CENTRELINES[shape](span, rise)
