r"""Limit analysis, equilibrium: the loads and joints of a chain of blocks in units of its total
weight and length scale (:class:`Scaled`), the forces and moments at every joint from those at
joint 0, the thrust line they draw, and the linear program of equilibrium with the line of
thrust inside every joint that the static method and the self-weight margin solve
(:mod:`archquake.limit_analysis` states the theory)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import linprog

from ..errors import UnsolvedProgramError
from ..geometry import BlockArch, Structure
from .results import DIRECTIONS, ThrustLine

LP_TOLERANCE = 1e-10
"""Primal and dual feasibility tolerance of the linear program (HiGHS), in units of the total
weight and the arch's length scale. HiGHS's default, 1e-7, lets the line of thrust of an arch of
thousands of voussoirs stray a few 1e-7 of a joint's depth out of it, on a vertex whose
multiplier is off by 1e-6; at 1e-10 the optimum agrees with the kinematic method to 1e-9 and
costs no more time."""


def check_direction(direction: str) -> str:
    """``direction`` if it is one of :data:`~archquake.limit_analysis.results.DIRECTIONS`;
    ValueError otherwise."""
    if direction not in DIRECTIONS:
        raise ValueError(f"direction must be one of {DIRECTIONS}, got {direction!r}")
    return direction


def oriented_arch(arch: BlockArch, direction: str) -> BlockArch:
    """The arch as analysed in ``direction``: itself for ``"l"``, mirrored for ``"r"``."""
    return arch if check_direction(direction) == "l" else arch.mirrored()


@dataclass(frozen=True)
class Scaled:
    """Dimensionless data of an arch: forces / total weight, lengths / the arch's length scale,
    positions relative to its reference point (the loads:
    :class:`~archquake.geometry.BlockLoads`)."""

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


def scaled_arrays(arch: BlockArch) -> Scaled:
    """The loads and joints of ``arch`` in units of its total weight and length scale."""
    length, ref = arch.length_scale, arch.reference_point
    loads = arch.loads
    weight = loads.total_weight
    return Scaled(
        loads.vertical / weight, (loads.vertical_x - ref[0]) / length,
        loads.horizontal / weight, (loads.horizontal_y - ref[1]) / length,
        loads.passive / weight, (loads.passive_y - ref[1]) / length, loads.passive_sign,
        (arch.joints[:, 0] - ref) / length, arch.joint_directions, arch.joint_normals,
        arch.joint_lengths / length, length, ref, weight,
    )


def cumulative_sums(values) -> np.ndarray:
    """``[0, v_0, v_0 + v_1, ...]``: the sum over the blocks left of every joint."""
    return np.concatenate(([0.0], np.cumsum(values)))


def joint_states(s: Scaled, x0: np.ndarray, k: float, passive: np.ndarray | None = None):
    """Joint forces and moments from the force (F_x, F_y) and moment M at joint 0 (scaled).

    Equilibrium of block i under its weight W_i along x = a_i, its horizontal load k H_i along
    y = b_i and its passive reaction s_i P_i along y = y_i: F_{i+1} = F_i + (k H_i + s_i P_i,
    -W_i), M_{i+1} = M_i - W_i a_i - k H_i b_i - s_i P_i y_i.
    """
    push = np.zeros_like(s.vertical) if passive is None else s.passive_sign * passive
    fx = x0[0] + cumulative_sums(k * s.horizontal + push)
    fy = x0[1] - cumulative_sums(s.vertical)
    m = x0[2] - cumulative_sums(s.vertical * s.vertical_x + k * s.horizontal * s.horizontal_y
                            + push * s.passive_y)
    return fx, fy, m


def thrust_line_of(arch: BlockArch, s: Scaled, fx, fy, m, k: float,
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


def lp_matrices(s: Scaled, fixed_k: float | None = None):
    """Equality and inequality matrices of the static linear program, sparse (CSC).

    Unknowns ``x = [F_x(0..n), F_y(0..n), M(0..n), P(passive blocks), k]`` (scaled), with
    ``P`` the passive reactions of the blocks that have one (bounded by :func:`solve_lp`);
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


def solve_lp(s: Scaled, fixed_k: float | None = None):
    """The linear program by HiGHS, at :data:`LP_TOLERANCE`; at HiGHS's default tolerances
    again if it reports numerical difficulties (a joint depth of 1e-6 of the arch's size)."""
    a_eq, b_eq, a_ub = lp_matrices(s, fixed_k)
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


UNBOUNDED = (
    "the arch does not collapse under any horizontal load multiplier (a thrust line fits inside "
    "it for every k: the arch is too thick or too shallow for a mechanism)"
)


def is_strut(arch: BlockArch) -> bool:
    """Whether a horizontal line crosses every joint of an arch on fixed springings strictly
    between its ends (a nearly flat arch thicker than its rise): a thrust along it, grown
    without bound, carries any finite load with its line inside every joint, so the arch never
    collapses. A structure's piers may overturn: never a strut."""
    if isinstance(arch, Structure):
        return False
    y = np.asarray(arch.joints)[:, :, 1]
    return bool(np.max(np.min(y, axis=1)) < np.min(np.max(y, axis=1))
                - 1e-9 * arch.length_scale)


def lp_failure(res, arch: BlockArch) -> UnsolvedProgramError:
    """The error of a linear program that HiGHS ends without an answer (neither optimal,
    infeasible nor unbounded: numerical difficulties or a limit reached) for an arch that is
    not a strut (:func:`is_strut`): its geometry is too degenerate to analyse."""
    return UnsolvedProgramError(
        f"the limit-analysis linear program of this arch cannot be solved "
                      f"({str(res.message).strip()}): its geometry is degenerate (nearly flat, "
                      "or very large beside its thickness?)")


def original_arch(arch: BlockArch, direction: str) -> BlockArch:
    """The arch in its own frame, from the arch analysed in ``direction``."""
    return arch if direction == "l" else arch.mirrored()
