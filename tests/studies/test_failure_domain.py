import json
import math

import numpy as np
import pytest

from archquake import FourLinkModel
from archquake.cli import main
from archquake.fourlink.engine import check_restitution
from archquake.fourlink.impact import restitution
from archquake.fourlink.mechanism import mechanisms
from archquake.fourlink.time_history import simulate
from archquake.geometry import GRAVITY, irregular_sample
from archquake.ground_motion import oppenheim_pulse
from archquake.reference_arches import oppenheim as oppenheim_arch
from archquake.studies.failure_domain import domain_of, domain_slice, inclusive_range


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
    s = domain_slice(classify, grid, duration=0.4, resolution_g=1e-6)
    got = [(iv.status, iv.half_cycle) for iv in s.intervals]
    assert got == [k for _, k in edges]
    for iv, (start, _) in zip(s.intervals[1:], edges[1:], strict=True):
        assert iv.start == pytest.approx(start, abs=1e-6)
    assert s.failure_acceleration_g == pytest.approx(0.4912, abs=1e-6)
    assert s.first_half_cycle_acceleration_g == pytest.approx(0.6, abs=1e-6)
    assert s.intervals[-1].end == pytest.approx(1.0)


def test_third_class_inside_one_scan_cell_is_resolved():
    # a narrow collapse window entirely inside one grid cell, between two rest/recovery classes
    edges = [(0.0, ("recovery", 0)), (0.5000, ("collapse", 3)), (0.5100, ("collapse", 1))]
    classify, _ = make_classifier(edges)
    s = domain_slice(classify, [0.4, 0.6], resolution_g=1e-7)
    assert [iv.half_cycle for iv in s.intervals] == [0, 3, 1]
    assert s.intervals[1].start == pytest.approx(0.5, abs=1e-7)
    assert s.intervals[2].start == pytest.approx(0.51, abs=1e-7)


def test_no_collapse_gives_nan_and_json_null():
    s = domain_slice(lambda a: ("recovery", 0), [0.1, 0.2, 0.3])
    assert math.isnan(s.failure_acceleration_g)
    assert s.to_dict()["failure_acceleration"] is None
    assert len(s.intervals) == 1


@pytest.mark.parametrize("grid", [[0.3], [0.3, 0.2], []])
def test_bad_grid(grid):
    with pytest.raises(ValueError, match="amplitudes"):
        domain_slice(lambda a: ("rest", 0), grid)


# --------------------------------------------------------------------------------------------
# The failure domain of an arch with the compiled engine [paper, Sect. 5.3.3, Fig. 16]
# --------------------------------------------------------------------------------------------


def test_nominal_failure_acceleration_matches_paper_point_q(nominal, paper):
    # Fig. 17: Oppenheim's arch with c_v = 0.875 fails from 0.49 g at t_p = 0.40 s
    q = paper["dynamics"]["NA"]["failure_acceleration_tp040"]
    domain = domain_of(FourLinkModel.from_arch(nominal, "paper"),
        [0.40], inclusive_range(0.40, 0.60, 0.01), resolution_g=1e-4, extend_to_g=None)
    assert domain.restitution == (paper["dynamics"]["NA"]["restitution_paper"],) * 2
    assert domain.slices[0].failure_acceleration_g == pytest.approx(q, abs=0.01)
    # below Q the arch recovers (it moves: Q is above k), from Q on it collapses after an impact
    first = domain.slices[0].intervals
    assert (first[0].status, first[1].status, first[1].half_cycle) == ("recovery", "collapse", 2)


def test_first_half_cycle_boundary_decreases_with_duration(nominal, paper):
    # Oppenheim's curve: the shorter the pulse, the larger the acceleration that overturns the
    # arch in the first half cycle; it stays above the activation multiplier k
    durations = inclusive_range(0.1, 1.0, 0.1)
    domain = domain_of(FourLinkModel.from_arch(nominal, "paper"),
        durations, np.geomspace(0.3, 20.0, 40), resolution_g=1e-3, extend_to_g=None)
    first = domain.first_half_cycle_accelerations_g
    assert np.all(np.isfinite(first))
    assert np.all(np.diff(first) < 0)
    assert np.all(domain.failure_accelerations_g <= first)
    k = paper["table1"]["NA"]["load_multiplier"]
    assert domain.limit_multiplier == pytest.approx(k, abs=1e-4)
    assert np.all(first > k)


@pytest.mark.parametrize("direction", ["l", "r"])
def test_domain_classification_agrees_with_direct_simulations(nominal, direction):
    # an irregular arch whose computed restitution exceeds 1 one way (c_lr c_rl < 1)
    arch = irregular_sample(nominal, 0.10, 5, 1)[4]
    pair = mechanisms(arch)
    c_lr, c_rl = restitution("computed", *pair)
    assert max(c_lr, c_rl) > 1.0 > c_lr * c_rl
    durations = [0.3, 0.5]
    domain = domain_of(FourLinkModel.from_arch(arch, "computed"),
        durations, inclusive_range(0.2, 1.4, 0.05), direction=direction, resolution_g=1e-4,
        extend_to_g=None)
    sign = -1.0 if direction == "l" else 1.0
    checked = 0
    for s in domain.slices:
        for iv in s.intervals:
            if iv.end - iv.start < 4e-4:
                continue
            for a in (iv.start + 2e-4, 0.5 * (iv.start + iv.end), iv.end - 2e-4):
                out = simulate(pair, oppenheim_pulse(sign * a * GRAVITY, s.duration),
                               (c_lr, c_rl), record=False)
                assert (out.status.label, out.half_cycle) == (iv.status, iv.half_cycle), (
                    s.duration, a)
                checked += 1
    assert checked >= 12


def test_engine_restitution_check_allows_one_coefficient_above_one():
    assert check_restitution(1.3, 0.7) == (1.3, 0.7)
    for bad in [(1.3, 0.8), (0.0, 0.5), (float("nan"), 0.5), (0.5, float("inf")), (-0.5, 0.5)]:
        with pytest.raises(ValueError, match="restitution"):
            check_restitution(*bad)


def test_inclusive_range_includes_stop_and_is_decimal():
    assert inclusive_range(0.2, 1.0, 0.01).tolist() == [round(0.2 + 0.01 * i, 2)
                                                        for i in range(81)]
    assert inclusive_range(0.1, 1.0, 0.025).size == 37
    assert inclusive_range(0.1, 0.34, 0.1).tolist() == [0.1, 0.2, 0.3]
    with pytest.raises(ValueError, match="step"):
        inclusive_range(0.1, 1.0, 0.0)


def test_plot_failure_domain_draws_the_curves(nominal):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from archquake.plotting import plot_failure_domain

    domain = domain_of(FourLinkModel.from_arch(nominal, "paper"),
        [0.4, 0.6, 0.8], np.geomspace(0.3, 2.0, 25), extend_to_g=None)
    ax = plot_failure_domain(domain)
    lines = {line.get_label(): line for line in ax.get_lines()}
    failure = next(v for k, v in lines.items() if k.startswith("failure curve"))
    assert np.allclose(failure.get_ydata(), domain.failure_accelerations_g)
    k_line = next(v for k, v in lines.items() if k.startswith("limit analysis"))
    assert np.allclose(k_line.get_ydata(), domain.limit_multiplier)
    assert ax.get_xlabel().startswith("pulse duration")
    plt.close(ax.figure)


def test_domain_defaults_reach_the_first_half_cycle_boundary(capsys):
    """With its default amplitudes (0.05-1.5 g) the command scans on until the collapse in the
    first half cycle is found: 3.07 g at t_p = 0.2 s and 1.59 g at 0.3 s for Oppenheim's arch
    (computed restitution). Each boundary is checked by direct analyses on either side."""
    assert main(["domain", "--durations", "0.2,0.3", "--json"]) == 0
    slices = json.loads(capsys.readouterr().out)
    pair = mechanisms(oppenheim_arch())
    coefficients = restitution("computed", *pair)
    for entry, expected in zip(slices, (3.07, 1.59), strict=True):
        boundary = entry["first_half_cycle_acceleration"]
        assert boundary == pytest.approx(expected, abs=0.01)
        assert entry["scanned_to"] >= boundary
        for amplitude, first_half in ((boundary - 0.002, False), (boundary + 0.002, True)):
            pulse = oppenheim_pulse(-amplitude * GRAVITY, entry["duration"])
            outcome = simulate(pair, pulse, coefficients).outcome
            assert (outcome.collapsed and outcome.half_cycle == 1) is first_half


def test_domain_says_when_a_boundary_lies_beyond_the_cap(capsys):
    assert main(["domain", "--durations", "0.05", "--extend-to", "3"]) == 0
    text = capsys.readouterr().out
    assert "> 3" in text and "beyond" in text and "--extend-to 3 g" in text
    assert main(["domain", "--durations", "0.05", "--extend-to", "3", "--json"]) == 0
    (entry,) = json.loads(capsys.readouterr().out)
    assert entry["first_half_cycle_acceleration"] is None and entry["scanned_to"] == 3.0
