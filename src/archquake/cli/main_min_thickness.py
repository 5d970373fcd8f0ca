"""``archquake min-thickness``: the thinnest arch of a shape that stands under its own weight;
:func:`archquake.limit_analysis.min_thickness` and
:func:`archquake.limit_analysis.shaped_min_thickness`."""

from __future__ import annotations

import argparse
import math

from . import options
from .output import print_json

DESCRIPTION = (
    "The minimum thickness under its own weight of the arch of the shape options: its "
    "centreline and voussoirs kept, the thickness scaled until a line of thrust just fits; and "
    "its ratio to the radius (circular arches) or to the span.")


def configure(parser: argparse.ArgumentParser) -> None:
    """The options of ``archquake min-thickness``."""
    parser.description = DESCRIPTION
    group = parser.add_argument_group("arch shape (defaults: Oppenheim's arch)")
    options.add_shape_options(group, thickness=False)
    parser.add_argument("--friction", type=options.number, default=None, metavar="MU",
                        help="Coulomb friction coefficient of the joints, >= 0: the thrust line "
                             "must also lie within every joint's friction cone; below a "
                             "critical friction no thickness suffices, which is printed as the "
                             "verdict (default: none, nothing slides)")
    from ..defaults import RING_BONDS

    rings = parser.add_argument_group("rings (default: one ring, the arch)")
    rings.add_argument("--rings", type=int, metavar="N",
                       help="the arch in N concentric rings of equal thickness that can "
                            "separate (a multi-ring brick arch; not a pointed one), all scaled "
                            "together: the thinnest whole arch that stands")
    rings.add_argument("--ring-bond", choices=RING_BONDS,
                       help="joints of adjacent rings on the same radial lines (aligned) or "
                            "offset by half a voussoir (staggered) (default: aligned)")
    rings.add_argument("--ring-friction", type=options.number, metavar="MU",
                       help="Coulomb friction coefficient of the interfaces between rings, "
                            ">= 0 (default: they open but do not slide)")
    options.add_json_option(parser)


def run(args: argparse.Namespace) -> int:
    """The minimum thickness of the arch of the shape options."""
    if args.rings is not None or args.ring_bond is not None or args.ring_friction is not None:
        return _rings(args)
    from ..errors import NoThicknessError
    from ..geometry import shaped_arch
    from ..limit_analysis import min_thickness, shaped_min_thickness
    from ..limit_analysis.friction import check_friction

    with options.naming_options():
        shape, kwargs = options.shape_spec(args).shape_arguments()
    friction = None if args.friction is None else check_friction(args.friction)
    try:
        if shape is None:
            thickness = min_thickness(kwargs["radius"], kwargs["embrace"], kwargs["voussoirs"],
                                      friction=friction)
        else:
            thickness = shaped_min_thickness(shape, friction=friction, **kwargs)
    except NoThicknessError as exc:
        if friction is None:
            raise
        if args.json:
            print_json({"min_thickness": None, "ratio": None, "friction": friction,
                        "verdict": str(exc)})
        else:
            print(f"no minimum thickness: {exc}")
        return 0
    if shape is None:
        scale, of = kwargs["radius"], "radius"
        what = (f"circular arch, R = {kwargs['radius']:g} m, alpha = "
                f"{math.degrees(kwargs['embrace']):g} deg, n = {kwargs['voussoirs']}")
    else:
        line = shaped_arch(shape, thickness=thickness, **kwargs).centreline
        scale, of = (line.radius, "radius") if shape == "circular" else (line.span, "span")
        what = (f"{shape} arch, span = {line.span:g} m, rise = {line.rise:g} m, n = "
                f"{kwargs['voussoirs']}, {kwargs['faces']} faces")
    if friction is not None:
        what += f"; friction {friction:g} at the joints"
    if args.json:
        out = {"min_thickness": thickness, "ratio": thickness / scale, "ratio_of": of}
        if friction is not None:
            out["friction"] = friction
        print_json(out)
    else:
        symbol = "R" if of == "radius" else "span"
        print(f"minimum thickness under self-weight: t_min = {thickness:.6g} m "
              f"(t_min/{symbol} = {thickness / scale:.6g}; {what})")
    return 0


def _rings(args: argparse.Namespace) -> int:
    """The minimum thickness of the arch of the shape options in rings, all scaled together
    (:func:`archquake.limit_analysis.assembly_min_thickness` of
    :func:`archquake.geometry.multi_ring`)."""
    from ..geometry import multi_ring
    from ..geometry.rings import ARC_ERROR
    from ..geometry.spec import StructureSpec
    from ..limit_analysis import assembly_min_thickness, min_thickness, shaped_min_thickness

    if args.rings is None:
        raise ValueError("--ring-bond and --ring-friction need --rings N")
    if args.friction is not None:
        raise ValueError("--friction: with --rings the interfaces between rings take "
                         "--ring-friction; the voussoir joints do not slide")
    with options.naming_options():
        spec = options.shape_spec(args)
        StructureSpec(**{**spec.to_dict(), "rings": args.rings,
                         "ring_bond": args.ring_bond, "ring_friction": args.ring_friction})
        shape, kwargs = spec.shape_arguments()
    common = {"rings": args.rings, "voussoirs": kwargs["voussoirs"],
              "bond": args.ring_bond or "aligned", "ring_friction": args.ring_friction}
    size = kwargs.get("radius") or min(kwargs["span"], kwargs["rise"])
    # one drawing of the curved faces for every thickness tried: chords of sagitta at most
    # ARC_ERROR x 0.1 of the radius (or of the smaller of span and rise)
    common["arc_error"] = ARC_ERROR * 0.1 * size
    if "radius" in kwargs:  # a circle by its radius and embrace
        scale, of = kwargs["radius"], "radius"

        def build(t):
            return multi_ring(kwargs["radius"], kwargs["embrace"], t, **common)
        what = (f"circular arch, R = {kwargs['radius']:g} m, alpha = "
                f"{math.degrees(kwargs['embrace']):g} deg")
    else:
        scale, of = kwargs["span"], "span"
        if shape == "circular":  # the ratio to the radius, (s^2 / 4 + r^2) / (2 r)
            scale, of = (kwargs["span"] ** 2 / 4 + kwargs["rise"] ** 2) / (
                2 * kwargs["rise"]), "radius"

        def build(t):
            return multi_ring(shape=shape, span=kwargs["span"], rise=kwargs["rise"],
                              thickness=t, **common)
        what = f"{shape} arch, span = {kwargs['span']:g} m, rise = {kwargs['rise']:g} m"
    what += (f", n = {kwargs['voussoirs']}, {args.rings} {common['bond']} rings, ring "
             "interfaces " + ("that do not slide" if args.ring_friction is None
                              else f"with friction {args.ring_friction:g}"))
    from ..errors import NoThicknessError

    try:
        # every state of the arch of rings is one of the one-ring arch (its ring interfaces
        # are joints within its voussoirs): no thinner than the one ring's (the chain
        # program's), searched from a little below it (the chords' areas differ)
        if "radius" in kwargs:
            one = min_thickness(kwargs["radius"], kwargs["embrace"], kwargs["voussoirs"])
        else:
            one = shaped_min_thickness(shape, **kwargs)
        thickness = assembly_min_thickness(build, 0.9 * one, 0.5 * size)
    except NoThicknessError as exc:
        if args.json:
            print_json({"min_thickness": None, "ratio": None, "rings": args.rings,
                        "verdict": str(exc)})
        else:
            print(f"no minimum thickness: {exc}")
        return 0
    if args.json:
        print_json({"min_thickness": thickness, "ratio": thickness / scale, "ratio_of": of,
                    "rings": args.rings, "ring_bond": common["bond"],
                    "ring_friction": args.ring_friction})
    else:
        symbol = "R" if of == "radius" else "span"
        print(f"minimum thickness under self-weight: t_min = {thickness:.6g} m "
              f"(t_min/{symbol} = {thickness / scale:.6g}; {what})")
    return 0
