r"""A site described by named values: its seismic action and the knowledge of the structure.

:class:`SiteSpec` is to a site what :class:`~archquake.geometry.StructureSpec` is to a
structure: the values an engineer names (the NTC 2018 national-grid table of the site, or one
code spectrum's parameters, the soil and topography, the knowledge level), checked once, and
turned into the library's values: the site's actions of the code check
(:meth:`SiteSpec.actions`, :class:`~archquake.site.local_mechanism.SiteAction`), its hazard
curve for the risk (:meth:`SiteSpec.hazard_curve`), the confidence factor. The report
(``archquake assess --site ...``) records it (:meth:`SiteSpec.to_dict`,
:meth:`SiteSpec.from_dict`); the command line's site options map onto it.

Two ways to give the action:

- **the national grid** (``grid``): the file of the site's a_g, F0, Tc* at the return periods
  of NTC 2018 Annex A (:func:`~archquake.site.spectra.read_ntc_site`); the actions of SLV and
  SLC follow from the nominal life and use class
  (:func:`~archquake.site.spectra.return_period`), and the file is also a hazard curve (1/T_R
  at a_g S);
- **one spectrum** (``code``: ``"ntc2018"`` with ``ag``, ``f0``, ``tc_star``; ``"ec8"`` with
  ``agr``, ``spectrum_type``, ``importance``; ``"user"`` with ``file``), the action of
  ``limit_state`` (default SLV).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any

CODES = ("ntc2018", "ec8", "user")
"""The spectra a site may be given by: NTC 2018, EN 1998-1, a user's table."""

_FIELDS_OF = {
    "ntc2018": {"ag", "f0", "tc_star", "soil", "topography", "topography_ratio", "damping"},
    "ec8": {"agr", "spectrum_type", "importance", "soil", "damping"},
    "user": {"file"},
    "grid": {"grid", "nominal_life", "use_class", "soil", "topography", "topography_ratio",
             "damping"},
}
"""The fields each way of giving the action takes (``limit_state`` and the knowledge fields go
with every way)."""


@dataclass(frozen=True)
class SiteSpec:
    """A site by named values (see the module).

    Every field is optional (``None``: not given, its default applies).

    Parameters
    ----------
    code : {"ntc2018", "ec8", "user"}, optional
        One spectrum (not with ``grid``).
    grid : str, optional
        Path of the site's NTC 2018 national-grid table (TR, ag, F0, Tc*).
    ag, f0, tc_star : float, optional
        NTC 2018: a_g on rock [g], F0 [-], Tc* [s].
    soil : str, optional
        Soil category A-E (default A).
    topography : str, optional
        Topographic category T1-T4 (default T1).
    topography_ratio : float, optional
        Height of the site over the slope's, in [0, 1] (NTC 2018 Table 3.2.V).
    damping : float, optional
        Viscous damping [%] (default 5).
    agr, spectrum_type, importance : optional
        EN 1998-1: a_gR [g], type 1 or 2, gamma_I.
    file : str, optional
        A user's spectrum table (period [s], Se [g]).
    limit_state : {"SLV", "SLC"}, optional
        The limit state of one spectrum (default SLV); with ``grid``, check only this one
        (default both).
    nominal_life : float, optional
        V_N [years] (default 50), with ``grid``.
    use_class : str, optional
        I-IV (default II), with ``grid``.
    knowledge_level : {"LC1", "LC2", "LC3"}, optional
        The structure's knowledge level (default LC1).
    confidence_factor : float, optional
        F_C itself, instead of ``knowledge_level``.

    Raises
    ------
    ValueError
        Naming the field: both or neither of ``code`` and ``grid``, a field that does not apply
        to the way given, an unknown code or limit state, a missing parameter.
    """

    code: str | None = None
    grid: str | None = None
    ag: float | None = None
    f0: float | None = None
    tc_star: float | None = None
    soil: str | None = None
    topography: str | None = None
    topography_ratio: float | None = None
    damping: float | None = None
    agr: float | None = None
    spectrum_type: int | None = None
    importance: float | None = None
    file: str | None = None
    limit_state: str | None = None
    nominal_life: float | None = None
    use_class: str | None = None
    knowledge_level: str | None = None
    confidence_factor: float | None = None

    def __post_init__(self):
        from .local_mechanism import LIMIT_STATES, confidence_factor

        code = None if self.code is None else str(self.code).strip().lower()
        if (code is None) == (self.grid is None):
            raise ValueError("code: give a site as either its national-grid table (grid) or "
                             "one spectrum (code ntc2018, ec8 or user), not both or neither")
        if code is not None and code not in CODES:
            raise ValueError(f"code must be one of {', '.join(CODES)}, got {self.code!r}")
        object.__setattr__(self, "code", code)
        way = code or "grid"
        extra = sorted(name for name in {n for f in _FIELDS_OF.values() for n in f}
                       - _FIELDS_OF[way] if getattr(self, name) is not None)
        if extra:
            raise ValueError(f"{extra[0]} does not apply to a site given by "
                             f"{'its national-grid table' if way == 'grid' else code}")
        if self.limit_state is not None:
            state = str(self.limit_state).strip().upper()
            if state not in LIMIT_STATES:
                raise ValueError(f"limit_state must be one of {', '.join(LIMIT_STATES)}, got "
                                 f"{self.limit_state!r}")
            object.__setattr__(self, "limit_state", state)
        confidence_factor(self.knowledge_level, self.confidence_factor)
        required = {"ntc2018": ("ag", "f0", "tc_star"), "ec8": ("agr",), "user": ("file",)}
        for name in required.get(code, ()):
            if getattr(self, name) is None:
                raise ValueError(f"{name} must be given for a site given by {code}")

    @property
    def fc(self) -> float:
        """The confidence factor F_C
        (:func:`~archquake.site.local_mechanism.confidence_factor`)."""
        from .local_mechanism import confidence_factor

        return confidence_factor(self.knowledge_level, self.confidence_factor)

    def _defaults(self) -> dict[str, Any]:
        return {"soil": self.soil or "A", "topography": self.topography or "T1",
                "damping": 5.0 if self.damping is None else self.damping}

    def spectrum(self, limit_state: str | None = None):
        """The site's elastic spectrum (:class:`~archquake.site.spectra.ElasticSpectrum`) of
        ``limit_state`` (with ``grid``; default :attr:`limit_state`, else SLV)."""
        from . import spectra

        d = self._defaults()
        if self.code == "ntc2018":
            return spectra.ntc2018_spectrum(self.ag, self.f0, self.tc_star, d["soil"],
                                            d["topography"], d["damping"],
                                            topography_ratio=self.topography_ratio)
        if self.code == "ec8":
            return spectra.ec8_spectrum(self.agr, int(self.spectrum_type or 1), d["soil"],
                                        1.0 if self.importance is None else self.importance,
                                        d["damping"])
        if self.code == "user":
            return spectra.read_spectrum(self.file)
        state = limit_state or self.limit_state or "SLV"
        return spectra.read_ntc_site(self.grid).spectrum(
            state, d["soil"], d["topography"], d["damping"],
            50.0 if self.nominal_life is None else self.nominal_life, self.use_class or "II",
            topography_ratio=self.topography_ratio)

    @property
    def limit_states(self) -> tuple[str, ...]:
        """The limit states checked: :attr:`limit_state`, or SLV and SLC with ``grid``, SLV
        with one spectrum."""
        from .local_mechanism import LIMIT_STATES

        if self.limit_state is not None:
            return (self.limit_state,)
        return LIMIT_STATES if self.grid is not None else ("SLV",)

    def actions(self) -> list:
        """The site's actions of the code check, one per limit state
        (:class:`~archquake.site.local_mechanism.SiteAction`)."""
        from .local_mechanism import SiteAction

        return [SiteAction.of(state, self.spectrum(state)) for state in self.limit_states]

    def hazard_curve(self, im: str = "PGA"):
        """The site's hazard curve (:func:`~archquake.site.hazard.ntc_hazard_curve`: 1/T_R at
        the spectrum's ordinate on the site's soil) for a site given by its national grid;
        None for one spectrum (a spectrum is no hazard curve)."""
        if self.grid is None:
            return None
        from .hazard import read_ntc_hazard_curve

        return read_ntc_hazard_curve(self.grid, im=im, soil=self.soil,
                                     topography=self.topography or "T1")

    def describe(self) -> str:
        """One line: the site as given."""
        d = self._defaults()
        if self.grid is not None:
            where = f"the NTC 2018 national-grid table {self.grid}"
        elif self.code == "ntc2018":
            where = (f"NTC 2018, a_g = {self.ag:g} g, F0 = {self.f0:g}, Tc* = "
                     f"{self.tc_star:g} s")
        elif self.code == "ec8":
            where = f"EN 1998-1 type {self.spectrum_type or 1}, a_gR = {self.agr:g} g"
        else:
            where = f"the spectrum of {self.file}"
        soil = "" if self.code == "user" else f", soil {d['soil']}, {d['topography']}"
        return f"{where}{soil}; FC = {self.fc:g}"

    def to_dict(self) -> dict[str, Any]:
        """The fields given (the others are their defaults)."""
        return {f.name: getattr(self, f.name) for f in dataclasses.fields(self)
                if getattr(self, f.name) is not None}

    @classmethod
    def from_dict(cls, values: dict[str, Any]) -> SiteSpec:
        """The spec of :meth:`to_dict`; an unknown field is refused by name."""
        names = {f.name for f in dataclasses.fields(cls)}
        unknown = sorted(set(values) - names)
        if unknown:
            raise ValueError(f"{unknown[0]}: not a field of a site (fields: "
                             f"{', '.join(sorted(names))})")
        return cls(**values)
