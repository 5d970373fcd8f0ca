"""Record-based fragility (multiple-stripe analysis): stripes, the study's fits and bands,
incremental view, excluded arches, execution and the command line, each against an independent
value (the fits themselves: tests/studies/test_fragility_fits.py)."""

import json
import math

import numpy as np
import pandas as pd
import pytest

from archquake import oppenheim
from archquake.cli import main
from archquake.fourlink.impact import restitution
from archquake.fourlink.mechanism import mechanisms
from archquake.fourlink.time_history import simulate
from archquake.ground_motion import RecordSuite, read_suite, scale_to_im, stochastic_suite
from archquake.models import ModelSpec
from archquake.studies.arch_sample import STATUS_EXCLUDED
from archquake.studies.fits import LognormalFragility
from archquake.studies.record_fragility import (
    NOMINAL_ARCH,
    RecordFragilitySettings,
    load_record_fragility,
    record_fragility_result,
    record_outcomes,
    run_record_fragility,
)
from exclusion_reference import independent_exclusions
from likelihood_grid import grid_mle

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
    argv = ["record-fragility", "--records", str(suite_dir), "--im", "pga", "--levels", LEVELS,
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
                                       sample_size=1, epsilon=0.0,
                                       model=ModelSpec(restitution="computed"))
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
    from archquake import FourLinkModel, oppenheim
    from archquake.fourlink.engine import outcomes_grid

    dynamics = FourLinkModel.from_arch(oppenheim(), "computed")
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


def test_settings_stored_under_former_names_load():
    """``tolerance`` is read as ``epsilon``, the restitution ``"blocks"`` or ``"rigid-blocks"``
    of an earlier version as ``"measured"``."""
    settings = RecordFragilitySettings(suite=RecordSuite.from_stochastic(1, **SUITE),
                                       levels=(0.5, 1.0), model=ModelSpec(restitution="measured"),
                                       epsilon=0.05)
    for former in ("blocks", "rigid-blocks"):
        stored = settings.to_dict()
        stored["tolerance"] = stored.pop("epsilon")
        stored["restitution"] = former
        assert RecordFragilitySettings.from_dict(stored) == settings


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
    (["--levels", "0.5,1", "--samples", "0"], "--samples must be an integer in [1, 100000]"),
])
def test_cli_bad_record_inputs_are_clear_errors(extra, message, suite_dir, tmp_path, capsys):
    argv = ["record-fragility", "--records", str(suite_dir), "--out", str(tmp_path / "o"),
            "--no-progress", *extra]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("archquake: error:") and message in err


def test_cli_bad_record_paths_are_clear_errors(tmp_path, capsys):
    empty = tmp_path / "empty"
    empty.mkdir()
    (empty / "notes.txt").write_text("no records here\n")
    base = ["record-fragility", "--levels", "0.5,1", "--out", str(tmp_path / "o"), "--no-progress"]
    assert main([*base, "--records", str(empty)]) == 2
    assert f"record folder '{empty}': no record files" in capsys.readouterr().err
    assert main([*base, "--records", str(tmp_path / "missing.csv")]) == 2
    assert "missing.csv': no such file" in capsys.readouterr().err


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
    grid = grid_mle(result.levels, result.trials, result.failures,
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
    argv = ["record-fragility", "--records", str(suite_dir), "--im", "pgv", "--levels",
            "0.4:2.4:0.25", "--samples", "2", "--out", str(out), "--plot-dir", str(plots),
            "--export-nrml", str(nrml), "--no-progress"]
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


# --------------------------------------------------------------------------------------------
# arches that cannot be analysed: the rule of the pulse study (archquake.studies.arch_sample)
# --------------------------------------------------------------------------------------------

EXCLUDING = {"epsilon": 0.5, "seed": 0, "sample_size": 5, "levels": (0.5, 1.0, 1.5),
             "bootstrap": 20}
"""epsilon = 0.5: of arches 0-4 (seed 0), one comes apart and two cannot stand."""


@pytest.fixture(scope="module")
def excluding_study(tmp_path_factory):
    settings = RecordFragilitySettings(suite=RecordSuite.from_stochastic(2, seed=1, **SUITE),
                                       **EXCLUDING)
    out = tmp_path_factory.mktemp("excluding") / "out"
    return run_record_fragility(settings, out, backend="serial", progress=False), out


def test_arches_that_cannot_be_analysed_are_excluded_as_in_the_pulse_study(nominal,
                                                                             excluding_study):
    from archquake.studies.fragility import FragilitySettings, run_fragility

    result, out = excluding_study
    expected = independent_exclusions(nominal, 0.5, 5, 0)
    assert set(expected.values()) == {"not an arch", "cannot stand"}
    assert result.excluded == expected
    # the pulse study with the same sample excludes the same arches, for the same reasons
    pulse = run_fragility(FragilitySettings(sample_size=5, epsilon=0.5, seed=0, durations=(0.4,),
                                            amplitudes_g=(0.3, 0.6), limit_sample_size=5),
                          backend="serial", progress=False)
    assert pulse.excluded == expected
    t = result.table
    dropped = t["arch"].isin(list(expected))
    assert set(t.loc[dropped, "status"]) == {STATUS_EXCLUDED}
    assert not t.loc[dropped, "integrated"].any()
    assert dict(t.loc[dropped].groupby("arch")["excluded"].first()) == expected
    assert set(t.loc[~dropped, "excluded"]) == {""}
    # the stripes count the analysed arches only, rebuilt from their rows
    analysed = sorted(set(range(5)) - set(expected))
    assert result.analysed == len(analysed) and result.arches.tolist() == analysed
    assert result.trials == len(analysed) * 2
    rows = t[t["arch"].isin(analysed)]
    pairs = rows.groupby(["arch", "record", "level"])["status"].apply(lambda s: (s == 2).any())
    assert result.probability == pytest.approx(pairs.groupby(level="level").mean().to_numpy(),
                                               abs=0)
    summary = result.summary()
    assert summary["arches"] == {"drawn": 5, "analysed": len(analysed), "excluded": {
        why: sorted(i for i, w in expected.items() if w == why)
        for why in ("not an arch", "cannot stand")}}
    assert summary["analyses"]["total"] == (len(analysed) + 1) * 2 * 3 * 2
    assert set(result.incremental()["arch"]) == {*analysed, NOMINAL_ARCH}
    assert result.arch_failed(analysed[-1]).shape == (2, 3)
    with pytest.raises(ValueError, match=f"arch {min(expected)} was excluded"):
        result.arch_failed(min(expected))
    # saved and reloaded: the same exclusions
    again = load_record_fragility(out)
    assert again.excluded == expected and np.array_equal(again.probability, result.probability)


def test_a_study_whose_every_arch_is_excluded_is_an_error(tmp_path):
    # every arch of epsilon = 0.99 (seed 3) comes apart or falls: nothing to estimate
    settings = RecordFragilitySettings(suite=RecordSuite.from_stochastic(1, **SUITE),
                                       levels=(0.5, 1.0), sample_size=3, epsilon=0.99, seed=3,
                                       bootstrap=10)
    with pytest.raises(ValueError, match="every one of the 3 irregular arches was excluded"):
        run_record_fragility(settings, backend="serial", progress=False)


def test_an_arch_that_never_collapses_stays_at_rest_at_every_level():
    """The task on the arches of a thick flat arch (k = inf both ways): rows at rest, not
    integrated, analysed (the nominal arch itself could not be a study's nominal arch)."""
    from archquake import circular_arch
    from archquake.execution import StudyPlan
    from archquake.studies.record_fragility import record_fragility_task

    thick_flat = circular_arch(1.0, math.radians(40), 0.5, 6)
    settings = RecordFragilitySettings(suite=RecordSuite.from_stochastic(1, **SUITE),
                                       levels=(0.5, 2.0), nominal=thick_flat, sample_size=2,
                                       epsilon=0.02, bootstrap=10)
    columns = record_fragility_task(StudyPlan(settings.to_dict(), 0, 2, 2).chunk(0))
    assert columns["arch"].tolist() == [0] * 4 + [1] * 4
    assert set(columns["status"]) == {0} and not columns["integrated"].any()
    assert set(columns["excluded"]) == {""} and np.all(np.isinf(columns["k_l"]))


def test_an_unexpected_error_names_the_arch_that_raised_it(monkeypatch):
    from archquake.errors import StudyError
    from archquake.execution import StudyPlan
    from archquake.studies import record_fragility

    real = record_fragility.record_outcomes
    calls = []

    def failing_second_arch(model, motion, factors):
        calls.append(model)
        if len(calls) == 3:  # two records per arch: the first record of arch 1
            raise RuntimeError("integrator failure")
        return real(model, motion, factors)

    monkeypatch.setattr(record_fragility, "record_outcomes", failing_second_arch)
    settings = RecordFragilitySettings(suite=RecordSuite.from_stochastic(2, **SUITE),
                                       levels=(0.5, 1.0), sample_size=2, seed=11, bootstrap=10)
    with pytest.raises(StudyError, match=r"irregular arch 1 \(SeedSequence\(11, spawn_key=\(1,\)"
                                         r"\)\) stopped the study: RuntimeError: integrator"):
        record_fragility.record_fragility_task(StudyPlan(settings.to_dict(), 11, 3, 3).chunk(0))


def test_a_study_written_before_the_excluded_column_loads_and_is_not_resumed(excluding_study,
                                                                             tmp_path):
    """A finished study without the column ``excluded`` (none was excluded then) gives the same
    result; interrupted, its chunks cannot be joined with new ones: a clear refusal."""
    import shutil

    result, out = excluding_study
    analysed = result.table[result.table["excluded"] == ""]
    settings = RecordFragilitySettings(suite=RecordSuite.from_stochastic(2, seed=1, **SUITE),
                                       **{**EXCLUDING, "epsilon": 0.05})
    fresh = run_record_fragility(settings, tmp_path / "new", backend="serial", progress=False)
    old_table = fresh.table.drop(columns="excluded")
    old = record_fragility_result(settings, old_table)
    assert old.excluded == {} and np.array_equal(old.probability, fresh.probability)
    assert old.lognormal == fresh.lognormal
    assert len(analysed) < len(result.table)
    # an interrupted study of the earlier format: chunks without the column
    interrupted = tmp_path / "old"
    shutil.copytree(tmp_path / "new", interrupted)
    (interrupted / "summary.json").unlink()
    for path in sorted((interrupted / "chunks").glob("chunk-*.npz")):
        with np.load(path) as data:
            columns = {k: data[k] for k in data.files if k != "excluded"}
        np.savez(path, **columns)
    (sorted((interrupted / "chunks").glob("chunk-*.npz"))[-1]).unlink()
    with pytest.raises(ValueError, match=r"cannot resume .*earlier version of archquake.*no "
                                         r"column 'excluded'"):
        run_record_fragility(settings, interrupted, backend="serial", progress=False,
                             resume=True)
