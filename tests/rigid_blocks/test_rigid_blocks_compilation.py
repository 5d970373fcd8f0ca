"""What a first run of the rigid-block model compiles: every solver function once, whatever path
calls it (as tests/test_compilation.py checks for the four-link engine).

An outcome, a recorded history, a record ground motion, a failure slice on a worker-like copy of
the assembly, a single block and the impact measurement all reach the one driver
(:func:`archquake.rigid_blocks.solver.run`) with the same argument types: two signatures would be
two compilations of seconds each on a fresh clone. Run in a fresh process so that other tests'
calls do not count.
"""

import pickle

import pytest

from compilation_probe import compiled_signatures as probe

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
domain_of(RigidBlockModel(copy), [0.2], [0.1, 0.2], resolution_g=0.1, extend_to_g=None)
block_outcome(rectangular_block(0.4, 2.0), None)
closing_impact(arch, np.ones((7, 3)))
from archquake.geometry import circular_arch
many = circular_arch(10.0, 2.748893571891069, 1.5, 15)  # the active set cycles: Lemke solves
assert block_outcome(many, oppenheim_pulse(-1.0 * GRAVITY, 0.27)).fallback_steps > 0
from archquake.rigid_blocks import band, contact_problem, contacts, lemke, solver
import archquake.ground_motion as gm
"""


def compiled_signatures(cache_dir=None) -> dict:
    return probe(SCRIPT, "contacts, band, contact_problem, lemke, solver, gm", cache_dir)


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
    assert counts.get("lemke") == 1 and counts.get("solve_lemke") == 1
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
