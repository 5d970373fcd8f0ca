"""Arches on piers and buttresses: the pier rules, joints, mass properties against closed forms,
value equality, mirror images and JSON round trips."""

import json
import math

import numpy as np
import pytest

from archquake.geometry import (
    Fill,
    Pier,
    Structure,
    arch_from_dict,
    arch_on_piers,
    circular_arch,
    load_arch,
    shaped_arch,
)
from archquake.geometry.piers import pier_blocks


def springing(nominal):
    """Intrados and extrados springing points of Oppenheim's arch, from R, t and beta_0."""
    beta0 = (math.pi - nominal.embrace) / 2
    return [np.array([-r * math.cos(beta0), r * math.sin(beta0)]) for r in (9.25, 10.75)]


def area(polygon) -> float:
    x, y = np.asarray(polygon).T
    return 0.5 * abs(float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y)))


def test_pier_follows_the_rules(nominal):
    """Inner face on the vertical through the intrados springing point, top along the springing
    joint then horizontal, width from that point outward, height from the ground up to it."""
    p_in, p_out = springing(nominal)
    s = arch_on_piers(nominal, 3.0, 6.0, 3)
    assert s.n_voussoirs == 7 + 2 * 3 and s.arch_blocks == range(3, 10)
    ground = p_in[1] - 6.0
    left = [s.pier_polygon(i) for i in range(3)]
    xs = np.concatenate([p[:, 0] for p in left])
    assert xs.max() == pytest.approx(p_in[0]) and xs.min() == pytest.approx(p_in[0] - 3.0)
    assert left[0][:, 1].min() == pytest.approx(ground)
    top = left[-1]
    for point in (p_in, p_out, (p_in[0] - 3.0, p_out[1])):  # the top's corners
        assert np.min(np.hypot(*(top - point).T)) < 1e-12
    # courses of equal height below the springing: bed joints at 2 m and 4 m
    assert s.joints[:3, :, 1] == pytest.approx(np.array([[0, 0], [2, 2], [4, 4]]) + ground)
    # intrados end on the inner face, extrados end on the outer face (left pier)
    assert s.joints[:3, 0, 0] == pytest.approx(p_in[0])
    assert s.joints[:3, 1, 0] == pytest.approx(p_in[0] - 3.0)
    # the right pier is the mirror image
    assert s.joints[-3:, :, 0] == pytest.approx(-s.joints[:3, :, 0][::-1])
    assert s.joints[3:11] == pytest.approx(nominal.joints)


def test_joint_normals_run_along_the_chain(nominal):
    """Every joint's normal points from block j-1 into block j: up through the left pier, down
    through the right one."""
    s = arch_on_piers(nominal, 3.0, 6.0, 2)
    mid = s.joints.mean(axis=1)
    for j in range(s.n_voussoirs):
        assert (s.centroids[j] - mid[j]) @ s.joint_normals[j] > 0
    assert s.joint_normals[:2] == pytest.approx(np.array([[0, 1], [0, 1]]))
    assert s.joint_normals[-2:] == pytest.approx(np.array([[0, -1], [0, -1]]))


def test_pier_mass_is_its_area(nominal):
    """A rectangular pier weighs rho (b h + the part above the intrados springing: b rise -
    reach rise / 2); its courses below the top are b x h / c."""
    p_in, p_out = springing(nominal)
    reach, rise = p_in[0] - p_out[0], p_out[1] - p_in[1]
    width, height, courses = 3.0, 6.0, 3
    s = arch_on_piers(nominal, width, height, courses)
    total = width * height + width * rise - 0.5 * reach * rise
    assert s.masses[:3].sum() == pytest.approx(2000 * total, rel=1e-13)
    assert s.masses[:2] == pytest.approx(2000 * width * height / courses, rel=1e-13)
    assert s.centroids[0] == pytest.approx([p_in[0] - width / 2, p_in[1] - height + 1.0])
    assert s.inertias[0] == pytest.approx(2000 * 3 * 2 * (3**2 + 2**2) / 12)
    assert s.masses[3:10] == pytest.approx(nominal.masses)
    assert s.total_mass == pytest.approx(2 * 2000 * total + nominal.total_mass)


def test_buttresses_tapered_and_stepped(nominal):
    """A tapered buttress is a trapezoid below the springing, a stepped one a stack of
    rectangles; the bed joint under a setback is the narrower course."""
    p_in, p_out = springing(nominal)
    reach, rise = p_in[0] - p_out[0], p_out[1] - p_in[1]
    top = 2.5 * rise - 0.5 * reach * rise
    tapered = Structure(nominal, Pier.tapered(2.5, 4.0, 6.0), Pier.tapered(2.5, 4.0, 6.0))
    assert tapered.masses[0] == pytest.approx(2000 * (0.5 * (4.0 + 2.5) * 6.0 + top))
    assert tapered.joint_lengths[0] == pytest.approx(4.0)
    stepped = Structure(nominal, Pier.stepped((4.0, 3.0, 2.5), 6.0), None)
    assert stepped.masses[:3] == pytest.approx(2000 * np.array([8.0, 6.0, 5.0 + top]))
    assert stepped.joint_lengths[:3] == pytest.approx([4.0, 3.0, 2.5])
    assert stepped.n_voussoirs == 10 and stepped.joints[-1] == pytest.approx(nominal.joints[-1])
    assert "buttress 2.5 m wide (4 m at the base)" in stepped.describe()


def test_unequal_piers_and_their_mirror_image(nominal):
    s = Structure(nominal, Pier(3.0, 6.0), Pier(4.0, 5.0, 2))
    assert s.n_voussoirs == 10 and not s.is_symmetric()
    m = s.mirrored()
    assert (m.left, m.right) == (s.right, s.left)
    # block i of the mirror is block n-1-i of the structure, reflected
    flip = np.array([-1.0, 1.0])
    assert m.centroids == pytest.approx((s.centroids * flip)[::-1], abs=1e-12)
    assert m.masses == pytest.approx(s.masses[::-1], rel=1e-12)
    assert arch_on_piers(nominal, 3.0, 6.0, 2).is_symmetric()


def test_narrow_pier_and_other_bad_input_are_value_errors(nominal):
    reach = springing(nominal)[0][0] - springing(nominal)[1][0]  # 1.4712 m, 1.5 cos(11.25 deg)
    with pytest.raises(ValueError, match=r"pier width must be at least the horizontal extent "
                                         r"of the springing joint, 1\.4711"):
        arch_on_piers(nominal, 1.4, 6.0)
    assert arch_on_piers(nominal, reach, 6.0).n_voussoirs == 9  # exactly the joint's extent
    with pytest.raises(ValueError, match="height must be a finite number > 0"):
        Pier(3.0, -1.0)
    with pytest.raises(ValueError, match="courses must be an integer"):
        Pier(3.0, 6.0, 1.5)
    with pytest.raises(ValueError, match="outer_face must start on the ground"):
        Pier(3.0, 6.0, outer_face=((4.0, 1.0),))
    with pytest.raises(ValueError, match="rises outward"):  # a horseshoe arch
        arch_on_piers(circular_arch(10.0, math.radians(200), 1.5, 8), 3.0, 6.0)
    with pytest.raises(ValueError, match="either by width and height"):
        arch_on_piers(nominal, 3.0, 6.0, left=Pier(3.0, 6.0))
    with pytest.raises(ValueError, match="arch must be an arch"):
        Structure(arch_on_piers(nominal, 3.0, 6.0))


def test_shaped_and_flat_faced_arches_stand_on_piers():
    """Any arch: the pier's top follows its springing joint (horizontal for an elliptical
    arch)."""
    ellipse = shaped_arch("elliptical", span=10.0, rise=3.0, thickness=0.6, voussoirs=8)
    s = arch_on_piers(ellipse, 1.5, 4.0, 2)
    assert ellipse.joints[0, :, 1] == pytest.approx([0.0, 0.0], abs=1e-12)  # horizontal
    assert s.masses[:2].sum() == pytest.approx(2000 * 1.5 * 4.0)
    flat = shaped_arch("circular", span=10.0, rise=4.0, thickness=0.8, voussoirs=6,
                       faces="flat")
    assert arch_on_piers(flat, 2.0, 5.0).is_symmetric(1e-12)


def test_pier_blocks_of_a_springing_joint_of_a_square():
    """A unit springing joint at 45 degrees on a pier 2 wide and 3 high in 3 courses: every
    course by hand."""
    joint = np.array([[0.0, 0.0], [-math.sqrt(0.5), math.sqrt(0.5)]])
    polygons, joints = pier_blocks(Pier(2.0, 3.0, 3), joint)
    assert [area(p) for p in polygons] == pytest.approx([2.0, 2.0, 2.0 + 2 * 0.7071068 - 0.25],
                                                        rel=1e-7)
    assert joints[:, :, 1] == pytest.approx(np.array([[-3, -3], [-2, -2], [-1, -1]]))


def test_value_equality_and_json_round_trip(nominal, tmp_path):
    s = Structure(nominal, Pier(3.0, 6.0, 2), Pier.stepped((4.0, 3.0), 5.0),
                  Fill(0.5, 1600.0, "extrados", math.radians(30), 0.33))
    again = arch_from_dict(json.loads(json.dumps(s.to_dict())))
    assert again == s and hash(again) == hash(s)
    assert again.masses == pytest.approx(s.masses, rel=1e-15)
    path = tmp_path / "structure.json"
    path.write_text(json.dumps(s.to_dict()))
    assert load_arch(path) == s
    assert s != Structure(nominal, Pier(3.0, 6.0, 2), Pier.stepped((4.0, 3.0), 5.0))
    with pytest.raises(ValueError, match="unknown key"):
        arch_from_dict({"arch": nominal.to_dict(), "piers": {}})
    with pytest.raises(ValueError, match="a pier is missing the key"):
        arch_from_dict({"arch": nominal.to_dict(), "left_pier": {"width": 3.0}})


def test_describe_names_arch_piers_and_fill(nominal):
    text = Structure(nominal, Pier(3.0, 6.0), Pier(3.0, 6.0), Fill(0.5, 1600.0)).describe()
    assert text == ("n = 7 voussoirs, embrace = 157.5 deg, mean radius = 10 m, mean thickness "
                    "= 1.5 m; on two rectangular piers 3 m wide, 6 m high, 1 course; fill 0.5 m "
                    "over the crown, 1600 kg/m^3, inertia centroid")


def test_crown_and_thickness_scale_are_the_arch_s(nominal):
    s = arch_on_piers(nominal, 3.0, 6.0, 2)
    block, point = s.crown()
    assert block == 2 + 3 and point == pytest.approx([0.0, 10.75])
    assert s.thickness_scale == 1.5


def test_joint_names(nominal):
    s = Structure(nominal, Pier(3.0, 6.0, 2), None)
    names = [s.joint_name(j) for j in range(s.n_voussoirs + 1)]
    assert names[:3] == ["left pier base", "left pier bed joint 1", "left springing"]
    assert names[3] == "arch joint 1" and names[-1] == "right fixed springing"
    right = Structure(nominal, None, Pier(3.0, 6.0, 3))
    assert [right.joint_name(j) for j in range(7, 11)] == [
        "right springing", "right pier bed joint 2", "right pier bed joint 1", "right pier base"]
