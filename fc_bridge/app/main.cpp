// cover-fc-bridge --id U --autopilot px4|ardupilot --url URL: UAV U's link to its flight
// controller over MAVLink, on the companion computer. Turns the UAV agent's commands into
// body-rate + thrust setpoints, handles mode and arming by the autopilot's rules, lands the
// UAV when the agent falls silent, and publishes the autopilot's state.
#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include <iostream>
#include <stdexcept>

#include "cover/config/config_error.hpp"
#include "cover/config/yaml_reader.hpp"
#include "cover/dds/cli_options.hpp"
#include "cover/dds/dds_error.hpp"
#include "cover/fc_bridge/fc_bridge_params.hpp"
#include "cover/logging/log.hpp"
#include "cover/mavlink/connection_url.hpp"
#include "cover/startup/startup.hpp"
#include "cover/time_sync/clock_responder.hpp"
#include "fc_bridge_node.hpp"
#include "signing_key_file.hpp"

namespace {

constexpr const char* kExitCodes =
    "Exit codes: 0 stopped by SIGINT/SIGTERM (its normal end); 1 an unexpected error (its\n"
    "message on stderr); 2 usage or configuration error (a bad URL, parameter or key file);\n"
    "3 DDS or the link could not start (a UDP port taken, a host not found). A serial device "
    "missing at start-up is waited for (it may\n"
    "appear late at boot); a link lost later is opened again until it is back.";

struct CommandLine {
  int uav_id = 0;
  std::string autopilot;
  std::string url;
  std::string params_file = cover::config::default_config_dir() + "/fc_bridge.yaml";
  std::string clock = "system";
  double hover_thrust = 0.0;
  bool auto_arm = false;
  bool real_firmware = false;
  std::string signing_key_file;
  cover::dds::DdsCliOptions dds;
};

void add_options(CLI::App& app, CommandLine& cli) {
  app.add_option("--id", cli.uav_id, "UAV id U (topics cover/uav/U/cmd, cover/uav/U/fc)")
      ->required()
      ->check(CLI::Range(0, 255));
  app.add_option("--autopilot", cli.autopilot,
                 "px4: OFFBOARD mode, NAV_LAND; ardupilot: Copter's GUIDED_NOGPS and LAND")
      ->required()
      ->check(CLI::IsMember({"px4", "ardupilot"}));
  app.add_option("--url", cli.url,
                 "the autopilot, as MAVSDK writes it: udpin://IP:PORT (listen, answer the "
                 "sender), udpout://HOST:PORT, serial:///dev/ttyX:BAUD")
      ->required();
  app.add_option("--params", cli.params_file, "bridge settings (fc_bridge: section)")
      ->capture_default_str();
  app.add_option("--clock", cli.clock,
                 "lockstep: the simulator's ticks; realtime: the simulator's time; system: the "
                 "host's clock (a vehicle). The agent's clock: its command stamps are on it")
      ->check(CLI::IsMember({"lockstep", "realtime", "system"}))
      ->capture_default_str();
  app.add_option("--hover-thrust", cli.hover_thrust,
                 "normalised thrust that hovers, the estimator's start (overrides the params)");
  app.add_flag("--auto-arm", cli.auto_arm,
               "SIMULATION ONLY: request offboard and arm without an operator");
  app.add_flag("--real-firmware", cli.real_firmware,
               "the autopilot is a real firmware (SITL) on cover-sim's physics (cover-sim "
               "--firmware): the simulator's time is 0 until its first tick (the firmware "
               "aligns before it), and in lockstep no wait for the HIGHRES_IMU that closes each "
               "step of COVER's simulated autopilot");
  app.add_option("--signing-key-file", cli.signing_key_file,
                 "MAVLink v2 signing: 64 hex digits; frames written are signed, unsigned or "
                 "wrongly signed frames from the autopilot are refused");
  cli.dds.add_to(app);
}

cover::fc_bridge::NodeOptions node_options(const CommandLine& cli, const CLI::App& app) {
  cover::fc_bridge::NodeOptions options;
  options.uav_id = static_cast<std::uint32_t>(cli.uav_id);
  options.clock = *cover::sim_clock::parse_clock_mode(cli.clock);
  options.step_frames = !cli.real_firmware;
  options.bridge.autopilot = *cover::parse_autopilot(cli.autopilot);
  options.bridge.params = cover::fc_bridge::FcBridgeParams::load_file(cli.params_file);
  if (app.count("--hover-thrust") > 0) options.bridge.params.hover_thrust = cli.hover_thrust;
  if (cli.auto_arm) options.bridge.params.auto_arm = true;
  options.bridge.params.validate();
  if (!cli.signing_key_file.empty()) {
    const auto key = cover::fc_bridge::load_signing_key(cli.signing_key_file);
    options.bridge.signing_key = key;
    options.parser.signing_key = key;
    options.parser.require_signed = true;
  }
  return options;
}

void log_start(const CommandLine& cli, const cover::fc_bridge::NodeOptions& o,
               const cover::dds::ParticipantOptions& dds) {
  const auto& p = o.bridge.params;
  spdlog::info("UAV {}: {} autopilot on {}, clock {}, {} domain {}{}", cli.uav_id, cli.autopilot,
               cli.url, cli.clock, cover::dds::vendor_name(dds.vendor), dds.domain_id,
               o.bridge.signing_key ? ", MAVLink signing on" : "");
  spdlog::info(
      "hover thrust {:.4f} (estimated online within [{:.2f}, {:.2f}]), land after {:.0f} ms "
      "without an agent command, link lost after {:.1f} s without HEARTBEAT",
      p.hover_thrust, p.hover_thrust_min, p.hover_thrust_max, p.cmd_timeout_s * 1e3,
      p.heartbeat_timeout_s);
  if (p.auto_arm) {
    spdlog::warn("*** AUTO-ARM ON: this bridge arms the autopilot BY ITSELF. Simulation only. ***");
  } else {
    spdlog::info("arming only on an operator's request (cover fc arm {})", cli.uav_id);
  }
}

}  // namespace

int main(int argc, char** argv) {
  CommandLine cli;
  cover::startup::Program program;
  program.name = "cover-fc-bridge";
  program.description = "cover-fc-bridge: one UAV's link to its PX4 / ArduPilot flight controller";
  program.exit_codes = kExitCodes;
  program.logger_name = [&] { return "fc_bridge" + std::to_string(cli.uav_id); };
  program.add_flags = [&](CLI::App& app) { add_options(app, cli); };
  program.exits = {cover::startup::exit_on<cover::dds::DdsError>(3)};
  return cover::startup::run_main(argc, argv, program, [&](const CLI::App& app) {
    cover::mavlink::ConnectionUrl url;
    try {
      url = cover::mavlink::ConnectionUrl::parse(cli.url);
    } catch (const std::invalid_argument& e) {
      throw cover::config::ConfigError(std::string("--url: ") + e.what());
    }
    const cover::fc_bridge::NodeOptions options = node_options(cli, app);
    const cover::dds::ParticipantOptions dds =
        cli.dds.resolve("cover-fc-bridge-" + std::to_string(cli.uav_id));
    log_start(cli, options, dds);
    cover::dds::Participant participant(dds);
    cover::time_sync::ClockResponder clock_responder(
        participant, "cover-fc-bridge-" + std::to_string(cli.uav_id));
    cover::fc_bridge::FcBridgeNode node(participant, options, cover::mavlink::make_link(url));
    if (!node.start() && url.kind != cover::mavlink::ConnectionUrl::Kind::Serial) {
      std::cerr << "cover-fc-bridge: the link " << url.to_string() << " could not start\n";
      return 3;
    }
    node.run();
    return 0;
  });
}
