r"""The library's results as the data the page draws: JSON-ready dicts of plain lists.

Every drawing is in the structure's own frame (x to the right, y up, metres). The limit
analysis of Mech-r, which the library carries out on the mirrored structure (and the command
line reports in that frame), is mapped back to the structure's own frame, :math:`x \to -x`, so
both mechanisms are drawn on the structure the user shaped.

The motion of the blocks is sent as a rigid motion of every block per frame, ``(dx, dy,
rotation)``: the displacement of a reference point ``c`` of the block [m] and its rotation
about that point [rad, counterclockwise], so that a point ``p`` of the block at rest is at

.. math::

    p' = c + d + R(\vartheta)\,(p - c)

-- what an SVG ``translate(d) rotate(theta, c)`` draws, and what
:meth:`archquake.rigid_blocks.BlockHistory.outlines` computes for the rigid blocks. For the
four-link model the blocks of each link turn with it (:func:`four_link_motion`): link AB about
A, link CD about D, link BC carried by B; the blocks outside A..D stay still.
"""

from __future__ import annotations

import math

import numpy as np

FRAME_RATE = 25.0
"""Frames per second of the animation [1/s]."""

MAX_ANIMATION_TIME = 60.0
"""Longest stretch of a time history animated [s]."""

MAX_BLOCK_FRAMES = 150_000
"""Most block positions of an animation (blocks times frames): a structure of many blocks under a
long motion is animated at a lower frame rate, so that its answer stays a few megabytes."""

SERIES_POINTS = 1200
"""Most points of a time series sent for a small plot [-]."""

_MIRROR = np.array([-1.0, 1.0])


def rounded(values, digits: int = 5) -> list:
    """Plain nested lists of ``values`` rounded to ``digits`` decimals (smaller JSON)."""
    return np.round(np.asarray(values, dtype=float), digits).tolist()


def finite(x) -> float | None:
    """``x`` as a float, None when it is not finite (JSON has no nan)."""
    x = float(x)
    return x if math.isfinite(x) else None


def json_ready(value):
    """``value`` with every float that is not finite replaced by None (JSON has no nan),
    tuples as lists."""
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    if isinstance(value, dict):
        return {k: json_ready(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [json_ready(v) for v in value]
    return value


# ------------------------------------------------------------------------------ the structure
def pyplot():
    """``matplotlib.pyplot`` on the file-only Agg backend: the page's figures are PNG images,
    and the server opens no window."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def structure_view(structure) -> dict:
    """The blocks of a structure as the page draws them.

    Parameters
    ----------
    structure : BlockArch or BlockAssembly
        An arch of any kind or a :class:`~archquake.geometry.Structure`; a block assembly is
        drawn by :func:`assembly_view`.

    Returns
    -------
    dict
        ``blocks`` (outline of every block [m]), ``kinds`` (``"voussoir"`` or ``"pier"`` per
        block), ``fill`` (``{"outlines", "blocks", "level"}``: every fill column, the block
        that carries it and the fill's surface [m]; None without fill), ``ground`` (segments
        [m] under the piers and springings), ``bounds`` ``[xmin, xmax, ymin, ymax]`` [m] and
        ``description``.
    """
    from ..geometry.structure import describe_arch

    if hasattr(structure, "interfaces") and hasattr(structure, "polygons"):
        return assembly_view(structure)
    n = structure.n_voussoirs
    blocks = [structure.outline(i, points=16) for i in range(n)]
    kinds = list(getattr(structure, "block_kinds", ("voussoir",) * n))
    kinds = ["pier" if "pier" in k else "voussoir" for k in kinds]
    fill = None
    columns = getattr(structure, "fill_columns", None)
    if columns is not None:
        carriers = list(getattr(structure, "arch_blocks", range(n)))
        fill = {"outlines": [rounded(o, 4) for o in columns.outlines], "blocks": carriers,
                "level": float(columns.level)}
    ground = [rounded(structure.joints[j], 4) for j in (0, -1)]
    points = np.concatenate(blocks + ([np.asarray(o) for o in columns.outlines]
                                      if columns is not None else []))
    return {"blocks": [rounded(b, 4) for b in blocks], "kinds": kinds, "fill": fill,
            "ground": ground,
            "bounds": [float(points[:, 0].min()), float(points[:, 0].max()),
                       float(points[:, 1].min()), float(points[:, 1].max())],
            "description": describe_arch(structure)}


def limit_view(results) -> dict:
    """Both limit analyses as the page draws them, in the structure's own frame.

    Parameters
    ----------
    results : (LimitAnalysis, LimitAnalysis)
        :func:`archquake.limit_analysis.both_directions` of the structure.

    Returns
    -------
    dict
        ``k_l``, ``k_r``, ``k`` = min [-], and per direction (``"l"``, ``"r"``): ``k``, the
        ``hinges`` (``x``, ``y`` [m], ``label``, ``joint``, ``face``, ``where`` on a structure;
        ``joint`` is numbered in the frame of the analysis, mirrored for Mech-r, as the command
        line reports it), the line of action of the resultant (``funicular``) and the
        ``pressure_points`` on the joints [m].
    """
    out = {}
    for r in results:
        flip = _MIRROR if r.direction == "r" else np.ones(2)
        labels = "ABCD" if r.is_four_hinge else [f"H{i + 1}" for i in range(len(r.hinges))]
        hinges = []
        for hinge, point, label in zip(r.hinges, r.hinge_points, labels, strict=False):
            entry = {"x": float(point[0] * flip[0]), "y": float(point[1]), "label": label,
                     "joint": int(hinge.joint), "face": hinge.face}
            if hasattr(r.arch, "joint_name"):
                entry["where"] = r.arch.joint_name(hinge.joint)
            hinges.append(entry)
        out[r.direction] = {"k": float(r.load_multiplier), "hinges": hinges,
                            "funicular": rounded(r.funicular() * flip, 4),
                            "pressure_points": rounded(r.thrust_line.points * flip, 4)}
    k_l, k_r = out["l"]["k"], out["r"]["k"]
    return {"k_l": k_l, "k_r": k_r, "k": min(k_l, k_r), **out}


# ------------------------------------------------------------------------------ block assemblies
DIRECTIONS = {"+x": "l", "-x": "r"}
"""The page's name of each direction of :func:`archquake.limit_analysis.assembly_limits`: the
forces toward +x are Mech-l's, toward -x Mech-r's (both drawn on the structure as it is: an
assembly's analysis is not mirrored)."""

DISPLACEMENT = 0.06
"""Largest displacement of a block corner in a drawn mechanism, as a fraction of the
structure's size [-] (as :func:`archquake.plotting.plot_assembly_limit` draws it)."""

def block_groups(assembly) -> tuple[str | None, list]:
    """The spans or rings of an assembly's blocks, read from their names by the builders' own
    readers (:func:`archquake.geometry.bridge.spans_of` and
    :func:`~archquake.geometry.bridge.rings_of`: :func:`~archquake.geometry.bridge.multi_span`
    names ``"span 2 voussoir 3"``, spans from 1;
    :func:`archquake.geometry.multi_ring` ``"ring 0, voussoir 4"``, ring 0 the intrados one).

    Returns
    -------
    (str or None, list)
        ``"span"``, ``"ring"`` or None (neither), and per block its span or ring counted from 1
        (ring 1 the intrados ring), None for a pier course or a block of neither.
    """
    from ..geometry.bridge import rings_of, spans_of

    n = assembly.n_blocks
    spans = [next(iter(spans_of(assembly, [i])), None) for i in range(n)]
    if any(g is not None for g in spans):
        return "span", spans
    rings = [next(iter(rings_of(assembly, [i])), None) for i in range(n)]
    if any(g is not None for g in rings):
        return "ring", [None if g is None else g + 1 for g in rings]
    return None, [None] * n


def describe_assembly(assembly) -> str:
    """One line on a block assembly: its spans or rings, blocks and interfaces."""
    kind, groups = block_groups(assembly)
    count = len({g for g in groups if g is not None})
    interfaces = int(np.asarray(assembly.interfaces.a).size)
    whole = f"{assembly.n_blocks} blocks and {interfaces} interfaces"
    if kind == "span":
        return (f"a bridge of {count} spans on {count + 1} piers: a block assembly of {whole} "
                f"(no interface slides)")
    if kind == "ring":
        ring = np.asarray(assembly.interfaces.kind) == "ring"
        mu = np.asarray(assembly.interfaces.friction, dtype=float)[ring]
        slides = ("the rings do not slide on each other" if not np.isfinite(mu).any()
                  else f"friction {float(mu.min()):g} between the rings")
        return (f"an arch of {count} ring{'' if count == 1 else 's'}: a block assembly of "
                f"{whole} ({slides})")
    return f"a block assembly of {whole}"


def assembly_view(assembly) -> dict:
    """The blocks of a block assembly as the page draws them (the keys of
    :func:`structure_view`).

    Parameters
    ----------
    assembly : BlockAssembly
        Several spans, several rings, or any assembly.

    Returns
    -------
    dict
        ``assembly`` True, ``blocks`` (outline of every block [m]), ``kinds`` (``"pier"`` for
        a pier course, else ``"voussoir"``), ``fill`` None, ``ground`` (the foundation
        interfaces [m]), ``bounds`` ``[xmin, xmax, ymin, ymax]`` [m], ``group`` (``"span"``,
        ``"ring"`` or None) and ``groups`` (each block's span or ring from 1, or None:
        :func:`block_groups`), ``description``.
    """
    from ..geometry.assembly import GROUND

    blocks = [np.asarray(p, dtype=float) for p in assembly.polygons]
    names = tuple(getattr(assembly, "names", None) or ())
    kinds = ["pier" if str(n).startswith("pier") else "voussoir" for n in names] or \
        ["voussoir"] * len(blocks)
    faces = assembly.interfaces
    ground = np.asarray(faces.a) == GROUND
    p0, p1 = np.asarray(faces.p0, dtype=float), np.asarray(faces.p1, dtype=float)
    points = np.concatenate(blocks)
    kind, groups = block_groups(assembly)
    return {"assembly": True, "blocks": [rounded(b, 4) for b in blocks], "kinds": kinds,
            "fill": None,
            "ground": [rounded([a, b], 4) for a, b in zip(p0[ground], p1[ground], strict=True)],
            "bounds": [float(points[:, 0].min()), float(points[:, 0].max()),
                       float(points[:, 1].min()), float(points[:, 1].max())],
            "group": kind, "groups": groups, "description": describe_assembly(assembly)}


def _moving_groups(result, groups: list) -> list[int]:
    """The spans or rings (from 1) with a block that moves in the mechanism of ``result``."""
    from ..geometry.bridge import moving_blocks

    if not math.isfinite(result.load_multiplier):
        return []
    return sorted({groups[j] for j in moving_blocks(result) if groups[j] is not None})


def assembly_mechanism_view(result, groups: list) -> dict:
    """One direction's collapse of an assembly under one friction law, as the page draws it.

    Parameters
    ----------
    result : AssemblyLimit
        :func:`archquake.limit_analysis.assembly_limit`.
    groups : list
        Every block's span or ring (:func:`block_groups`).

    Returns
    -------
    dict
        ``law``, ``k`` [-] and ``tilt`` [deg] (None: no collapse), ``converged``; the mechanism:
        ``displaced`` (``{"block", "outline"}``: every block that moves, displaced by its
        collapse velocity so that the fastest corner moves :data:`DISPLACEMENT` of the
        structure's size [m]), ``interfaces`` (``{"p0", "p1", "state", "hinge"}`` of every
        interface that rocks, slides or separates; ``hinge`` the end that stays closed of one
        that rocks, else None [m]), ``pressure_points`` of the loaded interfaces [m],
        ``thrust`` (the segments of the line of thrust,
        :meth:`~archquake.limit_analysis.AssemblyLimit.thrust_line`, each ``[P, X]`` [m]),
        ``moving`` (the spans or rings, from 1, whose blocks move), and the length of ring
        interface that opens (rocks or separates, without sliding) and that slides,
        ``ring_opens_m`` and ``ring_slides_m`` [m] (0 without rings).
    """
    c = result.contacts
    corners = np.concatenate([np.asarray(o, dtype=float) for o in c.outlines])
    scale = DISPLACEMENT * float(max(np.ptp(corners[:, 0]), np.ptp(corners[:, 1])) or 1.0)
    k = float(result.load_multiplier)
    displaced = []
    if math.isfinite(k):
        for j, outline in enumerate(c.outlines):
            outline = np.asarray(outline, dtype=float)
            moved = outline + scale * result.velocity_at(j, outline)
            if np.max(np.abs(moved - outline)) > 1e-3 * scale:
                displaced.append({"block": j, "outline": rounded(moved, 4)})
    interfaces = []
    for i, state in enumerate(result.state):
        if state == "closed" or not math.isfinite(k):
            continue
        hinge = None
        if "rocks" in state:
            end = c.p0[i] if result.opening[i, 0] < result.opening[i, 1] else c.p1[i]
            hinge = rounded(end, 4)
        interfaces.append({"p0": rounded(c.p0[i], 4), "p1": rounded(c.p1[i], 4),
                           "state": str(state), "kind": str(c.kind[i]), "hinge": hinge})
    normal = np.asarray(result.normal, dtype=float)
    loaded = np.isfinite(result.pressure[:, 0]) & (normal > 1e-9 * max(float(normal.max(
        initial=0.0)), 1e-300))
    opens, slides = result.ring_lengths() if math.isfinite(k) else (0.0, 0.0)
    thrust = rounded(result.thrust_line()[0], 4) if math.isfinite(k) else []
    return {"law": result.law, "k": finite(k), "tilt": finite(result.tilt) if math.isfinite(k)
            else None, "converged": bool(result.converged), "displaced": displaced,
            "interfaces": interfaces, "pressure_points": rounded(result.pressure[loaded], 4),
            "thrust": thrust,
            "moving": _moving_groups(result, groups),
            "ring_opens_m": opens, "ring_slides_m": slides}


def governing(laws: dict):
    """Of one direction's results by law, the one that governs: the non-associative law's when
    friction is given (slip without opening, the physical one), else the only one (as
    ``archquake limit`` takes it: :func:`archquake.limit_analysis.governing_law`)."""
    from ..limit_analysis import governing_law

    return governing_law(laws)


def assembly_limit_view(assembly, results) -> dict:
    """Both directions' collapse of a block assembly, under each friction law, as the page shows
    it.

    Parameters
    ----------
    assembly : BlockAssembly
        The structure.
    results : dict
        :func:`archquake.limit_analysis.assembly_limits` of it: ``{"+x": {law: AssemblyLimit},
        "-x": ...}``.

    Returns
    -------
    dict
        ``assembly`` True; ``k_l``, ``k_r`` (the governing law's multiplier toward +x and -x,
        :func:`governing`) and ``k`` = the least [-] (None: no collapse); ``group``
        (``"span"``, ``"ring"`` or None); per direction (``"l"`` for +x, ``"r"`` for -x,
        :data:`DIRECTIONS`): ``direction`` (``"+x"``/``"-x"``), ``laws`` (every law's
        :func:`assembly_mechanism_view`, the governing one first); and ``first``: the sentence
        saying which spans or rings move first, at the least k.
    """
    group, groups = block_groups(assembly)
    out = {"assembly": True, "group": group}
    ks = {}
    for direction, laws in results.items():
        main = governing(laws)
        ordered = [main] + [r for r in laws.values() if r is not main]
        name = DIRECTIONS[direction]
        out[name] = {"direction": direction,
                     "laws": [assembly_mechanism_view(r, groups) for r in ordered]}
        ks[name] = float(main.load_multiplier)
    k = min(ks.values())
    out.update(k_l=finite(ks["l"]), k_r=finite(ks["r"]), k=finite(k))
    out["first"] = _first_sentence(out, group, k)
    return out


def _first_sentence(out: dict, group: str | None, k: float) -> str:
    if not math.isfinite(k):
        return "no horizontal load makes it collapse"
    parts = []
    for name in ("l", "r"):
        main = out[name]["laws"][0]
        if main["k"] is None or main["k"] > k * (1 + 1e-6):
            continue
        moving = main["moving"]
        what = (f"{group}{'' if len(moving) == 1 else 's'} "
                f"{', '.join(str(m) for m in moving)}" if group and moving else "the blocks")
        verb = "moves" if group and len(moving) == 1 else "move"
        toward = "toward +x (Mech-l)" if name == "l" else "toward -x (Mech-r)"
        parts.append(f"{what} {verb} first {toward}")
    where = {"span": " (spans from the left)", "ring": " (ring 1 the intrados ring)"}
    return (f"at k = {k:.4f} ({math.degrees(math.atan(k)):.2f} deg of tilt): "
            f"{'; '.join(parts)}{where.get(group, '')}")


# ------------------------------------------------------------------------------ the code check
def _ag_text(value) -> str:
    """A PGA capacity as the page writes it: None is beyond the largest a_g searched."""
    return "a_g > 1.5 g" if value is None else f"a_g = {value:.3f} g"


def limit_state_verdict(check, limit_state: str) -> dict | None:
    """The verdict of one limit state of a code check, with the sentence an engineer signs.

    The limit state holds when one of the Circolare's routes (the linear check, the nonlinear
    check) holds in both directions (:meth:`LocalMechanismCheck.holds
    <archquake.site.local_mechanism.LocalMechanismCheck.holds>`); each route's ratio is its
    lesser direction's capacity/demand.

    Parameters
    ----------
    check : LocalMechanismCheck
        :func:`archquake.site.local_mechanism.check_local_mechanism`.
    limit_state : {"SLV", "SLC"}

    Returns
    -------
    dict or None
        ``limit_state``, ``holds``, ``ag_g`` (the site's a_g [g]), ``pga_capacity_g`` (the
        a_g up to which it holds [g]; None beyond 1.5 g), ``ratios`` ``{route: ratio}`` [-]
        and ``sentence``, e.g. ``"SLV holds: capacity/demand 2.11 (linear), 1.84
        (nonlinear); PGA capacity a_g = 0.707 g against the site's 0.25 g"``; None when the
        limit state was not checked.
    """
    holds = check.holds(limit_state)
    if holds is None:
        return None
    ratios = {route: min(c.ratio for c in checks)
              for route, checks in check.routes(limit_state).items()}
    capacity = check.pga_capacity(limit_state)
    ag = check.actions[limit_state].ag
    routes = ", ".join(f"{r:.2f} ({route})" for route, r in ratios.items())
    sentence = (f"{limit_state} {'holds' if holds else 'FAILS'}: capacity/demand {routes}; "
                f"PGA capacity {_ag_text(capacity)} against the site's {ag:g} g")
    return {"limit_state": limit_state, "holds": holds, "ag_g": ag,
            "pga_capacity_g": capacity, "ratios": ratios, "sentence": sentence}


def check_view(check) -> dict:
    """A code check of the collapse mechanism as the page shows it.

    Parameters
    ----------
    check : LocalMechanismCheck
        :func:`archquake.site.local_mechanism.check_local_mechanism`.

    Returns
    -------
    dict
        ``code`` (edition and clauses), ``verdicts`` (:func:`limit_state_verdict` of each limit
        state of the actions; ``holds`` None and a sentence saying so for one that no check could be
        made of, as SLC when the nonlinear check does not apply), ``participation``, ``linear`` and
        ``nonlinear`` (the library's ``to_dict``; each nonlinear check also with ``au_star_g``,
        :math:`a^*(d_u^*)` [g], and ``d0_star_m``), ``curves`` (per direction: ``direction``,
        ``d0_star_m``, the capacity curve's ``d_star_m`` [m] and ``a_star_g`` [g]), ``actions`` (per
        limit state: ``ag_g`` and the spectrum's ``to_dict``), ``passes`` and ``notes``.
    """
    from ..constants import GRAVITY
    from ..site.local_mechanism import LIMIT_STATES

    whole = check.to_dict()
    curves = {c.direction: c for c in check.curves}
    nonlinear = []
    for c in check.nonlinear:
        curve = curves[c.direction]
        nonlinear.append({**c.to_dict(), "d0_star_m": curve.d0,
                          "au_star_g": float(curve.acceleration_at(c.ultimate_displacement))
                          / GRAVITY})
    verdicts = []
    for state in LIMIT_STATES:
        verdict = limit_state_verdict(check, state)
        if verdict is None and state in check.actions:  # asked for, but no check applied
            verdict = {"limit_state": state, "holds": None, "ag_g": check.actions[state].ag,
                       "pga_capacity_g": None, "ratios": {},
                       "sentence": f"{state} not checked: no check of {state} could be made "
                                   "for this structure (see the note below)"}
        if verdict is not None:
            verdicts.append(verdict)
    return json_ready({
        "code": whole["code"], "verdicts": verdicts, "passes": whole["passes"],
        "participation": whole["participation"], "linear": whole["linear"],
        "nonlinear": nonlinear,
        "curves": [{"direction": c.direction, "d0_star_m": c.d0,
                    "d_star_m": rounded(c.spectral_displacement, 7),
                    "a_star_g": rounded(c.spectral_acceleration / GRAVITY, 7)}
                   for c in check.curves],
        "actions": whole["actions"], "notes": whole["notes"]})


# ------------------------------------------------------------------------------ the motion
def animation_end(*ends: float) -> float:
    """The end of an animation [s]: the latest of ``ends`` (at most
    :data:`MAX_ANIMATION_TIME`)."""
    return min(max([e for e in ends if math.isfinite(e)], default=0.0), MAX_ANIMATION_TIME)


def frame_rate(end: float, blocks: int) -> float:
    """Frames per second of an animation of ``blocks`` blocks lasting ``end`` seconds:
    :data:`FRAME_RATE`, or fewer (at least one) to keep within :data:`MAX_BLOCK_FRAMES`."""
    return float(min(FRAME_RATE, max(1.0, MAX_BLOCK_FRAMES / (max(blocks, 1) * max(end, 1e-9)))))


def frame_times(*ends: float, rate: float = FRAME_RATE) -> np.ndarray:
    """Times of the frames of an animation [s]: ``rate`` per second from 0 to
    :func:`animation_end` of ``ends``."""
    end = animation_end(*ends)
    return np.arange(int(math.floor(end * rate + 1e-9)) + 1) / rate


def _rotation(angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s], [s, c]])


def mechanism_motion(mechanism, theta: float, centres: np.ndarray) -> np.ndarray:
    r"""Rigid motion of every block of a four-link mechanism at ``theta``, in its own frame.

    Link k turns by :math:`\delta_k` (:mod:`archquake.fourlink.mechanism`): the blocks of AB
    about A, those of CD about D, those of BC about B, which moves to :math:`B(\theta)`; so a
    block's reference point ``c`` goes to :math:`P_k' + R(\delta_k)(c - P_k)`.

    Parameters
    ----------
    mechanism : FourLinkMechanism
        Mech-l or Mech-r (on its own, possibly mirrored, arch).
    theta : float
        Lagrangian coordinate [rad].
    centres : ndarray, shape (n, 2)
        Reference point of every block, in the mechanism's frame [m].

    Returns
    -------
    ndarray, shape (n, 3)
        ``(dx, dy, rotation)`` of every block [m, m, rad]; zero for the blocks outside A..D.
    """
    out = np.zeros((centres.shape[0], 3))
    joints = [h.joint for h in mechanism.hinges]
    a, b_u, _, d = mechanism.hinge_points
    theta_bc, theta_cd = (float(x) for x in mechanism.closure(theta))
    b = a + mechanism.ab * np.array([math.cos(theta), math.sin(theta)])
    turns = (theta - mechanism.theta_u, theta_bc - mechanism.theta_bc_u,
             theta_cd - mechanism.theta_cd_u)
    pivots = ((a, a), (b_u, b), (d, d))
    for k, ((before, after), turn) in enumerate(zip(pivots, turns, strict=True)):
        blocks = slice(joints[k], joints[k + 1])
        c = centres[blocks]
        moved = after + (c - before) @ _rotation(turn).T
        out[blocks, :2] = moved - c
        out[blocks, 2] = turn
    return out


def four_link_motion(model, history, times: np.ndarray) -> np.ndarray:
    """Rigid motion of every block of the structure at ``times`` in a four-link time history,
    in the structure's own frame.

    Parameters
    ----------
    model : FourLinkModel
        The model that made ``history``.
    history : TimeHistory
        Its time history; at a time after its end the last recorded state is kept.
    times : ndarray
        Times of the frames [s].

    Returns
    -------
    ndarray, shape (len(times), n, 3)
        ``(dx, dy, rotation)`` of every block about its centroid
        (:attr:`BlockArch.centroids <archquake.geometry.BlockArch.centroids>`).
    """
    arch = model.arch
    n = arch.n_voussoirs
    centres = np.asarray(arch.centroids)
    mirrored = centres[::-1] * _MIRROR  # block n-1-i of the mirror is block i
    t = history.t
    theta = np.concatenate([s.theta for s in history.segments])
    state = history.mechanism
    index = np.clip(np.searchsorted(t, times, side="right") - 1, 0, t.size - 1)
    out = np.zeros((times.size, n, 3))
    for f, i in enumerate(index):
        if state[i] == "l":
            out[f] = mechanism_motion(model.mechanisms[0], float(theta[i]), centres)
        elif state[i] == "r":
            moved = mechanism_motion(model.mechanisms[1], float(theta[i]), mirrored)[::-1]
            out[f] = moved * np.array([-1.0, 1.0, -1.0])
    return out


def block_motion(history, times: np.ndarray) -> np.ndarray:
    """Rigid motion of every block at ``times`` in a rigid-block time history.

    Parameters
    ----------
    history : BlockHistory
        The history; at a time after its end the last record is kept.
    times : ndarray
        Times of the frames [s].

    Returns
    -------
    ndarray, shape (len(times), n, 3)
        ``(dx, dy, rotation)`` of every block about its centroid (``history.assembly``), as
        :meth:`~archquake.rigid_blocks.BlockHistory.outlines` moves it.
    """
    index = np.clip(np.searchsorted(history.times, times, side="right") - 1, 0,
                    history.times.size - 1)
    return np.concatenate([history.displacements[index],
                           history.rotations[index][..., None]], axis=2)


def _series(t, y) -> dict:
    """A time series thinned to at most :data:`SERIES_POINTS` points for a small plot."""
    t, y = np.asarray(t, dtype=float), np.asarray(y, dtype=float)
    step = max(1, int(math.ceil(t.size / SERIES_POINTS)))
    return {"t": rounded(t[::step], 4), "y": rounded(y[::step], 6)}


def motion_view(motion) -> dict:
    """The ground acceleration for a small plot: ``name``, ``duration`` [s] and the series
    ``t`` [s], ``y`` [g] to a little past its end."""
    from ..geometry import GRAVITY
    from ..ground_motion import LINEAR

    end = float(motion.duration)
    t = np.linspace(0.0, end * 1.1 if end > 0 else 1.0, SERIES_POINTS)
    if motion.kind == LINEAR:  # a record: its own samples, thinned
        t = np.asarray(motion.times, dtype=float)
    return {"name": motion.name, "duration": end,
            **_series(t, np.asarray(motion.acceleration(t)) / GRAVITY)}


def four_link_outcome(outcome) -> dict:
    """The outcome of the four-link model as the page shows it."""
    return {"status": outcome.status.label, "half_cycle": int(outcome.half_cycle),
            "impacts": int(outcome.impacts), "collapse_time": finite(outcome.collapse_time),
            "max_phi": finite(outcome.max_phi)}


def block_outcome(outcome) -> dict:
    """The outcome of the rigid-block model as the page shows it."""
    return {"status": outcome.status.label, "collapse_time": finite(outcome.collapse_time),
            "max_rotation": finite(outcome.max_rotation),
            "max_crown_drop": finite(outcome.max_crown_drop), "decided": bool(outcome.decided)}


def four_link_view(model, history, times) -> dict:
    """A four-link time history for the page: the blocks, their motion per frame, the outcome
    and the rotation phi(t) [rad] (+ Mech-l, - Mech-r)."""
    arch = model.arch
    return {"blocks": [rounded(arch.outline(i, points=16), 4) for i in range(arch.n_voussoirs)],
            "centres": rounded(arch.centroids, 5),
            "frames": rounded(four_link_motion(model, history, times), 5),
            "outcome": four_link_outcome(history.outcome),
            "end": float(history.t[-1]), "series": _series(history.t, history.phi),
            "restitution": [float(c) for c in model.restitution]}


def rigid_block_view(history, times) -> dict:
    """A rigid-block time history for the page: the blocks, their motion per frame, the
    outcome and the drop of the crown [m] over time."""
    assembly = history.assembly
    return {"blocks": [rounded(o, 4) for o in assembly.outlines],
            "centres": rounded(assembly.centroids, 5),
            "frames": rounded(block_motion(history, times), 5),
            "outcome": block_outcome(history.outcome),
            "end": float(history.times[-1]), "series": _series(history.times,
                                                               history.crown_drop)}


__all__ = ["DIRECTIONS", "DISPLACEMENT", "FRAME_RATE", "MAX_ANIMATION_TIME", "MAX_BLOCK_FRAMES",
           "animation_end", "assembly_limit_view", "assembly_mechanism_view", "assembly_view",
           "block_groups", "block_motion", "block_outcome", "check_view", "describe_assembly",
           "finite", "four_link_motion", "four_link_outcome", "four_link_view", "frame_rate",
           "frame_times", "governing", "json_ready", "limit_state_verdict", "limit_view",
           "mechanism_motion", "motion_view", "rigid_block_view", "rounded", "structure_view"]
