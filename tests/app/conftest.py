"""Fixtures of the page's tests: the command line's own answers (the independent reference the
page must agree with) and the page's application."""

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]

pytest.importorskip("starlette", reason="the app extra (starlette, uvicorn) is not installed")


def run_cli(*argv: str, cwd=None) -> subprocess.CompletedProcess:
    """``archquake argv`` in a fresh interpreter (as a user runs it)."""
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src")}
    return subprocess.run([sys.executable, "-m", "archquake", *argv], capture_output=True,
                          text=True, cwd=cwd or ROOT, env=env, timeout=300)


def cli_json(*argv: str) -> dict:
    """The ``--json`` output of ``archquake argv``."""
    done = run_cli(*argv, "--json")
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


def cli_error(*argv: str, cwd=None) -> str:
    """The one-line error of ``archquake argv`` (exit status 2), without ``archquake: error: ``."""
    done = run_cli(*argv, cwd=cwd)
    assert done.returncode == 2, (done.stdout, done.stderr)
    line = done.stderr.strip().splitlines()[-1]
    assert line.startswith("archquake: error: ")
    return line.removeprefix("archquake: error: ")


BAD_GEOMETRY = '{"blocks": [[[0, 0], [1, 0], [1, 1]]]}'
"""A geometry file the command line refuses: one block, where a mechanism needs four."""


def pytest_collection_modifyitems(items):
    """Starlette's test client warns that it will move from httpx to its successor; the page's
    tests use httpx, which it still supports."""
    for item in items:
        item.add_marker(pytest.mark.filterwarnings(
            "ignore:Using `httpx` with `starlette.testclient` is deprecated"))


@pytest.fixture()
def client(tmp_path):
    """The page's application in a test client (its jobs' workers are real processes)."""
    from starlette.testclient import TestClient

    from archquake.app.server import create_app

    app = create_app(tmp_path / "work", hosts=("testserver",), warm=False)
    with TestClient(app) as test_client:
        yield test_client
