"""Where the stripes of a record-based fragility go (archquake.studies.stripes): the pilot's
first collapsing factor checked against single analyses of the scaled records, and the levels
against the formula of the module's docstring, computed here from hand-made pilots."""

import math

import numpy as np
import pytest

from archquake.fourlink import FourLinkModel
from archquake.ground_motion.suites import RecordSuite
from archquake.status import Status
from archquake.studies.record_fragility import STOCHASTIC_SUITE
from archquake.studies.stripes import (
    PILOT_RANGE,
    median_collapse_pga,
    record_pilot,
    stripe_levels,
)


class Suite:
    """Records known only by their intensities (what stripe_levels reads of a suite)."""

    def __init__(self, **values):
        self.values = {k: np.asarray(v, dtype=float) for k, v in values.items()}

    def intensities(self, name):
        return self.values[name]


def four_digits(x):
    return float(f"{x:.4g}")


def test_levels_span_the_first_collapses_of_the_records():
    pilot = {"pga_levels": [0.3, 3.0], "pga": [0.5, 1.0, 0.25], "first_factor": [2.0, 0.6, 4.0]}
    suite = Suite(pga=[0.5, 1.0, 0.25], pgv=[0.4, 0.5, 0.1])
    # PGA at the first collapse: 1.0, 0.6, 1.0 g -> 0.48 ... 1.25 g
    expected = [four_digits(0.48 * (1.25 / 0.48) ** (j / 4)) for j in range(5)]
    assert stripe_levels(pilot, suite, "pga", 5) == pytest.approx(expected, rel=0, abs=0)
    # PGV scales with the record: 0.8, 0.3, 0.4 m/s; the weaker arches lower the first stripe
    levels = stripe_levels(pilot, suite, "pgv", 4, weaker=0.5)
    assert levels[0] == four_digits(0.8 * 0.5 * 0.3) and levels[-1] == four_digits(1.25 * 0.8)
    assert np.allclose(np.diff(np.log(levels)), np.log(1.0 / 0.12) / 3, rtol=1e-3)


def test_records_that_do_not_collapse_raise_the_top_to_the_pilots():
    pilot = {"pga_levels": [0.3, 3.0], "pga": [0.5, 1.0, 0.25], "first_factor": [2.0, None, None]}
    suite = Suite(pga=[0.5, 1.0, 0.25])
    levels = stripe_levels(pilot, suite, "pga", 3)
    assert levels[0] == four_digits(0.8 * 1.0) and levels[-1] == 3.0  # the median top: 3 g
    none = {**pilot, "first_factor": [None, None, None]}
    assert stripe_levels(none, suite, "pga", 3) == (0.3, four_digits(math.sqrt(0.9)), 3.0)


def test_median_collapse_pga():
    pilot = {"pga": [0.5, 1.0, 0.25, 2.0], "first_factor": [2.0, 0.6, None, 0.8]}
    # first collapses 1.0, 0.6, none, 1.6 g: the lower median of (0.6, 1.0, 1.6, inf)
    assert median_collapse_pga(pilot) == 1.0
    assert median_collapse_pga({**pilot, "first_factor": [None, None, None, 0.123456]}) == 0.2469
    assert median_collapse_pga({**pilot, "first_factor": [None] * 4}) is None


def test_pilot_finds_the_first_collapse_of_each_record(nominal):
    model = FourLinkModel.from_arch(nominal, "paper")
    suite = RecordSuite.from_stochastic(2, 3, **STOCHASTIC_SUITE)
    pilot = record_pilot(model, suite)
    grid = min(model.load_multipliers) * np.geomspace(*PILOT_RANGE)
    assert pilot["pga_levels"] == pytest.approx(grid, rel=1e-15)
    assert pilot["pga"] == pytest.approx(suite.intensities("pga"), rel=1e-15)

    def collapses(motion, factor):
        return any(model.outcome(motion.scaled(sign * factor)).status == Status.COLLAPSE
                   for sign in (1.0, -1.0))

    found = 0
    for motion, pga, first in zip(suite.motions(), pilot["pga"], pilot["first_factor"],
                                  strict=True):
        factors = grid / pga
        if first is None:
            assert not collapses(motion, factors[-1])
            continue
        found += 1
        i = int(np.argmin(np.abs(factors - first)))
        assert factors[i] == first and collapses(motion, first)
        assert i == 0 or not collapses(motion, factors[i - 1])
    assert found


def test_the_pilot_of_the_rigid_blocks_stops_at_the_first_collapse(nominal):
    """A model of single analyses (the rigid blocks) is run up the grid until the first level
    that collapses the structure: that level collapses it under single analyses, the level
    below does not, and a record is run twice (both polarities) at every level up to it."""
    from archquake.rigid_blocks import RigidBlockModel

    model = RigidBlockModel(nominal)
    suite = RecordSuite.from_stochastic(2, 3, **STOCHASTIC_SUITE)
    pilot = record_pilot(model, suite)
    grid = min(model.load_multipliers) * np.geomspace(*PILOT_RANGE)
    assert pilot["pga_levels"] == pytest.approx(grid, rel=1e-15) and pilot["undecided"] == 0

    def collapses(motion, factor):
        return any(model.outcome(motion.scaled(sign * factor)).status == Status.COLLAPSE
                   for sign in (1.0, -1.0))

    for motion, pga, first, runs in zip(suite.motions(), pilot["pga"], pilot["first_factor"],
                                        pilot["analyses"], strict=True):
        factors = grid / pga
        if first is None:
            assert runs == 2 * factors.size
            continue
        i = int(np.argmin(np.abs(factors - first)))
        assert factors[i] == first and collapses(motion, first) and runs == 2 * (i + 1)
        assert i == 0 or not collapses(motion, factors[i - 1])
