#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "cover/sim/world.hpp"

namespace cover::sim::fc {

// MAVLink speaks NED world / FRD body; the simulator ENU world / FLU body.

// A body vector FLU <-> FRD: (x, -y, -z) (its own inverse).
Eigen::Vector3d flu_to_frd(const Eigen::Vector3d& v);
inline Eigen::Vector3d frd_to_flu(const Eigen::Vector3d& v) {
  return flu_to_frd(v);
}

// The attitude FRD body -> NED world of an FLU body -> ENU world attitude.
Eigen::Quaterniond ned_frd_attitude(const Eigen::Quaterniond& enu_flu);

// The UAV's specific force (what its accelerometer reads: thrust and drag over the mass,
// gravity's reaction while it rests on a surface), FLU body, m/s^2.
Eigen::Vector3d uav_specific_force_flu(const World& world);

}  // namespace cover::sim::fc
