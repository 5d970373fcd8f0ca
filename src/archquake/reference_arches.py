"""Named reference arches, and the paper's published numbers."""

from __future__ import annotations

import tomllib
from importlib import resources

from .defaults import oppenheim_dimensions
from .geometry import DEFAULT_DENSITY, CircularArch, circular_arch


def paper_values() -> dict:
    """The paper's published numbers (``archquake/data/paper_values.toml``), as nested dicts.

    Tables 1-3, the dynamic outcomes of Sect. 5 and the settings of its studies; units m, s,
    rad and accelerations in g. The test suite, :data:`OPPENHEIM` and
    :mod:`archquake.paper_reproduction` all read them from this one file.

    Returns
    -------
    dict
        The TOML file, parsed (e.g. ``paper_values()["table1"]["NA"]["load_multiplier"]`` is
        0.37).
    """
    text = resources.files("archquake").joinpath("data", "paper_values.toml").read_text("utf-8")
    return tomllib.loads(text)


OPPENHEIM = oppenheim_dimensions()
"""Oppenheim's arch [paper, Sect. 2]: R = 10 m, alpha = 157.5 deg, t = 1.5 m, n = 7 (from the
paper's values, ``[oppenheim]``), as the keyword arguments of
:func:`archquake.geometry.circular_arch` (m, rad)."""


def oppenheim(density: float = DEFAULT_DENSITY) -> CircularArch:
    """Oppenheim's arch, the paper's nominal arch "NA" (R = 10 m, 157.5 deg, t = 1.5 m, n = 7).

    Parameters
    ----------
    density : float, default 2000
        Density of the masonry [kg/m^3]; it cancels from every result of the paper.

    Returns
    -------
    CircularArch
        Seven equal voussoirs with radial joints, symmetric about the vertical axis.

    References
    ----------
    .. [1] The paper, Sect. 2 (after Oppenheim, 1992): the nominal arch of every study; its
       limit analysis, mechanism and dynamics are Tables 1-3 and Figs. 2, 6, 9-16.
    """
    return circular_arch(**OPPENHEIM, density=density)

