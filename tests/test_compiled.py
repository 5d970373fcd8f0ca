"""The note of a first run that compiles an engine (archquake.compiled): whether an engine is
ready is checked against what numba then does (loads it from its cache or compiles it), and
the note is printed once, by the command line's process only."""

import io
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from archquake import compiled
from archquake.cli import main

ENABLE_NOTES = compiled.enable_notes  # the tests' conftest makes it a no-op: the real one

ROOT = Path(__file__).resolve().parents[1]

PROBE = textwrap.dedent("""
    import json, sys
    sys.path.insert(0, {module_dir!r})
    from archquake.compiled import is_ready
    import probe_module
    before = is_ready(probe_module.twice)
    probe_module.twice(2.0)
    print(json.dumps({{"ready": before, "hits": sum(probe_module.twice.stats.cache_hits.values()),
                      "misses": sum(probe_module.twice.stats.cache_misses.values())}}))
""")


def _probe(module_dir: Path, cache_dir: Path) -> dict:
    """In a fresh interpreter with numba's cache in ``cache_dir``: whether ``twice`` was ready
    before its first call, and whether numba then loaded it (hits) or compiled it (misses)."""
    import json

    code = PROBE.format(module_dir=str(module_dir))
    env = {"PYTHONPATH": str(ROOT / "src"), "NUMBA_CACHE_DIR": str(cache_dir)}
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env,
                         cwd=ROOT)
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout.splitlines()[-1])


def test_ready_is_what_numba_then_does(tmp_path):
    """A function never compiled is not ready and numba compiles it; in the next process it is
    ready and numba loads it from the cache; once its source changes it is not ready again
    (numba's index is stale) and numba compiles it again."""
    module = tmp_path / "code" / "probe_module.py"
    module.parent.mkdir()
    module.write_text("import numba\n\n@numba.njit(cache=True)\ndef twice(x):\n"
                      "    return 2.0 * x\n")
    cache = tmp_path / "cache"
    first = _probe(module.parent, cache)
    assert first == {"ready": False, "hits": 0, "misses": 1}
    second = _probe(module.parent, cache)
    assert second == {"ready": True, "hits": 1, "misses": 0}
    module.write_text("import numba\n\n@numba.njit(cache=True)\ndef twice(x):\n"
                      "    return x + x  # another source\n")
    third = _probe(module.parent, cache)
    assert third == {"ready": False, "hits": 0, "misses": 1}


class _Cold:
    """A dispatcher that numba has neither compiled nor cached: ``is_ready`` reads no cache
    from it and says True (no note), so the tests make it cold through ``is_ready``."""

    overloads: dict = {}


@pytest.fixture
def notes(monkeypatch):
    """Notes enabled, every engine cold; disabled again after the test."""
    monkeypatch.setattr(compiled, "is_ready", lambda dispatcher: False)
    monkeypatch.setattr(compiled, "enable_notes", ENABLE_NOTES)
    compiled.enable_notes()
    yield
    compiled.enable_notes(False)


def test_a_cold_engine_is_announced_once_with_its_name(notes):
    out = io.StringIO()
    assert compiled.announce(compiled.RIGID_BLOCKS, _Cold(), file=out)
    assert not compiled.announce(compiled.RIGID_BLOCKS, _Cold(), file=out)  # once
    assert compiled.announce(compiled.FOUR_LINK, _Cold(), file=out)
    lines = out.getvalue().splitlines()
    assert len(lines) == 2
    assert lines[0] == ("archquake: note: compiling the rigid-block solver for this processor "
                        "(about 45 s), once: later runs load it")
    assert "the four-link engine" in lines[1]


def test_nothing_is_announced_unless_enabled_or_where_the_engine_is_ready(monkeypatch):
    out = io.StringIO()
    monkeypatch.setattr(compiled, "enable_notes", ENABLE_NOTES)
    compiled.enable_notes(False)
    monkeypatch.setattr(compiled, "is_ready", lambda dispatcher: False)
    assert not compiled.announce(compiled.RIGID_BLOCKS, _Cold(), file=out)  # a library call
    compiled.enable_notes()
    try:
        monkeypatch.setattr(compiled, "is_ready", lambda dispatcher: True)
        assert not compiled.announce(compiled.RIGID_BLOCKS, _Cold(), file=out)
    finally:
        compiled.enable_notes(False)
    assert out.getvalue() == ""


def test_a_dispatcher_compiled_in_this_process_is_ready():
    from archquake import oppenheim
    from archquake.rigid_blocks import block_outcome
    from archquake.rigid_blocks.solver import run

    block_outcome(oppenheim(), None)
    assert run.overloads and compiled.is_ready(run)


def test_the_warm_ups_of_the_pools_name_their_engines(notes, capsys):
    """A pool warmed up by one of these compiles that engine in its workers: the process that
    starts it says so (the workers say nothing)."""
    from archquake.rigid_blocks.model import warm_up as rigid_warm_up
    from archquake.rigid_blocks.solver import run
    from archquake.studies.fragility import warm_up as fragility_warm_up
    from archquake.studies.record_fragility import warm_up as record_warm_up

    assert list(compiled.engines_of(rigid_warm_up)) == [(compiled.RIGID_BLOCKS, run)]
    from archquake.fourlink.engine import integrate

    for warm_up in (fragility_warm_up, record_warm_up):
        assert list(compiled.engines_of(warm_up)) == [(compiled.FOUR_LINK, integrate)]
    assert list(compiled.engines_of(None)) == []
    compiled.announce_for_workers(rigid_warm_up)
    compiled.announce_for_workers(fragility_warm_up)
    err = capsys.readouterr().err.splitlines()
    assert [line.split(" for ")[0] for line in err] == [
        "archquake: note: compiling the rigid-block solver",
        "archquake: note: compiling the four-link engine"]


def test_a_command_announces_the_engine_it_compiles(monkeypatch, capsys, tmp_path):
    """The command line enables the notes: a study of the rigid blocks whose engines are not
    ready says so once for each before it runs it (here they are ready, and said cold): the
    rigid-block solver, and the four-link engine of its default search's screen."""
    monkeypatch.setattr(compiled, "is_ready", lambda dispatcher: False)
    monkeypatch.setattr(compiled, "enable_notes", ENABLE_NOTES)
    try:
        status = main(["fragility", "--model", "rigid-blocks", "--samples", "2",
                       "--durations", "0.4", "--amplitudes", "0.1,0.2", "--limit-samples",
                       "10", "--no-progress", "--out", str(tmp_path / "study")])
    finally:
        compiled.enable_notes(False)
    assert status == 0
    notes = [line for line in capsys.readouterr().err.splitlines() if "compiling" in line]
    assert notes == ["archquake: note: compiling the rigid-block solver for this processor "
                     "(about 45 s), once: later runs load it",
                     "archquake: note: compiling the four-link engine for this processor "
                     "(about 20 s), once: later runs load it"]


def test_a_study_names_the_engines_of_its_model():
    """The four-link model runs its engine; the rigid blocks run their solver, and a study of
    them the four-link engine of its screen where it has one (the default search on arches,
    every record study of arches): not with the exhaustive grid, nor for a bridge."""
    from archquake.fourlink.engine import integrate
    from archquake.geometry import StructureSpec
    from archquake.models import ModelSpec
    from archquake.rigid_blocks.solver import run
    from archquake.studies.fragility import FragilitySettings

    four_link, blocks = (compiled.FOUR_LINK, integrate), (compiled.RIGID_BLOCKS, run)
    assert ModelSpec("four-link").engines() == [four_link]
    assert ModelSpec("rigid-blocks").engines() == [blocks]
    assert FragilitySettings(sample_size=2).engines() == [four_link]
    assert FragilitySettings(sample_size=2, model="rigid-blocks").engines() == [blocks, four_link]
    assert FragilitySettings(sample_size=2, model="rigid-blocks",
                             search="exhaustive").engines() == [blocks]
    bridge = StructureSpec(spans=3, piers=(3.2, 6.0))
    assert FragilitySettings(sample_size=2, model="rigid-blocks",
                             description=bridge).engines() == [blocks]


def test_readiness_is_read_once_per_engine(monkeypatch):
    """A study builds a model per arch: the cache's index is read at the first only."""
    calls = []
    monkeypatch.setattr(compiled, "is_ready", lambda dispatcher: calls.append(1) or True)
    monkeypatch.setattr(compiled, "enable_notes", ENABLE_NOTES)
    compiled.enable_notes()
    try:
        for _ in range(5):
            assert not compiled.announce(compiled.FOUR_LINK, _Cold())
    finally:
        compiled.enable_notes(False)
    assert calls == [1]
