// cover-foxglove-bridge [--config config/foxglove_bridge.yaml] [--port 8765]: the live view. Serves
// every catalogued topic of the fleet over the Foxglove WebSocket protocol (CDR as on the wire, OMG
// IDL schemas), and Foxglove's own 3D types (cover/foxglove/tf, cover/foxglove/scene) from the
// relative states and references, so Foxglove's 3D panel shows the UGV frames, the UAVs, the decks
// and the reference paths without configuration (docs/recording.md).
#include <spdlog/spdlog.h>
#include <sys/resource.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "bridge_node.hpp"
#include "cover/config/config_error.hpp"
#include "cover/config/yaml_reader.hpp"
#include "cover/dds/cli_options.hpp"
#include "cover/dds/dds_error.hpp"
#include "cover/foxglove/live_view_params.hpp"
#include "cover/logging/log.hpp"
#include "cover/startup/startup.hpp"

namespace {

constexpr const char* kExitCodes =
    "Exit codes: 0 stopped by SIGINT/SIGTERM (its normal end); 1 an unexpected error (its\n"
    "message on stderr); 2 usage or configuration error; 3 DDS could not start; 4 the port\n"
    "cannot be listened on (in use?).\n"
    "Open it in Foxglove: Open connection -> Foxglove WebSocket -> ws://HOST:PORT.";

// As the recorder's: bursts of many topics at once are not lost in the socket.
constexpr int kReceiveBufferBytes = 8 * 1024 * 1024;

double cpu_seconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

struct CommandLine {
  std::string config_file = cover::config::default_config_dir() + "/foxglove_bridge.yaml";
  cover::foxglove::LiveViewParams flags;  // the flags given (the others are not read)
  std::vector<std::string> topic_globs;
  cover::dds::DdsCliOptions dds;
};

void add_options(CLI::App& app, CommandLine& cli) {
  auto& f = cli.flags;
  app.add_option("--config", cli.config_file,
                 "settings (foxglove: section); the flags below override its keys")
      ->capture_default_str();
  app.add_option("--port", f.port, "TCP port, 0: any free port, logged (foxglove.port)");
  app.add_option("--address", f.address, "address to listen on (foxglove.address)");
  app.add_option("--uavs", f.uavs, "UAV ids 0..N-1 to serve topics of (foxglove.uavs)");
  app.add_option("--ugvs", f.ugvs, "UGV ids 0..N-1 to serve topics of (foxglove.ugvs)");
  app.add_option("--topics", cli.topic_globs,
                 "serve only topics matching these globs, e.g. 'cover/uav/*' (default: all)");
  app.add_option("--client-queue-kib", f.client_queue_kib,
                 "KiB waiting for one client before its new messages are dropped "
                 "(foxglove.client_queue_kib)");
  app.add_option("--slow-client-timeout-s", f.slow_client_timeout_s,
                 "a client whose queue stays full this long (not reading) is disconnected "
                 "(foxglove.slow_client_timeout_s)");
  app.add_option("--max-clients", f.max_clients,
                 "connections served at once (foxglove.max_clients)");
  app.add_option("--scene-rate-hz", f.scene_rate_hz,
                 "rate of cover/foxglove/tf and cover/foxglove/scene (foxglove.scene_rate_hz)");
  app.add_option("--deck-size-m", f.deck_size_m,
                 "side of the deck drawn per UGV (foxglove.deck_size_m)");
  cli.dds.add_to(app);
}

// The file's settings, then each flag given on top of them, then the bounds.
cover::foxglove::LiveViewParams load(const CLI::App& app, const CommandLine& cli) {
  auto p = cover::foxglove::LiveViewParams::load_file(cli.config_file);
  const auto& f = cli.flags;
  auto given = [&](const char* flag) { return app.count(flag) > 0; };
  if (given("--port")) p.port = f.port;
  if (given("--address")) p.address = f.address;
  if (given("--uavs")) p.uavs = f.uavs;
  if (given("--ugvs")) p.ugvs = f.ugvs;
  if (given("--client-queue-kib")) p.client_queue_kib = f.client_queue_kib;
  if (given("--slow-client-timeout-s")) p.slow_client_timeout_s = f.slow_client_timeout_s;
  if (given("--max-clients")) p.max_clients = f.max_clients;
  if (given("--scene-rate-hz")) p.scene_rate_hz = f.scene_rate_hz;
  if (given("--deck-size-m")) p.deck_size_m = f.deck_size_m;
  p.validate();
  return p;
}

cover::foxglove_bridge::BridgeOptions bridge_options(const cover::foxglove::LiveViewParams& p,
                                                     const std::vector<std::string>& globs) {
  cover::foxglove_bridge::BridgeOptions o;
  o.server.address = p.address;
  o.server.port = static_cast<std::uint16_t>(p.port);
  o.server.client_queue_bytes = static_cast<std::size_t>(p.client_queue_kib) * 1024;
  o.server.slow_client_timeout_s = p.slow_client_timeout_s;
  o.server.max_clients = static_cast<std::size_t>(p.max_clients);
  o.tap.fleet.uavs = static_cast<std::uint32_t>(p.uavs);
  o.tap.fleet.ugvs = static_cast<std::uint32_t>(p.ugvs);
  o.tap.topic_globs = globs;
  o.scene_rate_hz = p.scene_rate_hz;
  o.scene.uavs = o.tap.fleet.uavs;
  o.scene.ugvs = o.tap.fleet.ugvs;
  o.scene.deck_size_m = p.deck_size_m;
  o.scene.stale_after_s = p.stale_after_s;
  return o;
}

// Serves until SIGINT/SIGTERM; the exit code.
int serve(const CLI::App& app, const CommandLine& cli) {
  const auto start = std::chrono::steady_clock::now();
  const auto options = bridge_options(load(app, cli), cli.topic_globs);
  cover::dds::ParticipantOptions dds = cli.dds.resolve("cover-foxglove-bridge");
  dds.receive_buffer_bytes = kReceiveBufferBytes;
  spdlog::info("{} domain {}, fleet of {} UAVs and {} UGVs, settings {}",
               cover::dds::vendor_name(dds.vendor), dds.domain_id, options.tap.fleet.uavs,
               options.tap.fleet.ugvs, cli.config_file);
  cover::dds::Participant participant(dds);
  std::unique_ptr<cover::foxglove_bridge::BridgeNode> node;
  try {
    node = std::make_unique<cover::foxglove_bridge::BridgeNode>(participant, options);
  } catch (const std::runtime_error& e) {
    if (dynamic_cast<const cover::dds::DdsError*>(&e) != nullptr) throw;
    std::cerr << "cover-foxglove-bridge: " << e.what() << "\n";
    return 4;
  }
  node->run();
  node.reset();
  const double elapsed_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  spdlog::info("bridge CPU {:.3f} s over {:.3f} s: {:.1f} % of one core", cpu_seconds(), elapsed_s,
               100.0 * cpu_seconds() / std::max(elapsed_s, 1e-9));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CommandLine cli;
  cover::startup::Program program;
  program.name = "cover-foxglove-bridge";
  program.description =
      "cover-foxglove-bridge: the live view. Every catalogued topic of the fleet and "
      "Foxglove's 3D types (UGV frames, UAVs, decks, reference paths) over the Foxglove "
      "WebSocket protocol";
  program.exit_codes = kExitCodes;
  program.logger_name = [] { return std::string("foxglove_bridge"); };
  program.add_flags = [&](CLI::App& app) { add_options(app, cli); };
  program.exits = {cover::startup::exit_on<cover::dds::DdsError>(3)};
  return cover::startup::run_main(argc, argv, program,
                                  [&](const CLI::App& app) { return serve(app, cli); });
}
