"""Geometry inputs that used to give a wrong answer or a traceback: blocks listed right to left,
densities no arch has, files nested too deeply, keys given twice, paths that are not paths."""

import json
import warnings

import numpy as np
import pytest

from archquake import FourLinkModel, oppenheim
from archquake.geometry import circular_arch, irregular_arch, load_arch, shaped_arch, surveyed_arch
from archquake.geometry.blocks import DENSITY_RANGE
from archquake.ground_motion import ground_motion


def _polygons(arch, points=12):
    return [arch.outline(i, points)[:-1] for i in range(arch.n_voussoirs)]


def _radial_joints(arch):
    inner, outer = arch.joint_extents()
    beta = arch.joint_angles
    return np.stack((arch.point(inner, beta), arch.point(outer, beta)), axis=1)


def test_blocks_listed_right_to_left_give_the_same_four_link_answer():
    """The same stones, listed either way: the same joints (those of the circular arch they were
    cut from), the same c_v, mechanisms and outcome; the reversed listing is said."""
    arch = irregular_arch(oppenheim(), 0.1, rng=3)  # asymmetric: a mislabelling would show
    blocks = _polygons(arch)
    left_to_right = surveyed_arch(blocks)
    with pytest.warns(UserWarning, match="listed right to left.*reverse order"):
        right_to_left = surveyed_arch(blocks[::-1])
    assert right_to_left.to_dict() == left_to_right.to_dict()
    assert right_to_left.joints == pytest.approx(_radial_joints(arch), abs=1e-12)
    a = FourLinkModel.from_arch(left_to_right, "computed")
    b = FourLinkModel.from_arch(right_to_left, "computed")
    assert a.restitution == b.restitution
    assert a.load_multipliers == b.load_multipliers
    pulse = ground_motion("oppenheim", -0.6 * 9.81, 0.5)
    assert a.outcome(pulse) == b.outcome(pulse)


def test_given_springings_follow_the_blocks_when_they_are_reversed():
    arch = irregular_arch(oppenheim(), 0.1, rng=3)
    blocks = _polygons(arch)
    springings = _radial_joints(arch)[[0, -1]]
    with pytest.warns(UserWarning, match="right to left"):
        reversed_survey = surveyed_arch(blocks[::-1], springings=springings[::-1])
    assert reversed_survey.to_dict() == surveyed_arch(blocks, springings).to_dict()


def test_a_file_of_blocks_listed_right_to_left_is_named_in_the_warning(tmp_path):
    arch = irregular_arch(oppenheim(), 0.1, rng=3)
    path = tmp_path / "survey.json"
    path.write_text(json.dumps({"blocks": [b.tolist() for b in _polygons(arch)[::-1]]}))
    with pytest.warns(UserWarning, match=r"geometry file '.*survey.json': the blocks are listed "
                                         r"right to left"):
        load_arch(path)


@pytest.mark.parametrize("density", [1e300, 1e-300, 0.5, 2e5, float("nan"), -2000.0])
def test_density_outside_the_range_is_refused_by_every_arch(density):
    low, high = DENSITY_RANGE
    message = rf"density must be a number in \[{low:g}, {high:g}\] kg/m\^3"
    with pytest.raises(ValueError, match=message):
        circular_arch(10.0, 2.0, 1.5, 7, density=density)
    with pytest.raises(ValueError, match=message):
        shaped_arch("parabolic", span=10.0, rise=4.0, thickness=1.0, voussoirs=7,
                    density=density)
    with pytest.raises(ValueError, match=message):
        surveyed_arch(_polygons(oppenheim()), density=density)


def test_density_within_the_range_scales_the_masses_exactly():
    """A light and a heavy arch of the range: masses proportional to the density, and the
    load multiplier (independent of the density) the same."""
    low, high = DENSITY_RANGE
    light, heavy = (circular_arch(10.0, 2.0, 1.5, 7, density=d) for d in (low, high))
    assert heavy.masses == pytest.approx(light.masses * high / low, rel=1e-12)
    k_light = FourLinkModel.from_arch(light, "computed").load_multipliers
    k_heavy = FourLinkModel.from_arch(heavy, "computed").load_multipliers
    assert k_heavy == pytest.approx(k_light, rel=1e-9)


def test_density_of_a_geometry_file_is_checked_naming_the_file(tmp_path):
    path = tmp_path / "heavy.json"
    path.write_text(json.dumps({**oppenheim().to_dict(), "density": 1e300}))
    with pytest.raises(ValueError, match=r"geometry file '.*heavy.json': density must be"):
        load_arch(path)


def test_a_deeply_nested_geometry_file_is_an_error_naming_the_file(tmp_path):
    path = tmp_path / "deep.json"
    path.write_text("[" * 100_000)
    with pytest.raises(ValueError, match=r"geometry file '.*deep.json' is not valid JSON"):
        load_arch(path)
    path.write_text('{"blocks": ' + "[" * 100_000 + "]" * 100_000 + "}")
    with pytest.raises(ValueError, match=r"deep.json' is not valid JSON: .*nested too deeply"):
        load_arch(path)


def test_a_key_given_twice_in_a_geometry_file_is_refused(tmp_path):
    text = json.dumps(oppenheim().to_dict())
    path = tmp_path / "twice.json"
    path.write_text(text[:-1] + ', "density": 1800}')
    with pytest.raises(ValueError, match="twice.json' is not valid JSON: the key 'density' is "
                                         "given twice"):
        load_arch(path)


def test_nan_in_a_geometry_file_is_refused(tmp_path):
    path = tmp_path / "nan.json"
    path.write_text('{"angles": [NaN], "thicknesses": [1], "radii": [1]}')
    with pytest.raises(ValueError, match="NaN is not a JSON number"):
        load_arch(path)


def test_load_arch_of_something_that_is_not_a_path_names_the_parameter():
    with pytest.raises(ValueError, match="path must be the name of a geometry file"):
        load_arch(3)


def test_no_warning_for_blocks_listed_left_to_right():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        surveyed_arch(_polygons(oppenheim()))
