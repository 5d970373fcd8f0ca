r"""Irregular arches: the paper's eq. (1) [1]_, on the circle and on any centreline.

For every voussoir :math:`i`, independently, with :math:`\tilde p` drawn from the uniform
distribution on [-1, 1] and the tolerance :math:`\varepsilon` (``epsilon``):

- on the paper's circular :class:`~archquake.geometry.CircularArch` (eq. (1) of [1]_):

  .. math::

      \tilde\alpha_i = \frac{\alpha}{n} \left(1 + \varepsilon\, \tilde p_{\alpha_i}\right),
      \qquad
      \tilde t_i = t \left(1 + \varepsilon\, \tilde p_{t_i}\right),
      \qquad
      \tilde R_i = R \left(1 + \chi\, \tilde p_{R_i}\right),
      \qquad
      \chi = \varepsilon\, t / R;

- on a :class:`~archquake.geometry.ShapedArch` of any centreline, its generalisation: the
  voussoir's share of the centreline arc length, its thickness and a shift of its own centreline
  along the normal,

  .. math::

      \tilde\ell_i = \frac{L}{n} \left(1 + \varepsilon\, \tilde p_{\alpha_i}\right), \qquad
      \tilde t_i = t \left(1 + \varepsilon\, \tilde p_{t_i}\right), \qquad
      \tilde\delta_i = \varepsilon\, t\, \tilde p_{R_i}.

  On a circle :math:`\ell_i = R\alpha_i` and the shifted centreline is the circle of radius
  :math:`R + \varepsilon t \tilde p = R(1 + \chi \tilde p)`: the same thing, draw for draw (a
  circular :class:`~archquake.geometry.ShapedArch` and the :class:`~archquake.geometry.CircularArch`
  of the same circle give the same irregular arches for the same seed, to round-off).

The nominal values are the nominal arch's per-voussoir values (so an irregular or explicit arch
can be perturbed again). The total stays deterministic: the drawn angles (lengths) are rescaled
by a common factor so that they fill the nominal embrace (the centreline; each half of a pointed
arch separately, so that its crown joint stays at the crown) -- the paper states that the total
is fixed without saying how. The springings stay where they were. A surveyed arch has no
centreline to perturb.

References
----------
.. [1] The paper, Sect. 2, eq. (1) and Fig. 1b-c; Sect. 5.3.3 (h = 40 arches for the fragility
   curves, s = 1000 for the distribution of the load multiplier).
"""

from __future__ import annotations

import numpy as np

from .blocks import BlockArch


def check_epsilon(epsilon) -> float:
    r"""The one check of the paper's :math:`\varepsilon` (eq. (1)): a number in [0, 1).

    Parameters
    ----------
    epsilon : float
        :math:`\varepsilon` [-].

    Returns
    -------
    float
        ``epsilon`` as a float.

    Raises
    ------
    ValueError
        Naming ``epsilon`` when it is not a number in [0, 1).
    """
    try:
        eps = float(epsilon)
    except (TypeError, ValueError):
        eps = float("nan")
    if isinstance(epsilon, bool) or not 0.0 <= eps < 1.0:
        raise ValueError(f"epsilon must be in [0, 1), got {epsilon!r}")
    return eps


def irregular_arch(nominal: BlockArch, epsilon: float,
                   rng: np.random.Generator | int | None = None) -> BlockArch:
    r"""Random irregular arch drawn around a nominal one [paper, Sect. 2, eq. (1)].

    Parameters
    ----------
    nominal : CircularArch or ShapedArch
        The nominal arch.
    epsilon : float
        :math:`\varepsilon` [-], in [0, 1); the paper's study uses 0.10 (:math:`\chi = 0.015`
        for Oppenheim's arch). ``epsilon = 0`` returns the nominal arch.
    rng : numpy.random.Generator, int or None
        Source of randomness (an int seeds a new generator; None draws fresh entropy). The draws
        are made in one call ``rng.uniform(-1, 1, size=(3, n))``: row 0 angles (lengths), row 1
        thicknesses, row 2 radii (normal shifts).

    Returns
    -------
    CircularArch or ShapedArch
        The irregular arch, of the nominal arch's kind and density
        (:meth:`CircularArch.perturbed <archquake.geometry.CircularArch.perturbed>`,
        :meth:`ShapedArch.perturbed <archquake.geometry.ShapedArch.perturbed>`).

    Raises
    ------
    ValueError
        When ``epsilon`` is not in [0, 1), or ``nominal`` has no centreline to perturb.

    See Also
    --------
    irregular_sample : many arches, one seeded stream each.

    References
    ----------
    .. [1] The paper, Sect. 2, eq. (1) and Fig. 1b-c.
    """
    eps = check_epsilon(epsilon)
    perturbed = getattr(nominal, "perturbed", None)
    if not isinstance(nominal, BlockArch) or perturbed is None:
        raise ValueError(
            "irregular arches are drawn around an arch with a centreline (CircularArch or "
            "ShapedArch), "
            f"got {type(nominal).__name__}")
    try:
        rng = np.random.default_rng(rng)
    except (TypeError, ValueError):  # numpy's message would not name the parameter
        raise ValueError(f"rng must be a numpy.random.Generator, a seed (an integer >= 0) or "
                         f"None, got {rng!r}") from None
    p = rng.uniform(-1.0, 1.0, size=(3, nominal.n_voussoirs))
    if eps == 0.0:
        return nominal
    try:
        return perturbed(eps, p)
    except ValueError as exc:  # the draw is not an arch: say which parameter made it
        raise ValueError(f"epsilon {eps:g} draws an irregular arch that is not valid: "
                         f"{exc}") from exc


def irregular_sample(nominal: BlockArch, epsilon: float, sample_size: int,
                     seed: int | None) -> list[BlockArch]:
    r"""``sample_size`` irregular arches drawn around ``nominal`` [paper, Sect. 2, eq. (1)].

    Arch ``i`` is drawn by :func:`irregular_arch` (eq. (1) of [1]_) with its own generator,
    seeded by the child ``i`` of ``numpy.random.SeedSequence(seed).spawn(sample_size)``. The child
    ``i`` does not depend on ``sample_size``, so arch ``i`` is the same whatever the size of the
    sample, and any part of a study can redraw it alone:
    ``irregular_sample(nominal, epsilon, i + 1, seed)[i]``.

    Parameters
    ----------
    nominal : CircularArch or ShapedArch
        The nominal arch.
    epsilon : float
        The paper's :math:`\varepsilon` [-], in [0, 1).
    sample_size : int
        Number of arches (the paper's :math:`s` or :math:`h`), >= 0.
    seed : int or None
        Entropy of the root ``SeedSequence``, >= 0; ``None`` draws fresh entropy (not
        reproducible).

    Returns
    -------
    list of CircularArch or ShapedArch
        ``sample_size`` irregular arches.

    References
    ----------
    .. [1] The paper, Sect. 2, eq. (1), and Sect. 5.3.3 (h = 40 arches for the fragility curves,
       s = 1000 for the distribution of the load multiplier).
    """
    if isinstance(sample_size, bool) or not float(sample_size).is_integer() or sample_size < 0:
        raise ValueError(f"sample_size must be an integer >= 0 (number of arches), got "
                         f"{sample_size!r}")
    if seed is not None and (isinstance(seed, bool) or not float(seed).is_integer() or seed < 0):
        raise ValueError(f"seed must be an integer >= 0 or None, got {seed!r}")
    children = np.random.SeedSequence(None if seed is None else int(seed)).spawn(int(sample_size))
    return [irregular_arch(nominal, epsilon, np.random.default_rng(child)) for child in children]
