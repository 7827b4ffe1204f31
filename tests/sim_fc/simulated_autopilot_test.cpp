// The simulated PX4 / ArduPilot autopilot driven by frames from our Encoder, as a
// flight-controller bridge would drive it: mode and arming rules, the setpoint's mapping
// onto the plant, offboard loss, land mode, the streams and fault injection.
#include <gtest/gtest.h>

#include <cmath>

#include "autopilot_bench.hpp"
#include "cover/sim/fc/frame_conventions.hpp"

namespace {

using cover::sim::fc::AutopilotEvent;
using cover::sim::fc::AutopilotProfile;
using cover::sim::fc::FlightMode;
using cover::sim::fc::SimFcParams;
using cover::sim::fc::test::AutopilotBench;
namespace mav = cover::mavlink;
namespace px4 = cover::mavlink::px4_mode;
namespace copter = cover::mavlink::copter_mode;

constexpr std::uint32_t kPx4Offboard = px4::kMainOffboard;
constexpr double kMaxThrust = 20.0;  // config/sim/world_default.yaml

// Streams 1 s of setpoints, switches to OFFBOARD / GUIDED_NOGPS and arms.
void fly_offboard(AutopilotBench& bench, float thrust) {
  bench.stream(1.0, thrust);
  const bool is_px4 = bench.autopilot().profile() == AutopilotProfile::Px4;
  ASSERT_EQ(bench.set_mode(is_px4 ? kPx4Offboard : copter::kGuidedNoGps)->result,
            mav::mav_result::kAccepted);
  ASSERT_EQ(bench.arm()->result, mav::mav_result::kAccepted);
}

bool has_event(const cover::sim::fc::SimulatedAutopilot& autopilot, AutopilotEvent::Kind kind,
               const std::string& text) {
  for (const auto& e : autopilot.events()) {
    if (e.kind == kind && e.text.find(text) != std::string::npos) return true;
  }
  return false;
}

TEST(SimulatedAutopilot, OffboardRefusedBeforeAStreamAndAcceptedAfterOneSecondAt50Hz) {
  AutopilotBench bench(AutopilotProfile::Px4);
  auto ack = bench.set_mode(kPx4Offboard);
  ASSERT_TRUE(ack);
  EXPECT_EQ(ack->command, mav::mav_cmd::kDoSetMode);
  EXPECT_EQ(ack->result, mav::mav_result::kTemporarilyRejected);
  EXPECT_EQ(ack->target_system, 245);
  EXPECT_EQ(ack->target_component, mav::mav_comp::kOnboardComputer);
  EXPECT_EQ(bench.last_statustext(), "Offboard: no setpoint stream");
  EXPECT_EQ(bench.autopilot().mode(), FlightMode::Manual);

  bench.stream(0.5, 0.0F);  // half a second is not enough
  EXPECT_EQ(bench.set_mode(kPx4Offboard)->result, mav::mav_result::kTemporarilyRejected);
  bench.stream(0.5, 0.0F);
  EXPECT_EQ(bench.set_mode(kPx4Offboard)->result, mav::mav_result::kAccepted);
  EXPECT_EQ(bench.autopilot().mode(), FlightMode::Offboard);
  bench.tick();
  EXPECT_EQ(bench.sent<mav::Heartbeat>().back().custom_mode, px4::custom_mode(kPx4Offboard));
}

TEST(SimulatedAutopilot, GuidedNoGpsRefusedAsFailedOnArduPilot) {
  AutopilotBench bench(AutopilotProfile::ArduPilot);
  EXPECT_EQ(bench.set_mode(copter::kGuidedNoGps)->result, mav::mav_result::kFailed);
  EXPECT_NE(bench.last_statustext().find("no setpoint stream"), std::string::npos);
  bench.stream(1.0, 0.0F);
  EXPECT_EQ(bench.set_mode(copter::kGuidedNoGps)->result, mav::mav_result::kAccepted);
}

TEST(SimulatedAutopilot, AStreamWithAGapStartsAgain) {
  AutopilotBench bench(AutopilotProfile::Px4);
  bench.stream(0.8, 0.0F);
  bench.idle(0.6);  // slower than 2 Hz: the stream is broken
  bench.stream(0.6, 0.0F);
  EXPECT_EQ(bench.set_mode(kPx4Offboard)->result, mav::mav_result::kTemporarilyRejected);
  bench.stream(0.4, 0.0F);
  EXPECT_EQ(bench.set_mode(kPx4Offboard)->result, mav::mav_result::kAccepted);
}

TEST(SimulatedAutopilot, ArmsOnlyByCommand) {
  AutopilotBench bench(AutopilotProfile::Px4);
  bench.stream(1.0, 0.7F);
  EXPECT_EQ(bench.set_mode(kPx4Offboard)->result, mav::mav_result::kAccepted);
  auto step = bench.stream(0.5, 0.7F);
  EXPECT_FALSE(bench.autopilot().armed());  // setpoints and OFFBOARD never arm
  EXPECT_EQ(step.plant_command.thrust_m_s2, 0.0);
  EXPECT_EQ(bench.sent<mav::Heartbeat>().back().base_mode & mav::mav_mode_flag::kSafetyArmed, 0);

  EXPECT_EQ(bench.arm()->result, mav::mav_result::kAccepted);
  step = bench.stream(0.1, 0.7F);
  EXPECT_TRUE(bench.autopilot().armed());
  EXPECT_NEAR(step.plant_command.thrust_m_s2, 0.7 * kMaxThrust, 1e-5);
  bench.idle(1.0);  // let the next heartbeat out
  EXPECT_NE(bench.sent<mav::Heartbeat>().back().base_mode & mav::mav_mode_flag::kSafetyArmed, 0);
  EXPECT_TRUE(has_event(bench.autopilot(), AutopilotEvent::Kind::Arming, "Armed (commanded)"));
}

TEST(SimulatedAutopilot, ArmingInOffboardNeedsAFreshSetpointUnlessForced) {
  AutopilotBench bench(AutopilotProfile::Px4);
  bench.stream(1.0, 0.0F);
  ASSERT_EQ(bench.set_mode(kPx4Offboard)->result, mav::mav_result::kAccepted);
  bench.idle(0.6);
  EXPECT_EQ(bench.arm()->result, mav::mav_result::kTemporarilyRejected);
  EXPECT_EQ(bench.last_statustext(), "Arming denied: no offboard setpoint");
  EXPECT_FALSE(bench.autopilot().armed());
  EXPECT_EQ(bench.arm(true, 21196.0F)->result, mav::mav_result::kAccepted);
  EXPECT_TRUE(bench.autopilot().armed());
  EXPECT_TRUE(has_event(bench.autopilot(), AutopilotEvent::Kind::Arming, "FORCED"));
}

TEST(SimulatedAutopilot, DisarmingInTheAirIsRefused) {
  AutopilotBench bench(AutopilotProfile::ArduPilot);
  fly_offboard(bench, 0.7F);
  bench.stream(1.0, 0.7F);
  ASSERT_GT(bench.world().state().uav.position_m.z, 0.2);
  EXPECT_EQ(bench.arm(false)->result, mav::mav_result::kFailed);
  EXPECT_TRUE(bench.autopilot().armed());
  EXPECT_EQ(bench.last_statustext(), "Disarming denied: not landed");
}

TEST(SimulatedAutopilot, HeartbeatCarriesEachProfilesCustomMode) {
  AutopilotBench px4_bench(AutopilotProfile::Px4);
  px4_bench.tick();
  auto hb = px4_bench.sent<mav::Heartbeat>().at(0);
  EXPECT_EQ(hb.autopilot, mav::mav_autopilot::kPx4);
  EXPECT_EQ(hb.type, mav::mav_type::kQuadrotor);
  EXPECT_EQ(hb.custom_mode, 0x00010000u);  // MANUAL: main mode 1 in bits 16-23
  EXPECT_EQ(hb.base_mode, mav::mav_mode_flag::kCustomModeEnabled);
  EXPECT_EQ(hb.system_status, mav::mav_state::kStandby);
  EXPECT_EQ(px4_bench.received().at(0).system_id, AutopilotBench::kSystem);
  EXPECT_EQ(px4_bench.received().at(0).component_id, 1);
  EXPECT_EQ(px4_bench.set_mode(px4::kMainPosctl)->result, mav::mav_result::kAccepted);
  px4_bench.idle(1.0);
  EXPECT_EQ(px4_bench.sent<mav::Heartbeat>().back().custom_mode, 0x00030000u);
  EXPECT_EQ(px4_bench.command(mav::mav_cmd::kNavLand)->result, mav::mav_result::kAccepted);
  px4_bench.idle(1.0);
  // AUTO (4) with sub mode LAND (6) in bits 24-31.
  EXPECT_EQ(px4_bench.sent<mav::Heartbeat>().back().custom_mode, 0x06040000u);

  AutopilotBench ardu_bench(AutopilotProfile::ArduPilot);
  ardu_bench.tick();
  hb = ardu_bench.sent<mav::Heartbeat>().at(0);
  EXPECT_EQ(hb.autopilot, mav::mav_autopilot::kArdupilotMega);
  EXPECT_EQ(hb.custom_mode, copter::kStabilize);
  EXPECT_EQ(ardu_bench.set_mode(copter::kLoiter)->result, mav::mav_result::kAccepted);
  EXPECT_EQ(ardu_bench.set_mode(copter::kLand)->result, mav::mav_result::kAccepted);
  ardu_bench.idle(1.0);
  EXPECT_EQ(ardu_bench.sent<mav::Heartbeat>().back().custom_mode, copter::kLand);
  EXPECT_EQ(ardu_bench.set_mode(copter::kAuto)->result, mav::mav_result::kFailed);  // not simulated
}

TEST(SimulatedAutopilot, Px4OffboardLossLandsAfterComOfLossTAndDisarmsOnTouchdown) {
  AutopilotBench bench(AutopilotProfile::Px4);
  fly_offboard(bench, 0.7F);
  bench.stream(1.0, 0.6F);
  ASSERT_GT(bench.world().state().uav.position_m.z, 0.5);
  const double last_setpoint_s = bench.t_s() - 2 * AutopilotBench::kPeriodS;
  bench.idle(0.95);
  EXPECT_EQ(bench.autopilot().mode(), FlightMode::Offboard);  // COM_OF_LOSS_T = 1 s
  bench.idle(0.1);
  EXPECT_EQ(bench.autopilot().mode(), FlightMode::Land);
  ASSERT_EQ(bench.autopilot().events().size() > 0, true);
  double failsafe_s = -1.0;
  for (const auto& e : bench.autopilot().events()) {
    if (e.kind == AutopilotEvent::Kind::Failsafe) failsafe_s = e.time_s;
  }
  EXPECT_NEAR(failsafe_s - last_setpoint_s, 1.0, 0.011);
  bool said_so = false;
  for (const auto& t : bench.sent<mav::StatusText>()) {
    said_so = said_so || t.text_string().find("Failsafe: offboard lost") == 0;
    if (t.text_string().find("Failsafe") == 0) {
      EXPECT_EQ(t.severity, 2);
    }
  }
  EXPECT_TRUE(said_so);
  bench.idle(1.0);
  EXPECT_EQ(bench.sent<mav::Heartbeat>().back().system_status, mav::mav_state::kCritical);

  // Descends levelled at the land speed and disarms on touchdown.
  double tilt_cos = 1.0;
  for (int i = 0; i < 1500 && bench.autopilot().armed(); ++i) {
    bench.tick();
    const auto q = bench.world().state().uav.attitude.eigen();
    tilt_cos = std::min(tilt_cos, (q * Eigen::Vector3d::UnitZ()).z());
  }
  EXPECT_FALSE(bench.autopilot().armed());
  EXPECT_TRUE(bench.world().state().uav_contact.resting);
  EXPECT_GT(tilt_cos, std::cos(0.3));
  EXPECT_TRUE(has_event(bench.autopilot(), AutopilotEvent::Kind::Arming, "Disarmed (landed)"));
  EXPECT_EQ(bench.tick().plant_command.thrust_m_s2, 0.0);
  bench.idle(0.3);
  EXPECT_EQ(bench.sent<mav::ExtendedSysState>().back().landed_state,
            mav::mav_landed_state::kOnGround);
}

TEST(SimulatedAutopilot, LandModeDescendsAtTheLandSpeed) {
  SimFcParams params;
  params.land_speed_m_s = 0.4;
  AutopilotBench bench(AutopilotProfile::Px4, cover::sim::fc::test::ground_world(), params);
  fly_offboard(bench, 0.7F);
  bench.stream(1.5, 0.6F);
  ASSERT_EQ(bench.command(mav::mav_cmd::kNavLand)->result, mav::mav_result::kAccepted);
  bench.idle(3.0);
  EXPECT_NEAR(bench.world().state().uav.velocity_m_s.z, -0.4, 0.05);
  bench.idle(0.2);
  EXPECT_EQ(bench.sent<mav::ExtendedSysState>().back().landed_state,
            mav::mav_landed_state::kLanding);
}

TEST(SimulatedAutopilot, ArduPilotGuidedTimeoutLevelsThenLands) {
  AutopilotBench bench(AutopilotProfile::ArduPilot);
  fly_offboard(bench, 0.7F);
  bench.stream(1.0, 0.6F);
  bench.stream(1.0, 0.515F);  // about hover
  bench.idle(2.9);
  EXPECT_TRUE(bench.autopilot().events().back().kind != AutopilotEvent::Kind::Failsafe);
  bench.idle(0.2);  // GUID_TIMEOUT = 3 s: levelled, height held, still GUIDED_NOGPS
  EXPECT_EQ(bench.autopilot().mode(), FlightMode::Offboard);
  EXPECT_TRUE(has_event(bench.autopilot(), AutopilotEvent::Kind::Failsafe, "levelling"));
  const double height_m = bench.world().state().uav.position_m.z;
  bench.idle(1.5);
  EXPECT_NEAR(bench.world().state().uav.position_m.z, height_m, 0.3);
  bench.idle(0.6);  // guid_level_hold_s = 2 s later: LAND
  EXPECT_EQ(bench.autopilot().mode(), FlightMode::Land);
  bench.idle(1.0);
  EXPECT_EQ(bench.sent<mav::Heartbeat>().back().custom_mode, copter::kLand);
}

TEST(SimulatedAutopilot, ThrustIsTheTrueMaxThrustTimesTheSetpoint) {
  auto world = cover::sim::fc::test::ground_world();
  world.uav.max_thrust_m_s2 = 25.0;
  AutopilotBench bench(AutopilotProfile::Px4, world);
  fly_offboard(bench, 0.5F);
  bench.send(bench.setpoint(0.5F));
  EXPECT_DOUBLE_EQ(bench.tick().plant_command.thrust_m_s2, 12.5);
  bench.send(bench.setpoint(1.7F));  // beyond full throttle: full throttle
  EXPECT_DOUBLE_EQ(bench.tick().plant_command.thrust_m_s2, 25.0);
  bench.send(bench.setpoint(-0.2F));
  EXPECT_DOUBLE_EQ(bench.tick().plant_command.thrust_m_s2, 0.0);
}

TEST(SimulatedAutopilot, RatesFrdBecomeFluAndTelemetryIsNedFrd) {
  auto world = cover::sim::fc::test::ground_world();
  world.uav_initial.yaw_rad = 0.0;  // facing east (ENU x)
  AutopilotBench bench(AutopilotProfile::Px4, world);
  bench.tick();
  // At rest: the accelerometer reads -g along FRD z; the attitude faces east: NED yaw +90 deg.
  const auto imu = bench.sent<mav::HighresImu>().back();
  EXPECT_NEAR(imu.zacc, -9.81, 1e-4);
  EXPECT_NEAR(imu.xacc, 0.0, 1e-6);
  EXPECT_EQ(imu.time_usec, 0u);
  const auto att = bench.sent<mav::AttitudeQuaternion>().back();
  EXPECT_NEAR(att.q1, std::sqrt(0.5), 1e-6);
  EXPECT_NEAR(att.q4, std::sqrt(0.5), 1e-6);
  EXPECT_NEAR(att.q2, 0.0, 1e-6);
  EXPECT_NEAR(att.q3, 0.0, 1e-6);

  fly_offboard(bench, 0.5F);
  bench.send(bench.setpoint(0.6F, 0.1F, -0.2F, 0.3F));
  const auto step = bench.tick();
  EXPECT_NEAR(step.plant_command.body_rate_rad_s.x, 0.1, 1e-6);
  EXPECT_NEAR(step.plant_command.body_rate_rad_s.y, 0.2, 1e-6);
  EXPECT_NEAR(step.plant_command.body_rate_rad_s.z, -0.3, 1e-6);
  for (int i = 0; i < 20; ++i) {
    bench.send(bench.setpoint(0.6F, 0.1F, -0.2F, 0.3F));
    bench.tick();
  }
  // The plant turns FLU (0.1, 0.2, -0.3); its gyro, reported FRD, reads the setpoint back.
  const auto gyro = bench.sent<mav::HighresImu>().back();
  EXPECT_NEAR(gyro.xgyro, 0.1, 0.01);
  EXPECT_NEAR(gyro.ygyro, -0.2, 0.01);
  EXPECT_NEAR(gyro.zgyro, 0.3, 0.01);
  const auto target = bench.sent<mav::AttitudeTarget>().back();
  EXPECT_NEAR(target.body_pitch_rate, -0.2F, 1e-6);
  EXPECT_NEAR(target.thrust, 0.6F, 1e-6);
  EXPECT_EQ(target.type_mask, mav::attitude_target_typemask::kIgnoreAttitude);
}

TEST(SimulatedAutopilot, NedAttitudeOfANorthFacingVehicleIsIdentity) {
  const Eigen::Quaterniond north = cover::sim::yaw_quaternion(M_PI / 2);
  const Eigen::Quaterniond q = cover::sim::fc::ned_frd_attitude(north);
  EXPECT_NEAR(std::abs(q.w()), 1.0, 1e-12);
  // Pitching nose up in ENU/FLU (negative rotation about FLU y) is nose up in FRD too.
  const Eigen::Quaterniond nose_up =
      north * Eigen::Quaterniond(Eigen::AngleAxisd(-0.2, Eigen::Vector3d::UnitY()));
  const Eigen::Vector3d forward_ned =
      cover::sim::fc::ned_frd_attitude(nose_up) * Eigen::Vector3d::UnitX();
  EXPECT_LT(forward_ned.z(), 0.0);  // NED z is down: the nose points up
}

TEST(SimulatedAutopilot, ModeSwitchInjectionTakesOverFromTheSetpoints) {
  AutopilotBench bench(AutopilotProfile::Px4);
  fly_offboard(bench, 0.7F);
  bench.stream(1.0, 0.6F);
  bench.autopilot().inject_mode_switch(FlightMode::Position);
  EXPECT_EQ(bench.autopilot().mode(), FlightMode::Position);
  EXPECT_TRUE(has_event(bench.autopilot(), AutopilotEvent::Kind::Mode, "POSCTL (RC switch)"));
  const auto step = bench.stream(0.5, 0.9F);  // the companion keeps streaming: ignored
  EXPECT_LT(step.plant_command.thrust_m_s2, 0.9 * kMaxThrust - 3.0);
  EXPECT_NEAR(bench.world().state().uav.velocity_m_s.z, 0.0, 0.5);
  bench.idle(1.0);
  EXPECT_EQ(bench.sent<mav::Heartbeat>().back().custom_mode, 0x00030000u);
  EXPECT_TRUE(bench.autopilot().armed());
}

TEST(SimulatedAutopilot, SetpointsOnlyForThisSystemFromTheCompanionWithRatesAndThrust) {
  AutopilotBench bench(AutopilotProfile::Px4);
  auto wrong_target = bench.setpoint(0.5F);
  wrong_target.target_system = 1;
  EXPECT_FALSE(bench.send(wrong_target).setpoint_accepted);
  EXPECT_EQ(bench.last_statustext(), "Setpoint for system 1 ignored: this is system 3");
  auto attitude = bench.setpoint(0.5F);
  attitude.type_mask = 7;  // rates ignored, attitude used: not supported
  EXPECT_FALSE(bench.send(attitude).setpoint_accepted);
  auto no_thrust = bench.setpoint(0.5F);
  no_thrust.type_mask = 128 | 64;
  EXPECT_FALSE(bench.send(no_thrust).setpoint_accepted);
  auto nan = bench.setpoint(std::nanf(""));
  EXPECT_FALSE(bench.send(nan).setpoint_accepted);

  const auto ok = bench.send(bench.setpoint(0.5F));
  EXPECT_TRUE(ok.setpoint_accepted);
  EXPECT_EQ(ok.setpoint_time_boot_ms, 0u);
  mav::Encoder echo(AutopilotBench::kSystem, 1);  // its own frames coming back
  EXPECT_FALSE(bench.send(bench.setpoint(0.9F), &echo).setpoint_accepted);
  mav::Encoder intruder(200, 191);
  EXPECT_FALSE(bench.send(bench.setpoint(0.9F), &intruder).setpoint_accepted);
  EXPECT_EQ(bench.autopilot().setpoints_accepted(), 1u);
  EXPECT_EQ(bench.autopilot().setpoints_ignored(), 5u);
}

TEST(SimulatedAutopilot, TakesSetpointsFromACompanionOnItsOwnSystem) {
  AutopilotBench bench(AutopilotProfile::Px4);
  mav::Encoder onboard(AutopilotBench::kSystem, mav::mav_comp::kOnboardComputer);
  EXPECT_TRUE(bench.send(bench.setpoint(0.5F), &onboard).setpoint_accepted);
}

TEST(SimulatedAutopilot, AnswersTimesyncAndReleasesThePayloadOnTheGripperCommand) {
  AutopilotBench bench(AutopilotProfile::Px4);
  bench.idle(0.5);
  mav::Timesync request;
  request.ts1 = 123456789;
  const auto response = bench.send(request);
  ASSERT_EQ(response.frames.size(), 1u);
  const auto reply = bench.sent<mav::Timesync>().back();
  EXPECT_EQ(reply.ts1, 123456789);
  EXPECT_EQ(reply.tc1, 500'000'000);

  EXPECT_EQ(bench.command(211, 0.0F, 0.0F)->result, mav::mav_result::kAccepted);
  EXPECT_TRUE(bench.tick().release_payload);
  EXPECT_FALSE(bench.tick().release_payload);
  EXPECT_NE(bench.command(211, 0.0F, 1.0F)->result, mav::mav_result::kAccepted);  // grab
  EXPECT_EQ(bench.command(512)->result, mav::mav_result::kUnsupported);
  mav::CommandLong elsewhere;
  elsewhere.command = mav::mav_cmd::kComponentArmDisarm;
  elsewhere.param[0] = 1.0F;
  elsewhere.target_system = 9;
  EXPECT_TRUE(bench.send(elsewhere).frames.empty());  // not addressed to it: silence
}

TEST(SimulatedAutopilot, StreamsAtTheirRatesAndHeartbeatsStopOnInjection) {
  AutopilotBench bench(AutopilotProfile::ArduPilot);
  bench.idle(2.0);
  EXPECT_EQ(bench.sent<mav::Heartbeat>().size(), 2u);
  EXPECT_EQ(bench.sent<mav::AttitudeQuaternion>().size(), 100u);
  EXPECT_EQ(bench.sent<mav::HighresImu>().size(), 200u);
  EXPECT_EQ(bench.sent<mav::AttitudeTarget>().size(), 20u);
  EXPECT_EQ(bench.sent<mav::ExtendedSysState>().size(), 10u);
  EXPECT_EQ(bench.sent<mav::SysStatus>().size(), 2u);
  EXPECT_EQ(bench.sent<mav::BatteryStatus>().size(), 2u);
  const auto battery = bench.sent<mav::BatteryStatus>().back();
  EXPECT_NEAR(battery.voltages[0], 4200, 5);
  EXPECT_EQ(battery.voltages[4], UINT16_MAX);

  bench.autopilot().stop_heartbeats();
  bench.clear();
  bench.idle(2.0);
  EXPECT_TRUE(bench.sent<mav::Heartbeat>().empty());
  EXPECT_EQ(bench.sent<mav::AttitudeQuaternion>().size(), 100u);
  EXPECT_FALSE(bench.autopilot().heartbeat_frame());
}

TEST(SimulatedAutopilot, BatterySagsUnderLoadAndEmpties) {
  AutopilotBench bench(AutopilotProfile::Px4);
  fly_offboard(bench, 0.7F);
  bench.stream(3.0, 0.55F);
  const auto status = bench.sent<mav::SysStatus>().back();
  EXPECT_LT(status.voltage_battery, 16800);
  EXPECT_GT(status.voltage_battery, 14000);
  EXPECT_GT(status.current_battery, 500);  // > 5 A in flight
  EXPECT_LE(status.battery_remaining, 100);
}

}  // namespace
