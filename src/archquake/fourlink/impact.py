r"""Impact between Mech-l and Mech-r: the coefficient of restitution (Sect. 4.4 in [1]_).

When a mechanism returns to its undisplaced configuration (``theta = theta_u`` with
``theta' > 0``) its hinges close and the motion continues in the other mechanism, from that
mechanism's ``theta_u`` with (Sect. 4.4 and Eq. (8) in [1]_, after [2]_)

.. math::

    \dot\theta'_f = -c_v\,\dot\theta_i.

Eq. (8) in [1]_ defines :math:`c_v = \dot\theta'_f / \dot\theta_i`; here :math:`c_v > 0` and
the sign is written out: the arch moves on into the other mechanism (its theta then
decreases). Six models of :math:`c_v` are offered (:data:`RESTITUTION_MODELS`); the three that
compute it from the arch are described below.

Computed restitution
--------------------
Impulses act at the closing joints (the edges opposite to the pre-impact hinges) and at the hinges
of the post-impact mechanism (Sect. 4.4 of [1]_). Every such impulse acts either at a hinge of the
post-impact mechanism or between two voussoirs of the same post-impact block, so it does no work
on the velocity field ``u_to`` of the post-impact mechanism. Hence the generalised momentum of the
post-impact mechanism is conserved through the impact:

.. math::

    \dot\theta'_f\,M_{to}(\theta'_u)
    = \dot\theta_i \sum_i \left(m_i\,v_i \cdot u_i + I_i\,w_i\,\omega_i\right),

where :math:`v_i, w_i` and :math:`u_i, \omega_i` are the centroid velocity and angular velocity
of voussoir i per unit rate in the pre- and post-impact mechanisms
(:meth:`FourLinkMechanism.mode_shape`), so

.. math::

    c_v = -\frac{\sum_i \left(m_i\,v_i \cdot u_i + I_i\,w_i\,\omega_i\right)}{M_{to}(\theta'_u)}.

This is the impulse-momentum balance of the three post-impact blocks (linear and angular momentum,
eight hinge impulse components and theta'_f). By the Cauchy-Schwarz inequality (in the inner
product :math:`\langle v, u\rangle = \sum_i m_i\,v_i \cdot u_i + I_i\,w_i\,\omega_i`, of which
:math:`M_{from}` and :math:`M_{to}` are the squared norms) the kinetic energy ratio

.. math::

    \frac{T_f}{T_i} = c_v^2\,\frac{M_{to}(\theta'_u)}{M_{from}(\theta_u)}
    = \frac{\langle v, u\rangle^2}{\langle v, v\rangle\,\langle u, u\rangle} \le 1.

For Oppenheim's arch (hinges at joints 0, 3, 5, 7) this gives ``c_v = 0.6450`` (kinetic energy
ratio 0.416); with 70 voussoirs and the hinges of the least kinematic multiplier (joints 1, 26, 52,
70, k = 0.3535) ``c_v = 0.736``, and with 140 voussoirs (joints 1, 53, 104, 140, k = 0.3534)
``c_v = 0.728``: about 0.73 in the continuous limit.

Link-wise restitution (the paper's rule)
----------------------------------------
The paper states its rule link by link, as Housner does for a rocking block (Sect. 4.4 of [1]_,
[3]_):
at the impact the springing hinge A of the pre-impact mechanism jumps to the opposite face of the
same springing joint, A'; the post-impact link A'B' (the voussoirs between that springing and the
next hinge of the post-impact mechanism) turns about A' afterwards. Its angular momentum about A'
is conserved through the impact, the impulse at B' neglected (an impulse at A' has no moment
about A'):

.. math::

    \omega' \sum_i \left(I_i + m_i\,|g_i - A'|^2\right)
    = \sum_i \left(I_i\,\omega_i + m_i\,(g_i - A') \times v_i\right)

over the voussoirs i of A'B', with ``v_i, omega_i`` their pre-impact velocities. Where A'B' lies
inside the pre-impact link AB, which turns about A at ``theta'``, this is Housner's rule
([3]_; for a rectangular block whose diagonal makes the angle :math:`\alpha` with the
vertical it is :math:`1 - \tfrac32 \sin^2\alpha`):

.. math::

    c_v = \frac{\omega'}{\dot\theta}
    = \frac{\sum_i \left(I_i + m_i\,(g_i - A') \cdot (g_i - A)\right)}
           {\sum_i \left(I_i + m_i\,|g_i - A'|^2\right)}

and the paper takes it as the ratio of the post- to the pre-impact Lagrangian rate. For
Oppenheim's arch (A'B' = voussoirs 0-1, from the post-impact hinge at joint 2) it gives 0.883
with annular-sector voussoirs and 0.8749 with flat-faced (trapezoidal) voussoirs
(``shaped_arch("circular", ..., faces="flat")``): the paper's 0.875 (model ``"link"``; the
computed model gives 0.6456 for that arch). The rule presumes that the pre-impact hinge A stands
at the springing, on the joint of A': where the collapse mechanism has its hinge A one joint up
(as for many pointed, elliptical and basket-handle arches), voussoirs of A'B' are at rest before
the impact and the rule gives much lower values (0 when A'B' is a single voussoir at rest). On
piers (:class:`~archquake.geometry.Structure`) the same holds: where the hinge A of the
pre-impact mechanism is at a pier's base and A' at the same base's other toe, A'B' is the pier
with what it carries and the rule is Housner's rule for that rocking body; where A is higher up
(Oppenheim's arch on piers 3 m x 6 m: A one joint above the left springing, Mech-r's link A'B'
the left pier and the first voussoir, both at rest in Mech-l) the rule gives 0 and does not
apply. The models ``"computed"`` and ``"measured"`` balance the momentum of every block of the
chain, pier courses and fill included, and apply to any structure. It is
not a consistent momentum balance of the arch: the impulse at B'
is not negligible -- it is what sets the other two links of the post-impact mechanism in motion --,
the momentum of those links is not accounted for, and the rate of one link is taken for the rate
of the mechanism's own coordinate (the rate of its other springing link). The generalised momentum
balance above (model ``"computed"``) accounts for every voussoir and every impulse; its kinetic
energy never grows. Other assumptions tried for n = 7: point masses without rotary inertia
0.664; impulses at the pre-impact hinges (generalised momentum of the pre-impact mechanism
conserved) 1.55 (> 1, not physical); post-impact hinges at the same joints on the opposite faces
(a Housner-like reversal of every hinge) 1.40 in theta' (kinetic energy ratio 0.53); Housner's rule
for the whole pre-impact block AB 0.908, for block CD 1.018.

Restitution measured on the rigid blocks
----------------------------------------
The package's second model of the arch (:mod:`archquake.rigid_blocks`: every voussoir a rigid
block, contacts at both ends of every joint, Newton's impact law with restitution 0, Coulomb
friction) has impacts of its own, with no assumption on where the impulses act or which
mechanism follows. Model ``"measured"`` (:func:`measured_restitution`) measures them: the arch,
closed in its undisplaced configuration, moves with the velocity field of the pre-impact
mechanism returning to ``theta_u`` -- the state of every four-link impact --, one time step of
the rigid-block model resolves the impact (:func:`archquake.rigid_blocks.impacts.closing_impact`),
and c_v is the coefficient that leaves the four-link model the kinetic energy the blocks keep,

.. math::

    c_v = \sqrt{\frac{T_1}{T_0}\,\frac{M_{from}(\theta_u)}{M_{to}(\theta'_u)}},

with :math:`T_0, T_1` the kinetic energy of the blocks before and after the impact. It gives
Housner's ratio of angular velocities :math:`1 - 1.5 \sin^2\alpha` for a rectangular block
(his energy ratio :math:`r` is its square), and does not depend on
the time step nor, from mu = 0.5 up (the joints stick at the impact), on the friction
coefficient.

For Oppenheim's arch it gives ``c_v = 0.7478`` (the blocks keep 55.9 % of the kinetic energy),
between the computed 0.645 and the paper's 0.875. The blocks do not continue in Mech-r: 85 % of
the kinetic energy after the impact moves in Mech-r's mode (whose rate alone would give
c_v = 0.691), the rest in a five-hinge motion (hinges at joints 0, 2, 3, 5 and 7) that no
four-link model contains; matching the energy, not the rate of Mech-r, keeps in the four-link
model all the energy the arch can spend on reopening. The energy balance of the ``"computed"``
model assumes the arch moves on in Mech-r alone, which removes that other motion, and with it
energy: hence its lower value. A rigid-block arch released at rest from Mech-l's shape does
not return in Mech-l's mode exactly (its motion drifts, with small impacts before the closing):
over its first two half cycles of free rocking from phi_0 = 0.002-0.02 rad it keeps per half
cycle the kinetic energy of c_v = 0.75-0.82.

References
----------
.. [1] The paper, Sect. 4.4, Eq. (8); Sect. 5.2 (c_v = 0.875 for Oppenheim's arch).
.. [2] De Lorenzis, L., DeJong, M. and Ochsendorf, J. (2007). Failure of masonry arches under
   impulse base motion. Earthquake Engineering & Structural Dynamics 36, 2119-2136.
.. [3] Housner, G. W. (1963). The behavior of inverted pendulum structures during earthquakes.
   Bulletin of the Seismological Society of America 53(2), 403-417.
"""

from __future__ import annotations

import contextlib
import math
import numbers

import numpy as np

from ..geometry import BlockArch
from ..reference_arches import paper_values
from .mechanism import FourLinkMechanism

PAPER_RESTITUTION = float(paper_values()["dynamics"]["NA"]["restitution_paper"])
"""Coefficient of restitution the paper uses for Oppenheim's arch [paper, Sect. 5.2]."""


def original_arch(mechanism: FourLinkMechanism) -> BlockArch:
    """The arch in the original (unmirrored) frame of ``mechanism``.

    Parameters
    ----------
    mechanism : FourLinkMechanism
        Mech-l or Mech-r.

    Returns
    -------
    BlockArch
        ``mechanism.arch`` for Mech-l, its mirror image for Mech-r.
    """
    return mechanism.arch if mechanism.direction == "l" else mechanism.arch.mirrored()


def _check_same_arch(mech_from: FourLinkMechanism, mech_to: FourLinkMechanism) -> BlockArch:
    arch_from, arch_to = original_arch(mech_from), original_arch(mech_to)
    if arch_from.n_voussoirs != arch_to.n_voussoirs or not (
        np.allclose(arch_from.masses, arch_to.masses, rtol=1e-12, atol=0.0)
        and np.allclose(arch_from.centroids, arch_to.centroids, rtol=0.0, atol=1e-9)
    ):
        raise ValueError(
            "mech_from and mech_to must be mechanisms of the same arch (Mech-r built on its "
            "mirrored arch)"
        )
    return arch_from


def generalised_momentum(mech_from: FourLinkMechanism, mech_to: FourLinkMechanism) -> float:
    r"""Generalised momentum of ``mech_to`` carried by the motion of ``mech_from`` at unit rate.

    .. math::

        \langle v, u\rangle = \sum_i \left(m_i\,v_i \cdot u_i + I_i\,w_i\,\omega_i\right)

    over the voussoirs of the arch, with :math:`v_i, w_i` and :math:`u_i, \omega_i` the mode
    shapes of ``mech_from`` and ``mech_to`` at their undisplaced configurations
    (:meth:`FourLinkMechanism.mode_shape`, original frame). With ``mech_from = mech_to`` it is
    :math:`M(\theta_u)` of the equation of motion.

    Parameters
    ----------
    mech_from, mech_to : FourLinkMechanism
        Two mechanisms of the same arch (Mech-r built on its mirrored arch).

    Returns
    -------
    float
        :math:`\langle v, u\rangle` [kg m^2/m].

    Raises
    ------
    ValueError
        If the two mechanisms are not mechanisms of the same arch (voussoir masses and
        centroids compared in the original frame).
    """
    arch = _check_same_arch(mech_from, mech_to)
    v, w = mech_from.mode_shape()
    u, omega = mech_to.mode_shape()
    return float(np.sum(arch.masses * np.sum(v * u, axis=1) + arch.inertias * w * omega))


def computed_restitution(mech_from: FourLinkMechanism, mech_to: FourLinkMechanism) -> float:
    r"""Coefficient of restitution c_v of the impact that ends ``mech_from`` and starts ``mech_to``.

    Conservation of the generalised momentum of the post-impact mechanism (impulses at its
    hinges and at the closing joints do no work on its velocity field; see the module
    docstring):

    .. math::

        c_v = -\frac{\langle v, u\rangle}{\langle u, u\rangle}
            = -\frac{\sum_i \left(m_i\,v_i \cdot u_i + I_i\,w_i\,\omega_i\right)}
                    {M_{to}(\theta'_u)}

    (:func:`generalised_momentum`). It stands for the :math:`c_v` of Eq. (8) in [1]_, whose
    impulses act at the closing joints as in [2]_; the kinetic energy it leaves is at most the
    energy before the impact (:func:`kinetic_energy_ratio`).

    Parameters
    ----------
    mech_from, mech_to : FourLinkMechanism
        The pre- and post-impact mechanisms of the same arch.

    Returns
    -------
    float
        c_v [-].

    Raises
    ------
    ValueError
        If the two mechanisms are not mechanisms of the same arch.

    References
    ----------
    .. [1] The paper, Sect. 4.4, Eq. (8).
    .. [2] De Lorenzis, L., DeJong, M. and Ochsendorf, J. (2007). Failure of masonry arches
       under impulse base motion. Earthquake Engineering & Structural Dynamics 36, 2119-2136.

    Examples
    --------
    Oppenheim's arch keeps 41.6 % of its kinetic energy at each impact:

    >>> from archquake import oppenheim
    >>> from archquake.fourlink.mechanism import mechanisms
    >>> mech_l, mech_r = mechanisms(oppenheim())
    >>> round(computed_restitution(mech_l, mech_r), 4)
    0.645
    >>> round(kinetic_energy_ratio(mech_l, mech_r), 3)
    0.416
    """
    return -generalised_momentum(mech_from, mech_to) / generalised_momentum(mech_to, mech_to)


def kinetic_energy_ratio(mech_from: FourLinkMechanism, mech_to: FourLinkMechanism,
                         coefficient: float | None = None) -> float:
    r"""Kinetic energy after / before the impact.

    .. math::

        \frac{T_f}{T_i} = c_v^2\,\frac{M_{to}(\theta'_u)}{M_{from}(\theta_u)}

    Parameters
    ----------
    mech_from, mech_to : FourLinkMechanism
        The pre- and post-impact mechanisms of the same arch.

    coefficient : float, optional
        c_v [-]; defaults to :func:`computed_restitution`, for which the ratio is <= 1
        (Cauchy-Schwarz, see the module docstring).

    Returns
    -------
    float
        :math:`T_f/T_i` [-].

    Raises
    ------
    ValueError
        If the two mechanisms are not mechanisms of the same arch.
    """
    if coefficient is None:
        coefficient = computed_restitution(mech_from, mech_to)
    return float(coefficient**2 * generalised_momentum(mech_to, mech_to)
                 / generalised_momentum(mech_from, mech_from))


def _original_point(mechanism: FourLinkMechanism, point) -> np.ndarray:
    """A point of ``mechanism``'s frame in the original (unmirrored) frame [m]."""
    point = np.array(point, dtype=float)
    if mechanism.direction == "r":
        point[0] = -point[0]
    return point


def link_restitution(mech_from: FourLinkMechanism, mech_to: FourLinkMechanism) -> float:
    r"""Coefficient of restitution c_v of the paper's link-wise rule (Sect. 4.4 of [1]_).

    The post-impact link A'B' -- the link of ``mech_to`` on the springing side of
    ``mech_from``'s hinge A -- turns about its springing hinge A' after the impact (for a
    symmetric arch: A's joint, the opposite face). Its angular momentum about A' is conserved,
    the impulse at B' neglected, and the ratio of its angular velocity to the rate ``theta'`` of
    ``mech_from`` is taken as c_v:

    .. math::

        c_v = \frac{\sum_{i \in A'B'} \left(I_i \omega_i + m_i (g_i - A') \times v_i\right)}
                   {\sum_{i \in A'B'} \left(I_i + m_i |g_i - A'|^2\right)}

    with ``v_i, omega_i`` the velocities of voussoir i per unit ``theta'`` of ``mech_from``
    (:meth:`FourLinkMechanism.mode_shape`), i.e. Housner's rocking-block rule when A'B' lies in
    the pre-impact link AB [2]_. The sign is that of a rotation in the sense of ``mech_from``'s
    ``theta'`` (mirrored for Mech-r). See the module docstring for why this is not a consistent
    momentum balance of the arch.

    Parameters
    ----------
    mech_from, mech_to : FourLinkMechanism
        The pre- and post-impact mechanisms of the same arch (Mech-l and Mech-r, either way).

    Returns
    -------
    float
        c_v [-] (0.883 for Oppenheim's arch with annular-sector voussoirs, 0.875 with flat
        faces).

    Raises
    ------
    ValueError
        If the two mechanisms are not mechanisms of the same arch.

    References
    ----------
    .. [1] The paper, Sect. 4.4, Eq. (8); Sect. 5.2 (0.875 for Oppenheim's arch).
    .. [2] Housner, G. W. (1963). The behavior of inverted pendulum structures during
       earthquakes. Bulletin of the Seismological Society of America 53(2), 403-417.

    Examples
    --------
    >>> from archquake import oppenheim
    >>> from archquake.fourlink.mechanism import mechanisms
    >>> mech_l, mech_r = mechanisms(oppenheim())
    >>> round(link_restitution(mech_l, mech_r), 3)
    0.883
    """
    arch = _check_same_arch(mech_from, mech_to)
    n = arch.n_voussoirs
    # A' is mech_to's hinge on the springing side of mech_from's A: its D (its frame is the
    # mirror of mech_from's); for a symmetric arch it stands on A's joint, on the other face
    pivot = _original_point(mech_to, mech_to.hinge_points[3])  # A'
    voussoirs = np.arange(mech_to.hinges[2].joint, mech_to.hinges[3].joint)  # its link CD
    if mech_to.direction == "r":
        voussoirs = n - 1 - voussoirs
    v, w = mech_from.mode_shape()  # original frame, counterclockwise positive
    arm = arch.centroids[voussoirs] - pivot
    m, inertia = arch.masses[voussoirs], arch.inertias[voussoirs]
    momentum = np.sum(inertia * w[voussoirs]
                      + m * (arm[:, 0] * v[voussoirs, 1] - arm[:, 1] * v[voussoirs, 0]))
    inertia_about_pivot = np.sum(inertia + m * np.sum(arm**2, axis=1))
    # per unit theta' of mech_from; in a mirrored frame the sense of rotation is reversed
    sense = 1.0 if mech_from.direction == "l" else -1.0
    return float(sense * momentum / inertia_about_pivot)


def measured_restitution(mech_from: FourLinkMechanism, mech_to: FourLinkMechanism,
                         settings=None) -> float:
    r"""Coefficient of restitution c_v measured on the rigid-block model of the same arch.

    The arch, closed in its undisplaced configuration, moves with the velocity field of
    ``mech_from`` returning to ``theta_u`` (:meth:`FourLinkMechanism.mode_shape`, the state of
    every four-link impact); one step of the rigid-block model
    (:func:`archquake.rigid_blocks.impacts.closing_impact`: every voussoir a block, unilateral
    contacts at both ends of every joint, restitution 0, Coulomb friction) resolves the impact,
    and c_v is the coefficient that leaves the four-link model the kinetic energy the blocks
    keep:

    .. math::

        c_v = \sqrt{\frac{T_1}{T_0}\,\frac{M_{from}(\theta_u)}{M_{to}(\theta'_u)}}

    (:func:`archquake.rigid_blocks.impacts.equivalent_restitution`; the module docstring says
    what it gives for Oppenheim's arch and why energy, not the rate of ``mech_to``).

    Parameters
    ----------
    mech_from, mech_to : FourLinkMechanism
        The pre- and post-impact mechanisms of the same arch.
    settings : archquake.rigid_blocks.BlockSettings, optional
        Friction coefficient and time step of the rigid-block model (default: its defaults,
        mu = 0.8, h = 1 ms; the value does not change for mu >= 0.5 or with h).

    Returns
    -------
    float
        c_v [-] (0.7478 for Oppenheim's arch).

    Raises
    ------
    ValueError
        If the two mechanisms are not mechanisms of the same arch.
    """
    from ..rigid_blocks.impacts import equivalent_restitution  # the second model, on demand

    arch = _check_same_arch(mech_from, mech_to)
    modes = [np.column_stack(m.mode_shape()) for m in (mech_from, mech_to)]
    return equivalent_restitution(arch, *modes, settings)


def velocity_after_impact(theta_dot_before, coefficient: float):
    r"""Rate of the post-impact mechanism (Sect. 4.4 and Eq. (8) in [1]_).

    .. math::

        \dot\theta'_f = -c_v\,\dot\theta_i

    Parameters
    ----------
    theta_dot_before : float or array
        :math:`\dot\theta_i`, rate of the pre-impact mechanism at its :math:`\theta_u` [rad/s]
        (positive: it is closing).

    coefficient : float
        c_v [-].

    Returns
    -------
    float or array
        :math:`\dot\theta'_f` [rad/s] (negative: the post-impact mechanism opens).

    References
    ----------
    .. [1] The paper, Sect. 4.4, Eq. (8).
    """
    return -coefficient * np.asarray(theta_dot_before, dtype=float)


# ---------------------------------------------------------------------- registry
def _computed(mech_l, mech_r, nominal):
    return computed_restitution(mech_l, mech_r), computed_restitution(mech_r, mech_l)


def _nominal(mech_l, mech_r, nominal):
    if nominal is None:
        raise ValueError(
            "restitution model 'nominal' needs nominal=(nominal_mech_l, nominal_mech_r), the "
            "mechanisms of the nominal arch"
        )
    nom_l, nom_r = nominal
    return _computed(nom_l, nom_r, None)


def _link(mech_l, mech_r, nominal):
    return link_restitution(mech_l, mech_r), link_restitution(mech_r, mech_l)


def _measured(mech_l, mech_r, nominal):
    return measured_restitution(mech_l, mech_r), measured_restitution(mech_r, mech_l)


def _paper(mech_l, mech_r, nominal):
    return PAPER_RESTITUTION, PAPER_RESTITUTION


def _elastic(mech_l, mech_r, nominal):
    return 1.0, 1.0


RESTITUTION_MODELS = {
    "computed": _computed,
    "link": _link,
    "nominal": _nominal,
    "paper": _paper,
    "elastic": _elastic,
    "measured": _measured,
}
"""Restitution models by name, each ``f(mech_l, mech_r, nominal) -> (c_l_to_r, c_r_to_l)``:

- ``"computed"``: :func:`computed_restitution` of this arch's mechanisms, both ways;
- ``"link"``: :func:`link_restitution`, the paper's link-wise rule (0.875 for Oppenheim's arch
  with flat-faced voussoirs, 0.883 with annular sectors);
- ``"nominal"``: the computed values of the nominal arch's mechanisms (``nominal=``), applied to
  an irregular arch as the paper does [paper, Sect. 4.4];
- ``"paper"``: 0.875, the value the paper uses for Oppenheim's arch [paper, Sect. 5.2];
- ``"elastic"``: 1, no energy lost at impact [paper, Sect. 5.2, Figs. 9-11];
- ``"measured"``: :func:`measured_restitution`, measured on the rigid-block model of this
  arch (0.7478 for Oppenheim's arch).
"""

FORMER_RESTITUTION_NAMES = {"blocks": "measured", "rigid-blocks": "measured"}
"""Names that results stored by earlier versions give a restitution model: ``"blocks"`` and then
``"rigid-blocks"`` (the rigid-block model's own name) for ``"measured"``. Only the readers of
stored results accept them (:func:`stored_restitution_model`)."""


def stored_restitution_model(model):
    """The restitution model of a stored result: a former name (:data:`FORMER_RESTITUTION_NAMES`)
    read as the current one, any other model as it is (checked where the settings are made)."""
    return FORMER_RESTITUTION_NAMES.get(model, model) if isinstance(model, str) else model


def check_restitution_model(model) -> str | float:
    """The one validation rule of a restitution model: a name of :data:`RESTITUTION_MODELS` or
    an imposed coefficient c_v in (0, 1].

    Numbers may be given as text (the command line's ``--restitution 0.875``).

    Parameters
    ----------
    model : str or float
        The model.

    Returns
    -------
    str or float
        The name, or the coefficient as a float [-].

    Raises
    ------
    ValueError
        Naming the valid models when ``model`` is none of them.
    """
    if isinstance(model, str) and model in RESTITUTION_MODELS:
        return model
    value = math.nan
    if isinstance(model, str):
        with contextlib.suppress(ValueError):
            value = float(model)
    elif isinstance(model, numbers.Real) and not isinstance(model, bool):
        value = float(model)
    if math.isnan(value):
        raise ValueError(f"restitution must be one of {sorted(RESTITUTION_MODELS)} or a number "
                         f"in (0, 1], got {model!r}")
    if not (0.0 < value <= 1.0):
        raise ValueError(f"restitution coefficient must be in (0, 1], got {model!r}")
    return value


def restitution(model, mech_l: FourLinkMechanism, mech_r: FourLinkMechanism,
                nominal: tuple[FourLinkMechanism, FourLinkMechanism] | None = None
                ) -> tuple[float, float]:
    """Coefficients of restitution for the impacts Mech-l -> Mech-r and Mech-r -> Mech-l.

    Parameters
    ----------
    model : str or float
        A name in :data:`RESTITUTION_MODELS` or an imposed value c_v in (0, 1] used both ways.
    mech_l, mech_r : FourLinkMechanism
        The two mechanisms of the arch.
    nominal : pair of FourLinkMechanism, optional
        Mech-l and Mech-r of the nominal arch, for ``model="nominal"``.

    Returns
    -------
    (c_l_to_r, c_r_to_l) : tuple of float
        c_v of the impacts Mech-l -> Mech-r and Mech-r -> Mech-l [-].

    Raises
    ------
    ValueError
        If ``model`` is neither a name of :data:`RESTITUTION_MODELS` nor a number in (0, 1]
        (:func:`check_restitution_model`), if ``model="nominal"`` is given without
        ``nominal``, or if the mechanisms are not mechanisms of one arch.

    References
    ----------
    .. [1] The paper, Sect. 4.4 (the nominal arch's c_v for the irregular arches) and
       Sect. 5.2 (0.875 for Oppenheim's arch).

    Examples
    --------
    >>> from archquake import oppenheim
    >>> from archquake.fourlink.mechanism import mechanisms
    >>> mech_l, mech_r = mechanisms(oppenheim())
    >>> restitution("paper", mech_l, mech_r)
    (0.875, 0.875)
    >>> restitution(0.9, mech_l, mech_r)
    (0.9, 0.9)
    """
    model = check_restitution_model(model)
    if isinstance(model, str):
        c_lr, c_rl = RESTITUTION_MODELS[model](mech_l, mech_r, nominal)
        return float(c_lr), float(c_rl)
    return model, model
