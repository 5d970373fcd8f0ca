"""The fragility study of a bridge (``archquake fragility --model rigid-blocks --spans N``):
irregular bridges, one irregular arch a span, analysed by the rigid blocks. Checked against
independent values: each member's limit analysis (the blocks rest below its k and move above it
under a pulse long enough to open a mechanism), the members ``limit --samples`` draws, and the
members whose piers cannot seat the draws."""

import json

import numpy as np
import pandas as pd
import pytest

from archquake.cli import main
from archquake.errors import UnseatedError
from archquake.geometry.spec import StructureSpec
from archquake.limit_analysis import assembly_limit
from archquake.studies.arch_sample import BridgeSample
from archquake.studies.fragility import FragilitySettings, run_fragility

BRIDGE = ["--spans", "2", "--piers", "3,6"]
SEED = 3  # on 3 m piers, member 2 of the 4 of seed 3 cannot be seated: drawn and left out


def _settings(**kw):
    return FragilitySettings(description=StructureSpec(spans=2, piers="3,6"), seed=SEED,
                             sample_size=4, durations=(0.4,),
                             amplitudes_g=tuple(np.round(np.arange(0.10, 0.261, 0.02), 2)),
                             limit_sample_size=4, model="rigid-blocks", **kw)


@pytest.fixture(scope="module")
def study(tmp_path_factory):
    out = tmp_path_factory.mktemp("bridge_fragility")
    return run_fragility(_settings(search="exhaustive"), out, progress=False), out


def test_the_members_are_the_descriptions_sample_and_unseated_ones_are_left_out(study):
    result, _ = study
    members = list(StructureSpec(spans=2, piers="3,6", epsilon=0.1, seed=SEED).sample(4))
    unseated = {i for i, m in enumerate(members) if isinstance(m, UnseatedError)}
    assert unseated == {2}  # the setting of the test: one of each kind
    assert result.summary()["arches"]["excluded"] == {"not seated": [2]}
    sample = BridgeSample(StructureSpec(spans=2, piers="3,6"), 0.1, SEED)
    for i, member in enumerate(members):
        if i not in unseated:
            assert sample.arch(i).to_dict() == member.to_dict()


def test_the_blocks_rest_below_each_members_k_and_move_above_it(study):
    # the independent value: each member's own linear program (associative, nothing slides at
    # these piers), per direction; Oppenheim's pulse of 0.4 s holds a g long enough for a
    # mechanism to open above k and never below it
    result, _ = study
    members = list(StructureSpec(spans=2, piers="3,6", epsilon=0.1, seed=SEED).sample(4))
    table = result.table
    checked = 0
    for i, member in enumerate(members):
        rows = table[table["arch"] == i]
        if isinstance(member, UnseatedError):
            assert (rows["status"] == -2).all() and rows["k_l"].isna().all()
            continue
        for direction, toward in (("l", "+x"), ("r", "-x")):
            k = assembly_limit(member, toward).load_multiplier
            line = rows[rows["direction"] == direction]
            assert line[f"k_{direction}"].to_numpy() == pytest.approx(k, rel=1e-12)
            a, status = line["amplitude_g"].to_numpy(), line["status"].to_numpy()
            assert line["analysed"].all()
            far = np.abs(a - k) > 2e-3
            assert np.all((status[far] == 0) == (a[far] < k)), (i, direction, k, a, status)
            checked += int(far.sum())
    assert checked >= 40


def test_the_limit_sample_is_the_limit_commands(study, capsys):
    # the same members by the command's own path (governing_multiplier, member by member)
    result, out = study
    limit = pd.read_parquet(out / "limit_sample" / "results.parquet")
    assert main(["limit", *BRIDGE, "--epsilon", "0.1", "--seed", str(SEED), "--samples", "4",
                 "--json"]) == 0
    cli = json.loads(capsys.readouterr().out)
    k = np.fmin(limit["k_l"].to_numpy(), limit["k_r"].to_numpy())
    assert list(limit["excluded"]) == ["", "", "not seated", ""]
    assert cli["k"][2] is None and [r["member"] for r in cli["refused"]] == [2]
    assert [cli["k"][i] for i in (0, 1, 3)] == pytest.approx(k[[0, 1, 3]], rel=1e-12)
    assert result.nominal_load_multiplier == pytest.approx(cli["k_nominal"], rel=1e-12)


def test_the_screened_search_of_bridges_is_the_exhaustive_grids(study, tmp_path):
    # no four-link screen: its coarse scan alone, which infers only what its safeguard allows
    exhaustive, _ = study
    screened = run_fragility(_settings(), tmp_path, progress=False)
    assert screened.settings.search == "screened"
    columns = ["arch", "direction", "duration", "amplitude_g", "status"]
    pd.testing.assert_frame_equal(screened.table[columns], exhaustive.table[columns])
    assert screened.table["analysed"].sum() < exhaustive.table["analysed"].sum()


def test_settings_of_a_bridge_read_back_and_refuse_the_four_link_model():
    settings = _settings()
    again = FragilitySettings.from_dict(json.loads(json.dumps(settings.to_dict())))
    assert again == settings and again.description == settings.description
    assert "nominal" not in settings.to_dict()  # the description builds it
    with pytest.raises(ValueError, match="no four-link model"):
        FragilitySettings(description=StructureSpec(spans=2, piers="3,6"))
    with pytest.raises(ValueError, match="draws no irregular arch of its own"):
        FragilitySettings(description=StructureSpec(spans=2, piers="3,6", epsilon=0.1),
                          model="rigid-blocks")
    with pytest.raises(ValueError, match="several spans of one arch"):
        FragilitySettings(description=StructureSpec(rings=2), model="rigid-blocks")


def test_the_command(tmp_path, capsys):
    argv = [*BRIDGE, "--seed", str(SEED), "--samples", "2", "--durations", "0.4",
            "--amplitudes", "0.1,0.2", "--limit-samples", "2", "--no-progress", "--out"]
    assert main(["fragility", "--model", "rigid-blocks", *argv, str(tmp_path / "a")]) == 0
    text = capsys.readouterr().out
    assert "h = 2 irregular bridges (epsilon = 0.1, seed 3)" in text
    assert "nominal bridge: k = " in text
    assert main(["fragility", "--model", "four-link", *argv, str(tmp_path / "b")]) == 2
    assert "no four-link model: leave --model out" in capsys.readouterr().err
    assert main(["fragility", *argv, str(tmp_path / "c")]) == 0  # without --model: the blocks
    captured = capsys.readouterr()
    assert "the rigid-block model analyses it" in captured.err
    assert "h = 2 irregular bridges" in captured.out
    assert main(["fragility", "--rings", "2", "--out", str(tmp_path / "d")]) == 2
    assert "limit, rigid-blocks, domain and assess analyse" in capsys.readouterr().err


def test_a_bridge_under_fill(tmp_path):
    # the fill rides on its blocks in both models: the nominal k is the filled bridge's limit
    # analysis, and every member rests below its own k
    description = StructureSpec(spans=2, piers="3.2,6", fill_cover=0.5)
    settings = FragilitySettings(description=description, sample_size=1, durations=(0.4,),
                                 amplitudes_g=(0.05, 0.1), limit_sample_size=1,
                                 model="rigid-blocks")
    result = run_fragility(settings, tmp_path, progress=False)
    nominal = description.nominal()
    k = min(assembly_limit(nominal, d).load_multiplier for d in ("+x", "-x"))
    assert result.nominal_load_multiplier == pytest.approx(k, rel=1e-12)
    rows = result.table
    assert (rows["status"] == 0).all() and (rows["amplitude_g"] < rows[["k_l", "k_r"]].min(
        axis=1)).all()


def test_a_study_of_bridges_is_estimated_by_its_blocks():
    # a step of the rigid blocks costs time linear in the blocks: the study of 20 bridges of
    # three spans (81 s in one process) is given the workers asked for, not run here as an
    # arch's study of its size would be
    from archquake.studies.fragility import _serial_seconds
    from archquake.studies.strategies import workers_that_pay

    grid = dict(sample_size=20, durations=(0.5,), limit_sample_size=200,
                amplitudes_g=tuple(np.round(np.arange(0.10, 0.401, 0.01), 2)))
    bridges = FragilitySettings(description=StructureSpec(spans=3, piers="3.2,6"),
                                model="rigid-blocks", **grid)
    arches = FragilitySettings(model="rigid-blocks", **grid)
    assert workers_that_pay(_serial_seconds(arches), 2) is None  # about 4 s: here
    assert workers_that_pay(_serial_seconds(bridges), 2) == 2
    assert _serial_seconds(bridges) > 20.0


def test_the_text_names_arches_for_a_study_of_arches(tmp_path, capsys):
    assert main(["fragility", "--samples", "2", "--durations", "0.4", "--amplitudes", "0.2,0.3",
                 "--limit-samples", "2", "--no-progress", "--no-model-check", "--out",
                 str(tmp_path)]) == 0
    text = capsys.readouterr().out
    assert "h = 2 irregular arches" in text and "nominal arch: k = " in text
    assert "over s = 2 arches" in text and "of the nominal arch's failure domains" in text


def test_a_bridge_its_piers_cannot_carry_is_refused_naming_the_option(tmp_path, capsys):
    assert main(["fragility", "--model", "rigid-blocks", *BRIDGE, "--pier-middle", "1,6",
                 "--out", str(tmp_path)]) == 2
    assert "--pier-middle: intermediate pier width must be at least 2.94236 m" in \
        capsys.readouterr().err
    assert not any(tmp_path.iterdir())  # refused before the study starts


def test_the_figures_name_the_bridge(study):
    import matplotlib

    matplotlib.use("Agg")
    from archquake.plotting import plot_fragility_curve, plot_fragility_surface

    result, _ = study
    labels = plot_fragility_curve(result, 0.4).get_legend_handles_labels()[1]
    assert any(label.startswith("nominal bridge, limit analysis k = ") for label in labels)
    assert not any("arch" in label for label in labels)
    labels = plot_fragility_surface(result).get_legend_handles_labels()[1]
    assert all("nominal bridge" in label for label in labels)
