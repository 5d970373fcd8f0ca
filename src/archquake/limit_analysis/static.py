r"""Limit analysis, static method: the linear program of :mod:`.equilibrium` maximising the
load multiplier (the lower bound), and the hinges of the collapse read from its thrust line and
duals (:mod:`archquake.limit_analysis` states the theory)."""

from __future__ import annotations

import numpy as np

from ..errors import NeverCollapsesError
from ..geometry import FACES, BlockArch, Hinge
from .equilibrium import UNBOUNDED, is_strut, lp_failure, scaled_arrays, solve_lp, thrust_line_of
from .kinematic import mechanisms
from .results import LimitAnalysis, ThrustLine
from .self_weight import cannot_stand, check_stands

HINGE_TOLERANCE = 1e-7
"""A joint is a hinge when its pressure point is within this fraction of the joint's contact
depth (its length) from one of its ends."""


def static_analysis(arch: BlockArch, direction: str) -> LimitAnalysis:
    """The static method on ``arch`` as analysed in ``direction``: the largest multiplier of a
    thrust line inside every joint, and the hinges where it touches them."""
    s = scaled_arrays(arch)
    res = solve_lp(s)
    if res.status != 0 and is_strut(arch):  # unbounded, which HiGHS may fail to tell
        raise NeverCollapsesError(UNBOUNDED)
    if res.status == 2:
        raise cannot_stand(arch, direction)
    if res.status == 3:
        raise NeverCollapsesError(UNBOUNDED)
    if res.status != 0:
        raise lp_failure(res, arch)
    nj = arch.n_voussoirs + 1
    x = res.x
    k = float(x[-1])
    check_stands(k, arch, direction)
    fx, fy, m = x[:nj], x[nj : 2 * nj], x[2 * nj : 3 * nj]
    passive = np.zeros(arch.n_voussoirs)
    passive[s.passive_blocks] = x[3 * nj : -1]
    line = thrust_line_of(arch, s, fx, fy, m, k, passive)
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
        mech = mechanisms(arch, candidate_joints=joints)
        match = np.all(on_face[mech.joints, mech.faces], axis=1) & np.isfinite(mech.k)
        if np.any(match):
            close = np.flatnonzero(match)
            return mech.hinges(int(close[np.argmin(np.abs(mech.k[close] - k))]))
    mech = mechanisms(arch)
    return mech.hinges(int(np.nanargmin(np.abs(mech.k - k))))
