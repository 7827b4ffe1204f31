// cover-sim: the simulated world as a process. Runs a scenario's world (UGVs, one plant
// per UAV, sensors), shares it through shared memory, publishes the relative states and
// its clock on DDS, flies the UAV agents' commands and writes the run's result.
#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "cover/config/config_error.hpp"
#include "cover/config/yaml_reader.hpp"
#include "cover/dds/cli_options.hpp"
#include "cover/firmware_link/firmware_kind.hpp"
#include "cover/logging/log.hpp"
#include "cover/mission/mission_params.hpp"
#include "cover/shm/segment_name.hpp"
#include "cover/sim/closed_loop.hpp"
#include "cover/sim/closed_loop_report.hpp"
#include "cover/sim/percentile.hpp"
#include "cover/startup/startup.hpp"
#include "cover/time_sync/clock_responder.hpp"
#include "fleet.hpp"
#include "sim_node.hpp"

namespace {

constexpr const char* kExitCodes =
    "Exit codes: 0 every task succeeded; 1 a task failed (the result says which);\n"
    "2 usage or configuration error; 3 DDS, shared memory or a MAVLink port could not start;\n"
    "4 lockstep stalled or a UAV agent never connected (the log names it); 130 interrupted.";

constexpr int kSimReceiveBufferBytes = 4 << 20;

struct CommandLine {
  std::string scenario = "scenario2";
  std::string clock = "lockstep";
  std::uint64_t seed = 0;
  std::string run_id = "local";
  std::string result_file;
  std::string plot_file;
  std::string summary_file;
  bool standing = false;
  int uavs = 0;  // 0: the scenario's
  int ugvs = 0;
  std::vector<double> relative_gap;  // start_s, duration_s
  std::string params_file = cover::config::default_config_dir() + "/sim/sim_process.yaml";
  // Flight controllers and UGV IMUs over MAVLink.
  std::string fc = "direct";
  std::string fc_params_file = cover::config::default_config_dir() + "/sim/sim_fc.yaml";
  int fc_bind_port_base = 14580;
  int fc_peer_port_base = 14540;
  std::string fc_mode_switch;  // T_S:MODE
  double fc_heartbeat_stop_s = -1.0;
  std::string ugv_imu = "shm";
  int ugv_imu_bind_port_base = 14680;
  int ugv_imu_peer_port_base = 14640;
  // Real firmware (PX4 / ArduCopter SITL) flying the motor-level UAV.
  std::string firmware;
  int firmware_port_base = -1;    // -1: the firmware's own (PX4 4560, ArduPilot 9002)
  std::string firmware_uav_file;  // empty: config/sim/firmware_uav_<firmware>.yaml
  std::string mocap;              // vrpn[:PORT]
  std::string mocap_config = cover::config::default_config_dir() + "/sim/mocap.yaml";
  cover::dds::DdsCliOptions dds;
};

std::string scenario_file(const std::string& name_or_path) {
  if (name_or_path.find('/') != std::string::npos ||
      (name_or_path.size() > 5 && name_or_path.substr(name_or_path.size() - 5) == ".yaml")) {
    return name_or_path;
  }
  return cover::sim::scenario_path(name_or_path);
}

// UAV u's autopilot at the end of the run: its mode, arming, failsafes and link counts.
nlohmann::json autopilot_json(const cover::sim::Fleet& fleet, const cover::sim::SimNode& node,
                              int u) {
  namespace fc = cover::sim::fc;
  const fc::SimulatedAutopilot& autopilot = fleet.autopilot(u);
  nlohmann::json failsafes = nlohmann::json::array();
  nlohmann::json events = nlohmann::json::array();
  for (const fc::AutopilotEvent& e : autopilot.events()) {
    const nlohmann::json one = {
        {"t_s", e.time_s}, {"kind", fc::to_string(e.kind)}, {"text", e.text}};
    if (e.kind == fc::AutopilotEvent::Kind::Failsafe) failsafes.push_back(one);
    events.push_back(one);
  }
  nlohmann::json out = {{"autopilot", cover::to_string(autopilot.profile())},
                        {"system_id", autopilot.system_id()},
                        {"mode", autopilot.mode_name()},
                        {"armed", autopilot.armed()},
                        {"setpoints_accepted", autopilot.setpoints_accepted()},
                        {"setpoints_ignored", autopilot.setpoints_ignored()},
                        {"failsafe_events", failsafes},
                        {"events", events}};
  if (const auto* links = node.autopilot_links()) {
    const cover::mavlink::ParserStats& rx = links->stats(u);
    out["link"] = {{"url", links->describe(u)},         {"frames_received", rx.frames},
                   {"rx_errors", rx.errors()},          {"unknown_ids", rx.unknown_ids},
                   {"sequence_gaps", rx.sequence_gaps}, {"send_failures", links->send_failures(u)}};
  }
  return out;
}

// UAV u's real firmware at the end of the run: its physics link's counts.
nlohmann::json firmware_json(const cover::sim::Fleet& fleet, int u) {
  const cover::firmware_link::FirmwareLink& link = fleet.firmware_link(u);
  const cover::firmware_link::FirmwareLinkStats stats = link.stats();
  return {{"firmware", fleet.firmware_name()},
          {"link", link.describe()},
          {"frames_sent", stats.frames_sent},
          {"answers", stats.answers},
          {"answers_missed", stats.answers_missed},
          {"frames_rejected", stats.frames_rejected},
          {"armed", stats.armed}};
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
    if (fleet.has_autopilots()) one["fc"] = autopilot_json(fleet, node, u);
    if (fleet.has_firmware()) one["firmware"] = firmware_json(fleet, u);
    uavs.push_back(one);
    all_succeeded = all_succeeded && r.success;
  }
  nlohmann::json out = uavs[0];
  out["success"] = all_succeeded;
  out["scenario"] = fleet.scenario().name;
  out["seed"] = fleet.scenario().world.seed;
  out["clock"] = cli.clock;
  out["speed_factor"] = node.wall_time_s() > 0.0 ? fleet.time_s() / node.wall_time_s() : 0.0;
  out["startup_s"] = node.startup_s();
  // What the agents' answers cost the simulator: every command and trace it received.
  const std::uint64_t samples = node.samples_received();
  out["agent_samples"] = {
      {"received", samples},
      {"per_wall_s",
       node.wall_time_s() > 0.0 ? static_cast<double>(samples) / node.wall_time_s() : 0.0},
      {"per_tick", fleet.tick() > 0 ? static_cast<double>(samples) / fleet.tick() : 0.0},
      {"ticks_published_again", node.republished_ticks()},
      {"answers_awaited_again", node.awaited_answers()}};
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

void add_mavlink_options(CLI::App& app, CommandLine& cli) {
  app.add_option(
         "--fc", cli.fc,
         "the UAVs' flight controller: direct (the agent's cover/uav/<u>/cmd flies the "
         "plant), px4 or ardupilot (a simulated autopilot per UAV speaking MAVLink over "
         "UDP; a cover-fc-bridge turns the agent's commands into its setpoints; in lockstep a tick "
         "waits for the SET_ATTITUDE_TARGET whose time_boot_ms is its time)")
      ->check(CLI::IsMember({"direct", "px4", "ardupilot"}))
      ->capture_default_str();
  app.add_option("--fc-params", cli.fc_params_file, "simulated autopilots' settings")
      ->capture_default_str();
  app.add_option("--fc-bind-port-base", cli.fc_bind_port_base,
                 "UAV u's autopilot binds UDP 127.0.0.1:(this + u), as PX4 SITL")
      ->check(CLI::Range(1, 65535))
      ->capture_default_str();
  app.add_option("--fc-peer-port-base", cli.fc_peer_port_base,
                 "UAV u's autopilot sends to 127.0.0.1:(this + u), where its bridge listens")
      ->check(CLI::Range(1, 65535))
      ->capture_default_str();
  app.add_option("--fc-mode-switch", cli.fc_mode_switch,
                 "T_S:MODE: at simulated time T_S the safety pilot switches UAV 0's autopilot to "
                 "MODE (POSCTL, LOITER, MANUAL, STABILIZE, LAND, ...), e.g. 25:POSCTL");
  app.add_option("--fc-heartbeat-stop", cli.fc_heartbeat_stop_s,
                 "T_S: UAV 0's autopilot sends no HEARTBEAT from simulated time T_S (its other "
                 "streams go on)");
  app.add_option("--firmware", cli.firmware,
                 "px4 or ardupilot: each UAV is a motor-level quadrotor flown by a real firmware "
                 "(PX4 SITL's simulator_mavlink on TCP 4560 + u, ArduPilot SITL's JSON backend "
                 "on UDP 9002 + 10 u); its cover-fc-bridge talks to the firmware directly. The "
                 "UGVs hold still until every firmware's estimator has aligned")
      ->check(CLI::IsMember({"px4", "ardupilot"}));
  app.add_option("--firmware-port-base", cli.firmware_port_base,
                 "the first UAV's physics port (default: the firmware's own, 4560 / 9002)")
      ->check(CLI::Range(1, 65535));
  app.add_option("--firmware-uav", cli.firmware_uav_file,
                 "the motor-level UAV and its sensors (default: "
                 "config/sim/firmware_uav_px4.yaml / firmware_uav_arducopter.yaml)");
  app.add_option("--ugv-imu", cli.ugv_imu,
                 "how the UGV agents read their IMU: shm (the world segment) or mavlink (UGV k's "
                 "simulated PX4 rover sends HIGHRES_IMU for every sample over UDP; the segment "
                 "stays)")
      ->check(CLI::IsMember({"shm", "mavlink"}))
      ->capture_default_str();
  app.add_option("--ugv-imu-bind-port-base", cli.ugv_imu_bind_port_base,
                 "UGV k's rover autopilot binds UDP 127.0.0.1:(this + k)")
      ->check(CLI::Range(1, 65535))
      ->capture_default_str();
  app.add_option("--ugv-imu-peer-port-base", cli.ugv_imu_peer_port_base,
                 "UGV k's rover autopilot sends to 127.0.0.1:(this + k) (cover-ugv-agent --source "
                 "mavlink --url udpin://127.0.0.1:PORT)")
      ->check(CLI::Range(1, 65535))
      ->capture_default_str();
}

// A port base plus `count` vehicles stays below 65536.
cover::sim::MavlinkPorts checked_ports(int bind_base, int peer_base, int count,
                                       const std::string& flag) {
  if (bind_base + count > 65536 || peer_base + count > 65536) {
    throw cover::config::ConfigError(flag + ": base + " + std::to_string(count) +
                                     " vehicles passes port 65535");
  }
  return {static_cast<std::uint16_t>(bind_base), static_cast<std::uint16_t>(peer_base)};
}

cover::sim::MavlinkRunOptions mavlink_options(const CommandLine& cli,
                                              const cover::sim::Fleet& fleet,
                                              const cover::sim::fc::SimFcParams& fc_params) {
  cover::sim::MavlinkRunOptions m;
  m.params = fc_params;
  m.autopilot_ports = checked_ports(cli.fc_bind_port_base, cli.fc_peer_port_base, fleet.uav_count(),
                                    "--fc-*-port-base");
  m.ugv_imu = cli.ugv_imu == "mavlink";
  m.ugv_imu_ports = checked_ports(cli.ugv_imu_bind_port_base, cli.ugv_imu_peer_port_base,
                                  fleet.world(0).ugv_count(), "--ugv-imu-*-port-base");
  const bool faults = !cli.fc_mode_switch.empty() || cli.fc_heartbeat_stop_s >= 0.0;
  if (faults && !fleet.has_autopilots()) {
    throw cover::config::ConfigError(
        "--fc-mode-switch / --fc-heartbeat-stop need --fc px4 or --fc ardupilot");
  }
  if (!cli.fc_mode_switch.empty()) {
    const auto colon = cli.fc_mode_switch.find(':');
    std::optional<cover::sim::fc::FlightMode> mode;
    double t_s = -1.0;
    if (colon != std::string::npos) {
      mode = cover::sim::fc::parse_mode_name(cli.fc_mode_switch.substr(colon + 1));
      try {
        t_s = std::stod(cli.fc_mode_switch.substr(0, colon));
      } catch (const std::exception&) {
        t_s = -1.0;
      }
    }
    if (!mode || !(t_s >= 0.0)) {
      throw cover::config::ConfigError(
          "--fc-mode-switch: expected T_S:MODE with T_S >= 0 and MODE one of AUTO.LOITER, BRAKE, "
          "MANUAL, STABILIZE, POSCTL, LOITER, OFFBOARD, GUIDED_NOGPS, LAND, AUTO.LAND (got '" +
          cli.fc_mode_switch + "')");
    }
    m.mode_switch_time_s = t_s;
    m.mode_switch_to = *mode;
  }
  m.heartbeat_stop_time_s = cli.fc_heartbeat_stop_s;
  return m;
}

void add_options(CLI::App& app, CommandLine& cli) {
  app.add_option("--scenario", cli.scenario, "name in config/scenarios/ or a YAML path")
      ->capture_default_str();
  app.add_option("--clock", cli.clock,
                 "lockstep: advance a tick once every UAV agent answered it (deterministic); "
                 "realtime: wall-clock pace")
      ->check(CLI::IsMember({"lockstep", "realtime"}))
      ->capture_default_str();
  app.add_option("--seed", cli.seed, "world seed (default: the scenario's)");
  app.add_option("--uavs", cli.uavs, "fly UAVs 0..N-1 of the scenario (default: all)");
  app.add_option("--ugvs", cli.ugvs, "run UGVs 0..M-1 of the scenario (default: all)");
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
  add_mavlink_options(app, cli);
  app.add_option("--mocap", cli.mocap,
                 "vrpn[:PORT] (3883): serve every vehicle's world pose as a VRPN tracker (ugv<k>, "
                 "uav<u>) instead of publishing the relative states: a cover-mocap-relay makes "
                 "them (docs/mocap.md); the run starts once it is connected");
  app.add_option("--mocap-config", cli.mocap_config,
                 "the simulated mocap system: rate, latency, noise, dropouts, up axis, units")
      ->capture_default_str();
  cli.dds.add_to(app);
}

// The run's options from the command line, checked against the fleet and the settings.
cover::sim::SimRunOptions run_options(const CommandLine& cli, const cover::sim::Fleet& fleet,
                                      const cover::sim::FleetAutopilots& autopilots) {
  cover::sim::SimRunOptions options;
  options.clock = cli.clock == "lockstep" ? cover::sim::SimClockMode::Lockstep
                                          : cover::sim::SimClockMode::Realtime;
  options.standing = cli.standing;
  options.mavlink = mavlink_options(cli, fleet, autopilots.params);
  options.mocap = cover::sim::parse_mocap_option(cli.mocap, cli.mocap_config);
  if (!cli.relative_gap.empty()) {
    if (!(cli.relative_gap[0] >= 0.0 && cli.relative_gap[1] > 0.0)) {
      throw cover::config::ConfigError("--relative-gap: START_S must be >= 0, DURATION_S > 0");
    }
    options.relative_gap_start_s = cli.relative_gap[0];
    options.relative_gap_s = cli.relative_gap[1];
  }
  return options;
}

// Real firmware: the motor-level UAV and one physics link per UAV, bound now.
cover::sim::FleetFirmware fleet_firmware(const CommandLine& cli, int uav_count) {
  namespace link = cover::firmware_link;
  const cover::Autopilot kind = *cover::parse_autopilot(cli.firmware);
  cover::sim::FleetFirmware firmware;
  firmware.name = cover::display_name(kind);
  const std::string file =
      cli.firmware_uav_file.empty()
          ? cover::config::default_config_dir() + "/sim/" + link::firmware_uav_file_name(kind)
          : cli.firmware_uav_file;
  firmware.uav = cover::sim::FirmwareUavParams::load_file(file);
  const int base =
      cli.firmware_port_base > 0 ? cli.firmware_port_base : link::default_port_base(kind);
  if (link::firmware_port(kind, base, uav_count - 1) > 65535) {
    throw cover::config::ConfigError("--firmware-port-base: " + std::to_string(uav_count) +
                                     " UAVs pass port 65535");
  }
  const link::Pacing pacing =
      cli.clock == "lockstep" ? link::Pacing::Lockstep : link::Pacing::Realtime;
  for (int u = 0; u < uav_count; ++u) {
    firmware.links.push_back(link::make_link(kind, u, base, pacing));
  }
  spdlog::info("{} firmware flies each UAV ({}): motor-level UAV from {}", firmware.name,
               link::to_string(pacing), file);
  return firmware;
}

cover::sim::Fleet make_fleet(const CommandLine& cli, const cover::sim::Scenario& scenario,
                             const cover::sim::SimProcessParams& params,
                             const cover::mission::MissionParams& mission,
                             const cover::sim::FleetAutopilots& autopilots) {
  if (cli.firmware.empty()) return cover::sim::Fleet(scenario, params, mission, autopilots);
  if (autopilots.profile) {
    throw cover::config::ConfigError(
        "--firmware and --fc px4|ardupilot: the UAV is flown by a real firmware or by a "
        "simulated autopilot, not both");
  }
  return cover::sim::Fleet(scenario, params, mission, fleet_firmware(cli, scenario.uav_count()));
}

// Runs the world to its end (or until stopped); the exit code.
int run(const CLI::App& app, const CommandLine& cli) {
  cover::sim::Scenario scenario = cover::sim::Scenario::load_file(scenario_file(cli.scenario));
  if (app.count("--seed") > 0) scenario.world.seed = cli.seed;
  if (cli.uavs > 0 || cli.ugvs > 0) {
    scenario.keep_fleet(cli.uavs > 0 ? cli.uavs : scenario.uav_count(),
                        cli.ugvs > 0 ? cli.ugvs : static_cast<int>(scenario.world.ugvs.size()));
  }
  const auto params = cover::sim::SimProcessParams::load_file(cli.params_file);
  const auto mission = cover::mission::MissionParams::load_file(
      cover::config::default_config_dir() + "/mission.yaml");
  cover::sim::FleetAutopilots autopilots;
  autopilots.profile = cover::parse_autopilot(cli.fc);  // nullopt: direct
  const bool mavlink = autopilots.profile || cli.ugv_imu == "mavlink";
  if (mavlink) autopilots.params = cover::sim::fc::SimFcParams::load_file(cli.fc_params_file);
  // In lockstep every step's frames end with a HIGHRES_IMU, which a bridge waits for
  // (docs/flight-controller.md, "Lockstep"): the simulator's contract, not the firmware's.
  if (cli.clock == "lockstep") autopilots.closing = cover::sim::fc::StepClosing::HighresImu;
  cover::sim::Fleet fleet = make_fleet(cli, scenario, params, mission, autopilots);
  cover::dds::ParticipantOptions dds = cli.dds.resolve("cover-sim");
  // Every UAV agent's command and trace arrive on this one socket, and a lockstep tick's
  // answers all at once: sixteen agents overflowed the OS default 208 KiB (commands lost
  // until the lockstep stalled).
  if (dds.receive_buffer_bytes == 0) dds.receive_buffer_bytes = kSimReceiveBufferBytes;
  const cover::sim::SimRunOptions options = run_options(cli, fleet, autopilots);
  const std::string segment_name = cover::shm::segment_name(dds.domain_id, cli.run_id);
  // Declared first, removed last: see SimNode.
  cover::shm::SeqlockWriter<cover::sim::SharedWorld> segment(
      segment_name, cover::sim::kWorldSegmentLayoutVersion);
  cover::dds::Participant participant(dds);
  // The UAV agents take its relative states: they measure its clock (docs/time.md).
  cover::time_sync::ClockResponder clock_responder(participant, "cover-sim");
  cover::sim::SimNode node(participant, segment, fleet, options, params);
  spdlog::info(
      "{}: {} UAV(s), {} UGV(s), seed {}, clock {}, flight controller {}, UGV IMU {}, {} on "
      "domain {}, segment {}",
      scenario.name, fleet.uav_count(), scenario.world.ugvs.size(), scenario.world.seed, cli.clock,
      cli.firmware.empty() ? cli.fc : cli.firmware + " firmware", cli.ugv_imu,
      cover::dds::vendor_name(dds.vendor), dds.domain_id, segment_name);
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
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CommandLine cli;
  cover::startup::Program program;
  program.name = "cover-sim";
  program.description =
      "cover-sim: the simulated world of a scenario, shared over DDS and shared memory; with "
      "--fc px4|ardupilot each UAV has a simulated autopilot speaking MAVLink over UDP";
  program.exit_codes = kExitCodes;
  program.logger_name = [] { return std::string("sim"); };
  program.add_flags = [&](CLI::App& app) { add_options(app, cli); };
  program.exits = {cover::startup::exit_on<std::invalid_argument>(2)};
  program.other_exit = 3;  // DDS, shared memory, a MAVLink port
  return cover::startup::run_main(argc, argv, program,
                                  [&](const CLI::App& app) { return run(app, cli); });
}
