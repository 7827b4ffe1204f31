// The ground station's page in Debian's chromium (headless, WebGL through SwiftShader) driven
// by playwright-core, against the running system browser_test.cpp started. Each step waits on
// a condition with a deadline scaled by COVER_TEST_TIME_SCALE; a screenshot of each state goes
// to SCREENSHOTS. Prints one line per step; exits 1 naming the step that failed.
//   GS_URL=http://127.0.0.1:PORT/?token=... SCREENSHOTS=DIR AGENT_PID=N CHROMIUM=/usr/bin/chromium
//   WEB_DIR=<source>/web node page_test.mjs
import { mkdtempSync, rmSync } from "node:fs";
import { createRequire } from "node:module";
import { join } from "node:path";

const require = createRequire(join(process.env.WEB_DIR, "package.json"));
const { chromium } = require("playwright-core");
const scale = Math.max(1, Number(process.env.COVER_TEST_TIME_SCALE ?? "1") || 1);
const s = (ms) => ms * scale;
const shots = process.env.SCREENSHOTS;

// Chromium's singleton socket path must be short (108 bytes): its own folder under /tmp,
// removed at the end, rather than the test's deep scratch folder.
const chromiumTmp = mkdtempSync("/tmp/cover-gs-");
process.on("exit", () => rmSync(chromiumTmp, { recursive: true, force: true }));
const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM ?? "/usr/bin/chromium",
  headless: true,
  args: ["--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader"],
  env: { ...process.env, TMPDIR: chromiumTmp },
});
let page;
let step = "start";
// A screenshot is the state's artifact, not what the step checks: one that a loaded machine
// cannot render in time is reported, and the step goes on.
async function shot(name) {
  try {
    await page.screenshot({ path: join(shots, `${name}.png`), fullPage: true, timeout: s(30000) });
  } catch (e) {
    console.log(`screenshot ${name} not taken: ${e.message.split("\n")[0]}`);
  }
}
function ok(what) {
  console.log(`ok ${what}`);
}

try {
  page = await browser.newPage({ viewport: { width: 1400, height: 1000 } });
  const errors = [];
  page.on("pageerror", (e) => errors.push(String(e)));

  step = "rows listed";
  await page.goto(process.env.GS_URL);
  for (const kind of ["sim", "uav-agent", "ugv-agent", "task-manager", "fc-bridge"]) {
    step = `rows listed: ${kind}`;
    await page.waitForSelector(`#fleet tbody tr[data-kind="${kind}"]:not(.stale)`, { timeout: s(30000) });
  }
  await page.waitForFunction(() => document.querySelectorAll('#fleet tr[data-kind="ugv-agent"]').length === 2, null, { timeout: s(10000) });
  step = "rows listed";
  await shot("fleet");
  ok(step);

  step = "3D canvas not blank";
  await page.waitForSelector('#fleet tr[data-kind="uav-agent"]');
  const drawn = await page.waitForFunction(() => {
    const c = document.querySelector("#view3d");
    const copy = document.createElement("canvas");
    copy.width = c.width; copy.height = c.height;
    const g = copy.getContext("2d");
    g.drawImage(c, 0, 0);
    const px = g.getImageData(0, 0, c.width, c.height).data;
    let lit = 0;
    const colors = new Set();
    for (let i = 0; i < px.length; i += 4) {
      if (Math.abs(px[i] - 13) + Math.abs(px[i + 1] - 17) + Math.abs(px[i + 2] - 23) > 30) lit++;
      colors.add((px[i] << 16) | (px[i + 1] << 8) | px[i + 2]);
    }
    const fraction = lit / (c.width * c.height);
    return fraction > 0.01 && colors.size > 8 ? { fraction, colors: colors.size } : false;
  }, null, { timeout: s(10000) });
  const d = await drawn.jsonValue();
  await page.locator("#view3d").screenshot({ path: join(shots, "view3d.png") });
  ok(`${step}: ${(100 * d.fraction).toFixed(1)} % of its pixels drawn, ${d.colors} colours`);

  step = "invalid task shows the reason beside the field";
  await page.fill('#task-form input[name="task_id"]', "page-invalid");
  await page.fill('#task-form input[name="vmax_m_s"]', "-1");
  await page.click("#submit-task");
  const reason = page.locator('#task-form .field-error[data-field="vmax_m_s"]');
  await reason.filter({ hasText: /vmax_m_s/ }).waitFor({ timeout: s(10000) });
  await shot("invalid-task");
  ok(`${step}: ${await reason.textContent()}`);

  // The task manager holds a task while its UAV's autopilot is disarmed (the operator arms
  // it): the task is queued first, then armed from the page, and it flies at once (the
  // autopilot disarms by itself 11 s after arming on the ground: in lockstep well under 1 s).
  const fc = page.locator('#fc .fc-uav[data-uav="0"]');
  async function fcCommand(cmd) {
    await fc.locator(`button[data-cmd="${cmd}"]`).click();
    await page.waitForSelector("#confirm:not([hidden])", { timeout: s(2000) });
    const question = await page.textContent("#confirm-text");
    if (!question.includes(cmd.toUpperCase())) throw new Error(`the confirmation does not name ${cmd}: ${question}`);
    await shot(`fc-${cmd}-confirm`);
    await page.click("#confirm-yes");
    const answer = fc.locator(".fc-answer");
    await answer.filter({ hasText: new RegExp(`^${cmd}: (accepted|refused|no answer)`) }).waitFor({ timeout: s(15000) });
    await shot(`fc-${cmd}`);
    return answer.textContent();
  }

  step = "task submitted from the page is held for the disarmed autopilot";
  await page.evaluate(() => {
    window.__progress = new Set();
    setInterval(() => {
      const row = document.querySelector('#tasks tr[data-task="page-task-1"]');
      if (row && /m to go/.test(row.textContent)) window.__progress.add(row.querySelector("td:nth-child(4)").textContent.split(",")[0]);
    }, 20);
  });
  await page.fill('#task-form input[name="task_id"]', "page-task-1");
  await page.fill('#task-form input[name="vmax_m_s"]', "1.0");
  await page.fill('#task-form input[name="final_point_m"]', "0, 0, 0.05");
  await page.selectOption('#task-form select[name="final_action"]', "land");
  await fc.waitFor({ timeout: s(10000) });
  await page.click("#submit-task");
  await page.locator("#task-answer").filter({ hasText: /^accepted/ }).waitFor({ timeout: s(15000) });
  await page.waitForSelector('#tasks tr[data-task="page-task-1"][data-state="queued"]', { timeout: s(10000) });
  await shot("task-queued");
  ok(`${step}: ${await page.textContent("#task-answer")}`);

  step = "arm through the simulated autopilot with confirmation; the task flies, progress and success appear";
  const armed = await fcCommand("arm");
  if (!/^arm: accepted/.test(armed)) throw new Error(`the autopilot did not arm: ${armed}`);
  // A lockstep flight lasts a few seconds: the manager's list (every 0.5 s) may not catch
  // it running; the UAV's live progress is watched above.
  await page.waitForSelector('#tasks tr[data-task="page-task-1"][data-state="succeeded"]', { timeout: s(120000) });
  const stages = await page.evaluate(() => [...window.__progress]);
  if (stages.length === 0) throw new Error("no progress (stage, distance to go) shown while it flew");
  await shot("task-succeeded");
  await shot("ground-station");
  ok(`${step}: ${armed}; stages seen ${stages.join(" ")}`);

  step = "abort asks for confirmation and the task ends aborted";
  await page.fill('#task-form input[name="task_id"]', "page-task-2");
  await page.fill('#task-form input[name="from_ugv"]', "1");
  await page.fill('#task-form input[name="to_ugv"]', "0");
  await page.click("#submit-task");
  await page.locator("#task-answer").filter({ hasText: /^accepted/ }).waitFor({ timeout: s(15000) });
  await page.click('#tasks button.abort[data-task="page-task-2"]', { timeout: s(10000) });
  await page.waitForSelector("#confirm:not([hidden])", { timeout: s(2000) });
  await shot("abort-confirm");
  await page.click("#confirm-yes");
  await page.waitForSelector('#tasks tr[data-task="page-task-2"][data-state="aborted"]', { timeout: s(60000) });
  await shot("task-aborted");
  ok(step);

  step = "land through the simulated autopilot with confirmation";
  const landed = await fcCommand("land");
  if (!/^land: (accepted|refused): \S/.test(landed)) throw new Error(`no answer of the autopilot: ${landed}`);
  ok(`${step}: ${landed}`);

  step = "a killed agent's row turns red within 1 s";
  const pid = Number(process.env.AGENT_PID);
  const killed = Date.now();
  process.kill(pid, "SIGKILL");
  await page.waitForSelector('#fleet tr.stale[data-kind="uav-agent"]', { timeout: s(1000) });
  const red_ms = Date.now() - killed;
  await shot("agent-killed");
  ok(`${step}: red ${red_ms} ms after the kill`);

  if (errors.length) throw new Error(`page errors: ${errors.join("; ")}`);
  await browser.close();
} catch (e) {
  console.log(`FAILED ${step}: ${e.message.split("\n")[0]}`);
  try {
    console.log(`fleet on the page: ${(await page.textContent("#fleet")).replace(/\s+/g, " ")}`);
  } catch (f) {
    console.log(`no page to read: ${f.message.split("\n")[0]}`);
  }
  await shot("failed");
  await browser.close();
  process.exit(1);
}
