r"""Limit analysis, the analyses: one direction (:func:`limit_analysis`) by either method
(:data:`METHODS`), both directions (:func:`both_directions`, :func:`load_multipliers`), many
arches (:func:`load_multipliers_of`, :func:`limit_sample`) and the virtual displacements of a
mechanism (:func:`virtual_displacements`)."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from ..defaults import DEFAULT_LIMIT_METHOD, LIMIT_METHODS
from ..geometry import BlockArch, irregular_sample
from .equilibrium import is_strut, lp_failure, oriented_arch, scaled_arrays, solve_lp
from .kinematic import (
    KINEMATIC_BATCH,
    check_enumerable,
    family_arrays,
    kinematic_analysis,
    kinematic_multipliers,
    mechanism_motion,
)
from .results import DIRECTIONS, LimitAnalysis, LimitSample
from .self_weight import check_stands_at_rest
from .static import static_analysis


def _check_method(method: str) -> str:
    if method not in METHODS:
        raise ValueError(f"method must be one of {tuple(METHODS)}, got {method!r}")
    return method


METHODS = dict(zip(LIMIT_METHODS, (static_analysis, kinematic_analysis), strict=True))
"""Registry of the limit-analysis methods: ``"static"`` (linear program, lower bound) and
``"kinematic"`` (enumeration of four-hinge mechanisms, upper bound)."""


def limit_analysis(arch: BlockArch, direction: str = "l",
                   method: str = DEFAULT_LIMIT_METHOD) -> LimitAnalysis:
    """Collapse load multiplier, hinges and thrust line of an arch [paper, Sect. 3].

    Parameters
    ----------
    arch : BlockArch
        The arch (in its own frame): any :class:`~archquake.geometry.BlockArch`.
    direction : {"l", "r"}
        ``"l"``: horizontal forces ``k m_i g`` toward +x (Mech-l); ``"r"``: the same analysis of
        ``arch.mirrored()`` (Mech-r, reported in the mirrored frame, as Table 1 of the paper).
    method : {"static", "kinematic"}
        ``"static"``: linear program (HiGHS); ``"kinematic"``: minimum over the admissible
        four-hinge mechanisms. Both give the same result (uniqueness theorem); see the module's
        description for both formulations.

    Returns
    -------
    LimitAnalysis
        The load multiplier [-], the hinges, the thrust line at collapse and the arch analysed.

    Raises
    ------
    ValueError
        For an unknown direction or method, or when ``arch`` is not a
        :class:`~archquake.geometry.BlockArch`; if the
        arch cannot stand under its own weight (no thrust line at k = 0: a negative or no
        collapse multiplier), or never collapses (a thrust line for every k).

    References
    ----------
    .. [1] The paper, Sect. 3, eq. (2) and Table 1: Oppenheim's arch has k = 0.37 and the
       hinges A, B, C, D at joints 0, 3, 5, 7.

    Examples
    --------
    Table 1 of [1]_:

    >>> from archquake import oppenheim
    >>> result = limit_analysis(oppenheim(), "l")
    >>> round(result.load_multiplier, 4)
    0.37
    >>> [(h.joint, h.face) for h in result.hinges]
    [(0, 'intrados'), (3, 'extrados'), (5, 'intrados'), (7, 'extrados')]
    """
    if not isinstance(arch, BlockArch):
        raise ValueError(f"arch must be a CircularArch, a ShapedArch or a SurveyedArch, got "
                         f"{type(arch).__name__}")
    method = _check_method(method)
    result = METHODS[method](oriented_arch(arch, direction), direction)
    if not arch.is_symmetric():
        check_stands_at_rest(arch)
    return result


def virtual_displacements(result: LimitAnalysis) -> np.ndarray:
    r"""Horizontal virtual displacement of every block's horizontal load in the collapse
    mechanism.

    The mechanism of ``result`` (its hinges, or its hinges and separating joint) moves its
    blocks rigidly; block :math:`i` of a moving part turning at rate :math:`\omega` with a
    point at height :math:`y_0` moving horizontally at :math:`v_0` has the horizontal velocity
    :math:`v_0 - \omega (y - y_0)` at height :math:`y` (a rigid-body field), taken on the line
    of action :math:`y = b_i` of its horizontal load :math:`H_i`
    (:class:`~archquake.geometry.BlockLoads`). The field is scaled so that the largest
    displacement is 1 and the horizontal loads do positive work; blocks outside the mechanism
    (a pier below a hinge at its bed joint, the blocks beyond the springing hinges) do not
    move.

    These are the :math:`\delta_{x,i}` of the participating mass of a local mechanism
    (:mod:`archquake.site.local_mechanism`).

    Parameters
    ----------
    result : LimitAnalysis
        A collapse mechanism (:func:`limit_analysis`), in the frame of ``result.arch``.

    Returns
    -------
    ndarray, shape (n,)
        :math:`\delta_{x,i}` [-] of every block of ``result.arch``, in [-1, 1] (0 for a block
        that does not move).

    Examples
    --------
    Oppenheim's arch (Table 1 of the paper: hinges at joints 0, 3, 5, 7): every voussoir moves.

    >>> from archquake import oppenheim
    >>> dx = virtual_displacements(limit_analysis(oppenheim(), "l"))
    >>> round(float(dx.max()), 6), bool((dx > 0).all())
    (1.0, True)
    """
    s = scaled_arrays(result.arch)
    blocks, sense = mechanism_motion(s, result.hinges, result.separation)
    dx = np.zeros(result.arch.n_voussoirs)
    for j0, j1, vx0, rate, y0 in blocks:
        dx[j0:j1] = sense * (vx0 - rate * (s.horizontal_y[j0:j1] - y0))
    return dx / np.max(np.abs(dx))


def both_directions(arch: BlockArch, method: str = DEFAULT_LIMIT_METHOD
                    ) -> tuple[LimitAnalysis, LimitAnalysis]:
    r"""Limit analyses for Mech-l and Mech-r: ``(result_l, result_r)``.

    Parameters
    ----------
    arch : BlockArch
        The arch.
    method : {"static", "kinematic"}
        Limit-analysis method (:func:`limit_analysis`).

    Returns
    -------
    result_l, result_r : LimitAnalysis
        Mech-l in the frame of ``arch``, Mech-r in the frame of its mirror image; their load
        multipliers are the paper's :math:`\tilde k_l` and :math:`\tilde k_r` [-].
    """
    if not isinstance(arch, BlockArch):
        raise ValueError(f"arch must be a CircularArch, a ShapedArch or a SurveyedArch, got "
                         f"{type(arch).__name__}")
    method = _check_method(method)
    # each direction refuses a negative multiplier: two non-negative ones bracket k = 0, so
    # the arch stands at rest
    return tuple(METHODS[method](oriented_arch(arch, d), d) for d in DIRECTIONS)


def load_multipliers(arch: BlockArch, method: str = DEFAULT_LIMIT_METHOD) -> tuple[float, float]:
    """``(k_l, k_r)`` of an arch, without hinges or thrust line (the fast path of studies).

    Parameters
    ----------
    arch : BlockArch
        The arch.
    method : {"static", "kinematic"}
        Limit-analysis method.

    Returns
    -------
    k_l, k_r : float
        Load multipliers of Mech-l and Mech-r [-]. A direction in which the arch never
        collapses gives ``inf``; an arch that admits no thrust line at all (too thin to stand)
        gives ``nan`` with the static method (the kinematic method gives the negative multiplier
        of its self-weight mechanism).
    """
    k_l, k_r = load_multipliers_of([arch], method)[0]
    return float(k_l), float(k_r)


def load_multipliers_of(arches: Sequence[BlockArch],
                        method: str = DEFAULT_LIMIT_METHOD) -> np.ndarray:
    """``(k_l, k_r)`` of each of many arches, shape (len(arches), 2): :func:`load_multipliers`
    for a sample. The kinematic method evaluates the mechanisms of all arches with the same
    number of voussoirs together, :data:`KINEMATIC_BATCH` at a time, in one compiled call
    (about 3x faster per arch than one by one); the static method solves one linear program per
    arch and direction.
    """
    _check_method(method)
    arches = list(arches)
    out = np.empty((len(arches), 2))
    for col, direction in enumerate(DIRECTIONS):
        oriented = [oriented_arch(a, direction) for a in arches]
        if method == "kinematic":
            by_size: dict[int, list[int]] = {}
            for i, a in enumerate(oriented):
                by_size.setdefault(a.n_voussoirs, []).append(i)
            for size, rows in by_size.items():
                # at most KINEMATIC_BATCH arches, and about 4 million multipliers, per call
                check_enumerable(size)
                count = family_arrays(tuple(range(size + 1)))[0].shape[0]
                batch = max(1, min(KINEMATIC_BATCH, 4_000_000 // count))
                for start in range(0, len(rows), batch):
                    part = rows[start:start + batch]
                    out[part, col] = kinematic_multipliers([oriented[i] for i in part])
            continue
        for i, a in enumerate(oriented):
            res = solve_lp(scaled_arrays(a))
            status = {0: None, 2: math.nan, 3: math.inf}.get(res.status, "failed")
            if res.status != 0 and is_strut(a):  # unbounded, which HiGHS may fail to tell
                status = math.inf
            if status == "failed":
                raise lp_failure(res, a)
            out[i, col] = float(res.x[-1]) if status is None else status
    return out


def limit_sample(
    nominal: BlockArch, epsilon: float, sample_size: int, seed: int | None = 0,
    method: str = DEFAULT_LIMIT_METHOD,
) -> LimitSample:
    r"""k~_l and k~_r of ``sample_size`` irregular arches around ``nominal`` [paper, Figs. 17-20].

    The arches are those of :func:`archquake.geometry.irregular_sample` with the same
    ``epsilon`` and ``seed`` (arch ``i`` from child ``i`` of ``SeedSequence(seed)``).

    Parameters
    ----------
    nominal : CircularArch or ShapedArch
        The nominal arch.
    epsilon : float
        The paper's epsilon [-], in [0, 1).
    sample_size : int
        Number of arches s [-] (>= 0; the paper: 1000).
    seed : int or None
        Root seed.
    method : {"static", "kinematic"}
        Limit-analysis method.

    Returns
    -------
    LimitSample
        :math:`\tilde k_l, \tilde k_r` of every arch and
        :math:`\tilde k = \min(\tilde k_l, \tilde k_r)` [-], whose empirical distribution
        (:func:`archquake.studies.fits.empirical_cdf`) is the blue curve of Figs. 17-20 of
        the paper.
    """
    _check_method(method)
    if isinstance(sample_size, bool) or not float(sample_size).is_integer() or sample_size < 0:
        raise ValueError(f"sample_size must be an integer >= 0 (number of arches), got "
                         f"{sample_size!r}")
    arches = irregular_sample(nominal, epsilon, int(sample_size), seed)
    k = load_multipliers_of(arches, method).reshape(-1, 2)
    k_l, k_r = k[:, 0].copy(), k[:, 1].copy()
    k_l.setflags(write=False)
    k_r.setflags(write=False)
    return LimitSample(k_l, k_r, float(epsilon), seed, method)
