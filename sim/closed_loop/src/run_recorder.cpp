#include "cover/sim/run_recorder.hpp"

#include "cover/sim/percentile.hpp"

#include <algorithm>
#include <cmath>

namespace cover::sim {
namespace {

using model::Stage;

bool in_transition_stage(const mission::ControllerStatus& status) {
  return status.stage.state == mission::MissionState::Running &&
         status.stage.stage == Stage::Transition;
}

}  // namespace

RunRecorder::RunRecorder(const Scenario& scenario, const mission::Task& task,
                         const mission::MissionParams& mission, const ClosedLoopOptions& options)
    : scenario_(scenario), task_(task), mission_(mission), options_(options) {
  result_.ugv_paths.resize(scenario.world.ugvs.size());
  mpc_us_.reserve(static_cast<std::size_t>(scenario.max_duration_s * options.control_rate_hz) + 1);
  mpc_cpu_us_.reserve(mpc_us_.capacity());
  command_us_.reserve(mpc_us_.capacity());
}

void RunRecorder::record(const mission::ControllerStatus& status,
                         const mission::ControlCommand& command, const World& world) {
  const WorldState& ws = world.state();
  track_transitions(status, command, ws);
  record_tracking(status, world);
  if (status.solve_us > 0.0) mpc_us_.push_back(status.solve_us);
  // Measurement -> command of the steps SAMPC flew (0: a host that does not measure it).
  if (status.solve_us > 0.0 && status.command_us > 0.0) command_us_.push_back(status.command_us);
  // 0 when the step's CPU time was not measured (a UAV agent's trace does not carry it).
  if (status.solve_cpu_us > 0.0) mpc_cpu_us_.push_back(status.solve_cpu_us);
  if (status.planned) plan_ms_.push_back(status.plan_ms);
  if (status.failsafe == mission::Failsafe::EmergencyHover ||
      status.failsafe == mission::Failsafe::EmergencyLanding ||
      status.failsafe == mission::Failsafe::SolverError) {
    ++result_.failsafe_steps;
  }
  record_path(status, ws);
  if (options_.record_step_trace) record_step(status, command, world);
  // An aborted task is over for the run once its safe action has disarmed the motors, a
  // task failed by the failsafe ladder once its emergency landing has, one the autopilot
  // took over (a pilot's mode switch, its link or bridge lost) once the UAV is at rest:
  // the run watches the autopilot land it.
  const bool landing = status.failsafe == mission::Failsafe::EmergencyHover ||
                       status.failsafe == mission::Failsafe::EmergencyLanding ||
                       (status.failsafe == mission::Failsafe::AutopilotControl &&
                        !world.state().uav_contact.resting);
  const bool over = mission::is_terminal(status.stage.state) && !landing &&
                    (status.stage.state != mission::MissionState::Aborted || !command.armed);
  if (done_time_s_ < 0.0 && over) done_time_s_ = ws.time_s;
  ++steps_;
}

void RunRecorder::record_release(const World& world) {
  result_.release_points.push_back(world.state().payload.release_position_m.eigen().head<2>());
}

bool RunRecorder::finished(double time_s) const {
  if (time_s > scenario_.max_duration_s + 1e-9) return true;
  return done_time_s_ >= 0.0 && time_s - done_time_s_ >= scenario_.settle_time_s;
}

void RunRecorder::record_tracking(const mission::ControllerStatus& status, const World& world) {
  const bool running = status.stage.state == mission::MissionState::Running;
  if (running && status.stage.stage == Stage::Final && status.failsafe == mission::Failsafe::None) {
    const RelativeState truth = world.true_relative_state(status.stage.reference_ugv);
    abs_error_sum_ += (truth.position_m - status.reference_position_m).cwiseAbs();
    ++result_.final_tracking_samples;
  }
}

void RunRecorder::record_path(const mission::ControllerStatus& status, const WorldState& ws) {
  if (!options_.record_paths || steps_ % options_.record_every_control_steps != 0) return;
  const bool staged = status.stage.state != mission::MissionState::NotStarted;
  result_.uav_path.push_back(
      {ws.uav.position_m.eigen().head<2>(), staged ? static_cast<int>(status.stage.stage) : -1});
  for (std::size_t k = 0; k < result_.ugv_paths.size(); ++k) {
    result_.ugv_paths[k].push_back(ws.ugvs[k].position_m.eigen().head<2>());
  }
}

void RunRecorder::record_step(const mission::ControllerStatus& status,
                              const mission::ControlCommand& command, const World& world) {
  StepSample sample;
  sample.time_s = world.state().time_s;
  const bool running = status.stage.state == mission::MissionState::Running;
  sample.stage_code = running ? static_cast<int>(status.stage.stage) : -1;
  sample.process_index = static_cast<int>(status.stage.process_index);
  sample.reference_ugv = status.stage.reference_ugv;
  const RelativeState truth = world.true_relative_state(status.stage.reference_ugv);
  sample.position_m = truth.position_m;
  sample.velocity_m_s = truth.velocity_m_s;
  sample.reference_position_m = status.reference_position_m;
  sample.thrust_m_s2 = command.thrust_m_s2;
  sample.body_rate_rad_s = command.body_rate_rad_s;
  sample.disturbance_m_s2 = status.disturbance_m_s2;
  result_.step_trace.push_back(sample);
}

void RunRecorder::track_transitions(const mission::ControllerStatus& status,
                                    const mission::ControlCommand& command,
                                    const WorldState& world) {
  std::vector<TransitionRecord>& records = result_.transitions;
  const Eigen::Vector3d position = world.uav.position_m.eigen();
  const bool in_transition = in_transition_stage(status);
  const bool same =
      tracker_.open && records.back().process_index == static_cast<int>(status.stage.process_index);
  if (tracker_.open && !(in_transition && same)) close_transition(world, status);
  if (in_transition && !tracker_.open) open_transition(status, world);
  if (tracker_.open) {
    TransitionRecord& r = records.back();
    r.path_length_m += (position - tracker_.last_position).norm();
    if (world.time_s - r.start_time_s <= options_.switch_window_s) {
      const double rate_change = (command.body_rate_rad_s - tracker_.last_rates).norm();
      r.peak_rate_change_rad_s = std::max(r.peak_rate_change_rad_s, rate_change);
      tracker_.rate_change_square_sum += rate_change * rate_change;
      ++tracker_.window_steps;
      r.rms_rate_change_rad_s = std::sqrt(tracker_.rate_change_square_sum / tracker_.window_steps);
      r.peak_thrust_change_m_s2 =
          std::max(r.peak_thrust_change_m_s2, std::abs(command.thrust_m_s2 - tracker_.last_thrust));
      r.peak_world_speed_m_s =
          std::max(r.peak_world_speed_m_s, world.uav.velocity_m_s.eigen().norm());
    }
  }
  tracker_.last_position = position;
  tracker_.last_rates = command.body_rate_rad_s;
  tracker_.last_thrust = command.thrust_m_s2;
}

void RunRecorder::open_transition(const mission::ControllerStatus& status,
                                  const WorldState& world) {
  TransitionRecord r;
  r.process_index = static_cast<int>(status.stage.process_index);
  r.start_time_s = world.time_s;
  // The stage started with the last measured position: the path starts where the UAV was.
  r.start_world_m = tracker_.last_position;
  r.start_world_velocity_m_s = world.uav.velocity_m_s.eigen();
  result_.transitions.push_back(r);
  tracker_.open = true;
  tracker_.rate_change_square_sum = 0.0;
  tracker_.window_steps = 0;
}

void RunRecorder::close_transition(const WorldState& world,
                                   const mission::ControllerStatus& status) {
  TransitionRecord& r = result_.transitions.back();
  r.end_time_s = world.time_s;
  r.end_world_m = world.uav.position_m.eigen();
  r.straight_length_m = (r.end_world_m - r.start_world_m).norm();
  // It ended by reaching its point iff the machine moved on (not failed, not cut off).
  r.completed = status.stage.state != mission::MissionState::Failed &&
                status.stage.state != mission::MissionState::Aborted &&
                !(status.stage.stage == Stage::Transition &&
                  static_cast<int>(status.stage.process_index) == r.process_index);
  tracker_.open = false;
}

void RunRecorder::fill_action_errors(const World& world) {
  const WorldState& ws = world.state();
  for (const mission::TransitionProcess& p : task_.processes) {
    if (p.final_action == mission::FinalAction::Deliver && ws.payload.released &&
        std::isnan(result_.delivery_error_m)) {
      const Eigen::Vector3d at = ws.payload.release_position_in_ugv_m[p.to_ugv].eigen();
      result_.delivery_error_m = (at - p.final_point_m).head<2>().norm();
    }
  }
  const mission::TransitionProcess& last = task_.processes.back();
  if (last.final_action == mission::FinalAction::Land &&
      result_.mission_state == mission::MissionState::Complete) {
    const RelativeState on_deck = world.true_relative_state(last.to_ugv);
    result_.landing_error_m = (on_deck.position_m - last.final_point_m).head<2>().norm();
    result_.landed_on_target_deck = ws.uav_contact.resting && ws.uav_contact.surface == last.to_ugv;
    result_.landing_points.push_back(ws.uav.position_m.eigen().head<2>());
  }
}

// The shortest path within the task's limits from every completed transition's start,
// arriving by the stage's own end (transition_bound.hpp).
void RunRecorder::add_transition_bounds(ClosedLoopResult& result) const {
  for (TransitionRecord& r : result.transitions) {
    if (!r.completed) continue;
    const mission::TransitionProcess& process = task_.processes[r.process_index];
    TransitionBoundParams params;
    params.vmax_m_s = process.vmax_m_s;
    params.amax_m_s2 = process.amax_m_s2;
    params.reach_tolerance_m = mission_.transition_reach_tolerance_m;
    params.speed_threshold_m_s = mission_.speed_threshold_m_s;
    const UgvMotionPattern target(scenario_.world.ugvs[process.to_ugv].pattern);
    r.bound = shortest_transition_bound(target, r.start_time_s, r.start_world_m.head<2>(),
                                        r.start_world_velocity_m_s.head<2>(),
                                        r.end_time_s - r.start_time_s, params);
    if (!r.bound.reached) continue;
    result.bound_path_length_m += r.bound.path_length_m;
    result.bound_straight_length_m += r.bound.straight_length_m;
  }
}

// Flies every completed transition's start again with the eq. 30 law (approach_law.hpp).
void RunRecorder::fill_eq30_law_transitions() {
  for (TransitionRecord& r : result_.transitions) {
    if (!r.completed) continue;
    const mission::TransitionProcess& process = task_.processes[r.process_index];
    ApproachLawParams law;
    law.vmax_m_s = process.vmax_m_s;
    law.amax_m_s2 = process.amax_m_s2;
    law.reach_tolerance_m = mission_.transition_reach_tolerance_m;
    law.speed_threshold_m_s = mission_.speed_threshold_m_s;
    const UgvMotionPattern target(scenario_.world.ugvs[process.to_ugv].pattern);
    r.eq30_law = fly_approach_law(target, r.start_time_s, r.start_world_m.head<2>(),
                                  r.start_world_velocity_m_s.head<2>(), law);
    result_.eq30_law_path_length_m += r.eq30_law.path_length_m;
    result_.eq30_law_straight_length_m += r.eq30_law.straight_length_m;
  }
}

bool RunRecorder::task_succeeded(const World& world) const {
  if (result_.mission_state != mission::MissionState::Complete) return false;
  for (const auto& p : task_.processes) {
    if (p.final_action == mission::FinalAction::Deliver && !world.state().payload.released) {
      return false;
    }
  }
  const auto& last = task_.processes.back();
  return last.final_action != mission::FinalAction::Land || result_.landed_on_target_deck;
}

ClosedLoopResult RunRecorder::finish(const World& world,
                                     const mission::ControllerStatus& last_status,
                                     const std::string& status, mission::MissionState state) {
  if (tracker_.open) close_transition(world.state(), last_status);
  result_.mission_state = state;
  result_.status = status;
  result_.duration_s = done_time_s_ >= 0.0 ? done_time_s_ : world.state().time_s;
  for (TransitionRecord& r : result_.transitions) {
    const auto& p = task_.processes[r.process_index];
    r.from_ugv = p.from_ugv;
    r.to_ugv = p.to_ugv;
    if (!r.completed) continue;
    result_.total_path_length_m += r.path_length_m;
    result_.total_straight_length_m += r.straight_length_m;
  }
  if (result_.final_tracking_samples > 0) {
    result_.final_tracking_error_m = abs_error_sum_ / result_.final_tracking_samples;
  }
  fill_action_errors(world);
  fill_eq30_law_transitions();
  result_.success = task_succeeded(world);
  result_.mpc_median_us = percentile(mpc_us_, 0.5);
  result_.mpc_p99_us = percentile(mpc_us_, 0.99);
  result_.mpc_cpu_median_us = percentile(mpc_cpu_us_, 0.5);
  result_.mpc_cpu_p99_us = percentile(mpc_cpu_us_, 0.99);
  result_.command_median_us = percentile(command_us_, 0.5);
  result_.command_p99_us = percentile(command_us_, 0.99);
  result_.plan_median_ms = percentile(plan_ms_, 0.5);
  result_.plan_max_ms = percentile(plan_ms_, 1.0);
  return result_;
}

}  // namespace cover::sim
