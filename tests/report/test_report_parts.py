"""The parts of the paper's reproduction run alone: each, called with its inputs, returns the
paper's numbers where the paper prints them, and the same values as in the whole report (the
regression fixture of ``reproduce --quick``)."""

import numpy as np
import pytest
from report_regression import assert_same, load_fixture

from archquake import oppenheim
from archquake.report.paper import parts
from archquake.report.paper.settings import ARCH_NAMES, ReproductionSettings
from archquake.report.render import jsonable

QUICK = ReproductionSettings.quick_settings()


@pytest.fixture(scope="module")
def report_values(data_dir):
    """The whole report's numbers at the quick settings (the fixture)."""
    return load_fixture(data_dir)


@pytest.fixture(scope="module")
def arches():
    return parts.paper_arches(QUICK)


@pytest.fixture(scope="module")
def cases(arches):
    return parts.restitution_cases(QUICK, arches)


def test_paper_q_and_its_tolerance_are_the_papers(paper):
    q = paper["dynamics"]["NA"]["failure_acceleration_tp040"]
    assert parts.paper_q() == q
    assert parts.q_agrees(q + 0.009) and not parts.q_agrees(q - 0.011)


def test_limit_table_alone_matches_table1_and_the_report(arches, paper, report_values):
    table1 = parts.limit_table(arches, paper)
    ref = paper["table1"]["NA"]
    assert table1["NA"]["k"] == pytest.approx(ref["load_multiplier"], abs=5e-5)
    assert table1["NA"]["beta_l"] == pytest.approx(ref["beta"], abs=5e-5)
    assert (table1["NA"]["joints_l"], table1["NA"]["faces_l"]) == (ref["joints"], ref["faces"])
    assert table1["NA"]["k_r"] == pytest.approx(table1["NA"]["k_l"], rel=1e-9)  # symmetric
    assert table1["NA"]["agrees"]
    assert_same(jsonable(table1), report_values["table1"], "table1")


def test_mechanism_tables_alone_match_tables2_3_and_the_report(arches, paper, report_values):
    table2, table3 = parts.mechanism_tables(arches, paper)
    for key in ("theta_u", "theta_bc_u", "theta_cd_u"):
        assert table2["NA"]["l"][key] == pytest.approx(paper["table2"]["NA"][key], abs=5e-5)
    for key in ("ab", "bc", "cd"):
        assert table2["NA"]["l"][key] == pytest.approx(paper["table2"]["NA"][key], abs=5e-3)
    for key in ("theta_cr", "phi_cr"):
        assert table3["NA"]["l"][key] == pytest.approx(paper["table3"]["NA"][key], abs=5e-4)
    assert table2["NA"]["agrees"] and table3["NA"]["agrees"]
    assert_same(jsonable(table2), report_values["table2"], "table2")
    assert_same(jsonable(table3), report_values["table3"], "table3")


def test_each_arch_is_built_once_and_its_variants_share_its_tables(arches, cases):
    """The front door: one FourLinkModel per arch; a coefficient of restitution is a variant
    that shares the limit analyses, mechanisms and tables."""
    from archquake.geometry import irregular_sample

    drawn = irregular_sample(oppenheim(), QUICK.epsilon, 2, QUICK.seed)  # RA-1, RA-2: 0 and 1
    assert [arches.arch("RA-1"), arches.arch("RA-2")] == drawn
    assert arches.arch("NA") == oppenheim()
    for case in (*cases.values(), parts.elastic_case(arches)):
        for name in ARCH_NAMES:
            variant, model = case.models[name], arches.models[name]
            assert variant.tables is model.tables and variant.mechanisms is model.mechanisms
            assert variant.restitution == case.pair


def test_restitution_cases_are_the_papers_and_the_nominal_arch_computed(arches, cases, paper,
                                                                         report_values):
    c = paper["dynamics"]["NA"]["restitution_paper"]
    assert cases["paper"].pair == (c, c)
    computed = arches.nominal.with_restitution("computed").restitution
    assert cases["computed"].pair == computed  # one value for every arch, as the paper does
    assert parts.elastic_case(arches).pair == (1.0, 1.0)
    assert_same(jsonable(parts.restitution_summary(arches, cases)),
                report_values["restitution"], "restitution")


def test_free_vibrations_alone(arches, cases, paper, report_values):
    free = parts.free_vibrations(QUICK, arches, cases, paper)
    phi0 = paper["dynamics"]["NA"]["free_vibration_phi0"]
    # c_v = 1 loses no energy: every half cycle of Mech-l returns to phi0 (closed form)
    assert free.summary["elastic"]["NA"]["peaks_l"] == pytest.approx(
        [phi0] * len(free.summary["elastic"]["NA"]["peaks_l"]), abs=1e-6)
    assert all(free.agrees(case) for case in ("elastic", "paper", "computed"))
    assert_same(jsonable(free.summary), report_values["free_vibration"], "free_vibration")


def test_pulse_responses_alone_match_fig15(cases, paper, report_values):
    pulses = parts.pulse_responses(cases, paper)
    rows = pulses.summary["paper"]["cases"]
    for row, (duration, amplitude, status, half_cycle) in zip(
            rows, paper["dynamics"]["NA"]["pulse_cases"], strict=True):
        assert (row["duration"], row["amplitude"]) == (duration, amplitude)
        assert (row["NA"]["status"], row["NA"]["half_cycle"]) == (status, half_cycle)
    assert pulses.summary["paper"]["nominal_agrees"]
    assert_same(jsonable(pulses.summary), report_values["pulse"], "pulse")


def test_failure_domain_alone_matches_point_q(arches, cases, paper, report_values):
    domain = parts.failure_domain(QUICK, arches, cases)
    q = domain.summary["q_tp040"]["paper"]
    assert q == pytest.approx(paper["dynamics"]["NA"]["failure_acceleration_tp040"], abs=0.01)
    assert domain.summary["activation"] == pytest.approx(
        paper["table1"]["NA"]["load_multiplier"], abs=5e-5)
    assert_same(jsonable(domain.summary), report_values["failure_domain"], "failure_domain")


def test_fragility_alone(cases, report_values):
    frag = parts.fragility(QUICK, cases)
    probability = np.asarray(frag.summary["probability"])
    assert np.array_equal(probability * QUICK.fragility_sample_size,
                          frag.summary["failures"])  # eq. (9): P_F = h_f / h
    # the fixture first: its keys must all be there, a key added since must be named in ADDED
    assert_same(report_values["fragility"], jsonable(frag.summary), "fragility")
    assert_same(jsonable(frag.limit_sample), report_values["limit_sample"], "limit_sample")


def test_comparison_statistics_from_rows_computed_by_hand():
    """Relative differences a/b - 1, the band of 5 %, the duration from which all agree."""
    summary = {"restitution": {"x": [0.7, 0.7], "y": [0.8, 0.8]}, "rows": [
        {"duration": 0.7, "rigid_block": 0.50, "four_link": {"x": 0.51, "y": 0.52}},
        {"duration": 0.3, "rigid_block": 1.00, "four_link": {"x": 1.50, "y": None}},
        {"duration": 0.5, "rigid_block": 0.60, "four_link": {"x": 0.62, "y": 0.66}},
    ]}
    st = parts.comparison_statistics(summary)
    assert st["durations"] == [0.3, 0.5, 0.7]
    assert st["difference"]["x"][0.3] == pytest.approx(0.5)
    assert st["difference"]["y"][0.3] is None
    assert st["difference"]["y"][0.5] == pytest.approx(0.1)
    assert st["agree_from"] == {"x": 0.5, "y": 0.7}  # x: 3.3 % at 0.5 s; y: 10 % at 0.5 s
    assert st["all_from"] == 0.7 and st["short"] == [0.3, 0.5]
    assert st["largest_long"] == (pytest.approx(0.04), "y", 0.7)
    assert parts.long_pulses_agree(summary)
