"""The paper's report (``archquake reproduce``): every table and figure of the paper,
regenerated beside the paper's values.

- :mod:`~archquake.report.paper.parts`: the parts of the reproduction, each a function of the
  settings and of the values it needs, returning values (every arch built once, as its
  :class:`~archquake.fourlink.FourLinkModel`);
- :mod:`~archquake.report.paper.figures`: the figures, drawn from those values;
- :mod:`~archquake.report.paper.text`: the captions, paragraphs and table rows, written from them;
- :mod:`~archquake.report.paper.settings`: :class:`ReproductionSettings` and the report's fixed
  choices;
- :mod:`~archquake.report.paper.reproduction`: :func:`reproduce`, which runs the parts in order
  and writes ``report.html``, ``report.md``, ``results.json`` and the figures.

The rendering, the formatters and the timed steps are those of every report
(:mod:`archquake.report`).
"""

from .reproduction import STEPS, Reproduction, reproduce
from .settings import ReproductionSettings

__all__ = ["STEPS", "Reproduction", "ReproductionSettings", "reproduce"]
