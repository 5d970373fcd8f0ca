r"""Hazard curves: the mean annual frequency :math:`\lambda(x)` [1/yr] at which a site's
intensity measure exceeds a level :math:`x` [g].

The curve
    :class:`HazardCurve`: intensity levels (strictly increasing, > 0) and their annual
    frequencies of exceedance (> 0, non-increasing), in one intensity measure (``PGA`` or
    ``SA(T)``, in g). Between two levels it is interpolated log-log (a power law
    :math:`\lambda = \lambda_i (x/x_i)^{-k_i}`); below the first level the first frequency is
    held (the curve says nothing there); beyond the last level a power-law tail continues the
    slope of the last two levels (:meth:`HazardCurve.frequency`).
Readers
    :func:`read_openquake_hazard_curve` (the engine's ``hazard_curve-<kind>-<IMT>_<id>.csv``
    [1]_: probabilities of exceedance in the investigation time, converted to annual
    frequencies under Poisson occurrence, :func:`annual_frequency`, as OpenQuake does [2]_),
    :func:`read_hazard_csv` (two columns, IM [g] and annual frequency [1/yr]),
    :func:`ntc_hazard_curve` (the NTC 2018 national-grid parameters of a site at its nine
    return periods [3]_: :math:`\lambda = 1/T_R` at the spectrum's ordinate,
    :func:`read_ntc_hazard_curve` from the file of
    :func:`archquake.site.spectra.read_ntc_site`), and :func:`read_hazard_curve`, which
    recognises each from the content.

References
----------
.. [1] GEM Foundation (2024). The OpenQuake engine user manual: hazard curves
   (``hazard_curve-mean-PGA_<calc_id>.csv``: a comment line with ``investigation_time`` and
   ``imt``, then ``lon,lat,depth,poe-<iml>...``, one row per site).
.. [2] GEM Foundation. ``openquake.risklib.scientific.annual_frequency_of_exceedence``:
   :math:`\lambda = -\ln(1 - \mathrm{poe}) / T`.
.. [3] Ministero delle Infrastrutture e dei Trasporti (2018). NTC 2018, D.M. 17 gennaio 2018:
   §3.2.3.2.1 (the spectrum, :math:`a_{max} = S\,a_g` at T = 0) and Allegato A (the national
   grid's :math:`a_g, F_0, T_C^*` at return periods 30 to 2475 years).
"""

from __future__ import annotations

import math
import os
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..ranges import number

__all__ = ["HAZARD_FORMATS", "HazardCurve", "annual_frequency", "canonical_im",
           "hazard_format", "ntc_hazard_curve", "read_hazard_csv", "read_hazard_curve",
           "read_ntc_hazard_curve", "read_openquake_hazard_curve"]

HAZARD_FORMATS = ("openquake", "csv", "ntc")
"""Formats of a hazard-curve file :func:`read_hazard_curve` reads: an OpenQuake export, a
two-column CSV, the NTC 2018 national-grid parameters of a site."""


def canonical_im(name: str) -> str:
    """OpenQuake's name of an intensity measure in g: ``"PGA"`` or ``"SA(T)"`` (T the period
    [s], written as Python writes the float: ``SA(1.0)``), from any spelling archquake reads
    (``pga``, ``sa(1)``, ``SA( 0.5 )``).

    Parameters
    ----------
    name : str

    Returns
    -------
    str

    Raises
    ------
    ValueError
        For another measure: hazard curves and the risk are in g, in PGA or SA(T).

    Examples
    --------
    >>> canonical_im("pga"), canonical_im("sa(1)")
    ('PGA', 'SA(1.0)')
    """
    from ..results_io import openquake_imt

    try:
        imt, factor = openquake_imt(name)
    except ValueError:
        imt, factor = None, None
    if imt is None or factor != 1.0 or imt == "IA":
        raise ValueError(f"intensity measure {name!r}: hazard curves and the risk of collapse "
                         f"are in g, in PGA or SA(T) with T the period [s]")
    return imt


@dataclass(frozen=True, eq=False)
class HazardCurve:
    r"""A site's hazard curve in one intensity measure.

    Attributes
    ----------
    levels : ndarray, shape (n,)
        Intensity levels :math:`x_i` [g], strictly increasing, > 0; n >= 2.
    frequencies : ndarray, shape (n,)
        Mean annual frequencies of exceedance :math:`\lambda_i` [1/yr], > 0, non-increasing,
        the last two different (they set the tail's slope).
    im : str
        The intensity measure: ``"PGA"`` or ``"SA(T)"`` with T the period [s] (as OpenQuake
        names them; ``pga`` and ``sa(0.5)`` are read the same).
    source : str
        Where the curve comes from and how it was converted (said in the output).
    notes : tuple of str
        What the reader changed (levels dropped, ...), said in the output.

    Raises
    ------
    ValueError
        Naming the row (0-based level index) where the levels do not increase or the
        frequencies increase, or a level or frequency that is not a finite number > 0.
    """

    levels: np.ndarray
    frequencies: np.ndarray
    im: str = "PGA"
    source: str = ""
    notes: tuple[str, ...] = field(default=())

    def __post_init__(self) -> None:
        levels = np.array(self.levels, dtype=float).ravel()
        frequencies = np.array(self.frequencies, dtype=float).ravel()
        if levels.size != frequencies.size:
            raise ValueError(f"a hazard curve needs as many frequencies as levels, got "
                             f"{levels.size} levels and {frequencies.size} frequencies")
        if levels.size < 2:
            raise ValueError(f"a hazard curve needs at least 2 levels, got {levels.size}")
        for name, values, unit in (("level", levels, "g"), ("frequency", frequencies, "1/yr")):
            bad = np.flatnonzero(~(np.isfinite(values) & (values > 0)))
            if bad.size:
                i = int(bad[0])
                raise ValueError(f"hazard curve row {i}: the {name} must be a finite number "
                                 f"> 0 [{unit}], got {values[i]!r}")
        rising = np.flatnonzero(np.diff(levels) <= 0)
        if rising.size:
            i = int(rising[0]) + 1
            raise ValueError(f"hazard curve row {i}: the levels must increase strictly, got "
                             f"{levels[i]!r} g after {levels[i - 1]!r} g")
        up = np.flatnonzero(np.diff(frequencies) > 0)
        if up.size:
            i = int(up[0]) + 1
            raise ValueError(
                f"hazard curve row {i}: the annual frequency of exceedance must not increase "
                f"with the level, got {frequencies[i]!r} 1/yr at {levels[i]!r} g after "
                f"{frequencies[i - 1]!r} 1/yr at {levels[i - 1]!r} g (not monotone)")
        if frequencies[-1] == frequencies[-2]:
            raise ValueError(f"hazard curve row {levels.size - 1}: the last two frequencies "
                             f"are equal ({frequencies[-1]!r} 1/yr): they set the slope of "
                             f"the tail beyond the last level, which must fall")
        levels.flags.writeable = False
        frequencies.flags.writeable = False
        object.__setattr__(self, "levels", levels)
        object.__setattr__(self, "frequencies", frequencies)
        object.__setattr__(self, "im", canonical_im(self.im))
        object.__setattr__(self, "notes", tuple(self.notes))

    @property
    def slopes(self) -> np.ndarray:
        r"""Log-log slopes :math:`k_i = -\ln(\lambda_{i+1}/\lambda_i) / \ln(x_{i+1}/x_i)` [-]
        of the n - 1 intervals (>= 0)."""
        return -np.diff(np.log(self.frequencies)) / np.diff(np.log(self.levels))

    @property
    def tail_slope(self) -> float:
        """Slope k [-] of the power-law tail beyond the last level: that of the last interval."""
        return float(self.slopes[-1])

    def frequency(self, intensity) -> np.ndarray:
        r"""Annual frequency of exceedance [1/yr] at intensities ``intensity`` [g].

        .. math::

            \lambda(x) = \begin{cases}
                \lambda_1 & x < x_1 \\
                \lambda_i\,(x/x_i)^{-k_i} & x_i \le x \le x_{i+1} \\
                \lambda_n\,(x/x_n)^{-k_{n-1}} & x > x_n
            \end{cases}

        log-log interpolation between levels; below the first level the first frequency held
        (a lower value than the curve's continuation would give: the annual frequency of
        collapse computed with it misses what the fragility adds below :math:`x_1`); beyond
        the last level the power law of the last interval.

        Parameters
        ----------
        intensity : array_like
            Intensities [g] (>= 0; 0 gives :math:`\lambda_1`).

        Returns
        -------
        ndarray
        """
        x = np.asarray(intensity, dtype=float)
        u = np.log(np.maximum(x, self.levels[0]))
        logs_x, logs_f = np.log(self.levels), np.log(self.frequencies)
        inside = np.interp(u, logs_x, logs_f)
        beyond = logs_f[-1] - self.tail_slope * (u - logs_x[-1])
        return np.exp(np.where(u > logs_x[-1], beyond, inside))

    def to_dict(self) -> dict:
        """JSON-ready: ``im``, ``levels`` [g], ``frequencies`` [1/yr], ``tail_slope`` [-],
        ``source``, ``notes``."""
        return {"im": self.im, "levels": self.levels.tolist(),
                "frequencies": self.frequencies.tolist(), "tail_slope": self.tail_slope,
                "source": self.source, "notes": list(self.notes)}


def annual_frequency(poe, investigation_time: float) -> np.ndarray:
    r"""Annual frequency of exceedance of a probability of exceedance in a time, under Poisson
    occurrence (as OpenQuake's ``annual_frequency_of_exceedence``, the module's references):

    .. math::

        \lambda = -\frac{\ln(1 - \mathrm{poe})}{T}.

    Parameters
    ----------
    poe : array_like
        Probabilities of exceedance in ``investigation_time``, in [0, 1) [-].
    investigation_time : float
        T > 0 [yr].

    Returns
    -------
    ndarray
        :math:`\lambda` [1/yr].

    Raises
    ------
    ValueError
        If T is not > 0 or a probability is outside [0, 1).

    Examples
    --------
    >>> round(float(annual_frequency(0.1, 50.0)), 8)  # 10 % in 50 years: 1/475 yr
    0.00210721
    """
    t = float(investigation_time)
    if not (math.isfinite(t) and t > 0):
        raise ValueError(f"investigation_time must be > 0 [yr], got {investigation_time!r}")
    p = np.asarray(poe, dtype=float)
    if not np.all((p >= 0) & (p < 1)):
        raise ValueError("probabilities of exceedance must lie in [0, 1)")
    return -np.log1p(-p) / t


# ---------------------------------------------------------------------------------------------
# Readers
# ---------------------------------------------------------------------------------------------

_OQ_TIME = re.compile(r"investigation_time\s*=\s*([0-9.eE+-]+)")
_OQ_IMT = re.compile(r"""imt\s*=\s*(?:'([^']*)'|"([^"]*)"|\\"([^"\\]*)\\")""")


def _read_text(path) -> str:
    try:
        return Path(path).read_text(encoding="utf-8-sig")
    except FileNotFoundError:
        raise ValueError(f"hazard curve file {str(path)!r} does not exist") from None
    except IsADirectoryError:
        raise ValueError(f"hazard curve file {str(path)!r} is a directory") from None
    except UnicodeDecodeError:
        raise ValueError(f"hazard curve file {str(path)!r} is not UTF-8 text") from None
    except OSError as exc:
        raise ValueError(f"cannot read the hazard curve {str(path)!r}: {exc.strerror}") from None


def _is_ntc(text: str) -> bool:
    """A national-grid site file: its header names ag and F0."""
    header = next((line for line in text.splitlines()
                   if line.strip() and not line.lstrip().startswith("#")), "")
    cells = {c.strip().lower() for c in re.split(r"[,;\s]+", header)}
    return {"ag", "f0"} <= cells


def ntc_hazard_curve(site, *, im: str = "PGA", soil: str | None = None,
                     topography: str = "T1") -> HazardCurve:
    r"""The hazard curve of a site of the NTC 2018 national grid: at each of its return periods
    :math:`T_R`, the annual frequency :math:`1/T_R` of exceeding the elastic spectrum's
    ordinate (NTC 2018 §3.2.3.2.1 and Annex A, the module's references).

    For ``PGA`` the ordinate is :math:`S_e(0) = a_g S` with :math:`S = S_S S_T`
    (NTC 2018 §3.2.3.2.1): :math:`a_g` on rock (soil A, :math:`S = 1`) when no soil is given;
    for ``SA(T)`` it is :math:`S_e(T)` at 5 % damping
    (:func:`archquake.site.spectra.ntc2018_spectrum`, with the site's :math:`F_0` and
    :math:`T_C^*` of each return period).
    The grid's return periods are those of uniform-hazard spectra, so the curve is
    :math:`\lambda(S_e(T; T_R)) = 1/T_R` (a Poisson rate of exceedance); the tail beyond
    2475 years continues the power law of the last two return periods.

    Parameters
    ----------
    site : NtcSiteHazard
        (:func:`archquake.site.spectra.read_ntc_site`).
    im : str
        ``PGA`` or ``SA(T)``.
    soil : str, optional
        Soil category A-E (NTC 2018 Table 3.2.IV); None: rock, the grid's :math:`a_g`.
    topography : str
        Topographic category T1-T4 (Table 3.2.V), with a soil.

    Returns
    -------
    HazardCurve

    Raises
    ------
    ValueError
        For an unknown soil or topography, or ordinates that do not increase with the return
        period (naming the row).
    """
    from .spectra import ntc2018_spectrum

    im = canonical_im(im)
    period = 0.0 if im == "PGA" else float(im[3:-1])
    ground = "A" if soil is None else soil
    levels = [float(ntc2018_spectrum(ag, f0, tc, ground, topography if soil else "T1")
                    .acceleration(period))
              for ag, f0, tc in zip(site.ag, site.f0, site.tc_star, strict=True)]
    where = ("on rock (the grid's ag)" if soil is None
             else f"on soil {soil}, topography {topography}")
    ordinate = "ag S" if im == "PGA" else f"Se({period:g} s) at 5 % damping"
    source = (f"NTC 2018 national grid {site.name}: annual frequency 1/TR at {ordinate} "
              f"{where}, TR {site.return_periods[0]:g} to {site.return_periods[-1]:g} yr")
    return HazardCurve(levels, [1.0 / tr for tr in site.return_periods], im=im, source=source)


def read_ntc_hazard_curve(path: str | os.PathLike, *, im: str = "PGA", soil: str | None = None,
                          topography: str = "T1") -> HazardCurve:
    """:func:`ntc_hazard_curve` of the site file ``path``
    (:func:`archquake.site.spectra.read_ntc_site`: columns TR, ag, F0, Tc*)."""
    from .spectra import read_ntc_site

    site = read_ntc_site(path)
    try:
        return ntc_hazard_curve(site, im=im, soil=soil, topography=topography)
    except ValueError as exc:
        raise ValueError(f"{Path(path).name}: {exc}") from None


def _is_openquake(text: str) -> bool:
    """An OpenQuake export: its comment line names the investigation time, or its header
    starts ``lon,lat``."""
    lines = [line.strip() for line in text.splitlines() if line.strip()]
    if not lines:
        return False
    if lines[0].startswith("#") and "investigation_time" in lines[0]:
        return True
    header = [line for line in lines if not line.startswith("#")]
    return bool(header) and header[0].replace(" ", "").lower().startswith("lon,lat,")


def read_openquake_hazard_curve(path: str | os.PathLike, *,
                                site_index: int | None = None) -> HazardCurve:
    r"""Read a hazard curve exported by the OpenQuake engine (``hazard_curve-mean-PGA_*.csv``).

    The file (the OpenQuake user manual, the module's references) starts with a comment line
    holding the investigation time T and the intensity measure type, e.g.
    ``#,,,,,"generated_by='OpenQuake engine 3.18.0', ..., kind='mean',
    investigation_time=50.0, imt='PGA'"``, then the header ``lon,lat,depth,poe-<iml>,...``
    and one row per site of probabilities of exceedance in T. They become annual frequencies
    :math:`\lambda = -\ln(1-\mathrm{poe})/T` (Poisson occurrence, :func:`annual_frequency`).
    Levels whose probability is 0 at the end of the row (no exceedance computed there) are
    dropped, and so are leading levels of probability 1 (an infinite frequency); the curve's
    ``notes`` say so.

    Parameters
    ----------
    path : str or os.PathLike
        The CSV file.
    site_index : int, optional
        Row of the site (0-based, in the file's order); required when the file holds several
        sites.

    Returns
    -------
    HazardCurve

    Raises
    ------
    ValueError
        If the comment line has no ``investigation_time`` or ``imt``, the header has no
        ``poe-`` column, a value is not a number, the file holds several sites and no
        ``site_index`` (or one out of range), or the curve is not monotone (naming the row).
    """
    text = _read_text(path)
    name = Path(path).name
    lines = [line for line in text.splitlines() if line.strip()]
    comments = [line for line in lines if line.lstrip().startswith("#")]
    rows = [line for line in lines if not line.lstrip().startswith("#")]
    meta = " ".join(comments)
    time_match, imt_match = _OQ_TIME.search(meta), _OQ_IMT.search(meta)
    if time_match is None or imt_match is None:
        raise ValueError(f"{name}: not an OpenQuake hazard curve: its comment line must give "
                         f"investigation_time and imt")
    try:
        investigation_time = number(time_match.group(1))
    except ValueError:
        raise ValueError(f"{name}: investigation_time {time_match.group(1)!r} is not a "
                         f"number") from None
    imt = next(g for g in imt_match.groups() if g is not None)
    if not rows:
        raise ValueError(f"{name}: no header line lon,lat,depth,poe-...")
    header = [cell.strip() for cell in rows[0].split(",")]
    columns = [j for j, cell in enumerate(header) if cell.startswith("poe-")]
    if not columns:
        raise ValueError(f"{name}: the header has no poe-<level> column: {rows[0]!r}")
    try:
        levels = np.array([number(header[j][4:]) for j in columns])
    except ValueError as exc:
        raise ValueError(f"{name}: a level of the header is not a number ({exc})") from None
    sites = rows[1:]
    if not sites:
        raise ValueError(f"{name}: no site row after the header")
    if site_index is None:
        if len(sites) > 1:
            raise ValueError(f"{name} holds {len(sites)} sites: choose one with site_index "
                             f"(--site-index) in [0, {len(sites)})")
        site_index = 0
    if not (0 <= int(site_index) < len(sites)):
        raise ValueError(f"site_index must be in [0, {len(sites)}) for {name}, got "
                         f"{site_index!r}")
    cells = [cell.strip() for cell in sites[int(site_index)].split(",")]
    if len(cells) != len(header):
        raise ValueError(f"{name}: site row {site_index} has {len(cells)} cells, the header "
                         f"{len(header)}")
    try:
        poes = np.array([number(cells[j]) for j in columns])
        where = {h: number(cells[j]) for j, h in enumerate(header) if h in ("lon", "lat")}
    except ValueError as exc:
        raise ValueError(f"{name}: site row {site_index}: {exc}") from None
    bad = np.flatnonzero(~((poes >= 0) & (poes <= 1)))
    if bad.size:
        i = int(bad[0])
        raise ValueError(f"{name}: poe-{header[columns[i]][4:]} = {poes[i]!r} is not a "
                         f"probability in [0, 1]")
    notes = []
    keep = np.ones(poes.size, dtype=bool)
    certain = np.flatnonzero(poes == 1.0)
    if certain.size:
        lead = int(np.argmin(np.append(poes, 0.0) == 1.0))  # leading run of ones
        keep[:lead] = False
        if lead:
            notes.append(f"{lead} first level(s) with probability 1 of exceedance (an "
                         f"infinite annual frequency) dropped: the curve starts at "
                         f"{levels[lead]:g} g")
    nonzero = np.flatnonzero(poes > 0)
    last = int(nonzero[-1]) if nonzero.size else -1
    if last < poes.size - 1:
        keep[last + 1:] = False
        notes.append(f"{poes.size - 1 - last} last level(s) with probability 0 of exceedance "
                     f"dropped: beyond {levels[last]:g} g the curve is the power-law tail")
    levels, poes = levels[keep], poes[keep]
    if levels.size < 2:
        raise ValueError(f"{name}: fewer than 2 levels with a probability of exceedance in "
                         f"(0, 1)")
    frequencies = -np.log1p(-poes) / investigation_time
    place = ", ".join(f"{k} {v:g}" for k, v in where.items())
    source = (f"OpenQuake hazard curve {name} (site {site_index}{': ' + place if place else ''})"
              f", probabilities of exceedance in {investigation_time:g} yr converted to annual "
              f"frequencies as -ln(1 - poe) / {investigation_time:g} (Poisson)")
    try:
        return HazardCurve(levels, frequencies, im=imt, source=source, notes=tuple(notes))
    except ValueError as exc:
        raise ValueError(f"{name}: {exc}") from None


def read_hazard_csv(path: str | os.PathLike, *, im: str | None = None) -> HazardCurve:
    """Read a hazard curve from a plain CSV file: two columns, the intensity [g] and its annual
    frequency of exceedance [1/yr], one level a row, increasing.

    Lines starting with ``#`` and empty lines are skipped. A first row that is not two numbers
    is a header; if its first cell names an intensity measure (``PGA``, ``SA(0.5)``), that is
    the curve's.

    Parameters
    ----------
    path : str or os.PathLike
        The CSV file.
    im : str, optional
        The intensity measure (``PGA`` or ``SA(T)``); required unless the header names it
        (and must then agree with it).

    Returns
    -------
    HazardCurve

    Raises
    ------
    ValueError
        For a row that is not two numbers (naming the line), no intensity measure, or a curve
        that is not monotone (naming the row).
    """
    text = _read_text(path)
    name = Path(path).name
    rows = []
    header_im = None
    first = True
    for lineno, line in enumerate(text.splitlines(), start=1):
        stripped = line.strip()
        if not stripped or stripped.startswith("#"):
            continue
        cells = [cell.strip() for cell in re.split(r"[,;\t]", stripped)]
        try:
            if len(cells) != 2:
                raise ValueError
            rows.append((number(cells[0]), number(cells[1])))
        except ValueError:
            if first:
                try:
                    header_im = canonical_im(cells[0])
                except ValueError:
                    header_im = None
                first = False
                continue
            raise ValueError(f"{name} line {lineno}: expected two numbers, the intensity [g] "
                             f"and its annual frequency of exceedance [1/yr], got "
                             f"{stripped!r}") from None
        first = False
    if im is None and header_im is None:
        raise ValueError(f"{name}: name the intensity measure (--im PGA or SA(T)): the file's "
                         f"header does not")
    if im is not None and header_im is not None and canonical_im(im) != header_im:
        raise ValueError(f"{name}: its header names {header_im}, but {canonical_im(im)} was "
                         f"asked for")
    if not rows:
        raise ValueError(f"{name}: no row of numbers")
    data = np.array(rows)
    try:
        return HazardCurve(data[:, 0], data[:, 1], im=im if im is not None else header_im,
                           source=f"hazard curve {name} (annual frequencies of exceedance)")
    except ValueError as exc:
        raise ValueError(f"{name}: {exc}") from None


def hazard_format(path: str | os.PathLike) -> str:
    """The format of a hazard file, recognised from its content: ``openquake`` if its first
    line is a comment naming ``investigation_time`` or its header starts ``lon,lat``; ``ntc``
    if its header names ``ag`` and ``F0``; else ``csv``."""
    text = _read_text(path)
    return "openquake" if _is_openquake(text) else "ntc" if _is_ntc(text) else "csv"


def read_hazard_curve(path: str | os.PathLike, *, format: str | None = None,
                      im: str | None = None, site_index: int | None = None,
                      soil: str | None = None, topography: str = "T1") -> HazardCurve:
    """Read a hazard curve, its format given or recognised from the content.

    Parameters
    ----------
    path : str or os.PathLike
        The file.
    format : {"openquake", "csv", "ntc"}, optional
        Default: ``openquake`` if the first line is a comment naming ``investigation_time``
        or the header starts ``lon,lat``; ``ntc`` if the header names ``ag`` and ``F0``; else
        ``csv``.
    im : str, optional
        The intensity measure of a plain CSV (:func:`read_hazard_csv`); for an OpenQuake file,
        if given, it must be the file's.
    site_index : int, optional
        The site of an OpenQuake file of several (:func:`read_openquake_hazard_curve`).
    soil, topography : str, optional
        Of a national-grid site (:func:`ntc_hazard_curve`; ``im`` defaults to PGA there).

    Returns
    -------
    HazardCurve

    Raises
    ------
    ValueError
        For an unknown format or what the readers refuse.
    """
    if format is None:
        format = hazard_format(path)
    if format != "ntc" and (soil is not None or topography != "T1"):
        raise ValueError("soil and topography (--soil, --topography) are for a national-grid "
                         "site (ntc format)")
    if format == "ntc":
        if site_index is not None:
            raise ValueError("site_index (--site-index) is for OpenQuake files of several "
                             "sites, not a national-grid site")
        return read_ntc_hazard_curve(path, im="PGA" if im is None else im, soil=soil,
                                     topography=topography)
    if format == "openquake":
        curve = read_openquake_hazard_curve(path, site_index=site_index)
        if im is not None and canonical_im(im) != curve.im:
            raise ValueError(f"{Path(path).name} is a hazard curve of {curve.im}, but "
                             f"{canonical_im(im)} was asked for")
        return curve
    if format == "csv":
        if site_index is not None:
            raise ValueError("site_index (--site-index) is for OpenQuake files of several "
                             "sites, not a plain CSV")
        return read_hazard_csv(path, im=im)
    raise ValueError(f"hazard format must be one of {', '.join(HAZARD_FORMATS)}, got "
                     f"{format!r}")
