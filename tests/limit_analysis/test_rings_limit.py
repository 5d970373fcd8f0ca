"""Limit analysis of arches of several rings (:func:`archquake.geometry.multi_ring` through
:func:`archquake.limit_analysis.assembly.assembly_limit`) against independent values: the chain
program of the one-ring arch, the bound theorems, and the minimum thickness of the semicircle.

The associative program is the lower-bound one (:mod:`archquake.limit_analysis.assembly`), and
its dual the upper-bound one, so two theorems of limit analysis order the multipliers of
related assemblies (associative friction; the non-associative law is not ordered by them):

- **fewer contact forces, smaller k** (static): an assembly whose friction cones are narrower
  admits fewer statically admissible states, so its k is no larger; k never grows as a ring
  friction falls.
- **more interfaces, smaller k** (kinematic): if every block of assembly A is a union of blocks
  of assembly B (B cut along more interfaces), any mechanism of A is one of B, its pieces moving
  together, with the same work of the loads and no dissipation (associative friction
  dissipates nothing), so k(B) <= k(A). :func:`multi_ring` draws every circle through the same
  points whatever the rings inside and outside it when the joints are aligned, so two aligned
  rings glue back into the one-ring arch exactly, and four into two.
"""

import math

import numpy as np
import pytest

from archquake.errors import CannotStandError
from archquake.geometry import circular_arch, multi_ring
from archquake.limit_analysis import load_multipliers
from archquake.limit_analysis.assembly import assembly_limit

ALPHA = math.radians(157.5)


def k_of(structure, direction="+x", **kwargs):
    return assembly_limit(structure, direction, **kwargs).load_multiplier


def test_one_ring_converges_to_the_chain_program():
    # the chain program (exact annular sectors) of Oppenheim's arch, 7 voussoirs: k = 0.37001;
    # the chords' polygons weigh a little less at the intrados-extrados segments, so k converges
    # to it as O(arc_error): the error falls ten-fold with arc_error
    k_chain = load_multipliers(circular_arch(10.0, ALPHA, 1.5, 7), "static")[0]
    errors = []
    for e in (1.5e-2, 1.5e-3, 1.5e-4):
        arch = multi_ring(10.0, ALPHA, 1.5, rings=1, voussoirs=7, arc_error=e)
        errors.append(abs(k_of(arch) - k_chain))
    assert errors[1] < 1e-4  # the default arc_error, 1e-3 of the thickness: 1.5 mm
    assert errors[2] < 1e-5
    for coarse, fine in zip(errors[:-1], errors[1:], strict=True):
        assert 5 < coarse / fine < 20  # first order in arc_error


@pytest.mark.parametrize("direction", ["+x", "-x"])
def test_two_aligned_rings_no_stronger_than_one(direction):
    # the two rings glue back into the one-ring arch (same chord points), so every mechanism of
    # the one ring is one of the two: k(2) <= k(1). With ring interfaces that cannot slide the
    # rings may still separate (open): the LP finds the same four-hinge mechanism through both
    # rings, no weaker one, so the two are equal to the LP's accuracy here.
    one = k_of(multi_ring(10.0, ALPHA, 1.5, rings=1, voussoirs=7), direction)
    two = k_of(multi_ring(10.0, ALPHA, 1.5, rings=2, voussoirs=7), direction)
    assert two <= one + 1e-9
    assert two == pytest.approx(one, rel=1e-8)


@pytest.mark.parametrize(("radius", "alpha_deg", "thickness", "voussoirs"), [
    (10.0, 157.5, 1.5, 7),   # Oppenheim's arch
    (5.0, 180.0, 1.0, 12),   # a thick semicircle
    (8.0, 120.0, 0.8, 10),   # a segmental arch
])
def test_weaker_rings_never_increase_k(radius, alpha_deg, thickness, voussoirs):
    alpha = math.radians(alpha_deg)
    one = k_of(multi_ring(radius, alpha, thickness, rings=1, voussoirs=voussoirs))
    two = [k_of(multi_ring(radius, alpha, thickness, rings=2, voussoirs=voussoirs,
                           ring_friction=mu)) for mu in (0.8, 0.5, 0.3)]
    four = k_of(multi_ring(radius, alpha, thickness, rings=4, voussoirs=voussoirs,
                           ring_friction=0.5))
    slack = 1e-9
    assert two[0] <= one + slack                      # cut along the rings
    assert two[2] <= two[1] + slack <= two[0] + 2 * slack  # a lower ring friction
    assert four <= two[1] + slack                     # four rings cut the two further
    assert two[1] < one                               # and weak rings do weaken the arch


def test_staggered_bond_locks_without_ring_sliding():
    # with staggered joints every crack through the thickness runs along a ring interface for
    # half a voussoir, where the pieces turn about a hinge and so slide on the interface: if it
    # cannot slide (Heyman's hypothesis on the ring interfaces) there is no mechanism at all
    # (k = inf, above the aligned arch's finite k). With friction the bond is stronger than the
    # aligned rings for Oppenheim's arch (a check, not a theorem: a thin semicircle of 40
    # voussoirs, t/R = 0.15, mu = 0.5, gives 0.03245 staggered against 0.03275 aligned)
    staggered = k_of(multi_ring(10.0, ALPHA, 1.5, rings=2, voussoirs=7, bond="staggered"))
    assert math.isinf(staggered)
    for mu in (0.3, 0.6):
        aligned = k_of(multi_ring(10.0, ALPHA, 1.5, rings=3, voussoirs=20, ring_friction=mu))
        bonded = k_of(multi_ring(10.0, ALPHA, 1.5, rings=3, voussoirs=20, bond="staggered",
                                 ring_friction=mu))
        assert bonded > aligned


def stands(structure) -> bool:
    try:
        assembly_limit(structure)
    except CannotStandError:
        return False
    return True


def test_minimum_thickness_of_the_semicircle_in_rings():
    # Milankovitch: a semicircle stands down to t/R = 0.1075 (40 voussoirs: 0.10746 by the chain
    # program, min_thickness). One ring: stands at 0.11, falls at 0.10. Two aligned rings whose
    # interface cannot slide: the same (they glue back, and the one-ring mechanism is the
    # weakest). Two rings with ring friction 0.5: each ring is a semicircle of t/R = 0.055 on
    # its own, and the rings slide on each other, so at 0.11 the arch falls; 0.15 stands.
    def arch(t, rings, **kw):
        return multi_ring(1.0, math.pi, t, rings=rings, voussoirs=40, **kw)

    assert stands(arch(0.11, 1)) and not stands(arch(0.10, 1))
    assert stands(arch(0.11, 2)) and not stands(arch(0.10, 2))
    assert not stands(arch(0.11, 2, ring_friction=0.5))
    assert stands(arch(0.15, 2, ring_friction=0.5))


def test_which_interfaces_move_when_rings_separate():
    # Oppenheim's arch in two aligned rings sliding on each other at mu = 0.3: the collapse
    # slides ring interfaces, the hinges of the voussoir joints rock
    result = assembly_limit(multi_ring(10.0, ALPHA, 1.5, rings=2, voussoirs=7,
                                       ring_friction=0.3))
    kinds = result.contacts.kind
    sliding = np.array(result.interfaces_that("slides"), dtype=int)
    assert sliding.size and set(kinds[sliding]) == {"ring"}
    assert {"bed", "foundation"} & set(kinds[result.interfaces_that("rocks")])


@pytest.mark.parametrize("shape", ["parabolic", "elliptical", "catenary", "three-centred"])
def test_one_ring_of_a_shape_converges_to_the_chain_program(shape):
    # the chain program of the shaped arch (joints normal to the centreline at equal arc
    # lengths, exact faces by quadrature) against one ring of chords: within 1e-3 at a
    # sagitta of 10 mm, 1e-5 at 0.1 mm
    from archquake.geometry import shaped_arch

    rise = 4.0 if shape == "three-centred" else 3.0
    k_chain = load_multipliers(shaped_arch(shape, span=10.0, rise=rise, thickness=0.8,
                                           voussoirs=9), "static")[0]
    for e, tolerance in ((1e-2, 1e-3), (1e-4, 1e-5)):
        arch = multi_ring(shape=shape, span=10.0, rise=rise, thickness=0.8, rings=1,
                          voussoirs=9, arc_error=e)
        assert abs(k_of(arch) - k_chain) < tolerance
