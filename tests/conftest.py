import math

import pytest

from archquake import oppenheim
from archquake.reference_arches import paper_values

PAPER = paper_values()


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
