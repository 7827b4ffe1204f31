// COMMAND_LONG as the simulated autopilot answers it: every command addressed to it gets a
// COMMAND_ACK, a refusal a STATUSTEXT first (the reason a bridge reports).
#include <cmath>

#include "cover/mavlink/protocol.hpp"
#include "cover/sim/fc/simulated_autopilot.hpp"

namespace cover::sim::fc {

namespace {

namespace result = mavlink::mav_result;

constexpr std::uint16_t kDoGripper = 211;   // MAV_CMD_DO_GRIPPER: param2 0 release, 1 grab
constexpr float kForceArmMagic = 21196.0F;  // param2 of ARM_DISARM: skip the checks
constexpr std::uint8_t kSeverityWarning = 4;
constexpr std::uint8_t kSeverityInfo = 6;

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
      set_mode(FlightMode::Land, now_s, "commanded");
      outcome = result::kAccepted;
      break;
    case mavlink::mav_cmd::kDoGripper:  // param2 0 release, 1 grab
      outcome = gripper_command(command, now_s);
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
}

std::uint8_t SimulatedAutopilot::set_mode_command(const mavlink::CommandLong& command,
                                                  double now_s) {
  const auto mode = requested_mode(profile_, command.param[0], command.param[1], command.param[2]);
  if (!mode) {
    event(AutopilotEvent::Kind::Refusal, now_s,
          "Mode " + std::to_string(static_cast<long>(command.param[1])) + "/" +
              std::to_string(static_cast<long>(command.param[2])) + " not available",
          kSeverityWarning);
    return profile_ == AutopilotProfile::Px4 ? result::kDenied : result::kFailed;
  }
  if (*mode == FlightMode::Offboard && mode_ != FlightMode::Offboard &&
      !stream_established(now_s)) {
    return refused(profile_ == AutopilotProfile::Px4 ? "Offboard: no setpoint stream"
                                                     : "GUIDED_NOGPS refused: no setpoint stream",
                   now_s);
  }
  set_mode(*mode, now_s, "commanded");
  return result::kAccepted;
}

std::uint8_t SimulatedAutopilot::arm_command(const mavlink::CommandLong& command, double now_s) {
  const bool forced = command.param[1] == kForceArmMagic;
  if (command.param[0] == 1.0F) {
    if (armed_) return result::kAccepted;
    if (forced) {
      arm(now_s, "commanded, FORCED: checks skipped");
      return result::kAccepted;
    }
    if (mode_ == FlightMode::Land) return refused("Arming denied: land mode", now_s);
    if (mode_ == FlightMode::Offboard && !setpoint_fresh(now_s)) {
      return refused("Arming denied: no offboard setpoint", now_s);
    }
    arm(now_s, "commanded");
    return result::kAccepted;
  }
  if (command.param[0] == 0.0F) {
    if (!armed_) return result::kAccepted;
    if (!resting_ && !forced) return refused("Disarming denied: not landed", now_s);
    disarm(now_s, forced ? "commanded, FORCED" : "commanded");
    return result::kAccepted;
  }
  return refused("Arming: param1 must be 0 or 1", now_s);
}

std::uint8_t SimulatedAutopilot::gripper_command(const mavlink::CommandLong& command,
                                                 double now_s) {
  if (command.param[1] != 0.0F) return refused("Gripper: only release is simulated", now_s);
  release_requested_ = true;
  event(AutopilotEvent::Kind::Payload, now_s, "Gripper: release", kSeverityInfo);
  return result::kAccepted;
}

std::uint8_t SimulatedAutopilot::refused(const std::string& why, double now_s) {
  event(AutopilotEvent::Kind::Refusal, now_s, why, kSeverityWarning);
  return refusal_result();
}

// PX4 answers a request it cannot grant now "temporarily rejected"; ArduPilot "failed".
std::uint8_t SimulatedAutopilot::refusal_result() const {
  return profile_ == AutopilotProfile::Px4 ? result::kTemporarilyRejected : result::kFailed;
}

}  // namespace cover::sim::fc
