#include "params_reference.hpp"

#include <algorithm>
#include <cstddef>
#include <sstream>
#include <utility>

#include "cover/config/param_fields.hpp"
#include "cover/fc_bridge/fc_bridge_params.hpp"
#include "cover/foxglove/live_view_params.hpp"
#include "cover/ground_station/station_params.hpp"
#include "cover/mission/mission_params.hpp"
#include "cover/mocap/relay_params.hpp"
#include "cover/planner/planner_params.hpp"
#include "cover/sampc/sampc_params.hpp"
#include "cover/sim/fc/sim_fc_params.hpp"
#include "cover/sim/firmware_uav_params.hpp"
#include "cover/sim/mocap/mocap_server_params.hpp"
#include "cover/sim/scenario.hpp"
#include "cover/sim/world_params.hpp"
#include "cover/task_manager/task_limits.hpp"
#include "cover/time_sync/time_sync_params.hpp"
#include "cover/vocabulary/fleet_size.hpp"
#include "sim_process_params.hpp"
#include "uav_agent_params.hpp"
#include "ugv_agent_params.hpp"

namespace cover::params_reference {
namespace {

constexpr const char* kRegenerate =
    "build/tools/cover-params/cover-params --markdown > docs/parameters.md";

template <typename Params>
Section section(const char* title, const char* header, std::string intro) {
  return {title, header, std::move(intro), config::field_table<Params>()};
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// Lines [from, to) of `lines`, each behind `mark`, at most `limit` of them.
void append_lines(std::string& out, const std::vector<std::string>& lines, std::size_t from,
                  std::size_t to, const char* mark, std::size_t limit) {
  for (std::size_t i = from; i < to && i < from + limit; ++i) out += mark + lines[i] + "\n";
  if (to > from + limit)
    out += mark + std::string("... ") + std::to_string(to - from - limit) + " more lines\n";
}

}  // namespace

std::vector<Section> sections() {
  // The order a reader meets them: the UAV agent's files, the ground side, then the
  // simulator's, then the field hardware's.
  return {
      section<sampc::SampcParams>(
          "SAMPC", "uav_agent/sampc/include/cover/sampc/sampc_params.hpp",
          "`config/sampc.yaml`, section `sampc` (required): the stage-adaptive MPC. Read by "
          "`cover-uav-agent` and the in-process harness (`cover-bench scenario`, `table1`)."),
      section<planner::PlannerParams>(
          "Stage planner", "uav_agent/planner/include/cover/planner/planner_params.hpp",
          "`config/planner.yaml`, section `planner`: the MINCO stage planner. Read by "
          "`cover-uav-agent`, the in-process harness and `cover-plan`."),
      section<mission::MissionParams>(
          "Mission", "uav_agent/mission/include/cover/mission/mission_params.hpp",
          "`config/mission.yaml`, section `mission`: the stage machine, its thresholds and "
          "failsafes. Read by `cover-uav-agent`, `cover-sim` and the in-process harness."),
      section<time_sync::TimeSyncParams>(
          "Time sync", "services/time_sync/include/cover/time_sync/time_sync_params.hpp",
          "`config/time_sync.yaml`, section `time_sync`: clock offsets between hosts "
          "(`docs/time.md`). Read by `cover-uav-agent` (from its configuration folder), "
          "`cover-ugv-agent` and `cover-task-manager` (beside their configuration file; "
          "defaults when there is none)."),
      section<task_manager::TaskLimits>(
          "Task manager", "task_manager/dispatch/include/cover/task_manager/task_limits.hpp",
          "`config/task_manager.yaml`, section `task_manager`: what the task manager accepts "
          "and how long it waits for the agents. Read by `cover-task-manager`."),
      section<uav_agent::UavAgentParams>(
          "UAV agent", "uav_agent/app/params/uav_agent_params.hpp",
          "`config/uav_agent.yaml`, section `uav_agent` (required): the process's own settings "
          "(status period, lockstep waits, the realtime loop's rehearsal, control CPU and "
          "spin). Read by `cover-uav-agent` (from its configuration folder, or `--config`); "
          "`--control-cpu`, `--spin-after-rehearsal-s` and `--rehearsal-lead-s` override "
          "their keys."),
      section<ugv::UgvAgentParams>(
          "UGV agent", "ugv_agent/app/params/ugv_agent_params.hpp",
          "`config/ugv_agent.yaml`, section `ugv_agent` (required): the IMU filter and the "
          "speed estimator as sub-sections. Read by `cover-ugv-agent`; the simulator and the "
          "in-process harness take `imu_filter` and `speed_estimator` from it too, so that "
          "they filter as the agent does."),
      section<sim::WorldParams>(
          "Simulated world", "sim/include/cover/sim/world_params.hpp",
          "`config/sim/world_*.yaml` (top-level mappings `world`, `uav`, `payload`, "
          "`relative_sensor`, `imu`, `odometry`, and the list `ugvs`, below), and the `sim` "
          "mapping of a scenario file. Read by `cover-sim` and the in-process harness."),
      section<sim::UgvParams>(
          "Simulated world: each entry of `ugvs`", "sim/include/cover/sim/world_params.hpp",
          "The world file's list `ugvs` (required, 1 to " + std::to_string(fleet::kMaxUgvs) +
              " entries): each UGV's deck and motion. Read by `cover-sim` and the in-process "
              "harness, with the world."),
      section<sim::Scenario>(
          "Scenario", "sim/closed_loop/include/cover/sim/scenario.hpp",
          "`config/scenarios/*.yaml`, top level. Besides these keys: `sim` (the world, "
          "above), `task` (inline) or `task_file` (relative to the scenario file), and the "
          "list `extra_uavs` (below). Read by `cover-sim` and `cover-bench scenario`."),
      section<sim::ExtraUav>(
          "Scenario: each entry of `extra_uavs`", "sim/closed_loop/include/cover/sim/scenario.hpp",
          "A further UAV in the same world (up to " + std::to_string(fleet::kMaxUavs) +
              " UAVs in all), beside its `task_file` (required, relative to the scenario "
              "file). Read by `cover-sim`."),
      section<sim::SimProcessParams>(
          "Simulator process", "sim/app/params/sim_process_params.hpp",
          "`config/sim/sim_process.yaml`, section `sim_process` (required): lockstep "
          "deadlines and the offboard failsafe. Read by `cover-sim` (`--params`)."),
      section<sim::mocap::MocapServerParams>(
          "Simulated motion capture", "sim/mocap/include/cover/sim/mocap/mocap_server_params.hpp",
          "`config/sim/mocap.yaml`, section `mocap`: the simulator's VRPN server. Read by "
          "`cover-sim --mocap` (`--mocap-config`)."),
      section<sim::fc::SimFcParams>(
          "Simulated flight controllers", "sim/fc/include/cover/sim/fc/sim_fc_params.hpp",
          "`config/sim/sim_fc.yaml`, section `sim_fc` (required): the simulated PX4 / "
          "ArduPilot autopilots. Read by `cover-sim --fc px4|ardupilot` and `--ugv-imu "
          "mavlink` (`--fc-params`)."),
      section<sim::FirmwareUavParams>(
          "Simulated UAV for real firmware", "sim/include/cover/sim/firmware_uav_params.hpp",
          "`config/sim/firmware_uav_px4.yaml` (PX4's SITL iris) and "
          "`firmware_uav_arducopter.yaml` (ArduCopter's quad X), section `firmware_uav` "
          "(required): the motor-level quadrotor a real PX4 / ArduCopter SITL flies, and the "
          "IMU, barometer and magnetometer its estimator reads. Read by the motor-level "
          "plant's tests (tests/sim); the simulator links of issue 32 (PX4's "
          "simulator_mavlink, ArduPilot's JSON backend) are to read it."),
      section<fc_bridge::FcBridgeParams>(
          "Flight-controller bridge", "fc_bridge/core/include/cover/fc_bridge/fc_bridge_params.hpp",
          "`config/fc_bridge.yaml`, section `fc_bridge` (required): the link from a UAV agent "
          "to its PX4 / ArduPilot (`docs/flight-controller.md`). Read by `cover-fc-bridge`."),
      section<mocap::RelayParams>(
          "Motion-capture relay", "mocap/core/include/cover/mocap/relay_params.hpp",
          "`config/mocap.yaml`, section `mocap` (required): a real motion-capture system over "
          "VRPN (`docs/mocap.md`). Besides these keys, the required map `bodies` (`uav<u>` / "
          "`ugv<k>` to the server's body names). Read by `cover-mocap-relay`."),
      section<foxglove::LiveViewParams>(
          "Live view (Foxglove)", "foxglove/params/include/cover/foxglove/live_view_params.hpp",
          "`config/foxglove_bridge.yaml`, section `foxglove`: the Foxglove WebSocket server "
          "(`docs/recording.md`). Read by `cover-foxglove-bridge` (`--config`); a flag given "
          "on its command line overrides its key."),
      section<ground_station::StationParams>(
          "Ground station", "ground_station/params/include/cover/ground_station/station_params.hpp",
          "`config/ground_station.yaml`, section `ground_station`: the operator's page and its "
          "WebSocket API (`docs/ground-station.md`). Read by `cover-ground-station` "
          "(`--config`); a flag given on its command line overrides its key."),
  };
}

std::string markdown() {
  std::string page =
      "# Parameters\n"
      "\n"
      "Generated by `cover-params --markdown` from the parameter structs' declarations: do "
      "not edit by hand; regenerate with `" +
      std::string(kRegenerate) +
      "` (the test `cover_params_docs_check` fails while it differs).\n"
      "\n"
      "Each struct declares its fields once (`services/config/include/cover/config/"
      "param_fields.hpp`): loading, validation, the shipped-file tests and this page walk "
      "the same list. Every key is optional unless marked (required); a key left out takes "
      "the default shown. A dotted key is a nested mapping (`intercept.velocity_nodes` is "
      "`velocity_nodes` under `intercept:`). An unknown key is an error, with its file and "
      "line. The shipped files in `config/` explain each choice in their comments.\n"
      "\n"
      "Not on this page (not declared through `fields()`): `config/dds.yaml` "
      "(`docs/dds-vendors.md`), `config/intake.yaml`, task files (`config/tasks/`, "
      "`docs/tasks.md`) and launch files (`config/launch/`, `docs/launch.md`).\n";
  for (const Section& s : sections()) {
    page += "\n## " + s.title + "\n\n" + s.intro + " Declared in `" + s.header + "`.\n\n" + s.table;
  }
  return page;
}

std::string drift_report(const std::string& committed, const std::string& generated) {
  if (committed == generated) return "";
  const std::vector<std::string> old_lines = lines_of(committed);
  const std::vector<std::string> new_lines = lines_of(generated);
  // One hunk: everything between the common first and last lines.
  std::size_t head = 0;
  while (head < old_lines.size() && head < new_lines.size() && old_lines[head] == new_lines[head]) {
    ++head;
  }
  std::size_t tail = 0;
  while (tail < old_lines.size() - head && tail < new_lines.size() - head &&
         old_lines[old_lines.size() - 1 - tail] == new_lines[new_lines.size() - 1 - tail]) {
    ++tail;
  }
  constexpr std::size_t kContext = 3;
  constexpr std::size_t kShown = 20;
  const std::size_t context_from = head > kContext ? head - kContext : 0;
  std::string out = "docs/parameters.md differs from `cover-params --markdown`:\n";
  out += "--- docs/parameters.md\n+++ cover-params --markdown\n";
  out += "@@ -" + std::to_string(head + 1) + " +" + std::to_string(head + 1) + " @@\n";
  append_lines(out, old_lines, context_from, head, " ", kContext);
  append_lines(out, old_lines, head, old_lines.size() - tail, "-", kShown);
  append_lines(out, new_lines, head, new_lines.size() - tail, "+", kShown);
  const std::size_t context_to = new_lines.size() - tail + std::min(tail, kContext);
  append_lines(out, new_lines, new_lines.size() - tail, context_to, " ", kContext);
  if (old_lines.size() == new_lines.size() && head == old_lines.size()) {
    out += "(the lines agree: the files differ in their final newline)\n";
  }
  out += "Regenerate it (from the repository root, after building cover-params):\n  ";
  out += kRegenerate;
  out += "\n";
  return out;
}

}  // namespace cover::params_reference
