#pragma once

#include <string>

#include "cover/fc_bridge/autopilot_view.hpp"
#include "cover/fc_bridge/command_sender.hpp"

namespace cover::fc_bridge {

// The UAV's last line on the companion computer. While COVER flies the UAV (armed, in
// OFFBOARD / GUIDED_NOGPS), no fresh agent command for `cmd_timeout_s`, or a command with
// `handover`, and the autopilot is sent to its own land mode at once, faster than PX4's
// own offboard loss (1 s); it is asked again until its HEARTBEAT shows the land mode (or
// it disarms), with the reason kept for cover/uav/U/fc. An autopilot whose HEARTBEAT
// stops while COVER flies it is asked to land too, blind: only its downlink may be gone,
// and the UAV agent has failed its task (nobody would end the flight otherwise).
class SafetySupervisor {
 public:
  // `land_confirm_s`: after an accepted land request, how long the HEARTBEAT gets to show
  // the land mode before the request goes out again.
  SafetySupervisor(double cmd_timeout_s, double land_confirm_s, double retry_after_refusal_s);

  // A fresh, flyable agent command.
  void on_command(bool handover, double now_s);
  // Whether a land request should go out now; `triggered` is true on the check that
  // decided to land (the caller logs the reason once).
  struct Decision {
    bool request_land = false;
    bool triggered = false;
    bool reached = false;  // the land mode (or disarmed) was just seen: the request ends
  };
  // `bridge_ran`: false when the caller itself was descheduled since its last check (its
  // pass came late): the agent's commands may be queued, undelivered, so the command
  // timeout is not judged on this pass (the next one judges it).
  Decision check(const AutopilotView& autopilot, double now_s, bool bridge_ran = true);
  // The answer to the land request that went out.
  void on_land_result(CommandOutcome outcome, double now_s);

  bool landing() const { return latched_; }
  // Why the bridge last commanded land; empty when it never did.
  const std::string& reason() const { return reason_; }

 private:
  void trigger(std::string reason, double now_s);

  double cmd_timeout_s_;
  double land_confirm_s_;
  double retry_after_refusal_s_;
  double last_command_s_ = -1.0;
  bool handover_ = false;
  bool cover_flew_ = false;  // COVER flew the UAV when the link was last up
  bool latched_ = false;
  bool awaiting_answer_ = false;
  double next_request_s_ = 0.0;
  std::string reason_;
};

}  // namespace cover::fc_bridge
