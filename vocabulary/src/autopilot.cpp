#include "cover/vocabulary/autopilot.hpp"

namespace cover {

const char* to_string(Autopilot autopilot) {
  return autopilot == Autopilot::Px4 ? "px4" : "ardupilot";
}

const char* display_name(Autopilot autopilot) {
  return autopilot == Autopilot::Px4 ? "PX4" : "ArduCopter";
}

std::optional<Autopilot> parse_autopilot(const std::string& text) {
  if (text == "px4") return Autopilot::Px4;
  if (text == "ardupilot") return Autopilot::ArduPilot;
  return std::nullopt;
}

}  // namespace cover
