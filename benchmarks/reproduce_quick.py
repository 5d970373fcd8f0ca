"""``archquake reproduce --quick`` with this version and an older one, side by side: its wall
time, and every number of its ``results.json`` compared.

    python benchmarks/reproduce_quick.py --b-src OLD/src [--repeats 1] [--untimed 1]
                                         [--rtol 0]

with ``OLD`` an older version of the package (``git archive COMMIT src | tar -x -C OLD``).
Each run is the command as a user types it (``python -m archquake reproduce --quick --out DIR
--no-progress``) in a fresh interpreter whose package comes from ``src`` (``PYTHONPATH``);
the two versions are first run ``--untimed`` times each (their compiled code cached), then
interleaved ``--repeats`` times; the medians of the wall time and of the CPU time of the command
and its worker processes are printed side by side with their ratio.

The results are then compared number by number: every leaf of the two ``results.json`` at the
same path, except the timings and what names the version (``timings``, ``elapsed``,
``seconds``, ``version``, ``settings``). Numbers are equal when ``|a - b| <= rtol max(|a|,
|b|)`` (``--rtol``, default 0: bit for bit), strings and booleans when identical. A path that
only one side has (a result added, or a key renamed, between the versions) is listed apart: it
is a change of the report's layout, not of a value. The script prints the count of values
compared, every value that differs with its relative difference (up to ``--show``), the paths
of only one side, and exits 1 if a value differs.

Measured against f1415e3 (``git archive f1415e3 src``, the version before the studies were made
faster), median of three interleaved runs on a quiet two-processor machine (``--untimed 0
--repeats 3``): 10.0 s against 9.9 s of wall time, 13.5 s against 13.9 s of CPU; of 1,430
values, two differ, in the last bit (the impact's energy
ratio and Mech-r's share, relative 2.0e-16 and 1.3e-16: summed in another order); 83 paths are
in one version only, results added since (the rigid blocks' upper curves, the undecided counts)
or keys renamed (``blocks`` to ``measured``). With ``--rtol 1e-15`` every value is equal.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

SKIPPED = ("timings", "elapsed", "seconds", "version", "settings", "cpu", "background")
"""Keys whose values are not results (times, the version, the settings as given, which process
ran a part)."""


def _cpu() -> float:
    """CPU seconds of the finished child processes (the command and its workers)."""
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def run(src: Path, out: Path) -> tuple[float, float, dict]:
    """One ``reproduce --quick`` into ``out`` with the package of ``src``: (wall s, CPU s,
    results.json)."""
    env = {**os.environ, "PYTHONPATH": str(src)}
    cpu0, t0 = _cpu(), time.perf_counter()
    done = subprocess.run([sys.executable, "-m", "archquake", "reproduce", "--quick", "--out",
                           str(out), "--no-progress"], env=env, capture_output=True, text=True)
    wall, cpu = time.perf_counter() - t0, _cpu() - cpu0
    if done.returncode:
        raise SystemExit(f"reproduce --quick with {src} failed:\n{done.stderr[-3000:]}")
    return wall, cpu, json.loads((out / "results.json").read_text())


def leaves(value, path=()):
    """``(path, leaf)`` of every number, string, boolean or null in a JSON value, skipping the
    keys of :data:`SKIPPED`."""
    if isinstance(value, dict):
        for key, item in value.items():
            if not any(s in str(key).lower() for s in SKIPPED):
                yield from leaves(item, (*path, str(key)))
    elif isinstance(value, list):
        for i, item in enumerate(value):
            yield from leaves(item, (*path, str(i)))
    else:
        yield path, value


def equal(a, b, rtol: float) -> bool:
    """Whether two leaves are equal (numbers to ``rtol``, nan equal to nan)."""
    numbers = (int, float)
    if isinstance(a, numbers) and isinstance(b, numbers) and not isinstance(a, bool) \
            and not isinstance(b, bool):
        if math.isnan(a) or math.isnan(b):
            return math.isnan(a) and math.isnan(b)
        return abs(a - b) <= rtol * max(abs(a), abs(b))
    return a == b


def compare(a: dict, b: dict, rtol: float) -> tuple[int, list[str], list[str]]:
    """The count of leaves compared, the values that differ and the paths of one side only, as
    lines."""
    la, lb = dict(leaves(a)), dict(leaves(b))
    differences, one_side = [], []
    for path in sorted(set(la) | set(lb)):
        name = "/".join(path)
        if path not in la or path not in lb:
            one_side.append(f"{name}: only in {'A' if path in la else 'B'}")
        elif not equal(la[path], lb[path], rtol):
            x, y = la[path], lb[path]
            relative = ""
            if all(isinstance(v, int | float) and not isinstance(v, bool) for v in (x, y)):
                relative = f"  (relative {abs(x - y) / max(abs(x), abs(y)):.1e})"
            differences.append(f"{name}: A {x!r}  B {y!r}{relative}")
    return len(set(la) & set(lb)), differences, one_side


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--b-src", type=Path, required=True,
                        help="the older version's source directory (OLD/src)")
    parser.add_argument("--repeats", type=int, default=1)
    parser.add_argument("--untimed", type=int, default=1)
    parser.add_argument("--rtol", type=float, default=0.0)
    parser.add_argument("--show", type=int, default=40, help="differences printed at most")
    args = parser.parse_args(argv)
    if not (args.b_src / "archquake" / "__init__.py").is_file():
        # else PYTHONPATH would name nothing and the installed package would run as B
        parser.error(f"--b-src: {args.b_src} holds no archquake package (give OLD/src)")
    variants = {"A": ROOT / "src", "B": args.b_src.resolve()}
    times = {"A": [], "B": []}
    results = {}
    with tempfile.TemporaryDirectory() as tmp:
        for i in range(args.untimed):
            for name, src in variants.items():
                run(src, Path(tmp) / f"untimed-{name}-{i}")
        for i in range(args.repeats):
            for name, src in variants.items():
                wall, cpu, results[name] = run(src, Path(tmp) / f"{name}-{i}")
                times[name].append((wall, cpu))
    print(f"archquake reproduce --quick, median of {args.repeats} interleaved runs")
    print(f"  A: {variants['A']}\n  B: {variants['B']}")
    print(f"{'':<22}{'A':>9}{'B':>9}{'B / A':>9}")
    for k, label in enumerate(("wall time [s]", "CPU time [s]")):
        a = statistics.median(t[k] for t in times["A"])
        b = statistics.median(t[k] for t in times["B"])
        print(f"{label:<22}{a:9.1f}{b:9.1f}{b / a:9.2f}")
    count, differences, one_side = compare(results["A"], results["B"], args.rtol)
    print(f"results.json: {count} values compared, {len(differences)} differ (rtol "
          f"{args.rtol:g})")
    for line in differences[:args.show]:
        print("  " + line)
    print(f"{len(one_side)} paths in one version only (results added or keys renamed)")
    for line in one_side[:args.show]:
        print("  " + line)
    return 1 if differences else 0


if __name__ == "__main__":
    raise SystemExit(main())
