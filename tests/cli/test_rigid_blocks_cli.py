"""``archquake rigid-blocks``: the rigid-block model from the command line."""

import csv
import json

import pytest

from archquake.cli import main


def run_json(capsys, *argv):
    assert main(["rigid-blocks", *argv, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_json_outcomes_around_activation(capsys):
    """Oppenheim's arch: k = 0.37 (limit analysis), so -0.30 g leaves it at rest and a long
    -0.6 g pulse brings it down; the JSON carries the documented keys."""
    rest = run_json(capsys, "--amplitude", "-0.30", "--duration", "0.5")
    assert rest["outcome"] == "rest" and rest["collapse_time"] is None
    assert rest["max_rotation"] < 1e-8 and rest["max_slip"] < 1e-8
    collapse = run_json(capsys, "--amplitude", "-0.6", "--duration", "0.5")
    assert collapse["outcome"] == "collapse"
    assert 1.5 < collapse["collapse_time"] < 5.0
    for key in ("max_rotation", "max_crown_drop", "max_slip"):
        assert collapse[key] > 0
    assert collapse["max_crown_drop"] > 0.5  # beyond the four-link critical drop (0.33 t)


def test_recovery_with_output_and_plot(tmp_path, capsys):
    csv_path, png = tmp_path / "h.csv", tmp_path / "h.png"
    assert main(["rigid-blocks", "--amplitude", "-0.6", "--duration", "0.3", "--friction", "0.7",
                 "--output", str(csv_path), "--plot", str(png)]) == 0
    out = capsys.readouterr().out
    assert "comes back to rest" in out and "friction 0.7" in out
    rows = list(csv.DictReader(csv_path.open()))
    assert {"t_s", "crown_drop_m", "x3_m", "rotation6_rad", "opening7_m", "slip0_m"} <= set(
        rows[0])
    assert float(rows[0]["t_s"]) == 0.0
    assert max(float(r["opening3_m"]) for r in rows) > 0.01
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_animation_of_a_short_record(tmp_path, capsys):
    """--t-end records a fixed time; undecided by then, the run says so."""
    gif = tmp_path / "h.gif"
    assert main(["rigid-blocks", "--amplitude", "-0.6", "--duration", "0.3", "--t-end", "0.4",
                 "--animate", str(gif)]) == 0
    assert "not decided" in capsys.readouterr().out
    assert gif.read_bytes()[:6] == b"GIF89a"


def test_record_and_irregular_arch(tmp_path, capsys):
    record = tmp_path / "r.csv"
    record.write_text("time_s,acc_g\n0,0\n0.1,-0.2\n0.5,-0.2\n0.6,0\n")
    out = run_json(capsys, "--record", str(record), "--scale-to", "0.25", "--epsilon", "0.1",
                   "--seed", "3", "--time-step", "0.002")
    assert out["outcome"] == "rest" and out["time_step"] == 0.002


@pytest.mark.parametrize("argv, message", [
    (["--friction", "-1"], "friction"),
    (["--time-step", "0"], "--time-step must be > 0"),
    (["--scale-to", "0.3"], "--scale-to"),
    (["--record", "missing.csv"], "missing.csv"),
])
def test_bad_options_are_reported(capsys, argv, message):
    assert main(["rigid-blocks", *argv]) == 2
    err = capsys.readouterr().err
    assert err.startswith("archquake: error:") and message in err
