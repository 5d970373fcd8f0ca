"""``archquake spectrum``: the numbers of the codes by hand, and every bad input as one line
``archquake: error: ...`` naming its option, exit status 2."""

import json
import math

import pytest

from archquake.cli import main
from site_reference import GRID_TABLE

NTC_C = ["spectrum", "--code", "ntc2018", "--ag", "0.25", "--f0", "2.4", "--tc-star", "0.3",
         "--soil", "C"]

SITE = GRID_TABLE


def _json(argv, capsys):
    assert main([*argv, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_ntc_text_shows_the_corners_and_the_table(capsys):
    assert main([*NTC_C, "--periods", "0.3,1"]) == 0
    out = capsys.readouterr().out
    # S_S = 1.70 - 0.6 * 2.4 * 0.25 = 1.34; T_D = 4 * 0.25 + 1.6 = 2.6 s; plateau 0.804 g;
    # at 1 s: 0.804 * T_C = 0.804 * 0.468663 = 0.37680 g
    for text in ("S = 1.34", "T_D = 2.6 s", "T_E = 6 s", "T_F = 10 s", "0.80400", "0.37680"):
        assert text in out


def test_ntc_json(capsys):
    data = _json([*NTC_C, "--periods", "0:0.4:0.2,1"], capsys)
    assert data["spectrum"]["code"] == "NTC 2018"
    assert data["spectrum"]["t_c"] == pytest.approx(1.05 * 0.3 ** -0.33 * 0.3)
    periods = [row["period_s"] for row in data["rows"]]
    assert periods == [0.0, 0.2, 0.4, 1.0]
    assert data["rows"][0]["se_g"] == pytest.approx(0.335)     # ag S = 0.25 * 1.34
    assert data["rows"][2]["se_g"] == pytest.approx(0.804)     # ag S F0 = 0.335 * 2.4
    # SDe = Se g (T / 2 pi)^2 = 0.804 * 9.81 * 0.04 / (4 pi^2) = 0.0079914 m
    assert data["rows"][2]["sde_m"] == pytest.approx(0.804 * 9.81 * 0.16 / (4 * math.pi ** 2))


def test_default_periods_are_0_to_4_s(capsys):
    rows = _json(NTC_C, capsys)["rows"]
    assert rows[0]["period_s"] == 0.0 and rows[-1]["period_s"] == 4.0 and len(rows) == 41


def test_ec8(capsys):
    data = _json(["spectrum", "--code", "ec8", "--agr", "0.2", "--type", "1", "--soil", "B",
                  "--periods", "0.3,3"], capsys)
    # plateau 2.5 a_g S = 2.5 * 0.2 * 1.2 = 0.6 g; at 3 s 0.6 * 0.5 * 2 / 9 = 0.066667 g
    assert [r["se_g"] for r in data["rows"]] == pytest.approx([0.6, 0.6 / 9])
    assert data["spectrum"]["t_d"] == 2.0


def test_user_file_takes_its_own_periods(tmp_path, capsys):
    path = tmp_path / "sp.csv"
    path.write_text("T,Sa\n0,0.3\n0.5,0.7\n1,0.35\n")
    data = _json(["spectrum", "--code", "user", "--file", str(path)], capsys)
    assert data["spectrum"]["code"] == "user file sp.csv"
    assert [r["se_g"] for r in data["rows"]] == [0.3, 0.7, 0.35]
    data = _json(["spectrum", "--code", "user", "--file", str(path), "--periods", "0.25"],
                 capsys)
    assert data["rows"][0]["se_g"] == pytest.approx(0.5)      # (0.3 + 0.7) / 2


def test_site_at_slv(tmp_path, capsys):
    path = tmp_path / "site.csv"
    path.write_text(SITE)
    data = _json(["spectrum", "--site", str(path), "--limit-state", "SLC", "--soil", "B",
                  "--periods", "0"], capsys)
    # SLC, V_R = 50: T_R = -50 / ln(0.95) = 974.79 years, just below the 975 node (0.270 g)
    assert data["site"]["return_period"] == pytest.approx(974.79, abs=0.01)
    assert data["site"]["ag"] == pytest.approx(0.270, abs=1e-4)
    # soil B: S_S = 1.40 - 0.40 F0 ag = 1.40 - 0.4 * 2.41 * 0.27 = 1.1397 -> PGA = ag S
    ag, f0 = data["site"]["ag"], data["site"]["f0"]
    assert data["rows"][0]["se_g"] == pytest.approx(ag * (1.40 - 0.40 * f0 * ag))


@pytest.mark.parametrize("argv, words", [
    (["--code", "ntc2018", "--ag", "2.45", "--f0", "2.4", "--tc-star", "0.3"],
     ["--ag", "not m/s^2"]),
    ([*NTC_C[1:], "--f0", "1.2"], ["--f0", "[2, 3.5]"]),
    ([*NTC_C[1:], "--soil", "F"], ["--soil", "A, B, C, D, E"]),
    ([*NTC_C[1:], "--topography", "T9"], ["--topography", "T1, T2, T3, T4"]),
    ([*NTC_C[1:], "--damping", "0"], ["--damping"]),
    ([*NTC_C[1:], "--periods", "-1"], ["--periods", ">= 0"]),
    ([*NTC_C[1:], "--periods", "0:1"], ["--periods", "start:stop:step"]),
    ([*NTC_C[1:], "--agr", "0.2"], ["--agr", "does not apply"]),
    (["--code", "ntc2018", "--ag", "0.2"], ["--f0", "--tc-star", "must be given"]),
    (["--code", "ec8", "--agr", "0.2", "--type", "3"], ["--type", "1 or 2"]),
    (["--code", "ec8", "--agr", "1.0", "--importance", "2"], ["--importance", "--agr"]),
    (["--code", "eurocode"], ["--code", "ntc2018, ec8 or user"]),
    (["--ag", "0.2"], ["--code"]),
    (["--code", "user", "--file", "/nonexistent/sp.csv"], ["sp.csv"]),
])
def test_bad_input_names_the_option(argv, words, capsys):
    assert main(["spectrum", *argv]) == 2
    err = capsys.readouterr().err
    assert err.startswith("archquake: error: ") and err.count("\n") == 1
    for word in words:
        assert word in err


def test_bad_site_inputs(tmp_path, capsys):
    path = tmp_path / "site.csv"
    path.write_text(SITE)
    # SLO, V_N 10, class I: V_R = 35 years, T_R = -35 / ln(0.19) = 21.1 years < 30
    argv = ["spectrum", "--site", str(path), "--limit-state", "SLO", "--nominal-life", "10",
            "--use-class", "I"]
    assert main(argv) == 2
    assert "T_R = 21.1 years" in capsys.readouterr().err
    assert main(["spectrum", "--site", str(path), "--limit-state", "ULS"]) == 2
    assert "--limit-state must be one of SLO, SLD, SLV, SLC" in capsys.readouterr().err
    assert main(["spectrum", "--site", str(path)]) == 2
    assert "--limit-state must be given" in capsys.readouterr().err
    user = tmp_path / "sp.csv"
    user.write_text("0,0.3\n1,0.2\n")
    assert main(["spectrum", "--code", "user", "--file", str(user), "--periods", "2"]) == 2
    assert "outside the spectrum of user file sp.csv" in capsys.readouterr().err
    path.write_text("TR,ag,F0\n30,0.06,2.4\n")
    assert main(["spectrum", "--site", str(path), "--limit-state", "SLV"]) == 2
    assert "--site: site file site.csv" in capsys.readouterr().err


def test_help_names_the_clauses(capsys):
    with pytest.raises(SystemExit):
        main(["spectrum", "--help"])
    out = " ".join(capsys.readouterr().out.split())
    for text in ("NTC 2018 §3.2.3.2", "3.2.2-3.2.7", "EN 1998-1:2004 §3.2.2.2", "Annex A"):
        assert text in out
