"""Oppenheim's arch cut into more voussoirs: the rigid-block model's activation and failure.

    python benchmarks/rigid_block_voussoirs.py [--voussoirs 7 9 11 ...] [--faces curved flat]
        [--duration 0.4] [--out DIR]

For every voussoir count and face shape (curved: the paper's voussoirs; flat: chords, the
polygons a DEM code takes), Oppenheim's geometry (R = 10 m, 157.5 degrees, t = 1.5 m):

- ``k``: the limit analysis's load multiplier (Mech-l), and the rigid blocks' activation
  checked against it: a constant ground acceleration 1 % below k leaves the arch at rest, 1 %
  above it moves it;
- the failure acceleration of the rigid blocks under Oppenheim's pulse of ``--duration`` [s]
  (the failure domain's search with its defaults, boundaries to 0.005 g), the recovery bands
  above it and the undecided analyses (there must be none);
- the run's contact problems: steps left to Lemke's algorithm in the analysis at the failure
  acceleration + 0.05 g, and its time.

Writes ``DIR/voussoirs.csv`` and the figure ``DIR/voussoirs.png`` (the user guide's figure,
``docs/user_guide/images/rigid_blocks_voussoirs.png``). The failure acceleration need not be
smooth in the count: hinges form only at joints, and after the first impact the motion depends
on where they are (user guide, "How many voussoirs").
"""

from __future__ import annotations

import argparse
import csv
import math
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))

from archquake.geometry import GRAVITY  # noqa: E402
from archquake.geometry.spec import StructureSpec  # noqa: E402
from archquake.ground_motion import oppenheim_pulse, rectangular_pulse  # noqa: E402
from archquake.limit_analysis import both_directions  # noqa: E402
from archquake.rigid_blocks import RigidBlockModel, block_outcome  # noqa: E402
from archquake.studies.failure_domain import domain_of  # noqa: E402

COUNTS = (7, 8, 9, 10, 11, 12, 13, 14, 15, 17, 20, 25, 30)


def arch_of(voussoirs: int, faces: str):
    return StructureSpec(voussoirs=voussoirs, faces=faces).nominal()


def row_of(voussoirs: int, faces: str, duration: float) -> dict:
    arch = arch_of(voussoirs, faces)
    k = both_directions(arch)[0].load_multiplier
    below = block_outcome(arch, rectangular_pulse(-0.99 * k * GRAVITY, 1.0))
    above = block_outcome(arch, rectangular_pulse(-1.01 * k * GRAVITY, 1.0))
    start = time.perf_counter()
    domain = domain_of(RigidBlockModel(arch), durations=[duration])
    seconds = time.perf_counter() - start
    piece = domain.slice(duration)
    failure = piece.failure_acceleration_g
    probe = block_outcome(arch, oppenheim_pulse(-(failure + 0.05) * GRAVITY, duration))
    recoveries = piece.recovery_above_g
    return {
        "voussoirs": voussoirs, "faces": faces, "k": k,
        "rest_below_k": below.status.label == "rest",
        "moves_above_k": above.status.label != "rest",
        "failure_g": failure,
        "recovery_above_g": ";".join(f"{a:.3f}-{b:.3f}" for a, b in recoveries),
        "undecided": int(domain.undecided_analyses),
        "lemke_steps_at_failure": probe.fallback_steps,
        "unsolved_steps_at_failure": probe.unconverged_steps,
        "domain_seconds": seconds,
    }


def plot(rows: list[dict], duration: float, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7.0, 4.2))
    for faces, marker in (("curved", "o"), ("flat", "s")):
        sub = [r for r in rows if r["faces"] == faces]
        if not sub:
            continue
        n = [r["voussoirs"] for r in sub]
        ax.plot(n, [r["failure_g"] for r in sub], marker=marker, label=f"failure, {faces} faces")
        ax.plot(n, [r["k"] for r in sub], marker=marker, linestyle=":", fillstyle="none",
                label=f"k (limit analysis), {faces} faces")
    ax.set_xlabel("voussoirs n [-]")
    ax.set_ylabel("acceleration [g]")
    ax.set_title(f"Oppenheim's arch in n voussoirs: rigid blocks, pulse t_p = {duration:g} s")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--voussoirs", type=int, nargs="+", default=list(COUNTS))
    parser.add_argument("--faces", nargs="+", default=["curved", "flat"],
                        choices=["curved", "flat"])
    parser.add_argument("--duration", type=float, default=0.4)
    parser.add_argument("--out", type=Path, default=Path("voussoirs-benchmark"))
    args = parser.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    rows = []
    print(f"Oppenheim's arch, rigid blocks, pulse t_p = {args.duration:g} s (accelerations [g])")
    print(f"  {'n':>3} {'faces':>6} {'k':>7} {'act. ok':>7} {'failure':>8} {'undecided':>9}"
          f" {'Lemke steps':>11} {'time [s]':>8}  recovery above failure")
    for faces in args.faces:
        for n in args.voussoirs:
            row = row_of(n, faces, args.duration)
            rows.append(row)
            ok = row["rest_below_k"] and row["moves_above_k"]
            print(f"  {n:>3} {faces:>6} {row['k']:>7.4f} {str(ok):>7} {row['failure_g']:>8.3f}"
                  f" {row['undecided']:>9d} {row['lemke_steps_at_failure']:>11d}"
                  f" {row['domain_seconds']:>8.1f}  {row['recovery_above_g'] or '-'}",
                  flush=True)
            with open(args.out / "voussoirs.csv", "w", newline="") as f:
                writer = csv.DictWriter(f, fieldnames=list(rows[0]))
                writer.writeheader()
                writer.writerows(rows)
    plot(rows, args.duration, args.out / "voussoirs.png")
    total = sum(r["undecided"] for r in rows)
    print(f"undecided analyses in all: {total}; written {args.out / 'voussoirs.csv'} and "
          f"{args.out / 'voussoirs.png'}")
    return 0 if total == 0 and not any(math.isnan(r["failure_g"]) for r in rows) else 1


if __name__ == "__main__":
    sys.exit(main())
