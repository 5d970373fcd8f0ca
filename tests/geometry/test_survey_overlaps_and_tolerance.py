"""The survey's overlap check by a sweep (it was a quadratic double loop), checked against the
pairwise check on valid and broken surveys; and its contact tolerance, stated and settable."""

import json
import math
import time

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from survey_reference import check_overlaps_pairwise

from archquake import oppenheim
from archquake.geometry import circular_arch, load_arch, surveyed_arch
from archquake.geometry.survey import SURVEY_TOLERANCE, SURVEY_TOLERANCE_RANGE, _check_overlaps


def _blocks(arch, points=6):
    return [arch.outline(i, points)[:-1] for i in range(arch.n_voussoirs)]


def _verdict(check, blocks, tol):
    try:
        check(blocks, tol)
    except ValueError as exc:
        return str(exc)
    return None


@st.composite
def broken_surveys(draw):
    """The blocks of a circular arch, some moved, swapped or duplicated."""
    n = draw(st.integers(4, 12))
    arch = circular_arch(10.0, draw(st.floats(1.0, 3.0)), draw(st.floats(0.3, 2.0)), n)
    blocks = _blocks(arch, draw(st.integers(2, 8)))
    for _ in range(draw(st.integers(0, 3))):
        i = draw(st.integers(0, n - 1))
        change = draw(st.sampled_from(("move", "swap", "copy")))
        if change == "move":
            step = draw(st.sampled_from((1e-12, 1e-6, 1e-3, 0.05, 0.5, 3.0)))
            angle = draw(st.floats(0, 2 * math.pi))
            blocks[i] = blocks[i] + step * np.array([math.cos(angle), math.sin(angle)])
        elif change == "swap":
            j = draw(st.integers(0, n - 1))
            blocks[i], blocks[j] = blocks[j], blocks[i]
        else:
            blocks[draw(st.integers(0, n - 1))] = blocks[i].copy()
    return blocks


@given(broken_surveys())
@settings(deadline=None)
def test_sweep_finds_what_the_pairwise_check_finds(blocks):
    """The same verdict, naming the same pair of blocks, as the pairwise check it replaced."""
    tol = SURVEY_TOLERANCE * float(np.ptp(np.vstack(blocks), axis=0).max())
    assert _verdict(_check_overlaps, blocks, tol) == _verdict(check_overlaps_pairwise, blocks,
                                                              tol)


def test_ten_thousand_blocks_check_in_seconds():
    """2 000 blocks took 69 s in the pairwise check; 10 000 now take a few seconds in all (the
    bound leaves room for a loaded machine)."""
    blocks = _blocks(circular_arch(10.0, 0.9 * math.pi, 1.5, 10_000), 4)
    surveyed_arch(_blocks(oppenheim(), 4))  # compiled (or loaded) before the timing
    start = time.perf_counter()
    survey = surveyed_arch(blocks)
    assert time.perf_counter() - start < 60
    assert survey.n_voussoirs == 10_000


def test_a_gap_beyond_the_tolerance_names_the_gap_and_the_tolerance():
    """A block moved up by 1 micrometre leaves a gap of 1e-6 m times the sine of its joint's
    slope to its left neighbour (the offset along the joint's normal)."""
    nominal = oppenheim()
    blocks = _blocks(nominal)
    offset = np.array([0.0, 1e-6])  # a block moved by 1 micrometre
    blocks[3] = blocks[3] + offset
    gap = abs(offset @ nominal.joint_normals[3])
    size = float(np.ptp(np.vstack(blocks), axis=0).max())
    with pytest.raises(ValueError, match=rf"blocks 2 and 3 do not touch along a segment.*"
                                         rf"{gap:.3g} m apart at their closest, the contact "
                                         rf"tolerance is {SURVEY_TOLERANCE * size:.3g} m "
                                         rf"\(1e-09 of the arch's size"):
        surveyed_arch(blocks)


def test_a_settable_tolerance_accepts_the_gap_and_keeps_the_joints():
    """With a tolerance of 1e-6 of the size (20 micrometres here) the block moved by 1
    micrometre touches its neighbours; the joints are those of the arch to that gap."""
    nominal = oppenheim()
    blocks = _blocks(nominal)
    blocks[3] = blocks[3] + np.array([0.0, 1e-6])
    survey = surveyed_arch(blocks, tolerance=1e-6)
    exact = surveyed_arch(_blocks(nominal))
    assert survey.joints == pytest.approx(exact.joints, abs=2e-6)
    assert survey.to_dict()["tolerance"] == 1e-6
    assert "tolerance" not in exact.to_dict()  # the default is not written


def test_the_tolerance_of_a_geometry_file(tmp_path):
    blocks = _blocks(oppenheim())
    blocks[3] = blocks[3] + np.array([0.0, 1e-6])
    path = tmp_path / "survey.json"
    path.write_text(json.dumps({"blocks": [b.tolist() for b in blocks], "tolerance": 1e-6}))
    assert load_arch(path).tolerance == 1e-6
    low, high = SURVEY_TOLERANCE_RANGE
    path.write_text(json.dumps({"blocks": [b.tolist() for b in blocks], "tolerance": 0.5}))
    with pytest.raises(ValueError, match=rf"survey.json': tolerance must be a number in "
                                         rf"\[{low:g}, {high:g}\]"):
        load_arch(path)
