#include "cover/wire/ugv_imu_measurement.hpp"

#include <cmath>

#include "cover/wire/eigen.hpp"
#include "cover/wire/enums.hpp"

namespace cover::wire {

mission::UgvImuMeasurement from_msg(const msg::UgvImu& m) {
  mission::UgvImuMeasurement imu;
  imu.stamp_s = to_seconds(m.stamp_ns);
  imu.motion.specific_force_m_s2 = to_eigen(m.specific_force_m_s2);
  imu.motion.angular_velocity_rad_s = to_eigen(m.angular_velocity_rad_s);
  imu.motion.angular_acceleration_rad_s2 = to_eigen(m.angular_acceleration_rad_s2);
  const std::optional<model::SpeedSource> source = from_msg(m.speed_source);
  if (source && std::isfinite(m.speed_m_s)) {
    imu.motion.speed_m_s = m.speed_m_s;
    imu.motion.speed_source = *source;
  }
  return imu;
}

}  // namespace cover::wire
