#pragma once

#include <array>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "autopilot_links.hpp"
#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"
#include "cover/shm/seqlock_writer.hpp"
#include "fleet.hpp"
#include "latency/sensor_latency.hpp"
#include "mocap_link.hpp"
#include "ugv_imu_links.hpp"

namespace cover::sim {

enum class SimClockMode { Lockstep, Realtime };

// The MAVLink side of a run with simulated autopilots (cover-sim --fc px4|ardupilot) and
// of the UGV IMUs served over MAVLink (--ugv-imu mavlink).
struct MavlinkRunOptions {
  MavlinkPorts autopilot_ports{14580, 14540};
  // Faults injected into UAV 0's autopilot at a simulated time (< 0: none): the safety
  // pilot's mode switch, and heartbeats that stop.
  double mode_switch_time_s = -1.0;
  fc::FlightMode mode_switch_to = fc::FlightMode::Position;
  double heartbeat_stop_time_s = -1.0;
  bool ugv_imu = false;
  MavlinkPorts ugv_imu_ports{14680, 14640};
  fc::SimFcParams params;  // the rover autopilots' ids and heartbeat rate (PX4's)
};

struct SimRunOptions {
  SimClockMode clock = SimClockMode::Lockstep;
  // A standing world (a system that flies whatever tasks it is sent): runs until stopped,
  // whatever the scenario's task and max_duration_s say.
  bool standing = false;
  // A motion-capture outage to inject (docs/failsafes.md): no relative state is published
  // for any UAV from relative_gap_start_s for relative_gap_s of simulated time (< 0: none).
  double relative_gap_start_s = -1.0;
  double relative_gap_s = 0.0;
  MavlinkRunOptions mavlink;
  // Served as VRPN trackers to a cover-mocap-relay instead of published (--mocap vrpn).
  MocapRunOptions mocap;
};

// Why a run ended.
enum class SimExit { Finished, Interrupted, Stalled, StartupTimeout };
// Real firmware: its physics link did not connect, or its estimator never aligned, are
// StartupTimeout.

// cover-sim's DDS, shared-memory and MAVLink side around the Fleet: publishes relative
// states (as a motion-capture bridge would), the clock and the world segment; takes every
// UAV agent's trace, and its command either from DDS (the direct path) or as the
// SET_ATTITUDE_TARGET a flight-controller bridge sends the UAV's simulated autopilot.
class SimNode {
 public:
  // `segment` is the world's shared memory; it outlives the node and the participant, so
  // that its removal (which ends the UGV agents' sources) is the simulator's last act.
  // Throws std::runtime_error when a MAVLink port cannot be bound.
  SimNode(dds::Participant& participant, shm::SeqlockWriter<SharedWorld>& segment, Fleet& fleet,
          SimRunOptions options, const SimProcessParams& params);
  ~SimNode();
  // Runs the world; the MAVLink links are stopped when it returns (the fleet's autopilots
  // are then the caller's to read).
  SimExit run();

  // Realtime sensor-to-command latency samples, ms. Direct path: from writing a tick's
  // relative states to taking the agent's command (cover/uav/<u>/cmd) that names them.
  // With autopilots: from writing tick k's relative states to the simulator's reader
  // thread taking off the socket the first SET_ATTITUDE_TARGET whose time_boot_ms is
  // nearest tick k's time (the whole path agent -> DDS -> bridge -> MAVLink), while the
  // agent's task runs.
  const std::vector<double>& latency_ms() const { return latency_.samples_ms(); }
  // What UAV `uav`'s link saw (autopilots only, after run()).
  const AutopilotLinks* autopilot_links() const { return autopilot_links_.get(); }
  // The run's wall time: in lockstep from the first tick every agent answered (before it,
  // startup_s of start-up), in realtime from the start.
  double wall_time_s() const { return wall_time_s_; }
  double startup_s() const { return startup_s_; }
  // Lockstep: ticks published again (some agent's answer missing), and the answers awaited
  // by those publications (each an agent asked to answer again).
  std::uint64_t republished_ticks() const { return republished_ticks_; }
  std::uint64_t awaited_answers() const { return awaited_answers_; }
  // Samples the agents sent the simulator (commands and traces), all received.
  std::uint64_t samples_received() const;
  // The last task status message per UAV (the stage machine's one-line status).
  std::string task_message(int uav) const;

 private:
  struct Mailbox {
    std::optional<msg::UavCommand> command;
    std::optional<msg::ControlTrace> trace;
    std::int64_t command_received_ns = -1;  // monotonic
    std::string task_message;
    // Autopilots: the newest time_boot_ms of a setpoint the autopilot took, and how many.
    std::int64_t setpoint_ms = -1;
    std::uint64_t setpoints = 0;
    std::int64_t setpoint_received_ns = 0;  // monotonic, of the newest
    std::size_t events_logged = 0;
    // Real firmware: as its bridge reports it (cover/uav/<u>/fc).
    bool estimator_ok = false;
    bool firmware_landing = false;  // in its own land mode
  };

  bool wait_for_agents();
  void note_first_tick_answered();
  bool run_over() const;
  SimExit run_lockstep();
  SimExit run_realtime();
  // `awaited` empty: the tick's first publication; otherwise published again for these
  // UAVs, whose answers are missing (only their relative states are written again).
  void publish_tick(const std::vector<std::uint32_t>& awaited = {});
  std::vector<std::uint32_t> unanswered(std::int64_t tick_ns) const;  // mutex_ held
  bool relative_withheld(double t_s);
  enum class TickWait { Answered, Stalled, Interrupted };
  TickWait wait_for_commands(std::int64_t tick_ns);
  void apply_commands(bool lockstep);
  void on_command(int uav, const msg::UavCommand& command);
  void on_trace(int uav, const msg::ControlTrace& trace);
  bool answered(const Mailbox& box, std::int64_t tick_ns) const;
  void log_stall(int uav, const Mailbox& box, std::int64_t tick_ns, double timeout_s) const;
  // Real firmware (sim_node_firmware.cpp).
  bool wait_for_firmware();
  void on_fc_state(int uav, const msg::FcState& state);
  // Steps the firmware alone until every one has aligned; false when one has not within
  // firmware_align_timeout_s of its time (or a stop was asked).
  bool settle_firmware();
  int first_unaligned_uav() const;  // -1: none
  // Autopilots (sim_node_autopilot.cpp); the mutex held where named _locked.
  bool uses_autopilots() const { return fleet_.has_autopilots(); }
  std::int64_t latency_key(std::int64_t relative_stamp_ns) const;
  void start_autopilot_links();
  void set_sim_time();
  void on_autopilot_frame(int uav, const mavlink::Frame& frame);
  void note_setpoint_locked(int uav, std::uint32_t time_boot_ms, std::int64_t received_ns);
  void apply_autopilots();
  void inject_autopilot_faults_locked(double t_s);
  void log_autopilot_events_locked(int uav);
  void send_keepalive_heartbeats();
  void republish_mavlink();
  void publish_ugv_imu(double t_s);

  Fleet& fleet_;
  SimRunOptions options_;
  SimProcessParams params_;
  shm::SeqlockWriter<SharedWorld>& segment_;
  dds::Writer<msg::SimClock> clock_writer_;
  std::vector<std::vector<dds::Writer<msg::RelativeState>>> relative_writers_;  // [uav][ugv]

  mutable std::mutex mutex_;
  std::condition_variable arrived_;
  std::vector<Mailbox> mailboxes_;
  // Lockstep: the tick wait_for_commands waits on (under mutex_). A command or trace wakes
  // it only when it completes that tick's answer: one wake-up per tick, not one per sample.
  std::int64_t awaited_tick_ns_ = -1;
  // Keyed as the path names a tick's states: the direct path's commands by their stamp,
  // the autopilots' setpoints by the tick (latency_key).
  SensorLatency latency_;
  double wall_time_s_ = 0.0;
  double startup_s_ = 0.0;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point stepping_since_;
  std::uint64_t republished_ticks_ = 0;
  std::uint64_t awaited_answers_ = 0;
  bool in_relative_gap_ = false;

  // Autopilots: the simulated time the reader threads stamp frames with (under mutex_).
  double sim_time_s_ = 0.0;
  std::vector<std::chrono::steady_clock::time_point> keepalive_sent_;
  bool mode_switch_done_ = false;
  bool heartbeat_stop_done_ = false;
  std::unique_ptr<UgvImuLinks> ugv_imu_links_;
  std::unique_ptr<MocapLink> mocap_;  // --mocap: the relative states go out as mocap poses

  std::vector<dds::Reader<msg::UavCommand>> command_readers_;
  std::vector<dds::Reader<msg::ControlTrace>> trace_readers_;
  std::vector<dds::Reader<msg::FcState>> fc_state_readers_;  // real firmware
  dds::Reader<msg::TaskStatus> task_status_reader_;
  // Last: its reader threads call into the members above.
  std::unique_ptr<AutopilotLinks> autopilot_links_;
};

}  // namespace cover::sim
