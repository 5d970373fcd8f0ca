"""Arch descriptions as dicts and JSON files, of any kind.

Four JSON objects describe an arch (every length in m, angle in rad, density in kg/m^3; every
value a JSON number):

- the paper's circular arch voussoir by voussoir, ``{"angles": [...], "thicknesses": [...],
  "radii": [...]}`` (:meth:`CircularArch.from_dict <archquake.geometry.CircularArch.from_dict>`,
  placed symmetric);
- a surveyed arch, ``{"blocks": [[[x, y], ...], ...], "springings": ...}``
  (:mod:`archquake.geometry.survey`);
- an arch of a shape voussoir by voussoir, ``{"shape": ..., "span": ..., "rise": ...,
  "faces": ..., "lengths": [...], "thicknesses": [...], "offsets": [...]}``
  (:meth:`ShapedArch.to_dict <archquake.geometry.ShapedArch.to_dict>`);
- an arch on piers or with fill, ``{"arch": <one of the above>, "left_pier": ...,
  "right_pier": ..., "fill": ...}`` (:meth:`Structure.to_dict
  <archquake.geometry.Structure.to_dict>`).

One JSON object describes any block assembly (a wall, a portal, ...), not an arch:

- ``{"blocks": [[[x, y], ...], ...], "supports": [[[x, y], ...], ...], "density": ...,
  "friction": ..., "tolerance": ...}`` (:meth:`BlockAssembly.to_dict
  <archquake.geometry.assembly.BlockAssembly.to_dict>`): ``"blocks"`` with ``"supports"``
  (an empty list: the ground is the lowest line of the blocks), ``"friction"`` or ``"kinds"``.
  ``"blocks"`` alone (or with ``"springings"``) stays the surveyed arch it always was.

Each may hold a ``"density"``. The kind is told by the keys. :func:`load_arch` also reads a
drawing (a ``.dxf`` file, :func:`archquake.geometry.dxf.read_dxf`) as a block assembly.
"""

from __future__ import annotations

import os
import warnings
from pathlib import Path

from ..constants import DEFAULT_DENSITY
from .arch import CircularArch
from .assembly import BlockAssembly
from .blocks import BlockArch, read_json_file
from .fill import Fill
from .piers import Pier
from .shaped import ShapedArch
from .structure import Structure
from .survey import SurveyedArch

KINDS = {"angles": CircularArch, "blocks": SurveyedArch, "shape": ShapedArch, "arch": Structure}
"""The key that tells each kind of description."""

ASSEMBLY_KEYS = ("supports", "friction", "kinds")
"""Keys that make a ``"blocks"`` description a :class:`BlockAssembly` (not a surveyed arch)."""


def arch_from_dict(data, *, density: float = DEFAULT_DENSITY,
                   replace_density: bool = False) -> BlockArch | BlockAssembly:
    """The arch (or block assembly) a dict describes (see the module for the forms).

    Parameters
    ----------
    data : dict
        The description.
    density : float, default 2000
        Density [kg/m^3] when ``data`` gives none, or always with ``replace_density``.
    replace_density : bool, default False
        Whether ``density`` replaces the density ``data`` gives (a structure's arch's included).

    Returns
    -------
    CircularArch, SurveyedArch, ShapedArch, Structure or BlockAssembly

    Raises
    ------
    ValueError
        When ``data`` is not a dict of one of the five forms (the message says which keys were
        expected) or describes no valid arch.
    """
    if not isinstance(data, dict):
        raise ValueError("geometry must be a JSON object: {'angles', 'thicknesses', 'radii'} "
                         "per voussoir, {'blocks'} polygons, or {'shape', ...}; got "
                         f"{type(data).__name__}")
    if "blocks" in data and any(key in data for key in ASSEMBLY_KEYS):
        if replace_density:
            data = {**data, "density": density}
        return BlockAssembly.from_dict(data, density=density)
    kinds = [key for key in KINDS if key in data]
    if len(kinds) != 1:
        if not kinds and not {"thicknesses", "radii"} & set(data):
            raise ValueError("geometry must have one of the keys 'angles' (with 'thicknesses' "
                             "and 'radii'), 'blocks' or 'shape'; got "
                             f"{sorted(map(str, data))}")
        if len(kinds) > 1:
            raise ValueError(f"geometry has the keys {kinds} of different kinds of arch; give one")
        kinds = ["angles"]  # an incomplete circular description: its own error names the key
    cls = KINDS[kinds[0]]
    if cls is Structure:
        return _structure_from_dict(data, density, replace_density)
    if replace_density:
        data = {**data, "density": density}
    if cls is ShapedArch:
        return ShapedArch.from_dict({"density": density, **data})
    return cls.from_dict(data, density=density)


def _structure_from_dict(data: dict, density: float, replace_density: bool) -> Structure:
    """The structure of :meth:`Structure.to_dict <archquake.geometry.Structure.to_dict>`:
    ``arch`` any arch description, the other keys optional."""
    keys = {"arch", "left_pier", "right_pier", "fill"}
    unknown = sorted(set(data) - keys)
    if unknown:
        raise ValueError(f"a structure has unknown key(s) {unknown}; allowed: {sorted(keys)}")
    arch = arch_from_dict(data["arch"], density=density, replace_density=replace_density)
    if isinstance(arch, Structure):
        raise ValueError("a structure's 'arch' must describe an arch, not a structure")
    left, right, fill = (data.get(k) for k in ("left_pier", "right_pier", "fill"))
    return Structure(arch, None if left is None else Pier.from_dict(left),
                     None if right is None else Pier.from_dict(right),
                     None if fill is None else Fill.from_dict(fill))


def load_arch(path: str | Path, *, density: float = DEFAULT_DENSITY,
              replace_density: bool = False, units: str | None = None
              ) -> BlockArch | BlockAssembly:
    """The arch of a JSON file of any of the forms of the module, or the block assembly of a
    JSON file or a drawing (``.dxf``, :func:`archquake.geometry.dxf.read_dxf`, in the units
    of its header).

    Parameters
    ----------
    path : str or pathlib.Path
        The file (UTF-8 JSON).
    density : float, default 2000
        Density [kg/m^3] when the file gives none, or always with ``replace_density``.
    replace_density : bool, default False
        Whether ``density`` replaces the density the file gives (every file archquake writes
        gives one).
    units : str, optional
        A drawing's length unit, overriding its header's (:func:`~archquake.geometry.dxf.read_dxf`).

    Returns
    -------
    CircularArch, SurveyedArch, ShapedArch, Structure or BlockAssembly

    Raises
    ------
    ValueError
        Naming the file, when it cannot be read, is not JSON (with the line) or does not
        describe an arch.
    """
    if not isinstance(path, str | os.PathLike):
        raise ValueError(f"path must be the name of a geometry file (str or os.PathLike), got "
                         f"{path!r}")
    if Path(path).suffix.lower() == ".dxf":
        from .dxf import read_dxf

        try:
            return read_dxf(path, density=density, units=units)
        except ValueError as exc:
            raise ValueError(f"geometry file {str(path)!r}: {exc}") from exc
    data = read_json_file(path, "a JSON object with 'angles', 'thicknesses' and 'radii', or "
                                "'blocks', or 'shape'")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            arch = arch_from_dict(data, density=density, replace_density=replace_density)
        except ValueError as exc:
            raise ValueError(f"geometry file {str(path)!r}: {exc}") from exc
    for warning in caught:  # said again, naming the file
        warnings.warn(f"geometry file {str(path)!r}: {warning.message}", warning.category,
                      stacklevel=2)
    return arch
