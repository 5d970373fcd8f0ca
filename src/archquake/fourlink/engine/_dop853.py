"""Coefficients of the Dormand-Prince 8(5,3) pair with its 7th-order dense output.

E. Hairer, S. P. Norsett, G. Wanner, "Solving Ordinary Differential Equations I", 2nd ed.,
Springer (1993), Sect. II.5 (the DOP853 pair) and Sect. II.6 (its dense output); the same
numbers as scipy's DOP853.
"""

import numpy as np

C = np.array([
    0.0, 0.05260015195876773, 0.0789002279381516, 0.1183503419072274, 0.2816496580927726,
    0.3333333333333333, 0.25, 0.3076923076923077, 0.6512820512820513, 0.6, 0.8571428571428571,
    1.0, 1.0, 0.1, 0.2, 0.7777777777777778,
])

A = np.array([
    [
        0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
    ],
    [
        0.05260015195876773, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
        0.0,
    ],
    [
        0.0197250569845379, 0.0591751709536137, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
        0.0, 0.0, 0.0, 0.0,
    ],
    [
        0.02958758547680685, 0.0, 0.08876275643042054, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
        0.0, 0.0, 0.0, 0.0,
    ],
    [
        0.2413651341592667, 0.0, -0.8845494793282861, 0.924834003261792, 0.0, 0.0, 0.0, 0.0, 0.0,
        0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
    ],
    [
        0.037037037037037035, 0.0, 0.0, 0.17082860872947386, 0.12546768756682242, 0.0, 0.0, 0.0,
        0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
    ],
    [
        0.037109375, 0.0, 0.0, 0.17025221101954405, 0.06021653898045596, -0.017578125, 0.0, 0.0,
        0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
    ],
    [
        0.03709200011850479, 0.0, 0.0, 0.17038392571223998, 0.10726203044637328,
        -0.015319437748624402, 0.008273789163814023, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
    ],
    [
        0.6241109587160757, 0.0, 0.0, -3.3608926294469414, -0.868219346841726, 27.59209969944671,
        20.154067550477894, -43.48988418106996, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
    ],
    [
        0.47766253643826434, 0.0, 0.0, -2.4881146199716677, -0.590290826836843, 21.230051448181193,
        15.279233632882423, -33.28821096898486, -0.020331201708508627, 0.0, 0.0, 0.0, 0.0, 0.0,
        0.0, 0.0,
    ],
    [
        -0.9371424300859873, 0.0, 0.0, 5.186372428844064, 1.0914373489967295, -8.149787010746927,
        -18.52006565999696, 22.739487099350505, 2.4936055526796523, -3.0467644718982196, 0.0, 0.0,
        0.0, 0.0, 0.0, 0.0,
    ],
    [
        2.273310147516538, 0.0, 0.0, -10.53449546673725, -2.0008720582248625, -17.9589318631188,
        27.94888452941996, -2.8589982771350235, -8.87285693353063, 12.360567175794303,
        0.6433927460157636, 0.0, 0.0, 0.0, 0.0, 0.0,
    ],
    [
        0.054293734116568765, 0.0, 0.0, 0.0, 0.0, 4.450312892752409, 1.8915178993145003,
        -5.801203960010585, 0.3111643669578199, -0.1521609496625161, 0.20136540080403034,
        0.04471061572777259, 0.0, 0.0, 0.0, 0.0,
    ],
    [
        0.056167502283047954, 0.0, 0.0, 0.0, 0.0, 0.0, 0.25350021021662483, -0.2462390374708025,
        -0.12419142326381637, 0.15329179827876568, 0.00820105229563469, 0.007567897660545699,
        -0.008298, 0.0, 0.0, 0.0,
    ],
    [
        0.03183464816350214, 0.0, 0.0, 0.0, 0.0, 0.028300909672366776, 0.053541988307438566,
        -0.05492374857139099, 0.0, 0.0, -0.00010834732869724932, 0.0003825710908356584,
        -0.00034046500868740456, 0.1413124436746325, 0.0, 0.0,
    ],
    [
        -0.42889630158379194, 0.0, 0.0, 0.0, 0.0, -4.697621415361164, 7.683421196062599,
        4.06898981839711, 0.3567271874552811, 0.0, 0.0, 0.0, -0.0013990241651590145,
        2.9475147891527724, -9.15095847217987, 0.0,
    ],
])

B = np.array([
    0.054293734116568765, 0.0, 0.0, 0.0, 0.0, 4.450312892752409, 1.8915178993145003,
    -5.801203960010585, 0.3111643669578199, -0.1521609496625161, 0.20136540080403034,
    0.04471061572777259,
])

E3 = np.array([
    -0.18980075407240762, 0.0, 0.0, 0.0, 0.0, 4.450312892752409, 1.8915178993145003,
    -5.801203960010585, -0.4226823213237919, -0.1521609496625161, 0.20136540080403034,
    0.02265179219836082, 0.0,
])

E5 = np.array([
    0.01312004499419488, 0.0, 0.0, 0.0, 0.0, -1.2251564463762044, -0.4957589496572502,
    1.6643771824549864, -0.35032884874997366, 0.3341791187130175, 0.08192320648511571,
    -0.022355307863886294, 0.0,
])

D = np.array([
    [
        -8.428938276109013, 0.0, 0.0, 0.0, 0.0, 0.5667149535193777, -3.0689499459498917,
        2.38466765651207, 2.117034582445028, -0.871391583777973, 2.2404374302607883,
        0.6315787787694688, -0.08899033645133331, 18.148505520854727, -9.194632392478356,
        -4.436036387594894,
    ],
    [
        10.427508642579134, 0.0, 0.0, 0.0, 0.0, 242.28349177525817, 165.20045171727028,
        -374.5467547226902, -22.113666853125306, 7.733432668472264, -30.674084731089398,
        -9.332130526430229, 15.697238121770845, -31.139403219565178, -9.35292435884448,
        35.81684148639408,
    ],
    [
        19.985053242002433, 0.0, 0.0, 0.0, 0.0, -387.0373087493518, -189.17813819516758,
        527.8081592054236, -11.57390253995963, 6.8812326946963, -1.0006050966910838,
        0.7777137798053443, -2.778205752353508, -60.19669523126412, 84.32040550667716,
        11.99229113618279,
    ],
    [
        -25.69393346270375, 0.0, 0.0, 0.0, 0.0, -154.18974869023643, -231.5293791760455,
        357.6391179106141, 93.40532418362432, -37.45832313645163, 104.0996495089623,
        29.8402934266605, -43.53345659001114, 96.32455395918828, -39.17726167561544,
        -149.72683625798564,
    ],
])


# ---------------------------------------------------------------------------------------------
# The step and the dense output written out stage by stage
# ---------------------------------------------------------------------------------------------

GENERATED_BEGIN = "# --- begin: written out by _dop853.written_out_source(); do not edit by hand"
GENERATED_END = "# --- end: written out by _dop853.written_out_source()"

_DECORATOR = '@numba.njit(cache=True, fastmath={"reassoc", "contract"}, _nrt=False)'
"""Compiled with reassociation and fused multiply-adds allowed: the stage sums are evaluated in
whatever order is fastest (round-off level differences; NaN and infinity keep their meaning);
without numba's reference counting (``_nrt=False``): the step allocates nothing, and counting
the references of its eight array arguments on entry and exit cost a fifth of an analysis."""


def _combination(weights, names) -> str:
    """``w_0 * name_0 + w_1 * name_1 + ...`` over the non-zero weights (exact float literals)."""
    terms = [f"{float(w)!r} * {n}" for w, n in zip(weights, names, strict=False) if w != 0.0]
    return " + ".join(terms) if terms else "0.0"


def _wrap(line: str, indent: int, width: int = 99) -> list[str]:
    """Break a long assignment at `` + `` into continuation lines inside its parentheses."""
    pad = " " * indent
    if len(pad + line) <= width:
        return [pad + line]
    head, _, rest = line.partition("(")
    terms = rest.split(" + ")
    lines, current = [], pad + head + "("
    for k, term in enumerate(terms):
        piece = term + ("" if k == len(terms) - 1 else " +")
        if len(current) + 1 + len(piece) > width and not current.endswith("("):
            lines.append(current)
            current = pad + "    " + piece
        else:
            current = current + ("" if current.endswith("(") else " ") + piece
    lines.append(current)
    return lines


def _rhs_call(target: str, time: str, theta: str, theta_dot: str) -> list[str]:
    return [f"    {target} = motion_rhs({time}, {theta}, {theta_dot}, m, tab, xg_step, tcap,",
            "                    tcap_left, kind, params, times, values)"]


def written_out_source() -> str:
    """Source of the engine's ``dop853_step`` and ``dense_coefficients``: the stages of the
    tableau above written out with their non-zero coefficients as literals, every stage held in
    local variables.

    The same arithmetic as loops over ``A``, ``B``, ``E5``, ``E3`` and ``D``, but a loop over the
    tableau with a test for zero entries made a step cost about three times the twelve
    right-hand-side evaluations it needs. :mod:`archquake.fourlink.engine.stepper` holds the text
    this function returns between :data:`GENERATED_BEGIN` and :data:`GENERATED_END`, and a test
    checks that it is unchanged.
    """
    v = [f"v{j}" for j in range(16)]  # theta' at stage j
    w = [f"w{j}" for j in range(16)]  # theta'' at stage j
    out = [GENERATED_BEGIN, "", "",
           _DECORATOR,
           "def dop853_step(t, y0, y1, f0, f1, h, m, tab, xg_step, tcap, tcap_left, kind, params,",
           "                times, values, rtol, atol, K):",
           '    """One Dormand-Prince 8(5,3) step; stages kept in ``K`` for the dense output.',
           "",
           "    Returns ``(theta, theta', theta'', error_norm)`` at ``t + h``.\"\"\"",
           "    v0 = f0",
           "    w0 = f1"]
    for s in range(1, 12):
        out += _wrap(f"z = y0 + h * ({_combination(A[s, :s], v)})", 4)
        out += _wrap(f"v{s} = y1 + h * ({_combination(A[s, :s], w)})", 4)
        out += _rhs_call(f"w{s}", f"t + {float(C[s])!r} * h", "z", f"v{s}")
    out += _wrap(f"n0 = y0 + h * ({_combination(B, v)})", 4)
    out += _wrap(f"n1 = y1 + h * ({_combination(B, w)})", 4)
    out += ["    v12 = n1"]
    out += _rhs_call("w12", "t + h", "n0", "n1")
    for j in range(13):
        out += [f"    K[{j}, 0] = v{j}", f"    K[{j}, 1] = w{j}"]
    out += _wrap(f"e50 = ({_combination(E5, v)})", 4)
    out += _wrap(f"e51 = ({_combination(E5, w)})", 4)
    out += _wrap(f"e30 = ({_combination(E3, v)})", 4)
    out += _wrap(f"e31 = ({_combination(E3, w)})", 4)
    out += [
        "    sc0 = atol + rtol * max(abs(y0), abs(n0))",
        "    sc1 = atol + rtol * max(abs(y1), abs(n1))",
        "    e50 /= sc0",
        "    e51 /= sc1",
        "    e30 /= sc0",
        "    e31 /= sc1",
        "    n5 = e50 * e50 + e51 * e51",
        "    n3 = e30 * e30 + e31 * e31",
        "    if n5 == 0.0 and n3 == 0.0:",
        "        err = 0.0",
        "    else:",
        "        err = abs(h) * n5 / math.sqrt((n5 + 0.01 * n3) * 2.0)",
        "    return n0, n1, w12, err",
        "", "",
        _DECORATOR,
        "def dense_coefficients(t, y0, y1, n0, n1, h, m, tab, xg_step, tcap, tcap_left, kind,",
        "                       params, times, values, K, Fd):",
        '    """Coefficients ``Fd`` (7, 2) of the 7th-order dense output of the last step."""',
    ]
    used = {0, 12} | {j for j in range(13) if np.any(A[13:16, j] != 0.0) or np.any(D[:, j] != 0.0)}
    for j in sorted(used):
        out += [f"    v{j} = K[{j}, 0]", f"    w{j} = K[{j}, 1]"]
    for s in range(13, 16):
        out += _wrap(f"z = y0 + h * ({_combination(A[s, :s], v)})", 4)
        out += _wrap(f"v{s} = y1 + h * ({_combination(A[s, :s], w)})", 4)
        out += _rhs_call(f"w{s}", f"t + {float(C[s])!r} * h", "z", f"v{s}")
    for c, (y, n, k) in enumerate((("y0", "n0", v), ("y1", "n1", w))):
        out += [f"    dy = {n} - {y}",
                f"    Fd[0, {c}] = dy",
                f"    Fd[1, {c}] = h * {k[0]} - dy",
                f"    Fd[2, {c}] = 2.0 * dy - h * ({k[12]} + {k[0]})"]
        for i in range(4):
            out += _wrap(f"Fd[{3 + i}, {c}] = h * ({_combination(D[i], k)})", 4)
    out += ["", "", GENERATED_END]
    return "\n".join(out) + "\n"
