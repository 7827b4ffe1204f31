#pragma once

#include <optional>

#include "cover/launch/launch_file.hpp"
#include "cover/launch/launched_fleet.hpp"

namespace cover::launch {

// The operator's page a launch adds with `ground_station: true` (or `cover-launch
// --ground-station`): cover-ground-station on 127.0.0.1:8080, which prints its address with
// the token into its log. Started before the run's processes, so it shows the run to its end.
inline constexpr const char* kGroundStationName = "ground_station";

// The station's process (a bare executable name: looked up beside the launcher first),
// listening for `fleet`'s vehicles, else the default fleet size.
ProcessSpec ground_station_spec(const std::optional<LaunchedFleet>& fleet = std::nullopt);

// Puts the station at the front of `file`; throws std::invalid_argument when a process of
// the file already has its name.
void add_ground_station(LaunchFile& file);

}  // namespace cover::launch
