#include <gtest/gtest.h>

#include <cmath>
#include <deque>

#include "cover/sim/world.hpp"
#include "cover/vocabulary/angles.hpp"
#include "test_worlds.hpp"

namespace cover::sim {
namespace {

const QuadrotorCommand kIdle{};

TEST(UgvImu, AtRestReadsGravityRawAndFiltered) {
  WorldParams params = test::noiseless_world({test::stationary_at(1.0, -2.0, 0.7)});
  World world(params);
  world.advance(kIdle, 1.0);
  const ImuReading& reading = world.imu_sensor().latest(0);
  const Eigen::Vector3d gravity(0.0, 0.0, params.gravity_m_s2);
  EXPECT_LT((reading.raw.specific_force_m_s2 - gravity).norm(), 1e-12);
  EXPECT_LT((reading.filtered.specific_force_m_s2 - gravity).norm(), 1e-12);
  EXPECT_LT(reading.filtered.angular_velocity_rad_s.norm(), 1e-12);
  EXPECT_LT(reading.filtered.angular_acceleration_rad_s2.norm(), 1e-12);
}

TEST(UgvImu, NoisyImuAtRestAveragesToGravityPlusBias) {
  WorldParams params = test::noiseless_world({test::stationary_at(0.0, 0.0)});
  params.imu.specific_force_noise_m_s2 = 0.05;
  World world(params);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int count = 0;
  for (int i = 0; i < 5000; ++i) {
    world.step(kIdle);
    if (world.state().step_index % 5 == 0) {
      sum += world.imu_sensor().latest(0).raw.specific_force_m_s2;
      ++count;
    }
  }
  EXPECT_EQ(count, 1000);  // 200 Hz over 5 s
  EXPECT_LT((sum / count - Eigen::Vector3d(0, 0, 9.81)).norm(), 0.01);
}

TEST(UgvImu, CircleReadsCentripetalAccelerationInBodyY) {
  const double v = 0.8, w = 0.5;
  World world(test::noiseless_world({test::circle(v, w)}));
  world.advance(kIdle, 3.0);  // past the filter's transient
  const ImuReading& reading = world.imu_sensor().latest(0);
  EXPECT_NEAR(reading.raw.specific_force_m_s2.x(), 0.0, 1e-9);
  EXPECT_NEAR(reading.raw.specific_force_m_s2.y(), v * w, 1e-9);  // turning left: +y
  EXPECT_NEAR(reading.raw.specific_force_m_s2.z(), 9.81, 1e-9);
  EXPECT_NEAR(reading.raw.angular_velocity_rad_s.z(), w, 1e-12);
  EXPECT_NEAR(reading.filtered.specific_force_m_s2.y(), v * w, 1e-6);
  EXPECT_NEAR(reading.filtered.angular_velocity_rad_s.z(), w, 1e-6);
  EXPECT_NEAR(reading.filtered.angular_acceleration_rad_s2.z(), 0.0, 1e-6);
}

// The estimate is the truth seen through the filters' lag (the gyro's and the angular
// acceleration's first-order time constants): compared with the truth that much earlier,
// it must follow the signal.
TEST(UgvImu, FilteredAngularAccelerationTracksFigureEight) {
  UgvMotionPatternParams eight;
  eight.kind = MotionPatternKind::FigureEight;
  eight.speed_m_s = 0.8;
  eight.half_length_m = 2.5;
  eight.half_width_m = 1.2;
  const WorldParams params = test::noiseless_world({eight});
  World world(params);
  const auto time_constant_s = [](double cutoff_hz) {
    return 1.0 / (2.0 * model::kPi * cutoff_hz);
  };
  const double lag_s = time_constant_s(params.imu_filter.angular_velocity_cutoff_hz) +
                       time_constant_s(params.imu_filter.angular_acceleration_cutoff_hz);
  const int lag_steps = static_cast<int>(std::lround(lag_s * params.physics_rate_hz));
  world.advance(kIdle, 5.0);
  std::deque<double> truth_history;
  double worst = 0.0, peak = 0.0;
  for (int i = 0; i < 10000; ++i) {
    world.step(kIdle);
    truth_history.push_back(world.state().ugvs[0].yaw_acceleration_rad_s2);
    if (static_cast<int>(truth_history.size()) <= lag_steps) continue;
    truth_history.pop_front();
    const double lagged_truth = truth_history.front();
    const auto& filtered = world.imu_sensor().latest(0).filtered;
    worst = std::max(worst, std::abs(filtered.angular_acceleration_rad_s2.z() - lagged_truth));
    peak = std::max(peak, std::abs(lagged_truth));
  }
  EXPECT_GT(peak, 0.05);
  EXPECT_LT(worst, 0.25 * peak);
}

}  // namespace
}  // namespace cover::sim

namespace cover::sim {
namespace {

TEST(UgvImu, CorruptedSamplesAreRejectedAndTheFilteredOutputStaysFinite) {
  WorldParams params = test::noiseless_world({test::circle(0.5, 0.35)});
  params.imu.fault_probability = 0.3;
  World world(params);
  int rejected = 0;
  for (int i = 0; i < 5000; ++i) {
    world.step(QuadrotorCommand{});
    if (world.state().step_index % 5 != 0) continue;
    const ImuReading& reading = world.imu_sensor().latest(0);
    rejected += reading.status == ugv::ImuFilterStatus::RejectedNonFinite;
    EXPECT_TRUE(reading.filtered.angular_velocity_rad_s.allFinite());
    EXPECT_TRUE(reading.filtered.angular_acceleration_rad_s2.allFinite());
  }
  EXPECT_GT(rejected, 200);  // ~30 % of 1000 samples
  EXPECT_NEAR(world.imu_sensor().latest(0).filtered.angular_velocity_rad_s.z(), 0.35, 1e-3);
}

}  // namespace
}  // namespace cover::sim
