"""``archquake assess --site ...``: the report's code check at the site is the library's, made
independently here (the check, the risk from the trusted model's record fragility), the first
screen carries the verdict, and the regenerate command keeps the site."""

import json
import math
import shlex

import pytest
from test_assess import write_records  # noqa: E402  (tests/report is on the path)

from archquake.cli import main
from archquake.limit_analysis import both_directions
from archquake.reference_arches import oppenheim
from archquake.report.assess.site import site_part, trusted_pga_fragility, verdict_text
from archquake.site.fragility_models import LognormalCollapseFragility
from archquake.site.local_mechanism import check_local_mechanism
from archquake.site.risk import risk
from archquake.site.spec import SiteSpec

GRID = """TR,ag,F0,Tc*
30,0.079,2.39,0.27
50,0.104,2.33,0.28
72,0.126,2.32,0.29
101,0.148,2.32,0.30
140,0.170,2.34,0.31
201,0.197,2.35,0.32
475,0.261,2.36,0.35
975,0.331,2.40,0.36
2475,0.436,2.45,0.38
"""


@pytest.fixture(scope="module")
def assessed(tmp_path_factory):
    """A quick assessment of Oppenheim's arch at a site, through the command line."""
    base = tmp_path_factory.mktemp("assess_site")
    grid = base / "grid.csv"
    grid.write_text(GRID)
    records = write_records(base / "records")
    out = base / "report"
    assert main(["assess", "--records", str(records), "--quick", "--out", str(out),
                 "--no-progress", "--site", str(grid), "--soil", "C",
                 "--knowledge-level", "LC2"]) == 0
    results = json.loads((out / "results.json").read_text())
    return {"out": out, "grid": grid, "results": results}


def test_the_check_is_the_librarys(assessed):
    site = SiteSpec(grid=str(assessed["grid"]), soil="C", knowledge_level="LC2")
    direct = check_local_mechanism(oppenheim(), site.actions(), confidence_factor=1.2)
    check = assessed["results"]["site"]["check"]
    assert check["verdict"] == {s: direct.holds(s) for s in ("SLV", "SLC")}
    for mine, theirs in zip(check["nonlinear"], direct.nonlinear, strict=True):
        assert mine["ratio"] == pytest.approx(theirs.ratio, rel=1e-12)
    assert check["participation"][0]["confidence_factor"] == 1.2


def test_the_risk_convolves_the_reported_fragility_with_the_sites_curve(assessed):
    results = assessed["results"]
    entry, model = trusted_pga_fragility(results)
    fit = entry["lognormal"]
    site = SiteSpec(grid=str(assessed["grid"]), soil="C")
    direct = risk(LognormalCollapseFragility(fit["median"], fit["dispersion"], "PGA"),
                  site.hazard_curve(), years=50.0)
    mine = results["site"]["risk"]
    assert mine["annual_frequency"] == pytest.approx(direct.annual_frequency, rel=1e-12)
    assert mine["probability"] == pytest.approx(1 - math.exp(-50 * direct.annual_frequency),
                                                rel=1e-9)
    assert mine["model"] == model


def test_the_first_screen_and_section_six_carry_the_check(assessed):
    text = (assessed["out"] / "report.md").read_text()
    summary = text.split("## 1.")[0]
    assert "CODE CHECK AT THE SITE" in summary
    assert "## 6. Is it safe here?" in text and "fig6_capacity_curve.png" in text
    assert verdict_text(assessed["results"]["site"]) in summary
    # the dynamic route is made or says why not; never silently absent
    dynamic = assessed["results"]["site"]["dynamic"]
    assert ("verdict" in dynamic) or dynamic["skipped"]


def test_the_regenerate_command_keeps_the_site(assessed):
    command = assessed["results"]["command"]["regenerate"]
    words = shlex.split(command)
    assert words[words.index("--site") + 1] == str(assessed["grid"])
    assert words[words.index("--knowledge-level") + 1] == "LC2"


def test_the_risk_takes_the_trusted_models_fragility():
    # where the first screen trusts the rigid blocks, their study's fit is the risk's
    results = {"trusted": {"model": "rigid-blocks"},
               "records": {"ims": {"pga": {"lognormal": {"median": 0.9, "dispersion": 0.3}}}},
               "rigid_block_studies": {"records": {"ims": {"pga": {
                   "lognormal": {"median": 0.6, "dispersion": 0.4}}}}}}
    entry, model = trusted_pga_fragility(results)
    assert model == "rigid-blocks" and entry["lognormal"]["median"] == 0.6


def test_a_spectrum_site_has_no_risk_and_says_why():
    site = SiteSpec(code="ntc2018", ag=0.25, f0=2.4, tc_star=0.3, soil="C")
    summary, check = site_part(oppenheim(), site, [], {"records": {}})
    assert "national-grid" in summary["risk"]["skipped"]
    assert "skipped" in summary["dynamic"]
    assert check.linear and summary["check"]["verdict"]["SLV"] == check.holds("SLV")
    assert both_directions(oppenheim())[0].load_multiplier == pytest.approx(
        summary["check"]["participation"][0]["alpha0"], rel=1e-12)


@pytest.mark.parametrize("argv, option", [
    (["assess", "--ag", "0.25", "--out", "x"], "--site"),
    (["assess", "--code", "ntc2018", "--ag", "0.25", "--f0", "2.4", "--out", "x"],
     "--tc-star"),
])
def test_site_options_without_a_site_are_refused(argv, option, capsys, tmp_path,
                                                 monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(argv) == 2
    assert option in capsys.readouterr().err


def test_assess_refuses_a_passive_fill_before_writing_anything(tmp_path, capsys):
    # both dynamic models run in an assessment, and neither carries the passive reaction
    out = tmp_path / "report"
    assert main(["assess", "--quick", "--fill-cover", "0.7", "--fill-passive", "32,0.3",
                 "--out", str(out), "--no-progress"]) == 2
    assert "--fill-passive" in capsys.readouterr().err
    assert not out.exists() or not any(out.iterdir())
