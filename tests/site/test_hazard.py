"""Hazard curves: OpenQuake's exports and plain CSV read into annual frequencies of exceedance,
checked by hand at stated levels; the interpolation between, below and beyond the levels; the
refusals (not monotone, negative intensity, a measure not in g)."""

import math
from pathlib import Path

import numpy as np
import pytest

from archquake.site.hazard import (
    HazardCurve,
    annual_frequency,
    canonical_im,
    read_hazard_csv,
    read_hazard_curve,
    read_openquake_hazard_curve,
)

DATA = Path(__file__).parents[1] / "data" / "site"
QA_CURVE = DATA / "openquake_classical_damage_case_1_hcurves_PGA.csv"
MANUAL_CURVE = DATA / "openquake_manual_hazard_curve-mean-PGA.csv"


def test_openquake_poe_becomes_annual_frequency_by_hand():
    curve = read_openquake_hazard_curve(QA_CURVE)
    assert curve.im == "PGA"
    assert curve.levels.size == 28 and curve.levels[0] == 0.05 and curve.levels[-1] == 1.4
    # poe-0.05 = 0.5917765 in 50 years: lambda = -ln(1 - 0.5917765) / 50 = -ln(0.4082235) / 50
    #          = 0.895938 / 50 = 0.0179188 1/yr
    assert curve.frequencies[0] == pytest.approx(0.0179188, rel=1e-5)
    # poe-1.4 = 3.033695e-05: for small poe, lambda ~ poe / 50 (1 + poe / 2) = 6.06748e-07
    assert curve.frequencies[-1] == pytest.approx(3.033695e-05 / 50 * (1 + 3.033695e-05 / 2),
                                                  rel=1e-9)
    assert "Poisson" in curve.source and "50" in curve.source


def test_annual_frequency_of_10_percent_in_50_years_is_1_in_475():
    # the classical 475-year return period: -ln(0.9) / 50 = 0.105361 / 50 = 1 / 474.56
    assert 1 / float(annual_frequency(0.10, 50.0)) == pytest.approx(474.56, abs=0.01)


def test_openquake_file_of_several_sites_needs_a_site_index():
    with pytest.raises(ValueError, match=r"holds 4 sites: choose one with site_index "
                                         r"\(--site-index\) in \[0, 4\)"):
        read_openquake_hazard_curve(MANUAL_CURVE)
    curve = read_openquake_hazard_curve(MANUAL_CURVE, site_index=0)
    # the engine 3.18 comment line: investigation_time=1.0, imt='PGA'
    # poe 0.455386 in 1 year: -ln(0.544614) = 0.607678 1/yr
    assert curve.frequencies[0] == pytest.approx(0.607678, rel=1e-5)
    with pytest.raises(ValueError, match=r"site_index must be in \[0, 4\)"):
        read_openquake_hazard_curve(MANUAL_CURVE, site_index=4)
    # site 1 exceeds only its first level: no curve
    with pytest.raises(ValueError, match="fewer than 2 levels"):
        read_openquake_hazard_curve(MANUAL_CURVE, site_index=1)


def test_trailing_zero_probabilities_are_dropped_and_said(tmp_path):
    path = tmp_path / "hazard_curve-mean-SA(0.5)_7.csv"
    path.write_text(
        "#,,,,,\"generated_by='OpenQuake engine 3.18.0', start_date='2023-10-03T06:09:08', "
        "checksum=1, kind='mean', investigation_time=50.0, imt='SA(0.5)'\"\n"
        "lon,lat,depth,poe-0.1,poe-0.2,poe-0.4,poe-0.8\n"
        "12.5,41.9,0.0,0.5,0.1,0.01,0.0\n")
    curve = read_hazard_curve(path)  # recognised from the content
    assert curve.im == "SA(0.5)" and curve.levels.tolist() == [0.1, 0.2, 0.4]
    assert "1 last level(s) with probability 0" in curve.notes[0]
    # poe 0.01 in 50 yr: -ln(0.99) / 50 = 0.01005034 / 50
    assert curve.frequencies[-1] == pytest.approx(0.01005034 / 50, rel=1e-6)


def test_plain_csv_with_comments_and_a_header_naming_the_measure(tmp_path):
    path = tmp_path / "site.csv"
    path.write_text("# my site\nSA(1),lambda [1/yr]\n0.1,0.01\n# mid comment\n0.2,0.004\n"
                    "0.4, 0.001\n")
    curve = read_hazard_curve(path)
    assert curve.im == "SA(1.0)"
    assert curve.frequencies.tolist() == [0.01, 0.004, 0.001]
    with pytest.raises(ValueError, match="its header names SA\\(1.0\\), but PGA was asked"):
        read_hazard_csv(path, im="PGA")


def test_plain_csv_without_a_measure_needs_one(tmp_path):
    path = tmp_path / "site.csv"
    path.write_text("0.1,0.01\n0.2,0.004\n")
    with pytest.raises(ValueError, match="name the intensity measure"):
        read_hazard_curve(path, format="csv")
    assert read_hazard_curve(path, im="pga").im == "PGA"


def test_a_curve_that_is_not_monotone_is_refused_naming_the_row(tmp_path):
    path = tmp_path / "site.csv"
    path.write_text("PGA,freq\n0.1,0.01\n0.2,0.004\n0.3,0.005\n0.4,0.001\n")
    with pytest.raises(ValueError, match=r"row 2: the annual frequency of exceedance must not "
                                         r"increase .*not monotone"):
        read_hazard_curve(path)
    with pytest.raises(ValueError, match=r"row 1: the levels must increase strictly"):
        HazardCurve([0.2, 0.1, 0.3], [3.0, 2.0, 1.0])


def test_a_negative_intensity_is_refused():
    with pytest.raises(ValueError, match=r"row 0: the level must be a finite number > 0 \[g\]"):
        HazardCurve([-0.1, 0.2], [0.01, 0.001])
    with pytest.raises(ValueError, match="row 1: the frequency must be"):
        HazardCurve([0.1, 0.2], [0.01, 0.0])


def test_a_row_that_is_not_two_numbers_is_refused_naming_the_line(tmp_path):
    path = tmp_path / "site.csv"
    path.write_text("PGA,freq\n0.1,0.01\n0.2,abc\n")
    with pytest.raises(ValueError, match="line 3: expected two numbers"):
        read_hazard_curve(path)


def test_measures_not_in_g_are_refused():
    assert canonical_im(" sa( 0.5 ) ") == "SA(0.5)"
    for name in ("pgv", "arias", "d5-95"):
        with pytest.raises(ValueError, match="in g, in PGA or SA"):
            canonical_im(name)


def test_interpolation_log_log_held_below_power_law_beyond():
    curve = HazardCurve([0.1, 0.4, 1.6], [1e-2, 1e-3, 1e-5])
    # between levels: the geometric mean of the levels has the geometric mean frequency
    assert curve.frequency(0.2) == pytest.approx(math.sqrt(1e-2 * 1e-3), rel=1e-12)
    # below the first level: held
    assert curve.frequency([0.0, 0.05]) == pytest.approx([1e-2, 1e-2], rel=1e-14)
    # beyond: slope of the last interval, k = ln(100) / ln(4) = 3.3219; at 3.2 g one more
    # factor 2 in IM: 1e-5 * 2**-3.3219 = 1e-5 / 10
    assert curve.tail_slope == pytest.approx(math.log(100) / math.log(4))
    assert curve.frequency(3.2) == pytest.approx(1e-6, rel=1e-12)
    assert np.all(np.diff(curve.frequency(np.geomspace(0.01, 10, 50))) <= 0)


# --- NTC 2018 national grid -------------------------------------------------------------------

NTC_SITE = """# a site of the national grid (the format of archquake.site.spectra.read_ntc_site)
TR, ag, F0, Tc*
30, 0.060, 2.48, 0.27
50, 0.078, 2.47, 0.28
72, 0.094, 2.46, 0.29
101, 0.110, 2.44, 0.30
140, 0.127, 2.43, 0.31
201, 0.148, 2.42, 0.32
475, 0.212, 2.40, 0.34
975, 0.270, 2.41, 0.35
2475, 0.360, 2.44, 0.37
"""


@pytest.fixture
def ntc_site(tmp_path):
    path = tmp_path / "ntc_site.csv"
    path.write_text(NTC_SITE)
    return path


def test_ntc_site_on_rock_is_one_over_tr_at_ag(ntc_site):
    curve = read_hazard_curve(ntc_site)  # recognised from its header
    assert curve.im == "PGA"
    assert curve.levels.tolist() == pytest.approx([0.060, 0.078, 0.094, 0.110, 0.127, 0.148,
                                                   0.212, 0.270, 0.360])
    assert curve.frequencies[6] == pytest.approx(1 / 475)
    assert "on rock" in curve.source
    # tail: slope ln(2475/975) / ln(0.360/0.270) = 0.93156 / 0.28768 = 3.2382
    assert curve.tail_slope == pytest.approx(3.2382, rel=1e-4)


def test_ntc_site_on_soil_c_is_ag_times_s(ntc_site):
    curve = read_hazard_curve(ntc_site, soil="C")
    # NTC 2018 Table 3.2.IV, soil C: S_S = 1.70 - 0.60 F0 ag in [1, 1.5]; at 475 years
    # 1.70 - 0.60 * 2.40 * 0.212 = 1.70 - 0.30528 = 1.39472, PGA = 0.212 * 1.39472 = 0.29568064 g
    assert curve.levels[6] == pytest.approx(0.29568064, rel=1e-9)
    # at 30 years the bound 1.5: 1.70 - 0.60 * 2.48 * 0.06 = 1.6107 -> 1.5, PGA = 0.09 g
    assert curve.levels[0] == pytest.approx(0.09, rel=1e-12)
    assert "soil C" in curve.source


def test_ntc_site_spectral_ordinate(ntc_site):
    curve = read_hazard_curve(ntc_site, im="SA(0.2)")
    # on rock at 475 years: T_C = Tc* = 0.34 s, T_B = 0.1133 s: 0.2 s is on the plateau,
    # Se = ag F0 = 0.212 * 2.40 = 0.5088 g
    assert curve.levels[6] == pytest.approx(0.5088, rel=1e-9)
    with pytest.raises(ValueError, match="soil and topography"):
        read_hazard_curve(ntc_site, format="csv", soil="C")
