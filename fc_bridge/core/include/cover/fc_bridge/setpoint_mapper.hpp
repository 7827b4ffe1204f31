#pragma once

#include <cstdint>

#include "cover/fc_bridge/agent_command.hpp"
#include "cover/mavlink/messages.hpp"

namespace cover::fc_bridge {

// The agent's command as SET_ATTITUDE_TARGET: type_mask 128 (attitude ignored: body rates
// and thrust fly), rates FLU -> FRD (p, -q, -r), thrust u = c * hover / g clamped to
// [0, 1] (0 when the agent says disarmed), time_boot_ms = the command's stamp in ms (the
// simulator in lockstep matches it to its tick).
class SetpointMapper {
 public:
  explicit SetpointMapper(double gravity_m_s2) : gravity_m_s2_(gravity_m_s2) {}

  // `command` must be flyable (is_flyable); `hover_thrust` in (0, 1).
  mavlink::SetAttitudeTarget map(const AgentCommand& command, double hover_thrust,
                                 std::uint8_t target_system, std::uint8_t target_component) const;
  double normalised_thrust(const AgentCommand& command, double hover_thrust) const;

 private:
  double gravity_m_s2_;
};

}  // namespace cover::fc_bridge
