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
                       resolution=RESOLUTION, extend_to_g=None, search="exhaustive")
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
    domain = domain_of(RigidBlockModel(oppenheim()), (0.6,), grid, resolution=RESOLUTION,
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
