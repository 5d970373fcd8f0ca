"""Choices and defaults shared by the Python API, the command line and the report.

One place for each: the library's functions, the command line's options and the report read them
from here, so "the same" study has the same defaults wherever it is run. This module imports
nothing heavy, so the command line can build its options (and answer ``--help``) quickly.
"""

from __future__ import annotations

import functools
import math
import tomllib
from importlib import resources

SHAPES: tuple[str, ...] = ("circular", "pointed", "elliptical", "parabolic", "catenary",
                           "three-centred")
"""Names of the shapes of a centreline (:data:`archquake.geometry.CENTRELINES` holds their
builders, in this order)."""

RING_BONDS: tuple[str, ...] = ("aligned", "staggered")
"""The bonds of the rings of a brick arch (:func:`archquake.geometry.multi_ring`): every ring's
joints on the same radial lines, or offset by half a voussoir from the ring inside it."""

VOUSSOIR_FACES: tuple[str, ...] = ("curved", "flat")
"""Faces of a voussoir of a shaped arch: ``"curved"`` (the intrados and extrados offset curves)
or ``"flat"`` (chords between the ends of its joints)."""

ANALYTIC_GROUND_MOTIONS: tuple[str, ...] = (
    "oppenheim", "rectangular", "sine", "harmonic", "ricker", "ricker-antisymmetric",
    "cycloidal-a", "cycloidal-b", "cycloidal-c", "mavroeidis-papageorgiou",
)
"""Names of the analytic ground motions (:data:`archquake.ground_motion.GROUND_MOTIONS`), whose
factory takes ``(amplitude [m/s^2], time scale [s])``."""

DEFAULT_MOTION = "oppenheim"
"""Ground motion of an analysis of one arch when none is named: Oppenheim's pulse [paper,
Sect. 5.3.1]."""

DEFAULT_PULSE = (-1.0, 0.27)
"""``(amplitude [g], time scale [s])`` of the pulse of an analysis of one arch when none is
given (``archquake simulate``, ``archquake rigid-blocks``): the paper's Fig. 15."""


def oppenheim_dimensions() -> dict:
    """Oppenheim's arch [paper, Sect. 2], read from the paper's values (``[oppenheim]`` of
    ``archquake/data/paper_values.toml``) without importing anything heavy.

    Returns
    -------
    dict
        ``radius`` [m], ``embrace`` [rad], ``thickness`` [m] and ``voussoirs``: the keyword
        arguments of :func:`archquake.geometry.circular_arch` (R = 10 m, alpha = 157.5 deg,
        t = 1.5 m, n = 7); a new dict on every call.
    """
    return dict(_oppenheim())


def circular_defaults() -> dict:
    """Oppenheim's arch as a structure's description gives a circular arch by default
    (:class:`archquake.geometry.StructureSpec`): ``radius`` [m], ``embrace`` [deg],
    ``thickness`` [m] and ``voussoirs``; a new dict on every call.

    Examples
    --------
    >>> circular_defaults()
    {'radius': 10.0, 'embrace': 157.5, 'thickness': 1.5, 'voussoirs': 7}
    """
    arch = oppenheim_dimensions()
    return {"radius": arch["radius"], "embrace": math.degrees(arch["embrace"]),
            "thickness": arch["thickness"], "voussoirs": arch["voussoirs"]}


@functools.cache
def _oppenheim() -> tuple:
    text = resources.files("archquake").joinpath("data", "paper_values.toml").read_text("utf-8")
    arch = tomllib.loads(text)["oppenheim"]
    return (("radius", float(arch["radius"])), ("embrace", math.radians(arch["embrace_deg"])),
            ("thickness", float(arch["thickness"])), ("voussoirs", int(arch["voussoirs"])))


LIMIT_METHODS: tuple[str, ...] = ("static", "kinematic")
"""Limit-analysis methods: the static linear program (HiGHS) and the kinematic enumeration of
mechanisms. They give the same load multipliers (to ~1e-14) and hinges."""

DEFAULT_LIMIT_METHOD = "static"
"""Limit-analysis method of a single arch."""

DEFAULT_SAMPLE_LIMIT_METHOD = "kinematic"
"""Limit-analysis method of a sample of arches (the CDF of k~): the same numbers, faster."""

DEFAULT_RESTITUTION = "computed"
"""Restitution model of every analysis unless one is chosen: the coefficients computed from the
momentum balance of the impact of this arch
(:func:`archquake.fourlink.impact.computed_restitution`)."""

DEFAULT_SEED = 0
"""Root seed of irregular arches and samples."""

REPORT_SEED = 2024
"""Root seed of the irregular arches of the paper's reproduction (``archquake reproduce``)."""

DEFAULT_IM = "pga"
"""Intensity measure of the stripes of a record-based fragility study."""

DEFAULT_INTENSITY_MEASURES = "pga,pgv,pgd,arias,d5-95"
"""The intensity measures ``archquake records`` computes unless told."""

DEFAULT_EPSILON = 0.10
"""Tolerance epsilon of the irregular draw of a study [paper, eq. (1) and Sect. 5.3.3]."""

DEFAULT_BACKEND = "serial"
"""How a study runs unless told: in this process (``"processes"`` with ``workers``, ``"dask"``
with a scheduler). Starting worker processes costs about 1.5 s each, more than the paper's
whole study."""

DEFAULT_RESOLUTION_G = 1e-3
"""Bisection width of every boundary of a failure domain [g]."""

DOMAIN_DURATIONS = (0.1, 1.0, 0.025)
"""``(start, stop, step)`` [s] of the pulse durations of a failure domain (stop included)."""

DOMAIN_AMPLITUDES_G = (0.05, 1.5, 0.01)
"""``(start, stop, step)`` [g] of the scan of a failure domain (extended up to
:data:`DEFAULT_EXTEND_TO_G` where needed)."""

MAX_PULSE_DURATION = 60.0
"""Longest pulse duration t_p of a failure domain, a comparison or a fragility study [s]: the
pulses of near-fault records last a few seconds (the paper's reach 1 s); a duration of minutes
is a unit mistake, and the rigid-block model would take millions of steps for it."""

STUDY_DURATIONS = (0.4, 0.5, 0.6, 0.7)
"""Pulse durations t_p [s] of a fragility study [paper, Sect. 5.3.3]."""

STUDY_AMPLITUDES_G = (0.20, 1.00, 0.01)
"""``(start, stop, step)`` [g] of the amplitudes of a fragility study (the paper's 0.01 g steps;
the range is not stated in the paper)."""

STUDY_SAMPLE_SIZE = 40
"""Number h of irregular arches analysed dynamically in a fragility study [paper, Sect. 5.3.3]."""

LIMIT_SAMPLE_SIZE = 1000
"""Number s of irregular arches of the limit-analysis CDF of k~ [paper, Sect. 5.3.3]."""

DEFAULT_EXTEND_TO_G = 20.0
"""Cap [g] of the extension of a failure-domain scan beyond its grid: the scan goes on until the
collapse in the first half cycle is found, at most up to this amplitude. Oppenheim's arch
collapses in the first half cycle from 12.1 g at t_p = 0.1 s and from 3.07 g at t_p = 0.2 s."""

# --- bounds on the size of a computation: larger requests are refused with an error that names
# them, instead of running for hours or exhausting the memory

MIN_RESOLUTION_G = 1e-9
"""Finest bisection tolerance of a failure-domain boundary [g]. The analyses themselves are
accurate to about 1e-11 (relative), so finer boundaries carry no information; below the spacing
of floating-point numbers the bisection could never end."""

MAX_GRID_POINTS = 1_000_000
"""Most (duration, amplitude) points of one arch's grid: a failure-domain scan (with its
extension) or the grid of a fragility study (about a minute of analyses per arch)."""

MAX_SAMPLES = 100_000
"""Most irregular arches h of the dynamic part of a fragility study (the paper: 40)."""

MAX_LIMIT_SAMPLES = 1_000_000
"""Most irregular arches s of the limit-analysis sample of a fragility study (the paper: 1000)."""

MAX_STUDY_ANALYSES = 100_000_000
"""Most dynamic analyses (2 directions x h arches x durations x amplitudes) of one fragility
study: some CPU-hours (a cluster's study); more is several studies with different seeds."""

MAX_ACCELERATION_G = 1000.0
"""Largest ground acceleration accepted [g], in magnitude: far beyond any earthquake and fifty
times the largest amplitude a failure domain scans by default; at 1e150 g the step sizes of the
integrator underflow."""

PLAUSIBLE_PEAK_G = 5.0
"""Largest peak acceleration of a record [g] read without a warning: above it (no record on
file comes near it; the largest recorded are about 4 g) the values are likely in cm/s^2 or m/s^2,
not g."""

RECORD_TIME_STEP_RANGE = (1e-6, 1.0)
"""Accepted time steps between the samples of a record [s]: accelerographs sample at 50 to
1000 Hz (0.02 to 0.001 s); a step outside this range is a unit or header mistake."""

MAX_RECORD_DURATION = 3600.0
"""Longest record accepted [s]: an hour, far beyond any earthquake's shaking (some minutes)."""

MAX_RECORD_FILE_BYTES = 256 * 2**20
"""Largest record file read [bytes]: a record of an hour sampled at 1000 Hz is about 60 MB of
text."""

MAX_CYCLES = 10_000
"""Most cycles of a harmonic ground motion: each costs the integrator some tens of steps, and
one analysis is limited to :data:`archquake.fourlink.engine.DEFAULT_MAX_STEPS` steps."""

MAX_RECORD_SAMPLES = 1_000_000
"""Most samples of a generated (stochastic) ground motion: every sample is a breakpoint the
integrator does not step across, and one analysis is limited to
:data:`archquake.fourlink.engine.DEFAULT_MAX_STEPS` steps."""

MAX_BLOCK_STEPS = 5_000_000
"""Most time steps of one rigid-block analysis (some minutes for the paper's arch)."""

# --- the rigid-block model and its comparison with the four-link model

DEFAULT_FRICTION = 0.8
"""Coulomb friction coefficient of the joints of the rigid-block model [-]."""

DEFAULT_TIME_STEP = 1e-3
"""Time step of the rigid-block model for a structure of :data:`REFERENCE_THICKNESS` [s]; any
other structure's default step is scaled from it
(:func:`archquake.rigid_blocks.dynamics.structure_time_step`)."""

REST_MARGIN = 1e-12
"""Relative margin [-] below the activation acceleration within which an analysis of a scaled
record is integrated rather than declared at rest (round-off of the interpolation between
samples; :meth:`archquake.fourlink.FourLinkModel.scaled_record_outcomes`)."""

DEFAULT_COARSE_FACTOR = 2
"""Steps of the time step that the rigid-block model takes as one while no contact starts or
stops carrying an impulse (:class:`archquake.rigid_blocks.BlockSettings`; every impact,
lift-off and landing is taken at the time step) [-]: half the contact problems of a rocking
arch, the failure accelerations of Oppenheim's arch at t_p = 0.3-0.7 s within 0.0008 g of
those at a quarter of the step (``benchmarks/rigid_block_time_step.py``)."""

MAX_COARSE_FACTOR = 1000
"""Most steps of the time step taken as one by the rigid-block model [-]: a coarse step is never
longer than the motion allows a step to be (0.02 sqrt(t/g), 7.8 default steps of any arch), so
a larger factor means nothing unless the time step is over a hundred times the default's
finer; a typo like ``--coarse-factor 20000`` is refused rather than silently clipped."""

REFERENCE_THICKNESS = 1.5
"""Thickness at which :data:`DEFAULT_TIME_STEP` resolves the rigid-block model (Oppenheim's arch:
its failure accelerations within 0.001 g of those at a quarter of the step for t_p = 0.4-0.7 s,
``benchmarks/rigid_block_time_step.py``) [m]."""

COMPARE_DURATIONS = (0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 1.0)
"""Pulse durations t_p [s] of a comparison of the two models (``archquake compare``)."""

COMPARE_AMPLITUDES_G = (0.3, 3.0, 0.1)
"""``(start, stop, step)`` [g] of the amplitude scan of a comparison, the same for both models:
from below the activation of Oppenheim's arch (k = 0.37) to 3 g (its collapse in the first half
cycle at t_p = 0.2 s is at 3.07 g)."""

COMPARE_RESOLUTION_G = 5e-3
"""Bisection width of every boundary of a comparison [g], the same for both models (a
rigid-block analysis costs about 100 four-link ones)."""

MIN_COMPARE_RESOLUTION_G = 1e-6
"""Finest bisection width of a comparison on the command line [g]: a rigid-block boundary is
decided by time steps of 1 ms, finer widths only cost analyses."""

COMPARE_RESTITUTIONS = ("computed", "link", "paper", "measured")
"""Restitution models of the four-link model in a comparison (names of
:data:`archquake.fourlink.impact.RESTITUTION_MODELS`)."""

AGREEMENT_BAND = 0.05
"""Relative difference [-] of the two models' failure accelerations called agreement (both
reports)."""

MAX_BLOCK_GRID_POINTS = 10_000
"""Most (duration, amplitude) points of a rigid-block failure curve's scan that its search
analyses whatever the outcomes (the coarse scan of a coarse search, and its extension): some
tens of minutes of analyses on two cores (a point costs 10-100 ms)."""

# --- the two models, and how a study searches a grid (archquake.studies.strategies)

MODELS = ("four-link", "rigid-blocks")
"""The dynamic models (:mod:`archquake.models`)."""

DEFAULT_MODEL = "four-link"
"""The model a study runs unless told otherwise: the paper's."""

DEFAULT_LEVEL_STRIDE = 4
"""Levels between the coarse points of a searched line of stripes of a record-based study [-]
(20 levels: 5 coarse points)."""

SEARCHES = ("exhaustive", "bisection", "screened")
"""The search strategies of a grid (:mod:`archquake.studies.strategies`)."""

DEFAULT_STRIDE = 8
"""Grid steps between two points of the coarse scan of ``bisection`` and ``screened`` [-]: on
the paper's grid of 0.01 g, a coarse scan every 0.08 g."""

DEFAULT_SEARCH = {"four-link": "exhaustive", "rigid-blocks": "screened"}
"""Search strategy of a grid per model: the four-link model analyses a whole grid in one compiled
call (about 15 µs a point), so every point is analysed; a rigid-block analysis costs 3-10 ms
under a pulse (0.2 ms at rest), so the grid is scanned coarsely, every change of outcome
bisected, and the stretches where its outcome is not smooth in the amplitude analysed point by
point (``"screened"``, :mod:`archquake.studies.strategies`: the outcomes of the exhaustive grid
in every case compared). Under records it analyses nearly every level (only rest is smooth
there) and costs more than ``"exhaustive"``, which the record-based study therefore runs
(:data:`RECORD_STUDY_SEARCH`). ``"bisection"`` is faster still, and misses the
isolated recoveries of the rigid-block model among its late collapses."""

RECORD_STUDY_SEARCH = {"four-link": "exhaustive", "rigid-blocks": "exhaustive"}
"""Search strategy of the record-based study (``record-fragility``) per model: every level.
Under a record only rest is smooth in the level, and rest is the cheapest analysis, so
``"screened"`` analyses nearly every level and adds its bisections: 34 s against 32 s exhaustive
(``python benchmarks/fragility_command.py --study records``). Under pulses it pays, a little
(:data:`DEFAULT_SEARCH`): it infers rest and the collapses decided during the pulse, 0.9 and
3.8 ms an analysis against 5.3 ms for a collapse after the pulse and 7.4 ms for a recovery,
which it must analyse (``python benchmarks/rigid_block_fragility.py``, a busy machine); on the
paper's study 80-95 % of the exhaustive grid's analysis time (``--study paper``), and no search
that reproduces the exhaustive grid can do much better, since the points it may infer hold
about 28 % of that time."""

# --- fill over an arch (archquake.geometry.fill)

FILL_INERTIA_MODELS = ("none", "centroid", "extrados")
"""Where the fill's horizontal inertia force acts (:mod:`archquake.geometry.fill`): nowhere,
through each column's centroid, or on the extrados below it."""

DEFAULT_FILL_INERTIA = "centroid"
"""The fill moves with its voussoir: the one model the dynamic models share
(:mod:`archquake.geometry.fill`)."""

# --- records compatible with a site's spectrum (archquake.site.compatible_records)

COMPATIBILITY_RULES = ("ntc2018", "ec8")
"""Rules of spectrum compatibility: NTC 2018 §3.2.3.6 (the mean within -10 %/+30 % of the
target) and EN 1998-1 §3.2.3.1.2(4) (not below 90 %, the mean PGA not below the site's)."""

DEFAULT_RECORD_COUNT = 7
"""Records of a selection unless told [-]: seven, so that the effects are their mean (NTC 2018
§7.3.5; with three to six, the most unfavourable one)."""

DEFAULT_PERIOD_RANGE = (0.15, 2.0)
"""Period range of the compatibility check unless told [s]: the code's 0.15-2.0 s (a rocking
arch has no elastic period T to widen it to 2T; the user may)."""

DEFAULT_FACTOR_RANGE = (0.5, 4.0)
"""Range of the scale factor of any record unless told [-]: a record scaled by more than about
four, or shrunk by more than half, is a different earthquake; the code sets no limit, and the
user may widen it."""
