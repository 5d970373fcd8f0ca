"""The limit analysis of any assembly with Coulomb friction, against closed forms and the chain
program of the arch."""

import math

import numpy as np
import pytest

import archquake
from archquake.constants import GRAVITY
from archquake.errors import CannotStandError
from archquake.geometry import circular_arch
from archquake.limit_analysis import (
    Contacts,
    assembly_limit,
    assembly_limits,
    assembly_stands,
    contacts_of,
    friction_margin,
    load_multipliers,
)


def rectangle_stack(width: float, heights, friction=math.inf, density=2000.0) -> Contacts:
    """Rectangles of one width stacked on the ground, centred on x = 0: interface 0 the base,
    interface j the bed joint under block j (normal +y, from the body below into the one above;
    the tangent, the normal turned by +90 degrees, points to -x: p0 is the right end)."""
    heights = np.asarray(heights, dtype=float)
    tops = np.cumsum(heights)
    bottoms = tops - heights
    n = heights.size
    half = 0.5 * width
    outlines = tuple(np.array([[-half, y0], [half, y0], [half, y1], [-half, y1]])
                     for y0, y1 in zip(bottoms, tops, strict=True))
    weight = density * width * heights * GRAVITY
    centre_y = 0.5 * (bottoms + tops)
    return Contacts(
        n_blocks=n, a=np.arange(-1, n - 1), b=np.arange(n),
        p0=np.column_stack((np.full(n, half), bottoms)),
        p1=np.column_stack((np.full(n, -half), bottoms)),
        normal=np.tile([0.0, 1.0], (n, 1)), friction=np.full(n, float(friction)),
        kind=np.array(["foundation"] + ["bed"] * (n - 1)),
        vertical=weight, vertical_x=np.zeros(n), horizontal=weight, horizontal_y=centre_y,
        outlines=outlines)


# ------------------------------------------------------------------ a block on a rigid base
@pytest.mark.parametrize("width, height", [(0.4, 1.0), (1.0, 0.5)])
def test_a_block_rocks_at_b_over_h_without_friction(width, height):
    # Statics of the block about its base corner: k W h/2 = W b/2, so k = b/h.
    for direction in ("+x", "-x"):
        result = assembly_limit(rectangle_stack(width, [height]), direction)
        assert result.load_multiplier == pytest.approx(width / height, rel=1e-9)
        assert result.law == "no sliding"
        assert list(result.state) == ["rocks"]


@pytest.mark.parametrize("friction", [0.1, 0.3])
def test_a_block_slides_at_mu_below_b_over_h(friction):
    # The base carries N = W and T = k W <= mu N: k = mu (< b/h = 0.4), by either law.
    block = rectangle_stack(0.4, [1.0], friction)
    for law in ("associative", "non-associative"):
        result = assembly_limit(block, "+x", law=law)
        assert result.load_multiplier == pytest.approx(friction, rel=1e-7)
        assert result.state[0] == "slides"
        assert result.converged
    # tilting table: tan(theta) = mu
    assert result.tilt == pytest.approx(math.degrees(math.atan(friction)), rel=1e-6)


def test_with_friction_above_b_over_h_the_block_rocks():
    result = assembly_limit(rectangle_stack(0.4, [1.0], 0.6), "+x", law="non-associative")
    assert result.load_multiplier == pytest.approx(0.4, rel=1e-9)
    assert list(result.state) == ["rocks"]


def test_a_stack_of_two_blocks_rocks_as_one_or_slides():
    # Two blocks b x h: the base carries 2W with its resultant at height h (moment 2 k W h <=
    # 2 W b/2: k <= b/(2h)), the upper joint W at h/2 (k <= b/h); both slide at k = mu.
    b, h = 0.5, 1.0
    rocking = assembly_limit(rectangle_stack(b, [h, h], 0.8), "+x", law="non-associative")
    assert rocking.load_multiplier == pytest.approx(b / (2 * h), rel=1e-9)
    assert rocking.state[0] == "rocks" and rocking.state[1] == "closed"
    sliding = assembly_limit(rectangle_stack(b, [h, h], 0.2), "+x", law="non-associative")
    assert sliding.load_multiplier == pytest.approx(0.2, rel=1e-7)
    assert "slides" in set(sliding.state)


def test_a_block_that_cannot_stand_is_refused():
    # friction zero on a level base still stands (no shear needed); a base tilted by
    # atan(0.75) does not (it needs mu >= 0.75)
    block = rectangle_stack(0.4, [1.0], 0.0)
    assert assembly_stands(block)
    tilted = Contacts(**{**block.__dict__, "normal": np.array([[-0.6, 0.8]]),
                         "p0": np.array([[0.16, 0.12]]), "p1": np.array([[-0.16, -0.12]])})
    assert not assembly_stands(tilted)
    with pytest.raises(CannotStandError):
        assembly_limit(tilted, "+x")


def test_a_block_touching_nothing_is_named():
    stack = rectangle_stack(0.4, [1.0, 1.0])
    loose = Contacts(**{**stack.__dict__, "a": stack.a[:1], "b": stack.b[:1], "p0": stack.p0[:1],
                        "p1": stack.p1[:1], "normal": stack.normal[:1],
                        "friction": stack.friction[:1], "kind": stack.kind[:1]})
    with pytest.raises(ValueError, match=r"block\(s\) \[1\] touch nothing"):
        assembly_limit(loose, "+x")


# ------------------------------------------------------------------ an arch as an assembly
@pytest.mark.parametrize("arch", [archquake.oppenheim(), circular_arch(2.0, 2.6, 0.35, 11)])
def test_without_friction_the_assembly_program_is_the_chain_program(arch):
    # Two formulations (joint resultants and moments / end forces of every interface) of the
    # same lower-bound problem, and the chain's kinematic enumeration.
    left, right = load_multipliers(arch)
    kinematic = load_multipliers(arch, method="kinematic")
    plus = assembly_limit(arch, "+x")
    minus = assembly_limit(arch, "-x")
    assert plus.load_multiplier == pytest.approx(left, rel=1e-8)
    assert minus.load_multiplier == pytest.approx(right, rel=1e-8)
    assert plus.load_multiplier == pytest.approx(kinematic[0], rel=1e-8)
    assert len(plus.interfaces_that("rocks")) == 4


@pytest.mark.parametrize("piers", [False, True])
def test_a_passive_fill_in_the_assembly_program_is_the_chain_programs(piers):
    # the passive reaction an unknown bounded force of the program (Contacts.passive), against
    # the chain program's static and kinematic forms (LP and enumeration), which carry it their
    # own way
    from archquake.geometry import Fill, Pier, shaped_arch
    from archquake.geometry.structure import Structure

    arch = shaped_arch("circular", span=4.0, rise=1.2, thickness=0.45, voussoirs=8,
                       faces="flat")
    pier = Pier(1.2, 3.0, 3) if piers else None
    structure = Structure(arch, pier, pier, Fill(0.5, 1800.0, "centroid", math.radians(30.0),
                                                 0.33))
    assert contacts_of(structure).passive.max() > 0
    left, right = load_multipliers(structure)
    kinematic = load_multipliers(structure, method="kinematic")
    plus, minus = (assembly_limit(structure, d).load_multiplier for d in ("+x", "-x"))
    assert plus == pytest.approx(left, rel=1e-9)
    assert minus == pytest.approx(right, rel=1e-9)
    assert plus == pytest.approx(kinematic[0], rel=1e-8)
    without = Structure(arch, pier, pier, Fill(0.5, 1800.0, "centroid"))
    assert plus > 1.05 * assembly_limit(without, "+x").load_multiplier


def test_a_bounded_push_on_a_block_by_hand():
    # one block 0.4 m x 2 m on the ground, W = 2000 g 0.8 N/m: alone it rocks about its right
    # corner at k = b / (2 h_c) = 0.2 / 1 = 0.2. A resistance up to P at height 1.5 m pushing
    # toward -x adds P 1.5 to the moment about that corner: k = (0.2 W + 1.5 P) / (1 W);
    # pushing toward +x it resists nothing (it cannot pull)
    stack = rectangle_stack(0.4, [2.0])
    weight = float(stack.vertical[0])
    bound = 0.1 * weight
    for sign, expected in ((-1.0, 0.2 + 1.5 * 0.1), (1.0, 0.2)):
        pushed = Contacts(**{**stack.__dict__, "passive": np.array([bound]),
                             "passive_y": np.array([1.5]), "passive_sign": np.array([sign])})
        assert assembly_limit(pushed, "+x").load_multiplier == pytest.approx(expected,
                                                                             rel=1e-9)


def test_oppenheim_hinges_are_the_chain_programs():
    arch = archquake.oppenheim()
    from archquake.limit_analysis import both_directions
    joints = sorted(h.joint for h in both_directions(arch)[0].hinges)
    assert assembly_limit(arch, "+x").interfaces_that("rocks") == joints


@pytest.mark.parametrize("friction", [0.25, 0.35, 0.5, 0.8])
def test_standing_with_friction_agrees_with_the_chain_program(friction):
    for arch in (archquake.oppenheim(), circular_arch(1.0, math.pi, 0.15, 30)):
        assert assembly_stands(arch, friction=friction) == (friction_margin(arch, friction) >= 0)


def test_friction_only_lowers_the_multiplier_and_non_associative_never_exceeds():
    arch = archquake.oppenheim()
    heyman = assembly_limit(arch, "+x").load_multiplier
    previous = heyman
    for mu in (1.0, 0.5, 0.4, 0.35, 0.3):
        limits = assembly_limits(arch, friction=mu)["+x"]
        assoc, nonassoc = limits["associative"], limits["non-associative"]
        assert assoc.load_multiplier <= previous + 1e-12
        assert nonassoc.load_multiplier <= assoc.load_multiplier + 1e-9
        assert nonassoc.converged
        # the converged forces obey Coulomb's law
        assert np.all(np.abs(nonassoc.shear) <= mu * nonassoc.normal + 1e-6 * arch.total_mass)
        previous = assoc.load_multiplier


def test_friction_per_interface_kind():
    arch = archquake.oppenheim()
    c = contacts_of(arch, friction={"foundation": 0.3})
    assert np.all(c.friction[c.kind == "foundation"] == 0.3)
    assert np.all(np.isinf(c.friction[c.kind == "bed"]))
    with pytest.raises(ValueError, match="friction"):
        contacts_of(arch, friction=-1.0)


def test_the_mechanism_does_positive_work_and_opens_no_contact_inward():
    arch = archquake.oppenheim()
    result = assembly_limit(arch, "+x")
    assert np.all(result.opening >= -1e-9)
    c = result.contacts
    work = sum(c.horizontal[j] * result.velocity_at(j, [[0.0, c.horizontal_y[j]]])[0, 0]
               for j in range(c.n_blocks))
    assert work > 0
