#include "cover/planner/trajectory_metrics.hpp"

#include <algorithm>

namespace cover::planner {

TrajectoryMetrics measure_trajectory(const Trajectory& trajectory, const StageProblem& problem,
                                     int samples_per_piece) {
  TrajectoryMetrics m;
  const double duration = trajectory.duration_s();
  const Eigen::Vector3d v0 = initial_velocity(problem);
  m.duration_s = duration;
  const int samples = std::max(1, samples_per_piece * trajectory.piece_count());
  for (int k = 0; k <= samples; ++k) {
    const double t = duration * k / samples;
    m.max_speed_m_s = std::max(m.max_speed_m_s, trajectory.velocity(t).norm());
    m.max_acc_m_s2 = std::max(m.max_acc_m_s2, trajectory.acceleration(t).norm());
  }
  m.start_position_error_m = (trajectory.position(0.0) - problem.start_position_m).norm();
  m.start_velocity_error_m_s = (trajectory.velocity(0.0) - v0).norm();
  m.start_acc_m_s2 = trajectory.acceleration(0.0).norm();
  m.end_position_error_m = (trajectory.position(duration) - problem.goal_position_m).norm();
  m.end_speed_m_s = trajectory.velocity(duration).norm();
  m.end_acc_m_s2 = trajectory.acceleration(duration).norm();
  const double speed_limit = std::max(problem.vmax_m_s, v0.norm());
  m.speed_violation = std::max(0.0, m.max_speed_m_s / speed_limit - 1.0);
  m.acc_violation = std::max(0.0, m.max_acc_m_s2 / problem.amax_m_s2 - 1.0);
  return m;
}

}  // namespace cover::planner
