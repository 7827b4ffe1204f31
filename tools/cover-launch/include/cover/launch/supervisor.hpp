#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "cover/launch/launch_plan.hpp"

namespace cover::launch {

// What became of one process of a run.
struct ProcessOutcome {
  std::string name;
  std::string dds;
  std::optional<int> pid;        // the latest one; none when it was never started
  std::optional<int> exit_code;  // of the latest run; 128 + signal when killed by a signal
  std::string stopped_by;        // "", "SIGINT", "SIGTERM" or "SIGKILL": the last one sent
  int respawns = 0;              // restarts after a death (respawn: true)
  std::optional<double> cpu_s;   // CPU time (user + system) of the latest run, once it ended
  std::optional<std::int64_t> max_rss_kib;  // its peak resident memory, KiB, once it ended
  int realtime_priority = 0;  // the SCHED_FIFO priority it runs at; 0: normal scheduling
  std::vector<int> cpus;      // the CPUs it was pinned to (cpu_affinity); empty: any
};

struct RunOutcome {
  int exit_code = 0;   // the launcher's, see exit_codes.hpp
  std::string reason;  // one sentence for the summary
  std::vector<ProcessOutcome> processes;
  std::vector<std::string> leftover_segments;  // removed from /dev/shm
};

// Starts the plan's processes in order, each with its log in the run folder and in a
// session of its own, watches them until the run is over (the ends_run process exits,
// SIGINT/SIGTERM reaches the launcher through ShutdownSignal, or, in a mission, another
// process dies for good), then stops the survivors one after another in reverse start
// order: SIGINT, grace period, SIGTERM, grace period, SIGKILL. A process with respawn: true
// that dies is restarted after its delay instead, up to max_respawns times; one waiting for
// its restart when the run ends is not restarted. In a standing or field launch a process
// that dies for good is logged and the others go on, and keep_running processes outlive a
// run that ended without a signal, watched until a signal comes or they end. Finally
// removes /dev/shm entries named with the run id. Logs every decision.
RunOutcome supervise(const LaunchPlan& plan);

}  // namespace cover::launch
