// cover-uav-agent --id U: the UAV's process. Plans (MINCO) and controls (SAMPC, 100 Hz) the
// UAV in the UGVs' frames from their relative states and IMUs, publishes the command.
#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include <iostream>

#include "cover/config/config_error.hpp"
#include "cover/config/settings_flags.hpp"
#include "cover/config/yaml_reader.hpp"
#include "cover/dds/cli_options.hpp"
#include "cover/dds/dds_error.hpp"
#include "cover/logging/log.hpp"
#include "cover/mission/task_file.hpp"
#include "cover/sampc/sampc_params.hpp"
#include "cover/startup/startup.hpp"
#include "cover/vocabulary/fleet_size.hpp"
#include "uav_agent_node.hpp"

namespace {

constexpr const char* kExitCodes =
    "Exit codes: 0 stopped by SIGINT/SIGTERM; 1 an unexpected error (its message on stderr);\n"
    "2 usage, configuration or task-file error; 3 DDS could not start.";

struct CommandLine {
  int uav_id = 0;
  std::string task_file;
  std::string clock = "lockstep";
  std::string config_dir = cover::config::default_config_dir();
  std::string method;
  int ugv_count = cover::fleet::kDefaultUgvs;
  bool fc_bridge = false;
  cover::dds::DdsCliOptions dds;
  cover::config::SettingsFlags<cover::uav_agent::UavAgentParams> settings{
      "uav_agent", cover::config::default_config_dir() + "/uav_agent.yaml"};
};

void add_options(CLI::App& app, CommandLine& cli) {
  app.add_option("--id", cli.uav_id, "UAV id U (topics cover/uav/U/...)")
      ->required()
      ->check(CLI::Range(0, 255));
  app.add_option("--task", cli.task_file,
                 "fly this task file (config/tasks/*.yaml format); otherwise wait for one on "
                 "cover/task/request");
  app.add_option("--clock", cli.clock,
                 "lockstep: one step per simulator tick; realtime: the simulator's time, stepping "
                 "on each fresh relative state; system: the host's clock (field)")
      ->check(CLI::IsMember({"lockstep", "realtime", "system"}))
      ->capture_default_str();
  app.add_option(
         "--config-dir", cli.config_dir,
         "folder of mission.yaml, planner.yaml, sampc.yaml, intake.yaml, time_sync.yaml and "
         "uav_agent.yaml (unless --config names another)")
      ->capture_default_str();
  app.add_option("--method", cli.method,
                 "override sampc.yaml's mode: " + cover::sampc::mode_names(" | "));
  app.add_option("--ugv-count", cli.ugv_count, "UGV ids accepted in tasks are 0..N-1")
      ->check(CLI::Range(1, cover::fleet::kMaxUgvs))
      ->capture_default_str();
  app.add_flag("--fc-bridge", cli.fc_bridge,
               "a flight-controller bridge (cover-fc-bridge) flies this UAV: a task starts only "
               "while its autopilot is armed and in OFFBOARD / GUIDED_NOGPS (cover/uav/U/fc), "
               "and fails the moment it is not. Without the flag a bridge heard on that topic "
               "gates tasks all the same");
  cli.settings.add_to(app, {"control_cpu", "spin_after_rehearsal_s", "rehearsal_lead_s"});
  cli.dds.add_to(app);
}

cover::uav_agent::AgentOptions agent_options(CommandLine& cli) {
  cover::uav_agent::AgentOptions options;
  options.uav_id = static_cast<std::uint32_t>(cli.uav_id);
  options.ugv_count = cli.ugv_count;
  options.clock = *cover::sim_clock::parse_clock_mode(cli.clock);
  options.fc_bridge = cli.fc_bridge;
  options.params = cli.settings.load();
  if (!cli.task_file.empty())
    options.task = cover::mission::load_task_file(cli.task_file, cli.ugv_count);
  options.intake = cover::wire::IntakeLimits::load_file(cli.config_dir + "/intake.yaml");
  options.time_sync =
      cover::time_sync::TimeSyncParams::load_file(cli.config_dir + "/time_sync.yaml");
  return options;
}

cover::uav::ControllerConfig controller_config(const CommandLine& cli) {
  cover::uav::ControllerConfig config = cover::uav::ControllerConfig::load(cli.config_dir);
  if (!cli.method.empty()) {
    const auto mode = cover::sampc::parse_mode(cli.method);
    if (!mode) throw cover::config::ConfigError("--method: unknown method '" + cli.method + "'");
    config.sampc.mode = *mode;
  }
  return config;
}

}  // namespace

int main(int argc, char** argv) {
  CommandLine cli;
  cover::startup::Program program;
  program.name = "cover-uav-agent";
  program.description = "cover-uav-agent: one UAV's planner and SAMPC controller over DDS";
  program.exit_codes = kExitCodes;
  program.logger_name = [&] { return "uav_agent" + std::to_string(cli.uav_id); };
  program.add_flags = [&](CLI::App& app) { add_options(app, cli); };
  program.exits = {cover::startup::exit_on<cover::dds::DdsError>(3)};
  return cover::startup::run_main(argc, argv, program, [&](const CLI::App&) {
    cli.settings.default_to(cli.config_dir + "/uav_agent.yaml");
    const cover::uav_agent::AgentOptions options = agent_options(cli);
    cover::uav::ControllerConfig config = controller_config(cli);
    const cover::dds::ParticipantOptions dds =
        cli.dds.resolve("cover-uav-agent-" + std::to_string(cli.uav_id));
    cover::dds::Participant participant(dds);
    spdlog::info("UAV {} on {} domain {}, clock {}, method {}", cli.uav_id,
                 cover::dds::vendor_name(dds.vendor), dds.domain_id, cli.clock,
                 cover::sampc::to_string(config.sampc.mode));
    cover::uav_agent::UavAgentNode node(participant, options, std::move(config));
    return node.run();
  });
}
