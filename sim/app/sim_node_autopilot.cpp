// SimNode's MAVLink side: the simulated autopilots' links (frames in on reader threads,
// ACKs and streams out), lockstep over MAVLink, the injected autopilot faults, and the
// UGV IMUs served as rover autopilots.
#include <spdlog/spdlog.h>

#include <cmath>

#include "cover/clock/clock.hpp"
#include "cover/wire/control.hpp"
#include "sim_node.hpp"

namespace cover::sim {

namespace {
constexpr std::chrono::seconds kKeepalivePeriod{1};
}  // namespace

void SimNode::start_autopilot_links() {
  keepalive_sent_.assign(static_cast<std::size_t>(fleet_.uav_count()),
                         std::chrono::steady_clock::time_point{});
  auto links = std::make_unique<AutopilotLinks>(
      fleet_.uav_count(), options_.mavlink.autopilot_ports,
      [this](int u, const mavlink::Frame& frame) { on_autopilot_frame(u, frame); });
  std::lock_guard<std::mutex> lock(mutex_);
  autopilot_links_ = std::move(links);
  for (int u = 0; u < fleet_.uav_count(); ++u) {
    const fc::SimulatedAutopilot& autopilot = fleet_.autopilot(u);
    spdlog::info("UAV {}: simulated {} autopilot, MAVLink system {}, {}, {} and disarmed", u,
                 cover::to_string(autopilot.profile()), autopilot.system_id(),
                 autopilot_links_->describe(u), autopilot.mode_name());
  }
}

void SimNode::set_sim_time() {
  std::lock_guard<std::mutex> lock(mutex_);
  sim_time_s_ = fleet_.time_s();
}

void SimNode::on_autopilot_frame(int u, const mavlink::Frame& frame) {
  const std::int64_t received_ns = clock::monotonic_ns();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!autopilot_links_) return;  // a frame before the node finished starting
    const fc::FrameResponse response = fleet_.autopilot(u).on_frame(frame, sim_time_s_);
    autopilot_links_->send(u, response.frames);
    if (response.setpoint_accepted) {
      note_setpoint_locked(u, response.setpoint_time_boot_ms, received_ns);
    }
    log_autopilot_events_locked(u);
  }
  arrived_.notify_all();
}

// Lockstep: the tick a setpoint answers. Realtime: the latency of the first setpoint of each
// tick, the tick being time_boot_ms rounded to the nearest control period (time_boot_ms is
// the agent's command stamp: its clock, the simulator's time extrapolated from the last
// tick it heard, read when the tick's relative state woke it: within a fraction of a
// period of the tick's time, either side). Counted while the agent's last trace says its
// task runs: only then does it step on each relative state, as the direct path's measure
// (commands that name a relative state) counts.
void SimNode::note_setpoint_locked(int u, std::uint32_t time_boot_ms, std::int64_t received_ns) {
  Mailbox& box = mailboxes_[u];
  if (box.setpoints++ == 0) {
    spdlog::info("UAV {}: first setpoint from the bridge (SET_ATTITUDE_TARGET, time_boot_ms {})", u,
                 time_boot_ms);
  }
  box.setpoint_ms = std::max<std::int64_t>(box.setpoint_ms, time_boot_ms);
  box.setpoint_received_ns = received_ns;
  const bool running = box.trace && box.trace->task_state == msg::TaskState::TASK_RUNNING;
  if (options_.clock != SimClockMode::Realtime || !running) return;
  const std::int64_t tick = std::llround(time_boot_ms * params_.control_rate_hz / 1000.0);
  latency_.answered(u, tick, received_ns);
}

void SimNode::apply_autopilots() {
  for (int u = 0; u < fleet_.uav_count(); ++u) {
    std::lock_guard<std::mutex> lock(mutex_);
    mission::ControllerStatus status;
    if (mailboxes_[u].trace) status = wire::from_msg(*mailboxes_[u].trace);
    if (u == 0) inject_autopilot_faults_locked(fleet_.time_s());
    autopilot_links_->send(u, fleet_.apply_autopilot(u, status));
    log_autopilot_events_locked(u);
  }
}

void SimNode::inject_autopilot_faults_locked(double t_s) {
  const MavlinkRunOptions& m = options_.mavlink;
  fc::SimulatedAutopilot& autopilot = fleet_.autopilot(0);
  if (!mode_switch_done_ && m.mode_switch_time_s >= 0.0 && t_s + 1e-9 >= m.mode_switch_time_s) {
    mode_switch_done_ = true;
    spdlog::warn(
        "injected fault: the safety pilot switches UAV 0's autopilot to {} at t = {:.2f} s",
        fc::mode_name(autopilot.profile(), m.mode_switch_to), t_s);
    autopilot.inject_mode_switch(m.mode_switch_to);
  }
  if (!heartbeat_stop_done_ && m.heartbeat_stop_time_s >= 0.0 &&
      t_s + 1e-9 >= m.heartbeat_stop_time_s) {
    heartbeat_stop_done_ = true;
    spdlog::warn("injected fault: UAV 0's autopilot stops its heartbeats at t = {:.2f} s", t_s);
    autopilot.stop_heartbeats();
  }
}

void SimNode::log_autopilot_events_locked(int u) {
  for (const std::string& note : fleet_.autopilot(u).take_link_notes()) {
    spdlog::info("UAV {} autopilot: {}", u, note);
  }
  const auto& events = fleet_.autopilot(u).events();
  Mailbox& box = mailboxes_[u];
  for (; box.events_logged < events.size(); ++box.events_logged) {
    const fc::AutopilotEvent& e = events[box.events_logged];
    const bool bad =
        e.kind == fc::AutopilotEvent::Kind::Failsafe || e.kind == fc::AutopilotEvent::Kind::Refusal;
    spdlog::log(bad ? spdlog::level::warn : spdlog::level::info,
                "UAV {} autopilot: {} at t = {:.2f} s", u, e.text, e.time_s);
  }
}

// While simulated time stands still (waiting for the agents, or a lockstep tick not yet
// answered), a real autopilot would still send its heartbeat: a bridge that waits for one
// before it streams setpoints (at start, or restarted) would otherwise never start. Only
// while its bridge is silent: in a lockstep run that streams, heartbeats come on simulated
// time alone, and one sent at a wall-clock moment would make the run depend on the
// machine's timing.
void SimNode::send_keepalive_heartbeats() {
  if (!uses_autopilots()) return;
  const auto now = std::chrono::steady_clock::now();
  std::lock_guard<std::mutex> lock(mutex_);
  for (int u = 0; u < fleet_.uav_count(); ++u) {
    auto& sent = keepalive_sent_[static_cast<std::size_t>(u)];
    const auto since_setpoint_ns = clock::monotonic_ns() - mailboxes_[u].setpoint_received_ns;
    const bool streaming = mailboxes_[u].setpoints > 0 &&
                           std::chrono::nanoseconds(since_setpoint_ns) < kKeepalivePeriod;
    if (streaming || now - sent < kKeepalivePeriod) continue;
    sent = now;
    if (const auto heartbeat = fleet_.autopilot(u).heartbeat_frame()) {
      autopilot_links_->send(u, *heartbeat);
    }
  }
}

void SimNode::republish_mavlink() {
  send_keepalive_heartbeats();
  if (ugv_imu_links_) ugv_imu_links_->send_again();
}

void SimNode::publish_ugv_imu(double t_s) {
  if (ugv_imu_links_) ugv_imu_links_->send_new_samples(fleet_.shared(), t_s);
}

}  // namespace cover::sim
