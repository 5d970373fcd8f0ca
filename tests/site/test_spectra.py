"""Elastic spectra of NTC 2018 and EN 1998-1, user spectra and the NTC national-grid hazard,
checked against hand calculations of the codes' formulas (arithmetic written in each test)."""

import json
import math

import numpy as np
import pytest

from archquake.checks import json_dumps
from archquake.site import (
    ElasticSpectrum,
    NtcSiteHazard,
    ec8_spectrum,
    ntc2018_spectrum,
    read_ntc_site,
    read_spectrum,
    return_period,
    user_spectrum,
)
from archquake.site.spectra import damping_correction

G = 9.81
EPS = 1e-9


# --- NTC 2018 ---------------------------------------------------------------------------------

@pytest.fixture
def soil_c():
    """NTC 2018, soil C, ag = 0.25 g, F0 = 2.4, Tc* = 0.3 s, T1, 5 %."""
    return ntc2018_spectrum(0.25, 2.4, 0.3, soil="C")


def test_ntc_soil_c_corner_values_by_hand(soil_c):
    s_s = 1.70 - 0.60 * 2.4 * 0.25          # = 1.34, inside [1.00, 1.50]
    assert s_s == pytest.approx(1.34)
    c_c = 1.05 * 0.3 ** -0.33                # = 1.05 * 1.48782 = 1.56221
    assert c_c == pytest.approx(1.56221, abs=1e-5)
    t_c = c_c * 0.3                          # = 0.468663 s
    assert soil_c.s == pytest.approx(1.34)
    assert soil_c.t_c == pytest.approx(0.468663, abs=1e-6)
    assert soil_c.t_b == pytest.approx(0.468663 / 3, abs=1e-6)
    assert soil_c.t_d == pytest.approx(4 * 0.25 + 1.6)   # 2.6 s
    assert (soil_c.t_e, soil_c.t_f) == (6.0, 10.0)          # Table 3.2.VIII, soil C
    assert soil_c.eta == 1.0                                # sqrt(10 / (5 + 5))
    assert soil_c.pga == pytest.approx(0.25 * 1.34)         # 0.335 g
    plateau = 0.25 * 1.34 * 1.0 * 2.4                       # ag S eta F0 = 0.804 g
    assert soil_c.acceleration(0.3) == pytest.approx(0.804)
    assert soil_c.acceleration(t_c) == pytest.approx(plateau)
    # velocity branch at T = 1 s: 0.804 * 0.468663 / 1 = 0.376805 g
    assert soil_c.acceleration(1.0) == pytest.approx(0.376805, abs=1e-6)
    # displacement branch at T = 4 s: 0.804 * 0.468663 * 2.6 / 16 = 0.0612308 g
    assert soil_c.acceleration(4.0) == pytest.approx(0.0612308, abs=1e-7)
    assert soil_c.code == "NTC 2018"


def test_ntc_first_branch_in_the_code_form(soil_c):
    # NTC eq. 3.2.2: ag S eta F0 [T/TB + (1 - T/TB) / (eta F0)]; at T = TB / 2:
    # 0.804 * [0.5 + 0.5 / 2.4] = 0.804 * 0.708333 = 0.5695 g
    assert soil_c.acceleration(soil_c.t_b / 2) == pytest.approx(0.5695, abs=1e-9)


def test_ntc_continuity_at_the_corners(soil_c):
    for corner in (soil_c.t_b, soil_c.t_c, soil_c.t_d):
        below, above = soil_c.acceleration([corner - EPS, corner + EPS])
        assert below == pytest.approx(above, rel=1e-7)
    # the displacement is continuous at T_F and steps at T_E by 0.025 (2 pi)^2 = 0.98696
    below, above = soil_c.displacement([6.0 - EPS, 6.0 + EPS])
    assert above / below == pytest.approx(0.025 * (2 * math.pi) ** 2, rel=1e-7)
    below, above = soil_c.displacement([10.0 - EPS, 10.0 + EPS])
    assert below == pytest.approx(above, rel=1e-7)


def test_ntc_displacement_by_hand(soil_c):
    # pseudo-spectral up to T_E: at T = 1 s, 0.376805 g * 9.81 * (1 / 2 pi)^2 = 0.093633 m
    assert soil_c.displacement(1.0) == pytest.approx(0.376805 * 9.81 / (4 * math.pi ** 2),
                                                     rel=1e-6)
    # d_g = 0.025 ag g S T_C T_D = 0.025 * 0.25 * 9.81 * 1.34 * 0.468663 * 2.6 = 0.100118 m
    d_g = 0.025 * 0.25 * 9.81 * 1.34 * 0.468663 * 2.6
    assert soil_c.displacement(12.0) == pytest.approx(d_g, rel=1e-6)
    assert soil_c.ground_displacement == pytest.approx(d_g, rel=1e-6)
    # halfway between T_E = 6 and T_F = 10 s: d_g [2.4 + (1 - 2.4) / 2] = 1.7 d_g
    assert soil_c.displacement(8.0) == pytest.approx(1.7 * d_g, rel=1e-6)
    assert soil_c.displacement(0.0) == 0.0


@pytest.mark.parametrize("soil, ag, f0, s_s", [
    ("A", 0.3, 2.5, 1.00),
    ("B", 0.10, 2.5, 1.20),    # 1.40 - 0.40 * 2.5 * 0.10 = 1.30 -> 1.20 (upper bound)
    ("B", 0.50, 3.0, 1.00),    # 1.40 - 0.40 * 3.0 * 0.50 = 0.80 -> 1.00 (lower bound)
    ("B", 0.40, 2.5, 1.00),    # 1.40 - 0.40 * 2.5 * 0.40 = 1.00
    ("C", 0.10, 2.5, 1.50),    # 1.70 - 0.15 = 1.55 -> 1.50
    ("D", 0.10, 2.4, 1.80),    # 2.40 - 1.50 * 0.24 = 2.04 -> 1.80
    ("D", 0.30, 2.4, 1.32),    # 2.40 - 1.50 * 0.72 = 1.32
    ("D", 0.50, 2.4, 0.90),    # 2.40 - 1.80 = 0.60 -> 0.90
    ("E", 0.20, 2.5, 1.45),    # 2.00 - 1.10 * 0.50 = 1.45
    ("E", 0.05, 2.5, 1.60),    # 2.00 - 0.1375 = 1.8625 -> 1.60
])
def test_ntc_stratigraphic_amplification(soil, ag, f0, s_s):
    assert ntc2018_spectrum(ag, f0, 0.3, soil).s == pytest.approx(s_s)


@pytest.mark.parametrize("soil, c_c", [
    ("A", 1.0), ("B", 1.10 * 0.4 ** -0.20), ("D", 1.25 * 0.4 ** -0.50),
    ("E", 1.15 * 0.4 ** -0.40)])
def test_ntc_c_c(soil, c_c):
    # e.g. D: 1.25 / sqrt(0.4) = 1.97642
    assert ntc2018_spectrum(0.2, 2.5, 0.4, soil).t_c == pytest.approx(c_c * 0.4)
    assert ntc2018_spectrum(0.2, 2.5, 0.4, soil).t_b == pytest.approx(c_c * 0.4 / 3)


def test_ntc_topography():
    assert ntc2018_spectrum(0.2, 2.5, 0.3, "A", "T4").s == pytest.approx(1.4)
    assert ntc2018_spectrum(0.2, 2.5, 0.3, "A", "T3").s == pytest.approx(1.2)
    # halfway up a T4 slope: 1 + (1.4 - 1) * 0.5 = 1.2; soil B, S_S = 1.40 - 0.4*2.5*0.2 = 1.2
    sp = ntc2018_spectrum(0.2, 2.5, 0.3, "B", "t4", topography_ratio=0.5)
    assert sp.s == pytest.approx(1.2 * 1.2)
    assert ntc2018_spectrum(0.2, 2.5, 0.3, "A", "T2", topography_ratio=0.0).s == 1.0


def test_damping_correction():
    assert damping_correction(10.0) == pytest.approx(math.sqrt(10 / 15))   # 0.8165
    assert damping_correction(2.0) == pytest.approx(math.sqrt(10 / 7))     # 1.1952
    assert damping_correction(30.0) == 0.55        # sqrt(10 / 35) = 0.5345 < 0.55
    sp = ntc2018_spectrum(0.25, 2.4, 0.3, "C", damping=10.0)
    assert sp.acceleration(0.3) == pytest.approx(0.804 * math.sqrt(10 / 15))
    assert sp.pga == pytest.approx(0.335)          # eta does not change Se(0)


def test_vectorised_and_scalar():
    sp = ntc2018_spectrum(0.25, 2.4, 0.3, "C")
    grid = np.linspace(0.0, 4.0, 41).reshape(41, 1)
    se = sp.acceleration(grid)
    assert se.shape == (41, 1) and isinstance(sp.acceleration(1.0), float)
    assert np.allclose(se[:, 0], [sp.acceleration(t) for t in grid[:, 0]])
    assert np.allclose(sp.displacement(grid[:, 0]),
                       se[:, 0] * 9.81 * (grid[:, 0] / (2 * np.pi)) ** 2)


@pytest.mark.parametrize("kwargs, words", [
    (dict(ag=2.45), ["ag", "g, not m/s^2"]),
    (dict(ag=0.0), ["ag"]),
    (dict(f0=1.5), ["f0", "[2, 3.5]"]),
    (dict(f0=float("nan")), ["f0"]),
    (dict(tc_star=1.2), ["tc_star", "(0, 1]"]),
    (dict(tc_star=-0.1), ["tc_star"]),
    (dict(soil="F"), ["soil", "A, B, C, D, E"]),
    (dict(topography="T5"), ["topography", "T1, T2, T3, T4"]),
    (dict(damping=0.0), ["damping", "(0, 30]"]),
    (dict(damping=40.0), ["damping"]),
    (dict(topography_ratio=1.5), ["topography_ratio", "[0, 1]"]),
    (dict(ag="0.2_5"), ["ag"]),
])
def test_ntc_refuses_bad_input_naming_the_parameter(kwargs, words):
    args = dict(ag=0.25, f0=2.4, tc_star=0.3) | kwargs
    with pytest.raises(ValueError) as info:
        ntc2018_spectrum(**args)
    for word in words:
        assert word in str(info.value)


@pytest.mark.parametrize("period", [-0.1, float("nan"), float("inf"), [0.1, -1.0]])
def test_bad_periods_are_refused(period):
    sp = ntc2018_spectrum(0.25, 2.4, 0.3)
    with pytest.raises(ValueError, match="period"):
        sp.acceleration(period)
    with pytest.raises(ValueError, match="period"):
        sp.displacement(period)


# --- EN 1998-1 --------------------------------------------------------------------------------

def test_ec8_type1_soil_b_by_hand():
    sp = ec8_spectrum(0.2, 1, "B", importance=1.2)
    ag = 1.2 * 0.2                                        # a_g = gamma_I a_gR = 0.24 g
    assert (sp.s, sp.t_b, sp.t_c, sp.t_d) == (1.2, 0.15, 0.5, 2.0)   # Table 3.2
    assert sp.ag == pytest.approx(0.24)
    assert sp.pga == pytest.approx(ag * 1.2)              # 0.288 g
    assert sp.acceleration(0.3) == pytest.approx(2.5 * ag * 1.2)        # 0.72 g
    assert sp.acceleration(0.075) == pytest.approx(0.288 * (1 + 0.5 * 1.5))   # 0.504 g
    assert sp.acceleration(1.0) == pytest.approx(0.72 * 0.5 / 1.0)     # 0.36 g
    assert sp.acceleration(3.0) == pytest.approx(0.72 * 0.5 * 2.0 / 9)  # 0.08 g
    assert sp.displacement(1.0) == pytest.approx(0.36 * 9.81 / (4 * math.pi ** 2))
    # Annex A: d_g = 0.025 a_g g S T_C T_D = 0.025 * 0.24 * 9.81 * 1.2 * 0.5 * 2 = 0.0706 m
    assert sp.displacement(11.0) == pytest.approx(0.025 * 0.24 * 9.81 * 1.2 * 0.5 * 2.0)
    assert (sp.t_e, sp.t_f) == (5.0, 10.0)                # Table A.1, ground type B
    assert sp.code == "EN 1998-1:2004"


def test_ec8_type2_soil_d():
    sp = ec8_spectrum(0.1, 2, "D", damping=10.0)
    assert (sp.s, sp.t_b, sp.t_c, sp.t_d) == (1.8, 0.10, 0.30, 1.2)   # Table 3.3
    # plateau 2.5 * 0.1 * 1.8 * sqrt(10 / 15) = 0.45 * 0.816497 = 0.367423 g
    assert sp.acceleration(0.2) == pytest.approx(0.367423, abs=1e-6)
    for corner in (sp.t_b, sp.t_c, sp.t_d):
        below, above = sp.acceleration([corner - EPS, corner + EPS])
        assert below == pytest.approx(above, rel=1e-7)


@pytest.mark.parametrize("kwargs, word", [
    (dict(agr=3.0), "agr"), (dict(spectrum_type=3), "spectrum_type"),
    (dict(soil="S1"), "soil"), (dict(importance=0.0), "importance"),
    (dict(damping=-1.0), "damping")])
def test_ec8_refuses_bad_input(kwargs, word):
    with pytest.raises(ValueError, match=word):
        ec8_spectrum(**(dict(agr=0.2) | kwargs))


# --- user spectra -----------------------------------------------------------------------------

def test_user_spectrum_interpolates_and_refuses_outside(tmp_path):
    path = tmp_path / "site.csv"
    path.write_text("# spectrum of the site\nperiod, Sa\n0.0, 0.30\n0.5, 0.70  # peak\n"
                    "1.0, 0.35\n")
    sp = read_spectrum(path)
    assert sp.code == "user file site.csv"
    assert sp.acceleration(0.25) == pytest.approx(0.5)        # (0.30 + 0.70) / 2
    assert sp.acceleration(0.75) == pytest.approx(0.525)      # (0.70 + 0.35) / 2
    assert sp.pga == pytest.approx(0.30)
    # SDe = Se g (T / 2 pi)^2 = 0.7 * 9.81 * (0.5 / 2 pi)^2 = 0.043486 m
    assert sp.displacement(0.5) == pytest.approx(0.7 * 9.81 * 0.25 / (4 * math.pi ** 2))
    with pytest.raises(ValueError, match="outside.*from 0 to 1 s"):
        sp.acceleration(1.5)
    assert sp.s is None and sp.t_c is None


def test_user_spectrum_whitespace_without_header(tmp_path):
    path = tmp_path / "s.txt"
    path.write_text("0.1   0.4\n0.2\t0.6\n")
    sp = read_spectrum(path)
    assert sp.acceleration(0.15) == pytest.approx(0.5)
    with pytest.raises(ValueError, match="PGA"):
        _ = sp.pga


@pytest.mark.parametrize("text, words", [
    ("0.0, 0.3\n", ["at least two rows"]),
    ("0.0, 0.3\n0.0, 0.4\n", ["strictly increasing"]),
    ("0.0, 0.3\n0.5, -0.1\n", ["accelerations", ">= 0"]),
    ("0.0, 0.3\n0.5\n", ["line 2", "2 columns"]),
    ("T,Sa\n0.0, 0.3\nx, 0.4\n", ["line 3"]),
])
def test_user_file_errors(tmp_path, text, words):
    path = tmp_path / "bad.csv"
    path.write_text(text)
    with pytest.raises(ValueError) as info:
        read_spectrum(path)
    for word in ["bad.csv", *words]:
        assert word in str(info.value)


# --- limit states and the national grid -------------------------------------------------------

@pytest.mark.parametrize("state, life, use, expected", [
    ("SLV", 50, "II", 474.56),      # -50 / ln(0.90) = 474.56 -> the 475 years of the codes
    ("SLC", 50, "II", 974.79),      # -50 / ln(0.95) = 974.79 -> 975
    ("SLO", 50, "II", 30.11),       # -50 / ln(0.19) = 50 / 1.66073
    ("SLD", 50, "II", 50.29),       # -50 / ln(0.37) = 50 / 0.99425
    ("SLV", 100, "IV", 1898.24),    # V_R = 100 * 2.0 = 200: -200 / ln(0.9)
    ("SLV", 10, "I", 332.19),       # V_R = 10 * 0.7 = 7 -> 35 years: -35 / ln(0.9)
])
def test_return_period(state, life, use, expected):
    assert return_period(state, life, use) == pytest.approx(expected, abs=0.01)


def test_return_period_refuses():
    with pytest.raises(ValueError, match="limit_state.*SLO, SLD, SLV, SLC"):
        return_period("ULS")
    with pytest.raises(ValueError, match="use_class"):
        return_period("SLV", use_class="V")
    with pytest.raises(ValueError, match="nominal_life"):
        return_period("SLV", nominal_life=0.0)


SITE = """# a site of the national grid
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
def site(tmp_path):
    path = tmp_path / "site.csv"
    path.write_text(SITE)
    return read_ntc_site(path)


def test_site_reproduces_its_nodes(site):
    assert site.return_periods == (30.0, 50.0, 72.0, 101.0, 140.0, 201.0, 475.0, 975.0, 2475.0)
    assert site.parameters(475) == pytest.approx((0.212, 2.40, 0.34))
    assert site.parameters(30) == pytest.approx((0.060, 2.48, 0.27))
    assert site.parameters(2475) == pytest.approx((0.360, 2.44, 0.37))


def test_site_interpolation_in_log_log(site):
    # at T_R = sqrt(201 * 475) = 308.99 years log(T_R) is halfway: each parameter is the
    # geometric mean of its neighbours, e.g. ag = sqrt(0.148 * 0.212) = 0.177132 g
    ag, f0, tc = site.parameters(math.sqrt(201 * 475))
    assert ag == pytest.approx(0.177132, abs=1e-6)
    assert f0 == pytest.approx(math.sqrt(2.42 * 2.40))
    assert tc == pytest.approx(math.sqrt(0.32 * 0.34))
    # at SLV (474.56 years), just below the 475 node: ag = 0.148 (0.212/0.148)^w with
    # w = ln(474.56/201) / ln(475/201) = 0.998924
    # -> 0.212 * 1.432432^-0.001076 = 0.211918 g
    assert site.parameters(return_period("SLV"))[0] == pytest.approx(0.211918, abs=1e-6)


def test_site_spectrum(site):
    sp = site.spectrum("SLC", soil="B", damping=5.0)
    ag, f0, tc = site.parameters(-50 / math.log(0.95))
    expected = ntc2018_spectrum(ag, f0, tc, "B")
    assert sp == expected
    assert isinstance(sp, ElasticSpectrum) and sp.code == "NTC 2018"


def test_site_refuses_outside_the_table(site):
    with pytest.raises(ValueError, match=r"return_period must be in \[30, 2475\]"):
        site.parameters(3000)
    with pytest.raises(ValueError, match="return_period"):
        site.spectrum("SLO", nominal_life=10, use_class="I")   # T_R = 35 / 1.66 = 21 years


def test_site_file_header_in_any_order_and_case(tmp_path):
    path = tmp_path / "s.csv"
    path.write_text("tc_star;AG;tr;f0\n0.27;0.06;30;2.48\n0.37;0.36;2475;2.44\n")
    site = read_ntc_site(path)
    assert site.ag == (0.06, 0.36) and site.return_periods == (30.0, 2475.0)
    path.write_text("30 0.06 2.48 0.27\n2475 0.36 2.44 0.37\n")      # no header: TR, ag, F0, Tc*
    assert read_ntc_site(path).tc_star == (0.27, 0.37)


@pytest.mark.parametrize("text, word", [
    ("TR,ag,F0\n30,0.06,2.48\n", "header"),
    ("TR,ag,F0,Tc*\n30,0.06,2.48,0.27\n", "at least two"),
    ("TR,ag,F0,Tc*\n30,0.06,2.48,0.27\n20,0.07,2.48,0.27\n", "strictly increasing"),
    ("TR,ag,F0,Tc*\n30,0.6,2.48,0.27\n50,2.5,2.48,0.27\n", "ag"),
    ("TR,ag,F0,Tc*\n30,0.06,1.0,0.27\n50,0.07,2.48,0.27\n", "f0"),
])
def test_site_file_errors(tmp_path, text, word):
    path = tmp_path / "s.csv"
    path.write_text(text)
    with pytest.raises(ValueError, match=word):
        read_ntc_site(path)


def test_to_dict_is_json(soil_c, site):
    data = json.loads(json_dumps(soil_c.to_dict()))
    assert data["code"] == "NTC 2018" and data["pga"] == pytest.approx(0.335)
    assert data["t_d"] == pytest.approx(2.6) and data["soil"] == "C"
    assert json.loads(json_dumps(site.to_dict()))["ag"][6] == 0.212
    table = user_spectrum([0.1, 0.2], [0.3, 0.4], name="x").to_dict()
    assert table["pga"] is None and table["periods"] == [0.1, 0.2]
    assert isinstance(NtcSiteHazard((30, 50), (0.1, 0.2), (2.5, 2.5), (0.3, 0.3)),
                      NtcSiteHazard)


def test_headers_with_units(tmp_path):
    path = tmp_path / "sp.csv"
    path.write_text("T [s], Sa [g]\n0.0, 0.2\n1.0, 0.4\n")
    assert read_spectrum(path).acceleration(0.5) == pytest.approx(0.3)   # (0.2 + 0.4) / 2
    path.write_text("period [s]   Se [g]\n0.0   0.2\n1.0   0.4\n")
    assert read_spectrum(path).acceleration(0.25) == pytest.approx(0.25)  # 0.2 + 0.2 / 4
    site = tmp_path / "site.csv"
    site.write_text("TR [years], ag [g], F0, Tc* [s]\n30, 0.06, 2.48, 0.27\n"
                    "50, 0.078, 2.47, 0.28\n")
    assert read_ntc_site(site).f0 == (2.48, 2.47)


def test_a_row_with_an_empty_field_is_not_a_header(tmp_path):
    path = tmp_path / "sp.csv"
    path.write_text("0.1,,0.3\n0.2,0.4\n0.3,0.5\n")
    with pytest.raises(ValueError, match="line 1"):
        read_spectrum(path)


def test_a_spectrum_made_by_hand_is_checked():
    with pytest.raises(ValueError, match="ntc2018_spectrum, ec8_spectrum or user_spectrum"):
        ElasticSpectrum("my code", ag=0.2)
    with pytest.raises(ValueError, match="ordered"):
        ElasticSpectrum("my code", ag=0.2, f0=2.5, s=1.0, eta=1.0, t_b=0.5, t_c=0.4, t_d=2.0,
                        t_e=4.5, t_f=10.0)
    with pytest.raises(ValueError, match="strictly increasing"):
        ElasticSpectrum("mine", periods=(0.0, 0.0), accelerations=(0.1, 0.2))
    with pytest.raises(ValueError, match="period"):
        ntc2018_spectrum(0.2, 2.5, 0.3).acceleration(None)
