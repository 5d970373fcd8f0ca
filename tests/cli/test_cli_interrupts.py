"""Stopping a study: Ctrl-C (SIGINT) and SIGTERM end it cleanly, with no traceback and no worker
process left behind, and the study continues with --resume."""

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pandas as pd
import pytest

from archquake.cli import main
from archquake.results_io import load_study
from archquake.studies.failure_domain import inclusive_range
from archquake.studies.fragility import FragilitySettings, run_fragility

pytestmark = pytest.mark.skipif(not Path("/proc/self/stat").exists(),
                                reason="lists processes through /proc (Linux)")
SRC = Path(__file__).parents[2] / "src"
# long enough (about 2 s of work after the first chunk) that the signal always finds it running,
# even when the first chunk is late because the workers compile the engine (a fresh clone)
STUDY = ["fragility", "--samples", "100", "--durations", "0.4", "--amplitudes", "0.3:0.9:0.001",
         "--limit-samples", "4", "--seed", "11", "--no-progress"]


@pytest.fixture(scope="module")
def uninterrupted():
    settings = FragilitySettings(sample_size=100, durations=(0.4,),
                                 amplitudes_g=tuple(inclusive_range(0.3, 0.9, 0.001)),
                                 limit_sample_size=4, seed=11)
    return run_fragility(settings, backend="serial", progress=False).table


def _sigint_default() -> None:
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def _running_in_group(pgid: int) -> list[int]:
    """Processes of process group ``pgid`` that are still running (zombies left to an init
    that does not reap them are not)."""
    running = []
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
        except OSError:
            continue
        if int(fields[2]) == pgid and fields[0] != "Z":
            running.append(int(stat.parent.name))
    return running


@pytest.mark.parametrize("signum, whole_group", [(signal.SIGINT, True),
                                                 (signal.SIGTERM, False)])
def test_a_signal_stops_the_study_cleanly_and_it_resumes(tmp_path, capsys, uninterrupted,
                                                         signum, whole_group):
    out = tmp_path / "study"
    env = {**os.environ, "PYTHONPATH": str(SRC)}
    # a command started in the background by a shell without job control inherits SIGINT
    # ignored, and so would the study: it is started here as from a terminal, SIGINT default
    proc = subprocess.Popen([sys.executable, "-m", "archquake.cli", *STUDY, "--workers", "2",
                             "--out", str(out)], env=env, start_new_session=True,
                            preexec_fn=_sigint_default,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        deadline = time.monotonic() + 60
        while not list((out / "chunks").glob("chunk-*.npz")):
            assert proc.poll() is None, proc.communicate()
            assert time.monotonic() < deadline, "the study wrote no chunk"
            time.sleep(0.02)
        # Ctrl-C in a terminal signals the whole process group; kill(1) only the study
        if whole_group:
            os.killpg(proc.pid, signum)
        else:
            os.kill(proc.pid, signum)
        _, err = proc.communicate(timeout=30)
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
    assert proc.returncode == 128 + signum, err
    assert "Traceback" not in err
    assert "interrupted" in err and "--resume" in err
    deadline = time.monotonic() + 10  # pool workers and the resource tracker are gone
    while _running_in_group(proc.pid):
        assert time.monotonic() < deadline, "processes of the study survived it"
        time.sleep(0.05)
    assert not (out / "summary.json").exists()
    assert main([*STUDY, "--out", str(out), "--resume", "--json"]) == 0
    capsys.readouterr()
    pd.testing.assert_frame_equal(load_study(out).table, uninterrupted)
    assert not list(out.rglob("*.tmp"))


def test_sigterm_is_turned_into_an_interrupt_only_around_worker_processes(monkeypatch):
    from archquake.cli import _signals, main_fragility, main_limit

    default = signal.getsignal(signal.SIGTERM)
    seen = []

    def spy(args):
        seen.append(signal.getsignal(signal.SIGTERM))
        return 0

    monkeypatch.setattr(main_limit, "run", spy)
    monkeypatch.setattr(main_fragility, "run", spy)
    assert main(["limit"]) == 0
    assert main(["fragility", "--out", "unused", "--workers", "2"]) == 0
    assert main(["fragility", "--out", "unused"]) == 0
    # a command in this process keeps the default action (a Python handler would wait for a
    # long compiled loop to return); a study on workers stops them cleanly
    assert seen == [default, _signals.raise_terminated, default]
    assert signal.getsignal(signal.SIGTERM) == default


def _interrupt_from_compiled_code():
    """What Ctrl-C during a numba-compiled call raises: CPython's ``SystemError`` ("returned a
    result with an exception set") whose cause is the KeyboardInterrupt."""
    try:
        raise KeyboardInterrupt
    except KeyboardInterrupt as interrupt:
        raise SystemError("CPUDispatcher(<function outcomes>) returned a result with an "
                          "exception set") from interrupt


@pytest.mark.parametrize("stop_at", [1, 3])
def test_ctrl_c_inside_compiled_code_of_a_record_study_is_an_interrupt(tmp_path, capsys,
                                                                      monkeypatch, stop_at):
    """Ctrl-C while an arch of a record study runs in compiled code is "interrupted", exit 130
    (128 + SIGINT = 128 + 2), not "irregular arch N stopped the study: SystemError"; the
    study then resumes to the table of an uninterrupted run."""
    from archquake.studies import record_fragility

    data = Path(__file__).parents[1] / "data" / "decaying_sine.csv"
    argv = ["record-fragility", "--records", str(data), "--levels", "0.3:0.9:0.3",
            "--samples", "3", "--seed", "5", "--no-progress", "--json"]
    real, calls = record_fragility.record_outcomes, []

    def interrupted_at(*args, **kwargs):
        calls.append(1)
        if len(calls) == stop_at + 1:  # the nominal arch is call 1
            _interrupt_from_compiled_code()
        return real(*args, **kwargs)

    monkeypatch.setattr(record_fragility, "record_outcomes", interrupted_at)
    out = tmp_path / "study"
    assert main([*argv, "--out", str(out)]) == 130
    err = capsys.readouterr().err
    assert err.startswith("archquake: interrupted (SIGINT)") and "--resume" in err
    assert "stopped the study" not in err and "SystemError" not in err
    monkeypatch.setattr(record_fragility, "record_outcomes", real)
    assert main([*argv, "--out", str(out), "--resume"]) == 0
    assert main([*argv, "--out", str(tmp_path / "whole")]) == 0
    capsys.readouterr()
    pd.testing.assert_frame_equal(load_study(out).table, load_study(tmp_path / "whole").table)


def test_ctrl_c_inside_compiled_code_of_a_pulse_study_is_an_interrupt(tmp_path, capsys,
                                                                     monkeypatch):
    from archquake.studies import fragility

    def interrupted(*args, **kwargs):
        _interrupt_from_compiled_code()

    monkeypatch.setattr(fragility, "model_outcomes", interrupted)
    assert main(["fragility", "--samples", "2", "--durations", "0.4", "--amplitudes",
                 "0.3:0.5:0.1", "--limit-samples", "2", "--no-progress",
                 "--out", str(tmp_path / "s")]) == 130
    err = capsys.readouterr().err
    assert err.startswith("archquake: interrupted (SIGINT)") and "stopped the study" not in err


def test_ctrl_c_inside_compiled_code_of_an_assessment_is_an_interrupt(tmp_path, capsys,
                                                                      monkeypatch):
    """As in a study: the assessment's record studies and domains run compiled code too."""
    from archquake.report.assess import assessment

    def interrupted(*args, **kwargs):
        _interrupt_from_compiled_code()

    monkeypatch.setattr(assessment, "_compute", interrupted)
    assert main(["assess", "--quick", "--out", str(tmp_path / "a"), "--no-progress"]) == 130
    err = capsys.readouterr().err
    assert err.startswith("archquake: interrupted (SIGINT)") and "SystemError" not in err
