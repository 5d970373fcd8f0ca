"""Small Sphinx helpers of the archquake documentation.

- ``.. exports:: package`` -- a table of the names a package exports (its ``__all__``), each
  linked to the page of the module that defines it, so a re-exported name is documented once.
- ``.. command-line-help::`` -- the ``--help`` text of ``archquake`` and of every subcommand, as
  argparse prints it (never parsed as reStructuredText, so a help string cannot break the build).
- references by import: a Python reference that Sphinx cannot resolve by name is looked up the
  way Python would find it from the module of the docstring (its imports, its package, absolute
  names) and linked to the page of the object it reaches -- or of its nearest documented parent
  (a class for an undocumented field). An object outside archquake that imports is set as plain
  text (the build is offline: no other project's inventory to link to). A name that does not
  import at all stays a warning, so a reference to something that no longer exists fails the build.
- summaries in their own scope: a docstring's first sentence in a summary table is resolved as in
  its own module (``:func:`simulate``` of a module docstring, listed on another page).
- a module is a module: autosummary finds ``package.name`` with ``getattr(package, "name")``, so
  a submodule shadowed by a function of the same name that the package re-exports
  (``archquake.ground_motion.stochastic``) would be documented as that function, and the module
  not at all; here a dotted name that is an imported module is that module.
- ``archquake_docstring_fixes`` (conf.py): corrections applied to a docstring when it is read,
  for a module whose source cannot be edited at the moment; one that no longer applies fails the
  build, so it is removed once the source is corrected.
- :func:`example_argv` -- the command line the gallery gives every example: ``--quick`` and an
  output directory under ``docs/_build``.
"""

from __future__ import annotations

import importlib
import inspect
import itertools
import os
import sys
from pathlib import Path

from docutils import nodes
from docutils.parsers.rst import directives
from docutils.statemachine import StringList
from sphinx.pycode import ModuleAnalyzer
from sphinx.util import logging
from sphinx.util.docutils import SphinxDirective
from sphinx.util.nodes import make_refnode

logger = logging.getLogger(__name__)

_extract_summary = None  # Sphinx's own, wrapped by extract_summary below
EXAMPLE_OUTPUT = Path(__file__).resolve().parents[1] / "_build" / "example-output"


def example_argv(gallery_conf, script_vars) -> list[str]:
    """Arguments of an example run by the gallery: the reduced size, figures under ``_build``.

    The gallery runs an example in its own folder; the output folder is given relative to it, so
    that what the example prints does not show where the site was built.
    """
    EXAMPLE_OUTPUT.mkdir(parents=True, exist_ok=True)
    here = Path(script_vars["src_file"]).resolve().parent
    return ["--quick", "--out", os.path.relpath(EXAMPLE_OUTPUT, here)]


def _is_alias(name: str, obj) -> bool:
    """Whether ``obj`` is a class or function reached under a second name (``second =
    first``): documented as a constant of its module, whose docstring refers to the one
    documented object."""
    own = getattr(getattr(obj, "py_func", obj), "__name__", name)
    return (inspect.isclass(obj) or callable(obj)) and own != name


def _defining_module(package: str, name: str, obj) -> tuple[str | None, list[str]]:
    """The module that defines ``obj``, exported by ``package`` as ``name``, and its docstring."""
    if ((inspect.isclass(obj) or inspect.isfunction(obj) or hasattr(obj, "py_func"))
            and not _is_alias(name, obj)):
        return obj.__module__, (inspect.getdoc(obj) or "").splitlines()
    # data: the module whose source documents the name (``NAME = ...`` and a docstring), first
    # among the package's own modules, then anywhere in archquake (a package re-exports a
    # constant of :mod:`archquake.constants`)
    pkg = importlib.import_module(package)
    top = importlib.import_module(package.partition(".")[0])
    own = sorted(_submodules(pkg))
    for modname in [*own, *(m for m in sorted(_submodules(top)) if m not in own)]:
        module = importlib.import_module(modname)
        if getattr(module, name, None) is not obj:
            continue
        try:
            documented = ModuleAnalyzer.for_module(modname).find_attr_docs()
        except Exception:  # noqa: BLE001 -- no source: not the defining module
            continue
        if ("", name) in documented:
            return modname, list(documented[("", name)])
    return None, []


def _submodules(pkg) -> list[str]:
    import pkgutil

    names = [pkg.__name__]
    if hasattr(pkg, "__path__"):
        for info in pkgutil.walk_packages(pkg.__path__, prefix=pkg.__name__ + "."):
            if not any(part.startswith("_") for part in info.name.split(".")):
                names.append(info.name)
    return names


class Exports(SphinxDirective):
    """``.. exports:: package``: the names in ``package.__all__`` with links to their pages."""

    required_arguments = 1
    has_content = False

    def run(self):
        from sphinx import addnodes
        from sphinx.ext import autosummary

        package = self.arguments[0]
        module = importlib.import_module(package)
        names = [n for n in getattr(module, "__all__", ()) if not n.startswith("_")]
        if not names or not hasattr(module, "__path__"):
            return []
        lines = [".. list-table::", "   :widths: 35 65", "   :class: exports", ""]
        homes = []
        for name in names:
            obj = getattr(module, name)
            home, doc = _defining_module(package, name, obj)
            if home is None:
                raise self.error(f"{package}.{name}: no module of {package} documents it "
                                 "(a constant needs a docstring where it is defined)")
            homes.append(home)
            summary = autosummary.extract_summary(doc, self.state.document.settings)
            target = name if _is_alias(name, obj) else getattr(obj, "__qualname__", name)
            lines += [f"   * - :py:obj:`{name} <{home}.{target}>`",
                      f"     - {summary}"]
        container = nodes.container()
        self.state.nested_parse(StringList(lines, source=f"exports of {package}"),
                                self.content_offset, container)
        rows = list(container.findall(nodes.row))
        for home, row in zip(homes, rows, strict=True):  # summaries resolve in their own module
            for xref in row.findall(addnodes.pending_xref):
                xref["py:module"] = home
        rubric = nodes.rubric(text=f"Names exported by {package}")
        return [rubric, *container.children]


class CommandLineHelp(SphinxDirective):
    """``.. command-line-help::``: ``archquake --help`` and every subcommand's ``--help``."""

    has_content = False
    option_spec = {"module": directives.unchanged}

    def run(self):
        module = importlib.import_module(self.options.get("module", "archquake.cli"))
        width = os.environ.get("COLUMNS")
        os.environ["COLUMNS"] = "80"  # argparse wraps to the terminal: the same on every machine
        try:
            parser = module.build_parser()
            sections = self._sections(parser)
        finally:
            if width is None:
                del os.environ["COLUMNS"]
            else:
                os.environ["COLUMNS"] = width
        return sections

    @staticmethod
    def _sections(parser):
        sections = [("archquake", parser)]
        for action in parser._actions:  # argparse keeps its subparsers here
            choices = getattr(action, "choices", None)
            if isinstance(choices, dict):
                sections += [(f"archquake {name}", sub) for name, sub in choices.items()]
        out = []
        for title, sub in sections:
            section = nodes.section(ids=[nodes.make_id(f"command {title}")])
            section += nodes.title(text=title)
            help_text = sub.format_help()
            section += nodes.literal_block(help_text, help_text, language="text")
            out.append(section)
        return out


def _walk(obj, parts):
    for part in parts:
        obj = getattr(obj, part)
    return obj


def _import_path(dotted: str):
    """The object at ``dotted`` (``package.module.Class.attr``), imported; KeyError if none."""
    parts = dotted.split(".")
    for i in range(len(parts), 0, -1):
        modname = ".".join(parts[:i])
        try:
            module = importlib.import_module(modname)
        except ImportError:
            continue
        try:
            return _walk(module, parts[i:])
        except AttributeError:
            break
    raise KeyError(dotted)


def _field(owner_path: str, attr: str):
    """A dataclass field (or annotated attribute) ``attr`` of the class at ``owner_path``."""
    try:
        owner = _import_path(owner_path)
    except KeyError:
        return False
    return inspect.isclass(owner) and any(attr in getattr(k, "__annotations__", {})
                                          for k in owner.__mro__)


def _lookup(scope: str | None, target: str):
    """Find ``target`` as Python would from module ``scope``: in its namespace (its imports
    included), as a submodule of it or of its packages, or as an absolute name."""
    scopes = []
    if scope:
        parts = scope.split(".")
        scopes = [".".join(parts[:i]) for i in range(len(parts), 0, -1)]
    for module_name in scopes:
        module = importlib.import_module(module_name)
        try:
            return _walk(module, target.split(".")), f"{module_name}.{target}"
        except AttributeError:
            pass
        try:  # a submodule shadowed in the package namespace by a name it re-exports
            return _import_path(f"{module_name}.{target}"), f"{module_name}.{target}"
        except KeyError:
            pass
    try:
        return _import_path(target), target
    except KeyError:
        pass
    owner, _, attr = target.rpartition(".")
    for module_name in [*scopes, ""]:  # a field of a class: declared, not a class attribute
        owner_path = f"{module_name}.{owner}" if module_name else owner
        if owner and _field(owner_path, attr):
            return None, f"{owner_path}.{attr}"
    return None, None


def _canonical(obj, path: str, domain) -> str:
    """Where ``obj``, reached as ``path``, is documented (or would be)."""
    import types

    if obj is None:  # a declared field: documented, if at all, under its class
        owner_path, _, attr = path.rpartition(".")
        return f"{_canonical(_import_path(owner_path), owner_path, domain)}.{attr}"
    if isinstance(obj, types.ModuleType):
        return obj.__name__
    func = getattr(obj, "py_func", obj)  # a compiled (numba) function documents its Python one
    qualname = getattr(func, "__qualname__", None)
    module = getattr(func, "__module__", None)
    if qualname and module and (inspect.isclass(func) or inspect.isfunction(func)):
        return f"{module}.{qualname}"
    # a method, property or data reached through its owner: the owner's canonical name + attr
    owner_path, _, attr = path.rpartition(".")
    if owner_path:
        try:
            owner = _import_path(owner_path)
        except KeyError:
            owner = None
        if owner is not None and not isinstance(owner, types.ModuleType):
            return f"{_canonical(owner, owner_path, domain)}.{attr}"
    # module-level data: the documented entry of that name that is this very object
    for name, entry in domain.objects.items():
        if name.rsplit(".", 1)[-1] != attr or entry.objtype != "data":
            continue
        try:
            if _import_path(name) is obj:
                return name
        except KeyError:
            continue
    return path


def resolve_by_import(app, env, node, contnode):
    """``missing-reference``: resolve a Python reference by importing what it names."""
    if node.get("refdomain") != "py":
        return None
    target = node["reftarget"].lstrip(".~")
    obj, path = _lookup(node.get("py:module"), target)
    if path is None and node.get("py:class"):
        obj, path = _lookup(node.get("py:module"), f"{node['py:class']}.{target}")
    domain = env.get_domain("py")
    if path is None:
        return _unique(app, node, contnode, domain, target)
    name = _canonical(obj, path, domain)
    if not name.startswith("archquake"):
        return contnode  # exists, but its documentation is not part of this site
    while name:
        entry = domain.objects.get(name)
        if entry is not None:
            return make_refnode(app.builder, node["refdoc"], entry.docname, entry.node_id,
                                contnode, name)
        name = name.rpartition(".")[0]
    return None


def _unique(app, node, contnode, domain, target: str):
    """The one documented archquake object whose name ends with ``target``, if there is one.

    For a name used out of its module's scope: a summary of a docstring shown in a table on
    another page, or a function a module imports inside a function. Two candidates: no link.
    """
    suffix = "." + target
    found = [name for name in domain.objects if name.endswith(suffix)
             and name.startswith("archquake.")]
    if len(found) != 1:
        return None
    entry = domain.objects[found[0]]
    return make_refnode(app.builder, node["refdoc"], entry.docname, entry.node_id, contnode,
                        found[0])


ABBREVIATIONS = ("et al.", "e.g.", "i.e.", "vs.", "cf.", "Sect.", "Sects.", "eq.", "eqs.", "Eq.",
                 "Eqs.", "Fig.", "Figs.", "Ref.", "approx.")
"""A summary does not end after one of these (the paper is cited as "[paper, Sect. 2, eq. (1)]")."""


def extract_summary(doc, settings) -> str:
    """The first sentence of a docstring, for the summary tables of autosummary.

    Sphinx cuts the first paragraph at the first period followed by a space, unless the cut ends
    with one of four abbreviations, and checks the cut by parsing the whole paragraph instead of
    the cut: a period inside an inline literal (``joints 0 .. n``) leaves half a literal and a
    docutils warning, and "[paper, Sect. 2]" ends the sentence at "Sect.". Here the summary grows
    by a sentence until it ends with no abbreviation and its own markup parses cleanly.
    """
    from sphinx.ext import autosummary

    summary = _extract_summary(doc, settings)
    lines = [line.strip() for line in doc]
    while lines and not lines[0]:
        lines.pop(0)
    stanza = " ".join(itertools.takewhile(bool, lines))
    if not stanza.startswith(summary.rstrip(".")):
        return summary  # a heading or a block, not a sentence: Sphinx's choice stands
    sentences = autosummary.periods_re.split(stanza)
    for i in range(1, len(sentences) + 1):
        candidate = ". ".join(sentences[:i]).rstrip(".") + "."
        if i < len(sentences) and candidate.endswith(ABBREVIATIONS):
            continue
        if _parses(autosummary, candidate, settings):
            return candidate
    return summary


def _parses(autosummary, text: str, settings) -> bool:
    node = autosummary._parse_summary([text], settings)
    return not any(node.findall(nodes.system_message))


def _scoped_autosummary():
    from sphinx import addnodes
    from sphinx.ext import autosummary

    class ScopedAutosummary(autosummary.Autosummary):
        """autosummary whose summaries resolve their references in their own module."""

        def get_table(self, items):
            result = super().get_table(items)
            rows = [row for node in result for row in node.findall(nodes.row)]
            for (_, _, _, real_name), row in zip(items, rows, strict=False):
                module = _module_of(real_name)
                for xref in row.findall(addnodes.pending_xref):
                    if xref.get("refdomain") == "py" and module:
                        xref["py:module"] = module
            return result

    return ScopedAutosummary


def _module_of(name: str) -> str | None:
    """The longest importable module prefix of ``name``."""
    parts = name.split(".")
    for i in range(len(parts), 0, -1):
        try:
            importlib.import_module(".".join(parts[:i]))
        except ImportError:
            continue
        return ".".join(parts[:i])
    return None


def _prefer_modules(import_by_name):
    """Wrap autosummary's ``_import_by_name`` so that an imported module's name gives the module."""

    def _import_by_name(name, *args, **kwargs):
        obj, parent, modname = import_by_name(name, *args, **kwargs)
        module = sys.modules.get(name)
        if module is not None and obj is not module:
            return module, None, name
        return obj, parent, modname

    _import_by_name.wrapped = import_by_name
    return _import_by_name


def fix_docstring(app, what, name, obj, options, lines):
    """``autodoc-process-docstring``: apply ``archquake_docstring_fixes`` to ``name``."""
    fixes = [(old, new) for target, old, new in app.config.archquake_docstring_fixes
             if target == name]
    if not fixes:
        return
    text = "\n".join(lines)
    for old, new in fixes:
        if old not in text:
            logger.warning("archquake_docstring_fixes: %r is no longer in the docstring of %s; "
                           "correct the docstring in the source and delete this entry of "
                           "conf.py", old, name)
            continue
        text = text.replace(old, new)
    lines[:] = text.split("\n")


def setup(app):
    from sphinx.ext import autosummary

    app.add_config_value("archquake_docstring_fixes", [], "env")
    app.connect("autodoc-process-docstring", fix_docstring, priority=100)
    app.add_directive("autosummary", _scoped_autosummary(), override=True)

    global _extract_summary
    if autosummary.extract_summary is not extract_summary:
        _extract_summary = autosummary.extract_summary
        autosummary.extract_summary = extract_summary
    if not hasattr(autosummary._import_by_name, "wrapped"):
        autosummary._import_by_name = _prefer_modules(autosummary._import_by_name)
    app.connect("missing-reference", resolve_by_import)
    app.add_directive("exports", Exports)
    app.add_directive("command-line-help", CommandLineHelp)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
