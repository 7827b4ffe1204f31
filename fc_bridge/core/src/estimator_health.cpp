#include "cover/fc_bridge/estimator_health.hpp"

#include "cover/mavlink/protocol.hpp"
#include "cover/mavlink/state_messages.hpp"

namespace cover::fc_bridge {
namespace {

namespace mav = cover::mavlink;
namespace sensor = cover::mavlink::mav_sys_status_sensor;
namespace flag = cover::mavlink::estimator_flags;
// ArduPilot's EKF_STATUS_FLAGS bit 10 is EKF_UNINITIALIZED (PX4's is a GPS glitch).
constexpr std::uint16_t kArduPilotUninitialised = 1024;

void append(std::string& text, const char* part, const char* separator = ", ") {
  if (!text.empty()) text += separator;
  text += part;
}

}  // namespace

void EstimatorHealthTracker::on_sys_status(const mavlink::SysStatus& status) {
  sys_status_seen_ = true;
  present_ = status.onboard_control_sensors_present;
  enabled_ = status.onboard_control_sensors_enabled;
  healthy_ = status.onboard_control_sensors_health;
}

void EstimatorHealthTracker::on_estimator_flags(std::uint16_t flags) {
  flags_seen_ = true;
  flags_ = flags;
}

std::string EstimatorHealthTracker::sensor_problems() const {
  struct Sensor {
    std::uint32_t bit;
    const char* name;
  };
  constexpr Sensor kSensors[] = {{sensor::kGyro3d, "gyro"},
                                 {sensor::kAccel3d, "accelerometer"},
                                 {sensor::kMag3d, "magnetometer"},
                                 {sensor::kAbsolutePressure, "barometer"},
                                 {sensor::kAhrs, "attitude estimator (AHRS)"}};
  std::string text;
  for (const Sensor& s : kSensors) {
    const bool in_use = (present_ & s.bit) != 0 && (enabled_ & s.bit) != 0;
    if (in_use && (healthy_ & s.bit) == 0) append(text, s.name);
  }
  return text.empty() ? text : text + " unhealthy";
}

std::string EstimatorHealthTracker::flag_summary() const {
  if (kind_ == Autopilot::ArduPilot && (flags_ & kArduPilotUninitialised) != 0) {
    return "EKF not initialised";
  }
  std::string good;
  if ((flags_ & flag::kAttitude) != 0) append(good, "attitude");
  if ((flags_ & flag::kVelocityHoriz) != 0) append(good, "horizontal velocity");
  if ((flags_ & flag::kVelocityVert) != 0) append(good, "vertical velocity");
  if ((flags_ & flag::kPosVertAbs) != 0) append(good, "altitude");
  if ((flags_ & (flag::kPosHorizRel | flag::kPosHorizAbs)) != 0) append(good, "position");
  std::string text = good.empty() ? "no valid estimate" : good + " ok";
  if ((flags_ & flag::kAttitude) == 0) append(text, "attitude not aligned", "; ");
  if ((flags_ & flag::kAccelError) != 0) append(text, "accelerometer error", "; ");
  return text;
}

EstimatorHealth EstimatorHealthTracker::health() const {
  EstimatorHealth h;
  h.reported = sys_status_seen_ || flags_seen_;
  if (!h.reported) return h;
  const bool ahrs_ok =
      !sys_status_seen_ || (present_ & sensor::kAhrs) == 0 || (healthy_ & sensor::kAhrs) != 0;
  const bool flags_ok =
      !flags_seen_ || ((flags_ & flag::kAttitude) != 0 &&
                       !(kind_ == Autopilot::ArduPilot && (flags_ & kArduPilotUninitialised) != 0));
  h.attitude_ok = ahrs_ok && flags_ok;
  if (flags_seen_) h.text = flag_summary();
  const std::string problems = sys_status_seen_ ? sensor_problems() : std::string();
  if (!problems.empty()) append(h.text, problems.c_str(), "; ");
  if (h.text.empty()) h.text = "sensors healthy (no estimator flags reported)";
  return h;
}

bool EstimatorHealthTracker::vertical_velocity_ok() const {
  return !flags_seen_ || (flags_ & mavlink::estimator_flags::kVelocityVert) != 0;
}

}  // namespace cover::fc_bridge
