"""Assess a structure: the paper's method and both models applied to it, against real records,
in one report an engineer can read, check and file (``archquake assess``).

:func:`assess` runs, for one structure (an arch of any shape, surveyed, on piers, under fill;
Oppenheim's arch by default):

1. the limit analysis both ways: does it stand, at what horizontal acceleration does it start to
   move (k_l, k_r), where are the hinges, and its geometric safety factor -- or the verdict that
   it cannot stand, with the reason (the report then stops there);
2. the four-link mechanisms, their critical rotations and the coefficient of restitution of
   every rule;
3. the failure domain under Oppenheim's pulse with both models, the four-link model and the
   rigid blocks (on a second process while the rest runs), and where they disagree;
4. the effect of irregularity: irregular arches drawn with the user's epsilon, the CDF of k~ and
   the fragility under pulses;
5. the record-based fragility (multiple-stripe analysis) against real records (the FEMA P695
   pulse-like near-field set when the ``records`` extra is installed, else a synthetic suite, with
   a note), in PGA, PGV and Sa(T), with lognormal medians and dispersions and an OpenQuake NRML
   file per intensity measure;
6. where the two models' failure accelerations under pulses disagree beyond the agreement band
   (:func:`~archquake.report.assess.parts.trusted_model`), the studies of 4 and 5 again with the
   rigid-block model (the same draws, pulses, records and stripes; fewer arches), on every
   processor: the first screen then gives the rigid-block numbers, and the four-link ones
   beside them marked "not used";

and writes ``report.html`` (self-contained: figures embedded, opens offline), ``report.md`` with
the figures beside it, ``results.json`` (every number, the settings, versions and run times) and
the NRML files into ``out_dir``, whose first screen is the summary: the verdict, the capacities
in words and numbers, which model each comes from (``model`` beside every result of
``results.json``) and how far the two agree, and the assumptions. Each study runs in its own
subdirectory of ``out_dir`` and finished parts are kept, so an interrupted assessment continues
with ``resume=True``.

This module only orchestrates: the parts compute (:mod:`archquake.report.assess.parts`,
:mod:`archquake.report.assess.records`, with the library's own calls), the figures are drawn from
their values (:mod:`archquake.report.assess.figures`), the words written from the numbers
(:mod:`archquake.report.assess.text`) and the files rendered (:mod:`archquake.report.render`).
"""

from __future__ import annotations

import contextlib
import os
import shlex
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..._version import __version__
from ...compiled import announce_all
from ...errors import StudyError
from ...rigid_blocks.model import engines as rigid_block_engines
from ..render import (
    Bullets,
    Document,
    Figure,
    Paragraph,
    Section,
    Table,
    environment,
    jsonable,
    save,
    write_html,
    write_markdown,
)
from . import parts, text
from . import records as record_parts
from .settings import DEFAULT_SUITE, FALLBACK_RECORDS, AssessmentSettings, time_scale

ASSESSMENT_JSON = "assessment.json"
"""What an assessment directory records of its assessment: the structure, the settings, the
records and the version (a resume must match it)."""

STRUCTURE_JSON = "structure.json"
"""The structure, as ``--geometry`` reads it (the command that regenerates the report uses it)."""

PARTS_DIR = "parts"
"""Subdirectory of the finished parts that are kept for a resume (the rigid-block domain, the
records' pilot)."""

FRAGILITY_DIR = "fragility_pulses"
"""Subdirectory of the fragility study under pulses."""

RECORDS_DIR = "records_{im}"
"""Subdirectory of each record-based fragility study (``{im}``: the intensity measure)."""

RIGID_BLOCKS_SUFFIX = "_rigid_blocks"
"""Added to :data:`FRAGILITY_DIR` and :data:`RECORDS_DIR` for the rigid-block model's studies,
run where the two models disagree (:func:`~archquake.report.assess.parts.trusted_model`)."""

TITLE = "archquake: seismic assessment"
"""The title of the report's page."""

STYLE = (".verdict{font-size:1.08em;font-weight:bold;border-left:6px solid #444;"
         "padding:0.4em 0.8em;background:#f4f4f4}.cannot{border-color:#b00;color:#800}"
         ".note{color:#444;font-size:0.92em}ul{margin-top:0.2em}li{margin:0.1em 0}")
"""The assessment's additions to the report's style (the verdict's box)."""


@dataclass(frozen=True)
class Assessment:
    """Result of :func:`assess`.

    Attributes
    ----------
    results : dict
        Every number of the report (also written to ``results.json``).
    directory : Path
        Where ``report.html``, ``report.md``, ``results.json``, the figures and the NRML files
        are.
    files : tuple of str
        The files of the report in ``directory``: the two pages, ``results.json``, the figures
        (PNG) and the NRML files.
    """

    results: dict
    directory: Path
    files: tuple[str, ...]

    @property
    def stands(self) -> bool:
        """Whether the structure stands under its own weight."""
        return bool(self.results["verdict"]["stands"])

    @property
    def verdict(self) -> str:
        """The verdict in words (the report's first paragraph), after the warning on the
        undecided rigid-block analyses when there are too many
        (:func:`~archquake.report.assess.text.undecided_warning_text`)."""
        if "left_out" in self.results:  # a block assembly's assessment
            from .assembly import verdict_text

            return verdict_text(self.results)
        warning = text.undecided_warning_text(self.results)
        return text.verdict_text(self.results) if warning is None else (
            f"{warning}\n{text.verdict_text(self.results)}")


# ------------------------------------------------------------------------------ records
def choose_suite(records=None, suite: str | None = None, settings: AssessmentSettings | None
                 = None):
    """The records of an assessment, and a note on them.

    Parameters
    ----------
    records : str, Path, sequence of them, or RecordSuite, optional
        Record files and folders (:meth:`archquake.ground_motion.RecordSuite.from_paths`), or
        a suite.
    suite : str, optional
        A built-in suite (:data:`archquake.ground_motion.BUILTIN_SUITES`).
    settings : AssessmentSettings, optional
        ``record_count`` (the ground motions kept) and ``seed`` (of a synthetic suite).

    Returns
    -------
    (RecordSuite, str)
        The suite and a note ("" or what replaced the default records and how to get them).

    Raises
    ------
    ValueError
        For both ``records`` and ``suite``, an unknown suite, a bad record file.
    ImportError
        For a built-in suite named explicitly without the ``records`` extra.
    """
    from ...ground_motion.fema_p695 import INSTALL_HINT
    from ...ground_motion.suites import RecordSuite
    from ...studies.record_fragility import STOCHASTIC_SUITE

    settings = AssessmentSettings() if settings is None else settings
    if records is not None and suite is not None:
        raise ValueError("give records (files and folders) or suite (a built-in suite), not "
                         "both")
    note = ""
    if isinstance(records, RecordSuite):
        chosen = records
    elif records is not None:
        chosen = RecordSuite.from_paths(records)
    elif suite is not None:
        chosen = RecordSuite.from_builtin(suite)
    else:
        try:
            chosen = RecordSuite.from_builtin(DEFAULT_SUITE)
        except ImportError:
            chosen = RecordSuite.from_stochastic(FALLBACK_RECORDS, settings.seed,
                                                 **STOCHASTIC_SUITE)
            note = (f"These are synthetic ground motions, not real records: the built-in FEMA "
                    f"P695 records are not installed. Install them with {INSTALL_HINT} and "
                    f"run the assessment again to use the pulse-like near-field records.")
    return record_parts.select_records(chosen, settings.record_count), note


def check_before_writing(structure, settings: AssessmentSettings) -> None:
    """What an assessment can refuse before it writes anything: a friction with which the
    rigid-block model cannot hold the structure up (its failure domain would stop the
    assessment after minutes). The settings check their own ranges.

    Raises
    ------
    ValueError
        Naming ``friction`` and why.
    """
    from ...geometry import BlockArch
    from ...limit_analysis import standing_with_friction

    if isinstance(structure, BlockArch):
        verdict = standing_with_friction(structure, settings.friction)
        if verdict.part == "joints":  # it stands, but not with this friction
            raise ValueError(f"friction must let the rigid-block model of the assessment "
                             f"hold the structure up, got {settings.friction:g}: "
                             f"{verdict.reason}; give a larger one")


def how_to_restart(out: Path) -> str:
    """What an assessment stopped by an error after it wrote parts says to do next."""
    return (f"the assessment in {out} stopped there: the parts it finished are kept, so once "
            f"the cause is fixed with the same settings, run it again with --resume "
            f"(resume=True); with other settings, choose a new --out (or delete {out})")


def _suite_words(suite: dict | None) -> str:
    """A stored suite in words."""
    kind = (suite or {}).get("kind")
    if kind == "builtin":
        return f"the built-in suite {suite.get('name')!r}"
    if kind == "stochastic":
        return ("synthetic records (the built-in ones were not installed: the 'records' extra "
                "was missing)")
    if kind == "files":
        return f"{len(suite.get('records', []))} record files of --records"
    return "other records"


# ------------------------------------------------------------------------------ directory
def _difference(stored: dict, record: dict) -> str | None:
    if stored.get("suite") != record["suite"] and stored.get("structure") == record["structure"]:
        return (f"its records differ: it was started with {_suite_words(stored.get('suite'))}, "
                f"this run has {_suite_words(record['suite'])} (installing or removing the "
                f"'records' extra changes the default suite); continue it with the records it "
                f"started with (the same --suite or --records), or assess with these records "
                f"in a new --out")
    for key in ("archquake", "structure", "suite"):
        if stored.get(key) != record[key]:
            return f"{key} differs"
    old, new = stored.get("settings", {}), record["settings"]
    for key in sorted(set(old) | set(new)):
        if old.get(key) != new.get(key):
            return (f"setting {key!r} differs: the directory has {old.get(key)!r}, this "
                    f"assessment {new.get(key)!r}")
    return None


def prepare_directory(out: Path, record: dict, resume: bool) -> None:
    """Create the assessment's directory, or check that it continues the same assessment.

    Parameters
    ----------
    out : Path
    record : dict
        What :data:`ASSESSMENT_JSON` records.
    resume : bool

    Raises
    ------
    ValueError
        For a directory that holds another assessment, or one without ``resume``, or files that
        are no assessment's.
    """
    from ...results_io import read_json, write_json

    if out.exists() and not out.is_dir():
        raise ValueError(f"out_dir {out} exists and is not a directory")
    stored = out / ASSESSMENT_JSON
    if stored.is_file():
        if not resume:
            raise ValueError(f"out_dir {out} holds an assessment already; pass resume=True "
                             f"(--resume) to continue it, or choose another directory")
        difference = _difference(read_json(stored), record)
        if difference is not None:
            raise ValueError(f"cannot resume the assessment in {out}: {difference}; use the "
                             f"same structure, records and settings, or another directory")
        return
    if out.is_dir() and any(out.iterdir()):
        raise ValueError(f"out_dir {out} exists and is not empty (and holds no assessment); "
                         f"choose a new or empty directory")
    out.mkdir(parents=True, exist_ok=True)
    write_json(out / STRUCTURE_JSON, record["structure"])
    write_json(stored, record)


def _kept(out: Path, name: str, key: dict):
    """A finished part kept in :data:`PARTS_DIR`, if it was computed from ``key``."""
    from ...results_io import read_json

    path = out / PARTS_DIR / f"{name}.json"
    if not path.is_file():
        return None
    data = read_json(path)
    return data["value"] if data.get("key") == jsonable(key) else None


def _keep(out: Path, name: str, key: dict, value) -> None:
    from ...results_io import write_json

    (out / PARTS_DIR).mkdir(exist_ok=True)
    write_json(out / PARTS_DIR / f"{name}.json", {"key": jsonable(key),
                                                  "value": jsonable(value)})


# ------------------------------------------------------------------------------ the command
def regenerate_command(out: Path, record: dict, settings: AssessmentSettings) -> tuple[str, str]:
    """The command that regenerates the report from the files the assessment wrote (with
    ``--resume``: the finished studies are reused, or computed again where they are gone), and
    a note on what it cannot say.

    Parameters
    ----------
    out : Path
    record : dict
        :data:`ASSESSMENT_JSON`'s content.
    settings : AssessmentSettings

    Returns
    -------
    (str, str)
    """
    words = ["archquake", "assess", "--geometry", str((out / STRUCTURE_JSON).resolve())]
    suite = record["suite"]
    note = ""
    if suite["kind"] == "builtin":
        words += ["--suite", suite["name"]]
        if settings.record_count is not None and not settings.quick:
            note = "It keeps the settings' record_count ground motions of the suite."
    elif suite["kind"] == "files":
        words += ["--records", *(r["path"] for r in suite["records"])]
    else:
        note = ("The synthetic records are drawn again when the built-in ones are not "
                "installed.")
    defaults = AssessmentSettings()
    for name in ("epsilon", "seed", "restitution", "friction", "sa_period"):
        value = getattr(settings, name)
        if value != getattr(defaults, name):
            words += [f"--{name.replace('_', '-')}", f"{value:g}" if isinstance(value, float)
                      else str(value)]
    if settings.quick:
        words.append("--quick")
    if "site" in record:
        from .site import site_words

        words += site_words(record["site"])
    words += ["--out", str(out.resolve()), "--resume"]
    base = (AssessmentSettings.quick_settings if settings.quick else AssessmentSettings)(
        epsilon=settings.epsilon, seed=settings.seed, restitution=settings.restitution,
        friction=settings.friction, sa_period=settings.sa_period)
    if base.to_dict() != settings.to_dict():
        changed = [k for k, v in settings.to_dict().items() if base.to_dict()[k] != v]
        note = (note + " " if note else "") + (
            f"Settings the command's options do not cover ({', '.join(changed)}) are in "
            f"{ASSESSMENT_JSON}: run archquake.report.assess.assess with them.")
    return shlex.join(words), note


# ------------------------------------------------------------------------------ driver
def assess(structure=None, *, records=None, suite: str | None = None,
           epsilon: float | None = None, sa_period: float | None = None, quick: bool = False,
           out_dir, progress: bool = True, resume: bool = False,
           settings: AssessmentSettings | None = None, command: str | None = None,
           site=None, description=None) -> Assessment:
    """Assess a structure: the paper's method and both models applied to it, against real
    records, in a report (module docstring).

    Parameters
    ----------
    structure : BlockArch or BlockAssembly, optional
        An arch (circular, shaped, surveyed) or a :class:`~archquake.geometry.Structure` (on
        piers, under fill); default Oppenheim's arch (:func:`archquake.oppenheim`). A block
        assembly (several spans, an arch of several rings, a drawing) has the assessment of
        :mod:`archquake.report.assess.assembly` (its limit analysis, the rigid-block model's
        check of it and the code's linear check at a site).
    records : str, Path, sequence of them, or RecordSuite, optional
        Record files and folders of the record-based fragility (PEER .AT2, CSV in g, ESM .ASC).
    suite : str, optional
        A built-in suite instead (:data:`archquake.ground_motion.BUILTIN_SUITES`). Default
        (neither): the FEMA P695 pulse-like near-field records when the ``records`` extra is
        installed, else a synthetic suite, with a note saying how to get the real ones.
    epsilon : float, optional
        epsilon of the irregular arches [-], in [0, 1) (default 0.10, the paper's).
    sa_period : float, optional
        Period T [s] of a third record-based fragility in Sa(T).
    quick : bool
        Reduced sizes (:meth:`AssessmentSettings.quick_settings`): a smoke test.
    out_dir : str or Path
        Where the report goes: a new or empty directory (or an assessment's, with ``resume``).
    progress : bool
        A progress bar over the parts on stderr.
    resume : bool
        Continue the assessment saved in ``out_dir`` (same structure, records and settings):
        finished parts and studies are reused.
    settings : AssessmentSettings, optional
        Every setting (instead of ``epsilon``, ``sa_period`` and ``quick``).
    command : str, optional
        The command line that ran the assessment (recorded in the report).
    site : SiteSpec, optional
        A site (:class:`archquake.site.spec.SiteSpec`): the report then adds the code check
        of the collapse mechanism there (NTC 2018 §8.7.1, Circolare 2019 §C8.7.1), the code's
        dynamic route on the assessment's records with the trusted model, and the annual risk
        of collapse from the site's hazard curve (:mod:`archquake.report.assess.site`); the
        first screen gains the verdict.
    description : StructureSpec, optional
        The description a block assembly was built from: where it is several spans of one arch
        (not rings, not a drawing) the report draws irregular bridges around it and gives the
        distribution of their collapse multiplier
        (:func:`~archquake.report.assess.assembly.irregular_part`); ignored otherwise.

    Returns
    -------
    Assessment

    Raises
    ------
    ValueError
        For an invalid setting (naming it), records and suite both given, a bad record file, or
        an ``out_dir`` that holds files of something else or another assessment.
    ImportError
        For a built-in suite named explicitly without the ``records`` extra.

    Examples
    --------
    >>> from archquake.geometry import shaped_arch
    >>> arch = shaped_arch("pointed", span=10, rise=7, thickness=0.6, voussoirs=12)
    >>> report = assess(arch, quick=True, out_dir="pointed-arch")  # doctest: +SKIP
    >>> report.verdict[:16]  # doctest: +SKIP
    'VERDICT: STANDS.'
    """
    from ...geometry import BlockArch
    from ...reference_arches import oppenheim
    from ..running import Steps

    t_start = time.perf_counter()
    if not isinstance(out_dir, str | os.PathLike) or not str(out_dir).strip():
        raise ValueError(f"out_dir must name a directory (str or os.PathLike), got {out_dir!r}")
    structure = oppenheim() if structure is None else structure
    assembly = hasattr(structure, "interfaces") and hasattr(structure, "polygons")
    if not (isinstance(structure, BlockArch) or assembly):
        raise ValueError(f"structure must be an arch, a Structure or a block assembly "
                         f"(archquake.geometry), got {type(structure).__name__}")
    if settings is None:
        options = {"epsilon": AssessmentSettings().epsilon if epsilon is None else epsilon,
                   "sa_period": sa_period}
        settings = (AssessmentSettings.quick_settings(**options) if quick
                    else AssessmentSettings(**options))
    elif epsilon is not None or sa_period is not None or quick:
        raise ValueError("give epsilon, sa_period and quick in settings, or settings not at all")
    if assembly:  # several spans, rings, a drawing: the limit analysis and the rigid blocks
        from ...geometry.fill import check_dynamic_fill
        from ...site.spec import SiteSpec

        check_dynamic_fill(structure)  # before anything is written: the rigid blocks run
        if records is not None or suite is not None:
            raise ValueError("records and suite: the assessment of a block assembly runs no "
                             "record study (archquake.report.assess.assembly.LEFT_OUT)")
        if site is not None and not isinstance(site, SiteSpec):
            raise ValueError(f"site must be a SiteSpec (archquake.site.spec), got "
                             f"{type(site).__name__}")
        return _assess_assembly(structure, settings=settings, out_dir=out_dir,
                               progress=progress, resume=resume, command=command, site=site,
                               description=bridge_description(description))
    check_before_writing(structure, settings)
    out = Path(out_dir)
    timings: dict[str, float] = {}
    t0 = time.perf_counter()
    record_suite, suite_note = choose_suite(records, suite, settings)
    timings["records read"] = time.perf_counter() - t0
    from ...geometry.fill import check_dynamic_fill
    from ...site.spec import SiteSpec

    fill = getattr(structure, "fill", None)
    if fill is not None and fill.has_passive:  # before anything is written: both models run
        check_dynamic_fill(structure)
    if site is not None and not isinstance(site, SiteSpec):
        raise ValueError(f"site must be a SiteSpec (archquake.site.spec), got "
                         f"{type(site).__name__}")
    record = {"archquake": __version__, "structure": structure.to_dict(),
              "settings": settings.to_dict(), "suite": record_suite.to_dict()}
    if site is not None:
        record["site"] = site.to_dict()
    prepare_directory(out, record, resume)
    regenerate, note = regenerate_command(out, record, settings)
    results = {
        "structure": _structure_entry(structure),
        "settings": settings.to_dict(),
        "command": {"given": command, "regenerate": regenerate, "note": note},
    }
    steps = Steps(9 + 2 * len(settings.intensity_measures()) + (site is not None),
                  progress=progress, desc="assess")
    try:
        try:
            computed = _compute(structure, settings, record_suite, suite_note, out, resume,
                                results, steps)
            if site is not None and results["limit"] is not None:
                from .site import site_part

                with steps("code check at the site"):
                    results["site"], computed.site_check = site_part(
                        structure, site, record_suite, results, progress=False)
        except (ValueError, StudyError) as exc:  # after parts were written: how to go on
            stopped = StudyError if isinstance(exc, StudyError) else ValueError
            raise stopped(f"{exc}; {how_to_restart(out)}") from exc
        with steps("figures"):
            figures = _figures(out, structure, results, computed)
        timings.update(steps.timings)
        timings["total"] = time.perf_counter() - t_start
        results["timings"] = timings
        results["environment"] = environment()
        with steps("report"):
            files = write_report(out, results, figures)
    finally:
        steps.close()
    return Assessment(results, out, files)


# ------------------------------------------------------------------------------ assemblies
def _regenerate(command: str | None, out: Path) -> str:
    if not command:
        return ("archquake.report.assess.assess with the same structure and settings, "
                f"out_dir={str(out)!r}, resume=True")
    words = shlex.split(command)
    if "--resume" not in words:
        words.append("--resume")
    return shlex.join(words)


QUICK_ASSEMBLY_RECORDS = 3
"""Records of the record-based fragility of an assembly in a quick assessment (a smoke test;
the code's dynamic route keeps the suite's, from which it selects the compatible ones)."""


def _record_figure(results: dict):
    """The figure of an assembly's record-based fragility (:func:`.assembly.record_part`)."""
    import matplotlib.pyplot as plt

    from ...studies.fits import LognormalFragility

    rec = results["records"]
    capacity = np.sort([r["collapse_pga_g"] for r in rec["records"]
                        if r["collapse_pga_g"] is not None])
    fig, ax = plt.subplots(figsize=(6.5, 4.2), constrained_layout=True)
    levels = np.asarray(rec["levels_g"])
    n = len(rec["records"])
    if capacity.size:
        ax.step(np.concatenate(([levels[0]], capacity)),
                np.arange(capacity.size + 1) / n, where="post", color="0.3",
                label=f"{n} records")
    if rec["lognormal"]:
        fit = LognormalFragility(rec["lognormal"]["median"], rec["lognormal"]["dispersion"])
        x = np.geomspace(levels[0], levels[-1], 200)
        ax.plot(x, fit(x), color="tab:red",
                label=f"lognormal: median {fit.median:.3f} g, beta {fit.dispersion:.2f}")
    ax.axvline(results["limit"]["k"], color="0.5", linestyle="--", linewidth=1)
    ax.set_xscale("log")
    ticks = [t for t in (0.05, 0.1, 0.2, 0.5, 1.0, 2.0, 5.0, 10.0)
             if levels[0] <= t <= levels[-1]]
    ax.set_xticks(ticks, [f"{t:g}" for t in ticks])
    ax.xaxis.set_minor_formatter(plt.NullFormatter())
    ax.set_xlabel("PGA [g]")
    ax.set_ylabel("probability of collapse [-]")
    ax.set_ylim(0, 1.02)
    ax.legend(loc="lower right")
    ax.set_title("Rigid blocks: collapse under the records, scaled")
    return fig


def bridge_description(description):
    """The description of a bridge of several spans of one arch, whose irregular bridges an
    assessment draws (:func:`assess`'s ``description``); None for none, and for rings or a
    geometry file (a surveyed arch has no centreline to perturb)."""
    from ...geometry.spec import StructureSpec

    if description is None:
        return None
    if not isinstance(description, StructureSpec):
        raise ValueError(f"description must be a StructureSpec (archquake.geometry) or None, "
                         f"got {type(description).__name__}")
    if not description.bridge_of_arches or description.geometry is not None:
        return None
    return description


def _assess_assembly(structure, *, settings, out_dir, progress: bool = True,
                    resume: bool = False, command: str | None = None, site=None,
                    description=None):
    """Assess a block assembly (:mod:`archquake.report.assess.assembly`): :func:`assess` of
    one.

    Parameters
    ----------
    structure : BlockAssembly
        Several spans (:func:`~archquake.geometry.bridge.multi_span`), an arch of several rings
        (:func:`~archquake.geometry.multi_ring`), or any assembly.
    settings : AssessmentSettings
        Its ``friction`` is that of the interfaces without their own; its sizes of studies do
        not apply.
    out_dir : str or Path
    progress : bool
    resume : bool
        The assessment is computed again (it keeps no parts), into the same directory.
    command : str, optional
        The command line that ran it.
    site : SiteSpec, optional
        The site of the code check.
    description : StructureSpec, optional
        The description of a bridge of several spans of one arch: its irregular bridges'
        multipliers are drawn (:func:`~.assembly.irregular_part`).

    Returns
    -------
    Assessment
    """
    import matplotlib

    matplotlib.use("Agg")
    from ...errors import CannotStandError
    from ...plotting import plot_assembly_limits
    from ..render import save, write_html, write_markdown
    from ..running import Steps
    from .assembly import (
        LEFT_OUT,
        activation_part,
        assembly_name,
        assembly_risk,
        domain_part,
        dynamic_part,
        irregular_part,
        limit_part,
        record_part,
        sections,
    )

    t_start = time.perf_counter()
    out = Path(out_dir)
    data = structure.to_dict() if hasattr(structure, "to_dict") else {
        "polygons": [np.asarray(p).tolist() for p in structure.polygons],
        "names": list(structure.names or ()), "kind": type(structure).__name__}
    record = {"archquake": __version__, "structure": data, "settings": settings.to_dict(),
              "suite": {"kind": "none"}}
    if site is not None:
        record["site"] = site.to_dict()
    if description is not None:
        record["description"] = description.to_dict()
    prepare_directory(out, record, resume)
    results: dict = {
        "structure": {"name": assembly_name(structure), "kind": type(structure).__name__,
                      "blocks": structure.n_blocks,
                      "interfaces": int(len(structure.interfaces.a))},
        "settings": settings.to_dict(),
        "command": {"given": command, "regenerate": _regenerate(command, out), "note": ""},
        "left_out": list(LEFT_OUT)}
    steps = Steps(5 + 2 * (site is not None) + (description is not None), progress=progress,
                  desc="assess")
    timings = {}
    figures = {}
    domain = None
    try:
        with steps("limit analysis"):
            try:
                summary, laws, governing = limit_part(structure, settings.friction)
            except CannotStandError as exc:
                summary, laws, governing = None, None, None
                results["cannot_stand"] = str(exc)
            results["limit"] = summary
        if summary is not None and description is not None:
            with steps("irregular bridges (limit analysis)"):
                results["irregular"] = irregular_part(description, summary["k"], settings)
        if summary is not None:
            with steps("rigid-block check of the limit"):
                results["rigid_blocks"] = activation_part(structure, summary["k"],
                                                          summary["direction"],
                                                          settings.friction)
            with steps("failure domain under pulses (rigid blocks)"):
                results["domain"], domain = domain_part(structure, summary["k"],
                                                        summary["direction"], settings,
                                                        results["rigid_blocks"])
            suite, records_note = choose_suite(settings=settings)
            with steps("record-based fragility (rigid blocks)"):
                fragility_suite = (record_parts.select_records(suite, QUICK_ASSEMBLY_RECORDS)
                                   if settings.quick else suite)
                results["records"] = {**record_part(structure, summary["k"], fragility_suite,
                                                    settings.friction),
                                      "records_note": records_note}
        if site is not None and summary is not None:
            from ...site.local_mechanism import check_local_mechanism

            with steps("code check at the site"):
                check = check_local_mechanism(structure, site.actions(),
                                              confidence_factor=site.fc, limit=governing)
                results["site"] = {
                    "site": site.to_dict(), "describe": site.describe(),
                    "check": check.to_dict(),
                    "risk": assembly_risk(site, results["records"])}
            with steps("code's dynamic route (rigid blocks)"):
                results["site"]["dynamic"] = {
                    **dynamic_part(structure, site, suite, settings.friction, progress),
                    "records_note": records_note}
        with steps("figures"):
            if laws is not None:
                from .. import render

                fig = plot_assembly_limits(laws)
                name = save(fig, out, "fig1_collapse.png")
                figures["collapse"] = render.Figure(
                    name, "Fig. 1", "The collapse of the structure toward +x (left) and -x "
                    "(right), one row per friction law: the blocks (grey), the mechanism's "
                    "displaced blocks (red outline), interfaces that rock (red, the hinge a "
                    "dot), slide (blue), both (purple) or separate (orange), the pressure "
                    "points of the loaded interfaces (black).", None)
            if "quantiles" in (results.get("irregular") or {}):
                from ...plotting import plot_k_distribution
                from .. import render

                r = results["irregular"]
                ax = plot_k_distribution([x for x in r["k"] if x is not None], r["k_nominal"],
                                         f"bridges, epsilon {r['epsilon']:g}, seed {r['seed']}")
                ax.figure.set_layout_engine("constrained")
                figures["irregular"] = render.Figure(
                    save(ax.figure, out, "fig1b_irregular_bridges.png"), "Fig. 1b",
                    "The collapse multiplier k of irregular bridges around this one (every "
                    "span its own irregular arch): the fraction of them with a lower k, and "
                    "the nominal bridge's k (dashed).", None)
            if domain is not None:
                import matplotlib.pyplot as plt

                from ...plotting import plot_failure_domain

                fig, ax = plt.subplots(figsize=(7.5, 5.0), constrained_layout=True)
                plot_failure_domain(domain, ax)
                ax.set_title(f"Rigid blocks: Oppenheim's pulse, the first pushing toward "
                             f"{results['domain']['direction']}")  # not an arch's Mech-l/r
                figures["domain"] = render.Figure(
                    save(fig, out, "fig2_failure_domain.png"), "Fig. 2",
                    "The rigid-block model's failure domain under Oppenheim's pulse: no "
                    "motion, recovery and collapse over the pulse duration t_p and amplitude; "
                    "dashed: the collapse multiplier k of the limit analysis.", None)
            if "lognormal" in (results.get("records") or {}):
                figures["records"] = render.Figure(
                    save(_record_figure(results), out, "fig3_record_fragility.png"),
                    "Fig. 3", "The record-based collapse fragility with the rigid-block model: "
                    "the records' collapse PGA (steps: the share of records collapsed at or "
                    "below it) and the lognormal fit (line); dashed: k g.", None)
        timings.update(steps.timings)
        timings["total"] = time.perf_counter() - t_start
        results["timings"] = timings
        results["environment"] = environment()
        with steps("report"):
            results["figures"] = {k: {"file": f.file, "label": f.label, "caption": f.caption}
                                  for k, f in figures.items()}
            results["files"] = ["report.html", "report.md", "results.json",
                                *(f.file for f in figures.values())]
            from ...results_io import write_json

            write_json(out / "results.json", jsonable(results))
            document = Document(TITLE, f"Seismic assessment of {results['structure']['name']}",
                                sections(results, figures), verdicts=False, style=STYLE)
            write_html(out / "report.html", document)
            write_markdown(out / "report.md", document)
    finally:
        steps.close()
    results["verdict"] = {"stands": results["limit"] is not None}
    return Assessment(results, out, tuple(results["files"]))



def structure_name(structure) -> str:
    """A short name of a structure for the report's heading: its kind, main sizes and blocks,
    and whether it stands on piers or carries fill.

    Parameters
    ----------
    structure : BlockArch

    Returns
    -------
    str
    """
    import math

    from ...geometry import CircularArch

    arch = getattr(structure, "arch", structure)
    n = arch.n_voussoirs
    if isinstance(arch, CircularArch):
        name = (f"circular arch, R = {float(np.mean(arch.radii)):.4g} m, embrace "
                f"{math.degrees(arch.embrace):.4g} deg, t = {arch.thickness_scale:.3g} m, "
                f"{n} voussoirs")
    elif hasattr(arch, "centreline"):
        line = arch.centreline
        name = (f"{line.shape} arch, span {line.span:.4g} m, rise {line.rise:.4g} m, t = "
                f"{arch.thickness_scale:.3g} m, {n} voussoirs")
    else:
        name = f"surveyed arch of {n} blocks"
    if getattr(structure, "left", None) is not None or getattr(structure, "right", None):
        name += ", on piers"
    if getattr(structure, "fill", None) is not None:
        name += ", under fill"
    return name


def _structure_entry(structure) -> dict:
    from ...geometry.structure import describe_arch

    description = describe_arch(structure)
    if description.startswith("n ="):
        description = "circular arch, " + description
    return {"name": structure_name(structure), "description": description,
            "kind": type(structure).__name__, "blocks": structure.n_voussoirs,
            "file": STRUCTURE_JSON, "data": structure.to_dict()}


@dataclass
class _Computed:
    """The values the figures are drawn from."""

    limit: object = None
    four_link: object = None
    pulses: object = None
    irregularity: object = None
    records: dict | None = None
    rigid_block_irregularity: object = None
    site_check: object = None


def _compute(structure, settings: AssessmentSettings, suite, suite_note: str, out: Path,
             resume: bool, results: dict, steps) -> _Computed:
    """Run the parts in order, filling ``results``; the rigid blocks on a second process."""
    from ...limit_analysis import geometric_safety_factor
    from ...studies.failure_domain import FailureDomain
    from ..running import Background

    computed = _Computed()
    with steps("limit analysis"):
        limit = parts.limit_part(structure)
        results["verdict"] = limit.summary["verdict"]
        results["limit"] = ({k: v for k, v in limit.summary.items() if k != "verdict"}
                            if limit.collapses else None)
        results["safety"] = geometric_safety_factor(structure).to_dict()
        results["sliding"] = (parts.sliding_part(structure, settings.friction)
                              if limit.collapses else None)
    computed.limit = limit
    scale = time_scale(structure)
    results["sizes"] = {"time_scale": scale}
    if not limit.collapses:
        results.update(four_link=None, pulses={}, irregularity={}, records={},
                       summary={"stands": results["verdict"]["stands"]})
        return computed
    k, governing = results["limit"]["k"], results["limit"]["governing"]
    durations = settings.pulse_durations(structure)
    grid = parts.pulse_grid(k, settings)
    rb_key = {"durations": durations, "amplitudes_g": grid, "direction": governing,
              "resolution": settings.domain_resolution_g, "friction": settings.friction,
              "form": "FailureDomain.to_dict"}
    kept = _kept(out, "rigid_blocks_domain", rb_key) if resume else None
    with Background.start() as background:
        task = None
        if kept is None:
            # the second process compiles the rigid blocks on a first run: said here, once
            announce_all(rigid_block_engines())
            task = background.submit(parts.rigid_block_domain, structure, durations, grid,
                                     governing, settings.domain_resolution_g, settings.friction)
        with steps("four-link mechanisms"):
            four_link = parts.four_link_part(structure, settings)
            results["four_link"] = four_link.summary
        computed.four_link = four_link
        model = four_link.model
        with steps("failure domain, four-link"):
            fl_domains = (None if model is None else parts.four_link_domains(
                model, durations, grid, settings.domain_resolution_g))
        with steps("irregularity under pulses"):
            results["irregularity"], computed.irregularity = _irregularity(
                structure, settings, model, out, resume, results)
        results["records"], computed.records, check = _records(
            structure, settings, suite, suite_note, model, out, resume, steps, results,
            background)
        with steps("waiting for the rigid blocks (second process)"):
            background_runs = {}
            if task is None:
                rigid = FailureDomain.from_dict(kept)
                background_runs["rigid-block failure domain"] = "kept from the run resumed"
            else:
                run = task.result()
                rigid = run.result
                _keep(out, "rigid_blocks_domain", rb_key, rigid.to_dict())
                background_runs["rigid-block failure domain"] = run.describe()
            if check is not None:
                key, level, pending, checked = check
                if isinstance(pending, list):
                    background_runs["rigid-block check under the records"] = ("kept from the run "
                                                                         "resumed")
                    statuses = pending
                else:
                    run = pending.result()
                    statuses = run.result
                    _keep(out, "record_check", key, statuses)
                    background_runs["rigid-block check under the records"] = run.describe()
                results["records"]["check"] = record_parts.record_check(model, checked, level,
                                                                        statuses)
            results["background"] = background_runs
    pulses = parts.pulse_part(fl_domains, rigid, governing, grid)
    results["pulses"] = pulses.summary
    computed.pulses = pulses
    results["trusted"] = parts.trusted_model(pulses.summary, model is not None)
    results["rigid_block_studies"] = {}
    if results["trusted"]["model"] == "rigid-blocks" and model is not None:
        results["rigid_block_studies"] = _rigid_block_studies(
            structure, settings, suite, out, resume, steps, results, computed)
    results["sizes"].update(_sizes(settings, results, suite))
    results["summary"] = _summary(results)
    return computed


def _rigid_block_studies(structure, settings, suite, out: Path, resume: bool, steps,
                         results: dict, computed: _Computed) -> dict:
    """The studies of irregular arches and records again with the rigid-block model, where it
    is the one the first screen trusts: the same durations, amplitudes, records and stripes as
    the four-link studies, on every processor (the second process is done by now)."""
    from ...execution import process_pool

    out_studies: dict = {}
    workers = min(2, os.cpu_count() or 1)
    with contextlib.ExitStack() as stack:
        pool = stack.enter_context(process_pool(workers)) if workers > 1 else None
        if computed.irregularity is not None:
            study = computed.irregularity.result.settings
            with steps("irregularity under pulses, rigid-block model"):
                part = parts.irregularity_part(
                    structure, settings, study.durations, study.amplitudes_g,
                    out / (FRAGILITY_DIR + RIGID_BLOCKS_SUFFIX), resume, model="rigid-blocks",
                    pool=pool)
            computed.rigid_block_irregularity = part
            out_studies["irregularity"] = part.summary
        ims = (results.get("records") or {}).get("ims") or {}
        entries = {}
        for im, entry in ims.items():
            with steps(f"records: {text.im_label(im)}, rigid-block model"):
                if entry.get("structure_only"):
                    model = settings.model_spec("rigid-blocks").build(structure)
                    stripes = record_parts.structure_stripes(
                        model, suite, im, entry["levels"], bootstrap=settings.bootstrap,
                        seed=settings.seed)
                    _four_link_nrml_aside(out, results["records"]["ims"][im])
                    nrml, why = record_parts.export_structure_nrml(stripes, out)
                    entries[im] = record_parts.structure_stripes_summary(stripes, nrml, why)
                else:
                    directory = out / (RECORDS_DIR.format(im=record_parts.file_stem(im))
                                       + RIGID_BLOCKS_SUFFIX)
                    result = record_parts.record_study(
                        structure, suite, im, entry["levels"], settings, directory, resume,
                        model="rigid-blocks", pool=pool)
                    _four_link_nrml_aside(out, results["records"]["ims"][im])
                    nrml, why = record_parts.export_nrml(result, out, im)
                    entries[im] = record_parts.record_summary(result, nrml, why)
        if entries:
            out_studies["records"] = {"ims": entries}
    return out_studies


FOUR_LINK_NRML_SUFFIX = "_four_link"
"""Added to the stem of the four-link model's NRML file where the rigid blocks are the model
the report trusts: ``fragility_<im>.xml`` is then the rigid blocks' (the file a risk study
reads), ``fragility_<im>_four_link.xml`` the four-link model's, kept beside it."""


def _four_link_nrml_aside(out: Path, entry: dict) -> None:
    """Move the four-link model's NRML file of a record study aside (renamed with
    :data:`FOUR_LINK_NRML_SUFFIX`), so that the trusted model's takes its name."""
    name = entry.get("nrml")
    if not name:
        return
    aside = f"{Path(name).stem}{FOUR_LINK_NRML_SUFFIX}.xml"
    (out / name).replace(out / aside)
    entry["nrml"] = aside


def _irregularity(structure, settings, model, out: Path, resume: bool, results: dict):
    """The irregularity part, or why it was not run."""
    if model is None:
        return {"skipped": "the four-link model, which the studies of irregular arches run, "
                           "does not apply to this structure"}, None
    if not parts.has_centreline(structure):
        return {"skipped": "irregular arches are drawn around an arch with a centreline "
                           "(circular or shaped); a surveyed arch has none"}, None
    durations = settings.fragility_durations(structure)
    domains = parts.four_link_domains(model, durations,
                                      parts.pulse_grid(results["limit"]["k"], settings), 1e-3)
    fa = np.fmin(domains["l"].failure_accelerations_g, domains["r"].failure_accelerations_g)
    amplitudes = parts.fragility_amplitudes(fa, results["limit"]["k"], settings)
    part = parts.irregularity_part(structure, settings, durations, amplitudes,
                                   out / FRAGILITY_DIR, resume)
    return part.summary, part


def _records(structure, settings, suite, note: str, model, out: Path, resume: bool, steps,
             results: dict, background):
    """The record-based fragility in every intensity measure, or why it was not run; and the
    check of the two models under the records, given to the second process: ``(key, level,
    task or the kept statuses, the records checked)`` or None."""
    from ...studies.stripes import median_collapse_pga, record_pilot, stripe_levels

    if model is None:
        with steps("records"):
            return {"skipped": "the four-link model, which the record-based study runs, does "
                               "not apply to this structure"}, None, None
    irregular = parts.has_centreline(structure)
    with steps("records: where the stripes go"):
        key = {"suite": suite.to_dict(), "model": model.describe()}
        pilot = _kept(out, "record_pilot", key) if resume else None
        if pilot is None:
            pilot = record_pilot(model, suite)
            _keep(out, "record_pilot", key, pilot)
    check = None
    level = median_collapse_pga(pilot)
    if level is not None:
        checked = record_parts.select_records(suite, record_parts.CHECK_RECORDS)
        check_key = {"suite": checked.to_dict(), "level_pga": level,
                     "friction": settings.friction}
        kept = _kept(out, "record_check", check_key) if resume else None
        check = (check_key, level, kept if kept is not None else background.submit(
            record_parts.rigid_block_record_outcomes, structure, checked.to_dict(), level,
            settings.friction), checked)
    studies, entries = {}, {}
    quantiles = (results.get("irregularity") or {}).get("limit_sample", {}).get("quantiles")
    weaker = 1.0
    if quantiles and settings.epsilon > 0:
        weaker = float(np.clip(quantiles["0.05"] / results["limit"]["k"], 0.25, 1.0))
    for im in settings.intensity_measures():
        with steps(f"records: {text.im_label(im)}"):
            levels = stripe_levels(pilot, suite, im, settings.record_levels, weaker)
            if irregular:
                directory = out / RECORDS_DIR.format(im=record_parts.file_stem(im))

                def study(pool, im=im, levels=levels, directory=directory):
                    return record_parts.record_study(structure, suite, im, levels, settings,
                                                     directory, resume, pool=pool)

                # its chunks on this process and on the second one, idle once its tasks
                # (the rigid blocks' failure domain, the check under the records) are done
                result = background.study(study).result().result
                nrml, why = record_parts.export_nrml(result, out, im)
                entries[im] = record_parts.record_summary(result, nrml, why)
            else:  # no irregular arches around a surveyed arch: the structure alone
                result = record_parts.structure_stripes(
                    model, suite, im, levels, bootstrap=settings.bootstrap, seed=settings.seed)
                nrml, why = record_parts.export_structure_nrml(result, out)
                entries[im] = record_parts.structure_stripes_summary(result, nrml, why)
            studies[im] = result
    pga, pgv = suite.intensities("pga"), suite.intensities("pgv")
    listed = []
    for meta, a, v, f in zip(suite.metadata, pga, pgv, pilot["first_factor"], strict=True):
        keep = {k: meta[k] for k in ("name", "event", "year", "station", "magnitude",
                                     "component", "record_sequence_number", "site_class",
                                     "rupture_distance_km", "vs30", "path") if k in meta}
        keep.update(pga=float(a), pgv=float(v),
                    pilot_first_collapse_pga=None if f is None else float(f * a))
        listed.append(keep)
    return {"suite": {**{k: v for k, v in suite.to_dict().items() if k != "records"},
                      "description": suite.describe(), "count": len(suite)},
            "note": note, "records": listed, "pilot": pilot, "weaker": weaker,
            "ims": entries}, studies, check


def _sizes(settings: AssessmentSettings, results: dict, suite) -> dict:
    """The sizes the assessment ran at (the report says what it reduced)."""
    out = {"pulse_durations": len(results["pulses"]["durations"])}
    irr = results.get("irregularity") or {}
    if "settings" in irr:
        out.update(fragility_arches=irr["settings"]["sample_size"],
                   limit_arches=irr["settings"]["limit_sample_size"])
    rec = results.get("records") or {}
    if "ims" in rec:
        first = next(iter(rec["ims"].values()))
        from ...ground_motion.fema_p695 import BUILTIN_SUITES

        whole = (BUILTIN_SUITES[rec["suite"]["name"]].motions if rec["suite"]["kind"] ==
                 "builtin" else len(suite))
        out.update(record_arches=first["sample_size"], records=first["records"],
                   suite_records=whole, levels=len(first["levels"]))
    rigid = results.get("rigid_block_studies") or {}
    if "irregularity" in rigid:
        out["rigid_block_fragility_arches"] = rigid["irregularity"]["settings"]["sample_size"]
    if "records" in rigid:
        out["rigid_block_record_arches"] = next(iter(rigid["records"]["ims"].values()))[
            "sample_size"]
    return out


def _off_by(four_link, used):
    """The four-link number over the one used, minus 1 (None where either is missing)."""
    if four_link is None or used is None or used == 0:
        return None
    return float(four_link) / float(used) - 1.0


def _record_entry(entry: dict) -> dict:
    keys = ("unit", "lognormal", "nominal_lognormal", "total", "model", "undecided",
            "sample_size", "lognormal_undecided_as_collapse",
            "nominal_lognormal_undecided_as_collapse")
    return {k: entry[k] for k in keys if k in entry}


def _summary(results: dict) -> dict:
    """The numbers of the first screen (also in ``results.json``): each capacity with the
    ``model`` it comes from (``trusted``: :func:`~archquake.report.assess.parts.trusted_model`)
    and, where that is the rigid-block model, the four-link model's beside it (``four_link``,
    with ``off_by``, its number over the one used minus 1, and ``used`` False)."""
    trusted = results.get("trusted") or {"model": "four-link", "agree": True}
    name = trusted["model"]
    rigid = results.get("rigid_block_studies") or {}
    out = {"stands": True, "k": results["limit"]["k"],
           "safety_factor": results["safety"].get("factor"), "model": name,
           "agree": trusted["agree"], "k_from": "limit analysis"}
    rows = results["pulses"]["rows"]
    applies = bool((results.get("four_link") or {}).get("applies"))
    both = [r for r in rows if (r["difference"] if applies else r["rigid_blocks"]) is not None]
    if rows:
        out["pulse_long"] = {**rows[-1], "model": name}
        shorter = [r for r in both if r["duration"] < rows[-1]["duration"]]
        out["pulse_short"] = {**shorter[0], "model": name} if shorter else None
    irr = results.get("irregularity") or {}
    if "durations" in irr:
        q = irr["limit_sample"].get("quantiles") or {}
        curve = irr["durations"][-1]
        entry = {"arches": irr["analysed"], "k_5": q.get("0.05"), "k_5_from": "limit analysis",
                 "curve": curve, "model": irr.get("model", "four-link")}
        if "irregularity" in rigid:
            used = rigid["irregularity"]["durations"][-1]
            entry.update(curve=used, model="rigid-blocks",
                         arches=rigid["irregularity"]["analysed"],
                         undecided=rigid["irregularity"]["undecided"],
                         four_link={"curve": curve, "arches": irr["analysed"], "used": False,
                                    "off_by": _off_by(curve["lognormal_median"],
                                                      used["lognormal_median"])})
        out["irregular"] = entry
    rec = results.get("records") or {}
    if "ims" in rec:
        used_ims = (rigid.get("records") or {}).get("ims") or {}
        out["records"] = {}
        for im, e in rec["ims"].items():
            entry = {**_record_entry(e), "model": e.get("model", "four-link")}
            if im in used_ims:
                r = used_ims[im]
                median = "lognormal" if r["lognormal"]["median"] is not None else (
                    "nominal_lognormal")
                entry = {**_record_entry(r), "four_link": {
                    **_record_entry(e), "used": False,
                    "off_by": _off_by(e[median]["median"], r[median]["median"]),
                    "off_by_of": median}}
            out["records"][im] = entry
        check = rec.get("check")
        if check is not None:
            out["record_check"] = {k: check[k] for k in ("level_pga", "pairs", "agree", "both",
                                                         "neither", "four_link_only",
                                                         "rigid_blocks_only")}
            out["record_check"]["rigid_blocks_undecided"] = check.get("rigid_blocks_undecided")
    return out


# ------------------------------------------------------------------------------ figures
def _figure(directory: Path, name: str, figure, label: str, caption: str) -> Figure:
    return Figure(save(figure, directory, name), label, caption, None)


def _figures(out: Path, structure, results: dict, computed: _Computed) -> dict:
    """Draw and write the figures, each with its caption."""
    import matplotlib

    matplotlib.use("Agg")
    from . import figures as draw

    figures = {}
    limit = computed.limit
    figures["structure"] = _figure(
        out, "fig1_structure.png",
        draw.structure_figure(structure, limit.analyses,
                              title="The structure: " + results["verdict"]["reason"][:80]),
        "Fig. 1", text.structure_caption(results))
    if not limit.collapses:
        return figures
    if computed.four_link.model is not None:
        figures["mechanisms"] = _figure(out, "fig2_mechanisms.png",
                                        draw.mechanisms_figure(computed.four_link.model),
                                        "Fig. 2", text.mechanisms_caption(results))
    figures["domain"] = _figure(out, "fig3_failure_domain.png",
                                draw.domain_figure(computed.pulses), "Fig. 3",
                                text.domain_caption(results))
    if computed.irregularity is not None:
        d = computed.irregularity.result.durations
        shown = [float(d[0])] if d.size == 1 else [float(d[0]), float(d[-1])]
        figures["irregularity"] = _figure(
            out, "fig4_irregularity.png",
            draw.irregularity_figure(computed.irregularity, shown), "Fig. 4",
            text.irregularity_caption(results, shown))
    if computed.records:
        figures["records"] = _figure(out, "fig5_record_fragility.png",
                                     draw.record_figure(computed.records), "Fig. 5",
                                     text.record_caption(results))
    if computed.site_check is not None:
        from .site import caption

        figures["site"] = _figure(out, "fig6_capacity_curve.png",
                                  draw.site_figure(computed.site_check), "Fig. 6",
                                  caption(results["site"]))
    return figures


# ------------------------------------------------------------------------------ rendering
def sections(results: dict, figures: dict) -> list[Section]:
    """The sections of the report, from ``results.json`` and the figures; the summary first.

    Parameters
    ----------
    results : dict
        ``results.json``.
    figures : dict
        :class:`~archquake.report.render.Figure` by key (``structure``, ``mechanisms``,
        ``domain``, ``irregularity``, ``records``; those drawn).

    Returns
    -------
    list of Section
    """
    verdict = results["verdict"]
    kind = "verdict" if verdict["stands"] else "verdict cannot"
    summary = [Paragraph(text.verdict_text(results), kind)]
    warning = text.undecided_warning_text(results)
    if warning:  # said first: the rigid blocks' answers are bounded, not decided
        summary.insert(0, Paragraph(warning, "note"))
    rows = text.summary_rows(results)
    if rows:
        summary.append(Table(["capacity", "value", "from", "the other model, beside"], rows))
        if results.get("trusted"):
            summary.append(Paragraph(text.model_text(results)))
        summary.append(Paragraph(text.agreement_text(results)))
    note = (results.get("records") or {}).get("note")
    if note:
        summary.append(Paragraph(note, "note"))
    if results.get("site"):
        from .site import verdict_text as site_verdict

        summary.insert(2 if warning else 1, Paragraph(site_verdict(results["site"]), "verdict"))
    if results["settings"]["quick"]:
        summary.append(Paragraph("QUICK RUN: reduced sizes for a smoke test, not an "
                                 "assessment.", "note"))
    summary.append(Paragraph("Assumptions (as in the paper, Heyman's for the limit analysis):",
                             "note"))
    summary.append(Bullets(text.ASSUMPTIONS))
    out = [Section("Summary", summary)]
    limit_blocks = [Paragraph(text.structure_text(results)), figures["structure"]]
    if results["limit"] is not None:
        limit_blocks.insert(1, Table(["mechanism", "k [-]", "hinge", "where", "face", "x [m]",
                                      "y [m]"], text.hinge_rows(results)))
    if results.get("sliding"):
        limit_blocks.append(Paragraph(text.sliding_text(results["sliding"]), "note"))
        limit_blocks.append(Table(["mechanism", "law", "k [-]", "rocking joints",
                                   "sliding joints"], text.sliding_rows(results["sliding"])))
    out.append(Section("1. The structure and its limit analysis", limit_blocks))
    if results["limit"] is None:
        out.append(Section("Run, versions and settings", _run_blocks(results)))
        return out
    fl = results["four_link"]
    blocks = [Paragraph(text.mechanisms_text(results))]
    if fl["applies"]:
        blocks += [Table(["quantity", "Mech-l", "Mech-r"], text.mechanism_rows(results)),
                   Table(["restitution rule", "c_lr", "c_rl", "what it is"],
                         text.restitution_rows(results)), figures["mechanisms"]]
    out.append(Section("2. The four-link mechanisms", blocks))
    out.append(Section("3. Failure domain under pulses: both models", [
        Paragraph(text.domain_text(results)),
        Table(text.domain_header(results), text.domain_rows(results)), figures["domain"]]))
    irr = [Paragraph(text.irregularity_text(results))]
    if "durations" in results["irregularity"]:
        irr += [Table(["t_p [s]", "structure's failure acceleration [g]",
                       "lognormal median [g]", "lognormal dispersion",
                       "P_F just below the structure's failure acceleration"],
                      text.irregularity_rows(results)), figures["irregularity"]]
    rigid = results.get("rigid_block_studies") or {}
    if "irregularity" in rigid:
        irr += [Paragraph(text.rigid_irregularity_text(results)),
                Table(["t_p [s]", "structure's failure acceleration [g]",
                       "lognormal median [g]", "lognormal dispersion",
                       "P_F just below the structure's failure acceleration",
                       "undecided analyses"], text.irregularity_rows(results, rigid=True))]
    out.append(Section("4. Irregular masonry", irr))
    rec = [Paragraph(text.record_text(results))]
    if "ims" in results["records"]:
        rec += [Table(["IM [unit]", "levels", "median, irregular arches", "total beta",
                       "median, the structure", "record-to-record beta", "geometric beta",
                       "NRML file"], text.record_rows(results)), figures["records"],
                Paragraph("The records, and the level at which each first collapses the "
                          "structure itself (either polarity; '-': not within the stripes):"),
                Table(text.record_list_header(results), text.record_list_rows(results))]
    if "records" in rigid:
        rec += [Paragraph(text.rigid_record_text(results)),
                Table(["IM [unit]", "levels", "median, irregular arches", "total beta",
                       "median, the structure", "record-to-record beta", "geometric beta",
                       "undecided analyses"], text.record_rows(results, rigid=True))]
    out.append(Section("5. Record-based fragility", rec))
    if results.get("site"):
        out.append(Section("6. Is it safe here? The code check at the site",
                           _site_blocks(results, figures)))
    out.append(Section("Run, versions and settings", _run_blocks(results)))
    return out


def _site_blocks(results: dict, figures: dict) -> list:
    from . import site as words

    site = results["site"]
    blocks = [Paragraph(words.check_text(site)),
              Table(["limit state", "route", "mechanism", "capacity", "demand",
                     "capacity / demand", "verdict", "holds up to a_g"],
                    words.check_rows(site))]
    if "site" in figures:
        blocks.append(figures["site"])
    blocks.append(Paragraph(words.dynamic_text(site)))
    rows = words.dynamic_rows(site)
    if rows:
        blocks.append(Table(["model", "record", "factor", "outcome", "peak rotation [rad]"],
                            rows))
    blocks.append(Paragraph(words.risk_text(site)))
    return blocks


def _run_blocks(results: dict) -> list:
    blocks = []
    if "pulses" in results and results["pulses"]:
        blocks.append(Paragraph(text.reduced_text(results)))
    blocks.append(Table(["part", "wall time [s]"],
                        [[k, f"{v:.2f}"] for k, v in results["timings"].items()]))
    for task, run in (results.get("background") or {}).items():
        if isinstance(run, dict):
            blocks.append(Paragraph(f"The {task} ran on {run['ran on']} beside the parts above: "
                                    f"{run['seconds']:.1f} s of analyses, "
                                    f"{run['wall_seconds']:.1f} s from its start to its "
                                    f"result."))
        else:
            blocks.append(Paragraph(f"The {task}: {run}."))
    env = results["environment"]
    blocks.append(Paragraph("Versions: " + ", ".join(f"{k} {v}" for k, v in env.items()) + "."))
    blocks.append(Paragraph("Settings: " + ", ".join(f"{k} = {v}" for k, v in
                                                     results["settings"].items()) + "."))
    blocks.append(Paragraph("To regenerate this report:"))
    blocks.append(Bullets(text.command_text(results)))
    return blocks


def write_report(directory, results: dict, figures: dict) -> tuple[str, ...]:
    """Write ``report.html``, ``report.md`` and ``results.json`` into ``directory`` (the figures
    are there already).

    Parameters
    ----------
    directory : str or Path
    results : dict
        ``results.json``.
    figures : dict
        The figures by key.

    Returns
    -------
    tuple of str
        Every file of the report in ``directory``.
    """
    from ...results_io import write_json

    out = Path(directory)
    results["figures"] = {key: {"file": f.file, "label": f.label, "caption": f.caption}
                          for key, f in figures.items()}
    rigid = ((results.get("rigid_block_studies") or {}).get("records") or {}).get("ims", {})
    nrml = [e["nrml"] for e in [*(results.get("records") or {}).get("ims", {}).values(),
                                *rigid.values()] if e.get("nrml")]
    results["files"] = ["report.html", "report.md", "results.json",
                        *(f.file for f in figures.values()), *nrml]
    write_json(out / "results.json", jsonable(results))
    document = Document(TITLE, text.heading(results), sections(results, figures),
                        verdicts=False, style=STYLE)
    write_html(out / "report.html", document)
    write_markdown(out / "report.md", document)
    return tuple(results["files"])


__all__ = ["ASSESSMENT_JSON", "FRAGILITY_DIR", "PARTS_DIR", "RECORDS_DIR", "RIGID_BLOCKS_SUFFIX",
           "STRUCTURE_JSON",
           "STYLE", "TITLE", "Assessment", "assess", "choose_suite", "prepare_directory",
           "regenerate_command", "sections", "structure_name", "write_report"]
