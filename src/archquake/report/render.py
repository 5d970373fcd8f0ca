"""A report as a value, and its files: self-contained HTML, Markdown beside the figures, JSON.

A report is a :class:`Document`: a title and :class:`Section` s of blocks -- a
:class:`Paragraph`, a :class:`Bullets` list, a :class:`Table` (a header and rows of strings) or a
:class:`Figure` (a PNG file beside the report, its label, caption and verdict).
:func:`write_html` embeds every figure (base64), so the page opens offline;
:func:`write_markdown` links them; :func:`save` writes a figure's PNG beside them.
:func:`jsonable` turns a report's numbers into plain JSON values and :func:`environment` records
what ran them. Nothing here knows which report it writes.

>>> doc = Document("Example", "An example", (Section("Numbers", (
...     Paragraph("Two numbers."), Table(("a", "b"), (("1", "2"),)))),))
>>> print(markdown(doc))
# An example
<BLANKLINE>
## Numbers
<BLANKLINE>
Two numbers.
<BLANKLINE>
| a | b |
|---|---|
| 1 | 2 |
<BLANKLINE>
"""

from __future__ import annotations

import base64
import html
import math
import platform
import sys
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .._version import __version__


@dataclass(frozen=True)
class Paragraph:
    """A paragraph of plain text.

    Attributes
    ----------
    text : str
    kind : str or None
        A style of the HTML page for it (a class of :attr:`Document.style`; None: plain).
    """

    text: str
    kind: str | None = None


@dataclass(frozen=True)
class Bullets:
    """A list of plain-text items.

    Attributes
    ----------
    items : sequence of str
    """

    items: Sequence


@dataclass(frozen=True)
class Table:
    """A table of strings.

    Attributes
    ----------
    header : sequence of str
    rows : sequence of sequence of str
    """

    header: Sequence
    rows: Sequence


@dataclass(frozen=True)
class Figure:
    """A figure of a report: a PNG file beside it, with its label, caption and verdict.

    Attributes
    ----------
    file : str
        File name of the PNG, relative to the report's folder.
    label : str
        Shown in bold before the caption (for the paper's report: the paper's figure, "Fig. 2").
    caption : str
    agrees : bool or None
        Whether the figure agrees with its reference (None: nothing to compare).
    """

    file: str
    label: str
    caption: str
    agrees: bool | None

    @property
    def verdict(self) -> str:
        """``"agrees"``, ``"differs"`` or ``"no comparison"``."""
        if self.agrees is None:
            return "no comparison"
        return "agrees" if self.agrees else "differs"

    @property
    def stem(self) -> str:
        """The file name without its suffix (the figure's key in ``results.json``)."""
        return Path(self.file).stem


@dataclass(frozen=True)
class Section:
    """A section: a title and its blocks in order.

    Attributes
    ----------
    title : str
    blocks : sequence of Paragraph, Table or Figure
    """

    title: str
    blocks: Sequence


@dataclass(frozen=True)
class Document:
    """A report.

    Attributes
    ----------
    title : str
        The page's title (the browser's tab).
    heading : str
        The report's heading.
    sections : sequence of Section
    verdicts : bool
        Show each figure's verdict (agrees, differs, no comparison) after its label; a report
        that compares nothing with a reference leaves them out.
    style : str
        CSS added to :data:`CSS` in the HTML page (the classes of its paragraphs).
    """

    title: str
    heading: str
    sections: Sequence
    verdicts: bool = True
    style: str = ""


# ------------------------------------------------------------------------------ HTML
CSS = ("body{font-family:sans-serif;max-width:1100px;margin:2em auto;line-height:1.4}"
       "table{border-collapse:collapse;margin:1em 0;font-size:0.9em}"
       "td,th{border:1px solid #bbb;padding:3px 8px;text-align:left}"
       "th{background:#eee}figure{margin:1.5em 0}img{max-width:100%}"
       "figcaption{font-size:0.92em;color:#333}.agrees{color:#070}.differs{color:#b00}")
"""The style of the HTML report (verdicts in green and red)."""


def html_table(table: Table) -> str:
    """A table as HTML.

    Parameters
    ----------
    table : Table

    Returns
    -------
    str
    """
    head = "".join(f"<th>{html.escape(h)}</th>" for h in table.header)
    body = "".join("<tr>" + "".join(f"<td>{html.escape(str(c))}</td>" for c in row) + "</tr>"
                   for row in table.rows)
    return f"<table><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>"


def html_figure(figure: Figure, directory: Path, verdict: bool = True) -> str:
    """A figure as HTML, its PNG embedded (base64).

    Parameters
    ----------
    figure : Figure
    directory : Path
        Where the PNG is.
    verdict : bool
        Show the figure's verdict after its label.

    Returns
    -------
    str
    """
    data = base64.b64encode((Path(directory) / figure.file).read_bytes()).decode("ascii")
    shown = ""
    if verdict:
        word = figure.verdict
        shown = f" (<span class='{word.split()[0]}'>{word}</span>)"
    return (f"<figure><img alt='{html.escape(figure.label)}' "
            f"src='data:image/png;base64,{data}'><figcaption><b>{figure.label}"
            f"</b>{shown}. {html.escape(figure.caption)}</figcaption></figure>")


def write_html(path, document: Document, directory=None) -> Path:
    """Write ``document`` as one self-contained HTML page.

    Parameters
    ----------
    path : str or Path
        The page.
    document : Document
    directory : str or Path, optional
        Where the figures' PNG files are (default: the page's folder).

    Returns
    -------
    Path
    """
    path = Path(path)
    directory = path.parent if directory is None else Path(directory)
    parts = ["<!DOCTYPE html><html><head><meta charset='utf-8'><title>"
             f"{document.title}</title><style>{CSS}{document.style}</style></head><body>",
             f"<h1>{document.heading}</h1>"]
    for section in document.sections:
        parts.append(f"<h2>{html.escape(section.title)}</h2>")
        for block in section.blocks:
            if isinstance(block, Paragraph):
                kind = "" if block.kind is None else f" class='{html.escape(block.kind)}'"
                parts.append(f"<p{kind}>{html.escape(block.text)}</p>")
            elif isinstance(block, Bullets):
                parts.append("<ul>" + "".join(f"<li>{html.escape(str(item))}</li>"
                                              for item in block.items) + "</ul>")
            elif isinstance(block, Table):
                parts.append(html_table(block))
            else:
                parts.append(html_figure(block, directory, document.verdicts))
    parts.append("</body></html>")
    path.write_text("\n".join(parts), encoding="utf-8")
    return path


# ------------------------------------------------------------------------------ Markdown
def markdown_table(table: Table) -> str:
    """A table as Markdown (a ``|`` in a cell escaped).

    Parameters
    ----------
    table : Table

    Returns
    -------
    str
    """
    def cell(c):
        return str(c).replace("|", "\\|")

    lines = ["| " + " | ".join(cell(h) for h in table.header) + " |",
             "|" + "---|" * len(table.header)]
    lines += ["| " + " | ".join(cell(c) for c in row) + " |" for row in table.rows]
    return "\n".join(lines)


def markdown(document: Document) -> str:
    """``document`` as Markdown, its figures linked by file name.

    Parameters
    ----------
    document : Document

    Returns
    -------
    str
    """
    parts = [f"# {document.heading}", ""]
    for section in document.sections:
        parts += [f"## {section.title}", ""]
        for block in section.blocks:
            if isinstance(block, Paragraph):
                parts += [block.text, ""]
            elif isinstance(block, Bullets):
                parts += [f"- {item}" for item in block.items] + [""]
            elif isinstance(block, Table):
                parts += [markdown_table(block), ""]
            else:
                verdict = f" ({block.verdict})" if document.verdicts else ""
                parts += [f"![{block.label}]({block.file})", "",
                          f"**{block.label}**{verdict}. {block.caption}", ""]
    return "\n".join(parts)


def write_markdown(path, document: Document) -> Path:
    """Write ``document`` as Markdown (the figures' PNG files belong beside it).

    Parameters
    ----------
    path : str or Path
    document : Document

    Returns
    -------
    Path
    """
    path = Path(path)
    path.write_text(markdown(document), encoding="utf-8")
    return path


# ------------------------------------------------------------------------------ figures
DPI = 110
"""Resolution of the report's PNG figures [dots per inch]."""


def save(figure, directory, name: str) -> str:
    """Write ``figure`` as PNG into ``directory`` and close it.

    Parameters
    ----------
    figure : matplotlib.figure.Figure
    directory : str or Path
    name : str
        File name.

    Returns
    -------
    str
        ``name``.
    """
    import matplotlib.pyplot as plt

    figure.savefig(Path(directory) / name, dpi=DPI)
    plt.close(figure)
    return name


# ------------------------------------------------------------------------------ JSON
def jsonable(obj):
    """Plain JSON values: arrays to lists, NaN to None, tuple keys to strings.

    Parameters
    ----------
    obj : object
        Nested dicts, lists, tuples, arrays and numbers.

    Returns
    -------
    object

    Examples
    --------
    >>> jsonable({("NA", 0.4): np.array([1.0, np.nan])})
    {"('NA', 0.4)": [1.0, None]}
    """
    if isinstance(obj, dict):
        return {str(k): jsonable(v) for k, v in obj.items()}
    if isinstance(obj, list | tuple):
        return [jsonable(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return jsonable(obj.tolist())
    if isinstance(obj, np.generic):
        return jsonable(obj.item())
    if isinstance(obj, float) and not math.isfinite(obj):
        return None
    return obj


def environment() -> dict:
    """What ran a report: archquake, Python, the platform, the numerical libraries, the
    processors.

    Returns
    -------
    dict
    """
    import os

    import matplotlib
    import numba
    import scipy

    return {"archquake": __version__, "python": sys.version.split()[0],
            "platform": platform.platform(), "numpy": np.__version__, "scipy": scipy.__version__,
            "numba": numba.__version__, "matplotlib": matplotlib.__version__,
            "processors": os.cpu_count()}


__all__ = ["CSS", "DPI", "Bullets", "Document", "Figure", "Paragraph", "Section", "Table",
           "environment", "html_figure", "html_table", "jsonable", "markdown", "markdown_table",
           "save", "write_html", "write_markdown"]
