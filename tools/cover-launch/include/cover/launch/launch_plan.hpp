#pragma once

#include <sys/types.h>

#include <map>
#include <string>
#include <vector>

#include "cover/launch/dds_override.hpp"
#include "cover/launch/launch_file.hpp"
#include "cover/launch/respawn_policy.hpp"

namespace cover::launch {

// What the command line adds to a launch file.
struct LaunchOptions {
  std::vector<DdsOverride> dds_overrides;        // applied in order
  std::map<std::string, std::string> variables;  // override the file's variables
  int domain_id = 0;                             // 0..232
  std::string run_dir;                           // absolute or relative to the cwd
  // A DDS-Security fleet directory (absolute or relative to the cwd); replaces the file's
  // launch.security. Empty: the file's.
  std::string security_directory;
  bool record = false;    // --record: as the file's `record: true`
  bool foxglove = false;  // --foxglove: as the file's `foxglove: true`
  bool ground_station = false;  // --ground-station: as the file's `ground_station: true`
  // --dds-profile / $COVER_DDS_PROFILE: the config/dds.yaml profile every process uses; one
  // naming a discovery_server adds the server (discovery_server.hpp). Empty: none.
  std::string dds_profile;
  pid_t launcher_pid = 0;
};

// One process ready to spawn: placeholders expanded, executable not yet resolved.
struct PlannedProcess {
  std::string name;
  std::string executable;  // as in the file
  std::vector<std::string> args;
  std::string dds;
  std::string netns;  // empty: the launcher's network namespace
  // "KEY=value": the file's env, COVER_DDS, COVER_DDS_DOMAIN, and when secure
  // COVER_DDS_SECURITY and COVER_DDS_IDENTITY.
  std::vector<std::string> env;
  std::string identity;  // DDS-Security identity; empty: plain DDS
  bool ends_run = false;
  RespawnPolicy respawn;
  bool keep_running = false;  // standing / field: outlives the run's end (not a signal)
  // SCHED_FIFO priority to start it with (0: normal); the file's, unless {clock} is
  // lockstep (then 0, and realtime_priority_withheld holds the file's).
  int realtime_priority = 0;
  int realtime_priority_withheld = 0;
  // The CPUs to pin it to (empty: any); the file's, unless {clock} is lockstep (then
  // empty, and cpu_affinity_withheld holds the file's).
  std::vector<int> cpu_affinity;
  std::vector<int> cpu_affinity_withheld;
};

struct LaunchPlan {
  std::string name;
  LaunchKind kind = LaunchKind::Mission;
  std::string run_id;
  std::string run_dir;
  std::string launch_dir;
  int domain_id = 0;
  std::string security_directory;  // absolute; empty: plain DDS
  // The user's state directory ({state_dir}, config/state_dir.hpp) when the file or a flag
  // uses it, created before anything starts; empty otherwise.
  std::string state_dir;
  // Every variable's value as the processes get it (flags applied, built-in placeholders
  // expanded): the run's report names them, e.g. where the task database is.
  std::map<std::string, std::string> variables;
  double grace_period_s = 3.0;
  std::vector<PlannedProcess> processes;
};

// Applies `options` to `file` and expands every variable and argument. Throws
// std::invalid_argument on a bad override, domain or variable (a usage error), and
// config::ConfigError when {state_dir} is used and the user has none.
LaunchPlan make_plan(LaunchFile file, const LaunchOptions& options);

}  // namespace cover::launch
