"""ModelSpec: the model choice as one value (archquake.models).

Its stored form must read every study stored so far (the flat keys of the settings of
``FragilitySettings`` and ``RecordFragilitySettings``), and building from it must give the models
``model_for`` gives.
"""

import math

import pytest

from archquake import GRAVITY, circular_arch, oppenheim
from archquake.defaults import DEFAULT_SEARCH, DEFAULT_TIME_STEP, MODELS
from archquake.ground_motion import oppenheim_pulse
from archquake.models import ModelSpec, model_for, model_spec, screening_model
from archquake.rigid_blocks import BlockSettings


@pytest.mark.parametrize("spec", [
    ModelSpec(),
    ModelSpec("four-link", restitution="paper"),
    ModelSpec("four-link", restitution=0.7),
    ModelSpec("rigid-blocks", friction=0.6, time_step=0.002, coarse_factor=1),
    ModelSpec("rigid-blocks"),
])
def test_round_trip_through_its_dict(spec):
    data = spec.to_dict()
    assert set(data) == {"model", "restitution", "friction", "time_step", "coarse_factor"}
    assert data["model"] == spec.name
    assert ModelSpec.from_dict(data) == spec
    assert hash(ModelSpec.from_dict(data)) == hash(spec)


def test_reads_the_flat_keys_of_a_stored_study():
    """A study's settings hold the model's keys among their own; a study stored before a
    setting existed lacks its key and was computed with the value of STORED_DEFAULTS (before
    coarse steps, every step at h); a former restitution name is read as the current one."""
    stored = {"nominal": {"kind": "circular"}, "sample_size": 40, "epsilon": 0.1,
              "seed": 1, "restitution": "nominal", "model": "rigid-blocks", "search": "screened",
              "stride": 4, "friction": 0.7, "time_step": 0.0005, "coarse_factor": 2}
    assert ModelSpec.from_dict(stored) == ModelSpec("rigid-blocks", "nominal", 0.7, 0.0005, 2)
    older = {"nominal": {}, "restitution": "blocks", "seed": 1}  # before rigid blocks
    assert ModelSpec.from_dict(older) == ModelSpec("four-link", restitution="measured",
                                                   time_step=DEFAULT_TIME_STEP, coarse_factor=1)


def test_the_study_settings_store_the_same_keys_in_the_same_order():
    """The spec is stored flat, where the settings stored its fields before it."""
    from archquake.studies.fragility import FragilitySettings

    keys = list(FragilitySettings(sample_size=2, limit_sample_size=2).to_dict())
    assert keys == ["nominal", "sample_size", "epsilon", "durations", "amplitudes_g", "seed",
                    "restitution", "limit_sample_size", "limit_method", "motion", "model",
                    "search", "stride", "friction", "time_step", "coarse_factor"]


@pytest.mark.parametrize("kwargs, message", [
    ({"name": "dem"}, "model must be one of 'four-link', 'rigid-blocks', got 'dem'"),
    ({"restitution": "blocks"}, "restitution must be one of"),
    ({"restitution": 1.5}, r"restitution coefficient must be in \(0, 1\]"),
    ({"friction": -0.1}, "friction must be >= 0"),
    ({"time_step": 0.0}, "time_step must be > 0"),
    ({"coarse_factor": 0}, r"coarse_factor must be an integer in \[1, 1000\]"),
])
def test_a_bad_setting_is_refused_by_its_name(kwargs, message):
    with pytest.raises(ValueError, match=message):
        ModelSpec(**kwargs)


def test_build_is_model_for():
    arch = oppenheim()
    four_link = ModelSpec(restitution="paper").build(arch)
    again = model_for(arch, "four-link", restitution="paper")
    assert four_link.restitution == again.restitution == (0.875, 0.875)
    assert four_link.load_multipliers == again.load_multipliers
    blocks = ModelSpec("rigid-blocks", friction=0.6, coarse_factor=1).build(arch)
    expected = model_for(arch, "rigid-blocks",
                         block_settings=BlockSettings(friction=0.6, coarse_factor=1))
    assert blocks.settings == expected.settings
    assert blocks.settings.time_step == DEFAULT_TIME_STEP  # chosen from Oppenheim's arch
    pulse = oppenheim_pulse(-GRAVITY, 0.44)  # the paper's Fig. 15b: both collapse
    assert blocks.outcome(pulse).status == expected.outcome(pulse).status


def test_the_nominal_restitution_takes_the_nominal_arch():
    nominal = oppenheim()
    spec = ModelSpec(restitution="nominal")
    assert spec.needs_nominal and not ModelSpec("rigid-blocks", "nominal").needs_nominal
    assert (spec.build(nominal, nominal).restitution
            == model_for(nominal, restitution="computed").restitution)


def test_resolved_records_the_time_step_of_the_structure():
    """1 ms for Oppenheim's arch, 1.5 m thick; sqrt(t / 1.5 m) ms for one t thick."""
    assert ModelSpec("rigid-blocks").resolved(oppenheim()).time_step == DEFAULT_TIME_STEP
    assert ModelSpec("rigid-blocks", time_step=0.002).resolved(oppenheim()).time_step == 0.002
    thin = circular_arch(10.0, 2.75, 0.375, 9)
    assert ModelSpec().resolved(thin).time_step == pytest.approx(5e-4)


def test_capabilities_answer_what_the_studies_asked_by_name():
    for name in MODELS:
        spec = ModelSpec(name)
        assert spec.default_search == DEFAULT_SEARCH[name]
        assert spec.grid_in_one_call == spec.model_class.grid_in_one_call
    four_link, blocks = ModelSpec("four-link"), ModelSpec("rigid-blocks")
    assert (four_link.chunk_size, blocks.chunk_size) == (2, 1)
    assert (four_link.nominal_resolution_g, blocks.nominal_resolution_g) == (1e-4, 2e-3)
    assert (four_link.checks_standing, blocks.checks_standing) == (False, True)
    assert four_link.screening() is None
    assert blocks.screening("paper") == ModelSpec("four-link", restitution="paper")


def test_the_screening_model_of_the_rigid_blocks_is_the_four_link_model_of_the_arch():
    blocks = ModelSpec("rigid-blocks").build(oppenheim())
    screen = screening_model(blocks)
    assert screen.name == "four-link" and screen.restitution_model == "computed"
    four_link = ModelSpec().build(oppenheim())
    assert screening_model(four_link) is four_link


def test_check_motion_refuses_a_step_that_cannot_follow_the_pulse():
    pulse = oppenheim_pulse(-GRAVITY, 0.06)
    assert ModelSpec(time_step=0.5).check_motion(oppenheim(), pulse) == math.inf
    with pytest.raises(ValueError, match="time_step must be at most 0.003 s"):
        ModelSpec("rigid-blocks", time_step=0.004).check_motion(oppenheim(), pulse)


def test_model_spec_takes_a_spec_a_name_or_nothing():
    spec = ModelSpec("rigid-blocks", friction=0.5)
    assert model_spec(spec) is spec
    assert model_spec("rigid-blocks") == ModelSpec("rigid-blocks")
    assert model_spec(None) == ModelSpec()
    with pytest.raises(ValueError, match="model must be a ModelSpec"):
        model_spec(3)


@pytest.mark.parametrize(("kwargs", "match"), [
    ({"friction": -0.1}, "friction"), ({"time_step": 0.0}, "time_step"),
    ({"coarse_factor": 0}, "coarse_factor")])
def test_the_four_link_spec_still_checks_the_block_settings_it_is_given(kwargs, match):
    # the check is skipped only for the defaults, which are valid
    with pytest.raises(ValueError, match=match):
        ModelSpec("four-link", **kwargs)


def test_the_four_link_spec_with_defaults_does_not_import_the_rigid_blocks():
    import subprocess
    import sys

    code = ("import sys; from archquake.models import ModelSpec; ModelSpec('four-link'); "
            "print('archquake.rigid_blocks' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.strip()
    assert out == "False"
