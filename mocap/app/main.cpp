// cover-mocap-relay --config config/mocap.yaml: relative states from a motion-capture
// system. Reads every configured rigid body over VRPN, filters each, and publishes the
// state of every UAV u in every UGV k's frame on cover/uav/<u>/rel/<k> at the mocap rate,
// stamped with the capture time on our clock (docs/mocap.md).
#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include <stdexcept>

#include "cover/config/config_error.hpp"
#include "cover/config/yaml_reader.hpp"
#include "cover/dds/cli_options.hpp"
#include "cover/dds/dds_error.hpp"
#include "cover/logging/log.hpp"
#include "cover/mocap/relay_params.hpp"
#include "cover/startup/startup.hpp"
#include "cover/time_sync/clock_responder.hpp"
#include "relay_node.hpp"

namespace {

constexpr const char* kExitCodes =
    "Exit codes: 0 stopped by SIGINT/SIGTERM (its normal end); 1 an unexpected error (its\n"
    "message on stderr); 2 usage or configuration error (a bad server address, body table or\n"
    "parameter); 3 DDS could not start. A mocap server that is away (at start or later) is\n"
    "waited for, with back-off: never an exit.";

struct CommandLine {
  std::string config_file = cover::config::default_config_dir() + "/mocap.yaml";
  std::string server;
  std::string time_source;
  cover::dds::DdsCliOptions dds;
};

void add_options(CLI::App& app, CommandLine& cli) {
  app.add_option("--config", cli.config_file,
                 "settings (mocap: section: server, up_axis, units, bodies, filter)")
      ->capture_default_str();
  app.add_option("--server", cli.server, "HOST:PORT of the VRPN server (overrides mocap.server)");
  app.add_option("--time-source", cli.time_source,
                 "server: the server's clock is ours (simulator, chrony); offset: estimated "
                 "from arrival times (overrides mocap.time_source)")
      ->check(CLI::IsMember({"server", "offset"}));
  cli.dds.add_to(app);
}

cover::mocap::RelayParams load(const CommandLine& cli) {
  auto params = cover::mocap::RelayParams::load_file(cli.config_file);
  if (!cli.server.empty()) params.server = cli.server;
  if (!cli.time_source.empty()) params.time_source = cli.time_source;
  params.validate();
  return params;
}

cover::vrpn::ClientOptions client_options(const cover::mocap::RelayParams& p) {
  cover::vrpn::ClientOptions o;
  cover::vrpn::parse_server(p.server, o.host, o.port);
  for (const auto& b : p.bodies) o.session.bodies.push_back(b.name);
  o.connect_timeout_s = p.connect_timeout_s;
  o.backoff_min_s = p.backoff_min_s;
  o.backoff_max_s = p.backoff_max_s;
  o.silence_timeout_s = p.silence_timeout_s;
  return o;
}

void log_start(const cover::mocap::RelayParams& p, const cover::dds::ParticipantOptions& dds) {
  spdlog::info("VRPN server {} ({} up, {}), time source {}, {} domain {}", p.server, p.up_axis,
               p.units, p.time_source, cover::dds::vendor_name(dds.vendor), dds.domain_id);
  for (const auto& b : p.bodies) spdlog::info("body {} = '{}'", b.key(), b.name);
  spdlog::info(
      "filter: constant-velocity Kalman, accel {:.1f} m/s^2, position noise {:.4f} m; jump gate "
      "{:.3f} m, lost after {:.0f} ms, frame timeout {:.1f} ms",
      p.filter.accel_noise_m_s2, p.filter.position_noise_m, p.jump_gate_m, p.lost_after_s * 1e3,
      p.frame_timeout_s * 1e3);
}

}  // namespace

int main(int argc, char** argv) {
  CommandLine cli;
  cover::startup::Program program;
  program.name = "cover-mocap-relay";
  program.description =
      "cover-mocap-relay: relative states cover/uav/<u>/rel/<k> from a motion-capture system "
      "(VRPN: NOKOV, Vicon, OptiTrack, Qualisys), for the whole fleet";
  program.exit_codes = kExitCodes;
  program.logger_name = [] { return std::string("mocap_relay"); };
  program.add_flags = [&](CLI::App& app) { add_options(app, cli); };
  program.exits = {cover::startup::exit_on<std::invalid_argument>(2),
                   cover::startup::exit_on<cover::dds::DdsError>(3)};
  return cover::startup::run_main(argc, argv, program, [&](const CLI::App&) {
    const cover::mocap::RelayParams params = load(cli);
    const cover::dds::ParticipantOptions dds = cli.dds.resolve("cover-mocap-relay");
    log_start(params, dds);
    cover::dds::Participant participant(dds);
    // The UAV agents take its relative states: they measure this host's clock.
    cover::time_sync::ClockResponder clock_responder(participant, "cover-mocap-relay");
    cover::mocap::RelayNode node(participant, params, client_options(params));
    node.run();
    return 0;
  });
}
