// cover-sim: the simulated world as a process. Runs a scenario's world (UGVs, one plant
// per UAV, sensors), shares it through shared memory, publishes the relative states and
// its clock on DDS, flies the UAV agents' commands and writes the run's result.
#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <vector>

#include "cover/config/config_error.hpp"
#include "cover/config/yaml_reader.hpp"
#include "cover/dds/cli_options.hpp"
#include "cover/dds/dds_error.hpp"
#include "cover/logging/log.hpp"
#include "cover/mission/mission_params.hpp"
#include "cover/process/shutdown_signal.hpp"
#include "cover/shm/segment_name.hpp"
#include "cover/sim/closed_loop.hpp"
#include "cover/sim/closed_loop_report.hpp"
#include "cover/sim/percentile.hpp"
#include "fleet.hpp"
#include "sim_node.hpp"

namespace {

constexpr const char* kExitCodes =
    "Exit codes: 0 every task succeeded; 1 a task failed (the result says which);\n"
    "2 usage or configuration error; 3 DDS or shared memory could not start;\n"
    "4 lockstep stalled or a UAV agent never connected (the log names it); 130 interrupted.";

struct CommandLine {
  std::string scenario = "scenario2";
  std::string clock = "lockstep";
  std::uint64_t seed = 0;
  std::string run_id = "local";
  std::string result_file;
  std::string plot_file;
  std::string summary_file;
  bool standing = false;
  std::vector<double> relative_gap;  // start_s, duration_s
  std::string params_file = cover::config::default_config_dir() + "/sim/sim_process.yaml";
  cover::dds::DdsCliOptions dds;
};

std::string scenario_file(const std::string& name_or_path) {
  if (name_or_path.find('/') != std::string::npos ||
      (name_or_path.size() > 5 && name_or_path.substr(name_or_path.size() - 5) == ".yaml")) {
    return name_or_path;
  }
  return cover::sim::scenario_path(name_or_path);
}

nlohmann::json result_json(cover::sim::Fleet& fleet, const cover::sim::SimNode& node,
                           const CommandLine& cli,
                           std::vector<cover::sim::ClosedLoopResult>& runs) {
  nlohmann::json uavs = nlohmann::json::array();
  bool all_succeeded = true;
  for (int u = 0; u < fleet.uav_count(); ++u) {
    std::string message = node.task_message(u);
    runs.push_back(fleet.result(u, message.empty() ? "no task status received" : message,
                                fleet.reported_state(u)));
    cover::sim::ClosedLoopResult& r = runs.back();
    r.wall_time_s = node.wall_time_s();
    r.realtime_factor = r.wall_time_s > 0.0 ? fleet.time_s() / r.wall_time_s : 0.0;
    nlohmann::json one = cover::sim::summary_json(r);
    one["uav"] = u;
    one["task_id"] = fleet.scenario().task_of(u).task_id;
    uavs.push_back(one);
    all_succeeded = all_succeeded && r.success;
  }
  nlohmann::json out = uavs[0];
  out["success"] = all_succeeded;
  out["scenario"] = fleet.scenario().name;
  out["seed"] = fleet.scenario().world.seed;
  out["clock"] = cli.clock;
  out["speed_factor"] = node.wall_time_s() > 0.0 ? fleet.time_s() / node.wall_time_s() : 0.0;
  if (fleet.uav_count() > 1) out["uavs"] = uavs;
  const auto& latency = node.latency_ms();
  if (!latency.empty()) {
    out["latency_ms"] = {{"p50", cover::sim::percentile(latency, 0.5)},
                         {"p99", cover::sim::percentile(latency, 0.99)},
                         {"samples", latency.size()}};
  }
  return out;
}

int finish(cover::sim::Fleet& fleet, const cover::sim::SimNode& node, const CommandLine& cli) {
  std::vector<cover::sim::ClosedLoopResult> runs;
  const nlohmann::json out = result_json(fleet, node, cli, runs);
  if (!cli.result_file.empty()) {
    std::ofstream(cli.result_file) << out.dump(2) << "\n";
    spdlog::info("result written to {}", cli.result_file);
  }
  if (!cli.plot_file.empty()) {
    cover::sim::write_path_plot(runs[0], fleet.scenario(),
                                fleet.scenario().name + ": " + fleet.scenario().description +
                                    " (processes, " + cli.clock + ")",
                                cli.plot_file);
  }
  std::string summary;
  for (std::size_t u = 0; u < runs.size(); ++u) {
    spdlog::info("UAV {}: {} ({})", u, runs[u].success ? "SUCCESS" : "FAILED", runs[u].status);
    summary += "UAV " + std::to_string(u) + ", task '" +
               fleet.scenario().task_of(static_cast<int>(u)).task_id + "' (" + cli.clock +
               ", processes)\n" + cover::sim::readable_summary(runs[u]);
  }
  if (!cli.summary_file.empty()) std::ofstream(cli.summary_file) << summary;
  return out["success"].get<bool>() ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  cover::process::ShutdownSignal::install();
  CLI::App app{"cover-sim: the simulated world of a scenario, shared over DDS and shared memory"};
  app.footer(kExitCodes);
  CommandLine cli;
  app.add_option("--scenario", cli.scenario, "name in config/scenarios/ or a YAML path")
      ->capture_default_str();
  app.add_option("--clock", cli.clock,
                 "lockstep: advance a tick once every UAV agent answered it (deterministic); "
                 "realtime: wall-clock pace")
      ->check(CLI::IsMember({"lockstep", "realtime"}))
      ->capture_default_str();
  app.add_option("--seed", cli.seed, "world seed (default: the scenario's)");
  app.add_option("--run-id", cli.run_id, "names the shared-memory segment with the DDS domain")
      ->capture_default_str();
  app.add_option("--result", cli.result_file, "write the run's result JSON here at exit");
  app.add_option("--plot", cli.plot_file, "write the world-frame SVG plot here at exit");
  app.add_option("--summary", cli.summary_file, "write the readable result here at exit");
  app.add_flag("--standing", cli.standing,
               "run until stopped (a standing system flying the tasks it is sent), no result");
  app.add_option("--params", cli.params_file, "cover-sim settings")->capture_default_str();
  app.add_option("--relative-gap", cli.relative_gap,
                 "START_S DURATION_S: inject a motion-capture outage, no relative state published "
                 "in that window of simulated time (realtime; in lockstep every tick of it waits "
                 "for the agents' input timeout)")
      ->expected(2);
  cli.dds.add_to(app);
  CLI11_PARSE(app, argc, argv);
  cover::logging::init("sim");
  try {
    cover::sim::Scenario scenario = cover::sim::Scenario::load_file(scenario_file(cli.scenario));
    if (app.count("--seed") > 0) scenario.world.seed = cli.seed;
    const auto params = cover::sim::SimProcessParams::load_file(cli.params_file);
    const auto mission = cover::mission::MissionParams::load_file(
        cover::config::default_config_dir() + "/mission.yaml");
    cover::sim::Fleet fleet(scenario, params, mission);
    const cover::dds::ParticipantOptions dds = cli.dds.resolve("cover-sim");
    cover::sim::SimRunOptions options;
    options.clock = cli.clock == "lockstep" ? cover::sim::SimClockMode::Lockstep
                                            : cover::sim::SimClockMode::Realtime;
    options.standing = cli.standing;
    if (!cli.relative_gap.empty()) {
      if (!(cli.relative_gap[0] >= 0.0 && cli.relative_gap[1] > 0.0)) {
        throw cover::config::ConfigError("--relative-gap: START_S must be >= 0, DURATION_S > 0");
      }
      options.relative_gap_start_s = cli.relative_gap[0];
      options.relative_gap_s = cli.relative_gap[1];
    }
    const std::string segment_name = cover::shm::segment_name(dds.domain_id, cli.run_id);
    // Declared first, removed last: see SimNode.
    cover::shm::SeqlockWriter<cover::sim::SharedWorld> segment(
        segment_name, cover::sim::kWorldSegmentLayoutVersion);
    cover::dds::Participant participant(dds);
    cover::sim::SimNode node(participant, segment, fleet, options, params);
    spdlog::info("{}: {} UAV(s), {} UGV(s), seed {}, clock {}, {} on domain {}, segment {}",
                 scenario.name, fleet.uav_count(), scenario.world.ugvs.size(), scenario.world.seed,
                 cli.clock, cover::dds::vendor_name(dds.vendor), dds.domain_id, segment_name);
    switch (node.run()) {
      case cover::sim::SimExit::Finished:
        return finish(fleet, node, cli);
      case cover::sim::SimExit::Interrupted:
        spdlog::info("interrupted at t = {:.2f} s", fleet.time_s());
        return cli.standing ? 0 : 130;  // a standing world ends by being stopped
      case cover::sim::SimExit::Stalled:
      case cover::sim::SimExit::StartupTimeout:
        return 4;
    }
  } catch (const cover::config::ConfigError& e) {
    std::cerr << "cover-sim: " << e.what() << "\n";
    return 2;
  } catch (const std::invalid_argument& e) {
    std::cerr << "cover-sim: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "cover-sim: " << e.what() << "\n";
    return 3;
  }
  return 0;
}
