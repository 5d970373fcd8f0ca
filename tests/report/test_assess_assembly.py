"""``archquake assess`` of a block assembly (several spans, an arch of several rings): its
limit analysis, the rigid-block model's check of it and the code's linear check, each against
an independent value (the chain's own analysis, the single span on piers, the Circolare's
formulas)."""

import json
import math

import numpy as np
import pytest

from archquake.cli import main
from archquake.geometry.spec import StructureSpec
from archquake.limit_analysis import assembly_limit, limit_analysis
from archquake.reference_arches import oppenheim
from archquake.report.assess import AssessmentSettings, assess
from archquake.report.assess.assembly import LEFT_OUT, limit_part
from archquake.report.assess.assessment import choose_suite
from archquake.rigid_blocks import RigidBlockModel
from archquake.site.local_mechanism import (
    SiteAction,
    check_local_mechanism,
    participation,
)
from archquake.site.spectra import ec8_spectrum


def cli_json(*argv):
    """The ``--json`` output of ``archquake argv``, in this process."""
    import contextlib
    import io

    buffer = io.StringIO()
    with contextlib.redirect_stdout(buffer):
        assert main([*argv, "--json"]) == 0
    return json.loads(buffer.getvalue())


def _bridge():
    return StructureSpec(spans=3, piers="3,6").nominal()


@pytest.fixture(scope="module")
def bridge_report(tmp_path_factory):
    out = tmp_path_factory.mktemp("assess_spans") / "report"
    assert main(["assess", "--spans", "3", "--piers", "3,6", "--code", "ec8", "--agr", "0.2",
                 "--quick", "--out", str(out), "--no-progress"]) == 0
    return out, json.loads((out / "results.json").read_text())


@pytest.mark.parametrize("structure", [oppenheim(),
                                       StructureSpec(piers="1.5,4", fill_cover=0.5).nominal()],
                         ids=["Oppenheim", "on piers under fill"])
def test_an_assemblys_participation_is_the_chains(structure):
    """The equivalent oscillator (M*, e*) of the assembly program's collapse velocities equals
    that of the chain's limit analysis and virtual displacements, to round-off."""
    for chain, way in (("l", "+x"), ("r", "-x")):
        p_chain = participation(limit_analysis(structure, chain))
        p_assembly = participation(assembly_limit(structure, way))
        assert p_assembly.alpha0 == pytest.approx(p_chain.alpha0, rel=1e-12)
        assert p_assembly.participating_mass == pytest.approx(p_chain.participating_mass,
                                                              rel=1e-12)
        assert p_assembly.mass_fraction == pytest.approx(p_chain.mass_fraction, rel=1e-12)
        assert p_assembly.moving_weight == pytest.approx(p_chain.moving_weight, rel=1e-12)


def test_the_linear_check_of_an_assembly_follows_the_circolare():
    """a0* = alpha0 g / (e* FC) against a_g S / q, the nonlinear route declined by name."""
    structure = _bridge()
    action = SiteAction.of("SLV", ec8_spectrum(0.2, soil="B"))
    check = check_local_mechanism(structure, action, confidence_factor=1.35)
    assert not check.nonlinear and "not traced in its displaced configuration" in check.notes[0]
    for p, linear in zip(check.participations, check.linear, strict=True):
        assert 0.0 < p.mass_fraction <= 1.0
        assert linear.capacity == pytest.approx(p.alpha0 / (p.mass_fraction * 1.35),
                                                rel=1e-12)
        assert linear.demand == pytest.approx(action.spectrum.pga / 2.0, rel=1e-12)
        assert linear.passes == (linear.capacity >= linear.demand)


def test_the_end_span_fails_first_as_the_single_span_on_its_piers():
    """Toward +x the last span moves, toward -x the first, at the multiplier of one such arch
    on the same piers (the shared piers are as stiff as an end pier: within 1e-3)."""
    summary, _, governing = limit_part(_bridge(), 0.8)
    one = assembly_limit(StructureSpec(piers="3,6").nominal(), "+x", friction=0.8,
                         law="non-associative").load_multiplier
    by_way = {e["direction"]: e for e in summary["governing"]}
    assert by_way["+x"]["spans"] == [3] and by_way["-x"]["spans"] == [1]
    for r in governing:
        assert r.load_multiplier == pytest.approx(one, rel=1e-3)
    assert summary["k"] == min(r.load_multiplier for r in governing)


def test_the_report_of_three_spans(bridge_report):
    out, results = bridge_report
    text = (out / "report.md").read_text()
    k = results["limit"]["k"]
    assert results["limit"]["direction"] in ("+x", "-x")
    # the first screen says which span fails first, and how; the rigid blocks confirm k
    first = text.split("## 1.")[0]
    assert f"{k:.4f} g" in first and ("span 1:" in first or "span 3:" in first)
    act = results["rigid_blocks"]
    below, above = act["runs"]
    assert act["agrees"] and not below["moves"] and above["moves"]
    assert below["status"] == "rest" and above["status"] != "rest"
    assert below["max_opening_m"] < 1e-9 and above["max_opening_m"] > act["threshold_m"]
    assert below["acceleration_g"] == pytest.approx(0.9 * k)
    assert "The rigid-block model agrees" in first
    # the rigid blocks' failure domain under pulses: below k nothing moves, at any duration
    domain = results["domain"]
    assert domain["rows"] and (out / "fig2_failure_domain.png").is_file()
    for row in domain["rows"]:
        assert abs(row["moves_from_g"] - k) <= domain["resolution_g"]
        assert row["collapse_from_g"] > k and not row["undecided"]
    assert "## 3. Failure domain under pulses (rigid blocks)" in text
    # the site: the linear route and the dynamic route with the rigid blocks; no risk
    site = results["site"]
    assert site["check"]["linear"] and not site["check"]["nonlinear"]
    assert "skipped" in site["risk"]
    assert "CODE CHECK AT THE SITE" in first and "Dynamic route" in first
    dynamic = site["dynamic"]
    assert [v["model"] for v in dynamic["verdicts"]] == ["rigid-blocks"]
    assert len(dynamic["runs"]) == len(dynamic["selection"]["records"]) >= 3
    # rigid blocks cannot move while the ground's acceleration stays below k g (the limit
    # analysis), and must have passed it where they moved
    suite, _ = choose_suite(settings=AssessmentSettings.quick_settings())
    pga = dict(zip(suite.names, suite.intensities("pga"), strict=True))  # [g]
    for run in dynamic["runs"]:
        peak = run["factor"] * pga[run["record"]]
        if peak < k:
            assert run["status"] == "rest"
    statuses = {run["status"] for run in dynamic["runs"]}
    assert dynamic["verdict"]["verdict"] == ("fail" if "collapse" in statuses else
                                             "undecided" if "undecided" in statuses else "pass")
    assert "each run through the rigid-blocks model" in text
    # the record-based fragility: no record collapses the blocks at k g (they cannot move
    # below it), and the stripes' fit is the lognormal of the records' collapse PGAs, each
    # known to the grid's step (15 %): the geometric mean and log deviation of those PGAs
    rec = results["records"]
    assert rec["undecided"] == 0 and len(rec["records"]) == 3  # a quick assessment's
    capacity = np.array([r["collapse_pga_g"] for r in rec["records"]], dtype=float)
    step = math.log(rec["levels_g"][1] / rec["levels_g"][0])
    assert step == pytest.approx(math.log(30) / 24)
    assert np.all(capacity > k * (1 + 1e-9))
    fit = rec["lognormal"]
    assert abs(math.log(fit["median"]) - np.log(capacity).mean()) < step
    assert abs(fit["dispersion"] - np.log(capacity).std()) < step
    assert "## 3b. Record-based fragility (rigid blocks)" in text
    assert (out / "fig3_record_fragility.png").is_file()
    for item in LEFT_OUT:
        assert item in text
    # the irregular bridges: the members of `limit --samples` with the assessment's epsilon,
    # seed and friction, member by member (their k from another path of the limit analysis);
    # on piers 3 m wide some draws cannot be seated, and the report says so
    irregular = results["irregular"]
    assert irregular["size"] == 20 and irregular["epsilon"] == 0.1 and irregular["seed"] == 0
    limit = cli_json("limit", "--spans", "3", "--piers", "3,6", "--epsilon", "0.1",
                     "--samples", "20", "--friction", "0.8")
    assert [x is None for x in irregular["k"]] == [x is None for x in limit["k"]]
    assert irregular["refused"] and irregular["k_nominal"] == pytest.approx(k, rel=1e-12)
    assert [x for x in irregular["k"] if x is not None] == pytest.approx(
        [x for x in limit["k"] if x is not None], rel=1e-12)
    assert all(x < k for x in irregular["k"] if x is not None)
    assert "## 1b. Irregular bridges" in text and "WARNING: " in text
    assert (out / "fig1b_irregular_bridges.png").is_file()
    assert "irregular bridges around it (epsilon 0.1), 5 % start to collapse below" in first
    assert (out / "fig1_collapse.png").stat().st_size > 20_000
    assert results["command"]["regenerate"].endswith("--resume")


def test_the_rigid_block_model_of_an_assembly_has_its_load_multipliers():
    structure = _bridge()
    model = RigidBlockModel(structure)
    k = model.load_multipliers
    assert k == pytest.approx((assembly_limit(structure, "+x").load_multiplier,
                               assembly_limit(structure, "-x").load_multiplier), rel=1e-12)
    assert all(math.isfinite(v) and v > 0 for v in k)


@pytest.mark.parametrize(("argv", "message"), [
    (["--spans", "3", "--piers", "3,6", "--records", "x.AT2"], "--records: the assessment of a "
                                                                "block assembly"),
    (["--rings", "2", "--epsilon", "0.2"], "--epsilon: the assessment of a block assembly"),
    (["--rings", "2", "--sa-period", "0.5"], "--sa-period"),
    (["--spans", "3", "--piers", "3,6", "--knowledge-level", "LC2"],
     "the site's options need --site FILE or --code"),
    (["--rings", "0"], "--rings must be an integer >= 1, got 0"),
    (["--spans", "0"], "--spans must be an integer in [1, 100], got 0"),
    (["--spans", "2", "--piers", "3,6", "--fill-cover", "0.5", "--fill-passive", "30,0.33"],
     "--fill-passive: the fill's passive reaction is a limit-analysis model"),
])
def test_what_an_assemblys_assessment_refuses(argv, message, capsys, tmp_path):
    assert main(["assess", *argv, "--out", str(tmp_path / "x"), "--no-progress"]) == 2
    assert message in capsys.readouterr().err
    assert not (tmp_path / "x").exists()


def test_the_library_refuses_records_for_an_assembly(tmp_path):
    with pytest.raises(ValueError, match="runs no record study"):
        assess(_bridge(), suite="fema-p695-near-field-pulse", out_dir=tmp_path / "x",
               settings=AssessmentSettings.quick_settings())


def test_heyman_beside_the_friction_laws():
    """With friction 0.8 the two rings slide on each other before they hinge: the governing
    multiplier is below Heyman's (nothing slides), which is the one-ring arch's."""
    rings = StructureSpec(rings=2).nominal()
    summary, _, _ = limit_part(rings, 0.8)
    heyman = summary["heyman"]["+x"]
    assert heyman == pytest.approx(limit_analysis(oppenheim(), "l").load_multiplier, rel=1e-3)
    assert summary["k"] < heyman
    entry = summary["governing"][0]
    assert entry["law"] == "non-associative" and entry["ring_slides_m"] > 0
    assert np.isfinite(summary["k"])


def test_a_failure_domain_beyond_the_budget_is_skipped_with_its_estimate():
    """The rigid blocks' domain is estimated from the check's analyses before it runs: an
    assembly whose analysis takes 100 s is not scanned, and the report says how long it would
    take."""
    from archquake.report.assess.assembly import DOMAIN_ANALYSES, DOMAIN_BUDGET, domain_part

    settings = AssessmentSettings.quick_settings()
    structure = _bridge()
    summary, domain = domain_part(structure, 0.14, "+x", settings,
                                  {"runs": [{"seconds": 0.01}, {"seconds": 100.0}]})
    durations = len(settings.pulse_durations(structure))
    assert domain is None and summary["estimate_s"] == durations * DOMAIN_ANALYSES * 100.0
    assert summary["estimate_s"] > DOMAIN_BUDGET
    assert f"about {summary['estimate_s'] / 60:.0f} minutes" in summary["skipped"]


def test_ring_friction_keeps_the_other_interfaces_friction_of_the_command_line(tmp_path):
    """With --ring-friction the assembly gives its own friction (the other interfaces do not
    slide); assess's --friction is then the other interfaces', as for limit: the same k."""
    from archquake.limit_analysis import assembly_limits

    rings = StructureSpec(rings=2, ring_friction=0.6).nominal()
    summary, _, _ = limit_part(rings.with_friction({**rings.friction, "bed": 0.7,
                                                    "foundation": 0.7}), 0.8)
    expected = assembly_limits(rings, friction={"bed": 0.7, "foundation": 0.7})
    k = min(r.load_multiplier for laws in expected.values() for r in laws.values()
            if r.law == "non-associative")
    assert summary["k"] == pytest.approx(k, rel=1e-9)


def test_the_risk_of_an_assembly_is_cornells_closed_form():
    """The annual frequency of collapse from a record fragility (lognormal, median theta,
    dispersion beta) and a power-law hazard lambda(x) = k0 x^-kk: Cornell's closed form
    k0 theta^-kk exp(kk^2 beta^2 / 2) (Cornell et al. 2002, eq. 12). Without a hazard curve
    the risk is skipped with the reason."""
    from archquake.report.assess.assembly import assembly_risk
    from archquake.site.hazard import HazardCurve

    k0, kk, theta, beta = 1e-4, 2.0, 0.43, 0.2
    x = np.geomspace(1e-3, 100.0, 60)

    class Site:
        def hazard_curve(self, im):
            assert im == "PGA"
            return HazardCurve(x, k0 * x**-kk, im="PGA")

    risk = assembly_risk(Site(), {"lognormal": {"median": theta, "dispersion": beta}})
    expected = k0 * theta**-kk * math.exp(0.5 * kk**2 * beta**2)
    assert risk["annual_frequency"] == pytest.approx(expected, rel=1e-2)
    assert risk["model"] == "rigid-blocks"

    class Spectrum:
        def hazard_curve(self, im):
            return None

    assert "hazard curve" in assembly_risk(Spectrum(), {})["skipped"]
    assert "record-based" in assembly_risk(Site(), {"skipped": "budget"})["skipped"]


def test_where_the_rigid_blocks_move_below_k_the_ramp_gives_their_multiplier():
    """Two staggered rings, friction 0.8: the check finds the blocks moving 10 % below the
    iteration's k (0.2417), so the report gives the rigid blocks' own multiplier by the ramp
    test, between a held acceleration at rest and one that moves them (0.17 and 0.19 g,
    tests/rigid_blocks/test_curved_joints.py), and the first screen says to take it."""
    from archquake.geometry import multi_ring
    from archquake.report.assess.assembly import activation_part, verdict_text

    arch = multi_ring(10.0, math.radians(157.5), 1.5, rings=2, voussoirs=7, bond="staggered")
    summary, _, _ = limit_part(arch, 0.8)
    act = activation_part(arch, summary["k"], summary["direction"], 0.8)
    assert not act["agrees"] and act["runs"][0]["moves"]
    assert 0.17 < act["ramp"]["multiplier"] < 0.19 < summary["k"]
    text = verdict_text({"limit": summary, "rigid_blocks": act})
    assert "does NOT confirm" in text and "take this lower value" in text
