#pragma once

#include <optional>

#include "cover/launch/launch_file.hpp"
#include "cover/launch/launched_fleet.hpp"

namespace cover::launch {

// The live view a launch adds with `foxglove: true` (or `cover-launch --foxglove`):
// cover-foxglove-bridge on its default port 8765, serving every catalogued topic and the
// 3D scene to Foxglove (docs/recording.md). Started before the run's processes (after the
// recorder), so it is stopped after them and shows the run to its end.
inline constexpr const char* kLiveViewName = "foxglove";

// The bridge's process (a bare executable name: looked up beside the launcher first),
// binding `fleet`'s topics, else every vehicle's.
ProcessSpec live_view_spec(const std::optional<LaunchedFleet>& fleet = std::nullopt);

// Puts the bridge at the front of `file` (behind a recorder added later); throws
// std::invalid_argument when a process of the file already has its name.
void add_live_view(LaunchFile& file);

}  // namespace cover::launch
