"""The page builds the structure and the ground motion that the command line builds from the
same values, and refuses bad input with the command line's message, naming the field where the
command line names the option."""

import json

import numpy as np
import pytest
from app_reference import BAD_GEOMETRY, cli_error, cli_json, fields_named

from archquake.app.inputs import LIMITS, Uploads, motion_from_spec, structure_from_spec
from archquake.limit_analysis import both_directions


@pytest.mark.parametrize("spec, argv", [
    ({"thickness": 1.2}, ["--thickness", "1.2"]),
    ({"shape": "pointed", "span": 10, "rise": 7, "thickness": 0.6, "voussoirs": 12},
     ["--shape", "pointed", "--span", "10", "--rise", "7", "--thickness", "0.6",
      "--voussoirs", "12"]),
    ({"piers": "2,4,2", "fill_cover": 0.5}, ["--piers", "2,4,2", "--fill-cover", "0.5"]),
    ({"piers": "2,4,2", "fill_cover": 0.5, "fill_passive": "30,0.33"},
     ["--piers", "2,4,2", "--fill-cover", "0.5", "--fill-passive", "30,0.33"]),
    ({"epsilon": 0.1, "seed": 3}, ["--epsilon", "0.1", "--seed", "3"]),
], ids=["thickness", "pointed", "piers-fill", "passive-fill", "irregular"])
def test_structure_has_the_load_multipliers_of_archquake_limit(spec, argv):
    _, structure = structure_from_spec(spec)
    k_l, k_r = (r.load_multiplier for r in both_directions(structure))
    printed = cli_json("limit", *argv)
    assert (k_l, k_r) == pytest.approx((printed["k_l"], printed["k_r"]), rel=1e-12)


@pytest.mark.parametrize("spec, argv", [
    ({"thickness": -1}, ["--thickness", "-1"]),
    ({"shape": "pointed", "span": 10}, ["--shape", "pointed", "--span", "10"]),
    ({"embrace": 400}, ["--embrace", "400"]),
    ({"piers": "2,x"}, ["--piers", "2,x"]),
    ({"fill_density": 1800}, ["--fill-density", "1800"]),
], ids=["thickness", "rise-missing", "embrace", "piers", "fill-without-cover"])
def test_bad_structure_gets_the_command_lines_message(spec, argv):
    with pytest.raises(ValueError) as refused:
        structure_from_spec(spec)
    assert str(refused.value) == fields_named(cli_error("limit", *argv))
    assert "--" not in str(refused.value)


def test_structure_limits_and_unknown_fields():
    with pytest.raises(ValueError, match=rf"^voussoirs must be at most {LIMITS['blocks']}"):
        structure_from_spec({"voussoirs": LIMITS["blocks"] + 1})
    with pytest.raises(ValueError, match=r"unknown structure field\(s\) \['wall'\]"):
        structure_from_spec({"wall": 1})
    with pytest.raises(ValueError, match="the structure has 211 blocks"):
        structure_from_spec({"voussoirs": 195, "piers": "2,4,8"})


def test_geometry_file_message_names_the_file_as_given(tmp_path):
    uploads = Uploads(tmp_path)
    entry = uploads.save("geometry", "C:\\survey\\bad.json", BAD_GEOMETRY.encode())
    assert entry["name"] == "bad.json" and str(tmp_path) in entry["path"]
    (tmp_path / "cwd").mkdir()
    (tmp_path / "cwd" / "bad.json").write_text(BAD_GEOMETRY)
    expected = cli_error("limit", "--geometry", "bad.json", cwd=tmp_path / "cwd")
    with pytest.raises(ValueError) as refused:
        structure_from_spec(uploads.resolve({"geometry": entry["token"]}, "geometry",
                                            "geometry"))
    assert str(refused.value) == expected
    assert expected.startswith("geometry file 'bad.json': ")


def test_uploads_refuse_foreign_tokens_and_keep_a_bounded_number(tmp_path):
    uploads = Uploads(tmp_path, keep=2)
    first = uploads.save("record", "a.csv", b"0,0\n1,0.1\n")
    for name in ("b.csv", "c.csv"):
        uploads.save("record", name, b"0,0\n1,0.1\n")
    assert len(list(tmp_path.iterdir())) == 2
    with pytest.raises(ValueError, match="no longer kept"):
        uploads.file(first["token"], "record")
    with pytest.raises(ValueError, match="not the token of an uploaded file"):
        uploads.file("../../etc/passwd", "record")
    with pytest.raises(ValueError, match="a geometry file is one of .json"):
        uploads.save("geometry", "arch.py", b"print(1)")


def test_pulse_is_the_command_lines_pulse():
    from archquake.cli import build_parser
    from archquake.cli.options import motion_from_args

    spec = {"motion": "harmonic", "amplitude": -0.4, "duration": 0.5, "params": {"cycles": 2},
            "reverse": True}
    args = build_parser(["simulate"]).parse_args(
        ["simulate", "--motion", "harmonic", "--amplitude=-0.4", "--duration", "0.5",
         "--param", "cycles=2", "--reverse"])
    expected = motion_from_args(args)
    motion = motion_from_spec(spec)
    t = np.linspace(0, 1.2, 97)
    assert np.array_equal(motion.acceleration(t), expected.acceleration(t))
    assert motion.duration == expected.duration == pytest.approx(1.0)


def test_bad_motion_gets_the_command_lines_message_and_the_pages_limits():
    with pytest.raises(ValueError) as refused:
        motion_from_spec({"motion": "harmonic", "params": {"n": 2}})
    assert str(refused.value) == fields_named(cli_error("simulate", "--motion", "harmonic",
                                                        "--param", "n=2"))
    with pytest.raises(ValueError, match="^amplitude must be within"):
        motion_from_spec({"amplitude": 50})
    with pytest.raises(ValueError, match="the ground motion lasts 200 s"):
        motion_from_spec({"motion": "harmonic", "duration": 1, "cycles": 200})


def test_record_is_read_as_the_command_line_reads_it(tmp_path, data_dir):
    from archquake.ground_motion import read_record

    uploads = Uploads(tmp_path)
    entry = uploads.save("record", "decaying_sine.AT2",
                         (data_dir / "decaying_sine.AT2").read_bytes())
    spec = uploads.resolve({"record": entry["token"], "scale_to": 0.3}, "record", "record")
    motion = motion_from_spec(spec)
    expected = read_record(data_dir / "decaying_sine.AT2", scale_to=0.3)
    assert np.array_equal(motion.values, expected.values)
    assert json.dumps(spec["record"]["name"]) == '"decaying_sine.AT2"'
