#include <gtest/gtest.h>

#include <cmath>

#include "cover/sim/ugv_motion_pattern.hpp"
#include "cover/vocabulary/angles.hpp"
#include "test_worlds.hpp"

namespace cover::sim {
namespace {

using model::kPi;

double wrap_angle(double a) {
  return std::atan2(std::sin(a), std::cos(a));
}

std::vector<UgvMotionPatternParams> all_moving_patterns() {
  std::vector<UgvMotionPatternParams> out;
  out.push_back(test::circle(0.5, 0.35, 1.0, -2.0));
  out.push_back(test::circle(0.8, -0.5));  // clockwise
  UgvMotionPatternParams eight;
  eight.kind = MotionPatternKind::FigureEight;
  eight.speed_m_s = 0.8;
  eight.half_length_m = 2.5;
  eight.half_width_m = 1.2;
  eight.orientation_rad = 0.4;
  out.push_back(eight);
  UgvMotionPatternParams star;
  star.kind = MotionPatternKind::Star;
  star.speed_m_s = 0.8;
  star.radius_m = 2.0;
  star.star_points = 5;
  star.star_depth = 0.2;
  out.push_back(star);
  UgvMotionPatternParams s_curve;
  s_curve.kind = MotionPatternKind::SCurve;
  s_curve.speed_m_s = 1.0;
  s_curve.half_width_m = 1.0;
  s_curve.wavelength_m = 8.0;
  s_curve.orientation_rad = kPi;
  out.push_back(s_curve);
  UgvMotionPatternParams line;
  line.kind = MotionPatternKind::BackAndForth;
  line.speed_m_s = 1.0;
  line.half_length_m = 2.0;
  line.origin_m = {0.0, 1.4};
  out.push_back(line);
  return out;
}

TEST(MotionPattern, CircleHasRadiusVOverWAndSpeedV) {
  const UgvMotionPattern circle(test::circle(0.5, 0.25, 3.0, -1.0));
  for (double t = 0.0; t < 30.0; t += 0.37) {
    const UgvKinematics k = circle.at(t);
    EXPECT_NEAR((k.position_m - Eigen::Vector2d(3.0, -1.0)).norm(), 0.5 / 0.25, 1e-12);
    EXPECT_NEAR(k.velocity_m_s.norm(), 0.5, 1e-12);
    EXPECT_NEAR(k.yaw_rate_rad_s, 0.25, 1e-12);
    EXPECT_NEAR(k.yaw_acceleration_rad_s2, 0.0, 1e-12);
    // centripetal: |a| = v w, pointing at the centre
    EXPECT_NEAR(k.acceleration_m_s2.norm(), 0.5 * 0.25, 1e-12);
    EXPECT_GT(k.acceleration_m_s2.dot(Eigen::Vector2d(3.0, -1.0) - k.position_m), 0.0);
  }
}

TEST(MotionPattern, DerivativesMatchFiniteDifferences) {
  const double h = 1e-5;
  for (const auto& params : all_moving_patterns()) {
    const UgvMotionPattern pattern(params);
    SCOPED_TRACE(to_string(params.kind));
    for (double t = 0.3; t < 40.0; t += 1.13) {
      const UgvKinematics before = pattern.at(t - h), now = pattern.at(t),
                          after = pattern.at(t + h);
      const Eigen::Vector2d velocity = (after.position_m - before.position_m) / (2 * h);
      const Eigen::Vector2d acceleration = (after.velocity_m_s - before.velocity_m_s) / (2 * h);
      EXPECT_LT((velocity - now.velocity_m_s).norm(), 1e-6);
      EXPECT_LT((acceleration - now.acceleration_m_s2).norm(), 1e-6);
      EXPECT_NEAR(wrap_angle(after.yaw_rad - before.yaw_rad) / (2 * h), now.yaw_rate_rad_s, 1e-6);
      EXPECT_NEAR((after.yaw_rate_rad_s - before.yaw_rate_rad_s) / (2 * h),
                  now.yaw_acceleration_rad_s2, 1e-5);
    }
  }
}

TEST(MotionPattern, HeadingFollowsVelocityExceptReciprocatingLine) {
  for (const auto& params : all_moving_patterns()) {
    const UgvMotionPattern pattern(params);
    SCOPED_TRACE(to_string(params.kind));
    for (double t = 0.0; t < 40.0; t += 0.71) {
      const UgvKinematics k = pattern.at(t);
      const Eigen::Vector2d forward(std::cos(k.yaw_rad), std::sin(k.yaw_rad));
      if (params.kind == MotionPatternKind::BackAndForth) {
        // drives forward and in reverse along its axis, never sideways
        EXPECT_NEAR(std::abs(forward.dot(k.velocity_m_s)), k.velocity_m_s.norm(), 1e-12);
        EXPECT_DOUBLE_EQ(k.yaw_rad, params.orientation_rad);
      } else {
        ASSERT_GT(k.velocity_m_s.norm(), 1e-3);
        EXPECT_NEAR(forward.dot(k.velocity_m_s.normalized()), 1.0, 1e-12);
      }
    }
  }
}

TEST(MotionPattern, PeakSpeedEqualsConfiguredMaximum) {
  for (const auto& params : all_moving_patterns()) {
    const UgvMotionPattern pattern(params);
    SCOPED_TRACE(to_string(params.kind));
    double peak = 0.0;
    for (double t = 0.0; t < 60.0; t += 0.001)
      peak = std::max(peak, pattern.at(t).velocity_m_s.norm());
    EXPECT_LE(peak, params.speed_m_s + 1e-9);
    EXPECT_GT(peak, params.speed_m_s - 1e-4);
  }
}

TEST(MotionPattern, FigureEightCrossesItsCentreAndSpansItsExtent) {
  const auto params = all_moving_patterns()[2];
  const UgvMotionPattern eight(params);
  const UgvKinematics start = eight.at(0.0);
  EXPECT_LT((start.position_m - params.origin_m).norm(), 1e-12);  // crossing point at t = 0
  double max_x = 0.0, max_y = 0.0;
  for (double t = 0.0; t < 60.0; t += 0.01) {
    const Eigen::Vector2d d = eight.at(t).position_m - params.origin_m;
    const Eigen::Rotation2Dd to_local(-params.orientation_rad);
    const Eigen::Vector2d local = to_local * d;
    max_x = std::max(max_x, std::abs(local.x()));
    max_y = std::max(max_y, std::abs(local.y()));
  }
  EXPECT_NEAR(max_x, params.half_length_m, 1e-3);
  EXPECT_NEAR(max_y, params.half_width_m, 1e-3);
}

TEST(MotionPattern, StarRadiusOscillatesBetweenTipsAndNotches) {
  const auto params = all_moving_patterns()[3];
  const UgvMotionPattern star(params);
  double r_min = 1e9, r_max = 0.0;
  for (double t = 0.0; t < 60.0; t += 0.005) {
    const double r = (star.at(t).position_m - params.origin_m).norm();
    r_min = std::min(r_min, r);
    r_max = std::max(r_max, r);
  }
  EXPECT_NEAR(r_max, params.radius_m * (1 + params.star_depth), 1e-3);
  EXPECT_NEAR(r_min, params.radius_m * (1 - params.star_depth), 1e-3);
}

TEST(MotionPattern, SCurveAdvancesAlongItsOrientationWithinItsAmplitude) {
  const auto params = all_moving_patterns()[4];  // oriented along -x
  const UgvMotionPattern s_curve(params);
  double previous_x = 1.0;
  for (double t = 0.0; t < 30.0; t += 0.1) {
    const UgvKinematics k = s_curve.at(t);
    EXPECT_LT(k.position_m.x(), previous_x);  // always progressing along -x
    previous_x = k.position_m.x();
    EXPECT_LE(std::abs(k.position_m.y()), params.half_width_m + 1e-12);
  }
}

TEST(MotionPattern, BackAndForthStaysOnItsSegmentAndReverses) {
  const auto params = all_moving_patterns()[5];
  const UgvMotionPattern line(params);
  bool went_left = false, went_right = false;
  for (double t = 0.0; t < 30.0; t += 0.01) {
    const UgvKinematics k = line.at(t);
    EXPECT_DOUBLE_EQ(k.position_m.y(), 1.4);
    EXPECT_LE(std::abs(k.position_m.x()), params.half_length_m + 1e-12);
    went_left |= k.velocity_m_s.x() < -0.5;
    went_right |= k.velocity_m_s.x() > 0.5;
  }
  EXPECT_TRUE(went_left && went_right);
}

TEST(MotionPattern, StationaryNeverMoves) {
  const UgvMotionPattern still(test::stationary_at(1.0, 2.0, 0.3));
  const UgvKinematics k = still.at(12.0);
  EXPECT_EQ(k.position_m, Eigen::Vector2d(1.0, 2.0));
  EXPECT_EQ(k.velocity_m_s, Eigen::Vector2d::Zero());
  EXPECT_DOUBLE_EQ(k.yaw_rad, 0.3);
}

TEST(MotionPattern, RejectsAbsurdParameters) {
  auto params = test::circle(0.5, 0.0);
  EXPECT_THROW(params.validate(), cover::config::ConfigError);
  params = test::circle(std::nan(""), 0.3);
  EXPECT_THROW(params.validate(), cover::config::ConfigError);
  params.kind = MotionPatternKind::Star;
  params.speed_m_s = 0.8;
  params.star_depth = 1.5;
  EXPECT_THROW(params.validate(), cover::config::ConfigError);
}

}  // namespace
}  // namespace cover::sim
