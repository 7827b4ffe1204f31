#include <gtest/gtest.h>

#include <deque>

#include "cover/sim/world.hpp"
#include "test_worlds.hpp"

namespace cover::sim {
namespace {

QuadrotorCommand climbing_turn() {
  QuadrotorCommand command;
  command.thrust_m_s2 = 11.5;
  command.body_rate_rad_s = Vec3(0.3, -0.2, 0.5);
  return command;
}

TEST(RelativeSensor, LatencyDelaysTheMeasurementByTheConfiguredTime) {
  WorldParams params =
      test::noiseless_world({test::circle(0.5, 0.35), test::circle(0.8, -0.25, 3, 0)});
  params.relative_sensor.latency_s = 0.03;
  params.relative_sensor.rate_hz = 100.0;
  World world(params);
  EXPECT_DOUBLE_EQ(world.relative_sensor().latency_s(), 0.03);
  std::deque<std::pair<double, RelativeState>> truth;  // (time, truth in G1)
  int checked = 0;
  for (int i = 0; i < 2000; ++i) {
    world.step(climbing_turn());
    truth.emplace_back(world.state().time_s, world.true_relative_state(1));
    if (!world.relative_sensor().has_measurement()) continue;
    const RelativeState& measured = world.relative_sensor().latest(1);
    const double age = world.state().time_s - measured.stamp_s;
    EXPECT_GE(age, 0.03 - 1e-9);
    EXPECT_LT(age, 0.03 + 0.01);  // latency + at most one sample period
    if (std::abs(age - 0.03) < 1e-9) {
      for (const auto& [t, state] : truth) {
        if (std::abs(t - measured.stamp_s) > 1e-9) continue;
        EXPECT_LT((state.position_m - measured.position_m).norm(), 1e-12);
        EXPECT_LT((state.velocity_m_s - measured.velocity_m_s).norm(), 1e-12);
        EXPECT_LT(state.attitude.angularDistance(measured.attitude), 1e-9);
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 100);
}

TEST(RelativeSensor, RelativeVelocityIsTheDerivativeOfRelativePositionInGk) {
  WorldParams params = test::noiseless_world({test::circle(0.8, 0.5)});
  params.uav_initial.start_on_ugv = -1;
  params.uav_initial.position_m = {1.0, 2.0, 3.0};
  World world(params);
  world.advance(climbing_turn(), 1.0);
  const RelativeState before = world.true_relative_state(0);
  world.step(climbing_turn());
  const RelativeState middle = world.true_relative_state(0);
  world.step(climbing_turn());
  const RelativeState after = world.true_relative_state(0);
  const Eigen::Vector3d numeric =
      (after.position_m - before.position_m) / (2 * world.physics_dt_s());
  EXPECT_LT((numeric - middle.velocity_m_s).norm(), 1e-4);
}

TEST(RelativeSensor, NoiseHasTheConfiguredSpread) {
  WorldParams params = test::noiseless_world({test::stationary_at(0, 0)});
  params.relative_sensor.position_noise_m = 0.01;
  params.relative_sensor.latency_s = 0.0;
  params.uav_initial.start_on_ugv = -1;
  params.uav_initial.position_m = {1.0, 0.0, 0.0};  // resting on the ground: truth constant
  World world(params);
  double sum_sq = 0.0;
  int n = 0;
  for (int i = 0; i < 20000; ++i) {
    world.step(QuadrotorCommand{});
    if (world.state().step_index % 10 != 0) continue;
    sum_sq +=
        (world.relative_sensor().latest(0).position_m - world.true_relative_state(0).position_m)
            .squaredNorm();
    ++n;
  }
  EXPECT_NEAR(std::sqrt(sum_sq / (3 * n)), 0.01, 0.001);
}

}  // namespace
}  // namespace cover::sim

namespace cover::sim {
namespace {

TEST(RelativeSensor, DropoutsLeaveOlderStampsButNeverFutureOnes) {
  WorldParams params = test::noiseless_world({test::stationary_at(0, 0)});
  params.relative_sensor.dropout_probability = 0.5;
  params.relative_sensor.latency_s = 0.0;
  World world(params);
  int stale = 0, fresh = 0;
  for (int i = 0; i < 5000; ++i) {
    world.step(QuadrotorCommand{});
    if (world.state().step_index % 10 != 0 || !world.relative_sensor().has_measurement()) continue;
    const double age = world.state().time_s - world.relative_sensor().latest(0).stamp_s;
    EXPECT_GE(age, -1e-12);
    (age > 1e-9 ? stale : fresh)++;
  }
  // about half the samples are lost
  EXPECT_GT(stale, 150);
  EXPECT_GT(fresh, 150);
}

}  // namespace
}  // namespace cover::sim
