#include "cover/uav/uav_loop.hpp"

#include <algorithm>
#include <chrono>
#include <utility>

#include "cover/config/config_error.hpp"

namespace cover::uav {

namespace {

std::string summary(const mission::Task& task) {
  std::string text = "task '" + task.task_id + "': " + std::to_string(task.processes.size()) +
                     " process(es), G" + std::to_string(task.processes.front().from_ugv);
  for (const mission::TransitionProcess& p : task.processes) {
    text += " -> G" + std::to_string(p.to_ugv);
  }
  return text;
}

}  // namespace

UavLoop::UavLoop(std::uint32_t uav_id, int ugv_count, ControllerConfig config,
                 mission::PlanClock plan_clock)
    : uav_id_(uav_id),
      ugv_count_(ugv_count),
      config_(std::move(config)),
      plan_clock_(plan_clock),
      state_stamps_s_(static_cast<std::size_t>(std::max(ugv_count, 0)), 0.0) {
  config::check(ugv_count >= 1, "uav_loop.ugv_count", "must be >= 1");
  config_.validate();
  idle_output_.status.failsafe = mission::Failsafe::WaitingForInputs;
}

TaskDecision UavLoop::give_task(const mission::Task& task) {
  if (task.uav_id < 0 || static_cast<std::uint32_t>(task.uav_id) != uav_id_) {
    return {false, "task '" + task.task_id + "' is for UAV " + std::to_string(task.uav_id) +
                       ", this is UAV " + std::to_string(uav_id_)};
  }
  if (controller_ && !mission::is_terminal(task_state())) {
    return {false, "task '" + controller_->stage_machine().task().task_id +
                       "' is still running (abort it first)"};
  }
  // A failed task's emergency landing owns the motors until it has disarmed.
  const mission::Failsafe failsafe = output().status.failsafe;
  if (failsafe == mission::Failsafe::EmergencyHover ||
      failsafe == mission::Failsafe::EmergencyLanding) {
    return {false, std::string("the UAV is in its failsafe (") + mission::to_string(failsafe) +
                       "): no task until it has landed"};
  }
  try {
    controller_.emplace(task, ugv_count_, config_.mission, config_.planner, config_.sampc,
                        plan_clock_);
  } catch (const config::ConfigError& e) {
    return {false, e.what()};
  }
  task_ugvs_ = task.ugvs();
  return {true, summary(task)};
}

bool UavLoop::abort(double now_s) {
  return controller_ && controller_->abort(now_s);
}

void UavLoop::yield_to_autopilot(double now_s) {
  if (controller_) controller_->yield_to_autopilot(now_s);
}

void UavLoop::take_back(double now_s) {
  if (controller_) controller_->take_back(now_s);
}

const mission::ControllerOutput& UavLoop::step(double now_s, UavInputs& inputs,
                                               CommandOutput& output) {
  StepOutput step;
  step.uav_id = uav_id_;
  step.stamp_s = now_s;
  if (controller_) {
    // Measurement -> command: from taking the inputs to the command handed to the output.
    const auto measured = std::chrono::steady_clock::now();
    feed_inputs(inputs);
    controller_->step(now_s);
    controller_->set_command_time_us(
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - measured)
            .count());
    step.measurement_stamp_s = state_stamps_s_[controller_->stage_machine().reference_ugv()];
  }
  step.output = &this->output();
  output.write(step);
  // The command is out: SAMPC prepares the next step before its measurement arrives.
  if (controller_) controller_->prepare_next_step();
  return *step.output;
}

void UavLoop::feed_inputs(UavInputs& inputs) {
  mission::RelativeMeasurement state;
  mission::UgvImuMeasurement imu;
  for (const int k : task_ugvs_) {
    if (inputs.relative_state(k, state)) {
      controller_->set_relative_state(k, state);
      state_stamps_s_[k] = state.stamp_s;
    }
    if (inputs.ugv_imu(k, imu)) controller_->set_ugv_imu(k, imu);
  }
}

const mission::Task* UavLoop::task() const {
  return controller_ ? &controller_->stage_machine().task() : nullptr;
}

mission::MissionState UavLoop::task_state() const {
  return controller_ ? controller_->stage_machine().decision().state
                     : mission::MissionState::NotStarted;
}

const mission::MissionController* UavLoop::controller() const {
  return controller_ ? &*controller_ : nullptr;
}

const mission::ControllerOutput& UavLoop::output() const {
  return controller_ ? controller_->output() : idle_output_;
}

std::string UavLoop::describe() const {
  return controller_ ? controller_->stage_machine().describe() : "no task";
}

}  // namespace cover::uav
