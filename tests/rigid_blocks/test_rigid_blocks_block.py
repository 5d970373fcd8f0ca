"""The rigid-block model on a single block: Housner's rocking, overturning, Coulomb sliding,
energy and convergence, each against a closed form or an ODE written here independently.

The rocking ODE (Housner 1963) of a rectangular block of half-width b, half-height h on a rigid
base, in the frame of the ground, with theta > 0 counterclockwise (rocking on the left corner):

    theta'' = -p^2 [ sin(alpha - theta) - (xg''/g) cos(alpha - theta) ]    (theta > 0)
    theta'' = +p^2 [ sin(alpha + theta) + (xg''/g) cos(alpha + theta) ]    (theta < 0)

with alpha = atan(b/h), R = sqrt(b^2 + h^2), p^2 = 3 g / (4 R); at theta = 0 the angular
velocity is multiplied by r = 1 - 1.5 sin^2(alpha) (angular momentum conserved about the
impacting corner, no bounce).
"""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from archquake.geometry import GRAVITY
from archquake.ground_motion import HARMONIC, LINEAR, GroundMotion, read_record, rectangular_pulse
from archquake.rigid_blocks import (
    BlockSettings,
    block_outcome,
    rectangular_block,
    simulate_blocks,
)
from archquake.rigid_blocks.contact_problem import local_coulomb
from archquake.rigid_blocks.solver import mean_acceleration

WIDTH, HEIGHT = 0.4, 2.0
B, H = WIDTH / 2, HEIGHT / 2
ALPHA = math.atan2(B, H)
RADIUS = math.hypot(B, H)
P = math.sqrt(3.0 * GRAVITY / (4.0 * RADIUS))
HOUSNER_R = 1.0 - 1.5 * math.sin(ALPHA) ** 2


@pytest.fixture(scope="module")
def block():
    return rectangular_block(WIDTH, HEIGHT)


def tilted(theta: float):
    """Initial state of the block turned by theta > 0 about its left corner, at rest."""
    corner, centroid = np.array([-B, 0.0]), np.array([0.0, H])
    c, s = math.cos(theta), math.sin(theta)
    moved = corner + np.array([[c, -s], [s, c]]) @ (centroid - corner)
    q0 = np.array([[*(moved - centroid), theta]])
    return q0, np.zeros((1, 3))


def rocking(ground, theta0: float, t_end: float, breaks=()):
    """Housner's rocking ODE with impacts (module docstring) by solve_ivp.

    Returns (overturned, impact times, solution segments).
    """
    def rhs(side):
        def f(t, y):
            a = ground(t) / GRAVITY
            if side > 0:
                return [y[1], -P * P * (math.sin(ALPHA - y[0]) - a * math.cos(ALPHA - y[0]))]
            return [y[1], P * P * (math.sin(ALPHA + y[0]) + a * math.cos(ALPHA + y[0]))]
        return f

    t0, y, segments, impacts = 0.0, [theta0, 0.0], [], []
    for stop in sorted({b for b in breaks if 0 < b < t_end} | {t_end}):
        while t0 < stop:
            if y[0] != 0.0 or y[1] != 0.0:
                side = 1 if (y[0] > 0 or (y[0] == 0 and y[1] > 0)) else -1
            else:  # at rest on its base: lifts off only above g tan(alpha)
                a = ground(0.5 * (t0 + stop))
                if abs(a) <= GRAVITY * math.tan(ALPHA):
                    t0 = stop
                    break
                side = 1 if a > 0 else -1
            hit = lambda t, y: y[0]  # noqa: E731
            hit.terminal, hit.direction = True, -side
            over = lambda t, y: abs(y[0]) - 0.5 * math.pi  # noqa: E731
            over.terminal = True
            sol = solve_ivp(rhs(side), [t0, stop], y, events=[hit, over], rtol=1e-11,
                            atol=1e-13, dense_output=True)
            segments.append(sol)
            if sol.t_events[1].size:
                return True, impacts, segments
            if sol.t_events[0].size:
                t0 = float(sol.t_events[0][0])
                impacts.append(t0)
                y = [0.0, HOUSNER_R * float(sol.y_events[0][0][1])]
                continue
            y, t0 = list(sol.y[:, -1]), stop
    return False, impacts, segments


def crossings(history, count: int):
    """First ``count`` times [s] at which the block's rotation crosses zero (linear interp.)."""
    th, t = history.rotations[:, 0], history.times
    k = np.flatnonzero(np.sign(th[:-1]) * np.sign(th[1:]) < 0)[:count]
    return t[k] + (t[k + 1] - t[k]) * th[k] / (th[k] - th[k + 1])


def test_free_rocking_half_cycle_matches_housner(block):
    """Time from release at rest (theta0 = alpha/2) to the first impact: solve_ivp of the
    nonlinear ODE, and Housner's closed form of the linearised one, (1/p) arccosh(1/(1 -
    theta0/alpha)) -- within 0.2 % for this slender block."""
    theta0 = 0.5 * ALPHA
    _, impacts, _ = rocking(lambda t: 0.0, theta0, 1.0)
    closed_form = math.acosh(1.0 / (1.0 - theta0 / ALPHA)) / P
    assert impacts[0] == pytest.approx(closed_form, rel=2e-3)
    history = simulate_blocks(block, None, BlockSettings(time_step=2e-4),
                              initial=tilted(theta0), t_end=0.6)
    assert crossings(history, 1)[0] == pytest.approx(impacts[0], abs=1e-4)  # O(h) timing


def test_rocking_amplitude_decays_by_housner_coefficient(block):
    """Energy after / before each impact = r^2, r = 1 - 1.5 sin^2(alpha): the rocking
    amplitude theta_i after impact i obeys cos(alpha - theta_i) - cos(alpha)
    = r^(2i) (cos(alpha - theta_0) - cos(alpha)) (Housner 1963, restitution 0, no slip)."""
    theta0 = 0.5 * ALPHA
    history = simulate_blocks(block, None, BlockSettings(time_step=1e-4),
                              initial=tilted(theta0), t_end=3.4)
    times = crossings(history, 4)
    th, t = history.rotations[:, 0], history.times
    energy0 = math.cos(ALPHA - theta0) - math.cos(ALPHA)
    for i in range(1, 4):
        window = (t > times[i - 1]) & (t < times[i])
        amplitude = float(np.abs(th[window]).max())
        energy = math.cos(ALPHA - amplitude) - math.cos(ALPHA)
        # the closing corner sinks by up to theta h |u_n| (O(h)): 0.3 % of the energy here
        assert energy / energy0 == pytest.approx(HOUSNER_R ** (2 * i), rel=3e-3)
    # the impacts conserve angular momentum about the new corner: no slip, no bounce
    assert history.outcome.max_slip < 1e-5


@pytest.mark.parametrize("duration", [0.3, 0.6])
def test_overturning_threshold_of_rectangular_pulse(block, duration):
    """Lowest amplitude of a rectangular pulse that overturns the block: bisection on the
    rocking ODE with impacts (solve_ivp) vs the rigid-block failure acceleration, within 1 %
    (both bisected to 1e-3 g; the block model's time step is 1 ms)."""
    def overturns(a_g):
        overturned, _, _ = rocking(lambda t: a_g * GRAVITY if t < duration else 0.0, 0.0,
                                   duration + 8.0, breaks=(duration,))
        return overturned

    lo, hi = 0.2, 2.0
    assert not overturns(lo) and overturns(hi)
    while hi - lo > 1e-3:
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if overturns(mid) else (mid, hi)
    ode = 0.5 * (lo + hi)
    from archquake.rigid_blocks import RigidBlockModel
    from archquake.studies.failure_domain import domain_of

    dem = domain_of(RigidBlockModel(block), [duration], np.arange(0.15, 1.0, 0.05),
                    direction="r", motion="rectangular", resolution_g=1e-3,
                    extend_to_g=None).slices[0]
    assert dem.failure_acceleration_g == pytest.approx(ode, rel=1e-2)
    # and the block starts rocking at g tan(alpha) = 0.2 g (statics)
    assert dem.intervals[0].status == "rest"
    assert dem.intervals[1].start == pytest.approx(math.tan(ALPHA), abs=1e-3)


def test_sliding_block_follows_coulomb():
    """A squat block (b/h = 2) on a base with mu = 0.3 under a constant ground acceleration
    a = 0.5 g slides, relative to the ground, by -(a - mu g) t^2 / 2 exactly (it cannot tip:
    a/g < b/h), and its base stays closed."""
    squat = rectangular_block(2.0, 0.5)
    mu, a = 0.3, 0.5 * GRAVITY
    history = simulate_blocks(squat, rectangular_pulse(a, 2.0),
                              BlockSettings(friction=mu, time_step=1e-3), t_end=1.0)
    t = history.times
    exact = -0.5 * (a - mu * GRAVITY) * t**2
    np.testing.assert_allclose(history.displacements[:, 0, 0], exact, rtol=1e-9, atol=1e-12)
    # the contact problem's compliance (1e-9 of the Delassus diagonal) lets it sink by 1e-11 m
    np.testing.assert_allclose(history.displacements[:, 0, 1], 0.0, atol=1e-9)
    np.testing.assert_allclose(history.rotations[:, 0], 0.0, atol=1e-9)
    # friction = mu x normal force, on the block toward +x against its slide; the base's tangent
    # (its normal +y turned by +90 degrees) is -x, hence the sign
    total_normal = history.normal_forces[1:, 0].sum(axis=1)
    total_tangent = history.tangential_forces[1:, 0].sum(axis=1)
    np.testing.assert_allclose(total_normal, squat.total_mass * GRAVITY, rtol=1e-7)
    np.testing.assert_allclose(-total_tangent, mu * total_normal, rtol=1e-7)


def test_block_below_friction_limit_sticks():
    """Same block with a = 0.25 g < mu g: no slip at all (static friction)."""
    squat = rectangular_block(2.0, 0.5)
    out = block_outcome(squat, rectangular_pulse(0.25 * GRAVITY, 1.0),
                        BlockSettings(friction=0.3))
    assert out.status.label == "rest"
    assert out.max_slip < 1e-9


def test_energy_is_never_created_beyond_discretisation(block):
    """Free rocking (no excitation): the recorded energies close the balance
    E(t) - E(0) = W_input - D to round-off (theta = 1/2); each impact removes (1 - r^2) of the
    kinetic energy; between impacts the total energy may rise above its running minimum only
    by the time-discretisation error of the contact Jacobians (first order in h: it halves
    with h, and stays below 0.2 % of E(0) at h = 1 ms), never by a source."""
    rises = []
    for h in (1e-3, 5e-4):  # every step at h (the coarse steps: test_rigid_blocks_coarse_steps)
        history = simulate_blocks(block, None, BlockSettings(time_step=h, coarse_factor=1),
                                  initial=tilted(0.5 * ALPHA), t_end=3.0)
        energy = history.total_energy
        balance = energy - energy[0] + history.dissipated_energy - history.input_work
        assert np.abs(balance).max() < 1e-9 * energy[0]
        rise = float((energy - np.minimum.accumulate(energy)).max())
        rises.append(rise / energy[0])
        assert energy[-1] < 0.7 * energy[0]  # four impacts: r^8 = 0.62
    assert rises[0] < 2e-3
    assert 1.6 < rises[0] / rises[1] < 2.5


def test_convergence_of_impact_times_is_first_order(block):
    """Impact times vs the ODE as h shrinks, RMS over 9 release angles (which samples where the
    impact falls within its step). The first impact ends a smooth motion: its error halves with
    h. The second follows an impact resolved to within a step (and a closing corner that sinks
    by up to theta h |u_n|): its error is O(h) times a factor that depends on where the impact
    falls, and its fitted order is 1."""
    angles = np.linspace(0.4, 0.6, 9) * ALPHA
    reference = [rocking(lambda t: 0.0, theta0, 3.0)[1][:2] for theta0 in angles]
    steps = np.array([2e-3, 1e-3, 5e-4, 2.5e-4, 1.25e-4])
    first, second = [], []
    for h in steps:
        errors = []
        for theta0, impacts in zip(angles, reference, strict=True):
            history = simulate_blocks(block, None, BlockSettings(time_step=h, coarse_factor=1),
                                      initial=tilted(theta0), t_end=impacts[1] + 0.05)
            errors.append(crossings(history, 2) - impacts)
        errors = np.abs(np.array(errors))
        first.append(np.sqrt(np.mean(errors[:, 0] ** 2)))
        second.append(np.sqrt(np.mean(errors[:, 1] ** 2)))
    first_orders = np.log2(np.array(first[:-1]) / np.array(first[1:]))
    np.testing.assert_allclose(first_orders, 1.0, atol=0.1)
    order = np.polyfit(np.log(steps), np.log(second), 1)[0]
    assert 0.8 < order < 1.4, order
    assert second[1] < 5e-3  # at h = 1 ms


@pytest.mark.parametrize("motion", [
    rectangular_pulse(3.0, 0.0123),
    GroundMotion(LINEAR, [0.0, 0.0104, 0.02, 0.0371], [0.0, 2.0, -1.0, 0.5]),
    GroundMotion(HARMONIC, params=[1.5, 0.0137, 2.5]),
], ids=["step", "linear", "harmonic"])
def test_mean_acceleration_is_the_integral_of_evaluate(motion):
    """The impulse of the ground motion over a step equals the quadrature of the one
    definition of the ground acceleration (ground_motion.evaluate), breakpoints included."""
    from scipy.integrate import quad

    for t0 in np.arange(-0.002, 0.045, 0.0031):
        t1 = t0 + 0.0029
        points = [x for x in np.concatenate((motion.times, [motion.duration])) if t0 < x < t1]
        exact, _ = quad(motion.acceleration, t0, t1, points=points or None, epsabs=1e-13)
        mean = mean_acceleration(t0, t1, *motion.compiled())
        assert mean * (t1 - t0) == pytest.approx(exact, abs=1e-11)


def test_record_ground_motion_drives_the_block(block, tmp_path):
    """A recorded accelerogram (linear between samples) drives the model as its analytic twin:
    a record holding 0.5 g for 0.4 s rocks the block as the rectangular pulse of that size."""
    path = tmp_path / "flat.csv"
    path.write_text("time_s,acc_g\n0,0.5\n0.4,0.5\n0.4001,0\n")
    record = read_record(path)
    pulse = rectangular_pulse(0.5 * GRAVITY, 0.4)
    a = block_outcome(block, record)
    b = block_outcome(block, pulse)
    assert a.status == b.status
    assert a.max_rotation == pytest.approx(b.max_rotation, rel=2e-3)


@pytest.mark.parametrize("name, period", [("ricker", 0.3), ("ricker-antisymmetric", 0.25),
                                          ("mavroeidis-papageorgiou", 0.4), ("cycloidal-b", 0.3),
                                          ("cycloidal-c", 0.35)])
def test_mean_acceleration_of_every_analytic_pulse(name, period):
    """The other analytic pulses too (Ricker's wavelets and Mavroeidis and Papageorgiou's pulse
    by quadrature, the cycloidal pulses with their phase in closed form): over 1 ms steps
    across the whole pulse, the step's impulse is the quadrature of evaluate. A Ricker
    wavelet of 3 g left an arch at rest (its mean was taken as 0), and the phase of a cosine
    cycloidal pulse was ignored."""
    from scipy.integrate import quad

    from archquake.ground_motion import ground_motion

    motion = ground_motion(name, 3.0 * 9.81, period)
    end = motion.duration
    for t0 in np.arange(-0.002, end + 0.002, 0.00731):
        t1 = t0 + 1e-3
        exact, _ = quad(motion.acceleration, t0, t1, points=[x for x in (0.0, end)
                                                             if t0 < x < t1] or None,
                        epsabs=1e-14)
        assert mean_acceleration(t0, t1, *motion.compiled()) * 1e-3 == pytest.approx(
            exact, abs=1e-12 * 3.0 * 9.81)


def test_ricker_pulse_moves_the_arch(nominal):
    """A 1.5 g Ricker wavelet (period 0.5 s) moves Oppenheim's arch (k = 0.37 g)."""
    from archquake.ground_motion import ground_motion

    outcome = block_outcome(nominal, ground_motion("ricker", -1.5 * 9.81, 0.5))
    assert outcome.status.label in ("recovery", "collapse") and outcome.max_rotation > 1e-3


@pytest.mark.parametrize("wnt", [0.0, 0.3, -0.3])
def test_local_coulomb_solution_satisfies_the_law(wnt):
    """Every local solution is complementary, inside the cone, and slides against u_t."""
    rng = np.random.default_rng(4)
    wnn, wtt, mu = 1.0, 1.2, 0.8
    for ufn, uft in rng.normal(size=(200, 2)):
        pn, pt = local_coulomb(ufn, uft, wnn, wnt, wtt, mu)
        un = ufn + wnn * pn + wnt * pt
        ut = uft + wnt * pn + wtt * pt
        assert pn >= 0 and un >= -1e-12 and abs(pn * un) < 1e-12
        assert abs(pt) <= mu * pn + 1e-12
        if abs(ut) > 1e-12:
            assert abs(pt) == pytest.approx(mu * pn) and pt * ut <= 0
