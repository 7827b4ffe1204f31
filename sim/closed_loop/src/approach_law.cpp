#include "cover/sim/approach_law.hpp"

#include <algorithm>
#include <cmath>

namespace cover::sim {

ApproachLawResult fly_approach_law(const UgvMotionPattern& target, double start_time_s,
                                   const Eigen::Vector2d& start_position_m,
                                   const Eigen::Vector2d& start_velocity_m_s,
                                   const ApproachLawParams& params) {
  ApproachLawResult result;
  Eigen::Vector2d position = start_position_m;
  Eigen::Vector2d velocity = start_velocity_m_s;
  const int steps = static_cast<int>(std::ceil(params.max_duration_s / params.step_s));
  for (int k = 0; k < steps; ++k) {
    const UgvKinematics ugv = target.at(start_time_s + k * params.step_s);
    const Eigen::Vector2d to_ugv = ugv.position_m - position;
    const double distance = to_ugv.norm();
    if (distance < params.reach_tolerance_m &&
        (velocity - ugv.velocity_m_s).norm() < params.speed_threshold_m_s) {
      result.reached = true;
      result.duration_s = k * params.step_s;
      break;
    }
    // Eq. 30 in the world: the UGV's velocity plus the approach, which brakes at amax so
    // that it stops at the UGV.
    const double approach_m_s =
        std::min(params.vmax_m_s, std::sqrt(2.0 * params.amax_m_s2 * distance));
    const Eigen::Vector2d direction =
        distance > 1e-9 ? Eigen::Vector2d(to_ugv / distance) : Eigen::Vector2d::Zero();
    const Eigen::Vector2d wanted = ugv.velocity_m_s + approach_m_s * direction;
    Eigen::Vector2d acceleration = (wanted - velocity) / params.response_time_s;
    const double norm = acceleration.norm();
    if (norm > params.amax_m_s2) acceleration *= params.amax_m_s2 / norm;
    velocity += acceleration * params.step_s;
    const Eigen::Vector2d next = position + velocity * params.step_s;
    result.path_length_m += (next - position).norm();
    position = next;
  }
  if (!result.reached) result.duration_s = params.max_duration_s;
  result.straight_length_m = (position - start_position_m).norm();
  return result;
}

}  // namespace cover::sim
