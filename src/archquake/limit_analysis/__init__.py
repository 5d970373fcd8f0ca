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

from .analysis import (
    METHODS,
    both_directions,
    limit_analysis,
    limit_sample,
    load_multipliers,
    load_multipliers_of,
    virtual_displacements,
)
from .assembly import (
    AssemblyLimit,
    Contacts,
    assembly_limit,
    assembly_limits,
    assembly_min_thickness,
    assembly_multipliers,
    assembly_stands,
    contacts_of,
    governing_law,
    governing_multiplier,
)
from .equilibrium import LP_TOLERANCE
from .friction import friction_margin, standing_with_friction
from .kinematic import (
    FACE_PATTERNS,
    KINEMATIC_BATCH,
    MAX_ENUMERATED_VOUSSOIRS,
)
from .kinematic import mechanisms as _mechanisms  # noqa: F401 -- the name tests import
from .results import (
    AGREEMENT_TOLERANCE,
    DIRECTIONS,
    LimitAnalysis,
    LimitSample,
    ThrustLine,
    multiplier_distribution,
)
from .self_weight import Standing, self_weight_margin, standing
from .static import HINGE_TOLERANCE
from .thickness import (
    MAX_PIER_XTOL,
    GeometricSafetyFactor,
    geometric_safety_factor,
    min_pier_width,
    min_thickness,
    shaped_min_thickness,
)

__all__ = [
    "AGREEMENT_TOLERANCE", "DIRECTIONS", "FACE_PATTERNS", "HINGE_TOLERANCE", "KINEMATIC_BATCH",
    "LP_TOLERANCE", "MAX_ENUMERATED_VOUSSOIRS", "MAX_PIER_XTOL", "METHODS",
    "AssemblyLimit", "Contacts", "GeometricSafetyFactor", "LimitAnalysis", "LimitSample",
    "Standing", "ThrustLine",
    "assembly_limit", "assembly_limits", "assembly_min_thickness", "assembly_multipliers",
    "assembly_stands",
    "governing_law", "governing_multiplier",
    "both_directions", "contacts_of",
    "friction_margin", "geometric_safety_factor", "limit_analysis",
    "limit_sample", "load_multipliers", "load_multipliers_of", "min_pier_width",
    "multiplier_distribution",
    "min_thickness", "self_weight_margin", "shaped_min_thickness", "standing",
    "standing_with_friction", "virtual_displacements",
]
