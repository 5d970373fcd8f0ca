"""The front door: :class:`FourLinkModel`, everything the dynamics of one arch needs, built once.

The paper's chain from an arch to its dynamics -- limit analysis in both directions [paper,
Sect. 3], the two four-link mechanisms built on its hinges [Sects. 4.1-4.2], the coefficients of
restitution of the impacts between them [Sect. 4.4] and the compiled tables of their equations of
motion [eqs. (6)-(7)] -- is one value, built by :meth:`FourLinkModel.from_arch`. Every analysis of
the arch runs from it: a time history (:meth:`~FourLinkModel.simulate`), an outcome
(:meth:`~FourLinkModel.outcome`), a grid of pulses in one compiled call
(:meth:`~FourLinkModel.outcomes`); the failure domain and the studies run from it through the model
protocol (:func:`archquake.studies.failure_domain.domain_of`).

>>> from archquake import FourLinkModel, GRAVITY, oppenheim
>>> from archquake.ground_motion import oppenheim_pulse
>>> dynamics = FourLinkModel.from_arch(oppenheim(), restitution="paper")
>>> dynamics.simulate(oppenheim_pulse(-GRAVITY, 0.27)).outcome.status.label
'collapse'
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import ClassVar

import numpy as np

from ..checks import pulse_grid
from ..defaults import (
    DEFAULT_LIMIT_METHOD,
    DEFAULT_RESTITUTION,
    REST_MARGIN,
)
from ..geometry import GRAVITY, BlockArch


@dataclass(frozen=True, eq=False)
class FourLinkModel:
    """The four-link model of one arch: its limit analyses, mechanisms, restitution and compiled
    tables.

    Build it with :meth:`from_arch` (or :func:`archquake.models.model_for` with
    ``model="four-link"``). It satisfies :class:`archquake.models.StructuralModel`. It is
    immutable and compared by identity; building it costs two limit analyses and the tabulation
    of two mechanisms (a few tens of milliseconds), after which every analysis is a call of the
    compiled engine.

    Attributes
    ----------
    arch : BlockArch
        The arch (of any shape: :mod:`archquake.geometry`).
    limit : (LimitAnalysis, LimitAnalysis)
        Limit analyses of Mech-l and Mech-r [paper, Sect. 3] (Mech-r on the mirrored arch):
        the load multipliers ``k_l``, ``k_r`` [-] and the hinges.
    mechanisms : (FourLinkMechanism, FourLinkMechanism)
        Mech-l and Mech-r [paper, Sects. 4.1-4.2].
    restitution : (float, float)
        Coefficients of restitution ``(c_lr, c_rl)`` of the impacts Mech-l -> Mech-r and
        Mech-r -> Mech-l [-] (eq. (8) of the paper: ``theta'`` after = ``-c`` times before).
    restitution_model : str or float
        The model they come from (a name of :data:`archquake.fourlink.impact.RESTITUTION_MODELS` or
        an imposed value).
    tables : (MechanismTable, MechanismTable)
        Compiled tables of the equations of motion of Mech-l and Mech-r (eqs. (6)-(7) of the
        paper; :func:`archquake.fourlink.engine.tabulate`).
    """

    arch: BlockArch
    limit: tuple
    mechanisms: tuple
    restitution: tuple[float, float]
    restitution_model: str | float
    tables: tuple

    name: ClassVar[str] = "four-link"
    """The model's name (:data:`archquake.models.MODELS`)."""
    grid_in_one_call: ClassVar[bool] = True
    """A whole grid of pulses, or every level of a record, is one compiled call
    (:meth:`outcomes`, :meth:`scaled_record_outcomes`)."""
    counts_half_cycles: ClassVar[bool] = True
    """An outcome says in which half cycle the arch collapses."""
    checks_standing: ClassVar[bool] = False
    """An arch that cannot stand is refused when the model is built (:meth:`from_arch`)."""

    def check_motion(self, motion) -> float:
        """Any ground motion is resolved (the engine integrates with an adaptive step).

        Parameters
        ----------
        motion : GroundMotion
            Horizontal ground acceleration [m/s^2].

        Returns
        -------
        float
            inf: no time step to refuse.
        """
        return float("inf")

    def check_stands(self) -> None:
        """Nothing to check: the model of an arch that cannot stand is never built."""

    @property
    def structure(self) -> BlockArch:
        """The structure the model describes (the arch)."""
        return self.arch

    @property
    def settings(self) -> dict:
        """The model's settings: the restitution model and the coefficients it gives.

        Returns
        -------
        dict
            ``restitution`` (the model's name or the imposed value) and
            ``restitution_coefficients`` ``[c_lr, c_rl]`` [-].
        """
        return {"restitution": self.restitution_model,
                "restitution_coefficients": [float(c) for c in self.restitution]}

    def describe(self) -> dict:
        """JSON-ready name and settings of the model (what results record of it).

        Returns
        -------
        dict
            ``model`` (``"four-link"``) and the :attr:`settings`.
        """
        return {"model": self.name, **self.settings}

    @classmethod
    def from_arch(cls, arch: BlockArch, restitution=DEFAULT_RESTITUTION,
                  nominal: BlockArch | FourLinkModel | None = None, *,
                  limit_method: str = DEFAULT_LIMIT_METHOD) -> FourLinkModel:
        """Limit analyses, mechanisms, restitution and tables of ``arch``.

        Parameters
        ----------
        arch : BlockArch
            The arch: circular, of any shape or surveyed.
        restitution : str or float
            Restitution model (:func:`archquake.fourlink.impact.check_restitution_model`):
            ``"computed"`` (default), ``"link"``, ``"nominal"``, ``"paper"``, ``"elastic"`` or an
            imposed c_v in (0, 1].
        nominal : BlockArch or FourLinkModel, optional
            The nominal arch, for ``restitution="nominal"`` (default: ``arch`` itself).
        limit_method : {"static", "kinematic"}
            Limit-analysis method (the same hinges and multipliers).

        Returns
        -------
        FourLinkModel

        Raises
        ------
        ValueError
            If ``arch`` is not an :class:`~archquake.geometry.CircularArch`, the restitution model
            is unknown, ``limit_method`` is unknown, or the arch cannot be analysed:
            :class:`~archquake.errors.CannotStandError` (it cannot stand under its own weight),
            :class:`~archquake.errors.NeverCollapsesError` (no load multiplier sets it in
            motion), or a collapse mechanism that is not a four-link mechanism.
        """
        from ..compiled import announce_all
        from ..limit_analysis import both_directions
        from .engine import tabulate
        from .impact import check_restitution_model
        from .mechanism import mechanisms

        if not isinstance(arch, BlockArch):
            raise ValueError(f"arch must be a CircularArch, a ShapedArch or a SurveyedArch, got "
                             f"{type(arch).__name__}")
        check_restitution_model(restitution)  # before any work
        limit = both_directions(arch, method=limit_method)
        pair = mechanisms(arch, limit=limit)
        announce_all(engines())  # a first run compiles it: say so
        tables = (tabulate(pair[0]), tabulate(pair[1]))
        unset = cls(arch, tuple(limit), tuple(pair), (1.0, 1.0), "elastic", tables)
        return unset.with_restitution(restitution, nominal)

    def with_restitution(self, restitution, nominal: BlockArch | FourLinkModel | None = None
                         ) -> FourLinkModel:
        """The same arch with another restitution model (the limit analyses, mechanisms and
        tables are shared, not rebuilt).

        Parameters
        ----------
        restitution : str or float
            Restitution model, as in :meth:`from_arch`.
        nominal : BlockArch or FourLinkModel, optional
            The nominal arch, for ``restitution="nominal"`` (default: this arch).

        Returns
        -------
        FourLinkModel

        Raises
        ------
        ValueError
            For an unknown model or an invalid ``nominal``.
        """
        from .impact import check_restitution_model
        from .impact import restitution as restitution_pair

        model = check_restitution_model(restitution)
        nominal_pair = None
        if model == "nominal":
            nominal_pair = self._nominal_mechanisms(nominal)
        coefficients = restitution_pair(model, *self.mechanisms, nominal=nominal_pair)
        return replace(self, restitution=coefficients, restitution_model=model)

    def _nominal_mechanisms(self, nominal):
        from .mechanism import mechanisms

        if isinstance(nominal, FourLinkModel):
            return nominal.mechanisms
        if isinstance(nominal, BlockArch):
            return mechanisms(nominal)
        if nominal is None:
            return self.mechanisms
        raise ValueError(f"nominal must be an arch or a FourLinkModel, got "
                         f"{type(nominal).__name__}")

    # ------------------------------------------------------------------ quantities
    @property
    def load_multipliers(self) -> tuple[float, float]:
        """``(k_l, k_r)``: horizontal load multipliers of Mech-l and Mech-r [-]."""
        return (float(self.limit[0].load_multiplier), float(self.limit[1].load_multiplier))

    @property
    def load_multiplier(self) -> float:
        """``k = min(k_l, k_r)`` [-]: the ground acceleration, in g, at which the arch starts to
        move in one direction or the other (eq. (2) of the paper)."""
        return min(self.load_multipliers)

    # ------------------------------------------------------------------ analyses
    def simulate(self, ground_motion=None, *, t_end: float | None = None, initial=None,
                 record_dt: float = 2e-3, **options):
        """Time history of the arch under ``ground_motion`` [paper, Sect. 5].

        Parameters
        ----------
        ground_motion : GroundMotion, optional
            Horizontal ground acceleration [m/s^2]; ``None``: a still ground (free vibration,
            with ``initial``).
        t_end : float, optional
            End of the record [s] (default: the end of the excitation or the decision, whichever
            is later, plus :data:`archquake.fourlink.time_history.DEFAULT_EXTRA_TIME`).
        initial : tuple, optional
            ``(mechanism, phi0 [rad], phidot0 [rad/s])``; default: at rest.
        record_dt : float
            Spacing of the recorded samples [s].
        **options
            Integrator options of :func:`archquake.fourlink.time_history.simulate` (``rtol``,
            ``atol``, ``rest_velocity``, ``max_step``, ``max_steps``).

        Returns
        -------
        TimeHistory

        Raises
        ------
        ValueError, RuntimeError
            As :func:`archquake.fourlink.time_history.simulate`.
        """
        from .time_history import simulate

        return simulate(self.tables, ground_motion, self.restitution, t_end=t_end,
                        initial=initial, record_dt=record_dt, **options)

    def free_vibration(self, phi0: float = 0.02, *, mechanism: str = "l",
                       t_end: float = 10.0, **options):
        """Free rocking released from rest at ``phi0`` [rad] in ``mechanism`` [paper, Sect. 5.2,
        Figs. 9-14].

        Parameters
        ----------
        phi0 : float
            Initial rotation ``phi = theta_u - theta`` [rad] (the paper: 0.02).
        mechanism : {"l", "r"}
            Mechanism displaced initially.
        t_end : float
            End of the record [s].
        **options
            As :meth:`simulate`.

        Returns
        -------
        TimeHistory
        """
        return self.simulate(None, initial=(mechanism, phi0, 0.0), t_end=t_end, **options)

    def outcome(self, ground_motion, **options):
        """Outcome of the arch under ``ground_motion`` (no record: the compiled fast path).

        Parameters
        ----------
        ground_motion : GroundMotion
            Horizontal ground acceleration [m/s^2].
        **options
            Integrator options of :func:`archquake.fourlink.time_history.simulate`.

        Returns
        -------
        Outcome

        Raises
        ------
        ValueError
            As :func:`archquake.fourlink.time_history.simulate`.
        """
        from .time_history import simulate

        return simulate(self.tables, ground_motion, self.restitution, record=False, **options)

    def outcomes(self, durations, amplitudes_g, motion: str = "oppenheim") -> dict:
        """Outcomes of a grid of pulses, in one compiled call.

        Parameters
        ----------
        durations : array_like
            Pulse durations t_p [s].
        amplitudes_g : array_like
            Signed amplitudes of the first pulse [g] (``-1`` is the paper's -1 g, which opens
            Mech-l); broadcast against ``durations``.
        motion : str
            Pulse shape, a name of :data:`archquake.ground_motion.ANALYTIC_GROUND_MOTIONS`
            (default Oppenheim's pulse: ``a`` for ``t_p``, then ``-a/2`` for ``2 t_p``).

        Returns
        -------
        dict of ndarray
            ``status`` (:class:`archquake.status.Status` codes), ``half_cycle``, ``impacts``,
            ``collapse_time`` [s], ``max_phi`` [rad] and ``steps``, each of the broadcast shape.

        Raises
        ------
        ValueError, RuntimeError
            As :func:`archquake.fourlink.engine.outcomes_grid`.
        """
        from .engine import outcomes_grid

        durations, amplitudes_g = pulse_grid(durations, amplitudes_g)
        table_l, table_r = self.tables
        c_lr, c_rl = self.restitution
        return outcomes_grid(table_l, table_r, c_lr, c_rl, durations, GRAVITY * amplitudes_g,
                             motion)


    def scaled_record_outcomes(self, motion, factors) -> dict[str, np.ndarray]:
        """Outcomes under one record scaled by each of ``factors``, in one compiled call.

        An analysis whose scaled record stays strictly inside the activation accelerations
        (``-k_l g < s xg'' < k_r g`` at every sample, eq. (2) of the paper, with the relative
        margin :data:`archquake.defaults.REST_MARGIN`) is at rest without being integrated: the
        record is piecewise linear, so its extremes are samples, and the engine would decide
        the same.

        Parameters
        ----------
        motion : GroundMotion
            A ``LINEAR`` record [m/s^2].
        factors : array_like of float
            Signed scale factors [-]; a negative factor applies the reversed record.

        Returns
        -------
        dict of ndarray
            ``status`` (0 rest, 1 recovery, 2 collapse), ``half_cycle``, ``impacts``,
            ``collapse_time`` [s], ``max_phi`` [rad] and ``integrated`` (False where the scaled
            record stays below the activation acceleration: rest, not integrated), one per
            factor.

        Raises
        ------
        ValueError
            If ``motion`` is not piecewise linear, or as
            :func:`archquake.fourlink.engine.outcomes_grid`.
        RuntimeError
            As :func:`archquake.fourlink.engine.outcomes_grid`.
        """
        from ..ground_motion import LINEAR
        from .engine import outcomes_grid

        if motion.kind != LINEAR:
            raise ValueError(f"record_outcomes takes a piecewise-linear record, got kind "
                             f"{motion.kind} ({motion.name!r})")
        table_l, table_r = self.tables
        c_lr, c_rl = self.restitution
        s = np.asarray(factors, dtype=float).ravel()
        v_max, v_min = float(np.max(motion.values)), float(np.min(motion.values))
        # rounding is monotone: max(v * s) is v_max * s for s > 0 and v_min * s for s < 0
        high = np.where(s > 0, s * v_max, s * v_min)
        low = np.where(s > 0, s * v_min, s * v_max)
        threshold_r = table_r.activation_g * GRAVITY  # Mech-r opens when xg'' > k_r g
        threshold_l = -table_l.activation_g * GRAVITY  # Mech-l opens when xg'' < -k_l g
        run = ~((high < threshold_r * (1.0 - REST_MARGIN))
                & (low > threshold_l * (1.0 - REST_MARGIN)))
        out = {"status": np.zeros(s.size, dtype=np.int8),
               "half_cycle": np.zeros(s.size, dtype=np.int16),
               "impacts": np.zeros(s.size, dtype=np.int32),
               "collapse_time": np.full(s.size, np.nan), "max_phi": np.zeros(s.size),
               "integrated": run}
        if np.any(run):
            signed = s[run]
            grid = outcomes_grid(table_l, table_r, c_lr, c_rl, np.ones(signed.size), signed,
                                 motion)
            for name in ("status", "half_cycle", "impacts", "collapse_time", "max_phi"):
                out[name][run] = grid[name]
        return out


def engines() -> list[tuple[str, object]]:
    """The compiled engine of the four-link model, ``[(name, entry point)]``
    (:mod:`archquake.compiled`): the driver's integration of one analysis, which every path
    of the engine compiles (a grid of analyses calls it)."""
    from ..compiled import FOUR_LINK
    from .engine import integrate

    return [(FOUR_LINK, integrate)]
