r"""The quasi-static ramp (tilt) test of a rigid-block structure: its collapse multiplier.

A horizontal ground acceleration that grows slowly from zero, :math:`\ddot x_g(t) = -s\,r\,g\,t`,
loads every block with the inertial force :math:`s\,k(t)\,m_i g` along x, :math:`k(t) = r t`
(``r`` the ``rate`` [1/s], ``s = +1`` for the direction ``"+x"`` and ``-1`` for ``"-x"``), the
load of limit analysis (a horizontal acceleration ``k g`` acting on every block). A constant
ratio ``k`` is the load of a table tilted by :math:`\theta = \arctan k` (gravity ``g cos(theta)``
across the table and ``g sin(theta)`` along it: their ratio is ``tan(theta)``), so the test is
also the tilting-table test [1]_. The structure is the rigid-block model of
:mod:`archquake.rigid_blocks.dynamics` (unilateral contacts, Coulomb friction without
dilatancy: a non-associative law, so the multiplier it finds is the physical one, which the
associative limit analysis may overestimate [2]_).

Onset of motion
---------------
Rigid blocks do not move at all while the load is below the collapse multiplier (only
round-off: about :math:`10^{-10}` of the thickness). Let ``t`` be the thickness of the
structure [m] and :math:`\delta = ` ``threshold`` :math:`\times\,t` [m]. The measure of motion
is the largest opening (larger end gap) or slip (tangential offset at the more closed end) of
any joint, ``m(t)`` [m]; it is read at every step and its crossings of
:math:`\delta_i = 10^{i-1}\,\delta` (``i = 1, 2, 3``) are located by linear interpolation
between steps, at multipliers :math:`k_1 < k_2 < k_3`. Past the onset :math:`k_c` the motion
grows as the cube of the time since the onset: a block sliding under the load
:math:`(k(t) - \mu) m g` slips by

.. math::

    u = \frac{g\,r\,(t - t_c)^3}{6},

and a mechanism (a block rocking, an arch's four hinges) as :math:`A r \bigl(\sinh p\tau -
p\tau\bigr)/p^3 = A r \tau^3/6\,(1 + p^2\tau^2/20 + \dots)` with :math:`\tau = t - t_c` (its
linearised equation :math:`\ddot\theta = A\,r\,\tau + p^2\theta` from rest, ``p`` the rate of
growth of the unstable mechanism [1/s]). So :math:`m \propto (k - k_c)^3` near the onset, and
two crossings extrapolate back to it: with :math:`\rho = (\delta_{i+1}/\delta_i)^{1/3} =
10^{1/3}`,

.. math::

    k_c = \frac{k_{i+1} - \rho\,k_i}{1 - \rho}.

The multiplier is :math:`k_c` of the first pair (``i = 1``); the second pair's differs from it by
the higher-order terms, which grow with :math:`\delta`, about ten times more for it than for the
first: their difference, plus one step's growth of the load :math:`r h`, is the stated error

.. math::

    \epsilon_k = \lvert k_c^{(1,2)} - k_c^{(2,3)} \rvert + r\,h.

The lag of the first crossing behind the onset, :math:`k_1 - k_c`, is
:math:`r\,(6\delta/(g r))^{1/3}` for sliding (0.0009 at ``r`` = 0.05 /s for a block 0.4 m wide)
and is what the extrapolation removes; the extrapolated multiplier converges as
:math:`r \to 0` (``benchmarks/rigid_block_ramp.py``).

Joints at the onset: at the third crossing (the decision), a joint *rocks* if its opening, and
*slides* if its slip, is at least :math:`\delta_2` (a tenth of the measure then).

The ramp in pieces
------------------
The ramp is run in pieces, each from rest: a piece starting at the multiplier :math:`k_a`
loads the structure with :math:`k_a + r t` (a jump of the load from rest is exact for rigid
blocks below the onset: they do not move). A piece in which the measure stays below
:math:`10^{-3}\,\delta` (at rest to round-off) is passed; once a piece moves, the analysis starts
again from the start of the piece before it (at rest, whatever moved below
:math:`10^{-3}\delta` at its end) and runs, doubling its length, until the measure crosses
:math:`\delta_3`: the ramp stops as soon as the onset is decided, at most a few pieces past it,
and never follows the collapse. No onset up to ``max_multiplier`` gives ``inf``; an onset
within its error of zero gives 0: the structure does not stand under its own weight (it moves
from the start of the ramp, as the square of the time, and the cubic extrapolation would fall a
little below zero).

Friction
--------
The solver takes one Coulomb coefficient for every contact
(:class:`~archquake.rigid_blocks.dynamics.BlockSettings`); the test takes one too.

Oppenheim's arch (``archquake.oppenheim()``, load toward +x, default rate): with
:math:`\mu \ge 0.5` four hinges form (joints 0, 3, 5, 7) at :math:`k = 0.3700`, the limit
analysis's multiplier; below, the right springing slides beside three hinges and the multiplier
falls: 0.3184 at :math:`\mu = 0.45`, 0.2638 at 0.4 (hinges 0, 3, 5), 0.1472 at 0.3 (hinges 1,
3, 6). Each is, within the stated error (6e-5), the multiplier of the static program with
Coulomb cones at the joint ends (the associative bound): on this arch the non-associative
multiplier reaches it (``tests/rigid_blocks/test_ramp.py``).

References
----------
.. [1] G. W. Housner, "The behavior of inverted pendulum structures during earthquakes", Bull.
   Seismol. Soc. Am. 53 (1963) 403-417 (the block's static multiplier ``b/h``).

.. [2] M. Gilbert, C. Casapulla, H. M. Ahmed, "Limit analysis of masonry block structures with
   non-associative frictional joints using linear programming", Comput. Struct. 84 (2006)
   873-887.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields

import numpy as np

from .._equality import value_equality
from ..checks import json_float
from ..defaults import DEFAULT_FRICTION, MAX_BLOCK_STEPS
from ..geometry import GRAVITY
from ..ground_motion import LINEAR, GroundMotion
from .dynamics import BlockSettings, simulate_blocks, structure_assembly, time_step_for

DEFAULT_RAMP_RATE = 0.05
r"""Default growth of the multiplier per second, ``r`` [1/s]: the ground acceleration grows by
0.05 g per second. The extrapolated onset is then within 2e-6 of the exact multiplier of
Housner's block (rocking 0.4, sliding 0.3) and of Oppenheim's arch (0.3700), with a stated
error of 3e-5 to 6e-5, where the first crossing lags by 0.0009 to 0.0016; the lag falls as
``r^(2/3)`` (``benchmarks/rigid_block_ramp.py``). A test to ``k`` = 0.4 takes about 10 s of
motion, some 0.05 s of computation."""

DEFAULT_RAMP_THRESHOLD = 1e-6
"""Default first threshold of the measure of motion, as a fraction of the thickness [-]:
10,000 times the round-off of a structure at rest (about 1e-10 of its thickness)."""

REST_FRACTION = 1e-3
"""A piece of the ramp is at rest while its measure of motion stays below this fraction of the
first threshold [-] (10 times the round-off at the default threshold)."""

THRESHOLD_RATIO = 10.0
"""Ratio of successive thresholds :math:`\\delta_{i+1} / \\delta_i` [-]."""

PIECE_MULTIPLIER = 0.05
"""Growth of the multiplier over one piece of the ramp [-] (at least 50 time steps)."""

DIRECTIONS = ("+x", "-x")
"""Directions of the horizontal load ``k g`` on the blocks (the ground accelerates the other
way): ``"+x"`` is the load of Mech-l of :mod:`archquake.limit_analysis`."""


@value_equality
@dataclass(frozen=True)
class RampOnset:
    """The onset of motion in one direction of a ramp test.

    Attributes
    ----------
    direction : str
        ``"+x"`` or ``"-x"``: the direction of the horizontal load on the blocks.
    multiplier : float
        Collapse multiplier ``k``: the ratio of the horizontal load to the weight at the
        onset of motion [-] (module docstring); ``inf`` if nothing moved up to
        ``max_multiplier``; 0 if the structure does not stand under its own weight (it moved
        from the start of the ramp).
    error : float
        Estimated error of ``multiplier`` [-] (module docstring); nan if nothing moved.
    crossings : tuple of float
        Multipliers at which the measure of motion crossed its three thresholds [-].
    rocking_joints : tuple of int
        Joints open at the decision, as the structure's interfaces
        (:meth:`~archquake.rigid_blocks.Assembly.interfaces_of`: the chords of a ring interface
        that the rigid blocks take as one arc are all listed).
    sliding_joints : tuple of int
        Joints slipping at the decision, the same way.
    found : bool
        Whether the onset was found below ``max_multiplier``.
    steps : int
        Time steps taken in this direction, over every piece [-].
    """

    direction: str
    multiplier: float
    error: float
    crossings: tuple
    rocking_joints: tuple
    sliding_joints: tuple
    found: bool
    steps: int

    @property
    def tilt(self) -> float:
        """Tilt of a table that loads as the multiplier does, ``atan(k)`` [degrees]."""
        return math.degrees(math.atan(self.multiplier))

    @property
    def mode(self) -> str:
        """``"rocking"``, ``"sliding"``, ``"mixed"`` (both) or ``"none"`` (nothing moved)."""
        rocks, slides = bool(self.rocking_joints), bool(self.sliding_joints)
        return {(True, False): "rocking", (False, True): "sliding",
                (True, True): "mixed"}.get((rocks, slides), "none")

    def to_dict(self) -> dict:
        """JSON-ready summary (nan and inf as None, :func:`archquake.checks.json_float`)."""
        out = {f.name: getattr(self, f.name) for f in fields(self)}
        out.update(multiplier=json_float(self.multiplier), error=json_float(self.error),
                   tilt=json_float(self.tilt), mode=self.mode,
                   crossings=[json_float(k) for k in self.crossings],
                   rocking_joints=list(self.rocking_joints),
                   sliding_joints=list(self.sliding_joints))
        return out


@value_equality
@dataclass(frozen=True)
class RampResult:
    """The ramp test of a structure in both directions.

    Attributes
    ----------
    onsets : tuple of RampOnset
        One per direction tested, in the order asked.
    friction : float
        Coulomb coefficient of every contact [-].
    rate : float
        Growth of the multiplier per second [1/s].
    threshold : float
        First threshold of the measure of motion, as a fraction of the thickness [-].
    time_step : float
        Time step [s].
    """

    onsets: tuple
    friction: float
    rate: float
    threshold: float
    time_step: float

    def onset(self, direction: str) -> RampOnset:
        """The onset in ``direction`` (``"+x"`` or ``"-x"``)."""
        for onset in self.onsets:
            if onset.direction == direction:
                return onset
        raise ValueError(f"direction must be one of {[o.direction for o in self.onsets]}, "
                         f"got {direction!r}")

    @property
    def multiplier(self) -> float:
        """The smaller multiplier of the directions tested [-]."""
        return min(onset.multiplier for onset in self.onsets)

    def to_dict(self) -> dict:
        """JSON-ready summary."""
        return {"onsets": [o.to_dict() for o in self.onsets], "friction": self.friction,
                "rate": self.rate, "threshold": self.threshold, "time_step": self.time_step,
                "multiplier": json_float(self.multiplier)}


def _check_positive(name: str, value, unit: str, at_most: float | None = None) -> float:
    try:
        value = float(value)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be a number [{unit}], got {value!r}") from exc
    if not (math.isfinite(value) and value > 0):
        raise ValueError(f"{name} must be a finite number > 0 [{unit}], got {value!r}")
    if at_most is not None and value > at_most:
        raise ValueError(f"{name} must be at most {at_most:g} [{unit}], got {value!r}")
    return value


def _piece(assembly, settings: BlockSettings, sign: float, start: float, rate: float,
           length: float):
    """Run one piece of the ramp from rest: load ``start + rate t`` for ``length`` seconds.

    Returns ``(multipliers (nr,), measure (nr,), openings (nr, nj), slips (nr, nj), steps)``.
    """
    h = float(settings.time_step)
    end = length + 4.0 * h  # the table outlasts the last step
    motion = GroundMotion(LINEAR, [0.0, end],
                          [-sign * start * GRAVITY, -sign * (start + rate * end) * GRAVITY],
                          name="ramp")
    history = simulate_blocks(assembly, motion, settings, t_end=length)
    openings = history.openings
    slips = np.abs(history.slips)
    measure = np.maximum(openings.max(axis=1), slips.max(axis=1))
    return start + rate * history.times, measure, openings, slips, history.outcome.steps


def _crossing(k: np.ndarray, measure: np.ndarray, level: float) -> float:
    """First multiplier at which ``measure`` reaches ``level``, interpolated linearly [-]."""
    i = int(np.argmax(measure >= level))
    if i == 0:
        return float(k[0])
    w = (level - measure[i - 1]) / (measure[i] - measure[i - 1])
    return float(k[i - 1] + w * (k[i] - k[i - 1]))


def _onset(assembly, settings: BlockSettings, direction: str, rate: float, threshold: float,
           max_multiplier: float) -> RampOnset:
    """The onset of motion in one direction (module docstring, "The ramp in pieces")."""
    sign = 1.0 if direction == "+x" else -1.0
    h = float(settings.time_step)
    levels = threshold * assembly.thickness * THRESHOLD_RATIO ** np.arange(3)
    rest = REST_FRACTION * levels[0]
    piece = max(PIECE_MULTIPLIER, 50.0 * h * rate)
    steps, start, previous = 0, 0.0, 0.0
    while start < max_multiplier:
        length = min(piece, max_multiplier - start)
        k, measure, *_, n = _piece(assembly, settings, sign, start, rate, length / rate)
        steps += n
        if measure.max() >= rest:
            break
        previous, start = start, start + length
    else:
        return RampOnset(direction, math.inf, math.nan, (), (), (), False, steps)
    # from the start of the piece before (at rest), doubling until the third threshold
    span = 2.0 * piece
    while True:
        span = min(span, max_multiplier - previous)
        k, measure, openings, slips, n = _piece(assembly, settings, sign, previous, rate,
                                                span / rate)
        steps += n
        if measure.max() >= levels[2] or previous + span >= max_multiplier:
            break
        span *= 2.0
    if measure.max() < levels[2]:
        return RampOnset(direction, math.inf, math.nan, (), (), (), False, steps)
    crossings = tuple(_crossing(k, measure, level) for level in levels)
    rho = THRESHOLD_RATIO ** (1.0 / 3.0)
    first = (crossings[1] - rho * crossings[0]) / (1.0 - rho)
    second = (crossings[2] - rho * crossings[1]) / (1.0 - rho)
    decision = int(np.argmax(measure >= levels[2]))
    rocking = assembly.interfaces_of(np.flatnonzero(openings[decision] >= levels[1]))
    sliding = assembly.interfaces_of(np.flatnonzero(slips[decision] >= levels[1]))
    error = abs(first - second) + rate * h
    # moving from the start: the structure does not stand under its own weight
    return RampOnset(direction, float(first) if first > error else 0.0, float(error), crossings,
                     rocking, sliding, True, steps)


def ramp_test(structure, *, friction: float | None = None, rate: float = DEFAULT_RAMP_RATE,
              threshold: float = DEFAULT_RAMP_THRESHOLD, max_multiplier: float = 2.0,
              directions=DIRECTIONS, time_step: float | None = None) -> RampResult:
    r"""The quasi-static ramp (tilt) test: the multiplier at the onset of sustained motion.

    A horizontal load :math:`k(t)\,m_i g` on every block, :math:`k(t) = r t`, in each direction
    (module docstring): the collapse multiplier is the ``k`` at the onset of motion,
    extrapolated back from the crossings of three thresholds of the largest joint opening or
    slip,

    .. math::

        k_c = \frac{k_2 - 10^{1/3} k_1}{1 - 10^{1/3}},

    the tilt of the equivalent table :math:`\arctan k_c`.

    Parameters
    ----------
    structure : BlockArch or Assembly
        The structure (an arch by :func:`~archquake.rigid_blocks.from_arch`).
    friction : float, optional
        Coulomb coefficient of every contact [-], >= 0 and finite (the solver takes one for
        all contacts); None: :data:`archquake.defaults.DEFAULT_FRICTION` (0.8).
    rate : float
        Growth of the multiplier per second ``r`` [1/s], in (0, 10]: the ground acceleration
        grows by ``r g`` per second.
    threshold : float
        First threshold of the measure of motion as a fraction of the thickness [-], in
        [1e-8, 1e-3] (the others 10 and 100 times it).
    max_multiplier : float
        Largest multiplier ramped to [-], in (0, 10].
    directions : sequence of str
        Directions tested, of ``("+x", "-x")`` (the direction of the load on the blocks).
    time_step : float, optional
        Time step [s]; None: the structure's default
        (:func:`~archquake.rigid_blocks.dynamics.structure_time_step`).

    Returns
    -------
    RampResult
        The onset in each direction, with its multiplier, tilt, error and joints.

    Raises
    ------
    ValueError
        Naming the parameter out of its range (``rate`` also if the ramp to
        ``max_multiplier`` would take more than
        :data:`~archquake.defaults.MAX_BLOCK_STEPS` time steps), or as
        :func:`~archquake.rigid_blocks.simulate_blocks` for the structure.

    References
    ----------
    .. [1] M. Gilbert, C. Casapulla, H. M. Ahmed, "Limit analysis of masonry block structures
       with non-associative frictional joints using linear programming", Comput. Struct. 84
       (2006) 873-887.

    Examples
    --------
    Housner's block 0.4 m x 1 m rocks at ``k = b/h = 0.4`` when it cannot slide:

    >>> from archquake.rigid_blocks import rectangular_block
    >>> result = ramp_test(rectangular_block(0.4, 1.0), friction=2.0, directions=("+x",))
    >>> onset = result.onset("+x")
    >>> round(onset.multiplier, 3), onset.mode
    (0.4, 'rocking')
    """
    assembly = structure_assembly(structure)
    friction = DEFAULT_FRICTION if friction is None else friction
    if isinstance(friction, bool) or not isinstance(friction, (int, float, np.floating)):
        raise ValueError(f"friction must be one number >= 0 [-] (the solver takes one "
                         f"coefficient for every contact), got {friction!r}")
    if not (math.isfinite(friction) and friction >= 0):
        raise ValueError(f"friction must be a finite number >= 0 [-], got {friction!r}")
    rate = _check_positive("rate", rate, "1/s", at_most=10.0)
    threshold = _check_positive("threshold", threshold, "-", at_most=1e-3)
    if threshold < 1e-8:
        raise ValueError(f"threshold must be at least 1e-8 [-] (above round-off), got "
                         f"{threshold!r}")
    max_multiplier = _check_positive("max_multiplier", max_multiplier, "-", at_most=10.0)
    if isinstance(directions, str):
        directions = (directions,)
    directions = tuple(directions)
    if not directions or any(d not in DIRECTIONS for d in directions):
        raise ValueError(f"directions must be a non-empty sequence of {DIRECTIONS}, got "
                         f"{directions!r}")
    h = time_step_for(assembly) if time_step is None else _check_positive(
        "time_step", time_step, "s")
    if max_multiplier / rate / h > MAX_BLOCK_STEPS:
        raise ValueError(f"rate must be at least {max_multiplier / (MAX_BLOCK_STEPS * h):.3g} "
                         f"[1/s] to ramp to {max_multiplier:g} in at most {MAX_BLOCK_STEPS} "
                         f"time steps of {h:g} s (MAX_BLOCK_STEPS), got {rate!r}")
    settings = BlockSettings(friction=float(friction), time_step=h)
    onsets = tuple(_onset(assembly, settings, d, rate, threshold, max_multiplier)
                   for d in directions)
    return RampResult(onsets, float(friction), rate, threshold, h)


__all__ = ["DEFAULT_RAMP_RATE", "DEFAULT_RAMP_THRESHOLD", "DIRECTIONS", "PIECE_MULTIPLIER",
           "REST_FRACTION", "THRESHOLD_RATIO", "RampOnset", "RampResult", "ramp_test"]
