#include "cover/sim/fc/autopilot_mode.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "cover/mavlink/protocol.hpp"

namespace cover::sim::fc {

namespace px4 = mavlink::px4_mode;
namespace copter = mavlink::copter_mode;

constexpr std::uint32_t kCopterBrake = 17;
constexpr FlightMode kModes[] = {FlightMode::Hold, FlightMode::Manual, FlightMode::Position,
                                 FlightMode::Offboard, FlightMode::Land};

FlightMode start_mode(Autopilot profile) {
  return profile == Autopilot::Px4 ? FlightMode::Hold : FlightMode::Manual;
}

const char* mode_name(Autopilot profile, FlightMode mode) {
  const bool is_px4 = profile == Autopilot::Px4;
  switch (mode) {
    case FlightMode::Hold:
      return is_px4 ? "AUTO.LOITER" : "BRAKE";
    case FlightMode::Manual:
      return is_px4 ? "MANUAL" : "STABILIZE";
    case FlightMode::Position:
      return is_px4 ? "POSCTL" : "LOITER";
    case FlightMode::Offboard:
      return is_px4 ? "OFFBOARD" : "GUIDED_NOGPS";
    case FlightMode::Land:
      return is_px4 ? "AUTO.LAND" : "LAND";
  }
  return "UNKNOWN";
}

std::uint32_t custom_mode(Autopilot profile, FlightMode mode) {
  if (profile == Autopilot::Px4) {
    switch (mode) {
      case FlightMode::Hold:
        return px4::custom_mode(px4::kMainAuto, px4::kAutoSubLoiter);
      case FlightMode::Manual:
        return px4::custom_mode(px4::kMainManual);
      case FlightMode::Position:
        return px4::custom_mode(px4::kMainPosctl);
      case FlightMode::Offboard:
        return px4::custom_mode(px4::kMainOffboard);
      case FlightMode::Land:
        return px4::custom_mode(px4::kMainAuto, px4::kAutoSubLand);
    }
  }
  switch (mode) {
    case FlightMode::Hold:
      return kCopterBrake;
    case FlightMode::Manual:
      return copter::kStabilize;
    case FlightMode::Position:
      return copter::kLoiter;
    case FlightMode::Offboard:
      return copter::kGuidedNoGps;
    case FlightMode::Land:
      return copter::kLand;
  }
  return 0;
}

namespace {

// A float parameter that must hold a small whole number (a mode number).
std::optional<std::uint32_t> whole(float value) {
  if (!std::isfinite(value) || value < 0.0F || value > 255.0F) return std::nullopt;
  if (std::nearbyint(value) != value) return std::nullopt;
  return static_cast<std::uint32_t>(value);
}

}  // namespace

std::optional<FlightMode> requested_mode(Autopilot profile, float param1, float param2,
                                         float param3) {
  const auto flags = whole(param1);
  if (!flags || (*flags & mavlink::mav_mode_flag::kCustomModeEnabled) == 0) return std::nullopt;
  const auto main = whole(param2);
  if (!main) return std::nullopt;
  for (FlightMode mode : kModes) {
    const std::uint32_t custom = custom_mode(profile, mode);
    if (profile == Autopilot::ArduPilot) {
      if (custom == *main) return mode;
      continue;
    }
    if (px4::main_mode(custom) != *main) continue;
    // Only AUTO has sub modes here (LOITER, LAND); a PX4 ground station sends 0 for the others.
    const auto sub = whole(param3);
    if (px4::main_mode(custom) != px4::kMainAuto || (sub && *sub == px4::sub_mode(custom))) {
      return mode;
    }
  }
  return std::nullopt;
}

std::optional<FlightMode> parse_mode_name(const std::string& text) {
  std::string upper = text;
  std::transform(upper.begin(), upper.end(), upper.begin(),
                 [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  for (FlightMode mode : kModes) {
    for (Autopilot profile : {Autopilot::Px4, Autopilot::ArduPilot}) {
      if (upper == mode_name(profile, mode)) return mode;
    }
  }
  if (upper == "LAND") return FlightMode::Land;
  return std::nullopt;
}

}  // namespace cover::sim::fc
