"""The record-based study of a bridge (``archquake record-fragility --model rigid-blocks
--spans N``): irregular bridges, one irregular arch a span, under scaled records; its rows are
the rigid blocks of each member drawn by the description's own sample, under the scaled record."""

from pathlib import Path

import pytest

from archquake.cli import main
from archquake.errors import UnseatedError
from archquake.geometry.spec import StructureSpec
from archquake.ground_motion import RecordSuite
from archquake.rigid_blocks import RigidBlockModel
from archquake.studies.record_fragility import RecordFragilitySettings, run_record_fragility

SUITE = RecordSuite.from_stochastic(1, seed=4, significant_duration=2.0, duration=4.0)
BRIDGE = {"spans": 2, "piers": "3,6"}
SEED = 3  # member 2 of seed 3 cannot be seated on 3 m piers
RECORD = Path(__file__).parents[1] / "data" / "decaying_sine.csv"


@pytest.fixture(scope="module")
def study():
    settings = RecordFragilitySettings(suite=SUITE, levels=(0.1, 0.3, 0.5), sample_size=3,
                                       seed=SEED, model="rigid-blocks", bootstrap=10,
                                       description=StructureSpec(**BRIDGE))
    return run_record_fragility(settings, backend="serial", progress=False)


def test_rows_are_the_rigid_blocks_of_each_member_under_the_scaled_record(study):
    members = list(StructureSpec(**BRIDGE, epsilon=0.1, seed=SEED).sample(3))
    assert isinstance(members[2], UnseatedError)
    motion = SUITE.motions()[0]
    table = study.table
    assert set(table.loc[table["arch"] == 2, "excluded"]) == {"not seated"}
    nominal = StructureSpec(**BRIDGE).nominal()
    checked = 0
    for _, row in table[table["excluded"] == ""].iterrows():
        bridge = nominal if row["arch"] < 0 else members[int(row["arch"])]
        factor = row["polarity"] * row["scale_factor"]
        expected = RigidBlockModel(bridge).outcome(motion.scaled(factor)).status
        assert int(expected) == row["status"], row.to_dict()
        checked += 1
    assert checked == 3 * 3 * 2  # two members and the nominal bridge, 3 levels, 2 polarities
    assert study.summary()["settings"]["description"] == {"piers": [3.0, 6.0, 1], "spans": 2}


def test_settings_read_back_and_the_command(tmp_path, capsys):
    settings = RecordFragilitySettings(suite=SUITE, levels=(0.1, 0.3), sample_size=1,
                                       model="rigid-blocks",
                                       description=StructureSpec(**BRIDGE))
    assert RecordFragilitySettings.from_dict(settings.to_dict()) == settings
    with pytest.raises(ValueError, match="no four-link model"):
        RecordFragilitySettings(suite=SUITE, levels=(0.1,), description=StructureSpec(**BRIDGE))
    argv = ["record-fragility", "--spans", "2", "--piers", "3,6", "--records",
            str(RECORD), "--levels", "0.1,0.3", "--samples", "1", "--seed", "1", "--no-progress",
            "--out"]
    assert main([*argv[:1], "--model", "rigid-blocks", *argv[1:], str(tmp_path / "a")]) == 0
    text = capsys.readouterr().out
    assert "h = 1 irregular bridges (epsilon = 0.1, seed 1) and the nominal bridge" in text
    assert main([*argv[:1], "--model", "four-link", *argv[1:], str(tmp_path / "b")]) == 2
    assert "no four-link model: leave --model out" in capsys.readouterr().err


def test_the_nrml_file_names_bridges(tmp_path):
    # four short stochastic records collapse the bridges from about 2.5 g PGA: fits to export
    suite = RecordSuite.from_stochastic(4, seed=4, significant_duration=2.0, duration=4.0)
    settings = RecordFragilitySettings(suite=suite, levels=(2.0, 2.5, 3.0, 4.0),
                                       sample_size=1, seed=1, model="rigid-blocks", bootstrap=10,
                                       description=StructureSpec(**BRIDGE))
    result = run_record_fragility(settings, backend="serial", progress=False)
    assert result.lognormal is not None or result.nominal_lognormal is not None
    text = result.export_nrml(tmp_path / "bridges.xml").read_text()
    assert 'id="masonry-bridge' in text and "irregular bridges" in text
    assert "arch" not in text.replace("archquake", "")
