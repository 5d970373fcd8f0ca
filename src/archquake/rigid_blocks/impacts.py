r"""The impact of a closing structure in the rigid-block model, and the coefficient of
restitution of a one-degree-of-freedom model that loses the same energy.

A rocking mechanism (a block on one corner, an arch on four hinges) returns to its undeformed
configuration with the velocity field ``v_0 = theta'_i u_from`` of its mode ``u_from`` (block
velocities per unit rate of its coordinate) and closes: the open joints land. In the
rigid-block model this impact is one step of the Moreau-Jean scheme
(:mod:`archquake.rigid_blocks.solver`): every contact is closed (gap 0), each one that the
motion would drive into penetration is active, and Newton's law with restitution 0 and
Coulomb friction decides the impulses and the velocities ``v_1`` after the impact.
:func:`closing_impact` runs exactly that step from the undeformed configuration.

A one-degree-of-freedom model (Housner's block, the four-link model of an arch) instead
continues in the mode ``u_to`` of the other side with ``theta'_f = -c theta'_i``. The
coefficient that leaves it the kinetic energy the blocks keep is

.. math::

    c = \sqrt{\frac{T_1}{T_0}\,\frac{M_{from}}{M_{to}}}, \qquad
    M_{x} = u_x^T \mathbf{M} u_x, \quad T_k = \tfrac12 v_k^T \mathbf{M} v_k

(:func:`equivalent_restitution`), with ``M = diag(m_i, m_i, I_i)`` the mass matrix of the
blocks. The blocks need not continue in ``u_to``: the share of ``T_1`` in that mode is
reported as well (:attr:`ClosingImpact.mode_share`).

For a rectangular block of slenderness ``alpha`` rocking on a rigid base the blocks keep
rotating about the new corner with the angular momentum about it, so ``c`` is Housner's ratio
of angular velocities [1]_,

.. math::

    c = \left|\frac{\dot\theta_f}{\dot\theta_i}\right| = 1 - \tfrac32 \sin^2\alpha, \qquad
    r = c^2 = \frac{T_1}{T_0},

whose square is the ratio ``r`` of the kinetic energies after and before the impact in
[1]_. With no friction the impact law makes ``v_1`` the projection of ``v_0`` in the metric of
``M`` on the cone of velocities that drive no closed contact into penetration [2]_,

.. math::

    v_1 = \mathop{\mathrm{arg\,min}}_{v \,:\, H_n v \ge 0}\;
    \tfrac12 (v - v_0)^T \mathbf{M} (v - v_0)

(``H_n`` the normal Jacobian rows of the closed contacts,
:mod:`archquake.rigid_blocks.contacts`); with enough friction the joints stick at the impact and
the result no longer depends on ``mu`` (for Oppenheim's arch from about ``mu = 0.5`` up).

The measurement is independent of the rate ``theta'_i`` because the impact law is positively
homogeneous in the velocities once the weight's impulse over the step is negligible: the
velocities are scaled so that the fastest centroid moves at :data:`IMPACT_SPEED` times the
velocity the weight gives in one step (its impulse is then 1e-4 of the velocities), and the
result does not depend on the time step.

References
----------
.. [1] G. W. Housner, "The behavior of inverted pendulum structures during earthquakes", Bull.
   Seismol. Soc. Am. 53 (1963) 403-417.

.. [2] J. J. Moreau, "Unilateral contact and dry friction in finite freedom dynamics", in
   Nonsmooth Mechanics and Applications, CISM Courses and Lectures 302, Springer (1988) 1-82.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..constants import GRAVITY
from .dynamics import BlockSettings, resolved_settings, simulate_blocks, structure_assembly

IMPACT_SPEED = 1e4
"""Speed of the fastest centroid before the impact, in units of ``g h`` (the velocity the
weight gives in one time step h) [-]: the weight's share of the impact is 1e-4."""


def _mass_diagonal(assembly) -> np.ndarray:
    """``diag(M)`` of the blocks, shape (nb, 3): m, m, I [kg/m, kg/m, kg m]."""
    return np.column_stack((assembly.masses, assembly.masses, assembly.inertias))


def _check_mode(assembly, mode, name: str) -> np.ndarray:
    """``mode`` as a finite (nb, 3) array [m/s, m/s, rad/s] that moves some centroid; a
    ``ValueError`` naming ``name`` otherwise."""
    nb = assembly.n_blocks
    try:
        u = np.array(mode, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be an array of shape ({nb}, 3) [m/s, m/s, rad/s]") \
            from None
    if u.shape != (nb, 3) or not np.all(np.isfinite(u)):
        raise ValueError(f"{name} must be a finite array of shape ({nb}, 3) [m/s, m/s, rad/s], "
                         f"got shape {u.shape}")
    if not np.any(u[:, :2]):
        raise ValueError(f"{name} must move some centroid (a non-zero velocity field)")
    return u


@dataclass(frozen=True, eq=False)
class ClosingImpact:
    """The impact of a structure that closes with a given velocity field (module docstring).

    Attributes
    ----------
    velocities_before, velocities_after : ndarray, shape (nb, 3)
        Velocities ``(u, w, omega)`` of the blocks before and after the impact, for the given
        field [m/s, m/s, rad/s].
    kinetic_energy_before, kinetic_energy_after : float
        ``T_0`` and ``T_1`` of those velocities [J/m].
    mass_matrix : ndarray, shape (nb, 3)
        Diagonal of the mass matrix [kg/m, kg/m, kg m].
    """

    velocities_before: np.ndarray
    velocities_after: np.ndarray
    kinetic_energy_before: float
    kinetic_energy_after: float
    mass_matrix: np.ndarray

    @property
    def energy_ratio(self) -> float:
        """``T_1 / T_0``: the share of the kinetic energy the impact leaves [-], in [0, 1]."""
        return self.kinetic_energy_after / self.kinetic_energy_before

    def mode_rate(self, mode) -> float:
        r"""Rate of ``mode`` in the velocities after the impact: the projection
        ``v_1^T M u / u^T M u`` [1/s per unit of the field].

        Parameters
        ----------
        mode : array_like, shape (nb, 3)
            Block velocities per unit rate of the coordinate, ``u`` [m, m, rad per rad].

        Returns
        -------
        float
            :math:`\dot\theta_f = v_1^T \mathbf{M} u \,/\, u^T \mathbf{M} u`, in the scale of
            the velocities given to :func:`closing_impact`.
        """
        u = np.asarray(mode, dtype=float)
        return float(np.sum(self.mass_matrix * self.velocities_after * u)
                     / np.sum(self.mass_matrix * u * u))

    def mode_share(self, mode) -> float:
        r"""Share of the kinetic energy after the impact that moves in ``mode`` [-].

        Parameters
        ----------
        mode : array_like, shape (nb, 3)
            Block velocities per unit rate of the coordinate, ``u`` [m, m, rad per rad].

        Returns
        -------
        float
            :math:`\tfrac12 \dot\theta_f^2\, u^T \mathbf{M} u \,/\, T_1`, in [0, 1]
            (:meth:`mode_rate`).
        """
        u = np.asarray(mode, dtype=float)
        rate = self.mode_rate(u)
        return float(0.5 * rate**2 * np.sum(self.mass_matrix * u * u)
                     / self.kinetic_energy_after)


def closing_impact(structure, velocities, settings: BlockSettings | None = None
                   ) -> ClosingImpact:
    r"""One Moreau-Jean step of ``structure`` closed in its undeformed configuration and moving
    with ``velocities``: the rigid-block model's impact (module docstring).

    The field is scaled by :math:`s = N g h / \max_i \max(|u_i|, |w_i|)`
    (N = :data:`IMPACT_SPEED`), one step is run from :math:`q_0 = 0`, and the velocities after
    it are recovered from the step's position update and scaled back:

    .. math::

        v_1 = \frac{1}{s}\,\frac{q_1 / h - (1 - \theta)\, s\, v_0}{\theta}.

    Parameters
    ----------
    structure : BlockArch or Assembly
        The structure.
    velocities : array_like, shape (nb, 3)
        Velocity field before the impact [m/s, m/s, rad/s] (a mode shape returning to the
        undeformed configuration); only its direction matters.
    settings : BlockSettings, optional
        Friction and time step of the model (default :class:`BlockSettings`).

    Returns
    -------
    ClosingImpact
        With the velocities in the scale of ``velocities``.

    Raises
    ------
    ValueError
        If ``velocities`` is not a finite array of shape (nb, 3) that moves some centroid, or
        ``structure`` is not an arch or an :class:`~archquake.rigid_blocks.assembly.Assembly`.
    """
    assembly = structure_assembly(structure)
    v0 = _check_mode(assembly, velocities, "velocities")
    # one step of h: the law of a single step (a coarse step would be taken again at h anyway)
    settings = replace(resolved_settings(settings, assembly), coarse_factor=1)
    h = float(settings.time_step)
    scale = IMPACT_SPEED * GRAVITY * h / float(np.abs(v0[:, :2]).max())
    start = v0 * scale
    history = simulate_blocks(assembly, None, settings, initial=(np.zeros_like(start), start),
                              t_end=2.0 * h, record_every=1)
    # the step's update q_1 = q_0 + h ((1 - theta) v_0 + theta v_1), from q_0 = 0
    q1 = np.column_stack((history.displacements[1], history.rotations[1]))
    theta = float(settings.theta)
    after = (q1 / h - (1.0 - theta) * start) / theta
    mass = _mass_diagonal(assembly)
    return ClosingImpact(
        velocities_before=v0, velocities_after=after / scale,
        kinetic_energy_before=float(0.5 * np.sum(mass * v0 * v0)),
        kinetic_energy_after=float(0.5 * np.sum(mass * after * after)) / scale**2,
        mass_matrix=mass)


def equivalent_restitution(structure, mode_from, mode_to,
                           settings: BlockSettings | None = None) -> float:
    r"""Coefficient of restitution c of the impact from mode ``mode_from`` into ``mode_to``
    that leaves the kinetic energy the rigid blocks keep (module docstring):

    .. math::

        c = \sqrt{\frac{T_1}{T_0}\,\frac{u_{from}^T \mathbf{M} u_{from}}
                                          {u_{to}^T \mathbf{M} u_{to}}}

    Parameters
    ----------
    structure : BlockArch or Assembly
        The structure.
    mode_from, mode_to : array_like, shape (nb, 3)
        Block velocities per unit rate of the coordinate before and after the impact
        [m, m, rad per rad]; ``mode_from`` is the field that closes the structure.
    settings : BlockSettings, optional
        Friction and time step of the model (default :class:`BlockSettings`).

    Returns
    -------
    float
        c [-], in [0, 1] when ``mode_from`` and ``mode_to`` have the same generalised mass.

    Raises
    ------
    ValueError
        If a mode is not a finite array of shape (nb, 3) that moves some centroid.

    Examples
    --------
    Housner's block 0.2 m x 1 m, rocking from one corner onto the other (with enough friction
    to stick), keeps :math:`1 - 1.5 \sin^2\alpha` of its angular velocity:

    >>> import numpy as np
    >>> from archquake.rigid_blocks import rectangular_block
    >>> from archquake.rigid_blocks.dynamics import BlockSettings
    >>> b, h = 0.2, 1.0
    >>> def rocking(x_pivot):  # block velocities per unit counterclockwise rate about a corner
    ...     return np.array([[-(0.5 * h), 0.0 - x_pivot, 1.0]])
    >>> c = equivalent_restitution(rectangular_block(b, h), rocking(b / 2), rocking(-b / 2),
    ...                            BlockSettings(friction=1.0))
    >>> alpha = np.arctan(b / h)
    >>> bool(abs(c - (1 - 1.5 * np.sin(alpha) ** 2)) < 1e-3)
    True
    """
    assembly = structure_assembly(structure)
    u_from = _check_mode(assembly, mode_from, "mode_from")
    u_to = _check_mode(assembly, mode_to, "mode_to")
    impact = closing_impact(assembly, u_from, settings)
    mass = impact.mass_matrix
    ratio = float(np.sum(mass * u_from * u_from) / np.sum(mass * u_to * u_to))
    return math.sqrt(impact.energy_ratio * ratio)


__all__ = ["IMPACT_SPEED", "ClosingImpact", "closing_impact", "equivalent_restitution"]
