#pragma once

#include <optional>
#include <string>

#include "cover/launch/launch_file.hpp"
#include "cover/launch/launched_fleet.hpp"

namespace cover::launch {

// The flight recorder a launch adds with `record: true` (or `cover-launch --record`):
// `cover record` into <run_dir>/recording.mcap, every catalogued topic. It is the first
// process, so it is stopped last (SIGINT: it closes the file with its summary) and hears
// the run to its end.
inline constexpr const char* kRecorderName = "recorder";
inline constexpr const char* kRecordingFileName = "recording.mcap";

// `cover` beside the launcher, then on $PATH, then the one of this build tree.
std::string recorder_executable();

// The recorder's process, never respawned (a restart would truncate the recording);
// binding `fleet`'s topics, else every vehicle's.
ProcessSpec recorder_spec(const std::string& executable,
                          const std::optional<LaunchedFleet>& fleet = std::nullopt);

// Puts the recorder first in `file`; throws std::invalid_argument when a process of the
// file already has its name.
void add_recorder(LaunchFile& file, const std::string& executable);

}  // namespace cover::launch
