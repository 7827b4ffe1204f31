#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "cover/sim/world.hpp"
#include "test_worlds.hpp"

namespace cover::sim {
namespace {

const QuadrotorCommand kIdle{};

TEST(UgvOdometry, NoiselessCircleReadsTheSpeedAtItsRateOnImuSamples) {
  World world(test::noiseless_world({test::circle(0.8, 0.5)}));
  int odometry_samples = 0;
  for (int i = 0; i < 1000; ++i) {
    world.step(kIdle);
    const auto wheel = world.odometry_sensor().sampled_now(0);
    if (!wheel) continue;
    ++odometry_samples;
    EXPECT_NEAR(*wheel, 0.8, 1e-12);
    // Delivered with the IMU sample of the same step.
    const ImuReading& reading = world.imu_sensor().latest(0);
    EXPECT_EQ(reading.raw.stamp_s, world.state().time_s);
    ASSERT_TRUE(reading.raw.wheel_speed_m_s.has_value());
    EXPECT_EQ(*reading.raw.wheel_speed_m_s, *wheel);
  }
  EXPECT_EQ(odometry_samples, 50);  // 50 Hz over 1 s
  const ImuReading& reading = world.imu_sensor().latest(0);
  EXPECT_EQ(reading.speed.source, model::SpeedSource::WheelOdometry);
  EXPECT_NEAR(reading.speed.speed_m_s, 0.8, 1e-9);
}

TEST(UgvOdometry, NoiseAndScaleErrorAreSeededAndBounded) {
  WorldParams params = test::noiseless_world({test::circle(0.5, 0.35)});
  params.odometry.speed_noise_m_s = 0.02;
  params.odometry.scale_error_sigma = 0.01;
  World first(params), second(params);
  double sum = 0.0, sum_sq = 0.0;
  int n = 0;
  std::vector<double> estimates;
  for (int i = 0; i < 20000; ++i) {
    first.step(kIdle);
    second.step(kIdle);
    const auto a = first.odometry_sensor().sampled_now(0);
    ASSERT_EQ(a, second.odometry_sensor().sampled_now(0));
    if (!a) continue;
    sum += *a;
    sum_sq += *a * *a;
    ++n;
    estimates.push_back(first.imu_sensor().latest(0).speed.speed_m_s);
  }
  const double mean = sum / n;
  const double sigma = std::sqrt(sum_sq / n - mean * mean);
  EXPECT_NEAR(mean, 0.5, 0.5 * 0.04);  // scale error: 4 sigma
  EXPECT_GT(mean, 0.0);
  EXPECT_NEAR(sigma, 0.02, 0.003);
  // The low-passed estimate spreads less than one sample: 5 Hz at 50 Hz leaves ~0.55.
  double estimate_sq = 0.0;
  for (double e : estimates) estimate_sq += (e - mean) * (e - mean);
  EXPECT_LT(std::sqrt(estimate_sq / n), 0.7 * sigma);
}

TEST(UgvOdometry, WorldWithoutOdometryFallsBackToTheImuWhileTurning) {
  WorldParams params = test::noiseless_world({test::circle(0.8, 0.5), test::stationary_at(5, 0)});
  for (UgvParams& ugv : params.ugvs) ugv.has_wheel_odometry = false;
  World world(params);
  world.advance(kIdle, 3.0);
  EXPECT_FALSE(world.odometry_sensor().has_odometry(0));
  EXPECT_FALSE(world.imu_sensor().latest(0).raw.wheel_speed_m_s.has_value());
  const ugv::SpeedEstimate& turning = world.imu_sensor().latest(0).speed;
  EXPECT_EQ(turning.source, model::SpeedSource::Imu);
  EXPECT_NEAR(turning.speed_m_s, 0.8, 1e-6);
  // Standing still (no yaw rate) and no odometry: no estimate.
  EXPECT_EQ(world.imu_sensor().latest(1).speed.source, model::SpeedSource::None);
}

TEST(UgvOdometry, ReversingReadsNegative) {
  UgvMotionPatternParams line;
  line.kind = MotionPatternKind::BackAndForth;
  line.speed_m_s = 0.8;
  line.half_length_m = 2.0;
  World world(test::noiseless_world({line}));
  double lowest = 0.0, highest = 0.0;
  for (int i = 0; i < 30000; ++i) {
    world.step(kIdle);
    const UgvState& ugv = world.state().ugvs[0];
    if (const auto wheel = world.odometry_sensor().sampled_now(0)) {
      EXPECT_NEAR(*wheel, true_forward_speed_m_s(ugv), 1e-12);
      lowest = std::min(lowest, *wheel);
      highest = std::max(highest, *wheel);
    }
  }
  EXPECT_GT(highest, 0.7);
  // back_and_forth keeps its heading and reverses (its yaw does not turn round).
  EXPECT_LT(lowest, -0.7);
}

TEST(UgvOdometry, RateMustDivideTheImuRate) {
  WorldParams params = test::noiseless_world({test::circle(0.8, 0.5)});
  params.odometry.rate_hz = 30.0;
  try {
    params.validate();
    FAIL() << "expected a ConfigError";
  } catch (const config::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("odometry.rate_hz"), std::string::npos) << e.what();
  }
  params.odometry.rate_hz = 50.0;
  params.odometry.speed_noise_m_s = -1.0;
  EXPECT_THROW(params.validate(), config::ConfigError);
}

}  // namespace
}  // namespace cover::sim
