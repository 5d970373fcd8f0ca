"""Limit analysis and the four-link mechanism together: independent checks of each other."""

import json

import numpy as np
import pytest

from archquake.cli import main
from archquake.fourlink.impact import restitution
from archquake.fourlink.mechanism import mechanisms
from archquake.geometry import irregular_arch
from archquake.limit_analysis import both_directions


@pytest.mark.parametrize("seed", range(12))
def test_activation_equals_limit_analysis_multiplier_on_irregular_arches(nominal, seed):
    arch = irregular_arch(nominal, 0.1, rng=seed)
    la = both_directions(arch)
    mech = mechanisms(arch, limit=la)
    for m, r in zip(mech, la, strict=True):
        # virtual work of the dynamic model at theta_u == static LP multiplier
        assert m.activation_g == pytest.approx(r.load_multiplier, abs=1e-9)
        assert m.theta_cr < m.theta_u


def test_irregular_arch_differs_in_the_two_directions(nominal):
    arch = irregular_arch(nominal, 0.1, rng=4)
    mech_l, mech_r = mechanisms(arch)
    assert abs(mech_l.theta_u - mech_r.theta_u) > 1e-3
    c_lr, c_rl = restitution("computed", mech_l, mech_r)
    assert c_lr > 0 and c_rl > 0 and c_lr != pytest.approx(c_rl, abs=1e-6)


@pytest.mark.parametrize("seed", range(8))
def test_computed_restitution_never_creates_energy(nominal, seed):
    # c_v is a ratio of rates of two different coordinates, so it may exceed 1 when the two
    # mechanisms differ; the kinetic energy may not grow, and over a full cycle (l -> r -> l)
    # the rate ratio c_lr c_rl = <u_l, u_r>^2 / (|u_l|^2 |u_r|^2) <= 1 (Cauchy-Schwarz).
    from archquake.fourlink.impact import kinetic_energy_ratio

    mech_l, mech_r = mechanisms(irregular_arch(nominal, 0.1, rng=seed))
    c_lr, c_rl = restitution("computed", mech_l, mech_r)
    assert kinetic_energy_ratio(mech_l, mech_r, c_lr) <= 1 + 1e-12
    assert kinetic_energy_ratio(mech_r, mech_l, c_rl) <= 1 + 1e-12
    assert c_lr * c_rl <= 1 + 1e-12


def test_mechanism_cli_reproduces_tables_2_and_3(capsys, paper):
    assert main(["mechanism", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    t2, t3 = paper["table2"]["NA"], paper["table3"]["NA"]
    for d in "lr":
        m = out[d]
        for key in ("theta_u", "theta_bc_u", "theta_cd_u"):
            assert m[key] == pytest.approx(t2[key], abs=1e-4)
        for key in ("ab", "bc", "cd"):
            assert m[key] == pytest.approx(t2[key], abs=0.01)
        assert m["theta_cr"] == pytest.approx(t3["theta_cr"], abs=1e-4)
        assert m["theta_cr"] / m["theta_u"] == pytest.approx(t3["ratio"], abs=1e-3)
        assert m["activation"] == pytest.approx(paper["table1"]["NA"]["load_multiplier"],
                                                abs=1e-3)
    assert out["restitution"]["l_to_r"] == pytest.approx(out["restitution"]["r_to_l"])
    assert 0.6 < out["restitution"]["l_to_r"] < 0.7


def test_mechanism_cli_restitution_choices(capsys):
    assert main(["mechanism", "--json", "--restitution", "0.875"]) == 0
    assert json.loads(capsys.readouterr().out)["restitution"]["l_to_r"] == 0.875
    assert main(["mechanism", "--json", "--epsilon", "0.1", "--seed", "3",
                 "--restitution", "nominal"]) == 0
    nominal_value = json.loads(capsys.readouterr().out)["restitution"]
    assert main(["mechanism", "--json", "--restitution", "computed"]) == 0
    assert nominal_value == json.loads(capsys.readouterr().out)["restitution"]
    assert main(["mechanism", "--restitution", "bouncy"]) == 2
    assert "--restitution must be one of" in capsys.readouterr().err
    assert main(["mechanism", "--restitution", "1.5"]) == 2
    assert "(0, 1]" in capsys.readouterr().err


def test_mechanism_cli_text_output(capsys):
    assert main(["mechanism"]) == 0
    text = capsys.readouterr().out
    assert "theta_u" in text and "0.8972" in text and "restitution" in text
    assert np.isfinite(float(text.split("theta_u")[1].split()[0]))
