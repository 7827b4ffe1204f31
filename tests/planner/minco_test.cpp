#include "cover/planner/minco.hpp"

#include <gtest/gtest.h>

namespace cover::planner {
namespace {

struct MincoFixture : ::testing::Test {
  void SetUp() override {
    head << Eigen::Vector3d(1.0, 2.0, 0.5), Eigen::Vector3d(0.8, -0.3, 0.1),
        Eigen::Vector3d(0.2, 0.0, -0.4);
    tail << Eigen::Vector3d(-3.0, 0.5, 1.5), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero();
    waypoints.resize(3, 3);
    waypoints << 0.5, -1.0, -2.0, 2.5, 1.5, 1.0, 1.0, 1.2, 1.4;
    durations.resize(4);
    durations << 1.2, 0.7, 2.5, 1.1;
    minco.set_conditions(head, tail, 4);
    minco.set_parameters(waypoints, durations);
  }
  Eigen::Matrix3d head, tail;
  Eigen::Matrix3Xd waypoints;
  Eigen::VectorXd durations;
  MinimumJerkMinco minco;
};

TEST_F(MincoFixture, MeetsBoundaryConditionsAndWaypoints) {
  const Trajectory trajectory = minco.trajectory();
  const double end = trajectory.duration_s();
  EXPECT_NEAR(end, durations.sum(), 1e-12);
  for (int k = 0; k < 3; ++k) {
    EXPECT_LT((trajectory.derivative(0.0, k) - head.col(k)).norm(), 1e-9) << "start order " << k;
    EXPECT_LT((trajectory.derivative(end, k) - tail.col(k)).norm(), 1e-9) << "end order " << k;
  }
  double t = 0.0;
  for (int i = 0; i < 3; ++i) {
    t += durations(i);
    EXPECT_LT((trajectory.position(t) - waypoints.col(i)).norm(), 1e-9) << "waypoint " << i;
  }
}

// Minimum-jerk optimality makes the pieces C4 at the joints.
TEST_F(MincoFixture, IsFourTimesContinuousAtJoints) {
  const Trajectory trajectory = minco.trajectory();
  const auto& pieces = trajectory.pieces();
  for (std::size_t i = 0; i + 1 < pieces.size(); ++i) {
    const Trajectory left({pieces[i]});
    const Trajectory right({pieces[i + 1]});
    for (int k = 0; k <= 4; ++k) {
      const Eigen::Vector3d a = left.derivative(left.duration_s(), k);
      const Eigen::Vector3d b = right.derivative(0.0, k);
      EXPECT_LT((a - b).norm(), 1e-7 * (1.0 + a.norm())) << "joint " << i << " order " << k;
    }
  }
}

TEST_F(MincoFixture, JerkEnergyMatchesNumericalIntegral) {
  const Trajectory trajectory = minco.trajectory();
  const int steps = 20000;
  const double h = trajectory.duration_s() / steps;
  double integral = 0.0;
  for (int k = 0; k < steps; ++k) {  // midpoint rule; jerk is discontinuous only at joints
    integral += trajectory.jerk((k + 0.5) * h).squaredNorm() * h;
  }
  EXPECT_NEAR(minco.jerk_energy(), integral, 1e-3 * integral);
}

// The adjoint gradient of the jerk energy w.r.t. waypoints and durations vs central
// differences of the full map (q, T) -> c -> energy.
TEST_F(MincoFixture, EnergyGradientMatchesFiniteDifferences) {
  MinimumJerkMinco::Coefficients grad_c = MinimumJerkMinco::Coefficients::Zero(24, 3);
  Eigen::VectorXd partial_T = Eigen::VectorXd::Zero(4), grad_T(4);
  Eigen::Matrix3Xd grad_q(3, 3);
  minco.add_jerk_energy_gradient(grad_c, partial_T);
  minco.propagate_gradient(grad_c, partial_T, grad_q, grad_T);

  const auto energy_at = [&](const Eigen::Matrix3Xd& q, const Eigen::VectorXd& T) {
    MinimumJerkMinco other;
    other.set_conditions(head, tail, 4);
    other.set_parameters(q, T);
    return other.jerk_energy();
  };
  const double h = 1e-6;
  for (int i = 0; i < 4; ++i) {
    Eigen::VectorXd plus = durations, minus = durations;
    plus(i) += h;
    minus(i) -= h;
    const double numeric = (energy_at(waypoints, plus) - energy_at(waypoints, minus)) / (2 * h);
    EXPECT_NEAR(grad_T(i), numeric, 1e-5 * (1.0 + std::abs(numeric))) << "T" << i;
  }
  for (int i = 0; i < 3; ++i) {
    for (int axis = 0; axis < 3; ++axis) {
      Eigen::Matrix3Xd plus = waypoints, minus = waypoints;
      plus(axis, i) += h;
      minus(axis, i) -= h;
      const double numeric = (energy_at(plus, durations) - energy_at(minus, durations)) / (2 * h);
      EXPECT_NEAR(grad_q(axis, i), numeric, 1e-5 * (1.0 + std::abs(numeric)))
          << "q" << i << " axis " << axis;
    }
  }
}

}  // namespace
}  // namespace cover::planner
