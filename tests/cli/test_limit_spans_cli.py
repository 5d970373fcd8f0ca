"""``archquake limit --spans N``: several arches on shared piers; the description's fields
``spans`` and ``pier_middle``; the other commands refuse several spans by name."""

import json

import pytest

from archquake import oppenheim
from archquake.cli import main
from archquake.geometry import Pier, StructureSpec
from archquake.geometry.bridge import multi_span
from archquake.geometry.structure import Structure
from archquake.limit_analysis import load_multipliers


def _json(argv, capsys):
    assert main([*argv, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_three_spans_on_piers_both_directions_and_the_spans_that_move(capsys):
    out = _json(["limit", "--spans", "3", "--piers", "3,6"], capsys)
    plus = out["directions"]["+x"]["no sliding"]
    minus = out["directions"]["-x"]["no sliding"]
    # a symmetric bridge: the two directions are mirror images, the same k, mirrored spans
    assert plus["load_multiplier"] == pytest.approx(minus["load_multiplier"], rel=1e-7)
    assert out["k"] == pytest.approx(min(plus["load_multiplier"], minus["load_multiplier"]))
    assert plus["spans_moving"] and all(1 <= s <= 3 for s in plus["spans_moving"])
    assert sorted(4 - s for s in plus["spans_moving"]) == minus["spans_moving"]
    # the end span, whose end pier the load pushes outward, is among those that fail
    assert 3 in plus["spans_moving"] and 1 in minus["spans_moving"]
    # never above the single arch on the same piers (Oppenheim's arch, chain program)
    single = min(load_multipliers(Structure(oppenheim(), Pier(3.0, 6.0), Pier(3.0, 6.0))))
    assert out["k"] <= single * (1 + 1e-9)


def test_massive_middle_piers_give_the_end_span_on_a_fixed_springing(capsys):
    # the spans decouple on piers that cannot move (40 m wide, 2 m high): k is the least of
    # Mech-l and Mech-r of the arch on its end pier and a fixed springing (chain program)
    out = _json(["limit", "--spans", "2", "--piers", "3,6", "--pier-middle", "40,2",
                 "--faces", "flat"], capsys)
    arch = StructureSpec(faces="flat").nominal()
    k_l, k_r = load_multipliers(Structure(arch, Pier(3.0, 6.0), None))
    assert out["k"] == pytest.approx(min(k_l, k_r), rel=1e-9)


def test_the_text_output_and_the_figure(tmp_path, capsys):
    figure = tmp_path / "bridge.png"
    assert main(["limit", "--spans", "2", "--piers", "3,6,2", "--plot", str(figure)]) == 0
    text = capsys.readouterr().out
    assert "spans that move" in text
    assert "2 spans on 3 piers, a block assembly of 20 blocks" in text  # 2 x 7 + 3 x 2
    assert figure.stat().st_size > 0


def test_the_description_builds_the_bridge():
    spec = StructureSpec.from_dict({"spans": 3, "piers": "3,6", "pier_middle": [4, 6, 2]})
    assert spec.spans == 3 and spec.pier_middle == (4.0, 6.0, 2)
    assert StructureSpec.from_dict(spec.to_dict()) == spec
    expected = multi_span(oppenheim(), 3, end_piers=(Pier(3.0, 6.0),) * 2,
                          middle_pier=Pier(4.0, 6.0, 2))
    assert spec.nominal() == expected
    # one span is today's arch on piers
    assert isinstance(StructureSpec(spans=1, piers="3,6").nominal(), Structure)


@pytest.mark.parametrize("argv, message", [
    (["--spans", "2"], "--spans 2 needs the piers between the spans: give --pier-middle"),
    (["--spans", "101", "--piers", "3,6"], r"--spans must be an integer in \[1, 100\]"),
    (["--pier-middle", "3,6"], "--pier-middle is the pier between two spans"),
    # Oppenheim's arch (t = 1.5 m, embrace 157.5 deg): the radial springing joint at 78.75 deg
    # from the vertical reaches t sin(78.75 deg) = 1.5 x 0.980785 = 1.47118 m; two seats
    (["--spans", "2", "--piers", "3,6", "--pier-middle", "2.9,6"],
     "--pier-middle: intermediate pier width must be at least 2.94236 m"),
    (["--spans", "2", "--piers", "2.9,6"], "--piers: intermediate pier width must be at least "
                                           "2.94236 m"),
])
def test_refusals_name_the_options(argv, message, capsys):
    assert main(["limit", *argv]) == 2
    assert message.split(r"\[")[0].replace("\\", "") in capsys.readouterr().err


@pytest.mark.parametrize("command", [
    ["compare", "--piers", "3,6"], ["limit", "--min-pier-width", "--piers", ",6"]])
def test_other_commands_refuse_several_spans_by_name(command, capsys):
    assert main([*command, "--spans", "2"]) == 2
    err = capsys.readouterr().err
    assert ("--spans 2 builds several arches on shared piers: limit, rigid-blocks, domain, "
            "fragility, record-fragility and assess analyse them") in err


def test_the_rigid_blocks_take_several_spans(capsys):
    # the bridge's k is 0.1439 (the end span with its pier): a pulse of a tenth of it never
    # moves the blocks (rigid blocks do not move below the static threshold)
    assert main(["rigid-blocks", "--piers", "3,6", "--spans", "3", "--amplitude", "0.014",
                 "--json"]) == 0
    assert '"outcome": "rest"' in capsys.readouterr().out


def test_fill_over_several_spans_from_the_command_line(capsys):
    # one span with fill is the single arch on piers with fill (its chain program); three spans
    # under the same fill never stand more than one (a span among others has the same arch and
    # fill, and piers that also move)
    fill = ["--fill-cover", "0.5", "--fill-density", "1800"]
    one = _json(["limit", "--piers", "3,6", "--faces", "flat", *fill], capsys)
    three = _json(["limit", "--spans", "3", "--piers", "3,6", "--faces", "flat", *fill], capsys)
    assert three["k"] <= one["k"] * (1 + 1e-9)
    # with the fill's passive reaction, each span's voussoirs pushed toward its middle: the
    # end span still fails as the single arch on its piers (the chain program with the same
    # reaction), far above the bridge without it
    passive = ["--fill-passive", "30,0.33"]
    one_p = _json(["limit", "--piers", "3,6", "--faces", "flat", *fill, *passive], capsys)
    three_p = _json(["limit", "--spans", "3", "--piers", "3,6", "--faces", "flat", *fill,
                     *passive], capsys)
    assert three_p["k"] == pytest.approx(one_p["k"], rel=1e-9)
    assert three_p["k"] > 1.5 * three["k"]
    spec = StructureSpec(spans=3, piers="3,6", fill_cover=0.5, fill_density=1800.0)
    bridge = spec.nominal()
    assert bridge.fill.cover == 0.5 and bridge.fill.density == 1800.0
    assert bridge.carriers.size == 3 * 7 + 2  # every voussoir and the two middle piers
    # the rigid blocks carry the fill as mass: a pulse of a tenth of k never moves them
    assert main(["rigid-blocks", "--piers", "3,6", "--spans", "3", *fill, "--amplitude",
                 f"{0.1 * three['k']:.4f}", "--json"]) == 0
    assert '"outcome": "rest"' in capsys.readouterr().out


def test_spans_of_rings_on_piers_under_fill(capsys):
    # two aligned rings that cannot slide act as the one-ring arch (cut into the same radial
    # joints): on Oppenheim's piers the single span's k is the chain program's 0.1439 to the
    # chords' error; three spans under fill carry the rings' names and spans
    out = _json(["limit", "--rings", "2", "--piers", "3,6"], capsys)
    single = min(load_multipliers(Structure(oppenheim(), Pier(3.0, 6.0), Pier(3.0, 6.0))))
    assert out["k"] == pytest.approx(single, rel=1e-3)
    out = _json(["limit", "--rings", "2", "--spans", "3", "--piers", "3,6", "--fill-cover",
                 "0.5", "--ring-friction", "0.6"], capsys)
    assert out["rings"]["count"] == 2
    assert "span 2 ring 1, voussoir 3" in out["rings"]["blocks"]
    plus = out["directions"]["+x"]["associative"]
    assert plus["spans_moving"] == [3]
