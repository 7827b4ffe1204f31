// The simulated PX4 / ArduPilot autopilot driven by frames from our Encoder, as a
// flight-controller bridge would drive it: mode and arming rules, the setpoint's mapping
// onto the plant, offboard loss, land mode, the streams and fault injection.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "autopilot_bench.hpp"
#include "cover/sim/fc/frame_conventions.hpp"

namespace {

using cover::Autopilot;
using cover::sim::fc::AutopilotEvent;
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
  const bool is_px4 = bench.autopilot().profile() == Autopilot::Px4;
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

// PX4 SITL, disarmed, no setpoint for over a minute: DO_SET_MODE OFFBOARD answered ACCEPTED
// twice, the HEARTBEAT showing OFFBOARD; the arm then TEMPORARILY_REJECTED with two EVENTs.
TEST(SimulatedAutopilot, Px4AcceptsOffboardDisarmedWithoutSetpointsAndRefusesTheArmThen) {
  AutopilotBench bench(Autopilot::Px4);
  bench.idle(2.0);
  bench.clear();
  auto ack = bench.set_mode(kPx4Offboard);
  ASSERT_TRUE(ack);
  EXPECT_EQ(ack->command, mav::mav_cmd::kDoSetMode);
  EXPECT_EQ(ack->result, mav::mav_result::kAccepted);
  EXPECT_EQ(ack->target_system, 245);
  EXPECT_EQ(ack->target_component, mav::mav_comp::kOnboardComputer);
  EXPECT_EQ(bench.autopilot().mode(), FlightMode::Offboard);
  bench.idle(1.0);
  EXPECT_EQ(bench.sent<mav::Heartbeat>().back().custom_mode, px4::custom_mode(kPx4Offboard));

  bench.clear();
  ack = bench.arm();
  ASSERT_TRUE(ack);
  EXPECT_EQ(ack->result, mav::mav_result::kTemporarilyRejected);
  EXPECT_FALSE(bench.autopilot().armed());
  EXPECT_EQ(bench.event_texts(),
            (std::vector<std::string>{"Arming denied: Resolve system health failures first",
                                      "No offboard signal"}));
  EXPECT_TRUE(bench.sent<mav::StatusText>().empty());  // PX4: EVENTs only
  for (const auto& e : bench.sent<mav::Event>()) EXPECT_EQ(e.log_levels & 0x0F, 2);  // critical

  bench.stream(0.1, 0.0F);  // an offboard signal: a setpoint within COM_OF_LOSS_T
  EXPECT_EQ(bench.arm()->result, mav::mav_result::kAccepted);
  EXPECT_EQ(bench.event_texts().back(), "Armed by external command");
}

TEST(SimulatedAutopilot, Px4AnswersEveryDoSetModeWithTwoIdenticalAcks) {
  AutopilotBench bench(Autopilot::Px4);
  for (const std::uint32_t main :
       {std::uint32_t{px4::kMainPosctl}, kPx4Offboard, std::uint32_t{99}}) {
    bench.clear();
    bench.set_mode(main);
    const auto acks = bench.sent<mav::CommandAck>();
    ASSERT_EQ(acks.size(), 2u) << main;
    EXPECT_EQ(acks[0].result, acks[1].result);
    EXPECT_EQ(acks[0].command, acks[1].command);
    EXPECT_EQ(acks[0].target_system, acks[1].target_system);
  }
  AutopilotBench ardupilot(Autopilot::ArduPilot);
  ardupilot.set_mode(copter::kLoiter);
  EXPECT_EQ(ardupilot.sent<mav::CommandAck>().size(), 1u);
  bench.clear();
  bench.arm(true, 21196.0F);
  EXPECT_EQ(bench.sent<mav::CommandAck>().size(), 1u);  // COMPONENT_ARM_DISARM: one
}

// Armed, PX4 checks OFFBOARD's requirements: the offboard signal.
TEST(SimulatedAutopilot, Px4RefusesOffboardWhileArmedWithoutAnOffboardSignal) {
  AutopilotBench bench(Autopilot::Px4);
  ASSERT_EQ(bench.arm()->result, mav::mav_result::kAccepted);  // in AUTO.LOITER: no stream needed
  bench.clear();
  EXPECT_EQ(bench.set_mode(kPx4Offboard)->result, mav::mav_result::kTemporarilyRejected);
  EXPECT_EQ(bench.autopilot().mode(), FlightMode::Hold);
  EXPECT_EQ(bench.event_texts(),
            (std::vector<std::string>{"Switching to mode 'Offboard' is currently not possible",
                                      "No offboard signal"}));
  bench.stream(0.2, 0.0F);
  EXPECT_EQ(bench.set_mode(kPx4Offboard)->result, mav::mav_result::kAccepted);
}

// ArduCopter SITL: GUIDED_NOGPS with no setpoints ACK 0, then arming ACK 0 ("Arming motors").
TEST(SimulatedAutopilot, ArduPilotEntersGuidedNoGpsWithoutSetpointsAndArmsInIt) {
  AutopilotBench bench(Autopilot::ArduPilot);
  bench.companion_heartbeat();
  EXPECT_EQ(bench.set_mode(copter::kGuidedNoGps)->result, mav::mav_result::kAccepted);
  EXPECT_EQ(bench.autopilot().mode(), FlightMode::Offboard);
  EXPECT_EQ(bench.arm()->result, mav::mav_result::kAccepted);
  EXPECT_TRUE(bench.autopilot().armed());
  EXPECT_EQ(bench.last_statustext(), "Arming motors");
}

// The offboard signal is PX4's: a setpoint within COM_OF_LOSS_T (offboardCheck.cpp).
TEST(SimulatedAutopilot, Px4OffboardSignalIsASetpointWithinComOfLossT) {
  AutopilotBench bench(Autopilot::Px4);
  ASSERT_EQ(bench.set_mode(kPx4Offboard)->result, mav::mav_result::kAccepted);
  bench.send(bench.setpoint(0.0F));
  bench.idle(0.95);
  EXPECT_EQ(bench.arm()->result, mav::mav_result::kAccepted);
  EXPECT_EQ(bench.arm(false)->result, mav::mav_result::kAccepted);
  bench.idle(0.1);  // 1.05 s since the setpoint
  EXPECT_EQ(bench.arm()->result, mav::mav_result::kTemporarilyRejected);
}

TEST(SimulatedAutopilot, ArmsOnlyByCommand) {
  AutopilotBench bench(Autopilot::Px4);
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
  AutopilotBench bench(Autopilot::Px4);
  bench.stream(1.0, 0.0F);
  ASSERT_EQ(bench.set_mode(kPx4Offboard)->result, mav::mav_result::kAccepted);
  bench.idle(1.1);
  EXPECT_EQ(bench.arm()->result, mav::mav_result::kTemporarilyRejected);
  EXPECT_TRUE(has_event(bench.autopilot(), AutopilotEvent::Kind::Refusal,
                        "Arming denied: no offboard signal"));
  EXPECT_FALSE(bench.autopilot().armed());
  EXPECT_EQ(bench.arm(true, 21196.0F)->result, mav::mav_result::kAccepted);
  EXPECT_TRUE(bench.autopilot().armed());
  EXPECT_TRUE(has_event(bench.autopilot(), AutopilotEvent::Kind::Arming, "FORCED"));
}

// ArduCopter SITL, descending in LAND: the disarm answered 4 FAILED, no text.
TEST(SimulatedAutopilot, DisarmingInTheAirIsRefused) {
  AutopilotBench bench(Autopilot::ArduPilot);
  fly_offboard(bench, 0.7F);
  bench.stream(1.0, 0.7F);
  ASSERT_EQ(bench.command(mav::mav_cmd::kNavLand)->result, mav::mav_result::kAccepted);
  bench.idle(0.5);
  ASSERT_GT(bench.world().state().uav.position_m.z, 0.2);
  bench.clear();
  EXPECT_EQ(bench.arm(false)->result, mav::mav_result::kFailed);
  EXPECT_TRUE(bench.autopilot().armed());
  EXPECT_TRUE(bench.sent<mav::StatusText>().empty());
  EXPECT_TRUE(
      has_event(bench.autopilot(), AutopilotEvent::Kind::Refusal, "Disarming denied: not landed"));

  AutopilotBench px4_bench(Autopilot::Px4);
  fly_offboard(px4_bench, 0.7F);
  px4_bench.stream(1.0, 0.7F);
  EXPECT_EQ(px4_bench.arm(false)->result, mav::mav_result::kTemporarilyRejected);
  EXPECT_EQ(px4_bench.event_texts().back(), "Disarming denied: not landed");
}

TEST(SimulatedAutopilot, HeartbeatCarriesEachProfilesCustomMode) {
  AutopilotBench px4_bench(Autopilot::Px4);
  px4_bench.tick();
  auto hb = px4_bench.sent<mav::Heartbeat>().at(0);
  EXPECT_EQ(hb.autopilot, mav::mav_autopilot::kPx4);
  EXPECT_EQ(hb.type, mav::mav_type::kQuadrotor);
  // AUTO.LOITER (Hold): PX4 SITL's mode after boot; main mode 4 in bits 16-23, sub mode 3 in
  // bits 24-31.
  EXPECT_EQ(hb.custom_mode, 0x03040000u);
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

  AutopilotBench ardu_bench(Autopilot::ArduPilot);
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

TEST(SimulatedAutopilot, Px4OffboardLossDescendsAfterComOfLossTAndDisarmsTwoSecondsAfterTouchdown) {
  AutopilotBench bench(Autopilot::Px4);
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
  const auto texts = bench.event_texts();
  EXPECT_NE(std::find(texts.begin(), texts.end(), "Failsafe activated: switching to Descend"),
            texts.end());
  bench.idle(1.0);
  EXPECT_EQ(bench.sent<mav::Heartbeat>().back().system_status, mav::mav_state::kCritical);

  // Descends levelled at the land speed; touches down; disarms COM_DISARM_LAND (2 s) later.
  double tilt_cos = 1.0;
  double touchdown_s = -1.0;
  for (int i = 0; i < 2000 && bench.autopilot().armed(); ++i) {
    bench.tick();
    const auto q = bench.world().state().uav.attitude.eigen();
    tilt_cos = std::min(tilt_cos, (q * Eigen::Vector3d::UnitZ()).z());
    if (touchdown_s < 0.0 && bench.world().state().uav_contact.resting) touchdown_s = bench.t_s();
  }
  EXPECT_FALSE(bench.autopilot().armed());
  EXPECT_TRUE(bench.world().state().uav_contact.resting);
  EXPECT_GT(tilt_cos, std::cos(0.3));
  double disarmed_s = -1.0;
  for (const auto& e : bench.autopilot().events()) {
    if (e.text == "Disarmed (auto: landed)") disarmed_s = e.time_s;
  }
  ASSERT_GT(touchdown_s, 0.0);
  EXPECT_NEAR(disarmed_s - touchdown_s, 2.0, 0.011);
  EXPECT_EQ(bench.event_texts().back(), "Disarmed by landing");
  EXPECT_TRUE(bench.autopilot().landed_in_land_mode());
  EXPECT_EQ(bench.tick().plant_command.thrust_m_s2, 0.0);
  bench.idle(1.0);
  EXPECT_EQ(bench.sent<mav::ExtendedSysState>().back().landed_state,
            mav::mav_landed_state::kOnGround);
  // Disarmed after its landing, PX4 shows the mode the landing interrupted again.
  EXPECT_EQ(bench.autopilot().mode(), FlightMode::Offboard);
  const auto hb = bench.sent<mav::Heartbeat>().back();
  EXPECT_EQ(hb.custom_mode, px4::custom_mode(kPx4Offboard));
  EXPECT_EQ(hb.base_mode & mav::mav_mode_flag::kSafetyArmed, 0);
}

TEST(SimulatedAutopilot, LandModeDescendsAtTheLandSpeed) {
  SimFcParams params;
  params.land_speed_m_s = 0.4;
  AutopilotBench bench(Autopilot::Px4, cover::sim::fc::test::ground_world(), params);
  fly_offboard(bench, 0.7F);
  bench.stream(1.5, 0.6F);
  ASSERT_EQ(bench.command(mav::mav_cmd::kNavLand)->result, mav::mav_result::kAccepted);
  bench.idle(3.0);
  EXPECT_NEAR(bench.world().state().uav.velocity_m_s.z, -0.4, 0.05);
  bench.idle(0.2);
  EXPECT_EQ(bench.sent<mav::ExtendedSysState>().back().landed_state,
            mav::mav_landed_state::kLanding);
}

// `duration_s` without setpoints, the companion's HEARTBEAT once a second (alive, silent).
void alive_without_setpoints(AutopilotBench& bench, double duration_s) {
  for (double left = duration_s; left > 1e-9; left -= 1.0) {
    bench.companion_heartbeat();
    bench.idle(std::min(1.0, left));
  }
}

bool said(const AutopilotBench& bench, const std::string& words) {
  for (const auto& t : bench.sent<mav::StatusText>()) {
    if (t.text_string().find(words) != std::string::npos) return true;
  }
  return false;
}

SimFcParams watching_the_bench() {
  SimFcParams params;
  params.ardupilot.mav_gcs_sysid = 245;  // the bench's companion
  return params;
}

// ArduCopter without setpoints levels and holds its height after GUID_TIMEOUT (3 s), for as
// long as the companion's HEARTBEAT comes; once that stops, its GCS failsafe (FS_GCS_ENABLE
// 5) lands FS_GCS_TIMEOUT (5 s) after the last one: the height held 4 s, then a descent.
TEST(SimulatedAutopilot, ArduPilotGuidedTimeoutLevelsAndTheGcsFailsafeLands) {
  AutopilotBench bench(Autopilot::ArduPilot, cover::sim::fc::test::ground_world(),
                       watching_the_bench());
  bench.companion_heartbeat();
  fly_offboard(bench, 0.7F);
  bench.stream(1.0, 0.6F);
  bench.companion_heartbeat();
  bench.stream(1.0, 0.515F);  // about hover
  alive_without_setpoints(bench, 2.9);
  EXPECT_TRUE(bench.autopilot().events().back().kind != AutopilotEvent::Kind::Failsafe);
  alive_without_setpoints(bench, 0.2);  // GUID_TIMEOUT = 3 s: levelled, height held
  EXPECT_EQ(bench.autopilot().mode(), FlightMode::Offboard);
  EXPECT_TRUE(has_event(bench.autopilot(), AutopilotEvent::Kind::Failsafe, "levelling"));
  const double height_m = bench.world().state().uav.position_m.z;
  alive_without_setpoints(bench, 8.0);  // the companion alive: held, as long as it lives
  EXPECT_EQ(bench.autopilot().mode(), FlightMode::Offboard);
  EXPECT_NEAR(bench.world().state().uav.position_m.z, height_m, 0.3);
  bench.companion_heartbeat();  // its last
  bench.idle(4.9);
  EXPECT_EQ(bench.autopilot().mode(), FlightMode::Offboard);
  bench.idle(0.2);  // FS_GCS_TIMEOUT = 5 s after it
  EXPECT_EQ(bench.autopilot().mode(), FlightMode::Land);
  EXPECT_TRUE(said(bench, "GCS Failsafe"));
  bench.idle(3.5);  // the failsafe's LAND holds its height 4 s first
  EXPECT_NEAR(bench.world().state().uav.position_m.z, height_m, 0.3);
  bench.idle(2.0);
  EXPECT_LT(bench.world().state().uav.velocity_m_s.z, -0.3);
  bench.companion_heartbeat();  // back: the failsafe clears, the LAND goes on
  bench.idle(0.1);
  EXPECT_TRUE(said(bench, "GCS Failsafe Cleared"));
  EXPECT_EQ(bench.sent<mav::Heartbeat>().back().custom_mode, copter::kLand);
}

// Only the watched system's HEARTBEAT counts, and only once one has come; armed on the
// ground, the failsafe disarms.
TEST(SimulatedAutopilot, ArduPilotGcsFailsafeWatchesOneSystemAndDisarmsOnTheGround) {
  {
    AutopilotBench bench(Autopilot::ArduPilot);  // watches its own id; the bench is 245
    bench.companion_heartbeat();
    fly_offboard(bench, 0.0F);
    bench.idle(6.0);
    EXPECT_TRUE(bench.autopilot().armed()) << "a HEARTBEAT of another system was watched";
  }
  AutopilotBench bench(Autopilot::ArduPilot, cover::sim::fc::test::ground_world(),
                       watching_the_bench());
  fly_offboard(bench, 0.0F);
  bench.companion_heartbeat();  // the first and last
  bench.idle(4.9);
  EXPECT_TRUE(bench.autopilot().armed());
  bench.idle(0.2);
  EXPECT_FALSE(bench.autopilot().armed());
  EXPECT_TRUE(said(bench, "GCS Failsafe - Disarming"));
}

TEST(SimulatedAutopilot, ThrustIsTheTrueMaxThrustTimesTheSetpoint) {
  auto world = cover::sim::fc::test::ground_world();
  world.uav.max_thrust_m_s2 = 25.0;
  AutopilotBench bench(Autopilot::Px4, world);
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
  AutopilotBench bench(Autopilot::Px4, world);
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
  const Eigen::Quaterniond q = cover::sim::ned_frd_attitude(north);
  EXPECT_NEAR(std::abs(q.w()), 1.0, 1e-12);
  // Pitching nose up in ENU/FLU (negative rotation about FLU y) is nose up in FRD too.
  const Eigen::Quaterniond nose_up =
      north * Eigen::Quaterniond(Eigen::AngleAxisd(-0.2, Eigen::Vector3d::UnitY()));
  const Eigen::Vector3d forward_ned =
      cover::sim::ned_frd_attitude(nose_up) * Eigen::Vector3d::UnitX();
  EXPECT_LT(forward_ned.z(), 0.0);  // NED z is down: the nose points up
}

TEST(SimulatedAutopilot, ModeSwitchInjectionTakesOverFromTheSetpoints) {
  AutopilotBench bench(Autopilot::Px4);
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
  AutopilotBench bench(Autopilot::Px4);
  auto wrong_target = bench.setpoint(0.5F);
  wrong_target.target_system = 1;
  EXPECT_FALSE(bench.send(wrong_target).setpoint_accepted);
  // The firmwares ignore such frames silently; cover-sim's log says why.
  EXPECT_TRUE(bench.sent<mav::StatusText>().empty());
  EXPECT_EQ(bench.autopilot().events().back().text,
            "Setpoint for system 1 ignored: this is system 3");
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
  AutopilotBench bench(Autopilot::Px4);
  mav::Encoder onboard(AutopilotBench::kSystem, mav::mav_comp::kOnboardComputer);
  EXPECT_TRUE(bench.send(bench.setpoint(0.5F), &onboard).setpoint_accepted);
}

TEST(SimulatedAutopilot, AnswersTimesyncAndReleasesThePayloadOnTheGripperCommand) {
  AutopilotBench bench(Autopilot::Px4);
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

// PX4 SITL's onboard link without a request, over 2 s (docs/autopilots.md, measured on real SITL).
TEST(SimulatedAutopilot, Px4StreamsItsOnboardSetAndHeartbeatsStopOnInjection) {
  AutopilotBench bench(Autopilot::Px4);
  bench.idle(2.0);
  EXPECT_EQ(bench.sent<mav::Heartbeat>().size(), 2u);
  EXPECT_EQ(bench.count(30), 200u);  // ATTITUDE 100 Hz
  EXPECT_EQ(bench.sent<mav::AttitudeQuaternion>().size(), 100u);
  EXPECT_EQ(bench.sent<mav::HighresImu>().size(), 100u);
  EXPECT_EQ(bench.sent<mav::AttitudeTarget>().size(), 20u);
  EXPECT_EQ(bench.sent<mav::ExtendedSysState>().size(), 10u);
  EXPECT_EQ(bench.sent<mav::SysStatus>().size(), 10u);
  EXPECT_EQ(bench.sent<mav::BatteryStatus>().size(), 1u);
  EXPECT_EQ(bench.sent<mav::EstimatorStatus>().size(), 2u);
  // ALTITUDE and VFR_HUD at 10 Hz: skipped whole by our parser, nothing refused.
  EXPECT_GE(bench.parser_stats().unknown_frames, 39u);
  EXPECT_EQ(bench.parser_stats().errors(), 0u);
  EXPECT_EQ(bench.parser_stats().unknown_ids, 0u);
  EXPECT_TRUE(bench.sent<mav::StatusText>().empty());
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
  AutopilotBench bench(Autopilot::Px4);
  fly_offboard(bench, 0.7F);
  bench.stream(3.0, 0.55F);
  const auto status = bench.sent<mav::SysStatus>().back();
  EXPECT_LT(status.voltage_battery, 16800);
  EXPECT_GT(status.voltage_battery, 14000);
  EXPECT_GT(status.current_battery, 500);  // > 5 A in flight
  EXPECT_LE(status.battery_remaining, 100);
}

}  // namespace
