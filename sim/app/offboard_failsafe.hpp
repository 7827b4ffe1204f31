#pragma once

#include "cover/sim/world.hpp"
#include "cover/sim/world_segment.hpp"

namespace cover::sim {

// The simulated flight controller between a UAV agent and its plant: motors off until
// the first command, the agent's command while it is fresh, and on offboard loss a
// levelled descent that disarms on contact (latched).
class OffboardFailsafe {
 public:
  OffboardFailsafe(double timeout_s, double descent_rate_m_s)
      : timeout_s_(timeout_s), descent_rate_m_s_(descent_rate_m_s) {}

  // `command_age_s`: time since the last command arrived (< 0: none yet).
  QuadrotorCommand plant_command(const QuadrotorCommand& agent_command, double command_age_s,
                                 const World& world);
  OffboardState state() const { return state_; }
  // True on the call where the state changed (for a log line).
  bool changed() const { return changed_; }

 private:
  QuadrotorCommand descent_command(const World& world) const;

  double timeout_s_;
  double descent_rate_m_s_;
  OffboardState state_ = OffboardState::WaitingForAgent;
  bool changed_ = false;
};

}  // namespace cover::sim
