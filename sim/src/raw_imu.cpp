#include "cover/sim/raw_imu.hpp"

namespace cover::sim {

RawImuSample to_raw(const ugv::ImuSample& sample) {
  RawImuSample raw;
  raw.stamp_s = sample.stamp_s;
  raw.specific_force_m_s2 = Vec3(sample.specific_force_m_s2);
  raw.angular_velocity_rad_s = Vec3(sample.angular_velocity_rad_s);
  raw.has_wheel_speed = sample.wheel_speed_m_s ? 1 : 0;
  raw.wheel_speed_m_s = sample.wheel_speed_m_s.value_or(0.0);
  return raw;
}

}  // namespace cover::sim
