"""The front door: FourLinkModel from an arch to its dynamics, and one default per choice.

The command line and the Python API run "the same" analysis with the same defaults; each check
below runs both and compares their answers (the physics of each is checked elsewhere against
the paper and independent methods)."""

import json

import pytest

from archquake import GRAVITY, FourLinkModel, Status, oppenheim, oppenheim_pulse
from archquake.cli import main
from archquake.fourlink.impact import restitution
from archquake.fourlink.mechanism import mechanisms
from archquake.limit_analysis import both_directions
from archquake.studies.failure_domain import domain_of


def test_quick_start_reproduces_the_paper(paper):
    """The README's quick start: Fig. 15 at t_p = 0.27 s (collapse in the second half cycle)
    and point Q of Fig. 16 (0.49 g), with the paper's c_v."""
    dynamics = FourLinkModel.from_arch(oppenheim(), restitution="paper")
    history = dynamics.simulate(oppenheim_pulse(-GRAVITY, 0.27))
    assert history.outcome.status is Status.COLLAPSE and history.outcome.half_cycle == 2
    assert dynamics.outcome(oppenheim_pulse(-GRAVITY, 0.27)).half_cycle == 2
    q = domain_of(dynamics, [0.4]).slices[0].failure_acceleration_g
    assert q == pytest.approx(paper["dynamics"]["NA"]["failure_acceleration_tp040"], abs=0.01)


def test_arch_dynamics_holds_the_chain_built_by_the_plain_functions():
    arch = oppenheim()
    dynamics = FourLinkModel.from_arch(arch)
    la = both_directions(arch)
    assert dynamics.load_multipliers == tuple(x.load_multiplier for x in la)
    pair = mechanisms(arch)
    assert [m.theta_u for m in dynamics.mechanisms] == [m.theta_u for m in pair]
    assert dynamics.restitution == restitution("computed", *pair)  # the default model
    assert dynamics.tables[0].theta_u == pair[0].theta_u


def test_nominal_restitution_takes_the_nominal_arch(nominal):
    from archquake import irregular_arch

    rough = irregular_arch(nominal, 0.1, rng=4)
    nominal_dynamics = FourLinkModel.from_arch(nominal)
    for given in (nominal, nominal_dynamics):
        assert (FourLinkModel.from_arch(rough, "nominal", given).restitution
                == nominal_dynamics.restitution)
    with pytest.raises(ValueError, match="restitution must be one of"):
        FourLinkModel.from_arch(nominal, "bouncy")
    with pytest.raises(ValueError, match="arch must be a CircularArch"):
        FourLinkModel.from_arch("Oppenheim")


def test_domain_command_and_python_agree_with_their_defaults(capsys):
    assert main(["domain", "--durations", "0.3,0.6", "--json"]) == 0
    cli = json.loads(capsys.readouterr().out)
    for row in cli:  # the check against the rigid blocks: tests/studies/test_agreement_probe.py
        assert row.pop("model_check")["skipped"] is False
    python = domain_of(FourLinkModel.from_arch(oppenheim()), [0.3, 0.6]).to_list()
    assert cli == json.loads(json.dumps(python))


def test_simulate_command_and_python_agree_with_their_defaults(capsys):
    assert main(["simulate", "--json"]) == 0
    cli = json.loads(capsys.readouterr().out)
    outcome = FourLinkModel.from_arch(oppenheim()).simulate(oppenheim_pulse(-GRAVITY, 0.27)).outcome
    assert (cli["outcome"], cli["half_cycle"]) == (outcome.status.label, outcome.half_cycle)
    assert cli["max_phi"] == outcome.max_phi


def test_fragility_command_defaults_are_the_settings_defaults(monkeypatch, tmp_path):
    from archquake.execution import default_backend
    from archquake.studies import fragility

    seen = {}

    def capture(settings, out_dir, **options):
        seen["settings"], seen["options"] = settings, options
        raise SystemExit(0)

    monkeypatch.setattr(fragility, "run_fragility", capture)
    with pytest.raises(SystemExit):
        main(["fragility", "--out", str(tmp_path / "study")])
    assert seen["settings"] == fragility.FragilitySettings()
    assert default_backend(None, seen["options"]["workers"], seen["options"]["scheduler"]) \
        == default_backend()


def test_another_restitution_shares_the_tables():
    dynamics = FourLinkModel.from_arch(oppenheim())
    link = dynamics.with_restitution("link")
    assert link.tables is dynamics.tables and link.mechanisms is dynamics.mechanisms
    assert link.restitution == FourLinkModel.from_arch(oppenheim(), "link").restitution
    assert link.restitution_model == "link" and dynamics.restitution_model == "computed"
    assert dynamics.with_restitution(0.5).restitution == (0.5, 0.5)
