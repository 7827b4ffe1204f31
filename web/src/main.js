// cover-ground-station's page: one WebSocket to the station (its API: ground_station/core
// api.hpp), state rows at the station's rate, requests answered one by one.
import uPlot from "uplot";
import { createScene } from "./scene.js";

const $ = (s) => document.querySelector(s);
const token = new URLSearchParams(location.search).get("token") ?? "";
// Read by the browser tests and cover-bench ground-station: state_latencies_ms from a state's
// sent_ms; per pushed row drawn, latencies_ms from the sample's own wall-clock stamp and
// server_latencies_ms from the station's receive time; arrival_latencies_ms from the sample's
// stamp to the message's arrival (before drawing); row_updates: times each fleet row was drawn
// ("uav-agent/0": n).
const stats = { states: 0, pushes: 0, state_latencies_ms: [], latencies_ms: [], server_latencies_ms: [],
  arrival_latencies_ms: [], fleet_updates: 0, row_updates: {}, first_state_ms: 0,
  urgent_frames: 0, lazy_frames: 0 };
window.__gs = stats;
const kMaxLatencies = 5000;
function note(list, value) {
  list.push(value);
  if (list.length > kMaxLatencies) list.shift();
}

let ws;
let nextId = 1;
const pending = new Map();
let lastState = null;

function connect() {
  const q = token ? `?token=${encodeURIComponent(token)}` : "";
  ws = new WebSocket(`ws://${location.host}/ws${q}`);
  ws.onopen = () => { $("#conn").textContent = "connected"; $("#conn").className = "ok"; };
  ws.onclose = () => {
    $("#conn").textContent = "disconnected: reconnecting"; $("#conn").className = "bad";
    setTimeout(connect, 1000);
  };
  ws.onmessage = (e) => {
    const m = JSON.parse(e.data);
    if (m.type === "state") onState(m);
    else if (m.type === "rows") onRows(m.rows);
    else if (m.type === "reply" && pending.has(m.id)) { pending.get(m.id)(m); pending.delete(m.id); }
  };
  $("#rights").textContent = token ? "commands allowed (token)" : "read only: open the address with its token to command";
}

function request(body) {
  const id = `r${nextId++}`;
  return new Promise((resolve) => {
    pending.set(id, resolve);
    ws.send(JSON.stringify({ ...body, id }));
  });
}

// Two steps: the action names itself, the operator confirms, then the answer shows.
function confirmThen(text) {
  return new Promise((resolve) => {
    $("#confirm-text").textContent = text;
    $("#confirm").hidden = false;
    const done = (yes) => { $("#confirm").hidden = true; resolve(yes); };
    $("#confirm-yes").onclick = () => done(true);
    $("#confirm-no").onclick = () => done(false);
  });
}

const short = (s) => (typeof s === "string" ? s.replace(/^[A-Z]+_(?:[A-Z]+_)?/, "").toLowerCase() : s);

function onState(m) {
  stats.states++;
  note(stats.state_latencies_ms, Date.now() - m.sent_ms);
  if (!stats.first_state_ms) stats.first_state_ms = Date.now();
  lastState = m;
  takePlotSamples(m.live);
  const urgent = renderFleet(m.fleet);
  requestFrame(urgent);
}

// Frames. Each frame the page draws costs Chromium ~2.5 ms of CPU on a small machine
// whatever changed (cover-bench ground-station: a one-character change 28 times a second
// took 9.6 % of a core), so the page draws what changed in as few frames as it can:
//  - at the next animation frame, what the operator must see at once: a row whose text
//    changed (state, failsafe, task, autopilot), a row turning stale or fresh, a row
//    appearing;
//  - within kLazyFrameMs of the last frame, what only moves: ages, clock offsets, task
//    progress, plots, the 3D view, the autopilots' and recorder's lines.
// Both kinds go in the same frame when they meet.
const kLazyFrameMs = 150;
let frameRequested = false;
let lazyTimer = 0;
let lastFrameMs = -Infinity;

function requestFrame(urgent) {
  if (frameRequested) return;
  if (urgent) {
    clearTimeout(lazyTimer);
    lazyTimer = 0;
    frameRequested = true;
    stats.urgent_frames++;
    requestAnimationFrame(drawFrame);
    return;
  }
  if (lazyTimer) return;
  const wait = Math.max(0, lastFrameMs + kLazyFrameMs - performance.now());
  lazyTimer = setTimeout(() => {
    lazyTimer = 0;
    if (!frameRequested) {
      frameRequested = true;
      stats.lazy_frames++;
      requestAnimationFrame(drawFrame);
    }
  }, wait);
}

let drawnState = null;
function drawFrame() {
  frameRequested = false;
  clearTimeout(lazyTimer);
  lazyTimer = 0;
  lastFrameMs = performance.now();
  const m = lastState;
  if (m && m !== drawnState) {
    drawnState = m;
    renderTasks(m.tasks, m.fleet, m.manager);
    renderFc(m.fleet);
    renderRecorder(m.recorder);
    drawPlots();
    view.update(m.live, m.fleet, m.world);
  }
  drawFleet();
}

// The fleet table: one element per row ("kind/id"), its cells written only when their text
// changed. A state lists every row (their order, ages, staleness); a pushed row is one whose
// status just arrived.
const fleetRows = new Map(); // key -> <tr>, its drawn texts in tr.texts
const dirtyRows = new Map(); // key -> { row, urgent, at_ms }, drawn at the next frame
let fleetOrder = "";
const rowKey = (r) => `${r.kind}/${r.id ?? ""}`;

// Whether the state changed what must be seen at once.
function renderFleet(rows) {
  const order = rows.map(rowKey).join(" ");
  let urgent = false;
  if (order !== fleetOrder) {
    fleetOrder = order;
    const keys = new Set(rows.map(rowKey));
    for (const [key, tr] of fleetRows) if (!keys.has(key)) { tr.remove(); fleetRows.delete(key); }
    const body = $("#fleet tbody");
    for (const r of rows) body.appendChild(fleetRow(r));
    urgent = true;
  }
  stats.fleet_updates++;
  return queueRows(rows, true) || urgent;
}

function fleetRow(r) {
  const key = rowKey(r);
  let tr = fleetRows.get(key);
  if (!tr) {
    tr = document.createElement("tr");
    tr.dataset.kind = r.kind;
    tr.dataset.id = r.id ?? "";
    for (let i = 0; i < 9; i++) tr.appendChild(document.createElement("td"));
    tr.texts = [];
    fleetRows.set(key, tr);
  }
  return tr;
}

function onRows(rows) {
  stats.pushes++;
  const now = Date.now();
  for (const r of rows) if (r.source_ms !== undefined) note(stats.arrival_latencies_ms, now - r.source_ms);
  requestFrame(queueRows(rows, false));
}

// The texts of a row's cells; the age (3) and the clock offset (8) move with every sample.
const kMovingCells = new Set([3, 8]);
function rowTexts(r) {
  const offset = r.last && r.last.max_clock_offset_ms !== undefined ? `${r.last.max_clock_offset_ms.toFixed(1)} ms` : "-";
  const lost = r.stale ? (r.age_s > 10 * r.stale_after_s ? "LOST " : "STALE ") : "";
  return [r.kind, r.id ?? "-", r.processes.join(", "), `${lost}${r.age_s.toFixed(2)} s`, r.state ?? "",
    r.failsafe ?? "", r.task ?? "", r.autopilot ?? "", offset].map(String);
}

// A row turning stale or fresh; a pushed row whose text changed. A state's rows carry what
// moves (the simulator's time is in its row's text), a pushed row what its sample changed.
function changesWhatMatters(tr, r, texts, fromState) {
  if (!tr) return false; // pushed before the first state listed it
  if (tr.classList.contains("stale") !== !!r.stale) return true;
  return !fromState && texts.some((text, i) => !kMovingCells.has(i) && tr.texts[i] !== text);
}

// Rows to draw at the next frame; whether one of them must be seen at once.
function queueRows(rows, fromState) {
  let urgent = false;
  const at = performance.now();
  for (const r of rows) {
    const key = rowKey(r);
    const texts = rowTexts(r);
    const pushed = dirtyRows.get(key);
    const matters = changesWhatMatters(fleetRows.get(key), r, texts, fromState) || !!pushed?.urgent;
    urgent = urgent || matters;
    // A state arriving before the frame is newer, but the pushed row's stamps are still drawn.
    const row = pushed?.row.recv_ms !== undefined && r.recv_ms === undefined
      ? { ...r, recv_ms: pushed.row.recv_ms, source_ms: pushed.row.source_ms } : r;
    dirtyRows.set(key, { row, texts, urgent: matters, at_ms: at });
  }
  return urgent;
}

// A row that hears nothing more turns stale when its age passes stale_after_s, on the page's
// own clock: red at once, not at the station's next state.
const staleTimers = new Map(); // key -> timeout
function watchStaleness(key, r, heardAtMs) {
  clearTimeout(staleTimers.get(key));
  if (r.stale || !(r.stale_after_s > 0)) return;
  const due = heardAtMs + 1000 * (r.stale_after_s - r.age_s) - performance.now();
  staleTimers.set(key, setTimeout(() => {
    const tr = fleetRows.get(key);
    if (!tr || tr.classList.contains("stale")) return;
    const aged = { ...r, stale: true, age_s: r.stale_after_s, recv_ms: undefined, source_ms: undefined };
    dirtyRows.set(key, { row: aged, texts: rowTexts(aged), urgent: true, at_ms: performance.now() });
    requestFrame(true);
  }, Math.max(0, due) + 1));
}

function drawFleet() {
  const now = Date.now();
  for (const [key, { row: r, texts, urgent, at_ms }] of dirtyRows) {
    const tr = fleetRows.get(key);
    if (!tr) continue;
    texts.forEach((text, i) => {
      const cell = tr.cells[i];
      if (tr.texts[i] !== text) cell.textContent = text;
    });
    tr.texts = texts;
    tr.classList.toggle("stale", !!r.stale);
    watchStaleness(key, r, at_ms);
    stats.row_updates[key] = (stats.row_updates[key] ?? 0) + 1;
    // The latency of what changed the page: a pushed row the operator had to see at once.
    if (urgent && r.source_ms !== undefined) note(stats.latencies_ms, now - r.source_ms);
    if (urgent && r.recv_ms !== undefined) note(stats.server_latencies_ms, now - r.recv_ms);
  }
  dirtyRows.clear();
}

// A write that changes nothing still replaces the text node, and the page is laid out and
// painted again: at the state's rate that is most of the page's frames.
function setText(el, text) {
  if (el.textContent !== text) el.textContent = text;
}

function esc(s) {
  return String(s ?? "").replace(/[&<>"]/g, (c) => ({ "&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;" }[c]));
}

function renderTasks(tasks, fleet, note) {
  setText($("#manager-note"), note ? `(${note})` : "");
  const status = {};
  for (const r of fleet) if (r.kind === "uav-agent" && r.last) status[r.last.task_id] = r.last;
  const html = [...tasks].reverse().map((t) => {
    const s = status[t.task_id];
    const progress = s ? `${short(s.stage)} ${s.process_index + 1}/${s.process_count}, ${s.distance_to_stage_point_m.toFixed(2)} m to go, solver ${(s.solve_time_us / 1000).toFixed(1)} ms, failsafe ${short(s.failsafe)}` : "";
    const live = ["queued", "dispatched", "running"].includes(t.state);
    return `<tr data-task="${esc(t.task_id)}" data-state="${t.state}"><td>${esc(t.task_id)}</td><td>${t.uav_id}</td><td class="state">${t.state}</td>` +
      `<td>${esc(progress)}</td><td>${esc(t.reason)}</td><td>${live ? `<button class="abort" data-task="${esc(t.task_id)}">Abort</button>` : ""}</td></tr>`;
  }).join("");
  // Only when it changed: a row (and its Abort button) stays the same element under the
  // operator's pointer while the task waits.
  if (html !== lastTasksHtml) {
    $("#tasks tbody").innerHTML = html;
    lastTasksHtml = html;
  }
}
let lastTasksHtml = "";

$("#tasks").addEventListener("click", async (e) => {
  const id = e.target.dataset?.task;
  if (!e.target.classList.contains("abort") || !id) return;
  if (!(await confirmThen(`Abort task ${id}? The UAV holds, then lands.`))) return;
  const reply = await request({ op: "abort", task_id: id, reason: "operator (ground station page)" });
  $("#task-answer").textContent = `abort ${id}: ${reply.message}`;
});

const point = (s) => s.split(",").map((x) => Number(x.trim()));
$("#task-form").addEventListener("submit", async (e) => {
  e.preventDefault();
  const f = new FormData(e.target);
  document.querySelectorAll("#task-form .field-error").forEach((el) => { el.textContent = ""; });
  const task = {
    task_id: f.get("task_id"),
    uav_id: Number(f.get("uav_id")),
    processes: [{
      from_ugv: Number(f.get("from_ugv")), to_ugv: Number(f.get("to_ugv")),
      initial_point_m: point(f.get("initial_point_m")), transition_point_m: point(f.get("transition_point_m")),
      final_point_m: point(f.get("final_point_m")), final_action: f.get("final_action"),
      vmax_m_s: Number(f.get("vmax_m_s")), amax_m_s2: Number(f.get("amax_m_s2")),
    }],
  };
  const reply = await request({ op: "submit", task });
  $("#task-answer").textContent = `${reply.ok ? "accepted" : "refused"}: ${reply.message}`;
  if (!reply.ok) {
    const el = document.querySelector(`#task-form .field-error[data-field="${reply.field}"]`) ?? $("#task-error");
    el.textContent = reply.message;
  }
});

const fcAnswers = {};
function renderFc(fleet) {
  const bridges = fleet.filter((r) => r.kind === "fc-bridge" && r.id !== null);
  const root = $("#fc");
  for (const r of bridges) {
    let box = root.querySelector(`.fc-uav[data-uav="${r.id}"]`);
    if (!box) {
      box = document.createElement("div");
      box.className = "fc-uav";
      box.dataset.uav = r.id;
      box.innerHTML = `<div class="fc-status"></div>` +
        ["arm", "offboard", "land", "disarm"].map((c) => `<button class="fc-cmd" data-cmd="${c}">${c}</button>`).join(" ") +
        ` <span class="fc-answer"></span>`;
      root.appendChild(box);
    }
    const s = r.last ?? {};
    const battery = s.battery_remaining >= 0 ? `${Math.round(100 * s.battery_remaining)} %` : "?";
    setText(box.querySelector(".fc-status"),
      `UAV ${r.id}: link ${s.link_ok ? "ok" : "LOST"}, ${short(s.autopilot)}, mode ${s.mode_name ?? "?"}, ` +
      `${s.armed ? "ARMED" : "disarmed"}, battery ${battery}, hover thrust ${(s.hover_thrust ?? 0).toFixed(3)}, ` +
      `parameters ${s.flight_blocker ? "BLOCKED: " + s.flight_blocker : "ok"}`);
  }
}

$("#fc").addEventListener("click", async (e) => {
  if (!e.target.classList.contains("fc-cmd")) return;
  const box = e.target.closest(".fc-uav");
  const uav = Number(box.dataset.uav);
  const cmd = e.target.dataset.cmd;
  if (!(await confirmThen(`${cmd.toUpperCase()} UAV ${uav}? The autopilot decides and answers.`))) return;
  const answer = box.querySelector(".fc-answer");
  answer.textContent = `${cmd}: waiting for the autopilot`;
  const reply = await request({ op: "fc", uav_id: uav, command: cmd });
  answer.textContent = `${cmd}: ${reply.message}`;
  answer.className = `fc-answer ${reply.ok ? "accepted" : "refused"}`;
  fcAnswers[uav] = reply;
});

// The recorder's file and size as the station sees them (stat() at its rate): the size grows
// while it records. data-* carry the same for the browser tests.
function renderRecorder(r) {
  if (!r) return;
  const el = $("#rec-status");
  const size = r.bytes < 1e6 ? `${(r.bytes / 1e3).toFixed(1)} kB` : `${(r.bytes / 1e6).toFixed(2)} MB`;
  const text = r.running ? `recording ${r.file}, ${size}` : r.file ? `stopped: ${r.file}, ${size}` : "not recording";
  if (el.dataset.bytes === String(r.bytes) && el.dataset.running === String(r.running) &&
      el.dataset.file === String(r.file) && el.textContent === text) return;
  el.textContent = text;
  el.dataset.running = r.running;
  el.dataset.file = r.file;
  el.dataset.bytes = r.bytes;
  $("#rec-start").disabled = r.running;
  $("#rec-stop").disabled = !r.running;
}
$("#rec-start").onclick = async () => { $("#rec-status").textContent = (await request({ op: "record", action: "start" })).message; };
$("#rec-stop").onclick = async () => { $("#rec-status").textContent = (await request({ op: "record", action: "stop" })).message; };

// Live plots: the last 60 s of every UAV's tracking error, thrust and solve time, one series
// per UAV; made again when a UAV appears (its history before is empty).
const kPlotSamples = 600;
const kPlotColours = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#17becf"];
const plotSpecs = [
  ["#plot-tracking", "tracking error", "m", (u) => u.tracking_error_m],
  ["#plot-thrust", "thrust", "m/s²", (u) => u.thrust_m_s2],
  ["#plot-solve", "solve time", "ms", (u) => (u.solve_time_us !== undefined ? u.solve_time_us / 1000 : undefined)],
];
let plotUavs = []; // UAV ids, in series order
const plotTimes = [];
let plotValues = plotSpecs.map(() => []); // per plot, per UAV: values aligned with plotTimes
let plots = [];
function makePlots(uavIds) {
  for (const plot of plots) plot.destroy();
  plots = plotSpecs.map(([el, label, unit]) => new uPlot({
    width: 420, height: 120, legend: { show: true }, scales: { x: { time: true } },
    series: [{}, ...uavIds.map((u, i) => ({ label: `UAV ${u} ${label} (${unit})`, stroke: kPlotColours[i % kPlotColours.length] }))],
  }, [[], ...uavIds.map(() => [])], $(el)));
}
makePlots([]);
// A state's samples go in as it arrives; the plots are drawn at most 5 times a second, in
// the page's frames.
function takePlotSamples(live) {
  const ids = Object.keys(live ?? {}).sort((a, b) => Number(a) - Number(b));
  if (ids.length === 0) return;
  if (ids.join() !== plotUavs.join()) {
    plotValues = plotSpecs.map((_, k) => ids.map((u) => {
      const was = plotUavs.indexOf(u);
      return was >= 0 ? plotValues[k][was] : plotTimes.map(() => null);
    }));
    plotUavs = ids;
    makePlots(ids);
  }
  plotTimes.push(Date.now() / 1000);
  plotSpecs.forEach(([, , , value], k) => ids.forEach((u, i) => plotValues[k][i].push(value(live[u]) ?? null)));
  if (plotTimes.length > kPlotSamples) {
    plotTimes.shift();
    for (const perUav of plotValues) for (const values of perUav) values.shift();
  }
  plotsDirty = true;
}
let plotsDirty = false;
let lastPlotMs = -Infinity;
function drawPlots() {
  if (!plotsDirty || performance.now() - lastPlotMs < 200) return;
  plotsDirty = false;
  lastPlotMs = performance.now();
  plots.forEach((plot, k) => plot.setData([plotTimes, ...plotValues[k]]));
}

// The 3D view (scene.js), in the world frame or a chosen UGV's.
const view = createScene($("#view3d"), $("#frame"), stats);
connect();
