// cover-ugv-agent: one process per UGV. Reads UGV k's raw IMU (the simulator's shared
// memory, a CSV replay, or a device driver), filters it and publishes cover/ugv/<k>/imu at
// the IMU's rate and cover/ugv/<k>/status as a heartbeat. See ugv_agent/README.md.
#include <unistd.h>
#include <CLI/CLI.hpp>

#include <chrono>
#include <memory>
#include <optional>

#include "cover/config/config_error.hpp"
#include "cover/config/yaml_reader.hpp"
#include "cover/dds/cli_options.hpp"
#include "cover/dds/participant.hpp"
#include "cover/logging/log.hpp"
#include "cover/mavlink/connection_url.hpp"
#include "cover/process/shutdown_signal.hpp"
#include "cover/shm/segment_name.hpp"
#include "cover/startup/startup.hpp"
#include "cover/time_sync/clock_responder.hpp"
#include "cover/time_sync/offset_monitor.hpp"
#include "cover/time_sync/peer_name.hpp"
#include "cover/vocabulary/fleet_size.hpp"
#include "imu_publisher.hpp"
#include "source_factory.hpp"
#include "ugv_agent.hpp"

namespace {

using namespace cover::ugv;  // a .cpp file: the agent's own names

struct CommandLine {
  SourceOptions source;
  std::string config_path = cover::config::default_config_dir() + "/ugv_agent.yaml";
  cover::dds::DdsCliOptions dds;
};

void add_options(CLI::App& app, CommandLine& cli) {
  app.add_option("--id", cli.source.ugv_id,
                 "UGV index k: reads UGV k's IMU, publishes cover/ugv/k/*")
      ->required()
      ->check(CLI::Range(0, cover::fleet::kMaxUgvs - 1));
  app.add_option("--source", cli.source.kind,
                 "Where the raw IMU comes from: sim (the simulator's shared memory), csv "
                 "(replay --csv FILE) or mavlink (the UGV's autopilot at --url)")
      ->check(CLI::IsMember({"sim", "csv", "mavlink"}))
      ->capture_default_str();
  app.add_option("--run-id", cli.source.run_id,
                 "sim: the simulator run to attach to; with the DDS domain it names the "
                 "segment /cover_sim_d<domain>_<run-id>")
      ->capture_default_str();
  app.add_option("--csv", cli.source.csv_path, "csv: the file to replay (docs/imu_csv.md)")
      ->check(CLI::ExistingFile);
  app.add_option("--replay-rate", cli.source.replay_rate,
                 "csv: replay X times faster than real time")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--url", cli.source.mavlink_url,
                 "mavlink: the autopilot's link, udpin://IP:PORT (listen), udpout://HOST:PORT or "
                 "serial:///dev/ttyX:BAUD; reads HIGHRES_IMU (SCALED_IMU when that is all)");
  app.add_option("--mavlink-stamp", cli.source.mavlink_stamp,
                 "mavlink: stamp samples with the autopilot's time (the simulator: simulated "
                 "time) or their receive time on this host's system clock (the field)")
      ->check(CLI::IsMember({"autopilot", "receive"}))
      ->capture_default_str();
  app.add_option("--config", cli.config_path, "Agent parameters (section ugv_agent)")
      ->capture_default_str();
  cli.dds.add_to(app);
}

// Checks what CLI11 cannot express; throws CLI::ValidationError.
void check_combination(const CommandLine& cli) {
  if (cli.source.kind == "csv" && cli.source.csv_path.empty()) {
    throw CLI::ValidationError("--source csv needs --csv FILE");
  }
  if (cli.source.kind != "csv" && !cli.source.csv_path.empty()) {
    throw CLI::ValidationError("--csv is only for --source csv");
  }
  if (cli.source.kind == "mavlink" && cli.source.mavlink_url.empty()) {
    throw CLI::ValidationError("--source mavlink needs --url URL (e.g. udpin://0.0.0.0:14640)");
  }
  if (cli.source.kind != "mavlink" && !cli.source.mavlink_url.empty()) {
    throw CLI::ValidationError("--url is only for --source mavlink");
  }
}

// The simulator may start after its agents: wait for its segment, but stay responsive to
// SIGINT/SIGTERM meanwhile. False when shutdown was requested first.
bool wait_for_segment(const std::string& name, double wait_s) {
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::duration<double>(wait_s);
  const std::string path = cover::shm::segment_path(name);
  while (::access(path.c_str(), F_OK) != 0 && std::chrono::steady_clock::now() < give_up) {
    if (cover::process::ShutdownSignal::wait_for(std::chrono::milliseconds(100))) return false;
  }
  return true;
}

int run(const CommandLine& cli) {
  UgvAgentParams params;
  cover::dds::ParticipantOptions dds_options;
  SourceOptions source_options = cli.source;
  cover::time_sync::TimeSyncParams time_sync;
  try {
    params = UgvAgentParams::load_file(cli.config_path);
    time_sync = cover::time_sync::TimeSyncParams::load_beside(cli.config_path);
    dds_options = cli.dds.resolve("cover-ugv-agent-" + std::to_string(cli.source.ugv_id));
    source_options.dds_domain = dds_options.domain_id;
    if (source_options.kind == "sim") {
      cover::shm::segment_name(source_options.dds_domain, source_options.run_id);  // checks
    }
    if (source_options.kind == "mavlink") {
      cover::mavlink::ConnectionUrl::parse(source_options.mavlink_url);  // checks
    }
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return kExitUsage;
  }

  cover::dds::Participant participant(dds_options);
  // The UAV agents take this UGV's IMU: they measure this host's clock, and this agent
  // logs its offset to them (docs/time.md).
  const std::string process = "cover-ugv-agent-" + std::to_string(cli.source.ugv_id);
  // It asks the clocks of the UAV agents that ask its own (those that take its IMU), not
  // every UAV agent of the fleet.
  cover::time_sync::OffsetMonitor clock_offsets(participant, {process, {}, time_sync, true});
  cover::time_sync::ClockResponder clock_responder(
      participant, process, [&clock_offsets](const std::string& asker) {
        if (cover::time_sync::peer_matches(asker, {"cover-uav-agent-*"})) {
          clock_offsets.add_peer(asker.substr(asker.rfind('/') + 1));
        }
      });
  ImuPublisher publisher(participant, static_cast<std::uint32_t>(cli.source.ugv_id));
  std::unique_ptr<ImuSource> source;
  try {
    if (source_options.kind == "sim") {
      const std::string name =
          cover::shm::segment_name(source_options.dds_domain, source_options.run_id);
      spdlog::info("waiting up to {} s for segment {}", params.segment_wait_s, name);
      if (!wait_for_segment(name, params.segment_wait_s)) {
        spdlog::info("shutdown requested while waiting for the simulator");
        return kExitOk;
      }
    }
    source = make_source(source_options, params);
  } catch (const std::exception& e) {
    spdlog::error("IMU source failed: {}", e.what());
    return kExitSourceFailed;
  }
  spdlog::info("started: source {}, DDS {} on domain {}, nominal IMU {} Hz", source->describe(),
               cover::dds::vendor_name(participant.vendor()), participant.domain_id(),
               params.nominal_imu_rate_hz);
  UgvAgent agent(params, std::move(source), publisher);
  return agent.run();
}

}  // namespace

int main(int argc, char** argv) {
  CommandLine cli;
  cover::startup::Program program;
  program.name = "cover-ugv-agent";
  program.description =
      "cover-ugv-agent: UGV k's IMU publisher. Reads the raw IMU, runs the IMU filter "
      "(config section ugv_agent.imu_filter) and publishes every accepted sample on "
      "cover/ugv/<k>/imu, plus a heartbeat on cover/ugv/<k>/status.\n"
      "Exit codes: 0 stopped (SIGINT/SIGTERM) or replay finished, 1 an unexpected error (its "
      "message on stderr), 2 usage or configuration error (a malformed --url too), 3 the IMU "
      "source failed (no segment within segment_wait_s, malformed CSV, simulator gone, MAVLink "
      "port taken).";
  program.logger_name = [&] { return "ugv_agent" + std::to_string(cli.source.ugv_id); };
  program.add_flags = [&](CLI::App& app) { add_options(app, cli); };
  program.check_flags = [&](const CLI::App&) { check_combination(cli); };
  return cover::startup::run_main(argc, argv, program, [&](const CLI::App&) { return run(cli); });
}
