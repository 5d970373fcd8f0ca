"""The option groups that several commands share, and what turns their values into the library's
arguments.

Each group is one function ``add_<group>(parser)``, so that a command takes a group with one line
of its ``configure``; the values are read by the function beside it (``arch_from_args``,
``motion_from_args``, ...). Building the options imports nothing heavy: the choices and the
defaults they show come from :mod:`archquake.defaults`, the same values the run uses.

A structure and a ground motion are described in the library, by named values
(:class:`archquake.geometry.StructureSpec`, :class:`archquake.ground_motion.MotionSpec`): here
their options are mapped onto those names (``--pier-left`` is ``pier_left``, ``--param
NAME=VALUE`` is ``params``), and a description refused names its fields, which
:data:`FIELD_OPTIONS` names as options (``--piers: ...``).

The options do not check what the library checks: the library raises a :class:`ValueError`
that names its parameter (``sample_size must be ...``) and :func:`option_message` names the
option instead (``--samples must be ...``), through one table, :data:`OPTION_NAMES`. What is left
here is what the library cannot check: combinations of options that are not a description's.
"""

from __future__ import annotations

import argparse
import contextlib
import os
import re

from ..constants import DEFAULT_DENSITY, DEFAULT_FILL_DENSITY
from ..defaults import (
    ANALYTIC_GROUND_MOTIONS,
    COMPATIBILITY_RULES,
    DEFAULT_COARSE_FACTOR,
    DEFAULT_EPSILON,
    DEFAULT_FACTOR_RANGE,
    DEFAULT_FILL_INERTIA,
    DEFAULT_FRICTION,
    DEFAULT_LEVEL_STRIDE,
    DEFAULT_MODEL,
    DEFAULT_MOTION,
    DEFAULT_PERIOD_RANGE,
    DEFAULT_PULSE,
    DEFAULT_RECORD_COUNT,
    DEFAULT_RESTITUTION,
    DEFAULT_SEED,
    DEFAULT_STRIDE,
    FILL_INERTIA_MODELS,
    MAX_ACCELERATION_G,
    MAX_COARSE_FACTOR,
    MAX_CYCLES,
    MAX_SAMPLES,
    SEARCHES,
    SHAPES,
    STUDY_SAMPLE_SIZE,
    VOUSSOIR_FACES,
    circular_defaults,
)
from ..errors import DescriptionError
from ..ranges import number

# ---------------------------------------------------------------------------------------------
# library parameters -> options
# ---------------------------------------------------------------------------------------------

OPTION_NAMES = {
    "fill_passive": "--fill-passive",
    "sample_size": "--samples",
    "limit_sample_size": "--limit-samples",
    "limit_method": "--limit-method",
    "epsilon": "--epsilon",
    "seed": "--seed",
    "restitution": "--restitution",
    "durations": "--durations",
    "amplitudes": "--amplitudes",
    "amplitudes_g": "--amplitudes",
    "resolution_g": "--resolution",
    "extend_to_g": "--extend-to",
    "direction": "--direction",
    "levels": "--levels",
    "im": "--im",
    "workers": "--workers",
    "friction": "--friction",
    "time_step": "--time-step",
    "coarse_factor": "--coarse-factor",
    "t_end": "--t-end",
    "phi0": "--phi0",
    "duration": "--duration",
    "cycles": "--cycles",
    "scale_to": "--scale-to",
    "shape": "--shape",
    "span": "--span",
    "rise": "--rise",
    "radius": "--radius",
    "radii": "--radius",
    "embrace": "--embrace",
    "thickness": "--thickness",
    "voussoirs": "--voussoirs",
    "faces": "--faces",
    "sa_period": "--sa-period",
    "count": "--records-count",
    "period_range": "--period-range",
    "factor_range": "--factor-range",
    "rule": "--compatibility",
    "rings": "--rings",
    "ring_friction": "--ring-friction",
}
"""The option of each parameter of the library that an option sets, for the messages of
:func:`option_message` (``sample_size`` of :class:`~archquake.studies.fragility.FragilitySettings`
is ``--samples``, ``epsilon`` of eq. (1) is ``--epsilon``, ...)."""

_NAMED = re.compile(r"^([a-z][a-z0-9_]*)(?=(?: [a-z]+)? must\b|:)")


def option_message(message: str) -> str:
    """A message of the library that names a parameter, naming its option instead.

    Only a message that starts with the parameter (``"epsilon must be in [0, 1), got 1.5"``,
    ``"im: unknown intensity measure ..."``) is changed; one that starts otherwise is about
    something else (a file, a drawn arch) and is left as it is.

    Parameters
    ----------
    message : str
        The text of a :class:`ValueError` of the library.

    Returns
    -------
    str
        The message with the parameter replaced by its option (:data:`OPTION_NAMES`).

    Examples
    --------
    >>> option_message("sample_size must be an integer in [1, 100000], got 0")
    '--samples must be an integer in [1, 100000], got 0'
    >>> option_message("durations x amplitudes = 2 x 3 = 6 analyses")
    'durations x amplitudes = 2 x 3 = 6 analyses'
    >>> option_message("cannot resume: setting 'sample_size' differs")
    "cannot resume: --samples (setting 'sample_size') differs"
    """
    message = _SETTING.sub(_setting_option, message)
    match = _NAMED.match(message)
    if match is None or match.group(1) not in OPTION_NAMES:
        return message
    return OPTION_NAMES[match.group(1)] + message[match.end(1):]


SETTING_OPTIONS = {
    **OPTION_NAMES,
    "model": "--model", "search": "--search", "stride": "--stride",
    "nominal": "the arch (its geometry options)",
    "suite": "the records (--records or --suite)",
    "im_unit": "the unit of --im",
    "motion": "the pulse shape",
}
"""The option (or the words) of each setting a study records, for a refused resume
(``setting 'sample_size' differs`` is said ``--samples differs``)."""

_SETTING = re.compile(r"\bsetting '([a-z][a-z0-9_]*)'")


def _setting_option(match: re.Match) -> str:
    name = SETTING_OPTIONS.get(match.group(1))
    return match.group(0) if name is None else f"{name} (setting {match.group(1)!r})"


def given(args: argparse.Namespace, *names: str) -> list[str]:
    """The options among ``names`` given on the command line (not None, empty or False; a
    number 0 is given: ``--rise 0`` is a rise of zero, which the library refuses by name)."""
    return [f"--{name.replace('_', '-')}" for name in names
            if (value := getattr(args, name)) is not None and value is not False
            and value != []]


FIELD_OPTIONS = {
    **{name: f"--{name.replace('_', '-')}" for name in (
        "shape", "span", "rise", "radius", "embrace", "thickness", "voussoirs", "faces",
        "geometry", "units", "piers", "pier_left", "pier_right",
        "spans", "pier_middle",
        "fill_cover", "fill_density", "fill_inertia", "fill_passive",
        "rings", "ring_bond", "ring_friction",
        "density", "epsilon",
        "seed", "motion", "amplitude", "duration", "cycles", "record", "suite", "scale_to",
        "reverse")},
    "params": "--param",
    "suite_record": "--record",
}
"""The option of each field of a structure's or a ground motion's description, for the
messages of :func:`naming_options` (``suite_record``, the record of a built-in suite, is given by
``--record`` with ``--suite``)."""


@contextlib.contextmanager
def naming_options():
    """A refused description (:class:`~archquake.errors.DescriptionError`) as a
    :class:`ValueError` whose message names the options (:data:`FIELD_OPTIONS`) instead of the
    fields."""
    try:
        yield
    except DescriptionError as exc:
        raise ValueError(exc.naming(FIELD_OPTIONS)) from None


# ---------------------------------------------------------------------------------------------
# the arch
# ---------------------------------------------------------------------------------------------


def add_shape_options(group, *, thickness: bool = True) -> None:
    """``--shape``, ``--span``, ``--rise``, ``--radius``, ``--embrace``, ``--thickness`` (unless
    ``thickness=False``), ``--voussoirs`` and ``--faces``: an arch by its shape."""
    defaults = circular_defaults()
    group.add_argument("--shape", choices=SHAPES, default=None,
                       help=f"shape of the centreline (default: {SHAPES[0]}); every shape but the "
                            "circle is given by --span and --rise, with its springings on y = 0")
    group.add_argument("--span", type=number, default=None,
                       help="span of the centreline [m] (with --rise)")
    group.add_argument("--rise", type=number, default=None,
                       help="rise of the centreline [m] (with --span)")
    group.add_argument("--radius", type=number, default=None,
                       help=f"mean radius R of a circular arch [m] (default: "
                            f"{defaults['radius']:g} unless --span and --rise are given)")
    group.add_argument("--embrace", type=number, default=None,
                       help=f"angle of embrace alpha of a circular arch [deg] (default: "
                            f"{defaults['embrace']:g})")
    if thickness:
        group.add_argument("--thickness", type=number, default=None,
                           help=f"thickness t, normal to the centreline [m] (default: "
                                f"{defaults['thickness']:g})")
    voussoirs = defaults["voussoirs"]
    group.add_argument("--voussoirs", type=int, default=None,
                       help=f"number of voussoirs n, of equal centreline length (default: "
                            f"{voussoirs}, {voussoirs + voussoirs % 2} for a pointed arch, "
                            f"which needs an even number)")
    group.add_argument("--faces", choices=VOUSSOIR_FACES, default=None,
                       help="voussoir faces: curved (following intrados and extrados) or flat "
                            f"(chords between the joint ends) (default: {VOUSSOIR_FACES[0]})")


def _add_geometry_file_option(group) -> None:
    group.add_argument("--geometry", metavar="FILE.json|FILE.dxf",
                       help="explicit arch, instead of the options above: a JSON file with "
                            "'angles' [rad], 'thicknesses' [m], 'radii' [m] per voussoir (a "
                            "circular arch), or 'blocks' (block polygons [[x, y], ...] [m], left "
                            "to right, optionally 'springings'); or any block assembly: a JSON "
                            "file with 'blocks' and 'supports', or a DXF drawing of closed "
                            "polylines (supports on a layer named SUPPORT or GROUND, else the "
                            "ground is the lowest line)")
    group.add_argument("--units", choices=("mm", "cm", "m", "in", "ft"), default=None,
                       help="length unit of a DXF drawing, overriding its header's $INSUNITS "
                            "(default: the header's; a drawing without units is taken in m, "
                            "with a warning)")


def add_arch_options(parser: argparse.ArgumentParser) -> None:
    """The arch of a command that analyses one: its shape (default Oppenheim's arch) or a file,
    and optionally one irregular arch drawn around it (``--epsilon``, ``--seed``)."""
    group = parser.add_argument_group("arch geometry (defaults: Oppenheim's arch)")
    add_shape_options(group)
    _add_geometry_file_option(group)
    add_structure_options(parser)
    group.add_argument("--epsilon", type=number, default=None, metavar="EPS",
                       help="draw one irregular arch around the arch above with the "
                            "irregularity epsilon in [0, 1) of the paper's eq. (1) (with "
                            "--spans: one a span)")
    group.add_argument("--seed", type=int, default=None,
                       help=f"seed of the irregular draw (default: {DEFAULT_SEED})")


def add_nominal_arch_options(parser: argparse.ArgumentParser) -> None:
    """The nominal arch of a sample of irregular arches, with the sample's ``--epsilon``
    (default 0.10) and ``--seed`` (default 0)."""
    group = parser.add_argument_group("nominal arch geometry (defaults: Oppenheim's arch)")
    add_shape_options(group)
    _add_geometry_file_option(group)
    add_structure_options(parser)
    group.add_argument("--epsilon", type=number, default=DEFAULT_EPSILON, metavar="EPS",
                       help="irregularity epsilon in [0, 1) of the irregular arches drawn "
                            "around the nominal arch (paper eq. 1; default: %(default)s)")
    group.add_argument("--seed", type=int, default=DEFAULT_SEED,
                       help="root seed of the sample: arch i is drawn from "
                            "SeedSequence(seed, spawn_key=(i,)) (default: %(default)s)")


# ---------------------------------------------------------------------------------------------
# piers, buttresses and fill
# ---------------------------------------------------------------------------------------------

def add_structure_options(parser: argparse.ArgumentParser) -> None:
    """``--piers``, ``--pier-left``, ``--pier-right``, ``--fill-*`` and ``--density``: the arch
    on piers or buttresses and under a fill (:class:`archquake.geometry.Structure`)."""
    group = parser.add_argument_group("piers, fill and masonry (default: fixed springings, no "
                                      "fill)")
    pier = ("WIDTH [m] from the intrados springing point outward, HEIGHT [m] from the ground "
            "up to it, COURSES of equal height (default 1)")
    group.add_argument("--piers", metavar="WIDTH,HEIGHT[,COURSES]",
                       help=f"put the arch on two equal rectangular piers: {pier}")
    group.add_argument("--pier-left", metavar="WIDTH,HEIGHT[,COURSES]",
                       help="the pier under the left springing only (with --pier-right: "
                            "unequal piers)")
    group.add_argument("--pier-right", metavar="WIDTH,HEIGHT[,COURSES]",
                       help="the pier under the right springing only")
    group.add_argument("--spans", type=int, default=None, metavar="N",
                       help=f"N equal arches in a row on N + 1 piers (a bridge, an arcade; "
                            f"{', '.join(SPANS_COMMANDS[:-1])} and {SPANS_COMMANDS[-1]}): the "
                            "end piers those of --piers, --pier-left, --pier-right, the ones "
                            "between the spans --pier-middle (default: 1)")
    group.add_argument("--pier-middle", metavar="WIDTH,HEIGHT[,COURSES]",
                       help="the piers between the spans: WIDTH [m] between the two intrados "
                            "springing points each carries, HEIGHT [m] from the ground up to "
                            "them, COURSES (default: the --piers value)")
    group.add_argument("--fill-cover", type=number, metavar="M",
                       help="a level fill over the arch, this deep above the crown [m]")
    group.add_argument("--fill-density", type=number, metavar="KG/M3",
                       help=f"density of the fill [kg/m^3] (default: {DEFAULT_FILL_DENSITY:g})")
    group.add_argument("--fill-inertia", choices=FILL_INERTIA_MODELS,
                       help="where the fill's horizontal inertia force acts: none (dead load "
                            "only), centroid (through each column's centroid: the fill moves "
                            "with its voussoir; the dynamic models' one) or extrados (on the "
                            f"extrados below it) (default: {DEFAULT_FILL_INERTIA})")
    group.add_argument("--fill-passive", metavar="PHI,MOBILISATION",
                       help="a passive reaction of the fill toward midspan on each voussoir: "
                            "angle of friction PHI [deg] and mobilised fraction of Rankine's "
                            "passive pressure in [0, 1]")
    group.add_argument("--density", type=number, metavar="KG/M3",
                       help=f"density of the masonry, arch and piers [kg/m^3] (default: "
                            f"the --geometry file's, else {DEFAULT_DENSITY:g}); given, it "
                            "replaces the density of the --geometry file")
    add_ring_options(parser)


def add_ring_options(parser: argparse.ArgumentParser) -> None:
    """``--rings``, ``--ring-bond`` and ``--ring-friction``: the circular arch of the shape
    options cut into rings that can separate (:func:`archquake.geometry.multi_ring`); only
    ``limit``, ``rigid-blocks`` and ``assess`` analyse one (:func:`refuse_rings`)."""
    from ..defaults import RING_BONDS

    group = parser.add_argument_group("rings (limit, rigid-blocks, domain and assess; default: "
                                      "one ring, the arch)")
    group.add_argument("--rings", type=int, metavar="N",
                       help="cut the arch of the shape options (not a pointed one) into N "
                            "concentric rings of equal thickness that can separate (a "
                            "multi-ring brick arch), on fixed springings or on the piers and "
                            "under the fill of the options above (with --spans: a bridge of "
                            "them)")
    group.add_argument("--ring-bond", choices=RING_BONDS,
                       help="joints of adjacent rings on the same radial lines (aligned) or "
                            "offset by half a voussoir, with half voussoirs at the springings "
                            "(staggered: brickwork) (default: aligned)")
    group.add_argument("--ring-friction", type=number, metavar="MU",
                       help="Coulomb friction coefficient of the interfaces between rings, "
                            ">= 0 (default: they open but do not slide); --friction then gives "
                            "the other interfaces' (without it they do not slide)")


def refuse_rings(args: argparse.Namespace) -> None:
    """Refuse ``--rings`` (and its options) naming them: an arch of several rings is a block
    assembly, which only the commands of :data:`RING_COMMANDS` analyse."""
    present = given(args, "rings", "ring_bond", "ring_friction") if hasattr(args, "rings") \
        else []
    if present:
        raise ValueError(f"{', '.join(present)}: an arch of several rings is a block assembly, "
                         f"which {', '.join(RING_COMMANDS[:-1])} and {RING_COMMANDS[-1]} "
                         "analyse; this command does not")


def describes_assembly(args: argparse.Namespace) -> bool:
    """Whether the options may describe a block assembly: several spans, rings, or a
    ``--geometry`` file (which may hold one)."""
    return (getattr(args, "rings", None) is not None
            or getattr(args, "spans", None) not in (None, 1)
            or bool(getattr(args, "geometry", None)))


def shape_spec(args: argparse.Namespace):
    """The :class:`~archquake.geometry.StructureSpec` of the shape options alone (an arch of a
    shape, whatever else the command takes); a refused description names the options."""
    from ..geometry.spec import SHAPE_FIELDS, StructureSpec

    values = {name: getattr(args, name, None) for name in SHAPE_FIELDS}
    with naming_options():
        return StructureSpec(**{k: v for k, v in values.items() if v is not None})


SPANS_COMMANDS = ("limit", "rigid-blocks", "domain", "fragility", "record-fragility", "assess")
"""The commands that take several spans (``--spans`` of 2 or more)."""

RING_COMMANDS = ("limit", "rigid-blocks", "domain", "assess")
"""The commands that take an arch of several rings (``--rings``)."""


def structure_spec(args: argparse.Namespace, *, draw: bool = True, spans: bool = False):
    """The :class:`~archquake.geometry.StructureSpec` of the geometry, structure and (with
    ``draw``) irregularity options: each option given is the field of its name (``--pier-left``
    is ``pier_left``); a refused description names the options.

    Parameters
    ----------
    args : argparse.Namespace
    draw : bool
        Whether ``--epsilon`` and ``--seed`` draw one irregular arch (``False`` where they are
        the settings of a sample, or not options at all).
    spans : bool
        Whether the command takes several spans (:data:`SPANS_COMMANDS`); else ``--spans``
        other than 1 is refused by name.
    """
    from ..geometry.spec import (
        RING_FIELDS,
        SHAPE_FIELDS,
        SPAN_FIELDS,
        STRUCTURE_FIELDS,
        StructureSpec,
    )

    names = SHAPE_FIELDS + ("geometry", "units") + STRUCTURE_FIELDS + RING_FIELDS + ("density",)
    names += SPAN_FIELDS
    if not spans and (getattr(args, "spans", None) or 1) > 1:  # 0 or less: refused below
        raise ValueError(f"--spans {args.spans} builds several arches on shared piers: "
                         f"{', '.join(SPANS_COMMANDS[:-1])} and {SPANS_COMMANDS[-1]} analyse "
                         "them, this command does not")
    if draw:
        names += ("epsilon", "seed")
    values = {name: getattr(args, name, None) for name in names}
    if getattr(args, "min_pier_width", False):
        values["piers"] = None  # the piers are what --min-pier-width finds
    for name, metavar in _TEXT_FIELDS.items():
        if isinstance(values.get(name), str) and not values[name].strip():
            raise ValueError(f"{FIELD_OPTIONS[name]} was given an empty value, got "
                             f"{values[name]!r}: give {metavar} or leave the option out")
    with naming_options():
        return StructureSpec(**{k: v for k, v in values.items() if v is not None})


_TEXT_FIELDS = {"piers": "WIDTH,HEIGHT[,COURSES]", "pier_left": "WIDTH,HEIGHT[,COURSES]",
                "pier_right": "WIDTH,HEIGHT[,COURSES]", "fill_passive": "PHI,MOBILISATION"}
_TEXT_FIELDS["pier_middle"] = "WIDTH,HEIGHT[,COURSES]"
"""The structure options given as text, and what each takes: an empty one is refused (it was
silently absent)."""


def nominal_arch_from_args(args: argparse.Namespace):
    """The arch of the geometry options, before any irregular draw (on piers and under fill if
    the structure options say so)."""
    refuse_rings(args)
    with naming_options():
        return structure_spec(args, draw=False).nominal()


def sampled_structure_from_args(args: argparse.Namespace) -> dict:
    """What a sample of irregular structures is drawn around: ``{"nominal": arch}``, or for a
    bridge of several spans of one arch ``{"description": StructureSpec}`` (its members one
    irregular arch a span, :class:`archquake.studies.arch_sample.BridgeSample`); ``--epsilon``
    and ``--seed`` are the sample's."""
    refuse_rings(args)
    if (getattr(args, "spans", None) or 1) > 1:
        spec = structure_spec(args, draw=False, spans=True)  # no rings: a bridge of arches
        with naming_options():
            spec.nominal()  # refused now, naming the options
        return {"description": spec}
    return {"nominal": nominal_arch_from_args(args)}


def pier_from_option(option: str, text: str, *, blank_width: bool = False):
    """``(width, height, courses)`` of ``--piers WIDTH,HEIGHT[,COURSES]``, the width None when
    ``blank_width`` and left blank (:func:`archquake.geometry.spec.pier_field`); errors name
    the option."""
    from ..geometry.spec import pier_field

    field = option.removeprefix("--").replace("-", "_")
    with naming_options():
        return pier_field(field, text, blank_width=blank_width)


ASSEMBLY_COMMANDS = ("limit", "rigid-blocks", "domain")
"""The commands that take any block assembly (``--geometry`` with supports, or a drawing)."""


def arches_from_args(args: argparse.Namespace, *, assembly: bool = False, spans: bool = False):
    """``(nominal, arch)``: the arch before and after the optional irregular draw.
    ``assembly``: whether the command takes any block assembly (an arch of several rings too),
    else one is refused; ``spans``: whether it takes several spans (``--spans``), else they are
    refused."""
    if not assembly:
        refuse_rings(args)
    with naming_options():
        nominal, arch = structure_spec(args, spans=spans).arches()
    if not assembly and hasattr(arch, "interfaces"):
        raise ValueError(f"--geometry {args.geometry} describes a block assembly, not a chain of "
                         "voussoirs between two springings: "
                         f"{' and '.join(ASSEMBLY_COMMANDS)} analyse one, this command does not")
    return nominal, arch


def arch_from_args(args: argparse.Namespace, *, assembly: bool = False, spans: bool = False):
    """The arch described by the geometry options (after the irregular draw, if any);
    ``assembly``: whether the command takes any block assembly; ``spans``: several spans."""
    return arches_from_args(args, assembly=assembly, spans=spans)[1]


def drawn(args: argparse.Namespace) -> str:
    """How the command line names the irregular arch of ``--epsilon`` and ``--seed``."""
    return (f"the irregular arch drawn with --epsilon {args.epsilon:g} (seed "
            f"{DEFAULT_SEED if args.seed is None else args.seed})")


@contextlib.contextmanager
def analysing(args: argparse.Namespace):
    """Name the irregular arch (epsilon and seed) in an error of its analysis."""
    try:
        yield
    except ValueError as exc:
        if getattr(args, "epsilon", None) is None:
            raise
        raise ValueError(f"{drawn(args)}: {exc}") from exc


# ---------------------------------------------------------------------------------------------
# the four-link model
# ---------------------------------------------------------------------------------------------

RESTITUTION_METAVAR = "computed|link|measured|nominal|paper|elastic|VALUE"
"""The restitution models (:data:`archquake.fourlink.impact.RESTITUTION_MODELS`) as the
``--restitution`` options show them."""

RESTITUTION_HELP = (
    "'computed' from the momentum balance of the whole arch, 'link' from the paper's link-wise "
    "rule (Housner's rule for the post-impact springing link), 'measured' on the rigid-block "
    "model of the arch (the kinetic energy its blocks keep at the impact), 'nominal' = the "
    "nominal arch's computed value (the paper's practice for irregular arches), 'paper' = "
    "0.875, 'elastic' = 1, or a number in (0, 1]")
"""The restitution models, as the help of every ``--restitution`` option lists them."""


def add_restitution_option(parser: argparse.ArgumentParser, *, of_a_model: bool = False
                           ) -> None:
    """``--restitution``: the restitution model of the four-link model. ``of_a_model``: the
    command chooses its model (``--model``), so the option's default is None and
    :func:`model_spec_from_args` tells a value given from none (:data:`MODEL_OPTIONS`)."""
    parser.add_argument(
        "--restitution", default=None if of_a_model else DEFAULT_RESTITUTION,
        metavar=RESTITUTION_METAVAR,
        help=f"coefficient of restitution c_v at impacts: {RESTITUTION_HELP}"
             + (" (four-link model only)" if of_a_model else "")
             + f" (default: {DEFAULT_RESTITUTION})")


# ---------------------------------------------------------------------------------------------
# the rigid-block model
# ---------------------------------------------------------------------------------------------


def add_rigid_block_options(parser: argparse.ArgumentParser, *, time_step: bool = True,
                            of_a_model: bool = False) -> None:
    """``--friction`` and (unless ``time_step=False``) ``--time-step`` and ``--coarse-factor``
    of the rigid-block model. ``of_a_model``: the command chooses its model (``--model``), so
    the options' defaults are None and :func:`model_spec_from_args` tells a value given from
    none (:data:`MODEL_OPTIONS`)."""
    parser.add_argument("--friction", type=number,
                        default=None if of_a_model else DEFAULT_FRICTION, metavar="MU",
                        help="Coulomb friction coefficient of the joints of the rigid-block "
                             f"model, >= 0 (default: {DEFAULT_FRICTION})")
    if time_step:
        parser.add_argument("--time-step", type=number, default=None, metavar="H",
                            help="time step of the rigid-block model [s] (default: chosen from "
                                 "the structure, 1 ms x sqrt(t / 1.5 m) for a thickness t: "
                                 "1 ms for Oppenheim's arch)")
        parser.add_argument("--coarse-factor", type=int,
                            default=None if of_a_model else DEFAULT_COARSE_FACTOR, metavar="K",
                            help="take steps of K time steps while no contact starts or stops "
                                 "carrying an impulse, and every step where one does at the "
                                 "time step: 2 halves the time of a study at the accuracy of "
                                 "the time step (user guide, 'What a rigid-block study costs'); "
                                 f"1 takes every step at the time step; at most "
                                 f"{MAX_COARSE_FACTOR} (default: {DEFAULT_COARSE_FACTOR})")


# ---------------------------------------------------------------------------------------------
# which model, and how a study searches its grid
# ---------------------------------------------------------------------------------------------


def model_name(text: str) -> str:
    """The name of ``--model``, checked (:func:`archquake.models.check_model`)."""
    from ..models import check_model

    try:
        return check_model(text)
    except ValueError as exc:
        raise argparse.ArgumentTypeError(str(exc).replace("model must", "must")) from None


def add_model_options(parser: argparse.ArgumentParser, *, search: bool = True) -> None:
    """``--model`` (four-link or rigid-blocks) and, for a study, ``--search`` and ``--stride``
    (:mod:`archquake.studies.strategies`)."""
    group = parser.add_argument_group("model and search")
    group.add_argument("--model", type=model_name, default=None,
                       metavar="four-link|rigid-blocks",
                       help="the dynamic model: the paper's four-link mechanism, or every "
                            "voussoir a rigid block with Coulomb friction (the trusted one for "
                            f"short pulses) (default: {DEFAULT_MODEL}; rigid-blocks for a block "
                            "assembly, several spans, rings or a drawing of one, which has no "
                            "four-link model)")
    if search:
        add_search_options(group)


def add_search_options(group) -> None:
    """``--search`` and ``--stride``: how a study searches each line of its grid
    (:mod:`archquake.studies.strategies`)."""
    group.add_argument("--search", choices=SEARCHES, default=None,
                       help="how each line of the grid is searched: every point, a coarse scan "
                            "with bisection of every change, or that screened by the four-link "
                            "model with the stretches whose outcome is not smooth analysed "
                            "point by point (default: screened for the rigid blocks under "
                            "pulses, else exhaustive)")
    group.add_argument("--stride", type=int, default=None, metavar="N",
                       help=f"grid steps between the coarse points of bisection and screened "
                            f"(default: {DEFAULT_STRIDE} amplitudes, {DEFAULT_LEVEL_STRIDE} "
                            f"levels of a record-based study)")


ASSEMBLY_MODEL = "rigid-blocks"
"""The model of a block assembly (several spans, rings, a drawing of one): not one chain of
voussoirs between two springings, it has no four-link model."""


def structure_model_spec(args: argparse.Namespace, assembly: bool):
    """The :class:`~archquake.models.ModelSpec` of the options for a structure that is a block
    assembly or not: without ``--model``, an assembly takes the rigid blocks and the command
    says so on stderr; ``--model four-link`` with an assembly is refused by name."""
    if not assembly:
        return model_spec_from_args(args)
    if args.model not in (None, ASSEMBLY_MODEL):
        raise ValueError(f"a block assembly (several spans, rings, a drawing of one) is not one "
                         f"chain of voussoirs between two springings, so it has no {args.model} "
                         f"model: leave --model out or give --model {ASSEMBLY_MODEL}")
    if args.model is None:
        import sys

        print("archquake: note: a block assembly (several spans, rings, a drawing of one) has "
              "no four-link model: the rigid-block model analyses it", file=sys.stderr)
    return model_spec_from_args(args, ASSEMBLY_MODEL)


def model_spec_from_args(args: argparse.Namespace, name: str | None = None, *,
                         both: bool = False):
    """The :class:`~archquake.models.ModelSpec` of the model options a command has:
    ``--model`` (or ``name``, for a command of one model), ``--restitution``, ``--friction``,
    ``--time-step``, ``--coarse-factor`` (each option the dest of a field of the spec; one a
    command lacks takes the spec's default). A refused setting names its option
    (:func:`option_message`). ``both``: the command runs both models, so the options of the
    other model are its, not refused (each spec takes its own)."""
    from dataclasses import fields

    from ..models import ModelSpec

    values = {}
    for spec_field in fields(ModelSpec):
        dest = "model" if spec_field.name == "name" else spec_field.name
        if getattr(args, dest, None) is not None:
            values[spec_field.name] = getattr(args, dest)
    if name is not None:
        values["name"] = name
    chosen = values.get("name", ModelSpec.name)
    for dest, model in MODEL_OPTIONS.items():
        if dest in values and model != chosen and both:
            del values[dest]
        elif dest in values and model != chosen:
            option = f"--{dest.replace('_', '-')}"
            raise ValueError(f"{option} is a setting of the {model} model, and this study runs "
                             f"the {chosen} model, which has none: leave {option} out, or "
                             f"choose --model {model}")
    return ModelSpec(**values)


MODEL_OPTIONS = {"restitution": "four-link", "friction": "rigid-blocks",
                 "time_step": "rigid-blocks", "coarse_factor": "rigid-blocks"}
"""The model each model option sets. A command that chooses its model (``--model``) refuses the
options of the other one (:func:`model_spec_from_args`): accepted, they would be recorded in the
study without effect, and a resume without them refused."""


def structure_model(args: argparse.Namespace, spec):
    """The model ``spec`` (:func:`model_spec_from_args`) builds for the arch of the geometry
    options (with the nominal arch, for ``--restitution nominal``)."""
    nominal, arch = arches_from_args(args)
    with analysing(args):
        return spec.build(arch, nominal)


# ---------------------------------------------------------------------------------------------
# execution and output
# ---------------------------------------------------------------------------------------------


PATH_OPTIONS = ("out", "plot_dir", "output", "plot", "animate", "geometry", "record",
                "records", "export_nrml", "paths")
"""The options that name a file or a directory (:func:`check_paths`)."""


def check_paths(args: argparse.Namespace) -> None:
    """Refuse an empty file or directory name (``--out ""`` would be the current directory,
    ``--plot ""`` no file at all), naming the option."""
    for name in PATH_OPTIONS:
        value = getattr(args, name, None)
        values = value if isinstance(value, list) else [value]
        if any(isinstance(v, str) and not v.strip() for v in values):
            option = f"--{name.replace('_', '-')}" if name != "paths" else "PATH"
            raise ValueError(f"{option} must name a file or directory, got {value!r}")


def add_workers_option(parser, *, help: str) -> None:
    """``--workers N``: local worker processes (checked by :func:`check_workers` for every
    command)."""
    parser.add_argument("--workers", type=int, default=None, metavar="N", help=help)


def add_execution_options(parser: argparse.ArgumentParser) -> None:
    """``--workers`` or ``--scheduler``, and ``--resume``: how a study runs."""
    run = parser.add_mutually_exclusive_group()
    add_workers_option(run, help="local worker processes, at most 4 per CPU (default: 1, run "
                                 "in this process)")
    run.add_argument("--scheduler", metavar="tcp://HOST:PORT",
                     help="run the chunks on the Dask cluster of this scheduler")
    parser.add_argument("--resume", action="store_true",
                        help="continue the interrupted study in --out (same settings)")


def check_workers(workers: int | None) -> int | None:
    """The ``--workers`` value of any command, checked: None or 1 (run in this process) ->
    None. At most 4 processes per CPU of this machine: more would only share them."""
    cpus = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    most = 4 * (cpus or 1)
    if workers is not None and not 1 <= workers <= most:
        raise ValueError(f"--workers must be an integer in [1, {most}] (4 per CPU of this "
                         f"machine: more processes would only share them, each with its own "
                         f"memory), got {workers}")
    return None if workers in (None, 1) else workers


def add_samples_option(parser: argparse.ArgumentParser) -> None:
    """``--samples``: the number h of irregular arches of a study."""
    parser.add_argument("--samples", type=int, default=STUDY_SAMPLE_SIZE,
                        help=f"number h of irregular arches analysed dynamically, at most "
                             f"{MAX_SAMPLES} (default: %(default)s)")


def add_study_output_options(parser: argparse.ArgumentParser) -> None:
    """``--out``, how the study runs (``--workers``/``--scheduler``, ``--resume``),
    ``--plot-dir``, ``--no-progress`` and ``--json``."""
    parser.add_argument("--out", required=True, metavar="DIR",
                        help="study directory (new or empty, or an interrupted study with "
                             "--resume)")
    add_execution_options(parser)
    parser.add_argument("--plot-dir", metavar="DIR",
                        help="write the figures of the study as PNG files here: the "
                             "fragility curves and surface, or with records the fragility "
                             "curve and the incremental view")
    add_progress_option(parser, "no progress bars")
    add_json_option(parser, "print the summary as JSON")


def add_json_option(parser, help: str = "machine-readable output") -> None:
    """``--json``: machine-readable output."""
    parser.add_argument("--json", action="store_true", help=help)


def add_plot_option(parser, help: str) -> None:
    """``--plot FILE.png``: a figure."""
    parser.add_argument("--plot", metavar="FILE.png", help=help)


def add_model_check_option(parser) -> None:
    """``--no-model-check``: skip the check of the four-link numbers against the rigid-block
    model (:func:`model_check`)."""
    parser.add_argument("--no-model-check", action="store_true",
                        help="skip the check of the four-link failure accelerations against "
                             "the rigid-block model (both under Oppenheim's pulse at up to 3 "
                             "of the durations, to 0.01 g: about a second); the output says "
                             "it was skipped")


def model_check(args: argparse.Namespace, structure, four_link, durations) -> dict:
    """Check the four-link model's failure accelerations of ``structure`` against the trusted
    rigid-block model at a few of ``durations``
    (:func:`archquake.studies.comparison.agreement_probe`), unless ``--no-model-check``.
    ``four_link`` is the model, or a call that builds it. A check that cannot be made (a model
    refused, a pulse the rigid blocks' time step cannot resolve) is said as undecided.

    Returns
    -------
    dict
        ``skipped`` (bool), ``lines`` (the warnings to print: the durations beyond the band or
        undecided, or that the check was skipped), ``probe`` (the JSON-ready probe, None when
        skipped) and ``value`` (the :class:`~archquake.studies.comparison.AgreementProbe`).
    """
    if getattr(args, "no_model_check", False):
        return {"skipped": True, "probe": None, "value": None,
                "lines": ["four-link values not checked against the rigid-block model "
                          "(--no-model-check)"]}
    from ..studies.comparison import agreement_probe, probe_durations

    probed = probe_durations(durations)
    try:
        if callable(four_link):  # built here, so that a model that cannot be is said
            four_link = four_link()
        probe = agreement_probe(structure, probed, four_link=four_link,
                                direction=getattr(args, "direction", "l"))
    except ValueError as exc:  # e.g. a pulse the rigid blocks' time step cannot resolve
        return {"skipped": False, "probe": {"error": str(exc)}, "value": None,
                "lines": [f"model check undecided: the four-link values could not be checked "
                          f"against the rigid-block model: {exc}"]}
    lines = probe.messages()
    if not lines:
        lines = ["four-link values checked against the rigid-block model at t_p = "
                 + ", ".join(f"{r.duration:g}" for r in probe.rows)
                 + f" s: within {100 * probe.band:g} %"]
    return {"skipped": False, "probe": probe.to_dict(), "value": probe, "lines": lines}


def model_check_of_row(check: dict, duration: float) -> dict:
    """What a JSON row of one duration carries of :func:`model_check`: ``skipped``,
    ``disagrees`` and ``undecided`` (anywhere probed), ``band`` and ``probed`` (the probe's row
    at this duration, None when not probed there)."""
    if check["skipped"]:
        return {"skipped": True}
    probe = check["value"]
    if probe is None:
        return {"skipped": False, **check["probe"]}
    row = probe.row_at(duration)
    return {"skipped": False, "disagrees": probe.disagrees, "undecided": probe.undecided,
            "band": probe.band, "probed": None if row is None else row.to_dict()}


def model_check_note(check: dict, duration: float) -> str:
    """The note beside a four-link failure acceleration at ``duration`` ("" where it was not
    probed or agrees)."""
    if check is None:
        return ""
    probe = check["value"]
    row = None if probe is None else probe.row_at(duration)
    if row is None:
        return ""
    if row.beyond:
        return (f"  [rigid blocks (trusted): {row.rigid_block:.2f} g; four-link off by "
                f"{100 * row.difference:+.0f} %]")
    if row.undecided:
        return "  [model check undecided]"
    return ""


def add_progress_option(parser, help: str = "no progress bar on stderr") -> None:
    """``--no-progress``."""
    parser.add_argument("--no-progress", action="store_true", help=help)


# ---------------------------------------------------------------------------------------------
# suites of records
# ---------------------------------------------------------------------------------------------

BUILTIN_SUITE_NAMES = ("fema-p695-far-field", "fema-p695-near-field-pulse",
                       "fema-p695-near-field-no-pulse")
"""The built-in record suites (the keys of :data:`archquake.ground_motion.BUILTIN_SUITES`, which
a test compares), named here so that building the options imports nothing heavy."""


def add_suite_option(group, what: str = "instead of record files") -> None:
    """``--suite NAME``: a built-in suite of real records (read by :func:`suite_from_args`)."""
    group.add_argument("--suite", metavar="NAME",
                       help=f"a built-in suite of real records {what}: "
                            f"{', '.join(BUILTIN_SUITE_NAMES)} (the FEMA P695 record sets, "
                            f"both components of every record; needs pip install "
                            f'"archquake[records]")')


def suite_from_args(args: argparse.Namespace, paths: str = "records"):
    """The :class:`~archquake.ground_motion.RecordSuite` of ``--records PATH...`` or ``--suite
    NAME`` (None when neither is given).

    Parameters
    ----------
    args : argparse.Namespace
    paths : str
        The option of the record files (``records``).

    Returns
    -------
    RecordSuite or None

    Raises
    ------
    ValueError
        For both options, an unknown suite (naming ``--suite``), the ``records`` extra missing
        (saying how to install it) or a bad record file.
    """
    from ..ground_motion import RecordSuite

    files, name = getattr(args, paths, None), getattr(args, "suite", None)
    if files and name:
        raise ValueError(f"--{paths.replace('_', '-')} and --suite: give record files or a "
                         f"built-in suite, not both")
    if name:
        try:
            return RecordSuite.from_builtin(name)
        except ImportError as exc:
            raise ValueError(f"--suite {name}: {exc}") from None
        except ValueError as exc:
            raise ValueError(f"--suite: {exc}") from None
    if files:
        return RecordSuite.from_paths(files)
    return None


# ---------------------------------------------------------------------------------------------
# the site's spectrum, and records compatible with it
# ---------------------------------------------------------------------------------------------

def _pair(option: str):
    """The type of an option ``LOW,HIGH``: two numbers."""
    def parse(text: str) -> tuple[float, float]:
        parts = text.split(",")
        try:
            values = tuple(number(p) for p in parts)
        except ValueError:
            values = ()
        if len(values) != 2:
            raise argparse.ArgumentTypeError(f"{option} takes two numbers LOW,HIGH, got "
                                             f"{text!r}")
        return values

    return parse


def add_dynamic_route_options(parser: argparse.ArgumentParser) -> None:
    """``--records`` or ``--suite``, ``--records-count``, ``--period-range``,
    ``--factor-range`` and ``--compatibility``: records selected from a suite and scaled to be
    compatible with the site's spectrum (read by :func:`compatible_selection_from_args`)."""
    group = parser.add_argument_group("records compatible with the site's spectrum")
    group.add_argument("--records", nargs="+", metavar="PATH",
                       help="the candidate records: files and folders of record files")
    add_suite_option(group, "as the candidate records")
    group.add_argument("--records-count", type=int, default=DEFAULT_RECORD_COUNT, metavar="N",
                       help="records to select, >= 3: with 7 or more the effects are their "
                            "mean, with 3 to 6 the most unfavourable one (NTC 2018 §7.3.5) "
                            "(default: %(default)s)")
    group.add_argument("--period-range", type=_pair("--period-range"),
                       default=DEFAULT_PERIOD_RANGE, metavar="TMIN,TMAX",
                       help="periods over which the records' mean spectrum must match the "
                            "site's [s]; a rocking arch has no elastic period, so the code's "
                            "range is kept unless widened (default: "
                            f"{DEFAULT_PERIOD_RANGE[0]:g},{DEFAULT_PERIOD_RANGE[1]:g})")
    group.add_argument("--factor-range", type=_pair("--factor-range"),
                       default=DEFAULT_FACTOR_RANGE, metavar="LOW,HIGH",
                       help="range of every record's scale factor [-] (default: "
                            f"{DEFAULT_FACTOR_RANGE[0]:g},{DEFAULT_FACTOR_RANGE[1]:g})")
    group.add_argument("--compatibility", choices=COMPATIBILITY_RULES, default=None,
                       help="the rule: ntc2018, the mean within -10%% and +30%% of the "
                            "site's spectrum (§3.2.3.6); ec8, not below 90%% and its mean PGA "
                            "not below the site's (EN 1998-1 §3.2.3.1.2) (default: ec8 for "
                            "--code ec8, else ntc2018)")


def compatible_selection_from_args(args: argparse.Namespace, target, way: str = "ntc2018"):
    """The records of :func:`add_dynamic_route_options` selected and scaled for ``target``, the
    spectrum given the :func:`site_way` ``way`` (whose code's rule applies unless
    ``--compatibility`` says otherwise;
    :func:`archquake.site.compatible_records.select_compatible_records`)."""
    from ..site.compatible_records import select_compatible_records

    suite = suite_from_args(args)
    if suite is None:
        raise ValueError("give the candidate records: --records PATH... or --suite NAME")
    rule = args.compatibility or ("ec8" if way == "ec8" else COMPATIBILITY_RULES[0])
    return select_compatible_records(
        suite, target, count=args.records_count, period_range=args.period_range,
        rule=rule, factor_range=args.factor_range)


# ---------------------------------------------------------------------------------------------
# one ground motion
# ---------------------------------------------------------------------------------------------

def add_motion_options(parser: argparse.ArgumentParser) -> None:
    """Options that define one ground motion (read by :func:`motion_from_args`)."""
    m = parser.add_argument_group("ground motion")
    # no argparse defaults (the description applies them), so that an option given where it
    # does not apply (with --record, with --phi0) can be refused instead of ignored
    m.add_argument("--motion", choices=ANALYTIC_GROUND_MOTIONS + ("record", "stochastic"),
                   default=None, metavar="NAME",
                   help="oppenheim (a for t_p then -a/2 for 2 t_p), rectangular, sine, "
                        "harmonic, ricker, ricker-antisymmetric, cycloidal-a, cycloidal-b, "
                        "cycloidal-c, mavroeidis-papageorgiou, record (--record FILE) or "
                        f"stochastic (Rezaeian-Der Kiureghian model) (default: {DEFAULT_MOTION})")
    m.add_argument("--amplitude", type=number, default=None,
                   help=f"signed peak acceleration of a pulse [g], within "
                        f"+-{MAX_ACCELERATION_G:g}; -1 starts Mech-l "
                        f"(default: {DEFAULT_PULSE[0]})")
    m.add_argument("--duration", type=number, default=None,
                   help="time scale of a pulse [s]: its duration t_p (oppenheim, rectangular) "
                        f"or its period (the others) (default: {DEFAULT_PULSE[1]})")
    m.add_argument("--param", action="append", default=[], metavar="NAME=VALUE",
                   help="a parameter of the chosen motion (repeatable): cycles (harmonic), n "
                        "(cycloidal-c), gamma and phase [rad] (mavroeidis-papageorgiou), seed "
                        "and the model parameters of stochastic (arias_intensity [m/s], "
                        "significant_duration [s], midpoint_time [s], filter_frequency [Hz], "
                        "filter_frequency_rate [Hz/s], filter_damping, high_pass_frequency "
                        "[Hz], dt [s], duration [s])")
    m.add_argument("--cycles", type=number, default=None,
                   help=f"cycles of the harmonic motion, at most {MAX_CYCLES} (same as --param "
                        f"cycles=N)")
    m.add_argument("--record", metavar="FILE",
                   help="accelerogram: two-column CSV (time [s], acceleration [g]), PEER NGA "
                        ".AT2 or ESM ASCII (implies --motion record); with --suite the name of "
                        "a ground motion of the suite")
    add_suite_option(m, "from which --record names a ground motion")
    m.add_argument("--scale-to", type=number, default=None, metavar="PGA",
                   help="scale the record or stochastic motion to this peak ground "
                        "acceleration [g]")
    m.add_argument("--reverse", action="store_true",
                   help="apply the motion with its sign flipped (the other polarity, -xg''(t))")


def motion_parameters(args: argparse.Namespace) -> dict[str, str] | None:
    """``--param NAME=VALUE`` as ``{name: value text}`` (None when not given): the values and
    which motion takes them are checked by the motion's description."""
    if not args.param:
        return None
    params: dict[str, str] = {}
    for item in args.param:
        name, sep, text = item.partition("=")
        name = name.strip()
        if not sep or not name:
            raise ValueError(f"--param must be NAME=VALUE, got {item!r}")
        if name in params:
            raise ValueError(f"--param {name} is given twice")
        params[name] = text
    return params


def motion_spec(args: argparse.Namespace):
    """The :class:`~archquake.ground_motion.MotionSpec` of the motion options: each option
    given is the field of its name, ``--param`` is ``params`` and ``--record`` with ``--suite``
    is ``suite_record``; a refused description names the options."""
    from ..ground_motion.spec import MotionSpec

    suite = getattr(args, "suite", None)
    values = {"motion": args.motion, "amplitude": args.amplitude, "duration": args.duration,
              "cycles": args.cycles, "params": motion_parameters(args), "suite": suite,
              "suite_record" if suite else "record": args.record, "scale_to": args.scale_to,
              "reverse": args.reverse or None}
    with naming_options():
        return MotionSpec(**{k: v for k, v in values.items() if v is not None})


def motion_from_args(args: argparse.Namespace):
    """The ground motion of the motion options (reversed with ``--reverse``)."""
    spec = motion_spec(args)
    with naming_options():
        return spec.build()


# ---------------------------------------------------------------------------------------------
# the site: its elastic spectrum (archquake.site.spectra)
# ---------------------------------------------------------------------------------------------

CODE_OPTIONS = {
    "ntc2018": ("ag", "f0", "tc_star", "topography", "topography_ratio", "soil", "damping"),
    "ec8": ("agr", "type", "importance", "soil", "damping"),
    "user": ("file",),
    "site": ("site", "limit_state", "nominal_life", "use_class", "topography",
             "topography_ratio", "soil", "damping"),
}
"""The options each way of giving a site's spectrum takes (the others are refused by name)."""

PARAMETER_OPTIONS = {
    "ag": "--ag", "f0": "--f0", "tc_star": "--tc-star", "soil": "--soil",
    "topography": "--topography", "topography_ratio": "--topography-ratio",
    "damping": "--damping", "agr": "--agr", "spectrum_type": "--type",
    "importance": "--importance", "limit_state": "--limit-state",
    "nominal_life": "--nominal-life", "use_class": "--use-class",
}
"""The option of each parameter of :mod:`archquake.site.spectra`, for its messages."""



def add_site_options(parser: argparse.ArgumentParser) -> None:
    """The site's elastic spectrum: ``--code ntc2018|ec8|user`` with its parameters, or
    ``--site FILE`` (the NTC 2018 national grid) at ``--limit-state``
    (:mod:`archquake.site.spectra`)."""
    parser.add_argument("--code", default=None, metavar="ntc2018|ec8|user",
                        help="the code of the spectrum (default: ntc2018 with --site)")
    ntc = parser.add_argument_group("NTC 2018 (--code ntc2018, or --site)")
    ntc.add_argument("--ag", type=number, default=None, metavar="G",
                     help="ground acceleration on rock a_g [g]")
    ntc.add_argument("--f0", type=number, default=None, metavar="F",
                     help="maximum spectral amplification F0 [-]")
    ntc.add_argument("--tc-star", type=number, default=None, metavar="T",
                     help="Tc* [s]")
    ntc.add_argument("--topography", default=None, metavar="T1|T2|T3|T4",
                     help="topographic category, Table 3.2.V (default: T1)")
    ntc.add_argument("--topography-ratio", type=number, default=None, metavar="R",
                     help="height of the site over that of the slope, in [0, 1]: S_T falls "
                          "linearly from the top (1, the default) to 1 at the base (0)")
    ec8 = parser.add_argument_group("EN 1998-1 (--code ec8)")
    ec8.add_argument("--agr", type=number, default=None, metavar="G",
                     help="reference peak ground acceleration on ground A a_gR [g]")
    ec8.add_argument("--type", default=None, metavar="1|2",
                     help="spectrum type: 1 (Table 3.2) or 2 (Table 3.3) (default: 1)")
    ec8.add_argument("--importance", type=number, default=None, metavar="GAMMA",
                     help="importance factor gamma_I [-] (default: 1.0)")
    both = parser.add_argument_group("both codes")
    both.add_argument("--soil", default=None, metavar="A|B|C|D|E",
                      help="soil (ground) category (default: A)")
    both.add_argument("--damping", type=number, default=None, metavar="XI",
                      help="viscous damping [%%], in (0, 30] (default: 5)")
    user = parser.add_argument_group("a user's spectrum (--code user)")
    user.add_argument("--file", default=None, metavar="PATH",
                      help="two columns: period [s], Se [g]")
    site = parser.add_argument_group("the NTC 2018 hazard of a site (--site)")
    site.add_argument("--site", default=None, metavar="FILE",
                      help="CSV with columns TR [years], ag [g], F0, Tc* [s] (header names "
                           "tr, ag, f0, tc_star or tc*)")
    site.add_argument("--limit-state", default=None, metavar="SLO|SLD|SLV|SLC",
                      help="limit state (P_VR 81, 63, 10, 5 %%)")
    site.add_argument("--nominal-life", type=number, default=None, metavar="YEARS",
                      help="nominal life V_N [years] (default: 50)")
    site.add_argument("--use-class", default=None, metavar="I|II|III|IV",
                      help="use class, C_U = 0.7, 1.0, 1.5, 2.0 (default: II)")


def site_way(args: argparse.Namespace, *, limit_state: bool = False) -> str:
    """Which spectrum the options ask for: a code's, a user's, or a site's (``limit_state``:
    ``--limit-state`` names the limit state of a code's spectrum too, as for the check)."""
    code = None if args.code is None else args.code.strip().lower()
    if args.site is not None:
        if code not in (None, "ntc2018"):
            raise ValueError(f"--site gives an NTC 2018 spectrum, not --code {args.code}")
        way = "site"
    elif code is None:
        raise ValueError("give --code ntc2018, ec8 or user, or --site FILE")
    elif code not in ("ntc2018", "ec8", "user"):
        raise ValueError(f"--code must be ntc2018, ec8 or user, got {args.code!r}")
    else:
        way = code
    names = {n for ns in CODE_OPTIONS.values() for n in ns}
    foreign = given(args, *sorted(names - set(CODE_OPTIONS[way])
                                  - ({"limit_state"} if limit_state else set())))
    if foreign:
        what = "--site" if way == "site" else f"--code {way}"
        verb = "does" if len(foreign) == 1 else "do"
        raise ValueError(f"{', '.join(foreign)} {verb} not apply to {what}")
    return way


def site_option_message(exc: ValueError) -> ValueError:
    """The library's message naming a parameter, naming its option instead."""
    text = str(exc)
    if text.startswith("ag = importance * agr "):
        return ValueError("a_g = --importance x --agr" + text[len("ag = importance * agr"):])
    if text.startswith("period "):
        return ValueError(f"--periods: {text}")
    for name, option in sorted(PARAMETER_OPTIONS.items(), key=lambda kv: -len(kv[0])):
        if text.startswith(name + " "):
            return ValueError(option + text[len(name):])
    return exc


def _site_required(args: argparse.Namespace, *names: str) -> None:
    missing = [f"--{n.replace('_', '-')}" for n in names if getattr(args, n) is None]
    if missing:
        raise ValueError(f"{', '.join(missing)} must be given")


def site_spectrum(args: argparse.Namespace, way: str, limit_state: str | None = None):
    """The spectrum of the options (of ``limit_state`` for ``--site``, default
    ``--limit-state``), and what the site gave (or None)."""
    from ..site import spectra

    soil = "A" if args.soil is None else args.soil
    damping = 5.0 if args.damping is None else args.damping
    topography = "T1" if args.topography is None else args.topography
    if way == "ntc2018":
        _site_required(args, "ag", "f0", "tc_star")
        return spectra.ntc2018_spectrum(args.ag, args.f0, args.tc_star, soil, topography,
                                        damping, topography_ratio=args.topography_ratio), None
    if way == "ec8":
        _site_required(args, "agr")
        kind = 1 if args.type is None else args.type.strip()
        if kind not in (1, "1", "2"):
            raise ValueError(f"--type must be 1 or 2, got {args.type!r}")
        return spectra.ec8_spectrum(args.agr, int(kind), soil,
                                    1.0 if args.importance is None else args.importance,
                                    damping), None
    if way == "user":
        _site_required(args, "file")
        try:
            return spectra.read_spectrum(args.file), None
        except ValueError as exc:
            raise ValueError(f"--file: {exc}") from None
    limit_state = args.limit_state if limit_state is None else limit_state
    if limit_state is None:
        _site_required(args, "limit_state")
    try:
        hazard = spectra.read_ntc_site(args.site)
    except ValueError as exc:
        raise ValueError(f"--site: {exc}") from None
    life = 50.0 if args.nominal_life is None else args.nominal_life
    use = "II" if args.use_class is None else args.use_class
    tr = spectra.return_period(limit_state, life, use)
    try:
        ag, f0, tc_star = hazard.parameters(tr)
    except ValueError as exc:
        raise ValueError(f"--limit-state {limit_state} with --nominal-life {life:g} and "
                         f"--use-class {use} gives T_R = {tr:.1f} years, outside the table of "
                         f"--site {hazard.name} ({hazard.return_periods[0]:g} to "
                         f"{hazard.return_periods[-1]:g} years): {exc}") from None
    spectrum = spectra.ntc2018_spectrum(ag, f0, tc_star, soil, topography, damping,
                                        topography_ratio=args.topography_ratio)
    site = {"file": hazard.name, "limit_state": limit_state.strip().upper(),
            "nominal_life": life, "use_class": use.strip().upper(), "return_period": tr,
            "ag": ag, "f0": f0, "tc_star": tc_star}
    return spectrum, site


SITE_FIELD_OPTIONS = {"grid": "--site", "spectrum_type": "--type", "file": "--file"}
"""The option of each field of :class:`~archquake.site.spec.SiteSpec` not named ``--field``."""


def site_spec(args: argparse.Namespace):
    """The :class:`~archquake.site.spec.SiteSpec` of the site options (and the knowledge
    options, where the command has them); a refusal names the option."""
    from ..site.spec import SiteSpec

    site_way(args, limit_state=True)
    code = None if args.code is None else args.code.strip().lower()
    kind = None if args.type is None else args.type.strip()
    if kind is not None and kind not in ("1", "2"):
        raise ValueError(f"--type must be 1 or 2, got {args.type!r}")
    fields = {
        "code": "ntc2018" if code is None and args.site is None else code,
        "grid": args.site, "ag": args.ag, "f0": args.f0, "tc_star": args.tc_star,
        "soil": args.soil, "topography": args.topography,
        "topography_ratio": args.topography_ratio, "damping": args.damping, "agr": args.agr,
        "spectrum_type": None if kind is None else int(kind), "importance": args.importance,
        "file": args.file, "limit_state": args.limit_state,
        "nominal_life": args.nominal_life, "use_class": args.use_class,
        "knowledge_level": getattr(args, "knowledge_level", None),
        "confidence_factor": getattr(args, "confidence_factor", None)}
    try:
        return SiteSpec(**fields)
    except ValueError as exc:
        raise _site_field_message(exc) from None


def _site_field_message(exc: ValueError) -> ValueError:
    text = str(exc)
    name = text.split(" ", 1)[0].rstrip(":")
    option = SITE_FIELD_OPTIONS.get(name, f"--{name.replace('_', '-')}")
    if name.isidentifier() and name.islower():
        text = option + text[len(name):]
    return site_option_message(ValueError(text))


def site_actions(args: argparse.Namespace) -> list:
    """The site's actions of the code check (:meth:`~archquake.site.spec.SiteSpec.actions`):
    with ``--site``, SLV and SLC (or the ``--limit-state`` given); with a spectrum
    (``--code``), that spectrum as the action of ``--limit-state`` (default SLV)."""
    spec = site_spec(args)
    try:
        return spec.actions()
    except ValueError as exc:
        raise _site_field_message(exc) from None
    except OSError as exc:  # a site or spectrum file that cannot be read
        option = "--site" if spec.grid is not None else "--file"
        raise ValueError(f"{option}: {exc.strerror or exc}: {exc.filename}") from None
