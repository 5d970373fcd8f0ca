"""``make run`` on fresh clones of two commits, side by side: set-up and the report, as a new
user meets them (no virtual environment, no compiled code cached; pip's cache of downloaded
packages is kept, as on any machine that has installed them once).

    python benchmarks/make_run.py [--baseline COMMIT] [--candidate COMMIT] [--repeats 3]

Each run clones this repository at the commit into a new temporary directory and times, from
outside, ``make .venv/.installed-base`` (the virtual environment and the package's
dependencies) and then ``make run`` (``archquake reproduce``: compiling the integrator, the
limit analysis and the rigid-block solver, then the report). The two commits alternate, so that
both see the same load of a shared machine; the medians and the ratio candidate / baseline are
printed.

Measured (2 cores): ``--repeats 1``, 79.8 s against 101.1 s for 6880f41 (ratio 0.79; set-up
25.2 s against 32.9 s, the report 54.5 s against 68.1 s); the whole ``make run`` of a fresh clone
timed from outside, three runs each, median 83.5 s (82.5-92.8) against 118.7 s (105.3-119.1),
ratio 0.78.
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def one_run(commit: str) -> dict[str, float]:
    """Clone at ``commit`` and time the set-up and the report [s]."""
    with tempfile.TemporaryDirectory() as tmp:
        clone = Path(tmp) / "archquake"
        subprocess.run(["git", "clone", "--quiet", str(ROOT), str(clone)], check=True)
        subprocess.run(["git", "checkout", "--quiet", commit], cwd=clone, check=True)
        times = {}
        for name, target in (("set-up", ".venv/.installed-base"), ("report", "run")):
            t0 = time.perf_counter()
            subprocess.run(["make", target], cwd=clone, check=True,
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            times[name] = time.perf_counter() - t0
        times["make run"] = times["set-up"] + times["report"]
        return times


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--baseline", default="6880f41", help="the commit to compare with")
    parser.add_argument("--candidate", default="HEAD", help="the commit measured")
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args(argv)
    for option, commit in (("--baseline", args.baseline), ("--candidate", args.candidate)):
        if subprocess.run(["git", "rev-parse", "--verify", "--quiet", f"{commit}^{{commit}}"],
                          cwd=ROOT, capture_output=True).returncode != 0:
            parser.error(f"{option}: {commit!r} is not a commit of this repository")
    if args.repeats < 1:
        parser.error(f"--repeats must be an integer >= 1, got {args.repeats}")
    commits = {"candidate": args.candidate, "baseline": args.baseline}
    runs: dict[str, list[dict[str, float]]] = {name: [] for name in commits}
    for k in range(args.repeats):
        for name, commit in commits.items():
            runs[name].append(one_run(commit))
            print(f"run {k + 1} {name} ({commit}): " + ", ".join(
                f"{phase} {t:.1f} s" for phase, t in runs[name][-1].items()), flush=True)
    print(f"\nmedians of {args.repeats} runs [s]   candidate   baseline   ratio")
    for phase in ("set-up", "report", "make run"):
        a = statistics.median(r[phase] for r in runs["candidate"])
        b = statistics.median(r[phase] for r in runs["baseline"])
        print(f"{phase:<28}{a:>10.1f}{b:>11.1f}{a / b:>8.2f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
