r"""Compiled Moreau-Jean time stepping of rigid blocks with unilateral Coulomb contacts.

Everything here is ``numba``-compiled; :func:`run` is the one driver of an analysis, the other
functions are its small helpers (section "The driver"). :mod:`archquake.rigid_blocks.dynamics`
prepares the arrays and reads the results.

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

Contacts and their detection
----------------------------
Each joint ``j`` between bodies ``a`` and ``b`` has a contact at each of its two ends
``k = 0, 1`` (contact ``2 j + k``). The contact follows two material points, one of each body,
that coincide with the end of the joint in the undeformed configuration: ``p_a`` (on body ``a``)
and ``p_b`` (on body ``b``). The face of body ``a`` is the joint segment carried by ``a``, with
normal ``n_a`` and tangent ``t_a``. With ``c`` a centroid in the deformed configuration, ``r``
the undeformed offset of the contact point from it and ``R`` the rotation matrix (the ground
has ``theta = 0`` and ``c = 0``), the gap and the tangential offset of the contact are

.. math::

    p_a = c_a + R(\theta_a)\,r_a, \quad p_b = c_b + R(\theta_b)\,r_b, \quad
    n_a = R(\theta_a)\,n_j, \quad t_a = R(\theta_a)\,t_j,

    g = (p_b - p_a) \cdot n_a, \qquad s = (p_b - p_a) \cdot t_a

[m] exactly, for any rotation (nothing is linearised). This is the corner-to-face contact of
two convex polygons that touch along a common flat face: while the two faces are in contact or
turn about one end (a hinge), that end is a material point of both blocks, so the pair of
points stays exact at large rotations; the other end lifts off (``g > 0``) and lands again.
Only sliding moves ``p_b`` along the face; the contact holds (is *valid*) while the projection
of ``p_b`` on the face lies on the face of body ``a``,

.. math::

    \ell_{lo} \le o_k + s \le \ell_{hi}

with :math:`o_k` the position of the end along the joint (0 or its length) [m] and
:math:`[\ell_{lo}, \ell_{hi}]` the face (:attr:`Assembly.face_extents`: by default the joint
extended by 10 % of its length at each end, since beyond its end the exact contact would be
the corner of ``a`` on the face of ``b``, which differs to second order only, slip times
relative rotation).
Contacts of other faces (an extrados on a neighbouring block) are not detected: they cannot
occur before an arch collapses.

The normal and tangential relative velocities are the exact time derivatives of ``g`` and
``s``, ``u_n = H_n v`` and ``u_t = H_t v``, whose rows (the Jacobian ``H``) are, with the planar
cross product :math:`r \times n = r_x n_y - r_y n_x`,

.. math::

    H_{n,a} = -\bigl(n_a^T,\; (p_b - c_a) \times n_a\bigr), \qquad
    H_{n,b} = \bigl(n_a^T,\; (p_b - c_b) \times n_a\bigr)

and the same with ``t_a`` for ``H_t``: the turning of the face of ``a`` moves the lever arm of
body ``a`` from ``p_a`` to ``p_b`` (:func:`contact_geometry`).

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
theta = 1/2) and never drifts at rest.

Contact problem
---------------
With the free velocity :math:`v^f = v_k + \mathbf{M}^{-1} \int f\,dt` (the step without contact
impulses), the local velocities of the active contacts are affine in their impulses, through
the Delassus matrix:

.. math::

    u = u^f + W P, \qquad u^f = H_k v^f, \qquad W = H_k \mathbf{M}^{-1} H_k^T.

It is solved exactly (to round-off) by a primal-dual active-set method,
:func:`solve_active_set`: guess the state of every contact (open, stick, slide either way; the
previous step's states), solve the linear system in the impulses that the states define, switch
the states that the solution contradicts, repeat (usually 1-2 solves; the normal rows of the
contacts that stick or slide and the tangential rows of the sticking ones carry a compliance of
:data:`REGULARISATION` times their diagonal, which picks the smallest of the statically
indeterminate impulses). Two contacts couple only through a block they both touch, so with the
contacts numbered joint by joint ``W`` is a band matrix (for an arch each joint couples with its
two neighbours: half-bandwidth 7 in the impulses, whatever the number of blocks): it is
assembled block by block and solved in band storage, by Cholesky's factorisation when no
contact slides (the system is then symmetric positive definite), else by Gaussian elimination
(:func:`band_cholesky_solve`, :func:`band_lu_solve`, :func:`band_solve`): a step costs time and
memory linear in the number of blocks.

The active-set method has no guarantee of convergence: its states can cycle (measured on
Oppenheim's arch cut into 50 voussoirs under its pulse: at 79 of 4,000 steps, at the onset of
the motion and at impacts, where tens of contacts change state at once; with one switch per
solve, in the manner of Murty's least-index rule, most of these still cycle after 2,000
solves). Where it gives up after :data:`ACTIVE_SET_SOLVES` solves, the step's problem is
solved by **Lemke's algorithm** (:func:`solve_lemke`, :mod:`archquake.rigid_blocks.lemke`),
which cannot cycle: in two dimensions Coulomb's law is exactly a linear complementarity problem
(Stewart and Trinkle's formulation, with the slip rate as an unknown), whose matrix, with the
compliance above and the same on the slip rate, is copositive-plus, and whose problem is
feasible; Lemke's algorithm with the lexicographic ratio test then ends on a solution after
finitely many pivots (Cottle, Pang and Stone, Thm. 4.4.13; the module's docstring). Its
solution's states are handed back to the active-set method, which solves the same states to
round-off (so that both methods give the same impulses where both converge); where it would
switch them, Lemke's impulses are kept. The fallback costs a dense tableau: 4 unknowns per
active contact and about 1.5 pivots per unknown, 0.2 s for the 93 active contacts of the
50-voussoir arch (``benchmarks/rigid_block_contact_solver.py``), paid only at the steps where
the active-set method gave up. Should Lemke's algorithm end without a solution (never observed:
a guard against round-off), projected Gauss-Seidel takes over [2]_ (Ch. 13),
:func:`solve_contacts`: sweeps forward and backward in turn, each contact's problem solved
exactly by :func:`local_coulomb` with the others' impulses fixed,

.. math::

    P_c \leftarrow \operatorname{local}\bigl(u_c - W_{cc} P_c,\; W_{cc},\; \mu\bigr), \qquad
    v \leftarrow v + \mathbf{M}^{-1} H_c^T \Delta P_c,

stopping when :math:`\max_c (|\Delta P_{n,c}| + |\Delta P_{t,c}|) \le \mathrm{tol}\;\bar m g h`
(the impulse of a mean block's weight over a step, scaled) or after ``max_iterations`` sweeps
(counted as unconverged: the outcome is then undecided). Gauss-Seidel alone converges slowly on
an arch (the thrust runs through a chain of blocks and the friction split between the two ends
of a joint is indeterminate), and its residual velocities make a still arch creep; hence the
direct methods.

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
                    would repeat them are skipped (:func:`steady_steps`)

The structure reaches the driver as three packed arrays (the blocks, :data:`BODY_FIELDS`; the
contacts, :data:`CONTACT_FIELDS`; the bodies of every contact) and the settings as one vector
(:data:`SETTINGS_FIELDS`, :func:`pack_settings`): one compiled signature serves every structure
and every analysis. How each part is compiled was chosen by measurement, as in the four-link
engine's driver: the parts of a step that take arrays (the contact geometry, the contact
problem, the active set, the bookkeeping) are compiled on their own without numba's reference
counting (``_nrt=False``: they allocate nothing; counting the references of the arrays handed
to a helper, at every call, cost as much as the arithmetic of the active set), and the small
helpers they call for every contact are inlined into them (``inline="always"``). In the short
loops of the band solvers the indices are unsigned: numba checks a signed index for wrapping
around at every access, which kept them from being vectorised (1.7 times slower).

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
from .lemke import LEMKE_SOLVED, solve_contact_lcp

REGULARISATION = 1e-9
"""Compliance of the rows of the contact problem that hold a velocity to zero (the normal row of a
contact that sticks or slides, the tangential row of one that sticks), relative to their
diagonal [-]."""

ACTIVE_SET_SOLVES = 60
"""Default largest number of linear solves of the active-set method in a step before Lemke's
algorithm takes over [-] (the setting ``active_set_solves``)."""

POLISH_SOLVES = 4
"""Largest number of linear solves of the active-set method from the states of Lemke's
solution [-] (:func:`solve_lemke`): one where they hold to its tolerances."""

SINGLE_SWITCH_AFTER = 10
"""After this many solves [-] the active-set method switches one contradicted state per solve (the
first one, in the manner of Murty's least-index rule) instead of all, which ends cycles."""

ACTIVATION_GAP = 1e-9
"""Predicted gap, as a fraction of the joint's length, below which a contact is active [-]: a
closed joint's round-off gap (1e-16 m) must not drop it from the contact problem."""

ARCH_BANDWIDTH = 7
"""Half-bandwidth of the impulses of an arch's contact problem [-]: each block touches the two
contacts of each of its two joints, so contacts up to 3 apart couple, and the impulses (two per
contact) up to ``2 * 3 + 1``. :func:`solve_active_set` solves an arch's systems with the band
solvers written out for this value (:func:`arch_cholesky_solve`, :func:`arch_lu_solve`), any
other structure's with the general ones, to the same results."""

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
    "unconverged_steps", "final_time", "closed", "fallbacks",
)
"""Layout of the summary vector returned by :func:`run`: outcome code; 1 if decided; collapse and
decision times [s] (nan if none); largest block rotation [rad], crown drop, slip, opening and
drop [m]; steps, linear solves or sweeps in all, most in one step, unconverged steps [-]; final
time of the run [s]; 1 if every joint was closed; steps left to Gauss-Seidel [-] (a coarse step
counts in ``steps`` as the steps ``h`` it spans). Everything but
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


@numba.njit(cache=True, _nrt=False)
def local_coulomb(ufn, uft, wnn, wnt, wtt, mu):
    r"""Exact solution of one contact's problem: impulses ``(P_n, P_t)`` [N s/m].

    The local velocity is ``u = uf + W P`` (``uf`` without this contact's impulse, ``W`` its
    2 x 2 Delassus block); the law is ``0 <= u_n perp P_n >= 0`` with Coulomb friction. The cases
    are tried in turn:

    .. math::

        \text{separation:}\quad P = 0 \quad \text{if } u^f_n \ge 0,

        \text{stick:}\quad P = -W^{-1} u^f \quad \text{if } P_n \ge 0,\;
        |P_t| \le \mu P_n \quad (u = 0),

        \text{slide:}\quad P_t = \sigma \mu P_n, \quad
        P_n = \frac{-u^f_n}{W_{nn} + \sigma \mu W_{nt}} \quad
        \text{if } \sigma u_t \le 0 \quad (u_n = 0,\; \sigma = +1 \text{ then } -1),

    with :math:`u_t = u^f_t + (W_{nt} + \sigma \mu W_{tt}) P_n`; a sliding case whose
    denominator is not positive is skipped. Should none hold (not reached for a positive
    definite ``W`` and a moderate mu), a frictionless push :math:`P = (-u^f_n / W_{nn}, 0)` is
    returned.

    Parameters
    ----------
    ufn, uft : float
        Normal and tangential velocity without this contact's impulse [m/s].
    wnn, wnt, wtt : float
        Entries of the symmetric 2 x 2 Delassus block [m/kg], i.e. (m/s) per
        (N s/m).
    mu : float
        Friction coefficient [-], >= 0.

    Returns
    -------
    pn, pt : float
        Normal and tangential impulse [N s/m].
    """
    if ufn >= 0.0:
        return 0.0, 0.0
    det = wnn * wtt - wnt * wnt
    pn = (-ufn * wtt + uft * wnt) / det
    pt = (-uft * wnn + ufn * wnt) / det
    if pn >= 0.0 and abs(pt) <= mu * pn:
        return pn, pt
    for s in (1.0, -1.0):
        denominator = wnn + s * mu * wnt
        if denominator <= 0.0:
            continue
        pn = -ufn / denominator
        ut = uft + (wnt + s * mu * wtt) * pn
        if s * ut <= 0.0:
            return pn, s * mu * pn
    # not reached for a positive definite W and a moderate mu; fall back to a frictionless push
    return -ufn / wnn, 0.0


# ---------------------------------------------------------------------------------------------
# Layout of the packed arrays
# ---------------------------------------------------------------------------------------------

BODY_FIELDS = ("mass", "inertia", "centroid_x", "centroid_y")
"""Columns of the body array ``bodies`` (nb, 4): mass [kg/m], polar moment of inertia [kg m] and
undeformed centroid [m] of every block."""

BODY_MASS, BODY_INERTIA, BODY_X, BODY_Y = range(4)

CONTACT_FIELDS = ("ra_x", "ra_y", "rb_x", "rb_y", "normal_x", "normal_y", "tangent_x",
                  "tangent_y", "offset", "face_lo", "face_hi", "length")
"""Columns of the contact array ``contacts`` (nc, 12), contact ``2 j + k`` being end ``k`` of joint
``j``: the undeformed contact point relative to the centroid of body a and of body b (absolute for
the ground) [m], the joint's unit normal and tangent [-], the position of the end along the joint
(0 or its length), the face of body a along the joint and the joint's length [m]. The bodies
themselves are the int array ``contact_bodies`` (nc, 2): ``(a, b)``, -1 for the ground."""

RA_X, RA_Y, RB_X, RB_Y, N_X, N_Y, T_X, T_Y, OFFSET, FACE_LO, FACE_HI, LENGTH = range(12)

SETTINGS_FIELDS = (
    "time_step", "theta", "friction", "tolerance", "max_iterations", "gravity",
    "excitation_end", "n_steps", "drop_limit", "rest_energy", "closed_gap", "rest_steps",
    "open_rest_steps", "moved_threshold", "energy_margin", "record_stride", "tail_steps",
    "crown_block", "crown_x", "crown_y", "coarse_factor", "active_set_solves",
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
algorithm at every step) [-]."""

(S_TIME_STEP, S_THETA, S_FRICTION, S_TOLERANCE, S_MAX_ITERATIONS, S_GRAVITY, S_EXCITATION_END,
 S_N_STEPS, S_DROP_LIMIT, S_REST_ENERGY, S_CLOSED_GAP, S_REST_STEPS, S_OPEN_REST_STEPS,
 S_MOVED_THRESHOLD, S_ENERGY_MARGIN, S_RECORD_STRIDE, S_TAIL_STEPS, S_CROWN_BLOCK, S_CROWN_X,
 S_CROWN_Y, S_COARSE_FACTOR, S_ACTIVE_SET_SOLVES) = range(22)

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
# Contacts: geometry, relative velocities, impulses
# ---------------------------------------------------------------------------------------------


@numba.njit(cache=True, inline="always")
def _rotate(c, s, x, y):
    """``(x, y)`` turned by the angle whose cosine and sine are ``c, s`` [-] (same units)."""
    return c * x - s * y, s * x + c * y


@numba.njit(cache=True, _nrt=False)
def contact_geometry(q, bodies, contacts, contact_bodies, trig, gap, slip, valid, jac):
    r"""Gap [m], tangential offset [m], validity and Jacobian rows of every contact at ``q``.

    Evaluates, for every contact ``c`` (module docstring, "Contacts and their detection"),

    .. math::

        g = (p_b - p_a) \cdot n_a, \qquad s = (p_b - p_a) \cdot t_a, \qquad
        \text{valid} \iff \ell_{lo} \le o + s \le \ell_{hi},

        H_{n,a} = -\bigl(n_a^T,\; (p_b - c_a) \times n_a\bigr), \quad
        H_{n,b} = \bigl(n_a^T,\; (p_b - c_b) \times n_a\bigr),

    and the same with ``t_a`` for ``H_t``: a contact is valid while the projection of its
    point of body b on the face of body a, ``offset + slip`` along the face from the joint's
    first end [m], lies in ``[face_lo, face_hi]`` [m]. ``jac[c]`` holds ``(Gn_a, Gt_a, Gn_b,
    Gt_b)``, each a row of 3 so that the normal and tangential relative velocities are
    ``u_n = Gn_a . v_a + Gn_b . v_b`` (same for ``t``) [m/s]; the rows of the ground are 0.

    Parameters
    ----------
    q : array (nb, 3)
        Displacements ``(x, y, theta)`` of the blocks [m, m, rad].
    bodies : array (nb, 4)
        The blocks (:data:`BODY_FIELDS`).
    contacts : array (nc, 12)
        The contacts (:data:`CONTACT_FIELDS`).
    contact_bodies : array of int (nc, 2)
        Bodies a and b of every contact (-1 for the ground).
    trig : array (nb, 2)
        Work space: the cosine and sine of every block's rotation [-].
    gap, slip : array (nc,)
        Output: ``g`` and ``s`` [m].
    valid : array of bool (nc,)
        Output: whether the contact holds.
    jac : array (nc, 12)
        Output: Jacobian rows [-, -, m] per body and direction.
    """
    for i in range(q.shape[0]):
        trig[i, 0] = math.cos(q[i, 2])
        trig[i, 1] = math.sin(q[i, 2])
    for c in range(contacts.shape[0]):
        a, b = contact_bodies[c, 0], contact_bodies[c, 1]
        if a >= 0:
            cos_a, sin_a = trig[a, 0], trig[a, 1]
            xa, ya = _rotate(cos_a, sin_a, contacts[c, RA_X], contacts[c, RA_Y])
            cax, cay = bodies[a, BODY_X] + q[a, 0], bodies[a, BODY_Y] + q[a, 1]
            pax, pay = cax + xa, cay + ya
            nx, ny = _rotate(cos_a, sin_a, contacts[c, N_X], contacts[c, N_Y])
            tx, ty = _rotate(cos_a, sin_a, contacts[c, T_X], contacts[c, T_Y])
        else:
            cax = cay = 0.0
            pax, pay = contacts[c, RA_X], contacts[c, RA_Y]
            nx, ny = contacts[c, N_X], contacts[c, N_Y]
            tx, ty = contacts[c, T_X], contacts[c, T_Y]
        if b >= 0:
            xb, yb = _rotate(trig[b, 0], trig[b, 1], contacts[c, RB_X], contacts[c, RB_Y])
            cbx, cby = bodies[b, BODY_X] + q[b, 0], bodies[b, BODY_Y] + q[b, 1]
            pbx, pby = cbx + xb, cby + yb
        else:
            cbx = cby = 0.0
            pbx, pby = contacts[c, RB_X], contacts[c, RB_Y]
        dx, dy = pbx - pax, pby - pay
        gap[c] = dx * nx + dy * ny
        slip[c] = dx * tx + dy * ty
        along = contacts[c, OFFSET] + slip[c]
        valid[c] = contacts[c, FACE_LO] <= along <= contacts[c, FACE_HI]
        # lever arms from each centroid to the contact point p_b
        rax, ray = pbx - cax, pby - cay
        rbx, rby = pbx - cbx, pby - cby
        if a >= 0:
            jac[c, 0] = -nx
            jac[c, 1] = -ny
            jac[c, 2] = -(rax * ny - ray * nx)
            jac[c, 3] = -tx
            jac[c, 4] = -ty
            jac[c, 5] = -(rax * ty - ray * tx)
        else:
            for k in range(6):
                jac[c, k] = 0.0
        if b >= 0:
            jac[c, 6] = nx
            jac[c, 7] = ny
            jac[c, 8] = rbx * ny - rby * nx
            jac[c, 9] = tx
            jac[c, 10] = ty
            jac[c, 11] = rbx * ty - rby * tx
        else:
            for k in range(6, 12):
                jac[c, k] = 0.0


@numba.njit(cache=True, inline="always")
def _relative_velocity(v, a, b, jac, c):
    """Normal and tangential relative velocity ``(u_n, u_t)`` [m/s] of contact ``c`` between
    bodies ``a`` and ``b`` (-1: the ground) for block velocities ``v`` (nb, 3) [m/s, m/s,
    rad/s], through its Jacobian rows ``jac[c]`` (:func:`contact_geometry`).

    The indices are cast to unsigned integers once they are known to be >= 0: numba checks a
    signed index for wrapping around (a negative index counts from the end) at every access,
    which here cost as much as the arithmetic (so in the other helpers of every contact)."""
    uc = np.uint64(c)
    un = 0.0
    ut = 0.0
    if a >= 0:
        ua = np.uint64(a)
        va0, va1, va2 = v[ua, 0], v[ua, 1], v[ua, 2]
        un += jac[uc, 0] * va0 + jac[uc, 1] * va1 + jac[uc, 2] * va2
        ut += jac[uc, 3] * va0 + jac[uc, 4] * va1 + jac[uc, 5] * va2
    if b >= 0:
        ub = np.uint64(b)
        vb0, vb1, vb2 = v[ub, 0], v[ub, 1], v[ub, 2]
        un += jac[uc, 6] * vb0 + jac[uc, 7] * vb1 + jac[uc, 8] * vb2
        ut += jac[uc, 9] * vb0 + jac[uc, 10] * vb1 + jac[uc, 11] * vb2
    return un, ut


@numba.njit(cache=True, inline="always")
def _apply_impulse(v, inv_mass, a, b, jac, c, pn, pt):
    """Add to the velocities ``v`` (nb, 3) [m/s, m/s, rad/s], in place, the change
    ``M^-1 H_c^T (pn, pt)`` that the impulses ``pn, pt`` [N s/m] of contact ``c`` give bodies
    ``a`` and ``b``; ``inv_mass`` (nb, >= 2) holds the inverse mass [m/kg] and inertia
    [1/(kg m)] of every block (unsigned indices: :func:`_relative_velocity`)."""
    uc = np.uint64(c)
    if a >= 0:
        ua = np.uint64(a)
        im, ii = inv_mass[ua, 0], inv_mass[ua, 1]
        v[ua, 0] += im * (jac[uc, 0] * pn + jac[uc, 3] * pt)
        v[ua, 1] += im * (jac[uc, 1] * pn + jac[uc, 4] * pt)
        v[ua, 2] += ii * (jac[uc, 2] * pn + jac[uc, 5] * pt)
    if b >= 0:
        ub = np.uint64(b)
        im, ii = inv_mass[ub, 0], inv_mass[ub, 1]
        v[ub, 0] += im * (jac[uc, 6] * pn + jac[uc, 9] * pt)
        v[ub, 1] += im * (jac[uc, 7] * pn + jac[uc, 10] * pt)
        v[ub, 2] += ii * (jac[uc, 8] * pn + jac[uc, 11] * pt)


@numba.njit(cache=True, inline="always")
def _delassus(inv_mass, a, b, jac, c):
    """The 2 x 2 Delassus block ``H_c M^-1 H_c^T`` of contact ``c`` (bodies ``a``, ``b``),
    ``(W_nn, W_nt, W_tt)`` [m/kg], from the inverse masses and inertias ``inv_mass`` (nb, >= 2)
    and the Jacobian rows ``jac[c]``."""
    wnn = wnt = wtt = 0.0
    for body, k in ((a, 0), (b, 6)):
        if body >= 0:
            im, ii = inv_mass[body, 0], inv_mass[body, 1]
            wnn += im * (jac[c, k] ** 2 + jac[c, k + 1] ** 2) + ii * jac[c, k + 2] ** 2
            wnt += (im * (jac[c, k] * jac[c, k + 3] + jac[c, k + 1] * jac[c, k + 4])
                    + ii * jac[c, k + 2] * jac[c, k + 5])
            wtt += im * (jac[c, k + 3] ** 2 + jac[c, k + 4] ** 2) + ii * jac[c, k + 5] ** 2
    return wnn, wnt, wtt


# ---------------------------------------------------------------------------------------------
# The contact problem of a step
# ---------------------------------------------------------------------------------------------


@numba.njit(cache=True, _nrt=False)
def solve_contacts(v, inv_mass, contact_bodies, jac, w, active, impulse, mu, tol_impulse,
                   max_iterations):
    r"""Projected Gauss-Seidel on the active contacts; ``v`` enters free and leaves corrected.

    The warm start ``impulse`` of the active contacts is applied first (the others are set to
    0); then every sweep visits the active contacts, forward on even sweeps and backward on odd
    ones, and replaces each one's impulse by the exact solution of its own problem with the
    others fixed [1]_:

    .. math::

        u^f_c = u_c(v) - W_{cc} P_c, \qquad
        P_c^{new} = \operatorname{local\_coulomb}(u^f_c, W_{cc}, \mu), \qquad
        v \leftarrow v + \mathbf{M}^{-1} H_c^T (P_c^{new} - P_c).

    It stops after the first sweep in which no impulse changed by more than ``tol_impulse``
    (measured as :math:`|\Delta P_n| + |\Delta P_t|`), or after ``max_iterations`` sweeps.

    Parameters
    ----------
    v : array (nb, 3)
        In: the free velocities; out: the velocities at the end of the step [m/s, m/s, rad/s].
    inv_mass : array (nb, >= 2)
        Inverse masses [m/kg] and inertias [1/(kg m)].
    contact_bodies : array of int (nc, 2)
        Bodies of every contact (-1: the ground).
    jac : array (nc, 12)
        Jacobian rows (:func:`contact_geometry`).
    w : array (nc, 3)
        Work space: the Delassus blocks ``(W_nn, W_nt, W_tt)`` of the active contacts [m/kg].
    active : array of bool (nc,)
        The active set.
    impulse : array (nc, 2)
        In: the warm start; out: the impulses ``(P_n, P_t)`` [N s/m].
    mu : float
        Friction coefficient [-].
    tol_impulse : float
        Largest change of an impulse in the last sweep [N s/m].
    max_iterations : int
        Largest number of sweeps.

    Returns
    -------
    sweeps : int
        Sweeps made.
    converged : bool
        Whether the tolerance was met.

    References
    ----------
    .. [1] V. Acary, B. Brogliato, "Numerical methods for nonsmooth dynamical systems",
       Springer (2008), Ch. 13.
    """
    nc = contact_bodies.shape[0]
    for c in range(nc):
        if active[c]:
            a, b = contact_bodies[c, 0], contact_bodies[c, 1]
            w[c, 0], w[c, 1], w[c, 2] = _delassus(inv_mass, a, b, jac, c)
            _apply_impulse(v, inv_mass, a, b, jac, c, impulse[c, 0], impulse[c, 1])
        else:
            impulse[c, 0] = 0.0
            impulse[c, 1] = 0.0
    sweeps = 0
    while sweeps < max_iterations:
        change = 0.0
        for i in range(nc):
            c = i if sweeps % 2 == 0 else nc - 1 - i
            if not active[c]:
                continue
            a, b = contact_bodies[c, 0], contact_bodies[c, 1]
            un, ut = _relative_velocity(v, a, b, jac, c)
            pn, pt = impulse[c, 0], impulse[c, 1]
            ufn = un - (w[c, 0] * pn + w[c, 1] * pt)
            uft = ut - (w[c, 1] * pn + w[c, 2] * pt)
            new_pn, new_pt = local_coulomb(ufn, uft, w[c, 0], w[c, 1], w[c, 2], mu)
            dpn, dpt = new_pn - pn, new_pt - pt
            if dpn != 0.0 or dpt != 0.0:
                _apply_impulse(v, inv_mass, a, b, jac, c, dpn, dpt)
                impulse[c, 0] = new_pn
                impulse[c, 1] = new_pt
                change = max(change, abs(dpn) + abs(dpt))
        sweeps += 1
        if change <= tol_impulse:
            return sweeps, True
    return sweeps, False


@numba.njit(cache=True)
def incidence(contact_bodies, nb):
    """The contacts of every block, and the half-bandwidth of the contact problem.

    Parameters
    ----------
    contact_bodies : array of int (nc, 2)
        Bodies a and b of every contact (-1: the ground).
    nb : int
        Number of blocks.

    Returns
    -------
    pointer : array of int (nb + 1,)
        The contacts of block ``i`` are the rows ``pointer[i]:pointer[i + 1]`` of
        ``incident``.
    incident : array of int (2 nc, 2)
        Block by block, each of its contacts (increasing) and the block's side in it: 0 if it
        is body a, 1 if body b.
    half_bandwidth : int
        The largest ``|c - d|`` [-] of two contacts that touch one block: the Delassus block
        of ``c, d`` is zero beyond it (at least 1, the two ends of a joint).
    """
    nc = contact_bodies.shape[0]
    pointer = np.zeros(nb + 1, dtype=np.int64)
    for c in range(nc):
        for side in range(2):
            body = contact_bodies[c, side]
            if body >= 0:
                pointer[body + 1] += 1
    for i in range(nb):
        pointer[i + 1] += pointer[i]
    fill = pointer[:nb].copy()
    incident = np.zeros((max(pointer[nb], 1), 2), dtype=np.int64)
    for c in range(nc):
        for side in range(2):
            body = contact_bodies[c, side]
            if body >= 0:
                incident[fill[body], 0] = c
                incident[fill[body], 1] = side
                fill[body] += 1
    half_bandwidth = 1
    for i in range(nb):
        if pointer[i + 1] > pointer[i]:
            half_bandwidth = max(half_bandwidth,
                                 incident[pointer[i + 1] - 1, 0] - incident[pointer[i], 0])
    return pointer, incident, half_bandwidth


@numba.njit(cache=True, _nrt=False)
def band_solve(ab, b, n, kl):
    r"""Solve ``A x = b`` for a band matrix ``A`` (n x n, ``kl`` diagonals below and above the
    main one) by Gaussian elimination with partial pivoting, in place.

    ``A`` is stored by rows, :math:`A_{ij}` = ``ab[i, j - i + kl]`` for :math:`|j - i| \le kl`,
    in an array of at least ``3 kl + 1`` columns whose last ``kl`` are zero: the row
    interchanges widen the upper triangle of the factor to ``2 kl`` diagonals [1]_. The entries
    outside the band are zero and never touched, so the elimination, the pivots and the
    solution are those of the dense algorithm (the same operations in the same order, less the
    ones on zeros): ``(n kl (2 kl))`` operations instead of :math:`n^3 / 3`.

    Parameters
    ----------
    ab : array (>= n, >= 3 kl + 1)
        The band of ``A`` (any units); overwritten by the factor.
    b : array (>= n,)
        Right-hand side; overwritten by ``x`` (in the units of ``b`` over those of ``A``).
    n : int
        Size of the system.
    kl : int
        Half-bandwidth, >= 0.

    References
    ----------
    .. [1] G. H. Golub, C. F. Van Loan, "Matrix computations", 4th ed., Johns Hopkins (2013),
       Sect. 4.3 (band Gaussian elimination with partial pivoting).
    """
    upper = 2 * kl
    for k in range(n):
        last = min(n - 1, k + kl)
        p = k
        big = abs(ab[k, kl])
        for i in range(k + 1, last + 1):
            if abs(ab[i, k - i + kl]) > big:
                big = abs(ab[i, k - i + kl])
                p = i
        right = min(n - 1, k + upper)
        if p != k:
            for j in range(k, right + 1):
                ab[k, j - k + kl], ab[p, j - p + kl] = ab[p, j - p + kl], ab[k, j - k + kl]
            b[k], b[p] = b[p], b[k]
        pivot = ab[k, kl]
        for i in range(k + 1, last + 1):
            f = ab[i, k - i + kl] / pivot
            if f != 0.0:
                for j in range(k + 1, right + 1):
                    ab[i, j - i + kl] -= f * ab[k, j - k + kl]
                b[i] -= f * b[k]
    for k in range(n - 1, -1, -1):
        s = b[k]
        for j in range(k + 1, min(n - 1, k + upper) + 1):
            s -= ab[k, j - k + kl] * b[j]
        b[k] = s / ab[k, kl]


@numba.njit(cache=True, inline="always")
def _coupling(scaled, c, side_c, d, side_d, wband, i, k):
    """Add a block's part of the Delassus block of contacts c, d, ``H_c,b M_b^-1 H_d,b^T``
    [m/kg], to rows ``2i, 2i+1`` and columns ``2k, 2k+1`` (``k >= i``; for ``k = i`` the upper
    triangle only) of ``W`` in upper band storage ``wband`` (:func:`_assemble_delassus`), from
    the rows of ``scaled``: the Jacobian rows of each contact scaled by ``M_b^-1/2``;
    ``side_c``, ``side_d`` (0 or 6) say whether the block is body a or b of each contact."""
    uc, ud = np.uint64(side_c), np.uint64(side_d)
    rc, rd = np.uint64(c), np.uint64(d)
    cnx, cny, cnr = scaled[rc, uc], scaled[rc, uc + 1], scaled[rc, uc + 2]
    ctx, cty, ctr = scaled[rc, uc + 3], scaled[rc, uc + 4], scaled[rc, uc + 5]
    dnx, dny, dnr = scaled[rd, ud], scaled[rd, ud + 1], scaled[rd, ud + 2]
    dtx, dty, dtr = scaled[rd, ud + 3], scaled[rd, ud + 4], scaled[rd, ud + 5]
    rn, rt = np.uint64(2 * i), np.uint64(2 * i + 1)
    off = np.uint64(2 * (k - i))
    wband[rn, off] += cnx * dnx + cny * dny + cnr * dnr
    wband[rn, off + 1] += cnx * dtx + cny * dty + cnr * dtr
    wband[rt, off] += ctx * dtx + cty * dty + ctr * dtr
    if k > i:
        wband[rt, off - 1] += ctx * dnx + cty * dny + ctr * dnr


@numba.njit(cache=True, inline="always")
def _scaled_rows(inv_mass, body, jac, c, first, scaled):
    """Jacobian rows ``first .. first + 5`` of contact ``c`` (of block ``body``) scaled by
    ``M_body^-1/2``: ``(m^-1/2, m^-1/2, I^-1/2)`` per row of 3, into ``scaled[c]``."""
    ub, uc, f = np.uint64(body), np.uint64(c), np.uint64(first)
    sm, si = inv_mass[ub, 2], inv_mass[ub, 3]
    scaled[uc, f] = sm * jac[uc, f]
    scaled[uc, f + 1] = sm * jac[uc, f + 1]
    scaled[uc, f + 2] = si * jac[uc, f + 2]
    scaled[uc, f + 3] = sm * jac[uc, f + 3]
    scaled[uc, f + 4] = sm * jac[uc, f + 4]
    scaled[uc, f + 5] = si * jac[uc, f + 5]


@numba.njit(cache=True, inline="always")
def _assemble_delassus(v, inv_mass, contact_bodies, jac, m, idx, pos, pointer, incident, kl,
                       wband, uf, scaled):
    r"""The Delassus matrix :math:`W = H M^{-1} H^T = \sum_b H_b M_b^{-1} H_b^T` of the ``m``
    active contacts ``idx[:m]`` and their free velocities :math:`u^f = H v` (into ``uf``), rows
    ``2 i`` normal and ``2 i + 1`` tangential of the ``i``-th.

    ``W`` is symmetric: its upper band is stored, ``wband[r, s]`` = :math:`W_{r, r + s}`
    (``s = 0 .. kl``). Block by block (``pointer``, ``incident``: :func:`incidence`), every pair
    of active contacts that touch it couples: the cost is linear in the number of contacts.
    Each entry is a dot product of Jacobian rows scaled by :math:`M_b^{-1/2}` (``scaled``, work
    space (nc, 12))."""
    size = 2 * m
    for r in range(size):
        for off in range(kl + 1):
            wband[r, off] = 0.0
    for i in range(m):
        c = idx[i]
        a, b = contact_bodies[c, 0], contact_bodies[c, 1]
        uf[2 * i], uf[2 * i + 1] = _relative_velocity(v, a, b, jac, c)
        if a >= 0:
            _scaled_rows(inv_mass, a, jac, c, 0, scaled)
        if b >= 0:
            _scaled_rows(inv_mass, b, jac, c, 6, scaled)
    for body in range(pointer.size - 1):
        end = pointer[body + 1]
        for e in range(pointer[body], end):
            c = incident[e, 0]
            i = pos[c]
            if i < 0:
                continue
            side_c = 6 * incident[e, 1]
            for e2 in range(e, end):  # contacts in increasing order: k >= i
                d = incident[e2, 0]
                k = pos[d]
                if k >= 0:
                    _coupling(scaled, c, side_c, d, 6 * incident[e2, 1], wband, i, k)


@numba.njit(cache=True, inline="always")
def _back_substitution(ab, b, n, kl):
    """Solve ``U x = y`` in place (``b`` holds ``y``, then ``x``) for the upper factor ``U`` of
    the band solvers, stored by rows with the inverse of its diagonal at ``ab[k, kl]`` and
    :math:`U_{k, k + s}` at ``ab[k, kl + s]``; by columns, unsigned indices
    (:func:`band_cholesky_solve`)."""
    ukl = np.uint64(kl)
    for k in range(n - 1, -1, -1):
        uk = np.uint64(k)
        b[uk] *= ab[uk, ukl]
        xk = b[uk]
        for s in range(1, min(kl, k) + 1):
            us = np.uint64(s)
            b[uk - us] -= ab[uk - us, ukl + us] * xk


@numba.njit(cache=True, _nrt=False)
def band_cholesky_solve(ab, b, n, kl):
    r"""Solve ``A x = b`` for a symmetric positive definite band matrix ``A`` (n x n, ``kl``
    diagonals on either side of the main one) by Cholesky's factorisation
    :math:`A = U^T U` [1]_, in place.

    ``A`` is stored by rows as for :func:`band_solve`, :math:`A_{ij}` =
    ``ab[i, j - i + kl]``; only the upper half (``j >= i``) is read, and it is overwritten by
    ``U``. About :math:`n\,kl^2 / 2` operations, no pivoting. Every loop runs along a row (the
    factorisation right-looking, the substitutions by columns), so that the innermost
    operations are independent of one another.

    Parameters
    ----------
    ab : array (>= n, >= 2 kl + 1)
        The band of ``A``; its upper half is overwritten by ``U``.
    b : array (>= n,)
        Right-hand side; overwritten by ``x``.
    n : int
        Size of the system.
    kl : int
        Half-bandwidth, >= 0.

    Returns
    -------
    bool
        False if a pivot is not positive (``A`` is not positive definite to round-off): ``ab``
        and ``b`` are then spoilt.

    References
    ----------
    .. [1] G. H. Golub, C. F. Van Loan, "Matrix computations", 4th ed., Johns Hopkins (2013),
       Sect. 4.3.5 (band Cholesky).
    """
    # unsigned indices: numba checks a signed index for wrapping around (a negative index
    # counts from the end), which keeps these short loops from being vectorised (measured:
    # 1.7 times slower); the rows are padded with zeros (at least 3 kl + 1 columns), so that
    # every update runs over kl + 1 entries whatever the row
    ukl = np.uint64(kl)
    for k in range(n):
        uk = np.uint64(k)
        d = ab[uk, ukl]
        if not d > 0.0:
            return False
        inverse = 1.0 / math.sqrt(d)
        ab[uk, ukl] = inverse  # the diagonal keeps 1 / U_kk: a product, not a division, below
        for t in range(1, kl + 1):
            ab[uk, ukl + np.uint64(t)] *= inverse
        for s in range(1, min(kl, n - 1 - k) + 1):
            us = np.uint64(s)
            f = ab[uk, ukl + us]
            if f != 0.0:
                ui = uk + us
                for t in range(kl + 1):
                    ut = np.uint64(t)
                    ab[ui, ukl + ut] -= f * ab[uk, ukl + us + ut]
    for k in range(n):  # U^T y = b
        uk = np.uint64(k)
        b[uk] *= ab[uk, ukl]
        yk = b[uk]
        for s in range(1, min(kl, n - 1 - k) + 1):
            us = np.uint64(s)
            b[uk + us] -= ab[uk, ukl + us] * yk
    _back_substitution(ab, b, n, kl)
    return True


@numba.njit(cache=True, _nrt=False)
def band_lu_solve(ab, b, n, kl, scale):
    r"""Solve ``A x = b`` for a band matrix ``A`` (n x n, ``kl`` diagonals on either side of
    the main one) by Gaussian elimination without pivoting, in place; False if a pivot falls
    below ``1e-10`` times its row's ``scale`` (the caller then pivots, :func:`band_solve`).

    ``A`` is stored by rows as for :func:`band_solve`, zero-padded to ``3 kl + 1`` columns;
    ``ab`` and ``b`` are overwritten by the factors and by ``x``. About :math:`n\,kl^2`
    operations, in loops of ``kl`` independent updates (see :func:`band_cholesky_solve`).

    Parameters
    ----------
    ab : array (>= n, >= 3 kl + 1)
        The band of ``A``; overwritten.
    b : array (>= n,)
        Right-hand side; overwritten by ``x``.
    n : int
        Size of the system.
    kl : int
        Half-bandwidth, >= 0.
    scale : array (>= n,)
        A positive size of every row (its diagonal) [units of ``A``].

    Returns
    -------
    bool
        Whether every pivot was large enough (if not, ``ab`` and ``b`` are spoilt).
    """
    ukl = np.uint64(kl)
    for k in range(n):
        uk = np.uint64(k)
        pivot = ab[uk, ukl]
        if not abs(pivot) > 1e-10 * scale[uk]:
            return False
        inverse = 1.0 / pivot
        ab[uk, ukl] = inverse  # the diagonal keeps 1 / U_kk: a product, not a division, below
        for s in range(1, min(kl, n - 1 - k) + 1):
            us = np.uint64(s)
            ui = uk + us
            f = ab[ui, ukl - us] * inverse
            if f != 0.0:
                for t in range(1, kl + 1):
                    ut = np.uint64(t)
                    ab[ui, ukl - us + ut] -= f * ab[uk, ukl + ut]
                b[ui] -= f * b[uk]
    _back_substitution(ab, b, n, kl)
    return True


@numba.njit(cache=True, _nrt=False)
def arch_cholesky_solve(ab, b, n):
    r""":func:`band_cholesky_solve` for the half-bandwidth of an arch, :data:`ARCH_BANDWIDTH` = 7,
    written out: the same operations in the same order on the same numbers (the results are
    equal bit for bit, tested), with the forward substitution done row by row as the factor
    is made, and nothing read outside the upper band (columns 7 to 14; the padding is not
    needed). Row ``k`` of the factor is held in registers while it updates the seven rows
    below it, which the loops over a band of a known length did not manage (measured: the
    factorisation and substitutions of 32 unknowns take 1.3 us instead of 1.7)."""
    for k in range(n):
        d = ab[k, 7]
        if not d > 0.0:
            return False
        inverse = 1.0 / math.sqrt(d)
        ab[k, 7] = inverse
        r1 = ab[k, 8] * inverse
        r2 = ab[k, 9] * inverse
        r3 = ab[k, 10] * inverse
        r4 = ab[k, 11] * inverse
        r5 = ab[k, 12] * inverse
        r6 = ab[k, 13] * inverse
        r7 = ab[k, 14] * inverse
        ab[k, 8] = r1
        ab[k, 9] = r2
        ab[k, 10] = r3
        ab[k, 11] = r4
        ab[k, 12] = r5
        ab[k, 13] = r6
        ab[k, 14] = r7
        b[k] *= inverse  # U^T y = b, row k
        yk = b[k]
        below = n - 1 - k
        if below >= 1:
            i = k + 1
            ab[i, 7] -= r1 * r1
            ab[i, 8] -= r1 * r2
            ab[i, 9] -= r1 * r3
            ab[i, 10] -= r1 * r4
            ab[i, 11] -= r1 * r5
            ab[i, 12] -= r1 * r6
            ab[i, 13] -= r1 * r7
            b[i] -= r1 * yk
        if below >= 2:
            i = k + 2
            ab[i, 7] -= r2 * r2
            ab[i, 8] -= r2 * r3
            ab[i, 9] -= r2 * r4
            ab[i, 10] -= r2 * r5
            ab[i, 11] -= r2 * r6
            ab[i, 12] -= r2 * r7
            b[i] -= r2 * yk
        if below >= 3:
            i = k + 3
            ab[i, 7] -= r3 * r3
            ab[i, 8] -= r3 * r4
            ab[i, 9] -= r3 * r5
            ab[i, 10] -= r3 * r6
            ab[i, 11] -= r3 * r7
            b[i] -= r3 * yk
        if below >= 4:
            i = k + 4
            ab[i, 7] -= r4 * r4
            ab[i, 8] -= r4 * r5
            ab[i, 9] -= r4 * r6
            ab[i, 10] -= r4 * r7
            b[i] -= r4 * yk
        if below >= 5:
            i = k + 5
            ab[i, 7] -= r5 * r5
            ab[i, 8] -= r5 * r6
            ab[i, 9] -= r5 * r7
            b[i] -= r5 * yk
        if below >= 6:
            i = k + 6
            ab[i, 7] -= r6 * r6
            ab[i, 8] -= r6 * r7
            b[i] -= r6 * yk
        if below >= 7:
            i = k + 7
            ab[i, 7] -= r7 * r7
            b[i] -= r7 * yk
    _back_substitution(ab, b, n, 7)
    return True


@numba.njit(cache=True, _nrt=False)
def arch_lu_solve(ab, b, n, scale):
    r""":func:`band_lu_solve` for the half-bandwidth of an arch, :data:`ARCH_BANDWIDTH` = 7,
    written out as :func:`arch_cholesky_solve`: the same operations in the same order (equal bit for
    bit, tested), row ``k`` of ``U`` held in registers while it updates the seven rows below
    it. Elimination without pivoting reads and writes the band only, never its padding."""
    for k in range(n):
        pivot = ab[k, 7]
        if not abs(pivot) > 1e-10 * scale[k]:
            return False
        inverse = 1.0 / pivot
        ab[k, 7] = inverse
        u1 = ab[k, 8]
        u2 = ab[k, 9]
        u3 = ab[k, 10]
        u4 = ab[k, 11]
        u5 = ab[k, 12]
        u6 = ab[k, 13]
        u7 = ab[k, 14]
        bk = b[k]
        below = n - 1 - k
        if below >= 1:
            i = k + 1
            f = ab[i, 6] * inverse
            if f != 0.0:
                ab[i, 7] -= f * u1
                ab[i, 8] -= f * u2
                ab[i, 9] -= f * u3
                ab[i, 10] -= f * u4
                ab[i, 11] -= f * u5
                ab[i, 12] -= f * u6
                ab[i, 13] -= f * u7
                b[i] -= f * bk
        if below >= 2:
            i = k + 2
            f = ab[i, 5] * inverse
            if f != 0.0:
                ab[i, 6] -= f * u1
                ab[i, 7] -= f * u2
                ab[i, 8] -= f * u3
                ab[i, 9] -= f * u4
                ab[i, 10] -= f * u5
                ab[i, 11] -= f * u6
                ab[i, 12] -= f * u7
                b[i] -= f * bk
        if below >= 3:
            i = k + 3
            f = ab[i, 4] * inverse
            if f != 0.0:
                ab[i, 5] -= f * u1
                ab[i, 6] -= f * u2
                ab[i, 7] -= f * u3
                ab[i, 8] -= f * u4
                ab[i, 9] -= f * u5
                ab[i, 10] -= f * u6
                ab[i, 11] -= f * u7
                b[i] -= f * bk
        if below >= 4:
            i = k + 4
            f = ab[i, 3] * inverse
            if f != 0.0:
                ab[i, 4] -= f * u1
                ab[i, 5] -= f * u2
                ab[i, 6] -= f * u3
                ab[i, 7] -= f * u4
                ab[i, 8] -= f * u5
                ab[i, 9] -= f * u6
                ab[i, 10] -= f * u7
                b[i] -= f * bk
        if below >= 5:
            i = k + 5
            f = ab[i, 2] * inverse
            if f != 0.0:
                ab[i, 3] -= f * u1
                ab[i, 4] -= f * u2
                ab[i, 5] -= f * u3
                ab[i, 6] -= f * u4
                ab[i, 7] -= f * u5
                ab[i, 8] -= f * u6
                ab[i, 9] -= f * u7
                b[i] -= f * bk
        if below >= 6:
            i = k + 6
            f = ab[i, 1] * inverse
            if f != 0.0:
                ab[i, 2] -= f * u1
                ab[i, 3] -= f * u2
                ab[i, 4] -= f * u3
                ab[i, 5] -= f * u4
                ab[i, 6] -= f * u5
                ab[i, 7] -= f * u6
                ab[i, 8] -= f * u7
                b[i] -= f * bk
        if below >= 7:
            i = k + 7
            f = ab[i, 0] * inverse
            if f != 0.0:
                ab[i, 1] -= f * u1
                ab[i, 2] -= f * u2
                ab[i, 3] -= f * u3
                ab[i, 4] -= f * u4
                ab[i, 5] -= f * u5
                ab[i, 6] -= f * u6
                ab[i, 7] -= f * u7
                b[i] -= f * bk
    _back_substitution(ab, b, n, 7)
    return True


@numba.njit(cache=True, inline="always")
def _state_system(m, idx, state, mu, kl, wband, uf, aband, rhs, scale, full):
    r"""The linear system of the active-set method for the current ``state`` of every active
    contact (:func:`solve_active_set`), in the band ``aband`` (half-bandwidth ``kl``, rows
    zero-padded to ``3 kl + 1`` columns, :func:`band_solve`), ``rhs`` and the size of every row,
    ``scale``: ``W`` (from its upper band ``wband``) with the compliance on its diagonal; the
    rows and columns of an open contact those of the identity (``P = 0``); the tangential row
    of a sliding one ``P_t - sigma mu P_n = 0``.

    Returns whether a contact slides. If none does, the system is symmetric positive definite
    and only its upper half is written (what :func:`band_cholesky_solve` reads), unless
    ``full``. For an arch's half-bandwidth (:data:`ARCH_BANDWIDTH`) the entries outside the
    band are not written for Cholesky's factorisation (:func:`arch_cholesky_solve` does not
    read them), unless ``full`` (for :func:`band_solve`, whose row interchanges fill the
    padding)."""
    size = 2 * m
    sliding = False
    for i in range(m):
        sliding = sliding or state[idx[i]] >= 2
    ukl = np.uint64(kl)
    # the arch's Cholesky (arch_cholesky_solve) reads the upper band and nothing else
    lean = kl == ARCH_BANDWIDTH and not (sliding or full)
    for r in range(size):
        ur = np.uint64(r)
        if not lean:
            for off in range(kl):
                aband[ur, np.uint64(off)] = 0.0
            for off in range(2 * kl + 1, 3 * kl + 1):
                aband[ur, np.uint64(off)] = 0.0
        for off in range(kl + 1):
            aband[ur, ukl + np.uint64(off)] = wband[ur, np.uint64(off)]
        aband[ur, ukl] += REGULARISATION * wband[ur, 0]
        rhs[ur] = -uf[ur]
    if sliding or full:  # the lower half too
        for r in range(size):
            ur = np.uint64(r)
            for s in range(1, min(kl, size - 1 - r) + 1):
                us = np.uint64(s)
                aband[ur + us, ukl - us] = wband[ur, us]
    for i in range(m):
        st = state[idx[i]]
        if st == 0:
            for r in (2 * i, 2 * i + 1):
                for col in range(max(0, r - kl), min(size, r + kl + 1)):
                    aband[r, col - r + kl] = 0.0
                    aband[col, r - col + kl] = 0.0
                aband[r, kl] = 1.0
                rhs[r] = 0.0
        elif st >= 2:
            rt = 2 * i + 1
            for off in range(2 * kl + 1):
                aband[rt, off] = 0.0
            aband[rt, kl] = 1.0
            aband[rt, kl - 1] = -mu if st == 2 else mu
            rhs[rt] = 0.0
    for r in range(size):
        scale[r] = abs(aband[r, kl])
    return sliding


@numba.njit(cache=True, inline="always")
def _row_velocity(r, size, kl, wband, uf, impulses):
    r"""Row ``r`` of :math:`u = u^f + W P` [m/s] from the upper band ``wband`` of ``W``."""
    u = uf[r]
    for s in range(min(kl, size - 1 - r) + 1):
        u += wband[r, s] * impulses[r + s]
    for s in range(1, min(kl, r) + 1):
        u += wband[r - s, s] * impulses[r - s]
    return u


@numba.njit(cache=True, inline="always")
def _switch_states(m, idx, state, mu, p_tol, u_tol, kl, wband, uf, impulses, solves):
    """Switch the states that the impulses ``impulses`` (rows ``2 i``, ``2 i + 1`` of the
    ``i``-th active contact) contradict (:func:`solve_active_set`); after
    :data:`SINGLE_SWITCH_AFTER` solves only the first. The velocities ``u = u^f + W P`` are
    computed where a test needs them: the normal one of an open contact, the tangential one of
    a sliding contact (a sticking one has ``u = 0`` up to the compliance). Returns whether any
    state changed."""
    size = 2 * m
    changed = False
    for i in range(m):
        c = idx[i]
        pn, pt = impulses[2 * i], impulses[2 * i + 1]
        st = state[c]
        new = st
        if st == 0:
            if _row_velocity(2 * i, size, kl, wband, uf, impulses) < -u_tol:
                new = 1
        elif pn < -p_tol:
            new = 0
        elif st == 1:
            if abs(pt) > mu * pn + p_tol:
                new = 2 if pt > 0.0 else 3
        elif st == 2:
            if _row_velocity(2 * i + 1, size, kl, wband, uf, impulses) > u_tol:
                new = 1
        elif _row_velocity(2 * i + 1, size, kl, wband, uf, impulses) < -u_tol:
            new = 1
        if new != st and not (changed and solves > SINGLE_SWITCH_AFTER):
            state[c] = new
            changed = True
    return changed


@numba.njit(cache=True, _nrt=False)
def solve_active_set(v, inv_mass, contact_bodies, jac, active, impulse, state, mu, p_tol, u_tol,
                     work, max_solves):
    r"""Contact problem of a step by a primal-dual active-set method; ``v`` enters free.

    Every active contact has a state (-1 for an inactive one): 0 open (``P = 0``), 1 stick
    (``u = 0``), 2 slide with ``P_t = +mu P_n`` and 3 slide with ``P_t = -mu P_n``
    (``u_n = 0``). For the current states the impulses solve one linear system in the
    Delassus matrix ``W = H M^-1 H^T`` (assembled once), with
    ``u = u^f + W P`` and :math:`\rho` = :data:`REGULARISATION`:

    .. math::

        \text{open:}\quad P_n = 0,\; P_t = 0,

        \text{stick:}\quad (W P)_n + \rho W_{nn} P_n = -u^f_n, \quad
        (W P)_t + \rho W_{tt} P_t = -u^f_t,

        \text{slide } (\sigma = \pm 1):\quad (W P)_n + \rho W_{nn} P_n = -u^f_n, \quad
        P_t = \sigma \mu P_n.

    The states that the solution contradicts are switched and the system is solved again,
    until none is:

    .. math::

        \text{open} \to \text{stick if } u_n < -\epsilon_u; \qquad
        \text{stick or slide} \to \text{open if } P_n < -\epsilon_P;

        \text{stick} \to \text{slide } \operatorname{sign}(P_t) \text{ if }
        |P_t| > \mu P_n + \epsilon_P; \qquad
        \text{slide } \sigma \to \text{stick if } \sigma u_t > \epsilon_u

    (``u`` evaluated without the compliance). After :data:`SINGLE_SWITCH_AFTER` solves only the
    first contradicted state is switched per solve; after :data:`ACTIVE_SET_SOLVES` the method
    gives up. The compliance picks the smallest impulses among the statically indeterminate
    ones (the split of the friction force between the two ends of a joint). The states start
    from the previous step's; a newly active contact starts sticking. On convergence the
    impulses are written to ``impulse`` and applied to ``v``; otherwise ``v`` and ``impulse``
    keep their input values (the impulses of the previous step, 0 for an inactive contact) and
    the caller falls back to Gauss-Seidel.

    Two contacts couple only through a block they both touch, so ``W`` is a band matrix when
    the contacts are numbered along the structure (an arch: joint by joint, each coupled to its
    two neighbours): it is assembled block by block in band storage
    (:func:`_assemble_delassus`) and the system of the states solved by Cholesky's
    factorisation if no contact slides (:func:`band_cholesky_solve`: it is then symmetric
    positive definite), else by Gaussian elimination (:func:`band_lu_solve`, and with pivoting,
    :func:`band_solve`, should a pivot be small), at a cost linear in the number of contacts.

    Parameters
    ----------
    v : array (nb, 3)
        In: the free velocities; out (if converged): the velocities at the end of the step
        [m/s, m/s, rad/s].
    inv_mass : array (nb, 4)
        Inverse masses [m/kg] and inertias [1/(kg m)], and their square roots.
    contact_bodies : array of int (nc, 2)
        Bodies of every contact (-1: the ground).
    jac : array (nc, 12)
        Jacobian rows (:func:`contact_geometry`).
    active : array of bool (nc,)
        The active set.
    impulse : array (nc, 2)
        Out: the impulses ``(P_n, P_t)`` [N s/m] (0 for inactive contacts).
    state : array of int (nc,)
        In: the previous step's states; out: the new ones.
    mu : float
        Friction coefficient [-].
    p_tol, u_tol : float
        Tolerances :math:`\epsilon_P` [N s/m] and :math:`\epsilon_u` [m/s] of the switching
        tests.
    work : tuple
        ``(idx, pos, pointer, incident, kl, wband, aband, rhs, uf, scale, scaled)``: the block
        incidence ``pointer, incident`` of :func:`incidence` and the half-bandwidth of the
        impulses ``kl = 2 b + 1`` (``b`` that of the contacts); work space: ``idx``, ``pos``
        (nc,) int (the active contacts, and the position of each among them, -1 if inactive),
        ``wband`` (2 nc, kl + 1), ``aband`` (2 nc, 3 kl + 1), ``rhs``, ``uf``, ``scale``
        (2 nc,), ``scaled`` (nc, 12).

    Returns
    -------
    solves : int
        Linear solves made (0 if no contact is active).
    converged : bool
        Whether a consistent set of states was found.
    """
    idx, pos, pointer, incident, kl, wband, aband, rhs, uf, scale, scaled = work
    nc = contact_bodies.shape[0]
    m = 0
    for c in range(nc):
        if active[c]:
            idx[m] = c
            pos[c] = m
            m += 1
            if state[c] < 0:  # newly active: guess that it sticks
                state[c] = 1
        else:
            pos[c] = -1
            state[c] = -1
            impulse[c, 0] = 0.0
            impulse[c, 1] = 0.0
    if m == 0:
        return 0, True
    _assemble_delassus(v, inv_mass, contact_bodies, jac, m, idx, pos, pointer, incident, kl,
                       wband, uf, scaled)
    solves = 0
    converged = False
    while solves < max_solves:
        sliding = _state_system(m, idx, state, mu, kl, wband, uf, aband, rhs, scale, False)
        if sliding and kl == ARCH_BANDWIDTH:
            solved = arch_lu_solve(aband, rhs, 2 * m, scale)
        elif sliding:
            solved = band_lu_solve(aband, rhs, 2 * m, kl, scale)
        elif kl == ARCH_BANDWIDTH:
            solved = arch_cholesky_solve(aband, rhs, 2 * m)
        else:
            solved = band_cholesky_solve(aband, rhs, 2 * m, kl)
        if not solved:  # a small pivot: assemble again and pivot
            _state_system(m, idx, state, mu, kl, wband, uf, aband, rhs, scale, True)
            band_solve(aband, rhs, 2 * m, kl)
        solves += 1
        if not _switch_states(m, idx, state, mu, p_tol, u_tol, kl, wband, uf, rhs, solves):
            converged = True
            break
    if converged:
        for i in range(m):
            c = idx[i]
            impulse[c, 0] = rhs[2 * i] if state[c] != 0 else 0.0
            impulse[c, 1] = rhs[2 * i + 1] if state[c] != 0 else 0.0
            _apply_impulse(v, inv_mass, contact_bodies[c, 0], contact_bodies[c, 1], jac, c,
                           impulse[c, 0], impulse[c, 1])
    return solves, converged


@numba.njit(cache=True)
def solve_lemke(v, inv_mass, contact_bodies, jac, active, impulse, state, mu, p_tol, u_tol,
                work):
    r"""Contact problem of a step by Lemke's algorithm, where the active-set method gave up;
    ``v`` enters free.

    The Delassus matrix and free velocities of the active contacts, as
    :func:`solve_active_set` left them in ``work``, are written out dense and the problem solved
    as a linear complementarity problem (:mod:`archquake.rigid_blocks.lemke`: a method that
    cannot cycle, and a problem that always has a solution). Its states are handed back to the
    active-set method, which then solves them to round-off (usually in one linear solve, the
    impulses then those it would have found had it converged); should it switch them and fail
    again, Lemke's impulses are applied as they are.

    Parameters
    ----------
    v, inv_mass, contact_bodies, jac, active, impulse, state, mu, p_tol, u_tol, work
        As for :func:`solve_active_set`, called just before with the same arguments (``v``
        unchanged since).

    Returns
    -------
    pivots : int
        Pivots of Lemke's algorithm and linear solves of the active-set method after it.
    converged : bool
        Whether the problem was solved (False only if Lemke's algorithm failed, not observed).
    """
    idx, pos, pointer, incident, kl, wband, aband, rhs, uf, scale, scaled = work
    nc = contact_bodies.shape[0]
    m = 0
    for c in range(nc):
        if active[c]:
            m += 1
    size = 2 * m
    dense = np.zeros((size, size))
    for r in range(size):
        for s in range(min(kl, size - 1 - r) + 1):
            dense[r, r + s] = wband[r, s]
            dense[r + s, r] = wband[r, s]
    free = uf[:size].copy()
    impulses = np.zeros(size)
    states = np.zeros(m, dtype=np.int64)
    code, pivots = solve_contact_lcp(dense, free, mu, REGULARISATION, impulses, states)
    if code != LEMKE_SOLVED:
        return pivots, False
    for i in range(m):
        state[idx[i]] = states[i]
    v_free = v.copy()
    solves, converged = solve_active_set(v, inv_mass, contact_bodies, jac, active, impulse,
                                         state, mu, p_tol, u_tol, work, POLISH_SOLVES)
    if converged:
        return pivots + solves, True
    v[:] = v_free  # the active-set method switched Lemke's states and failed: Lemke's impulses
    for i in range(m):
        c = idx[i]
        state[c] = states[i]
        impulse[c, 0] = impulses[2 * i]
        impulse[c, 1] = impulses[2 * i + 1]
        _apply_impulse(v, inv_mass, contact_bodies[c, 0], contact_bodies[c, 1], jac, c,
                       impulse[c, 0], impulse[c, 1])
    return pivots + solves, True


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
    _, cy = _rotate(cos_c, sin_c, crown_x, crown_y)
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
    out[:buffer.shape[0]] = buffer
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
            un, _ = _relative_velocity(v_old, contact_bodies[c, 0], contact_bodies[c, 1], jac, c)
            active[c] = carried[c] or (gap[c] + theta * h * un
                                       <= ACTIVATION_GAP * contacts[c, LENGTH])
        else:
            active[c] = False


@numba.njit(cache=True, _nrt=False)
def _contact_work(v_old, v, v_free, bodies):
    r"""Work of the contact impulses over the step [J/m],

    .. math::

        \sum_c P_c \cdot H_c rac{v_k + v_{k+1}}{2}
        = rac{v_k + v_{k+1}}{2} \cdot \mathbf{M} (v_{k+1} - v^f),

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
                 last):
    r"""How many steps from ``step`` on repeat a static equilibrium (0 if none can be skipped).

    Called after two consecutive steps at rest (kinetic energy at most
    :data:`STEADY_ENERGY` :math:`T_{rest}` before and after the last one): the contact
    forces held the blocks under the mean ground acceleration ``ag`` [m/s^2] of the last step,
    so every following step under the same acceleration repeats it (the same contact problem,
    the same zero velocities). Those steps are

    - before the end of the excitation, of a piecewise-constant motion (``STEP``): the steps
      that lie wholly in the piece of the next step, if its mean acceleration is ``ag`` (to
      round-off: the mean over a step is computed from its ends) (``times[i] <= t <
      times[i + 1]``, up to the step that meets ``times[i + 1]``);
    - after it, on a still ground: the steps of the count of rest up to the one that decides
      (its window, ``rest_steps`` if every joint is ``closed``, else ``open_rest_steps``, less
      the ``rest_count`` steps already counted and the ``last`` steps ``h`` of the step just
      taken, which the next test counts), so that the decision falls on the same step as
      without the skip.

    Nothing of the outcome changes but the round-off of the skipped steps (velocities of
    :math:`10^{-13}` m/s). Returns the number of steps to skip [-]."""
    t = step * h
    if t >= settings[S_EXCITATION_END]:
        if ag != 0.0:
            return 0
        needed = settings[S_REST_STEPS] if closed else settings[S_OPEN_REST_STEPS]
        return max(0, int(needed) - rest_count - last)
    if kind != STEP or abs(mean_acceleration(t, t + h, kind, params, times, values)
                           - ag) > 1e-12 * settings[S_GRAVITY]:  # the same, to round-off
        return 0
    n = times.size
    i = np.searchsorted(times, t, side="right")  # times[i - 1] <= t < times[i]
    if i >= n:
        return 0
    last = int(math.floor(times[i] / h)) - 1  # the last step wholly before times[i]
    return max(0, last - step)


# ---------------------------------------------------------------------------------------------
# The driver
# ---------------------------------------------------------------------------------------------


@numba.njit(cache=True)
def run(bodies, contacts, contact_bodies, q0, v0, kind, params, times, values, settings):
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
        The blocks (:data:`BODY_FIELDS`).
    contacts : array (nc, 12)
        The contacts (:data:`CONTACT_FIELDS`).
    contact_bodies : array of int (nc, 2)
        Bodies a and b of every contact (-1: the ground).
    q0, v0 : array (nb, 3)
        Initial displacements [m, m, rad] and velocities [m/s, m/s, rad/s].
    kind, params, times, values
        The compiled ground motion (``GroundMotion.compiled()``; accelerations [m/s^2], times
        [s]).
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
    h, theta, mu = settings[S_TIME_STEP], settings[S_THETA], settings[S_FRICTION]
    gravity = settings[S_GRAVITY]
    n_steps = int(settings[S_N_STEPS])
    max_iterations = int(settings[S_MAX_ITERATIONS])
    record_stride = int(settings[S_RECORD_STRIDE])
    tail_steps = int(settings[S_TAIL_STEPS])
    crown_block = int(settings[S_CROWN_BLOCK])
    crown_x, crown_y = settings[S_CROWN_X], settings[S_CROWN_Y]
    coarse = max(1, int(settings[S_COARSE_FACTOR]))
    active_set_solves = int(settings[S_ACTIVE_SET_SOLVES])
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
        # -------- 6.-8. a coarse step if one fits, taken again at h if a contact changes
        m = coarse if (step % coarse == 0 and step + coarse <= stop_step) else 1
        if m > 1:
            impulse_k[:] = impulse
            state_k[:] = state
        while True:
            hs = m * h
            tol_impulse = settings[S_TOLERANCE] * mean_mass * gravity * hs
            p_tol = 1e-12 * mean_mass * gravity * hs
            u_tol = 1e-12 * gravity * hs
            # -------- 6. free velocities
            ag = mean_acceleration(t, t + hs, kind, params, times, values)
            _free_velocities(v, v_old, v_free, hs, ag, gravity)
            # -------- 7. active set
            _active_set(gap, valid, v_old, contact_bodies, contacts, jac, theta, hs, carried,
                        active)
            # -------- 8. the contact problem
            sweeps, converged = solve_active_set(v, inv_mass, contact_bodies, jac, active,
                                                 impulse, state, mu, p_tol, u_tol, problem,
                                                 active_set_solves)
            direct = converged
            if not converged and m == 1:  # fall back to Lemke's algorithm
                fallbacks += 0 if decided else 1
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
            v[:] = v_old
            impulse[:] = impulse_k
            state[:] = state_k
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
        if not decided and max(kinetic_before, energies[0]) <= steady_energy:
            skip = min(steady_steps(step, h, ag, kind, params, times, values, settings,
                                    rest_count, closed, last), stop_step - step)
            if recording:  # the skipped steps' records: the same state
                for k in range(step, step + skip):
                    if k >= next_record:
                        rec_energy, rec_q, rec_contacts = _record(
                            n_rec, k * h, q, gap, slip, impulse, hs, energies, rec_energy,
                            rec_q, rec_contacts)
                        n_rec += 1
                        next_record = (k // record_stride + 1) * record_stride
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
    return summary, (rec_energy[:n_rec], rec_q[:n_rec], rec_contacts[:n_rec])
