"""Limit analysis with fill: every inertia model and the passive reaction by the static linear
program and by the kinematic enumeration (the same loads), the thrust line in equilibrium with
them, and fill on an arch between piers."""

import math

import numpy as np
import pytest

from archquake.geometry import Fill, Structure, arch_on_piers, shaped_arch
from archquake.limit_analysis import AGREEMENT_TOLERANCE, both_directions, load_multipliers

PASSIVE = {"no passive": (None, None), "passive": (math.radians(30), 0.33)}


def hinges(result):
    return [(h.joint, h.face) for h in result.hinges]


@pytest.mark.parametrize("passive", list(PASSIVE))
@pytest.mark.parametrize("inertia", ["none", "centroid", "extrados"])
def test_static_and_kinematic_agree_with_fill(nominal, inertia, passive):
    """The static method maximises k with the passive reactions as bounded unknowns; the
    kinematic one minimises over mechanisms with the reactions' largest absorbed work: by
    duality the same k, and the same hinges."""
    structure = Structure(nominal, fill=Fill(0.5, 1600.0, inertia, *PASSIVE[passive]))
    static, kinematic = (both_directions(structure, m) for m in ("static", "kinematic"))
    for s, k in zip(static, kinematic, strict=True):
        assert s.load_multiplier == pytest.approx(k.load_multiplier, abs=AGREEMENT_TOLERANCE)
        assert hinges(s) == hinges(k) and s.is_four_hinge
    # the batch path of samples gives the same numbers
    assert load_multipliers(structure, "kinematic") == pytest.approx(
        (static[0].load_multiplier, static[1].load_multiplier), abs=AGREEMENT_TOLERANCE)


def test_fill_models_in_the_order_their_forces_act(nominal):
    """The fill's weight stabilises: without its inertia ('none') k is highest; its horizontal
    force applied lower ('extrados') costs less than through the column's centroid; a passive
    reaction adds resistance to each."""
    k = {}
    for inertia in ("none", "centroid", "extrados"):
        for name, passive in PASSIVE.items():
            structure = Structure(nominal, fill=Fill(0.5, 1600.0, inertia, *passive))
            k[inertia, name] = both_directions(structure)[0].load_multiplier
    assert k["centroid", "no passive"] < k["extrados", "no passive"] < k["none", "no passive"]
    for inertia in ("none", "centroid", "extrados"):
        assert k[inertia, "passive"] > k[inertia, "no passive"]


@pytest.mark.parametrize("method", ["static", "kinematic"])
def test_thrust_line_balances_the_loads(nominal, method):
    """Between two joints the joint force changes by the block's load (weight, horizontal load,
    passive reaction); the passive reactions stay within their bounds and push toward
    midspan."""
    structure = Structure(nominal, fill=Fill(0.5, 1600.0, "extrados", math.radians(30), 0.33))
    result = both_directions(structure, method)[0]
    line = result.thrust_line
    assert np.diff(line.forces, axis=0) == pytest.approx(line.loads, abs=1e-9 * 1e6)
    loads = structure.loads
    k = result.load_multiplier
    passive = line.loads[:, 0] - k * loads.horizontal
    assert np.all(passive * loads.passive_sign >= -1e-6)
    assert np.all(np.abs(passive) <= loads.passive + 1e-6)
    assert line.loads[:, 1] == pytest.approx(-loads.vertical)


def test_fill_between_piers(nominal):
    """A bridge on piers, both methods: on wide piers the mechanism stays in the filled arch
    (the same k and hinges as on fixed springings, shifted by the courses), on narrower ones it
    runs through a pier and k drops."""
    fill = Fill(0.5, 1600.0, "centroid", math.radians(35), 0.1)
    fixed = both_directions(Structure(nominal, fill=fill))[0]
    for width, runs_through in ((8.0, False), (3.0, True)):
        structure = arch_on_piers(nominal, width, 6.0, 2, fill=fill)
        static, kinematic = (both_directions(structure, m) for m in ("static", "kinematic"))
        for s, k in zip(static, kinematic, strict=True):
            assert s.load_multiplier == pytest.approx(k.load_multiplier,
                                                      abs=AGREEMENT_TOLERANCE)
            assert hinges(s) == hinges(k)
        if runs_through:
            assert static[0].load_multiplier < 0.9 * fixed.load_multiplier
            assert hinges(static[0])[-1] == (11, "extrados")  # the right pier's outer toe
        else:
            assert static[0].load_multiplier == pytest.approx(fixed.load_multiplier, rel=1e-9)
            assert hinges(static[0]) == [(j + 2, f) for j, f in hinges(fixed)]


def test_fill_over_a_shaped_arch_with_curved_faces():
    """Offset curves of an ellipse as extrados (columns by quadrature): both methods agree."""
    arch = shaped_arch("elliptical", span=12.0, rise=4.0, thickness=0.8, voussoirs=8)
    structure = Structure(arch, fill=Fill(0.6, 1700.0, "extrados", math.radians(30), 0.5))
    static, kinematic = (both_directions(structure, m) for m in ("static", "kinematic"))
    for s, k in zip(static, kinematic, strict=True):
        assert s.load_multiplier == pytest.approx(k.load_multiplier, abs=AGREEMENT_TOLERANCE)
