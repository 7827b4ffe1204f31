#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "cover/sim/world.hpp"
#include "test_worlds.hpp"

namespace cover::sim {
namespace {

QuadrotorCommand thrust_only(double thrust_m_s2) {
  QuadrotorCommand command;
  command.thrust_m_s2 = thrust_m_s2;
  return command;
}

WorldParams free_flight_world(double start_height_m) {
  WorldParams params = test::noiseless_world({test::stationary_at(10.0, 10.0)});
  params.uav_initial.start_on_ugv = -1;
  params.uav_initial.position_m = {0.0, 0.0, start_height_m};
  return params;
}

TEST(Quadrotor, HoversWithThrustScaledByTrueOverNominalMass) {
  WorldParams params = free_flight_world(2.0);
  World world(params);
  const double hover = params.gravity_m_s2 * params.uav.mass_true_kg / params.uav.mass_nominal_kg;
  EXPECT_DOUBLE_EQ(world.hover_thrust_command_m_s2(), hover);
  // a UAV starting in mid-air starts spun up to hover thrust
  const double z0 = world.state().uav.position_m.z;
  world.advance(thrust_only(hover), 5.0);
  EXPECT_NEAR(world.state().uav.position_m.z, z0, 1e-9);
  EXPECT_NEAR(world.state().uav.velocity_m_s.z, 0.0, 1e-9);
  EXPECT_FALSE(world.state().uav_contact.resting);
}

TEST(Quadrotor, NominalHoverThrustSinksBecauseOfTheMassMismatch) {
  WorldParams params = free_flight_world(5.0);
  World world(params);
  world.advance(thrust_only(params.gravity_m_s2), 1.0);
  // true mass +5 %: net acceleration about -g * 0.05 / 1.05 = -0.47 m/s^2 (drag slows it)
  EXPECT_LT(world.state().uav.velocity_m_s.z, -0.3);
}

TEST(Quadrotor, ZeroThrustFallsAndRestsOnTheGroundWithoutSinking) {
  World world(free_flight_world(3.0));
  double lowest = 1e9;
  bool reached_ground = false;
  for (int i = 0; i < 4000; ++i) {
    world.step(thrust_only(0.0));
    lowest = std::min(lowest, world.state().uav.position_m.z);
    reached_ground |= world.state().uav_contact.resting;
  }
  EXPECT_TRUE(reached_ground);
  EXPECT_GE(lowest, 0.0);
  EXPECT_EQ(world.state().uav.position_m.z, 0.0);
  EXPECT_EQ(world.state().uav.velocity_m_s.eigen(), Eigen::Vector3d::Zero());
  EXPECT_EQ(world.state().uav_contact.surface, -1);
}

TEST(Quadrotor, FallsOntoAMovingDeckAndRidesWithIt) {
  WorldParams params = test::noiseless_world({test::circle(0.5, 0.35)});
  params.uav_initial.start_on_ugv = -1;
  const UgvMotionPattern pattern(params.ugvs[0].pattern);
  const UgvKinematics start = pattern.at(0.0);
  params.uav_initial.position_m = {start.position_m.x(), start.position_m.y(), 0.5};
  World world(params);
  double lowest_relative = 1e9;
  for (int i = 0; i < 3000; ++i) {
    world.step(thrust_only(0.0));
    lowest_relative = std::min(lowest_relative, world.true_relative_state(0).position_m.z());
  }
  EXPECT_TRUE(world.state().uav_contact.resting);
  EXPECT_EQ(world.state().uav_contact.surface, 0);
  EXPECT_GE(lowest_relative, -1e-12);  // never below the deck
  const RelativeState on_deck = world.true_relative_state(0);
  EXPECT_NEAR(on_deck.position_m.z(), 0.0, 1e-12);
  EXPECT_LT(on_deck.velocity_m_s.norm(), 1e-9);  // carried: no motion relative to G0
  // it fell for ~0.2 s while the deck drove on at 0.5 m/s: ~0.1 m behind the deck centre
  EXPECT_LE(std::abs(on_deck.position_m.x()), params.ugvs[0].deck_half_length_m);
  EXPECT_LE(std::abs(on_deck.position_m.y()), params.ugvs[0].deck_half_width_m);
}

TEST(Quadrotor, StartsOnItsDeckAndLiftsOffWithEnoughThrust) {
  WorldParams params = test::noiseless_world({test::circle(0.5, 0.35)});
  World world(params);
  EXPECT_TRUE(world.state().uav_contact.resting);
  world.advance(thrust_only(world.hover_thrust_command_m_s2() * 0.95), 0.5);
  EXPECT_TRUE(world.state().uav_contact.resting);  // below weight: stays put
  world.advance(thrust_only(world.hover_thrust_command_m_s2() * 1.3), 1.0);
  EXPECT_FALSE(world.state().uav_contact.resting);
  EXPECT_GT(world.true_relative_state(0).position_m.z(), 0.5);
}

TEST(Quadrotor, RateLoopIsAFirstOrderLagWithLimits) {
  WorldParams params = free_flight_world(50.0);
  World world(params);
  QuadrotorCommand command = thrust_only(world.hover_thrust_command_m_s2());
  command.body_rate_rad_s = Vec3(0.0, 0.0, 1.0);
  world.advance(command, params.uav.rate_time_constant_s);
  EXPECT_NEAR(world.state().uav.body_rate_rad_s.z, 1.0 - std::exp(-1.0), 1e-3);
  command.body_rate_rad_s = Vec3(100.0, 0.0, 0.0);  // far beyond the roll-rate limit
  world.advance(command, 0.3);
  EXPECT_NEAR(world.state().uav.body_rate_rad_s.x, params.uav.max_roll_pitch_rate_rad_s, 1e-3);
}

TEST(Quadrotor, ThrustFollowsTheCommandThroughAFirstOrderLagAndLimits) {
  WorldParams params = free_flight_world(50.0);
  World world(params);
  const double start_n = world.state().uav.thrust_n;  // spun up to hover
  const double target_n = 15.0 * params.uav.mass_nominal_kg;
  world.advance(thrust_only(15.0), params.uav.thrust_time_constant_s);
  EXPECT_NEAR(world.state().uav.thrust_n, target_n + (start_n - target_n) * std::exp(-1.0), 1e-3);
  world.advance(thrust_only(1e3), 0.3);  // far beyond the motors
  EXPECT_NEAR(world.state().uav.thrust_n, params.uav.max_thrust_m_s2 * params.uav.mass_nominal_kg,
              1e-3);
}

TEST(World, RejectsNonFiniteCommandsAndHoldsTheLastOne) {
  World world(free_flight_world(2.0));
  const double hover = world.hover_thrust_command_m_s2();
  EXPECT_EQ(world.step(thrust_only(hover)), StepStatus::Ok);
  QuadrotorCommand bad = thrust_only(std::numeric_limits<double>::quiet_NaN());
  EXPECT_EQ(world.step(bad), StepStatus::CommandRejected);
  EXPECT_EQ(world.state().last_command.thrust_m_s2, hover);
  EXPECT_TRUE(world.state().uav.position_m.eigen().allFinite());
}

template <typename T>
bool same_bits(const T& a, const T& b) {
  return std::memcmp(&a, &b, sizeof(T)) == 0;  // Vec3, Quat, double: no padding bytes
}

// Field by field: padding bytes of the bool/int members carry no meaning.
bool bitwise_equal(const WorldState& a, const WorldState& b) {
  bool equal =
      same_bits(a.time_s, b.time_s) && a.step_index == b.step_index && a.ugv_count == b.ugv_count;
  for (int k = 0; k < a.ugv_count; ++k) {
    const UgvState &u = a.ugvs[k], &v = b.ugvs[k];
    equal = equal && same_bits(u.position_m, v.position_m) &&
            same_bits(u.velocity_m_s, v.velocity_m_s) && same_bits(u.yaw_rad, v.yaw_rad);
  }
  const QuadrotorState &p = a.uav, &q = b.uav;
  return equal && same_bits(p.position_m, q.position_m) &&
         same_bits(p.velocity_m_s, q.velocity_m_s) && same_bits(p.attitude, q.attitude) &&
         same_bits(p.body_rate_rad_s, q.body_rate_rad_s) && same_bits(p.thrust_n, q.thrust_n) &&
         a.uav_contact.resting == b.uav_contact.resting &&
         same_bits(a.payload.position_m, b.payload.position_m);
}

TEST(World, SameSeedSameTrajectoryBitForBit) {
  WorldParams params = WorldParams::load_default();
  params.relative_sensor.position_noise_m = 0.01;
  World first(params), second(params);
  QuadrotorCommand command = thrust_only(11.0);
  command.body_rate_rad_s = Vec3(0.2, -0.1, 0.3);
  for (int i = 0; i < 3000; ++i) {
    first.step(command);
    second.step(command);
  }
  EXPECT_TRUE(bitwise_equal(first.state(), second.state()));
  for (int k = 0; k < first.ugv_count(); ++k) {
    EXPECT_EQ(first.relative_sensor().latest(k).position_m,
              second.relative_sensor().latest(k).position_m);
    EXPECT_EQ(first.imu_sensor().latest(k).raw.specific_force_m_s2,
              second.imu_sensor().latest(k).raw.specific_force_m_s2);
  }
  params.seed += 1;
  World other(params);
  for (int i = 0; i < 3000; ++i) other.step(command);
  EXPECT_NE(other.relative_sensor().latest(0).position_m,
            first.relative_sensor().latest(0).position_m);
}

TEST(World, PayloadReleaseRecordsThePointAndLandsOnTheDeck) {
  WorldParams params = test::noiseless_world({test::stationary_at(0.0, 0.0)});
  params.payload.attached_at_start = true;
  params.uav_initial.start_on_ugv = -1;
  params.uav_initial.position_m = {0.05, 0.0, 0.6};
  World world(params);
  EXPECT_DOUBLE_EQ(world.hover_thrust_command_m_s2(),
                   params.gravity_m_s2 * (params.uav.mass_true_kg + params.payload.mass_kg) /
                       params.uav.mass_nominal_kg);
  ASSERT_TRUE(world.release_payload());
  EXPECT_FALSE(world.release_payload());  // nothing left to drop
  const PayloadState& payload = world.state().payload;
  EXPECT_NEAR(payload.release_position_in_ugv_m[0].x, 0.05, 1e-12);
  EXPECT_NEAR(payload.release_position_in_ugv_m[0].z, 0.3, 1e-12);
  world.advance(thrust_only(world.hover_thrust_command_m_s2()), 1.0);
  EXPECT_TRUE(payload.contact.resting);
  EXPECT_EQ(payload.contact.surface, 0);
  EXPECT_NEAR(payload.position_m.z, params.ugvs[0].deck_height_m, 1e-12);
}

}  // namespace
}  // namespace cover::sim
