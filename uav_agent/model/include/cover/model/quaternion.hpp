#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

namespace cover::model {

// Quaternions are stored as Eigen::Vector4d in Hamilton convention, `w` first (docs/model.md),
// which is the layout inside the state vector. These helpers keep the algebra explicit.
using QuaternionWxyz = Eigen::Vector4d;

// Matrix L(q) with q (x) p = L(q) p.
inline Eigen::Matrix4d left_product_matrix(const QuaternionWxyz& q) {
  Eigen::Matrix4d m;
  m << q(0), -q(1), -q(2), -q(3),  //
      q(1), q(0), -q(3), q(2),     //
      q(2), q(3), q(0), -q(1),     //
      q(3), -q(2), q(1), q(0);
  return m;
}

// Matrix R(p) with q (x) p = R(p) q.
inline Eigen::Matrix4d right_product_matrix(const QuaternionWxyz& p) {
  Eigen::Matrix4d m;
  m << p(0), -p(1), -p(2), -p(3),  //
      p(1), p(0), p(3), -p(2),     //
      p(2), -p(3), p(0), p(1),     //
      p(3), p(2), -p(1), p(0);
  return m;
}

inline QuaternionWxyz multiply(const QuaternionWxyz& q, const QuaternionWxyz& p) {
  return left_product_matrix(q) * p;
}

// Rotation matrix of a unit quaternion (maps body vectors into the parent frame).
inline Eigen::Matrix3d rotation_matrix(const QuaternionWxyz& q) {
  const double w = q(0), x = q(1), y = q(2), z = q(3);
  Eigen::Matrix3d r;
  r << 1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y),  //
      2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x),   //
      2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y);
  return r;
}

// R(q) [0, 0, 1]: the thrust direction. Written in the homogeneous form (w^2 - x^2 - y^2 + z^2
// for the last row) so that it and its Jacobian are polynomials in q.
inline Eigen::Vector3d thrust_direction(const QuaternionWxyz& q) {
  const double w = q(0), x = q(1), y = q(2), z = q(3);
  return {2 * (x * z + w * y), 2 * (y * z - w * x), w * w - x * x - y * y + z * z};
}

// d thrust_direction / dq (3x4, columns w x y z).
inline Eigen::Matrix<double, 3, 4> thrust_direction_jacobian(const QuaternionWxyz& q) {
  const double w = q(0), x = q(1), y = q(2), z = q(3);
  Eigen::Matrix<double, 3, 4> j;
  j << 2 * y, 2 * z, 2 * w, 2 * x,   //
      -2 * x, -2 * w, 2 * z, 2 * y,  //
      2 * w, -2 * x, -2 * y, 2 * z;
  return j;
}

// Yaw-only attitude [cos(psi/2), 0, 0, sin(psi/2)].
inline QuaternionWxyz yaw_quaternion(double yaw_rad) {
  return {std::cos(0.5 * yaw_rad), 0.0, 0.0, std::sin(0.5 * yaw_rad)};
}

inline Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v(2), v(1),  //
      v(2), 0, -v(0),   //
      -v(1), v(0), 0;
  return m;
}

}  // namespace cover::model
