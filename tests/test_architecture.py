"""The import contract of the package: two models side by side, imports flowing one way.

- the rigid-block model imports nothing of the four-link model, directly or through another
  module, so that it can check it; the one declared exception runs the other way: the four-link
  model's ``"measured"`` restitution (``archquake.fourlink.impact``) measures c_v on the rigid
  blocks (``archquake.rigid_blocks.impacts``), and no other four-link module imports the blocks;
- geometry and ground motions import neither model;
- the studies import no model's own module (``archquake.fourlink.*``, ``archquake.rigid_blocks.*``):
  they hold an ``archquake.models.ModelSpec`` and ask the model protocol, never which model runs;
  the comparison of the two models (``archquake.studies.comparison``) is the one exception;
- the leaves (command line, report, plotting, the interactive page) are imported by no other
  module, and no module imports the package root;
- the two reports (the paper's and the assessment) import nothing of each other: what both use
  lies beside them in ``archquake.report``;
- the interactive page reaches nothing of the command line: both describe structures and ground
  motions through the library (``archquake.geometry.spec``, ``archquake.ground_motion.spec``);
- no module imports a private name (``_name``) of another module.

Each rule is a function of the import graph, so the test also shows that it flags a violation.
"""

import ast
from pathlib import Path

import pytest

from import_graph import ROOT, package_imports

MODELS = ("archquake.fourlink", "archquake.rigid_blocks")
LEAVES = ("archquake.cli", "archquake.report", "archquake.plotting",
          "archquake.rigid_blocks.plotting", "archquake.app", "archquake.__main__")
REPORTS = ("archquake.report.paper", "archquake.report.assess")
BLOCKS_RESTITUTION = ("archquake.fourlink.impact", "archquake.rigid_blocks.impacts")
"""The declared exception: the edge from the four-link model to the rigid blocks."""
COMPARISON = "archquake.studies.comparison"
"""The one study that imports both models' own modules: it compares them."""


def _within(module: str, package: str) -> bool:
    return module == package or module.startswith(package + ".")


def _reach(graph: dict[str, set[str]], start: str) -> set[str]:
    """Modules ``start`` imports, directly or through others."""
    seen, stack = set(), [start]
    while stack:
        for nxt in graph.get(stack.pop(), ()):
            if nxt not in seen:
                seen.add(nxt)
                stack.append(nxt)
    return seen


def contract_violations(graph: dict[str, set[str]]) -> list[str]:
    """Every breach of the contract of the module docstring, as readable lines."""
    out = []
    for module in graph:
        reached = _reach(graph, module)
        if _within(module, "archquake.rigid_blocks"):
            out += [f"{module} reaches the four-link model through {m}" for m in sorted(reached)
                    if _within(m, "archquake.fourlink")]
        if _within(module, "archquake.fourlink"):
            out += [f"{module} imports the rigid blocks ({m})" for m in sorted(graph[module])
                    if _within(m, "archquake.rigid_blocks") and (module, m) != BLOCKS_RESTITUTION]
        for base in ("archquake.geometry", "archquake.ground_motion", "archquake.constants",
                     "archquake.limit_analysis"):
            if _within(module, base):
                out += [f"{module} reaches a model ({m})" for m in sorted(reached)
                        if any(_within(m, p) for p in MODELS)]
        if _within(module, "archquake.studies") and module != COMPARISON:
            out += [f"{module} imports a model's own module ({m})" for m in sorted(graph[module])
                    if any(_within(m, p) for p in MODELS)]
        for own, other in (REPORTS, REPORTS[::-1]):
            if _within(module, own):
                out += [f"{module} imports the other report ({m})" for m in sorted(graph[module])
                        if _within(m, other)]
        if _within(module, "archquake.app"):
            out += [f"{module} reaches the command line ({m})" for m in sorted(reached)
                    if _within(m, "archquake.cli")]
        if module != "archquake" and "archquake" in graph[module]:
            out.append(f"{module} imports the package root")
        if not any(_within(module, leaf) for leaf in LEAVES):
            out += [f"{module} imports the leaf {m}" for m in sorted(graph[module])
                    if any(_within(m, leaf) for leaf in LEAVES)]
    return out


def test_import_contract_holds():
    assert contract_violations(package_imports()) == []


@pytest.mark.parametrize("importer, imported", [
    ("archquake.rigid_blocks.solver", "archquake.fourlink.mechanism"),
    ("archquake.rigid_blocks.dynamics", "archquake.studies.fragility"),  # reaches the four links
    ("archquake.fourlink.time_history", "archquake.rigid_blocks.dynamics"),
    ("archquake.geometry.blocks", "archquake.rigid_blocks.assembly"),
    ("archquake.ground_motion.core", "archquake.fourlink.engine"),
    ("archquake.execution", "archquake"),
    ("archquake.studies.fragility", "archquake.plotting"),
    ("archquake.studies.fragility", "archquake.rigid_blocks.dynamics"),
    ("archquake.studies.record_outcomes", "archquake.fourlink.engine"),
    ("archquake.studies.failure_domain", "archquake.fourlink"),
    ("archquake.report.assess.text", "archquake.report.paper.text"),
    ("archquake.app.inputs", "archquake.cli.options"),
    ("archquake.app.tasks", "archquake.cli.output"),
])
def test_contract_flags_a_violation(importer, imported):
    graph = package_imports()
    assert importer in graph and imported in graph
    graph[importer] = graph[importer] | {imported}
    assert contract_violations(graph), f"{importer} -> {imported} was not flagged"


def test_the_comparison_alone_may_import_the_models():
    graph = package_imports()
    graph[COMPARISON] = graph[COMPARISON] | {"archquake.fourlink.impact",
                                             "archquake.rigid_blocks.dynamics"}
    assert contract_violations(graph) == []


def test_the_declared_exception_is_the_only_edge_between_the_models():
    graph = package_imports()
    edges = {(a, b) for a, targets in graph.items() for b in targets
             if any(_within(a, p) for p in MODELS) and any(_within(b, p) for p in MODELS)
             and _within(a, MODELS[0]) != _within(b, MODELS[0])}
    assert edges == {BLOCKS_RESTITUTION}


def private_imports(src: Path = ROOT / "src") -> list[str]:
    """``from X import _name`` across modules of the package (``__version__`` is public)."""
    out = []
    for path in sorted((src / "archquake").glob("**/*.py")):
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom) and node.level:
                names = [a.name for a in node.names
                         if a.name.startswith("_") and not a.name.startswith("__")]
                out += [f"{path.relative_to(src)}: {node.module}.{n}" for n in names]
    return out


def test_no_module_imports_a_private_name_of_another():
    assert private_imports() == []


def test_private_import_check_flags_one(tmp_path):
    package = tmp_path / "archquake"
    package.mkdir()
    (package / "a.py").write_text("def _helper():\n    return 1\n")
    (package / "b.py").write_text("from .a import _helper\n")
    assert private_imports(tmp_path) == ["archquake/b.py: a._helper"]


def test_python_dash_m_archquake_answers_version():
    import subprocess
    import sys

    from archquake import __version__

    done = subprocess.run([sys.executable, "-m", "archquake", "--version"], capture_output=True,
                          text=True, cwd=ROOT, env={"PYTHONPATH": str(ROOT / "src")})
    assert done.returncode == 0, done.stderr
    assert __version__ in done.stdout
