"""A structure described by named values (StructureSpec): it builds the structure the geometry
builders build from the same values, its refusals name the field, and its JSON form reads back
to the same description."""

import math

import numpy as np
import pytest

from archquake.errors import DescriptionError
from archquake.geometry import (
    Fill,
    Pier,
    Structure,
    StructureSpec,
    circular_arch,
    irregular_arch,
    shaped_arch,
)


def same_blocks(built, expected) -> None:
    """The two structures have the same kind, joints and mass properties, to the last bit."""
    assert type(built) is type(expected)
    assert built.n_voussoirs == expected.n_voussoirs
    for name in ("joints", "masses", "centroids", "inertias"):
        assert np.array_equal(getattr(built, name), getattr(expected, name)), name
    assert built.to_dict() == expected.to_dict()


@pytest.mark.parametrize("fields, expected", [
    ({}, lambda: circular_arch(10.0, math.radians(157.5), 1.5, 7)),
    ({"thickness": 1.2, "voussoirs": 9, "embrace": 150},
     lambda: circular_arch(10.0, math.radians(150), 1.2, 9)),
    ({"shape": "pointed", "span": 10, "rise": 7, "thickness": 0.6},
     lambda: shaped_arch("pointed", span=10, rise=7, thickness=0.6, voussoirs=8)),
    ({"span": 12, "rise": 4, "faces": "flat", "density": 2400},
     lambda: shaped_arch("circular", span=12, rise=4, thickness=1.5, voussoirs=7, faces="flat",
                         density=2400)),
    ({"piers": "2,4,2", "fill_cover": 0.5},
     lambda: Structure(circular_arch(10.0, math.radians(157.5), 1.5, 7), Pier(2, 4, 2),
                       Pier(2, 4, 2), Fill(0.5))),
    ({"shape": "parabolic", "span": 10, "rise": 3, "pier_left": [3, 6], "pier_right": "4,5,2",
      "fill_cover": 0.4, "fill_density": 1600, "fill_inertia": "extrados",
      "fill_passive": "30,0.5"},
     lambda: Structure(shaped_arch("parabolic", span=10, rise=3, thickness=1.5, voussoirs=7),
                       Pier(3, 6), Pier(4, 5, 2),
                       Fill(0.4, 1600, "extrados", math.radians(30), 0.5))),
    ({"epsilon": 0.15, "seed": 4, "voussoirs": 9, "thickness": 1.3},
     lambda: irregular_arch(circular_arch(10.0, math.radians(157.5), 1.3, 9), 0.15, rng=4)),
    ({"epsilon": 0.1, "piers": "2,4"},
     lambda: irregular_arch(Structure(circular_arch(10.0, math.radians(157.5), 1.5, 7),
                                      Pier(2, 4), Pier(2, 4)), 0.1, rng=0)),
], ids=["oppenheim", "circular", "pointed", "flat-by-span", "piers-fill", "unequal-piers",
        "irregular", "irregular-on-piers"])
def test_build_gives_the_structure_of_the_builders(fields, expected):
    spec = StructureSpec.from_dict(fields)
    same_blocks(spec.build(), expected())
    nominal, structure = spec.arches()
    assert (nominal is structure) == ("epsilon" not in fields)


def test_the_nominal_structure_is_before_the_draw():
    spec = StructureSpec(epsilon=0.2, seed=3, thickness=1.4)
    same_blocks(spec.nominal(), circular_arch(10.0, math.radians(157.5), 1.4, 7))
    assert not np.array_equal(spec.build().joints, spec.nominal().joints)


def test_a_geometry_file_is_the_whole_arch(tmp_path):
    arch = shaped_arch("elliptical", span=8, rise=3, thickness=0.5, voussoirs=10)
    path = tmp_path / "arch.json"
    import json

    path.write_text(json.dumps(arch.to_dict()))
    same_blocks(StructureSpec(geometry=str(path)).build(), arch)
    same_blocks(StructureSpec(geometry=str(path), piers=(2, 3)).build(),
                Structure(arch, Pier(2, 3), Pier(2, 3)))


@pytest.mark.parametrize("fields, message", [
    ({"shape": "pointed", "radius": 5},
     "radius apply to circular arches only; a pointed arch is given by span and rise"),
    ({"span": 10, "embrace": 120},
     "span, embrace: a circular arch is given by span and rise or by radius and embrace, not "
     "both"),
    ({"span": 10}, "a circular arch needs span and rise [m]"),
    ({"shape": "elliptical"}, "an elliptical arch needs span and rise [m]"),
    ({"embrace": 400}, "embrace must be in (0, 360) degrees, got 400"),
    ({"geometry": "arch.json", "thickness": 1}, "geometry gives the whole arch; it cannot be "
                                                "combined with thickness"),
    ({"piers": "3,x"}, "piers takes numbers separated by commas, got '3,x'"),
    ({"piers": [3, 6, 1.5]}, "piers: COURSES must be an integer >= 1, got 1.5"),
    ({"pier_right": "3,-6"}, "pier_right: height must be a finite number > 0 [m], got -6.0"),
    ({"piers": "3,6", "pier_left": "3,6"},
     "piers gives both piers; use pier_left and pier_right for unequal ones, not both"),
    ({"fill_density": 1600, "fill_inertia": "none"},
     "fill_density, fill_inertia: the fill needs fill_cover (its depth above the crown [m])"),
    ({"fill_cover": -1}, "fill_cover: cover must be in [0, 10000] m, got -1.0"),
    ({"fill_cover": 0.5, "fill_density": 0},
     "fill_density: fill density must be in (0, 100000] kg/m^3, got 0.0"),
    ({"fill_cover": 0.5, "fill_passive": "95,0.3"},
     "fill_passive: PHI must be in (0, 90) degrees, got 95"),
    ({"fill_cover": 0.5, "fill_passive": "30,2"},
     "fill_passive: mobilisation must be in [0, 1] [-], got 2.0"),
    ({"fill_cover": 0.5, "fill_passive": "30"},
     "fill_passive takes 2 to 2 numbers separated by commas, got '30'"),
    ({"density": -5}, "density must be a number in [1, 100000] kg/m^3 (air to four times "
                      "osmium), got -5.0"),
    ({"seed": 3}, "seed needs epsilon (the seed of an irregular arch)"),
    ({"epsilon": 0.1, "seed": -1}, "seed must be an integer >= 0, got -1"),
    ({"thickness": "thick"}, "thickness must be a number, got 'thick'"),
    ({"voussoirs": 9.5}, "voussoirs must be an integer, got 9.5"),
    ({"shape": "gothic"}, "shape must be one of ['circular', 'pointed', 'elliptical', "
                          "'parabolic', 'catenary', 'three-centred'], got 'gothic'"),
    ({"faces": "round"}, "faces must be one of ['curved', 'flat'], got 'round'"),
])
def test_a_refused_description_names_the_field(fields, message):
    with pytest.raises(DescriptionError) as refused:
        StructureSpec.from_dict(fields).build()
    assert str(refused.value) == message


@pytest.mark.parametrize("fields, message", [
    ({"piers": "1.2,6"}, "piers: left pier: pier width must be at least"),
    ({"pier_left": "1.2,6"}, "pier_left: left pier: pier width must be at least"),
    ({"epsilon": 0.95, "seed": 2, "voussoirs": 30},
     "the irregular arch drawn with epsilon 0.95 (seed 2) is not a valid arch: "),
])
def test_a_structure_that_cannot_be_built_names_the_field(fields, message):
    with pytest.raises(DescriptionError, match="^" + message.replace("(", r"\(")
                       .replace(")", r"\)")):
        StructureSpec.from_dict(fields).build()


def test_the_builders_name_the_same_parameters():
    """A value the builders refuse keeps their message, which names the field already."""
    with pytest.raises(ValueError, match=r"^thickness must be < 2 x radius = 20.0 m"):
        StructureSpec(thickness=25).build()
    with pytest.raises(ValueError, match=r"^epsilon must be in \[0, 1\), got 1.5"):
        StructureSpec(epsilon=1.5).build()


def test_messages_name_the_fields_as_a_naming_says():
    """The command line names its options: the same message, field by field."""
    with pytest.raises(DescriptionError) as refused:
        StructureSpec(fill_inertia="none")
    options = {"fill_inertia": "--fill-inertia", "fill_cover": "--fill-cover"}
    assert refused.value.naming(options) == ("--fill-inertia: the fill needs --fill-cover M (its "
                                             "depth above the crown [m])")


@pytest.mark.parametrize("fields", [
    {},
    {"shape": "pointed", "span": 10, "rise": 7, "thickness": 0.6, "voussoirs": 12,
     "faces": "flat"},
    {"radius": 8, "embrace": 140, "piers": "2,4,2", "fill_cover": 0.5, "fill_passive": "30,0.5",
     "density": 2200, "epsilon": 0.1, "seed": 5},
    {"pier_left": [3, 6], "pier_right": "4,5,2"},
])
def test_json_reads_back_to_the_same_description(fields):
    import json

    spec = StructureSpec.from_dict(fields)
    again = StructureSpec.from_dict(json.loads(json.dumps(spec.to_dict())))
    assert again == spec
    same_blocks(again.build(), spec.build())


def test_from_dict_refuses_what_is_not_a_description():
    with pytest.raises(DescriptionError, match=r"unknown structure field\(s\) \['wall'\]"):
        StructureSpec.from_dict({"wall": 1})
    with pytest.raises(DescriptionError, match="must be described by a JSON object, got list"):
        StructureSpec.from_dict([1])
    assert StructureSpec.from_dict({"thickness": "", "span": None}) == StructureSpec()
    assert StructureSpec.from_dict({"thickness": "1.2", "voussoirs": "9"}) == StructureSpec(
        thickness=1.2, voussoirs=9)


def test_shape_arguments_apply_the_defaults():
    assert StructureSpec().shape_arguments() == (None, {
        "radius": 10.0, "embrace": math.radians(157.5), "voussoirs": 7, "faces": "curved"})
    assert StructureSpec(shape="pointed", span=10, rise=7).shape_arguments() == (
        "pointed", {"span": 10.0, "rise": 7.0, "voussoirs": 8, "faces": "curved"})
