#include "cover/planner/stage_problem.hpp"

#include <Eigen/Geometry>

namespace cover::planner {

Eigen::Vector3d initial_velocity(const StageProblem& problem) {
  if (!problem.transition_stage) return problem.start_velocity_m_s;
  return problem.start_velocity_m_s +
         problem.ugv_angular_velocity_rad_s.cross(problem.start_position_m);
}

Eigen::Vector3d initial_acceleration(const StageProblem& problem) {
  if (problem.transition_stage) return Eigen::Vector3d::Zero();
  const Eigen::Vector3d& a = problem.start_acceleration_m_s2;
  const double norm = a.norm();
  if (norm > problem.amax_m_s2) return a * (problem.amax_m_s2 / norm);
  return a;
}

}  // namespace cover::planner
