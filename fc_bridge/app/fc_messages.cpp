#include "fc_messages.hpp"

#include <algorithm>
#include <limits>

#include "cover/mavlink/protocol.hpp"

namespace cover::fc_bridge {
namespace {

msg::FcAutopilot autopilot_of(std::uint8_t mav_autopilot) {
  switch (mav_autopilot) {
    case mavlink::mav_autopilot::kPx4:
      return msg::FcAutopilot::FC_AUTOPILOT_PX4;
    case mavlink::mav_autopilot::kArdupilotMega:
      return msg::FcAutopilot::FC_AUTOPILOT_ARDUPILOT;
    default:
      return msg::FcAutopilot::FC_AUTOPILOT_UNKNOWN;
  }
}

msg::FcMode mode_of(FcMode mode) {
  switch (mode) {
    case FcMode::Offboard:
      return msg::FcMode::FC_MODE_OFFBOARD;
    case FcMode::Land:
      return msg::FcMode::FC_MODE_LAND;
    case FcMode::Manual:
      return msg::FcMode::FC_MODE_MANUAL;
    case FcMode::Other:
      return msg::FcMode::FC_MODE_OTHER;
    case FcMode::Unknown:
      break;
  }
  return msg::FcMode::FC_MODE_UNKNOWN;
}

msg::FcLandedState landed_of(LandedState state) {
  switch (state) {
    case LandedState::OnGround:
      return msg::FcLandedState::FC_LANDED_ON_GROUND;
    case LandedState::InAir:
      return msg::FcLandedState::FC_LANDED_IN_AIR;
    case LandedState::Takeoff:
      return msg::FcLandedState::FC_LANDED_TAKEOFF;
    case LandedState::Landing:
      return msg::FcLandedState::FC_LANDED_LANDING;
    case LandedState::Undefined:
      break;
  }
  return msg::FcLandedState::FC_LANDED_UNDEFINED;
}

msg::FcParameterWeight weight_of(ParameterWeight weight) {
  switch (weight) {
    case ParameterWeight::Blocking:
      return msg::FcParameterWeight::FC_PARAMETER_BLOCKING;
    case ParameterWeight::Advisory:
      return msg::FcParameterWeight::FC_PARAMETER_ADVISORY;
    case ParameterWeight::Info:
      break;
  }
  return msg::FcParameterWeight::FC_PARAMETER_INFO;
}

msg::FcParameter parameter_of(const ParameterFinding& f) {
  msg::FcParameter p;
  p.name = f.name;
  p.known = f.known;
  p.absent = f.absent;
  p.value = f.value;
  p.weight = weight_of(f.weight);
  p.needed = f.needed;
  p.why = f.why;
  p.ok = f.ok;
  return p;
}

msg::FcStream stream_of(const StreamState& s) {
  msg::FcStream m;
  m.name = s.request.name;
  m.asked_hz = s.request.rate_hz;
  m.measured_hz = s.measured_hz;
  m.arriving = s.arriving;
  m.refusal = s.refusal;
  return m;
}

std::uint32_t saturate(std::uint64_t count) {
  return static_cast<std::uint32_t>(
      std::min<std::uint64_t>(count, std::numeric_limits<std::uint32_t>::max()));
}

}  // namespace

AgentCommand from_msg(const msg::UavCommand& command) {
  AgentCommand c;
  c.stamp_ns = command.stamp_ns;
  c.seq = command.seq;
  c.thrust_m_s2 = command.thrust_m_s2;
  c.roll_rate_rad_s = command.body_rates_rad_s.x;
  c.pitch_rate_rad_s = command.body_rates_rad_s.y;
  c.yaw_rate_rad_s = command.body_rates_rad_s.z;
  c.armed = command.armed;
  c.release_payload = command.release_payload;
  c.handover = command.handover;
  return c;
}

msg::FcState to_msg(const FcStatus& s, std::uint32_t uav_id, std::int64_t stamp_ns) {
  msg::FcState m;
  m.uav_id = uav_id;
  m.stamp_ns = stamp_ns;
  m.link_ok = s.link_ok;
  m.autopilot = autopilot_of(s.reported_autopilot);
  m.system_id = s.system_id;
  m.armed = s.armed;
  m.mode = mode_of(s.mode);
  m.mode_name = s.mode_name;
  m.custom_mode = s.custom_mode;
  m.landed_state = landed_of(s.landed_state);
  m.battery_voltage_v = s.battery_voltage_v;
  m.battery_remaining = s.battery_remaining;
  m.hover_thrust = s.hover_thrust;
  m.setpoint_rate_hz = s.setpoint_rate_hz;
  m.rx_errors = saturate(s.rx_errors);
  m.rx_dropped = saturate(s.rx_dropped);
  m.status_text = s.status_text;
  m.offboard_ready = s.offboard_ready;
  m.failsafe = s.failsafe;
  m.rx_unknown = saturate(s.rx_unknown);
  m.streams.clear();
  for (const StreamState& stream : s.streams) m.streams.push_back(stream_of(stream));
  m.streams_missing = s.streams_missing;
  m.estimator_reported = s.estimator.reported;
  m.estimator_ok = s.estimator.attitude_ok;
  m.estimator = s.estimator.text;
  m.parameters.clear();
  for (const ParameterFinding& finding : s.parameters)
    m.parameters.push_back(parameter_of(finding));
  m.flight_blocker = s.flight_blocker;
  m.auto_disarm_s = s.auto_disarm_s;
  return m;
}

std::optional<OperatorCommand> from_msg(msg::FcCommandKind kind) {
  switch (kind) {
    case msg::FcCommandKind::FC_COMMAND_ARM:
      return OperatorCommand::Arm;
    case msg::FcCommandKind::FC_COMMAND_DISARM:
      return OperatorCommand::Disarm;
    case msg::FcCommandKind::FC_COMMAND_OFFBOARD:
      return OperatorCommand::Offboard;
    case msg::FcCommandKind::FC_COMMAND_LAND:
      return OperatorCommand::Land;
  }
  return std::nullopt;
}

msg::FcCommandResult to_msg(CommandOutcome outcome) {
  switch (outcome) {
    case CommandOutcome::Accepted:
      return msg::FcCommandResult::FC_RESULT_ACCEPTED;
    case CommandOutcome::Refused:
      return msg::FcCommandResult::FC_RESULT_REFUSED;
    case CommandOutcome::NoAnswer:
      break;
  }
  return msg::FcCommandResult::FC_RESULT_NO_ANSWER;
}

bool differs(const msg::FcState& a, const msg::FcState& b) {
  return a.link_ok != b.link_ok || a.autopilot != b.autopilot || a.system_id != b.system_id ||
         a.armed != b.armed || a.mode != b.mode || a.mode_name != b.mode_name ||
         a.landed_state != b.landed_state || a.offboard_ready != b.offboard_ready ||
         a.status_text != b.status_text || a.failsafe != b.failsafe ||
         a.streams_missing != b.streams_missing || a.flight_blocker != b.flight_blocker ||
         a.estimator != b.estimator || a.auto_disarm_s != b.auto_disarm_s;
}

}  // namespace cover::fc_bridge
