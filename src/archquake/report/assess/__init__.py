"""The assessment of one structure (``archquake assess``): the paper's method and both models
applied to it, against real records, in one report an engineer can read, check and file.

- :mod:`~archquake.report.assess.parts`: the parts under the structure's own weight and under
  pulses (limit analysis, four-link mechanisms, both models' failure domains, irregularity), each
  a function of the structure, the settings and the values it needs, returning values;
- :mod:`~archquake.report.assess.records`: the record-based fragility and the check of the two
  models under the records;
- :mod:`~archquake.report.assess.figures`: the figures, drawn from the parts' values;
- :mod:`~archquake.report.assess.text`: the verdict, summary, captions and table rows, written
  from ``results.json``;
- :mod:`~archquake.report.assess.settings`: :class:`AssessmentSettings` and the report's fixed
  choices;
- :mod:`~archquake.report.assess.assessment`: :func:`assess`, which runs the parts in order and
  writes ``report.html``, ``report.md``, ``results.json``, the figures and the NRML files.

The rendering, the formatters and the timed steps are those of every report
(:mod:`archquake.report`).
"""

from .assessment import Assessment, assess, choose_suite
from .settings import AssessmentSettings

__all__ = ["Assessment", "AssessmentSettings", "assess", "choose_suite"]
