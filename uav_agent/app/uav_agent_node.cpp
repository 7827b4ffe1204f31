#include "uav_agent_node.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <thread>

#include "cover/clock/clock.hpp"
#include "cover/process/shutdown_signal.hpp"
#include "cover/process/thread_placement.hpp"
#include "cover/wire/control.hpp"
#include "cover/wire/eigen.hpp"
#include "cover/wire/enums.hpp"
#include "cover/wire/reference.hpp"
#include "cover/wire/task.hpp"
#include "cover/wire/task_status.hpp"

namespace cover::uav_agent {

namespace {
using namespace std::chrono_literals;

// A lockstep wait's slice: a shutdown request ends a long wait (connect_timeout_s for a
// missing publisher, input_wait_s twice a tick for a missing input) within it, well inside
// cover-launch's grace of 3 s before SIGTERM.
constexpr std::chrono::milliseconds kShutdownSlice{100};

// Calls `wait_until(until)` (true: what it waits for came) in slices up to `deadline`;
// false at the deadline or on a shutdown request.
template <typename WaitUntil>
bool wait_unless_shutdown(std::chrono::steady_clock::time_point deadline, WaitUntil wait_until) {
  while (true) {
    const auto until = std::min(deadline, std::chrono::steady_clock::now() + kShutdownSlice);
    if (wait_until(until)) return true;
    if (until >= deadline || process::ShutdownSignal::requested()) return false;
  }
}

bool on_ladder(mission::Failsafe f) {
  return f == mission::Failsafe::ImuHold || f == mission::Failsafe::EmergencyHover ||
         f == mission::Failsafe::EmergencyLanding || f == mission::Failsafe::EmergencyLanded;
}

// One line for a failsafe change: the new state, and for the ladder the input that was
// lost (cause, frame, age) or, on leaving it, that the stage resumes replanned.
std::string failsafe_event(const mission::ControllerStatus& s, mission::Failsafe before) {
  const std::string was = mission::to_string(before);
  if (s.failsafe == mission::Failsafe::None) {
    if (before == mission::Failsafe::ImuHold) return "failsafe cleared (was " + was + "): IMU back";
    return on_ladder(before)
               ? "failsafe cleared (was " + was + "): inputs back, stage resumes replanned"
               : "failsafe cleared (was " + was + ")";
  }
  std::string line =
      std::string("failsafe ") + mission::to_string(s.failsafe) + " (was " + was + ")";
  if (on_ladder(s.failsafe)) {
    char age[32];
    std::snprintf(age, sizeof age, "%.3f", s.failsafe_input_age_s);
    line += ": " + std::string(mission::to_string(s.failsafe_cause)) + " of G" +
            std::to_string(s.stage.reference_ugv) + " (" + age + " s old)";
  }
  return line;
}

// The processes whose samples a UAV agent takes: its relative states (the simulator or
// a mocap relay), its autopilot's state, and the IMUs of its task's UGVs (every UGV's
// before it has a task, so that a task's UGVs are measured before it arrives).
std::vector<std::string> clock_peers(std::uint32_t uav_id, const mission::Task* task) {
  std::vector<std::string> peers{"cover-sim", "cover-mocap-relay*",
                                 "cover-fc-bridge-" + std::to_string(uav_id)};
  if (task == nullptr) {
    peers.push_back("cover-ugv-agent-*");
  } else {
    for (const int k : task->ugvs()) peers.push_back("cover-ugv-agent-" + std::to_string(k));
  }
  return peers;
}

time_sync::MonitorOptions monitor_options(const AgentOptions& options) {
  time_sync::MonitorOptions m;
  m.process = "cover-uav-agent-" + std::to_string(options.uav_id);
  m.peers = clock_peers(options.uav_id, options.task ? &*options.task : nullptr);
  m.params = options.time_sync;
  return m;
}

}  // namespace

UavAgentNode::UavAgentNode(dds::Participant& participant, AgentOptions options,
                           uav::ControllerConfig config)
    : options_(std::move(options)),
      loop_(options_.uav_id, options_.ugv_count, std::move(config),
            options_.clock == sim_clock::ClockMode::Lockstep ? mission::PlanClock::Lockstep
                                                             : mission::PlanClock::Realtime),
      inputs_(participant, options_.uav_id, options_.ugv_count, options_.intake),
      command_(participant, options_.uav_id),
      status_writer_(participant.make_writer(dds::topics::uav_status(options_.uav_id))),
      task_status_writer_(participant.make_writer(dds::topics::task_status())),
      reference_writer_(participant.make_writer(dds::topics::uav_reference(options_.uav_id))),
      intake_(participant, options_.uav_id),
      fc_gate_(participant, options_.uav_id, options_.fc_bridge, options_.params.fc_stale_after_s),
      clock_responder_(participant, "cover-uav-agent-" + std::to_string(options_.uav_id)),
      clock_offsets_(participant, monitor_options(options_)),
      clock_(participant, options_.clock, static_cast<int>(options_.uav_id)) {
  if (options_.task) accept(*options_.task, 0.0);
}

int UavAgentNode::run() {
  if (options_.clock == sim_clock::ClockMode::Lockstep) {
    run_lockstep();
  } else {
    run_realtime();
  }
  if (answers_repeated_ > 0) {
    spdlog::info("{} lockstep answer(s) written again for ticks published again",
                 answers_repeated_);
  }
  if (const LockstepTimes& t = lockstep_times_; t.ticks > 0) {
    spdlog::info(
        "lockstep: {} ticks; wall time waiting for ticks {:.3f} s, for their inputs "
        "{:.3f} s, stepping {:.3f} s (of which waiting for plans {:.3f} s)",
        t.ticks, t.tick_wait_s, t.input_wait_s, t.step_s, t.plan_wait_s);
  }
  spdlog::info("shutting down: {}", loop_.describe());
  return 0;
}

void UavAgentNode::run_lockstep() {
  auto last_tick = std::chrono::steady_clock::now();
  bool connected = false;
  auto seconds_since = [](std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  while (!process::ShutdownSignal::requested()) {
    const auto waiting = std::chrono::steady_clock::now();
    const auto tick = clock_.next_tick(100ms);
    if (!tick) {
      // The heartbeat goes on between ticks (before the first, or while the simulator
      // waits for another agent): a ground side must see this agent is up.
      publish_status(last_step_s_);
      if (std::chrono::steady_clock::now() - last_tick >
          clock::to_milliseconds(options_.params.silence_warning_s)) {
        spdlog::warn("no simulator tick on cover/sim/clock for {:.1f} s",
                     options_.params.silence_warning_s);
        last_tick = std::chrono::steady_clock::now();
      }
      continue;
    }
    last_tick = std::chrono::steady_clock::now();
    if (tick->answered_before) {
      command_.write_again();
      ++answers_repeated_;
      continue;
    }
    // Answer the first tick only once the task's inputs are connected: samples published
    // before that are lost, and the run would start later than the in-process one.
    if (!connected && loop_.task()) connected = connect_inputs();
    const auto inputs = std::chrono::steady_clock::now();
    // Before the first answered tick the wait is start-up (discovery, the others' start).
    if (lockstep_times_.ticks > 0) lockstep_times_.tick_wait_s += seconds_since(waiting);
    wait_for_inputs(tick->tick);
    const auto stepping = std::chrono::steady_clock::now();
    lockstep_times_.input_wait_s += seconds_since(inputs);
    step(wire::to_seconds(tick->tick.stamp_ns));
    lockstep_times_.step_s += seconds_since(stepping);
    ++lockstep_times_.ticks;
    if (loop_.output().status.planned) {
      lockstep_times_.plan_wait_s += 1e-3 * loop_.output().status.plan_wait_ms;
    }
  }
}

// A lockstep tick is stepped on the inputs of that tick: wait (bounded) until the
// relative states and UGV IMU published for it have arrived.
bool UavAgentNode::connect_inputs() {
  const auto deadline =
      std::chrono::steady_clock::now() + clock::to_milliseconds(options_.params.connect_timeout_s);
  spdlog::info("waiting up to {:.1f} s for the task's inputs' publishers",
               options_.params.connect_timeout_s);
  // Matching is seen by asking the readers (as dds::Reader::wait_for_writers does).
  const bool connected = wait_unless_shutdown(deadline, [&](auto until) {
    while (inputs_.missing_writer()) {
      if (std::chrono::steady_clock::now() >= until) return false;
      std::this_thread::sleep_for(1ms);
    }
    return true;
  });
  if (connected) {
    spdlog::info("inputs connected");
  } else if (const auto missing = inputs_.missing_writer()) {
    if (!process::ShutdownSignal::requested()) spdlog::error("{}", *missing);
  }
  return connected;
}

void UavAgentNode::wait_for_inputs(const msg::SimClock& tick) {
  const auto deadline =
      std::chrono::steady_clock::now() + clock::to_milliseconds(options_.params.input_wait_s);
  // Blocks on the readers' arrivals (no polling: a poll's sleep costs its slack every tick).
  const auto inputs_arrived = [&](auto until) {
    return inputs_.wait_for_stamps(tick.relative_stamp_ns, tick.imu_stamp_ns, until);
  };
  if (loop_.task() && !wait_unless_shutdown(deadline, inputs_arrived)) {
    spdlog::warn("tick {}: inputs missing after {:.1f} s, stepping on what arrived", tick.tick,
                 options_.params.input_wait_s);
  }
  // Through an autopilot: its state after the step our last command flew (whether it is
  // armed and in OFFBOARD decides when a held task starts and when a flight fails).
  const std::int64_t flown_ns = previous_tick_ns_;
  previous_tick_ns_ = tick.stamp_ns;
  if (flown_ns < 0 || !fc_gate_.bridge_present()) return;
  // The bridge stamps a step with the autopilot's time: whole microseconds.
  constexpr std::int64_t kAutopilotStampResolution_ns = 1000;
  const auto state_arrived = [&](auto until) {
    return fc_gate_.wait_for_stamp(flown_ns - kAutopilotStampResolution_ns, until);
  };
  if (!wait_unless_shutdown(deadline, state_arrived)) {
    spdlog::warn(
        "tick {}: the bridge's state after step {:.2f} s missing after {:.1f} s, stepping "
        "on the one before",
        tick.tick, wire::to_seconds(flown_ns), options_.params.input_wait_s);
  }
}

namespace {
constexpr double kStaleStepPeriods = 1.5;

// A spin-wait's pause: lets the core's other hyperthread run and saves power.
inline void cpu_relax() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#elif defined(__aarch64__)
  asm volatile("yield");
#endif
}
}  // namespace

void UavAgentNode::run_realtime() {
  const double period_s = loop_.config().mission.control_period_s;
  // The samples of `waited_on` already stepped on. Counts are per reader: when the reference
  // UGV changes, the new reader's count says nothing of what was stepped on, so the wait is
  // for its next sample.
  const dds::Reader<msg::RelativeState>* waited_on = nullptr;
  std::uint64_t seen = 0;
  place_control_thread();
  while (!process::ShutdownSignal::requested()) {
    // Step on each fresh relative state of the reference frame, or after 1.5 control periods
    // when none comes (the controller then hovers on stale inputs: the failsafe). Not after
    // one period: a state a little late (jitter, DDS-Security's decryption) would get a step
    // on the old state just before its own, a command a period old (e2e secure p99 10.7 ms,
    // 1.4 ms with the half period's slack).
    dds::Reader<msg::RelativeState>* reader = nullptr;
    if (const auto* controller = loop_.controller()) {
      reader = inputs_.relative_reader(controller->stage_machine().reference_ugv());
    }
    if (reader) {
      if (reader != waited_on) {
        waited_on = reader;
        seen = reader->received_count();
        last_state_arrival_.reset();
      }
      if (wait_for_relative_state(*reader, seen, period_s)) seen = reader->received_count();
    } else {
      process::ShutdownSignal::wait_for(clock::to_milliseconds(period_s));
    }
    const auto now = clock_.now_s();
    if (now) {
      step(*now);
    } else {
      publish_status(last_step_s_);  // no simulator time yet: the heartbeat still goes out
    }
  }
}

// Waits up to 1.5 control periods for a relative state beyond `seen`; on the way, at
// rehearsal_lead_s before the one due (a period after the last), rehearses the feedback.
bool UavAgentNode::wait_for_relative_state(dds::Reader<msg::RelativeState>& reader,
                                           std::uint64_t seen, double period_s) {
  using Clock = std::chrono::steady_clock;
  const auto seconds = [](double s) {
    return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
  };
  const auto start = Clock::now();
  const auto give_up = start + seconds(kStaleStepPeriods * period_s);
  bool arrived = false;
  const UavAgentParams& p = options_.params;
  if (p.rehearsal_lead_s > 0.0 && last_state_arrival_) {
    const auto rehearse_at = *last_state_arrival_ + seconds(period_s - p.rehearsal_lead_s);
    if (rehearse_at > start && rehearse_at < give_up) {
      arrived = reader.wait_for_sample_until(rehearse_at, seen);
      if (!arrived) {
        loop_.rehearse();
        if (spin_allowed_) {
          arrived = spin_for_sample(
              reader, seen, std::min(give_up, Clock::now() + seconds(p.spin_after_rehearsal_s)));
        }
      }
    }
  }
  if (!arrived) arrived = reader.wait_for_sample_until(give_up, seen);
  if (arrived) {
    last_state_arrival_ = Clock::now();
  } else {
    last_state_arrival_.reset();
  }
  return arrived;
}

// On the CPU, no sleep: its core runs nothing else until the sample is there (the DDS
// receive thread that brings it runs on another core, place_control_thread).
bool UavAgentNode::spin_for_sample(const dds::Reader<msg::RelativeState>& reader,
                                   std::uint64_t seen,
                                   std::chrono::steady_clock::time_point until) {
  while (std::chrono::steady_clock::now() < until) {
    if (reader.received_count() > seen) return true;
    for (int i = 0; i < 16; ++i) cpu_relax();
  }
  return reader.received_count() > seen;
}

// The control thread alone on control_cpu, the process's other threads on its other CPUs;
// again after a task's start (its planner thread is started by this thread, on its CPU).
void UavAgentNode::place_control_thread() {
  const int cpu = options_.params.control_cpu;
  if (options_.clock == sim_clock::ClockMode::Lockstep) return;
  if (cpu < 0) {
    if (options_.params.spin_after_rehearsal_s > 0.0 && !placement_logged_) {
      spdlog::warn(
          "spin_after_rehearsal_s ignored: no control_cpu (spinning on the core of the "
          "DDS threads would hold off the state awaited); the control thread sleeps");
    }
    placement_logged_ = true;
    return;
  }
  const process::ThreadPlacement placed = process::place_calling_thread_alone(cpu);
  if (!placed.placed) {
    if (spin_allowed_ || !placement_logged_) {
      spdlog::error(
          "control thread not placed on CPU {}: {}; every thread stays where it was, "
          "and the control thread sleeps until its state (no spin)",
          cpu, placed.error);
    }
    spin_allowed_ = false;
    placement_logged_ = true;
    return;
  }
  spin_allowed_ = options_.params.spin_after_rehearsal_s > 0.0;
  if (!placement_logged_) {
    spdlog::info("control thread on CPU {}, the other {} thread(s) on CPU {}; {}", cpu,
                 placed.threads_moved, placed.others,
                 spin_allowed_ ? fmt::format("after its rehearsal it waits for the state on the "
                                             "CPU for up to {:.2f} ms",
                                             1e3 * options_.params.spin_after_rehearsal_s)
                               : std::string("it sleeps until its state"));
    placement_logged_ = true;
  }
}

void UavAgentNode::step(double now_s) {
  last_step_s_ = now_s;
  take_requests(now_s);
  follow_autopilot(now_s);
  inputs_.set_now(now_s);
  loop_.step(now_s, inputs_, command_);
  publish_reference_if_replanned();
  log_changes();
  publish_task_status_on_change(now_s);
  if (now_s >= next_status_s_) {
    publish_status(now_s);
    next_status_s_ = now_s + options_.params.status_period_s;
  }
}

void UavAgentNode::take_requests(double now_s) {
  while (const auto request = intake_.take_task()) {
    // A sender re-sends until it sees the task taken: the task already flying is not new.
    const mission::Task* current = loop_.task();
    if (current && current->task_id == request->task_id &&
        !mission::is_terminal(loop_.task_state())) {
      continue;
    }
    accept(wire::from_msg(*request), now_s);
  }
  while (const auto abort = intake_.take_abort()) {
    if (held_task_ && (abort->task_id.empty() || abort->task_id == held_task_->task_id)) {
      spdlog::warn("task '{}' aborted ({}) before the autopilot was ready", held_task_->task_id,
                   abort->reason);
      msg::TaskStatus status = wire::rejected_task_status(
          wire::to_msg(*held_task_, now_s), options_.uav_id, now_s, "aborted: " + abort->reason);
      status.state = msg::TaskState::TASK_CANCELLED;
      task_status_writer_.write(status);
      held_task_.reset();
      continue;
    }
    const mission::Task* task = loop_.task();
    if (!task || (!abort->task_id.empty() && abort->task_id != task->task_id)) {
      spdlog::warn("abort of task '{}' ignored: not the running task", abort->task_id);
      continue;
    }
    if (loop_.abort(now_s)) {
      spdlog::warn("task '{}' aborted ({}): holding, then {}", task->task_id, abort->reason,
                   mission::to_string(loop_.config().mission.abort_action));
    }
  }
}

void UavAgentNode::accept(const mission::Task& task, double now_s) {
  if (held_task_) {
    // A sender re-sends until it sees its task taken: the held one is taken. Another task
    // is refused as while flying (starting it would bypass what the held one waits for).
    if (held_task_->task_id == task.task_id) return;
    const std::string reason = "busy: task '" + held_task_->task_id + "' is " + held_reason_;
    spdlog::error("task '{}' rejected: {}", task.task_id, reason);
    task_status_writer_.write(
        wire::rejected_task_status(wire::to_msg(task, now_s), options_.uav_id, now_s, reason));
    return;
  }
  if (!loop_.task() || mission::is_terminal(loop_.task_state())) {
    if (const auto reason = start_blocker()) {
      held_task_ = task;
      held_reason_ = *reason;
      publish_held_status(now_s);
      return;
    }
  }
  start(task, now_s);
}

// The autopilot first (without it nothing flies), then the clocks: an input stamped on a
// clock 0.1 s off is stale on arrival, and one ahead is refused (intake.yaml).
std::optional<std::string> UavAgentNode::start_blocker() const {
  if (const auto reason = fc_gate_.not_ready_reason()) {
    return "waiting for the autopilot: " + *reason;
  }
  if (const auto reason = clock_offsets_.limit_reason()) {
    return "waiting for the clocks to agree: " + *reason;
  }
  return std::nullopt;
}

void UavAgentNode::start(const mission::Task& task, double now_s) {
  const uav::TaskDecision decision = loop_.give_task(task);
  if (!decision.accepted) {
    spdlog::error("task '{}' rejected: {}", task.task_id, decision.reason);
    task_status_writer_.write(wire::rejected_task_status(wire::to_msg(task, now_s), options_.uav_id,
                                                         now_s, decision.reason));
    return;
  }
  spdlog::info("accepted {}", decision.reason);
  place_control_thread();  // the task's planner thread started on this thread's CPU
  inputs_.subscribe(task.ugvs());
  clock_offsets_.set_peers(clock_peers(options_.uav_id, &task));
  reported_key_.clear();
}

// The autopilot decides who flies: a held task starts once it flies our setpoints; a
// flight fails the moment it stops (a pilot's mode switch, its own failsafe, its link
// lost), and holds afresh once it flies them again.
void UavAgentNode::follow_autopilot(double now_s) {
  if (held_task_) {
    const std::optional<std::string> blocker = start_blocker();
    if (!blocker) {
      spdlog::info("starting task '{}' (was {})", held_task_->task_id, held_reason_);
      const mission::Task task = std::move(*held_task_);
      held_task_.reset();
      start(task, now_s);
    } else if (*blocker != held_reason_) {
      held_reason_ = *blocker;
      publish_held_status(now_s);
    }
  }
  // A flight in progress is failed by its autopilot only: a clock drifting mid-flight
  // shows in the status and the ladder, which act on the inputs' ages.
  const std::optional<std::string> reason = fc_gate_.not_ready_reason();
  const mission::MissionController* controller = loop_.controller();
  if (!controller) return;
  if (!controller->yielded() && reason && loop_.output().command.armed) {
    autopilot_failure_ = *reason;
    spdlog::error("task '{}' fails: {}; not commanding, observers stopped", loop_.task()->task_id,
                  *reason);
    loop_.yield_to_autopilot(now_s);
  } else if (controller->yielded() && !reason) {
    spdlog::warn("autopilot flies COVER's setpoints again: holding the UAV where it is");
    loop_.take_back(now_s);
  }
}

void UavAgentNode::publish_held_status(double now_s) {
  spdlog::info("task '{}' {}", held_task_->task_id, held_reason_);
  msg::TaskStatus status = wire::rejected_task_status(wire::to_msg(*held_task_, now_s),
                                                      options_.uav_id, now_s, held_reason_);
  status.state = msg::TaskState::TASK_PENDING;
  task_status_writer_.write(status);
}

void UavAgentNode::publish_reference_if_replanned() {
  const mission::MissionController* controller = loop_.controller();
  if (!controller || !controller->output().status.planned) return;
  const mission::ControllerStatus& status = controller->output().status;
  if (status.plan_late_steps > 0) {
    // Realtime: the plan was not ready at its step; the loop flew on without it.
    spdlog::warn("stage plan adopted {} control step(s) late (planned in {:.2f} ms)",
                 status.plan_late_steps, status.plan_ms);
  }
  const mission::StageDecision& d = status.stage;
  reference_writer_.write(wire::to_reference(controller->reference_trajectory(), options_.uav_id,
                                             controller->reference_start_s(), d.reference_ugv,
                                             d.stage));
}

void UavAgentNode::publish_status(double now_s) {
  wire::UavStatusInputs in;
  in.uav_id = options_.uav_id;
  in.stamp_s = now_s;
  in.state = loop_.task_state();
  in.output = &loop_.output();
  in.rejected_samples = inputs_.rejections().total();
  if (const auto worst = clock_offsets_.largest()) {
    in.max_clock_offset_ms = time_sync::ns_to_ms(worst->estimate.offset_ns);
    in.max_offset_peer = worst->peer;
  }
  if (held_task_) {
    // The task it holds is its task: a ground side that dispatched it must see it taken
    // (and why it waits, in its TaskStatus), not an idle agent to send it to again.
    in.task_id = held_task_->task_id;
    in.state = mission::MissionState::NotStarted;
    in.process_count = static_cast<std::uint32_t>(held_task_->processes.size());
  } else if (const mission::Task* task = loop_.task()) {
    in.task_id = task->task_id;
    in.process_count = static_cast<std::uint32_t>(task->processes.size());
    mission::RelativeMeasurement state;
    if (inputs_.relative_state(loop_.output().status.stage.reference_ugv, state)) {
      in.position_m = state.position_m;
      in.velocity_m_s = state.velocity_m_s;
    }
  }
  status_writer_.write(wire::to_status(in));
}

void UavAgentNode::publish_task_status_on_change(double now_s) {
  const mission::Task* task = loop_.task();
  if (!task) return;
  const mission::StageDecision& d = loop_.output().status.stage;
  const mission::Failsafe failsafe = loop_.output().status.failsafe;
  const std::string key = task->task_id + "/" + mission::to_string(loop_.task_state()) + "/" +
                          std::to_string(d.process_index) + "/" + model::to_string(d.stage) + "/" +
                          mission::to_string(failsafe);
  if (key == reported_key_) return;
  reported_key_ = key;
  // A change on the failsafe ladder is reported with its cause (the task's history keeps
  // it); the others (landed, aborted, ...) with the stage machine's line.
  const bool failsafe_changed = failsafe != reported_failsafe_ && !failsafe_event_.empty() &&
                                (on_ladder(failsafe) || on_ladder(reported_failsafe_));
  reported_failsafe_ = failsafe;
  const std::string message = failsafe == mission::Failsafe::AutopilotControl
                                  ? "failed: " + autopilot_failure_
                              : failsafe_changed ? failsafe_event_
                                                 : loop_.describe();
  msg::TaskStatus status = wire::to_task_status(task->task_id, options_.uav_id, now_s, d,
                                                task->processes.size(), message);
  status.state = wire::to_msg(loop_.task_state());
  task_status_writer_.write(status);
}

void UavAgentNode::log_changes() {
  const mission::ControllerStatus& s = loop_.output().status;
  if (loop_.task()) {
    const std::string stage = std::string(mission::to_string(s.stage.state)) + " process " +
                              std::to_string(s.stage.process_index) + " " +
                              model::to_string(s.stage.stage) + " stage, frame G" +
                              std::to_string(s.stage.reference_ugv);
    if (stage != logged_stage_) {
      spdlog::info("{}", loop_.describe());
      logged_stage_ = stage;
    }
  }
  if (s.failsafe != logged_failsafe_) {
    failsafe_event_ = failsafe_event(s, logged_failsafe_);
    if (s.failsafe == mission::Failsafe::None) {
      spdlog::info("{}", failsafe_event_);
    } else {
      spdlog::warn("{}", failsafe_event_);
    }
    logged_failsafe_ = s.failsafe;
  }
  const bool handover = loop_.output().command.handover;
  if (handover && !logged_handover_) {
    spdlog::warn(
        "handing the UAV over to the flight controller's landing: no relative state "
        "of G{} to land on",
        s.stage.reference_ugv);
  }
  logged_handover_ = handover;
}

}  // namespace cover::uav_agent
