#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <tuple>

#include "cover/config/yaml_reader.hpp"
#include "cover/sampc/horizon_cost.hpp"
#include "cover/sampc/intercept_velocity.hpp"
#include "cover/sampc/sampc.hpp"
#include "cover/vocabulary/angles.hpp"

namespace cover::sampc {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

model::UgvMotion driving(double speed_m_s, double yaw_rate_rad_s) {
  model::UgvMotion ugv;
  ugv.angular_velocity_rad_s = Vector3d(0.0, 0.0, yaw_rate_rad_s);
  ugv.speed_m_s = speed_m_s;
  ugv.speed_source = model::SpeedSource::WheelOdometry;
  return ugv;
}

// Eq. 30 without the hold radius: -(Omega x p)_xy - p_hat s.
Vector2d eq30(const model::UgvMotion& ugv, const Vector3d& p, double s) {
  Vector2d v = -ugv.angular_velocity_rad_s.cross(p).head<2>();
  if (p.head<2>().norm() > 0.0) v -= p.head<2>().normalized() * s;
  return v;
}

TEST(InterceptVelocity, MeanVelocityOfAStraightAndATurningUgv) {
  EXPECT_LT((ugv_mean_velocity(0.8, 0.0, 3.0) - Vector2d(0.8, 0.0)).norm(), 1e-15);
  EXPECT_LT((ugv_mean_velocity(0.8, 0.4, 0.0) - Vector2d(0.8, 0.0)).norm(), 1e-15);
  // A quarter circle of radius u / w: D = (u / w) [1, 1], over tau = (pi / 2) / w.
  const double u = 0.5, w = 0.25, tau = model::kPi / 2.0 / w;
  EXPECT_LT((ugv_mean_velocity(u, w, tau) * tau - Vector2d(u / w, u / w)).norm(), 1e-12);
  EXPECT_LT((ugv_mean_velocity(u, -w, tau) * tau - Vector2d(u / w, -u / w)).norm(), 1e-12);
  // The series below the threshold joins the closed form.
  EXPECT_LT((ugv_mean_velocity(u, 1e-4, 0.999) - ugv_mean_velocity(u, 1e-4, 1.001)).norm(), 1e-6);
}

// D(tau) / tau by numerical integration (midpoints) of speed u + a t at yaw rate w, stopped
// at zero speed.
Vector2d integrated_mean_velocity(double u, double w, double a, double tau) {
  constexpr int kSteps = 200000;
  const double dt = tau / kSteps;
  Vector2d d = Vector2d::Zero();
  for (int i = 0; i < kSteps; ++i) {
    const double t = (i + 0.5) * dt;
    d += std::max(u + a * t, 0.0) * Vector2d(std::cos(w * t), std::sin(w * t)) * dt;
  }
  return d / tau;
}

TEST(InterceptVelocity, MeanVelocityOfAnAcceleratingUgvAndOfOneThatBrakesToAStop) {
  // Straight: u + a tau / 2.
  EXPECT_LT((ugv_mean_velocity(0.5, 0.0, 4.0, 0.2) - Vector2d(0.9, 0.0)).norm(), 1e-15);
  for (const auto& [u, w, a, tau] : {std::tuple{0.5, 0.3, 0.2, 4.0},
                                     {0.8, -0.35, -0.1, 5.0},
                                     {0.6, 0.005, 0.3, 1.0},
                                     {0.6, 0.02, -0.2, 2.0}}) {
    EXPECT_LT((ugv_mean_velocity(u, w, tau, a) - integrated_mean_velocity(u, w, a, tau)).norm(),
              1e-9)
        << u << " " << w << " " << a << " " << tau;
  }
  // Braking from 1 m/s at 1 m/s^2: stopped after 0.5 m, whatever the time to go.
  for (const double tau : {2.0, 4.0, 6.0}) {
    EXPECT_LT((ugv_mean_velocity(1.0, 0.0, tau, -1.0) * tau - Vector2d(0.5, 0.0)).norm(), 1e-12);
    EXPECT_LT(
        (ugv_mean_velocity(1.0, 0.4, tau, -1.0) - integrated_mean_velocity(1.0, 0.4, -1.0, tau))
            .norm(),
        1e-9);
  }
  // The series below the threshold joins the closed form.
  EXPECT_LT(
      (ugv_mean_velocity(0.5, 1e-2, 0.999, 0.3) - ugv_mean_velocity(0.5, 1e-2, 1.001, 0.3)).norm(),
      1e-3);
}

TEST(InterceptVelocity, UsesTheUgvsOwnAccelerationClampedAndNeverANaN) {
  InterceptParams params;
  model::UgvMotion ugv = driving(0.8, 0.0);
  ugv.forward_acceleration_m_s2 = 0.3;
  EXPECT_EQ(predicted_forward_acceleration_m_s2(params, ugv), 0.3);
  ugv.forward_acceleration_m_s2 = -5.0;
  EXPECT_EQ(predicted_forward_acceleration_m_s2(params, ugv), -params.max_ugv_acceleration_m_s2);
  ugv.forward_acceleration_m_s2 = kNaN;
  EXPECT_EQ(predicted_forward_acceleration_m_s2(params, ugv), 0.0);
  ugv.forward_acceleration_m_s2 = 0.3;
  params.use_ugv_acceleration = false;
  EXPECT_EQ(predicted_forward_acceleration_m_s2(params, ugv), 0.0);
}

// A straight-driving UGV speeding up: eq. 30 (the collision course with a target of constant
// velocity) keeps re-aiming behind it; the law with the UGV's acceleration aims where it
// will be. A point mass flying each, in the world, from abeam and ahead of the UGV (from
// behind, both fly nearly straight).
TEST(InterceptVelocity, APointMassMeetsAnAcceleratingUgvOnAStraighterPathThanEq30) {
  const auto ratio = [](bool with_acceleration, const Vector2d& start) {
    InterceptParams params;
    params.use_ugv_acceleration = with_acceleration;
    const double s = 1.5, dt = 0.01, accel = 0.3;
    Vector2d uav = start, ugv_position(0.0, 0.0);
    double u = 0.3, length = 0.0;
    for (int i = 0; i < 5000; ++i) {
      const Vector2d rel = uav - ugv_position;
      if (rel.norm() < 0.05) return length / (uav - start).norm();
      model::UgvMotion ugv = driving(u, 0.0);
      ugv.forward_acceleration_m_s2 = accel;
      const Vector3d p(rel.x(), rel.y(), 1.0);
      const Vector2d v = intercept_velocity(params, ugv, p, s, eq30(ugv, p, s), s).velocity_m_s;
      const Vector2d inertial = v + Vector2d(u, 0.0);
      uav += inertial * dt;
      length += inertial.norm() * dt;
      ugv_position.x() += u * dt;
      u += accel * dt;
    }
    return kInf;
  };
  for (const Vector2d& start : {Vector2d(0.0, 4.0), Vector2d(3.0, 3.0), Vector2d(2.0, -4.0)}) {
    const double with = ratio(true, start), without = ratio(false, start);
    EXPECT_LT(with, without - 0.002) << start.transpose() << ": " << with << " " << without;
    EXPECT_LT(with, 1.02) << start.transpose();
  }
}

TEST(InterceptVelocity, FallsBackToEq30BitForBitWithTheReason) {
  const InterceptParams params;
  const Vector3d p(2.0, -1.5, 1.2);
  const double s = 1.0;
  struct Case {
    model::UgvMotion ugv;
    InterceptFallback expected;
  };
  model::UgvMotion unknown = driving(0.8, 0.35);
  unknown.speed_source = model::SpeedSource::None;
  model::UgvMotion imu_nan = driving(kNaN, 0.35);
  imu_nan.speed_source = model::SpeedSource::Imu;
  const Case cases[] = {
      {unknown, InterceptFallback::NoSpeed},
      {imu_nan, InterceptFallback::NoSpeed},
      {driving(kInf, 0.35), InterceptFallback::NoSpeed},
      {driving(-0.5, 0.35), InterceptFallback::Reversing},
      {driving(0.05, 0.35), InterceptFallback::SlowUgv},
      {driving(0.8, 1e6), InterceptFallback::FastTurn},
      {driving(0.8, -1.5), InterceptFallback::FastTurn},
  };
  for (const Case& c : cases) {
    const Vector2d base = eq30(c.ugv, p, s);
    const InterceptVelocity law = intercept_velocity(params, c.ugv, p, s, base, 1.0);
    EXPECT_EQ(law.fallback, c.expected) << to_string(c.expected);
    EXPECT_EQ(law.velocity_m_s, base) << to_string(c.expected);
  }
  const model::UgvMotion good = driving(0.8, 0.35);
  const Vector2d base = eq30(good, p, s);
  EXPECT_EQ(intercept_velocity(params, good, Vector3d(kNaN, 0, 1), s, base, 1.0).fallback,
            InterceptFallback::BadInput);
  EXPECT_EQ(intercept_velocity(params, good, p, kNaN, base, 1.0).fallback,
            InterceptFallback::BadInput);
  EXPECT_EQ(intercept_velocity(params, good, p, s, base, kNaN).fallback,
            InterceptFallback::BadInput);
  EXPECT_EQ(intercept_velocity(params, good, p, s, Vector2d(kNaN, 0), 1.0).fallback,
            InterceptFallback::BadInput);
  // A NaN yaw rate makes eq. 30 NaN too: refused, and nothing is added to it.
  const model::UgvMotion nan_turn = driving(0.8, kNaN);
  EXPECT_NE(intercept_velocity(params, nan_turn, p, s, eq30(nan_turn, p, s), 1.0).fallback,
            InterceptFallback::None);
}

TEST(InterceptVelocity, AStraightDrivingUgvIsAlreadyInterceptedByEq30) {
  // Without rotation the frame only translates: eq. 30's straight line to the UGV in G is
  // a straight line in the world, and the lead is zero.
  const model::UgvMotion ugv = driving(0.8, 0.0);
  const Vector3d p(-3.0, 2.0, 1.5);
  const InterceptVelocity law =
      intercept_velocity(InterceptParams{}, ugv, p, 1.0, eq30(ugv, p, 1.0), 1.0);
  EXPECT_EQ(law.fallback, InterceptFallback::None);
  // (to the time-to-go search's tolerance: 2.4e-7 s)
  EXPECT_LT((law.velocity_m_s - eq30(ugv, p, 1.0)).norm(), 1e-7);
}

TEST(InterceptVelocity, AimsAtWhereTheTurningUgvWillBeAtTheEarliestArrival) {
  const double u = 0.8, w = 0.35, s = 1.0;
  const model::UgvMotion ugv = driving(u, w);
  const auto ugv_at = [&](double tau) {
    return Vector2d(u / w * Vector2d(std::sin(w * tau), 1.0 - std::cos(w * tau)));
  };
  for (const Vector3d& p : {Vector3d(-1.5, 2.0, 1.5), Vector3d(2.5, 0.0, 1.5)}) {
    const Vector2d rotation = ugv.angular_velocity_rad_s.cross(p).head<2>();
    // The relative velocity (to the UGV's translation now) that flies straight from p to
    // the UGV at tau.
    const auto needed = [&](double tau) {
      return Vector2d((ugv_at(tau) - p.head<2>()) / tau - Vector2d(u, 0.0));
    };
    for (const bool solve : {true, false}) {
      InterceptParams params;  // the constant-velocity aim (the fastest flight: below)
      params.fastest_straight_flight = false;
      params.solve_time_to_go = solve;
      // Solved: the approach at the speed limit (s = vmax), far from the braking curve;
      // without the solve, a limit that does not cut the lead.
      const double limit = solve ? s : 2.0;
      const InterceptVelocity law = intercept_velocity(params, ugv, p, s, eq30(ugv, p, s), limit);
      ASSERT_EQ(law.fallback, InterceptFallback::None);
      const double tau = law.time_to_go_s;
      // The inertial velocity v + Omega x p + [u, 0] flies from p to D(tau) in tau.
      const Vector2d inertial = law.velocity_m_s + rotation + Vector2d(u, 0.0);
      EXPECT_LT((p.head<2>() + inertial * tau - ugv_at(tau)).norm(), 1e-8) << solve;
      if (!solve) {
        EXPECT_NEAR(tau, p.head<2>().norm() / s, 1e-12);
        continue;
      }
      // Solved: the whole approach speed relative to the UGV, and no earlier arrival within
      // it (a fine scan); not |p| / s.
      EXPECT_NEAR((law.velocity_m_s + rotation).norm(), s, 1e-8);
      for (double t = 0.05; t < tau - 1e-3; t += 0.001) ASSERT_GT(needed(t).norm(), s) << t;
      EXPECT_GT(std::abs(tau - p.head<2>().norm() / s), 0.05);
      // On the braking curve (s below the limit) the lead goes on top of eq. 30: the law
      // without the solve, bit for bit.
      InterceptParams unsolved = params;
      unsolved.solve_time_to_go = false;
      const double slow = 0.6;
      EXPECT_EQ(intercept_velocity(params, ugv, p, slow, eq30(ugv, p, slow), s).velocity_m_s,
                intercept_velocity(unsolved, ugv, p, slow, eq30(ugv, p, slow), s).velocity_m_s);
    }
  }
}

TEST(InterceptVelocity, EarliestTimeToGoIsTheStraightLineForAStraightUgvAndNoneWhenOutrun) {
  // Driving straight: D(tau) = [u tau, 0], so the relative flight is p / tau: tau = |p| / s.
  EXPECT_NEAR(earliest_time_to_go_s(0.8, 0.0, Vector2d(3.0, 4.0), 1.25, 10.0).value(), 4.0, 1e-9);
  // At the axis nothing to fly.
  EXPECT_EQ(earliest_time_to_go_s(0.8, 0.3, Vector2d::Zero(), 1.0, 6.0).value(), 0.0);
  // A UGV that turns away faster than the approach closes (a tiny s): none within the cap,
  // and the law then takes |p| / s, capped.
  EXPECT_FALSE(earliest_time_to_go_s(0.8, 0.3, Vector2d(-30.0, 0.0), 0.01, 6.0).has_value());
  // Non-finite inputs: no time to go, never a NaN one.
  EXPECT_FALSE(earliest_time_to_go_s(0.8, 0.3, Vector2d(kNaN, 1.0), 1.0, 6.0).has_value());
  EXPECT_FALSE(earliest_time_to_go_s(kNaN, 0.3, Vector2d(3.0, 1.0), 1.0, 6.0).has_value());
  EXPECT_FALSE(earliest_time_to_go_s(0.8, kNaN, Vector2d(3.0, 1.0), 1.0, 6.0).has_value());
  EXPECT_FALSE(earliest_time_to_go_s(0.8, 0.3, Vector2d(3.0, 1.0), kNaN, 6.0).has_value());
  EXPECT_FALSE(earliest_time_to_go_s(0.8, 0.3, Vector2d(3.0, 1.0), 1.0, kInf).has_value());
  const model::UgvMotion ugv = driving(0.8, 0.3);
  const Vector3d far(-30.0, 0.0, 1.0);
  EXPECT_EQ(
      intercept_velocity(InterceptParams{}, ugv, far, 0.01, eq30(ugv, far, 0.01), 1.0).time_to_go_s,
      InterceptParams{}.max_time_to_go_s);
}

TEST(InterceptVelocity, KeepsTheRelativeSpeedWithinTheLimitAndCapsTheTimeToGo) {
  InterceptParams params;
  const double w = 0.35, s = 1.0;
  const model::UgvMotion ugv = driving(3.0, w);  // a fast UGV: a large lead
  const Vector3d p(-8.0, 6.0, 1.5);
  const Vector2d base = eq30(ugv, p, s);
  for (const double limit : {0.5, 1.2, 2.0}) {
    const InterceptVelocity law = intercept_velocity(params, ugv, p, s, base, limit);
    const Vector2d relative = law.velocity_m_s + ugv.angular_velocity_rad_s.cross(p).head<2>();
    EXPECT_LE(relative.norm(), std::max(limit, s) + 1e-12) << limit;
    EXPECT_LE(law.time_to_go_s, params.max_time_to_go_s);
    EXPECT_LE(std::abs(w) * law.time_to_go_s, params.max_predicted_turn_rad + 1e-12);
  }
  params.max_time_to_go_s = 1.0;
  EXPECT_EQ(intercept_velocity(params, ugv, p, s, base, 2.0).time_to_go_s, 1.0);
}

TEST(InterceptVelocity, FiniteForHostileInputs) {
  const InterceptParams params;
  const Vector2d zero = Vector2d::Zero();
  // At the UGV's axis (tau = 0) the lead vanishes.
  const InterceptVelocity origin =
      intercept_velocity(params, driving(0.8, 0.35), Vector3d::Zero(), 1.0, zero, 1.0);
  EXPECT_EQ(origin.fallback, InterceptFallback::None);
  EXPECT_LT(origin.velocity_m_s.norm(), 1e-15);
  // A reference at rest (s = 0): the capped tau, a finite lead within the limit.
  const Vector3d p(3.0, 1.0, 1.0);
  const model::UgvMotion ugv = driving(0.8, 0.35);
  const InterceptVelocity still = intercept_velocity(params, ugv, p, 0.0, eq30(ugv, p, 0.0), 1.0);
  EXPECT_TRUE(still.velocity_m_s.allFinite());
  EXPECT_GT(still.time_to_go_s, 0.0);
  // An absurd but finite speed is clamped, never amplified.
  const InterceptVelocity huge =
      intercept_velocity(params, driving(1e300, 0.35), p, 1.0, eq30(ugv, p, 1.0), 1.0);
  EXPECT_TRUE(huge.velocity_m_s.allFinite());
  EXPECT_TRUE(intercept_velocity(params, driving(0.8, 1e-300), p, 1e-300, zero, 1.0)
                  .velocity_m_s.allFinite());
}

// A point mass with the law as its velocity, against a UGV on a circle, in the world.
// Returns the world path length over the straight line from start to where it met the UGV.
// The law never asks for more than s relative to the UGV's translation: checked every step.
double point_mass_path_ratio(Mode mode, double u, double w, const Vector2d& start, double heading,
                             const InterceptParams& params = InterceptParams{}) {
  const double s = 1.0, dt = 0.01;
  Vector2d uav = start, ugv_position(0.0, 0.0);
  double length = 0.0;
  const model::UgvMotion ugv = driving(u, w);
  for (int i = 0; i < 10000; ++i) {
    const Eigen::Rotation2Dd to_world(heading);
    const Vector2d rel = to_world.inverse() * (uav - ugv_position);
    if (rel.norm() < 0.05) return length / (uav - start).norm();
    const Vector3d p(rel.x(), rel.y(), 1.0);
    Vector2d v = eq30(ugv, p, s);
    if (mode == Mode::Intercept) v = intercept_velocity(params, ugv, p, s, v, s).velocity_m_s;
    EXPECT_LE((v + ugv.angular_velocity_rad_s.cross(p).head<2>()).norm(), s + 1e-9);
    const Vector2d inertial =
        to_world * (v + ugv.angular_velocity_rad_s.cross(p).head<2>() + Vector2d(u, 0.0));
    uav += inertial * dt;
    length += inertial.norm() * dt;
    ugv_position += to_world * Vector2d(u, 0.0) * dt;
    heading += w * dt;
  }
  return kInf;
}

// Eq. 30 copies the UGV's curve (measured 1.009 .. 1.11 on average from these starts); the
// intercept law's world path stays within about 2 % of the straight line on average (it
// re-aims as it goes: tau = |p| / s is not the exact time to go on a circle, and the speed
// limit shortens the lead), and is straight for a straight-driving UGV.
TEST(InterceptVelocity, APointMassFollowingItMeetsATurningUgvOnANearStraightPath) {
  for (const auto& [u, w] : {std::pair{0.5, 0.25}, {0.5, 0.35}, {0.8, 0.35}, {0.8, -0.5}}) {
    double intercept_sum = 0.0, cover_sum = 0.0;
    for (int i = 0; i < 6; ++i) {
      const double bearing = model::kTwoPi * i / 6.0;
      const Vector2d start = 5.0 * Vector2d(std::cos(bearing), std::sin(bearing));
      for (const double heading : {0.0, 2.0, 4.0}) {
        const double intercept = point_mass_path_ratio(Mode::Intercept, u, w, start, heading);
        const double cover = point_mass_path_ratio(Mode::Cover, u, w, start, heading);
        EXPECT_LT(intercept, 1.04) << u << ", " << w << " from " << start.transpose();
        intercept_sum += intercept;
        cover_sum += cover;
      }
    }
    EXPECT_LT(intercept_sum / 18.0, 1.025) << u << ", " << w;
    EXPECT_LT(intercept_sum, cover_sum) << u << ", " << w;
  }
  EXPECT_LT(point_mass_path_ratio(Mode::Intercept, 0.8, 0.0, Vector2d(4, 3), 0.3), 1.0 + 1e-9);
}

// The fastest straight flight against the constant-velocity aim: both re-solved every step,
// the constant-velocity aim bends each time the UGV's turn invalidates its last answer.
TEST(InterceptVelocity, TheFastestStraightFlightMeetsATurningUgvOnAStraighterPath) {
  InterceptParams constant_velocity;
  constant_velocity.fastest_straight_flight = false;
  for (const auto& [u, w] : {std::pair{0.5, 0.35}, {0.8, 0.35}, {0.8, -0.5}}) {
    double fastest_sum = 0.0, constant_sum = 0.0;
    for (int i = 0; i < 6; ++i) {
      const double bearing = model::kTwoPi * i / 6.0;
      const Vector2d start = 5.0 * Vector2d(std::cos(bearing), std::sin(bearing));
      for (const double heading : {0.0, 2.0, 4.0}) {
        fastest_sum += point_mass_path_ratio(Mode::Intercept, u, w, start, heading);
        constant_sum +=
            point_mass_path_ratio(Mode::Intercept, u, w, start, heading, constant_velocity);
      }
    }
    // Measured: 1.0000 / 1.0000 / 1.0030 against 1.0020 / 1.0112 / 1.0184.
    EXPECT_LT(fastest_sum / 18.0, 1.005) << u << ", " << w;
    EXPECT_LT(fastest_sum, constant_sum) << u << ", " << w;
  }
}

// The fastest straight flight: from p along the law's direction, at the fastest speed within
// s of the UGV's velocity at every instant, the UAV meets the UGV at tau (integrated
// finely here), and no earlier tau allows a meeting.
TEST(InterceptVelocity, FlyingTheFastestStraightFlightMeetsTheTurningUgvAtItsTimeToGo) {
  const double u = 0.8, w = 0.35, s = 1.0;
  const model::UgvMotion ugv = driving(u, w);
  for (const Vector3d& p :
       {Vector3d(-1.5, 2.0, 1.5), Vector3d(2.5, 0.0, 1.5), Vector3d(-4.0, -3.0, 1.0)}) {
    const InterceptVelocity law =
        intercept_velocity(InterceptParams{}, ugv, p, s, eq30(ugv, p, s), s);
    ASSERT_EQ(law.fallback, InterceptFallback::None);
    const Vector2d relative = law.velocity_m_s + ugv.angular_velocity_rad_s.cross(p).head<2>();
    EXPECT_NEAR(relative.norm(), s, 1e-9);
    const Vector2d direction = (relative + Vector2d(u, 0.0)).normalized();
    const double tau = law.time_to_go_s;
    Vector2d uav = p.head<2>();
    constexpr int kSteps = 20000;
    for (int i = 0; i < kSteps; ++i) {
      const double t = (i + 0.5) * tau / kSteps;
      uav += fastest_speed_along(direction, ugv_velocity_at(u, w, t), s) * direction * tau / kSteps;
    }
    EXPECT_LT((uav - ugv_mean_velocity(u, w, tau) * tau).norm(), 1e-4) << p.transpose();
    const auto earliest = earliest_fastest_straight_flight(u, w, p.head<2>(), s, 10.0);
    ASSERT_TRUE(earliest.has_value());
    EXPECT_NEAR(earliest->time_to_go_s, tau, 1e-6);  // (its own horizon: another grid)
  }
}

TEST(InterceptVelocity, FastestSpeedAlongARayWithinTheLimit) {
  const Vector2d x = Vector2d::UnitX();
  EXPECT_DOUBLE_EQ(fastest_speed_along(x, Vector2d::Zero(), 1.5), 1.5);
  EXPECT_DOUBLE_EQ(fastest_speed_along(x, Vector2d(1.0, 0.0), 1.5), 2.5);    // with the UGV
  EXPECT_DOUBLE_EQ(fastest_speed_along(x, Vector2d(-1.0, 0.0), 1.5), 0.5);   // head-on
  EXPECT_NEAR(fastest_speed_along(x, Vector2d(0.0, 0.8), 1.0), 0.6, 1e-15);  // abeam
  EXPECT_EQ(fastest_speed_along(x, Vector2d(-2.0, 0.0), 1.5), 0.0);          // outrun: none
  EXPECT_EQ(fastest_speed_along(x, Vector2d(0.0, 2.0), 1.5), 0.0);           // the ray misses
  EXPECT_EQ(fastest_speed_along(x, Vector2d(kNaN, 0.0), 1.5), 0.0);
}

TEST(InterceptVelocity, FastestStraightFlightIsTheConstantVelocityOneForAStraightUgv) {
  // Without turn or acceleration the fastest speed along a line is constant: the same answer.
  for (const Vector2d& p : {Vector2d(3.0, 4.0), Vector2d(-2.0, 1.0), Vector2d(0.5, -3.0)}) {
    const auto flight = earliest_fastest_straight_flight(0.8, 0.0, p, 1.25, 10.0);
    const auto tau = earliest_time_to_go_s(0.8, 0.0, p, 1.25, 10.0);
    ASSERT_TRUE(flight && tau) << p.transpose();
    EXPECT_NEAR(flight->time_to_go_s, *tau, 1e-6) << p.transpose();
    const Vector2d meet(0.8 * *tau, 0.0);
    EXPECT_LT((flight->direction - (meet - p).normalized()).norm(), 1e-6);
  }
  EXPECT_EQ(earliest_fastest_straight_flight(0.8, 0.3, Vector2d::Zero(), 1.0, 6.0)->time_to_go_s,
            0.0);
  EXPECT_FALSE(earliest_fastest_straight_flight(0.8, 0.3, Vector2d(-30.0, 0.0), 0.01, 6.0));
  EXPECT_FALSE(earliest_fastest_straight_flight(kNaN, 0.3, Vector2d(3.0, 1.0), 1.0, 6.0));
  EXPECT_FALSE(earliest_fastest_straight_flight(0.8, 0.3, Vector2d(3.0, 1.0), 1.0, 6.0, kInf));
}

TEST(InterceptVelocity, AChangingTurnGetsTheConstantVelocityAim) {
  InterceptParams fastest, constant_velocity;
  constant_velocity.fastest_straight_flight = false;
  model::UgvMotion ugv = driving(0.8, 0.35);
  const Vector3d p(-3.0, 2.0, 1.0);
  const auto law = [&](const InterceptParams& params) {
    return intercept_velocity(params, ugv, p, 1.0, eq30(ugv, p, 1.0), 1.0).velocity_m_s;
  };
  EXPECT_GT((law(fastest) - law(constant_velocity)).norm(), 1e-3);  // a steady turn
  ugv.angular_acceleration_rad_s2.z() = 2.0 * fastest.fastest_flight_max_yaw_acceleration_rad_s2;
  EXPECT_EQ(law(fastest), law(constant_velocity));
}

SampcInput transition_input(const model::UgvMotion& ugv) {
  SampcInput in;
  in.stage = model::Stage::Transition;
  in.uav_state = model::uav_state_at_rest(Vector3d(1.5, -2.0, 1.2));
  in.ugv = ugv;
  in.speed_limit_m_s = 1.5;
  for (int k = 0; k <= kMaxHorizon; ++k) {
    in.reference.position_m[k] = Vector3d(1.5 - 0.05 * k, -2.0 + 0.08 * k, 1.2);
    in.reference.velocity_m_s[k] = Vector3d(-0.5, 0.8, 0.0);
  }
  return in;
}

TEST(InterceptVelocity, InterceptModeIsCoverWhereverThePredictionIsNotTrusted) {
  SampcParams cover_params;
  cover_params.custom_velocity_nodes = 3;
  // The laws themselves: with the reachable-change limit node 1 of both sits near the UAV's
  // own velocity.
  cover_params.eq30_acceleration_limit_m_s2 = 0.0;
  SampcParams intercept_params = cover_params;
  intercept_params.mode = Mode::Intercept;
  intercept_params.intercept.velocity_nodes = 4;
  model::UgvMotion unknown_speed = driving(0.8, 0.4);
  unknown_speed.speed_source = model::SpeedSource::None;
  const SampcInput in = transition_input(unknown_speed);
  model::UavState predicted[kMaxHorizon + 1];
  for (int k = 0; k <= kMaxHorizon; ++k)
    predicted[k] = model::uav_state_at_rest(Vector3d(1, -1, 1));
  HorizonCost a, b;
  build_horizon_cost(cover_params, in, 0.0, a, {}, 0.0, predicted);
  build_horizon_cost(intercept_params, in, 0.0, b, {}, 0.0, predicted);
  EXPECT_EQ(b.intercept.fallback, InterceptFallback::NoSpeed);
  for (int k = 0; k <= cover_params.horizon_steps; ++k) {
    EXPECT_EQ(a.nodes[k].velocity_ref_m_s, b.nodes[k].velocity_ref_m_s) << k;
    EXPECT_EQ(a.nodes[k].velocity_weight, b.nodes[k].velocity_weight) << k;
    EXPECT_EQ(a.nodes[k].squared_distance_ref_m2, b.nodes[k].squared_distance_ref_m2) << k;
  }
  // With a valid speed the customised nodes lead the UGV; the initial and final stages
  // stay cover's.
  const SampcInput valid = transition_input(driving(0.8, 0.4));
  build_horizon_cost(intercept_params, valid, 0.0, b, {}, 0.0, predicted);
  EXPECT_EQ(b.intercept.fallback, InterceptFallback::None);
  EXPECT_GT(b.intercept.time_to_go_s, 0.0);
  build_horizon_cost(cover_params, valid, 0.0, a, {}, 0.0, predicted);
  for (int k = 0; k <= cover_params.custom_velocity_nodes; ++k) {
    EXPECT_GT((a.nodes[k].velocity_ref_m_s - b.nodes[k].velocity_ref_m_s).norm(), 0.05) << k;
  }
  // ... on its own number of nodes.
  const int last = intercept_params.intercept.velocity_nodes;
  ASSERT_GT(last, cover_params.custom_velocity_nodes);
  EXPECT_GT(b.nodes[last].velocity_weight.x(), 0.0);
  EXPECT_EQ(b.nodes[last + 1].velocity_weight.x(), 0.0);
  EXPECT_EQ(a.nodes[last].velocity_weight.x(), 0.0);
  for (const model::Stage stage : {model::Stage::Initial, model::Stage::Final}) {
    SampcInput tracking = valid;
    tracking.stage = stage;
    build_horizon_cost(cover_params, tracking, 0.0, a);
    build_horizon_cost(intercept_params, tracking, 0.0, b);
    EXPECT_EQ(a.nodes[1].velocity_ref_m_s, b.nodes[1].velocity_ref_m_s);
    EXPECT_EQ(a.nodes[1].position_weight, b.nodes[1].position_weight);
  }
}

// After a frame switch the lead builds up over switch_smoothing_s: the first transition
// solve references exactly cover's velocities, later ones intercept's own.
TEST(InterceptVelocity, TheLeadBuildsUpOverTheSwitchSmoothing) {
  SampcParams cover_params;
  SampcParams intercept_params = cover_params;
  intercept_params.mode = Mode::Intercept;
  Sampc cover(cover_params), intercept(intercept_params);
  SampcInput in = transition_input(driving(0.8, 0.35));
  in.stage = model::Stage::Initial;  // the same cost for both methods before the switch
  for (int step = 0; step < 5; ++step) {
    cover.solve(in);
    intercept.solve(in);
  }
  cover.reset_frame();
  intercept.reset_frame();
  in.stage = model::Stage::Transition;
  const auto velocity_ref_gap = [&] {
    double gap = 0.0;
    for (int k = 1; k <= intercept_params.intercept.velocity_nodes; ++k) {
      gap = std::max(gap, (cover.horizon_cost().nodes[k].velocity_ref_m_s -
                           intercept.horizon_cost().nodes[k].velocity_ref_m_s)
                              .norm());
    }
    return gap;
  };
  cover.solve(in);
  intercept.solve(in);
  EXPECT_LT(velocity_ref_gap(), 1e-12);
  const int smoothing_steps =
      static_cast<int>(std::ceil(cover_params.switch_smoothing_s / cover_params.control_period_s));
  for (int step = 0; step < smoothing_steps; ++step) {
    cover.solve(in);
    intercept.solve(in);
  }
  EXPECT_EQ(intercept.horizon_cost().intercept.fallback, InterceptFallback::None);
  EXPECT_GT(velocity_ref_gap(), 0.05);
}

TEST(InterceptVelocity, ParamsLoadAndRejectBadValuesNamingTheKey) {
  const auto load = [](const std::string& text) {
    config::YamlReader reader(YAML::Load(text), "test:sampc");
    return SampcParams::load(reader);
  };
  const SampcParams p = load("mode: intercept\nintercept: {max_time_to_go_s: 2.5}");
  EXPECT_EQ(p.mode, Mode::Intercept);
  EXPECT_EQ(p.intercept.max_time_to_go_s, 2.5);
  EXPECT_EQ(p.intercept.min_ugv_speed_m_s, InterceptParams{}.min_ugv_speed_m_s);
  EXPECT_THROW(load("intercept: {max_time_to_go: 2.5}"), config::ConfigError);
  for (const char* bad :
       {"intercept: {min_ugv_speed_m_s: -1}", "intercept: {max_ugv_yaw_rate_rad_s: 0}",
        "intercept: {max_time_to_go_s: .nan}", "intercept: {max_predicted_turn_rad: 7}",
        "intercept: {velocity_nodes: 21}", "intercept: {velocity_nodes: 0}",
        "intercept: {max_ugv_acceleration_m_s2: -0.1}",
        "intercept: {max_ugv_acceleration_m_s2: .inf}",
        "intercept: {fastest_flight_max_yaw_acceleration_rad_s2: -1}"}) {
    try {
      load(bad);
      ADD_FAILURE() << bad;
    } catch (const config::ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("sampc.intercept."), std::string::npos) << e.what();
    }
  }
  // The shipped file's intercept section: SampcParams.ShippedConfigLoadsAndEqualsTheDefaults.
  EXPECT_EQ(parse_mode("intercept"), Mode::Intercept);
  EXPECT_EQ(mode_names(" | "), "cover | no-ref-vxy | coni-mpc | intercept");
}

}  // namespace
}  // namespace cover::sampc
