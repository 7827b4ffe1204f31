#include "offboard_failsafe.hpp"

#include "cover/sim/fc/levelled_flight.hpp"

namespace cover::sim {

QuadrotorCommand OffboardFailsafe::plant_command(const QuadrotorCommand& agent_command,
                                                 double command_age_s, bool handover,
                                                 const World& world) {
  const OffboardState before = state_;
  if (state_ == OffboardState::WaitingForAgent && command_age_s >= 0.0) {
    state_ = OffboardState::Offboard;
  }
  if (state_ == OffboardState::Offboard && command_age_s > timeout_s_) {
    state_ = OffboardState::LossDescent;
  } else if (state_ == OffboardState::Offboard && handover) {
    state_ = OffboardState::LossDescent;
    handed_over_ = true;
  }
  if (state_ == OffboardState::LossDescent && world.state().uav_contact.resting) {
    state_ = OffboardState::LossDisarmed;
  }
  changed_ = state_ != before;
  switch (state_) {
    case OffboardState::Offboard:
      return agent_command;
    case OffboardState::LossDescent:
      return fc::levelled_vertical_speed_command(world, -descent_rate_m_s_);
    case OffboardState::WaitingForAgent:
    case OffboardState::LossDisarmed:
      break;
  }
  return QuadrotorCommand{};
}

}  // namespace cover::sim
