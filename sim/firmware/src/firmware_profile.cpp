#include "cover/firmware/firmware_profile.hpp"

#include <chrono>

#include "cover/firmware/params_file.hpp"
#include "cover/mavlink/state_messages.hpp"

namespace cover::firmware {
namespace {

using namespace std::chrono_literals;
constexpr double kStandardGravity_m_s2 = 9.80665;  // SIH's CONSTANTS_ONE_G
constexpr auto kParamTimeout = 5s;

}  // namespace

FirmwareProfile px4_sih_profile() {
  FirmwareProfile p;
  p.firmware = Autopilot::Px4;
  p.bridge_autopilot = "px4";
  p.flight_params = {
      // Without RC, PX4's default reaction to lost setpoints (Position) falls through to
      // NAV_RCL_ACT (Return): docs/flight-controller.md asks for Land.
      {"COM_OBL_RC_ACT", "4"},
      // No logger (a ulog of 13 MB a minute with SIH) in the test's scratch folder.
      {"SDLOG_BACKEND", "0"},
  };
  p.wrong_params = {{"COM_OBL_RC_ACT", "6"},  // terminate: drops the UAV
                    {"NAV_DLL_ACT", "2"},     // a ground-station link made an arming need
                    {"COM_OF_LOSS_T", "5"},   // PX4 would fly stale setpoints for 5 s
                    {"SDLOG_BACKEND", "0"}};
  p.wrong_names = {"COM_OBL_RC_ACT", "NAV_DLL_ACT", "COM_OF_LOSS_T"};
  p.blocking_names = {"COM_OBL_RC_ACT"};
  p.bridge_hover_start = 0.54;  // SIH's default quad (1 kg, 4 x 5 N) hovers at 0.490
  // SIH's drag, SIH_KDV 1 N/(m/s) on SIH_MASS 1 kg: a thrust error it balances at a steady
  // climb is otherwise invisible to the velocity-aided estimate.
  p.bridge_params = {{"velocity_drag_per_s", "1.0"}};
  p.offboard_loss_param = "COM_OF_LOSS_T";
  p.pilot_mode_main = mav::px4_mode::kMainAuto;  // AUTO.LOITER: Hold
  p.pilot_mode_sub = mav::px4_mode::kAutoSubLoiter;
  p.pilot_mode_name = "AUTO.LOITER";
  p.bytewise_params = true;
  p.needed_streams = {mav::HighresImu::kId, mav::ExtendedSysState::kId, mav::SysStatus::kId,
                      mav::BatteryStatus::kId, mav::EstimatorStatus::kId};
  return p;
}

FirmwareProfile arducopter_profile() {
  FirmwareProfile p;
  p.firmware = Autopilot::ArduPilot;
  p.bridge_autopilot = "ardupilot";
  // docs/flight-controller.md, "Connecting a real ArduPilot"; GUID_TIMEOUT and
  // FS_GCS_TIMEOUT are its defaults. The GCS failsafe watches the bridge's HEARTBEAT (the
  // vehicle's own system id) and lands when it stops.
  p.flight_params = {{"FS_THR_ENABLE", "0"},          {"ATC_ANGLE_BOOST", "0"},
                     {"GUID_OPTIONS", "8"},           {"GUID_TIMEOUT", "3"},
                     {"FS_GCS_ENABLE", "5"},          {"FS_GCS_TIMEOUT", "5"},
                     {"MAV_GCS_SYSID", kOwnSystemId}, {"EK3_GPS_CHECK", "0"}};
  p.wrong_params = {{"ATC_ANGLE_BOOST", "1"},   // thrust compensated twice
                    {"GUID_OPTIONS", "0"},      // thrust read as a climb rate
                    {"FS_THR_ENABLE", "1"},     // arming needs an RC receiver
                    {"FS_GCS_ENABLE", "0"},     // ArduPilot's defaults: the bridge's death
                    {"MAV_GCS_SYSID", "255"}};  // is no failsafe
  p.wrong_names = {"ATC_ANGLE_BOOST", "GUID_OPTIONS", "FS_THR_ENABLE", "FS_GCS_ENABLE",
                   "MAV_GCS_SYSID"};
  p.blocking_names = {"ATC_ANGLE_BOOST", "GUID_OPTIONS"};
  p.bridge_hover_start = 0.43;  // SITL's copter.parm says MOT_THST_HOVER 0.39
  p.offboard_loss_param = "GUID_TIMEOUT";
  // BRAKE: holds where it is by itself. LOITER or ALT_HOLD would follow SITL's RC sticks,
  // whose throttle rests at its minimum (nobody holds them): the UAV would sink to the
  // ground within seconds.
  p.pilot_mode_main = 17;
  p.pilot_mode_name = "BRAKE";
  p.bytewise_params = false;
  p.needed_streams = {mav::HighresImu::kId, mav::ExtendedSysState::kId, mav::SysStatus::kId,
                      mav::BatteryStatus::kId, mav::EkfStatusReport::kId};
  return p;
}

bool in_offboard(Autopilot firmware, const mav::Heartbeat& heartbeat) {
  if (firmware == Autopilot::Px4) {
    return mav::px4_mode::main_mode(heartbeat.custom_mode) == mav::px4_mode::kMainOffboard;
  }
  return heartbeat.custom_mode == mav::copter_mode::kGuidedNoGps;
}

bool in_land(Autopilot firmware, const mav::Heartbeat& heartbeat) {
  if (firmware == Autopilot::Px4) {
    return mav::px4_mode::main_mode(heartbeat.custom_mode) == mav::px4_mode::kMainAuto &&
           mav::px4_mode::sub_mode(heartbeat.custom_mode) == mav::px4_mode::kAutoSubLand;
  }
  return heartbeat.custom_mode == mav::copter_mode::kLand;
}

bool is_land_command(Autopilot firmware, const mav::CommandLong& command) {
  if (firmware == Autopilot::Px4) return command.command == mav::mav_cmd::kNavLand;
  return command.command == mav::mav_cmd::kDoSetMode &&
         command.param[1] == static_cast<float>(mav::copter_mode::kLand);
}

bool is_control_command(const mav::CommandLong& command) {
  return command.command == mav::mav_cmd::kDoSetMode ||
         command.command == mav::mav_cmd::kComponentArmDisarm ||
         command.command == mav::mav_cmd::kNavLand;
}

std::optional<double> firmware_hover_thrust(Autopilot firmware, FirmwareMonitor& monitor) {
  if (firmware == Autopilot::ArduPilot) {
    const auto hover = monitor.read_param("MOT_THST_HOVER", kParamTimeout);
    if (!hover) return std::nullopt;
    return hover->value(false);
  }
  const auto mass = monitor.read_param("SIH_MASS", kParamTimeout);
  const auto max_thrust = monitor.read_param("SIH_T_MAX", kParamTimeout);
  if (!mass || !max_thrust || max_thrust->value(true) <= 0.0) return std::nullopt;
  return mass->value(true) * kStandardGravity_m_s2 / (4.0 * max_thrust->value(true));
}

}  // namespace cover::firmware
