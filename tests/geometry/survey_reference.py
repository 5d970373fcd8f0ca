"""The survey's former overlap check, pairwise over every two blocks (quadratic): the reference
that :func:`archquake.geometry.overlaps.first_overlap` is checked against, and timed beside it
(benchmarks/survey_overlaps.py). It uses the survey's own pair tests, which the sweep's
compiled kernel reimplements."""

import numpy as np

from archquake.geometry import survey


def check_overlaps_pairwise(polygons, tol):
    """The pairwise check of every two blocks whose boxes meet, as the survey did it before its
    sweep (quadratic in the number of blocks): the reference the sweep is checked against."""
    boxes = np.array([[*v.min(axis=0), *v.max(axis=0)] for v in polygons])
    for a in range(len(polygons)):
        for b in range(a + 1, len(polygons)):
            if (boxes[a, 0] > boxes[b, 2] + tol or boxes[b, 0] > boxes[a, 2] + tol
                    or boxes[a, 1] > boxes[b, 3] + tol or boxes[b, 1] > boxes[a, 3] + tol):
                continue
            va, vb = polygons[a], polygons[b]
            if (survey._crossing(*survey._edges(va), *survey._edges(vb), tol)
                    or np.any(survey._inside(va, vb, tol))
                    or np.any(survey._inside(vb, va, tol))):
                raise ValueError(f"blocks {a} and {b} overlap")
            if b > a + 1 and survey._contacts(va, vb, tol):
                raise ValueError(f"blocks {a} and {b} touch along a segment but are not "
                                 "neighbours: list the blocks left to right")
