r"""The code check of a local collapse mechanism: NTC 2018 §8.7.1 and Circolare 2019 §C8.7.1.

An arch's collapse mechanism is a local mechanism of masonry in the sense of the Italian code:
a chain of rigid blocks turning about hinges, checked by *kinematic analysis* [1]_ [2]_. This
module takes the mechanism of the limit analysis (:func:`archquake.limit_analysis.limit_analysis`)
and the site's elastic spectra (:mod:`archquake.site.spectra`) and makes both of the
Circolare's checks, in each direction of the ground motion.

**Participating mass** (Circolare 2019, eqs. C8.7.1.2-C8.7.1.3). With :math:`P_i` the weight of
block :math:`i` [N/m] (a voussoir, a pier course, a fill column riding on its voussoir) and
:math:`\delta_{x,i}` the horizontal virtual displacement of its load's point in the mechanism
(:func:`archquake.limit_analysis.virtual_displacements`),

.. math::

    M^* = \frac{\left(\sum_i P_i\,\delta_{x,i}\right)^2}{g \sum_i P_i\,\delta_{x,i}^2},
    \qquad e^* = \frac{g M^*}{\sum_i P_i},

summed over the blocks that move (the weights that generate horizontal forces on the chain);
for bare masonry :math:`P_i` is the block's weight and its horizontal load, for a fill the
horizontal load :math:`H_i` weighs the displacements and :math:`P_i = W_i` enters the sum of
weights. A single rigid block has :math:`e^* = 1`.

**Spectral acceleration of activation** (eq. C8.7.1.4):

.. math::

    a_0^* = \frac{\alpha_0 \sum_i P_i}{M^* F_C} = \frac{\alpha_0\, g}{e^* F_C},

with :math:`\alpha_0` the load multiplier of the limit analysis and :math:`F_C` the confidence
factor of the knowledge level (§C8.5.4: LC1 1.35, LC2 1.20, LC3 1.00).

**Linear check** (simplified, §C8.7.1.2.1), at the life-safety limit state SLV, for a mechanism
at ground level:

.. math::

    a_0^* \ge \frac{a_g(P_{V_R})\, S}{q}, \qquad q = 2.0,

with :math:`a_g S` the peak ground acceleration of the site's SLV spectrum (the spectrum's
ordinate at :math:`T = 0`).

**Nonlinear check** (§C8.7.1.2.2). The capacity curve is the load multiplier
:math:`\alpha` of the mechanism in its displaced configuration, by virtual work on the exact
large-displacement kinematics of the four-link mechanism
(:class:`~archquake.fourlink.mechanism.FourLinkMechanism`: :math:`\alpha(\theta) =
-F(\theta)/P(\theta)`, the coefficients of its equation of motion), against the horizontal
displacement :math:`d_k` of a control point. The control point chosen here is the centre of
mass of the moving blocks (the Circolare leaves the point to the analyst); its displacement
maps to the equivalent oscillator's by eq. C8.7.1.7,

.. math::

    d^* = d_k\,\frac{\sum_i P_i\,\delta_{x,i}^2}{\delta_{x,k} \sum_i P_i\,\delta_{x,i}}
        = \frac{d_k}{e^*} \quad (\delta_{x,k} = \textstyle\sum_i P_i \delta_{x,i} / \sum_i P_i),
    \qquad a^* = \frac{\alpha\, g}{e^* F_C}.

The curve falls to zero at :math:`d_0^*`, the critical angle of the paper's Sect. 4.2 (where
gravity stops resisting the motion). The displacement capacity is a fraction of it: at the
near-collapse limit state SLC, :math:`d_u^* = 0.4\, d_0^*`; at SLV, :math:`0.6` of the SLC's,
:math:`0.24\, d_0^*` (:data:`ULTIMATE_FRACTIONS`, the Circolare 2019 edition; the Circolare
2009 had a single ultimate displacement :math:`0.4\, d_0^*` for SLV). The secant period at
:math:`d_s^* = 0.4\, d_u^*` of the limit state,

.. math::

    T_s = 2\pi \sqrt{d_s^* / a_s^*}, \qquad a_s^* = a^*(d_s^*),

enters the site's displacement spectrum of that limit state, and the check at ground level is

.. math::

    d_u^* \ge S_{De}(T_s).

**PGA capacity.** For each check, the site's :math:`a_g` at which it just holds, with the other
parameters of the site's spectrum unchanged (:class:`SiteAction`): the capacity an engineer
compares with the hazard.

The Circolare's choices made here, and why, are listed in the user guide ("Is it safe here?").

References
----------
.. [1] Ministero delle Infrastrutture e dei Trasporti (2018). Aggiornamento delle Norme
   tecniche per le costruzioni (NTC 2018), D.M. 17 gennaio 2018, §8.7.1.
.. [2] Circolare 21 gennaio 2019, n. 7 C.S.LL.PP., Istruzioni per l'applicazione
   dell'Aggiornamento delle NTC 2018, §C8.7.1 (eqs. C8.7.1.1-C8.7.1.9) and §C8.5.4
   (confidence factors).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy.optimize import brentq

from ..constants import GRAVITY
from ..geometry import BlockArch

KNOWLEDGE_LEVELS = {"LC1": 1.35, "LC2": 1.20, "LC3": 1.00}
"""Confidence factor :math:`F_C` of each knowledge level (Circolare 2019 §C8.5.4, Table
C8.5.IV)."""

BEHAVIOUR_FACTOR = 2.0
"""Behaviour factor :math:`q` of the linear check of a local mechanism (Circolare 2019
§C8.7.1.2.1)."""

ULTIMATE_FRACTIONS = {"SLV": 0.24, "SLC": 0.40}
r""":math:`d_u^* / d_0^*` at each limit state (Circolare 2019 §C8.7.1.2.2): 0.4 at SLC, 0.6 of
that at SLV."""

SECANT_FRACTION = 0.4
r""":math:`d_s^* / d_u^*`: the secant period is taken at 0.4 of the limit state's displacement
capacity (Circolare 2019 §C8.7.1.2.2)."""

LIMIT_STATES = ("SLV", "SLC")
"""The limit states of the check: life safety (linear and nonlinear) and near collapse
(nonlinear)."""

_LARGEST_AG = 1.5
"""The largest a_g [g] searched for a PGA capacity (beyond it, the capacity is reported as
more than this)."""


def confidence_factor(knowledge_level: str | None = None, value: float | None = None) -> float:
    """The confidence factor :math:`F_C` of a knowledge level, or a value given directly.

    Parameters
    ----------
    knowledge_level : {"LC1", "LC2", "LC3"}, optional
        Circolare 2019 §C8.5.4 (default LC1, 1.35, when neither is given).
    value : float, optional
        :math:`F_C` itself, >= 1 (not with ``knowledge_level``).

    Raises
    ------
    ValueError
        For both or an unknown level, or a value below 1.

    Examples
    --------
    >>> confidence_factor("LC2"), confidence_factor(value=1.1), confidence_factor()
    (1.2, 1.1, 1.35)
    """
    if knowledge_level is not None and value is not None:
        raise ValueError("give either knowledge_level or the confidence factor, not both")
    if value is not None:
        value = float(value)
        if not math.isfinite(value) or not 1.0 <= value <= 2.0:
            raise ValueError(f"confidence_factor must be in [1, 2], got {value}")
        return value
    level = "LC1" if knowledge_level is None else str(knowledge_level).upper()
    if level not in KNOWLEDGE_LEVELS:
        raise ValueError(f"knowledge_level must be one of {', '.join(KNOWLEDGE_LEVELS)}, "
                         f"got {knowledge_level!r}")
    return KNOWLEDGE_LEVELS[level]


# ------------------------------------------------------------------------------ participation
@dataclass(frozen=True)
class Participation:
    r"""The equivalent oscillator of a mechanism (Circolare 2019 eqs. C8.7.1.2-C8.7.1.4).

    Attributes
    ----------
    direction : str
        ``"l"`` (toward +x) or ``"r"``.
    alpha0 : float
        Load multiplier of activation [-].
    participating_mass : float
        :math:`M^*` [kg/m].
    mass_fraction : float
        :math:`e^*` [-], in (0, 1].
    moving_weight : float
        :math:`\sum_i P_i` over the moving blocks [N/m].
    confidence_factor : float
        :math:`F_C` [-].
    """

    direction: str
    alpha0: float
    participating_mass: float
    mass_fraction: float
    moving_weight: float
    confidence_factor: float

    @property
    def spectral_acceleration(self) -> float:
        r""":math:`a_0^* = \alpha_0 g / (e^* F_C)` [m/s^2]."""
        return self.alpha0 * GRAVITY / (self.mass_fraction * self.confidence_factor)

    @property
    def spectral_acceleration_g(self) -> float:
        r""":math:`a_0^*` [g]."""
        return self.spectral_acceleration / GRAVITY

    def to_dict(self) -> dict[str, Any]:
        """Plain values for JSON, units in the keys."""
        return {"direction": self.direction, "alpha0": self.alpha0,
                "participating_mass_kg_per_m": self.participating_mass,
                "mass_fraction": self.mass_fraction,
                "moving_weight_N_per_m": self.moving_weight,
                "confidence_factor": self.confidence_factor,
                "a0_star_m_per_s2": self.spectral_acceleration,
                "a0_star_g": self.spectral_acceleration_g}


def participation_of(alpha0: float, weights, horizontal, displacements, direction: str,
                     confidence_factor: float = 1.0) -> Participation:
    r""":math:`M^*`, :math:`e^*` from the blocks' weights, horizontal loads and virtual
    displacements (Circolare 2019 eqs. C8.7.1.2-C8.7.1.3).

    Parameters
    ----------
    alpha0 : float
        Load multiplier of activation [-], > 0.
    weights : array of float, shape (n,)
        :math:`P_i` [N/m], >= 0.
    horizontal : array of float, shape (n,)
        The horizontal load per unit multiplier of each block [N/m] (equal to ``weights`` for
        bare masonry).
    displacements : array of float, shape (n,)
        :math:`\delta_{x,i}` [any length unit]; 0 for a block that does not move.
    direction : str
        ``"l"`` or ``"r"``, carried along.
    confidence_factor : float
        :math:`F_C`.

    Returns
    -------
    Participation

    Examples
    --------
    One block: :math:`e^* = 1` whatever its displacement.

    >>> p = participation_of(0.2, [1000.0], [1000.0], [0.3], "l")
    >>> round(p.mass_fraction, 12), round(p.participating_mass * 9.81, 6)
    (1.0, 1000.0)
    """
    weights, horizontal, dx = (np.asarray(v, dtype=float) for v in
                               (weights, horizontal, displacements))
    if not (weights.shape == horizontal.shape == dx.shape) or weights.ndim != 1:
        raise ValueError("weights, horizontal and displacements must be arrays of one length")
    if not (np.all(np.isfinite(weights)) and np.all(weights >= 0.0)):
        raise ValueError("weights must be finite and >= 0")
    if not math.isfinite(alpha0) or alpha0 <= 0.0:
        raise ValueError(f"alpha0 must be > 0, got {alpha0}")
    moving = dx != 0.0
    if not np.any(moving & (horizontal > 0.0)):
        raise ValueError("no block with a horizontal load moves in the mechanism")
    first = float(np.sum(horizontal * dx))
    second = float(np.sum(horizontal * dx ** 2))
    mass = first ** 2 / (GRAVITY * second)
    weight = float(np.sum(weights[moving]))
    return Participation(direction, float(alpha0), mass, GRAVITY * mass / weight, weight,
                         float(confidence_factor))


def participation(result, confidence_factor: float = 1.0) -> Participation:
    r"""The equivalent oscillator of a collapse mechanism of the limit analysis.

    Parameters
    ----------
    result : LimitAnalysis
        :func:`archquake.limit_analysis.limit_analysis` of the structure in one direction.
    confidence_factor : float
        :math:`F_C` (:func:`confidence_factor`).

    Returns
    -------
    Participation
        :math:`\alpha_0` is the limit analysis's load multiplier; the weights and horizontal
        loads are the structure's (:class:`~archquake.geometry.BlockLoads`), the
        displacements :func:`~archquake.limit_analysis.virtual_displacements`.
    """
    from ..limit_analysis import virtual_displacements

    if hasattr(result, "contacts"):  # the mechanism of a block assembly
        return _assembly_participation(result, confidence_factor)
    loads = result.arch.loads
    return participation_of(result.load_multiplier, loads.vertical, loads.horizontal,
                            virtual_displacements(result), result.direction,
                            confidence_factor)


def _assembly_participation(result, confidence_factor: float) -> Participation:
    r"""The equivalent oscillator of the mechanism of an
    :class:`~archquake.limit_analysis.AssemblyLimit` (several spans, rings, a drawing): the
    horizontal virtual displacement of block :math:`j`'s load is that of its velocity at the
    height :math:`b_j` of its horizontal load, :math:`u_j - \omega_j (b_j - y_0)` (a rigid
    body's horizontal velocity does not depend on the abscissa); the blocks that do not move
    (:func:`archquake.geometry.bridge.moving_blocks`) have none."""
    from ..geometry.bridge import moving_blocks

    c = result.contacts
    points = np.column_stack((c.vertical_x, c.horizontal_y))
    dx = np.zeros(c.n_blocks)
    for j in moving_blocks(result):
        # a moving block whose load point moves only vertically still counts in the weights
        dx[j] = float(result.velocity_at(j, points[j:j + 1])[0, 0]) or 1e-300
    return participation_of(result.load_multiplier, c.vertical, c.horizontal, dx,
                            result.direction, confidence_factor)


# ------------------------------------------------------------------------------ capacity curve
@dataclass(frozen=True, eq=False)
class CapacityCurve:
    r"""The capacity curve of a mechanism (Circolare 2019 §C8.7.1.2.2).

    Attributes
    ----------
    direction : str
        ``"l"`` or ``"r"``.
    rotation : ndarray
        :math:`\varphi = \theta_u - \theta` of the first link [rad], from 0 to the critical
        angle (or the linkage's kinematic limit).
    control_displacement : ndarray
        :math:`d_k`: horizontal displacement of the control point, the centre of mass of the
        moving blocks [m].
    multiplier : ndarray
        :math:`\alpha` in the displaced configuration [-].
    participation : Participation
        :math:`M^*, e^*, F_C` of the undisplaced mechanism.
    """

    direction: str
    rotation: np.ndarray
    control_displacement: np.ndarray
    multiplier: np.ndarray
    participation: Participation

    @property
    def spectral_displacement(self) -> np.ndarray:
        r""":math:`d^* = d_k / e^*` [m] (eq. C8.7.1.7 with the centre of mass as control
        point)."""
        return self.control_displacement / self.participation.mass_fraction

    @property
    def spectral_acceleration(self) -> np.ndarray:
        r""":math:`a^* = \alpha g / (e^* F_C)` [m/s^2]."""
        p = self.participation
        return self.multiplier * GRAVITY / (p.mass_fraction * p.confidence_factor)

    @property
    def d0(self) -> float:
        r""":math:`d_0^*` [m]: where the curve reaches zero (the critical angle); the end of the
        curve when the linkage locks first."""
        return float(self.spectral_displacement[-1])

    def acceleration_at(self, displacement) -> np.ndarray:
        r""":math:`a^*(d^*)` [m/s^2], linear between the curve's points."""
        return np.interp(displacement, self.spectral_displacement, self.spectral_acceleration)

    def ultimate_displacement(self, limit_state: str) -> float:
        r""":math:`d_u^*` of a limit state [m] (:data:`ULTIMATE_FRACTIONS`)."""
        return ULTIMATE_FRACTIONS[_limit_state(limit_state)] * self.d0

    def secant(self, limit_state: str) -> tuple[float, float, float]:
        r""":math:`d_s^*` [m], :math:`a_s^*` [m/s^2] and :math:`T_s` [s] of a limit state."""
        d_s = SECANT_FRACTION * self.ultimate_displacement(limit_state)
        a_s = float(self.acceleration_at(d_s))
        return d_s, a_s, 2.0 * math.pi * math.sqrt(d_s / a_s)

    def to_dict(self) -> dict[str, Any]:
        """Plain values for JSON, units in the keys."""
        return {"direction": self.direction, "rotation_rad": self.rotation.tolist(),
                "control_displacement_m": self.control_displacement.tolist(),
                "multiplier": self.multiplier.tolist(),
                "spectral_displacement_m": self.spectral_displacement.tolist(),
                "spectral_acceleration_m_per_s2": self.spectral_acceleration.tolist(),
                "d0_star_m": self.d0}


def _limit_state(limit_state: str) -> str:
    state = str(limit_state).upper()
    if state not in LIMIT_STATES:
        raise ValueError(f"limit_state must be one of {', '.join(LIMIT_STATES)}, "
                         f"got {limit_state!r}")
    return state


_STEP = 1e-6
"""Step of the central differences of the blocks' positions [rad]."""

_SCAN = 2001
"""Points of the scan for the first zero of the capacity curve."""


def rigid_capacity_curve(masses, positions: Callable[[np.ndarray], np.ndarray], limit: float,
                         direction: str = "l", confidence_factor: float = 1.0,
                         points: int = 201) -> CapacityCurve:
    r"""The capacity curve of any one-degree-of-freedom mechanism of rigid blocks, by virtual
    work in the displaced configuration.

    With :math:`\mathbf g_i(\varphi)` the centroid of block :math:`i` when the mechanism has
    turned by :math:`\varphi`, the horizontal load multiplier in equilibrium there is

    .. math::

        \alpha(\varphi) = \frac{\sum_i m_i\, dy_i/d\varphi}{\sum_i m_i\, dx_i/d\varphi}

    (the work of the horizontal loads :math:`\alpha m_i g` balances the rise of the weights;
    central differences of the positions), and the curve ends where :math:`\alpha` falls to
    zero for the first time (scanned, then Brent's method), or at ``limit`` if it does not.

    Parameters
    ----------
    masses : array of float, shape (n,)
        Mass of every block [kg/m] (its weight is the vertical load and its inertia the
        horizontal one, at its centroid).
    positions : callable
        ``positions(phi)`` for an array ``phi`` of shape (p,) [rad]: the centroids, shape
        (p, n, 2) [m], moving toward +x as ``phi`` grows.
    limit : float
        The largest rotation of the mechanism [rad] (where it locks or stops closing).
    direction : str
        Carried along.
    confidence_factor : float
        :math:`F_C`.
    points : int
        Points of the curve, >= 11.

    Returns
    -------
    CapacityCurve
        The control point is the centre of mass of the moving blocks.
    """
    if int(points) != points or points < 11:
        raise ValueError(f"points must be an integer >= 11, got {points}")
    masses = np.asarray(masses, dtype=float)

    def rates(phi):
        phi = np.atleast_1d(np.asarray(phi, dtype=float))
        return (positions(phi + _STEP) - positions(phi - _STEP)) / (2.0 * _STEP)

    def multiplier(phi):
        v = rates(phi)
        return (v[..., 1] @ masses) / (v[..., 0] @ masses)

    velocity = rates(0.0)[0]
    alpha0 = float(multiplier(0.0)[0])
    if not alpha0 > 0.0:
        raise ValueError("gravity does not resist the mechanism at rest (alpha0 <= 0)")
    end = float(limit)
    scan = np.linspace(0.0, end, _SCAN)
    below = np.flatnonzero(multiplier(scan) <= 0.0)
    if below.size:  # the first zero: gravity stops resisting (the critical angle)
        i = int(below[0])
        end = float(brentq(lambda p: float(multiplier(p)[0]), scan[i - 1], scan[i],
                           xtol=1e-13))
    phi = np.linspace(0.0, end, int(points))
    alpha = multiplier(phi)
    alpha[-1] = max(alpha[-1], 0.0) if end < limit else alpha[-1]
    dx = velocity[:, 0]
    moving = np.abs(velocity).max(axis=1) > 1e-9 * np.abs(velocity).max()
    dx = np.where(moving, dx, 0.0)
    part = participation_of(alpha0, masses * GRAVITY, masses * GRAVITY,
                            np.where(moving & (dx == 0.0), 1e-300, dx), direction,
                            confidence_factor)
    x = positions(phi)[..., 0]
    centre = (x[:, moving] @ masses[moving]) / masses[moving].sum()
    return CapacityCurve(direction, phi, centre - centre[0], alpha, part)


def _rotation(points: np.ndarray, pivot: np.ndarray, angle: np.ndarray) -> np.ndarray:
    """``points`` (n, 2) turned by ``angle`` (p,) about ``pivot`` (p, 2) or (2,): (p, n, 2)."""
    c, s = np.cos(angle)[:, None], np.sin(angle)[:, None]
    rel = points[None, :, :] - np.asarray(pivot, dtype=float).reshape(-1, 1, 2)
    return np.stack((c * rel[..., 0] - s * rel[..., 1], s * rel[..., 0] + c * rel[..., 1]),
                    axis=-1)


def capacity_curve(mechanism, confidence_factor: float = 1.0, points: int = 201
                   ) -> CapacityCurve:
    r"""The capacity curve of a four-link mechanism, on its exact large-displacement
    kinematics.

    Every voussoir (pier course, fill column riding on it) of a link turns rigidly with it:
    link AB about A by :math:`\theta - \theta_u`, link BC with :math:`B(\theta)` by
    :math:`\theta_{bc} - \theta_{bc,u}`, link CD about D by :math:`\theta_{cd} -
    \theta_{cd,u}` (the four-bar closure,
    :meth:`~archquake.fourlink.mechanism.FourLinkMechanism.closure`), and
    :func:`rigid_capacity_curve` takes it from there, up to the linkage's kinematic limit.

    Parameters
    ----------
    mechanism : FourLinkMechanism
        Mech-l or Mech-r (:func:`archquake.fourlink.mechanism.mechanisms`), in its own frame.
    confidence_factor : float
        :math:`F_C`.
    points : int
        Points of the curve, >= 11.

    Returns
    -------
    CapacityCurve
    """
    mech = mechanism
    arch = mech.arch
    ja, jb, jc, jd = (h.joint for h in mech.hinges)
    a, b_u, _, d = mech.hinge_points
    g = arch.centroids

    def positions(phi):
        theta = mech.theta_u - phi
        theta_bc, theta_cd = mech.closure(theta)
        b, _ = mech.points(theta)
        out = np.broadcast_to(g, (phi.size, *g.shape)).copy()
        out[:, ja:jb] = a + _rotation(g[ja:jb], a, theta - mech.theta_u)
        out[:, jb:jc] = b[:, None, :] + _rotation(g[jb:jc], b_u,
                                                   theta_bc - mech.theta_bc_u)
        out[:, jc:jd] = d + _rotation(g[jc:jd], d, theta_cd - mech.theta_cd_u)
        return out

    return rigid_capacity_curve(arch.masses, positions, mech.theta_u - mech.theta_limit,
                                mech.direction, confidence_factor, points)


# ------------------------------------------------------------------------------ the checks
@dataclass(frozen=True)
class SiteAction:
    """The seismic action of one limit state at the site.

    Parameters
    ----------
    limit_state : {"SLV", "SLC"}
        The limit state.
    ag : float
        The site's :math:`a_g` for the limit state's return period [g] (the PGA of a user's
        spectrum).
    spectrum_at : callable
        ``spectrum_at(ag)``: the site's elastic spectrum
        (:class:`~archquake.site.spectra.ElasticSpectrum`: ``acceleration(T)`` [g],
        ``displacement(T)`` [m], ``pga`` [g]) at any :math:`a_g`, the other parameters of
        the site unchanged; ``spectrum_at(ag)`` is the action itself. Used for the PGA
        capacity.
    """

    limit_state: str
    ag: float
    spectrum_at: Callable[[float], Any]
    spectrum: Any = field(init=False, repr=False, compare=False)

    def __post_init__(self):
        object.__setattr__(self, "limit_state", _limit_state(self.limit_state))
        if not math.isfinite(self.ag) or self.ag <= 0.0:
            raise ValueError(f"ag must be > 0 [g], got {self.ag}")
        object.__setattr__(self, "spectrum", self.spectrum_at(self.ag))

    @classmethod
    def of(cls, limit_state: str, spectrum) -> SiteAction:
        """The action of a limit state given by its spectrum
        (:class:`~archquake.site.spectra.ElasticSpectrum`).

        The same site at another :math:`a_g` keeps the other inputs: for NTC 2018, F0, Tc*,
        the soil, topography and damping (so S_S and T_D follow :math:`a_g`); for EN 1998-1 the
        spectrum type, soil, importance and damping; a user's table is scaled in proportion.
        """
        from .spectra import ec8_spectrum, ntc2018_spectrum

        details = dict(spectrum.details)
        if spectrum.code == "NTC 2018":
            def spectrum_at(ag):
                return ntc2018_spectrum(ag, spectrum.f0, details["tc_star"], spectrum.soil,
                                        details["topography"], spectrum.damping,
                                        topography_ratio=details.get("topography_ratio"))
            ag = spectrum.ag
        elif spectrum.code == "EN 1998-1:2004":
            importance = details["importance"]

            def spectrum_at(ag):
                return ec8_spectrum(ag / importance, details["spectrum_type"], spectrum.soil,
                                    importance, spectrum.damping)
            ag = spectrum.ag
        else:
            ag = spectrum.pga

            def spectrum_at(value):
                return _Scaled(spectrum, value / ag)
        return cls(limit_state, ag, spectrum_at)

    def capacity_ag(self, demand: Callable[[Any], float], capacity: float) -> float | None:
        """The :math:`a_g` [g] at which ``demand(spectrum_at(ag)) == capacity`` (demand
        increasing with :math:`a_g`); None when the check holds up to
        :data:`_LARGEST_AG`."""
        def gap(ag: float) -> float:
            return demand(self.spectrum_at(ag)) - capacity

        low = 1e-4
        if gap(low) >= 0.0:
            return 0.0
        if gap(_LARGEST_AG) <= 0.0:
            return None
        return float(brentq(gap, low, _LARGEST_AG, xtol=1e-6))


@dataclass(frozen=True)
class Elevation:
    r"""Where a mechanism stands in a building: the floor demand of Circolare 2009 §C8A.4.

    A mechanism at height :math:`Z` of a building of height :math:`H`, first-mode period
    :math:`T_1` and :math:`N` storeys is shaken by the floor's motion, amplified from the
    ground's. The Circolare 2009 (§C8A.4.9, linear; §C8A.4.10, nonlinear) takes the first
    mode's floor demand, with :math:`\psi(Z) = Z/H` and :math:`\gamma = 3N/(2N+1)`:

    .. math::

        a_0^* \ge \frac{S_e(T_1)\,\psi(Z)\,\gamma}{q}, \qquad
        d_u^* \ge S_{De}(T_1)\,\psi(Z)\,\gamma\,
        \frac{(T_s/T_1)^2}{\sqrt{(1 - T_s/T_1)^2 + 0.02\,T_s/T_1}} \quad (T_s < 1.5\,T_1),

        d_u^* \ge S_{De}(T_s) \quad (T_s \ge 1.5\,T_1),

    each beside the check at ground level (the larger demand governs). The Circolare 2019
    replaced these by the floor spectra of §C7.2.3, not implemented here: this is the older
    edition's demand, stated as such in every output.

    Parameters
    ----------
    height : float
        :math:`Z`, the height of the mechanism's base above the foundation [m], > 0.
    building_height : float
        :math:`H` [m], >= ``height``.
    building_period : float
        :math:`T_1` [s], > 0.
    storeys : int
        :math:`N`, >= 1.
    """

    height: float
    building_height: float
    building_period: float
    storeys: int

    def __post_init__(self):
        for name in ("height", "building_height", "building_period"):
            value = getattr(self, name)
            if not isinstance(value, (int, float)) or not math.isfinite(value) or value <= 0:
                raise ValueError(f"{name} must be > 0, got {value!r}")
        if self.height > self.building_height:
            raise ValueError(f"height must be <= building_height = {self.building_height:g} m "
                             f"(the mechanism stands in the building), got {self.height:g}")
        if int(self.storeys) != self.storeys or self.storeys < 1:
            raise ValueError(f"storeys must be an integer >= 1, got {self.storeys!r}")

    @property
    def amplification(self) -> float:
        r""":math:`\psi(Z)\,\gamma` [-]."""
        return self.height / self.building_height * 3 * self.storeys / (2 * self.storeys + 1)

    def linear_demand(self, spectrum, behaviour_factor: float) -> float:
        """The floor's acceleration demand of the linear check [g]."""
        return (float(spectrum.acceleration(self.building_period)) * self.amplification
                / behaviour_factor)

    def displacement_demand(self, spectrum, secant_period: float) -> float:
        """The floor's displacement demand of the nonlinear check [m]."""
        ratio = secant_period / self.building_period
        if ratio >= 1.5:
            return float(spectrum.displacement(secant_period))
        return (float(spectrum.displacement(self.building_period)) * self.amplification
                * ratio ** 2 / math.sqrt((1.0 - ratio) ** 2 + 0.02 * ratio))

    def to_dict(self) -> dict[str, Any]:
        return {"height_m": self.height, "building_height_m": self.building_height,
                "building_period_s": self.building_period, "storeys": self.storeys,
                "psi_gamma": self.amplification,
                "demand": "Circolare 2009 C8A.4.9-10 (first-mode floor demand)"}


@dataclass(frozen=True)
class _Scaled:
    """A user's spectrum scaled by a factor (its PGA capacity: the factor times its PGA)."""

    spectrum: Any
    factor: float

    @property
    def pga(self) -> float:
        return self.factor * self.spectrum.pga

    def acceleration(self, period):
        return self.factor * self.spectrum.acceleration(period)

    def displacement(self, period):
        return self.factor * self.spectrum.displacement(period)

    def to_dict(self) -> dict[str, Any]:
        return {**self.spectrum.to_dict(), "scaled_by": self.factor}


class _Verdict:
    """What a check concludes from its ratio of capacity to demand."""

    @property
    def passes(self) -> bool:
        """True when the capacity covers the demand (the ratio is at least 1)."""
        return self.ratio >= 1.0


@dataclass(frozen=True)
class LinearCheck(_Verdict):
    r"""The linear check at SLV of one direction: :math:`a_0^* \ge a_g S / q`.

    Attributes
    ----------
    capacity, demand : float
        :math:`a_0^*` and :math:`a_g S / q` [g].
    pga_capacity : float or None
        The site :math:`a_g` at which the check just holds [g] (None: beyond 1.5 g).
    """

    limit_state: str
    direction: str
    capacity: float
    demand: float
    behaviour_factor: float
    pga_capacity: float | None

    @property
    def ratio(self) -> float:
        """Capacity / demand [-]."""
        return self.capacity / self.demand


    def to_dict(self) -> dict[str, Any]:
        return {"limit_state": self.limit_state, "direction": self.direction,
                "a0_star_g": self.capacity, "demand_g": self.demand,
                "behaviour_factor": self.behaviour_factor, "ratio": self.ratio,
                "passes": self.passes, "pga_capacity_ag_g": self.pga_capacity}


@dataclass(frozen=True)
class NonlinearCheck(_Verdict):
    r"""The nonlinear check of one limit state and direction: :math:`d_u^* \ge S_{De}(T_s)`.

    Attributes
    ----------
    ultimate_displacement : float
        :math:`d_u^*` [m].
    secant_displacement, secant_acceleration, secant_period : float
        :math:`d_s^*` [m], :math:`a_s^*` [m/s^2], :math:`T_s` [s].
    demand : float
        :math:`S_{De}(T_s)` [m].
    pga_capacity : float or None
        The site :math:`a_g` at which the check just holds [g] (None: beyond 1.5 g).
    """

    limit_state: str
    direction: str
    ultimate_displacement: float
    secant_displacement: float
    secant_acceleration: float
    secant_period: float
    demand: float
    pga_capacity: float | None

    @property
    def ratio(self) -> float:
        """Capacity / demand [-]."""
        return self.ultimate_displacement / self.demand


    def to_dict(self) -> dict[str, Any]:
        return {"limit_state": self.limit_state, "direction": self.direction,
                "du_star_m": self.ultimate_displacement, "ds_star_m": self.secant_displacement,
                "as_star_m_per_s2": self.secant_acceleration,
                "Ts_s": self.secant_period, "demand_SDe_m": self.demand, "ratio": self.ratio,
                "passes": self.passes, "pga_capacity_ag_g": self.pga_capacity}


@dataclass(frozen=True, eq=False)
class LocalMechanismCheck:
    """The code check of an arch's collapse mechanisms in both directions.

    Attributes
    ----------
    participations : tuple of Participation
        Mech-l, Mech-r (from the limit analysis).
    curves : tuple of CapacityCurve
        Their capacity curves (empty when the nonlinear check does not apply, see ``notes``).
    linear : tuple of LinearCheck
        SLV, per direction.
    nonlinear : tuple of NonlinearCheck
        Per limit state and direction.
    actions : dict
        The site's action of each limit state (:class:`SiteAction`).
    notes : tuple of str
        What was not checked, and why.
    """

    participations: tuple[Participation, ...]
    curves: tuple[CapacityCurve, ...]
    linear: tuple[LinearCheck, ...]
    nonlinear: tuple[NonlinearCheck, ...]
    actions: Mapping[str, SiteAction]
    notes: tuple[str, ...] = ()
    elevation: Elevation | None = None

    def routes(self, limit_state: str) -> dict[str, tuple]:
        """The checks of a limit state by route: ``{"linear": ..., "nonlinear": ...}``, each
        the checks of both directions (a route missing when not made)."""
        state = _limit_state(limit_state)
        out = {}
        for name, checks in (("linear", self.linear), ("nonlinear", self.nonlinear)):
            mine = tuple(c for c in checks if c.limit_state == state)
            if mine:
                out[name] = mine
        return out

    def holds(self, limit_state: str) -> bool | None:
        """The verdict of a limit state: it holds when one of the Circolare's routes (the
        linear check, the nonlinear check) holds in both directions, each route being a
        complete check by itself (§C8.7.1.2); None if the limit state was not checked."""
        routes = self.routes(limit_state)
        if not routes:
            return None
        return any(all(c.passes for c in checks) for checks in routes.values())

    @property
    def passes(self) -> bool | None:
        """True when every limit state checked holds; None if none was checked."""
        verdicts = [v for v in (self.holds(s) for s in LIMIT_STATES) if v is not None]
        return all(verdicts) if verdicts else None

    def pga_capacity(self, limit_state: str) -> float | None:
        """The site :math:`a_g` [g] up to which the limit state holds: the larger over the
        routes of the least over the directions; None when it holds beyond 1.5 g (or was not
        checked)."""
        best = None
        for checks in self.routes(limit_state).values():
            values = [math.inf if c.pga_capacity is None else c.pga_capacity for c in checks]
            best = min(values) if best is None else max(best, min(values))
        return None if best is None or math.isinf(best) else best

    def to_dict(self) -> dict[str, Any]:
        """Plain values for JSON."""
        return {
            "code": "NTC 2018 §8.7.1, Circolare 2019 §C8.7.1",
            "participation": [p.to_dict() for p in self.participations],
            "linear": [c.to_dict() for c in self.linear],
            "nonlinear": [c.to_dict() for c in self.nonlinear],
            "capacity_curves": [c.to_dict() for c in self.curves],
            "verdict": {s: self.holds(s) for s in LIMIT_STATES},
            "passes": self.passes,
            "pga_capacity_g": {s: self.pga_capacity(s) for s in LIMIT_STATES},
            "actions": {s: {"ag_g": a.ag, "spectrum": _spectrum_dict(a.spectrum)}
                        for s, a in self.actions.items()},
            "elevation": None if self.elevation is None else self.elevation.to_dict(),
            "notes": list(self.notes),
        }


def _spectrum_dict(spectrum) -> Any:
    to_dict = getattr(spectrum, "to_dict", None)
    return to_dict() if callable(to_dict) else str(spectrum)


def assembly_directions(structure, friction=None) -> tuple:
    """The governing collapse of a block assembly toward +x and -x: the non-associative law
    where an interface can slide (the physical one), else Heyman's
    (:func:`archquake.limit_analysis.assembly_limits`).

    Parameters
    ----------
    structure : BlockAssembly
    friction : None, float or dict, optional
        Coulomb coefficient of the interfaces over their own [-]
        (:meth:`~archquake.limit_analysis.assembly.Contacts.with_friction`).

    Returns
    -------
    (AssemblyLimit, AssemblyLimit)
    """
    from ..limit_analysis import assembly_limits, governing_law

    return tuple(governing_law(laws) for laws in
                 assembly_limits(structure, friction=friction).values())


def check_local_mechanism(structure: BlockArch, actions, *, confidence_factor: float = 1.0,
                          behaviour_factor: float = BEHAVIOUR_FACTOR, limit=None,
                          points: int = 201, elevation: Elevation | None = None
                          ) -> LocalMechanismCheck:
    r"""The code check of a structure's collapse mechanisms at a site (Circolare 2019
    §C8.7.1).

    Parameters
    ----------
    structure : BlockArch or BlockAssembly
        Any arch or structure of :mod:`archquake.geometry`; or a block assembly (several
        spans, rings, a drawing), whose mechanism has the linear check only (its note says
        why).
    actions : SiteAction or iterable of SiteAction
        The site's action at SLV and/or SLC; the linear check needs SLV.
    confidence_factor : float
        :math:`F_C` (:func:`confidence_factor`).
    behaviour_factor : float
        :math:`q` of the linear check (default 2.0).
    limit : pair of LimitAnalysis, optional
        :func:`archquake.limit_analysis.both_directions` of the structure, if at hand (of an
        assembly: a pair of AssemblyLimit, default :func:`assembly_directions`).
    points : int
        Points of each capacity curve.
    elevation : Elevation, optional
        Where the structure stands in a building (default: on the ground); the larger of the
        ground's and the floor's demand governs.

    Returns
    -------
    LocalMechanismCheck

    Raises
    ------
    CannotStandError
        If the structure does not stand under its own weight.
    ValueError
        For a bad action or factor.
    """
    from ..fourlink.mechanism import mechanisms
    from ..limit_analysis import both_directions

    if isinstance(actions, SiteAction):
        actions = (actions,)
    actions = {a.limit_state: a for a in actions}
    if not actions:
        raise ValueError("give the site's action of at least one limit state (SLV or SLC)")
    behaviour_factor = float(behaviour_factor)
    if not math.isfinite(behaviour_factor) or behaviour_factor < 1.0:
        raise ValueError(f"behaviour_factor must be >= 1, got {behaviour_factor}")
    assembly = hasattr(structure, "interfaces")
    if limit is None:
        limit = assembly_directions(structure) if assembly else both_directions(structure)
    parts = tuple(participation(r, confidence_factor) for r in limit)
    notes = []
    linear = []
    if "SLV" in actions:
        action = actions["SLV"]
        for p in parts:
            capacity = p.spectral_acceleration_g
            def demand(s):
                ground = s.pga / behaviour_factor
                if elevation is None:
                    return ground
                return max(ground, elevation.linear_demand(s, behaviour_factor))

            linear.append(LinearCheck("SLV", p.direction, capacity, demand(action.spectrum),
                                      behaviour_factor, action.capacity_ag(demand, capacity)))
    else:
        notes.append("the linear check (SLV only) was not made: no SLV action given")
    curves: tuple[CapacityCurve, ...] = ()
    nonlinear = []
    try:
        if assembly:
            raise ValueError("the collapse mechanism of a block assembly is not traced in its "
                             "displaced configuration (its capacity curve needs the "
                             "kinematics of a four-link chain); the linear check stands by "
                             "itself, and the rigid-block model is the dynamic check")
        mechs = mechanisms(structure, limit)
    except ValueError as exc:  # a two-block mechanism, or fill that is no mass
        notes.append(f"the nonlinear check was not made: {exc}")
    else:
        curves = tuple(capacity_curve(m, confidence_factor, points) for m in mechs)
        for curve, part in zip(curves, parts, strict=True):
            if abs(curve.participation.alpha0 - part.alpha0) > 1e-6 * part.alpha0:
                notes.append(
                    f"the nonlinear check was not made: the capacity curve of the blocks' "
                    f"weights and inertia starts at alpha = {curve.participation.alpha0:.4f}, "
                    f"not at the limit analysis's alpha0 = {part.alpha0:.4f} (the fill's "
                    f"passive reaction is in the limit analysis, not in the curve)")
                curves = ()
                break
        for state, action in (actions.items() if curves else ()):
            for curve in curves:
                d_u = curve.ultimate_displacement(state)
                d_s, a_s, t_s = curve.secant(state)

                def demand(s, t=t_s):
                    ground = float(s.displacement(t))
                    if elevation is None:
                        return ground
                    return max(ground, elevation.displacement_demand(s, t))

                nonlinear.append(NonlinearCheck(
                    state, curve.direction, d_u, d_s, a_s, t_s, demand(action.spectrum),
                    action.capacity_ag(demand, d_u)))
    return LocalMechanismCheck(parts, curves, tuple(linear), tuple(nonlinear), actions,
                               tuple(notes), elevation)
