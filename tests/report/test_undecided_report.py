"""The reports keep undecided rigid-block analyses apart: counted, a failure acceleration above
an undecided band given as a range and never compared, a warning first when there are many.

The rigid-block model is forced to leave chosen analyses undecided (``forced_undecided``); the
expected values are counted from the calls it received and the forced pattern.
"""

import numpy as np
import pytest

import forced_undecided as forced
from archquake import oppenheim
from archquake.fourlink import FourLinkModel
from archquake.ground_motion import RecordSuite
from archquake.report.assess import parts as assess_parts
from archquake.report.assess import records as assess_records
from archquake.report.assess import text as assess_text
from archquake.report.paper import parts as paper_parts
from archquake.report.paper import text as paper_text
from archquake.rigid_blocks import RigidBlockModel
from archquake.status import Status
from archquake.studies.comparison import compare_models
from archquake.studies.failure_domain import FailureDomain, domain_of
from archquake.studies.undecided import undecided_warning

DURATIONS = (0.4, 0.6)
GRID = np.round(np.arange(0.2, 1.2001, 0.05), 10)


@pytest.fixture
def calls(monkeypatch):
    return forced.force(monkeypatch)


def test_assessment_pulse_part_bounds_the_rigid_blocks_failure(calls):
    arch = oppenheim()
    rigid = domain_of(RigidBlockModel(arch), DURATIONS, GRID, resolution_g=1e-3,
                      extend_to_g=None, search="exhaustive")
    four_link = assess_parts.four_link_domains(FourLinkModel.from_arch(arch), DURATIONS, GRID,
                                               1e-3)
    part = assess_parts.pulse_part(four_link, rigid, "l", GRID)
    made = sum(1 for c in calls if c[2] is Status.UNDECIDED)
    summary = part.summary
    assert summary["rigid_blocks"]["undecided"] == made > 0
    short, long = summary["rows"]
    k_l = RigidBlockModel(arch).load_multipliers[0]
    low = k_l * forced.UNDECIDED_BAND[0]
    assert abs(short["rigid_blocks_undecided_from"] - low) <= 1e-3
    assert short["difference"] is None and long["difference"] is not None
    assert long["rigid_blocks_undecided_from"] is None
    assert short["rigid_blocks_undecided"] + long["rigid_blocks_undecided"] == made
    # the same domain, kept and rebuilt, keeps its counts
    kept = rigid.to_dict()
    assert FailureDomain.from_dict(kept).undecided == rigid.undecided
    del kept["undecided"]  # as a domain kept before undecided analyses were counted
    assert FailureDomain.from_dict(kept).undecided == ()
    results = {"pulses": summary}
    rows = assess_text.domain_rows(results)
    assert rows[0][2] == f"{short['rigid_blocks_undecided_from']:.3f}-{short['rigid_blocks']:.3f}"
    assert assess_text.undecided_warning_text(results) == undecided_warning(
        made, len(calls), "rigid-block analyses")


def test_assessment_record_check_counts_undecided_pairs_apart():
    suite = RecordSuite.from_stochastic(2, seed=4, significant_duration=2.0, duration=4.0)
    model = FourLinkModel.from_arch(oppenheim())
    rigid = [[int(Status.UNDECIDED), 2], [0, int(Status.UNDECIDED)]]
    level = 0.6
    check = assess_records.record_check(model, suite, level, rigid)
    from archquake.studies.record_fragility import record_outcomes

    expected = {"both": 0, "neither": 0, "four_link_only": 0, "rigid_blocks_only": 0}
    for motion, pga, rb in zip(suite.motions(), suite.intensities("pga"), rigid, strict=True):
        factor = level / float(pga)
        for a, b in zip(record_outcomes(model, motion, [factor, -factor])["status"], rb,
                        strict=True):
            if b != -1:
                expected[{(True, True): "both", (False, False): "neither",
                          (True, False): "four_link_only",
                          (False, True): "rigid_blocks_only"}[(a == 2, b == 2)]] += 1
    assert check["rigid_blocks_undecided"] == 2
    assert {k: check[k] for k in expected} == expected
    assert check["agree"] == (expected["both"] + expected["neither"]) / 4
    assert "undecided in 2" in assess_text.check_words(check)


def test_reproduction_comparison_does_not_compare_an_undecided_failure(calls):
    comparison = compare_models(oppenheim(), DURATIONS, amplitudes_g=GRID, resolution_g=1e-3,
                                restitutions=("paper",), search="exhaustive")
    summary = {"rows": comparison.to_list(), "restitution": comparison.restitution,
               "scan_g": [float(GRID[0]), float(GRID[-1]), 0.05]}
    stats = paper_parts.comparison_statistics(summary)
    assert stats["difference"]["paper"][0.4] is None
    assert stats["difference"]["paper"][0.6] is not None
    rows = paper_text.comparison_rows(summary)
    low = comparison.rigid_block_undecided_from_g()[0]
    assert rows[0][1].startswith(f"{low:.3f}-") and "%" not in rows[0][2]
    assert "%" in rows[1][2]
