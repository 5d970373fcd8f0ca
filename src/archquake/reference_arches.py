"""Named reference arches."""

from __future__ import annotations

import math
import tomllib
from importlib import resources

from .geometry import DEFAULT_DENSITY, Arch, circular_arch

OPPENHEIM = {"radius": 10.0, "embrace": math.radians(157.5), "thickness": 1.5, "voussoirs": 7}
"""Oppenheim's arch [paper, Sect. 2]: R = 10 m, alpha = 157.5 deg, t = 1.5 m, n = 7."""


def oppenheim(density: float = DEFAULT_DENSITY) -> Arch:
    """Oppenheim's arch, the paper's nominal arch "NA" (R = 10 m, 157.5 deg, t = 1.5 m, n = 7)."""
    return circular_arch(**OPPENHEIM, density=density)


def paper_values() -> dict:
    """The paper's published numbers (``archquake/data/paper_values.toml``), as nested dicts.

    Tables 1-3, the dynamic outcomes of Sect. 5 and the settings of its studies; units m, s,
    rad and accelerations in g. The test suite and :mod:`archquake.paper_reproduction` both read
    them from this one file.
    """
    text = resources.files("archquake").joinpath("data", "paper_values.toml").read_text("utf-8")
    return tomllib.loads(text)
