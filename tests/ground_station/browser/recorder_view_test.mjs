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

  step((now = "the world frame offered and drawn"));
  await page.waitForSelector('#frame option[value="world"]', { state: "attached", timeout: s(30000) });
  await showFrame(page, "world");
  const world = await waitForDrawnCanvas(page, s(30000), "world");
  await shot("view3d-world", page.locator("#view3d"));
  // What the world's own motion changes between two pictures of one frame: the frame switch
  // must change much more than that.
  await page.waitForTimeout(600);
  await canvasPixels(page, "world-later");
  const motion = await pixelDifference(page, "world", "world-later");
  ok(`${now}: ${(100 * world.fraction).toFixed(1)} % of its pixels drawn, ${world.colors} colours, ` +
     `motion alone changes ${(100 * motion).toFixed(1)} % of its pixels`);

  step((now = "switching to UGV 1's frame changes the picture"));
  await showFrame(page, "ugv:1");
  const deadline = Date.now() + s(30000);
  let ugv;
  let diff = 0;
  // The new frame is drawn within a draw period (0.2 s) of the choice.
  for (;;) {
    ugv = await canvasPixels(page, "ugv");
    diff = await pixelDifference(page, "world", "ugv");
    if (diff > Math.max(0.02, 3 * motion) && ugv.fraction > 0.01) break;
    if (Date.now() > deadline) throw new Error(`the picture did not change: ${(100 * diff).toFixed(1)} % of its pixels`);
    await page.waitForTimeout(200);
  }
  await shot("view3d-ugv1", page.locator("#view3d"));
  ok(`${now}: ${(100 * diff).toFixed(1)} % of its pixels changed, ${(100 * ugv.fraction).toFixed(1)} % drawn`);

  step((now = "back to the world frame"));
  await showFrame(page, "world");
  const back = await waitForDrawnCanvas(page, s(30000));
  ok(`${now}: ${(100 * back.fraction).toFixed(1)} % drawn`);
});
