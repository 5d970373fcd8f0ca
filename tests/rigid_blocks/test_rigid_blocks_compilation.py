"""What a first run of the rigid-block model compiles: every solver function once, whatever path
calls it (as tests/test_compilation.py checks for the four-link engine).

An outcome, a recorded history, a record ground motion, a failure slice on a worker-like copy of
the assembly, a single block and the impact measurement all reach the one driver
(:func:`archquake.rigid_blocks.solver.run`) with the same argument types: two signatures would be
two compilations of seconds each on a fresh clone. Run in a fresh process so that other tests'
calls do not count.
"""

import json
import pickle
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]

SCRIPT = """
import json
import pickle
import numba
import numpy as np
from archquake import oppenheim
from archquake.geometry import GRAVITY
from archquake.ground_motion import oppenheim_pulse, read_record
from archquake.rigid_blocks import (block_outcome, from_arch, rectangular_block,
                                    simulate_blocks)
from archquake.rigid_blocks import RigidBlockModel
from archquake.studies.failure_domain import domain_of
from archquake.rigid_blocks.impacts import closing_impact

arch = oppenheim()
pulse = oppenheim_pulse(-0.5 * GRAVITY, 0.2)
block_outcome(arch, pulse)
simulate_blocks(arch, pulse, t_end=0.05)
block_outcome(arch, read_record({record!r}, scale_to=0.1))
copy = pickle.loads(pickle.dumps(from_arch(arch)))  # as a worker process receives it
domain_of(RigidBlockModel(copy), [0.2], [0.1, 0.2], resolution=0.1, extend_to_g=None)
block_outcome(rectangular_block(0.4, 2.0), None)
closing_impact(arch, np.ones((7, 3)))
from archquake.rigid_blocks import solver
import archquake.ground_motion as gm
counts = {{}}
for module in (solver, gm):
    for name, f in vars(module).items():
        if isinstance(f, numba.core.registry.CPUDispatcher) and f.signatures:
            counts[name] = len(f.signatures)
print(json.dumps(counts))
"""


def compiled_signatures(cache_dir=None) -> dict:
    env = {"PYTHONPATH": str(ROOT / "src")}
    if cache_dir is not None:
        env["NUMBA_CACHE_DIR"] = str(cache_dir)
    record = str(ROOT / "tests" / "data" / "decaying_sine.AT2")
    out = subprocess.run([sys.executable, "-c", SCRIPT.format(record=record)],
                         capture_output=True, text=True, cwd=ROOT, env=env)
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout.splitlines()[-1])


def test_every_rigid_block_entry_point_is_compiled_once():
    """With the on-disk cache, the driver and the functions called from Python are loaded once
    per signature."""
    counts = compiled_signatures()
    assert counts.get("run") == 1
    twice = {name: n for name, n in counts.items() if n > 1}
    assert not twice, f"compiled more than once: {twice}"


@pytest.mark.slow
def test_every_rigid_block_function_is_compiled_once_on_a_fresh_cache(tmp_path):
    """Everything compiled from scratch: the helpers too."""
    counts = compiled_signatures(tmp_path)
    assert counts.get("run") == 1 and counts.get("contact_geometry") == 1
    twice = {name: n for name, n in counts.items() if n > 1}
    assert not twice, f"compiled more than once: {twice}"


def test_pickled_assembly_keeps_its_packed_arrays_writable():
    """A worker unpickles the assembly with its cached packed arrays: they stay writable, so the
    driver is not compiled again for read-only arrays."""
    from archquake import oppenheim
    from archquake.rigid_blocks import from_arch
    from archquake.rigid_blocks.dynamics import contact_arrays

    assembly = from_arch(oppenheim())
    contact_arrays(assembly)
    copy = pickle.loads(pickle.dumps(assembly))
    for name, array in contact_arrays(copy).items():
        assert array.flags.writeable and array.flags.c_contiguous, name
