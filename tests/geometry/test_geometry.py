import json
import math

import numpy as np
import pytest
from scipy import integrate

from archquake.geometry import CircularArch, circular_arch, irregular_arch


def test_oppenheim_arch_springings_and_joints(nominal, paper):
    beta = nominal.joint_angles
    assert nominal.n_voussoirs == 7
    assert beta[0] == pytest.approx(math.radians(11.25), abs=1e-15)
    assert beta[-1] == pytest.approx(math.pi - math.radians(11.25), abs=1e-14)
    # Table 1 hinge angles are joints 0, 3, 5, 7 of the nominal arch
    assert beta[paper["table1"]["NA"]["joints"]] == pytest.approx(
        paper["table1"]["NA"]["beta"], abs=1e-4
    )


def test_mass_properties_match_numerical_integration_of_annular_sector():
    arch = circular_arch(3.0, math.radians(100), 0.9, 5, density=1800.0)
    i = 2
    ri, ro = arch.inner_radii[i], arch.outer_radii[i]
    b0, b1 = arch.joint_angles[i], arch.joint_angles[i + 1]
    # integrate in polar coordinates (r, beta): x = -r cos beta, y = r sin beta, dA = r dr dbeta
    rho = arch.density
    m = rho * integrate.dblquad(lambda r, b: r, b0, b1, ri, ro)[0]
    mx = rho * integrate.dblquad(lambda r, b: -r * np.cos(b) * r, b0, b1, ri, ro)[0]
    my = rho * integrate.dblquad(lambda r, b: r * np.sin(b) * r, b0, b1, ri, ro)[0]
    io = rho * integrate.dblquad(lambda r, b: r**3, b0, b1, ri, ro)[0]
    assert arch.masses[i] == pytest.approx(m, rel=1e-12)
    assert arch.centroids[i] == pytest.approx([mx / m, my / m], rel=1e-10)
    assert arch.inertias[i] == pytest.approx(io - m * ((mx / m) ** 2 + (my / m) ** 2), rel=1e-9)


def test_mirror_reflects_centroids_and_is_an_involution():
    arch = irregular_arch(circular_arch(10, math.radians(157.5), 1.5, 7), 0.1, rng=3)
    m = arch.mirrored()
    c, cm = arch.centroids, m.centroids[::-1]
    assert cm[:, 0] == pytest.approx(-c[:, 0], abs=1e-12)
    assert cm[:, 1] == pytest.approx(c[:, 1], abs=1e-12)
    assert m.mirrored().joint_angles == pytest.approx(arch.joint_angles, abs=1e-14)
    assert not arch.is_symmetric()


def test_nominal_arch_is_symmetric(nominal):
    assert nominal.is_symmetric()
    assert nominal.centroids[:, 0].sum() == pytest.approx(0.0, abs=1e-12)


def test_joint_contact_is_overlap_of_radial_extents():
    arch = CircularArch.from_voussoirs([0.5] * 4, [1.0, 1.2, 1.0, 1.0], [10.0, 10.3, 10.0, 10.0])
    inner, outer = arch.joint_extents()
    assert inner.tolist() == pytest.approx([9.5, 9.7, 9.7, 9.5, 9.5])
    assert outer.tolist() == pytest.approx([10.5, 10.5, 10.5, 10.5, 10.5])


def test_irregular_tolerance_zero_gives_nominal(nominal):
    assert irregular_arch(nominal, 0.0, rng=1) is nominal


def test_irregular_draws_are_reproducible_and_bounded(nominal):
    a = irregular_arch(nominal, 0.1, rng=42)
    b = irregular_arch(nominal, 0.1, rng=np.random.default_rng(42))
    assert a.to_dict() == b.to_dict()
    assert a.embrace == pytest.approx(nominal.embrace, abs=1e-14)
    assert a.start_angle == nominal.start_angle
    chi = 0.1 * 1.5 / 10
    arches = [irregular_arch(nominal, 0.1, rng=s) for s in range(300)]
    t = np.array([x.thicknesses for x in arches])
    r = np.array([x.radii for x in arches])
    alpha = np.array([x.angles for x in arches])
    assert t.min() >= 1.5 * 0.9 and t.max() <= 1.5 * 1.1
    assert r.min() >= 10 * (1 - chi) and r.max() <= 10 * (1 + chi)
    # rescaled angles stay close to the U[-eps, eps] band (the rescaling factor is within 1 +- eps)
    a0 = nominal.angles[0]
    assert alpha.min() >= a0 * 0.9 / 1.1 and alpha.max() <= a0 * 1.1 / 0.9
    # uniform on [-1, 1]: mean 0, variance 1/3 for the normalised thickness draws
    p_t = (t / 1.5 - 1) / 0.1
    assert p_t.mean() == pytest.approx(0.0, abs=0.05)
    assert p_t.var() == pytest.approx(1 / 3, abs=0.03)
    # independence: correlation between parameters and between voussoirs is small
    p_r = (r / 10 - 1) / chi
    corr = np.corrcoef(np.column_stack([p_t, p_r]).T)
    off = corr[~np.eye(corr.shape[0], dtype=bool)]
    assert np.abs(off).max() < 0.2


def test_json_round_trip(tmp_path, nominal):
    arch = irregular_arch(nominal, 0.1, rng=7)
    path = tmp_path / "arch.json"
    path.write_text(json.dumps(arch.to_dict()))
    back = CircularArch.from_json(path)
    assert back.joint_angles == pytest.approx(arch.joint_angles, abs=1e-14)
    assert back.masses == pytest.approx(arch.masses, rel=1e-14)


@pytest.mark.parametrize(
    "kwargs, message",
    [
        ({"radius": -1, "embrace": 2.0, "thickness": 1, "voussoirs": 7}, "radius"),
        ({"radius": 10, "embrace": 0.0, "thickness": 1, "voussoirs": 7}, "embrace"),
        ({"radius": 10, "embrace": 7.0, "thickness": 1, "voussoirs": 7}, "embrace"),
        ({"radius": 10, "embrace": 2.0, "thickness": 0, "voussoirs": 7}, "thickness"),
        ({"radius": 10, "embrace": 2.0, "thickness": 20, "voussoirs": 7}, "thickness"),
        ({"radius": 10, "embrace": 2.0, "thickness": 1, "voussoirs": 3}, "voussoirs"),
        ({"radius": 10, "embrace": 2.0, "thickness": 1, "voussoirs": 5.5}, "voussoirs"),
        ({"radius": float("nan"), "embrace": 2.0, "thickness": 1, "voussoirs": 7}, "radius"),
    ],
)
def test_bad_circular_input_names_the_parameter(kwargs, message):
    with pytest.raises(ValueError, match=message):
        circular_arch(**kwargs)


@pytest.mark.parametrize("eps", [-0.1, 1.0, 2.0, float("nan"), "x"])
def test_bad_tolerance(nominal, eps):
    with pytest.raises(ValueError, match="epsilon"):
        irregular_arch(nominal, eps, rng=0)


def test_non_touching_voussoirs_rejected():
    with pytest.raises(ValueError, match="joint 2"):
        CircularArch.from_voussoirs([0.4] * 4, [1, 1, 1, 1], [10, 10, 12, 12])


@pytest.mark.parametrize(
    "content, message",
    [
        ("{not json", "not valid JSON"),
        ("[1, 2]", "JSON object"),
        ('{"angles": [0.4, 0.4, 0.4, 0.4], "radii": [1, 1, 1, 1]}', "missing"),
        ('{"angles": [0.4, 0.4, 0.4, 0.4], "thicknesses": [0.2, 0.2, 0.2], '
         '"radii": [1, 1, 1, 1]}', "same length"),
        ('{"angles": [0.4, 0.4, 0.4, -0.4], "thicknesses": [0.2, 0.2, 0.2, 0.2], '
         '"radii": [1, 1, 1, 1]}', "angles"),
        ('{"angles": "abc", "thicknesses": [0.2], "radii": [1]}', "list"),
        ('{"angles": [0.4, 0.4, 0.4, 0.4], "thicknesses": [0.2, 0.2, 0.2, 0.2], '
         '"radii": [1, 1, 1, 1], "colour": 3}', "unknown"),
        ('{"angles": [2, 2, 2, 2], "thicknesses": [0.2, 0.2, 0.2, 0.2], '
         '"radii": [1, 1, 1, 1]}', "360"),
    ],
)
def test_bad_json_geometry(tmp_path, content, message):
    path = tmp_path / "g.json"
    path.write_text(content)
    with pytest.raises(ValueError, match=message):
        CircularArch.from_json(path)


def test_missing_json_file(tmp_path):
    with pytest.raises(ValueError, match="cannot read"):
        CircularArch.from_json(tmp_path / "nope.json")
