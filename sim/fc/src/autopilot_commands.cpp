// COMMAND_LONG and PARAM_REQUEST_READ as the simulated autopilot answers them. Every command
// addressed to it gets a COMMAND_ACK (PX4: two for DO_SET_MODE, as PX4 SITL sends); the
// reasons for a refusal go out as each firmware gives them (autopilot_reports.cpp), and only
// those the real firmware was seen to give or that its source sends.
#include <array>
#include <cmath>

#include "cover/config/format_number.hpp"
#include "cover/mavlink/protocol.hpp"
#include "cover/sim/fc/simulated_autopilot.hpp"

namespace cover::sim::fc {

namespace {

namespace result = mavlink::mav_result;

constexpr float kForceArmMagic = 21196.0F;  // param2 of ARM_DISARM: skip the checks
constexpr std::uint8_t kSeverityInfo = 6;

// PARAM_ERROR (345; common.xml): PX4's answer to a request for a name it does not have. Not
// in COVER's codec (its bridge skips it as an unknown type): written here from its fields
// (int16 param_index, uint8 target_system, target_component, char[16] param_id, uint8
// error), CRC_EXTRA checked against a frame from PX4 SITL.
constexpr std::uint32_t kParamErrorId = 345;
constexpr std::uint8_t kParamErrorCrcExtra = 209;
constexpr std::size_t kParamErrorLength = 21;
constexpr std::uint8_t kParamErrorDoesNotExist = 1;

// A float command parameter that must hold a whole number >= 0 (a message id).
std::optional<std::uint32_t> message_id(float value) {
  if (!std::isfinite(value) || value < 0.0F || value > 16777215.0F) return std::nullopt;
  if (std::nearbyint(value) != value) return std::nullopt;
  return static_cast<std::uint32_t>(value);
}

}  // namespace

void SimulatedAutopilot::handle_command(const mavlink::Frame& frame,
                                        const mavlink::CommandLong& command, double now_s) {
  if (command.target_system != system_id() && command.target_system != 0) return;
  if (command.target_component != 0 && command.target_component != mavlink::mav_comp::kAutopilot1) {
    return;
  }
  std::uint8_t outcome = result::kUnsupported;
  switch (command.command) {
    case mavlink::mav_cmd::kDoSetMode:
      outcome = set_mode_command(command, now_s);
      break;
    case mavlink::mav_cmd::kComponentArmDisarm:
      outcome = arm_command(command, now_s);
      break;
    case mavlink::mav_cmd::kNavLand:
      outcome = land_command(now_s);
      break;
    case mavlink::mav_cmd::kDoGripper:  // param2 0 release, 1 grab
      outcome = gripper_command(command, now_s);
      break;
    case mavlink::mav_cmd::kSetMessageInterval:
      outcome = message_interval_command(command, now_s);
      break;
    default:
      break;
  }
  mavlink::CommandAck ack;
  ack.command = command.command;
  ack.result = outcome;
  ack.target_system = frame.system_id;
  ack.target_component = frame.component_id;
  queue(ack);
  if (profile_ == Autopilot::Px4 && command.command == mavlink::mav_cmd::kDoSetMode) {
    queue(ack);
  }
}

// PX4 lets any mode be chosen while disarmed (UserModeIntention::change: "always allow mode
// change while disarmed"; seen: OFFBOARD accepted with no setpoint for a minute) and checks
// OFFBOARD's offboard signal only while armed; ArduPilot's GUIDED_NOGPS init always
// succeeds (mode_guided_nogps.cpp).
std::uint8_t SimulatedAutopilot::set_mode_command(const mavlink::CommandLong& command,
                                                  double now_s) {
  const auto mode = requested_mode(profile_, command.param[0], command.param[1], command.param[2]);
  if (!mode) {
    log_event(AutopilotEvent::Kind::Refusal, now_s,
              "Mode " + std::to_string(static_cast<long>(command.param[1])) + "/" +
                  std::to_string(static_cast<long>(command.param[2])) + " not simulated");
    return profile_ == Autopilot::Px4 ? result::kDenied : result::kFailed;
  }
  if (*mode == FlightMode::Land) return land_command(now_s);
  const bool px4_offboard_blocked = profile_ == Autopilot::Px4 && *mode == FlightMode::Offboard &&
                                    mode_ != FlightMode::Offboard && armed_ &&
                                    !offboard_signal(now_s);
  if (px4_offboard_blocked) {
    log_event(AutopilotEvent::Kind::Refusal, now_s,
              "OFFBOARD refused while armed: no offboard signal");
    report(Px4Event("commander_modeswitch_not_avail", Px4EventLevel::Critical)
               .arg(custom_mode(profile_, FlightMode::Offboard))
               .arg(kPx4NavigationOffboard),
           now_s);
    report(Px4Event("check_modes_offboard_signal", Px4EventLevel::Critical)
               .arg(std::uint32_t{0})
               .arg(std::uint8_t{0}),
           now_s);
    return result::kTemporarilyRejected;
  }
  set_mode(*mode, now_s, "commanded");
  return result::kAccepted;
}

std::uint8_t SimulatedAutopilot::arm_command(const mavlink::CommandLong& command, double now_s) {
  if (command.param[0] == 0.0F) return disarm_command(command, now_s);
  if (command.param[0] != 1.0F) {
    log_event(AutopilotEvent::Kind::Refusal, now_s, "Arming: param1 must be 0 or 1");
    return refusal_result();
  }
  if (armed_) return result::kAccepted;
  if (command.param[1] == kForceArmMagic) {
    arm(now_s, "commanded, FORCED: checks skipped");
    return result::kAccepted;
  }
  if (mode_ == FlightMode::Land) {
    log_event(AutopilotEvent::Kind::Refusal, now_s, "Arming denied: land mode");
    return refusal_result();
  }
  // PX4 SITL, armed in OFFBOARD with no setpoint stream: ACK 1 and these two EVENTs.
  if (profile_ == Autopilot::Px4 && mode_ == FlightMode::Offboard && !offboard_signal(now_s)) {
    log_event(AutopilotEvent::Kind::Refusal, now_s, "Arming denied: no offboard signal");
    report(Px4Event("commander_arm_denied_resolve_failures", Px4EventLevel::Critical), now_s);
    report(Px4Event("check_modes_offboard_signal", Px4EventLevel::Critical)
               .arg(std::uint32_t{0})
               .arg(std::uint8_t{0}),
           now_s);
    return result::kTemporarilyRejected;
  }
  arm(now_s, "commanded");
  return result::kAccepted;
}

// ArduCopter refuses a disarm off the ground with ACK 4 and no text (seen); PX4 with its
// event (Commander: not landed).
std::uint8_t SimulatedAutopilot::disarm_command(const mavlink::CommandLong& command, double now_s) {
  if (!armed_) return result::kAccepted;
  const bool forced = command.param[1] == kForceArmMagic;
  if (!resting_ && !forced) {
    log_event(AutopilotEvent::Kind::Refusal, now_s, "Disarming denied: not landed");
    report(Px4Event("commander_disarm_denied_not_landed", Px4EventLevel::Critical), now_s);
    return refusal_result();
  }
  disarm(now_s, forced ? "commanded, FORCED" : "commanded", px4_arm_reason::kExternalCommand);
  return result::kAccepted;
}

std::uint8_t SimulatedAutopilot::land_command(double now_s) {
  if (mode_ != FlightMode::Land) {
    set_mode(FlightMode::Land, now_s, "commanded");
    report(Px4Event("commander_landing_current_pos", Px4EventLevel::Info), now_s);
  }
  return result::kAccepted;
}

std::uint8_t SimulatedAutopilot::gripper_command(const mavlink::CommandLong& command,
                                                 double now_s) {
  if (command.param[1] != 0.0F) {
    log_event(AutopilotEvent::Kind::Refusal, now_s, "Gripper: only release is simulated");
    return refusal_result();
  }
  release_requested_ = true;
  log_event(AutopilotEvent::Kind::Payload, now_s, "Gripper: release");
  return result::kAccepted;
}

// MAV_CMD_SET_MESSAGE_INTERVAL: param1 the message id, param2 the interval (us; 0 default,
// -1 off). A message the autopilot does not stream: PX4 answers 4 FAILED, ArduPilot 2
// DENIED and says so (both seen).
std::uint8_t SimulatedAutopilot::message_interval_command(const mavlink::CommandLong& command,
                                                          double now_s) {
  const auto id = message_id(command.param[0]);
  if (id && streams_.set_interval(*id, command.param[1], now_s)) {
    const double hz = streams_.rate_hz(*id);
    link_notes_.push_back("SET_MESSAGE_INTERVAL: message " + std::to_string(*id) +
                          (hz > 0.0 ? " at " + config::format_number(hz) + " Hz" : " off"));
    return result::kAccepted;
  }
  const long asked = id ? static_cast<long>(*id) : -1L;
  link_notes_.push_back("SET_MESSAGE_INTERVAL refused: message " + std::to_string(asked) +
                        " is no stream of this autopilot");
  say(kSeverityInfo, "No ap_message for mavlink id (" + std::to_string(asked) + ")");
  return profile_ == Autopilot::Px4 ? result::kFailed : result::kDenied;
}

// PX4 answers a request it cannot grant now "temporarily rejected"; ArduPilot "failed".
std::uint8_t SimulatedAutopilot::refusal_result() const {
  return profile_ == Autopilot::Px4 ? result::kTemporarilyRejected : result::kFailed;
}

// By name (param_index -1) or by index. A name it does not have: ArduPilot stays silent,
// PX4 answers PARAM_ERROR (both seen).
void SimulatedAutopilot::handle_param_request(const mavlink::Frame& frame,
                                              const mavlink::ParamRequestRead& request) {
  if (request.target_system != system_id() && request.target_system != 0) return;
  const bool by_name = request.param_index < 0;
  std::optional<std::size_t> index;
  if (by_name) {
    index = parameters_.index_of(mavlink::param_id_string(request.param_id));
  } else if (static_cast<std::size_t>(request.param_index) < parameters_.size()) {
    index = static_cast<std::size_t>(request.param_index);
  }
  if (index) {
    queue(parameters_.value_message(*index, by_name));
    return;
  }
  if (profile_ != Autopilot::Px4 || !by_name) return;
  std::array<std::uint8_t, kParamErrorLength> payload{};
  const auto param_index = static_cast<std::uint16_t>(request.param_index);
  payload[0] = static_cast<std::uint8_t>(param_index & 0xFF);
  payload[1] = static_cast<std::uint8_t>(param_index >> 8);
  payload[2] = frame.system_id;
  payload[3] = frame.component_id;
  for (std::size_t i = 0; i < request.param_id.size(); ++i) {
    payload[4 + i] = static_cast<std::uint8_t>(request.param_id[i]);
  }
  payload[20] = kParamErrorDoesNotExist;
  outbox_.push_back(
      encoder_.frame(kParamErrorId, kParamErrorCrcExtra, payload.data(), payload.size()));
}

}  // namespace cover::sim::fc
