"""The site: its seismic action (code spectra and the national-grid hazard) and what is checked
against it.

:mod:`archquake.site.spectra`
    elastic response spectra of NTC 2018, EN 1998-1 and a user's table; the NTC 2018 hazard of
    a site on the national grid and the return period of a limit state.
:mod:`archquake.site.local_mechanism`
    the code check of the structure's collapse mechanism (NTC 2018 §8.7.1, Circolare 2019
    §C8.7.1): participating mass, capacity curve, linear and nonlinear checks, PGA capacity.
:mod:`archquake.site.hazard`
    hazard curves: OpenQuake's exports, a plain table, the NTC 2018 national grid.
:mod:`archquake.site.fragility_models`
    fragilities: lognormal, discrete, OpenQuake NRML, archquake's own studies.
:mod:`archquake.site.risk`
    the mean annual frequency of collapse and the probability of collapse in a span of years.
"""

from .spectra import (
    ElasticSpectrum,
    NtcSiteHazard,
    ec8_spectrum,
    ntc2018_spectrum,
    read_ntc_site,
    read_spectrum,
    return_period,
    user_spectrum,
)

__all__ = ["ElasticSpectrum", "NtcSiteHazard", "ec8_spectrum", "ntc2018_spectrum",
           "read_ntc_site", "read_spectrum", "return_period", "user_spectrum"]
