r"""How a study finds the outcomes along a grid: every point, or a coarse scan and bisection.

A study asks, for one structure, one pulse duration (or record) and one direction, the outcome
class at every point of an increasing grid of amplitudes (or intensity levels)
:math:`a_0 < a_1 < \dots < a_{n-1}`. The four-link model answers a whole grid in one compiled
call (about 15 µs a point), the rigid-block model one analysis at a time (3-10 ms): for it the
search strategy is where the speed comes from. Three strategies (:data:`SEARCHES`):

``exhaustive``
    Every grid point is analysed.
``bisection``
    A coarse scan every ``stride`` points (the first and the last included), then every pair of
    neighbouring coarse points with different outcomes is bisected on the grid's indices until
    the change lies between two neighbouring grid points (a third outcome met inside a bracket
    is bisected on both sides). The points between two coarse points with the same outcome take
    that outcome without analysis.
``screened``
    As ``bisection``, with two safeguards. The coarse scan is refined where a cheap screening
    model (the four-link model of the same structure, a whole grid in one call) changes outcome:
    the grid points on both sides of each of its changes are analysed too. And an outcome is
    inferred only between two analysed points whose outcome is *smooth* in the amplitude: rest
    (the structure never moved), or a collapse decided while the excitation still acts; every
    other stretch (recoveries, collapses after the excitation, after rocking and impacts) is
    analysed point by point.

``bisection`` gives the outcome of the exhaustive grid at every point under one condition,
which is also where it can differ from it: between two coarse points with the same outcome, the
outcome does not change and change back. A band of another outcome narrower than ``stride``
grid steps that lies wholly between two coarse points is missed. The rigid-block model has such
bands: after a pulse an arch that rocks for seconds before it collapses is in a chaotic regime,
and at isolated amplitudes, one or two grid steps of 0.01 g wide, it recovers instead. Such
outcomes are sensitive to any perturbation, the time step included: halving the step from 1 ms
changes the status of about one grid point in a hundred of the paper's study, all of them in
these stretches (``benchmarks/rigid_block_time_step.py``); a strategy must reproduce them all
the same, since it is compared with the exhaustive grid of the same model. They lie among the
collapses decided after the excitation, which is why ``screened`` analyses those
stretches whole; between a rest and a rest, or a collapse during the pulse and another, no band
was found in any case we ran (the test suite and ``benchmarks/rigid_block_fragility.py``
compare with the exhaustive grid). With ``stride = 1`` both are the exhaustive grid.
:func:`search_grid` reports which points were analysed, so a result can say which outcomes are
inferred.

The outcome of a point is an integer key (for the failure domain: the status and the half cycle
of a collapse; for fragility: the status), compared for equality only.

An analysis the model left undecided (:attr:`archquake.status.Status.UNDECIDED`) is a key of its
own, never one of its neighbours': a change to or from it is bisected like any other, and it is
not smooth, so ``screened`` analyses every point between it and the analysed points beside it.
Only ``bisection`` infers it, between two analysed points both undecided; a study counts the
points of its table that are undecided, analysed or inferred (:mod:`archquake.studies.undecided`).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np

from ..checks import check_integer
from ..defaults import DEFAULT_STRIDE, SEARCHES


def check_search(search: str) -> str:
    """Validate a search strategy, one of :data:`SEARCHES`.

    Parameters
    ----------
    search : str
        ``"exhaustive"``, ``"bisection"`` or ``"screened"``.

    Returns
    -------
    str

    Raises
    ------
    ValueError
        For any other value; the message lists the strategies.
    """
    if search not in SEARCHES:
        raise ValueError(f"search must be one of {', '.join(repr(s) for s in SEARCHES)}, got "
                         f"{search!r}")
    return search


def check_stride(stride) -> int:
    """Validate the coarse stride: an integer >= 1 [grid steps]."""
    if isinstance(stride, bool) or not isinstance(stride, int | np.integer) or stride < 1:
        raise ValueError(f"stride must be an integer >= 1 [grid steps], got {stride!r}")
    return int(stride)


def coarse_indices(n: int, stride: int, hints: Sequence[int] = ()) -> np.ndarray:
    """The indices of the coarse scan: every ``stride``-th of ``range(n)``, the last one, and
    ``hints`` (each with its two neighbours), sorted and unique.

    Parameters
    ----------
    n : int
        Number of grid points [-], >= 1.
    stride : int
        Grid steps between coarse points [-], >= 1.
    hints : sequence of int
        Indices where a screening model changes outcome (the change lies between ``i`` and
        ``i + 1``: both are scanned).

    Returns
    -------
    ndarray of int
    """
    base = np.arange(0, n, check_stride(stride))
    extra = [n - 1]
    for i in hints:
        extra += [int(i) - 1, int(i), int(i) + 1]
    idx = np.unique(np.concatenate([base, np.asarray(extra, dtype=np.int64)]))
    return idx[(idx >= 0) & (idx < n)]


def change_hints(keys: np.ndarray) -> list[int]:
    """Indices ``i`` where ``keys[i] != keys[i + 1]`` (a screening model's changes)."""
    keys = np.asarray(keys)
    return [int(i) for i in np.flatnonzero(keys[1:] != keys[:-1])]


def search_grid(classify: Callable[[np.ndarray], np.ndarray], n: int, *,
                search: str = "bisection", stride: int = DEFAULT_STRIDE,
                screen: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Outcome keys at every point of a grid of ``n`` points, by the strategy ``search``.

    Parameters
    ----------
    classify : callable
        ``classify(indices) -> keys`` or ``-> (keys, smooth)``: integer outcome keys of the
        grid points ``indices`` (an int array, increasing) and, optionally, whether each
        outcome is smooth in the amplitude (module docstring; default all smooth); called with
        several indices at a time (the coarse scan in one call, so that a model may analyse
        them together or in parallel), never twice for the same index.
    n : int
        Number of grid points [-], >= 1.
    search : {"exhaustive", "bisection", "screened"}
        The strategy (module docstring).
    stride : int
        Grid steps between coarse points of ``bisection`` and ``screened`` [-].
    screen : ndarray of int, optional
        The screening model's keys at every grid point (``screened`` only; without them the
        coarse scan is not refined, the other safeguard stays).

    Returns
    -------
    keys : ndarray of int64, shape (n,)
        The outcome key of every point (analysed or inferred).
    analysed : ndarray of bool, shape (n,)
        Which points were analysed.

    Raises
    ------
    ValueError
        For an unknown strategy, a bad ``stride`` or ``n``, or a ``screen`` that is not ``n``
        keys.

    Examples
    --------
    A step from 0 to 1 at index 37 of 61 points costs 9 coarse analyses and 3 bisections:

    >>> keys, analysed = search_grid(lambda i: (i >= 37).astype(int), 61, stride=8)
    >>> int(np.flatnonzero(keys)[0]), int(analysed.sum())
    (37, 12)
    """
    check_search(search)
    if isinstance(n, bool) or not isinstance(n, int | np.integer) or n < 1:
        raise ValueError(f"n must be an integer >= 1 [grid points], got {n!r}")
    n = int(n)
    keys = np.zeros(n, dtype=np.int64)
    smooth = np.ones(n, dtype=bool)
    analysed = np.zeros(n, dtype=bool)

    def run(indices) -> None:
        indices = np.asarray(sorted(set(int(i) for i in indices) - set(np.flatnonzero(analysed))),
                             dtype=np.int64)
        if indices.size:
            out = classify(indices)
            if isinstance(out, tuple):
                out, smooth[indices] = out
            keys[indices] = np.asarray(out, dtype=np.int64)
            analysed[indices] = True

    if search == "exhaustive":
        run(np.arange(n))
        return keys, analysed
    hints: list[int] = []
    if search == "screened" and screen is not None:
        if np.asarray(screen).shape != (n,):
            raise ValueError(f"the screening model's keys must be one per grid point ({n}), "
                             f"got shape {np.asarray(screen).shape}")
        hints = change_hints(screen)
    coarse = coarse_indices(n, stride, hints)
    run(coarse)
    stack = [(int(a), int(b)) for a, b in zip(coarse[:-1], coarse[1:], strict=True)]
    while stack:
        lo, hi = stack.pop()
        if hi - lo <= 1 or keys[lo] == keys[hi]:
            continue
        mid = (lo + hi) // 2
        run([mid])
        stack += [(lo, mid), (mid, hi)]
    if search == "screened":  # stretches whose outcome is not smooth: every point
        done = np.flatnonzero(analysed)
        for a, b in zip(done[:-1], done[1:], strict=True):
            if b - a > 1 and not (smooth[a] and smooth[b]):
                run(np.arange(a + 1, b))
    # fill the points between analysed neighbours of equal key
    done = np.flatnonzero(analysed)
    for a, b in zip(done[:-1], done[1:], strict=True):
        if b - a > 1:
            keys[a + 1:b] = keys[a]  # keys[a] == keys[b] here: every change was bisected
    return keys, analysed


def search_caveat(search: str, not_analysed: int, points: int, stride: int) -> str | None:
    """What a study searched by ``bisection`` must say with its results: that it can miss
    bands of another outcome, and how many points of its grid it did not analyse.

    ``bisection`` infers the outcome of every point between two coarse points of equal outcome
    (module docstring): a band of collapse among survivals (or of survival among collapses)
    that lies wholly between them is missed, and its boundaries are bisected only where a
    change was found. The other strategies say nothing more: ``exhaustive`` analyses every
    point, ``screened`` every stretch whose outcome is not smooth.

    Parameters
    ----------
    search : {"exhaustive", "bisection", "screened"}
        The strategy of the study.
    not_analysed : int
        Points of the grid whose outcome was inferred, not analysed [-].
    points : int
        Points of the grid [-].
    stride : int
        Grid steps between the coarse points [-].

    Returns
    -------
    str or None
        One sentence for ``bisection``, None otherwise.

    Examples
    --------
    >>> search_caveat("bisection", 32, 34, 33)[:60]
    "search 'bisection' did not analyse 32 of the 34 grid points:"
    >>> search_caveat("screened", 3, 34, 8) is None
    True
    """
    if check_search(search) != "bisection":
        return None
    return (f"search 'bisection' did not analyse {not_analysed} of the {points} grid points: "
            f"it takes their outcome from the coarse points every {stride} steps around them, "
            f"so it misses any band of collapse (or of survival) narrower than that lying "
            f"between two coarse points of the same outcome, and its boundaries are exact only "
            f"where it found a change; --search screened or exhaustive analyse those points")


def pulse_grid_outcomes(model, durations, amplitudes_g, *, motion: str = "oppenheim",
                        search: str = "exhaustive", stride: int = DEFAULT_STRIDE,
                        screen=None) -> dict[str, np.ndarray]:
    """Outcomes of a model over a (direction x duration x amplitude) grid of pulses.

    Both directions of the pulse (``"l"``: first pulse ``-a g``; ``"r"``: ``+a g``), every
    duration, and along every amplitude line the strategy ``search`` (the status, and the half
    cycle of a collapse where the model counts them, are the outcome compared).

    Parameters
    ----------
    model : StructuralModel
        The model of the structure (:mod:`archquake.models`).
    durations : array_like
        Pulse durations t_p [s].
    amplitudes_g : array_like
        Increasing amplitudes a >= 0 [g].
    motion : str
        Pulse shape (:data:`archquake.ground_motion.ANALYTIC_GROUND_MOTIONS`).
    search : {"exhaustive", "bisection", "screened"}
        The strategy along each amplitude line.
    stride : int
        Grid steps between coarse points [-].
    screen : StructuralModel, optional
        The screening model of ``screened`` (none: the coarse scan is not refined by one).

    Returns
    -------
    dict of ndarray
        ``direction`` ("l"/"r"), ``duration`` [s], ``amplitude_g`` [g], ``status``
        (:class:`archquake.status.Status` codes), ``half_cycle`` and ``analysed`` (False where
        the outcome was inferred from the analysed neighbours), 2 x durations x amplitudes rows
        in that order.

    Raises
    ------
    ValueError
        For a bad strategy or stride.
    """
    check_search(search)
    d = np.atleast_1d(np.asarray(durations, dtype=float))
    a = np.atleast_1d(np.asarray(amplitudes_g, dtype=float))
    parts = []
    for direction, sign in (("l", -1.0), ("r", 1.0)):
        status = np.zeros((d.size, a.size), dtype=np.int64)
        half_cycle = np.zeros((d.size, a.size), dtype=np.int64)
        analysed = np.zeros((d.size, a.size), dtype=bool)
        if search == "exhaustive" and model.grid_in_one_call:
            out = model.outcomes(d[:, None], sign * a[None, :], motion)  # one compiled call
            status[:], half_cycle[:] = out["status"], out["half_cycle"]
            analysed[:] = True
        else:
            for i, tp in enumerate(d):
                screen_keys = None
                if search == "screened" and screen is not None:
                    out = screen.outcomes(float(tp), sign * a, motion)
                    screen_keys = _keys(out)
                end = excitation_end(motion, float(tp))

                def classify(indices, tp=tp, end=end, sign=sign):
                    out = model.outcomes(float(tp), sign * a[indices], motion)
                    return _keys(out), smooth_outcomes(out, end)

                keys, analysed[i] = search_grid(classify, a.size, search=search, stride=stride,
                                                screen=screen_keys)
                status[i], half_cycle[i] = keys // 1000, keys % 1000
        grid_d, grid_a = np.meshgrid(d, a, indexing="ij")
        parts.append({"direction": np.full(grid_d.size, direction),
                      "duration": grid_d.ravel(), "amplitude_g": grid_a.ravel(),
                      "status": status.ravel(), "half_cycle": half_cycle.ravel(),
                      "analysed": analysed.ravel()})
    return {name: np.concatenate([p[name] for p in parts]) for name in parts[0]}


def excitation_end(motion: str, duration: float) -> float:
    """Time [s] at which the pulse ``motion`` of duration ``duration`` [s] ends."""
    from ..ground_motion import ground_motion

    return float(ground_motion(motion, 1.0, duration).duration)


def smooth_outcomes(out: dict, excitation_end: float | None) -> np.ndarray:
    """Which outcomes of a model's ``outcomes`` are smooth in the amplitude (module docstring):
    rest, or a collapse decided by ``excitation_end`` [s] under a pulse. Under a record
    (``excitation_end=None``) only rest: a record lasts tens of seconds, and a later excursion
    topples a structure at one level and not at the next, so a collapse during it is not
    smooth in the level (:func:`archquake.studies.record_outcomes.searched_record_outcomes`);
    a rest is (every instant's acceleration scales down with the level, and those a structure
    carries at rest form an interval about 0)."""
    status = np.atleast_1d(np.asarray(out["status"], dtype=np.int64))
    if excitation_end is None:
        return status == 0
    time = np.atleast_1d(np.asarray(out["collapse_time"], dtype=float))
    return (status == 0) | ((status == 2) & (time <= excitation_end))


POOL_START_SECONDS = 3.0
"""Wall time [s] before a pool of fresh worker processes analyses anything: each starts an
interpreter and imports numpy, pandas, scipy, numba and the package (2-3 s measured on the 2
cores of the development machine, the two workers starting together;
``benchmarks/fragility_command.py``)."""

ANALYSIS_SECONDS = {("four-link", "pulse"): 1.5e-5, ("four-link", "record"): 5e-3,
                    ("rigid-blocks", "pulse"): 3e-3, ("rigid-blocks", "record"): 8e-2}
"""Time of one analysis by model and excitation [s], of one process, measured: the four-link
grid under pulses 15 µs a point; a rigid-block analysis under Oppenheim's pulse 3 ms on
average over the paper's grid (0.3 ms at rest, 6 ms for a recovery); under 20-s records,
about 5 ms (four-link) and 80 ms (rigid blocks)."""

ARCH_BLOCKS = 7
"""Blocks of the arch on which :data:`ANALYSIS_SECONDS` were measured (Oppenheim's
voussoirs) [-]."""

ARCH_SECONDS = 0.06
"""Time to draw one arch of a study and build its model [s] (the four-link model's tables and
limit analysis dominate, about 60 ms)."""


def study_seconds(model: str, excitation: str, arches: int, analyses: int,
                  blocks: int | None = None) -> float:
    """Estimated serial time of a study's analyses [s]: ``arches`` x :data:`ARCH_SECONDS` +
    ``analyses`` x :data:`ANALYSIS_SECONDS` of the model under the excitation, the latter
    scaled by ``blocks`` / :data:`ARCH_BLOCKS` for a structure of more blocks than the arch
    they were measured on (a step of the rigid blocks costs time linear in the blocks: at
    least that much; a bridge of three spans, 25 blocks, takes about 15 times an arch's).

    Parameters
    ----------
    model : {"four-link", "rigid-blocks"}
        The model's name.
    excitation : {"pulse", "record"}
        What the analyses apply.
    arches : int
        Arches drawn and modelled [-].
    analyses : int
        Grid points of all arches [-].
    blocks : int, optional
        Blocks of the structure, when more than an arch's (a bridge) [-].

    Returns
    -------
    float

    Examples
    --------
    The paper's study with the four-link model, 40 arches x 488 points:

    >>> round(study_seconds("four-link", "pulse", 40, 40 * 488), 2)  # 2.4 + 0.29
    2.69
    """
    scale = 1.0 if blocks is None else max(1.0, blocks / ARCH_BLOCKS)
    return arches * ARCH_SECONDS + analyses * ANALYSIS_SECONDS[(model, excitation)] * scale


def pool_pays(seconds: float, workers: int) -> bool:
    """Whether ``seconds`` of serial work end sooner on ``workers`` fresh worker processes than
    in this process: ``POOL_START_SECONDS + seconds / workers < seconds``.

    A study of the four-link model's 40 arches (about 3 s of work) ends in half the time in
    the process that reads the command (``benchmarks/fragility_command.py``): two workers would
    spend as long starting as it takes to finish.

    Parameters
    ----------
    seconds : float
        Estimated serial time of the work [s] (:func:`study_seconds`).
    workers : int
        Worker processes [-].

    Returns
    -------
    bool

    Examples
    --------
    >>> pool_pays(5.0, 2), pool_pays(7.0, 2)  # 3 + 2.5 > 5, 3 + 3.5 < 7
    (False, True)
    """
    return workers > 1 and POOL_START_SECONDS + seconds / workers < seconds


def workers_that_pay(seconds: float, workers, *, backend=None, scheduler=None,
                     pool=None):
    """The worker processes a study starts: ``workers``, or None (the calling process) when
    the caller chose no backend, pool or cluster and the study's estimated ``seconds`` of work
    end sooner in this process than on fresh workers (:func:`pool_pays`).

    Parameters
    ----------
    seconds : float
        Estimated serial time of the study [s] (:func:`study_seconds`).
    workers : int or None
        The worker processes asked for [-].
    backend, scheduler, pool : optional
        What the caller gave :func:`archquake.execution.run_study`: any of them keeps
        ``workers`` as given.

    Returns
    -------
    int or None

    Raises
    ------
    ValueError
        For ``workers`` not an integer >= 1.

    Examples
    --------
    >>> workers_that_pay(5.0, 2), workers_that_pay(7.0, 2), workers_that_pay(5.0, 2, pool=0)
    (None, 2, 2)
    """
    if backend is None and pool is None and workers is not None and scheduler is None:
        if not pool_pays(seconds, check_integer("workers", workers)):
            return None  # fewer seconds of work than starting the workers would save
    return workers


def _keys(out: dict) -> np.ndarray:
    """Outcome keys of a model's ``outcomes``: status code x 1000 + the half cycle of a collapse
    (0 for a model that does not count half cycles)."""
    status = np.atleast_1d(np.asarray(out["status"], dtype=np.int64))
    half = np.atleast_1d(np.asarray(out["half_cycle"], dtype=np.int64))
    return status * 1000 + np.where(status == 2, half, 0)


__all__ = ["ANALYSIS_SECONDS", "ARCH_BLOCKS", "ARCH_SECONDS", "DEFAULT_STRIDE",
           "POOL_START_SECONDS",
           "SEARCHES", "change_hints", "check_search", "check_stride",
           "coarse_indices", "excitation_end", "pool_pays", "pulse_grid_outcomes",
           "search_caveat", "search_grid", "smooth_outcomes", "study_seconds",
           "workers_that_pay"]
