#pragma once

#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cover/process/child_process.hpp"

// Missions run through cover-launch, by the benchmarks and the integration tests alike.
namespace cover::bench {

// One run of cover-launch, reporting with --json.
struct LaunchRequest {
  std::string launch_file;         // path of the launch file
  int domain = 0;                  // --domain
  std::filesystem::path run_dir;   // --run-dir: the processes' logs, the result, the plot
  std::vector<std::string> flags;  // more of cover-launch's flags (--dds, --clock, --seed)
};

// What a run of cover-launch gave.
struct LaunchOutcome {
  int exit_code = -1;       // -1: it did not end within the timeout
  nlohmann::json result;    // its --json report; discarded (not an object) if it gave none
  std::string stdout_text;  // all it printed on stdout
};

// cover-launch's argv for `request` (the launcher built beside this tree).
std::vector<std::string> launch_argv(const LaunchRequest& request);

// Runs `request` to its end, `timeout` at most for its output and as much for its exit.
// The launcher's own log lines (stderr) go to `log_file`, or to this process's stderr when
// it is empty.
LaunchOutcome run_launcher(const LaunchRequest& request, const std::string& log_file,
                           std::chrono::milliseconds timeout);

// The run's identity that cover-launch writes to <run_dir>/run.json before it starts a
// process (run_id, domain...: tools/cover-launch run_report.hpp), once it is there; nullopt
// when `launch` ends, or `timeout` passes, without it. How a tool beside a launch finds the
// run (the simulator's segment) by what the launch says instead of guessing its id.
std::optional<nlohmann::json> wait_for_run_identity(const std::filesystem::path& run_dir,
                                                    cover::process::ChildProcess& launch,
                                                    std::chrono::milliseconds timeout);

// The launch file config/launch/<launch_name>.yaml.
std::string launch_file_path(const std::string& launch_name);

// One mission through cover-launch (`--json`): the launch file under config/launch/, the
// extra flags, one DDS domain. Returns the launcher's JSON report, or an empty object when
// it gave none. The launcher's log and run directory are removed after a successful run
// and kept (their path on stderr, prefixed with `who`) otherwise, to show why.
nlohmann::json run_launch(const std::string& launch_name, const std::vector<std::string>& flags,
                          int domain, const std::string& who,
                          std::chrono::minutes timeout = std::chrono::minutes(5));

}  // namespace cover::bench
