#include "cover/mission/stage_machine.hpp"

#include <cmath>
#include <cstdio>
#include <utility>

namespace cover::mission {

using model::Stage;

StageMachine::StageMachine(Task task, MissionParams params)
    : task_(std::move(task)), params_(params) {
  params_.validate();
  if (!task_.processes.empty()) decision_.reference_ugv = task_.processes.front().from_ugv;
}

const StageDecision& StageMachine::update(double time_s, const Eigen::Vector3d& position_m,
                                          const Eigen::Vector3d& velocity_m_s) {
  // One-step events are cleared every step; latched flags (armed, payload_released) stay.
  decision_.stage_started = false;
  decision_.release_payload = false;
  if (is_terminal(decision_.state)) return decision_;
  if (task_.processes.empty()) {
    fail(FailureReason::InvalidState, time_s);
    return decision_;
  }
  if (!std::isfinite(time_s) || !position_m.allFinite() || !velocity_m_s.allFinite()) {
    fail(FailureReason::InvalidState, time_s);
    return decision_;
  }
  if (decision_.state == MissionState::NotStarted) {
    decision_.state = MissionState::Running;
    start_stage(0, Stage::Initial, time_s);
    return decision_;
  }

  decision_.stage_time_s = time_s - stage_start_s_;
  last_distance_m_ = (position_m - decision_.target_point_m).norm();
  if (decision_.stage_time_s > timeout_s(decision_.stage)) {
    fail(FailureReason::StageTimeout, time_s);
    return decision_;
  }
  if (!reached(position_m, velocity_m_s)) return decision_;

  switch (decision_.stage) {
    case Stage::Initial:
      start_stage(decision_.process_index, Stage::Transition, time_s);
      break;
    case Stage::Transition:
      start_stage(decision_.process_index, Stage::Final, time_s);
      break;
    case Stage::Final:
      finish_final_stage(time_s);
      break;
  }
  return decision_;
}

void StageMachine::finish_final_stage(double time_s) {
  switch (process().final_action) {
    case FinalAction::Land:
      // Landing is always the last process (Task::validate): disarm and end the task.
      decision_.armed = false;
      decision_.state = MissionState::Complete;
      return;
    case FinalAction::Deliver:
      decision_.release_payload = true;
      decision_.payload_released = true;
      break;
    case FinalAction::None:
      break;
  }
  if (decision_.process_index + 1 < task_.processes.size()) {
    start_stage(decision_.process_index + 1, Stage::Initial, time_s);
  } else {
    // Nothing left: keep holding the final point (the controller keeps tracking it).
    decision_.state = MissionState::Complete;
  }
}

bool StageMachine::abort(double time_s) {
  if (is_terminal(decision_.state)) return false;
  if (std::isfinite(time_s) && decision_.state == MissionState::Running) {
    decision_.stage_time_s = time_s - stage_start_s_;
  }
  decision_.state = MissionState::Aborted;
  return true;
}

void StageMachine::fail(FailureReason reason, double time_s) {
  if (is_terminal(decision_.state)) return;
  if (std::isfinite(time_s) && decision_.state == MissionState::Running) {
    decision_.stage_time_s = time_s - stage_start_s_;
  }
  decision_.state = MissionState::Failed;
  decision_.failure = reason;
}

void StageMachine::start_stage(std::size_t process_index, Stage stage, double time_s) {
  decision_.process_index = process_index;
  decision_.stage = stage;
  decision_.stage_started = true;
  decision_.stage_time_s = 0.0;
  stage_start_s_ = time_s;
  const TransitionProcess& p = process();
  // Sec. 3.2: the initial stage flies in Gi; the frame switches to Gj at the transition stage.
  decision_.reference_ugv = stage == Stage::Initial ? p.from_ugv : p.to_ugv;
  switch (stage) {
    case Stage::Initial:
      decision_.target_point_m = p.initial_point_m;
      break;
    case Stage::Transition:
      decision_.target_point_m = p.transition_point_m;
      break;
    case Stage::Final:
      decision_.target_point_m = p.final_point_m;
      break;
  }
}

bool StageMachine::reached(const Eigen::Vector3d& position_m,
                           const Eigen::Vector3d& velocity_m_s) const {
  const bool acts = decision_.stage == Stage::Final && process().final_action != FinalAction::None;
  double tolerance_m = params_.reach_tolerance_m;
  if (acts) tolerance_m = params_.action_tolerance_m;
  if (decision_.stage == Stage::Transition) tolerance_m = params_.transition_reach_tolerance_m;
  const double speed_m_s = acts ? params_.action_speed_threshold_m_s : params_.speed_threshold_m_s;
  return (position_m - decision_.target_point_m).norm() <= tolerance_m &&
         velocity_m_s.norm() <= speed_m_s;
}

double StageMachine::timeout_s(Stage stage) const {
  switch (stage) {
    case Stage::Initial:
      return params_.initial_timeout_s;
    case Stage::Transition:
      return params_.transition_timeout_s;
    case Stage::Final:
      return params_.final_timeout_s;
  }
  return params_.final_timeout_s;
}

std::string StageMachine::describe() const {
  char text[256];
  if (task_.processes.empty()) return "task has no process";
  const TransitionProcess& p = process();
  const Eigen::Vector3d& t = decision_.target_point_m;
  std::snprintf(text, sizeof(text),
                "%s: process %zu (G%d->G%d) %s stage, frame G%d, target [%.2f, %.2f, %.2f] m, "
                "%.2f m away, stage time %.1f s%s%s",
                to_string(decision_.state), decision_.process_index, p.from_ugv, p.to_ugv,
                model::to_string(decision_.stage), decision_.reference_ugv, t.x(), t.y(), t.z(),
                last_distance_m_, decision_.stage_time_s,
                decision_.state == MissionState::Failed ? ", failure: " : "",
                decision_.state == MissionState::Failed ? to_string(decision_.failure) : "");
  return text;
}

}  // namespace cover::mission
