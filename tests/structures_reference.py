"""Reference structures built by hand, independently of archquake.geometry.piers: a rigid lintel
(one block) to stand on two columns, and the block polygons of an arch on rectangular piers as
a surveyed-blocks description."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from archquake.geometry import BlockArch
from archquake.geometry.mass import polygon_properties


@dataclass(frozen=True, eq=False)
class Lintel(BlockArch):
    """One rigid rectangular block ``span + 2 bearing`` long and ``depth`` deep, its underside on
    y = 0, resting on two bearings ``bearing`` wide at the ends of ``span``: the "arch" of a
    portal frame. Its springing joints are the bearings, intrados end inward."""

    span: float
    bearing: float
    depth: float
    density: float = 2000.0
    _cache: dict = field(default_factory=dict, init=False, repr=False, compare=False)

    @property
    def n_voussoirs(self) -> int:
        return 1

    def _polygon(self) -> np.ndarray:
        x0, x1 = -self.span / 2 - self.bearing, self.span / 2 + self.bearing
        return np.array([[x0, 0.0], [x1, 0.0], [x1, self.depth], [x0, self.depth]])

    def _joints(self) -> np.ndarray:
        h = self.span / 2
        return np.array([[[-h, 0.0], [-h - self.bearing, 0.0]],
                         [[h, 0.0], [h + self.bearing, 0.0]]])

    def _mass_properties(self):
        m, c, i = polygon_properties(self._polygon(), self.density)
        return np.array([m]), np.array([c]), np.array([i])

    def outline(self, i: int, points: int = 24) -> np.ndarray:
        p = self._polygon()
        return np.vstack((p, p[:1]))

    def mirrored(self) -> Lintel:
        return self

    def to_dict(self) -> dict:
        return {"span": self.span, "bearing": self.bearing, "depth": self.depth}


def portal_blocks(width: float, height: float, courses: int, span: float, depth: float):
    """The blocks of a portal by hand: two columns ``width`` x ``height`` of ``courses`` equal
    courses under a one-block lintel ``span + 2 width`` long, left to right (left column bottom
    up, lintel, right column top down), and the two column bases (springings)."""
    h = span / 2
    dy = height / courses
    left = [[[-h - width, -height + k * dy], [-h, -height + k * dy], [-h, -height + (k + 1) * dy],
             [-h - width, -height + (k + 1) * dy]] for k in range(courses)]
    right = [[[-x, y] for x, y in b] for b in left][::-1]
    lintel = [[-h - width, 0.0], [h + width, 0.0], [h + width, depth], [-h - width, depth]]
    springings = [[[-h, -height], [-h - width, -height]], [[h, -height], [h + width, -height]]]
    return [*left, lintel, *right], springings


def piers_survey(arch, left, right, points: int = 400):
    """The blocks of ``arch`` on rectangular piers as polygons [m], drawn by hand from its two
    springing joints: a pier ``(width, height)`` (or None) has its inner face on the vertical
    through the intrados springing point, from ``height`` below it; its top runs along the
    springing joint and then horizontally out to ``width``. The voussoirs are the arch's
    outlines, ``points`` points a curved face. Returns ``(blocks, springings)`` for
    :func:`archquake.geometry.surveyed_arch`: the pier bases (or the arch's springings)."""
    blocks = [arch.outline(i, points)[:-1].tolist() for i in range(arch.n_voussoirs)]
    springings = [arch.joints[0].tolist(), arch.joints[-1].tolist()]
    for side, pier in ((0, left), (1, right)):
        if pier is None:
            continue
        width, height = pier
        (x_in, y_in), (x_out, y_out) = arch.joints[0 if side == 0 else -1]
        out = -1.0 if side == 0 else 1.0  # the outward direction
        ground = y_in - height
        polygon = [[x_in, ground], [x_in, y_in], [x_out, y_out], [x_in + out * width, y_out],
                   [x_in + out * width, ground]]
        springings[side] = [[x_in, ground], [x_in + out * width, ground]]
        if side == 0:
            blocks.insert(0, polygon)
        else:
            blocks.append(polygon)
    return blocks, springings
