#pragma once

#include <Eigen/Core>

namespace cover::model {

// Standard gravity; the hover thrust per unit mass.
inline constexpr double kGravity_m_s2 = 9.81;

// Sizes of the full 19-state model, its input, and the 10 UAV states the controller
// actually decides (the UGV quantities are known parameters over the horizon).
inline constexpr int kStateSize = 19;
inline constexpr int kInputSize = 4;
inline constexpr int kUavStateSize = 10;

// Index of the first component of each block of the state (docs/model.md, "System model").
// The first three blocks are also the layout of UavState.
namespace idx {
inline constexpr int kPosition = 0;          // p: UAV position in G_k (m)
inline constexpr int kVelocity = 3;          // v: UAV velocity in G_k (m/s)
inline constexpr int kQuaternion = 6;        // q: attitude of A in G_k, Hamilton, w x y z
inline constexpr int kSpecificForce = 10;    // a: UGV accelerometer reading in G_k (m/s^2)
inline constexpr int kAngularVelocity = 13;  // Omega: UGV angular velocity in G_k (rad/s)
inline constexpr int kAngularAccel = 16;     // beta: UGV angular acceleration in G_k (rad/s^2)
}  // namespace idx

// Index of each input component: collective thrust per unit mass (m/s^2), body rates (rad/s).
namespace input_idx {
inline constexpr int kThrust = 0;
inline constexpr int kRateX = 1;
inline constexpr int kRateY = 2;
inline constexpr int kRateZ = 3;
}  // namespace input_idx

using State = Eigen::Matrix<double, kStateSize, 1>;
using UavState = Eigen::Matrix<double, kUavStateSize, 1>;
using Input = Eigen::Matrix<double, kInputSize, 1>;

// u_h = [g, 0, 0, 0]: holds a level UAV still relative to a UGV at rest.
inline Input hover_input() {
  return Input(kGravity_m_s2, 0.0, 0.0, 0.0);
}

// A UAV state at `position_m`, at rest and level (q = identity).
inline UavState uav_state_at_rest(const Eigen::Vector3d& position_m) {
  UavState x = UavState::Zero();
  x.segment<3>(idx::kPosition) = position_m;
  x(idx::kQuaternion) = 1.0;
  return x;
}

}  // namespace cover::model
