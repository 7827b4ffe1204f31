#pragma once

#include <optional>
#include <string>

#include "cover/fc_bridge/autopilot_view.hpp"
#include "cover/fc_bridge/command_sender.hpp"

namespace cover::fc_bridge {

// The mode and arming procedure, in the autopilots' order: setpoints stream (> 2 Hz for
// `offboard_stream_s`), then OFFBOARD / GUIDED_NOGPS, then arm. The bridge arms only on an
// operator's request, or by itself when `auto_arm` is set (simulation only): then it runs
// the procedure once per run, and gives it up for good when the pilot (or the bridge's
// own failsafe) takes the autopilot out of OFFBOARD, never fighting them.
class OffboardSequencer {
 public:
  OffboardSequencer(double offboard_stream_s, bool auto_arm, double retry_after_failure_s);

  // nullopt when an OFFBOARD request may go out now; otherwise why not (the setpoint
  // stream has not flowed long enough).
  std::optional<std::string> offboard_refusal(double streaming_for_s) const;

  enum class Step { None, RequestOffboard, RequestArm };
  // auto_arm: the next step to request now (one at a time).
  Step next(const AutopilotView& autopilot, double streaming_for_s, double now_s);
  void on_result(Step step, CommandOutcome outcome, double now_s);
  // Ends the automatic procedure (logged by the caller with `why`).
  void stop();

  bool automatic() const { return auto_arm_ && !stopped_; }
  bool engaged() const { return engaged_; }

 private:
  double offboard_stream_s_;
  bool auto_arm_;
  double retry_after_failure_s_;
  bool stopped_ = false;
  bool seen_offboard_ = false;  // OFFBOARD was reached: leaving it is someone's decision
  bool engaged_ = false;        // armed in OFFBOARD was reached
  bool awaiting_answer_ = false;
  Step last_step_ = Step::None;  // not requested again before next_attempt_s_
  double next_attempt_s_ = 0.0;
};

}  // namespace cover::fc_bridge
