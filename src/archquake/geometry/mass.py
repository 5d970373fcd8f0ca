r"""Mass properties of planar regions bounded by segments, circular arcs and smooth curves.

A block of an arch is a planar region whose boundary is a closed chain of *pieces*, each a
:class:`Segment`, an :class:`Arc` or a smooth parametric :class:`Curve`, traversed
counterclockwise. Its area, first moments and polar second moment follow from Green's theorem
as line integrals along the boundary: for a function :math:`f` homogeneous of degree
:math:`k` in the coordinates :math:`(x, y)` relative to a reference point,

.. math::

    \iint_\Omega f \,\mathrm dA = \frac{1}{k + 2} \oint_{\partial\Omega} f\,(x\,\mathrm dy
    - y\,\mathrm dx),

because :math:`\nabla\cdot(f\,(x, y)) = (k + 2) f` (Euler's theorem on homogeneous functions).
With :math:`f = 1, x, y, x^2 + y^2` it gives the area :math:`A`, the first moments
:math:`Q_x, Q_y` and the polar moment :math:`J` about the reference point. Every piece
contributes its own line integral, so a region is the sum of its pieces:

- a segment :math:`p_0 \to p_1`: in closed form (:math:`x\,\mathrm dy - y\,\mathrm dx` is
  constant along it, :math:`p_0 \times p_1`), the shoelace formulas of a polygon [1]_;
- an arc of a circle: in closed form, as the circular sector it spans (centre to the arc's
  ends) minus its two radial segments, so a region bounded by circular arcs is exact to
  round-off;
- a smooth curve: by composite Gauss-Legendre quadrature of the line integral, with panels
  doubled until two successive sums agree to :data:`CURVE_RTOL` (analytic curves converge
  exponentially; 10^-13 relative is reached with a few panels).

The reference point of a region is the start of its first piece (close to the region), which
keeps the sums free of cancellation far from the origin. Mass properties are per unit depth:
with density :math:`\rho` [kg/m^3], mass :math:`\rho A` [kg/m], centroid
:math:`(Q_x, Q_y)/A` [m] and polar moment of inertia about the centroid
:math:`\rho\,(J - |Q|^2/A)` [kg m].

References
----------
.. [1] Steger, C. (1996). On the calculation of arbitrary moments of polygons. Technical
   report FGBV-96-05, Technische Universitaet Muenchen (the polygon formulas).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

CURVE_RTOL = 1e-13
"""Relative agreement of two successive Gauss-Legendre sums (panels doubled) at which the line
integral along a smooth curve is accepted [-]."""

CURVE_NOISE_RTOL = 1e-9
"""Largest relative difference of two successive sums of :meth:`Curve.moments` accepted as the
noise of the integrand, when doubling the panels no longer reduces it [-]."""

_GAUSS_NODES = 20
_MAX_PANELS = 1024
_NODES, _WEIGHTS = np.polynomial.legendre.leggauss(_GAUSS_NODES)


def _cross(a, b):
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def _segment_moments(start, end, reference) -> tuple[float, float, float, float]:
    """``(A, Q_x, Q_y, J)`` of the segment ``start -> end`` about ``reference``: along it
    ``x dy - y dx`` is the constant ``p0 x p1`` (the shoelace formulas)."""
    x0, y0 = start[0] - reference[0], start[1] - reference[1]
    x1, y1 = end[0] - reference[0], end[1] - reference[1]
    c = x0 * y1 - x1 * y0
    return (c / 2.0, c * (x0 + x1) / 6.0, c * (y0 + y1) / 6.0,
            c * (x0 * x0 + x0 * x1 + x1 * x1 + y0 * y0 + y0 * y1 + y1 * y1) / 12.0)


@dataclass(frozen=True)
class Segment:
    """A straight piece of a boundary, from ``start`` to ``end`` [m]."""

    start: tuple[float, float]
    end: tuple[float, float]

    def __post_init__(self):
        object.__setattr__(self, "start", (float(self.start[0]), float(self.start[1])))
        object.__setattr__(self, "end", (float(self.end[0]), float(self.end[1])))

    def points(self, count: int = 2) -> np.ndarray:
        """``count`` points from ``start`` to ``end`` [m], shape (count, 2)."""
        tau = np.linspace(0.0, 1.0, max(int(count), 2))[:, None]
        return (1.0 - tau) * np.asarray(self.start) + tau * np.asarray(self.end)

    def moments(self, reference) -> tuple[float, float, float, float]:
        """Green line integrals ``(A, Q_x, Q_y, J)`` of this piece about ``reference`` [m^2,
        m^3, m^3, m^4]."""
        return _segment_moments(self.start, self.end, reference)


@dataclass(frozen=True)
class Arc:
    """An arc of a circle: centre [m], radius [m] and polar angles [rad] from ``start_angle`` to
    ``end_angle`` (counterclockwise when ``end_angle > start_angle``)."""

    centre: tuple[float, float]
    radius: float
    start_angle: float
    end_angle: float

    def __post_init__(self):
        object.__setattr__(self, "centre", (float(self.centre[0]), float(self.centre[1])))
        for name in ("radius", "start_angle", "end_angle"):
            object.__setattr__(self, name, float(getattr(self, name)))

    def _at(self, angle) -> np.ndarray:
        angle = np.asarray(angle, dtype=float)
        return np.asarray(self.centre) + self.radius * np.stack((np.cos(angle), np.sin(angle)),
                                                                axis=-1)

    def _point(self, angle: float) -> tuple[float, float]:
        return (self.centre[0] + self.radius * math.cos(angle),
                self.centre[1] + self.radius * math.sin(angle))

    @property
    def start(self) -> tuple[float, float]:
        """First point of the arc [m]."""
        return self._point(self.start_angle)

    @property
    def end(self) -> tuple[float, float]:
        """Last point of the arc [m]."""
        return self._point(self.end_angle)

    def points(self, count: int = 24) -> np.ndarray:
        """``count`` points along the arc [m], shape (count, 2), ends included."""
        return self._at(np.linspace(self.start_angle, self.end_angle, max(int(count), 2)))

    def moments(self, reference) -> np.ndarray:
        r"""Green line integrals ``(A, Q_x, Q_y, J)`` of the arc about ``reference``, exact.

        The closed loop centre -> start -> (arc) -> end -> centre bounds a circular sector of
        signed angle :math:`\Delta`, whose moments about the reference point at :math:`-q` from
        the centre are :math:`A = r^2\Delta/2`, :math:`Q = A q + (r^3/3) S` and
        :math:`J = |q|^2 A + (2 r^3/3)\, q\cdot S + r^4\Delta/4`, with
        :math:`S = \int u\,\mathrm d\theta = (\Delta\sin\theta, -\Delta\cos\theta)`; the arc
        is that loop minus its two radial segments.
        """
        qx, qy = self.centre[0] - reference[0], self.centre[1] - reference[1]
        r, t0, t1 = self.radius, self.start_angle, self.end_angle
        delta = t1 - t0
        sx, sy = math.sin(t1) - math.sin(t0), math.cos(t0) - math.cos(t1)
        area = 0.5 * r * r * delta
        r3 = r**3 / 3.0
        sector = (area, area * qx + r3 * sx, area * qy + r3 * sy,
                  (qx * qx + qy * qy) * area + 2.0 * r3 * (qx * sx + qy * sy)
                  + r**4 * delta / 4.0)
        a0 = _segment_moments(self.centre, self.start, reference)
        a1 = _segment_moments(self.end, self.centre, reference)
        return tuple(sector[k] - a0[k] - a1[k] for k in range(4))


@dataclass(frozen=True)
class Curve:
    """A smooth parametric piece: ``path(u)`` -> points (..., 2) [m] and ``velocity(u)`` ->
    derivatives (..., 2) [m per unit u], for ``u`` from ``start_parameter`` to
    ``end_parameter``.

    ``path`` and ``velocity`` must accept arrays of parameters; they are compared by equality
    (bound methods of equal objects compare equal), so a curve built from a value object is a
    value.
    """

    path: Callable[[np.ndarray], np.ndarray]
    velocity: Callable[[np.ndarray], np.ndarray]
    start_parameter: float
    end_parameter: float

    def __post_init__(self):
        object.__setattr__(self, "start_parameter", float(self.start_parameter))
        object.__setattr__(self, "end_parameter", float(self.end_parameter))

    @property
    def start(self) -> tuple[float, float]:
        """First point of the curve [m]."""
        return tuple(np.asarray(self.path(np.array([self.start_parameter])))[0].tolist())

    @property
    def end(self) -> tuple[float, float]:
        """Last point of the curve [m]."""
        return tuple(np.asarray(self.path(np.array([self.end_parameter])))[0].tolist())

    def points(self, count: int = 24) -> np.ndarray:
        """``count`` points along the curve [m], shape (count, 2), ends included."""
        u = np.linspace(self.start_parameter, self.end_parameter, max(int(count), 2))
        return np.asarray(self.path(u), dtype=float)

    def _gauss(self, reference, panels: int) -> tuple[np.ndarray, np.ndarray]:
        """The four line integrals with ``panels`` panels, and the same sums of the absolute
        values of their integrands (the scale against which convergence is judged)."""
        edges = np.linspace(self.start_parameter, self.end_parameter, panels + 1)
        half = 0.5 * np.diff(edges)
        u = (0.5 * (edges[:-1] + edges[1:]))[:, None] + half[:, None] * _NODES[None, :]
        w = (half[:, None] * _WEIGHTS[None, :]).ravel()
        p = np.asarray(self.path(u.ravel()), dtype=float) - reference
        dp = np.asarray(self.velocity(u.ravel()), dtype=float)
        c = _cross(p, dp) * w
        r2 = p[:, 0] ** 2 + p[:, 1] ** 2
        values = np.array([c.sum() / 2.0, (c * p[:, 0]).sum() / 3.0, (c * p[:, 1]).sum() / 3.0,
                           (c * r2).sum() / 4.0])
        a = np.abs(c)
        scale = np.array([a.sum() / 2.0, (a * np.sqrt(r2)).sum() / 3.0,
                          (a * np.sqrt(r2)).sum() / 3.0, (a * r2).sum() / 4.0])
        return values, scale

    def moments(self, reference) -> np.ndarray:
        """Green line integrals ``(A, Q_x, Q_y, J)`` of the curve about ``reference``, by
        composite Gauss-Legendre quadrature: 20 nodes per panel, panels doubled from 2 until two
        successive sums differ by at most :data:`CURVE_RTOL` times the integral of the absolute
        value of each integrand.

        A sum can also stop at the noise of its integrand: a small piece of a curve whose points
        are computed with round-off (a catenary's, far from the origin) gives sums that agree
        to that noise from the first panels, and more panels only draw more of it. When a
        doubling no longer halves the largest difference and that difference is below
        :data:`CURVE_NOISE_RTOL`, the sum has converged to the noise and is accepted (it used to
        go on to 1024 panels, making an arch of 10 000 curved voussoirs take minutes)."""
        panels = 2
        previous, _ = self._gauss(reference, panels)
        change = math.inf
        while True:
            panels *= 2
            current, scale = self._gauss(reference, panels)
            ratio = float(np.max(np.abs(current - previous) / np.maximum(scale, 1e-300)))
            if (ratio <= CURVE_RTOL or panels >= _MAX_PANELS
                    or (ratio <= CURVE_NOISE_RTOL and ratio > 0.5 * change)):
                return current
            previous, change = current, ratio


Piece = Segment | Arc | Curve
"""A piece of a boundary."""


def _check_chain(pieces: Sequence[Piece], name: str) -> float:
    """Check that the pieces form a closed chain; return a length scale of the region [m]."""
    if len(pieces) < 2:
        raise ValueError(f"{name} must be bounded by at least two pieces, got {len(pieces)}")
    ends = [(p.start, p.end) for p in pieces]
    xs = [q[0] for pair in ends for q in pair]
    ys = [q[1] for pair in ends for q in pair]
    if not all(math.isfinite(v) for v in xs + ys):
        raise ValueError(f"{name} has a boundary point that is not a finite number")
    size = max(max(xs) - min(xs), max(ys) - min(ys))
    for i, (_, end) in enumerate(ends):
        start = ends[(i + 1) % len(ends)][0]
        gap = math.hypot(end[0] - start[0], end[1] - start[1])
        if gap > 1e-9 * max(size, 1e-300):
            raise ValueError(f"{name}: the boundary is not closed (piece {i} ends {gap:.3g} m "
                             "away from the start of the next one)")
    return size


def region_moments(pieces: Sequence[Piece], reference) -> np.ndarray:
    """Signed area and moments ``(A, Q_x, Q_y, J)`` of the region bounded by ``pieces`` about
    ``reference`` [m^2, m^3, m^3, m^4] (positive for a counterclockwise boundary)."""
    reference = (float(reference[0]), float(reference[1]))
    total = [0.0, 0.0, 0.0, 0.0]
    for piece in pieces:
        moments = piece.moments(reference)
        for k in range(4):
            total[k] += float(moments[k])
    return np.array(total)


def region_properties(pieces: Sequence[Piece], density: float, *, name: str = "the region",
                      check: bool = True) -> tuple[float, np.ndarray, float]:
    """Mass [kg/m], centroid [m] and polar moment of inertia about the centroid [kg m] of the
    region bounded by the closed chain ``pieces``, per unit depth.

    Parameters
    ----------
    pieces : sequence of Segment, Arc or Curve
        The boundary, each piece starting where the previous one ends, the last ending where the
        first starts; counterclockwise or clockwise.
    density : float
        Density [kg/m^3].
    name : str
        How the region is named in error messages (e.g. ``"block 3"``).
    check : bool, default True
        Check that the pieces close the boundary; False for a boundary closed by construction
        (the blocks of a :class:`~archquake.geometry.ShapedArch`), whose area must then be
        counterclockwise.

    Returns
    -------
    mass : float
        [kg/m].
    centroid : ndarray, shape (2,)
        [m].
    inertia : float
        About the centroid [kg m].

    Raises
    ------
    ValueError
        When the boundary is not closed or encloses no area.
    """
    reference = np.array(pieces[0].start, dtype=float)
    a, qx, qy, j = region_moments(pieces, reference)
    if check:
        size = _check_chain(pieces, name)
        if not abs(a) > 1e-12 * size * size:
            raise ValueError(f"{name} encloses no area")
    elif not a > 0.0:
        raise ValueError(f"{name} encloses no area counterclockwise")
    if a < 0:
        a, qx, qy, j = -a, -qx, -qy, -j
    offset = np.array([qx, qy]) / a
    return float(density * a), reference + offset, float(density * (j - a * (offset @ offset)))


def polygon_properties(vertices, density: float, *, name: str = "the polygon"
                       ) -> tuple[float, np.ndarray, float]:
    """Mass [kg/m], centroid [m] and polar moment of inertia about the centroid [kg m] of a
    polygon, per unit depth (:func:`region_properties` of its edges).

    Parameters
    ----------
    vertices : array_like, shape (k, 2)
        Vertices [m] in order (either sense), not repeated at the end.
    density : float
        Density [kg/m^3].
    name : str
        How the polygon is named in error messages.
    """
    v = np.asarray(vertices, dtype=float)
    edges = [Segment(v[i], v[(i + 1) % len(v)]) for i in range(len(v))]
    return region_properties(edges, density, name=name)


def polygon_mass_properties(polygons, density) -> tuple[np.ndarray, np.ndarray, np.ndarray,
                                                        np.ndarray]:
    """Area [m^2], mass [kg/m], centroid [m] and polar moment about the centroid [kg m] of
    counter-clockwise polygons, per unit depth, by the shoelace formulas of the module,
    vectorised over the polygons (the straight edges of :func:`polygon_properties`, for many
    polygons at once).

    Parameters
    ----------
    polygons : sequence of array (k_i, 2)
        Counter-clockwise vertices [m], not repeated at the end.
    density : array of float, shape (n,)
        Density of every polygon [kg/m^3].

    Returns
    -------
    area, mass : ndarray (n,)
    centroid : ndarray (n, 2)
    inertia : ndarray (n,)
    """
    counts = np.array([len(p) for p in polygons])
    starts = np.concatenate(([0], np.cumsum(counts)[:-1]))
    v = np.vstack(polygons)
    owner = np.repeat(np.arange(counts.size), counts)
    reference = v[starts]
    p = v - reference[owner]  # about each polygon's first vertex: no cancellation far away
    nxt = np.arange(len(v)) + 1
    nxt[starts + counts - 1] = starts
    q = p[nxt]
    c = p[:, 0] * q[:, 1] - p[:, 1] * q[:, 0]
    x0, y0, x1, y1 = p[:, 0], p[:, 1], q[:, 0], q[:, 1]
    area = np.add.reduceat(c, starts) / 2.0
    qx = np.add.reduceat(c * (x0 + x1), starts) / 6.0
    qy = np.add.reduceat(c * (y0 + y1), starts) / 6.0
    j = np.add.reduceat(c * (x0 * x0 + x0 * x1 + x1 * x1 + y0 * y0 + y0 * y1 + y1 * y1),
                        starts) / 12.0
    offset = np.column_stack((qx, qy)) / area[:, None]
    density = np.asarray(density, dtype=float)
    inertia = density * (j - area * np.sum(offset * offset, axis=1))
    return area, density * area, reference + offset, inertia
