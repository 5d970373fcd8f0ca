"""Write the synthetic test records ``decaying_sine.csv`` and ``decaying_sine.AT2``.

Both sample the same analytic accelerogram (not a real record)::

    a(t) = 0.4 exp(-t / 0.5) sin(2 pi t / 0.25)    [g]

``tests/test_records.py`` holds its own copy of the formula and compares the files against it.
Run ``python tests/data/make_records.py`` to rewrite the files.
"""

from pathlib import Path

import numpy as np

HERE = Path(__file__).parent


def acceleration_g(t):
    return 0.4 * np.exp(-t / 0.5) * np.sin(2 * np.pi * t / 0.25)


def write_csv(path: Path) -> None:
    t = 0.01 * np.arange(201)
    lines = [
        "# synthetic accelerogram: a(t) = 0.4 exp(-t/0.5) sin(2 pi t/0.25) [g]",
        "# columns: time [s], ground acceleration [g]",
        "time_s,acc_g",
    ]
    lines += [f"{ti:.2f},{ai:.10g}" for ti, ai in zip(t, acceleration_g(t), strict=True)]
    path.write_text("\n".join(lines) + "\n")


def write_at2(path: Path) -> None:
    npts, dt = 300, 0.005
    a = acceleration_g(dt * np.arange(npts))
    lines = [
        "PEER NGA STRONG MOTION DATABASE RECORD",
        "SYNTHETIC DECAYING SINE 0.4 EXP(-T/0.5) SIN(2 PI T/0.25), ARCHQUAKE TEST DATA",
        "ACCELERATION TIME SERIES IN UNITS OF G",
        f"NPTS= {npts:5d}, DT=   .0050 SEC",
    ]
    for start in range(0, npts, 5):
        lines.append("".join(f"{x:15.7E}" for x in a[start:start + 5]))
    path.write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    write_csv(HERE / "decaying_sine.csv")
    write_at2(HERE / "decaying_sine.AT2")
