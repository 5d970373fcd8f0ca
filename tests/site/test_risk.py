"""The annual frequency of collapse: against Cornell's closed form (power-law hazard, lognormal
fragility), a hand integration of a piecewise-linear fragility, OpenQuake's published
classical-damage result (its own discrete rule, written out here) and, where it is installed,
OpenQuake's risk library; the fragility readers (NRML continuous and discrete, archquake's own
NRML, a record fragility study with undecided analyses) and their refusals."""

import json
import math
import os
import subprocess
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from archquake.results_io import lognormal_moments, save_study, write_fragility_nrml
from archquake.site.fragility_models import (
    DiscreteCollapseFragility,
    LognormalCollapseFragility,
    lognormal_from_moments,
    read_fragility,
    read_fragility_nrml,
)
from archquake.site.hazard import HazardCurve, read_hazard_curve
from archquake.site.risk import risk

DATA = Path(__file__).parents[1] / "data" / "site"
QA_CURVE = DATA / "openquake_classical_damage_case_1_hcurves_PGA.csv"
QA_CONTINUOUS = DATA / "openquake_classical_damage_case_1_fragility_continuous.xml"
QA_DISCRETE = DATA / "openquake_classical_damage_case_1_fragility_discrete.xml"
QA_P_COMPLETE_100_YEARS = 7.144331e-02
"""OpenQuake's expected probability of the complete state in 100 years,
qa_tests_data/classical_damage/case_1/expected/damage_continuous.csv (engine 3.22)."""


def power_law(k0, k, low=1e-4, high=10.0, n=30):
    x = np.geomspace(low, high, n)
    return HazardCurve(x, k0 * x**-k, im="PGA")


@pytest.mark.parametrize("k, median, beta", [(2.0, 0.5, 0.4), (3.0, 0.3, 0.6),
                                              (1.5, 1.0, 0.2), (2.5, 0.2, 0.8)])
def test_matches_cornells_closed_form(k, median, beta):
    # lambda(x) = k0 x^-k, lognormal fragility: lambda_c = k0 theta^-k exp(k^2 beta^2 / 2)
    # (Cornell et al. 2002, eq. 9). The curve spans 1e-4 to 10 g, beyond which the tail is the
    # same power law, and P_f(1e-4 g) < Phi(-10): the closed form holds to rounding.
    k0 = 1e-3
    result = risk(LognormalCollapseFragility(median, beta), power_law(k0, k))
    exact = k0 * median**-k * math.exp(k * k * beta * beta / 2)
    assert result.annual_frequency == pytest.approx(exact, rel=1e-6)  # the brief: < 0.5 %
    assert result.integration_error < 1e-6 * exact
    assert result.probability == pytest.approx(1 - math.exp(-50 * exact), rel=1e-6)
    assert result.return_period == pytest.approx(1 / exact, rel=1e-6)


def test_piecewise_linear_fragility_by_hand():
    # lambda = 1e-3 x^-2; P = 0 below 0.1 g, linear to 0.5 at 0.5 g (slope 1.25 /g), to 1 at
    # 1 g (slope 1 /g), 1 above. By parts, lambda_c = integral of lambda dP
    #   = 1e-3 [1.25 (1/0.1 - 1/0.5) + 1.0 (1/0.5 - 1/1)] = 1e-3 (10 + 1) = 0.011 1/yr
    fragility = DiscreteCollapseFragility([0.1, 0.5, 1.0], [0.0, 0.5, 1.0])
    hazard = HazardCurve(np.geomspace(0.01, 0.8, 12), 1e-3 * np.geomspace(0.01, 0.8, 12)**-2.0)
    result = risk(fragility, hazard)
    assert result.annual_frequency == pytest.approx(0.011, rel=1e-8)
    # beyond 0.8 g (the tail): P(0.8) lambda(0.8) + integral from 0.8 to 1 of lambda dP
    #   = 0.8 * 1e-3 / 0.64 + 1e-3 * 1.0 * (1/0.8 - 1) = 1.25e-3 + 0.25e-3 = 1.5e-3
    assert result.tail_share == pytest.approx(1.5e-3 / 0.011, rel=1e-8)
    # 50 years: 1 - exp(-0.55) = 0.423050
    assert result.probability == pytest.approx(0.423050, abs=1e-6)


def test_a_jump_at_the_first_fragility_level_is_counted():
    # P = 0.2 from 0.2 g on (a jump), then 0.2 held: lambda_c = 0.2 lambda(0.2 g) = 0.2 * 1e-3
    # / 0.04 = 5e-3 1/yr
    fragility = DiscreteCollapseFragility([0.2], [0.2])
    result = risk(fragility, power_law(1e-3, 2.0, low=0.01, high=1.0))
    assert result.annual_frequency == pytest.approx(5e-3, rel=1e-9)


def openquake_rule(hazard_poes, investigation_time, probabilities):
    """OpenQuake's classical_damage (openquake.risklib.scientific): annual frequencies
    -ln(1 - poe)/T, the frequency of occurrence of each level the difference of the means of
    its neighbours' frequencies (the first and last level doubled), dotted with P_f."""
    afoe = -np.log(1 - np.asarray(hazard_poes)) / investigation_time
    padded = np.concatenate([[afoe[0]], afoe, [afoe[-1]]])
    means = (padded[:-1] + padded[1:]) / 2
    return (means[:-1] - means[1:]) @ probabilities


def test_openquake_published_classical_damage_through_our_readers():
    hazard = read_hazard_curve(QA_CURVE)
    fragility = read_fragility_nrml(QA_CONTINUOUS)  # default: the 'complete' limit state
    assert fragility.no_damage_limit == 0.05
    poes = 1 - np.exp(-hazard.frequencies * 50.0)
    # OpenQuake's own discrete rule on the file's 28 levels gives its published number
    lam = openquake_rule(poes, 50.0, fragility(hazard.levels))
    assert 1 - math.exp(-100 * lam) == pytest.approx(QA_P_COMPLETE_100_YEARS, rel=1e-6)
    # ... which is 10 % above the integral: 0.05-g steps on a curve that falls by 3 between
    # 0.05 and 0.1 g. On a grid of 28000 levels (and adding the tail beyond 1.4 g, which the
    # rule leaves out) the rule converges to our integral.
    result = risk(fragility, hazard, years=100.0)
    assert lam / result.annual_frequency == pytest.approx(1.102, abs=0.001)
    x = np.linspace(0.05, 1.4, 28000)
    fine = openquake_rule(1 - np.exp(-hazard.frequency(x) * 50.0), 50.0, fragility(x))
    fine += fragility(1.4) * hazard.frequencies[-1]
    assert fine == pytest.approx(result.annual_frequency, rel=1e-4)
    assert result.tail_share == pytest.approx(fragility(1.4) * hazard.frequencies[-1]
                                              / result.annual_frequency, rel=0.1)


# --- OpenQuake's own risk library (its own interpreter, when installed) ----------------------

OPENQUAKE_CLASSICAL_DAMAGE = r"""
import json, sys
import numpy as np
from openquake.risklib import scientific

args = json.loads(sys.argv[1])
ff = scientific.FragilityFunctionContinuous("complete", args["mean"], args["stddev"],
                                            args["min"], args["max"], args["nodamage"])

class Functions(list):
    steps_per_interval = None  # older engines read it from the list

out = {}
for key, (imls, poes) in args["curves"].items():
    poos = scientific.classical_damage(Functions([ff]), np.array(imls), np.array(poes), 50.0,
                                       100.0)
    out[key] = float(poos[1])
print(json.dumps(out))
"""


def test_openquake_risk_library_agrees():
    from test_nrml_openquake import openquake_python

    python = openquake_python()
    if python is None:
        pytest.skip("OpenQuake is not installed: run `make openquake` (or set "
                    "ARCHQUAKE_OPENQUAKE_PYTHON)")
    hazard = read_hazard_curve(QA_CURVE)
    fragility = read_fragility_nrml(QA_CONTINUOUS)
    x = np.linspace(0.05, 1.4, 2800)
    curves = {"file": [hazard.levels.tolist(), (1 - np.exp(-hazard.frequencies * 50)).tolist()],
              "fine": [x.tolist(), (1 - np.exp(-hazard.frequency(x) * 50)).tolist()]}
    args = {"mean": 0.6, "stddev": 0.48, "min": 0.05, "max": 1.4, "nodamage": 0.05,
            "curves": curves}
    proc = subprocess.run([python, "-c", OPENQUAKE_CLASSICAL_DAMAGE, json.dumps(args)],
                          capture_output=True, text=True, timeout=600,
                          env={k: v for k, v in os.environ.items() if k != "PYTHONPATH"})
    assert proc.returncode == 0, proc.stderr[-3000:]
    out = json.loads(proc.stdout.strip().splitlines()[-1])
    assert out["file"] == pytest.approx(QA_P_COMPLETE_100_YEARS, rel=1e-5)
    result = risk(fragility, hazard, years=100.0)
    # OpenQuake's rule on 2800 levels, without the tail beyond 1.4 g: within 0.1 %
    lam = -math.log(1 - out["fine"]) / 100
    assert lam == pytest.approx(result.annual_frequency * (1 - result.tail_share), rel=1e-3)


# --- fragility readers -------------------------------------------------------------------------

def test_nrml_continuous_mean_stddev_give_back_median_and_dispersion(tmp_path):
    # a lognormal of median 0.35 g and beta 0.5: mean m = 0.35 exp(0.125) = 0.396605,
    # stddev s = m sqrt(exp(0.25) - 1) = 0.396605 * 0.533213 = 0.211475
    m = 0.35 * math.exp(0.125)
    s = m * math.sqrt(math.exp(0.25) - 1)
    assert (m, s) == pytest.approx(lognormal_moments(0.35, 0.5), rel=1e-12)
    path = tmp_path / "hand.xml"
    path.write_text(f"""<?xml version="1.0" encoding="utf-8"?>
<nrml xmlns="http://openquake.org/xmlns/nrml/0.5">
  <fragilityModel id="m" assetCategory="building" lossCategory="structural">
    <description>by hand</description>
    <limitStates>slight collapse</limitStates>
    <fragilityFunction id="arch" format="continuous" shape="logncdf">
      <imls imt="SA(0.5)" minIML="0.05" maxIML="2.0"/>
      <params ls="slight" mean="0.1" stddev="0.05"/>
      <params ls="collapse" mean="{m!r}" stddev="{s!r}"/>
    </fragilityFunction>
  </fragilityModel>
</nrml>
""")
    fragility = read_fragility_nrml(path)
    assert fragility.im == "SA(0.5)"
    assert fragility.median == pytest.approx(0.35, rel=1e-12)
    assert fragility.dispersion == pytest.approx(0.5, rel=1e-12)
    slight = read_fragility_nrml(path, limit_state="slight")
    # mean 0.1, stddev 0.05: 1 + s^2/m^2 = 1.25, median 0.1 / sqrt(1.25) = 0.0894427,
    # beta sqrt(ln 1.25) = 0.472381
    assert (slight.median, slight.dispersion) == pytest.approx((0.0894427, 0.472381), rel=1e-6)
    assert lognormal_from_moments(0.1, 0.05) == pytest.approx((0.0894427, 0.472381), rel=1e-6)


def test_reads_the_nrml_archquake_writes(tmp_path):
    path = write_fragility_nrml(tmp_path / "f.xml", [("masonry-arch", 0.42, 0.35),
                                                     ("masonry-arch-nominal", 0.6, 0.25)],
                                im="pga", min_iml=0.1, max_iml=2.0)
    first = read_fragility_nrml(path)
    assert (first.median, first.dispersion) == pytest.approx((0.42, 0.35), rel=1e-12)
    nominal = read_fragility_nrml(path, function_id="masonry-arch-nominal")
    assert (nominal.median, nominal.dispersion) == pytest.approx((0.6, 0.25), rel=1e-12)
    with pytest.raises(ValueError, match="no fragility function of SA\\(1.0\\): its intensity "
                                         "measures are PGA"):
        read_fragility_nrml(path, im="SA(1.0)")


def test_nrml_discrete_is_linear_between_levels():
    fragility = read_fragility_nrml(QA_DISCRETE)  # 'complete', the last state
    assert fragility.levels.tolist() == [0.05, 0.2, 0.4, 0.6, 0.8, 1.0, 1.2, 1.4]
    # halfway between 0.2 g (0.097) and 0.4 g (0.414): 0.2555; above 1.4 g: 0.959 held
    assert fragility([0.3, 2.0, 0.01]) == pytest.approx([0.2555, 0.959, 0.0])
    extreme = read_fragility_nrml(QA_DISCRETE, limit_state="extreme")
    assert extreme(0.4) == pytest.approx(0.636)


def test_nrml_without_the_collapse_state_is_refused_naming_its_states():
    with pytest.raises(ValueError, match="has no limit state 'collapse': its states are slight, "
                                         "moderate, extensive, complete"):
        read_fragility_nrml(QA_CONTINUOUS, limit_state="collapse")


def test_nrml_default_state_is_the_last_when_none_is_named_collapse(tmp_path):
    path = tmp_path / "states.xml"
    path.write_text("""<nrml xmlns="http://openquake.org/xmlns/nrml/0.5"><fragilityModel id="m"
      assetCategory="building" lossCategory="structural"><limitStates>light heavy</limitStates>
      <fragilityFunction id="a" format="discrete"><imls imt="PGA">0.1 0.2</imls>
      <poes ls="light">0.5 0.9</poes><poes ls="heavy">0.1 0.3</poes></fragilityFunction>
      </fragilityModel></nrml>""")
    assert read_fragility_nrml(path).probabilities.tolist() == [0.1, 0.3]


def _record_study(directory, failures, upper):
    """A record fragility study's summary.json as run_record_fragility writes it (its fields
    read here: im, levels, trials, failures, probability_upper, lognormal)."""
    trials = 10
    summary = {"im": "pga", "im_unit": "g", "levels": [0.2, 0.4, 0.8, 1.6], "trials": trials,
               "failures": failures, "probability": [f / trials for f in failures],
               "probability_upper": [u / trials for u in upper],
               "lognormal": {"median": 0.6, "dispersion": 0.5}}
    save_study(directory, pd.DataFrame({"arch": [0]}), summary=summary)
    return directory


def _piecewise_linear_risk(levels, probabilities, k0):
    """lambda_c of a piecewise-linear P (0 below the first level, held above the last) under
    lambda = k0 x^-2, by hand: P_0 lambda(x_0) + sum of s_j k0 (1/x_j - 1/x_{j+1})."""
    total = probabilities[0] * k0 / levels[0] ** 2
    for j in range(len(levels) - 1):
        slope = (probabilities[j + 1] - probabilities[j]) / (levels[j + 1] - levels[j])
        total += slope * k0 * (1 / levels[j] - 1 / levels[j + 1])
    return total


def test_record_fragility_study_undecided_give_an_upper_bound(tmp_path):
    study = _record_study(tmp_path / "rf", failures=[0, 2, 6, 9], upper=[1, 3, 7, 10])
    hazard = power_law(1e-3, 2.0, low=0.01, high=5.0)
    empirical = read_fragility(study, fit="empirical")
    assert empirical.undecided == 4
    result = risk(empirical.fragility, hazard, upper=empirical.upper)
    levels = [0.2, 0.4, 0.8, 1.6]
    assert result.annual_frequency == pytest.approx(
        _piecewise_linear_risk(levels, [0, 0.2, 0.6, 0.9], 1e-3), rel=1e-8)
    assert result.annual_frequency_upper == pytest.approx(
        _piecewise_linear_risk(levels, [0.1, 0.3, 0.7, 1.0], 1e-3), rel=1e-8)
    # lognormal: the study's fit below, a refit of the upper counts above
    lognormal = read_fragility(study)
    assert (lognormal.fragility.median, lognormal.fragility.dispersion) == (0.6, 0.5)
    assert lognormal.upper.median < 0.6
    bounds = risk(lognormal.fragility, hazard, upper=lognormal.upper)
    assert bounds.annual_frequency == pytest.approx(1e-3 * 0.6**-2 * math.exp(2 * 0.25),
                                                    rel=1e-6)
    assert bounds.annual_frequency_upper > bounds.annual_frequency
    # without undecided analyses there is no upper bound
    plain = read_fragility(_record_study(tmp_path / "plain", [0, 2, 6, 9], [0, 2, 6, 9]))
    assert plain.upper is None and plain.undecided == 0


def test_fragility_and_hazard_in_different_measures_are_refused():
    hazard = HazardCurve([0.1, 1.0], [1e-2, 1e-4], im="SA(1.0)")
    with pytest.raises(ValueError, match=r"the fragility is in PGA but the hazard curve in "
                                         r"SA\(1.0\)"):
        risk(LognormalCollapseFragility(0.5, 0.4, im="PGA"), hazard)


def test_bad_fragility_values_are_refused():
    with pytest.raises(ValueError, match="median of a lognormal fragility must be"):
        LognormalCollapseFragility(-0.5, 0.4)
    with pytest.raises(ValueError, match="fragility levels must be > 0"):
        DiscreteCollapseFragility([-0.1, 0.2], [0.0, 1.0])
    with pytest.raises(ValueError, match="years must be > 0"):
        risk(LognormalCollapseFragility(0.5, 0.4), power_law(1e-3, 2.0), years=0)


def test_assessment_folder_is_read_through_its_nrml_files(tmp_path):
    # archquake assess writes fragility_<im>.xml beside its report
    write_fragility_nrml(tmp_path / "fragility_pga.xml", [("masonry-arch", 0.8, 0.3)],
                         im="pga", min_iml=0.1, max_iml=2.0)
    write_fragility_nrml(tmp_path / "fragility_sa_0.5.xml", [("masonry-arch", 1.1, 0.4)],
                         im="sa(0.5)", min_iml=0.1, max_iml=3.0)
    read = read_fragility(tmp_path, im="SA(0.5)")
    assert read.fragility.im == "SA(0.5)"
    assert read.fragility.median == pytest.approx(1.1, rel=1e-12)
    assert read_fragility(tmp_path, im="PGA").fragility.median == pytest.approx(0.8, rel=1e-12)
    with pytest.raises(ValueError, match="hold lognormal fits only"):
        read_fragility(tmp_path, fit="empirical")


def test_pulse_fragility_study_is_refused_with_the_reason(tmp_path):
    save_study(tmp_path, pd.DataFrame({"arch": [0]}), summary={"durations": []})
    with pytest.raises(ValueError, match="pulse fragility study: its intensity is the amplitude "
                                         "of a pulse"):
        read_fragility(tmp_path)
