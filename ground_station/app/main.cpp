// cover-ground-station [--config config/ground_station.yaml] [--port 8080] [--bind 127.0.0.1]
// [--token-file F]: the operator's page in a browser. Serves the page (web/, built into the build
// folder) and its WebSocket API: the fleet as `cover fleet` lists it, the task manager's queue per
// UAV with each task's progress, submit / abort, each UAV's autopilot and its commands with the
// autopilot's answer, the live plots and 3D view, the recorder. A thin adapter: the API and its
// checks are cover_ground_station_api, the server cover_ground_station_web.
#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include <filesystem>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>

#include "cover/config/config_error.hpp"
#include "cover/config/settings_flags.hpp"
#include "cover/dds/cli_options.hpp"
#include "cover/dds/dds_error.hpp"
#include "cover/dds/vendor.hpp"
#include "cover/ground_station/access.hpp"
#include "cover/ground_station/station_params.hpp"
#include "cover/shm/segment_name.hpp"
#include "cover/startup/startup.hpp"
#include "station.hpp"

namespace {

namespace gs = cover::ground_station;

constexpr const char* kExitCodes =
    "Exit codes: 0 stopped by SIGINT/SIGTERM (its normal end); 1 an unexpected error; 2 usage or\n"
    "configuration error (a bind address other than loopback without --token-file, an\n"
    "unreadable token file, a bad key in --config); 3 DDS could not start; 4 the port cannot be "
    "listened on (in use?).\n"
    "Open the address it prints (with its token) in a browser.";

struct CommandLine {
  cover::config::SettingsFlags<gs::StationParams> settings{
      "ground_station", cover::config::default_config_dir() + "/ground_station.yaml"};
  std::string web_dir;
  std::string sim_run_id = "default";
  cover::dds::DdsCliOptions dds;
};

std::string self_dir() {
  std::error_code ec;
  const auto self = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::string(".") : self.parent_path().string();
}

// The page's folder: --web-dir, else web/ beside this program (the build folder's).
std::string web_dir(const CommandLine& cli) {
  if (!cli.web_dir.empty()) return cli.web_dir;
  const std::string dir = self_dir();
  for (const std::string& candidate : {dir + "/web", dir + "/../web", dir + "/../../web/dist"}) {
    if (std::filesystem::exists(candidate + "/index.html")) return candidate;
  }
  return dir + "/web";
}

// `cover record` with this process's DDS flags; empty when `cover` is not found.
std::vector<std::string> recorder_argv(const CommandLine& cli,
                                       const cover::dds::ParticipantOptions& dds) {
  const std::string dir = self_dir();
  for (const std::string& candidate : {dir + "/cover", dir + "/../tools/cover/cover"}) {
    if (!std::filesystem::exists(candidate)) continue;
    std::vector<std::string> argv{candidate,  "record",
                                  "--dds",    cover::dds::vendor_name(dds.vendor),
                                  "--domain", std::to_string(dds.domain_id)};
    if (!cli.dds.security_directory.empty()) {
      argv.insert(argv.end(),
                  {"--security", cli.dds.security_directory, "--identity", cli.dds.identity});
    }
    if (!cli.dds.config_path.empty())
      argv.insert(argv.end(), {"--dds-config", cli.dds.config_path});
    if (!cli.dds.profile.empty()) argv.insert(argv.end(), {"--dds-profile", cli.dds.profile});
    return argv;
  }
  return {};
}

void add_options(CLI::App& app, CommandLine& cli) {
  cli.settings.add_to(app, {"port", "bind", "token_file", "record_dir", "state_rate_hz",
                            "push_coalesce_ms", "max_clients", "client_queue_kib",
                            "slow_client_timeout_s", "manager_query_period_s", "uavs", "ugvs"});
  app.add_option("--web-dir", cli.web_dir, "the page's files (default: web/ of the build folder)");
  app.add_option("--run-id", cli.sim_run_id,
                 "the simulator run whose world poses give the page its world frame (segment "
                 "/cover_sim_d<domain>_<run-id> on this host, as the UGV agents')")
      ->capture_default_str();
  cli.dds.add_to(app);
}

// The settings (the file's, the flags given over them), then the checks across them.
gs::StationParams load(const CommandLine& cli) {
  const gs::StationParams p = cli.settings.load();
  try {
    cover::shm::segment_name(0, cli.sim_run_id);
  } catch (const std::invalid_argument& e) {
    throw cover::config::ConfigError(std::string("--run-id: ") + e.what());
  }
  if (!gs::is_loopback(p.bind) && p.token_file.empty()) {
    throw cover::config::ConfigError("bind " + p.bind +
                                     ": any address but loopback needs token_file "
                                     "(--token-file): every request from the network must "
                                     "carry the token");
  }
  return p;
}

int serve(const CommandLine& cli) {
  const gs::StationParams p = load(cli);
  gs::StationOptions options;
  options.web.transport.address = p.bind;
  options.web.transport.port = static_cast<std::uint16_t>(p.port);
  options.web.transport.max_clients = static_cast<std::size_t>(p.max_clients);
  options.web.transport.client_queue_bytes = static_cast<std::size_t>(p.client_queue_kib) * 1024;
  options.web.transport.slow_client_timeout_s = p.slow_client_timeout_s;
  options.web.static_dir = web_dir(cli);
  try {
    options.web.access.token =
        p.token_file.empty() ? gs::make_token() : gs::read_token_file(p.token_file);
  } catch (const std::runtime_error& e) {
    std::cerr << "cover-ground-station: " << e.what() << "\n";
    return cover::startup::kExitUsage;
  }
  options.web.access.token_required = !gs::is_loopback(p.bind);
  options.fleet.uavs = static_cast<std::uint32_t>(p.uavs);
  options.fleet.ugvs = static_cast<std::uint32_t>(p.ugvs);
  options.state_rate_hz = p.state_rate_hz;
  options.push_coalesce_ms = p.push_coalesce_ms;
  options.manager_query_period_s = p.manager_query_period_s;
  options.command_timeout_s = p.command_timeout_s;
  options.record_dir = p.record_dir;
  if (!std::filesystem::exists(options.web.static_dir + "/index.html")) {
    spdlog::warn("no page in {} (build the target ground_station_web): the API is served alone",
                 options.web.static_dir);
  }
  const auto dds = cli.dds.resolve("cover-ground-station");
  options.record_argv = recorder_argv(cli, dds);
  options.dds_domain = dds.domain_id;
  options.sim_run_id = cli.sim_run_id;
  cover::dds::Participant participant(dds);
  std::unique_ptr<gs::Station> station;
  try {
    station = std::make_unique<gs::Station>(participant, options);
  } catch (const std::runtime_error& e) {
    if (dynamic_cast<const cover::dds::DdsError*>(&e) != nullptr) throw;
    std::cerr << "cover-ground-station: " << e.what() << "\n";
    return 4;
  }
  const std::string host = p.bind == "0.0.0.0" || p.bind == "::" ? "HOST" : p.bind;
  // Printed once, on stdout: the only place the token is shown.
  std::cout << "ground station: open http://" << host << ":" << station->port()
            << "/?token=" << options.web.access.token << std::endl;
  spdlog::info(
      "serving {} on {}:{} ({}), {} domain {}, settings {}", options.web.static_dir, p.bind,
      station->port(),
      options.web.access.token_required ? "token on every request" : "loopback: token for commands",
      cover::dds::vendor_name(dds.vendor), dds.domain_id, cli.settings.source());
  station->run();
  const auto stats = station->web_stats();
  spdlog::info("stopped: {} pages served, {} requests refused, {} slow pages dropped",
               stats.connections, stats.refused, stats.slow_disconnects);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CommandLine cli;
  cover::startup::Program program;
  program.name = "cover-ground-station";
  program.description =
      "cover-ground-station: the operator's page in a browser: the fleet, tasks, autopilots, "
      "live plots and 3D view, the recorder";
  program.exit_codes = kExitCodes;
  program.logger_name = [] { return std::string("ground_station"); };
  program.add_flags = [&](CLI::App& app) { add_options(app, cli); };
  program.exits = {cover::startup::exit_on<cover::dds::DdsError>(3)};
  return cover::startup::run_main(argc, argv, program, [&](const CLI::App&) { return serve(cli); });
}
