// cover-foxglove-bridge [--port 8765]: the live view. Serves every catalogued topic of the
// fleet over the Foxglove WebSocket protocol (CDR as on the wire, OMG IDL schemas), and
// Foxglove's own 3D types (cover/foxglove/tf, cover/foxglove/scene) from the relative
// states and references, so Foxglove's 3D panel shows the UGV frames, the UAVs, the decks
// and the reference paths without configuration (docs/recording.md).
#include <spdlog/spdlog.h>
#include <sys/resource.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <iostream>
#include <stdexcept>

#include "bridge_node.hpp"
#include "cover/config/config_error.hpp"
#include "cover/dds/cli_options.hpp"
#include "cover/dds/dds_error.hpp"
#include "cover/logging/log.hpp"
#include "cover/process/shutdown_signal.hpp"

namespace {

constexpr const char* kExitCodes =
    "Exit codes: 0 stopped by SIGINT/SIGTERM (its normal end); 2 usage or configuration\n"
    "error; 3 DDS could not start; 4 the port cannot be listened on (in use?).\n"
    "Open it in Foxglove: Open connection -> Foxglove WebSocket -> ws://HOST:PORT.";

// As the recorder's: bursts of many topics at once are not lost in the socket.
constexpr int kReceiveBufferBytes = 8 * 1024 * 1024;

double cpu_seconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

}  // namespace

int main(int argc, char** argv) {
  cover::process::ShutdownSignal::install();
  CLI::App app{
      "cover-foxglove-bridge: the live view. Every catalogued topic of the fleet and "
      "Foxglove's 3D types (UGV frames, UAVs, decks, reference paths) over the Foxglove "
      "WebSocket protocol"};
  app.footer(kExitCodes);
  cover::foxglove_bridge::BridgeOptions options;
  std::size_t queue_kib = options.server.client_queue_bytes / 1024;
  app.add_option("--port", options.server.port, "TCP port (0: any free port, logged)")
      ->capture_default_str();
  app.add_option("--address", options.server.address, "address to listen on")
      ->capture_default_str();
  app.add_option("--uavs", options.tap.fleet.uavs, "UAV ids 0..N-1 to serve topics of")
      ->check(CLI::Range(1u, 64u))
      ->capture_default_str();
  app.add_option("--ugvs", options.tap.fleet.ugvs, "UGV ids 0..N-1 to serve topics of")
      ->check(CLI::Range(1u, 64u))
      ->capture_default_str();
  app.add_option("--topics", options.tap.topic_globs,
                 "serve only topics matching these globs, e.g. 'cover/uav/*' (default: all)");
  app.add_option("--client-queue-kib", queue_kib,
                 "bytes waiting for one client before its new messages are dropped (KiB)")
      ->check(CLI::Range(64, 1024 * 1024))
      ->capture_default_str();
  app.add_option("--slow-client-timeout-s", options.server.slow_client_timeout_s,
                 "a client whose queue stays full this long (not reading) is disconnected")
      ->check(CLI::Range(0.1, 3600.0))
      ->capture_default_str();
  app.add_option("--max-clients", options.server.max_clients, "connections served at once")
      ->check(CLI::Range(1, 256))
      ->capture_default_str();
  app.add_option("--scene-rate-hz", options.scene_rate_hz,
                 "rate of cover/foxglove/tf and cover/foxglove/scene")
      ->check(CLI::Range(0.1, 100.0))
      ->capture_default_str();
  app.add_option("--deck-size-m", options.scene.deck_size_m, "side of the deck drawn per UGV")
      ->check(CLI::Range(0.1, 20.0))
      ->capture_default_str();
  cover::dds::DdsCliOptions dds_cli;
  dds_cli.add_to(app);
  CLI11_PARSE(app, argc, argv);
  cover::logging::init("foxglove_bridge");
  options.server.client_queue_bytes = queue_kib * 1024;
  options.scene.uavs = options.tap.fleet.uavs;
  options.scene.ugvs = options.tap.fleet.ugvs;
  const auto start = std::chrono::steady_clock::now();
  try {
    cover::dds::ParticipantOptions dds = dds_cli.resolve("cover-foxglove-bridge");
    dds.receive_buffer_bytes = kReceiveBufferBytes;
    spdlog::info("{} domain {}, fleet of {} UAVs and {} UGVs", cover::dds::vendor_name(dds.vendor),
                 dds.domain_id, options.tap.fleet.uavs, options.tap.fleet.ugvs);
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
    // What the bridge cost, for cover-bench record's share of a core during a run.
    const double elapsed_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    spdlog::info("bridge CPU {:.3f} s over {:.3f} s: {:.1f} % of one core", cpu_seconds(),
                 elapsed_s, 100.0 * cpu_seconds() / std::max(elapsed_s, 1e-9));
    return 0;
  } catch (const cover::config::ConfigError& e) {
    std::cerr << "cover-foxglove-bridge: " << e.what() << "\n";
    return 2;
  } catch (const cover::dds::DdsError& e) {
    std::cerr << "cover-foxglove-bridge: " << e.what() << "\n";
    return 3;
  }
}
