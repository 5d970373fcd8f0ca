"""The former location of the paper's reproduction, now :mod:`archquake.report`."""

from .report.paper import Reproduction, reproduce
from .report.settings import (
    AGREEMENT_BAND,
    ARCH_COLOURS,
    ARCH_NAMES,
    PHI_TOLERANCE,
    RECORD_LEVELS,
    ReproductionSettings,
)

__all__ = ["AGREEMENT_BAND", "ARCH_COLOURS", "ARCH_NAMES", "PHI_TOLERANCE", "RECORD_LEVELS",
           "Reproduction", "ReproductionSettings", "reproduce"]
