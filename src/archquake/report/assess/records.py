"""The record-based fragility of an assessment: the records, the multiple-stripe analysis of the
structure and its irregular arches in each intensity measure (or of the structure alone), what
``results.json`` records of it, its OpenQuake NRML file, and the two models' check under the
records.

- :func:`select_records`: the ground motions an assessment keeps of a suite;
- :func:`record_study`, :func:`record_summary`, :func:`export_nrml`: the study of
  :func:`archquake.studies.record_fragility.run_record_fragility` at the stripes of
  :func:`archquake.studies.stripes.stripe_levels`, its numbers and its NRML file;
- :func:`structure_stripes`, :func:`structure_stripes_summary`, :func:`export_structure_nrml`:
  the same for a structure without irregular arches around it (a surveyed arch);
- :func:`rigid_block_record_outcomes`, :func:`record_check`: both models under the records
  scaled to one PGA (:func:`archquake.studies.stripes.median_collapse_pga`).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ...checks import json_float
from .settings import AssessmentSettings


def select_records(suite, count: int | None):
    """The first ``count`` ground motions of a suite (all when None or the suite is not larger).

    A built-in suite keeps its fault-normal components (component ``"a"``, which carries the
    pulse of a near-field record) first, in suite order, then the others; files the first by
    name; a stochastic suite its first ``count`` motions.

    Parameters
    ----------
    suite : RecordSuite
    count : int or None

    Returns
    -------
    RecordSuite
    """
    from ...ground_motion.suites import RecordSuite

    if count is None or count >= len(suite):
        return suite
    if suite.kind == "builtin":
        meta = suite.metadata
        order = ([m["name"] for m in meta if m.get("component") == "a"]
                 + [m["name"] for m in meta if m.get("component") != "a"])
        spec = suite.builtin
        return RecordSuite.from_builtin(spec["name"], spec["scaling"], records=order[:count])
    if suite.kind == "files":
        return RecordSuite(files=suite.files[:count])
    spec = suite.stochastic
    return RecordSuite.from_stochastic(count, spec["seed"], **spec["parameters"])


def record_study(structure, suite, im: str, levels, settings: AssessmentSettings,
                 directory=None, resume: bool = False, model: str = "four-link", pool=None):
    """One record-based fragility (multiple-stripe analysis) of the structure and its irregular
    arches, with the model ``model``
    (:func:`archquake.studies.record_fragility.run_record_fragility`): ``record_sample_size``
    arches with the four-link model, ``rigid_block_record_sample_size`` with the rigid blocks.

    Parameters
    ----------
    structure : BlockArch
    suite : RecordSuite
    im : str
        The intensity measure of the stripes.
    levels : sequence of float
        The stripes [the IM's unit] (:func:`archquake.studies.stripes.stripe_levels`).
    settings : AssessmentSettings
        epsilon, seed, restitution, h, bootstrap.
    directory : str or Path, optional
        The study's directory (resumable).
    resume : bool
        Continue the study saved in ``directory``, if one was started there
        (:func:`archquake.execution.resumable_study`).
    model : {"four-link", "rigid-blocks"}
        The model of every arch (:meth:`AssessmentSettings.model_spec`).
    pool : WorkerPool, optional
        Worker processes to run the study on (:func:`archquake.execution.process_pool`);
        None: in this process. The results do not depend on it.

    Returns
    -------
    RecordFragilityResult
    """
    from ...execution import resumable_study
    from ...studies.record_fragility import RecordFragilitySettings, run_record_fragility

    spec = settings.model_spec(model)
    size = (settings.record_sample_size if spec.grid_in_one_call
            else settings.rigid_block_record_sample_size)
    study = RecordFragilitySettings(
        suite=suite, levels=tuple(levels), im=im, nominal=structure, sample_size=size,
        epsilon=settings.epsilon, seed=settings.seed, model=spec, bootstrap=settings.bootstrap)
    resume = resume and resumable_study(directory) is not None  # only where it was started
    return run_record_fragility(study, directory, resume=resume, progress=False,
                                **({"backend": "serial"} if pool is None else {"pool": pool}))


CHECK_RECORDS = 14
"""Ground motions of the rigid blocks' check under the records: the first of the suite in the
order of :func:`select_records` (of a FEMA P695 near-field set, its 14 fault-normal components,
which carry the pulses). A rigid-block analysis of a record costs about a thousand four-link
ones."""


def rigid_block_record_outcomes(structure, suite: dict, level_pga: float,
                                friction: float) -> list[list[int]]:
    """The rigid-block model's outcome under every record of a suite scaled to one PGA, in both
    polarities (a task for the second process: module level, picklable arguments).

    Parameters
    ----------
    structure : BlockArch
    suite : dict
        :meth:`archquake.ground_motion.RecordSuite.to_dict`.
    level_pga : float
        The PGA every record is scaled to [g].
    friction : float
        Coulomb friction coefficient of the joints [-].

    Returns
    -------
    list of [int, int]
        Per record, the status code (:class:`archquake.status.Status`: 0 rest, 1 recovery,
        2 collapse, -1 undecided) as recorded and reversed.
    """
    from ...ground_motion.suites import RecordSuite
    from ...models import ModelSpec

    model = ModelSpec("rigid-blocks", friction=friction).build(structure)
    out = []
    with warnings.catch_warnings():
        # the records are read again here: the assessment said what it had to say of each
        # when it read the suite, once (a warning of this process would be printed raw)
        warnings.filterwarnings("ignore", message="record file .* is implausible")
        records = RecordSuite.from_dict(suite)
        for motion, pga in zip(records.motions(cached=True), records.intensities("pga"),
                               strict=True):
            factor = level_pga / float(pga)
            out.append([int(model.outcome(motion.scaled(sign * factor)).status)
                        for sign in (1.0, -1.0)])
    return out


def record_check(model, suite, level_pga: float, rigid_blocks: list) -> dict:
    """Both models under every record of the suite scaled to one PGA, in both polarities: on
    how many of them they agree about collapse.

    Parameters
    ----------
    model : FourLinkModel
        The structure's four-link model.
    suite : RecordSuite
    level_pga : float
        The PGA every record is scaled to [g]
        (:func:`archquake.studies.stripes.median_collapse_pga`).
    rigid_blocks : list of [int, int]
        :func:`rigid_block_record_outcomes` at the same level.

    Returns
    -------
    dict
        ``level_pga`` [g], ``pairs`` (records x 2), the counts ``both``, ``neither``,
        ``four_link_only`` and ``rigid_blocks_only`` (collapse), ``rigid_blocks_undecided``
        (pairs the rigid blocks left undecided, in none of the four), ``agree`` (the fraction
        of pairs where the two agree; an undecided pair is not known to agree) and
        ``by_record`` (``name``, the status codes of both models as recorded and reversed).
    """
    from ...status import Status
    from ...studies.record_fragility import record_outcomes

    rows, counts = [], {"both": 0, "neither": 0, "four_link_only": 0, "rigid_blocks_only": 0,
                        "rigid_blocks_undecided": 0}
    for motion, pga, rb, name in zip(suite.motions(cached=True), suite.intensities("pga"),
                                     rigid_blocks, suite.names, strict=True):
        factor = level_pga / float(pga)
        fl = [int(v) for v in record_outcomes(model, motion, [factor, -factor])["status"]]
        for a, b in zip(fl, rb, strict=True):
            if b == Status.UNDECIDED:
                counts["rigid_blocks_undecided"] += 1
                continue
            key = {(True, True): "both", (False, False): "neither",
                   (True, False): "four_link_only", (False, True): "rigid_blocks_only"}[
                (a == 2, b == 2)]
            counts[key] += 1
        rows.append({"name": name, "four_link": fl, "rigid_blocks": [int(v) for v in rb]})
    pairs = 2 * len(rows)
    return {"level_pga": level_pga, "pairs": pairs, **counts,
            "agree": (counts["both"] + counts["neither"]) / pairs, "by_record": rows}


def file_stem(im: str) -> str:
    """An intensity measure's name as part of a file name: ``sa(0.5)`` -> ``sa_0.5``."""
    return im.replace("(", "_").replace(")", "")


def record_summary(result, nrml: str | None, nrml_note: str) -> dict:
    """What ``results.json`` records of one record-based fragility.

    Parameters
    ----------
    result : RecordFragilityResult
    nrml : str or None
        File name of its NRML export (None: none written).
    nrml_note : str
        Why there is none, or ``""``.

    Returns
    -------
    dict
        ``unit``, ``levels``, ``probability``, ``nominal_probability``, ``lognormal`` and
        ``nominal_lognormal`` (``median`` [unit], ``dispersion`` [-]), the dispersions
        (``record_to_record``, ``geometric``, ``total``, ``srss``), ``analyses``, ``arches``,
        the nominal structure's lowest collapsing level by record (``first_collapse``),
        ``nrml``, ``model`` (the name of the model), ``undecided`` (the count of undecided
        analyses, :mod:`archquake.studies.undecided`) and, where some are, the fits with every
        undecided pair counted as a failure (``lognormal_undecided_as_collapse``,
        ``nominal_lognormal_undecided_as_collapse``: the other end of the range the median
        lies in).
    """
    from ...studies.fits import fit_lognormal_or_none

    summary = result.summary()
    variability = summary["variability"]
    incremental = result.incremental()
    nominal = incremental[incremental["arch"] == -1]
    first = {str(r): json_float(v) for r, v in zip(nominal["record"], nominal["first_collapse"],
                                                     strict=True)}
    return {
        "im": summary["im"], "unit": summary["im_unit"], "levels": summary["levels"],
        "records": len(result.records), "sample_size": result.settings.sample_size,
        "analysed": result.analysed, "arches": summary["arches"],
        "probability": summary["probability"],
        "nominal_probability": summary["nominal"]["probability"],
        "lognormal": {k: summary["lognormal"][k] for k in ("median", "dispersion")},
        "nominal_lognormal": {k: summary["nominal"]["lognormal"][k]
                              for k in ("median", "dispersion")},
        **{k: variability[k] for k in ("record_to_record", "geometric", "total", "srss")},
        "analyses": summary["analyses"], "first_collapse": first,
        "nrml": nrml, "nrml_note": nrml_note,
        "model": result.settings.model.name, "undecided": summary["undecided"],
        **_undecided_fits(result, fit_lognormal_or_none),
    }


def _undecided_fits(result, fit) -> dict:
    """The lognormal fits with the undecided pairs counted as failures (none: {})."""
    if not (result.undecided.any() or result.nominal_undecided.any()):
        return {}
    levels = np.asarray(result.levels, dtype=float)

    def as_dict(f):
        return {"median": None if f is None else float(f.median),
                "dispersion": None if f is None else float(f.dispersion)}

    upper = np.round(result.probability_upper * result.trials)
    nominal = np.round(result.nominal_probability_upper * len(result.records))
    return {"lognormal_undecided_as_collapse": as_dict(fit(levels, result.trials, upper)),
            "nominal_lognormal_undecided_as_collapse": as_dict(
                fit(levels, len(result.records), nominal))}


@dataclass(frozen=True, eq=False)
class StructureStripes:
    """The record-based fragility of the structure alone (multiple-stripe analysis), for a
    structure around which no irregular arches are drawn (a surveyed arch): the record-to-record
    part of :func:`archquake.studies.record_fragility.run_record_fragility`, the same counts,
    fit and bootstrap band as that study's nominal arch.

    Attributes
    ----------
    im : str
        The intensity measure.
    unit : str
        Its unit.
    levels : ndarray, shape (L,)
        The stripes [unit].
    records : tuple of str
        The records, in suite order.
    collapsed : bool ndarray, shape (R, L, 2)
        Collapse under every record, level and polarity (as recorded, reversed).
    integrated : int
        Analyses integrated (the others never reach the activation: at rest).
    lognormal : LognormalFragility or None
        The maximum-likelihood fit (:func:`archquake.studies.fits.fit_lognormal_or_none`).
    band : BootstrapBand or None
        Its bootstrap band over the records.
    model : str
        The name of the model that gave the outcomes.
    undecided : int
        Analyses the model left undecided (the rigid blocks'; none of them is a collapse in
        ``collapsed``, :mod:`archquake.studies.undecided`).
    """

    im: str
    unit: str
    levels: np.ndarray
    records: tuple
    collapsed: np.ndarray
    integrated: int
    lognormal: object
    band: object
    model: str = "four-link"
    undecided: int = 0

    @property
    def failed(self) -> np.ndarray:
        """Collapse in either polarity, shape (R, L)."""
        return self.collapsed.any(axis=-1)

    @property
    def probability(self) -> np.ndarray:
        """The fraction of the records that collapse the structure at each level [-]."""
        return self.failed.mean(axis=0)


def structure_stripes(model, suite, im: str, levels, *, bootstrap: int, seed: int):
    """The record-based fragility of the structure alone: every record of the suite scaled to
    each level and applied in both polarities
    (:func:`archquake.studies.record_fragility.record_outcomes`), a pair failing if it
    collapses in either; the lognormal fit by maximum likelihood and its bootstrap band over
    the records, on the random stream the record-based study gives its nominal arch (so the
    numbers are that study's for the same structure).

    Parameters
    ----------
    model : StructuralModel
        The structure's model (either; an undecided analysis of the rigid blocks counts as no
        collapse here, as in the record-based study's point estimate).
    suite : RecordSuite
    im : str
        The intensity measure of the stripes.
    levels : sequence of float
        The stripes [the IM's unit].
    bootstrap : int
        Bootstrap resamples.
    seed : int
        Root seed of the bootstrap.

    Returns
    -------
    StructureStripes
    """
    from ...ground_motion.suites import stripe_measure
    from ...studies.fits import bootstrap_lognormal, fit_lognormal_or_none
    from ...studies.record_fragility import BOOTSTRAP_KEY, DEFAULT_CONFIDENCE, record_outcomes
    from ...studies.undecided import undecided_count

    measure = stripe_measure(im)
    x = np.asarray(levels, dtype=float)
    factors = suite.scale_factors(measure.name, x)
    collapsed = np.zeros((len(suite), x.size, 2), dtype=bool)
    integrated = undecided = 0
    for r, motion in enumerate(suite.motions(cached=True)):
        out = record_outcomes(model, motion, np.concatenate([factors[r], -factors[r]]))
        collapsed[r] = (out["status"].reshape(2, -1) == 2).T
        integrated += int(out["integrated"].sum())
        undecided += undecided_count(out["status"])
    failed = collapsed.any(axis=-1)
    fit = fit_lognormal_or_none(x, failed.shape[0], failed.sum(axis=0))
    band = None
    if fit is not None:
        stream = np.random.default_rng(
            np.random.SeedSequence(seed, spawn_key=(BOOTSTRAP_KEY,)).spawn(2)[1])
        band = bootstrap_lognormal(x, failed, fit, resamples=bootstrap,
                                   confidence=DEFAULT_CONFIDENCE, rng=stream)
    return StructureStripes(measure.name, measure.unit, x, tuple(suite.names), collapsed,
                            integrated, fit, band, model.name, undecided)


def structure_stripes_summary(stripes: StructureStripes, nrml: str | None,
                              nrml_note: str) -> dict:
    """What ``results.json`` records of :func:`structure_stripes`, with the keys of
    :func:`record_summary` (the irregular arches' fits and dispersions None).

    Parameters
    ----------
    stripes : StructureStripes
    nrml : str or None
        File name of its NRML export.
    nrml_note : str
        Why there is none, or ``""``.

    Returns
    -------
    dict
    """
    failed = stripes.failed
    fit = stripes.lognormal
    first = {}
    for name, row in zip(stripes.records, failed, strict=True):
        first[name] = float(stripes.levels[np.argmax(row)]) if row.any() else None
    rtr = None if fit is None else float(fit.dispersion)
    return {
        "im": stripes.im, "unit": stripes.unit, "levels": stripes.levels.tolist(),
        "records": len(stripes.records), "sample_size": 0, "analysed": 0, "arches": None,
        "structure_only": True, "probability": None,
        "nominal_probability": stripes.probability.tolist(),
        "lognormal": {"median": None, "dispersion": None},
        "nominal_lognormal": {"median": None if fit is None else float(fit.median),
                              "dispersion": rtr},
        "record_to_record": rtr, "geometric": None, "total": None, "srss": None,
        "analyses": {"total": int(stripes.collapsed.size),
                     "integrated": stripes.integrated,
                     "at_rest_without_integration": int(stripes.collapsed.size)
                     - stripes.integrated},
        "first_collapse": first, "nrml": nrml, "nrml_note": nrml_note,
        "model": stripes.model,
        "undecided": {"analyses": stripes.undecided, "of": int(stripes.collapsed.size)},
    }


def export_structure_nrml(stripes: StructureStripes, directory) -> tuple[str | None, str]:
    """Write the fit of :func:`structure_stripes` as an OpenQuake NRML fragility model
    (:func:`archquake.results_io.write_fragility_nrml`, id ``masonry-arch-nominal``).

    Parameters
    ----------
    stripes : StructureStripes
    directory : str or Path

    Returns
    -------
    (str or None, str)
        The file's name, or None and why no file was written.
    """
    from ..._version import __version__
    from ...results_io import write_fragility_nrml

    if stripes.lognormal is None:
        return None, ("no fragility function to export: the stripes admit no lognormal fit (no "
                      "collapse, no survival, or a single step between two levels)")
    name = f"fragility_{file_stem(stripes.im)}.xml"
    x = stripes.levels
    write_fragility_nrml(
        Path(directory) / name,
        [("masonry-arch-nominal", stripes.lognormal.median, stripes.lognormal.dispersion)],
        im=stripes.im, min_iml=float(x[0]), max_iml=float(x[-1]),
        description=f"archquake {__version__}: collapse of a masonry arch, lognormal fit by "
                    f"maximum likelihood to multiple stripes of {stripes.im} ({x[0]:g} to "
                    f"{x[-1]:g} {stripes.unit}), {len(stripes.records)} records x 2 "
                    f"polarities; the structure alone")
    return name, ""


def export_nrml(result, directory, im: str) -> tuple[str | None, str]:
    """Write a record-based fragility's lognormal fits as an OpenQuake NRML fragility model
    (:meth:`~archquake.studies.record_fragility.RecordFragilityResult.export_nrml`) beside the
    report.

    Parameters
    ----------
    result : RecordFragilityResult
    directory : str or Path
    im : str

    Returns
    -------
    (str or None, str)
        The file's name, or None and why no file was written.
    """
    name = f"fragility_{file_stem(im)}.xml"
    try:
        result.export_nrml(Path(directory) / name, taxonomy="masonry-arch")
    except ValueError as exc:
        return None, str(exc)
    return name, ""


__all__ = ["CHECK_RECORDS", "StructureStripes", "export_nrml", "export_structure_nrml",
           "file_stem", "record_check", "record_study", "record_summary",
           "rigid_block_record_outcomes", "select_records", "structure_stripes",
           "structure_stripes_summary"]
