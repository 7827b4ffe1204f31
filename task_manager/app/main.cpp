// cover-task-manager: accepts tasks from ground stations, persists them (SQLite), keeps one
// queue per UAV, dispatches each to its UAV agent when it is free, follows it to the end.
#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include "cover/config/config_error.hpp"
#include "cover/config/state_dir.hpp"
#include "cover/config/yaml_reader.hpp"
#include "cover/dds/cli_options.hpp"
#include "cover/dds/dds_error.hpp"
#include "cover/logging/log.hpp"
#include "cover/startup/startup.hpp"
#include "cover/task_manager/store_error.hpp"
#include "cover/time_sync/offset_monitor.hpp"
#include "cover/vocabulary/fleet_size.hpp"
#include "manager_node.hpp"

namespace {

constexpr const char* kExitCodes =
    "Exit codes: 0 stopped by SIGINT/SIGTERM; 1 an unexpected error (its message on stderr);\n"
    "2 usage or configuration error;\n"
    "3 the database cannot be opened (path, permissions, a newer schema, no state directory for\n"
    "the default one) or DDS cannot start.";

// tasks.db in the user's state directory, which is created if missing: never the folder
// the manager happens to be started from (issue 31). No such directory is a database that
// cannot be opened (exit 3), not a configuration error.
std::string default_database() {
  try {
    const std::string dir = cover::config::default_state_dir();
    cover::config::create_state_dir(dir);
    return dir + "/tasks.db";
  } catch (const cover::config::ConfigError& e) {
    throw cover::task_manager::StoreError(std::string("default database: ") + e.what());
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::string db_path;  // empty: tasks.db in the user's state directory
  std::string config_path = cover::config::default_config_dir() + "/task_manager.yaml";
  cover::task_manager::ManagerOptions options;
  cover::dds::DdsCliOptions dds;
  cover::startup::Program program;
  program.name = "cover-task-manager";
  program.description =
      "cover-task-manager: task queues per UAV, persisted, dispatched and followed";
  program.exit_codes = kExitCodes;
  program.logger_name = [] { return std::string("task_manager"); };
  program.add_flags = [&](CLI::App& app) {
    app.add_option("--db", db_path,
                   "SQLite database (created if missing; WAL, synchronous FULL); default "
                   "$XDG_STATE_HOME/cover/tasks.db, else ~/.local/state/cover/tasks.db");
    app.add_option("--config", config_path, "limits and timeouts")->capture_default_str();
    app.add_option("--uavs,--max-uavs", options.max_uavs, "UAV ids 0..N-1 are served")
        ->check(CLI::Range(1, cover::fleet::kMaxUavs))
        ->capture_default_str();
    app.add_option("--ugvs,--max-ugvs", options.max_ugvs,
                   "UGV ids 0..N-1 are heard and may be named in tasks")
        ->check(CLI::Range(1, cover::fleet::kMaxUgvs))
        ->capture_default_str();
    dds.add_to(app);
  };
  program.exits = {cover::startup::exit_on<cover::task_manager::StoreError>(3),
                   cover::startup::exit_on<cover::dds::DdsError>(3)};
  return cover::startup::run_main(argc, argv, program, [&](const CLI::App&) {
    const auto limits = cover::task_manager::TaskLimits::load_file(config_path);
    if (db_path.empty()) db_path = default_database();
    cover::task_manager::TaskStore store(db_path);
    const auto participant_options = dds.resolve("cover-task-manager");
    cover::dds::Participant participant(participant_options);
    // The manager judges the agents' samples: it measures its clock against theirs and
    // logs the offsets (docs/time.md).
    cover::time_sync::OffsetMonitor clock_offsets(
        participant, {"cover-task-manager",
                      {"cover-uav-agent-*", "cover-ugv-agent-*", "cover-fc-bridge-*"},
                      cover::time_sync::TimeSyncParams::load_beside(config_path)});
    const auto active = store.in_states(
        {cover::task_manager::TaskState::Dispatched, cover::task_manager::TaskState::Running});
    spdlog::info("database {} (schema {}): {} task(s) in flight to re-learn; {} on domain {}",
                 db_path, store.schema_version(), active.size(),
                 cover::dds::vendor_name(participant_options.vendor),
                 participant_options.domain_id);
    cover::task_manager::ManagerNode node(participant, store, limits, options);
    return node.run();
  });
}
