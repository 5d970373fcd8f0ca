"""The faster search strategies against the exhaustive grid, with the rigid-block model.

``screened`` must give the outcome of the exhaustive grid at every point (hence the same failure
accelerations and P_F); ``bisection`` may miss the isolated outcomes of the rigid blocks' chaotic
late regime (a recovery among late collapses, or a collapse among recoveries:
studies.strategies), and the test says how many it misses here.
"""

import numpy as np
import pytest

from archquake import irregular_arch, oppenheim
from archquake.models import model_for
from archquake.studies.failure_domain import domain_of, inclusive_range
from archquake.studies.strategies import pulse_grid_outcomes

ARCHES = {"NA": oppenheim(), "RA-7": irregular_arch(oppenheim(), 0.10, rng=7)}


@pytest.fixture(scope="module")
def grids():
    """Outcomes of both arches at short and paper durations, by each strategy."""
    amplitudes = inclusive_range(0.2, 0.8, 0.02)
    out = {}
    for name, arch in ARCHES.items():
        blocks, four_link = model_for(arch, "rigid-blocks"), model_for(arch, "four-link")
        for search in ("exhaustive", "screened", "bisection"):
            out[name, search] = pulse_grid_outcomes(blocks, [0.25, 0.5], amplitudes,
                                                    search=search, stride=4, screen=four_link)
    return out


@pytest.mark.parametrize("arch", list(ARCHES))
def test_screened_equals_the_exhaustive_grid(grids, arch):
    exhaustive, screened = grids[arch, "exhaustive"], grids[arch, "screened"]
    assert exhaustive["analysed"].all()
    np.testing.assert_array_equal(screened["status"], exhaustive["status"])
    assert screened["analysed"].sum() < exhaustive["analysed"].sum()


def test_bisection_differs_only_inside_bands_narrower_than_its_stride(grids):
    """Where bisection differs from the grid, the grid's outcome there belongs to a band of
    fewer than ``stride`` (4) points that bisection, inferring from its neighbours, does not
    see -- a recovery among collapses or a collapse among recoveries (here even below the first
    coarse collapse: bisection's failure acceleration can be too high); never a rest."""
    stride = 4
    for arch in ARCHES:
        exhaustive, bisection = grids[arch, "exhaustive"], grids[arch, "bisection"]
        for line, guess in zip(exhaustive["status"].reshape(4, -1),
                               bisection["status"].reshape(4, -1), strict=True):
            for i in np.flatnonzero(line != guess):
                lo, hi = i, i
                while lo > 0 and line[lo - 1] == line[i]:
                    lo -= 1
                while hi + 1 < line.size and line[hi + 1] == line[i]:
                    hi += 1
                assert hi - lo + 1 < stride and line[i] in (1, 2)
        assert (exhaustive["status"] != bisection["status"]).mean() < 0.05


def test_rigid_block_domain_is_the_same_by_every_strategy():
    """The failure domain (grid, then bisection of every change to the resolution) of
    Oppenheim's arch with rigid blocks, at a short and a long pulse."""
    model = model_for(oppenheim(), "rigid-blocks")
    grid = inclusive_range(0.3, 1.5, 0.1)
    domains = {search: domain_of(model, [0.25, 0.5], grid, resolution_g=0.01, extend_to_g=None,
                                 search=search, stride=4)
               for search in ("exhaustive", "screened", "bisection")}
    for search, domain in domains.items():
        assert domain.slices == domains["exhaustive"].slices, search
        assert domain.model["model"] == "rigid-blocks" and domain.search == search
    assert sum(domains["screened"].analyses) < sum(domains["exhaustive"].analyses)


def test_disagreement_of_two_domains_is_where_exactly_one_collapses():
    """domain_disagreement from the domains' intervals, against the two models' outcomes
    evaluated directly at points inside each piece (and outside every piece they agree)."""
    from archquake.ground_motion import oppenheim_pulse
    from archquake.studies.comparison import domain_disagreement

    arch = oppenheim()
    four_link, blocks = model_for(arch, "four-link", restitution="paper"), model_for(
        arch, "rigid-blocks")
    grid = inclusive_range(0.3, 1.5, 0.1)
    first = domain_of(four_link, [0.2, 0.5], grid, resolution_g=0.01, extend_to_g=None)
    second = domain_of(blocks, [0.2, 0.5], grid, resolution_g=0.01, extend_to_g=None)
    gap = domain_disagreement(first, second)
    assert gap.names == ("four-link", "rigid-blocks")
    short, long = gap.intervals
    assert short and gap.width_g()[0] > 5 * gap.width_g()[1]  # the models part at short pulses
    for tp, piece in zip(gap.durations, gap.intervals, strict=True):
        for lo, hi, which in piece:
            if hi - lo < 0.03:
                continue  # within the bisections' resolution of a boundary
            mid = 0.5 * (lo + hi)
            pulse = oppenheim_pulse(-mid * 9.81, tp)
            collapsed = four_link.outcome(pulse).collapsed, blocks.outcome(pulse).collapsed
            assert collapsed == ((True, False) if which == "first only" else (False, True))
    json = gap.to_list()
    assert json[0]["duration"] == 0.2
    assert {"from", "to", "collapses"} <= set(json[0]["intervals"][0])
