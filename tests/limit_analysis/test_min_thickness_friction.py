"""The minimum thickness of a semicircular arch with Coulomb friction at its joints, against the
published solution of the Couplet-Heyman problem with finite friction (Cocchetti & Rizzi,
Frattura ed Integrita Strutturale 51 (2020) 356-375, Table 3).

Their values (weight lumped on the centreline, r the centreline radius): purely rotational
collapse at t/r = 0.107426 down to mu = 0.395832; a mixed rotational-sliding one below, down to
mu = 0.309215 (t/r = 0.200637, the new sliding joint at 28.6362 deg from the springing); no
equilibrium below. Our voussoirs carry their weight at their true centroids (Milankovitch's
assumption, t/r = 0.1075 without friction), so the thicknesses differ by a per cent or less; the
arch of 44 voussoirs has a joint at 7 x 180/44 = 28.636 deg, where the published sliding joint
is (with coarser joints elsewhere the discrete arch could stand at a lower friction).
"""

import math

import pytest

from archquake.errors import NoThicknessError
from archquake.geometry import circular_arch
from archquake.limit_analysis import friction_margin, min_thickness, shaped_min_thickness

N = 44


def test_above_the_rotational_friction_nothing_changes():
    heyman = min_thickness(1.0, math.pi, N)
    assert heyman == pytest.approx(0.1075, abs=2e-4)  # Milankovitch
    for mu in (0.3965, 0.5, 0.8):
        assert min_thickness(1.0, math.pi, N, friction=mu) == pytest.approx(heyman, abs=1e-10)


def test_just_below_the_published_rotational_friction_the_arch_must_be_thicker():
    # published 0.395832 (centreline weights); ours is 0.39523 for true centroids: between them
    heyman = min_thickness(1.0, math.pi, N)
    assert min_thickness(1.0, math.pi, N, friction=0.3945) > heyman * (1 + 1e-4)


def test_no_thickness_below_the_published_least_friction():
    # mu_min = 0.309215 published; here 0.3092153
    near = min_thickness(1.0, math.pi, N, friction=0.30923)
    assert near == pytest.approx(0.200637, rel=0.015)  # published t/r at mu_min
    assert friction_margin(circular_arch(1.0, math.pi, near, N), 0.30923) >= 0
    with pytest.raises(NoThicknessError, match="friction 0.3092"):
        min_thickness(1.0, math.pi, N, friction=0.30920)


def test_the_minimum_grows_as_the_friction_falls_in_the_mixed_range():
    values = [min_thickness(1.0, math.pi, N, friction=mu) for mu in (0.38, 0.35, 0.32)]
    assert values == sorted(values)


def test_a_shaped_semicircle_agrees():
    # the same arch through the shapes' builder
    shaped = shaped_min_thickness("circular", voussoirs=N, radius=1.0, embrace=math.pi,
                                  friction=0.35)
    assert shaped == pytest.approx(min_thickness(1.0, math.pi, N, friction=0.35), rel=1e-8)


@pytest.mark.parametrize("bad", [-0.1, float("nan"), True, "0.3"])
def test_bad_friction_is_refused(bad):
    with pytest.raises(ValueError, match="friction"):
        min_thickness(1.0, math.pi, N, friction=bad)
