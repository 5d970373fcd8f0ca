"""Studies over many analyses, written against the model protocol
(:class:`archquake.models.StructuralModel`), so that either model runs them.

:mod:`.failure_domain` (outcome regions over pulse duration and amplitude, Fig. 16 of the paper),
:mod:`.fragility` (Monte Carlo fragility of irregular arches under pulses, Figs. 17-21),
:mod:`.record_fragility` (record-based fragility, multiple-stripe analysis) and
:mod:`.comparison` (the two models side by side). Each module is imported on demand.
"""
