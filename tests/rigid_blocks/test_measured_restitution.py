"""The restitution measured on the rigid-block model ('measured'): Housner's coefficient for a
block, Moreau's projection for a frictionless arch, its invariances, the registry entry and the
command line."""

import json
import math
import subprocess
import sys

import numpy as np
import pytest
from scipy.optimize import nnls

from archquake import FourLinkModel, irregular_arch, oppenheim
from archquake.cli import main
from archquake.fourlink.impact import restitution
from archquake.rigid_blocks import GROUND, BlockSettings, from_arch, rectangular_block
from archquake.rigid_blocks.impacts import closing_impact, equivalent_restitution

WIDTH, HEIGHT = 0.4, 2.0


def rocking_mode(corner_x: float, height: float) -> np.ndarray:
    """Velocity (u, w, omega) of a block with centroid (0, height/2) turning at unit angular
    velocity (counterclockwise) about its base corner (corner_x, 0)."""
    r = np.array([0.0, 0.5 * height]) - np.array([corner_x, 0.0])
    return np.array([[-r[1], r[0], 1.0]])


@pytest.mark.parametrize("width", [0.4, 1.0, 1.6])
def test_block_coefficient_is_housners(width):
    """A block rocking on its left corner (turning clockwise back to its base) lands on its
    right corner: c = 1 - 1.5 sin^2(alpha), the square root of Housner's energy ratio r
    (Housner 1963: angular momentum about the new corner conserved), to the weight's share of
    the impact (1e-4)."""
    block = rectangular_block(width, HEIGHT)
    alpha = math.atan2(0.5 * width, 0.5 * HEIGHT)
    housner = 1.0 - 1.5 * math.sin(alpha) ** 2
    closing = -rocking_mode(-0.5 * width, HEIGHT)  # about the left corner, returning
    after = rocking_mode(0.5 * width, HEIGHT)
    c = equivalent_restitution(block, closing, after)
    assert c == pytest.approx(housner, rel=1e-4)
    # and the blocks do rotate about the new corner: all the energy is in that mode
    assert closing_impact(block, closing).mode_share(after) == pytest.approx(1.0, rel=1e-4)


def contact_jacobian(assembly) -> np.ndarray:
    """Normal relative velocity of every contact (both ends of every joint) per block velocity
    (u, w, omega), written here from the joints' geometry."""
    rows = []
    for j in range(assembly.n_joints):
        a, b = assembly.joint_bodies[j]
        n = assembly.joint_normals[j]
        for point in assembly.joint_points[j]:
            row = np.zeros((assembly.n_blocks, 3))
            for body, sign in ((b, 1.0), (a, -1.0)):
                if body != GROUND:
                    r = point - assembly.centroids[body]
                    row[body] += sign * np.array([n[0], n[1], r[0] * n[1] - r[1] * n[0]])
            rows.append(row.ravel())
    return np.array(rows)


def test_frictionless_arch_impact_is_moreaus_projection(nominal):
    """With no friction and restitution 0 the velocity after the impact is the projection of
    the velocity before on the cone {J v >= 0} in the metric of M (Moreau 1988); here by
    non-negative least squares on the contact impulses, v = v0 + M^-1 J^T lambda."""
    asm = from_arch(nominal)
    mech_l, _ = FourLinkModel.from_arch(nominal).mechanisms
    v0 = np.column_stack(mech_l.mode_shape())
    jac = contact_jacobian(asm)
    m = np.column_stack((asm.masses, asm.masses, asm.inertias)).ravel()
    impulses, _ = nnls((jac / np.sqrt(m)).T, -np.sqrt(m) * v0.ravel())
    projected = v0.ravel() + jac.T @ impulses / m
    impact = closing_impact(nominal, v0, BlockSettings(friction=0.0))
    # the weight acts over the step too: 1e-4 of the velocities (IMPACT_SPEED)
    np.testing.assert_allclose(impact.velocities_after.ravel(), projected,
                               atol=2e-4 * np.abs(v0).max())
    assert impact.energy_ratio == pytest.approx(0.5 * np.sum(m * projected**2)
                                                / impact.kinetic_energy_before, rel=1e-5)


def test_measurement_does_not_depend_on_time_step_or_friction_above_sticking(nominal):
    """Documented invariances: the impact law is homogeneous in the velocities (the weight's
    impulse is 1e-4 of them), so the time step does not matter; from mu = 0.5 up the joints
    stick at the impact and the friction coefficient does not matter; below it they slide."""
    mech_l, mech_r = FourLinkModel.from_arch(nominal).mechanisms
    modes = [np.column_stack(m.mode_shape()) for m in (mech_l, mech_r)]
    reference = equivalent_restitution(nominal, *modes)
    for settings in (BlockSettings(time_step=1e-4), BlockSettings(friction=0.5),
                     BlockSettings(friction=5.0)):
        assert equivalent_restitution(nominal, *modes, settings) == pytest.approx(
            reference, rel=2e-4), settings
    assert equivalent_restitution(nominal, *modes, BlockSettings(friction=0.1)) > reference + 0.05


def test_regression_measured_restitution_of_oppenheims_arch(nominal):
    """The value the documentation quotes (0.7478), between the computed value (a motion
    forced into Mech-r) and the frictionless projection of the test above (the joints free to
    slide keep more energy); the same both ways on the symmetric arch."""
    c_lr, c_rl = FourLinkModel.from_arch(nominal, "measured").restitution
    assert c_lr == pytest.approx(0.7478, abs=1e-4)
    assert c_rl == pytest.approx(c_lr, rel=1e-9)
    mech_l, mech_r = FourLinkModel.from_arch(nominal).mechanisms
    frictionless = equivalent_restitution(
        nominal, *[np.column_stack(m.mode_shape()) for m in (mech_l, mech_r)],
        BlockSettings(friction=0.0))
    computed = restitution("computed", mech_l, mech_r)[0]
    assert computed < c_lr < frictionless
    # the documented split: 85 % of the energy after the impact in Mech-r's mode, whose rate
    # alone would give c_v = 0.691; the rest in a motion with hinges at joints 0, 2, 3, 5, 7
    u_l, u_r = (np.column_stack(m.mode_shape()) for m in (mech_l, mech_r))
    impact = closing_impact(nominal, u_l)
    assert impact.mode_share(u_r) == pytest.approx(0.855, abs=1e-3)
    assert -impact.mode_rate(u_r) == pytest.approx(0.691, abs=1e-3)
    rotation = np.concatenate(([0.0], impact.velocities_after[:, 2], [0.0]))
    hinges = np.flatnonzero(np.abs(np.diff(rotation)) > 1e-3 * np.abs(rotation).max())
    assert hinges.tolist() == [0, 2, 3, 5, 7]


def test_irregular_arch_measured_restitution_mirrors():
    """The impact Mech-l -> Mech-r of an arch is the impact Mech-r -> Mech-l of its mirror
    image: the two coefficients swap."""
    arch = irregular_arch(oppenheim(), 0.10, rng=1)
    c_lr, c_rl = FourLinkModel.from_arch(arch, "measured").restitution
    m_lr, m_rl = FourLinkModel.from_arch(arch.mirrored(), "measured").restitution
    assert abs(c_lr - c_rl) > 0.01  # an irregular arch: they differ
    assert m_lr == pytest.approx(c_rl, rel=1e-3)
    assert m_rl == pytest.approx(c_lr, rel=1e-3)


def test_impact_module_loads_the_rigid_blocks_only_on_demand():
    code = ("import sys; import archquake.fourlink.impact, archquake.fourlink.model; "
            "print([m for m in sys.modules if m.startswith('archquake.rigid_blocks')])")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True)
    assert out.stdout.strip() == "[]"


def test_cli_mechanism_prints_measured_restitution(capsys, nominal):
    assert main(["mechanism", "--restitution", "measured", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    expected = FourLinkModel.from_arch(nominal, "measured").restitution
    assert out["restitution"]["l_to_r"] == pytest.approx(expected[0], rel=1e-12)
    assert out["restitution"]["r_to_l"] == pytest.approx(expected[1], rel=1e-12)


@pytest.mark.parametrize("command", ["mechanism", "domain", "fragility", "simulate",
                                     "reproduce"])
def test_every_restitution_option_lists_measured(capsys, command):
    with pytest.raises(SystemExit):
        main([command, "--help"])
    text = " ".join(capsys.readouterr().out.split())
    assert "--restitution" in text and "'measured' on the rigid-block model" in text
    assert "'rigid-blocks' measured" not in text and "formerly" not in text


def test_bad_mode_is_a_value_error(nominal):
    with pytest.raises(ValueError, match="velocities"):
        closing_impact(nominal, np.zeros((3, 3)))
    with pytest.raises(ValueError, match="mode_to"):
        equivalent_restitution(nominal, np.ones((7, 3)), np.zeros((7, 3)))


@pytest.mark.parametrize("former", ["blocks", "rigid-blocks"])
def test_former_names_are_refused_and_read_from_stored_results(capsys, former):
    """The restitution measured on the rigid blocks has one name, ``"measured"``; the names it
    had (``"blocks"``, then ``"rigid-blocks"``, the model's own name) are refused where a model
    is given and read as ``"measured"`` only where a stored result is read."""
    from archquake.fourlink.impact import check_restitution_model, stored_restitution_model

    with pytest.raises(ValueError, match=rf"restitution must be one of .*'measured'.*got "
                                         rf"'{former}'"):
        check_restitution_model(former)
    assert main(["mechanism", "--restitution", former]) == 2
    assert f"got '{former}'" in capsys.readouterr().err
    assert stored_restitution_model(former) == "measured"
    for model in ("computed", "nominal", 0.875):
        assert stored_restitution_model(model) == model
