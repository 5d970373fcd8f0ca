"""The regression fixture of ``archquake reproduce --quick`` and how a result is compared with it.

The fixture (tests/data/regression_reproduce_quick_results.json) is that run's results.json as it
was before the package was reorganised, environment and timings removed.
"""

import json

import pytest

FIXTURE = "regression_reproduce_quick_results.json"
VOLATILE = {"environment", "timings", "background", "rigid_block_seconds"}
"""Keys that depend on the machine and the run, not on the physics."""
RENAMED = {"tolerance": "epsilon", "blocks": "measured"}
"""Keys renamed since the fixture was written (the names pass: epsilon of eq. (1); the
restitution measured on the rigid blocks)."""
ADDED = {"two_models", "fig16_failure_domain_both_models", "fig17_20_fragility_both_models",
         "rigid_fragility_sample_size", "coarse_factor", "undecided", "undecided_analyses",
         "probability_upper", "probability_upper_largest_gap", "probability_below_nominal_upper",
         "nominal_failure_undecided_from", "failure_undecided_from"}
"""Keys added since the fixture was written (the paper's study with both models, the rigid blocks'
coarse steps, the counts and bounds of undecided analyses): a new key is allowed only if it is
named here; every key of the fixture must still be there, unchanged."""


def load_fixture(data_dir) -> dict:
    """The fixture's results."""
    return json.loads((data_dir / FIXTURE).read_text())


def assert_same(a, b, where="results"):
    """Structures equal, strings and keys exactly, numbers to 1e-9 relative (the last bits of a
    float may differ between processors; anything a refactoring changes differs by far more)."""
    if isinstance(a, dict):
        a = {RENAMED.get(k, k): v for k, v in a.items()}
        keys = set(a) - VOLATILE
        new = set(b) - VOLATILE - keys
        assert keys <= set(b) and new <= ADDED, (
            f"{where}: keys {sorted(keys ^ (set(b) - VOLATILE))}")
        for key in keys:
            assert_same(a[key], b[key], f"{where}.{key}")
    elif isinstance(a, list):
        assert isinstance(b, list) and len(a) == len(b), f"{where}: lengths differ"
        for i, (x, y) in enumerate(zip(a, b, strict=True)):
            assert_same(x, y, f"{where}[{i}]")
    elif isinstance(a, float) and not isinstance(b, bool):
        assert isinstance(b, int | float), f"{where}: {a!r} vs {b!r}"
        assert b == pytest.approx(a, rel=1e-9, abs=1e-12), f"{where}: {a!r} vs {b!r}"
    else:
        assert a == b, f"{where}: {a!r} vs {b!r}"
