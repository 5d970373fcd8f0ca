"""The fragility study with the rigid-block model: the same execution layer (serial, processes,
Dask, resume), results that say which model made them, and rows equal to direct analyses."""

import math

import numpy as np
import pandas as pd
import pytest

from archquake import GRAVITY
from archquake.cli import main
from archquake.ground_motion import oppenheim_pulse
from archquake.models import ModelSpec
from archquake.results_io import load_study
from archquake.rigid_blocks import RigidBlockModel
from archquake.studies.fragility import FragilitySettings, run_fragility

TINY = {"sample_size": 2, "durations": (0.4,), "limit_sample_size": 4, "seed": 3,
        "amplitudes_g": tuple(np.round(np.arange(0.10, 0.71, 0.05), 2)), "model": "rigid-blocks",
        "stride": 4}
FAST = {"progress": False, "nominal_resolution_g": 0.01, "limit_chunk_size": 2}


@pytest.fixture(scope="module")
def serial():
    return run_fragility(FragilitySettings(**TINY), backend="serial", **FAST)


def test_results_say_which_model_made_them(serial):
    summary = serial.summary()
    assert summary["settings"]["model"] == "rigid-blocks"
    assert summary["settings"]["search"] == "screened"
    assert summary["nominal_restitution"] == [None, None]  # no coefficient of restitution
    assert serial.nominal_domains[0].model["model"] == "rigid-blocks"


def test_analysed_rows_are_the_rigid_block_outcomes(serial):
    """Every analysed row against a direct analysis of the same arch and pulse."""
    table = serial.table
    sample = serial.settings.sample
    rows = table[table["analysed"]]
    assert len(rows) > 0
    for _, row in rows.sample(6, random_state=0).iterrows():
        model = RigidBlockModel(sample.arch(int(row["arch"])))
        sign = -1.0 if row["direction"] == "l" else 1.0
        pulse = oppenheim_pulse(sign * row["amplitude_g"] * GRAVITY, row["duration"])
        assert int(model.outcome(pulse).status) == row["status"]


def test_screened_equals_the_exhaustive_study(serial):
    exhaustive = run_fragility(FragilitySettings(**TINY, search="exhaustive"), backend="serial",
                               **FAST)
    assert np.array_equal(exhaustive.probability, serial.probability)
    assert np.array_equal(exhaustive.table["status"], serial.table["status"])
    assert exhaustive.table["analysed"].all() and not serial.table["analysed"].all()


def test_the_same_results_serially_on_processes_and_on_dask(serial):
    from distributed import Client, LocalCluster

    settings = FragilitySettings(**TINY)
    processes = run_fragility(settings, backend="processes", workers=2, **FAST)
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=False,
                      dashboard_address=None) as cluster, Client(cluster) as client:
        dask = run_fragility(settings, backend="dask", scheduler=client, **FAST)
    for other in (processes, dask):
        pd.testing.assert_frame_equal(other.table, serial.table)
        assert np.array_equal(other.probability, serial.probability)


def test_an_interrupted_study_resumes_and_a_change_of_model_is_refused(serial, tmp_path):
    out = tmp_path / "study"
    settings = FragilitySettings(**TINY)
    run_fragility(settings, out, backend="serial", **FAST)
    for name in ("summary.json", "results.parquet", "results.csv", "curves.csv"):
        (out / name).unlink()
    chunks = sorted((out / "chunks").glob("chunk-*.npz"))
    assert len(chunks) == 2  # one arch per chunk with the rigid blocks
    chunks[1].unlink()
    resumed = run_fragility(settings, out, backend="serial", resume=True, **FAST)
    pd.testing.assert_frame_equal(resumed.table, serial.table)
    assert load_study(out).metadata["timings"]["chunks_resumed"] == 1
    four_link = FragilitySettings(**{**TINY, "model": "four-link"})
    with pytest.raises(ValueError, match="differ"):
        run_fragility(four_link, out, backend="serial", resume=True, **FAST)
    coarser = FragilitySettings(**{**TINY, "model": ModelSpec("rigid-blocks", time_step=0.002)})
    with pytest.raises(ValueError, match="differ"):
        run_fragility(coarser, out, backend="serial", resume=True, **FAST)


def test_the_time_step_reaches_every_analysis():
    """A study at h = 2 ms: its rows are the outcomes of the model with that step (and it says
    so), and the settings round-trip through their JSON form."""
    settings = FragilitySettings(**{**TINY, "sample_size": 1, "search": "exhaustive",
                                    "model": ModelSpec("rigid-blocks", time_step=0.002)})
    assert FragilitySettings.from_dict(settings.to_dict()) == settings
    assert settings.to_dict()["time_step"] == 0.002
    result = run_fragility(settings, backend="serial", **FAST)
    model = settings.model.build(settings.sample.arch(0))
    assert model.settings.time_step == 0.002
    rows = result.table[result.table["direction"] == "r"]
    for _, row in rows.iloc[::3].iterrows():
        pulse = oppenheim_pulse(row["amplitude_g"] * GRAVITY, row["duration"])
        assert int(model.outcome(pulse).status) == row["status"]
    with pytest.raises(ValueError, match="time_step"):
        ModelSpec("rigid-blocks", time_step=-1.0)


def test_a_step_that_cannot_resolve_the_study_is_refused_before_any_analysis(capsys):
    """The limit of the contact law on the nominal arch, 0.02 sqrt(t/g) with Oppenheim's
    t = 1.5 m (7.82 ms), and 1/20 of the shortest pulse duration, are checked when the settings
    are made, not when the first arch is analysed; the four-link model ignores the step."""
    limit = 0.02 * math.sqrt(1.5 / GRAVITY)
    assert limit == pytest.approx(0.00782, abs=1e-5)
    FragilitySettings(**{**TINY, "model": ModelSpec("rigid-blocks", time_step=0.999 * limit)})
    with pytest.raises(ValueError, match=r"time_step must be at most 0.00782 s .* 1.5 m thick"):
        FragilitySettings(**{**TINY, "model": ModelSpec("rigid-blocks", time_step=1.01 * limit)})
    with pytest.raises(ValueError, match=r"at most 0.003 s .* shortest piece 0.06 s"):
        FragilitySettings(**{**TINY, "durations": (0.06, 0.4),
                             "model": ModelSpec("rigid-blocks", time_step=0.004)})
    FragilitySettings(**{**TINY, "model": ModelSpec("four-link", time_step=0.5)})
    assert main(["fragility", "--model", "rigid-blocks", "--time-step", "0.009", "--samples",
                 "2", "--out", "never-written"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("archquake: error: --time-step must be at most 0.00782 s")
