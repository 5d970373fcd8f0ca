"""An assessment refuses up front what would stop it after minutes, and one stopped later, or
resumed with other records, says how to go on."""

import pytest

from archquake.cli import main
from archquake.defaults import MAX_LIMIT_SAMPLES, MAX_SAMPLES
from archquake.limit_analysis import friction_margin
from archquake.reference_arches import oppenheim
from archquake.report.assess import AssessmentSettings, assess
from archquake.report.assess import assessment as assessment_module


# Oppenheim's arch stands on its joints from a friction of about 0.2 (friction_margin: -inf at
# 0.20, +0.046 at 0.22): below, the rigid-block domain would stop the assessment after minutes
@pytest.mark.parametrize("friction", [0.0, 0.1, 0.19])
def test_an_assessment_with_a_friction_that_cannot_hold_the_arch_is_refused_before_writing(
        tmp_path, capsys, friction):
    assert friction_margin(oppenheim(), friction) < 0  # the premise
    out = tmp_path / "a"
    with pytest.raises(ValueError, match=f"friction must let the rigid-block model .* got "
                                         f"{friction:g}"):
        assess(oppenheim(), settings=AssessmentSettings.quick_settings(friction=friction),
               out_dir=out, progress=False)
    assert not out.exists()
    assert main(["assess", "--quick", "--friction", f"{friction:g}", "--out", str(out),
                 "--no-progress"]) == 2
    assert "archquake: error: --friction must let the rigid-block model" in (
        capsys.readouterr().err)
    assert not out.exists()


@pytest.mark.parametrize("friction", [0.22, 0.6])
def test_a_friction_that_holds_the_arch_passes_the_check(friction):
    assert friction_margin(oppenheim(), friction) > 0
    assessment_module.check_before_writing(
        oppenheim(), AssessmentSettings.quick_settings(friction=friction))


@pytest.mark.parametrize("name, most", [("fragility_sample_size", MAX_SAMPLES),
                                        ("record_sample_size", MAX_SAMPLES),
                                        ("limit_sample_size", MAX_LIMIT_SAMPLES)])
def test_a_sample_larger_than_the_studies_take_is_refused_by_the_settings(name, most):
    """Refused where the settings are made, before any part runs (the studies refuse it
    after the parts before them)."""
    assert getattr(AssessmentSettings(**{name: most}), name) == most
    for too_many in (most + 1, 10 * most):
        with pytest.raises(ValueError, match=f"^{name} must be an integer in "):
            AssessmentSettings(**{name: too_many})


def test_an_assessment_stopped_after_writing_says_how_to_go_on_and_resumes(tmp_path,
                                                                          monkeypatch):
    out = tmp_path / "a"

    def every_arch_excluded(*args, **kwargs):
        raise ValueError("every irregular arch is excluded")

    monkeypatch.setattr(assessment_module, "_compute", every_arch_excluded)
    with pytest.raises(ValueError) as stopped:
        assess(oppenheim(), quick=True, suite=None, out_dir=out, progress=False)
    message = str(stopped.value)
    assert message.startswith("every irregular arch is excluded; the assessment in ")
    assert "--resume" in message and "new --out" in message
    # the folder is resumable: the same assessment continues (here: stops again the same way)
    with pytest.raises(ValueError, match="every irregular arch is excluded"):
        assess(oppenheim(), quick=True, out_dir=out, progress=False, resume=True)


@pytest.mark.parametrize("before, now, words", [
    ({"kind": "stochastic", "count": 6}, {"kind": "builtin", "name": "fema-p695-near-field"},
     ("synthetic records", "the built-in suite 'fema-p695-near-field'")),
    ({"kind": "builtin", "name": "fema-p695-far-field"}, {"kind": "stochastic", "count": 6},
     ("the built-in suite 'fema-p695-far-field'", "synthetic records")),
])
def test_a_resume_with_other_records_names_the_suite_change_and_what_to_do(tmp_path, before,
                                                                           now, words):
    """An assessment started before the records extra was installed (synthetic records) and
    resumed after it (the built-in suite, the new default), or the other way round."""
    record = {"archquake": "1", "structure": {"arch": 1}, "settings": {"seed": 1}}
    out = tmp_path / "a"
    assessment_module.prepare_directory(out, {**record, "suite": before}, resume=False)
    with pytest.raises(ValueError) as refused:
        assessment_module.prepare_directory(out, {**record, "suite": now}, resume=True)
    message = str(refused.value)
    assert f"it was started with {words[0]}" in message and f"this run has {words[1]}" in message
    assert "'records' extra" in message
    assert "the same --suite or --records" in message and "new --out" in message
