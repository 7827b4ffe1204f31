#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <random>

#include "cover/test/scratch_dir.hpp"
#include "cover/ugv/imu_filter.hpp"
#include "cover/vocabulary/angles.hpp"

namespace cover::ugv {
namespace {

ImuSample sample_at(double t, const Eigen::Vector3d& force, const Eigen::Vector3d& rate) {
  ImuSample s;
  s.stamp_s = t;
  s.specific_force_m_s2 = force;
  s.angular_velocity_rad_s = rate;
  return s;
}

const Eigen::Vector3d kGravity(0.0, 0.0, 9.81);

TEST(ImuFilter, FirstSampleSeedsTheOutput) {
  ImuFilter filter;
  EXPECT_FALSE(filter.has_output());
  EXPECT_EQ(filter.update(sample_at(0.0, kGravity, Eigen::Vector3d(0, 0, 0.3))),
            ImuFilterStatus::Started);
  EXPECT_TRUE(filter.has_output());
  EXPECT_EQ(filter.output().specific_force_m_s2, kGravity);
  EXPECT_EQ(filter.output().angular_velocity_rad_s.z(), 0.3);
}

TEST(ImuFilter, RejectsNanAndKeepsLastGoodOutput) {
  ImuFilter filter;
  filter.update(sample_at(0.0, kGravity, Eigen::Vector3d::Zero()));
  filter.update(sample_at(0.005, kGravity, Eigen::Vector3d(0, 0, 0.1)));
  const FilteredImu before = filter.output();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(filter.update(sample_at(0.010, Eigen::Vector3d(nan, 0, 9.81), Eigen::Vector3d::Zero())),
            ImuFilterStatus::RejectedNonFinite);
  EXPECT_EQ(filter.update(sample_at(0.010, kGravity, Eigen::Vector3d(0, nan, 0))),
            ImuFilterStatus::RejectedNonFinite);
  EXPECT_EQ(filter.update(sample_at(nan, kGravity, Eigen::Vector3d::Zero())),
            ImuFilterStatus::RejectedNonFinite);
  EXPECT_EQ(filter.output().stamp_s, before.stamp_s);
  EXPECT_EQ(filter.output().specific_force_m_s2, before.specific_force_m_s2);
  EXPECT_EQ(filter.output().angular_velocity_rad_s, before.angular_velocity_rad_s);
  EXPECT_EQ(filter.output().angular_acceleration_rad_s2, before.angular_acceleration_rad_s2);
  EXPECT_TRUE(filter.output().angular_acceleration_rad_s2.allFinite());
  // and it carries on normally afterwards
  EXPECT_EQ(filter.update(sample_at(0.015, kGravity, Eigen::Vector3d::Zero())),
            ImuFilterStatus::Updated);
}

TEST(ImuFilter, RejectsZeroNegativeDtAndOutOfRange) {
  ImuFilter filter;
  filter.update(sample_at(1.0, kGravity, Eigen::Vector3d::Zero()));
  EXPECT_EQ(filter.update(sample_at(1.0, kGravity, Eigen::Vector3d::Zero())),
            ImuFilterStatus::RejectedStaleStamp);
  EXPECT_EQ(filter.update(sample_at(0.9, kGravity, Eigen::Vector3d::Zero())),
            ImuFilterStatus::RejectedStaleStamp);
  EXPECT_EQ(filter.update(sample_at(1.005, Eigen::Vector3d(0, 0, 1e4), Eigen::Vector3d::Zero())),
            ImuFilterStatus::RejectedOutOfRange);
  EXPECT_EQ(filter.update(sample_at(1.005, kGravity, Eigen::Vector3d(0, 0, 100.0))),
            ImuFilterStatus::RejectedOutOfRange);
  EXPECT_EQ(filter.output().specific_force_m_s2, kGravity);
}

TEST(ImuFilter, RestartsAfterALongGap) {
  ImuFilter filter;
  filter.update(sample_at(0.0, kGravity, Eigen::Vector3d::Zero()));
  const Eigen::Vector3d tilted(1.0, 0.0, 9.7);
  EXPECT_EQ(filter.update(sample_at(5.0, tilted, Eigen::Vector3d::Zero())),
            ImuFilterStatus::RestartedAfterGap);
  EXPECT_EQ(filter.output().specific_force_m_s2, tilted);
}

TEST(ImuFilter, StepResponseMatchesFirstOrderCutOffDespiteJitter) {
  ImuFilterParams params;
  params.specific_force_cutoff_hz = 10.0;
  ImuFilter filter(params);
  filter.update(sample_at(0.0, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()));
  const double tau = 1.0 / (cover::model::kTwoPi * 10.0);
  // jittered 200 Hz stamps: 3, 7, 5, 3, 7, ... ms
  const double periods[] = {0.003, 0.007, 0.005};
  double t = 0.0;
  for (int i = 0; t < tau - 1e-12; ++i) {
    const double next = std::min(t + periods[i % 3], tau);
    filter.update(sample_at(next, Eigen::Vector3d(1, 1, 1), Eigen::Vector3d::Zero()));
    t = next;
  }
  // a first-order lag reaches 1 - 1/e after one time constant, whatever the sampling
  EXPECT_NEAR(filter.output().specific_force_m_s2.x(), 1.0 - std::exp(-1.0), 1e-12);
}

TEST(ImuFilter, AngularAccelerationOfARampIsItsSlope) {
  ImuFilter filter;
  const double slope = 0.8;  // rad/s^2
  for (int i = 0; i <= 400; ++i) {
    const double t = 0.005 * i;
    filter.update(sample_at(t, kGravity, Eigen::Vector3d(0, 0, slope * t)));
  }
  EXPECT_NEAR(filter.output().angular_acceleration_rad_s2.z(), slope, 1e-3);
}

// The angular acceleration's noise is what the controller feels (beta x p over the
// horizon, docs/benchmarks.md Fig. 8): the simulated gyro's white noise (0.005 rad/s at
// 200 Hz, config/sim/world_default.yaml) turning at a steady 0.5 rad/s must leave beta
// within 0.02 rad/s^2 (1-sigma) with the shipped cut-offs; a 5 Hz cut-off leaves 0.064.
TEST(ImuFilter, ShippedCutOffsKeepTheGyroNoiseOutOfTheAngularAcceleration) {
  ImuFilter filter(ImuFilterParams::load_default());
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.005);
  double sum_squares = 0.0;
  int count = 0;
  for (int i = 0; i < 4000; ++i) {
    const Eigen::Vector3d rate(noise(rng), noise(rng), 0.5 + noise(rng));
    filter.update(sample_at(0.005 * i, kGravity, rate));
    if (i >= 1000) {  // settled
      sum_squares += filter.output().angular_acceleration_rad_s2.squaredNorm() / 3.0;
      ++count;
    }
  }
  EXPECT_LT(std::sqrt(sum_squares / count), 0.02);
}

TEST(ImuFilter, ParamsRejectNonPositiveCutOff) {
  ImuFilterParams params;
  params.angular_acceleration_cutoff_hz = 0.0;
  EXPECT_THROW(params.validate(), cover::config::ConfigError);
}

TEST(ImuFilterParams, LoadFileReadsTheAgentSection) {
  const std::string path = cover::test::scratch_path("imu_filter_params.yaml");
  std::ofstream(path) << "ugv_agent:\n  status_rate_hz: 2\n  imu_filter:\n"
                         "    specific_force_cutoff_hz: 20\n";
  EXPECT_EQ(ImuFilterParams::load_file(path).specific_force_cutoff_hz, 20.0);
  std::ofstream(path) << "ugv_agent:\n  imu_filter:\n    cutoff_hz: 20\n";
  EXPECT_THROW(ImuFilterParams::load_file(path), cover::config::ConfigError);
  std::ofstream(path) << "imu_filter:\n  specific_force_cutoff_hz: 20\n";
  EXPECT_THROW(ImuFilterParams::load_file(path), cover::config::ConfigError);
  EXPECT_NO_THROW(ImuFilterParams::load_default());
}

}  // namespace
}  // namespace cover::ugv
