r"""Limit analysis of an arch under self-weight and horizontal forces [paper, Sect. 3].

Heyman's hypotheses [2]_: the masonry has no tensile strength, an infinite compressive strength,
and the voussoirs do not slide. Every voussoir :math:`i` carries its weight :math:`m_i g`
(downward) and a horizontal force :math:`k\, m_i g` at its centroid pointing left -> right (+x);
the horizontal load multiplier :math:`k` at collapse is the activation threshold of the motion,
:math:`|\ddot x_g| / g \ge k` (eq. (2) of [1]_). This is mechanism Mech-l; Mech-r is the same
analysis of the arch mirrored about the vertical axis, and its hinges are reported in the mirrored
frame (as Table 1 of [1]_).

The same analysis holds for any chain of blocks between two supports
(:class:`~archquake.geometry.BlockArch`): an arch on piers or buttresses
(:class:`~archquake.geometry.Structure`), whose hinges may form at the piers' bed joints and
bases, and an arch carrying fill, whose blocks carry loads other than their own weight
(:class:`~archquake.geometry.BlockLoads`): a weight :math:`W_i` along the vertical
:math:`x = a_i`, a horizontal load :math:`k H_i` along the horizontal :math:`y = b_i` and a
passive reaction :math:`s_i P_i` along :math:`y = y_i`, bounded,
:math:`0 \le P_i \le \bar P_i` (:mod:`archquake.geometry.fill`). For bare masonry
:math:`W_i = H_i = m_i g`, :math:`(a_i, b_i)` the centroid and no :math:`P_i`: the paper's case.

Two independent methods give the same :math:`k` (uniqueness theorem of limit analysis).

**Static (lower bound): a linear program.** The unknowns are the force
:math:`\mathbf F_j = (F_{x,j}, F_{y,j})` that the part of the arch left of joint :math:`j` exerts
on the part right of it, its moment :math:`M_j` about a reference point, at every joint
:math:`j = 0 \dots n`, the passive reactions :math:`P_i` and :math:`k`. With
:math:`\mathbf p_{\mathrm{in},j}` the intrados end of joint :math:`j`, :math:`\mathbf e_j` the
unit vector along it toward its extrados end, :math:`h_j` its depth and :math:`\mathbf n_j` its
normal, the normal force is :math:`N_j = \mathbf n_j \cdot \mathbf F_j` and the pressure point
:math:`\mathbf p_{\mathrm{in},j} + u_j \mathbf e_j` with
:math:`u_j N_j = \mathbf p_{\mathrm{in},j} \times \mathbf F_j - M_j`:

.. math::

    \max\ k \quad \text{subject to} \quad
    \begin{aligned}
    & F_{x,i+1} = F_{x,i} + k\, H_i + s_i P_i, \quad F_{y,i+1} = F_{y,i} - W_i, \\
    & M_{i+1} = M_i - W_i\, a_i - k\, H_i\, b_i - s_i P_i\, y_i,
      \quad 0 \le P_i \le \bar P_i, \qquad i = 0 \dots n-1, \\
    & 0 \le u_j N_j \le h_j N_j, \qquad j = 0 \dots n:
    \end{aligned}

equilibrium of every block, and at every joint a compressive normal force whose pressure point
lies in the contact. For the paper's circular arch (radial joints of progressive angle
:math:`\beta_j`, contact :math:`[r_{\mathrm{in},j}, r_{\mathrm{out},j}]`, moments about the
centre O) the last line reads :math:`r_{\mathrm{in},j} N_j \le -M_j \le r_{\mathrm{out},j} N_j`.
It is solved by HiGHS (:func:`scipy.optimize.linprog`) in units of the total weight and the
arch's length scale. The hinges are the joints where the pressure point is on a face (to
:data:`HINGE_TOLERANCE` of the joint's depth).

**Kinematic (upper bound): the least mechanism.** Every four-hinge mechanism with hinges
:math:`A < B < C < D` at joints :math:`a < b < c < d` (for the paper's arches the admissible ones
have alternating faces) has, by virtual work on a rigid-block displacement of velocity
:math:`(\delta x, \delta y)` at each load's line of action, the multiplier

.. math::

    k_{\mathrm{mech}} = \frac{-\sum_i W_i\, \delta y_i(a_i)
    + \sum_i \bar P_i \max\left(0, -s_i\, \delta x_i(y_i)\right)}{\sum_i H_i\, \delta x_i(b_i)}

(for bare masonry :math:`-\sum_i m_i \delta y_i / \sum_i m_i \delta x_i` at the centroids: a
passive reaction resists a block moving into the fill with its largest value and does no work
on one moving away), and the collapse multiplier is the least over the kinematically admissible
mechanisms (every hinge opening the right way). For completeness the enumeration also holds the
two-block mechanisms in which one joint opens over its whole depth; they govern only thick
arches under loads k of order 1 and more, and with them the two methods agree for every arch
(checked on random arches), with fill and passive reactions as without (LP duality).

**Standing.** A structure stands when a thrust line fits at k = 0 (:func:`self_weight_margin`
>= 0). When it does not, :class:`CannotStandError` says why (:func:`standing`): the arch (it does
not stand even on fixed springings) or its piers (it does, but not on them); an asymmetric
structure that stands only under a push one way is refused too. :func:`min_pier_width` finds the
narrowest piers on which an arch stands, :func:`min_thickness` the thinnest arch, and
:func:`geometric_safety_factor` divides the structure's own by them (Heyman's geometric factor of
safety).

Notes
-----
The joint moment :math:`M` of a force :math:`\mathbf F` whose line of action crosses the radial
joint line at radius :math:`r` is :math:`M = r\, (\mathbf e_r \times \mathbf F) = -r N`, with
:math:`\mathbf e_r = (-\cos\beta, \sin\beta)` the outward radial unit vector and
:math:`\mathbf e_t = (\sin\beta, \cos\beta)` the unit vector along the arch (left -> right).
The forces are returned in newtons per unit depth [N/m] (the loads are per unit depth).

References
----------
.. [1] The paper, Sect. 3, eq. (2), Table 1 and Figs. 2-4.
.. [2] Heyman, J. (1966). The stone skeleton. International Journal of Solids and Structures 2,
   249-279.
"""

from __future__ import annotations

import functools
import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass, replace

import numba
import numpy as np
from scipy.optimize import brentq, linprog

from .defaults import DEFAULT_LIMIT_METHOD, LIMIT_METHODS
from .errors import CannotStandError, NeverCollapsesError
from .geometry import (
    FACES,
    BlockArch,
    CircularArch,
    Fill,
    Hinge,
    Pier,
    ShapedArch,
    Structure,
    centreline,
    circular_arch,
    irregular_sample,
    shaped_arch,
)
from .geometry.blocks import check_voussoir_count

DIRECTIONS = ("l", "r")
"""Directions of the horizontal forces: ``"l"`` = Mech-l (forces toward +x on the arch as
given), ``"r"`` = Mech-r (the same forces on the mirrored arch)."""

HINGE_TOLERANCE = 1e-7
"""A joint is a hinge when its pressure point is within this fraction of the joint's contact
depth (its length) from one of its ends."""

MAX_ENUMERATED_VOUSSOIRS = 60
"""Largest number of voussoirs for the kinematic method, which enumerates all
``2 C(n+1, 4)`` four-hinge mechanisms (about a million for n = 60)."""

AGREEMENT_TOLERANCE = 1e-9
"""Largest difference between the static and the kinematic load multipliers of one arch."""

LP_TOLERANCE = 1e-10
"""Primal and dual feasibility tolerance of the linear program (HiGHS), in units of the total
weight and the arch's length scale. HiGHS's default, 1e-7, lets the line of thrust of an arch of
thousands of voussoirs stray a few 1e-7 of a joint's depth out of it, on a vertex whose
multiplier is off by 1e-6; at 1e-10 the optimum agrees with the kinematic method to 1e-9 and
costs no more time."""


# ---------------------------------------------------------------------------------- results
@dataclass(frozen=True, eq=False)
class ThrustLine:
    """The line of thrust: pressure point and joint force at every joint ``j = 0 .. n``.

    Attributes
    ----------
    offsets : array of float, shape (n+1,)
        Distance of the pressure point on every joint from the joint's intrados end [m], in
        ``[0, length of the joint]``; nan at a joint that transmits no normal force (a
        separating joint, whose force, if any, lies along the joint).
    radii : array of float, shape (n+1,), or None
        For a circular :class:`~archquake.geometry.CircularArch` (radial joints): the radius of
        every pressure point [m] (nan where ``offsets`` is); None for other arches.
    points : array of float, shape (n+1, 2)
        Pressure points (x, y) [m].
    forces : array of float, shape (n+1, 2)
        Force (F_x, F_y) that the part of the arch left of the joint exerts on the part right of
        it [N/m] (for joint 0: the left support on voussoir 0; for joint n: voussoir n-1 on the
        right support).
    loads : array of float, shape (n, 2), or None
        Resultant of the loads applied to every block at collapse [N/m]: its weight, its
        horizontal load and its passive reaction (:class:`~archquake.geometry.BlockLoads`).
    load_points : array of float, shape (n, 2), or None
        A point of the line of action of every block's resultant load [m].
    """

    offsets: np.ndarray
    radii: np.ndarray | None
    points: np.ndarray
    forces: np.ndarray
    loads: np.ndarray | None = None
    load_points: np.ndarray | None = None

    def funicular(self, arch: BlockArch, load_multiplier: float) -> np.ndarray:
        """Vertices of the funicular polygon (line of action of the resultant) [m], (2n+1, 2).

        Inside voussoir ``i`` the resultant acts along ``F_i`` from the pressure point ``p_i``
        until it meets the line of action of the voussoir's load (:attr:`loads` through
        :attr:`load_points`; without them ``m_i g (k, -1)`` through its centroid), and along
        ``F_{i+1}`` from there to ``p_{i+1}``. The vertices are ``p_0, q_0, p_1, q_1, ...,
        p_n``.
        """
        p, f = self.points[:-1], self.forces[:-1]
        if self.loads is None:
            c = arch.centroids
            load = np.broadcast_to(np.array([load_multiplier, -1.0]), f.shape)
        else:
            c, load = self.load_points, self.loads
        # p + s f = c + u load  ->  s (f x load) = (c - p) x load
        denom = f[:, 0] * load[:, 1] - f[:, 1] * load[:, 0]
        d = c - p
        s = (d[:, 0] * load[:, 1] - d[:, 1] * load[:, 0]) / np.where(denom == 0.0, np.nan, denom)
        q = p + s[:, None] * f
        q = np.where(np.isfinite(q), q, 0.5 * (p + self.points[1:]))
        out = np.empty((2 * arch.n_voussoirs + 1, 2))
        out[0::2] = self.points
        out[1::2] = q
        return out


@dataclass(frozen=True, eq=False)
class LimitAnalysis:
    """Result of the limit analysis of one arch in one direction.

    Attributes
    ----------
    load_multiplier : float
        Horizontal load multiplier k at collapse [-] (k_l for ``"l"``, k_r for ``"r"``).
    hinges : tuple of Hinge
        The hinges, left to right, in the frame of ``arch``: the four hinges A, B, C, D of the
        collapse mechanism (the paper's case), or two hinges when ``separation`` is set.
    thrust_line : ThrustLine
        The line of thrust at collapse.
    direction : str
        ``"l"`` (Mech-l) or ``"r"`` (Mech-r).
    arch : BlockArch
        The arch analysed: the given one for ``"l"``, its mirror image for ``"r"``.
    method : str
        ``"static"`` or ``"kinematic"``.
    separation : int or None
        ``None`` for a four-hinge mechanism. Otherwise the joint that opens over its whole depth
        (no normal force through it; under the no-sliding hypothesis it may still carry a shear
        force along the joint) in a two-block mechanism with two hinges; this happens only for
        thick arches under large horizontal loads (k of order 1 or more), never for the paper's
        arches, and the four-link model of the paper does not apply to it.
    """

    load_multiplier: float
    hinges: tuple[Hinge, ...]
    thrust_line: ThrustLine
    direction: str
    arch: BlockArch
    method: str = DEFAULT_LIMIT_METHOD
    separation: int | None = None

    @property
    def is_four_hinge(self) -> bool:
        """True for a four-hinge (three-block) collapse mechanism."""
        return self.separation is None and len(self.hinges) == 4

    @property
    def hinge_angles(self) -> np.ndarray:
        """Progressive angles beta of the hinges A, B, C, D [rad] (paper Table 1)."""
        return np.array([h.beta(self.arch) for h in self.hinges])

    @property
    def hinge_points(self) -> np.ndarray:
        """Positions (x, y) of the hinges A, B, C, D [m], shape (4, 2)."""
        return np.array([h.point(self.arch) for h in self.hinges])

    def funicular(self) -> np.ndarray:
        """Funicular polygon of the collapse state [m], see :meth:`ThrustLine.funicular`."""
        return self.thrust_line.funicular(self.arch, self.load_multiplier)


@dataclass(frozen=True, eq=False)
class LimitSample:
    """Load multipliers of a sample of irregular arches [paper, Sect. 5.3.3, Figs. 17-20].

    Attributes
    ----------
    load_multiplier_l, load_multiplier_r : array of float, shape (s,)
        k~_l and k~_r of every arch [-].
    epsilon : float
        epsilon of the irregular draw.
    seed : int or None
        Root seed of the sample (arch ``i`` uses child ``i`` of ``SeedSequence(seed)``).
    method : str
        ``"static"`` or ``"kinematic"``.
    """

    load_multiplier_l: np.ndarray
    load_multiplier_r: np.ndarray
    epsilon: float
    seed: int | None
    method: str = DEFAULT_LIMIT_METHOD

    @property
    def load_multiplier(self) -> np.ndarray:
        """k~ = min(k~_l, k~_r) of every arch [-]."""
        return np.minimum(self.load_multiplier_l, self.load_multiplier_r)


# ---------------------------------------------------------------------------------- checks
def _check_direction(direction: str) -> str:
    if direction not in DIRECTIONS:
        raise ValueError(f"direction must be one of {DIRECTIONS}, got {direction!r}")
    return direction


def _check_method(method: str) -> str:
    if method not in METHODS:
        raise ValueError(f"method must be one of {tuple(METHODS)}, got {method!r}")
    return method


def _oriented(arch: BlockArch, direction: str) -> BlockArch:
    return arch if _check_direction(direction) == "l" else arch.mirrored()


# ---------------------------------------------------------------------------------- data
@dataclass(frozen=True)
class _Scaled:
    """Dimensionless data of an arch: forces / total weight, lengths / the arch's length scale,
    positions relative to its reference point (the loads: :class:`~archquake.geometry.
    BlockLoads`)."""

    vertical: np.ndarray  # W_i / W (n,)
    vertical_x: np.ndarray  # a_i (n,)
    horizontal: np.ndarray  # H_i / W (n,)
    horizontal_y: np.ndarray  # b_i (n,)
    passive: np.ndarray  # largest passive reaction / W (n,)
    passive_y: np.ndarray  # its height (n,)
    passive_sign: np.ndarray  # its direction, -1, 0, +1 (n,)
    start: np.ndarray  # intrados end of every joint (n+1, 2)
    direction: np.ndarray  # unit vector intrados -> extrados end (n+1, 2)
    normal: np.ndarray  # unit normal from voussoir j-1 into j (n+1, 2)
    depth: np.ndarray  # length of every joint's contact (n+1,)
    length: float  # L [m]
    reference: np.ndarray  # [m]
    weight: float  # W = total weight [N/m]

    @property
    def passive_blocks(self) -> np.ndarray:
        """Blocks with a passive reaction (an unknown of the static method each)."""
        return np.flatnonzero((self.passive > 0) & (self.passive_sign != 0))


def _scaled(arch: BlockArch) -> _Scaled:
    length, ref = arch.length_scale, arch.reference_point
    loads = arch.loads
    weight = loads.total_weight
    return _Scaled(
        loads.vertical / weight, (loads.vertical_x - ref[0]) / length,
        loads.horizontal / weight, (loads.horizontal_y - ref[1]) / length,
        loads.passive / weight, (loads.passive_y - ref[1]) / length, loads.passive_sign,
        (arch.joints[:, 0] - ref) / length, arch.joint_directions, arch.joint_normals,
        arch.joint_lengths / length, length, ref, weight,
    )


def _cumulative(values) -> np.ndarray:
    return np.concatenate(([0.0], np.cumsum(values)))


def _joint_states(s: _Scaled, x0: np.ndarray, k: float, passive: np.ndarray | None = None):
    """Joint forces and moments from the force (F_x, F_y) and moment M at joint 0 (scaled).

    Equilibrium of block i under its weight W_i along x = a_i, its horizontal load k H_i along
    y = b_i and its passive reaction s_i P_i along y = y_i: F_{i+1} = F_i + (k H_i + s_i P_i,
    -W_i), M_{i+1} = M_i - W_i a_i - k H_i b_i - s_i P_i y_i.
    """
    push = np.zeros_like(s.vertical) if passive is None else s.passive_sign * passive
    fx = x0[0] + _cumulative(k * s.horizontal + push)
    fy = x0[1] - _cumulative(s.vertical)
    m = x0[2] - _cumulative(s.vertical * s.vertical_x + k * s.horizontal * s.horizontal_y
                            + push * s.passive_y)
    return fx, fy, m


def _thrust_line(arch: BlockArch, s: _Scaled, fx, fy, m, k: float,
                 passive: np.ndarray | None = None) -> ThrustLine:
    """The pressure point on joint j: where the line of action of F_j crosses the joint,
    ``p_in + u e`` with ``u N = p_in x F - M`` (``N = n . F``, ``M`` the moment of F about the
    reference point); and the resultant load on every block."""
    normal = s.normal[:, 0] * fx + s.normal[:, 1] * fy
    moment_in = s.start[:, 0] * fy - s.start[:, 1] * fx
    with np.errstate(divide="ignore", invalid="ignore"):
        u = np.where(np.abs(normal) > 1e-10, (moment_in - m) / normal, np.nan)
    points = s.reference + (s.start + u[:, None] * s.direction) * s.length
    offsets = u * s.length
    radii = arch.joint_extents()[0] + offsets if hasattr(arch, "joint_extents") else None
    forces = np.column_stack((fx, fy)) * s.weight
    push = np.zeros_like(s.vertical) if passive is None else s.passive_sign * passive
    horizontal = k * s.horizontal + push
    with np.errstate(divide="ignore", invalid="ignore"):
        height = np.where(horizontal != 0.0, (k * s.horizontal * s.horizontal_y
                                              + push * s.passive_y) / horizontal,
                          s.horizontal_y)
    loads = np.column_stack((horizontal, -s.vertical)) * s.weight
    load_points = s.reference + np.column_stack((s.vertical_x, height)) * s.length
    arrays = (offsets, points, forces, loads, load_points) + (() if radii is None else (radii,))
    for arr in arrays:
        arr.setflags(write=False)
    return ThrustLine(offsets, radii, points, forces, loads, load_points)


# ---------------------------------------------------------------------------------- static
def _lp_matrices(s: _Scaled, fixed_k: float | None = None):
    """Equality and inequality matrices of the static linear program, sparse (CSC).

    Unknowns ``x = [F_x(0..n), F_y(0..n), M(0..n), P(passive blocks), k]`` (scaled), with
    ``P`` the passive reactions of the blocks that have one (bounded by :func:`_solve_lp`);
    with ``fixed_k`` the last one is a margin ``delta`` instead, the uniform distance (in units
    of weight x joint depth) by which the pressure point stays inside every joint's contact.
    Every equation involves two neighbouring joints, at most one passive reaction and the last
    unknown, so the matrices have at most four non-zeros per row: stored sparse, an arch of ten
    thousand voussoirs (30 004 unknowns) takes a few megabytes where the dense matrices took
    seven gigabytes.
    """
    from scipy.sparse import csc_array

    v, a, h, b = s.vertical, s.vertical_x, s.horizontal, s.horizontal_y
    n = v.size
    nj = n + 1
    pushed = s.passive_blocks
    nv = 3 * nj + pushed.size + 1
    rows = np.arange(n)
    ones = np.ones(n)
    eq = []  # (row indices, column indices, values) of the non-zeros
    b_eq = np.zeros(3 * n)
    # horizontal: F_x,i - F_x,i+1 + k H_i + s_i P_i = 0
    eq += [(rows, rows, ones), (rows, rows + 1, -ones)]
    # vertical: F_y,i - F_y,i+1 = W_i
    eq += [(n + rows, nj + rows, ones), (n + rows, nj + rows + 1, -ones)]
    b_eq[n : 2 * n] = v
    # moment about O: M_i - M_i+1 - k H_i b_i - s_i P_i y_i = W_i a_i
    eq += [(2 * n + rows, 2 * nj + rows, ones), (2 * n + rows, 2 * nj + rows + 1, -ones)]
    b_eq[2 * n :] = v * a
    if pushed.size:
        columns = 3 * nj + np.arange(pushed.size)
        sign = s.passive_sign[pushed]
        eq += [(pushed, columns, sign), (2 * n + pushed, columns, -sign * s.passive_y[pushed])]
    last = np.full(n, nv - 1)
    if fixed_k is None:
        eq += [(rows, last, h), (2 * n + rows, last, -h * b)]
    else:
        b_eq[:n] = -fixed_k * h
        b_eq[2 * n :] += fixed_k * h * b
    # the pressure point p_in + u e in the joint, 0 <= u N <= h N with u N = p_in x F - M and
    # N = n . F: -(p_in x F) + M <= 0 and p_in x F - M - h N <= 0
    j = np.arange(nj)
    unit = np.ones(nj)
    (px, py), (nx, ny), h = s.start.T, s.normal.T, s.depth
    ub = [(j, j, py), (j, nj + j, -px), (j, 2 * nj + j, unit),
          (nj + j, j, -py - h * nx), (nj + j, nj + j, px - h * ny),
          (nj + j, 2 * nj + j, -unit)]
    if fixed_k is not None:
        ub += [(j, np.full(nj, nv - 1), h), (nj + j, np.full(nj, nv - 1), h)]

    def assemble(parts, shape):
        r, col, v = (np.concatenate([p[i] for p in parts]) for i in range(3))
        return csc_array((v, (r, col)), shape=shape)

    return assemble(eq, (3 * n, nv)), b_eq, assemble(ub, (2 * nj, nv))


def _solve_lp(s: _Scaled, fixed_k: float | None = None):
    """The linear program by HiGHS, at :data:`LP_TOLERANCE`; at HiGHS's default tolerances
    again if it reports numerical difficulties (a joint depth of 1e-6 of the arch's size)."""
    a_eq, b_eq, a_ub = _lp_matrices(s, fixed_k)
    cost = np.zeros(a_eq.shape[1])
    cost[-1] = -1.0
    bounds = np.full((a_eq.shape[1], 2), np.nan)  # free, but for the passive reactions
    pushed = s.passive_blocks
    nj = s.depth.size
    bounds[3 * nj:3 * nj + pushed.size] = np.column_stack((np.zeros(pushed.size),
                                                           s.passive[pushed]))
    bounds = [(None if np.isnan(lo) else lo, None if np.isnan(hi) else hi) for lo, hi in bounds]
    problem = {"A_ub": a_ub, "b_ub": np.zeros(a_ub.shape[0]), "A_eq": a_eq, "b_eq": b_eq,
               "bounds": bounds if pushed.size else (None, None), "method": "highs"}
    res = linprog(cost, **problem, options={"primal_feasibility_tolerance": LP_TOLERANCE,
                                            "dual_feasibility_tolerance": LP_TOLERANCE})
    if res.status == 4:
        res = linprog(cost, **problem)
    return res


_UNBOUNDED = (
    "the arch does not collapse under any horizontal load multiplier (a thrust line fits inside "
    "it for every k: the arch is too thick or too shallow for a mechanism)"
)


def _is_strut(arch: BlockArch) -> bool:
    """Whether a horizontal line crosses every joint of an arch on fixed springings strictly
    between its ends (a nearly flat arch thicker than its rise): a thrust along it, grown
    without bound, carries any finite load with its line inside every joint, so the arch never
    collapses. A structure's piers may overturn: never a strut."""
    if isinstance(arch, Structure):
        return False
    y = np.asarray(arch.joints)[:, :, 1]
    return bool(np.max(np.min(y, axis=1)) < np.min(np.max(y, axis=1))
                - 1e-9 * arch.length_scale)


def _lp_failure(res, arch: BlockArch) -> ValueError:
    """The error of a linear program that HiGHS ends without an answer (neither optimal,
    infeasible nor unbounded: numerical difficulties or a limit reached) for an arch that is
    not a strut (:func:`_is_strut`): its geometry is too degenerate to analyse."""
    return ValueError(f"the limit-analysis linear program of this arch cannot be solved "
                      f"({str(res.message).strip()}): its geometry is degenerate (nearly flat, "
                      "or very large beside its thickness?)")


def _original(arch: BlockArch, direction: str) -> BlockArch:
    """The arch in its own frame, from the arch analysed in ``direction``."""
    return arch if direction == "l" else arch.mirrored()


def _check_stands(k: float, arch: BlockArch, direction: str) -> None:
    """Refuse a negative collapse multiplier: such an arch falls under its own weight (k = 0
    admits no thrust line inside it), so it has no activation threshold."""
    if k < 0.0:
        if not isinstance(arch, Structure):
            raise CannotStandError(
                f"the arch cannot stand under its own weight: its collapse load multiplier is "
                f"k = {k:.4g} < 0 (it would need a horizontal push to stand), so no ground "
                "acceleration threshold exists"
            )
        reason = standing(_original(arch, direction)).reason
        raise CannotStandError(f"{reason} (its collapse load multiplier is k = {k:.4g} < 0: it "
                               "would need a horizontal push to stand)")


def _cannot_stand(arch: BlockArch, direction: str) -> CannotStandError:
    """The error of an arch that admits no thrust line for any load multiplier, with its
    reason."""
    if not isinstance(arch, Structure):
        return CannotStandError(
            "the arch admits no thrust line inside its joints for any horizontal load multiplier "
            "(it cannot stand; the thickness is below the minimum)"
        )
    return CannotStandError(standing(_original(arch, direction)).reason)


def _static(arch: BlockArch, direction: str) -> LimitAnalysis:
    s = _scaled(arch)
    res = _solve_lp(s)
    if res.status != 0 and _is_strut(arch):  # unbounded, which HiGHS may fail to tell
        raise NeverCollapsesError(_UNBOUNDED)
    if res.status == 2:
        raise _cannot_stand(arch, direction)
    if res.status == 3:
        raise NeverCollapsesError(_UNBOUNDED)
    if res.status != 0:
        raise _lp_failure(res, arch)
    nj = arch.n_voussoirs + 1
    x = res.x
    k = float(x[-1])
    _check_stands(k, arch, direction)
    fx, fy, m = x[:nj], x[nj : 2 * nj], x[2 * nj : 3 * nj]
    passive = np.zeros(arch.n_voussoirs)
    passive[s.passive_blocks] = x[3 * nj : -1]
    line = _thrust_line(arch, s, fx, fy, m, k, passive)
    hinges, separation = _hinges_from_thrust_line(arch, line, res.ineqlin.marginals, k)
    return LimitAnalysis(k, hinges, line, direction, arch, "static", separation)


def _hinges_from_thrust_line(arch: BlockArch, line: ThrustLine, marginals, k: float):
    """The hinges of the collapse state from the LP solution: ``(hinges, separation)``.

    A joint face is active when the pressure point lies on it (within ``HINGE_TOLERANCE`` of the
    contact depth) or when its constraint carries a non-zero dual; a joint with no normal force
    is active on both faces. Exactly four active joints on alternating faces are the hinges.
    Otherwise (a degenerate optimum) every admissible mechanism whose active joints are all
    active in the LP solution has the LP multiplier (virtual work of the LP's equilibrium), so
    the mechanisms are enumerated among the active joints and the one whose multiplier is
    closest to the LP's is taken.
    """
    depth = arch.joint_lengths
    nj = depth.size
    duals = np.abs(np.asarray(marginals))
    dual_scale = max(float(duals.max(initial=0.0)), 1e-300)
    no_force = np.isnan(line.offsets)
    with np.errstate(invalid="ignore"):
        on_inner = no_force | (line.offsets <= HINGE_TOLERANCE * depth) | (
            duals[:nj] > 1e-9 * dual_scale)
        on_outer = no_force | ((depth - line.offsets) <= HINGE_TOLERANCE * depth) | (
            duals[nj:] > 1e-9 * dual_scale)
    joints = np.flatnonzero(on_inner | on_outer)
    if joints.size == 4 and not np.any(on_inner[joints] & on_outer[joints]):
        faces = tuple(FACES[0] if on_inner[j] else FACES[1] for j in joints)
        return tuple(Hinge(int(j), f) for j, f in zip(joints, faces, strict=True)), None
    on_face = np.column_stack((on_inner, on_outer, on_inner & on_outer, np.ones(nj, bool)))
    if joints.size >= 3:
        mech = _mechanisms(arch, candidate_joints=joints)
        match = np.all(on_face[mech.joints, mech.faces], axis=1) & np.isfinite(mech.k)
        if np.any(match):
            close = np.flatnonzero(match)
            return mech.hinges(int(close[np.argmin(np.abs(mech.k[close] - k))]))
    mech = _mechanisms(arch)
    return mech.hinges(int(np.nanargmin(np.abs(mech.k - k))))


# ---------------------------------------------------------------------------------- kinematic
FACE_PATTERNS = tuple(itertools.product(FACES, repeat=4))
"""Face patterns of the hinges A, B, C, D enumerated by the kinematic method: all sixteen. The
alternating ones (intrados, extrados, intrados, extrados and the reverse) are the only
admissible ones for arches like the paper's; others (e.g. a middle block with both hinges on
the intrados) govern only thick arches under large horizontal loads."""

_SEPARATION = 2
"""Face code of a joint that opens over its whole depth (its rotation pole lies on the joint's
line outside the contact)."""

_COMBINATIONS: dict[tuple[int, int], np.ndarray] = {}


def _joint_combinations(n_joints: int, size: int) -> np.ndarray:
    key = (n_joints, size)
    if key not in _COMBINATIONS:
        combos = np.array(list(itertools.combinations(range(n_joints), size)), dtype=int)
        combos = combos.reshape(-1, size)
        combos.setflags(write=False)
        _COMBINATIONS[key] = combos
    return _COMBINATIONS[key]


@dataclass(frozen=True)
class _Mechanisms:
    """Candidate mechanisms: joints and faces (0 intrados, 1 extrados, 2 separation; -1 unused)
    and the virtual-work multiplier (nan where not kinematically admissible)."""

    joints: np.ndarray  # (M, 4)
    faces: np.ndarray  # (M, 4)
    k: np.ndarray  # (M,)

    def hinges(self, i: int) -> tuple[tuple[Hinge, ...], int | None]:
        hinges = tuple(
            Hinge(int(j), FACES[int(f)])
            for j, f in zip(self.joints[i], self.faces[i], strict=True) if f in (0, 1)
        )
        sep = [int(j) for j, f in zip(self.joints[i], self.faces[i], strict=True)
               if f == _SEPARATION]
        return hinges, (sep[0] if sep else None)


class _Geometry:
    """Scaled joint and block data shared by the mechanism families, for a batch of B arches
    with the same number of voussoirs (leading axis of every array)."""

    def __init__(self, arches: Sequence[BlockArch]):
        scaled = [_scaled(a) for a in arches]
        self.start_x = np.array([g.start[:, 0] for g in scaled])  # (B, n+1)
        self.start_y = np.array([g.start[:, 1] for g in scaled])
        self.dir_x = np.array([g.direction[:, 0] for g in scaled])
        self.dir_y = np.array([g.direction[:, 1] for g in scaled])
        self.depth = np.array([g.depth for g in scaled])
        zero = np.zeros((len(arches), 1))

        def cumulative(values):
            return np.hstack((zero, np.cumsum(np.array(values), axis=1)))

        self.cv = cumulative([g.vertical for g in scaled])  # (B, n+1)
        self.cvx = cumulative([g.vertical * g.vertical_x for g in scaled])
        self.ch = cumulative([g.horizontal for g in scaled])
        self.chy = cumulative([g.horizontal * g.horizontal_y for g in scaled])
        self.passive = np.array([g.passive * (g.passive_sign != 0) for g in scaled])  # (B, n)
        self.passive_y = np.array([g.passive_y for g in scaled])
        self.passive_sign = np.array([g.passive_sign for g in scaled])
        self.has_passive = bool(np.any(self.passive > 0))


@numba.njit(cache=True, inline="always")
def _admissible_sign(rel, required, count):
    """The sense (+1 or -1) in which the mechanism is admissible, else 0.

    ``rel[:count]``: relative rotations (right minus left) at the active joints;
    ``required[:count]``: the sign each must have (-1: joint opens on the extrados side, i.e.
    hinge on the intrados; +1: the reverse; 0: impossible). The mechanism may run either way
    (overall sign).
    """
    forward = True
    backward = True
    scale = 0.0
    for i in range(count):
        if not math.isfinite(rel[i]):
            return 0.0
        forward = forward and rel[i] * required[i] > 0.0
        backward = backward and -rel[i] * required[i] > 0.0
        scale = max(scale, abs(rel[i]))
    for i in range(count):
        if not abs(rel[i]) > 1e-12 * scale:
            return 0.0
    return 1.0 if forward else (-1.0 if backward else 0.0)


@numba.njit(cache=True, inline="always")
def _sums(c, cw, b, j0, j1):
    """Load and its first moment over the blocks between joints j0 and j1 of arch b."""
    return c[b, j1] - c[b, j0], cw[b, j1] - cw[b, j0]


@numba.njit(cache=True, inline="always")
def _passive_work(passive, passive_y, passive_sign, b, j0, j1, vx0, rate, y0, sign):
    r"""Largest work rate the passive reactions of blocks j0 .. j1-1 of arch b can absorb in a
    motion whose horizontal velocity at height y is ``sign (vx0 - rate (y - y0))``:
    :math:`\sum_i \bar P_i \max(0, -s_i u_i)` (a reaction resists a block that moves into the
    fill, and does no work on one that moves away from it)."""
    total = 0.0
    for i in range(j0, j1):
        if passive[b, i] > 0.0:
            u = sign * (vx0 - rate * (passive_y[b, i] - y0))
            total += passive[b, i] * max(0.0, -passive_sign[b, i] * u)
    return total


@numba.njit(cache=True)
def _mechanism_multipliers(start_x, start_y, dir_x, dir_y, depth, cv, cvx, ch, chy, passive,
                           passive_y, passive_sign, has_passive, joints, faces, separating,
                           out):
    """``out[b, q]``: the multiplier of mechanism ``q`` of arch ``b`` (nan if not admissible).

    Arrays of the arches (scaled, one row per arch): intrados ends ``start_x, start_y``, unit
    directions to the extrados end ``dir_x, dir_y`` and lengths ``depth`` of the joints'
    contacts (B, n+1); cumulative vertical loads and their moments ``cv, cvx`` and horizontal
    loads and their moments ``ch, chy`` (B, n+1); largest passive reactions, their heights and
    directions (B, n), used when ``has_passive``. Mechanism ``q``: active ``joints[q]`` and
    ``faces[q]`` (0 intrados, 1 extrados), and ``separating[q]``: -1 for four face hinges, else
    the position (0-2) of the joint that opens over its whole depth among three active joints.

    Four face hinges A, B, C, D at joints a < b < c < d, three moving blocks: block AB
    (voussoirs a..b-1) rotates about A with rate 1, block CD about D with rate w3, block BC moves
    with the velocity of B plus a rotation w2. Closure (velocity of D zero): ``(B - A) + w2
    (C - B) + w3 (D - C) = 0``: the rotation of BC about the intersection of AB and DC, with
    ``w2 = 0`` (translation) when AB // DC.

    Two face hinges and a separating joint, two moving blocks: without sliding the relative
    motion at a joint is a rotation about a pole on its line; outside the contact the
    whole joint opens and transmits no force (nor work: the relative velocity is normal to the
    joint). Block 1 (a..b-1) turns about P_a with rate 1, block 2 (b..c-1) about P_c with rate
    w2, and the three poles are collinear (three-centre theorem), which places the pole of the
    separating joint at the intersection of its line with the line through the other two. A
    pole beyond the intrados end acts as an intrados hinge, beyond the extrados end as an
    extrados hinge, inside the contact it is not admissible.

    Work rates of the loads, run in the admissible sense: ``W_H`` of the horizontal loads per
    unit k (> 0), ``W_V`` of the weights, and the largest work ``D`` the passive reactions can
    absorb (:func:`_passive_work`); ``k = (D - W_V) / W_H``.
    """
    px = np.empty(4)
    py = np.empty(4)
    rel = np.empty(4)
    required = np.empty(4)
    for b in range(depth.shape[0]):
        for q in range(joints.shape[0]):
            s = separating[q]
            count = 4 if s < 0 else 3
            for i in range(count):
                j = joints[q, i]
                r = 0.0 if faces[q, i] == 0 else depth[b, j]
                px[i] = start_x[b, j] + r * dir_x[b, j]
                py[i] = start_y[b, j] + r * dir_y[b, j]
                required[i] = -1.0 if faces[q, i] == 0 else 1.0
            ja, jb, jc = joints[q, 0], joints[q, 1], joints[q, 2]
            if s < 0:
                jd = joints[q, 3]
                ux, uy = px[2] - px[1], py[2] - py[1]
                vx_, vy_ = px[3] - px[2], py[3] - py[2]
                rx, ry = px[0] - px[1], py[0] - py[1]
                det = ux * vy_ - uy * vx_
                if not abs(det) > 1e-14:
                    out[b, q] = np.nan
                    continue
                w2 = (rx * vy_ - ry * vx_) / det
                w3 = (ux * ry - uy * rx) / det
                v1, vx1 = _sums(cv, cvx, b, ja, jb)
                v2, vx2 = _sums(cv, cvx, b, jb, jc)
                v3, vx3 = _sums(cv, cvx, b, jc, jd)
                h1, hy1 = _sums(ch, chy, b, ja, jb)
                h2, hy2 = _sums(ch, chy, b, jb, jc)
                h3, hy3 = _sums(ch, chy, b, jc, jd)
                mx = (-(hy1 - h1 * py[0]) - h2 * (py[1] - py[0]) - w2 * (hy2 - h2 * py[1])
                      - w3 * (hy3 - h3 * py[3]))
                my = ((vx1 - v1 * px[0]) + v2 * (px[1] - px[0]) + w2 * (vx2 - v2 * px[1])
                      + w3 * (vx3 - v3 * px[3]))
                rel[0], rel[1], rel[2], rel[3] = 1.0, w2 - 1.0, w3 - w2, -w3
            else:
                o0 = 1 if s == 0 else 0
                o1 = 1 if s == 2 else 2
                sj = joints[q, s]
                ex, ey = dir_x[b, sj], dir_y[b, sj]
                sx, sy = start_x[b, sj], start_y[b, sj]
                dqx, dqy = px[o1] - px[o0], py[o1] - py[o0]
                denom = ex * dqy - ey * dqx
                rho = np.nan
                if abs(denom) > 1e-14:
                    rho = ((px[o0] - sx) * dqy - (py[o0] - sy) * dqx) / denom
                px[s], py[s] = sx + rho * ex, sy + rho * ey
                if rho <= 0.0:
                    required[s] = -1.0
                elif rho >= depth[b, sj]:
                    required[s] = 1.0
                else:
                    required[s] = 0.0
                bax, bay = px[1] - px[0], py[1] - py[0]
                bcx, bcy = px[1] - px[2], py[1] - py[2]
                norm = bcx * bcx + bcy * bcy
                w2 = (bax * bcx + bay * bcy) / norm if norm > 1e-28 else np.nan
                v1, vx1 = _sums(cv, cvx, b, ja, jb)
                v2, vx2 = _sums(cv, cvx, b, jb, jc)
                h1, hy1 = _sums(ch, chy, b, ja, jb)
                h2, hy2 = _sums(ch, chy, b, jb, jc)
                mx = -(hy1 - h1 * py[0]) - w2 * (hy2 - h2 * py[2])
                my = (vx1 - v1 * px[0]) + w2 * (vx2 - v2 * px[2])
                rel[0], rel[1], rel[2] = 1.0, w2 - 1.0, -w2
            sign = _admissible_sign(rel, required, count)
            if sign == 0.0 or not sign * mx > 1e-14:
                out[b, q] = np.nan
                continue
            absorbed = 0.0
            if has_passive:
                absorbed = _passive_work(passive, passive_y, passive_sign, b, ja, jb, 0.0, 1.0,
                                         py[0], sign)
                if s < 0:
                    absorbed += _passive_work(passive, passive_y, passive_sign, b, jb, jc,
                                              -(py[1] - py[0]), w2, py[1], sign)
                    absorbed += _passive_work(passive, passive_y, passive_sign, b, jc,
                                              joints[q, 3], 0.0, w3, py[3], sign)
                else:
                    absorbed += _passive_work(passive, passive_y, passive_sign, b, jb, jc, 0.0,
                                              w2, py[2], sign)
            out[b, q] = (sign * my + absorbed) / (sign * mx)


def _four_hinge_family(combos: np.ndarray):
    """Four face hinges at joints a < b < c < d, with every combination of faces: ``(joints,
    faces, separating)`` as :func:`_mechanism_multipliers` takes them."""
    patterns = np.array([[FACES.index(f) for f in p] for p in FACE_PATTERNS], dtype=np.int64)
    joints = np.repeat(combos, len(patterns), axis=0)
    faces = np.tile(patterns, (combos.shape[0], 1))
    return joints, faces, np.full(joints.shape[0], -1, dtype=np.int64)


def _separation_family(combos: np.ndarray):
    """Two face hinges (every combination of faces) and one joint that opens over its whole
    depth, among three joints a < b < c: ``(joints, faces, separating)``, column 4 unused
    (-1)."""
    n_t = combos.shape[0]
    role = np.repeat(np.arange(3), 4)  # which of a, b, c separates
    face_pairs = np.tile(np.array([[0, 0], [0, 1], [1, 0], [1, 1]]), (3, 1))
    faces3 = np.full((12, 3), _SEPARATION)
    for r in range(3):
        rows = role == r
        faces3[np.ix_(rows, [i for i in range(3) if i != r])] = face_pairs[rows]
    pad = np.full((12 * n_t, 1), -1)
    joints = np.hstack((np.repeat(combos, 12, axis=0), pad)).astype(np.int64)
    faces = np.hstack((np.tile(faces3, (n_t, 1)), pad)).astype(np.int64)
    return joints, faces, np.tile(role, n_t).astype(np.int64)


@functools.lru_cache(maxsize=8)
def _family_arrays(pool: tuple[int, ...]):
    """``(joints, faces, separating)`` of both mechanism families over the joints ``pool``
    (built once per pool: every arch with as many voussoirs shares them)."""
    pool = np.asarray(pool, dtype=np.int64)
    families = [_four_hinge_family(pool[_joint_combinations(pool.size, 4)]),
                _separation_family(pool[_joint_combinations(pool.size, 3)])]
    arrays = tuple(np.ascontiguousarray(np.concatenate([f[i] for f in families]))
                   for i in range(3))
    for a in arrays:
        a.setflags(write=False)
    return arrays


def _check_enumerable(n_voussoirs: int) -> None:
    """Refuse an enumeration of every mechanism of an arch with too many voussoirs."""
    if n_voussoirs > MAX_ENUMERATED_VOUSSOIRS:
        raise ValueError(
            f"method 'kinematic' enumerates every mechanism and needs voussoirs <= "
            f"{MAX_ENUMERATED_VOUSSOIRS}, got {n_voussoirs}; use method 'static'"
        )


def _mechanism_families(arches: Sequence[BlockArch],
                        candidate_joints: np.ndarray | None = None):
    """``(joints (M, 4), faces (M, 4), k (B, M))``: the virtual-work multiplier of every
    one-degree-of-freedom mechanism of each arch of a batch (same number of voussoirs), nan if
    not admissible (:func:`_mechanism_multipliers`).

    Two families: four face hinges (three blocks), and two face hinges plus a joint that opens
    over its whole depth (two blocks); together they are every one-degree-of-freedom mechanism
    of the chain of voussoirs. Admissible: the relative rotation at each hinge opens the joint on
    the opposite face, and the horizontal loads do positive work [kinematic theorem; zero
    dissipation at hinges]. ``candidate_joints`` restricts the active joints.
    """
    n = arches[0].n_voussoirs
    if any(a.n_voussoirs != n for a in arches):
        raise ValueError("a batch of arches must have the same number of voussoirs")
    if candidate_joints is None:
        _check_enumerable(n)
    pool = np.arange(n + 1) if candidate_joints is None else np.asarray(candidate_joints, int)
    joints, faces, separating = _family_arrays(tuple(pool.tolist()))
    geo = _Geometry(arches)
    k = np.empty((len(arches), joints.shape[0]))
    _mechanism_multipliers(geo.start_x, geo.start_y, geo.dir_x, geo.dir_y, geo.depth, geo.cv,
                           geo.cvx, geo.ch, geo.chy, geo.passive, geo.passive_y,
                           geo.passive_sign, geo.has_passive, joints, faces, separating, k)
    return joints, faces, k


def _mechanisms(arch: BlockArch, candidate_joints: np.ndarray | None = None) -> _Mechanisms:
    """Every one-degree-of-freedom mechanism of one arch (:func:`_mechanism_families`)."""
    joints, faces, k = _mechanism_families([arch], candidate_joints)
    return _Mechanisms(joints, faces, k[0])


KINEMATIC_BATCH = 64
"""Arches whose mechanisms are enumerated together by :func:`load_multipliers_of`."""


def _kinematic_multipliers(arches: Sequence[BlockArch]) -> np.ndarray:
    """Smallest admissible multiplier of each arch of a batch (inf if none), shape (B,)."""
    _, _, k = _mechanism_families(arches)
    finite = np.isfinite(k)
    with np.errstate(invalid="ignore"):
        return np.where(finite.any(axis=1), np.min(np.where(finite, k, np.inf), axis=1), np.inf)


def _cross2(a, b) -> float:
    return float(a[0] * b[1] - a[1] * b[0])


def _mechanism_motion(s: _Scaled, hinges: tuple[Hinge, ...], separation: int | None):
    """The moving blocks of a mechanism, as :func:`_mechanism_multipliers` sets them in motion:
    ``(j0, j1, vx0, rate, y0)`` for the blocks j0 .. j1-1 moving together, whose horizontal
    velocity at height y is ``vx0 - rate (y - y0)`` (scaled), and the sense (+1 or -1) in which
    the horizontal loads do positive work."""
    def point(joint: int, face: str) -> np.ndarray:
        r = 0.0 if face == FACES[0] else s.depth[joint]
        return s.start[joint] + r * s.direction[joint]

    if separation is None:
        a, b, c, d = (point(h.joint, h.face) for h in hinges)
        det = _cross2(c - b, d - c)
        w2, w3 = _cross2(a - b, d - c) / det, _cross2(c - b, a - b) / det
        ja, jb, jc, jd = (h.joint for h in hinges)
        blocks = [(ja, jb, 0.0, 1.0, a[1]), (jb, jc, -(b[1] - a[1]), w2, b[1]),
                  (jc, jd, 0.0, w3, d[1])]
    else:
        faces = {h.joint: h.face for h in hinges}
        joints = sorted([*faces, separation])
        position = joints.index(separation)
        poles = [None if j == separation else point(j, faces[j]) for j in joints]
        p0, p1 = (poles[i] for i in range(3) if i != position)
        e, start = s.direction[separation], s.start[separation]
        rho = _cross2(p0 - start, p1 - p0) / _cross2(e, p1 - p0)
        poles[position] = start + rho * e
        ba, bc = poles[1] - poles[0], poles[1] - poles[2]
        w2 = float(ba @ bc / (bc @ bc))
        blocks = [(joints[0], joints[1], 0.0, 1.0, poles[0][1]),
                  (joints[1], joints[2], 0.0, w2, poles[2][1])]
    work = sum(float(np.sum(s.horizontal[j0:j1] * (vx0 - rate * (s.horizontal_y[j0:j1] - y0))))
               for j0, j1, vx0, rate, y0 in blocks)
    return blocks, (1.0 if work > 0 else -1.0)


def _collapse_passive(s: _Scaled, hinges: tuple[Hinge, ...], separation: int | None
                      ) -> np.ndarray:
    """The passive reactions at collapse in a mechanism (scaled): the largest one on every
    block that moves into the fill, none on the others (the work :func:`_passive_work`
    counts)."""
    passive = np.zeros_like(s.vertical)
    if not np.any(s.passive > 0):
        return passive
    blocks, sense = _mechanism_motion(s, hinges, separation)
    for j0, j1, vx0, rate, y0 in blocks:
        u = sense * (vx0 - rate * (s.passive_y[j0:j1] - y0))
        into = -s.passive_sign[j0:j1] * u > 0.0
        passive[j0:j1] = np.where(into, s.passive[j0:j1], 0.0)
    return passive


def _mechanism_thrust_line(arch: BlockArch, hinges: tuple[Hinge, ...],
                           separation: int | None):
    """Multiplier and thrust line of the equilibrium through the mechanism's hinges.

    Unknowns: force and moment at joint 0 and k; the passive reactions are those of the
    collapse (:func:`_collapse_passive`). The thrust passes through each hinge point P:
    ``M_j = P x F_j``; a separating joint carries no normal force, ``n_j . F_j = 0``, and a
    force along its own line, ``M_j = p_in x F_j``.
    """
    s = _scaled(arch)
    passive = _collapse_passive(s, hinges, separation)
    push = s.passive_sign * passive
    cv, cvx = _cumulative(s.vertical), _cumulative(s.vertical * s.vertical_x)
    ch, chy = _cumulative(s.horizontal), _cumulative(s.horizontal * s.horizontal_y)
    cp, cpy = _cumulative(push), _cumulative(push * s.passive_y)
    rows = []

    def through(j: int, px: float, py: float):
        # F_x = F_x0 + k ch + cp, F_y = F_y0 - cv, M = M0 - cvx - k chy - cpy;
        # M - (px F_y - py F_x) = 0
        return ([py, -px, 1.0, py * ch[j] - chy[j]], cvx[j] + cpy[j] - px * cv[j] - py * cp[j])

    for h in hinges:
        px, py = s.start[h.joint] + (0.0 if h.face == FACES[0] else s.depth[h.joint]) \
            * s.direction[h.joint]
        rows.append(through(h.joint, px, py))
    if separation is not None:
        j = separation
        nx, ny = s.normal[j]
        rows.append(([nx, ny, 0.0, nx * ch[j]], ny * cv[j] - nx * cp[j]))
        rows.append(through(j, *s.start[j]))
    mat = np.array([r[0] for r in rows])
    rhs = np.array([r[1] for r in rows])
    x = np.linalg.solve(mat, rhs)
    k = float(x[3])
    fx, fy, m = _joint_states(s, x[:3], k, passive)
    return k, _thrust_line(arch, s, fx, fy, m, k, passive)


def _kinematic(arch: BlockArch, direction: str) -> LimitAnalysis:
    mech = _mechanisms(arch)
    if not np.any(np.isfinite(mech.k)):
        raise NeverCollapsesError(_UNBOUNDED)
    best = int(np.nanargmin(mech.k))
    _check_stands(float(mech.k[best]), arch, direction)
    hinges, separation = mech.hinges(best)
    _, line = _mechanism_thrust_line(arch, hinges, separation)
    return LimitAnalysis(float(mech.k[best]), hinges, line, direction, arch, "kinematic",
                         separation)


METHODS = dict(zip(LIMIT_METHODS, (_static, _kinematic), strict=True))
"""Registry of the limit-analysis methods: ``"static"`` (linear program, lower bound) and
``"kinematic"`` (enumeration of four-hinge mechanisms, upper bound)."""


# ---------------------------------------------------------------------------------- public API
def limit_analysis(arch: BlockArch, direction: str = "l",
                   method: str = DEFAULT_LIMIT_METHOD) -> LimitAnalysis:
    """Collapse load multiplier, hinges and thrust line of an arch [paper, Sect. 3].

    Parameters
    ----------
    arch : BlockArch
        The arch (in its own frame): any :class:`~archquake.geometry.BlockArch`.
    direction : {"l", "r"}
        ``"l"``: horizontal forces ``k m_i g`` toward +x (Mech-l); ``"r"``: the same analysis of
        ``arch.mirrored()`` (Mech-r, reported in the mirrored frame, as Table 1 of the paper).
    method : {"static", "kinematic"}
        ``"static"``: linear program (HiGHS); ``"kinematic"``: minimum over the admissible
        four-hinge mechanisms. Both give the same result (uniqueness theorem); see the module's
        description for both formulations.

    Returns
    -------
    LimitAnalysis
        The load multiplier [-], the hinges, the thrust line at collapse and the arch analysed.

    Raises
    ------
    ValueError
        For an unknown direction or method, or when ``arch`` is not a
        :class:`~archquake.geometry.BlockArch`; if the
        arch cannot stand under its own weight (no thrust line at k = 0: a negative or no
        collapse multiplier), or never collapses (a thrust line for every k).

    References
    ----------
    .. [1] The paper, Sect. 3, eq. (2) and Table 1: Oppenheim's arch has k = 0.37 and the
       hinges A, B, C, D at joints 0, 3, 5, 7.

    Examples
    --------
    Table 1 of [1]_:

    >>> from archquake import oppenheim
    >>> result = limit_analysis(oppenheim(), "l")
    >>> round(result.load_multiplier, 4)
    0.37
    >>> [(h.joint, h.face) for h in result.hinges]
    [(0, 'intrados'), (3, 'extrados'), (5, 'intrados'), (7, 'extrados')]
    """
    if not isinstance(arch, BlockArch):
        raise ValueError(f"arch must be a CircularArch, a ShapedArch or a SurveyedArch, got "
                         f"{type(arch).__name__}")
    method = _check_method(method)
    result = METHODS[method](_oriented(arch, direction), direction)
    if not arch.is_symmetric():
        _check_stands_at_rest(arch)
    return result


def virtual_displacements(result: LimitAnalysis) -> np.ndarray:
    r"""Horizontal virtual displacement of every block's horizontal load in the collapse
    mechanism.

    The mechanism of ``result`` (its hinges, or its hinges and separating joint) moves its
    blocks rigidly; block :math:`i` of a moving part turning at rate :math:`\omega` with a
    point at height :math:`y_0` moving horizontally at :math:`v_0` has the horizontal velocity
    :math:`v_0 - \omega (y - y_0)` at height :math:`y` (a rigid-body field), taken on the line
    of action :math:`y = b_i` of its horizontal load :math:`H_i`
    (:class:`~archquake.geometry.BlockLoads`). The field is scaled so that the largest
    displacement is 1 and the horizontal loads do positive work; blocks outside the mechanism
    (a pier below a hinge at its bed joint, the blocks beyond the springing hinges) do not
    move.

    These are the :math:`\delta_{x,i}` of the participating mass of a local mechanism
    (:mod:`archquake.site.local_mechanism`).

    Parameters
    ----------
    result : LimitAnalysis
        A collapse mechanism (:func:`limit_analysis`), in the frame of ``result.arch``.

    Returns
    -------
    ndarray, shape (n,)
        :math:`\delta_{x,i}` [-] of every block of ``result.arch``, in [-1, 1] (0 for a block
        that does not move).

    Examples
    --------
    Oppenheim's arch (Table 1 of the paper: hinges at joints 0, 3, 5, 7): every voussoir moves.

    >>> from archquake import oppenheim
    >>> dx = virtual_displacements(limit_analysis(oppenheim(), "l"))
    >>> round(float(dx.max()), 6), bool((dx > 0).all())
    (1.0, True)
    """
    s = _scaled(result.arch)
    blocks, sense = _mechanism_motion(s, result.hinges, result.separation)
    dx = np.zeros(result.arch.n_voussoirs)
    for j0, j1, vx0, rate, y0 in blocks:
        dx[j0:j1] = sense * (vx0 - rate * (s.horizontal_y[j0:j1] - y0))
    return dx / np.max(np.abs(dx))


def _check_stands_at_rest(arch: BlockArch) -> None:
    """Refuse an asymmetric structure that admits thrust lines only under a push in one
    direction: its load multipliers in the two directions are then of opposite signs, and the
    positive one alone does not show that it cannot stand (a symmetric one, whose k_l = k_r,
    stands whenever k >= 0)."""
    if _margin(arch) < 0.0:
        verdict = standing(arch)
        raise CannotStandError(f"{verdict.reason} (it stands only under a horizontal push: its "
                               "load multiplier in the other direction is negative)")


def both_directions(arch: BlockArch, method: str = DEFAULT_LIMIT_METHOD
                    ) -> tuple[LimitAnalysis, LimitAnalysis]:
    r"""Limit analyses for Mech-l and Mech-r: ``(result_l, result_r)``.

    Parameters
    ----------
    arch : BlockArch
        The arch.
    method : {"static", "kinematic"}
        Limit-analysis method (:func:`limit_analysis`).

    Returns
    -------
    result_l, result_r : LimitAnalysis
        Mech-l in the frame of ``arch``, Mech-r in the frame of its mirror image; their load
        multipliers are the paper's :math:`\tilde k_l` and :math:`\tilde k_r` [-].
    """
    if not isinstance(arch, BlockArch):
        raise ValueError(f"arch must be a CircularArch, a ShapedArch or a SurveyedArch, got "
                         f"{type(arch).__name__}")
    method = _check_method(method)
    # each direction refuses a negative multiplier: two non-negative ones bracket k = 0, so
    # the arch stands at rest
    return tuple(METHODS[method](_oriented(arch, d), d) for d in DIRECTIONS)


def load_multipliers(arch: BlockArch, method: str = DEFAULT_LIMIT_METHOD) -> tuple[float, float]:
    """``(k_l, k_r)`` of an arch, without hinges or thrust line (the fast path of studies).

    Parameters
    ----------
    arch : BlockArch
        The arch.
    method : {"static", "kinematic"}
        Limit-analysis method.

    Returns
    -------
    k_l, k_r : float
        Load multipliers of Mech-l and Mech-r [-]. A direction in which the arch never
        collapses gives ``inf``; an arch that admits no thrust line at all (too thin to stand)
        gives ``nan`` with the static method (the kinematic method gives the negative multiplier
        of its self-weight mechanism).
    """
    k_l, k_r = load_multipliers_of([arch], method)[0]
    return float(k_l), float(k_r)


def load_multipliers_of(arches: Sequence[BlockArch],
                        method: str = DEFAULT_LIMIT_METHOD) -> np.ndarray:
    """``(k_l, k_r)`` of each of many arches, shape (len(arches), 2): :func:`load_multipliers`
    for a sample. The kinematic method evaluates the mechanisms of all arches with the same
    number of voussoirs together, :data:`KINEMATIC_BATCH` at a time, in one compiled call
    (about 3x faster per arch than one by one); the static method solves one linear program per
    arch and direction.
    """
    _check_method(method)
    arches = list(arches)
    out = np.empty((len(arches), 2))
    for col, direction in enumerate(DIRECTIONS):
        oriented = [_oriented(a, direction) for a in arches]
        if method == "kinematic":
            by_size: dict[int, list[int]] = {}
            for i, a in enumerate(oriented):
                by_size.setdefault(a.n_voussoirs, []).append(i)
            for size, rows in by_size.items():
                # at most KINEMATIC_BATCH arches, and about 4 million multipliers, per call
                _check_enumerable(size)
                count = _family_arrays(tuple(range(size + 1)))[0].shape[0]
                batch = max(1, min(KINEMATIC_BATCH, 4_000_000 // count))
                for start in range(0, len(rows), batch):
                    part = rows[start:start + batch]
                    out[part, col] = _kinematic_multipliers([oriented[i] for i in part])
            continue
        for i, a in enumerate(oriented):
            res = _solve_lp(_scaled(a))
            status = {0: None, 2: math.nan, 3: math.inf}.get(res.status, "failed")
            if res.status != 0 and _is_strut(a):  # unbounded, which HiGHS may fail to tell
                status = math.inf
            if status == "failed":
                raise _lp_failure(res, a)
            out[i, col] = float(res.x[-1]) if status is None else status
    return out


def limit_sample(
    nominal: BlockArch, epsilon: float, sample_size: int, seed: int | None = 0,
    method: str = DEFAULT_LIMIT_METHOD,
) -> LimitSample:
    r"""k~_l and k~_r of ``sample_size`` irregular arches around ``nominal`` [paper, Figs. 17-20].

    The arches are those of :func:`archquake.geometry.irregular_sample` with the same
    ``epsilon`` and ``seed`` (arch ``i`` from child ``i`` of ``SeedSequence(seed)``).

    Parameters
    ----------
    nominal : CircularArch or ShapedArch
        The nominal arch.
    epsilon : float
        The paper's epsilon [-], in [0, 1).
    sample_size : int
        Number of arches s [-] (>= 0; the paper: 1000).
    seed : int or None
        Root seed.
    method : {"static", "kinematic"}
        Limit-analysis method.

    Returns
    -------
    LimitSample
        :math:`\tilde k_l, \tilde k_r` of every arch and
        :math:`\tilde k = \min(\tilde k_l, \tilde k_r)` [-], whose empirical distribution
        (:func:`archquake.studies.fits.empirical_cdf`) is the blue curve of Figs. 17-20 of
        the paper.
    """
    _check_method(method)
    if isinstance(sample_size, bool) or not float(sample_size).is_integer() or sample_size < 0:
        raise ValueError(f"sample_size must be an integer >= 0 (number of arches), got "
                         f"{sample_size!r}")
    arches = irregular_sample(nominal, epsilon, int(sample_size), seed)
    k = load_multipliers_of(arches, method).reshape(-1, 2)
    k_l, k_r = k[:, 0].copy(), k[:, 1].copy()
    k_l.setflags(write=False)
    k_r.setflags(write=False)
    return LimitSample(k_l, k_r, float(epsilon), seed, method)


# ---------------------------------------------------------------------------------- thickness
def self_weight_margin(arch: BlockArch) -> float:
    r"""Largest uniform margin of the thrust line under self-weight alone (k = 0) [-].

    The static linear program of the module's description with :math:`k = 0` and the margin
    :math:`\delta` maximised instead: with :math:`h_j` the depth of joint :math:`j` and forces in
    units of the total weight,

    .. math::

        \delta h_j \le u_j N_j \le (h_j - \delta) N_j,
        \qquad u_j N_j = \mathbf p_{\mathrm{in},j} \times \mathbf F_j - M_j .

    :math:`\delta \ge 0` exactly when a thrust line in equilibrium with the self-weight fits in the
    arch; it changes sign at the minimum thickness (:func:`min_thickness`).
    It is ``inf`` when the thrust can grow without bound with the line of thrust inside every
    joint: a shallow arch whose thickness exceeds its rise stands as a strut under any thrust.
    """
    res = _solve_lp(_scaled(arch), fixed_k=0.0)
    if res.status == 3 or (res.status != 0 and _is_strut(arch)):
        return math.inf
    if res.status != 0:
        raise ValueError(f"the self-weight linear program of this arch cannot be solved "
                         f"({res.message.strip()}): its geometry is degenerate (a nearly flat "
                         "arch?)")
    return float(res.x[-1])


def friction_margin(arch: BlockArch, friction: float) -> float:
    r"""The self-weight margin of :func:`self_weight_margin` with Coulomb friction at the
    joints: the joints may also slide, so the force through every joint must lie within its
    friction cone [-].

    With :math:`N_j = \mathbf n_j \cdot \mathbf F_j` the normal and
    :math:`T_j = \mathbf e_j \cdot \mathbf F_j` the tangential force on joint :math:`j` (its
    springings included), the linear program of :func:`self_weight_margin` gets the rows

    .. math::

        -\mu N_j \le T_j \le \mu N_j, \qquad j = 0 \dots n .

    When it has no solution, no state of the arch in equilibrium with its own weight respects
    the contacts (no tension, no sliding beyond friction): the arch cannot stand with this
    friction, and ``-inf`` is returned. This is exact in that direction for any friction law
    (without equilibrium there is no rest); a feasible program shows a state of rest exists.
    The rigid-block model of the arch (:mod:`archquake.rigid_blocks`), whose joints carry the
    same cones, stands on a still ground exactly when the margin is >= 0 (tested on either side
    of the threshold).

    Parameters
    ----------
    arch : BlockArch
        The arch or structure.
    friction : float
        Coulomb friction coefficient :math:`\mu` of every joint, >= 0 [-].

    Returns
    -------
    float
        The margin :math:`\delta` (``inf`` when unbounded), or ``-inf`` when the arch cannot
        stand with this friction.

    Examples
    --------
    Oppenheim's arch stands with the rigid-block model's default friction 0.8, not with 0.2
    (its springing joints are steeper than the friction cone of 0.2):

    >>> from archquake import oppenheim
    >>> friction_margin(oppenheim(), 0.8) > 0, friction_margin(oppenheim(), 0.2)
    (True, -inf)
    """
    from scipy.sparse import csc_array, vstack

    if not (isinstance(friction, int | float) and math.isfinite(friction) and friction >= 0):
        raise ValueError(f"friction must be a finite number >= 0, got {friction!r}")
    s = _scaled(arch)
    a_eq, b_eq, a_ub = _lp_matrices(s, fixed_k=0.0)
    nj, nv = s.depth.size, a_eq.shape[1]
    j = np.arange(nj)
    (ex, ey), (nx, ny) = s.direction.T, s.normal.T
    # T - mu N <= 0 and -T - mu N <= 0 on the force (F_x, F_y) of every joint
    cone = csc_array((np.concatenate((ex - friction * nx, ey - friction * ny,
                                      -ex - friction * nx, -ey - friction * ny)),
                      (np.concatenate((j, j, nj + j, nj + j)),
                       np.concatenate((j, nj + j, j, nj + j)))), shape=(2 * nj, nv))
    a_ub = vstack((a_ub, cone)).tocsc()
    cost = np.zeros(nv)
    cost[-1] = -1.0
    pushed = s.passive_blocks
    bounds = [(None, None)] * nv
    for i, block in enumerate(pushed):
        bounds[3 * nj + i] = (0.0, float(s.passive[block]))
    res = linprog(cost, A_ub=a_ub, b_ub=np.zeros(a_ub.shape[0]), A_eq=a_eq, b_eq=b_eq,
                  bounds=bounds, method="highs")
    if res.status == 2:
        return -math.inf
    if res.status == 3:
        return math.inf
    if res.status != 0:
        raise ValueError(f"the self-weight linear program with friction of this arch cannot be "
                         f"solved ({res.message.strip()}): its geometry is degenerate")
    return float(res.x[-1])


def standing_with_friction(structure: BlockArch, friction: float) -> Standing:
    """The verdict of :func:`standing` for blocks whose joints may slide, with Coulomb friction
    ``friction`` [-] (:func:`friction_margin`): the rigid-block model's structure under its own
    weight.

    Returns
    -------
    Standing
        ``part`` is ``"joints"`` when the structure would stand without sliding but not with
        this friction.
    """
    verdict = standing(structure)
    if not verdict.stands:
        return verdict
    margin = friction_margin(structure, friction)
    if margin >= 0.0:
        return Standing(True, None, f"it stands under its own weight with friction "
                                    f"{friction:g}", margin)
    return Standing(False, "joints", f"with friction {friction:g} at its joints the arch cannot "
                    "stand under its own weight: no line of thrust in equilibrium with it lies "
                    "within the friction cone of every joint (its joints slide at rest)", margin)


def min_thickness(
    radius: float, embrace: float, voussoirs: int, *, xtol: float = 1e-12,
) -> float:
    """Minimum thickness of a circular arch that stands under its own weight [m].

    Root of :func:`self_weight_margin` in the thickness of ``circular_arch(radius, embrace, t,
    voussoirs)``, found by bracketing and Brent's method. Classical check: a semicircular arch
    (embrace pi) with many voussoirs gives ``t / R`` close to 0.1075 (Heyman's 0.106 [1]_ with
    Milankovitch's correction).

    Parameters
    ----------
    radius : float
        Mean radius R [m].
    embrace : float
        Angle of embrace alpha [rad].
    voussoirs : int
        Number of voussoirs n.
    xtol : float
        Absolute tolerance on t / R [-].

    Returns
    -------
    float
        The minimum thickness t [m].

    References
    ----------
    .. [1] Heyman, J. (1982). The Masonry Arch. Chichester: Ellis Horwood.
    """
    circular_arch(radius, embrace, 0.5 * radius, voussoirs)  # checks the input
    ratio = _min_thickness_ratio(
        lambda ratio: circular_arch(radius, embrace, ratio * radius, voussoirs), 2.0, xtol,
        f"radius={radius} m, embrace={embrace} rad, voussoirs={voussoirs}")
    return float(ratio * radius)


def _min_thickness_ratio(arch_of, largest: float, xtol: float, what: str) -> float:
    """Root in ``(0, largest)`` of the self-weight margin of ``arch_of(ratio)``: bracketed from
    ``largest / 4`` (up toward ``largest``, then halving down), then Brent's method."""

    def margin(ratio: float) -> float:
        # only its sign matters: clipped, an unbounded margin (inf) still brackets the root
        return min(max(self_weight_margin(arch_of(ratio)), -1.0), 1.0)

    hi = 0.25 * largest
    while margin(hi) < 0.0:
        hi = 0.5 * (hi + largest)
        if hi > (1.0 - 5e-4) * largest:
            raise ValueError(
                "no thickness lets this arch stand under its own weight below its largest "
                f"thickness ({what})")
    lo = 0.5 * hi
    while margin(lo) >= 0.0:
        hi, lo = lo, 0.5 * lo
        if lo < 1e-12:
            return hi
    return float(brentq(margin, lo, hi, xtol=xtol, rtol=4 * np.finfo(float).eps))


def shaped_min_thickness(
    shape: str, *, voussoirs: int, span: float | None = None, rise: float | None = None,
    radius: float | None = None, embrace: float | None = None, faces: str = "curved",
    xtol: float = 1e-12,
) -> float:
    r"""Minimum thickness of an arch of a shape that stands under its own weight [m].

    The centreline stays and the thickness t of :func:`~archquake.geometry.shaped_arch` scales:
    root of :func:`self_weight_margin` in t, found by bracketing below twice the centreline's
    smallest radius of curvature (where the intrados would fold) and Brent's method. For a
    semicircle with many voussoirs ``t / R`` tends to Milankovitch's 0.1075 [1]_.

    Parameters
    ----------
    shape : str
        One of :data:`~archquake.geometry.SHAPES`.
    voussoirs : int
        Number of voussoirs n.
    span, rise : float, optional
        Span and rise of the centreline [m].
    radius, embrace : float, optional
        For a circular arch, instead of span and rise: radius [m] and embrace [rad].
    faces : {"curved", "flat"}
        Voussoir faces.
    xtol : float
        Absolute tolerance on t / span [-].

    Returns
    -------
    float
        The minimum thickness t [m].

    References
    ----------
    .. [1] Heyman, J. (1982). The Masonry Arch. Chichester: Ellis Horwood (Milankovitch's
       semicircle).
    """
    line = centreline(shape, span, rise, radius=radius, embrace=embrace)
    check_voussoir_count(voussoirs)
    largest = 2.0 * line.min_radius_of_curvature(0.0, line.length) / line.span

    def arch_of(ratio: float) -> ShapedArch:
        return shaped_arch(shape, span=span, rise=rise, radius=radius, embrace=embrace,
                           thickness=ratio * line.span, voussoirs=voussoirs, faces=faces)

    arch_of(0.25 * largest)  # checks the input
    ratio = _min_thickness_ratio(arch_of, largest, xtol,
                                 f"{shape} arch of {voussoirs} voussoirs")
    return float(ratio * line.span)


# ---------------------------------------------------------------------------------- piers
@dataclass(frozen=True)
class Standing:
    """Whether a structure stands under its own weight, and if not which part fails.

    Attributes
    ----------
    stands : bool
        True when a line of thrust in equilibrium with the self-weight (k = 0) fits inside
        every joint (:func:`self_weight_margin` >= 0).
    part : str or None
        None when it stands; otherwise the part that cannot carry the thrust: ``"arch"`` (the
        arch, with its fill, does not stand even on fixed springings), ``"piers"``,
        ``"left pier"`` or ``"right pier"`` (the arch stands on fixed springings, but not on
        these piers), or ``"joints"`` (it stands without sliding, not with the friction of
        :func:`standing_with_friction`).
    reason : str
        One sentence saying so.
    margin : float
        The self-weight margin of the structure [-] (:func:`self_weight_margin`).
    """

    stands: bool
    part: str | None
    reason: str
    margin: float


def _margin(arch: BlockArch) -> float:
    try:
        return self_weight_margin(arch)
    except ValueError:  # a degenerate linear program: no thrust line either
        return -math.inf


def standing(structure: BlockArch) -> Standing:
    """The verdict on a structure under its own weight: does it stand, and if not, is it the
    arch or the piers that cannot carry the thrust?

    The structure stands when its self-weight margin is >= 0. If it does not, the arch (with its
    fill) is analysed on fixed springings: if it does not stand there either the arch is the
    cause; otherwise the piers are, and each pier is tried alone (the other springing fixed) to
    name the one that fails (both, when neither fails alone or both do).

    Parameters
    ----------
    structure : BlockArch
        An arch or a :class:`~archquake.geometry.Structure`.

    Returns
    -------
    Standing

    Examples
    --------
    Oppenheim's arch stands on piers 3 m wide and 6 m high, not on piers 2 m wide:

    >>> from archquake import oppenheim
    >>> from archquake.geometry import arch_on_piers
    >>> standing(arch_on_piers(oppenheim(), 3.0, 6.0)).stands
    True
    >>> standing(arch_on_piers(oppenheim(), 2.0, 6.0)).part
    'piers'
    """
    if not isinstance(structure, BlockArch):
        raise ValueError(f"structure must be an arch or a Structure, got "
                         f"{type(structure).__name__}")
    margin = _margin(structure)
    if margin >= 0.0:
        return Standing(True, None, "it stands under its own weight", margin)
    piers = isinstance(structure, Structure) and (structure.left is not None
                                                  or structure.right is not None)
    if not piers or _margin(structure.without_piers()) < 0.0:
        where = ", even on fixed springings" if piers else ""
        return Standing(False, "arch", f"the arch cannot stand under its own weight{where}: no "
                        "line of thrust fits inside it (its thickness is below the minimum)",
                        margin)
    failing = [side for side in ("left", "right") if getattr(structure, side) is not None
               and _margin(replace(structure, **{("right" if side == "left" else "left"):
                                                 None})) < 0.0]
    if len(failing) == 1 and getattr(structure, "right" if failing[0] == "left" else "left"):
        part = f"{failing[0]} pier"
        piers_text = f"the {part} ({getattr(structure, failing[0]).describe()})"
    else:
        part = "piers"
        sides = [getattr(structure, side) for side in ("left", "right")]
        described = [p.describe() for p in sides if p is not None]
        piers_text = ("the piers (" + (described[0] if len(set(described)) == 1
                                       else " and ".join(described)) + ")")
    return Standing(False, part, f"{piers_text} cannot carry the arch's thrust: the arch "
                    "stands on fixed springings, but no line of thrust fits through these "
                    "piers (too narrow for their height; see min_pier_width)", margin)


MAX_PIER_XTOL = 1e-3
"""Coarsest tolerance of :func:`min_pier_width`, as a fraction of the arch's size [-]."""


def min_pier_width(arch: BlockArch, height: float, courses: int = 1, *,
                   fill: Fill | None = None, xtol: float = 1e-9) -> float:
    """Narrowest equal rectangular piers on which an arch stands under its own weight [m]
    (to ``xtol``, from above: the arch stands on the width returned).

    The piers (:class:`~archquake.geometry.Pier`, ``height`` high in ``courses`` courses) are
    widened from the narrowest that fit the springing joints (their horizontal extent) until
    :func:`self_weight_margin` of the structure turns >= 0: bracketed by doubling, then Brent's
    method on the margin, as :func:`min_thickness` does on the thickness.

    Parameters
    ----------
    arch : BlockArch
        The arch (circular, shaped or surveyed; a :class:`~archquake.geometry.Structure` stands
        for its arch and its fill, its own piers set aside).
    height : float
        Height of the piers from the ground to the intrados springing point [m].
    courses : int, default 1
        Courses of each pier [-].
    fill : Fill, optional
        Fill over the arch (default: a Structure's own, else none).
    xtol : float, default 1e-9
        Absolute tolerance on the width [m], in (0, :data:`MAX_PIER_XTOL` x the arch's size]
        (a coarser tolerance may return a width on which the arch cannot stand).

    Returns
    -------
    float
        The width [m] (the narrowest that fits when the arch stands on it already).

    Raises
    ------
    CannotStandError
        When the arch does not stand even on fixed springings (no pier helps).
    ValueError
        For a bad height, number of courses or ``xtol``, or no width up to a thousand times
        the arch's size that makes it stand.

    Examples
    --------
    >>> from archquake import oppenheim
    >>> round(min_pier_width(oppenheim(), 6.0), 3)
    2.045
    """
    if isinstance(arch, Structure):
        fill = arch.fill if fill is None else fill
        arch = arch.arch
    Pier(1.0, height, courses)  # checks height and courses
    size = arch.length_scale
    largest = MAX_PIER_XTOL * size
    if isinstance(xtol, bool) or not isinstance(xtol, int | float | np.floating | np.integer) \
            or not 0.0 < xtol <= largest:
        raise ValueError(f"xtol must be a number in (0, {largest:.4g}] m ({MAX_PIER_XTOL:g} of "
                         f"the arch's size {size:.4g} m), got {xtol!r}")
    free = Structure(arch, fill=fill)
    if _margin(free) < 0.0:
        raise CannotStandError(standing(free).reason + "; no pier can make it stand")
    joints = arch.joints
    reach = max(float(joints[0, 0, 0] - joints[0, 1, 0]),
                float(joints[-1, 1, 0] - joints[-1, 0, 0]), 0.0)

    def margin(width: float) -> float:
        pier = Pier(width, height, courses)
        return min(max(_margin(Structure(arch, pier, pier, fill)), -1.0), 1.0)

    lo = max(reach, 1e-6 * size)
    if margin(lo) >= 0.0:
        return lo
    hi = max(2.0 * lo, 0.1 * size)
    while margin(hi) < 0.0:
        lo, hi = hi, 2.0 * hi
        if hi > 1e3 * size:
            raise ValueError(f"no pier width up to {hi:.4g} m makes this arch stand on piers "
                             f"{height:g} m high")
    width = float(brentq(margin, lo, hi, xtol=xtol))
    for _ in range(4):  # the root to xtol may fall short of it: the width returned stands
        if margin(width) >= 0.0:
            break
        width = min(width + xtol, hi)
    return width


# ---------------------------------------------------------------------------------- safety
@dataclass(frozen=True)
class GeometricSafetyFactor:
    """Heyman's geometric factor of safety of a structure, or why it has none.

    Attributes
    ----------
    kind : {"thickness", "pier width"} or None
        What is scaled: the arch's thickness or its piers' width; None when the factor is not
        defined (``note`` says why).
    value : float or None
        The structure's thickness or pier width [m].
    minimum : float or None
        The least thickness or pier width on which it stands under its own weight [m].
    factor : float or None
        ``value / minimum`` [-].
    note : str
        What the factor is of, or why there is none.
    thickness : GeometricSafetyFactor or None
        For an arch on piers: the bare arch's factor in thickness (whether defined or not);
        None otherwise.
    """

    kind: str | None
    value: float | None
    minimum: float | None
    factor: float | None
    note: str
    thickness: GeometricSafetyFactor | None = None

    def to_dict(self) -> dict:
        """The factor as JSON-ready data.

        Returns
        -------
        dict
            ``kind``, ``value`` and ``minimum`` [m], ``factor`` [-] (None when not defined) and
            ``note``; an arch on piers also has ``thickness``, the bare arch's factor as a dict
            of the same keys.
        """
        out = {"kind": self.kind, "value": self.value, "minimum": self.minimum,
               "factor": self.factor}
        if self.thickness is not None:
            out["thickness"] = self.thickness.to_dict()
        out["note"] = self.note
        return out


def _same_geometry(arch: BlockArch, other: BlockArch) -> bool:
    """Whether two arches have the same joints (to 1e-9 of their size) and kind."""
    return (type(arch) is type(other) and arch.n_voussoirs == other.n_voussoirs
            and bool(np.allclose(arch.joints, other.joints, rtol=0.0,
                                 atol=1e-9 * arch.length_scale)))


def _thickness_safety_factor(arch: BlockArch) -> GeometricSafetyFactor:
    """The factor in thickness of an arch on fixed springings (its fill set aside)."""
    try:
        if isinstance(arch, CircularArch):
            t, r, n = float(arch.thicknesses[0]), float(arch.radii[0]), arch.n_voussoirs
            if _same_geometry(arch, circular_arch(r, arch.embrace, t, n, density=arch.density)):
                t_min = min_thickness(r, arch.embrace, n)
                return GeometricSafetyFactor(
                    "thickness", t, t_min, t / t_min,
                    f"thickness over the minimum thickness of a circular arch of the same "
                    f"radius, embrace and {n} voussoirs")
        elif isinstance(arch, ShapedArch):
            line, t, n = arch.centreline, float(arch.thicknesses[0]), arch.n_voussoirs
            nominal = shaped_arch(line.shape, thickness=t, voussoirs=n, span=line.span,
                                  rise=line.rise, faces=arch.faces, density=arch.density)
            if _same_geometry(arch, nominal):
                t_min = shaped_min_thickness(line.shape, voussoirs=n, span=line.span,
                                             rise=line.rise, faces=arch.faces)
                return GeometricSafetyFactor(
                    "thickness", t, t_min, t / t_min,
                    f"thickness over the minimum thickness of a {line.shape} arch of the same "
                    f"span, rise and {n} voussoirs")
    except (ValueError, CannotStandError) as exc:
        return GeometricSafetyFactor(None, None, None, None,
                                     f"the minimum thickness could not be found: {exc}")
    return GeometricSafetyFactor(None, None, None, None,
                                 "not defined: the arch's voussoirs are not equal and of one "
                                 "thickness (an irregular or surveyed arch), so there is no "
                                 "thickness to scale")


def geometric_safety_factor(structure: BlockArch) -> GeometricSafetyFactor:
    r"""The geometric safety factor of a structure: how much thinner (or its piers narrower) it
    could be and still stand under its own weight (Heyman's geometric factor of safety [1]_).

    For an arch on two equal rectangular piers: the piers' width over the narrowest on which it
    stands (:func:`min_pier_width`, fill included),

    .. math::

        \mathrm{SF} = \frac{b}{b_{\min}}.

    Otherwise, for an arch of equal voussoirs and constant thickness (as
    :func:`~archquake.geometry.circular_arch` or :func:`~archquake.geometry.shaped_arch` build
    it): its thickness over the minimum thickness of the same centreline and voussoirs
    (:func:`min_thickness`, :func:`shaped_min_thickness`), of the bare arch on fixed springings,
    :math:`\mathrm{SF} = t / t_{\min}`. Irregular and surveyed arches have no thickness to
    scale: the factor is not defined for them (a value that says so, not an error).

    Parameters
    ----------
    structure : BlockArch
        An arch (circular, shaped or surveyed) or a :class:`~archquake.geometry.Structure` on
        piers or under fill.

    Returns
    -------
    GeometricSafetyFactor
        For an arch on piers, the factor in pier width, with the bare arch's factor in
        thickness as its ``thickness``; otherwise the factor in thickness.

    References
    ----------
    .. [1] Heyman, J. (1982). The Masonry Arch. Chichester: Ellis Horwood.

    Examples
    --------
    >>> from archquake.geometry import circular_arch
    >>> arch = circular_arch(1.0, math.pi, 0.15, 10)
    >>> sf = geometric_safety_factor(arch)
    >>> sf.kind, round(sf.factor, 3)
    ('thickness', 1.396)
    """
    arch = structure.arch if isinstance(structure, Structure) else structure
    thickness = _thickness_safety_factor(arch)
    if isinstance(structure, Structure) and thickness.kind is not None and (
            structure.fill is not None):
        thickness = replace(thickness, note=thickness.note + " (the bare arch, without its fill)")
    piers = isinstance(structure, Structure) and (structure.left is not None
                                                  or structure.right is not None)
    if not piers:
        return thickness
    left, right = structure.left, structure.right

    def undefined(note: str) -> GeometricSafetyFactor:
        return GeometricSafetyFactor(None, None, None, None, note, thickness)

    if left is None or left != right or not left.is_rectangular:
        return undefined("not defined for piers that are not two equal rectangular ones (the "
                         "narrowest piers are found for two equal rectangular piers)")
    try:
        width = min_pier_width(structure, left.height, left.courses)
    except (ValueError, CannotStandError) as exc:
        return undefined(f"the narrowest piers could not be found: {exc}")
    return GeometricSafetyFactor(
        "pier width", left.width, width, left.width / width,
        f"width of the piers over the narrowest equal rectangular piers {left.height:g} m high "
        f"on which the arch" + (" with its fill" if structure.fill is not None else "")
        + " stands", thickness)
