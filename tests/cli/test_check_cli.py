"""``archquake check``: the site's actions reach the check (the table's a_g at the limit
states' return periods), the output carries the check, and every bad input is one line
``archquake: error: ...`` naming its option, exit status 2."""

import json
import math

import pytest

from archquake.cli import main
from site_reference import GRID_TABLE

SITE = GRID_TABLE

NTC_C = ["check", "--code", "ntc2018", "--ag", "0.25", "--f0", "2.4", "--tc-star", "0.3",
         "--soil", "C"]


def _json(argv, capsys):
    assert main([*argv, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_site_gives_slv_and_slc_at_their_return_periods(tmp_path, capsys):
    # V_N = 50 years, class II: T_R = -50 / ln(1 - 0.10) = 474.6 years (SLV), just below the
    # table's 475, and -50 / ln(1 - 0.05) = 974.8 years (SLC): Annex A's log-log interpolation
    site = tmp_path / "site.csv"
    site.write_text(SITE)
    out = _json(["check", "--site", str(site), "--soil", "B", "--knowledge-level", "LC2"],
                capsys)
    for state, p_vr, (tr1, ag1), (tr2, ag2) in (("SLV", 0.10, (201, 0.148), (475, 0.212)),
                                                 ("SLC", 0.05, (475, 0.212), (975, 0.270))):
        tr = -50.0 / math.log(1.0 - p_vr)
        ag = math.exp(math.log(ag1) + math.log(ag2 / ag1) * math.log(tr / tr1)
                      / math.log(tr2 / tr1))
        assert out["actions"][state]["ag_g"] == pytest.approx(ag, rel=1e-12)
    assert {c["limit_state"] for c in out["nonlinear"]} == {"SLV", "SLC"}
    assert all(p["confidence_factor"] == 1.2 for p in out["participation"])
    # the verdict is the routes': SLV holds when a route holds in both directions
    linear = all(c["passes"] for c in out["linear"])
    nonlinear = all(c["passes"] for c in out["nonlinear"] if c["limit_state"] == "SLV")
    assert out["verdict"]["SLV"] == (linear or nonlinear)


def test_one_spectrum_is_the_slv_action_and_the_text_names_the_clauses(capsys):
    assert main(NTC_C) == 0
    text = capsys.readouterr().out
    assert "Circolare 2019 §C8.7.1" in text and "Verdict SLV" in text
    assert "SLC" not in text.split("Verdict")[0].split("Nonlinear")[0]


def test_plot_writes_the_capacity_curve(tmp_path, capsys):
    path = tmp_path / "capacity.png"
    assert main([*NTC_C, "--plot", str(path)]) == 0
    assert path.stat().st_size > 10_000


@pytest.mark.parametrize("argv, option", [
    (["check"], "--code"),
    ([*NTC_C, "--knowledge-level", "LC4"], "--knowledge-level"),
    ([*NTC_C, "--confidence-factor", "0.8"], "--confidence-factor"),
    ([*NTC_C, "--knowledge-level", "LC1", "--confidence-factor", "1.1"], "--confidence-factor"),
    ([*NTC_C, "--limit-state", "SLD"], "--limit-state"),
    ([*NTC_C, "--elevation", "6"], "--building-height"),
    ([*NTC_C, "--elevation", "16", "--building-height", "12", "--building-period", "0.4",
      "--storeys", "4"], "--elevation"),
    (["check", "--code", "ntc2018", "--ag", "0.25", "--f0", "1.5", "--tc-star", "0.3"],
     "--f0"),
    (["check", "--code", "ntc2018", "--ag", "-0.25", "--f0", "2.4", "--tc-star", "0.3"],
     "--ag"),
    (["check", "--code", "ntc2018", "--ag", "0.25", "--f0", "2.4", "--tc-star", "0.3",
      "--soil", "Z"], "--soil"),
])
def test_bad_input_names_its_option(argv, option, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("archquake: error:") and option in err
    assert "Traceback" not in err


@pytest.mark.parametrize("argv, option", [
    (["check", "--site", "/no/such/site.csv"], "--site"),
    (["check", "--code", "user", "--file", "/no/such/spectrum.csv"], "--file"),
])
def test_a_site_file_that_cannot_be_read_is_named_by_its_option(argv, option, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"archquake: error: {option}:") and "Traceback" not in err
