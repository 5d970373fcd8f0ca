import json
import logging
import os
import signal
import socket
import subprocess
import sys
import threading
import time
import types
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from pandas.testing import assert_frame_equal

import archquake
import toy_tasks
from archquake import execution
from archquake.errors import StudyError, StudyWarning
from archquake.execution import (
    StudyPlan,
    chunk_path,
    item_seed_sequence,
    run_study,
)
from archquake.results_io import load_study

TESTS = Path(__file__).parent
SRC = TESTS.parent / "src"


def direct_table(seed, n_items, draws):
    """What toy_tasks.random_task must produce, computed without chunks: item i draws from
    the i-th child spawned from the root SeedSequence(seed)."""
    children = np.random.SeedSequence(seed).spawn(n_items)
    values = np.concatenate([np.random.default_rng(c).standard_normal(draws) for c in children])
    items = np.repeat(np.arange(n_items), draws)
    return pd.DataFrame({"item": items, "draw": np.tile(np.arange(draws), n_items),
                         "value": values, "label": [f"arch-{i}" for i in items]})


@pytest.fixture(scope="module")
def dask_scheduler():
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  host="127.0.0.1", dashboard_address=":0",
                                  silence_logs=logging.ERROR) as cluster:
        yield cluster.scheduler_address


# ------------------------------------------------------------------------------- seeding, plan


@pytest.mark.parametrize("seed, item", [(0, 0), (12345, 7), (2**40 + 3, 999)])
def test_item_seed_sequence_is_the_spawned_child(seed, item):
    child = np.random.SeedSequence(seed).spawn(item + 5)[item]
    own = item_seed_sequence(seed, item)
    assert own.entropy == child.entropy and own.spawn_key == child.spawn_key == (item,)
    assert np.array_equal(own.generate_state(8), child.generate_state(8))
    assert np.array_equal(np.random.default_rng(own).random(5),
                          np.random.default_rng(child).random(5))


def test_plan_splits_items_into_consecutive_chunks():
    plan = StudyPlan({"a": 1}, seed=3, n_items=10, chunk_size=3)
    assert plan.n_chunks == 4  # ceil(10 / 3)
    bounds = [(c.index, c.start, c.stop, len(c)) for c in plan.chunks()]
    assert bounds == [(0, 0, 3, 3), (1, 3, 6, 3), (2, 6, 9, 3), (3, 9, 10, 1)]
    assert np.array_equal(np.concatenate([c.items for c in plan.chunks()]), np.arange(10))
    chunk = plan.chunk(2)
    assert [s.spawn_key for s in chunk.seed_sequences()] == [(6,), (7,), (8,)]
    assert chunk.settings == {"a": 1} and chunk.seed == 3


def test_plan_settings_are_normalised_through_json():
    plan = StudyPlan({"range": (0.1, 0.2), "n": np.int64(4)}, 0, 1, 1)
    assert plan.settings == {"range": [0.1, 0.2], "n": 4}
    assert json.loads(json.dumps(plan.describe()))["settings"] == plan.settings


@pytest.mark.parametrize("kwargs, message", [
    ({"n_items": 0}, "n_items"),
    ({"chunk_size": 0}, "chunk_size"),
    ({"chunk_size": 2.5}, "chunk_size"),
    ({"seed": -1}, "seed"),
    ({"seed": None}, "seed"),
    ({"settings": {"f": object()}}, "JSON"),
    ({"settings": [1, 2]}, "mapping"),
])
def test_plan_rejects_invalid_input(kwargs, message):
    args = {"settings": {}, "seed": 0, "n_items": 5, "chunk_size": 2} | kwargs
    with pytest.raises(ValueError, match=message):
        StudyPlan(**args)


@pytest.mark.parametrize("kwargs, message", [
    ({"backend": "threads"}, "serial, processes, dask"),
    ({"backend": "processes", "workers": 0}, "workers"),
    ({"backend": "processes", "workers": -2}, "workers"),
    ({"backend": "serial", "workers": 2}, "serial"),
    ({"backend": "dask"}, "scheduler"),
    ({"backend": "dask", "scheduler": "127.0.0.1:8786"}, "tcp://HOST:PORT"),
    ({"backend": "dask", "scheduler": "tcp://127.0.0.1"}, "tcp://HOST:PORT"),
    ({"scheduler": "tcp://127.0.0.1:99999"}, "1..65535"),
    ({"backend": "dask", "scheduler": "tcp://127.0.0.1:8786", "workers": 2}, "workers"),
    ({"backend": "processes", "scheduler": "tcp://127.0.0.1:8786"}, "scheduler"),
    ({"backend": "serial", "resume": True}, "out_dir"),
])
def test_run_study_rejects_invalid_execution_options(kwargs, message):
    with pytest.raises(ValueError, match=message):
        run_study(toy_tasks.trivial_task, StudyPlan({}, 0, 4, 2), progress=False, **kwargs)


# ------------------------------------------------------------------------- reproducibility


def test_rows_do_not_depend_on_chunking_and_match_direct_draws():
    expected = direct_table(seed=42, n_items=7, draws=3)
    for chunk_size in (1, 3, 7):
        table = run_study(toy_tasks.random_task, StudyPlan({"draws": 3}, 42, 7, chunk_size),
                          backend="serial", progress=False)
        assert_frame_equal(table, expected, check_dtype=False)


def test_backends_and_worker_counts_give_identical_results(dask_scheduler, capsys):
    plan = StudyPlan({"draws": 2}, seed=2024, n_items=9, chunk_size=2)
    expected = direct_table(2024, 9, 2)
    serial = run_study(toy_tasks.random_task, plan, backend="serial", progress=False)
    assert_frame_equal(serial, expected, check_dtype=False)
    runs = {
        "processes(1)": dict(backend="processes", workers=1),
        "processes(2)": dict(backend="processes", workers=2),
        "dask address": dict(scheduler=dask_scheduler),
    }
    for name, options in runs.items():
        capsys.readouterr()
        table = run_study(toy_tasks.random_task, plan, progress=True, **options)
        assert_frame_equal(table, serial, obj=name)
        assert table.attrs["study"]["backend"] == options.get("backend", "dask")
        assert table.attrs["study"]["workers"] == options.get("workers", 2)
        assert "5/5" in capsys.readouterr().err  # the progress bar followed every chunk
    distributed = pytest.importorskip("distributed")
    with distributed.Client(dask_scheduler, set_as_default=False) as client:
        table = run_study(toy_tasks.random_task, plan, scheduler=client, progress=False)
        assert_frame_equal(table, serial, obj="dask client")
        assert client.status == "running"  # a client passed in is left open


def test_process_workers_share_the_cores_instead_of_oversubscribing():
    table = run_study(toy_tasks.threads_task, StudyPlan({}, 0, 2, 1), backend="processes",
                      workers=2, progress=False)
    cap = max(1, os.cpu_count() // 2)  # two workers split the cores
    expected_numba = int(os.environ.get("NUMBA_NUM_THREADS", cap))  # an explicit choice wins
    assert table["numba_env"].tolist() == [expected_numba] * 2
    assert table["omp_env"].tolist() == [int(os.environ.get("OMP_NUM_THREADS", cap))] * 2
    assert table["numba_threads"].tolist() == [expected_numba] * 2


@pytest.fixture
def threaded_cluster():
    """A one-worker Dask cluster on loopback whose scheduler and worker run in this process, so
    that a test can stop them while a study runs."""
    distributed = pytest.importorskip("distributed")
    import dask

    # a cluster whose scheduler was stopped gives up reaching it at teardown after 1 s, not 30
    with dask.config.set({"distributed.comm.timeouts.connect": "1s"}), \
            distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                                     protocol="tcp", host="127.0.0.1", dashboard_address=":0",
                                     silence_logs=logging.CRITICAL) as cluster:
        yield cluster


def _stop_dask_in(seconds, cluster, what):
    def stop():
        if what == "workers":
            for worker in list(cluster.workers.values()):
                cluster.sync(worker.close)
        else:
            cluster.sync(cluster.scheduler.close)

    timer = threading.Timer(seconds, stop)
    timer.start()
    return timer


@pytest.mark.parametrize("what, message", [
    ("workers", r"no worker for 1 s"),
    ("scheduler", r"lost the connection to the Dask scheduler"),
])
def test_a_dask_cluster_that_dies_stops_the_study_with_a_clear_error(
        threaded_cluster, monkeypatch, tmp_path, what, message):
    monkeypatch.setattr(execution, "DASK_WORKER_TIMEOUT", 1.0)
    out = tmp_path / "study"
    settings = {"draws": 2, "sleep": 0.1}
    timer = _stop_dask_in(0.5, threaded_cluster, what)
    t0 = time.monotonic()
    try:
        with pytest.raises(StudyError, match=message) as info:
            run_study(toy_tasks.random_task, StudyPlan(settings, 3, 16, 1), out,
                      scheduler=threaded_cluster.scheduler_address, progress=False)
    finally:
        timer.join()
    assert time.monotonic() - t0 < 15  # a bounded wait, not for ever
    assert "of 16 chunks" in str(info.value) and "resume" in str(info.value)
    saved = len(list((out / "chunks").glob("chunk-*.npz")))
    assert 1 <= saved < 16
    table = run_study(toy_tasks.random_task, StudyPlan(settings, 3, 16, 1), out,
                      backend="serial", resume=True, progress=False)
    assert table.attrs["study"]["timings"]["chunks_resumed"] == saved
    assert_frame_equal(table, direct_table(3, 16, 2), check_dtype=False)


def test_a_chunk_that_kills_its_dask_workers_is_named():
    distributed = pytest.importorskip("distributed")
    chunk = StudyPlan({}, 0, 10, 4).chunk(1)

    class KilledFuture:  # what Dask reports once the chunk has killed its allowed workers
        status = "error"

        def exception(self):
            worker = types.SimpleNamespace(address="tcp://127.0.0.1:1")
            return distributed.KilledWorker("_run_chunk-1", worker, 3)

    with pytest.raises(StudyError, match=r"chunk 1 \(items 4\.\.7\) was lost with every"):
        execution._dask_result(KilledFuture(), chunk, "tcp://127.0.0.1:8786", "2 of 3")


def test_unreachable_scheduler_fails_fast_with_clear_message(monkeypatch, tmp_path):
    monkeypatch.setattr(execution, "SCHEDULER_TIMEOUT", 1.0)
    with socket.socket() as s:  # a port on which nothing listens
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    t0 = time.monotonic()
    with pytest.raises(ValueError, match=f"could not connect to the Dask scheduler at "
                                         f"tcp://127.0.0.1:{port}"):
        run_study(toy_tasks.trivial_task, StudyPlan({}, 0, 2, 1), tmp_path / "study",
                  scheduler=f"tcp://127.0.0.1:{port}", progress=False)
    assert time.monotonic() - t0 < 5.0
    assert not (tmp_path / "study").exists()  # nothing started, so a retry needs no --resume


# --------------------------------------------------------------------------- task results


@pytest.mark.parametrize("results, message", [
    ([{"a": [1], "b": [1, 2]}], "equal lengths"),
    ([{"a": [[1, 2]]}], "one-dimensional"),
    ([{"__chunk__": [1]}], "not starting with '__'"),
    ([{}], "non-empty dict"),
    ([[1, 2]], "non-empty dict"),
    ([{"a": [1]}, {"b": [1]}], "same columns"),
])
def test_invalid_task_result_is_reported(results, message):
    plan = StudyPlan({"results": results}, 0, len(results), 1)
    with pytest.raises(ValueError, match=message):
        run_study(toy_tasks.echo_task, plan, backend="serial", progress=False)


def test_task_exception_propagates_and_keeps_finished_chunks(tmp_path):
    plan = StudyPlan({}, 0, 6, 2)
    with pytest.raises(RuntimeError, match="chunk 1 failed"):
        run_study(toy_tasks.failing_task, plan, tmp_path, backend="serial", progress=False)
    assert chunk_path(tmp_path, 0).is_file()
    assert not chunk_path(tmp_path, 1).exists() and not chunk_path(tmp_path, 2).exists()


# --------------------------------------------------------------------- checkpoints, resume


def test_study_directory_holds_plan_chunks_and_results(tmp_path):
    plan = StudyPlan({"draws": 2, "note": "x"}, seed=5, n_items=5, chunk_size=2)
    table = run_study(toy_tasks.random_task, plan, tmp_path, backend="serial", progress=False)
    study = json.loads((tmp_path / "study.json").read_text())
    assert study["settings"] == {"draws": 2, "note": "x"}
    assert (study["seed"], study["n_items"], study["chunk_size"], study["n_chunks"]) == (5, 5, 2, 3)
    assert study["archquake_version"] == archquake.__version__
    assert study["task"] == "toy_tasks.random_task"
    files = sorted(p.name for p in (tmp_path / "chunks").iterdir())
    assert files == ["chunk-000000.npz", "chunk-000001.npz", "chunk-000002.npz"]
    with np.load(chunk_path(tmp_path, 1)) as data:  # chunk 1 = items 2, 3
        assert np.array_equal(data["item"], [2, 2, 3, 3])
    stored = load_study(tmp_path)
    assert_frame_equal(stored.table, table)
    assert_frame_equal(table, direct_table(5, 5, 2), check_dtype=False)
    assert stored.metadata["timings"]["chunks_computed"] == 3
    assert stored.metadata["seed"] == 5


def test_existing_directory_needs_resume_and_the_same_study(tmp_path):
    plan = StudyPlan({"draws": 2, "tolerance": 0.1}, seed=1, n_items=4, chunk_size=2)
    run_study(toy_tasks.random_task, plan, tmp_path, backend="serial", progress=False)
    with pytest.raises(ValueError, match="not empty.*resume=True"):
        run_study(toy_tasks.random_task, plan, tmp_path, backend="serial", progress=False)
    changed = StudyPlan({"draws": 2, "tolerance": 0.2}, seed=1, n_items=4, chunk_size=2)
    with pytest.raises(ValueError, match="setting 'tolerance' differs.*0.1.*0.2"):
        run_study(toy_tasks.random_task, changed, tmp_path, backend="serial", resume=True)
    with pytest.raises(ValueError, match="seed differs"):
        run_study(toy_tasks.random_task, StudyPlan(plan.settings, 2, 4, 2), tmp_path,
                  backend="serial", resume=True)
    with pytest.raises(ValueError, match=r"items per chunk \(chunk_size: .*\) differs: the "
                                         r"directory has 2, this study has 1"):
        run_study(toy_tasks.random_task, StudyPlan(plan.settings, 1, 4, 1), tmp_path,
                  backend="serial", resume=True)
    with pytest.raises(ValueError, match=r"kind of study \(task\) differs"):
        run_study(toy_tasks.busy_task, plan, tmp_path, backend="serial", resume=True)
    other = tmp_path / "other"
    other.mkdir()
    (other / "notes.txt").write_text("x")
    with pytest.raises(ValueError, match="holds no study.json"):
        run_study(toy_tasks.random_task, plan, other, backend="serial", resume=True)
    # resuming a finished study computes nothing and gives the same table
    again = run_study(toy_tasks.random_task, plan, tmp_path, backend="serial", resume=True,
                      progress=False)
    assert again.attrs["study"]["timings"]["chunks_computed"] == 0
    assert_frame_equal(again, direct_table(1, 4, 2), check_dtype=False)


def test_resume_after_killing_the_study_process(tmp_path):
    out, log = tmp_path / "study", tmp_path / "computed.log"
    settings = {"draws": 3, "sleep": 0.25, "log": str(log)}
    script = (
        f"import sys; sys.path[:0] = {[str(SRC), str(TESTS)]!r}\n"
        "import toy_tasks\n"
        "from archquake.execution import StudyPlan, run_study\n"
        f"plan = StudyPlan({settings!r}, seed=11, n_items=12, chunk_size=2)\n"
        f"run_study(toy_tasks.random_task, plan, {str(out)!r}, backend='serial', "
        "progress=False)\n"
    )
    proc = subprocess.Popen([sys.executable, "-c", script], start_new_session=True)
    try:
        deadline = time.monotonic() + 30
        while len(list((out / "chunks").glob("chunk-*.npz"))) < 2:
            assert proc.poll() is None, "the study process ended before it was killed"
            assert time.monotonic() < deadline, "the study process wrote no chunks"
            time.sleep(0.02)
        os.killpg(proc.pid, signal.SIGKILL)
    finally:
        proc.wait()
    assert proc.returncode == -signal.SIGKILL
    before = {p.name: p.stat().st_mtime_ns for p in (out / "chunks").glob("chunk-*.npz")}
    assert 2 <= len(before) < 6  # killed part way through

    plan = StudyPlan(settings, seed=11, n_items=12, chunk_size=2)
    table = run_study(toy_tasks.random_task, plan, out, backend="processes", workers=2,
                      resume=True, progress=False)

    for name, mtime in before.items():  # finished chunks were not rewritten ...
        assert (out / "chunks" / name).stat().st_mtime_ns == mtime
    computed = [int(line) for line in log.read_text().split()]
    for index in (int(name[6:12]) for name in before):  # ... nor recomputed
        assert computed.count(index) == 1
    assert set(computed) == set(range(6))
    assert table.attrs["study"]["timings"]["chunks_resumed"] == len(before)
    uninterrupted = run_study(toy_tasks.random_task, StudyPlan({"draws": 3}, 11, 12, 2),
                              backend="serial", progress=False)
    assert_frame_equal(table, uninterrupted)
    assert_frame_equal(load_study(out).table, uninterrupted)
    assert not list(out.rglob("*.tmp"))


def _pickled_chunk(path):
    with open(path, "wb") as f:
        np.savez(f, __chunk__=np.array([1, 2, 4]), item=np.array([object(), 1], dtype=object))


@pytest.mark.parametrize("damage", [
    lambda p: p.write_bytes(p.read_bytes()[:-40]),  # truncated
    lambda p: p.write_bytes(b"not a zip file at all"),  # garbage
    lambda p: p.write_bytes(b""),  # empty
    _pickled_chunk,  # an object array, which is never loaded (no pickles)
    lambda p: np.savez(p, item=np.arange(3)),  # no chunk header
    lambda p: np.savez(p, __chunk__=np.array([7, 0, 2]), __seconds__=np.array(0.0),
                       item=np.arange(3)),  # another chunk's header
], ids=["truncated", "garbage", "empty", "pickled", "headerless", "misplaced"])
def test_resume_recomputes_a_damaged_chunk_with_a_warning(tmp_path, damage):
    plan = StudyPlan({"draws": 2}, seed=4, n_items=6, chunk_size=2)
    run_study(toy_tasks.random_task, plan, tmp_path, backend="serial", progress=False)
    (tmp_path / "summary.json").unlink()
    path = chunk_path(tmp_path, 1)
    damage(path)
    with pytest.warns(StudyWarning, match=rf"{path}.*recomputed") as caught:
        table = run_study(toy_tasks.random_task, plan, tmp_path, backend="serial",
                          resume=True, progress=False)
    assert [str(w.message) for w in caught if w.category is StudyWarning][1:] == []
    assert table.attrs["study"]["timings"]["chunks_computed"] == 1
    assert_frame_equal(table, direct_table(4, 6, 2), check_dtype=False)
    with np.load(path) as data:  # written anew
        assert data["__chunk__"].tolist() == [1, 2, 4]


@pytest.mark.parametrize("content", [b"{\"format\": \"archquake-study\", ", b"\xff\xfe",
                                     b"[1, 2]"])
def test_a_damaged_study_json_names_the_file_and_the_way_out(tmp_path, content):
    plan = StudyPlan({}, 0, 4, 2)
    run_study(toy_tasks.trivial_task, plan, tmp_path, backend="serial", progress=False)
    (tmp_path / "study.json").write_bytes(content)
    with pytest.raises(ValueError, match=rf"{tmp_path / 'study.json'}.*start again"):
        run_study(toy_tasks.trivial_task, plan, tmp_path, backend="serial", resume=True,
                  progress=False)


def test_damaged_results_name_their_file(tmp_path):
    run_study(toy_tasks.trivial_task, StudyPlan({}, 0, 4, 2), tmp_path, backend="serial",
              progress=False)
    (tmp_path / "results.parquet").write_bytes(b"PAR1 garbage")
    with pytest.raises(ValueError, match=rf"{tmp_path / 'results.parquet'}"):
        load_study(tmp_path)
    (tmp_path / "summary.json").write_text("{")
    with pytest.raises(ValueError, match=rf"{tmp_path / 'summary.json'} is not valid JSON"):
        load_study(tmp_path)


# -------------------------------------------------------------------------------- progress


def test_progress_bar_counts_finished_chunks(capsys):
    plan = StudyPlan({}, 0, 5, 2)
    run_study(toy_tasks.trivial_task, plan, backend="serial", progress=True)
    err = capsys.readouterr().err
    assert "3/3" in err and "chunk" in err
    run_study(toy_tasks.trivial_task, plan, backend="serial", progress=False)
    assert capsys.readouterr().err == ""


def test_progress_bar_starts_at_resumed_chunks(tmp_path, capsys):
    plan = StudyPlan({}, 0, 6, 2)
    run_study(toy_tasks.trivial_task, plan, tmp_path, backend="serial", progress=False)
    chunk_path(tmp_path, 2).unlink()
    (tmp_path / "summary.json").unlink()
    run_study(toy_tasks.trivial_task, plan, tmp_path, backend="serial", resume=True)
    err = capsys.readouterr().err
    assert "2/3" in err and "3/3" in err and "0/3" not in err



WORKER_COMPILES = '''
import numba
import numpy as np
from archquake.execution import process_pool


def compile_in_worker(x):
    @numba.njit
    def twice(a):
        return 2.0 * a
    return float(twice(np.float64(x)))


if __name__ == "__main__":
    with process_pool(2) as pool:
        print(sum(pool.map(compile_in_worker, [1.0, 2.0])))
'''


def test_workers_compile_when_the_main_module_imported_numba(tmp_path):
    """A worker re-imports the parent's main module; if that imported numba, capping its
    threads through NUMBA_NUM_THREADS made every later compilation in the worker fail ('Cannot
    set NUMBA_NUM_THREADS to a different value once the threads have been launched')."""
    script = tmp_path / "study.py"
    script.write_text(WORKER_COMPILES)
    src = str(Path(__file__).resolve().parents[1] / "src")
    out = subprocess.run([sys.executable, str(script)], capture_output=True, text=True,
                         env={**os.environ, "PYTHONPATH": src}, timeout=120)
    assert out.returncode == 0, out.stderr[-2000:]
    assert float(out.stdout.split()[-1]) == 6.0


def test_closing_the_client_of_a_lost_cluster_logs_nothing_of_distributeds(monkeypatch,
                                                                            caplog):
    """After a lost scheduler, closing the client makes distributed log its cancelled
    reconnection with two tracebacks before our message: they are silenced; a study that
    ends well leaves the loggers as they were."""
    import logging

    pytest.importorskip("distributed")  # its loggers exist once it is imported, as in a study

    class Client:
        def close(self):
            logging.getLogger("distributed.client").error("Traceback (most recent call last)")

    def lost(*args):
        raise StudyError("lost the connection to the Dask scheduler")

    monkeypatch.setattr(execution, "_dask_client", lambda scheduler: (Client(), True))
    monkeypatch.setattr(execution, "_run", lost)
    caplog.set_level(logging.DEBUG)
    with pytest.raises(StudyError, match="lost the connection"):
        run_study(toy_tasks.trivial_task, StudyPlan({}, 0, 2, 1),
                  scheduler="tcp://127.0.0.1:8786", progress=False)
    assert not [r for r in caplog.records if r.name.startswith("distributed")]
    assert not logging.getLogger("distributed.client").disabled
    monkeypatch.setattr(execution, "_run", lambda *args: "table")
    assert run_study(toy_tasks.trivial_task, StudyPlan({}, 0, 2, 1),
                     scheduler="tcp://127.0.0.1:8786", progress=False) == "table"
    assert [r.name for r in caplog.records] == ["distributed.client"]  # not silenced then


@pytest.mark.parametrize("error", [ConnectionResetError("[Errno 104] Connection reset by peer"),
                                   ConnectionAbortedError("aborted")])
def test_a_reset_connection_to_the_scheduler_is_a_lost_scheduler(threaded_cluster, monkeypatch,
                                                                 tmp_path, error):
    # a connection reset while a result is fetched (the scheduler gone between two checks)
    # ends as the lost scheduler does: the words scheduler and resume, not a raw OSError
    original = execution._dask_result
    calls = {"n": 0}

    def flaky(future, chunk, address, unfinished):
        calls["n"] += 1
        if calls["n"] == 3:
            raise error
        return original(future, chunk, address, unfinished)

    monkeypatch.setattr(execution, "_dask_result", flaky)
    with pytest.raises(StudyError, match="lost the connection to the Dask scheduler") as info:
        run_study(toy_tasks.random_task, StudyPlan({"draws": 2, "sleep": 0.0}, 3, 8, 1),
                  tmp_path / "study", scheduler=threaded_cluster.scheduler_address,
                  progress=False)
    assert "resume" in str(info.value) and "chunks unfinished" in str(info.value)
    cause = info.value
    while cause is not None and not isinstance(cause, ConnectionError):
        cause = cause.__cause__
    assert isinstance(cause, type(error))  # the reset itself kept as the cause
