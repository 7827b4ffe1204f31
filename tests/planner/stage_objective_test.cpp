#include "cover/planner/stage_objective.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace cover::planner {
namespace {

// Full objective (energy + rho T + both penalties, active) vs central differences in the
// optimiser's variables (tau, q). Parameterised over problems that activate each term.
struct GradientCase {
  const char* name;
  Eigen::Vector3d start, v0, goal;
  double vmax, amax;
  Eigen::Vector3d a0 = Eigen::Vector3d::Zero();
};

class ObjectiveGradient : public ::testing::TestWithParam<GradientCase> {};

TEST_P(ObjectiveGradient, MatchesFiniteDifferences) {
  const GradientCase& c = GetParam();
  PlannerParams params;
  params.pieces = 4;
  StageObjective objective(params);
  objective.set_problem(c.start, c.v0, c.a0, c.goal, c.vmax, c.amax);
  // Short durations so the speed and acceleration penalties are active.
  Eigen::VectorXd durations(4);
  durations << 0.9, 1.3, 0.6, 1.1;
  Eigen::Matrix3Xd waypoints(3, 3);
  for (int i = 0; i < 3; ++i) {
    waypoints.col(i) =
        c.start + (c.goal - c.start) * (i + 1) / 4.0 + Eigen::Vector3d(0.3, -0.2, 0.1);
  }
  std::vector<double> x(static_cast<std::size_t>(objective.dimension()));
  std::vector<double> gradient(x.size());
  objective.encode(waypoints, durations, x.data());
  const double cost = objective.evaluate(x.data(), gradient.data());
  ASSERT_GT(cost, 1.0);
  for (std::size_t k = 0; k < x.size(); ++k) {
    const double h = 1e-6 * (1.0 + std::abs(x[k]));
    std::vector<double> plus = x, minus = x;
    plus[k] += h;
    minus[k] -= h;
    const double numeric =
        (objective.evaluate(plus.data(), nullptr) - objective.evaluate(minus.data(), nullptr)) /
        (2.0 * h);
    EXPECT_NEAR(gradient[k], numeric, 1e-5 * (std::abs(numeric) + 1.0)) << c.name << " x" << k;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Cases, ObjectiveGradient,
    ::testing::Values(
        GradientCase{"long_fast", {6.0, 2.0, 1.0}, {0.5, 0.0, 0.0}, {0.0, 0.0, 1.5}, 1.0, 2.0},
        GradientCase{
            "overspeed_start", {2.0, -1.0, 1.0}, {2.5, 1.0, 0.0}, {0.0, 0.0, 1.5}, 1.0, 1.5},
        GradientCase{"short", {0.2, 0.1, 1.0}, {0.0, 0.0, 0.0}, {0.0, 0.0, 1.5}, 1.2, 3.0},
        // Starting mid-manoeuvre: a braking start acceleration.
        GradientCase{"braking_start",
                     {0.2, 0.1, 1.0},
                     {-0.3, 0.1, 0.2},
                     {0.0, 0.0, 0.05},
                     1.5,
                     2.0,
                     {1.8, -0.4, 0.5}}),
    [](const ::testing::TestParamInfo<GradientCase>& info) { return info.param.name; });

TEST(TimeMap, IsPositiveMonotoneAndInvertible) {
  double previous = 0.0;
  for (double tau = -20.0; tau <= 20.0; tau += 0.25) {
    const double duration = StageObjective::duration_from_tau(tau);
    EXPECT_GT(duration, previous);
    EXPECT_NEAR(StageObjective::tau_from_duration(duration), tau, 1e-9 * (1.0 + std::abs(tau)));
    const double h = 1e-6;
    const double numeric =
        (StageObjective::duration_from_tau(tau + h) - StageObjective::duration_from_tau(tau - h)) /
        (2 * h);
    EXPECT_NEAR(StageObjective::duration_derivative(tau), numeric, 1e-6 * (1.0 + numeric));
    previous = duration;
  }
}

}  // namespace
}  // namespace cover::planner
