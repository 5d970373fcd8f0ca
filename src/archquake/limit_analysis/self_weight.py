r"""Limit analysis, self-weight: whether a structure stands under its own weight (k = 0), its
margin (:func:`self_weight_margin`), the verdict naming the part that fails (:func:`standing`)
and the refusals of a structure that cannot stand that both methods share."""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

from ..errors import CannotStandError, UnsolvedProgramError
from ..geometry import BlockArch, Structure
from .equilibrium import is_strut, original_arch, scaled_arrays, solve_lp


def check_stands(k: float, arch: BlockArch, direction: str) -> None:
    """Refuse a negative collapse multiplier: such an arch falls under its own weight (k = 0
    admits no thrust line inside it), so it has no activation threshold."""
    if k < 0.0:
        if not isinstance(arch, Structure):
            raise CannotStandError(
                f"the arch cannot stand under its own weight: its collapse load multiplier is "
                f"k = {k:.4g} < 0 (it would need a horizontal push to stand), so no ground "
                "acceleration threshold exists"
            )
        reason = standing(original_arch(arch, direction)).reason
        raise CannotStandError(f"{reason} (its collapse load multiplier is k = {k:.4g} < 0: it "
                               "would need a horizontal push to stand)")


def cannot_stand(arch: BlockArch, direction: str) -> CannotStandError:
    """The error of an arch that admits no thrust line for any load multiplier, with its
    reason."""
    if not isinstance(arch, Structure):
        return CannotStandError(
            "the arch admits no thrust line inside its joints for any horizontal load multiplier "
            "(it cannot stand; the thickness is below the minimum)"
        )
    return CannotStandError(standing(original_arch(arch, direction)).reason)


def check_stands_at_rest(arch: BlockArch) -> None:
    """Refuse an asymmetric structure that admits thrust lines only under a push in one
    direction: its load multipliers in the two directions are then of opposite signs, and the
    positive one alone does not show that it cannot stand (a symmetric one, whose k_l = k_r,
    stands whenever k >= 0)."""
    if stand_margin(arch) < 0.0:
        verdict = standing(arch)
        raise CannotStandError(f"{verdict.reason} (it stands only under a horizontal push: its "
                               "load multiplier in the other direction is negative)")


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
    res = solve_lp(scaled_arrays(arch), fixed_k=0.0)
    if res.status == 3 or (res.status != 0 and is_strut(arch)):
        return math.inf
    if res.status != 0:
        raise UnsolvedProgramError(
            f"the self-weight linear program of this arch cannot be solved "
                         f"({res.message.strip()}): its geometry is degenerate (a nearly flat "
                         "arch?)")
    return float(res.x[-1])


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


def stand_margin(arch: BlockArch) -> float:
    """:func:`self_weight_margin`, or ``-inf`` when its linear program is degenerate (no thrust
    line either)."""
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
    margin = stand_margin(structure)
    if margin >= 0.0:
        return Standing(True, None, "it stands under its own weight", margin)
    piers = isinstance(structure, Structure) and (structure.left is not None
                                                  or structure.right is not None)
    if not piers or stand_margin(structure.without_piers()) < 0.0:
        where = ", even on fixed springings" if piers else ""
        return Standing(False, "arch", f"the arch cannot stand under its own weight{where}: no "
                        "line of thrust fits inside it (its thickness is below the minimum)",
                        margin)
    failing = [side for side in ("left", "right") if getattr(structure, side) is not None
               and stand_margin(replace(structure, **{("right" if side == "left" else "left"):
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
