r"""Fragility of a structure at a site: :math:`P(\mathrm{collapse} \mid IM = x)`, in one
intensity measure in g, read from where archquake or OpenQuake wrote it.

The functions
    :class:`LognormalCollapseFragility` (median :math:`\theta` [g], dispersion :math:`\beta`)
    and :class:`DiscreteCollapseFragility` (levels and probabilities, linear between them, 0
    below the first level, the last probability held above the last).
Readers
    :func:`read_fragility_nrml`: an OpenQuake NRML 0.5 fragility model [1]_
    (``format="discrete"``, ``imls`` and ``poes`` per limit state; or
    ``format="continuous" shape="logncdf"``, whose ``mean`` and ``stddev`` are those of the
    intensity in linear space, converted to
    :math:`\theta = m/\sqrt{1 + s^2/m^2}` and :math:`\beta = \sqrt{\ln(1 + s^2/m^2)}`, the
    inverse of :func:`archquake.results_io.lognormal_moments`).
    :func:`read_fragility_study`: a study folder of ``archquake record-fragility --out DIR``
    (the lognormal fit or the stripes' probabilities; analyses the model left undecided give an
    upper-bound function, :mod:`archquake.studies.undecided`), or the NRML files ``archquake
    assess`` writes beside its report. :func:`read_fragility` takes either.

References
----------
.. [1] GEM Foundation. The OpenQuake engine: NRML 0.5 fragility models (``fragilityModel``,
   ``limitStates``, ``fragilityFunction`` of ``format="discrete"`` and
   ``format="continuous" shape="logncdf"``); ``openquake.risklib.scientific
   .FragilityFunctionContinuous``.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from scipy import stats

from ..ranges import number
from .hazard import canonical_im

__all__ = ["COLLAPSE_LIMIT_STATES", "DiscreteCollapseFragility", "FRAGILITY_FITS",
           "LognormalCollapseFragility", "StudyFragility", "lognormal_from_moments",
           "read_fragility", "read_fragility_nrml", "read_fragility_study"]

COLLAPSE_LIMIT_STATES = ("collapse", "complete")
"""Names of a limit state taken for collapse when none is chosen (else the last state)."""

FRAGILITY_FITS = ("lognormal", "empirical")
"""How a study's stripes become a function: its lognormal fit, or the stripes' probabilities
interpolated linearly (:class:`DiscreteCollapseFragility`)."""


@dataclass(frozen=True)
class LognormalCollapseFragility:
    r"""Lognormal fragility :math:`P(x) = \Phi(\ln(x/\theta)/\beta)` (0 at or below
    ``no_damage_limit``).

    Attributes
    ----------
    median : float
        :math:`\theta` > 0 [g].
    dispersion : float
        :math:`\beta` > 0 [-].
    im : str
        The intensity measure (``PGA``, ``SA(T)``).
    no_damage_limit : float
        Intensity [g] at or below which the probability is 0 (OpenQuake's ``noDamageLimit``;
        0: none).
    source : str
        Where it comes from (said in the output).
    """

    median: float
    dispersion: float
    im: str = "PGA"
    no_damage_limit: float = 0.0
    source: str = ""

    def __post_init__(self) -> None:
        for name in ("median", "dispersion"):
            value = getattr(self, name)
            if not (isinstance(value, int | float) and math.isfinite(value) and value > 0):
                raise ValueError(f"{name} of a lognormal fragility must be a finite number "
                                 f"> 0, got {value!r}")
        if not (math.isfinite(self.no_damage_limit) and self.no_damage_limit >= 0):
            raise ValueError(f"no_damage_limit must be >= 0 [g], got {self.no_damage_limit!r}")
        object.__setattr__(self, "im", canonical_im(self.im))

    def __call__(self, intensity) -> np.ndarray:
        """P(collapse | IM = x) [-] at intensities ``intensity`` [g]."""
        x = np.asarray(intensity, dtype=float)
        with np.errstate(divide="ignore"):
            z = np.log(np.where(x > 0, x, np.nan) / self.median) / self.dispersion
        p = np.where(x > 0, stats.norm.cdf(z), 0.0)
        return np.where(x <= self.no_damage_limit, 0.0, p)

    @property
    def lowest(self) -> float:
        """Intensity [g] below which P < 1e-15 (where the integral of the risk may start)."""
        return max(self.median * math.exp(-8.0 * self.dispersion), self.no_damage_limit)

    def describe(self) -> str:
        text = f"lognormal, median {self.median:.4g} g, dispersion {self.dispersion:.3g}"
        if self.no_damage_limit:
            text += f", 0 at or below {self.no_damage_limit:g} g"
        return text

    def to_dict(self) -> dict:
        """JSON-ready: ``kind`` ``"lognormal"``, ``median`` [g], ``dispersion``, ``im``,
        ``no_damage_limit`` [g], ``source``."""
        return {"kind": "lognormal", "median": self.median, "dispersion": self.dispersion,
                "im": self.im, "no_damage_limit": self.no_damage_limit, "source": self.source}


@dataclass(frozen=True, eq=False)
class DiscreteCollapseFragility:
    """Fragility given at levels: linear between them, 0 below the first, the last probability
    held above the last.

    Attributes
    ----------
    levels : ndarray, shape (n,)
        Intensities [g], strictly increasing, > 0.
    probabilities : ndarray, shape (n,)
        P(collapse | IM = level) in [0, 1] [-] (not necessarily monotone: a stripe's estimate).
    im : str
        The intensity measure.
    source : str
        Where it comes from.
    """

    levels: np.ndarray
    probabilities: np.ndarray
    im: str = "PGA"
    source: str = ""

    def __post_init__(self) -> None:
        levels = np.array(self.levels, dtype=float).ravel()
        p = np.array(self.probabilities, dtype=float).ravel()
        if levels.size != p.size or levels.size < 1:
            raise ValueError(f"a discrete fragility needs as many probabilities as levels "
                             f"(>= 1), got {levels.size} and {p.size}")
        if not np.all(np.isfinite(levels) & (levels > 0)):
            raise ValueError(f"fragility levels must be > 0 [g], got {levels.tolist()}")
        if np.any(np.diff(levels) <= 0):
            raise ValueError(f"fragility levels must increase strictly, got {levels.tolist()}")
        if not np.all((p >= 0) & (p <= 1)):
            raise ValueError(f"fragility probabilities must lie in [0, 1], got {p.tolist()}")
        levels.flags.writeable = False
        p.flags.writeable = False
        object.__setattr__(self, "levels", levels)
        object.__setattr__(self, "probabilities", p)
        object.__setattr__(self, "im", canonical_im(self.im))

    def __call__(self, intensity) -> np.ndarray:
        """P(collapse | IM = x) [-] at intensities ``intensity`` [g]."""
        x = np.asarray(intensity, dtype=float)
        p = np.interp(x, self.levels, self.probabilities)
        return np.where(x < self.levels[0], 0.0, p)

    @property
    def lowest(self) -> float:
        """The first level [g]: the probability is 0 below it."""
        return float(self.levels[0])

    def describe(self) -> str:
        return (f"discrete, {self.levels.size} levels {self.levels[0]:g} to "
                f"{self.levels[-1]:g} g, P from {self.probabilities[0]:.3g} to "
                f"{self.probabilities[-1]:.3g} (linear between levels, 0 below, the last held "
                f"above)")

    def to_dict(self) -> dict:
        """JSON-ready: ``kind`` ``"discrete"``, ``levels`` [g], ``probabilities``, ``im``,
        ``source``."""
        return {"kind": "discrete", "levels": self.levels.tolist(),
                "probabilities": self.probabilities.tolist(), "im": self.im,
                "source": self.source}


@dataclass(frozen=True)
class StudyFragility:
    """A fragility read from a study: the function, and the upper-bound function where the
    model left analyses undecided.

    Attributes
    ----------
    fragility : LognormalCollapseFragility or DiscreteCollapseFragility
        Undecided analyses counted as survivals (the studies' point estimate, a lower bound).
    upper : LognormalCollapseFragility or DiscreteCollapseFragility or None
        Undecided analyses counted as collapses; None when no analysis was undecided.
    undecided : int
        Undecided arch-record pairs over the stripes (0: the two bounds are the same).
    """

    fragility: object
    upper: object | None = None
    undecided: int = 0


def lognormal_from_moments(mean: float, stddev: float) -> tuple[float, float]:
    r"""Median and dispersion of a lognormal variable from its mean and standard deviation in
    linear space (OpenQuake's ``mean`` and ``stddev`` of a ``logncdf`` fragility function):

    .. math::

        \beta = \sqrt{\ln\left(1 + s^2/m^2\right)}, \qquad
        \theta = \frac{m}{\sqrt{1 + s^2/m^2}},

    the inverse of :func:`archquake.results_io.lognormal_moments`.

    Parameters
    ----------
    mean, stddev : float
        m > 0 and s > 0 [the unit of the intensity].

    Returns
    -------
    median, dispersion : float

    Raises
    ------
    ValueError
        If m or s is not a finite number > 0.

    Examples
    --------
    >>> median, beta = lognormal_from_moments(0.6, 0.48)
    >>> round(median, 6), round(beta, 6)
    (0.468521, 0.703346)
    """
    m, s = float(mean), float(stddev)
    if not (math.isfinite(m) and m > 0 and math.isfinite(s) and s > 0):
        raise ValueError(f"a lognormal needs mean > 0 and stddev > 0, got {mean!r}, "
                         f"{stddev!r}")
    ratio = 1.0 + (s / m) ** 2
    return m / math.sqrt(ratio), math.sqrt(math.log(ratio))


# ---------------------------------------------------------------------------------------------
# NRML
# ---------------------------------------------------------------------------------------------


def _local(tag: str) -> str:
    return tag.rsplit("}", 1)[-1]


def _children(element, name):
    return [child for child in element if _local(child.tag) == name]


def _floats(text: str | None, what: str) -> np.ndarray:
    try:
        return np.array([number(cell) for cell in (text or "").split()])
    except ValueError:
        raise ValueError(f"{what}: {text!r} is not a list of numbers") from None


def read_fragility_nrml(path: str | os.PathLike, *, limit_state: str | None = None,
                        function_id: str | None = None, im: str | None = None):
    r"""Read one fragility function of an OpenQuake NRML fragility model (0.5; the module's
    references).

    Parameters
    ----------
    path : str or os.PathLike
        The XML file (``<nrml><fragilityModel>``).
    limit_state : str, optional
        The limit state taken for collapse. Default: the one named ``collapse`` or
        ``complete`` (case ignored), else the last of ``limitStates``.
    function_id : str, optional
        The ``fragilityFunction``'s ``id`` (OpenQuake's taxonomy). Default: the first in the
        file (of ``im`` if given): for archquake's files, the irregular arches' total fit.
    im : str, optional
        Only functions of this intensity measure.

    Returns
    -------
    LognormalCollapseFragility or DiscreteCollapseFragility
        A ``continuous`` ``logncdf`` function becomes the lognormal of median
        :math:`m/\sqrt{1+s^2/m^2}` and dispersion :math:`\sqrt{\ln(1+s^2/m^2)}`
        (:func:`lognormal_from_moments`) and keeps ``noDamageLimit``; its ``minIML`` and
        ``maxIML`` (where OpenQuake clips the intensity) are not applied: the lognormal holds
        at every intensity. A ``discrete`` one is :class:`DiscreteCollapseFragility` of its
        ``imls`` and the limit state's ``poes``.

    Raises
    ------
    ValueError
        If the file is not an NRML fragility model, names no such limit state (naming the
        states it has), function or intensity measure, or has an intensity measure not in g.
    """
    import xml.etree.ElementTree as ET

    name = Path(path).name
    try:
        root = ET.parse(path).getroot()
    except FileNotFoundError:
        raise ValueError(f"fragility file {str(path)!r} does not exist") from None
    except ET.ParseError as exc:
        raise ValueError(f"{name} is not XML: {exc}") from None
    except OSError as exc:
        raise ValueError(f"cannot read {str(path)!r}: {exc.strerror}") from None
    models = [root] if _local(root.tag) == "fragilityModel" else _children(root,
                                                                           "fragilityModel")
    if not models:
        raise ValueError(f"{name} is not an NRML fragility model (no fragilityModel element)")
    model = models[0]
    states_element = _children(model, "limitStates")
    states = (states_element[0].text or "").split() if states_element else []
    if not states:
        raise ValueError(f"{name}: the fragility model names no limitStates")
    if limit_state is None:
        named = [s for s in states if s.lower() in COLLAPSE_LIMIT_STATES]
        chosen = named[0] if named else states[-1]
    elif limit_state in states:
        chosen = limit_state
    else:
        raise ValueError(f"{name} has no limit state {limit_state!r}: its states are "
                         f"{', '.join(states)}")
    functions = _children(model, "fragilityFunction")
    if not functions:
        raise ValueError(f"{name}: the fragility model has no fragilityFunction")
    wanted_im = None if im is None else canonical_im(im)
    candidates = []
    for function in functions:
        imls = _children(function, "imls")
        if not imls or "imt" not in imls[0].attrib:
            raise ValueError(f"{name}: fragilityFunction {function.get('id')!r} has no "
                             f"<imls imt=...>")
        candidates.append((function, imls[0], imls[0].get("imt")))
    if function_id is not None:
        candidates = [c for c in candidates if c[0].get("id") == function_id]
        if not candidates:
            raise ValueError(f"{name} has no fragilityFunction of id {function_id!r}: its "
                             f"ids are {', '.join(str(f.get('id')) for f in functions)}")
    if wanted_im is not None:
        matching = []
        for c in candidates:
            try:
                if canonical_im(c[2]) == wanted_im:
                    matching.append(c)
            except ValueError:
                pass
        if not matching:
            raise ValueError(f"{name} has no fragility function of {wanted_im}: its "
                             f"intensity measures are "
                             f"{', '.join(sorted({c[2] for c in candidates}))}")
        candidates = matching
    function, imls, imt = candidates[0]
    ident = function.get("id")
    fmt = function.get("format")
    no_damage = imls.get("noDamageLimit") or function.get("noDamageLimit")
    no_damage = 0.0 if no_damage is None else number(no_damage)
    source = f"NRML {name}, function {ident!r}, limit state {chosen!r}"
    if fmt == "continuous":
        if function.get("shape", "logncdf") != "logncdf":
            raise ValueError(f"{name}: continuous function {ident!r} of shape "
                             f"{function.get('shape')!r}: only logncdf is read")
        params = [p for p in _children(function, "params") if p.get("ls") == chosen]
        if not params:
            raise ValueError(f"{name}: function {ident!r} has no params for limit state "
                             f"{chosen!r}")
        try:
            mean, stddev = number(params[0].get("mean")), number(params[0].get("stddev"))
        except (TypeError, ValueError):
            raise ValueError(f"{name}: function {ident!r}, limit state {chosen!r}: mean and "
                             f"stddev must be numbers") from None
        median, dispersion = lognormal_from_moments(mean, stddev)
        return LognormalCollapseFragility(
            median, dispersion, im=imt, no_damage_limit=no_damage,
            source=f"{source} (logncdf of mean {mean:g} and stddev {stddev:g} of the "
                   f"intensity)")
    if fmt == "discrete":
        levels = _floats(imls.text, f"{name}: function {ident!r} imls")
        poes = [p for p in _children(function, "poes") if p.get("ls") == chosen]
        if not poes:
            raise ValueError(f"{name}: function {ident!r} has no poes for limit state "
                             f"{chosen!r}")
        probabilities = _floats(poes[0].text, f"{name}: function {ident!r} poes")
        return DiscreteCollapseFragility(levels, probabilities, im=imt, source=source)
    raise ValueError(f"{name}: function {ident!r} has format {fmt!r}: expected continuous or "
                     f"discrete")


# ---------------------------------------------------------------------------------------------
# Study folders
# ---------------------------------------------------------------------------------------------


def _record_fragility_study(directory: Path, summary: dict, *, fit: str,
                            im: str | None) -> StudyFragility:
    from ..studies.fits import fit_lognormal_or_none

    try:
        study_im = canonical_im(summary["im"])
        levels = np.asarray(summary["levels"], dtype=float)
        trials = int(summary["trials"])
        failures = np.asarray(summary["failures"], dtype=float)
        upper_p = np.asarray(summary.get("probability_upper", failures / trials), dtype=float)
    except (KeyError, TypeError) as exc:
        raise ValueError(f"{directory}: the record fragility summary lacks {exc}") from None
    if im is not None and canonical_im(im) != study_im:
        raise ValueError(f"{directory} is a fragility in {study_im}, but {canonical_im(im)} "
                         f"was asked for")
    upper_failures = np.rint(upper_p * trials)
    undecided = int((upper_failures - failures).sum())
    where = f"record fragility study {directory.name}"
    if fit == "empirical":
        lower = DiscreteCollapseFragility(levels, failures / trials, im=study_im,
                                          source=f"{where}: stripes' probabilities")
        upper = None
        if undecided:
            upper = DiscreteCollapseFragility(levels, upper_failures / trials, im=study_im,
                                              source=f"{where}: stripes' upper probabilities "
                                                     f"(undecided counted as collapses)")
        return StudyFragility(lower, upper, undecided)
    if fit != "lognormal":
        raise ValueError(f"fit must be one of {', '.join(FRAGILITY_FITS)}, got {fit!r}")
    total = summary.get("lognormal") or {}
    if total.get("median") is None:
        raise ValueError(f"{directory}: the stripes admit no lognormal fit (no collapse, no "
                         f"survival, or a single step between two levels): use --fit "
                         f"empirical")
    lower = LognormalCollapseFragility(
        float(total["median"]), float(total["dispersion"]), im=study_im,
        source=f"{where}: lognormal fit (maximum likelihood) of the irregular arches")
    upper = None
    if undecided:
        refit = fit_lognormal_or_none(levels, trials, upper_failures)
        if refit is None:
            upper = DiscreteCollapseFragility(
                levels, upper_failures / trials, im=study_im,
                source=f"{where}: stripes' upper probabilities (no lognormal fit)")
        else:
            upper = LognormalCollapseFragility(
                float(refit.median), float(refit.dispersion), im=study_im,
                source=f"{where}: lognormal fit of the upper counts (undecided counted as "
                       f"collapses)")
    return StudyFragility(lower, upper, undecided)


def read_fragility_study(directory: str | os.PathLike, *, fit: str = "lognormal",
                         im: str | None = None, limit_state: str | None = None,
                         function_id: str | None = None) -> StudyFragility:
    """Read the fragility of a study folder.

    Parameters
    ----------
    directory : str or os.PathLike
        ``archquake record-fragility --out DIR`` (its ``summary.json``: the lognormal fit of
        the irregular arches, the stripes' counts and their upper bounds with undecided
        analyses), or an ``archquake assess --out DIR`` folder (its NRML files
        ``fragility_<im>.xml``, :func:`read_fragility_nrml`: the model the report trusts; the
        four-link model's ``fragility_<im>_four_link.xml`` beside them are not read).
    fit : {"lognormal", "empirical"}
        For a record fragility study: its lognormal fit, or the stripes' probabilities
        (:class:`DiscreteCollapseFragility`). With undecided analyses the upper bound is the
        lognormal refitted to the counts with undecided pairs as collapses (or their
        probabilities).
    im : str, optional
        The intensity measure wanted (must be the study's; chooses the NRML file of an
        assessment).
    limit_state, function_id : str, optional
        For NRML files (:func:`read_fragility_nrml`).

    Returns
    -------
    StudyFragility

    Raises
    ------
    ValueError
        For a folder that holds neither, a pulse fragility study (its intensity is a pulse's
        amplitude at each duration, not a site's), or what the readers refuse.
    """
    from ..results_io import read_json

    directory = Path(directory)
    if not directory.is_dir():
        raise ValueError(f"fragility study {str(directory)!r} is not a folder")
    summary_path = directory / "summary.json"
    if summary_path.is_file():
        record = read_json(summary_path)
        summary = record.get("summary", {}) if isinstance(record, dict) else {}
        if isinstance(summary, dict) and "probability_upper" in summary and "im" in summary:
            return _record_fragility_study(directory, summary, fit=fit, im=im)
        if isinstance(summary, dict) and "durations" in summary:
            raise ValueError(f"{directory} is a pulse fragility study: its intensity is the "
                             f"amplitude of a pulse of each duration, which a site's hazard "
                             f"curve does not describe; run archquake record-fragility")
    files = sorted(directory.glob("fragility_*.xml"))
    # an assessment that trusts the rigid blocks keeps the four-link model's files aside
    aside = [f.name for f in files if f.stem.endswith("_four_link")]
    files = [f for f in files if not f.stem.endswith("_four_link")]
    if aside and not files:
        raise ValueError(f"{directory}: the assessment trusts the rigid-block model, whose "
                         f"record study admits no lognormal fit, so it wrote no NRML file; "
                         f"{', '.join(aside)} is the four-link model's, which the assessment "
                         f"does not trust there (give that file itself to use it anyway)")
    if files:
        if fit != "lognormal":
            raise ValueError(f"{directory}: the NRML files of an assessment hold lognormal "
                             f"fits only (fit must be lognormal)")
        errors = []
        for path in files:
            try:
                return StudyFragility(read_fragility_nrml(path, limit_state=limit_state,
                                                          function_id=function_id, im=im))
            except ValueError as exc:
                errors.append(str(exc))
        raise ValueError(f"{directory}: no NRML file fits: " + "; ".join(errors))
    raise ValueError(f"{directory} holds no record fragility study (summary.json) and no "
                     f"NRML fragility file (fragility_*.xml)")


def read_fragility(path: str | os.PathLike, *, fit: str = "lognormal", im: str | None = None,
                   limit_state: str | None = None,
                   function_id: str | None = None) -> StudyFragility:
    """Read a fragility from a study folder (:func:`read_fragility_study`) or an NRML file
    (:func:`read_fragility_nrml`).

    Parameters
    ----------
    path : str or os.PathLike
    fit, im, limit_state, function_id
        As :func:`read_fragility_study`.

    Returns
    -------
    StudyFragility

    Raises
    ------
    ValueError
        For a path that does not exist or what the readers refuse.
    """
    path = Path(path)
    if path.is_dir():
        return read_fragility_study(path, fit=fit, im=im, limit_state=limit_state,
                                    function_id=function_id)
    if not path.exists():
        raise ValueError(f"fragility {str(path)!r} does not exist")
    if fit not in FRAGILITY_FITS:
        raise ValueError(f"fit must be one of {', '.join(FRAGILITY_FITS)}, got {fit!r}")
    return StudyFragility(read_fragility_nrml(path, limit_state=limit_state,
                                              function_id=function_id, im=im))
