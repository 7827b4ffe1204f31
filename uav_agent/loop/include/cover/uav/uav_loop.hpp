#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "cover/mission/mission_controller.hpp"
#include "cover/uav/controller_config.hpp"
#include "cover/uav/uav_io.hpp"
#include "cover/vocabulary/task.hpp"

namespace cover::uav {

struct TaskDecision {
  bool accepted = false;
  std::string reason;  // why not, or a one-line summary of the accepted task
};

// The UAV's control loop, hosted by the in-process harness and by the DDS agent alike:
// each step it pulls the inputs of the UGVs its task names, steps the MissionController
// and pushes the command. It owns the task's lifetime: a task is accepted when none runs
// (none yet, or the last one ended), replaced then, and can be aborted at run time.
// Never throws after construction; without a task it commands the motors off.
class UavLoop {
 public:
  // Throws config::ConfigError when a parameter is invalid. `plan_clock`: whether a step
  // waits for a plan due at it (lockstep: simulated time, the harness and a lockstep agent)
  // or flies on (realtime); see mission::PlanClock.
  UavLoop(std::uint32_t uav_id, int ugv_count, ControllerConfig config,
          mission::PlanClock plan_clock = mission::PlanClock::Lockstep);

  // Rejects (with the reason) a task for another UAV, an invalid one, or any task while
  // one is running.
  TaskDecision give_task(const mission::Task& task);
  // Aborts the running task (MissionController::abort); false when none runs.
  bool abort(double now_s);
  // The autopilot stopped flying COVER's setpoints, or flies them again
  // (MissionController::yield_to_autopilot / take_back); no-ops without a task.
  void yield_to_autopilot(double now_s);
  void take_back(double now_s);

  // One control step: the inputs, the controller's step, the command to `output`, then
  // (the command out) SAMPC's preparation of the next step, so that a measurement waits for
  // the feedback phase only (MissionController::prepare_next_step).
  const mission::ControllerOutput& step(double now_s, UavInputs& inputs, CommandOutput& output);
  // Just before the next step's measurement is due: warms the caches for its feedback
  // (MissionController::rehearse_feedback). Changes no result; a no-op without a task.
  void rehearse() {
    if (controller_) controller_->rehearse_feedback();
  }

  bool has_task() const { return controller_.has_value(); }
  // The task being flown (or the last one); nullptr before the first.
  const mission::Task* task() const;
  // NotStarted when there is no task.
  mission::MissionState task_state() const;
  const mission::MissionController* controller() const;
  const mission::ControllerOutput& output() const;
  // The stage machine's one-line status, or "no task".
  std::string describe() const;
  std::uint32_t uav_id() const { return uav_id_; }
  int ugv_count() const { return ugv_count_; }
  const ControllerConfig& config() const { return config_; }

 private:
  void feed_inputs(UavInputs& inputs);

  std::uint32_t uav_id_;
  int ugv_count_;
  ControllerConfig config_;
  mission::PlanClock plan_clock_;
  std::optional<mission::MissionController> controller_;
  std::vector<int> task_ugvs_;          // the UGVs the task names, each once
  std::vector<double> state_stamps_s_;  // stamp of the last relative state per UGV
  mission::ControllerOutput idle_output_;
};

}  // namespace cover::uav
