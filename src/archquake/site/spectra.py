r"""Elastic response spectra of the horizontal ground acceleration at a site: NTC 2018, EN 1998-1
and a spectrum of the user's, and the Italian hazard of the national grid.

One value, :class:`ElasticSpectrum`, answers ``acceleration(period)`` (``Se`` [g]) and
``displacement(period)`` (``SDe`` [m]) whichever way it was made:

:func:`ntc2018_spectrum`
    Italian building code, NTC 2018 [1]_ §3.2.3.2.1 (eqs. 3.2.2-3.2.7) and §3.2.3.2.3
    (displacement); the national-grid parameters ``(ag, F0, Tc*)`` of a site at the nine return
    periods of its Annex A are :class:`NtcSiteHazard` (:func:`read_ntc_site`), and the return
    period of a limit state is :func:`return_period` (§2.4, §3.2.1).
:func:`ec8_spectrum`
    EN 1998-1:2004 [2]_ §3.2.2.2 (eqs. 3.2-3.6, Tables 3.2 and 3.3) and its Annex A for the
    displacement at long periods.
:func:`user_spectrum`, :func:`read_spectrum`
    a table of ``(T, Se)``, interpolated linearly; refused outside its periods.

The code spectra
----------------
Both codes share one shape. With :math:`a_g` the ground acceleration on rock [g], :math:`S` the
soil (and, for NTC, topography) factor, :math:`\eta` the damping correction, :math:`F_0` the
plateau amplification (NTC; 2.5 in EN 1998-1) and the corner periods
:math:`T_B < T_C < T_D`:

.. math::

   S_e(T) = \begin{cases}
     a_g S \left[1 + \dfrac{T}{T_B} (\eta F_0 - 1)\right] & 0 \le T < T_B \\
     a_g S \eta F_0 & T_B \le T < T_C \\
     a_g S \eta F_0 \dfrac{T_C}{T} & T_C \le T < T_D \\
     a_g S \eta F_0 \dfrac{T_C T_D}{T^2} & T_D \le T
   \end{cases}
   \qquad \eta = \sqrt{\frac{10}{5 + \xi}} \ge 0.55

(NTC 2018 eqs. 3.2.2 and 3.2.4, whose first branch
:math:`\eta F_0 [T/T_B + (1 - T/T_B)/(\eta F_0)]` is the one above; EN 1998-1 eqs. 3.2-3.6),
:math:`\xi` the viscous damping [%]. NTC 2018 (Table 3.2.IV, eqs. 3.2.3, 3.2.5-3.2.7):
:math:`S = S_S S_T`, :math:`T_C = C_C T_C^*`, :math:`T_B = T_C / 3`,
:math:`T_D = 4.0\, a_g / g + 1.6` s, with :math:`S_S` and :math:`C_C` of the soil category
(A-E) and :math:`S_T` of the topographic category (T1-T4, Table 3.2.V). EN 1998-1:
:math:`a_g = \gamma_I a_{gR}` and :math:`S, T_B, T_C, T_D` of Table 3.2 (type 1) or 3.3 (type 2).

The displacement spectrum is the pseudo-spectral one up to :math:`T_E`, then goes linearly to
the ground displacement :math:`d_g` at :math:`T_F` and stays there (NTC 2018 §3.2.3.2.3 with
Table 3.2.VIII; EN 1998-1 eq. 3.7, Annex A eqs. A.1-A.2 with Table A.1 and eq. 3.12):

.. math::

   S_{De}(T) = \begin{cases}
     S_e(T)\, g\, (T / 2\pi)^2 & T \le T_E \\
     0.025\, a_g g\, S T_C T_D \left[F_0 \eta + (1 - F_0 \eta)
       \dfrac{T - T_E}{T_F - T_E}\right] & T_E < T \le T_F \\
     d_g = 0.025\, a_g g\, S T_C T_D & T_F < T
   \end{cases}

The codes' 0.025 is :math:`1/(2\pi)^2 = 0.02533` rounded, so :math:`S_{De}` steps down by 1.3 %
at :math:`T_E`, as the codes write it. EN 1998-1 defines :math:`S_e` up to 4 s and its Annex A
(informative) the displacement beyond; here :math:`S_e` beyond 4 s continues the
:math:`T_C T_D / T^2` branch (the pseudo-acceleration of Annex A's displacement up to
:math:`T_E`).

A user spectrum
---------------
A table of periods [s] and :math:`S_e` [g] (:func:`read_spectrum`), interpolated linearly and
refused outside its first and last period; :math:`S_{De} = S_e\, g\, (T / 2\pi)^2`.

The national grid (NTC 2018 Annex A)
------------------------------------
The hazard at a site is ``(ag, F0, Tc*)`` at the return periods 30, 50, 72, 101, 140, 201, 475,
975 and 2475 years; between two of them, each parameter :math:`p` is interpolated in
log-log [1]_ (Annex A):

.. math::

   \log p = \log p_1 + \log\left(\frac{p_2}{p_1}\right)
            \frac{\log(T_R / T_{R1})}{\log(T_{R2} / T_{R1})}

Return periods outside the table are refused (no extrapolation). The return period of a limit
state (§2.4, §3.2.1) is :math:`T_R = -V_R / \ln(1 - P_{V_R})` with :math:`V_R = V_N C_U \ge 35`
years, :math:`C_U` = 0.7, 1.0, 1.5, 2.0 for use classes I-IV and :math:`P_{V_R}` = 81, 63, 10,
5 % for SLO, SLD, SLV, SLC (Table 3.2.I).

References
----------
.. [1] Ministero delle Infrastrutture e dei Trasporti (2018). Aggiornamento delle "Norme tecniche
   per le costruzioni" (NTC 2018), D.M. 17 gennaio 2018, G.U. n. 42, 20 febbraio 2018: §2.4,
   §3.2 and Allegato A (from NTC 2008, D.M. 14 gennaio 2008).
.. [2] CEN (2004). EN 1998-1:2004 Eurocode 8: Design of structures for earthquake resistance,
   Part 1: General rules, seismic actions and rules for buildings, §3.2.2 and Annex A.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..constants import GRAVITY
from ..ranges import number

MIN_ETA = 0.55
"""Lower bound of the damping correction factor eta [-] (NTC 2018 eq. 3.2.4, EN 1998-1 eq. 3.6)."""
MAX_AG_G = 1.5
"""Largest ground acceleration accepted [g]: a larger one is taken for a value in m/s^2."""
F0_RANGE = (2.0, 3.5)
"""Accepted range of NTC's F0 [-] (the national grid's values lie in about [2.2, 3.0])."""
MAX_TC_STAR = 1.0
"""Largest NTC Tc* accepted [s] (the national grid's values lie below 0.6 s)."""
MAX_DAMPING = 30.0
"""Largest viscous damping accepted [%]."""

NTC_SOILS = {
    # soil: (S_S = clip(a - b F0 ag, low, high), C_C = c Tc*^e), NTC 2018 Table 3.2.IV
    "A": ((1.00, 0.00, 1.00, 1.00), (1.00, 0.00)),
    "B": ((1.40, 0.40, 1.00, 1.20), (1.10, -0.20)),
    "C": ((1.70, 0.60, 1.00, 1.50), (1.05, -0.33)),
    "D": ((2.40, 1.50, 0.90, 1.80), (1.25, -0.50)),
    "E": ((2.00, 1.10, 1.00, 1.60), (1.15, -0.40)),
}
"""NTC 2018 Table 3.2.IV: soil category -> ((a, b, low, high) of
``S_S = min(max(a - b F0 ag/g, low), high)``, (c, e) of ``C_C = c Tc*^e``)."""
NTC_TOPOGRAPHY = {"T1": 1.0, "T2": 1.2, "T3": 1.2, "T4": 1.4}
"""NTC 2018 Table 3.2.V: topographic category -> S_T at the top of the slope or ridge [-]."""
NTC_DISPLACEMENT_CORNERS = {"A": (4.5, 10.0), "B": (5.0, 10.0), "C": (6.0, 10.0),
                            "D": (6.0, 10.0), "E": (6.0, 10.0)}
"""NTC 2018 Table 3.2.VIII (and EN 1998-1 Table A.1): soil -> (T_E, T_F) [s]."""
EC8_SOILS = {
    # spectrum type -> soil -> (S, T_B, T_C, T_D), EN 1998-1 Tables 3.2 and 3.3
    1: {"A": (1.0, 0.15, 0.4, 2.0), "B": (1.2, 0.15, 0.5, 2.0), "C": (1.15, 0.20, 0.6, 2.0),
        "D": (1.35, 0.20, 0.8, 2.0), "E": (1.4, 0.15, 0.5, 2.0)},
    2: {"A": (1.0, 0.05, 0.25, 1.2), "B": (1.35, 0.05, 0.25, 1.2), "C": (1.5, 0.10, 0.25, 1.2),
        "D": (1.8, 0.10, 0.30, 1.2), "E": (1.6, 0.05, 0.25, 1.2)},
}
"""EN 1998-1 Tables 3.2 (type 1) and 3.3 (type 2): type -> soil -> (S, T_B [s], T_C [s],
T_D [s])."""
EC8_PLATEAU = 2.5
"""EN 1998-1's spectral amplification on the plateau (NTC's F0) [-]."""
DISPLACEMENT_FACTOR = 0.025
"""The codes' factor of the ground displacement d_g = 0.025 ag S T_C T_D (NTC 2018 §3.2.3.2.3,
EN 1998-1 eq. 3.12) [-]."""

NTC_RETURN_PERIODS = (30.0, 50.0, 72.0, 101.0, 140.0, 201.0, 475.0, 975.0, 2475.0)
"""Return periods of the national grid's parameters, NTC 2018 Annex A [years]."""
USE_CLASSES = {"I": 0.7, "II": 1.0, "III": 1.5, "IV": 2.0}
"""NTC 2018 §2.4.3: use class -> coefficient C_U [-]."""
LIMIT_STATES = {"SLO": 0.81, "SLD": 0.63, "SLV": 0.10, "SLC": 0.05}
"""NTC 2018 Table 3.2.I: limit state -> probability of exceedance P_VR in the reference
period [-]."""
MIN_REFERENCE_PERIOD = 35.0
"""NTC 2018 §2.4.3: the reference period V_R is at least 35 years."""


def _number(name: str, value, unit: str, low: float | None = None, high: float | None = None,
            *, low_open: bool = False, hint: str = "") -> float:
    """``value`` as a finite float in ``[low, high]`` (``(low, high]`` if ``low_open``), or a
    ValueError naming ``name``, the range and the unit."""
    try:
        if isinstance(value, bool):
            raise TypeError
        out = number(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number [{unit}], got {value!r}") from None
    left = "(" if low_open else "["
    span = (f" in {left}{low:g}, {high:g}]" if low is not None and high is not None
            else f" > {low:g}" if low is not None else "")
    bad = (not math.isfinite(out)
           or (low is not None and (out <= low if low_open else out < low))
           or (high is not None and out > high))
    if bad:
        raise ValueError(f"{name} must be a finite number{span} [{unit}], got {value!r}{hint}")
    return out


def _choice(name: str, value, options) -> str:
    key = str(value).strip().upper()
    if key not in options:
        raise ValueError(f"{name} must be one of {', '.join(options)}, got {value!r}")
    return key


def damping_correction(damping: float) -> float:
    r"""Damping correction factor :math:`\eta = \sqrt{10 / (5 + \xi)} \ge 0.55` [-].

    Parameters
    ----------
    damping : float
        Viscous damping ratio :math:`\xi` [%], in (0, 30].

    Returns
    -------
    float

    References
    ----------
    NTC 2018 eq. 3.2.4; EN 1998-1 eq. 3.6.

    Examples
    --------
    >>> damping_correction(5.0)
    1.0
    """
    xi = _number("damping", damping, "%", 0.0, MAX_DAMPING, low_open=True)
    return max(math.sqrt(10.0 / (5.0 + xi)), MIN_ETA)


def _periods(period) -> np.ndarray:
    try:
        t = None if isinstance(period, str) else np.asarray(period, dtype=float)
    except (TypeError, ValueError):
        t = None
    if t is None:
        raise ValueError(f"period must be a number or an array of numbers [s], got {period!r}")
    if not np.all(np.isfinite(t)) or np.any(t < 0.0):
        bad = t[~(np.isfinite(t) & (t >= 0.0))].ravel()[0]
        raise ValueError(f"period must be finite and >= 0 [s], got {float(bad)!r}")
    return t


def _out(value: np.ndarray, period):
    return float(value) if np.ndim(period) == 0 else value


@dataclass(frozen=True)
class ElasticSpectrum:
    """An elastic response spectrum of the horizontal ground acceleration at a site.

    Made by :func:`ntc2018_spectrum`, :func:`ec8_spectrum`, :func:`user_spectrum` or
    :func:`read_spectrum`; the formulas are those of the module docstring. For a code spectrum
    every corner parameter is set and ``periods``/``accelerations`` are ``None``; for a user
    spectrum the reverse.

    Attributes
    ----------
    code : str
        What the spectrum is: ``"NTC 2018"``, ``"EN 1998-1:2004"`` or ``"user file <name>"``.
    ag : float or None
        Ground acceleration on rock a_g [g] (EN 1998-1: ``gamma_I a_gR``).
    f0 : float or None
        Plateau amplification F0 [-] (2.5 for EN 1998-1).
    s : float or None
        Soil (times topography, for NTC) factor S [-].
    eta : float or None
        Damping correction factor [-].
    damping : float or None
        Viscous damping [%].
    t_b, t_c, t_d, t_e, t_f : float or None
        Corner periods [s] (``t_e``, ``t_f`` of the displacement spectrum).
    soil : str or None
        Soil category (A-E).
    details : tuple of (str, object)
        The code's other inputs (``tc_star``, ``topography``, ``s_s``, ``s_t``, ``c_c``,
        ``spectrum_type``, ``importance``, ``agr``), for the record.
    periods, accelerations : tuple of float or None
        The table of a user spectrum: periods [s], strictly increasing, and Se [g].
    """

    code: str
    ag: float | None = None
    f0: float | None = None
    s: float | None = None
    eta: float | None = None
    damping: float | None = None
    t_b: float | None = None
    t_c: float | None = None
    t_d: float | None = None
    t_e: float | None = None
    t_f: float | None = None
    soil: str | None = None
    details: tuple = ()
    periods: tuple | None = None
    accelerations: tuple | None = None

    def __post_init__(self):
        if self.is_table:
            t, sa = _check_table(self.periods, self.accelerations)
            object.__setattr__(self, "periods", t)
            object.__setattr__(self, "accelerations", sa)
            return
        corners = (self.t_b, self.t_c, self.t_d, self.t_e, self.t_f)
        factors = (self.ag, self.f0, self.s, self.eta)
        if any(v is None for v in corners + factors):
            raise ValueError("an ElasticSpectrum needs ag, f0, s, eta and the corner periods "
                             "t_b, t_c, t_d, t_e, t_f, or periods and accelerations; make one "
                             "with ntc2018_spectrum, ec8_spectrum or user_spectrum")
        if not all(math.isfinite(v) and v > 0 for v in corners + factors):
            raise ValueError("ag, f0, s, eta and the corner periods must be finite and > 0")
        if not (self.t_b < self.t_c <= self.t_d and self.t_e < self.t_f):
            raise ValueError(f"the corner periods must be ordered t_b < t_c <= t_d and "
                             f"t_e < t_f [s], got {corners}")

    @property
    def is_table(self) -> bool:
        """Whether the spectrum is a user's table (else a code's formula)."""
        return self.periods is not None

    @property
    def pga(self) -> float:
        """Peak ground acceleration Se(0) [g] (``a_g S`` for the codes).

        Raises
        ------
        ValueError
            For a table that does not start at period 0.
        """
        if self.is_table and self.periods[0] > 0.0:
            raise ValueError(f"the spectrum of {self.code} starts at T = {self.periods[0]:g} s: "
                             "its PGA (Se at T = 0) is not tabulated; add a row for period 0")
        return float(self.acceleration(0.0))

    @property
    def ground_displacement(self) -> float | None:
        """d_g = 0.025 a_g g S T_C T_D [m] of a code spectrum (``None`` for a table)."""
        if self.is_table:
            return None
        return DISPLACEMENT_FACTOR * self.ag * GRAVITY * self.s * self.t_c * self.t_d

    def acceleration(self, period):
        """Spectral acceleration Se [g] at ``period`` [s].

        Parameters
        ----------
        period : float or array_like
            Periods [s], finite and >= 0 (and within the table of a user spectrum).

        Returns
        -------
        float or ndarray
            Se [g], a float for a scalar period.

        Raises
        ------
        ValueError
            For a negative or non-finite period, or one outside a user table.
        """
        t = _periods(period)
        if self.is_table:
            first, last = self.periods[0], self.periods[-1]
            outside = (t < first) | (t > last)
            if np.any(outside):
                raise ValueError(f"period {t[outside].ravel()[0]:g} s is outside the spectrum "
                                 f"of {self.code}, tabulated from {first:g} to {last:g} s")
            return _out(np.interp(t, self.periods, self.accelerations), period)
        top = self.ag * self.s * self.eta * self.f0
        with np.errstate(divide="ignore", invalid="ignore"):
            se = np.where(
                t < self.t_b, self.ag * self.s * (1.0 + t / self.t_b * (self.eta * self.f0 - 1.0)),
                np.where(t < self.t_c, top,
                         np.where(t < self.t_d, top * self.t_c / t,
                                  top * self.t_c * self.t_d / np.maximum(t, self.t_d) ** 2)))
        return _out(se, period)

    def displacement(self, period):
        """Spectral displacement SDe [m] at ``period`` [s] (module docstring).

        Parameters
        ----------
        period : float or array_like
            Periods [s], finite and >= 0.

        Returns
        -------
        float or ndarray
            SDe [m], a float for a scalar period.
        """
        t = _periods(period)
        sde = np.asarray(self.acceleration(t)) * GRAVITY * (t / (2.0 * math.pi)) ** 2
        if not self.is_table:
            dg = self.ground_displacement
            ramp = (self.f0 * self.eta + (1.0 - self.f0 * self.eta)
                    * (t - self.t_e) / (self.t_f - self.t_e))
            sde = np.where(t <= self.t_e, sde, np.where(t <= self.t_f, dg * ramp, dg))
        return _out(sde, period)

    def to_dict(self) -> dict:
        """The spectrum as plain values for JSON: code, PGA and parameters, or the table."""
        out: dict = {"code": self.code}
        if self.is_table:
            out["periods"] = list(self.periods)
            out["accelerations"] = list(self.accelerations)
            out["pga"] = self.pga if self.periods[0] == 0.0 else None
            return out
        out.update(pga=self.pga, ag=self.ag, f0=self.f0, s=self.s, eta=self.eta,
                   damping=self.damping, t_b=self.t_b, t_c=self.t_c, t_d=self.t_d,
                   t_e=self.t_e, t_f=self.t_f, ground_displacement=self.ground_displacement,
                   soil=self.soil)
        out.update(dict(self.details))
        return out


def _check_ag(name: str, ag) -> float:
    return _number(name, ag, "g", 0.0, MAX_AG_G, low_open=True,
                   hint=" (in g, not m/s^2: 0.25 g is 2.45 m/s^2)")


def ntc_soil_factors(soil: str, ag: float, f0: float, tc_star: float) -> tuple[float, float]:
    """NTC 2018 Table 3.2.IV: the stratigraphic amplification S_S and C_C of a soil category.

    Parameters
    ----------
    soil : str
        Soil category, A-E.
    ag : float
        Ground acceleration on rock [g].
    f0 : float
        Plateau amplification F0 [-].
    tc_star : float
        Tc* [s].

    Returns
    -------
    (float, float)
        ``(S_S, C_C)`` [-].

    Examples
    --------
    >>> ntc_soil_factors("C", 0.25, 2.4, 0.3)[0]  # 1.70 - 0.60 * 2.4 * 0.25
    1.34
    """
    (a, b, low, high), (c, e) = NTC_SOILS[_choice("soil", soil, NTC_SOILS)]
    s_s = round(min(max(a - b * f0 * ag, low), high), 12)
    return s_s, c * tc_star ** e


def ntc2018_spectrum(ag: float, f0: float, tc_star: float, soil: str = "A",
                     topography: str = "T1", damping: float = 5.0, *,
                     topography_ratio: float | None = None) -> ElasticSpectrum:
    r"""The elastic spectrum of NTC 2018 §3.2.3.2.1 (horizontal) and §3.2.3.2.3 (displacement).

    Parameters
    ----------
    ag : float
        Ground acceleration on horizontal rock a_g [g], in (0, 1.5].
    f0 : float
        Maximum spectral amplification F0 [-], in [2.0, 3.5].
    tc_star : float
        Tc*, the period at the start of the plateau's velocity branch on rock [s], in (0, 1].
    soil : str
        Soil category A-E (NTC 2018 §3.2.2, Table 3.2.II).
    topography : str
        Topographic category T1-T4 (Table 3.2.III).
    damping : float
        Viscous damping xi [%], in (0, 30].
    topography_ratio : float, optional
        Height of the site above the base of the slope or ridge over the slope's height, in
        [0, 1]: S_T falls linearly from its value at the top (ratio 1, the default) to 1 at the
        base (ratio 0), Table 3.2.V's note.

    Returns
    -------
    ElasticSpectrum
        With :math:`S = S_S S_T`, :math:`T_C = C_C T_C^*`, :math:`T_B = T_C / 3`,
        :math:`T_D = 4 a_g/g + 1.6` s, :math:`T_E, T_F` of Table 3.2.VIII.

    Raises
    ------
    ValueError
        Naming the parameter and its range (a ground acceleration above 1.5 g is taken for a
        value in m/s^2).

    References
    ----------
    NTC 2018 eqs. 3.2.2-3.2.7, Tables 3.2.IV, 3.2.V and 3.2.VIII, §3.2.3.2.3.

    Examples
    --------
    >>> sp = ntc2018_spectrum(0.25, 2.4, 0.3, soil="C")
    >>> round(sp.s, 4), round(sp.t_d, 4)   # S_S = 1.70 - 0.6 * 2.4 * 0.25; T_D = 4 * 0.25 + 1.6
    (1.34, 2.6)
    """
    ag = _check_ag("ag", ag)
    f0 = _number("f0", f0, "-", *F0_RANGE)
    tc_star = _number("tc_star", tc_star, "s", 0.0, MAX_TC_STAR, low_open=True)
    soil = _choice("soil", soil, NTC_SOILS)
    topography = _choice("topography", topography, NTC_TOPOGRAPHY)
    eta = damping_correction(damping)
    s_t_top = NTC_TOPOGRAPHY[topography]
    if topography_ratio is None:
        s_t = s_t_top
    else:
        ratio = _number("topography_ratio", topography_ratio, "-", 0.0, 1.0)
        s_t = 1.0 + (s_t_top - 1.0) * ratio
    s_s, c_c = ntc_soil_factors(soil, ag, f0, tc_star)
    t_c = c_c * tc_star
    t_e, t_f = NTC_DISPLACEMENT_CORNERS[soil]
    details = (("tc_star", tc_star), ("topography", topography), ("topography_ratio",
               topography_ratio), ("s_s", s_s), ("s_t", s_t), ("c_c", c_c))
    return ElasticSpectrum(code="NTC 2018", ag=ag, f0=f0, s=s_s * s_t, eta=eta,
                           damping=float(damping), t_b=t_c / 3.0, t_c=t_c,
                           t_d=4.0 * ag + 1.6, t_e=t_e, t_f=t_f, soil=soil, details=details)


def ec8_spectrum(agr: float, spectrum_type: int = 1, soil: str = "A", importance: float = 1.0,
                 damping: float = 5.0) -> ElasticSpectrum:
    r"""The elastic spectrum of EN 1998-1:2004 §3.2.2.2 (Type 1 or 2), with Annex A's
    displacement at long periods.

    Parameters
    ----------
    agr : float
        Reference peak ground acceleration on type A ground a_gR [g], in (0, 1.5].
    spectrum_type : int
        1 (Table 3.2, large earthquakes) or 2 (Table 3.3, Ms <= 5.5).
    soil : str
        Ground type A-E (Table 3.1).
    importance : float
        Importance factor gamma_I [-], in (0, 2]; ``a_g = gamma_I a_gR``.
    damping : float
        Viscous damping xi [%], in (0, 30].

    Returns
    -------
    ElasticSpectrum
        F0 = 2.5; T_E, T_F of Annex A Table A.1.

    References
    ----------
    EN 1998-1:2004 eqs. 3.2-3.7, 3.12, Tables 3.2, 3.3; Annex A eqs. A.1-A.2, Table A.1.

    Examples
    --------
    >>> sp = ec8_spectrum(0.2, 1, "B")
    >>> round(sp.acceleration(0.3), 6)  # plateau: 2.5 * 0.2 * 1.2
    0.6
    """
    agr = _check_ag("agr", agr)
    importance = _number("importance", importance, "-", 0.0, 2.0, low_open=True)
    try:
        kind = int(spectrum_type)
        if kind != spectrum_type or isinstance(spectrum_type, bool):
            raise ValueError
    except (TypeError, ValueError):
        kind = None
    if kind not in EC8_SOILS:
        raise ValueError(f"spectrum_type must be 1 or 2, got {spectrum_type!r}")
    soil = _choice("soil", soil, EC8_SOILS[kind])
    eta = damping_correction(damping)
    s, t_b, t_c, t_d = EC8_SOILS[kind][soil]
    t_e, t_f = NTC_DISPLACEMENT_CORNERS[soil]
    ag = _check_ag("ag = importance * agr", importance * agr)
    details = (("agr", agr), ("importance", importance), ("spectrum_type", kind))
    return ElasticSpectrum(code="EN 1998-1:2004", ag=ag, f0=EC8_PLATEAU, s=s, eta=eta,
                           damping=float(damping), t_b=t_b, t_c=t_c, t_d=t_d, t_e=t_e,
                           t_f=t_f, soil=soil, details=details)


def _check_table(periods, accelerations) -> tuple[tuple, tuple]:
    """The table of a user spectrum as two tuples of floats, or a ValueError saying what is
    wrong with it."""
    try:
        t = np.asarray(periods, dtype=float)
        sa = np.asarray(accelerations, dtype=float)
    except (TypeError, ValueError):
        raise ValueError("periods and accelerations must be numbers") from None
    if t.ndim != 1 or sa.shape != t.shape:
        raise ValueError(f"periods and accelerations must be two lists of the same length, got "
                         f"shapes {t.shape} and {sa.shape}")
    if len(t) < 2:
        raise ValueError(f"a spectrum needs at least two rows (periods), got {len(t)}")
    if not np.all(np.isfinite(t)) or np.any(t < 0.0):
        raise ValueError("periods must be finite and >= 0 [s]")
    if np.any(np.diff(t) <= 0.0):
        i = int(np.nonzero(np.diff(t) <= 0.0)[0][0])
        raise ValueError(f"periods must be strictly increasing [s], got {t[i]:g} then "
                         f"{t[i + 1]:g}")
    if not np.all(np.isfinite(sa)) or np.any(sa < 0.0):
        raise ValueError("accelerations must be finite and >= 0 [g]")
    return tuple(t.tolist()), tuple(sa.tolist())


def user_spectrum(periods, accelerations, name: str = "spectrum") -> ElasticSpectrum:
    """A spectrum given as a table: periods [s] and Se [g], interpolated linearly.

    Parameters
    ----------
    periods : array_like
        Periods [s], finite, >= 0, strictly increasing, at least two.
    accelerations : array_like
        Se [g] at those periods, finite and >= 0.
    name : str
        Shown in ``code`` as ``"user file <name>"``.

    Returns
    -------
    ElasticSpectrum
        Refusing periods outside the table.

    Examples
    --------
    >>> sp = user_spectrum([0.0, 0.5, 1.0], [0.3, 0.7, 0.35], name="site.csv")
    >>> sp.code, round(sp.acceleration(0.25), 6)  # (0.3 + 0.7) / 2
    ('user file site.csv', 0.5)
    """
    t, sa = _check_table(periods, accelerations)
    return ElasticSpectrum(code=f"user file {name}", periods=t, accelerations=sa)


def _is_number(text: str) -> bool:
    try:
        number(text)
    except ValueError:
        return False
    return True


def _read_table(path, columns: int, what: str, *, named_header: bool = False
                ) -> tuple[list[str] | None, list[list[float]]]:
    """The rows of a CSV or whitespace table: '#' starts a comment, the first line may be a
    header (with ``named_header``, one name per column). Fields are separated by commas or
    semicolons where a line has them, else by whitespace. Returns ``(header or None, rows)``."""
    path = Path(path)
    header, rows = None, []
    text = path.read_text(encoding="utf-8-sig")
    for line_number, raw in enumerate(text.splitlines(), start=1):
        line = raw.split("#", 1)[0].strip()
        if not line:
            continue
        separator = r"[,;]" if ("," in line or ";" in line) else r"\s+"
        fields = [f.strip() for f in re.split(separator, line)]
        if fields and not fields[-1]:
            fields.pop()  # a trailing separator
        try:
            values = [number(f) for f in fields]
        except ValueError:
            if header is None and not rows and not any(_is_number(f) for f in fields):
                header = fields
                if named_header and len(header) != columns:
                    raise ValueError(f"{what} {path.name}: the header names {len(header)} "
                                     f"columns, expected {columns}") from None
                continue
            raise ValueError(f"{what} {path.name}, line {line_number}: cannot read {raw.strip()!r}"
                             f" as {columns} numbers") from None
        if len(values) != columns:
            raise ValueError(f"{what} {path.name}, line {line_number}: expected {columns} "
                             f"columns, got {len(values)}")
        rows.append(values)
    return header, rows


def read_spectrum(path) -> ElasticSpectrum:
    """A user spectrum from a file of two columns: period [s] and Se [g].

    CSV (commas or semicolons) or whitespace-separated; ``#`` starts a comment; the first line
    may be a header. Periods strictly increasing, Se >= 0, at least two rows.

    Parameters
    ----------
    path : str or path-like
        The file.

    Returns
    -------
    ElasticSpectrum
        ``code = "user file <file name>"``.

    Raises
    ------
    ValueError
        Naming the file and the line.
    """
    path = Path(path)
    _, rows = _read_table(path, 2, "spectrum file")
    if len(rows) < 2:
        raise ValueError(f"spectrum file {path.name}: at least two rows (period, Se) are needed,"
                         f" got {len(rows)}")
    t, sa = zip(*rows, strict=True)
    try:
        return user_spectrum(t, sa, name=path.name)
    except ValueError as exc:
        raise ValueError(f"spectrum file {path.name}: {exc}") from None


def return_period(limit_state: str, nominal_life: float = 50.0, use_class: str = "II") -> float:
    r"""Return period T_R [years] of the seismic action of a limit state, NTC 2018 §2.4, §3.2.1.

    :math:`V_R = \max(V_N C_U, 35)`, :math:`T_R = -V_R / \ln(1 - P_{V_R})`.

    Parameters
    ----------
    limit_state : str
        ``"SLO"``, ``"SLD"``, ``"SLV"`` or ``"SLC"`` (P_VR = 81, 63, 10, 5 %).
    nominal_life : float
        Nominal life V_N [years] (Table 2.4.I: 10, 50, 100), > 0.
    use_class : str
        ``"I"``-``"IV"`` (C_U = 0.7, 1.0, 1.5, 2.0).

    Returns
    -------
    float
        T_R [years], not rounded (475 years is 474.6).

    Examples
    --------
    >>> round(return_period("SLV"))
    475
    """
    state = _choice("limit_state", limit_state, LIMIT_STATES)
    use = _choice("use_class", use_class, USE_CLASSES)
    life = _number("nominal_life", nominal_life, "years", 0.0, 10000.0, low_open=True)
    reference = max(life * USE_CLASSES[use], MIN_REFERENCE_PERIOD)
    return -reference / math.log(1.0 - LIMIT_STATES[state])


@dataclass(frozen=True)
class NtcSiteHazard:
    """The NTC 2018 hazard of a site: ``(ag, F0, Tc*)`` at the return periods of Annex A.

    Attributes
    ----------
    return_periods : tuple of float
        T_R [years], strictly increasing (the grid's 30, 50, 72, 101, 140, 201, 475, 975,
        2475, or some of them).
    ag : tuple of float
        Ground acceleration on rock [g] at each return period.
    f0 : tuple of float
        F0 [-].
    tc_star : tuple of float
        Tc* [s].
    name : str
        Where the values come from (the file's name).
    """

    return_periods: tuple
    ag: tuple
    f0: tuple
    tc_star: tuple
    name: str = "site"

    def __post_init__(self):
        n = len(self.return_periods)
        if n < 2 or any(len(v) != n for v in (self.ag, self.f0, self.tc_star)):
            raise ValueError("a site hazard needs at least two return periods, each with ag, f0 "
                             f"and tc_star; got {n} return periods")
        tr = [_number("return period", v, "years", 0.0, low_open=True)
              for v in self.return_periods]
        if any(b <= a for a, b in zip(tr, tr[1:], strict=False)):
            raise ValueError(f"return periods must be strictly increasing [years], got {tr}")
        ag = [_check_ag("ag", v) for v in self.ag]
        f0 = [_number("f0", v, "-", *F0_RANGE) for v in self.f0]
        tc = [_number("tc_star", v, "s", 0.0, MAX_TC_STAR, low_open=True) for v in self.tc_star]
        for field, values in (("return_periods", tr), ("ag", ag), ("f0", f0), ("tc_star", tc)):
            object.__setattr__(self, field, tuple(values))

    def parameters(self, return_period: float) -> tuple[float, float, float]:
        """``(ag [g], F0 [-], Tc* [s])`` at ``return_period`` [years], NTC 2018 Annex A.

        Each parameter is interpolated linearly in log(p) over log(T_R) between the two
        tabulated return periods around it (the tabulated values at the nodes).

        Raises
        ------
        ValueError
            For a return period outside the table (no extrapolation).
        """
        tr = _number("return_period", return_period, "years", 0.0, low_open=True)
        first, last = self.return_periods[0], self.return_periods[-1]
        if not first <= tr <= last:
            raise ValueError(f"return_period must be in [{first:g}, {last:g}] years (the "
                             f"return periods of {self.name}; NTC 2018 Annex A interpolates, "
                             f"it is not extrapolated here), got {return_period!r}")
        i = min(int(np.searchsorted(self.return_periods, tr, side="right")) - 1,
                len(self.return_periods) - 2)
        tr1, tr2 = self.return_periods[i], self.return_periods[i + 1]
        w = math.log(tr / tr1) / math.log(tr2 / tr1)
        out = tuple(math.exp(math.log(p[i]) + math.log(p[i + 1] / p[i]) * w)
                    for p in (self.ag, self.f0, self.tc_star))
        return out  # type: ignore[return-value]

    def spectrum(self, limit_state: str, soil: str = "A", topography: str = "T1",
                 damping: float = 5.0, nominal_life: float = 50.0, use_class: str = "II", *,
                 topography_ratio: float | None = None) -> ElasticSpectrum:
        """The NTC 2018 spectrum of a limit state at this site (:func:`return_period`,
        :meth:`parameters`, :func:`ntc2018_spectrum`)."""
        ag, f0, tc_star = self.parameters(return_period(limit_state, nominal_life, use_class))
        return ntc2018_spectrum(ag, f0, tc_star, soil, topography, damping,
                                topography_ratio=topography_ratio)

    def to_dict(self) -> dict:
        """Plain values for JSON."""
        return {"name": self.name, "return_periods": list(self.return_periods),
                "ag": list(self.ag), "f0": list(self.f0), "tc_star": list(self.tc_star)}


_SITE_COLUMNS = {"tr": "tr", "ag": "ag", "f0": "f0", "tc_star": "tc_star", "tc*": "tc_star"}


def read_ntc_site(path) -> NtcSiteHazard:
    """The national-grid hazard of a site from a CSV: columns TR [years], ag [g], F0 [-],
    Tc* [s].

    A header names the columns (case-insensitive ``tr``, ``ag``, ``f0``, ``tc_star`` or
    ``tc*``), in any order; without one they are in that order. ``#`` starts a comment;
    commas, semicolons or whitespace separate the fields.

    Parameters
    ----------
    path : str or path-like
        The file.

    Returns
    -------
    NtcSiteHazard

    Raises
    ------
    ValueError
        Naming the file, the line or the column.
    """
    path = Path(path)
    header, rows = _read_table(path, 4, "site file", named_header=True)
    order = [0, 1, 2, 3]
    if header is not None:
        names = [_SITE_COLUMNS.get((h.split() or [""])[0].lower()) for h in header]
        missing = [c for c in ("tr", "ag", "f0", "tc_star") if c not in names]
        if missing or len(names) != 4:
            raise ValueError(f"site file {path.name}: the header must name the columns tr, ag, "
                             f"f0, tc_star (or tc*), got {header}")
        order = [names.index(c) for c in ("tr", "ag", "f0", "tc_star")]
    if len(rows) < 2:
        raise ValueError(f"site file {path.name}: at least two return periods are needed, got "
                         f"{len(rows)}")
    columns = [tuple(row[j] for row in rows) for j in order]
    try:
        return NtcSiteHazard(*columns, name=path.name)
    except ValueError as exc:
        raise ValueError(f"site file {path.name}: {exc}") from None


__all__ = ["EC8_SOILS", "LIMIT_STATES", "NTC_DISPLACEMENT_CORNERS", "NTC_RETURN_PERIODS",
           "NTC_SOILS", "NTC_TOPOGRAPHY", "USE_CLASSES", "ElasticSpectrum", "NtcSiteHazard",
           "damping_correction", "ec8_spectrum", "ntc2018_spectrum", "ntc_soil_factors",
           "read_ntc_site", "read_spectrum", "return_period", "user_spectrum"]
