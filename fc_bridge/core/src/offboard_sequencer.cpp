#include "cover/fc_bridge/offboard_sequencer.hpp"

#include <cstdio>

namespace cover::fc_bridge {

OffboardSequencer::OffboardSequencer(double offboard_stream_s, bool auto_arm,
                                     double retry_after_failure_s)
    : offboard_stream_s_(offboard_stream_s),
      auto_arm_(auto_arm),
      retry_after_failure_s_(retry_after_failure_s) {}

std::optional<std::string> OffboardSequencer::offboard_refusal(double streaming_for_s) const {
  if (streaming_for_s >= offboard_stream_s_) return std::nullopt;
  char text[160];
  std::snprintf(text, sizeof(text),
                "setpoints have streamed for %.2f s, the autopilot needs %.2f s of them before "
                "offboard (is the UAV agent running?)",
                streaming_for_s, offboard_stream_s_);
  return std::string(text);
}

OffboardSequencer::Step OffboardSequencer::next(const AutopilotView& autopilot,
                                                double streaming_for_s, double now_s) {
  if (!automatic() || !autopilot.link_ok) return Step::None;
  if (seen_offboard_ && autopilot.mode != FcMode::Offboard) {
    stop();  // the pilot, an operator or the failsafe chose another mode
    return Step::None;
  }
  seen_offboard_ = seen_offboard_ || autopilot.mode == FcMode::Offboard;
  if (engaged_) {
    if (!autopilot.armed) stop();
    return Step::None;
  }
  if (autopilot.armed && autopilot.mode == FcMode::Offboard) {
    engaged_ = true;
    return Step::None;
  }
  if (awaiting_answer_) return Step::None;
  Step step = Step::None;
  if (autopilot.mode != FcMode::Offboard) {
    if (!offboard_refusal(streaming_for_s)) step = Step::RequestOffboard;
  } else if (!autopilot.armed) {
    step = Step::RequestArm;
  }
  if (step == last_step_ && now_s < next_attempt_s_) return Step::None;
  awaiting_answer_ = step != Step::None;
  return step;
}

void OffboardSequencer::on_result(Step step, CommandOutcome outcome, double now_s) {
  awaiting_answer_ = false;
  last_step_ = step;
  // Accepted: the HEARTBEAT (1 Hz) shows the new mode or arming within about a second;
  // the next step goes out as soon as it does, the same one not before then.
  next_attempt_s_ = now_s + (outcome == CommandOutcome::Accepted ? 1.5 : retry_after_failure_s_);
}

void OffboardSequencer::stop() {
  stopped_ = true;
}

}  // namespace cover::fc_bridge
