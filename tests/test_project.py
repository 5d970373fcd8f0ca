"""The project's own commands: every file a make target runs exists."""

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def test_every_script_a_make_target_runs_exists():
    makefile = (ROOT / "Makefile").read_text()
    scripts = re.findall(r"\b((?:benchmarks|examples|docs|tests)/[\w./-]+\.py)\b", makefile)
    assert scripts, "the Makefile runs no script of the project"
    missing = [s for s in scripts if not (ROOT / s).is_file()]
    assert not missing, f"make targets run missing files: {missing}"


def test_run_all_finds_every_benchmark():
    import importlib.util

    spec = importlib.util.spec_from_file_location("run_all", ROOT / "benchmarks" / "run_all.py")
    run_all = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(run_all)
    found = {p.name for p in run_all.benchmark_scripts()}
    expected = {p.name for p in (ROOT / "benchmarks").glob("*.py")} - {"run_all.py"}
    assert found == expected


from import_graph import package_imports  # noqa: E402

HEAVY = {"scipy.optimize", "scipy.stats", "scipy.integrate", "pandas", "matplotlib", "pyarrow",
         "distributed", "dask", "tqdm"}


def test_command_line_help_imports_no_heavy_module():
    """``archquake --version`` and every ``--help`` answer in a few tenths of a second: building
    the options imports none of the heavy modules (each costs 0.1-0.5 s); a subcommand imports
    what it needs when it runs."""
    import subprocess
    import sys

    code = ("import sys; from archquake.cli import build_parser; build_parser(); "
            "print(' '.join(sorted(sys.modules)))")
    loaded = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                            check=True, cwd=ROOT, env={"PYTHONPATH": str(ROOT / "src")}).stdout
    assert not HEAVY & set(loaded.split())


def test_package_has_no_import_cycle():
    """No module of the package imports, directly or through others, a module that imports it
    (lazy imports inside functions count: they hide a cycle, they do not remove it)."""
    graph = package_imports()
    assert "archquake.fourlink.linkage" in graph and not graph["archquake.fourlink.linkage"]
    assert "archquake.fourlink.mechanism" not in graph["archquake.fourlink.equations_of_motion"]
    state = {}

    def visit(node, path):
        state[node] = "open"
        for nxt in sorted(graph[node]):
            if state.get(nxt) == "open":
                cycle = path[path.index(nxt):] + [nxt]
                raise AssertionError("import cycle: " + " -> ".join(cycle))
            if nxt not in state:
                visit(nxt, path + [nxt])
        state[node] = "done"

    for node in sorted(graph):
        if node not in state:
            visit(node, [node])
