import math
import os

import pytest
from hypothesis import HealthCheck, settings

from archquake import oppenheim
from archquake.reference_arches import paper_values

PAPER = paper_values()


@pytest.fixture(autouse=True)
def _no_compile_notes(monkeypatch):
    """The command line's note that it is compiling an engine (archquake.compiled) depends on
    what numba's cache holds when a test runs, which on a fresh clone is the order of the tests:
    the tests of the command line's output see none. tests/test_compiled.py tests the notes."""
    from archquake import compiled

    monkeypatch.setattr(compiled, "enable_notes", lambda enabled=True: None)


@pytest.fixture(scope="session")
def paper():
    """The paper's published numbers (src/archquake/data/paper_values.toml)."""
    return PAPER


@pytest.fixture(scope="session")
def nominal():
    """Oppenheim's arch NA."""
    return oppenheim()


DEG = math.pi / 180.0


@pytest.fixture(scope="session")
def data_dir():
    """The folder of the tests' data files (records, regression fixtures)."""
    from pathlib import Path

    return Path(__file__).parent / "data"


# Property-based tests (Hypothesis): "ci", the default, runs few examples so that the whole suite
# stays fast; "fuzz" (make fuzz: HYPOTHESIS_PROFILE=fuzz pytest -m fuzz) runs many. The time of
# an example is bounded by the tests themselves (tests/fuzzing.py), not by Hypothesis's
# deadline, which a shared machine would trip.
settings.register_profile("ci", max_examples=20, deadline=None, derandomize=True,
                          database=None, suppress_health_check=[HealthCheck.too_slow])
settings.register_profile("fuzz", max_examples=400, deadline=None,
                          suppress_health_check=[HealthCheck.too_slow])
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))
