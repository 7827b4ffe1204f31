#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "cover/sim/world.hpp"
#include "cover/ugv/speed_estimator.hpp"
#include "cover/ugv/ugv_sensor_pipeline.hpp"

namespace cover::ugv {
namespace {

using model::SpeedSource;

constexpr double kDt_s = 0.005;  // 200 Hz
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// A filtered IMU output of a vehicle driving at `speed` with `yaw_rate` (no side slip).
FilteredImu turning(double stamp_s, double speed_m_s, double yaw_rate_rad_s) {
  FilteredImu imu;
  imu.stamp_s = stamp_s;
  imu.specific_force_m_s2 = {0.0, speed_m_s * yaw_rate_rad_s, 9.81};
  imu.angular_velocity_rad_s = {0.0, 0.0, yaw_rate_rad_s};
  return imu;
}

// Feeds `seconds` of IMU outputs from `t0` at 200 Hz; returns the next stamp.
double drive(SpeedEstimator& estimator, double t0_s, double seconds, double speed_m_s,
             double yaw_rate_rad_s) {
  const int n = static_cast<int>(std::lround(seconds / kDt_s));
  for (int i = 0; i < n; ++i) {
    EXPECT_EQ(estimator.update_imu(turning(t0_s + i * kDt_s, speed_m_s, yaw_rate_rad_s)),
              SpeedSampleStatus::Accepted);
  }
  return t0_s + n * kDt_s;
}

TEST(SpeedEstimator, StartsWithoutAnEstimate) {
  SpeedEstimator estimator;
  EXPECT_EQ(estimator.estimate().source, SpeedSource::None);
  EXPECT_FALSE(estimator.estimate().valid());
}

TEST(SpeedEstimator, NoisyOdometryIsLowPassedAndPreferred) {
  SpeedEstimator estimator;
  std::mt19937_64 rng(5);
  std::normal_distribution<double> noise(0.0, 0.05);
  double worst = 0.0;
  for (int i = 0; i < 1000; ++i) {
    const double t = i * kDt_s;
    if (i % 4 == 0) {
      EXPECT_EQ(estimator.update_odometry({t, 0.6 + noise(rng)}), SpeedSampleStatus::Accepted);
    }
    // The IMU disagrees (0.9 m/s): fresh odometry wins.
    estimator.update_imu(turning(t, 0.9, 0.5));
    if (i > 100) worst = std::max(worst, std::abs(estimator.estimate().speed_m_s - 0.6));
    EXPECT_EQ(estimator.estimate().source, SpeedSource::WheelOdometry);
  }
  // One sample's noise is 0.05; the 5 Hz low-pass at 50 Hz leaves ~0.55 of it (sigma 0.028).
  EXPECT_LT(worst, 0.12);
}

TEST(SpeedEstimator, StaleOdometryFallsBackToTheImuOrNothing) {
  SpeedEstimator estimator;
  estimator.update_odometry({0.0, 0.7});
  estimator.update_imu(turning(0.1, 0.7, 0.0));
  EXPECT_EQ(estimator.estimate().source, SpeedSource::WheelOdometry);
  // 0.2 s later the wheel speed is stale; driving straight, the IMU has nothing either.
  estimator.update_imu(turning(0.21, 0.7, 0.0));
  EXPECT_EQ(estimator.estimate().source, SpeedSource::None);
  EXPECT_EQ(estimator.estimate().speed_m_s, 0.0);
  // Turning long enough, the IMU takes over.
  drive(estimator, 0.3, 1.5, 0.7, 0.4);
  EXPECT_EQ(estimator.estimate().source, SpeedSource::Imu);
  EXPECT_NEAR(estimator.estimate().speed_m_s, 0.7, 1e-9);
  // Odometry after a gap restarts from its sample (no blend with the old 0.7).
  estimator.update_odometry({2.0, 0.3});
  EXPECT_EQ(estimator.estimate().source, SpeedSource::WheelOdometry);
  EXPECT_EQ(estimator.estimate().speed_m_s, 0.3);
}

TEST(SpeedEstimator, ImuSpeedNeedsASteadyTurn) {
  SpeedEstimator estimator;
  double t = drive(estimator, 0.0, 0.9, 0.8, 0.5);
  EXPECT_EQ(estimator.estimate().source, SpeedSource::None);  // not settled yet
  t = drive(estimator, t, 0.2, 0.8, 0.5);
  EXPECT_EQ(estimator.estimate().source, SpeedSource::Imu);
  EXPECT_NEAR(estimator.estimate().speed_m_s, 0.8, 1e-9);
  // Straight (yaw rate below the threshold): invalid at once.
  t = drive(estimator, t, 0.05, 0.8, 0.1);
  EXPECT_EQ(estimator.estimate().source, SpeedSource::None);
  // Turning again: another full settle time.
  t = drive(estimator, t, 0.5, 0.8, -0.5);
  EXPECT_EQ(estimator.estimate().source, SpeedSource::None);
  drive(estimator, t, 0.6, 0.8, -0.5);
  EXPECT_EQ(estimator.estimate().source, SpeedSource::Imu);
  EXPECT_NEAR(estimator.estimate().speed_m_s, 0.8, 1e-9);  // right turn, same speed
}

TEST(SpeedEstimator, JumpyRatioIsNotASpeed) {
  SpeedEstimator estimator;
  // Lateral force alternating +-0.4 m/s^2 around 0.8 * 0.5 (bumps, slip): ratio +-0.8 m/s.
  for (int i = 0; i < 600; ++i) {
    FilteredImu imu = turning(i * kDt_s, 0.8, 0.5);
    imu.specific_force_m_s2.y() += (i % 2 == 0 ? 0.4 : -0.4);
    estimator.update_imu(imu);
  }
  EXPECT_EQ(estimator.estimate().source, SpeedSource::None);
}

TEST(SpeedEstimator, ReversingIsReportedNegative) {
  SpeedEstimator from_imu;
  drive(from_imu, 0.0, 2.0, -0.5, 0.3);  // reversing while turning: a_y = u r < 0
  EXPECT_EQ(from_imu.estimate().source, SpeedSource::Imu);
  EXPECT_NEAR(from_imu.estimate().speed_m_s, -0.5, 1e-9);

  SpeedEstimator from_wheels;
  from_wheels.update_odometry({0.0, -0.4});
  EXPECT_EQ(from_wheels.estimate().source, SpeedSource::WheelOdometry);
  EXPECT_EQ(from_wheels.estimate().speed_m_s, -0.4);
}

TEST(SpeedEstimator, BadSamplesAreRejectedWithAStatusAndChangeNothing) {
  SpeedEstimator estimator;
  estimator.update_odometry({1.0, 0.5});
  const SpeedEstimate before = estimator.estimate();
  EXPECT_EQ(estimator.update_odometry({1.01, kNaN}), SpeedSampleStatus::RejectedNonFinite);
  EXPECT_EQ(estimator.update_odometry({kInf, 0.5}), SpeedSampleStatus::RejectedNonFinite);
  EXPECT_EQ(estimator.update_odometry({1.02, -kInf}), SpeedSampleStatus::RejectedNonFinite);
  EXPECT_EQ(estimator.update_odometry({1.03, 50.0}), SpeedSampleStatus::RejectedOutOfRange);
  EXPECT_EQ(estimator.update_odometry({1.0, 0.6}), SpeedSampleStatus::RejectedStaleStamp);
  EXPECT_EQ(estimator.update_odometry({0.5, 0.6}), SpeedSampleStatus::RejectedStaleStamp);

  FilteredImu bad = turning(1.05, 0.5, 0.5);
  bad.specific_force_m_s2.y() = kNaN;
  EXPECT_EQ(estimator.update_imu(bad), SpeedSampleStatus::RejectedNonFinite);
  bad = turning(kNaN, 0.5, 0.5);
  EXPECT_EQ(estimator.update_imu(bad), SpeedSampleStatus::RejectedNonFinite);
  EXPECT_EQ(estimator.update_imu(turning(1.05, 0.5, 0.5)), SpeedSampleStatus::Accepted);
  EXPECT_EQ(estimator.update_imu(turning(1.05, 0.5, 0.5)), SpeedSampleStatus::RejectedStaleStamp);
  EXPECT_EQ(estimator.estimate().speed_m_s, before.speed_m_s);
  EXPECT_EQ(estimator.estimate().source, SpeedSource::WheelOdometry);
  EXPECT_TRUE(std::isfinite(estimator.estimate().speed_m_s));
  EXPECT_STREQ(to_string(SpeedSampleStatus::RejectedOutOfRange),
               "rejected: speed beyond max_speed_m_s");
}

TEST(SpeedEstimator, ImplausibleImuRatioIsNotAnEstimate) {
  SpeedEstimator estimator;
  // 12 m/s from a_y / yaw_rate: beyond max_speed_m_s (a tilted or sliding vehicle).
  drive(estimator, 0.0, 2.0, 12.0, 0.5);
  EXPECT_EQ(estimator.estimate().source, SpeedSource::None);
}

TEST(SpeedEstimator, PipelineFeedsOdometryThenFilterThenImu) {
  UgvSensorPipeline pipeline;
  ImuSample sample;
  sample.stamp_s = 0.0;
  sample.specific_force_m_s2 = {0.0, 0.4, 9.81};
  sample.angular_velocity_rad_s = {0.0, 0.0, 0.5};
  sample.wheel_speed_m_s = 0.8;
  const UgvSensorResult first = pipeline.update(sample);
  EXPECT_EQ(first.imu_status, ImuFilterStatus::Started);
  EXPECT_EQ(first.odometry_status, SpeedSampleStatus::Accepted);
  EXPECT_EQ(pipeline.speed().estimate().source, SpeedSource::WheelOdometry);
  sample.stamp_s = 0.005;
  sample.wheel_speed_m_s = kNaN;
  const UgvSensorResult second = pipeline.update(sample);
  EXPECT_EQ(second.odometry_status, SpeedSampleStatus::RejectedNonFinite);
  EXPECT_EQ(second.imu_status, ImuFilterStatus::Updated);
  EXPECT_EQ(pipeline.speed().estimate().speed_m_s, 0.8);
}

TEST(SpeedEstimatorParams, LoadRejectsUnknownKeysAndValidateNamesTheKey) {
  YAML::Node node = YAML::Load("{odometry_timeout_s: 0.3, imu_settle: 1}");
  config::YamlReader reader(node, "test");
  EXPECT_THROW(SpeedEstimatorParams::load(reader), config::ConfigError);
  SpeedEstimatorParams p;
  p.imu_min_yaw_rate_rad_s = 0.0;
  try {
    p.validate("ugv_agent.speed_estimator");
    FAIL() << "expected a ConfigError";
  } catch (const config::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("ugv_agent.speed_estimator.imu_min_yaw_rate_rad_s"),
              std::string::npos)
        << e.what();
  }
  p = {};
  p.max_speed_m_s = kNaN;
  EXPECT_THROW(p.validate(), config::ConfigError);
}

// The IMU-derived estimate on the paper's circles, through the simulator's IMU model
// (noise and per-UGV bias) and the agent's filter: error against the true speed over
// seeds, with and without wheel odometry.
struct CircleError {
  double rms_m_s = 0.0;
  double worst_m_s = 0.0;
  double valid_fraction = 0.0;
};

CircleError measure_on_circle(double speed_m_s, double yaw_rate_rad_s, bool odometry) {
  double sum_sq = 0.0, worst = 0.0;
  int n = 0, samples = 0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    sim::WorldParams params;
    params.seed = seed;
    sim::UgvParams ugv;
    ugv.pattern.kind = sim::MotionPatternKind::Circle;
    ugv.pattern.speed_m_s = speed_m_s;
    ugv.pattern.yaw_rate_rad_s = yaw_rate_rad_s;
    ugv.has_wheel_odometry = odometry;
    params.ugvs.push_back(ugv);
    params.uav_initial.start_on_ugv = -1;
    sim::World world(params);
    for (int i = 0; i < 10000; ++i) {  // 10 s; measured after the first 2 s
      world.step(cover::sim::QuadrotorCommand{});
      if (i < 2000 || world.state().step_index % 5 != 0) continue;
      const SpeedEstimate& estimate = world.imu_sensor().latest(0).speed;
      ++samples;
      if (!estimate.valid()) continue;
      const double error = estimate.speed_m_s - speed_m_s;
      sum_sq += error * error;
      worst = std::max(worst, std::abs(error));
      ++n;
    }
  }
  return {n > 0 ? std::sqrt(sum_sq / n) : kNaN, worst, static_cast<double>(n) / samples};
}

TEST(SpeedEstimator, ErrorOnThePaperCirclesWithAndWithoutOdometry) {
  const struct {
    double v, w;
  } settings[] = {{0.5, 0.25}, {0.5, 0.35}, {0.5, 0.5}, {0.8, 0.25}, {0.8, 0.35}, {0.8, 0.5}};
  for (const auto& s : settings) {
    const CircleError imu = measure_on_circle(s.v, s.w, false);
    const CircleError wheels = measure_on_circle(s.v, s.w, true);
    std::printf(
        "circle v %.2f m/s w %.2f rad/s: IMU rms %.3f worst %.3f valid %.2f | "
        "odometry rms %.3f worst %.3f valid %.2f\n",
        s.v, s.w, imu.rms_m_s, imu.worst_m_s, imu.valid_fraction, wheels.rms_m_s, wheels.worst_m_s,
        wheels.valid_fraction);
    // Always valid on a steady circle.
    EXPECT_EQ(imu.valid_fraction, 1.0);
    EXPECT_EQ(wheels.valid_fraction, 1.0);
    // Bias-dominated: 0.02 m/s^2 / w rms (0.08 m/s at 0.25 rad/s) plus noise.
    EXPECT_LT(imu.rms_m_s, 1.5 * 0.02 / s.w + 0.02);
    // Scale error 1 % and 0.02 m/s noise, low-passed.
    EXPECT_LT(wheels.rms_m_s, 0.03);
  }
}

}  // namespace
}  // namespace cover::ugv
