// The lab in a real browser: headless Chromium (Debian's /usr/bin/chromium) driven by playwright-core.
// usage: node lab.test.cjs URL SCREENSHOT_DIR
// Checks: the page loads with no console error and no request outside 127.0.0.1; a Monte Carlo run
// draws its band; a sampling run draws its histogram; switching the Cornell box from `uniform` to `mis`
// changes the image and adds a curve, and `mixture` at weight 0.2 adds a curve named by its weight.
// Writes one screenshot of each bench.
"use strict";
const { chromium } = require("playwright-core");
const path = require("path");

const [url, shots] = process.argv.slice(2);
if (!url || !shots) {
  console.error("usage: node lab.test.cjs URL SCREENSHOT_DIR");
  process.exit(2);
}
const failures = [];
const check = (ok, what) => {
  console.log(`${ok ? "ok  " : "FAIL"} ${what}`);
  if (!ok) failures.push(what);
};

(async () => {
  const browser = await chromium.launch({
    executablePath: "/usr/bin/chromium",
    headless: true,
    args: ["--no-sandbox", "--disable-gpu", "--disable-background-networking", "--no-first-run"],
  });
  const page = await browser.newPage({ viewport: { width: 1280, height: 1000 } });
  page.setDefaultTimeout(60_000);
  const errors = [];
  const outside = [];
  page.on("console", (m) => { if (m.type() === "error") errors.push(m.text()); });
  page.on("pageerror", (e) => errors.push(String(e)));
  page.on("request", (r) => {
    const u = new URL(r.url());
    if (!(u.protocol === "data:" || u.protocol === "blob:" || u.hostname === "127.0.0.1")) outside.push(r.url());
  });

  await page.goto(url);
  await page.waitForFunction(() => window.labReady === true);
  check(!(await page.$("#fatal")), "the page's script reached the server");

  // Monte Carlo: x^2 over [0, 2], uniform, N = 2^4 .. 2^12: a band of 9 points.
  await page.selectOption("#mc-integral", "x_sq");
  await page.selectOption("#mc-estimator", "uniform");
  await page.fill("#mc-max", "12");
  await page.click("#mc-run");
  await page.waitForFunction(() => {
    const b = document.querySelector("#mc-trace .band");
    return b && Number(b.dataset.points) >= 9 && !document.querySelector("#mc-run").disabled;
  });
  const mc = await page.evaluate(() => ({
    band: document.querySelector("#mc-trace .band").getAttribute("d").length,
    curves: document.querySelectorAll("#mc-vs-n .curve").length,
  }));
  check(mc.band > 50 && mc.curves === 1, `a Monte Carlo run draws its band and its RMSE curve (${JSON.stringify(mc)})`);
  // a second estimator adds a curve beside the first
  await page.selectOption("#mc-estimator", "jittered");
  await page.click("#mc-run");
  await page.waitForFunction(() => document.querySelectorAll("#mc-vs-n .curve").length === 2
    && !document.querySelector("#mc-run").disabled);
  await page.screenshot({ path: path.join(shots, "lab-mc.png"), fullPage: true });

  // Sampling: the book's density by a guide table of 32 bins, histogram of 80 bins.
  await page.click("nav button[data-bench=sampling]");
  await page.selectOption("#s-density", "book_sin2");
  await page.selectOption("#s-method", "guide_table");
  await page.fill("#s-n", "32");
  await page.fill("#s-bins", "80");
  await page.click("#s-run");
  await page.waitForFunction(() => document.querySelectorAll("#s-hist .bar").length === 80);
  const bars = await page.evaluate(() => [...document.querySelectorAll("#s-hist .bar")]
    .filter((b) => Number(b.getAttribute("height")) > 1).length);
  check(bars > 60, `a sampling run draws its histogram (${bars} of 80 bars visible)`);
  check(await page.$("#s-hist .density") !== null, "the density is drawn over the histogram");
  await page.selectOption("#d-pdf", "cosine");
  await page.click("#d-run");
  await page.waitForFunction(() => document.querySelectorAll("#d-observed rect").length > 400);
  const p = await page.textContent("#d-numbers");
  check(/p-value/.test(p), "a run on the sphere reports its chi-square p-value");
  await page.screenshot({ path: path.join(shots, "lab-sampling.png"), fullPage: true });

  // The Cornell box: uniform, then mis.
  await page.click("nav button[data-bench=cornell]");
  const frameOf = (gen, minSpp) => page.waitForFunction(([g, s]) => {
    const c = document.querySelector("#c-image");
    const st = document.querySelector("#c-status").textContent;
    const spp = Number((st.match(/: (\d+) spp/) || [0, 0])[1]);
    return Number(c.dataset.generation) >= g && spp >= s;
  }, [gen, minSpp]);
  // The generation the server answered to the page's last change of settings.
  const generationAfter = async (previous) => {
    await page.waitForFunction((p) => Number(document.body.dataset.renderGeneration || 0) > p, previous);
    return page.evaluate(() => Number(document.body.dataset.renderGeneration));
  };
  const pixels = () => page.evaluate(() => {
    const c = document.querySelector("#c-image");
    return Array.from(c.getContext("2d").getImageData(0, 0, c.width, c.height).data);
  });
  const curves = () => page.evaluate(() => document.querySelectorAll("#c-curves .curve").length);

  await page.selectOption("#c-strategy", "uniform");
  const g1 = await generationAfter(0);
  // A frame of uniform: the render the page opened on (mis) is over and adds nothing more. Its
  // curve, if it drew one, would be replaced by the mis curve below rather than joined: clear it.
  await frameOf(g1, 1);
  await Promise.all([
    page.waitForResponse((r) => r.url().includes("/api/render/clear")),
    page.click("#c-clear"),
  ]);
  await frameOf(g1, 4);
  await page.waitForFunction(() => {
    const cs = [...document.querySelectorAll("#c-curves .curve")];
    return cs.length === 1 && (cs[0].dataset.label || "").startsWith("uniform");
  });
  const uniform = await pixels();
  const before = await curves();
  await page.selectOption("#c-strategy", "mis");
  const g2 = await generationAfter(g1);
  check(g2 > g1, `switching the strategy restarts the render (generation ${g1} -> ${g2})`);
  await frameOf(g2, 4);
  await page.waitForFunction((n) => document.querySelectorAll("#c-curves .curve").length > n, before);
  const mis = await pixels();
  let diff = 0;
  for (let i = 0; i < mis.length; i++) diff += Math.abs(mis[i] - uniform[i]);
  diff /= mis.length;
  check(uniform.length === mis.length && diff > 1, `uniform -> mis changes the image (mean |difference| ${diff.toFixed(2)} of 255)`);
  check((await curves()) === before + 1, `uniform -> mis adds a curve (${before} -> ${await curves()})`);
  // let the curves grow a little for the screenshot
  await page.waitForTimeout(4000);
  await page.screenshot({ path: path.join(shots, "lab-cornell.png"), fullPage: true });

  // The mixture weight: `mixture` at 0.2 restarts the render and adds a curve named by its weight.
  await page.selectOption("#c-strategy", "mixture");
  const g3 = await generationAfter(g2);
  await page.fill("#c-weight", "0.2");
  await page.dispatchEvent("#c-weight", "change");
  const g4 = await generationAfter(g3);
  await frameOf(g4, 4);
  const named = await page.waitForFunction(
    () => [...document.querySelectorAll("#c-curves .curve")].some((c) => (c.dataset.label || "").startsWith("mixture w=0.2 ")),
    null, { timeout: 30000 }).then(() => true, () => false);
  check(named, "mixture at weight 0.2 adds a curve labelled with its weight");

  check(errors.length === 0, `no console error${errors.length ? ": " + errors.join(" | ") : ""}`);
  check(outside.length === 0, `no request outside 127.0.0.1${outside.length ? ": " + outside.join(" ") : ""}`);
  await browser.close();
  if (failures.length) {
    console.error(`${failures.length} check(s) failed`);
    process.exit(1);
  }
  console.log("browser test: all checks hold");
})().catch((e) => {
  console.error(e);
  process.exit(1);
});
