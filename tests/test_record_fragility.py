"""Record-based fragility (multiple-stripe analysis): stripes, fits, bands, incremental view,
execution and the command line, each against an independent value."""

import json
import math

import numpy as np
import pandas as pd
import pytest
from scipy import special, stats

from archquake import oppenheim
from archquake.cli import main
from archquake.fourlink.impact import restitution
from archquake.fourlink.mechanism import mechanisms
from archquake.fourlink.time_history import simulate
from archquake.ground_motion import read_suite, scale_to_im, stochastic_suite
from archquake.studies.fragility import LognormalFragility, fit_lognormal
from archquake.studies.record_fragility import (
    NOMINAL_ARCH,
    RecordFragilitySettings,
    RecordSuite,
    bootstrap_lognormal,
    common_dispersion_fit,
    load_record_fragility,
    probit_newton,
    record_fragility_result,
    record_outcomes,
    run_record_fragility,
    separated,
)

LEVELS = "0.3:1.9:0.2"  # pga [g]: below activation (k = 0.37) up to most records collapsing
SUITE = {"significant_duration": 4.0, "midpoint_time": 3.0, "filter_frequency": 1.0,
         "filter_frequency_rate": 0.0, "duration": 6.0}


@pytest.fixture(scope="module")
def suite_dir(tmp_path_factory):
    """Four 6-s synthetic accelerograms (1 Hz) written as two-column CSV files in g."""
    folder = tmp_path_factory.mktemp("suite")
    for motion in stochastic_suite(4, seed=0, **SUITE):
        np.savetxt(folder / f"{motion.name}.csv",
                   np.column_stack([motion.times, motion.values / 9.81]), delimiter=",",
                   header="time_s,acc_g", comments="", fmt="%.10g")
    return folder


@pytest.fixture(scope="module")
def nominal_pair():
    """Mech-l, Mech-r and the computed restitution pair of Oppenheim's arch, built here."""
    pair = mechanisms(oppenheim())
    return pair, restitution("computed", *pair)


def _collapses(pair, c, motion):
    return simulate(pair, motion, c, record=False).status.label == "collapse"


def test_nominal_arch_fraction_equals_records_collapsing_in_simulate(suite_dir, nominal_pair,
                                                                     tmp_path, capsys):
    """``--epsilon 0 --samples 1`` is the nominal arch alone: at every stripe, P is the
    fraction of records that collapse it (either polarity) in simulate()."""
    argv = ["fragility", "--records", str(suite_dir), "--im", "pga", "--levels", LEVELS,
            "--epsilon", "0", "--samples", "1", "--out", str(tmp_path / "out"), "--json",
            "--no-progress"]
    assert main(argv) == 0
    summary = json.loads(capsys.readouterr().out)
    levels = np.round(np.arange(0.3, 1.91, 0.2), 10)
    assert summary["im"] == "pga" and summary["levels"] == pytest.approx(levels, abs=1e-12)
    pair, c = nominal_pair
    records = read_suite(suite_dir)
    expected = []
    for x in levels:
        failed = [_collapses(pair, c, scale_to_im(m, "pga", x))
                  or _collapses(pair, c, scale_to_im(m.reversed(), "pga", x)) for m in records]
        expected.append(np.mean(failed))
    assert summary["probability"] == pytest.approx(expected, abs=0)
    assert summary["nominal"]["probability"] == pytest.approx(expected, abs=0)
    assert 0 < min(e for e in expected if e > 0) and max(expected) > 0.5  # a real test
    assert set(summary["lognormal"]) >= {"median", "dispersion"}
    assert summary["variability"]["geometric"] == 0.0


def test_stripes_of_arias_intensity_scale_records_as_scale_to_im(nominal_pair):
    """Arias intensity scales with the square of the factor: the study's outcomes are those of
    simulate() of scale_to_im(record, "arias", level), record by record."""
    pair, c = nominal_pair
    suite = RecordSuite.from_stochastic(2, seed=4, **SUITE)
    settings = RecordFragilitySettings(suite=suite, levels=(0.05, 0.2, 0.6), im="arias",
                                       sample_size=1, epsilon=0.0, restitution="computed")
    result = run_record_fragility(settings, backend="serial", progress=False)
    nominal = result.table[result.table["arch"] == NOMINAL_ARCH]
    for row, motion in zip(nominal.itertuples(), [m for m in suite.motions() for _ in range(6)],
                           strict=True):
        oriented = motion if row.polarity == 1 else motion.reversed()
        out = simulate(pair, scale_to_im(oriented, "arias", row.level), c, record=False)
        assert (row.status, row.half_cycle) == (int(out.status), out.half_cycle)


def test_analyses_below_activation_are_exact_rests():
    """Skipped analyses (no sample reaches the activation acceleration) are what the engine
    decides when it integrates them, including factors a hair either side of the threshold."""
    from archquake import ArchDynamics, oppenheim
    from archquake.fourlink.engine import outcomes_grid

    dynamics = ArchDynamics.from_arch(oppenheim(), "computed")
    tables, c = dynamics.tables, dynamics.restitution
    motion = stochastic_suite(1, seed=2, **SUITE)[0]
    k = tables[1].activation_g * 9.81  # Mech-r opens when xg'' > k_r g
    f_edge = k / np.max(motion.values)
    factors = np.array([0.2, 0.5, 0.9, 1 - 1e-9, 1 - 1e-13, 1 + 1e-13, 1.2, 3.0]) * f_edge
    signed = np.concatenate([factors, -factors])
    out = record_outcomes(dynamics, motion, signed)
    reference = outcomes_grid(*tables, *c, 1.0, signed, motion)
    for name in ("status", "half_cycle", "impacts", "max_phi"):
        assert np.array_equal(out[name], reference[name]), name
    assert np.sum(~out["integrated"]) >= 6 and np.all(out["status"][~out["integrated"]] == 0)


# --------------------------------------------------------------------------------------------
# fits
# --------------------------------------------------------------------------------------------


def _grid_mle(levels, trials, failures, medians, dispersions):
    """Brute force: the likelihood on a (median, dispersion) grid, its best node."""
    x = np.log(np.asarray(levels, float))
    m, b = np.meshgrid(np.log(medians), dispersions, indexing="ij")
    s = (x[None, None, :] - m[..., None]) / b[..., None]
    n = np.broadcast_to(trials, x.shape)
    ll = (failures * stats.norm.logcdf(s) + (n - failures) * stats.norm.logsf(s)).sum(-1)
    i, j = np.unravel_index(np.argmax(ll), ll.shape)
    return medians[i], dispersions[j]


def test_lognormal_fits_are_the_maximum_of_a_likelihood_grid():
    rng = np.random.default_rng(11)
    levels = np.linspace(0.2, 1.6, 15)
    trials = 60
    failures = rng.binomial(trials, stats.norm.cdf(np.log(levels / 0.7) / 0.45))
    medians, dispersions = np.linspace(0.5, 0.9, 401), np.linspace(0.25, 0.7, 451)
    grid_median, grid_beta = _grid_mle(levels, trials, failures, medians, dispersions)
    fit = fit_lognormal(levels, trials, failures)  # the study's fit
    assert fit.median == pytest.approx(grid_median, abs=1e-3)
    assert fit.dispersion == pytest.approx(grid_beta, abs=1e-3)
    a, b = probit_newton(np.log(levels), trials, failures[None, :])  # the bootstrap's refit
    assert 1 / b[0] == pytest.approx(fit.dispersion, rel=1e-7)
    assert math.exp(-a[0] / b[0]) == pytest.approx(fit.median, rel=1e-7)


def test_separated_stripes_have_no_fit():
    levels = [0.2, 0.4, 0.6, 0.8]
    assert separated(levels, 10, [0, 0, 10, 10])  # a step
    assert separated(levels, 10, [0, 0, 4, 10])  # quasi-complete: one mixed stripe
    assert separated(levels, 10, [0, 0, 0, 0]) and separated(levels, 10, [10] * 4)
    assert not separated(levels, 10, [0, 3, 4, 10])
    assert not separated(levels, 10, [0, 10, 0, 10])  # non-monotone: a finite maximum exists


def test_geometric_dispersion_is_the_maximum_of_a_profile_likelihood_grid():
    """Two records, one median each and a common dispersion: brute force over a grid of all
    three parameters (separable: for each dispersion, the best median of each record)."""
    rng = np.random.default_rng(3)
    levels = np.linspace(0.3, 2.0, 12)
    truth = [(0.7, 0.3), (1.2, 0.3)]
    failures = np.array([rng.binomial(40, stats.norm.cdf(np.log(levels / m) / b))
                         for m, b in truth])
    fit = common_dispersion_fit(levels, 40, failures)
    medians, dispersions = np.geomspace(0.4, 2.0, 801), np.linspace(0.1, 0.6, 251)
    x = np.log(levels)
    s = (x[None, None, :] - np.log(medians)[:, None, None]) / dispersions[None, :, None]
    log_p, log_q = special.log_ndtr(s), special.log_ndtr(-s)
    best = 0.0
    for z in failures:
        ll = (z * log_p + (40 - z) * log_q).sum(-1)
        best = best + ll.max(axis=0)  # best median of this record, for every dispersion
    assert fit.dispersion == pytest.approx(dispersions[np.argmax(best)], abs=2e-3)
    for r, z in enumerate(failures):
        beta = dispersions[np.argmax(best)]
        sr = (x[None, :] - np.log(medians)[:, None]) / beta
        ll = (z * stats.norm.logcdf(sr) + (40 - z) * stats.norm.logsf(sr)).sum(-1)
        assert fit.medians[r] == pytest.approx(medians[np.argmax(ll)], rel=5e-3)


def test_geometric_dispersion_recovers_the_spread_of_simulated_arches():
    """Arches whose collapse level is lognormal around a median per record: the common
    dispersion of the fit is that spread."""
    rng = np.random.default_rng(8)
    levels = np.geomspace(0.3, 3.0, 20)
    record_medians = np.array([0.6, 0.9, 1.3, 1.8])
    capacity = record_medians[None, :] * np.exp(0.25 * rng.standard_normal((2000, 4)))
    failed = levels[None, None, :] >= capacity[..., None]
    fit = common_dispersion_fit(levels, 2000, failed.sum(axis=0))
    assert fit.dispersion == pytest.approx(0.25, rel=0.05)
    assert fit.medians == pytest.approx(record_medians, rel=0.03)


def _synthetic_failed(arches, records, rng):
    """Collapse of (arch, record) pairs: the collapse level is lognormal (median 0.8 g,
    dispersion 0.3 from the record, 0.2 from the arch)."""
    levels = np.geomspace(0.3, 2.0, 12)
    capacity = 0.8 * np.exp(0.3 * rng.standard_normal(records)[None, :]
                            + 0.2 * rng.standard_normal((arches, records)))
    return levels, levels[None, None, :] >= capacity[..., None]


def test_bootstrap_band_holds_the_fit_and_narrows_with_more_data():
    widths = []
    for arches, records in ((8, 8), (40, 40)):
        levels, failed = _synthetic_failed(arches, records, np.random.default_rng(1))
        fit = fit_lognormal(levels, arches * records, failed.sum(axis=(0, 1)))
        band = bootstrap_lognormal(levels, failed, fit, resamples=400, confidence=0.9,
                                   rng=np.random.default_rng(2))
        curve = fit(band.x)
        assert np.all(band.lower <= curve + 1e-9) and np.all(curve <= band.upper + 1e-9)
        lo, hi = band.median_interval
        assert lo <= fit.median <= hi
        widths.append((np.mean(band.upper - band.lower), hi - lo))
        again = bootstrap_lognormal(levels, failed, fit, resamples=400, confidence=0.9,
                                    rng=np.random.default_rng(2))
        assert np.array_equal(again.lower, band.lower)  # seeded
    # 5 times the records and arches: about half the width (the records dominate)
    assert widths[1][0] < 0.7 * widths[0][0] and widths[1][1] < 0.7 * widths[0][1]


def test_bootstrap_counts_are_those_of_the_resampled_pairs():
    """The counts of a resample are rebuilt from the resampled arches and records: with one
    resample drawn by hand, the refit equals fit_lognormal of those counts."""
    levels, failed = _synthetic_failed(6, 5, np.random.default_rng(4))
    fit = fit_lognormal(levels, 30, failed.sum(axis=(0, 1)))
    rng = np.random.default_rng(9)
    band = bootstrap_lognormal(levels, failed, fit, resamples=10, confidence=0.9, rng=rng,
                               x=np.array([fit.median]))
    rng = np.random.default_rng(9)
    w_arch = rng.multinomial(6, np.full(6, 1 / 6), size=10)
    w_rec = rng.multinomial(5, np.full(5, 1 / 5), size=10)
    refits = []
    for b in range(10):
        arches = np.repeat(np.arange(6), w_arch[b])
        records = np.repeat(np.arange(5), w_rec[b])
        z = failed[arches][:, records].sum(axis=(0, 1))
        if not separated(levels, 30, z):
            refits.append(fit_lognormal(levels, 30, z)(fit.median))
    lo, hi = np.percentile(refits, [5, 95])
    assert band.lower[0] == pytest.approx(lo, abs=1e-6)
    assert band.upper[0] == pytest.approx(hi, abs=1e-6)


# --------------------------------------------------------------------------------------------
# the study: table, views, execution
# --------------------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def small_study(suite_dir, tmp_path_factory):
    settings = RecordFragilitySettings(suite=RecordSuite.from_paths(suite_dir),
                                       levels=(0.3, 0.6, 0.9, 1.2, 1.5, 1.8), sample_size=3,
                                       bootstrap=100)
    out = tmp_path_factory.mktemp("study") / "out"
    return run_record_fragility(settings, out, backend="serial", progress=False), out


def test_table_has_one_row_per_arch_record_level_polarity(small_study):
    result, _ = small_study
    t = result.table
    assert len(t) == 4 * 4 * 6 * 2
    assert list(t["arch"].unique()) == [0, 1, 2, NOMINAL_ARCH]
    counts = t.groupby(["arch", "record", "level", "polarity"]).size()
    assert counts.eq(1).all()
    # either polarity: the stripe counts rebuilt from the rows
    pairs = t[t["arch"] >= 0].groupby(["arch", "record", "level"])["status"].apply(
        lambda s: bool((s == 2).any()))
    expected = pairs.groupby(level="level").mean()
    assert result.probability == pytest.approx(expected.to_numpy(), abs=0)


def test_incremental_view_from_the_rows(small_study):
    result, _ = small_study
    t = result.table
    view = result.incremental().set_index(["arch", "record"])
    for (arch, record), rows in t.groupby(["arch", "record"]):
        failed = rows.groupby("level")["status"].apply(lambda s: bool((s == 2).any()))
        levels = failed.index.to_numpy()
        hits = levels[failed.to_numpy()]
        row = view.loc[(arch, record)]
        if hits.size == 0:
            assert math.isnan(row["first_collapse"]) and row["recoveries_above"] == 0
            continue
        assert row["first_collapse"] == hits[0]
        survivors = [v for v, f in zip(levels, failed, strict=True) if v > hits[0] and not f]
        assert row["recoveries_above"] == len(survivors)
        assert row["recovery_levels"] == " ".join(f"{v:g}" for v in survivors)


def test_saved_study_reloads_as_the_same_result(small_study):
    result, out = small_study
    again = load_record_fragility(out)
    pd.testing.assert_frame_equal(again.table, result.table, check_like=False)
    assert again.lognormal == result.lognormal
    assert np.array_equal(again.band.lower, result.band.lower)
    stored = json.loads((out / "summary.json").read_text())["summary"]
    assert stored["probability"] == result.probability.tolist()
    curves = pd.read_csv(out / "curves.csv")
    assert curves["probability"].to_numpy() == pytest.approx(result.probability)


def test_results_do_not_depend_on_the_backend(suite_dir):
    settings = RecordFragilitySettings(suite=RecordSuite.from_paths(suite_dir),
                                       levels=(0.5, 1.0, 1.5), sample_size=3, bootstrap=50)
    from distributed import Client, LocalCluster

    serial = run_record_fragility(settings, backend="serial", progress=False, chunk_size=2)
    processes = run_record_fragility(settings, backend="processes", workers=2, progress=False)
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=False,
                      dashboard_address=None) as cluster, Client(cluster) as client:
        dask = run_record_fragility(settings, backend="dask", scheduler=client, progress=False)
    for other in (processes, dask):
        pd.testing.assert_frame_equal(other.table, serial.table)
        assert other.summary()["lognormal"] == serial.summary()["lognormal"]


def test_resume_continues_and_refuses_changed_records(suite_dir, tmp_path):
    import shutil

    folder = tmp_path / "records"
    shutil.copytree(suite_dir, folder)
    settings = RecordFragilitySettings(suite=RecordSuite.from_paths(folder),
                                       levels=(0.6, 1.2), sample_size=2, bootstrap=20)
    out = tmp_path / "out"
    full = run_record_fragility(settings, out, backend="serial", progress=False)
    (out / "summary.json").unlink()
    (out / "chunks" / "chunk-000001.npz").unlink()  # as if interrupted
    resumed = run_record_fragility(settings, out, backend="serial", progress=False,
                                   resume=True)
    pd.testing.assert_frame_equal(resumed.table, full.table)
    assert resumed.metadata["timings"]["chunks_resumed"] == 2
    changed = folder / "stochastic-001.csv"
    changed.write_text(changed.read_text().replace("time_s", "time_s ", 1))
    with pytest.raises(ValueError, match="stochastic-001.csv' has changed"):
        run_record_fragility(RecordFragilitySettings(
            suite=RecordSuite.from_paths(folder), levels=(0.6, 1.2), sample_size=2, bootstrap=20),
            out, backend="serial", progress=False, resume=True)
    # a worker refuses a file that changed after the study was set up
    with pytest.raises(ValueError, match="has changed since the study was set up"):
        settings.suite.motions()


def test_result_from_a_table_checks_its_order(small_study):
    result, _ = small_study
    shuffled = result.table.sample(frac=1.0, random_state=0).reset_index(drop=True)
    with pytest.raises(ValueError, match="not ordered"):
        record_fragility_result(result.settings, shuffled)


def test_plots_of_a_record_study(small_study):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from archquake.plotting import plot_incremental, plot_record_fragility

    result, _ = small_study
    ax = plot_record_fragility(result)
    assert ax.get_xlabel() == "pga [g]"
    plotted = [line.get_ydata() for line in ax.get_lines() if line.get_marker() == "o"]
    assert np.allclose(plotted[0], result.probability)
    ax2 = plot_incremental(result, arch=NOMINAL_ARCH)
    assert ax2.get_xlabel() == "pga [g]"
    plt.close("all")


# --------------------------------------------------------------------------------------------
# the command line: bad inputs
# --------------------------------------------------------------------------------------------


@pytest.mark.parametrize("extra, message", [
    (["--im", "foo", "--levels", "0.5,1"], "--im: unknown intensity measure 'foo'"),
    (["--im", "d5-95", "--levels", "5,10"], "'d5-95'"),
    (["--levels", "0,0.5,1"], "--levels must be pga values > 0 [g]"),
    (["--levels", "1,0.5"], "--levels must increase"),
    ([], "--levels is required with --records"),
    (["--levels", "0.5,1", "--durations", "0.4"], "--durations: options of the pulse study"),
    (["--levels", "0.5,1", "--samples", "0"], "--samples must be an integer in [1, 100000]"),
])
def test_cli_bad_record_inputs_are_clear_errors(extra, message, suite_dir, tmp_path, capsys):
    argv = ["fragility", "--records", str(suite_dir), "--out", str(tmp_path / "o"),
            "--no-progress", *extra]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("archquake: error:") and message in err


def test_cli_bad_record_paths_are_clear_errors(tmp_path, capsys):
    empty = tmp_path / "empty"
    empty.mkdir()
    (empty / "notes.txt").write_text("no records here\n")
    base = ["fragility", "--levels", "0.5,1", "--out", str(tmp_path / "o"), "--no-progress"]
    assert main([*base, "--records", str(empty)]) == 2
    assert f"record folder '{empty}': no record files" in capsys.readouterr().err
    assert main([*base, "--records", str(tmp_path / "missing.csv")]) == 2
    assert "missing.csv': no such file" in capsys.readouterr().err
    assert main(["fragility", "--im", "pgv", "--out", str(tmp_path / "o")]) == 2
    assert "--im: only for a record-based study" in capsys.readouterr().err


def test_settings_refuse_bad_values():
    suite = RecordSuite.from_stochastic(1, **SUITE)
    with pytest.raises(ValueError, match="levels must be pgv values > 0"):
        RecordFragilitySettings(suite=suite, levels=(0.0, 1.0), im="pgv")
    with pytest.raises(ValueError, match="cannot define stripes"):
        RecordFragilitySettings(suite=suite, levels=(1.0,), im="d5-95")
    with pytest.raises(ValueError, match="bootstrap"):
        RecordFragilitySettings(suite=suite, levels=(1.0,), bootstrap=3)
    with pytest.raises(ValueError, match="either files or a stochastic suite"):
        RecordSuite()


def test_lognormal_fragility_of_the_study_maximises_its_likelihood(small_study):
    result, _ = small_study
    grid = _grid_mle(result.levels, result.trials, result.failures,
                     np.linspace(0.4, 1.4, 501), np.linspace(0.1, 1.2, 551))
    assert result.lognormal.median == pytest.approx(grid[0], abs=3e-3)
    assert result.lognormal.dispersion == pytest.approx(grid[1], abs=3e-3)
    assert isinstance(result.lognormal, LognormalFragility)


def test_report_function_runs_each_measure_on_the_synthetic_suite():
    from archquake.studies.record_fragility import STOCHASTIC_SUITE, oppenheim_record_fragility

    results = oppenheim_record_fragility(("pgv",), records=2, sample_size=1,
                                         levels={"pgv": (1.0, 2.0)}, bootstrap=10,
                                         suite_parameters={**STOCHASTIC_SUITE, "duration": 8.0})
    result = results["pgv"]
    assert result.settings.im == "pgv" and result.levels.tolist() == [1.0, 2.0]
    assert result.records == ("stochastic-000", "stochastic-001")
    with pytest.raises(ValueError, match="no default levels for 'sa\\(0.5\\)'"):
        oppenheim_record_fragility(("sa(0.5)",), records=1, sample_size=1)


def test_cli_record_study_writes_tables_figures_and_nrml(suite_dir, tmp_path, capsys):
    import xml.etree.ElementTree as ET

    out, plots, nrml = tmp_path / "out", tmp_path / "figs", tmp_path / "arch.xml"
    argv = ["fragility", "--records", str(suite_dir), "--im", "pgv", "--levels", "0.4:2.4:0.25",
            "--samples", "2", "--out", str(out), "--plot-dir", str(plots), "--export-nrml",
            str(nrml), "--no-progress"]
    assert main(argv) == 0
    text = capsys.readouterr().out
    assert "Record-based fragility: h = 2 irregular arches" in text and "pgv [m/s]" in text
    for name in ("results.parquet", "results.csv", "curves.csv", "incremental.csv",
                 "summary.json", "study.json"):
        assert (out / name).is_file(), name
    pngs = sorted(p.name for p in plots.glob("*.png"))
    assert pngs == ["record_fragility_pgv.png", "record_incremental_pgv.png"]
    summary = json.loads((out / "summary.json").read_text())["summary"]
    functions = ET.parse(nrml).getroot().iter("{http://openquake.org/xmlns/nrml/0.5}imls")
    assert {f.get("imt") for f in functions} == {"PGV"}
    assert summary["im_unit"] == "m/s" and summary["lognormal"]["median"] is not None
