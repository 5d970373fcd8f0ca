"""What the page draws: the motion of the blocks of both models and the limit analysis in the
structure's own frame, checked against the library's kinematics and the command line's hinges."""

import math

import numpy as np
import pytest
from app_reference import cli_json

from archquake.app.inputs import structure_from_spec
from archquake.app.views import (
    FRAME_RATE,
    MAX_BLOCK_FRAMES,
    block_motion,
    four_link_motion,
    frame_rate,
    frame_times,
    limit_view,
)
from archquake.geometry import GRAVITY
from archquake.ground_motion import oppenheim_pulse
from archquake.limit_analysis import both_directions
from archquake.models import model_for


def moved(point, motion, centre):
    """Where a point of a block goes under the page's rigid motion (dx, dy, rotation about
    centre): what the page's SVG transform draws."""
    dx, dy, rot = motion
    c, s = math.cos(rot), math.sin(rot)
    r = np.asarray(point) - centre
    return centre + np.array([dx, dy]) + np.array([c * r[0] - s * r[1], s * r[0] + c * r[1]])


# an arch that is not symmetric, so that Mech-r differs from Mech-l
ASYMMETRIC = {"epsilon": 0.15, "seed": 4, "voussoirs": 9, "thickness": 1.3}


@pytest.mark.parametrize("spec", [{}, ASYMMETRIC, {"piers": "1.5,3,2"}],
                         ids=["oppenheim", "irregular", "piers"])
@pytest.mark.parametrize("mech", [0, 1], ids=["Mech-l", "Mech-r"])
def test_four_link_blocks_stay_joined_at_every_joint(spec, mech):
    """The linkage in the structure's own frame: the blocks of a link move as one (their joints
    stay closed), neighbouring links share their hinge, the springings stay on the ground, and
    hinges B, C are where the mechanism's own kinematics puts them."""
    nominal, structure = structure_from_spec(spec)
    model = model_for(structure, "four-link", nominal=nominal)
    mechanism = model.mechanisms[mech]
    phi = 0.6 * mechanism.phi_cr
    segment = type("S", (), {})()
    segment.theta = np.array([mechanism.theta_u - phi])
    history = type("H", (), {})()
    history.t, history.segments = np.array([0.0]), (segment,)
    history.mechanism = np.array(["l" if mech == 0 else "r"])
    motion = four_link_motion(model, history, np.array([0.0]))[0]
    centres = np.asarray(structure.centroids)
    n = structure.n_voussoirs
    joints = [h.joint for h in mechanism.hinges]
    if mech == 1:  # joint j of the mirror is joint n - j of the structure
        joints = sorted(n - j for j in joints)
    hinge_points = {j: structure.hinge_point(j, face) for j, face in zip(
        joints, [h.face for h in (mechanism.hinges if mech == 0 else mechanism.hinges[::-1])],
        strict=True)}
    assert np.count_nonzero(np.abs(motion[:, 2]) > 1e-12) >= 3
    for j in range(n + 1):
        ends = [structure.joints[j][k] for k in (0, 1)]
        left = [moved(p, motion[j - 1], centres[j - 1]) if j > 0 else p for p in ends]
        right = [moved(p, motion[j], centres[j]) if j < n else p for p in ends]
        if j in hinge_points:  # the hinge is shared, the joint opens on the other face
            p = hinge_points[j]
            a = moved(p, motion[j - 1], centres[j - 1]) if j > 0 else p
            b = moved(p, motion[j], centres[j]) if j < n else p
            assert np.allclose(a, b, atol=1e-9)
            assert not np.allclose(left, right, atol=1e-6)
        else:
            assert np.allclose(left, right, atol=1e-9)  # closed joint: one rigid body
    b, c = mechanism.points(mechanism.theta_u - phi)
    flip = np.array([-1.0, 1.0]) if mech == 1 else np.ones(2)
    for hinge, expected in zip(sorted(hinge_points)[1:3], (b, c) if mech == 0 else (c, b),
                               strict=True):
        got = moved(hinge_points[hinge], motion[hinge], centres[hinge])
        assert np.allclose(got, expected * flip, atol=1e-9)


def test_four_link_frames_follow_the_time_history():
    """The first link of the moving mechanism turns by -phi(t) of the time history (+phi in
    Mech-l, -phi in Mech-r), and nothing moves before the ground acceleration reaches k g."""
    _, structure = structure_from_spec(ASYMMETRIC)
    model = model_for(structure, "four-link")
    history = model.simulate(oppenheim_pulse(-0.9 * GRAVITY, 0.3))
    times = frame_times(float(history.t[-1]))
    frames = four_link_motion(model, history, times)
    index = np.clip(np.searchsorted(history.t, times, side="right") - 1, 0, history.t.size - 1)
    phi = history.phi[index]
    first_l = model.mechanisms[0].hinges[0].joint
    first_r = structure.n_voussoirs - 1 - model.mechanisms[1].hinges[0].joint
    turn = np.where(history.mechanism[index] == "r", frames[:, first_r, 2],
                    frames[:, first_l, 2])
    assert np.allclose(turn, -phi, atol=1e-12)
    assert (history.mechanism[index] == "r").any() and (history.mechanism[index] == "l").any()
    at_rest = history.mechanism[index] == "rest"
    assert np.all(frames[at_rest] == 0.0)


def test_rigid_block_frames_draw_the_histories_outlines():
    _, structure = structure_from_spec({"piers": "1.5,3,2", "fill_cover": 0.4})
    model = model_for(structure, "rigid-blocks")
    history = model.simulate(oppenheim_pulse(-1.0 * GRAVITY, 0.3), record_every=40)
    times = np.array([0.0, 0.52, 1.0, history.times[-1] + 5.0])
    frames = block_motion(history, times)
    centres = history.assembly.centroids
    for f, t in enumerate(times):
        record = min(int(np.searchsorted(history.times, t, side="right")) - 1,
                     history.times.size - 1)
        for i, (outline, expected) in enumerate(zip(history.assembly.outlines,
                                                    history.outlines(record), strict=True)):
            got = np.array([moved(p, frames[f, i], centres[i]) for p in outline])
            assert np.allclose(got, expected, atol=1e-12)


def test_frame_times_run_to_the_later_end_at_the_frame_rate():
    times = frame_times(2.0, 3.02, math.nan)
    assert times[0] == 0.0 and times[-1] == pytest.approx(3.0) and np.allclose(
        np.diff(times), 0.04)
    assert frame_times(1e6)[-1] == pytest.approx(60.0)
    assert frame_rate(60.0, 7) == FRAME_RATE
    rate = frame_rate(60.0, 200)  # many blocks for long: fewer frames
    assert rate < FRAME_RATE and frame_times(60.0, rate=rate).size * 200 <= MAX_BLOCK_FRAMES + 200


def test_limit_view_puts_mech_r_in_the_structures_frame():
    """The hinges of both mechanisms are those ``archquake limit --json`` reports, Mech-r's
    mirrored back from its frame (x -> -x, joint j -> n - j)."""
    argv = ["--epsilon", "0.15", "--seed", "4", "--voussoirs", "9", "--thickness", "1.3"]
    printed = cli_json("limit", *argv)
    _, structure = structure_from_spec(ASYMMETRIC)
    view = limit_view(both_directions(structure))
    assert (view["k_l"], view["k_r"]) == pytest.approx((printed["k_l"], printed["k_r"]),
                                                       rel=1e-12)
    n = structure.n_voussoirs
    for direction in ("l", "r"):
        listed = printed["mechanisms"][direction]["hinges"]
        drawn = view[direction]["hinges"]
        assert [h["joint"] for h in drawn] == [h["joint"] for h in listed]
        for hinge, entry in zip(drawn, listed, strict=True):
            joint = entry["joint"] if direction == "l" else n - entry["joint"]
            face = entry["face"]
            point = structure.hinge_point(joint, face)
            assert (hinge["x"], hinge["y"]) == pytest.approx(tuple(point), abs=1e-9)
