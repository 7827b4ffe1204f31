// cover-ground-station [--port 8080] [--bind 127.0.0.1] [--token-file F]: the operator's page in
// a browser. Serves the page (web/, built into the build folder) and its WebSocket API: the
// fleet as `cover fleet` lists it, the task manager's queue per UAV with each task's progress,
// submit / abort, each UAV's autopilot and its commands with the autopilot's answer, the live
// plots and 3D view, the recorder. A thin adapter: the API and its checks are
// cover_ground_station_api, the server cover_ground_station_web.
#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include <filesystem>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>

#include "cover/dds/cli_options.hpp"
#include "cover/dds/dds_error.hpp"
#include "cover/dds/vendor.hpp"
#include "cover/ground_station/access.hpp"
#include "cover/shm/segment_name.hpp"
#include "cover/startup/startup.hpp"
#include "station.hpp"

namespace {

namespace gs = cover::ground_station;

constexpr const char* kExitCodes =
    "Exit codes: 0 stopped by SIGINT/SIGTERM (its normal end); 1 an unexpected error; 2 usage\n"
    "(a bind address other than loopback without --token-file, an unreadable token file, no\n"
    "page folder); 3 DDS could not start; 4 the port cannot be listened on (in use?).\n"
    "Open the address it prints (with its token) in a browser.";

struct CommandLine {
  int port = 8080;
  std::string bind = "127.0.0.1";
  std::string token_file;
  std::string web_dir;
  std::string record_dir = ".";
  std::string sim_run_id = "default";
  double state_rate_hz = 10.0;
  int max_clients = 16;
  int client_queue_kib = 1024;
  double slow_client_timeout_s = 2.0;
  cover::recording::FleetSize fleet;
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
  app.add_option("--port", cli.port, "TCP port of the page, 0: any free port (printed)")
      ->check(CLI::Range(0, 65535))
      ->capture_default_str();
  app.add_option("--bind", cli.bind,
                 "address to listen on; any but loopback needs --token-file (every request must "
                 "then carry the token)")
      ->capture_default_str();
  app.add_option("--token-file", cli.token_file,
                 "the token (first line, >= 16 characters); without it a new token is made and "
                 "printed once with the page's address");
  app.add_option("--web-dir", cli.web_dir, "the page's files (default: web/ of the build folder)");
  app.add_option("--record-dir", cli.record_dir, "folder of the recordings started from the page")
      ->capture_default_str();
  app.add_option("--run-id", cli.sim_run_id,
                 "the simulator run whose world poses give the page its world frame (segment "
                 "/cover_sim_d<domain>_<run-id> on this host, as the UGV agents')")
      ->capture_default_str();
  app.add_option("--state-rate-hz", cli.state_rate_hz,
                 "rate of the page's fleet, task and plot rows")
      ->check(CLI::Range(1.0, 50.0))
      ->capture_default_str();
  app.add_option("--max-clients", cli.max_clients, "pages served at once")
      ->check(CLI::Range(1, 256))
      ->capture_default_str();
  app.add_option("--client-queue-kib", cli.client_queue_kib,
                 "KiB waiting for one page before its new messages are dropped")
      ->check(CLI::Range(16, 65536))
      ->capture_default_str();
  app.add_option("--slow-client-timeout-s", cli.slow_client_timeout_s,
                 "a page whose queue stays full this long (not reading) is disconnected")
      ->check(CLI::Range(0.1, 60.0))
      ->capture_default_str();
  app.add_option("--uavs", cli.fleet.uavs, "UAV ids 0..N-1 to listen for")->capture_default_str();
  app.add_option("--ugvs", cli.fleet.ugvs, "UGV ids 0..N-1 to listen for")->capture_default_str();
  cli.dds.add_to(app);
}

void check_flags(const CLI::App&, const CommandLine& cli) {
  try {
    cover::shm::segment_name(0, cli.sim_run_id);
  } catch (const std::invalid_argument& e) {
    throw CLI::ValidationError("--run-id", e.what());
  }
  if (!gs::is_loopback(cli.bind) && cli.token_file.empty()) {
    throw CLI::ValidationError("--bind " + cli.bind,
                               "any address but loopback needs --token-file: every request "
                               "from the network must carry the token");
  }
}

int serve(const CommandLine& cli) {
  gs::StationOptions options;
  options.web.address = cli.bind;
  options.web.port = static_cast<std::uint16_t>(cli.port);
  options.web.static_dir = web_dir(cli);
  options.web.max_clients = static_cast<std::size_t>(cli.max_clients);
  options.web.client_queue_bytes = static_cast<std::size_t>(cli.client_queue_kib) * 1024;
  options.web.slow_client_timeout_s = cli.slow_client_timeout_s;
  try {
    options.web.access.token =
        cli.token_file.empty() ? gs::make_token() : gs::read_token_file(cli.token_file);
  } catch (const std::runtime_error& e) {
    std::cerr << "cover-ground-station: " << e.what() << "\n";
    return cover::startup::kExitUsage;
  }
  options.web.access.token_required = !gs::is_loopback(cli.bind);
  options.fleet = cli.fleet;
  options.state_rate_hz = cli.state_rate_hz;
  options.record_dir = cli.record_dir;
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
  const std::string host = cli.bind == "0.0.0.0" || cli.bind == "::" ? "HOST" : cli.bind;
  // Printed once, on stdout: the only place the token is shown.
  std::cout << "ground station: open http://" << host << ":" << station->port()
            << "/?token=" << options.web.access.token << std::endl;
  spdlog::info(
      "serving {} on {}:{} ({}), {} domain {}", options.web.static_dir, cli.bind, station->port(),
      options.web.access.token_required ? "token on every request" : "loopback: token for commands",
      cover::dds::vendor_name(dds.vendor), dds.domain_id);
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
  program.check_flags = [&](const CLI::App& app) { check_flags(app, cli); };
  program.exits = {cover::startup::exit_on<cover::dds::DdsError>(3)};
  return cover::startup::run_main(argc, argv, program, [&](const CLI::App&) { return serve(cli); });
}
