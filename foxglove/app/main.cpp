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
#include "cover/config/settings_flags.hpp"
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
  cover::config::SettingsFlags<cover::foxglove::LiveViewParams> settings{
      "foxglove", cover::config::default_config_dir() + "/foxglove_bridge.yaml"};
  std::vector<std::string> topic_globs;
  cover::dds::DdsCliOptions dds;
};

void add_options(CLI::App& app, CommandLine& cli) {
  cli.settings.add_to(
      app, {"port", "address", "uavs", "ugvs", "client_queue_kib", "slow_client_timeout_s",
            "max_clients", "scene_rate_hz", "deck_size_m"});
  app.add_option("--topics", cli.topic_globs,
                 "serve only topics matching these globs, e.g. 'cover/uav/*' (default: all)");
  cli.dds.add_to(app);
}

cover::foxglove_bridge::BridgeOptions bridge_options(const cover::foxglove::LiveViewParams& p,
                                                     const std::vector<std::string>& globs) {
  cover::foxglove_bridge::BridgeOptions o;
  o.server.transport.address = p.address;
  o.server.transport.port = static_cast<std::uint16_t>(p.port);
  o.server.transport.client_queue_bytes = static_cast<std::size_t>(p.client_queue_kib) * 1024;
  o.server.transport.slow_client_timeout_s = p.slow_client_timeout_s;
  o.server.transport.max_clients = static_cast<std::size_t>(p.max_clients);
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
int serve(const CommandLine& cli) {
  const auto start = std::chrono::steady_clock::now();
  const auto options = bridge_options(cli.settings.load(), cli.topic_globs);
  cover::dds::ParticipantOptions dds = cli.dds.resolve("cover-foxglove-bridge");
  dds.receive_buffer_bytes = kReceiveBufferBytes;
  spdlog::info("{} domain {}, fleet of {} UAVs and {} UGVs, settings {}",
               cover::dds::vendor_name(dds.vendor), dds.domain_id, options.tap.fleet.uavs,
               options.tap.fleet.ugvs, cli.settings.source());
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
  return cover::startup::run_main(argc, argv, program, [&](const CLI::App&) { return serve(cli); });
}
