r"""Equation of motion of the four-link mechanism: Sect. 4.3, Eqs. (5)-(7) in [1]_, after [2]_.

Lagrange's equation (Eq. (5) in [1]_)

.. math::

    \frac{d}{dt}\frac{\partial T}{\partial \dot\theta} - \frac{\partial T}{\partial \theta}
    + \frac{\partial V}{\partial \theta} = Q

for the three rigid blocks of a :class:`~archquake.fourlink.mechanism.FourLinkMechanism`, with the
real (irregular) mass, centre of mass and moment of inertia of every block, gives for Mech-l (Eq.
(6) in [1]_)

.. math::

    M(\theta)\,\ddot\theta + L(\theta)\,\dot\theta^2 + F(\theta)\,g = P(\theta)\,\ddot x_g

with, for blocks k = 1, 2, 3 of mass :math:`m_k`, centre of mass :math:`G_k = (x_{G_k},
y_{G_k})`, moment of inertia :math:`I_k` about :math:`G_k` and rotation :math:`\delta_k`
(:mod:`archquake.fourlink.mechanism`),

.. math::

    T = \tfrac12 M(\theta)\,\dot\theta^2, \qquad
    M = \sum_k m_k \left|\frac{dG_k}{d\theta}\right|^2
        + I_k \left(\frac{d\delta_k}{d\theta}\right)^2, \qquad
    L = \frac12 \frac{dM}{d\theta},

.. math::

    F = \frac1g \frac{dV}{d\theta} = \sum_k m_k \frac{dy_{G_k}}{d\theta}, \qquad
    P = -\sum_k m_k \frac{dx_{G_k}}{d\theta}.

:math:`F g` is Eq. (4) in [1]_; :math:`P\,\ddot x_g` is the generalised force :math:`Q` of the
inertial forces :math:`-m_k \ddot x_g` (x toward +x of the mechanism's frame, :math:`\ddot x_g`
[m/s^2]). In closed form, with the pivot inertias :math:`J_k` (about A, B, D), the arms
:math:`r_k, \psi_k` of Eq. (3) in [1]_ and the four-bar rates :math:`w_{bc} =
d\theta_{bc}/d\theta`, :math:`w_{cd} = d\theta_{cd}/d\theta`, :math:`a_{bc} = dw_{bc}/d\theta`,
:math:`a_{cd} = dw_{cd}/d\theta` of :func:`~archquake.fourlink.linkage.four_bar_rates`:

.. math::

    M &= J_1 + m_2\,AB^2 + J_2\,w_{bc}^2 + J_3\,w_{cd}^2 + 2\,m_2\,AB\,r_2\,w_{bc} \cos\chi,
    \qquad \chi = \theta_{bc} + \psi_2 - \theta,

    L &= J_2\,w_{bc}\,a_{bc} + J_3\,w_{cd}\,a_{cd}
        + m_2\,AB\,r_2 \left[a_{bc} \cos\chi - w_{bc}\,(w_{bc} - 1) \sin\chi\right],

    F &= m_1 r_1 \cos(\theta + \psi_1) + m_2\,AB \cos\theta
        + m_2 r_2\,w_{bc} \cos(\theta_{bc} + \psi_2) + m_3 r_3\,w_{cd} \cos(\theta_{cd} + \psi_3),

    P &= m_1 r_1 \sin(\theta + \psi_1) + m_2\,AB \sin\theta
        + m_2 r_2\,w_{bc} \sin(\theta_{bc} + \psi_2) + m_3 r_3\,w_{cd} \sin(\theta_{cd} + \psi_3).

Mech-r lives in the mirrored frame, so the ground acceleration of the original frame enters with
the opposite sign (Eq. (7) in [1]_):

.. math::

    M(\theta')\,\ddot\theta' + L(\theta')\,\dot\theta'^2 + F(\theta')\,g
    = -P(\theta')\,\ddot x_g.

This is the one definition of M, L, F, P (:func:`coefficients_from_parameters`, a function of a
mechanism's flat parameter vector): a mechanism evaluates it
(:meth:`~archquake.fourlink.mechanism.FourLinkMechanism.coefficients`, with the angular
acceleration and the kinetic energy beside it), the compiled engine
(:mod:`archquake.fourlink.engine`) does not re-derive it, it tabulates this very function
(:func:`archquake.fourlink.engine.tabulate`), and the slope of the potential energy is
:math:`dV/d\theta = g F`
(:meth:`~archquake.fourlink.mechanism.FourLinkMechanism.potential_energy_derivative`). Masses are
per unit depth of the arch: :math:`m_k` [kg/m], so M and L are in [kg m^2/m] and F and P in [kg
m/m].

References
----------
.. [1] The paper, Sect. 4.2, Eqs. (3)-(4) (potential energy) and Sect. 4.3, Eqs. (5)-(7)
   (Lagrange's equation, the equations of motion of Mech-l and Mech-r).
.. [2] Oppenheim, I. J. (1992). The masonry arch as a four-link mechanism under base motion.
   Earthquake Engineering & Structural Dynamics 21 (the coefficients M, L, F, P, which [1]_
   takes from it).
"""

from __future__ import annotations

import numpy as np

from .linkage import four_bar_closure, four_bar_rates


def coefficients_from_parameters(theta, parameters):
    r"""M, L, F, P at ``theta`` from a mechanism's flat parameter vector (Eq. (6) in [1]_).

    The closed forms of the module docstring: the four-bar closure and rates at ``theta``
    (:func:`~archquake.fourlink.linkage.four_bar_closure`,
    :func:`~archquake.fourlink.linkage.four_bar_rates`), then

    .. math::

        M &= J_1 + m_2\,AB^2 + J_2\,w_{bc}^2 + J_3\,w_{cd}^2 + 2\,m_2\,AB\,r_2\,w_{bc} \cos\chi,

        L &= J_2\,w_{bc}\,a_{bc} + J_3\,w_{cd}\,a_{cd}
            + m_2\,AB\,r_2 \left[a_{bc} \cos\chi - w_{bc}\,(w_{bc} - 1) \sin\chi\right],

        F &= m_1 r_1 \cos(\theta + \psi_1) + m_2\,AB \cos\theta
            + m_2 r_2\,w_{bc} \cos(\theta_{bc} + \psi_2)
            + m_3 r_3\,w_{cd} \cos(\theta_{cd} + \psi_3),

        P &= m_1 r_1 \sin(\theta + \psi_1) + m_2\,AB \sin\theta
            + m_2 r_2\,w_{bc} \sin(\theta_{bc} + \psi_2)
            + m_3 r_3\,w_{cd} \sin(\theta_{cd} + \psi_3),

    with :math:`\chi = \theta_{bc} + \psi_2 - \theta`. Plain array arithmetic, so the same
    function serves the mechanism, the tables of the engine and the tests.

    Parameters
    ----------
    theta : float or array
        Lagrangian coordinate [rad].

    parameters : ndarray, shape (23,)
        :attr:`archquake.fourlink.mechanism.FourLinkMechanism.parameters` (layout
        :data:`archquake.fourlink.mechanism.PARAMETER_NAMES`).

    Returns
    -------
    M : float or array
        Generalised mass (moment of inertia of the mechanism about its coordinate)
        [kg m^2/m].

    L : float or array
        Coefficient of ``theta'^2``, ``1/2 dM/d theta`` [kg m^2/m].

    F : float or array
        Gravity coefficient ``(1/g) dV/d theta`` [kg m/m].

    P : float or array
        Ground-acceleration coefficient [kg m/m]. All four are NaN where the linkage cannot
        close.

    References
    ----------
    .. [1] The paper, Sect. 4.2, Eq. (4) and Sect. 4.3, Eqs. (5)-(6).
    """
    p = parameters
    ax, ay, dx, dy = p[0], p[1], p[2], p[3]
    ab, bc, cd, branch = p[4], p[5], p[6], p[7]
    theta_bc_u, theta_cd_u = p[9], p[10]
    m1, r1, psi1, j1 = p[11], p[12], p[13], p[14]
    m2, r2, psi2, j2 = p[15], p[16], p[17], p[18]
    m3, r3, psi3, j3 = p[19], p[20], p[21], p[22]
    theta_bc, theta_cd = four_bar_closure(
        theta, ax, ay, dx, dy, ab, bc, cd, branch, theta_bc_u, theta_cd_u
    )
    w_bc, w_cd, a_bc, a_cd = four_bar_rates(theta, theta_bc, theta_cd, ab, bc, cd)
    chi = theta_bc + psi2 - theta
    coupling = m2 * ab * r2
    mass = j1 + m2 * ab * ab + j2 * w_bc * w_bc + j3 * w_cd * w_cd \
        + 2.0 * coupling * w_bc * np.cos(chi)
    centrifugal = j2 * w_bc * a_bc + j3 * w_cd * a_cd \
        + coupling * (a_bc * np.cos(chi) - w_bc * (w_bc - 1.0) * np.sin(chi))
    gravity = m1 * r1 * np.cos(theta + psi1) + m2 * ab * np.cos(theta) \
        + m2 * r2 * w_bc * np.cos(theta_bc + psi2) + m3 * r3 * w_cd * np.cos(theta_cd + psi3)
    ground = m1 * r1 * np.sin(theta + psi1) + m2 * ab * np.sin(theta) \
        + m2 * r2 * w_bc * np.sin(theta_bc + psi2) + m3 * r3 * w_cd * np.sin(theta_cd + psi3)
    return mass, centrifugal, gravity, ground
