r"""Rigid-block dynamics of an arch (or any :class:`Assembly`) under a ground motion.

:func:`block_outcome` decides what happens (the fast path: no record, stops as soon as the
outcome is certain); :func:`simulate_blocks` records the time history as well. Both run the one
compiled driver :func:`archquake.rigid_blocks.solver.run` (Moreau-Jean time stepping [1]_, [2]_
with unilateral contacts, Coulomb friction and restitution 0; see that module for the scheme
and the frame of the ground, :mod:`~archquake.rigid_blocks.contacts` for the contact detection
and :mod:`~archquake.rigid_blocks.contact_problem` for the contact problem). A single block
(:func:`~archquake.rigid_blocks.assembly.rectangular_block`) rocks as Housner's [3]_; an arch is
a discrete model of the kind against which the four-link model has been checked [4]_.

The structure starts at rest in its undeformed configuration, every joint closed (unless an
``initial`` state is given); the contact forces that hold it under its weight are found in the
first step (the contact problem of a step at rest is the static problem), so no settling steps
are needed.

Outcome
-------
With ``t`` the thickness of the structure (:attr:`Assembly.thickness`) [m], ``M`` its mass
[kg/m], ``g`` the acceleration of gravity, :math:`t_{exc}` the end of the excitation [s],
:math:`\delta` the largest downward displacement of a block centroid or of the crown point
[m], ``T`` the kinetic and ``V`` the potential energy relative to the undeformed configuration
[J/m] (:mod:`archquake.rigid_blocks.solver`), and :math:`c_{drop}`, :math:`\epsilon_E`,
:math:`v_r` the settings ``collapse_drop``, ``energy_margin``, ``rest_speed`` of
:class:`BlockSettings`, the outcome is tested at every step.

``collapse``
    The drop reaches ``collapse_drop`` times the thickness (default 1.0), at any time; or, once
    the excitation is over, the total mechanical energy falls below ``-energy_margin`` times
    ``M g t`` (default 0.01):

    .. math::

        \delta \ge c_{drop}\,t \quad\text{or}\quad
        \bigl(t_k \ge t_{exc} \;\text{and}\; T + V < -\epsilon_E\,M g t\bigr).

    For Oppenheim's arch the four-link mechanism passes its point of no return (theta_cr) with
    hinge B lowered by 0.50 m = 0.33 t, so a drop of t is well beyond it; with no input the
    energy cannot rise again, so a structure below the energy of its closed configuration
    (potential 0) can never return to it. ``collapse_time`` is the time at which either test
    first holds.
``recovery``
    After the end of the excitation, the kinetic energy stays below that of the whole mass
    moving at ``rest_speed`` times :math:`\sqrt{g t}` for a window of consecutive steps:

    .. math::

        T \le \tfrac12\,M\,\bigl(v_r \sqrt{g t}\bigr)^2 \quad\text{for}\quad
        \begin{cases}
        \text{rest\_window (default 0.1 s)} & \text{every joint closed,} \\
        \text{open\_rest\_window (default 1 s)} & \text{a joint open,}
        \end{cases}

    a joint being closed when both its contacts are valid with a gap at most ``closed_gap``
    times the thickness (the window that applies is that of the current step; a step that is
    not still starts the count again). A structure that is closed and still, with no
    excitation, stays so. A structure still with a joint open is a recovery at rest in a
    displaced configuration (``BlockOutcome.closed`` False): blocks that slipped can wedge
    with a joint open, which the four-link model cannot represent. The longer window keeps a
    near-critical arch that passes slowly near an unstable equilibrium from being taken for
    one at rest. Both windows are at least a tenth of, and one, period :math:`T_s =
    \sqrt{H / g}` of the structure (``H`` its height): a tall structure turns slowly.
``rest``
    As recovery, but no joint ever opened, and none slipped at its more closed end, by more
    than ``moved_opening`` times the thickness during the whole run: the structure moved with
    the ground.

``undecided``
    None of these within ``settle_time`` seconds after the excitation (at least 20 periods
    :math:`T_s`: a tall structure rocks longer before it comes to rest; or by ``t_end``, for a
    time history cut short), or a step whose contact problem was not solved before the
    decision (neither the active-set method, Lemke's algorithm nor Gauss-Seidel solved it: the
    motion after it cannot be trusted; not observed):
    :attr:`Status.UNDECIDED <archquake.status.Status>`, ``decided = False``, never a collapse
    nor a recovery by default.

The outcome, its times and its maxima are those of the decision: a time history recorded on
after it (:func:`simulate_blocks`) reports the same outcome as :func:`block_outcome`.

References
----------
.. [1] M. Jean, "The non-smooth contact dynamics method", Comput. Methods Appl. Mech. Engrg.
   177 (1999) 235-257.

.. [2] V. Acary, B. Brogliato, "Numerical methods for nonsmooth dynamical systems", Springer
   (2008).

.. [3] G. W. Housner, "The behavior of inverted pendulum structures during earthquakes", Bull.
   Seismol. Soc. Am. 53 (1963) 403-417.

.. [4] M. J. DeJong, "Seismic assessment strategies for masonry structures", PhD thesis, MIT
   (2009).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, fields, replace

import numpy as np

from .._equality import value_equality
from ..checks import json_float
from ..compiled import RIGID_BLOCKS, announce
from ..defaults import (
    DEFAULT_COARSE_FACTOR,
    DEFAULT_FRICTION,
    DEFAULT_TIME_STEP,
    MAX_BLOCK_STEPS,
    MAX_COARSE_FACTOR,
    REFERENCE_THICKNESS,
)
from ..geometry import GRAVITY, BlockArch
from ..ground_motion import LINEAR, STEP, GroundMotion
from ..status import Status
from . import solver
from .assembly import GROUND, STICK_FRICTION, Assembly, from_arch, from_block_assembly
from .band import ARCH_BANDWIDTH
from .block_space import block_band
from .contact_problem import ACTIVE_SET_SOLVES, incidence
from .contacts import CONTACT_FIELDS

MAX_BLOCKS = 100
r"""Largest number of blocks of a structure that the rigid-block model analyses [-].

The cost of a step grows linearly with the number of blocks (the contact problem is a band
matrix: about 0.65 us per block and linear solve, ``benchmarks/rigid_blocks_scaling.py``) and so
does the memory (kilobytes per block), but the number of linear solves per step grows too: the
active-set method needs more of them when many joints open or slide at once (about 1.2 per step
for Oppenheim's 7 voussoirs, 20 for 50, 75 for 100 under a 1 g pulse), and an analysis of
100 blocks takes seconds to minutes. A larger structure is refused before anything is
built. Above about ten blocks the active-set method may also cycle at the onset of motion or at
an impact; the step is then solved by Lemke's algorithm, which cannot cycle and costs a dense
tableau (:mod:`archquake.rigid_blocks.contact_problem`, "Contact problem"): most of the time of an
analysis of 100 blocks."""

MAX_ASSEMBLY_BLOCKS = 400
r"""Largest number of blocks of an :class:`Assembly` given as such (a wall, any planar set of
blocks) [-]. Its joints are renumbered to a small bandwidth (:func:`joint_order`), so a step
costs what the bandwidth allows, and where its contacts outnumber its blocks the contact
problem is solved in the blocks' velocities (:func:`contact_unknowns`): a wall in running bond
of 195 blocks and 546 joints runs 12 simulated seconds a minute under a 0.3 g pulse
(``benchmarks/rigid_block_wall.py``; far slower where its joints start to slide at once). An
arch's voussoirs stay limited to :data:`MAX_BLOCKS` (a chain that rocks as a mechanism: many
joints change state at once)."""

CONTACT_STEP_FRACTION = 0.02
r"""Longest time step, as a fraction of :math:`\sqrt{t / g}` (``t`` the thickness of the
structure) [-]: a contact closing at the speed of a fall through a thickness,
:math:`\sqrt{g t}`, sinks by at most :math:`\theta h \sqrt{g t}` in its step, 1 % of the
thickness for ``theta = 1/2`` (7.8 ms for Oppenheim's arch, 4 ms for a block 0.4 m wide)."""

SETTLE_PERIODS, REST_PERIODS, OPEN_REST_PERIODS = 20.0, 0.1, 1.0
r"""The windows of the outcome criteria in periods of the structure, :math:`T_s =
\sqrt{H / g}` with ``H`` its height (:attr:`Assembly.height`) [-]: the time observed after
the excitation is at least ``SETTLE_PERIODS`` periods, the windows of rest at least
``REST_PERIODS`` (every joint closed) and ``OPEN_REST_PERIODS`` (a joint open) periods,
whatever :class:`BlockSettings` says. A tall structure rocks slowly: it needs longer to come to
rest, and its turning points last longer. For the arches of a few metres of the paper
(Oppenheim's: ``H`` = 8.2 m, :math:`T_s` = 0.91 s) the settings' windows are the longer."""

PULSE_STEPS = 20
"""Fewest steps in the shortest piece of a pulse (the time scale of an analytic pulse, the
shortest piece of a piecewise-constant one) [-]."""

UNKNOWNS = ("auto", "impulses", "velocities")
"""The unknowns of the contact problem's linear systems (:class:`BlockSettings`, ``unknowns``)."""

BLOCK_SPACE_GAIN = 2.0
"""Factor [-] by which the blocks' velocities must need fewer operations a factorisation than
the impulses to be chosen (:func:`contact_unknowns`)."""

PHASES = ("still", "pulse", "free", "window")
"""The phases of an analysis in which :func:`outcome_with_phases` counts the steps solved."""

STATUS_NAMES = {solver.REST: Status.REST, solver.RECOVERY: Status.RECOVERY,
                solver.COLLAPSE: Status.COLLAPSE}
"""Outcome code of :func:`archquake.rigid_blocks.solver.run` -> name."""


@dataclass(frozen=True)
class BlockSettings:
    r"""Settings of a rigid-block analysis (module docstring for the outcome criteria).

    Parameters
    ----------
    friction : float
        Coulomb friction coefficient mu of every joint [-], >= 0.
    time_step : float or None
        Time step h [s], > 0; None (the default) chooses it from the structure when an analysis
        starts (:func:`structure_time_step`: 1 ms for Oppenheim's arch, 1.5 m thick, and
        :math:`\sqrt{t / 1.5\,\mathrm{m}}` ms for a structure ``t`` thick).
    theta : float
        Parameter of the theta-method, in [0.5, 1] [-]; 0.5 (the default) is the trapezoidal
        rule, whose energy bookkeeping is exact.
    tolerance : float
        Gauss-Seidel tolerance (the last resort, as ``max_iterations``): largest change of an
        impulse in the last sweep, as a fraction of the impulse ``m_mean g h`` of a mean block's
        weight over a step [-], > 0.
    max_iterations : int
        Largest number of Gauss-Seidel sweeps per step [-], >= 1: the last resort of the contact
        problem, after the active-set method and Lemke's algorithm
        (:mod:`archquake.rigid_blocks.contact_problem`, "Contact problem"; not reached in any test).
    collapse_drop : float
        Drop of a block centroid or of the crown that defines a collapse, as a fraction of the
        thickness [-], > 0.
    energy_margin : float
        Margin of the energy test of collapse, as a fraction of ``M g t`` [-], > 0.
    rest_speed : float
        Speed of rest as a fraction of ``sqrt(g t)`` [-], > 0: the structure is still while
        its kinetic energy is at most ``M (rest_speed sqrt(g t))^2 / 2``.
    closed_gap : float
        Largest gap of a closed joint as a fraction of the thickness [-], > 0.
    moved_opening : float
        Largest opening or slip of a structure that never moved, as a fraction of the
        thickness [-], > 0.
    rest_window : float
        Time the structure must stay closed and still to be back at rest [s], > 0; at least
        :data:`REST_PERIODS` periods of the structure.
    open_rest_window : float
        Time the structure must stay still with a joint open to be at rest in a displaced
        configuration (blocks that slipped and wedged) [s], > 0; longer than ``rest_window``
        so that an arch passing slowly near an unstable equilibrium is not taken for one at
        rest; at least :data:`OPEN_REST_PERIODS` periods of the structure.
    settle_time : float
        Longest time observed after the end of the excitation [s], > 0; at least
        :data:`SETTLE_PERIODS` periods of the structure.
    coarse_factor : int
        Steps ``h`` taken as one while no contact starts or stops carrying an impulse [-],
        in [1, :data:`~archquake.defaults.MAX_COARSE_FACTOR`]; a step in which one does is
        taken again at ``h`` (2, the default, halves the steps of a rocking arch and resolves
        every impact, lift-off and landing at ``h``: :mod:`archquake.rigid_blocks.solver`,
        "Coarse steps"); 1 takes every step at ``h``. A coarse step is never longer than the
        motion allows a step to be (:func:`check_time_step`): under a shorter pulse or a finer
        record the analysis takes fewer steps ``h`` as one, down to every step at ``h``.
    active_set_solves : int
        Largest number of linear solves of the active-set method in a step before Lemke's
        algorithm solves the step's contact problem [-], >= 0
        (:mod:`archquake.rigid_blocks.contact_problem`, "Contact problem"): the active-set
        method is fast but may cycle, Lemke's algorithm cannot. 0 solves every step by Lemke's
        algorithm (a check of the active-set method: the same motion to round-off, many times
        slower).
    skip_rest : bool
        Skip the steps that would repeat a static equilibrium (True, the default): a structure
        at rest under a constant piece of a piecewise-constant pulse stays at rest to the
        piece's end, and one at rest after the excitation stays at rest through its window of
        rest (:func:`archquake.rigid_blocks.solver.steady_steps`); at rest under a motion that
        varies (a record, a sine), it stays at rest while the step's mean acceleration lies in
        the range in which its contact problem holds it
        (:func:`archquake.rigid_blocks.contact_problem.rest_range`,
        :func:`archquake.rigid_blocks.solver.held_steps`), moved by the creep of the
        compliance as those steps would move it. False takes every step: the same outcome, its
        times and maxima, the check of the skip (``benchmarks/rigid_block_savings.py`` times
        both, ``--records`` under records).
    unknowns : str
        The unknowns of the linear systems of the contact problem (the same states, tests and
        solution to the compliance's resolution): ``"impulses"``, two a contact, in a band of
        ``W`` (:func:`~archquake.rigid_blocks.contact_problem.solve_active_set`), or
        ``"velocities"``, three a block
        (:func:`~archquake.rigid_blocks.block_space.solve_active_set_blocks`), cheaper where
        contacts outnumber blocks in a wide band (walls, rings); ``"auto"`` (the default)
        chooses the one of fewer operations (:func:`contact_unknowns`): arches and arches on
        piers keep the impulses, bit for bit.

    Raises
    ------
    ValueError
        If a field is not a finite number (``skip_rest``: not a bool), ``friction < 0``,
        ``theta`` is outside [0.5, 1],
        ``max_iterations`` is not an integer >= 1, or another field is not > 0.

    Notes
    -----
    The thresholds are scaled to the structure when an analysis starts, with ``t`` its
    thickness [m], ``M`` its mass [kg/m] and ``g`` [m/s^2] (module docstring):

    .. math::

        \delta_{lim} = c_{drop}\,t, \qquad E_{margin} = \epsilon_E\,M g t, \qquad
        T_{rest} = \tfrac12 M v_r^2\,g t, \qquad g_{closed} = c_{gap}\,t, \qquad
        d_{moved} = c_{moved}\,t,

    with :math:`c_{drop}, \epsilon_E, v_r, c_{gap}, c_{moved}` = ``collapse_drop``,
    ``energy_margin``, ``rest_speed``, ``closed_gap``, ``moved_opening``; the time windows are
    scaled with the period of the structure :math:`T_s = \sqrt{H / g}` (``H`` its height,
    :attr:`Assembly.height`),

    .. math::

        T_{settle} = \max(\text{settle\_time},\, 20\,T_s), \quad
        T_{rest} = \max(\text{rest\_window},\, 0.1\,T_s), \quad
        T_{open} = \max(\text{open\_rest\_window},\, T_s)

    (:data:`SETTLE_PERIODS`, :data:`REST_PERIODS`, :data:`OPEN_REST_PERIODS`) and rounded to
    whole steps (at least one).
    """

    friction: float = DEFAULT_FRICTION
    time_step: float | None = None
    theta: float = 0.5
    tolerance: float = 1e-6
    max_iterations: int = 1000
    collapse_drop: float = 1.0
    energy_margin: float = 0.01
    rest_speed: float = 1e-4
    closed_gap: float = 1e-4
    moved_opening: float = 1e-5
    rest_window: float = 0.1
    open_rest_window: float = 1.0
    settle_time: float = 20.0
    coarse_factor: int = DEFAULT_COARSE_FACTOR
    active_set_solves: int = ACTIVE_SET_SOLVES
    skip_rest: bool = True
    unknowns: str = "auto"

    def __post_init__(self):
        if not isinstance(self.skip_rest, bool | np.bool_):
            raise ValueError(f"skip_rest must be True or False, got {self.skip_rest!r}")
        if self.unknowns not in UNKNOWNS:
            raise ValueError(f"unknowns must be one of {', '.join(UNKNOWNS)}, "
                             f"got {self.unknowns!r}")
        for f in fields(self):
            value = getattr(self, f.name)
            if f.name == "time_step" and value is None:  # chosen from the structure
                continue
            if f.name in ("skip_rest", "unknowns"):
                continue
            if isinstance(value, bool) or not isinstance(value, (int, float)):
                raise ValueError(f"{f.name} must be a number, got {value!r}")
            if not math.isfinite(value):
                raise ValueError(f"{f.name} must be finite, got {value!r}")
        if self.friction < 0:
            raise ValueError(f"friction must be >= 0 [-], got {self.friction!r}")
        if not 0.5 <= self.theta <= 1.0:
            raise ValueError(f"theta must be in [0.5, 1] [-], got {self.theta!r}")
        value = self.max_iterations
        if int(value) != value or value < 1:
            raise ValueError(f"max_iterations must be an integer >= 1, got {value!r}")
        value = self.coarse_factor
        if (isinstance(value, bool) or not isinstance(value, int | float | np.integer)
                or not 1 <= value <= MAX_COARSE_FACTOR or int(value) != value):
            raise ValueError(f"coarse_factor must be an integer in [1, {MAX_COARSE_FACTOR}] "
                             f"(MAX_COARSE_FACTOR), got {value!r}")
        value = self.active_set_solves
        if int(value) != value or value < 0:
            raise ValueError(f"active_set_solves must be an integer >= 0, got {value!r}")
        for name in ("time_step", "tolerance", "collapse_drop", "energy_margin", "rest_speed",
                     "closed_gap", "moved_opening", "rest_window", "open_rest_window",
                     "settle_time"):
            if getattr(self, name) is not None and getattr(self, name) <= 0:
                raise ValueError(f"{name} must be > 0, got {getattr(self, name)!r}")


@value_equality
@dataclass(frozen=True)
class BlockOutcome:
    """What a rigid-block analysis decided.

    Attributes
    ----------
    status : Status
        ``Status.REST``, ``Status.RECOVERY``, ``Status.COLLAPSE`` or, when the run did not decide
        (:attr:`decided` False), ``Status.UNDECIDED`` (module docstring;
        :class:`archquake.status.Status`, as the four-link model's outcomes carry it; its label
        ``"undecided"`` in JSON and text).
    collapse_time : float
        Time at which the collapse became certain [s]; nan without collapse.
    max_rotation : float
        Largest absolute rotation of a block until the decision [rad] (as every maximum here:
        until the last step if undecided).
    max_crown_drop : float
        Largest downward displacement of the crown point [m].
    max_slip : float
        Largest tangential offset at the more closed end of a joint [m].
    max_opening : float
        Largest gap at a joint end whose contact is valid [m].
    decided : bool
        False if the run reached ``settle_time`` after the excitation undecided (or, for
        :func:`simulate_blocks` with ``t_end``, reached ``t_end``), or if a step's contact
        problem was not solved before the decision (``unconverged_steps``).
    closed : bool
        Every joint closed (both contacts valid with a gap at most ``closed_gap`` times the
        thickness) at the decision (at the last step if undecided); False for a recovery at
        rest in a displaced configuration, and as a rule for a collapse.
    decision_time : float
        Time at which the outcome was decided [s]; nan if undecided.
    steps : int
        Time steps taken to the decision (to the end if undecided) [-].
    mean_iterations : float
        Mean number of linear solves of the active-set method per step [-]; a step left to
        Lemke's algorithm counts its pivots too (and Gauss-Seidel's sweeps, should it be
        reached).
    fallback_steps : int
        Steps whose contact problem the active-set method left to Lemke's algorithm [-].
    unconverged_steps : int
        Of these, steps that neither Lemke's algorithm nor Gauss-Seidel solved [-] (none in any
        test); any makes the outcome undecided.
    """

    status: Status
    collapse_time: float
    max_rotation: float
    max_crown_drop: float
    max_slip: float
    max_opening: float
    decided: bool
    closed: bool
    decision_time: float
    steps: int
    mean_iterations: float
    fallback_steps: int
    unconverged_steps: int

    @property
    def collapsed(self) -> bool:
        """Whether the structure collapses."""
        return self.status is Status.COLLAPSE

    def to_dict(self) -> dict:
        """JSON-ready summary: every field by name, in the units above (nan as None,
        :func:`archquake.checks.json_float`; the status by its label).

        Returns
        -------
        dict
        """
        out = {}
        for f in fields(self):
            value = getattr(self, f.name)
            if isinstance(value, Status):
                value = value.label
            elif isinstance(value, float):
                value = json_float(value)
            out[f.name] = value
        return out


@dataclass(frozen=True, eq=False)
class BlockHistory:
    """Recorded time history of a rigid-block analysis (arrays over the records, SI units).

    Attributes
    ----------
    assembly : Assembly
        The blocks and joints.
    outcome : BlockOutcome
        The outcome of the run.
    times : array (nr,)
        Times [s].
    displacements : array (nr, nb, 2)
        Centroid displacement of every block relative to the ground [m].
    rotations : array (nr, nb)
        Rotation of every block [rad], counterclockwise.
    gaps : array (nr, nj, 2)
        Gap at both ends of every joint [m] (> 0 open, < 0 a small penetration).
    offsets : array (nr, nj, 2)
        Tangential offset at both ends of every joint [m].
    normal_forces, tangential_forces : array (nr, nj, 2)
        Mean contact forces over the step that ends at each record, ``P / h`` [N/m] (0 at the
        first record).
    kinetic_energy, potential_energy, dissipated_energy, input_work : array (nr,)
        Energies ``T``, ``V``, ``D`` and ``W`` [J/m] (module docstring of
        :mod:`archquake.rigid_blocks.solver`); for ``theta = 1/2``,
        ``T + V + D - W`` stays at its initial value ``T(0) + V(0)`` to round-off.
    motion_name : str
        Name of the ground motion.
    settings : BlockSettings
        The settings of the run.
    """

    assembly: Assembly
    outcome: BlockOutcome
    times: np.ndarray
    displacements: np.ndarray
    rotations: np.ndarray
    gaps: np.ndarray
    offsets: np.ndarray
    normal_forces: np.ndarray
    tangential_forces: np.ndarray
    kinetic_energy: np.ndarray
    potential_energy: np.ndarray
    dissipated_energy: np.ndarray
    input_work: np.ndarray
    motion_name: str = ""
    settings: BlockSettings = field(default_factory=BlockSettings)

    @property
    def openings(self) -> np.ndarray:
        """Opening of every joint: its larger end gap, >= 0 [m], shape (nr, nj)."""
        return np.maximum(self.gaps.max(axis=2), 0.0)

    @property
    def slips(self) -> np.ndarray:
        """Slip of every joint: the tangential offset at its more closed end [m], (nr, nj)."""
        closer = np.argmin(self.gaps, axis=2)
        return np.take_along_axis(self.offsets, closer[..., None], axis=2)[..., 0]

    @property
    def crown_drop(self) -> np.ndarray:
        r"""Downward displacement of the crown point [m], shape (nr,).

        With ``r`` the crown point relative to its block's centroid [m],
        :math:`-\bigl(y + r_x \sin\theta + r_y (\cos\theta - 1)\bigr)`.
        """
        block, point = self.assembly.crown
        r = point - self.assembly.centroids[block]
        th = self.rotations[:, block]
        dy = self.displacements[:, block, 1] + np.sin(th) * r[0] + np.cos(th) * r[1] - r[1]
        return -dy

    @property
    def total_energy(self) -> np.ndarray:
        """Kinetic plus potential energy [J/m]."""
        return self.kinetic_energy + self.potential_energy

    def outlines(self, record: int) -> list[np.ndarray]:
        """Outline polygon of every block at record ``record`` [m] (ground frame).

        Parameters
        ----------
        record : int
            Index of the record.

        Returns
        -------
        list of array (k_i, 2)
            Every outline turned by the block's rotation about its centroid and moved with it.
        """
        out = []
        for i, outline in enumerate(self.assembly.outlines):
            c0 = self.assembly.centroids[i]
            th = self.rotations[record, i]
            rot = np.array([[math.cos(th), -math.sin(th)], [math.sin(th), math.cos(th)]])
            out.append(c0 + self.displacements[record, i] + (outline - c0) @ rot.T)
        return out


def joint_half_bandwidth(joint_bodies, n_blocks: int, order=None) -> int:
    r"""Half-bandwidth of the contact problem in the joints [-]: the largest distance
    ``|k - l|`` between the positions of two joints that touch one block, the joints numbered
    in ``order`` (the caller's order if None).

    With the two contacts of the joint at position ``k`` numbered ``2k, 2k + 1``, the
    half-bandwidth of the contacts that :func:`~archquake.rigid_blocks.contact_problem.incidence`
    computes is ``2 b + 1`` and that of the impulses ``4 b + 3`` (two per contact): a
    contact problem costs :math:`O(n\,k_l^2)` per linear solve.

    Parameters
    ----------
    joint_bodies : array of int (nj, 2)
        Bodies of every joint (:data:`GROUND` for a support).
    n_blocks : int
        Number of blocks.
    order : array of int (nj,), optional
        Joint at every position: position ``k`` holds the caller's joint ``order[k]``.

    Returns
    -------
    int
        ``b`` [-] (0 if no block has two joints).
    """
    bodies = np.asarray(joint_bodies)
    nj = bodies.shape[0]
    position = np.arange(nj)
    if order is not None:
        position = np.empty(nj, dtype=np.int64)
        position[np.asarray(order)] = np.arange(nj)
    lo = np.full(n_blocks, nj, dtype=np.int64)
    hi = np.full(n_blocks, -1, dtype=np.int64)
    for side in range(2):
        body = bodies[:, side]
        block = body >= 0
        np.minimum.at(lo, body[block], position[block])
        np.maximum.at(hi, body[block], position[block])
    used = hi >= 0
    return int((hi[used] - lo[used]).max(initial=0))


def joint_order(assembly: Assembly) -> np.ndarray:
    r"""The order in which the solver numbers the joints: position ``k`` holds joint
    ``order[k]`` of the assembly (read-only (nj,) int; cached on the assembly).

    The Delassus matrix of the contact problem is a band matrix whose half-bandwidth is set by
    the joints that touch one block (:func:`joint_half_bandwidth`): small for a chain numbered
    along it (an arch), large for a wall whose joints come in an arbitrary order. The joints are
    renumbered by the reverse Cuthill-McKee ordering [1]_ of their adjacency graph (two joints
    adjacent when they touch one block; ``scipy.sparse.csgraph.reverse_cuthill_mckee``), and
    the new order is kept only where it makes the half-bandwidth strictly smaller: an arch, or
    any structure already well numbered, keeps its own order (the identity), so its analyses
    are unchanged to the bit. Every output of an analysis is given back in the assembly's joint
    order (:func:`simulate_blocks`).

    Parameters
    ----------
    assembly : Assembly
        The blocks and joints.

    Returns
    -------
    array of int (nj,)
        The permutation.

    References
    ----------
    .. [1] A. George, J. W. H. Liu, "Computer solution of large sparse positive definite
       systems", Prentice-Hall (1981), Sec. 4.3 (the reverse Cuthill-McKee algorithm).
    """
    if "joint_order" not in assembly._cache:
        from scipy.sparse import csr_matrix
        from scipy.sparse.csgraph import reverse_cuthill_mckee

        bodies, nb, nj = assembly.joint_bodies, assembly.n_blocks, assembly.n_joints
        order = np.arange(nj)
        rows = np.concatenate([np.flatnonzero(bodies[:, side] >= 0) for side in range(2)])
        cols = np.concatenate([bodies[bodies[:, side] >= 0, side] for side in range(2)])
        incidence = csr_matrix((np.ones(rows.size), (rows, cols)), shape=(nj, nb))
        adjacency = (incidence @ incidence.T).tocsr()
        candidate = np.asarray(reverse_cuthill_mckee(adjacency, symmetric_mode=True),
                               dtype=np.int64)
        if (joint_half_bandwidth(bodies, nb, candidate)
                < joint_half_bandwidth(bodies, nb)):
            order = candidate
        order = np.ascontiguousarray(order, dtype=np.int64)
        order.setflags(write=False)
        assembly._cache["joint_order"] = order
    return assembly._cache["joint_order"]


def contact_unknowns(assembly: Assembly, unknowns: str = "auto",
                     reorder: bool = True) -> tuple[np.ndarray, int]:
    r"""The blocks' band of the contact problem in the blocks' velocities, ``(position, kb)``
    (:func:`~archquake.rigid_blocks.block_space.block_band`), or an empty ``position`` to solve
    it in the impulses (:class:`BlockSettings`, ``unknowns``).

    ``"auto"`` counts the operations of a factorisation of each band (``n k^2``: ``2 nc``
    impulses of half-bandwidth ``kl``, :func:`~archquake.rigid_blocks.contact_problem.incidence`,
    against ``3 nb`` velocities of half-bandwidth ``kb``) and takes the velocities where they
    are fewer by :data:`BLOCK_SPACE_GAIN` (the refinement of the impulses costs a solve or two
    more). An arch, whose band in the impulses is :data:`~.band.ARCH_BANDWIDTH` wide, keeps
    the impulses. Computed once and cached on the assembly.
    """
    key = ("contact_unknowns", unknowns, reorder)
    if key not in assembly._cache:
        assembly._cache[key] = _contact_unknowns(assembly, unknowns, reorder)
    return assembly._cache[key]


def _contact_unknowns(assembly: Assembly, unknowns: str, reorder: bool):
    """:func:`contact_unknowns`, computed (it caches it on the assembly)."""
    contact_bodies = contact_arrays(assembly, reorder)["contact_bodies"]
    nb = assembly.n_blocks
    none = (np.zeros(0, dtype=np.int64), 0)
    if unknowns == "impulses":
        return none
    if unknowns == "velocities":
        return block_band(contact_bodies, nb)
    _, _, half = incidence(contact_bodies, nb)
    kl = 2 * half + 1
    if kl <= ARCH_BANDWIDTH:
        return none
    position, kb = block_band(contact_bodies, nb)
    impulses = 2 * contact_bodies.shape[0] * kl**2
    velocities = 3 * nb * kb**2
    return (position, kb) if velocities * BLOCK_SPACE_GAIN < impulses else none


def contact_arrays(assembly: Assembly, reorder: bool = True) -> dict[str, np.ndarray]:
    """The packed arrays of the compiled solver: contact ``2 k + e`` is end ``e`` of the joint
    at position ``k`` of :func:`joint_order` (``reorder``; joint ``k`` itself without).

    ``bodies`` (nb, 4): mass [kg/m], inertia [kg m] and centroid [m] of every block
    (:data:`archquake.rigid_blocks.contacts.BODY_FIELDS`); ``contacts`` (nc, 14): the contact
    point relative to the centroid of body a and of body b in the undeformed configuration (the
    absolute point for the ground) [m], the joint's unit normal and tangent [-], the position of
    the end along the joint (0 or its length), the face of body a along the joint and the joint's
    length [m], its friction [-] and curvature [1/m] (along a curved joint: the normal and
    tangent at the end, lengths along the arc;
    :data:`~archquake.rigid_blocks.contacts.CONTACT_FIELDS`); ``contact_bodies``
    (nc, 2) int: bodies a and b (:data:`GROUND` for a support).

    Parameters
    ----------
    assembly : Assembly
        The blocks and joints.

    Returns
    -------
    dict of str to array
        The three arrays, contiguous and writable (one compiled signature whatever the
        assembly's arrays are), ``nc = 2 nj``; computed once and cached on the assembly.
    """
    key = "contacts" if reorder else "contacts_natural"
    if key not in assembly._cache:
        nj = assembly.n_joints
        order = joint_order(assembly) if reorder else np.arange(nj)
        joint_bodies = assembly.joint_bodies[order]
        joint_points = assembly.joint_points[order]
        ca = np.repeat(joint_bodies[:, 0], 2)
        cb = np.repeat(joint_bodies[:, 1], 2)
        points = joint_points.reshape(2 * nj, 2)
        centroid = np.vstack((assembly.centroids, np.zeros((1, 2))))  # index -1: the ground
        lengths = assembly.arc_lengths[order]
        normals = assembly.end_normals()[order].reshape(2 * nj, 2)
        faces = assembly.face_extents[order]
        columns = {
            "ra": points - centroid[ca], "rb": points - centroid[cb],
            "normal": normals,
            "tangent": np.column_stack((-normals[:, 1], normals[:, 0])),
            "offset": np.column_stack((np.zeros(nj), lengths)).reshape(-1),
            "face_lo": np.repeat(faces[:, 0], 2),
            "face_hi": np.repeat(faces[:, 1], 2),
            "length": np.repeat(lengths, 2),
            "friction": np.repeat(np.full(nj, np.nan) if assembly.friction is None else
                                  np.minimum(assembly.friction[order], STICK_FRICTION), 2),
            "curvature": np.repeat(assembly.curvature[order], 2),
        }
        contacts = np.column_stack([np.reshape(x, (2 * nj, -1)) for x in columns.values()])
        assert contacts.shape[1] == len(CONTACT_FIELDS)
        bodies = np.column_stack((assembly.masses, assembly.inertias, assembly.centroids))
        assembly._cache[key] = {
            "bodies": np.ascontiguousarray(bodies, dtype=float),
            "contacts": np.ascontiguousarray(contacts, dtype=float),
            "contact_bodies": np.ascontiguousarray(np.column_stack((ca, cb)), dtype=np.int64),
        }
    return assembly._cache[key]


def check_size(n_blocks: int, limit: int | None = None) -> None:
    """Refuse a structure of more than ``limit`` blocks.

    Parameters
    ----------
    n_blocks : int
        Number of blocks of the structure (of voussoirs of an arch) [-].
    limit : int, optional
        The largest number of blocks [-]: :data:`MAX_BLOCKS` (the default, an arch's
        voussoirs) or :data:`MAX_ASSEMBLY_BLOCKS` (an :class:`Assembly` given as such).

    Raises
    ------
    ValueError
        If ``n_blocks > limit``.
    """
    if limit is None or limit == MAX_BLOCKS:
        if n_blocks > MAX_BLOCKS:
            raise ValueError(f"the rigid-block model takes at most {MAX_BLOCKS} blocks "
                             f"(MAX_BLOCKS), this structure has {n_blocks} (voussoirs or "
                             f"blocks): the solves per step grow with the blocks that move at "
                             f"once, and an analysis would take minutes; use fewer voussoirs")
    elif n_blocks > limit:
        raise ValueError(f"the rigid-block model takes an assembly of at most {limit} blocks "
                         f"(MAX_ASSEMBLY_BLOCKS), this one has {n_blocks}: a step's contact "
                         f"problem grows with the blocks and their joints' bandwidth")


def structure_assembly(structure) -> Assembly:
    """The :class:`Assembly` of an arch (converted once, cached on it) or an Assembly itself.

    Raises
    ------
    ValueError
        If ``structure`` is neither, or has more than :data:`MAX_BLOCKS` voussoirs (an arch) or
        :data:`MAX_ASSEMBLY_BLOCKS` blocks (an Assembly) (refused before
        an arch is converted).
    """
    if isinstance(structure, Assembly):
        check_size(structure.n_blocks, MAX_ASSEMBLY_BLOCKS)
        return structure
    if isinstance(structure, BlockArch):
        check_size(structure.n_voussoirs)
        key = "_rigid_block_assembly"
        if key not in structure._cache:
            structure._cache[key] = from_arch(structure)
        return structure._cache[key]
    if hasattr(structure, "interfaces") and hasattr(structure, "polygons"):  # BlockAssembly
        check_size(structure.n_blocks, MAX_ASSEMBLY_BLOCKS)
        return from_block_assembly(structure)
    raise ValueError(f"structure must be an arch, a block assembly or an Assembly, got "
                     f"{type(structure).__name__}")


def structure_time_step(thickness: float) -> float:
    r"""The default time step of the rigid-block model for a structure ``thickness`` thick [s].

    .. math::

        h = h_0 \sqrt{t / t_0}, \qquad h_0 = 1\ \mathrm{ms}, \quad t_0 = 1.5\ \mathrm{m}

    (:data:`archquake.defaults.DEFAULT_TIME_STEP`, :data:`archquake.defaults.REFERENCE_THICKNESS`):
    rigid blocks under gravity obey no length scale of their own, so a structure ``k`` times
    smaller moves :math:`\sqrt{k}` times faster, and the same step relative to
    :math:`\sqrt{t / g}` resolves it as well. Measured: Oppenheim's arch scaled down four times
    (R = 2.5 m, t = 0.375 m) under pulses half as long fails at 1 ms at exactly the accelerations
    of the full arch at 2 ms (0.005 g too high at t_p = 0.2 s), and at 0.5 ms at those of the
    full arch at 1 ms. The step of Oppenheim's arch itself is 1 ms exactly.

    Parameters
    ----------
    thickness : float
        Thickness (length scale) of the structure [m], > 0.

    Returns
    -------
    float
        The time step [s].
    """
    return DEFAULT_TIME_STEP * math.sqrt(float(thickness) / REFERENCE_THICKNESS)


def time_step_for(structure) -> float:
    """The default time step of a structure (an arch or an :class:`Assembly`) [s]:
    :func:`structure_time_step` of its thickness."""
    return structure_time_step(structure_assembly(structure).thickness)


def study_time_step(time_step: float | None, nominal) -> float:
    """The time step of a study [s]: ``time_step`` if given, else that of its ``nominal``
    structure (:func:`time_step_for`; :data:`archquake.defaults.DEFAULT_TIME_STEP` for what is
    not a structure, which the study's own checks then refuse)."""
    if time_step is not None:
        return time_step
    try:
        return time_step_for(nominal)
    except ValueError:  # not a structure: said where the study checks its nominal
        return DEFAULT_TIME_STEP


def resolved_settings(settings: BlockSettings | None, structure) -> BlockSettings:
    """``settings`` (None: the defaults) with a time step: its own, or that of ``structure``
    (an arch or an :class:`Assembly`; :func:`time_step_for`) when it has none."""
    settings = BlockSettings() if settings is None else settings
    if settings.time_step is not None:
        return settings
    return replace(settings, time_step=time_step_for(structure))


def check_time_step(time_step: float, motion: GroundMotion, thickness: float) -> float:
    r"""Refuse a time step that cannot resolve the motion.

    The step ``h`` must resolve the contact law and the ground motion:

    .. math::

        h \le c\,\sqrt{t / g}, \qquad h \le T_m / N \ \text{(a pulse)}, \qquad
        h \le \Delta t \ \text{(a record)},

    with ``t`` the thickness [m], :math:`c` = :data:`CONTACT_STEP_FRACTION`, :math:`T_m` the
    time scale of an analytic pulse (its ``params[1]``: the period of a sine or Ricker pulse)
    or the shortest piece in which a piecewise-constant one moves the ground (``t_p`` of
    Oppenheim's or a rectangular pulse) [s], :math:`N` = :data:`PULSE_STEPS`, and
    :math:`\Delta t` the (median) sample spacing of a record (a piecewise-linear table) [s];
    a still ground sets no limit. A longer step averages the pulse away (a 1 s step leaves
    Oppenheim's arch at rest under a -1 g pulse of 0.27 s that collapses it: the mean ground
    acceleration of a step over the whole pulse is zero) or lets contacts sink into one
    another. At the default step (1 ms for Oppenheim's arch, :func:`structure_time_step`),
    halving it leaves the outcomes 0.01 g on either side of Oppenheim's failure accelerations
    unchanged (tested).

    Parameters
    ----------
    time_step : float
        The time step h [s].
    motion : GroundMotion
        The ground motion.
    thickness : float
        Thickness (length scale) of the structure [m].

    Returns
    -------
    float
        The longest step allowed [s] (a coarse step is never longer).

    Raises
    ------
    ValueError
        Naming ``time_step``, the longest step allowed and why.
    """
    limits = [(CONTACT_STEP_FRACTION * math.sqrt(thickness / GRAVITY),
               f"{CONTACT_STEP_FRACTION:g} sqrt(t/g) for a structure {thickness:g} m thick (a "
               f"closing contact would sink by more than 1 % of it)")]
    times, values = np.asarray(motion.times), np.asarray(motion.values)
    if motion.is_analytic and motion.params[0] != 0.0:
        limits.append((float(motion.params[1]) / PULSE_STEPS,
                       f"1/{PULSE_STEPS} of the pulse's time scale {float(motion.params[1]):g} s"))
    elif motion.kind == STEP and np.any(values != 0.0):
        piece = float(np.min(np.diff(times)[values != 0.0]))
        limits.append((piece / PULSE_STEPS,
                       f"1/{PULSE_STEPS} of the pulse's shortest piece {piece:g} s"))
    elif motion.kind == LINEAR and np.any(values != 0.0):
        spacing = float(np.median(np.diff(times)))
        limits.append((spacing, f"the record's sample spacing {spacing:g} s"))
    longest, why = min(limits)
    if time_step > longest * (1.0 + 1e-9):
        name = motion.name or "the ground motion"
        raise ValueError(f"time_step must be at most {longest:.3g} s to resolve the motion "
                         f"({name}): {why}; got {time_step:g} s")
    return longest


def observation_windows(assembly: Assembly, settings: BlockSettings) -> tuple[float, float,
                                                                              float]:
    r"""The time observed after the excitation and the two windows of rest of an analysis [s]:
    the settings' ``settle_time``, ``rest_window`` and ``open_rest_window``, or
    :data:`SETTLE_PERIODS`, :data:`REST_PERIODS` and :data:`OPEN_REST_PERIODS` periods
    :math:`T_s = \sqrt{H / g}` of the structure if longer.

    Parameters
    ----------
    assembly : Assembly
        The structure (its :attr:`~Assembly.height` [m]).
    settings : BlockSettings
        The settings.

    Returns
    -------
    (float, float, float)
        ``(settle, rest, open_rest)`` [s].
    """
    period = math.sqrt(assembly.height / GRAVITY)
    return (max(settings.settle_time, SETTLE_PERIODS * period),
            max(settings.rest_window, REST_PERIODS * period),
            max(settings.open_rest_window, OPEN_REST_PERIODS * period))


def _initial_state(assembly: Assembly, initial) -> tuple[np.ndarray, np.ndarray]:
    """Checked ``(q0, v0)``, each (nb, 3) [m, m, rad] and [m/s, m/s, rad/s]; zeros for None."""
    nb = assembly.n_blocks
    if initial is None:
        return np.zeros((nb, 3)), np.zeros((nb, 3))
    try:
        q0, v0 = (np.array(x, dtype=float) for x in initial)
    except (TypeError, ValueError) as exc:
        raise ValueError("initial must be (displacements, velocities), two arrays of shape "
                         f"({nb}, 3) [m, m, rad] and [m/s, m/s, rad/s]") from exc
    if q0.shape != (nb, 3) or v0.shape != (nb, 3):
        raise ValueError(f"initial state arrays must have shape ({nb}, 3), got {q0.shape} and "
                         f"{v0.shape}")
    if not (np.all(np.isfinite(q0)) and np.all(np.isfinite(v0))):
        raise ValueError("initial state must be finite")
    return q0, v0


def _run(structure, motion: GroundMotion | None, settings: BlockSettings | None, *,
         initial=None, record_every: int = 0, t_end: float | None = None,
         tail: float = 0.5, reorder: bool = True):
    """Check the input, scale the thresholds to the structure and run the compiled driver.

    Returns ``(assembly, settings, motion, outcome, records, order, phases)`` (records as
    :func:`archquake.rigid_blocks.solver.run` returns them, their contacts numbered in the
    joint order ``order``, :func:`joint_order` if ``reorder``; ``phases`` the steps solved by
    phase, :func:`outcome_with_phases`).
    """
    assembly = structure_assembly(structure)
    settings = BlockSettings() if settings is None else settings
    if not isinstance(settings, BlockSettings):
        raise ValueError(f"settings must be a BlockSettings, got {type(settings).__name__}")
    if motion is None:
        from ..ground_motion import still_ground

        motion = still_ground()
    if not isinstance(motion, GroundMotion):
        raise ValueError(f"motion must be a GroundMotion, got {type(motion).__name__}")
    q0, v0 = _initial_state(assembly, initial)
    settings = resolved_settings(settings, assembly)
    h = float(settings.time_step)
    longest = check_time_step(h, motion, assembly.thickness)
    # a coarse step resolves the motion as a step must: never longer than the longest allowed
    coarse = max(1, min(int(settings.coarse_factor), int(longest * (1.0 + 1e-9) / h)))
    excitation_end = motion.duration
    windows = observation_windows(assembly, settings)
    if t_end is not None and not (math.isfinite(t_end) and t_end > 0):
        raise ValueError(f"t_end must be a finite time > 0 [s], got {t_end!r}")
    # the time run [s]: to t_end, or to the end of the excitation and its first window, and the
    # tail recorded after the decision; counted in steps only once the count is known to fit
    span = t_end if t_end is not None else excitation_end + windows[0]
    recorded_tail = tail if t_end is None and record_every else 0.0
    if not (span + recorded_tail) / h <= MAX_BLOCK_STEPS:  # inf and 1e300 steps alike
        count = f"{span / h:.3g}" if math.isfinite(span / h) else "too many"
        raise ValueError(f"the analysis would take {count} time steps of {h:g} s (to "
                         f"{span:.4g} s), more than {MAX_BLOCK_STEPS} (MAX_BLOCK_STEPS): "
                         f"use a larger time step or a shorter t_end")
    if t_end is not None:
        n_steps, tail_steps = int(math.ceil(t_end / h - 1e-9)), -1
    else:
        tail_steps = int(round(min(tail / h, MAX_BLOCK_STEPS + 1)))
        n_steps = int(math.ceil(span / h)) + (tail_steps if record_every else 0)
    thickness = assembly.thickness
    total_mass = assembly.total_mass
    arrays = contact_arrays(assembly, reorder)
    order = joint_order(assembly) if reorder else np.arange(assembly.n_joints)
    # writeable copies: one compiled signature whether the arrays are frozen or unpickled
    kind, params, times, values = (np.array(x, dtype=float) if i else x
                                   for i, x in enumerate(motion.compiled()))
    crown_block, crown_point = assembly.crown
    crown_r = crown_point - assembly.centroids[crown_block]
    packed = solver.pack_settings(
        time_step=h, theta=settings.theta, friction=settings.friction,
        tolerance=settings.tolerance, max_iterations=settings.max_iterations, gravity=GRAVITY,
        excitation_end=excitation_end, n_steps=n_steps,
        drop_limit=settings.collapse_drop * thickness,
        rest_energy=0.5 * total_mass * (settings.rest_speed**2) * GRAVITY * thickness,
        closed_gap=settings.closed_gap * thickness,
        rest_steps=max(1, int(round(windows[1] / h))),
        open_rest_steps=max(1, int(round(windows[2] / h))),
        moved_threshold=settings.moved_opening * thickness,
        energy_margin=settings.energy_margin * total_mass * GRAVITY * thickness,
        record_stride=int(record_every), tail_steps=tail_steps,
        crown_block=crown_block, crown_x=crown_r[0], crown_y=crown_r[1],
        coarse_factor=coarse, active_set_solves=settings.active_set_solves,
        skip_rest=1.0 if settings.skip_rest else 0.0)
    announce(RIGID_BLOCKS, solver.run)  # a first run compiles it: say so
    summary, records = solver.run(arrays["bodies"], arrays["contacts"], arrays["contact_bodies"],
                                  q0, v0, int(kind), params, times, values, packed,
                                  contact_unknowns(assembly, settings.unknowns, reorder))
    s = dict(zip(solver.SUMMARY_FIELDS, summary.tolist(), strict=True))
    status = int(s["status"])
    decided = bool(s["decided"]) and s["unconverged_steps"] == 0
    steps = int(s["steps"])
    outcome = BlockOutcome(
        status=STATUS_NAMES[status] if decided else Status.UNDECIDED,
        collapse_time=s["collapse_time"] if decided else math.nan,
        max_rotation=s["max_rotation"], max_crown_drop=s["max_crown_drop"],
        max_slip=s["max_slip"], max_opening=s["max_opening"], decided=decided,
        closed=bool(s["closed"]),
        decision_time=s["decision_time"] if decided else math.nan, steps=steps,
        mean_iterations=s["iterations"] / max(steps, 1), fallback_steps=int(s["fallbacks"]),
        unconverged_steps=int(s["unconverged_steps"]),
    )
    phases = {name: int(s[key]) for name, key in zip(
        PHASES, ("solved_still", "solved_pulse", "solved_free", "solved_window"), strict=True)}
    return assembly, settings, motion, outcome, records, order, phases


def block_outcome(structure, motion: GroundMotion | None, settings: BlockSettings | None = None,
                  *, initial=None, reorder: bool = True) -> BlockOutcome:
    """Outcome of the rigid-block model under a ground motion (no record; stops when decided).

    Parameters
    ----------
    structure : BlockArch or Assembly
        The structure (an arch is converted once by :func:`from_arch`, cached on the arch).
    motion : GroundMotion or None
        Horizontal ground acceleration [m/s^2]; None for a still ground.
    settings : BlockSettings, optional
        Settings of the analysis (default :class:`BlockSettings`).
    initial : (array (nb, 3), array (nb, 3)), optional
        Initial displacements ``(x, y, theta)`` [m, m, rad] and velocities [m/s, m/s, rad/s]
        of the blocks; default: at rest, undeformed.
    reorder : bool
        Number the joints in the solver by :func:`joint_order` (default) or in the assembly's
        own order (False, for comparison).

    Returns
    -------
    BlockOutcome
        The outcome (module docstring), decided within ``settle_time`` after the end of the
        motion or reported undecided (``Status.UNDECIDED``).

    Raises
    ------
    ValueError
        If ``structure``, ``motion`` or ``settings`` has the wrong type, ``initial`` is not
        two finite arrays of shape (nb, 3), the structure has more than :data:`MAX_BLOCKS`
        voussoirs or :data:`MAX_ASSEMBLY_BLOCKS`
        blocks, the time step cannot resolve the motion (:func:`check_time_step`), or the
        analysis would take more than :data:`archquake.defaults.MAX_BLOCK_STEPS` time steps.

    Examples
    --------
    A block 0.2 m x 1 m on a still ground stays at rest:

    >>> from archquake.rigid_blocks import rectangular_block
    >>> outcome = block_outcome(rectangular_block(0.2, 1.0), None,
    ...                         BlockSettings(time_step=0.002, settle_time=0.5))
    >>> outcome.status.label, outcome.decided
    ('rest', True)
    """
    return _run(structure, motion, settings, initial=initial, reorder=reorder)[3]


def outcome_with_phases(structure, motion: GroundMotion | None,
                        settings: BlockSettings | None = None) -> tuple[BlockOutcome, dict]:
    """:func:`block_outcome`, and where its steps went: the steps solved until the decision
    (a contact problem each; a coarse step counts one, a skipped step none) by phase
    (:data:`PHASES`).

    Parameters
    ----------
    structure, motion, settings
        As :func:`block_outcome`.

    Returns
    -------
    (BlockOutcome, dict of str to int)
        The outcome, and the steps solved [-] by the names of :data:`PHASES`: ``still``
        during the excitation before the structure first moves (its kinetic energy above that
        of rest), ``pulse`` during the excitation after that, ``free`` after the excitation
        while the structure moves, ``window`` after it in the window of rest that decides.
    """
    out = _run(structure, motion, settings)
    return out[3], out[6]


def simulate_blocks(structure, motion: GroundMotion | None,
                    settings: BlockSettings | None = None, *, initial=None,
                    record_every: int = 1, t_end: float | None = None,
                    tail: float = 0.5, reorder: bool = True) -> BlockHistory:
    """Time history of the rigid-block model under a ground motion.

    Parameters
    ----------
    structure : BlockArch or Assembly
        The structure.
    motion : GroundMotion or None
        Horizontal ground acceleration [m/s^2]; None for a still ground.
    settings : BlockSettings, optional
        Settings of the analysis (default :class:`BlockSettings`).
    initial : (array (nb, 3), array (nb, 3)), optional
        Initial displacements and velocities (see :func:`block_outcome`).
    record_every : int
        Record every ``record_every``-th step (>= 1).
    t_end : float, optional
        Run exactly to this time [s] (whatever the outcome); by default the run stops ``tail``
        seconds after the outcome is decided.
    tail : float
        Time recorded after the decision [s], >= 0 (to show the collapse or the rest).
    reorder : bool
        Number the joints in the solver by :func:`joint_order` (the default: the same motion,
        to round-off, at a cost that depends on the numbering); False keeps the assembly's own
        order (for comparison). The records are in the assembly's joint order either way.

    Returns
    -------
    BlockHistory
        The records (the first at t = 0) and the outcome.

    Raises
    ------
    ValueError
        As :func:`block_outcome`; also if ``record_every`` is not an integer >= 1, ``tail`` is
        not a finite time >= 0 or ``t_end`` not a finite time > 0.
    """
    if isinstance(record_every, bool) or int(record_every) != record_every or record_every < 1:
        raise ValueError(f"record_every must be an integer >= 1, got {record_every!r}")
    if not (math.isfinite(tail) and tail >= 0):
        raise ValueError(f"tail must be a finite time >= 0 [s], got {tail!r}")
    assembly, settings, motion, outcome, records, order, _ = _run(
        structure, motion, settings, initial=initial, record_every=int(record_every),
        t_end=t_end, tail=tail, reorder=reorder)
    energy, q, per_contact = records
    nr, nb, nj = energy.shape[0], assembly.n_blocks, assembly.n_joints
    q = q.reshape(nr, nb, 3)
    nc = 2 * nj
    position = np.empty(nj, dtype=np.int64)  # of the caller's joint j in the solver's order
    position[order] = np.arange(nj)
    gap = per_contact[:, :nc].reshape(nr, nj, 2)[:, position]
    slip = per_contact[:, nc:2 * nc].reshape(nr, nj, 2)[:, position]
    force = per_contact[:, 2 * nc:].reshape(nr, nj, 2, 2)[:, position]
    t = energy[:, 0]
    energy = energy[:, 1:]
    return BlockHistory(
        assembly=assembly, outcome=outcome, times=t, displacements=q[:, :, :2],
        rotations=q[:, :, 2], gaps=gap, offsets=slip,
        normal_forces=force[..., 0], tangential_forces=force[..., 1],
        kinetic_energy=energy[:, 0], potential_energy=energy[:, 1],
        dissipated_energy=energy[:, 2], input_work=energy[:, 3], motion_name=motion.name,
        settings=settings,
    )


__all__ = ["CONTACT_STEP_FRACTION", "GROUND", "MAX_ASSEMBLY_BLOCKS", "MAX_BLOCKS",
           "OPEN_REST_PERIODS", "PULSE_STEPS", "REST_PERIODS", "SETTLE_PERIODS", "BlockHistory",
           "BlockOutcome", "BlockSettings", "block_outcome", "check_size", "check_time_step",
           "contact_arrays", "contact_unknowns", "joint_half_bandwidth", "joint_order",
           "observation_windows",
           "resolved_settings", "simulate_blocks", "structure_time_step", "study_time_step",
           "time_step_for"]
