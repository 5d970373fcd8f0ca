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
:mod:`archquake.site.compatible_records`
    records selected from a suite and scaled so that their mean spectrum matches a site's
    (NTC 2018 §3.2.3.6, EN 1998-1 §3.2.3.1.2).
:mod:`archquake.site.dynamic_check`
    the structure under those records by both dynamic models, and the code's verdict (NTC 2018
    §7.3.5).
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
