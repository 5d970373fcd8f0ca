"""A site of the NTC 2018 national grid for the tests: a_g [g], F0 [-], Tc* [s] at the nine
return periods of Annex A (illustrative values, of the order of the grid's in central Italy;
the tests compute what they expect from these numbers by hand)."""

GRID_TABLE = """TR,ag,F0,Tc*
30,0.060,2.48,0.27
50,0.078,2.47,0.28
72,0.094,2.46,0.29
101,0.110,2.44,0.30
140,0.127,2.43,0.31
201,0.148,2.42,0.32
475,0.212,2.40,0.34
975,0.270,2.41,0.35
2475,0.360,2.44,0.37
"""
"""The site's table, as :func:`archquake.site.spectra.read_ntc_site` reads it."""
