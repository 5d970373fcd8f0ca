r"""The four-link model beside the rigid-block model: how far to trust the four-link model.

The same arch under the same pulses, in the package's two models:

- the four-link model [paper, Sects. 4-5] (:class:`archquake.fourlink.FourLinkModel`): one
  degree of freedom, the hinges of the limit analysis, impacts by a coefficient of restitution
  chosen by a rule (:data:`archquake.fourlink.impact.RESTITUTION_MODELS`);
- the rigid-block model (:mod:`archquake.rigid_blocks`): every voussoir a block, unilateral
  contacts with Coulomb friction at both ends of every joint, Newton impacts with restitution 0;
  any mechanism may form and change, blocks may slide.

:func:`compare_models` computes, per pulse duration t_p, the failure acceleration (the lowest
collapsing amplitude, and the recovery bands above it) of the rigid-block model and of the
four-link model with each restitution model, both by the one failure-domain search over the model
protocol (:func:`archquake.studies.failure_domain.domain_of`), on the same amplitude scan bisected
to the same resolution, and with no extension of the scan (a failure acceleration above the scan
is reported as none, for either model).

For Oppenheim's arch under Oppenheim's pulse (``archquake compare``; the numbers are in the
README and the report) the two models agree for long pulses, where the arch falls in its first
swing, and differ for short ones, where it collapses only after impacts and the energy an impact
leaves decides: there the four-link answer depends strongly on its coefficient of restitution,
and the rigid blocks do not move on in a four-link mechanism after an impact
(:mod:`archquake.fourlink.impact`, model ``"measured"``).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field, replace

import numpy as np

from ..checks import json_float
from ..defaults import (
    AGREEMENT_BAND,
    COMPARE_AMPLITUDES_G,
    COMPARE_DURATIONS,
    COMPARE_RESOLUTION_G,
    COMPARE_RESTITUTIONS,
    DEFAULT_STRIDE,
)
from ..geometry import BlockArch


@dataclass(frozen=True, eq=False)
class ModelComparison:
    """Failure accelerations of the rigid-block and four-link models, duration by duration.

    Attributes
    ----------
    arch : BlockArch
        The arch.
    rigid_block : FailureDomain
        The rigid-block model's outcome intervals per duration.
    four_link : dict
        ``{restitution model: FailureDomain}`` of the four-link model, in the order given.
    amplitudes_g : ndarray
        The amplitude scan of both models [g].
    resolution_g : float
        Bisection width of every boundary of both models [g].
    settings : BlockSettings
        Friction, time step and outcome criteria of the rigid-block model.
    skipped : dict
        ``{restitution model: why}`` of the restitution models left out because they give no
        positive coefficient for this structure (the paper's link rule on piers).
    """

    arch: BlockArch
    rigid_block: object
    four_link: dict
    amplitudes_g: np.ndarray
    resolution_g: float
    settings: object = None
    skipped: dict = field(default_factory=dict)

    @property
    def durations(self) -> np.ndarray:
        """Pulse durations t_p [s]."""
        return self.rigid_block.durations

    @property
    def restitution(self) -> dict[str, tuple[float, float]]:
        """``{model: (c_lr, c_rl)}``: the coefficients of restitution of the four-link runs [-]."""
        return {name: tuple(domain.restitution) for name, domain in self.four_link.items()}

    @property
    def load_multiplier(self) -> float:
        """k of the mechanism the pulse opens [-]: no model moves below ``a = k``."""
        return next(iter(self.four_link.values())).limit_multiplier

    def failure_accelerations_g(self) -> dict[str, np.ndarray]:
        """``{"rigid_block": ..., <restitution model>: ...}``: the lowest collapsing amplitude
        per duration [g] (nan: none in the scan); for the rigid blocks the lowest decided one,
        which is only an upper bound where an undecided band lies below it
        (:meth:`rigid_block_undecided_from_g`)."""
        out = {"rigid_block": self.rigid_block.failure_accelerations_g}
        for name, domain in self.four_link.items():
            out[name] = domain.failure_accelerations_g
        return out

    def rigid_block_undecided_from_g(self) -> np.ndarray:
        """Per duration, the lowest amplitude [g] of an undecided band of the rigid-block model
        below its lowest decided collapse (anywhere in the scan without one): its failure
        acceleration lies between this and :meth:`failure_accelerations_g` (nan: decided;
        :attr:`archquake.studies.failure_domain.DomainSlice.failure_undecided_from_g`)."""
        return np.array([s.failure_undecided_from_g for s in self.rigid_block.slices])

    @property
    def undecided_analyses(self) -> int:
        """Rigid-block analyses left undecided [-] (the four-link model decides every one)."""
        return self.rigid_block.undecided_analyses

    def relative_differences(self) -> dict[str, np.ndarray]:
        """``{restitution model: (a_four_link - a_rigid_block) / a_rigid_block}`` per duration
        [-] (nan where either has no failure in the scan, or the rigid-block failure
        acceleration is not decided: an undecided band lies below it)."""
        rigid = np.where(np.isnan(self.rigid_block_undecided_from_g()),
                         self.rigid_block.failure_accelerations_g, np.nan)
        return {name: domain.failure_accelerations_g / rigid - 1.0
                for name, domain in self.four_link.items()}

    def to_list(self) -> list[dict]:
        """JSON-ready list, one entry per duration: ``duration`` [s], ``rigid_block`` and
        ``four_link`` (``{model: ...}``) failure accelerations [g] (None: none in the scan, see
        ``scanned_to``), the recovery bands above them ``recovery_above`` (``{"rigid_block":
        [[from, to], ...], "four_link": {model: [...]}}`` [g]) and ``scanned_to`` [g]; and only
        where a model collapses at the lowest amplitude scanned, ``failure_acceleration_bound``
        (``{"rigid_block": "upper", <model>: "upper"}`` for those models: the failure
        acceleration is at most the value given). The rigid-block model's undecided analyses:
        ``undecided`` (``{"rigid_block": [[from, to], ...]}``, its undecided bands [g]),
        ``undecided_analyses`` (``{"rigid_block": count}``) and, only where a band lies below
        its lowest decided collapse, ``failure_undecided_from`` (``{"rigid_block": a}``: its
        failure acceleration lies between ``a`` and ``rigid_block``)."""
        out = []
        counts = self.rigid_block.undecided or (0,) * len(self.rigid_block.slices)
        for i, rb in enumerate(self.rigid_block.slices):
            fl = {name: domain.slices[i] for name, domain in self.four_link.items()}
            upper = {name: "upper" for name, s in (("rigid_block", rb), *fl.items())
                     if s.failure_acceleration_bound == "upper"}
            out.append({
                "duration": rb.duration,
                "rigid_block": json_float(rb.failure_acceleration_g),
                "four_link": {name: json_float(s.failure_acceleration_g) for name, s in fl.items()},
                "recovery_above": {
                    "rigid_block": [list(b) for b in rb.recovery_above_g],
                    "four_link": {name: [list(b) for b in s.recovery_above_g]
                                  for name, s in fl.items()}},
                "scanned_to": rb.scanned_to_g,
                **({"failure_acceleration_bound": upper} if upper else {}),
                "undecided": {"rigid_block": [list(b) for b in rb.undecided_bands_g]},
                "undecided_analyses": {"rigid_block": int(counts[i])},
                **({"failure_undecided_from": {"rigid_block": rb.failure_undecided_from_g}}
                   if math.isfinite(rb.failure_undecided_from_g) else {}),
            })
        return out


def _scan(amplitudes_g) -> np.ndarray:
    from .failure_domain import check_amplitudes, inclusive_range

    if amplitudes_g is None:
        return inclusive_range(*COMPARE_AMPLITUDES_G)
    return check_amplitudes(amplitudes_g)


def _four_link(dynamics, model: str, settings):
    """``dynamics`` with restitution ``model``; ``"measured"`` measured with the rigid-block
    model's ``settings`` (its friction and time step) when they are not the defaults."""
    from ..rigid_blocks.dynamics import resolved_settings

    if (model == "measured" and settings is not None
            and settings != resolved_settings(None, dynamics.arch)):
        from ..fourlink.impact import measured_restitution

        mech_l, mech_r = dynamics.mechanisms
        pair = (measured_restitution(mech_l, mech_r, settings),
                measured_restitution(mech_r, mech_l, settings))
        return replace(dynamics, restitution=pair, restitution_model=model)
    return dynamics.with_restitution(model)


def _check_curve(curve, durations, direction, motion, settings, resolution_g, grid) -> None:
    from ..rigid_blocks import BlockSettings
    from .failure_domain import FailureDomain

    described = getattr(curve, "model", None) or {}
    if not isinstance(curve, FailureDomain) or described.get("model") != "rigid-blocks":
        raise ValueError(f"rigid_block must be the FailureDomain of a RigidBlockModel, got "
                         f"{type(curve).__name__}")
    expected = BlockSettings() if settings is None else settings
    same = (curve.durations.shape == durations.shape
            and np.allclose(curve.durations, durations, rtol=0, atol=1e-12)
            and curve.direction == direction and curve.motion == motion
            and {k: v for k, v in described.items() if k != "model"}
            == {k: getattr(expected, k) for k in described if k != "model"}
            and all(s.resolution_g == resolution_g and s.intervals[0].start == grid[0]
                    and s.scanned_to_g == grid[-1] for s in curve.slices))
    if not same:
        raise ValueError("rigid_block must be the failure curve of the same durations, "
                         "direction, motion, settings, amplitude scan and resolution")


def compare_models(arch: BlockArch, durations: Sequence[float] | None = None, *,
                   restitutions: Sequence[str] = COMPARE_RESTITUTIONS, amplitudes_g=None,
                   resolution_g: float = COMPARE_RESOLUTION_G, direction: str = "l",
                   motion: str = "oppenheim", settings=None, workers: int | None = None,
                   progress: bool = False, dynamics=None, rigid_block=None,
                   search: str | None = None, stride: int | None = None) -> ModelComparison:
    """Failure accelerations of the rigid-block and four-link models of ``arch`` under pulses.

    Parameters
    ----------
    arch : BlockArch
        The arch.
    durations : sequence of float, optional
        Pulse durations t_p [s] (default :data:`archquake.defaults.COMPARE_DURATIONS`).
    restitutions : sequence of str
        Restitution models of the four-link runs (default computed, link, paper, measured).
    amplitudes_g : sequence of float, optional
        Increasing amplitude scan of both models [g] (default
        :data:`archquake.defaults.COMPARE_AMPLITUDES_G`, 0.3-3.0 g in 0.1 g steps).
    resolution_g : float
        Bisection width of every boundary of both models [g].
    direction : {"l", "r"}
        ``"l"``: the first pulse is ``-a g`` (opens Mech-l); ``"r"``: ``+a g``.
    motion : str
        Pulse shape (a name of :data:`archquake.ground_motion.ANALYTIC_GROUND_MOTIONS`; default
        Oppenheim's pulse).
    settings : archquake.rigid_blocks.BlockSettings, optional
        Friction, time step and outcome criteria of the rigid-block model (also those of the
        ``"measured"`` restitution).
    workers : int, optional
        Local worker processes of the rigid-block curve, one duration per task.
    progress : bool
        Progress bar over the rigid-block durations (the long part).
    dynamics : FourLinkModel, optional
        The arch's four-link model, if already built.
    rigid_block : FailureDomain, optional
        The rigid-block model's failure domain, if already computed (e.g. on another process)
        with the same durations, direction, motion, settings, scan and resolution (checked).
    search : {"exhaustive", "bisection", "screened"}, optional
        Search strategy of the rigid-block scan (:mod:`archquake.studies.strategies`; default
        :data:`archquake.defaults.DEFAULT_SEARCH` of the rigid blocks). The four-link runs
        analyse every grid point.
    stride : int
        Grid steps between the coarse points of the faster searches [-].

    Returns
    -------
    ModelComparison
    """
    from ..fourlink.impact import check_restitution_model
    from ..fourlink.model import FourLinkModel
    from ..rigid_blocks import BlockSettings, RigidBlockModel
    from .failure_domain import check_direction, check_durations, domain_of

    if not isinstance(arch, BlockArch):
        raise ValueError(f"arch must be a BlockArch, got {type(arch).__name__}")
    d = check_durations(COMPARE_DURATIONS if durations is None else durations)
    grid = _scan(amplitudes_g)
    check_direction(direction)
    if not (isinstance(resolution_g, (int, float)) and math.isfinite(resolution_g)
            and resolution_g > 0):
        raise ValueError(f"resolution_g must be a finite number > 0 [g], got {resolution_g!r}")
    names = tuple(restitutions)
    if not names:
        raise ValueError("restitutions must name at least one restitution model")
    for name in names:
        if not isinstance(name, str):
            raise ValueError(f"restitutions must be names of restitution models, got {name!r}")
        check_restitution_model(name)
    if dynamics is None:
        dynamics = FourLinkModel.from_arch(arch)
    elif not isinstance(dynamics, FourLinkModel) or dynamics.arch is not arch:
        raise ValueError("dynamics must be the FourLinkModel of arch")
    blocks = RigidBlockModel(arch, BlockSettings() if settings is None else settings)
    settings = blocks.settings  # with the time step used
    if rigid_block is None:
        rigid_block = domain_of(blocks, d, grid, direction=direction, motion=motion,
                                resolution_g=float(resolution_g), extend_to_g=None, search=search,
                                stride=DEFAULT_STRIDE if stride is None else stride,
                                workers=workers, progress=progress)
    else:
        _check_curve(rigid_block, d, direction, motion, settings, float(resolution_g), grid)
    four_link, skipped = {}, {}
    for name in names:
        model = _four_link(dynamics, name, settings)
        c = np.asarray(model.restitution, dtype=float)
        if not np.all(np.isfinite(c) & (c > 0)):  # e.g. the paper's link rule on piers
            shown = c + 0.0  # -0.0 printed as 0
            skipped[name] = (f"its coefficients of restitution are {shown[0]:.4g} and "
                             f"{shown[1]:.4g}: "
                             f"the rule does not apply to this structure's mechanisms")
            continue
        four_link[name] = domain_of(model, d, grid, direction=direction,
                                    resolution_g=float(resolution_g), extend_to_g=None,
                                    motion=motion)
    if not four_link:
        raise ValueError("no restitution model applies to this structure: "
                         + "; ".join(f"{n}: {why}" for n, why in skipped.items()))
    return ModelComparison(arch, rigid_block, four_link, grid, float(resolution_g), settings,
                           skipped)


@dataclass(frozen=True)
class Disagreement:
    """Where two failure domains of the same structure disagree on collapse, per duration.

    Attributes
    ----------
    durations : tuple of float
        Pulse durations t_p [s].
    intervals : tuple of tuple of (float, float, str)
        Per duration, the amplitude intervals ``(from, to, which)`` [g] where one model collapses
        and the other does not; ``which`` is ``"first only"`` (the first domain collapses, the
        second does not) or ``"second only"``.
    names : (str, str)
        The two domains' model names (as they describe themselves).
    """

    durations: tuple[float, ...]
    intervals: tuple[tuple[tuple[float, float, str], ...], ...]
    names: tuple[str, str]

    def width_g(self) -> np.ndarray:
        """Total width of the disagreement per duration [g]."""
        return np.array([sum(b - a for a, b, _ in piece) for piece in self.intervals])

    def to_list(self) -> list[dict]:
        """JSON-ready list: ``duration`` [s] and ``intervals`` (``from``, ``to`` [g],
        ``collapses``: the name of the model that collapses there).

        Returns
        -------
        list of dict
        """
        return [{"duration": d,
                 "intervals": [{"from": a, "to": b,
                                "collapses": self.names[0 if which == "first only" else 1]}
                               for a, b, which in piece]}
                for d, piece in zip(self.durations, self.intervals, strict=True)]


def _collapse_edges(piece) -> list[tuple[float, float, bool]]:
    return [(iv.start, iv.end, iv.status == "collapse") for iv in piece.intervals]


def domain_disagreement(first, second) -> Disagreement:
    """Where two failure domains disagree on collapse: the four-link model's error, in the
    (pulse duration, amplitude) plane, estimated by the rigid-block model.

    The two domains are values already computed (no analysis is run): at every duration the
    amplitude axis is cut at the boundaries of both, and every piece where exactly one of them
    collapses is reported. With the four-link domain first and the rigid-block domain second,
    ``"first only"`` is where the four-link model predicts a collapse the rigid blocks do not
    (unconservative nowhere, conservative there) and ``"second only"`` where it misses one (the
    four-link model is unconservative).

    Parameters
    ----------
    first, second : FailureDomain
        Domains of the same durations (to 1e-9 s) and direction; their boundaries are known to
        their resolutions, so a disagreement narrower than the coarser resolution may be the
        bisection's, not the models'.

    Returns
    -------
    Disagreement

    Raises
    ------
    ValueError
        If the durations or directions differ.
    """
    from .failure_domain import FailureDomain

    if not (isinstance(first, FailureDomain) and isinstance(second, FailureDomain)):
        raise ValueError("first and second must be FailureDomain values")
    if (first.durations.shape != second.durations.shape
            or not np.allclose(first.durations, second.durations, rtol=0, atol=1e-9)
            or first.direction != second.direction):
        raise ValueError("the two domains must have the same durations and direction")
    out = []
    for a, b in zip(first.slices, second.slices, strict=True):
        ea, eb = _collapse_edges(a), _collapse_edges(b)
        lo = max(ea[0][0], eb[0][0])
        hi = min(ea[-1][1], eb[-1][1])
        cuts = sorted({lo, hi, *(x for e in ea + eb for x in e[:2] if lo < x < hi)})
        piece = []
        for x0, x1 in zip(cuts[:-1], cuts[1:], strict=False):
            mid = 0.5 * (x0 + x1)
            ca = next(c for s, e, c in ea if s <= mid <= e)
            cb = next(c for s, e, c in eb if s <= mid <= e)
            if ca != cb:
                which = "first only" if ca else "second only"
                if piece and piece[-1][2] == which and piece[-1][1] == x0:
                    piece[-1] = (piece[-1][0], x1, which)
                else:
                    piece.append((x0, x1, which))
        out.append(tuple(piece))
    names = tuple((d.model or {}).get("model", "?") for d in (first, second))
    return Disagreement(tuple(float(s.duration) for s in first.slices), tuple(out), names)


PROBE_RESOLUTION_G = 0.01
"""Bisection width of both models' failure accelerations in :func:`agreement_probe` [g]."""

PROBE_STEP_G = 0.05
"""Spacing of the amplitude scan of :func:`agreement_probe` [g], from just below the load
multiplier k (no model moves below ``a = k``) up to :data:`PROBE_TOP_G`."""

PROBE_TOP_G = 3.0
"""Highest amplitude :func:`agreement_probe` analyses [g]: a failure acceleration above it is
reported as undecided."""

PROBE_REFERENCE_DURATIONS = (0.25, 0.5, 1.0)
"""Pulse durations [s] of :func:`agreement_probe` for a command without its own (under
records): short, middle and long pulses of the paper's range, where the two models disagree
most, somewhat, and least on Oppenheim's arch."""

PROBE_DURATIONS = 3
"""Durations a command's probe takes from its own (:func:`probe_durations`) [-]."""


def probe_durations(durations, count: int = PROBE_DURATIONS) -> tuple[float, ...]:
    """A few durations across ``durations``: all of them if at most ``count``, else the
    shortest, the longest and those evenly between them (by rank) [s].

    Parameters
    ----------
    durations : sequence of float
        A command's pulse durations t_p [s].
    count : int
        Most durations kept, >= 2.

    Returns
    -------
    tuple of float
    """
    d = sorted({float(x) for x in np.atleast_1d(np.asarray(durations, dtype=float))})
    if not d:
        raise ValueError("durations must hold at least one pulse duration t_p [s]")
    if not (isinstance(count, int) and count >= 2):
        raise ValueError(f"count must be an integer >= 2, got {count!r}")
    if len(d) <= count:
        return tuple(d)
    ranks = np.unique(np.round(np.linspace(0, len(d) - 1, count)).astype(int))
    return tuple(d[i] for i in ranks)


@dataclass(frozen=True)
class ProbeRow:
    """The two models' failure accelerations under Oppenheim's pulse at one duration.

    Attributes
    ----------
    duration : float
        Pulse duration t_p [s].
    four_link, rigid_block : float
        Failure accelerations [g] (nan: none found, or not decided: see ``undecided``).
    difference : float
        ``(four_link - rigid_block) / rigid_block`` [-] (nan when undecided).
    beyond : bool
        Whether ``|difference|`` exceeds the band (False when undecided).
    undecided : str
        Why no difference is known, in words ("" when it is).
    """

    duration: float
    four_link: float
    rigid_block: float
    difference: float
    beyond: bool
    undecided: str = ""

    def to_dict(self) -> dict:
        """JSON-ready: ``duration`` [s], ``four_link``, ``rigid_block`` [g] (None: none),
        ``difference`` [-] (None: undecided), ``beyond_band`` and ``undecided`` (the reason, or
        None)."""
        return {"duration": self.duration, "four_link": json_float(self.four_link),
                "rigid_block": json_float(self.rigid_block),
                "difference": json_float(self.difference), "beyond_band": self.beyond,
                "undecided": self.undecided or None}


@dataclass(frozen=True)
class AgreementProbe:
    """Whether the four-link model's failure accelerations agree with the rigid-block model's
    (:func:`agreement_probe`).

    Attributes
    ----------
    rows : tuple of ProbeRow
        One per probed duration, shortest first.
    band : float
        The agreement band [-] (:data:`archquake.defaults.AGREEMENT_BAND`).
    resolution_g : float
        Bisection width of both models' failure accelerations [g].
    restitution : (float, float)
        The four-link model's coefficients of restitution (l->r, r->l) [-].
    seconds : float
        Wall-clock time of the probe [s].
    on_piers : bool
        Whether the structure stands on a pier (the rigid blocks' agreement with LMGC90 is
        then 0.4 %; 1 % on fixed supports).
    """

    rows: tuple
    band: float
    resolution_g: float
    restitution: tuple
    seconds: float = 0.0
    on_piers: bool = True

    @property
    def disagrees(self) -> bool:
        """Whether the models disagree beyond the band at some probed duration."""
        return any(r.beyond for r in self.rows)

    @property
    def undecided(self) -> bool:
        """Whether some probed duration has no known difference."""
        return any(r.undecided for r in self.rows)

    def row_at(self, duration: float):
        """The row of ``duration`` (to 1e-9 s), or None."""
        return next((r for r in self.rows if abs(r.duration - duration) <= 1e-9), None)

    def messages(self) -> list[str]:
        """One line per probed duration where the four-link value is not to be trusted: beyond
        the band, or no difference known."""
        out = []
        for r in self.rows:
            if r.beyond:
                where = "0.4 % on piers" if self.on_piers else "1 % on fixed supports"
                out.append(f"the rigid-block model (trusted; agrees with LMGC90 to {where}) "
                           f"gives {r.rigid_block:.2f} g at t_p = {r.duration:g} s: the "
                           f"four-link value ({r.four_link:.2f} g) is off by "
                           f"{100 * r.difference:+.0f} %")
            elif r.undecided:
                out.append(f"model check undecided at t_p = {r.duration:g} s: {r.undecided}")
        return out

    def to_dict(self) -> dict:
        """JSON-ready: ``band``, ``resolution`` [g], ``restitution``, ``disagrees``,
        ``undecided`` and ``rows`` (:meth:`ProbeRow.to_dict`); not its wall time
        (``seconds``), so that a study's summary is the same when it is resumed."""
        return {"band": self.band, "resolution": self.resolution_g,
                "restitution": [float(c) for c in self.restitution],
                "disagrees": self.disagrees, "undecided": self.undecided,
                "rows": [r.to_dict() for r in self.rows]}


def probe_grid(limit_multiplier: float) -> np.ndarray:
    """The amplitude scan of :func:`agreement_probe` [g]: from just below the load multiplier
    ``k`` (rounded down to :data:`PROBE_STEP_G`, at least one step) to :data:`PROBE_TOP_G`."""
    from .failure_domain import inclusive_range

    k = float(limit_multiplier)
    start = max(PROBE_STEP_G, PROBE_STEP_G * math.floor(0.99 * k / PROBE_STEP_G)) \
        if math.isfinite(k) else PROBE_STEP_G
    return inclusive_range(start, PROBE_TOP_G, PROBE_STEP_G)


def agreement_rows(four_link, rigid_block) -> tuple:
    """Duration by duration, the two failure domains' failure accelerations, their relative
    difference and whether it is beyond :data:`~archquake.defaults.AGREEMENT_BAND`.

    Parameters
    ----------
    four_link, rigid_block : FailureDomain
        The four-link and the rigid-block domain of one structure, same durations (to 1e-9 s).

    Returns
    -------
    tuple of ProbeRow
        No difference is known (``undecided`` says why) where either model collapses at the
        lowest amplitude scanned or at none, or where the rigid blocks are undecided below
        their lowest decided collapse.
    """
    from .failure_domain import FailureDomain

    if not (isinstance(four_link, FailureDomain) and isinstance(rigid_block, FailureDomain)):
        raise ValueError("four_link and rigid_block must be FailureDomain values")
    if (four_link.durations.shape != rigid_block.durations.shape
            or not np.allclose(four_link.durations, rigid_block.durations, rtol=0, atol=1e-9)):
        raise ValueError("the two domains must have the same durations")
    rows = []
    for a, b in zip(four_link.slices, rigid_block.slices, strict=True):
        why = []
        for name, s in (("four-link", a), ("rigid-block", b)):
            if s.failure_acceleration_bound == "upper":
                why.append(f"the {name} model collapses from the lowest amplitude scanned "
                           f"({s.intervals[0].start:g} g)")
            elif math.isnan(s.failure_acceleration_g):
                why.append(f"the {name} model does not collapse up to {s.scanned_to_g:g} g")
        if math.isfinite(b.failure_undecided_from_g):
            why.append(f"the rigid-block analyses are undecided from "
                       f"{b.failure_undecided_from_g:.2f} g")
        fa, fb = a.failure_acceleration_g, b.failure_acceleration_g
        diff = math.nan if why else fa / fb - 1.0
        rows.append(ProbeRow(float(a.duration), fa, fb, diff,
                             bool(not why and abs(diff) > AGREEMENT_BAND), "; ".join(why)))
    return tuple(rows)


def agreement_probe(arch: BlockArch, durations: Sequence[float], *, four_link=None,
                    settings=None, direction: str = "l",
                    resolution_g: float = PROBE_RESOLUTION_G) -> AgreementProbe:
    """Do the four-link and the rigid-block model agree on the failure acceleration of
    ``arch`` under Oppenheim's pulse? A cheap check beside any four-link number.

    At every duration both models' failure accelerations (the lowest collapsing amplitude) are
    found by the one failure-domain search (:func:`archquake.studies.failure_domain.domain_of`)
    on the scan :func:`probe_grid` bisected to ``resolution_g`` (the rigid blocks by the
    ``bisection`` search, no extension of the scan); the relative difference is called beyond
    the band where ``|a_four_link / a_rigid_block - 1| >``
    :data:`~archquake.defaults.AGREEMENT_BAND`. The rigid-block model is the one trusted: it
    agrees with the discrete-element code LMGC90 to 1 % on fixed supports and 0.4 % on piers,
    where the four-link model keeps the four hinges of the limit analysis.

    No difference is known (the row says why) where either model collapses at the lowest
    amplitude scanned or at none, or where the rigid blocks left an undecided band below their
    lowest decided collapse (:mod:`archquake.studies.undecided`).

    Parameters
    ----------
    arch : BlockArch
        The structure.
    durations : sequence of float
        Pulse durations t_p [s] (a few: :func:`probe_durations`).
    four_link : FourLinkModel, optional
        The four-link model whose numbers are checked (its restitution); default the arch's
        with the default restitution.
    settings : BlockSettings, optional
        The rigid-block model's settings (default :class:`~archquake.rigid_blocks.BlockSettings`).
    direction : {"l", "r"}
        Direction of the first pulse.
    resolution_g : float
        Bisection width of both failure accelerations [g].

    Returns
    -------
    AgreementProbe

    Raises
    ------
    ValueError
        If ``four_link`` is not a FourLinkModel of ``arch``, or the durations, direction or
        resolution are refused by :func:`~archquake.studies.failure_domain.domain_of`.
    """
    import time

    from ..fourlink.model import FourLinkModel
    from ..rigid_blocks import BlockSettings, RigidBlockModel
    from .failure_domain import domain_of

    start = time.perf_counter()
    if four_link is None:
        four_link = FourLinkModel.from_arch(arch)
    elif not isinstance(four_link, FourLinkModel) or four_link.arch is not arch:
        raise ValueError("four_link must be the FourLinkModel of arch")
    d = tuple(sorted(float(x) for x in durations))
    grid = probe_grid(four_link.load_multiplier)
    fl = domain_of(four_link, d, grid, direction=direction, resolution_g=resolution_g,
                   extend_to_g=None)
    blocks = RigidBlockModel(arch, BlockSettings() if settings is None else settings)
    rb = domain_of(blocks, d, grid, direction=direction, resolution_g=resolution_g,
                   extend_to_g=None, search="bisection")
    rows = agreement_rows(fl, rb)
    on_piers = getattr(arch, "left", None) is not None or getattr(arch, "right", None) is not None
    return AgreementProbe(rows, AGREEMENT_BAND, float(resolution_g),
                          tuple(float(c) for c in four_link.restitution),
                          time.perf_counter() - start, on_piers)


__all__ = ["AgreementProbe", "Disagreement", "ModelComparison", "ProbeRow", "agreement_probe",
           "agreement_rows",
           "compare_models", "domain_disagreement", "probe_durations", "probe_grid",
           "PROBE_REFERENCE_DURATIONS"]
