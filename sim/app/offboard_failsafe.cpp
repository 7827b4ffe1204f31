#include "offboard_failsafe.hpp"

#include <algorithm>

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
      return descent_command(world);
    case OffboardState::WaitingForAgent:
    case OffboardState::LossDisarmed:
      break;
  }
  return QuadrotorCommand{};
}

// Level the attitude (rates against the tilt) and track a constant sink rate with the
// hover thrust the flight controller has learned.
QuadrotorCommand OffboardFailsafe::descent_command(const World& world) const {
  const QuadrotorState& uav = world.state().uav;
  const Eigen::Quaterniond q = uav.attitude.eigen();
  const Eigen::Vector3d up_in_body = q.inverse() * Eigen::Vector3d::UnitZ();
  const double attitude_gain_1_s = 4.0;
  const double sink_gain_1_s = 2.0;
  QuadrotorCommand command;
  // Body z toward world up: rotate about up_body x e_z.
  const Eigen::Vector3d tilt_axis = Eigen::Vector3d::UnitZ().cross(up_in_body);
  command.body_rate_rad_s = Vec3(attitude_gain_1_s * tilt_axis);
  const double sink_error_m_s = -descent_rate_m_s_ - uav.velocity_m_s.z;
  const double hover = world.hover_thrust_command_m_s2();
  command.thrust_m_s2 =
      std::clamp(hover * (1.0 + sink_gain_1_s * sink_error_m_s / world.params().gravity_m_s2),
                 0.5 * hover, 1.5 * hover);
  return command;
}

}  // namespace cover::sim
