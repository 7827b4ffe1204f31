#include "cover/fc_bridge/command_sender.hpp"

#include "cover/mavlink/protocol.hpp"

namespace cover::fc_bridge {
namespace {
namespace mav = cover::mavlink;
// An autopilot working on a command (IN_PROGRESS) gets this many ACK timeouts to finish.
constexpr double kInProgressTimeouts = 10.0;
}  // namespace

const char* to_string(CommandOutcome outcome) {
  switch (outcome) {
    case CommandOutcome::Accepted:
      return "accepted";
    case CommandOutcome::Refused:
      return "refused";
    case CommandOutcome::NoAnswer:
      return "no answer";
  }
  return "no answer";
}

const char* mav_result_text(std::uint8_t result) {
  switch (result) {
    case mav::mav_result::kAccepted:
      return "accepted";
    case mav::mav_result::kTemporarilyRejected:
      return "temporarily rejected";
    case mav::mav_result::kDenied:
      return "denied";
    case mav::mav_result::kUnsupported:
      return "unsupported";
    case mav::mav_result::kFailed:
      return "failed";
    case mav::mav_result::kInProgress:
      return "in progress";
    case 6:
      return "cancelled";
    case 7:
      return "only as COMMAND_LONG";
    case 8:
      return "only as COMMAND_INT";
    case 9:
      return "unsupported frame";
    default:
      return "unknown result";
  }
}

const char* command_name(std::uint16_t command) {
  switch (command) {
    case mav::mav_cmd::kNavLand:
      return "NAV_LAND";
    case mav::mav_cmd::kDoSetMode:
      return "DO_SET_MODE";
    case mav::mav_cmd::kDoGripper:
      return "DO_GRIPPER";
    case mav::mav_cmd::kComponentArmDisarm:
      return "COMPONENT_ARM_DISARM";
    case mav::mav_cmd::kSetMessageInterval:
      return "SET_MESSAGE_INTERVAL";
    default:
      return "COMMAND";
  }
}

CommandSender::CommandSender(double ack_timeout_s, int retries)
    : ack_timeout_s_(ack_timeout_s), retries_(retries) {
  pending_.reserve(8);
  results_.reserve(8);
}

std::optional<mavlink::CommandLong> CommandSender::start(const CommandSpec& spec,
                                                         std::uint8_t target_system,
                                                         std::uint8_t target_component,
                                                         std::uint64_t token, double now_s,
                                                         bool preempt) {
  for (std::size_t i = 0; i < pending_.size(); ++i) {
    if (pending_[i].message.command != spec.command) continue;
    if (!preempt) return std::nullopt;
    finish(i, CommandOutcome::Refused, "superseded by a newer command of the same kind");
    break;
  }
  Pending p;
  p.message.command = spec.command;
  p.message.param = spec.param;
  p.message.target_system = target_system;
  p.message.target_component = target_component;
  p.message.confirmation = 0;
  p.token = token;
  p.deadline_s = now_s + ack_timeout_s_;
  pending_.push_back(p);
  return p.message;
}

void CommandSender::on_ack(const mavlink::CommandAck& ack, std::uint8_t own_system,
                           std::uint8_t own_component, double now_s) {
  if (ack.target_system != 0 && ack.target_system != own_system) return;
  if (ack.target_component != 0 && ack.target_component != own_component) return;
  for (std::size_t i = 0; i < pending_.size(); ++i) {
    if (pending_[i].message.command != ack.command) continue;
    if (ack.result == mav::mav_result::kInProgress) {
      pending_[i].deadline_s = now_s + kInProgressTimeouts * ack_timeout_s_;
      return;
    }
    std::string text = mav_result_text(ack.result);
    if (ack.result != mav::mav_result::kAccepted && ack.result_param2 != 0) {
      text += " (reason code " + std::to_string(ack.result_param2) + ")";
    }
    finish(i,
           ack.result == mav::mav_result::kAccepted ? CommandOutcome::Accepted
                                                    : CommandOutcome::Refused,
           std::move(text));
    return;
  }
}

void CommandSender::poll(double now_s, std::vector<mavlink::CommandLong>& resend) {
  for (std::size_t i = 0; i < pending_.size();) {
    Pending& p = pending_[i];
    if (now_s < p.deadline_s) {
      ++i;
      continue;
    }
    if (p.sends > retries_) {
      finish(i, CommandOutcome::NoAnswer,
             "no COMMAND_ACK after " + std::to_string(p.sends) + " sends");
      continue;  // finish() removed index i
    }
    ++p.sends;
    ++p.message.confirmation;
    p.deadline_s = now_s + ack_timeout_s_;
    resend.push_back(p.message);
    ++i;
  }
}

bool CommandSender::busy(std::uint16_t command) const {
  for (const Pending& p : pending_) {
    if (p.message.command == command) return true;
  }
  return false;
}

void CommandSender::finish(std::size_t index, CommandOutcome outcome, std::string message) {
  results_.push_back(
      {pending_[index].token, pending_[index].message.command, outcome, std::move(message)});
  pending_.erase(pending_.begin() + static_cast<std::ptrdiff_t>(index));
}

}  // namespace cover::fc_bridge
