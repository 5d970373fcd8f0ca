"""How many signatures each compiled function has after a script runs in a fresh interpreter
(so that other tests' calls do not count): the probe of tests/test_compilation.py (the
four-link engine) and tests/rigid_blocks/test_rigid_blocks_compilation.py (the rigid blocks)."""

import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

RECORD = ROOT / "tests" / "data" / "decaying_sine.AT2"
"""A record file the scripts may read, as ``{record!r}``."""

COUNT = """
import json
import numba
counts = {{}}
for module in ({modules},):
    for name, f in vars(module).items():
        if isinstance(f, numba.core.registry.CPUDispatcher) and f.signatures:
            counts[name] = len(f.signatures)
print(json.dumps(counts))
"""


def compiled_signatures(script: str, modules: str, cache_dir=None) -> dict:
    """``{function name: number of signatures}`` of the compiled functions of ``modules`` (the
    names, as the script imports them, comma-separated) after ``script`` ran, with numba's
    on-disk cache or, given ``cache_dir``, an empty one."""
    env = {"PYTHONPATH": str(ROOT / "src")}
    if cache_dir is not None:
        env["NUMBA_CACHE_DIR"] = str(cache_dir)
    code = script.format(record=str(RECORD)) + COUNT.format(modules=modules)
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT,
                         env=env)
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout.splitlines()[-1])
