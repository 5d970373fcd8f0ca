r"""The loads a block carries in the limit analysis: its weight, its horizontal inertia force and
a bounded passive reaction.

Every block ``i`` of a structure (:class:`~archquake.geometry.BlockArch`) carries, per unit
depth,

- a vertical load :math:`W_i` [N/m] (downward) along the vertical line :math:`x = a_i` [m];
- a horizontal load :math:`k\,H_i` [N/m] toward +x along the horizontal line :math:`y = b_i`
  [m], with :math:`k` the load multiplier of the limit analysis;
- optionally a horizontal passive reaction :math:`s_i P_i` along :math:`y = y_{p,i}`, of
  direction :math:`s_i \in \{-1, 0, +1\}` and magnitude :math:`0 \le P_i \le \bar P_i` [N/m]
  (an unknown of the limit analysis, bounded).

Only the line of action of each force matters to the equilibrium of a rigid block and to the
virtual work of a rigid-body motion (the work of a vertical force depends on the vertical
velocity, which is the same along a vertical line; likewise for a horizontal force), so a
vertical load is given by its x and a horizontal one by its y.

For a bare block :math:`W_i = H_i = m_i g` at its centroid (:meth:`BlockLoads.of_masses`); the
fill over an arch changes them (:mod:`archquake.geometry.fill`).
"""

from __future__ import annotations

from dataclasses import dataclass, fields

import numpy as np

from ..constants import GRAVITY


def _frozen(values, name: str, n: int | None = None) -> np.ndarray:
    arr = np.array(values, dtype=float)
    if arr.ndim != 1 or (n is not None and arr.size != n):
        raise ValueError(f"{name} must be one value per block ({n}), got shape {arr.shape}")
    arr.setflags(write=False)
    return arr


@dataclass(frozen=True, eq=False)
class BlockLoads:
    r"""Loads of every block of a structure for the limit analysis (see the module).

    Parameters
    ----------
    vertical : array of float, shape (n,)
        Weight :math:`W_i` of every block [N/m], >= 0, > 0 in total.
    vertical_x : array of float, shape (n,)
        Abscissa :math:`a_i` of its line of action [m].
    horizontal : array of float, shape (n,)
        Horizontal load per unit load multiplier :math:`H_i` [N/m], >= 0.
    horizontal_y : array of float, shape (n,)
        Ordinate :math:`b_i` of its line of action [m].
    passive : array of float, shape (n,), optional
        Largest passive reaction :math:`\bar P_i` [N/m], >= 0 (default none).
    passive_y : array of float, shape (n,), optional
        Ordinate :math:`y_{p,i}` of the passive reaction [m].
    passive_sign : array of float, shape (n,), optional
        Its direction :math:`s_i`: +1 toward +x, -1 toward -x, 0 none.

    Raises
    ------
    ValueError
        For arrays of different lengths, non-finite values, negative loads or a direction other
        than -1, 0, +1.
    """

    vertical: np.ndarray
    vertical_x: np.ndarray
    horizontal: np.ndarray
    horizontal_y: np.ndarray
    passive: np.ndarray | None = None
    passive_y: np.ndarray | None = None
    passive_sign: np.ndarray | None = None

    def __post_init__(self):
        vertical = _frozen(self.vertical, "vertical")
        n = vertical.size
        set_ = object.__setattr__
        set_(self, "vertical", vertical)
        for name in ("vertical_x", "horizontal", "horizontal_y"):
            set_(self, name, _frozen(getattr(self, name), name, n))
        for name in ("passive", "passive_y", "passive_sign"):
            value = getattr(self, name)
            set_(self, name, _frozen(np.zeros(n) if value is None else value, name, n))
        everything = np.concatenate([getattr(self, name) for name in (
            "vertical", "vertical_x", "horizontal", "horizontal_y", "passive", "passive_y")])
        if not np.isfinite(everything).all():
            raise ValueError("loads and their lines of action must be finite numbers")
        if vertical.min(initial=0.0) < 0 or not vertical.sum() > 0:
            raise ValueError("vertical loads must be >= 0 [N/m] with a positive total")
        if self.horizontal.min(initial=0.0) < 0:
            raise ValueError("horizontal loads must be >= 0 [N/m]")
        if self.passive.min(initial=0.0) < 0:
            raise ValueError("passive reactions must be >= 0 [N/m]")
        if np.any(np.abs(self.passive_sign) * (np.abs(self.passive_sign) - 1.0) != 0.0):
            raise ValueError("passive_sign must be -1, 0 or +1 for every block")

    @classmethod
    def of_masses(cls, masses, centroids) -> BlockLoads:
        """The loads of bare blocks: weight :math:`m_i g` and horizontal load :math:`k m_i g`,
        both through the centroid.

        Parameters
        ----------
        masses : array of float, shape (n,)
            [kg/m].
        centroids : array of float, shape (n, 2)
            [m].
        """
        weight = np.asarray(masses, dtype=float) * GRAVITY
        c = np.asarray(centroids, dtype=float)
        if not (weight.ndim == 1 and c.shape == (weight.size, 2) and weight.min() > 0
                and np.isfinite(c).all()):
            return cls(weight, c[:, 0], weight, c[:, 1])  # the checks say what is wrong
        # an arch's own mass properties are checked: no need to check them again
        loads = object.__new__(cls)
        zeros = np.zeros(weight.size)
        arrays = (weight, c[:, 0].copy(), weight, c[:, 1].copy(), zeros, zeros, zeros)
        for f, value in zip(fields(cls), arrays, strict=True):
            value.setflags(write=False)
            object.__setattr__(loads, f.name, value)
        return loads

    @property
    def n_blocks(self) -> int:
        """Number of blocks n [-]."""
        return int(self.vertical.size)

    @property
    def total_weight(self) -> float:
        r""":math:`\sum_i W_i` [N/m]."""
        return float(self.vertical.sum())

    @property
    def has_passive(self) -> bool:
        """Whether any block has a passive reaction."""
        return bool(np.any((self.passive > 0) & (self.passive_sign != 0)))


__all__ = ["BlockLoads"]
