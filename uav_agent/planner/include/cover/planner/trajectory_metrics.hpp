#pragma once

#include "cover/planner/stage_problem.hpp"
#include "cover/planner/trajectory.hpp"

namespace cover::planner {

// How well a trajectory solves its stage, from dense sampling (not the optimiser's samples).
struct TrajectoryMetrics {
  double duration_s = 0.0;
  double max_speed_m_s = 0.0;
  double max_acc_m_s2 = 0.0;
  double start_position_error_m = 0.0;
  double start_velocity_error_m_s = 0.0;  // against v0 of eq. 23
  double start_acc_m_s2 = 0.0;
  double end_position_error_m = 0.0;
  double end_speed_m_s = 0.0;
  double end_acc_m_s2 = 0.0;
  // Fractions of the limit, >= 0. The speed limit is max(vm, |v0|): a stage that starts
  // faster than vm (unavoidable right after a frame switch) may not speed up further.
  double speed_violation = 0.0;
  double acc_violation = 0.0;
};

TrajectoryMetrics measure_trajectory(const Trajectory& trajectory, const StageProblem& problem,
                                     int samples_per_piece = 100);

}  // namespace cover::planner
