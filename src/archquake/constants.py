"""Physical constants and material defaults: the few numbers every part of archquake shares.

This module depends on nothing, so that geometry, ground motions and both dynamic models can
import it without importing one another.
"""

GRAVITY = 9.81
"""Acceleration of gravity g [m/s^2] (the paper does not state it; 9.81 is used throughout)."""

DEFAULT_DENSITY = 2000.0
"""Default masonry density [kg/m^3]. It cancels from every result of the paper."""

__all__ = ["DEFAULT_DENSITY", "GRAVITY"]
