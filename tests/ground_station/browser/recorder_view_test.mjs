// The recorder and the 3D view's frames from the page, against the running system
// browser_test.cpp started (the simulator's standing world in real time, both UGV agents,
// the UAV agent, the station reading the simulator's world): start a recording, see its file and its size
// grow, stop it (the test then reads the file as MCAP); the world frame and each UGV's
// frame drawn, switching frames changes the picture. Prints "recording <file>" for the test.
//   GS_URL=... SCREENSHOTS=DIR CHROMIUM=... WEB_DIR=<source>/web node recorder_view_test.mjs
import { canvasPixels, pixelDifference, run, s, until, waitForDrawnCanvas, waitForRows } from "./harness.mjs";

// Chooses `frame` on the page and waits until two pictures of it were drawn since.
async function showFrame(page, frame) {
  const before = await page.evaluate(() => window.__gs.view?.draws ?? 0);
  await page.selectOption("#frame", frame);
  await until(page, ([f, n]) => window.__gs.view?.frame === f && window.__gs.view.draws >= n + 2,
    [frame, before], s(30000), `two pictures drawn in ${frame}`);
}

await run(async ({ page, shot, ok, step }) => {
  let now;
  step((now = "rows listed"));
  await page.goto(process.env.GS_URL, { timeout: s(30000) });
  await waitForRows(page, ["sim", "ugv-agent", "uav-agent"]);
  ok(now);

  step((now = "recording started from the page, its file shown and its size growing"));
  const status = page.locator("#rec-status");
  await page.click("#rec-start");
  await page.waitForSelector('#rec-status[data-running="true"]', { timeout: s(30000) });
  const file = await status.getAttribute("data-file");
  if (!file.endsWith(".mcap")) throw new Error(`no recording file shown: ${await status.textContent()}`);
  const sizes = [];
  await until(page, () => {
    const el = document.querySelector("#rec-status");
    const bytes = Number(el.dataset.bytes);
    window.__recSizes = [...new Set([...(window.__recSizes ?? []), bytes])].filter((b) => b > 0);
    return el.textContent.includes(el.dataset.file) && window.__recSizes.length >= 3;
  }, null, s(60000), "the recording's size growing (3 sizes)");
  sizes.push(...(await page.evaluate(() => window.__recSizes)));
  await shot("recording");
  ok(`${now}: ${file}, sizes seen ${sizes.join(" ")} bytes`);

  step((now = "recording stopped from the page"));
  await page.click("#rec-stop");
  await page.waitForSelector('#rec-status[data-running="false"]', { timeout: s(30000) });
  await page.locator("#rec-status").filter({ hasText: /^stopped: / }).waitFor({ timeout: s(30000) });
  await shot("recording-stopped");
  console.log(`recording ${file}`);
  ok(`${now}: ${await status.textContent()}`);

  // Each frame by what defines it: the shown frame's deck is the light one, at the origin
  // the camera looks at (the middle of the canvas); the world frame has none. The vehicles
  // move all the time, so "pixels differ" alone would hold without a switch.
  step((now = "the world frame offered and drawn"));
  await page.waitForSelector('#frame option[value="world"]', { state: "attached", timeout: s(30000) });
  await showFrame(page, "world");
  const world = await waitForDrawnCanvas(page, s(30000), "world");
  await shot("view3d-world", page.locator("#view3d"));
  if (world.frameDeck > 0.0005) throw new Error(`a frame's deck in the world frame: ${(100 * world.frameDeck).toFixed(2)} %`);
  ok(`${now}: ${(100 * world.fraction).toFixed(1)} % of its pixels drawn, ${world.colors} colours, no frame deck`);

  step((now = "switching to UGV 1's frame changes the picture: its deck lit, in the middle"));
  await showFrame(page, "ugv:1");
  const ugv = await waitForDrawnCanvas(page, s(30000), "ugv");
  const diff = await pixelDifference(page, "world", "ugv");
  const at = ugv.frameDeckAt;
  if (ugv.frameDeck < 0.001 || !at || Math.abs(at[0] - 0.5) > 0.2 || Math.abs(at[1] - 0.5) > 0.25) {
    throw new Error(`UGV 1's deck not lit in the middle: ${(100 * ugv.frameDeck).toFixed(2)} % at ${JSON.stringify(at)}`);
  }
  await shot("view3d-ugv1", page.locator("#view3d"));
  ok(`${now}: ${(100 * diff).toFixed(1)} % of its pixels changed, the deck ${(100 * ugv.frameDeck).toFixed(2)} % of the canvas at ` +
     `(${at[0].toFixed(2)}, ${at[1].toFixed(2)})`);

  step((now = "back to the world frame"));
  await showFrame(page, "world");
  const back = await waitForDrawnCanvas(page, s(30000));
  if (back.frameDeck > 0.0005) throw new Error(`UGV 1's deck still lit: ${(100 * back.frameDeck).toFixed(2)} %`);
  ok(`${now}: ${(100 * back.fraction).toFixed(1)} % drawn`);
});
