r"""Limit analysis of any planar block assembly, with Coulomb friction at its interfaces.

The statics of :mod:`archquake.limit_analysis` for a chain of blocks hold for any set of rigid
blocks and the straight interfaces between them (:class:`~archquake.geometry.BlockAssembly`: a
wall, a portal, a drawing; an arch is one, :func:`contacts_of`). Every block :math:`j` carries a
weight :math:`W_j` along the vertical :math:`x = a_j` and a horizontal load :math:`k H_j` along
the horizontal :math:`y = b_j` (:class:`~archquake.geometry.BlockLoads`; for a bare block
:math:`W_j = H_j = m_j g` at its centroid), and :math:`k` is the horizontal load multiplier:
with no cohesion only the direction of the load matters, so :math:`k = \tan\theta` for a
tilting table tilted by :math:`\theta` (LACT3's test [1]_).

**Static formulation (the associative linear program).** Interface :math:`i` between bodies
:math:`a_i` and :math:`b_i` (one of them may be the ground), from :math:`\mathbf p_{i,0}` to
:math:`\mathbf p_{i,1}`, with unit normal :math:`\mathbf n_i` from :math:`a_i` into :math:`b_i`
and tangent :math:`\boldsymbol\tau_i = (\mathbf p_{i,1} - \mathbf p_{i,0}) / \ell_i`, carries
normal forces :math:`n_{i,0}, n_{i,1} \ge 0` at its ends and a shear force :math:`t_i`: the force
of :math:`a_i` on :math:`b_i` is :math:`(n_{i,0} + n_{i,1})\,\mathbf n_i + t_i
\boldsymbol\tau_i`, the normal forces acting at their ends (so the resultant's pressure point
lies in the interface: no tension) and the shear along the interface. Then

.. math::

    \max k \quad\text{subject to}\quad
    \mathbf A \mathbf f + k\, \mathbf h + \mathbf w = 0, \qquad
    n_{i,0}, n_{i,1} \ge 0, \qquad |t_i| \le \mu_i (n_{i,0} + n_{i,1})

(three equilibrium equations per block; :math:`\mu_i = \infty`: Heyman's hypothesis, the
interface does not slide). This is the lower-bound program of Livesley [2]_ and of LACT3. Its
dual is the upper-bound (kinematic) program: the multipliers of the equilibrium rows are the
virtual velocities :math:`(u_j, v_j, \omega_j)` of the blocks in the collapse mechanism
(:attr:`AssemblyLimit.velocities`), with, at every interface end, an opening rate
:math:`\delta_n \ge 0` and, where it slips, the opening :math:`\delta_n = \mu |\delta_t|` that
normality (an associative flow rule) demands. For a chain without friction it is the program
of :mod:`archquake.limit_analysis` written with other unknowns, and gives the same :math:`k`
(tested).

**Non-associative friction.** Real joints slide without opening (no dilatancy), and then the
associative multiplier can overestimate the collapse load [2]_: it is an upper bound of
nothing in particular. The iterative method of Gilbert, Casapulla and Ahmed [3]_ treats the
friction of each interface as a cohesion fixed from the normal force of the previous iteration,
:math:`|t_i| \le c_i^{(r)} = \mu_i \bar N_i^{(r-1)}` (its flow rule is a slip without opening:
the non-associative one), starting from the associative solution's normal forces, relaxed as
:math:`\bar N^{(r)} = \beta N^{(r)} + (1 - \beta) \bar N^{(r-1)}`. In a statically
indeterminate assembly (a wall) the program's optimum leaves many normal forces free, and an
arbitrary choice among them makes the iteration wander: each step therefore takes, at the
step's :math:`k`, the state whose normal forces are nearest the previous ones (a second linear
program, least sum of absolute differences). It stops when :math:`k`, the normal forces of the
interfaces at their shear capacity and Coulomb's law (:math:`|t_i| \le \mu_i N_i` with the
state's own normal forces) all hold to :data:`NONASSOCIATIVE_TOLERANCE`.
At convergence the forces satisfy Coulomb's law exactly (statically
admissible) and the mechanism slides without dilatancy (kinematically admissible for the
non-associative law): a solution of the non-associative problem, not proved the least one; where
the iteration does not converge, the result says so. The rigid-block model under a slowly
growing acceleration (:func:`archquake.rigid_blocks.ramp.ramp_test`) is the arbiter.

References
----------
.. [1] LACT3, limit analysis of tilting-table tests of 2D block assemblies (associative
   Coulomb friction, interfaces from a DXF drawing).
.. [2] R. K. Livesley, "Limit analysis of structures formed from rigid blocks", Int. J. Numer.
   Methods Eng. 12 (1978) 1853-1871.
.. [3] M. Gilbert, C. Casapulla and H. M. Ahmed, "Limit analysis of masonry block structures with
   non-associative frictional joints using linear programming", Comput. Struct. 84 (2006)
   873-887.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import linprog
from scipy.sparse import coo_array

from ..constants import GRAVITY
from ..errors import UnsolvedProgramError

GROUND = -1
"""Body index of the ground [-]."""

NONASSOCIATIVE_ITERATIONS = 100
"""Largest number of linear programs of the non-associative iteration [-]."""

NONASSOCIATIVE_TOLERANCE = 1e-6
"""Convergence of the non-associative iteration: the largest change of a normal force, as a
fraction of the assembly's weight, and of k [-]."""

RELAXATION = 1.0
r"""First relaxation :math:`\beta` of the normal forces between iterations [-], halved (down to
0.02) whenever k turns back (Gilbert et al. relax the iteration to damp its
oscillations)."""

MOTION_TOLERANCE = 1e-6
"""An interface end opens or slips when its rate exceeds this fraction of the mechanism's
largest velocity [-]."""


@dataclass(frozen=True, eq=False)
class Contacts:
    """The statics' view of an assembly: blocks with loads and the interfaces between them.

    Attributes
    ----------
    n_blocks : int
        Number of blocks [-].
    a, b : array of int, shape (ni,)
        The two bodies of every interface (:data:`GROUND` for a support).
    p0, p1 : array of float, shape (ni, 2)
        Its ends [m]; the tangent ``(p1 - p0) / |p1 - p0|`` is ``normal`` turned by +90 deg.
    normal : array of float, shape (ni, 2)
        Unit normal from body a into body b [-].
    friction : array of float, shape (ni,)
        Coulomb coefficient [-]; ``inf``: the interface cannot slide.
    kind : array of str, shape (ni,)
        ``"bed"``, ``"head"``, ``"ring"`` or ``"foundation"``.
    vertical, vertical_x, horizontal, horizontal_y : array of float, shape (n_blocks,)
        Every block's weight [N/m] and the abscissa of its line [m], its horizontal load per
        unit multiplier [N/m] and the ordinate of its line [m].
    outlines : tuple of arrays
        Every block's outline [m], for drawing.
    passive, passive_y, passive_sign : array of float, shape (n_blocks,)
        The passive reaction of a fill on every block (:mod:`archquake.geometry.fill`): its
        largest value :math:`\bar P_i` [N/m] (0: none), the ordinate of its line [m] and its
        direction (+1 toward +x, -1 toward -x, 0 none). In the program an unknown horizontal
        force in :math:`[0, \bar P_i]`: a resistance, not a load.
    """

    n_blocks: int
    a: np.ndarray
    b: np.ndarray
    p0: np.ndarray
    p1: np.ndarray
    normal: np.ndarray
    friction: np.ndarray
    kind: np.ndarray
    vertical: np.ndarray
    vertical_x: np.ndarray
    horizontal: np.ndarray
    horizontal_y: np.ndarray
    outlines: tuple
    passive: np.ndarray | None = None
    passive_y: np.ndarray | None = None
    passive_sign: np.ndarray | None = None

    def __post_init__(self):
        zeros = np.zeros(self.n_blocks)
        for name in ("passive", "passive_y", "passive_sign"):
            if getattr(self, name) is None:
                object.__setattr__(self, name, zeros)

    @property
    def resisting(self) -> np.ndarray:
        """The blocks a passive reaction acts on (a bound > 0 and a direction) [-]."""
        return np.flatnonzero((self.passive_sign != 0) & (self.passive > 0))

    @property
    def n_interfaces(self) -> int:
        """Number of interfaces [-]."""
        return int(self.a.size)

    @property
    def tangent(self) -> np.ndarray:
        """Unit tangent of every interface, from p0 to p1 [-], shape (ni, 2)."""
        return np.column_stack((-self.normal[:, 1], self.normal[:, 0]))

    def with_friction(self, friction) -> Contacts:
        """A copy whose interfaces have the Coulomb coefficient ``friction`` [-]: one number,
        one per interface, or a dict interface kind -> coefficient (kinds it does not name
        keep theirs)."""
        mu = np.array(self.friction, dtype=float)
        if isinstance(friction, dict):
            for kind, value in friction.items():
                mu[self.kind == kind] = _check_friction(value, f"friction[{kind!r}]")
        else:
            values = np.broadcast_to(np.asarray(friction, dtype=float), mu.shape)
            for value in np.unique(values):
                _check_friction(float(value), "friction")
            mu = values.copy()
        return Contacts(**{**self.__dict__, "friction": mu})


def _check_friction(value, name: str) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float | np.floating) \
            or math.isnan(value) or value < 0:
        raise ValueError(f"{name} must be a Coulomb coefficient >= 0 (inf: no sliding), "
                         f"got {value!r}")
    return float(value)


def contacts_of(structure, friction=None) -> Contacts:
    """The blocks, loads and interfaces of a structure.

    Parameters
    ----------
    structure : BlockAssembly or BlockArch
        Any assembly (:class:`~archquake.geometry.BlockAssembly`), or a chain
        (:class:`~archquake.geometry.BlockArch`: an arch, an arch on piers, with fill), whose
        joints are ``"bed"`` interfaces and whose two ends on the ground ``"foundation"`` ones.
    friction : None, float or dict, optional
        Coulomb coefficient of the interfaces [-] (see :meth:`Contacts.with_friction`); by
        default the assembly's own, or none (no sliding) for a chain.

    Returns
    -------
    Contacts
    """
    if hasattr(structure, "interfaces"):
        contacts = _assembly_contacts(structure)
    else:
        contacts = _chain_contacts(structure)
    return contacts if friction is None else contacts.with_friction(friction)


def _assembly_contacts(assembly) -> Contacts:
    """An assembly's interfaces; its blocks' loads: their weights through their centroids, or
    the loads it gives (``loads``: an assembly under fill,
    :class:`~archquake.geometry.bridge.FilledAssembly`, whose blocks carry the fill's columns as
    a chain's voussoirs do)."""
    faces = assembly.interfaces
    loads = getattr(assembly, "loads", None)
    if loads is None:
        weight = np.asarray(assembly.mass, dtype=float) * GRAVITY
        centroid = np.asarray(assembly.centroid, dtype=float)
        vertical, vertical_x = weight, centroid[:, 0].copy()
        horizontal, horizontal_y = weight, centroid[:, 1].copy()
    else:
        vertical, vertical_x = loads.vertical, loads.vertical_x
        horizontal, horizontal_y = loads.horizontal, loads.horizontal_y
    return Contacts(
        n_blocks=int(assembly.n_blocks), a=np.asarray(faces.a, dtype=np.int64),
        b=np.asarray(faces.b, dtype=np.int64), p0=np.asarray(faces.p0, dtype=float),
        p1=np.asarray(faces.p1, dtype=float), normal=np.asarray(faces.normal, dtype=float),
        friction=np.asarray(faces.friction, dtype=float), kind=np.asarray(faces.kind),
        vertical=np.asarray(vertical, dtype=float),
        vertical_x=np.asarray(vertical_x, dtype=float),
        horizontal=np.asarray(horizontal, dtype=float),
        horizontal_y=np.asarray(horizontal_y, dtype=float), outlines=tuple(assembly.polygons),
        **_passive_of(loads))


def _passive_of(loads) -> dict:
    """The passive reaction's fields of :class:`Contacts` from a structure's
    :class:`~archquake.geometry.loads.BlockLoads` (none without loads)."""
    if loads is None:
        return {}
    return {name: np.asarray(getattr(loads, name), dtype=float)
            for name in ("passive", "passive_y", "passive_sign")}


def _chain_contacts(arch) -> Contacts:
    n = arch.n_voussoirs
    loads = arch.loads
    joints = np.asarray(arch.joints, dtype=float)
    a = np.arange(-1, n)
    b = np.arange(0, n + 1)
    b[-1] = GROUND
    kind = np.full(n + 1, "bed", dtype=object)
    kind[[0, -1]] = "foundation"
    return Contacts(
        n_blocks=n, a=a, b=b, p0=joints[:, 0].copy(), p1=joints[:, 1].copy(),
        normal=np.asarray(arch.joint_normals, dtype=float).copy(),
        friction=np.full(n + 1, np.inf), kind=kind.astype(str),
        vertical=np.asarray(loads.vertical, dtype=float),
        vertical_x=np.asarray(loads.vertical_x, dtype=float),
        horizontal=np.asarray(loads.horizontal, dtype=float),
        horizontal_y=np.asarray(loads.horizontal_y, dtype=float),
        outlines=tuple(arch.outline(i) for i in range(n)), **_passive_of(loads))


# --------------------------------------------------------------------------- the program
@dataclass(frozen=True)
class _Program:
    """The equilibrium rows of an assembly, in units of its weight and size."""

    a_eq: object        # sparse (3 nb, 3 ni + np + 1): columns n0, n1, t of every interface,
    b_eq: np.ndarray    # the passive reactions of the np resisting blocks, then k
    passive: np.ndarray  # the passive reactions' upper bounds (np,)
    weight: float       # total weight [N/m]
    origin: np.ndarray  # [m]
    size: float         # [m]


def _program(c: Contacts, sign: float) -> _Program:
    ni, nb = c.n_interfaces, c.n_blocks
    points = np.concatenate((c.p0, c.p1))
    origin = points.mean(axis=0)
    size = float(np.max(np.hypot(*(points - origin).T))) or 1.0
    weight = float(np.sum(c.vertical))
    p0 = (c.p0 - origin) / size
    p1 = (c.p1 - origin) / size
    n, t = c.normal, c.tangent
    rows, cols, vals = [], [], []

    def put(body, column, force, point):
        keep = body >= 0
        body, column, force, point = body[keep], column[keep], force[keep], point[keep]
        moment = point[:, 0] * force[:, 1] - point[:, 1] * force[:, 0]
        for r, value in enumerate((force[:, 0], force[:, 1], moment)):
            rows.append(3 * body + r)
            cols.append(column)
            vals.append(value)

    index = np.arange(ni)
    for column, force, point in ((index, n, p0), (ni + index, n, p1), (2 * ni + index, t, p0)):
        put(c.b, column, force, point)      # the force of a on b
        put(c.a, column, -force, point)     # and of b on a
    resisting = c.resisting  # a horizontal force s_i P on block i at height y_i
    along = c.passive_sign[resisting]
    index = 3 * ni + np.arange(resisting.size)
    rows += [3 * resisting, 3 * resisting + 2]
    cols += [index, index]
    vals += [along, -(c.passive_y[resisting] - origin[1]) / size * along]
    live = 3 * ni + resisting.size
    live_h = sign * c.horizontal / weight
    live_y = (c.horizontal_y - origin[1]) / size
    blocks = np.arange(nb)
    rows += [3 * blocks, 3 * blocks + 2]
    cols += [np.full(nb, live), np.full(nb, live)]
    vals += [live_h, -live_y * live_h]
    w = c.vertical / weight
    wx = (c.vertical_x - origin[0]) / size
    b_eq = np.zeros(3 * nb)
    b_eq[3 * blocks + 1] = w
    b_eq[3 * blocks + 2] = w * wx
    a_eq = coo_array((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                     shape=(3 * nb, live + 1)).tocsc()
    return _Program(a_eq, b_eq, c.passive[resisting] / weight, weight, origin, size)


def _check_connected(c: Contacts) -> None:
    touched = np.zeros(c.n_blocks, dtype=bool)
    touched[c.a[c.a >= 0]] = True
    touched[c.b[c.b >= 0]] = True
    if not touched.all():
        raise ValueError(f"block(s) {np.flatnonzero(~touched).tolist()} touch nothing: an "
                         "assembly's blocks must each rest on another block or the ground")


def _solve(prog: _Program, c: Contacts, shear: np.ndarray | None, fixed_k: float | None):
    """Solve the program; ``shear``: the fixed shear capacities (non-associative step), else
    Coulomb's cone with the interfaces' friction."""
    ni = c.n_interfaces
    nv = prog.a_eq.shape[1]
    cost = np.zeros(nv)
    cost[-1] = -1.0
    bounds = np.empty((nv, 2))
    bounds[:2 * ni] = (0.0, np.inf)
    bounds[2 * ni:3 * ni] = (-np.inf, np.inf)
    bounds[3 * ni:-1, 0], bounds[3 * ni:-1, 1] = 0.0, prog.passive
    bounds[-1] = (-np.inf, np.inf) if fixed_k is None else (fixed_k, fixed_k)
    a_ub = b_ub = None
    finite = np.isfinite(c.friction)
    if shear is not None:
        bounds[2 * ni:3 * ni, 0] = np.where(finite, -shear, -np.inf)
        bounds[2 * ni:3 * ni, 1] = np.where(finite, shear, np.inf)
    elif finite.any():
        rows = np.flatnonzero(finite)
        m = rows.size
        r = np.arange(m)
        mu = c.friction[rows]
        # t - mu (n0 + n1) <= 0 and -t - mu (n0 + n1) <= 0
        a_ub = coo_array((np.concatenate((np.ones(m), -mu, -mu, -np.ones(m), -mu, -mu)),
                          (np.concatenate((r, r, r, m + r, m + r, m + r)),
                           np.concatenate((2 * ni + rows, rows, ni + rows,
                                           2 * ni + rows, rows, ni + rows)))),
                         shape=(2 * m, nv)).tocsc()
        b_ub = np.zeros(2 * m)
    res = linprog(cost, A_ub=a_ub, b_ub=b_ub, A_eq=prog.a_eq, b_eq=prog.b_eq,
                  bounds=bounds, method="highs")
    return res


def _closest(prog: _Program, c: Contacts, shear: np.ndarray, k: float, target: np.ndarray):
    """Of the states in equilibrium at ``k`` within the shear capacities ``shear``, the one
    whose normal forces are nearest ``target`` (least sum of absolute differences): the
    non-associative iteration's step from its previous state, where the program's optimum
    leaves the normal forces of a statically indeterminate assembly free."""
    from scipy.sparse import hstack, identity, vstack

    ni = c.n_interfaces
    nv = prog.a_eq.shape[1]
    cost = np.concatenate((np.zeros(nv), np.ones(ni)))
    finite = np.isfinite(c.friction)
    bounds = np.empty((nv + ni, 2))
    bounds[:2 * ni] = (0.0, np.inf)
    bounds[2 * ni:3 * ni, 0] = np.where(finite, -shear, -np.inf)
    bounds[2 * ni:3 * ni, 1] = np.where(finite, shear, np.inf)
    bounds[3 * ni:nv - 1, 0], bounds[3 * ni:nv - 1, 1] = 0.0, prog.passive
    bounds[nv - 1] = (k, k)
    bounds[nv:] = (0.0, np.inf)
    pick = hstack((identity(ni), identity(ni), coo_array((ni, nv - 2 * ni))))
    # (n0 + n1) - s <= target and -(n0 + n1) - s <= -target
    a_ub = vstack((hstack((pick, -identity(ni))), hstack((-pick, -identity(ni))))).tocsc()
    b_ub = np.concatenate((target, -target))
    a_eq = hstack((prog.a_eq, coo_array((prog.a_eq.shape[0], ni)))).tocsc()
    return linprog(cost, A_ub=a_ub, b_ub=b_ub, A_eq=a_eq, b_eq=prog.b_eq, bounds=bounds,
                   method="highs")


# --------------------------------------------------------------------------- results
@dataclass(frozen=True, eq=False)
class AssemblyLimit:
    r"""The collapse of an assembly under a horizontal load one way (:func:`assembly_limit`).

    Attributes
    ----------
    direction : str
        ``"+x"`` (the load toward +x) or ``"-x"``.
    load_multiplier : float
        The collapse multiplier :math:`k` [-] (``inf``: no collapse under any horizontal load).
    tilt : float
        The tilt of a tilting table at collapse, :math:`\arctan k` [deg].
    law : str
        ``"no sliding"``, ``"associative"`` or ``"non-associative"``.
    iterations : int
        Linear programs solved [-] (1 for the first two laws).
    converged : bool
        Whether the non-associative iteration converged (always True otherwise).
    normal, shear : array of float, shape (ni,)
        Normal (compressive) and shear force of every interface at collapse [N/m].
    pressure : array of float, shape (ni, 2)
        The pressure point of every interface [m] (NaN where its normal force is zero).
    velocities : array of float, shape (nb, 3)
        The mechanism: every block's rigid motion ``(u, v, omega)`` [m/s, m/s, rad/s], its
        velocity at ``origin`` and its rotation rate, scaled so that the fastest block corner
        moves at 1 m/s (:meth:`velocity_at`).
    opening : array of float, shape (ni, 2)
        Opening rate of every interface at its two ends [m/s] (>= 0).
    slip : array of float, shape (ni,)
        Slip rate of every interface [m/s] (along its tangent).
    state : array of str, shape (ni,)
        ``"closed"``, ``"rocks"`` (one end opens: a hinge at the other), ``"separates"`` (both
        open), ``"slides"`` or ``"rocks and slides"``.
    contacts : Contacts
        The assembly analysed.
    origin : array of float, shape (2,)
        The point at which :attr:`velocities` are given [m].
    """

    direction: str
    load_multiplier: float
    law: str
    iterations: int
    converged: bool
    normal: np.ndarray
    shear: np.ndarray
    pressure: np.ndarray
    velocities: np.ndarray
    opening: np.ndarray
    slip: np.ndarray
    state: np.ndarray
    contacts: Contacts
    origin: np.ndarray

    @property
    def tilt(self) -> float:
        """The tilting table's angle at collapse, atan(k) [deg]."""
        return math.degrees(math.atan(self.load_multiplier))

    def velocity_at(self, block: int, points) -> np.ndarray:
        """Velocity of block ``block`` at ``points`` (m, 2) [m/s] in the mechanism."""
        u, v, w = self.velocities[block]
        p = np.asarray(points, dtype=float) - self.origin
        return np.column_stack((u - w * p[:, 1], v + w * p[:, 0]))

    def ring_lengths(self) -> tuple[float, float]:
        """The length of ring interface (an arch of several rings) that opens (rocks or
        separates, without sliding) and that slides [m], the chords summed; 0 without rings."""
        c = self.contacts
        ring = np.asarray(c.kind) == "ring"
        length = np.hypot(*(c.p1 - c.p0).T)
        state = np.asarray(self.state).astype(str)
        opens = ring & np.isin(state, ("rocks", "separates"))
        slides = ring & (np.char.find(state, "slides") >= 0)
        return float(length[opens].sum()), float(length[slides].sum())

    def interfaces_that(self, state: str) -> list[int]:
        """The interfaces whose state contains ``state`` (``"rocks"``, ``"slides"``, ...)."""
        return [i for i, s in enumerate(self.state) if state in s]

    def thrust_line(self) -> tuple[np.ndarray, np.ndarray]:
        r"""The line of thrust at collapse, as segments inside the blocks [m].

        The force of body :math:`a_i` on :math:`b_i` at a loaded interface,
        :math:`N_i \mathbf n_i + t_i \boldsymbol\tau_i`, acts along the line through its
        pressure point :math:`\mathbf P_i` in its direction; block :math:`j`'s load, its weight
        :math:`W_j` along :math:`x = a_j` and :math:`\pm k H_j` along :math:`y = b_j`, along the
        line through :math:`(a_j, b_j)` in the direction :math:`(\pm k H_j, -W_j)`. A block
        held by two loaded interfaces (every voussoir of a single ring, every course of a pier)
        is in equilibrium under three forces, which meet in one point :math:`\mathbf X_j` of
        the load's line: the line of thrust through it is the polygon :math:`\mathbf P_i \to
        \mathbf X_j \to \mathbf P_{i'}` that graphic statics draws, each segment from a
        pressure point along its force to the load's line (a block on one interface: the one
        segment to the load's line). A block that carries more (a pier's top under two arches),
        or a voussoir loaded through a ring interface (the rings share the thrust: no ring has
        a line of its own), or one with an interface that carries shear without a normal force
        (where it cannot slide), has no single line through it and gives no segment; nor does
        a force parallel to the load's line, or meeting it farther from the block than the
        block's size.

        Returns
        -------
        segments : array of float, shape (m, 2, 2)
            The segments' ends ``[P_i, X]`` [m].
        blocks : array of int, shape (m,)
            The block of every segment.
        """
        c = self.contacts
        sign = _sign(self.direction)
        force = self.normal[:, None] * c.normal + self.shear[:, None] * c.tangent
        magnitude = np.hypot(force[:, 0], force[:, 1])
        carries = magnitude > 1e-9 * max(float(np.max(magnitude, initial=0.0)), 0.0)
        loaded = np.isfinite(self.pressure[:, 0]) & carries
        segments, blocks = [], []
        for j in range(c.n_blocks):
            point = np.array([c.vertical_x[j], c.horizontal_y[j]])
            load = np.array([sign * self.load_multiplier * c.horizontal[j], -c.vertical[j]])
            outline = np.asarray(c.outlines[j], dtype=float)
            reach = float(np.max(np.ptp(outline, axis=0)))
            centre = outline.mean(axis=0)
            touching = (c.a == j) | (c.b == j)
            held = np.flatnonzero(loaded & touching)
            if (held.size > 2 or np.any(carries & ~loaded & touching)
                    or np.any(c.kind[held] == "ring")):
                continue
            for i in held:
                d = force[i]
                cross = d[0] * load[1] - d[1] * load[0]
                if abs(cross) <= 1e-9 * np.hypot(*d) * np.hypot(*load):
                    continue
                # P + s d = point + r load
                rel = point - self.pressure[i]
                s = (rel[0] * load[1] - rel[1] * load[0]) / cross
                x = self.pressure[i] + s * d
                if np.hypot(*(x - centre)) <= reach:
                    segments.append((self.pressure[i], x))
                    blocks.append(j)
        return np.array(segments, dtype=float).reshape(-1, 2, 2), np.array(blocks, dtype=int)

    def to_dict(self) -> dict:
        """A JSON-ready summary: k, tilt, law, convergence and the moving interfaces."""
        c = self.contacts
        moving = [{"interface": i, "bodies": [int(c.a[i]), int(c.b[i])],
                   "kind": str(c.kind[i]), "state": str(s)}
                  for i, s in enumerate(self.state) if s != "closed"]
        k = self.load_multiplier
        return {"direction": self.direction, "law": self.law,
                "load_multiplier": k if math.isfinite(k) else None,
                "tilt_deg": self.tilt if math.isfinite(k) else None,
                "iterations": self.iterations, "converged": self.converged,
                "rocking": self.interfaces_that("rocks"),
                "sliding": self.interfaces_that("slides"),
                "separating": self.interfaces_that("separates"),
                "moving_interfaces": moving}


def _motion(c: Contacts, prog: _Program, marginals: np.ndarray):
    """Velocities of the blocks from the equilibrium rows' multipliers, and the interfaces'
    openings, slips and states."""
    v = -np.asarray(marginals, dtype=float).reshape(-1, 3)
    # velocity of a block at a point p (scaled frame about prog.origin)
    def at(body, p):
        out = np.zeros((body.size, 2))
        ok = body >= 0
        vb = v[body[ok]]
        out[ok, 0] = vb[:, 0] - vb[:, 2] * p[ok, 1]
        out[ok, 1] = vb[:, 1] + vb[:, 2] * p[ok, 0]
        return out

    p0 = (c.p0 - prog.origin) / prog.size
    p1 = (c.p1 - prog.origin) / prog.size
    rel0 = at(c.b, p0) - at(c.a, p0)
    rel1 = at(c.b, p1) - at(c.a, p1)
    opening = np.column_stack((np.sum(rel0 * c.normal, axis=1), np.sum(rel1 * c.normal, axis=1)))
    slip = np.sum(rel0 * c.tangent, axis=1)
    corners = [np.asarray(o, dtype=float) for o in c.outlines]
    speed = 0.0
    for j, outline in enumerate(corners):
        p = (outline - prog.origin) / prog.size
        u = v[j, 0] - v[j, 2] * p[:, 1]
        w = v[j, 1] + v[j, 2] * p[:, 0]
        speed = max(speed, float(np.max(np.hypot(u, w))))
    if speed <= 0.0 or not math.isfinite(speed):
        speed = 1.0
    opening, slip = opening / speed, slip / speed
    tol = MOTION_TOLERANCE
    slides = np.abs(slip) > tol
    turns = np.abs(opening[:, 0] - opening[:, 1]) > tol
    opens = opening.min(axis=1) > tol
    state = np.full(c.n_interfaces, "closed", dtype=object)
    state[turns & ~opens] = "rocks"
    state[opens & ~slides] = "separates"
    state[slides] = "slides"
    state[slides & turns] = "rocks and slides"
    # in metres: translations u * size, rotation rates unchanged; the fastest corner at 1 m/s
    velocities = np.column_stack((v[:, :2] / speed, v[:, 2] / (speed * prog.size)))
    return velocities, opening, slip, state.astype(str)


def _result(c, prog, res, direction, law, iterations, converged, k=None) -> AssemblyLimit:
    ni = c.n_interfaces
    x = res.x
    n0, n1, t = x[:ni] * prog.weight, x[ni:2 * ni] * prog.weight, x[2 * ni:3 * ni] * prog.weight
    normal = n0 + n1
    with np.errstate(invalid="ignore", divide="ignore"):
        u = np.where(normal > 0, n1 / np.where(normal > 0, normal, 1.0), np.nan)
    pressure = c.p0 + u[:, None] * (c.p1 - c.p0)
    velocities, opening, slip, state = _motion(c, prog, res.eqlin.marginals)
    return AssemblyLimit(direction=direction, load_multiplier=float(x[-1]) if k is None else k,
                         law=law, iterations=iterations, converged=converged, normal=normal,
                         shear=t, pressure=pressure, velocities=velocities, opening=opening,
                         slip=slip, state=state, contacts=c, origin=prog.origin)


def _failure(res, what: str) -> UnsolvedProgramError:
    return UnsolvedProgramError(f"the {what} linear program of this assembly cannot be solved "
                      f"({res.message.strip()}): its geometry is degenerate")


def _sign(direction: str) -> float:
    if direction not in ("+x", "-x"):
        raise ValueError(f"direction must be '+x' or '-x', got {direction!r}")
    return 1.0 if direction == "+x" else -1.0


def assembly_limit(structure, direction: str = "+x", *, friction=None,
                   law: str = "associative") -> AssemblyLimit:
    r"""The horizontal load multiplier at collapse of any assembly, one way.

    Parameters
    ----------
    structure : BlockAssembly, BlockArch or Contacts
        The assembly (:func:`contacts_of`).
    direction : {"+x", "-x"}
        The way the horizontal load pushes.
    friction : None, float or dict, optional
        Coulomb coefficient of the interfaces [-] (see :meth:`Contacts.with_friction`).
    law : {"associative", "non-associative"}
        The friction law: normality (the classical program, LACT3's), or slip without opening
        by the iterative method of Gilbert et al. (see the module). Without friction (every
        coefficient infinite) both are Heyman's, reported as ``"no sliding"``.

    Returns
    -------
    AssemblyLimit

    Raises
    ------
    CannotStandError
        When the assembly cannot stand under its own weight (no equilibrium at k = 0 within
        the interfaces' contacts and friction).
    ValueError
        For a block that touches nothing, or a degenerate geometry.
    """
    from ..errors import CannotStandError

    c = structure if isinstance(structure, Contacts) else contacts_of(structure)
    if friction is not None:
        c = c.with_friction(friction)
    if law not in ("associative", "non-associative"):
        raise ValueError(f"law must be 'associative' or 'non-associative', got {law!r}")
    _check_connected(c)
    sign = _sign(direction)
    prog = _program(c, sign)
    res = _solve(prog, c, None, None)
    if res.status == 2:
        raise CannotStandError("the assembly cannot stand under its own weight: no set of "
                               "contact forces without tension and within the friction cones "
                               "balances its blocks")
    if res.status == 3:
        inf_res = _solve(prog, c, None, 0.0)
        return _result(c, prog, inf_res, direction,
                       "no sliding" if not np.isfinite(c.friction).any() else law, 1, True,
                       k=math.inf)
    if res.status != 0:
        raise _failure(res, "static")
    if res.x[-1] < -1e-9:
        raise CannotStandError(f"the assembly stands only under a horizontal push "
                               f"{direction} of at least {-res.x[-1]:.3g} times its weight: it "
                               "cannot stand under its own weight alone")
    if not np.isfinite(c.friction).any():
        return _result(c, prog, res, direction, "no sliding", 1, True)
    if law == "associative":
        return _result(c, prog, res, direction, law, 1, True)
    return _nonassociative(c, prog, res, direction)


def _nonassociative(c: Contacts, prog: _Program, res, direction: str) -> AssemblyLimit:
    ni = c.n_interfaces
    finite = np.isfinite(c.friction)
    mu = np.where(finite, c.friction, 0.0)
    relaxed = res.x[:ni] + res.x[ni:2 * ni]
    k_old, change_old = res.x[-1], 0.0
    beta = RELAXATION
    last = res
    tol = NONASSOCIATIVE_TOLERANCE
    for iteration in range(1, NONASSOCIATIVE_ITERATIONS + 1):
        capacity = mu * relaxed
        step = _solve(prog, c, capacity, None)
        if step.status in (2, 3):
            # no state within these capacities (or an unbounded k): the iteration cannot go
            # on; the previous capacities' answer is returned, marked not converged
            return _result(c, prog, last, direction, "non-associative", iteration, False)
        if step.status != 0:
            raise _failure(step, "non-associative")
        k = step.x[-1]
        near = _closest(prog, c, capacity, k - 1e-10 * max(1.0, abs(k)), relaxed)
        forces = near.x[:3 * ni] if near.status == 0 else step.x[:3 * ni]
        new = forces[:ni] + forces[ni:2 * ni]
        shear = forces[2 * ni:3 * ni]
        last = step
        # converged: k settled, the normal forces of the interfaces at their shear capacity
        # (the sliding ones) settled, and every shear within Coulomb's cone of its own normal
        # force (statically admissible)
        at_capacity = finite & (capacity > tol) & (np.abs(shear) >= capacity - tol)
        settled = float(np.max(np.abs(new - relaxed)[at_capacity], initial=0.0))
        admissible = bool(np.all(np.abs(shear[finite]) <= mu[finite] * new[finite] + tol))
        if abs(k - k_old) <= tol and settled <= tol and admissible:
            return _result(c, prog, step, direction, "non-associative", iteration + 1, True)
        change = k - k_old
        if change * change_old < 0.0 and abs(change) > tol:  # k oscillates: relax harder
            beta = max(0.5 * beta, 0.02)
        relaxed = beta * new + (1.0 - beta) * relaxed
        k_old, change_old = k, change
    return _result(c, prog, last, direction, "non-associative",
                   NONASSOCIATIVE_ITERATIONS + 1, False)


def assembly_limits(structure, *, friction=None) -> dict[str, dict[str, AssemblyLimit]]:
    """Both directions' collapse under each friction law: ``{"+x": {"associative": ...,
    "non-associative": ...}, "-x": {...}}`` (only ``"no sliding"`` when nothing can slide)."""
    c = structure if isinstance(structure, Contacts) else contacts_of(structure)
    if friction is not None:
        c = c.with_friction(friction)
    laws = ("associative", "non-associative") if np.isfinite(c.friction).any() else (
        "associative",)
    out = {}
    for direction in ("+x", "-x"):
        out[direction] = {}
        for law in laws:
            result = assembly_limit(c, direction, law=law)
            out[direction][result.law] = result
    return out


def governing_law(laws: dict) -> AssemblyLimit:
    """Of one direction's results by law (:func:`assembly_limits`), the one that governs: the
    non-associative law's where an interface can slide (slip without opening, the physical
    one), else the only one."""
    return laws.get("non-associative") or next(iter(laws.values()))


def governing_multiplier(structure, *, friction=None) -> float:
    """The least collapse multiplier of both directions under the governing friction law
    (:func:`governing_law`: the non-associative one where an interface can slide) [-]: the k
    of :func:`assembly_limits`, without the law that does not govern."""
    c = structure if isinstance(structure, Contacts) else contacts_of(structure)
    if friction is not None:
        c = c.with_friction(friction)
    law = "non-associative" if np.isfinite(c.friction).any() else "associative"
    return min(assembly_limit(c, d, law=law).load_multiplier for d in ("+x", "-x"))


def assembly_multipliers(structure) -> tuple[float, float]:
    """``(k_l, k_r)``: the collapse multipliers toward +x and -x by the static program with the
    assembly's own friction (:func:`assembly_limit`, its default law) [-]; inf where there is
    no mechanism. What :attr:`archquake.rigid_blocks.RigidBlockModel.load_multipliers` states
    of an assembly.

    Raises
    ------
    archquake.errors.CannotStandError
        When the assembly cannot stand under its own weight.
    """
    return tuple(float(assembly_limit(structure, d).load_multiplier) for d in ("+x", "-x"))


def assembly_stands(structure, *, friction=None) -> bool:
    """Whether some set of contact forces balances the assembly under its own weight (no
    tension, within the friction cones)."""
    c = structure if isinstance(structure, Contacts) else contacts_of(structure)
    if friction is not None:
        c = c.with_friction(friction)
    _check_connected(c)
    res = _solve(_program(c, 1.0), c, None, 0.0)
    if res.status not in (0, 2):
        raise _failure(res, "self-weight")
    return res.status == 0


def assembly_min_thickness(build, low: float, high: float, *, rtol: float = 1e-6) -> float:
    r"""The least thickness at which the assembly ``build(thickness)`` stands under its own
    weight (:func:`assembly_stands`), by bisection: an arch of several rings
    (:func:`~archquake.geometry.multi_ring`) with all its rings scaled together.

    Bisection assumes that an arch that stands at a thickness stands at every larger one in
    ``[low, high]`` (a thicker arch holds the thinner one's thrust lines: Heyman's safe
    theorem for one ring, and the same for rings whose interfaces the thicker arch's
    rings also offer).

    Parameters
    ----------
    build : callable
        ``thickness [m] -> BlockAssembly``.
    low, high : float
        The bracket [m], ``0 < low < high``: the arch must stand at ``high``.
    rtol : float, default 1e-6
        Width of the final bracket relative to its upper end [-].

    Below the minimum, with friction at the ring interfaces, the self-weight program is
    infeasible and can be so badly conditioned that HiGHS returns no verdict: such a thickness
    counts as not standing. The thickness returned always stands (an optimal solution of the
    program proves it), so it is never below the minimum; a failure above the minimum could
    only make it larger.

    Returns
    -------
    float
        The thickness [m] (the upper end of the final bracket, at which it stands); ``low``
        when it stands there already.

    Raises
    ------
    NoThicknessError
        When it does not stand at ``high`` (e.g. rings that slide on each other with too little
        friction to act together).
    ValueError
        For a bracket out of order.
    """
    from ..errors import NoThicknessError

    if not (0 < low < high and math.isfinite(high)):
        raise ValueError(f"the bracket must have 0 < low < high [m], got {low!r}, {high!r}")

    def stands(thickness: float) -> bool:
        try:
            return assembly_stands(build(thickness))
        except UnsolvedProgramError:  # HiGHS could not solve it: counted as not standing
            return False

    if not stands(high):
        raise NoThicknessError(f"the arch does not stand under its own weight at any thickness "
                               f"up to {high:.6g} m")
    if stands(low):
        return low
    while high - low > rtol * high:
        middle = 0.5 * (low + high)
        if stands(middle):
            high = middle
        else:
            low = middle
    return high
