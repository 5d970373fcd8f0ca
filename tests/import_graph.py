"""The import graph of the package, read from its source (for the architecture tests)."""

from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def package_imports() -> dict[str, set[str]]:
    """Modules of the package each module imports (at module level or inside a function; not
    under ``if TYPE_CHECKING``), from the source."""
    import ast

    src = ROOT / "src"
    files = sorted((src / "archquake").glob("**/*.py"))
    modules = {}
    for path in files:
        parts = list(path.relative_to(src).with_suffix("").parts)
        is_package = parts[-1] == "__init__"
        if is_package:
            parts = parts[:-1]
        modules[".".join(parts)] = (path, is_package)
    graph = {}
    for name, (path, is_package) in modules.items():
        package = name.split(".") if is_package else name.split(".")[:-1]
        found = set()
        stack = list(ast.parse(path.read_text()).body)
        while stack:
            node = stack.pop()
            if (isinstance(node, ast.If) and isinstance(node.test, ast.Name)
                    and node.test.id == "TYPE_CHECKING"):
                stack.extend(node.orelse)
                continue
            if isinstance(node, ast.ImportFrom) and node.level:
                base = package[: len(package) - node.level + 1]
                target = ".".join(base + ([node.module] if node.module else []))
                candidates = ([target] if node.module else [])
                candidates += [f"{target}.{a.name}" for a in node.names]
                found |= {c for c in candidates if c in modules}
            elif isinstance(node, ast.Import):
                found |= {a.name for a in node.names if a.name in modules}
            stack.extend(ast.iter_child_nodes(node))
        graph[name] = found - {name}
    return graph
