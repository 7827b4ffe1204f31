// The telemetry streams of the simulated autopilot, in MAVLink's frames (NED / FRD).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "cover/mavlink/protocol.hpp"
#include "cover/mavlink/state_messages.hpp"
#include "cover/sim/fc/frame_conventions.hpp"
#include "cover/sim/fc/simulated_autopilot.hpp"

namespace cover::sim::fc {

namespace {

namespace sensor = mavlink::mav_sys_status_sensor;
namespace flag = mavlink::estimator_flags;

// MAV_SYS_STATUS_SENSOR bits beyond the codec's.
constexpr std::uint32_t kRateControl = 0x400;
constexpr std::uint32_t kAttitudeStabilisation = 0x800;
constexpr std::uint32_t kYawPosition = 0x1000;
constexpr std::uint32_t kZAltitudeControl = 0x2000;
constexpr std::uint32_t kXyPositionControl = 0x4000;
constexpr std::uint32_t kMotorOutputs = 0x8000;
constexpr std::uint32_t kGeofence = 0x100000;
constexpr std::uint32_t kTerrain = 0x400000;
constexpr std::uint32_t kLogging = 0x1000000;
constexpr std::uint32_t kBattery = 0x2000000;
constexpr std::uint32_t kProximity = 0x4000000;
constexpr std::uint32_t kPropulsion = 0x40000000;
constexpr std::uint32_t kImuBaroMag =
    sensor::kGyro3d | sensor::kAccel3d | sensor::kMag3d | sensor::kAbsolutePressure;

// SYS_STATUS sensor bits as PX4 SITL and ArduCopter SITL sent them (real SITL, docs/autopilots.md),
// without GPS and RC receiver (the simulated vehicle has neither). PX4 reports the AHRS healthy
// without declaring it present; ArduPilot enables and passes it (and its pre-arm check)
// once EKF3 has aligned.
struct SensorBits {
  std::uint32_t present, enabled, health;
};
SensorBits px4_sensors(bool aligned) {
  const std::uint32_t present = kImuBaroMag | kXyPositionControl | kBattery;
  std::uint32_t health = kImuBaroMag | kAttitudeStabilisation | kXyPositionControl | kMotorOutputs |
                         kLogging | kBattery | sensor::kPrearmCheck;
  if (aligned) health |= sensor::kAhrs;
  return {present, present, health};
}
SensorBits ardupilot_sensors(bool aligned) {
  const std::uint32_t control = kRateControl | kAttitudeStabilisation | kYawPosition;
  const std::uint32_t present = kImuBaroMag | control | kZAltitudeControl | kXyPositionControl |
                                kMotorOutputs | kGeofence | sensor::kAhrs | kTerrain | kLogging |
                                kBattery | sensor::kPrearmCheck | kPropulsion;
  std::uint32_t enabled = kImuBaroMag | control | kMotorOutputs | kTerrain | kBattery |
                          sensor::kPrearmCheck | kPropulsion;
  std::uint32_t health = kImuBaroMag | control | kMotorOutputs | kGeofence | kTerrain | kLogging |
                         kBattery | kProximity | kPropulsion;
  if (aligned) {
    enabled |= sensor::kAhrs;
    health |= sensor::kAhrs | sensor::kPrearmCheck;
  }
  return {present, enabled, health};
}

// Estimator flags once aligned, as ArduCopter SITL reported them before its GPS fix:
// attitude, horizontal and vertical velocity, absolute altitude, constant-position mode
// (0x00a7). ArduPilot's bit 10 before: EKF_UNINITIALIZED.
constexpr std::uint16_t kAlignedFlags = flag::kAttitude | flag::kVelocityHoriz |
                                        flag::kVelocityVert | flag::kPosVertAbs |
                                        flag::kConstPosMode;
constexpr std::uint16_t kArduPilotUninitialised = 1024;

// HIGHRES_IMU.fields_updated: x/y/z acceleration and x/y/z gyro.
constexpr std::uint16_t kImuFieldsUpdated = 0x3F;
constexpr std::uint8_t kBatteryFunctionAll = 1;
constexpr std::uint8_t kBatteryTypeLipo = 1;
constexpr std::uint8_t kBatteryChargeStateOk = 1;
constexpr std::uint8_t kSeverityInfo = 6;
constexpr double kTimeTolerance_s = 1e-9;

// Messages without a struct in the codec (common.xml; CRC_EXTRA checked against PX4 SITL's
// frames): ATTITUDE, VFR_HUD, ALTITUDE.
constexpr std::uint8_t kAttitudeCrcExtra = 39;
constexpr std::size_t kAttitudeLength = 28;
constexpr std::uint8_t kVfrHudCrcExtra = 20;
constexpr std::size_t kVfrHudLength = 20;
constexpr std::uint8_t kAltitudeCrcExtra = 47;
constexpr std::size_t kAltitudeLength = 32;

// Little-endian packing of a payload, field after field.
class Packer {
 public:
  template <typename T>
  Packer& put(T value) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &value, sizeof(T));
    for (std::size_t i = 0; i < sizeof(T); ++i) {
      payload_[used_++] = static_cast<std::uint8_t>(bits >> (8 * i));
    }
    return *this;
  }
  Packer& put(double value) { return put(static_cast<float>(value)); }
  const std::uint8_t* data() const { return payload_.data(); }
  std::size_t size() const { return used_; }

 private:
  std::array<std::uint8_t, mavlink::kMaxPayloadLength> payload_{};
  std::size_t used_ = 0;
};

std::uint32_t boot_ms(double now_s) {
  return static_cast<std::uint32_t>(std::llround(std::max(0.0, now_s) * 1000.0));
}

std::uint64_t boot_us(double now_s) {
  return static_cast<std::uint64_t>(std::llround(std::max(0.0, now_s) * 1e6));
}

std::uint16_t millivolts(double volts) {
  return static_cast<std::uint16_t>(std::clamp(std::lround(volts * 1000.0), 0L, 65534L));
}

std::int16_t centiamps(double amps) {
  return static_cast<std::int16_t>(std::clamp(std::lround(amps * 100.0), 0L, 32767L));
}

std::int8_t percent(double fraction) {
  return static_cast<std::int8_t>(std::clamp(std::lround(fraction * 100.0), 0L, 100L));
}

// Roll, pitch, yaw (rad) of a NED/FRD attitude.
Eigen::Vector3d euler(const Eigen::Quaterniond& q) {
  const double roll = std::atan2(2.0 * (q.w() * q.x() + q.y() * q.z()),
                                 1.0 - 2.0 * (q.x() * q.x() + q.y() * q.y()));
  const double pitch = std::asin(std::clamp(2.0 * (q.w() * q.y() - q.z() * q.x()), -1.0, 1.0));
  const double yaw = std::atan2(2.0 * (q.w() * q.z() + q.x() * q.y()),
                                1.0 - 2.0 * (q.y() * q.y() + q.z() * q.z()));
  return {roll, pitch, yaw};
}

// LOCAL_POSITION_NED: the world's ENU position and velocity in NED, as an autopilot's
// estimator would give them (exact: the simulated autopilot's estimate is the truth).
mavlink::LocalPositionNed local_position(double now_s, const World& world) {
  const auto& uav = world.state().uav;
  mavlink::LocalPositionNed p;
  p.time_boot_ms = boot_ms(now_s);
  p.x = static_cast<float>(uav.position_m.y);
  p.y = static_cast<float>(uav.position_m.x);
  p.z = static_cast<float>(-uav.position_m.z);
  p.vx = static_cast<float>(uav.velocity_m_s.y);
  p.vy = static_cast<float>(uav.velocity_m_s.x);
  p.vz = static_cast<float>(-uav.velocity_m_s.z);
  return p;
}

}  // namespace

void SimulatedAutopilot::queue_streams(double now_s, const World& world,
                                       const QuadrotorCommand& command) {
  namespace mav = mavlink;
  if (streams_.due(mav::Heartbeat::kId, now_s) && !heartbeats_stopped_) queue(heartbeat());
  if (streams_.due(stream_id::kAttitude, now_s)) outbox_.push_back(euler_attitude(now_s, world));
  if (streams_.due(mav::AttitudeQuaternion::kId, now_s)) queue(attitude(now_s, world));
  if (streams_.due(mav::AttitudeTarget::kId, now_s)) {
    queue(attitude_target(now_s, world, command));
  }
  if (streams_.due(mav::ExtendedSysState::kId, now_s)) {
    mav::ExtendedSysState state;
    state.landed_state = landed_state(world);
    queue(state);
  }
  if (streams_.due(mav::SysStatus::kId, now_s)) queue(sys_status(now_s));
  if (streams_.due(mav::BatteryStatus::kId, now_s)) queue(battery_status());
  const std::uint32_t estimator =
      profile_ == Autopilot::Px4 ? mav::EstimatorStatus::kId : mav::EkfStatusReport::kId;
  if (streams_.due(estimator, now_s)) outbox_.push_back(estimator_report(now_s));
  queue_unknown_types(now_s, world);
  // In lockstep every step carries the position too, asked or not: a vertical velocity that
  // began when a request happened to arrive would feed the bridge's hover estimate from a
  // step that depends on the machine's load, and the run would not repeat bit for bit.
  const bool position_due = streams_.due(mav::LocalPositionNed::kId, now_s);
  if (position_due || closing_ == StepClosing::HighresImu) queue(local_position(now_s, world));
  // Last: the simulator's lockstep contract (StepClosing) closes every step's frames with
  // the IMU sample of the step, whatever its stream's rate; otherwise at that rate.
  const bool imu_due = streams_.due(mav::HighresImu::kId, now_s);
  if (imu_due || closing_ == StepClosing::HighresImu) queue(highres_imu(now_s, world));
}

// VFR_HUD and ALTITUDE: two of the message types PX4 streams that COVER's codec does not
// know (MessageStreams has them for PX4 only).
void SimulatedAutopilot::queue_unknown_types(double now_s, const World& world) {
  const auto& uav = world.state().uav;
  if (streams_.due(stream_id::kVfrHud, now_s)) {
    const Eigen::Quaterniond q = ned_frd_attitude(uav.attitude.eigen());
    const double heading_deg = std::fmod(euler(q).z() * 180.0 / M_PI + 360.0, 360.0);
    Packer p;
    p.put(std::hypot(uav.velocity_m_s.x, uav.velocity_m_s.y))  // airspeed (no wind)
        .put(std::hypot(uav.velocity_m_s.x, uav.velocity_m_s.y))
        .put(uav.position_m.z)
        .put(uav.velocity_m_s.z)
        .put(static_cast<std::int16_t>(std::lround(heading_deg)))
        .put(static_cast<std::uint16_t>(
            std::lround(100.0 * std::clamp(world.state().last_command.thrust_m_s2 /
                                               world.params().uav.max_thrust_m_s2,
                                           0.0, 1.0))));
    outbox_.push_back(encoder_.frame(stream_id::kVfrHud, kVfrHudCrcExtra, p.data(), kVfrHudLength));
  }
  if (streams_.due(stream_id::kAltitude, now_s)) {
    Packer p;
    p.put(boot_us(now_s));
    for (int i = 0; i < 4; ++i) p.put(uav.position_m.z);  // monotonic, amsl, local, relative
    p.put(std::numeric_limits<float>::quiet_NaN()).put(uav.position_m.z);  // terrain, clearance
    outbox_.push_back(
        encoder_.frame(stream_id::kAltitude, kAltitudeCrcExtra, p.data(), kAltitudeLength));
  }
}

bool SimulatedAutopilot::estimator_aligned(double now_s) const {
  const double align_s = profile_ == Autopilot::Px4 ? params_.px4.estimator_align_s
                                                    : params_.ardupilot.estimator_align_s;
  return now_s + kTimeTolerance_s >= align_s;
}

// ArduPilot announces its EKF's alignment (seen on ArduCopter SITL); PX4 sends no event.
void SimulatedAutopilot::report_alignment(double now_s) {
  if (alignment_reported_ || !estimator_aligned(now_s)) return;
  alignment_reported_ = true;
  say(kSeverityInfo, "EKF3 IMU0 tilt alignment complete");
}

mavlink::Heartbeat SimulatedAutopilot::heartbeat() const {
  mavlink::Heartbeat h;
  h.custom_mode = custom_mode(profile_, mode_);
  h.type = mavlink::mav_type::kQuadrotor;
  h.autopilot = profile_ == Autopilot::Px4 ? mavlink::mav_autopilot::kPx4
                                           : mavlink::mav_autopilot::kArdupilotMega;
  h.base_mode = mavlink::mav_mode_flag::kCustomModeEnabled |
                (armed_ ? mavlink::mav_mode_flag::kSafetyArmed : 0);
  h.system_status = system_status();
  return h;
}

std::uint8_t SimulatedAutopilot::system_status() const {
  if (in_failsafe_) return mavlink::mav_state::kCritical;
  return armed_ ? mavlink::mav_state::kActive : mavlink::mav_state::kStandby;
}

mavlink::HighresImu SimulatedAutopilot::highres_imu(double now_s, const World& world) const {
  const Eigen::Vector3d force = flu_to_frd(uav_specific_force_flu(world));
  const Eigen::Vector3d gyro = flu_to_frd(world.state().uav.body_rate_rad_s.eigen());
  mavlink::HighresImu imu;
  imu.time_usec = boot_us(now_s);
  imu.xacc = static_cast<float>(force.x());
  imu.yacc = static_cast<float>(force.y());
  imu.zacc = static_cast<float>(force.z());
  imu.xgyro = static_cast<float>(gyro.x());
  imu.ygyro = static_cast<float>(gyro.y());
  imu.zgyro = static_cast<float>(gyro.z());
  imu.fields_updated = kImuFieldsUpdated;
  return imu;
}

mavlink::AttitudeQuaternion SimulatedAutopilot::attitude(double now_s, const World& world) const {
  const Eigen::Quaterniond q = ned_frd_attitude(world.state().uav.attitude.eigen());
  const Eigen::Vector3d rates = flu_to_frd(world.state().uav.body_rate_rad_s.eigen());
  mavlink::AttitudeQuaternion a;
  a.time_boot_ms = boot_ms(now_s);
  a.q1 = static_cast<float>(q.w());
  a.q2 = static_cast<float>(q.x());
  a.q3 = static_cast<float>(q.y());
  a.q4 = static_cast<float>(q.z());
  a.rollspeed = static_cast<float>(rates.x());
  a.pitchspeed = static_cast<float>(rates.y());
  a.yawspeed = static_cast<float>(rates.z());
  return a;
}

// ATTITUDE (30): the same attitude as Euler angles, PX4's fastest stream (100 Hz).
mavlink::EncodedFrame SimulatedAutopilot::euler_attitude(double now_s, const World& world) {
  const Eigen::Quaterniond q = ned_frd_attitude(world.state().uav.attitude.eigen());
  const Eigen::Vector3d angles = euler(q);
  const Eigen::Vector3d rates = flu_to_frd(world.state().uav.body_rate_rad_s.eigen());
  Packer p;
  p.put(boot_ms(now_s)).put(angles.x()).put(angles.y()).put(angles.z());
  p.put(rates.x()).put(rates.y()).put(rates.z());
  return encoder_.frame(stream_id::kAttitude, kAttitudeCrcExtra, p.data(), kAttitudeLength);
}

// What the rate controller is flying: the plant command in the setpoint's terms.
mavlink::AttitudeTarget SimulatedAutopilot::attitude_target(double now_s, const World& world,
                                                            const QuadrotorCommand& command) const {
  const Eigen::Vector3d rates = flu_to_frd(command.body_rate_rad_s.eigen());
  const Eigen::Quaterniond q = ned_frd_attitude(world.state().uav.attitude.eigen());
  mavlink::AttitudeTarget t;
  t.time_boot_ms = boot_ms(now_s);
  t.q = {static_cast<float>(q.w()), static_cast<float>(q.x()), static_cast<float>(q.y()),
         static_cast<float>(q.z())};
  t.body_roll_rate = static_cast<float>(rates.x());
  t.body_pitch_rate = static_cast<float>(rates.y());
  t.body_yaw_rate = static_cast<float>(rates.z());
  t.thrust = static_cast<float>(
      std::clamp(command.thrust_m_s2 / world.params().uav.max_thrust_m_s2, 0.0, 1.0));
  t.type_mask = mavlink::attitude_target_typemask::kIgnoreAttitude;
  return t;
}

std::uint8_t SimulatedAutopilot::landed_state(const World& world) const {
  if (world.state().uav_contact.resting) return mavlink::mav_landed_state::kOnGround;
  if (armed_ && mode_ == FlightMode::Land) return mavlink::mav_landed_state::kLanding;
  return mavlink::mav_landed_state::kInAir;
}

mavlink::SysStatus SimulatedAutopilot::sys_status(double now_s) const {
  const bool aligned = estimator_aligned(now_s);
  const SensorBits bits =
      profile_ == Autopilot::Px4 ? px4_sensors(aligned) : ardupilot_sensors(aligned);
  mavlink::SysStatus s;
  s.onboard_control_sensors_present = bits.present;
  s.onboard_control_sensors_enabled = bits.enabled;
  s.onboard_control_sensors_health = bits.health;
  s.voltage_battery = millivolts(battery_.voltage_v());
  s.current_battery = centiamps(battery_.current_a());
  s.battery_remaining = percent(battery_.remaining());
  return s;
}

mavlink::BatteryStatus SimulatedAutopilot::battery_status() const {
  mavlink::BatteryStatus b;
  b.voltages.fill(std::numeric_limits<std::uint16_t>::max());
  for (int i = 0; i < battery_.cells() && i < static_cast<int>(b.voltages.size()); ++i) {
    b.voltages[static_cast<std::size_t>(i)] = millivolts(battery_.cell_voltage_v());
  }
  b.current_battery = centiamps(battery_.current_a());
  b.current_consumed = static_cast<std::int32_t>(std::lround(battery_.consumed_mah()));
  b.battery_function = kBatteryFunctionAll;
  b.type = kBatteryTypeLipo;
  b.battery_remaining = percent(battery_.remaining());
  b.charge_state = kBatteryChargeStateOk;
  return b;
}

// PX4's ESTIMATOR_STATUS / ArduPilot's EKF_STATUS_REPORT: its flags once aligned.
mavlink::EncodedFrame SimulatedAutopilot::estimator_report(double now_s) {
  const bool aligned = estimator_aligned(now_s);
  if (profile_ == Autopilot::Px4) {
    mavlink::EstimatorStatus s;
    s.time_usec = boot_us(now_s);
    s.flags = aligned ? kAlignedFlags : 0;
    return encoder_.encode(s);
  }
  mavlink::EkfStatusReport r;
  r.flags = aligned ? kAlignedFlags : kArduPilotUninitialised;
  return encoder_.encode(r);
}

}  // namespace cover::sim::fc
