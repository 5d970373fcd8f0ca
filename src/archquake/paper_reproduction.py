"""The former location of the paper's reproduction, now :mod:`archquake.report`.

Its names are re-exported from there, so that code written against this module keeps working:
:func:`~archquake.report.paper.reproduce` and :class:`~archquake.report.paper.Reproduction`
(:mod:`archquake.report.paper.reproduction`),
:class:`~archquake.report.paper.settings.ReproductionSettings` and the report's fixed choices
:data:`~archquake.report.paper.settings.AGREEMENT_BAND`,
:data:`~archquake.report.paper.settings.ARCH_COLOURS`,
:data:`~archquake.report.paper.settings.ARCH_NAMES`,
:data:`~archquake.report.paper.settings.PHI_TOLERANCE` and
:data:`~archquake.report.paper.settings.RECORD_LEVELS` (:mod:`archquake.report.paper.settings`).
New code imports them from :mod:`archquake.report`.
"""

from .report.paper import Reproduction, reproduce
from .report.paper.settings import (
    AGREEMENT_BAND,
    ARCH_COLOURS,
    ARCH_NAMES,
    PHI_TOLERANCE,
    RECORD_LEVELS,
    ReproductionSettings,
)

__all__ = ["AGREEMENT_BAND", "ARCH_COLOURS", "ARCH_NAMES", "PHI_TOLERANCE", "RECORD_LEVELS",
           "Reproduction", "ReproductionSettings", "reproduce"]
