"""The ramp (tilt) test of the rigid blocks against closed forms and limit analysis.

Every multiplier is compared with a value found otherwise: Housner's block and a stack of two
blocks by hand (statics of a rigid body about its corner, Coulomb's law at its base), Oppenheim's
arch by :func:`archquake.limit_analysis.load_multipliers` and, with friction that governs, by a
static linear program with Coulomb cones written here (a second method: equilibrium of the
blocks, not their motion).
"""

import json
import math

import numpy as np
import pytest
from scipy.optimize import linprog

from archquake import oppenheim
from archquake.geometry import circular_arch
from archquake.limit_analysis import load_multipliers
from archquake.rigid_blocks import GROUND, Assembly, from_arch, rectangular_block
from archquake.rigid_blocks.ramp import PIECE_MULTIPLIER, ramp_test

WIDTH, HEIGHT = 0.4, 1.0
"""Housner's block of the tests [m]: b/h = 0.4."""


def stack_of_two(width: float, height: float, density: float = 2000.0) -> Assembly:
    """Two equal blocks ``width`` x ``height``, one on the other, on the ground (joint 0 the
    base, joint 1 between the blocks; both faces wide enough to slide on)."""
    b = 0.5 * width
    mass = density * width * height
    return Assembly(
        masses=[mass, mass], centroids=[[0.0, 0.5 * height], [0.0, 1.5 * height]],
        inertias=[mass * (width**2 + height**2) / 12.0] * 2,
        joint_bodies=[[GROUND, 0], [0, 1]],
        joint_points=[[[-b, 0.0], [b, 0.0]], [[-b, height], [b, height]]],
        joint_normals=[[0.0, 1.0], [0.0, 1.0]],
        face_extents=[[-100.0 * width, 101.0 * width]] * 2, crown=(1, (-b, 2 * height)),
        thickness=width)


def static_multiplier(assembly: Assembly, friction: float) -> float:
    """Largest k for which the blocks can be in equilibrium under their weight and k times it
    along +x, with a compressive force in Coulomb's cone at each end of every joint (the static
    theorem with friction: associative, an upper bound of the non-associative multiplier)."""
    nb, nj = assembly.n_blocks, assembly.n_joints
    nv = 4 * nj + 1  # (normal, tangential) at both ends of every joint, then k
    weight = assembly.masses / assembly.total_mass  # forces scaled by the total weight
    a_eq = np.zeros((3 * nb, nv))
    for j, (a, b) in enumerate(assembly.joint_bodies):
        n = assembly.joint_normals[j]
        t = np.array([-n[1], n[0]])
        for end in range(2):
            p = assembly.joint_points[j, end]
            for comp, d in ((0, n), (1, t)):
                col = 4 * j + 2 * end + comp
                for body, sign in ((b, 1.0), (a, -1.0)):
                    if body == GROUND:
                        continue
                    r = p - assembly.centroids[body]
                    a_eq[3 * body:3 * body + 2, col] += sign * d
                    a_eq[3 * body + 2, col] += sign * (r[0] * d[1] - r[1] * d[0])
    a_eq[0::3, -1] = weight
    b_eq = np.zeros(3 * nb)
    b_eq[1::3] = weight
    a_ub = []
    for c in range(2 * nj):  # |t| <= mu n
        for sign in (1.0, -1.0):
            row = np.zeros(nv)
            row[2 * c + 1], row[2 * c] = sign, -friction
            a_ub.append(row)
    bounds = [(0, None), (None, None)] * (2 * nj) + [(None, None)]
    cost = np.zeros(nv)
    cost[-1] = -1.0
    res = linprog(cost, A_ub=np.array(a_ub), b_ub=np.zeros(len(a_ub)), A_eq=a_eq, b_eq=b_eq,
                  bounds=bounds)
    assert res.status == 0, res.message
    return float(res.x[-1])


def test_block_that_cannot_slide_rocks_at_b_over_h():
    # Housner: about the corner, k m g h/2 = m g b/2, so k = b/h = 0.4/1.0 = 0.4; tilt atan(0.4)
    result = ramp_test(rectangular_block(WIDTH, HEIGHT), friction=2.0)
    for onset in result.onsets:
        assert onset.found
        assert onset.error < 1e-3
        assert abs(onset.multiplier - 0.4) <= onset.error
        assert abs(onset.tilt - 21.8014) < 1e-3 + math.degrees(onset.error)
        assert onset.rocking_joints == (0,) and onset.sliding_joints == ()
        assert onset.mode == "rocking"
        # the lag the extrapolation removes: the first crossing is after the onset
        assert onset.crossings[0] > onset.multiplier + 3 * onset.error


def test_block_with_low_friction_slides_at_mu():
    # Coulomb at the base: k m g = mu m g before b/h is reached (mu = 0.3 < 0.4)
    result = ramp_test(rectangular_block(WIDTH, HEIGHT), friction=0.3)
    for onset in result.onsets:
        assert abs(onset.multiplier - 0.3) <= onset.error
        assert onset.sliding_joints == (0,) and onset.rocking_joints == ()


@pytest.mark.parametrize("rate", [0.4, 0.1, 0.025])
def test_stated_error_bounds_the_error_at_every_rate(rate):
    # sliding at mu = 0.3 exactly (closed form), and the stated error holds at fast rates too
    onset = ramp_test(rectangular_block(WIDTH, HEIGHT), friction=0.3, rate=rate,
                      directions=("+x",)).onset("+x")
    assert abs(onset.multiplier - 0.3) <= onset.error
    assert onset.error < 0.01 * rate + 1e-3


def test_stack_of_two_blocks_rocks_about_the_base_corner_or_slides_at_the_base():
    stack = stack_of_two(WIDTH, HEIGHT)
    # whole stack about the base corner: centroid at H = 1.0 m, half-width 0.2 m:
    # k = 0.2 / 1.0 = 0.2 (the top block alone would need b/h = 0.4)
    rocking = ramp_test(stack, friction=2.0).onset("+x")
    assert abs(rocking.multiplier - 0.2) <= rocking.error
    assert rocking.rocking_joints == (0,) and rocking.sliding_joints == ()
    # mu = 0.15 < 0.2: the base slides, at k = mu (2 m g k = mu 2 m g)
    sliding = ramp_test(stack, friction=0.15).onset("-x")
    assert abs(sliding.multiplier - 0.15) <= sliding.error
    assert 0 in sliding.sliding_joints and sliding.rocking_joints == ()
    # the static program agrees with the hand values
    assert static_multiplier(stack, 2.0) == pytest.approx(0.2, abs=1e-9)
    assert static_multiplier(stack, 0.15) == pytest.approx(0.15, abs=1e-9)


def test_oppenheim_arch_that_cannot_slide_takes_the_limit_analysis_multiplier():
    arch = oppenheim()
    k_l, k_r = load_multipliers(arch)  # 0.370 each way (symmetric arch)
    result = ramp_test(arch, friction=5.0)
    for onset, k in zip(result.onsets, (k_l, k_r), strict=True):
        assert onset.error < 2e-4
        assert abs(onset.multiplier - k) <= onset.error
        # a four-hinge mechanism, nothing slides
        assert len(onset.rocking_joints) == 4 and onset.sliding_joints == ()
    # the arch is symmetric: the hinges of one direction mirror those of the other
    n = arch.n_voussoirs
    plus, minus = result.onset("+x").rocking_joints, result.onset("-x").rocking_joints
    assert sorted(n - j for j in plus) == sorted(minus)


def test_another_arch_takes_its_limit_analysis_multiplier():
    # a circular arch R = 5 m, 170 degrees, t = 0.5 m, 8 voussoirs: k = 0.0755 both ways
    arch = circular_arch(5.0, math.radians(170.0), 0.5, 8)
    k_l, k_r = load_multipliers(arch)
    result = ramp_test(arch, friction=5.0)
    for onset, k in zip(result.onsets, (k_l, k_r), strict=True):
        assert abs(onset.multiplier - k) <= onset.error
        assert len(onset.rocking_joints) == 4 and onset.sliding_joints == ()


def test_arch_too_thin_to_stand_moves_at_zero():
    # t = 0.15 m on R = 5 m: no thrust line fits (limit analysis: nan), so it cannot stand
    arch = circular_arch(5.0, math.radians(170.0), 0.15, 8)
    assert all(math.isnan(k) for k in load_multipliers(arch))
    onset = ramp_test(arch, friction=5.0, directions="+x").onset("+x")
    assert onset.found and onset.multiplier == 0.0 and onset.tilt == 0.0


def test_oppenheim_arch_friction_that_governs_lowers_the_multiplier():
    arch = oppenheim()
    assembly = from_arch(arch)
    k_rocking = load_multipliers(arch)[0]
    # mu = 0.8: the four hinges still govern, as with no sliding at all
    high = ramp_test(arch, friction=0.8, directions=("+x",)).onset("+x")
    assert abs(high.multiplier - k_rocking) <= high.error
    assert high.sliding_joints == ()
    # mu = 0.4: three hinges and a support that slides, at a lower multiplier: that of the
    # static program with Coulomb cones (here the associative bound is reached)
    low = ramp_test(arch, friction=0.4).onset("+x")
    assert low.multiplier < k_rocking - 0.05
    assert abs(low.multiplier - static_multiplier(assembly, 0.4)) <= low.error
    assert len(low.rocking_joints) == 3
    assert set(low.sliding_joints) <= {0, arch.n_voussoirs}  # a springing joint
    assert len(low.sliding_joints) == 1


@pytest.mark.parametrize("friction, mode", [(0.3, "mixed"), (0.45, "mixed"), (0.5, "rocking")])
def test_oppenheim_arch_takes_the_multiplier_of_the_static_program_with_friction(friction,
                                                                                  mode):
    # below about mu = 0.5 a springing slides beside three hinges, above it four hinges govern
    arch = oppenheim()
    onset = ramp_test(arch, friction=friction, directions="+x").onset("+x")
    assert abs(onset.multiplier - static_multiplier(from_arch(arch), friction)) <= onset.error
    assert onset.mode == mode


def test_ramp_stops_once_the_onset_is_decided():
    # the load the blocks saw, over every piece run, ends a few pieces past the onset:
    # at most the pieces up to the onset (k / rate seconds), the piece that moved and the
    # final run of at most four pieces (no collapse followed)
    rate = 0.05
    block = rectangular_block(WIDTH, HEIGHT)
    result = ramp_test(block, friction=2.0, rate=rate, directions=("+x",))
    onset = result.onset("+x")
    simulated = onset.steps * result.time_step  # [s], coarse steps count as one: an upper bound
    assert simulated * rate <= onset.multiplier + 6 * PIECE_MULTIPLIER


def test_nothing_moves_below_the_largest_multiplier():
    onset = ramp_test(rectangular_block(WIDTH, HEIGHT), friction=2.0, max_multiplier=0.3,
                      directions="+x").onset("+x")
    assert not onset.found and onset.multiplier == math.inf and math.isnan(onset.error)
    assert onset.mode == "none"
    assert json.loads(json.dumps(onset.to_dict()))["multiplier"] is None  # inf, said as null


def test_result_reads_as_json():
    result = ramp_test(rectangular_block(WIDTH, HEIGHT), friction=0.3)
    data = json.loads(json.dumps(result.to_dict()))
    assert [o["direction"] for o in data["onsets"]] == ["+x", "-x"]
    assert data["onsets"][0]["sliding_joints"] == [0] and data["onsets"][0]["mode"] == "sliding"
    assert abs(data["multiplier"] - 0.3) <= max(o["error"] for o in data["onsets"])
    # tilt of a table: tan(16.699 deg) = 0.3
    assert math.tan(math.radians(data["onsets"][0]["tilt"])) == pytest.approx(
        data["onsets"][0]["multiplier"], rel=1e-12)


@pytest.mark.parametrize("kwargs, name", [
    ({"rate": 0.0}, "rate"), ({"rate": math.inf}, "rate"), ({"rate": 11.0}, "rate"),
    ({"friction": -0.1}, "friction"), ({"friction": math.inf}, "friction"),
    ({"friction": [0.3, 0.4]}, "friction"), ({"threshold": 1e-9}, "threshold"),
    ({"threshold": 0.1}, "threshold"), ({"max_multiplier": 0.0}, "max_multiplier"),
    ({"directions": ("up",)}, "directions"), ({"directions": ()}, "directions"),
    ({"time_step": -1.0}, "time_step"), ({"time_step": 0.1}, "time_step"),
    ({"rate": 1e-6}, "rate"),  # 2 / 1e-6 s at 0.5 ms: 4e9 steps
])
def test_bad_input_is_refused_naming_the_parameter(kwargs, name):
    with pytest.raises(ValueError, match=name):
        ramp_test(rectangular_block(WIDTH, HEIGHT), **kwargs)
