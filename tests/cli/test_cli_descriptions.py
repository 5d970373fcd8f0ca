"""The command line's geometry and motion options are the fields of the library's descriptions:
the options build the structure and the motion the descriptions build from the same values, and
a refused description names the options, each field by its own."""

import numpy as np
import pytest

from archquake.cli import build_parser, main
from archquake.cli.options import FIELD_OPTIONS, arches_from_args, motion_from_args
from archquake.geometry import StructureSpec
from archquake.ground_motion import MotionSpec
from archquake.ground_motion.spec import STOCHASTIC_PARAMETERS


def parsed(command: str, *argv: str):
    return build_parser([command]).parse_args([command, *argv])


@pytest.mark.parametrize("argv, fields", [
    ([], {}),
    (["--thickness", "1.2", "--voussoirs", "9", "--embrace", "150"],
     {"thickness": 1.2, "voussoirs": 9, "embrace": 150}),
    (["--shape", "pointed", "--span", "10", "--rise", "7", "--thickness", "0.6", "--faces",
      "flat"], {"shape": "pointed", "span": 10, "rise": 7, "thickness": 0.6, "faces": "flat"}),
    (["--pier-left", "3,6", "--pier-right", "4,5,2", "--fill-cover", "0.4", "--fill-density",
      "1600", "--fill-inertia", "extrados", "--fill-passive", "30,0.5", "--density", "2400"],
     {"pier_left": (3, 6, 1), "pier_right": (4, 5, 2), "fill_cover": 0.4,
      "fill_density": 1600, "fill_inertia": "extrados", "fill_passive": (30, 0.5),
      "density": 2400}),
    (["--epsilon", "0.15", "--seed", "4", "--piers", "2,4,2"],
     {"epsilon": 0.15, "seed": 4, "piers": (2, 4, 2)}),
], ids=["oppenheim", "circular", "pointed-flat", "unequal-piers-fill", "irregular-on-piers"])
def test_the_options_build_the_structure_of_the_description(argv, fields):
    nominal, structure = arches_from_args(parsed("limit", *argv))
    expected_nominal, expected = StructureSpec(**fields).arches()
    for built, wanted in ((nominal, expected_nominal), (structure, expected)):
        assert type(built) is type(wanted)
        for name in ("joints", "masses", "centroids", "inertias"):
            assert np.array_equal(getattr(built, name), getattr(wanted, name)), name


@pytest.mark.parametrize("argv, fields", [
    ([], {}),
    (["--motion", "harmonic", "--amplitude=-0.4", "--duration", "0.5", "--param", "cycles=2",
      "--reverse"], {"motion": "harmonic", "amplitude": -0.4, "duration": 0.5,
                     "params": {"cycles": 2}, "reverse": True}),
    (["--motion", "harmonic", "--cycles", "3"], {"motion": "harmonic", "cycles": 3}),
    (["--motion", "stochastic", "--param", "seed=4", "--scale-to", "0.5"],
     {"motion": "stochastic", "params": {"seed": 4}, "scale_to": 0.5}),
], ids=["default", "harmonic", "cycles", "stochastic"])
def test_the_options_build_the_motion_of_the_description(argv, fields):
    motion = motion_from_args(parsed("simulate", *argv))
    expected = MotionSpec(**fields).build()
    t = np.linspace(0.0, 1.2 * expected.duration, 301)
    assert motion.duration == expected.duration
    assert np.array_equal(motion.acceleration(t), expected.acceleration(t))


def test_every_field_is_an_option_of_the_commands():
    """Each field of both descriptions has its option in FIELD_OPTIONS, and the commands that
    describe a structure or a motion take that option."""
    fields = set(StructureSpec.__dataclass_fields__) | set(MotionSpec.__dataclass_fields__)
    assert set(FIELD_OPTIONS) == fields
    limit = {o for a in build_parser(["limit"])._subparsers._group_actions[0]
             .choices["limit"]._actions for o in a.option_strings}
    simulate = {o for a in build_parser(["simulate"])._subparsers._group_actions[0]
                .choices["simulate"]._actions for o in a.option_strings}
    assert {FIELD_OPTIONS[f] for f in StructureSpec.__dataclass_fields__} <= limit
    assert {FIELD_OPTIONS[f] for f in MotionSpec.__dataclass_fields__} <= simulate
    assert "duration" in STOCHASTIC_PARAMETERS


@pytest.mark.parametrize("argv, message", [
    (["limit", "--fill-inertia", "none"],
     "--fill-inertia: the fill needs --fill-cover M (its depth above the crown [m])"),
    (["limit", "--shape", "pointed", "--embrace", "120"],
     "--embrace apply to circular arches only; a pointed arch is given by --span and --rise"),
    (["limit", "--epsilon", "0.95", "--seed", "2", "--voussoirs", "30"],
     "the irregular arch drawn with --epsilon 0.95 (seed 2) is not a valid arch: "),
    (["simulate", "--motion", "stochastic", "--duration", "3"],
     "--duration applies to an analytic pulse, not to a stochastic motion (use --param "
     "duration=...)"),
    (["simulate", "--suite", "fema-p695-far-field"],
     "--suite fema-p695-far-field needs --record NAME: the ground motion of the suite to "
     "apply"),
])
def test_a_refused_description_names_the_options(capsys, argv, message):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"archquake: error: {message}") and err.count("\n") == 1
