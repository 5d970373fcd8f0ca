"""``archquake spectrum``: the elastic response spectrum of a site (NTC 2018, EN 1998-1, a user's
table, or the NTC 2018 national-grid hazard of a site at a limit state);
:mod:`archquake.site.spectra`."""

from __future__ import annotations

import argparse

from ..ranges import number, parse_values
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

CODE_OPTIONS = {
    "ntc2018": ("ag", "f0", "tc_star", "topography", "topography_ratio", "soil", "damping"),
    "ec8": ("agr", "type", "importance", "soil", "damping"),
    "user": ("file",),
    "site": ("site", "limit_state", "nominal_life", "use_class", "topography",
             "topography_ratio", "soil", "damping"),
}
"""The options each way of giving the spectrum takes (the others are refused by name)."""

PARAMETER_OPTIONS = {
    "ag": "--ag", "f0": "--f0", "tc_star": "--tc-star", "soil": "--soil",
    "topography": "--topography", "topography_ratio": "--topography-ratio",
    "damping": "--damping", "agr": "--agr", "spectrum_type": "--type",
    "importance": "--importance", "limit_state": "--limit-state",
    "nominal_life": "--nominal-life", "use_class": "--use-class",
}
"""The option of each parameter of :mod:`archquake.site.spectra`, for its messages."""


def configure(parser: argparse.ArgumentParser) -> None:
    """The options of ``archquake spectrum``."""
    parser.description = DESCRIPTION
    parser.add_argument("--code", default=None, metavar="ntc2018|ec8|user",
                        help="the code of the spectrum (default: ntc2018 with --site)")
    ntc = parser.add_argument_group("NTC 2018 (--code ntc2018, or --site)")
    ntc.add_argument("--ag", type=number, default=None, metavar="G",
                     help="ground acceleration on rock a_g [g]")
    ntc.add_argument("--f0", type=number, default=None, metavar="F",
                     help="maximum spectral amplification F0 [-]")
    ntc.add_argument("--tc-star", type=number, default=None, metavar="T",
                     help="Tc* [s]")
    ntc.add_argument("--topography", default=None, metavar="T1|T2|T3|T4",
                     help="topographic category, Table 3.2.V (default: T1)")
    ntc.add_argument("--topography-ratio", type=number, default=None, metavar="R",
                     help="height of the site over that of the slope, in [0, 1]: S_T falls "
                          "linearly from the top (1, the default) to 1 at the base (0)")
    ec8 = parser.add_argument_group("EN 1998-1 (--code ec8)")
    ec8.add_argument("--agr", type=number, default=None, metavar="G",
                     help="reference peak ground acceleration on ground A a_gR [g]")
    ec8.add_argument("--type", default=None, metavar="1|2",
                     help="spectrum type: 1 (Table 3.2) or 2 (Table 3.3) (default: 1)")
    ec8.add_argument("--importance", type=number, default=None, metavar="GAMMA",
                     help="importance factor gamma_I [-] (default: 1.0)")
    both = parser.add_argument_group("both codes")
    both.add_argument("--soil", default=None, metavar="A|B|C|D|E",
                      help="soil (ground) category (default: A)")
    both.add_argument("--damping", type=number, default=None, metavar="XI",
                      help="viscous damping [%%], in (0, 30] (default: 5)")
    user = parser.add_argument_group("a user's spectrum (--code user)")
    user.add_argument("--file", default=None, metavar="PATH",
                      help="two columns: period [s], Se [g]")
    site = parser.add_argument_group("the NTC 2018 hazard of a site (--site)")
    site.add_argument("--site", default=None, metavar="FILE",
                      help="CSV with columns TR [years], ag [g], F0, Tc* [s] (header names "
                           "tr, ag, f0, tc_star or tc*)")
    site.add_argument("--limit-state", default=None, metavar="SLO|SLD|SLV|SLC",
                      help="limit state (P_VR 81, 63, 10, 5 %%)")
    site.add_argument("--nominal-life", type=number, default=None, metavar="YEARS",
                      help="nominal life V_N [years] (default: 50)")
    site.add_argument("--use-class", default=None, metavar="I|II|III|IV",
                      help="use class, C_U = 0.7, 1.0, 1.5, 2.0 (default: II)")
    parser.add_argument("--periods", default=None, metavar="LIST",
                        help="periods [s]: numbers and ranges start:stop:step, comma-separated "
                             f"(default: {DEFAULT_PERIODS}; a user file: its own periods)")
    options.add_json_option(
        parser, 'machine-readable output: {"spectrum": {code, parameters}, "rows": '
                '[{"period_s", "se_g", "sde_m"}]}')


def _way(args: argparse.Namespace) -> str:
    """Which spectrum the options ask for: a code's, a user's, or a site's."""
    code = None if args.code is None else args.code.strip().lower()
    if args.site is not None:
        if code not in (None, "ntc2018"):
            raise ValueError(f"--site gives an NTC 2018 spectrum, not --code {args.code}")
        way = "site"
    elif code is None:
        raise ValueError("give --code ntc2018, ec8 or user, or --site FILE")
    elif code not in ("ntc2018", "ec8", "user"):
        raise ValueError(f"--code must be ntc2018, ec8 or user, got {args.code!r}")
    else:
        way = code
    names = {n for ns in CODE_OPTIONS.values() for n in ns}
    foreign = options.given(args, *sorted(names - set(CODE_OPTIONS[way])))
    if foreign:
        what = "--site" if way == "site" else f"--code {way}"
        verb = "does" if len(foreign) == 1 else "do"
        raise ValueError(f"{', '.join(foreign)} {verb} not apply to {what}")
    return way


def _option_message(exc: ValueError) -> ValueError:
    """The library's message naming a parameter, naming its option instead."""
    text = str(exc)
    if text.startswith("ag = importance * agr "):
        return ValueError("a_g = --importance x --agr" + text[len("ag = importance * agr"):])
    if text.startswith("period "):
        return ValueError(f"--periods: {text}")
    for name, option in sorted(PARAMETER_OPTIONS.items(), key=lambda kv: -len(kv[0])):
        if text.startswith(name + " "):
            return ValueError(option + text[len(name):])
    return exc


def _required(args: argparse.Namespace, *names: str) -> None:
    missing = [f"--{n.replace('_', '-')}" for n in names if getattr(args, n) is None]
    if missing:
        raise ValueError(f"{', '.join(missing)} must be given")


def _spectrum(args: argparse.Namespace, way: str):
    """The spectrum, and what the site gave (or None)."""
    from ..site import spectra

    soil = "A" if args.soil is None else args.soil
    damping = 5.0 if args.damping is None else args.damping
    topography = "T1" if args.topography is None else args.topography
    if way == "ntc2018":
        _required(args, "ag", "f0", "tc_star")
        return spectra.ntc2018_spectrum(args.ag, args.f0, args.tc_star, soil, topography,
                                        damping, topography_ratio=args.topography_ratio), None
    if way == "ec8":
        _required(args, "agr")
        kind = 1 if args.type is None else args.type.strip()
        if kind not in (1, "1", "2"):
            raise ValueError(f"--type must be 1 or 2, got {args.type!r}")
        return spectra.ec8_spectrum(args.agr, int(kind), soil,
                                    1.0 if args.importance is None else args.importance,
                                    damping), None
    if way == "user":
        _required(args, "file")
        try:
            return spectra.read_spectrum(args.file), None
        except ValueError as exc:
            raise ValueError(f"--file: {exc}") from None
    _required(args, "limit_state")
    try:
        hazard = spectra.read_ntc_site(args.site)
    except ValueError as exc:
        raise ValueError(f"--site: {exc}") from None
    life = 50.0 if args.nominal_life is None else args.nominal_life
    use = "II" if args.use_class is None else args.use_class
    tr = spectra.return_period(args.limit_state, life, use)
    try:
        ag, f0, tc_star = hazard.parameters(tr)
    except ValueError as exc:
        raise ValueError(f"--limit-state {args.limit_state} with --nominal-life {life:g} and "
                         f"--use-class {use} gives T_R = {tr:.1f} years, outside the table of "
                         f"--site {hazard.name} ({hazard.return_periods[0]:g} to "
                         f"{hazard.return_periods[-1]:g} years): {exc}") from None
    spectrum = spectra.ntc2018_spectrum(ag, f0, tc_star, soil, topography, damping,
                                        topography_ratio=args.topography_ratio)
    site = {"file": hazard.name, "limit_state": args.limit_state.strip().upper(),
            "nominal_life": life, "use_class": use.strip().upper(), "return_period": tr,
            "ag": ag, "f0": f0, "tc_star": tc_star}
    return spectrum, site


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
    way = _way(args)
    try:
        spectrum, site = _spectrum(args, way)
        if args.periods is None:
            periods = (list(spectrum.periods) if spectrum.is_table
                       else parse_values(DEFAULT_PERIODS, "--periods"))
        else:
            periods = parse_values(args.periods, "--periods")
        se = spectrum.acceleration(periods).tolist()
        sde = spectrum.displacement(periods).tolist()
    except ValueError as exc:
        raise _option_message(exc) from None
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
