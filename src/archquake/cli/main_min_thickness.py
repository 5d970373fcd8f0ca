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
    options.add_json_option(parser)


def run(args: argparse.Namespace) -> int:
    """The minimum thickness of the arch of the shape options."""
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
