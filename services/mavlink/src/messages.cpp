#include "cover/mavlink/messages.hpp"

#include <algorithm>
#include <cstring>

#include "byte_cursor.hpp"

// Each pack/unpack lists the fields in wire order: sorted by type size, largest first
// (stable), then the extensions in declaration order (common.xml; node-mavlink 2.3.0's
// FIELDS offsets agree). The reader works on a frame's zero-filled payload, so absent
// (trimmed or v1) trailing fields read as zero.

namespace cover::mavlink {

using detail::PayloadReader;
using detail::PayloadWriter;

void Heartbeat::pack(std::uint8_t* payload) const {
  PayloadWriter w(payload);
  w.put(custom_mode);
  w.put(type);
  w.put(autopilot);
  w.put(base_mode);
  w.put(system_status);
  w.put(mavlink_version);
}

Heartbeat Heartbeat::unpack(const std::uint8_t* payload) {
  Heartbeat m;
  PayloadReader r(payload);
  r.get(m.custom_mode);
  r.get(m.type);
  r.get(m.autopilot);
  r.get(m.base_mode);
  r.get(m.system_status);
  r.get(m.mavlink_version);
  return m;
}

void SysStatus::pack(std::uint8_t* payload) const {
  PayloadWriter w(payload);
  w.put(onboard_control_sensors_present);
  w.put(onboard_control_sensors_enabled);
  w.put(onboard_control_sensors_health);
  w.put(load);
  w.put(voltage_battery);
  w.put(current_battery);
  w.put(drop_rate_comm);
  w.put(errors_comm);
  w.put(errors_count1);
  w.put(errors_count2);
  w.put(errors_count3);
  w.put(errors_count4);
  w.put(battery_remaining);
  w.put(onboard_control_sensors_present_extended);
  w.put(onboard_control_sensors_enabled_extended);
  w.put(onboard_control_sensors_health_extended);
}

SysStatus SysStatus::unpack(const std::uint8_t* payload) {
  SysStatus m;
  PayloadReader r(payload);
  r.get(m.onboard_control_sensors_present);
  r.get(m.onboard_control_sensors_enabled);
  r.get(m.onboard_control_sensors_health);
  r.get(m.load);
  r.get(m.voltage_battery);
  r.get(m.current_battery);
  r.get(m.drop_rate_comm);
  r.get(m.errors_comm);
  r.get(m.errors_count1);
  r.get(m.errors_count2);
  r.get(m.errors_count3);
  r.get(m.errors_count4);
  r.get(m.battery_remaining);
  r.get(m.onboard_control_sensors_present_extended);
  r.get(m.onboard_control_sensors_enabled_extended);
  r.get(m.onboard_control_sensors_health_extended);
  return m;
}

void ScaledImu::pack(std::uint8_t* payload) const {
  PayloadWriter w(payload);
  w.put(time_boot_ms);
  w.put(xacc);
  w.put(yacc);
  w.put(zacc);
  w.put(xgyro);
  w.put(ygyro);
  w.put(zgyro);
  w.put(xmag);
  w.put(ymag);
  w.put(zmag);
  w.put(temperature);
}

ScaledImu ScaledImu::unpack(const std::uint8_t* payload) {
  ScaledImu m;
  PayloadReader r(payload);
  r.get(m.time_boot_ms);
  r.get(m.xacc);
  r.get(m.yacc);
  r.get(m.zacc);
  r.get(m.xgyro);
  r.get(m.ygyro);
  r.get(m.zgyro);
  r.get(m.xmag);
  r.get(m.ymag);
  r.get(m.zmag);
  r.get(m.temperature);
  return m;
}

void AttitudeQuaternion::pack(std::uint8_t* payload) const {
  PayloadWriter w(payload);
  w.put(time_boot_ms);
  w.put(q1);
  w.put(q2);
  w.put(q3);
  w.put(q4);
  w.put(rollspeed);
  w.put(pitchspeed);
  w.put(yawspeed);
  w.put(repr_offset_q);
}

AttitudeQuaternion AttitudeQuaternion::unpack(const std::uint8_t* payload) {
  AttitudeQuaternion m;
  PayloadReader r(payload);
  r.get(m.time_boot_ms);
  r.get(m.q1);
  r.get(m.q2);
  r.get(m.q3);
  r.get(m.q4);
  r.get(m.rollspeed);
  r.get(m.pitchspeed);
  r.get(m.yawspeed);
  r.get(m.repr_offset_q);
  return m;
}

void CommandLong::pack(std::uint8_t* payload) const {
  PayloadWriter w(payload);
  w.put(param);
  w.put(command);
  w.put(target_system);
  w.put(target_component);
  w.put(confirmation);
}

CommandLong CommandLong::unpack(const std::uint8_t* payload) {
  CommandLong m;
  PayloadReader r(payload);
  r.get(m.param);
  r.get(m.command);
  r.get(m.target_system);
  r.get(m.target_component);
  r.get(m.confirmation);
  return m;
}

void CommandAck::pack(std::uint8_t* payload) const {
  PayloadWriter w(payload);
  w.put(command);
  w.put(result);
  w.put(progress);
  w.put(result_param2);
  w.put(target_system);
  w.put(target_component);
}

CommandAck CommandAck::unpack(const std::uint8_t* payload) {
  CommandAck m;
  PayloadReader r(payload);
  r.get(m.command);
  r.get(m.result);
  r.get(m.progress);
  r.get(m.result_param2);
  r.get(m.target_system);
  r.get(m.target_component);
  return m;
}

void SetAttitudeTarget::pack(std::uint8_t* payload) const {
  PayloadWriter w(payload);
  w.put(time_boot_ms);
  w.put(q);
  w.put(body_roll_rate);
  w.put(body_pitch_rate);
  w.put(body_yaw_rate);
  w.put(thrust);
  w.put(target_system);
  w.put(target_component);
  w.put(type_mask);
  w.put(thrust_body);
}

SetAttitudeTarget SetAttitudeTarget::unpack(const std::uint8_t* payload) {
  SetAttitudeTarget m;
  PayloadReader r(payload);
  r.get(m.time_boot_ms);
  r.get(m.q);
  r.get(m.body_roll_rate);
  r.get(m.body_pitch_rate);
  r.get(m.body_yaw_rate);
  r.get(m.thrust);
  r.get(m.target_system);
  r.get(m.target_component);
  r.get(m.type_mask);
  r.get(m.thrust_body);
  return m;
}

void AttitudeTarget::pack(std::uint8_t* payload) const {
  PayloadWriter w(payload);
  w.put(time_boot_ms);
  w.put(q);
  w.put(body_roll_rate);
  w.put(body_pitch_rate);
  w.put(body_yaw_rate);
  w.put(thrust);
  w.put(type_mask);
}

AttitudeTarget AttitudeTarget::unpack(const std::uint8_t* payload) {
  AttitudeTarget m;
  PayloadReader r(payload);
  r.get(m.time_boot_ms);
  r.get(m.q);
  r.get(m.body_roll_rate);
  r.get(m.body_pitch_rate);
  r.get(m.body_yaw_rate);
  r.get(m.thrust);
  r.get(m.type_mask);
  return m;
}

void HighresImu::pack(std::uint8_t* payload) const {
  PayloadWriter w(payload);
  w.put(time_usec);
  w.put(xacc);
  w.put(yacc);
  w.put(zacc);
  w.put(xgyro);
  w.put(ygyro);
  w.put(zgyro);
  w.put(xmag);
  w.put(ymag);
  w.put(zmag);
  w.put(abs_pressure);
  w.put(diff_pressure);
  w.put(pressure_alt);
  w.put(temperature);
  w.put(fields_updated);
  w.put(id);
}

HighresImu HighresImu::unpack(const std::uint8_t* payload) {
  HighresImu m;
  PayloadReader r(payload);
  r.get(m.time_usec);
  r.get(m.xacc);
  r.get(m.yacc);
  r.get(m.zacc);
  r.get(m.xgyro);
  r.get(m.ygyro);
  r.get(m.zgyro);
  r.get(m.xmag);
  r.get(m.ymag);
  r.get(m.zmag);
  r.get(m.abs_pressure);
  r.get(m.diff_pressure);
  r.get(m.pressure_alt);
  r.get(m.temperature);
  r.get(m.fields_updated);
  r.get(m.id);
  return m;
}

void Timesync::pack(std::uint8_t* payload) const {
  PayloadWriter w(payload);
  w.put(tc1);
  w.put(ts1);
  w.put(target_system);
  w.put(target_component);
}

Timesync Timesync::unpack(const std::uint8_t* payload) {
  Timesync m;
  PayloadReader r(payload);
  r.get(m.tc1);
  r.get(m.ts1);
  r.get(m.target_system);
  r.get(m.target_component);
  return m;
}

void BatteryStatus::pack(std::uint8_t* payload) const {
  PayloadWriter w(payload);
  w.put(current_consumed);
  w.put(energy_consumed);
  w.put(temperature);
  w.put(voltages);
  w.put(current_battery);
  w.put(id);
  w.put(battery_function);
  w.put(type);
  w.put(battery_remaining);
  w.put(time_remaining);
  w.put(charge_state);
  w.put(voltages_ext);
  w.put(mode);
  w.put(fault_bitmask);
}

BatteryStatus BatteryStatus::unpack(const std::uint8_t* payload) {
  BatteryStatus m;
  PayloadReader r(payload);
  r.get(m.current_consumed);
  r.get(m.energy_consumed);
  r.get(m.temperature);
  r.get(m.voltages);
  r.get(m.current_battery);
  r.get(m.id);
  r.get(m.battery_function);
  r.get(m.type);
  r.get(m.battery_remaining);
  r.get(m.time_remaining);
  r.get(m.charge_state);
  r.get(m.voltages_ext);
  r.get(m.mode);
  r.get(m.fault_bitmask);
  return m;
}

void ExtendedSysState::pack(std::uint8_t* payload) const {
  PayloadWriter w(payload);
  w.put(vtol_state);
  w.put(landed_state);
}

ExtendedSysState ExtendedSysState::unpack(const std::uint8_t* payload) {
  ExtendedSysState m;
  PayloadReader r(payload);
  r.get(m.vtol_state);
  r.get(m.landed_state);
  return m;
}

void StatusText::pack(std::uint8_t* payload) const {
  PayloadWriter w(payload);
  w.put(severity);
  w.put(text);
  w.put(id);
  w.put(chunk_seq);
}

StatusText StatusText::unpack(const std::uint8_t* payload) {
  StatusText m;
  PayloadReader r(payload);
  r.get(m.severity);
  r.get(m.text);
  r.get(m.id);
  r.get(m.chunk_seq);
  return m;
}

std::string StatusText::text_string() const {
  const auto end = std::find(text.begin(), text.end(), '\0');
  return std::string(text.begin(), end);
}

void StatusText::set_text(const std::string& value) {
  text.fill('\0');
  std::copy_n(value.begin(), std::min(value.size(), text.size()), text.begin());
}

}  // namespace cover::mavlink
