"""Ground motions by name: :data:`GROUND_MOTIONS` and :func:`ground_motion`."""

from __future__ import annotations

import inspect
from collections.abc import Callable

from .. import defaults
from .core import GroundMotion
from .pulses import (
    antisymmetric_ricker_wavelet,
    cycloidal_a,
    cycloidal_b,
    cycloidal_c,
    harmonic,
    mavroeidis_papageorgiou_pulse,
    oppenheim_pulse,
    rectangular_pulse,
    ricker_wavelet,
    sine_pulse,
)
from .records import record
from .stochastic import stochastic_motion


def stochastic(seed: int = 0, **parameters) -> GroundMotion:
    """Factory of the ``"stochastic"`` entry of :data:`GROUND_MOTIONS`:
    :func:`~.stochastic.stochastic_motion` ``(rng=seed, **parameters)``.

    Parameters
    ----------
    seed : int
        Seed of the white noise, >= 0 [-].
    **parameters
        Model parameters of :func:`~.stochastic.stochastic_motion` (``arias_intensity`` [m/s],
        ``significant_duration`` [s], ``midpoint_time`` [s], ``filter_frequency`` [Hz],
        ``filter_frequency_rate`` [Hz/s], ``filter_damping`` [-], ``high_pass_frequency`` [Hz],
        ``dt`` [s], ``duration`` [s]).
    """
    if isinstance(seed, bool) or float(seed) != int(float(seed)) or int(float(seed)) < 0:
        raise ValueError(f"seed must be a whole number >= 0, got {seed!r}")
    return stochastic_motion(rng=int(float(seed)), **parameters)

GROUND_MOTIONS: dict[str, Callable[..., GroundMotion]] = {
    "oppenheim": oppenheim_pulse,
    "rectangular": rectangular_pulse,
    "sine": sine_pulse,
    "harmonic": harmonic,
    "ricker": ricker_wavelet,
    "ricker-antisymmetric": antisymmetric_ricker_wavelet,
    "cycloidal-a": cycloidal_a,
    "cycloidal-b": cycloidal_b,
    "cycloidal-c": cycloidal_c,
    "mavroeidis-papageorgiou": mavroeidis_papageorgiou_pulse,
    "record": record,
    "stochastic": stochastic,
}
"""Registry of ground motions: name -> factory.

The analytic shapes (listed in :data:`ANALYTIC_GROUND_MOTIONS`) are
``factory(amplitude [m/s^2], time scale [s], **shape parameters)`` with an acceleration
``amplitude * shape(t / time scale)``: the time scale is the pulse duration t_p (``oppenheim``,
``rectangular``) or the period (the others). Their extra parameters: ``harmonic`` ``cycles``;
``cycloidal-c`` ``n`` (main cycles); ``mavroeidis-papageorgiou`` ``gamma`` and ``phase`` [rad].
``record`` is ``record(path, scale_to=None)`` with ``scale_to`` the target peak acceleration [g];
``stochastic`` is ``stochastic(seed=0, **model parameters)`` (:func:`stochastic`).
"""

ANALYTIC_GROUND_MOTIONS: tuple[str, ...] = defaults.ANALYTIC_GROUND_MOTIONS
"""Names in :data:`GROUND_MOTIONS` whose factory takes ``(amplitude [m/s^2], duration [s])``
(named in :mod:`archquake.defaults`, which the command line reads without importing the ground
motions)."""


def ground_motion(name: str, *args, **kwargs) -> GroundMotion:
    """Ground motion by name from :data:`GROUND_MOTIONS`; an unknown name lists the options.

    ``ground_motion("oppenheim", amplitude, duration)`` for an analytic shape (extra shape
    parameters by keyword, e.g. ``ground_motion("harmonic", a, period, cycles=3)``),
    ``ground_motion("record", path, scale_to=None)`` for a recorded accelerogram.
    """
    try:
        factory = GROUND_MOTIONS[name]
    except KeyError:
        raise ValueError(
            f"unknown ground motion {name!r}; choose one of {sorted(GROUND_MOTIONS)}"
        ) from None
    return factory(*args, **kwargs)


def shape_parameters(name: str) -> dict[str, object]:
    """Extra parameters of an analytic ground motion: ``{name: default}`` (after amplitude and
    time scale), e.g. ``{"cycles": 1}`` for ``harmonic``."""
    if name not in ANALYTIC_GROUND_MOTIONS:
        raise ValueError(f"{name!r} is not one of the analytic ground motions "
                         f"{list(ANALYTIC_GROUND_MOTIONS)}")
    params = list(inspect.signature(GROUND_MOTIONS[name]).parameters.values())[2:]
    return {p.name: p.default for p in params if p.kind is not p.KEYWORD_ONLY}
