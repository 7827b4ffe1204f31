#include "message_json.hpp"

#include <string>

namespace cover::mavlink::test {

namespace {

template <typename T, std::size_t N>
nlohmann::json array(const std::array<T, N>& values) {
  nlohmann::json out = nlohmann::json::array();
  for (const T& v : values) out.push_back(v);
  return out;
}

template <typename M>
nlohmann::json named(const char* name, const Frame& frame) {
  return {{"message", name}, {"fields", to_json(*decode<M>(frame))}};
}

}  // namespace

nlohmann::json to_json(const Heartbeat& m) {
  return {{"custom_mode", m.custom_mode},     {"type", m.type},
          {"autopilot", m.autopilot},         {"base_mode", m.base_mode},
          {"system_status", m.system_status}, {"mavlink_version", m.mavlink_version}};
}

nlohmann::json to_json(const SysStatus& m) {
  return {{"onboard_control_sensors_present", m.onboard_control_sensors_present},
          {"onboard_control_sensors_enabled", m.onboard_control_sensors_enabled},
          {"onboard_control_sensors_health", m.onboard_control_sensors_health},
          {"load", m.load},
          {"voltage_battery", m.voltage_battery},
          {"current_battery", m.current_battery},
          {"drop_rate_comm", m.drop_rate_comm},
          {"errors_comm", m.errors_comm},
          {"errors_count1", m.errors_count1},
          {"errors_count2", m.errors_count2},
          {"errors_count3", m.errors_count3},
          {"errors_count4", m.errors_count4},
          {"battery_remaining", m.battery_remaining},
          {"onboard_control_sensors_present_extended", m.onboard_control_sensors_present_extended},
          {"onboard_control_sensors_enabled_extended", m.onboard_control_sensors_enabled_extended},
          {"onboard_control_sensors_health_extended", m.onboard_control_sensors_health_extended}};
}

nlohmann::json to_json(const ScaledImu& m) {
  return {{"time_boot_ms", m.time_boot_ms},
          {"xacc", m.xacc},
          {"yacc", m.yacc},
          {"zacc", m.zacc},
          {"xgyro", m.xgyro},
          {"ygyro", m.ygyro},
          {"zgyro", m.zgyro},
          {"xmag", m.xmag},
          {"ymag", m.ymag},
          {"zmag", m.zmag},
          {"temperature", m.temperature}};
}

nlohmann::json to_json(const AttitudeQuaternion& m) {
  return {{"time_boot_ms", m.time_boot_ms},
          {"q1", m.q1},
          {"q2", m.q2},
          {"q3", m.q3},
          {"q4", m.q4},
          {"rollspeed", m.rollspeed},
          {"pitchspeed", m.pitchspeed},
          {"yawspeed", m.yawspeed},
          {"repr_offset_q", array(m.repr_offset_q)}};
}

nlohmann::json to_json(const CommandLong& m) {
  return {{"param", array(m.param)},
          {"command", m.command},
          {"target_system", m.target_system},
          {"target_component", m.target_component},
          {"confirmation", m.confirmation}};
}

nlohmann::json to_json(const CommandAck& m) {
  return {{"command", m.command},
          {"result", m.result},
          {"progress", m.progress},
          {"result_param2", m.result_param2},
          {"target_system", m.target_system},
          {"target_component", m.target_component}};
}

nlohmann::json to_json(const SetAttitudeTarget& m) {
  return {{"time_boot_ms", m.time_boot_ms},     {"q", array(m.q)},
          {"body_roll_rate", m.body_roll_rate}, {"body_pitch_rate", m.body_pitch_rate},
          {"body_yaw_rate", m.body_yaw_rate},   {"thrust", m.thrust},
          {"target_system", m.target_system},   {"target_component", m.target_component},
          {"type_mask", m.type_mask},           {"thrust_body", array(m.thrust_body)}};
}

nlohmann::json to_json(const AttitudeTarget& m) {
  return {{"time_boot_ms", m.time_boot_ms},
          {"q", array(m.q)},
          {"body_roll_rate", m.body_roll_rate},
          {"body_pitch_rate", m.body_pitch_rate},
          {"body_yaw_rate", m.body_yaw_rate},
          {"thrust", m.thrust},
          {"type_mask", m.type_mask}};
}

nlohmann::json to_json(const HighresImu& m) {
  return {{"time_usec", std::to_string(m.time_usec)},
          {"xacc", m.xacc},
          {"yacc", m.yacc},
          {"zacc", m.zacc},
          {"xgyro", m.xgyro},
          {"ygyro", m.ygyro},
          {"zgyro", m.zgyro},
          {"xmag", m.xmag},
          {"ymag", m.ymag},
          {"zmag", m.zmag},
          {"abs_pressure", m.abs_pressure},
          {"diff_pressure", m.diff_pressure},
          {"pressure_alt", m.pressure_alt},
          {"temperature", m.temperature},
          {"fields_updated", m.fields_updated},
          {"id", m.id}};
}

nlohmann::json to_json(const Timesync& m) {
  return {{"tc1", std::to_string(m.tc1)},
          {"ts1", std::to_string(m.ts1)},
          {"target_system", m.target_system},
          {"target_component", m.target_component}};
}

nlohmann::json to_json(const BatteryStatus& m) {
  return {{"current_consumed", m.current_consumed},
          {"energy_consumed", m.energy_consumed},
          {"temperature", m.temperature},
          {"voltages", array(m.voltages)},
          {"current_battery", m.current_battery},
          {"id", m.id},
          {"battery_function", m.battery_function},
          {"type", m.type},
          {"battery_remaining", m.battery_remaining},
          {"time_remaining", m.time_remaining},
          {"charge_state", m.charge_state},
          {"voltages_ext", array(m.voltages_ext)},
          {"mode", m.mode},
          {"fault_bitmask", m.fault_bitmask}};
}

nlohmann::json to_json(const ExtendedSysState& m) {
  return {{"vtol_state", m.vtol_state}, {"landed_state", m.landed_state}};
}

nlohmann::json to_json(const StatusText& m) {
  return {{"severity", m.severity},
          {"text", m.text_string()},
          {"id", m.id},
          {"chunk_seq", m.chunk_seq}};
}

nlohmann::json to_json(const HilSensor& m) {
  return {{"time_usec", std::to_string(m.time_usec)},
          {"xacc", m.xacc},
          {"yacc", m.yacc},
          {"zacc", m.zacc},
          {"xgyro", m.xgyro},
          {"ygyro", m.ygyro},
          {"zgyro", m.zgyro},
          {"xmag", m.xmag},
          {"ymag", m.ymag},
          {"zmag", m.zmag},
          {"abs_pressure", m.abs_pressure},
          {"diff_pressure", m.diff_pressure},
          {"pressure_alt", m.pressure_alt},
          {"temperature", m.temperature},
          {"fields_updated", m.fields_updated},
          {"id", m.id}};
}

nlohmann::json to_json(const HilActuatorControls& m) {
  return {{"time_usec", std::to_string(m.time_usec)},
          {"flags", std::to_string(m.flags)},
          {"controls", array(m.controls)},
          {"mode", m.mode}};
}

nlohmann::json to_json(const HilStateQuaternion& m) {
  return {{"time_usec", std::to_string(m.time_usec)},
          {"attitude_quaternion", array(m.attitude_quaternion)},
          {"rollspeed", m.rollspeed},
          {"pitchspeed", m.pitchspeed},
          {"yawspeed", m.yawspeed},
          {"lat", m.lat},
          {"lon", m.lon},
          {"alt", m.alt},
          {"vx", m.vx},
          {"vy", m.vy},
          {"vz", m.vz},
          {"ind_airspeed", m.ind_airspeed},
          {"true_airspeed", m.true_airspeed},
          {"xacc", m.xacc},
          {"yacc", m.yacc},
          {"zacc", m.zacc}};
}

nlohmann::json to_json(const HilGps& m) {
  return {{"time_usec", std::to_string(m.time_usec)},
          {"lat", m.lat},
          {"lon", m.lon},
          {"alt", m.alt},
          {"eph", m.eph},
          {"epv", m.epv},
          {"vel", m.vel},
          {"vn", m.vn},
          {"ve", m.ve},
          {"vd", m.vd},
          {"cog", m.cog},
          {"fix_type", m.fix_type},
          {"satellites_visible", m.satellites_visible},
          {"id", m.id},
          {"yaw", m.yaw}};
}

nlohmann::json frame_to_json(const Frame& frame) {
  switch (frame.message_id) {
    case Heartbeat::kId:
      return named<Heartbeat>("HEARTBEAT", frame);
    case SysStatus::kId:
      return named<SysStatus>("SYS_STATUS", frame);
    case ScaledImu::kId:
      return named<ScaledImu>("SCALED_IMU", frame);
    case AttitudeQuaternion::kId:
      return named<AttitudeQuaternion>("ATTITUDE_QUATERNION", frame);
    case CommandLong::kId:
      return named<CommandLong>("COMMAND_LONG", frame);
    case CommandAck::kId:
      return named<CommandAck>("COMMAND_ACK", frame);
    case SetAttitudeTarget::kId:
      return named<SetAttitudeTarget>("SET_ATTITUDE_TARGET", frame);
    case AttitudeTarget::kId:
      return named<AttitudeTarget>("ATTITUDE_TARGET", frame);
    case HighresImu::kId:
      return named<HighresImu>("HIGHRES_IMU", frame);
    case Timesync::kId:
      return named<Timesync>("TIMESYNC", frame);
    case BatteryStatus::kId:
      return named<BatteryStatus>("BATTERY_STATUS", frame);
    case ExtendedSysState::kId:
      return named<ExtendedSysState>("EXTENDED_SYS_STATE", frame);
    case StatusText::kId:
      return named<StatusText>("STATUSTEXT", frame);
    case HilSensor::kId:
      return named<HilSensor>("HIL_SENSOR", frame);
    case HilActuatorControls::kId:
      return named<HilActuatorControls>("HIL_ACTUATOR_CONTROLS", frame);
    case HilStateQuaternion::kId:
      return named<HilStateQuaternion>("HIL_STATE_QUATERNION", frame);
    case HilGps::kId:
      return named<HilGps>("HIL_GPS", frame);
    default:
      return nullptr;
  }
}

}  // namespace cover::mavlink::test
