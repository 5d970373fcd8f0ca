"""The four-link mechanism, its equation of motion, impacts and the rigid-block model on arches
of any shape, each checked against an independent value."""

import math

import numpy as np
import pytest

from archquake.fourlink.impact import computed_restitution, kinetic_energy_ratio, restitution
from archquake.fourlink.mechanism import mechanisms
from archquake.fourlink.time_history import free_vibration
from archquake.geometry import GRAVITY, SHAPES, irregular_arch, shaped_arch, surveyed_arch
from archquake.limit_analysis import both_directions
from archquake.studies.failure_domain import domain_of
from kinematics_reference import instantaneous_velocities, mirrored_hinges

RISES = {"circular": 3.5, "pointed": 7.5, "elliptical": 4.0, "parabolic": 4.5, "catenary": 4.5,
         "three-centred": 3.0}


def arch_of(shape, faces="curved", seed=None):
    arch = shaped_arch(shape, span=10.0, rise=RISES[shape], thickness=0.8, voussoirs=8,
                       faces=faces)
    return arch if seed is None else irregular_arch(arch, 0.1, rng=seed)


def oppenheim_flat():
    return shaped_arch("circular", radius=10.0, embrace=math.radians(157.5), thickness=1.5,
                       voussoirs=7, faces="flat")


@pytest.mark.parametrize("shape", SHAPES)
@pytest.mark.parametrize("faces", ["curved", "flat"])
def test_activation_of_the_mechanism_is_the_limit_multiplier(shape, faces):
    """Virtual work of the dynamic model at theta_u equals the static LP's multiplier."""
    arch = arch_of(shape, faces, seed=3)
    limit = both_directions(arch)
    for mech, result in zip(mechanisms(arch, limit=limit), limit, strict=True):
        assert mech.activation_g == pytest.approx(result.load_multiplier, abs=1e-9)
        assert result.thrust_line.points[[h.joint for h in mech.hinges]] == pytest.approx(
            mech.hinge_points, abs=1e-6)
        assert mech.theta_limit < mech.theta_cr < mech.theta_u
        assert mech.is_admissible


def _independent_computed_restitution(arch, hinges_l, hinges_r_original):
    """c_v = -<v, u> / <u, u> in the kinetic-energy metric, with the velocity fields of both
    mechanisms from their instantaneous centres (tests/kinematics_reference.py), the post-impact
    field scaled to unit rate of its own coordinate (its first link turning at -1 in the
    original frame, the mirror of +1)."""
    v, w = instantaneous_velocities(arch, hinges_l)
    u, om = instantaneous_velocities(arch, hinges_r_original)
    last = hinges_r_original[-1].joint - 1  # a voussoir of the post-impact link at the right
    scale = -1.0 / om[last]
    u, om = u * scale, om * scale
    m, inertia = arch.masses, arch.inertias
    num = np.sum(m * np.sum(v * u, axis=1) + inertia * w * om)
    den = np.sum(m * np.sum(u * u, axis=1) + inertia * om * om)
    return -num / den


@pytest.mark.parametrize("shape", SHAPES)
def test_computed_restitution_matches_an_independent_momentum_balance(shape):
    arch = arch_of(shape, seed=5)
    mech_l, mech_r = mechanisms(arch)
    c = computed_restitution(mech_l, mech_r)
    expected = _independent_computed_restitution(arch, mech_l.hinges,
                                                 mirrored_hinges(arch, mech_r.hinges))
    assert c == pytest.approx(expected, rel=1e-9)
    assert 0.0 < kinetic_energy_ratio(mech_l, mech_r) <= 1.0


def _trapezoid(points, density):
    x, y = points[:, 0], points[:, 1]
    x1, y1 = np.roll(x, -1), np.roll(y, -1)
    c = x * y1 - x1 * y
    area = c.sum() / 2
    g = np.array([((x + x1) * c).sum(), ((y + y1) * c).sum()]) / (6 * area)
    polar = ((x * x + x * x1 + x1 * x1 + y * y + y * y1 + y1 * y1) * c).sum() / 12
    return density * abs(area), g, density * (abs(polar) - abs(area) * g @ g)


def test_link_restitution_of_flat_faced_oppenheim_arch_is_the_papers():
    """Oppenheim's arch with flat-faced (trapezoidal) voussoirs: the paper's link-wise rule
    gives its 0.875 to three decimals (Housner's rule for voussoirs 0-1 turning from the
    intrados to the extrados end of the springing joint, written here from the joint ends)."""
    arch = oppenheim_flat()
    mech_l, mech_r = mechanisms(arch)
    assert [h.joint for h in mech_l.hinges] == [0, 3, 5, 7]
    c_lr, c_rl = restitution("link", mech_l, mech_r)
    assert round(c_lr, 3) == 0.875 and c_rl == pytest.approx(c_lr, rel=1e-12)
    radius, beta = (9.25, 10.75), math.radians(11.25)
    step = math.radians(157.5) / 7
    centre = np.array([0.0, -10.0 * math.cos(math.radians(157.5) / 2)])

    def corner(r, b):
        return centre + r * np.array([-math.cos(b), math.sin(b)])

    a, a_prime = corner(radius[0], beta), corner(radius[1], beta)
    props = [_trapezoid(np.array([corner(radius[0], beta + i * step),
                                  corner(radius[0], beta + (i + 1) * step),
                                  corner(radius[1], beta + (i + 1) * step),
                                  corner(radius[1], beta + i * step)]), arch.density)
             for i in (0, 1)]
    num = sum(inertia + m * (g - a_prime) @ (g - a) for m, g, inertia in props)
    den = sum(inertia + m * (g - a_prime) @ (g - a_prime) for m, g, inertia in props)
    assert c_lr == pytest.approx(num / den, rel=1e-12)
    # the momentum balance of the whole arch gives a much lower value, as for curved faces
    assert restitution("computed", mech_l, mech_r)[0] == pytest.approx(0.6456, abs=1e-4)


@pytest.mark.parametrize("shape", ["pointed", "elliptical", "three-centred"])
def test_elastic_free_rocking_conserves_energy(shape):
    """c_v = 1 on a symmetric arch: the energy M theta'^2 / 2 + V(theta) is the same before
    and after every impact and along every segment (to the integrator's tolerance)."""
    mech_l, mech_r = mechanisms(arch_of(shape))
    history = free_vibration((mech_l, mech_r), (1.0, 1.0), phi0=0.02, t_end=6.0)
    assert history.impact_times.size >= 2
    energies = []
    for segment in history.segments:
        if segment.mechanism == "rest":
            continue
        mech = mech_l if segment.mechanism == "l" else mech_r
        m = mech.coefficients(segment.theta)[0]
        energies.append(0.5 * m * segment.theta_dot**2 + mech.potential_energy(segment.theta))
    energies = np.concatenate(energies)
    scale = abs(mech_l.potential_energy(mech_l.theta_u - 0.02)
                - mech_l.potential_energy(mech_l.theta_u))
    assert np.ptp(energies) <= 1e-5 * scale


@pytest.mark.parametrize("shape", ["pointed", "parabolic"])
def test_rigid_block_model_of_a_shaped_arch_starts_moving_at_its_limit_multiplier(shape):
    """The independent rigid-block model (its own contact dynamics, the arch's joints read by
    its one adapter) stays at rest 1 % below k and opens the limit analysis's four hinges 1 %
    above it."""
    from archquake.ground_motion import rectangular_pulse
    from archquake.rigid_blocks import block_outcome, simulate_blocks

    arch = arch_of(shape, seed=2)
    result = both_directions(arch)[0]
    k = result.load_multiplier
    below = block_outcome(arch, rectangular_pulse(-0.99 * k * GRAVITY, 1.0))
    assert below.status.label == "rest" and below.max_opening < 1e-8
    history = simulate_blocks(arch, rectangular_pulse(-1.01 * k * GRAVITY, 1.0), t_end=1.0,
                              record_every=50)
    opened = {(int(j), int(e)) for j, e in zip(*np.nonzero(history.gaps[-1] > 1e-4),
                                                strict=True)}
    assert opened == {(h.joint, 1 if h.face == "intrados" else 0) for h in result.hinges}


def test_surveyed_arch_runs_through_the_dynamics(nominal):
    """A surveyed arch is an arch like any other for the mechanisms and impacts."""
    survey = surveyed_arch([nominal.outline(i, 200)[:-1] for i in range(7)])
    reference = [m.theta_cr for m in mechanisms(nominal)]
    assert [m.theta_cr for m in mechanisms(survey)] == pytest.approx(reference, abs=1e-5)
    assert restitution("computed", *mechanisms(survey))[0] == pytest.approx(
        restitution("computed", *mechanisms(nominal))[0], abs=1e-5)


def test_failure_domain_and_fragility_of_a_pointed_arch():
    """The studies take a shaped arch unchanged: below k the arch does not move, the k line of
    the domain is the limit analysis's, and a fragility study's settings store the arch."""
    from archquake import FourLinkModel
    from archquake.studies.fragility import FragilitySettings, run_fragility

    arch = arch_of("pointed")
    k = both_directions(arch)[0].load_multiplier
    domain = domain_of(FourLinkModel.from_arch(arch, "computed"),
        [0.4, 0.6], np.linspace(0.05, 1.0, 20))
    assert domain.limit_multiplier == pytest.approx(k, abs=1e-12)
    for piece in domain.slices:
        assert piece.intervals[0].status == "rest"
        assert piece.intervals[0].end == pytest.approx(k, abs=2e-3)
    settings = FragilitySettings(nominal=arch, sample_size=2, limit_sample_size=4,
                                 durations=(0.4,), amplitudes_g=(0.1, 0.3, 0.5))
    assert FragilitySettings.from_dict(settings.to_dict()) == settings
    result = run_fragility(settings, progress=False, backend="serial")
    assert result.nominal_load_multiplier == pytest.approx(k, abs=1e-9)
    assert result.limit_load_multipliers.size == 4
    with pytest.raises(ValueError, match="centreline"):
        FragilitySettings(nominal=surveyed_arch([arch.outline(i)[:-1] for i in range(8)]))
