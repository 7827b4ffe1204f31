#include "cover/sim/fc/frame_conventions.hpp"

namespace cover::sim::fc {

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
