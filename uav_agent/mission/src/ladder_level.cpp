#include "cover/mission/ladder_level.hpp"

namespace cover::mission {

const char* to_string(LadderLevel level) {
  switch (level) {
    case LadderLevel::Nominal:
      return "nominal";
    case LadderLevel::ImuHold:
      return "imu-hold";
    case LadderLevel::EmergencyHover:
      return "emergency-hover";
    case LadderLevel::EmergencyLanding:
      return "emergency-landing";
    case LadderLevel::Disarmed:
      return "emergency-landed";
  }
  return "unknown";
}

}  // namespace cover::mission
