"""The irregular sample of the studies (archquake.studies.arch_sample): the same arches whatever
the chunking, the workers or the study, and one rule for an arch that cannot be analysed,
checked against an arch-by-arch classification that does not use the module."""

import math

import numpy as np
import pytest

from archquake import circular_arch
from archquake.errors import CannotStandError, NeverCollapsesError
from archquake.execution import StudyPlan, run_study
from archquake.geometry import irregular_sample
from archquake.limit_analysis import limit_sample, load_multipliers
from archquake.models import ModelSpec
from archquake.studies.arch_sample import (
    EXCLUSIONS,
    ArchSample,
    analysable_model,
    check_analysed,
    check_nominal,
    exclusion_summary,
    nominal_json,
    nominal_model,
)
from archquake.studies.fragility import limit_task
from exclusion_reference import independent_exclusions

SHAPE = ("angles", "thicknesses", "radii")


def _same_arch(a, b) -> bool:
    return all(np.array_equal(getattr(a, n), getattr(b, n)) for n in SHAPE) and (
        a.start_angle == b.start_angle)


# --------------------------------------------------------------------------------------------
# drawing and seeding
# --------------------------------------------------------------------------------------------


def test_arch_i_is_arch_i_of_irregular_sample_whatever_the_sample_size(nominal):
    sample = ArchSample(nominal, 0.10, seed=7)
    reference = irregular_sample(nominal, 0.10, 9, 7)  # SeedSequence(7).spawn(9)
    assert all(_same_arch(a, b) for a, b in zip(sample.arches(9), reference, strict=True))
    # drawn alone, in another order, arch 6 is the same arch
    assert _same_arch(sample.arch(6), reference[6])
    assert all(_same_arch(sample.arch(i), reference[i]) for i in (8, 2, 5))
    assert not _same_arch(sample.arch(0), ArchSample(nominal, 0.10, seed=8).arch(0))
    assert ArchSample(nominal, 0.0, seed=1).arch(3) is nominal  # epsilon 0: the nominal arch


@pytest.mark.parametrize("chunk_size", [1, 4, 11])
def test_the_limit_sample_does_not_depend_on_chunks_or_workers(nominal, chunk_size):
    """The limit-analysis task of the pulse study over 11 arches, in chunks of 1, 4 or 11, in
    this process or on two worker processes: the values of limit_sample (one loop, no chunks)."""
    settings = {"nominal": nominal.to_dict(), "epsilon": 0.10, "limit_method": "kinematic"}
    plan = StudyPlan(settings, seed=3, n_items=11, chunk_size=chunk_size)
    reference = limit_sample(nominal, 0.10, 11, 3, "kinematic")
    backends = ({"backend": "serial"}, {"backend": "processes", "workers": 2})
    for options in backends[: 2 if chunk_size == 4 else 1]:  # one run on processes is enough
        table = run_study(limit_task, plan, progress=False, **options)
        assert np.array_equal(table["k_l"], reference.load_multiplier_l)
        assert np.array_equal(table["k_r"], reference.load_multiplier_r)
        assert table["arch"].tolist() == list(range(11))


def test_settings_validate_the_sample(nominal):
    with pytest.raises(ValueError, match=r"epsilon must be in \[0, 1\), got 1.0"):
        ArchSample(nominal, 1.0, 0)
    with pytest.raises(ValueError, match="seed must be an integer >= 0, got -1"):
        ArchSample(nominal, 0.1, -1)
    with pytest.raises(ValueError, match="seed must be an integer >= 0"):
        ArchSample(nominal, 0.1, 1.5)
    with pytest.raises(ValueError, match="nominal must be an arch"):
        ArchSample("arch", 0.1, 0)
    assert ArchSample(nominal, 0.1, np.int64(4)).seed == 4


# --------------------------------------------------------------------------------------------
# the exclusion rule
# --------------------------------------------------------------------------------------------


def test_exclusions_are_those_of_an_arch_by_arch_classification(nominal):
    """epsilon = 0.5: some drawn arches come apart, some cannot carry their own weight; the
    model of every other arch is built."""
    expected = independent_exclusions(nominal, 0.5, 12, 0)
    assert set(expected.values()) == {"not an arch", "cannot stand"}  # both cases occur
    sample = ArchSample(nominal, 0.5, 0)
    members = [sample.member(i) for i in range(12)]
    assert {m.index: m.excluded for m in members if m.excluded} == expected
    for m in members:
        if m.analysed:
            assert m.model is not None and not m.never_collapses
            assert m.load_multipliers == pytest.approx(load_multipliers(m.arch), abs=1e-9)
        else:
            assert m.model is None and all(math.isnan(k) for k in m.load_multipliers)
    # the limit sample applies the same rule: nan and the reason for the same arches
    k, why = sample.load_multipliers(range(12), "static")
    assert {i: w for i, w in enumerate(why) if w} == expected
    assert np.all(np.isnan(k[why != ""])) and np.all(k[why == ""] >= 0)


def test_an_arch_that_never_collapses_is_analysed_not_excluded():
    thick_flat = circular_arch(1.0, math.radians(40), 0.5, 6)  # k = inf in both directions
    member = ArchSample(thick_flat, 0.02, 0).member(0)
    assert member.analysed and member.never_collapses
    assert member.load_multipliers == (math.inf, math.inf)
    with pytest.raises(ValueError, match="the nominal arch cannot be analysed: .*collapse"):
        check_nominal(thick_flat)


def test_the_rule_by_error_of_the_model(monkeypatch, nominal):
    """What building a model raises decides: cannot stand, no mechanism in one direction only or
    any other ValueError (a mechanism the four-link model does not describe) excludes the arch;
    any other error is no property of the arch and propagates."""
    import archquake.models

    for error, reason in ((CannotStandError("no thrust line"), "cannot stand"),
                          (NeverCollapsesError("no mechanism in direction r"), "not analysable"),
                          (ValueError("a joint opens over its whole depth"), "not analysable")):
        def raising(*args, error=error, **kwargs):
            raise error

        monkeypatch.setattr(archquake.models, "model_for", raising)
        assert analysable_model(nominal) == (None, reason)  # nominal: k finite both ways
    monkeypatch.setattr(archquake.models, "model_for",
                        lambda *a, **k: (_ for _ in ()).throw(RuntimeError("integrator")))
    with pytest.raises(RuntimeError, match="integrator"):
        analysable_model(nominal)
    # and a bridge's draws its piers cannot seat (BridgeSample)
    assert set(EXCLUSIONS) == {"not an arch", "cannot stand", "not analysable", "not seated"}


def test_summary_and_the_study_without_arches():
    excluded = {4: "cannot stand", 1: "not an arch", 2: "cannot stand"}
    assert exclusion_summary(6, excluded) == {
        "drawn": 6, "analysed": 3,
        "excluded": {"not an arch": [1], "cannot stand": [2, 4]}}
    check_analysed(6, excluded, 0.5)  # six drawn, three excluded: three arches to count
    with pytest.raises(ValueError, match=r"every one of the 3 irregular arches was excluded "
                                         r"\(not an arch: 1, cannot stand: 2\).*epsilon = 0.5"):
        check_analysed(3, {0: "cannot stand", 1: "not an arch", 2: "cannot stand"}, 0.5)


def test_the_nominal_model_is_built_once_per_arch_and_restitution(nominal):
    a = nominal_model(nominal)
    again = nominal_model(type(nominal).from_dict(nominal.to_dict()))  # an equal arch
    assert again is a
    assert nominal_model(nominal, ModelSpec(restitution="paper")) is not a
    assert nominal_model(nominal, ModelSpec(restitution="paper")).restitution == (0.875, 0.875)
    assert a.load_multipliers == pytest.approx(load_multipliers(nominal), abs=1e-9)
    assert nominal_json(nominal) == nominal_json(type(nominal).from_dict(nominal.to_dict()))
