// The browser check fed a deliberately broken page: it must report each kind of failure.
// usage: node book/check/selftest.mjs BUILT_DIR   (a built book; a copy of it is tampered with)
import { execFileSync } from "node:child_process";
import { cpSync, mkdtempSync, readFileSync, writeFileSync, rmSync } from "node:fs";
import { tmpdir } from "node:os";
import { join } from "node:path";

const built = process.argv[2];
const dir = mkdtempSync(join(tmpdir(), "rtl-book-selftest-"));
cpSync(built, dir, { recursive: true });
const page = join(dir, "ch02-a-simple-monte-carlo-program.html");
const broken = [
  '<img src="figures/no-such-figure.png" alt="missing">',
  '<img src="http://example.com/figure.png" alt="remote">',
  "<p>an unrendered formula: \\\\( \\\\frac{a}{b} \\\\) and $$x^{2}$$</p>",
  "<p>a formula KaTeX cannot parse: \\( \\frac{a}{ \\)</p>",
  '<script>console.error("deliberate console error")</script>',
].join("\n");
writeFileSync(page, readFileSync(page, "utf8").replace("</main>", broken + "\n</main>"));
let out = "";
let failed = false;
try {
  out = execFileSync("node", [new URL("check.mjs", import.meta.url).pathname, "--built", dir,
    "--only", "ch02-a-simple-monte-carlo-program.html"], { encoding: "utf8" });
} catch (e) {
  failed = true;
  out = e.stdout;
}
// A 404 page built for the root of a host (mdBook's default site-url) while the site is under /book/.
const notFound = join(dir, "404.html");
writeFileSync(notFound, readFileSync(notFound, "utf8").replace('<base href="/book/">', '<base href="/">'));
let probeOut = "";
try {
  probeOut = execFileSync("node", [new URL("check.mjs", import.meta.url).pathname, "--built", dir,
    "--only", "no-such-part/no-such-page.html"], { encoding: "utf8" });
} catch (e) {
  probeOut = e.stdout;
}
rmSync(dir, { recursive: true, force: true });
const want = [
  ["exit status", failed],
  ["missing image", /image does not load: figures\/no-such-figure\.png/.test(out)],
  ["request to another host", /request leaves 127\.0\.0\.1: http:\/\/example\.com/.test(out)],
  ["raw TeX", /raw TeX fragments visible/.test(out)],
  ["console error", /console error: deliberate console error/.test(out)],
  ["404 page with the wrong base", /the 404 page has no styles/.test(probeOut)],
];
const missed = want.filter(([, ok]) => !ok).map(([what]) => what);
if (missed.length) {
  console.log(out + probeOut);
  console.log(`selftest: the check did not report: ${missed.join(", ")}`);
  process.exit(1);
}
console.log("selftest OK: a broken page fails the check for each of its faults");
