r"""Bridges and arcades: several equal arches in a row on shared piers, as one block assembly.

The bridge is rigid blocks on piers, as Gilbert and Melbourne analyse it [1]_.

:func:`multi_span` puts ``spans`` copies of one arch (any :class:`~archquake.geometry.BlockArch`:
circular, of any shape, surveyed) side by side on ``spans + 1`` piers:

- **End piers** are those of an arch on piers (:class:`~archquake.geometry.Structure`,
  :mod:`archquake.geometry.piers`): under the first arch's left springing and the last arch's
  right one, their width measured outward from the intrados springing point; None leaves a
  fixed springing (a support on the springing joint).
- **Intermediate piers** (:func:`~archquake.geometry.piers.middle_pier_blocks`) carry the right
  springing of one arch and the left springing of the next: their faces are the verticals
  through the two intrados springing points, so the arches stand ``middle_pier.width`` apart
  (from one intrados springing point to the next) and the clear span between two piers is the
  arch's intrados chord; the top follows both springing joints and is level between their
  extrados ends. A pier narrower than its two seats (the extrados ends would cross) is refused
  with the width it needs.
- **Courses**: every pier is a stack of ``courses`` blocks of equal height; the top course
  carries the seats.

Arch :math:`k` (0-based) is the given arch translated by :math:`k\,(c + W)` along x, with
:math:`c` the horizontal distance between its two intrados springing points and :math:`W` the
intermediate pier's width.

**Blocks**, left to right: the left end pier's courses from the ground up, then for each span
its voussoirs (left to right) followed by the next pier's courses (an intermediate pier's from
the ground up, the right end pier's from the top down). With one span these are exactly the
blocks of :func:`~archquake.geometry.assembly.from_arch` of the arch on its two end piers, in the
same order, with the same supports. Every block is named (``"span 2 voussoir 3"``, ``"pier 1
course 2"``, spans and piers counted from 1 and 0 left to right, voussoirs and courses from 1):
:func:`spans_of` reads the names back.

**Supports**: a square under every pier's base (and on a fixed springing's joint), as
:func:`~archquake.geometry.assembly.from_arch` puts them.

**Interface kinds** (without friction none slides, Heyman's hypothesis [2]_): voussoir joints
``"bed"``, pier courses on each other ``"bed"``, the
arches' springings on the piers ``"bed"``, the piers' bases (and fixed springings)
``"foundation"``.

Not yet: fill over the arches (the fill is no block of an assembly; an arch carrying one is
refused).

References
----------
.. [1] Gilbert, M. and Melbourne, C. (1994). Rigid-block analysis of masonry structures. The
   Structural Engineer 72(21), 356-361 (multi-span bridges as rigid blocks on piers).
.. [2] Heyman, J. (1966). The stone skeleton. Int. J. Solids Struct. 2, 249-279 (no tension,
   no sliding: the interfaces' default).

Examples
--------
Three spans of an 8-voussoir arch on piers of three courses:

>>> from archquake.geometry import Pier, shaped_arch
>>> arch = shaped_arch("circular", span=4.0, rise=2.0, thickness=0.4, voussoirs=8)
>>> bridge = multi_span(arch, 3, end_piers=(Pier(1.5, 3.0, 3),) * 2,
...                     middle_pier=Pier(1.5, 3.0, 3))
>>> bridge.n_blocks  # 3 x 8 voussoirs and 4 x 3 courses
36
>>> spans_of(bridge, [3, 12, 14])  # a voussoir of span 1, a pier course, one of span 2
[1, 2]
"""

from __future__ import annotations

import math
import re

import numpy as np

from .assembly import ARC_POINTS, BlockAssembly
from .blocks import BlockArch
from .piers import Pier, middle_pier_blocks
from .structure import Structure

MAX_SPANS = 100
"""Most spans of :func:`multi_span` [-]."""

_SPAN_NAME = re.compile(r"span (\d+) ")


def _check_spans(spans) -> int:
    if isinstance(spans, bool) or not isinstance(spans, int | np.integer) or not (
            1 <= spans <= MAX_SPANS):
        raise ValueError(f"spans must be an integer in [1, {MAX_SPANS}], got {spans!r}")
    return int(spans)


def _support(p_in: np.ndarray, p_out: np.ndarray, normal: np.ndarray, side: float) -> np.ndarray:
    """The square on a joint on its far side (``side`` -1 before the chain, +1 after it), as
    :func:`~archquake.geometry.assembly.from_arch` puts it."""
    d = side * float(np.hypot(*(p_out - p_in))) * normal
    return np.array([p_in, p_out, p_out + d, p_in + d])


def multi_span(arch: BlockArch, spans: int, *, end_piers=(None, None),
               middle_pier: Pier | None = None, friction=None,
               points: int = ARC_POINTS) -> BlockAssembly:
    r"""``spans`` equal arches in a row on ``spans + 1`` piers, as a block assembly (see the
    module).

    Parameters
    ----------
    arch : BlockArch
        The arch of every span, on fixed springings and without fill (circular, shaped or
        surveyed); its density is the masonry's, piers included [kg/m^3].
    spans : int
        Number of arches, in [1, :data:`MAX_SPANS`].
    end_piers : (Pier or None, Pier or None), default (None, None)
        The piers under the first arch's left springing and the last arch's right one, as
        :class:`~archquake.geometry.Structure` puts them; None: a fixed springing.
    middle_pier : Pier, optional
        The intermediate piers (rectangular): ``width`` the distance between the two intrados
        springing points each carries [m], ``height`` from the ground up to them [m], its
        courses. Needed with two spans or more.
    friction : None, float or dict
        Coulomb coefficient of the interfaces [-] (:class:`~archquake.geometry.BlockAssembly`).
    points : int, default 24
        Points on each curved face of a voussoir (:func:`~archquake.geometry.assembly.from_arch`).

    Returns
    -------
    BlockAssembly
        Named blocks (``"pier 0 course 1"``, ``"span 1 voussoir 1"``, ...).

    Raises
    ------
    ValueError
        Naming the parameter: an arch that is not a BlockArch, is on piers already or carries
        fill; spans out of range; end piers not a pair of Pier or None, or one that does not fit
        its springing; no intermediate pier with two spans or more, or one that is not
        rectangular, whose springings are not at one height, or narrower than its two seats
        (the message gives the width needed).
    """
    if isinstance(arch, Structure):
        what = "carries fill" if arch.fill is not None else "is on piers already"
        raise ValueError(f"arch must be an arch on fixed springings: this one {what} (multi_span "
                         "puts the arch on its piers; fill over several spans is not modelled "
                         "yet)")
    if not isinstance(arch, BlockArch):
        raise ValueError(f"arch must be a BlockArch, got {type(arch).__name__}")
    spans = _check_spans(spans)
    try:
        left, right = end_piers
    except (TypeError, ValueError):
        raise ValueError(f"end_piers must be a pair (left, right) of Pier or None, got "
                         f"{end_piers!r}") from None
    for name, pier in (("end_piers[0]", left), ("end_piers[1]", right)):
        if pier is not None and not isinstance(pier, Pier):
            raise ValueError(f"{name} must be a Pier or None, got {type(pier).__name__}")
    if spans > 1 and not isinstance(middle_pier, Pier):
        raise ValueError(f"middle_pier must be a Pier with {spans} spans (the piers between "
                         f"them), got {type(middle_pier).__name__}")
    ends = Structure(arch, left, right)  # the end piers where an arch on piers has them
    n_left, n_arch, n_right = ends.n_left, arch.n_voussoirs, ends.n_right
    voussoirs = [np.asarray(arch.outline(i, points), dtype=float)[:-1] for i in range(n_arch)]
    joints, normals = ends.joints, ends.joint_normals
    pitch = 0.0
    middle = []
    if spans > 1:
        chord = float(arch.joints[-1, 0, 0] - arch.joints[0, 0, 0])
        pitch = chord + middle_pier.width
        shift = np.array([pitch, 0.0])
        try:
            middle = middle_pier_blocks(middle_pier, arch.joints[-1], arch.joints[0] + shift)
        except ValueError as exc:
            raise ValueError(f"middle_pier: {exc}") from exc

    def moved(polygon: np.ndarray, k: int) -> np.ndarray:
        return polygon if k == 0 else polygon + np.array([k * pitch, 0.0])

    polygons, names, kinds = [], [], []

    def add(blocks, labels, chain: bool) -> range:
        """Append blocks; ``chain``: consecutive ones rest on each other (pier courses,
        voussoirs)."""
        start = len(polygons)
        polygons.extend(blocks)
        names.extend(labels)
        if chain:
            kinds.extend((i, i + 1, "bed") for i in range(start, len(polygons) - 1))
        return range(start, len(polygons))

    pier = add([ends.outline(i)[:-1] for i in range(n_left)],
               [f"pier 0 course {c + 1}" for c in range(n_left)], True)
    seat = pier[-1] if pier else None  # the block under the next arch's left springing
    for k in range(spans):
        span = add([moved(v, k) for v in voussoirs],
                   [f"span {k + 1} voussoir {i + 1}" for i in range(n_arch)], True)
        if seat is not None:
            kinds.append((seat, span[0], "bed"))
        if k < spans - 1:
            pier = add([moved(p, k) for p in middle],
                       [f"pier {k + 1} course {c + 1}" for c in range(len(middle))], True)
        else:
            last = n_left + n_arch
            pier = add([moved(ends.outline(i)[:-1], k) for i in range(last, last + n_right)],
                       [f"pier {spans} course {n_right - c}" for c in range(n_right)], True)
        seat = None
        if pier:
            top = pier[-1] if k < spans - 1 else pier[0]  # the right end pier runs top down
            kinds.append((span[-1], top, "bed"))
            seat = top

    supports = [_support(*joints[0], normals[0], -1.0)]
    for k in range(spans - 1):
        base = middle[0]
        x0, x1 = float(base[:, 0].min()), float(base[:, 0].max())
        y = float(base[:, 1].min())
        width = x1 - x0
        supports.append(moved(np.array([(x0, y), (x0, y - width), (x1, y - width), (x1, y)]), k))
    end = joints[-1] if spans == 1 else joints[-1] + np.array([(spans - 1) * pitch, 0.0])
    supports.append(_support(*end, normals[-1], 1.0))

    return BlockAssembly(tuple(polygons), arch.density, tuple(supports), friction,
                         kinds=tuple(kinds), names=tuple(names))


def spans_of(assembly: BlockAssembly, blocks) -> list[int]:
    """The spans (counted from 1) of the voussoirs among ``blocks`` (block indices) of an
    assembly built by :func:`multi_span` (read from the blocks' names); piers belong to no
    span."""
    out = set()
    for i in blocks:
        name = assembly.names[int(i)] if assembly.names else ""
        match = _SPAN_NAME.match(name)
        if match:
            out.add(int(match.group(1)))
    return sorted(out)


def moving_blocks(result, tolerance: float = 1e-6) -> list[int]:
    """The blocks that move in the mechanism of an
    :class:`~archquake.limit_analysis.AssemblyLimit`: a corner's velocity above ``tolerance``
    [m/s] (the fastest corner moves at 1 m/s)."""
    moving = []
    for i, outline in enumerate(result.contacts.outlines):
        speed = np.hypot(*result.velocity_at(i, outline).T)
        if math.isfinite(float(speed.max())) and float(speed.max()) > tolerance:
            moving.append(i)
    return moving


__all__ = ["MAX_SPANS", "moving_blocks", "multi_span", "spans_of"]
