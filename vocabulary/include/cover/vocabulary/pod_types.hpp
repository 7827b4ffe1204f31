#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <type_traits>

namespace cover::sim {

// Plain vector and quaternion types for the world state. Eigen's types are not
// trivially copyable, and the world state must be memcpy-able into a shared-memory
// segment (a later issue runs the simulator as its own process). Convert at the edges.
struct Vec3 {
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;

  Vec3() = default;
  Vec3(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}
  explicit Vec3(const Eigen::Vector3d& v) : x(v.x()), y(v.y()), z(v.z()) {}
  Eigen::Vector3d eigen() const { return {x, y, z}; }
};

// Hamilton quaternion, w first (docs/model.md).
struct Quat {
  double w = 1.0;
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;

  Quat() = default;
  explicit Quat(const Eigen::Quaterniond& q) : w(q.w()), x(q.x()), y(q.y()), z(q.z()) {}
  Eigen::Quaterniond eigen() const { return {w, x, y, z}; }
};

static_assert(std::is_trivially_copyable_v<Vec3>);
static_assert(std::is_trivially_copyable_v<Quat>);

// Rotation about world z by `yaw_rad` (UGVs are planar: yaw only).
inline Eigen::Quaterniond yaw_quaternion(double yaw_rad) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()));
}

}  // namespace cover::sim
