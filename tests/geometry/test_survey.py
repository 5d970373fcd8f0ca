"""Surveyed arches: block polygons, joints found where neighbours touch, clear errors."""


import numpy as np
import pytest

from archquake.geometry import SurveyedArch, irregular_arch, surveyed_arch


def polygons(arch, points=40):
    """The blocks of an arch as polygons, its curved faces sampled at ``points`` points."""
    return [arch.outline(i, points)[:-1] for i in range(arch.n_voussoirs)]


def radial_joints(arch):
    inner, outer = arch.joint_extents()
    beta = arch.joint_angles
    return np.stack((arch.point(inner, beta), arch.point(outer, beta)), axis=1)


def test_joints_of_sampled_oppenheim_arch_are_its_radial_joints(nominal):
    survey = surveyed_arch(polygons(nominal))
    assert survey.n_voussoirs == 7
    assert survey.joints == pytest.approx(radial_joints(nominal), abs=1e-12)
    assert survey.joint_angles == pytest.approx(nominal.joint_angles, abs=1e-12)
    # the normals point from voussoir j-1 into voussoir j
    mid = survey.joints.mean(axis=1)
    for j in range(7):
        assert (nominal.centroids[j] - mid[j]) @ survey.joint_normals[j] > 0
    assert survey.is_symmetric(1e-12)


def test_contact_of_irregular_blocks_is_the_overlap_of_their_joints(nominal):
    """Neighbours of different thickness touch along the overlap of their joint edges."""
    arch = irregular_arch(nominal, 0.1, rng=4)
    survey = surveyed_arch(polygons(arch))
    assert survey.joints == pytest.approx(radial_joints(arch), abs=1e-12)


def test_polygon_mass_properties_converge_to_the_sectors(nominal):
    """Polygons inscribed in the arcs lose area as (angle/chords)^2: the error falls 4x when the
    sampling doubles and is below 1e-6 with 400 points a face."""
    errors = []
    for points in (100, 200, 400):
        survey = surveyed_arch(polygons(nominal, points))
        errors.append(np.max(np.abs(survey.masses / nominal.masses - 1)))
        assert survey.centroids == pytest.approx(nominal.centroids, abs=0.2 / points**2)
    # a face of p points has p - 1 chords
    assert errors[0] / errors[1] == pytest.approx((199 / 99) ** 2, rel=1e-3)
    assert errors[1] / errors[2] == pytest.approx((399 / 199) ** 2, rel=1e-3)
    assert errors[2] < 1e-6


def test_given_springings_and_either_vertex_order(nominal):
    blocks = polygons(nominal, 10)
    found = surveyed_arch(blocks)
    given = surveyed_arch([b[::-1] for b in blocks], springings=radial_joints(nominal)[[0, -1]])
    assert given.joints == pytest.approx(found.joints, abs=1e-12)
    assert given.masses == pytest.approx(found.masses, rel=1e-13)
    reversed_ends = radial_joints(nominal)[[0, -1]][:, ::-1]
    assert surveyed_arch(blocks, springings=reversed_ends).joints == pytest.approx(
        found.joints, abs=1e-12)


def test_rectangular_blocks_on_a_flat_lintel_like_arch():
    """Four unit squares side by side between two supports: joints are the shared vertical
    edges, springings the outer vertical edges (facing away from the neighbour)."""
    blocks = [[[i, 0], [i + 1, 0], [i + 1, 1], [i, 1]] for i in range(4)]
    survey = surveyed_arch(blocks)
    expected = np.array([[[x, 0.0], [x, 1.0]] for x in range(5)])
    assert survey.joints == pytest.approx(expected)
    assert survey.joint_normals == pytest.approx(np.tile([1.0, 0.0], (5, 1)))
    assert survey.masses == pytest.approx(np.full(4, 2000.0))
    assert survey.inertias == pytest.approx(np.full(4, 2000.0 * 2 / 12))


def test_dict_round_trip_and_mirror(nominal):
    survey = surveyed_arch(polygons(irregular_arch(nominal, 0.1, rng=1), 8))
    assert SurveyedArch.from_dict(survey.to_dict()) == survey
    mirror = survey.mirrored()
    assert mirror.mirrored() == survey
    assert mirror.centroids[::-1] == pytest.approx(survey.centroids * [-1, 1], abs=1e-12)
    assert mirror.joints[::-1] == pytest.approx(survey.joints * [-1, 1], abs=1e-12)


def _moved(blocks, i, offset):
    out = [b.copy() for b in blocks]
    out[i] = out[i] + np.asarray(offset)
    return out


@pytest.mark.parametrize(
    ("change", "message"),
    [
        (lambda b: _moved(b, 3, [0.0, 0.02]), "blocks 2 and 3 do not touch"),
        (lambda b: _moved(b, 3, [0.0, -0.02]), "blocks 2 and 3 overlap"),
        (lambda b: b[:3], "at least 4 blocks"),
        (lambda b: [b[0], b[2], b[1], *b[3:]], "blocks 0 and 2 touch"),
        (lambda b: [*b[:2], np.array([[0, 0], [1, 1], [1, 0], [0, 1]]), *b[3:]],
         "block 2 is not a simple polygon"),
        (lambda b: [*b[:2], np.array([[0, 0], [1, 1]]), *b[3:]], "block 2 must have at least"),
        (lambda b: [*b[:2], np.array([[0, 0], [1, 1], [2, 2]]), *b[3:]],
         "block 2 encloses no area"),
        (lambda b: [*b[:2], [[0, 0], [1, float("nan")], [2, 3]], *b[3:]], "block 2"),
    ],
)
def test_bad_surveys_name_the_block(nominal, change, message):
    with pytest.raises(ValueError, match=message):
        surveyed_arch(change(polygons(nominal, 10)))


def test_springing_off_its_block_is_an_error(nominal):
    springings = radial_joints(nominal)[[0, -1]] + [0.0, 0.5]
    with pytest.raises(ValueError, match=r"springings\[0\] does not lie on the boundary of "
                                         "block 0"):
        surveyed_arch(polygons(nominal, 10), springings=springings)


def test_springing_that_cannot_be_found_asks_for_it():
    """A first block hanging below its neighbour, both its free edges facing sideways (80
    degrees from the direction away from the neighbour): no springing within 60 degrees."""
    blocks = [[[0.0, 0.0], [1.0, 0.0], [0.5, -3.0]],
              *[[[i, 0.0], [i + 1, 0.0], [i + 1, 1.0], [i, 1.0]] for i in range(3)]]
    with pytest.raises(ValueError, match="springing joint of block 0.*give 'springings'"):
        surveyed_arch(blocks)


# ------------------------------------------------------------------ files of every kind
def test_load_arch_reads_the_three_kinds(tmp_path, nominal):
    import json

    from archquake.geometry import CircularArch, ShapedArch, load_arch, shaped_arch

    circle = tmp_path / "circle.json"
    circle.write_text(json.dumps(nominal.to_dict()))
    assert load_arch(circle) == CircularArch.from_json(circle) == nominal
    survey = surveyed_arch(polygons(nominal, 12))
    blocks = tmp_path / "blocks.json"
    blocks.write_text(json.dumps({"blocks": [b.tolist() for b in polygons(nominal, 12)]}))
    assert load_arch(blocks) == survey
    shaped = irregular_arch(shaped_arch("three-centred", span=12.0, rise=4.0, thickness=0.6,
                                        voussoirs=9, faces="flat"), 0.1, rng=3)
    recipe = tmp_path / "shaped.json"
    recipe.write_text(json.dumps(shaped.to_dict()))
    loaded = load_arch(recipe)
    assert isinstance(loaded, ShapedArch) and loaded == shaped


@pytest.mark.parametrize(
    ("content", "message"),
    [
        ('{"blocks": [], "angles": [1]}', "different kinds"),
        ('{"colour": 3}', "one of the keys"),
        ('[1, 2]', "JSON object"),
        ('{"blocks": 3}', "list of polygons"),
        ('{"shape": "oval", "span": 1, "rise": 1, "lengths": [1], "thicknesses": [1], '
         '"offsets": [0]}', "shape must be one of"),
        ('{"shape": "pointed", "span": 10, "rise": 8, "lengths": [1, 1, 1, 1], '
         '"thicknesses": [0.5, 0.5, 0.5, 0.5]}', "missing"),
        ('{"blocks": [[[0, 0], [1, 0], [1, true]]]}', "'blocks' has true"),
        ('{"shape": "pointed", "span": "10", "rise": 8, "lengths": [1], "thicknesses": [1], '
         '"offsets": [0]}', "'span' has \"10\""),
    ],
)
def test_bad_geometry_files_name_the_file(tmp_path, content, message):
    from archquake.geometry import load_arch

    path = tmp_path / "g.json"
    path.write_text(content)
    with pytest.raises(ValueError, match=message) as info:
        load_arch(path)
    assert "g.json" in str(info.value)
