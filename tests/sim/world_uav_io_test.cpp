#include <gtest/gtest.h>

#include "cover/sim/scenario.hpp"
#include "cover/sim/world.hpp"
#include "cover/sim/world_uav_io.hpp"
#include "test_worlds.hpp"

namespace cover::sim {
namespace {

// What the in-process UAV loop receives: the UGV agent's filter output and speed estimate.
TEST(WorldUavInputs, PaperScenarioCarriesTheWheelOdometrySpeed) {
  const Scenario scenario = Scenario::load_file(scenario_path("scenario1"));
  World world(scenario.world);
  world.advance({}, 3.0);
  WorldUavInputs inputs(world);
  for (int k = 0; k < world.ugv_count(); ++k) {
    mission::UgvImuMeasurement m;
    ASSERT_TRUE(inputs.ugv_imu(k, m));
    EXPECT_EQ(m.motion.speed_source, model::SpeedSource::WheelOdometry);
    EXPECT_TRUE(m.motion.speed_valid());
    EXPECT_NEAR(m.motion.speed_m_s, 0.8, 0.05);  // 1 % scale error, 0.02 m/s noise
    EXPECT_EQ(m.motion.speed_m_s, world.imu_sensor().latest(k).speed.speed_m_s);
  }
}

TEST(WorldUavInputs, WithoutOdometryTheSpeedComesFromTheImuOrIsInvalid) {
  WorldParams params = test::noiseless_world({test::circle(0.8, 0.5), test::stationary_at(5, 0)});
  for (UgvParams& ugv : params.ugvs) ugv.has_wheel_odometry = false;
  World world(params);
  world.advance({}, 3.0);
  WorldUavInputs inputs(world);
  mission::UgvImuMeasurement turning, parked;
  ASSERT_TRUE(inputs.ugv_imu(0, turning));
  ASSERT_TRUE(inputs.ugv_imu(1, parked));
  EXPECT_EQ(turning.motion.speed_source, model::SpeedSource::Imu);
  EXPECT_NEAR(turning.motion.speed_m_s, 0.8, 1e-6);
  EXPECT_EQ(parked.motion.speed_source, model::SpeedSource::None);
  EXPECT_FALSE(parked.motion.speed_valid());
}

}  // namespace
}  // namespace cover::sim
