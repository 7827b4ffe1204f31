#include "cover/vocabulary/world_segment.hpp"

namespace cover::sim {

const char* to_string(OffboardState state) {
  switch (state) {
    case OffboardState::WaitingForAgent:
      return "waiting-for-agent";
    case OffboardState::Offboard:
      return "offboard";
    case OffboardState::LossDescent:
      return "offboard-loss-descent";
    case OffboardState::LossDisarmed:
      return "offboard-loss-disarmed";
  }
  return "unknown";
}

}  // namespace cover::sim
