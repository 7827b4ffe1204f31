#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <string>

namespace cover::mocap {

// A pose in COVER's world frame: z up, metres.
struct WorldPose {
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();
  Eigen::Quaterniond attitude = Eigen::Quaterniond::Identity();
};

// A server's pose (its up axis, its units, quaternion x, y, z, w) in COVER's world frame.
// y up: the server's frame is ours rotated -90 deg about x, so (X, Y, Z) -> (X, -Z, Y),
// bodies' axes included (a level body reads as the identity in both).
WorldPose to_world(const std::array<double, 3>& position, const std::array<double, 4>& xyzw,
                   const std::string& up_axis, const std::string& units);

}  // namespace cover::mocap
