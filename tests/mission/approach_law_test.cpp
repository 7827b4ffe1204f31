// The eq. 30 point-mass model that Table 1 prints next to the closed-loop ratio.
#include "cover/sim/approach_law.hpp"

#include <gtest/gtest.h>

#include <cmath>

using cover::sim::ApproachLawParams;
using cover::sim::fly_approach_law;
using cover::sim::MotionPatternKind;
using cover::sim::UgvMotionPattern;
using cover::sim::UgvMotionPatternParams;

namespace {

UgvMotionPattern circle(double speed_m_s, double yaw_rate_rad_s) {
  UgvMotionPatternParams p;
  p.kind = MotionPatternKind::Circle;
  p.speed_m_s = speed_m_s;
  p.yaw_rate_rad_s = yaw_rate_rad_s;
  p.validate();
  return UgvMotionPattern(p);
}

UgvMotionPattern standing_still() {
  UgvMotionPatternParams p;
  p.kind = MotionPatternKind::Stationary;
  p.validate();
  return UgvMotionPattern(p);
}

}  // namespace

// A UGV at rest: the law is a straight line at vmax, braking at amax.
TEST(ApproachLaw, FliesStraightToAStandingUgv) {
  const ApproachLawParams params;
  const auto r = fly_approach_law(standing_still(), 0.0, {5.0, 0.0}, {0.0, 0.0}, params);
  ASSERT_TRUE(r.reached);
  EXPECT_NEAR(r.path_length_m / r.straight_length_m, 1.0, 1e-3);
  EXPECT_GT(r.straight_length_m, 5.0 - params.reach_tolerance_m);
  // Never faster than vmax: at least 5 m / 1 m/s minus the tolerance.
  EXPECT_GT(r.duration_s, (5.0 - params.reach_tolerance_m) / params.vmax_m_s);
  EXPECT_LT(r.duration_s, 8.0);
}

// A circling UGV: the UAV moves with it, so part of its circle is in the path (the reason
// eq. 30 cannot reach Lt/Ls = 1), and the faster the UGV, the longer the detour.
TEST(ApproachLaw, CopiesTheCurveOfACirclingUgv) {
  const ApproachLawParams params;
  const auto slow = fly_approach_law(circle(0.5, 0.35), 0.0, {-6.0, 0.0}, {0.0, 0.0}, params);
  const auto fast = fly_approach_law(circle(0.8, 0.35), 0.0, {-6.0, 0.0}, {0.0, 0.0}, params);
  ASSERT_TRUE(slow.reached);
  ASSERT_TRUE(fast.reached);
  const double slow_ratio = slow.path_length_m / slow.straight_length_m;
  const double fast_ratio = fast.path_length_m / fast.straight_length_m;
  EXPECT_GT(slow_ratio, 1.005);
  EXPECT_GT(fast_ratio, slow_ratio);
}

// A UGV faster than the approach limit cannot be caught: not reached, finite lengths.
TEST(ApproachLaw, GivesUpOnAUgvItCannotCatch) {
  ApproachLawParams params;
  params.vmax_m_s = 0.2;
  params.max_duration_s = 5.0;
  const auto r = fly_approach_law(circle(0.8, 0.05), 0.0, {-20.0, 0.0}, {0.0, 0.0}, params);
  EXPECT_FALSE(r.reached);
  EXPECT_DOUBLE_EQ(r.duration_s, 5.0);
  EXPECT_TRUE(std::isfinite(r.path_length_m));
  EXPECT_TRUE(std::isfinite(r.straight_length_m));
}
