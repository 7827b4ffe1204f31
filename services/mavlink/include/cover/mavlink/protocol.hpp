#pragma once

#include <cstdint>

namespace cover::mavlink {

// The common.xml enum values COVER uses, named once.
namespace mav_autopilot {
inline constexpr std::uint8_t kGeneric = 0;
inline constexpr std::uint8_t kArdupilotMega = 3;
inline constexpr std::uint8_t kInvalid = 8;
inline constexpr std::uint8_t kPx4 = 12;
}  // namespace mav_autopilot

namespace mav_type {
inline constexpr std::uint8_t kQuadrotor = 2;
inline constexpr std::uint8_t kGcs = 6;
inline constexpr std::uint8_t kGroundRover = 10;
inline constexpr std::uint8_t kOnboardController = 18;
}  // namespace mav_type

namespace mav_mode_flag {
inline constexpr std::uint8_t kCustomModeEnabled = 1;
inline constexpr std::uint8_t kSafetyArmed = 128;
}  // namespace mav_mode_flag

namespace mav_state {
inline constexpr std::uint8_t kStandby = 3;
inline constexpr std::uint8_t kActive = 4;
inline constexpr std::uint8_t kCritical = 5;
}  // namespace mav_state

namespace mav_cmd {
inline constexpr std::uint16_t kNavLand = 21;
inline constexpr std::uint16_t kDoSetMode = 176;
// param1: gripper instance (1), param2: 0 release / 1 grab (GRIPPER_ACTIONS).
inline constexpr std::uint16_t kDoGripper = 211;
inline constexpr std::uint16_t kComponentArmDisarm = 400;
// param1: message id, param2: interval in us (-1: stop, 0: default rate).
inline constexpr std::uint16_t kSetMessageInterval = 511;
}  // namespace mav_cmd

// SYS_STATUS onboard_control_sensors_* bits (MAV_SYS_STATUS_SENSOR).
namespace mav_sys_status_sensor {
inline constexpr std::uint32_t kGyro3d = 1;
inline constexpr std::uint32_t kAccel3d = 2;
inline constexpr std::uint32_t kMag3d = 4;
inline constexpr std::uint32_t kAbsolutePressure = 8;
inline constexpr std::uint32_t kAhrs = 0x200000;
inline constexpr std::uint32_t kPrearmCheck = 0x10000000;
}  // namespace mav_sys_status_sensor

// PARAM_VALUE.param_type (MAV_PARAM_TYPE).
namespace mav_param_type {
inline constexpr std::uint8_t kUint8 = 1;
inline constexpr std::uint8_t kInt8 = 2;
inline constexpr std::uint8_t kInt16 = 4;
inline constexpr std::uint8_t kInt32 = 6;
inline constexpr std::uint8_t kReal32 = 9;
}  // namespace mav_param_type

namespace mav_result {
inline constexpr std::uint8_t kAccepted = 0;
inline constexpr std::uint8_t kTemporarilyRejected = 1;
inline constexpr std::uint8_t kDenied = 2;
inline constexpr std::uint8_t kUnsupported = 3;
inline constexpr std::uint8_t kFailed = 4;
inline constexpr std::uint8_t kInProgress = 5;
}  // namespace mav_result

namespace mav_landed_state {
inline constexpr std::uint8_t kUndefined = 0;
inline constexpr std::uint8_t kOnGround = 1;
inline constexpr std::uint8_t kInAir = 2;
inline constexpr std::uint8_t kTakeoff = 3;
inline constexpr std::uint8_t kLanding = 4;
}  // namespace mav_landed_state

namespace mav_comp {
inline constexpr std::uint8_t kAutopilot1 = 1;
inline constexpr std::uint8_t kMissionPlanner = 190;
inline constexpr std::uint8_t kOnboardComputer = 191;
}  // namespace mav_comp

// SET_ATTITUDE_TARGET.type_mask bits.
namespace attitude_target_typemask {
inline constexpr std::uint8_t kIgnoreBodyRollRate = 1;
inline constexpr std::uint8_t kIgnoreBodyPitchRate = 2;
inline constexpr std::uint8_t kIgnoreBodyYawRate = 4;
inline constexpr std::uint8_t kThrustBodySet = 32;
inline constexpr std::uint8_t kIgnoreThrust = 64;
inline constexpr std::uint8_t kIgnoreAttitude = 128;
}  // namespace attitude_target_typemask

// PX4's custom mode: main mode in bits 16-23, sub mode in bits 24-31.
namespace px4_mode {
inline constexpr std::uint8_t kMainManual = 1;
inline constexpr std::uint8_t kMainAltctl = 2;
inline constexpr std::uint8_t kMainPosctl = 3;
inline constexpr std::uint8_t kMainAuto = 4;
inline constexpr std::uint8_t kMainAcro = 5;
inline constexpr std::uint8_t kMainOffboard = 6;
inline constexpr std::uint8_t kMainStabilized = 7;
inline constexpr std::uint8_t kAutoSubLand = 6;
inline constexpr std::uint8_t kAutoSubLoiter = 3;
inline constexpr std::uint32_t custom_mode(std::uint8_t main, std::uint8_t sub = 0) {
  return (static_cast<std::uint32_t>(main) << 16) | (static_cast<std::uint32_t>(sub) << 24);
}
inline constexpr std::uint8_t main_mode(std::uint32_t custom) {
  return (custom >> 16) & 0xFF;
}
inline constexpr std::uint8_t sub_mode(std::uint32_t custom) {
  return (custom >> 24) & 0xFF;
}
}  // namespace px4_mode

// ArduCopter's custom modes (the flight mode number).
namespace copter_mode {
inline constexpr std::uint32_t kStabilize = 0;
inline constexpr std::uint32_t kAcro = 1;
inline constexpr std::uint32_t kAltHold = 2;
inline constexpr std::uint32_t kAuto = 3;
inline constexpr std::uint32_t kGuided = 4;
inline constexpr std::uint32_t kLoiter = 5;
inline constexpr std::uint32_t kRtl = 6;
inline constexpr std::uint32_t kLand = 9;
inline constexpr std::uint32_t kPosHold = 16;
inline constexpr std::uint32_t kGuidedNoGps = 20;
}  // namespace copter_mode

}  // namespace cover::mavlink
