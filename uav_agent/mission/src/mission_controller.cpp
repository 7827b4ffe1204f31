#include "cover/mission/mission_controller.hpp"
#include "cover/mission/task_file.hpp"

#include <time.h>

#include <chrono>
#include <cmath>
#include <utility>

#include "cover/mission/ladder_level.hpp"
#include "cover/mission/radial_approach.hpp"
#include "cover/sampc/horizon_cost.hpp"

namespace cover::mission {

using model::Stage;

namespace {

Task validated(Task task, int ugv_count) {
  validate_task(task, ugv_count);
  return task;
}

std::vector<sampc::Mode> process_modes(const Task& task, sampc::Mode configured) {
  std::vector<sampc::Mode> modes;
  for (const TransitionProcess& process : task.processes) {
    modes.push_back(sampc::parse_mode(process.method).value_or(configured));
  }
  return modes;
}

// CPU time of the calling thread: SAMPC's own cost, apart from preemption.
double thread_cpu_us() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return 1e6 * static_cast<double>(ts.tv_sec) + 1e-3 * static_cast<double>(ts.tv_nsec);
}

}  // namespace

MissionController::MissionController(Task task, int ugv_count, MissionParams mission,
                                     planner::PlannerParams planner, sampc::SampcParams sampc,
                                     PlanClock clock, PlanWorker::PlanFunction plan)
    : params_(mission),
      ugv_count_(ugv_count),
      machine_(validated(std::move(task), ugv_count), mission),
      sampc_((sampc.validate(), sampc)),
      process_modes_(process_modes(machine_.task(), sampc.mode)),
      task_ugvs_(machine_.task().ugvs()),
      inputs_(static_cast<std::size_t>(ugv_count)),
      plan_clock_(clock),
      observer_(static_cast<int>(std::lround(mission.observer_window_s / mission.control_period_s)),
                mission.control_period_s, mission.observer_time_constant_s),
      ladder_(mission),
      plan_worker_(plan ? std::move(plan) : stage_plan_function(planner), planner.pieces) {
  // The four trajectories that take turns (flown, adopted, the worker's two) are sized once
  // here: no plan and no adoption allocates on either thread.
  trajectory_.reserve(planner.pieces);
  adopted_.trajectory.reserve(planner.pieces);
  output_.status.stage = machine_.decision();
  idle(Failsafe::WaitingForInputs);
}

void MissionController::set_relative_state(int ugv, const RelativeMeasurement& measurement) {
  if (ugv < 0 || ugv >= ugv_count_) {
    ++ignored_inputs_;
    return;
  }
  inputs_[ugv].state = measurement;
  inputs_[ugv].has_state = true;
}

void MissionController::set_ugv_imu(int ugv, const UgvImuMeasurement& measurement) {
  if (ugv < 0 || ugv >= ugv_count_) {
    ++ignored_inputs_;
    return;
  }
  inputs_[ugv].imu = measurement;
  inputs_[ugv].has_imu = true;
}

InputHealth MissionController::input_health(int ugv, double now_s) const {
  if (ugv < 0 || ugv >= ugv_count_) return assess_inputs(LadderInput{}, now_s, params_);
  const UgvInputs& in = inputs_[ugv];
  const LadderInput input{in.has_state, &in.state, in.has_imu, in.imu.stamp_s, &in.imu.motion};
  return assess_inputs(input, now_s, params_);
}

bool MissionController::task_inputs_healthy(double now_s) const {
  for (const int ugv : task_ugvs_) {
    if (input_health(ugv, now_s).cause != FailsafeCause::None) return false;
  }
  return true;
}

// The failsafe ladder on the reference frame's inputs: true when it wrote this step's
// command (emergency hover, landing, or motors off after it), false when SAMPC flies.
bool MissionController::emergency_step(int reference, double now_s) {
  const InputHealth health = input_health(reference, now_s);
  const LadderLevel before = ladder_.level();
  const LadderLevel level = ladder_.update(health, now_s);
  output_.status.failsafe_cause = ladder_.cause();
  output_.status.failsafe_input_age_s = ladder_.cause_age_s();
  if (ladder_.resumed()) {
    // The inputs are back: the stage goes on from where the hover left the UAV; a task that
    // had ended holds that point instead (an abort then holds and lands again).
    ++reference_epoch_;
    sampc_.reset_frame();
    observer_.reset();
    if (holding_) {
      hold_current_point(now_s);
      descending_ = false;
      touchdown_since_s_ = -1.0;
      abort_time_s_ = now_s;
    } else {
      need_plan();
    }
  }
  if (level == LadderLevel::EmergencyLanding && before != LadderLevel::EmergencyLanding) {
    machine_.fail(FailureReason::StaleInput, now_s);
  }
  if (level == LadderLevel::Nominal || level == LadderLevel::ImuHold) return false;
  const UgvInputs& in = inputs_[reference];
  output_.command = ladder_.command(health.state_usable ? &in.state : nullptr, now_s);
  switch (ladder_.level()) {
    case LadderLevel::EmergencyHover:
      output_.status.failsafe = Failsafe::EmergencyHover;
      break;
    case LadderLevel::EmergencyLanding:
      output_.status.failsafe = Failsafe::EmergencyLanding;
      break;
    default:
      output_.status.failsafe = Failsafe::EmergencyLanded;
      break;
  }
  output_.status.stage = machine_.decision();
  return true;
}

const ControllerOutput& MissionController::step(double now_s) {
  rehearsal_due_ = false;
  // A host that did not call prepare_next_step still gets the last step's bookkeeping.
  if (sampc_stepped_) finish_sampc_step();
  output_.command.release_payload = false;
  output_.status.planned = false;
  output_.status.solve_us = 0.0;
  output_.status.solve_cpu_us = 0.0;
  output_.status.feedback_us = 0.0;
  output_.status.command_us = 0.0;
  if (not_flying_step(now_s)) return output_;

  // 1. Inputs of the current reference frame: without them, the failsafe ladder.
  int reference = machine_.reference_ugv();
  if (emergency_step(reference, now_s)) return output_;

  // 2. Stage machine on the state in the current frame; a new stage needs a new plan.
  const RelativeMeasurement& state = inputs_[reference].state;
  const StageDecision& decision = machine_.update(now_s, state.position_m, state.velocity_m_s);
  output_.status.stage = decision;
  output_.command.release_payload = decision.release_payload;
  use_process_method(decision.process_index);
  if (decision.stage_started) need_plan();
  if (!decision.armed) {
    idle(Failsafe::Landed);
    return output_;
  }

  // 3. The frame may have switched (transition stage): its own inputs are needed.
  reference = machine_.reference_ugv();
  if (reference != last_reference_ugv_) switch_frame(reference);
  if (emergency_step(reference, now_s)) return output_;
  const bool ended =
      decision.state == MissionState::Failed || decision.state == MissionState::Aborted;
  if (ended && !holding_) hold_current_point(now_s);
  if (decision.state == MissionState::Aborted) {
    run_abort_action(inputs_[reference].state, now_s);
    if (disarmed_after_abort_) {
      idle(Failsafe::Landed);
      return output_;
    }
  }
  advance_plan(now_s);

  // 4. SAMPC on the horizon reference.
  command_from_sampc(inputs_[reference], now_s);
  report_degraded_flight(decision);
  return output_;
}

// The steps that fly nothing of ours: the autopilot flies (we only keep a hover command
// ready for when it hands back), the UAV is down, or the task has not started and some
// UGV it flies between is not heard yet (a UAV that took off toward a UGV it never heard,
// its agent late to discover over a lossy link, could only hover and land when the frame
// switched to it).
bool MissionController::not_flying_step(double now_s) {
  if (yielded_) {
    output_.command.thrust_m_s2 = ladder_.hover_thrust_m_s2();
    output_.command.body_rate_rad_s.setZero();
    output_.command.armed = true;
    output_.status.failsafe = Failsafe::AutopilotControl;
    output_.status.stage = machine_.decision();
    return true;
  }
  if (ladder_.level() == LadderLevel::Disarmed) {
    idle(Failsafe::EmergencyLanded);
    return true;
  }
  if (!machine_.decision().armed || disarmed_after_abort_) {
    idle(Failsafe::Landed);
    return true;
  }
  if (machine_.decision().state == MissionState::NotStarted && !task_inputs_healthy(now_s)) {
    idle(Failsafe::WaitingForInputs);
    return true;
  }
  return false;
}

// The previous plan's states mean nothing in the new frame; its body-frame inputs still do.
void MissionController::switch_frame(int reference) {
  ++reference_epoch_;
  sampc_.reset_frame();
  // Frames are level (planar UGVs): the vertical estimate (mass) carries over, the
  // horizontal one (drag in this frame's motion) does not.
  disturbance_m_s2_.head<2>().setZero();
  // The observer restarts its window in the new frame; its vertical part moves into the
  // integral's so that the thrust does not step at the switch.
  disturbance_m_s2_.z() += observer_.estimate_m_s2().z();
  observer_.reset();
  last_reference_ugv_ = reference;
}

// A command SAMPC made while the ladder holds on the IMU, or while the UAV holds a point
// after its task ended, says so in the status.
void MissionController::report_degraded_flight(const StageDecision& decision) {
  if (ladder_.level() == LadderLevel::ImuHold && output_.status.failsafe == Failsafe::None) {
    output_.status.failsafe = Failsafe::ImuHold;
  }
  if (holding_ && output_.status.failsafe == Failsafe::None) {
    output_.status.failsafe =
        decision.state == MissionState::Aborted ? Failsafe::Aborted : Failsafe::MissionFailed;
  }
}

bool MissionController::abort(double now_s) {
  if (!machine_.abort(now_s)) return false;
  abort_time_s_ = now_s;
  output_.status.stage = machine_.decision();
  return true;
}

void MissionController::yield_to_autopilot(double now_s) {
  machine_.fail(FailureReason::AutopilotControl, now_s);
  yielded_ = true;
  output_.status.stage = machine_.decision();
}

void MissionController::take_back(double now_s) {
  if (!yielded_) return;
  yielded_ = false;
  ++reference_epoch_;
  sampc_.reset_frame();
  observer_.reset();
  observer_time_s_ = -1.0;
  disturbance_m_s2_.head<2>().setZero();
  hold_current_point(now_s);
}

void MissionController::use_process_method(std::size_t process_index) {
  if (process_index < process_modes_.size()) sampc_.set_mode(process_modes_[process_index]);
}

void MissionController::hold_current_point(double now_s) {
  // Hold where the task ended, in the current frame, with the tracking weights.
  ++reference_epoch_;
  holding_ = true;
  plan_pending_ = false;
  plan_request_id_ = 0;  // a plan still in flight is never adopted
  coasting_ = false;
  trajectory_.assign_hold(inputs_[machine_.reference_ugv()].state.position_m);
  stage_start_s_ = now_s;
}

void MissionController::run_abort_action(const RelativeMeasurement& state, double now_s) {
  if (params_.abort_action != AbortAction::Land) return;
  if (!descending_ && now_s - abort_time_s_ >= params_.abort_hold_s) {
    // A straight vertical line down from the held point at the descent rate; the deck or
    // the ground stops the UAV long before its end.
    const double depth_m = 20.0;
    planner::TrajectoryPiece piece;
    piece.duration_s = depth_m / params_.abort_descent_rate_m_s;
    piece.coefficients.row(0) = trajectory_.position(now_s - stage_start_s_).transpose();
    piece.coefficients(1, 2) = -params_.abort_descent_rate_m_s;
    trajectory_.assign(&piece, 1);
    stage_start_s_ = now_s;
    descending_ = true;
    ++reference_epoch_;
    return;
  }
  if (!descending_) return;
  const double reference_z = trajectory_.position(now_s - stage_start_s_).z();
  const bool held_up = state.position_m.z() - reference_z > params_.land_detect_gap_m &&
                       std::abs(state.velocity_m_s.z()) < params_.land_detect_speed_m_s;
  if (!held_up) {
    touchdown_since_s_ = -1.0;
  } else if (touchdown_since_s_ < 0.0) {
    touchdown_since_s_ = now_s;
  } else if (now_s - touchdown_since_s_ >= params_.land_detect_time_s) {
    disarmed_after_abort_ = true;
  }
}

// A new stage (or the stage resumed after the hover) needs a plan: a request still in
// flight was for what came before, and is never adopted.
void MissionController::need_plan() {
  plan_pending_ = true;
  plan_attempts_ = 0;
  plan_request_id_ = 0;
  coast_on_request_ = true;
}

// Adopts the plan in flight at its step, then asks for one if the stage still has none
// (its first request, or a retry after a plan that was not usable).
void MissionController::advance_plan(double now_s) {
  const double half_period_s = 0.5 * params_.control_period_s;
  if (plan_request_id_ != 0 && now_s >= plan_adopt_at_s_ - half_period_s) adopt_plan(now_s);
  if (plan_pending_ && plan_request_id_ == 0) {
    request_plan(now_s);
    // plan_adopt_steps 0: adopted in this very step.
    if (now_s >= plan_adopt_at_s_ - half_period_s) adopt_plan(now_s);
  }
}

void MissionController::request_plan(double now_s) {
  plan_request_id_ = plan_worker_.request(stage_problem());
  plan_request_s_ = now_s;
  plan_adopt_at_s_ = now_s + params_.plan_adopt_steps * params_.control_period_s;
  if (!coast_on_request_) return;
  // A retry keeps flying the failed plan (a finite hold of its start); a new stage coasts.
  coast_on_request_ = false;
  ++reference_epoch_;
  const RelativeMeasurement& state = inputs_[machine_.reference_ugv()].state;
  coasting_ = true;
  coast_position_m_ = state.position_m;
  coast_velocity_m_s_ = state.velocity_m_s;
  stage_start_s_ = now_s;
}

void MissionController::adopt_plan(double now_s) {
  // Lockstep: this step is the plan's, whatever the machine's speed: wait for it.
  const bool wait = plan_clock_ == PlanClock::Lockstep;
  const auto started = std::chrono::steady_clock::now();
  if (!plan_worker_.take(plan_request_id_, adopted_, wait)) return;  // realtime: fly on
  output_.status.plan_wait_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started).count();
  output_.status.plan_late_steps =
      static_cast<int>(std::lround((now_s - plan_adopt_at_s_) / params_.control_period_s));
  plan_request_id_ = 0;
  output_.status.planned = true;
  output_.status.plan_status = adopted_.status;
  output_.status.plan_ms = adopted_.solve_ms;
  // Even a failed plan returns a finite trajectory (hold the start): fly it meanwhile. The
  // swap hands the previous trajectory's storage to the worker (nothing freed here).
  std::swap(trajectory_, adopted_.trajectory);
  ++reference_epoch_;
  stage_start_s_ = plan_request_s_;
  coasting_ = false;
  plan_pending_ = !planner::is_usable(adopted_.status);
  if (plan_pending_ && ++plan_attempts_ >= params_.max_plan_attempts) {
    machine_.fail(FailureReason::PlanningFailed, now_s);
    output_.status.stage = machine_.decision();
  }
}

planner::StageProblem MissionController::stage_problem() const {
  const StageDecision& decision = machine_.decision();
  const UgvInputs& in = inputs_[decision.reference_ugv];
  const TransitionProcess& process = machine_.task().processes[decision.process_index];
  planner::StageProblem problem;
  problem.start_position_m = in.state.position_m;
  problem.start_velocity_m_s = in.state.velocity_m_s;
  problem.goal_position_m = decision.target_point_m;
  problem.vmax_m_s = process.vmax_m_s;
  problem.amax_m_s2 = process.amax_m_s2;
  // Eq. 23 at the transition stage; the prior method (coni-mpc) has no such compensation.
  problem.transition_stage =
      decision.stage == Stage::Transition && sampc_.params().mode != sampc::Mode::ConiMpc;
  problem.ugv_angular_velocity_rad_s = in.imu.motion.angular_velocity_rad_s;
  // The final stage begins in the transition's frame while the UAV still brakes from its
  // approach. Planned from zero acceleration, the plan runs on while the UAV cannot drop its
  // braking attitude at once, and the UAV trails it (Scenario 4: 3 cm); with all of SAMPC's
  // planned braking the plan stops short and the UAV overshoots it (Scenario 2: 2.9 cm).
  if (decision.stage == Stage::Final && decision.stage_started && output_.command.armed &&
      output_.status.failsafe == Failsafe::None) {
    const Eigen::Vector3d planned = (sampc_.planned_state(1).segment<3>(model::idx::kVelocity) -
                                     sampc_.planned_state(0).segment<3>(model::idx::kVelocity)) /
                                    sampc_.params().step_s;
    problem.start_acceleration_m_s2 = params_.final_start_acceleration_fraction * planned;
  }
  if (flies_radial_approach()) {
    // The radial approach replaces the plan's horizontal part: plan the height alone. A
    // 3-D plan's height bends with its horizontal part, which nothing flies (Scenario 2: a
    // 0.7 m dip and the climb back, 1.5 m of an 11 m transition path).
    problem.start_position_m.head<2>() = problem.goal_position_m.head<2>();
    problem.start_velocity_m_s.head<2>().setZero();
  }
  return problem;
}

void MissionController::fill_reference(double t_s, sampc::HorizonReference& reference) const {
  const sampc::SampcParams& p = sampc_.params();
  for (int k = 0; k <= p.horizon_steps; ++k) {
    const double t_k = t_s + k * p.step_s;
    if (coasting_) {
      reference.position_m[k] = coast_position_m_ + t_k * coast_velocity_m_s_;
      reference.velocity_m_s[k] = coast_velocity_m_s_;
      reference.acceleration_m_s2[k].setZero();
      continue;
    }
    reference.position_m[k] = trajectory_.position(t_k);
    reference.velocity_m_s[k] = trajectory_.velocity(t_k);
    reference.acceleration_m_s2[k] = trajectory_.acceleration(t_k);
  }
}

bool MissionController::flies_radial_approach() const {
  return !holding_ && machine_.decision().stage == Stage::Transition &&
         params_.transition_reference == TransitionReference::RadialApproach &&
         sampc_.params().mode != sampc::Mode::ConiMpc;
}

void MissionController::fill_approach(const Eigen::Vector3d& position_m,
                                      const Eigen::Vector3d& velocity_m_s,
                                      const Eigen::Vector3d& ugv_angular_velocity_rad_s,
                                      double stage_time_s) {
  const TransitionProcess& process = machine_.task().processes[machine_.decision().process_index];
  const Eigen::Vector3d& p = position_m;
  // The UAV's velocity relative to the UGV's translation (eq. 23's v + Omega x p).
  const Eigen::Vector3d relative = velocity_m_s + ugv_angular_velocity_rad_s.cross(p);
  const double radius = p.head<2>().norm();
  const double closing = radius > 1e-9 ? -relative.head<2>().dot(p.head<2>()) / radius : 0.0;
  RadialApproachLimits limits;
  limits.vmax_m_s = process.vmax_m_s;
  limits.amax_m_s2 = process.amax_m_s2;
  limits.brake_m_s2 = params_.approach_brake_fraction * process.amax_m_s2;
  limits.speed_up_ramp_s = params_.approach_speed_up_ramp_s;
  const sampc::SampcParams& sp = sampc_.params();
  fill_radial_approach(p, closing, stage_time_s, limits, sp.horizon_steps, sp.step_s,
                       sampc_input_.reference);
}

void MissionController::fill_sampc_input(const UgvInputs& inputs, const model::UavState& uav_state,
                                         double now_s) {
  const double t_s = now_s - stage_start_s_;
  sampc_input_.uav_state = uav_state;
  fill_reference(t_s, sampc_input_.reference);
  if (flies_radial_approach()) {
    fill_approach(uav_state.segment<3>(model::idx::kPosition),
                  uav_state.segment<3>(model::idx::kVelocity),
                  inputs.imu.motion.angular_velocity_rad_s, t_s);
  }
  sampc_input_.ugv = inputs.imu.motion;
  sampc_input_.ugv.forward_acceleration_m_s2 = inputs.imu.motion.specific_force_m_s2.x();
  sampc_input_.speed_limit_m_s =
      machine_.task().processes[machine_.decision().process_index].vmax_m_s;
  const Eigen::Vector3d disturbance = disturbance_m_s2_ + observer_.estimate_m_s2();
  sampc_input_.ugv.specific_force_m_s2 -= disturbance;
  output_.status.disturbance_m_s2 = disturbance;
}

// SAMPC's waiting preparation was made for this step: its time, under the same reference
// (a new plan, coast, hold or frame since makes it another problem).
bool MissionController::preparation_is_for(double now_s) const {
  return sampc_.prepared() && prepared_epoch_ == reference_epoch_ && prepared_for_s_ >= 0.0 &&
         std::abs(now_s - prepared_for_s_) < 0.5 * params_.control_period_s;
}

void MissionController::command_from_sampc(const UgvInputs& inputs, double now_s) {
  // Holding after a failure tracks a point: the x-y-z-ref weights of the final stage.
  sampc_input_.stage = holding_ ? Stage::Final : machine_.decision().stage;
  model::UavState measured = sampc_input_.uav_state;
  measured.segment<3>(model::idx::kPosition) = inputs.state.position_m;
  measured.segment<3>(model::idx::kVelocity) = inputs.state.velocity_m_s;
  const Eigen::Quaterniond q = inputs.state.attitude.normalized();
  measured.segment<4>(model::idx::kQuaternion) << q.w(), q.x(), q.y(), q.z();

  const bool prepared = preparation_is_for(now_s);
  prepared_for_s_ = -1.0;
  // This thread's CPU clock is a system call (2-3 us each here, against a 3 us feedback): on
  // the measurement's path the feedback's wall time stands for its CPU time.
  const double cpu_before_us = prepared ? 0.0 : thread_cpu_us();
  // Prepared: the reference and UGV motion are the preparation's (for this very time); only
  // the measurement is new. Else the whole input from the measurement, and the whole solve.
  if (prepared) {
    sampc_input_.uav_state = measured;
  } else {
    fill_sampc_input(inputs, measured, now_s);
  }
  const sampc::SampcOutput out =
      prepared ? sampc_.feedback(sampc_input_) : sampc_.solve(sampc_input_);
  output_.status.solve_cpu_us = prepared ? out.feedback_us : thread_cpu_us() - cpu_before_us;
  output_.status.solve_status = out.status;
  output_.status.solve_us = out.prepare_us + out.feedback_us;
  output_.status.feedback_us = prepared ? out.feedback_us : out.prepare_us + out.feedback_us;
  output_.status.reference_position_m = sampc_input_.reference.position_m[0];
  output_.command.thrust_m_s2 = out.command(model::input_idx::kThrust);
  output_.command.body_rate_rad_s = out.command.tail<3>();
  output_.command.armed = true;
  output_.status.failsafe = sampc::is_error(out.status) ? Failsafe::SolverError : Failsafe::None;
  sampc_stepped_ = true;
  sampc_step_s_ = now_s;
  sampc_inputs_ = inputs;
  sampc_command_ = out.command;
}

void MissionController::prepare_next_step() {
  if (!sampc_stepped_) return;
  const double cpu_before_us = thread_cpu_us();
  finish_sampc_step();
  // After a solver error SAMPC starts afresh from the next measurement.
  if (sampc::is_error(output_.status.solve_status)) return;
  const double next_s = sampc_step_s_ + params_.control_period_s;
  const UgvInputs& inputs = inputs_[machine_.reference_ugv()];
  fill_sampc_input(inputs, sampc_.predicted_state(params_.control_period_s), next_s);
  sampc_.prepare(sampc_input_);
  prepared_for_s_ = next_s;
  prepared_epoch_ = reference_epoch_;
  rehearsal_due_ = true;
  output_.status.solve_cpu_us += thread_cpu_us() - cpu_before_us;
}

// What the step learns from its measurement once its command is out: the tracking
// integral and the observer (both feed the next preparation's UGV motion), and the
// failsafe ladder's memory of the last good flight.
void MissionController::finish_sampc_step() {
  sampc_stepped_ = false;
  const UgvInputs& inputs = sampc_inputs_;
  integrate_disturbance(inputs.state.position_m, sampc_input_.reference.position_m[0]);
  // The observer compares consecutive steps' model predictions: the model of this step is
  // its measurement with this step's UGV motion.
  sampc_input_.ugv = inputs.imu.motion;
  sampc_input_.ugv.forward_acceleration_m_s2 = inputs.imu.motion.specific_force_m_s2.x();
  sampc_input_.ugv.specific_force_m_s2 -= disturbance_m_s2_ + observer_.estimate_m_s2();
  update_observer(sampc_command_, sampc_step_s_);
  // What SAMPC treats as the hover thrust (a - d along z): the emergency hover's thrust.
  ladder_.remember(inputs.state, sampc_input_.ugv.specific_force_m_s2.z(), output_.command,
                   sampc_step_s_);
}

void MissionController::update_observer(const model::Input& applied, double now_s) {
  if (params_.observer_window_s <= 0.0) return;
  // Only consecutive control steps describe the model's prediction of one period.
  const bool consecutive =
      observer_time_s_ >= 0.0 && std::abs(now_s - observer_time_s_ - params_.control_period_s) <
                                     0.5 * params_.control_period_s;
  if (!consecutive) observer_.reset();
  observer_.update(sampc_input_.uav_state, sampc_input_.ugv, applied);
  observer_time_s_ = now_s;
}

void MissionController::integrate_disturbance(const Eigen::Vector3d& position_m,
                                              const Eigen::Vector3d& reference_m) {
  // At the transition stage (xy-z-ref) the horizontal position is not tracked: there is no
  // horizontal error to integrate, only the height.
  const bool tracks_xy = sampc::reference_mode_for(sampc_.params().mode, sampc_input_.stage) ==
                         sampc::ReferenceMode::XyzRef;
  Eigen::Vector3d error = (position_m - reference_m)
                              .cwiseMax(-params_.integral_error_clip_m)
                              .cwiseMin(params_.integral_error_clip_m);
  if (!tracks_xy) error.head<2>().setZero();
  // Below the point (error < 0) the model must learn of a downward pull: d decreases.
  disturbance_m_s2_ += params_.integral_gain_1_s3 * params_.control_period_s * error;
  disturbance_m_s2_ = disturbance_m_s2_.cwiseMax(-params_.integral_limit_m_s2)
                          .cwiseMin(params_.integral_limit_m_s2);
}

void MissionController::idle(Failsafe reason) {
  output_.command.thrust_m_s2 = 0.0;
  output_.command.body_rate_rad_s.setZero();
  output_.command.armed = false;
  output_.status.failsafe = reason;
  output_.status.stage = machine_.decision();
}

}  // namespace cover::mission
