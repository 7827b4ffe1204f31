// The World with the motor-level UAV a real firmware flies: resting on a moving deck its IMU
// feels the deck, settling on a still deck before the world starts, lift-off on the
// firmware's outputs, and the firmware's clock running while the world's waits.
#include <gtest/gtest.h>

#include <cmath>

#include "cover/config/yaml_reader.hpp"
#include "cover/sim/firmware_uav_params.hpp"
#include "cover/sim/world.hpp"
#include "test_worlds.hpp"

namespace cover::sim {
namespace {

FirmwareUavParams px4_uav() {
  FirmwareUavParams params = FirmwareUavParams::load_file(
      config::default_config_dir() + "/sim/firmware_uav_px4.yaml", 1000.0);
  params.sensors.imu.specific_force_noise_m_s2 = 0.0;
  params.sensors.imu.angular_velocity_noise_rad_s = 0.0;
  params.sensors.imu.specific_force_bias_sigma_m_s2 = 0.0;
  params.sensors.imu.angular_velocity_bias_sigma_rad_s = 0.0;
  return params;
}

MotorOutputs all(double u) {
  return {u, u, u, u};
}

// The last IMU sample over `steps` steps holding `outputs`.
UavImuSample imu_after(World& world, const MotorOutputs& outputs, int steps) {
  UavImuSample last;
  for (int i = 0; i < steps; ++i) {
    world.step(outputs);
    if (world.motor_uav().sensors().imu) last = *world.motor_uav().sensors().imu;
  }
  return last;
}

TEST(MotorWorld, RestingOnATurningDeckTheImuFeelsTheDeck) {
  const double speed = 1.0, yaw_rate = 0.35;
  World world(test::noiseless_world({test::circle(speed, yaw_rate)}), px4_uav());
  ASSERT_TRUE(world.state().uav_contact.resting);
  const UavImuSample imu = imu_after(world, all(0.0), 200);
  ASSERT_TRUE(world.state().uav_contact.resting);
  EXPECT_NEAR(imu.angular_velocity_flu_rad_s.z(), yaw_rate, 1e-6);
  // Gravity up, and the centripetal v * w towards the circle's centre (the body's left).
  EXPECT_NEAR(imu.specific_force_flu_m_s2.z(), world.params().gravity_m_s2, 1e-6);
  EXPECT_NEAR(imu.specific_force_flu_m_s2.norm(),
              std::hypot(world.params().gravity_m_s2, speed * yaw_rate), 1e-3);
}

TEST(MotorWorld, SettlingHoldsTheDeckStillThenTheDeckCarriesTheUav) {
  World world(test::noiseless_world({test::circle(1.0, 0.35)}), px4_uav());
  UavImuSample still;
  for (int i = 0; i < 500; ++i) {
    world.settle_uav(all(0.0));
    if (world.motor_uav().sensors().imu) still = *world.motor_uav().sensors().imu;
  }
  EXPECT_NEAR(still.angular_velocity_flu_rad_s.norm(), 0.0, 1e-9);  // PX4 can align
  EXPECT_NEAR(still.specific_force_flu_m_s2.z(), world.params().gravity_m_s2, 1e-9);
  EXPECT_NEAR(world.state().uav.velocity_m_s.eigen().norm(), 0.0, 1e-12);

  const UavImuSample moving = imu_after(world, all(0.0), 300);
  EXPECT_NEAR(moving.angular_velocity_flu_rad_s.z(), 0.35, 1e-6);
  EXPECT_NEAR(world.state().uav.velocity_m_s.eigen().norm(), 1.0, 0.05);
  // The deck's jump from rest to speed is no IMU reading: the last sample is the deck's.
  EXPECT_LT(moving.specific_force_flu_m_s2.norm(), 11.0);
}

TEST(MotorWorld, LiftsOffAboveTheHoverOutputAndStaysBelowIt) {
  World world(test::noiseless_world({test::stationary_at(0.0, 0.0)}), px4_uav());
  const double hover = world.motor_uav().plant().hover_output(0.0, world.params().gravity_m_s2);
  imu_after(world, all(0.95 * hover), 500);
  EXPECT_TRUE(world.state().uav_contact.resting);
  imu_after(world, all(1.2 * hover), 1000);
  EXPECT_FALSE(world.state().uav_contact.resting);
  EXPECT_GT(world.true_relative_state(0).position_m.z(), 0.2);
}

TEST(MotorWorld, SettlingRunsTheFirmwareClockWhileTheWorldWaits) {
  World world(test::noiseless_world({test::circle(1.0, 0.35)}), px4_uav());
  for (int i = 0; i < 100; ++i) world.settle_uav(all(0.0));
  EXPECT_EQ(world.state().time_s, 0.0);
  EXPECT_EQ(world.motor_uav().firmware_step(), 100u);
  EXPECT_NEAR(world.motor_uav().firmware_time_s(), 0.1, 1e-12);
  world.step(all(0.0));
  EXPECT_EQ(world.motor_uav().firmware_step(), 101u);
  EXPECT_NEAR(world.state().time_s, 0.001, 1e-12);
}

}  // namespace
}  // namespace cover::sim
