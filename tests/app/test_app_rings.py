"""The page describes structures as the command line does; an arch of several rings (a block
assembly, which only ``archquake limit`` analyses) is refused with a message, not a crash."""

import pytest

from archquake.app.inputs import structure_from_spec


def test_rings_are_refused_by_the_page():
    with pytest.raises(ValueError, match="archquake limit"):
        structure_from_spec({"rings": 2})
    nominal, structure = structure_from_spec({"voussoirs": 7})
    assert structure.n_voussoirs == 7
