"""Which drawn arches a study must exclude, found arch by arch without the studies (for the
tests of the one exclusion rule, archquake.studies.arch_sample)."""

import numpy as np

from archquake.geometry import irregular_arch
from archquake.limit_analysis import load_multipliers


def independent_exclusions(nominal, epsilon, count, seed) -> dict[int, str]:
    """Arches that are not arches or cannot stand, by index: arch i drawn with the generator of
    child i of ``SeedSequence(seed).spawn(count)``, refused by the draw of eq. (1), or with a
    static load multiplier that is not >= 0 (nan: no thrust line at all)."""
    expected = {}
    children = np.random.SeedSequence(seed).spawn(count)
    for i in range(count):
        try:
            arch = irregular_arch(nominal, epsilon, np.random.default_rng(children[i]))
        except ValueError:
            expected[i] = "not an arch"
            continue
        if not all(k >= 0 for k in load_multipliers(arch, "static")):
            expected[i] = "cannot stand"
    return expected
