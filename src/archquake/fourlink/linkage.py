r"""Kinematics of a four-bar linkage: closure in closed form, velocity and acceleration analysis.

The linkage of a four-hinge arch mechanism [paper, Sect. 4.1]: fixed hinges A and D, link AB
turning about A by the Lagrangian coordinate ``theta``, link DC about D, and the coupler BC. Angles
are measured from +x: ``theta`` of A->B, ``theta_bc`` of B->C and ``theta_cd`` of D->C. The loop
equation is

.. math::

    AB\,e(\theta) + BC\,e(\theta_{bc}) = AD + CD\,e(\theta_{cd}),
    \qquad e(a) = (\cos a, \sin a).

Plain functions of floats and arrays, with no physics (masses, gravity) and no imports from the
package: the mechanism (:mod:`archquake.fourlink.mechanism`) and the equation of motion
(:mod:`archquake.fourlink.equations_of_motion`) both build on them.

References
----------
[1] "Dynamic response of masonry arch with geometrical irregularities subjected to a pulse-type
    ground motion" (the paper), Sect. 4.1.
"""

from __future__ import annotations

import numpy as np


def wrap_angle(angle):
    """``angle`` [rad] reduced to [-pi, pi) [rad] (vectorised)."""
    return (angle + np.pi) % (2.0 * np.pi) - np.pi


def four_bar_closure(theta, ax, ay, dx, dy, ab, bc, cd, branch, theta_bc_ref, theta_cd_ref):
    """Angles of links BC and DC for a given ``theta``: the four-bar closure in closed form.

    B = A + AB (cos theta, sin theta) and C is the intersection of the circle of radius BC about B
    with the circle of radius CD about D on the assembly branch ``branch`` (+1: C to the left of
    the directed line B->D, -1: to the right).

    Parameters
    ----------
    theta : float or array
        Lagrangian coordinate [rad].
    ax, ay, dx, dy : float
        Fixed hinges A and D [m].
    ab, bc, cd : float
        Link lengths [m].
    branch : float
        Assembly branch, +1 or -1.
    theta_bc_ref, theta_cd_ref : float
        Reference angles [rad]; the results are the angles within pi of them (continuous with the
        undisplaced configuration when the references are ``theta_bc_u, theta_cd_u``).

    Returns
    -------
    theta_bc, theta_cd : float or array
        Angle of B->C and of D->C [rad]; NaN where the linkage cannot close.
    """
    bx = ax + ab * np.cos(theta)
    by = ay + ab * np.sin(theta)
    ux = dx - bx
    uy = dy - by
    dist = np.sqrt(ux * ux + uy * uy)
    ux = ux / dist
    uy = uy / dist
    along = (bc * bc - cd * cd + dist * dist) / (2.0 * dist)
    across = branch * np.sqrt(bc * bc - along * along)  # NaN when the circles do not meet
    cx = bx + along * ux - across * uy
    cy = by + along * uy + across * ux
    theta_bc = theta_bc_ref + wrap_angle(np.arctan2(cy - by, cx - bx) - theta_bc_ref)
    theta_cd = theta_cd_ref + wrap_angle(np.arctan2(cy - dy, cx - dx) - theta_cd_ref)
    return theta_bc, theta_cd


def four_bar_rates(theta, theta_bc, theta_cd, ab, bc, cd):
    """First and second derivatives of ``theta_bc`` and ``theta_cd`` with respect to ``theta``.

    From the loop equation ``AB e(theta) + BC e(theta_bc) = AD + CD e(theta_cd)`` with
    ``e(a) = (cos a, sin a)``, differentiated once (velocity analysis) and twice (acceleration
    analysis) and projected on ``e(theta_cd)`` and ``e(theta_bc)``::

        w_bc  = -AB sin(theta_cd - theta) / (BC sin(theta_cd - theta_bc))
        w_cd  =  AB sin(theta_bc - theta) / (CD sin(theta_bc - theta_cd))
        a_bc  = [AB cos(theta - theta_cd) + BC w_bc^2 cos(theta_bc - theta_cd) - CD w_cd^2]
                / (BC sin(theta_cd - theta_bc))
        a_cd  = [-AB cos(theta - theta_bc) - BC w_bc^2 + CD w_cd^2 cos(theta_cd - theta_bc)]
                / (CD sin(theta_bc - theta_cd))

    They diverge where B, C, D are aligned (the linkage reaches a dead point).

    Parameters
    ----------
    theta, theta_bc, theta_cd : float or array
        Link angles [rad] on the closure (see :func:`four_bar_closure`).
    ab, bc, cd : float
        Link lengths [m].

    Returns
    -------
    w_bc, w_cd, a_bc, a_cd : float or array
        ``d theta_bc/d theta``, ``d theta_cd/d theta`` [-] and ``d^2 theta_bc/d theta^2``,
        ``d^2 theta_cd/d theta^2`` [1/rad].
    """
    s = np.sin(theta_cd - theta_bc)
    w_bc = -ab * np.sin(theta_cd - theta) / (bc * s)
    w_cd = -ab * np.sin(theta_bc - theta) / (cd * s)
    c = np.cos(theta_bc - theta_cd)
    a_bc = (ab * np.cos(theta - theta_cd) + bc * w_bc * w_bc * c - cd * w_cd * w_cd) / (bc * s)
    a_cd = -(-ab * np.cos(theta - theta_bc) - bc * w_bc * w_bc + cd * w_cd * w_cd * c) / (cd * s)
    return w_bc, w_cd, a_bc, a_cd
