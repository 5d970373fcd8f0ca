"""Reports: the paper's tables and figures regenerated beside its values (:func:`reproduce`).

A report is computed, drawn, written and rendered apart, so that each piece can be rerun,
tested and reused by another report:

- :mod:`~archquake.report.parts`: the parts of the paper's reproduction, each a function of the
  settings and of the values it needs, returning values (every arch built once, as its
  :class:`~archquake.fourlink.FourLinkModel`);
- :mod:`~archquake.report.figures`: the figures, drawn from those values;
- :mod:`~archquake.report.text`: the captions, paragraphs and table rows, written from them;
- :mod:`~archquake.report.render`: a report as a value (:class:`~archquake.report.render.Document`)
  and its files: self-contained HTML, Markdown, JSON;
- :mod:`~archquake.report.running`: the steps timed under a progress bar, long tasks on a second
  process;
- :mod:`~archquake.report.settings`: :class:`ReproductionSettings` and the report's fixed choices;
- :mod:`~archquake.report.paper`: :func:`reproduce`, which runs the parts in order and writes
  ``report.html``, ``report.md``, ``results.json`` and the figures (``archquake reproduce``).

The names below are imported on first use (PEP 562).
"""

# name -> module that defines it (imported on first use)
_LAZY = {
    "ReproductionSettings": "settings",
    "ARCH_NAMES": "settings",
    "ARCH_COLOURS": "settings",
    "RECORD_LEVELS": "settings",
    "AGREEMENT_BAND": "settings",
    "PHI_TOLERANCE": "settings",
    "Reproduction": "paper",
    "reproduce": "paper",
}


def __getattr__(name: str):
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module 'archquake.report' has no attribute {name!r}")
    from importlib import import_module

    value = getattr(import_module(f".{module}", __name__), name)
    globals()[name] = value
    return value


def __dir__():
    return sorted([*globals(), *_LAZY])


__all__ = ["AGREEMENT_BAND", "ARCH_COLOURS", "ARCH_NAMES", "PHI_TOLERANCE", "RECORD_LEVELS",
           "Reproduction", "ReproductionSettings", "reproduce"]
