"""A site by named values: the same actions as the functions it names, a lossless record, and
refusals naming the field."""

import pytest

from archquake.site.local_mechanism import SiteAction
from archquake.site.spec import SiteSpec
from archquake.site.spectra import ntc2018_spectrum, read_ntc_site
from site_reference import GRID_TABLE

GRID = GRID_TABLE


def test_one_spectrum_is_the_slv_action():
    spec = SiteSpec(code="ntc2018", ag=0.25, f0=2.4, tc_star=0.3, soil="C",
                    knowledge_level="LC2")
    (action,) = spec.actions()
    direct = SiteAction.of("SLV", ntc2018_spectrum(0.25, 2.4, 0.3, "C"))
    assert action.limit_state == "SLV" and action.ag == direct.ag
    assert action.spectrum.pga == pytest.approx(direct.spectrum.pga, rel=1e-15)
    assert spec.fc == 1.2 and spec.hazard_curve() is None
    assert SiteSpec.from_dict(spec.to_dict()) == spec


def test_grid_gives_slv_and_slc_and_a_hazard_curve(tmp_path):
    path = tmp_path / "grid.csv"
    path.write_text(GRID)
    spec = SiteSpec(grid=str(path), soil="B")
    states = {a.limit_state: a for a in spec.actions()}
    site = read_ntc_site(path)
    assert set(states) == {"SLV", "SLC"}
    assert states["SLC"].spectrum.pga == pytest.approx(
        site.spectrum("SLC", "B").pga, rel=1e-15)
    curve = spec.hazard_curve()
    # the curve's frequencies are 1/TR at the nine return periods
    assert curve.frequencies[0] == pytest.approx(1 / 30) and curve.frequencies[-1] == \
        pytest.approx(1 / 2475)


@pytest.mark.parametrize("fields, name", [
    ({}, "code"),
    ({"code": "ntc2018", "grid": "x.csv"}, "code"),
    ({"code": "nz"}, "code"),
    ({"code": "ntc2018", "ag": 0.2, "f0": 2.4}, "tc_star"),
    ({"code": "ntc2018", "ag": 0.2, "f0": 2.4, "tc_star": 0.3, "agr": 0.2}, "agr"),
    ({"code": "user", "file": "s.csv", "limit_state": "SLO"}, "limit_state"),
    ({"code": "user", "file": "s.csv", "knowledge_level": "LC0"}, "knowledge_level"),
])
def test_refusals_name_the_field(fields, name):
    with pytest.raises(ValueError, match=name):
        SiteSpec(**fields)
    with pytest.raises(ValueError, match="altitude"):
        SiteSpec.from_dict({"code": "user", "file": "s.csv", "altitude": 3})
