"""``archquake limit --epsilon E --samples N``: k over N irregular arches or bridges, each drawn
from its own child of the seed; checked member by member against the other program of the
limit analysis, on arches and on bridges whose middle piers leave every span to itself."""

import json

import numpy as np
import pytest

from archquake import oppenheim
from archquake.cli import main
from archquake.geometry import Pier, irregular_sample
from archquake.geometry.irregular import irregular_arch
from archquake.geometry.structure import Structure
from archquake.limit_analysis import assembly_limit, load_multipliers


def _json(argv, capsys):
    assert main([*argv, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_the_arches_of_a_sample_are_the_studies_and_their_k_the_assembly_programs(capsys):
    # member i is irregular_sample's arch i (the fragility studies' streams); its k, from the
    # chain program, equals the assembly program's (end forces of every joint, another LP)
    out = _json(["limit", "--epsilon", "0.1", "--seed", "4", "--samples", "6"], capsys)
    arches = irregular_sample(oppenheim(), 0.1, 6, 4)
    expected = [min(assembly_limit(a, d).load_multiplier for d in ("+x", "-x")) for a in arches]
    assert out["k"] == pytest.approx(expected, rel=1e-8)
    assert out["k_nominal"] == pytest.approx(min(load_multipliers(oppenheim())), rel=1e-12)
    assert out["refused"] == [] and out["min"] == min(out["k"])
    assert out["quantiles"]["0.5"] == pytest.approx(float(np.median(out["k"])))


def test_bridges_on_massive_middle_piers_are_each_spans_own(capsys):
    # middle piers 40 m wide and 2 m high: each member's k is the least of its three spans' own
    # (the end ones on their end pier), by the chain program, from the member's own stream
    argv = ["limit", "--spans", "3", "--piers", "3,6", "--pier-middle", "40,2", "--faces",
            "flat", "--epsilon", "0.1", "--seed", "2", "--samples", "3"]
    out = _json(argv, capsys)
    from archquake.geometry import StructureSpec

    arch = StructureSpec(faces="flat").nominal()
    pier = Pier(3.0, 6.0)
    for child, k in zip(np.random.SeedSequence(2).spawn(3), out["k"], strict=True):
        rng = np.random.default_rng(child)
        draws = [irregular_arch(arch, 0.1, rng=rng) for _ in range(3)]
        alone = [Structure(draws[0], pier, None), draws[1], Structure(draws[2], None, pier)]
        assert k == pytest.approx(min(min(load_multipliers(s)) for s in alone), rel=1e-9)


def test_draws_the_piers_cannot_seat_are_left_out_and_said(capsys):
    # piers 3 m wide seat the nominal arch's springings (2.94 m) but not every draw's
    assert main(["limit", "--spans", "3", "--piers", "3,6", "--epsilon", "0.1", "--samples",
                 "6", "--no-progress"]) == 0
    text = capsys.readouterr().out
    assert "k over 6 irregular bridges (epsilon 0.1, seed 0" in text
    assert "warning: " in text and "could not be built and are left out" in text
    out = _json(["limit", "--spans", "3", "--piers", "3,6", "--epsilon", "0.1", "--samples",
                 "6"], capsys)
    left_out = [r["member"] for r in out["refused"]]
    assert left_out and all(out["k"][i] is None for i in left_out)
    assert "intermediate pier width must be at least" in out["refused"][0]["reason"]


@pytest.mark.parametrize(("argv", "message"), [
    (["--samples", "5"], "--samples draws irregular structures: give --epsilon"),
    (["--epsilon", "0.1", "--samples", "0"], "--samples must be an integer in [1, 100000]"),
    (["--epsilon", "0.1", "--samples", "3", "--arbiter"], "--arbiter tests one structure"),
    (["--epsilon", "0.1", "--samples", "3", "--min-pier-width", "--piers", ",6"],
     "leave out --samples"),
    (["--spans", "2", "--piers", "3.2,6", "--epsilon", "0.1", "--samples", "3", "--method",
      "kinematic"], "block assemblies take the static method"),
])
def test_refusals(argv, message, capsys):
    assert main(["limit", *argv]) == 2
    assert message in capsys.readouterr().err


def test_the_figure(tmp_path, capsys):
    path = tmp_path / "k.png"
    assert main(["limit", "--epsilon", "0.1", "--samples", "20", "--plot", str(path),
                 "--no-progress"]) == 0
    assert path.stat().st_size > 10_000 and "figure written to" in capsys.readouterr().out


def test_members_that_cannot_stand_are_counted_apart(capsys):
    # a thin arch (t = 0.9 m) drawn with epsilon 0.2: some members cannot stand under their own
    # weight; the assembly program's own test (another LP) says which
    from archquake.geometry import StructureSpec
    from archquake.limit_analysis import assembly_stands

    argv = ["limit", "--thickness", "0.9", "--epsilon", "0.2", "--samples", "12"]
    out = _json(argv, capsys)
    weak = out["cannot_stand"]
    assert weak and all(out["k"][i] is None for i in weak)
    arches = irregular_sample(StructureSpec(thickness=0.9).nominal(), 0.2, 12, 0)
    assert [i for i, a in enumerate(arches) if not assembly_stands(a)] == weak
    assert main([*argv, "--no-progress"]) == 0
    assert f"warning: {len(weak)} of 12 cannot stand under their own weight" in \
        capsys.readouterr().out
