"""Reports: the paper's tables and figures regenerated beside its values (:mod:`.paper`,
``archquake reproduce``) and the assessment of one structure (:mod:`.assess`,
``archquake assess``).

Each report is a subpackage, computed, drawn, written and rendered apart, so that each piece can
be rerun, tested and reused:

- ``parts``: each a function of the settings and of the values it needs, returning values;
- ``figures``: the figures, drawn from those values;
- ``text``: the captions, paragraphs and table rows, written from them;
- ``settings``: the report's settings and fixed choices;
- :mod:`~archquake.report.paper.reproduction` and :mod:`~archquake.report.assess.assessment`:
  :func:`reproduce` and :func:`~archquake.report.assess.assess`, which run the parts in order
  and write ``report.html``, ``report.md``, ``results.json`` and the figures.

What both reports use lies beside them:

- :mod:`~archquake.report.render`: a report as a value
  (:class:`~archquake.report.render.Document`) and its files: self-contained HTML, Markdown,
  JSON, the figures' PNG;
- :mod:`~archquake.report.formatting`: numbers, differences and outcomes in words;
- :mod:`~archquake.report.running`: the steps timed under a progress bar, long tasks on a second
  process.

The science a report states is the library's (:mod:`archquake.limit_analysis`,
:mod:`archquake.studies`): a user gets the same numbers without writing a report. The names below
are imported on first use (PEP 562).
"""

# name -> module that defines it (imported on first use)
_LAZY = {
    "ReproductionSettings": "paper.settings",
    "ARCH_NAMES": "paper.settings",
    "ARCH_COLOURS": "paper.settings",
    "RECORD_LEVELS": "paper.settings",
    "AGREEMENT_BAND": "paper.settings",
    "PHI_TOLERANCE": "paper.settings",
    "Reproduction": "paper.reproduction",
    "reproduce": "paper.reproduction",
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
