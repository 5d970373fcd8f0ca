"""What the page's answers are checked against: the command line's own answers, in a fresh
interpreter, as a user runs it."""

import json
import os
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


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


def fields_named(message: str) -> str:
    """The command line's ``message`` as the page says it: each option named by its field
    (``--fill-cover`` is ``fill_cover``, ``--param`` is ``params``), without what its value
    looks like (``--fill-cover M`` is ``fill_cover``)."""
    return re.sub(r"--([a-z][a-z-]*)(?: [A-Z]+\b)?",
                  lambda m: "params" if m[1] == "param" else m[1].replace("-", "_"), message)


BAD_GEOMETRY = '{"blocks": [[[0, 0], [1, 0], [1, 1]]]}'
"""A geometry file the command line refuses: one block, where a mechanism needs four."""
