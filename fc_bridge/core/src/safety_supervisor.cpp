#include "cover/fc_bridge/safety_supervisor.hpp"

#include <cmath>
#include <cstdio>

namespace cover::fc_bridge {

SafetySupervisor::SafetySupervisor(double cmd_timeout_s, double land_confirm_s,
                                   double retry_after_refusal_s)
    : cmd_timeout_s_(cmd_timeout_s),
      land_confirm_s_(land_confirm_s),
      retry_after_refusal_s_(retry_after_refusal_s) {}

void SafetySupervisor::on_command(bool handover, double now_s) {
  last_command_s_ = now_s;
  handover_ = handover;
}

SafetySupervisor::Decision SafetySupervisor::check(const AutopilotView& autopilot, double now_s,
                                                   bool bridge_ran) {
  Decision decision;
  if (latched_ && (!autopilot.armed || autopilot.mode == FcMode::Land)) {
    latched_ = false;
    decision.reached = true;
    return decision;
  }
  if (autopilot.link_ok) {
    cover_flew_ = autopilot.cover_flying();
  } else if (!latched_ && cover_flew_) {
    trigger("autopilot link lost (no HEARTBEAT) while COVER flew the UAV: land requested blind",
            now_s);
    decision.triggered = true;
  }
  if (!latched_ && autopilot.cover_flying()) {
    if (handover_) {
      trigger("the UAV agent handed over (no relative state to land on)", now_s);
      decision.triggered = true;
    } else if (last_command_s_ < 0.0) {
      trigger("no command from the UAV agent since the bridge started", now_s);
      decision.triggered = true;
    } else if (bridge_ran && now_s - last_command_s_ > cmd_timeout_s_) {
      char text[128];
      std::snprintf(text, sizeof(text), "no command from the UAV agent for %.0f ms (limit %.0f ms)",
                    (now_s - last_command_s_) * 1e3, cmd_timeout_s_ * 1e3);
      trigger(text, now_s);
      decision.triggered = true;
    }
  }
  // Sent with the link down too: a lost downlink may leave the uplink working.
  if (latched_ && !awaiting_answer_ && now_s >= next_request_s_) {
    decision.request_land = true;
    awaiting_answer_ = true;
  }
  return decision;
}

void SafetySupervisor::on_land_result(CommandOutcome outcome, double now_s) {
  awaiting_answer_ = false;
  switch (outcome) {
    case CommandOutcome::Accepted:
      next_request_s_ = now_s + land_confirm_s_;
      break;
    case CommandOutcome::Refused:
      next_request_s_ = now_s + retry_after_refusal_s_;
      break;
    case CommandOutcome::NoAnswer:  // its own resends spaced it: 4 frames a second at most
      next_request_s_ = now_s;
      break;
  }
}

void SafetySupervisor::trigger(std::string reason, double now_s) {
  latched_ = true;
  awaiting_answer_ = false;
  next_request_s_ = now_s;
  reason_ = std::move(reason);
}

}  // namespace cover::fc_bridge
