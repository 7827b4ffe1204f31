#include "cover/launch/live_view.hpp"

#include <stdexcept>

namespace cover::launch {

ProcessSpec live_view_spec(const std::optional<LaunchedFleet>& fleet) {
  ProcessSpec spec;
  spec.name = kLiveViewName;
  spec.executable = "cover-foxglove-bridge";
  spec.args = fleet_args(fleet);
  // Stateless: a restarted bridge serves as before (clients reconnect).
  spec.respawn.enabled = true;
  return spec;
}

void add_live_view(LaunchFile& file) {
  for (const auto& process : file.processes) {
    if (process.name == kLiveViewName) {
      throw std::invalid_argument(
          std::string("foxglove: the launch file already has a process named '") + kLiveViewName +
          "'");
    }
  }
  file.processes.insert(file.processes.begin(), live_view_spec(launched_fleet(file)));
}

}  // namespace cover::launch
