"""What a first run compiles: every engine function once, whatever path calls it.

The functions of every module of :mod:`archquake.fourlink.engine` (and the ground motion's
``evaluate``) are counted by name; the names are distinct across the modules.

A function compiled for two argument types (read-only and writable arrays, a literal constant
and an int64) is compiled twice on a fresh clone: seconds each. The paths of the report --
a pulse response, a free vibration, a grid of pulses, a failure domain -- must all share one
compilation of each function. Run in a fresh process so that other tests' calls do not count.
"""

import pytest

from compilation_probe import compiled_signatures as probe

SCRIPT = """
import json
import numba
import numpy as np
from archquake import oppenheim
from archquake.fourlink import engine
from archquake import FourLinkModel
from archquake.ground_motion import oppenheim_pulse, read_record
from archquake.fourlink.mechanism import mechanisms
from archquake.fourlink.time_history import free_vibration, simulate
from archquake.studies.failure_domain import domain_of

arch = oppenheim()
pair = mechanisms(arch)
simulate(pair, oppenheim_pulse(-9.81, 0.27), (0.875, 0.875))
simulate(pair, oppenheim_pulse(-9.81, 0.27), (0.875, 0.875), record=False)
simulate(pair, read_record({record!r}, scale_to=0.5), (0.875, 0.875))
free_vibration(pair, (1.0, 1.0), phi0=0.02, t_end=2.0)
domain_of(FourLinkModel.from_arch(arch), [0.3, 0.4], np.linspace(0.3, 1.0, 8), resolution_g=0.01,
          extend_to_g=None)
tables = [engine.tabulate(m) for m in pair]
tables[0].functions(np.linspace(tables[0].theta_lo, tables[0].theta_u, 5))
from archquake.fourlink.engine import driver, rules, stepper, tables
import archquake.ground_motion as gm
"""


def compiled_signatures(cache_dir=None) -> dict:
    return probe(SCRIPT, "driver, rules, stepper, tables, gm", cache_dir)


def test_every_engine_entry_point_is_compiled_once():
    """With the on-disk cache, the entry points called from Python are loaded once per
    signature: two signatures of integrate would be two compilations on a fresh clone."""
    counts = compiled_signatures()
    assert counts.get("integrate") == 1 and counts.get("_grid") == 1
    twice = {name: n for name, n in counts.items() if n > 1}
    assert not twice, f"compiled more than once: {twice}"


@pytest.mark.slow
def test_every_engine_function_is_compiled_once_on_a_fresh_cache(tmp_path):
    """Everything compiled from scratch (about 30 s): the helpers too."""
    counts = compiled_signatures(tmp_path)
    assert counts.get("dop853_step") == 1 and counts.get("dense_coefficients") == 1
    twice = {name: n for name, n in counts.items() if n > 1}
    assert not twice, f"compiled more than once: {twice}"
