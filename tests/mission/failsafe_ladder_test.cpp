#include "cover/mission/failsafe_ladder.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <string>

#include "cover/mission/ladder_level.hpp"
#include "cover/test/scratch_dir.hpp"
#include "cover/test/shipped_params.hpp"

using cover::mission::assess_inputs;
using cover::mission::FailsafeCause;
using cover::mission::FailsafeLadder;
using cover::mission::InputHealth;
using cover::mission::LadderInput;
using cover::mission::LadderLevel;
using cover::mission::MissionParams;
using cover::model::kGravity_m_s2;
using cover::model::RelativeState;
using cover::model::UgvMotion;

namespace {

struct Inputs {
  RelativeState state;
  UgvMotion imu;
  double imu_stamp_s = 0.0;
  LadderInput view() const { return LadderInput{true, &state, true, imu_stamp_s, &imu}; }
};

InputHealth lost() {
  InputHealth health;
  health.cause = FailsafeCause::StateStale;
  health.age_s = 0.1;
  return health;
}

cover::mission::ControlCommand hover_command(double thrust_m_s2) {
  cover::mission::ControlCommand command;
  command.thrust_m_s2 = thrust_m_s2;
  command.armed = true;
  return command;
}

InputHealth fresh() {
  InputHealth health;
  health.state_usable = true;
  return health;
}

// A vertical plant: the UAV's true hover thrust is `hover_m_s2`; the ground is at
// `ground_m` (contact: it rests there). Returns the speed at the first contact.
struct VerticalPlant {
  double z_m = 1.0;
  double vz_m_s = 0.0;
  double ground_m = -0.3;
  double hover_m_s2 = kGravity_m_s2;
  double touchdown_speed_m_s = -1.0;
  void step(const cover::mission::ControlCommand& command, double dt_s) {
    const double thrust = command.armed ? command.thrust_m_s2 : 0.0;
    vz_m_s += kGravity_m_s2 * (thrust / hover_m_s2 - 1.0) * dt_s;
    z_m += vz_m_s * dt_s;
    if (z_m <= ground_m) {
      if (touchdown_speed_m_s < 0.0) touchdown_speed_m_s = std::abs(vz_m_s);
      z_m = ground_m;
      vz_m_s = 0.0;
    }
  }
  RelativeState measured(double t_s) const {
    RelativeState s;
    s.stamp_s = t_s;
    s.position_m.z() = z_m;
    s.velocity_m_s.z() = vz_m_s;
    return s;
  }
};

}  // namespace

TEST(AssessInputs, NamesTheFirstProblemAndItsAge) {
  const MissionParams params;
  Inputs in;
  EXPECT_EQ(assess_inputs(in.view(), 0.05, params).cause, FailsafeCause::None);
  EXPECT_TRUE(assess_inputs(in.view(), 0.05, params).state_usable);

  const InputHealth stale = assess_inputs(in.view(), 0.25, params);
  EXPECT_EQ(stale.cause, FailsafeCause::StateStale);
  EXPECT_NEAR(stale.age_s, 0.25, 1e-12);
  EXPECT_FALSE(stale.state_usable);

  EXPECT_EQ(assess_inputs(LadderInput{}, 0.0, params).cause, FailsafeCause::StateMissing);
  EXPECT_EQ(assess_inputs(in.view(), std::numeric_limits<double>::quiet_NaN(), params).cause,
            FailsafeCause::ClockInvalid);
  Inputs bad = in;
  bad.state.velocity_m_s.y() = std::numeric_limits<double>::infinity();
  EXPECT_EQ(assess_inputs(bad.view(), 0.0, params).cause, FailsafeCause::StateInvalid);
  bad = in;
  bad.imu.angular_velocity_rad_s.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(assess_inputs(bad.view(), 0.0, params).cause, FailsafeCause::ImuInvalid);
}

TEST(AssessInputs, HoldsAStaleImuOnlyWithinImuHold) {
  MissionParams params;
  params.imu_timeout_s = 0.1;
  params.imu_hold_s = 0.1;
  Inputs in;
  in.state.stamp_s = 0.3;
  in.imu_stamp_s = 0.15;
  const InputHealth held = assess_inputs(in.view(), 0.3, params);  // IMU 0.15 s old
  EXPECT_EQ(held.cause, FailsafeCause::ImuStale);
  EXPECT_TRUE(held.imu_held);
  EXPECT_TRUE(held.state_usable);
  in.imu_stamp_s = 0.05;
  EXPECT_FALSE(assess_inputs(in.view(), 0.3, params).imu_held);  // 0.25 s old
}

TEST(FailsafeLadder, HoversThenLandsAfterEmergencyHover) {
  MissionParams params;
  params.emergency_hover_s = 1.0;
  FailsafeLadder ladder(params);
  EXPECT_EQ(ladder.update(fresh(), 0.0), LadderLevel::Nominal);
  EXPECT_FALSE(ladder.changed());
  EXPECT_EQ(ladder.update(lost(), 0.1), LadderLevel::EmergencyHover);
  EXPECT_TRUE(ladder.changed());
  EXPECT_EQ(ladder.cause(), FailsafeCause::StateStale);
  EXPECT_EQ(ladder.update(lost(), 1.09), LadderLevel::EmergencyHover);
  EXPECT_FALSE(ladder.changed());
  EXPECT_EQ(ladder.update(lost(), 1.1), LadderLevel::EmergencyLanding);
  EXPECT_TRUE(ladder.changed());
  // Latched: inputs back do not end the landing.
  EXPECT_EQ(ladder.update(fresh(), 1.2), LadderLevel::EmergencyLanding);
  EXPECT_FALSE(ladder.resumed());
}

TEST(FailsafeLadder, InputsBackDuringTheHoverResumeOnce) {
  FailsafeLadder ladder{MissionParams{}};
  ladder.update(lost(), 0.1);
  EXPECT_EQ(ladder.update(fresh(), 0.5), LadderLevel::Nominal);
  EXPECT_TRUE(ladder.resumed());
  EXPECT_TRUE(ladder.changed());
  ladder.update(fresh(), 0.51);
  EXPECT_FALSE(ladder.resumed());
}

TEST(FailsafeLadder, ImuHoldClimbsToTheHoverAndBackWithoutResume) {
  FailsafeLadder ladder{MissionParams{}};
  InputHealth held;
  held.cause = FailsafeCause::ImuStale;
  held.imu_held = true;
  held.state_usable = true;
  EXPECT_EQ(ladder.update(held, 0.11), LadderLevel::ImuHold);
  EXPECT_EQ(ladder.update(fresh(), 0.12), LadderLevel::Nominal);
  EXPECT_FALSE(ladder.resumed());  // SAMPC flew all along: nothing to replan
  ladder.update(held, 0.2);
  InputHealth gone = held;
  gone.imu_held = false;
  EXPECT_EQ(ladder.update(gone, 0.31), LadderLevel::EmergencyHover);
  EXPECT_EQ(ladder.cause(), FailsafeCause::ImuStale);
}

TEST(FailsafeLadder, HoverUsesTheLastHoverThrustAndLevelsABlindTilt) {
  FailsafeLadder ladder{MissionParams{}};
  RelativeState tilted;
  tilted.attitude = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()));
  ladder.remember(tilted, 10.4, hover_command(10.4), 0.0);
  ladder.update(lost(), 0.1);
  // Blind: the attitude is propagated with the commanded rates, as the rate loop follows.
  Eigen::Quaterniond attitude = tilted.attitude;
  cover::mission::ControlCommand command;
  for (int i = 1; i <= 300; ++i) {
    command = ladder.command(nullptr, 0.1 + 0.01 * i);
    const Eigen::Vector3d rotation = command.body_rate_rad_s * 0.01;
    attitude =
        attitude * Eigen::Quaterniond(Eigen::AngleAxisd(rotation.norm(), rotation.normalized()));
    EXPECT_TRUE(command.armed);
    EXPECT_TRUE(std::isfinite(command.thrust_m_s2));
  }
  EXPECT_LT(std::acos(std::min(1.0, (attitude * Eigen::Vector3d::UnitZ()).z())), 0.01);
  EXPECT_NEAR(command.thrust_m_s2, 10.4, 0.05);
  EXPECT_NEAR(command.body_rate_rad_s.z(), 0.0, 1e-12);  // no yaw
}

TEST(FailsafeLadder, MeasuredLandingTouchesDownSlowlyAndDisarmsOnContact) {
  MissionParams params;
  FailsafeLadder ladder(params);
  VerticalPlant plant;
  plant.hover_m_s2 = 10.3;
  ladder.remember(plant.measured(0.0), 10.3, hover_command(10.3), 0.0);
  InputHealth imu_lost;  // the IMU is gone, the relative state still comes
  imu_lost.cause = FailsafeCause::ImuStale;
  imu_lost.state_usable = true;
  double t = 0.0;
  bool disarmed_in_air = false;
  while (t < 20.0 && ladder.level() != LadderLevel::Disarmed) {
    t += 0.01;
    ladder.update(imu_lost, t);
    const RelativeState s = plant.measured(t);
    const auto command = ladder.command(&s, t);
    EXPECT_FALSE(command.handover) << "measured, the agent lands the UAV itself";
    if (!command.armed && plant.z_m > plant.ground_m) disarmed_in_air = true;
    plant.step(command, 0.01);
  }
  EXPECT_EQ(ladder.level(), LadderLevel::Disarmed);
  EXPECT_FALSE(disarmed_in_air);
  EXPECT_GE(plant.touchdown_speed_m_s, 0.0);
  EXPECT_LE(plant.touchdown_speed_m_s, 1.0);
  EXPECT_FALSE(ladder.command(nullptr, t + 0.01).armed);  // stays off
}

TEST(FailsafeLadder, BlindLandingDisarmsOnlyBelowTheFloor) {
  MissionParams params;
  FailsafeLadder ladder(params);
  VerticalPlant plant;
  plant.z_m = 0.7;
  plant.hover_m_s2 = 10.3;
  ladder.remember(plant.measured(0.0), 10.3, hover_command(10.3), 0.0);
  double t = 0.0;
  double disarm_height_m = 1e9;
  while (t < 30.0 && ladder.level() != LadderLevel::Disarmed) {
    t += 0.01;
    ladder.update(lost(), t);
    const auto command = ladder.command(nullptr, t);
    if (!command.armed) disarm_height_m = plant.z_m;
    plant.step(command, 0.01);
  }
  EXPECT_EQ(ladder.level(), LadderLevel::Disarmed);
  EXPECT_DOUBLE_EQ(disarm_height_m, plant.ground_m);  // on the ground when the motors stop
  EXPECT_LE(plant.touchdown_speed_m_s, 1.0);
}

// Blind, the hover may still be dead-reckoned (inputs could come back), but the landing is
// handed to the flight controller from its first step, and stays handed over even if a
// relative state returns.
TEST(FailsafeLadder, BlindLandingHandsOverToTheFlightController) {
  MissionParams params;
  FailsafeLadder ladder(params);
  VerticalPlant plant;
  ladder.remember(plant.measured(0.0), 10.3, hover_command(10.3), 0.0);
  double t = 0.0;
  bool handed_over_in_hover = false;
  bool landing_handed_over = false;
  while (t < 5.0 && ladder.level() != LadderLevel::EmergencyLanding) {
    t += 0.01;
    ladder.update(lost(), t);
    const bool handover = ladder.command(nullptr, t).handover;
    if (ladder.level() == LadderLevel::EmergencyHover && handover) handed_over_in_hover = true;
    if (ladder.level() == LadderLevel::EmergencyLanding) landing_handed_over = handover;
  }
  ASSERT_EQ(ladder.level(), LadderLevel::EmergencyLanding);
  EXPECT_FALSE(handed_over_in_hover);
  EXPECT_TRUE(landing_handed_over);  // from the landing's first step
  EXPECT_TRUE(ladder.handed_over());
  const RelativeState back = plant.measured(t);
  EXPECT_TRUE(ladder.command(&back, t + 0.01).handover);
}

// The hover's vertical control takes its gains from the params: 0.2 m below the held
// height and sinking at 0.1 m/s, it asks for the acceleration the gains say, the integral
// bounded by its limit.
TEST(FailsafeLadder, VerticalGainsAreTheParams) {
  const auto push_m_s2 = [](const MissionParams& params) {
    FailsafeLadder ladder(params);
    VerticalPlant plant;  // at 1.0 m, hovering
    ladder.remember(plant.measured(0.0), kGravity_m_s2, hover_command(kGravity_m_s2), 0.0);
    ladder.update(lost(), 0.01);
    EXPECT_EQ(ladder.level(), LadderLevel::EmergencyHover);
    RelativeState low = plant.measured(0.01);
    low.position_m.z() = 0.8;
    low.velocity_m_s.z() = -0.1;
    return ladder.command(&low, 0.01).thrust_m_s2 - kGravity_m_s2;
  };
  MissionParams params;
  params.emergency_integral_gain_1_s3 = 0.0;
  EXPECT_NEAR(push_m_s2(params), 2.0 * 0.2 + 2.5 * 0.1, 1e-9);  // the defaults
  params.emergency_height_gain_1_s2 = 4.0;
  params.emergency_speed_gain_1_s = 5.0;
  EXPECT_NEAR(push_m_s2(params), 4.0 * 0.2 + 5.0 * 0.1, 1e-9);
  params.emergency_integral_gain_1_s3 = 10.0;  // one step: 10 * 0.2 m * 0.01 s = 0.02
  params.emergency_integral_limit_m_s2 = 0.005;
  EXPECT_NEAR(push_m_s2(params), 4.0 * 0.2 + 5.0 * 0.1 + 0.005, 1e-9);
}

TEST(FailsafeLadder, VerticalGainsAreReadFromYamlAndChecked) {
  // Every field (MissionParams::fields), shipped with its default value.
  const std::string shipped = cover::config::default_config_dir() + "/mission.yaml";
  cover::test::expect_shipped_file_holds_defaults(MissionParams::load_file(shipped), shipped,
                                                  "mission");
  const std::string path = cover::test::scratch_path("mission.yaml");
  std::ofstream(path) << "mission:\n  emergency_height_gain_1_s2: 3.0\n"
                         "  emergency_integral_gain_1_s3: 0\n";
  const MissionParams read = MissionParams::load_file(path);
  EXPECT_EQ(read.emergency_height_gain_1_s2, 3.0);
  EXPECT_EQ(read.emergency_integral_gain_1_s3, 0.0);  // 0 disables the integral
  for (const char* bad :
       {"emergency_height_gain_1_s2: 0", "emergency_speed_gain_1_s: -1",
        "emergency_integral_gain_1_s3: .nan", "emergency_integral_limit_m_s2: 100"}) {
    std::ofstream(path) << "mission:\n  " << bad << "\n";
    const std::string key = std::string(bad).substr(0, std::string(bad).find(':'));
    try {
      MissionParams::load_file(path);
      ADD_FAILURE() << bad << " accepted";
    } catch (const cover::config::ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("mission." + key), std::string::npos) << e.what();
    }
  }
}

// The hover thrust comes from the flight itself: thrust along up against the change of
// vertical speed, whatever the mass, and not from the deck or across a missed step.
TEST(HoverThrustEstimate, LearnsTheThrustThatHoldsTheHeight) {
  cover::mission::HoverThrustEstimate estimate;
  const double true_hover_m_s2 = 10.6;  // heavier than nominal
  double z_m = 1.0;
  double vz_m_s = 0.0;
  double t_s = 0.0;
  for (int k = 0; k < 200; ++k, t_s += 0.01) {
    // A climbing-then-braking thrust profile: the window's mean is not the hover thrust.
    const double thrust_m_s2 = true_hover_m_s2 * (1.0 + 0.05 * std::sin(3.0 * t_s));
    estimate.add(t_s, z_m, vz_m_s, thrust_m_s2, 0.01);
    const double accel_m_s2 = kGravity_m_s2 * (thrust_m_s2 / true_hover_m_s2 - 1.0);
    z_m += vz_m_s * 0.01 + 0.5 * accel_m_s2 * 1e-4;
    vz_m_s += accel_m_s2 * 0.01;
  }
  ASSERT_TRUE(estimate.valid());
  EXPECT_NEAR(estimate.value_m_s2(), true_hover_m_s2, 1e-3 * true_hover_m_s2);

  estimate.add(t_s + 0.5, z_m, vz_m_s, true_hover_m_s2, 0.01);  // a gap: starts anew
  EXPECT_FALSE(estimate.valid());
  cover::mission::HoverThrustEstimate on_deck;
  for (int k = 0; k < 100; ++k) on_deck.add(0.01 * k, 0.0, 0.0, 5.0, 0.01);
  EXPECT_FALSE(on_deck.valid());
}
