#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "cover/fc_bridge/autopilot_profile.hpp"
#include "cover/mavlink/messages.hpp"

namespace cover::fc_bridge {

enum class CommandOutcome { Accepted, Refused, NoAnswer };
const char* to_string(CommandOutcome outcome);
// MAV_RESULT in words: "temporarily rejected", "denied", ...
const char* mav_result_text(std::uint8_t result);
const char* command_name(std::uint16_t command);  // "DO_SET_MODE", "COMPONENT_ARM_DISARM"...

struct CommandResult {
  std::uint64_t token = 0;  // the caller's tag given to start()
  std::uint16_t command = 0;
  CommandOutcome outcome = CommandOutcome::NoAnswer;
  std::string message;  // the autopilot's answer, in words
};

// COMMAND_LONG with the protocol's handshake: one command in flight per command id (the
// COMMAND_ACK names only the id), sent again after `ack_timeout_s` with confirmation + 1,
// up to `retries` times, then "no answer". IN_PROGRESS extends the wait without resending
// (a resend could start the action again).
class CommandSender {
 public:
  CommandSender(double ack_timeout_s, int retries);

  // The COMMAND_LONG to send now, or nullopt when one of the same id is still in flight
  // (busy). With `preempt`, that one is given up (reported refused, superseded) instead.
  std::optional<mavlink::CommandLong> start(const CommandSpec& spec, std::uint8_t target_system,
                                            std::uint8_t target_component, std::uint64_t token,
                                            double now_s, bool preempt);
  // An ACK from the autopilot; `own_system` / `own_component`: ours, to skip ACKs that
  // answer someone else (a ground station's command to the same autopilot).
  void on_ack(const mavlink::CommandAck& ack, std::uint8_t own_system, std::uint8_t own_component,
              double now_s);
  // Appends the resends due at `now_s` to `resend`; commands out of retries end as results.
  void poll(double now_s, std::vector<mavlink::CommandLong>& resend);

  bool busy(std::uint16_t command) const;
  // Finished commands since the last call, oldest first; the caller clears it.
  std::vector<CommandResult>& results() { return results_; }

 private:
  struct Pending {
    mavlink::CommandLong message;
    std::uint64_t token = 0;
    int sends = 1;
    double deadline_s = 0.0;
  };
  void finish(std::size_t index, CommandOutcome outcome, std::string message);

  double ack_timeout_s_;
  int retries_;
  std::vector<Pending> pending_;
  std::vector<CommandResult> results_;
};

}  // namespace cover::fc_bridge
