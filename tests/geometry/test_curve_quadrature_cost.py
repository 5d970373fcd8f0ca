"""The mass properties of curved voussoirs: a small piece of a curve whose points carry
round-off stops refining once its sums agree to that noise (it used to refine to 1024 panels:
10 000 catenary voussoirs took minutes), and the properties are unchanged to that noise."""

import numpy as np
import pytest

from archquake.geometry import mass, shaped_arch


def _count_sums(monkeypatch):
    calls = {"n": 0}
    original = mass.Curve._gauss

    def counted(self, reference, panels):
        calls["n"] += 1
        return original(self, reference, panels)

    monkeypatch.setattr(mass.Curve, "_gauss", counted)
    return calls


def test_small_curved_voussoirs_take_few_sums_and_add_up_to_the_whole(monkeypatch):
    """2 000 voussoirs of a catenary arch: at most 3 sums per face on average (there were 10),
    and together they weigh what 10 voussoirs of the same arch weigh (whose faces converge to
    1e-13), with the same first moment, to 1e-9."""
    coarse = shaped_arch("catenary", span=10.0, rise=4.5, thickness=1.5, voussoirs=10)
    calls = _count_sums(monkeypatch)
    fine = shaped_arch("catenary", span=10.0, rise=4.5, thickness=1.5, voussoirs=2000)
    masses, centroids = fine.masses, fine.centroids
    assert calls["n"] <= 3 * 2 * 2000
    assert masses.sum() == pytest.approx(coarse.masses.sum(), rel=1e-9)
    moment = (masses[:, None] * centroids).sum(axis=0)
    expected = (coarse.masses[:, None] * coarse.centroids).sum(axis=0)
    assert moment == pytest.approx(expected, rel=1e-9, abs=1e-9 * np.abs(expected).max())
