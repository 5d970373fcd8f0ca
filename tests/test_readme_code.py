"""The README's Python code refers only to names it defines or imports, and every import
resolves. The README's blocks run studies of minutes (a fragility study of 40 arches, a
rigid-block failure curve), so they are checked statically here rather than run; the user
guide's blocks, which are small, run (tests/test_docs_code.py). A block that used an undefined
``arch`` and a module that no longer exists went unnoticed before this test."""

import ast
import builtins
import importlib
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
BLOCKS = re.findall(r"^```python\n(.*?)^```", (ROOT / "README.md").read_text(),
                    re.MULTILINE | re.DOTALL)


def test_the_readme_shows_python_code():
    assert len(BLOCKS) >= 5


def _defined_and_used(tree: ast.AST) -> tuple[set[str], list[ast.Name]]:
    defined = set(dir(builtins))
    used = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import | ast.ImportFrom):
            defined |= {(a.asname or a.name).split(".")[0] for a in node.names}
        elif isinstance(node, ast.FunctionDef | ast.ClassDef):
            defined.add(node.name)
            defined |= {a.arg for a in node.args.args} if hasattr(node, "args") else set()
        elif isinstance(node, ast.Lambda):
            defined |= {a.arg for a in node.args.args}
        elif isinstance(node, ast.Name):
            if isinstance(node.ctx, ast.Store | ast.Del):
                defined.add(node.id)
            else:
                used.append(node)
    return defined, used


@pytest.mark.parametrize("number", range(len(BLOCKS)), ids=lambda n: f"block{n + 1}")
def test_readme_block_defines_every_name_it_uses(number):
    tree = ast.parse(BLOCKS[number], f"README.md block {number + 1}")
    defined, used = _defined_and_used(tree)
    undefined = sorted({f"{n.id} (line {n.lineno})" for n in used if n.id not in defined})
    assert not undefined, f"README.md block {number + 1} uses undefined names: {undefined}"


@pytest.mark.parametrize("number", range(len(BLOCKS)), ids=lambda n: f"block{n + 1}")
def test_readme_block_imports_resolve(number):
    tree = ast.parse(BLOCKS[number])
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            module = importlib.import_module(node.module)
            missing = [a.name for a in node.names if not hasattr(module, a.name)]
            assert not missing, f"README.md block {number + 1}: {node.module} has no {missing}"
        elif isinstance(node, ast.Import):
            for alias in node.names:
                importlib.import_module(alias.name)
