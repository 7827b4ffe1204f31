#include "cover/sim/fc/levelled_flight.hpp"

#include <algorithm>

namespace cover::sim::fc {

QuadrotorCommand levelled_vertical_speed_command(const World& world, double vertical_speed_m_s) {
  const QuadrotorState& uav = world.state().uav;
  const Eigen::Quaterniond q = uav.attitude.eigen();
  const Eigen::Vector3d up_in_body = q.inverse() * Eigen::Vector3d::UnitZ();
  const double attitude_gain_1_s = 4.0;
  const double sink_gain_1_s = 2.0;
  QuadrotorCommand command;
  // Body z toward world up: rotate about up_body x e_z.
  const Eigen::Vector3d tilt_axis = Eigen::Vector3d::UnitZ().cross(up_in_body);
  command.body_rate_rad_s = Vec3(attitude_gain_1_s * tilt_axis);
  const double sink_error_m_s = vertical_speed_m_s - uav.velocity_m_s.z;
  const double hover = world.hover_thrust_command_m_s2();
  command.thrust_m_s2 =
      std::clamp(hover * (1.0 + sink_gain_1_s * sink_error_m_s / world.params().gravity_m_s2),
                 0.5 * hover, 1.5 * hover);
  return command;
}

QuadrotorCommand levelled_height_hold_command(const World& world, double hold_height_m) {
  // A gentle height loop: 1 m of error asks for 1 m/s, at most 0.5 m/s either way.
  const double height_gain_1_s = 1.0;
  const double max_speed_m_s = 0.5;
  const double error_m = hold_height_m - world.state().uav.position_m.z;
  return levelled_vertical_speed_command(
      world, std::clamp(height_gain_1_s * error_m, -max_speed_m_s, max_speed_m_s));
}

}  // namespace cover::sim::fc
