// The telemetry streams of the simulated autopilot, in MAVLink's frames (NED / FRD).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "cover/mavlink/protocol.hpp"
#include "cover/sim/fc/frame_conventions.hpp"
#include "cover/sim/fc/simulated_autopilot.hpp"

namespace cover::sim::fc {

namespace {

// MAV_SYS_STATUS_SENSOR bits of what the simulated vehicle has and uses: 3D gyro,
// 3D accelerometer, angular rate control, attitude stabilisation, motor outputs, battery.
constexpr std::uint32_t kSensors = 0x1u | 0x2u | 0x400u | 0x800u | 0x8000u | 0x2000000u;
// HIGHRES_IMU.fields_updated: x/y/z acceleration and x/y/z gyro.
constexpr std::uint16_t kImuFieldsUpdated = 0x3F;
constexpr std::uint8_t kBatteryFunctionAll = 1;
constexpr std::uint8_t kBatteryTypeLipo = 1;
constexpr std::uint8_t kBatteryChargeStateOk = 1;

std::uint32_t boot_ms(double now_s) {
  return static_cast<std::uint32_t>(std::llround(std::max(0.0, now_s) * 1000.0));
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

}  // namespace

void SimulatedAutopilot::queue_streams(double now_s, const World& world,
                                       const QuadrotorCommand& command) {
  if (heartbeat_stream_.due(now_s) && !heartbeats_stopped_) queue(heartbeat());
  if (attitude_stream_.due(now_s)) queue(attitude(now_s, world));
  if (target_stream_.due(now_s)) queue(attitude_target(now_s, world, command));
  if (ext_state_stream_.due(now_s)) {
    mavlink::ExtendedSysState state;
    state.landed_state = landed_state(world);
    queue(state);
  }
  if (status_stream_.due(now_s)) {
    queue(sys_status());
    queue(battery_status());
  }
  // Last: in lockstep the IMU sample closes the step's frames, and a bridge waits for it
  // before the next tick's command (docs/flight-controller.md, "Lockstep").
  if (imu_stream_.due(now_s)) queue(highres_imu(now_s, world));
}

mavlink::Heartbeat SimulatedAutopilot::heartbeat() const {
  mavlink::Heartbeat h;
  h.custom_mode = custom_mode(profile_, mode_);
  h.type = mavlink::mav_type::kQuadrotor;
  h.autopilot = profile_ == AutopilotProfile::Px4 ? mavlink::mav_autopilot::kPx4
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
  imu.time_usec = static_cast<std::uint64_t>(std::llround(std::max(0.0, now_s) * 1e6));
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

mavlink::SysStatus SimulatedAutopilot::sys_status() const {
  mavlink::SysStatus s;
  s.onboard_control_sensors_present = kSensors;
  s.onboard_control_sensors_enabled = kSensors;
  s.onboard_control_sensors_health = kSensors;
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

}  // namespace cover::sim::fc
