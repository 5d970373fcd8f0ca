"""The assessment at a site (``archquake assess --site ...``): the code check of the collapse
mechanism, the code's dynamic route with the trusted model, and the annual risk of collapse,
as values for the report, then its words.

The science is the library's (:mod:`archquake.site`):
:func:`~archquake.site.local_mechanism.check_local_mechanism`,
:func:`~archquake.site.compatible_records.select_compatible_records` and
:func:`~archquake.site.dynamic_check.run_dynamic_check`, :func:`~archquake.site.risk.risk`.
This module calls them with the assessment's structure, site, records and record fragility,
and keeps what they say, including why a part was not made.
"""

from __future__ import annotations

import math
from typing import Any

DYNAMIC_COUNTS = (7, 6, 5, 4, 3)
"""Records of the dynamic route, in the order tried: seven (the mean effect, NTC 2018
§7.3.5), else as many as the assessment's suite holds, down to three (the most unfavourable
effect)."""

RISK_YEARS = 50.0
"""The span of the probability of collapse [yr]: the nominal life of ordinary structures, NTC
2018 §2.4.1."""


def site_part(structure, site, suite, results: dict, *, progress: bool = False):
    """The site's part of the assessment.

    Parameters
    ----------
    structure : BlockArch
        The structure assessed.
    site : SiteSpec
        The site (:class:`archquake.site.spec.SiteSpec`).
    suite : RecordSuite
        The assessment's records, from which the dynamic route selects the compatible ones.
    results : dict
        The assessment's results so far: the record-based fragility in PGA of the model the
        first screen trusts (``results["trusted"]``) is the fragility of the risk.
    progress : bool
        Progress bars of the dynamic route.

    Returns
    -------
    summary : dict
        JSON-ready: ``site``, ``check``, ``dynamic``, ``risk`` (each part either its values or
        ``{"skipped": reason}``).
    check : LocalMechanismCheck
        For the figure.
    """
    from ...site.local_mechanism import check_local_mechanism

    actions = site.actions()
    check = check_local_mechanism(structure, actions, confidence_factor=site.fc)
    summary: dict[str, Any] = {"site": site.to_dict(), "describe": site.describe(),
                               "check": check.to_dict()}
    summary["dynamic"] = _dynamic(structure, site, actions, suite, progress)
    summary["risk"] = _risk(site, results)
    return summary, check


def dynamic_selection(site, actions, suite):
    """The records of the code's dynamic route at the SLV action (or the only one given):
    seven compatible with its spectrum, else as many as the suite has (>= 3).

    Returns
    -------
    (action, selection, skipped)
        The action and the :class:`~archquake.site.compatible_records.CompatibleSelection`, or
        ``skipped``, a JSON-ready dict saying why there is none (the others then None).
    """
    from ...site.compatible_records import select_compatible_records

    action = next((a for a in actions if a.limit_state == "SLV"), actions[0])
    rule = "ec8" if site.code == "ec8" else "ntc2018"
    selection, error = None, ""
    for count in DYNAMIC_COUNTS:  # seven records, else as many as the suite has (>= 3)
        try:
            selection = select_compatible_records(suite, action.spectrum, rule=rule,
                                                  count=count)
            break
        except ValueError as exc:
            error = str(exc)
            if "count must be at most" not in error:
                break
    if selection is None:
        return None, None, {"skipped": f"no selection of the assessment's records: {error}"}
    if not selection.compatible:
        return None, None, {
            "skipped": "the assessment's records hold no subset compatible with the site's "
                       f"{action.limit_state} spectrum: {selection.summary()}",
            "selection": selection.to_dict()}
    return action, selection, None


def _dynamic(structure, site, actions, suite, progress: bool) -> dict:
    """The code's dynamic route at the SLV action (or the only one given)."""
    from ...site.dynamic_check import run_dynamic_check

    action, selection, skipped = dynamic_selection(site, actions, suite)
    if skipped is not None:
        return skipped
    dynamic = run_dynamic_check(structure, selection, progress=progress)
    return {"limit_state": action.limit_state, **dynamic.to_dict()}


def trusted_pga_fragility(results: dict) -> tuple[dict | None, str]:
    """The record-based fragility in PGA of the model the first screen trusts, and that
    model's name: the rigid blocks' study where the two models disagree
    (``results["rigid_block_studies"]``), else the four-link model's."""
    trusted = (results.get("trusted") or {}).get("model", "four-link")
    if trusted == "rigid-blocks":
        studies = (results.get("rigid_block_studies") or {}).get("records") or {}
    else:
        studies = results.get("records") or {}
    return (studies.get("ims") or {}).get("pga"), trusted


def _risk(site, results: dict) -> dict:
    """The annual frequency of collapse from the site's hazard curve and the record fragility
    in PGA of the trusted model."""
    from ...site.fragility_models import LognormalCollapseFragility
    from ...site.risk import risk

    hazard = site.hazard_curve("PGA")
    if hazard is None:
        return {"skipped": "the site is given by one spectrum, not its hazard curve: give its "
                           "national-grid table (--site FILE) for the risk"}
    entry, model = trusted_pga_fragility(results)
    fit = (entry or {}).get("lognormal") or {}
    if not fit.get("median") or not fit.get("dispersion"):
        return {"skipped": f"no lognormal fragility in PGA from the record-based study of the "
                           f"{model} model"}
    fragility = LognormalCollapseFragility(
        float(fit["median"]), float(fit["dispersion"]), "PGA",
        source=f"the record-based fragility of the irregular arches ({model} model)")
    return {**risk(fragility, hazard, years=RISK_YEARS).to_dict(), "model": model}


# ------------------------------------------------------------------------------------ words
def _sci(value) -> str:
    return "-" if value is None or not math.isfinite(value) else f"{value:.3g}"


def _state(value) -> str:
    return {True: "HOLDS", False: "FAILS", None: "not checked"}[value]


def _capacity(value) -> str:
    return "beyond 1.5 g" if value is None else f"{value:.3f} g"


def verdict_text(site: dict) -> str:
    """The first screen's line on the site: the code's verdict of each limit state, the
    dynamic route's and the risk."""
    check = site["check"]
    states = []
    for state, verdict in check["verdict"].items():
        if verdict is None:
            continue
        ag = check["actions"][state]["ag_g"]
        states.append(f"{state} {_state(verdict)} (holds up to a_g = "
                      f"{_capacity(check['pga_capacity_g'][state])}; site {ag:.3f} g)")
    out = (f"CODE CHECK AT THE SITE (NTC 2018 §8.7.1, Circolare 2019 §C8.7.1): "
           f"{'; '.join(states)}.")
    dynamic = site["dynamic"]
    if "verdict" in dynamic:
        v = dynamic["verdict"]
        out += (f" Dynamic route (NTC 2018 §3.2.3.6, §7.3.5) with the {v['model']} model, "
                f"{v['records']} compatible records: {v['verdict'].upper()}.")
    risk = site["risk"]
    if "annual_frequency" in risk:
        out += (f" Annual frequency of collapse {_sci(risk['annual_frequency'])} 1/yr, "
                f"probability {100 * risk['probability']:.2f} % in {risk['years']:g} years "
                f"(the {risk['model']} model's record fragility in PGA")
        tail = risk.get("tail_share")
        if tail is not None and math.isfinite(tail) and tail > 0.1:
            out += (f"; {100 * tail:.0f} % of it from beyond the hazard curve's last level, "
                    "extrapolated")
        out += ")."
    return out


def check_rows(site: dict) -> list[list[str]]:
    """One row per check: limit state, route, direction, capacity, demand, ratio, verdict,
    a_g at which it holds."""
    names = {"l": "Mech-l", "r": "Mech-r", "+x": "toward +x", "-x": "toward -x"}
    rows = []
    check = site["check"]
    for c in check["linear"]:
        rows.append([c["limit_state"], "linear (§C8.7.1.2.1)", names[c["direction"]],
                     f"a0* = {c['a0_star_g']:.4f} g", f"a_g S / q = {c['demand_g']:.4f} g",
                     f"{c['ratio']:.2f}", _state(c["passes"]),
                     _capacity(c["pga_capacity_ag_g"])])
    for c in check["nonlinear"]:
        rows.append([c["limit_state"], "nonlinear (§C8.7.1.2.2)", names[c["direction"]],
                     f"d_u* = {c['du_star_m']:.4f} m", f"SDe({c['Ts_s']:.2f} s) = "
                     f"{c['demand_SDe_m']:.4f} m", f"{c['ratio']:.2f}", _state(c["passes"]),
                     _capacity(c["pga_capacity_ag_g"])])
    return rows


def check_text(site: dict) -> str:
    """The check in words: the site, the oscillator, the choices."""
    check = site["check"]
    p = check["participation"][0]
    actions = ", ".join(f"{s} a_g = {a['ag_g']:.4f} g" for s, a in check["actions"].items())
    mass = p["participating_mass_kg_per_m"] / 1e3
    text = (f"The site: {site['describe']} ({actions}). The collapse mechanism of the limit "
            f"analysis is checked as a local mechanism (Circolare 2019 §C8.7.1): alpha0 = "
            f"{p['alpha0']:.4f}, participating mass M* = {mass:.2f} t/m, e* = "
            f"{p['mass_fraction']:.4f}, a0* = alpha0 g / (e* FC) = "
            f"{p['a0_star_g']:.4f} g (FC = {p['confidence_factor']:g}). The linear check asks "
            "a0* >= a_g S / q (q = 2); the nonlinear one, on the capacity curve of the "
            "mechanism's exact kinematics, d_u* >= SDe(T_s) with d_u* = 0.24 d0* at SLV and "
            "0.40 d0* at SLC. A limit state holds when either route holds in both directions.")
    for note in check["notes"]:
        text += f" Note: {note}."
    return text


def dynamic_text(site: dict) -> str:
    """The dynamic route in words."""
    dynamic = site["dynamic"]
    if "skipped" in dynamic:
        return f"The code's dynamic route was not made: {dynamic['skipped']}"
    sel = dynamic["selection"]
    verdicts = "; ".join(
        f"{v['model']}: {v['verdict']} ({v['collapses']} collapses, {v['undecided']} "
        f"undecided of {v['records']}; {v['reason']})" for v in dynamic["verdicts"])
    models = [v["model"] for v in dynamic["verdicts"]]
    through = ("the rigid-block model (whose verdict is stated) and the four-link model beside "
               "it" if len(models) > 1 else f"the {models[0]} model")
    return (f"The code's dynamic route (NTC 2018 §3.2.3.6 and §7.3.5) at the "
            f"{dynamic['limit_state']} spectrum: {len(sel['records'])} of the assessment's "
            f"records, scaled so that their mean spectrum lies within the code's band; "
            f"each run through {through}. {verdicts}. A collapse under any record fails the "
            f"check; an undecided run is never a pass."
            + (f" {dynamic['records_note']}" if dynamic.get("records_note") else ""))


def dynamic_rows(site: dict) -> list[list[str]]:
    """One row per record run: model, record, factor, outcome, peak rotation."""
    dynamic = site["dynamic"]
    if "runs" not in dynamic:
        return []
    return [[r["model"], r["record"], f"{r['factor']:.3f}", str(r["status"]),
             "-" if r.get("peak_response") is None else f"{r['peak_response']:.2e}"]
            for r in dynamic["runs"]]


def risk_text(site: dict) -> str:
    """The risk in words."""
    risk = site["risk"]
    if "skipped" in risk:
        return f"The annual risk of collapse was not computed: {risk['skipped']}."
    fragility = risk["fragility"]
    tail = risk["tail_share"]
    text = (f"The annual risk of collapse: the record-based fragility in PGA "
            f"({risk['model']} model: lognormal, median {fragility.get('median', float('nan')):.3f}"
            f" g, dispersion {fragility.get('dispersion', float('nan')):.3f}) convolved with the "
            f"site's hazard curve ({risk['hazard_source']}): lambda_c = "
            f"{_sci(risk['annual_frequency'])} 1/yr, return period "
            f"{_sci(risk['return_period'])} years, probability of collapse "
            f"{100 * risk['probability']:.3f} % in {risk['years']:g} years.")
    if tail is not None and not math.isnan(tail) and tail > 0.1:
        text += (f" {100 * tail:.0f} % of lambda_c comes from beyond the hazard curve's last "
                 "level (2,475 years on the national grid), where the curve is extrapolated "
                 "as a power law: the figure rests on that extrapolation.")
    return text


_FIELD_OPTIONS = {"grid": "--site", "spectrum_type": "--type"}


def site_words(site: dict) -> list[str]:
    """The command line's options of a site (:meth:`archquake.site.spec.SiteSpec.to_dict`),
    for the command that regenerates the report."""
    words = []
    for name, value in site.items():
        words += [_FIELD_OPTIONS.get(name, f"--{name.replace('_', '-')}"),
                  f"{value:g}" if isinstance(value, float) else str(value)]
    return words


def caption(site: dict) -> str:
    """The caption of the capacity-curve figure."""
    return ("The capacity curve of the collapse mechanism at the site (Circolare 2019 "
            "§C8.7.1.2.2): spectral acceleration a* against spectral displacement d* of the "
            "equivalent oscillator, by virtual work on the mechanism's exact kinematics, to "
            "d0* where gravity stops resisting; open markers: the displacement capacities d_u* "
            "of SLV and SLC, filled markers on the axis: the demands SDe(T_s); dashed: the "
            "linear check's demand a_g S / q beside a0*, where the curve starts.")
