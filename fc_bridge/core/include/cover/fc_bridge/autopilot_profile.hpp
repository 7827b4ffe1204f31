#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "cover/vocabulary/autopilot.hpp"

namespace cover::fc_bridge {

// The flight mode as COVER needs to know it (the autopilot's own name comes apart).
enum class FcMode {
  Unknown,   // no HEARTBEAT yet, or a custom mode not mapped
  Offboard,  // PX4 OFFBOARD / ArduPilot GUIDED_NOGPS: COVER's setpoints fly the UAV
  Land,      // the autopilot's own landing
  Manual,    // a pilot flies it (manual, stabilized, altitude, position, acro...)
  Other,     // any other autopilot mode (mission, hold, RTL...)
};
const char* to_string(FcMode mode);

// A COMMAND_LONG's command id and its seven parameters.
struct CommandSpec {
  std::uint16_t command = 0;
  std::array<float, 7> param{};
};

// How one autopilot family is asked for a mode, and how its HEARTBEAT names its mode:
//  PX4:       DO_SET_MODE (1, main mode 6) for OFFBOARD; NAV_LAND for its land mode;
//             custom_mode = main mode << 16 | sub mode << 24.
//  ArduPilot: DO_SET_MODE (1, 20) for GUIDED_NOGPS, (1, 9) for LAND; custom_mode = the
//             Copter flight mode number.
class AutopilotProfile {
 public:
  explicit AutopilotProfile(Autopilot kind) : kind_(kind) {}
  Autopilot kind() const { return kind_; }
  // MAV_AUTOPILOT this family reports in its HEARTBEAT.
  std::uint8_t mav_autopilot() const;
  CommandSpec offboard_command() const;
  CommandSpec land_command() const;
  CommandSpec arm_command(bool arm) const;
  const char* offboard_mode_name() const;  // "OFFBOARD" / "GUIDED_NOGPS"

  // From a HEARTBEAT's base_mode and custom_mode (no custom mode flag: Unknown).
  FcMode decode_mode(std::uint8_t base_mode, std::uint32_t custom_mode) const;
  std::string mode_name(std::uint8_t base_mode, std::uint32_t custom_mode) const;

 private:
  Autopilot kind_;
};

}  // namespace cover::fc_bridge
