"""Where the time of ``archquake assess`` goes, part by part, for one or two source trees side
by side (e.g. a change and its baseline), the runs interleaved.

Run: ``python benchmarks/assess_command.py --quick`` (this tree; a quick assessment, about a
minute), ``python benchmarks/assess_command.py --src OTHER/src --src src`` (two trees, baseline
first: the ratio is the second over the first), ``--repeats N``; any other option is passed to
``archquake assess`` (``--piers 3,6``, ``--sa-period 0.5``). Without ``--quick`` the default
assessment runs (several minutes where the two models disagree).

Each run is a fresh process (``python -m archquake assess``), so that its start-up counts: the
wall time of the command, the part of it before the assessment starts (interpreter, imports,
reading the records: ``start-up``), every timed part of ``results.json`` (``timings``; the
numba cache is loaded inside the first part that calls a compiled function), the tasks of the
second process (``background``, concurrent with the parts) and the time after the report is
written (``exit``). The median over the repeats is printed per tree.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]


def one_run(src: Path, options: list[str]) -> dict[str, float]:
    """One ``archquake assess`` with the package of ``src``: its phases [s]."""
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "report"
        env = {**os.environ, "PYTHONPATH": str(src)}
        t0 = time.perf_counter()
        subprocess.run([sys.executable, "-m", "archquake", "assess", "--out", str(out),
                        "--no-progress", *options], env=env, check=True,
                       stdout=subprocess.DEVNULL)
        wall = time.perf_counter() - t0
        results = json.loads((out / "results.json").read_text())
    timings = dict(results["timings"])
    total = timings.pop("total")
    phases = {"command (wall)": wall, "start-up and exit": wall - total}
    phases.update(timings)
    for task, run in (results.get("background") or {}).items():
        if isinstance(run, dict):
            phases[f"[second process] {task}"] = run["seconds"]
    phases["models agree"] = float(bool((results.get("trusted") or {}).get("agree")))
    return phases


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--src", action="append", type=Path, default=None,
                        help="a source tree (the directory holding archquake/); twice for a "
                             "baseline and a change (default: this tree's src)")
    parser.add_argument("--repeats", type=int, default=1)
    args, options = parser.parse_known_args(argv)
    trees = args.src or [ROOT / "src"]
    runs: list[list[dict]] = [[] for _ in trees]
    for _ in range(args.repeats):
        for i, src in enumerate(trees):  # interleaved: the load of the machine is shared
            runs[i].append(one_run(src.resolve(), options))
    names = list(dict.fromkeys(k for tree in runs for r in tree for k in r))
    load = open("/proc/loadavg").read().split()[0] if Path("/proc/loadavg").exists() else "?"
    print(f"archquake assess {' '.join(options)}: median of {args.repeats} [s], load average "
          f"{load}")
    print(f"{'phase':58s}" + "".join(f"{str(t)[-24:]:>26s}" for t in trees)
          + ("       ratio" if len(trees) == 2 else ""))
    for name in names:
        values = [float(np.median([r.get(name, np.nan) for r in tree])) for tree in runs]
        line = f"{name[:58]:58s}" + "".join(f"{v:26.2f}" for v in values)
        if len(trees) == 2 and values[0] > 0:
            line += f"{values[1] / values[0]:12.2f}"
        print(line)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
