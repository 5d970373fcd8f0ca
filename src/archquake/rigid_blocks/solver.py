r"""Compiled Moreau-Jean time stepping of rigid blocks with unilateral Coulomb contacts: the
driver.

Everything here is ``numba``-compiled but the layouts of the settings and the summary;
:func:`run` is the one driver of an analysis, the other functions are its small helpers
(section "The driver"). It takes a step by stages, each in a module of its own: the contact
geometry (:mod:`archquake.rigid_blocks.contacts`, "Contacts and their detection"), the contact
problem (:mod:`archquake.rigid_blocks.contact_problem`, "Contact problem"; Lemke's algorithm in
:mod:`archquake.rigid_blocks.lemke`) and the band solvers of its linear systems
(:mod:`archquake.rigid_blocks.band`). :mod:`archquake.rigid_blocks.dynamics` prepares the
arrays and reads the results.

Frame and unknowns
------------------
The equations are written in the frame of the ground, which translates with the ground
displacement ``xg(t)``: the supports are fixed in it, and every block carries, besides its
weight, the inertial (d'Alembert) force ``-m_i xg''(t)`` along x at its centroid (no moment, the
frame does not turn). So the ground displacement is never needed (a record's integrated
displacement drifts), contacts are detected against fixed supports, and every displacement is
relative to the ground. Block ``i`` has the coordinates ``q_i = (x_i, y_i, theta_i)`` (centroid
displacement [m] and rotation [rad], counterclockwise) and the velocities ``v_i = (u_i, w_i,
omega_i)`` [m/s, m/s, rad/s]; the mass matrix and the external forces are

.. math::

    \mathbf{M} = \operatorname{diag}(m_i, m_i, I_i), \qquad
    f_i(t) = \bigl(-m_i\,\ddot x_g(t),\; -m_i\,g,\; 0\bigr)

[kg/m, kg/m, kg m] and [N/m, N/m, N] per unit depth.

Time stepping (Moreau-Jean, theta-method)
-----------------------------------------
On each step ``[t_k, t_k + h]``, with the contact geometry and the Jacobians evaluated at
``q_k`` [1]_, [2]_ (Ch. 10):

.. math::

    \mathbf{M} (v_{k+1} - v_k) = \int_{t_k}^{t_{k+1}} f\,dt + H_k^T P_{k+1}, \qquad
    q_{k+1} = q_k + h\,[(1 - \theta) v_k + \theta v_{k+1}]

where the impulse of the external forces is exact (weight, and the ground acceleration
integrated over the step by :func:`mean_acceleration`, so a jump of a pulse inside a step costs
no accuracy): :math:`\int f_i\,dt = -h\,m_i\,(\bar a_g, g, 0)` with :math:`\bar a_g` the mean
ground acceleration over the step. The valid contacts whose predicted gap is below
:data:`ACTIVATION_GAP` times the joint's length ``L`` (zero but for round-off) form the active
set

.. math::

    \mathcal{I}_k = \{\, c \text{ valid} : g_c(q_k) + \theta\,h\,u_{n,c}(v_k)
    \le \epsilon_a L_c \,\}, \qquad \epsilon_a = 10^{-9};

for them the impulses ``P = (P_n, P_t)`` [N s/m] satisfy Newton's impact law with restitution 0
at the velocity level [3]_ and Coulomb's law (friction coefficient mu) as complementarity
conditions on the velocities ``u = H_k v_{k+1}`` at the end of the step:

.. math::

    0 \le u_n \perp P_n \ge 0, \qquad |P_t| \le \mu P_n, \qquad
    u_t \ne 0 \Rightarrow P_t = -\mu P_n \operatorname{sign}(u_t)

(the impulse lies in Coulomb's cone and opposes the slip); the other contacts carry no impulse.
A closing contact penetrates by at most ``theta h |u_n|`` (0.25 mm for 0.5 m/s at h = 1 ms,
theta = 1/2) and never drifts at rest. The contact problem that these conditions pose at every
step, and how it is solved: :mod:`archquake.rigid_blocks.contact_problem`.

Energy
------
Kinetic energy in the ground frame, potential energy of the weights (zero in the undeformed
configuration), work of the inertial forces ``-m xg''`` (the input) and work of the contact
impulses (its opposite is the dissipated energy), all [J/m]:

.. math::

    T = \tfrac12 \sum_i \bigl(m_i (u_i^2 + w_i^2) + I_i \omega_i^2\bigr), \qquad
    V = \sum_i m_i\,g\,y_i,

    W_{k+1} - W_k = -h\,\bar a_g \sum_i m_i\,\frac{u_{i,k} + u_{i,k+1}}{2}, \qquad
    D_{k+1} - D_k = -\sum_{c \in \mathcal{I}_k} P_c \cdot
    \frac{H_c v_k + H_c v_{k+1}}{2}.

For ``theta = 1/2`` and these linear forces,
:math:`(T + V)_{k+1} - (T + V)_k = (W_{k+1} - W_k) - (D_{k+1} - D_k)` holds exactly per step,
so the bookkeeping closes to round-off. The scheme is not exactly dissipative: the contact
Jacobians are those of ``q_k``, in which a persistent pivot's velocity ``v_k`` (made zero in
the configuration of the previous step) is not exactly zero, so the contact work can be
positive by O(h^2) per step; for a rocking block this is 0.15 % of its energy over 3 s at
h = 1 ms, halving with h (tested). The same lag costs energy where a pivot forms: in the
Jacobian of ``q_k`` the pivot separates under ``v_k`` at about :math:`h \omega^2 r` (``r``
its distance from the centroid), and once :math:`\theta h^2 \omega^2 r` passes the
activation gap it leaves the active set for one step, falls freely and lands again, losing
about :math:`\tfrac12 m (g h)^2` and sinking by :math:`g h^2`. A block 0.4 m x 2 m released
at half its slenderness loses so 0.018, 0.055, 0.11 and 0.53 J (of 233 J) before its first
impact at h = 0.25, 0.5, 1 and 2 ms. One reason why a coarser step makes an arch look stronger
(``benchmarks/rigid_block_time_step.py``: at 2 ms Oppenheim's arch fails 0.005 g higher under
a pulse of 0.4 s).

Coarse steps
------------
With ``coarse_factor = k > 1`` (:class:`~archquake.rigid_blocks.dynamics.BlockSettings`; 2 by
default, and never a step longer than the motion allows) a step that starts on the grid of
``k h`` is first taken with the length ``k h``; where a contact starts or stops carrying an
impulse in it (an impact, a lift-off, a landing: a contact enters or leaves the set of those
that are active and stick or slide) or the active-set method does not converge, it is taken
again from the same state at ``h``, and the steps at ``h`` go on to the next point of the
coarse grid. Between the events of the contacts a rocking structure moves smoothly, and the
second-order scheme keeps its accuracy at ``k h``; every event is resolved at ``h``. In this
mode a contact that carried an impulse at the end of a step stays in the active set of the next
while it is valid (the active-set method opens it if it separates): otherwise the lag of the
Jacobian above ("Energy") lifts a persistent pivot off for one step at ``k h`` nearly every
other step, and each lift-off would be an event. The
energy balance of every step closes whatever its length. Measured
(``benchmarks/rigid_block_time_step.py``, ``benchmarks/rigid_block_fragility.py``) at
``k = 2``, ``h = 1`` ms: the failure accelerations of Oppenheim's arch at t_p = 0.3-0.7 s lie
within 0.0008 g of those at uniform steps of 0.25 ms (at uniform 1 ms within 0.0023 g, at
uniform 2 ms up to 0.0125 g above), at 0.25 s within 0.0086 g (1 ms: 0.0172 g), for about half
the contact problems (the paper's rigid-block study in 27 s instead of 50 s on two workers);
``k = 3`` gave -0.0156 g at 0.25 s and within 0.0008 g from 0.3 s on, not studied further.
Where the smooth motion dominates, the coarse steps cost what they save: a block rocking
freely is timed as with every step at ``k h``, since the lag above is first order in the step.
Rest counts its window in steps ``h``: a coarse step counts as ``k``. A step is coarse only
where it starts on the grid of ``k h``, so that records at every ``k``-th step fall on the same
times whatever is recorded.

The driver
----------
:func:`run` is a short loop over small compiled helpers; one loop is one step, in these phases
(the code carries the same numbers)::

    1. geometry     gap, offset, validity and Jacobian of every contact at q_k
    2. measure      energies, drops, rotations and the joints at t_k
    3. record       the first state at or after every record_stride-th step h (recording
                    only; every record_stride-th state when every step is at h)
    4. decide       the outcome tests (:func:`run`), until one holds
    5. stop?        decided (and the record's tail done), or the last step
    6. free         the impulse of the weight and of the ground over the step: v^f
    7. active set   the valid contacts whose predicted gap closes
    8. contacts     the contact problem: active-set method, else Lemke's algorithm (else
                    Gauss-Seidel, not observed); a coarse step
                    in which a contact starts or stops carrying an impulse (or the active-set
                    method fails) is taken again at h from 6 ("Coarse steps")
    9. advance      energy bookkeeping and the positions q_{k+1}
    10. at rest     two steps at rest under one constant ground acceleration: the steps that
                    would repeat them are skipped (:func:`steady_steps`; unless the setting
                    ``skip_rest`` is 0); under a motion that varies (not STEP), the steps
                    whose mean accelerations lie in the range in which the contact problem
                    holds the blocks (:func:`~.contact_problem.rest_range`,
                    :func:`held_steps`), the blocks moved by the creep of those steps
                    (:func:`_creep`)

Where the steps go (``benchmarks/rigid_block_savings.py``, Oppenheim's arch under Oppenheim's
pulse over the paper's grid, t_p = 0.4-0.7 s x 0.2-0.8 g, the steps solved by phase that the
summary counts): 61 % during the pulse once the arch moves, 38 % after it while it moves (the
free rocking of the recoveries, the fall of the collapses to the drop that decides), under
0.5 % at rest (the rest of a pulse below the arch's activation, and the window of rest, are
skipped: 5-7 steps solved of 1300-2200). Under a record most steps are at rest (50-99 % of a
30 s far-field record at 0.3-1.5 g on Oppenheim's arch), and the rest within the range that
holds the arch is skipped: ``python benchmarks/rigid_block_savings.py --records`` measures it
side by side with every step taken. Deciding every recovery at the end of the pulse would
save at most 15 % of the steps. No recovery is decided from its energy before it comes to rest:
``T + V`` falls after the excitation (up to the O(h^2) of "Energy"), but a level that no
collapse can pass from below is the least mountain pass of ``V`` between the rest and every
configuration of collapse, over every mechanism of the blocks (hinges at any joints, several at
once, and sliding, which lowers ``V`` with no barrier at all where friction lets it): no bound
of it is proved here, and the outcome must be that of the full run.

The structure reaches the driver as three packed arrays (the blocks,
:data:`~.contacts.BODY_FIELDS`; the contacts, :data:`~.contacts.CONTACT_FIELDS`; the bodies of
every contact) and the settings as one vector (:data:`SETTINGS_FIELDS`, :func:`pack_settings`):
one compiled signature serves every structure and every analysis. How each part is compiled
was chosen by measurement, as in the four-link engine's driver: the parts of a step that take
arrays (the contact geometry, the contact problem, the active set, the bookkeeping) are
compiled on their own without numba's reference counting (``_nrt=False``: they allocate
nothing; counting the references of the arrays handed to a helper, at every call, cost as much
as the arithmetic of the active set), and the small helpers they call for every contact are
inlined into them (``inline="always"``), from whichever module holds them.

References
----------
.. [1] M. Jean, "The non-smooth contact dynamics method", Comput. Methods Appl. Mech. Engrg. 177
   (1999) 235-257.

.. [2] V. Acary, B. Brogliato, "Numerical methods for nonsmooth dynamical systems", Springer
   (2008), Ch. 10 (Moreau-Jean time stepping) and Ch. 12-13 (Gauss-Seidel for the contact
   problem).

.. [3] J. J. Moreau, "Unilateral contact and dry friction in finite freedom dynamics", in
   Nonsmooth Mechanics and Applications, CISM Courses and Lectures 302, Springer (1988) 1-82.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from ..ground_motion import HARMONIC, STEP, analytic_duration, evaluate
from .band import copy_1d, copy_2d
from .block_space import solve_active_set_blocks
from .contact_problem import (
    SWITCH_VELOCITY,
    incidence,
    rest_range,
    solve_active_set,
    solve_contacts,
    solve_lemke,
)
from .contacts import (
    BODY_INERTIA,
    BODY_MASS,
    FRICTION,
    LENGTH,
    contact_geometry,
    relative_velocity,
    rotate,
)

ACTIVATION_GAP = 1e-9
"""Predicted gap, as a fraction of the joint's length, below which a contact is active [-]: a
closed joint's round-off gap (1e-16 m) must not drop it from the contact problem."""

RETRY_STEPS = 16
"""Steps [-] after which a structure at rest under a varying ground motion is tested again for
a skip (:func:`held_steps`) when the last test skipped none: each test costs two solves of
the contact problem."""

STEADY_ENERGY = 1e-12
r"""Kinetic energy below which a step is at rest, as a fraction of the energy of rest
:math:`T_{rest}` [-] (velocities about :math:`10^{-6}` of the speed of rest,
:math:`10^{-10}` m/s for Oppenheim's arch; round-off leaves :math:`10^{-13}` m/s in a structure
held by its contacts). Two consecutive steps at rest under the same ground acceleration are a
static equilibrium: :func:`run` skips the steps that would repeat them (:func:`steady_steps`).
A contact may be at its friction limit in it (the active-set method then calls it sliding, at
zero speed); a slide that starts would leave the rest within a step: a velocity of
:math:`10^{-10}` m/s after one step of 1 ms is an unbalanced acceleration of
:math:`10^{-7}` m/s^2, and any smaller one moves a block by less than a micrometre over a
pulse."""

REST, RECOVERY, COLLAPSE = 0, 1, 2
"""Outcome codes of :func:`run` [-] (-1 while undecided)."""

SUMMARY_FIELDS = (
    "status", "decided", "collapse_time", "decision_time", "max_rotation", "max_crown_drop",
    "max_slip", "max_opening", "max_drop", "steps", "iterations", "max_iterations_used",
    "unconverged_steps", "final_time", "closed", "fallbacks", "solved_still", "solved_pulse",
    "solved_free", "solved_window",
)
"""Layout of the summary vector returned by :func:`run`: outcome code; 1 if decided; collapse and
decision times [s] (nan if none); largest block rotation [rad], crown drop, slip, opening and
drop [m]; steps, linear solves or sweeps in all, most in one step, unconverged steps [-]; final
time of the run [s]; 1 if every joint was closed; steps left to Gauss-Seidel [-] (a coarse step
counts in ``steps`` as the steps ``h`` it spans); the steps solved (a contact problem each, a
coarse step and a step skipped as in :func:`steady_steps` counting one and none) until the
decision by phase [-]: during the excitation while the structure has not yet moved (its kinetic
energy never above :math:`T_{rest}`), during the excitation after that, after it while the
structure moves (the count of rest at 0), and after it in the window of rest. Everything but
the final time is that of the decision (of the last step if undecided): a recording that goes on
after the decision changes nothing of it."""


_G1, _G2 = math.sqrt(5.0 - 2.0 * math.sqrt(10.0 / 7.0)) / 3.0, math.sqrt(
    5.0 + 2.0 * math.sqrt(10.0 / 7.0)) / 3.0
GAUSS_NODES = (-_G2, -_G1, 0.0, _G1, _G2)
GAUSS_WEIGHTS = ((322.0 - 13.0 * math.sqrt(70.0)) / 900.0, (322.0 + 13.0 * math.sqrt(70.0)) / 900.0,
                 128.0 / 225.0, (322.0 + 13.0 * math.sqrt(70.0)) / 900.0,
                 (322.0 - 13.0 * math.sqrt(70.0)) / 900.0)
"""Nodes on [-1, 1] and weights of 5-point Gauss-Legendre quadrature [-] (exact for
polynomials of degree 9)."""


@numba.njit(cache=True, _nrt=False)
def mean_acceleration(t0, t1, kind, params, times, values):
    r"""Mean ground acceleration [m/s^2] over ``[t0, t1]`` [s]: its integral / (t1 - t0).

    For every kind of the compiled representation of :mod:`archquake.ground_motion`: the same
    function as :func:`archquake.ground_motion.evaluate`, integrated in closed form,

    .. math::

        \bar a_g = \frac{1}{t_1 - t_0} \int_{t_0}^{t_1} a_g(t)\,dt, \qquad
        \int_a^b A \sin(\omega t + \phi)\,dt
        = \frac{A}{\omega}\,\bigl(\cos(\omega a + \phi) - \cos(\omega b + \phi)\bigr)

    for a harmonic motion (clipped to ``[0, cycles * period]``), the exact sum of rectangles
    (STEP) or trapezoids (LINEAR) of the pieces of a tabulated one (0 outside its times); the
    other analytic pulses (Ricker's wavelets, Mavroeidis and Papageorgiou's pulse), smooth on
    ``[0, duration)``, by 5-point Gauss-Legendre quadrature of the part of the interval inside
    it (exact to round-off for a step much shorter than the pulse's period).

    Parameters
    ----------
    t0, t1 : float
        Interval [s], ``t1 > t0``.
    kind : int
        A kind of :mod:`archquake.ground_motion` (``STEP``, ``LINEAR``, ``HARMONIC``, ...).
    params : array of float
        For the analytic kinds: their parameters (for HARMONIC amplitude [m/s^2], period [s],
        number of cycles [-] and phase [rad]).
    times, values : array of float
        For STEP and LINEAR: increasing times [s] and accelerations [m/s^2].

    Returns
    -------
    float
        The mean acceleration [m/s^2].
    """
    total = 0.0
    if kind == HARMONIC:
        amplitude, period, cycles, phase = params[0], params[1], params[2], params[3]
        a = max(t0, 0.0)
        b = min(t1, cycles * period)
        if b > a:
            w = 2.0 * math.pi / period
            total = amplitude / w * (math.cos(w * a + phase) - math.cos(w * b + phase))
        return total / (t1 - t0)
    if kind > HARMONIC:  # smooth on [0, duration): Gauss-Legendre on the part inside it
        a = max(t0, 0.0)
        b = min(t1, analytic_duration(kind, params))
        if b > a:
            mid, half = 0.5 * (a + b), 0.5 * (b - a)
            for k in range(5):
                total += GAUSS_WEIGHTS[k] * evaluate(mid + half * GAUSS_NODES[k], kind, params,
                                                     times, values)
            total *= half
        return total / (t1 - t0)
    n = times.size
    if n < 2 or t1 <= times[0] or t0 >= times[n - 1]:
        return 0.0
    i = max(np.searchsorted(times, t0, side="right") - 1, 0)
    while i < n - 1 and times[i] < t1:
        a = max(t0, times[i])
        b = min(t1, times[i + 1])
        if b > a:
            if kind == STEP:
                total += values[i] * (b - a)
            else:  # LINEAR
                slope = (values[i + 1] - values[i]) / (times[i + 1] - times[i])
                fa = values[i] + slope * (a - times[i])
                fb = values[i] + slope * (b - times[i])
                total += 0.5 * (fa + fb) * (b - a)
        i += 1
    return total / (t1 - t0)


SETTINGS_FIELDS = (
    "time_step", "theta", "friction", "tolerance", "max_iterations", "gravity",
    "excitation_end", "n_steps", "drop_limit", "rest_energy", "closed_gap", "rest_steps",
    "open_rest_steps", "moved_threshold", "energy_margin", "record_stride", "tail_steps",
    "crown_block", "crown_x", "crown_y", "coarse_factor", "active_set_solves", "skip_rest",
)
"""Entries of the settings vector of :func:`run` (:func:`pack_settings`; counts and indices stored
as floats): time step h [s]; theta [-]; friction coefficient mu [-]; Gauss-Seidel tolerance as a
fraction of ``m_mean g h`` [-]; largest number of Gauss-Seidel sweeps per step [-]; g [m/s^2];
end of the excitation :math:`t_{exc}` [s]; largest number of steps [-]; drop of collapse
:math:`\\delta_{lim}` [m]; kinetic energy of rest :math:`T_{rest}` [J/m]; largest gap of a closed
contact [m]; steps of rest that decide with every joint closed, and with a joint open [-]; opening
and slip at or below which the structure never moved [m]; :math:`E_{margin}` of the energy test
of collapse [J/m]; ``record_stride`` (every ``record_stride``-th state recorded, 0: no record)
and ``tail_steps`` (steps recorded after the decision, -1: to ``n_steps``) [-]; the block that
carries the crown point and that point relative to its centroid [m]; the steps of ``h`` taken as
one while no contact starts or stops carrying an impulse (:func:`run`) [-]; the largest number of
linear solves of the active-set method in a step before Lemke's algorithm takes over (0: Lemke's
algorithm at every step) [-]; 1 to skip the steps that repeat a static equilibrium
(:func:`steady_steps`), 0 to take every step (the same outcome: a check) [-]."""

(S_TIME_STEP, S_THETA, S_FRICTION, S_TOLERANCE, S_MAX_ITERATIONS, S_GRAVITY, S_EXCITATION_END,
 S_N_STEPS, S_DROP_LIMIT, S_REST_ENERGY, S_CLOSED_GAP, S_REST_STEPS, S_OPEN_REST_STEPS,
 S_MOVED_THRESHOLD, S_ENERGY_MARGIN, S_RECORD_STRIDE, S_TAIL_STEPS, S_CROWN_BLOCK, S_CROWN_X,
 S_CROWN_Y, S_COARSE_FACTOR, S_ACTIVE_SET_SOLVES, S_SKIP_REST) = range(23)

RECORD_ENERGY_FIELDS = ("t", "kinetic", "potential", "dissipated", "input")
"""Columns of the record of times and energies: t [s], T, V, D, W [J/m]."""


def pack_settings(**values) -> np.ndarray:
    """The settings vector of :func:`run` from its entries by name (:data:`SETTINGS_FIELDS`).

    Parameters
    ----------
    **values : float
        Every name of :data:`SETTINGS_FIELDS`, in the units stated there.

    Returns
    -------
    ndarray (len(SETTINGS_FIELDS),)

    Raises
    ------
    ValueError
        If a name is missing or unknown.
    """
    missing = set(SETTINGS_FIELDS) - set(values)
    unknown = set(values) - set(SETTINGS_FIELDS)
    if missing or unknown:
        raise ValueError(f"settings: missing {sorted(missing)}, unknown {sorted(unknown)}")
    return np.array([float(values[name]) for name in SETTINGS_FIELDS])


# ---------------------------------------------------------------------------------------------
# Parts of the driver loop
# ---------------------------------------------------------------------------------------------


@numba.njit(cache=True, _nrt=False)
def _kinetic_energy(bodies, v):
    """Kinetic energy :math:`T` of the blocks at velocities ``v`` (nb, 3) [J/m]."""
    kinetic = 0.0
    for i in range(bodies.shape[0]):
        kinetic += 0.5 * (bodies[i, BODY_MASS] * (v[i, 0] ** 2 + v[i, 1] ** 2)
                          + bodies[i, BODY_INERTIA] * v[i, 2] ** 2)
    return kinetic


@numba.njit(cache=True, _nrt=False)
def _measure(q, bodies, gravity, crown_block, crown_x, crown_y):
    """Potential energy [J/m], largest block rotation [rad], and the drops [m] at ``q``: the
    largest downward displacement of a centroid or of the crown point, and the crown's.

    Returns ``(potential, max_rotation, drop, crown_drop)``."""
    potential = 0.0
    drop = 0.0
    rotation = 0.0
    for i in range(bodies.shape[0]):
        potential += bodies[i, BODY_MASS] * gravity * q[i, 1]
        drop = max(drop, -q[i, 1])
        rotation = max(rotation, abs(q[i, 2]))
    cos_c, sin_c = math.cos(q[crown_block, 2]), math.sin(q[crown_block, 2])
    _, cy = rotate(cos_c, sin_c, crown_x, crown_y)
    crown_drop = -(q[crown_block, 1] + cy - crown_y)
    return potential, rotation, max(drop, crown_drop), crown_drop


@numba.njit(cache=True, _nrt=False)
def _joints(gap, slip, valid, closed_gap, max_slip, max_opening):
    """The joints at the current step: the largest slip (at the more closed end of a joint)
    and opening (of a valid contact) so far [m], and whether every joint is closed (both of
    its contacts valid with a gap at most ``closed_gap`` [m]).

    Returns ``(max_slip, max_opening, closed)``."""
    closed = True
    for j in range(gap.size // 2):
        c0, c1 = 2 * j, 2 * j + 1
        closer = c0 if gap[c0] <= gap[c1] else c1
        max_slip = max(max_slip, abs(slip[closer]))
        for c in (c0, c1):
            if valid[c]:
                max_opening = max(max_opening, gap[c])
                if gap[c] > closed_gap:
                    closed = False
            else:
                closed = False
    return max_slip, max_opening, closed


@numba.njit("float64[:, ::1](float64[:, ::1], int64)", cache=True)
def _grow(buffer, n):
    """``buffer`` (rows, k) with room for row ``n``: itself, or a copy twice as long.

    Its signature is declared: numba would otherwise compile it once more for the literal first
    row (0) of a record."""
    if n < buffer.shape[0]:
        return buffer
    out = np.empty((2 * buffer.shape[0], buffer.shape[1]))
    copy_2d(out, buffer)  # not a slice assignment: this function compiles at import
    return out


@numba.njit(cache=True, inline="always")
def _record(n, t, q, gap, slip, impulse, h, energies, rec_energy, rec_q, rec_contacts):
    """Record the state at ``t`` [s] as row ``n``: time and the energies ``(T, V, D, W)``
    [J/m], the displacements [m, m, rad], and per contact the gap and offset [m] and the mean
    forces ``P / h`` [N/m] of the step that ends here. The buffers grow as needed.

    Returns ``(rec_energy, rec_q, rec_contacts)``."""
    rec_energy = _grow(rec_energy, n)
    rec_q = _grow(rec_q, n)
    rec_contacts = _grow(rec_contacts, n)
    rec_energy[n, 0] = t
    for k in range(4):
        rec_energy[n, 1 + k] = energies[k]
    nb = q.shape[0]
    for i in range(nb):
        for k in range(3):
            rec_q[n, 3 * i + k] = q[i, k]
    nc = gap.size
    for c in range(nc):
        rec_contacts[n, c] = gap[c]
        rec_contacts[n, nc + c] = slip[c]
        rec_contacts[n, 2 * nc + 2 * c] = impulse[c, 0] / h
        rec_contacts[n, 2 * nc + 2 * c + 1] = impulse[c, 1] / h
    return rec_energy, rec_q, rec_contacts


@numba.njit(cache=True, inline="always")
def _decide(t, drop, kinetic, potential, closed, max_opening, max_slip, rest_count, last,
            settings):
    r"""The outcome tests at ``t`` [s] (docstring of :func:`run`), at the end of a step of
    ``last`` steps ``h`` (a coarse step counts as the steps it spans).

    Returns ``(status, rest_count)``: :data:`COLLAPSE`, :data:`RECOVERY`, :data:`REST` or -1
    (undecided), and the count of consecutive still steps ``h``."""
    after = t >= settings[S_EXCITATION_END]
    if drop >= settings[S_DROP_LIMIT] or (after and kinetic + potential
                                          < -settings[S_ENERGY_MARGIN]):
        return COLLAPSE, rest_count
    if after and kinetic <= settings[S_REST_ENERGY]:
        rest_count += last
        needed = settings[S_REST_STEPS] if closed else settings[S_OPEN_REST_STEPS]
        if rest_count >= needed:
            moved = (max_opening > settings[S_MOVED_THRESHOLD]
                     or max_slip > settings[S_MOVED_THRESHOLD])
            return (RECOVERY if moved else REST), rest_count
        return -1, rest_count
    return -1, 0


@numba.njit(cache=True, _nrt=False)
def _free_velocities(v, v_old, v_free, h, ag, gravity):
    """Keep ``v`` (nb, 3) in ``v_old`` and make it the free velocity of the step, also kept in
    ``v_free``: the impulse of the weight and of the inertial force ``-m ag`` over ``h`` [s],
    ``ag`` the mean ground acceleration [m/s^2]."""
    for i in range(v.shape[0]):
        v_old[i, 0] = v[i, 0]
        v_old[i, 1] = v[i, 1]
        v_old[i, 2] = v[i, 2]
        v[i, 0] -= h * ag
        v[i, 1] -= h * gravity
        v_free[i, 0] = v[i, 0]
        v_free[i, 1] = v[i, 1]
        v_free[i, 2] = v[i, 2]


@numba.njit(cache=True, _nrt=False)
def _active_set(gap, valid, v_old, contact_bodies, contacts, jac, theta, h, carried, active):
    r"""The active set: the valid contacts that carried an impulse at the end of the last step
    (``carried``), and those whose predicted gap :math:`g + \theta h u_n(v_k)` is at most
    :data:`ACTIVATION_GAP` times their joint's length."""
    for c in range(gap.size):
        if valid[c]:
            un, _ = relative_velocity(v_old, contact_bodies[c, 0], contact_bodies[c, 1], jac, c)
            active[c] = carried[c] or (gap[c] + theta * h * un
                                       <= ACTIVATION_GAP * contacts[c, LENGTH])
        else:
            active[c] = False


@numba.njit(cache=True, _nrt=False)
def _contact_work(v_old, v, v_free, bodies):
    r"""Work of the contact impulses over the step [J/m],

    .. math::

        \sum_c P_c \cdot H_c \frac{v_k + v_{k+1}}{2}
        = \frac{v_k + v_{k+1}}{2} \cdot \mathbf{M} (v_{k+1} - v^f),

    since :math:`\mathbf{M} (v_{k+1} - v^f) = H^T P`: a sum over the blocks, not the
    contacts."""
    work = 0.0
    for i in range(v.shape[0]):
        m, inertia = bodies[i, BODY_MASS], bodies[i, BODY_INERTIA]
        work += 0.5 * (m * ((v_old[i, 0] + v[i, 0]) * (v[i, 0] - v_free[i, 0])
                            + (v_old[i, 1] + v[i, 1]) * (v[i, 1] - v_free[i, 1]))
                       + inertia * (v_old[i, 2] + v[i, 2]) * (v[i, 2] - v_free[i, 2]))
    return work


@numba.njit(cache=True, _nrt=False)
def _advance(q, v_old, v, bodies, h, theta, ag):
    r"""Positions :math:`q_{k+1} = q_k + h ((1 - \theta) v_k + \theta v_{k+1})`, in place.

    Returns the work of the inertial forces over the step and the kinetic energy at its end
    [J/m]."""
    work = 0.0
    kinetic = 0.0
    for i in range(q.shape[0]):
        m = bodies[i, BODY_MASS]
        work -= m * h * ag * 0.5 * (v_old[i, 0] + v[i, 0])
        kinetic += 0.5 * (m * (v[i, 0] ** 2 + v[i, 1] ** 2)
                          + bodies[i, BODY_INERTIA] * v[i, 2] ** 2)
        for k in range(3):
            q[i, k] += h * ((1.0 - theta) * v_old[i, k] + theta * v[i, k])
    return work, kinetic


@numba.njit(cache=True, _nrt=False)
def _changed(active, state, carried):
    """Whether a contact starts or stops carrying an impulse in this step (``carried``: the
    contacts that carried one at the end of the last step; a contact carries one when it is
    active and sticks or slides, ``state > 0``)."""
    for c in range(active.size):
        if (active[c] and state[c] > 0) != carried[c]:
            return True
    return False


@numba.njit(cache=True, _nrt=False)
def steady_steps(step, h, ag, kind, params, times, values, settings, rest_count, closed,
                 last, stop_step):
    r"""How many steps from ``step`` on repeat a static equilibrium (0 if none can be skipped).

    Called after two consecutive steps at rest (kinetic energy at most
    :data:`STEADY_ENERGY` :math:`T_{rest}` before and after the last one): the contact
    forces held the blocks under the mean ground acceleration ``ag`` [m/s^2] of the last step,
    so every following step under the same acceleration repeats it (the same contact problem,
    the same zero velocities). Those steps are

    - before the end of the excitation, of a piecewise-constant motion (``STEP``): the steps
      that lie wholly in the piece of the next step, if its mean acceleration is ``ag`` (to
      round-off: the mean over a step is computed from its ends) (``times[i] <= t <
      times[i + 1]``), up to the last point of the grid of coarse steps (``coarse_factor``
      ``k``: the multiples of ``k``) before the step that meets ``times[i + 1]``: from there on
      the steps are those of the run without the skip, coarse or not, so a motion that starts
      in a later piece is taken by the same steps;
    - after it, on a still ground: the steps of the count of rest up to the one that decides
      (its window, ``rest_steps`` if every joint is ``closed``, else ``open_rest_steps``, less
      the ``rest_count`` steps already counted and the ``last`` steps ``h`` of the step just
      taken, which the next test counts), the count advanced as the run without the skip
      advances it (a coarse step of ``k`` from a multiple of ``k`` whose step fits before
      ``stop_step``, else a step ``h``), so that the decision falls on the same step as
      without the skip.

    Nothing of the outcome changes but the round-off of the skipped steps (velocities of
    :math:`10^{-13}` m/s): the same status, times of collapse and of decision, steps
    (``BlockSettings.skip_rest`` False takes them all: tested). Returns the number of steps to
    skip [-]."""
    t = step * h
    coarse = max(1, int(settings[S_COARSE_FACTOR]))
    if t >= settings[S_EXCITATION_END]:
        if ag != 0.0:
            return 0
        needed = settings[S_REST_STEPS] if closed else settings[S_OPEN_REST_STEPS]
        s, count = step, rest_count + last  # the count that the test at step s sees
        while count < needed:
            m = coarse if (s % coarse == 0 and s + coarse <= stop_step) else 1
            s += m
            count += m
        return s - step
    if kind != STEP or abs(mean_acceleration(t, t + h, kind, params, times, values)
                           - ag) > 1e-12 * settings[S_GRAVITY]:  # the same, to round-off
        return 0
    n = times.size
    i = np.searchsorted(times, t, side="right")  # times[i - 1] <= t < times[i]
    if i >= n:
        return 0
    whole = int(math.floor(times[i] / h)) - 1  # the last step wholly before times[i]
    return max(0, (whole // coarse) * coarse - step)


@numba.njit(cache=True, _nrt=False)
def held_steps(step, h, a0, lo, hi, kind, params, times, values, settings, stop_step):
    r"""How many steps from ``step`` on a structure at rest stays so under a ground motion that
    varies (0 if none can be skipped): the steps that end before the end of the excitation and
    whose mean ground accelerations all lie in :math:`[a_0 + lo, a_0 + hi]`, the range in which
    the contact problem keeps the blocks still (:func:`~.contact_problem.rest_range`), up to
    the last point of the grid of coarse steps (``coarse_factor`` ``k``) before the first that
    does not. A coarse step's mean acceleration is the mean of those of its steps ``h``, so it
    lies in the range too; from that point on the steps are those of the run without the skip.
    The skip ends before the end of the excitation, so that the step that reaches it, which
    starts the count of rest, is taken.
    """
    coarse = max(1, int(settings[S_COARSE_FACTOR]))
    end = settings[S_EXCITATION_END]
    k = step
    while k < stop_step and (k + 1) * h < end:
        a = mean_acceleration(k * h, (k + 1) * h, kind, params, times, values) - a0
        if not lo <= a <= hi:
            break
        k += 1
    return max(0, (k // coarse) * coarse - step)


@numba.njit(cache=True, _nrt=False)
def _creep(q, v, bodies, start, end, h, theta, coarse, a0, kind, params, times, values, v0, dv):
    r"""Move the blocks, in place, as the steps ``start .. end`` (steps ``h``) that a skip
    under a varying motion leaves out would have moved them: a step of length ``hs`` from rest
    ends at the velocity :math:`(h_s / h_c)(v_0 + \delta\,\partial v)` of the affine path of
    :func:`~.contact_problem.rest_range` (computed for the longest step, :math:`h_c = k h`:
    the velocities of rest are those that the compliance of the contacts leaves, proportional
    to the impulses, so to the step), and
    :math:`q \leftarrow q + h_s\,((1 - \theta) v_{old} + \theta v)`, over the steps the run
    without the skip takes (coarse from the grid of ``k h``). The compliance lets a structure
    at rest creep by :math:`10^{-9}` of its size over a record; without this the skip would
    leave it where it was, and a chaotic rocking that starts later would diverge from the full
    run's. Sets ``v`` to the last step's velocities; returns their kinetic energy [J/m]."""
    hc = coarse * h
    s = start
    while s < end:
        m = coarse if s % coarse == 0 and s + coarse <= end else 1
        hs = m * h
        delta = mean_acceleration(s * h, s * h + hs, kind, params, times, values) - a0
        factor = hs / hc
        for i in range(q.shape[0]):
            for k in range(3):
                new = factor * (v0[i, k] + delta * dv[i, k])
                q[i, k] += hs * ((1.0 - theta) * v[i, k] + theta * new)
                v[i, k] = new
        s += m
    return _kinetic_energy(bodies, v)


@numba.njit(cache=True, _nrt=False)
def _path_impulses(delta, m, idx, p0, dp, impulse):
    """The impulses of the ``m`` active contacts ``idx[:m]`` at ``delta`` on their affine path
    (:func:`~.contact_problem.rest_range`), into ``impulse``."""
    for i in range(m):
        impulse[idx[i], 0] = p0[2 * i] + delta * dp[2 * i]
        impulse[idx[i], 1] = p0[2 * i + 1] + delta * dp[2 * i + 1]


# ---------------------------------------------------------------------------------------------
# The driver
# ---------------------------------------------------------------------------------------------

@numba.njit(cache=True)
def run(bodies, contacts, contact_bodies, q0, v0, kind, params, times, values, settings,
        blocks_band):
    r"""Integrate the blocks from ``(q0, v0)`` under the ground motion; decide the outcome.

    One loop of the driver is one step, in the phases of the module docstring ("The driver").
    With :math:`\delta` the largest downward displacement of a block centroid or of the crown
    point [m], ``T`` and ``V`` the kinetic and potential energy [J/m], the outcome is

    .. math::

        \text{collapse} \iff \delta \ge \delta_{lim} \;\text{ or }\;
        \bigl(t \ge t_{exc} \text{ and } T + V < -E_{margin}\bigr),

        \text{recovery or rest} \iff t \ge t_{exc} \text{ and } T \le T_{rest}
        \text{ for } N \text{ consecutive steps}, \quad
        N = \begin{cases} \text{rest\_steps} & \text{every joint closed} \\
        \text{open\_rest\_steps} & \text{otherwise} \end{cases}

    (a joint is closed when both its contacts are valid with gap <= ``closed_gap``; the count
    restarts at every step that is not still); rest if no valid contact ever opened, and no
    joint ever slipped at its more closed end, by more than ``moved_threshold``, recovery
    otherwise. A run that reaches ``n_steps`` undecided returns status -1. The summary is that
    of the decision: a record's tail after it (``tail_steps``) changes nothing of it.

    Parameters
    ----------
    bodies : array (nb, 4)
        The blocks (:data:`~.contacts.BODY_FIELDS`).
    contacts : array (nc, 14)
        The contacts (:data:`~.contacts.CONTACT_FIELDS`; among them the friction coefficient
        of the contact's joint, nan for the settings' ``friction``).
    contact_bodies : array of int (nc, 2)
        Bodies a and b of every contact (-1: the ground).
    q0, v0 : array (nb, 3)
        Initial displacements [m, m, rad] and velocities [m/s, m/s, rad/s].
    kind, params, times, values
        The compiled ground motion (``GroundMotion.compiled()``; accelerations [m/s^2], times
        [s]).
    blocks_band : tuple
        ``(position, kb)``: to solve the contact problems in the blocks' velocities
        (:func:`~.block_space.solve_active_set_blocks`), the blocks' positions in the band and
        its half-bandwidth (:func:`~.block_space.block_band`); an empty ``position`` solves them
        in the impulses (:func:`~.contact_problem.solve_active_set`). Either way a step where
        the active-set method gives up is solved by Lemke's algorithm.
    settings : array
        The settings vector (:data:`SETTINGS_FIELDS`, :func:`pack_settings`). With
        ``record_stride > 0``, the first state at or after every ``record_stride``-th step
        ``h`` is recorded (every ``record_stride``-th state if every step is at ``h``; with
        coarse steps, ``record_stride`` a multiple of ``coarse_factor`` records at its
        multiples exactly) and the run goes on
        ``tail_steps`` steps after the outcome is decided (or to ``n_steps`` if
        ``tail_steps < 0``); with 0 it stops at the decision.

    Returns
    -------
    summary : array (len(SUMMARY_FIELDS),)
        The fields of :data:`SUMMARY_FIELDS`, as floats.
    records : tuple of arrays
        ``(energies, q, contacts)`` over the records: (nr, 5) the columns of
        :data:`RECORD_ENERGY_FIELDS`; (nr, 3 nb) the displacements ``(x, y, theta)`` of every
        block [m, m, rad]; (nr, 4 nc) the gaps, then the tangential offsets [m], then the mean
        contact forces ``(normal, tangential)`` of every contact over the step that ends at the
        record [N/m]. Empty when not recording.
    """
    # -------- 0. set up
    nb, nc = bodies.shape[0], contacts.shape[0]
    h, theta = settings[S_TIME_STEP], settings[S_THETA]
    mu = np.empty(nc)  # every contact's friction: its joint's own, else the settings'
    for c in range(nc):
        own = contacts[c, FRICTION]
        mu[c] = settings[S_FRICTION] if math.isnan(own) else own
    gravity = settings[S_GRAVITY]
    n_steps = int(settings[S_N_STEPS])
    max_iterations = int(settings[S_MAX_ITERATIONS])
    record_stride = int(settings[S_RECORD_STRIDE])
    tail_steps = int(settings[S_TAIL_STEPS])
    crown_block = int(settings[S_CROWN_BLOCK])
    crown_x, crown_y = settings[S_CROWN_X], settings[S_CROWN_Y]
    coarse = max(1, int(settings[S_COARSE_FACTOR]))
    active_set_solves = int(settings[S_ACTIVE_SET_SOLVES])
    skip_rest = settings[S_SKIP_REST] != 0.0
    in_blocks = blocks_band[0].size > 0
    mean_mass = bodies[:, BODY_MASS].mean()
    inv_mass = np.empty((nb, 4))  # 1/m, 1/I, their square roots
    for i in range(nb):
        inv_mass[i, 0] = 1.0 / bodies[i, BODY_MASS]
        inv_mass[i, 1] = 1.0 / bodies[i, BODY_INERTIA]
        inv_mass[i, 2] = math.sqrt(inv_mass[i, 0])
        inv_mass[i, 3] = math.sqrt(inv_mass[i, 1])
    q = q0.copy()
    v = v0.copy()
    v_old = np.empty_like(v)
    v_free = np.empty_like(v)
    trig = np.empty((nb, 2))
    gap = np.zeros(nc)
    slip = np.zeros(nc)
    valid = np.zeros(nc, dtype=np.bool_)
    active = np.zeros(nc, dtype=np.bool_)
    carried = np.zeros(nc, dtype=np.bool_)  # carried an impulse at the end of the last step
    jac = np.zeros((nc, 12))
    w = np.zeros((nc, 3))
    impulse = np.zeros((nc, 2))
    impulse_k = np.zeros((nc, 2))  # the last step's, to take a coarse step again
    state = -np.ones(nc, dtype=np.int64)
    state_k = -np.ones(nc, dtype=np.int64)
    pointer, incident, half_bandwidth = incidence(contact_bodies, nb)
    kl = 2 * half_bandwidth + 1  # of the unknowns: two per contact
    problem = (np.zeros(nc, dtype=np.int64), np.zeros(nc, dtype=np.int64), pointer, incident,
               kl, np.zeros((2 * nc, kl + 1)), np.zeros((2 * nc, 3 * kl + 1)),
               np.zeros(2 * nc), np.zeros(2 * nc), np.zeros(2 * nc), np.zeros((nc, 12)))
    recording = record_stride > 0
    capacity = min(n_steps // record_stride + 2, 1024) if recording else 1
    rec_energy = np.zeros((capacity, 5))
    rec_q = np.zeros((capacity, 3 * nb))
    rec_contacts = np.zeros((capacity, 4 * nc))
    n_rec = 0
    next_record = 0  # the first step h at or after which the next state is recorded
    energies = np.zeros(4)  # kinetic, potential, dissipated, input [J/m]
    path = (np.zeros(2 * nc), np.zeros(2 * nc), np.zeros(2 * nc), np.zeros((nb, 3)),
            np.zeros((nb, 3)), np.zeros(nc, dtype=np.int64),
            np.zeros((nc, 2)))  # rest_range's impulses and work space
    v_rest = np.zeros((nb, 3))
    dv_rest = np.zeros((nb, 3))
    retry = 0  # the first step at which a skip under a varying motion is tried again
    hc = coarse * h  # its steps' longest: the largest velocities of rest

    energies[0] = _kinetic_energy(bodies, v)
    steady_energy = STEADY_ENERGY * settings[S_REST_ENERGY]
    status = -1
    decided = False
    collapse_time = math.nan
    decision_time = math.nan
    max_rotation = max_crown_drop = max_slip = max_opening = max_drop = 0.0
    rest_count = 0
    closed = True
    iterations = max_used = unconverged = fallbacks = 0
    solved = np.zeros(4, dtype=np.int64)  # steps solved by phase (SUMMARY_FIELDS)
    moved_once = False
    stop_step = n_steps
    step = decision_step = 0
    last = 1  # steps h of the last step taken
    hs = h  # its length [s]
    while step < stop_step:
        t = step * h
        # -------- 1. geometry
        contact_geometry(q, bodies, contacts, contact_bodies, trig, gap, slip, valid, jac)
        # -------- 2. measure (the outcome's maxima until the decision: a record's tail after
        #             it changes nothing of the outcome)
        energies[1], rotation, drop, crown_drop = _measure(q, bodies, gravity, crown_block,
                                                           crown_x, crown_y)
        if not decided:
            max_rotation = max(max_rotation, rotation)
            max_crown_drop = max(max_crown_drop, crown_drop)
            max_drop = max(max_drop, drop)
            max_slip, max_opening, closed = _joints(gap, slip, valid, settings[S_CLOSED_GAP],
                                                    max_slip, max_opening)
        # -------- 3. record
        if recording and step >= next_record:
            rec_energy, rec_q, rec_contacts = _record(n_rec, t, q, gap, slip, impulse, hs,
                                                      energies, rec_energy, rec_q, rec_contacts)
            n_rec += 1
            next_record = (step // record_stride + 1) * record_stride
        # -------- 4. decide
        if not decided:
            status, rest_count = _decide(t, drop, energies[0], energies[1], closed, max_opening,
                                         max_slip, rest_count, last, settings)
            if status == COLLAPSE:
                collapse_time = t
            if status >= 0:
                decided = True
                decision_time = t
                decision_step = step
                # -------- 5. stop?
                if not recording:
                    break
                stop_step = n_steps if tail_steps < 0 else min(n_steps, step + tail_steps + 1)
                if step + 1 >= stop_step:
                    break
        if not decided:
            moved_once = moved_once or energies[0] > settings[S_REST_ENERGY]
            if t < settings[S_EXCITATION_END]:
                solved[1 if moved_once else 0] += 1
            else:
                solved[3 if rest_count > 0 else 2] += 1
        # -------- 6.-8. a coarse step if one fits, taken again at h if a contact changes
        m = coarse if (step % coarse == 0 and step + coarse <= stop_step) else 1
        if m > 1:
            copy_2d(impulse_k, impulse)
            copy_1d(state_k, state)
        while True:
            hs = m * h
            tol_impulse = settings[S_TOLERANCE] * mean_mass * gravity * hs
            p_tol = 1e-12 * mean_mass * gravity * hs
            u_tol = SWITCH_VELOCITY * gravity * hs  # the compliance's resolution
            # -------- 6. free velocities
            ag = mean_acceleration(t, t + hs, kind, params, times, values)
            _free_velocities(v, v_old, v_free, hs, ag, gravity)
            # -------- 7. active set
            _active_set(gap, valid, v_old, contact_bodies, contacts, jac, theta, hs, carried,
                        active)
            # -------- 8. the contact problem
            if in_blocks:
                sweeps, converged = solve_active_set_blocks(
                    v, inv_mass, contact_bodies, jac, active, impulse, state, mu, p_tol, u_tol,
                    blocks_band[0], blocks_band[1], active_set_solves)
            else:
                sweeps, converged = solve_active_set(v, inv_mass, contact_bodies, jac, active,
                                                     impulse, state, mu, p_tol, u_tol, problem,
                                                     active_set_solves)
            direct = converged
            if not converged and m == 1:  # fall back to Lemke's algorithm
                fallbacks += 0 if decided else 1
                if in_blocks:  # the assembled problem that Lemke's algorithm reads
                    solve_active_set(v, inv_mass, contact_bodies, jac, active, impulse, state,
                                     mu, p_tol, u_tol, problem,
                                     np.int64(0))  # not a literal: one compiled signature
                pivots, converged = solve_lemke(v, inv_mass, contact_bodies, jac, active,
                                                impulse, state, mu, p_tol, u_tol, problem)
                sweeps += pivots
                if not converged:  # not observed: Gauss-Seidel from the last impulses
                    sweeps, converged = solve_contacts(v, inv_mass, contact_bodies, jac, w,
                                                       active, impulse, mu, tol_impulse,
                                                       max_iterations)
            if not decided:  # the outcome's counts stop at the decision too
                iterations += sweeps
                max_used = max(max_used, sweeps)
            if m == 1 or (direct and not _changed(active, state, carried)):
                break
            # a contact starts or stops carrying an impulse: the step again, at h
            copy_2d(v, v_old)
            copy_2d(impulse, impulse_k)
            copy_1d(state, state_k)
            m = 1
        if not decided and not converged:
            unconverged += 1
        if coarse > 1:  # the contacts that carry an impulse stay active (Coarse steps)
            for c in range(nc):
                carried[c] = active[c] and (state[c] > 0 if direct else impulse[c, 0] > 0.0)
        # -------- 9. advance: energy bookkeeping (exact for theta = 1/2) and positions
        energies[2] -= _contact_work(v_old, v, v_free, bodies)
        kinetic_before = energies[0]
        work, energies[0] = _advance(q, v_old, v, bodies, hs, theta, ag)
        energies[3] += work
        step += m
        last = m
        # -------- 10. at rest under a constant load: skip the steps that repeat it
        if (skip_rest and not decided
                and max(kinetic_before, energies[0]) <= steady_energy):
            skip = min(steady_steps(step, h, ag, kind, params, times, values, settings,
                                    rest_count, closed, last, stop_step), stop_step - step)
            held = 0  # active contacts on the affine path of a skip under a varying motion
            if (skip == 0 and kind != STEP and step >= retry
                    and step * h < settings[S_EXCITATION_END]):
                for i in range(nb):
                    v_rest[i, 0] = v[i, 0] - hc * ag
                    v_rest[i, 1] = v[i, 1] - hc * gravity
                    v_rest[i, 2] = v[i, 2]
                    dv_rest[i, 0] = -hc
                lo, hi, held = rest_range(
                    v_rest, dv_rest, inv_mass, contact_bodies, jac, active, state, mu,
                    1e-12 * mean_mass * gravity * hc, SWITCH_VELOCITY * gravity * hc,
                    steady_energy, problem, path)
                if lo <= 0.0 <= hi:
                    skip = min(held_steps(step, h, ag, lo, hi, kind, params, times, values,
                                          settings, stop_step), stop_step - step)
                if skip == 0:
                    retry = step + RETRY_STEPS
                    held = 0
            crept = step  # the skipped steps whose creep has moved the blocks (_creep)
            if recording:  # the skipped steps' records: the same state
                for k in range(step, step + skip):
                    if k >= next_record:
                        if held > 0:  # the forces of the step that ends at k, and the creep
                            _path_impulses(mean_acceleration(k * h - hc, k * h, kind, params,
                                                             times, values) - ag,
                                           held, problem[0], path[0], path[1], impulse)
                            reached = min(step + skip, -(-k // coarse) * coarse)
                            energies[0] = _creep(q, v, bodies, crept, reached, h, theta,
                                                 coarse, ag, kind, params, times, values,
                                                 path[3], path[4])
                            crept = reached
                        rec_energy, rec_q, rec_contacts = _record(
                            n_rec, k * h, q, gap, slip, impulse, hc if held > 0 else hs,
                            energies, rec_energy, rec_q, rec_contacts)
                        n_rec += 1
                        next_record = (k // record_stride + 1) * record_stride
            if held > 0:  # the last skipped step's impulses and the creep, recorded or not
                _path_impulses(mean_acceleration((step + skip) * h - hc, (step + skip) * h,
                                                 kind, params, times, values) - ag,
                               held, problem[0], path[0], path[1], impulse)
                hs = hc
                energies[0] = _creep(q, v, bodies, crept, step + skip, h, theta, coarse, ag,
                                     kind, params, times, values, path[3], path[4])
            if skip > 0 and step * h >= settings[S_EXCITATION_END]:
                rest_count += skip
            step += skip
    summary = np.zeros(len(SUMMARY_FIELDS))
    summary[0] = status
    summary[1] = 1.0 if decided else 0.0
    summary[2] = collapse_time
    summary[3] = decision_time
    summary[4] = max_rotation
    summary[5] = max_crown_drop
    summary[6] = max_slip
    summary[7] = max_opening
    summary[8] = max_drop
    summary[9] = decision_step if decided else step
    summary[10] = iterations
    summary[11] = max_used
    summary[12] = unconverged
    summary[13] = step * h
    summary[14] = 1.0 if closed else 0.0
    summary[15] = fallbacks
    for k in range(4):
        summary[16 + k] = solved[k]
    return summary, (rec_energy[:n_rec], rec_q[:n_rec], rec_contacts[:n_rec])
