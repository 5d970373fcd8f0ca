"""Limit analysis, results: what an analysis returns (:class:`LimitAnalysis` with its
:class:`ThrustLine`, :class:`LimitSample` of a sample of arches) and the constants every stage
shares (:mod:`archquake.limit_analysis` states the theory)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..defaults import DEFAULT_LIMIT_METHOD
from ..geometry import BlockArch, Hinge

DIRECTIONS = ("l", "r")
"""Directions of the horizontal forces: ``"l"`` = Mech-l (forces toward +x on the arch as
given), ``"r"`` = Mech-r (the same forces on the mirrored arch)."""


AGREEMENT_TOLERANCE = 1e-9
"""Largest difference between the static and the kinematic load multipliers of one arch."""


@dataclass(frozen=True, eq=False)
class ThrustLine:
    """The line of thrust: pressure point and joint force at every joint ``j = 0 .. n``.

    Attributes
    ----------
    offsets : array of float, shape (n+1,)
        Distance of the pressure point on every joint from the joint's intrados end [m], in
        ``[0, length of the joint]``; nan at a joint that transmits no normal force (a
        separating joint, whose force, if any, lies along the joint).
    radii : array of float, shape (n+1,), or None
        For a circular :class:`~archquake.geometry.CircularArch` (radial joints): the radius of
        every pressure point [m] (nan where ``offsets`` is); None for other arches.
    points : array of float, shape (n+1, 2)
        Pressure points (x, y) [m].
    forces : array of float, shape (n+1, 2)
        Force (F_x, F_y) that the part of the arch left of the joint exerts on the part right of
        it [N/m] (for joint 0: the left support on voussoir 0; for joint n: voussoir n-1 on the
        right support).
    loads : array of float, shape (n, 2), or None
        Resultant of the loads applied to every block at collapse [N/m]: its weight, its
        horizontal load and its passive reaction (:class:`~archquake.geometry.BlockLoads`).
    load_points : array of float, shape (n, 2), or None
        A point of the line of action of every block's resultant load [m].
    """

    offsets: np.ndarray
    radii: np.ndarray | None
    points: np.ndarray
    forces: np.ndarray
    loads: np.ndarray | None = None
    load_points: np.ndarray | None = None

    def funicular(self, arch: BlockArch, load_multiplier: float) -> np.ndarray:
        """Vertices of the funicular polygon (line of action of the resultant) [m], (2n+1, 2).

        Inside voussoir ``i`` the resultant acts along ``F_i`` from the pressure point ``p_i``
        until it meets the line of action of the voussoir's load (:attr:`loads` through
        :attr:`load_points`; without them ``m_i g (k, -1)`` through its centroid), and along
        ``F_{i+1}`` from there to ``p_{i+1}``. The vertices are ``p_0, q_0, p_1, q_1, ...,
        p_n``.
        """
        p, f = self.points[:-1], self.forces[:-1]
        if self.loads is None:
            c = arch.centroids
            load = np.broadcast_to(np.array([load_multiplier, -1.0]), f.shape)
        else:
            c, load = self.load_points, self.loads
        # p + s f = c + u load  ->  s (f x load) = (c - p) x load
        denom = f[:, 0] * load[:, 1] - f[:, 1] * load[:, 0]
        d = c - p
        s = (d[:, 0] * load[:, 1] - d[:, 1] * load[:, 0]) / np.where(denom == 0.0, np.nan, denom)
        q = p + s[:, None] * f
        q = np.where(np.isfinite(q), q, 0.5 * (p + self.points[1:]))
        out = np.empty((2 * arch.n_voussoirs + 1, 2))
        out[0::2] = self.points
        out[1::2] = q
        return out


@dataclass(frozen=True, eq=False)
class LimitAnalysis:
    """Result of the limit analysis of one arch in one direction.

    Attributes
    ----------
    load_multiplier : float
        Horizontal load multiplier k at collapse [-] (k_l for ``"l"``, k_r for ``"r"``).
    hinges : tuple of Hinge
        The hinges, left to right, in the frame of ``arch``: the four hinges A, B, C, D of the
        collapse mechanism (the paper's case), or two hinges when ``separation`` is set.
    thrust_line : ThrustLine
        The line of thrust at collapse.
    direction : str
        ``"l"`` (Mech-l) or ``"r"`` (Mech-r).
    arch : BlockArch
        The arch analysed: the given one for ``"l"``, its mirror image for ``"r"``.
    method : str
        ``"static"`` or ``"kinematic"``.
    separation : int or None
        ``None`` for a four-hinge mechanism. Otherwise the joint that opens over its whole depth
        (no normal force through it; under the no-sliding hypothesis it may still carry a shear
        force along the joint) in a two-block mechanism with two hinges; this happens only for
        thick arches under large horizontal loads (k of order 1 or more), never for the paper's
        arches, and the four-link model of the paper does not apply to it.
    """

    load_multiplier: float
    hinges: tuple[Hinge, ...]
    thrust_line: ThrustLine
    direction: str
    arch: BlockArch
    method: str = DEFAULT_LIMIT_METHOD
    separation: int | None = None

    @property
    def is_four_hinge(self) -> bool:
        """True for a four-hinge (three-block) collapse mechanism."""
        return self.separation is None and len(self.hinges) == 4

    @property
    def hinge_angles(self) -> np.ndarray:
        """Progressive angles beta of the hinges A, B, C, D [rad] (paper Table 1)."""
        return np.array([h.beta(self.arch) for h in self.hinges])

    @property
    def hinge_points(self) -> np.ndarray:
        """Positions (x, y) of the hinges A, B, C, D [m], shape (4, 2)."""
        return np.array([h.point(self.arch) for h in self.hinges])

    def funicular(self) -> np.ndarray:
        """Funicular polygon of the collapse state [m], see :meth:`ThrustLine.funicular`."""
        return self.thrust_line.funicular(self.arch, self.load_multiplier)


@dataclass(frozen=True, eq=False)
class LimitSample:
    """Load multipliers of a sample of irregular arches [paper, Sect. 5.3.3, Figs. 17-20].

    Attributes
    ----------
    load_multiplier_l, load_multiplier_r : array of float, shape (s,)
        k~_l and k~_r of every arch [-].
    epsilon : float
        epsilon of the irregular draw.
    seed : int or None
        Root seed of the sample (arch ``i`` uses child ``i`` of ``SeedSequence(seed)``).
    method : str
        ``"static"`` or ``"kinematic"``.
    """

    load_multiplier_l: np.ndarray
    load_multiplier_r: np.ndarray
    epsilon: float
    seed: int | None
    method: str = DEFAULT_LIMIT_METHOD

    @property
    def load_multiplier(self) -> np.ndarray:
        """k~ = min(k~_l, k~_r) of every arch [-]."""
        return np.minimum(self.load_multiplier_l, self.load_multiplier_r)


def multiplier_distribution(k, k_nominal: float) -> dict:
    """What a sample of load multipliers says beside the nominal one: ``min``, ``max``,
    ``mean``, ``quantiles`` (0.05, 0.5, 0.95, keyed ``"0.05"``, ...) and ``below_nominal`` (the
    fraction of the sample below ``k_nominal``); empty for an empty sample.

    Parameters
    ----------
    k : array_like
        The multipliers of the structures drawn [-] (none missing).
    k_nominal : float
        The nominal structure's [-].

    Returns
    -------
    dict
        JSON-ready floats.
    """
    k = np.asarray(k, dtype=float)
    if not k.size:
        return {}
    return {"min": float(k.min()), "max": float(k.max()), "mean": float(k.mean()),
            "quantiles": {f"{q:g}": float(np.quantile(k, q)) for q in (0.05, 0.5, 0.95)},
            "below_nominal": float(np.mean(k < k_nominal))}
