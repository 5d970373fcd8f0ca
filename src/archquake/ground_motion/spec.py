"""A ground motion described by named values: :class:`MotionSpec`.

The command line and the interactive page describe a ground motion the same way, by the values
a user gives (an analytic pulse by its name, amplitude in g and duration; a recorded
accelerogram by its file; a record of a built-in suite; the stochastic model by its parameters;
scaled to a peak ground acceleration, reversed), and both build it here: the command line maps
its options onto these names (``--param NAME=VALUE`` is ``params``), the page sends them as
JSON. A value left out (``None``) takes its default: Oppenheim's pulse of
:data:`~archquake.defaults.DEFAULT_PULSE`.

A refused description is a :class:`~archquake.errors.DescriptionError` whose message names its
fields (``"scale_to applies to a recorded accelerogram (record) ..."``); the command line says
the same naming its options (``--scale-to ... (--record FILE)``). A value that a builder of
:mod:`archquake.ground_motion` refuses is refused by it, with its own message, which names the
same parameter (``"duration must be ..."``).

Examples
--------
>>> from archquake.ground_motion.spec import MotionSpec
>>> spec = MotionSpec.from_dict({"motion": "harmonic", "amplitude": -0.4, "duration": 0.5,
...                              "params": {"cycles": 2}, "reverse": True})
>>> motion = spec.build()
>>> round(motion.duration, 6)
1.0
>>> MotionSpec.from_dict(spec.to_dict()) == spec
True
>>> MotionSpec(motion="ricker", scale_to=0.3).build()
Traceback (most recent call last):
...
archquake.errors.DescriptionError: scale_to applies to a recorded accelerogram (record) or a \
stochastic motion; a pulse takes amplitude
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields

from ..constants import GRAVITY
from ..defaults import (
    ANALYTIC_GROUND_MOTIONS,
    DEFAULT_MOTION,
    DEFAULT_PULSE,
    MAX_ACCELERATION_G,
)
from ..errors import DescriptionError
from ..ranges import number_field

STOCHASTIC_PARAMETERS = ("seed", "arias_intensity", "significant_duration", "midpoint_time",
                         "filter_frequency", "filter_frequency_rate", "filter_damping",
                         "high_pass_frequency", "dt", "duration")
"""Parameters of the ``"stochastic"`` motion (:func:`archquake.ground_motion.stochastic`)."""

MOTIONS = ANALYTIC_GROUND_MOTIONS + ("record", "stochastic")
"""The values of ``motion``: an analytic pulse, ``"record"`` or ``"stochastic"``."""


def _literal(value) -> str:
    return DescriptionError.literal(value)


@dataclass(frozen=True)
class MotionSpec:
    """A ground motion by named values.

    Every field is optional (``None``: not given).

    Parameters
    ----------
    motion : str, optional
        One of :data:`MOTIONS`: an analytic pulse (default
        :data:`~archquake.defaults.DEFAULT_MOTION`), ``"record"`` (implied by ``record``) or
        ``"stochastic"`` (the Rezaeian-Der Kiureghian model).
    amplitude : float, optional
        Signed peak acceleration of a pulse [g], within
        +-:data:`~archquake.defaults.MAX_ACCELERATION_G`; -1 starts Mech-l (default
        ``DEFAULT_PULSE[0]``).
    duration : float, optional
        Time scale of a pulse [s]: its duration (oppenheim, rectangular) or its period (the
        others) (default ``DEFAULT_PULSE[1]``).
    cycles : float, optional
        Cycles of the harmonic motion (the same as ``params={"cycles": ...}``).
    params : dict, optional
        Parameters of the motion by name (:func:`~archquake.ground_motion.shape_parameters`
        of a pulse, :data:`STOCHASTIC_PARAMETERS` of the stochastic motion), numbers or their
        text.
    record : str, optional
        Path of an accelerogram: two-column CSV (time [s], acceleration [g]), PEER NGA .AT2 or
        ESM ASCII.
    suite : str, optional
        A built-in suite of real records (:data:`~archquake.ground_motion.BUILTIN_SUITES`,
        the ``records`` extra), with ``suite_record``.
    suite_record : str or int, optional
        The record of ``suite``: its name, or its index in the suite.
    scale_to : float, optional
        Scale the record or the stochastic motion to this peak ground acceleration [g].
    reverse : bool, optional
        Apply the motion with its sign flipped (the other polarity).

    Raises
    ------
    DescriptionError
        Naming the field: a value of the wrong type, a motion that is none of
        :data:`MOTIONS`, a parameter the motion does not take, an amplitude out of range, or
        fields that do not go together (a record with an amplitude, ``scale_to`` with a pulse
        ...).
    """

    motion: str | None = None
    amplitude: float | None = None
    duration: float | None = None
    cycles: float | None = None
    params: dict | None = None
    record: str | None = None
    suite: str | None = None
    suite_record: str | int | None = None
    scale_to: float | None = None
    reverse: bool | None = None

    def __post_init__(self):
        set_ = object.__setattr__
        for name in ("amplitude", "duration", "cycles", "scale_to"):
            if getattr(self, name) is not None:
                set_(self, name, number_field(name, getattr(self, name)))
        for name in ("motion", "record", "suite"):
            value = getattr(self, name)
            if value is not None and not isinstance(value, str):
                raise DescriptionError(f"{{{name}}} must be a name, got {_literal(repr(value))}")
        if self.motion is not None and self.motion not in MOTIONS:
            raise DescriptionError(f"{{motion}} must be one of {_literal(list(MOTIONS))}, got "
                                   f"{_literal(repr(self.motion))}")
        if self.reverse is not None and not isinstance(self.reverse, bool):
            raise DescriptionError(f"{{reverse}} must be true or false, got "
                                   f"{_literal(repr(self.reverse))}")
        if self.params is not None and not isinstance(self.params, dict):
            raise DescriptionError("{params} must be a JSON object {{name: value}}")
        index = self.suite_record
        if index is not None and (isinstance(index, bool) or not isinstance(index, int | str)):
            raise DescriptionError(f"{{suite_record}} must be the name or the index of a record "
                                   f"of the suite, got {_literal(repr(index))}")
        if self.suite is not None and self.suite_record is None:
            raise DescriptionError(f"{{suite}} {_literal(self.suite)} needs {{suite_record:NAME}}: "
                                   f"the ground motion of the suite to apply")
        if self.suite is not None and self.record is not None:
            raise DescriptionError("{record} and {suite}: give a record file or a record of a "
                                   "built-in suite, not both")
        kind = self.kind
        if kind == "record":
            if not self.recorded:
                raise DescriptionError("{motion} record needs {record:FILE}")
            if self.motion not in (None, "record"):
                raise DescriptionError(f"{{record:FILE}} is a recorded motion; it cannot be "
                                       f"combined with {{motion}} {self.motion}")
            self._refuse("amplitude", "a record (use {scale_to:PGA})")
            self._refuse("duration", "a record")
            set_(self, "params", self._parameters(()))
        elif kind == "stochastic":
            self._refuse("amplitude", "a stochastic motion (use {scale_to:PGA})")
            self._refuse("duration", "a stochastic motion (use {params} duration=...)")
            set_(self, "params", self._parameters(STOCHASTIC_PARAMETERS))
        else:
            if self.scale_to is not None:
                raise DescriptionError("{scale_to} applies to a recorded accelerogram "
                                       "({record:FILE}) or a stochastic motion; a pulse takes "
                                       "{amplitude}")
            amplitude = self.pulse[0]
            if not (math.isfinite(amplitude) and abs(amplitude) <= MAX_ACCELERATION_G):
                # in g: the builders see m/s^2
                raise DescriptionError(f"{{amplitude}} must be a finite acceleration within "
                                       f"+-{MAX_ACCELERATION_G:g} g, got {amplitude:g}")
            from .registry import shape_parameters

            set_(self, "params", self._parameters(tuple(shape_parameters(kind))))

    @property
    def recorded(self) -> bool:
        """Whether a record is given (a file, or a record of a suite)."""
        return self.record is not None or self.suite_record is not None

    @property
    def kind(self) -> str:
        """The motion: its ``motion``, ``"record"`` for a record, or the default pulse."""
        if self.recorded or self.motion == "record":
            return "record"
        return DEFAULT_MOTION if self.motion is None else self.motion

    @property
    def pulse(self) -> tuple[float, float]:
        """``(amplitude [g], duration [s])`` of a pulse, defaults applied."""
        return (DEFAULT_PULSE[0] if self.amplitude is None else self.amplitude,
                DEFAULT_PULSE[1] if self.duration is None else self.duration)

    def _refuse(self, name: str, what: str) -> None:
        if getattr(self, name) is not None:
            raise DescriptionError(f"{{{name}}} applies to an analytic pulse, not to {what}")

    def _parameters(self, allowed) -> dict[str, float] | None:
        """``params`` checked against ``allowed`` (and ``cycles`` with them), their values as
        floats; None when not given."""
        kind = self.kind
        if self.cycles is not None and "cycles" not in allowed:
            raise DescriptionError(f"{{cycles}} applies to {{motion}} harmonic, not {kind}")
        if self.params is None:
            return None
        out: dict[str, float] = {}
        for name, value in self.params.items():
            shown = _literal(name)
            if name not in allowed:
                options = ", ".join(allowed) if allowed else "none"
                raise DescriptionError(f"{{params}} {shown} does not apply to {{motion}} {kind}; "
                                       f"its parameters: {options}")
            try:
                out[name] = number_field("params", value)
            except DescriptionError:
                raise DescriptionError(f"{{params}} {shown}: {_literal(repr(value))} is not a "
                                       f"number") from None
            if name == "cycles" and self.cycles is not None:
                raise DescriptionError(f"{{params}} {shown} is given twice")
        return out

    @property
    def parameters(self) -> dict[str, float]:
        """The parameters of the motion by name: ``params`` and ``cycles``."""
        cycles = {} if self.cycles is None else {"cycles": self.cycles}
        return {**cycles, **(self.params or {})}

    # ------------------------------------------------------------------ the motion
    def build(self):
        """The ground motion described (reversed with ``reverse``).

        Returns
        -------
        GroundMotion

        Raises
        ------
        ValueError
            A :class:`~archquake.errors.DescriptionError` naming the field for a suite that
            cannot be read (the ``records`` extra missing) or has no such record, or a scaling
            it refuses; the builder's own error (naming the same parameter) for a value it
            refuses, or the record file's.
        """
        from .registry import ground_motion

        kind = self.kind
        params = self.parameters
        if kind == "record":
            if self.suite is not None:
                motion = self._scaled(self._suite_motion())
            else:
                from .records import read_record

                motion = read_record(self.record, scale_to=self.scale_to)
        elif kind == "stochastic":
            motion = self._scaled(ground_motion("stochastic", **params))
        else:
            amplitude, duration = self.pulse
            motion = ground_motion(kind, amplitude * GRAVITY, duration, **params)
        return motion.reversed() if self.reverse else motion

    def _scaled(self, motion):
        """``motion`` scaled to the peak ground acceleration ``scale_to`` (itself without)."""
        if self.scale_to is None:
            return motion
        from .intensity import scale_to_im

        try:
            return scale_to_im(motion, "pga", self.scale_to)
        except ValueError as exc:
            raise DescriptionError(f"{{scale_to}}: {_literal(exc)}") from None

    def _suite_motion(self):
        """The ground motion ``suite_record`` (a name or an index) of the built-in suite."""
        from .fema_p695 import builtin_suite

        name = _literal(self.suite)
        try:
            records = builtin_suite(self.suite)
        except ImportError as exc:
            raise DescriptionError(f"{{suite}} {name}: {_literal(exc)}") from None
        except ValueError as exc:
            raise DescriptionError(f"{{suite}}: {_literal(exc)}") from None
        wanted = self.suite_record
        if isinstance(wanted, int):
            if not 0 <= wanted < len(records):
                raise DescriptionError(f"{{suite_record}} must be an integer in [0, "
                                       f"{len(records) - 1}], got {wanted}")
            return records[wanted].motion
        for r in records:
            if r.name == wanted:
                return r.motion
        raise DescriptionError(f"{{suite_record}} {_literal(repr(wanted))} is not a ground motion "
                               f"of {{suite}} {name}; its ground motions: "
                               f"{_literal(', '.join(r.name for r in records))}")

    # ------------------------------------------------------------------ JSON
    def to_dict(self) -> dict:
        """The fields given, as JSON values: :meth:`from_dict` reads it back to an equal
        description."""
        return {f.name: v for f in fields(self) if (v := getattr(self, f.name)) is not None}

    @classmethod
    def from_dict(cls, data) -> MotionSpec:
        """The description of a dict of fields (the page's JSON, or :meth:`to_dict`); a value
        None or ``""`` is not given, nor an empty ``params``.

        Raises
        ------
        DescriptionError
            For something else than a dict, an unknown field, or a value the description
            refuses.
        """
        DescriptionError.check_fields(data, [f.name for f in fields(cls)], "ground motion")
        return cls(**{k: v for k, v in data.items() if v is not None and v != "" and v != {}})


__all__ = ["MOTIONS", "STOCHASTIC_PARAMETERS", "MotionSpec"]
