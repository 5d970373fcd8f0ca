"""The report of ``archquake reproduce``: every table, figure and number."""

import json

import numpy as np
import pytest
from report_regression import assert_same, load_fixture

from archquake.cli import main
from archquake.report import ReproductionSettings
from archquake.report.paper import STEPS

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
EXPECTED_FIGURES = (
    "fig02_nominal_arch", "fig04_irregular_arches", "fig06_08_potential_energy",
    "fig09_11_free_vibration_elastic", "fig12_14_free_vibration_paper",
    "fig12_14_free_vibration_computed", "fig15_pulse_response_paper",
    "fig15_pulse_response_computed", "fig16_failure_domain", "fig17_fragility_tp0.40",
    "fig18_fragility_tp0.50", "fig19_fragility_tp0.60", "fig20_fragility_tp0.70",
    "fig21_fragility_surface", "record_fragility", "comparison_rigid_blocks",
    "fig16_failure_domain_both_models", "fig17_20_fragility_both_models",
)


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    out = tmp_path_factory.mktemp("report")
    status = main(["reproduce", "--quick", "--out", str(out), "--no-progress"])
    assert status == 0
    return out, json.loads((out / "results.json").read_text())


def test_report_files_written(report):
    out, _ = report
    for name in ("report.html", "report.md", "results.json"):
        assert (out / name).stat().st_size > 1000, name


def test_every_figure_is_a_valid_png(report):
    import matplotlib.image as mpimg

    out, results = report
    assert sorted(results["figures"]) == sorted(EXPECTED_FIGURES)
    for stem in EXPECTED_FIGURES:
        path = out / f"{stem}.png"
        assert path.read_bytes()[:8] == PNG_SIGNATURE, stem
        image = mpimg.imread(path)
        assert image.ndim == 3 and image.shape[0] > 200 and image.shape[1] > 200, stem
        assert np.ptp(image[..., :3]) > 0.5, f"{stem} is blank"


def test_html_embeds_every_figure_and_needs_no_files(report):
    out, results = report
    text = (out / "report.html").read_text()
    assert text.count("src='data:image/png;base64,") == len(EXPECTED_FIGURES)
    assert ".png'" not in text and '.png"' not in text  # no link to a file beside it
    for fig in results["figures"].values():
        assert fig["paper_figure"] in text


def test_markdown_links_every_figure(report):
    out, _ = report
    text = (out / "report.md").read_text()
    for stem in EXPECTED_FIGURES:
        assert f"]({stem}.png)" in text


def test_tables_match_the_paper(report, paper):
    _, results = report
    t1, t2, t3 = (results[f"table{i}"]["NA"] for i in (1, 2, 3))
    assert t1["k"] == pytest.approx(paper["table1"]["NA"]["load_multiplier"], abs=5e-5)
    assert t1["beta_l"] == pytest.approx(paper["table1"]["NA"]["beta"], abs=5e-5)
    assert t1["paper"]["beta"] == paper["table1"]["NA"]["beta"]
    for key in ("theta_u", "theta_bc_u", "theta_cd_u"):
        assert t2["l"][key] == pytest.approx(paper["table2"]["NA"][key], abs=5e-5)
    for key in ("ab", "bc", "cd"):
        assert t2["l"][key] == pytest.approx(paper["table2"]["NA"][key], abs=5e-3)
    assert t3["l"]["phi_cr"] == pytest.approx(paper["table3"]["NA"]["phi_cr"], abs=5e-5)
    assert t1["agrees"] and t2["agrees"] and t3["agrees"]
    for name in ("RA-1", "RA-2"):  # our own irregular arches: both directions, four hinges
        assert len(results["table1"][name]["beta_l"]) == 4
        assert 0.2 < results["table1"][name]["k"] < 0.5


def test_pulse_outcomes_and_point_q_match_the_paper(report, paper):
    out, results = report
    pulses = results["pulse"]["paper"]
    assert pulses["restitution"] == [paper["dynamics"]["NA"]["restitution_paper"]] * 2
    for row, (duration, _, status, half_cycle) in zip(
            pulses["cases"], paper["dynamics"]["NA"]["pulse_cases"], strict=True):
        assert row["duration"] == duration
        assert (row["NA"]["status"], row["NA"]["half_cycle"]) == (status, half_cycle)
        assert row["NA"]["agrees"]
    q = results["failure_domain"]["q_tp040"]["paper"]
    assert q == pytest.approx(paper["dynamics"]["NA"]["failure_acceleration_tp040"], abs=0.01)
    # the computed coefficient of restitution is the one of archquake.fourlink.impact, not the
    # paper's
    assert results["restitution"]["computed"][0] == pytest.approx(0.645, abs=1e-3)
    # the report names the models and the number each gives (link: tests/fourlink/test_impact.py)
    assert results["restitution"]["link"][0] == pytest.approx(0.883, abs=1e-3)
    notes = (out / "report.md").read_text()
    assert "'link'" in notes and "0.8831" in notes and "'computed'" in notes


def test_free_vibrations_and_fragility_numbers(report):
    _, results = report
    for case in ("elastic", "paper", "computed"):
        for name in ("NA", "RA-1", "RA-2"):
            entry = results["free_vibration"][case][name]
            assert entry["peaks_l"] and entry["outcome"] != "collapse"
    # NA released at phi0 = 0.02 with c_v = 1 returns to the same amplitude
    assert results["free_vibration"]["elastic"]["NA"]["peaks_l"][0] == pytest.approx(0.02,
                                                                                      abs=1e-6)
    frag = results["fragility"]
    assert frag["arches"] == 6 and len(frag["curves"]) == 4
    probability, failures = np.array(frag["probability"]), np.array(frag["failures"])
    assert probability.shape == (4, len(frag["amplitudes_g"]))
    assert np.all(probability[:, 0] == 0.0)  # 0.2 g moves no arch (k~ > 0.25)
    assert np.all(probability[:, -1] == 1.0)  # 0.8 g breaks every arch at t_p = 0.4-0.7 s
    assert np.array_equal(probability * 6, failures)  # eq. (9): P_F = h_f / h
    for curve, duration in zip(frag["curves"], (0.4, 0.5, 0.6, 0.7), strict=True):
        assert curve["duration"] == duration
        assert 0.37 < curve["nominal_failure_acceleration"] < 0.6
    assert results["limit_sample"]["count"] == 100


def test_captions_state_agreement_with_the_paper(report):
    _, results = report
    figures = results["figures"]
    for stem in ("fig02_nominal_arch", "fig06_08_potential_energy",
                 "fig09_11_free_vibration_elastic", "fig12_14_free_vibration_paper",
                 "fig15_pulse_response_paper", "fig16_failure_domain"):
        assert figures[stem]["agrees"] is True, stem
        assert "agrees" in figures[stem]["caption"]
    # with the computed c_v = 0.645 the arch recovers at t_p = 0.27 s, unlike the paper's Fig. 15c
    assert figures["fig15_pulse_response_computed"]["agrees"] is False
    assert "differs" in figures["fig15_pulse_response_computed"]["caption"]


def test_runtime_and_environment_recorded(report):
    _, results = report
    assert results["settings"]["quick"] is True
    assert results["environment"]["archquake"]
    timings = results["timings"]
    assert list(timings) == [*STEPS, "report", "total"] and all(v >= 0 for v in timings.values())
    assert timings["total"] >= sum(v for k, v in timings.items() if k != "total") - 1e-6


def test_comparison_section_comes_from_compare_models(report, nominal):
    """The section's numbers are those of archquake.studies.comparison.compare_models (the curve of
    the
    rigid blocks ran on a second process) at the quick settings; its paragraph and table quote
    them."""
    from archquake.studies.comparison import compare_models
    from archquake.studies.failure_domain import inclusive_range

    out, results = report
    settings = ReproductionSettings.quick_settings()
    comparison = compare_models(nominal, settings.comparison_durations,
                                amplitudes_g=inclusive_range(0.3, 3.0, 0.1),
                                resolution_g=settings.comparison_resolution_g)
    section = results["comparison"]
    assert section["rows"] == json.loads(json.dumps(comparison.to_list()))
    assert section["restitution"]["measured"][0] == pytest.approx(0.7478, abs=1e-4)
    text = (out / "report.md").read_text()
    part = text[text.index("## How far to trust the four-link model"):]
    part = part[:part.index("\n## ", 5)]
    for row in section["rows"]:
        assert f"| {row['duration']:.2f} | {row['rigid_block']:.3f} |" in part
        for value in row["four_link"].values():
            assert f"{value:.3f}" in part
    assert "Long pulses agree. From t_p = 0.70 s on" in part
    assert results["figures"]["comparison_rigid_blocks"]["agrees"] is True


def test_record_fragility_section_comes_from_the_study(report):
    """The section's fits are those of oppenheim_record_fragility at the quick sizes."""
    from archquake.studies.record_fragility import oppenheim_record_fragility

    out, results = report
    s = ReproductionSettings.quick_settings()
    studies = oppenheim_record_fragility(
        ("pga", "pgv"), records=s.record_count, sample_size=s.record_sample_size,
        epsilon=s.epsilon, seed=s.seed, suite_seed=s.seed,
        levels={"pga": s.record_levels_pga, "pgv": s.record_levels_pgv},
        bootstrap=s.record_bootstrap)
    text = (out / "report.md").read_text()
    for im, study in studies.items():
        entry = results["record_fragility"][im]
        assert entry["probability"] == study.probability.tolist()
        assert entry["lognormal"]["median"] == pytest.approx(study.lognormal.median, rel=1e-12)
        variability = study.variability()
        for key in ("record_to_record", "geometric", "total"):
            assert entry[key] == pytest.approx(variability[key], rel=1e-12)
        assert f"{study.lognormal.median:.3f}" in text
    assert "## Record-based fragility (PGA, PGV)" in text


def test_settings_reject_bad_values():
    with pytest.raises(ValueError, match="restitution"):
        ReproductionSettings(restitution=1.5)
    with pytest.raises(ValueError, match="fragility_sample_size"):
        ReproductionSettings(fragility_sample_size=1)
    with pytest.raises(ValueError, match="epsilon"):
        ReproductionSettings(epsilon=1.0)
    with pytest.raises(ValueError, match="amplitude"):
        ReproductionSettings(amplitude_min_g=0.5, amplitude_max_g=0.52)
    with pytest.raises(ValueError, match="record_count"):
        ReproductionSettings(record_count=1)
    with pytest.raises(ValueError, match="record_levels_pga"):
        ReproductionSettings(record_levels_pga=(0.5, 0.4))
    with pytest.raises(ValueError, match="comparison_durations"):
        ReproductionSettings(comparison_durations=())


def test_cli_reports_bad_restitution(tmp_path, capsys):
    assert main(["reproduce", "--quick", "--restitution", "0", "--out", str(tmp_path)]) == 2
    assert "restitution" in capsys.readouterr().err
    assert main(["reproduce", "--quick", "--restitution", "bogus", "--out", str(tmp_path)]) == 2
    assert "--restitution must be one of" in capsys.readouterr().err


def test_regression_results_json_unchanged_by_restructuring(report, data_dir):
    """Every number of ``reproduce --quick`` is what it was before the package was reorganised:
    the fixture is that run's results.json (environment and timings removed). A change of a
    number here must be a deliberate change of physics, with the fixture regenerated."""
    _, results = report
    assert_same(load_fixture(data_dir), results)


def test_both_models_section_comes_from_the_studies(report):
    """The section that runs Figs. 16-20 with both models: its numbers are those of the
    library's calls at the report's settings, and the text names the model that collapses."""
    from archquake import model_for, oppenheim
    from archquake.report.paper.parts import rigid_block_fragility
    from archquake.report.paper.settings import ReproductionSettings
    from archquake.studies.failure_domain import domain_of, inclusive_range

    out, results = report
    settings = ReproductionSettings.quick_settings()
    both = results["two_models"]
    grid = inclusive_range(0.30, settings.comparison_amplitude_max_g,
                           settings.comparison_amplitude_step_g)
    four_link = domain_of(model_for(oppenheim(), restitution=0.875),
                          settings.comparison_durations, grid,
                          resolution_g=settings.comparison_resolution_g, extend_to_g=None)
    assert both["domain"]["four_link_failure_g"] == four_link.failure_accelerations_g.tolist()
    assert both["domain"]["rigid_block_failure_g"] == [
        row["rigid_block"] for row in results["comparison"]["rows"]]
    rigid = rigid_block_fragility(settings)
    assert np.array_equal(both["fragility"]["rigid_blocks"], rigid.probability)
    assert both["fragility"]["search"] == "screened"
    html = (out / "report.html").read_text()
    assert "Both models in the paper" in html and "multi-fidelity" in html
