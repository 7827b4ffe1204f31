#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

#include "cover/dds/participant.hpp"
#include "cover/sim_clock/agent_clock.hpp"
#include "cover/time_sync/clock_responder.hpp"
#include "cover/time_sync/offset_monitor.hpp"
#include "cover/time_sync/time_sync_params.hpp"
#include "cover/uav/uav_loop.hpp"
#include "cover/vocabulary/fleet_size.hpp"
#include "cover/wire/intake.hpp"
#include "dds_uav_io.hpp"
#include "fc_gate.hpp"
#include "task_intake.hpp"
#include "uav_agent_params.hpp"

namespace cover::uav_agent {

struct AgentOptions {
  std::uint32_t uav_id = 0;
  int ugv_count = fleet::kDefaultUgvs;
  sim_clock::ClockMode clock = sim_clock::ClockMode::Lockstep;
  std::optional<mission::Task> task;  // from --task FILE; otherwise from cover/task/request
  wire::IntakeLimits intake;          // config/intake.yaml
  UavAgentParams params;              // config/uav_agent.yaml (and its flags)
  // A flight-controller bridge flies this UAV (--fc-bridge): tasks wait for its autopilot
  // even before its first state is heard. Without it, a bridge heard on cover/uav/<u>/fc
  // gates tasks all the same.
  bool fc_bridge = false;
  // config/time_sync.yaml: a task waits while the clock offset to a peer whose samples
  // the agent takes (simulator or mocap relay, UGV agents, its bridge) exceeds the limit.
  time_sync::TimeSyncParams time_sync;
};

// The UAV agent: DDS inputs -> UavLoop -> DDS command, trace, status, task status.
class UavAgentNode {
 public:
  UavAgentNode(dds::Participant& participant, AgentOptions options, uav::ControllerConfig config);
  // Runs until shutdown is requested; returns the process exit code.
  int run();

 private:
  void run_lockstep();
  void run_realtime();
  bool wait_for_relative_state(dds::Reader<msg::RelativeState>& reader, std::uint64_t seen,
                               double period_s);
  static bool spin_for_sample(const dds::Reader<msg::RelativeState>& reader, std::uint64_t seen,
                              std::chrono::steady_clock::time_point until);
  void place_control_thread();
  // Lockstep, before the first tick of a task: every input's publisher matched; false after
  // connect_timeout_s (logged) or on a shutdown request.
  bool connect_inputs();
  void wait_for_inputs(const msg::SimClock& tick);
  void step(double now_s);
  void take_requests(double now_s);
  void accept(const mission::Task& task, double now_s);
  void start(const mission::Task& task, double now_s);
  // Why an accepted task may not start now (the autopilot, the clocks); nullopt: it may.
  std::optional<std::string> start_blocker() const;
  void follow_autopilot(double now_s);
  void publish_held_status(double now_s);
  void publish_status(double now_s);
  void publish_reference_if_replanned();
  void publish_task_status_on_change(double now_s);
  void log_changes();

  AgentOptions options_;
  uav::UavLoop loop_;
  DdsUavInputs inputs_;
  DdsCommandOutput command_;
  dds::Writer<msg::UavStatus> status_writer_;
  dds::Writer<msg::TaskStatus> task_status_writer_;
  dds::Writer<msg::ReferenceTrajectory> reference_writer_;
  TaskIntake intake_;
  FcGate fc_gate_;
  time_sync::ClockResponder clock_responder_;  // the task manager measures this host's clock
  time_sync::OffsetMonitor clock_offsets_;     // this host's clock to the inputs' hosts
  std::optional<mission::Task> held_task_;     // accepted, waiting for start_blocker() to clear
  std::string held_reason_;                    // why it waits (last published)
  std::string autopilot_failure_;              // why the autopilot took the task over
  sim_clock::AgentClock clock_;
  double next_status_s_ = 0.0;
  double last_step_s_ = 0.0;  // time of the last control step (the status stamp between steps)
  std::uint64_t answers_repeated_ = 0;  // lockstep ticks answered again (a lost answer)
  std::int64_t previous_tick_ns_ = -1;  // lockstep: the tick stepped last (its command flew)
  // Realtime: when the last relative state woke the loop (the next is due a period later).
  std::optional<std::chrono::steady_clock::time_point> last_state_arrival_;
  bool spin_allowed_ = false;      // realtime: placed alone on control_cpu, spinning configured
  bool placement_logged_ = false;  // the placement's first outcome is logged, later ones not
  // Where a lockstep run's wall time goes (logged at the end): waiting for the simulator's
  // tick, for that tick's inputs, and the step (of which waiting for a plan due at it).
  struct LockstepTimes {
    std::uint64_t ticks = 0;
    double tick_wait_s = 0.0;
    double input_wait_s = 0.0;
    double step_s = 0.0;
    double plan_wait_s = 0.0;
  } lockstep_times_;
  std::string reported_key_;  // task id, state, process, stage of the last TaskStatus
  std::string logged_stage_;  // stage line last logged
  mission::Failsafe logged_failsafe_ = mission::Failsafe::WaitingForInputs;
  bool logged_handover_ = false;
  std::string failsafe_event_;  // the last failsafe entry or exit, with its cause
  mission::Failsafe reported_failsafe_ = mission::Failsafe::WaitingForInputs;
};

}  // namespace cover::uav_agent
