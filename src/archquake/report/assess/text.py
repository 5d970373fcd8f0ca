"""The words of an assessment: its verdict, summary, captions, paragraphs and table rows, each
written from the numbers of ``results.json`` (:func:`archquake.report.assess.assess`), never by
hand.

The formatters are those of every report (:mod:`archquake.report.formatting`); what is written
here is the assessment's own: the first screen (:func:`verdict_text`, :func:`summary_rows`,
:func:`agreement_text`, :data:`ASSUMPTIONS`), then a paragraph, a table and a caption per part.
"""

from __future__ import annotations

from ..formatting import number, percent
from .settings import AGREEMENT_BAND

ASSUMPTIONS = (
    "Rigid blocks: the masonry does not deform; all motion is rotation (and, in the rigid-block "
    "model, sliding) at the joints.",
    "No tension: a joint carries compression only, and opens (a hinge forms) where the line of "
    "thrust reaches its edge.",
    "Infinite compressive strength: no crushing at the hinges.",
    "No sliding in the limit analysis and the four-link model (Heyman's hypotheses); the "
    "rigid-block model allows it, with Coulomb friction.",
    "A plane model of unit depth: in-plane motion only, under a horizontal ground acceleration; "
    "no out-of-plane or vertical excitation, no soil-structure interaction.",
)
"""The assumptions every result of an assessment rests on."""

MODEL_NAMES = {"four-link": "four-link model", "rigid-blocks": "rigid-block model"}
"""The models in words."""


def im_label(im: str) -> str:
    """An intensity measure in words: ``PGA``, ``PGV``, ``Sa(0.5 s)``."""
    if im.startswith("sa("):
        return f"Sa({im[3:-1]} s)"
    return im.upper()


def _g(x, digits: int = 3) -> str:
    return "-" if x is None else f"{x:.{digits}f} g"


def _factor_text(safety: dict) -> str:
    if safety.get("factor") is None:
        return ""
    what = "thickness" if safety["kind"] == "thickness" else "pier width"
    return (f"geometric safety factor {safety['factor']:.2f} ({what} {safety['value']:.3g} m "
            f"over the least that stands, {safety['minimum']:.3g} m)")


# ------------------------------------------------------------------------------ first screen
def heading(results: dict) -> str:
    """The report's heading: ``"Seismic assessment: <the structure>"``."""
    return f"Seismic assessment: {results['structure']['name']}"


def verdict_text(results: dict) -> str:
    """The verdict in one paragraph: does the structure stand, when does it start to move, how
    safe is its geometry.

    Parameters
    ----------
    results : dict
        ``results.json``.

    Returns
    -------
    str
    """
    verdict, safety = results["verdict"], results["safety"]
    factor = _factor_text(safety) or _factor_text(safety.get("thickness") or {})
    if not verdict["stands"]:
        reason = verdict["reason"]
        text = (f"VERDICT: CANNOT STAND (the {verdict['part'] or 'structure'}). "
                f"{reason[:1].upper()}{reason[1:]}.")
        if factor:
            text += f" Its {factor}."
        return text + " No seismic capacity exists; the assessment stops here."
    if not verdict["collapses"]:
        return (f"VERDICT: STANDS, AND NO HORIZONTAL ACCELERATION COLLAPSES IT. "
                f"{verdict['reason']}.")
    limit = results["limit"]
    text = (f"VERDICT: STANDS. A horizontal ground acceleration of {limit['k']:.3f} g sets it "
            f"in motion (limit analysis: k_l = {limit['k_l']:.3f}, k_r = {limit['k_r']:.3f}); "
            f"below it the structure moves with the ground.")
    if factor:
        text += f" Its {factor}."
    return text + collapse_text(results)


def collapse_text(results: dict) -> str:
    """The collapse capacities of the verdict, from the model the first screen uses, in one
    sentence (``""`` without them)."""
    s = results.get("summary") or {}
    long = s.get("pulse_long")
    if long is None or "model" not in s:
        return ""
    used = s["model"]
    value = long["rigid_blocks"] if used == "rigid-blocks" else long["four_link"]
    undecided = long.get("rigid_blocks_undecided_from") is not None
    if value is None or (undecided and used == "rigid-blocks"):
        return ""
    text = (f" It collapses under a long pulse (t_p = {long['duration']:.2f} s) of "
            f"{value:.3f} g")
    pga = (s.get("records") or {}).get("pga")
    if pga is not None:
        fit = pga["lognormal"] if pga["lognormal"]["median"] is not None else (
            pga["nominal_lognormal"])
        if fit["median"] is not None:
            who = "irregular arches" if fit is pga["lognormal"] else "the structure"
            text += f" and under the records at a median PGA of {fit['median']:.3f} g ({who})"
    if used == "rigid-blocks":
        return text + (" by the rigid-block model, used because the two models disagree (the "
                       "four-link model's numbers, beside them below, are not used).")
    return text + " by the four-link model (the two models agree)."


def _rigid_cell(row: dict, beyond: str) -> str:
    """The rigid blocks' failure acceleration, as the range it lies in where an undecided band
    lies below it."""
    rb, low = row["rigid_blocks"], row.get("rigid_blocks_undecided_from")
    if low is not None:
        return f"{low:.3f}-" + ("" if rb is None else f"{rb:.3f}") + " g (undecided between)"
    return beyond if rb is None else _g(rb)


def not_used_words(value: str, off_by) -> str:
    """A four-link number shown beside the rigid-block one it is not used for:
    ``"four-link: 0.202 g (off by +25.0 %, not used)"``.

    Parameters
    ----------
    value : str
        The four-link number, in words.
    off_by : float or None
        Four-link over the number used, minus 1 [-] (None: not comparable).

    Returns
    -------
    str
    """
    off = "" if off_by is None else f"off by {percent(off_by)}, "
    return f"four-link: {value} ({off}not used)"


def _pulse_cells(row: dict, scanned: float, four_link: bool = True,
                 model: str = "four-link") -> list[str]:
    fl = row["four_link"]
    beyond = f"> {scanned:g} g"
    rigid = _rigid_cell(row, beyond)
    if not four_link:
        return [rigid, MODEL_NAMES["rigid-blocks"], "the four-link model does not apply"]
    flv = beyond if fl is None else _g(fl)
    if model == "rigid-blocks":
        return [rigid, MODEL_NAMES["rigid-blocks"], not_used_words(flv, row["difference"])
                + ("" if row["difference"] is not None
                   else ": " + difference_words(None, row))]
    return [flv, f"{MODEL_NAMES['four-link']} (the two agree)",
            f"rigid blocks: {rigid} ({difference_words(row['difference'], row)})"]


def difference_words(difference, row: dict | None = None) -> str:
    """The four-link model's failure acceleration against the rigid blocks', in words.

    Parameters
    ----------
    difference : float or None
        Four-link over rigid blocks, minus 1 [-] (None: one does not collapse in the scan, or
        the rigid blocks' is undecided).
    row : dict, optional
        The row of the duration (says why there is no difference).

    Returns
    -------
    str
    """
    if difference is None:
        if row is not None and row.get("rigid_blocks_undecided_from") is not None:
            return "no difference: the rigid blocks' failure acceleration is undecided"
        if row is not None and row["four_link"] is None and row["rigid_blocks"] is None:
            return "neither collapses in the scan"
        return "one model does not collapse in the scan"
    if abs(difference) <= AGREEMENT_BAND:
        return f"{percent(difference)}: agree within {100 * AGREEMENT_BAND:g} %"
    side = "unconservative" if difference > 0 else "conservative"
    return (f"{percent(difference)}: differ; the four-link model is {side} (the rigid blocks "
            f"collapse {'lower' if difference > 0 else 'higher'})")


def _model_words(entry: dict, agree: bool) -> str:
    name = MODEL_NAMES[entry.get("model", "four-link")]
    if entry.get("model", "four-link") == "four-link" and agree:
        return f"{name} (the two agree)"
    return name


def _record_value(entry: dict) -> str:
    fit, nominal = entry["lognormal"], entry["nominal_lognormal"]
    unit = entry["unit"]
    if fit["median"] is None and nominal["median"] is None:
        return "no lognormal fit (see Section 5)"
    if fit["median"] is None:
        why = ("no irregular arches" if not entry.get("sample_size") else
               f"no lognormal fit of the {entry['sample_size']} irregular arches")
        return (f"median {number(nominal['median'], 3)} {unit}, beta "
                f"{number(nominal['dispersion'], 2)} (the structure; {why})")
    return (f"median {number(fit['median'], 3)} {unit}, beta {number(fit['dispersion'], 2)} "
            f"(irregular arches); {number(nominal['median'], 3)} {unit} (the structure)")


def undecided_words(entry: dict) -> str:
    """What a result's undecided analyses leave open, or ``""`` without any
    (:mod:`archquake.studies.undecided`)."""
    count = (entry.get("undecided") or {}).get("analyses", 0)
    if not count:
        return ""
    text = (f"; {count} of {entry['undecided']['of']} rigid-block analyses undecided, counted "
            f"as neither")
    upper = entry.get("lognormal_undecided_as_collapse") or {}
    nominal = entry.get("nominal_lognormal_undecided_as_collapse") or {}
    which = upper if (entry.get("lognormal") or {}).get("median") is not None else nominal
    if which.get("median") is not None:
        text += (f": the median lies between {number(which['median'], 3)} {entry['unit']} "
                 f"(undecided as collapses) and the value given (as survivals)")
    return text


def summary_rows(results: dict) -> list[list[str]]:
    """The capacities of the first screen: quantity, value, the model it comes from, and the
    other model beside it (the four-link model's number marked "not used" where the two
    disagree and the rigid-block model's is used).

    Parameters
    ----------
    results : dict
        ``results.json``.

    Returns
    -------
    list of list of str
    """
    s = results["summary"]
    rows = []
    limit = results["limit"]
    if limit is None:
        return rows
    agree = bool(s.get("agree", True))
    used = s.get("model", "four-link")
    rows.append(["start of motion (activation)",
                 f"{limit['k']:.3f} g (k_l = {limit['k_l']:.3f}, k_r = {limit['k_r']:.3f})",
                 "limit analysis (both models start to move there)", "-"])
    scanned = results["pulses"].get("amplitudes_g", [0.0])[-1]
    applies = bool((results.get("four_link") or {}).get("applies"))
    for key, what in (("pulse_long", "long"), ("pulse_short", "short")):
        row = s.get(key)
        if row is not None:
            rows.append([f"collapse under a {what} pulse (Oppenheim's, t_p = "
                         f"{row['duration']:.2f} s)",
                         *_pulse_cells(row, scanned, applies, row.get("model", used))])
    irregular = s.get("irregular")
    if irregular is not None:
        q = irregular.get("k_5")
        text = []
        if q is not None:
            text.append(f"5 % of the arches start to move below {q:.3f} g (limit analysis; "
                        f"the structure: {limit['k']:.3f} g)")
        c = irregular.get("curve")
        if c is not None and c.get("lognormal_median") is not None:
            text.append(f"at t_p = {c['duration']:.2f} s, median collapse "
                        f"{c['lognormal_median']:.3f} g (the structure: "
                        f"{number(c['nominal_failure_acceleration'], 3)} g)")
        other = "-"
        fl = irregular.get("four_link")
        if fl is not None:
            curve = fl["curve"]
            other = not_used_words(f"median collapse {number(curve['lognormal_median'], 3)} g "
                                   f"({fl['arches']} arches; the structure: "
                                   f"{number(curve['nominal_failure_acceleration'], 3)} g)",
                                   fl["off_by"])
        value = ("; ".join(text) or "-") + undecided_words(irregular)
        rows.append([f"irregular masonry (epsilon = {results['settings']['epsilon']:g}, "
                     f"{irregular['arches']} arches)", value, _model_words(irregular, agree),
                     other])
    check = s.get("record_check")
    for im, entry in (s.get("records") or {}).items():
        other = []
        fl = entry.get("four_link")
        if fl is not None:
            other.append(not_used_words(_record_value(fl), fl["off_by"]))
        if check is not None and im == "pga":
            other.append(check_words(check))
        rows.append([f"collapse under the records, {im_label(im)}",
                     _record_value(entry) + undecided_words(entry),
                     _model_words(entry, agree), "; ".join(other) or "-"])
    return rows


def model_text(results: dict) -> str:
    """Which model the first screen's numbers come from, and why, in one paragraph."""
    trusted = results.get("trusted")
    if trusted is None:
        return ""
    if trusted["model"] == "four-link":
        return (f"Model used: the four-link model (the paper's). Its numbers are given because "
                f"{trusted['reason']}; the rigid-block model's failure accelerations are beside "
                f"them, and the activation and the 5 % quantile of k~ are of the limit "
                f"analysis.")
    text = (f"Model used: the rigid-block model (every block rigid, any mechanism, sliding "
            f"with Coulomb friction; within 1 % of the discrete-element code LMGC90), because "
            f"{trusted['reason']}. Every collapse capacity and fragility on this screen is "
            f"the rigid-block model's; the four-link model's is shown beside it, marked "
            f"\"not used\", with how far it is off. The activation and the 5 % quantile of k~ "
            f"are of the limit analysis.")
    return text


def check_words(check: dict) -> str:
    """The check of the two models under the records, in a few words."""
    text = (f"at PGA {check['level_pga']:.3g} g the rigid blocks agree on "
            f"{check['both'] + check['neither']} of {check['pairs']} record-polarities")
    if check["rigid_blocks_only"]:
        text += f"; they collapse in {check['rigid_blocks_only']} where the four-link does not"
    if check["four_link_only"]:
        text += f"; survive {check['four_link_only']} where it collapses"
    if check.get("rigid_blocks_undecided"):
        text += f"; undecided in {check['rigid_blocks_undecided']}"
    return text


def undecided_warning_text(results: dict) -> str | None:
    """The warning the report opens with when the rigid blocks left more than
    :data:`archquake.studies.undecided.UNDECIDED_WARNING_FRACTION` of their analyses
    undecided (the failure domain and the check under the records), else None."""
    from ...studies.undecided import undecided_warning

    count = total = 0
    rb = (results.get("pulses") or {}).get("rigid_blocks") or {}
    if rb.get("undecided") is not None:
        count, total = rb["undecided"], rb["analyses"]
    check = (results.get("records") or {}).get("check") or {}
    if check.get("rigid_blocks_undecided") is not None:
        count += check["rigid_blocks_undecided"]
        total += check["pairs"]
    rigid = results.get("rigid_block_studies") or {}
    studies = [rigid["irregularity"]] if "irregularity" in rigid else []
    studies += list(((rigid.get("records") or {}).get("ims") or {}).values())
    for study in studies:
        undecided = study.get("undecided") or {}
        count += undecided.get("analyses", 0) + undecided.get("nominal_analyses", 0)
        total += undecided.get("of", 0) + undecided.get("nominal_of", 0)
    return undecided_warning(count, total, "rigid-block analyses")


def agreement_text(results: dict) -> str:
    """How far the two models agree, in one paragraph.

    Parameters
    ----------
    results : dict
        ``results.json``.

    Returns
    -------
    str
    """
    pulses = results["pulses"]
    if "agreement" not in pulses:
        return ("Only the rigid-block model describes this structure's collapse under pulses: "
                + results["four_link"].get("reason", "") + ".")
    a = pulses["agreement"]
    n, within = len(pulses["rows"]), len(a["within"])
    text = (f"How far the two models agree: their failure accelerations under Oppenheim's pulse "
            f"agree within {100 * a['band']:g} % at {within or 'none'} of the {n} pulse "
            f"durations")
    if a["from"] is not None:
        text += f" (every duration from t_p = {a['from']:.2f} s on)"
    if a["largest"] is not None:
        text += (f"; the largest difference is {percent(a['largest']['difference'])} at t_p = "
                 f"{a['largest']['duration']:.2f} s")
    only = a["only"]
    for name, durations in only.items():
        if durations:
            text += (f"; only the {MODEL_NAMES[name]} collapses in the scan at t_p = "
                     + ", ".join(f"{d:.2f}" for d in durations) + " s")
    disagreeing = a.get("disagreeing", [])
    text += (". Where one collapses and the other does not is hatched in Fig. 3"
             + (f" ({len(disagreeing)} duration{'s' if len(disagreeing) != 1 else ''})"
               if disagreeing else " (nowhere)") + ".")
    above = [r for r in pulses["rows"] if r["difference"] is not None
             and r["difference"] > a["band"]]
    if above:
        text += (f" Where they differ the four-link model overestimates the capacity at "
                 f"{len(above)} durations: the rigid-block model, which takes any mechanism "
                 f"and lets the blocks slide, is the more complete of the two.")
    trusted = results.get("trusted") or {}
    if trusted.get("model") == "rigid-blocks":
        text += (" So the fragility of irregular arches and against the records is computed "
                 "with the rigid-block model too, on the same arches' draws, pulses, records "
                 "and stripes, and that is the one used above; the four-link model's is beside "
                 "it (Sections 4 and 5). The rigid blocks also check the four-link model under "
                 "the records on the structure itself, at one PGA.")
    else:
        text += (" The fragility of irregular arches and against the records is of the "
                 "four-link model, which the rigid blocks confirm under pulses; they check it "
                 "under the records on the structure itself, at one PGA.")
    return text


# ------------------------------------------------------------------------------ structure
def structure_text(results: dict) -> str:
    """What the structure is and how it was analysed."""
    st = results["structure"]
    text = (f"The structure: {st['description']} ({st['blocks']} blocks). Limit analysis by "
            f"the static method (a linear program): the largest horizontal load multiplier k "
            f"for which a line of thrust in equilibrium with the weights and horizontal forces "
            f"k m_i g fits inside every joint, left to right (Mech-l) and right to left "
            f"(Mech-r).")
    safety = results["safety"]
    if safety.get("note"):
        text += f" Geometric safety factor: {safety['note']}"
        text += "." if safety.get("factor") is None else f": {safety['factor']:.3f}."
        inner = safety.get("thickness")
        if inner and inner.get("factor") is not None:
            text += f" The arch's own: {inner['note']}: {inner['factor']:.3f}."
    return text


def structure_caption(results: dict) -> str:
    """Caption of the drawing of the structure."""
    if results["limit"] is None:
        return (f"The structure drawn to scale [m]. {results['verdict']['reason'][:1].upper()}"
                f"{results['verdict']['reason'][1:]}.")
    limit = results["limit"]
    return (f"The structure drawn to scale [m], with the line of thrust at activation (blue: "
            f"the line of action of the resultant and its pressure points on the joints) and "
            f"the four hinges of each mechanism: left, forces left to right, k_l = "
            f"{limit['k_l']:.4f}; right, forces right to left, k_r = {limit['k_r']:.4f} (the "
            f"mirrored structure's analysis, drawn in the structure's own frame).")


def hinge_rows(results: dict) -> list[list[str]]:
    """Rows of the hinges' table: mechanism, hinge, where, face, x, y."""
    rows = []
    for d, mech in results["limit"]["mechanisms"].items():
        name = "Mech-l" if d == "l" else "Mech-r"
        k = results["limit"][f"k_{d}"]
        for i, h in enumerate(mech["hinges"]):
            rows.append([name if i == 0 else "", f"{k:.4f}" if i == 0 else "", h["label"],
                         h["where"], h["face"], f"{h['x']:.3f}", f"{h['y']:.3f}"])
    return rows


def sliding_text(sliding: dict) -> str:
    """What the table of sliding as well as rocking shows."""
    return (f"Sliding as well as rocking: with Coulomb friction {sliding['friction']:g} at every "
            "joint (the rigid-block model's), the limit analysis under the associative law "
            "(the classical linear program), under the non-associative one (slip without "
            "opening) and the rigid-block model's multiplier under a slowly growing "
            "acceleration, the arbiter. Where they equal Heyman's k above, no joint slides. Joints "
            "are numbered from the left end of the structure in its own frame (not mirrored).")


def sliding_rows(sliding: dict) -> list[list[str]]:
    """Rows of the sliding table: mechanism, law, k, rocking and sliding joints."""
    rows = []
    for d, laws in sliding["directions"].items():
        for i, (law, entry) in enumerate(laws.items()):
            k = "none" if entry["k"] is None else f"{entry['k']:.4f}"
            name = ("Mech-l" if d == "l" else "Mech-r") if i == 0 else ""
            rows.append([name, law, k,
                         ", ".join(map(str, entry["rocking"])) or "-",
                         ", ".join(map(str, entry["sliding"])) or "-"])
    return rows


# ------------------------------------------------------------------------------ four links
MECHANISM_QUANTITIES = (
    ("theta_u", "theta_u, undisplaced link AB [rad]", 4),
    ("ab", "|AB| [m]", 3), ("bc", "|BC| [m]", 3), ("cd", "|CD| [m]", 3),
    ("theta_cr", "theta_cr, critical angle [rad]", 4),
    ("phi_cr", "phi_cr = theta_u - theta_cr, critical rotation [rad]", 4),
    ("ratio", "theta_cr / theta_u [-]", 4),
    ("activation", "activation -F/P [g]", 4),
)
"""The quantities of a four-link mechanism in the report's table: key, label, decimals."""


def mechanism_rows(results: dict) -> list[list[str]]:
    """Rows of the four-link mechanisms' table: quantity, Mech-l, Mech-r."""
    m = results["four_link"]["mechanisms"]
    return [[label, number(m["l"][key], digits), number(m["r"][key], digits)]
            for key, label, digits in MECHANISM_QUANTITIES]


RESTITUTION_WORDS = {
    "computed": "momentum balance of the impact of this structure (the default)",
    "link": "the paper's link-wise rule (Housner's rule for the post-impact springing link)",
    "measured": "measured on the rigid-block model: the kinetic energy its blocks keep",
    "paper": "the paper's value for Oppenheim's arch",
    "elastic": "no energy lost at an impact",
}
"""What each restitution rule is, in words."""


def restitution_rows(results: dict) -> list[list[str]]:
    """Rows of the restitution table: rule, c_lr, c_rl, what it is."""
    used = results["four_link"]["used"]["rule"]
    rows = []
    for rule, pair in results["four_link"]["restitution"].items():
        mark = " (used)" if rule == used else ""
        if isinstance(pair, dict):
            rows.append([rule + mark, "-", "-", f"not available: {pair['error']}"])
        else:
            rows.append([rule + mark, f"{pair[0]:.4f}", f"{pair[1]:.4f}",
                         RESTITUTION_WORDS.get(rule, "")])
    if isinstance(used, float):
        pair = results["four_link"]["used"]["pair"]
        rows.append([f"{used:g} (used)", f"{pair[0]:.4f}", f"{pair[1]:.4f}", "imposed"])
    return rows


def mechanisms_text(results: dict) -> str:
    """The paragraph of the four-link part."""
    fl = results["four_link"]
    if not fl["applies"]:
        return (f"The four-link model does not apply to this structure: {fl['reason']}. Its "
                f"dynamics are those of the rigid-block model alone.")
    return ("The paper's four-link model: the structure rocks as three rigid blocks on the four "
            "hinges of its limit analysis (a four-bar linkage), one mechanism each way. It "
            "collapses when the rotation phi = theta_u - theta passes the critical rotation "
            "phi_cr, where the potential energy is largest; an impact closes the hinges and "
            "opens the other mechanism, losing kinetic energy by the coefficient of restitution "
            "c_v (c_lr from Mech-l to Mech-r, c_rl back).")


def mechanisms_caption(results: dict) -> str:
    """Caption of the potential energy of the mechanisms."""
    m = results["four_link"]["mechanisms"]
    return (f"Potential energy V(phi) - V(0) of the two four-link mechanisms per unit depth; its "
            f"maximum is the critical rotation, phi_cr = {m['l']['phi_cr']:.4f} rad (Mech-l) and "
            f"{m['r']['phi_cr']:.4f} rad (Mech-r): beyond it gravity no longer brings the "
            f"structure back.")


# ------------------------------------------------------------------------------ pulses
def domain_text(results: dict) -> str:
    """The paragraph of the failure domain."""
    p = results["pulses"]
    sizes = results["sizes"]
    d = p["durations"]
    rb = p["rigid_blocks"]
    text = (f"Oppenheim's pulse: the ground accelerates at -a g for t_p, then at +a g/2 for "
            f"2 t_p (the first pulse toward the weaker direction, "
            f"{'Mech-l' if p['direction'] == 'l' else 'Mech-r'}). Both models analysed "
            f"{len(d)} durations from {d[0]:.2f} to {d[-1]:.2f} s (the paper's 0.1-1.0 s scaled "
            f"to the size of the structure by {sizes['time_scale']:.3f}) on the same scan of "
            f"{len(p['amplitudes_g'])} amplitudes from {p['amplitudes_g'][0]:g} to "
            f"{p['amplitudes_g'][-1]:g} g, every boundary bisected to {p['resolution_g']:g} g. "
            f"The rigid-block model: every block rigid, Coulomb friction "
            f"{rb['model'].get('friction', '-')} at the joints; {rb['analyses']} analyses, "
            f"its scan screened by the four-link model ({rb['search']}).")
    text += _undecided_text(p)
    if "four_link" in p:
        c = p["four_link"][p["direction"]]["restitution"]
        text += (f" The four-link model: restitution '{results['four_link']['used']['rule']}', "
                 f"c_v = {number(c[0], 3)}.")
    return text


def _undecided_text(p: dict) -> str:
    """What the rigid blocks left undecided in the failure domain, in words (a result kept
    before they were counted says nothing)."""
    count = p["rigid_blocks"].get("undecided")
    if count is None:
        return ""
    text = f" Of its analyses {count} were left undecided"
    bands = [(r["duration"], r["rigid_blocks_undecided_bands"]) for r in p["rows"]
             if r.get("rigid_blocks_undecided_bands")]
    if not bands:
        return text + "."
    text += (": undecided amplitudes at " + "; ".join(
        f"t_p = {d:.2f} s, " + ", ".join(f"{a:.3f}-{b:.3f} g" for a, b in bs)
        for d, bs in bands) + ". A failure acceleration above an undecided band is not "
        "decided: the table gives the range it lies in (a-b), and no difference.")
    return text


def domain_rows(results: dict) -> list[list[str]]:
    """Rows of the failure accelerations' table, per duration (the rigid blocks' failure
    acceleration as the range ``a-b`` it lies in where an undecided band starts at ``a`` below
    it)."""
    p = results["pulses"]
    top = p["amplitudes_g"][-1]
    rows = []
    for r in p["rows"]:
        def cell(v):
            return f"> {top:g}" if v is None else f"{v:.3f}"

        rigid = cell(r["rigid_blocks"])
        low = r.get("rigid_blocks_undecided_from")
        if low is not None:
            rigid = f"{low:.3f}-" + ("" if r["rigid_blocks"] is None else rigid)
        row = [f"{r['duration']:.2f}", cell(r["four_link"]), rigid,
               percent(r["difference"])]
        if "four_link" in p:
            row.append(cell(r.get("four_link_first_half_cycle")))
            row.append(cell(r.get("four_link_other_direction")))
        rows.append(row)
    return rows


def domain_header(results: dict) -> list[str]:
    """Header of the failure accelerations' table."""
    header = ["t_p [s]", "four-link [g]", "rigid blocks [g]", "difference"]
    if "four_link" in results["pulses"]:
        other = "Mech-r" if results["pulses"]["direction"] == "l" else "Mech-l"
        header += ["four-link, first half cycle [g]", f"four-link, the other way ({other}) [g]"]
    return header


def domain_caption(results: dict) -> str:
    """Caption of the failure domain."""
    p = results["pulses"]
    if "four_link" not in p:
        return ("Failure domain of the rigid-block model under Oppenheim's pulse: rest, "
                "recovery and collapse over pulse duration and amplitude.")
    return ("Failure domain under Oppenheim's pulse of duration t_p and amplitude a: the "
            "four-link model's regions (grey: no motion, below k; green: (1) recovery; orange: "
            "(2) collapse after impacts; red: (3) collapse in the first half cycle) and failure "
            "curve (dots), the rigid-block model's failure curve (red squares), and, hatched, "
            "where one model collapses and the other does not (red: only the rigid blocks "
            "collapse, the four-link model is unconservative; blue: only the four-link model "
            f"collapses), where that band is wider than "
            f"{p['disagreement_shown_above_g']:g} g, twice the bisection width.")


# ------------------------------------------------------------------------------ irregularity
def irregularity_text(results: dict) -> str:
    """The paragraph of the irregularity part."""
    irr = results["irregularity"]
    if "skipped" in irr:
        return f"Not assessed: {irr['skipped']}."
    s = irr["settings"]
    ls = irr["limit_sample"]
    text = (f"Irregular arches drawn around the structure by the paper's eq. (1) with epsilon "
            f"= {s['epsilon']:g} (every voussoir's angle, thickness and radius perturbed by up "
            f"to epsilon times a fraction of the nominal; seed {s['seed']}): the limit analysis "
            f"of s = {ls['count']} of them gives the distribution of k~ = min(k~_l, k~_r): mean "
            f"{number(ls['mean'])}, standard deviation {number(ls['std'])}, "
            f"{100 * (ls['fraction_below_nominal'] or 0):.1f} % below the structure's k")
    q = ls.get("quantiles")
    if q:
        text += f", 5 % quantile {q['0.05']:.4f}"
    text += (f". h = {irr['analysed']} of them under Oppenheim's pulse at t_p = "
             + ", ".join(f"{d:g}" for d in s["durations"])
             + f" s (the paper's 0.4-0.7 s scaled), amplitudes {s['amplitudes_g'][0]:g}-"
               f"{s['amplitudes_g'][-1]:g} g in {len(s['amplitudes_g'])} steps, each arch with "
               f"its own restitution ('{s['restitution']}'): P_F = h_f/h (eq. 9), an arch failing "
               f"when it collapses in either direction.")
    excluded = irr["arches"].get("excluded", 0) if isinstance(irr.get("arches"), dict) else 0
    if excluded:
        text += f" {excluded} drawn arches could not be analysed and are left out."
    return text


def irregularity_rows(results: dict, rigid: bool = False) -> list[list[str]]:
    """Rows of the irregularity table, per duration (``rigid``: of the rigid-block model's
    study, with its undecided analyses)."""
    if not rigid:
        return [[f"{c['duration']:.2f}", number(c["nominal_failure_acceleration"], 3),
                 number(c["lognormal_median"], 3), number(c["lognormal_dispersion"], 3),
                 number(c["probability_below_nominal"], 3)]
                for c in results["irregularity"]["durations"]]
    rows = []
    for c in results["rigid_block_studies"]["irregularity"]["durations"]:
        below = number(c["probability_below_nominal"], 3)
        if c.get("probability_below_nominal_upper") is not None:
            below += f"-{c['probability_below_nominal_upper']:.3f}"
        rows.append([f"{c['duration']:.2f}", number(c["nominal_failure_acceleration"], 3),
                     number(c["lognormal_median"], 3), number(c["lognormal_dispersion"], 3),
                     below, str(c["undecided"])])
    return rows


def rigid_irregularity_text(results: dict) -> str:
    """The paragraph of the rigid-block model's study of irregular arches."""
    study = results["rigid_block_studies"]["irregularity"]
    undecided = study["undecided"]
    return (f"With the rigid-block model (used on the first screen: the two models disagree "
            f"under pulses): the same h = {study['analysed']} irregular arches (the same "
            f"draws, seed {study['seed']}), durations and amplitudes, friction "
            f"{study['settings']['friction']:g}, time step {study['settings']['time_step']:g} s"
            f" (coarse factor {study['settings']['coarse_factor']}). Of its "
            f"{undecided['of']} analyses {undecided['analyses']} were left undecided (and "
            f"{undecided['nominal_analyses']} of the structure's own): neither collapses nor "
            f"survivals; where P_F has bounds the table gives both (undecided as survivals - "
            f"as collapses). The figure above is the four-link model's.")


def _figure_model_text(results: dict, study: str) -> str:
    """Which model a figure of the four-link studies draws, and where the rigid-block model's
    numbers are when they are the ones used."""
    if study not in (results.get("rigid_block_studies") or {}):
        return f" {MODEL_NAMES['four-link'][:1].upper()}{MODEL_NAMES['four-link'][1:]}."
    return (" Four-link model (not used on the first screen); the rigid-block model's study, "
            "used there, is in the table below.")


def irregularity_caption(results: dict, durations) -> str:
    """Caption of the fragility curves of the irregular arches."""
    irr = results["irregularity"]
    return ("Fragility of the irregular arches (epsilon = "
            f"{irr['settings']['epsilon']:g}) under Oppenheim's pulse at t_p = "
            + " and ".join(f"{d:.2f}" for d in durations)
            + " s: the fraction P_F of arches that collapse (dots), the paper's fifth-degree "
              "fit (dashed) and a lognormal fit (grey); in blue the CDF of k~ by limit analysis "
              "and the structure's k; the black dash-dot line is the structure's own failure "
              "acceleration, where its step fragility (the paper's eq. 10) jumps from 0 to 1. "
              "P_F > 0 left of it: irregular arches fail where the regular one would not."
            + _figure_model_text(results, "irregularity"))


# ------------------------------------------------------------------------------ records
def record_text(results: dict) -> str:
    """The paragraph of the record-based fragility."""
    rec = results["records"]
    if "skipped" in rec:
        return f"Not assessed: {rec['skipped']}."
    first = next(iter(rec["ims"].values()))
    alone = bool(first.get("structure_only"))
    text = f"Records: {rec['suite']['description']}." + (f" {rec['note']}" if rec["note"]
                                                          else "")
    if alone:
        text += (f" Multiple-stripe analysis of the structure alone (no irregular arches are "
                 f"drawn around a surveyed arch): every record scaled to each of "
                 f"{len(first['levels'])} levels of each intensity measure and applied in both "
                 f"polarities, with the four-link model; a record fails the structure if it "
                 f"collapses it in either polarity.")
    else:
        text += (f" Multiple-stripe analysis: every record scaled to each of "
                 f"{len(first['levels'])} levels of each intensity measure and applied in both "
                 f"polarities to the structure and to h = {first['sample_size']} irregular "
                 f"arches (epsilon = {results['settings']['epsilon']:g}), with the four-link "
                 f"model; an arch-record pair fails if it collapses in either polarity.")
    text += (" The levels span the PGA at which the records first collapse the structure (a "
             "pilot on a grid from k to 30 k), widened by 0.8 below"
             + ("" if alone else f" (times {rec['weaker']:.2f}, the 5 % quantile of k~ over k, "
                                 f"for the weaker irregular arches)")
             + " and 1.25 above. Lognormal fragility functions P(collapse | IM) = "
               "Phi(ln(IM/median)/beta) fitted by maximum likelihood (Baker 2015)"
             + ("; beta is the record-to-record dispersion." if alone else
                ": the total beta pools every pair; record-to-record is the structure's own "
                "fit; geometric, the spread of the irregular arches for the same records."))
    check = rec.get("check")
    if check is not None:
        text += (f" A check of the four-link model by the rigid blocks: the structure itself "
                 f"under {check['pairs'] // 2} of the records (the fault-normal components "
                 f"first) scaled to PGA = {check['level_pga']:.3g} g (the median "
                 f"of the PGAs at which the records first collapse it), both polarities: the "
                 f"two models agree on {check['both'] + check['neither']} of {check['pairs']} "
                 f"(both collapse in {check['both']}, neither in {check['neither']}; only the "
                 f"rigid blocks in {check['rigid_blocks_only']}, only the four-link model in "
                 f"{check['four_link_only']}"
                 + (f"; the rigid blocks undecided in {check['rigid_blocks_undecided']}"
                    if check.get("rigid_blocks_undecided") is not None else "") + ").")
    files = [e["nrml"] for e in rec["ims"].values() if e["nrml"]]
    if files:
        text += (" The fits are written as OpenQuake NRML fragility models (continuous logncdf, "
                 "limit state 'collapse'; "
                 + ("" if alone else "'masonry-arch' the irregular arches, ")
                 + "'masonry-arch-nominal' the structure): " + ", ".join(files) + ".")
    return text


def record_rows(results: dict, rigid: bool = False) -> list[list[str]]:
    """Rows of the record-based fragility's table, per intensity measure (``rigid``: of the
    rigid-block model's study, with its undecided analyses in the last column)."""
    rows = []
    ims = (results["rigid_block_studies"]["records"] if rigid else results["records"])["ims"]
    for im, e in ims.items():
        last = (e["nrml"] or "-") if not rigid else (
            f"{e['undecided']['analyses']} of {e['undecided']['of']}"
            + ("" if "nominal_analyses" not in e["undecided"] else
               f" (the structure: {e['undecided']['nominal_analyses']})"))
        rows.append([f"{im_label(im)} [{e['unit']}]", f"{e['levels'][0]:.3g}-"
                     f"{e['levels'][-1]:.3g}", number(e["lognormal"]["median"], 3),
                     number(e["total"], 3), number(e["nominal_lognormal"]["median"], 3),
                     number(e["record_to_record"], 3), number(e["geometric"], 3), last])
    return rows


def rigid_record_text(results: dict) -> str:
    """The paragraph of the rigid-block model's record-based fragility."""
    ims = results["rigid_block_studies"]["records"]["ims"]
    first = next(iter(ims.values()))
    who = ("the structure alone" if first.get("structure_only") else
           f"the structure and h = {first['sample_size']} irregular arches (the first of the "
           f"same draws)")
    return (f"With the rigid-block model (used on the first screen: the two models disagree "
            f"under pulses): {who} under the same records at the same stripes, both "
            f"polarities. An undecided pair is neither a collapse nor a survival: the fits "
            f"(as every study's point estimate) count it as a survival, a lower bound of "
            f"P_F, and where there is one the first screen also gives the median with it "
            f"counted as a collapse, and the count. The NRML files fragility_<im>.xml are "
            f"the rigid-block model's (the fragility a risk study reads), the four-link "
            f"model's beside them as fragility_<im>_four_link.xml; the figure is the "
            f"four-link model's.")


def record_list_rows(results: dict) -> list[list[str]]:
    """Rows of the records' table: each record's metadata and the level at which it first
    collapses the structure."""
    rows = []
    ims = results["records"]["ims"]
    near = str(results["records"]["suite"].get("name", "")).startswith("fema-p695-near")
    for r in results["records"]["records"]:
        component = str(r.get("component", "-"))
        if near:
            component = {"a": "a, fault-normal", "b": "b, fault-parallel"}.get(component,
                                                                            component)
        cells = [r["name"], str(r.get("event", "-")), str(r.get("year", "-")),
                 str(r.get("station", "-")), number(r.get("magnitude"), 1), component,
                 f"{r['pga']:.3f}", f"{r['pgv']:.3f}"]
        for im in ims:
            cells.append(number(ims[im]["first_collapse"].get(r["name"]), 3))
        rows.append(cells)
    return rows


def record_list_header(results: dict) -> list[str]:
    """Header of the records' table."""
    return (["record", "event", "year", "station", "M", "component", "PGA [g]", "PGV [m/s]"]
            + [f"first collapse, {im_label(im)} [{e['unit']}]"
               for im, e in results["records"]["ims"].items()])


def record_caption(results: dict) -> str:
    """Caption of the record-based fragility."""
    rec = results["records"]
    first = next(iter(rec["ims"].values()))
    if first.get("structure_only"):
        return (f"P(collapse | IM) of the structure against {first['records']} ground motions "
                f"in both polarities: squares, the fraction of the records that collapse it at "
                f"each stripe; dashed, the lognormal fit and its 90 % bootstrap band. "
                + "; ".join(f"{im_label(im)}: median {number(e['nominal_lognormal']['median'], 3)}"
                            f" {e['unit']}, beta {number(e['record_to_record'], 3)}"
                            for im, e in rec["ims"].items()) + "."
                + _figure_model_text(results, "records"))
    return (f"P(collapse | IM) against {first['records']} ground motions in both polarities: "
            f"black dots, the {first['analysed']} irregular arches; line, the lognormal fit and "
            f"(grey) its 90 % bootstrap band; blue squares and dashed line, the structure "
            f"itself. " + "; ".join(
                f"{im_label(im)}: median {number(e['lognormal']['median'], 3)} {e['unit']}, "
                f"beta {number(e['total'], 3)}" for im, e in rec["ims"].items()) + "."
            + _figure_model_text(results, "records"))


# ------------------------------------------------------------------------------ the run
def reduced_text(results: dict) -> str:
    """What an assessment reduced to meet its time budget, in one paragraph."""
    z = results["sizes"]
    s = results["settings"]
    parts = [f"{z['pulse_durations']} pulse durations for both failure domains (the paper's "
             f"Fig. 16 has 37), {s['amplitude_points']} amplitudes bisected to "
             f"{s['domain_resolution_g']:g} g"]
    if z.get("fragility_arches") is not None:
        parts.append(f"h = {z['fragility_arches']} irregular arches under pulses (the paper: "
                     f"40) and s = {z['limit_arches']} by limit analysis (the paper: 1000)")
    if z.get("record_arches") is not None:
        parts.append(f"h = {z['record_arches']} irregular arches under {z['records']} of the "
                     f"suite's {z['suite_records']} ground motions at {z['levels']} levels "
                     f"(a full study: 40 arches, 20 levels), {s['bootstrap']} bootstrap "
                     f"resamples")
    if z.get("rigid_block_fragility_arches") is not None:
        parts.append(f"with the rigid-block model (used on the first screen), h = "
                     f"{z['rigid_block_fragility_arches']} irregular arches under the same "
                     f"pulses")
    if z.get("rigid_block_record_arches") is not None:
        parts.append(f"h = {z['rigid_block_record_arches']} irregular arches under the same "
                     f"records and stripes (a rigid-block analysis of a record costs about "
                     f"four thousand four-link ones)")
    text = "Study sizes, chosen to fit the time budget: " + "; ".join(parts) + "."
    if not (z.get("rigid_block_fragility_arches") or z.get("rigid_block_record_arches")):
        text += (" The rigid-block model runs on the structure itself (under pulses, and under "
                 "the records at one PGA): the two models agree, and the studies of irregular "
                 "arches and records are the four-link model's.")
    if s["quick"]:
        text = ("QUICK RUN: reduced sizes for a smoke test, not an assessment. " + text)
    return text


def command_text(results: dict) -> list[str]:
    """The commands that regenerate the report."""
    out = []
    given = results["command"].get("given")
    if given:
        out.append(f"As run: {given}")
    out.append(f"From the files it wrote: {results['command']['regenerate']}")
    if results["command"].get("note"):
        out.append(results["command"]["note"])
    return out


__all__ = ["ASSUMPTIONS", "MECHANISM_QUANTITIES", "MODEL_NAMES", "RESTITUTION_WORDS",
           "agreement_text", "check_words", "collapse_text", "command_text", "difference_words",
           "domain_caption", "domain_header", "domain_rows", "domain_text", "heading",
           "hinge_rows", "im_label", "irregularity_caption", "irregularity_rows",
           "irregularity_text", "mechanism_rows", "mechanisms_caption", "mechanisms_text",
           "model_text", "not_used_words", "record_caption", "record_list_header",
           "record_list_rows", "record_rows", "record_text", "reduced_text", "restitution_rows",
           "rigid_irregularity_text", "rigid_record_text", "structure_caption", "structure_text",
           "summary_rows", "undecided_words", "verdict_text"]
