// cover-firmware: a real firmware (PX4 or ArduCopter SITL) as one of a launch's processes.
// Finds the build (COVER_PX4_SITL / COVER_ARDUPILOT_SITL, or --sitl), starts it on its
// instance number in its own working directory with COVER's parameters, and on SIGINT /
// SIGTERM stops it (SIGKILL after a grace period: PX4 waiting for its simulator ignores
// SIGTERM) and removes what it left in /tmp.
#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <vector>

#include "cover/config/config_error.hpp"
#include "cover/firmware/firmware_build.hpp"
#include "cover/firmware/instance_slot.hpp"
#include "cover/firmware/params_file.hpp"
#include "cover/firmware/sitl_process.hpp"
#include "cover/process/shutdown_signal.hpp"
#include "cover/startup/startup.hpp"
#include "param_assignment.hpp"

namespace {

namespace fw = cover::firmware;
using namespace std::chrono_literals;

constexpr const char* kExitCodes =
    "Exit codes: 0 stopped by SIGINT/SIGTERM; 1 the firmware ended by itself (its console log\n"
    "is named); 2 usage or a bad parameter file; 3 no firmware build, or it could not start.";

struct CommandLine {
  std::string firmware;
  int instance = 0;
  std::string workdir;
  std::string physics = "cover";
  std::vector<std::string> param_files;
  std::vector<std::string> params;
  std::string sitl;
};

void add_flags(CLI::App& app, CommandLine& cli) {
  app.add_option("firmware", cli.firmware, "px4 or ardupilot")
      ->required()
      ->check(CLI::IsMember({"px4", "ardupilot"}));
  app.add_option("--instance", cli.instance,
                 "SITL instance N: system id N + 1, its ports shifted by N (PX4) or 10 N "
                 "(ArduPilot)")
      ->check(CLI::Range(0, 9))
      ->capture_default_str();
  app.add_option("--workdir", cli.workdir,
                 "where the firmware writes (parameters, logs, eeprom) and its console.log")
      ->required();
  app.add_option("--physics", cli.physics,
                 "cover: cover-sim is its physics (PX4 simulator_mavlink on TCP 4560 + N, "
                 "ArduPilot JSON on UDP 9002 + 10 N); builtin: its own (PX4 SIH, ArduPilot's "
                 "quad model)")
      ->check(CLI::IsMember({"cover", "builtin"}))
      ->capture_default_str();
  app.add_option("--params", cli.param_files,
                 "a file of `NAME value` lines (config/firmware/), applied in order");
  app.add_option("--param", cli.params, "NAME=VALUE, after the files");
  app.add_option("--sitl", cli.sitl,
                 "the SITL build directory (default: $COVER_PX4_SITL / $COVER_ARDUPILOT_SITL)");
}

fw::FirmwareParams collect_params(const CommandLine& cli) {
  fw::FirmwareParams params;
  for (const std::string& file : cli.param_files) {
    try {
      for (auto& p : fw::read_params_file(file)) params.push_back(std::move(p));
    } catch (const std::runtime_error& e) {
      throw cover::config::ConfigError(e.what());  // a bad file is a usage error
    }
  }
  for (const std::string& text : cli.params) params.push_back(fw::parse_param_assignment(text));
  return params;
}

std::optional<fw::FirmwareBuild> find_build(const CommandLine& cli, cover::Autopilot firmware) {
  const char* variable =
      firmware == cover::Autopilot::Px4 ? "COVER_PX4_SITL" : "COVER_ARDUPILOT_SITL";
  if (!cli.sitl.empty()) ::setenv(variable, cli.sitl.c_str(), 1);
  const fw::FirmwareLookup lookup =
      firmware == cover::Autopilot::Px4 ? fw::find_px4_sitl() : fw::find_arducopter_sitl();
  if (!lookup.build) spdlog::error("{}", lookup.missing);
  return lookup.build;
}

fw::SitlProcess start(const CommandLine& cli, cover::Autopilot firmware,
                      const fw::FirmwareBuild& build, fw::InstanceSlot slot,
                      const fw::FirmwareParams& params) {
  const std::filesystem::path workdir = std::filesystem::absolute(cli.workdir);
  const bool builtin = cli.physics == "builtin";
  if (firmware == cover::Autopilot::Px4) {
    return builtin ? fw::SitlProcess::start_px4(build, std::move(slot), workdir, params)
                   : fw::SitlProcess::start_px4_hil(build, std::move(slot), workdir, params);
  }
  return builtin ? fw::SitlProcess::start_arducopter(build, std::move(slot), workdir, params)
                 : fw::SitlProcess::start_arducopter_json(build, std::move(slot), workdir, params);
}

int run(const CommandLine& cli) {
  const cover::Autopilot firmware = *cover::parse_autopilot(cli.firmware);  // CLI11 checked it
  const fw::FirmwareParams params = collect_params(cli);
  const std::optional<fw::FirmwareBuild> build = find_build(cli, firmware);
  if (!build) return 3;
  fw::InstanceSlot slot = fw::InstanceSlot::claim(firmware, cli.instance, cli.instance);
  fw::SitlProcess sitl = start(cli, firmware, *build, std::move(slot), params);
  spdlog::info(
      "{} SITL instance {} started (pid {}, {} physics, {} parameters), system id {}; "
      "its console: {}",
      cover::display_name(firmware), sitl.instance(), sitl.pid(), cli.physics, params.size(),
      sitl.system_id(), sitl.console_log().string());
  while (!cover::process::ShutdownSignal::wait_for(200ms)) {
    if (!sitl.running()) {
      const int code = sitl.stop();
      spdlog::error("{} SITL instance {} ended by itself (exit {}); see {}",
                    cover::display_name(firmware), sitl.instance(), code,
                    sitl.console_log().string());
      return 1;
    }
  }
  const int code = sitl.stop(5s);
  spdlog::info("{} SITL instance {} stopped (exit {})", cover::display_name(firmware),
               sitl.instance(), code);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CommandLine cli;
  cover::startup::Program program;
  program.name = "cover-firmware";
  program.description =
      "cover-firmware: a real PX4 or ArduCopter SITL instance as a launch process "
      "(docs/flight-controller.md, \"Real firmware in COVER's world\")";
  program.exit_codes = kExitCodes;
  program.logger_name = [] { return std::string("firmware"); };
  program.add_flags = [&](CLI::App& app) { add_flags(app, cli); };
  program.other_exit = 3;
  return cover::startup::run_main(argc, argv, program, [&](const CLI::App&) { return run(cli); });
}
