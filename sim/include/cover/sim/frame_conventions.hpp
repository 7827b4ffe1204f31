#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace cover::sim {

// The simulator's frames are ENU world / FLU body; MAVLink, PX4's simulator_mavlink and
// ArduPilot's JSON backend speak NED world / FRD body. Each map swaps or negates axes and
// is its own inverse.

// A world vector ENU <-> NED: (y, x, -z).
Eigen::Vector3d enu_to_ned(const Eigen::Vector3d& v);
// A body vector FLU <-> FRD: (x, -y, -z).
Eigen::Vector3d flu_to_frd(const Eigen::Vector3d& v);
inline Eigen::Vector3d frd_to_flu(const Eigen::Vector3d& v) {
  return flu_to_frd(v);
}

// The attitude FRD body -> NED world of an FLU body -> ENU world attitude, normalised, in
// the hemisphere w >= 0 as autopilots report it.
Eigen::Quaterniond ned_frd_attitude(const Eigen::Quaterniond& enu_flu);

}  // namespace cover::sim
