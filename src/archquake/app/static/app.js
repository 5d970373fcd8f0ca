// archquake app: the page. It sends the form to the server's JSON API and draws what comes back
// (SVG); long computations are jobs that it polls. No library, no build step.
"use strict";

const $ = (id) => document.getElementById(id);
const SVG = "http://www.w3.org/2000/svg";
const state = {
  options: null, geometry: null, record: null, structure: null, structureRequest: null,
  shake: null, domain: null, assess: null, anim: null, checkRequest: null, unavailable: null,
};

// ---------------------------------------------------------------------------- the API
async function api(path, body, init = {}) {
  const options = { ...init };
  if (body !== undefined) {
    options.method = options.method || "POST";
    if (body instanceof Blob) {
      options.body = body;
    } else {
      options.body = JSON.stringify(body);
      options.headers = { "Content-Type": "application/json", ...(options.headers || {}) };
    }
  }
  const response = await fetch(path, options);
  const type = response.headers.get("content-type") || "";
  const data = type.includes("json") ? await response.json() : await response.blob();
  if (!response.ok) {
    const error = new Error((data && data.error) || `${response.status} ${response.statusText}`);
    error.status = response.status;
    throw error;
  }
  return data;
}

function status(text) { $("status").textContent = text; }

function showMessage(text) {
  const box = $("message");
  document.querySelectorAll("[data-option].invalid").forEach((el) => el.classList.remove("invalid"));
  if (!text) { box.hidden = true; box.textContent = ""; return; }
  box.hidden = false;
  box.textContent = text;
  // the first word of the message that is a field of the form (messages name their fields)
  const fields = new Set([...document.querySelectorAll("[data-option]")].map((el) => el.dataset.option));
  const key = (text.match(/[a-z][a-z0-9_]*/g) || []).find((word) => fields.has(word));
  if (key) {
    document.querySelectorAll(`[data-option="${key}"]`).forEach((el) => el.classList.add("invalid"));
  }
}

// ---------------------------------------------------------------------------- the form
const value = (id) => $(id).value.trim();
const number = (id) => (value(id) === "" ? null : Number(value(id)));

function structureSpec() {
  const spec = {};
  if (fromFile()) {
    if (state.geometry) spec.geometry = state.geometry.token;
  } else {
    const shape = value("shape");
    if (shape !== "circular") spec.shape = shape;
    if (shape === "circular" && value("circle-by") === "angle") {
      spec.radius = number("radius");
      spec.embrace = number("embrace");
    } else {
      spec.span = number("span");
      spec.rise = number("rise");
    }
    spec.thickness = number("thickness");
    spec.voussoirs = number("voussoirs");
    if (value("faces") !== "curved") spec.faces = value("faces");
  }
  if ($("piers-on").checked) {
    spec.piers = [value("pier-width"), value("pier-height"), value("pier-courses")].join(",");
  }
  const spans = value("spans");
  if (spans !== "" && spans !== "1") {
    spec.spans = number("spans");
    spec.pier_middle = [value("middle-width"), value("middle-height"), value("middle-courses")].join(",");
  }
  const rings = value("rings");
  if (rings !== "" && rings !== "1") {
    spec.rings = number("rings");
    if (value("ring-bond") !== "aligned") spec.ring_bond = value("ring-bond");
    if (value("ring-friction") !== "") spec.ring_friction = number("ring-friction");
  }
  if ($("fill-on").checked) {
    spec.fill_cover = number("fill-cover");
    spec.fill_density = number("fill-density");
    spec.fill_inertia = value("fill-inertia");
    if (value("fill-phi") !== "" || value("fill-mobilisation") !== "") {
      spec.fill_passive = [value("fill-phi"), value("fill-mobilisation")].join(",");
    }
  }
  for (const key of ["density", "epsilon", "seed"]) {
    if (value(key) !== "") spec[key] = number(key);
  }
  return spec;
}

function motionSpec() {
  const source = value("motion-source");
  const spec = { reverse: $("reverse").checked };
  if (source === "pulse") {
    spec.motion = value("pulse");
    spec.amplitude = number("amplitude");
    spec.duration = number("duration");
    const params = {};
    document.querySelectorAll("#pulse-params input").forEach((el) => {
      if (el.value.trim() !== "") params[el.dataset.param] = Number(el.value);
    });
    spec.params = params;
  } else if (source === "record") {
    if (!state.record) throw new Error("choose a record file first");
    spec.record = state.record.token;
    spec.scale_to = number("scale-to");
  } else {
    spec.suite = value("suite");
    spec.suite_record = Number(value("suite-record"));
    spec.scale_to = number("scale-to");
  }
  return spec;
}

function modelsSpec() {
  return { restitution: value("restitution") || null, friction: number("friction") };
}

// ---------------------------------------------------------------------------- drawing
function el(tag, attrs = {}, parent = null) {
  const node = document.createElementNS(SVG, tag);
  for (const [k, v] of Object.entries(attrs)) node.setAttribute(k, v);
  if (parent) parent.appendChild(node);
  return node;
}

const pointsText = (pts) => pts.map((p) => `${p[0]},${p[1]}`).join(" ");

// An SVG in metres, y up: returns the group to draw in and a function placing text.
function scene(svg, bounds, margin = 0.08) {
  svg.replaceChildren();
  let [x0, x1, y0, y1] = bounds;
  const pad = margin * Math.max(x1 - x0, y1 - y0, 1e-6);
  x0 -= pad; x1 += pad; y0 -= pad; y1 += pad;
  svg.setAttribute("viewBox", `${x0} ${-y1} ${x1 - x0} ${y1 - y0}`);
  const world = el("g", { transform: "scale(1,-1)" }, svg);
  const scale = (y1 - y0) / 300;
  const text = (x, y, label, cls = "label") => {
    const t = el("text", { x, y: -y, class: cls, "text-anchor": "middle",
                           "dominant-baseline": "middle",
                           "font-size": 13 * scale }, svg);
    t.textContent = label;
    return t;
  };
  return { world, text, scale };
}

function drawBlocks(world, structure, blocks = structure.blocks) {
  const polygons = [];
  const columns = [];
  if (structure.fill) {
    structure.fill.outlines.forEach((outline, k) => {
      columns.push([el("polygon", { points: pointsText(outline), class: "column" }, world),
                    structure.fill.blocks[k]]);
    });
  }
  blocks.forEach((outline, i) => {
    const kind = structure.kinds[i] === "pier" ? "block pier" : "block";
    polygons.push(el("polygon", { points: pointsText(outline), class: kind }, world));
  });
  for (const segment of structure.ground) {
    const [a, b] = segment;
    const w = Math.abs(b[0] - a[0]) || 1;
    const xs = [Math.min(a[0], b[0]) - 0.3 * w, Math.max(a[0], b[0]) + 0.3 * w];
    el("line", { x1: xs[0], y1: a[1], x2: xs[1], y2: b[1], class: "ground" }, world);
  }
  return { polygons, columns };
}

// The bounds of the structure grown to hold the displaced blocks of both directions' mechanisms.
function assemblyBounds(answer) {
  let [x0, x1, y0, y1] = answer.structure.bounds;
  for (const direction of ["l", "r"]) {
    const limit = answer.limit && answer.limit[direction];
    if (!limit) continue;
    for (const d of limit.laws[0].displaced) {
      for (const [x, y] of d.outline) {
        x0 = Math.min(x0, x); x1 = Math.max(x1, x); y0 = Math.min(y0, y); y1 = Math.max(y1, y);
      }
    }
  }
  return [x0, x1, y0, y1];
}

// A block assembly's mechanism (the governing friction law's), as plot_assembly_limit draws it:
// the blocks, the displaced ones dashed, the interfaces that move coloured by what they do, the
// hinges, the pressure points and the line of thrust through them.
function drawAssemblyMechanism(svg, answer, direction) {
  const s = answer.structure;
  const bounds = assemblyBounds(answer);
  // a wide structure (a bridge) gets a lower drawing, not a band of empty space
  const aspect = (bounds[3] - bounds[2]) / Math.max(bounds[1] - bounds[0], 1e-9);
  svg.style.height = `${Math.round(Math.max(150, Math.min(300, 1.1 * svg.clientWidth * aspect)))}px`;
  const { world, scale } = scene(svg, bounds, 0.04);
  drawBlocks(world, s);
  const limit = answer.limit && answer.limit[direction];
  if (!limit) return;
  const law = limit.laws[0];
  for (const d of law.displaced) {
    el("polygon", { points: pointsText(d.outline), class: "displaced", "data-block": d.block }, world);
  }
  const classOf = { rocks: "rocks", slides: "slides", "rocks and slides": "both", separates: "separates" };
  for (const f of law.interfaces) {
    el("line", { x1: f.p0[0], y1: f.p0[1], x2: f.p1[0], y2: f.p1[1],
                 class: `iface ${classOf[f.state] || "rocks"}` }, world);
  }
  for (const seg of law.thrust || []) {
    el("line", { x1: seg[0][0], y1: seg[0][1], x2: seg[1][0], y2: seg[1][1], class: "thrust" }, world);
  }
  for (const p of law.pressure_points) {
    el("circle", { cx: p[0], cy: p[1], r: 2 * scale, class: "point dark" }, world);
  }
  for (const f of law.interfaces) {
    // a ring interface is many short chords: its hinges would hide it (the table says how
    // much of it opens and slides)
    if (f.hinge && f.kind !== "ring") el("circle", { cx: f.hinge[0], cy: f.hinge[1], r: 5 * scale, class: "hinge" }, world);
  }
}

function drawMechanism(svg, answer, direction) {
  if (answer.structure.assembly) { drawAssemblyMechanism(svg, answer, direction); return; }
  svg.style.height = "";
  const s = answer.structure;
  const { world, text, scale } = scene(svg, s.bounds);
  drawBlocks(world, s);
  const limit = answer.limit && answer.limit[direction];
  if (!limit) return;
  el("polyline", { points: pointsText(limit.funicular), class: "thrust" }, world);
  for (const p of limit.pressure_points) {
    el("circle", { cx: p[0], cy: p[1], r: 3 * scale, class: "point" }, world);
  }
  const span = s.bounds[1] - s.bounds[0];
  for (const h of limit.hinges) {
    el("circle", { cx: h.x, cy: h.y, r: 6 * scale, class: "hinge" }, world);
    const up = h.face === "extrados" ? 1 : -1;
    text(h.x, h.y + up * 0.05 * span, h.label);
  }
}

function setK(answer) {
  const fmt = (k) => (k === null || k === undefined ? "–" : k.toFixed(4));
  const limit = answer && answer.limit;
  $("k-l").textContent = limit ? fmt(limit.k_l) : "–";
  $("k-r").textContent = limit ? fmt(limit.k_r) : "–";
  $("k-value").textContent = limit ? fmt(limit.k) : "–";
}

function showStructure(answer) {
  state.structure = answer;
  setK(answer);
  $("description").textContent = answer.structure.description;
  const verdict = $("verdict");
  if (answer.verdict) {
    verdict.hidden = false;
    verdict.textContent = `${answer.verdict[0].toUpperCase()}${answer.verdict.slice(1)}: ${answer.message}`;
  } else {
    verdict.hidden = true;
  }
  drawMechanism($("svg-l"), answer, "l");
  drawMechanism($("svg-r"), answer, "r");
  showAssembly(answer);
}

// For a block assembly: the legend of its drawing, every direction and law's k and tilt, which
// spans or rings move first, and the parts of the page that need one chain of voussoirs.
function showAssembly(answer) {
  const assembly = Boolean(answer && answer.structure.assembly);
  $("legend-chain").hidden = assembly;
  $("legend-assembly").hidden = !assembly;
  const limit = assembly ? answer.limit : null;
  $("assembly-first").hidden = !limit;
  $("assembly-laws").hidden = !limit;
  if (limit) {
    $("assembly-first").textContent = `${limit.first[0].toUpperCase()}${limit.first.slice(1)}`;
    const what = limit.group ? `${limit.group}s that move` : "";
    const rings = limit.group === "ring";
    const rows = [];
    for (const direction of ["l", "r"]) {
      for (const [i, law] of limit[direction].laws.entries()) {
        rows.push([`${MECH[direction]} (${limit[direction].direction})`,
                   `${law.law}${i === 0 && limit[direction].laws.length > 1 ? " (governs)" : ""}`,
                   fixed(law.k, 4), fixed(law.tilt, 2),
                   ...(what ? [law.moving.join(", ") || "–"] : []),
                   ...(rings ? [fixed(law.ring_opens_m, 2), fixed(law.ring_slides_m, 2)] : []),
                   law.converged ? "" : "did not converge"]);
      }
    }
    tableOf($("assembly-laws"),
      "Limit analysis of the block assembly (archquake limit): k = tan(tilt) of a tilting table",
      ["direction", "friction law", "k [-]", "tilt [deg]", ...(what ? [what] : []),
       ...(rings ? ["ring interfaces open [m]", "slide [m]"] : []), ""], rows);
  }
  const unavailable = (answer && answer.unavailable) || null;
  $("shake-note").hidden = !unavailable;
  $("shake-note").textContent = unavailable
    ? "Several spans or rings: \u201cShake it\u201d runs the rigid blocks alone on the whole " +
      "assembly; the four-link model is the mechanism of one chain of voussoirs." : "";
  const was = state.unavailable;
  state.unavailable = unavailable;
  if (!state.domain && (unavailable || was)) {
    $("domain-start").disabled = Boolean(unavailable && unavailable.domain);
    $("domain-status").textContent = unavailable && unavailable.domain
      ? `Not available: ${unavailable.domain}` : "not computed";
  }
  if (!state.assess && (unavailable || was)) {
    $("assess").disabled = Boolean(unavailable && unavailable.assess);
    $("assess-status").textContent = unavailable && unavailable.assess
      ? `Not available: ${unavailable.assess}` : "";
  }
}

// ---------------------------------------------------------------------------- live structure
let structureTimer = null;
function structureChanged() {
  clearTimeout(structureTimer);
  structureTimer = setTimeout(updateStructure, 120);
  checkChanged();
}

function clearStructure(note) {
  state.structure = null;
  setK(null);
  $("verdict").hidden = true;
  $("description").textContent = note;
  for (const id of ["svg-l", "svg-r"]) { $(id).replaceChildren(); $(id).style.height = ""; }
  showAssembly(null);
}

const fromFile = () => document.querySelector("input[name=source]:checked").value === "file";

async function updateStructure() {
  if (state.structureRequest) state.structureRequest.abort();
  if (fromFile() && !state.geometry) {
    clearStructure("choose a geometry file: its blocks and limit analysis appear here");
    status("waiting for a geometry file");
    return;
  }
  const controller = new AbortController();
  state.structureRequest = controller;
  status("analysing…");
  try {
    const answer = await api("/api/structure", { structure: structureSpec() },
                             { signal: controller.signal });
    showMessage("");
    showStructure(answer);
    status(answer.verdict ? answer.verdict : "ready");
  } catch (error) {
    if (error.name === "AbortError") return;
    showMessage(error.message);
    setK(null);
    status("input refused");
  }
}

// ---------------------------------------------------------------------------- the code check
const MECH = { l: "Mech-l", r: "Mech-r", "+x": "toward +x", "-x": "toward -x" };
const COLOURS = { l: "#1f77b4", r: "#ff7f0e" };
let checkTimer = null;
function checkChanged() {
  clearTimeout(checkTimer);
  checkTimer = setTimeout(updateCheck, 150);
}

function siteSpec() {
  const spec = {};
  document.querySelectorAll("#site-section [data-site]").forEach((input) => {
    if (input.closest("#slc-fields") && !$("slc-on").checked) return;
    const v = input.value.trim();
    if (v !== "") spec[input.dataset.site] = input.type === "number" ? Number(v) : v;
  });
  return spec;
}

function showCheckMessage(text) {
  const box = $("check-message");
  document.querySelectorAll("[data-site].invalid").forEach((e) => e.classList.remove("invalid"));
  box.hidden = !text;
  box.textContent = text || "";
  const word = text ? (text.match(/^[a-z][a-z0-9_]*/) || [""])[0] : "";
  document.querySelectorAll(`[data-site="${word}"]`).forEach((e) => e.classList.add("invalid"));
}

function clearCheck(note) {
  $("check-verdicts").replaceChildren();
  $("check-site").textContent = note || "";
  $("check-linear").replaceChildren();
  $("check-nonlinear").replaceChildren();
  $("check-curve").replaceChildren();
  $("check-legend").replaceChildren();
  $("check-figure").hidden = true;
  $("check-notes").textContent = "";
}

async function updateCheck() {
  if (state.checkRequest) state.checkRequest.abort();
  if (fromFile() && !state.geometry) {
    showCheckMessage("");
    clearCheck("choose a geometry file: its code check appears here");
    return;
  }
  const controller = new AbortController();
  state.checkRequest = controller;
  $("check-panel").classList.add("stale");
  $("check-progress").textContent = "checking…";
  try {
    const answer = await api("/api/check", { structure: structureSpec(), site: siteSpec() },
                             { signal: controller.signal });
    showCheckMessage("");
    showCheck(answer);
  } catch (error) {
    if (error.name === "AbortError") return;
    clearCheck("");
    showCheckMessage(error.message);
  }
  $("check-panel").classList.remove("stale");
  $("check-progress").textContent = "";
}

const fixed = (x, digits) => (x === null || x === undefined ? "–" : x.toFixed(digits));
const upTo = (ag) => (ag === null || ag === undefined ? "> 1.5" : ag.toFixed(3));

function tableOf(table, caption, head, rows) {
  table.replaceChildren();
  table.hidden = rows.length === 0;  // a check not made: the note says why
  const cap = document.createElement("caption");
  cap.textContent = caption;
  table.appendChild(cap);
  const tr = document.createElement("tr");
  for (const h of head) {
    const th = document.createElement("th");
    th.innerHTML = h;  // the page's own headings, with sub/superscripts
    tr.appendChild(th);
  }
  table.appendChild(tr);
  for (const row of rows) {
    const line = document.createElement("tr");
    for (const cell of row) {
      const td = document.createElement("td");
      if (typeof cell === "boolean") {
        td.textContent = cell ? "holds" : "FAILS";
        td.className = cell ? "holds" : "fails";
      } else {
        td.textContent = cell;
      }
      line.appendChild(td);
    }
    table.appendChild(line);
  }
}

function showCheck(answer) {
  if (!answer.check) {
    clearCheck("");
    const p = document.createElement("p");
    p.className = "verdict";
    p.textContent = `${answer.verdict[0].toUpperCase()}${answer.verdict.slice(1)}: ${answer.message}`;
    $("check-verdicts").replaceChildren(p);
    return;
  }
  const c = answer.check;
  $("check-verdicts").replaceChildren(...c.verdicts.map((v) => {
    const p = document.createElement("p");
    p.className = `check-verdict ${v.holds === null ? "unchecked" : v.holds ? "holds" : "fails"}`;
    p.id = `check-verdict-${v.limit_state}`;
    p.textContent = v.sentence;
    return p;
  }));
  const fc = answer.confidence_factor;
  const level = { "1.35": "LC1", "1.20": "LC2", "1.00": "LC3" }[fc.toFixed(2)];
  $("check-site").textContent = Object.entries(c.actions).map(([stateName, a]) => {
    const s = a.spectrum;
    return `${stateName}: ${s.code} spectrum, soil ${s.soil}, topography ${s.topography}: ` +
      `a_g = ${s.ag} g, F0 = ${s.f0}, Tc* = ${s.tc_star} s; S = S_S S_T = ${s.s.toFixed(3)}, ` +
      `PGA = a_g S = ${s.pga.toFixed(3)} g, T_B = ${s.t_b.toFixed(3)} s, ` +
      `T_C = ${s.t_c.toFixed(3)} s, T_D = ${s.t_d.toFixed(2)} s, damping ${s.damping} %`;
  }).join("\n") + `\nKnowledge level ${level}: confidence factor F_C = ${fc.toFixed(2)} (§C8.5.4).`;
  const linear = Object.fromEntries(c.linear.map((x) => [x.direction, x]));
  const q = c.linear.length ? c.linear[0].behaviour_factor : null;
  tableOf($("check-linear"),
    "Equivalent oscillator (eqs. C8.7.1.2-4) and linear check at SLV (§C8.7.1.2.1): " +
    `a0* ≥ a_g S / q${q === null ? "" : `, q = ${q}`}`,
    ["", "α<sub>0</sub> [-]", "M* [t/m]", "e* [-]", "a<sub>0</sub>* [g]",
     "a<sub>g</sub> S / q [g]", "capacity / demand [-]", "holds up to a<sub>g</sub> [g]", ""],
    c.participation.map((p) => {
      const l = linear[p.direction];
      return [MECH[p.direction], fixed(p.alpha0, 4), fixed(p.participating_mass_kg_per_m / 1000, 2),
              fixed(p.mass_fraction, 4), fixed(p.a0_star_g, 4),
              l ? fixed(l.demand_g, 4) : "–", l ? fixed(l.ratio, 2) : "–",
              l ? upTo(l.pga_capacity_ag_g) : "–", l ? l.passes : "not made"];
    }));
  tableOf($("check-nonlinear"),
    "Nonlinear check (§C8.7.1.2.2): d_u* ≥ S_De(T_s); d_u* = 0.24 d0* at SLV, 0.40 d0* at SLC; " +
    "T_s at d_s* = 0.4 d_u*",
    ["", "", "d<sub>0</sub>* [m]", "d<sub>u</sub>* [m]", "T<sub>s</sub> [s]",
     "S<sub>De</sub>(T<sub>s</sub>) [m]", "capacity / demand [-]", "holds up to a<sub>g</sub> [g]", ""],
    c.nonlinear.map((n) => [n.limit_state, MECH[n.direction], fixed(n.d0_star_m, 4),
                            fixed(n.du_star_m, 4), fixed(n.Ts_s, 3), fixed(n.demand_SDe_m, 4),
                            fixed(n.ratio, 2), upTo(n.pga_capacity_ag_g), n.passes]));
  $("check-figure").hidden = c.curves.length === 0;
  capacityChart($("check-curve"), $("check-legend"), c);
  $("check-notes").textContent = c.notes.length ? `Note: ${c.notes.join("; ")}.` : "";
}

// Ticks at 1, 2 or 5 times a power of ten, about n of them up to top.
function ticks(top, n = 5) {
  const raw = top / n;
  const power = 10 ** Math.floor(Math.log10(raw));
  const step = [1, 2, 5, 10].map((m) => m * power).find((s) => s >= raw);
  const out = [];
  for (let k = 0; k === 0 || out[k - 1] < top - 1e-9 * step; k += 1) {
    out.push(Number((k * step).toPrecision(12)));
  }
  return out;  // the last one at or past top
}

function capacityChart(svg, legend, c) {
  svg.replaceChildren();
  const W = 520, H = 300, L = 52, B = 38, T = 10, R = 14;
  svg.setAttribute("viewBox", `0 0 ${W} ${H}`);
  let curves = c.curves;
  const same = curves.length === 2 && curves[0].d_star_m.length === curves[1].d_star_m.length &&
    curves[0].d_star_m.every((d, i) => Math.abs(d - curves[1].d_star_m[i]) < 1e-6 &&
                                       Math.abs(curves[0].a_star_g[i] - curves[1].a_star_g[i]) < 1e-6);
  if (same) curves = curves.slice(0, 1);
  const linear = c.linear.length ? c.linear[0] : null;
  let xmax = 0, ymax = 0;
  for (const k of curves) { xmax = Math.max(xmax, ...k.d_star_m); ymax = Math.max(ymax, ...k.a_star_g); }
  for (const n of c.nonlinear) xmax = Math.max(xmax, n.demand_SDe_m);
  if (linear) ymax = Math.max(ymax, linear.demand_g);
  if (!(xmax > 0)) xmax = 1;
  if (!(ymax > 0)) ymax = 1;
  const xt = ticks(xmax * 1.02), yt = ticks(ymax * 1.05);
  xmax = xt[xt.length - 1]; ymax = yt[yt.length - 1];
  const X = (d) => L + (W - L - R) * (d / xmax);
  const Y = (a) => T + (H - T - B) * (1 - a / ymax);
  for (const x of xt) {
    el("line", { x1: X(x), y1: T, x2: X(x), y2: H - B, class: "grid" }, svg);
    const t = el("text", { x: X(x), y: H - B + 14, class: "tick", "text-anchor": "middle" }, svg);
    t.textContent = x;
  }
  for (const y of yt) {
    el("line", { x1: L, y1: Y(y), x2: W - R, y2: Y(y), class: "grid" }, svg);
    const t = el("text", { x: L - 5, y: Y(y) + 3, class: "tick", "text-anchor": "end" }, svg);
    t.textContent = y;
  }
  el("line", { x1: L, y1: H - B, x2: W - R, y2: H - B, class: "axis" }, svg);
  el("line", { x1: L, y1: T, x2: L, y2: H - B, class: "axis" }, svg);
  const xl = el("text", { x: (L + W - R) / 2, y: H - 6, class: "axis-label", "text-anchor": "middle" }, svg);
  xl.textContent = "spectral displacement d* [m]";
  const yl = el("text", { x: 13, y: (T + H - B) / 2, class: "axis-label", "text-anchor": "middle",
                          transform: `rotate(-90 13 ${(T + H - B) / 2})` }, svg);
  yl.textContent = "spectral acceleration a* [g]";
  const items = [];
  const swatch = (html, colour, shape) => items.push(
    `<span class="key" style="color:${colour}">${shape}</span> ${html}`);
  if (linear) {
    el("line", { x1: L, y1: Y(linear.demand_g), x2: W - R, y2: Y(linear.demand_g), class: "demand-line" }, svg);
    swatch(`linear check's demand a<sub>g</sub> S / q = ${linear.demand_g.toFixed(3)} g`, "#555", "╌");
  }
  for (const k of curves) {
    const colour = COLOURS[k.direction];
    const pts = k.d_star_m.map((d, i) => `${X(d).toFixed(1)},${Y(k.a_star_g[i]).toFixed(1)}`).join(" ");
    el("polyline", { points: pts, class: "curve", stroke: colour, "stroke-width": 2 }, svg);
    swatch(`${same ? "Mech-l = Mech-r" : MECH[k.direction]}: capacity curve, d<sub>0</sub>* = ${k.d0_star_m.toFixed(3)} m`, colour, "━");
    for (const n of c.nonlinear.filter((x) => x.direction === k.direction)) {
      const square = n.limit_state === "SLC";
      const mark = (x, y, filled) => (square
        ? el("rect", { x: x - 4.5, y: y - 4.5, width: 9, height: 9, class: "marker", stroke: colour, fill: filled ? colour : "#fff" }, svg)
        : el("circle", { cx: x, cy: y, r: 5, class: "marker", stroke: colour, fill: filled ? colour : "#fff" }, svg));
      mark(X(n.du_star_m), Y(n.au_star_g), false);
      mark(X(n.demand_SDe_m), Y(0), true);
      swatch(`${n.limit_state}: capacity d<sub>u</sub>* = ${n.du_star_m.toFixed(3)} m`, colour, square ? "□" : "○");
      swatch(`${n.limit_state}: demand S<sub>De</sub>(T<sub>s</sub>) = ${n.demand_SDe_m.toFixed(3)} m (T<sub>s</sub> = ${n.Ts_s.toFixed(2)} s)`, colour, square ? "■" : "●");
    }
  }
  legend.innerHTML = items.join("<br>");  // built from the page's text and numbers only
}

// ---------------------------------------------------------------------------- uploads
async function upload(kind, file) {
  const headers = { "X-File-Name": file.name, "Content-Type": "application/octet-stream" };
  return api(`/api/upload/${kind}`, file, { headers });
}

async function geometryChosen() {
  const file = $("geometry-file").files[0];
  if (!file) return;
  state.geometry = null;
  $("geometry-name").textContent = "";
  try {
    const answer = await upload("geometry", file);
    state.geometry = answer;
    $("geometry-name").textContent = `${answer.name} read`;
    showMessage("");
    updateStructure();
    checkChanged();
  } catch (error) {
    showMessage(error.message);
    $("geometry-name").textContent = `${file.name} refused`;
    clearStructure(`${file.name} refused: see the message above`);
  }
}

// the server's warnings (a record's implausible peak ...) in a box of the page, as text
function showWarnings(id, warnings) {
  const box = $(id);
  box.textContent = (warnings || []).map((w) => `Warning: ${w}`).join("\n");
  box.hidden = !box.textContent;
}

async function recordChosen() {
  const file = $("record-file").files[0];
  if (!file) return;
  state.record = null;
  showWarnings("record-warnings", []);
  try {
    const answer = await upload("record", file);
    state.record = answer;
    $("record-name").textContent =
      `${answer.name}: ${answer.samples} samples, ${answer.duration.toFixed(2)} s, ` +
      `PGA ${answer.pga_g.toFixed(3)} g`;
    showWarnings("record-warnings", answer.warnings);
    showMessage("");
  } catch (error) {
    showMessage(error.message);
    $("record-name").textContent = `${file.name} refused`;
  }
}

// ---------------------------------------------------------------------------- jobs
async function startJob(kind, body, handlers) {
  const job = await api(`/api/jobs/${kind}`, body);
  const poll = async () => {
    let status;
    try {
      status = await api(`/api/jobs/${job.id}`);
    } catch (error) {
      handlers.error(error.message);
      return;
    }
    handlers.progress(status);
    if (status.state === "running") {
      handlers.timer = setTimeout(poll, 250);
    } else if (status.state === "done") {
      handlers.done(status.result);
    } else if (status.state === "failed") {
      handlers.error(status.error);
    } else {
      handlers.cancelled && handlers.cancelled();
    }
  };
  handlers.id = job.id;
  handlers.timer = setTimeout(poll, 150);
  return handlers;
}

async function cancelJob(handlers) {
  if (!handlers || !handlers.id) return;
  clearTimeout(handlers.timer);
  try { await api(`/api/jobs/${handlers.id}`, undefined, { method: "DELETE" }); } catch (e) { /* gone */ }
  handlers.cancelled && handlers.cancelled();
}

// ---------------------------------------------------------------------------- shaking
function setOutcome(name, text, cls) {
  const span = $(`outcome-${name}`);
  span.textContent = text;
  span.className = `outcome ${cls || ""}`;
}

function describeOutcome(name, view) {
  if (view.error) {
    setOutcome(name, "not available", "error");
    $(`detail-${name}`).textContent = view.error;
    return;
  }
  const o = view.outcome;
  let text = o.status;
  let detail;
  if (name === "four-link") {
    if (o.status === "collapse") text += ` (half cycle ${o.half_cycle})`;
    detail = `impacts ${o.impacts}; largest rotation φ = ${o.max_phi === null ? "–" : o.max_phi.toFixed(4)} rad` +
      (o.collapse_time !== null ? `; point of no return at t = ${o.collapse_time.toFixed(3)} s` : "") +
      `; c_v = ${view.restitution.map((c) => c.toFixed(3)).join(" / ")}`;
  } else {
    detail = `up to the decision: largest block rotation ${o.max_rotation.toFixed(4)} rad, ` +
      `crown drop ${o.max_crown_drop.toFixed(4)} m` +
      (o.collapse_time !== null ? `; collapse certain at t = ${o.collapse_time.toFixed(3)} s` : "") +
      (o.decided ? "" : " (undecided at the end of the run)");
  }
  setOutcome(name, text, o.status);
  $(`detail-${name}`).textContent = detail;
}

async function shake() {
  stopAnimation();
  if (state.shake) await cancelJob(state.shake);
  let body;
  try {
    body = { structure: structureSpec(), motion: motionSpec(), models: modelsSpec() };
  } catch (error) { showMessage(error.message); return; }
  for (const name of ["four-link", "rigid-blocks"]) { setOutcome(name, "…", ""); }
  showWarnings("shake-warnings", []);
  $("shake-progress").textContent = "starting…";
  $("shake-cancel").hidden = false;
  const handlers = {
    progress: (s) => { $("shake-progress").textContent = `running: ${s.progress.text}`; },
    done: (result) => {
      $("shake-progress").textContent = "";
      $("shake-cancel").hidden = true;
      state.shake = null;
      showWarnings("shake-warnings", result.warnings);
      showShake(result);
    },
    error: (message) => {
      $("shake-progress").textContent = "";
      $("shake-cancel").hidden = true;
      state.shake = null;
      showMessage(message);
      for (const name of ["four-link", "rigid-blocks"]) setOutcome(name, "", "");
    },
    cancelled: () => {
      $("shake-progress").textContent = "cancelled";
      $("shake-cancel").hidden = true;
      state.shake = null;
      for (const name of ["four-link", "rigid-blocks"]) setOutcome(name, "", "");
    },
  };
  try {
    state.shake = await startJob("simulate", body, handlers);
    showMessage("");
  } catch (error) {
    handlers.error(error.message);
  }
}

function rigidMotion(frame, centre) {
  const [dx, dy, rot] = frame;
  return `translate(${dx} ${dy}) rotate(${rot * 180 / Math.PI} ${centre[0]} ${centre[1]})`;
}

function setupModelScene(svg, view, structure, bounds) {
  const { world } = scene(svg, bounds, 0.05);
  if (view.error) return null;
  const drawn = drawBlocks(world, structure, view.blocks);
  return { view, drawn };
}

function showShake(result) {
  const base = result.structure;
  // room for the blocks to move: the structure's bounds grown by half their size
  const [x0, x1, y0, y1] = base.bounds;
  const w = x1 - x0;
  const bounds = [x0 - 0.25 * w, x1 + 0.25 * w, y0 - 0.35 * (y1 - y0), y1 + 0.1 * (y1 - y0)];
  const scenes = {};
  for (const name of ["four-link", "rigid-blocks"]) {
    describeOutcome(name, result[name]);
    scenes[name] = setupModelScene($(`anim-${name}`), result[name], base, bounds);
  }
  const times = result.times;
  const charts = {
    motion: lineChart($("chart-motion"), [{ ...result.motion, color: "#444" }], times),
    phi: lineChart($("chart-phi"), result["four-link"].series ? [{ ...result["four-link"].series, color: "#1f77b4" }] : [], times),
    drop: lineChart($("chart-drop"), result["rigid-blocks"].series ? [{ ...result["rigid-blocks"].series, color: "#b2182b" }] : [], times),
  };
  state.anim = { result, scenes, charts, times, frame: 0, playing: false, clock: 0 };
  const slider = $("time");
  slider.max = Math.max(0, times.length - 1);
  slider.value = 0;
  slider.disabled = false;
  $("play").disabled = false;
  showFrame(0);
  playAnimation();
}

function showFrame(index) {
  const anim = state.anim;
  if (!anim) return;
  const n = anim.times.length;
  const i = Math.max(0, Math.min(n - 1, index));
  anim.frame = i;
  for (const scene of Object.values(anim.scenes)) {
    if (!scene) continue;
    const frame = scene.view.frames[i];
    const centres = scene.view.centres;
    scene.drawn.polygons.forEach((poly, b) => poly.setAttribute("transform", rigidMotion(frame[b], centres[b])));
    for (const [poly, b] of scene.drawn.columns) {
      poly.setAttribute("transform", rigidMotion(frame[b], centres[b]));
    }
  }
  const t = anim.times[i];
  for (const chart of Object.values(anim.charts)) chart(t);
  $("time").value = i;
  $("time-text").textContent = `t = ${t.toFixed(2)} s`;
}

function playAnimation() {
  const anim = state.anim;
  if (!anim) return;
  if (anim.frame >= anim.times.length - 1) anim.frame = 0;
  anim.playing = true;
  $("play").textContent = "❚❚ Pause";
  let last = performance.now();
  let clock = anim.times[anim.frame];
  const step = (now) => {
    if (!anim.playing || state.anim !== anim) return;
    clock += ((now - last) / 1000) * Number(value("speed"));
    last = now;
    const index = Math.floor(clock * anim.result.fps + 1e-9);
    showFrame(index);
    if (index >= anim.times.length - 1) { stopAnimation(); return; }
    requestAnimationFrame(step);
  };
  requestAnimationFrame(step);
}

function stopAnimation() {
  if (state.anim) state.anim.playing = false;
  $("play").textContent = "▶ Play";
}

// A small line chart of series {t, y, color} over the frames' times; returns cursor(t).
function lineChart(svg, series, times) {
  svg.replaceChildren();
  const W = 300, H = 110, L = 34, B = 16, T = 6, R = 6;
  svg.setAttribute("viewBox", `0 0 ${W} ${H}`);
  svg.setAttribute("preserveAspectRatio", "none");
  const tmax = Math.max(times.length ? times[times.length - 1] : 1,
                        ...series.map((s) => (s.t.length ? s.t[s.t.length - 1] : 0)), 1e-6);
  let ymin = 0, ymax = 0;
  for (const s of series) for (const y of s.y) { if (y < ymin) ymin = y; if (y > ymax) ymax = y; }
  if (ymax - ymin < 1e-12) { ymax += 1; ymin -= 1; }
  const X = (t) => L + (W - L - R) * (t / tmax);
  const Y = (y) => T + (H - T - B) * (1 - (y - ymin) / (ymax - ymin));
  el("line", { x1: L, y1: Y(0), x2: W - R, y2: Y(0), class: "axis" }, svg);
  el("line", { x1: L, y1: T, x2: L, y2: H - B, class: "axis" }, svg);
  for (const [y, label] of [[ymax, ymax], [ymin, ymin]]) {
    const t = el("text", { x: L - 3, y: Y(y) + 3, class: "tick", "text-anchor": "end" }, svg);
    t.textContent = Number(label).toPrecision(2);
  }
  const end = el("text", { x: W - R, y: H - 3, class: "tick", "text-anchor": "end" }, svg);
  end.textContent = `${tmax.toFixed(1)} s`;
  for (const s of series) {
    const pts = s.t.map((t, i) => `${X(t).toFixed(1)},${Y(s.y[i]).toFixed(1)}`).join(" ");
    el("polyline", { points: pts, class: "curve", stroke: s.color }, svg);
  }
  const cursor = el("line", { x1: L, y1: T, x2: L, y2: H - B, class: "cursor" }, svg);
  return (t) => { const x = X(t); cursor.setAttribute("x1", x); cursor.setAttribute("x2", x); };
}

// ---------------------------------------------------------------------------- failure domain
async function startDomain() {
  const body = {
    structure: structureSpec(), models: modelsSpec(),
    domain: { durations: value("domain-durations"), amplitudes: value("domain-amplitudes"),
              direction: value("domain-direction") },
  };
  $("domain-start").disabled = true;
  $("domain-cancel").disabled = false;
  $("domain-status").textContent = "starting…";
  $("domain-progress").value = 0;
  const finish = (text) => {
    $("domain-start").disabled = false;
    $("domain-cancel").disabled = true;
    $("domain-status").textContent = text;
    state.domain = null;
  };
  const handlers = {
    progress: (s) => {
      const p = s.progress;
      $("domain-progress").max = p.total;
      $("domain-progress").value = p.done;
      $("domain-status").textContent = `${p.done} / ${p.total}: ${p.text} (${s.elapsed.toFixed(0)} s)`;
    },
    done: (result) => {
      const img = $("domain-figure");
      if (result.figure) img.src = result.figure;
      img.hidden = !result.figure;  // none where neither model could be built
      const n = (result["four-link"].analyses || 0) + (result["rigid-blocks"].analyses || 0);
      const u = (result["four-link"].undecided || 0) + (result["rigid-blocks"].undecided || 0);
      finish(`done: ${n} analyses, ${u} undecided` +
             (result["four-link"].error ? `; four-link model: ${result["four-link"].error}` : "") +
             (result["rigid-blocks"].error ? `; rigid blocks: ${result["rigid-blocks"].error}` : "") +
             (result.model_check && result.model_check.messages.length
               ? `; four-link values: ${result.model_check.messages.join("; ")}` : ""));
    },
    error: (message) => { finish("failed"); showMessage(message); },
    cancelled: () => finish("cancelled"),
  };
  try {
    state.domain = await startJob("domain", body, handlers);
    showMessage("");
  } catch (error) {
    handlers.error(error.message);
  }
}

// ---------------------------------------------------------------------------- assessment
async function startAssess() {
  $("assess").disabled = true;
  $("assess-cancel").disabled = false;
  $("assess-status").textContent = "starting…";
  const finish = (html) => {
    $("assess").disabled = false;
    $("assess-cancel").disabled = true;
    $("assess-status").innerHTML = "";
    if (html) $("assess-status").append(...html);
    state.assess = null;
  };
  const handlers = {
    progress: (s) => { $("assess-status").textContent = `${s.progress.text}: ${s.elapsed.toFixed(0)} s`; },
    done: (result) => {
      const link = document.createElement("a");
      link.href = `/api/download/${result.file}`;
      link.id = "assess-download";
      link.textContent = `download the report (${result.file})`;
      const verdict = document.createElement("div");
      verdict.textContent = result.verdict || "";
      finish([link, verdict]);
    },
    error: (message) => { finish([document.createTextNode("failed")]); showMessage(message); },
    cancelled: () => finish([document.createTextNode("cancelled")]),
  };
  try {
    state.assess = await startJob("assess", { structure: structureSpec() }, handlers);
  } catch (error) {
    handlers.error(error.message);
  }
}

// ---------------------------------------------------------------------------- set-up
function fillSelect(select, values, selected) {
  select.replaceChildren(...values.map((v) => {
    const option = document.createElement("option");
    option.value = v; option.textContent = v; if (v === selected) option.selected = true;
    return option;
  }));
}

function showSpanRingFields() {
  const spans = value("spans"), rings = value("rings");
  $("middle-pier").hidden = spans === "" || spans === "1";
  $("ring-fields").hidden = rings === "" || rings === "1";
}

function showShapeFields() {
  const circular = value("shape") === "circular";
  $("given-by-label").hidden = !circular;
  const by = circular ? value("circle-by") : "size";
  document.querySelectorAll("[data-for]").forEach((label) => { label.hidden = label.dataset.for !== by; });
  if (by === "size" && value("span") === "") {
    const R = number("radius"), a = (number("embrace") * Math.PI) / 180;
    $("span").value = (2 * R * Math.sin(a / 2)).toFixed(3);
    $("rise").value = (R * (1 - Math.cos(a / 2))).toFixed(3);
  }
}

function showSource() {
  const file = document.querySelector("input[name=source]:checked").value === "file";
  $("by-file").hidden = !file;
  $("by-shape").hidden = file;
}

function showPulseParams() {
  const params = state.options.motions[value("pulse")] || {};
  const box = $("pulse-params");
  box.replaceChildren();
  for (const [name, fallback] of Object.entries(params)) {
    const label = document.createElement("label");
    label.textContent = `${name} `;
    const input = document.createElement("input");
    input.type = "number"; input.step = "any"; input.dataset.param = name;
    input.placeholder = String(fallback); input.id = `param-${name}`;
    label.appendChild(input);
    box.appendChild(label);
  }
}

function showMotionSource() {
  const source = value("motion-source");
  $("motion-pulse").hidden = source !== "pulse";
  $("motion-record").hidden = source !== "record";
  $("motion-suite").hidden = source !== "suite";
  $("motion-scale").hidden = source === "pulse";
}

async function loadSuites() {
  try {
    const suites = await api("/api/suites");
    if (!suites.length) return;
    state.suites = suites;
    fillSelect($("suite"), suites.map((s) => s.name));
    const showRecords = () => {
      const suite = suites.find((s) => s.name === value("suite"));
      $("suite-record").replaceChildren(...suite.records.map((r, i) => {
        const option = document.createElement("option");
        option.value = i; option.textContent = r; return option;
      }));
    };
    $("suite").addEventListener("change", showRecords);
    showRecords();
    $("suite-option").disabled = false;
  } catch (error) { /* no built-in records: the option stays disabled */ }
}

async function init() {
  const options = await api("/api/options");
  state.options = options;
  fillSelect($("shape"), options.shapes, "circular");
  fillSelect($("faces"), options.faces, "curved");
  fillSelect($("fill-inertia"), options.fill_inertia, options.default_fill_inertia);
  fillSelect($("pulse"), Object.keys(options.motions), "oppenheim");
  const c = options.circular;
  $("radius").value = c.radius; $("embrace").value = c.embrace;
  $("thickness").value = c.thickness; $("thickness-slider").value = c.thickness;
  $("voussoirs").value = c.voussoirs;
  $("voussoirs").max = options.limits.blocks;
  $("amplitude").value = options.pulse.amplitude; $("duration").value = options.pulse.duration;
  $("restitution").placeholder = options.restitution; $("friction").value = options.friction;
  $("domain-durations").value = options.domain.durations;
  $("domain-amplitudes").value = options.domain.amplitudes;
  showShapeFields(); showPulseParams(); showMotionSource(); showSpanRingFields();
  for (const id of ["spans", "rings"]) $(id).addEventListener("input", showSpanRingFields);

  document.querySelectorAll("#by-shape input, #by-shape select, details input, details select")
    .forEach((input) => input.addEventListener("input", structureChanged));
  $("thickness").addEventListener("input", () => { $("thickness-slider").value = value("thickness"); });
  $("thickness-slider").addEventListener("input", () => {
    $("thickness").value = $("thickness-slider").value; structureChanged();
  });
  $("shape").addEventListener("change", () => { showShapeFields(); structureChanged(); });
  $("circle-by").addEventListener("change", () => { showShapeFields(); structureChanged(); });
  document.querySelectorAll("input[name=source]").forEach((r) => r.addEventListener("change", () => {
    showSource(); structureChanged();
  }));
  document.querySelectorAll("#site-section input, #site-section select")
    .forEach((input) => input.addEventListener("input", checkChanged));
  $("slc-on").addEventListener("change", () => {
    $("slc-fields").hidden = !$("slc-on").checked; checkChanged();
  });
  $("geometry-file").addEventListener("change", geometryChosen);
  $("record-file").addEventListener("change", recordChosen);
  $("pulse").addEventListener("change", showPulseParams);
  $("motion-source").addEventListener("change", showMotionSource);
  $("shake").addEventListener("click", shake);
  $("shake-cancel").addEventListener("click", () => cancelJob(state.shake));
  $("play").addEventListener("click", () => (state.anim && state.anim.playing ? stopAnimation() : playAnimation()));
  $("time").addEventListener("input", () => { stopAnimation(); showFrame(Number($("time").value)); });
  $("domain-start").addEventListener("click", startDomain);
  $("domain-cancel").addEventListener("click", () => cancelJob(state.domain));
  $("assess").addEventListener("click", startAssess);
  $("assess-cancel").addEventListener("click", () => cancelJob(state.assess));
  $("figure-link").addEventListener("click", async (event) => {
    event.preventDefault();
    try {
      const blob = await api("/api/figure", { structure: structureSpec() });
      window.open(URL.createObjectURL(blob), "_blank");
    } catch (error) { showMessage(error.message); }
  });
  loadSuites();
  updateCheck();
  await updateStructure();
}

init().catch((error) => { showMessage(`the page could not start: ${error.message}`); });
