"""The record-based (multiple-stripe) study with the rigid-block model: levels searched like
amplitudes, the same outcomes as the exhaustive stripes, rows equal to direct analyses."""

import numpy as np
import pytest

from archquake.ground_motion import RecordSuite
from archquake.rigid_blocks import RigidBlockModel
from archquake.studies.record_fragility import RecordFragilitySettings, run_record_fragility

SUITE = RecordSuite.from_stochastic(1, seed=4, significant_duration=2.0, duration=4.0)
LEVELS = tuple(np.round(np.arange(0.3, 2.01, 0.25), 2))


@pytest.fixture(scope="module")
def studies():
    out = {}
    for search in ("exhaustive", "screened", "bisection"):
        settings = RecordFragilitySettings(suite=SUITE, levels=LEVELS, sample_size=1, seed=2,
                                           model="rigid-blocks", search=search, stride=2,
                                           bootstrap=10)
        out[search] = run_record_fragility(settings, backend="serial", progress=False)
    return out


def test_screened_stripes_equal_the_exhaustive_ones(studies):
    exhaustive, screened = studies["exhaustive"], studies["screened"]
    assert exhaustive.table["integrated"].all()
    np.testing.assert_array_equal(screened.table["status"], exhaustive.table["status"])
    np.testing.assert_array_equal(screened.probability, exhaustive.probability)
    assert exhaustive.summary()["settings"]["model"] == "rigid-blocks"


def test_rows_are_the_rigid_block_outcomes_of_the_scaled_records(studies):
    result = studies["exhaustive"]
    sample = result.settings.sample
    motion = SUITE.motions()[0]
    table = result.table
    for _, row in table.iloc[::5].iterrows():
        arch = result.settings.nominal if row["arch"] < 0 else sample.arch(int(row["arch"]))
        factor = row["polarity"] * row["scale_factor"]
        expected = RigidBlockModel(arch).outcome(motion.scaled(factor)).status
        assert int(expected) == row["status"]


def test_bisection_needs_fewer_analyses(studies):
    analysed = {s: int(r.table["integrated"].sum()) for s, r in studies.items()}
    assert analysed["bisection"] <= analysed["screened"] <= analysed["exhaustive"]
