"""How a fragility study chooses its search and where it runs: every level under records, and a
study shorter than starting worker processes runs in the process that asked for it, with the
same results (studies.strategies.pool_pays)."""

import math

import numpy as np
import pandas as pd
import pytest

from archquake.studies.fragility import FragilitySettings, _serial_seconds, run_fragility
from archquake.studies.strategies import POOL_START_SECONDS, pool_pays, study_seconds

TINY = {"sample_size": 2, "durations": (0.4,), "limit_sample_size": 4, "seed": 3,
        "amplitudes_g": (0.2, 0.4, 0.6)}
FAST = {"progress": False, "nominal_resolution_g": 0.05, "limit_chunk_size": 2}


@pytest.mark.parametrize("model, search", [("four-link", "exhaustive"),
                                           ("rigid-blocks", "screened")])
def test_the_default_search_under_pulses_and_under_records(model, search):
    from archquake.ground_motion import RecordSuite
    from archquake.studies.record_fragility import RecordFragilitySettings

    assert FragilitySettings(**TINY, model=model).search == search
    suite = RecordSuite.from_stochastic(1, seed=4, significant_duration=2.0, duration=4.0)
    records = RecordFragilitySettings(suite=suite, levels=(0.3, 0.6), model=model)
    assert records.search == "exhaustive"  # only rest is smooth under a record
    assert RecordFragilitySettings(suite=suite, levels=(0.3, 0.6), model=model,
                                   search="screened").search == "screened"


def test_the_estimate_of_a_study_is_its_arches_and_analyses():
    # the paper's four-link study: 41 arches (40 and the nominal one) x 2 x 4 x 61 points:
    # 41 x 0.06 s + 41 x 488 x 15 us = 2.46 + 0.30014 s, and 1,000 limit analyses at 1 ms
    settings = FragilitySettings(amplitudes_g=tuple(np.round(np.arange(0.2, 0.805, 0.01), 2)))
    assert _serial_seconds(settings) == pytest.approx(2.46 + 41 * 488 * 1.5e-5 + 1.0)
    # the rigid blocks: 41 x 0.06 + 41 x 488 x 3 ms = 2.46 + 60.024 s
    blocks = FragilitySettings(amplitudes_g=settings.amplitudes_g, model="rigid-blocks")
    assert _serial_seconds(blocks) == pytest.approx(2.46 + 60.024 + 1.0)
    assert study_seconds("rigid-blocks", "record", 2, 100) == pytest.approx(0.12 + 8.0)


def test_workers_pay_only_beyond_what_starting_them_costs():
    # seconds s on w workers: POOL_START_SECONDS + s / w < s, i.e. s > 3 w / (w - 1): 6 s on 2
    assert POOL_START_SECONDS == 3.0
    assert not pool_pays(5.99, 2) and pool_pays(6.01, 2)
    assert not pool_pays(4.49, 3) and pool_pays(4.51, 3)  # 3 x 3 / 2 = 4.5 s
    assert not pool_pays(math.inf, 1)  # one worker never beats this process


def test_a_small_study_on_workers_runs_here_with_the_same_results(monkeypatch):
    settings = FragilitySettings(**TINY)
    serial = run_fragility(settings, backend="serial", **FAST)
    here = run_fragility(settings, workers=2, **FAST)  # about 0.2 s of work: no pool
    assert here.metadata["backend"] == "serial"
    pd.testing.assert_frame_equal(here.table, serial.table)
    np.testing.assert_array_equal(here.probability, serial.probability)
    from archquake.studies import strategies

    monkeypatch.setattr(strategies, "pool_pays", lambda seconds, workers: True)
    pooled = run_fragility(settings, workers=2, **FAST)
    assert pooled.metadata["backend"] == "processes"
    pd.testing.assert_frame_equal(pooled.table, serial.table)



def test_a_small_record_study_on_workers_runs_here_with_the_same_results():
    from archquake.ground_motion import RecordSuite
    from archquake.studies.record_fragility import RecordFragilitySettings, run_record_fragility

    suite = RecordSuite.from_stochastic(1, seed=4, significant_duration=2.0, duration=4.0)
    settings = RecordFragilitySettings(suite=suite, levels=(0.3, 0.6), sample_size=1, seed=2,
                                       bootstrap=10)
    assert settings.search == "exhaustive"
    # 2 arches x 1 record x 2 levels x 2 polarities = 8 analyses: 2 x 0.06 + 8 x 5 ms = 0.16 s
    serial = run_record_fragility(settings, backend="serial", progress=False)
    here = run_record_fragility(settings, workers=2, progress=False)
    assert here.metadata["backend"] == "serial"
    pd.testing.assert_frame_equal(here.table, serial.table)


def _pid(_=None):
    import os

    return os.getpid()


def test_a_forked_worker_runs_in_another_process_and_only_on_linux(monkeypatch):
    import os
    import sys

    from archquake.execution import forked_pool

    if not sys.platform.startswith("linux"):
        assert forked_pool() is None
        return
    with forked_pool() as pool:
        assert pool.submit(_pid).result() != os.getpid()
    monkeypatch.setattr(sys, "platform", "darwin")
    assert forked_pool() is None


def test_a_study_run_here_gives_its_limit_sample_to_a_forked_worker(monkeypatch, tmp_path):
    """With two workers asked for and a study too small for fresh ones, the limit sample of 250
    arches (0.25 s estimated, FORK_PAYS_SECONDS) runs on a forked worker while the arches run
    here: the same table, limit sample and curves as the serial run, its directory written (so
    that the study can be resumed), and on one worker, or with fewer arches, no fork."""
    import sys

    from archquake import execution
    from archquake.studies import fragility

    if not sys.platform.startswith("linux"):
        pytest.skip("processes are forked only on Linux")
    settings = FragilitySettings(**{**TINY, "limit_sample_size": 250})
    assert settings.limit_sample_size * fragility.LIMIT_ANALYSIS_SECONDS >= (
        fragility.FORK_PAYS_SECONDS)
    serial = run_fragility(settings, tmp_path / "serial", backend="serial", **FAST)
    forks, fork = [], execution.forked_pool

    def counted():
        forks.append(1)
        return fork()

    monkeypatch.setattr(execution, "forked_pool", counted)
    here = run_fragility(settings, tmp_path / "here", workers=2, **FAST)
    assert forks == [1] and here.metadata["backend"] == "serial"
    pd.testing.assert_frame_equal(here.table, serial.table)
    for side in ("load_multiplier_l", "load_multiplier_r"):
        np.testing.assert_array_equal(getattr(here.limit_sample, side),
                                      getattr(serial.limit_sample, side))
    np.testing.assert_array_equal(here.probability, serial.probability)
    written = pd.read_parquet(tmp_path / "here" / fragility.LIMIT_DIRECTORY / "results.parquet")
    assert len(written) == 250
    run_fragility(settings, workers=1, **FAST)
    run_fragility(FragilitySettings(**TINY), workers=2, **FAST)
    assert forks == [1]


def _sigterm_is_default(_=None):
    import signal

    return signal.getsignal(signal.SIGTERM) == signal.SIG_DFL


def test_a_forked_worker_ends_on_sigterm_though_the_command_handles_it():
    """The command turns SIGTERM into an exception (cli._signals); a forked worker inherits
    the handler, and the pool's loop would catch that exception and go on: its initializer
    restores the default action, so that terminating the pool ends it at once."""
    import signal
    import sys
    import time

    from archquake.execution import forked_pool

    if not sys.platform.startswith("linux"):
        pytest.skip("processes are forked only on Linux")

    def handler(signum, frame):
        raise RuntimeError("terminated")

    previous = signal.signal(signal.SIGTERM, handler)
    try:
        pool = forked_pool()
        assert pool.submit(_sigterm_is_default).result()
        start = time.monotonic()
        pool.terminate_workers()
        assert time.monotonic() - start < 2.0
    finally:
        signal.signal(signal.SIGTERM, previous)
