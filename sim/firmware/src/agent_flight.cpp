#include "cover/firmware/agent_flight.hpp"

#include <algorithm>
#include <cmath>

#include "cover/clock/clock.hpp"

namespace cover::firmware {
namespace {

constexpr double kHeightGain_per_s = 1.0;  // climb speed asked per metre below the height
constexpr double kMaxClimb_m_s = 1.0;
constexpr double kSpeedGain_per_s = 2.0;  // thrust per m/s of climb-speed error, / g
constexpr double kLevelGain_per_s = 2.0;  // rate asked per radian of tilt
constexpr double kMinThrust_g = 0.6;
constexpr double kMaxThrust_g = 1.4;

double height_thrust(const FirmwareMonitor& monitor, double height) {
  const auto p = monitor.position();
  if (!p) return kGravity_m_s2;
  const double climb = -p->value.vz;
  const double wanted =
      std::clamp(kHeightGain_per_s * (height - height_m(p->value)), -kMaxClimb_m_s, kMaxClimb_m_s);
  return std::clamp(kGravity_m_s2 + kSpeedGain_per_s * (wanted - climb),
                    kMinThrust_g * kGravity_m_s2, kMaxThrust_g * kGravity_m_s2);
}

}  // namespace

Euler euler(const mavlink::AttitudeQuaternion& q) {
  const double w = q.q1, x = q.q2, y = q.q3, z = q.q4;
  Euler e;
  e.roll = std::atan2(2.0 * (w * x + y * z), 1.0 - 2.0 * (x * x + y * y));
  e.pitch = std::asin(std::clamp(2.0 * (w * y - z * x), -1.0, 1.0));
  e.yaw = std::atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z));
  return e;
}

AgentSetpoint motors_off() {
  return AgentSetpoint{};
}

AgentSetpoint hover() {
  AgentSetpoint s;
  s.thrust_m_s2 = kGravity_m_s2;
  s.armed = true;
  return s;
}

AgentStream::Policy hold_height(const FirmwareMonitor& monitor, double height_m,
                                AgentSetpoint extra) {
  return [&monitor, height_m, extra] {
    AgentSetpoint s = hover();
    s.thrust_m_s2 = height_thrust(monitor, height_m);
    if (const auto a = monitor.attitude()) {
      const Euler e = euler(a->value);
      // FRD roll is FLU roll; FRD pitch (nose up) is minus FLU pitch (about y left).
      s.roll_rate = extra.roll_rate != 0.0 ? extra.roll_rate : -kLevelGain_per_s * e.roll;
      s.pitch_rate = extra.pitch_rate != 0.0 ? extra.pitch_rate : kLevelGain_per_s * e.pitch;
    }
    s.yaw_rate = extra.yaw_rate;
    return s;
  };
}

AgentStream::Policy roll_rate_doublet(const FirmwareMonitor& monitor, double height_m,
                                      std::int64_t start_ns, double rate,
                                      std::chrono::milliseconds duration,
                                      std::chrono::milliseconds pause) {
  const std::int64_t step_ns = std::chrono::nanoseconds(duration).count();
  const std::int64_t pause_ns = std::chrono::nanoseconds(pause).count();
  const auto level = hold_height(monitor, height_m);
  return [&monitor, height_m, start_ns, rate, step_ns, pause_ns, level] {
    const std::int64_t t = clock::monotonic_ns() - start_ns;
    if (t >= 2 * step_ns + pause_ns) return level();
    AgentSetpoint s = hover();
    s.thrust_m_s2 = height_thrust(monitor, height_m);
    s.roll_rate = t < step_ns ? rate : t < step_ns + pause_ns ? 0.0 : -rate;
    return s;
  };
}

}  // namespace cover::firmware
