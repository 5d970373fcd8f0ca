"""Fuzzing the geometry readers and builders: files valid, borderline and hostile (a circular
arch's lists, block polygons, shapes, structures; wrong types, non-finite numbers, keys given
twice, deep nesting, bytes that are not UTF-8). Each is read by ``load_arch`` and by ``archquake
limit --geometry``: an arch and a strict-JSON result, or one error naming the file."""

import json
import math
import string

import pytest
from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st

from archquake import oppenheim
from archquake.geometry import circular_arch, irregular_arch, load_arch, shaped_arch
from fuzzing import check_run, run_cli, time_limit

pytestmark = pytest.mark.fuzz

NUMBER = st.one_of(st.floats(allow_nan=False, allow_infinity=False, width=64),
                   st.floats(0.01, 20.0), st.integers(-5, 50),
                   st.sampled_from([0, -1, 1e300, 1e-300, 5e-324]))
JSON_SCALAR = st.one_of(NUMBER, st.booleans(), st.none(), st.text(max_size=6))
JSON_VALUE = st.recursive(JSON_SCALAR, lambda inner: st.one_of(
    st.lists(inner, max_size=5), st.dictionaries(st.text(max_size=6), inner, max_size=4)),
    max_leaves=20)


def _circular():
    base = oppenheim().to_dict()
    return st.fixed_dictionaries({
        "angles": st.one_of(st.just(base["angles"]),
                            st.lists(st.floats(-0.5, 1.0), min_size=0, max_size=12)),
        "thicknesses": st.one_of(st.just(base["thicknesses"]),
                                 st.lists(NUMBER, min_size=0, max_size=12)),
        "radii": st.one_of(st.just(base["radii"]), st.lists(NUMBER, min_size=0, max_size=12)),
    }, optional={"start_angle": NUMBER, "density": NUMBER, "extra": JSON_SCALAR})


def _polygon():
    point = st.tuples(st.floats(-20, 20), st.floats(-20, 20)).map(list)
    return st.lists(point, min_size=0, max_size=8)


@st.composite
def _survey(draw):
    """Blocks of a real arch, moved, reordered or replaced; or random polygons."""
    n = draw(st.integers(4, 10))
    arch = circular_arch(10.0, draw(st.floats(1.0, 3.0)), draw(st.floats(0.3, 2.0)), n)
    blocks = [arch.outline(i, draw(st.integers(2, 6)))[:-1].tolist() for i in range(n)]
    for _ in range(draw(st.integers(0, 2))):
        i = draw(st.integers(0, len(blocks) - 1))
        change = draw(st.sampled_from(("move", "random", "reverse", "drop")))
        if change == "move":
            dx, dy = draw(st.sampled_from([1e-12, 1e-7, 1e-3, 0.3])), draw(st.floats(-1, 1))
            blocks[i] = [[x + dx, y + dy * dx] for x, y in blocks[i]]
        elif change == "random":
            blocks[i] = draw(_polygon())
        elif change == "reverse":
            blocks = blocks[::-1]
        elif len(blocks) > 1:
            blocks.pop(i)
    out = {"blocks": blocks}
    if draw(st.booleans()):
        out["tolerance"] = draw(st.one_of(st.floats(1e-13, 0.1), NUMBER))
    return out


def _shaped():
    return st.fixed_dictionaries({
        "shape": st.sampled_from(["parabolic", "pointed", "catenary", "elliptical", "circular",
                                  "gothic", ""]),
        "span": NUMBER, "rise": NUMBER, "thickness": NUMBER,
    }, optional={"voussoirs": st.one_of(st.integers(-2, 30), NUMBER), "faces": JSON_SCALAR})


CONTENT = st.one_of(
    _circular().map(json.dumps),
    _survey().map(json.dumps),
    _shaped().map(json.dumps),
    st.builds(lambda arch, pier: json.dumps({"arch": arch, "left_pier": pier}),
              _circular(), JSON_VALUE),
    JSON_VALUE.map(json.dumps),
    st.sampled_from(["", " ", "{", "[" * 5000, "{" * 100_000, '{"angles": [NaN]}',
                     '{"angles": [1], "angles": [2]}', "null", "1e400", '"text"',
                     json.dumps(oppenheim().to_dict())[:-1] + ', "density": 1e300}']),
    st.text(string.printable, max_size=50),
).map(str.encode) | st.binary(max_size=64)


def _readable(path):
    try:
        return load_arch(path)
    except ValueError as exc:
        assert str(path.name) in str(exc) or "path" in str(exc), str(exc)
        return None


@pytest.mark.filterwarnings("ignore:geometry file .* listed right to left:UserWarning")
@settings(suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])
@given(CONTENT)
def test_a_geometry_file_gives_an_arch_or_an_error_naming_it(tmp_path, content):
    path = tmp_path / "arch.json"
    path.write_bytes(content)
    with time_limit():
        arch = _readable(path)
    event("arch" if arch is not None else "refused")
    argv = ["limit", "--geometry", str(path), "--json"]
    status, out, err = run_cli(argv)
    kind = check_run(argv, status, out, err, names=["arch.json", "--geometry", "arch",
                                                    "thrust"])
    assert (kind == "ok") <= (arch is not None)


@given(radius=NUMBER, embrace=NUMBER, thickness=NUMBER, voussoirs=st.one_of(
    st.integers(-3, 10**30), NUMBER), density=NUMBER)
def test_circular_arch_builds_or_names_the_parameter(radius, embrace, thickness, voussoirs,
                                                     density):
    names = ("radius", "radii", "embrace", "thickness", "voussoirs", "density")
    try:
        arch = circular_arch(radius, embrace, thickness, voussoirs, density=density)
    except ValueError as exc:
        assert any(name in str(exc) for name in names), str(exc)
        return
    assert all(math.isfinite(m) and m > 0 for m in arch.masses)


@given(shape=st.sampled_from(["parabolic", "pointed", "catenary", "elliptical",
                              "three-centred", "circular"]),
       span=NUMBER, rise=NUMBER, thickness=NUMBER, voussoirs=st.integers(-2, 40))
def test_shaped_arch_builds_or_names_the_parameter(shape, span, rise, thickness, voussoirs):
    try:
        with time_limit():
            arch = shaped_arch(shape, span=span, rise=rise, thickness=thickness,
                               voussoirs=voussoirs)
            masses = arch.masses  # computed when first asked: an error may come only now
    except ValueError as exc:
        assert any(name in str(exc) for name in ("span", "rise", "thickness", "voussoirs",
                                                 "shape", "arch")), str(exc)
        return
    assert all(math.isfinite(m) and m > 0 for m in masses)


@given(epsilon=NUMBER, rng=st.one_of(st.integers(-10, 2**70), NUMBER, st.text(max_size=3)))
def test_irregular_arch_draws_or_names_the_parameter(epsilon, rng):
    try:
        arch = irregular_arch(oppenheim(), epsilon, rng=rng)
    except ValueError as exc:
        assert str(exc).startswith(("epsilon", "rng")) or "arch" in str(exc), str(exc)
        return
    assert arch.n_voussoirs == 7
