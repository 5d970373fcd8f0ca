"""Record suites (archquake.ground_motion.suites): where a study's records come from, their
digests, the motions rebuilt from the stored suite, and the scaling to levels of an intensity
measure, each against an independent value (hashlib, read_suite, the IM of the scaled record)."""

import hashlib
import shutil
from pathlib import Path

import numpy as np
import pytest

from archquake.ground_motion import (
    RecordSuite,
    intensity_measure,
    read_suite,
    scale_factors,
    stochastic_suite,
    stripe_measure,
)

DATA = Path(__file__).resolve().parents[1] / "data"
STOCHASTIC = {"significant_duration": 4.0, "midpoint_time": 3.0, "filter_frequency": 1.0,
              "filter_frequency_rate": 0.0, "duration": 6.0}


@pytest.fixture()
def folder(tmp_path):
    d = tmp_path / "suite"
    d.mkdir()
    for name in ("decaying_sine.csv", "decaying_sine.AT2", "decaying_sine.ASC"):
        shutil.copy(DATA / name, d / name)
    (d / "README.txt").write_text("three records\n")
    return d


def test_a_folder_is_its_files_with_their_digests(folder):
    suite = RecordSuite.from_paths(folder)
    assert suite.kind == "files" and len(suite) == 3
    assert suite.names == tuple(m.name for m in read_suite(folder))
    for f in suite.files:
        assert f.sha256 == hashlib.sha256(Path(f.path).read_bytes()).hexdigest()
        assert Path(f.path).is_absolute() and Path(f.path).name == f.name
    assert [f.file_format for f in suite.files] == ["esm", "at2", "csv"]
    for ours, theirs in zip(suite.motions(), read_suite(folder), strict=True):
        assert ours.name == theirs.name and np.array_equal(ours.values, theirs.values)
    again = RecordSuite.from_dict(suite.to_dict())
    assert again == suite and again.to_dict() == suite.to_dict()


def test_a_changed_file_is_refused(folder):
    suite = RecordSuite.from_paths(folder)
    changed = folder / "decaying_sine.csv"
    changed.write_text(changed.read_text() + "\n")
    with pytest.raises(ValueError, match="decaying_sine.csv' has changed since the study"):
        suite.motions()
    changed.unlink()
    with pytest.raises(ValueError, match="decaying_sine.csv' of the study cannot be read"):
        suite.motions()


def test_the_stochastic_suite_is_drawn_again_from_its_seed():
    suite = RecordSuite.from_stochastic(3, seed=5, **STOCHASTIC)
    reference = stochastic_suite(3, seed=5, **STOCHASTIC)
    assert suite.kind == "stochastic" and suite.names == tuple(m.name for m in reference)
    motions = RecordSuite.from_dict(suite.to_dict()).motions()
    assert all(np.array_equal(a.values, b.values) for a, b in zip(motions, reference,
                                                                  strict=True))
    cached = suite.motions(cached=True)
    assert all(a is b for a, b in zip(cached, suite.motions(cached=True), strict=True))
    assert all(np.array_equal(a.values, b.values) for a, b in zip(cached, reference,
                                                                  strict=True))
    with pytest.raises(ValueError, match="count must be an integer >= 1"):
        RecordSuite.from_stochastic(0)
    with pytest.raises(ValueError, match="seed must be an integer >= 0"):
        RecordSuite.from_stochastic(2, seed=-1)
    with pytest.raises(ValueError, match="either files or a stochastic suite"):
        RecordSuite()


@pytest.mark.parametrize("im", ["pga", "pgv", "arias", "sa(0.5)"])
def test_scaled_records_have_the_level_as_their_intensity(im):
    """The factor s_rj brings record r to level x_j: the IM of s_rj times the record is x_j
    (Arias intensity: s^2 times, the others s times)."""
    suite = RecordSuite.from_stochastic(2, seed=1, **STOCHASTIC)
    measure = intensity_measure(im)
    levels = np.array([0.2, 0.7, 1.5])
    factors = suite.scale_factors(im, levels)
    assert factors.shape == (2, 3)
    for r, motion in enumerate(suite.motions()):
        for j, level in enumerate(levels):
            assert measure(motion.scaled(factors[r, j])) == pytest.approx(level, rel=1e-9)
    assert np.array_equal(factors, scale_factors(suite.intensities(im), levels,
                                                 measure.exponent))


def test_a_record_without_intensity_cannot_be_scaled_and_some_measures_do_not_scale(tmp_path):
    quiet = tmp_path / "quiet.csv"
    quiet.write_text("0,0\n0.01,0\n0.02,0\n")
    suite = RecordSuite.from_paths([quiet, DATA / "decaying_sine.csv"])
    with pytest.raises(ValueError, match=r"records with pga = 0 cannot be scaled.*quiet\.csv"):
        suite.intensities("pga")
    with pytest.raises(ValueError, match="cannot define stripes"):
        stripe_measure("d5-95")
    with pytest.raises(ValueError, match="^im: unknown intensity measure 'foo'"):
        stripe_measure("foo")
