#pragma once

#include <Eigen/Core>

#include "cover/sim/ugv_motion_pattern.hpp"
#include "cover/vocabulary/motion_limits.hpp"

namespace cover::sim {

// The transition stage as the paper's velocity law (eq. 30) would fly it with a perfect
// controller: a horizontal point mass whose velocity relative to the target UGV's
// translation points at the UGV, at the reference speed, while the UGV drives its
// pattern. In the world frame the UAV therefore moves with the UGV's velocity plus the
// approach, so part of the UGV's own curve is in its path: this is what Table 1's L_t/L_s
// can reach at best with eq. 30, given the same start. The benchmark prints it next to the
// closed-loop ratio, so a reader can tell the controller's losses from the law's.
struct ApproachLawParams {
  double vmax_m_s = mission::kDefaultVmax_m_s;    // approach speed limit relative to the UGV
  double amax_m_s2 = mission::kDefaultAmax_m_s2;  // acceleration limit (world frame)
  double response_time_s = 0.1;                   // first-order lag of the velocity toward the law
  double reach_tolerance_m = 0.3;                 // the stage ends this close to the UGV ...
  double speed_threshold_m_s = 0.3;               // ... and this slow relative to it
  double step_s = 0.01;                           // Euler step
  double max_duration_s = 60.0;                   // gives up (reached = false) after this
};

struct ApproachLawResult {
  bool reached = false;
  double duration_s = 0.0;
  double path_length_m = 0.0;      // L_t of the ideal flight
  double straight_length_m = 0.0;  // L_s: |end - start|
};

// Flies from `start_position_m` with `start_velocity_m_s` (world, horizontal) at time
// `start_time_s` toward the UGV driving `target`.
ApproachLawResult fly_approach_law(const UgvMotionPattern& target, double start_time_s,
                                   const Eigen::Vector2d& start_position_m,
                                   const Eigen::Vector2d& start_velocity_m_s,
                                   const ApproachLawParams& params);

}  // namespace cover::sim
