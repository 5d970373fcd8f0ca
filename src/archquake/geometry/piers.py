r"""Piers and buttresses under the springings of an arch: their blocks and joints.

A :class:`Pier` is drawn under the springing joint of an arch (the joint from the intrados
springing point :math:`P_i` to the extrados springing point :math:`P_e`) by these rules, stated
for the left pier (the right one is its mirror image under the right springing):

- **Inner face**: the vertical through :math:`P_i`, from the ground up to :math:`P_i`.
- **Top**: the springing joint from :math:`P_i` to :math:`P_e`, then a horizontal line at the
  height of :math:`P_e` out to the outer face.
- **Size**: ``width`` :math:`b` [m] is measured horizontally from :math:`P_i` outward (so the
  top reaches :math:`x_{P_i} - b`); ``height`` :math:`h` [m] from the ground (the pier's base,
  its joint with the support) up to :math:`P_i`. The width must be at least the horizontal
  extent of the springing joint, :math:`x_{P_i} - x_{P_e}`.
- **Outer face**: by default the vertical at the distance :math:`b` from the inner face (a
  rectangular pier). A buttress has an outer face of its own: a polyline of points
  :math:`(w, y)` -- distance from the inner face and height above the ground [m] -- from the
  ground up (``outer_face``), continued straight to :math:`(b, h)` and vertically from there to
  the top. :meth:`Pier.tapered` (a straight batter) and :meth:`Pier.stepped` (a width per
  course) build the usual ones.
- **Courses**: the pier is a stack of ``courses`` blocks of equal height :math:`h/c`, with
  horizontal bed joints; the top course reaches up to the springing joint. The joint between two
  courses is their overlap (the narrower of the two where the outer face steps back).

The joints follow the contract of :mod:`archquake.geometry`: along the chain of blocks from the
left support to the right one, the normal of the base and bed joints of the left pier points up
and that of the right pier down, so their *intrados end* is on the inner face (toward the span)
and their *extrados end* on the outer face: a hinge at the extrados end of a pier's base is at
its outer toe.

An **intermediate pier** (:func:`middle_pier_blocks`) carries the right springing of one arch
and the left springing of the next: its faces are the verticals through the two intrados
springing points, so its ``width`` is their distance and the clear span between two piers is
the arch's intrados chord; its top follows both springing joints and runs level between their
extrados ends; it needs the width of the two seats (the horizontal extents of the two joints),
else the extrados ends would cross. Its courses are of equal height, the top one carrying both
seats.

A pier needs a springing joint that rises outward (its extrados end no lower than its intrados
end and not inside the span): an arch over more than a semicircle (a horseshoe) is not put on
piers.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .._equality import value_equality
from .blocks import LENGTH_RANGE, check_json_numbers, check_length, real_number

MAX_COURSES = 1000
"""Most courses of a pier [-]."""


def _check_courses(courses) -> int:
    if isinstance(courses, bool) or not isinstance(courses, int | float | np.integer) or not (
            float(courses).is_integer()):
        raise ValueError(f"courses must be an integer >= 1, got {courses!r}")
    c = int(courses)
    if not 1 <= c <= MAX_COURSES:
        raise ValueError(f"courses must be in [1, {MAX_COURSES}], got {c}")
    return c


@value_equality
@dataclass(frozen=True)
class Pier:
    r"""A pier or buttress under a springing of an arch (see the module's rules).

    Parameters
    ----------
    width : float
        Width :math:`b` at the top, horizontally from the intrados springing point outward [m].
    height : float
        Height :math:`h` from the ground up to the intrados springing point [m].
    courses : int, default 1
        Number of courses (blocks) of equal height [-], >= 1.
    outer_face : sequence of (float, float), optional
        Points :math:`(w, y)` [m] of the outer face below the top, from the ground up: the
        distance from the inner face (> 0) and the height above the ground (from 0, never
        decreasing, at most ``height``); the face runs through them to :math:`(b, h)` and up.
        Empty (default): a rectangular pier.

    Raises
    ------
    ValueError
        For a width or height not in :data:`~archquake.geometry.LENGTH_RANGE`, a number of
        courses not in [1, :data:`MAX_COURSES`], or an outer face that does not start on the
        ground, goes down, leaves [0, height] or reaches the inner face.

    Examples
    --------
    >>> Pier(3.0, 6.0, 2).describe()
    'rectangular pier 3 m wide, 6 m high, 2 courses'
    >>> Pier.stepped((4.0, 3.0, 2.0), 6.0).outer_face
    ((4.0, 0.0), (4.0, 2.0), (3.0, 2.0), (3.0, 4.0), (2.0, 4.0))
    """

    width: float
    height: float
    courses: int = 1
    outer_face: tuple = ()

    def __post_init__(self):
        width = check_length("width", self.width)
        height = check_length("height", self.height)
        courses = _check_courses(self.courses)
        try:
            face = tuple((real_number("outer_face w", w, "m"), real_number("outer_face y", y, "m"))
                         for w, y in self.outer_face)
        except (TypeError, ValueError) as exc:
            raise ValueError(f"outer_face must be a sequence of (w, y) points [m] (numbers): "
                             f"{exc}") from exc
        if face:
            points = np.array(face)
            if not np.all(np.isfinite(points)):
                raise ValueError("outer_face must hold finite numbers [m]")
            if points[0, 1] != 0.0:
                raise ValueError(f"outer_face must start on the ground (y = 0), got y = "
                                 f"{points[0, 1]:g} m")
            if np.any(np.diff(points[:, 1]) < 0) or points[-1, 1] > height:
                raise ValueError(f"outer_face heights must never decrease and stay in [0, "
                                 f"height = {height:g}] m, got {points[:, 1].tolist()}")
            if np.any(points[:, 0] <= 0):
                raise ValueError(f"outer_face widths must be > 0 [m] (the outer face may not "
                                 f"reach the inner face), got {points[:, 0].tolist()}")
            if np.any(points[:, 0] > LENGTH_RANGE[1]):
                raise ValueError(f"outer_face widths must be at most {LENGTH_RANGE[1]:g} m")
        object.__setattr__(self, "width", width)
        object.__setattr__(self, "height", height)
        object.__setattr__(self, "courses", courses)
        object.__setattr__(self, "outer_face", face)

    @classmethod
    def tapered(cls, width: float, base_width: float, height: float, courses: int = 1) -> Pier:
        """A buttress whose outer face runs straight from ``base_width`` on the ground to
        ``width`` at the height of the intrados springing [m]."""
        return cls(width, height, courses, ((check_length("base_width", base_width), 0.0),))

    @classmethod
    def stepped(cls, widths, height: float) -> Pier:
        """A buttress of ``len(widths)`` courses of equal height, course ``k`` (from the ground
        up) ``widths[k]`` wide [m]: its outer face steps at the bed joints; the top course's
        width is the pier's width."""
        try:
            widths = [check_length(f"widths[{k}]", w) for k, w in enumerate(widths)]
        except TypeError as exc:
            raise ValueError("widths must be a sequence of numbers [m]") from exc
        if not widths:
            raise ValueError("widths must hold one width per course, got none")
        h = check_length("height", height)
        c = len(widths)
        face = []
        for k, w in enumerate(widths[:-1]):
            face += [(w, k * h / c), (w, (k + 1) * h / c)]
        face.append((widths[-1], (c - 1) * h / c))
        return cls(widths[-1], h, c, tuple(face))

    @property
    def is_rectangular(self) -> bool:
        """Whether the outer face is the vertical at the pier's width."""
        return all(w == self.width for w, _ in self.outer_face)

    def describe(self) -> str:
        """One line: the kind of pier, its size and courses."""
        kind = "rectangular pier" if self.is_rectangular else "buttress"
        base = "" if self.is_rectangular else f" ({self.outer_face[0][0]:g} m at the base)"
        courses = "1 course" if self.courses == 1 else f"{self.courses} courses"
        return f"{kind} {self.width:g} m wide{base}, {self.height:g} m high, {courses}"

    def to_dict(self) -> dict:
        """``{"width", "height", "courses", "outer_face"}`` [m], as read by
        :meth:`from_dict`."""
        return {"width": self.width, "height": self.height, "courses": self.courses,
                "outer_face": [list(p) for p in self.outer_face]}

    @classmethod
    def from_dict(cls, data) -> Pier:
        """The pier of :meth:`to_dict` (``courses`` and ``outer_face`` optional)."""
        if not isinstance(data, dict):
            raise ValueError(f"a pier must be a JSON object with 'width' and 'height', got "
                             f"{type(data).__name__}")
        keys = {"width", "height", "courses", "outer_face"}
        unknown = sorted(set(data) - keys)
        if unknown:
            raise ValueError(f"a pier has unknown key(s) {unknown}; allowed: {sorted(keys)}")
        missing = [k for k in ("width", "height") if k not in data]
        if missing:
            raise ValueError(f"a pier is missing the key(s) {missing}")
        for key in ("width", "height", "courses"):
            if key in data:
                check_json_numbers(key, data[key], 0)
        if "outer_face" in data:
            check_json_numbers("outer_face", data["outer_face"], 2)
        return cls(data["width"], data["height"], data.get("courses", 1),
                   tuple(tuple(p) for p in data.get("outer_face", ())))

    # ------------------------------------------------------------------ geometry
    def face_polyline(self, top: float) -> np.ndarray:
        """The outer face from the ground to the pier's top at height ``top`` (>= ``height``)
        above the ground, as points ``(w, y)`` [m], heights never decreasing."""
        points = list(self.outer_face) or [(self.width, 0.0)]
        points.append((self.width, self.height))
        if top > self.height:
            points.append((self.width, top))
        return np.array(points)


def _clip(face: np.ndarray, y0: float, y1: float) -> np.ndarray:
    """The part of the face polyline between heights ``y0 < y1``, from y0 up: a horizontal step
    on y0 or y1 belongs to the course on the other side of it."""
    out = []
    for (wa, ya), (wb, yb) in zip(face[:-1], face[1:], strict=True):
        if ya == yb:  # a step: inside the course only strictly between its bed joints
            if y0 < ya < y1:
                out += [(wa, ya), (wb, yb)]
            continue
        lo, hi = max(ya, y0), min(yb, y1)
        if hi <= lo:
            continue
        for y in (lo, hi):
            out.append((wa + (wb - wa) * (y - ya) / (yb - ya), y))
    points = [out[0]]
    for p in out[1:]:
        if p != points[-1]:
            points.append(p)
    return np.array(points)


def seat(springing) -> tuple[np.ndarray, np.ndarray, float, float]:
    """The seat of a left springing joint on a pier: ``(P_i, P_e, reach, rise)``, its two ends
    [m], its horizontal extent :math:`x_{P_i} - x_{P_e}` and its rise :math:`y_{P_e} - y_{P_i}`
    [m] (both >= 0).

    Raises
    ------
    ValueError
        When the joint does not rise outward from its intrados end (beyond a relative 1e-12).
    """
    p_in, p_out = (np.asarray(p, dtype=float) for p in springing)
    reach = float(p_in[0] - p_out[0])  # horizontal extent of the springing joint
    rise = float(p_out[1] - p_in[1])
    size = max(float(np.hypot(*(p_out - p_in))), 1e-300)
    if reach < -1e-12 * size or rise < -1e-12 * size:
        raise ValueError(
            "a pier needs a springing joint that rises outward from its intrados end (an arch "
            "over at most a semicircle): this springing joint runs "
            f"{'inward' if reach < 0 else 'downward'}")
    return p_in, p_out, max(reach, 0.0), max(rise, 0.0)


def pier_blocks(pier: Pier, springing) -> tuple[list[np.ndarray], np.ndarray]:
    """The blocks and joints of a left pier under the springing joint ``springing``.

    Parameters
    ----------
    pier : Pier
        The pier.
    springing : array_like, shape (2, 2)
        The arch's left springing joint: its intrados end :math:`P_i` and its extrados end
        :math:`P_e` [m].

    Returns
    -------
    polygons : list of ndarray (k, 2)
        The courses from the ground up, counterclockwise [m].
    joints : ndarray, shape (courses, 2, 2)
        The base and the bed joints from the ground up, each (intrados end on the inner face,
        extrados end on the outer face) [m].

    Raises
    ------
    ValueError
        When the springing joint does not rise outward, the pier is narrower than the
        horizontal extent of the springing joint or its outer face does not reach it, or the
        top course would not reach above its bed joint.
    """
    p_in, p_out, reach, rise = seat(springing)
    if pier.width < reach * (1.0 - 1e-12):
        raise ValueError(f"pier width must be at least the horizontal extent of the springing "
                         f"joint, {reach:.6g} m (the pier's top must carry the whole joint), got "
                         f"{pier.width:g} m")
    x_in, ground = float(p_in[0]), float(p_in[1]) - pier.height
    top = pier.height + rise
    face = pier.face_polyline(top)
    c = pier.courses
    beds = [pier.height * k / c for k in range(c)] + [top]
    polygons, joints = [], []
    previous_top = math.inf
    for k in range(c):
        y0, y1 = beds[k], beds[k + 1]
        part = _clip(face, y0, y1)
        outer = np.column_stack((x_in - part[:, 0], ground + part[:, 1]))[::-1]
        if k < c - 1:
            inner = [(x_in, ground + y0), (x_in, ground + y1)]
        else:
            inner = [(x_in, ground + y0), tuple(p_in), tuple(p_out)]
        polygon = _dedup(np.vstack((np.array(inner), outer)), 1e-12 * max(pier.width, top))
        polygons.append(polygon)
        below = min(part[0, 0], previous_top)
        joints.append(((x_in, ground + y0), (x_in - below, ground + y0)))
        previous_top = part[-1, 0]
    return polygons, np.array(joints, dtype=float)


def middle_pier_blocks(pier: Pier, right_springing, left_springing) -> list[np.ndarray]:
    r"""The blocks of an intermediate pier between two arches (see the module's rules).

    Parameters
    ----------
    pier : Pier
        A rectangular pier: ``width`` :math:`W` is the distance between the two intrados
        springing points it carries (its two faces), ``height`` :math:`h` from the ground up to
        them [m].
    right_springing : array_like, shape (2, 2)
        The right springing joint of the arch on its left: intrados end :math:`P_i`, extrados
        end :math:`P_e` [m].
    left_springing : array_like, shape (2, 2)
        The left springing joint of the arch on its right: :math:`Q_i`, :math:`Q_e` [m], with
        :math:`x_{Q_i} - x_{P_i} = W`.

    Returns
    -------
    list of ndarray (k, 2)
        The courses from the ground up, counterclockwise [m]: the faces are the verticals through
        :math:`P_i` and :math:`Q_i`, the top course's top the polyline :math:`Q_i, Q_e, P_e,
        P_i` (the two seats, level between them when both joints end at one height).

    Raises
    ------
    ValueError
        For a pier with an outer face (an intermediate pier has none), springing joints that do
        not rise outward or whose intrados ends are not at one height, or a pier narrower than
        its two seats, :math:`W < (x_{P_e} - x_{P_i}) + (x_{Q_i} - x_{Q_e})` (the extrados ends
        would cross), naming the width needed.
    """
    if not pier.is_rectangular:
        raise ValueError("an intermediate pier is rectangular (both its faces carry an arch): "
                         f"got {pier.describe()}")
    flip = np.array([-1.0, 1.0])
    p_in, p_out, reach_left, _ = seat(np.asarray(right_springing, dtype=float) * flip)
    p_in, p_out = p_in * flip, p_out * flip
    q_in, q_out, reach_right, _ = seat(left_springing)
    width = float(q_in[0] - p_in[0])
    scale = max(width, pier.height, float(np.hypot(*(p_out - p_in))))
    if abs(float(q_in[1] - p_in[1])) > 1e-9 * scale:
        raise ValueError(f"an intermediate pier carries two springings at one height: the "
                         f"intrados springing points are at y = {p_in[1]:.9g} m and "
                         f"{q_in[1]:.9g} m")
    needed = reach_left + reach_right
    if width < needed * (1.0 - 1e-12):
        raise ValueError(f"intermediate pier width must be at least {needed:.6g} m, the "
                         f"horizontal extents of the two springing joints it carries "
                         f"({reach_left:.6g} m + {reach_right:.6g} m; narrower, their extrados "
                         f"ends would cross), got {width:.6g} m")
    ground = float(p_in[1]) - pier.height
    c = pier.courses
    beds = [ground + pier.height * k / c for k in range(c)]
    x0, x1 = float(p_in[0]), float(q_in[0])
    polygons = [np.array([(x0, y0), (x1, y0), (x1, y1), (x0, y1)])
                for y0, y1 in zip(beds[:-1], beds[1:], strict=True)]
    top = np.array([(x0, beds[-1]), (x1, beds[-1]), tuple(q_in), tuple(q_out), tuple(p_out),
                    tuple(p_in)])
    polygons.append(_dedup(top, 1e-12 * scale))
    return polygons


def _dedup(points: np.ndarray, tol: float) -> np.ndarray:
    keep = [points[0]]
    for p in points[1:]:
        if np.hypot(*(p - keep[-1])) > tol:
            keep.append(p)
    if len(keep) > 1 and np.hypot(*(keep[-1] - keep[0])) <= tol:
        keep.pop()
    return np.array(keep)


__all__ = ["MAX_COURSES", "Pier", "middle_pier_blocks", "pier_blocks", "seat"]
