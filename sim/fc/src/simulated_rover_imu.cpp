#include "cover/sim/fc/simulated_rover_imu.hpp"

#include <cmath>

#include "cover/mavlink/messages.hpp"
#include "cover/mavlink/protocol.hpp"
#include "cover/sim/fc/frame_conventions.hpp"

namespace cover::sim::fc {

namespace {
constexpr std::uint16_t kImuFieldsUpdated = 0x3F;  // x/y/z acceleration and gyro
}  // namespace

SimulatedRoverImu::SimulatedRoverImu(std::uint8_t system_id, double heartbeat_rate_hz)
    : encoder_(system_id, mavlink::mav_comp::kAutopilot1), period_s_(1.0 / heartbeat_rate_hz) {}

mavlink::EncodedFrame SimulatedRoverImu::imu_frame(const RawImuSample& sample) {
  const Eigen::Vector3d force = flu_to_frd(sample.specific_force_m_s2.eigen());
  const Eigen::Vector3d gyro = flu_to_frd(sample.angular_velocity_rad_s.eigen());
  mavlink::HighresImu imu;
  imu.time_usec = static_cast<std::uint64_t>(std::llround(std::max(0.0, sample.stamp_s) * 1e6));
  imu.xacc = static_cast<float>(force.x());
  imu.yacc = static_cast<float>(force.y());
  imu.zacc = static_cast<float>(force.z());
  imu.xgyro = static_cast<float>(gyro.x());
  imu.ygyro = static_cast<float>(gyro.y());
  imu.zgyro = static_cast<float>(gyro.z());
  imu.fields_updated = kImuFieldsUpdated;
  return encoder_.encode(imu);
}

std::optional<mavlink::EncodedFrame> SimulatedRoverImu::heartbeat_due(double now_s) {
  if (now_s + 1e-9 < next_heartbeat_s_) return std::nullopt;
  next_heartbeat_s_ = now_s + period_s_;
  return heartbeat_frame();
}

mavlink::EncodedFrame SimulatedRoverImu::heartbeat_frame() {
  mavlink::Heartbeat h;
  h.custom_mode = mavlink::px4_mode::custom_mode(mavlink::px4_mode::kMainManual);
  h.type = mavlink::mav_type::kGroundRover;
  h.autopilot = mavlink::mav_autopilot::kPx4;
  h.base_mode = mavlink::mav_mode_flag::kCustomModeEnabled;
  h.system_status = mavlink::mav_state::kStandby;
  return encoder_.encode(h);
}

}  // namespace cover::sim::fc
