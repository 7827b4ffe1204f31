#include "cover/sim/rotor_geometry.hpp"

#include <Eigen/Geometry>

namespace cover::sim {

BodyWrench rotor_wrench(const RotorLayout& layout, const std::array<double, kRotorCount>& thrust_n,
                        const std::array<double, kRotorCount>& reaction_torque_n_m) {
  BodyWrench wrench;
  for (int i = 0; i < kRotorCount; ++i) {
    const Eigen::Vector3d force(0.0, 0.0, thrust_n[i]);
    wrench.force_n += force;
    wrench.torque_n_m += layout[i].position_flu_m.cross(force);
    wrench.torque_n_m.z() -= layout[i].spin_sign() * reaction_torque_n_m[i];
  }
  return wrench;
}

void validate_rotor_layout(const RotorLayout& layout, const std::string& context) {
  int counter_clockwise = 0;
  for (const RotorParams& rotor : layout) counter_clockwise += rotor.spin == "ccw" ? 1 : 0;
  config::check(counter_clockwise == 2, context,
                "two rotors must turn counter-clockwise and two clockwise");
}

}  // namespace cover::sim
