r"""Limit analysis, friction: the self-weight margin when the joints may also slide, with
Coulomb friction (:func:`friction_margin`), and the verdict of the rigid-block model's structure
at rest (:func:`standing_with_friction`)."""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import linprog

from ..geometry import BlockArch
from .equilibrium import lp_matrices, scaled_arrays
from .self_weight import Standing, standing


def check_friction(friction) -> float:
    """``friction`` as a Coulomb coefficient: a finite number >= 0 [-], else ValueError."""
    if isinstance(friction, bool) or not (isinstance(friction, int | float)
                                          and math.isfinite(friction) and friction >= 0):
        raise ValueError(f"friction must be a finite number >= 0, got {friction!r}")
    return float(friction)


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

    friction = check_friction(friction)
    s = scaled_arrays(arch)
    a_eq, b_eq, a_ub = lp_matrices(s, fixed_k=0.0)
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
