"""The code check of a local mechanism (Circolare 2019 §C8.7.1), each quantity against an
independent value: hand sums, closed forms, the paper's numbers, a second route."""

import math

import numpy as np
import pytest

from archquake import oppenheim
from archquake.constants import GRAVITY
from archquake.fourlink.mechanism import mechanisms
from archquake.geometry import arch_on_piers
from archquake.limit_analysis import both_directions, virtual_displacements
from archquake.site.local_mechanism import (
    KNOWLEDGE_LEVELS,
    SiteAction,
    capacity_curve,
    check_local_mechanism,
    confidence_factor,
    participation,
    participation_of,
    rigid_capacity_curve,
)


class LinearSpectrum:
    """A stand-in spectrum proportional to a_g: PGA = 1.2 a_g, a plateau 2.5 PGA up to
    0.5 s, then 1/T; SDe = Se g (T / 2 pi)^2."""

    def __init__(self, ag):
        self.pga = 1.2 * ag

    def acceleration(self, period):
        period = np.asarray(period, dtype=float)
        return 2.5 * self.pga * np.minimum(1.0, 0.5 / np.maximum(period, 1e-12))

    def displacement(self, period):
        period = np.asarray(period, dtype=float)
        return self.acceleration(period) * GRAVITY * (period / (2.0 * math.pi)) ** 2


def test_one_block_participates_whole():
    # M* = (P dx)^2 / (g P dx^2) = P / g, e* = 1, whatever dx
    p = participation_of(0.25, [2000.0], [2000.0], [0.7], "l")
    assert p.mass_fraction == pytest.approx(1.0, rel=1e-14)
    assert p.participating_mass == pytest.approx(2000.0 / GRAVITY, rel=1e-14)


def test_portal_frame_by_hand():
    # two columns of mass mc, height h, turning about their bases (centroids at h/2 move
    # h/2 per radian) and a beam of mass mb moving h:
    # M* = (mc + mb)^2 / (mc/2 + mb), e* = M* / (2 mc + mb)
    mc, mb, h = 3.0, 5.0, 4.0
    masses = np.array([mc, mc, mb])
    p = participation_of(0.3, masses * GRAVITY, masses * GRAVITY, [h / 2, h / 2, h], "l")
    m_star = (mc + mb) ** 2 / (mc / 2 + mb)
    assert p.participating_mass == pytest.approx(m_star, rel=1e-13)
    assert p.mass_fraction == pytest.approx(m_star / (2 * mc + mb), rel=1e-13)  # 64/6.5/11


def test_a0_star_from_alpha0_and_the_knowledge_level():
    # a0* = alpha0 g / (e* FC): Oppenheim's alpha0 = 0.37 (Table 1 of the paper)
    result = both_directions(oppenheim())[0]
    p = participation(result, confidence_factor("LC1"))
    assert p.alpha0 == pytest.approx(0.37, abs=5e-4)
    assert p.spectral_acceleration == pytest.approx(
        p.alpha0 * GRAVITY / (p.mass_fraction * 1.35), rel=1e-14)
    assert KNOWLEDGE_LEVELS == {"LC1": 1.35, "LC2": 1.20, "LC3": 1.00}


@pytest.mark.parametrize("structure", [oppenheim(), arch_on_piers(oppenheim(), 3.0, 6.0, 2)],
                         ids=["oppenheim", "on-piers"])
def test_participation_two_routes_agree(structure):
    # the limit analysis's virtual displacements (rigid-body fields of its mechanism) and the
    # four-link mechanism's mode shape (finite differences of its closure) give one e*
    limit = both_directions(structure)
    for result, mech in zip(limit, mechanisms(structure, limit), strict=True):
        from_limit = participation(result)
        from_curve = capacity_curve(mech).participation
        assert from_curve.mass_fraction == pytest.approx(from_limit.mass_fraction, rel=1e-8)
        assert from_curve.participating_mass == pytest.approx(
            from_limit.participating_mass, rel=1e-8)
        assert from_curve.alpha0 == pytest.approx(result.load_multiplier, rel=1e-8)


def test_blocks_outside_the_mechanism_do_not_move():
    # on piers 3 m x 6 m of two courses the hinges are at joints 3, 5, 8, 11: the left pier's
    # two courses and the first voussoir stay, and are not in the sum of weights
    structure = arch_on_piers(oppenheim(), 3.0, 6.0, 2)
    result = both_directions(structure)[0]
    dx = virtual_displacements(result)
    assert result.hinges[0].joint == 3
    assert np.all(dx[:3] == 0.0) and np.all(dx[3:] > 0.0)
    p = participation(result)
    assert p.moving_weight == pytest.approx(structure.loads.vertical[3:].sum(), rel=1e-14)


def test_capacity_curve_is_the_equation_of_motion_static_balance():
    # alpha(theta) by virtual work on the displaced blocks equals -F/P of the equation of
    # motion (fourlink.equations_of_motion, written independently); it falls to zero at the
    # critical angle, theta_u - theta_cr = 0.0691 rad for Oppenheim's arch (Sect. 5.1)
    mech, _ = mechanisms(oppenheim())
    curve = capacity_curve(mech)
    _, _, f, p = mech.coefficients(mech.theta_u - curve.rotation)
    np.testing.assert_allclose(curve.multiplier, -f / p, atol=1e-8)
    assert curve.rotation[-1] == pytest.approx(0.0691, abs=5e-5)
    assert curve.rotation[-1] == pytest.approx(mech.phi_cr, abs=1e-9)
    assert curve.multiplier[0] == pytest.approx(0.37, abs=5e-4)
    assert curve.multiplier[-1] == pytest.approx(0.0, abs=1e-9)


def _rocking_block(half_width, half_height):
    """A block of width 2b and height 2h on the ground, turning about its right toe (0, 0)."""
    centroid = np.array([[-half_width, half_height]])

    def positions(phi):
        c, s = np.cos(-phi)[:, None], np.sin(-phi)[:, None]  # clockwise, toward +x
        x, y = centroid[:, 0], centroid[:, 1]
        return np.stack((c * x - s * y, s * x + c * y), axis=-1)

    return positions


def test_rocking_block_capacity_curve_closed_form():
    # alpha(phi) = tan(atan(b/h) - phi); the curve ends at phi = atan(b/h), where the
    # centroid stands over the toe, having moved b (half the width); e* = 1 so d0* = b and
    # a0* = (b/h) g
    b, h = 0.4, 1.5
    curve = rigid_capacity_curve([1000.0], _rocking_block(b, h), math.pi / 2, points=101)
    np.testing.assert_allclose(curve.multiplier, np.tan(math.atan(b / h) - curve.rotation),
                               atol=1e-8)
    assert curve.rotation[-1] == pytest.approx(math.atan(b / h), abs=1e-10)
    assert curve.participation.mass_fraction == pytest.approx(1.0, rel=1e-12)
    assert curve.d0 == pytest.approx(b, rel=1e-9)
    assert curve.spectral_acceleration[0] == pytest.approx(b / h * GRAVITY, rel=1e-8)
    # the secant point at SLC: d_s = 0.4 * 0.4 * b; a* there from the closed form
    d_s, a_s, t_s = curve.secant("SLC")
    assert d_s == pytest.approx(0.16 * b, rel=1e-9)
    r = math.hypot(b, h)
    phi_s = math.atan(b / h) - math.asin((b - d_s) / r)  # x of the centroid: -r sin(a - phi)
    assert a_s == pytest.approx(math.tan(math.atan(b / h) - phi_s) * GRAVITY, rel=1e-4)
    assert t_s == pytest.approx(2 * math.pi * math.sqrt(d_s / a_s), rel=1e-12)


def test_linear_and_nonlinear_checks_against_hand_values():
    arch = oppenheim()
    fc = 1.2
    check = check_local_mechanism(arch, [SiteAction("SLV", 0.25, LinearSpectrum),
                                         SiteAction("SLC", 0.30, LinearSpectrum)],
                                  confidence_factor=fc)
    part = participation(both_directions(arch)[0], fc)
    for c in check.linear:
        # a0* >= a_g S / q: demand 1.2 * 0.25 / 2 = 0.15 g; the PGA capacity 1.2 ag / 2 = a0*
        assert c.demand == pytest.approx(0.15, rel=1e-14)
        assert c.capacity == pytest.approx(part.spectral_acceleration_g, rel=1e-12)
        assert c.pga_capacity == pytest.approx(c.capacity * 2.0 / 1.2, rel=1e-5)
        assert c.passes == (c.capacity >= 0.15)
    curve = capacity_curve(mechanisms(arch)[0], fc)
    for c in check.nonlinear:
        d_u = {"SLV": 0.24, "SLC": 0.40}[c.limit_state] * curve.d0
        assert c.ultimate_displacement == pytest.approx(d_u, rel=1e-9)
        ag = {"SLV": 0.25, "SLC": 0.30}[c.limit_state]
        demand = float(LinearSpectrum(ag).displacement(c.secant_period))
        assert c.demand == pytest.approx(demand, rel=1e-12)
        # SDe is proportional to a_g: the capacity is a_g d_u / SDe(T_s)
        assert c.pga_capacity == pytest.approx(ag * d_u / demand, rel=1e-5)
    assert check.holds("SLV") == any(all(c.passes for c in route)
                                     for route in check.routes("SLV").values())


def test_verdict_fails_where_no_route_holds():
    # at a_g = 2.5 x the least PGA capacity every check fails
    arch = oppenheim()
    check = check_local_mechanism(arch, SiteAction("SLV", 0.2, LinearSpectrum))
    capacity = check.pga_capacity("SLV")
    strong = check_local_mechanism(arch, SiteAction("SLV", min(1.4, 2.5 * capacity),
                                                    LinearSpectrum))
    assert strong.holds("SLV") is False and strong.passes is False
    assert strong.holds("SLC") is None


def test_bad_input_is_named():
    with pytest.raises(ValueError, match="knowledge_level"):
        confidence_factor("LC4")
    with pytest.raises(ValueError, match="confidence_factor"):
        confidence_factor(value=0.9)
    with pytest.raises(ValueError, match="limit_state"):
        SiteAction("SLD", 0.2, LinearSpectrum)
    with pytest.raises(ValueError, match="ag"):
        SiteAction("SLV", -0.2, LinearSpectrum)
    with pytest.raises(ValueError, match="behaviour_factor"):
        check_local_mechanism(oppenheim(), SiteAction("SLV", 0.2, LinearSpectrum),
                              behaviour_factor=0.5)


def test_ntc_action_at_another_ag_keeps_the_site():
    # NTC 2018 soil C, F0 2.4, Tc* 0.3 s: at a_g = 0.25 g the action itself; at 0.1 g,
    # S_S = min(1.5, 1.70 - 0.60 * 2.4 * 0.1) = 1.5 and T_D = 4 * 0.1 + 1.6 = 2.0 s
    from archquake.site.spectra import ntc2018_spectrum

    action = SiteAction.of("SLV", ntc2018_spectrum(0.25, 2.4, 0.3, "C"))
    assert action.ag == 0.25 and action.spectrum.pga == pytest.approx(0.25 * 1.34, rel=1e-12)
    low = action.spectrum_at(0.1)
    assert low.s == pytest.approx(1.5) and low.t_d == pytest.approx(2.0)


def test_oppenheim_at_an_italian_site_pga_capacity_is_where_the_check_just_holds():
    from archquake.site.spectra import ntc2018_spectrum

    action = SiteAction.of("SLC", ntc2018_spectrum(0.25, 2.4, 0.3, "C"))
    check = check_local_mechanism(oppenheim(), action, confidence_factor=1.35)
    for c in check.nonlinear:
        at_capacity = action.spectrum_at(c.pga_capacity)
        assert float(at_capacity.displacement(c.secant_period)) == pytest.approx(
            c.ultimate_displacement, rel=1e-4)


def test_floor_demand_of_a_mechanism_in_a_building():
    # Circolare 2009 C8A.4.9-10 by hand: Z = 6 m of H = 12 m, N = 4 storeys, T1 = 0.4 s:
    # psi gamma = 0.5 * 12 / 9 = 2/3; with the stand-in spectrum at a_g = 0.2 (PGA 0.24 g,
    # plateau 0.6 g at T1): linear demand 0.6 * 2/3 / 2 = 0.2 g > the ground's 0.12 g
    from archquake.site.local_mechanism import Elevation

    floor = Elevation(6.0, 12.0, 0.4, 4)
    assert floor.amplification == pytest.approx(2.0 / 3.0, rel=1e-14)
    check = check_local_mechanism(oppenheim(), SiteAction("SLV", 0.2, LinearSpectrum),
                                  elevation=floor)
    for c in check.linear:
        assert c.demand == pytest.approx(0.2, rel=1e-12)
    spectrum = LinearSpectrum(0.2)
    for c in check.nonlinear:
        r = c.secant_period / 0.4
        floor_demand = (float(spectrum.displacement(0.4)) * 2 / 3 * r ** 2
                        / math.sqrt((1 - r) ** 2 + 0.02 * r)) if r < 1.5 else 0.0
        assert c.demand == pytest.approx(
            max(float(spectrum.displacement(c.secant_period)), floor_demand), rel=1e-12)
    with pytest.raises(ValueError, match="height must be <= building_height"):
        Elevation(13.0, 12.0, 0.4, 4)
    with pytest.raises(ValueError, match="storeys"):
        Elevation(6.0, 12.0, 0.4, 0)


def test_passive_fill_leaves_the_nonlinear_check_out_and_says_why():
    # the fill's passive reaction raises alpha0 in the limit analysis; the capacity curve of
    # the blocks' weights does not carry it, so a nonlinear check would start elsewhere
    from archquake.geometry import StructureSpec

    structure = StructureSpec(fill_cover=1.0, fill_passive=(30.0, 0.5)).arches()[1]
    check = check_local_mechanism(structure, SiteAction("SLV", 0.25, LinearSpectrum))
    assert check.nonlinear == () and check.curves == ()
    assert any("passive" in note for note in check.notes)
    assert check.linear and check.holds("SLV") == all(c.passes for c in check.linear)
