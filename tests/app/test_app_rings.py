"""Several spans and several rings on the page: the structure is a block assembly, analysed as
``archquake limit`` analyses it (both directions, both friction laws), drawn from the JSON of
:mod:`archquake.app.views`; the parts of the page that need one chain of voussoirs say why they
are not available, and bad input gets the command line's message naming the field."""

import math

import numpy as np
import pytest
from app_reference import cli_error, cli_json, fields_named

from archquake.app.inputs import ASSEMBLY_UNAVAILABLE, LIMITS, is_assembly, structure_from_spec
from archquake.app.server import check_answer, structure_answer
from archquake.app.views import assembly_limit_view, json_ready

BRIDGE = {"spans": 3, "piers": "3,6"}
"""Three spans of Oppenheim's arch (R = 10 m, 157.5 deg, t = 1.5 m, 7 voussoirs) on four
piers 3 m wide and 6 m high, one course each: ``archquake limit --spans 3 --piers 3,6``."""

SITE = {"ag": 0.25, "f0": 2.4, "tc_star": 0.3}


def post(client, body):
    return client.post("/api/structure", json=body)


def test_page_builds_spans_and_rings_as_block_assemblies():
    _, bridge = structure_from_spec(BRIDGE)
    _, rings = structure_from_spec({"rings": 2})
    _, arch = structure_from_spec({"voussoirs": 7})
    assert is_assembly(bridge) and is_assembly(rings) and not is_assembly(arch)
    # 3 spans x 7 voussoirs + 4 piers x 1 course; 2 rings x 7 voussoirs (aligned)
    assert bridge.n_blocks == 3 * 7 + 4 and rings.n_blocks == 2 * 7
    assert arch.n_voussoirs == 7


def test_one_span_assembly_has_the_k_of_the_arch_on_its_piers():
    """``multi_span`` with one span is the arch on its two piers as a block assembly; its limit
    analysis (the assembly's program) gives the chain program's k of the arch on piers, within
    the outline's chords (24 points per curved face, sagitta ~ R (pi/(7*24))^2 / 2 ~ 1e-3 m on a
    10 m arch: k agrees to 1e-3 relative)."""
    from archquake.geometry import Pier
    from archquake.geometry.bridge import multi_span
    from archquake.limit_analysis import assembly_limits, both_directions

    nominal, on_piers = structure_from_spec({"piers": "3,6"})
    chain_k = min(r.load_multiplier for r in both_directions(on_piers))
    arch = on_piers.arch
    one = multi_span(arch, 1, end_piers=(Pier(3, 6), Pier(3, 6)), middle_pier=Pier(3, 6))
    view = json_ready(assembly_limit_view(one, assembly_limits(one)))
    assert view["k"] == pytest.approx(chain_k, rel=1e-3)
    # the page's answer for "spans 1" is the arch on piers itself, the same k exactly
    assert structure_answer({"spans": 1, "piers": "3,6"})["limit"]["k"] == pytest.approx(
        chain_k, rel=1e-12)


def test_rings_that_cannot_slide_have_the_k_of_the_one_ring_arch():
    """Two aligned rings whose ring interfaces cannot slide (friction inf) collapse as the arch
    of one ring does (the rings do not separate in its four-hinge mechanism); the one-ring arch
    is also Oppenheim's arch of the chain program, within the ring faces' chords (ARC_ERROR
    1e-3 m on a 1.5 m thick arch: 2e-4 relative)."""
    from archquake.limit_analysis import both_directions

    two = structure_answer({"rings": 2, "ring_friction": "inf"})["limit"]
    one = structure_answer({"rings": 1})["limit"]
    _, arch = structure_from_spec({})
    chain = min(r.load_multiplier for r in both_directions(arch))
    assert two["k"] == pytest.approx(one["k"], rel=1e-9)
    assert one["k"] == pytest.approx(chain, rel=2e-4)
    assert [law["law"] for law in two["l"]["laws"]] == ["no sliding"]
    assert two["l"]["laws"][0]["tilt"] == pytest.approx(math.degrees(math.atan(two["k"])))


def test_bridge_json_has_three_spans_of_blocks_and_the_command_lines_k(client):
    answer = post(client, {"structure": BRIDGE}).json()
    structure, limit = answer["structure"], answer["limit"]
    assert structure["assembly"] and structure["group"] == "span"
    groups = structure["groups"]
    assert [groups.count(span) for span in (1, 2, 3)] == [7, 7, 7]
    assert structure["kinds"].count("pier") == 4
    assert len(structure["blocks"]) == 25 and len(structure["ground"]) == 4  # 4 pier bases
    expected = cli_json("limit", "--spans", "3", "--piers", "3,6")
    assert limit["k"] == pytest.approx(expected["k"], rel=1e-9)
    # the bridge is its own mirror image: both directions collapse at the same k, the
    # mechanism of +x in the last span (the push toward it), of -x in the first
    assert limit["k_l"] == pytest.approx(limit["k_r"], rel=1e-6)
    assert limit["l"]["laws"][0]["moving"] == [3] and limit["r"]["laws"][0]["moving"] == [1]
    assert limit["first"].startswith(f"at k = {expected['k']:.4f}")
    assert "span 3 moves first toward +x" in limit["first"]
    # the drawn mechanism: the displaced voussoirs are all of span 3 (those between its
    # hinges), and the four hinges of a span's mechanism are drawn where the interfaces rock
    law = limit["l"]["laws"][0]
    moved = {d["block"] for d in law["displaced"]}
    assert {groups[b] for b in moved if groups[b] is not None} == {3}
    assert sum(f["hinge"] is not None for f in law["interfaces"]) == 4
    # the line of thrust: two segments in each of the 21 voussoirs and the 2 end piers (a
    # middle pier carries three thrusts and has none), meeting in each block
    thrust = np.asarray(law["thrust"])
    assert thrust.shape == (2 * (21 + 2), 2, 2)
    for a, b in zip(thrust[0::2], thrust[1::2], strict=True):
        assert np.hypot(*(a[1] - b[1])) < 1e-3
    # every displaced block is its outline moved rigidly: its edges keep their lengths
    for d in law["displaced"]:
        before = np.asarray(structure["blocks"][d["block"]])
        after = np.asarray(d["outline"])
        assert np.allclose(np.hypot(*np.diff(after, axis=0).T),
                           np.hypot(*np.diff(before, axis=0).T), atol=0.02 * 25)


def test_a_bridge_under_a_passive_fill_has_the_command_lines_k(client):
    fill = {"fill_cover": 0.5, "fill_passive": "30,0.33"}
    limit = post(client, {"structure": {**BRIDGE, **fill}}).json()["limit"]
    expected = cli_json("limit", "--spans", "3", "--piers", "3,6", "--fill-cover", "0.5",
                        "--fill-passive", "30,0.33")
    assert limit["k"] == pytest.approx(expected["k"], rel=1e-9)
    without = post(client, {"structure": {**BRIDGE, "fill_cover": 0.5}}).json()["limit"]
    assert limit["k"] > 1.5 * without["k"]


def test_ring_friction_gives_both_laws_the_non_associative_governing(client):
    limit = post(client, {"structure": {"rings": 2, "ring_friction": 0.5}}).json()["limit"]
    expected = cli_json("limit", "--rings", "2", "--ring-friction", "0.5")
    for name, direction in (("l", "+x"), ("r", "-x")):
        laws = {law["law"]: law for law in limit[name]["laws"]}
        assert list(laws) == ["non-associative", "associative"]
        for law, result in laws.items():
            want = expected["directions"][direction][law]
            assert result["k"] == pytest.approx(want["load_multiplier"], rel=1e-9)
            assert result["tilt"] == pytest.approx(want["tilt_deg"], rel=1e-9)
        # Coulomb without dilatancy collapses no later than with it
        assert laws["non-associative"]["k"] <= laws["associative"]["k"] + 1e-9
        assert laws["associative"]["ring_slides_m"] > 0
    assert limit["k"] == pytest.approx(expected["k"], rel=1e-9)


@pytest.mark.parametrize(("spec", "argv"), [
    ({"spans": 0}, ("--spans", "0")),
    ({"spans": 3, "pier_middle": "2,6"}, ("--spans", "3", "--pier-middle", "2,6")),
    ({"spans": 3}, ("--spans", "3")),
    ({"rings": 0}, ("--rings", "0")),
    ({"rings": 2, "ring_friction": -1}, ("--rings", "2", "--ring-friction", "-1")),
    ({"ring_bond": "staggered"}, ("--ring-bond", "staggered")),
])
def test_bad_spans_and_rings_get_the_command_lines_message(client, spec, argv):
    answer = post(client, {"structure": spec})
    assert answer.status_code == 400
    assert answer.json()["error"] == fields_named(cli_error("limit", *argv))


def test_more_rings_than_the_page_takes_are_refused_before_they_are_built(client):
    answer = post(client, {"structure": {"rings": 10**6}})
    assert answer.status_code == 400
    assert answer.json()["error"].startswith("rings 1000000 of 7 voussoirs make more than "
                                             f"{LIMITS['blocks']} blocks")


def test_parts_that_need_one_chain_say_why_not(client):
    answer = post(client, {"structure": BRIDGE}).json()
    assert answer["unavailable"] == ASSEMBLY_UNAVAILABLE
    assert set(ASSEMBLY_UNAVAILABLE) == {"four-link"}
    assert "archquake rigid-blocks --spans 3 --piers 3,6" in answer["unavailable"]["four-link"]
    # a single arch has none of these notes
    assert "unavailable" not in post(client, {"structure": {}}).json()


def test_the_failure_domain_of_a_bridge_is_the_rigid_blocks_as_the_command_line_gives_it():
    from archquake.app.tasks import failure_domain

    domain = {"durations": "0.4", "amplitudes": "0.1:0.4:0.05", "direction": "l",
              "motion": "oppenheim", "resolution": 0.01, "extend_to": 0.0}
    spec = {"structure": {"spans": 2, "piers": "3,6"}, "domain": domain}
    out = failure_domain(spec, lambda done, total, text: None)
    assert out["four-link"] == {"error": ASSEMBLY_UNAVAILABLE["four-link"]}
    assert "disagreement" not in out and out["figure"].startswith("data:image/png;base64,")
    rows = cli_json("domain", "--model", "rigid-blocks", "--spans", "2", "--piers", "3,6",
                    "--durations", "0.4", "--amplitudes", "0.1:0.4:0.05", "--resolution",
                    "0.01", "--extend-to", "0", "--no-progress")
    assert out["rigid-blocks"]["failure"]["failure_g"] == [rows[0]["failure_acceleration"]]
    assert out["rigid-blocks"]["undecided"] == rows[0]["undecided_analyses"] == 0


def test_the_code_check_of_a_bridge_is_the_librarys_linear_route():
    """The page's check of a block assembly is the library's (the linear route, the
    nonlinear one declined with its reason), with the assembly's own friction."""
    from archquake.app.inputs import site_from_spec
    from archquake.site.local_mechanism import check_local_mechanism

    answer = check_answer(BRIDGE, SITE)
    actions, fc = site_from_spec(SITE)
    _, bridge = structure_from_spec(BRIDGE)
    library = check_local_mechanism(bridge, actions, confidence_factor=fc).to_dict()
    check = answer["check"]
    assert check["linear"] and not check["nonlinear"]
    for mine, theirs in zip(check["linear"], library["linear"], strict=True):
        assert mine["direction"] == theirs["direction"] in ("+x", "-x")
        assert mine["a0_star_g"] == pytest.approx(theirs["a0_star_g"], rel=1e-12)
    assert any("not traced in its displaced configuration" in n for n in check["notes"])


def test_the_assessment_of_a_bridge_is_the_assemblys(tmp_path):
    """The page's report of several spans is the library's assessment of an assembly: its
    verdict names the span that fails first."""
    from archquake.app.tasks import _description, assessment_report

    _, bridge = structure_from_spec(BRIDGE)
    summary = assessment_report(bridge, tmp_path / "report", _description(BRIDGE))
    assert summary["verdict"].startswith("VERDICT: STANDS.")
    assert "span 1:" in summary["verdict"] or "span 3:" in summary["verdict"]
    assert "fig1_collapse.png" in summary["files"]
    # the irregular bridges of its description, as the command line's assessment draws them
    assert "fig1b_irregular_bridges.png" in summary["files"]
    assert "irregular bridges around it (epsilon 0.1)" in summary["verdict"]
    assert _description({"rings": 2}) is None
    assert _description({}) is None


def test_an_irregular_bridge_on_the_page_is_the_command_lines(client):
    structure = {**BRIDGE, "piers": "3.2,6", "epsilon": 0.1, "seed": 2}
    limit = post(client, {"structure": structure}).json()["limit"]
    expected = cli_json("limit", "--spans", "3", "--piers", "3.2,6", "--epsilon", "0.1",
                        "--seed", "2")
    assert limit["k"] == pytest.approx(expected["k"], rel=1e-9)


def test_time_history_of_a_bridge_is_the_rigid_blocks_only():
    """The page's time history of a bridge runs the rigid blocks on the assembly and says why
    the four-link model does not; the outcome is the library's for the same structure and
    pulse (:meth:`RigidBlockModel.outcome`, which runs without recording a history)."""
    from archquake.app.tasks import simulate
    from archquake.ground_motion import MotionSpec
    from archquake.models import ModelSpec

    motion = {"motion": "oppenheim", "amplitude": -0.3, "duration": 0.3}
    result = simulate({"structure": BRIDGE, "motion": motion}, lambda *a: None)
    assert result["four-link"] == {"error": ASSEMBLY_UNAVAILABLE["four-link"]}
    view = result["rigid-blocks"]
    _, bridge = structure_from_spec(BRIDGE)
    outcome = ModelSpec(name="rigid-blocks").build(bridge).outcome(
        MotionSpec.from_dict(motion).build())
    assert view["outcome"]["status"] == outcome.status.label
    assert len(view["blocks"]) == bridge.n_blocks == len(view["frames"][0])


def test_figure_of_rings_with_friction_has_a_row_per_law(client):
    """"figure (PNG)" draws every law's mechanism of both directions, as ``archquake limit
    --plot`` does: two rows (associative, non-associative) of two panels with ring friction, so
    the image is about twice as tall as the one row of the bridge without friction."""
    import io

    from PIL import Image

    sizes = []
    for structure in (BRIDGE, {"rings": 2, "ring_friction": 0.5}):
        answer = client.post("/api/figure", json={"structure": structure})
        assert answer.status_code == 200 and answer.headers["content-type"] == "image/png"
        sizes.append(Image.open(io.BytesIO(answer.content)).size)
    (w1, h1), (w2, h2) = sizes
    assert w1 == w2 and h2 == pytest.approx(2 * h1, rel=0.05)
