#pragma once

#include <cstdint>

namespace cover::fc_bridge {

// One command of the UAV agent (cover/uav/U/cmd, msg::UavCommand) as the bridge needs it:
// collective thrust per unit mass and body rates in FLU.
struct AgentCommand {
  std::int64_t stamp_ns = 0;
  std::uint32_t seq = 0;
  double thrust_m_s2 = 0.0;
  double roll_rate_rad_s = 0.0;   // about x forward
  double pitch_rate_rad_s = 0.0;  // about y left
  double yaw_rate_rad_s = 0.0;    // about z up
  bool armed = false;             // false: motors at zero thrust
  bool release_payload = false;
  bool handover = false;  // the agent cannot land the UAV: the autopilot's land mode must
};

// Whether a command can be flown: every number finite and within what a quadrotor can
// mean (a rate of 100 rad/s or a thrust of 100 g is corruption, not a command).
bool is_flyable(const AgentCommand& command);

}  // namespace cover::fc_bridge
