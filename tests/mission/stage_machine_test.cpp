#include <gtest/gtest.h>

#include <limits>

#include "cover/mission/stage_machine.hpp"
#include "cover/mission/task_file.hpp"

using cover::mission::FailureReason;
using cover::mission::FinalAction;
using cover::mission::MissionParams;
using cover::mission::MissionState;
using cover::mission::StageMachine;
using cover::mission::Task;
using cover::mission::TransitionProcess;
using cover::model::Stage;
using Eigen::Vector3d;

namespace {

TransitionProcess process(int from, int to, FinalAction action, double final_z) {
  TransitionProcess p;
  p.from_ugv = from;
  p.to_ugv = to;
  p.initial_point_m = Vector3d(0, 0, 1.5);
  p.transition_point_m = Vector3d(0, 0, 1.4);
  p.final_point_m = Vector3d(0.1, 0, final_z);
  p.final_action = action;
  return p;
}

Task deliver_then_land() {
  Task task;
  task.task_id = "deliver-land";
  task.processes = {process(0, 1, FinalAction::Deliver, 0.25),
                    process(1, 0, FinalAction::Land, 0.05)};
  cover::mission::validate_task(task, 2);
  return task;
}

const Vector3d kStill = Vector3d::Zero();
const Vector3d kFar(3.0, 0.0, 1.0);

}  // namespace

TEST(StageMachine, FirstUpdateStartsInitialStageInTheSourceFrame) {
  StageMachine machine(deliver_then_land(), MissionParams{});
  EXPECT_EQ(machine.decision().state, MissionState::NotStarted);
  const auto& d = machine.update(0.0, kFar, kStill);
  EXPECT_EQ(d.state, MissionState::Running);
  EXPECT_EQ(d.stage, Stage::Initial);
  EXPECT_EQ(d.reference_ugv, 0);
  EXPECT_TRUE(d.stage_started);
  EXPECT_EQ(d.target_point_m, Vector3d(0, 0, 1.5));
  EXPECT_FALSE(machine.update(0.01, kFar, kStill).stage_started);  // plan only once
}

TEST(StageMachine, WalksAllStagesWithFrameSwitchAndFinalActions) {
  StageMachine machine(deliver_then_land(), MissionParams{});
  double t = 0.0;
  machine.update(t, kFar, kStill);
  // Reaching each stage point (at rest) ends the stage; the next one starts at once.
  auto arrive = [&](const Vector3d& at) { return machine.update(t += 0.01, at, kStill); };

  auto d = arrive(Vector3d(0, 0, 1.5));
  EXPECT_EQ(d.stage, Stage::Transition);
  EXPECT_EQ(d.reference_ugv, 1);  // the frame switches at the transition stage
  EXPECT_TRUE(d.stage_started);
  EXPECT_DOUBLE_EQ(d.stage_time_s, 0.0);

  d = arrive(Vector3d(0, 0, 1.4));
  EXPECT_EQ(d.stage, Stage::Final);
  EXPECT_EQ(d.reference_ugv, 1);

  d = arrive(Vector3d(0.1, 0, 0.25));
  EXPECT_TRUE(d.release_payload);
  EXPECT_TRUE(d.payload_released);
  EXPECT_EQ(d.process_index, 1u);
  EXPECT_EQ(d.stage, Stage::Initial);
  EXPECT_EQ(d.reference_ugv, 1);  // the second process starts where the first ended

  d = arrive(Vector3d(0, 0, 1.5));
  EXPECT_FALSE(d.release_payload);  // a one-step event
  EXPECT_TRUE(d.payload_released);  // latched
  EXPECT_EQ(d.reference_ugv, 0);
  d = arrive(Vector3d(0, 0, 1.4));
  EXPECT_EQ(d.stage, Stage::Final);
  EXPECT_TRUE(d.armed);
  d = arrive(Vector3d(0.1, 0, 0.05));
  EXPECT_EQ(d.state, MissionState::Complete);
  EXPECT_FALSE(d.armed);  // land: disarm at the point
}

TEST(StageMachine, StageNeedsBothPositionAndLowSpeed) {
  StageMachine machine(deliver_then_land(), MissionParams{});
  machine.update(0.0, kFar, kStill);
  // At the point but too fast: stays.
  EXPECT_EQ(machine.update(0.01, Vector3d(0, 0, 1.5), Vector3d(0.5, 0, 0)).stage, Stage::Initial);
  // Inside the 0.15 m tolerance and slow: ends.
  EXPECT_EQ(machine.update(0.02, Vector3d(0.1, 0, 1.5), Vector3d(0.2, 0, 0)).stage,
            Stage::Transition);
}

TEST(StageMachine, FinalActionUsesTheTighterTolerance) {
  Task task;
  task.processes = {process(0, 1, FinalAction::Land, 0.05)};
  StageMachine machine(task, MissionParams{});
  double t = 0.0;
  machine.update(t, kFar, kStill);
  machine.update(t += 0.01, Vector3d(0, 0, 1.5), kStill);
  machine.update(t += 0.01, Vector3d(0, 0, 1.4), kStill);
  // 0.1 m off the landing point: within reach tolerance but not within action tolerance.
  EXPECT_EQ(machine.update(t += 0.01, Vector3d(0.2, 0, 0.05), kStill).state, MissionState::Running);
  EXPECT_EQ(machine.update(t += 0.01, Vector3d(0.12, 0, 0.06), kStill).state,
            MissionState::Complete);
}

TEST(StageMachine, NoActionTaskCompletesAndStaysArmed) {
  Task task;
  task.processes = {process(0, 1, FinalAction::None, 0.3)};
  StageMachine machine(task, MissionParams{});
  double t = 0.0;
  machine.update(t, kFar, kStill);
  machine.update(t += 0.01, Vector3d(0, 0, 1.5), kStill);
  machine.update(t += 0.01, Vector3d(0, 0, 1.4), kStill);
  const auto& d = machine.update(t += 0.01, Vector3d(0.1, 0, 0.3), kStill);
  EXPECT_EQ(d.state, MissionState::Complete);
  EXPECT_TRUE(d.armed);
  EXPECT_EQ(d.reference_ugv, 1);
}

TEST(StageMachine, StageTimeoutFailsWithClearStatus) {
  MissionParams params;
  params.transition_timeout_s = 5.0;
  StageMachine machine(deliver_then_land(), params);
  machine.update(0.0, kFar, kStill);
  machine.update(1.0, Vector3d(0, 0, 1.5), kStill);  // transition starts at t = 1
  EXPECT_EQ(machine.update(5.9, kFar, kStill).state, MissionState::Running);
  const auto& d = machine.update(6.1, kFar, kStill);
  EXPECT_EQ(d.state, MissionState::Failed);
  EXPECT_EQ(d.failure, FailureReason::StageTimeout);
  const std::string text = machine.describe();
  EXPECT_NE(text.find("transition stage"), std::string::npos) << text;
  EXPECT_NE(text.find("stage-timeout"), std::string::npos) << text;
  EXPECT_NE(text.find("G0->G1"), std::string::npos) << text;
  // A failed mission stays failed: reaching points does nothing any more.
  EXPECT_EQ(machine.update(6.2, Vector3d(0, 0, 1.4), kStill).state, MissionState::Failed);
}

TEST(StageMachine, NaNStateFailsInsteadOfPropagating) {
  StageMachine machine(deliver_then_land(), MissionParams{});
  machine.update(0.0, kFar, kStill);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto& d = machine.update(0.01, Vector3d(nan, 0, 1), kStill);
  EXPECT_EQ(d.state, MissionState::Failed);
  EXPECT_EQ(d.failure, FailureReason::InvalidState);
  EXPECT_TRUE(d.target_point_m.allFinite());
}

TEST(StageMachine, CallerReportedFailureIsKept) {
  StageMachine machine(deliver_then_land(), MissionParams{});
  machine.update(0.0, kFar, kStill);
  machine.fail(FailureReason::StaleInput, 0.5);
  EXPECT_EQ(machine.decision().failure, FailureReason::StaleInput);
  machine.fail(FailureReason::PlanningFailed, 0.6);  // the first reason wins
  EXPECT_EQ(machine.decision().failure, FailureReason::StaleInput);
}
