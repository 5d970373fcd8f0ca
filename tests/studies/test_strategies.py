"""The search strategies of a grid against the exhaustive grid (studies.strategies)."""

import numpy as np
import pytest

from archquake.studies.strategies import coarse_indices, search_grid


def _runs(rng, n, min_width):
    """A random outcome sequence of n points whose every run (band) is >= min_width long,
    except possibly the first and the last."""
    keys, value = [], int(rng.integers(3))
    while len(keys) < n:
        width = int(rng.integers(min_width, 3 * min_width + 1))
        keys += [value] * width
        value = (value + int(rng.integers(1, 3))) % 3
    return np.array(keys[:n])


def _counting(truth):
    calls = []

    def classify(indices):
        calls.extend(indices.tolist())
        return truth[indices]
    return classify, calls


@pytest.mark.parametrize("stride", [1, 2, 5, 8, 13])
@pytest.mark.parametrize("search", ["bisection", "screened"])
def test_equal_to_the_exhaustive_grid_when_bands_are_wider_than_the_stride(search, stride):
    rng = np.random.default_rng(stride)
    for _ in range(200):
        n = int(rng.integers(2, 120))
        truth = _runs(rng, n, stride)
        classify, calls = _counting(truth)
        keys, analysed = search_grid(classify, n, search=search, stride=stride,
                                     screen=truth if search == "screened" else None)
        assert np.array_equal(keys, truth)
        assert sorted(calls) == sorted(set(calls)), "an index was analysed twice"
        assert np.array_equal(np.flatnonzero(analysed), np.unique(calls))


def test_exhaustive_analyses_every_point():
    truth = np.array([0, 0, 1, 0, 2, 2])
    classify, calls = _counting(truth)
    keys, analysed = search_grid(classify, 6, search="exhaustive")
    assert np.array_equal(keys, truth) and analysed.all() and sorted(calls) == list(range(6))


def test_a_band_narrower_than_the_stride_is_missed_by_bisection_found_by_the_screen():
    """The one way the faster strategies differ from the grid: a band that starts and ends
    between two coarse points. The screening model's change near it brings it into the scan."""
    truth = np.zeros(33, dtype=int)
    truth[10:13] = 1  # a 3-point band between the coarse points 8 and 16
    keys, _ = search_grid(lambda i: truth[i], 33, search="bisection", stride=8)
    assert not keys.any()
    screen = np.zeros(33, dtype=int)
    screen[11:14] = 1  # the cheap model sees the band one point off
    keys, _ = search_grid(lambda i: truth[i], 33, search="screened", stride=8, screen=screen)
    assert np.array_equal(keys, truth)


def test_cost_of_one_change_is_the_coarse_scan_and_a_bisection():
    truth = (np.arange(61) >= 37).astype(int)
    classify, calls = _counting(truth)
    search_grid(classify, 61, stride=8)
    assert len(calls) == 9 + 3  # 0, 8, ..., 56, 60 and log2(8) bisections


def test_coarse_indices_include_the_ends_and_both_sides_of_every_hint():
    assert coarse_indices(20, 8, hints=[12]).tolist() == [0, 8, 11, 12, 13, 16, 19]


@pytest.mark.parametrize("kwargs, match", [
    ({"search": "smart"}, "search must be one of"),
    ({"stride": 0}, "stride must be an integer >= 1"),
    ({"search": "screened", "screen": [0, 1]}, "one per grid point"),
])
def test_bad_settings_are_refused(kwargs, match):
    with pytest.raises(ValueError, match=match):
        search_grid(lambda i: i * 0, 10, **kwargs)
