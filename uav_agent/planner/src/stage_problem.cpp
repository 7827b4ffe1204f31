#include "cover/planner/stage_problem.hpp"

#include <Eigen/Geometry>

namespace cover::planner {

Eigen::Vector3d initial_velocity(const StageProblem& problem) {
  if (!problem.transition_stage) return problem.start_velocity_m_s;
  return problem.start_velocity_m_s +
         problem.ugv_angular_velocity_rad_s.cross(problem.start_position_m);
}

}  // namespace cover::planner
