"""``archquake simulate`` against the paper's Fig. 15 statements (Sect. 5.3.2, REFERENCE.md)."""

import csv
import json
from pathlib import Path

import pytest

from archquake.cli import main

DATA = Path(__file__).parents[1] / "data"


def run_json(capsys, *argv):
    assert main(["simulate", *argv, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


@pytest.mark.parametrize("case", range(3))
def test_fig15_outcomes_with_paper_restitution(capsys, paper, case):
    duration, amplitude, outcome, half_cycle = paper["dynamics"]["NA"]["pulse_cases"][case]
    out = run_json(capsys, "--amplitude", str(amplitude), "--duration", str(duration),
                   "--restitution", "paper")
    assert out["outcome"] == outcome
    assert out["half_cycle"] == half_cycle
    if outcome == "collapse":
        assert out["impacts"] == half_cycle - 1
        assert 0 < out["collapse_time"] < 3 * duration + 5
    else:
        # decided by the energy barrier once the pulse is over; impacts counted until then
        assert out["collapse_time"] is None and out["half_cycle"] == 0


def test_below_activation_stays_at_rest(capsys):
    out = run_json(capsys, "--amplitude", "-0.3", "--duration", "0.3")
    assert out == {"outcome": "rest", "half_cycle": 0, "impacts": 0,
                   "impacts_before_decision": 0, "collapse_time": None, "max_phi": 0.0,
                   "at_rest_from": 0.0}


def test_output_csv_plot_and_text(tmp_path, capsys):
    csv_path, png = tmp_path / "h.csv", tmp_path / "h.png"
    assert main(["simulate", "--restitution", "paper", "--output", str(csv_path),
                 "--plot", str(png)]) == 0
    assert "collapses in half cycle 2" in capsys.readouterr().out
    rows = list(csv.DictReader(csv_path.open()))
    assert rows[0].keys() == {"t_s", "phi_rad", "theta_dot_rad_s", "mechanism"}
    assert {r["mechanism"] for r in rows} >= {"l", "r"}
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_record_and_free_vibration(capsys):
    out = run_json(capsys, "--record", str(DATA / "decaying_sine.csv"), "--scale-to", "0.2")
    assert out["outcome"] == "rest"  # 0.2 g < k = 0.37 g
    out = run_json(capsys, "--phi0", "0.02", "--restitution", "elastic", "--t-end", "6")
    assert out["outcome"] == "recovery" and out["max_phi"] == pytest.approx(0.02, rel=1e-9)


@pytest.mark.parametrize("argv, message", [
    (["--motion", "record"], "needs --record"),
    (["--scale-to", "0.3"], "--scale-to"),
    (["--cycles", "2"], "--cycles"),
    (["--duration", "-1"], "duration"),
    (["--record", "missing.csv"], "missing.csv"),
])
def test_simulate_bad_input(capsys, argv, message):
    assert main(["simulate", *argv]) == 2
    assert message in capsys.readouterr().err


@pytest.mark.parametrize("argv, message", [
    (["simulate", "--plot", "{missing}/x.png"], "cannot write the figure"),
    (["simulate", "--output", "{missing}/x.csv"], "cannot write the time history"),
    (["limit", "--plot", "{missing}/x.png"], "cannot write the figure"),
    (["reproduce", "--quick", "--no-progress", "--out", "{file}/report"], "error:"),
])
def test_unusable_output_paths_are_errors_not_tracebacks(tmp_path, capsys, argv, message):
    blocker = tmp_path / "a_file"
    blocker.write_text("")
    argv = [a.format(missing=tmp_path / "missing", file=blocker) for a in argv]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert message in err and "Traceback" not in err


def test_output_csv_reads_back_as_the_numbers_of_the_history(tmp_path):
    import numpy as np
    import pandas as pd

    from archquake import oppenheim
    from archquake.fourlink.impact import restitution
    from archquake.fourlink.mechanism import mechanisms
    from archquake.fourlink.time_history import simulate
    from archquake.geometry import GRAVITY
    from archquake.ground_motion import oppenheim_pulse

    path = tmp_path / "h.csv"
    assert main(["simulate", "--restitution", "paper", "--output", str(path)]) == 0
    table = pd.read_csv(path)
    for column in ("t_s", "phi_rad", "theta_dot_rad_s"):
        assert table[column].dtype == np.float64, column
    pair = mechanisms(oppenheim())
    history = simulate(pair, oppenheim_pulse(-GRAVITY, 0.27), restitution("paper", *pair))
    theta_dot = np.concatenate([s.theta_dot for s in history.segments])
    for column, values in (("t_s", history.t), ("phi_rad", history.phi),
                           ("theta_dot_rad_s", theta_dot)):
        np.testing.assert_allclose(table[column].to_numpy(), values, rtol=1e-15, atol=0)
    assert table["mechanism"].tolist() == history.mechanism.tolist()


def test_reported_impacts_are_those_of_the_recorded_motion(tmp_path, capsys):
    # Oppenheim's -1 g, 0.27 s pulse: the arch is still in its first half cycle when the pulse
    # ends (no impact before the decision) and then rocks to rest through many impacts.
    path = tmp_path / "h.csv"
    out = run_json(capsys, "--output", str(path))
    import pandas as pd

    table = pd.read_csv(path)
    state = table["mechanism"].to_numpy()
    # an impact ends a motion of Mech-l or Mech-r: the next row is the other one, or rest
    ends = (state[:-1] != "rest") & (state[1:] != state[:-1])
    switches = int(ends.sum())
    assert out["outcome"] == "recovery" and state[-1] == "rest"
    assert out["impacts_before_decision"] == 0
    assert out["impacts"] == switches > 10
    assert out["at_rest_from"] == table["t_s"].to_numpy()[1:][ends][-1]
    assert main(["simulate"]) == 0
    text = capsys.readouterr().out
    assert f"{switches} impact(s)" in text and "0 impact(s)" not in text
