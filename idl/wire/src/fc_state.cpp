#include "cover/wire/fc_state.hpp"

namespace cover::wire {

std::optional<std::string> fc_not_ready_reason(const msg::FcState& state) {
  if (!state.link_ok) return std::string("flight-controller link lost (no autopilot HEARTBEAT)");
  if (state.mode != msg::FcMode::FC_MODE_OFFBOARD) {
    const std::string mode = state.mode_name.empty() ? msg::to_string(state.mode) : state.mode_name;
    return "autopilot not in its offboard mode (mode " + mode + ")";
  }
  if (!state.armed) return std::string("autopilot disarmed");
  if (!state.offboard_ready) return std::string("autopilot not ready for offboard flight");
  return std::nullopt;
}

}  // namespace cover::wire
