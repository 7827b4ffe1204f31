#include "cover/wire/sensors.hpp"

#include "cover/wire/eigen.hpp"
#include "cover/wire/enums.hpp"

namespace cover::wire {

msg::RelativeState to_msg(const model::RelativeState& state, std::uint32_t uav_id,
                          std::uint32_t ugv_id, double position_std_m) {
  msg::RelativeState m;
  m.uav_id = uav_id;
  m.ugv_id = ugv_id;
  m.stamp_ns = to_stamp_ns(state.stamp_s);
  m.position_m = to_msg(state.position_m);
  m.velocity_m_s = to_msg(state.velocity_m_s);
  m.attitude = to_msg(state.attitude);
  m.valid = true;
  m.position_std_m = position_std_m;
  return m;
}

std::optional<model::RelativeState> from_msg(const msg::RelativeState& m) {
  if (!m.valid) return std::nullopt;
  model::RelativeState state;
  state.stamp_s = to_seconds(m.stamp_ns);
  state.position_m = to_eigen(m.position_m);
  state.velocity_m_s = to_eigen(m.velocity_m_s);
  state.attitude = to_eigen(m.attitude);
  return state;
}

msg::UgvImu to_msg(const ugv::FilteredImu& imu, const ugv::SpeedEstimate& speed,
                   std::uint32_t ugv_id, std::uint32_t seq) {
  msg::UgvImu m;
  m.ugv_id = ugv_id;
  m.stamp_ns = to_stamp_ns(imu.stamp_s);
  m.seq = seq;
  m.specific_force_m_s2 = to_msg(imu.specific_force_m_s2);
  m.angular_velocity_rad_s = to_msg(imu.angular_velocity_rad_s);
  m.angular_acceleration_rad_s2 = to_msg(imu.angular_acceleration_rad_s2);
  m.speed_m_s = speed.speed_m_s;
  m.speed_source = to_msg(speed.source);
  return m;
}

}  // namespace cover::wire
