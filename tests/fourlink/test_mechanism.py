import math

import numpy as np
import pytest

from archquake import irregular_arch
from archquake.fourlink.mechanism import FourLinkMechanism, mechanism_from_hinges
from archquake.geometry import GRAVITY, Hinge
from kinematics_reference import (
    Configurations,
    instantaneous_velocities,
    mirrored_hinges,
    nominal_hinges,
)

SEEDS = [1, 2, 3]


def _pair(arch, hinges):
    return (mechanism_from_hinges(arch, hinges, "l"),
            mechanism_from_hinges(arch.mirrored(), hinges, "r"))


@pytest.fixture(scope="module")
def na_pair(nominal, paper):
    return _pair(nominal, nominal_hinges(paper))


@pytest.fixture(scope="module", params=SEEDS, ids=lambda s: f"seed{s}")
def irregular_pair(request, nominal, paper):
    arch = irregular_arch(nominal, 0.1, rng=request.param)
    return arch, _pair(arch, nominal_hinges(paper))


@pytest.mark.parametrize("side", [0, 1], ids=["mech-l", "mech-r"])
def test_mechanism_matches_paper_table2(na_pair, paper, side):
    mech = na_pair[side]
    table = paper["table2"]["NA"]
    for name in ("theta_u", "theta_bc_u", "theta_cd_u"):
        assert getattr(mech, name) == pytest.approx(table[name], abs=1e-4), name
    for name in ("ab", "bc", "cd"):
        # Table 2 gives the lengths to 0.01 m
        assert getattr(mech, name) == pytest.approx(table[name], abs=0.005 + 1e-9), name


@pytest.mark.parametrize("side", [0, 1], ids=["mech-l", "mech-r"])
def test_critical_angle_matches_paper_table3(na_pair, paper, side):
    mech = na_pair[side]
    table = paper["table3"]["NA"]
    assert mech.theta_cr == pytest.approx(table["theta_cr"], abs=1e-4)
    assert mech.phi_cr == pytest.approx(table["phi_cr"], abs=1e-4)
    assert mech.theta_cr / mech.theta_u == pytest.approx(table["ratio"], abs=1e-3)


def _check_closure(mech):
    theta = np.linspace(mech.theta_limit, mech.theta_u, 801)
    b, c = mech.points(theta)
    d = mech.hinge_points[3]
    assert np.all(np.isfinite(c))
    assert np.hypot(*(c - b).T) == pytest.approx(np.full(theta.size, mech.bc), rel=1e-12)
    assert np.hypot(*(c - d).T) == pytest.approx(np.full(theta.size, mech.cd), rel=1e-12)
    theta_bc, theta_cd = mech.closure(theta)
    # the branch of the undisplaced configuration, followed without jumps
    assert theta_bc[-1] == pytest.approx(mech.theta_bc_u, abs=1e-12)
    assert theta_cd[-1] == pytest.approx(mech.theta_cd_u, abs=1e-12)
    assert np.max(np.abs(np.diff(theta_bc))) < 0.05
    assert np.max(np.abs(np.diff(theta_cd))) < 0.05


def test_closure_keeps_link_lengths_over_whole_range(na_pair, irregular_pair):
    for mech in (*na_pair, *irregular_pair[1]):
        _check_closure(mech)


def test_closure_matches_newton_continuation(irregular_pair):
    arch, (mech_l, _) = irregular_pair
    ref = Configurations(arch, mech_l.hinges)
    for phi in (0.02, 0.3, 0.8):
        theta = mech_l.theta_u - phi
        assert mech_l.closure(theta) == pytest.approx(ref.link_angles(theta), abs=1e-11)


def test_four_bar_rates_match_finite_differences(irregular_pair):
    _, mechs = irregular_pair
    h = 1e-5
    for mech in mechs:
        theta = mech.theta_u - np.array([0.0, 0.05, 0.3, 0.7])
        t2, t3, w2, w3, a2, a3 = mech.rates(theta)
        up, down = mech.closure(theta + h), mech.closure(theta - h)
        assert w2 == pytest.approx((up[0] - down[0]) / (2 * h), rel=1e-7, abs=1e-9)
        assert w3 == pytest.approx((up[1] - down[1]) / (2 * h), rel=1e-7, abs=1e-9)
        assert a2 == pytest.approx((up[0] - 2 * t2 + down[0]) / h**2, rel=1e-4, abs=1e-4)
        assert a3 == pytest.approx((up[1] - 2 * t3 + down[1]) / h**2, rel=1e-4, abs=1e-4)


def test_potential_energy_is_weight_times_height_of_voussoirs(na_pair, irregular_pair):
    for arch, mech in ((na_pair[0].arch, na_pair[0]), (irregular_pair[0], irregular_pair[1][0])):
        ref = Configurations(arch, mech.hinges)
        m = arch.masses
        v_u = GRAVITY * np.sum(m * arch.centroids[:, 1])
        guess = (ref.t2_u, ref.t3_u)
        for theta in np.linspace(mech.theta_u, mech.theta_u - 0.5, 11)[1:]:
            g, _, guess = ref.voussoirs(theta, guess)
            rise = GRAVITY * np.sum(m * g[:, 1]) - v_u
            assert mech.potential_energy(theta) - mech.potential_energy(mech.theta_u) == \
                pytest.approx(rise, rel=1e-10, abs=1e-6)


def test_potential_energy_has_its_maximum_at_critical_angle(na_pair, irregular_pair):
    for mech in (*na_pair, *irregular_pair[1]):
        theta = np.linspace(mech.theta_limit, mech.theta_u, 4001)
        v = mech.potential_energy(theta)
        assert mech.potential_energy(mech.theta_cr) >= v.max() - 1e-9 * abs(v).max()
        h = 1e-6
        slope = (mech.potential_energy(mech.theta_cr + h)
                 - mech.potential_energy(mech.theta_cr - h)) / (2 * h)
        assert abs(slope) < 1e-6 * mech.block_masses.sum() * GRAVITY
        # V rises from the undisplaced configuration up to theta_cr (recovery side)
        assert mech.theta_limit < mech.theta_cr < mech.theta_u
        assert mech.potential_energy(mech.theta_cr) > mech.potential_energy(mech.theta_u)


def test_kinematic_limit_of_oppenheim_arch_is_where_hinge_d_closes(na_pair):
    mech = na_pair[0]
    # at the limit block CD is back to its undisplaced orientation: joint D closes again
    _, theta_cd = mech.closure(mech.theta_limit)
    assert theta_cd == pytest.approx(mech.theta_cd_u, abs=1e-10)
    # before that every hinge keeps opening its joint (signs of an admissible mechanism)
    theta = np.linspace(mech.theta_limit, mech.theta_u, 1001)[1:-1]
    rot = mech.hinge_rotations(theta)
    assert np.all(np.sign(rot) == np.array([-1, 1, -1, 1]))
    # the four-bar dead point (|BD| = BC + CD, closed form) lies further on
    a, d = mech.hinge_points[0], mech.hinge_points[3]
    ad, gamma = np.hypot(*(d - a)), math.atan2(d[1] - a[1], d[0] - a[0])
    cosine = (ad**2 + mech.ab**2 - (mech.bc + mech.cd) ** 2) / (2 * mech.ab * ad)
    dead_point = gamma - math.acos(cosine)
    assert dead_point < mech.theta_limit
    assert mech.theta_u - mech.theta_limit == pytest.approx(1.0089, abs=1e-3)


def test_mech_r_of_symmetric_arch_is_mirror_of_mech_l(na_pair):
    mech_l, mech_r = na_pair
    for name in ("theta_u", "theta_bc_u", "theta_cd_u", "ab", "bc", "cd", "theta_cr",
                 "theta_limit", "activation_g"):
        assert getattr(mech_r, name) == pytest.approx(getattr(mech_l, name), abs=1e-12), name
    v_l, w_l = mech_l.mode_shape()
    v_r, w_r = mech_r.mode_shape()
    assert v_r == pytest.approx(v_l[::-1] * [-1.0, 1.0], abs=1e-10)
    assert w_r == pytest.approx(-w_l[::-1], abs=1e-12)


def test_mode_shape_matches_instantaneous_centres(irregular_pair):
    arch, (mech_l, mech_r) = irregular_pair
    v, w = instantaneous_velocities(arch, mech_l.hinges)
    got_v, got_w = mech_l.mode_shape()
    assert got_v == pytest.approx(v, abs=1e-10)
    assert got_w == pytest.approx(w, abs=1e-12)
    # Mech-r in the original frame: its block AB is the rightmost block there and turns at -1
    hinges = mirrored_hinges(arch, mech_r.hinges)
    v, w = instantaneous_velocities(arch, hinges)
    scale = -1.0 / w[hinges[3].joint - 1]
    v, w = scale * v, scale * w
    got_v, got_w = mech_r.mode_shape()
    assert got_v == pytest.approx(v, abs=1e-10)
    assert got_w == pytest.approx(w, abs=1e-12)
    # voussoirs outside the hinges do not move
    short = mechanism_from_hinges(arch, (Hinge(1, "intrados"), *mech_l.hinges[1:3],
                                         Hinge(6, "extrados")))
    v, w = short.mode_shape()
    assert np.all(v[[0, 6]] == 0.0) and np.all(w[[0, 6]] == 0.0)


def test_nominal_mechanism_is_admissible_and_reversed_faces_are_not(na_pair):
    assert na_pair[0].is_admissible and na_pair[1].is_admissible
    flipped = tuple(Hinge(h.joint, "extrados" if h.face == "intrados" else "intrados")
                    for h in na_pair[0].hinges)
    assert not mechanism_from_hinges(na_pair[0].arch, flipped).is_admissible


def test_invalid_mechanisms_raise(nominal, paper):
    hinges = nominal_hinges(paper)
    with pytest.raises(ValueError, match="direction"):
        mechanism_from_hinges(nominal, hinges, "up")
    with pytest.raises(ValueError, match="strictly increasing"):
        mechanism_from_hinges(nominal, (hinges[1], hinges[0], hinges[2], hinges[3]))
    with pytest.raises(ValueError, match=r"in \[0, 7\]"):
        mechanism_from_hinges(nominal, (*hinges[:3], Hinge(8, "extrados")))
    with pytest.raises(ValueError, match="four Hinge"):
        mechanism_from_hinges(nominal, hinges[:3])
    with pytest.raises(ValueError, match="CircularArch"):
        FourLinkMechanism("arch", hinges)
