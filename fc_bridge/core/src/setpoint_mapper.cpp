#include "cover/fc_bridge/setpoint_mapper.hpp"

#include <algorithm>
#include <cmath>

#include "cover/mavlink/protocol.hpp"

namespace cover::fc_bridge {
namespace {
constexpr double kMaxRate_rad_s = 100.0;
constexpr double kMaxThrust_m_s2 = 1000.0;
}  // namespace

bool is_flyable(const AgentCommand& c) {
  auto rate_ok = [](double v) { return std::isfinite(v) && std::abs(v) <= kMaxRate_rad_s; };
  return std::isfinite(c.thrust_m_s2) && std::abs(c.thrust_m_s2) <= kMaxThrust_m_s2 &&
         rate_ok(c.roll_rate_rad_s) && rate_ok(c.pitch_rate_rad_s) && rate_ok(c.yaw_rate_rad_s);
}

double SetpointMapper::normalised_thrust(const AgentCommand& command, double hover_thrust) const {
  if (!command.armed) return 0.0;
  const double u = command.thrust_m_s2 * hover_thrust / gravity_m_s2_;
  return std::isfinite(u) ? std::clamp(u, 0.0, 1.0) : 0.0;
}

mavlink::SetAttitudeTarget SetpointMapper::map(const AgentCommand& command, double hover_thrust,
                                               std::uint8_t target_system,
                                               std::uint8_t target_component) const {
  mavlink::SetAttitudeTarget target;
  const std::int64_t stamp_ms = std::max<std::int64_t>(command.stamp_ns, 0) / 1'000'000;
  target.time_boot_ms = static_cast<std::uint32_t>(stamp_ms & 0xFFFFFFFF);
  target.type_mask = mavlink::attitude_target_typemask::kIgnoreAttitude;
  target.target_system = target_system;
  target.target_component = target_component;
  target.body_roll_rate = static_cast<float>(command.roll_rate_rad_s);
  target.body_pitch_rate = static_cast<float>(-command.pitch_rate_rad_s);
  target.body_yaw_rate = static_cast<float>(-command.yaw_rate_rad_s);
  target.thrust = static_cast<float>(normalised_thrust(command, hover_thrust));
  return target;
}

}  // namespace cover::fc_bridge
