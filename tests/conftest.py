import math
import tomllib
from pathlib import Path

import pytest

from archquake import oppenheim

PAPER = tomllib.loads((Path(__file__).parent / "data" / "paper_values.toml").read_text())


@pytest.fixture(scope="session")
def paper():
    """The paper's published numbers (tests/data/paper_values.toml)."""
    return PAPER


@pytest.fixture(scope="session")
def nominal():
    """Oppenheim's arch NA."""
    return oppenheim()


DEG = math.pi / 180.0
