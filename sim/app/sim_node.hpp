#pragma once

#include <array>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"
#include "cover/shm/seqlock_writer.hpp"
#include "fleet.hpp"

namespace cover::sim {

enum class SimClockMode { Lockstep, Realtime };

struct SimRunOptions {
  SimClockMode clock = SimClockMode::Lockstep;
  // A standing world (a system that flies whatever tasks it is sent): runs until stopped,
  // whatever the scenario's task and max_duration_s say.
  bool standing = false;
  // A motion-capture outage to inject (docs/failsafes.md): no relative state is published
  // for any UAV from relative_gap_start_s for relative_gap_s of simulated time (< 0: none).
  double relative_gap_start_s = -1.0;
  double relative_gap_s = 0.0;
};

// Why a run ended.
enum class SimExit { Finished, Interrupted, Stalled, StartupTimeout };

// cover-sim's DDS and shared-memory side around the Fleet: publishes relative states
// (as a motion-capture bridge would), the clock and the world segment; takes every UAV
// agent's command and trace.
class SimNode {
 public:
  // `segment` is the world's shared memory; it outlives the node and the participant, so
  // that its removal (which ends the UGV agents' sources) is the simulator's last act.
  SimNode(dds::Participant& participant, shm::SeqlockWriter<SharedWorld>& segment, Fleet& fleet,
          SimRunOptions options, const SimProcessParams& params);
  SimExit run();

  // Sensor-to-command latency samples (realtime), ms.
  const std::vector<double>& latency_ms() const { return latency_ms_; }
  double wall_time_s() const { return wall_time_s_; }
  // The last task status message per UAV (the stage machine's one-line status).
  std::string task_message(int uav) const;

 private:
  struct Mailbox {
    std::optional<msg::UavCommand> command;
    std::optional<msg::ControlTrace> trace;
    std::int64_t command_received_ns = -1;  // monotonic
    std::string task_message;
  };

  bool wait_for_agents();
  bool run_over() const;
  SimExit run_lockstep();
  SimExit run_realtime();
  void publish_tick();
  bool relative_withheld(double t_s);
  enum class TickWait { Answered, Stalled, Interrupted };
  TickWait wait_for_commands(std::int64_t tick_ns);
  void apply_commands(bool lockstep);
  void on_command(int uav, const msg::UavCommand& command);

  Fleet& fleet_;
  SimRunOptions options_;
  SimProcessParams params_;
  shm::SeqlockWriter<SharedWorld>& segment_;
  dds::Writer<msg::SimClock> clock_writer_;
  std::vector<std::vector<dds::Writer<msg::RelativeState>>> relative_writers_;  // [uav][ugv]

  mutable std::mutex mutex_;
  std::condition_variable arrived_;
  std::vector<Mailbox> mailboxes_;
  // Publish time (monotonic ns) of the relative states of recent ticks, by stamp.
  std::array<std::pair<std::int64_t, std::int64_t>, 256> published_{};
  std::vector<double> latency_ms_;
  double wall_time_s_ = 0.0;
  std::uint64_t republished_ticks_ = 0;
  bool in_relative_gap_ = false;

  std::vector<dds::Reader<msg::UavCommand>> command_readers_;
  std::vector<dds::Reader<msg::ControlTrace>> trace_readers_;
  dds::Reader<msg::TaskStatus> task_status_reader_;
};

}  // namespace cover::sim
