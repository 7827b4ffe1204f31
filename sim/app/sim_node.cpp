#include "sim_node.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <thread>

#include "cover/clock/clock.hpp"
#include "cover/process/shutdown_signal.hpp"
#include "cover/vocabulary/mission_state.hpp"
#include "cover/wire/control.hpp"
#include "cover/wire/eigen.hpp"
#include "cover/wire/enums.hpp"
#include "cover/wire/sensors.hpp"
#include "cover/wire/ugv_imu_measurement.hpp"

namespace cover::sim {
namespace {

using namespace std::chrono_literals;

// The first wait before a tick is published again: short against the agents' step
// (~0.1 ms; a stage plan up to a few ms), long against a loopback round trip, so that a
// tick lost at start-up costs at most this. Each further wait doubles up to the longest:
// an agent that is only slow (a loaded host, a fleet of 16 on 2 cores) is not sent the
// tick 50 times a second, and DDS's own repair of a lost reliable sample (a 100 ms
// heartbeat) has the time to work.
constexpr std::chrono::milliseconds kFirstRepublish{20};
constexpr std::chrono::milliseconds kLongestRepublish{320};

}  // namespace

SimNode::SimNode(dds::Participant& participant, shm::SeqlockWriter<SharedWorld>& segment,
                 Fleet& fleet, SimRunOptions options, const SimProcessParams& params)
    : fleet_(fleet),
      options_(std::move(options)),
      params_(params),
      segment_(segment),
      clock_writer_(participant.make_writer(dds::topics::sim_clock())),
      mailboxes_(static_cast<std::size_t>(fleet.uav_count())),
      latency_(fleet.has_autopilots() ? SensorLatency::kTickKeyStep
                                      : SensorLatency::kStampKeyStep) {
  const int ugvs = fleet.world(0).ugv_count();
  for (int u = 0; u < fleet.uav_count(); ++u) {
    const auto uav = static_cast<std::uint32_t>(u);
    relative_writers_.emplace_back();
    for (int k = 0; k < ugvs; ++k) {
      relative_writers_[u].push_back(
          participant.make_writer(dds::topics::relative_state(uav, static_cast<std::uint32_t>(k))));
    }
    if (!fleet.has_autopilots()) {
      command_readers_.push_back(
          participant.make_reader(dds::topics::uav_command(uav),
                                  [this, u](const msg::UavCommand& c) { on_command(u, c); }));
    }
    trace_readers_.push_back(participant.make_reader(
        dds::topics::uav_trace(uav), [this, u](const msg::ControlTrace& t) { on_trace(u, t); }));
    if (fleet.has_firmware()) {
      fc_state_readers_.push_back(participant.make_reader(
          dds::topics::fc_state(uav), [this, u](const msg::FcState& s) { on_fc_state(u, s); }));
    }
  }
  task_status_reader_ =
      participant.make_reader(dds::topics::task_status(), [this](const msg::TaskStatus& s) {
        if (s.uav_id >= mailboxes_.size()) return;
        std::lock_guard<std::mutex> lock(mutex_);
        mailboxes_[s.uav_id].task_message = s.message;
      });
  segment_.write(fleet_.shared(), 0);
  if (options_.mavlink.ugv_imu) {
    ugv_imu_links_ = std::make_unique<UgvImuLinks>(ugvs, options_.mavlink.ugv_imu_ports,
                                                   options_.mavlink.params);
    for (int k = 0; k < ugvs; ++k) {
      spdlog::info("UGV {}'s IMU over MAVLink (a PX4 rover, system {}): {}", k,
                   options_.mavlink.params.ugv_system_id_base + k, ugv_imu_links_->describe(k));
    }
  }
  if (options_.mocap.enabled) mocap_ = std::make_unique<MocapLink>(fleet_, options_.mocap);
  if (fleet.has_autopilots()) start_autopilot_links();
}

SimNode::~SimNode() {
  if (autopilot_links_) autopilot_links_->stop();
}

void SimNode::on_command(int u, const msg::UavCommand& command) {
  const std::int64_t now_ns = clock::monotonic_ns();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    Mailbox& box = mailboxes_[u];
    box.command = command;
    box.command_received_ns = now_ns;
    if (options_.clock == SimClockMode::Realtime) {
      latency_.answered(u, command.measurement_stamp_ns, now_ns);
    }
    if (!answered(box, awaited_tick_ns_)) return;
  }
  arrived_.notify_all();
}

SimExit SimNode::run() {
  if (!wait_for_agents() || (fleet_.has_firmware() && !wait_for_firmware())) {
    // Stopped while waiting is a stop (a standing world's normal end), not a failed start.
    return process::ShutdownSignal::requested() ? SimExit::Interrupted : SimExit::StartupTimeout;
  }
  start_ = std::chrono::steady_clock::now();
  stepping_since_ = start_;
  const SimExit exit = options_.clock == SimClockMode::Lockstep ? run_lockstep() : run_realtime();
  if (autopilot_links_) autopilot_links_->stop();
  wall_time_s_ =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - stepping_since_).count();
  if (republished_ticks_ > 0) {
    spdlog::info("{} tick(s) published again before every agent answered, awaiting {} answer(s)",
                 republished_ticks_, awaited_answers_);
  }
  return exit;
}

// The first tick waits until every UAV agent listens to the clock and has a command
// writer: a tick published before that would be lost (volatile) and the run would differ
// from the in-process one.
bool SimNode::wait_for_agents() {
  const auto deadline =
      std::chrono::steady_clock::now() + clock::to_milliseconds(params_.startup_timeout_s);
  while (mocap_ && !mocap_->wait_for_client(100ms)) {
    if (process::ShutdownSignal::requested()) return false;
    if (std::chrono::steady_clock::now() >= deadline) {
      spdlog::error("no cover-mocap-relay connected to the VRPN server {} after {:.0f} s",
                    mocap_->describe(), params_.startup_timeout_s);
      return false;
    }
  }
  for (int u = 0; u < fleet_.uav_count(); ++u) {
    // With autopilots the command goes to the bridge: only the trace comes here.
    while ((!uses_autopilots() && command_readers_[u].matched_writers() == 0) ||
           trace_readers_[u].matched_writers() == 0) {
      if (process::ShutdownSignal::requested()) return false;
      send_keepalive_heartbeats();
      if (std::chrono::steady_clock::now() >= deadline) {
        spdlog::error("no UAV agent for UAV {} (cover-uav-agent --id {}) after {:.0f} s", u, u,
                      params_.startup_timeout_s);
        return false;
      }
      std::this_thread::sleep_for(1ms);
    }
  }
  const std::size_t uavs = static_cast<std::size_t>(fleet_.uav_count());
  if (!clock_writer_.wait_for_readers(uavs, clock::to_milliseconds(params_.startup_timeout_s))) {
    spdlog::error("only {} of {} UAV agents subscribed to cover/sim/clock",
                  clock_writer_.matched_readers(), uavs);
    return false;
  }
  spdlog::info("{} UAV agent(s) connected; starting", uavs);
  return true;
}

bool SimNode::relative_withheld(double t_s) {
  const double start_s = options_.relative_gap_start_s;
  const bool withheld = start_s >= 0.0 && t_s >= start_s && t_s < start_s + options_.relative_gap_s;
  if (withheld != in_relative_gap_) {
    spdlog::warn("injected fault: relative states {} at t = {:.2f} s",
                 withheld ? "withheld" : "published again", t_s);
    in_relative_gap_ = withheld;
  }
  return withheld;
}

void SimNode::publish_tick(const std::vector<std::uint32_t>& awaited) {
  const double t = fleet_.time_s();
  // The world first: the UGV agents wake on it and publish their IMU, which the UAV agent
  // awaits, while the relative states and the tick are still being written.
  segment_.write(fleet_.shared(), wire::to_stamp_ns(t));
  std::int64_t relative_stamp_ns = -1;
  const bool withheld = relative_withheld(t);
  if (mocap_) relative_stamp_ns = mocap_->serve(fleet_, withheld);
  for (int u = 0; u < fleet_.uav_count() && !withheld && !mocap_; ++u) {
    const World& world = fleet_.world(u);
    if (!world.relative_sensor().has_measurement()) continue;
    // Published again: only the UAVs still awaited may have lost theirs.
    if (!awaited.empty() && std::find(awaited.begin(), awaited.end(), u) == awaited.end()) {
      continue;
    }
    for (int k = 0; k < world.ugv_count(); ++k) {
      const msg::RelativeState m =
          wire::to_msg(world.relative_sensor().latest(k), static_cast<std::uint32_t>(u),
                       static_cast<std::uint32_t>(k));
      relative_stamp_ns = m.stamp_ns;
      // UAV u's agent reads the states of its task's UGVs only: N UAVs x M UGVs samples a
      // tick, most read by no one, were the simulator's cost growing as N^2.
      if (relative_writers_[u][k].matched_readers() > 0) relative_writers_[u][k].write(m);
    }
  }
  if (relative_stamp_ns >= 0) {
    const std::int64_t now_ns = clock::monotonic_ns();
    std::lock_guard<std::mutex> lock(mutex_);
    latency_.published(latency_key(relative_stamp_ns), now_ns);
  }
  publish_ugv_imu(t);
  msg::SimClock tick;
  tick.stamp_ns = wire::to_stamp_ns(t);
  tick.tick = fleet_.tick();
  tick.period_s = 1.0 / params_.control_rate_hz;
  tick.mode = options_.clock == SimClockMode::Lockstep ? msg::ClockMode::CLOCK_MODE_LOCKSTEP
                                                       : msg::ClockMode::CLOCK_MODE_REALTIME;
  tick.imu_stamp_ns =
      fleet_.latest_imu_stamp_s() >= 0.0 ? wire::to_stamp_ns(fleet_.latest_imu_stamp_s()) : -1;
  tick.relative_stamp_ns = relative_stamp_ns;
  tick.awaited = awaited;
  clock_writer_.write(tick);
}

void SimNode::on_trace(int u, const msg::ControlTrace& trace) {
  bool state_changed = false;
  bool completes_tick = false;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    Mailbox& box = mailboxes_[u];
    state_changed = !box.trace || box.trace->task_state != trace.task_state;
    box.trace = trace;
    completes_tick = answered(box, awaited_tick_ns_);
  }
  if (state_changed) {
    const auto state = wire::from_msg(trace.task_state);
    spdlog::info("UAV {}: task {} from t = {:.2f} s (its trace)", u,
                 state ? mission::to_string(*state) : "in an unknown state",
                 wire::to_seconds(trace.stamp_ns));
  }
  if (completes_tick) arrived_.notify_all();
}

std::int64_t SimNode::latency_key(std::int64_t relative_stamp_ns) const {
  return uses_autopilots() ? static_cast<std::int64_t>(fleet_.tick()) : relative_stamp_ns;
}

bool SimNode::answered(const Mailbox& box, std::int64_t tick_ns) const {
  const bool traced = box.trace && box.trace->stamp_ns == tick_ns;
  if (uses_autopilots()) return traced && box.setpoint_ms == tick_ns / 1'000'000;
  return box.command && box.command->stamp_ns == tick_ns && traced;
}

std::vector<std::uint32_t> SimNode::unanswered(std::int64_t tick_ns) const {
  std::vector<std::uint32_t> out;
  for (int u = 0; u < fleet_.uav_count(); ++u) {
    if (!answered(mailboxes_[u], tick_ns)) out.push_back(static_cast<std::uint32_t>(u));
  }
  return out;
}

SimNode::TickWait SimNode::wait_for_commands(std::int64_t tick_ns) {
  std::unique_lock<std::mutex> lock(mutex_);
  awaited_tick_ns_ = tick_ns;
  // The first tick is still start-up: an agent's reader may match the clock writer a
  // while after the writer matched it (discovery is not symmetric in time).
  const double timeout_s = fleet_.tick() == 0 ? params_.startup_timeout_s : params_.stall_timeout_s;
  const auto deadline = std::chrono::steady_clock::now() + clock::to_milliseconds(timeout_s);
  auto wait = kFirstRepublish;
  // A tick (or its relative states) can be lost: to a reader that matched just after it
  // was written, or to best-effort delivery. Publish it again until answered, naming the
  // UAVs still awaited: only they answer again (the others' answers arrived), and the
  // agents step each tick once.
  for (;;) {
    for (int u = 0; u < fleet_.uav_count(); ++u) {
      arrived_.wait_until(lock, std::min(deadline, std::chrono::steady_clock::now() + wait),
                          [&] { return answered(mailboxes_[u], tick_ns); });
      if (!answered(mailboxes_[u], tick_ns)) break;
    }
    const std::vector<std::uint32_t> awaited = unanswered(tick_ns);
    if (awaited.empty()) return TickWait::Answered;
    if (process::ShutdownSignal::requested()) return TickWait::Interrupted;
    if (std::chrono::steady_clock::now() >= deadline) {
      log_stall(static_cast<int>(awaited.front()), mailboxes_[awaited.front()], tick_ns, timeout_s);
      return TickWait::Stalled;
    }
    lock.unlock();
    publish_tick(awaited);
    republish_mavlink();
    lock.lock();
    ++republished_ticks_;
    awaited_answers_ += awaited.size();
    wait = std::min(2 * wait, kLongestRepublish);
  }
}

std::uint64_t SimNode::samples_received() const {
  std::uint64_t n = 0;
  for (const auto& r : command_readers_) n += r.received_count();
  for (const auto& r : trace_readers_) n += r.received_count();
  return n;
}

void SimNode::log_stall(int u, const Mailbox& box, std::int64_t tick_ns, double timeout_s) const {
  const double t_s = wire::to_seconds(tick_ns);
  if (!uses_autopilots()) {
    spdlog::error(
        "lockstep stalled at t = {:.2f} s: no command from UAV {} (cover-uav-agent --id {}, "
        "topic cover/uav/{}/cmd) for {:.1f} s",
        t_s, u, u, u, timeout_s);
    return;
  }
  if (!(box.trace && box.trace->stamp_ns == tick_ns)) {
    spdlog::error(
        "lockstep stalled at t = {:.2f} s: no trace from UAV {} (cover-uav-agent --id {}, "
        "topic cover/uav/{}/trace) for {:.1f} s",
        t_s, u, u, u, timeout_s);
    return;
  }
  spdlog::error(
      "lockstep stalled at t = {:.2f} s: UAV {}'s autopilot got no SET_ATTITUDE_TARGET with "
      "time_boot_ms {} from its bridge (cover-fc-bridge --id {}) on {} for {:.1f} s (newest "
      "taken: {}, {} in all)",
      t_s, u, tick_ns / 1'000'000, u, autopilot_links_->describe(u), timeout_s, box.setpoint_ms,
      box.setpoints);
}

void SimNode::apply_commands(bool lockstep) {
  if (uses_autopilots()) {
    apply_autopilots();
    return;
  }
  const std::int64_t now_ns = clock::monotonic_ns();
  for (int u = 0; u < fleet_.uav_count(); ++u) {
    mission::ControllerStatus status;
    mission::ControlCommand command;
    double age_s = -1.0;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      const Mailbox& box = mailboxes_[u];
      if (box.trace) status = wire::from_msg(*box.trace);
      if (fleet_.has_firmware()) fleet_.note_firmware_landing(u, box.firmware_landing);
      if (box.command) {
        command = wire::from_msg(*box.command);
        age_s = lockstep ? 0.0 : static_cast<double>(now_ns - box.command_received_ns) * 1e-9;
      }
    }
    fleet_.apply(u, status, command, age_s);
    if (fleet_.offboard_changed(u)) {
      const OffboardState state = fleet_.offboard_state(u);
      if (state == OffboardState::Offboard) {
        spdlog::info("UAV {}: offboard (agent commanding)", u);
      } else {
        spdlog::warn("UAV {}: {} at t = {:.2f} s{}", u, to_string(state), fleet_.time_s(),
                     fleet_.offboard_handed_over(u)
                         ? " (the agent handed over: no relative state to land on)"
                         : "");
      }
    }
  }
}

bool SimNode::run_over() const {
  return !options_.standing && fleet_.finished();
}

// Until every agent answered the first tick, the processes were still meeting (discovery,
// each agent waiting for its inputs' publishers: 0-150 ms of a Scenario 2 run, from run to
// run): start-up, reported apart (startup_s), not stepping; the wall time of the run, and
// so its real-time factor, counts from here.
void SimNode::note_first_tick_answered() {
  stepping_since_ = std::chrono::steady_clock::now();
  startup_s_ = std::chrono::duration<double>(stepping_since_ - start_).count();
  spdlog::info("every UAV agent answered the first tick after {:.3f} s: stepping", startup_s_);
}

SimExit SimNode::run_lockstep() {
  while (!run_over()) {
    if (process::ShutdownSignal::requested()) return SimExit::Interrupted;
    publish_tick();
    switch (wait_for_commands(wire::to_stamp_ns(fleet_.time_s()))) {
      case TickWait::Answered:
        if (fleet_.tick() == 0) note_first_tick_answered();
        break;
      case TickWait::Stalled:
        return SimExit::Stalled;
      case TickWait::Interrupted:
        return SimExit::Interrupted;
    }
    apply_commands(true);
    fleet_.advance();
    if (uses_autopilots()) set_sim_time();
  }
  return SimExit::Finished;
}

SimExit SimNode::run_realtime() {
  const auto period = std::chrono::nanoseconds(static_cast<long>(1e9 / params_.control_rate_hz));
  auto next = std::chrono::steady_clock::now();
  while (!run_over()) {
    if (process::ShutdownSignal::requested()) return SimExit::Interrupted;
    publish_tick();
    next += period;
    std::this_thread::sleep_until(next);  // the simulated world's pace, not a synchronisation
    apply_commands(false);
    fleet_.advance();
    if (uses_autopilots()) set_sim_time();
  }
  return SimExit::Finished;
}

std::string SimNode::task_message(int uav) const {
  std::lock_guard<std::mutex> lock(mutex_);
  return mailboxes_[uav].task_message;
}

}  // namespace cover::sim
