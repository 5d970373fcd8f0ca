r"""Limit analysis, kinematic method: every one-degree-of-freedom mechanism of a chain (four
hinges, or three and a joint opening over its whole depth) enumerated in compiled code, its
load multiplier by virtual work (the upper bound), its motion, and the equilibrium through its
hinges (:mod:`archquake.limit_analysis` states the theory)."""

from __future__ import annotations

import functools
import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass

import numba
import numpy as np

from ..errors import NeverCollapsesError
from ..geometry import FACES, BlockArch, Hinge
from .equilibrium import (
    UNBOUNDED,
    Scaled,
    cumulative_sums,
    joint_states,
    scaled_arrays,
    thrust_line_of,
)
from .results import LimitAnalysis
from .self_weight import check_stands

MAX_ENUMERATED_VOUSSOIRS = 60
"""Largest number of voussoirs for the kinematic method, which enumerates all
``2 C(n+1, 4)`` four-hinge mechanisms (about a million for n = 60)."""


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
        scaled = [scaled_arrays(a) for a in arches]
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
def family_arrays(pool: tuple[int, ...]):
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


def check_enumerable(n_voussoirs: int) -> None:
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
        check_enumerable(n)
    pool = np.arange(n + 1) if candidate_joints is None else np.asarray(candidate_joints, int)
    joints, faces, separating = family_arrays(tuple(pool.tolist()))
    geo = _Geometry(arches)
    k = np.empty((len(arches), joints.shape[0]))
    _mechanism_multipliers(geo.start_x, geo.start_y, geo.dir_x, geo.dir_y, geo.depth, geo.cv,
                           geo.cvx, geo.ch, geo.chy, geo.passive, geo.passive_y,
                           geo.passive_sign, geo.has_passive, joints, faces, separating, k)
    return joints, faces, k


def mechanisms(arch: BlockArch, candidate_joints: np.ndarray | None = None) -> _Mechanisms:
    """Every one-degree-of-freedom mechanism of one arch (:func:`_mechanism_families`)."""
    joints, faces, k = _mechanism_families([arch], candidate_joints)
    return _Mechanisms(joints, faces, k[0])


KINEMATIC_BATCH = 64
"""Arches whose mechanisms are enumerated together by :func:`load_multipliers_of`."""


def kinematic_multipliers(arches: Sequence[BlockArch]) -> np.ndarray:
    """Smallest admissible multiplier of each arch of a batch (inf if none), shape (B,)."""
    _, _, k = _mechanism_families(arches)
    finite = np.isfinite(k)
    with np.errstate(invalid="ignore"):
        return np.where(finite.any(axis=1), np.min(np.where(finite, k, np.inf), axis=1), np.inf)


def _cross2(a, b) -> float:
    return float(a[0] * b[1] - a[1] * b[0])


def mechanism_motion(s: Scaled, hinges: tuple[Hinge, ...], separation: int | None):
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


def _collapse_passive(s: Scaled, hinges: tuple[Hinge, ...], separation: int | None
                      ) -> np.ndarray:
    """The passive reactions at collapse in a mechanism (scaled): the largest one on every
    block that moves into the fill, none on the others (the work :func:`_passive_work`
    counts)."""
    passive = np.zeros_like(s.vertical)
    if not np.any(s.passive > 0):
        return passive
    blocks, sense = mechanism_motion(s, hinges, separation)
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
    s = scaled_arrays(arch)
    passive = _collapse_passive(s, hinges, separation)
    push = s.passive_sign * passive
    cv, cvx = cumulative_sums(s.vertical), cumulative_sums(s.vertical * s.vertical_x)
    ch, chy = cumulative_sums(s.horizontal), cumulative_sums(s.horizontal * s.horizontal_y)
    cp, cpy = cumulative_sums(push), cumulative_sums(push * s.passive_y)
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
    fx, fy, m = joint_states(s, x[:3], k, passive)
    return k, thrust_line_of(arch, s, fx, fy, m, k, passive)


def kinematic_analysis(arch: BlockArch, direction: str) -> LimitAnalysis:
    """The kinematic method on ``arch`` as analysed in ``direction``: the smallest multiplier
    of its admissible mechanisms, their hinges and the thrust line through them."""
    mech = mechanisms(arch)
    if not np.any(np.isfinite(mech.k)):
        raise NeverCollapsesError(UNBOUNDED)
    best = int(np.nanargmin(mech.k))
    check_stands(float(mech.k[best]), arch, direction)
    hinges, separation = mech.hinges(best)
    _, line = _mechanism_thrust_line(arch, hinges, separation)
    return LimitAnalysis(float(mech.k[best]), hinges, line, direction, arch, "kinematic",
                         separation)
