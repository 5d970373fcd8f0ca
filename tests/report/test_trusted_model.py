"""The first screen of ``archquake assess`` takes its numbers from the model it trusts: the
rigid-block model where the two models disagree beyond the agreement band (Oppenheim's arch on
piers 3 m wide and 6 m high), with the four-link numbers beside them marked "not used"; the
four-link model where they agree (Oppenheim's arch on fixed supports), saying so.

The rigid-block numbers are checked against the rigid-block studies run here by their own
calls (``domain_of``, ``run_fragility``, ``run_record_fragility``) with the same settings, in
this process (the assessment runs them on worker processes); the agreement against the two
models' failure accelerations computed here. Sizes are tiny: a smoke test of the wiring, not an
assessment.
"""

import json

import numpy as np
import pytest

import forced_undecided as forced
from archquake.geometry import arch_on_piers
from archquake.ground_motion import RecordSuite
from archquake.models import ModelSpec
from archquake.reference_arches import oppenheim
from archquake.report.assess import assess
from archquake.report.assess import parts as assess_parts
from archquake.report.assess.settings import AssessmentSettings
from archquake.status import Status
from archquake.studies.failure_domain import domain_of
from archquake.studies.record_fragility import STOCHASTIC_SUITE

TINY = {"durations": (0.4, 1.0), "amplitude_points": 10, "domain_resolution_g": 0.02,
        "fragility_sample_size": 2, "limit_sample_size": 20, "fragility_amplitude_points": 8,
        "record_sample_size": 2, "rigid_block_fragility_sample_size": 2,
        "rigid_block_record_sample_size": 1, "record_levels": 4, "record_count": 2,
        "bootstrap": 10}
"""Settings of the tiny assessments (a quick run, smaller still)."""


def tiny_settings(**changes):
    return AssessmentSettings.quick_settings(**{**TINY, **changes})


def tiny_suite():
    return RecordSuite.from_stochastic(2, 3, **STOCHASTIC_SUITE)


def on_piers():
    return arch_on_piers(oppenheim(), 3.0, 6.0)


@pytest.fixture(scope="module")
def disagreeing(tmp_path_factory):
    """Oppenheim's arch on piers 3 m x 6 m: the four-link model is unconservative there."""
    out = tmp_path_factory.mktemp("trusted") / "piers"
    settings = tiny_settings()
    result = assess(on_piers(), records=tiny_suite(), settings=settings, out_dir=out,
                    progress=False)
    return {"results": result.results, "out": out, "settings": settings,
            "md": (out / "report.md").read_text(), "verdict": result.verdict}


def first_screen(md: str) -> str:
    return md.split("## Summary")[1].split("\n## ")[0]


def table_row(screen: str, words: str) -> str:
    """The row of the first screen's table that holds ``words``."""
    return next(line for line in screen.splitlines() if line.startswith("|") and words in line)


def test_the_rigid_block_model_is_trusted_where_the_models_disagree(disagreeing):
    r = disagreeing["results"]
    s = disagreeing["settings"]
    structure = on_piers()
    p = r["pulses"]
    # the two failure accelerations at t_p = 1 s, each by its model's own call
    rigid = domain_of(ModelSpec("rigid-blocks", friction=s.friction).build(structure), [1.0],
                      p["amplitudes_g"], direction=p["direction"], resolution_g=p["resolution_g"],
                      extend_to_g=None).slices[0].failure_acceleration_g
    four = domain_of(ModelSpec("four-link", restitution=s.restitution).build(structure), [1.0],
                     p["amplitudes_g"], direction=p["direction"], resolution_g=p["resolution_g"],
                     extend_to_g=None).slices[0].failure_acceleration_g
    assert four / rigid - 1.0 > 0.05  # beyond the band: they disagree
    assert r["trusted"]["model"] == "rigid-blocks" and r["trusted"]["agree"] is False
    long = r["summary"]["pulse_long"]
    assert long["model"] == "rigid-blocks" and long["rigid_blocks"] == rigid
    screen = first_screen(disagreeing["md"])
    row = table_row(screen, "long pulse")
    cells = [c.strip() for c in row.strip("|").split("|")]
    assert cells[1] == f"{rigid:.3f} g" and cells[2] == "rigid-block model"
    off = 100.0 * (four / rigid - 1.0)
    assert cells[3] == f"four-link: {four:.3f} g (off by {off:+.1f} %, not used)"
    assert "Model used: the rigid-block model" in screen
    assert (f"under a long pulse (t_p = 1.00 s) of {rigid:.3f} g" in disagreeing["verdict"]
            and "by the rigid-block model" in disagreeing["verdict"])


def test_the_irregular_arches_on_the_first_screen_are_the_rigid_block_study(disagreeing):
    from archquake.studies.fragility import FragilitySettings, run_fragility

    r = disagreeing["results"]
    s = disagreeing["settings"]
    fl = r["irregularity"]
    assert fl["model"] == "four-link"
    again = run_fragility(FragilitySettings(
        nominal=on_piers(), sample_size=s.rigid_block_fragility_sample_size, epsilon=s.epsilon,
        durations=tuple(fl["settings"]["durations"]),
        amplitudes_g=tuple(fl["settings"]["amplitudes_g"]), seed=s.seed,
        model=ModelSpec("rigid-blocks", friction=s.friction),
        limit_sample_size=s.limit_sample_size), progress=False, backend="serial")
    theirs = again.summary()["durations"][-1]
    entry = r["summary"]["irregular"]
    assert entry["model"] == "rigid-blocks"
    assert entry["curve"]["lognormal_median"] == theirs["lognormal_median"]
    assert entry["curve"]["nominal_failure_acceleration"] == (
        theirs["nominal_failure_acceleration"])
    assert entry["undecided"]["analyses"] == again.undecided_analyses
    # the four-link study beside it, marked
    shown = entry["four_link"]
    assert shown["used"] is False and shown["curve"] == fl["durations"][-1]
    assert shown["off_by"] == pytest.approx(fl["durations"][-1]["lognormal_median"]
                                            / theirs["lognormal_median"] - 1.0, rel=1e-12)
    row = table_row(first_screen(disagreeing["md"]), "irregular masonry")
    assert "| rigid-block model |" in row and "not used)" in row
    assert f"{theirs['lognormal_median']:.3f} g" in row


def test_the_record_capacities_on_the_first_screen_are_the_rigid_block_study(disagreeing):
    from archquake.studies.record_fragility import RecordFragilitySettings, run_record_fragility

    r = disagreeing["results"]
    s = disagreeing["settings"]
    screen = first_screen(disagreeing["md"])
    for im in ("pga", "pgv"):
        fl = r["records"]["ims"][im]
        assert fl["model"] == "four-link"
        again = run_record_fragility(RecordFragilitySettings(
            suite=tiny_suite(), levels=tuple(fl["levels"]), im=im, nominal=on_piers(),
            sample_size=s.rigid_block_record_sample_size, epsilon=s.epsilon, seed=s.seed,
            model=ModelSpec("rigid-blocks", friction=s.friction), bootstrap=s.bootstrap),
            progress=False, backend="serial")
        entry = r["summary"]["records"][im]
        assert entry["model"] == "rigid-blocks"
        assert entry["nominal_lognormal"]["median"] == (
            None if again.nominal_lognormal is None else again.nominal_lognormal.median)
        assert entry["lognormal"]["median"] == (
            None if again.lognormal is None else again.lognormal.median)
        assert entry["undecided"]["analyses"] == int(again.undecided.sum())
        assert entry["four_link"]["used"] is False
        assert entry["four_link"]["nominal_lognormal"] == fl["nominal_lognormal"]
        row = table_row(screen, f"collapse under the records, {im.upper()}")
        assert "| rigid-block model |" in row and "four-link: median" in row
        assert "not used)" in row
    # results.json names the model of every result
    stored = json.loads((disagreeing["out"] / "results.json").read_text())
    assert {e["model"] for e in stored["rigid_block_studies"]["records"]["ims"].values()} == {
        "rigid-blocks"}
    assert stored["rigid_block_studies"]["irregularity"]["model"] == "rigid-blocks"


def test_the_four_link_model_is_used_and_named_where_the_models_agree(tmp_path):
    arch = oppenheim()
    settings = tiny_settings(durations=(0.7, 1.0), domain_resolution_g=0.01)
    result = assess(arch, records=tiny_suite(), settings=settings, out_dir=tmp_path / "opp",
                    progress=False)
    r = result.results
    p = r["pulses"]
    # the agreement, by the two models' own calls: within 5 % at both durations
    here = {}
    for name in ("four-link", "rigid-blocks"):
        spec = ModelSpec(name, restitution=settings.restitution, friction=settings.friction)
        domain = domain_of(spec.build(arch), list(settings.durations), p["amplitudes_g"],
                           direction=p["direction"], resolution_g=p["resolution_g"],
                           extend_to_g=None)
        here[name] = np.array([s.failure_acceleration_g for s in domain.slices])
    assert np.all(np.abs(here["four-link"] / here["rigid-blocks"] - 1.0) <= 0.05)
    assert r["trusted"] == {**r["trusted"], "model": "four-link", "agree": True}
    assert r["rigid_block_studies"] == {}
    assert r["summary"]["irregular"]["model"] == "four-link"
    assert {e["model"] for e in r["summary"]["records"].values()} == {"four-link"}
    screen = first_screen((tmp_path / "opp" / "report.md").read_text())
    assert "Model used: the four-link model" in screen and "not used" not in screen
    row = table_row(screen, "long pulse")
    assert f"| {here['four-link'][-1]:.3f} g | four-link model (the two agree) |" in row
    assert (f"of {here['four-link'][-1]:.3f} g" in result.verdict
            and "by the four-link model (the two models agree)" in result.verdict)


def test_the_trusted_model_by_hand():
    """Rows written by hand: within 5 % everywhere, or neither collapsing, is agreement; a
    difference of 6 %, one model alone collapsing, or an undecided rigid-block failure is not."""
    def row(duration, four_link, rigid, undecided_from=None):
        difference = (None if four_link is None or rigid is None or undecided_from is not None
                      else four_link / rigid - 1.0)
        return {"duration": duration, "four_link": four_link, "rigid_blocks": rigid,
                "difference": difference, "rigid_blocks_undecided_from": undecided_from}

    def pulses(*rows):
        return {"rows": list(rows), "agreement": {"band": 0.05}}

    agree = pulses(row(0.1, None, None), row(0.5, 0.52, 0.50), row(1.0, 0.40, 0.41))
    assert assess_parts.trusted_model(agree, True)["model"] == "four-link"  # +4 %, -2.4 %
    for bad in (row(1.0, 0.53, 0.50),                 # +6 %
                row(1.0, None, 0.50),                 # only the rigid blocks collapse
                row(1.0, 0.50, 0.50, undecided_from=0.45)):  # undecided below 0.50 g
        trusted = assess_parts.trusted_model(pulses(row(0.5, 0.52, 0.50), bad), True)
        assert trusted["model"] == "rigid-blocks" and trusted["disagreeing"] == [1.0]
    assert assess_parts.trusted_model({"rows": []}, False)["model"] == "rigid-blocks"


def test_undecided_rigid_block_analyses_stay_visible_on_the_first_screen(tmp_path, monkeypatch):
    """With the rigid blocks forced to leave bands undecided (in this process: one processor),
    the first screen counts them for each rigid-block study it uses, and the report warns."""
    import os

    calls = forced.force(monkeypatch)
    monkeypatch.setattr(os, "cpu_count", lambda: 1)
    result = assess(on_piers(), records=tiny_suite(), settings=tiny_settings(),
                    out_dir=tmp_path / "forced", progress=False)
    r = result.results
    assert r["trusted"]["model"] == "rigid-blocks"
    made = sum(1 for c in calls if c[2] is Status.UNDECIDED)
    counted = r["pulses"]["rigid_blocks"]["undecided"]
    studies = r["rigid_block_studies"]
    counted += studies["irregularity"]["undecided"]["analyses"]
    counted += studies["irregularity"]["undecided"]["nominal_analyses"]
    for entry in studies["records"]["ims"].values():
        counted += entry["undecided"]["analyses"] + entry["undecided"]["nominal_analyses"]
    counted += r["records"]["check"]["rigid_blocks_undecided"]
    assert counted == made > 0
    screen = first_screen((tmp_path / "forced" / "report.md").read_text())
    for im, entry in r["summary"]["records"].items():
        if entry["undecided"]["analyses"]:
            row = table_row(screen, f"collapse under the records, {im.upper()}")
            assert (f"{entry['undecided']['analyses']} of {entry['undecided']['of']} "
                    f"rigid-block analyses undecided") in row
    assert screen.lstrip().startswith("WARNING")


def test_the_nrml_files_are_the_trusted_models(disagreeing):
    # fragility_<im>.xml is the rigid blocks' fit (what a risk study reads), the four-link
    # model's fit kept beside it as fragility_<im>_four_link.xml; where the rigid blocks'
    # stripes admit no fit there is no fragility_<im>.xml and the risk's reader refuses the
    # folder rather than read the four-link model's file in its place
    from archquake.site.fragility_models import read_fragility_nrml, read_fragility_study

    r = disagreeing["results"]
    out = disagreeing["out"]
    rigid = r["rigid_block_studies"]["records"]["ims"]["pga"]
    four = r["records"]["ims"]["pga"]
    assert four["nrml"] == "fragility_pga_four_link.xml"
    aside = read_fragility_nrml(out / four["nrml"], function_id="masonry-arch")
    assert aside.median == pytest.approx(four["lognormal"]["median"], rel=1e-4)
    if rigid["lognormal"]["median"] is None:
        assert rigid["nrml"] is None and not (out / "fragility_pga.xml").exists()
        with pytest.raises(ValueError, match="four-link model's"):
            read_fragility_study(out, im="PGA")
        return
    assert rigid["nrml"] == "fragility_pga.xml"
    read = read_fragility_nrml(out / rigid["nrml"], function_id="masonry-arch")
    assert read.median == pytest.approx(rigid["lognormal"]["median"], rel=1e-4)
    study = read_fragility_study(out, im="PGA", function_id="masonry-arch").fragility
    assert study.median == pytest.approx(read.median, rel=1e-12)
    assert {"fragility_pga.xml", "fragility_pga_four_link.xml"} <= set(r["files"])
