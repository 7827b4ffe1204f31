#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "cover/mission/disturbance_observer.hpp"
#include "cover/mission/failsafe_ladder.hpp"
#include "cover/mission/mission_params.hpp"
#include "cover/mission/plan_worker.hpp"
#include "cover/mission/stage_machine.hpp"
#include "cover/planner/planner_params.hpp"
#include "cover/planner/trajectory.hpp"
#include "cover/sampc/sampc.hpp"
#include "cover/vocabulary/control_command.hpp"
#include "cover/vocabulary/controller_input.hpp"
#include "cover/vocabulary/controller_output.hpp"
#include "cover/vocabulary/failsafe.hpp"
#include "cover/vocabulary/relative_state.hpp"
#include "cover/vocabulary/task.hpp"
#include "cover/vocabulary/ugv_motion.hpp"

namespace cover::mission {

// What the UAV agent (later a DDS adapter) and the benchmarks call at 100 Hz. Holds the
// latest relative state and UGV IMU per UGV, runs the stage machine, plans each stage's
// reference at its start (eq. 23 at the transition stage, except for coni-mpc), feeds
// SAMPC the horizon reference and returns the command with a status. Never throws after
// construction and never outputs NaN: stale or invalid inputs give a hover command.
// Stage plans run on a PlanWorker's thread and are flown from a fixed later step
// (MissionParams::plan_adopt_steps, PlanClock); a step never runs the optimiser.
// The method (a sampc::kModes name) is SAMPC's `mode`, or the process's own `method` while
// that process is flown.
class MissionController {
 public:
  // Throws config::ConfigError when the task or a parameter set is invalid.
  // `clock`: what the adoption step does when its plan is not ready (wait in lockstep, fly
  // on in realtime). `plan`: what plans (tests put a slow or gated function here; default
  // the StagePlanner on `planner`).
  MissionController(Task task, int ugv_count, MissionParams mission, planner::PlannerParams planner,
                    sampc::SampcParams sampc, PlanClock clock = PlanClock::Lockstep,
                    PlanWorker::PlanFunction plan = {});
  MissionController(const MissionController&) = delete;
  MissionController& operator=(const MissionController&) = delete;

  // Inputs for an unknown UGV index are ignored (counted in `ignored_inputs()`).
  void set_relative_state(int ugv, const RelativeMeasurement& measurement);
  void set_ugv_imu(int ugv, const UgvImuMeasurement& measurement);

  // One control step at time `now_s` (same clock as the measurement stamps): the command
  // from the measurement. With a preparation waiting for this step (prepare_next_step) SAMPC
  // runs its feedback phase only; else (the first step, a new reference, a frame switch, a
  // step out of time) it prepares here too.
  const ControllerOutput& step(double now_s);

  // After the step's command is out: the step's bookkeeping on its measurement (tracking
  // integral, observer, failsafe memory), then SAMPC's preparation for the next step (at
  // now_s + control period) on the state predicted from this measurement and command, so
  // that the next step's measurement -> command is the feedback phase (real-time
  // iteration). A no-op after a step that flew no SAMPC command. Allocation-free.
  void prepare_next_step();
  // Between prepare_next_step and the next step: runs the waiting preparation's feedback on
  // the predicted state and discards it (Sampc::rehearse_feedback), so that the step's
  // feedback finds its data and code in the caches. Changes no result. Only while SAMPC
  // flies: after a step of the failsafe ladder nothing is prepared for the next.
  void rehearse_feedback() {
    if (rehearsal_due_) sampc_.rehearse_feedback();
  }

  // The wall time from the step taking its measurements to its command (the host measures
  // it around feeding the inputs and step()): reported in the status of this step.
  void set_command_time_us(double us) { output_.status.command_us = us; }

  // Ends the task on the operator's request: the next steps hold the point where the UAV
  // is, in its current reference frame, then MissionParams::abort_action. False when the
  // task had already ended.
  bool abort(double now_s);

  // The flight controller no longer flies COVER's setpoints (a pilot switched its mode, its
  // own failsafe, its link lost): the task fails with FailureReason::AutopilotControl, and
  // until take_back() the controller neither plans nor integrates its observers (a hand-back
  // must not start from state wound up against a vehicle it was not flying). Meanwhile it
  // commands a level hover on its hover thrust: what a pilot switching back gets first.
  void yield_to_autopilot(double now_s);
  // COVER's setpoints fly the UAV again: hold the point where it is, in the current frame,
  // with SAMPC's frame and the observers started afresh.
  void take_back(double now_s);
  bool yielded() const { return yielded_; }

  const ControllerOutput& output() const { return output_; }
  const StageMachine& stage_machine() const { return machine_; }
  // The last adopted plan (while the reference coasts before the first, the default one).
  const planner::Trajectory& reference_trajectory() const { return trajectory_; }
  // A plan requested and not adopted yet.
  bool plan_in_flight() const { return plan_request_id_ != 0; }
  // A step is blocked waiting for its plan (lockstep), as another thread sees it.
  bool waiting_for_plan() const { return plan_worker_.waiting(); }
  PlanClock plan_clock() const { return plan_clock_; }
  // When reference_trajectory()'s t = 0 was (same clock as step's now_s).
  double reference_start_s() const { return stage_start_s_; }
  int ignored_inputs() const { return ignored_inputs_; }
  // The method of the process being flown (its own, else SAMPC's configured mode).
  sampc::Mode method() const { return sampc_.params().mode; }
  // SAMPC's last cost: the intercept law's fallback reason and time to go are in it.
  const sampc::HorizonCost& horizon_cost() const { return sampc_.horizon_cost(); }

 private:
  struct UgvInputs {
    bool has_state = false;
    bool has_imu = false;
    RelativeMeasurement state;
    UgvImuMeasurement imu;
  };

  InputHealth input_health(int ugv, double now_s) const;
  // Every UGV of the task (each process's from and to) has fresh, valid inputs.
  bool task_inputs_healthy(double now_s) const;
  bool not_flying_step(double now_s);
  bool emergency_step(int reference, double now_s);
  void switch_frame(int reference);
  void report_degraded_flight(const StageDecision& decision);
  void need_plan();
  void advance_plan(double now_s);
  void request_plan(double now_s);
  void adopt_plan(double now_s);
  planner::StageProblem stage_problem() const;
  void fill_reference(double t_s, sampc::HorizonReference& reference) const;
  void command_from_sampc(const UgvInputs& inputs, double now_s);
  bool flies_radial_approach() const;
  void fill_approach(const Eigen::Vector3d& position_m, const Eigen::Vector3d& velocity_m_s,
                     const Eigen::Vector3d& ugv_angular_velocity_rad_s, double stage_time_s);
  // SAMPC's input for time now_s from the UAV state `uav_state` (measured or predicted):
  // stage, reference, UGV motion with the disturbance estimate taken off.
  void fill_sampc_input(const UgvInputs& inputs, const model::UavState& uav_state, double now_s);
  bool preparation_is_for(double now_s) const;
  void finish_sampc_step();
  void integrate_disturbance(const Eigen::Vector3d& position_m, const Eigen::Vector3d& reference_m);
  void update_observer(const model::Input& applied, double now_s);
  void use_process_method(std::size_t process_index);
  void hold_current_point(double now_s);
  void run_abort_action(const RelativeMeasurement& state, double now_s);
  void idle(Failsafe reason);

  MissionParams params_;
  int ugv_count_;
  StageMachine machine_;
  sampc::Sampc sampc_;
  // The method of each process: its own, else SAMPC's configured mode.
  std::vector<sampc::Mode> process_modes_;
  std::vector<int> task_ugvs_;  // Task::ugvs(), once: the step does not allocate
  std::vector<UgvInputs> inputs_;
  planner::Trajectory trajectory_;
  double stage_start_s_ = 0.0;
  int last_reference_ugv_ = -1;
  bool plan_pending_ = false;  // the stage has no usable plan yet
  int plan_attempts_ = 0;
  // Off-thread planning: the request in flight (0: none), its time origin and the time of
  // its adoption step; the slot its result is swapped into (no allocation here).
  PlanClock plan_clock_;
  std::uint64_t plan_request_id_ = 0;
  double plan_request_s_ = 0.0;
  double plan_adopt_at_s_ = 0.0;
  planner::PlanResult adopted_;
  // Until a new stage's plan is adopted the reference coasts from the state at its request
  // (the plan's own first-order start): the previous reference ended at the previous
  // stage's point, often in another frame.
  bool coast_on_request_ = false;
  bool coasting_ = false;
  Eigen::Vector3d coast_position_m_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d coast_velocity_m_s_ = Eigen::Vector3d::Zero();
  bool holding_ = false;  // mission failed or aborted: hold the position where it ended
  double abort_time_s_ = 0.0;
  bool descending_ = false;          // the abort's landing descent is under way
  double touchdown_since_s_ = -1.0;  // land detector: held up since then, < 0: not
  bool disarmed_after_abort_ = false;
  bool yielded_ = false;  // the autopilot does not fly our setpoints (yield_to_autopilot)
  int ignored_inputs_ = 0;
  // Integral estimate of the acceleration SAMPC's model misses, in the reference frame.
  Eigen::Vector3d disturbance_m_s2_ = Eigen::Vector3d::Zero();
  // Velocity-based estimate of the same (see DisturbanceObserver); fed only by consecutive
  // SAMPC steps in one frame.
  DisturbanceObserver observer_;
  double observer_time_s_ = -1.0;  // time of its last update, < 0: none
  FailsafeLadder ladder_;
  sampc::SampcInput sampc_input_;
  // The reference's source (plan, coast, hold, descent, frame) changes bump the epoch: a
  // preparation made under another epoch, or for another time, is not this step's.
  std::uint64_t reference_epoch_ = 0;
  std::uint64_t prepared_epoch_ = 0;
  double prepared_for_s_ = -1.0;  // the step time the waiting preparation is for, < 0: none
  bool rehearsal_due_ = false;    // prepare_next_step prepared SAMPC for the coming step
  bool sampc_stepped_ = false;    // this step's command is SAMPC's: prepare_next_step works
  double sampc_step_s_ = 0.0;     // that step's time
  model::Input sampc_command_ = model::hover_input();  // and its command
  UgvInputs sampc_inputs_;                             // and its reference frame's inputs
  ControllerOutput output_;
  // Last: its thread starts once everything it may be handed exists, and it is joined first.
  PlanWorker plan_worker_;
};

}  // namespace cover::mission
