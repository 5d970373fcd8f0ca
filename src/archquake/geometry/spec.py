r"""A structure described by named values: :class:`StructureSpec`.

The command line and the interactive page describe a structure the same way, by the values a
user gives (a shape with its span and rise, or a radius and an angle of embrace in degrees; a
thickness; piers; a fill; an irregularity :math:`\epsilon` and its seed; or a geometry file),
and both build it here: the command line maps its options onto these names (``--pier-left``
is ``pier_left``), the page sends them as JSON. A value left out (``None``) takes its default:
Oppenheim's arch, fixed springings, no fill, no irregular draw.

A refused description is a :class:`~archquake.errors.DescriptionError` whose message names its
fields (``"piers: left pier: pier width must be at least ..."``); the command line says the same
naming its options (``--piers: ...``). A value that a builder of :mod:`archquake.geometry`
refuses is refused by it, with its own message, which names the same parameter
(``"thickness must be ..."``).

Examples
--------
>>> from archquake.geometry.spec import StructureSpec
>>> spec = StructureSpec.from_dict({"shape": "pointed", "span": 10, "rise": 7,
...                                 "thickness": 0.6, "piers": "2,4,2"})
>>> spec.piers
(2.0, 4.0, 2)
>>> structure = spec.build()
>>> structure.n_voussoirs  # 8 voussoirs (even, for a pointed arch) and two courses per pier
12
>>> StructureSpec.from_dict(spec.to_dict()) == spec
True
>>> StructureSpec(span=10).build()
Traceback (most recent call last):
...
archquake.errors.DescriptionError: a circular arch needs span and rise [m]
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields

from ..constants import DEFAULT_DENSITY, DEFAULT_FILL_DENSITY
from ..defaults import (
    DEFAULT_FILL_INERTIA,
    DEFAULT_SEED,
    FILL_INERTIA_MODELS,
    SHAPES,
    VOUSSOIR_FACES,
    circular_defaults,
)
from ..errors import DescriptionError, UnseatedError
from ..ranges import number, number_field

SHAPE_FIELDS = ("shape", "span", "rise", "radius", "embrace", "thickness", "voussoirs", "faces")
"""The fields that describe an arch by its shape."""

STRUCTURE_FIELDS = ("piers", "pier_left", "pier_right", "fill_cover", "fill_density",
                    "fill_inertia", "fill_passive")
"""The fields that put the arch on piers or under fill."""

SPAN_FIELDS = ("spans", "pier_middle")
"""The fields that put several equal arches in a row on shared piers (a bridge, an arcade:
:func:`~archquake.geometry.bridge.multi_span`)."""

RING_FIELDS = ("rings", "ring_bond", "ring_friction")
"""The fields that cut a circular arch into rings that can separate
(:func:`~archquake.geometry.multi_ring`)."""

_NUMBERS = ("span", "rise", "radius", "embrace", "thickness", "fill_cover", "fill_density",
            "density", "epsilon")
_INTEGERS = ("voussoirs", "seed", "spans")
_CHOICES = {"shape": SHAPES, "faces": VOUSSOIR_FACES, "fill_inertia": FILL_INERTIA_MODELS}


def _literal(value) -> str:
    return DescriptionError.literal(value)


def integer_field(name: str, value) -> int:
    """``value`` of the field ``name`` as an int: an integer, a float with an integer value or
    the text of an integer; a :class:`~archquake.errors.DescriptionError` naming the field
    otherwise."""
    if isinstance(value, int) and not isinstance(value, bool):
        return value
    if isinstance(value, float) and value.is_integer():
        return int(value)
    if isinstance(value, str):
        try:
            return int(value)
        except ValueError:
            pass
    raise DescriptionError(f"{{{name}}} must be an integer, got {_literal(repr(value))}")


def _numbers(name: str, value, low: int, high: int, *, blank_first: bool = False) -> list:
    """The numbers of the field ``name``: the text ``"a,b[,c]"`` or a sequence; ``low`` to
    ``high`` of them; the first may be blank (None) when ``blank_first``."""
    if isinstance(value, str):
        parts = value.split(",")
    elif isinstance(value, list | tuple):
        parts = list(value)
    else:
        raise DescriptionError(f"{{{name}}} takes {low} to {high} numbers, got "
                               f"{_literal(repr(value))}")
    if not low <= len(parts) <= high:
        raise DescriptionError(f"{{{name}}} takes {low} to {high} numbers separated by commas, "
                               f"got {_literal(repr(value))}")
    out = []
    for k, part in enumerate(parts):
        blank = part is None or (isinstance(part, str) and not part.strip())
        if k == 0 and blank_first and blank:
            out.append(None)
            continue
        try:
            if isinstance(part, bool) or part is None:
                raise ValueError
            out.append(number(part))
        except (TypeError, ValueError):
            hint = (" (a blank WIDTH only with limit --min-pier-width)" if k == 0 and blank
                    else "")
            raise DescriptionError(f"{{{name}}} takes numbers separated by commas, got "
                                   f"{_literal(repr(value))}{hint}") from None
    return out


def pier_field(name: str, value, *, blank_width: bool = False):
    """The pier ``(width [m], height [m], courses)`` of the field ``name``, given as the text
    ``"WIDTH,HEIGHT[,COURSES]"`` or a sequence of those numbers (one course by default).

    Parameters
    ----------
    name : str
        The field (``piers``, ``pier_left``, ``pier_right``), for the messages.
    value : str or sequence
        The pier.
    blank_width : bool
        Accept a blank width (``",HEIGHT[,COURSES]"``: the narrowest piers are to be found):
        ``(None, height, courses)``.

    Returns
    -------
    tuple
        ``(width, height, courses)``, checked as :class:`~archquake.geometry.Pier` checks them.

    Raises
    ------
    DescriptionError
        Naming the field: not two or three numbers, a number of courses that is not an
        integer >= 1, or a width or height out of range.
    """
    from .piers import Pier

    width, height, *courses = _numbers(name, value, 2, 3, blank_first=blank_width)
    courses = courses[0] if courses else 1
    if not float(courses).is_integer() or courses < 1:
        raise DescriptionError(f"{{{name}}}: COURSES must be an integer >= 1, got {courses:g}")
    try:
        Pier(1.0 if width is None else width, height, int(courses))
    except ValueError as exc:
        raise DescriptionError(f"{{{name}}}: {_literal(exc)}") from None
    return width, height, int(courses)


@dataclass(frozen=True)
class StructureSpec:
    r"""A structure by named values: an arch of a shape or of a file, on piers, under fill,
    optionally drawn irregular [paper, eq. (1)].

    Every field is optional (``None``: not given, its default applies).

    Parameters
    ----------
    shape : str, optional
        Shape of the centreline, one of :data:`~archquake.defaults.SHAPES` (default
        ``"circular"``); every shape but the circle is given by ``span`` and ``rise``.
    span, rise : float, optional
        Span and rise of the centreline [m], with the springings on y = 0.
    radius : float, optional
        Mean radius :math:`R` of a circular arch [m] (default Oppenheim's, 10 m, unless
        ``span`` and ``rise`` are given).
    embrace : float, optional
        Angle of embrace :math:`\alpha` of a circular arch [deg], in (0, 360) (default 157.5).
    thickness : float, optional
        Thickness :math:`t` normal to the centreline [m] (default 1.5).
    voussoirs : int, optional
        Number of voussoirs :math:`n` of equal centreline length (default 7, 8 for a pointed
        arch, which needs an even number).
    faces : {"curved", "flat"}, optional
        Voussoir faces (default ``"curved"``).
    geometry : str, optional
        Path of a geometry file (:func:`~archquake.geometry.load_arch`): the whole arch,
        instead of the shape fields, or any block assembly (a JSON file with supports, or a
        DXF drawing).
    units : str, optional
        The length unit of a DXF drawing (``"mm"``, ``"cm"``, ``"m"``, ``"in"``, ``"ft"``),
        overriding its header's.
    piers : tuple or str, optional
        Two equal rectangular piers ``(width [m], height [m], courses)``, or the text
        ``"WIDTH,HEIGHT[,COURSES]"``: width from the intrados springing point outward, height
        from the ground up to it, courses of equal height (default 1).
    pier_left, pier_right : tuple or str, optional
        The pier under one springing only, as ``piers`` (unequal piers; not with ``piers``).
    spans : int, optional
        Number of equal arches in a row on shared piers, in [1, 100] (default 1); more than
        one makes a :class:`~archquake.geometry.BlockAssembly`
        (:func:`~archquake.geometry.bridge.multi_span`), the end piers those of ``piers``,
        ``pier_left`` and ``pier_right``; no fill and no irregular draw yet.
    pier_middle : tuple or str, optional
        The intermediate piers ``(width [m], height [m], courses)`` (width between the two
        intrados springing points each carries), as ``piers``; default: ``piers``.
    fill_cover : float, optional
        A level fill over the arch, this deep above the crown [m].
    fill_density : float, optional
        Density of the fill [kg/m^3] (default
        :data:`~archquake.constants.DEFAULT_FILL_DENSITY`).
    fill_inertia : str, optional
        Where the fill's horizontal inertia force acts, one of
        :data:`~archquake.defaults.FILL_INERTIA_MODELS` (default
        :data:`~archquake.defaults.DEFAULT_FILL_INERTIA`).
    fill_passive : tuple or str, optional
        A passive reaction of the fill, ``(phi [deg], mobilisation [-])`` or the text
        ``"PHI,MOBILISATION"``: angle of friction in (0, 90) and mobilised fraction of
        Rankine's passive pressure in [0, 1].
    rings : int, optional
        Cut the arch of the shape fields (a smooth centreline: not pointed; curved faces) into
        this many concentric rings of equal thickness that can separate, >= 1: a
        :class:`~archquake.geometry.BlockAssembly` (:func:`~archquake.geometry.multi_ring`)
        on fixed springings, without piers, fill or irregular draw.
    ring_bond : {"aligned", "staggered"}, optional
        The joints of adjacent rings on the same radial lines, or offset by half a voussoir
        (default ``"aligned"``); only with ``rings``.
    ring_friction : float, optional
        Coulomb coefficient of the ring interfaces [-], >= 0 (default: they do not slide);
        only with ``rings``.
    density : float, optional
        Density of the masonry, arch and piers [kg/m^3] (default: the geometry file's, else
        :data:`~archquake.constants.DEFAULT_DENSITY`); given, it replaces the geometry file's.
    epsilon : float, optional
        Draw one irregular arch around the arch with the irregularity :math:`\epsilon` in
        [0, 1) of eq. (1) (:func:`~archquake.geometry.irregular_arch`); with ``spans``, one a
        span, one after the other from one generator of the seed.
    seed : int, optional
        Seed of the irregular draw, >= 0 (default :data:`~archquake.defaults.DEFAULT_SEED`);
        only with ``epsilon``.

    Raises
    ------
    DescriptionError
        Naming the field: a value of the wrong type or not among its choices, piers or a
        passive reaction that cannot be read or are out of range, or fields that do not go
        together (a shape and a geometry file, ``span`` with ``radius``, a fill without
        ``fill_cover``, a seed without ``epsilon`` ...).
    """

    shape: str | None = None
    span: float | None = None
    rise: float | None = None
    radius: float | None = None
    embrace: float | None = None
    thickness: float | None = None
    voussoirs: int | None = None
    faces: str | None = None
    geometry: str | None = None
    units: str | None = None
    piers: tuple | str | None = None
    pier_left: tuple | str | None = None
    pier_right: tuple | str | None = None
    spans: int | None = None
    pier_middle: tuple | str | None = None
    fill_cover: float | None = None
    fill_density: float | None = None
    fill_inertia: str | None = None
    fill_passive: tuple | str | None = None
    rings: int | None = None
    ring_bond: str | None = None
    ring_friction: float | None = None
    density: float | None = None
    epsilon: float | None = None
    seed: int | None = None

    def __post_init__(self):
        set_ = object.__setattr__
        for name in _NUMBERS:
            if getattr(self, name) is not None:
                set_(self, name, number_field(name, getattr(self, name)))
        for name in _INTEGERS:
            if getattr(self, name) is not None:
                set_(self, name, integer_field(name, getattr(self, name)))
        for name, choices in _CHOICES.items():
            value = getattr(self, name)
            if value is not None and value not in choices:
                raise DescriptionError(f"{{{name}}} must be one of {_literal(list(choices))}, "
                                       f"got {_literal(repr(value))}")
        if self.geometry is not None and not isinstance(self.geometry, str):
            raise DescriptionError(f"{{geometry}} must be the path of a geometry file, got "
                                   f"{_literal(repr(self.geometry))}")
        if self.density is not None:
            from .blocks import check_density

            try:
                check_density(self.density, "{density}")
            except ValueError as exc:  # the value is a float: no braces but the field's
                raise DescriptionError(str(exc)) from None
        if self.geometry is not None:
            given = self._given(*SHAPE_FIELDS)
            if given:
                raise DescriptionError(f"{{geometry}} gives the whole arch; it cannot be "
                                       f"combined with {', '.join(given)}")
        else:
            self._check_shape()
        self._check_structure()
        self._check_spans()
        self._check_rings()
        if self.epsilon is None and self.seed is not None:
            raise DescriptionError("{seed} needs {epsilon} (the seed of an irregular arch)")
        if self.epsilon is not None and self.seed is not None and self.seed < 0:
            raise DescriptionError(f"{{seed}} must be an integer >= 0, got {self.seed}")

    def _given(self, *names: str) -> list[str]:
        """The fields among ``names`` that are given, each as a template's field."""
        return [f"{{{name}}}" for name in names if getattr(self, name) is not None]

    # ------------------------------------------------------------------ the arch
    def _check_shape(self) -> None:
        shape = self.shape or SHAPES[0]
        by_size, by_angle = self._given("span", "rise"), self._given("radius", "embrace")
        article = "an" if shape[0] in "aeiou" else "a"
        if shape != "circular" and by_angle:
            raise DescriptionError(f"{' and '.join(by_angle)} apply to circular arches only; "
                                   f"{article} {shape} arch is given by {{span}} and {{rise}}")
        if by_size and by_angle:
            raise DescriptionError(f"{', '.join(by_size + by_angle)}: a circular arch is given "
                                   "by {span} and {rise} or by {radius} and {embrace}, not both")
        if (shape != "circular" or by_size) and len(by_size) < 2:
            raise DescriptionError(f"{article} {shape} arch needs {{span}} and {{rise}} [m]")
        if shape == "circular" and not by_size:
            embrace = self._value("embrace")
            if not 0 < embrace < 360:  # in degrees: the builders see radians
                raise DescriptionError(f"{{embrace}} must be in (0, 360) degrees, got "
                                       f"{embrace:g}")

    def _value(self, name: str):
        value = getattr(self, name)
        return circular_defaults()[name] if value is None else value

    def shape_arguments(self) -> tuple[str | None, dict]:
        """``(shape, keyword arguments of shaped_arch without thickness and density)`` of the
        shape fields; ``shape`` is None for the paper's circular arch by radius and embrace
        with curved faces (:func:`~archquake.geometry.circular_arch`, centre at the origin;
        ``embrace`` then in radians).

        Raises
        ------
        DescriptionError
            For a description by a geometry file, which has no shape.
        """
        if self.geometry is not None:
            raise DescriptionError("{geometry} gives the whole arch; it has no shape fields")
        shape = self.shape or SHAPES[0]
        voussoirs = self._value("voussoirs")
        if self.voussoirs is None and shape == "pointed" and voussoirs % 2:
            voussoirs += 1  # a joint at the crown: half the voussoirs on each side
        faces = self.faces or VOUSSOIR_FACES[0]
        if shape != "circular" or self.span is not None or self.rise is not None:
            return shape, {"span": self.span, "rise": self.rise, "voussoirs": voussoirs,
                           "faces": faces}
        kwargs = {"radius": self._value("radius"),
                  "embrace": math.radians(self._value("embrace")), "voussoirs": voussoirs,
                  "faces": faces}
        return (None if faces == "curved" else "circular"), kwargs

    def _arch(self):
        """The arch of the shape fields or of the geometry file."""
        from .arch import circular_arch
        from .files import load_arch
        from .shaped import shaped_arch

        density = DEFAULT_DENSITY if self.density is None else self.density
        if self.units is not None and (self.geometry is None
                                       or not str(self.geometry).lower().endswith(".dxf")):
            raise DescriptionError("{units} is the length unit of a DXF drawing: give it with "
                                   "{geometry} FILE.dxf")
        if self.geometry is not None:
            # a density given replaces the file's (every file archquake writes gives one)
            return load_arch(self.geometry, density=density,
                             replace_density=self.density is not None, units=self.units)
        shape, kwargs = self.shape_arguments()
        thickness = self._value("thickness")
        if shape is None:
            return circular_arch(kwargs["radius"], kwargs["embrace"], thickness,
                                 kwargs["voussoirs"], density=density)
        return shaped_arch(shape, thickness=thickness, density=density, **kwargs)

    # ------------------------------------------------------------------ piers and fill
    def _check_structure(self) -> None:
        set_ = object.__setattr__
        if self.piers is not None and (self.pier_left is not None
                                       or self.pier_right is not None):
            raise DescriptionError("{piers} gives both piers; use {pier_left} and {pier_right} "
                                   "for unequal ones, not both")
        for name in ("piers", "pier_left", "pier_right"):
            if getattr(self, name) is not None:
                set_(self, name, pier_field(name, getattr(self, name)))
        fill = self._given("fill_density", "fill_inertia", "fill_passive")
        if self.fill_cover is None and fill:
            raise DescriptionError(f"{', '.join(fill)}: the fill needs {{fill_cover:M}} (its "
                                   "depth above the crown [m])")
        if self.fill_passive is not None:
            phi, mobilisation = _numbers("fill_passive", self.fill_passive, 2, 2)
            if not 0 < phi < 90:
                raise DescriptionError(f"{{fill_passive}}: PHI must be in (0, 90) degrees, got "
                                       f"{phi:g}")
            set_(self, "fill_passive", (phi, mobilisation))
        if self.fill_cover is not None:
            self.fill()

    # ------------------------------------------------------------------ spans
    def _check_spans(self) -> None:
        from .bridge import MAX_SPANS

        set_ = object.__setattr__
        if self.spans is not None and not 1 <= self.spans <= MAX_SPANS:
            raise DescriptionError(f"{{spans}} must be an integer in [1, {MAX_SPANS}], got "
                                   f"{self.spans}")
        if self.pier_middle is not None:
            set_(self, "pier_middle", pier_field("pier_middle", self.pier_middle))
        if (self.spans or 1) == 1:
            if self.pier_middle is not None:
                raise DescriptionError("{pier_middle} is the pier between two spans: give "
                                       "{spans} of 2 or more")
            return
        if self.pier_middle is None and self.piers is None:
            raise DescriptionError(f"{{spans}} {self.spans} needs the piers between the spans: "
                                   "give {pier_middle} (or {piers}, which gives all the piers)")

    def _bridge(self, arch):
        """The arch of the description in ``spans`` copies on shared piers (or a list of one
        arch a span: the irregular ones of :meth:`arches`)."""
        from .bridge import multi_span
        from .piers import Pier
        from .structure import Structure

        if isinstance(arch, Structure) or (hasattr(arch, "interfaces") and self.rings is None
                                           and not isinstance(arch, list)):
            what = "a structure" if isinstance(arch, Structure) else "a block assembly"
            raise DescriptionError(f"{{spans}} puts copies of one arch on piers; the geometry "
                                   f"file describes {what} already")
        given = self.pier_middle if self.pier_middle is not None else self.piers
        middle = None if given is None else Pier(*given)
        try:
            return multi_span(arch, self.spans or 1,
                              end_piers=(self.pier("left"), self.pier("right")),
                              middle_pier=middle, fill=self.fill())
        except ValueError as exc:
            text = str(exc).removeprefix("middle_pier: ")
            name = "pier_middle" if self.pier_middle is not None else "piers"
            for side in ("left", "right"):
                if text.startswith(f"{side} pier"):
                    name = f"pier_{side}" if getattr(self, f"pier_{side}") else "piers"
            raise DescriptionError(f"{{{name}}}: {_literal(text)}") from None

    def pier(self, side: str):
        """The :class:`~archquake.geometry.Pier` under the ``"left"`` or ``"right"`` springing
        (None for a fixed springing)."""
        from .piers import Pier

        given = self.piers if self.piers is not None else getattr(self, f"pier_{side}")
        return None if given is None else Pier(*given)

    def fill(self):
        """The :class:`~archquake.geometry.Fill` of the fill fields (None without
        ``fill_cover``)."""
        from .fill import Fill

        if self.fill_cover is None:
            return None
        passive = (None, None)
        if self.fill_passive is not None:
            phi, mobilisation = self.fill_passive
            passive = (math.radians(phi), mobilisation)
        try:
            return Fill(self.fill_cover,
                        DEFAULT_FILL_DENSITY if self.fill_density is None else self.fill_density,
                        self.fill_inertia or DEFAULT_FILL_INERTIA, *passive)
        except ValueError as exc:
            text = str(exc)
            name = "fill_density" if text.startswith("fill density") else (
                "fill_passive" if text.startswith("mobilisation") else "fill_cover")
            raise DescriptionError(f"{{{name}}}: {_literal(text)}") from None

    def _on_piers(self, arch):
        """``arch`` on the piers and under the fill of the description (``arch`` itself without
        them)."""
        from .structure import Structure

        present = self._given(*STRUCTURE_FIELDS)
        if not present:
            return arch
        if isinstance(arch, Structure):
            raise DescriptionError(f"the geometry file describes a structure already; it cannot "
                                   f"be combined with {', '.join(present)}")
        left, right, fill = self.pier("left"), self.pier("right"), self.fill()
        if left is None and right is None and fill is None:
            return arch
        try:
            return Structure(arch, left, right, fill)
        except ValueError as exc:
            text = str(exc)
            name = "fill_cover"
            for side in ("left", "right"):
                if text.startswith(f"{side} pier"):
                    name = f"pier_{side}" if getattr(self, f"pier_{side}") else "piers"
            raise DescriptionError(f"{{{name}}}: {_literal(text)}") from None

    # ------------------------------------------------------------------ rings
    def _check_rings(self) -> None:
        from .rings import RING_BONDS

        set_ = object.__setattr__
        if self.rings is None:
            given = self._given("ring_bond", "ring_friction")
            if given:
                raise DescriptionError(f"{', '.join(given)}: give {{rings}} (the number of "
                                       "rings of the arch)")
            return
        set_(self, "rings", integer_field("rings", self.rings))
        if self.rings < 1:
            raise DescriptionError(f"{{rings}} must be an integer >= 1, got {self.rings}")
        if self.ring_bond is not None and self.ring_bond not in RING_BONDS:
            raise DescriptionError(f"{{ring_bond}} must be one of {_literal(list(RING_BONDS))}, "
                                   f"got {_literal(repr(self.ring_bond))}")
        if self.ring_friction is not None:
            set_(self, "ring_friction", number_field("ring_friction", self.ring_friction))
            if not self.ring_friction >= 0:
                raise DescriptionError(f"{{ring_friction}} must be a Coulomb coefficient >= 0, "
                                       f"got {self.ring_friction:g}")
        other = self._given("geometry", "faces", "epsilon")
        if other:
            raise DescriptionError(f"{{rings}} cuts the arch of the shape fields into rings "
                                   f"with curved faces; it cannot be combined with "
                                   f"{', '.join(other)}")
        if self.shape == "pointed":
            raise DescriptionError("{rings} cuts an arch of a smooth centreline into rings; a "
                                   "pointed arch's crown is a corner: give another {shape}")

    def _rings(self):
        """The arch of several rings (:func:`~archquake.geometry.multi_ring`)."""
        from .rings import multi_ring

        shape, kwargs = self.shape_arguments()
        common = {"rings": self.rings, "voussoirs": kwargs["voussoirs"],
                  "bond": self.ring_bond or "aligned", "ring_friction": self.ring_friction,
                  "density": DEFAULT_DENSITY if self.density is None else self.density}
        if "radius" in kwargs:  # a circle by its radius and embrace (radians here)
            return multi_ring(kwargs["radius"], kwargs["embrace"], self._value("thickness"),
                              **common)
        return multi_ring(shape=shape, span=kwargs["span"], rise=kwargs["rise"],
                          thickness=self._value("thickness"), **common)

    @property
    def bridge_of_arches(self) -> bool:
        """Whether the description is several spans of one arch (not of rings): a bridge whose
        irregular draws put one irregular arch on every span (:meth:`arches`,
        :meth:`sample`)."""
        return (self.spans or 1) > 1 and self.rings is None

    # ------------------------------------------------------------------ the structure
    def nominal(self):
        """The structure before the irregular draw: the arch of the shape fields (or of the
        geometry file) on its piers and under its fill.

        Returns
        -------
        BlockArch or BlockAssembly
            A :class:`~archquake.geometry.CircularArch`, :class:`~archquake.geometry.ShapedArch`
            or :class:`~archquake.geometry.SurveyedArch`, or a
            :class:`~archquake.geometry.Structure` on piers or under fill; with ``spans`` of 2
            or more, or ``rings`` (or a geometry file of one), a
            :class:`~archquake.geometry.BlockAssembly`.

        Raises
        ------
        ValueError
            A :class:`~archquake.errors.DescriptionError` naming the field for piers or a fill
            the arch cannot carry; the builder's own error (naming the same parameter) for a
            value it refuses, or the geometry file's.
        """
        if self.rings is not None:
            if not self._given(*STRUCTURE_FIELDS, "spans"):
                return self._rings()
            return self._bridge(self._rings())  # rings on piers, under fill: spans of them
        if (self.spans or 1) > 1:
            return self._bridge(self._arch())
        return self._on_piers(self._arch())

    def arches(self):
        """``(nominal, structure)``: the structure before and after the irregular draw (the same
        object without ``epsilon``).

        Raises
        ------
        ValueError
            As :meth:`nominal`; for an epsilon out of [0, 1), an arch without a centreline to
            draw around, or a draw that is not a valid arch (naming epsilon and the seed).
        """
        nominal = self.nominal()
        if self.epsilon is None:
            return nominal, nominal
        seed = DEFAULT_SEED if self.seed is None else self.seed
        if self.bridge_of_arches:
            return nominal, self._seated(self._span_draws(self._arch(), seed, f"seed {seed}"),
                                         f"seed {seed}")
        return nominal, self._draw(nominal, seed)

    def _draw(self, arch, rng, which: str | None = None):
        """One irregular arch around ``arch`` (:func:`~archquake.geometry.irregular_arch`, from
        the seed or generator ``rng``); a refusal names epsilon and the seed (or ``which``
        draw it is)."""
        from .irregular import irregular_arch

        if not hasattr(arch, "perturbed"):
            raise DescriptionError("{epsilon} draws an irregular arch around an arch with a "
                                   "centreline; a surveyed arch ({geometry} with 'blocks') has "
                                   "none")
        try:
            return irregular_arch(arch, self.epsilon, rng=rng)
        except ValueError as exc:
            if exc.__cause__ is None:  # epsilon itself is out of its range
                raise
            what = self.drawn() if which is None else (
                f"the irregular arch drawn with {{epsilon}} {self.epsilon:g} ({which})")
            raise DescriptionError(f"{what} is not a valid arch: "
                                   f"{_literal(exc.__cause__)}; epsilon is too large for this "
                                   f"arch") from exc

    def sample(self, sample_size: int):
        """``sample_size`` irregular structures of the description, one at a time: member ``i``
        drawn from child ``i`` of ``SeedSequence(seed)``
        (:func:`~archquake.geometry.irregular_sample`'s streams, so an arch's sample is that of
        the paper's studies), a bridge's spans one after the other from it.

        Yields
        ------
        structure or DescriptionError
            Every member: the structure, or for a bridge whose piers cannot seat the draw's
            springings the :class:`~archquake.errors.DescriptionError` that refuses it.

        Raises
        ------
        ValueError
            As :meth:`arches`, for a description without ``epsilon``, or a size that is not an
            integer >= 1.
        """
        import numpy as np

        if isinstance(sample_size, bool) or not isinstance(sample_size, int) or sample_size < 1:
            raise ValueError(f"sample_size must be an integer >= 1, got {sample_size!r}")
        seed, around = self._sampling()
        return self._members(np.random.SeedSequence(seed).spawn(sample_size), around, seed)

    def _sampling(self):
        """``(seed, around)`` of a sample: its root seed and the arch drawn around (the
        bridge's one arch, else the whole structure), epsilon checked before any member."""
        from .irregular import check_epsilon

        if self.epsilon is None:
            raise DescriptionError("a sample of irregular structures needs {epsilon}")
        check_epsilon(self.epsilon)
        seed = DEFAULT_SEED if self.seed is None else self.seed
        return seed, (self._arch() if self.bridge_of_arches else self.nominal())

    def _members(self, children, around, seed):
        for i, child in enumerate(children):
            try:  # piers that cannot seat a bridge's springings: the member is not built
                member = self._member(around, child, f"member {i} of the sample of seed {seed}")
            except UnseatedError as exc:
                member = exc
            yield member

    def member(self, index: int):
        """Member ``index`` of :meth:`sample` alone, drawn from ``SeedSequence(seed,
        spawn_key=(index,))`` (child ``index`` of the seed, whatever the sample's size): what a
        study that draws its members one chunk at a time builds.

        Parameters
        ----------
        index : int
            Member index, >= 0.

        Returns
        -------
        BlockArch or BlockAssembly

        Raises
        ------
        DescriptionError
            As :meth:`sample` (without ``epsilon``), or for a draw that is not a valid arch;
            :class:`~archquake.errors.UnseatedError` for a bridge whose piers cannot seat the
            draw's springings (naming the member).
        """
        import numpy as np

        seed, around = self._sampling()
        child = np.random.SeedSequence(seed, spawn_key=(int(index),))
        return self._member(around, child, f"member {index} of the sample of seed {seed}")

    def _member(self, around, child, which: str):
        """The member of the generator seeded by ``child``, around the arch ``around``."""
        import numpy as np

        rng = np.random.default_rng(child)
        if not self.bridge_of_arches:
            return self._draw(around, rng, which)
        return self._seated(self._span_draws(around, rng, which), which)

    def _span_draws(self, arch, rng, which: str) -> list:
        """``spans`` irregular arches around ``arch``, one after the other from the generator
        (or seed) ``rng`` (span 1 first), each a draw of the paper's eq. (1) (:meth:`_draw`)."""
        import numpy as np

        rng = np.random.default_rng(rng)
        return [self._draw(arch, rng, which) for _ in range(self.spans)]

    def _seated(self, draws: list, which: str):
        """The bridge of the arches ``draws`` on the shared piers
        (:func:`~archquake.geometry.bridge.multi_span`); a refusal names the draw by
        ``which``."""
        try:
            return self._bridge(draws)
        except DescriptionError as exc:  # thicker end voussoirs need wider seats, ...
            raise UnseatedError(f"the {self.spans} irregular arches drawn with {{epsilon}} "
                                f"{self.epsilon:g} ({which}), on these piers: "
                                f"{exc.template}") from None

    def build(self):
        """The structure described (after the irregular draw, if any): :meth:`arches`\\ ``[1]``.

        Returns
        -------
        BlockArch
        """
        return self.arches()[1]

    def drawn(self) -> str:
        """How a message names the irregular arch of ``epsilon`` and ``seed`` (a template of
        :class:`~archquake.errors.DescriptionError`)."""
        return (f"the irregular arch drawn with {{epsilon}} {self.epsilon:g} (seed "
                f"{DEFAULT_SEED if self.seed is None else self.seed})")

    # ------------------------------------------------------------------ JSON
    def to_dict(self) -> dict:
        """The fields given, as JSON values (piers and the passive reaction as lists):
        :meth:`from_dict` reads it back to an equal description."""
        return {f.name: (list(v) if isinstance(v, tuple) else v) for f in fields(self)
                if (v := getattr(self, f.name)) is not None}

    @classmethod
    def from_dict(cls, data) -> StructureSpec:
        """The description of a dict of fields (the page's JSON, or :meth:`to_dict`); a value
        None or ``""`` is not given.

        Raises
        ------
        DescriptionError
            For something else than a dict, an unknown field, or a value the description
            refuses.
        """
        DescriptionError.check_fields(data, [f.name for f in fields(cls)], "structure")
        return cls(**{k: v for k, v in data.items() if v is not None and v != ""})


__all__ = ["RING_FIELDS", "SHAPE_FIELDS", "SPAN_FIELDS", "STRUCTURE_FIELDS", "StructureSpec",
           "integer_field", "number_field", "pier_field"]
