"""``archquake min-thickness --rings N``: the thinnest arch of several rings, all scaled
together, against the chain program's minimum thickness of the one-ring arch."""

import json
import math

import pytest

from archquake.cli import main
from archquake.limit_analysis import min_thickness

SEMICIRCLE = ["--radius", "1", "--embrace", "180"]


def _json(argv, capsys):
    assert main(["min-thickness", *argv, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_rings_that_cannot_slide_act_as_one_arch(capsys):
    # Two aligned rings whose interface does not slide: the one-ring arch's thrust line crosses
    # the ring interfaces in compression, so the rings stand exactly when the whole arch does:
    # Milankovitch's semicircle, t/R = 0.1075 (40 voussoirs: the chain program's 0.10746), to
    # the chords' error (sagittae of 1e-4 R: areas short by about 1e-4 of the voussoir's)
    chain = min_thickness(1.0, math.pi, 40)
    assert chain == pytest.approx(0.1075, abs=1e-4)
    out = _json([*SEMICIRCLE, "--voussoirs", "40", "--rings", "2"], capsys)
    assert out["min_thickness"] == pytest.approx(chain, abs=2e-4)
    assert out["ratio_of"] == "radius" and out["rings"] == 2


@pytest.mark.parametrize("mu", [0.5, 0.3])
def test_weak_ring_interfaces_never_thin_the_arch(mu, capsys):
    # every state of the arch of rings is one of the monolithic arch (its ring interfaces are
    # joints inside the voussoirs), so it stands only where the monolithic one does: its
    # minimum thickness is never below the one ring's (20 voussoirs: the chain program's)
    chain = min_thickness(1.0, math.pi, 20)
    out = _json([*SEMICIRCLE, "--voussoirs", "20", "--rings", "2", "--ring-friction",
                 str(mu)], capsys)
    if out["min_thickness"] is not None:  # else: no thickness (a verdict), above any
        assert out["min_thickness"] >= chain * (1 - 2e-3)
        assert out["min_thickness"] > 1.1 * chain  # rings that slide do need more


def test_refusals_name_the_options(capsys):
    assert main(["min-thickness", "--ring-friction", "0.5"]) == 2
    assert "--ring-bond and --ring-friction need --rings N" in capsys.readouterr().err
    assert main(["min-thickness", "--rings", "2", "--shape", "pointed", "--span", "4",
                 "--rise", "3"]) == 2
    assert "a pointed arch's crown is a corner" in capsys.readouterr().err
