"""Undecided analyses are counted, bounded and said, never taken for an outcome.

The rigid-block model is forced to leave chosen analyses undecided (``forced_undecided``), so
these tests do not depend on when its solver gives up; every expected value is counted from the
forced pattern (or from the calls the model received), not from the study's output.
"""

import math

import numpy as np
import pytest

import forced_undecided as forced
from archquake import oppenheim
from archquake.rigid_blocks import RigidBlockModel
from archquake.status import Status
from archquake.studies.failure_domain import domain_of
from archquake.studies.undecided import (
    UNDECIDED_WARNING_FRACTION,
    probability_bounds,
    undecided_count,
    undecided_warning,
)

RESOLUTION = 1e-3


@pytest.fixture
def calls(monkeypatch):
    return forced.force(monkeypatch)


@pytest.fixture(scope="module")
def k_l():
    return RigidBlockModel(oppenheim()).load_multipliers[0]


def test_warning_is_given_above_the_stated_fraction_only():
    n = 1000
    at = round(UNDECIDED_WARNING_FRACTION * n)
    assert undecided_warning(at, n) is None
    assert undecided_warning(at + 1, n).startswith(f"WARNING: {at + 1} of {n} analyses")
    assert undecided_warning(0, 0) is None


def test_probability_bounds_count_undecided_as_survival_then_as_collapse():
    rng = np.random.default_rng(1)
    status = rng.choice([0, 1, 2, -1], size=(50, 7))
    lower, upper = probability_bounds(status == 2, status == -1, axis=0)
    for j in range(7):
        column = status[:, j].tolist()
        assert lower[j] == column.count(2) / 50
        assert upper[j] == (column.count(2) + column.count(-1)) / 50
    assert undecided_count(status) == int((status == -1).sum())


def test_domain_reports_the_undecided_band_and_bounds_the_failure_acceleration(calls, k_l):
    durations, grid = (0.4, 0.6), np.round(np.arange(0.2, 1.2001, 0.05), 10)
    domain = domain_of(RigidBlockModel(oppenheim()), durations, grid, direction="l",
                       resolution_g=RESOLUTION, extend_to_g=None, search="exhaustive")
    low, high = (k_l * m for m in forced.UNDECIDED_BAND)
    second = [k_l * m for m in forced.SECOND_BAND]
    short, long = domain.slices
    # the short pulse: undecided below the first collapse and among the collapses
    bands = short.undecided_bands_g
    assert len(bands) == 2
    for (start, end), (a, b) in zip(bands, [(low, high), second], strict=True):
        assert abs(start - a) <= RESOLUTION and abs(end - b) <= RESOLUTION
    assert abs(short.failure_undecided_from_g - low) <= RESOLUTION
    assert abs(short.failure_acceleration_g - k_l * forced.COLLAPSE_FROM) <= RESOLUTION
    row = short.to_dict()
    assert row["undecided"] == [list(b) for b in bands]
    assert row["failure_undecided_from"] == short.failure_undecided_from_g
    # the long pulse: its undecided band lies above the failure, which stays decided
    assert len(long.undecided_bands_g) == 1
    assert math.isnan(long.failure_undecided_from_g)
    assert "failure_undecided_from" not in long.to_dict()
    # the counts: every call the model received that it left undecided
    for tp, count, undecided in zip(durations, domain.analyses, domain.undecided, strict=True):
        mine = [c for c in calls if c[0] == tp]
        assert count == len(mine)
        assert undecided == sum(1 for c in mine if c[2] is Status.UNDECIDED)
    assert domain.undecided_analyses == sum(1 for c in calls if c[2] is Status.UNDECIDED) > 0


def test_domain_without_undecided_analyses_reports_nothing_more(calls, k_l):
    """Below the undecided bands the domain and its JSON are as they always were."""
    grid = np.round(np.arange(0.05, 1.5 * k_l, 0.02), 10)
    domain = domain_of(RigidBlockModel(oppenheim()), (0.6,), grid, resolution_g=RESOLUTION,
                       extend_to_g=None, search="exhaustive")
    assert domain.undecided == (0,) and domain.slices[0].undecided_bands_g == []
    assert set(domain.slices[0].to_dict()) == {"duration", "failure_acceleration",
                                               "first_half_cycle_acceleration", "scanned_to",
                                               "intervals"}


def _forced_domain_counts(calls):
    return len(calls), sum(1 for c in calls if c[2] is Status.UNDECIDED)


def test_domain_command_warns_first_and_prints_the_bands(calls, capsys, k_l):
    from archquake.cli import main

    argv = ["domain", "--model", "rigid-blocks", "--durations", "0.4", "--amplitudes",
            "0.2:1.2:0.05", "--search", "exhaustive", "--resolution", "0.001"]
    assert main(argv) == 0
    lines = capsys.readouterr().out.splitlines()
    total, undecided = _forced_domain_counts(calls)
    assert undecided / total > UNDECIDED_WARNING_FRACTION
    assert lines[0] == undecided_warning(undecided, total, "rigid-block analyses")
    assert f"undecided: {undecided} of {total} analyses" in lines
    low = k_l * forced.UNDECIDED_BAND[0]
    (row,) = [line for line in lines if line.startswith("   0.400")]
    shown_low, shown_high = row.split()[1].split("..")
    assert abs(float(shown_low) - low) <= 1e-3
    assert abs(float(shown_high) - k_l * forced.COLLAPSE_FROM) <= 1e-3
    assert any("the failure acceleration is between" in line for line in lines)
    calls.clear()
    assert main([*argv, "--json"]) == 0
    import json

    (row,) = json.loads(capsys.readouterr().out)
    assert row["undecided_analyses"] == _forced_domain_counts(calls)[1]
    assert len(row["undecided"]) == 2 and abs(row["failure_undecided_from"] - low) <= 1e-3


FRAGILITY_GRID = dict(durations=(0.4, 0.6), amplitudes_g=tuple(np.round(
    np.arange(0.2, 1.2001, 0.05), 10)))


def _fragility_settings(**more):
    from archquake.studies.fragility import FragilitySettings

    return FragilitySettings(model="rigid-blocks", sample_size=4, epsilon=0.05,
                             limit_sample_size=4, search="exhaustive", **FRAGILITY_GRID,
                             **more)


def _expected_fragility(settings):
    """P_F bounds and counts from the forced pattern and each arch's own load multipliers."""
    failed, undecided, count = [], [], 0
    for i in range(settings.sample_size):
        member = settings.sample.member(i, settings.model)
        if member.model is None:
            continue
        k_l, k_r = member.model.load_multipliers
        codes = np.array([[[forced.status_of(a / k, tp) for a in settings.amplitudes_g]
                           for tp in settings.durations] for k in (k_l, k_r)])
        collapse = (codes == Status.COLLAPSE).any(axis=0)
        failed.append(collapse)
        undecided.append((codes == Status.UNDECIDED).any(axis=0) & ~collapse)
        count += int((codes == Status.UNDECIDED).sum())
    failed, undecided = np.array(failed), np.array(undecided)
    return failed.mean(axis=0), (failed | undecided).mean(axis=0), count, failed.shape[0]


def test_fragility_bounds_p_f_by_the_undecided_arches(calls, tmp_path):
    from archquake.studies.fragility import load_fragility, run_fragility

    settings = _fragility_settings()
    result = run_fragility(settings, tmp_path / "study", backend="serial", progress=False,
                           nominal_resolution_g=1e-3)
    lower, upper, count, h = _expected_fragility(settings)
    assert result.analysed == h
    np.testing.assert_array_equal(result.probability, lower)
    np.testing.assert_array_equal(result.probability_upper, upper)
    assert np.any(upper > lower)  # the forced pattern leaves some P_F undecided
    assert result.undecided_analyses == count > 0
    summary = result.summary()
    assert summary["undecided"]["analyses"] == count
    assert summary["undecided"]["of"] == 2 * h * lower.size
    nominal = sum(1 for c in calls if c[2] is Status.UNDECIDED) - count
    assert summary["undecided"]["nominal_analyses"] == nominal
    for i, row in enumerate(summary["durations"]):
        gap = upper[i] - lower[i]
        assert row["undecided"] == round(gap.sum() * h)
        assert ("probability_upper_largest_gap" in row) == bool(gap.any())
    curves = result.curves()
    np.testing.assert_array_equal(curves["probability_upper"], upper.ravel())
    # the stored study keeps the count; the nominal failure of the short pulse is bounded
    again = load_fragility(tmp_path / "study", nominal_resolution_g=1e-3)
    assert again.undecided_analyses == count
    k = min(RigidBlockModel(oppenheim()).load_multipliers)
    short = summary["durations"][0]
    assert abs(short["nominal_failure_undecided_from"] - k * forced.UNDECIDED_BAND[0]) <= 1e-3
    assert "nominal_failure_undecided_from" not in summary["durations"][1]


def test_fragility_command_warns_first_and_shows_the_bounds(calls, capsys, tmp_path):
    from archquake.cli import main

    settings = _fragility_settings()
    _, _, count, h = _expected_fragility(settings)
    calls.clear()
    argv = ["fragility", "--model", "rigid-blocks", "--samples", "4", "--epsilon", "0.05",
            "--limit-samples", "4", "--search", "exhaustive", "--durations", "0.4,0.6",
            "--amplitudes", "0.2:1.2:0.05", "--out", str(tmp_path / "cli"), "--no-progress"]
    assert main(argv) == 0
    lines = capsys.readouterr().out.splitlines()
    total = 2 * h * 2 * len(FRAGILITY_GRID["amplitudes_g"])
    nominal = [c for c in calls[2 * h * 2 * len(FRAGILITY_GRID["amplitudes_g"]):]]
    everything = sum(1 for c in calls if c[2] is Status.UNDECIDED)
    assert lines[0] == undecided_warning(everything, total + len(nominal))
    assert any(line.startswith(f"undecided: {count} of {total} analyses") for line in lines)
    assert any("as a failure it is the upper bound" in line for line in lines)


def test_record_fragility_bounds_the_stripes_by_the_undecided_pairs(calls, capsys):
    from archquake.cli.main_record_fragility import _print
    from archquake.ground_motion import RecordSuite
    from archquake.studies.record_fragility import RecordFragilitySettings, run_record_fragility

    suite = RecordSuite.from_stochastic(2, seed=4, significant_duration=2.0, duration=4.0)
    levels = tuple(np.round(np.arange(0.2, 1.2001, 0.05), 10))
    settings = RecordFragilitySettings(suite=suite, levels=levels, sample_size=3, seed=2,
                                       epsilon=0.05, model="rigid-blocks", search="exhaustive",
                                       bootstrap=10)
    result = run_record_fragility(settings, backend="serial", progress=False)
    codes = []
    for i in result.arches:  # each analysed arch's pattern, the same for every record
        member = settings.sample.member(int(i), settings.model)
        k = min(member.model.load_multipliers)
        codes.append([forced.status_of(x / k) for x in levels])
    codes = np.array(codes)
    lower = (codes == Status.COLLAPSE).mean(axis=0)
    upper = ((codes == Status.COLLAPSE) | (codes == Status.UNDECIDED)).mean(axis=0)
    np.testing.assert_allclose(result.probability, lower, rtol=0, atol=1e-12)
    np.testing.assert_allclose(result.probability_upper, upper, rtol=0, atol=1e-12)
    assert np.any(upper > lower)
    pairs = 2 * len(suite.names)  # records x polarities per arch and level
    summary = result.summary()
    assert summary["undecided"]["analyses"] == int((codes == Status.UNDECIDED).sum()) * pairs
    made = sum(1 for c in calls if c[2] is Status.UNDECIDED)
    assert summary["undecided"]["analyses"] + summary["undecided"]["nominal_analyses"] == made
    assert summary["probability_upper"] == result.probability_upper.tolist()
    _print(result, summary)
    lines = capsys.readouterr().out.splitlines()
    assert lines[0] == undecided_warning(made, len(calls))
    j = int(np.flatnonzero(upper > lower)[0])
    row = next(line for line in lines if line.split()[:1] == [f"{levels[j]:.4g}"])
    assert row.split()[1] == f"{lower[j]:.3f}-{upper[j]:.3f}"


def test_compare_never_compares_a_failure_acceleration_above_an_undecided_band(calls, capsys,
                                                                                k_l):
    from archquake.cli import main
    from archquake.studies.comparison import compare_models

    grid = np.round(np.arange(0.2, 1.2001, 0.05), 10)
    comparison = compare_models(oppenheim(), (0.4, 0.6), amplitudes_g=grid, resolution_g=1e-3,
                                restitutions=("computed",), search="exhaustive")
    made = sum(1 for c in calls if c[2] is Status.UNDECIDED)
    assert comparison.undecided_analyses == made > 0
    short, long = comparison.to_list()
    low = k_l * forced.UNDECIDED_BAND[0]
    assert abs(short["failure_undecided_from"]["rigid_block"] - low) <= 1e-3
    assert len(short["undecided"]["rigid_block"]) == 2
    assert "failure_undecided_from" not in long and len(long["undecided"]["rigid_block"]) == 1
    assert sum(row["undecided_analyses"]["rigid_block"] for row in (short, long)) == made
    difference = comparison.relative_differences()["computed"]
    assert math.isnan(difference[0]) and math.isfinite(difference[1])
    calls.clear()
    assert main(["compare", "--durations", "0.4,0.6", "--amplitudes", "0.2:1.2:0.05",
                 "--resolution", "0.001", "--search", "exhaustive", "--no-progress"]) == 0
    lines = capsys.readouterr().out.splitlines()
    made = sum(1 for c in calls if c[2] is Status.UNDECIDED)
    assert lines[0] == undecided_warning(made, len(calls), "rigid-block analyses")
    (row,) = [line for line in lines if line.startswith("   0.400")]
    cells = row.split()
    assert cells[1].startswith(f"{low:.3f}..") and "%" not in row
    assert f"rigid blocks undecided: {made} of {len(calls)} analyses" in lines


def test_failure_domain_figure_shades_the_undecided_bands(calls):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from archquake.plotting import DOMAIN_LABELS, plot_failure_domain

    grid = np.round(np.arange(0.2, 1.2001, 0.05), 10)
    domain = domain_of(RigidBlockModel(oppenheim()), (0.4, 0.6), grid, resolution_g=1e-3,
                       extend_to_g=None, search="exhaustive")
    ax = plot_failure_domain(domain)
    labels = [text.get_text() for text in ax.get_legend().get_texts()]
    assert DOMAIN_LABELS["undecided"] in labels
    plt.close(ax.figure)


def test_fragility_figure_marks_the_upper_bound_only_where_it_differs(calls):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from archquake.plotting import plot_fragility_curve
    from archquake.studies.fragility import run_fragility

    settings = _fragility_settings()
    result = run_fragility(settings, backend="serial", progress=False,
                           nominal_resolution_g=1e-3)
    lower, upper, _, _ = _expected_fragility(settings)
    for i, tp in enumerate(settings.durations):
        ax = plot_fragility_curve(result, tp)
        labels = [t.get_text() for t in ax.get_legend().get_texts()]
        differs = bool(np.any(upper[i] > lower[i]))
        assert any("upper bound" in label for label in labels) == differs
        plt.close(ax.figure)
