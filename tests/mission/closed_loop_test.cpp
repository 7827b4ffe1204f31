#include <gtest/gtest.h>

#include <cmath>

#include "cover/sim/closed_loop.hpp"
#include "cover/sim/world.hpp"

using cover::sim::ClosedLoop;
using cover::sim::ClosedLoopOptions;
using cover::sim::ControllerConfig;
using cover::sim::Scenario;

namespace {

ControllerConfig cover_config() {
  return ControllerConfig::load_default(cover::sampc::Mode::Cover);
}

}  // namespace

// The check: hovering above a circling UGV, the world-frame error settles < 5 cm.
TEST(ClosedLoop, HoversAboveCirclingUgvWithinFiveCentimetres) {
  Scenario scenario = Scenario::load_file(cover::sim::scenario_path("hover"));
  ControllerConfig config = cover_config();
  // A stage end that cannot trigger: the UAV keeps holding the initial point.
  config.mission.reach_tolerance_m = 1e-9;
  const double settle_s = 6.0;
  const double end_s = 9.0;
  scenario.max_duration_s = end_s;

  // Run the loop ourselves to watch the world-frame error at each step.
  cover::sim::World world(scenario.world);
  cover::mission::MissionController controller(scenario.task, world.ugv_count(), config.mission,
                                               config.planner, config.sampc);
  double worst_after_settling_m = 0.0;
  cover::sim::QuadrotorCommand command;
  while (world.state().time_s < end_s) {
    const double t = world.state().time_s;
    for (int k = 0; k < world.ugv_count(); ++k) {
      if (world.relative_sensor().has_measurement()) {
        const auto& rel = world.relative_sensor().latest(k);
        controller.set_relative_state(
            k, {rel.stamp_s, rel.position_m, rel.velocity_m_s, rel.attitude});
      }
      if (world.imu_sensor().has_reading()) {
        const auto& imu = world.imu_sensor().latest(k).filtered;
        cover::mission::UgvImuMeasurement m;
        m.stamp_s = imu.stamp_s;
        m.motion.specific_force_m_s2 = imu.specific_force_m_s2;
        m.motion.angular_velocity_rad_s = imu.angular_velocity_rad_s;
        m.motion.angular_acceleration_rad_s2 = imu.angular_acceleration_rad_s2;
        controller.set_ugv_imu(k, m);
      }
    }
    const auto& out = controller.step(t);
    ASSERT_TRUE(std::isfinite(out.command.thrust_m_s2));
    command.thrust_m_s2 = out.command.armed ? out.command.thrust_m_s2 : 0.0;
    command.body_rate_rad_s = cover::sim::Vec3(out.command.body_rate_rad_s);
    if (t >= settle_s) {
      const Eigen::Vector3d target = world.state().ugvs[0].to_world(Eigen::Vector3d(0, 0, 1.0));
      const double error = (world.state().uav.position_m.eigen() - target).norm();
      worst_after_settling_m = std::max(worst_after_settling_m, error);
    }
    world.advance(command, 0.01);
  }
  EXPECT_EQ(controller.output().status.stage.state, cover::mission::MissionState::Running);
  EXPECT_LT(worst_after_settling_m, 0.05);
}

// The check: a Scenario 2 run (take off from G0, transit, land on G1) succeeds.
TEST(ClosedLoop, ScenarioTwoLandsOnTheTargetUgv) {
  const ControllerConfig config = cover_config();
  ClosedLoopOptions options;
  options.record_paths = false;
  const ClosedLoop loop(Scenario::load_file(cover::sim::scenario_path("scenario2")), config.mission,
                        config.planner, config.sampc, options);
  const cover::sim::ClosedLoopResult result = loop.run();
  EXPECT_TRUE(result.success) << result.status;
  EXPECT_TRUE(result.landed_on_target_deck);
  EXPECT_LE(result.landing_error_m, 0.05);
  ASSERT_EQ(result.transitions.size(), 1u);
  EXPECT_TRUE(result.transitions[0].completed);
  EXPECT_GT(result.transitions[0].straight_length_m, 1.0);
}

// Same seed, same run: the harness is deterministic (timings aside).
TEST(ClosedLoop, SameSeedGivesTheSameRun) {
  const ControllerConfig config = cover_config();
  Scenario scenario = Scenario::load_file(cover::sim::scenario_path("hover"));
  scenario.max_duration_s = 2.0;
  const ClosedLoop loop(scenario, config.mission, config.planner, config.sampc);
  const auto a = loop.run();
  const auto b = loop.run();
  ASSERT_EQ(a.uav_path.size(), b.uav_path.size());
  for (std::size_t i = 0; i < a.uav_path.size(); ++i) {
    EXPECT_EQ(a.uav_path[i].uav_world_m, b.uav_path[i].uav_world_m);
  }
}

// Table 1's headline, short: cyclic transitions between circling UGVs; COVER's world path
// detours less than CoNi-MPC's (x-y-z-ref in the rotating frame), and every transition
// completes. Four transitions at (0.5 m/s, 0.35 rad/s).
TEST(ClosedLoop, CoverDetoursLessThanConiMpcBetweenCirclingUgvs) {
  auto ratio = [](cover::sampc::Mode mode) {
    Scenario scenario = Scenario::load_file(cover::sim::scenario_path("table1"));
    scenario.task = cover::mission::repeat_processes(scenario.task, 4);
    scenario.max_duration_s = 240.0;
    const ControllerConfig config = ControllerConfig::load_default(mode);
    ClosedLoopOptions options;
    options.record_paths = false;
    const auto result =
        ClosedLoop(scenario, config.mission, config.planner, config.sampc, options).run();
    EXPECT_TRUE(result.success) << result.status;
    EXPECT_EQ(result.transitions.size(), 4u);
    return result.total_path_length_m / result.total_straight_length_m;
  };
  const double cover = ratio(cover::sampc::Mode::Cover);
  const double coni = ratio(cover::sampc::Mode::ConiMpc);
  // Measured 1.19 and 1.49 (the full benchmark: cover-bench table1).
  EXPECT_LT(cover, 1.3);
  EXPECT_GT(coni, cover + 0.15);
}
