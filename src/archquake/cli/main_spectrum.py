"""``archquake spectrum``: the elastic response spectrum of a site (NTC 2018, EN 1998-1, a user's
table, or the NTC 2018 national-grid hazard of a site at a limit state);
:mod:`archquake.site.spectra`."""

from __future__ import annotations

import argparse

from ..ranges import parse_values
from . import options
from .output import print_json

DESCRIPTION = (
    "Elastic response spectrum of the horizontal ground acceleration at a site: Se [g] and "
    "SDe [m] per period, after the corner periods. --code ntc2018: NTC 2018 §3.2.3.2, eqs. "
    "3.2.2-3.2.7 (S = S_S S_T of Tables 3.2.IV-V, T_C = C_C Tc*, T_B = T_C/3, T_D = 4 ag/g + "
    "1.6 s, eta = sqrt(10/(5+xi)) >= 0.55) and the displacement spectrum of §3.2.3.2.3 (T_E, "
    "T_F of Table 3.2.VIII, eq. 3.2.12). --code ec8: EN 1998-1:2004 §3.2.2.2, eqs. 3.2-3.7, "
    "Tables 3.2 (type 1) and 3.3 (type 2), a_g = gamma_I a_gR, and Annex A's displacement "
    "beyond T_E. --code user: a file of two columns, period [s] and Se [g] (CSV or whitespace, "
    "'#' comments, an optional header), interpolated linearly. --site: the NTC 2018 hazard of a "
    "site (a CSV with columns TR, ag, F0, Tc* at the return periods of Annex A, interpolated "
    "in log-log) at the return period of --limit-state (NTC 2018 §2.4, §3.2.1: T_R = -V_R / "
    "ln(1 - P_VR), V_R = V_N C_U >= 35 years).")

DEFAULT_PERIODS = "0:4:0.1"
"""The periods shown when --periods is not given [s] (a user table: its own periods)."""

def configure(parser: argparse.ArgumentParser) -> None:
    """The options of ``archquake spectrum``."""
    parser.description = DESCRIPTION
    options.add_site_options(parser)
    parser.add_argument("--periods", default=None, metavar="LIST",
                        help="periods [s]: numbers and ranges start:stop:step, comma-separated "
                             f"(default: {DEFAULT_PERIODS}; a user file: its own periods)")
    options.add_json_option(
        parser, 'machine-readable output: {"spectrum": {code, parameters}, "rows": '
                '[{"period_s", "se_g", "sde_m"}]}')




def _text(spectrum, site, periods, se, sde) -> None:
    """The spectrum as text: its parameters, then a table."""
    if site is not None:
        print(f"site {site['file']}, {site['limit_state']} (V_N {site['nominal_life']:g} years,"
              f" use class {site['use_class']}): T_R = {site['return_period']:.1f} years, "
              f"ag = {site['ag']:.4f} g, F0 = {site['f0']:.3f}, Tc* = {site['tc_star']:.3f} s")
    if spectrum.is_table:
        print(f"{spectrum.code}: {len(spectrum.periods)} periods, {spectrum.periods[0]:g} to "
              f"{spectrum.periods[-1]:g} s, linear interpolation")
    else:
        details = dict(spectrum.details)
        head = f"{spectrum.code}, soil {spectrum.soil}"
        if "topography" in details:
            head += (f", {details['topography']}: ag = {spectrum.ag:.4g} g, F0 = "
                     f"{spectrum.f0:.4g}, Tc* = {details['tc_star']:.4g} s; S_S = "
                     f"{details['s_s']:.4g}, S_T = {details['s_t']:.4g}, C_C = "
                     f"{details['c_c']:.4g}")
        else:
            head += (f", type {details['spectrum_type']}: a_g = gamma_I a_gR = "
                     f"{details['importance']:g} x {details['agr']:g} = {spectrum.ag:.4g} g")
        print(head)
        print(f"S = {spectrum.s:.4g}, eta = {spectrum.eta:.4g} (damping {spectrum.damping:g} %),"
              f" PGA = a_g S = {spectrum.pga:.4g} g")
        print(f"T_B = {spectrum.t_b:.4g} s, T_C = {spectrum.t_c:.4g} s, T_D = {spectrum.t_d:.4g} "
              f"s, T_E = {spectrum.t_e:g} s, T_F = {spectrum.t_f:g} s; d_g = "
              f"{spectrum.ground_displacement:.4g} m")
    print(f"{'T [s]':>8}  {'Se [g]':>9}  {'SDe [m]':>9}")
    for t, a, d in zip(periods, se, sde, strict=True):
        print(f"{t:8.4g}  {a:9.5f}  {d:9.5f}")


def run(args: argparse.Namespace) -> int:
    """The spectrum of the options, at the periods."""
    way = options.site_way(args)
    try:
        spectrum, site = options.site_spectrum(args, way)
        if args.periods is None:
            periods = (list(spectrum.periods) if spectrum.is_table
                       else parse_values(DEFAULT_PERIODS, "--periods"))
        else:
            periods = parse_values(args.periods, "--periods")
        se = spectrum.acceleration(periods).tolist()
        sde = spectrum.displacement(periods).tolist()
    except ValueError as exc:
        raise options.site_option_message(exc) from None
    if args.json:
        out = {"spectrum": spectrum.to_dict()}
        if site is not None:
            out["site"] = site
        out["rows"] = [{"period_s": t, "se_g": a, "sde_m": d}
                       for t, a, d in zip(periods, se, sde, strict=True)]
        print_json(out)
        return 0
    _text(spectrum, site, periods, se, sde)
    return 0
