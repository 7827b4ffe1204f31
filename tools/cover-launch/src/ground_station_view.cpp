#include "cover/launch/ground_station_view.hpp"

#include <stdexcept>

namespace cover::launch {

ProcessSpec ground_station_spec(const std::optional<LaunchedFleet>& fleet) {
  ProcessSpec spec;
  spec.name = kGroundStationName;
  spec.executable = "cover-ground-station";
  spec.args = fleet_args(fleet);
  // The run's simulator world (its world frame on the page) and the run's folder for the
  // recordings started from the page.
  spec.args.insert(spec.args.end(), {"--run-id={run_id}", "--record-dir={run_dir}"});
  // Its state is the fleet's: a restarted station serves as before (pages reconnect).
  spec.respawn.enabled = true;
  return spec;
}

void add_ground_station(LaunchFile& file) {
  for (const auto& process : file.processes) {
    if (process.name == kGroundStationName) {
      throw std::invalid_argument(
          std::string("ground_station: the launch file already has a process named '") +
          kGroundStationName + "'");
    }
  }
  file.processes.insert(file.processes.begin(), ground_station_spec(launched_fleet(file)));
}

}  // namespace cover::launch
