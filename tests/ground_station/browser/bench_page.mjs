// cover-bench ground-station's browser side: the page in Debian's chromium (headless, as the
// browser test starts it), open on a running station, measured over BENCH_SECONDS:
//   - each fleet row's draws per second (window.__gs.row_updates, web/src/main.js);
//   - the latencies the page noted per pushed row drawn: from the sample's own wall-clock
//     stamp (latencies_ms) and from the station's receive time (server_latencies_ms);
//   - Chromium's CPU for the page: utime + stime (/proc/<pid>/stat) of the browser's renderer
//     and GPU processes over the window.
// Prints "measuring" when the window opens (the caller samples the server's CPU then), and one
// JSON line when it closes; exits 1 naming what failed.
//   GS_URL=http://127.0.0.1:PORT/?token=... BENCH_SECONDS=S CHROMIUM=/usr/bin/chromium
//   WEB_DIR=<source>/web WAIT_ROWS="uav-agent/0 uav-agent/1" node bench_page.mjs
import { mkdtempSync, readFileSync, readdirSync, rmSync } from "node:fs";
import { createRequire } from "node:module";
import { join } from "node:path";

const require = createRequire(join(process.env.WEB_DIR, "package.json"));
const { chromium } = require("playwright-core");
const scale = Math.max(1, Number(process.env.COVER_TEST_TIME_SCALE ?? "1") || 1);
const seconds = Number(process.env.BENCH_SECONDS ?? "30");
const waitRows = (process.env.WAIT_ROWS ?? "").split(" ").filter((k) => k);
const ticksPerSecond = 100; // USER_HZ: getconf CLK_TCK on Linux

// Chromium's singleton socket path must be short (108 bytes): its own folder under /tmp.
const chromiumTmp = mkdtempSync("/tmp/cover-gsb-");
process.on("exit", () => rmSync(chromiumTmp, { recursive: true, force: true }));

// pid -> { ppid, type, cpu_s } of every process now.
function processes() {
  const all = new Map();
  for (const name of readdirSync("/proc")) {
    if (!/^\d+$/.test(name)) continue;
    try {
      const stat = readFileSync(`/proc/${name}/stat`, "utf8");
      const fields = stat.slice(stat.lastIndexOf(")") + 2).split(" ");
      const cmdline = readFileSync(`/proc/${name}/cmdline`, "utf8");
      const type = /--type=([a-z-]+)/.exec(cmdline)?.[1] ?? "";
      all.set(Number(name), { ppid: Number(fields[1]), type, cpu_s: (Number(fields[11]) + Number(fields[12])) / ticksPerSecond });
    } catch {
      // gone meanwhile
    }
  }
  return all;
}

// CPU seconds of the renderer and GPU processes of the browser this script started (its
// descendants), by type.
function chromiumCpu(rootPid) {
  const all = processes();
  const descends = (pid) => {
    for (let p = pid, hops = 0; p > 1 && hops < 16; p = all.get(p)?.ppid ?? 0, hops++) if (p === rootPid) return true;
    return false;
  };
  const cpu = { renderer: 0, gpu: 0, renderers: 0, gpus: 0 };
  for (const [pid, p] of all) {
    if (pid === rootPid || !descends(pid)) continue;
    if (p.type === "renderer") { cpu.renderer += p.cpu_s; cpu.renderers++; }
    if (p.type === "gpu-process") { cpu.gpu += p.cpu_s; cpu.gpus++; }
  }
  return cpu;
}

// WebGL on SwiftShader as in the browser test. The page is composited in software, as Chromium
// does on a machine without a usable GPU, unless GPU_COMPOSITING=1: then SwiftShader composites
// it too, a GPU emulated on the CPU (several times the cost: docs/benchmarks.md).
const args = ["--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader"];
if (process.env.GPU_COMPOSITING !== "1") args.push("--disable-gpu-compositing");
const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM ?? "/usr/bin/chromium",
  headless: true,
  args,
  env: { ...process.env, TMPDIR: chromiumTmp },
});
let step = "open the page";
try {
  const page = await browser.newPage({ viewport: { width: 1400, height: 1000 } });
  await page.goto(process.env.GS_URL, { timeout: 120000 * scale });
  for (const key of waitRows) {
    step = `row ${key} on the page`;
    const [kind, id] = key.split("/");
    await page.waitForSelector(`#fleet tbody tr[data-kind="${kind}"][data-id="${id}"]:not(.stale)`, { timeout: 60000 * scale });
  }
  step = "warm-up";
  await page.waitForTimeout(2000); // the page's first draws and the JIT settle before the window
  const pid = process.pid;
  step = "measure";
  await page.evaluate(() => {
    const s = window.__gs;
    for (const list of [s.latencies_ms, s.server_latencies_ms, s.state_latencies_ms, s.arrival_latencies_ms]) list.length = 0;
    s.row_updates = {};
    s.states = 0;
    s.pushes = 0;
    s.urgent_frames = 0;
    s.lazy_frames = 0;
  });
  // The renderer's main thread by kind of work (Chrome DevTools Protocol, Performance domain):
  // where the page's own CPU goes.
  const cdp = await page.context().newCDPSession(page);
  await cdp.send("Performance.enable", { timeDomain: "threadTicks" });
  const metrics = async () => Object.fromEntries((await cdp.send("Performance.getMetrics")).metrics.map((m) => [m.name, m.value]));
  const main0 = await metrics();
  const cpu0 = chromiumCpu(pid);
  const t0 = performance.now();
  console.log("measuring");
  await page.waitForTimeout(seconds * 1000); // the measured window itself, not a synchronisation
  const stats = await page.evaluate(() => window.__gs);
  const cpu1 = chromiumCpu(pid);
  const main1 = await metrics();
  const mainThread = {};
  for (const k of ["ThreadTime", "TaskDuration", "ScriptDuration", "RecalcStyleDuration", "LayoutDuration", "RecalcStyleCount", "LayoutCount"])
    mainThread[k] = main1[k] - main0[k];
  const window_s = (performance.now() - t0) / 1000;
  console.log(JSON.stringify({
    window_s,
    renderer_cpu_s: cpu1.renderer - cpu0.renderer,
    gpu_cpu_s: cpu1.gpu - cpu0.gpu,
    main_thread: mainThread,
    renderers: cpu1.renderers,
    gpu_processes: cpu1.gpus,
    states: stats.states,
    pushes: stats.pushes,
    row_updates: stats.row_updates,
    latencies_ms: stats.latencies_ms,
    server_latencies_ms: stats.server_latencies_ms,
    state_latencies_ms: stats.state_latencies_ms,
    arrival_latencies_ms: stats.arrival_latencies_ms,
    urgent_frames: stats.urgent_frames,
    lazy_frames: stats.lazy_frames,
  }));
  await browser.close();
} catch (e) {
  console.log(`FAILED ${step}: ${e.message.split("\n")[0]}`);
  await browser.close();
  process.exit(1);
}
