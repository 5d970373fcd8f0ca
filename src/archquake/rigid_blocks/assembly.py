r"""The blocks and joints of a rigid-block model, and the one adapter from an arch.

An :class:`Assembly` is a planar set of rigid blocks (per unit depth) and of the joints between
them, in the undeformed configuration:

- block ``i``: mass ``m_i`` [kg/m], centroid ``c_i`` [m], polar moment of inertia ``I_i`` about
  the centroid [kg m] and, for drawing only, its outline polygon [m];
- joint ``j``: the two bodies it separates, ``a_j`` and ``b_j`` (block indices, or
  :data:`GROUND` for a support moving with the ground), the two end points ``p_j0``, ``p_j1`` of
  the segment along which they touch [m], and the unit normal ``n_j`` of that segment, pointing
  from body ``a_j`` into body ``b_j``. The tangent ``t_j = (p_j1 - p_j0) / |p_j1 - p_j0|`` is
  ``n_j`` turned by +90 degrees (the Assembly orients the ends so):

.. math::

    t_j = \frac{p_{j1} - p_{j0}}{\lVert p_{j1} - p_{j0} \rVert}
        = \begin{pmatrix} -n_{j,y} \\ n_{j,x} \end{pmatrix}, \qquad
    \mathbf{M} = \operatorname{diag}(m_1, m_1, I_1, \dots, m_{nb}, m_{nb}, I_{nb})

(the mass matrix of the coordinates ``(x_i, y_i, theta_i)`` of the blocks).

Contacts sit at the two ends of every joint (:mod:`archquake.rigid_blocks.dynamics`). Nothing in
the dynamics knows what kind of structure the blocks form: :func:`from_arch` is the only place
that reads an arch (any :class:`archquake.geometry.BlockArch`: its joints are segments and its
blocks have mass properties, whatever their shape), and :func:`rectangular_block` builds
Housner's block on a rigid base [1]_ for checks.

References
----------
.. [1] G. W. Housner, "The behavior of inverted pendulum structures during earthquakes", Bull.
   Seismol. Soc. Am. 53 (1963) 403-417.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..geometry import BlockArch, Structure
from ..geometry.fill import check_dynamic_fill

GROUND = -1
"""Body index of the ground (the supports) [-]; in the frame of the ground it does not move."""

STICK_FRICTION = 100.0
"""Coulomb coefficient [-] with which the solver takes a joint that cannot slide (friction
``inf``): a contact slides only once its tangential impulse exceeds 100 times its normal one
(a friction angle of 89.4 degrees), i.e. not while it carries any load, and Lemke's tableau
(:mod:`archquake.rigid_blocks.lemke`) stays finite."""

FACE_EXTENSION = 0.1
"""Default extension of the face of body a beyond each end of a joint, as a fraction of the
joint's length [-]: a corner that slides a little past the end of the opposite face stays in
contact (the exact contact there, the other corner on this face, differs to second order)."""


def _arc_lengths(chords: np.ndarray, curvature: np.ndarray) -> np.ndarray:
    """Lengths of the minor arcs of signed curvature ``curvature`` [1/m] over ``chords`` [m]
    (the chord where the curvature is 0) [m]."""
    kappa = np.abs(curvature)
    curved = kappa > 0
    out = np.array(chords, dtype=float, copy=True)
    k = kappa[curved]
    out[curved] = 2.0 * np.arcsin(np.minimum(0.5 * k * chords[curved], 1.0)) / k
    return out


def _frozen(array, dtype=float) -> np.ndarray:
    """A contiguous, read-only copy (or view) of ``array`` as ``dtype``."""
    arr = np.ascontiguousarray(array, dtype=dtype)
    arr.setflags(write=False)
    return arr


@dataclass(frozen=True, eq=False)
class Assembly:
    r"""Rigid blocks and joints in the undeformed configuration (SI units, per unit depth).

    Parameters
    ----------
    masses : array of float, shape (nb,)
        Mass of every block [kg/m], > 0.
    centroids : array of float, shape (nb, 2)
        Centroid of every block [m].
    inertias : array of float, shape (nb,)
        Polar moment of inertia of every block about its centroid [kg m], > 0.
    joint_bodies : array of int, shape (nj, 2)
        ``(a_j, b_j)`` of every joint: block indices or :data:`GROUND`; ``a_j != b_j``.
    joint_points : array of float, shape (nj, 2, 2)
        End points ``p_j0, p_j1`` of every joint [m].
    joint_normals : array of float, shape (nj, 2)
        Unit normal of every joint, from body ``a_j`` into body ``b_j`` [-]. If the ends are
        given in the other order, they are swapped so that the tangent ``p_j1 - p_j0`` is the
        normal turned by +90 degrees.
    face_extents : array of float, shape (nj, 2), optional
        The face of body ``a_j`` along the joint, as tangential coordinates from ``p_j0``
        [m]: a contact holds while its point of body ``b_j`` projects inside. Default: the
        joint extended by :data:`FACE_EXTENSION` of its length at each end.
    outlines : tuple of arrays (k_i, 2)
        Closed outline polygon of every block [m], for drawing.
    crown : (int, array of float (2,))
        A block and a point of it [m] whose downward displacement is reported as the "crown
        drop" (for an arch: the top of the extrados).
    thickness : float
        Length scale of the assembly [m], > 0 (for an arch: its mean thickness), to which the
        collapse and rest thresholds of :class:`~archquake.rigid_blocks.dynamics.BlockSettings`
        are scaled.
    name : str
        Description.
    friction : array of float, shape (nj,), optional
        Coulomb coefficient of every joint [-], >= 0 (``inf``: the joint cannot slide, solved
        as :data:`STICK_FRICTION`); None (the default): every joint takes the analysis's
        ``BlockSettings.friction``. Where given, it is used instead of the settings'.
    curvature : array of float, shape (nj,), optional
        Signed curvature of the face of body ``a_j`` along every joint [1/m]: 0 for a flat
        joint (the default for all), > 0 where that face is an arc of a circle whose centre
        lies inside ``a_j`` (convex), < 0 where it lies on the side of ``b_j`` (concave). A
        curved joint is the minor arc through its two end points; its face extents are arc
        lengths (:mod:`archquake.rigid_blocks.contacts`, "Curved faces").
    sources : tuple of tuple of int, optional
        Per joint, the indices of the interfaces of the structure it was built from that it
        stands for (:func:`from_block_assembly`: several for a curved joint); None: joint
        ``j`` is interface ``j``. :meth:`interfaces_of` reads it.

    Raises
    ------
    ValueError
        If a mass or inertia is not finite and > 0, an array has the wrong shape or a
        non-finite entry, a joint pairs a body with itself or an index outside
        ``GROUND .. nb - 1``, a joint has length 0, a normal is not perpendicular to its joint
        (to 1e-9 in the cosine), a face does not contain its joint, the crown block is not a
        block, the thickness is not finite and > 0, a friction coefficient is nan or < 0, or a
        curvature is not finite or too large for its joint (radius at most half the chord).

    Notes
    -----
    The arrays are stored as read-only copies; the normals are normalised to unit length and
    the ends (and face extents) of a joint are swapped where needed so that
    ``t_j = (-n_j,y, n_j,x)``. The default face of body ``a_j`` is

    .. math::

        [\,-\epsilon L_j,\; (1 + \epsilon) L_j\,], \qquad
        L_j = \lVert p_{j1} - p_{j0} \rVert, \quad \epsilon = 0.1

    (:data:`FACE_EXTENSION`).
    """

    masses: np.ndarray
    centroids: np.ndarray
    inertias: np.ndarray
    joint_bodies: np.ndarray
    joint_points: np.ndarray
    joint_normals: np.ndarray
    face_extents: np.ndarray | None = None
    outlines: tuple = ()
    crown: tuple = (0, (0.0, 0.0))
    thickness: float = 1.0
    name: str = ""
    friction: np.ndarray | None = None
    curvature: np.ndarray | None = None
    sources: tuple | None = None
    _cache: dict = field(default_factory=dict, init=False, repr=False, compare=False, hash=False)

    def __post_init__(self):
        masses = _frozen(self.masses)
        nb = masses.size
        if masses.ndim != 1 or nb == 0 or not np.all(np.isfinite(masses)) or np.any(masses <= 0):
            raise ValueError(f"masses must be a non-empty sequence of finite numbers > 0 [kg/m], "
                             f"got {np.asarray(self.masses).tolist()}")
        centroids = _frozen(self.centroids)
        if centroids.shape != (nb, 2) or not np.all(np.isfinite(centroids)):
            raise ValueError(f"centroids must be finite, of shape ({nb}, 2) [m], got shape "
                             f"{centroids.shape}")
        inertias = _frozen(self.inertias)
        if (inertias.shape != (nb,) or not np.all(np.isfinite(inertias))
                or np.any(inertias <= 0)):
            raise ValueError(f"inertias must be {nb} finite numbers > 0 [kg m]")
        bodies = np.array(self.joint_bodies, dtype=np.int64, copy=True)
        nj = bodies.shape[0] if bodies.ndim == 2 else 0
        if bodies.ndim != 2 or bodies.shape[1] != 2 or nj == 0:
            raise ValueError(f"joint_bodies must have shape (nj, 2) with nj >= 1, got "
                             f"{bodies.shape}")
        if np.any(bodies < GROUND) or np.any(bodies >= nb) or np.any(bodies[:, 0] == bodies[:, 1]):
            raise ValueError(f"joint_bodies must pair two different bodies among "
                             f"{GROUND} (ground) .. {nb - 1}, got {bodies.tolist()}")
        points = np.array(self.joint_points, dtype=float, copy=True)
        normals = np.array(self.joint_normals, dtype=float, copy=True)
        if points.shape != (nj, 2, 2) or normals.shape != (nj, 2):
            raise ValueError(f"joint_points must have shape ({nj}, 2, 2) and joint_normals "
                             f"({nj}, 2), got {points.shape} and {normals.shape}")
        if not (np.all(np.isfinite(points)) and np.all(np.isfinite(normals))):
            raise ValueError("joint_points and joint_normals must be finite")
        lengths = np.linalg.norm(points[:, 1] - points[:, 0], axis=1)
        if np.any(lengths <= 0):
            raise ValueError(f"every joint must have two distinct end points; joint "
                             f"{int(np.argmin(lengths))} has length 0")
        normals /= np.linalg.norm(normals, axis=1)[:, None]
        tangents = (points[:, 1] - points[:, 0]) / lengths[:, None]
        cos_angle = np.einsum("ij,ij->i", tangents, normals)
        if np.any(np.abs(cos_angle) > 1e-9):
            j = int(np.argmax(np.abs(cos_angle)))
            raise ValueError(f"joint_normals must be perpendicular to their joints; joint {j} "
                             f"makes {math.degrees(math.acos(np.clip(cos_angle[j], -1, 1))):.6g}"
                             " degrees with its normal")
        # orient the ends so that t = n turned by +90 degrees: t = (-n_y, n_x)
        flip = tangents[:, 0] * -normals[:, 1] + tangents[:, 1] * normals[:, 0] < 0
        points[flip] = points[flip][:, ::-1]
        if self.curvature is None:
            curvature = np.zeros(nj)
        else:
            curvature = np.array(np.broadcast_to(np.asarray(self.curvature, dtype=float), (nj,))
                                 if np.ndim(self.curvature) == 0 else self.curvature, dtype=float)
            if (curvature.shape != (nj,) or not np.all(np.isfinite(curvature))
                    or np.any(0.5 * np.abs(curvature) * lengths >= 1.0)):
                raise ValueError(f"curvature must be {nj} finite numbers [1/m], each with a "
                                 f"radius over half its joint's length, got "
                                 f"{np.asarray(self.curvature).tolist()}")
        lengths = _arc_lengths(lengths, curvature)
        if self.face_extents is None:
            faces = np.column_stack((-FACE_EXTENSION * lengths, (1 + FACE_EXTENSION) * lengths))
        else:
            faces = np.array(self.face_extents, dtype=float, copy=True)
            if faces.shape != (nj, 2) or np.any(np.isnan(faces)):
                raise ValueError(f"face_extents must have shape ({nj}, 2) [m], got "
                                 f"{faces.shape}")
            faces[flip] = lengths[flip, None] - faces[flip][:, ::-1]
            if np.any(faces[:, 0] > 0) or np.any(faces[:, 1] < lengths):
                raise ValueError("face_extents must contain their joints: [lo, hi] with lo <= 0 "
                                 "and hi >= the joint's length [m]")
        crown_block, crown_point = self.crown
        if not (0 <= int(crown_block) < nb):
            raise ValueError(f"crown block must be in 0 .. {nb - 1}, got {crown_block!r}")
        thickness = float(self.thickness)
        if not (math.isfinite(thickness) and thickness > 0):
            raise ValueError(f"thickness must be a finite number > 0 [m], got {self.thickness!r}")
        for name, value in (("masses", masses), ("centroids", centroids),
                            ("inertias", inertias), ("joint_bodies", _frozen(bodies, np.int64)),
                            ("joint_points", _frozen(points)),
                            ("joint_normals", _frozen(normals)),
                            ("face_extents", _frozen(faces)),
                            ("curvature", _frozen(curvature))):
            object.__setattr__(self, name, value)
        object.__setattr__(self, "outlines", tuple(_frozen(o) for o in self.outlines))
        object.__setattr__(self, "crown", (int(crown_block), _frozen(crown_point)))
        object.__setattr__(self, "thickness", thickness)
        if self.sources is not None:
            sources = tuple(tuple(int(i) for i in group) for group in self.sources)
            if len(sources) != nj or any(not group for group in sources):
                raise ValueError(f"sources must give {nj} non-empty groups of interfaces")
            object.__setattr__(self, "sources", sources)
        if self.friction is not None:
            friction = _frozen(np.broadcast_to(np.asarray(self.friction, dtype=float), (nj,))
                               if np.ndim(self.friction) == 0 else self.friction)
            if friction.shape != (nj,) or np.any(np.isnan(friction)) or np.any(friction < 0):
                raise ValueError(f"friction must be None or {nj} Coulomb coefficients >= 0 [-] "
                                 f"(inf: no sliding), got {np.asarray(self.friction).tolist()}")
            object.__setattr__(self, "friction", friction)

    @property
    def n_blocks(self) -> int:
        """Number of blocks nb [-]."""
        return int(self.masses.size)

    @property
    def n_joints(self) -> int:
        """Number of joints nj [-] (each with two contacts)."""
        return int(self.joint_bodies.shape[0])

    @property
    def total_mass(self) -> float:
        """Mass of all blocks [kg/m]."""
        return float(self.masses.sum())

    @property
    def height(self) -> float:
        """Height of the highest block centroid above the lowest end of a joint with the
        ground [m] (above the lowest centroid if no block rests on the ground), at least the
        thickness: the length whose free-fall time ``sqrt(height / g)`` sets the time scale of
        the structure's motion."""
        on_ground = (self.joint_bodies == GROUND).any(axis=1)
        if on_ground.any():
            base = float(self.joint_points[on_ground][:, :, 1].min())
        else:
            base = float(self.centroids[:, 1].min())
        return max(float(self.centroids[:, 1].max()) - base, self.thickness)

    @property
    def joint_lengths(self) -> np.ndarray:
        """Length of every joint [m]."""
        return np.linalg.norm(self.joint_points[:, 1] - self.joint_points[:, 0], axis=1)

    def interfaces_of(self, joints) -> tuple[int, ...]:
        """The structure's interfaces that the joints ``joints`` stand for, sorted
        (:attr:`sources`; the joints themselves where it is None)."""
        if self.sources is None:
            return tuple(sorted(int(j) for j in joints))
        return tuple(sorted({i for j in joints for i in self.sources[int(j)]}))

    @property
    def arc_lengths(self) -> np.ndarray:
        """Length of every joint's face along its arc [m] (its chord where it is flat)."""
        return _arc_lengths(self.joint_lengths, self.curvature)

    def end_normals(self) -> np.ndarray:
        """The normal of the face of body ``a_j`` at each end of every joint, shape (nj, 2, 2)
        [-]: the joint's normal where it is flat, the radial one (out of the centre where the
        face is convex, into it where concave) where it is curved."""
        normals = np.repeat(self.joint_normals[:, None, :], 2, axis=1)
        curved = self.curvature != 0
        if curved.any():
            points, kappa = self.joint_points[curved], self.curvature[curved]
            side, radius = np.sign(kappa), 1.0 / np.abs(kappa)
            half = 0.5 * self.joint_lengths[curved]
            middle = points.mean(axis=1)
            offset = side * np.sqrt(radius**2 - half**2)
            centre = middle - offset[:, None] * self.joint_normals[curved]
            normals[curved] = (side / radius)[:, None, None] * (points - centre[:, None, :])
        return normals


def from_arch(arch: BlockArch) -> Assembly:
    """The rigid-block model of an arch: its voussoirs on two supports that move with the ground.

    This is the only function of :mod:`archquake.rigid_blocks` that reads an arch, through the
    contract of every :class:`~archquake.geometry.BlockArch` (circular, of any shape, surveyed).
    Joint ``j`` (``0 .. n``) separates voussoir ``j - 1`` (the left support, :data:`GROUND`, for
    ``j = 0``) from voussoir ``j`` (the right support for ``j = n``); its contact segment is the
    arch's joint ``arch.joints[j]`` (intrados end first) and its normal
    ``arch.joint_normals[j]``, from voussoir ``j - 1`` into voussoir ``j``. The crown point is
    the top of the extrados (:meth:`~archquake.geometry.BlockArch.crown`); the length scale is
    the arch's mean thickness (:attr:`~archquake.geometry.BlockArch.thickness_scale`).

    A :class:`~archquake.geometry.Structure` is read the same way: its blocks are the courses of
    its piers and its voussoirs, joint 0 is the left pier's base on the ground and joint ``n``
    the right pier's, and a voussoir that carries fill carries it as part of its own mass,
    centroid and moment of inertia (the fill's ``"centroid"`` model); its crown and thickness
    are the arch's.

    Parameters
    ----------
    arch : BlockArch
        The arch: any :class:`~archquake.geometry.BlockArch` of ``n`` voussoirs (masses
        [kg/m], centroids [m], inertias [kg m], joints [m] and unit normals [-]).

    Returns
    -------
    Assembly
        ``n`` blocks and ``n + 1`` joints, named ``"arch of n voussoirs"`` (a structure: its
        description).

    Raises
    ------
    ValueError
        If the arch's data do not make a valid :class:`Assembly`, or it carries fill whose
        inertia model is not ``"centroid"`` (the fill is then no mass).
    """
    check_dynamic_fill(arch)
    n = arch.n_voussoirs
    bodies = np.column_stack((np.arange(-1, n), np.arange(0, n + 1)))
    bodies[-1, 1] = GROUND
    crown_block, crown_point = arch.crown()
    return Assembly(
        masses=arch.masses, centroids=arch.centroids, inertias=arch.inertias,
        joint_bodies=bodies, joint_points=arch.joints, joint_normals=arch.joint_normals,
        outlines=tuple(arch.outline(i) for i in range(n)),
        crown=(crown_block, crown_point), thickness=arch.thickness_scale,
        name=arch.describe() if isinstance(arch, Structure) else f"arch of {n} voussoirs",
    )


def rectangular_block(width: float, height: float, density: float = 2000.0) -> Assembly:
    r"""Housner's rigid block: a ``width`` x ``height`` rectangle standing on a rigid base.

    The block's base ``(-width/2, 0) .. (width/2, 0)`` is one joint against the ground (normal
    +y) [1]_, whose face reaches 100 widths beyond the block on either side (so that the block may
    slide); its centroid is ``(0, height/2)``; the crown point is the top of its left side, the
    length scale its width. Per unit depth, with :math:`\rho` the density, :math:`b` the width
    and :math:`h` the height:

    .. math::

        m = \rho\,b\,h, \qquad I = \frac{m\,(b^2 + h^2)}{12}, \qquad
        \tan\alpha = \frac{b}{h}

    (:math:`\alpha` is the slenderness angle of [1]_).

    Parameters
    ----------
    width, height : float
        Size of the block [m], > 0.
    density : float
        Density [kg/m^3], > 0.

    Returns
    -------
    Assembly
        One block [kg/m, m, kg m] and one joint against :data:`GROUND`.

    Raises
    ------
    ValueError
        If ``width``, ``height`` or ``density`` is not a finite number > 0.

    References
    ----------
    .. [1] G. W. Housner, "The behavior of inverted pendulum structures during earthquakes",
       Bull. Seismol. Soc. Am. 53 (1963) 403-417.

    Examples
    --------
    >>> block = rectangular_block(0.2, 1.0)
    >>> block.n_blocks, block.n_joints, round(block.total_mass, 6)
    (1, 1, 400.0)
    """
    for name, value in (("width", width), ("height", height), ("density", density)):
        if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
            raise ValueError(f"{name} must be a finite number > 0, got {value!r}")
    b, h = 0.5 * width, float(height)
    mass = density * width * height
    outline = np.array([[-b, 0.0], [b, 0.0], [b, h], [-b, h], [-b, 0.0]])
    return Assembly(
        masses=[mass], centroids=[[0.0, 0.5 * h]], inertias=[mass * (width**2 + h**2) / 12.0],
        joint_bodies=[[GROUND, 0]], joint_points=[[[-b, 0.0], [b, 0.0]]],
        joint_normals=[[0.0, 1.0]], face_extents=[[-100.0 * width, 101.0 * width]],
        outlines=(outline,), crown=(0, (-b, h)),
        thickness=float(width), name=f"rectangular block {width:g} m x {height:g} m",
    )


def from_block_assembly(blocks, *, thickness: float | None = None, arcs: bool = True) -> Assembly:
    r"""The rigid-block model of a general block assembly (a wall, a stack, any planar set of
    blocks on fixed supports).

    Reads, duck-typed, the attributes of :class:`archquake.geometry.assembly.BlockAssembly`:
    ``polygons`` (every block's outline [m]), ``mass`` [kg/m], ``centroid`` [m], ``inertia``
    [kg m], and its ``interfaces``: ``a``, ``b`` (bodies, ``-1`` for a support), ``p0``,
    ``p1`` (ends [m]), ``normal`` (from a into b [-]) and ``friction`` (Coulomb coefficient
    of every interface [-], ``inf``: no sliding), and ``kind``. Interface ``j`` becomes joint
    ``j`` (the solver renumbers the joints for a small bandwidth and gives every result back in
    this order: :func:`archquake.rigid_blocks.dynamics.joint_order`), but for the chords of a
    ring interface between two blocks, which become one curved joint where they lie on a
    circle (:func:`curved_joints`).

    Two choices that an arch makes by its shape are made here for any assembly:

    - the **crown** (the point whose drop is reported, ``max_crown_drop``) is the top of the
      highest block, among those whose top is highest (to 1e-9 of the assembly's height) the
      one whose centroid is nearest the middle of the assembly's width: for a wall, the middle
      of its top course (any block's centroid falling by ``collapse_drop`` thicknesses is a
      collapse whatever the crown);
    - the **thickness** (the length scale of the collapse and rest thresholds and of the
      default time step, :func:`~archquake.rigid_blocks.dynamics.structure_time_step`) is,
      unless given, the median over the blocks of the shorter side of each block's bounding
      box: for a wall of bricks laid flat, the height of a course (a brick falling by one course
      is a collapse; a contact closing at :math:`\sqrt{g t}` sinks by 1 % of a course in a
      step).

    Parameters
    ----------
    blocks : BlockAssembly
        The assembly (or any object with the attributes above).
    thickness : float, optional
        Length scale [m], > 0 (default: above).
    arcs : bool
        Make the chains of ring chords on a circle curved joints (:func:`curved_joints`); False
        keeps every chord a joint of its own (to compare the two).

    Returns
    -------
    Assembly
        ``n_blocks`` blocks and one joint per interface (per chain of ring chords on a circle),
        with the interfaces' friction
        (:attr:`Assembly.friction`), or none where the assembly gives none (its ``friction``
        None): the model's settings then give it.

    Raises
    ------
    ValueError
        If an attribute is missing, or the data do not make a valid :class:`Assembly`.
    """
    check_dynamic_fill(blocks)  # an assembly under fill carries it as mass
    try:
        polygons = [np.asarray(p, dtype=float) for p in blocks.polygons]
        masses, centroids = blocks.mass, blocks.centroid
        inertias, interfaces = blocks.inertia, blocks.interfaces
        a, b = np.asarray(interfaces.a), np.asarray(interfaces.b)
        p0, p1 = np.asarray(interfaces.p0, float), np.asarray(interfaces.p1, float)
        normals, friction = interfaces.normal, interfaces.friction
    except AttributeError as exc:
        raise ValueError(f"blocks must be a block assembly (polygons, mass, centroid, inertia, "
                         f"interfaces a/b/p0/p1/normal/friction): {exc}") from exc
    if not polygons:
        raise ValueError("blocks must hold at least one block")
    tops = np.array([p[:, 1].max() for p in polygons])
    lows = np.array([p[:, 1].min() for p in polygons])
    left = min(p[:, 0].min() for p in polygons)
    right = max(p[:, 0].max() for p in polygons)
    centroids = np.asarray(centroids, dtype=float)
    span = max(float(tops.max() - lows.min()), 1e-300)
    highest = np.flatnonzero(tops >= tops.max() - 1e-9 * span)
    crown = int(highest[np.argmin(np.abs(centroids[highest, 0] - 0.5 * (left + right)))])
    if thickness is None:
        sides = [min(np.ptp(p[:, 0]), np.ptp(p[:, 1])) for p in polygons]
        thickness = float(np.median(sides))
    kinds = np.asarray(getattr(interfaces, "kind", np.full(a.size, "")))
    joints = curved_joints(a, b, p0, p1, np.asarray(normals, dtype=float),
                           np.asarray(friction, dtype=float), (kinds == "ring") & arcs)
    a, b, p0, p1, normals, friction, curvature, members = joints
    points = np.stack((p0, p1), axis=1) if p0.size else np.zeros((0, 2, 2))
    return Assembly(
        masses=masses, centroids=centroids, inertias=inertias,
        joint_bodies=np.column_stack((a, b)), joint_points=points, joint_normals=normals,
        outlines=tuple(np.vstack((p, p[:1])) for p in polygons),
        crown=(crown, (centroids[crown, 0], tops[crown])), thickness=thickness,
        friction=None if getattr(blocks, "friction", 0.0) is None else friction,
        curvature=curvature, sources=members,
        name=f"assembly of {len(polygons)} blocks and {interfaces.a.size} interfaces",
    )


CIRCLE_TOLERANCE = 1e-3
"""Largest distance of a chain of chords' corners from the circle through its ends and its
middle corner, relative to the chain's chord, for the chain to be taken as an arc of that
circle by :func:`curved_joints` [-]."""

MAX_CHORD_TURN = math.radians(30.0)
"""Largest turn of the normal between two consecutive chords of a chain taken as an arc [rad]."""


def _circle(p, q, r):
    """Centre [m] and radius [m] of the circle through three points (None if collinear)."""
    d = 2.0 * ((q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]))
    if d == 0.0:
        return None
    pq, pr = np.dot(q, q) - np.dot(p, p), np.dot(r, r) - np.dot(p, p)
    centre = np.array([(pq * (r[1] - p[1]) - pr * (q[1] - p[1])) / d,
                       (pr * (q[0] - p[0]) - pq * (r[0] - p[0])) / d])
    return centre, float(np.linalg.norm(p - centre))


def _chains(indices, p0, p1, scale):
    """The interfaces ``indices`` (of one pair of bodies) as chains, each a list of indices
    in which every interface starts where the one before ends (to 1e-9 of ``scale``)."""
    key = lambda point: (round(point[0] / (1e-9 * scale)), round(point[1] / (1e-9 * scale)))  # noqa: E731
    starting = {key(p0[i]): i for i in indices}
    ending = {key(p1[i]) for i in indices}
    chains, seen = [], set()
    for first in indices:
        if key(p0[first]) in ending:
            continue  # not the start of a chain
        chain = [first]
        while (nxt := starting.get(key(p1[chain[-1]]))) is not None and nxt not in chain:
            chain.append(nxt)
        chains.append(chain)
        seen.update(chain)
    chains.extend([i] for i in indices if i not in seen)  # a closed loop: left as chords
    return chains


def _arc_of(chain, p0, p1, normals):
    """The signed curvature [1/m] of the arc a chain of chords lies on (0: none, it stays as
    chords): the circle through its ends and its middle corner, if every corner is within
    :data:`CIRCLE_TOLERANCE` of the chain's chord of it, every turn of the normal between two
    chords has the same sign and is below :data:`MAX_CHORD_TURN`, and the arc is shorter than
    a half circle."""
    if len(chain) < 2:
        return 0.0
    corners = np.vstack([p0[chain], p1[chain[-1:]]])
    start, end = corners[0], corners[-1]
    chord = float(np.linalg.norm(end - start))
    n0, n1 = normals[chain[:-1]], normals[chain[1:]]
    turns = np.arcsin(np.clip(n0[:, 0] * n1[:, 1] - n0[:, 1] * n1[:, 0], -1.0, 1.0))
    if (chord == 0.0 or np.any(np.abs(turns) >= MAX_CHORD_TURN)
            or not (np.all(turns > 0) or np.all(turns < 0))):
        return 0.0
    apex = corners[len(corners) // 2]
    circle = _circle(start, apex, end)
    if circle is None:
        return 0.0
    centre, radius = circle
    middle = 0.5 * (start + end)
    if (np.max(np.abs(np.linalg.norm(corners - centre, axis=1) - radius))
            > CIRCLE_TOLERANCE * chord or np.dot(apex - middle, centre - middle) >= 0):
        return 0.0  # not on the circle, or on its major arc
    # convex face of body a (> 0) where its centre lies on the side of a, against the normal
    side = -1.0 if np.dot(centre - middle, normals[chain[0]]) > 0 else 1.0
    return side / radius


def curved_joints(a, b, p0, p1, normals, friction, ring):
    r"""The joints of an assembly's interfaces, with every chain of ring chords between the
    same two blocks that lies on a circle made one curved joint.

    A curved interface (two rings of an arch touching along an arc) is given as chords. Cut
    so, every chord's end is a contact, the contacts of one interface outnumber the relative
    motions of its two blocks many times over, and the rings cannot slide on each other
    without opening at every corner (:mod:`archquake.rigid_blocks.contacts`, "Curved
    faces"). The arc itself, with a contact at each end, holds exactly what the whole arc
    holds. A chain is the chords ``i`` (``ring[i]``) between one pair of bodies, each starting
    where the one before ends; it is taken as the arc of the circle through its ends and its
    middle corner where every corner lies within :data:`CIRCLE_TOLERANCE` times the chain's
    chord of it (a chain of chords of a circle: to round-off), the chords all turn the same
    way by less than :data:`MAX_CHORD_TURN`, the arc is shorter than a half circle and its
    chords have one friction coefficient. Any other interface is kept as it is.

    Parameters
    ----------
    a, b : array of int (ni,)
        The two bodies of every interface.
    p0, p1 : array of float (ni, 2)
        Its ends [m], ``p1 - p0`` the normal turned by +90 degrees.
    normals : array of float (ni, 2)
        Its unit normal from body a into body b [-].
    friction : array of float (ni,)
        Its Coulomb coefficient [-].
    ring : array of bool (ni,)
        Whether it is a chord of a ring interface.

    Returns
    -------
    tuple of arrays
        ``(a, b, p0, p1, normals, friction, curvature, members)`` of the joints: an arc's
        joint at the place of its first chord, from the chain's first end to its last, with
        the normal of that chord between them and the arc's signed curvature [1/m] (0 for the
        others); ``members``, per joint the indices of the interfaces it stands for.
    """
    ni = a.size
    keep = np.ones(ni, dtype=bool)
    members = [(i,) for i in range(ni)]
    q0, q1 = p0.copy(), p1.copy()
    normal, curvature = normals.copy(), np.zeros(ni)
    scale = max(float(np.abs(np.concatenate([p0, p1])).max()), 1.0) if ni else 1.0
    pairs = {}
    for i in np.flatnonzero(ring):
        pairs.setdefault((int(a[i]), int(b[i])), []).append(int(i))
    for indices in pairs.values():
        for chain in _chains(indices, p0, p1, scale):
            same = np.all(friction[chain] == friction[chain[0]])
            kappa = _arc_of(chain, p0, p1, normals) if same else 0.0
            if kappa == 0.0:
                continue
            first = chain[0]
            q1[first] = p1[chain[-1]]
            tangent = (q1[first] - q0[first]) / np.linalg.norm(q1[first] - q0[first])
            normal[first] = (tangent[1], -tangent[0])  # the tangent is the normal turned +90
            curvature[first] = kappa
            members[first] = tuple(chain)
            keep[chain[1:]] = False
    return (a[keep], b[keep], q0[keep], q1[keep], normal[keep], friction[keep],
            curvature[keep], tuple(m for m, k in zip(members, keep, strict=True) if k))
