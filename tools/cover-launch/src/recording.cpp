#include "cover/launch/recording.hpp"

#include <cstdlib>
#include <stdexcept>

#include "cover/launch/executable_lookup.hpp"

namespace cover::launch {

std::string recorder_executable() {
  const char* path = std::getenv("PATH");
  if (resolve_executable("cover", "", self_executable_dir(), path != nullptr ? path : "")) {
    return "cover";
  }
  return COVER_CLI_BUILD_PATH;
}

ProcessSpec recorder_spec(const std::string& executable,
                          const std::optional<LaunchedFleet>& fleet) {
  ProcessSpec spec;
  spec.name = kRecorderName;
  spec.executable = executable;
  spec.args = {"record", "-o", std::string("{run_dir}/") + kRecordingFileName};
  const auto bound = fleet_args(fleet);
  spec.args.insert(spec.args.end(), bound.begin(), bound.end());
  spec.respawn.enabled = false;
  // On the launch's usual vendor (Fast DDS; --dds overrides): a Cyclone recorder matches
  // Fast DDS writers ~2 s late, and would miss the start of a lockstep run.
  return spec;
}

void add_recorder(LaunchFile& file, const std::string& executable) {
  for (const auto& process : file.processes) {
    if (process.name == kRecorderName) {
      throw std::invalid_argument(
          std::string("record: the launch file already has a process named '") + kRecorderName +
          "'");
    }
  }
  file.processes.insert(file.processes.begin(), recorder_spec(executable, launched_fleet(file)));
}

}  // namespace cover::launch
