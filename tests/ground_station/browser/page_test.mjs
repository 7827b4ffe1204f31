// The operator's flight from the page, against the running system browser_test.cpp started
// (simulated PX4, both UGV agents, bridge, UAV agent, task manager, station): the rows, the
// 3D canvas, an invalid task, a task armed and flown, an abort, a land, a killed agent.
// Each step waits on a condition with a deadline scaled by COVER_TEST_TIME_SCALE (harness.mjs).
//   GS_URL=... SCREENSHOTS=DIR AGENT_PID=N CHROMIUM=... WEB_DIR=<source>/web node page_test.mjs
import { run, s, waitForRows, waitForDrawnCanvas } from "./harness.mjs";

await run(async ({ page, shot, ok, step }) => {
  let now;
  step((now = "rows listed"));
  await page.goto(process.env.GS_URL, { timeout: s(30000) });
  await waitForRows(page, ["sim", "uav-agent", "ugv-agent", "task-manager", "fc-bridge"]);
  await shot("fleet");
  ok(now);

  step((now = "3D canvas not blank"));
  const d = await waitForDrawnCanvas(page, s(30000));
  await shot("view3d", page.locator("#view3d"));
  ok(`${now}: ${(100 * d.fraction).toFixed(1)} % of its pixels drawn, ${d.colors} colours`);

  step((now = "invalid task shows the reason beside the field"));
  await page.fill('#task-form input[name="task_id"]', "page-invalid");
  await page.fill('#task-form input[name="vmax_m_s"]', "-1");
  await page.click("#submit-task");
  const reason = page.locator('#task-form .field-error[data-field="vmax_m_s"]');
  await reason.filter({ hasText: /vmax_m_s/ }).waitFor({ timeout: s(30000) });
  await shot("invalid-task");
  ok(`${now}: ${await reason.textContent()}`);

  // The task manager holds a task while its UAV's autopilot is disarmed (the operator arms
  // it): the task is queued first, then armed from the page, and it flies at once (the
  // autopilot disarms by itself 11 s after arming on the ground: in lockstep well under 1 s).
  const fc = page.locator('#fc .fc-uav[data-uav="0"]');
  async function fcCommand(cmd) {
    await fc.locator(`button[data-cmd="${cmd}"]`).click();
    await page.waitForSelector("#confirm:not([hidden])", { timeout: s(10000) });
    const question = await page.textContent("#confirm-text");
    if (!question.includes(cmd.toUpperCase())) throw new Error(`the confirmation does not name ${cmd}: ${question}`);
    await shot(`fc-${cmd}-confirm`);
    await page.click("#confirm-yes");
    const answer = fc.locator(".fc-answer");
    await answer.filter({ hasText: new RegExp(`^${cmd}: (accepted|refused|no answer)`) }).waitFor({ timeout: s(30000) });
    await shot(`fc-${cmd}`);
    return answer.textContent();
  }

  step((now = "task submitted from the page is held for the disarmed autopilot"));
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
  await fc.waitFor({ timeout: s(30000) });
  await page.click("#submit-task");
  await page.locator("#task-answer").filter({ hasText: /^accepted/ }).waitFor({ timeout: s(30000) });
  await page.waitForSelector('#tasks tr[data-task="page-task-1"][data-state="queued"]', { timeout: s(30000) });
  await shot("task-queued");
  ok(`${now}: ${await page.textContent("#task-answer")}`);

  step((now = "arm through the simulated autopilot with confirmation; the task flies, progress and success appear"));
  const armed = await fcCommand("arm");
  if (!/^arm: accepted/.test(armed)) throw new Error(`the autopilot did not arm: ${armed}`);
  // A lockstep flight lasts a few seconds: the manager's list (every 0.5 s) may not catch
  // it running; the UAV's live progress is watched above.
  await page.waitForSelector('#tasks tr[data-task="page-task-1"][data-state="succeeded"]', { timeout: s(180000) });
  const stages = await page.evaluate(() => [...window.__progress]);
  if (stages.length === 0) throw new Error("no progress (stage, distance to go) shown while it flew");
  await shot("task-succeeded");
  await shot("ground-station");
  ok(`${now}: ${armed}; stages seen ${stages.join(" ")}`);

  step((now = "abort asks for confirmation and the task ends aborted"));
  await page.fill('#task-form input[name="task_id"]', "page-task-2");
  await page.fill('#task-form input[name="from_ugv"]', "1");
  await page.fill('#task-form input[name="to_ugv"]', "0");
  await page.click("#submit-task");
  await page.locator("#task-answer").filter({ hasText: /^accepted/ }).waitFor({ timeout: s(30000) });
  await page.click('#tasks button.abort[data-task="page-task-2"]', { timeout: s(30000) });
  await page.waitForSelector("#confirm:not([hidden])", { timeout: s(10000) });
  await shot("abort-confirm");
  await page.click("#confirm-yes");
  await page.waitForSelector('#tasks tr[data-task="page-task-2"][data-state="aborted"]', { timeout: s(90000) });
  await shot("task-aborted");
  ok(now);

  step((now = "land through the simulated autopilot with confirmation"));
  const landed = await fcCommand("land");
  if (!/^land: (accepted|refused): \S/.test(landed)) throw new Error(`no answer of the autopilot: ${landed}`);
  ok(`${now}: ${landed}`);

  // The one deadline that is the requirement itself (1 s), scaled only by the declared
  // COVER_TEST_TIME_SCALE of a slow machine.
  step((now = "a killed agent's row turns red within 1 s"));
  const pid = Number(process.env.AGENT_PID);
  const killed = Date.now();
  process.kill(pid, "SIGKILL");
  await page.waitForSelector('#fleet tr.stale[data-kind="uav-agent"]', { timeout: s(10000) });
  const redMs = Date.now() - killed;
  if (redMs > s(1000)) throw new Error(`red ${redMs} ms after the kill: later than ${s(1000)} ms`);
  await shot("agent-killed");
  ok(`${now}: red ${redMs} ms after the kill`);
});
