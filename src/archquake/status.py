"""Outcome classes of a dynamic analysis, shared by the compiled engine, results and tables.

The compiled engine (:mod:`archquake.fourlink.engine`) returns these codes as integers, a time
history's :class:`~archquake.fourlink.time_history.Outcome` carries them as :class:`Status`, and the
tables of :mod:`archquake.studies.fragility` store them as integers in their ``status`` column.
Outputs meant for people and JSON use the lower-case name, :attr:`Status.label` (``"rest"``,
``"recovery"``, ``"collapse"``).

This module imports nothing heavy: the command line and result readers use it without the
compiler.
"""

from __future__ import annotations

import enum


class Status(enum.IntEnum):
    """Outcome of one dynamic analysis [paper, Sect. 5.3].

    ``REST`` (0): the ground never activated a mechanism (its acceleration stayed between
    ``-k_l g`` and ``k_r g``, eq. (2) of the paper); ``RECOVERY`` (1): the arch moved and came
    back (it rocks with less and less energy, or comes to rest); ``COLLAPSE`` (2): the linkage
    reaches its kinematic limit (the "ever-increasing" rotation of Sect. 5.3.1 of the paper).
    ``UNDECIDED`` (-1) is the engine's code while an analysis runs; no four-link result carries
    it, a rigid-block outcome does when its run ended undecided
    (:class:`archquake.rigid_blocks.BlockOutcome`).

    Members are integers (the engine's codes, the tables' column); ``str()`` and formatting give
    the label. Comparing a member with a string raises ``TypeError`` instead of answering
    ``False``: write ``status is Status.COLLAPSE`` (or ``status.label == "collapse"``).
    """

    UNDECIDED = -1
    REST = 0
    RECOVERY = 1
    COLLAPSE = 2

    @property
    def label(self) -> str:
        """Lower-case name: ``"rest"``, ``"recovery"``, ``"collapse"`` (``"undecided"``)."""
        return self.name.lower()

    def __str__(self) -> str:
        return self.label

    def __format__(self, spec: str) -> str:
        return format(self.label, spec)

    def __eq__(self, other):
        if isinstance(other, str):
            raise TypeError(f"a Status is compared with Status members, not with the string "
                            f"{other!r} (use Status.{other.upper()} or .label)")
        return int.__eq__(self, other)

    def __ne__(self, other):
        return not self.__eq__(other)

    __hash__ = int.__hash__
