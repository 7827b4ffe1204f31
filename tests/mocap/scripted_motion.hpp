#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

// The tests' scripted motion (issue 23): a UGV accelerating (1 -> 3 m/s over 10 s) and
// turning harder and harder (yaw rate 0.1 -> 0.5 rad/s; lateral acceleration up to
// 1.5 m/s^2, a brisk car), a UAV moving in its frame. Written in G_k so the truth of "velocity as
// seen in G_k" is the analytic derivative, independent of the relay's formula.
namespace cover::test::mocap_motion {

struct Pose {
  Eigen::Vector3d position_m;
  Eigen::Quaterniond attitude;
};

inline double ugv_yaw(double t) {
  return 0.1 * t + 0.02 * t * t;
}

inline Pose ugv(double t) {
  return {Eigen::Vector3d(t + 0.1 * t * t, 0.3 * std::sin(0.5 * t), 0.3),
          Eigen::Quaterniond(Eigen::AngleAxisd(ugv_yaw(t), Eigen::Vector3d::UnitZ()))};
}

// UAV in G_k.
inline Eigen::Vector3d uav_in_ugv(double t) {
  return {1.0 + 0.5 * std::sin(0.8 * t), 0.3 * std::cos(0.6 * t), 1.2 + 0.2 * std::sin(t)};
}
inline Eigen::Vector3d uav_velocity_in_ugv(double t) {
  return {0.4 * std::cos(0.8 * t), -0.18 * std::sin(0.6 * t), 0.2 * std::cos(t)};
}
inline Eigen::Quaterniond uav_attitude_in_ugv(double t) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(0.2 * std::sin(t), Eigen::Vector3d::UnitZ()) *
                            Eigen::AngleAxisd(0.05, Eigen::Vector3d::UnitX()));
}

inline Pose uav(double t) {
  const Pose g = ugv(t);
  return {g.position_m + g.attitude * uav_in_ugv(t), g.attitude * uav_attitude_in_ugv(t)};
}

}  // namespace cover::test::mocap_motion
