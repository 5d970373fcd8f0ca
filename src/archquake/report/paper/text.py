"""The words of the paper's report: captions, paragraphs and table rows, each written from
values.

Every sentence that states a number or a verdict is written here from the values a part returned
(:mod:`archquake.report.paper.parts`) or their JSON form (``results.json``), never by hand, with
the formatters of every report (:mod:`archquake.report.formatting`); :func:`run_info` serves any
report.
"""

from __future__ import annotations

from ..formatting import agree, number, outcome_text, percent, signed
from ..render import Paragraph, Table
from .parts import below_nominal, comparison_statistics, paper_q, q_agrees
from .settings import AGREEMENT_BAND


def restitution_label(case: str, pair) -> str:
    """The coefficient of restitution of a case in words: ``"c_v = 0.875 (paper's)"``.

    Parameters
    ----------
    case : str
        ``"paper"`` or ``"computed"``.
    pair : (float, float)
        ``(c_lr, c_rl)`` [-].

    Returns
    -------
    str
    """
    name = "paper's" if case == "paper" else "computed"
    return f"c_v = {pair[0]:.3f} ({name})"


def oppenheim_text(paper: dict) -> str:
    """Oppenheim's arch as the paper gives it: radius, embrace, thickness, voussoirs.

    Parameters
    ----------
    paper : dict
        The paper's values (:func:`archquake.reference_arches.paper_values`).

    Returns
    -------
    str
    """
    a = paper["oppenheim"]
    return (f"R = {a['radius']:g} m, alpha = {a['embrace_deg']:g} deg, t = {a['thickness']:g} m, "
            f"n = {a['voussoirs']}")


# ------------------------------------------------------------------------------ captions
def nominal_arch_caption(table1: dict) -> str:
    """Caption of the nominal arch's hinges and thrust line beside the paper's (Fig. 2).

    Parameters
    ----------
    table1 : dict
        :func:`archquake.report.paper.parts.limit_table`.

    Returns
    -------
    str
    """
    paper_k = table1["NA"]["paper"]["k"]
    return (f"Collapse hinges and thrust line of Oppenheim's arch NA. The paper's Fig. 2 "
            f"shows hinges A, B, C, D at joints {table1['NA']['paper']['joints']} "
            f"(intrados, extrados, intrados, extrados) and k = {paper_k:.4f}; ours: "
            f"joints {table1['NA']['joints_l']}, k = {table1['NA']['k']:.4f} - "
            f"{agree(table1['NA']['agrees'])}.")


IRREGULAR_ARCHES_CAPTION = (
    "Collapse hinges and thrust lines of the irregular arches RA-1 and RA-2 (black) over the "
    "nominal arch (red); Mech-r on the mirrored arch. The paper's Fig. 4 shows the same for its "
    "own two random arches, whose geometry is not given: these are two arches drawn with the "
    "report's seed, so only the kind of result is comparable (hinges move away from the nominal "
    "joints, k~_l differs from k~_r).")
"""Caption of the irregular arches' hinges (Fig. 4): the paper's arches are not given."""


def potential_energy_caption(table3: dict) -> str:
    """Caption of the potential energy of the mechanisms beside the paper's (Figs. 6-8).

    Parameters
    ----------
    table3 : dict
        Table 3 (:func:`archquake.report.paper.parts.mechanism_tables`).

    Returns
    -------
    str
    """
    ours, ref = table3["NA"]["l"]["phi_cr"], table3["NA"]["paper"]["phi_cr"]
    return (f"Potential energy V(phi) - V(0) of the four-link mechanisms (eq. 3). The "
            f"paper's Fig. 6 has its maximum at phi_cr = {ref:.4f} rad for NA; ours at "
            f"{ours:.4f} rad - {agree(table3['NA']['agrees'])}. Figs. 7-8 show the "
            f"paper's random arches (phi_cr 0.1765/0.1545 and 0.1723/0.0627 rad); ours "
            f"are other draws: phi_cr = {table3['RA-1']['l']['phi_cr']:.4f}/"
            f"{table3['RA-1']['r']['phi_cr']:.4f} (RA-1) and "
            f"{table3['RA-2']['l']['phi_cr']:.4f}/{table3['RA-2']['r']['phi_cr']:.4f} "
            f"rad (RA-2), Mech-l/Mech-r.")


def free_vibration_figures(case: str) -> str:
    """The paper's figures of the free vibrations with a case: ``"Figs. 9-11"`` (elastic) or
    ``"Figs. 12-14"``.

    Parameters
    ----------
    case : str

    Returns
    -------
    str
    """
    return "Figs. 9-11" if case == "elastic" else "Figs. 12-14"


def free_vibration_caption(case: str, pair, agrees: bool) -> str:
    """Caption of the free vibrations of the three arches with one case (Figs. 9-14).

    Parameters
    ----------
    case : str
        ``"elastic"``, ``"paper"`` or ``"computed"``.
    pair : (float, float)
        Its ``(c_lr, c_rl)`` [-].
    agrees : bool
        :meth:`archquake.report.paper.parts.FreeVibrations.agrees`.

    Returns
    -------
    str
    """
    if case == "elastic":
        claim = ("with c_v = 1 the amplitude of the oscillation differs between the "
                 "directions but stays constant in each")
    else:
        claim = (f"with c_v < 1 (the paper uses 0.875; here {restitution_label(case, pair)}) the "
                 "amplitude in each direction decreases with time")
    return (f"Free vibrations of NA, RA-1 and RA-2 released at phi0 = 0.02 rad with "
            f"zero velocity (+phi in Mech-l, -phi' in Mech-r). Paper "
            f"({free_vibration_figures(case)}): {claim}. Ours: {agree(agrees)} for all three "
            f"arches.")


def pulse_response_caption(summary: dict, case: str) -> str:
    """Caption of the responses to Oppenheim's pulse with one case (Fig. 15), the nominal
    arch's outcomes beside the paper's.

    Parameters
    ----------
    summary : dict
        :attr:`archquake.report.paper.parts.PulseResponses.summary`.
    case : str

    Returns
    -------
    str
    """
    entry = summary[case]
    parts = []
    for row in entry["cases"]:
        na = row["NA"]
        parts.append(f"t_p = {row['duration']:.2f} s: paper {outcome_text(**na['paper'])}, ours "
                     f"{outcome_text(na['status'], na['half_cycle'])} ({agree(na['agrees'])})")
    return ("Response to Oppenheim's pulse xg''/g = -1 (a) of NA (blue), RA-1 (red) "
            f"and RA-2 (green), {restitution_label(case, entry['restitution'])}; open circles "
            "mark impacts, a dotted line the point of no return of a collapse, after which phi "
            "grows to the kinematic limit. "
            "Nominal arch - " + "; ".join(parts) + f". Overall: "
            f"{agree(entry['nominal_agrees'])}.")


def failure_domain_caption(summary: dict) -> str:
    """Caption of the failure domain of the nominal arch and point Q (Fig. 16).

    Parameters
    ----------
    summary : dict
        :attr:`archquake.report.paper.parts.FailureDomainPart.summary`.

    Returns
    -------
    str
    """
    q = summary["q_tp040"]["paper"]
    return ("Failure domain of Oppenheim's arch (epsilon = 0) under Oppenheim's pulse "
            "of duration t_p and amplitude xg''/g, c_v = "
            f"{summary['restitution'][0]:.3f}: recovery, collapse after impacts "
            "(second half cycle or later), collapse in the first half cycle; "
            f"dashed: k = {summary['activation']:.4f}, below which the arch does not "
            "move. At short durations the outcome is not monotone in the amplitude "
            "(bands of recovery inside the collapse region). The paper reads "
            f"Q = (0.40 s, {paper_q():.2f} g) off its failure curve; ours {q:.3f} g - "
            f"{agree(q_agrees(q))}.")


def fragility_curve_caption(result, curve: dict) -> str:
    """Caption of the fragility curve at one duration (Figs. 17-20).

    Parameters
    ----------
    result : FragilityResult
        The study.
    curve : dict
        Its entry for the duration (:attr:`archquake.report.paper.parts.FragilityPart.curves`).

    Returns
    -------
    str
    """
    duration = curve["duration"]
    below = curve["probability_below_nominal"]
    paper = f" (the paper: {paper_q():.2f} g)" if abs(duration - 0.4) < 1e-9 else ""
    return (f"Fragility curve at t_p = {duration:.2f} s: P_F = h_f/h (eq. 9) of "
            f"h = {result.settings.sample_size} irregular arches, an arch failing when "
            "it collapses under the pulse in either direction, with the paper's "
            "fifth-degree polynomial and a lognormal fit; blue: CDF of "
            "k~ = min(k~_l, k~_r) of "
            f"s = {result.limit_load_multipliers.size} arches by limit analysis; "
            "vertical lines: the nominal arch's k (blue) and failure acceleration "
            f"{nominal_q(curve)} g{paper} (black). The paper's point: irregular arches "
            "may fail below the nominal failure acceleration (P_F > 0 left of the "
            f"black line, where eq. 10 gives 0); ours: P_F = {number(below, 3)} at the "
            f"last step below it - {agree(below_nominal(curve))}.")


def fragility_surface_caption(result, curves: list) -> str:
    """Caption of the fragility surface beside the nominal arch's step surface (Fig. 21).

    Parameters
    ----------
    result : FragilityResult
        The study.
    curves : list of dict
        :attr:`archquake.report.paper.parts.FragilityPart.curves`.

    Returns
    -------
    str
    """
    below = [c for c in curves if below_nominal(c)]
    where = ", ".join(f"{c['duration']:.2f} s" for c in below) or "none"
    return ("Fragility surface P_F(t_p, xg''/g) of the irregular arches (epsilon = "
            f"{result.settings.epsilon:.2f}), plane facets between the fragility "
            "curves as in the paper, with the nominal arch's step surface (eq. 10, "
            "the paper's 'cylinder'). The paper's point: part of the surface lies at "
            "lower accelerations than the cylinder, where the nominal arch predicts "
            f"P_F = 0; ours: P_F > 0 below the nominal failure acceleration at "
            f"t_p = {where} - {agree(bool(below))}.")


def comparison_caption(agrees: bool) -> str:
    """Caption of the two models' failure accelerations side by side.

    Parameters
    ----------
    agrees : bool
        :func:`archquake.report.paper.parts.long_pulses_agree`.

    Returns
    -------
    str
    """
    return ("Failure acceleration of Oppenheim's arch under Oppenheim's pulse in the "
            "rigid-block model (black) and in the four-link model with each "
            "restitution model (left), and their relative difference (right). "
            "For long pulses (t_p >= 0.7 s) the two models should agree within 5 %: "
            + ("they do" if agrees else "they do not") + " - " + agree(agrees) + ".")


def record_fragility_caption(summary: dict) -> str:
    """Caption of the record-based fragility in PGA and PGV.

    Parameters
    ----------
    summary : dict
        :attr:`archquake.report.paper.parts.RecordFragilityPart.summary`.

    Returns
    -------
    str
    """
    parts = []
    for im, entry in summary.items():
        fit = entry["lognormal"]
        parts.append(f"{im.upper()}: median {number(fit['median'], 3)} {entry['unit']}, "
                     f"dispersion {number(fit['dispersion'], 3)}")
    first = next(iter(summary.values()))
    return (f"P(collapse | IM) of {first['sample_size']} irregular arches under "
            f"{first['records']} synthetic records in both polarities (black dots: "
            "the stripes; line: lognormal fit by maximum likelihood, grey its 90 % "
            "bootstrap band) and of the nominal arch (blue squares, dashed fit): "
            + "; ".join(parts) + ". The paper has no such figure (its conclusion "
            "names earthquake excitation as further work).")

# ------------------------------------------------------------------------------ tables
def table1_rows(table1: dict) -> list[list[str]]:
    """Rows of Table 1: NA beside the paper's values, RA-1 and RA-2 beside the paper's rows
    (other arches: for scale only).

    Parameters
    ----------
    table1 : dict
        ``results["table1"]`` (:func:`archquake.report.paper.parts.limit_table`).

    Returns
    -------
    list of list of str
        Arch and mechanism, quantity, paper, ours, difference.
    """
    na = table1["NA"]
    rows = [["NA, Mech-l", "k", number(na["paper"]["k"]), number(na["k_l"]),
             signed(na["difference"]["k"])]]
    for label, ref, ours, diff in zip("ABCD", na["paper"]["beta"], na["beta_l"],
                                      na["difference"]["beta"], strict=True):
        rows.append(["NA, Mech-l", f"beta_{label} [rad]", number(ref), number(ours),
                     signed(diff)])
    rows.append(["NA, Mech-r", "k", number(na["paper"]["k"]), number(na["k_r"]),
                 signed(na["k_r"] - na["paper"]["k"])])
    for name in ("RA-1", "RA-2"):
        ra = table1[name]
        printed, text = ra["paper_printed"], ra["paper_text"]
        for d in ("l", "r"):
            mech = "Mech-l" if d == "l" else "Mech-r"
            rows.append([f"{name}, {mech}", "k~",
                         f"{number(printed['load_multiplier_' + d])} "
                         f"(text {number(text['k_' + d])})",
                         number(ra["k_" + d]), "other arch"])
            rows.append([f"{name}, {mech}", "beta A, B, C, D [rad]",
                         ", ".join(number(b) for b in printed["beta_" + d]),
                         ", ".join(number(b) for b in ra["beta_" + d]), "other arch"])
    return rows


TABLE2_KEYS = (("theta_u", "theta_u [rad]"), ("theta_bc_u", "theta_BC(theta_u) [rad]"),
               ("theta_cd_u", "theta_CD(theta_u) [rad]"), ("ab", "AB [m]"), ("bc", "BC [m]"),
               ("cd", "CD [m]"))
"""The quantities of Table 2 and their labels."""


def table2_rows(table2: dict) -> list[list[str]]:
    """Rows of Table 2: the mechanisms of NA beside the paper's, RA-1 and RA-2 beside its rows.

    Parameters
    ----------
    table2 : dict
        ``results["table2"]`` (:func:`archquake.report.paper.parts.mechanism_tables`).

    Returns
    -------
    list of list of str
    """
    rows = []
    na, ra1, ra2 = table2["NA"], table2["RA-1"], table2["RA-2"]
    for key, label in TABLE2_KEYS:
        rows.append([label, number(na["paper"][key]), number(na["l"][key]),
                     number(na["r"][key]), signed(na["difference"][key]),
                     number(ra1["paper"][key]), number(ra1["l"][key]),
                     number(ra2["paper"][key]), number(ra2["l"][key])])
    rows.append(["theta'_u (Mech-r) [rad]", number(na["paper"]["theta_u"]), "-",
                 number(na["r"]["theta_u"]), signed(na["r"]["theta_u"] - na["paper"]["theta_u"]),
                 number(ra1["paper"]["theta_u_r"]), number(ra1["r"]["theta_u"]),
                 number(ra2["paper"]["theta_u_r"]), number(ra2["r"]["theta_u"])])
    return rows


def table3_rows(table3: dict) -> list[list[str]]:
    """Rows of Table 3: the critical angles of NA beside the paper's, RA-1 and RA-2 beside its
    rows.

    Parameters
    ----------
    table3 : dict
        ``results["table3"]`` (:func:`archquake.report.paper.parts.mechanism_tables`).

    Returns
    -------
    list of list of str
    """
    na = table3["NA"]
    ref = na["paper"]
    rows = [[f"NA, Mech-{d}", number(ref["theta_cr"]), number(na[d]["theta_cr"]),
             number(ref["phi_cr"]), number(na[d]["phi_cr"]), number(ref["ratio"], 3),
             number(na[d]["ratio"], 3), signed(na[d]["ratio"] - ref["ratio"], 4)]
            for d in ("l", "r")]
    for name in ("RA-1", "RA-2"):
        ref = table3[name]["paper"]
        for d in ("l", "r"):
            ours = table3[name][d]
            rows.append([f"{name}, {'Mech-l' if d == 'l' else 'Mech-r'}",
                         number(ref["theta_cr_" + d]), number(ours["theta_cr"]),
                         number(ref["phi_cr_" + d]), number(ours["phi_cr"]),
                         number(ref["ratio_" + d], 3), number(ours["ratio"], 3), "other arch"])
    return rows


def agreement_rows(results: dict) -> list[list[str]]:
    """Rows of the agreement table: every quantity of the nominal arch the paper prints, ours
    beside it (Tables 1-3, the outcomes of Fig. 15, point Q).

    Parameters
    ----------
    results : dict
        ``results.json``.

    Returns
    -------
    list of list of str
        Quantity, paper, ours, difference (or verdict).
    """
    t1, t2, t3 = results["table1"]["NA"], results["table2"]["NA"], results["table3"]["NA"]
    rows = [["k (Table 1)", number(t1["paper"]["k"]), number(t1["k"]),
             signed(t1["difference"]["k"])]]
    for label, ref, ours in zip("ABCD", t1["paper"]["beta"], t1["beta_l"], strict=True):
        rows.append([f"beta_{label} [rad] (Table 1)", number(ref), number(ours),
                     signed(ours - ref)])
    for key, label in TABLE2_KEYS:
        rows.append([f"{label} (Table 2)", number(t2["paper"][key]), number(t2["l"][key]),
                     signed(t2["difference"][key])])
    for key, label, digits in (("theta_cr", "theta_cr [rad]", 4), ("phi_cr", "phi_cr [rad]", 4),
                               ("ratio", "theta_cr/theta_u", 3)):
        rows.append([f"{label} (Table 3, Sect. 4.2)", number(t3["paper"][key], digits),
                     number(t3["l"][key], digits), signed(t3["difference"][key], 4)])
    pulses = results["pulse"]["paper"]
    for row in pulses["cases"]:
        na = row["NA"]
        rows.append([f"Fig. 15, NA, t_p = {row['duration']:.2f} s, c_v = "
                     f"{pulses['restitution'][0]:.3f}", outcome_text(**na["paper"]),
                     outcome_text(na["status"], na["half_cycle"]), agree(na["agrees"])])
    if "failure_domain" in results:
        q = results["failure_domain"]["q_tp040"]["paper"]
        rows.append([f"Q: failure acceleration at t_p = 0.40 s [g], c_v = "
                     f"{pulses['restitution'][0]:.3f}", number(paper_q(), 2), number(q, 3),
                     signed(q - paper_q(), 3)])
    return rows


def restitution_rows(results: dict) -> list[list[str]]:
    """Rows of the table of outcomes with both coefficients of restitution: the pulses of
    Fig. 15 and point Q, the paper's beside ours.

    Parameters
    ----------
    results : dict
        ``results.json``.

    Returns
    -------
    list of list of str
        c_v, case, paper, ours, verdict.
    """
    rows = []
    for case in ("paper", "computed"):
        pulses = results["pulse"][case]
        label = restitution_label(case, pulses["restitution"])
        for row in pulses["cases"]:
            na = row["NA"]
            rows.append([label, f"Fig. 15, t_p = {row['duration']:.2f} s",
                         outcome_text(**na["paper"]),
                         outcome_text(na["status"], na["half_cycle"]), agree(na["agrees"])])
        if "failure_domain" in results:
            q = results["failure_domain"]["q_tp040"][case]
            rows.append([label, "Q at t_p = 0.40 s [g]", number(paper_q(), 2), number(q, 3),
                         agree(q_agrees(q))])
    return rows


def notes(results: dict) -> list[str]:
    """The notes on where the paper is wrong or silent, and the choices made.

    Parameters
    ----------
    results : dict
        ``results.json`` (the coefficients of restitution and the settings).

    Returns
    -------
    list of str
    """
    c = results["restitution"]["computed"][0]
    lk = results["restitution"]["link"][0]
    s = results["settings"]
    return [
        "1. Coefficient of restitution. The paper uses c_v = 0.875 for Oppenheim's arch, "
        "quoting De Lorenzis et al. (2007). Three models give three numbers. 'computed' (the "
        "package's default): the momentum balance of the whole arch through the impact, with "
        "impulses at the closing joints and at the hinges of the post-impact mechanism, gives "
        f"c_v = {c:.4f} for this 7-voussoir arch (about 0.73 in the limit of many voussoirs), "
        "and the kinetic energy never grows at an impact. 'link': the paper's own rule read "
        "link by link as Housner does for a block (the post-impact springing link turns about "
        "the opposite face of the same springing joint, its angular momentum conserved, the "
        f"impulse at its other hinge neglected) gives c_v = {lk:.4f} with the annular-sector "
        "voussoirs of this arch and 0.875 with flat-faced voussoirs: that is the paper's "
        "number. It is not a consistent momentum balance: the neglected impulse is what sets "
        "the other links moving, their momentum is left out, and the rate of one link is taken "
        "for the rate of the mechanism's coordinate. 'paper': 0.875 imposed. This report uses "
        "the paper's 0.875 for every figure that reproduces the paper and shows the computed "
        "value beside it (Figs. 12-15, point Q). With the computed value the irregular arches "
        "take the nominal arch's value, as the paper applies one value to all arches. The table "
        "below gives the outcomes with both.",
        "2. Table 1 swaps the k~ values of RA-1 and RA-2 relative to the text of Sect. 3 (text: "
        "RA-1 k~_l = 0.4111, k~_r = 0.3104; RA-2 k~_l = 0.3946, k~_r = 0.3501). The geometry of "
        "RA-1 and RA-2 is not given in the paper, so they cannot be regenerated: this report "
        "draws two irregular arches of the same kind (epsilon = 0.10) from a fixed seed and "
        "shows the paper's rows beside them for scale only.",
        "3. Table 2's Mech-r rows have missing and shifted cells; for NA, Mech-r equals Mech-l by "
        "symmetry (ours: identical to round-off), and only theta'_u of RA-1 and RA-2 is legible.",
        "4. 'Mech-1' in the paper's text and captions is Mech-l (left).",
        "5. Not stated by the paper, chosen here: g = 9.81 m/s^2; density 2000 kg/m^3 (it cancels "
        "from every result); the sum of the voussoir angles of an irregular arch is kept equal "
        "to the nominal embrace by rescaling the drawn angles; the amplitude range of the "
        f"fragility scan ({s['amplitude_min_g']:.2f} to {s['amplitude_max_g']:.2f} g, which spans "
        f"the "
        "rise of every curve); the seed of the irregular arches; an irregular arch 'fails' "
        "when it collapses under the pulse in either direction (the paper analyses both and "
        "counts arches, h_f <= h); the collapse test ('ever-increasing phi') is the energy "
        "criterion of archquake.fourlink.engine: after the excitation an arch moving away from "
        "theta_u "
        "with more energy than V(theta_cr), or beyond theta_cr and not returning, collapses; "
        "during the excitation, reaching the kinematic limit of the linkage is collapse.",
    ]


def comparison_text(summary: dict) -> list[str]:
    """The paragraphs of the comparison section, every number from ``summary``."""
    st = comparison_statistics(summary)
    k = summary["load_multiplier"]
    c = summary["restitution"]
    top = summary["scan_g"][1]
    names, diff, rows = st["names"], st["difference"], st["rows"]
    models = ", ".join(f"{n} (c_v = {c[n][0]:.3f})" for n in names)
    text = [(f"The same arch in the package's two models: the four-link model of the paper "
             f"(one degree of freedom, the hinges of the limit analysis, impacts by a "
             f"coefficient of restitution c_v) with each restitution model - {models} - and "
             f"the rigid-block model (every voussoir a block, unilateral contacts with Coulomb "
             f"friction mu = {summary['friction']:g} at both ends of every joint, Newton "
             f"impacts with restitution 0, time step {1000 * summary['time_step']:g} ms, "
             f"{summary.get('coarse_factor', 1)} steps taken as one between the contacts' "
             f"events; "
             f"'measured' is the c_v measured on its impacts). Failure acceleration: the lowest "
             f"amplitude of Oppenheim's pulse that collapses the arch, both models on the same "
             f"scan ({summary['scan_g'][0]:g}-{top:g} g in {summary['scan_g'][2]:g} g steps) "
             f"with every boundary bisected to {summary['resolution_g']:g} g; the same numbers "
             f"as `archquake compare`.")]
    if st["all_from"] is not None:
        size, name, d = st["largest_long"]
        early = [f"{n} from {st['agree_from'][n]:.2f} s" for n in names
                 if st["agree_from"][n] < st["all_from"]]
        longest = rows[-1]
        a = longest["rigid_block"]
        text.append(
            f"Long pulses agree. From t_p = {st['all_from']:.2f} s on, the four-link failure "
            f"acceleration is within {100 * AGREEMENT_BAND:g} % of the rigid-block one with "
            f"every restitution model (largest: {name}, {percent(diff[name][d])} at "
            f"{d:.2f} s)" + (f"; {', '.join(early)}" if early else "") + ". Both models "
            f"then fail close to the static load multiplier k = {k:.3f}, which they share (the "
            f"rigid blocks start to move within 1 % of k, a tested property): at t_p = "
            f"{longest['duration']:.2f} s the rigid blocks fail at {a:.3f} g, "
            f"{100 * (a / k - 1):.1f} % above k, and the impact law, which decides the rest, "
            f"moves the answer little.")
    else:
        text.append(f"No duration of the comparison has every restitution model within "
                    f"{100 * AGREEMENT_BAND:g} % of the rigid-block model.")
    if st["short"]:
        first = rows[0]
        parts = []
        for n in names:
            v = first["four_link"][n]
            parts.append(f"{v:.3f} g ({n}, {percent(diff[n][first['duration']])})"
                         if v is not None else f"more than {top:g} g ({n})")
        rb = first["rigid_block"]
        rb_text = f"{rb:.3f} g" if rb is not None else f"more than {top:g} g"
        largest = st["largest_short"]
        impact = summary["impact"]
        by_duration = {n: dict(zip([r["duration"] for r in summary["rows"]],
                                   summary["half_cycle_at_failure"][n], strict=True))
                       for n in names}
        after_impact = [n for n in names
                        if all((by_duration[n][d] or 0) >= 2 for d in st["short"])]
        first_swing = [n for n in names if n not in after_impact]
        blocks = ""
        if "measured" in names:
            close = [d for d in st["short"] if diff["measured"][d] is not None]
            if close:
                worst = max(abs(diff["measured"][d]) for d in close)
                blocks = (f" With the c_v measured on the blocks ({c['measured'][0]:.3f}) the "
                          f"four-link model comes within {100 * worst:.1f} % of the rigid "
                          f"blocks at t_p = {', '.join(f'{d:g}' for d in close)} s")
                missing = [d for d in st["short"] if diff["measured"][d] is None]
                blocks += (f", but not at {', '.join(f'{d:g}' for d in missing)} s."
                           if missing else ".")
        text.append(
            f"Short pulses differ. At t_p = {first['duration']:.2f} s the rigid blocks fail at "
            f"{rb_text}, the four-link model at " + ", ".join(parts)
            + (f"; the largest difference below {st['all_from']:.2f} s is "
               f"{percent(diff[largest[1]][largest[2]])} ({largest[1]}, t_p = "
               f"{largest[2]:.2f} s)" if largest and st["all_from"] is not None else "")
            + ". A short pulse must be several times k to overturn the arch. At the failure "
              "acceleration of the four-link model the arch collapses after an impact (half "
              "cycle 2 or later) with " + (", ".join(after_impact) or "no model")
            + ("; with " + ", ".join(first_swing) + " it survives the impacts at some short "
               "durations, and falls only in its first swing, at a far higher amplitude (or "
               "beyond the scan)"
               if first_swing else "")
            + ". So the energy an impact leaves decides, and the four-link answer depends "
              "strongly on c_v. The rigid "
              f"blocks do not move on in a four-link mechanism after an impact: at the closing "
              f"of Mech-l they keep {100 * impact['energy_ratio']:.0f} % of the kinetic "
              f"energy, of which {100 * (1 - impact['mech_r_share']):.0f} % moves outside "
              f"Mech-r, with hinges at joints {', '.join(map(str, impact['hinges']))} "
              f"(archquake.fourlink.impact, model 'measured'), so no single c_v reproduces them."
            + blocks)
    bands_fl = sorted({r["duration"] for r in rows for v in r["recovery_above"]["four_link"]
                       .values() if v})
    bands_rb = [r["duration"] for r in rows if r["recovery_above"]["rigid_block"]]
    text.append(
        f"Above its failure acceleration the four-link model recovers again in a band at "
        f"{len(bands_fl)} of the {len(rows)} durations (between its collapse after an impact and "
        f"its collapse in the first half cycle, as in Fig. 16), the rigid-block model at "
        f"{len(bands_rb)}" + (f" ({', '.join(f'{d:g}' for d in bands_rb)} s)" if bands_rb
                              else "") + f" (on this scan: a band narrower than "
        f"{summary['scan_g'][2]:g} g can be missed). Cost: the rigid-block curve ran on "
        f"{summary['backend']}" + (" beside the paper's parts" if summary["backend"] !=
                                   "this process" else "")
        + f" ({summary['rigid_block_seconds']:.1f} s of analyses, after the compilation of "
          f"its solver); the four-link curves take well under a second.")
    counts = [r["undecided_analyses"]["rigid_block"] for r in rows
              if "undecided_analyses" in r]
    if counts:  # a result kept before undecided analyses were counted says nothing
        bounded = [r["duration"] for r in rows if "failure_undecided_from" in r]
        text.append(f"The rigid-block model left {sum(counts)} of its analyses undecided"
                    + (f"; at t_p = {', '.join(f'{d:g}' for d in bounded)} s an undecided "
                       f"band lies below its lowest decided collapse, so its failure "
                       f"acceleration there is the range given (a-b) and is not compared"
                       if bounded else "") + ".")
    return text


def comparison_rows(summary: dict) -> list[list[str]]:
    """Rows of the comparison's table: per duration the rigid-block failure acceleration, the
    four-link one with each restitution model and their difference, and the recovery bands.

    Parameters
    ----------
    summary : dict
        ``results["comparison"]``.

    Returns
    -------
    list of list of str
    """
    st = comparison_statistics(summary)
    top = summary["scan_g"][1]
    out = []
    for r in st["rows"]:
        rb = r["rigid_block"]
        cells = [f"{r['duration']:.2f}", number(rb, 3) if rb is not None else f"> {top:g}"]
        low = r.get("failure_undecided_from", {}).get("rigid_block")
        if low is not None:  # undecided below the lowest decided collapse: a range
            cells[1] = f"{low:.3f}-" + ("" if rb is None else f"{rb:.3f}")
            rb = None
        for n in st["names"]:
            v = r["four_link"][n]
            cells.append(f"> {top:g}" if v is None else
                         f"{v:.3f}" + ("" if rb is None else f" ({percent(v / rb - 1)})"))
        bands = [("rigid blocks", r["recovery_above"]["rigid_block"]),
                 *r["recovery_above"]["four_link"].items()]
        cells.append("; ".join(f"{n} " + ", ".join(f"{a:.2f}-{b:.2f}" for a, b in v)
                               for n, v in bands if v) or "-")
        out.append(cells)
    return out


def record_rows(record: dict) -> list[list[str]]:
    """Rows of the record-based fragility's table: per intensity measure the medians and the
    dispersions.

    Parameters
    ----------
    record : dict
        ``results["record_fragility"]``.

    Returns
    -------
    list of list of str
    """
    rows = []
    for im, e in record.items():
        rows.append([f"{im.upper()} [{e['unit']}]", number(e["lognormal"]["median"], 3),
                     number(e["total"], 3), number(e["nominal_lognormal"]["median"], 3),
                     number(e["record_to_record"], 3), number(e["geometric"], 3),
                     number(e["srss"], 3)])
    return rows


def record_text(record: dict, settings: dict) -> str:
    """The paragraph of the record-based fragility: what was run and what it shows.

    Parameters
    ----------
    record : dict
        ``results["record_fragility"]``.
    settings : dict
        ``results["settings"]``.

    Returns
    -------
    str
    """
    pga, pgv = record["pga"], record["pgv"]
    analyses = sum(e["analyses"]["total"] for e in record.values())
    integrated = sum(e["analyses"]["integrated"] for e in record.values())
    return (
        f"The paper's conclusion names earthquake excitation as further work: the fragility of "
        f"Oppenheim's arch and of {pga['sample_size']} irregular arches (epsilon = "
        f"{settings['epsilon']:.2f}, seed {settings['seed']}, arches 0-"
        f"{pga['sample_size'] - 1} of the fragility sample) against {pga['records']} synthetic "
        f"ground motions (archquake.studies.record_fragility.STOCHASTIC_SUITE, a modulated, "
        f"filtered "
        f"white noise, seed {settings['seed']}), each scaled to {len(pga['levels'])} levels of "
        f"PGA ({pga['levels'][0]:g}-{pga['levels'][-1]:g} g) and of PGV "
        f"({pgv['levels'][0]:g}-{pgv['levels'][-1]:g} m/s) and applied in both polarities "
        f"(multiple-stripe analysis; an arch-record pair fails if it collapses in either), "
        f"restitution '{pga['restitution']}': {analyses} analyses, {integrated} of them "
        f"integrated (the others never reach the arch's activation). Lognormal fragility "
        f"functions fitted by maximum likelihood on the stripes (Baker 2015); dispersions: "
        f"record-to-record (the nominal arch's fit), geometric (a common dispersion of "
        f"per-record fits to the irregular arches) and total (all pairs pooled), with "
        f"sqrt(rtr^2 + geo^2) beside the total for comparison; bands: "
        f"{settings['record_bootstrap']} bootstrap resamples. The sizes are reduced to fit the "
        f"report's time budget (the full study is 40 arches x 20 records x 20 levels: "
        f"`archquake record-fragility ...` or examples/record_fragility.py --full). "
        + " ".join(weaker(im, e) for im, e in record.items()))


def weaker(im: str, entry: dict) -> str:
    """How much lower the irregular arches' median is than the nominal arch's (the paper's
    point for pulses, Sect. 5.3.3, seen here with records)."""
    ours, nominal = entry["lognormal"]["median"], entry["nominal_lognormal"]["median"]
    if ours is None or nominal is None:
        return f"{im.upper()}: no lognormal fit for both."
    return (f"In {im.upper()} the median of the irregular arches is {ours:.3f} {entry['unit']}, "
            f"{100 * abs(1 - ours / nominal):.0f} % {'below' if ours < nominal else 'above'} "
            f"the nominal arch's {nominal:.3f} "
            f"{entry['unit']}.")




# ------------------------------------------------------------------------------ paragraphs
def introduction(settings: dict, paper: dict) -> str:
    """The opening paragraph of the paper's reproduction: the paper, its arches and c_v.

    Parameters
    ----------
    settings : dict
        :meth:`archquake.report.ReproductionSettings.to_dict`.
    paper : dict
        The paper's values.

    Returns
    -------
    str
    """
    s = settings
    return ("The paper: 'Dynamic response of masonry arch with geometrical irregularities "
            "subjected to a pulse-type ground motion'. Nominal arch: Oppenheim's arch NA "
            f"({oppenheim_text(paper)}). Irregular arches: epsilon "
            f"epsilon = {s['epsilon']:.2f}, seed {s['seed']}. Coefficient of restitution of "
            f"the paper's dynamic results: c_v = {s['restitution']:.3f}."
            + (" QUICK RUN: reduced sample sizes, not the paper's study."
               if s["quick"] else ""))


TABLE1_TEXT = (
    "Horizontal load multipliers and progressive angles of the collapse hinges (Mech-r in the "
    "mirrored frame, as in the paper). RA-1 and RA-2 are our own draws; the paper's rows are "
    "given beside them for scale (Table 1 as printed, the text's k~ in brackets).")
"""The paragraph above Table 1."""


def limit_sample_text(results: dict, paper: dict) -> str:
    """The sample of k~ by limit analysis and the size of the dynamic sample.

    Parameters
    ----------
    results : dict
        ``limit_sample``, ``fragility`` and ``settings`` of ``results.json``.
    paper : dict
        The paper's values (the nominal k).

    Returns
    -------
    str
    """
    ls = results["limit_sample"]
    return (f"Limit-analysis sample: s = {ls['count']} arches, k~ = min(k~_l, k~_r): mean "
            f"{ls['mean']:.4f}, standard deviation {ls['std']:.4f}, range "
            f"[{ls['min']:.4f}, {ls['max']:.4f}]; {100 * ls['fraction_below_nominal']:.1f} "
            "% of the arches start moving below the nominal k = "
            f"{paper['table1']['NA']['load_multiplier']:.2f}. Dynamic sample: h = "
            f"{results['fragility']['arches']} arches, amplitude step "
            f"{results['settings']['amplitude_step_g']:.2f} g.")


def fragility_rows(curves: list) -> list[list[str]]:
    """Rows of the fragility table: per duration the nominal failure acceleration, the
    lognormal fit and P_F below the nominal failure acceleration.

    Parameters
    ----------
    curves : list of dict
        ``results["fragility"]["curves"]``.

    Returns
    -------
    list of list of str
    """
    return [[f"{c['duration']:.2f}", nominal_q(c),
             number(c["lognormal_median"], 3), number(c["lognormal_dispersion"], 3),
             number(c["probability_below_nominal"], 3)] for c in curves]


def nominal_q(curve: dict) -> str:
    """The nominal failure acceleration of a fragility curve's entry [g], to 3 decimals,
    ``<= q`` when the nominal arch collapses at the lowest amplitude scanned (an upper bound)."""
    text = number(curve["nominal_failure_acceleration"], 3)
    return f"<= {text}" if curve.get("nominal_failure_acceleration_bound") == "upper" else text


def run_info(results: dict) -> list:
    """What a report says of its run: the time of every part, of the tasks run beside them,
    the environment and the settings.

    Parameters
    ----------
    results : dict
        ``timings`` (by part [s], ``report`` left out), ``background`` (by task:
        :meth:`archquake.report.running.TaskRun.describe`), ``environment`` and
        ``settings``.

    Returns
    -------
    list of Table and Paragraph
        The blocks of the report's section on its run.
    """
    env, s = results["environment"], results["settings"]
    blocks = [Table(["part", "wall time [s]"],
                    [[k, f"{v:.2f}"] for k, v in results["timings"].items() if k != "report"])]
    if results.get("background"):
        blocks.append(Paragraph("Run beside the parts above (a part waits for its result):"))
        blocks.append(Table(["task", "ran on", "analyses [s]", "from submission to result [s]"],
                            [[k, v["ran on"], f"{v['seconds']:.2f}", f"{v['wall_seconds']:.2f}"]
                             for k, v in results["background"].items()]))
    blocks.append(Paragraph(", ".join(f"{k} {v}" for k, v in env.items())
                            + f"; seed {s['seed']}."))
    blocks.append(Paragraph("Settings: " + ", ".join(f"{k} = {v}" for k, v in s.items()) + "."))
    return blocks


def two_models_text(summary: dict, resolution_g: float) -> list[str]:
    """Which answer to trust where: the paragraphs of the section that runs the paper's failure
    domain and fragility with both models, every number from ``summary``
    (``results["two_models"]``)."""
    domain, frag = summary["domain"], summary["fragility"]
    durations = domain["durations"]
    widths = domain["width_g"]
    close = [d for d, w in zip(durations, widths, strict=True) if w <= 2 * resolution_g]
    apart = [(d, w) for d, w in zip(durations, widths, strict=True) if w > 2 * resolution_g]
    rigid_only, four_only = [], []
    for row in domain["disagreement"]:
        for piece in row["intervals"]:
            if piece["to"] - piece["from"] <= 2 * resolution_g:
                continue
            target = rigid_only if piece["collapses"] == "rigid-blocks" else four_only
            target.append(f"{piece['from']:.2f}-{piece['to']:.2f} g at {row['duration']:g} s")
    c_v = domain["restitution"][0]
    text = [f"The paper's Fig. 16 and Figs. 17-20 run with both of the package's models: the "
            f"four-link model with the paper's c_v = {c_v:.3f} and the rigid-block model, on the "
            f"comparison's durations and scan (the rigid-block failure domain is the comparison's "
            f"curve above). Hatched on the failure-domain figure: where exactly one model "
            f"collapses."]
    if apart:
        text.append(
            "The two models agree on collapse, to the bisection's resolution, at t_p = "
            + (", ".join(f"{d:g}" for d in close) or "no duration") + " s, and disagree at "
            + ", ".join(f"{d:g} s (over {w:.2f} g)" for d, w in apart) + ". "
            + (f"The rigid blocks collapse where the four-link model recovers at "
               f"{'; '.join(rigid_only)}" if rigid_only else "The rigid blocks never collapse "
               "where the four-link model recovers")
            + "; " + (f"the four-link model collapses where the rigid blocks recover at "
                      f"{'; '.join(four_only)}" if four_only else "the four-link model never "
                      "collapses where the rigid blocks recover") + ".")
    else:
        text.append("The two models agree on collapse, to the bisection's resolution, at every "
                    "duration of the scan.")
    where = frag["largest_difference_at"]
    text.append(
        f"Fragility of the same {frag['arches_both']} irregular arches by both models (the first "
        f"of the four-link study's {frag['arches_four_link']}; the rigid-block study searched its "
        f"grid with '{frag['search']}', {frag['analysed']} analyses for "
        f"{frag['grid_points']} grid points, the same P_F as the exhaustive grid where they were "
        f"compared): the largest difference of P_F, rigid blocks minus four-link, is "
        f"{frag['largest_difference']:+.2f} at t_p = {where['duration']:g} s, a = "
        f"{where['amplitude_g']:.2f} g. The dashed red line is the multi-fidelity estimate of "
        f"the rigid blocks' P_F over all {frag['arches_four_link']} arches: the four-link P_F of "
        f"all of them corrected by the two models' mean difference on the arches both analysed."
        + _undecided_sentence(frag))
    if apart and close:
        text.append(
            f"Which answer to trust: for the pulses where the models agree (t_p = "
            f"{', '.join(f'{d:g}' for d in close)} s here) the four-link model's answer, which "
            f"costs microseconds, is the rigid blocks' too; where they part, the rigid-block "
            f"model is the one an independent discrete-element code confirms (README), and the "
            f"four-link answer depends on a coefficient of restitution that no rule gets right "
            f"at every duration.")
    return text


def _undecided_sentence(frag: dict) -> str:
    """The rigid-block fragility's undecided analyses and the bounds of its P_F, in words (a
    result kept before they were counted says nothing)."""
    undecided = frag.get("undecided")
    if undecided is None:
        return ""
    text = (f" Of the rigid-block analyses {undecided['analyses']} of {undecided['of']} were "
            f"left undecided")
    if not undecided["analyses"]:
        return text + "."
    import numpy as np

    gap = float(np.max(np.asarray(frag["rigid_blocks_upper"])
                       - np.asarray(frag["rigid_blocks"])))
    return (text + f": its P_F counts them as survivals (a lower bound); as collapses P_F "
                   f"would be up to {gap:.2f} higher.")


def two_models_domain_caption(summary: dict) -> str:
    """Caption of the failure domain by both models."""
    return ("Failure domain of the nominal arch by the four-link model (shaded regions, the "
            f"paper's c_v = {summary['domain']['restitution'][0]:.3f}) and the rigid-block "
            "model's failure curve (red); hatched: amplitudes where one model collapses and the "
            "other does not (red: only the rigid blocks collapse; blue: only the four-link "
            "model).")


def two_models_fragility_caption(summary: dict) -> str:
    """Caption of the fragility curves by both models."""
    f = summary["fragility"]
    return (f"P_F of the same {f['arches_both']} irregular arches by the rigid-block model "
            f"(red) and the four-link model (black), the four-link P_F of all "
            f"{f['arches_four_link']} arches (dotted) and the multi-fidelity estimate of the "
            f"rigid blocks' P_F over all of them (red dashed), per pulse duration.")
