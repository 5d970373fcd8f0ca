import numpy as np
import pytest
from scipy.integrate import solve_ivp

from archquake import irregular_arch
from archquake.fourlink.mechanism import mechanism_from_hinges
from archquake.geometry import GRAVITY, Hinge
from kinematics_reference import Configurations, nominal_hinges, virtual_work_multiplier

SEEDS = [1, 2, 3, 4]


def _pair(arch, hinges):
    return (mechanism_from_hinges(arch, hinges, "l"),
            mechanism_from_hinges(arch.mirrored(), hinges, "r"))


def _reference_coefficients(mech, theta, h=1e-5):
    """M, L, F, P by central differences of the voussoir positions (independent code path)."""
    arch = mech.arch
    ref = Configurations(arch, mech.hinges)
    m, inertia = arch.masses, arch.inertias

    def state(t, guess):
        g, rot, guess = ref.voussoirs(t, guess)
        return g, rot, guess

    def mass_and_forces(t, guess):
        g_up, r_up, _ = state(t + h, guess)
        g_dn, r_dn, _ = state(t - h, guess)
        dg = (g_up - g_dn) / (2 * h)
        dr = (r_up - r_dn) / (2 * h)
        mass = np.sum(m * np.sum(dg**2, axis=1) + inertia * dr**2)
        return mass, np.sum(m * dg[:, 1]), -np.sum(m * dg[:, 0])

    guess = ref.link_angles(theta)
    mass, gravity, ground = mass_and_forces(theta, guess)
    k = 2e-4  # fourth-order central difference of M
    mm = [mass_and_forces(theta + j * k, guess)[0] for j in (-2, -1, 1, 2)]
    l_term = 0.5 * (mm[0] - 8 * mm[1] + 8 * mm[2] - mm[3]) / (12 * k)
    return mass, l_term, gravity, ground


@pytest.mark.parametrize("seed", [None, *SEEDS], ids=lambda s: "NA" if s is None else f"seed{s}")
def test_coefficients_match_finite_differences_of_voussoir_positions(nominal, paper, seed):
    arch = nominal if seed is None else irregular_arch(nominal, 0.1, rng=seed)
    for mech in _pair(arch, nominal_hinges(paper)):
        for phi in (0.0, 0.05, 0.4):
            theta = mech.theta_u - phi
            m_ref, l_ref, f_ref, p_ref = _reference_coefficients(mech, theta)
            m, l, f, p = mech.coefficients(theta)
            scale = abs(m_ref)
            assert m == pytest.approx(m_ref, rel=1e-7)
            # L is a difference of differences: looser
            assert l == pytest.approx(l_ref, rel=1e-6, abs=1e-6 * scale)
            assert f == pytest.approx(f_ref, rel=1e-7, abs=1e-9 * scale)
            assert p == pytest.approx(p_ref, rel=1e-7, abs=1e-9 * scale)
            # F is eq. (4) of the paper divided by g: the slope of V (eq. (3), its own formula)
            k = 1e-5
            slope = (mech.potential_energy(theta + k) - mech.potential_energy(theta - k)) / (2 * k)
            assert f == pytest.approx(slope / GRAVITY, rel=1e-8, abs=1e-9 * scale)
            assert mech.potential_energy_derivative(theta) == pytest.approx(slope, rel=1e-8,
                                                                          abs=1e-8 * scale)


def test_coefficients_are_vectorised(nominal, paper):
    mech = mechanism_from_hinges(nominal, nominal_hinges(paper))
    theta = np.linspace(mech.theta_limit + 0.01, mech.theta_u, 7)
    together = np.array(mech.coefficients(theta))
    one_by_one = np.array([mech.coefficients(t) for t in theta]).T
    assert together == pytest.approx(one_by_one, rel=1e-14)


def test_activation_of_oppenheim_arch_is_paper_load_multiplier(nominal, paper):
    hinges = nominal_hinges(paper)
    k = paper["table1"]["NA"]["load_multiplier"]
    for mech in _pair(nominal, hinges):
        m, l, f, p = mech.coefficients(mech.theta_u)
        assert -f / p == pytest.approx(k, abs=1e-3)
        assert mech.activation_g == pytest.approx(virtual_work_multiplier(nominal, hinges),
                                                  rel=1e-12)


@pytest.mark.parametrize("seed", SEEDS)
@pytest.mark.parametrize("joints", [(0, 3, 5, 7), (0, 2, 4, 7), (1, 3, 6, 7)])
def test_activation_equals_virtual_work_multiplier(nominal, seed, joints):
    arch = irregular_arch(nominal, 0.1, rng=seed)
    faces = ("intrados", "extrados", "intrados", "extrados")
    hinges = tuple(Hinge(j, f) for j, f in zip(joints, faces, strict=True))
    mech = mechanism_from_hinges(arch, hinges)
    assert mech.activation_g == pytest.approx(virtual_work_multiplier(arch, hinges), rel=1e-10)
    mirror = arch.mirrored()
    mech_r = mechanism_from_hinges(mirror, hinges, "r")
    assert mech_r.activation_g == pytest.approx(virtual_work_multiplier(mirror, hinges), rel=1e-10)


def test_free_rocking_conserves_energy(nominal, paper):
    """T + V is constant along a free motion: checks L = 1/2 dM/dtheta against M and F."""
    arch = irregular_arch(nominal, 0.1, rng=7)
    for mech in _pair(arch, nominal_hinges(paper)):
        theta0 = mech.theta_u - 0.5 * mech.phi_cr

        def rhs(t, y, mech=mech):
            return [y[1], mech.angular_acceleration(y[0], y[1], 0.0)]

        sol = solve_ivp(rhs, (0.0, 1.0), [theta0, 0.0], rtol=1e-11, atol=1e-13,
                        dense_output=True)
        theta, rate = sol.y
        energy = mech.kinetic_energy(theta, rate) + mech.potential_energy(theta)
        assert np.ptp(energy) < 1e-8 * abs(mech.potential_energy(theta0))
        # released between theta_cr and theta_u, the arch swings back to theta_u
        assert theta.max() > mech.theta_u


def test_ground_acceleration_sign_of_each_mechanism(nominal, paper):
    arch = irregular_arch(nominal, 0.1, rng=5)
    mech_l, mech_r = _pair(arch, nominal_hinges(paper))
    g = GRAVITY
    # Mech-l moves (theta decreases) when the ground accelerates toward -x beyond k_l g
    assert mech_l.angular_acceleration(mech_l.theta_u, 0.0, -(mech_l.activation_g + 0.01) * g) < 0
    assert mech_l.angular_acceleration(mech_l.theta_u, 0.0, -(mech_l.activation_g - 0.01) * g) > 0
    assert mech_l.angular_acceleration(mech_l.theta_u, 0.0, 0.0) > 0
    # Mech-r (mirrored frame, eq. (7)) moves when the ground accelerates toward +x beyond k_r g
    assert mech_r.angular_acceleration(mech_r.theta_u, 0.0, (mech_r.activation_g + 0.01) * g) < 0
    assert mech_r.angular_acceleration(mech_r.theta_u, 0.0, (mech_r.activation_g - 0.01) * g) > 0
    assert mech_r.angular_acceleration(mech_r.theta_u, 0.0, -2.0 * g) > 0
