#pragma once

#include <yaml-cpp/yaml.h>

#include <map>
#include <string>
#include <vector>

#include "cover/launch/launch_kind.hpp"
#include "cover/launch/respawn_policy.hpp"

namespace cover::launch {

// One process of a launch file, as written (placeholders not yet expanded).
struct ProcessSpec {
  std::string name;        // [A-Za-z0-9_-]+, unique; names the log file <run_dir>/<name>.log
  std::string executable;  // bare name (looked up) or a path (relative to the launch file)
  std::vector<std::string> args;
  std::string dds = "fastdds";  // fastdds | cyclone, given to the child as COVER_DDS
  std::map<std::string, std::string> env;
  // A Linux network namespace (`ip netns`) to run in, e.g. one of scripts/wifi-sim's;
  // empty: the launcher's own network.
  std::string netns;
  // The DDS-Security identity when the launch is secure; empty: by role (see
  // security_identity.hpp).
  std::string identity;
  bool ends_run = false;  // its exit ends the run: exactly one in a mission, at most one else
  // Keys respawn, respawn_delay_s, max_respawns. `respawn` defaults to true in a standing or
  // field launch (except for the ends_run process), false in a mission.
  RespawnPolicy respawn;
  // Standing and field launches: the process is not stopped when the run ends by another
  // process's exit, only by a signal to the launcher (or its own end). Default: true for
  // cover-fc-bridge, whose autopilot must never lose its last line of defence to a
  // sibling's death; false for any other.
  bool keep_running = false;
  // SCHED_FIFO priority (1..99) for the process and its threads; 0: normal scheduling. For
  // the control path on a vehicle (the bridge above the agent): a woken process then runs
  // at once instead of after whatever else the computer runs. Not applied when {clock} is
  // lockstep: a lockstep run never sleeps, and FIFO processes that never sleep starve the
  // rest of the machine.
  int realtime_priority = 0;
  // The CPUs the process and its threads may run on (0-based); empty: any. For the UAV
  // agent: its DDS receive thread then wakes its control thread on the same core instead
  // of across cores (docs/launch.md has the measurement). Like realtime_priority, not
  // applied when {clock} is lockstep. A CPU the machine does not have is left out (logged).
  std::vector<int> cpu_affinity;
};

// A whole local system: `launch:` in a launch file. See config/launch/example.yaml.
struct LaunchFile {
  std::string name;                       // [A-Za-z0-9_.-]+; names the run folder and the run id
  LaunchKind kind = LaunchKind::Mission;  // `kind:`
  double grace_period_s = 3.0;
  std::map<std::string, std::string> variables;  // placeholder defaults
  std::vector<ProcessSpec> processes;            // start order; stopped in reverse
  // A DDS-Security fleet directory (cover security init): every process runs secure with
  // its own identity. Relative to the launch file's folder; empty: plain DDS.
  std::string security;
  // Records the run into <run_dir>/recording.mcap (recording.hpp): `record:`.
  bool record = false;
  // Serves the run live to Foxglove (cover-foxglove-bridge, live_view.hpp): `foxglove:`.
  bool foxglove = false;
  // Serves the operator's page (cover-ground-station, ground_station_view.hpp): `ground_station:`.
  bool ground_station = false;
  std::string directory;  // the launch file's folder, for relative executable paths

  // Throws ConfigError naming the offending process, key or argument.
  void validate() const;

  // Reads the mapping under `launch:`; `context` names the source in errors. A process's
  // `count: "{name}"` takes variable `name`'s value from `overrides` (the --var flags) when
  // given there, else from the file; the copies are made here (process_count.hpp).
  static LaunchFile parse(const YAML::Node& root, const std::string& context,
                          const std::string& directory,
                          const std::map<std::string, std::string>& overrides = {});
  static LaunchFile load_file(const std::string& path,
                              const std::map<std::string, std::string>& overrides = {});
  // throws ConfigError
};

// Placeholders every launch file may use besides its own variables: run_dir, run_id,
// domain, config_dir, state_dir.
const std::vector<std::string>& builtin_placeholders();

// Throws ConfigError unless `value` (of variable `key`, from the file or a --var flag) is
// well formed and uses only built-in placeholders.
void check_variable_value(const std::string& key, const std::string& value);

}  // namespace cover::launch
