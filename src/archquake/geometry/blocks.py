r"""The contract every step of archquake reads: an arch as rigid blocks and the joints between them.

An arch is a sequence of ``n`` rigid blocks (voussoirs) between two fixed springings, numbered
left to right ``0 .. n-1``, and a sequence of ``n + 1`` joints numbered ``0 .. n``: joint 0 is
the contact of voussoir 0 with the left support, joint ``n`` that of voussoir ``n-1`` with the
right support, and joint ``j`` in between is the contact of voussoirs ``j-1`` and ``j``.

- Each block is a planar region with exact mass properties per unit depth: mass ``m_i``
  [kg/m], centroid ``g_i`` [m] and polar moment of inertia ``I_i`` about the centroid
  [kg m] (:mod:`archquake.geometry.mass`).
- Each joint is a segment, the part of the boundary two neighbours (or a voussoir and a support)
  share, given by its two ends: the *intrados end* ``p_in`` and the *extrados end*
  ``p_out`` [m]. Its unit normal :math:`\mathbf n_j` points along the arch, from voussoir
  ``j-1`` (or the left support) into voussoir ``j`` (or the right support), and the ends are
  ordered so that :math:`\mathbf p_{out} - \mathbf p_{in}` is :math:`\mathbf n_j` turned by
  +90 degrees: for an arch standing over its span, the intrados end is the inner (lower) one.
- A hinge forms at an end of a joint (:class:`Hinge`): on the intrados face at ``p_in``, on
  the extrados face at ``p_out``.
- The *progressive angle* of a joint (:attr:`BlockArch.joint_angles`) is the direction of the
  joint from its intrados to its extrados end, measured as the paper measures the radial joints
  of a circular arch: a joint along :math:`(-\cos\beta, \sin\beta)` has angle :math:`\beta`
  (polar angle :math:`\pi - \beta`). For the radial joints of a circle it is the paper's
  progressive angle of the joint.

The classes that keep this contract: :class:`~archquake.geometry.CircularArch` (the paper's circular
arch of annular sectors with radial joints), :class:`~archquake.geometry.ShapedArch` (any shape
by its centreline) and :class:`~archquake.geometry.SurveyedArch` (block polygons).
"""

from __future__ import annotations

import json
import math
import numbers
from abc import ABC, abstractmethod
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..checks import json_loads
from .loads import BlockLoads

MIN_VOUSSOIRS = 4
"""Fewest voussoirs of an arch [-]: a four-hinge mechanism needs at least three blocks plus one
hinge-free joint choice; with fewer than four voussoirs the hinges cannot form at four distinct
joints with three moving blocks."""

MAX_VOUSSOIRS = 10_000
"""Most voussoirs of an arch. The static limit analysis (a sparse linear program of 3n + 4
unknowns) takes about a second for 10 000 voussoirs and grows faster than n (a minute for
100 000); convergence studies need a few hundred (the semicircle's minimum thickness, t/R =
0.1075, is reached to 1e-4 with 200)."""

LENGTH_RANGE = (1e-3, 1e4)
"""Accepted sizes of an arch [m] (radii, spans, rises): from a millimetre to ten kilometres. Far
outside, floating-point numbers lose the arch (at 1e300 m a 1.5 m thickness vanishes beside the
radius, at 1e-300 m the masses underflow)."""

DENSITY_RANGE = (1.0, 1e5)
"""Accepted densities of the masonry [kg/m^3], for every arch, however it is built or read:
from the density of air to four times that of the densest solid (osmium, 22 590 kg/m^3).
Outside, the numbers are not of masonry and the masses and forces of the dynamic models
overflow or underflow (a density of 1e-300 gives masses of zero)."""


def check_density(value, name: str = "density") -> float:
    """``value`` as a float in :data:`DENSITY_RANGE` [kg/m^3], or a ValueError naming ``name``
    and the range.

    Examples
    --------
    >>> check_density(2000)
    2000.0
    >>> check_density(1e300)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: density must be a number in [1, 100000] kg/m^3 (...), got 1e+300
    """
    low, high = DENSITY_RANGE
    try:
        density = float(value)
    except (TypeError, ValueError):
        density = math.nan
    if isinstance(value, bool) or not low <= density <= high:
        raise ValueError(f"{name} must be a number in [{low:g}, {high:g}] kg/m^3 (air to four "
                         f"times osmium), got {value!r}")
    return density


MAX_GEOMETRY_FILE_BYTES = 64 * 2**20
"""Largest geometry file read [bytes]: far above a file of :data:`MAX_VOUSSOIRS` voussoirs."""

FACES = ("intrados", "extrados")
"""The two faces of a joint a hinge can form on: the inner and the outer end of its contact."""


def check_voussoir_count(count, name: str = "voussoirs") -> int:
    """``count`` as an int in [:data:`MIN_VOUSSOIRS`, :data:`MAX_VOUSSOIRS`], or a ValueError
    naming ``name``."""
    try:  # an integer too large for a float is too many voussoirs, not an OverflowError
        whole = isinstance(count, numbers.Integral) or float(count).is_integer()
    except (TypeError, ValueError, OverflowError):
        whole = False
    if isinstance(count, bool) or not whole:
        raise ValueError(f"{name} must be an integer >= {MIN_VOUSSOIRS}, got {count!r}")
    n = int(count)
    if n < MIN_VOUSSOIRS:
        raise ValueError(f"{name} must be >= {MIN_VOUSSOIRS} for a four-hinge mechanism, got {n}")
    if n > MAX_VOUSSOIRS:
        raise ValueError(f"{name} must be at most {MAX_VOUSSOIRS} (MAX_VOUSSOIRS), got {n}")
    return n


def real_number(name: str, value, unit: str) -> float:
    """``value`` as a float, or a ValueError naming ``name`` for anything but a real number: a
    bool (``True`` is not 1 m), a text (``"3"``) or a complex number are refused, not converted.

    >>> real_number("width", 3, "m")
    3.0
    >>> real_number("width", True, "m")
    Traceback (most recent call last):
    ...
    ValueError: width must be a number [m], got True
    """
    if isinstance(value, bool | np.bool_ | str | bytes | complex | np.complexfloating):
        raise ValueError(f"{name} must be a number [{unit}], got {value!r}")
    try:
        return float(value)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be a number [{unit}], got {value!r}") from exc


def check_length(name: str, value) -> float:
    """``value`` [m] as a float in :data:`LENGTH_RANGE`, or a ValueError naming ``name``."""
    value = real_number(name, value, "m")
    if not math.isfinite(value) or value <= 0.0:
        raise ValueError(f"{name} must be a finite number > 0 [m], got {value!r}")
    if not LENGTH_RANGE[0] <= value <= LENGTH_RANGE[1]:
        raise ValueError(f"{name} must be in [{LENGTH_RANGE[0]:g}, {LENGTH_RANGE[1]:g}] m "
                         f"(LENGTH_RANGE), got {value:g} m")
    return value


def is_json_number(value) -> bool:
    """Whether a value read from JSON is a number (``true``/``false`` are not)."""
    return isinstance(value, int | float) and not isinstance(value, bool)


def check_json_numbers(key: str, value, depth: int) -> None:
    """Refuse anything but numbers in nested lists ``depth`` deep read from JSON (``true`` or
    ``"1.5"`` are refused, not converted), naming the key and the item."""
    if depth == 0:
        if not is_json_number(value):
            raise ValueError(f"geometry key '{key}' has {json_text(value)} where a number is "
                             "expected")
        return
    if not isinstance(value, list):
        raise ValueError(f"geometry key '{key}' must be a list, got {json_text(value)}")
    for item in value:
        check_json_numbers(key, item, depth - 1)


def json_text(value) -> str:
    """A value read from JSON as JSON text, for messages."""
    text = json.dumps(value)
    return text if len(text) <= 40 else text[:37] + "..."


def read_json_file(path: str | Path, expected: str):
    """The JSON value of a geometry file: UTF-8, at most :data:`MAX_GEOMETRY_FILE_BYTES`.

    Parameters
    ----------
    path : str or pathlib.Path
        The file.
    expected : str
        What the file should hold, for the message about an empty file.

    Raises
    ------
    ValueError
        Naming the file: unreadable, a directory, too large, not UTF-8, empty or not JSON (with
        the line).
    """
    path = Path(path)
    where = f"geometry file {str(path)!r}"
    try:
        if path.is_dir():
            raise ValueError(f"{where} is a directory, not a JSON file")
        size = path.stat().st_size
        if size > MAX_GEOMETRY_FILE_BYTES:
            raise ValueError(f"{where} has {size} bytes, more than the "
                             f"{MAX_GEOMETRY_FILE_BYTES} read (an arch has at most "
                             f"{MAX_VOUSSOIRS} voussoirs)")
        text = path.read_text(encoding="utf-8")
    except OSError as exc:
        raise ValueError(f"cannot read {where}: {exc.strerror}") from exc
    except UnicodeDecodeError as exc:
        raise ValueError(f"{where} is not UTF-8 text (byte {exc.object[exc.start]:#04x} at "
                         f"position {exc.start}); save it as UTF-8 JSON") from exc
    if not text.strip():
        raise ValueError(f"{where} is empty; expected {expected}")
    try:
        return json_loads(text)
    except json.JSONDecodeError as exc:
        raise ValueError(f"{where} is not valid JSON: {exc.msg} (line {exc.lineno})") from exc
    except ValueError as exc:  # a key given twice, NaN, a nesting too deep
        raise ValueError(f"{where} is not valid JSON: {exc}") from exc


def polygon_vertices(name: str, vertices, check=None) -> np.ndarray:
    """``vertices`` as a (k, 2) float array [m], consecutive repeats and a repeated first vertex
    dropped, or a ValueError naming ``name``: not a list of points, a coordinate not finite,
    fewer than three distinct vertices. ``check(name, v)``, if given, checks the parsed points
    further before the repeats are dropped."""
    try:
        v = np.array(vertices, dtype=float)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be a list of [x, y] points [m]") from exc
    if v.ndim != 2 or v.shape[1] != 2:
        raise ValueError(f"{name} must be a list of [x, y] points [m], got shape {v.shape}")
    if not np.all(np.isfinite(v)):
        raise ValueError(f"{name} has a coordinate that is not a finite number")
    if check is not None:
        check(name, v)
    keep = np.ones(len(v), dtype=bool)
    keep[1:] = np.any(v[1:] != v[:-1], axis=1)  # consecutive duplicates
    v = v[keep]
    if len(v) > 1 and np.all(v[0] == v[-1]):
        v = v[:-1]
    if len(v) < 3:
        raise ValueError(f"{name} must have at least three distinct vertices, got {len(v)}")
    return v


def float_array(name: str, values) -> np.ndarray:
    """``values`` as a one-dimensional float array (a copy), or a ValueError naming ``name``."""
    try:
        arr = np.array(values, dtype=float)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be a sequence of numbers, got {values!r}") from exc
    if arr.ndim != 1:
        raise ValueError(f"{name} must be a one-dimensional sequence, got shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} must contain only finite numbers, got {arr.tolist()}")
    return arr


def frozen_array(array) -> np.ndarray:
    """A read-only, contiguous float copy of ``array``."""
    arr = np.array(array, dtype=float, order="C")
    arr.setflags(write=False)
    return arr


class BlockArch(ABC):
    """Any arch: ``n`` rigid blocks between two springings and ``n + 1`` joints.

    Subclasses give the joints (:meth:`_joints`), the mass properties (:meth:`_mass_properties`),
    the outlines, the mirror image and a dictionary description; everything else follows. A
    subclass is a frozen dataclass with a ``_cache`` dict field that does not take part in
    comparisons.
    """

    density: float

    # ------------------------------------------------------------------ what a subclass gives
    @property
    @abstractmethod
    def n_voussoirs(self) -> int:
        """Number of voussoirs n [-]."""

    @abstractmethod
    def _joints(self) -> np.ndarray:
        """Ends ``(p_in, p_out)`` of every joint [m], shape (n+1, 2, 2)."""

    @abstractmethod
    def _mass_properties(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(masses (n,) [kg/m], centroids (n, 2) [m], inertias (n,) [kg m])``."""

    @abstractmethod
    def outline(self, i: int, points: int = 24) -> np.ndarray:
        """Closed outline polygon of voussoir ``i`` [m], the first vertex repeated at the end."""

    @abstractmethod
    def mirrored(self) -> BlockArch:
        """The arch mirrored about the vertical axis x = 0 (voussoir i of the mirror is voussoir
        n-1-i of this arch)."""

    @abstractmethod
    def to_dict(self) -> dict:
        """A JSON-ready description from which :func:`archquake.geometry.arch_from_dict` builds
        this arch again."""

    # ------------------------------------------------------------------ joints
    def _cached(self, key, compute):
        cache = self._cache  # type: ignore[attr-defined]
        if key not in cache:
            cache[key] = compute()
        return cache[key]

    @property
    def joints(self) -> np.ndarray:
        """Ends ``(p_in, p_out)`` of every joint ``j = 0 .. n`` [m], shape (n+1, 2, 2)."""
        return self._cached("joints", lambda: frozen_array(self._joints()))

    @property
    def joint_lengths(self) -> np.ndarray:
        """Length ``|p_out - p_in|`` of every joint's contact [m], shape (n+1,)."""
        return self._cached("joint_lengths", lambda: frozen_array(
            np.hypot(*(self.joints[:, 1] - self.joints[:, 0]).T)))

    @property
    def joint_directions(self) -> np.ndarray:
        """Unit vector from the intrados to the extrados end of every joint [-], (n+1, 2)."""
        return self._cached("joint_directions", lambda: frozen_array(
            (self.joints[:, 1] - self.joints[:, 0]) / self.joint_lengths[:, None]))

    @property
    def joint_normals(self) -> np.ndarray:
        """Unit normal of every joint, from voussoir j-1 into voussoir j [-], (n+1, 2): the
        joint's direction turned by -90 degrees."""
        e = self.joint_directions
        return self._cached("joint_normals",
                            lambda: frozen_array(np.column_stack((e[:, 1], -e[:, 0]))))

    @property
    def joint_angles(self) -> np.ndarray:
        r"""Progressive angle :math:`\beta_j` of every joint j = 0..n [rad]: the joint runs from
        its intrados to its extrados end along :math:`(-\cos\beta_j, \sin\beta_j)`; unwrapped
        left to right, starting in :math:`(-\pi, \pi]`."""
        e = self.joint_directions
        return self._cached("joint_angles", lambda: frozen_array(np.unwrap(np.arctan2(e[:, 1],
                                                                                 -e[:, 0]))))

    def hinge_point(self, joint: int, face: str) -> np.ndarray:
        """Position (x, y) [m] of a hinge on ``face`` (``"intrados"`` or ``"extrados"``) of
        ``joint``: the corresponding end of the joint's contact."""
        if face not in FACES:
            raise ValueError(f"face must be one of {FACES}, got {face!r}")
        return self.joints[joint, FACES.index(face)].copy()

    # ------------------------------------------------------------------ mass properties
    @property
    def masses(self) -> np.ndarray:
        """Mass m_i of every voussoir per unit depth [kg/m]."""
        return self._cached("mass", self._frozen_mass_properties)[0]

    @property
    def centroids(self) -> np.ndarray:
        """Centroid (x, y) of every voussoir [m], shape (n, 2)."""
        return self._cached("mass", self._frozen_mass_properties)[1]

    @property
    def inertias(self) -> np.ndarray:
        """Polar moment of inertia of every voussoir about its centroid, per unit depth [kg m]."""
        return self._cached("mass", self._frozen_mass_properties)[2]

    def _frozen_mass_properties(self):
        return tuple(frozen_array(a) for a in self._mass_properties())

    @property
    def total_mass(self) -> float:
        """Mass of the whole arch per unit depth [kg/m]."""
        return float(self.masses.sum())

    @property
    def loads(self) -> BlockLoads:
        r"""The loads of every block in the limit analysis (:mod:`archquake.geometry.loads`):
        for an arch of bare masonry its weight :math:`m_i g` and the horizontal load
        :math:`k\,m_i g`, both through the centroid; a structure with fill adds the fill's
        (:class:`~archquake.geometry.Structure`)."""
        return self._cached("loads", self._loads)

    def _loads(self) -> BlockLoads:
        return BlockLoads.of_masses(self.masses, self.centroids)

    # ------------------------------------------------------------------ scales
    @property
    def reference_point(self) -> np.ndarray:
        """A point near the arch [m] about which the limit analysis takes moments (the mean of
        the centroids)."""
        return self._cached("reference", lambda: frozen_array(self.centroids.mean(axis=0)))

    @property
    def length_scale(self) -> float:
        """Size of the arch [m]: the largest distance of a joint end from
        :attr:`reference_point` (the limit analysis works in this unit)."""
        return self._cached("length", lambda: float(np.max(np.hypot(
            *(self.joints.reshape(-1, 2) - self.reference_point).T))))

    @property
    def thickness_scale(self) -> float:
        """Mean depth of the joints [m] (a thickness of the arch, for thresholds)."""
        return float(np.mean(self.joint_lengths))

    def crown(self) -> tuple[int, np.ndarray]:
        """The voussoir and the point of its outline [m] that stand highest (the top of the
        extrados), the first one from the left if several do."""
        best, point = 0, None
        for i in range(self.n_voussoirs):
            outline = self.outline(i, 64)
            top = outline[int(np.argmax(outline[:, 1]))]
            if point is None or top[1] > point[1] + 1e-12 * self.length_scale:
                best, point = i, top
        return best, point

    # ------------------------------------------------------------------ symmetry
    def is_symmetric(self, atol: float = 1e-12) -> bool:
        """True when the arch equals its mirror image about the vertical axis.

        Parameters
        ----------
        atol : float, default 1e-12
            Absolute tolerance [m] on every joint end and centroid, relative to
            :attr:`length_scale`, and on the masses relative to the mean mass.
        """
        m = self.mirrored()
        scale = self.length_scale
        return bool(
            np.allclose(self.joints, m.joints, atol=atol * scale, rtol=0)
            and np.allclose(self.centroids, m.centroids, atol=atol * scale, rtol=0)
            and np.allclose(self.masses, m.masses, atol=atol * float(np.mean(self.masses)),
                            rtol=0)
        )


@dataclass(frozen=True)
class Hinge:
    """A hinge of a mechanism: a joint of an arch and the face of the joint it forms on.

    Parameters
    ----------
    joint : int
        Joint index j [-] (0 = left springing .. n = right springing).
    face : {"intrados", "extrados"}
        ``"intrados"`` (the intrados end of the joint's contact) or ``"extrados"`` (its
        extrados end).

    Examples
    --------
    The hinge A of Oppenheim's arch under forces toward +x (Table 1 of the paper):

    >>> from archquake import oppenheim
    >>> a = Hinge(0, "intrados")
    >>> round(a.radius(oppenheim()), 3), round(a.beta(oppenheim()), 4)
    (9.25, 0.1963)
    """

    joint: int
    face: str

    def __post_init__(self):
        if self.face not in FACES:
            raise ValueError(f"face must be one of {FACES}, got {self.face!r}")
        if isinstance(self.joint, bool) or int(self.joint) != self.joint or self.joint < 0:
            raise ValueError(f"joint must be an integer >= 0, got {self.joint!r}")
        object.__setattr__(self, "joint", int(self.joint))

    def radius(self, arch) -> float:
        """Distance of the hinge point from the centre of a circular
        :class:`~archquake.geometry.CircularArch` [m]: the edge of the joint's contact on this face.

        Raises
        ------
        ValueError
            For an arch without a centre (not an :class:`~archquake.geometry.CircularArch`); use
            :meth:`point`.
        """
        extents = getattr(arch, "joint_extents", None)
        if extents is None:
            raise ValueError(f"a hinge radius is defined for circular arches with radial joints "
                             f"(CircularArch), not for a {type(arch).__name__}; use Hinge.point")
        inner, outer = extents()
        return float(inner[self.joint] if self.face == "intrados" else outer[self.joint])

    def beta(self, arch: BlockArch) -> float:
        """Progressive angle of the hinge's joint [rad] (:attr:`BlockArch.joint_angles`)."""
        return float(arch.joint_angles[self.joint])

    def point(self, arch: BlockArch) -> np.ndarray:
        """Position (x, y) of the hinge point [m]: the end of the joint's contact on this
        face."""
        return arch.hinge_point(self.joint, self.face)
