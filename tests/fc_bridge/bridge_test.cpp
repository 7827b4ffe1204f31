#include "cover/fc_bridge/bridge.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "bridge_rig.hpp"
#include "cover/mavlink/state_messages.hpp"
#include "fake_autopilot.hpp"

namespace cover::fc_bridge {
namespace {

namespace mav = cover::mavlink;
using test::BridgeRig;
using test::commands;
using test::decoded;
using test::FakeAutopilot;
using test::kStep_s;
using test::kSys;
using Rig = BridgeRig;

TEST(Bridge, LearnsTheAutopilotsSystemIdAndTargetsIt) {
  Rig rig;
  FakeAutopilot ground_station(255, mav::mav_autopilot::kInvalid, 190);
  FakeAutopilot gimbal(kSys, mav::mav_autopilot::kPx4, 154);
  rig.bridge.on_frame(ground_station.heartbeat(false, 0), rig.t);
  rig.bridge.on_frame(gimbal.heartbeat(false, 0), rig.t);
  EXPECT_TRUE(rig.bridge.on_agent_command(rig.command(), rig.t).empty());  // no target yet
  EXPECT_EQ(rig.bridge.state(rig.t).system_id, 0);
  rig.heartbeat();
  rig.t += 0.01;
  const auto setpoints =
      decoded<mav::SetAttitudeTarget>(rig.bridge.on_agent_command(rig.command(), rig.t));
  ASSERT_EQ(setpoints.size(), 1U);
  EXPECT_EQ(setpoints[0].target_system, kSys);
  EXPECT_EQ(setpoints[0].target_component, 1);
  EXPECT_EQ(setpoints[0].type_mask, 128);
  const FcStatus s = rig.bridge.state(rig.t);
  EXPECT_EQ(s.system_id, kSys);
  EXPECT_TRUE(s.link_ok);
  EXPECT_EQ(s.reported_autopilot, mav::mav_autopilot::kPx4);
  rig.collect_notices();
  EXPECT_TRUE(rig.noticed("autopilot found: system 7 component 1, PX4"));
}

TEST(Bridge, IgnoresOtherSystemsOnceItKnowsItsAutopilot) {
  Rig rig;
  rig.heartbeat();
  FakeAutopilot other(kSys + 1, mav::mav_autopilot::kPx4);
  rig.bridge.on_frame(other.heartbeat(true, rig.offboard_mode()), rig.t);
  rig.bridge.on_frame(other.landed(mav::mav_landed_state::kInAir), rig.t);
  const FcStatus s = rig.bridge.state(rig.t);
  EXPECT_EQ(s.system_id, kSys);
  EXPECT_FALSE(s.armed);
  EXPECT_EQ(s.mode_name, "POSCTL");
  EXPECT_EQ(s.landed_state, LandedState::Undefined);
}

TEST(Bridge, CompanionHeartbeatAt1HzAsOnboardControllerOnTheAutopilotsSystem) {
  Rig rig;
  rig.run(0.5);  // nothing heard yet: provisional id, so a udpout peer hears us first
  rig.heartbeat();
  rig.written.clear();
  rig.run(3.0);
  const auto beats = test::parse(rig.written);
  int count = 0;
  for (const auto& f : beats) {
    const auto hb = mav::decode<mav::Heartbeat>(f);
    if (!hb) continue;
    ++count;
    EXPECT_EQ(f.system_id, kSys);
    EXPECT_EQ(f.component_id, 191);
    EXPECT_EQ(hb->type, 18);
    EXPECT_EQ(hb->autopilot, 8);
  }
  EXPECT_EQ(count, 3);
}

TEST(Bridge, HeartbeatLossAfterItsTimeoutEvenWhileOtherFramesArrive) {
  Rig rig;
  rig.flying();
  rig.run(0.5);
  rig.heartbeats = false;
  const double last_heartbeat = 100.0;
  while (rig.t < last_heartbeat + 1.49) {
    rig.step();
    rig.bridge.on_frame(rig.autopilot.imu(-9.81F), rig.t);
    rig.bridge.on_frame(rig.autopilot.landed(mav::mav_landed_state::kInAir), rig.t);
    ASSERT_TRUE(rig.bridge.state(rig.t).link_ok) << rig.t;
  }
  rig.run(0.03);
  EXPECT_FALSE(rig.bridge.state(rig.t).link_ok);
  EXPECT_FALSE(rig.bridge.state(rig.t).offboard_ready);
  rig.collect_notices();
  EXPECT_TRUE(rig.noticed("autopilot link LOST"));
  rig.heartbeat();
  EXPECT_TRUE(rig.bridge.state(rig.t).link_ok);
}

// Only the downlink may be gone: the bridge asks for the land mode blind (the agent has
// failed its task, nobody else would end the flight), again while nothing answers.
TEST(Bridge, HeartbeatLostWhileCoverFliesRequestsLandBlind) {
  Rig rig;
  rig.run(1.0);
  rig.flying();
  rig.run(0.5);
  ASSERT_TRUE(rig.sent_commands(mav::mav_cmd::kNavLand).empty());
  rig.heartbeats = false;
  rig.obey = false;
  rig.run(3.0);
  EXPECT_FALSE(rig.bridge.state(rig.t).link_ok);
  EXPECT_GE(rig.sent_commands(mav::mav_cmd::kNavLand).size(), 2u);
  EXPECT_NE(rig.bridge.state(rig.t).failsafe.find("link lost"), std::string::npos);
}

// On the ground, disarmed, a lost link asks for nothing.
TEST(Bridge, HeartbeatLostOnTheGroundRequestsNothing) {
  Rig rig;
  rig.run(1.0);
  rig.heartbeats = false;
  rig.run(3.0);
  EXPECT_FALSE(rig.bridge.state(rig.t).link_ok);
  EXPECT_TRUE(rig.sent_commands(mav::mav_cmd::kNavLand).empty());
}

TEST(Bridge, AgentSilentForTheTimeoutLandsWithinOneTick) {
  Rig rig;
  rig.run(1.0);
  rig.flying();
  rig.run(0.5);
  EXPECT_TRUE(rig.bridge.state(rig.t).offboard_ready);
  EXPECT_TRUE(rig.sent_commands(mav::mav_cmd::kNavLand).empty());
  rig.agent_alive = false;
  const double last_command = rig.t;
  double landed_at = -1.0;
  while (rig.t < last_command + 0.5 && landed_at < 0.0) {
    rig.step();
    if (!rig.sent_commands(mav::mav_cmd::kNavLand).empty()) landed_at = rig.t;
  }
  ASSERT_GT(landed_at, 0.0);
  EXPECT_GT(landed_at - last_command, 0.1);
  EXPECT_LE(landed_at - last_command, 0.1 + 0.02 + 1e-9);  // one 50 Hz tick
  rig.heartbeat();                                         // shows AUTO.LAND: the request ends
  rig.run(3.0);
  EXPECT_EQ(rig.sent_commands(mav::mav_cmd::kNavLand).size(), 1U);
  const FcStatus s = rig.bridge.state(rig.t);
  EXPECT_EQ(s.mode, FcMode::Land);
  EXPECT_NE(s.failsafe.find("no command from the UAV agent for"), std::string::npos) << s.failsafe;
  rig.collect_notices();
  EXPECT_TRUE(rig.noticed("LAND commanded: no command from the UAV agent"));
}

TEST(Bridge, LandRequestedAgainUntilTheAutopilotIsInLandMode) {
  Rig rig;
  rig.flying();
  rig.run(0.5);
  rig.obey = false;  // the autopilot does not answer
  rig.agent_alive = false;
  rig.heartbeats = false;
  for (int i = 0; i < 150; ++i) {
    rig.step();
    if (rig.steps % 50 == 0) rig.heartbeat();  // still armed in offboard
  }
  // 0.1 s silent, then 4 sends per request (0.25 s each) and a new request: > 1 request.
  const auto lands = rig.sent_commands(mav::mav_cmd::kNavLand);
  EXPECT_GE(lands.size(), 5U);
  EXPECT_EQ(lands[0].confirmation, 0);
  EXPECT_EQ(lands[1].confirmation, 1);
}

TEST(Bridge, HandoverCommandsLandAtOnce) {
  Rig rig(Autopilot::ArduPilot);
  rig.run(1.0);
  rig.flying();
  rig.run(0.3);
  rig.handover = true;
  rig.t += kStep_s;
  const auto& frames = rig.bridge.on_agent_command(rig.command(), rig.t);
  const auto sent = commands(frames);
  ASSERT_EQ(sent.size(), 1U);
  EXPECT_EQ(sent[0].command, mav::mav_cmd::kDoSetMode);
  EXPECT_EQ(sent[0].param[1], 9.0F);  // ArduPilot LAND
  EXPECT_EQ(sent[0].target_system, kSys);
  EXPECT_EQ(decoded<mav::SetAttitudeTarget>(frames).size(), 1U);  // the setpoint still goes
  EXPECT_NE(rig.bridge.state(rig.t).failsafe.find("handed over"), std::string::npos);
}

TEST(Bridge, NaNAndRepeatedCommandsCountAsMissing) {
  Rig rig;
  rig.heartbeat();
  rig.t += kStep_s;
  AgentCommand c = rig.command();
  EXPECT_EQ(rig.bridge.on_agent_command(c, rig.t).size(), 1U);
  EXPECT_TRUE(rig.bridge.on_agent_command(c, rig.t + 0.01).empty());  // verbatim repeat
  AgentCommand bad = rig.command();
  bad.stamp_ns += 20'000'000;
  bad.pitch_rate_rad_s = std::nan("");
  EXPECT_TRUE(rig.bridge.on_agent_command(bad, rig.t + 0.02).empty());
  AgentCommand older = rig.command();  // the realtime clock stepping back: still fresh
  older.stamp_ns -= 5'000'000;
  EXPECT_EQ(rig.bridge.on_agent_command(older, rig.t + 0.03).size(), 1U);
  rig.collect_notices();
  EXPECT_TRUE(rig.noticed("a repeat of the previous one"));
  // Only the first bad one of a run is logged; the NaN came in the same run.
  EXPECT_FALSE(rig.noticed("not flyable"));
}

TEST(Bridge, ARepeatOfACommandNotSentYetGoesOnceTheAutopilotIsKnown) {
  Rig rig;
  rig.t += kStep_s;
  const AgentCommand c = rig.command();
  EXPECT_TRUE(rig.bridge.on_agent_command(c, rig.t).empty());  // no autopilot yet
  rig.heartbeat();
  EXPECT_EQ(decoded<mav::SetAttitudeTarget>(rig.bridge.on_agent_command(c, rig.t)).size(), 1U);
  EXPECT_TRUE(rig.bridge.on_agent_command(c, rig.t).empty());  // sent: now a repeat
}

TEST(Bridge, NeverArmsWithoutAnOperatorOrAutoArm) {
  Rig rig;  // auto_arm false
  rig.run(1.0);
  rig.heartbeat();
  rig.run(10.0);
  EXPECT_TRUE(rig.sent_commands(mav::mav_cmd::kComponentArmDisarm).empty());
  EXPECT_TRUE(rig.sent_commands(mav::mav_cmd::kDoSetMode).empty());
  EXPECT_FALSE(rig.armed);
  rig.take(rig.bridge.on_operator_request(OperatorCommand::Arm, "req-1", rig.t));
  const auto arms = rig.sent_commands(mav::mav_cmd::kComponentArmDisarm);
  ASSERT_EQ(arms.size(), 1U);
  EXPECT_EQ(arms[0].param[0], 1.0F);
  EXPECT_EQ(arms[0].param[1], 0.0F);
  ASSERT_EQ(rig.bridge.replies().size(), 1U);
  EXPECT_EQ(rig.bridge.replies()[0].request_id, "req-1");
  EXPECT_EQ(rig.bridge.replies()[0].outcome, CommandOutcome::Accepted);
}

// Both firmwares arm before they ACK: the accepted answer is the new state, a second before
// the 1 Hz HEARTBEAT would show it (a task waiting for it starts that much sooner). A
// HEARTBEAT sent before the arming took effect and read after the ACK does not undo it; one
// still saying disarmed past AutopilotSession::kAckedStateHold_s does.
TEST(Bridge, ArmedFromTheAcceptedArmBeforeTheNextHeartbeat) {
  Rig rig;
  rig.heartbeats = false;  // only the HEARTBEATs this test sends
  rig.heartbeat();
  rig.run(0.5);
  ASSERT_FALSE(rig.bridge.state(rig.t).armed);
  rig.take(rig.bridge.on_operator_request(OperatorCommand::Arm, "arm", rig.t));
  ASSERT_TRUE(rig.armed);  // the autopilot armed and answered
  EXPECT_TRUE(rig.bridge.state(rig.t).armed);
  rig.armed = false;  // a HEARTBEAT from before the arming, read after the ACK
  rig.run(0.2);
  rig.heartbeat();
  EXPECT_TRUE(rig.bridge.state(rig.t).armed);
  rig.armed = true;
  rig.run(0.2);
  rig.heartbeat();
  EXPECT_TRUE(rig.bridge.state(rig.t).armed);
  // Once a HEARTBEAT has shown the arming, it is the autopilot's word again at once.
  rig.armed = false;
  rig.run(0.01);
  rig.heartbeat();
  EXPECT_FALSE(rig.bridge.state(rig.t).armed);

  // An arming the autopilot undid: the disarmed HEARTBEAT past the hold counts.
  rig.take(rig.bridge.on_operator_request(OperatorCommand::Arm, "arm again", rig.t));
  ASSERT_TRUE(rig.bridge.state(rig.t).armed);
  rig.armed = false;
  rig.run(AutopilotSession::kAckedStateHold_s + 0.05);
  rig.heartbeat();
  EXPECT_FALSE(rig.bridge.state(rig.t).armed);

  // A refused arm changes nothing.
  rig.obey = false;
  rig.take(rig.bridge.on_operator_request(OperatorCommand::Arm, "refused", rig.t));
  rig.bridge.on_frame(rig.autopilot.ack(mav::mav_cmd::kComponentArmDisarm,
                                        mav::mav_result::kTemporarilyRejected, 7, 191),
                      rig.t);
  EXPECT_FALSE(rig.bridge.state(rig.t).armed);
}

// The same for the mode: OFFBOARD / GUIDED_NOGPS accepted is the mode at once, an older
// HEARTBEAT within the hold does not undo it, a later one does.
TEST(Bridge, ModeFromTheAcceptedSetModeBeforeTheNextHeartbeat) {
  for (const Autopilot kind : {Autopilot::Px4, Autopilot::ArduPilot}) {
    Rig rig(kind);
    rig.heartbeats = false;
    rig.heartbeat();
    rig.run(1.1);  // the stream the request needs
    ASSERT_NE(rig.bridge.state(rig.t).mode, FcMode::Offboard);
    const std::uint32_t before = rig.custom_mode;
    rig.take(rig.bridge.on_operator_request(OperatorCommand::Offboard, "offboard", rig.t));
    ASSERT_EQ(rig.custom_mode, rig.offboard_mode()) << to_string(kind);
    EXPECT_EQ(rig.bridge.state(rig.t).mode, FcMode::Offboard) << to_string(kind);
    rig.custom_mode = before;  // sent before the change, read after the ACK
    rig.run(0.2);
    rig.heartbeat();
    EXPECT_EQ(rig.bridge.state(rig.t).mode, FcMode::Offboard) << to_string(kind);
    rig.run(AutopilotSession::kAckedStateHold_s);
    rig.heartbeat();  // the autopilot did not stay in it: its word counts again
    EXPECT_NE(rig.bridge.state(rig.t).mode, FcMode::Offboard) << to_string(kind);
  }
}

TEST(Bridge, AutoArmStreamsThenOffboardThenArms) {
  for (const Autopilot kind : {Autopilot::Px4, Autopilot::ArduPilot}) {
    Rig rig(kind, true);
    rig.heartbeat();
    double offboard_at = -1.0;
    double arm_at = -1.0;
    const double start = rig.t;
    for (int i = 0; i < 500; ++i) {
      rig.step();
      if (offboard_at < 0.0 && !rig.sent_commands(mav::mav_cmd::kDoSetMode).empty())
        offboard_at = rig.t;
      if (arm_at < 0.0 && !rig.sent_commands(mav::mav_cmd::kComponentArmDisarm).empty())
        arm_at = rig.t;
    }
    ASSERT_GT(offboard_at, 0.0) << to_string(kind);
    ASSERT_GT(arm_at, 0.0) << to_string(kind);
    EXPECT_GE(offboard_at - start, 1.0);  // after a second of setpoints
    EXPECT_LE(offboard_at - start, 1.1);
    EXPECT_GT(arm_at, offboard_at);
    EXPECT_EQ(rig.sent_commands(mav::mav_cmd::kDoSetMode)[0].param[1],
              kind == Autopilot::Px4 ? 6.0F : 20.0F);
    EXPECT_EQ(rig.sent_commands(mav::mav_cmd::kComponentArmDisarm).size(), 1U);
    EXPECT_TRUE(rig.bridge.state(rig.t).offboard_ready) << to_string(kind);
  }
}

TEST(Bridge, AutoArmGivesUpWhenThePilotTakesOver) {
  Rig rig(Autopilot::Px4, true);
  rig.heartbeat();
  rig.run(4.0);
  ASSERT_TRUE(rig.bridge.state(rig.t).offboard_ready);
  rig.custom_mode = mav::px4_mode::custom_mode(mav::px4_mode::kMainPosctl);  // RC switch
  rig.run(5.0);
  EXPECT_EQ(rig.sent_commands(mav::mav_cmd::kDoSetMode).size(), 1U);
  EXPECT_TRUE(rig.sent_commands(mav::mav_cmd::kNavLand).empty());  // the pilot flies
}

TEST(Bridge, OperatorOffboardBeforeTheStreamIsRefusedWithTheReason) {
  Rig rig;
  rig.agent_alive = false;
  rig.heartbeat();
  rig.run(0.1);
  rig.take(rig.bridge.on_operator_request(OperatorCommand::Offboard, "r1", rig.t));
  EXPECT_TRUE(rig.sent_commands(mav::mav_cmd::kDoSetMode).empty());
  ASSERT_EQ(rig.bridge.replies().size(), 1U);
  EXPECT_EQ(rig.bridge.replies()[0].outcome, CommandOutcome::Refused);
  EXPECT_NE(rig.bridge.replies()[0].message.find("setpoints have streamed for 0.00 s"),
            std::string::npos)
      << rig.bridge.replies()[0].message;
  rig.bridge.replies().clear();
  rig.agent_alive = true;
  rig.run(1.05);
  rig.take(rig.bridge.on_operator_request(OperatorCommand::Offboard, "r2", rig.t));
  EXPECT_EQ(rig.sent_commands(mav::mav_cmd::kDoSetMode).size(), 1U);
  ASSERT_EQ(rig.bridge.replies().size(), 1U);
  EXPECT_EQ(rig.bridge.replies()[0].outcome, CommandOutcome::Accepted);
}

TEST(Bridge, OperatorRequestWithoutAutopilotIsRefusedAtOnce) {
  Rig rig;
  rig.bridge.on_operator_request(OperatorCommand::Land, "r", rig.t);
  ASSERT_EQ(rig.bridge.replies().size(), 1U);
  EXPECT_EQ(rig.bridge.replies()[0].outcome, CommandOutcome::Refused);
  EXPECT_NE(rig.bridge.replies()[0].message.find("link is down"), std::string::npos);
}

TEST(Bridge, UnansweredOperatorCommandIsRetriedThenNoAnswer) {
  Rig rig;
  rig.heartbeat();
  rig.obey = false;
  rig.take(rig.bridge.on_operator_request(OperatorCommand::Disarm, "r", rig.t));
  rig.run(1.1);
  const auto sent = rig.sent_commands(mav::mav_cmd::kComponentArmDisarm);
  ASSERT_EQ(sent.size(), 4U);
  for (std::size_t i = 0; i < sent.size(); ++i) EXPECT_EQ(sent[i].confirmation, i);
  ASSERT_EQ(rig.bridge.replies().size(), 1U);
  EXPECT_EQ(rig.bridge.replies()[0].outcome, CommandOutcome::NoAnswer);
}

TEST(Bridge, PayloadReleaseOnTheRisingEdgeOnly) {
  Rig rig;
  rig.heartbeat();
  for (int i = 0; i < 10; ++i) {
    rig.t += kStep_s;
    AgentCommand c = rig.command();
    c.release_payload = i >= 3;
    rig.take(rig.bridge.on_agent_command(c, rig.t));
  }
  const auto grips = rig.sent_commands(mav::mav_cmd::kDoGripper);
  ASSERT_EQ(grips.size(), 1U);
  EXPECT_EQ(grips[0].param[0], 1.0F);
  EXPECT_EQ(grips[0].param[1], 0.0F);  // release
}

// The closed loop of a hover: the autopilot's IMU measures g u / u_true for the thrust u
// the bridge sends, the agent's command makes up for the error as a height loop would.
// With `velocity`, the autopilot's LOCAL_POSITION_NED gives the climb at 25 Hz too.
double hover_estimate_after(double hover_setting, double seconds, bool velocity = false) {
  const double truth = 9.81 / 20.0;
  BridgeConfig config = Rig::config(Autopilot::Px4, false);
  config.params.hover_thrust = hover_setting;
  Rig tuned(config);
  tuned.flying();
  double thrust = 0.0;
  double climb = 0.0;
  for (int i = 0; i < static_cast<int>(seconds / kStep_s); ++i) {
    tuned.t += kStep_s;
    ++tuned.steps;
    AgentCommand c = tuned.command();
    c.thrust_m_s2 = 9.81 - 2.0 * climb;  // the agent's vertical speed loop
    for (const auto& sp :
         decoded<mav::SetAttitudeTarget>(tuned.bridge.on_agent_command(c, tuned.t))) {
      thrust = sp.thrust;
    }
    const double force = 9.81 * thrust / truth;
    climb += (force - 9.81) * kStep_s;
    if (tuned.steps % 2 == 0) {
      tuned.bridge.on_frame(tuned.autopilot.imu(static_cast<float>(-force)), tuned.t);
      tuned.bridge.tick(tuned.t);
    }
    if (velocity && tuned.steps % 4 == 0) {
      mav::LocalPositionNed position;
      position.vz = static_cast<float>(-climb);  // NED
      tuned.bridge.on_frame(tuned.autopilot.send(position), tuned.t);
    }
    if (tuned.steps % 100 == 0) tuned.heartbeat();
    if (tuned.steps % 20 == 0) tuned.bridge.on_frame(tuned.autopilot.landed(tuned.landed), tuned.t);
  }
  tuned.collect_notices();
  EXPECT_TRUE(tuned.noticed("hover thrust estimate"));
  EXPECT_EQ(tuned.noticed("vertical velocity (LOCAL_POSITION_NED) aids"), velocity);
  return tuned.bridge.state(tuned.t).hover_thrust;
}

TEST(Bridge, HoverThrustMisSetByTwentyPercentConvergesInFlight) {
  const double truth = 9.81 / 20.0;
  EXPECT_NEAR(hover_estimate_after(1.2 * truth, 3.0), truth, 0.03 * truth);
  EXPECT_NEAR(hover_estimate_after(0.8 * truth, 3.0), truth, 0.03 * truth);
}

TEST(Bridge, HoverThrustAidedByTheAutopilotsVerticalVelocity) {
  const double truth = 9.81 / 20.0;
  EXPECT_NEAR(hover_estimate_after(1.2 * truth, 3.0, true), truth, 0.01 * truth);
  EXPECT_NEAR(hover_estimate_after(0.8 * truth, 3.0, true), truth, 0.01 * truth);
}

TEST(Bridge, HoverThrustRestsOnTheGround) {
  Rig rig;
  rig.heartbeat();
  for (int i = 0; i < 200; ++i) {
    rig.step();
    rig.bridge.on_frame(rig.autopilot.imu(-5.0F), rig.t);  // would pull the estimate up
  }
  EXPECT_DOUBLE_EQ(rig.bridge.state(rig.t).hover_thrust, 9.81 / 20.0);
}

TEST(Bridge, NoCommandNoFrameAndNeverNaNOnTheWire) {
  Rig rig;
  rig.heartbeat();
  rig.t += kStep_s;
  AgentCommand c = rig.command();
  c.thrust_m_s2 = 1e300;
  EXPECT_TRUE(rig.bridge.on_agent_command(c, rig.t).empty());
  c.seq += 1;
  c.thrust_m_s2 = 500.0;
  const auto sp = decoded<mav::SetAttitudeTarget>(rig.bridge.on_agent_command(c, rig.t));
  ASSERT_EQ(sp.size(), 1U);
  EXPECT_EQ(sp[0].thrust, 1.0F);
}

}  // namespace
}  // namespace cover::fc_bridge
