"""The fragility study [paper, Sect. 5.3.3, eq. (9), Figs. 17-21] at reduced size."""

import json

import numpy as np
import pandas as pd
import pytest

from archquake.cli import main
from archquake.execution import StudyPlan, process_pool
from archquake.fourlink.impact import restitution
from archquake.fourlink.mechanism import mechanisms
from archquake.fourlink.time_history import simulate
from archquake.geometry import GRAVITY, irregular_sample
from archquake.ground_motion import oppenheim_pulse
from archquake.limit_analysis import limit_sample, load_multipliers
from archquake.models import ModelSpec
from archquake.results_io import load_study
from archquake.studies.arch_sample import STATUS_EXCLUDED
from archquake.studies.failure_domain import inclusive_range
from archquake.studies.fits import fit_lognormal
from archquake.studies.fragility import (
    FragilitySettings,
    fragility_task,
    limit_task,
    load_fragility,
    run_fragility,
    warm_up,
)
from exclusion_reference import independent_exclusions

TINY = {"sample_size": 3, "durations": (0.4,),
        "amplitudes_g": tuple(inclusive_range(0.3, 0.9, 0.1)), "limit_sample_size": 6, "seed": 11}


@pytest.fixture(scope="module")
def small_result(tmp_path_factory):
    settings = FragilitySettings(sample_size=4, durations=(0.4, 0.6),
                                 amplitudes_g=tuple(inclusive_range(0.3, 0.9, 0.05)),
                                 limit_sample_size=8, seed=3)
    out = tmp_path_factory.mktemp("fragility") / "study"
    return run_fragility(settings, out, backend="serial", progress=False), out


def test_limit_task_gives_the_values_of_limit_sample(nominal):
    settings = {"nominal": FragilitySettings(nominal=nominal).to_dict()["nominal"],
                "epsilon": 0.1, "limit_method": "kinematic"}
    plan = StudyPlan(settings, seed=5, n_items=6, chunk_size=4)
    rows = [limit_task(chunk) for chunk in plan.chunks()]
    k_l = np.concatenate([r["k_l"] for r in rows])
    k_r = np.concatenate([r["k_r"] for r in rows])
    reference = limit_sample(nominal, 0.1, 6, 5, "kinematic")
    assert np.array_equal(k_l, reference.load_multiplier_l)
    assert np.array_equal(k_r, reference.load_multiplier_r)


def test_table_rows_agree_with_direct_simulations(nominal, small_result):
    result, _ = small_result
    table = result.table
    assert list(table.columns[:8]) == ["arch", "direction", "duration", "amplitude_g", "status",
                                       "half_cycle", "impacts", "collapse_time"]
    assert len(table) == 4 * 2 * 2 * 13
    arch = irregular_sample(nominal, 0.1, 4, 3)[2]
    pair = mechanisms(arch)
    c = restitution("nominal", *pair, nominal=mechanisms(nominal))
    k_l, k_r = load_multipliers(arch)
    rows = table[table["arch"] == 2]
    assert rows["k_l"].to_numpy() == pytest.approx(k_l, abs=1e-9)
    assert rows["k_r"].to_numpy() == pytest.approx(k_r, abs=1e-9)
    for _, row in rows.iloc[::5].iterrows():
        sign = -1.0 if row["direction"] == "l" else 1.0
        out = simulate(pair, oppenheim_pulse(sign * row["amplitude_g"] * GRAVITY,
                                             row["duration"]), c, record=False)
        assert (out.status, out.half_cycle) == (row["status"], row["half_cycle"])


def test_probability_of_failure_counts_either_direction(small_result):
    result, _ = small_result
    table = result.table
    failed = (table.assign(collapsed=table["status"] == 2)
              .groupby(["duration", "amplitude_g", "arch"])["collapsed"].any()
              .groupby(["duration", "amplitude_g"]).mean())
    expected = failed.to_numpy().reshape(result.probability.shape)
    assert np.array_equal(result.probability, expected)
    for direction, probability in (("l", result.probability_l), ("r", result.probability_r)):
        one = table[table["direction"] == direction]
        p = (one["status"] == 2).groupby([one["duration"], one["amplitude_g"]]).mean()
        assert np.array_equal(probability, p.to_numpy().reshape(probability.shape))
    assert np.all(result.probability >= np.maximum(result.probability_l, result.probability_r))


def test_outputs_hold_table_curves_and_summary(small_result):
    result, out = small_result
    stored = load_study(out)
    pd.testing.assert_frame_equal(stored.table, result.table, check_dtype=False)
    assert stored.metadata["seed"] == 3
    assert "archquake_version" in stored.metadata
    assert stored.summary["settings"]["sample_size"] == 4
    per = stored.summary["durations"]
    assert [p["duration"] for p in per] == [0.4, 0.6]
    curves = pd.read_csv(out / "curves.csv")
    assert np.allclose(curves["probability"], result.probability.ravel())
    k = load_study(out / "limit_sample").table
    assert np.array_equal(np.minimum(k["k_l"], k["k_r"]), result.limit_load_multipliers)
    # the nominal arch's step (eq. 10) is 0 below and 1 from its failure acceleration on
    q = result.nominal_failure_acceleration_g
    step = curves["nominal_step"].to_numpy().reshape(result.probability.shape)
    assert np.array_equal(step, (result.amplitudes_g[None, :] >= q[:, None]).astype(float))


def test_lognormal_is_fitted_to_the_rising_part(small_result):
    result, _ = small_result
    h = result.settings.sample_size
    for i, fit in enumerate(result.lognormal_fits):
        end = int(np.argmax(result.probability[i])) + 1
        assert result.lognormal_upper[i] == result.amplitudes_g[end - 1]
        if fit is not None:
            direct = fit_lognormal(result.amplitudes_g[:end], h, result.failures[i, :end])
            assert (fit.median, fit.dispersion) == (direct.median, direct.dispersion)


def test_a_saved_study_reloads_as_the_same_result(small_result, tmp_path):
    result, out = small_result
    loaded = load_fragility(out)
    assert loaded.settings == result.settings
    pd.testing.assert_frame_equal(loaded.table, result.table, check_dtype=False)
    for name in ("failures", "failures_l", "failures_r", "probability",
                 "nominal_failure_acceleration_g", "limit_load_multipliers"):
        assert np.array_equal(getattr(loaded, name), getattr(result, name)), name
    assert loaded.summary() == result.summary()
    # an interrupted study (no summary yet) is not a result
    (tmp_path / "empty").mkdir()
    with pytest.raises(ValueError):
        load_fragility(tmp_path / "empty")


@pytest.mark.parametrize("former", ["blocks", "rigid-blocks"])
def test_settings_stored_under_former_names_load(former):
    """A study stored by an earlier version loads: ``tolerance`` is read as ``epsilon`` and the
    restitution measured on the rigid blocks, stored as ``"blocks"`` or ``"rigid-blocks"``, as
    ``"measured"`` (the settings refuse those names when they are given)."""
    settings = FragilitySettings(**TINY, model=ModelSpec(restitution="measured"), epsilon=0.05)
    stored = settings.to_dict()
    stored["tolerance"] = stored.pop("epsilon")
    stored["restitution"] = former
    assert FragilitySettings.from_dict(stored) == settings
    with pytest.raises(ValueError, match=f"got '{former}'"):
        FragilitySettings(**TINY, model=ModelSpec(restitution=former))


def test_irregular_arches_fail_below_the_nominal_failure_acceleration():
    # The paper's finding (Sect. 5.3.3, Fig. 21): where the nominal arch survives (a < Q),
    # some irregular arches (epsilon = 0.10) already fail, at every pulse duration.
    settings = FragilitySettings(sample_size=20, durations=(0.4, 0.6),
                                 amplitudes_g=tuple(inclusive_range(0.20, 1.00, 0.02)),
                                 limit_sample_size=20, seed=0)
    result = run_fragility(settings, backend="serial", progress=False)
    q = result.nominal_failure_acceleration_g
    assert np.all(np.isfinite(q))
    below = result.probability_below_nominal()
    assert np.all(below > 0)
    assert np.all(result.lowest_failure_acceleration_g() < q)


def test_results_do_not_depend_on_the_backend():
    from distributed import Client, LocalCluster

    settings = FragilitySettings(**TINY)
    serial = run_fragility(settings, backend="serial", progress=False, chunk_size=1,
                           limit_chunk_size=2)
    processes = run_fragility(settings, backend="processes", workers=2, progress=False,
                              chunk_size=1, limit_chunk_size=2)
    # a pool started once (workers warmed up as they start) runs several studies
    with process_pool(2, warm_up=warm_up) as pool:
        pooled = [run_fragility(settings, pool=pool, progress=False, chunk_size=chunk,
                                limit_chunk_size=2) for chunk in (1, 2)]
        with pytest.raises(ValueError, match="pool is only used by backend 'processes'"):
            run_fragility(settings, backend="serial", pool=pool, progress=False)
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=False,
                      dashboard_address=None) as cluster, Client(cluster) as client:
        dask = run_fragility(settings, backend="dask", scheduler=client, progress=False,
                             chunk_size=1, limit_chunk_size=2)
    for other in (processes, dask, *pooled):
        pd.testing.assert_frame_equal(other.table, serial.table)
        assert np.array_equal(other.probability, serial.probability)
        assert np.array_equal(other.limit_load_multipliers, serial.limit_load_multipliers)


def test_plots_of_fragility(small_result):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from archquake.plotting import plot_fragility_curve, plot_fragility_surface

    result, _ = small_result
    ax = plot_fragility_curve(result, 0.6)
    dots = next(line for line in ax.get_lines() if line.get_label().startswith("P$_F$"))
    assert np.array_equal(dots.get_ydata(), result.probability[1])
    q_line = next(line for line in ax.get_lines()
                  if line.get_label().startswith("nominal arch, failure"))
    assert q_line.get_xdata()[0] == pytest.approx(result.nominal_failure_acceleration_g[1])
    plt.close(ax.figure)
    ax = plot_fragility_surface(result)
    assert ax.name == "3d"
    plt.close(ax.figure)


# --------------------------------------------------------------------------------------------
# Command line
# --------------------------------------------------------------------------------------------
def test_cli_domain_reproduces_point_q(capsys, paper):
    code = main(["domain", "--durations", "0.4", "--amplitudes", "0.40:0.60:0.01",
                 "--restitution", "paper", "--json"])
    assert code == 0
    (entry,) = json.loads(capsys.readouterr().out)
    q = paper["dynamics"]["NA"]["failure_acceleration_tp040"]
    assert entry["duration"] == 0.4
    assert entry["failure_acceleration"] == pytest.approx(q, abs=0.01)
    assert entry["intervals"][0]["outcome"] == "recovery"


FRAGILITY_ARGS = ["fragility", "--samples", "3", "--durations", "0.4",
                  "--amplitudes", "0.3:0.9:0.1", "--limit-samples", "6", "--seed", "11",
                  "--no-progress"]


@pytest.mark.parametrize("argv, message", [
    (["fragility", "--samples", "0"], "--samples"),
    (["fragility", "--amplitudes", "0.2:1.0:0"], "step"),
    (["fragility", "--amplitudes", "0.2:1.0:-0.1"], "step"),
    (["fragility", "--durations", ""], "--durations must not be empty"),
    (["fragility", "--durations=-0.4,0.5"], "--durations must be"),
    (["fragility", "--epsilon", "1.0"], "[0, 1)"),
    (["fragility", "--epsilon", "-0.1"], "[0, 1)"),
    (["fragility", "--limit-samples", "0"], "--limit-samples"),
    (["domain", "--durations", "0.4", "--amplitudes", "0.5:0.2:0.1"], "stop must be >= start"),
    (["domain", "--durations", "0", "--amplitudes", "0.2:0.5:0.1"], "--durations must be"),
    (["domain", "--durations", "0.4", "--amplitudes", "0.2:0.5:0.1", "--resolution", "0"],
     "--resolution"),
])
def test_cli_bad_inputs_are_clear_errors(argv, message, tmp_path, capsys):
    if argv[0] == "fragility":
        argv = argv + ["--out", str(tmp_path / "out")]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("archquake: error:") and message in err


def test_cli_unreachable_scheduler_is_a_clear_error(tmp_path, capsys, monkeypatch):
    monkeypatch.setattr("archquake.execution.SCHEDULER_TIMEOUT", 0.5)
    code = main(FRAGILITY_ARGS + ["--scheduler", "tcp://127.0.0.1:9", "--out",
                                  str(tmp_path / "out")])
    assert code == 2
    assert "could not connect to the Dask scheduler" in capsys.readouterr().err


def test_cli_fragility_resumes_an_interrupted_study(tmp_path, capsys):
    out = tmp_path / "study"
    assert main(FRAGILITY_ARGS + ["--out", str(out), "--json"]) == 0
    first = json.loads(capsys.readouterr().out)
    complete = load_study(out).table
    # an interrupted study: two of the three chunk files and the final results are missing
    for name in ("summary.json", "results.parquet", "results.csv", "curves.csv"):
        (out / name).unlink()
    for chunk in sorted((out / "chunks").glob("chunk-*.npz"))[1:]:
        chunk.unlink()
    assert main(FRAGILITY_ARGS + ["--out", str(out)]) == 2
    assert "--resume" in capsys.readouterr().err
    assert main(FRAGILITY_ARGS + ["--out", str(out), "--resume", "--json"]) == 0
    resumed = json.loads(capsys.readouterr().out)
    assert resumed == first
    stored = load_study(out)
    pd.testing.assert_frame_equal(stored.table, complete)
    assert stored.metadata["timings"]["chunks_resumed"] >= 1
    # a different setting cannot continue this study
    other = [a if a != "0.3:0.9:0.1" else "0.3:0.8:0.1" for a in FRAGILITY_ARGS]
    assert main(other + ["--out", str(out), "--resume"]) == 2
    assert "differs" in capsys.readouterr().err


def test_fragility_task_rows_are_tidy():
    settings = FragilitySettings(**TINY)
    plan = StudyPlan(settings.to_dict(), settings.seed, settings.sample_size, 2)
    columns = fragility_task(plan.chunk(0))
    n = 2 * 2 * 1 * 7
    assert all(len(v) == n for v in columns.values())
    assert columns["arch"].tolist() == [0] * 14 + [1] * 14
    assert set(columns["direction"]) == {"l", "r"}


def test_run_study_pool_is_only_for_the_processes_backend():
    from archquake.execution import run_study

    plan = StudyPlan(FragilitySettings(**TINY).to_dict(), 11, 3, 2)
    with pytest.raises(ValueError, match="pool is only used by backend 'processes'"):
        run_study(fragility_task, plan, backend="serial", pool=object(), progress=False)
    with pytest.raises(ValueError, match="workers must be None when a pool is given"):
        run_study(fragility_task, plan, backend="processes", workers=2,
                  pool=type("P", (), {"submit": None})(), progress=False)


def test_arches_equal_to_the_nominal_one_are_not_below_its_load_multiplier():
    # epsilon = 0 draws the nominal arch itself: no k~ is below k, although the kinematic k~
    # of the sample and the static k of the nominal arch differ in the last bits
    settings = FragilitySettings(sample_size=1, epsilon=0.0, durations=(0.4,),
                                 amplitudes_g=(0.3, 0.5), limit_sample_size=4)
    result = run_fragility(settings, backend="serial", progress=False)
    assert np.allclose(result.limit_load_multipliers, result.nominal_load_multiplier,
                       rtol=1e-9, atol=0)
    summary = result.summary()["limit_sample"]
    assert summary["fraction_below_nominal"] == 0.0
    assert summary["below_nominal_rtol"] == 1e-9


def test_arches_that_cannot_be_analysed_are_excluded_and_counted(nominal, tmp_path):
    # epsilon = 0.5: some drawn arches come apart, some cannot carry their own weight
    settings = FragilitySettings(sample_size=10, epsilon=0.5, durations=(0.4,),
                                 amplitudes_g=(0.3, 0.5, 0.7), limit_sample_size=16, seed=0)
    result = run_fragility(settings, tmp_path / "study", backend="serial", progress=False)
    expected = independent_exclusions(nominal, 0.5, 16, 0)
    dynamic = {i: why for i, why in expected.items() if i < 10}
    assert set(dynamic.values()) == {"not an arch", "cannot stand"}  # both cases occur
    assert result.excluded == dynamic
    # P_F = h_f / h over the arches analysed
    table = result.table
    analysed = table[~table["arch"].isin(list(dynamic))]
    collapsed = (analysed.assign(c=analysed["status"] == 2)
                 .groupby(["amplitude_g", "arch"])["c"].any().groupby("amplitude_g").mean())
    assert np.array_equal(result.probability[0], collapsed.to_numpy())
    assert set(table.loc[table["arch"].isin(list(dynamic)), "status"]) == {STATUS_EXCLUDED}
    summary = result.summary()
    assert summary["arches"] == {
        "drawn": 10, "analysed": 10 - len(dynamic),
        "excluded": {why: sorted(i for i, w in dynamic.items() if w == why)
                     for why in ("not an arch", "cannot stand")}}
    limit = summary["limit_sample"]
    assert limit["excluded"] == len(expected) and limit["count"] == 16 - len(expected)
    assert np.isfinite(limit["mean"])
    assert load_fragility(tmp_path / "study").excluded == dynamic


def test_cli_fragility_reports_excluded_arches(capsys, tmp_path):
    argv = ["fragility", "--epsilon", "0.5", "--samples", "6", "--durations", "0.4",
            "--amplitudes", "0.3,0.6", "--limit-samples", "6", "--no-progress", "--out"]
    assert main([*argv, str(tmp_path / "a"), "--plot-dir", str(tmp_path / "plots")]) == 0
    out = capsys.readouterr().out
    assert "excluded" in out and "cannot stand" in out
    assert len(list((tmp_path / "plots").glob("*.png"))) == 2
    # every arch of epsilon = 0.99 (seed 3) comes apart or falls: nothing to estimate
    assert main([*argv[:2], "0.99", *argv[3:], str(tmp_path / "b"), "--seed", "3"]) == 2
    err = capsys.readouterr().err
    assert "every one of the 6 irregular arches was excluded" in err and "Traceback" not in err


def test_an_unexpected_error_names_the_arch_that_raised_it(monkeypatch):
    from archquake.errors import StudyError
    from archquake.studies import fragility

    real = fragility.model_outcomes
    calls = []

    def failing_second(model, *args, **kwargs):
        calls.append(model)
        if len(calls) == 2:
            raise RuntimeError("integrator failure")
        return real(model, *args, **kwargs)

    monkeypatch.setattr(fragility, "model_outcomes", failing_second)
    plan = StudyPlan(FragilitySettings(**TINY).to_dict(), 11, 3, 2)
    with pytest.raises(StudyError, match=r"irregular arch 1 \(SeedSequence\(11, spawn_key=\(1,\)"
                                         r"\)\) stopped the study: RuntimeError: integrator"):
        fragility_task(plan.chunk(0))


def test_cli_resume_repairs_a_damaged_chunk_and_names_a_damaged_study_json(tmp_path, capsys):
    out = tmp_path / "study"
    assert main(FRAGILITY_ARGS + ["--out", str(out), "--json"]) == 0
    first = json.loads(capsys.readouterr().out)
    (out / "summary.json").unlink()
    damaged = sorted((out / "chunks").glob("chunk-*.npz"))[1]
    damaged.write_bytes(damaged.read_bytes()[:100])  # a truncated file
    assert main(FRAGILITY_ARGS + ["--out", str(out), "--resume", "--json"]) == 0
    captured = capsys.readouterr()
    assert json.loads(captured.out) == first
    assert captured.err.startswith(f"archquake: warning: {damaged} cannot be read")
    assert "recomputed" in captured.err and "Traceback" not in captured.err
    (out / "study.json").write_text("{ not json")
    assert main(FRAGILITY_ARGS + ["--out", str(out), "--resume"]) == 2
    err = capsys.readouterr().err
    assert f"{out / 'study.json'} is not valid JSON" in err and "delete" in err


def test_an_arch_that_never_collapses_stays_at_rest_at_every_amplitude():
    """The task on the arches of a thick flat arch (k = inf both ways): analysed, at rest
    (the rule of archquake.studies.arch_sample, as in the record-based study)."""
    import math

    from archquake import circular_arch

    thick_flat = circular_arch(1.0, math.radians(40), 0.5, 6)
    settings = FragilitySettings(nominal=thick_flat, sample_size=2, epsilon=0.02,
                                 durations=(0.4,), amplitudes_g=(0.5, 2.0), limit_sample_size=2)
    columns = fragility_task(StudyPlan(settings.to_dict(), settings.seed, 2, 2).chunk(0))
    assert set(columns["status"]) == {0} and set(columns["excluded"]) == {""}
    assert np.all(np.isinf(columns["k_l"])) and np.all(np.isinf(columns["k_r"]))
    limit = limit_task(StudyPlan({"nominal": thick_flat.to_dict(), "epsilon": 0.02,
                                  "limit_method": "static"}, 0, 2, 2).chunk(0))
    assert np.all(np.isinf(limit["k_l"])) and set(limit["excluded"]) == {""}
