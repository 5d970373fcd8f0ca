"""Exceptions of archquake beyond the plain :class:`ValueError` of bad input: a study that cannot
go on, the verdicts a caller tells apart from bad input (cannot stand, never collapses), and a
refused description whose message can name its fields otherwise (:class:`DescriptionError`).

This module imports nothing, so the command line can catch these errors without loading the
modules that raise them.
"""


class StudyError(RuntimeError):
    """A study cannot go on for a reason outside its input: its Dask cluster lost its scheduler
    or every worker, or a chunk keeps killing the workers that run it.

    The message says what happened and how to continue; the chunks finished before the error
    stay saved in the study directory, so the study can be resumed.
    """


def interrupt_in(exc: BaseException) -> KeyboardInterrupt | None:
    """The Ctrl-C (or SIGTERM, :mod:`archquake.cli._signals`) behind ``exc``, if any.

    A :class:`KeyboardInterrupt` raised while a numba-compiled function runs surfaces as a
    ``SystemError`` ("CPUDispatcher(...) returned a result with an exception set") whose cause
    is the interrupt, and a study wraps what an arch raised in a :class:`StudyError`: the
    interrupt is found along the chain of causes and contexts.

    Parameters
    ----------
    exc : BaseException
        What was raised.

    Returns
    -------
    KeyboardInterrupt or None
        The first interrupt of the chain (``exc`` itself if it is one).
    """
    seen = set()
    while exc is not None and id(exc) not in seen:
        if isinstance(exc, KeyboardInterrupt):
            return exc
        seen.add(id(exc))
        exc = exc.__cause__ or exc.__context__
    return None


class CannotStandError(ValueError):
    """The arch cannot stand under its own weight: no line of thrust fits inside it without a
    horizontal force (its largest load multiplier is negative, or none exists)."""


class NoThicknessError(ValueError):
    """No thickness of the arch's shape lets it stand under its own weight (with friction at
    its joints: the friction is below the least with which the shape can stand): a verdict on
    the shape, not a fault of the input."""


class NeverCollapsesError(ValueError):
    """The arch does not collapse under any horizontal load multiplier: a line of thrust fits
    inside it for every k, so no ground acceleration sets it in motion."""


class UnsolvedProgramError(ValueError):
    """HiGHS ended a limit analysis's linear program without an answer (neither optimal,
    infeasible nor unbounded: numerical difficulties or a limit reached): the structure's
    geometry is too degenerate to analyse, or, below a minimum thickness, the program is
    infeasible and too badly conditioned to say so."""


class StudyWarning(UserWarning):
    """Something in a study directory was repaired, e.g. a damaged checkpoint recomputed."""


class _Field:
    """A field of a :class:`DescriptionError`'s message, as one naming says it: ``{name}`` is
    its name, ``{name:METAVAR}`` its name followed by what its value looks like when the naming
    asks for it (the command line's ``--fill-cover M``)."""

    def __init__(self, name: str, metavar: bool):
        self.name, self.metavar = name, metavar

    def __format__(self, spec: str) -> str:
        return f"{self.name} {spec}" if spec and self.metavar else self.name


class _Naming(dict):
    """The fields of a template, each named by ``names`` (its own name where ``names`` has
    none, then without its metavar)."""

    def __init__(self, names):
        super().__init__()
        self.names = names

    def __missing__(self, field: str) -> _Field:
        return _Field(self.names.get(field, field), field in self.names)


class DescriptionError(ValueError):
    """A description of a structure or a ground motion refused (bad input): the message names
    the description's fields, and :meth:`~archquake.errors.DescriptionError.naming` says the
    same with other names for them (the command line names its options, ``--piers`` for
    ``piers``).

    Parameters
    ----------
    template : str
        The message, each field written ``{field}``, or ``{field:METAVAR}`` where a naming
        that renames the field shows what its value looks like; other braces doubled.

    Examples
    --------
    >>> error = DescriptionError("the fill needs {fill_cover:M} (its depth above the crown [m])")
    >>> str(error)
    'the fill needs fill_cover (its depth above the crown [m])'
    >>> error.naming({"fill_cover": "--fill-cover"})
    'the fill needs --fill-cover M (its depth above the crown [m])'
    """

    def __init__(self, template: str):
        self.template = template
        super().__init__(self.naming({}))

    def naming(self, names) -> str:
        """The message with each field named ``names[field]`` (the field's own name where
        ``names`` has none)."""
        return self.template.format_map(_Naming(names))

    @staticmethod
    def literal(value) -> str:
        """``str(value)`` for a template: its braces doubled."""
        return str(value).replace("{", "{{").replace("}", "}}")

    @classmethod
    def check_fields(cls, data, known, what: str) -> None:
        """Refuse ``data`` unless it is a dict whose keys are among ``known``, naming ``what``
        it describes (``"structure"``, ``"ground motion"``).

        Raises
        ------
        DescriptionError
            For something else than a dict, or an unknown field (all of them named).
        """
        if not isinstance(data, dict):
            raise cls(f"the {what} must be described by a JSON object, got "
                      f"{type(data).__name__}")
        unknown = sorted(set(data) - set(known))
        if unknown:
            raise cls(f"unknown {what} field(s) {cls.literal(unknown)}; known: "
                      f"{cls.literal(list(known))}")


class UnseatedError(DescriptionError):
    """Irregular arches drawn for the spans of a bridge whose piers cannot seat their
    springings (thicker end voussoirs need wider seats): that draw cannot be built, though
    the description is sound (a sample leaves the member out and says so)."""
