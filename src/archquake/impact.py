"""Impact between Mech-l and Mech-r: the coefficient of restitution [paper, Sect. 4.4].

When a mechanism returns to its undisplaced configuration (``theta = theta_u`` with
``theta' > 0``) its hinges close and the motion continues in the other mechanism, from that
mechanism's ``theta_u`` with (paper, Sect. 4.4; De Lorenzis et al. 2007 [2])::

    theta'_f = -c_v theta'_i

The sign says the arch moves on into the other mechanism (its theta then decreases).

Computed restitution
--------------------
Impulses act at the closing joints (the edges opposite to the pre-impact hinges) and at the hinges
of the post-impact mechanism [1, Sect. 4.4]. Every such impulse acts either at a hinge of the
post-impact mechanism or between two voussoirs of the same post-impact block, so it does no work
on the velocity field ``u_to`` of the post-impact mechanism. Hence the generalised momentum of the
post-impact mechanism is conserved through the impact::

    theta'_f M_to(theta_u') = theta'_i sum_i (m_i v_i . u_i + I_i w_i omega_i)

where ``v_i, w_i`` and ``u_i, omega_i`` are the centroid velocity and angular velocity of voussoir i
per unit rate in the pre- and post-impact mechanisms (:meth:`FourLinkMechanism.mode_shape`), so

    c_v = -sum_i (m_i v_i . u_i + I_i w_i omega_i) / M_to.

This is the impulse-momentum balance of the three post-impact blocks (linear and angular momentum,
eight hinge impulse components and theta'_f). By the Cauchy-Schwarz inequality the kinetic energy
ratio ``c_v^2 M_to / M_from`` is at most 1.

For Oppenheim's arch (hinges at joints 0, 3, 5, 7) this gives ``c_v = 0.6450`` (kinetic energy
ratio 0.416); with 70 voussoirs and the hinges of the least kinematic multiplier (joints 1, 26, 52,
70, k = 0.3535) ``c_v = 0.736``, and with 140 voussoirs (joints 1, 53, 104, 140, k = 0.3534)
``c_v = 0.728``: about 0.73 in the continuous limit.

Link-wise restitution (the paper's rule)
----------------------------------------
The paper states its rule link by link, as Housner does for a rocking block [1, Sect. 4.4], [3]:
at the impact the springing hinge A of the pre-impact mechanism jumps to the opposite face of the
same springing joint, A'; the post-impact link A'B' (the voussoirs between that springing and the
next hinge of the post-impact mechanism) turns about A' afterwards. Its angular momentum about A'
is conserved through the impact, the impulse at B' neglected (an impulse at A' has no moment
about A')::

    omega' sum_i (I_i + m_i |g_i - A'|^2) = sum_i (I_i omega_i + m_i (g_i - A') x v_i)

over the voussoirs i of A'B', with ``v_i, omega_i`` their pre-impact velocities. Where A'B' lies
inside the pre-impact link AB, which turns about A at ``theta'``, this is Housner's rule::

    c_v = omega' / theta'
        = sum_i (I_i + m_i (g_i - A') . (g_i - A)) / sum_i (I_i + m_i |g_i - A'|^2)

and the paper takes it as the ratio of the post- to the pre-impact Lagrangian rate. For
Oppenheim's arch (A'B' = voussoirs 0-1, from the post-impact hinge at joint 2) it gives 0.883
with annular-sector voussoirs and 0.8749 with flat-faced (trapezoidal) voussoirs
(``shaped_arch("circular", ..., faces="flat")``): the paper's 0.875 (model ``"link"``; the
computed model gives 0.6456 for that arch). The rule presumes that the pre-impact hinge A stands
at the springing, on the joint of A': where the collapse mechanism has its hinge A one joint up
(as for many pointed, elliptical and basket-handle arches), voussoirs of A'B' are at rest before
the impact and the rule gives much lower values (0 when A'B' is a single voussoir at rest). It is
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
mechanism follows. Model ``"blocks"`` (:func:`blocks_restitution`) measures them: the arch,
closed in its undisplaced configuration, moves with the velocity field of the pre-impact
mechanism returning to ``theta_u`` -- the state of every four-link impact --, one time step of
the rigid-block model resolves the impact (:func:`archquake.rigid_blocks.impacts.closing_impact`),
and c_v is the coefficient that leaves the four-link model the kinetic energy the blocks keep,
``c_v = sqrt(T_1/T_0 M_from/M_to)``. It gives Housner's ``r = 1 - 1.5 sin^2(alpha)`` for a
rectangular block, and does not depend on the time step nor, from mu = 0.5 up (the joints
stick at the impact), on the friction coefficient.

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
[1] The paper, Sect. 4.4.

[2] L. De Lorenzis, M. DeJong, J. Ochsendorf (2007), Failure of masonry arches under impulse base
    motion, Earthquake Engineering and Structural Dynamics 36, 2119-2136.

[3] G. W. Housner (1963), The behavior of inverted pendulum structures during earthquakes,
    Bulletin of the Seismological Society of America 53(2), 403-417.
"""

from __future__ import annotations

import contextlib
import math
import numbers

import numpy as np

from .geometry import BlockArch
from .mechanism import FourLinkMechanism
from .reference_arches import paper_values

PAPER_RESTITUTION = float(paper_values()["dynamics"]["NA"]["restitution_paper"])
"""Coefficient of restitution the paper uses for Oppenheim's arch [paper, Sect. 5.2]."""


def original_arch(mechanism: FourLinkMechanism) -> BlockArch:
    """The arch in the original (unmirrored) frame of ``mechanism``."""
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
    """``sum_i m_i v_i . u_i + I_i w_i omega_i`` [kg m^2/m] over the voussoirs of the arch.

    The generalised momentum of ``mech_to`` carried by the motion of ``mech_from`` at unit rate,
    both at their undisplaced configurations; with ``mech_from = mech_to`` it is ``M(theta_u)``.
    """
    arch = _check_same_arch(mech_from, mech_to)
    v, w = mech_from.mode_shape()
    u, omega = mech_to.mode_shape()
    return float(np.sum(arch.masses * np.sum(v * u, axis=1) + arch.inertias * w * omega))


def computed_restitution(mech_from: FourLinkMechanism, mech_to: FourLinkMechanism) -> float:
    """Coefficient of restitution c_v of the impact that ends ``mech_from`` and starts ``mech_to``.

    ``c_v = -sum_i (m_i v_i . u_i + I_i w_i omega_i) / M_to(theta_u')``: conservation of the
    generalised momentum of the post-impact mechanism (impulses at its hinges and at the closing
    joints do no work on its velocity field); see the module docstring.
    """
    return -generalised_momentum(mech_from, mech_to) / generalised_momentum(mech_to, mech_to)


def kinetic_energy_ratio(mech_from: FourLinkMechanism, mech_to: FourLinkMechanism,
                         coefficient: float | None = None) -> float:
    """Kinetic energy after / before the impact, ``c_v^2 M_to / M_from`` [-].

    ``coefficient`` defaults to :func:`computed_restitution`, for which the ratio is <= 1.
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
    r"""Coefficient of restitution c_v of the paper's link-wise rule [1, Sect. 4.4].

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
    the pre-impact link AB [3]. See the module docstring for why this is not a consistent
    momentum balance of the arch.

    Parameters
    ----------
    mech_from, mech_to : FourLinkMechanism
        The pre- and post-impact mechanisms of the same arch (Mech-l and Mech-r, either way).

    Returns
    -------
    float
        c_v [-] (0.883 for Oppenheim's arch with annular-sector voussoirs).
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


def blocks_restitution(mech_from: FourLinkMechanism, mech_to: FourLinkMechanism,
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
    """
    from .rigid_blocks.impacts import equivalent_restitution  # the second model, on demand

    arch = _check_same_arch(mech_from, mech_to)
    modes = [np.column_stack(m.mode_shape()) for m in (mech_from, mech_to)]
    return equivalent_restitution(arch, *modes, settings)


def velocity_after_impact(theta_dot_before, coefficient: float):
    """``theta'_f = -c_v theta'_i`` [rad/s]: the rate of the post-impact mechanism."""
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


def _blocks(mech_l, mech_r, nominal):
    return blocks_restitution(mech_l, mech_r), blocks_restitution(mech_r, mech_l)


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
    "blocks": _blocks,
}
"""Restitution models by name, each ``f(mech_l, mech_r, nominal) -> (c_l_to_r, c_r_to_l)``:

- ``"computed"``: :func:`computed_restitution` of this arch's mechanisms, both ways;
- ``"link"``: :func:`link_restitution`, the paper's link-wise rule (0.875 for Oppenheim's arch
  with flat-faced voussoirs, 0.883 with annular sectors);
- ``"nominal"``: the computed values of the nominal arch's mechanisms (``nominal=``), applied to
  an irregular arch as the paper does [paper, Sect. 4.4];
- ``"paper"``: 0.875, the value the paper uses for Oppenheim's arch [paper, Sect. 5.2];
- ``"elastic"``: 1, no energy lost at impact [paper, Sect. 5.2, Figs. 9-11];
- ``"blocks"``: :func:`blocks_restitution`, measured on the rigid-block model of this arch
  (0.7478 for Oppenheim's arch).
"""


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
        raise ValueError(
            f"restitution must be one of {sorted(RESTITUTION_MODELS)} or a number in (0, 1], "
            f"got {model!r}"
        )
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
    """
    model = check_restitution_model(model)
    if isinstance(model, str):
        c_lr, c_rl = RESTITUTION_MODELS[model](mech_l, mech_r, nominal)
        return float(c_lr), float(c_rl)
    return model, model
