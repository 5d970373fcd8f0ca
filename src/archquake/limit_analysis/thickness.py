r"""Limit analysis, least dimensions: the minimum thickness of an arch (:func:`min_thickness`,
:func:`shaped_min_thickness`), the narrowest piers on which it stands (:func:`min_pier_width`)
and Heyman's geometric safety factor (:func:`geometric_safety_factor`), all roots of the
self-weight margin (:mod:`.self_weight`)."""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
from scipy.optimize import brentq

from ..errors import CannotStandError, NoThicknessError
from ..geometry import (
    BlockArch,
    CircularArch,
    Fill,
    Pier,
    ShapedArch,
    Structure,
    centreline,
    circular_arch,
    shaped_arch,
)
from ..geometry.blocks import check_voussoir_count
from .friction import check_friction, friction_margin
from .self_weight import self_weight_margin, stand_margin, standing


def min_thickness(
    radius: float, embrace: float, voussoirs: int, *, xtol: float = 1e-12,
    friction: float | None = None,
) -> float:
    """Minimum thickness of a circular arch that stands under its own weight [m].

    Root of :func:`self_weight_margin` in the thickness of ``circular_arch(radius, embrace, t,
    voussoirs)``, found by bracketing and Brent's method. Classical check: a semicircular arch
    (embrace pi) with many voussoirs gives ``t / R`` close to 0.1075 (Heyman's 0.106 [1]_ with
    Milankovitch's correction).

    Parameters
    ----------
    radius : float
        Mean radius R [m].
    embrace : float
        Angle of embrace alpha [rad].
    voussoirs : int
        Number of voussoirs n.
    xtol : float
        Absolute tolerance on t / R [-].
    friction : float, optional
        Coulomb coefficient of the joints [-]: the joints may also slide, and the thrust line
        must lie within every joint's friction cone too (:func:`friction_margin`). Default:
        none (Heyman's hypothesis, nothing slides). For a semicircle the purely rotational
        minimum (t/R = 0.1075) needs a friction of about 0.395; below it the minimum grows,
        and below about 0.309 no thickness suffices (the Couplet-Heyman problem with finite
        friction [2]_; ``tests/limit_analysis/test_min_thickness_friction.py``).

    Returns
    -------
    float
        The minimum thickness t [m].

    Raises
    ------
    NoThicknessError
        When no thickness up to twice the radius lets the arch stand (with ``friction``: the
        friction is below the critical one of this arch's shape).

    References
    ----------
    .. [1] Heyman, J. (1982). The Masonry Arch. Chichester: Ellis Horwood.
    .. [2] G. Cocchetti and E. Rizzi, "Non-linear mechanics of the 'Couplet-Heyman problem'
       with finite friction", Frattura ed Integrita Strutturale 51 (2020) 356-375, Table 3.
    """
    circular_arch(radius, embrace, 0.5 * radius, voussoirs)  # checks the input
    ratio = _min_thickness_ratio(
        lambda ratio: circular_arch(radius, embrace, ratio * radius, voussoirs), 2.0, xtol,
        f"radius={radius} m, embrace={embrace} rad, voussoirs={voussoirs}", friction)
    return float(ratio * radius)


def _min_thickness_ratio(arch_of, largest: float, xtol: float, what: str,
                         friction: float | None = None) -> float:
    """Root in ``(0, largest)`` of the self-weight margin of ``arch_of(ratio)`` (with
    ``friction``: :func:`friction_margin`, ``-inf`` where no thrust line fits the friction
    cones): bracketed from ``largest / 4`` (up toward ``largest``, then halving down), then
    Brent's method."""
    if friction is not None:
        friction = check_friction(friction)

    def margin(ratio: float) -> float:
        # only its sign matters: clipped, an unbounded margin (inf) still brackets the root
        arch = arch_of(ratio)
        value = (self_weight_margin(arch) if friction is None
                 else friction_margin(arch, friction))
        return min(max(value, -1.0), 1.0)

    hi = 0.25 * largest
    while margin(hi) < 0.0:
        hi = 0.5 * (hi + largest)
        if hi > (1.0 - 5e-4) * largest and friction is not None:
            # with friction a thick arch may slide where a thinner one stands: look lower
            hi = next((r for r in np.linspace(largest / 64, largest, 64, endpoint=False)
                       if margin(r) >= 0.0),
                      hi)
            if margin(hi) >= 0.0:
                break
        if hi > (1.0 - 5e-4) * largest:
            if friction is None:
                raise NoThicknessError(
                    "no thickness lets this arch stand under its own weight below its largest "
                    f"thickness ({what})")
            raise NoThicknessError(
                f"with friction {friction:g} at its joints no thickness lets this arch stand "
                f"under its own weight, up to its largest thickness ({what}): the friction is "
                "below the least with which the shape can stand (its joints would slide "
                "whatever the thickness)")
    lo = 0.5 * hi
    while margin(lo) >= 0.0:
        hi, lo = lo, 0.5 * lo
        if lo < 1e-12:
            return hi
    return float(brentq(margin, lo, hi, xtol=xtol, rtol=4 * np.finfo(float).eps))


def shaped_min_thickness(
    shape: str, *, voussoirs: int, span: float | None = None, rise: float | None = None,
    radius: float | None = None, embrace: float | None = None, faces: str = "curved",
    xtol: float = 1e-12, friction: float | None = None,
) -> float:
    r"""Minimum thickness of an arch of a shape that stands under its own weight [m].

    The centreline stays and the thickness t of :func:`~archquake.geometry.shaped_arch` scales:
    root of :func:`self_weight_margin` in t, found by bracketing below twice the centreline's
    smallest radius of curvature (where the intrados would fold) and Brent's method. For a
    semicircle with many voussoirs ``t / R`` tends to Milankovitch's 0.1075 [1]_.

    Parameters
    ----------
    shape : str
        One of :data:`~archquake.geometry.SHAPES`.
    voussoirs : int
        Number of voussoirs n.
    span, rise : float, optional
        Span and rise of the centreline [m].
    radius, embrace : float, optional
        For a circular arch, instead of span and rise: radius [m] and embrace [rad].
    faces : {"curved", "flat"}
        Voussoir faces.
    xtol : float
        Absolute tolerance on t / span [-].
    friction : float, optional
        Coulomb coefficient of the joints [-] (see :func:`min_thickness`); default none.

    Returns
    -------
    float
        The minimum thickness t [m].

    References
    ----------
    .. [1] Heyman, J. (1982). The Masonry Arch. Chichester: Ellis Horwood (Milankovitch's
       semicircle).
    """
    line = centreline(shape, span, rise, radius=radius, embrace=embrace)
    check_voussoir_count(voussoirs)
    largest = 2.0 * line.min_radius_of_curvature(0.0, line.length) / line.span

    def arch_of(ratio: float) -> ShapedArch:
        return shaped_arch(shape, span=span, rise=rise, radius=radius, embrace=embrace,
                           thickness=ratio * line.span, voussoirs=voussoirs, faces=faces)

    arch_of(0.25 * largest)  # checks the input
    ratio = _min_thickness_ratio(arch_of, largest, xtol,
                                 f"{shape} arch of {voussoirs} voussoirs", friction)
    return float(ratio * line.span)


MAX_PIER_XTOL = 1e-3
"""Coarsest tolerance of :func:`min_pier_width`, as a fraction of the arch's size [-]."""


def min_pier_width(arch: BlockArch, height: float, courses: int = 1, *,
                   fill: Fill | None = None, xtol: float = 1e-9) -> float:
    """Narrowest equal rectangular piers on which an arch stands under its own weight [m]
    (to ``xtol``, from above: the arch stands on the width returned).

    The piers (:class:`~archquake.geometry.Pier`, ``height`` high in ``courses`` courses) are
    widened from the narrowest that fit the springing joints (their horizontal extent) until
    :func:`self_weight_margin` of the structure turns >= 0: bracketed by doubling, then Brent's
    method on the margin, as :func:`min_thickness` does on the thickness.

    Parameters
    ----------
    arch : BlockArch
        The arch (circular, shaped or surveyed; a :class:`~archquake.geometry.Structure` stands
        for its arch and its fill, its own piers set aside).
    height : float
        Height of the piers from the ground to the intrados springing point [m].
    courses : int, default 1
        Courses of each pier [-].
    fill : Fill, optional
        Fill over the arch (default: a Structure's own, else none).
    xtol : float, default 1e-9
        Absolute tolerance on the width [m], in (0, :data:`MAX_PIER_XTOL` x the arch's size]
        (a coarser tolerance may return a width on which the arch cannot stand).

    Returns
    -------
    float
        The width [m] (the narrowest that fits when the arch stands on it already).

    Raises
    ------
    CannotStandError
        When the arch does not stand even on fixed springings (no pier helps).
    ValueError
        For a bad height, number of courses or ``xtol``, or no width up to a thousand times
        the arch's size that makes it stand.

    Examples
    --------
    >>> from archquake import oppenheim
    >>> round(min_pier_width(oppenheim(), 6.0), 3)
    2.045
    """
    if isinstance(arch, Structure):
        fill = arch.fill if fill is None else fill
        arch = arch.arch
    Pier(1.0, height, courses)  # checks height and courses
    size = arch.length_scale
    largest = MAX_PIER_XTOL * size
    if isinstance(xtol, bool) or not isinstance(xtol, int | float | np.floating | np.integer) \
            or not 0.0 < xtol <= largest:
        raise ValueError(f"xtol must be a number in (0, {largest:.4g}] m ({MAX_PIER_XTOL:g} of "
                         f"the arch's size {size:.4g} m), got {xtol!r}")
    free = Structure(arch, fill=fill)
    if stand_margin(free) < 0.0:
        raise CannotStandError(standing(free).reason + "; no pier can make it stand")
    joints = arch.joints
    reach = max(float(joints[0, 0, 0] - joints[0, 1, 0]),
                float(joints[-1, 1, 0] - joints[-1, 0, 0]), 0.0)

    def margin(width: float) -> float:
        pier = Pier(width, height, courses)
        return min(max(stand_margin(Structure(arch, pier, pier, fill)), -1.0), 1.0)

    lo = max(reach, 1e-6 * size)
    if margin(lo) >= 0.0:
        return lo
    hi = max(2.0 * lo, 0.1 * size)
    while margin(hi) < 0.0:
        lo, hi = hi, 2.0 * hi
        if hi > 1e3 * size:
            raise ValueError(f"no pier width up to {hi:.4g} m makes this arch stand on piers "
                             f"{height:g} m high")
    width = float(brentq(margin, lo, hi, xtol=xtol))
    for _ in range(4):  # the root to xtol may fall short of it: the width returned stands
        if margin(width) >= 0.0:
            break
        width = min(width + xtol, hi)
    return width


@dataclass(frozen=True)
class GeometricSafetyFactor:
    """Heyman's geometric factor of safety of a structure, or why it has none.

    Attributes
    ----------
    kind : {"thickness", "pier width"} or None
        What is scaled: the arch's thickness or its piers' width; None when the factor is not
        defined (``note`` says why).
    value : float or None
        The structure's thickness or pier width [m].
    minimum : float or None
        The least thickness or pier width on which it stands under its own weight [m].
    factor : float or None
        ``value / minimum`` [-].
    note : str
        What the factor is of, or why there is none.
    thickness : GeometricSafetyFactor or None
        For an arch on piers: the bare arch's factor in thickness (whether defined or not);
        None otherwise.
    """

    kind: str | None
    value: float | None
    minimum: float | None
    factor: float | None
    note: str
    thickness: GeometricSafetyFactor | None = None

    def to_dict(self) -> dict:
        """The factor as JSON-ready data.

        Returns
        -------
        dict
            ``kind``, ``value`` and ``minimum`` [m], ``factor`` [-] (None when not defined) and
            ``note``; an arch on piers also has ``thickness``, the bare arch's factor as a dict
            of the same keys.
        """
        out = {"kind": self.kind, "value": self.value, "minimum": self.minimum,
               "factor": self.factor}
        if self.thickness is not None:
            out["thickness"] = self.thickness.to_dict()
        out["note"] = self.note
        return out


def _same_geometry(arch: BlockArch, other: BlockArch) -> bool:
    """Whether two arches have the same joints (to 1e-9 of their size) and kind."""
    return (type(arch) is type(other) and arch.n_voussoirs == other.n_voussoirs
            and bool(np.allclose(arch.joints, other.joints, rtol=0.0,
                                 atol=1e-9 * arch.length_scale)))


def _thickness_safety_factor(arch: BlockArch) -> GeometricSafetyFactor:
    """The factor in thickness of an arch on fixed springings (its fill set aside)."""
    try:
        if isinstance(arch, CircularArch):
            t, r, n = float(arch.thicknesses[0]), float(arch.radii[0]), arch.n_voussoirs
            if _same_geometry(arch, circular_arch(r, arch.embrace, t, n, density=arch.density)):
                t_min = min_thickness(r, arch.embrace, n)
                return GeometricSafetyFactor(
                    "thickness", t, t_min, t / t_min,
                    f"thickness over the minimum thickness of a circular arch of the same "
                    f"radius, embrace and {n} voussoirs")
        elif isinstance(arch, ShapedArch):
            line, t, n = arch.centreline, float(arch.thicknesses[0]), arch.n_voussoirs
            nominal = shaped_arch(line.shape, thickness=t, voussoirs=n, span=line.span,
                                  rise=line.rise, faces=arch.faces, density=arch.density)
            if _same_geometry(arch, nominal):
                t_min = shaped_min_thickness(line.shape, voussoirs=n, span=line.span,
                                             rise=line.rise, faces=arch.faces)
                return GeometricSafetyFactor(
                    "thickness", t, t_min, t / t_min,
                    f"thickness over the minimum thickness of a {line.shape} arch of the same "
                    f"span, rise and {n} voussoirs")
    except (ValueError, CannotStandError) as exc:
        return GeometricSafetyFactor(None, None, None, None,
                                     f"the minimum thickness could not be found: {exc}")
    return GeometricSafetyFactor(None, None, None, None,
                                 "not defined: the arch's voussoirs are not equal and of one "
                                 "thickness (an irregular or surveyed arch), so there is no "
                                 "thickness to scale")


def geometric_safety_factor(structure: BlockArch) -> GeometricSafetyFactor:
    r"""The geometric safety factor of a structure: how much thinner (or its piers narrower) it
    could be and still stand under its own weight (Heyman's geometric factor of safety).

    As Heyman defines it [1]_, for an arch on two equal rectangular piers: the piers' width over
    the narrowest on which it stands (:func:`min_pier_width`, fill included),

    .. math::

        \mathrm{SF} = \frac{b}{b_{\min}}.

    Otherwise, for an arch of equal voussoirs and constant thickness (as
    :func:`~archquake.geometry.circular_arch` or :func:`~archquake.geometry.shaped_arch` build
    it): its thickness over the minimum thickness of the same centreline and voussoirs
    (:func:`min_thickness`, :func:`shaped_min_thickness`), of the bare arch on fixed springings,
    :math:`\mathrm{SF} = t / t_{\min}`. Irregular and surveyed arches have no thickness to
    scale: the factor is not defined for them (a value that says so, not an error).

    Parameters
    ----------
    structure : BlockArch
        An arch (circular, shaped or surveyed) or a :class:`~archquake.geometry.Structure` on
        piers or under fill.

    Returns
    -------
    GeometricSafetyFactor
        For an arch on piers, the factor in pier width, with the bare arch's factor in
        thickness as its ``thickness``; otherwise the factor in thickness.

    References
    ----------
    .. [1] Heyman, J. (1982). The Masonry Arch. Chichester: Ellis Horwood.

    Examples
    --------
    >>> import math
    >>> from archquake.geometry import circular_arch
    >>> arch = circular_arch(1.0, math.pi, 0.15, 10)
    >>> sf = geometric_safety_factor(arch)
    >>> sf.kind, round(sf.factor, 3)
    ('thickness', 1.396)
    """
    arch = structure.arch if isinstance(structure, Structure) else structure
    thickness = _thickness_safety_factor(arch)
    if isinstance(structure, Structure) and thickness.kind is not None and (
            structure.fill is not None):
        thickness = replace(thickness, note=thickness.note + " (the bare arch, without its fill)")
    piers = isinstance(structure, Structure) and (structure.left is not None
                                                  or structure.right is not None)
    if not piers:
        return thickness
    left, right = structure.left, structure.right

    def undefined(note: str) -> GeometricSafetyFactor:
        return GeometricSafetyFactor(None, None, None, None, note, thickness)

    if left is None or left != right or not left.is_rectangular:
        return undefined("not defined for piers that are not two equal rectangular ones (the "
                         "narrowest piers are found for two equal rectangular piers)")
    try:
        width = min_pier_width(structure, left.height, left.courses)
    except (ValueError, CannotStandError) as exc:
        return undefined(f"the narrowest piers could not be found: {exc}")
    return GeometricSafetyFactor(
        "pier width", left.width, width, left.width / width,
        f"width of the piers over the narrowest equal rectangular piers {left.height:g} m high "
        f"on which the arch" + (" with its fill" if structure.fill is not None else "")
        + " stands", thickness)
