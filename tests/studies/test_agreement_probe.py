"""The check of the four-link model's failure accelerations against the rigid-block model
(:func:`archquake.studies.comparison.agreement_probe`) and the commands that print it.

Oppenheim's arch on piers 3 m wide and 6 m high is the structure where the models disagree: the
four-link model keeps the four hinges of the limit analysis, the rigid blocks (within 0.4 % of
LMGC90 on piers) do not. Oppenheim's bare arch under a long pulse (t_p = 1 s) is where they agree
(the arch falls in its first swing). The probe's numbers are compared with direct
:func:`~archquake.studies.failure_domain.domain_of` calls of each model, built here.
"""

import json

import numpy as np
import pytest

from archquake import FourLinkModel, oppenheim
from archquake.cli import main
from archquake.defaults import AGREEMENT_BAND
from archquake.geometry import arch_on_piers
from archquake.rigid_blocks import BlockSettings, RigidBlockModel
from archquake.studies.comparison import (
    PROBE_RESOLUTION_G,
    agreement_probe,
    probe_durations,
    probe_grid,
)
from archquake.studies.failure_domain import domain_of

PIERS = ("--piers", "3,6")
SHORT_SCAN = ("--amplitudes", "0.2:0.6:0.1")


@pytest.fixture(scope="module")
def on_piers():
    return arch_on_piers(oppenheim(), 3.0, 6.0, 2)


@pytest.fixture(scope="module")
def direct(on_piers):
    """Both models' failure accelerations at t_p = 0.5 s by their own domain_of calls."""
    fl = FourLinkModel.from_arch(on_piers)
    grid = probe_grid(fl.load_multiplier)
    four = domain_of(fl, [0.5], grid, resolution_g=PROBE_RESOLUTION_G, extend_to_g=None)
    blocks = domain_of(RigidBlockModel(on_piers, BlockSettings()), [0.5], grid,
                       resolution_g=PROBE_RESOLUTION_G, extend_to_g=None, search="bisection")
    return four.failure_accelerations_g[0], blocks.failure_accelerations_g[0]


def test_probe_durations_takes_the_ends_and_the_middle():
    # ten durations 0.1 .. 1.0: ranks linspace(0, 9, 3) = 0, 4.5, 9, rounded half to even
    # 0, 4, 9 -> 0.1, 0.5, 1.0 s; three or fewer are kept as given, sorted
    ten = [round(0.1 * i, 10) for i in range(1, 11)]
    assert probe_durations(ten) == (0.1, 0.5, 1.0)
    assert probe_durations([0.6, 0.3]) == (0.3, 0.6)
    with pytest.raises(ValueError, match="count"):
        probe_durations(ten, 1)


def test_probe_on_piers_equals_each_model_alone_and_disagrees(on_piers, direct):
    probe = agreement_probe(on_piers, [0.5])
    (row,) = probe.rows
    four, blocks = direct
    assert row.four_link == four and row.rigid_block == blocks
    # the four-link model on these piers: 0.376 g to 0.001 g (archquake domain --piers 3,6
    # --durations 0.5), the rigid blocks about a quarter g: the difference is far beyond 5 %
    assert abs(row.four_link - 0.376) <= PROBE_RESOLUTION_G
    assert row.difference == pytest.approx(four / blocks - 1.0)
    assert row.difference > AGREEMENT_BAND and row.beyond and probe.disagrees
    assert not row.undecided


def test_domain_on_piers_flags_the_four_link_value(capsys, direct):
    assert main(["domain", *PIERS, "--durations", "0.5", *SHORT_SCAN]) == 0
    out = capsys.readouterr().out
    four, blocks = direct
    first = out.splitlines()[0]
    assert first.startswith("warning: the rigid-block model (trusted; agrees with LMGC90 to "
                            "0.4 % on piers)")
    assert f"gives {blocks:.2f} g at t_p = 0.5 s" in first
    assert f"off by {100 * (four / blocks - 1):+.0f} %" in first
    table_row = next(line for line in out.splitlines() if line.lstrip().startswith("0.500"))
    assert f"[rigid blocks (trusted): {blocks:.2f} g" in table_row


def test_domain_json_carries_the_probe(capsys, direct):
    assert main(["domain", *PIERS, "--durations", "0.5", *SHORT_SCAN, "--json"]) == 0
    (row,) = json.loads(capsys.readouterr().out)
    check = row["model_check"]
    four, blocks = direct
    assert check["disagrees"] and check["band"] == AGREEMENT_BAND
    assert check["probed"]["four_link"] == four and check["probed"]["rigid_block"] == blocks
    assert check["probed"]["beyond_band"]


def test_bare_arch_under_a_long_pulse_agrees(capsys):
    # Oppenheim's arch at t_p = 1 s: both models collapse in the first swing, within 5 %
    assert main(["domain", "--durations", "1", "--amplitudes", "0.3:0.6:0.1"]) == 0
    out = capsys.readouterr().out
    assert "off by" not in out and "trusted" not in out
    assert out.splitlines()[0] == ("warning: four-link values checked against the rigid-block "
                                   "model at t_p = 1 s: within 5 %")


def test_no_model_check_says_it_skipped(capsys):
    assert main(["domain", *PIERS, "--durations", "0.5", *SHORT_SCAN,
                 "--no-model-check"]) == 0
    out = capsys.readouterr().out
    assert "not checked against the rigid-block model (--no-model-check)" in out
    assert "off by" not in out
    assert main(["domain", *PIERS, "--durations", "0.5", *SHORT_SCAN, "--no-model-check",
                 "--json"]) == 0
    (row,) = json.loads(capsys.readouterr().out)
    assert row["model_check"] == {"skipped": True}


def test_an_undecided_check_is_said(capsys):
    # t_p = 0.01 s: the rigid blocks' 1 ms step cannot resolve the pulse (1/20 of it is 0.5 ms)
    assert main(["domain", "--durations", "0.01", "--amplitudes", "0.3:0.5:0.1"]) == 0
    assert "warning: model check undecided" in capsys.readouterr().out


def test_compare_marks_the_disagreement(capsys, direct):
    argv = ["compare", *PIERS, "--durations", "0.5", *SHORT_SCAN, "--resolution", "0.01",
            "--no-progress"]
    assert main(argv) == 0
    out = capsys.readouterr().out
    four, blocks = direct
    assert f"({100 * (four / blocks - 1):+4.0f} %)!" in out
    assert "!: the four-link value is off by more than 5 %" in out
    assert main([*argv, "--json"]) == 0
    (row,) = json.loads(capsys.readouterr().out)
    assert row["beyond_band"]["computed"] and row["agreement_band"] == AGREEMENT_BAND


def test_fragility_json_carries_the_nominal_arch_probe(tmp_path, capsys, direct):
    assert main(["fragility", *PIERS, "--samples", "1", "--durations", "0.5", "--amplitudes",
                 "0.3,0.4", "--limit-samples", "2", "--out", str(tmp_path / "f"),
                 "--no-progress", "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    (row,) = summary["model_check"]["probe"]["rows"]
    four, blocks = direct
    assert row["four_link"] == four and row["rigid_block"] == blocks and row["beyond_band"]
    assert "seconds" not in summary["model_check"]["probe"]  # a resumed study's is the same
    assert np.isclose(summary["model_check"]["probe"]["band"], AGREEMENT_BAND)


def test_bare_arch_under_a_short_pulse_is_flagged_with_its_own_reference():
    # Oppenheim's arch at t_p = 0.25 s collapses only after impacts, where the four-link model
    # keeps its mechanism: the models disagree (compare_models' docstring); the rigid blocks'
    # reference on fixed supports is 1 % from LMGC90
    arch = oppenheim()
    probe = agreement_probe(arch, [0.25])
    (row,) = probe.rows
    fl = FourLinkModel.from_arch(arch)
    grid = probe_grid(fl.load_multiplier)
    blocks = domain_of(RigidBlockModel(arch, BlockSettings()), [0.25], grid,
                       resolution_g=PROBE_RESOLUTION_G, extend_to_g=None, search="bisection")
    assert row.rigid_block == blocks.failure_accelerations_g[0]
    assert row.beyond and not probe.on_piers
    (message,) = probe.messages()
    assert "agrees with LMGC90 to 1 % on fixed supports" in message
