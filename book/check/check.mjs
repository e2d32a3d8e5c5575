// The book as a reader sees it, checked in a real browser.
//
// Builds the book with mdBook into a temporary directory (or takes a built one), serves it on
// 127.0.0.1, and loads every page in headless Chromium with every other host unreachable. A page
// fails when
//   - an image does not load (a request fails or answers >= 400, or an <img> has no pixels),
//   - any raw TeX is visible in its text (outside code), or KaTeX reports a formula it cannot parse,
//   - the console shows an error (or a script throws),
//   - a request leaves 127.0.0.1.
// A missing page must be answered by the book's 404 page, with its styles and a working link to
// chapter 1 (the site is served under /book/, as `rtl lab` serves it).
// It also asserts that every chapter page (chNN-*) shows a figure and that the book shows at least
// 25 distinct ones.
//
// usage: node book/check/check.mjs [--built DIR] [--screenshots DIR] [--only PAGE.html]
//   (from the repository root; `npm ci --prefix book/check` installs the pinned playwright-core;
//   mdbook must be on PATH, Chromium at $CHROMIUM or /usr/bin/chromium)
import { chromium } from "playwright-core";
import { execFileSync } from "node:child_process";
import { createServer } from "node:http";
import { mkdtempSync, readdirSync, readFileSync, statSync, mkdirSync, rmSync } from "node:fs";
import { tmpdir } from "node:os";
import { join, extname, relative, resolve, sep } from "node:path";

const MIN_FIGURES = 25;
const args = process.argv.slice(2);
const opt = (name) => {
  const i = args.indexOf(name);
  return i >= 0 ? args[i + 1] : undefined;
};
const repo = resolve(new URL("../..", import.meta.url).pathname);

let root = opt("--built");
let scratch;
if (!root) {
  scratch = mkdtempSync(join(tmpdir(), "rtl-book-"));
  root = join(scratch, "site");
  execFileSync("mdbook", ["build", join(repo, "book"), "-d", root], { stdio: ["ignore", "ignore", "inherit"] });
}
root = resolve(root);
const shots = opt("--screenshots");
if (shots) mkdirSync(shots, { recursive: true });

function walk(dir) {
  return readdirSync(dir).flatMap((f) => {
    const p = join(dir, f);
    return statSync(p).isDirectory() ? walk(p) : [p];
  });
}
const pages = walk(root)
  // toc.html is mdBook's sidebar for readers without JavaScript, shown inside a frame of each page,
  // never opened on its own (opened alone, the browser asks for /favicon.ico, which it has no link for)
  .filter((p) => p.endsWith(".html") && relative(root, p) !== "toc.html")
  .map((p) => relative(root, p).split(sep).join("/"))
  .filter((p) => !opt("--only") || p === opt("--only"))
  .sort();
// A page that does not exist, two levels deep: the host answers with 404.html, whose styles, scripts
// and links must load from there too (its <base> is book.toml's site-url).
const PROBE = "no-such-part/no-such-page.html";
if (!opt("--only") || opt("--only") === PROBE) pages.push(PROBE);

const types = {
  ".html": "text/html; charset=utf-8", ".js": "text/javascript", ".mjs": "text/javascript",
  ".css": "text/css", ".svg": "image/svg+xml", ".png": "image/png", ".jpg": "image/jpeg",
  ".woff2": "font/woff2", ".woff": "font/woff", ".ttf": "font/ttf", ".json": "application/json",
  ".ico": "image/x-icon", ".csv": "text/csv", ".txt": "text/plain",
};
// The site is served under /book/, as `rtl lab` serves it (and as book.toml's site-url says), and a
// missing page is answered with the site's 404.html and status 404, as static hosts do.
const PREFIX = "/book/";
const server = createServer((req, res) => {
  const path = decodeURIComponent(new URL(req.url, "http://127.0.0.1").pathname);
  if (!path.startsWith(PREFIX)) { res.writeHead(404).end("not under /book/"); return; }
  let file = resolve(join(root, path.slice(PREFIX.length)));
  if (file !== root && !file.startsWith(root + sep)) { res.writeHead(403).end(); return; }
  try {
    if (statSync(file).isDirectory()) file = join(file, "index.html");
    const body = readFileSync(file);
    res.writeHead(200, { "content-type": types[extname(file)] ?? "application/octet-stream" }).end(body);
  } catch {
    try {
      res.writeHead(404, { "content-type": types[".html"] }).end(readFileSync(join(root, "404.html")));
    } catch {
      res.writeHead(404).end("not found");
    }
  }
});
await new Promise((ok) => server.listen(0, "127.0.0.1", ok));
const port = server.address().port;
const origin = `http://127.0.0.1:${port}`;

const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM ?? "/usr/bin/chromium",
  args: [
    "--no-sandbox",
    "--disable-gpu",
    "--host-resolver-rules=MAP * ~NOTFOUND, EXCLUDE 127.0.0.1",
    "--disable-background-networking",
    "--disable-component-update",
  ],
});
const context = await browser.newContext({ viewport: { width: 1200, height: 900 } });

// Raw TeX a reader could see: the delimiters and the commonest commands.
const TEX = /\\\(|\\\)|\\\[|\\\]|\$\$|\\frac|\\int|\\sum|\\theta|\\omega|\\mathrm|\\pi\b|\\cos|\\sin|\\,|\^\{|_\{/g;

const problems = [];
const figures = new Set();
for (const rel of pages) {
  const page = await context.newPage();
  const url = `${origin}${PREFIX}${rel}`;
  const probe = rel === PROBE;
  const here = [];
  page.on("console", (m) => {
    if (probe && m.location().url === url && /status of 404/.test(m.text())) return; // the probe's own 404
    if (m.type() === "error") here.push(`console error: ${m.text()} (${m.location().url.replace(origin, "")})`);
  });
  page.on("pageerror", (e) => here.push(`script error: ${e.message}`));
  page.on("request", (r) => {
    const u = new URL(r.url());
    if (u.protocol === "data:" || u.protocol === "blob:" || u.protocol === "about:") return;
    if (u.hostname !== "127.0.0.1") here.push(`request leaves 127.0.0.1: ${r.url().slice(0, 100)}`);
  });
  page.on("requestfailed", (r) => {
    if (new URL(r.url()).hostname === "127.0.0.1") here.push(`request failed: ${r.url().slice(origin.length)}`);
  });
  page.on("response", (r) => {
    if (probe && r.url() === url) return; // its 404 is the point; checked below
    if (r.status() >= 400) here.push(`HTTP ${r.status()}: ${r.url().slice(origin.length)}`);
  });
  const answer = await page.goto(url, { waitUntil: "load" });
  if (probe) {
    if (answer.status() !== 404) here.push(`a missing page answered ${answer.status()}, not 404`);
    const found = await page.evaluate(async () => {
      const styled = [...document.styleSheets]
        .some((s) => s.href && s.href.includes("css/general") && s.cssRules.length > 0);
      const link = [...document.querySelectorAll("a[href]")].find((a) => /ch01-[^/]*\.html$/.test(a.href));
      const status = link ? (await fetch(link.href)).status : 0;
      return { styled, title: document.querySelector("main h1")?.textContent ?? "", href: link?.href ?? "", status };
    });
    if (!found.styled) here.push("the 404 page has no styles (its <base> does not match where the site is served)");
    if (!/not found/i.test(found.title)) here.push(`the 404 page's heading is "${found.title}"`);
    if (found.status !== 200) here.push(`the 404 page's link to chapter 1 (${found.href || "none"}) answers ${found.status}`);
  }
  await page.waitForLoadState("networkidle").catch(() => {});
  const seen = await page.evaluate(() => {
    const main = document.querySelector("main") ?? document.body;
    const imgs = [...main.querySelectorAll("img")].map((i) => ({
      src: i.getAttribute("src"), url: i.currentSrc || i.src, ok: i.complete && i.naturalWidth > 0,
    }));
    const walker = document.createTreeWalker(main, NodeFilter.SHOW_TEXT, {
      acceptNode: (n) => n.parentElement.closest("code, pre, script, style, .katex, textarea")
        ? NodeFilter.FILTER_REJECT : NodeFilter.FILTER_ACCEPT,
    });
    let text = "";
    while (walker.nextNode()) text += walker.currentNode.data;
    return {
      imgs,
      text,
      katex: main.querySelectorAll(".katex").length,
      katexErrors: [...main.querySelectorAll(".katex-error")].map((e) => e.getAttribute("title")),
    };
  });
  for (const i of seen.imgs) {
    if (!i.ok) here.push(`image does not load: ${i.src}`);
    else figures.add(new URL(i.url).pathname);
  }
  const raw = seen.text.match(TEX) ?? [];
  if (raw.length) {
    const at = seen.text.search(TEX);
    here.push(`${raw.length} raw TeX fragments visible, e.g. "${seen.text.slice(Math.max(0, at - 30), at + 40).replace(/\s+/g, " ")}"`);
  }
  for (const e of seen.katexErrors) here.push(`KaTeX error: ${e}`);
  const base = rel.split("/").pop();
  if (/^ch\d\d-/.test(base) && seen.imgs.length === 0) here.push("a chapter without a figure");
  if (shots && (/^ch\d\d-/.test(base) || base === "introduction.html")) {
    await page.screenshot({ path: join(shots, base.replace(/\.html$/, ".png")), fullPage: true });
  }
  for (const p of here) problems.push(`${rel}: ${p}`);
  const distinct = new Set(seen.imgs.map((i) => i.src)).size; // mdBook draws each image twice (click to zoom)
  console.log(`${here.length ? "FAIL" : "ok  "} ${rel} (${distinct} figures, ${seen.katex} formulas)`);
  await page.close();
}
await browser.close();
server.close();
if (scratch) rmSync(scratch, { recursive: true, force: true });

if (figures.size < MIN_FIGURES && !opt("--only")) problems.push(`${figures.size} distinct figures in the book (want >= ${MIN_FIGURES})`);
if (problems.length) {
  console.log(problems.join("\n"));
  console.log(`book check: ${problems.length} problems over ${pages.length} pages`);
  process.exit(1);
}
console.log(`book check OK: ${pages.length} pages, ${figures.size} distinct figures, maths rendered, nothing fetched from outside 127.0.0.1`);
