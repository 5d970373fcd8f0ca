"""What a rigid-block outcome may say: a time step that resolves the motion, an undecided run
said to be undecided (never a collapse), an outcome that does not depend on what is recorded,
and windows of observation that grow with the period of a tall structure."""

import json
import math

import numpy as np
import pytest

from archquake.cli import main
from archquake.geometry import GRAVITY, circular_arch
from archquake.ground_motion import oppenheim_pulse, read_record, rectangular_pulse
from archquake.limit_analysis import both_directions
from archquake.rigid_blocks import (
    GROUND,
    Assembly,
    BlockSettings,
    block_outcome,
    from_arch,
    rectangular_block,
    simulate_blocks,
)
from archquake.rigid_blocks.dynamics import observation_windows
from archquake.status import Status
from archquake.studies.failure_domain import domain_slice


def run_json(capsys, *argv):
    assert main(["rigid-blocks", *argv, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


# --- (a) the time step against the motion ---------------------------------------------------


@pytest.mark.parametrize("time_step", [1.0, 0.1, 0.05])
def test_time_step_longer_than_the_motion_allows_is_refused(nominal, time_step):
    """A 1 s step averaged Oppenheim's pulse away ("the arch never moves" under a -1 g pulse
    that collapses it) and 0.05-0.1 s gave a wrong collapse time: refused, naming time_step."""
    with pytest.raises(ValueError, match="time_step"):
        block_outcome(nominal, oppenheim_pulse(-GRAVITY, 0.27), BlockSettings(time_step=time_step))


def test_cli_dem_refuses_a_time_step_of_a_second(capsys):
    assert main(["rigid-blocks", "--time-step", "1"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("archquake: error: --time-step must be at most")  # names the option
    assert "never moves" not in err


@pytest.mark.parametrize("extra", [["--t-end", "1e300"], ["--duration", "50"]])
def test_a_step_count_beyond_any_integer_is_refused_naming_the_limit(capsys, extra):
    """Hardening (found by the fuzzer): --time-step 1e-300 with --t-end 1e300 overflowed the
    number of steps ("cannot convert float infinity to integer") instead of a refusal."""
    assert main(["rigid-blocks", "--time-step", "1e-300", *extra, "--json"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("archquake: error:") and "MAX_BLOCK_STEPS" in err
    assert "Traceback" not in err and err.count("\n") == 1


def test_time_step_limits_of_the_contact_law_the_pulse_and_the_record(tmp_path):
    """Each limit on its own: 0.02 sqrt(t/g) for the contacts (4.04 ms for a block 0.4 m
    wide on a still ground), 1/20 of a pulse's shortest piece, a record's sample spacing."""
    block = rectangular_block(0.4, 2.0)
    limit = 0.02 * math.sqrt(0.4 / GRAVITY)
    assert block_outcome(block, None, BlockSettings(time_step=0.99 * limit,
                                                    settle_time=0.2)).decided
    with pytest.raises(ValueError, match="time_step.*thick"):
        block_outcome(block, None, BlockSettings(time_step=1.01 * limit))
    with pytest.raises(ValueError, match="time_step.*shortest piece 0.01 s"):
        block_outcome(block, rectangular_pulse(GRAVITY, 0.01), BlockSettings(time_step=1e-3))
    block_outcome(block, rectangular_pulse(GRAVITY, 0.01), BlockSettings(time_step=5e-4))
    path = tmp_path / "r.csv"
    rows = "".join(f"{0.002 * i:.3f},{0.1 * math.sin(i):.4f}\n" for i in range(200))
    path.write_text("time_s,acc_g\n" + rows)
    with pytest.raises(ValueError, match="time_step.*sample spacing 0.002 s"):
        block_outcome(block, read_record(path), BlockSettings(time_step=3e-3))


@pytest.mark.parametrize("duration, below, above", [(0.3, 0.67, 0.69), (0.5, 0.43, 0.45),
                                                    (0.7, 0.39, 0.41)])
def test_halving_the_default_step_keeps_the_outcomes_beside_the_failure_boundary(
        nominal, duration, below, above):
    """Convergence of the default step (1 ms): 0.01 g on either side of Oppenheim's failure
    accelerations (0.680, 0.439, 0.402 g at t_p = 0.3, 0.5, 0.7 s), half the step gives the
    same outcomes."""
    for amplitude, expected in ((below, Status.RECOVERY), (above, Status.COLLAPSE)):
        for time_step in (1e-3, 5e-4):
            outcome = block_outcome(nominal, oppenheim_pulse(-amplitude * GRAVITY, duration),
                                    BlockSettings(time_step=time_step))
            assert outcome.status is expected, (amplitude, time_step)


# --- (b) an undecided run is undecided -------------------------------------------------------


def test_run_cut_short_is_undecided_not_a_collapse(nominal):
    """t_end = 0.1 s stops a collapsing arch long before anything is certain: undecided, with
    no collapse time (it said "collapses (certain at t = nan s)")."""
    history = simulate_blocks(nominal, oppenheim_pulse(-GRAVITY, 0.27), t_end=0.1)
    outcome = history.outcome
    assert outcome.status is Status.UNDECIDED and not outcome.decided
    assert not outcome.collapsed and math.isnan(outcome.collapse_time)
    assert math.isnan(outcome.decision_time) and outcome.steps == 100
    assert outcome.to_dict()["status"] == "undecided"
    assert outcome.to_dict()["collapse_time"] is None


def test_cli_dem_cut_short_says_undecided(capsys):
    assert main(["rigid-blocks", "--t-end", "0.1"]) == 0
    out = capsys.readouterr().out
    assert "undecided" in out and "nan" not in out and "collapses" not in out
    data = run_json(capsys, "--t-end", "0.1")
    assert data["outcome"] == "undecided" and data["collapse_time"] is None


def test_failure_search_keeps_undecided_apart_from_collapse():
    """domain_slice classifies by the status's label: an undecided band is its own interval,
    and the failure acceleration is the first collapse, not the first undecided amplitude."""
    def classify(amplitude):
        if amplitude < 0.3:
            return Status.REST, 0
        return (Status.UNDECIDED, 0) if amplitude < 0.5 else (Status.COLLAPSE, 0)

    piece = domain_slice(classify, np.linspace(0.1, 1.0, 10), resolution_g=1e-3)
    assert [iv.status for iv in piece.intervals] == ["rest", "undecided", "collapse"]
    assert piece.failure_acceleration_g == pytest.approx(0.5, abs=1e-3)


def test_unsolved_contact_problem_is_undecided_not_a_motion():
    """An arch of ten voussoirs under 0.99 of its limit multiplier k (a constant acceleration
    for 1 s) cannot move (limit analysis). The active-set method cycles on its first step and
    Gauss-Seidel leaves it unsolved: the spurious motion that followed was reported a
    recovery. Rest, or undecided with the unsolved steps counted -- never a motion."""
    arch = circular_arch(10.0, math.radians(157.5), 1.5, 10)
    k = both_directions(arch)[0].load_multiplier
    outcome = block_outcome(arch, rectangular_pulse(-0.99 * k * GRAVITY, 1.0))
    assert outcome.status in (Status.REST, Status.UNDECIDED)
    if outcome.status is Status.UNDECIDED:
        assert outcome.unconverged_steps > 0 and not outcome.decided


# --- (c) recording does not change the outcome -----------------------------------------------


def test_recording_does_not_change_the_outcome(nominal):
    """The default analysis (-1 g, t_p = 0.27 s): 0.463 rad and 1.23 m (those of every step
    at a quarter of the step within 1e-3 rad and 0.02 m), whether the run stops at the decision
    or is recorded 0.5 s or 3 s beyond it (the recorded run once reported 1.1053 rad and
    4.1193 m); the summary's crown drop is the largest recorded up to the decision."""
    pulse = oppenheim_pulse(-GRAVITY, 0.27)
    alone = block_outcome(nominal, pulse)
    fine = block_outcome(nominal, pulse, BlockSettings(time_step=2.5e-4, coarse_factor=1))
    assert alone.status == fine.status
    assert alone.max_rotation == pytest.approx(fine.max_rotation, abs=1e-3)
    assert alone.max_crown_drop == pytest.approx(fine.max_crown_drop, abs=0.02)
    for history in (simulate_blocks(nominal, pulse),
                    simulate_blocks(nominal, pulse, t_end=alone.decision_time + 3.0)):
        assert history.outcome.to_dict() == alone.to_dict()
        assert history.crown_drop.max() > 2 * alone.max_crown_drop  # it fell on
        until = history.times <= alone.decision_time + 1e-9
        assert history.crown_drop[until].max() == pytest.approx(alone.max_crown_drop,
                                                                rel=1e-12)


def test_cli_dem_summary_does_not_depend_on_the_output(capsys, tmp_path):
    plain = run_json(capsys)
    recorded = run_json(capsys, "--output", str(tmp_path / "h.csv"))
    assert recorded == plain


# --- (d) windows that grow with the structure's period ---------------------------------------


def _polygon(points, density):
    x, y = points[:, 0], points[:, 1]
    x1, y1 = np.roll(x, -1), np.roll(y, -1)
    cross = x * y1 - x1 * y
    area = cross.sum() / 2
    centroid = np.array([((x + x1) * cross).sum(), ((y + y1) * cross).sum()]) / (6 * area)
    polar = ((x * x + x * x1 + x1 * x1 + y * y + y * y1 + y1 * y1) * cross).sum() / 12
    return density * abs(area), centroid, density * (abs(polar) - abs(area) * centroid @ centroid)


def buttressed(arch, height: float, width: float) -> Assembly:
    """``arch`` on two buttresses ``height`` metres tall: each a block under a springing joint,
    reaching ``width`` metres outward beyond its extrados end, standing on the ground."""
    asm = from_arch(arch)
    masses, centroids, inertias = list(asm.masses), list(asm.centroids), list(asm.inertias)
    bodies, points, normals = asm.joint_bodies.copy(), list(asm.joint_points), list(
        asm.joint_normals)
    base = asm.joint_points[[0, -1]][:, :, 1].min() - height
    for j, side in ((0, 0), (asm.n_joints - 1, 1)):
        p0, p1 = asm.joint_points[j]
        inner, outer = (p0, p1) if abs(p0[0]) < abs(p1[0]) else (p1, p0)
        out = math.copysign(abs(outer[0]) + width, outer[0])
        quad = np.array([inner, outer, [out, outer[1]], [out, base], [inner[0], base]])
        mass, centroid, inertia = _polygon(quad, arch.density)
        masses.append(mass)
        centroids.append(centroid)
        inertias.append(inertia)
        bodies[j, side] = len(masses) - 1
        bodies = np.vstack((bodies, [GROUND, len(masses) - 1]))
        points.append(np.array([[min(inner[0], out), base], [max(inner[0], out), base]]))
        normals.append(np.array([0.0, 1.0]))
    return Assembly(masses=masses, centroids=centroids, inertias=inertias, joint_bodies=bodies,
                    joint_points=np.array(points), joint_normals=np.array(normals),
                    crown=asm.crown, thickness=asm.thickness)


def test_tall_structure_is_decided_within_its_own_period(nominal):
    """Oppenheim's arch on 40 m buttresses under a 0.2 g pulse rocks for 20 s: beyond the 20 s
    that suit an arch of 8 m, it was cut off undecided and reported a collapse. Its period
    sqrt(H/g) = 2.2 s (H = 48 m, the highest centroid above the buttresses' base) sets 44 s of
    observation and longer windows of rest: it comes back to rest, decided, and running on
    5 s after the decision confirms it (closed and still)."""
    structure = buttressed(nominal, 40.0, 5.0)
    height = structure.centroids[:, 1].max() - (structure.joint_points[-1, 0, 1])
    assert structure.height == pytest.approx(height)
    period = math.sqrt(height / GRAVITY)
    settle, rest, open_rest = observation_windows(structure, BlockSettings())
    assert (settle, rest, open_rest) == pytest.approx((20 * period, 0.1 * period, period))
    assert observation_windows(from_arch(nominal), BlockSettings()) == (20.0, 0.1, 1.0)
    pulse = oppenheim_pulse(-0.2 * GRAVITY, 0.5)
    outcome = block_outcome(structure, pulse)
    assert outcome.status is Status.RECOVERY and outcome.decided and outcome.closed
    assert outcome.decision_time > pulse.duration + 20.0
    history = simulate_blocks(structure, pulse, t_end=outcome.decision_time + 5.0,
                              record_every=50)
    after = history.times >= outcome.decision_time
    assert history.outcome.to_dict() == outcome.to_dict()
    assert np.all(history.kinetic_energy[after] < 1e-6 * structure.total_mass * GRAVITY)
    assert history.openings[-1].max() < 1e-4 * structure.thickness


def test_identical_runs_compare_equal_and_histories_compare_by_identity():
    """Hardening: ``BlockHistory ==`` raised (arrays in a frozen dataclass), and two identical
    runs' outcomes (nan collapse time when the arch recovers) compared unequal."""
    from archquake import oppenheim
    from archquake.geometry import GRAVITY
    from archquake.ground_motion import oppenheim_pulse
    from archquake.rigid_blocks import block_outcome, simulate_blocks

    arch = oppenheim()
    recovery = oppenheim_pulse(-0.4 * GRAVITY, 0.5)  # below 0.439 g
    first, second = block_outcome(arch, recovery), block_outcome(arch, recovery)
    assert first.status.label == "recovery" and first.collapse_time != first.collapse_time
    assert first == second and hash(first) == hash(second)
    assert first != block_outcome(arch, oppenheim_pulse(-0.6 * GRAVITY, 0.4))
    one = simulate_blocks(arch, recovery, t_end=0.5)
    other = simulate_blocks(arch, recovery, t_end=0.5)
    assert one == one and one != other  # results compare by identity (archquake._equality)
    assert one.outcome == other.outcome
