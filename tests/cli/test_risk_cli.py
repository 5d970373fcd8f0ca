"""``archquake risk``: a fragility (NRML, a lognormal given by its median and dispersion) and a
hazard curve (OpenQuake's export, a plain CSV) give the annual frequency of collapse, checked
against Cornell's closed form and OpenQuake's published case; bad input is one line and exit
status 2."""

import json
import math
from pathlib import Path

import pytest

from archquake.cli import main

DATA = Path(__file__).parents[1] / "data" / "site"
QA_CURVE = str(DATA / "openquake_classical_damage_case_1_hcurves_PGA.csv")
QA_CONTINUOUS = str(DATA / "openquake_classical_damage_case_1_fragility_continuous.xml")
MANUAL_CURVE = str(DATA / "openquake_manual_hazard_curve-mean-PGA.csv")


def power_law_csv(path, k0=1e-3, k=2.0, im_header="PGA"):
    levels = [1e-4 * 10 ** (i / 4) for i in range(21)]  # 1e-4 to 10 g
    rows = [f"{x!r},{k0 * x**-k!r}" for x in levels]
    header = [f"{im_header},annual frequency [1/yr]"] if im_header else []
    path.write_text("\n".join(["# power law", *header, *rows]) + "\n")
    return str(path)


def test_lognormal_on_a_csv_power_law_is_cornells_closed_form(capsys, tmp_path):
    hazard = power_law_csv(tmp_path / "site.csv")
    assert main(["risk", "--median", "0.5", "--dispersion", "0.4", "--im", "PGA", "--hazard",
                 hazard, "--years", "50", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    # 1e-3 * 0.5^-2 * exp(4 * 0.16 / 2) = 4e-3 * exp(0.32) = 4e-3 * 1.377128 = 5.508513e-3
    assert out["annual_frequency"] == pytest.approx(5.508513e-3, rel=1e-6)
    assert out["probability"] == pytest.approx(1 - math.exp(-50 * 5.508513e-3), rel=1e-6)
    assert out["units"]["annual_frequency"] == "1/yr"
    assert out["hazard"]["im"] == "PGA"


def test_text_output_states_units(capsys):
    assert main(["risk", "--fragility", QA_CONTINUOUS, "--hazard", QA_CURVE,
                 "--years", "100"]) == 0
    text = capsys.readouterr().out
    assert "limit state 'complete'" in text
    assert "annual frequency of collapse lambda_c = " in text and "1/yr" in text
    assert "probability of collapse in 100 years = " in text
    assert "return period of collapse = " in text and " yr" in text
    assert "-ln(1 - poe) / 50 (Poisson)" in text
    assert "share of lambda_c from the tail beyond 1.4 g" in text


def test_openquake_case_json(capsys):
    assert main(["risk", "--fragility", QA_CONTINUOUS, "--hazard", QA_CURVE,
                 "--hazard-format", "openquake", "--years", "100", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    # median 0.6 / sqrt(1.64) = 0.468521 g, beta sqrt(ln 1.64) = 0.703346
    assert out["fragility"]["median"] == pytest.approx(0.468521, rel=1e-6)
    assert out["fragility"]["dispersion"] == pytest.approx(0.703346, rel=1e-6)
    # OpenQuake's coarse rule publishes 0.0714 in 100 years; the integral is 10 % lower in
    # frequency (tests/site/test_risk.py shows the rule converging to it on a fine grid)
    assert out["probability"] == pytest.approx(0.06505, abs=5e-5)


@pytest.mark.parametrize("argv, message", [
    (["--median", "0.5", "--dispersion", "0.4", "--im", "SA(1.0)", "--hazard", QA_CURVE],
     "is a hazard curve of PGA, but SA(1.0) was asked for"),
    (["--fragility", QA_CONTINUOUS, "--limit-state", "collapse", "--hazard", QA_CURVE],
     "has no limit state 'collapse': its states are slight, moderate, extensive, complete"),
    (["--fragility", QA_CONTINUOUS, "--hazard", MANUAL_CURVE],
     "holds 4 sites: choose one with site_index (--site-index) in [0, 4)"),
    (["--median", "-0.5", "--dispersion", "0.4", "--im", "PGA", "--hazard", QA_CURVE],
     "--median must be > 0, got -0.5"),
    (["--median", "0.5", "--im", "PGA", "--hazard", QA_CURVE],
     "give --fragility, or both --median and --dispersion"),
    (["--median", "0.5", "--dispersion", "0.4", "--hazard", QA_CURVE],
     "--median and --dispersion need --im"),
    (["--fragility", QA_CONTINUOUS, "--hazard", QA_CURVE, "--years", "0"],
     "--years must be > 0, got 0.0"),
    (["--fragility", "no-such.xml", "--hazard", QA_CURVE], "does not exist"),
])
def test_bad_input_is_one_line_and_exit_status_2(capsys, argv, message):
    assert main(["risk", *argv]) == 2
    err = capsys.readouterr().err
    assert err.startswith("archquake: error: ") and message in err
    assert err.count("\n") == 1


def test_mismatched_measures_name_both(capsys, tmp_path):
    hazard = power_law_csv(tmp_path / "sa.csv", im_header="SA(1.0)")
    assert main(["risk", "--fragility", QA_CONTINUOUS, "--hazard", hazard]) == 2
    err = capsys.readouterr().err
    assert "the fragility is in PGA but the hazard curve in SA(1.0)" in err


def test_non_monotone_and_negative_hazard_are_refused(capsys, tmp_path):
    bad = tmp_path / "bad.csv"
    bad.write_text("PGA,f\n0.1,0.01\n0.2,0.02\n")
    assert main(["risk", "--fragility", QA_CONTINUOUS, "--hazard", str(bad)]) == 2
    assert "row 1: the annual frequency of exceedance must not increase" in \
        capsys.readouterr().err
    bad.write_text("PGA,f\n-0.1,0.01\n0.2,0.002\n")
    assert main(["risk", "--fragility", QA_CONTINUOUS, "--hazard", str(bad)]) == 2
    assert "row 0: the level must be a finite number > 0 [g]" in capsys.readouterr().err


def test_ntc_site_takes_the_fragilitys_measure(capsys, tmp_path):
    site = tmp_path / "site.csv"
    site.write_text("TR,ag,F0,Tc*\n30,0.06,2.48,0.27\n475,0.212,2.40,0.34\n"
                    "2475,0.36,2.44,0.37\n")
    assert main(["risk", "--median", "0.5", "--dispersion", "0.4", "--im", "SA(0.2)",
                 "--hazard", str(site), "--soil", "B", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["hazard"]["im"] == "SA(0.2)" and "soil B" in out["hazard"]["source"]
    # 1/TR at the ordinates
    assert out["hazard"]["frequencies"] == pytest.approx([1 / 30, 1 / 475, 1 / 2475])
    assert main(["risk", "--median", "0.5", "--dispersion", "0.4", "--im", "PGA", "--hazard",
                 str(site), "--site-index", "0"]) == 2
    assert "site_index (--site-index) is for OpenQuake files" in capsys.readouterr().err
