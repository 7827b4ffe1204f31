#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "cover/sim/frame_conventions.hpp"
#include "cover/sim/world.hpp"

namespace cover::sim::fc {

// The frame maps themselves (enu_to_ned, flu_to_frd, ned_frd_attitude) are the simulator's:
// cover/sim/frame_conventions.hpp.

// The UAV's specific force (what its accelerometer reads: thrust and drag over the mass,
// gravity's reaction while it rests on a surface), FLU body, m/s^2.
Eigen::Vector3d uav_specific_force_flu(const World& world);

}  // namespace cover::sim::fc
