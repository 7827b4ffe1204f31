#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace cover::model {

// The UAV's state relative to one UGV, in that UGV's frame G_k (docs/model.md):
// p = R_k^T (p_uav - p_ugv), v = R_k^T (v_uav - v_ugv) - Omega x p (d/dt of p seen in G_k),
// q = q_k^-1 q_uav. What a relative localisation system (mocap, UWB + vision) measures and
// what the controller consumes; the simulator's sensor produces it, the wire carries it.
struct RelativeState {
  double stamp_s = 0.0;  // the instant the state describes (not when it arrived)
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d velocity_m_s = Eigen::Vector3d::Zero();
  Eigen::Quaterniond attitude = Eigen::Quaterniond::Identity();  // A in G_k
};

}  // namespace cover::model
