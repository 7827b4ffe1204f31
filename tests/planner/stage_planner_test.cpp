#include "cover/planner/stage_planner.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "cover/config/yaml_reader.hpp"
#include "cover/planner/benchmark_problems.hpp"
#include "cover/planner/trajectory_metrics.hpp"

namespace cover::planner {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kBoundaryTolerance = 1e-6;

StageProblem make_problem(const Eigen::Vector3d& start, const Eigen::Vector3d& v0,
                          const Eigen::Vector3d& goal, double vmax = 1.0, double amax = 2.0) {
  StageProblem problem;
  problem.start_position_m = start;
  problem.start_velocity_m_s = v0;
  problem.goal_position_m = goal;
  problem.vmax_m_s = vmax;
  problem.amax_m_s2 = amax;
  return problem;
}

void expect_boundaries_met(const TrajectoryMetrics& m) {
  EXPECT_LT(m.start_position_error_m, kBoundaryTolerance);
  EXPECT_LT(m.start_velocity_error_m_s, kBoundaryTolerance);
  EXPECT_LT(m.start_acc_m_s2, kBoundaryTolerance);
  EXPECT_LT(m.end_position_error_m, kBoundaryTolerance);
  EXPECT_LT(m.end_speed_m_s, kBoundaryTolerance);
  EXPECT_LT(m.end_acc_m_s2, kBoundaryTolerance);
}

class StagePlannerTest : public ::testing::Test {
 protected:
  StagePlanner planner{PlannerParams::load_file(config::default_config_dir() + "/planner.yaml")};
};

TEST_F(StagePlannerTest, TypicalStageConvergesWithinLimits) {
  const auto problem = make_problem({5.0, 2.0, 1.0}, {0.5, 0.0, 0.0}, {0.0, 0.0, 1.5});
  const PlanResult result = planner.plan(problem);
  ASSERT_EQ(result.status, PlanStatus::Ok) << result.reason;
  EXPECT_GT(result.iterations, 0);
  const auto m = measure_trajectory(result.trajectory, problem);
  expect_boundaries_met(m);
  EXPECT_LT(m.speed_violation, 0.05);
  EXPECT_LT(m.acc_violation, 0.05);
  // Not dawdling: the straight distance is ~5.5 m at 1 m/s.
  EXPECT_LT(m.duration_s, 2.0 * 5.5 / problem.vmax_m_s);
  EXPECT_GT(m.max_speed_m_s, 0.7 * problem.vmax_m_s);
}

// Deliverable check: boundary conditions to 1e-6 and limits within 5 % on a seeded,
// paper-like set (a subset of the benchmark's, to keep the test quick).
TEST_F(StagePlannerTest, BenchmarkSubsetMeetsBoundariesAndLimits) {
  for (const auto& problem : make_benchmark_problems(150, 7)) {
    const PlanResult result = planner.plan(problem);
    ASSERT_TRUE(is_usable(result.status)) << result.reason;
    const auto m = measure_trajectory(result.trajectory, problem);
    expect_boundaries_met(m);
    EXPECT_LE(m.speed_violation, 0.05);
    EXPECT_LE(m.acc_violation, 0.05);
  }
}

TEST_F(StagePlannerTest, StartAtGoalAtRestHolds) {
  const Eigen::Vector3d point(1.0, 2.0, 1.5);
  const PlanResult result = planner.plan(make_problem(point, Eigen::Vector3d::Zero(), point));
  EXPECT_EQ(result.status, PlanStatus::Ok);
  EXPECT_EQ(result.trajectory.duration_s(), 0.0);
  EXPECT_TRUE(result.trajectory.position(1.0).isApprox(point));
  EXPECT_TRUE(result.trajectory.velocity(1.0).isZero());
}

TEST_F(StagePlannerTest, StartAtGoalButMovingComesBack) {
  const Eigen::Vector3d point(0.0, 0.0, 1.5);
  const auto problem = make_problem(point, {0.8, 0.0, 0.0}, point);
  const PlanResult result = planner.plan(problem);
  ASSERT_TRUE(is_usable(result.status)) << result.reason;
  const auto m = measure_trajectory(result.trajectory, problem);
  expect_boundaries_met(m);
  EXPECT_GT(m.duration_s, 0.0);
  EXPECT_LT(m.acc_violation, 0.05);
}

TEST_F(StagePlannerTest, OneCentimetreStage) {
  const auto problem = make_problem({0.0, 0.0, 1.5}, Eigen::Vector3d::Zero(), {0.01, 0.0, 1.5});
  const PlanResult result = planner.plan(problem);
  ASSERT_TRUE(is_usable(result.status)) << result.reason;
  const auto m = measure_trajectory(result.trajectory, problem);
  expect_boundaries_met(m);
  EXPECT_LT(m.duration_s, 3.0);
  EXPECT_LT(m.acc_violation, 0.05);
}

TEST_F(StagePlannerTest, ThirtyMetreStage) {
  const auto problem = make_problem({30.0, 0.0, 1.0}, Eigen::Vector3d::Zero(), {0.0, 0.0, 1.0});
  const PlanResult result = planner.plan(problem);
  ASSERT_TRUE(is_usable(result.status)) << result.reason;
  const auto m = measure_trajectory(result.trajectory, problem);
  expect_boundaries_met(m);
  EXPECT_LE(m.speed_violation, 0.05);
  EXPECT_LE(m.acc_violation, 0.05);
  EXPECT_LT(m.duration_s, 2.0 * 30.0 / problem.vmax_m_s);
}

// |v0| = 4 m/s against vm = 1: the reference may not speed up beyond |v0| and must be back
// under vm once the decay allowed by the config has had time to act.
TEST_F(StagePlannerTest, InitialSpeedFarAboveLimitComesDown) {
  const auto problem = make_problem({3.0, 0.0, 1.5}, {0.0, 4.0, 0.0}, {0.0, 0.0, 1.5}, 1.0, 2.0);
  const PlanResult result = planner.plan(problem);
  ASSERT_TRUE(is_usable(result.status)) << result.reason;
  const auto m = measure_trajectory(result.trajectory, problem);
  expect_boundaries_met(m);
  EXPECT_LE(m.speed_violation, 0.05);  // against max(vm, |v0|)
  const double decay_time =
      (4.0 - 1.0) / (planner.params().overspeed_decel_fraction * problem.amax_m_s2);
  const Trajectory& trajectory = result.trajectory;
  ASSERT_GT(trajectory.duration_s(), decay_time + 1.0);
  for (double t = decay_time + 1.0; t <= trajectory.duration_s(); t += 0.05) {
    EXPECT_LE(trajectory.velocity(t).norm(), 1.05 * problem.vmax_m_s) << "t = " << t;
  }
}

// A transition start 7.2 m out, moving at 1.5 m/s about 50 degrees off the goal (Table 1 at
// (0.8, 0.35)): the plan turns and cruises. An initial guess bent by v0 * t once left
// L-BFGS in a wobbly local minimum, 14.6 s long.
TEST_F(StagePlannerTest, FastSidewaysStartTurnsAndCruises) {
  auto problem = make_problem({3.43, 6.28, 1.47}, {-1.45, -0.37, 0.29}, {0.0, 0.0, 1.5}, 1.0, 2.0);
  const PlanResult result = planner.plan(problem);
  ASSERT_TRUE(is_usable(result.status)) << result.reason;
  const double distance = (problem.goal_position_m - problem.start_position_m).norm();
  // Cruising at vmax with a turn and a stop takes about distance / vmax + 1 s.
  EXPECT_LT(result.trajectory.duration_s(), distance / problem.vmax_m_s + 1.5);
  expect_boundaries_met(measure_trajectory(result.trajectory, problem));
}

TEST_F(StagePlannerTest, NonFiniteOrAbsurdInputIsRejectedWithAFiniteHold) {
  const auto good = make_problem({1.0, 1.0, 1.0}, Eigen::Vector3d::Zero(), {0.0, 0.0, 1.5});
  std::vector<StageProblem> bad(8, good);
  bad[0].start_position_m.x() = kNaN;
  bad[1].start_velocity_m_s.y() = kNaN;
  bad[2].goal_position_m.z() = std::numeric_limits<double>::infinity();
  bad[3].vmax_m_s = kNaN;
  bad[4].amax_m_s2 = 0.0;
  bad[5].vmax_m_s = -1.0;  // vmax_uav < vmax_ugv in eq. 15
  bad[6].transition_stage = true;
  bad[6].ugv_angular_velocity_rad_s.z() = kNaN;
  bad[7].start_position_m.x() = 1.0e9;
  for (std::size_t k = 0; k < bad.size(); ++k) {
    const PlanResult result = planner.plan(bad[k]);
    EXPECT_EQ(result.status, PlanStatus::InvalidInput) << "case " << k;
    EXPECT_STRNE(result.reason, "") << "case " << k;
    EXPECT_TRUE(result.trajectory.is_finite()) << "case " << k;
    EXPECT_TRUE(result.trajectory.position(0.5).allFinite()) << "case " << k;
  }
  // The planner is not poisoned by bad input: a good problem still plans.
  EXPECT_EQ(planner.plan(good).status, PlanStatus::Ok);
}

TEST(StagePlanner, OptimiserStoppedEarlyStillGivesAUsableTrajectory) {
  PlannerParams params;
  params.max_evaluations = 3;
  StagePlanner planner(params);
  const auto problem = make_problem({6.0, -2.0, 1.0}, {1.0, 0.5, 0.0}, {0.0, 0.0, 1.5});
  const PlanResult result = planner.plan(problem);
  EXPECT_EQ(result.status, PlanStatus::EarlyStop) << result.reason;
  // The budget is checked before every evaluation.
  EXPECT_LE(result.iterations, 3);
  ASSERT_TRUE(result.trajectory.is_finite());
  expect_boundaries_met(measure_trajectory(result.trajectory, problem));
}

// Eq. 23 at the transition stage: v0 = v + Omega x p; elsewhere v0 = v.
TEST(StagePlanner, TransitionStageUsesRelativeTranslationalVelocity) {
  StageProblem problem = make_problem({4.0, 0.0, 1.5}, {0.0, -2.0, 0.0}, {0.0, 0.0, 1.5});
  problem.ugv_angular_velocity_rad_s = Eigen::Vector3d(0.0, 0.0, 0.5);
  EXPECT_TRUE(initial_velocity(problem).isApprox(Eigen::Vector3d(0.0, -2.0, 0.0)));
  problem.transition_stage = true;
  // Omega x p = (0, 0, 0.5) x (4, 0, 1.5) = (0, 2, 0): the rotation-induced part cancels.
  EXPECT_LT(initial_velocity(problem).norm(), 1e-12);

  StagePlanner planner{PlannerParams{}};
  const PlanResult result = planner.plan(problem);
  ASSERT_TRUE(is_usable(result.status)) << result.reason;
  EXPECT_LT(result.initial_velocity_m_s.norm(), 1e-12);
  EXPECT_LT(result.trajectory.velocity(0.0).norm(), 1e-9);
}

// A stage that starts braking (the final stage after the transition's approach) starts with
// that acceleration, capped at amax; at the transition stage it is ignored; a non-finite one
// is refused.
TEST(StagePlanner, StartAccelerationIsTheTrajectorysFirst) {
  StageProblem problem = make_problem({0.1, -0.05, 1.0}, {0.25, 0.0, 0.0}, {0.0, 0.0, 0.05});
  problem.vmax_m_s = 1.5;
  problem.start_acceleration_m_s2 = Eigen::Vector3d(-0.9, 0.2, 0.0);
  StagePlanner planner{PlannerParams{}};
  const PlanResult braking = planner.plan(problem);
  ASSERT_TRUE(is_usable(braking.status)) << braking.reason;
  EXPECT_LT((braking.trajectory.acceleration(0.0) - problem.start_acceleration_m_s2).norm(), 1e-6);
  EXPECT_LT((braking.trajectory.position(braking.trajectory.duration_s()) - problem.goal_position_m)
                .norm(),
            1e-6);

  problem.start_acceleration_m_s2 = Eigen::Vector3d(8.0, 0.0, 0.0);
  EXPECT_TRUE(initial_acceleration(problem).isApprox(Eigen::Vector3d(problem.amax_m_s2, 0, 0)));
  problem.transition_stage = true;
  EXPECT_EQ(initial_acceleration(problem), Eigen::Vector3d::Zero());
  problem.transition_stage = false;
  problem.start_acceleration_m_s2.x() = std::numeric_limits<double>::quiet_NaN();
  const PlanResult bad = planner.plan(problem);
  EXPECT_EQ(bad.status, PlanStatus::InvalidInput);
  EXPECT_TRUE(bad.trajectory.is_finite());
}

TEST(StagePlanner, InvalidParametersThrowAtConstruction) {
  PlannerParams params;
  params.pieces = 0;
  EXPECT_THROW(StagePlanner{params}, config::ConfigError);
}

}  // namespace
}  // namespace cover::planner
