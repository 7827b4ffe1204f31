#include "cover/fc_bridge/autopilot_session.hpp"

#include "cover/mavlink/messages.hpp"
#include "cover/mavlink/protocol.hpp"

namespace cover::fc_bridge {
namespace {
namespace mav = cover::mavlink;
constexpr std::uint16_t kNoVoltage = 0xFFFF;
}  // namespace

const char* to_string(LandedState state) {
  switch (state) {
    case LandedState::Undefined:
      return "undefined";
    case LandedState::OnGround:
      return "on ground";
    case LandedState::InAir:
      return "in air";
    case LandedState::Takeoff:
      return "taking off";
    case LandedState::Landing:
      return "landing";
  }
  return "undefined";
}

AutopilotSession::AutopilotSession(AutopilotProfile profile, double heartbeat_timeout_s)
    : profile_(profile), heartbeat_timeout_s_(heartbeat_timeout_s) {}

bool AutopilotSession::accept(const mavlink::Frame& frame, double now_s) {
  if (!known() && !learn(frame)) return false;
  if (frame.system_id != system_id_ || frame.component_id != component_id_) return false;
  switch (frame.message_id) {
    case mav::Heartbeat::kId:
      on_heartbeat(frame, now_s);
      break;
    case mav::SysStatus::kId:
      on_sys_status(frame);
      break;
    case mav::BatteryStatus::kId:
      on_battery_status(frame);
      break;
    case mav::ExtendedSysState::kId:
      on_extended_sys_state(frame);
      break;
    case mav::StatusText::kId:
      on_status_text(frame);
      break;
    default:
      break;
  }
  return true;
}

bool AutopilotSession::learn(const mavlink::Frame& frame) {
  const auto heartbeat = mav::decode<mav::Heartbeat>(frame);
  if (!heartbeat || heartbeat->autopilot == mav::mav_autopilot::kInvalid ||
      frame.component_id != mav::mav_comp::kAutopilot1 || frame.system_id == 0) {
    return false;
  }
  system_id_ = frame.system_id;
  component_id_ = frame.component_id;
  reported_autopilot_ = heartbeat->autopilot;
  return true;
}

bool AutopilotSession::link_ok(double now_s) const {
  return last_heartbeat_s_ >= 0.0 && now_s - last_heartbeat_s_ <= heartbeat_timeout_s_;
}

void AutopilotSession::on_heartbeat(const mavlink::Frame& frame, double now_s) {
  const auto hb = mav::Heartbeat::unpack(frame.payload.data());
  if (hb.autopilot == mav::mav_autopilot::kInvalid) return;
  last_heartbeat_s_ = now_s;
  reported_autopilot_ = hb.autopilot;
  const bool armed = (hb.base_mode & mav::mav_mode_flag::kSafetyArmed) != 0;
  const bool older_than_ack =
      acked_armed_ && armed != *acked_armed_ && now_s - acked_armed_s_ <= kAckedStateHold_s;
  if (!older_than_ack) {
    armed_ = armed;
    acked_armed_.reset();
  }
  const bool mode_older_than_ack =
      acked_mode_ && hb.custom_mode != *acked_mode_ && now_s - acked_mode_s_ <= kAckedStateHold_s;
  if (mode_older_than_ack) return;
  acked_mode_.reset();
  const bool changed = mode_name_ == "unknown" || hb.custom_mode != custom_mode_ ||
                       (hb.base_mode & mav::mav_mode_flag::kCustomModeEnabled) !=
                           (base_mode_ & mav::mav_mode_flag::kCustomModeEnabled);
  base_mode_ = hb.base_mode;
  custom_mode_ = hb.custom_mode;
  if (changed) {
    mode_ = profile_.decode_mode(hb.base_mode, hb.custom_mode);
    mode_name_ = profile_.mode_name(hb.base_mode, hb.custom_mode);
  }
}

void AutopilotSession::on_arming_accepted(bool armed, double now_s) {
  armed_ = armed;
  acked_armed_ = armed;
  acked_armed_s_ = now_s;
}

void AutopilotSession::on_mode_accepted(std::uint8_t base_mode, std::uint32_t custom_mode,
                                        double now_s) {
  base_mode_ =
      static_cast<std::uint8_t>((base_mode_ & mav::mav_mode_flag::kSafetyArmed) | base_mode);
  custom_mode_ = custom_mode;
  mode_ = profile_.decode_mode(base_mode_, custom_mode_);
  mode_name_ = profile_.mode_name(base_mode_, custom_mode_);
  acked_mode_ = custom_mode;
  acked_mode_s_ = now_s;
}

void AutopilotSession::on_sys_status(const mavlink::Frame& frame) {
  const auto s = mav::SysStatus::unpack(frame.payload.data());
  if (s.voltage_battery != kNoVoltage && s.voltage_battery != 0) {
    battery_voltage_v_ = s.voltage_battery / 1000.0;
  }
  if (s.battery_remaining >= 0) battery_remaining_ = s.battery_remaining / 100.0;
}

void AutopilotSession::on_battery_status(const mavlink::Frame& frame) {
  const auto b = mav::BatteryStatus::unpack(frame.payload.data());
  if (b.id != 0) return;  // the first battery: the one SYS_STATUS reports too
  double millivolts = 0.0;
  for (const std::uint16_t cell : b.voltages) {
    if (cell != kNoVoltage) millivolts += cell;
  }
  for (const std::uint16_t cell : b.voltages_ext) {
    if (cell != kNoVoltage && cell != 0) millivolts += cell;  // 0 here: not sent
  }
  if (millivolts > 0.0) battery_voltage_v_ = millivolts / 1000.0;
  if (b.battery_remaining >= 0) battery_remaining_ = b.battery_remaining / 100.0;
}

void AutopilotSession::on_extended_sys_state(const mavlink::Frame& frame) {
  const auto e = mav::ExtendedSysState::unpack(frame.payload.data());
  switch (e.landed_state) {
    case mav::mav_landed_state::kOnGround:
      landed_state_ = LandedState::OnGround;
      break;
    case mav::mav_landed_state::kInAir:
      landed_state_ = LandedState::InAir;
      break;
    case mav::mav_landed_state::kTakeoff:
      landed_state_ = LandedState::Takeoff;
      break;
    case mav::mav_landed_state::kLanding:
      landed_state_ = LandedState::Landing;
      break;
    default:
      landed_state_ = LandedState::Undefined;
      break;
  }
}

void AutopilotSession::report_text(std::string text, std::uint8_t severity) {
  status_text_ = std::move(text);
  status_severity_ = severity;
  ++status_text_count_;
}

void AutopilotSession::on_status_text(const mavlink::Frame& frame) {
  const auto t = mav::StatusText::unpack(frame.payload.data());
  status_text_ = t.text_string();
  status_severity_ = t.severity;
  ++status_text_count_;
}

}  // namespace cover::fc_bridge
