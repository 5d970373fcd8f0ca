import math

import pytest

from archquake.failure_domain import domain_slice


def make_classifier(edges):
    """Piecewise outcome: edges = [(amplitude where class starts, (status, half_cycle)), ...]."""
    calls = []

    def classify(a):
        calls.append(a)
        key = edges[0][1]
        for start, k in edges:
            if a >= start:
                key = k
        return key

    return classify, calls


def test_every_interval_found_including_non_monotone_ones():
    # rest < 0.37 <= recovery < 0.4912 <= collapse(2) < 0.5231 <= recovery < 0.6 <= collapse(1)
    edges = [(0.0, ("rest", 0)), (0.37, ("recovery", 0)), (0.4912, ("collapse", 2)),
             (0.5231, ("recovery", 0)), (0.6, ("collapse", 1))]
    classify, _ = make_classifier(edges)
    grid = [0.2 + 0.05 * i for i in range(17)]  # 0.2 .. 1.0
    s = domain_slice(classify, grid, duration=0.4, tolerance=1e-6)
    got = [(iv.status, iv.half_cycle) for iv in s.intervals]
    assert got == [k for _, k in edges]
    for iv, (start, _) in zip(s.intervals[1:], edges[1:], strict=True):
        assert iv.start == pytest.approx(start, abs=1e-6)
    assert s.failure_acceleration == pytest.approx(0.4912, abs=1e-6)
    assert s.first_half_cycle_acceleration == pytest.approx(0.6, abs=1e-6)
    assert s.intervals[-1].end == pytest.approx(1.0)


def test_third_class_inside_one_scan_cell_is_resolved():
    # a narrow collapse window entirely inside one grid cell, between two rest/recovery classes
    edges = [(0.0, ("recovery", 0)), (0.5000, ("collapse", 3)), (0.5100, ("collapse", 1))]
    classify, _ = make_classifier(edges)
    s = domain_slice(classify, [0.4, 0.6], tolerance=1e-7)
    assert [iv.half_cycle for iv in s.intervals] == [0, 3, 1]
    assert s.intervals[1].start == pytest.approx(0.5, abs=1e-7)
    assert s.intervals[2].start == pytest.approx(0.51, abs=1e-7)


def test_no_collapse_gives_nan_and_json_null():
    s = domain_slice(lambda a: ("recovery", 0), [0.1, 0.2, 0.3])
    assert math.isnan(s.failure_acceleration)
    assert s.to_dict()["failure_acceleration"] is None
    assert len(s.intervals) == 1


@pytest.mark.parametrize("grid", [[0.3], [0.3, 0.2], []])
def test_bad_grid(grid):
    with pytest.raises(ValueError, match="amplitudes"):
        domain_slice(lambda a: ("rest", 0), grid)
