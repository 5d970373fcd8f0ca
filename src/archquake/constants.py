"""Physical constants and material defaults: the few numbers every part of archquake shares.

This module depends on nothing, so that geometry, ground motions and both dynamic models can
import it without importing one another.
"""

GRAVITY = 9.81
"""Acceleration of gravity g [m/s^2] (the paper does not state it; 9.81 is used throughout)."""

DEFAULT_DENSITY = 2000.0
"""Default masonry density [kg/m^3]. It cancels from every result of the paper."""

DEFAULT_FILL_DENSITY = 1800.0
"""Default density of the fill over an arch [kg/m^3] (a compacted granular fill, unit weight
about 18 kN/m^3)."""

__all__ = ["DEFAULT_DENSITY", "DEFAULT_FILL_DENSITY", "GRAVITY"]
