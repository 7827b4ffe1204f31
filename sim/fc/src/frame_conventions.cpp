#include "cover/sim/fc/frame_conventions.hpp"

namespace cover::sim::fc {

Eigen::Vector3d flu_to_frd(const Eigen::Vector3d& v) {
  return {v.x(), -v.y(), -v.z()};
}

Eigen::Quaterniond ned_frd_attitude(const Eigen::Quaterniond& enu_flu) {
  Eigen::Matrix3d ned_from_enu;
  ned_from_enu << 0, 1, 0, 1, 0, 0, 0, 0, -1;
  const Eigen::Matrix3d flu_from_frd = Eigen::Vector3d(1, -1, -1).asDiagonal();
  Eigen::Quaterniond q(ned_from_enu * enu_flu.toRotationMatrix() * flu_from_frd);
  q.normalize();
  // One hemisphere (w >= 0), as autopilots report it.
  if (q.w() < 0.0) q.coeffs() *= -1.0;
  return q;
}

Eigen::Vector3d uav_specific_force_flu(const World& world) {
  const WorldState& ws = world.state();
  const Eigen::Quaterniond q = ws.uav.attitude.eigen();
  const double g = world.params().gravity_m_s2;
  if (ws.uav_contact.resting) return q.inverse() * Eigen::Vector3d(0.0, 0.0, g);
  const WorldParams& p = world.params();
  const double mass_kg = p.uav.mass_true_kg + (ws.payload.attached ? p.payload.mass_kg : 0.0);
  const Eigen::Vector3d velocity_body = q.inverse() * ws.uav.velocity_m_s.eigen();
  const Eigen::Vector3d drag = -p.uav.drag_coefficients_1_s.cwiseProduct(velocity_body);
  return Eigen::Vector3d(0.0, 0.0, ws.uav.thrust_n / mass_kg) + drag;
}

}  // namespace cover::sim::fc
