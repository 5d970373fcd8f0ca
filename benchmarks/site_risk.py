"""Cost of the annual frequency of collapse (archquake.site.risk.risk): a lognormal fragility on
OpenQuake's 28-level hazard curve of its classical-damage QA case, and on a 200-level power law,
against Cornell's closed form for the second (target: well under 1 s each).

    python benchmarks/site_risk.py
"""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "src"))

from archquake.site.fragility_models import LognormalCollapseFragility  # noqa: E402
from archquake.site.hazard import HazardCurve, read_hazard_curve  # noqa: E402
from archquake.site.risk import risk  # noqa: E402


def seconds(f, repeat):
    f()
    start = time.perf_counter()
    for _ in range(repeat):
        value = f()
    return (time.perf_counter() - start) / repeat, value


def main() -> int:
    fragility = LognormalCollapseFragility(0.47, 0.70)
    curve = read_hazard_curve(ROOT / "tests" / "data" / "site"
                              / "openquake_classical_damage_case_1_hcurves_PGA.csv")
    t, result = seconds(lambda: risk(fragility, curve), 50)
    print(f"OpenQuake QA curve, {curve.levels.size} levels: lambda_c = "
          f"{result.annual_frequency:.6g} 1/yr, P(50 yr) = {result.probability:.5f}, "
          f"error {result.integration_error:.1g} 1/yr, {t:.4f} s")
    x = np.geomspace(1e-4, 10.0, 200)
    k0, k = 1e-3, 2.5
    power = HazardCurve(x, k0 * x**-k)
    t, result = seconds(lambda: risk(fragility, power), 50)
    exact = k0 * fragility.median**-k * math.exp(k * k * fragility.dispersion**2 / 2)
    print(f"power law, {x.size} levels: lambda_c = {result.annual_frequency:.8g} 1/yr vs "
          f"Cornell {exact:.8g} (relative difference "
          f"{result.annual_frequency / exact - 1:.1e}), {t:.4f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
