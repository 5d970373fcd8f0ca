import json
import math

import numpy as np
import pytest

from archquake import circular_arch, oppenheim
from archquake.cli import main
from archquake.geometry import FACES, GRAVITY, irregular_sample
from archquake.limit_analysis import (
    AGREEMENT_TOLERANCE,
    _mechanisms,
    both_directions,
    limit_analysis,
    limit_sample,
    load_multipliers,
    load_multipliers_of,
    min_thickness,
    self_weight_margin,
)

DIRECTIONS = ("l", "r")
METHODS = ("static", "kinematic")


@pytest.fixture(scope="module")
def irregular_arches(nominal):
    """200 irregular Oppenheim arches, epsilon = 0.10 as in the paper."""
    return irregular_sample(nominal, 0.10, 200, seed=2024)


# ------------------------------------------------------------------ paper, Table 1
@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("direction", DIRECTIONS)
def test_oppenheim_load_multiplier_matches_paper_table1(nominal, paper, direction, method):
    result = limit_analysis(nominal, direction, method)
    assert result.load_multiplier == pytest.approx(paper["table1"]["NA"]["load_multiplier"],
                                                   abs=1e-3)


@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("direction", DIRECTIONS)
def test_oppenheim_hinges_match_paper_table1(nominal, paper, direction, method):
    table = paper["table1"]["NA"]
    result = limit_analysis(nominal, direction, method)
    assert [h.joint for h in result.hinges] == table["joints"]
    assert [h.face for h in result.hinges] == table["faces"]
    assert result.hinge_angles == pytest.approx(table["beta"], abs=1e-4)
    assert result.is_four_hinge and result.separation is None
    assert result.direction == direction and result.method == method


def test_nominal_arch_has_equal_multipliers_in_both_directions(nominal):
    left, right = both_directions(nominal)
    assert left.load_multiplier == pytest.approx(right.load_multiplier, abs=1e-12)
    assert left.hinges == right.hinges
    assert right.arch.is_symmetric()


def test_mech_r_is_mech_l_of_the_mirrored_arch(irregular_arches):
    arch = irregular_arches[0]
    right = limit_analysis(arch, "r")
    mirrored_left = limit_analysis(arch.mirrored(), "l")
    assert right.load_multiplier == pytest.approx(mirrored_left.load_multiplier, abs=1e-12)
    assert right.hinges == mirrored_left.hinges
    assert right.arch.joint_angles == pytest.approx(arch.mirrored().joint_angles, abs=1e-15)


# ------------------------------------------------------------------ static vs kinematic
def test_static_and_kinematic_agree_on_nominal_arch(nominal):
    for direction in DIRECTIONS:
        static = limit_analysis(nominal, direction, "static")
        kinematic = limit_analysis(nominal, direction, "kinematic")
        assert abs(static.load_multiplier - kinematic.load_multiplier) <= AGREEMENT_TOLERANCE
        assert static.hinges == kinematic.hinges


def test_static_and_kinematic_agree_on_200_irregular_arches(irregular_arches):
    """Uniqueness theorem: lower bound (LP) = upper bound (mechanisms), same hinges."""
    worst = 0.0
    for arch in irregular_arches:
        for direction in DIRECTIONS:
            static = limit_analysis(arch, direction, "static")
            kinematic = limit_analysis(arch, direction, "kinematic")
            worst = max(worst, abs(static.load_multiplier - kinematic.load_multiplier))
            assert static.hinges == kinematic.hinges
    assert worst <= AGREEMENT_TOLERANCE


@pytest.mark.parametrize(
    ("embrace_over_pi", "thickness", "separation", "faces"),
    [
        # thick arches under large loads: the left springing lifts off its support
        (0.5, 0.2, 0, ("intrados", "extrados")),
        # a middle block hinged on the intrados at both ends (non-alternating faces)
        (0.6, 0.5, None, ("extrados", "intrados", "intrados", "extrados")),
    ],
)
def test_static_and_kinematic_agree_beyond_alternating_four_hinge_mechanisms(
    embrace_over_pi, thickness, separation, faces,
):
    arch = circular_arch(1.0, embrace_over_pi * math.pi, thickness, 7)
    static = limit_analysis(arch, "l", "static")
    kinematic = limit_analysis(arch, "l", "kinematic")
    assert static.load_multiplier == pytest.approx(kinematic.load_multiplier, rel=1e-10)
    assert static.load_multiplier > 1.0
    assert static.hinges == kinematic.hinges
    assert static.separation == kinematic.separation == separation
    assert tuple(h.face for h in static.hinges) == faces
    if separation is not None:
        assert np.isnan(static.thrust_line.radii[separation])
        # no normal force: the force at the separating joint lies along the (radial) joint
        beta = arch.joint_angles[separation]
        force = static.thrust_line.forces[separation]
        normal = math.sin(beta) * force[0] + math.cos(beta) * force[1]
        assert abs(normal) <= 1e-9 * arch.total_mass * GRAVITY


def test_kinematic_mechanism_equilibrium_is_statically_admissible(irregular_arches):
    """The thrust line through the kinematic method's hinges fits inside every joint: the
    upper bound is also a lower bound, independently of the linear program."""
    for arch in irregular_arches[:50]:
        result = limit_analysis(arch, "r", "kinematic")
        inner, outer = result.arch.joint_extents()
        depth = outer - inner
        r = result.thrust_line.radii
        assert np.all(r >= inner - 1e-9 * depth) and np.all(r <= outer + 1e-9 * depth)


def test_sample_static_and_kinematic_agree(nominal):
    static = limit_sample(nominal, 0.10, 30, seed=5, method="static")
    kinematic = limit_sample(nominal, 0.10, 30, seed=5, method="kinematic")
    assert np.max(np.abs(static.load_multiplier_l - kinematic.load_multiplier_l)) <= 1e-9
    assert np.max(np.abs(static.load_multiplier_r - kinematic.load_multiplier_r)) <= 1e-9


def test_batched_kinematic_multipliers_equal_one_by_one(nominal):
    # arches of two sizes in one call, and more than one batch of the same size
    arches = (list(irregular_sample(nominal, 0.10, 70, 4))
              + list(irregular_sample(circular_arch(5.0, math.pi, 0.6, 9), 0.1, 3, 1)))
    together = load_multipliers_of(arches, "kinematic")
    alone = np.array([load_multipliers(a, "kinematic") for a in arches])
    assert np.array_equal(together, alone)
    static = load_multipliers_of(arches[:5], "static")
    assert np.max(np.abs(static - together[:5])) <= 1e-9


# ------------------------------------------------------------------ thrust line
@pytest.mark.parametrize("direction", DIRECTIONS)
def test_thrust_line_inside_every_joint_and_on_the_face_at_hinges(irregular_arches, direction):
    for arch in [*irregular_arches[:20], oppenheim()]:
        result = limit_analysis(arch, direction)
        inner, outer = result.arch.joint_extents()
        depth = outer - inner
        r = result.thrust_line.radii
        assert np.all(r >= inner - 1e-9 * depth)
        assert np.all(r <= outer + 1e-9 * depth)
        for hinge in result.hinges:
            assert r[hinge.joint] == pytest.approx(hinge.radius(result.arch),
                                                   abs=1e-7 * depth[hinge.joint])
        hinge_joints = {h.joint for h in result.hinges}
        others = [j for j in range(arch.n_voussoirs + 1) if j not in hinge_joints]
        # elsewhere the line of thrust is strictly inside (unique collapse state)
        assert np.all(np.minimum(r - inner, outer - r)[others] > 1e-6 * depth[others])
        assert result.hinge_points == pytest.approx(
            result.thrust_line.points[[h.joint for h in result.hinges]], abs=1e-6)
        assert result.thrust_line.points == pytest.approx(
            np.column_stack((-r * np.cos(result.arch.joint_angles),
                             r * np.sin(result.arch.joint_angles))), abs=1e-12)


def test_joint_forces_balance_the_loads_and_are_compressive(nominal):
    result = limit_analysis(nominal, "l")
    arch, k = result.arch, result.load_multiplier
    forces = result.thrust_line.forces
    weight = arch.masses * GRAVITY
    # voussoir i: F_i - F_{i+1} + m_i g (k, -1) = 0
    residual = forces[:-1] - forces[1:] + np.column_stack((k * weight, -weight))
    assert np.abs(residual).max() <= 1e-9 * arch.total_mass * GRAVITY
    beta = arch.joint_angles
    normal = np.sin(beta) * forces[:, 0] + np.cos(beta) * forces[:, 1]
    assert np.all(normal > 0)
    # overall: the support reactions carry the whole weight and the whole horizontal load
    assert forces[0, 1] - forces[-1, 1] == pytest.approx(arch.total_mass * GRAVITY, rel=1e-12)
    assert forces[-1, 0] - forces[0, 0] == pytest.approx(k * arch.total_mass * GRAVITY,
                                                         rel=1e-12)


def test_funicular_polygon_turns_at_the_load_lines(irregular_arches):
    """Inside each voussoir the resultant changes direction only on its load's line of action,
    and the segment leaving the vertex passes through the next pressure point (moment balance)."""
    result = limit_analysis(irregular_arches[3], "l")
    poly = result.funicular()
    arch, k = result.arch, result.load_multiplier
    pts, forces = result.thrust_line.points, result.thrust_line.forces
    q = poly[1::2]
    load = np.array([k, -1.0])
    to_centroid = q - arch.centroids
    assert np.abs(to_centroid[:, 0] * load[1] - to_centroid[:, 1] * load[0]).max() < 1e-9
    to_next = pts[1:] - q
    cross = to_next[:, 0] * forces[1:, 1] - to_next[:, 1] * forces[1:, 0]
    assert np.abs(cross).max() <= 1e-9 * np.abs(forces).max()


# ------------------------------------------------------------------ minimum thickness
def test_semicircular_arch_minimum_thickness_matches_closed_form(paper):
    """200 joints: the discrete hinge positions are within 0.45 deg of the continuous ones,
    which changes t/R by less than 1e-4; the reference is quoted to 4 digits (+-5e-5)."""
    ratio = min_thickness(1.0, math.pi, 200) / 1.0
    assert ratio == pytest.approx(paper["closed_form"]["semicircle_min_thickness_ratio"],
                                  abs=2e-4)


def test_minimum_thickness_is_where_self_weight_just_stands(nominal):
    radius, embrace, n = 10.0, nominal.embrace, nominal.n_voussoirs
    t_min = min_thickness(radius, embrace, n)
    # 1e-4 relative: well beyond the linear program's feasibility tolerance (1e-7)
    above = circular_arch(radius, embrace, t_min * (1 + 1e-4), n)
    below = circular_arch(radius, embrace, t_min * (1 - 1e-4), n)
    k_above = limit_analysis(above).load_multiplier
    assert 0.0 <= k_above < 1e-3
    with pytest.raises(ValueError, match="cannot stand"):
        limit_analysis(below)
    assert math.isnan(load_multipliers(below)[0])
    # the kinematic method sees a self-weight mechanism with a negative multiplier: both
    # methods refuse it as a collapse threshold, the sample path reports the number
    with pytest.raises(ValueError, match="cannot stand under its own weight"):
        limit_analysis(below, method="kinematic")
    assert load_multipliers(below, "kinematic")[0] < 0.0
    assert limit_analysis(above, method="kinematic").load_multiplier == pytest.approx(
        k_above, abs=1e-9)
    assert self_weight_margin(above) > 0.0 > self_weight_margin(below)


def test_minimum_thickness_of_a_shallow_arch_that_stands_as_a_strut():
    # embrace 10 degrees: above its rise the arch stands under any thrust (unbounded margin);
    # the minimum thickness is still where it stops standing
    embrace = math.radians(10)
    assert self_weight_margin(circular_arch(1.0, embrace, 0.5, 7)) == math.inf
    t_min = min_thickness(1.0, embrace, 7)
    assert 0 < t_min < 1.0 - math.cos(embrace / 2)  # below the rise
    limit_analysis(circular_arch(1.0, embrace, t_min * (1 + 1e-3), 7))  # stands
    with pytest.raises(ValueError, match="cannot stand"):
        limit_analysis(circular_arch(1.0, embrace, t_min * (1 - 1e-3), 7))


def test_minimum_thickness_scales_with_radius():
    assert min_thickness(7.0, math.radians(140), 9) == pytest.approx(
        7.0 * min_thickness(1.0, math.radians(140), 9), rel=1e-9)


# ------------------------------------------------------------------ sample
def test_limit_sample_arch_i_independent_of_sample_size(nominal):
    small = limit_sample(nominal, 0.10, 3, seed=11)
    large = limit_sample(nominal, 0.10, 8, seed=11)
    assert large.load_multiplier_l[:3] == pytest.approx(small.load_multiplier_l, abs=0)
    assert large.load_multiplier == pytest.approx(
        np.minimum(large.load_multiplier_l, large.load_multiplier_r), abs=0)
    arch = irregular_sample(nominal, 0.10, 8, 11)[5]
    assert load_multipliers(arch) == pytest.approx(
        (large.load_multiplier_l[5], large.load_multiplier_r[5]), abs=1e-12)


def test_limit_sample_with_zero_tolerance_is_the_nominal_multiplier(nominal, paper):
    sample = limit_sample(nominal, 0.0, 4, seed=1)
    assert sample.load_multiplier == pytest.approx(
        [paper["table1"]["NA"]["load_multiplier"]] * 4, abs=1e-3)


# ------------------------------------------------------------------ bad input
@pytest.mark.parametrize(
    ("call", "name"),
    [
        (lambda a: limit_analysis(a, direction="left"), "direction"),
        (lambda a: limit_analysis(a, method="lp"), "method"),
        (lambda a: both_directions(a, method="simplex"), "method"),
        (lambda a: limit_sample(a, 0.1, -1, seed=0), "sample_size"),
        (lambda a: limit_sample(a, 0.1, 2.5, seed=0), "sample_size"),
        (lambda a: limit_sample(a, 1.5, 2, seed=0), "epsilon"),
        (lambda a: limit_sample(a, 0.1, 2, seed=0, method="x"), "method"),
        (lambda a: irregular_sample(a, 0.1, -3, seed=0), "sample_size"),
        (lambda a: irregular_sample(a, 0.1, 3, seed=-1), "seed"),
        (lambda a: limit_analysis("arch"), "arch"),
        (lambda a: min_thickness(-1.0, math.pi, 10), "radius"),
        (lambda a: min_thickness(1.0, math.pi, 2), "voussoirs"),
    ],
)
def test_bad_input_names_the_parameter(nominal, call, name):
    with pytest.raises(ValueError, match=name):
        call(nominal)


def test_arch_that_never_collapses_is_reported():
    thick_flat = circular_arch(1.0, math.radians(40), 0.5, 6)
    with pytest.raises(ValueError, match="does not collapse"):
        limit_analysis(thick_flat)
    with pytest.raises(ValueError, match="does not collapse"):
        limit_analysis(thick_flat, method="kinematic")
    assert load_multipliers(thick_flat) == (math.inf, math.inf)
    assert load_multipliers(thick_flat, "kinematic") == (math.inf, math.inf)


def test_static_method_solves_an_arch_of_ten_thousand_voussoirs():
    # Oppenheim's arch cut into 10 000 voussoirs: the linear program has 30 004 unknowns
    arch = circular_arch(10.0, math.radians(157.38), 1.0, 10_000)
    result = limit_analysis(arch, "l")
    k = result.load_multiplier
    # lower bound: the line of thrust balances the loads and lies inside every joint
    weight = arch.masses * GRAVITY
    forces = result.thrust_line.forces
    residual = forces[:-1] - forces[1:] + np.column_stack((k * weight, -weight))
    assert np.abs(residual).max() <= 1e-9 * arch.total_mass * GRAVITY
    inner, outer = arch.joint_extents()
    r = result.thrust_line.radii
    assert np.all((r >= inner - 1e-9 * (outer - inner)) & (r <= outer + 1e-9 * (outer - inner)))
    # upper bound: its hinges form a mechanism whose virtual work gives the same multiplier
    assert result.is_four_hinge
    joints = np.array([h.joint for h in result.hinges])
    mech = _mechanisms(arch, candidate_joints=joints)
    faces = [FACES.index(h.face) for h in result.hinges]
    match = np.all(mech.joints == joints, axis=1) & np.all(mech.faces == faces, axis=1)
    assert mech.k[match] == pytest.approx(k, rel=1e-9)
    # and the multiplier converges from the coarse arches toward the fine one
    coarse = [load_multipliers(circular_arch(10.0, math.radians(157.38), 1.0, n))[0]
              for n in (500, 2000)]
    assert abs(coarse[1] - k) < abs(coarse[0] - k) < 1e-3


def test_kinematic_method_refuses_huge_enumerations():
    with pytest.raises(ValueError, match="voussoirs"):
        limit_analysis(circular_arch(1.0, math.pi, 0.2, 80), method="kinematic")
    with pytest.raises(ValueError, match="voussoirs"):  # the sample path, before any array
        load_multipliers(circular_arch(1.0, math.pi, 0.2, 200), method="kinematic")


# ------------------------------------------------------------------ command line
def test_cli_limit_json_matches_paper(capsys, paper):
    assert main(["limit", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    table = paper["table1"]["NA"]
    assert out["k"] == pytest.approx(table["load_multiplier"], abs=1e-3)
    assert out["k"] == min(out["k_l"], out["k_r"])
    for direction in DIRECTIONS:
        hinges = out["mechanisms"][direction]["hinges"]
        assert [h["joint"] for h in hinges] == table["joints"]
        assert [h["face"] for h in hinges] == table["faces"]
        assert [h["beta"] for h in hinges] == pytest.approx(table["beta"], abs=1e-4)


def test_cli_limit_text_table_has_units(capsys):
    assert main(["limit"]) == 0
    out = capsys.readouterr().out
    assert "Mech-l" in out and "Mech-r" in out
    assert "beta [rad]" in out and "0.3700" in out and "[m]" in out


def test_cli_limit_irregular_arch_is_reproducible_and_matches_library(capsys, nominal):
    argv = ["limit", "--json", "--epsilon", "0.1", "--seed", "7"]
    assert main(argv) == 0
    first = json.loads(capsys.readouterr().out)
    assert main(argv) == 0
    assert json.loads(capsys.readouterr().out) == first
    from archquake.geometry import irregular_arch
    k_l, k_r = load_multipliers(irregular_arch(nominal, 0.1, rng=7))
    assert first["k_l"] == pytest.approx(k_l, abs=1e-12)
    assert first["k_r"] == pytest.approx(k_r, abs=1e-12)


def test_cli_limit_geometry_file(capsys, tmp_path, nominal):
    arch = irregular_sample(nominal, 0.1, 1, 3)[0]
    path = tmp_path / "arch.json"
    path.write_text(json.dumps(arch.to_dict()))
    assert main(["limit", "--json", "--geometry", str(path)]) == 0
    out = json.loads(capsys.readouterr().out)
    assert (out["k_l"], out["k_r"]) == pytest.approx(load_multipliers(arch), abs=1e-12)


def test_cli_min_thickness(capsys):
    assert main(["min-thickness", "--json", "--radius", "2", "--embrace", "180",
                 "--voussoirs", "40"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["ratio"] == pytest.approx(out["min_thickness"] / 2.0)
    assert out["min_thickness"] == pytest.approx(min_thickness(2.0, math.pi, 40), rel=1e-9)
    assert main(["min-thickness"]) == 0
    assert "t_min" in capsys.readouterr().out


def test_cli_plot_writes_png(tmp_path, capsys):
    path = tmp_path / "limit.png"
    assert main(["limit", "--epsilon", "0.1", "--seed", "1", "--plot", str(path)]) == 0
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert str(path) in capsys.readouterr().out


@pytest.mark.parametrize(
    "argv",
    [
        ["limit", "--epsilon", "1.5"],
        ["limit", "--seed", "3"],
        ["limit", "--voussoirs", "2"],
        ["limit", "--geometry", "/nonexistent/arch.json"],
        ["limit", "--thickness", "-1"],
    ],
)
def test_cli_bad_input_exits_2_with_one_line(capsys, argv):
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("archquake: error: ") and "\n" not in err


def test_cli_unknown_method_is_rejected(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["limit", "--method", "simplex"])
    assert exc.value.code == 2
    assert "method" in capsys.readouterr().err


def test_cli_limit_help(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["limit", "--help"])
    assert exc.value.code == 0
    out = capsys.readouterr().out
    for option in ("--json", "--min-pier-width", "--plot", "--method", "--epsilon"):
        assert option in out


# ------------------------------------------------------------------ plots
def test_plots_return_axes(tmp_path, nominal):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from archquake.plotting import plot_arch, plot_limit_analysis, plot_load_multiplier_cdf

    arch = irregular_sample(nominal, 0.1, 1, 0)[0]
    ax = plot_limit_analysis(limit_analysis(arch, "l"), nominal=nominal)
    assert ax.get_xlabel() == "x [m]" and "k = " in ax.get_title()
    labels = [t.get_text() for t in ax.texts]
    assert [t for t in labels if len(t) == 1] == ["A", "B", "C", "D"]
    assert plot_arch(nominal, ax) is ax
    sample = limit_sample(nominal, 0.1, 20, seed=0)
    ax2 = plot_load_multiplier_cdf(sample.load_multiplier, nominal_k=0.37)
    assert "cumulative" in ax2.get_ylabel()
    ax2.figure.savefig(tmp_path / "cdf.png")
    plt.close("all")
