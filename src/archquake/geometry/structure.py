r"""An arch on piers or buttresses, with or without fill: one chain of blocks, one
:class:`~archquake.geometry.BlockArch`.

A :class:`Structure` puts an arch (circular, of any shape, or surveyed) on a :class:`Pier` at
either springing (or on a fixed springing where there is none) and may carry a :class:`Fill`
over it. It keeps the contract of every arch (:mod:`archquake.geometry`), so the limit analysis,
the four-link model and the rigid-block model analyse it as they analyse an arch:

- **Blocks** (the contract's "voussoirs") are, left to right, the courses of the left pier from
  the ground up, the arch's voussoirs, and the courses of the right pier from the top down:
  :attr:`Structure.n_voussoirs` counts them all, :attr:`Structure.arch_blocks` says which are
  the arch's, :attr:`Structure.block_kinds` what each is.
- **Joints**: the base of the left pier (on the left support), its bed joints, the arch's
  joints (its springing joints are where it rests on the piers), the right pier's bed joints
  and base (on the right support). Hinges may form at any of them.
- **Mass properties** of a pier course are those of its polygon; a voussoir carries its fill
  column rigidly (mass, centroid and moment of inertia of voussoir and column together), which
  is how both dynamic models see the fill (:mod:`archquake.geometry.fill`).
- **Loads** (:attr:`Structure.loads`): the weight of every block and column; the horizontal
  loads as the fill's inertia model says; the passive reaction of the fill.
- **Scales**: the crown is the arch's; the thickness that scales the rigid-block model's
  thresholds is the arch's (:attr:`Structure.thickness_scale`).
- **Mirror image** (Mech-r): the mirrored arch, the left and right piers swapped, the same fill.

:func:`arch_on_piers` builds an arch on two piers (equal or not).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from .._equality import value_equality
from .blocks import BlockArch
from .fill import Fill, FillColumns, carry_fill, fill_columns, fill_horizontal_loads
from .loads import BlockLoads
from .mass import polygon_properties
from .piers import Pier, pier_blocks

_FLIP = np.array([-1.0, 1.0])


def describe_arch(arch: BlockArch) -> str:
    """One line on an arch: its kind, size and voussoirs (units in brackets)."""
    n = arch.n_voussoirs
    if hasattr(arch, "radii"):  # the paper's circular arch
        return (f"n = {n} voussoirs, embrace = {math.degrees(arch.embrace):.4g} deg, mean radius "
                f"= {float(arch.radii.mean()):.4g} m, mean thickness = "
                f"{float(arch.thicknesses.mean()):.4g} m")
    if hasattr(arch, "centreline"):
        return (f"{arch.shape} arch, span = {arch.span:.4g} m, rise = {arch.rise:.4g} m, "
                f"n = {n} voussoirs ({arch.faces} faces), mean thickness = "
                f"{arch.thickness_scale:.4g} m")
    if isinstance(arch, Structure):
        return arch.describe()
    return f"surveyed arch of {n} blocks, median joint depth = {arch.thickness_scale:.4g} m"


@value_equality
@dataclass(frozen=True)
class Structure(BlockArch):
    """An arch on piers (or fixed springings) with or without fill (see the module).

    Parameters
    ----------
    arch : BlockArch
        The arch on fixed springings: a :class:`~archquake.geometry.CircularArch`,
        :class:`~archquake.geometry.ShapedArch` or :class:`~archquake.geometry.SurveyedArch`.
        Its density is the masonry's, piers included.
    left, right : Pier or None
        The pier under the left and the right springing; None for a fixed springing.
    fill : Fill or None
        The fill over the arch.

    Raises
    ------
    ValueError
        If ``arch`` is not an arch (or is itself a Structure), a pier or the fill is of the
        wrong type, or a pier does not fit its springing
        (:func:`~archquake.geometry.piers.pier_blocks`: narrower than the springing joint, a
        springing joint that does not rise outward).

    Examples
    --------
    Oppenheim's arch on two piers 3 m wide and 6 m high, each of two courses:

    >>> from archquake import oppenheim
    >>> s = arch_on_piers(oppenheim(), 3.0, 6.0, 2)
    >>> s.n_voussoirs, s.block_kinds[:3], s.arch_blocks
    (11, ('left pier', 'left pier', 'voussoir'), range(2, 9))
    >>> s.is_symmetric(), s.mirrored().left == s.right
    (True, True)
    """

    arch: BlockArch
    left: Pier | None = None
    right: Pier | None = None
    fill: Fill | None = None
    _cache: dict = field(default_factory=dict, init=False, repr=False, compare=False, hash=False)

    def __post_init__(self):
        if isinstance(self.arch, Structure) or not isinstance(self.arch, BlockArch):
            raise ValueError(f"arch must be an arch (CircularArch, ShapedArch or SurveyedArch), "
                             f"got {type(self.arch).__name__}")
        for name in ("left", "right"):
            value = getattr(self, name)
            if value is not None and not isinstance(value, Pier):
                raise ValueError(f"{name} must be a Pier or None, got {type(value).__name__}")
        if self.fill is not None and not isinstance(self.fill, Fill):
            raise ValueError(f"fill must be a Fill or None, got {type(self.fill).__name__}")
        arch = self.arch
        left = ([], np.empty((0, 2, 2)))
        right = ([], np.empty((0, 2, 2)))
        if self.left is not None:
            left = self._pier(self.left, arch.joints[0], "left")
        if self.right is not None:
            polygons, joints = self._pier(self.right, arch.joints[-1] * _FLIP, "right")
            right = ([(p * _FLIP)[::-1] for p in polygons][::-1], joints[::-1] * _FLIP)
        self._cache["piers"] = (left, right)
        if self.fill is not None:
            self._cache["fill"] = fill_columns(arch, self.fill)

    @staticmethod
    def _pier(pier: Pier, springing, side: str):
        try:
            polygons, joints = pier_blocks(pier, springing)
            for k, polygon in enumerate(polygons):
                polygon_properties(polygon, 1.0, name=f"course {k}")
        except ValueError as exc:
            raise ValueError(f"{side} pier: {exc}") from exc
        return polygons, joints

    # ------------------------------------------------------------------ blocks
    @property
    def density(self) -> float:
        """Density of the masonry (arch and piers) [kg/m^3]."""
        return self.arch.density

    @property
    def n_left(self) -> int:
        """Number of courses of the left pier (0 on a fixed springing) [-]."""
        return len(self._cache["piers"][0][0])

    @property
    def n_right(self) -> int:
        """Number of courses of the right pier (0 on a fixed springing) [-]."""
        return len(self._cache["piers"][1][0])

    @property
    def n_voussoirs(self) -> int:
        """Number of blocks n [-]: pier courses and voussoirs (the contract's "voussoirs")."""
        return self.n_left + self.arch.n_voussoirs + self.n_right

    @property
    def arch_blocks(self) -> range:
        """Indices of the arch's voussoirs among the blocks."""
        return range(self.n_left, self.n_left + self.arch.n_voussoirs)

    @property
    def block_kinds(self) -> tuple[str, ...]:
        """What every block is: ``"left pier"``, ``"voussoir"`` or ``"right pier"``."""
        return (("left pier",) * self.n_left + ("voussoir",) * self.arch.n_voussoirs
                + ("right pier",) * self.n_right)

    @property
    def fill_columns(self) -> FillColumns | None:
        """The fill over every voussoir of the arch (in the arch's own numbering), or None."""
        return self._cache.get("fill")

    def joint_name(self, j: int) -> str:
        """What joint ``j`` is, in words: ``"left pier base"``, ``"left pier bed joint 1"``
        (counted from the ground up), ``"left springing"``, ``"arch joint 3"`` (the arch's own
        numbering), ``"right springing"``, ``"right pier bed joint 1"``, ``"right pier base"``.
        """
        n_arch = self.arch.n_voussoirs
        if not 0 <= j <= self.n_voussoirs:
            raise ValueError(f"joint must be in [0, {self.n_voussoirs}], got {j}")
        if j < self.n_left:
            return "left pier base" if j == 0 else f"left pier bed joint {j}"
        k = j - self.n_left
        if k <= n_arch:
            side = "left " if self.left is not None else "left fixed "
            if k == 0:
                return side + "springing"
            if k == n_arch:
                return ("right " if self.right is not None else "right fixed ") + "springing"
            return f"arch joint {k}"
        bed = self.n_right - (k - n_arch)
        return "right pier base" if bed == 0 else f"right pier bed joint {bed}"

    def pier_polygon(self, i: int) -> np.ndarray:
        """Polygon of pier course ``i`` (a block index), counterclockwise [m]."""
        (left, _), (right, _) = self._cache["piers"]
        if i < self.n_left:
            return left[i]
        k = i - self.n_left - self.arch.n_voussoirs
        if 0 <= k < self.n_right:
            return right[k]
        raise ValueError(f"block {i} is not a pier course")

    def _joints(self) -> np.ndarray:
        (_, left), (_, right) = self._cache["piers"]
        return np.concatenate((left, self.arch.joints, right))

    def _mass_properties(self):
        n = self.n_voussoirs
        masses, centroids, inertias = np.empty(n), np.empty((n, 2)), np.empty(n)
        for i in (*range(self.n_left), *range(self.arch_blocks.stop, n)):
            m, c, inertia = polygon_properties(self.pier_polygon(i), self.density,
                                               name=f"pier course {i}")
            masses[i], centroids[i], inertias[i] = m, c, inertia
        blocks = self.arch_blocks
        m, c, inertia = self.arch.masses, self.arch.centroids, self.arch.inertias
        columns = self.fill_columns
        if columns is not None:  # voussoir and column, one rigid body
            m, c, inertia = carry_fill(m, c, inertia, columns.masses, columns.centroids,
                                       columns.inertias)
        masses[blocks.start:blocks.stop] = m
        centroids[blocks.start:blocks.stop] = c
        inertias[blocks.start:blocks.stop] = inertia
        return masses, centroids, inertias

    def _loads(self) -> BlockLoads:
        """Weights through the centroids of block and column; horizontal loads as the fill's
        inertia model says; the fill's passive reaction (:mod:`archquake.geometry.fill`)."""
        base = BlockLoads.of_masses(self.masses, self.centroids)
        columns = self.fill_columns
        if columns is None:
            return base
        blocks = slice(self.arch_blocks.start, self.arch_blocks.stop)
        horizontal = base.horizontal.copy()
        horizontal_y = base.horizontal_y.copy()
        if self.fill.inertia != "centroid":  # the centroid's: the base's, block and column
            horizontal[blocks], horizontal_y[blocks] = fill_horizontal_loads(
                self.arch.masses, self.arch.centroids, columns.masses, columns.centroids,
                columns.extrados_points[:, 1], self.fill.inertia)
        n = self.n_voussoirs
        passive, passive_y, sign = np.zeros(n), np.zeros(n), np.zeros(n)
        passive[blocks], passive_y[blocks], sign[blocks] = (columns.passive, columns.passive_y,
                                                            columns.passive_sign)
        return BlockLoads(base.vertical, base.vertical_x, horizontal, horizontal_y, passive,
                          passive_y, sign)

    def outline(self, i: int, points: int = 24) -> np.ndarray:
        """Closed outline of block ``i`` [m]: a pier course's polygon, or the voussoir's
        outline (``points`` per curved face)."""
        if i in self.arch_blocks:
            return self.arch.outline(i - self.n_left, points)
        polygon = self.pier_polygon(i)
        return np.vstack((polygon, polygon[:1]))

    def extrados(self, i: int) -> list:
        """The extrados of voussoir ``i`` (a block index) as pieces, left to right [m]."""
        if i not in self.arch_blocks:
            raise ValueError(f"block {i} is a pier course, not a voussoir: it has no extrados")
        return self.arch.extrados(i - self.n_left)

    # ------------------------------------------------------------------ scales
    @property
    def thickness_scale(self) -> float:
        """The arch's thickness [m] (its :attr:`~archquake.geometry.BlockArch.thickness_scale`):
        the length to which the rigid-block model scales its thresholds."""
        return self.arch.thickness_scale

    def crown(self) -> tuple[int, np.ndarray]:
        """The arch's crown: its block index and the top of its extrados [m]."""
        block, point = self.arch.crown()
        return block + self.n_left, point

    # ------------------------------------------------------------------ the contract
    def mirrored(self) -> Structure:
        """The structure mirrored about x = 0: the mirrored arch, the piers swapped."""
        return Structure(self.arch.mirrored(), self.right, self.left, self.fill)

    def without_piers(self) -> Structure:
        """The same arch and fill on fixed springings."""
        return replace(self, left=None, right=None)

    def perturbed(self, epsilon: float, draws: np.ndarray) -> Structure:
        """The structure on the irregular arch of :meth:`CircularArch.perturbed
        <archquake.geometry.CircularArch.perturbed>` (or the shaped arch's) for the draws of
        its voussoirs (the columns of ``draws`` at :attr:`arch_blocks`); the same piers under
        its springings, the same fill.

        Raises
        ------
        ValueError
            For an arch without a centreline to perturb (a surveyed arch).
        """
        perturbed = getattr(self.arch, "perturbed", None)
        if perturbed is None:
            raise ValueError("irregular arches are drawn around an arch with a centreline "
                             f"(CircularArch or ShapedArch), got {type(self.arch).__name__}")
        draws = np.asarray(draws, dtype=float)
        return replace(self, arch=perturbed(epsilon, draws[:, self.n_left:self.arch_blocks.stop]))

    def describe(self) -> str:
        """One line: the arch, its piers and its fill."""
        parts = [describe_arch(self.arch)]
        if self.left is not None and self.left == self.right:
            parts.append(f"on two {self.left.describe().replace('pier ', 'piers ', 1)}"
                         .replace("buttress ", "buttresses ", 1))
        elif self.left is not None or self.right is not None:
            for side in ("left", "right"):
                pier = getattr(self, side)
                parts.append(f"{side}: " + ("fixed springing" if pier is None
                                            else pier.describe()))
        if self.fill is not None:
            parts.append(self.fill.describe())
        return "; ".join(parts)

    def to_dict(self) -> dict:
        """``{"arch": {...}, "left_pier": {...} or None, "right_pier": ..., "fill": ...}``, as
        read by :func:`~archquake.geometry.arch_from_dict`."""
        return {"arch": self.arch.to_dict(),
                "left_pier": None if self.left is None else self.left.to_dict(),
                "right_pier": None if self.right is None else self.right.to_dict(),
                "fill": None if self.fill is None else self.fill.to_dict()}


def arch_on_piers(arch: BlockArch, width: float | None = None, height: float | None = None,
                  courses: int = 1, *, left: Pier | None = None, right: Pier | None = None,
                  fill: Fill | None = None) -> Structure:
    """An arch on two piers: equal ones (``width``, ``height``, ``courses``) or ``left`` and
    ``right`` given one by one.

    Parameters
    ----------
    arch : BlockArch
        The arch (circular, shaped or surveyed).
    width : float, optional
        Width of both piers, from the intrados springing point outward [m].
    height : float, optional
        Height of both piers, from the ground to the intrados springing point [m].
    courses : int, default 1
        Courses of equal height of each pier [-].
    left, right : Pier, optional
        The piers one by one (instead of ``width`` and ``height``; a side without one stays a
        fixed springing).
    fill : Fill, optional
        Fill over the arch.

    Returns
    -------
    Structure

    Raises
    ------
    ValueError
        Naming the parameter: both or neither of the two ways given, a pier that does not fit
        its springing (e.g. narrower than the horizontal extent of the springing joint).

    Examples
    --------
    >>> from archquake import oppenheim
    >>> arch_on_piers(oppenheim(), 2.0, 6.0).describe().split("; ")[1]
    'on two rectangular piers 2 m wide, 6 m high, 1 course'
    """
    equal = width is not None or height is not None
    if equal and (left is not None or right is not None):
        raise ValueError("give the piers either by width and height (equal piers) or by left "
                         "and right, not both")
    if equal:
        if width is None or height is None:
            raise ValueError("equal piers need both width [m] and height [m]")
        left = right = Pier(width, height, courses)
    elif left is None and right is None:
        raise ValueError("give the piers: width and height, or left and/or right")
    return Structure(arch, left, right, fill)


__all__ = ["Structure", "arch_on_piers", "describe_arch"]
