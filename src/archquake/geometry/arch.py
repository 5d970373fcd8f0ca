r"""The paper's circular arch: annular-sector voussoirs with radial joints [paper, Sect. 2].

An :class:`CircularArch` is a sequence of voussoirs with radial joints, each an annular sector with
its own angle, thickness and mean radius: one kind of :class:`~archquake.geometry.BlockArch` (the
contract of the package, :mod:`archquake.geometry`), with closed forms for its joints and mass
properties. :func:`circular_arch` builds the nominal arch of equal voussoirs;
:func:`~archquake.geometry.irregular_arch` and :func:`~archquake.geometry.irregular_sample` draw
random irregular arches around it (the paper's eq. (1), :meth:`CircularArch.perturbed`);
:meth:`CircularArch.from_voussoirs` / :meth:`CircularArch.from_json` take an arch given voussoir by
voussoir.

Notes
-----
Conventions of the circular arch (those of every arch are in :mod:`archquake.geometry`):

- Frame: x to the right, y up, centre O of the arch at the origin (Fig. 1a of [1]_); for a
  symmetric arch the springings are at :math:`y = R\cos\beta_0`. Units: m, rad, kg.
- Voussoirs are numbered left to right, ``0 .. n-1``; joints ``0 .. n``; joint 0 is the left
  springing, joint ``n`` the right springing. Voussoir ``i`` lies between joints ``i`` and ``i+1``.
- The progressive angle :math:`\beta` is measured from the left springing side: a point at
  radius :math:`r` on the radial line of progressive angle :math:`\beta` is
  :math:`(-r\cos\beta,\ r\sin\beta)` (polar angle :math:`\pi - \beta`). The left springing joint
  is at :math:`\beta_0`; for an arch symmetric about the vertical axis
  :math:`\beta_0 = (\pi - \alpha)/2`, where :math:`\alpha` is the angle of embrace (Fig. 1a of
  [1]_).
- Joints are radial (they pass through O). Each voussoir ``i`` is an annular sector of mean
  radius :math:`R_i`, thickness :math:`t_i` and angle :math:`\alpha_i`: inner radius
  :math:`R_i - t_i/2` (intrados), outer radius :math:`R_i + t_i/2` (extrados).
- Mass properties are per unit depth (out of plane), with density ``density`` [kg/m^3].

References
----------
.. [1] "Dynamic response of masonry arch with geometrical irregularities subjected to a
   pulse-type ground motion" -- called "the paper" throughout archquake; Sect. 2, eq. (1),
   Fig. 1.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .._equality import value_equality
from ..constants import DEFAULT_DENSITY
from .blocks import (
    LENGTH_RANGE,
    MAX_VOUSSOIRS,
    MIN_VOUSSOIRS,
    BlockArch,
    check_density,
    check_voussoir_count,
    float_array,
    is_json_number,
    json_text,
    read_json_file,
    real_number,
)
from .mass import Arc

RADIUS_RANGE = LENGTH_RANGE
"""Accepted mean radii of a voussoir [m]: :data:`~archquake.geometry.blocks.LENGTH_RANGE`,
from a millimetre to ten kilometres."""


def _check_voussoir_count(n: int) -> None:
    if n > MAX_VOUSSOIRS:
        raise ValueError(f"voussoirs must be at most {MAX_VOUSSOIRS} (MAX_VOUSSOIRS), got {n}")


def _check_positive(name: str, value: float, unit: str) -> float:
    value = real_number(name, value, unit)
    if not math.isfinite(value) or value <= 0.0:
        raise ValueError(f"{name} must be a finite number > 0 [{unit}], got {value!r}")
    return value


@value_equality
@dataclass(frozen=True)
class CircularArch(BlockArch):
    r"""An arch made of ``n`` voussoirs with radial joints (annular sectors), centre at O.

    Build arches with :func:`circular_arch`, :func:`irregular_arch`,
    :meth:`CircularArch.from_voussoirs` or :meth:`CircularArch.from_json`. Every constructor checks
    its input and raises a ``ValueError`` that names the parameter and its valid range. An arch is
    immutable; two arches are equal (and hash equal) when every field is equal, arrays element by
    element.

    Parameters
    ----------
    angles : array of float, shape (n,)
        Angle of embrace :math:`\alpha_i` of every voussoir [rad], left to right; all > 0 and
        summing to less than :math:`2\pi`.
    thicknesses : array of float, shape (n,)
        Thickness :math:`t_i` of every voussoir [m], in :math:`(0, 2 R_i)`.
    radii : array of float, shape (n,)
        Mean radius :math:`R_i` of every voussoir [m], > 0.
    start_angle : float
        Progressive angle :math:`\beta_0` of the left springing joint [rad].
    density : float, default 2000
        Density of the masonry [kg/m^3]; mass properties are per unit depth.

    Notes
    -----
    The contact at an inner joint is the overlap of the radial extents of the two voussoirs it
    separates (:meth:`joint_extents`); adjacent voussoirs must overlap. At least four voussoirs
    are needed for a four-hinge mechanism.

    References
    ----------
    .. [1] The paper, Sect. 2 and Fig. 1: the voussoir parameters :math:`\alpha_i, t_i, R_i`.
    """

    angles: np.ndarray
    thicknesses: np.ndarray
    radii: np.ndarray
    start_angle: float
    density: float = DEFAULT_DENSITY
    _cache: dict = field(default_factory=dict, init=False, repr=False, compare=False, hash=False)

    def __post_init__(self):
        angles = float_array("angles", self.angles)
        thicknesses = float_array("thicknesses", self.thicknesses)
        radii = float_array("radii", self.radii)
        n = angles.size
        if thicknesses.size != n or radii.size != n:
            raise ValueError(
                "angles, thicknesses and radii must have the same length (one value per "
                f"voussoir), got {n}, {thicknesses.size} and {radii.size}"
            )
        if n < MIN_VOUSSOIRS:
            raise ValueError(
                f"voussoirs must be >= {MIN_VOUSSOIRS} for a four-hinge mechanism, got {n}"
            )
        _check_voussoir_count(n)
        if np.any(angles <= 0):
            raise ValueError(f"angles must all be > 0 [rad], got {angles.tolist()}")
        if np.any(thicknesses <= 0):
            raise ValueError(f"thicknesses must all be > 0 [m], got {thicknesses.tolist()}")
        if np.any(radii <= 0):
            raise ValueError(f"radii must all be > 0 [m], got {radii.tolist()}")
        outside = np.flatnonzero((radii < RADIUS_RANGE[0]) | (radii > RADIUS_RANGE[1]))
        if outside.size:
            raise ValueError(f"radii must be in [{RADIUS_RANGE[0]:g}, {RADIUS_RANGE[1]:g}] m "
                             f"(RADIUS_RANGE); voussoir {int(outside[0])} has "
                             f"{radii[outside[0]]:g} m")
        if np.any(thicknesses >= 2.0 * radii):
            bad = int(np.argmax(thicknesses >= 2.0 * radii))
            raise ValueError(
                "thickness must be < 2 x radius for every voussoir (the intrados radius must be "
                f"> 0); voussoir {bad} has thickness {thicknesses[bad]} m and radius {radii[bad]} m"
            )
        total = float(angles.sum())
        if total >= 2.0 * math.pi:
            raise ValueError(
                f"the angle of embrace (sum of angles) must be in (0, 360) degrees, got "
                f"{math.degrees(total):.6g} degrees"
            )
        density = check_density(self.density)
        for name, arr in (("angles", angles), ("thicknesses", thicknesses), ("radii", radii)):
            arr.setflags(write=False)
            object.__setattr__(self, name, arr)
        object.__setattr__(self, "start_angle", float(self.start_angle))
        object.__setattr__(self, "density", density)
        inner, outer = self.joint_extents()
        bad = np.flatnonzero(inner >= outer)
        if bad.size and bad[0] in (0, n):  # a springing: the voussoir itself has no extent
            v = 0 if bad[0] == 0 else n - 1
            raise ValueError(
                f"voussoir {v} has no radial extent in floating point: its thickness "
                f"{thicknesses[v]:g} m vanishes beside its radius {radii[v]:g} m"
            )
        if bad.size:
            j = int(bad[0])
            raise ValueError(
                f"adjacent voussoirs must touch at every joint: at joint {j} the radial extents of "
                f"voussoirs {j - 1} and {j} do not overlap (contact [{inner[j]:.6g}, "
                f"{outer[j]:.6g}] m is empty)"
            )

    # ------------------------------------------------------------------ constructors
    @classmethod
    def from_voussoirs(
        cls, angles, thicknesses, radii, *, start_angle: float | None = None,
        density: float = DEFAULT_DENSITY,
    ) -> CircularArch:
        """Arch from per-voussoir arrays, placed symmetric by default.

        Parameters
        ----------
        angles : array_like of float, shape (n,)
            Angle of embrace of every voussoir [rad], left to right.
        thicknesses : array_like of float, shape (n,)
            Thickness of every voussoir [m].
        radii : array_like of float, shape (n,)
            Mean radius of every voussoir [m].
        start_angle : float, optional
            Progressive angle of the left springing joint [rad]. Default
            ``(pi - sum(angles)) / 2``, so that the springings are at the same height, as for a
            surveyed arch given only by its voussoirs.
        density : float, default 2000
            Density of the masonry [kg/m^3].

        Returns
        -------
        CircularArch
        """
        angles_arr = float_array("angles", angles)
        if start_angle is None:
            start_angle = (math.pi - float(angles_arr.sum())) / 2.0
        return cls(angles_arr, thicknesses, radii, start_angle, density)

    @classmethod
    def from_dict(cls, data: dict, *, density: float = DEFAULT_DENSITY) -> CircularArch:
        """Arch from a mapping with keys ``angles`` [rad], ``thicknesses`` [m], ``radii`` [m].

        Parameters
        ----------
        data : dict
            ``{"angles": [...], "thicknesses": [...], "radii": [...]}``, lists of numbers, and
            optionally ``"start_angle"`` [rad] and ``"density"`` [kg/m^3]; no other key. Without
            a start angle the arch is placed symmetric (:meth:`from_voussoirs`).
        density : float, default 2000
            Density of the masonry [kg/m^3] when ``data`` has none.

        Returns
        -------
        CircularArch

        Raises
        ------
        ValueError
            When a key is missing or unknown, or a value is not a list of numbers.
        """
        if not isinstance(data, dict):
            raise ValueError(
                "geometry must be a JSON object with keys 'angles', 'thicknesses', 'radii', got "
                f"{type(data).__name__}"
            )
        missing = [key for key in ("angles", "thicknesses", "radii") if key not in data]
        if missing:
            raise ValueError(
                f"geometry is missing the key(s) {missing}; expected 'angles' [rad], "
                "'thicknesses' [m] and 'radii' [m]"
            )
        unknown = sorted(set(data) - {"angles", "thicknesses", "radii", "start_angle", "density"})
        if unknown:
            raise ValueError(
                f"geometry has unknown key(s) {unknown}; allowed: 'angles', 'thicknesses', "
                "'radii', 'start_angle', 'density'"
            )
        for key in ("angles", "thicknesses", "radii"):
            if not isinstance(data[key], list):
                raise ValueError(f"geometry key '{key}' must be a list of numbers")
            _check_voussoir_count(len(data[key]))
            for i, value in enumerate(data[key]):
                if not is_json_number(value):
                    raise ValueError(f"geometry key '{key}' item {i} is {json_text(value)}, "
                                     f"not a number")
        for key, unit in (("density", "kg/m^3"), ("start_angle", "rad")):
            if key in data and not is_json_number(data[key]):
                raise ValueError(f"geometry key '{key}' is {json_text(data[key])}, not a "
                                 f"number [{unit}]")
        return cls.from_voussoirs(
            data["angles"], data["thicknesses"], data["radii"],
            start_angle=data.get("start_angle"), density=data.get("density", density),
        )

    @classmethod
    def from_json(cls, path: str | Path, *, density: float = DEFAULT_DENSITY) -> CircularArch:
        """Arch from a JSON file ``{"angles": [...], "thicknesses": [...], "radii": [...]}``.

        The file is UTF-8 JSON (at most
        :data:`~archquake.geometry.blocks.MAX_GEOMETRY_FILE_BYTES`); every value is a JSON
        number (``true`` or ``"1.5"`` are refused, not converted), with an optional
        ``"density"`` [kg/m^3]. Every error names the file.

        Parameters
        ----------
        path : str or pathlib.Path
            The file: one JSON object as read by :meth:`from_dict` (angles [rad], thicknesses
            [m], radii [m]).
        density : float, default 2000
            Density of the masonry [kg/m^3] when the file gives none.

        Returns
        -------
        CircularArch

        Raises
        ------
        ValueError
            When the file cannot be read, is not valid JSON (the message gives the line) or does
            not describe an arch.
        """
        data = read_json_file(path, "a JSON object with 'angles' [rad], 'thicknesses' [m] "
                                    "and 'radii' [m]")
        where = f"geometry file {str(path)!r}"
        try:
            return cls.from_dict(data, density=density)
        except ValueError as exc:
            raise ValueError(f"{where}: {exc}") from exc

    def to_dict(self) -> dict:
        """The complete description of this arch, as read by :meth:`from_dict`:
        ``CircularArch.from_dict(arch.to_dict()) == arch``.

        Returns
        -------
        dict
            ``{"angles": [rad], "thicknesses": [m], "radii": [m], "start_angle": rad,
            "density": kg/m^3}``, lists of floats and floats.
        """
        return {
            "angles": self.angles.tolist(),
            "thicknesses": self.thicknesses.tolist(),
            "radii": self.radii.tolist(),
            "start_angle": self.start_angle,
            "density": self.density,
        }

    # ------------------------------------------------------------------ basic geometry
    @property
    def n_voussoirs(self) -> int:
        """Number of voussoirs n [-]."""
        return int(self.angles.size)

    @property
    def embrace(self) -> float:
        """Angle of embrace alpha of the whole arch [rad]."""
        return float(self.angles.sum())

    @property
    def joint_angles(self) -> np.ndarray:
        """Progressive angle beta_j of every joint j = 0..n [rad]."""
        return self.start_angle + np.concatenate(([0.0], np.cumsum(self.angles)))

    @property
    def inner_radii(self) -> np.ndarray:
        """Intrados radius R_i - t_i/2 of every voussoir [m]."""
        return self.radii - 0.5 * self.thicknesses

    @property
    def outer_radii(self) -> np.ndarray:
        """Extrados radius R_i + t_i/2 of every voussoir [m]."""
        return self.radii + 0.5 * self.thicknesses

    def joint_extents(self) -> tuple[np.ndarray, np.ndarray]:
        """Radial extent of the contact at every joint j = 0..n [m].

        An inner joint is the overlap of the radial extents of the two voussoirs it separates
        ``[max(r_in), min(r_out)]``; a springing joint is its voussoir's own extent.

        Returns
        -------
        inner, outer : ndarray, shape (n+1,)
            Radius of the intrados and of the extrados edge of every joint's contact [m].
        """
        ri, ro = self.inner_radii, self.outer_radii
        inner = np.concatenate(([ri[0]], np.maximum(ri[:-1], ri[1:]), [ri[-1]]))
        outer = np.concatenate(([ro[0]], np.minimum(ro[:-1], ro[1:]), [ro[-1]]))
        return inner, outer

    def is_symmetric(self, atol: float = 1e-12) -> bool:
        """True when the arch equals its mirror image about the vertical axis.

        Parameters
        ----------
        atol : float, default 1e-12
            Absolute tolerance on every angle [rad], thickness and radius [m].
        """
        m = self.mirrored()
        return bool(
            np.allclose(self.angles, m.angles, atol=atol, rtol=0)
            and np.allclose(self.thicknesses, m.thicknesses, atol=atol, rtol=0)
            and np.allclose(self.radii, m.radii, atol=atol, rtol=0)
            and abs(self.start_angle - m.start_angle) <= atol
        )

    def mirrored(self) -> CircularArch:
        """The arch mirrored about the vertical axis x = 0.

        Voussoir i of the mirror is voussoir n-1-i of this arch; the mirror's left springing is
        at ``beta_0' = pi - beta_n``.
        """
        return CircularArch(
            self.angles[::-1].copy(), self.thicknesses[::-1].copy(), self.radii[::-1].copy(),
            math.pi - float(self.joint_angles[-1]), self.density,
        )

    @staticmethod
    def point(radius, beta) -> np.ndarray:
        r"""Cartesian point(s) at ``radius`` on the radial line of progressive angle ``beta``.

        Parameters
        ----------
        radius : float or array_like
            Distance from the centre O [m].
        beta : float or array_like
            Progressive angle [rad], broadcast against ``radius``.

        Returns
        -------
        ndarray, shape (..., 2)
            :math:`(x, y) = (-r \cos\beta,\ r \sin\beta)` [m].
        """
        radius = np.asarray(radius, dtype=float)
        beta = np.asarray(beta, dtype=float)
        return np.stack((-radius * np.cos(beta), radius * np.sin(beta)), axis=-1)

    # ------------------------------------------------------------------ the contract
    def _mass_properties(self):
        r"""Closed forms of the annular sectors: area :math:`\alpha_i (r_2^2 - r_1^2)/2`,
        centroid at :math:`\frac{2}{3}\frac{r_2^3 - r_1^3}{r_2^2 - r_1^2}
        \frac{\sin(\alpha_i/2)}{\alpha_i/2}` from O on the voussoir's mid-line, polar moment
        about O :math:`\rho\,\alpha_i (r_2^4 - r_1^4)/4`, moved to the centroid by the
        parallel-axis theorem."""
        ri, ro, a = self.inner_radii, self.outer_radii, self.angles
        area = 0.5 * a * (ro**2 - ri**2)
        mass = self.density * area
        # distance of the centroid of an annular sector from the centre O
        dist = (2.0 / 3.0) * (ro**3 - ri**3) / (ro**2 - ri**2) * np.sin(a / 2) / (a / 2)
        mid = self.joint_angles[:-1] + a / 2
        centroid = self.point(dist, mid)
        polar_o = self.density * a / 4.0 * (ro**4 - ri**4)  # about O
        return mass, centroid, polar_o - mass * dist**2

    def _joints(self) -> np.ndarray:
        """The radial joints: intrados end at the inner radius of the contact, extrados end at
        its outer radius (:meth:`joint_extents`)."""
        inner, outer = self.joint_extents()
        beta = self.joint_angles
        return np.stack((self.point(inner, beta), self.point(outer, beta)), axis=1)

    @property
    def reference_point(self) -> np.ndarray:
        """The centre O (the origin) [m]: the limit analysis takes moments about it."""
        return np.zeros(2)

    @property
    def length_scale(self) -> float:
        """The mean radius [m] (the unit of the limit analysis)."""
        return float(np.mean(self.radii))

    @property
    def thickness_scale(self) -> float:
        """Mean thickness of the voussoirs [m]."""
        return float(np.mean(self.thicknesses))

    def crown(self) -> tuple[int, np.ndarray]:
        """The top of the extrados: the point at progressive angle pi/2 on the extrados of the
        voussoir that holds it (or at the nearest joint if the arch does not reach it) [m]."""
        beta = self.joint_angles
        n = self.n_voussoirs
        top = float(np.clip(0.5 * math.pi, beta[0], beta[-1]))
        block = int(np.clip(np.searchsorted(beta, top, side="right") - 1, 0, n - 1))
        return block, self.point(self.outer_radii[block], top)

    def perturbed(self, epsilon: float, draws: np.ndarray) -> CircularArch:
        r"""The irregular arch of eq. (1) of [1]_ for given uniform draws.

        For every voussoir :math:`i`:

        .. math::

            \tilde\alpha_i = \alpha_i \left(1 + \varepsilon\, \tilde p_{\alpha_i}\right),
            \qquad
            \tilde t_i = t_i \left(1 + \varepsilon\, \tilde p_{t_i}\right),
            \qquad
            \tilde R_i = R_i \left(1 + \chi_i\, \tilde p_{R_i}\right),
            \qquad
            \chi_i = \varepsilon\, t_i / R_i,

        the angles then rescaled by a common factor so that they sum to this arch's embrace;
        the left springing angle :math:`\beta_0` is kept, so both springings stay where they
        were.

        Parameters
        ----------
        epsilon : float
            :math:`\varepsilon` [-].
        draws : ndarray, shape (3, n)
            :math:`\tilde p` in [-1, 1]: row 0 angles, row 1 thicknesses, row 2 radii.

        Returns
        -------
        CircularArch

        References
        ----------
        .. [1] The paper, Sect. 2, eq. (1) and Fig. 1b-c.
        """
        eps, p = float(epsilon), np.asarray(draws, dtype=float)
        angles = self.angles * (1.0 + eps * p[0])
        angles *= self.embrace / angles.sum()
        thicknesses = self.thicknesses * (1.0 + eps * p[1])
        chi = eps * self.thicknesses / self.radii
        radii = self.radii * (1.0 + chi * p[2])
        return CircularArch(angles, thicknesses, radii, self.start_angle, self.density)

    def extrados(self, i: int) -> list:
        """The extrados of voussoir ``i``: one :class:`~archquake.geometry.mass.Arc` of radius
        :math:`R_i + t_i/2` about O, from its left end to its right end [m]."""
        b0, b1 = self.joint_angles[i], self.joint_angles[i + 1]
        return [Arc((0.0, 0.0), float(self.outer_radii[i]), math.pi - b0, math.pi - b1)]

    def outline(self, i: int, points: int = 24) -> np.ndarray:
        """Closed polygon of voussoir ``i``'s outline, for drawing.

        Parameters
        ----------
        i : int
            Voussoir index, ``0 .. n-1``.
        points : int, default 24
            Points on each of the two arcs.

        Returns
        -------
        ndarray, shape (2 points + 1, 2)
            Vertices (x, y) [m], the first repeated at the end.
        """
        b0, b1 = self.joint_angles[i], self.joint_angles[i + 1]
        b = np.linspace(b0, b1, points)
        outer = self.point(self.outer_radii[i], b)
        inner = self.point(self.inner_radii[i], b[::-1])
        return np.vstack((outer, inner, outer[:1]))


def circular_arch(
    radius: float, embrace: float, thickness: float, voussoirs: int,
    *, density: float = DEFAULT_DENSITY,
) -> CircularArch:
    r"""Nominal circular arch with equal voussoirs and radial joints, symmetric about x = 0.

    Every voussoir has the angle :math:`\alpha / n`, the thickness :math:`t` and the mean radius
    :math:`R`; the left springing is at :math:`\beta_0 = (\pi - \alpha)/2` (Fig. 1a of [1]_).

    Parameters
    ----------
    radius : float
        Mean radius :math:`R` [m].
    embrace : float
        Angle of embrace :math:`\alpha` [rad], in :math:`(0, 2\pi)`.
    thickness : float
        Thickness :math:`t` [m], in :math:`(0, 2R)`.
    voussoirs : int
        Number of voussoirs :math:`n` [-], from 4 to :data:`MAX_VOUSSOIRS`.
    density : float, default 2000
        Density of the masonry [kg/m^3].

    Returns
    -------
    CircularArch

    Raises
    ------
    ValueError
        When a parameter is out of its range (the message names it and the range).

    See Also
    --------
    archquake.reference_arches.oppenheim : the paper's nominal arch.

    References
    ----------
    .. [1] The paper, Sect. 2 and Fig. 1a.

    Examples
    --------
    Oppenheim's arch (R = 10 m, 157.5 degrees, t = 1.5 m, n = 7):

    >>> import math
    >>> arch = circular_arch(10.0, math.radians(157.5), 1.5, 7)
    >>> arch.n_voussoirs, round(math.degrees(arch.embrace), 6)
    (7, 157.5)
    """
    radius = _check_positive("radius", radius, "m")
    thickness = _check_positive("thickness", thickness, "m")
    embrace = _check_positive("embrace", embrace, "rad")
    if embrace >= 2.0 * math.pi:
        raise ValueError(
            f"embrace must be in (0, 360) degrees, got {math.degrees(embrace):.6g} degrees"
        )
    if thickness >= 2.0 * radius:
        raise ValueError(
            f"thickness must be < 2 x radius = {2 * radius} m, got {thickness} m"
        )
    n = check_voussoir_count(voussoirs)
    if not embrace / n > 0.0:
        raise ValueError(f"embrace must give each of the {n} voussoirs an angle > 0, got "
                         f"{embrace!r} rad")
    return CircularArch(
        np.full(n, embrace / n), np.full(n, thickness), np.full(n, radius),
        (math.pi - embrace) / 2.0, density,
    )
