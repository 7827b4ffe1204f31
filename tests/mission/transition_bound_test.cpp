// The lower bound on a transition's path (Table 1's bound_ratio) and its cone solver.
#include "cover/sim/transition_bound.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "cover/sim/approach_law.hpp"
#include "cover/sim/cone_program.hpp"

using cover::sim::ApproachLawParams;
using cover::sim::MotionPatternKind;
using cover::sim::shortest_transition_bound;
using cover::sim::TransitionBoundParams;
using cover::sim::UgvMotionPattern;
using cover::sim::UgvMotionPatternParams;

namespace {

UgvMotionPattern circle(double speed_m_s, double yaw_rate_rad_s, double phase_rad = 0.0) {
  UgvMotionPatternParams p;
  p.kind = MotionPatternKind::Circle;
  p.speed_m_s = speed_m_s;
  p.yaw_rate_rad_s = yaw_rate_rad_s;
  p.phase_rad = phase_rad;
  p.origin_m = {2.5, 0.0};
  p.validate();
  return UgvMotionPattern(p);
}

UgvMotionPattern standing_still() {
  UgvMotionPatternParams p;
  p.kind = MotionPatternKind::Stationary;
  p.validate();
  return UgvMotionPattern(p);
}

cover::sim::SparseRow row(int variable, double coefficient) {
  return {{{variable, coefficient}}};
}

}  // namespace

// min x + y over the unit disc: -sqrt(2) at (-1, -1) / sqrt(2), certified by the gap.
TEST(ConeProgram, SolvesADiscToItsKnownOptimum) {
  cover::sim::ConeProgram program;
  program.variables = 2;
  program.cost = Eigen::Vector2d(1.0, 1.0);
  cover::sim::PlanarCone disc;
  disc.g = {row(0, 1.0), row(1, 1.0)};
  disc.rho = 1.0;
  program.cones.push_back(disc);
  const auto r = cover::sim::solve_cone_program(program, Eigen::Vector2d(3.0, -4.0));
  ASSERT_TRUE(r.feasible);
  EXPECT_NEAR(r.value, -std::sqrt(2.0), 1e-3);
  EXPECT_LE(r.lower_bound, -std::sqrt(2.0) + 1e-9);
  EXPECT_GT(r.lower_bound, -std::sqrt(2.0) - 1e-3);
}

// Two discs 3 apart with radius 1 do not meet: phase I says so.
TEST(ConeProgram, ReportsDisjointDiscsInfeasible) {
  cover::sim::ConeProgram program;
  program.variables = 2;
  program.cost = Eigen::Vector2d(0.0, 0.0);
  cover::sim::PlanarCone a;
  a.g = {row(0, 1.0), row(1, 1.0)};
  a.rho = 1.0;
  cover::sim::PlanarCone b = a;
  b.c = {3.0, 0.0};
  program.cones = {a, b};
  EXPECT_FALSE(cover::sim::solve_cone_program(program, Eigen::Vector2d::Zero()).feasible);
}

// A UGV at rest and a UAV at rest: the straight line, stopping the tolerance short.
TEST(TransitionBound, IsTheStraightLineToAStandingUgv) {
  const TransitionBoundParams params;
  const auto r =
      shortest_transition_bound(standing_still(), 0.0, {5.0, 0.0}, {0.0, 0.0}, 10.0, params);
  ASSERT_TRUE(r.reached);
  EXPECT_NEAR(r.path_length_m / r.straight_length_m, 1.0, 1e-3);
  EXPECT_NEAR(r.path_length_m, 5.0 - params.reach_tolerance_m, 1e-2);
  // At vmax it takes at least (5 - 0.3) / vmax; the budget leaves room, so T* is shorter.
  EXPECT_GT(r.arrival_time_s, (5.0 - params.reach_tolerance_m) / params.vmax_m_s - 0.2);
  EXPECT_LE(r.arrival_time_s, 10.0);
}

// Too short a budget to get there at vmax: no bound, no numbers made up.
TEST(TransitionBound, ReachesNothingWithinTooShortABudget) {
  const auto r = shortest_transition_bound(standing_still(), 0.0, {5.0, 0.0}, {0.0, 0.0}, 2.0,
                                           TransitionBoundParams{});
  EXPECT_FALSE(r.reached);
  EXPECT_TRUE(r.path_m.empty());
}

// The polyline keeps every limit it was given (a stationary target: A = amax, yaw rate 0).
TEST(TransitionBound, KeepsTheLimitsAlongThePath) {
  TransitionBoundParams params;
  const Eigen::Vector2d v0(0.0, 1.2);  // sideways and faster than vmax: must bend and slow
  const auto r = shortest_transition_bound(standing_still(), 0.0, {4.0, 0.0}, v0, 12.0, params);
  ASSERT_TRUE(r.reached);
  const auto n = r.path_m.size() - 1;
  const double dt = r.arrival_time_s / static_cast<double>(n);
  const double slack = 1e-6;
  Eigen::Vector2d previous = v0;
  double length = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Vector2d u = (r.path_m[k + 1] - r.path_m[k]) / dt;
    const double limit = std::max(params.vmax_m_s, v0.norm() - params.amax_m_s2 * k * dt);
    EXPECT_LE(u.norm(), limit + slack) << "segment " << k;
    const double change = k == 0 ? 0.5 * params.amax_m_s2 * dt : params.amax_m_s2 * dt;
    EXPECT_LE((u - previous).norm(), change + slack) << "segment " << k;
    previous = u;
    length += (r.path_m[k + 1] - r.path_m[k]).norm();
  }
  EXPECT_LE(r.path_m.back().norm(), params.reach_tolerance_m + slack);
  EXPECT_LE(previous.norm(), params.speed_threshold_m_s + 0.5 * params.amax_m_s2 * dt + slack);
  // The certified bound is the polyline's length less at most the duality gap.
  EXPECT_LE(r.path_length_m, length + 1e-9);
  EXPECT_GT(r.path_length_m, length - 10 * params.gap_tolerance_m);
  // The sideways start bends the path: longer than the straight line.
  EXPECT_GT(r.path_length_m / r.straight_length_m, 1.01);
}

// Random starts around a circling UGV: the eq. 30 law's flight keeps the limits, so the
// shortest path arriving by its arrival time is never longer than it.
TEST(TransitionBound, IsNeverAboveTheEq30Law) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_real_distribution<double> angle(0.0, 6.283185307179586);
  int compared = 0;
  for (int i = 0; i < 12; ++i) {
    const UgvMotionPattern target = circle(0.8, 0.35, angle(rng));
    const Eigen::Vector2d p0(-2.5 + 2.0 * unit(rng), 2.0 * unit(rng));
    const Eigen::Vector2d v0(0.8 * unit(rng), 0.8 * unit(rng));
    const ApproachLawParams law;
    const auto eq30 = cover::sim::fly_approach_law(target, 0.0, p0, v0, law);
    ASSERT_TRUE(eq30.reached) << "start " << i;
    TransitionBoundParams params;
    params.vmax_m_s = law.vmax_m_s;
    params.amax_m_s2 = law.amax_m_s2;
    const auto bound = shortest_transition_bound(target, 0.0, p0, v0, eq30.duration_s, params);
    ASSERT_TRUE(bound.reached) << "start " << i;
    EXPECT_LE(bound.path_length_m, eq30.path_length_m + 1e-6) << "start " << i;
    EXPECT_GE(bound.path_length_m, bound.straight_length_m - 1e-6) << "start " << i;
    ++compared;
  }
  EXPECT_EQ(compared, 12);
}
