// What every browser test of the ground station's page shares: Debian's chromium (headless,
// WebGL through SwiftShader) driven by playwright-core, deadlines scaled by
// COVER_TEST_TIME_SCALE, a screenshot per state in SCREENSHOTS, one line per step on stdout
// ("ok ..."), and on failure "FAILED <step>: <why>", the fleet as the page showed it, a
// "failed" screenshot and exit 1. The browser is closed on every way out: the end, a failure,
// SIGTERM/SIGINT from the test (playwright's own handlers), and chromium dies with this
// process even when it is killed (setpriv --pdeathsig).
//   GS_URL=http://127.0.0.1:PORT/?token=... SCREENSHOTS=DIR CHROMIUM=/usr/bin/chromium
//   WEB_DIR=<source>/web node <test>.mjs
import { chmodSync, mkdtempSync, rmSync, writeFileSync } from "node:fs";
import { createRequire } from "node:module";
import { join } from "node:path";

const require = createRequire(join(process.env.WEB_DIR, "package.json"));
const { chromium } = require("playwright-core");
export const scale = Math.max(1, Number(process.env.COVER_TEST_TIME_SCALE ?? "1") || 1);
export const s = (ms) => ms * scale;
const shots = process.env.SCREENSHOTS;

// Chromium's singleton socket path must be short (108 bytes): its own folder under /tmp,
// removed at the end, rather than the test's deep scratch folder.
const chromiumTmp = mkdtempSync("/tmp/cover-gs-");
process.on("exit", () => rmSync(chromiumTmp, { recursive: true, force: true }));

// Chromium started through setpriv: SIGKILL reaches it when this process ends, however it
// ends (a test that gives up kills this process; playwright's clean-up never runs then).
function chromiumDyingWithUs() {
  const wrapper = join(chromiumTmp, "chromium");
  const executable = process.env.CHROMIUM ?? "/usr/bin/chromium";
  writeFileSync(wrapper, `#!/bin/sh\nexec setpriv --pdeathsig KILL -- ${executable} "$@"\n`);
  chmodSync(wrapper, 0o755);
  return wrapper;
}

function ok(what) {
  console.log(`ok ${what}`);
}

// Runs `body({ page, shot, ok, step })` in a fresh page; `step(name)` names what a failure
// would be reported as.
export async function run(body) {
  const browser = await chromium.launch({
    executablePath: chromiumDyingWithUs(),
    headless: true,
    args: ["--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader"],
    env: { ...process.env, TMPDIR: chromiumTmp },
    timeout: s(60000),
  });
  let page;
  let current = "start";
  // A screenshot is the state's artifact, not what the step checks: one that a loaded
  // machine cannot render in time is reported, and the step goes on.
  async function shot(name, locator) {
    try {
      const options = { path: join(shots, `${name}.png`), timeout: s(30000) };
      await (locator ? locator.screenshot(options) : page.screenshot({ ...options, fullPage: true }));
    } catch (e) {
      console.log(`screenshot ${name} not taken: ${e.message.split("\n")[0]}`);
    }
  }
  try {
    page = await browser.newPage({ viewport: { width: 1400, height: 1000 } });
    page.setDefaultTimeout(s(30000));
    const errors = [];
    page.on("pageerror", (e) => errors.push(String(e)));
    await body({ page, shot, ok, step: (name) => { current = name; } });
    if (errors.length) throw new Error(`page errors: ${errors.join("; ")}`);
    await browser.close();
  } catch (e) {
    console.log(`FAILED ${current}: ${e.message.split("\n")[0]}`);
    try {
      console.log(`fleet on the page: ${(await page.textContent("#fleet", { timeout: s(5000) })).replace(/\s+/g, " ")}`);
    } catch (f) {
      console.log(`no page to read: ${f.message.split("\n")[0]}`);
    }
    if (page) await shot("failed");
    await browser.close().catch(() => {});
    process.exit(1);
  }
}

// Evaluates `fn(arg)` in the page every 100 ms until it returns a truthy value (returned),
// or throws after `timeoutMs` naming `what`. Not page.waitForFunction: its polling evaluates
// a string in the page, which the page's Content-Security-Policy (no eval) refuses.
export async function until(page, fn, arg, timeoutMs, what) {
  const deadline = Date.now() + timeoutMs;
  for (;;) {
    const value = await page.evaluate(fn, arg);
    if (value) return value;
    if (Date.now() > deadline) throw new Error(`not within ${timeoutMs} ms: ${what}`);
    await page.waitForTimeout(100);
  }
}

// The rows of a running system, each not stale (the page is connected and hears them).
export async function waitForRows(page, kinds, ugvs = 2) {
  for (const kind of kinds) {
    await page.waitForSelector(`#fleet tbody tr[data-kind="${kind}"]:not(.stale)`, { timeout: s(60000) });
  }
  await until(page, (n) => document.querySelectorAll('#fleet tr[data-kind="ugv-agent"]').length === n,
    ugvs, s(30000), `${ugvs} UGV agents' rows`);
}

// The 3D canvas's pixels, read in the page: the fraction not background and the number of
// colours; kept in the page under `name` (if given) for pixelDifference.
export function canvasPixels(page, name = "") {
  return page.evaluate((name) => {
    const c = document.querySelector("#view3d");
    const copy = document.createElement("canvas");
    copy.width = c.width; copy.height = c.height;
    const g = copy.getContext("2d");
    g.drawImage(c, 0, 0);
    const px = g.getImageData(0, 0, c.width, c.height).data;
    if (name) (window.__snapshots ??= {})[name] = px;
    let lit = 0;
    const colors = new Set();
    // The shown frame's deck is drawn light green (scene.js kFrameDeckColor), the others dark.
    const deck = { pixels: 0, x: 0, y: 0 };
    for (let i = 0; i < px.length; i += 4) {
      if (Math.abs(px[i] - 13) + Math.abs(px[i + 1] - 17) + Math.abs(px[i + 2] - 23) > 30) lit++;
      colors.add((px[i] << 16) | (px[i + 1] << 8) | px[i + 2]);
      if (px[i + 1] > 100 && px[i + 1] > px[i] + 30 && px[i + 1] > px[i + 2] + 30) {
        deck.pixels++;
        deck.x += (i / 4) % c.width;
        deck.y += Math.floor(i / 4 / c.width);
      }
    }
    const n = c.width * c.height;
    return { fraction: lit / n, colors: colors.size, frameDeck: deck.pixels / n,
             frameDeckAt: deck.pixels ? [deck.x / deck.pixels / c.width, deck.y / deck.pixels / c.height] : null };
  }, name);
}

// The fraction of pixels that differ (by more than 48 over the three channels) between two
// pictures kept by canvasPixels.
export function pixelDifference(page, a, b) {
  return page.evaluate(([a, b]) => {
    const p = window.__snapshots[a];
    const q = window.__snapshots[b];
    let changed = 0;
    for (let i = 0; i < p.length; i += 4) {
      if (Math.abs(p[i] - q[i]) + Math.abs(p[i + 1] - q[i + 1]) + Math.abs(p[i + 2] - q[i + 2]) > 48) changed++;
    }
    return changed / (p.length / 4);
  }, [a, b]);
}

// Waits until the canvas is drawn: more than 1 % of its pixels off the background, > 8 colours.
export async function waitForDrawnCanvas(page, timeoutMs, name = "") {
  const deadline = Date.now() + timeoutMs;
  for (;;) {
    const p = await canvasPixels(page, name);
    if (p.fraction > 0.01 && p.colors > 8) return p;
    if (Date.now() > deadline) throw new Error(`canvas blank: ${(100 * p.fraction).toFixed(2)} % drawn, ${p.colors} colours`);
    await page.waitForTimeout(200);
  }
}
