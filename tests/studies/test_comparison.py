"""``archquake compare`` and :func:`archquake.studies.comparison.compare_models`: the two models'
own failure curves side by side (the agreement for long pulses is checked in
rigid_blocks/test_rigid_blocks_arch.py::test_long_pulse_failure_agrees_with_four_link_model)."""

import json
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from archquake import FourLinkModel  # noqa: E402
from archquake.cli import main  # noqa: E402
from archquake.plotting import plot_model_comparison, plot_model_differences  # noqa: E402
from archquake.rigid_blocks import (
    BlockSettings,  # noqa: E402
    RigidBlockModel,  # noqa: E402
)
from archquake.studies.comparison import compare_models  # noqa: E402
from archquake.studies.failure_domain import domain_of  # noqa: E402

DURATIONS = (0.3, 0.6)
GRID = np.round(np.arange(0.3, 1.71, 0.1), 10)
RESOLUTION = 0.01


@pytest.fixture(scope="module")
def comparison(nominal):
    return compare_models(nominal, DURATIONS, amplitudes_g=GRID, resolution_g=RESOLUTION)


def test_values_are_each_models_own_failure_curve(nominal, comparison):
    """The four-link columns are FourLinkModel.failure_domain with each restitution model, the
    rigid-block column is the rigid-block model's failure domain: the same search, the same scan
    and resolution (its default strategy and the exhaustive grid give the same slices here)."""
    rigid = domain_of(RigidBlockModel(nominal), DURATIONS, GRID, resolution_g=RESOLUTION,
                      extend_to_g=None, search="exhaustive")
    assert comparison.rigid_block.slices == rigid.slices
    dynamics = FourLinkModel.from_arch(nominal)
    assert list(comparison.four_link) == ["computed", "link", "paper", "measured"]
    for model, domain in comparison.four_link.items():
        direct = domain_of(dynamics.with_restitution(model),
            DURATIONS, GRID, resolution_g=RESOLUTION, extend_to_g=None)
        assert domain.slices == direct.slices, model
        assert domain.restitution == direct.restitution
    rows = comparison.to_list()
    for i, row in enumerate(rows):
        assert row["duration"] == DURATIONS[i]
        assert row["rigid_block"] == rigid.failure_accelerations_g[i]
        assert row["recovery_above"]["rigid_block"] == [list(b) for b in
                                                       rigid.slices[i].recovery_above_g]
    fa = comparison.failure_accelerations_g()
    np.testing.assert_array_equal(comparison.relative_differences()["paper"],
                                  fa["paper"] / fa["rigid_block"] - 1.0)


def test_cli_json_contract(capsys, comparison):
    """``--json``: a list of {"duration", "rigid_block", "four_link": {"computed", "link",
    "paper", ...}} in g, the values of compare_models."""
    code = main(["compare", "--durations", ",".join(map(str, DURATIONS)), "--amplitudes",
                 "0.3:1.7:0.1", "--resolution", str(RESOLUTION), "--json", "--no-progress"])
    assert code == 0
    rows = json.loads(capsys.readouterr().out)
    assert isinstance(rows, list) and len(rows) == len(DURATIONS)
    for row, expected in zip(rows, comparison.to_list(), strict=True):
        assert {"duration", "rigid_block", "four_link"} <= set(row)
        assert {"computed", "link", "paper"} <= set(row["four_link"])
        # beyond the agreement band: |a_four_link / a_rigid_block - 1| > 0.05, from the values
        assert row.pop("agreement_band") == 0.05
        beyond = row.pop("beyond_band")
        assert beyond == {name: abs(a / row["rigid_block"] - 1) > 0.05
                          for name, a in row["four_link"].items()
                          if a is not None and row["rigid_block"] is not None
                          and "failure_undecided_from" not in row}
        assert row == json.loads(json.dumps(expected))
        # accelerations in g: above the activation k = 0.370 and within the scan
        for value in [row["rigid_block"], *row["four_link"].values()]:
            assert value is None or 0.37 < value <= 1.7


def test_cli_text_names_both_models(capsys):
    assert main(["compare", "--durations", "0.7", "--amplitudes", "0.3:0.6:0.1",
                 "--resolution", "0.02", "--no-progress"]) == 0
    out = capsys.readouterr().out
    assert "rigid blocks" in out and "paper 0.875" in out and "measured 0.748" in out


def test_cli_plot(tmp_path, capsys):
    path = tmp_path / "compare.png"
    assert main(["compare", "--durations", "0.7", "--amplitudes", "0.3:0.6:0.1",
                 "--resolution", "0.02", "--no-progress", "--plot", str(path)]) == 0
    assert path.stat().st_size > 10_000


def test_plots_draw_every_model(comparison):
    ax = plot_model_comparison(comparison)
    labels = [line.get_label() for line in ax.get_lines()]
    assert labels[0] == "rigid-block model"
    for model, domain in comparison.four_link.items():
        label = next(lb for lb in labels if f"({model})" in lb)
        np.testing.assert_allclose(
            ax.get_lines()[labels.index(label)].get_ydata(), domain.failure_accelerations_g)
    plt.close(ax.figure)
    ax = plot_model_differences(comparison)
    lines = {line.get_label().split(",")[0]: line for line in ax.get_lines()}
    np.testing.assert_allclose(lines["paper"].get_ydata(),
                               100 * comparison.relative_differences()["paper"])
    plt.close(ax.figure)


def test_measured_restitution_follows_the_friction_of_the_comparison(nominal):
    """With a friction low enough for the joints to slide at the impact, the 'measured' c_v is
    measured with that friction."""
    settings = BlockSettings(friction=0.3)  # the lowest friction it stands with is 0.206
    c = compare_models(nominal, (0.7,), amplitudes_g=(0.3, 0.5), resolution_g=0.05,
                       restitutions=("measured",), settings=settings)
    from archquake.fourlink.impact import measured_restitution

    mech_l, mech_r = FourLinkModel.from_arch(nominal).mechanisms
    assert c.restitution["measured"][0] == pytest.approx(
        measured_restitution(mech_l, mech_r, settings), rel=1e-12)
    assert c.restitution["measured"][0] > 0.755  # 0.759, vs 0.748 at mu = 0.8


def test_precomputed_rigid_block_curve_is_checked(nominal, comparison):
    again = compare_models(nominal, DURATIONS, amplitudes_g=GRID, resolution_g=RESOLUTION,
                           rigid_block=comparison.rigid_block, restitutions=("paper",))
    assert again.rigid_block is comparison.rigid_block
    assert again.four_link["paper"].slices == comparison.four_link["paper"].slices
    with pytest.raises(ValueError, match="rigid_block must be the failure curve"):
        compare_models(nominal, DURATIONS, amplitudes_g=GRID, resolution_g=2 * RESOLUTION,
                       rigid_block=comparison.rigid_block)


@pytest.mark.parametrize("kwargs, match", [
    ({"restitutions": ("bogus",)}, "restitution must be one of"),
    ({"restitutions": ()}, "at least one"),
    ({"resolution_g": 0.0}, "resolution_g"),
    ({"amplitudes_g": (0.5, 0.4)}, "increasing"),
    ({"direction": "x"}, "direction"),
    ({"durations": (0.0,)}, "durations"),
])
def test_bad_input_is_a_value_error(nominal, kwargs, match):
    with pytest.raises(ValueError, match=match):
        compare_models(nominal, **{"durations": (0.5,), **kwargs})


@pytest.mark.parametrize("argv, match", [
    (["--resolution", "0"], "--resolution"),
    (["--workers", "0"], "--workers"),
    (["--friction", "-1"], "--friction"),
    (["--time-step", "0"], "--time-step"),
    (["--durations", "0,0.5"], "--durations"),
    (["--amplitudes", "0.5"], "--amplitudes"),
    (["--plot", "figure.txt"], "cannot write the figure"),
])
def test_cli_bad_input_exits_2(capsys, argv, match):
    assert main(["compare", "--no-progress", *argv]) == 2
    err = capsys.readouterr().err
    assert err.startswith("archquake: error:") and match in err


def test_recovery_bands_of_a_slice_are_above_the_failure(comparison):
    for domain in [comparison.rigid_block, *comparison.four_link.values()]:
        for s in domain.slices:
            failure = s.failure_acceleration_g
            for lo, hi in s.recovery_above_g:
                assert not math.isnan(failure) and failure < lo < hi
