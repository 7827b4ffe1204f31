// The UAV's firmware-facing sensors: IMU, barometer, magnetometer, at their own rates.
#include "cover/sim/uav_sensor_suite.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "cover/config/yaml_reader.hpp"
#include "cover/vocabulary/world_state.hpp"

namespace cover::sim {
namespace {

constexpr double kG = 9.81;

UavSensorParams noiseless() {
  UavSensorParams p;
  p.imu.specific_force_noise_m_s2 = 0.0;
  p.imu.angular_velocity_noise_rad_s = 0.0;
  p.imu.specific_force_bias_sigma_m_s2 = 0.0;
  p.imu.angular_velocity_bias_sigma_rad_s = 0.0;
  p.barometer.pressure_noise_pa = 0.0;
  p.magnetometer.noise_gauss = 0.0;
  p.magnetometer.bias_sigma_gauss = 0.0;
  return p;
}

QuadrotorState at_rest(double yaw_rad = 0.0, double z_m = 0.0) {
  QuadrotorState s;
  s.position_m = Vec3(1.0, 2.0, z_m);
  s.attitude = Quat(yaw_quaternion(yaw_rad));
  return s;
}

TEST(UavSensorSuite, EachSensorSamplesAtItsOwnRate) {
  // 1 kHz physics: IMU 250 Hz every 4 steps, magnetometer 100 Hz every 10, baro 50 Hz every 20.
  UavSensorSuite suite(UavSensorParams{}, 1000.0, kG, 1);
  EXPECT_EQ(suite.imu_period_steps(), 4u);
  EXPECT_EQ(suite.magnetometer_period_steps(), 10u);
  EXPECT_EQ(suite.barometer_period_steps(), 20u);
  int imu = 0, mag = 0, baro = 0;
  for (std::uint64_t step = 1; step <= 1000; ++step) {
    const UavSensorFrame f = suite.update(step, step * 1e-3, at_rest(), Eigen::Vector3d::Zero());
    imu += f.imu ? 1 : 0;
    mag += f.magnetometer ? 1 : 0;
    baro += f.barometer ? 1 : 0;
    if (f.imu) EXPECT_DOUBLE_EQ(f.imu->stamp_s, step * 1e-3);
  }
  EXPECT_EQ(imu, 250);
  EXPECT_EQ(mag, 100);
  EXPECT_EQ(baro, 50);
}

TEST(UavSensorSuite, RateThatDoesNotDivideThePhysicsRateIsRejected) {
  UavSensorParams p;
  p.imu.rate_hz = 300.0;  // 1000 / 300 is not whole
  try {
    UavSensorSuite suite(p, 1000.0, kG, 1);
    FAIL() << "accepted 300 Hz at 1 kHz";
  } catch (const config::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("uav_sensors.imu.rate_hz"), std::string::npos) << e.what();
  }
  p.imu.rate_hz = 200.0;
  EXPECT_NO_THROW(UavSensorSuite(p, 1000.0, kG, 1));
}

TEST(UavImu, AtRestReadsGravityUpAndNoRotation) {
  UavSensorSuite suite(noiseless(), 1000.0, kG, 1);
  const UavSensorFrame f = suite.update(4, 0.004, at_rest(0.7), Eigen::Vector3d::Zero());
  ASSERT_TRUE(f.imu);
  EXPECT_LT((f.imu->specific_force_flu_m_s2 - Eigen::Vector3d(0, 0, kG)).norm(), 1e-12);
  EXPECT_LT(f.imu->angular_velocity_flu_rad_s.norm(), 1e-15);
}

TEST(UavImu, TiltedAndAcceleratingBodyReadsItInItsOwnAxes) {
  // Rolled +90 deg about FLU x (left side up): body y points world up, body z world -y
  // (ENU). At rest, gravity's reaction (world +z) reads along body +y; a world +y
  // acceleration of 2 m/s^2 reads along body -z.
  QuadrotorState s = at_rest();
  s.attitude = Quat(Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX())));
  s.body_rate_rad_s = Vec3(0.1, -0.2, 0.3);
  const UavImuSample r = true_uav_imu_sample(s, Eigen::Vector3d(0, 2, 0), kG, 0.0);
  EXPECT_LT((r.specific_force_flu_m_s2 - Eigen::Vector3d(0, kG, -2)).norm(), 1e-12);
  EXPECT_LT((r.angular_velocity_flu_rad_s - Eigen::Vector3d(0.1, -0.2, 0.3)).norm(), 1e-15);
  // Free fall reads zero.
  EXPECT_LT(true_uav_imu_sample(at_rest(), Eigen::Vector3d(0, 0, -kG), kG, 0.0)
                .specific_force_flu_m_s2.norm(),
            1e-12);
}

TEST(UavImu, NoiseAndBiasAreSeededAndHaveTheirSigmas) {
  // Same seed: the same samples. The mean over 2500 samples at rest is g + the bias drawn
  // once (within 4 sigma / sqrt(n) = 0.004 m/s^2); the spread is the white noise's 0.05.
  UavSensorSuite a(UavSensorParams{}, 1000.0, kG, 42);
  UavSensorSuite b(UavSensorParams{}, 1000.0, kG, 42);
  UavImu imu(UavSensorParams{}.imu, kG, 5);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double sum_sq_x = 0.0;
  const int n = 2500;
  for (int i = 0; i < n; ++i) {
    const UavImuSample r = imu.sample(at_rest(), Eigen::Vector3d::Zero(), i * 0.004);
    sum += r.specific_force_flu_m_s2;
    const double dx = r.specific_force_flu_m_s2.x() - imu.specific_force_bias_m_s2().x();
    sum_sq_x += dx * dx;
    const auto fa = a.update(4 * (i + 1), 0.0, at_rest(), Eigen::Vector3d::Zero());
    const auto fb = b.update(4 * (i + 1), 0.0, at_rest(), Eigen::Vector3d::Zero());
    ASSERT_EQ(fa.imu->specific_force_flu_m_s2, fb.imu->specific_force_flu_m_s2);
  }
  EXPECT_GT(imu.specific_force_bias_m_s2().norm(), 0.0);
  const Eigen::Vector3d mean = sum / n;
  EXPECT_LT((mean - Eigen::Vector3d(0, 0, kG) - imu.specific_force_bias_m_s2()).norm(),
            0.004 * 1.8);
  EXPECT_NEAR(std::sqrt(sum_sq_x / n), 0.05, 0.005);
}

TEST(Barometer, IsaPressureAtHomeAndItsDropOverTenMetres) {
  // ISA at 488 m: 101325 (1 - 0.0065 * 488 / 288.15)^5.255877 = 95598 Pa = 955.98 hPa,
  // 284.978 K = 11.828 C. Density p / (R T) = 95598 / (287.05 * 284.978) = 1.16866 kg/m^3, so
  // 10 m higher the pressure drops by rho g h = 1.16866 * 9.80665 * 10 = 114.6 Pa.
  UavSensorSuite suite(noiseless(), 1000.0, kG, 1);
  const auto ground = suite.update(20, 0.02, at_rest(0.0, 0.0), Eigen::Vector3d::Zero());
  const auto above = suite.update(40, 0.04, at_rest(0.0, 10.0), Eigen::Vector3d::Zero());
  ASSERT_TRUE(ground.barometer && above.barometer);
  EXPECT_NEAR(ground.barometer->pressure_hpa, 955.98, 0.01);
  EXPECT_NEAR(ground.barometer->temperature_c, 11.828, 1e-3);
  EXPECT_NEAR(ground.barometer->pressure_altitude_m, 488.0, 1e-6);
  EXPECT_NEAR(above.barometer->pressure_altitude_m, 498.0, 1e-6);
  EXPECT_NEAR(ground.barometer->pressure_hpa - above.barometer->pressure_hpa, 1.146, 0.002);
}

TEST(Barometer, NoiseIsOnThePressure) {
  BarometerParams p;  // 1.2 Pa: about 0.1 m
  Barometer baro(p, 3);
  double sum = 0.0, sum_sq = 0.0;
  const int n = 4000;
  for (int i = 0; i < n; ++i) {
    const double pa = baro.sample(0.0, 0.0).pressure_hpa * 100.0 - isa_pressure_pa(488.0);
    sum += pa;
    sum_sq += pa * pa;
  }
  EXPECT_NEAR(sum / n, 0.0, 4.0 * 1.2 / std::sqrt(n));
  EXPECT_NEAR(std::sqrt(sum_sq / n), 1.2, 0.1);
}

TEST(Magnetometer, ReadsTheWorldFieldInBodyAxes) {
  // Facing north (ENU yaw 90 deg): body x = north, y = west, z = up. Field (E 0.009,
  // N 0.216, U -0.426) reads (0.216, -0.009, -0.426).
  UavSensorSuite suite(noiseless(), 1000.0, kG, 1);
  const auto f = suite.update(10, 0.01, at_rest(M_PI / 2), Eigen::Vector3d::Zero());
  ASSERT_TRUE(f.magnetometer);
  EXPECT_LT((f.magnetometer->field_flu_gauss - Eigen::Vector3d(0.216, -0.009, -0.426)).norm(),
            1e-12);
}

TEST(Magnetometer, BiasIsDrawnOnceFromTheSeed) {
  MagnetometerParams p;
  p.noise_gauss = 0.0;
  Magnetometer a(p, 9), b(p, 9), c(p, 10);
  EXPECT_EQ(a.bias_gauss(), b.bias_gauss());
  EXPECT_NE(a.bias_gauss(), c.bias_gauss());
  const auto first = a.sample(at_rest(), 0.0).field_flu_gauss;
  EXPECT_EQ(first, a.sample(at_rest(), 0.1).field_flu_gauss);  // constant without noise
  EXPECT_LT((first - p.world_field_enu_gauss - a.bias_gauss()).norm(), 1e-15);
}

}  // namespace
}  // namespace cover::sim
