r"""Time histories of the rocking motion of an arch: :func:`simulate` and :func:`free_vibration`.

The arch moves in Mech-l or Mech-r by Eqs. (6) and (7) in [1]_,

.. math::

    M(\theta)\,\ddot\theta + L(\theta)\,\dot\theta^2 + F(\theta)\,g = \pm P(\theta)\,\ddot x_g(t)

(``+`` Mech-l, ``-`` Mech-r), solved alternately, with an impact at every return to
:math:`\theta_u` (Sect. 4.4 of [1]_: :math:`\dot\theta^+ = -c\,\dot\theta^-`, Eq. (8) in [1]_).
Both functions run the compiled engine of :mod:`archquake.fourlink.engine` (one physics for plots
and studies): the outcome comes from its outcome-only path, the record from its recording path.

Sign convention of the convenience array ``TimeHistory.phi``: :math:`+\varphi` while Mech-l
moves, :math:`-\varphi` while Mech-r moves, 0 at rest, with :math:`\varphi = \theta_u - \theta`
(as in Figs. 9-15 of [1]_, where Mech-l and Mech-r are drawn on either side of the time axis).

References
----------
.. [1] The paper, Sect. 4.3, Eqs. (6)-(7); Sect. 4.4, Eq. (8); Sect. 5.2 (free vibrations,
   Figs. 9-14) and Sect. 5.3 (pulses, Fig. 15).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .._equality import value_equality
from ..ground_motion import GroundMotion, still_ground
from ..status import Status
from . import engine

MECHANISM_NAMES = {"l": engine.MECH_L, "r": engine.MECH_R}
DEFAULT_EXTRA_TIME = 4.0
"""Seconds recorded after the outcome is decided (or the excitation ends) by default [s]."""


@value_equality
@dataclass(frozen=True)
class Outcome:
    """Outcome of one dynamic analysis.

    Parameters
    ----------
    status : Status
        ``Status.REST`` (never activated), ``Status.RECOVERY`` or ``Status.COLLAPSE``
        (:class:`archquake.status.Status`; ``status.label`` is ``"rest"``, ``"recovery"`` or
        ``"collapse"``).
    half_cycle : int
        Half cycle of motion in which the arch collapses [-]: 1 = the first, with no impact;
        ``h`` = after ``h - 1`` impacts; 0 if it does not collapse (Sect. 5.3 of the paper).
    impacts : int
        Impacts before the outcome was decided [-] (for a collapse, ``half_cycle - 1``).
    collapse_time : float
        Time [s] of the last crossing of ``theta_cr`` away from ``theta_u`` before the collapse
        (the point of no return); nan if the arch does not collapse (or, released beyond
        ``theta_cr``, never crosses it).
    max_phi : float
        Largest rotation ``phi = theta_u - theta`` [rad] of the mechanisms: reached during the
        excitation or, for a recovery, still to come after it (from the conserved energy,
        :mod:`archquake.fourlink.engine.rules`); for a collapse, ``theta_u - theta_lo`` of the
        collapsing mechanism (its kinematic limit).
    steps : int
        Integration steps of the analysis [-] (attempted steps, rejected ones included, and
        waits at rest) up to the decision (for a time history, up to the end of the record).
    """

    status: Status
    half_cycle: int
    impacts: int
    collapse_time: float
    max_phi: float
    steps: int

    @property
    def collapsed(self) -> bool:
        """Whether the arch collapses."""
        return self.status is Status.COLLAPSE


@dataclass(frozen=True, eq=False)
class Segment:
    """Motion between two events, in one state.

    Parameters
    ----------
    mechanism : str
        ``"l"``, ``"r"`` or ``"rest"``.
    t : ndarray
        Times [s].
    theta : ndarray
        Lagrangian coordinate [rad] (``theta_u`` of Mech-l at rest).
    phi : ndarray
        ``theta_u - theta`` [rad], >= 0 (0 at rest).
    theta_dot : ndarray
        theta' [rad/s].
    """

    mechanism: str
    t: np.ndarray
    theta: np.ndarray
    phi: np.ndarray
    theta_dot: np.ndarray


@dataclass(frozen=True, eq=False)
class TimeHistory:
    """Recorded motion of an arch.

    Parameters
    ----------
    segments : tuple of Segment
        Motion between events (activation, impact, rest), in order.
    outcome : Outcome
        The outcome of the analysis.
    impact_times : ndarray
        Times of the impacts [s].
    impact_velocities : ndarray, shape (n, 2)
        ``theta'`` just before every impact, in the closing mechanism (>= 0), and just after
        it, in the mechanism that takes over (``-c`` times the first, <= 0) [rad/s].
    impact_mechanisms : tuple of str
        Mechanism moving before every impact (``"l"`` or ``"r"``).
    crossing_times : ndarray
        Times [s] at which theta crosses theta_cr of the moving mechanism, in either
        direction.
    ground_motion : GroundMotion
        The excitation.
    """

    segments: tuple[Segment, ...]
    outcome: Outcome
    impact_times: np.ndarray
    impact_velocities: np.ndarray
    impact_mechanisms: tuple[str, ...]
    crossing_times: np.ndarray
    ground_motion: GroundMotion

    @property
    def t(self) -> np.ndarray:
        """Times of all recorded points [s]."""
        return np.concatenate([s.t for s in self.segments])

    @property
    def phi(self) -> np.ndarray:
        """Signed rotation [rad]: +phi in Mech-l, -phi in Mech-r, 0 at rest."""
        return np.concatenate([(-1.0 if s.mechanism == "r" else 1.0) * s.phi
                               for s in self.segments])

    @property
    def impacts(self) -> int:
        """Number of impacts in the recorded motion (``outcome.impacts`` counts only those
        before the outcome was decided, e.g. none for an arch that is still in its first half
        cycle when the excitation ends and then rocks to rest)."""
        return int(self.impact_times.size)

    @property
    def rest_time(self) -> float:
        """Time [s] from which the arch stays at rest to the end of the record (0 if it is never
        activated); nan if it is still moving at the end of the record or collapses."""
        if self.segments and self.segments[-1].mechanism == "rest":
            return float(self.segments[-1].t[0])
        return math.nan

    @property
    def mechanism(self) -> np.ndarray:
        """State of every recorded point: ``"l"``, ``"r"`` or ``"rest"``."""
        return np.concatenate([np.full(s.t.size, s.mechanism) for s in self.segments])


def _state_name(code: int) -> str:
    return {engine.MECH_L: "l", engine.MECH_R: "r"}.get(code, "rest")


def _outcome(out: np.ndarray, case: str) -> Outcome:
    """The Outcome of an outcome vector of the engine; a contradiction between the decision and
    the motion followed after it (recording path) is an error, not an outcome."""
    status = int(out[engine.OUT_STATUS])
    if status == engine.UNDECIDED or out[engine.OUT_TRUNCATED]:
        raise RuntimeError("the analysis stopped before its outcome was decided "
                           f"({int(out[engine.OUT_STEPS])} steps; {case})")
    outcome = Outcome(Status(status), int(out[engine.OUT_HALF_CYCLE]),
                      int(out[engine.OUT_IMPACTS]), float(out[engine.OUT_COLLAPSE_TIME]),
                      float(out[engine.OUT_MAX_PHI]), int(out[engine.OUT_STEPS]))
    if out[engine.OUT_CONTRADICTION]:
        raise RuntimeError(
            f"the motion after the decision contradicts it: "
            f"{engine.contradiction_message(out[engine.OUT_CONTRADICTION])} "
            f"(decided {outcome.status.label}, half cycle {outcome.half_cycle}, at "
            f"t = {out[engine.OUT_DECISION_TIME]!r} s; contradicted at "
            f"t = {out[engine.OUT_CONTRADICTION_TIME]!r} s; {case})")
    return outcome


def _tables(mechanisms):
    try:
        mech_l, mech_r = mechanisms
    except (TypeError, ValueError) as exc:
        raise ValueError("mechanisms must be a pair (Mech-l, Mech-r)") from exc
    tables = []
    for mech, name in ((mech_l, "l"), (mech_r, "r")):
        table = mech if isinstance(mech, engine.MechanismTable) else engine.tabulate(mech)
        if table.direction != name:
            raise ValueError(f"mechanisms must be (Mech-l, Mech-r); got direction "
                             f"{table.direction!r} in place of {name!r}")
        tables.append(table)
    return tuple(tables)


def simulate(mechanisms, ground_motion: GroundMotion | None = None, restitution=(1.0, 1.0), *,
             t_end: float | None = None, initial=None, record: bool = True,
             rtol: float = engine.DEFAULT_RTOL, atol: float = engine.DEFAULT_ATOL,
             rest_velocity: float = engine.DEFAULT_REST_VELOCITY,
             max_step: float = engine.DEFAULT_MAX_STEP, record_dt: float = 2e-3,
             max_steps: int = engine.DEFAULT_MAX_STEPS):
    r"""Rocking motion of an arch under a ground motion [paper, Sect. 5.3].

    From rest (or ``initial``), Eq. (6) in [1]_ is integrated while Mech-l moves and Eq. (7) in
    [1]_ while Mech-r moves,

    .. math::

        M_l(\theta)\,\ddot\theta + L_l(\theta)\,\dot\theta^2 + F_l(\theta)\,g
            = P_l(\theta)\,\ddot x_g,
        \qquad
        M_r(\theta')\,\ddot\theta' + L_r(\theta')\,\dot\theta'^2 + F_r(\theta')\,g
            = -P_r(\theta')\,\ddot x_g,

    a mechanism starts from rest when the ground opens it (Eq. (2) in [1]_:
    :math:`\ddot x_g/g < -k_l` or :math:`> k_r`), and at every return to :math:`\theta_u` the
    other one takes over with :math:`\dot\theta'^{+} = -c\,\dot\theta^{-}` (Sect. 4.4 of [1]_).
    The outcome is decided as in :mod:`archquake.fourlink.engine.rules`; the record follows the
    motion up to ``t_end`` and checks the decision against it.

    Parameters
    ----------
    mechanisms : tuple
        ``(Mech-l, Mech-r)``: :class:`~archquake.fourlink.mechanism.FourLinkMechanism` (tabulated
        here) or :class:`~archquake.fourlink.engine.MechanismTable`.
    ground_motion : GroundMotion, optional
        Horizontal ground acceleration [m/s^2]; ``None`` for a still ground.
    restitution : tuple of float, or float
        ``(c_lr, c_rl)``: coefficients of restitution of the impacts Mech-l -> Mech-r and
        Mech-r -> Mech-l [-], each > 0 with ``c_lr * c_rl <= 1``; a single number is used for
        both.
    t_end : float, optional
        End of the record [s]; default: the end of the excitation or the instant the outcome is
        decided, whichever is later, plus :data:`DEFAULT_EXTRA_TIME`; a collapse ends the
        record at the kinematic limit.
    initial : tuple, optional
        ``(mechanism, phi0, phidot0)``: start moving in ``"l"`` or ``"r"`` at ``phi = phi0``
        [rad] with ``phi' = phidot0`` [rad/s]; default: at rest.
    record : bool
        Record the motion; if False only the outcome is computed and returned.
    rtol, atol : float
        Tolerances of the local error of a step [-], [rad and rad/s].
    rest_velocity : float
        Speed after an impact below which the arch comes to rest [rad/s].
    max_step : float
        Largest step [s].
    record_dt : float
        Spacing of the recorded samples [s] (events are recorded exactly in addition).
    max_steps : int
        Most integration steps of the analysis, and of the record (a motion that needs more
        is a ValueError: shorten it, or ``t_end``).

    Returns
    -------
    TimeHistory or Outcome
        A :class:`TimeHistory` if ``record``, else the :class:`Outcome`.

    Raises
    ------
    ValueError
        For an invalid argument (the message names it), or if the analysis or the record needs
        more than ``max_steps`` steps.
    RuntimeError
        If the motion recorded after the decision contradicts the decided outcome (a check of
        the engine, :mod:`archquake.fourlink.engine.driver`).

    References
    ----------
    .. [1] The paper, Sect. 3, Eq. (2); Sect. 4.3, Eqs. (6)-(7); Sect. 4.4; Sect. 5.3.
    """
    c_lr, c_rl = engine.check_restitution(*_pair(restitution))
    table_l, table_r = _tables(mechanisms)
    motion = still_ground() if ground_motion is None else ground_motion
    if not isinstance(motion, GroundMotion):
        raise ValueError(f"ground_motion must be a GroundMotion or None, got {motion!r}")
    tab = engine.pack_pair(table_l, table_r)
    scal = tab[0]
    mech0, theta0, thetadot0 = _initial(initial, scal)
    for name, value in (("rtol", rtol), ("atol", atol), ("rest_velocity", rest_velocity),
                        ("max_step", max_step), ("record_dt", record_dt)):
        if not (math.isfinite(value) and value > 0):
            raise ValueError(f"{name} must be a finite number > 0, got {value!r}")
    if t_end is not None and not (math.isfinite(t_end) and t_end > 0):
        raise ValueError(f"t_end must be a finite time > 0 [s], got {t_end!r}")
    if isinstance(max_steps, bool) or not isinstance(max_steps, int) or max_steps < 1:
        raise ValueError(f"max_steps must be an integer >= 1, got {max_steps!r}")
    gm = engine.compiled_motion(motion)
    args = (tab, c_lr, c_rl) + gm
    opts = (rtol, atol, rest_velocity, max_step, max_steps)
    case = (f"{motion.name or 'ground motion'}, restitution ({c_lr!r}, {c_rl!r}), "
            f"initial {initial!r}")
    out, *_ = engine.integrate(*args, 0.0, np.inf, mech0, theta0, thetadot0, *opts, False, 1.0, 0.0)
    if out[engine.OUT_TRUNCATED]:
        raise ValueError(f"the analysis needs more than {max_steps} steps to decide its outcome "
                         f"(the ground motion lasts {motion.duration:g} s): use a shorter "
                         f"motion")
    outcome = _outcome(out, case)
    if not record:
        return outcome
    if t_end is None:
        t_end = max(out[engine.OUT_DECISION_TIME], motion.duration) + DEFAULT_EXTRA_TIME
    # the recording path follows the motion after the decision up to t_end and checks the
    # decision against it (a contradiction raises RuntimeError)
    out, rec, imp, crs = engine.integrate(*args, 0.0, float(t_end), mech0, theta0, thetadot0,
                                          *opts, True, float(record_dt), np.inf)
    if out[engine.OUT_TRUNCATED]:
        reached = float(rec[-1, 0]) if rec.shape[0] else 0.0
        raise ValueError(f"the record to t_end = {t_end:g} s needs more than {max_steps} steps "
                         f"(it reached t = {reached:.6g} s): use a shorter t_end")
    if int(out[engine.OUT_STATUS]) != engine.UNDECIDED:
        # the recording path decides by the same rules; its own outcome is reported
        outcome = _outcome(out, case)
    return _history(rec, imp, crs, scal, outcome, motion)


def _pair(restitution):
    try:
        c_lr, c_rl = restitution
    except (TypeError, ValueError):
        c_lr = c_rl = restitution
    return c_lr, c_rl


def _initial(initial, scal):
    if initial is None:
        return engine.REST_STATE, 0.0, 0.0
    try:
        name, phi0, phidot0 = initial
    except (TypeError, ValueError) as exc:
        raise ValueError("initial must be (mechanism 'l' or 'r', phi0 [rad], phidot0 [rad/s])"
                         ) from exc
    if name not in MECHANISM_NAMES:
        raise ValueError(f"initial mechanism must be one of {sorted(MECHANISM_NAMES)}, "
                         f"got {name!r}")
    m = MECHANISM_NAMES[name]
    phi0, phidot0 = float(phi0), float(phidot0)
    phi_max = scal[m, 0] - scal[m, 2]
    if not (0.0 <= phi0 < phi_max):
        raise ValueError(f"initial phi0 must be in [0, {phi_max:.6g}) rad, got {phi0!r}")
    if not math.isfinite(phidot0):
        raise ValueError(f"initial phidot0 must be a finite number [rad/s], got {phidot0!r}")
    if phi0 == 0.0 and phidot0 <= 0.0:
        if phidot0 < 0.0:
            raise ValueError("at phi0 = 0 the initial phidot0 must be >= 0 (phi cannot be < 0)")
        return engine.REST_STATE, 0.0, 0.0
    return m, scal[m, 0] - phi0, -phidot0


def _history(rec, imp, crs, scal, outcome, motion) -> TimeHistory:
    segments = []
    if rec.shape[0]:
        seg_ids = rec[:, 4]
        cuts = np.flatnonzero(np.diff(seg_ids) != 0) + 1
        states = rec[:, 3]
        # a segment id also changes when the arch comes to rest after an impact
        cuts = np.union1d(cuts, np.flatnonzero(np.diff(states) != 0) + 1)
        for part in np.split(np.arange(rec.shape[0]), cuts):
            rows = rec[part]
            state = int(rows[0, 3])
            if state >= 0:
                theta = rows[:, 1].copy()
                phi = scal[state, 0] - theta
            else:
                theta = np.full(rows.shape[0], scal[engine.MECH_L, 0])
                phi = np.zeros(rows.shape[0])
            segments.append(Segment(_state_name(state), rows[:, 0].copy(), theta, phi,
                                    rows[:, 2].copy()))
    return TimeHistory(tuple(segments), outcome, imp[:, 0].copy(), imp[:, 2:4].copy(),
                       tuple(_state_name(int(x)) for x in imp[:, 1]), crs[:, 0].copy(), motion)


def free_vibration(mechanisms, restitution=(1.0, 1.0), phi0: float = 0.02, *,
                   mechanism: str = "l", phidot0: float = 0.0, **kwargs):
    """Free rocking from a displaced configuration [paper, Sect. 5.2, Figs. 9-14].

    Eq. (6) (or (7)) of the paper with a still ground, from ``phi = phi0``, ``phi' = phidot0``
    in ``mechanism``: the paper releases its arches from ``phi0 = 0.02`` rad at rest,
    with ``c_v = 1`` (Figs. 9-11) and ``c_v = 0.875`` (Figs. 12-14).

    Parameters
    ----------
    mechanisms : tuple
        ``(Mech-l, Mech-r)`` (mechanisms or tables).
    restitution : tuple of float, or float
        ``(c_lr, c_rl)`` [-] (see :func:`simulate`).
    phi0 : float
        Initial rotation ``phi = theta_u - theta`` [rad], in ``[0, theta_u - theta_lo)`` (the
        paper uses 0.02).
    mechanism : str
        Mechanism displaced initially, ``"l"`` or ``"r"``.
    phidot0 : float
        Initial ``phi'`` [rad/s] (>= 0 when ``phi0 = 0``).
    **kwargs
        Passed to :func:`simulate` (``t_end``, ``record``, tolerances).

    Returns
    -------
    TimeHistory or Outcome
        As :func:`simulate`.

    Raises
    ------
    ValueError
        For an invalid argument (see :func:`simulate`).
    """
    return simulate(mechanisms, None, restitution, initial=(mechanism, phi0, phidot0), **kwargs)
