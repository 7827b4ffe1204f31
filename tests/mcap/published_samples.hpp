#pragma once
// The samples the recorder and live-view tests publish (tests/mcap, tests/foxglove): each
// type's awkward values (stamps beyond 2^53, UTF-8, thirds, empty and growing sequences),
// numbered so that every sample differs and the checks can find it again.
#include <cstdint>
#include <string>

#include "cover/msg/types.hpp"

namespace cover::test {

inline msg::UgvImu imu_sample(std::uint32_t i) {
  msg::UgvImu s;
  s.ugv_id = 1;
  s.stamp_ns = 1'764'000'000'123'456'789 + i * 5'000'000LL;  // beyond 2^53
  s.seq = i;
  s.specific_force_m_s2 = {0.1 * i, -1.0 / 3.0, 9.80665};
  s.angular_velocity_rad_s = {1e-9 * i, 0.25, -0.5};
  s.angular_acceleration_rad_s2 = {3.0, 2.0, 1.0 + i};
  s.speed_m_s = 2.5 + 0.01 * i;
  s.speed_source = msg::SpeedSource::SPEED_SOURCE_IMU;
  return s;
}

// A reference of `points` positions.
inline msg::ReferenceTrajectory reference_sample(std::uint32_t i, std::uint32_t points) {
  msg::ReferenceTrajectory s;
  s.uav_id = 0;
  s.stamp_ns = 1'764'000'000'000'000'000 + i;
  s.reference_ugv = 1;
  s.stage = msg::Stage::STAGE_TRANSITION;
  s.dt_s = 0.1;
  for (std::uint32_t k = 0; k < points; ++k) s.positions_m.push_back({1.0 * k, 2.0 * i, -0.5});
  s.velocities_m_s.push_back({0.0, 0.0, 1.0 * i});
  return s;
}

inline msg::TransitionTask task_sample(std::uint32_t i) {
  msg::TransitionTask s;
  s.task_id = "task-" + std::to_string(i) + " \xc3\xa9";  // UTF-8 survives
  s.uav_id = 0;
  s.stamp_ns = 1'764'000'000'000'000'000 + 1000 * i;
  msg::TransitionProcess p;
  p.from_ugv = 0;
  p.to_ugv = 1;
  p.initial_point_m = {1, 2, 3};
  p.final_action = msg::FinalAction::FINAL_ACTION_DELIVER;
  p.vmax_m_s = 1.5;
  p.method = i % 2 ? "cover" : "";
  s.processes.assign(i % 3, p);  // none, one or two
  return s;
}

// `sample` restamped: a warm-up sample, told apart from the checked ones by its stamp.
template <typename T>
T warm(T sample, std::int64_t stamp_ns) {
  sample.stamp_ns = stamp_ns;
  return sample;
}

}  // namespace cover::test
