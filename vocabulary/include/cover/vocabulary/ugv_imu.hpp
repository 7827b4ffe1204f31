#pragma once

#include <Eigen/Core>
#include <optional>

namespace cover::ugv {

// One raw IMU sample in the UGV body frame (FLU). Specific force includes gravity:
// a UGV at rest reads [0, 0, +9.81].
struct ImuSample {
  double stamp_s = 0.0;
  Eigen::Vector3d specific_force_m_s2 = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_velocity_rad_s = Eigen::Vector3d::Zero();
  // The wheel odometry's forward speed read with this sample, on vehicles that have it
  // (not part of the IMU, which ignores it: the device read delivers both, in order).
  std::optional<double> wheel_speed_m_s;
};

// What the controller consumes: the filtered a, Omega and the estimated beta (all in G_k).
struct FilteredImu {
  double stamp_s = 0.0;
  Eigen::Vector3d specific_force_m_s2 = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_velocity_rad_s = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_acceleration_rad_s2 = Eigen::Vector3d::Zero();
};

}  // namespace cover::ugv
