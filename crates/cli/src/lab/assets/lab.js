// rtl lab: the page's script. It asks the server (same origin) for numbers and draws them as SVG and
// canvas; no library, nothing from the network.
"use strict";

const $ = (id) => document.getElementById(id);
const SVG = "http://www.w3.org/2000/svg";
// Okabe & Ito's colour-blind-safe palette, always in this order; past its end, dashes tell lines apart.
const PALETTE = ["#D55E00", "#0072B2", "#009E73", "#E69F00", "#CC79A7", "#56B4E9", "#000000"];
const DASHES = ["", "7 4", "2 3", "9 3 2 3", "4 2 1 2 1 2", "12 4"];
// The colours of the heat maps (the sphere's grids, the keys): the variance map's own, `rtl study
// render`'s colour map, dark blue (low) to yellow-white (high), as the server serves it (/api/heat:
// colour k at t = k / (steps - 1)). No copy here.
const heat = { colours: null, loading: null };

// ---------------------------------------------------------------- the server, and when it is gone
class Offline extends Error {}
const GONE = "stopped: the lab server is not answering";

const net = { offline: false, wait: 500, timer: null, tick: null, next: 0, onBack: [] };

// A JSON request. A refusal (4xx, 5xx) throws an Error with the server's message and the parameter it
// names; no answer at all throws Offline (and the banner says so until the server is back).
async function api(path, opts) {
  let r;
  try {
    r = await fetch(path, opts);
  } catch (e) {
    wentOffline();
    throw new Offline("the lab server is not answering");
  }
  cameBack();
  let body = null;
  try { body = await r.json(); } catch (e) { body = null; }
  if (!r.ok) {
    const err = new Error((body && body.error) || ("HTTP " + r.status));
    err.parameter = body && body.parameter;
    err.status = r.status;
    throw err;
  }
  return body;
}

function wentOffline() {
  if (net.offline) return;
  net.offline = true;
  net.wait = 500;
  document.body.classList.add("offline");
  $("offline").hidden = false;
  scheduleProbe();
}

function cameBack() {
  if (!net.offline) return;
  net.offline = false;
  clearTimeout(net.timer);
  clearInterval(net.tick);
  document.body.classList.remove("offline");
  $("offline").hidden = true;
  // A server started again counts its generations from 1.
  cornell.minGeneration = 0;
  if ($("c-error").textContent === GONE) $("c-error").textContent = "";
  for (const f of net.onBack) f();
}

// Ask again after a wait that doubles up to 8 s, counting down on the banner.
function scheduleProbe() {
  clearTimeout(net.timer);
  clearInterval(net.tick);
  net.next = Date.now() + net.wait;
  const show = () => {
    const s = Math.max(0, Math.ceil((net.next - Date.now()) / 1000));
    $("offline-retry").textContent = `Trying again in ${s} s.`;
  };
  show();
  net.tick = setInterval(show, 500);
  net.timer = setTimeout(probe, net.wait);
  net.wait = Math.min(8000, net.wait * 2);
}

async function probe() {
  clearTimeout(net.timer);
  $("offline-retry").textContent = "Trying ...";
  try {
    const r = await fetch("/api/render/state?peek=1");
    if (r.ok || r.status < 500) { cameBack(); return; }
  } catch (e) { /* still gone */ }
  if (net.offline) scheduleProbe();
}

// What a handler's error becomes: a message in `box` (nothing more when the server is gone: the
// banner says it).
function report(box, e) {
  if (e instanceof Offline) {
    if (box) box.textContent = GONE;
    return;
  }
  if (!box) { console.warn(e); return; }
  box.textContent = "";
  const span = document.createElement("span");
  span.className = "error";
  span.textContent = e.message;
  box.appendChild(span);
}

// An event handler that never throws.
const guarded = (f, box) => async (...args) => {
  try { await f(...args); } catch (e) { report(typeof box === "function" ? box() : box, e); }
};

// ---------------------------------------------------------------- fields and their messages
// The message next to a field (made on first use; the field points at it for screen readers).
function fieldMsg(input) {
  let m = $(input.id + "-msg");
  if (!m) {
    m = document.createElement("span");
    m.id = input.id + "-msg";
    m.className = "field-msg";
    m.setAttribute("aria-live", "polite");
    const label = input.closest("label") || input;
    label.after(m);
    input.setAttribute("aria-describedby", m.id);
  }
  return m;
}

function markInvalid(input, message) {
  input.setAttribute("aria-invalid", "true");
  const m = fieldMsg(input);
  m.classList.remove("pending");
  m.textContent = message;
}

function markValid(input) {
  if (input.getAttribute("aria-invalid")) input.removeAttribute("aria-invalid");
  const m = $(input.id + "-msg");
  if (m && !input.dataset.queued) { m.classList.remove("pending"); m.textContent = ""; }
}

// Why a number field's value is refused, or null: its min, max and (unless data-any-step) whole numbers.
function numberProblem(input) {
  const v = input.validity;
  const range = input.max !== "" ? `from ${input.min} to ${input.max}` : `at least ${input.min}`;
  if (v.badInput || v.valueMissing || input.value.trim() === "") return `a number ${range}, please`;
  if (v.rangeUnderflow || v.rangeOverflow) return `${input.value} is out of range: ${range}`;
  if (v.stepMismatch && !input.dataset.anyStep) return `a whole number ${range}, please`;
  return null;
}

// Check the visible number fields of `inputs`; mark the bad ones. True when all are good.
function checkFields(inputs) {
  let ok = true;
  for (const i of inputs) {
    if (i.disabled || i.closest("label").style.display === "none") { markValid(i); continue; }
    const p = numberProblem(i);
    if (p) { markInvalid(i, p); ok = false; } else markValid(i);
  }
  return ok;
}

// ---------------------------------------------------------------- drawing
function el(name, attrs, parent) {
  const e = document.createElementNS(SVG, name);
  for (const [k, v] of Object.entries(attrs || {})) e.setAttribute(k, v);
  if (parent) parent.appendChild(e);
  return e;
}

function fmt(x, digits = 3) {
  if (x === null || x === undefined || !isFinite(x)) return "n/a";
  if (x === 0) return "0";
  const a = Math.abs(x);
  if (a >= 1e4 && a < 1e12) return Math.round(x).toLocaleString("en-US"); // 190,200, not 1.902e+5
  return a < 1e-3 ? x.toExponential(digits - 1) : x.toPrecision(digits);
}

// A p-value; one that underflows to 0 is below the smallest double the test computes.
function pValue(p) {
  const text = p === 0 ? "< 1e-300" : fmt(p, 2);
  return text + (p < 1e-3 ? " (not from this density)" : "");
}

// Least-squares slope of log10(y) against log10(x): the same fit as `plot::loglog_slope` of
// `rtl study`.
function loglogSlope(points) {
  const p = points.filter(([x, y]) => x > 0 && y > 0 && isFinite(x) && isFinite(y))
    .map(([x, y]) => [Math.log10(x), Math.log10(y)]);
  if (p.length < 2) return null;
  const mx = p.reduce((s, q) => s + q[0], 0) / p.length;
  const my = p.reduce((s, q) => s + q[1], 0) / p.length;
  let sxx = 0, sxy = 0;
  for (const [x, y] of p) { sxx += (x - mx) * (x - mx); sxy += (x - mx) * (y - my); }
  return sxx > 0 ? sxy / sxx : null;
}

// A chart: axes (log or linear), grid and labels; returns a mapping from data to the SVG.
function chart(svg, opts) {
  while (svg.firstChild) svg.removeChild(svg.firstChild);
  // As wide as drawn (text at its size on a phone as on a desktop), as high as the page says.
  const vb = svg.viewBox.baseVal;
  if (!svg.dataset.width) svg.dataset.width = vb.width;
  const W = Math.round(Math.max(300, svg.clientWidth || Number(svg.dataset.width))), H = vb.height;
  if (W !== vb.width) svg.setAttribute("viewBox", `0 0 ${W} ${H}`);
  // Room on the right for the last tick's label, centred on the axis's end.
  const m = { l: 56, r: 22, t: 10, b: 36 };
  const tr = (log) => log ? Math.log10 : (v) => v;
  const fx = tr(opts.logx), fy = tr(opts.logy);
  let [x0, x1] = opts.x.map(fx), [y0, y1] = opts.y.map(fy);
  if (!(x1 > x0)) { x0 -= 1; x1 += 1; }
  if (!(y1 > y0)) { y0 -= 1; y1 += 1; }
  if (opts.logx) { x0 = Math.floor(x0); x1 = Math.ceil(x1); }
  if (opts.logy) { y0 = Math.floor(y0); y1 = Math.ceil(y1); }
  const X = (v) => m.l + (fx(v) - x0) / (x1 - x0) * (W - m.l - m.r);
  const Y = (v) => H - m.b - (fy(v) - y0) / (y1 - y0) * (H - m.t - m.b);
  // Ticks [value, label]: powers of ten on a log axis; 1, 2 or 5 times one on a linear axis, with
  // as many decimals as the step needs (thousands as k: 50k).
  const ticks = (a, b, log) => {
    if (log) { const t = []; const step = Math.max(1, Math.ceil((b - a) / 8)); for (let k = a; k <= b; k += step) t.push([k, "1e" + k]); return t; }
    const span = b - a, raw = span / 5, mag = Math.pow(10, Math.floor(Math.log10(raw)));
    const step = [1, 2, 5, 10].map((s) => s * mag).find((s) => span / s <= 6);
    const digits = Math.max(0, Math.ceil(-Math.log10(step) - 1e-9));
    const label = (v) => Math.abs(v) >= 1e4 && step >= 1000 ? `${+(v / 1000).toFixed(Math.max(0, digits - 3))}k` : v.toFixed(digits);
    const t = []; for (let v = Math.ceil(a / step) * step; v <= b + 1e-12 * span; v += step) t.push([v, label(Math.abs(v) < 1e-12 * span ? 0 : v)]); return t;
  };
  for (const [t, text] of ticks(x0, x1, opts.logx)) {
    const x = m.l + (t - x0) / (x1 - x0) * (W - m.l - m.r);
    el("line", { x1: x, x2: x, y1: m.t, y2: H - m.b, class: "grid" }, svg);
    el("text", { x, y: H - m.b + 14, "text-anchor": "middle" }, svg).textContent = text;
  }
  for (const [t, text] of ticks(y0, y1, opts.logy)) {
    const y = H - m.b - (t - y0) / (y1 - y0) * (H - m.t - m.b);
    el("line", { x1: m.l, x2: W - m.r, y1: y, y2: y, class: "grid" }, svg);
    el("text", { x: m.l - 4, y: y + 4, "text-anchor": "end" }, svg).textContent = text;
  }
  el("rect", { x: m.l, y: m.t, width: W - m.l - m.r, height: H - m.t - m.b, class: "axis" }, svg);
  el("text", { x: (m.l + W - m.r) / 2, y: H - 4, "text-anchor": "middle" }, svg).textContent = opts.xlabel || "";
  const yl = el("text", { x: 12, y: (m.t + H - m.b) / 2, "text-anchor": "middle",
    transform: `rotate(-90 12 ${(m.t + H - m.b) / 2})` }, svg);
  yl.textContent = opts.ylabel || "";
  return { X, Y, W, H, m };
}

function polyline(svg, c, points, attrs) {
  const d = points.map(([x, y], i) => (i ? "L" : "M") + c.X(x).toFixed(1) + "," + c.Y(y).toFixed(1)).join("");
  return el("path", Object.assign({ d }, attrs), svg);
}

// A legend under a plot, outside its axes (it never covers a curve): entries {text, color, dash,
// kind: "line" | "bar" | "dots", wide}.
function legend(box, entries) {
  box.textContent = "";
  for (const e of entries) {
    const item = document.createElement("span");
    item.className = "item" + (e.wide ? " wide" : "");
    const key = document.createElementNS(SVG, "svg");
    key.setAttribute("viewBox", "0 0 28 10");
    key.setAttribute("aria-hidden", "true");
    if (e.kind === "bar") el("rect", { x: 4, y: 1, width: 20, height: 8, fill: e.color }, key);
    else if (e.kind === "none") key.setAttribute("width", "0");
    else el("line", { x1: 1, x2: 27, y1: 5, y2: 5, stroke: e.color, "stroke-width": e.kind === "dots" ? 1.5 : 2.4,
      "stroke-dasharray": e.dash || "", "stroke-linecap": e.kind === "dots" ? "round" : "butt" }, key);
    item.appendChild(key);
    item.appendChild(document.createTextNode(e.text));
    box.appendChild(item);
  }
}

function extent(values, log) {
  const v = values.filter((x) => isFinite(x) && (!log || x > 0));
  if (!v.length) return [1, 10];
  return [Math.min(...v), Math.max(...v)];
}

// A log-log chart of curves [{label, color, dash, points: [[x, y]]}], each with its fitted slope in
// the legend; `floors` are horizontal lines [{y, text, legend}] kept inside the y range.
function loglogCurves(svg, legendBox, curves, xlabel, ylabel, withSlope, floors = []) {
  const xs = curves.flatMap((s) => s.points.map((p) => p[0]));
  const ys = curves.flatMap((s) => s.points.map((p) => p[1])).concat(floors.map((f) => f.y));
  const c = chart(svg, { logx: true, logy: true, x: extent(xs, true), y: extent(ys, true), xlabel, ylabel });
  for (const f of floors) {
    el("line", { x1: c.m.l, x2: c.W - c.m.r, y1: c.Y(f.y), y2: c.Y(f.y), class: "floor" }, svg);
    el("text", { x: c.m.l + 4, y: c.Y(f.y) - 3, class: "floor-label" }, svg).textContent = f.text;
  }
  for (const s of curves) {
    const p = s.points.filter(([x, y]) => x > 0 && y > 0);
    if (!p.length) continue;
    const path = polyline(svg, c, p, { class: "curve", stroke: s.color, "stroke-dasharray": s.dash || "" });
    path.dataset.label = s.label;
    for (const [x, y] of p.length < 40 ? p : []) el("circle", { cx: c.X(x), cy: c.Y(y), r: 2, fill: s.color }, svg);
  }
  legend(legendBox, curves.map((s) => {
    const k = withSlope ? loglogSlope(s.fit || s.points) : null;
    return { text: s.label + (k === null ? "" : `  (slope ${k.toFixed(2)})`), color: s.color, dash: s.dash };
  }).concat(floors.map((f) => ({ text: f.legend, color: "#555", dash: "1 3", kind: "dots", wide: true }))));
  return c;
}

// The server's heat colours, once (again after a failure).
function heatInit() {
  if (heat.colours) return Promise.resolve();
  heat.loading = heat.loading || api("/api/heat").then((r) => { heat.colours = r.colours; })
    .finally(() => { heat.loading = null; });
  return heat.loading;
}

// The heat colour of t in [0, 1]: the server's colour of the nearest step.
function heatRgb(t) {
  const c = heat.colours;
  if (!c) return "#888";
  const k = Math.round(Math.max(0, Math.min(1, isFinite(t) ? t : 0)) * (c.length - 1));
  return `rgb(${c[k].join(",")})`;
}

// A colour key: the heat colours from left to right, ticks [[t in 0..1, label]] and a title.
function heatKey(svg, ticks, title) {
  while (svg.firstChild) svg.removeChild(svg.firstChild);
  const W = svg.viewBox.baseVal.width, x0 = 8, x1 = W - 8, n = 64;
  for (let i = 0; i < n; i++) {
    el("rect", { x: x0 + (x1 - x0) * i / n, y: 16, width: (x1 - x0) / n + 0.5, height: 10, fill: heatRgb((i + 0.5) / n) }, svg);
  }
  el("rect", { x: x0, y: 16, width: x1 - x0, height: 10, class: "axis" }, svg);
  el("text", { x: x0, y: 11 }, svg).textContent = title;
  for (const [t, label] of ticks) {
    const x = x0 + (x1 - x0) * t;
    el("line", { x1: x, x2: x, y1: 26, y2: 30, class: "axis" }, svg);
    el("text", { x, y: 41, "text-anchor": t === 0 ? "start" : t === 1 ? "end" : "middle" }, svg).textContent = label;
  }
}

// ---------------------------------------------------------------- the benches: switching
const BENCHES = ["mc", "sampling", "cornell"];
let activeBench = "mc";

function show(bench) {
  if (!BENCHES.includes(bench)) bench = "mc";
  activeBench = bench;
  for (const b of document.querySelectorAll("nav [role=tab]")) {
    const on = b.dataset.bench === bench;
    b.classList.toggle("on", on);
    b.setAttribute("aria-selected", on ? "true" : "false");
    b.tabIndex = on ? 0 : -1;
  }
  for (const s of document.querySelectorAll(".bench")) s.classList.toggle("on", s.id === "bench-" + bench);
  // The bench in the address: a reload or a link opens it again.
  if (location.hash !== "#" + bench) history.replaceState(null, "", "#" + bench);
  if (bench === "cornell") pollRender();
}

function tabsInit() {
  const tabs = [...document.querySelectorAll("nav [role=tab]")];
  for (const b of tabs) {
    b.onclick = () => show(b.dataset.bench);
    // Arrow keys move along the tabs, as in every tab list.
    b.onkeydown = (e) => {
      const i = tabs.indexOf(b);
      const j = e.key === "ArrowRight" ? (i + 1) % tabs.length : e.key === "ArrowLeft" ? (i + tabs.length - 1) % tabs.length
        : e.key === "Home" ? 0 : e.key === "End" ? tabs.length - 1 : -1;
      if (j < 0) return;
      e.preventDefault();
      tabs[j].focus();
      show(tabs[j].dataset.bench);
    };
  }
  window.addEventListener("hashchange", () => show(location.hash.slice(1)));
}

// ---------------------------------------------------------------- Monte Carlo
const mc = { list: null, runs: [], current: null, busy: false, cancel: false };

function mcIntegral() { return mc.list.integrals.find((i) => i.slug === $("mc-integral").value); }

// A fixed colour per estimator: its place in its integral's list.
function mcColor(slug, estimator) {
  const i = mc.list.integrals.find((x) => x.slug === slug).estimators.indexOf(estimator);
  return PALETTE[Math.max(0, i) % PALETTE.length];
}

function mcFillEstimators() {
  const sel = $("mc-estimator");
  sel.innerHTML = "";
  for (const e of mcIntegral().estimators) sel.add(new Option(e, e));
  mcDraw();
}

function mcDraw() {
  const integral = mcIntegral();
  const runs = mc.runs.filter((r) => r.slug === integral.slug);
  const cur = mc.current && mc.current.slug === integral.slug ? mc.current : runs[runs.length - 1];
  // the estimate and its band
  const svg = $("mc-trace");
  const pts = cur ? cur.points : [];
  const ys = pts.flatMap((p) => [p.lo, p.hi, p.estimate]).concat([integral.exact]).filter((v) => v !== null && isFinite(v));
  let [lo, hi] = extent(ys, false);
  const pad = 0.05 * (hi - lo || Math.abs(integral.exact) || 1);
  const ns = pts.length ? pts.map((p) => p.n) : [16, 65536];
  const c = chart(svg, { logx: true, logy: false, x: extent(ns, true), y: [lo - pad, hi + pad],
    xlabel: "samples N", ylabel: "estimate" });
  const banded = pts.filter((p) => p.lo !== null && p.hi !== null);
  if (banded.length) {
    const top = banded.map((p) => [p.n, p.hi]), bottom = banded.map((p) => [p.n, p.lo]).reverse();
    const d = top.concat(bottom).map(([x, y], i) => (i ? "L" : "M") + c.X(x).toFixed(1) + "," + c.Y(y).toFixed(1)).join("") + "Z";
    el("path", { d, class: "band", fill: cur.color, "fill-opacity": 0.2 }, svg).dataset.points = String(banded.length);
  }
  el("line", { x1: c.m.l, x2: c.W - c.m.r, y1: c.Y(integral.exact), y2: c.Y(integral.exact), class: "exact" }, svg);
  if (pts.length) polyline(svg, c, pts.map((p) => [p.n, p.estimate]), { class: "curve", stroke: cur.color });
  legend($("mc-trace-legend"), [{ text: `exact ${fmt(integral.exact, 6)}`, color: "#222", dash: "4 3" }]
    .concat(cur ? [{ text: cur.estimator + ", first run", color: cur.color },
      { text: "its 95% band", color: cur.color + "55", kind: "bar" }] : []));
  // RMS error against N and against time
  const curves = (key) => runs.map((r) => ({ label: r.estimator, color: r.color,
    points: r.points.map((p) => [key(p), p.rms_error]) }));
  loglogCurves($("mc-vs-n"), $("mc-vs-n-legend"), curves((p) => p.n), "samples N", "RMS error", true);
  loglogCurves($("mc-vs-t"), $("mc-vs-t-legend"), curves((p) => p.seconds_per_estimate), "seconds per estimate", "RMS error", true);
  const body = $("mc-table").tBodies[0];
  body.innerHTML = "";
  $("mc-table-caption").textContent = cur ? `${cur.estimator}: the first of the 30 runs at every N` : "the first of the 30 runs at every N";
  for (const p of pts) {
    const row = body.insertRow();
    for (const v of [p.n, fmt(p.estimate, 7), p.lo === null ? "n/a" : `${fmt(p.lo, 6)} .. ${fmt(p.hi, 6)}`,
      fmt(p.rms_error), fmt(p.mean_std_error), fmt(p.ns_per_sample)]) row.insertCell().textContent = v;
  }
}

const SHARED = "timed while the Cornell box was rendering too (it goes on for 3 s after its bench is left, " +
  "and a reference to its end): the times are slower than alone";

async function mcRun() {
  if (mc.busy) return;
  if (!checkFields([$("mc-max")])) { $("mc-status").textContent = ""; return; }
  const integral = mcIntegral(), estimator = $("mc-estimator").value;
  const max = parseInt($("mc-max").value, 10);
  mc.busy = true;
  mc.cancel = false;
  $("mc-run").disabled = true;
  mc.runs = mc.runs.filter((r) => !(r.slug === integral.slug && r.estimator === estimator));
  const run = { slug: integral.slug, estimator, color: mcColor(integral.slug, estimator), points: [] };
  mc.runs.push(run);
  mc.current = run;
  let shared = false;
  try {
    for (let k = 4; k <= max; k++) {
      $("mc-status").textContent = `N = 2^${k} ...`;
      const q = new URLSearchParams({ integral: integral.slug, estimator, log2_n: k });
      const p = await api("/api/mc/run?" + q);
      if (mc.cancel) break;
      shared = shared || p.shared_cores;
      run.points.push(p);
      mcDraw();
    }
    $("mc-status").textContent = mc.cancel ? "stopped: the plots were cleared"
      : `done: ${integral.integral}, ${estimator}, N up to 2^${max}` + (shared ? `; ${SHARED}` : "");
  } catch (e) {
    report($("mc-status"), e);
  } finally {
    mc.busy = false;
    mc.cancel = false;
    $("mc-run").disabled = false;
  }
}

// Clear the plots; a run under way stops (its next answer is thrown away).
function mcClear() {
  mc.runs = [];
  mc.current = null;
  if (mc.busy) { mc.cancel = true; $("mc-status").textContent = "stopping ..."; }
  mcDraw();
}

async function mcInit() {
  if (mc.list) return;
  const list = await api("/api/mc/list");
  mc.list = list;
  const sel = $("mc-integral");
  for (const i of mc.list.integrals) sel.add(new Option(`${i.integral} = ${fmt(i.exact, 6)}`, i.slug));
  sel.onchange = mcFillEstimators;
  const [lo, hi] = list.log2_n;
  $("mc-max").min = lo; $("mc-max").max = hi;
  $("mc-max").oninput = () => checkFields([$("mc-max")]);
  mcFillEstimators();
  $("mc-run").onclick = mcRun;
  $("mc-clear").onclick = mcClear;
}

// ---------------------------------------------------------------- sampling
let samplingList = null;

function sFillMethods() {
  const d = samplingList.densities.find((x) => x.name === $("s-density").value);
  const sel = $("s-method"), keep = sel.value;
  sel.innerHTML = "";
  for (const m of samplingList.methods) if (m !== "analytic" || d.analytic) sel.add(new Option(m.replace("_", " "), m));
  if ([...sel.options].some((o) => o.value === keep)) sel.value = keep;
  sShowFields();
}

// The fields of the method, and the server's limits on them (numerical inversion takes fewer samples).
function sShowFields() {
  const m = $("s-method").value, caps = samplingList.caps;
  $("s-n").parentElement.style.display = ["binary_search", "guide_table", "alias"].includes(m) ? "" : "none";
  $("s-tol").parentElement.style.display = m === "numeric" ? "" : "none";
  const samples = $("s-samples");
  samples.max = m === "numeric" ? caps.numeric_samples : caps.samples[1];
  samples.title = m === "numeric" ? `numerical inversion: at most ${caps.numeric_samples} samples (it is slow)` : "";
  sInputsChanged();
}

// The results shown are no longer those of the settings: say so.
function markStale(figure, box, why) {
  if (!box.firstChild) return;
  figure.classList.add("stale");
  let note = box.querySelector(".stale-note");
  if (!note) { note = document.createElement("div"); note.className = "stale-note"; box.prepend(note); }
  note.textContent = why;
}

function unmarkStale(figure, box) {
  figure.classList.remove("stale");
  const note = box.querySelector(".stale-note");
  if (note) note.remove();
}

function sInputsChanged() {
  checkFields([$("s-n"), $("s-samples"), $("s-bins")]);
  markStale($("s-figure"), $("s-numbers"), "These are the results of the last run, not of the settings above: press Sample.");
}

function numbers(box, rows) {
  box.textContent = "";
  for (const [k, v] of rows) {
    const d = document.createElement("div"), b = document.createElement("b");
    b.textContent = k;
    d.append(b, " " + v);
    box.appendChild(d);
  }
}

async function sRun() {
  if (!checkFields([$("s-n"), $("s-samples"), $("s-bins")])) {
    $("s-status").textContent = "";
    markStale($("s-figure"), $("s-numbers"), "Not run: a field above is refused. These are the results of the last run.");
    return;
  }
  const q = new URLSearchParams({ density: $("s-density").value, method: $("s-method").value,
    samples: $("s-samples").value, bins: $("s-bins").value });
  if ($("s-n").parentElement.style.display !== "none") q.set("n", $("s-n").value);
  if ($("s-tol").parentElement.style.display !== "none") q.set("tolerance", $("s-tol").value);
  $("s-status").textContent = "sampling ...";
  $("s-run").disabled = true;
  try {
    const r = await api("/api/sampling/line?" + q);
    const [a, b] = r.domain, nb = r.bins.length, w = (b - a) / nb;
    // Counts per bin, the bars' and the line's: the line is N times the density's integral over each
    // bin (from the exact CDF), the count the bar should have.
    const ymax = Math.max(...r.bins, ...r.expected, 1);
    const svg = $("s-hist");
    const c = chart(svg, { logx: false, logy: false, x: [a, b], y: [0, 1.08 * ymax], xlabel: "x", ylabel: "samples per bin" });
    r.bins.forEach((v, i) => {
      const x0 = c.X(a + i * w), x1 = c.X(a + (i + 1) * w);
      el("rect", { x: x0, y: c.Y(v), width: Math.max(0.5, x1 - x0 - 0.5), height: Math.max(0, c.Y(0) - c.Y(v)), class: "bar" }, svg);
    });
    const steps = r.expected.flatMap((e, i) => [[a + i * w, e], [a + (i + 1) * w, e]]);
    polyline(svg, c, steps, { class: "density expected" });
    legend($("s-hist-legend"), [{ text: "samples in each bin", color: "#8fb3d6", kind: "bar" },
      { text: `expected count of each bin: N × the density's integral over it (N = ${r.samples}, bin width ${fmt(w)})`, color: "#d55e00" }]);
    const method = r.method.replace("_", " ") + (r.n ? `, a table of ${r.n} bins` : "") + (r.tolerance ? `, tolerance ${r.tolerance}` : "");
    $("s-run-info").textContent = `${$("s-density").selectedOptions[0].textContent}; ${method}; ${r.samples} samples in ${nb} bins`;
    numbers($("s-numbers"), [
      ["method", method],
      ["max u-error", fmt(r.u_error)],
      ["max x-error", r.x_error === null ? "n/a (not an inversion)" : fmt(r.x_error)],
      ["ns per sample", fmt(r.ns_per_sample) + (r.shared_cores ? " (shared cores)" : "")],
      ["build", fmt(r.build_ms) + " ms"],
      ["chi-square", `${fmt(r.chi2.statistic, 4)} on ${r.chi2.dof} dof`],
      ["p-value", pValue(r.chi2.p_value)],
      ["outside the domain", String(r.outside_domain)],
    ]);
    unmarkStale($("s-figure"), $("s-numbers"));
    $("s-status").textContent = `${r.samples} samples` + (r.shared_cores ? `; ${SHARED}` : "");
  } catch (e) {
    if (e.parameter && $({ n: "s-n", samples: "s-samples", bins: "s-bins" }[e.parameter] || "-")) {
      markInvalid($({ n: "s-n", samples: "s-samples", bins: "s-bins" }[e.parameter]), e.message);
    }
    report($("s-status"), e);
    markStale($("s-figure"), $("s-numbers"), "This run was refused: these are the results of the last one.");
  } finally {
    $("s-run").disabled = false;
  }
}

function grid(svg, counts, n, vmax) {
  while (svg.firstChild) svg.removeChild(svg.firstChild);
  const size = 264, x0 = 30, y0 = 6, cell = size / n;
  for (let iy = 0; iy < n; iy++) for (let ix = 0; ix < n; ix++) {
    // row iy = 0 is cos theta = -1: draw it at the bottom
    el("rect", { x: x0 + ix * cell, y: y0 + (n - 1 - iy) * cell, width: cell + 0.3, height: cell + 0.3,
      fill: heatRgb(counts[iy * n + ix] / vmax) }, svg);
  }
  el("rect", { x: x0, y: y0, width: size, height: size, class: "axis" }, svg);
  el("text", { x: x0 + size / 2, y: y0 + size + 16, "text-anchor": "middle" }, svg).textContent = "phi 0 .. 2pi";
  el("text", { x: 16, y: y0 + 10, "text-anchor": "middle" }, svg).textContent = "+1";
  el("text", { x: 16, y: y0 + size, "text-anchor": "middle" }, svg).textContent = "-1";
  el("text", { x: 16, y: y0 + size / 2 + 4, "text-anchor": "middle" }, svg).textContent = "cos";
}

async function dRun() {
  if (!checkFields([$("d-samples"), $("d-cells")])) {
    markStale($("d-plots"), $("d-numbers"), "Not run: a field above is refused. These are the results of the last run.");
    return;
  }
  const q = new URLSearchParams({ pdf: $("d-pdf").value, samples: $("d-samples").value, cells: $("d-cells").value });
  $("d-status").textContent = "sampling ...";
  $("d-run").disabled = true;
  try {
    const r = await api("/api/sampling/sphere?" + q);
    await heatInit();
    const vmax = Math.max(...r.observed, ...r.expected, 1);
    grid($("d-observed"), r.observed, r.cells, vmax);
    grid($("d-expected"), r.expected, r.cells, vmax);
    heatKey($("d-key"), [[0, "0"], [0.5, fmt(vmax / 2)], [1, fmt(vmax)]], "samples per cell (both maps): dark few, bright many");
    numbers($("d-numbers"), [
      ["density", $("d-pdf").selectedOptions[0].textContent],
      ["chi-square", `${fmt(r.statistic, 4)} on ${r.dof} dof`],
      ["p-value", pValue(r.p_value)],
      ["outside support", String(r.outside_support)],
      ["density integrates to", fmt(r.expected_fraction, 4)],
      ["ns per direction", fmt(r.ns_per_sample) + (r.shared_cores ? " (shared cores)" : "")],
    ]);
    unmarkStale($("d-plots"), $("d-numbers"));
    $("d-status").textContent = `${r.samples} directions in ${r.cells} x ${r.cells} cells` + (r.shared_cores ? `; ${SHARED}` : "");
  } catch (e) {
    if (e.parameter && { samples: 1, cells: 1 }[e.parameter]) markInvalid($(e.parameter === "samples" ? "d-samples" : "d-cells"), e.message);
    report($("d-status"), e);
    markStale($("d-plots"), $("d-numbers"), "This run was refused: these are the results of the last one.");
  } finally {
    $("d-run").disabled = false;
  }
}

async function samplingInit() {
  if (samplingList) return;
  const list = await api("/api/sampling/list");
  samplingList = list;
  const caps = list.caps;
  for (const [id, [lo, hi]] of [["s-n", caps.n], ["s-samples", caps.samples], ["s-bins", caps.bins],
    ["d-samples", caps.samples], ["d-cells", caps.cells]]) { $(id).min = lo; $(id).max = hi; }
  for (const d of list.densities) $("s-density").add(new Option(d.about, d.name));
  for (const d of list.directions) $("d-pdf").add(new Option(d.about, d.name));
  $("s-density").onchange = sFillMethods;
  $("s-method").onchange = sShowFields;
  for (const id of ["s-n", "s-samples", "s-bins", "s-tol"]) $(id).oninput = sInputsChanged;
  for (const id of ["d-pdf", "d-samples", "d-cells"]) {
    $(id).oninput = () => {
      checkFields([$("d-samples"), $("d-cells")]);
      markStale($("d-plots"), $("d-numbers"), "These are the results of the last run, not of the settings above: press Sample.");
    };
  }
  sFillMethods();
  unmarkStale($("s-figure"), $("s-numbers"));
  $("s-run").onclick = guarded(sRun, $("s-status"));
  $("d-run").onclick = guarded(dRun, $("d-status"));
}

// ---------------------------------------------------------------- Cornell box
const cornell = { frame: -1, polling: false, strategies: [], settings: null, synced: {}, pending: {},
  minGeneration: 0, ready: false, errorFor: null, queued: {}, flushing: false };

// The fields, by the name of their query parameter.
const C_FIELDS = { strategy: "c-strategy", mixture_weight: "c-weight", rr: "c-rr", lds: "c-lds",
  sph_rect: "c-sph", width: "c-width", seed: "c-seed", max_depth: "c-depth" };
const C_CHECKBOXES = ["rr", "lds", "sph_rect"];
// How the offline banner names them.
const C_NAMES = { strategy: "strategy", mixture_weight: "mixture weight", rr: "Russian roulette",
  lds: "low-discrepancy", sph_rect: "spherical rectangles", width: "size", seed: "seed", max_depth: "max depth" };

function cValue(param) {
  const e = $(C_FIELDS[param]);
  return C_CHECKBOXES.includes(param) ? (e.checked ? "1" : "0") : e.value;
}

// What the server uses for `param`, as the field shows it.
function serverValue(s, param) {
  const v = s[param];
  return typeof v === "boolean" ? (v ? "1" : "0") : String(v);
}

function cDisabled(param, strategy) {
  if (param === "mixture_weight") return strategy !== "mixture";
  if (C_CHECKBOXES.includes(param)) return strategy !== "mis";
  return false;
}

// The strategy the fields are for: one waiting for the server, else the server's.
function cStrategy(s) {
  return cornell.queued.strategy ? cornell.queued.strategy.value : s.strategy;
}

// ------------------------------------------------ changes made while the server is gone
// `cornell.queued`: by parameter, the latest value of each field changed while the server did not
// answer ({ value }). Each is sent as its own parameter when the server is back (`cFlush`), in the
// order of C_FIELDS (the strategy before the fields it enables); until then its field is marked, and
// the banner counts them.

function markQueued(input, text) {
  input.dataset.queued = "1";
  if (input.getAttribute("aria-invalid")) input.removeAttribute("aria-invalid");
  const m = fieldMsg(input);
  m.classList.add("pending");
  m.textContent = text;
}

function unmarkQueued(input) {
  if (!input.dataset.queued) return;
  delete input.dataset.queued;
  const m = fieldMsg(input);
  // A refusal's message, put there meanwhile, stays.
  if (m.classList.contains("pending")) { m.classList.remove("pending"); m.textContent = ""; }
}

function cQueue(param, value) {
  cornell.queued[param] = { value };
  if (cornell.errorFor === param) { $("c-error").textContent = ""; cornell.errorFor = null; }
  markQueued($(C_FIELDS[param]), "waiting for the server: sent when it answers");
  cQueueShow();
}

function cUnqueue(param) {
  if (!cornell.queued[param]) return;
  delete cornell.queued[param];
  unmarkQueued($(C_FIELDS[param]));
  cQueueShow();
}

// The fields as the changes waiting make them (a strategy waiting enables its own fields; a value
// waiting in a field that is now disabled is dropped: a disabled field is never sent), and the
// banner's count.
function cQueueShow() {
  if (cornell.settings) {
    const strategy = cStrategy(cornell.settings);
    for (const [param, id] of Object.entries(C_FIELDS)) {
      const disabled = cDisabled(param, strategy);
      $(id).disabled = disabled;
      if (disabled && cornell.queued[param]) { delete cornell.queued[param]; unmarkQueued($(id)); }
    }
  }
  const waiting = Object.keys(C_FIELDS).filter((p) => cornell.queued[p]);
  const n = waiting.length;
  const shown = (p) => C_CHECKBOXES.includes(p) ? (cornell.queued[p].value === "1" ? "on" : "off") : cornell.queued[p].value;
  $("offline-queue").textContent = n ? `${n} change${n > 1 ? "s" : ""} waiting for the server (` +
    waiting.map((p) => `${C_NAMES[p]} ${shown(p)}`).join(", ") + "): sent when it answers." : "";
  document.body.dataset.queuedChanges = n;
}

// Send the changes waiting, one at a time (each its own parameter: a refused one stays on its
// field, marked, and blocks none of the others), then show what the server uses. Gone again: what
// is left waits for the next time.
async function cFlush() {
  if (cornell.flushing) return;
  cornell.flushing = true;
  try {
    while (!net.offline) {
      const param = Object.keys(C_FIELDS).find((p) => cornell.queued[p]);
      if (!param) break;
      const q = cornell.queued[param], input = $(C_FIELDS[param]);
      markQueued(input, "sending ...");
      const result = await cSend(param, q.value);
      if (result === "offline") {
        if (cornell.queued[param] === q) markQueued(input, "waiting for the server: sent when it answers");
        break;
      }
      // Changed again meanwhile: the newer value goes next.
      if (cornell.queued[param] === q) { delete cornell.queued[param]; unmarkQueued(input); }
    }
  } finally {
    cornell.flushing = false;
    cQueueShow();
    if (cornell.settings && !net.offline) syncControls(cornell.settings, true);
  }
}

// A change of one field: only that parameter goes to the server (a disabled field is never sent, and
// one refused value does not block the others). Refused, the field keeps the value, marked, with the
// server's message and what the render goes on with. The server gone, it waits (`cornell.queued`).
async function cChange(param) {
  const input = $(C_FIELDS[param]);
  if (input.disabled) return;
  if (input.type === "number") {
    const p = numberProblem(input);
    if (p) {
      // The latest value is this one: nothing of the field waits to be sent.
      cUnqueue(param);
      markInvalid(input, `${p}; not sent: the render goes on with ${cornell.settings ? serverValue(cornell.settings, param) : "the last value"}`);
      return;
    }
  }
  const value = cValue(param);
  // Gone, or changes made while it was gone still on their way: after them, in their order.
  if (net.offline || cornell.flushing || cornell.queued[param]) {
    cQueue(param, value);
    if (!net.offline) cFlush();
    return;
  }
  // It went away just now: the change waits for it, unless a newer one already does.
  if (await cSend(param, value) === "offline" && !cornell.queued[param]) cQueue(param, value);
}

// POST one parameter; "taken", "refused" (the field marked, with the server's message) or "offline".
async function cSend(param, value) {
  const input = $(C_FIELDS[param]);
  const q = new URLSearchParams({ [param]: value });
  cornell.pending[param] = true;
  try {
    const r = await api("/api/render/settings?" + q, { method: "POST" });
    cornell.minGeneration = Math.max(cornell.minGeneration, r.generation);
    markValid(input);
    if (cornell.errorFor === param) { $("c-error").textContent = ""; cornell.errorFor = null; }
    document.body.dataset.renderGeneration = r.generation;
    cornell.settings = r.settings;
    syncControls(r.settings, true);
    return "taken";
  } catch (e) {
    if (e instanceof Offline) return "offline";
    const field = e.parameter && C_FIELDS[e.parameter] ? $(C_FIELDS[e.parameter]) : input;
    const now = cornell.settings ? `; the render goes on with ${serverValue(cornell.settings, e.parameter || param)}` : "";
    markInvalid(field, e.message + now);
    $("c-error").textContent = `Refused: ${e.message}${now}.`;
    cornell.errorFor = e.parameter || param;
    return "refused";
  } finally {
    delete cornell.pending[param];
  }
}

// Show the server's settings (another tab may have changed them), except in a field being edited
// (focused and changed), holding a refused value (marked, with what the server uses instead) or a
// value waiting for the server.
function syncControls(s, afterOwnChange = false) {
  cornell.settings = s;
  const strategy = cStrategy(s);
  for (const [param, id] of Object.entries(C_FIELDS)) {
    const e = $(id), want = serverValue(s, param);
    const disabled = cDisabled(param, strategy);
    e.disabled = disabled;
    if (cornell.queued[param]) continue;
    const box = C_CHECKBOXES.includes(param);
    const shown = box ? (e.checked ? "1" : "0") : e.value;
    if (disabled) {
      // Not used by this strategy: never refused, shows the server's.
      if (e.getAttribute("aria-invalid")) markValid(e);
      if (cornell.errorFor === param) { $("c-error").textContent = ""; cornell.errorFor = null; }
    } else if (e.getAttribute("aria-invalid")) {
      const m = fieldMsg(e);
      m.textContent = m.textContent.replace(/the render goes on with .*$/, `the render goes on with ${want}`);
      continue;
    } else if (!afterOwnChange && (cornell.pending[param]
      || (document.activeElement === e && !box && shown !== cornell.synced[param]))) {
      continue; // being edited, or on its way to the server
    }
    if (shown !== want) { if (box) e.checked = want === "1"; else e.value = want; }
    cornell.synced[param] = want;
  }
}

async function drawPng(canvas, kind, id) {
  let r;
  try { r = await fetch(`/api/render/image?kind=${kind}&frame=${id}`); } catch (e) { wentOffline(); throw new Offline("gone"); }
  if (!r.ok) return;
  const bmp = await createImageBitmap(await r.blob());
  if (canvas.width !== bmp.width || canvas.height !== bmp.height) { canvas.width = bmp.width; canvas.height = bmp.height; }
  canvas.getContext("2d").drawImage(bmp, 0, 0);
}

// A fixed colour per strategy (its place in the server's list), and dashes for its other settings
// (in the order the server keeps the curves).
function curveStyles(curves) {
  const seen = {};
  return curves.map((c) => {
    const i = Math.max(0, cornell.strategies.indexOf(c.strategy));
    const k = seen[c.strategy] = (seen[c.strategy] ?? -1) + 1;
    return { color: PALETTE[i % PALETTE.length], dash: DASHES[k % DASHES.length] };
  });
}

function drawCurves(s) {
  const styles = curveStyles(s.curves);
  const widths = new Set(s.curves.map((c) => c.width));
  widths.add(s.settings.width);
  const floorAt = {};
  for (const f of s.floors) floorAt[f.width] = f;
  // Subtracting the reference's variance is right only where it is measured (at the reference's spp).
  const exact = (f) => f && f.measured_spp === f.reference_spp;
  const box = $("c-correct");
  box.disabled = !s.curves.some((c) => exact(floorAt[c.width]));
  const correct = box.checked && !box.disabled;
  const floors = s.floors.filter((f) => widths.has(f.width)).map((f) => ({
    y: f.rmse,
    text: `the reference's noise${widths.size > 1 ? ` at ${f.width} px` : ""}`,
    legend: `the reference's own noise at ${f.width} px, ${exact(f) ? "" : "at most "}about ${fmt(f.rmse, 2)} (it has ${f.reference_spp} spp): ` +
      (correct && exact(f) ? "subtracted from the curves at this size (marked corrected)"
        : "below this line a curve measures the reference's noise, not its own error"),
  }));
  const curves = s.curves.map((c, i) => {
    const f = floorAt[c.width];
    let points = c.points.map((p) => [p[0], p[2]]);
    let label = c.label;
    // The slope is fitted where the curve is well above the reference's noise (at it, it flattens
    // whatever the render does).
    let fit = f ? points.filter((p) => p[1] >= 2 * f.rmse) : points;
    if (correct && exact(f)) {
      const v = f.rmse * f.rmse;
      points = points.filter((p) => p[1] * p[1] >= 1.25 * v).map(([t, r]) => [t, Math.sqrt(r * r - v)]);
      fit = points;
      label += ", corrected";
    }
    return { label, color: styles[i].color, dash: styles[i].dash, points, fit };
  });
  const svg = $("c-curves");
  loglogCurves(svg, $("c-curves-legend"), curves, "seconds", correct ? "RMSE, the reference's noise subtracted" : "RMSE (linear radiance)", true, floors);
  if (correct) {
    legend($("c-curves-note"), [{ text: "corrected: sqrt(RMSE² − the reference's variance), the render and the reference " +
      "being independent; points less than 12% above the reference's noise are left out (there the difference is noise)",
    color: "#555", wide: true, kind: "none" }]);
  } else $("c-curves-note").textContent = "";
  svg.dataset.curves = s.curves.length;
  svg.dataset.floors = floors.length;
}

function describeReference(s) {
  const w = s.settings.width, f = s.floors.find((x) => x.width === w);
  let text = `Reference at ${w} px: ${s.reference}. `;
  text += `It is not exact: a render of ${s.reference_spp} spp has noise of its own, and every curve flattens at it ` +
    "whatever the strategy; only a curve that levels off above it (light's) is biased. Slopes are fitted above twice that noise. ";
  if (!f) text += "Its noise is measured once the reference is ready.";
  else if (f.measured_spp === f.reference_spp) {
    text += `Its noise: ${fmt(f.rmse, 2)} RMSE, measured by ${f.measured_by} at ${f.reference_spp} spp, the reference's twin ` +
      "(the same render under another seed): their mean squared difference is twice the reference's variance.";
  } else {
    text += `Its noise: at most about ${fmt(f.rmse, 2)} RMSE, from the error of ${f.measured_by} at ${f.measured_spp} spp ` +
      `(MSE × ${f.measured_spp} / (${f.reference_spp} + ${f.measured_spp}), its variance falling at least as 1/spp); ` +
      `measured exactly when a render like the reference (mis+rr+lds, depth 50, any seed but 999) reaches ${f.reference_spp} spp.`;
  }
  $("c-reference").textContent = text;
}

async function pollRender() {
  if (cornell.polling || !cornell.ready) return;
  cornell.polling = true;
  try {
    while (activeBench === "cornell" && document.visibilityState === "visible" && !net.offline) {
      try {
        await pollOnce();
      } catch (e) {
        // Gone: the banner's probe starts the polling again. Anything else: said, and asked again.
        if (e instanceof Offline) break;
        $("c-status").textContent = "";
        report($("c-status"), e);
        await new Promise((ok) => setTimeout(ok, 1000));
      }
    }
  } finally {
    cornell.polling = false;
  }
}

async function pollOnce() {
  const t0 = performance.now();
  const s = await api("/api/render/state");
  // An answer from before this page's last change of settings: its settings are no longer.
  if (s.generation >= cornell.minGeneration) syncControls(s.settings);
  const f = s.frame;
  if (f.id !== cornell.frame && f.id > 0) {
    cornell.frame = f.id;
    await Promise.all([drawPng($("c-image"), "image", f.id), drawPng($("c-variance"), "variance", f.id)]);
    $("c-image").dataset.frame = f.id;
    $("c-image").dataset.generation = f.generation;
  }
  const switching = f.generation !== s.generation ? " (switching)" : "";
  const resumed = f.resumed ? "; continued where this setting was left" : "";
  $("c-status").textContent = f.id > 0 ? `${s.settings.label}: ${f.spp} spp in ${fmt(f.seconds)} s, ` +
    `${fmt(f.rays_per_second)} rays/s, RMSE ${f.rmse === null ? "(waiting for the reference)" : fmt(f.rmse, 4)}${resumed}${switching}`
    : `${s.settings.label}: starting ...`;
  cornell.last = s;
  describeReference(s);
  drawCurves(s);
  const wait = 150 - (performance.now() - t0);
  if (wait > 0) await new Promise((ok) => setTimeout(ok, wait));
}

async function cClear() {
  const r = await api("/api/render/clear", { method: "POST" });
  cornell.minGeneration = Math.max(cornell.minGeneration, r.generation);
  document.body.dataset.renderGeneration = r.generation;
}

async function cornellInit() {
  if (cornell.ready) return;
  const [l] = await Promise.all([api("/api/render/list"), heatInit()]);
  cornell.strategies = l.strategies;
  for (const s of l.strategies) $("c-strategy").add(new Option(s, s));
  $("c-width").min = l.widths[0]; $("c-width").max = l.widths[1];
  syncControls(l.current, true);
  for (const param of Object.keys(C_FIELDS)) $(C_FIELDS[param]).onchange = () => cChange(param);
  $("c-clear").onclick = guarded(cClear, $("c-error"));
  $("c-correct").onchange = () => { if (cornell.last) drawCurves(cornell.last); };
  heatKey($("c-key"), [[0, "1e-4"], [2 / 7, "1e-2"], [4 / 7, "1"], [6 / 7, "1e2"], [1, "1e3"]],
    "log scale: dark low, bright high");
  document.addEventListener("visibilitychange", () => { if (activeBench === "cornell") pollRender(); });
  cornell.ready = true;
}

// Every bench's menus from the server; again when the server is back, if it was gone.
async function init() {
  try {
    await Promise.all([mcInit(), samplingInit(), cornellInit()]);
    const fatal = $("fatal");
    if (fatal) fatal.remove();
  } catch (e) {
    if (e instanceof Offline) return;
    if (!$("fatal")) {
      const p = document.createElement("p"); p.className = "error"; p.id = "fatal";
      p.textContent = "The lab's server did not answer as expected: " + e.message; document.body.prepend(p);
    }
  }
}

window.addEventListener("DOMContentLoaded", async () => {
  tabsInit();
  $("offline-now").onclick = probe;
  net.onBack.push(async () => {
    // What was changed meanwhile goes first (each change in its turn), then the menus and the polling.
    if (cornell.ready) cFlush();
    await init();
    if (activeBench === "cornell") pollRender();
  });
  await init();
  show(location.hash.slice(1));
  window.labReady = true;
});
