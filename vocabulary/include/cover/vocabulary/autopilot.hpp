#pragma once

#include <optional>
#include <string>

namespace cover {

// The autopilot firmware a UAV flies on: the one the bridge speaks to (fc_bridge), the one
// the simulator imitates (sim/fc) and the real one in the loop (sim/firmware, firmware_link).
enum class Autopilot { Px4, ArduPilot };

// "px4", "ardupilot": as flags, YAML and JSON name it.
const char* to_string(Autopilot autopilot);
// "PX4", "ArduCopter": as a log line or a table names it.
const char* display_name(Autopilot autopilot);
// "px4" / "ardupilot"; nullopt for anything else.
std::optional<Autopilot> parse_autopilot(const std::string& text);

}  // namespace cover
