"""The rigid-block model of whole arches: statics, activation against limit analysis, energy,
agreement with the four-link model for long pulses, and the outcome rules checked by running on.
"""

import math
import subprocess
import sys

import numpy as np
import pytest

from archquake import irregular_arch, oppenheim
from archquake.geometry import GRAVITY, CircularArch
from archquake.ground_motion import oppenheim_pulse, rectangular_pulse
from archquake.limit_analysis import both_directions
from archquake.rigid_blocks import (
    GROUND,
    Assembly,
    BlockSettings,
    RigidBlockModel,
    block_outcome,
    from_arch,
    simulate_blocks,
)
from archquake.studies.failure_domain import domain_of


def failure_curve(structure, durations, amplitudes_g, resolution_g, **options):
    """The rigid-block model's failure domain over a grid (no extension)."""
    return domain_of(RigidBlockModel(structure), durations, amplitudes_g,
                     resolution_g=resolution_g, extend_to_g=None, **options)

ARCHES = {"NA": oppenheim()} | {f"irregular-{seed}": irregular_arch(oppenheim(), 0.10, rng=seed)
                                for seed in (1, 2, 3)}


def test_from_arch_reads_the_joints_and_mass_properties(nominal):
    asm = from_arch(nominal)
    inner, outer = nominal.joint_extents()
    beta = nominal.joint_angles
    np.testing.assert_allclose(asm.joint_points[:, 0], CircularArch.point(inner, beta))
    np.testing.assert_allclose(asm.joint_points[:, 1], CircularArch.point(outer, beta))
    n = nominal.n_voussoirs
    assert asm.joint_bodies.tolist() == [[GROUND, 0]] + [[j - 1, j] for j in range(1, n)] + [
        [n - 1, GROUND]]
    # the normal points from voussoir j-1 into voussoir j: toward the centroid of j
    for j in range(n):
        towards = nominal.centroids[j] - asm.joint_points[j].mean(axis=0)
        assert towards @ asm.joint_normals[j] > 0
    np.testing.assert_allclose(asm.masses, nominal.masses)
    assert asm.total_mass == pytest.approx(
        nominal.density * 0.5 * nominal.embrace * (10.75**2 - 9.25**2))
    # crown: top of the extrados of the middle voussoir
    assert asm.crown[0] == 3
    np.testing.assert_allclose(asm.crown[1], [0.0, 10.75], atol=1e-12)
    assert asm.thickness == 1.5


def test_model_is_independent_of_the_four_link_code():
    """Importing and running the rigid-block model (its analyses, failure curves and impact
    measurement) loads none of the four-link modules."""
    code = ("import sys; from archquake import oppenheim; from archquake.rigid_blocks import "
            "block_outcome, RigidBlockModel; "
            "block_outcome(oppenheim(), None); "
            "from archquake.rigid_blocks.impacts import closing_impact; import numpy; "
            "closing_impact(oppenheim(), numpy.ones((7, 3))); "
            "bad = [m for m in ('mechanism', 'equations_of_motion', 'impact', 'engine', "
            "'time_history') if 'archquake.' + m in sys.modules]; print(bad)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True)
    assert out.stdout.strip() == "[]"


def test_arch_at_rest_carries_its_weight(nominal):
    """Still ground: nothing moves and the supports carry the weight (vertical reactions sum
    to M g, horizontal ones cancel); under a constant 0.2 g they also carry M a."""
    asm = from_arch(nominal)
    weight = asm.total_mass * GRAVITY
    for a in (0.0, 0.2):
        motion = None if a == 0 else rectangular_pulse(-a * GRAVITY, 2.0)
        history = simulate_blocks(nominal, motion, t_end=1.0, record_every=10)
        assert history.outcome.max_opening < 1e-9 and history.outcome.max_rotation < 1e-9
        forces = np.zeros((history.times.size, 2))
        for j, sign in ((0, 1.0), (asm.n_joints - 1, -1.0)):  # on the arch from each support
            n = asm.joint_normals[j]
            t = np.array([-n[1], n[0]])
            fn = history.normal_forces[:, j].sum(axis=1)
            ft = history.tangential_forces[:, j].sum(axis=1)
            forces += sign * (fn[:, None] * n + ft[:, None] * t)
        np.testing.assert_allclose(forces[1:, 1], weight, rtol=1e-7)
        np.testing.assert_allclose(forces[1:, 0], -asm.total_mass * a * GRAVITY,
                                   atol=1e-7 * weight)


def hinges_of(result, n: int) -> set[tuple[int, int]]:
    """(joint, end that opens) of every limit-analysis hinge, in the arch's own frame: an
    intrados hinge opens the joint's extrados end (1) and vice versa."""
    out = set()
    for hinge in result.hinges:
        joint = hinge.joint if result.direction == "l" else n - hinge.joint
        out.add((joint, 1 if hinge.face == "intrados" else 0))
    return out


@pytest.mark.parametrize("name", list(ARCHES))
@pytest.mark.parametrize("direction", ["l", "r"])
def test_activation_matches_limit_analysis(name, direction):
    """A constant ground acceleration (a 1 s step) 1 % below k leaves the arch at rest; 1 %
    above k it moves, opening the four hinges of the limit analysis."""
    arch = ARCHES[name]
    result = both_directions(arch)[0 if direction == "l" else 1]
    k = result.load_multiplier
    sign = -1.0 if direction == "l" else 1.0
    below = block_outcome(arch, rectangular_pulse(sign * 0.99 * k * GRAVITY, 1.0))
    assert below.status.label == "rest" and below.max_opening < 1e-8
    history = simulate_blocks(arch, rectangular_pulse(sign * 1.01 * k * GRAVITY, 1.0),
                              t_end=1.0, record_every=50)
    opening = history.gaps[-1]
    assert opening.max() > 1e-3
    opened = {(int(j), int(e)) for j, e in zip(*np.nonzero(opening > 1e-4), strict=True)}
    assert opened == hinges_of(result, arch.n_voussoirs)


def test_symmetric_arch_answers_both_directions_alike(nominal):
    """Mirror pulses on a symmetric arch give mirror responses -- to 0.1 %: the contact of a
    joint is not mirror-symmetric (the points of one block against the face of the other), so
    the two runs differ by their penetrations, which are O(h)."""
    left = block_outcome(nominal, oppenheim_pulse(-0.5 * GRAVITY, 0.4))
    right = block_outcome(nominal, oppenheim_pulse(0.5 * GRAVITY, 0.4))
    assert left.status == right.status
    assert left.max_rotation == pytest.approx(right.max_rotation, rel=1e-3)
    assert left.max_crown_drop == pytest.approx(right.max_crown_drop, rel=1e-3)


@pytest.mark.parametrize("coarse_factor", [1, 2])
def test_arch_energy_after_the_pulse(nominal, coarse_factor):
    """An arch rocking after a pulse: the energy balance closes (theta = 1/2, whatever the
    length of each step: every step at h, or coarse steps), and once the ground is still the
    total energy never rises above its running minimum by more than the discretisation error
    (0.5 % of the energy at the end of the pulse)."""
    motion = oppenheim_pulse(-0.6 * GRAVITY, 0.3)
    history = simulate_blocks(nominal, motion, BlockSettings(coarse_factor=coarse_factor),
                              tail=0.5)
    assert history.outcome.status.label == "recovery"
    energy = history.total_energy
    balance = energy - energy[0] + history.dissipated_energy - history.input_work
    assert np.abs(balance).max() < 1e-8 * np.abs(history.input_work).max()
    after = energy[history.times >= motion.duration]
    rise = float((after - np.minimum.accumulate(after)).max())
    assert rise < 5e-3 * after[0]
    # back at rest: the impacts dissipated it all but the potential energy of the small
    # permanent slips and penetrations
    assert history.kinetic_energy[-1] < 1e-9 * after[0]
    assert after[-1] < 1e-3 * after[0]


def test_long_pulse_failure_agrees_with_four_link_model(nominal):
    """For long pulses the rigid-block failure acceleration of Oppenheim's arch is within 5 %
    of the four-link model's, with every restitution model (the arch falls in its first swing,
    the impacts matter little there; measured at t_p = 0.7 s: 0.402 g vs 0.421 (computed),
    0.399 (link), 0.401 (paper), 0.410 g (blocks)), through ``archquake compare``'s function."""
    from archquake.studies.comparison import compare_models

    comparison = compare_models(nominal, [0.7, 1.0], amplitudes_g=np.arange(0.30, 0.61, 0.05),
                                resolution_g=2e-3)
    assert set(comparison.four_link) == {"computed", "link", "paper", "measured"}
    for restitution, difference in comparison.relative_differences().items():
        assert np.all(np.abs(difference) < 0.05), (restitution, difference)


def test_failure_curve_reports_activation_and_failure(nominal):
    curve = failure_curve(nominal, [0.5], amplitudes_g=np.arange(0.30, 0.61, 0.05),
                          resolution_g=5e-3)
    assert curve.model["model"] == "rigid-blocks"
    (row,) = curve.to_list()
    statuses = [iv["outcome"] for iv in row["intervals"]]
    assert statuses == ["rest", "recovery", "collapse"]
    # activation at k = 0.370 (limit analysis), failure above it
    assert row["intervals"][1]["from"] == pytest.approx(0.370, abs=5e-3)
    assert 0.40 < row["failure_acceleration"] < 0.50
    assert curve.slices[0].recovery_above_g == []


@pytest.mark.parametrize("amplitude", [0.43, 0.44, 0.46, 0.70])
def test_running_on_confirms_the_decided_outcome(nominal, amplitude):
    """Near the failure boundary of t_p = 0.5 s: running 4 s past the decision, a recovered
    arch stays closed and still, and a collapsed one keeps falling (its crown below a
    thickness)."""
    motion = oppenheim_pulse(-amplitude * GRAVITY, 0.5)
    decided = block_outcome(nominal, motion)
    history = simulate_blocks(nominal, motion, t_end=decided.decision_time + 4.0,
                              record_every=20)
    assert history.outcome.status == decided.status
    if decided.status.label == "collapse":
        assert history.crown_drop[-1] > 1.5 and history.crown_drop[-1] > 2 * np.max(
            history.crown_drop[history.times <= decided.decision_time])
    else:
        assert history.openings[-1].max() < 1e-4 * 1.5
        assert history.kinetic_energy[-1] < 1e-9 * nominal.total_mass * GRAVITY


@pytest.mark.parametrize("amplitude", [2.1, 2.5])
def test_arch_wedged_open_at_rest_is_a_recovery(nominal, amplitude):
    """After a large rocking motion under a short pulse (t_p = 0.2 s), blocks that slipped a
    fraction of a millimetre come to rest with a joint held open a little wider than a closed
    gap. That is a recovery in a displaced configuration (``closed`` False), decided after a
    second of stillness, not an undecided run counted as a collapse; running 5 s past the
    decision confirms it: the arch stays where it stopped, still, its crown up.

    The wedging is made by the steps: every step at 1 ms wedges here, while every step at 0.5
    or 0.25 ms, and the default coarse steps, close the arch (a recovery, ``closed`` True); the
    uniform 1 ms steps are kept for the decision they exercise."""
    settings = BlockSettings(coarse_factor=1)
    motion = oppenheim_pulse(-amplitude * GRAVITY, 0.2)
    for converged in (BlockSettings(), BlockSettings(time_step=2.5e-4, coarse_factor=1)):
        closed = block_outcome(nominal, motion, converged)
        assert closed.status.label == "recovery" and closed.closed
    decided = block_outcome(nominal, motion, settings)
    assert decided.status.label == "recovery" and decided.decided and not decided.closed
    history = simulate_blocks(nominal, motion, settings, t_end=decided.decision_time + 5.0,
                              record_every=50)
    after = history.times >= decided.decision_time
    assert np.all(history.kinetic_energy[after] < 1e-9 * nominal.total_mass * GRAVITY)
    assert np.ptp(history.crown_drop[after]) < 1e-6
    assert abs(history.crown_drop[-1]) < 1e-3 and history.openings[-1].max() < 1e-3


def test_bad_input_is_a_value_error(nominal):
    with pytest.raises(ValueError, match="friction"):
        BlockSettings(friction=-0.1)
    with pytest.raises(ValueError, match="theta"):
        BlockSettings(theta=0.3)
    with pytest.raises(ValueError, match="time_step"):
        BlockSettings(time_step=0.0)
    with pytest.raises(ValueError, match="structure"):
        block_outcome("arch", None)
    with pytest.raises(ValueError, match="motion"):
        block_outcome(nominal, 3.0)
    with pytest.raises(ValueError, match="initial"):
        block_outcome(nominal, None, initial=(np.zeros((2, 3)), np.zeros((2, 3))))
    with pytest.raises(ValueError, match="perpendicular"):
        Assembly([1.0], [[0, 0]], [1.0], [[GROUND, 0]], [[[0, 0], [1, 0]]], [[1.0, 1.0]])
    with pytest.raises(ValueError, match="joint_bodies"):
        Assembly([1.0], [[0, 0]], [1.0], [[0, 0]], [[[0, 0], [1, 0]]], [[0.0, 1.0]])
    with pytest.raises(ValueError, match="direction"):
        domain_of(RigidBlockModel(nominal), [0.5], direction="x")
    with pytest.raises(ValueError, match="durations"):
        domain_of(RigidBlockModel(nominal), [-1.0])
    with pytest.raises(ValueError, match="record_every"):
        simulate_blocks(nominal, None, record_every=0)
    assert math.isnan(block_outcome(nominal, None).collapse_time)


def test_failure_curve_on_two_workers_equals_the_serial_one(nominal):
    """Durations run on worker processes (which unpickle the arrays) give the same slices."""
    kwargs = {"amplitudes_g": np.arange(0.35, 0.61, 0.05), "resolution_g": 0.01}
    serial = failure_curve(nominal, [0.5, 0.7], **kwargs)
    parallel = failure_curve(nominal, [0.5, 0.7], workers=2, **kwargs)
    assert parallel.to_list() == serial.to_list()
