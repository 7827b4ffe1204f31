#include "sample_messages.hpp"

#include <limits>

namespace cover::mavlink::test {

namespace {

Heartbeat heartbeat() {
  Heartbeat m;
  m.custom_mode = 0x00060000;
  m.type = 2;
  m.autopilot = 12;
  m.base_mode = 129;
  m.system_status = 4;
  m.mavlink_version = 3;
  return m;
}

SysStatus sys_status() {
  SysStatus m;
  m.onboard_control_sensors_present = 0xDEADBEEF;
  m.onboard_control_sensors_enabled = 0x12345678;
  m.onboard_control_sensors_health = 0x80000001;
  m.load = 999;
  m.voltage_battery = 16123;
  m.current_battery = -1234;
  m.drop_rate_comm = 3;
  m.errors_comm = 65535;
  m.errors_count1 = 1;
  m.errors_count2 = 2;
  m.errors_count3 = 3;
  m.errors_count4 = 4;
  m.battery_remaining = -1;
  m.onboard_control_sensors_present_extended = 11;
  m.onboard_control_sensors_enabled_extended = 22;
  m.onboard_control_sensors_health_extended = 33;
  return m;
}

ScaledImu scaled_imu() {
  ScaledImu m;
  m.time_boot_ms = 4000000000U;
  m.xacc = -981;
  m.yacc = 12;
  m.zacc = std::numeric_limits<std::int16_t>::max();
  m.xgyro = std::numeric_limits<std::int16_t>::min();
  m.ygyro = 5;
  m.zgyro = -6;
  m.xmag = 100;
  m.ymag = -200;
  m.zmag = 300;
  m.temperature = -2150;
  return m;
}

AttitudeQuaternion attitude_quaternion() {
  AttitudeQuaternion m;
  m.time_boot_ms = 123456;
  m.q1 = 0.7071068F;
  m.q2 = -0.7071068F;
  m.q3 = 0.001F;
  m.q4 = -1e-7F;
  m.rollspeed = 1.5F;
  m.pitchspeed = -2.25F;
  m.yawspeed = 3.125F;
  m.repr_offset_q = {0.5F, -0.5F, 0.25F, 1e-20F};
  return m;
}

CommandLong command_long() {
  CommandLong m;
  m.param = {1.0F, 6.0F, -1.5F, 3.4e38F, 0.0F, 1e-3F, -7.0F};
  m.command = 176;
  m.target_system = 42;
  m.target_component = 1;
  m.confirmation = 2;
  return m;
}

CommandAck command_ack() {
  CommandAck m;
  m.command = 400;
  m.result = 2;
  m.progress = 100;
  m.result_param2 = -123456789;
  m.target_system = 245;
  m.target_component = 190;
  return m;
}

SetAttitudeTarget set_attitude_target() {
  SetAttitudeTarget m;
  m.time_boot_ms = 1000;
  m.q = {0.9F, 0.1F, -0.2F, 0.3F};
  m.body_roll_rate = 0.1F;
  m.body_pitch_rate = -0.2F;
  m.body_yaw_rate = 0.3F;
  m.thrust = 0.5F;
  m.target_system = 1;
  m.target_component = 1;
  m.type_mask = 128;
  m.thrust_body = {0.25F, -0.125F, 1.0F};
  return m;
}

AttitudeTarget attitude_target() {
  AttitudeTarget m;
  m.time_boot_ms = 99;
  m.q = {0.5F, 0.5F, -0.5F, 0.5F};
  m.body_roll_rate = -0.01F;
  m.body_pitch_rate = 0.02F;
  m.body_yaw_rate = -3.14159F;
  m.thrust = 0.73F;
  m.type_mask = 7;
  return m;
}

HighresImu highres_imu() {
  HighresImu m;
  m.time_usec = 18446744073709551000ULL;
  m.xacc = 0.1F;
  m.yacc = -0.2F;
  m.zacc = -9.81F;
  m.xgyro = 0.01F;
  m.ygyro = -0.02F;
  m.zgyro = 0.03F;
  m.xmag = 0.2F;
  m.ymag = -0.1F;
  m.zmag = 0.45F;
  m.abs_pressure = 1013.25F;
  m.diff_pressure = -0.5F;
  m.pressure_alt = 488.5F;
  m.temperature = 36.6F;
  m.fields_updated = 0x1FFF;
  m.id = 2;
  return m;
}

Timesync timesync() {
  Timesync m;
  m.tc1 = -9223372036854775000LL;
  m.ts1 = 1700000000123456789LL;
  m.target_system = 42;
  m.target_component = 1;
  return m;
}

BatteryStatus battery_status() {
  BatteryStatus m;
  m.current_consumed = -1;
  m.energy_consumed = 123456;
  m.temperature = 2512;
  m.voltages = {4100, 4110, 4120, 4130, 65535, 65535, 65535, 65535, 65535, 65535};
  m.current_battery = 2500;
  m.id = 1;
  m.battery_function = 1;
  m.type = 1;
  m.battery_remaining = 87;
  m.time_remaining = 600;
  m.charge_state = 1;
  m.voltages_ext = {7, 1, 2, 3};
  m.mode = 2;
  m.fault_bitmask = 0x80000000U;
  return m;
}

ExtendedSysState extended_sys_state() {
  ExtendedSysState m;
  m.vtol_state = 1;
  m.landed_state = 2;
  return m;
}

StatusText status_text() {
  StatusText m;
  m.severity = 4;
  m.set_text("Offboard: no setpoints for 0.5 s, holding attitude");  // all 50 bytes
  m.id = 513;
  m.chunk_seq = 7;
  return m;
}

HilSensor hil_sensor() {
  HilSensor m;
  m.time_usec = 18446744073709551000ULL;
  m.xacc = 0.25F;
  m.yacc = -0.5F;
  m.zacc = -9.80665F;
  m.xgyro = 1e-3F;
  m.ygyro = -2e-3F;
  m.zgyro = 3.5F;
  m.xmag = 0.216F;
  m.ymag = 0.009F;
  m.zmag = 0.426F;
  m.abs_pressure = 955.5F;
  m.diff_pressure = -0.125F;
  m.pressure_alt = 488.25F;
  m.temperature = 11.8F;
  m.fields_updated = 7167;
  m.id = 2;  // an extension, set: not trimmed
  return m;
}

HilActuatorControls hil_actuator_controls() {
  HilActuatorControls m;
  m.time_usec = 1234567890123ULL;
  m.flags = 0x8000000000000001ULL;
  for (std::size_t i = 0; i < m.controls.size(); ++i) {
    m.controls[i] = static_cast<float>(i) * 0.0625F - 0.5F;
  }
  m.controls[15] = 1.0F;
  m.mode = 129;
  return m;
}

HilStateQuaternion hil_state_quaternion() {
  HilStateQuaternion m;
  m.time_usec = 4000000123ULL;
  m.attitude_quaternion = {0.5F, -0.5F, 0.5F, -0.5F};
  m.rollspeed = 0.1F;
  m.pitchspeed = -0.2F;
  m.yawspeed = 0.3F;
  m.lat = 473977418;
  m.lon = -85455939;
  m.alt = std::numeric_limits<std::int32_t>::min();
  m.vx = -32768;
  m.vy = 32767;
  m.vz = -5;
  m.ind_airspeed = 65535;
  m.true_airspeed = 1200;
  m.xacc = -1000;
  m.yacc = 12;
  m.zacc = 999;
  return m;
}

HilGps hil_gps() {
  HilGps m;
  m.time_usec = 77ULL;
  m.lat = -473977418;
  m.lon = 1799999999;
  m.alt = 488000;
  m.eph = 80;
  m.epv = 120;
  m.vel = 150;
  m.vn = -100;
  m.ve = 110;
  m.vd = -7;
  m.cog = 35999;
  m.fix_type = 3;
  m.satellites_visible = 12;
  m.id = 1;
  m.yaw = 9000;
  return m;
}

}  // namespace

AllMessages sample_messages() {
  return {heartbeat(),
          sys_status(),
          scaled_imu(),
          attitude_quaternion(),
          command_long(),
          command_ack(),
          set_attitude_target(),
          attitude_target(),
          highres_imu(),
          timesync(),
          battery_status(),
          extended_sys_state(),
          status_text(),
          hil_sensor(),
          hil_actuator_controls(),
          hil_state_quaternion(),
          hil_gps()};
}

}  // namespace cover::mavlink::test
