"""Studies over many analyses, written against the model protocol
(:class:`archquake.models.StructuralModel`), so that either model runs them.

:mod:`.failure_domain` (outcome regions over pulse duration and amplitude, Fig. 16 of the paper),
:mod:`.arch_sample` (the irregular arches of a study: drawing, seeding, the one rule for an arch
that cannot be analysed, the nominal arch's model), :mod:`.fragility` (Monte Carlo fragility of
irregular arches under pulses, Figs. 17-21), :mod:`.record_fragility` (record-based fragility,
multiple-stripe analysis), :mod:`.fits` (the statistics of both: P_F, lognormal fits, bootstrap,
dispersions) and :mod:`.comparison` (the two models side by side). Each module is imported on
demand.
"""
