#pragma once

#include "cover/sim/world.hpp"
#include "cover/vocabulary/world_segment.hpp"

namespace cover::sim {

// The simulated flight controller between a UAV agent and its plant: motors off until
// the first command, the agent's command while it is fresh, and on offboard loss a
// levelled descent that disarms on contact (latched). A fresh command that hands the UAV
// over (the agent has no relative state left to land on) starts that descent at once.
class OffboardFailsafe {
 public:
  OffboardFailsafe(double timeout_s, double descent_rate_m_s)
      : timeout_s_(timeout_s), descent_rate_m_s_(descent_rate_m_s) {}

  // `command_age_s`: time since the last command arrived (< 0: none yet); `handover`: that
  // command's flag.
  QuadrotorCommand plant_command(const QuadrotorCommand& agent_command, double command_age_s,
                                 bool handover, const World& world);
  OffboardState state() const { return state_; }
  // The descent began on the agent's handover, not on a lost command stream.
  bool handed_over() const { return handed_over_; }
  // True on the call where the state changed (for a log line).
  bool changed() const { return changed_; }

 private:
  double timeout_s_;
  double descent_rate_m_s_;
  OffboardState state_ = OffboardState::WaitingForAgent;
  bool changed_ = false;
  bool handed_over_ = false;
};

}  // namespace cover::sim
