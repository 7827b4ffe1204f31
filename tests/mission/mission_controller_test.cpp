#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "cover/mission/mission_controller.hpp"
#include "cover/mission/task_file.hpp"
#include "cover/uav/controller_config.hpp"
#include "cover/uav/uav_loop.hpp"

using cover::mission::Failsafe;
using cover::mission::FailureReason;
using cover::mission::MissionController;
using cover::mission::MissionState;
using cover::mission::RelativeMeasurement;
using cover::mission::UgvImuMeasurement;

namespace {

MissionController make_controller() {
  const auto config = cover::uav::ControllerConfig::load_default(cover::sampc::Mode::Cover);
  const cover::mission::Task task = cover::mission::load_task_file(
      cover::config::default_config_dir() + "/tasks/scenario2.yaml", 2);
  return MissionController(task, 2, config.mission, config.planner, config.sampc);
}

// The UAV resting on both decks' origins, both UGVs at rest: a valid input set at `t`.
void feed_at_rest(MissionController& controller, double t) {
  for (int k = 0; k < 2; ++k) {
    RelativeMeasurement state;
    state.stamp_s = t;
    controller.set_relative_state(k, state);
    UgvImuMeasurement imu;
    imu.stamp_s = t;
    controller.set_ugv_imu(k, imu);
  }
}

void expect_finite(const cover::mission::ControlCommand& command) {
  EXPECT_TRUE(std::isfinite(command.thrust_m_s2));
  EXPECT_TRUE(command.body_rate_rad_s.allFinite());
}

}  // namespace

TEST(MissionController, StaysIdleAndDisarmedUntilInputsArrive) {
  MissionController controller = make_controller();
  const auto& out = controller.step(0.0);
  EXPECT_FALSE(out.command.armed);
  EXPECT_EQ(out.command.thrust_m_s2, 0.0);
  EXPECT_EQ(out.status.failsafe, Failsafe::WaitingForInputs);
  EXPECT_EQ(out.status.stage.state, MissionState::NotStarted);
}

// The start deck's inputs alone do not start the task: the UGV it flies to must be heard
// too (an agent late to discover it would take off toward a frame it cannot fly in).
TEST(MissionController, WaitsOnTheDeckUntilEveryUgvOfTheTaskIsHeard) {
  MissionController controller = make_controller();
  RelativeMeasurement state;
  state.stamp_s = 0.0;
  UgvImuMeasurement imu;
  imu.stamp_s = 0.0;
  controller.set_relative_state(0, state);
  controller.set_ugv_imu(0, imu);
  controller.set_relative_state(1, state);  // G1's state, not its IMU
  const auto& waiting = controller.step(0.0);
  EXPECT_FALSE(waiting.command.armed);
  EXPECT_EQ(waiting.status.failsafe, Failsafe::WaitingForInputs);
  EXPECT_EQ(waiting.status.stage.state, MissionState::NotStarted);
  feed_at_rest(controller, 0.01);
  const auto& started = controller.step(0.01);
  EXPECT_TRUE(started.command.armed);
  EXPECT_EQ(started.status.stage.state, MissionState::Running);
}

TEST(MissionController, StartsTheTaskAndPlansTheFirstStage) {
  MissionController controller = make_controller();
  ASSERT_EQ(controller.plan_clock(), cover::mission::PlanClock::Lockstep);
  feed_at_rest(controller, 0.0);
  const auto& out = controller.step(0.0);
  EXPECT_TRUE(out.command.armed);
  // Requested in this step, flown from the next (plan_adopt_steps 1): meanwhile the
  // reference coasts from where the UAV rests.
  EXPECT_FALSE(out.status.planned);
  EXPECT_TRUE(controller.plan_in_flight());
  EXPECT_TRUE(out.status.reference_position_m.isZero());
  EXPECT_EQ(out.status.failsafe, Failsafe::None);
  EXPECT_EQ(out.status.stage.state, MissionState::Running);
  EXPECT_EQ(out.status.stage.reference_ugv, 0);
  expect_finite(out.command);
  feed_at_rest(controller, 0.01);
  const auto& next = controller.step(0.01);
  EXPECT_TRUE(next.status.planned);
  EXPECT_FALSE(controller.plan_in_flight());
  EXPECT_EQ(next.status.plan_late_steps, 0);
  EXPECT_DOUBLE_EQ(controller.reference_start_s(), 0.0);  // the plan's time origin: its request
  // Taking off towards [0, 0, 1]: more than hover thrust.
  EXPECT_GT(next.command.thrust_m_s2, cover::model::kGravity_m_s2);
  EXPECT_DOUBLE_EQ(controller.reference_trajectory().position(1e9).z(), 1.0);
}

TEST(MissionController, StaleInputsHoverThenLandAndFailTheMission) {
  MissionController controller = make_controller();
  feed_at_rest(controller, 0.0);
  controller.step(0.0);
  const auto& stale = controller.step(0.2);  // inputs 0.2 s old (> 0.1 s)
  EXPECT_EQ(stale.status.failsafe, Failsafe::EmergencyHover);
  EXPECT_EQ(stale.status.failsafe_cause, cover::mission::FailsafeCause::StateStale);
  EXPECT_NEAR(stale.status.failsafe_input_age_s, 0.2, 1e-9);
  EXPECT_TRUE(stale.command.armed);
  EXPECT_TRUE(stale.command.body_rate_rad_s.isZero());  // level already
  EXPECT_EQ(stale.status.stage.state, MissionState::Running);
  const auto& landing = controller.step(1.25);  // 1.05 s in the hover (> 1.0 s)
  EXPECT_EQ(landing.status.failsafe, Failsafe::EmergencyLanding);
  EXPECT_EQ(landing.status.stage.state, MissionState::Failed);
  EXPECT_EQ(landing.status.stage.failure, FailureReason::StaleInput);
  // Fresh inputs again: the landing is latched (the task has failed), not a silent return.
  feed_at_rest(controller, 1.26);
  const auto& still = controller.step(1.26);
  EXPECT_EQ(still.status.failsafe, Failsafe::EmergencyLanding);
  expect_finite(still.command);
}

TEST(MissionController, InputsBackDuringTheHoverResumeTheStageReplanned) {
  MissionController controller = make_controller();
  feed_at_rest(controller, 0.0);
  controller.step(0.0);
  EXPECT_EQ(controller.step(0.3).status.failsafe, Failsafe::EmergencyHover);
  feed_at_rest(controller, 0.6);
  const auto& back = controller.step(0.6);
  EXPECT_EQ(back.status.failsafe, Failsafe::None);
  EXPECT_TRUE(controller.plan_in_flight());
  EXPECT_EQ(back.status.stage.state, MissionState::Running);
  feed_at_rest(controller, 0.61);
  EXPECT_TRUE(controller.step(0.61).status.planned);
  EXPECT_DOUBLE_EQ(controller.reference_start_s(), 0.6);
}

TEST(MissionController, AnAbortInterruptedByTheHoverHoldsTheNewPointAndLandsAgain) {
  MissionController controller = make_controller();
  feed_at_rest(controller, 0.0);
  controller.step(0.0);
  ASSERT_TRUE(controller.abort(0.01));
  feed_at_rest(controller, 0.01);
  controller.step(0.01);
  EXPECT_EQ(controller.step(0.3).status.failsafe, Failsafe::EmergencyHover);
  RelativeMeasurement moved;
  moved.stamp_s = 0.6;
  moved.position_m = Eigen::Vector3d(0.4, -0.2, 0.8);
  controller.set_relative_state(0, moved);
  UgvImuMeasurement imu;
  imu.stamp_s = 0.6;
  controller.set_ugv_imu(0, imu);
  const auto& back = controller.step(0.6);
  EXPECT_EQ(back.status.failsafe, Failsafe::Aborted);
  EXPECT_EQ(back.status.stage.state, MissionState::Aborted);
  EXPECT_TRUE(controller.reference_trajectory().position(0.0).isApprox(moved.position_m));
  EXPECT_FALSE(back.status.planned);  // no stage plan for a task that has ended
}

// The loop's inputs: the UAV at rest on both decks, stamped when the test says.
struct AtRest : cover::uav::UavInputs {
  double stamp_s = 0.0;
  bool relative_state(int, RelativeMeasurement& out) override {
    out = RelativeMeasurement{};
    out.stamp_s = stamp_s;
    return true;
  }
  bool ugv_imu(int, UgvImuMeasurement& out) override {
    out = UgvImuMeasurement{};
    out.stamp_s = stamp_s;
    return true;
  }
};
struct Discard : cover::uav::CommandOutput {
  void write(const cover::uav::StepOutput&) override {}
};

TEST(UavLoop, RefusesANewTaskWhileAnEmergencyLandingHasTheMotors) {
  const auto config = cover::uav::ControllerConfig::load_default(cover::sampc::Mode::Cover);
  cover::uav::UavLoop loop(0, 2, config);
  cover::mission::Task task = cover::mission::load_task_file(
      cover::config::default_config_dir() + "/tasks/scenario2.yaml", 2);
  task.uav_id = 0;
  ASSERT_TRUE(loop.give_task(task).accepted);
  AtRest inputs;
  Discard out;
  loop.step(0.0, inputs, out);
  inputs.stamp_s = -100.0;  // nothing fresh from now on
  loop.step(0.3, inputs, out);
  EXPECT_EQ(loop.step(1.4, inputs, out).status.failsafe, Failsafe::EmergencyLanding);
  EXPECT_EQ(loop.task_state(), MissionState::Failed);
  task.task_id = "next";
  const auto decision = loop.give_task(task);
  EXPECT_FALSE(decision.accepted);
  EXPECT_NE(decision.reason.find("emergency-landing"), std::string::npos) << decision.reason;
}

TEST(MissionController, StaleImuIsHeldBrieflyThenHovers) {
  MissionController controller = make_controller();
  feed_at_rest(controller, 0.0);
  controller.step(0.0);
  RelativeMeasurement state;
  state.stamp_s = 0.15;
  controller.set_relative_state(0, state);
  const auto& held = controller.step(0.15);  // IMU 0.15 s old: within 0.1 + 0.1
  EXPECT_EQ(held.status.failsafe, Failsafe::ImuHold);
  EXPECT_EQ(held.status.failsafe_cause, cover::mission::FailsafeCause::ImuStale);
  state.stamp_s = 0.25;
  controller.set_relative_state(0, state);
  EXPECT_EQ(controller.step(0.25).status.failsafe, Failsafe::EmergencyHover);
}

TEST(MissionController, NonFiniteStateNeverReachesTheCommand) {
  MissionController controller = make_controller();
  feed_at_rest(controller, 0.0);
  controller.step(0.0);
  RelativeMeasurement bad;
  bad.stamp_s = 0.01;
  bad.position_m.x() = std::numeric_limits<double>::quiet_NaN();
  controller.set_relative_state(0, bad);
  UgvImuMeasurement imu;
  imu.stamp_s = 0.01;
  imu.motion.angular_velocity_rad_s.z() = std::numeric_limits<double>::infinity();
  controller.set_ugv_imu(0, imu);
  const auto& out = controller.step(0.01);
  EXPECT_EQ(out.status.failsafe, Failsafe::EmergencyHover);
  EXPECT_EQ(out.status.failsafe_cause, cover::mission::FailsafeCause::StateInvalid);
  expect_finite(out.command);
}

TEST(MissionController, IgnoresInputsForUnknownUgvs) {
  MissionController controller = make_controller();
  controller.set_relative_state(5, RelativeMeasurement{});
  controller.set_ugv_imu(-1, UgvImuMeasurement{});
  EXPECT_EQ(controller.ignored_inputs(), 2);
}

TEST(MissionController, RejectsAnInvalidTaskAtConstruction) {
  const auto config = cover::uav::ControllerConfig::load_default(cover::sampc::Mode::Cover);
  cover::mission::Task task;  // no process
  EXPECT_THROW(MissionController(task, 2, config.mission, config.planner, config.sampc),
               cover::config::ConfigError);
}

// A process's own method replaces the configured one while it is flown, allocation-free
// (SAMPC's set_mode); a process without one flies the configured method.
TEST(MissionController, FliesEachProcessWithItsOwnMethod) {
  const auto config = cover::uav::ControllerConfig::load_default(cover::sampc::Mode::Cover);
  cover::mission::Task task = cover::mission::load_task_file(
      cover::config::default_config_dir() + "/tasks/scenario2.yaml", 2);
  for (const char* method : {"intercept", "coni-mpc", ""}) {
    task.processes[0].method = method;
    MissionController controller(task, 2, config.mission, config.planner, config.sampc);
    EXPECT_EQ(controller.method(), cover::sampc::Mode::Cover);  // before the task starts
    feed_at_rest(controller, 0.0);
    controller.step(0.0);
    const auto expected = cover::sampc::parse_mode(method).value_or(cover::sampc::Mode::Cover);
    EXPECT_EQ(controller.method(), expected) << method;
  }
}

// The autopilot stops flying COVER's setpoints mid-flight (a pilot's RC switch, its link
// lost): the task fails at once, nothing is planned or integrated, a level hover is
// commanded; handed back, the controller holds where the UAV is, observers restarted.
TEST(MissionController, YieldingToTheAutopilotFailsTheTaskAndFreezesTheController) {
  MissionController controller = make_controller();
  feed_at_rest(controller, 0.0);
  controller.step(0.0);
  feed_at_rest(controller, 0.01);
  ASSERT_EQ(controller.step(0.01).status.stage.state, MissionState::Running);
  controller.yield_to_autopilot(0.02);
  EXPECT_TRUE(controller.yielded());
  for (double t = 0.02; t < 1.0; t += 0.01) {
    feed_at_rest(controller, t);
    const auto& out = controller.step(t);
    ASSERT_EQ(out.status.failsafe, Failsafe::AutopilotControl);
    ASSERT_EQ(out.status.stage.state, MissionState::Failed);
    ASSERT_EQ(out.status.stage.failure, FailureReason::AutopilotControl);
    ASSERT_FALSE(out.status.planned);
    ASSERT_EQ(out.status.solve_us, 0.0);  // SAMPC not stepped
    ASSERT_TRUE(out.command.armed);
    ASSERT_TRUE(out.command.body_rate_rad_s.isZero());
    ASSERT_GT(out.command.thrust_m_s2, 0.5 * cover::model::kGravity_m_s2);
    expect_finite(out.command);
  }
  controller.take_back(1.0);
  EXPECT_FALSE(controller.yielded());
  feed_at_rest(controller, 1.0);
  const auto& back = controller.step(1.0);
  EXPECT_EQ(back.status.stage.state, MissionState::Failed);  // the task stays failed
  EXPECT_NE(back.status.failsafe, Failsafe::AutopilotControl);
  EXPECT_TRUE(back.command.armed);
  expect_finite(back.command);
  // Holding the point where it was handed back (at rest on the deck here).
  const Eigen::Vector3d held = controller.reference_trajectory().position(0.0);
  EXPECT_NEAR(held.z(), 0.0, 0.2);
}
