"""Run every benchmark of this folder, one after the other, each in its own process.

    python benchmarks/run_all.py [--only NAME ...]

Each script prints its own side-by-side figures; this runner adds the wall time and the exit
status of each and a summary at the end. A failing benchmark does not stop the others; the exit
status is 1 if any failed. The scripts are found by name (every ``*.py`` here but this one), so a
new benchmark is run without being registered; the longest take the arguments of :data:`ARGUMENTS`.
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent

ARGUMENTS = {"dask_study": ["--quick"], "assess_command": ["--quick"]}
"""The arguments of the scripts whose defaults take an hour or more (the 100,000-arch study on
Dask, the default assessment): the runner takes their quick forms, which print the same
figures on a smaller study; run the scripts by hand for the full ones."""


def benchmark_scripts() -> list[Path]:
    """Every benchmark script of this folder, in name order."""
    return sorted(p for p in HERE.glob("*.py") if p.name != Path(__file__).name)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", nargs="+", metavar="NAME",
                        help="run only these scripts (file names, with or without .py)")
    args = parser.parse_args(argv)
    scripts = benchmark_scripts()
    if args.only:
        wanted = {name.removesuffix(".py") for name in args.only}
        unknown = wanted - {p.stem for p in scripts}
        if unknown:
            parser.error(f"unknown benchmark(s) {sorted(unknown)}; available: "
                         f"{[p.stem for p in scripts]}")
        scripts = [p for p in scripts if p.stem in wanted]
    summary = []
    for script in scripts:
        print(f"\n=== {script.name} ===", flush=True)
        start = time.perf_counter()
        status = subprocess.call([sys.executable, str(script), *ARGUMENTS.get(script.stem, [])],
                                 cwd=HERE.parent)
        summary.append((script.name, status, time.perf_counter() - start))
    print("\n=== summary ===")
    for name, status, seconds in summary:
        print(f"{name:<32} {'ok' if status == 0 else f'FAILED ({status})':<12} {seconds:8.1f} s")
    return 1 if any(status for _, status, _ in summary) else 0


if __name__ == "__main__":
    sys.exit(main())
