#pragma once

#include <Eigen/Core>

namespace cover::planner {

// One stage to plan, everything expressed in the stage's reference frame G_k (paper sec. 4.2).
struct StageProblem {
  Eigen::Vector3d start_position_m = Eigen::Vector3d::Zero();
  // The UAV velocity v in G_k (the state's velocity, rotation-induced part included).
  Eigen::Vector3d start_velocity_m_s = Eigen::Vector3d::Zero();
  // The UAV's acceleration in G_k at the start, where the trajectory starts with it: a stage
  // that begins mid-manoeuvre would otherwise ask for zero acceleration at once. Ignored at
  // the transition stage (eq. 23's velocity is in another frame). Capped at amax_m_s2.
  Eigen::Vector3d start_acceleration_m_s2 = Eigen::Vector3d::Zero();
  // The stage transition point p_t(s); the trajectory ends there at rest.
  Eigen::Vector3d goal_position_m = Eigen::Vector3d::Zero();
  // Already relative limits (eq. 15: vm = vmax_uav - vmax_ugv, am = amax_uav - amax_ugv).
  double vmax_m_s = 1.0;
  double amax_m_s2 = 2.0;
  // Apply eq. 23 (transition stage only): v0 = v + Omega x p.
  bool transition_stage = false;
  // Omega: the reference UGV's angular velocity in G_k; used only when transition_stage.
  Eigen::Vector3d ugv_angular_velocity_rad_s = Eigen::Vector3d::Zero();
};

// The trajectory's initial velocity v0(s) of eq. 23: at the transition stage the part
// induced by the frame's rotation is removed (v + Omega x p is the relative translational
// velocity), so a fast-turning UGV far away does not make the start look over-speed.
Eigen::Vector3d initial_velocity(const StageProblem& problem);

// The trajectory's initial acceleration: start_acceleration_m_s2 capped at amax_m_s2, zero
// at the transition stage.
Eigen::Vector3d initial_acceleration(const StageProblem& problem);

}  // namespace cover::planner
