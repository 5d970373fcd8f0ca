import itertools
import math

import numpy as np
import pytest

from archquake import circular_arch, irregular_arch, oppenheim
from archquake.fourlink.impact import (
    RESTITUTION_MODELS,
    computed_restitution,
    generalised_momentum,
    kinetic_energy_ratio,
    restitution,
    velocity_after_impact,
)
from archquake.fourlink.mechanism import mechanism_from_hinges, mechanisms
from archquake.geometry import Hinge
from kinematics_reference import (
    instantaneous_velocities,
    mirrored_hinges,
    nominal_hinges,
    virtual_work_multiplier,
)

FACES = ("intrados", "extrados", "intrados", "extrados")


def _pair(arch, hinges):
    return (mechanism_from_hinges(arch, hinges, "l"),
            mechanism_from_hinges(arch.mirrored(), hinges, "r"))


def _impulse_momentum_restitution(arch, hinges_before, hinges_after, after_rate_block):
    """c_v from the impulse-momentum equations of the three post-impact blocks.

    Unknowns: theta'_f and the impulses (x, y) at the four post-impact hinges; equations: linear
    and angular momentum of each post-impact block. Pre-impact: block AB of the pre-impact
    mechanism turns at theta'_i = 1 about A. Post-impact velocities per unit theta'_f: block
    ``after_rate_block`` (0 = leftmost, 2 = rightmost) turns at -1 (Mech-r's block A'B', seen
    in the original frame).
    """
    v, w = instantaneous_velocities(arch, hinges_before)
    u, om = instantaneous_velocities(arch, hinges_after)
    joints = [h.joint for h in hinges_after]
    first = (joints[0], joints[1], joints[2])[after_rate_block]
    scale = -1.0 / om[first]
    u, om = u * scale, om * scale
    pts = [h.point(arch) for h in hinges_after]
    m, inertia, g = arch.masses, arch.inertias, arch.centroids

    def cross(a, b):
        return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]

    a_mat = np.zeros((9, 9))
    rhs = np.zeros(9)
    for k in range(3):
        lo, hi = joints[k], joints[k + 1]
        sl = slice(lo, hi)
        rows = slice(3 * k, 3 * k + 3)
        # momentum after (coefficient of theta'_f) minus momentum before = impulses
        lin_u = np.sum(m[sl, None] * u[sl], axis=0)
        ang_u = np.sum(m[sl] * cross(g[sl], u[sl]) + inertia[sl] * om[sl])
        lin_v = np.sum(m[sl, None] * v[sl], axis=0)
        ang_v = np.sum(m[sl] * cross(g[sl], v[sl]) + inertia[sl] * w[sl])
        a_mat[rows, 0] = [lin_u[0], lin_u[1], ang_u]
        rhs[rows] = [lin_v[0], lin_v[1], ang_v]
        for hinge, sign in ((k, 1.0), (k + 1, -1.0)):  # +J on the right block, -J on the left
            col = 1 + 2 * hinge
            p = pts[hinge]
            a_mat[3 * k, col] -= sign
            a_mat[3 * k + 1, col + 1] -= sign
            a_mat[3 * k + 2, col] -= sign * -p[1]
            a_mat[3 * k + 2, col + 1] -= sign * p[0]
    solution = np.linalg.solve(a_mat, rhs)
    return -solution[0]


def test_computed_restitution_of_oppenheim_arch(nominal, paper):
    hinges = nominal_hinges(paper)
    mech_l, mech_r = _pair(nominal, hinges)
    c = computed_restitution(mech_l, mech_r)
    independent = _impulse_momentum_restitution(nominal, hinges,
                                                mirrored_hinges(nominal, hinges), 2)
    assert c == pytest.approx(independent, rel=1e-10)
    assert c == pytest.approx(0.6450, abs=1e-4)
    # symmetric arch: the same both ways; the paper's 0.875 is not what this model gives
    assert computed_restitution(mech_r, mech_l) == pytest.approx(c, rel=1e-12)
    assert abs(c - paper["dynamics"]["NA"]["restitution_paper"]) > 0.2
    # M_to from the mode shape is the M of the equation of motion
    assert generalised_momentum(mech_r, mech_r) == pytest.approx(
        mech_r.coefficients(mech_r.theta_u)[0], rel=1e-12)


@pytest.mark.parametrize("seed", [1, 2, 3, 4, 5])
def test_impact_never_creates_energy_on_irregular_arches(nominal, paper, seed):
    arch = irregular_arch(nominal, 0.1, rng=seed)
    hinges = nominal_hinges(paper)
    mech_l, mech_r = _pair(arch, hinges)
    for before, after in ((mech_l, mech_r), (mech_r, mech_l)):
        c = computed_restitution(before, after)
        assert 0.0 < c < 1.0
        ratio = kinetic_energy_ratio(before, after)
        assert 0.0 < ratio <= 1.0
        assert ratio == pytest.approx(c**2 * before.coefficients(before.theta_u)[0] ** -1
                                      * after.coefficients(after.theta_u)[0], rel=1e-12)
    # the independent impulse-momentum solution, Mech-l -> Mech-r
    independent = _impulse_momentum_restitution(arch, hinges, mirrored_hinges(arch, hinges), 2)
    assert computed_restitution(mech_l, mech_r) == pytest.approx(independent, rel=1e-9)


def test_continuous_limit_of_restitution():
    """With 70 voussoirs and the hinges of the least kinematic multiplier, c_v is about 0.73."""
    arch = circular_arch(10.0, math.radians(157.5), 1.5, 70)
    joints = (1, 26, 52, 70)
    hinges = tuple(Hinge(j, f) for j, f in zip(joints, FACES, strict=True))
    k = virtual_work_multiplier(arch, hinges)
    # a local minimum of the kinematic multiplier among admissible neighbouring hinge sets
    for step in itertools.product((-1, 0, 1), repeat=4):
        near = tuple(min(max(j + s, 0), 70) for j, s in zip(joints, step, strict=True))
        if near == joints or len(set(near)) < 4:
            continue
        near_hinges = tuple(Hinge(j, f) for j, f in zip(near, FACES, strict=True))
        if mechanism_from_hinges(arch, near_hinges).is_admissible:
            assert virtual_work_multiplier(arch, near_hinges) > k
    mech_l, mech_r = _pair(arch, hinges)
    assert k == pytest.approx(0.3535, abs=1e-4)
    assert computed_restitution(mech_l, mech_r) == pytest.approx(0.736, abs=1e-3)


def test_velocity_after_impact_moves_into_the_other_mechanism():
    assert velocity_after_impact(2.0, 0.6) == pytest.approx(-1.2)


def test_restitution_registry(nominal, paper):
    hinges = nominal_hinges(paper)
    nominal_pair = _pair(nominal, hinges)
    arch = irregular_arch(nominal, 0.1, rng=11)
    pair = _pair(arch, hinges)
    c_nominal = computed_restitution(*nominal_pair)
    assert restitution("computed", *pair) == (computed_restitution(*pair),
                                              computed_restitution(pair[1], pair[0]))
    assert restitution("nominal", *pair, nominal=nominal_pair) == pytest.approx(
        (c_nominal, c_nominal), rel=1e-12)
    assert restitution("paper", *pair) == (paper["dynamics"]["NA"]["restitution_paper"],) * 2
    assert restitution("elastic", *pair) == (1.0, 1.0)
    assert restitution(0.875, *pair) == (0.875, 0.875)
    assert restitution(1, *pair) == (1.0, 1.0)
    assert set(RESTITUTION_MODELS) >= {"computed", "nominal", "paper", "elastic"}


@pytest.mark.parametrize("bad", [0.0, -0.5, 1.5, float("nan"), True, None, [0.8]])
def test_restitution_rejects_values_outside_unit_interval(nominal, paper, bad):
    pair = _pair(nominal, nominal_hinges(paper))
    with pytest.raises(ValueError, match=r"\(0, 1\]"):
        restitution(bad, *pair)


def test_restitution_unknown_name_lists_the_models(nominal, paper):
    pair = _pair(nominal, nominal_hinges(paper))
    with pytest.raises(ValueError, match="computed.*elastic.*nominal.*paper"):
        restitution("housner", *pair)
    with pytest.raises(ValueError, match="nominal="):
        restitution("nominal", *pair)


def test_mechanisms_of_different_arches_are_rejected(nominal, paper):
    hinges = nominal_hinges(paper)
    other = irregular_arch(nominal, 0.1, rng=1)
    with pytest.raises(ValueError, match="same arch"):
        computed_restitution(mechanism_from_hinges(nominal, hinges),
                             mechanism_from_hinges(other.mirrored(), hinges, "r"))


def _sector_properties(arch, i, rings=200, slices=400):
    """Mass [kg/m], centroid [m], centroidal inertia [kg m] of voussoir i by midpoint-rule
    integration over its annular sector (independent of the closed forms of geometry.py)."""
    b0, b1 = arch.joint_angles[i], arch.joint_angles[i + 1]
    r = np.linspace(arch.inner_radii[i], arch.outer_radii[i], rings + 1)
    b = np.linspace(b0, b1, slices + 1)
    rc, bc = np.meshgrid(0.5 * (r[1:] + r[:-1]), 0.5 * (b[1:] + b[:-1]), indexing="ij")
    dm = arch.density * rc * np.diff(r)[:, None] * np.diff(b)[None, :]
    x, y = -rc * np.cos(bc), rc * np.sin(bc)
    m = dm.sum()
    g = np.array([(dm * x).sum(), (dm * y).sum()]) / m
    inertia = (dm * ((x - g[0]) ** 2 + (y - g[1]) ** 2)).sum()
    return m, g, inertia


def _trapezoid_properties(arch, i):
    """The same for a flat-faced voussoir: the quadrilateral of its four joint ends (shoelace
    formulas for area, first and second moments)."""
    b0, b1 = arch.joint_angles[i], arch.joint_angles[i + 1]
    ri, ro = arch.inner_radii[i], arch.outer_radii[i]
    pts = np.array([[-r * np.cos(b), r * np.sin(b)] for r, b in
                    ((ri, b0), (ri, b1), (ro, b1), (ro, b0))])
    x, y = pts[:, 0], pts[:, 1]
    x1, y1 = np.roll(x, -1), np.roll(y, -1)
    c = x * y1 - x1 * y
    area = c.sum() / 2
    g = np.array([((x + x1) * c).sum(), ((y + y1) * c).sum()]) / (6 * area)
    polar = ((x * x + x * x1 + x1 * x1 + y * y + y * y1 + y1 * y1) * c).sum() / 12
    m = arch.density * abs(area)
    return m, g, arch.density * abs(polar) - m * g @ g


def _housner(properties, a, a_prime):
    """omega'/omega of a rigid body turning about a, then about a_prime, with its angular
    momentum about a_prime conserved (Housner 1963, for a block: 1 - 1.5 sin^2 alpha)."""
    num = sum(inertia + m * (g - a_prime) @ (g - a) for m, g, inertia in properties)
    den = sum(inertia + m * (g - a_prime) @ (g - a_prime) for m, g, inertia in properties)
    return num / den


def test_link_restitution_is_housners_rule_for_the_post_impact_link(nominal):
    """The model 'link' [paper, Sect. 4.4]: the post-impact link A'B' of Oppenheim's arch
    (voussoirs 0-1, between the springing joint 0 and Mech-r's hinge at joint 2) turns first about
    A (joint 0, intrados) with AB, then about A' (joint 0, extrados). Computed here from the
    voussoirs' own integration and the joint ends; with flat faces it is the paper's 0.875."""
    mech_l, mech_r = mechanisms(nominal)
    assert [h.joint for h in mech_r.hinges][2:] == [5, 7]  # mirrored frame: joints 2, 0
    a = np.array([-nominal.inner_radii[0] * np.cos(nominal.joint_angles[0]),
                  nominal.inner_radii[0] * np.sin(nominal.joint_angles[0])])
    a_prime = a * nominal.outer_radii[0] / nominal.inner_radii[0]
    annular = _housner([_sector_properties(nominal, i) for i in (0, 1)], a, a_prime)
    c_lr, c_rl = restitution("link", mech_l, mech_r)
    assert c_lr == pytest.approx(annular, rel=1e-6)
    assert c_rl == pytest.approx(c_lr, rel=1e-12)  # symmetric arch
    assert c_lr == pytest.approx(0.883, abs=5e-4)
    flat = _housner([_trapezoid_properties(nominal, i) for i in (0, 1)], a, a_prime)
    assert round(flat, 3) == 0.875
    # a single rectangular block reduces to Housner's closed form
    b, h = 0.4, 2.0
    corner, other = np.array([0.0, 0.0]), np.array([b, 0.0])
    block = [(1.0, np.array([b / 2, h / 2]), (b * b + h * h) / 12)]
    alpha = np.arctan(b / h)
    assert _housner(block, corner, other) == pytest.approx(1 - 1.5 * np.sin(alpha) ** 2)


def test_link_restitution_of_irregular_arches_matches_the_rigid_body_rule():
    """On irregular arches A'B' may differ from AB and A' need not face A exactly: the package
    uses the pre-impact velocity field; where A'B' lies inside AB it is Housner's rule again."""
    checked = 0
    for seed in range(12):
        arch = irregular_arch(oppenheim(), 0.1, rng=seed)
        mech_l, mech_r = mechanisms(arch)
        n = arch.n_voussoirs
        ja, jb = mech_l.hinges[0].joint, mech_l.hinges[1].joint
        first, last = n - mech_r.hinges[3].joint, n - mech_r.hinges[2].joint
        if not (ja <= first and last <= jb):
            continue
        a = mech_l.hinge_points[0]
        a_prime = mech_r.hinge_points[3] * np.array([-1.0, 1.0])
        props = [(arch.masses[i], arch.centroids[i], arch.inertias[i]) for i in
                 range(first, last)]
        assert restitution("link", mech_l, mech_r)[0] == pytest.approx(
            _housner(props, a, a_prime), rel=1e-10)
        checked += 1
    assert checked >= 8


def test_mechanism_command_prints_the_link_wise_coefficients(capsys):
    import json

    from archquake.cli import main

    assert main(["mechanism", "--restitution", "link", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)["restitution"]
    expected = restitution("link", *mechanisms(oppenheim()))
    assert (out["l_to_r"], out["r_to_l"]) == pytest.approx(expected, rel=1e-12)
    assert out["l_to_r"] == pytest.approx(0.883, abs=5e-4)
