#include "cover/fc_bridge/autopilot_profile.hpp"

#include "cover/mavlink/protocol.hpp"

namespace cover::fc_bridge {
namespace {

namespace mav = cover::mavlink;

struct ModeRow {
  std::uint32_t number;
  const char* name;
  FcMode mode;
};

// PX4 main modes (bits 16-23); AUTO (4) is refined by its sub mode below.
constexpr ModeRow kPx4Main[] = {
    {mav::px4_mode::kMainManual, "MANUAL", FcMode::Manual},
    {mav::px4_mode::kMainAltctl, "ALTCTL", FcMode::Manual},
    {mav::px4_mode::kMainPosctl, "POSCTL", FcMode::Manual},
    {mav::px4_mode::kMainAcro, "ACRO", FcMode::Manual},
    {mav::px4_mode::kMainOffboard, "OFFBOARD", FcMode::Offboard},
    {mav::px4_mode::kMainStabilized, "STABILIZED", FcMode::Manual},
    {8, "RATTITUDE", FcMode::Manual},
};

constexpr ModeRow kPx4AutoSub[] = {
    {1, "AUTO.READY", FcMode::Other},
    {2, "AUTO.TAKEOFF", FcMode::Other},
    {mav::px4_mode::kAutoSubLoiter, "AUTO.LOITER", FcMode::Other},
    {4, "AUTO.MISSION", FcMode::Other},
    {5, "AUTO.RTL", FcMode::Other},
    {mav::px4_mode::kAutoSubLand, "AUTO.LAND", FcMode::Land},
    {8, "AUTO.FOLLOW_TARGET", FcMode::Other},
    {9, "AUTO.PRECLAND", FcMode::Land},
};

// ArduCopter flight modes; LOITER and POSHOLD are flown by the pilot's sticks.
constexpr ModeRow kCopter[] = {
    {mav::copter_mode::kStabilize, "STABILIZE", FcMode::Manual},
    {mav::copter_mode::kAcro, "ACRO", FcMode::Manual},
    {mav::copter_mode::kAltHold, "ALT_HOLD", FcMode::Manual},
    {mav::copter_mode::kAuto, "AUTO", FcMode::Other},
    {mav::copter_mode::kGuided, "GUIDED", FcMode::Other},
    {mav::copter_mode::kLoiter, "LOITER", FcMode::Manual},
    {mav::copter_mode::kRtl, "RTL", FcMode::Other},
    {7, "CIRCLE", FcMode::Other},
    {mav::copter_mode::kLand, "LAND", FcMode::Land},
    {11, "DRIFT", FcMode::Manual},
    {13, "SPORT", FcMode::Manual},
    {14, "FLIP", FcMode::Other},
    {15, "AUTOTUNE", FcMode::Other},
    {mav::copter_mode::kPosHold, "POSHOLD", FcMode::Manual},
    {17, "BRAKE", FcMode::Other},
    {18, "THROW", FcMode::Other},
    {19, "AVOID_ADSB", FcMode::Other},
    {mav::copter_mode::kGuidedNoGps, "GUIDED_NOGPS", FcMode::Offboard},
    {21, "SMART_RTL", FcMode::Other},
    {22, "FLOWHOLD", FcMode::Manual},
    {23, "FOLLOW", FcMode::Other},
    {24, "ZIGZAG", FcMode::Other},
    {25, "SYSTEMID", FcMode::Other},
    {26, "AUTOROTATE", FcMode::Other},
    {27, "AUTO_RTL", FcMode::Other},
    {28, "TURTLE", FcMode::Manual},
};

template <std::size_t N>
const ModeRow* find(const ModeRow (&rows)[N], std::uint32_t number) {
  for (const ModeRow& row : rows) {
    if (row.number == number) return &row;
  }
  return nullptr;
}

const ModeRow* lookup(Autopilot kind, std::uint32_t custom_mode) {
  if (kind == Autopilot::ArduPilot) return find(kCopter, custom_mode);
  const std::uint8_t main = mav::px4_mode::main_mode(custom_mode);
  if (main == mav::px4_mode::kMainAuto) {
    return find(kPx4AutoSub, mav::px4_mode::sub_mode(custom_mode));
  }
  return find(kPx4Main, main);
}

bool custom_mode_flag(std::uint8_t base_mode) {
  return (base_mode & mav::mav_mode_flag::kCustomModeEnabled) != 0;
}

CommandSpec set_mode(float custom_main, float custom_sub = 0.0F) {
  CommandSpec spec;
  spec.command = mav::mav_cmd::kDoSetMode;
  spec.param[0] = mav::mav_mode_flag::kCustomModeEnabled;
  spec.param[1] = custom_main;
  spec.param[2] = custom_sub;
  return spec;
}

}  // namespace

const char* to_string(FcMode mode) {
  switch (mode) {
    case FcMode::Unknown:
      return "unknown";
    case FcMode::Offboard:
      return "offboard";
    case FcMode::Land:
      return "land";
    case FcMode::Manual:
      return "manual";
    case FcMode::Other:
      return "other";
  }
  return "unknown";
}

std::uint8_t AutopilotProfile::mav_autopilot() const {
  return kind_ == Autopilot::Px4 ? mav::mav_autopilot::kPx4 : mav::mav_autopilot::kArdupilotMega;
}

CommandSpec AutopilotProfile::offboard_command() const {
  return kind_ == Autopilot::Px4 ? set_mode(mav::px4_mode::kMainOffboard)
                                 : set_mode(mav::copter_mode::kGuidedNoGps);
}

CommandSpec AutopilotProfile::land_command() const {
  if (kind_ == Autopilot::ArduPilot) return set_mode(mav::copter_mode::kLand);
  // PX4 takes NAV_LAND at the current position into AUTO.LAND; NaN yaw / lat / lon /
  // altitude would mean "here", zeros are what PX4's commander reads as "not given" too.
  CommandSpec spec;
  spec.command = mav::mav_cmd::kNavLand;
  return spec;
}

CommandSpec AutopilotProfile::arm_command(bool arm) const {
  CommandSpec spec;
  spec.command = mav::mav_cmd::kComponentArmDisarm;
  spec.param[0] = arm ? 1.0F : 0.0F;  // never param2 = 21196 (forced): the autopilot judges
  return spec;
}

const char* AutopilotProfile::offboard_mode_name() const {
  return kind_ == Autopilot::Px4 ? "OFFBOARD" : "GUIDED_NOGPS";
}

FcMode AutopilotProfile::decode_mode(std::uint8_t base_mode, std::uint32_t custom_mode) const {
  if (!custom_mode_flag(base_mode)) return FcMode::Unknown;
  const ModeRow* row = lookup(kind_, custom_mode);
  return row != nullptr ? row->mode : FcMode::Unknown;
}

std::string AutopilotProfile::mode_name(std::uint8_t base_mode, std::uint32_t custom_mode) const {
  if (!custom_mode_flag(base_mode)) return "no custom mode";
  if (const ModeRow* row = lookup(kind_, custom_mode)) return row->name;
  if (kind_ == Autopilot::Px4) {
    return "PX4 mode " + std::to_string(mav::px4_mode::main_mode(custom_mode)) + "." +
           std::to_string(mav::px4_mode::sub_mode(custom_mode));
  }
  return "Copter mode " + std::to_string(custom_mode);
}

}  // namespace cover::fc_bridge
