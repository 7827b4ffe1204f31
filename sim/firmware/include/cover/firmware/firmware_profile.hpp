#pragma once
// What a firmware run (the firmware tests, cover-bench firmware) needs to know of each
// autopilot, in one place: how to start it for COVER, its modes as its HEARTBEAT says them,
// its land command, the parameter that times its own offboard-loss failsafe, its hover thrust.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "cover/firmware/firmware_build.hpp"
#include "cover/firmware/firmware_monitor.hpp"
#include "cover/firmware/sitl_process.hpp"
#include "cover/mavlink/messages.hpp"
#include "cover/mavlink/protocol.hpp"

namespace cover::firmware {

namespace mav = cover::mavlink;

struct FirmwareProfile {
  Autopilot firmware = Autopilot::Px4;
  std::string bridge_autopilot;  // cover-fc-bridge --autopilot
  // What COVER needs of it (docs/flight-controller.md), given at its start.
  FirmwareParams flight_params;
  // Values the parameter check must report as wrong, and the names it must give.
  FirmwareParams wrong_params;
  std::vector<std::string> wrong_names;
  std::vector<std::string> blocking_names;  // those that must hold COVER's tasks
  // The bridge's hover-thrust estimate starts here, about 10 % above the firmware's own
  // hover thrust, so the test sees it learn (the field's 20 % is the design case; 10 %
  // keeps the climb-out short).
  double bridge_hover_start = 0.0;
  // The bridge's own settings for this vehicle (keys of config/fc_bridge.yaml's fc_bridge
  // section), given to it with --params.
  FirmwareParams bridge_params;
  // The parameter that times the firmware's own reaction to lost setpoints.
  std::string offboard_loss_param;
  // The mode a ground station or a safety pilot's switch selects (DO_SET_MODE custom main
  // and sub mode), and its name as the bridge reports it.
  float pilot_mode_main = 0.0F;
  float pilot_mode_sub = 0.0F;
  std::string pilot_mode_name;
  // PX4 sends an integer parameter's bytes in PARAM_VALUE's float (PARAM_ENCODE_BYTEWISE).
  bool bytewise_params = false;
  // The streams the bridge must ask for and receive (message id).
  std::vector<std::uint32_t> needed_streams;
  // Its instance numbers: 4..9 leave 0..3 to a developer's own SITL runs.
  int first_instance = 4;
  int last_instance = 9;
};

FirmwareProfile px4_sih_profile();
FirmwareProfile arducopter_profile();

bool in_offboard(Autopilot firmware, const mav::Heartbeat& heartbeat);
bool in_land(Autopilot firmware, const mav::Heartbeat& heartbeat);
inline bool armed(const mav::Heartbeat& heartbeat) {
  return (heartbeat.base_mode & mav::mav_mode_flag::kSafetyArmed) != 0;
}
// The bridge's land command as it goes on the wire (PX4 NAV_LAND; ArduCopter DO_SET_MODE
// LAND).
bool is_land_command(Autopilot firmware, const mav::CommandLong& command);
// A command that takes or gives the vehicle: a mode change, arming, landing.
bool is_control_command(const mav::CommandLong& command);

// The normalised thrust that hovers the firmware's vehicle, as its parameters say:
// PX4 SIH: m g / (4 T_max) from SIH_MASS and SIH_T_MAX (SIH's rotor thrust is T_max times
// the motor command, linear); ArduCopter: MOT_THST_HOVER, which it learns in flight under
// its own altitude control (MOT_HOVER_LEARN 2). Read over the monitor's link; nullopt when
// it does not answer.
std::optional<double> firmware_hover_thrust(Autopilot firmware, FirmwareMonitor& monitor);

}  // namespace cover::firmware
