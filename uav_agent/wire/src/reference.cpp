#include "cover/wire/reference.hpp"

#include <algorithm>
#include <cmath>

#include "cover/wire/eigen.hpp"
#include "cover/wire/enums.hpp"

namespace cover::wire {

msg::ReferenceTrajectory to_reference(const planner::Trajectory& trajectory, std::uint32_t uav_id,
                                      double stage_start_s, int reference_ugv, model::Stage stage,
                                      double dt_s, int max_samples) {
  msg::ReferenceTrajectory m;
  m.uav_id = uav_id;
  m.stamp_ns = to_stamp_ns(stage_start_s);
  m.reference_ugv = static_cast<std::uint32_t>(std::max(reference_ugv, 0));
  m.stage = to_msg(stage, mission::MissionState::Running);
  const double duration_s = std::max(trajectory.duration_s(), 0.0);
  const int wanted = static_cast<int>(std::ceil(duration_s / dt_s)) + 1;
  const int samples = std::clamp(wanted, 1, std::max(max_samples, 2));
  m.dt_s = samples > 1 ? duration_s / (samples - 1) : 0.0;
  for (int i = 0; i < samples; ++i) {
    const double t = i * m.dt_s;
    m.positions_m.push_back(to_msg(trajectory.position(t)));
    m.velocities_m_s.push_back(to_msg(trajectory.velocity(t)));
  }
  return m;
}

}  // namespace cover::wire
