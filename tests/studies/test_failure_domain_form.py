"""The failure domain's lossless JSON form: ``FailureDomain.to_dict`` through JSON and back gives
the same domain, slice by slice and attribute by attribute, and the same derived numbers (the
failure curve, Oppenheim's curve, the bounds) as the domain computed."""

import json
import math

import numpy as np

from archquake.fourlink import FourLinkModel
from archquake.studies.failure_domain import DomainSlice, FailureDomain, Interval, domain_of


def through_json(domain: FailureDomain) -> FailureDomain:
    return FailureDomain.from_dict(json.loads(json.dumps(domain.to_dict())))


def same(a: FailureDomain, b: FailureDomain) -> None:
    assert a.slices == b.slices  # durations, intervals (ends, outcome, half cycle), resolution
    for name in ("direction", "limit_multiplier", "load_multipliers", "motion", "extend_to_g",
                 "model", "search", "analyses"):
        assert getattr(a, name) == getattr(b, name), name
    np.testing.assert_array_equal(a.restitution, b.restitution)  # nan where none
    np.testing.assert_array_equal(a.failure_accelerations_g, b.failure_accelerations_g)
    np.testing.assert_array_equal(a.first_half_cycle_accelerations_g,
                                  b.first_half_cycle_accelerations_g)
    assert a.to_list() == b.to_list()


def test_a_computed_domain_survives_the_round_trip(nominal):
    model = FourLinkModel.from_arch(nominal, "paper")
    domain = domain_of(model, [0.2, 0.5, 1.0], np.linspace(0.3, 1.5, 13), direction="r",
                       resolution_g=1e-3, extend_to_g=None)
    assert any(len(s.intervals) > 1 for s in domain.slices)
    back = through_json(domain)
    same(back, domain)
    assert back.restitution == domain.restitution == (0.875, 0.875)


def test_every_outcome_class_and_a_model_without_restitution():
    intervals = (Interval(0.2, 0.3, "rest", 0), Interval(0.3, 0.41, "recovery", 0),
                 Interval(0.41, 0.5, "undecided", 0), Interval(0.5, 0.9, "collapse", 2),
                 Interval(0.9, 2.0, "collapse", 1))
    domain = FailureDomain((DomainSlice(0.4, intervals, 5e-3),
                            DomainSlice(0.8, (Interval(0.2, 2.0, "collapse", 1),), 5e-3)),
                           "l", 0.3, (0.3, 0.31), (math.nan, math.nan), extend_to_g=6.0,
                           model={"model": "rigid-blocks", "friction": 0.8},
                           search="screened", analyses=(40, 12))
    data = domain.to_dict()
    assert data["restitution"] == [None, None]
    assert data["slices"][0]["intervals"][2] == {"from": 0.41, "to": 0.5,
                                                 "outcome": "undecided", "half_cycle": 0}
    back = through_json(domain)
    same(back, domain)
    assert back.slices[0].failure_acceleration_g == 0.5
    assert back.slices[1].failure_acceleration_bound == "upper"


def test_the_slices_are_those_of_to_list_with_their_resolution(nominal):
    domain = domain_of(FourLinkModel.from_arch(nominal, "paper"), [0.5], [0.3, 0.6, 0.9],
                       resolution_g=1e-2, extend_to_g=None)
    data = domain.to_dict()
    assert [{k: v for k, v in s.items() if k != "resolution_g"} for s in data["slices"]] == \
        domain.to_list()
    assert [s["resolution_g"] for s in data["slices"]] == [1e-2]
    # kept by an earlier version (a resumed assessment): the width under its former key
    for piece in data["slices"]:
        piece["resolution"] = piece.pop("resolution_g")
    same(FailureDomain.from_dict(json.loads(json.dumps(data))), domain)
