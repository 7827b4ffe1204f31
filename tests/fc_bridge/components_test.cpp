#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "cover/fc_bridge/autopilot_profile.hpp"
#include "cover/fc_bridge/command_sender.hpp"
#include "cover/fc_bridge/hover_thrust_estimator.hpp"
#include "cover/fc_bridge/setpoint_mapper.hpp"
#include "cover/fc_bridge/setpoint_stream.hpp"
#include "cover/mavlink/protocol.hpp"

namespace cover::fc_bridge {
namespace {

namespace mav = cover::mavlink;
constexpr std::uint8_t kCustom = mav::mav_mode_flag::kCustomModeEnabled;

TEST(AutopilotProfile, Px4ModesDecodeFromMainAndSubMode) {
  const AutopilotProfile px4(Autopilot::Px4);
  const auto offboard = mav::px4_mode::custom_mode(mav::px4_mode::kMainOffboard);
  EXPECT_EQ(offboard, 0x00060000U);
  EXPECT_EQ(px4.decode_mode(kCustom, offboard), FcMode::Offboard);
  EXPECT_EQ(px4.mode_name(kCustom, offboard), "OFFBOARD");
  const auto land =
      mav::px4_mode::custom_mode(mav::px4_mode::kMainAuto, mav::px4_mode::kAutoSubLand);
  EXPECT_EQ(px4.decode_mode(kCustom, land), FcMode::Land);
  EXPECT_EQ(px4.mode_name(kCustom, land), "AUTO.LAND");
  const auto posctl = mav::px4_mode::custom_mode(mav::px4_mode::kMainPosctl);
  EXPECT_EQ(px4.decode_mode(kCustom, posctl), FcMode::Manual);
  const auto loiter =
      mav::px4_mode::custom_mode(mav::px4_mode::kMainAuto, mav::px4_mode::kAutoSubLoiter);
  EXPECT_EQ(px4.decode_mode(kCustom, loiter), FcMode::Other);
  EXPECT_EQ(px4.decode_mode(0, offboard), FcMode::Unknown);  // no custom mode flag
  EXPECT_EQ(px4.decode_mode(kCustom, mav::px4_mode::custom_mode(42)), FcMode::Unknown);
  EXPECT_EQ(px4.mode_name(kCustom, mav::px4_mode::custom_mode(42, 1)), "PX4 mode 42.1");
}

TEST(AutopilotProfile, ArduPilotModesAreCopterNumbers) {
  const AutopilotProfile apm(Autopilot::ArduPilot);
  EXPECT_EQ(apm.decode_mode(kCustom, 20), FcMode::Offboard);
  EXPECT_EQ(apm.mode_name(kCustom, 20), "GUIDED_NOGPS");
  EXPECT_EQ(apm.decode_mode(kCustom, 9), FcMode::Land);
  EXPECT_EQ(apm.decode_mode(kCustom, 4), FcMode::Other);   // GUIDED is not our mode
  EXPECT_EQ(apm.decode_mode(kCustom, 0), FcMode::Manual);  // STABILIZE
  EXPECT_EQ(apm.decode_mode(kCustom, 5), FcMode::Manual);  // LOITER: the pilot's sticks
  EXPECT_EQ(apm.mode_name(kCustom, 99), "Copter mode 99");
}

TEST(AutopilotProfile, ModeAndArmCommands) {
  const AutopilotProfile px4(Autopilot::Px4);
  const AutopilotProfile apm(Autopilot::ArduPilot);
  EXPECT_EQ(px4.offboard_command().command, mav::mav_cmd::kDoSetMode);
  EXPECT_EQ(px4.offboard_command().param[0], 1.0F);
  EXPECT_EQ(px4.offboard_command().param[1], 6.0F);
  EXPECT_EQ(apm.offboard_command().param[1], 20.0F);
  EXPECT_EQ(px4.land_command().command, mav::mav_cmd::kNavLand);
  EXPECT_EQ(apm.land_command().command, mav::mav_cmd::kDoSetMode);
  EXPECT_EQ(apm.land_command().param[1], 9.0F);
  EXPECT_EQ(px4.arm_command(true).command, mav::mav_cmd::kComponentArmDisarm);
  EXPECT_EQ(px4.arm_command(true).param[0], 1.0F);
  EXPECT_EQ(px4.arm_command(true).param[1], 0.0F);  // never forced
  EXPECT_EQ(px4.arm_command(false).param[0], 0.0F);
  EXPECT_EQ(px4.mav_autopilot(), mav::mav_autopilot::kPx4);
  EXPECT_EQ(apm.mav_autopilot(), mav::mav_autopilot::kArdupilotMega);
  EXPECT_EQ(parse_autopilot("px4"), Autopilot::Px4);
  EXPECT_EQ(parse_autopilot("ardupilot"), Autopilot::ArduPilot);
  EXPECT_FALSE(parse_autopilot("PX4 "));
}

AgentCommand command(double thrust, double p, double q, double r, bool armed = true) {
  AgentCommand c;
  c.stamp_ns = 12'345'678'901;
  c.thrust_m_s2 = thrust;
  c.roll_rate_rad_s = p;
  c.pitch_rate_rad_s = q;
  c.yaw_rate_rad_s = r;
  c.armed = armed;
  return c;
}

TEST(SetpointMapper, RatesFluToFrdAndThrustNormalised) {
  const SetpointMapper mapper(9.81);
  const auto t = mapper.map(command(9.81, 0.1, 0.2, 0.3), 0.5, 7, 1);
  EXPECT_EQ(t.type_mask, 128);
  EXPECT_EQ(t.target_system, 7);
  EXPECT_EQ(t.target_component, 1);
  EXPECT_FLOAT_EQ(t.body_roll_rate, 0.1F);
  EXPECT_FLOAT_EQ(t.body_pitch_rate, -0.2F);
  EXPECT_FLOAT_EQ(t.body_yaw_rate, -0.3F);
  EXPECT_FLOAT_EQ(t.thrust, 0.5F);  // c = g: the hover thrust
  EXPECT_EQ(t.time_boot_ms, 12345U);
  EXPECT_FLOAT_EQ(mapper.map(command(4.905, 0, 0, 0), 0.4, 7, 1).thrust, 0.2F);
}

TEST(SetpointMapper, ThrustClampedAndZeroWhenDisarmed) {
  const SetpointMapper mapper(9.81);
  EXPECT_FLOAT_EQ(mapper.map(command(40.0, 0, 0, 0), 0.5, 1, 1).thrust, 1.0F);
  EXPECT_FLOAT_EQ(mapper.map(command(-3.0, 0, 0, 0), 0.5, 1, 1).thrust, 0.0F);
  EXPECT_FLOAT_EQ(mapper.map(command(9.81, 0, 0, 0, false), 0.5, 1, 1).thrust, 0.0F);
}

TEST(SetpointMapper, NaNOrAbsurdCommandsAreNotFlyable) {
  EXPECT_TRUE(is_flyable(command(9.81, 1, 2, 3)));
  EXPECT_FALSE(is_flyable(command(std::nan(""), 0, 0, 0)));
  EXPECT_FALSE(is_flyable(command(9.81, 0, std::nan(""), 0)));
  EXPECT_FALSE(is_flyable(command(9.81, 0, 0, INFINITY)));
  EXPECT_FALSE(is_flyable(command(9.81, 1e9, 0, 0)));
  EXPECT_FALSE(is_flyable(command(1e40, 0, 0, 0)));
}

TEST(SetpointStream, CountsTheRateAndBreaksOnGaps) {
  SetpointStream stream;
  EXPECT_EQ(stream.streaming_for_s(0.0), 0.0);
  for (int i = 0; i <= 150; ++i) stream.on_sent(i * 0.01);
  EXPECT_NEAR(stream.streaming_for_s(1.5), 1.5, 1e-9);
  EXPECT_NEAR(stream.rate_hz(1.5), 101.0, 1.0);
  EXPECT_EQ(stream.streaming_for_s(2.1), 0.0);  // 0.6 s without a setpoint: < 2 Hz
  stream.on_sent(2.7);
  EXPECT_EQ(stream.streaming_for_s(2.7), 0.0);  // starts again
  EXPECT_NEAR(stream.rate_hz(2.7), 1.0, 1e-9);
}

// Open loop: thrust commands around hover; the IMU measures g u / u_true, with noise and
// the motors' lag (30 ms), at 50 Hz.
double estimate_after(double initial, double truth, double seconds, unsigned seed) {
  HoverThrustEstimatorParams params;
  params.initial = initial;
  HoverThrustEstimator estimator(params);
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.8);
  double force = 9.81;
  const double dt = 0.02;
  for (int k = 0; k * dt < seconds; ++k) {
    const double t = k * dt;
    const double u = initial * (1.0 + 0.1 * std::sin(2.0 * t));
    force += (9.81 * u / truth - force) * dt / (0.03 + dt);
    estimator.update(u, force + noise(rng), t);
  }
  return estimator.estimate();
}

TEST(HoverThrustEstimator, ConvergesFromTwentyPercentOffInAFewSeconds) {
  const double truth = 0.4905;
  for (const double factor : {0.8, 1.2}) {
    for (unsigned seed = 1; seed <= 5; ++seed) {
      const double estimate = estimate_after(truth * factor, truth, 3.0, seed);
      EXPECT_NEAR(estimate, truth, 0.03 * truth) << "factor " << factor << " seed " << seed;
    }
  }
}

TEST(HoverThrustEstimator, StaysWithinItsBoundsAndRefusesNonsense) {
  HoverThrustEstimatorParams params;
  params.initial = 0.5;
  params.min = 0.4;
  params.max = 0.6;
  HoverThrustEstimator estimator(params);
  for (int k = 0; k < 500; ++k) estimator.update(0.5, 30.0, k * 0.02);  // "hovers" at 0.16
  EXPECT_DOUBLE_EQ(estimator.estimate(), 0.4);
  EXPECT_FALSE(estimator.update(std::nan(""), 9.81, 11.0));
  EXPECT_FALSE(estimator.update(0.5, std::nan(""), 11.0));
  EXPECT_FALSE(estimator.update(0.0, 9.81, 11.0));
  EXPECT_FALSE(estimator.update(0.5, 100.0, 11.0));
  EXPECT_DOUBLE_EQ(estimator.estimate(), 0.4);
}

CommandSpec arm_spec() {
  return AutopilotProfile(Autopilot::Px4).arm_command(true);
}

TEST(CommandSender, ResendsWithConfirmationUpToTheRetriesThenNoAnswer) {
  CommandSender sender(0.25, 3);
  const auto first = sender.start(arm_spec(), 7, 1, 42, 0.0, false);
  ASSERT_TRUE(first);
  EXPECT_EQ(first->confirmation, 0);
  EXPECT_EQ(first->target_system, 7);
  EXPECT_FALSE(sender.start(arm_spec(), 7, 1, 43, 0.1, false));  // one per command id
  std::vector<mav::CommandLong> resend;
  for (int k = 1; k <= 100; ++k) sender.poll(k * 0.02, resend);  // 2 s
  ASSERT_EQ(resend.size(), 3U);
  EXPECT_EQ(resend[0].confirmation, 1);
  EXPECT_EQ(resend[1].confirmation, 2);
  EXPECT_EQ(resend[2].confirmation, 3);
  ASSERT_EQ(sender.results().size(), 1U);
  EXPECT_EQ(sender.results()[0].token, 42U);
  EXPECT_EQ(sender.results()[0].outcome, CommandOutcome::NoAnswer);
  EXPECT_EQ(sender.results()[0].message, "no COMMAND_ACK after 4 sends");
  EXPECT_FALSE(sender.busy(mav::mav_cmd::kComponentArmDisarm));
}

TEST(CommandSender, AckAcceptsOrRefusesInWordsAndInProgressWaits) {
  CommandSender sender(0.25, 3);
  ASSERT_TRUE(sender.start(arm_spec(), 7, 1, 1, 0.0, false));
  mav::CommandAck ack;
  ack.command = mav::mav_cmd::kComponentArmDisarm;
  ack.result = mav::mav_result::kInProgress;
  sender.on_ack(ack, 7, 191, 0.1);
  std::vector<mav::CommandLong> resend;
  sender.poll(1.0, resend);
  EXPECT_TRUE(resend.empty());  // in progress: no resend
  ack.result = mav::mav_result::kDenied;
  ack.result_param2 = 3;
  ack.target_system = 9;  // someone else's answer
  sender.on_ack(ack, 7, 191, 1.1);
  EXPECT_TRUE(sender.results().empty());
  ack.target_system = 7;
  ack.target_component = 191;
  sender.on_ack(ack, 7, 191, 1.2);
  ASSERT_EQ(sender.results().size(), 1U);
  EXPECT_EQ(sender.results()[0].outcome, CommandOutcome::Refused);
  EXPECT_EQ(sender.results()[0].message, "denied (reason code 3)");
}

TEST(CommandSender, PreemptSupersedesTheCommandInFlight) {
  CommandSender sender(0.25, 3);
  const auto offboard = AutopilotProfile(Autopilot::ArduPilot).offboard_command();
  const auto land = AutopilotProfile(Autopilot::ArduPilot).land_command();
  ASSERT_TRUE(sender.start(offboard, 7, 1, 1, 0.0, false));
  const auto sent = sender.start(land, 7, 1, 2, 0.05, true);
  ASSERT_TRUE(sent);
  EXPECT_EQ(sent->param[1], 9.0F);
  ASSERT_EQ(sender.results().size(), 1U);
  EXPECT_EQ(sender.results()[0].token, 1U);
  EXPECT_EQ(sender.results()[0].outcome, CommandOutcome::Refused);
}

}  // namespace
}  // namespace cover::fc_bridge
