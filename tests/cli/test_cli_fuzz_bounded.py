"""Fuzzing the command line under a memory limit: each command line runs as its own process
with at most :data:`MEMORY_BYTES` of address space (``resource.setrlimit``) and
:data:`SECONDS` of time, and must end as in this process (result or one error line, status 0 or
2, no traceback, no MemoryError). Fewer examples than the in-process fuzzers: each pays for a
Python start and numpy's import."""

import os
import resource
import subprocess
import sys
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from test_cli_fuzz import COMMAND_LINES

from fuzzing import check_run

pytestmark = [pytest.mark.fuzz,
              pytest.mark.skipif(not hasattr(resource, "RLIMIT_AS"), reason="POSIX limits")]

MEMORY_BYTES = 3 * 2**30
"""Address space of a fuzzed command [bytes]: the largest grids and arches the command line
accepts fit well within it (a domain of a million analyses takes about 200 MB)."""
SECONDS = 300
"""Time of a fuzzed command [s]."""

SRC = Path(__file__).parents[2] / "src"
LARGE = st.sampled_from([
    ["domain", "--durations", "0.1:1:0.01", "--amplitudes", "0.05:1.5:0.01", "--json"],
    ["limit", "--voussoirs", "10000", "--json"],
    ["limit", "--shape", "parabolic", "--span", "10", "--rise", "4", "--voussoirs", "2000",
     "--json"],
    ["simulate", "--motion", "harmonic", "--cycles", "10000", "--amplitude", "0.2", "--json"],
    ["simulate", "--motion", "stochastic", "--param", "duration=600", "--param", "dt=0.001",
     "--json"],
])


def _limited():
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY_BYTES, MEMORY_BYTES))


@settings(max_examples=max(3, settings().max_examples // 5))
@given(st.one_of(LARGE, COMMAND_LINES.map(lambda parts: [*parts[0], *parts[1]]).filter(
    lambda argv: not any("\x00" in arg for arg in argv))))  # no process takes a NUL argument
def test_a_command_line_stays_within_its_memory_and_time(argv):
    env = {**os.environ, "PYTHONPATH": str(SRC)}
    run = subprocess.run([sys.executable, "-m", "archquake.cli", *argv], env=env,
                         capture_output=True, text=True, timeout=SECONDS,
                         preexec_fn=_limited)
    assert "MemoryError" not in run.stderr, (argv, run.stderr[-2000:])
    status = run.returncode
    if status == 2 and "usage:" in run.stderr:
        status = ("argparse", 2)
    check_run(argv, status, run.stdout, run.stderr)
