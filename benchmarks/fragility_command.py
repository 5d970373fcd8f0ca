"""Where the seconds of a whole ``archquake fragility`` (or ``record-fragility``) command go,
and two ways of running it side by side.

    python benchmarks/fragility_command.py [--study reduced|paper|four-link|records]
                                           [--repeats 3] [--untimed 1] [--a ARGS] [--b ARGS]
                                           [--b-src DIR]

Each run is the command as a user types it, in a fresh interpreter (``python -m archquake``),
writing its outputs to a new directory. A run is timed from outside (the wall time of the
process) and, inside, by timers wrapped around the phases of the command (the wrapped functions
are the package's own; nothing else changes):

- interpreter start: the process's wall time less the time measured inside it;
- imports: ``archquake.cli`` and the study's module with pandas, scipy and numba;
- settings: the options read and the study's settings built (the model spec resolved);
- dynamic study: the chunks of irregular arches (``execution.run_study`` of the fragility
  task), split into the time the tasks took in all (``task s``, summed over workers: the
  analyses, the search, the screening model and each arch's model built), the checkpoints of
  the chunks written, and the rest (worker processes started, their imports and compiled
  code loaded, waiting);
- limit sample: the limit analyses of the s arches (its own ``run_study``);
- nominal: the nominal arch's failure domains, when this process computes them (when a worker
  does, waiting for them is in the rest of the command);
- curves: the fits of the fragility curves;
- writing: results.parquet/.csv, curves.csv, summary.json (and the tables ``run_study``
  writes);
- figures (with ``--plot-dir``) and the rest of the command (printing, the model check);
- the CPU time of the command and its worker processes, which depends less than the wall time
  on what else runs on the machine (timed from outside).

The two variants A and B are first run ``--untimed`` times each (compiled code cached, files
read), then interleaved ``--repeats`` times each; the medians and the ratio B / A of every
phase are printed side by side. ``--b-src`` runs B on another copy of the package (the version
before a change: before/after). The defaults compare the command as a user runs it (A: its defaults
with ``--workers 2``) with the exhaustive grid (B: ``--search exhaustive``). ``--always-pool``,
an option of this script, not of the command, puts back the former rule of execution: worker
processes whenever ``--workers`` is above 1, whatever the study's size.

The figures of the user guide ("What screening can save", "What the whole command costs")::

    python benchmarks/fragility_command.py --study four-link --b "--workers 2" --b-src OLD/src
    python benchmarks/fragility_command.py --study paper --repeats 1 --untimed 0
    python benchmarks/fragility_command.py --study records --repeats 1 --b "--workers 2" \
        --b-src OLD/src

with ``OLD`` an older version of the package (``git archive b9d6ce0 src | tar -x -C OLD``).

Studies (``--study``):

``reduced``
    rigid blocks, 8 arches, t_p = 0.4 and 0.7 s, 0.20-0.80 g (the study to iterate on);
``paper``
    rigid blocks, the paper's 40 arches, 4 durations, 0.20-0.80 g in 0.01 g steps;
``four-link``
    the same paper-sized study with the four-link model;
``records``
    ``record-fragility`` with the rigid blocks: the nominal and one irregular arch under the 28
    near-field pulse records of FEMA P695 at 5 PGA levels, both polarities (560 analyses).
"""

from __future__ import annotations

import argparse
import functools
import json
import os
import resource
import shlex
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

STUDIES = {
    "reduced": "fragility --model rigid-blocks --samples 8 --durations 0.4,0.7 "
               "--amplitudes 0.2:0.8:0.01",
    "paper": "fragility --model rigid-blocks --amplitudes 0.2:0.8:0.01",
    "four-link": "fragility --amplitudes 0.2:0.8:0.01",
    "records": "record-fragility --model rigid-blocks --suite fema-p695-near-field-pulse "
               "--samples 1 --levels 0.2:1.8:0.4",
}
"""The commands of the studies (``archquake`` and the output options are added)."""

PHASES = ("interpreter start", "imports", "settings", "dynamic study", "  task s (summed)",
          "  checkpoints", "  pool, start-up, wait", "limit sample", "nominal", "curves",
          "writing", "figures", "rest of the command", "total", "CPU s, all processes")


def _child(argv: list[str]) -> None:
    """Run ``archquake ARGV`` in this process with timers around its phases; print them as one
    JSON line on stderr (prefixed ``PHASES``)."""
    started = time.perf_counter()
    phases = dict.fromkeys(PHASES, 0.0)
    always_pool = "--always-pool" in argv
    argv = [a for a in argv if a != "--always-pool"]
    import archquake.cli as cli
    from archquake import execution, results_io
    from archquake.cli import options

    study_module = ("archquake.studies.record_fragility" if argv[0] == "record-fragility"
                    else "archquake.studies.fragility")
    study = __import__(study_module, fromlist=["_"])
    phases["imports"] = time.perf_counter() - started
    if always_pool:  # the former rule: worker processes whenever --workers > 1
        from archquake.studies import fragility, strategies

        for module in (fragility, strategies):
            module.pool_pays = lambda seconds, workers: workers > 1

    def timed(owner, name, phase):
        original = getattr(owner, name)

        @functools.wraps(original)  # pickled by name: a worker runs the original
        def wrapper(*args, **kwargs):
            t0 = time.perf_counter()
            try:
                return original(*args, **kwargs)
            finally:
                phases[phase] += time.perf_counter() - t0

        setattr(owner, name, wrapper)

    current = {"study": None, "saved": 0.0}
    run_study = execution.run_study

    def timed_run_study(task, *args, **kwargs):
        current["study"] = "limit sample" if task.__name__.startswith("limit") else "dynamic"
        current["saved"] = 0.0
        t0 = time.perf_counter()
        table = run_study(task, *args, **kwargs)
        elapsed = time.perf_counter() - t0 - current["saved"]  # its tables: writing
        if current["study"] == "dynamic":
            phases["dynamic study"] += elapsed
            timings = table.attrs.get("study", {}).get("timings", {})
            phases["  task s (summed)"] += timings.get("task_seconds", 0.0)
            current["workers"] = table.attrs.get("study", {}).get("workers") or 1
        else:
            phases["limit sample"] += elapsed
        current["study"] = None
        return table

    execution.run_study = timed_run_study
    save_in_study = execution.save_study

    def timed_save_in_study(*args, **kwargs):
        t0 = time.perf_counter()
        out = save_in_study(*args, **kwargs)
        current["saved"] += time.perf_counter() - t0
        phases["writing"] += time.perf_counter() - t0
        return out

    execution.save_study = timed_save_in_study
    timed(options, "model_spec_from_args", "settings")
    timed(study.FragilitySettings if hasattr(study, "FragilitySettings")
          else study.RecordFragilitySettings, "__post_init__", "settings")
    timed(execution, "_save_chunk", "  checkpoints")
    timed(results_io, "save_study", "writing")
    for name in ("fragility_curves", "record_fragility_result"):
        if hasattr(study, name):
            timed(study, name, "curves")
    for name in ("_nominal_domains", "_nominal_outcomes"):
        if hasattr(study, name):
            timed(study, name, "nominal")
    command = __import__(f"archquake.cli.main_{argv[0].replace('-', '_')}", fromlist=["_"])
    if hasattr(command, "_plot"):
        timed(command, "_plot", "figures")
    try:
        cli.main(argv)
    except SystemExit as exc:
        if exc.code:
            raise
    total = time.perf_counter() - started
    workers = current.get("workers", 1)
    phases["  pool, start-up, wait"] = (phases["dynamic study"] - phases["  checkpoints"]
                                       - phases["  task s (summed)"] / workers)
    phases["rest of the command"] = total - sum(
        phases[p] for p in ("imports", "settings", "dynamic study", "limit sample", "nominal",
                            "curves", "writing", "figures"))
    phases["total"] = total
    print("PHASES " + json.dumps(phases), file=sys.stderr)


def _children_cpu() -> float:
    """CPU seconds of the finished child processes of this one and theirs (the command and its
    worker processes): less sensitive than wall time to what else the machine runs."""
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def _run(command: str, extra: str, src: Path) -> dict:
    """One run of ``archquake COMMAND EXTRA`` in a fresh interpreter, the package imported from
    ``src``; its phases [s]."""
    with tempfile.TemporaryDirectory() as tmp:
        argv = shlex.split(command) + shlex.split(extra) + ["--out", str(Path(tmp) / "out"),
                                                            "--no-progress"]
        env = {**os.environ, "PYTHONPATH": str(src)}
        t0 = time.perf_counter()
        cpu0 = _children_cpu()
        done = subprocess.run([sys.executable, __file__, "--child", *argv], env=env,
                              capture_output=True, text=True)
        wall = time.perf_counter() - t0
        cpu = _children_cpu() - cpu0
    if done.returncode:
        raise SystemExit(f"archquake {' '.join(argv)} failed:\n{done.stderr[-3000:]}")
    line = [x for x in done.stderr.splitlines() if x.startswith("PHASES ")][-1]
    phases = json.loads(line[len("PHASES "):])
    phases["interpreter start"] = wall - phases["total"]
    phases["total"] = wall
    phases["CPU s, all processes"] = cpu
    phases["output"] = done.stdout
    return phases


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if argv and argv[0] == "--child":
        _child(argv[1:])
        return 0
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--study", choices=STUDIES, default="reduced")
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--untimed", type=int, default=1,
                        help="untimed runs of each variant first (0 once its compiled code is "
                             "cached)")
    parser.add_argument("--b-src", type=Path, default=ROOT / "src",
                        help="the package's source directory of variant B, e.g. an older "
                             "version's (git archive COMMIT src | tar -x -C DIR: DIR/src); "
                             "default this one")
    parser.add_argument("--a", default="--workers 2", help="options of variant A")
    parser.add_argument("--b", default="--workers 2 --search exhaustive",
                        help="options of variant B (the baseline)")
    args = parser.parse_args(argv)
    if not (args.b_src / "archquake" / "__init__.py").is_file():  # PYTHONPATH naming nothing
        # would let the installed package run as B, and A and B would compare equal
        parser.error(f"--b-src: {args.b_src} holds no archquake package (give OLD/src)")
    command = STUDIES[args.study]
    variants = (("A", args.a, ROOT / "src"), ("B", args.b, args.b_src))
    for _ in range(args.untimed):  # compiled code cached and files read once: not timed
        for _, extra, src in variants:
            _run(command, extra, src)
    runs = {"A": [], "B": []}
    for _ in range(args.repeats):
        for name, extra, src in variants:
            runs[name].append(_run(command, extra, src))
    print(f"archquake {command} --out DIR --no-progress, median of {args.repeats} runs, "
          f"interleaved")
    print(f"  A: {args.a}\n  B: {args.b}" + ("" if args.b_src == ROOT / "src"
                                               else f" (package from {args.b_src})"))
    print(f"{'phase [s]':<26}{'A':>9}{'B':>9}{'B / A':>9}")
    for phase in PHASES:
        a = statistics.median(r[phase] for r in runs["A"])
        b = statistics.median(r[phase] for r in runs["B"])
        ratio = f"{b / a:9.2f}" if a > 0.05 else f"{'-':>9}"
        print(f"{phase:<26}{a:9.2f}{b:9.2f}{ratio}")
    same = [_curves(r["output"]) for r in runs["A"] + runs["B"]]
    print(f"printed results (table of curves) identical in every run: "
          f"{all(s == same[0] for s in same)}")
    return 0 if all(s == same[0] for s in same) else 1


def _curves(output: str) -> str:
    """The lines of a command's output that hold its results (not its timings or counts of
    analyses, which differ between strategies)."""
    return "\n".join(line for line in output.splitlines()
                     if line[:1].isdigit() or line.lstrip()[:1].isdigit()
                     or line.startswith(("k~", "nominal")))


if __name__ == "__main__":
    raise SystemExit(main())
