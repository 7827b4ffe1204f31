#include "cover/sim/world_segment.hpp"

namespace cover::sim {

const char* to_string(OffboardState state) {
  switch (state) {
    case OffboardState::WaitingForAgent:
      return "waiting-for-agent";
    case OffboardState::Offboard:
      return "offboard";
    case OffboardState::LossDescent:
      return "offboard-loss-descent";
    case OffboardState::LossDisarmed:
      return "offboard-loss-disarmed";
  }
  return "unknown";
}

RawImuSample to_raw(const ugv::ImuSample& sample) {
  RawImuSample raw;
  raw.stamp_s = sample.stamp_s;
  raw.specific_force_m_s2 = Vec3(sample.specific_force_m_s2);
  raw.angular_velocity_rad_s = Vec3(sample.angular_velocity_rad_s);
  raw.has_wheel_speed = sample.wheel_speed_m_s ? 1 : 0;
  raw.wheel_speed_m_s = sample.wheel_speed_m_s.value_or(0.0);
  return raw;
}

ugv::ImuSample from_raw(const RawImuSample& sample) {
  ugv::ImuSample s;
  s.stamp_s = sample.stamp_s;
  s.specific_force_m_s2 = sample.specific_force_m_s2.eigen();
  s.angular_velocity_rad_s = sample.angular_velocity_rad_s.eigen();
  if (sample.has_wheel_speed != 0) s.wheel_speed_m_s = sample.wheel_speed_m_s;
  return s;
}

}  // namespace cover::sim
