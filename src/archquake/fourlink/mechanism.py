r"""The four-link mechanism of an arch: Sects. 4.1-4.2 and Eqs. (3)-(4) in [1]_, after [2]_.

Once four hinges A, B, C, D have formed (left to right), the arch is a one-degree-of-freedom
linkage of three rigid blocks: block 1 (voussoirs between hinges A and B) turns about A, block 3
(between C and D) turns about D, and block 2 (between B and C) is carried by both. Its
configuration is described by the Lagrangian coordinate :math:`\theta` (Sect. 4.1 of [1]_).

Conventions
-----------
- Frame, joints and voussoirs as in :mod:`archquake.geometry`, for an arch of any shape: the
  hinges are ends of joints (:meth:`BlockArch.hinge_point
  <archquake.geometry.BlockArch.hinge_point>`) and the links are the blocks of voussoirs between
  them. A mechanism lives in its own frame: Mech-l in the frame of the arch, Mech-r in the frame
  of the arch mirrored about the vertical axis (:meth:`BlockArch.mirrored
  <archquake.geometry.BlockArch.mirrored>`), so that both move toward +x of their own frame.
- ``theta`` is the angle from +x of the vector A->B, ``theta_bc`` the angle of B->C and
  ``theta_cd`` the angle of the vector D->C; ``theta_u`` is ``theta`` in the undisplaced
  configuration. During the motion ``theta < theta_u`` and ``phi = theta_u - theta >= 0``.
- Block k turns by ``delta_1 = theta - theta_u``, ``delta_2 = theta_bc - theta_bc_u``,
  ``delta_3 = theta_cd - theta_cd_u`` respectively.
- The four-bar closure ``|C - B| = BC`` has two assembly branches; the mechanism follows the one
  of the undisplaced configuration.

Geometry of the links
---------------------
With :math:`e(a) = (\cos a, \sin a)`, the moving hinges are

.. math::

    B(\theta) = A + AB\,e(\theta), \qquad C(\theta) = B(\theta) + BC\,e(\theta_{bc}(\theta))
    = D + CD\,e(\theta_{cd}(\theta)),

and block k turns rigidly with its link about its pivot :math:`P_k` = A, B, D: its centre of mass
is

.. math::

    G_1 = A + r_1\,e(\theta + \psi_1), \qquad G_2 = B(\theta) + r_2\,e(\theta_{bc} + \psi_2),
    \qquad G_3 = D + r_3\,e(\theta_{cd} + \psi_3),

with :math:`r_k = |G_k - P_k|` [m] and :math:`\psi_k` [rad] the angle from the link (AB, BC, DC)
to the segment :math:`P_k G_k`, both fixed by the undisplaced configuration (the :math:`r_{AB},
r_{BC}, r_{CD}` and :math:`\psi, \psi_{BC}, \psi_{CD}` of Eq. (3) in [1]_). A block's mass, centre
of mass and moment of inertia about its pivot are those of its real voussoirs,

.. math::

    m_k = \sum_{i \in k} m_i, \qquad
    G_k = \frac{1}{m_k} \sum_{i \in k} m_i\,g_i, \qquad
    J_k = \sum_{i \in k} \left(I_i + m_i\,|g_i - P_k|^2\right),

with :math:`m_i` [kg/m], :math:`g_i` [m] and :math:`I_i` [kg m] the mass, centroid and moment of
inertia of voussoir i (per unit depth), so an irregular arch is treated as it is (Sect. 4.3 of
[1]_).

Nothing here assumes that the hinges stand on the arch or that a link is made of voussoirs only:
the hinges are ends of any joints of the chain, and a link is the consecutive blocks between two
of them. On a :class:`~archquake.geometry.Structure` (an arch on piers or buttresses) the limit
analysis may put A or D at a pier's base or bed joint, and link AB or CD then holds pier courses
and voussoirs, turning as one rigid body about the pier's toe. The fill over an arch rides on
its voussoir: :math:`m_i, g_i, I_i` are then those of the voussoir and its fill column together
(the fill's ``"centroid"`` inertia model, :mod:`archquake.geometry.fill`; the other models are
refused, their fill being no mass).

Potential energy and critical angle
-----------------------------------
The potential energy of the three blocks (Eq. (3) in [1]_, heights from A for blocks 1-2 and
from D for block 3) and its slope (Eq. (4) in [1]_) are

.. math::

    V(\theta) = g\left[m_1 r_1 \sin(\theta + \psi_1) + m_2\,AB \sin\theta
    + m_2 r_2 \sin(\theta_{bc} + \psi_2) + m_3 r_3 \sin(\theta_{cd} + \psi_3)\right],

.. math::

    \frac{dV}{d\theta} = g\left[m_1 r_1 \cos(\theta + \psi_1) + m_2\,AB \cos\theta
    + m_2 r_2 \cos(\theta_{bc} + \psi_2)\,\frac{d\theta_{bc}}{d\theta}
    + m_3 r_3 \cos(\theta_{cd} + \psi_3)\,\frac{d\theta_{cd}}{d\theta}\right] = g\,F(\theta),

with :math:`F` the gravity coefficient of the equation of motion
(:mod:`archquake.fourlink.equations_of_motion`). The critical angle :math:`\theta_{cr}` is the first
zero of :math:`dV/d\theta` below :math:`\theta_u` (Sect. 4.2 of [1]_): released at rest between
:math:`\theta_{cr}` and :math:`\theta_u` the arch returns, released below :math:`\theta_{cr}` it
collapses.

The four-bar kinematics (closure in closed form, velocity and acceleration analysis) live in
:mod:`archquake.fourlink.linkage`, plain functions of floats and arrays; the flat parameter vector
:attr:`FourLinkMechanism.parameters` (layout :data:`PARAMETER_NAMES`) carries everything they and
the equation of motion (:mod:`archquake.fourlink.equations_of_motion`) need.

References
----------
.. [1] The paper, Sect. 4.1 (Lagrangian coordinate), Sect. 4.2, Eqs. (3)-(4) (potential energy,
   critical angle), Sect. 4.3 (real inertial properties of an irregular arch), Table 2 and
   Sect. 5.1 (the mechanism and :math:`\theta_{cr}` of Oppenheim's arch).
.. [2] Oppenheim, I. J. (1992). The masonry arch as a four-link mechanism under base motion.
   Earthquake Engineering & Structural Dynamics 21.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import brentq

from ..geometry import GRAVITY, BlockArch, Hinge
from ..geometry.fill import check_dynamic_fill
from .equations_of_motion import coefficients_from_parameters
from .linkage import four_bar_closure, four_bar_rates, wrap_angle

DIRECTIONS = ("l", "r")
"""Mech-l (the arch sways toward +x) and Mech-r (toward -x; analysed on the mirrored arch)."""

PARAMETER_NAMES = (
    "ax", "ay", "dx", "dy", "ab", "bc", "cd", "branch", "theta_u", "theta_bc_u", "theta_cd_u",
    "m1", "r1", "psi1", "j1", "m2", "r2", "psi2", "j2", "m3", "r3", "psi3", "j3",
)
"""Layout of :attr:`FourLinkMechanism.parameters`: fixed hinges A and D [m], link lengths [m],
assembly branch (+1 or -1), undisplaced angles [rad], and for every block k = 1, 2, 3 its mass
``m_k`` [kg/m], the distance ``r_k`` [m] from its pivot (A, B, D) to its centre of mass, the angle
``psi_k`` [rad] between its link and the segment pivot->centre of mass (eq. (3) of the paper) and
its moment of inertia ``j_k`` about the pivot [kg m]."""

_LIMIT_GRID = 2001


def _angle(vector) -> float:
    return math.atan2(float(vector[1]), float(vector[0]))


def _perp(vectors):
    """Vectors turned by +90 degrees: the velocity of a point per unit counterclockwise spin."""
    vectors = np.asarray(vectors, dtype=float)
    return np.stack((-vectors[..., 1], vectors[..., 0]), axis=-1)


def _check_hinges(arch: BlockArch, hinges) -> tuple[Hinge, Hinge, Hinge, Hinge]:
    try:
        hinges = tuple(hinges)
    except TypeError as exc:
        raise ValueError(f"hinges must be a sequence of four Hinge, got {hinges!r}") from exc
    if len(hinges) != 4 or not all(isinstance(h, Hinge) for h in hinges):
        raise ValueError(f"hinges must be four Hinge (A, B, C, D), got {hinges!r}")
    joints = [h.joint for h in hinges]
    n = arch.n_voussoirs
    if not all(0 <= j <= n for j in joints):
        raise ValueError(f"hinge joints must be in [0, {n}] for this arch, got {joints}")
    if not all(j0 < j1 for j0, j1 in zip(joints[:-1], joints[1:], strict=True)):
        raise ValueError(
            f"hinge joints must be strictly increasing left to right (A < B < C < D), got {joints}"
        )
    return hinges  # type: ignore[return-value]


def _block_properties(arch: BlockArch, first: int, last: int, pivot: np.ndarray):
    """Mass [kg/m], centre of mass [m] and moment of inertia about ``pivot`` [kg m] of the
    voussoirs ``first .. last-1`` taken as one rigid block (parallel-axis theorem)."""
    m = arch.masses[first:last]
    g = arch.centroids[first:last]
    mass = float(m.sum())
    centroid = (m[:, None] * g).sum(axis=0) / mass
    j_pivot = float(np.sum(arch.inertias[first:last] + m * np.sum((g - pivot) ** 2, axis=1)))
    return mass, centroid, j_pivot


@dataclass(frozen=True, eq=False)
class FourLinkMechanism:
    r"""A four-hinge mechanism of an arch: three rigid blocks and a four-bar linkage.

    Build it with :func:`mechanism_from_hinges` (or :func:`mechanisms` from limit analysis). The
    blocks, their masses, centres of mass, arms :math:`r_k, \psi_k` and pivot inertias
    :math:`J_k` are those of the module docstring (Eq. (3) in [1]_), computed once from the real
    voussoirs; :attr:`theta_cr` is the first zero of :math:`dV/d\theta` below :math:`\theta_u`
    (Eq. (4) in [1]_), and the mechanism is activated from rest by a ground acceleration of
    magnitude

    .. math::

        k = -\frac{F(\theta_u)}{P(\theta_u)}

    [g], with :math:`F, P` the coefficients of the equation of motion
    (:mod:`archquake.fourlink.equations_of_motion`): by virtual work, the load multiplier of the
    same hinges (Sect. 3 of [1]_).

    Parameters
    ----------
    arch : BlockArch
        The arch in this mechanism's own frame (the mirrored arch for Mech-r).

    hinges : tuple of four Hinge
        Hinges A, B, C, D from left to right in that frame.

    direction : str
        ``"l"`` (Mech-l) or ``"r"`` (Mech-r).

    Attributes
    ----------
    theta_u, theta_bc_u, theta_cd_u : float
        Link angles in the undisplaced configuration [rad] (Table 2 of [1]_).

    ab, bc, cd : float
        Link lengths ``|AB|``, ``|BC|``, ``|CD|`` [m] (Table 2 of [1]_).

    theta_cr, phi_cr : float
        Critical angle where ``dV/dtheta = 0`` below ``theta_u`` (Eq. (4) of [1]_) and
        ``theta_u - theta_cr`` [rad]. ``theta_cr = theta_u`` if gravity does not resist the
        motion at ``theta_u`` (``dV/dtheta >= 0`` there); ``theta_cr = theta_limit`` if it
        resists it down to the limit.

    theta_limit : float
        Kinematic limit of the linkage [rad]: the largest ``theta < theta_u`` at which either a
        hinge's relative rotation returns to zero (that joint closes again and the blocks would
        interpenetrate: the linkage locks) or the four-bar closure ceases to exist (B, C, D
        aligned, a dead point where ``d theta_bc/d theta`` diverges). Whichever comes first; at
        most pi below ``theta_u``.

    activation_g : float
        ``-F(theta_u)/P(theta_u)``: magnitude of the ground acceleration [g] that activates this
        mechanism (the ground accelerates opposite to the direction of sway), equal to the load
        multiplier of the same hinges by virtual work.

    hinge_points : ndarray, shape (4, 2)
        A, B, C, D in the undisplaced configuration [m].

    block_masses : ndarray, shape (3,)
        Masses of blocks AB, BC, CD [kg/m].

    block_centroids : ndarray, shape (3, 2)
        Their centres of mass in the undisplaced configuration [m].

    block_inertias : ndarray, shape (3,)
        Their moments of inertia about their own centres of mass [kg m].

    block_arms, block_arm_angles : ndarray, shape (3,)
        ``r_k`` [m] and ``psi_k`` [rad] of Eq. (3) of [1]_: distance from the pivot (A, B, D)
        to the block's centre of mass, and angle from the link (AB, BC, DC) to that segment,
        in [-pi, pi).

    block_pivot_inertias : ndarray, shape (3,)
        Moments of inertia ``J_k`` about A, B, D respectively [kg m].

    branch : float
        Assembly branch of the four-bar closure (+1 or -1), see
        :func:`~archquake.fourlink.linkage.four_bar_closure`: +1 when C lies to the left of the
        directed line B->D in the undisplaced configuration.

    parameters : ndarray, shape (23,)
        Everything above that the kinematics and the equation of motion need, flat (layout
        :data:`PARAMETER_NAMES`), read-only; what the compiled engine tabulates from.

    Raises
    ------
    ValueError
        If ``arch`` is not a :class:`~archquake.geometry.BlockArch`, ``direction`` is not
        ``"l"`` or ``"r"``, ``hinges`` are not four :class:`~archquake.geometry.Hinge` on
        joints ``0 <= j <= n`` strictly increasing from left to right, or the arch carries a
        fill whose inertia model is not ``"centroid"``
        (:func:`archquake.geometry.fill.check_dynamic_fill`).

    References
    ----------
    .. [1] The paper, Sect. 3 (activation), Sects. 4.1-4.2, Eqs. (3)-(4), Table 2 and Sect. 5.1
       (:math:`\theta_{cr} = 0.8281` rad, :math:`\theta_u - \theta_{cr} = 0.0691` rad for
       Oppenheim's arch).

    Examples
    --------
    Mech-l of Oppenheim's arch (hinges at joints 0, 3, 5, 7; Table 2 and Sect. 5.1 of [1]_):

    >>> from archquake import oppenheim
    >>> from archquake.fourlink.mechanism import mechanisms
    >>> mech_l, mech_r = mechanisms(oppenheim())
    >>> [hinge.joint for hinge in mech_l.hinges]
    [0, 3, 5, 7]
    >>> round(mech_l.theta_u, 4), round(mech_l.ab, 2), round(mech_l.bc, 2)
    (0.8972, 11.18, 7.78)
    >>> round(mech_l.theta_cr, 4), round(mech_l.phi_cr, 4)
    (0.8281, 0.0691)
    >>> round(mech_l.activation_g, 3)
    0.37
    """

    arch: BlockArch
    hinges: tuple[Hinge, Hinge, Hinge, Hinge]
    direction: str = "l"
    theta_u: float = field(init=False)
    theta_bc_u: float = field(init=False)
    theta_cd_u: float = field(init=False)
    ab: float = field(init=False)
    bc: float = field(init=False)
    cd: float = field(init=False)
    theta_cr: float = field(init=False)
    phi_cr: float = field(init=False)
    theta_limit: float = field(init=False)
    activation_g: float = field(init=False)
    hinge_points: np.ndarray = field(init=False, repr=False)
    branch: float = field(init=False, repr=False)
    block_masses: np.ndarray = field(init=False, repr=False)
    block_centroids: np.ndarray = field(init=False, repr=False)
    block_inertias: np.ndarray = field(init=False, repr=False)
    block_arms: np.ndarray = field(init=False, repr=False)
    block_arm_angles: np.ndarray = field(init=False, repr=False)
    block_pivot_inertias: np.ndarray = field(init=False, repr=False)
    parameters: np.ndarray = field(init=False, repr=False)

    def __post_init__(self):
        if not isinstance(self.arch, BlockArch):
            raise ValueError(f"arch must be a CircularArch, a ShapedArch or a SurveyedArch, got "
                             f"{type(self.arch).__name__}")
        if self.direction not in DIRECTIONS:
            raise ValueError(f"direction must be one of {DIRECTIONS}, got {self.direction!r}")
        check_dynamic_fill(self.arch)
        hinges = _check_hinges(self.arch, self.hinges)
        set_ = object.__setattr__  # frozen dataclass: derived values are set once, here
        set_(self, "hinges", hinges)
        pts = np.array([h.point(self.arch) for h in hinges])
        a, b, c, d = pts
        theta_u, theta_bc_u, theta_cd_u = _angle(b - a), _angle(c - b), _angle(c - d)
        ab, bc, cd = (float(np.hypot(*v)) for v in (b - a, c - b, c - d))
        side = (d - b)[0] * (c - b)[1] - (d - b)[1] * (c - b)[0]
        branch = 1.0 if side >= 0.0 else -1.0
        ja, jb, jc, jd = (h.joint for h in hinges)
        m1, g1, j1 = _block_properties(self.arch, ja, jb, a)
        m2, g2, j2 = _block_properties(self.arch, jb, jc, b)
        m3, g3, j3 = _block_properties(self.arch, jc, jd, d)
        masses = np.array([m1, m2, m3])
        centroids = np.array([g1, g2, g3])
        pivots = np.array([a, b, d])
        arms = np.hypot(*(centroids - pivots).T)
        link_angles = np.array([theta_u, theta_bc_u, theta_cd_u])
        arm_angles = wrap_angle(np.arctan2(*(centroids - pivots).T[::-1]) - link_angles)
        pivot_inertias = np.array([j1, j2, j3])
        inertias = pivot_inertias - masses * arms**2
        params = np.array([
            a[0], a[1], d[0], d[1], ab, bc, cd, branch, theta_u, theta_bc_u, theta_cd_u,
            m1, arms[0], arm_angles[0], j1, m2, arms[1], arm_angles[1], j2,
            m3, arms[2], arm_angles[2], j3,
        ])
        for arr in (pts, masses, centroids, inertias, arms, arm_angles, pivot_inertias, params):
            arr.setflags(write=False)
        for name, value in (
            ("theta_u", theta_u), ("theta_bc_u", theta_bc_u), ("theta_cd_u", theta_cd_u),
            ("ab", ab), ("bc", bc), ("cd", cd), ("hinge_points", pts), ("branch", branch),
            ("block_masses", masses), ("block_centroids", centroids),
            ("block_inertias", inertias), ("block_arms", arms),
            ("block_arm_angles", arm_angles), ("block_pivot_inertias", pivot_inertias),
            ("parameters", params),
        ):
            set_(self, name, value)
        set_(self, "theta_limit", self._kinematic_limit())
        theta_cr = self._critical_angle()
        set_(self, "theta_cr", theta_cr)
        set_(self, "phi_cr", theta_u - theta_cr)
        _, _, f_u, p_u = self.coefficients(theta_u)
        set_(self, "activation_g", float(-f_u / p_u))

    # ------------------------------------------------------------------ kinematics
    def closure(self, theta):
        r"""Angles ``theta_bc(theta)``, ``theta_cd(theta)`` of links BC and DC [rad].

        The four-bar closure of :func:`~archquake.fourlink.linkage.four_bar_closure` on this
        mechanism's assembly branch: C is where the circle of radius BC about :math:`B(\theta)`
        meets the circle of radius CD about D,

        .. math::

            A + AB\,e(\theta) + BC\,e(\theta_{bc}) = D + CD\,e(\theta_{cd}),

        with the angles taken within pi of their undisplaced values (Sect. 4.1 of [1]_).

        Parameters
        ----------
        theta : float or array
            Lagrangian coordinate [rad].

        Returns
        -------
        theta_bc, theta_cd : float or array
            Angles of B->C and of D->C [rad]; NaN where the linkage cannot close.

        References
        ----------
        .. [1] The paper, Sect. 4.1 and Fig. 5.
        """
        ax, ay, dx, dy = self.hinge_points[0, 0], self.hinge_points[0, 1], \
            self.hinge_points[3, 0], self.hinge_points[3, 1]
        return four_bar_closure(
            np.asarray(theta, dtype=float), ax, ay, dx, dy, self.ab, self.bc, self.cd,
            self.branch, self.theta_bc_u, self.theta_cd_u,
        )

    def rates(self, theta):
        r"""Closure and its derivatives with respect to ``theta`` (vectorised).

        The velocity and acceleration analysis of the linkage
        (:func:`~archquake.fourlink.linkage.four_bar_rates`): the loop equation of :meth:`closure`
        differentiated once and twice with respect to :math:`\theta`.

        Parameters
        ----------
        theta : float or array
            Lagrangian coordinate [rad].

        Returns
        -------
        theta_bc, theta_cd : float or array
            Angles of B->C and D->C [rad] (:meth:`closure`).

        w_bc, w_cd : float or array
            :math:`d\theta_{bc}/d\theta`, :math:`d\theta_{cd}/d\theta` [-].

        a_bc, a_cd : float or array
            :math:`d^2\theta_{bc}/d\theta^2`, :math:`d^2\theta_{cd}/d\theta^2` [1/rad].
        """
        theta = np.asarray(theta, dtype=float)
        theta_bc, theta_cd = self.closure(theta)
        return (theta_bc, theta_cd,
                *four_bar_rates(theta, theta_bc, theta_cd, self.ab, self.bc, self.cd))

    def points(self, theta):
        r"""Positions of hinges B and C at ``theta``.

        :math:`B = A + AB\,e(\theta)`, :math:`C = B + BC\,e(\theta_{bc}(\theta))`.

        Parameters
        ----------
        theta : float or array
            Lagrangian coordinate [rad].

        Returns
        -------
        b, c : ndarray, shape (..., 2)
            B and C in this mechanism's frame [m]; NaN where the linkage cannot close.
        """
        theta = np.asarray(theta, dtype=float)
        theta_bc, _ = self.closure(theta)
        b = self.hinge_points[0] + self.ab * np.stack((np.cos(theta), np.sin(theta)), axis=-1)
        c = b + self.bc * np.stack((np.cos(theta_bc), np.sin(theta_bc)), axis=-1)
        return b, c

    def hinge_rotations(self, theta):
        r"""Relative rotation at hinges A, B, C, D.

        The rotation of the block on the right of each hinge relative to the one on its left
        (the ground for A and D), counterclockwise positive:

        .. math::

            (\delta_1,\; \delta_2 - \delta_1,\; \delta_3 - \delta_2,\; -\delta_3), \qquad
            \delta_1 = \theta - \theta_u,\;
            \delta_2 = \theta_{bc} - \theta_{bc,u},\;
            \delta_3 = \theta_{cd} - \theta_{cd,u}.

        For an admissible mechanism each hinge opens the joint on the face opposite to the
        hinge: intrados hinges turn clockwise (negative) and extrados hinges counterclockwise
        (positive) as ``theta`` decreases.

        Parameters
        ----------
        theta : float or array
            Lagrangian coordinate [rad].

        Returns
        -------
        ndarray, shape (..., 4)
            Relative rotations at A, B, C, D [rad].
        """
        theta = np.asarray(theta, dtype=float)
        theta_bc, theta_cd = self.closure(theta)
        d1 = theta - self.theta_u
        d2 = theta_bc - self.theta_bc_u
        d3 = theta_cd - self.theta_cd_u
        return np.stack((d1, d2 - d1, d3 - d2, -d3), axis=-1)

    @property
    def is_admissible(self) -> bool:
        """True when every hinge opens its joint on the face opposite to the hinge as ``theta``
        decreases from ``theta_u`` (no interpenetration at the start of the motion).

        Checked on the signs of :meth:`hinge_rotations` a small step (1e-6 of the range to
        :attr:`theta_limit`, at least 1e-6 rad) below ``theta_u``.
        """
        step = 1e-6 * max(1.0, self.theta_u - self.theta_limit)
        rot = self.hinge_rotations(self.theta_u - step)
        want = np.array([-1.0 if h.face == "intrados" else 1.0 for h in self.hinges])
        return bool(np.all(np.sign(rot) == want))

    def _closure_limit(self) -> float:
        """Largest theta < theta_u at which |BD| reaches BC + CD or |BC - CD| (dead point)."""
        a, d = self.hinge_points[0], self.hinge_points[3]
        ad = float(np.hypot(*(d - a)))
        gamma = _angle(d - a)
        candidates = []
        for reach in (self.bc + self.cd, abs(self.bc - self.cd)):
            # |B - D|^2 = AD^2 + AB^2 - 2 AB AD cos(theta - gamma) = reach^2
            cosine = (ad * ad + self.ab * self.ab - reach * reach) / (2.0 * self.ab * ad)
            if abs(cosine) <= 1.0:
                for base in (gamma + math.acos(cosine), gamma - math.acos(cosine)):
                    # the candidate of this family just below theta_u
                    k = math.ceil((self.theta_u - base) / (2.0 * math.pi)) - 1
                    candidate = base + 2.0 * math.pi * k
                    if self.theta_u - candidate < 1e-12:
                        candidate -= 2.0 * math.pi
                    candidates.append(candidate)
        return max(candidates, default=self.theta_u - math.pi)

    def _kinematic_limit(self) -> float:
        low = max(self._closure_limit(), self.theta_u - math.pi)
        span = self.theta_u - low
        # stay clear of the dead point itself, where the closure is singular
        grid = self.theta_u - span * np.linspace(0.0, 1.0, _LIMIT_GRID)[1:-1]
        rot = self.hinge_rotations(grid)
        limit = low
        for k in range(1, 4):  # hinge A turns by theta - theta_u, never back to zero above low
            r = rot[:, k]
            change = np.flatnonzero(np.sign(r[1:]) != np.sign(r[0]))
            if change.size:
                i = int(change[0]) + 1
                hi, lo = grid[i - 1], grid[i]

                def rotation(t, k=k):
                    return float(self.hinge_rotations(t)[k])

                root = lo if rotation(lo) == 0.0 else brentq(rotation, lo, hi, xtol=1e-13)
                limit = max(limit, root)
        return float(limit)

    # ------------------------------------------------------------------ energy
    def potential_energy(self, theta):
        r"""Potential energy :math:`V(\theta)` of the three blocks (Eq. (3) in [1]_).

        .. math::

            V = g\left[m_1 r_1 \sin(\theta + \psi_1) + m_2\,AB \sin\theta
            + m_2 r_2 \sin(\theta_{bc} + \psi_2) + m_3 r_3 \sin(\theta_{cd} + \psi_3)\right]

        Heights are measured from A for blocks 1 and 2 and from D for block 3, as in [1]_; V
        differs from :math:`g \sum_k m_k y_{G_k}` by the constant
        :math:`g\,[(m_1 + m_2)\,y_A + m_3\,y_D]`.

        Parameters
        ----------
        theta : float or array
            Lagrangian coordinate [rad].

        Returns
        -------
        float or array
            V [J/m] (per unit depth of the arch).

        References
        ----------
        .. [1] The paper, Sect. 4.2, Eq. (3) and Fig. 6 (V of Oppenheim's arch against
           :math:`\varphi = \theta_u - \theta`).
        """
        theta = np.asarray(theta, dtype=float)
        theta_bc, theta_cd = self.closure(theta)
        m, r, psi = self.block_masses, self.block_arms, self.block_arm_angles
        return GRAVITY * (
            m[0] * r[0] * np.sin(theta + psi[0]) + m[1] * self.ab * np.sin(theta)
            + m[1] * r[1] * np.sin(theta_bc + psi[1]) + m[2] * r[2] * np.sin(theta_cd + psi[2])
        )

    def potential_energy_derivative(self, theta):
        r"""Slope :math:`dV/d\theta` of the potential energy (Eq. (4) in [1]_).

        .. math::

            \frac{dV}{d\theta} = g\,F(\theta),

        with :math:`F` the gravity coefficient of the equation of motion
        (:func:`archquake.fourlink.equations_of_motion.coefficients_from_parameters`, the one place
        it is written; its closed form is Eq. (4) in [1]_ divided by :math:`g`).

        Parameters
        ----------
        theta : float or array
            Lagrangian coordinate [rad].

        Returns
        -------
        float or array
            dV/dtheta [J/m/rad]; it vanishes at :attr:`theta_cr` (Sect. 4.2 of [1]_).

        References
        ----------
        .. [1] The paper, Sect. 4.2, Eq. (4).
        """
        return GRAVITY * self.coefficients(theta)[2]

    def _critical_angle(self) -> float:
        """theta_cr: the first zero of dV/dtheta below theta_u (eq. (4) of the paper)."""
        if self.potential_energy_derivative(self.theta_u) >= 0.0:
            return self.theta_u
        span = self.theta_u - self.theta_limit
        grid = self.theta_u - span * np.linspace(0.0, 1.0, _LIMIT_GRID)
        grid[-1] = self.theta_limit + 1e-9 * span
        slope = self.potential_energy_derivative(grid)
        change = np.flatnonzero(slope > 0.0)
        if not change.size:
            return self.theta_limit
        i = int(change[0])
        return float(brentq(lambda t: float(self.potential_energy_derivative(t)),
                            grid[i], grid[i - 1], xtol=1e-14))

    # ------------------------------------------------------------------ dynamics
    def coefficients(self, theta):
        r"""Coefficients M, L, F, P of the equation of motion at ``theta`` (Eq. (6) in [1]_;
        vectorised).

        .. math::

            M(\theta)\,\ddot\theta + L(\theta)\,\dot\theta^2 + F(\theta)\,g
            = \pm P(\theta)\,\ddot x_g

        (``+`` for Mech-l, Eq. (6); ``-`` for Mech-r, Eq. (7) in [1]_), in this mechanism's own
        frame: :func:`~archquake.fourlink.equations_of_motion.coefficients_from_parameters` on
        :attr:`parameters`.

        Parameters
        ----------
        theta : float or array
            Lagrangian coordinate [rad].

        Returns
        -------
        M, L, F, P : float or array
            [kg m^2/m], [kg m^2/m], [kg m/m], [kg m/m]; see
            :func:`~archquake.fourlink.equations_of_motion.coefficients_from_parameters`.

        References
        ----------
        .. [1] The paper, Sect. 4.3, Eqs. (6)-(7).

        Examples
        --------
        At the undisplaced configuration, :math:`-F/P` is the load multiplier of the same hinges
        by virtual work: 0.37 for Oppenheim's arch (Table 1 of the paper).

        >>> from archquake import oppenheim
        >>> from archquake.fourlink.mechanism import mechanisms
        >>> mech_l, _ = mechanisms(oppenheim())
        >>> m, l, f, p = mech_l.coefficients(mech_l.theta_u)
        >>> round(float(-f / p), 3)
        0.37
        """
        return coefficients_from_parameters(np.asarray(theta, dtype=float), self.parameters)

    @property
    def ground_sign(self) -> float:
        """The sign with which the ground acceleration of the original frame enters the
        equation of motion: +1.0 for Mech-l (Eq. (6) in [1]_), -1.0 for Mech-r (Eq. (7) in [1]_,
        mirrored frame).

        References
        ----------
        .. [1] The paper, Sect. 4.3, Eqs. (6)-(7).
        """
        return 1.0 if self.direction == "l" else -1.0

    def angular_acceleration(self, theta, theta_dot, ground_acceleration):
        r"""Angular acceleration from the equation of motion (Eqs. (6)-(7) in [1]_).

        .. math::

            \ddot\theta = \frac{s\,P(\theta)\,\ddot x_g - L(\theta)\,\dot\theta^2
                               - F(\theta)\,g}{M(\theta)},

        with :math:`s` = +1 for Mech-l and -1 for Mech-r (:attr:`ground_sign`) and :math:`g` =
        :data:`~archquake.geometry.GRAVITY`.

        Parameters
        ----------
        theta : float or array
            Lagrangian coordinate [rad].

        theta_dot : float or array
            Its rate [rad/s].

        ground_acceleration : float or array
            Ground acceleration xg'' toward +x of the original (unmirrored) frame [m/s^2].

        Returns
        -------
        float or array
            ``theta''`` [rad/s^2] (broadcast over the three arguments).

        References
        ----------
        .. [1] The paper, Sect. 4.3, Eqs. (6)-(7).

        Examples
        --------
        Mech-l of Oppenheim's arch at rest in its undisplaced configuration: gravity alone
        closes it (:math:`\ddot\theta > 0`); a ground acceleration of -0.5 g, beyond the
        activation multiplier 0.37, opens it (:math:`\ddot\theta < 0`).

        >>> from archquake import oppenheim
        >>> from archquake.geometry import GRAVITY
        >>> from archquake.fourlink.mechanism import mechanisms
        >>> mech_l, _ = mechanisms(oppenheim())
        >>> bool(mech_l.angular_acceleration(mech_l.theta_u, 0.0, 0.0) > 0.0)
        True
        >>> bool(mech_l.angular_acceleration(mech_l.theta_u, 0.0, -0.5 * GRAVITY) < 0.0)
        True
        """
        m, l, f, p = self.coefficients(theta)
        return (self.ground_sign * p * np.asarray(ground_acceleration, dtype=float)
                - l * np.asarray(theta_dot, dtype=float) ** 2 - f * GRAVITY) / m

    def kinetic_energy(self, theta, theta_dot):
        r"""Kinetic energy of the mechanism relative to the ground.

        .. math::

            T = \tfrac12\,M(\theta)\,\dot\theta^2

        (the :math:`T` of Lagrange's equation, Eq. (5) in [1]_).

        Parameters
        ----------
        theta : float or array
            Lagrangian coordinate [rad].

        theta_dot : float or array
            Its rate [rad/s].

        Returns
        -------
        float or array
            T [J/m].

        References
        ----------
        .. [1] The paper, Sect. 4.3, Eq. (5).
        """
        m, _, _, _ = self.coefficients(theta)
        return 0.5 * m * np.asarray(theta_dot, dtype=float) ** 2

    def mode_shape(self):
        r"""Velocity field of the voussoirs at ``theta_u`` per unit rate ``theta'``.

        Voussoir i of block k moves with

        .. math::

            \frac{v_i}{\dot\theta} = \frac{dP_k}{d\theta}
            + \frac{d\theta_k}{d\theta}\,\hat z \times (g_i - P_k), \qquad
            \frac{\omega_i}{\dot\theta} = \frac{d\theta_k}{d\theta},

        in this mechanism's frame, with :math:`P_k` = A, B, D, :math:`\theta_k` =
        :math:`\theta, \theta_{bc}, \theta_{cd}` for k = 1, 2, 3, :math:`\hat z \times (x, y) =
        (-y, x)` (a quarter turn counterclockwise) and :math:`dB/d\theta = \hat z \times (B -
        A)` (A and D are fixed). For Mech-r the field is mirrored back to the original frame.
        The impact models of :mod:`archquake.fourlink.impact` are written with it.

        Returns
        -------
        velocities : ndarray, shape (n, 2)
            Velocity of the centroid of every voussoir of the original (unmirrored) arch, in the
            original frame and voussoir order, per unit ``d theta/dt`` [m/rad].

        angular : ndarray, shape (n,)
            Angular velocity of every voussoir, counterclockwise positive in the original
            frame, per unit ``d theta/dt`` [-]. Voussoirs outside the blocks are at rest.
        """
        n = self.arch.n_voussoirs
        ja, jb, jc, jd = (h.joint for h in self.hinges)
        _, _, w_bc, w_cd, _, _ = self.rates(self.theta_u)
        w_bc, w_cd = float(w_bc), float(w_cd)
        a, b, _, d = self.hinge_points
        g = self.arch.centroids
        velocities = np.zeros((n, 2))
        angular = np.zeros(n)
        velocities[ja:jb] = _perp(g[ja:jb] - a)
        angular[ja:jb] = 1.0
        v_b = _perp(b - a)
        velocities[jb:jc] = v_b + w_bc * _perp(g[jb:jc] - b)
        angular[jb:jc] = w_bc
        velocities[jc:jd] = w_cd * _perp(g[jc:jd] - d)
        angular[jc:jd] = w_cd
        if self.direction == "r":  # back to the original frame: mirror x, reverse the order
            velocities = velocities[::-1] * np.array([-1.0, 1.0])
            angular = -angular[::-1]
        return velocities, angular


def mechanism_from_hinges(arch: BlockArch, hinges, direction: str = "l") -> FourLinkMechanism:
    """The four-link mechanism of ``arch`` with hinges A, B, C, D.

    Equivalent to ``FourLinkMechanism(arch, tuple(hinges), direction)``.

    Parameters
    ----------
    arch : BlockArch
        The arch in the mechanism's frame: the arch itself for ``direction="l"``, the mirrored
        arch (:meth:`~archquake.geometry.BlockArch.mirrored`) for ``direction="r"``.
    hinges : sequence of four Hinge
        A, B, C, D left to right in that frame (strictly increasing joints).
    direction : str
        ``"l"`` or ``"r"``.

    Returns
    -------
    FourLinkMechanism
        The mechanism, in the frame of ``arch``.

    Raises
    ------
    ValueError
        As :class:`FourLinkMechanism` (bad arch, hinges or direction).
    """
    return FourLinkMechanism(arch, tuple(hinges), direction)


def mechanisms(arch: BlockArch, limit=None) -> tuple[FourLinkMechanism, FourLinkMechanism]:
    """Mech-l and Mech-r of ``arch``, with the hinges found by limit analysis.

    Parameters
    ----------
    arch : BlockArch
        The arch (in its own frame).
    limit : pair of limit-analysis results, optional
        ``(la_l, la_r)`` as returned by :func:`archquake.limit_analysis.both_directions`; each has
        ``.hinges`` (four Hinge) and ``.arch`` (the arch analysed: mirrored for Mech-r). Computed
        when not given.

    Returns
    -------
    mech_l, mech_r : FourLinkMechanism
        Mech-l in the frame of ``arch``, Mech-r in the mirrored frame.

    Raises
    ------
    ValueError
        If the collapse mechanism of either direction is not a four-hinge mechanism (a joint
        separates over its whole depth): the four-link model does not apply to that arch.

    References
    ----------
    .. [1] The paper, Sect. 3 (the hinges of the collapse mechanism by limit analysis, Table 1)
       and Sect. 4.1 (Mech-l, Mech-r, Fig. 3).

    Examples
    --------
    For a symmetric arch Mech-r is the mirror image of Mech-l (Table 2 of [1]_):

    >>> from archquake import oppenheim
    >>> mech_l, mech_r = mechanisms(oppenheim())
    >>> mech_l.direction, mech_r.direction
    ('l', 'r')
    >>> abs(mech_r.theta_u - mech_l.theta_u) < 1e-12
    True
    """
    if limit is None:
        from ..limit_analysis import both_directions

        limit = both_directions(arch)
    la_l, la_r = limit
    for la in limit:
        if not getattr(la, "is_four_hinge", True):
            raise ValueError(
                f"the collapse mechanism of direction {la.direction!r} is not a four-hinge "
                "mechanism (a joint separates over its whole depth), so the four-link model "
                "does not apply to this arch"
            )
    return (mechanism_from_hinges(la_l.arch, la_l.hinges, "l"),
            mechanism_from_hinges(la_r.arch, la_r.hinges, "r"))
