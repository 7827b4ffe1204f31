#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "cover/launch/launch_file.hpp"

namespace cover::launch {

// The vehicles a launch runs: UAV ids 0..uavs-1, UGV ids 0..ugvs-1.
struct LaunchedFleet {
  std::uint32_t uavs = 0;
  std::uint32_t ugvs = 0;
};

// The fleet a mission or standing launch runs, from the `--id N` of its vehicle processes
// (cover-uav-agent and cover-fc-bridge: UAVs; cover-ugv-agent: UGVs); none for a field
// launch (the other vehicles run elsewhere) or when a vehicle process's id is not a number
// written in the file. A recorder or live view binding only these vehicles' topics keeps
// ~20 readers instead of the whole fleet's 80, and Fast DDS checks every reader of a
// participant for each sample it receives.
std::optional<LaunchedFleet> launched_fleet(const LaunchFile& file);

// `--uavs N --ugvs M` for a process that binds a fleet's topics; none without a fleet.
std::vector<std::string> fleet_args(const std::optional<LaunchedFleet>& fleet);

}  // namespace cover::launch
