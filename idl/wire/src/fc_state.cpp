#include "cover/wire/fc_state.hpp"

#include <cstdio>

namespace cover::wire {

namespace {

// An autopilot disarms by itself when it stays armed on the ground (PX4 COM_DISARM_PRFLT,
// ArduPilot DISARM_DELAY): "arm, then submit later" fails on a real vehicle.
std::string disarmed_reason(const msg::FcState& state) {
  std::string why = "autopilot disarmed (arm it: cover fc arm " + std::to_string(state.uav_id);
  if (state.auto_disarm_s > 0.0) {
    char delay[96];
    std::snprintf(delay, sizeof delay,
                  "; it disarms by itself %.0f s after arming unless the UAV takes off",
                  state.auto_disarm_s);
    why += delay;
  }
  return why + ")";
}

}  // namespace

std::optional<std::string> fc_not_ready_reason(const msg::FcState& state) {
  if (!state.link_ok) return std::string("flight-controller link lost (no autopilot HEARTBEAT)");
  if (!state.flight_blocker.empty()) return state.flight_blocker;
  if (state.mode != msg::FcMode::FC_MODE_OFFBOARD) {
    const std::string mode = state.mode_name.empty() ? msg::to_string(state.mode) : state.mode_name;
    return "autopilot not in its offboard mode (mode " + mode + ")";
  }
  if (!state.armed) return disarmed_reason(state);
  if (!state.offboard_ready) return std::string("autopilot not ready for offboard flight");
  return std::nullopt;
}

}  // namespace cover::wire
