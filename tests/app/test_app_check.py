"""The page's seismic code check ("Is it safe here?", ``POST /api/check``): its numbers are the
library's check of the same structure at the same site, its site is refused as the command line
refuses it (the field named where ``archquake check`` names the option), and a structure that
cannot stand is an answer."""

import json

import pytest
from app_reference import cli_error, fields_named

from archquake.app.inputs import site_from_spec, structure_from_spec
from archquake.constants import GRAVITY
from archquake.site.local_mechanism import SiteAction, check_local_mechanism, confidence_factor
from archquake.site.spectra import ntc2018_spectrum

SITE = {"ag": 0.25, "f0": 2.4, "tc_star": 0.3, "soil": "C"}
"""The site of ``archquake check --code ntc2018 --ag 0.25 --f0 2.4 --tc-star 0.3 --soil C``."""
SLC = {"slc_ag": 0.32, "slc_f0": 2.5, "slc_tc_star": 0.32}


def post(client, structure, site):
    return client.post("/api/check", json={"structure": structure, "site": site})


def test_check_is_the_librarys_check_of_the_same_structure_and_site(client):
    answer = post(client, {"thickness": 1.2}, {**SITE, **SLC, "knowledge_level": "LC2"})
    assert answer.status_code == 200
    shown = answer.json()["check"]
    _, arch = structure_from_spec({"thickness": 1.2})
    actions = [SiteAction.of("SLV", ntc2018_spectrum(0.25, 2.4, 0.3, "C")),
               SiteAction.of("SLC", ntc2018_spectrum(0.32, 2.5, 0.32, "C"))]
    direct = check_local_mechanism(arch, actions, confidence_factor=confidence_factor("LC2"))
    for got, want in zip(shown["participation"], direct.participations, strict=True):
        assert got["alpha0"] == pytest.approx(want.alpha0, rel=1e-12)
        assert got["mass_fraction"] == pytest.approx(want.mass_fraction, rel=1e-12)
        assert got["a0_star_g"] == pytest.approx(want.spectral_acceleration_g, rel=1e-12)
    for got, want in zip(shown["linear"] + shown["nonlinear"], direct.linear + direct.nonlinear,
                         strict=True):
        assert (got["limit_state"], got["direction"]) == (want.limit_state, want.direction)
        assert got["ratio"] == pytest.approx(want.ratio, rel=1e-12)
        assert got["passes"] == want.passes
        assert got["pga_capacity_ag_g"] == pytest.approx(want.pga_capacity, rel=1e-12)
    for got, want in zip(shown["curves"], direct.curves, strict=True):
        assert got["d0_star_m"] == pytest.approx(want.d0, rel=1e-12)
        assert got["d_star_m"] == pytest.approx(want.spectral_displacement.tolist(), abs=1e-7)
        assert got["a_star_g"] == pytest.approx((want.spectral_acceleration / GRAVITY).tolist(),
                                                abs=1e-7)
    verdicts = {v["limit_state"]: v for v in shown["verdicts"]}
    assert set(verdicts) == {"SLV", "SLC"}
    for state, verdict in verdicts.items():
        assert verdict["holds"] == direct.holds(state)
        assert verdict["pga_capacity_g"] == pytest.approx(direct.pga_capacity(state), rel=1e-12)
        assert verdict["sentence"].startswith(
            f"{state} {'holds' if direct.holds(state) else 'FAILS'}: capacity/demand ")
    # independent of the library's arithmetic: the linear demand at SLV is a_g S / q with
    # S = S_S = 1.70 - 0.60 F0 a_g = 1.70 - 0.60 * 2.4 * 0.25 = 1.34 (NTC 2018 Table 3.2.IV,
    # soil C, T1) and q = 2: 0.25 * 1.34 / 2 = 0.1675 g
    assert [c["demand_g"] for c in shown["linear"]] == pytest.approx([0.1675, 0.1675], rel=1e-12)
    assert shown["code"] == "NTC 2018 §8.7.1, Circolare 2019 §C8.7.1"


def test_knowledge_level_divides_a0_star_by_its_confidence_factor(client):
    # a0* = alpha0 g / (e* FC) (Circolare 2019 eq. C8.7.1.4), FC = 1.35 (LC1), 1.00 (LC3):
    # the same mechanism's a0* at LC3 is 1.35 times that at LC1, its linear ratio too
    lc1, lc3 = (post(client, {}, {**SITE, "knowledge_level": level}).json()["check"]
                for level in ("LC1", "LC3"))
    for a, b in zip(lc1["participation"], lc3["participation"], strict=True):
        assert b["a0_star_g"] / a["a0_star_g"] == pytest.approx(1.35, rel=1e-12)
    for a, b in zip(lc1["linear"], lc3["linear"], strict=True):
        assert b["ratio"] / a["ratio"] == pytest.approx(1.35, rel=1e-12)


def test_sentence_states_the_governing_numbers(client):
    shown = post(client, {}, SITE).json()["check"]
    (verdict,) = shown["verdicts"]
    linear = min(c["ratio"] for c in shown["linear"])
    nonlinear = min(c["ratio"] for c in shown["nonlinear"])
    capacity = verdict["pga_capacity_g"]
    # the better route's PGA capacity: the larger over the routes of the lesser direction's
    assert capacity == pytest.approx(max(min(c["pga_capacity_ag_g"] for c in shown[route])
                                         for route in ("linear", "nonlinear")), rel=1e-12)
    assert verdict["sentence"] == (
        f"SLV {'holds' if linear >= 1 or nonlinear >= 1 else 'FAILS'}: capacity/demand "
        f"{linear:.2f} (linear), {nonlinear:.2f} (nonlinear); PGA capacity "
        f"a_g = {capacity:.3f} g against the site's 0.25 g")


def test_structure_that_cannot_stand_is_an_answer(client):
    answer = post(client, {"thickness": 0.3}, SITE)
    assert answer.status_code == 200
    body = answer.json()
    assert body["verdict"] == "cannot stand" and body["check"] is None
    assert "cannot stand" in body["message"]


@pytest.mark.parametrize("site, field", [
    ({**SITE, "soil": "F"}, "soil"),
    ({**SITE, "topography": "T9"}, "topography"),
    ({**SITE, "knowledge_level": "LC4"}, "knowledge_level"),
    ({**SITE, "ag": 0}, "ag"),
    ({**SITE, "ag": -0.1}, "ag"),
    ({**SITE, "ag": 2.45}, "ag"),
    ({**SITE, "ag": 1e300}, "ag"),
    ({**SITE, "ag": "0.2.5"}, "ag"),
    ({**SITE, "ag": True}, "ag"),
    ({**SITE, "f0": 1.9}, "f0"),
    ({**SITE, "f0": 3.6}, "f0"),
    ({**SITE, "f0": "abc"}, "f0"),
    ({**SITE, "tc_star": [0.3]}, "tc_star"),
    ({"ag": 0.25, "f0": 2.4}, "tc_star"),
    ({**SITE, "slc_ag": 0.3}, "slc_ag"),
    ({**SITE, **SLC, "slc_f0": 5}, "slc_f0"),
    ({**SITE, **SLC, "slc_ag": "x"}, "slc_ag"),
], ids=["soil", "topography", "knowledge-level", "ag-zero", "ag-negative", "ag-in-m/s2",
        "ag-huge", "ag-text", "ag-bool", "f0-low", "f0-high", "f0-text", "tc-star-list",
        "tc-star-missing", "slc-in-part", "slc-f0", "slc-ag-text"])
def test_bad_site_is_refused_naming_the_field(client, site, field):
    refused = post(client, {}, site)
    assert refused.status_code == 400
    assert refused.json()["error"].startswith(f"{field} ")
    with pytest.raises(ValueError, match=f"^{field} "):
        site_from_spec(site)


def test_nan_and_unknown_fields_are_refused(client):
    body = json.dumps({"structure": {}, "site": {**SITE, "ag": float("nan")}})
    assert "NaN" in body  # Python's JSON writes (and reads) a NaN literal
    refused = client.post("/api/check", content=body.encode(),
                          headers={"Content-Type": "application/json"})
    assert refused.status_code == 400
    assert refused.json()["error"].startswith("ag must be a finite number")
    unknown = post(client, {}, {**SITE, "pga": 0.3})
    assert unknown.status_code == 400 and "unknown site field(s) ['pga']" in unknown.json()["error"]
    assert post(client, {}, None).json()["error"].startswith("the site must be")
    bad_structure = post(client, {"thickness": -1}, SITE)
    assert bad_structure.status_code == 400
    assert bad_structure.json()["error"].startswith("thickness ")


@pytest.mark.parametrize("field, option, value", [
    ("soil", "--soil", "F"), ("f0", "--f0", "1.5"), ("knowledge_level", "--knowledge-level",
                                                     "LC4")])
def test_refusal_is_archquake_checks_message(client, field, option, value):
    argv = {"--ag": "0.25", "--f0": "2.4", "--tc-star": "0.3", "--soil": "C", option: value}
    expected = fields_named(cli_error("check", "--code", "ntc2018",
                                      *[x for pair in argv.items() for x in pair]))
    site = {**SITE, field: float(value) if field == "f0" else value}
    assert post(client, {}, site).json()["error"] == expected


def test_limit_state_no_check_applies_to_is_said_not_checked(client):
    # fill inertia 'none' is a limit-analysis model: the library makes no nonlinear check, so
    # SLC (which has only the nonlinear route) is not checked, and SLV only by the linear one
    structure = {"fill_cover": 0.5, "fill_inertia": "none"}
    shown = post(client, structure, {**SITE, **SLC}).json()["check"]
    _, arch = structure_from_spec(structure)
    direct = check_local_mechanism(
        arch, [SiteAction.of("SLV", ntc2018_spectrum(0.25, 2.4, 0.3, "C")),
               SiteAction.of("SLC", ntc2018_spectrum(0.32, 2.5, 0.32, "C"))],
        confidence_factor=1.35)
    assert direct.holds("SLC") is None and shown["notes"] == list(direct.notes)
    verdicts = {v["limit_state"]: v for v in shown["verdicts"]}
    assert verdicts["SLC"]["holds"] is None
    assert verdicts["SLC"]["sentence"].startswith("SLC not checked: ")
    assert list(verdicts["SLV"]["ratios"]) == ["linear"]
    assert direct.pga_capacity("SLV") is None  # holds beyond the largest a_g searched
    assert verdicts["SLV"]["sentence"].endswith("PGA capacity a_g > 1.5 g against the site's "
                                                "0.25 g")
    assert shown["nonlinear"] == [] and shown["curves"] == []
