#pragma once

#include <optional>
#include <string>

namespace cover::launch {

// What a launch file runs, which decides what a dying process does to the others
// (`launch.kind`, docs/launch.md):
//  - Mission: one run to its end (a scenario, a test). The ends_run process's exit ends
//    it; any other process that dies for good (without respawn, or with its restarts used
//    up) ends it too, as a failure.
//  - Standing: a system that serves until stopped (simulator, agents, task manager). Every
//    process but the ends_run one is respawned by default; one that dies for good is logged
//    and the others go on. Processes with keep_running outlive the run's end.
//  - Field: a real vehicle's processes (bridge to the autopilot, agents), started at boot;
//    the same rules as Standing.
enum class LaunchKind { Mission, Standing, Field };

// "mission", "standing", "field".
const char* to_string(LaunchKind kind);
std::optional<LaunchKind> parse_launch_kind(const std::string& text);

// Standing and Field: processes serve until stopped, respawned when they die.
inline bool serves_until_stopped(LaunchKind kind) {
  return kind != LaunchKind::Mission;
}

}  // namespace cover::launch
