"""Write the synthetic test records ``decaying_sine.csv``, ``decaying_sine.AT2`` and
``decaying_sine.ASC`` (ESM format).

All sample the same kind of analytic accelerogram (not a real record)::

    a(t) = 0.4 exp(-t / 0.5) sin(2 pi t / 0.25)    [g]      (CSV, AT2)
    a(t) = 300 exp(-t / 0.5) sin(2 pi t / 0.25)    [cm/s^2] (ESM)

The ESM file has the 64-line header of the Engineering Strong Motion database's ASCII files
(header format DYNA 1.2), filled with made-up event and station values.

``tests/ground_motion/test_records.py`` holds its own copy of the formula and compares the
files against it.
Run ``python tests/data/make_records.py`` to rewrite the files.
"""

from pathlib import Path

import numpy as np

HERE = Path(__file__).parent


def acceleration_g(t):
    return 0.4 * np.exp(-t / 0.5) * np.sin(2 * np.pi * t / 0.25)


def write_csv(path: Path) -> None:
    t = 0.01 * np.arange(201)
    lines = [
        "# synthetic accelerogram: a(t) = 0.4 exp(-t/0.5) sin(2 pi t/0.25) [g]",
        "# columns: time [s], ground acceleration [g]",
        "time_s,acc_g",
    ]
    lines += [f"{ti:.2f},{ai:.10g}" for ti, ai in zip(t, acceleration_g(t), strict=True)]
    path.write_text("\n".join(lines) + "\n")


def write_at2(path: Path) -> None:
    npts, dt = 300, 0.005
    a = acceleration_g(dt * np.arange(npts))
    lines = [
        "PEER NGA STRONG MOTION DATABASE RECORD",
        "SYNTHETIC DECAYING SINE 0.4 EXP(-T/0.5) SIN(2 PI T/0.25), ARCHQUAKE TEST DATA",
        "ACCELERATION TIME SERIES IN UNITS OF G",
        f"NPTS= {npts:5d}, DT=   .0050 SEC",
    ]
    for start in range(0, npts, 5):
        lines.append("".join(f"{x:15.7E}" for x in a[start:start + 5]))
    path.write_text("\n".join(lines) + "\n")


ESM_HEADER = """\
EVENT_NAME: SYNTHETIC DECAYING SINE
EVENT_ID: XX-2000-0001
EVENT_DATE_YYYYMMDD: 20000101
EVENT_TIME_HHMMSS: 120000
EVENT_LATITUDE_DEGREE: 42.0000
EVENT_LONGITUDE_DEGREE: 13.0000
EVENT_DEPTH_KM: 10.0
HYPOCENTER_REFERENCE: ARCHQUAKE TEST DATA
MAGNITUDE_W: 6.0
MAGNITUDE_W_REFERENCE: ARCHQUAKE TEST DATA
MAGNITUDE_L:
MAGNITUDE_L_REFERENCE:
FOCAL_MECHANISM: Normal faulting
NETWORK: XX
STATION_CODE: TEST
STATION_NAME: Test station
STATION_LATITUDE_DEGREE: 42.100000
STATION_LONGITUDE_DEGREE: 13.100000
STATION_ELEVATION_M: 100
LOCATION:
SENSOR_DEPTH_M:
VS30_M/S: 800
SITE_CLASSIFICATION_EC8: A
MORPHOLOGIC_CLASSIFICATION:
EPICENTRAL_DISTANCE_KM: 13.6
EARTHQUAKE_BACKAZIMUTH_DEGREE: 212.0
DATE_TIME_FIRST_SAMPLE_YYYYMMDD_HHMMSS: 20000101_120002.000
DATE_TIME_FIRST_SAMPLE_PRECISION: milliseconds
SAMPLING_INTERVAL_S: {dt:.6f}
NDATA: {npts}
DURATION_S: {duration:.3f}
STREAM: HNE
UNITS: cm/s^2
INSTRUMENT: HN
INSTRUMENT_ANALOG/DIGITAL: D
INSTRUMENTAL_FREQUENCY_HZ:
INSTRUMENTAL_DAMPING:
FULL_SCALE_G:
N_BIT_DIGITAL_CONVERTER:
PGA_CM/S^2: {pga:.6f}
TIME_PGA_S: {time_pga:.6f}
BASELINE_CORRECTION: BASELINE REMOVED
FILTER_TYPE: BUTTERWORTH
FILTER_ORDER: 2
LOW_CUT_FREQUENCY_HZ: 0.100
HIGH_CUT_FREQUENCY_HZ: 40.000
LATE/NORMAL_TRIGGERED: NT
DATABASE_VERSION: ESM
HEADER_FORMAT: DYNA 1.2
DATA_TYPE: ACCELERATION
PROCESSING: synthetic
DATA_TIMESTAMP_YYYYMMDD_HHMMSS: 20000101_130000.000
DATA_LICENSE: CC BY 4.0
DATA_CITATION: archquake test data
DATA_CREATOR: archquake
ORIGINAL_DATA_MEDIATOR_CITATION:
ORIGINAL_DATA_MEDIATOR:
ORIGINAL_DATA_CREATOR_CITATION:
ORIGINAL_DATA_CREATOR:
USER1:
USER2:
USER3:
USER4:
USER5:
"""


def esm_acceleration_cm_s2(t):
    return 300.0 * np.exp(-t / 0.5) * np.sin(2 * np.pi * t / 0.25)


def write_esm(path: Path) -> None:
    npts, dt = 250, 0.008
    a = esm_acceleration_cm_s2(dt * np.arange(npts))
    i = int(np.argmax(np.abs(a)))
    header = ESM_HEADER.format(dt=dt, npts=npts, duration=(npts - 1) * dt, pga=a[i],
                               time_pga=i * dt)
    assert len(header.splitlines()) == 64
    path.write_text(header + "".join(f"{x:.6e}\n" for x in a))


if __name__ == "__main__":
    write_csv(HERE / "decaying_sine.csv")
    write_at2(HERE / "decaying_sine.AT2")
    write_esm(HERE / "decaying_sine.ASC")
