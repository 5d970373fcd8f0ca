r"""Fill over an arch: what it weighs, where its weight and its inertia act, and the passive
reaction of the soil.

The basic model of a level fill (a bridge's fill, or the fill over a vault between buttresses)
as rigid-block analyses of masonry arches commonly take it [1]_ [2]_:

- **Geometry.** The fill's level surface stands at :math:`y_{top} = y_c + d`, with :math:`y_c`
  the top of the extrados (the crown) and :math:`d` the ``cover`` [m]. The fill over voussoir
  :math:`i` is the *column* between the vertical lines through the two ends of the voussoir's
  extrados, the extrados and the level surface; fill beyond the extrados springing points rests
  on the supports (piers, abutments) and is ignored. The columns are exact regions (the
  voussoir's extrados as it is: arcs, offset curves or segments; :mod:`archquake.geometry.mass`)
  of density :math:`\rho_f` [kg/m^3].
- **Weight.** The column's weight :math:`m_{f,i} g` is a vertical dead load on voussoir
  :math:`i` along the vertical through the column's centroid (the fill transmits no shear
  between columns, nor any load to the voussoir but this one).
- **Inertia** under a horizontal acceleration :math:`k g` (:data:`FILL_INERTIA_MODELS`):
  ``"none"`` (dead load only: the fill adds weight but no horizontal force), ``"centroid"``
  (the horizontal force :math:`k\,m_{f,i} g` through the column's centroid: the fill moves
  with its voussoir), ``"extrados"`` (the same force applied on the extrados at the point below
  the column's centroid). The default, ``"centroid"``, is the only one in which the fill is a
  mass: the dynamic models carry the fill as mass rigidly attached to each voussoir
  (:attr:`~archquake.geometry.Structure.masses`), so that only with it does the activation of
  the motion equal the limit analysis' load multiplier; it is also the most unfavourable of the
  three for an arch, whose horizontal force acts highest.
- **Passive reaction** (optional, angle of friction :math:`\phi` and mobilisation
  :math:`m_p`): on each voussoir a horizontal reaction pushing toward midspan (the middle of
  the extrados springing points), of magnitude

  .. math::

      0 \le P_i \le m_p\, K_p\, \gamma_f\, (y_{top} - y_{mid,i})\, \Delta y_i, \qquad
      K_p = \tan^2\!\left(\frac{\pi}{4} + \frac{\phi}{2}\right), \quad
      \gamma_f = \rho_f g,

  with :math:`\Delta y_i` the height range of the voussoir's extrados and :math:`y_{mid,i}`
  its middle (Rankine's passive pressure at mid-height times the height the voussoir offers,
  a fraction :math:`m_p` of it mobilised), applied on the extrados at :math:`y_{mid,i}`. A
  voussoir whose extrados straddles midspan gets none (its two sides push against each other).
  In the limit analysis :math:`P_i` is an unknown bounded as above: a resistance the fill
  offers, not a load.

Limits of the model: the fill has no strength of its own, spreads no load (a column loads only
its voussoir, vertically), and its passive reaction is a bound on a horizontal force, not a
soil model: the displacement needed to mobilise it is not checked, and the dynamic models
leave it out (they carry the fill's mass, not its resistance).

References
----------
.. [1] Gilbert, M. (2007). Limit analysis applied to masonry arch bridges: state-of-the-art and
   recent developments. Proc. 5th International Arch Bridges Conference, Madeira, 13-28.
.. [2] Heyman, J. (1982). The Masonry Arch. Chichester: Ellis Horwood (fill as dead load).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .._equality import value_equality
from ..constants import DEFAULT_FILL_DENSITY, GRAVITY
from ..defaults import DEFAULT_FILL_INERTIA, FILL_INERTIA_MODELS
from .blocks import LENGTH_RANGE, BlockArch, check_json_numbers, frozen_array, real_number
from .mass import Arc, Segment, region_moments

DYNAMIC_FILL_INERTIA = "centroid"
"""The inertia model of the fill in both dynamic models (mass rigidly attached to its
voussoir)."""


def _check_number(name: str, value, low: float, high: float, unit: str, *,
                  closed_low: bool = True) -> float:
    x = real_number(name, value, unit)
    ok = math.isfinite(x) and (x >= low if closed_low else x > low) and x <= high
    if not ok:
        bracket = "[" if closed_low else "("
        raise ValueError(f"{name} must be in {bracket}{low:g}, {high:g}] {unit}, got {value!r}")
    return x


@value_equality
@dataclass(frozen=True)
class Fill:
    r"""A level fill over an arch (see the module for the model and its limits).

    Parameters
    ----------
    cover : float
        Depth of fill above the top of the extrados (the crown) [m], >= 0.
    density : float, default :data:`~archquake.constants.DEFAULT_FILL_DENSITY`
        Density of the fill :math:`\rho_f` [kg/m^3], > 0.
    inertia : {"none", "centroid", "extrados"}, default "centroid"
        Where its horizontal inertia force acts (:data:`FILL_INERTIA_MODELS`).
    friction_angle : float, optional
        Angle of friction :math:`\phi` of the fill [rad], in (0, pi/2), for a passive
        reaction; None (default) for none.
    mobilisation : float, optional
        Mobilised fraction :math:`m_p` of the passive pressure [-], in [0, 1]; required with
        ``friction_angle``.

    Raises
    ------
    ValueError
        For a parameter out of its range, or only one of ``friction_angle`` and
        ``mobilisation``.

    Examples
    --------
    >>> import math
    >>> Fill(0.5, 1600.0, "extrados", math.radians(30), 0.33).describe()
    'fill 0.5 m over the crown, 1600 kg/m^3, inertia extrados, passive phi = 30 deg, m_p = 0.33'
    """

    cover: float
    density: float = DEFAULT_FILL_DENSITY
    inertia: str = DEFAULT_FILL_INERTIA
    friction_angle: float | None = None
    mobilisation: float | None = None

    def __post_init__(self):
        cover = _check_number("cover", self.cover, 0.0, LENGTH_RANGE[1], "m")
        density = _check_number("fill density", self.density, 0.0, 1e5, "kg/m^3",
                                closed_low=False)
        if self.inertia not in FILL_INERTIA_MODELS:
            raise ValueError(f"fill inertia must be one of {FILL_INERTIA_MODELS}, got "
                             f"{self.inertia!r}")
        if (self.friction_angle is None) != (self.mobilisation is None):
            raise ValueError("a passive reaction needs both friction_angle [rad] and "
                             "mobilisation [-]; give both or neither")
        set_ = object.__setattr__
        if self.friction_angle is not None:
            phi = _check_number("friction_angle", self.friction_angle, 0.0, 0.5 * math.pi,
                                "rad", closed_low=False)
            if phi >= 0.5 * math.pi:
                raise ValueError(f"friction_angle must be below pi/2 rad, got {phi!r}")
            set_(self, "friction_angle", phi)
            set_(self, "mobilisation", _check_number("mobilisation", self.mobilisation, 0.0,
                                                     1.0, "[-]"))
        set_(self, "cover", cover)
        set_(self, "density", density)

    @property
    def has_passive(self) -> bool:
        """Whether the fill offers a passive reaction."""
        return self.friction_angle is not None and self.mobilisation > 0

    @property
    def passive_coefficient(self) -> float:
        r"""Rankine's :math:`K_p = \tan^2(\pi/4 + \phi/2)` [-] (0 without a passive
        reaction)."""
        if self.friction_angle is None:
            return 0.0
        return math.tan(0.25 * math.pi + 0.5 * self.friction_angle) ** 2

    def describe(self) -> str:
        """One line: cover, density, inertia model and passive reaction."""
        text = (f"fill {self.cover:g} m over the crown, {self.density:g} kg/m^3, inertia "
                f"{self.inertia}")
        if self.friction_angle is not None:
            text += (f", passive phi = {math.degrees(self.friction_angle):.4g} deg, m_p = "
                     f"{self.mobilisation:g}")
        return text

    def to_dict(self) -> dict:
        """``{"cover", "density", "inertia", "friction_angle", "mobilisation"}`` [m, kg/m^3,
        rad], as read by :meth:`from_dict` (the last two only with a passive reaction)."""
        out = {"cover": self.cover, "density": self.density, "inertia": self.inertia}
        if self.friction_angle is not None:
            out |= {"friction_angle": self.friction_angle, "mobilisation": self.mobilisation}
        return out

    @classmethod
    def from_dict(cls, data) -> Fill:
        """The fill of :meth:`to_dict` (every key but ``cover`` optional)."""
        if not isinstance(data, dict):
            raise ValueError(f"a fill must be a JSON object with 'cover', got "
                             f"{type(data).__name__}")
        keys = {"cover", "density", "inertia", "friction_angle", "mobilisation"}
        unknown = sorted(set(data) - keys)
        if unknown:
            raise ValueError(f"a fill has unknown key(s) {unknown}; allowed: {sorted(keys)}")
        if "cover" not in data:
            raise ValueError("a fill is missing the key 'cover' [m]")
        for key in ("cover", "density", "friction_angle", "mobilisation"):
            if key in data:
                check_json_numbers(key, data[key], 0)
        return cls(data["cover"], data.get("density", DEFAULT_FILL_DENSITY),
                   data.get("inertia", DEFAULT_FILL_INERTIA), data.get("friction_angle"),
                   data.get("mobilisation"))


@dataclass(frozen=True, eq=False)
class FillColumns:
    r"""The fill over every voussoir of an arch (:func:`fill_columns`), per unit depth.

    Attributes
    ----------
    level : float
        Height of the fill's surface :math:`y_{top}` [m].
    masses : ndarray, shape (n,)
        Mass :math:`m_{f,i}` of every column [kg/m].
    centroids : ndarray, shape (n, 2)
        Its centroid [m].
    inertias : ndarray, shape (n,)
        Its polar moment of inertia about its centroid [kg m].
    extrados_points : ndarray, shape (n, 2)
        The point of the voussoir's extrados below the column's centroid [m].
    extrados_range : ndarray, shape (n, 2)
        Lowest and highest point of every voussoir's extrados [m].
    passive : ndarray, shape (n,)
        Largest passive reaction :math:`\bar P_i` [N/m] (0 without one).
    passive_y : ndarray, shape (n,)
        :math:`y_{mid,i}` [m].
    passive_sign : ndarray, shape (n,)
        Direction of the reaction: +1 toward +x (left of midspan), -1 toward -x, 0 none.
    outlines : tuple of ndarray
        Closed outline of every column [m], for drawing.
    """

    level: float
    masses: np.ndarray
    centroids: np.ndarray
    inertias: np.ndarray
    extrados_points: np.ndarray
    extrados_range: np.ndarray
    passive: np.ndarray
    passive_y: np.ndarray
    passive_sign: np.ndarray
    outlines: tuple


def _piece_range(piece, axis: int = 1) -> tuple[float, float]:
    """Lowest and highest coordinate ``axis`` (0: x, 1: y) of a piece [m], exact for segments
    and arcs."""
    ends = (piece.start[axis], piece.end[axis])
    if isinstance(piece, Segment):
        return min(ends), max(ends)
    if isinstance(piece, Arc):
        t0, t1 = sorted((piece.start_angle, piece.end_angle))
        values = list(ends)
        extremes = (0.5 * math.pi, -0.5 * math.pi) if axis == 1 else (0.0, math.pi)
        for extreme in extremes:
            k = math.ceil((t0 - extreme) / (2 * math.pi))
            if extreme + 2 * math.pi * k <= t1:
                trig = math.sin(extreme) if axis == 1 else math.cos(extreme)
                values.append(piece.centre[axis] + piece.radius * trig)
        return min(values), max(values)
    from scipy.optimize import minimize_scalar  # a smooth curve only (the command line's
    # options import this module and stay free of scipy.optimize)

    u = np.linspace(piece.start_parameter, piece.end_parameter, 257)
    y = np.asarray(piece.path(u), dtype=float)[:, axis]
    out = []
    for sign, index in ((1.0, int(np.argmin(y))), (-1.0, int(np.argmax(y)))):
        lo, hi = u[max(index - 1, 0)], u[min(index + 1, u.size - 1)]
        if lo > hi:
            lo, hi = hi, lo
        best = minimize_scalar(
            lambda t, s=sign: s * float(piece.path(np.array([t]))[0, axis]),
            bounds=(lo, hi), method="bounded", options={"xatol": 1e-13})
        out.append(min(sign * y[index], float(best.fun)) * sign)
    return out[0], out[1]


def _height_at(pieces, x: float) -> float:
    """Height of the extrados (pieces left to right) at abscissa ``x`` [m]."""
    for piece in pieces:
        (x0, _), (x1, _) = piece.start, piece.end
        if not min(x0, x1) - 1e-12 * (1 + abs(x)) <= x <= max(x0, x1) + 1e-12 * (1 + abs(x)):
            continue
        if isinstance(piece, Segment):
            if x1 == x0:
                return max(piece.start[1], piece.end[1])
            t = (x - x0) / (x1 - x0)
            return piece.start[1] + t * (piece.end[1] - piece.start[1])
        if isinstance(piece, Arc):
            c = np.clip((x - piece.centre[0]) / piece.radius, -1.0, 1.0)
            base = math.acos(c)
            t0, t1 = sorted((piece.start_angle, piece.end_angle))
            for angle in (base, -base):
                k = math.ceil((t0 - angle) / (2 * math.pi) - 1e-12)
                a = angle + 2 * math.pi * k
                if a <= t1 + 1e-12:
                    return piece.centre[1] + piece.radius * math.sin(a)
            continue
        from scipy.optimize import brentq

        u0, u1 = piece.start_parameter, piece.end_parameter

        def dx(u, piece=piece):
            return float(piece.path(np.array([u]))[0, 0]) - x

        u = u0 if dx(u0) == 0 else (u1 if dx(u1) == 0 else brentq(dx, u0, u1, xtol=1e-14))
        return float(piece.path(np.array([u]))[0, 1])
    raise ValueError(f"x = {x:g} m is not over this extrados")  # pragma: no cover


def fill_columns(arch: BlockArch, fill: Fill) -> FillColumns:
    """The fill over every voussoir of ``arch`` (see the module's model).

    Parameters
    ----------
    arch : CircularArch, ShapedArch or SurveyedArch
        The arch (its voussoirs' extrados, ``arch.extrados(i)``).
    fill : Fill
        The fill.

    Returns
    -------
    FillColumns

    Raises
    ------
    ValueError
        If the arch gives no extrados, or the extrados of a voussoir does not run left to right
        (an arch over more than a semicircle).
    """
    if not hasattr(arch, "extrados"):
        raise ValueError(f"fill needs an arch whose voussoirs have an extrados (a CircularArch, "
                         f"ShapedArch or SurveyedArch), got {type(arch).__name__}")
    n = arch.n_voussoirs
    faces = [arch.extrados(i) for i in range(n)]
    ranges = np.array([[min(r[0] for r in rs), max(r[1] for r in rs)]
                       for rs in ([_piece_range(p) for p in face] for face in faces)])
    level = float(ranges[:, 1].max()) + fill.cover
    scale = float(np.ptp(arch.joints.reshape(-1, 2), axis=0).max())
    masses, centroids, inertias, below, outlines = [], [], [], [], []
    for i, face in enumerate(faces):
        a, b = np.array(face[0].start), np.array(face[-1].end)
        xs = [_piece_range(p, 0) for p in face]
        if not (b[0] > a[0] + 1e-12 * scale and min(x[0] for x in xs) >= a[0] - 1e-12 * scale
                and max(x[1] for x in xs) <= b[0] + 1e-12 * scale):
            raise ValueError(f"fill needs an extrados that runs left to right: voussoir {i}'s "
                             "turns back (an arch over more than a semicircle cannot carry this "
                             "fill model)")
        top_right, top_left = (float(b[0]), level), (float(a[0]), level)
        pieces = [*face, Segment(tuple(b), top_right), Segment(top_right, top_left),
                  Segment(top_left, tuple(a))]
        area, qx, qy, j = region_moments(pieces, a)
        sign = 1.0 if area > 0 else -1.0
        area, qx, qy, j = sign * area, sign * qx, sign * qy, sign * j
        points = np.vstack([p.points(2 if isinstance(p, Segment) else 24)[:-1] for p in pieces])
        outlines.append(frozen_array(np.vstack((points, points[:1]))))
        if not area > 1e-12 * scale * scale:  # no fill over it (cover 0 at a flat top)
            masses.append(0.0)
            centroids.append(0.5 * (a + b))
            inertias.append(0.0)
        else:
            offset = np.array([qx, qy]) / area
            masses.append(fill.density * area)
            centroids.append(a + offset)
            inertias.append(fill.density * (j - area * (offset @ offset)))
        below.append((centroids[-1][0], _height_at(face, float(centroids[-1][0]))))
    centroids = np.array(centroids)
    midspan = 0.5 * (arch.joints[0, 1, 0] + arch.joints[-1, 1, 0])
    left_end = np.array([f[0].start[0] for f in faces])
    right_end = np.array([f[-1].end[0] for f in faces])
    tol = 1e-9 * scale
    sign = np.where(right_end <= midspan + tol, 1.0, np.where(left_end >= midspan - tol, -1.0,
                                                              0.0))
    mid = ranges.mean(axis=1)
    bound = (fill.mobilisation or 0.0) * fill.passive_coefficient * fill.density * GRAVITY * (
        level - mid) * np.ptp(ranges, axis=1)
    bound = np.where(sign != 0.0, bound, 0.0)
    return FillColumns(level, frozen_array(masses), frozen_array(centroids),
                       frozen_array(inertias), frozen_array(below), frozen_array(ranges),
                       frozen_array(bound), frozen_array(mid), frozen_array(sign),
                       tuple(outlines))


def carry_fill(masses, centroids, inertias, fill_masses, fill_centroids, fill_inertias):
    r"""Blocks and the fill columns they carry as one rigid body each (the ``"centroid"``
    model: the column moves with its block).

    .. math::

        m = m_b + m_f, \qquad \mathbf g = \frac{m_b \mathbf c_b + m_f \mathbf c_f}{m},
        \qquad J = J_b + m_b |\mathbf c_b - \mathbf g|^2 + J_f + m_f |\mathbf c_f - \mathbf g|^2

    (parallel axes).

    Parameters
    ----------
    masses, centroids, inertias : arrays, shapes (n,), (n, 2), (n,)
        Every block's mass [kg/m], centroid [m] and polar moment about it [kg m].
    fill_masses, fill_centroids, fill_inertias : arrays, same shapes
        The same of the column each carries (:class:`FillColumns`).

    Returns
    -------
    masses, centroids, inertias : arrays
        Of block and column together [kg/m, m, kg m].
    """
    m, c, inertia = masses, centroids, inertias
    mf, cf, jf = fill_masses, fill_centroids, fill_inertias
    total = m + mf
    g = (m[:, None] * c + mf[:, None] * cf) / total[:, None]
    inertia = (inertia + m * np.sum((c - g) ** 2, axis=1) + jf
               + mf * np.sum((cf - g) ** 2, axis=1))
    return total, g, inertia


def fill_horizontal_loads(masses, centroids, fill_masses, fill_centroids, extrados_y,
                          inertia: str):
    r"""Horizontal load per unit multiplier of blocks carrying fill columns, and the height of
    its line, as the fill's inertia model says (see the module).

    Parameters
    ----------
    masses, centroids : arrays, shapes (n,), (n, 2)
        The blocks' own mass [kg/m] and centroid [m].
    fill_masses, fill_centroids : arrays, shapes (n,), (n, 2)
        The columns' [kg/m, m].
    extrados_y : array, shape (n,)
        Height of the block's extrados below the column's centroid [m].
    inertia : {"none", "centroid", "extrados"}
        The fill's inertia model.

    Returns
    -------
    horizontal : array, shape (n,)
        :math:`H_i` [N/m]: :math:`m_b g` (none), :math:`(m_b + m_f) g` (centroid, extrados).
    horizontal_y : array, shape (n,)
        :math:`b_i` [m]: :math:`y_{c,b}` (none), the centroid of block and column (centroid),
        :math:`(m_b y_{c,b} + m_f y_e)/(m_b + m_f)` (extrados).
    """
    m, c, mf = masses, centroids, fill_masses
    if inertia == "none":
        return m * GRAVITY, c[:, 1].copy()
    if inertia == "extrados":
        return (m + mf) * GRAVITY, (m * c[:, 1] + mf * extrados_y) / (m + mf)
    if inertia == "centroid":
        total, g, _ = carry_fill(m, c, np.zeros_like(m), mf, fill_centroids, np.zeros_like(m))
        return total * GRAVITY, g[:, 1]
    raise ValueError(f"fill inertia must be one of {FILL_INERTIA_MODELS}, got {inertia!r}")


def check_dynamic_fill(structure) -> None:
    """Refuse a structure whose fill is not carried as mass (inertia other than
    :data:`DYNAMIC_FILL_INERTIA`) in a dynamic model.

    A fill's passive reaction is refused too: it is a bound on a horizontal force that the
    limit analysis mobilises at collapse, which neither dynamic model carries (the rigid blocks
    would start to move below the limit analysis' k, the four-link model would take the
    reaction's hinges without its force).

    Raises
    ------
    ValueError
        Naming the fill's inertia model, or its passive reaction.
    """
    fill = getattr(structure, "fill", None)
    if fill is not None and fill.has_passive:
        raise ValueError(
            "fill_passive: the fill's passive reaction is a limit-analysis model that "
            "neither dynamic model carries, so their activation would not equal the limit "
            "analysis' k; analyse the structure without it in the dynamic models (the limit "
            "analysis and the code check of the mechanism take it)")
    if fill is not None and fill.inertia != DYNAMIC_FILL_INERTIA:
        raise ValueError(
            f"fill inertia {fill.inertia!r} is a limit-analysis model: the dynamic models carry "
            f"the fill as mass moving with its voussoir (fill inertia "
            f"{DYNAMIC_FILL_INERTIA!r}), so that their activation equals the limit analysis' k")


__all__ = ["DEFAULT_FILL_INERTIA", "DYNAMIC_FILL_INERTIA", "FILL_INERTIA_MODELS", "Fill",
           "FillColumns", "carry_fill", "check_dynamic_fill", "fill_columns",
           "fill_horizontal_loads"]
