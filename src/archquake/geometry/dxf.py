r"""Block assemblies from CAD drawings (DXF) and back, through ``ezdxf``.

A drawing describes a :class:`~archquake.geometry.assembly.BlockAssembly` as closed polylines in
its model space:

- every closed ``LWPOLYLINE`` or 2D ``POLYLINE`` is a block, or a support when its layer is
  one of ``support_layers`` (case-insensitive; by default ``SUPPORT``, ``SUPPORTS``,
  ``GROUND`` and ``FOUNDATION``); with no support the ground is the lowest line of the blocks;
- lengths are converted to metres by the header's ``$INSUNITS`` (1 in = 0.0254 m, 1 ft =
  0.3048 m, mm, cm, m); a unitless drawing (``$INSUNITS`` 0 or absent) is taken in metres, with
  a warning that says so (give ``units``); ``units`` overrides the header;
- arcs in a polyline (bulges) are refused unless ``arc_chord_error`` [m] is given: then each is
  replaced by chords whose largest distance from the arc (the sagitta) is at most that;
- refused, naming the entity's handle and layer: an open polyline, a polyline of fewer than
  three distinct vertices, a polyface or mesh, a closed curve that is no polyline (``CIRCLE``,
  ``ELLIPSE``, ``SPLINE``: draw it as a polyline); other entities are ignored, with a warning
  for the geometric ones (``LINE``, ``ARC``, ``INSERT`` ...);
- every block keeps its entity's handle and layer in its name, so that the assembly's errors
  (an overlap, a block touching nothing) point into the drawing.

:func:`write_dxf` draws an assembly (blocks on layer ``BLOCKS``, supports on ``SUPPORT``, in
metres), which :func:`read_dxf` reads back equal.

Examples
--------
>>> import tempfile, pathlib
>>> from archquake.geometry.assembly import wall
>>> path = pathlib.Path(tempfile.mkdtemp()) / "wall.dxf"
>>> write_dxf(wall(2, 2, 0.4, 0.2), path)
>>> read_dxf(path) == wall(2, 2, 0.4, 0.2)
True
"""

from __future__ import annotations

import math
import os
import warnings
from collections import Counter
from pathlib import Path

import numpy as np

from ..constants import DEFAULT_DENSITY
from .assembly import BlockAssembly

UNITS = {"mm": 0.001, "cm": 0.01, "m": 1.0, "in": 0.0254, "ft": 0.3048}
"""Metres per drawing unit, by the names ``units`` takes."""

INSUNITS = {1: "in", 2: "ft", 4: "mm", 5: "cm", 6: "m"}
"""The header's ``$INSUNITS`` codes read (DXF reference, HEADER section); 0 is unitless."""

SUPPORT_LAYERS = ("SUPPORT", "SUPPORTS", "GROUND", "FOUNDATION")
"""Layers whose closed polylines are supports, by default (compared case-insensitively)."""

_ANNOTATIONS = {"TEXT", "MTEXT", "DIMENSION", "LEADER", "MLEADER", "ATTDEF", "POINT",
                "VIEWPORT"}
_CURVES = {"CIRCLE", "ELLIPSE", "SPLINE"}


def _entity(e) -> str:
    return f"{e.dxftype()} handle {e.dxf.handle}, layer {e.dxf.layer}"


def _scale(doc, units) -> float:
    """Metres per drawing unit, from ``units`` or the header."""
    if units is not None:
        if units not in UNITS:
            raise ValueError(f"units must be one of {list(UNITS)}, got {units!r}")
        return UNITS[units]
    code = int(doc.header.get("$INSUNITS", 0))
    if code == 0:
        warnings.warn("the drawing is unitless ($INSUNITS 0): its lengths are taken in metres; "
                      "give units= ('mm', 'cm', 'm', 'in', 'ft') if they are not", stacklevel=3)
        return 1.0
    if code not in INSUNITS:
        raise ValueError(f"the drawing's units ($INSUNITS {code}) are none of "
                         f"{sorted(INSUNITS.items())}; give units= {list(UNITS)}")
    return UNITS[INSUNITS[code]]


def _outline(e, arc_chord_error: float | None, scale: float) -> np.ndarray:
    """The vertices of a closed polyline entity [drawing units], or a ValueError naming it."""
    kind = e.dxftype()
    if kind == "LWPOLYLINE":
        points = np.array(list(e.get_points("xyb")), dtype=float).reshape(-1, 3)
        closed = bool(e.closed)
    else:
        if e.is_poly_face_mesh or e.is_polygon_mesh:
            raise ValueError(f"{_entity(e)}: a polyface or mesh is no block outline")
        points = np.array([(*v.dxf.location[:2], v.dxf.get("bulge", 0.0)) for v in e.vertices],
                          dtype=float).reshape(-1, 3)
        closed = bool(e.is_closed)
    if len(points) > 1 and not closed:
        # drawn closed by repeating its first vertex (to round-off of the drawing's size)
        # or beyond it, retracing its first edges: the outline ends where it first returns
        span = float(np.ptp(points[:, :2], axis=0).max())
        back = np.flatnonzero(np.all(np.abs(points[1:, :2] - points[0, :2]) <= 1e-9 * span,
                                     axis=1))
        if back.size and back[0] + 1 >= 3 and np.allclose(
                points[back[0] + 1:, :2], points[:len(points) - back[0] - 1, :2],
                rtol=0.0, atol=1e-9 * span):
            closed = True
            points = points[:back[0] + 1]
    if not closed:
        raise ValueError(f"{_entity(e)}: an open polyline is no block outline (close it)")
    if np.any(points[:, 2] != 0.0):
        if arc_chord_error is None:
            k = int(np.flatnonzero(points[:, 2] != 0.0)[0])
            raise ValueError(f"{_entity(e)}: vertex {k} starts an arc (bulge "
                             f"{points[k, 2]:.6g}); give arc_chord_error [m] to draw arcs as "
                             "chords, or draw the block with straight edges")
        from ezdxf import path as dxf_path

        flat = np.array([(v.x, v.y) for v in dxf_path.make_path(e).flattening(
            arc_chord_error / scale)], dtype=float)
        return flat
    xy = points[:, :2]
    same = 1e-9 * float(np.ptp(xy, axis=0).max()) if len(xy) else 0.0
    keep = np.ones(len(xy), dtype=bool)
    keep[1:] = np.any(np.abs(xy[1:] - xy[:-1]) > same, axis=1)
    xy = xy[keep]
    while len(xy) > 1 and np.all(np.abs(xy[0] - xy[-1]) <= same):
        xy = xy[:-1]
    if len(xy) < 3:
        raise ValueError(f"{_entity(e)}: a block needs at least three distinct vertices, got "
                         f"{len(xy)}")
    return xy


def read_dxf(path: str | os.PathLike, *, units: str | None = None,
             support_layers=SUPPORT_LAYERS, arc_chord_error: float | None = None,
             density: float = DEFAULT_DENSITY, friction=None,
             tolerance: float | None = None) -> BlockAssembly:
    """The block assembly a DXF drawing describes (see the module's rules).

    Parameters
    ----------
    path : str or os.PathLike
        The drawing.
    units : {"mm", "cm", "m", "in", "ft"}, optional
        The drawing's unit of length, overriding its header's ``$INSUNITS``.
    support_layers : sequence of str, default :data:`SUPPORT_LAYERS`
        Layers of the supports (compared case-insensitively).
    arc_chord_error : float, optional
        Largest distance [m] of a chord from the arc it replaces, > 0; arcs in polylines are
        refused without it.
    density : float, default 2000
        Density of every block [kg/m^3].
    friction : None, float or dict
        Coulomb coefficients (:class:`~archquake.geometry.assembly.BlockAssembly`).
    tolerance : float, optional
        Contact tolerance [m] (default 1e-6 of the assembly's size).

    Returns
    -------
    BlockAssembly
        Blocks in the order of the drawing, each named by its entity's handle and layer.

    Raises
    ------
    ValueError
        When the file cannot be read as DXF, holds no block, or an entity is refused (naming
        its handle and layer), or the blocks make no valid assembly (naming the blocks by index,
        handle and layer).
    """
    import ezdxf

    if arc_chord_error is not None and not (
            isinstance(arc_chord_error, int | float) and not isinstance(arc_chord_error, bool)
            and math.isfinite(arc_chord_error) and arc_chord_error > 0):
        raise ValueError(f"arc_chord_error must be a distance [m] > 0, got {arc_chord_error!r}")
    try:
        doc = ezdxf.readfile(os.fspath(path))
    except (OSError, ezdxf.DXFError) as exc:
        raise ValueError(f"cannot read the drawing {str(path)!r} as DXF: {exc}") from exc
    scale = _scale(doc, units)
    layers = {str(name).upper() for name in support_layers}
    blocks, supports, block_names, support_names = [], [], [], []
    ignored = Counter()
    for e in doc.modelspace():
        kind = e.dxftype()
        if kind in ("LWPOLYLINE", "POLYLINE"):
            v = _outline(e, arc_chord_error, scale) * scale
            name = f"handle {e.dxf.handle}, layer {e.dxf.layer}"
            if str(e.dxf.layer).upper() in layers:
                supports.append(v)
                support_names.append(name)
            else:
                blocks.append(v)
                block_names.append(name)
        elif kind in _CURVES:
            raise ValueError(f"{_entity(e)}: a curve is no block outline; draw the block as a "
                             "closed polyline of straight edges")
        elif kind not in _ANNOTATIONS:
            ignored[kind] += 1
    if ignored:
        listed = ", ".join(f"{n} {k}" for k, n in sorted(ignored.items()))
        warnings.warn(f"the drawing's {listed} entities are ignored: blocks and supports are "
                      "closed polylines", stacklevel=2)
    if not blocks:
        raise ValueError(f"the drawing {str(path)!r} holds no block: draw each as a closed "
                         f"polyline on a layer other than {sorted(layers)}")
    return BlockAssembly(tuple(blocks), density, tuple(supports), friction, tolerance,
                         names=tuple(block_names), support_names=tuple(support_names))


def write_dxf(assembly: BlockAssembly, path: str | os.PathLike) -> None:
    """Draw ``assembly`` as DXF (R2010, in metres): every block a closed LWPOLYLINE on layer
    ``BLOCKS``, every support one on layer ``SUPPORT``.

    Parameters
    ----------
    assembly : BlockAssembly
        The assembly (its density, friction and tolerance are not drawn).
    path : str or os.PathLike
        The file to write.
    """
    import ezdxf

    if not isinstance(assembly, BlockAssembly):
        raise ValueError(f"assembly must be a BlockAssembly, got {type(assembly).__name__}")
    doc = ezdxf.new("R2010")
    doc.header["$INSUNITS"] = 6
    doc.layers.add("BLOCKS")
    doc.layers.add("SUPPORT")
    msp = doc.modelspace()
    for layer, polygons in (("BLOCKS", assembly.polygons), ("SUPPORT", assembly.supports)):
        for polygon in polygons:
            msp.add_lwpolyline([tuple(map(float, p)) for p in polygon], close=True,
                               dxfattribs={"layer": layer})
    doc.saveas(Path(path))


__all__ = ["INSUNITS", "SUPPORT_LAYERS", "UNITS", "read_dxf", "write_dxf"]
