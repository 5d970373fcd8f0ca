"""Studies over many analyses, written against the model protocol
(:class:`archquake.models.StructuralModel`), so that either model runs them.

:mod:`.failure_domain` (outcome regions over pulse duration and amplitude, Fig. 16 of the paper),
:mod:`.arch_sample` (the irregular arches of a study: drawing, seeding, the one rule for an arch
that cannot be analysed, the nominal arch's model), :mod:`.fragility` (Monte Carlo fragility of
irregular arches under pulses, Figs. 17-21), :mod:`.record_fragility` (record-based fragility,
multiple-stripe analysis, over the analyses of :mod:`.record_outcomes`), :mod:`.stripes` (where
its stripes go: a pilot over the records and the levels chosen from it), :mod:`.fits` (the
statistics of both: P_F, lognormal fits, bootstrap, dispersions), :mod:`.comparison` (the two
models side by side: :func:`.comparison.compare_models`, :func:`.comparison.domain_disagreement`),
:mod:`.strategies` (how a study searches a grid of amplitudes or levels: every point, or a coarse
scan and bisection; the rigid-block model's studies owe their speed to it) and :mod:`.undecided`
(analyses a model left undecided: counted, bounding P_F, said on a study's first line). Each
module is imported on demand.
"""
