r"""The code's dynamic route: a structure under records compatible with its site, and the verdict.

Every record of a :class:`~archquake.site.compatible_records.CompatibleSelection`, scaled by its
factor, is applied to each dynamic model of the structure (:class:`archquake.models.ModelSpec`;
the rigid-block model, the trusted one, and the four-link model beside it), through the models'
protocol (``model.outcome(motion)``). A run ends in rest or recovery (the structure survives),
collapse, or, for the rigid-block model, undecided (its contact solver did not decide).

The verdict follows NTC 2018 §7.3.5 [1]_ (and EN 1998-1 §4.3.3.4.3 [2]_): with seven records or
more the effect on the structure is the mean of the records' effects, with three to six the most
unfavourable one. The effect of a record here is the peak rotation its outcome carries
(:data:`PEAK_RESPONSE`); a collapse is an unbounded effect, so

- a collapse under any record makes the mean (or the most unfavourable effect) unbounded: the
  check **fails**;
- otherwise an undecided run leaves the effect unknown: the verdict is **undecided**, never a
  pass;
- otherwise the structure survives every record: the check **passes** (no collapse), and the
  effect (mean or largest peak rotation [rad]) is reported for a displacement check beside it.

With ``polarities=(1, -1)`` each record is also applied reversed, and a record's effect is the
less favourable of its two polarities (a collapse in either is a collapse).

The verdict of the rigid-block model is the one stated (:attr:`DynamicCheck.verdict`); the
four-link model's stands beside it.

References
----------
.. [1] Ministero delle Infrastrutture e dei Trasporti (2018). NTC 2018, D.M. 17 gennaio 2018,
   §7.3.5 (with at least seven time histories, the mean of the effects; otherwise the most
   unfavourable) and §3.2.3.6 (the records).
.. [2] CEN (2004). EN 1998-1:2004, Eurocode 8, Part 1, §4.3.3.4.3 (Non-linear time-history
   analysis: at least seven records for the mean, otherwise the most unfavourable value).
"""

from __future__ import annotations

import math
import sys
from dataclasses import dataclass, fields

import numpy as np

from ..checks import json_float
from ..models import ModelSpec, model_spec
from ..status import Status
from .compatible_records import MIN_COUNT, CompatibleSelection, effect_rule

PASS, FAIL, UNDECIDED = "pass", "fail", "undecided"
VERDICTS = (PASS, FAIL, UNDECIDED)
"""The verdicts of a model: ``pass`` (no record collapses the structure), ``fail`` (one does:
the effect is unbounded), ``undecided`` (no collapse, but a run left undecided)."""

PEAK_RESPONSE = {
    "rigid-blocks": ("max_rotation", "largest rotation of a block [rad]"),
    "four-link": ("max_phi", "largest rotation of the four-link mechanism [rad]"),
}
"""The peak response an outcome of each model carries: the field and what it is."""

DEFAULT_MODELS = (ModelSpec("rigid-blocks"), ModelSpec("four-link"))
"""The models of the check unless told: the rigid-block model (its verdict is stated) and the
four-link model beside it."""
POLARITIES = (1, -1)
"""Polarities a record may be applied in: +1 as recorded, -1 reversed."""


@dataclass(frozen=True)
class RecordRun:
    """One scaled record through one model.

    Attributes
    ----------
    model : str
        The model's name.
    record : str
        The record's name.
    factor : float
        Its scale factor [-].
    polarity : int
        +1 as recorded, -1 reversed.
    status : Status
        The outcome: rest, recovery, collapse or undecided.
    peak_response : float
        The peak response of :data:`PEAK_RESPONSE` [rad] (until the collapse, or the end).
    collapse_time : float
        When the collapse became certain [s]; nan without one.
    """

    model: str
    record: str
    factor: float
    polarity: int
    status: Status
    peak_response: float
    collapse_time: float

    def to_dict(self) -> dict:
        """JSON-ready: every field by name, the status by its label, nan as None."""
        out = {f.name: getattr(self, f.name) for f in fields(self)}
        out["status"] = self.status.label
        out["peak_response"] = json_float(self.peak_response)
        out["collapse_time"] = json_float(self.collapse_time)
        return out


@dataclass(frozen=True)
class ModelVerdict:
    """The code's verdict for one model (module docstring).

    Attributes
    ----------
    model : str
        The model's name.
    verdict : str
        ``"pass"``, ``"fail"`` or ``"undecided"`` (:data:`VERDICTS`).
    effect_rule : str
        ``"mean"`` (seven records or more) or ``"most unfavourable"``.
    effect : float
        The effect by that rule [rad]: inf when a record collapses the structure, nan when a run
        is undecided.
    records : int
        Records [-].
    collapses : int
        Records that collapse the structure (in either polarity) [-].
    undecided : int
        Records with an undecided run and no collapse [-].
    reason : str
        The verdict in words.
    """

    model: str
    verdict: str
    effect_rule: str
    effect: float
    records: int
    collapses: int
    undecided: int
    reason: str

    def to_dict(self) -> dict:
        """JSON-ready: every field by name, inf and nan as None."""
        out = {f.name: getattr(self, f.name) for f in fields(self)}
        out["effect"] = json_float(self.effect)
        return out


def model_verdict(model: str, statuses, peaks) -> ModelVerdict:
    """The code's verdict from the outcomes of one model under the records (module docstring).

    Parameters
    ----------
    model : str
        The model's name (for the text).
    statuses : sequence of sequence of Status
        Per record, the statuses of its runs (one per polarity).
    peaks : sequence of sequence of float
        Per record, the peak responses of its runs [rad].

    Returns
    -------
    ModelVerdict

    Raises
    ------
    ValueError
        For fewer than three records (NTC 2018 §7.3.5), or statuses and peaks that do not
        match.
    """
    statuses = [list(s) for s in statuses]
    peaks = [list(p) for p in peaks]
    if len(statuses) != len(peaks) or any(len(s) != len(p) or not s
                                          for s, p in zip(statuses, peaks, strict=True)):
        raise ValueError("statuses and peaks must give the same runs (at least one) per record")
    count = len(statuses)
    if count < MIN_COUNT:
        raise ValueError(f"records must be at least {MIN_COUNT} for a time-history check "
                         f"(NTC 2018 §7.3.5), got {count}")
    for runs in statuses:
        for s in runs:
            if not isinstance(s, Status):
                raise ValueError(f"statuses must be Status members, got {s!r}")
    rule = effect_rule(count)
    collapses = sum(any(s is Status.COLLAPSE for s in runs) for runs in statuses)
    undecided = sum(any(s is Status.UNDECIDED for s in runs)
                    and not any(s is Status.COLLAPSE for s in runs) for runs in statuses)
    if collapses:
        return ModelVerdict(model, FAIL, rule, math.inf, count, collapses, undecided,
                            f"{collapses} of {count} records collapse the structure: the "
                            f"{rule} effect is unbounded")
    if undecided:
        return ModelVerdict(model, UNDECIDED, rule, math.nan, count, 0, undecided,
                            f"no record collapses the structure, but {undecided} of {count} "
                            f"runs are undecided: the {rule} effect is unknown")
    per_record = np.array([max(p) for p in peaks], dtype=float)
    effect = float(np.mean(per_record) if rule == "mean" else np.max(per_record))
    return ModelVerdict(model, PASS, rule, effect, count, 0, 0,
                        f"no record collapses the structure; the {rule} peak rotation is "
                        f"{effect:.4g} rad")


@dataclass(frozen=True, eq=False)
class DynamicCheck:
    """The structure under the selected records, by each model, and the verdicts.

    Attributes
    ----------
    selection : CompatibleSelection
        The records and their factors.
    models : tuple of ModelSpec
        The models, as resolved for the structure (the rigid blocks' time step).
    runs : tuple of RecordRun
        Every run, model by model, record by record, polarity by polarity.
    verdicts : tuple of ModelVerdict
        One per model, in the order of ``models``.
    """

    selection: CompatibleSelection
    models: tuple[ModelSpec, ...]
    runs: tuple[RecordRun, ...]
    verdicts: tuple[ModelVerdict, ...]

    @property
    def verdict(self) -> ModelVerdict:
        """The verdict stated: the rigid-block model's if it ran, else the first model's."""
        for v in self.verdicts:
            if v.model == "rigid-blocks":
                return v
        return self.verdicts[0]

    def to_dict(self) -> dict:
        """JSON-ready: the selection, the models, every run and the verdicts."""
        return {"selection": self.selection.to_dict(),
                "models": [m.to_dict() for m in self.models],
                "runs": [r.to_dict() for r in self.runs],
                "verdicts": [v.to_dict() for v in self.verdicts],
                "verdict": self.verdict.to_dict()}


def run_dynamic_check(structure, selection: CompatibleSelection, models=DEFAULT_MODELS, *,
                      polarities=(1,), allow_incompatible: bool = False,
                      progress: bool = True) -> DynamicCheck:
    """Every scaled record of ``selection`` through each model of ``structure``, and the code's
    verdict per model (module docstring).

    Parameters
    ----------
    structure : BlockArch
        The structure.
    selection : CompatibleSelection
        Records compatible with the site's spectrum
        (:func:`~archquake.site.compatible_records.select_compatible_records`).
    models : sequence of ModelSpec or str
        The models (default: the rigid blocks, then the four-link model, default settings).
    polarities : sequence of {1, -1}
        The records as recorded (1) and/or reversed (-1) (default as recorded).
    allow_incompatible : bool
        Run a selection that is not compatible with the target (the verdict is then no code
        verdict; default refused).
    progress : bool
        A progress bar on stderr.

    Returns
    -------
    DynamicCheck

    Raises
    ------
    ValueError
        For a selection that is not compatible (unless allowed; the message says why), an
        unknown model or polarity, a structure that cannot stand, or a record the rigid blocks'
        time step cannot resolve (as :meth:`archquake.models.ModelSpec.check_motion`).
    """
    from tqdm.auto import tqdm

    if not isinstance(selection, CompatibleSelection):
        raise ValueError(f"selection must be a CompatibleSelection, got "
                         f"{type(selection).__name__}")
    if not selection.compatible and not allow_incompatible:
        raise ValueError("selection is not compatible with the target spectrum: "
                         + "; ".join(selection.problems))
    polarities = tuple(polarities)
    if not polarities or any(p not in POLARITIES for p in polarities) or len(
            set(polarities)) != len(polarities):
        raise ValueError(f"polarities must be 1, -1 or both, got {polarities!r}")
    specs = tuple(model_spec(m).resolved(structure) if model_spec(m).name == "rigid-blocks"
                  else model_spec(m) for m in models)
    if not specs:
        raise ValueError("models must name at least one model")
    motions = selection.scaled_motions()
    built = []
    for spec in specs:
        model = spec.build(structure)
        if spec.model_class.checks_standing:
            model.check_stands()
        for motion in motions:
            spec.check_motion(structure, motion)
        built.append(model)

    runs, verdicts = [], []
    total = len(specs) * len(motions) * len(polarities)
    with tqdm(total=total, desc="dynamic check", unit="run", disable=not progress,
              file=sys.stderr) as bar:
        for spec, model in zip(specs, built, strict=True):
            field = PEAK_RESPONSE[spec.name][0]
            statuses, peaks = [], []
            for motion, factor in zip(motions, selection.factors, strict=True):
                statuses.append([])
                peaks.append([])
                for polarity in polarities:
                    bar.set_postfix_str(f"{spec.name} {motion.name}", refresh=False)
                    outcome = model.outcome(motion if polarity == 1 else motion.reversed())
                    run = RecordRun(spec.name, motion.name, float(factor), polarity,
                                    outcome.status, float(getattr(outcome, field)),
                                    float(outcome.collapse_time))
                    runs.append(run)
                    statuses[-1].append(run.status)
                    peaks[-1].append(run.peak_response)
                    bar.update()
            verdicts.append(model_verdict(spec.name, statuses, peaks))
    return DynamicCheck(selection, specs, tuple(runs), tuple(verdicts))


__all__ = ["DEFAULT_MODELS", "FAIL", "PASS", "PEAK_RESPONSE", "POLARITIES", "UNDECIDED",
           "VERDICTS", "DynamicCheck", "ModelVerdict", "RecordRun", "model_verdict",
           "run_dynamic_check"]
