// rtl lab: the page's script. It asks the server (same origin) for numbers and draws them as SVG and
// canvas; no library, nothing from the network.
"use strict";

const $ = (id) => document.getElementById(id);
const SVG = "http://www.w3.org/2000/svg";
const COLORS = ["#b8451f", "#1f6fb8", "#2e8b57", "#8e44ad", "#c98a00", "#008b8b", "#d0407a",
  "#5a5a5a", "#7a9a01", "#3b4cc0", "#a0522d", "#e67e22", "#16a085", "#9b59b6", "#34495e", "#c0392b"];

async function api(path, opts) {
  const r = await fetch(path, opts);
  const body = await r.json();
  if (!r.ok) throw new Error(body.error || ("HTTP " + r.status));
  return body;
}

function el(name, attrs, parent) {
  const e = document.createElementNS(SVG, name);
  for (const [k, v] of Object.entries(attrs || {})) e.setAttribute(k, v);
  if (parent) parent.appendChild(e);
  return e;
}

function showError(box, e) {
  box.textContent = "";
  const span = document.createElement("span");
  span.className = "error";
  span.textContent = e.message;
  box.appendChild(span);
}

function fmt(x, digits = 3) {
  if (x === null || x === undefined || !isFinite(x)) return "n/a";
  if (x === 0) return "0";
  const a = Math.abs(x);
  return (a >= 1e4 || a < 1e-3) ? x.toExponential(digits - 1) : x.toPrecision(digits);
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
  const vb = svg.viewBox.baseVal;
  const W = vb.width, H = vb.height;
  const m = { l: 56, r: 10, t: 10, b: 36 };
  const tr = (log) => log ? Math.log10 : (v) => v;
  const fx = tr(opts.logx), fy = tr(opts.logy);
  let [x0, x1] = opts.x.map(fx), [y0, y1] = opts.y.map(fy);
  if (!(x1 > x0)) { x0 -= 1; x1 += 1; }
  if (!(y1 > y0)) { y0 -= 1; y1 += 1; }
  if (opts.logx) { x0 = Math.floor(x0); x1 = Math.ceil(x1); }
  if (opts.logy) { y0 = Math.floor(y0); y1 = Math.ceil(y1); }
  const X = (v) => m.l + (fx(v) - x0) / (x1 - x0) * (W - m.l - m.r);
  const Y = (v) => H - m.b - (fy(v) - y0) / (y1 - y0) * (H - m.t - m.b);
  const ticks = (a, b, log) => {
    if (log) { const t = []; const step = Math.max(1, Math.ceil((b - a) / 8)); for (let k = a; k <= b; k += step) t.push(k); return t; }
    const span = b - a, raw = span / 5, mag = Math.pow(10, Math.floor(Math.log10(raw)));
    const step = [1, 2, 5, 10].map((s) => s * mag).find((s) => span / s <= 6);
    const t = []; for (let v = Math.ceil(a / step) * step; v <= b + 1e-12 * span; v += step) t.push(v); return t;
  };
  const label = (v, log) => log ? ("1e" + v) : fmt(v, 3);
  for (const t of ticks(x0, x1, opts.logx)) {
    const x = m.l + (t - x0) / (x1 - x0) * (W - m.l - m.r);
    el("line", { x1: x, x2: x, y1: m.t, y2: H - m.b, class: "grid" }, svg);
    el("text", { x, y: H - m.b + 14, "text-anchor": "middle" }, svg).textContent = label(t, opts.logx);
  }
  for (const t of ticks(y0, y1, opts.logy)) {
    const y = H - m.b - (t - y0) / (y1 - y0) * (H - m.t - m.b);
    el("line", { x1: m.l, x2: W - m.r, y1: y, y2: y, class: "grid" }, svg);
    el("text", { x: m.l - 4, y: y + 4, "text-anchor": "end" }, svg).textContent = label(t, opts.logy);
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

// A legend in a corner: "tr" (top right) or "bl" (bottom left, where falling curves seldom are).
function legend(svg, c, entries, corner = "tr") {
  const width = 26 + 6.2 * Math.max(0, ...entries.map((e) => e[0].length));
  const x = corner === "tr" ? c.W - c.m.r - width : c.m.l + 8;
  const top = corner === "tr" ? c.m.t + 12 : c.H - c.m.b - 8 - 14 * (entries.length - 1);
  entries.forEach(([text, color], i) => {
    const y = top + 14 * i;
    el("line", { x1: x, x2: x + 18, y1: y - 4, y2: y - 4, stroke: color, "stroke-width": 2 }, svg);
    el("text", { x: x + 22, y }, svg).textContent = text;
  });
}

function extent(values, log) {
  const v = values.filter((x) => isFinite(x) && (!log || x > 0));
  if (!v.length) return [1, 10];
  return [Math.min(...v), Math.max(...v)];
}

// A log-log chart of curves [{label, color, points: [[x, y]]}], each with its fitted slope.
function loglogCurves(svg, curves, xlabel, ylabel, withSlope) {
  const xs = curves.flatMap((s) => s.points.map((p) => p[0]));
  const ys = curves.flatMap((s) => s.points.map((p) => p[1]));
  const c = chart(svg, { logx: true, logy: true, x: extent(xs, true), y: extent(ys, true), xlabel, ylabel });
  for (const s of curves) {
    const p = s.points.filter(([x, y]) => x > 0 && y > 0);
    if (!p.length) continue;
    const path = polyline(svg, c, p, { class: "curve", stroke: s.color });
    path.dataset.label = s.label;
    for (const [x, y] of p.length < 40 ? p : []) el("circle", { cx: c.X(x), cy: c.Y(y), r: 2, fill: s.color }, svg);
  }
  legend(svg, c, curves.map((s) => {
    const k = withSlope ? loglogSlope(s.points) : null;
    return [s.label + (k === null ? "" : `  (slope ${k.toFixed(2)})`), s.color];
  }), "bl");
  return c;
}

// ---------------------------------------------------------------- the benches: switching
let activeBench = "mc";
function show(bench) {
  activeBench = bench;
  for (const b of document.querySelectorAll("nav button")) b.classList.toggle("on", b.dataset.bench === bench);
  for (const s of document.querySelectorAll(".bench")) s.classList.toggle("on", s.id === "bench-" + bench);
  if (bench === "cornell") pollRender();
}

// ---------------------------------------------------------------- Monte Carlo
const mc = { list: null, runs: [], current: null, busy: false };

function mcIntegral() { return mc.list.integrals.find((i) => i.slug === $("mc-integral").value); }

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
    el("path", { d, class: "band" }, svg).dataset.points = String(banded.length);
  }
  el("line", { x1: c.m.l, x2: c.W - c.m.r, y1: c.Y(integral.exact), y2: c.Y(integral.exact), class: "exact" }, svg);
  if (pts.length) polyline(svg, c, pts.map((p) => [p.n, p.estimate]), { class: "curve", stroke: cur.color });
  legend(svg, c, [[`exact ${fmt(integral.exact, 6)}`, "#222"]].concat(cur ? [[cur.estimator + ", 95% band", cur.color]] : []));
  // RMS error against N and against time
  const curves = (key) => runs.map((r) => ({ label: r.estimator, color: r.color,
    points: r.points.map((p) => [key(p), p.rms_error]) }));
  loglogCurves($("mc-vs-n"), curves((p) => p.n), "samples N", "RMS error", true);
  loglogCurves($("mc-vs-t"), curves((p) => p.seconds_per_estimate), "seconds per estimate", "RMS error", true);
  const body = $("mc-table").tBodies[0];
  body.innerHTML = "";
  for (const p of pts.slice(-8)) {
    const row = body.insertRow();
    for (const v of [p.n, fmt(p.estimate, 7), p.lo === null ? "n/a" : `${fmt(p.lo, 6)} .. ${fmt(p.hi, 6)}`,
      fmt(p.rms_error), fmt(p.mean_std_error), fmt(p.ns_per_sample)]) row.insertCell().textContent = v;
  }
}

async function mcRun() {
  if (mc.busy) return;
  const integral = mcIntegral(), estimator = $("mc-estimator").value;
  const max = Math.max(4, Math.min(20, parseInt($("mc-max").value, 10) || 16));
  mc.busy = true;
  $("mc-run").disabled = true;
  mc.runs = mc.runs.filter((r) => !(r.slug === integral.slug && r.estimator === estimator));
  const run = { slug: integral.slug, estimator, color: COLORS[mc.runs.length % COLORS.length], points: [] };
  mc.runs.push(run);
  mc.current = run;
  try {
    for (let k = 4; k <= max; k++) {
      $("mc-status").textContent = `N = 2^${k} ...`;
      const q = new URLSearchParams({ integral: integral.slug, estimator, log2_n: k });
      run.points.push(await api("/api/mc/run?" + q));
      mcDraw();
    }
    $("mc-status").textContent = `done: ${integral.integral}, ${estimator}, N up to 2^${max}`;
  } catch (e) {
    showError($("mc-status"), e);
  } finally {
    mc.busy = false;
    $("mc-run").disabled = false;
  }
}

async function mcInit() {
  mc.list = await api("/api/mc/list");
  const sel = $("mc-integral");
  for (const i of mc.list.integrals) sel.add(new Option(`${i.integral} = ${fmt(i.exact, 6)}`, i.slug));
  sel.onchange = mcFillEstimators;
  mcFillEstimators();
  $("mc-run").onclick = mcRun;
  $("mc-clear").onclick = () => { mc.runs = []; mc.current = null; mcDraw(); };
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

function sShowFields() {
  const m = $("s-method").value;
  $("s-n").parentElement.style.display = ["binary_search", "guide_table", "alias"].includes(m) ? "" : "none";
  $("s-tol").parentElement.style.display = m === "numeric" ? "" : "none";
}

function numbers(box, rows) {
  box.innerHTML = rows.map(([k, v]) => `<div><b>${k}</b> ${v}</div>`).join("");
}

async function sRun() {
  const q = new URLSearchParams({ density: $("s-density").value, method: $("s-method").value,
    samples: $("s-samples").value, bins: $("s-bins").value });
  if ($("s-n").parentElement.style.display !== "none") q.set("n", $("s-n").value);
  if ($("s-tol").parentElement.style.display !== "none") q.set("tolerance", $("s-tol").value);
  $("s-status").textContent = "sampling ...";
  try {
    const r = await api("/api/sampling/line?" + q);
    const [a, b] = r.domain, nb = r.bins.length, w = (b - a) / nb;
    const dens = r.bins.map((c) => c / (r.samples * w));
    const ymax = Math.max(...dens, ...r.curve.map((p) => p[1]));
    const svg = $("s-hist");
    const c = chart(svg, { logx: false, logy: false, x: [a, b], y: [0, 1.08 * ymax], xlabel: "x", ylabel: "density" });
    dens.forEach((v, i) => {
      const x0 = c.X(a + i * w), x1 = c.X(a + (i + 1) * w);
      el("rect", { x: x0, y: c.Y(v), width: Math.max(0.5, x1 - x0 - 0.5), height: Math.max(0, c.Y(0) - c.Y(v)), class: "bar" }, svg);
    });
    polyline(svg, c, r.curve, { class: "density" });
    legend(svg, c, [["samples / (N bin width)", "#9fb7d0"], ["the density", "#b8451f"]]);
    numbers($("s-numbers"), [
      ["method", r.method.replace("_", " ") + (r.n ? `, ${r.n} bins` : "") + (r.tolerance ? `, tol ${r.tolerance}` : "")],
      ["max u-error", fmt(r.u_error)],
      ["max x-error", r.x_error === null ? "n/a (not an inversion)" : fmt(r.x_error)],
      ["ns per sample", fmt(r.ns_per_sample)],
      ["build", fmt(r.build_ms) + " ms"],
      ["chi-square", `${fmt(r.chi2.statistic, 4)} on ${r.chi2.dof} dof`],
      ["p-value", fmt(r.chi2.p_value)],
      ["outside the domain", r.outside_domain],
    ]);
    $("s-status").textContent = `${r.samples} samples`;
  } catch (e) {
    showError($("s-status"), e);
  }
}

function heatColor(t) {
  t = Math.max(0, Math.min(1, t));
  const stops = [[0, [250, 250, 255]], [0.5, [120, 160, 220]], [1, [20, 30, 110]]];
  for (let i = 1; i < stops.length; i++) {
    const [t0, a] = stops[i - 1], [t1, b] = stops[i];
    if (t <= t1) { const f = (t - t0) / (t1 - t0); return `rgb(${a.map((v, k) => Math.round(v + f * (b[k] - v))).join(",")})`; }
  }
  return "rgb(20,30,110)";
}

function grid(svg, counts, n, vmax) {
  while (svg.firstChild) svg.removeChild(svg.firstChild);
  const size = 270, x0 = 24, y0 = 6, cell = size / n;
  for (let iy = 0; iy < n; iy++) for (let ix = 0; ix < n; ix++) {
    // row iy = 0 is cos theta = -1: draw it at the bottom
    el("rect", { x: x0 + ix * cell, y: y0 + (n - 1 - iy) * cell, width: cell + 0.3, height: cell + 0.3,
      fill: heatColor(counts[iy * n + ix] / vmax) }, svg);
  }
  el("rect", { x: x0, y: y0, width: size, height: size, class: "axis" }, svg);
  el("text", { x: x0 + size / 2, y: y0 + size + 16, "text-anchor": "middle" }, svg).textContent = "phi 0 .. 2pi";
  el("text", { x: 14, y: y0 + 10, "text-anchor": "middle" }, svg).textContent = "+1";
  el("text", { x: 14, y: y0 + size, "text-anchor": "middle" }, svg).textContent = "-1";
  el("text", { x: 14, y: y0 + size / 2 + 4, "text-anchor": "middle" }, svg).textContent = "cos";
}

async function dRun() {
  const q = new URLSearchParams({ pdf: $("d-pdf").value, samples: $("d-samples").value, cells: $("d-cells").value });
  $("d-status").textContent = "sampling ...";
  try {
    const r = await api("/api/sampling/sphere?" + q);
    const vmax = Math.max(...r.observed, ...r.expected, 1);
    grid($("d-observed"), r.observed, r.cells, vmax);
    grid($("d-expected"), r.expected, r.cells, vmax);
    numbers($("d-numbers"), [
      ["chi-square", `${fmt(r.statistic, 4)} on ${r.dof} dof`],
      ["p-value", fmt(r.p_value) + (r.p_value < 1e-3 ? "  (the samples are not from this density)" : "")],
      ["outside support", r.outside_support],
      ["density integrates to", fmt(r.expected_fraction, 4)],
      ["ns per direction", fmt(r.ns_per_sample)],
    ]);
    $("d-status").textContent = `${r.samples} directions`;
  } catch (e) {
    showError($("d-status"), e);
  }
}

async function samplingInit() {
  samplingList = await api("/api/sampling/list");
  for (const d of samplingList.densities) $("s-density").add(new Option(d.about, d.name));
  for (const d of samplingList.directions) $("d-pdf").add(new Option(d.about, d.name));
  $("s-density").onchange = sFillMethods;
  $("s-method").onchange = sShowFields;
  sFillMethods();
  $("s-run").onclick = sRun;
  $("d-run").onclick = dRun;
}

// ---------------------------------------------------------------- Cornell box
const cornell = { frame: -1, polling: false, timer: null, colors: {} };

function cSettings() {
  return new URLSearchParams({ strategy: $("c-strategy").value, width: $("c-width").value,
    seed: $("c-seed").value, max_depth: $("c-depth").value, mixture_weight: $("c-weight").value,
    rr: $("c-rr").checked ? 1 : 0, lds: $("c-lds").checked ? 1 : 0, sph_rect: $("c-sph").checked ? 1 : 0 });
}

async function cApply() {
  const mis = $("c-strategy").value === "mis";
  for (const id of ["c-rr", "c-lds", "c-sph"]) $(id).disabled = !mis;
  $("c-weight").disabled = $("c-strategy").value !== "mixture";
  try {
    const r = await api("/api/render/settings?" + cSettings(), { method: "POST" });
    document.body.dataset.renderGeneration = r.generation;
  } catch (e) {
    showError($("c-status"), e);
  }
}

async function drawPng(canvas, kind, id) {
  const r = await fetch(`/api/render/image?kind=${kind}&frame=${id}`);
  if (!r.ok) return;
  const bmp = await createImageBitmap(await r.blob());
  if (canvas.width !== bmp.width || canvas.height !== bmp.height) { canvas.width = bmp.width; canvas.height = bmp.height; }
  canvas.getContext("2d").drawImage(bmp, 0, 0);
}

function colorOf(label) {
  if (!(label in cornell.colors)) cornell.colors[label] = COLORS[Object.keys(cornell.colors).length % COLORS.length];
  return cornell.colors[label];
}

async function pollRender() {
  if (cornell.polling) return;
  cornell.polling = true;
  let first = true;
  try {
    while (activeBench === "cornell" && document.visibilityState === "visible") {
      const t0 = performance.now();
      const s = await api("/api/render/state");
      if (first) { syncControls(s.settings); first = false; }
      const f = s.frame;
      if (f.id !== cornell.frame && f.id > 0) {
        cornell.frame = f.id;
        await Promise.all([drawPng($("c-image"), "image", f.id), drawPng($("c-variance"), "variance", f.id)]);
        $("c-image").dataset.frame = f.id;
        $("c-image").dataset.generation = f.generation;
      }
      const stale = f.generation !== s.generation ? " (restarting)" : "";
      $("c-status").textContent = `${s.settings.label}: ${f.spp} spp in ${fmt(f.seconds)} s, ` +
        `${fmt(f.rays_per_second)} rays/s, RMSE ${f.rmse === null ? "(waiting for the reference)" : fmt(f.rmse, 4)}${stale}`;
      $("c-reference").textContent = "reference: " + s.reference;
      const svg = $("c-curves");
      loglogCurves(svg, s.curves.map((c) => ({ label: c.label, color: colorOf(c.label),
        points: c.points.map((p) => [p[0], p[2]]) })), "seconds", "RMSE (linear radiance)", true);
      svg.dataset.curves = s.curves.length;
      const wait = 150 - (performance.now() - t0);
      if (wait > 0) await new Promise((ok) => setTimeout(ok, wait));
    }
  } catch (e) {
    showError($("c-status"), e);
  } finally {
    cornell.polling = false;
  }
}

// Show the server's settings (another tab may have changed them).
function syncControls(s) {
  $("c-strategy").value = s.strategy;
  $("c-width").value = s.width; $("c-seed").value = s.seed; $("c-depth").value = s.max_depth;
  $("c-rr").checked = s.rr; $("c-lds").checked = s.lds; $("c-sph").checked = s.sph_rect;
  for (const id of ["c-rr", "c-lds", "c-sph"]) $(id).disabled = s.strategy !== "mis";
  $("c-weight").value = s.mixture_weight; $("c-weight").disabled = s.strategy !== "mixture";
}

async function cornellInit() {
  const l = await api("/api/render/list");
  for (const s of l.strategies) $("c-strategy").add(new Option(s, s));
  syncControls(l.current);
  for (const id of ["c-strategy", "c-weight", "c-rr", "c-lds", "c-sph", "c-width", "c-seed", "c-depth"]) $(id).onchange = cApply;
  $("c-clear").onclick = () => api("/api/render/clear", { method: "POST" });
  document.addEventListener("visibilitychange", () => { if (activeBench === "cornell") pollRender(); });
}

window.addEventListener("DOMContentLoaded", async () => {
  for (const b of document.querySelectorAll("nav button")) b.onclick = () => show(b.dataset.bench);
  try {
    await Promise.all([mcInit(), samplingInit(), cornellInit()]);
  } catch (e) {
    const p = document.createElement("p"); p.className = "error"; p.id = "fatal";
    p.textContent = "The lab's server did not answer: " + e.message; document.body.prepend(p);
  }
  const wanted = location.hash.slice(1);
  show(["mc", "sampling", "cornell"].includes(wanted) ? wanted : "mc");
  window.labReady = true;
});
