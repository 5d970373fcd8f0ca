"""
Record-based fragility
======================

Fragility of Oppenheim's arch and of its irregular sample against a record suite, in PGA and in
PGV.

Run:  python examples/record_fragility.py [--quick | --full] [--out DIR]

Every record of a synthetic suite (Rezaeian & Der Kiureghian's model, 20-s records: no files
needed) is scaled to each stripe level of the intensity measure and applied in both polarities to
h irregular arches (epsilon = 0.10) and to the nominal arch; P(collapse | IM) per stripe is fitted
with a lognormal fragility function by maximum likelihood, with a bootstrap band. The default
(and ``--quick``) size is reduced (5 arches, 5 records, 10 levels: seconds); ``--full`` (or
ARCHQUAKE_FULL=1) runs 40 arches x 20 records x 20 levels on two worker processes (about a
minute per intensity measure).
"""

import argparse
import os
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from archquake.plotting import plot_incremental, plot_record_fragility  # noqa: E402
from archquake.studies.record_fragility import DEFAULT_LEVELS, oppenheim_record_fragility  # noqa: E402


def main(argv=None):
    parser = argparse.ArgumentParser(
        description="Record-based fragility of Oppenheim's arch in PGA and PGV.")
    size = parser.add_mutually_exclusive_group()
    size.add_argument("--quick", action="store_true", help="the reduced size (the default)")
    size.add_argument("--full", action="store_true",
                      help="40 arches x 20 records x 20 levels (also ARCHQUAKE_FULL=1)")
    parser.add_argument("--out", default=".", help="folder of the figures")
    args = parser.parse_args(argv)
    full = args.full or (os.environ.get("ARCHQUAKE_FULL") == "1" and not args.quick)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    if full:
        options = {"records": 20, "sample_size": 40, "backend": "processes", "workers": 2}
        levels = DEFAULT_LEVELS
    else:  # every other level of the full grid, from the activation of the arch on
        options = {"records": 5, "sample_size": 5, "bootstrap": 200}
        levels = {im: values[3::2] for im, values in DEFAULT_LEVELS.items()}
    results = oppenheim_record_fragility(("pga", "pgv"), levels=levels, **options)

    fig, axes = plt.subplots(1, 2, figsize=(13, 5.2), constrained_layout=True)
    for ax, (im, result) in zip(axes, results.items(), strict=True):
        plot_record_fragility(result, ax)
        s = result.summary()
        unit = result.settings.unit
        print(f"{im} [{unit}]: levels {result.levels[0]:g}-{result.levels[-1]:g}, "
              f"{result.settings.sample_size} arches x {len(result.records)} records x 2 "
              f"polarities")
        print(f"  P(collapse | {im}) of the irregular arches: "
              f"{np.array2string(result.probability, precision=2)}; of the nominal arch: "
              f"{np.array2string(result.nominal_probability, precision=2)}")
        for what, fit in (("irregular arches", s["lognormal"]),
                          ("nominal arch", s["nominal"]["lognormal"])):
            text = ("no lognormal fit (the stripes go from none to all in one step)"
                    if fit["median"] is None else
                    f"median {fit['median']:.3f} {unit}, dispersion {fit['dispersion']:.3f}")
            print(f"  {what}: {text}")
        v = s["variability"]
        print("  dispersions: " + ", ".join(
            f"{name.replace('_', '-')} {'-' if v[name] is None else f'{v[name]:.3f}'}"
            for name in ("record_to_record", "geometric", "total")))
    fig.savefig(out / "record_fragility.png", dpi=130)
    plt.close(fig)
    ax = plot_incremental(results["pga"])
    ax.figure.savefig(out / "record_fragility_incremental_pga.png", dpi=130)
    plt.close(ax.figure)
    print("The paper's fragility curves (Figs. 17-20) are in the amplitude of one pulse shape; "
          "these are in the intensity of a suite of ground motions, the form a seismic "
          f"assessment uses. Figures written to {out}.")


if __name__ == "__main__":
    main()
