// The bridge's own logic (cover_fc_bridge_core, what cover-fc-bridge runs) on the simulated
// autopilot, every frame through our encoders and parsers both ways, stepped at 100 Hz of
// simulated time: what the bridge learns from the simulated PX4 / ArduPilot is what it
// learned from the real firmware (its streams asked for and arriving, its parameters,
// PX4's EVENTs in words, the auto-disarm delay).
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "autopilot_bench.hpp"
#include "cover/fc_bridge/bridge.hpp"

namespace {

using cover::Autopilot;
using cover::fc_bridge::AgentCommand;
using cover::fc_bridge::Bridge;
using cover::fc_bridge::BridgeConfig;
using cover::fc_bridge::FcStatus;
using cover::fc_bridge::OperatorCommand;
using cover::sim::fc::SimFcParams;
using cover::sim::fc::SimulatedAutopilot;
using cover::sim::fc::test::ground_world;
namespace mav = cover::mavlink;

constexpr std::uint8_t kSystem = 4;
constexpr double kPeriod_s = 0.01;

// A bridge and a simulated autopilot on one world. Each step: the autopilot's step (its
// frames to the bridge), the agent's command (while `agent`), the bridge's housekeeping
// every other step (50 Hz); whatever the bridge writes reaches the autopilot at once and
// its answers the bridge.
class BridgeOnAutopilot {
 public:
  explicit BridgeOnAutopilot(Autopilot profile, const SimFcParams& params = SimFcParams{})
      : world_(ground_world()), autopilot_(profile, kSystem, params), bridge_(config(profile)) {}

  void run(double seconds) {
    const int steps = static_cast<int>(std::lround(seconds / kPeriod_s));
    for (int i = 0; i < steps; ++i) step();
  }

  void step() {
    const cover::sim::fc::AutopilotStep s = autopilot_.step(t_, world_);
    to_bridge(s.frames);
    world_.advance(s.plant_command, kPeriod_s);
    if (agent) to_autopilot(bridge_.on_agent_command(command(), t_));
    if (++steps_ % 2 == 0) to_autopilot(bridge_.tick(t_));
    t_ = world_.state().time_s;
  }

  // As a ground station on the link would (the bridge never asks OFFBOARD without a stream).
  void ground_station(const mav::CommandLong& command) {
    mav::Encoder gcs(255, mav::mav_comp::kMissionPlanner);
    deliver(gcs.encode(command));
  }
  std::vector<cover::fc_bridge::OperatorReply> operator_request(OperatorCommand command) {
    to_autopilot(bridge_.on_operator_request(command, "test-" + std::to_string(++requests_), t_));
    run(0.5);  // a refusal waits up to 0.3 s for the autopilot's reasons
    std::vector<cover::fc_bridge::OperatorReply> replies;
    replies.swap(bridge_.replies());
    return replies;
  }

  FcStatus state() const { return bridge_.state(t_); }
  SimulatedAutopilot& autopilot() { return autopilot_; }
  double t_s() const { return t_; }

  bool agent = false;

 private:
  static BridgeConfig config(Autopilot profile) {
    BridgeConfig c;
    c.autopilot = profile;
    return c;
  }
  AgentCommand command() const {
    AgentCommand c;
    c.stamp_ns = static_cast<std::int64_t>(std::llround(t_ * 1e9));
    c.seq = static_cast<std::uint32_t>(steps_ + 1);
    c.thrust_m_s2 = 0.0;
    c.armed = false;
    return c;
  }
  void to_bridge(const std::vector<mav::EncodedFrame>& frames) {
    for (const auto& e : frames) {
      from_autopilot_.feed(e.bytes.data(), e.size,
                           [&](const mav::Frame& f) { bridge_.on_frame(f, t_); });
    }
    bridge_.set_parser_stats(from_autopilot_.stats());
  }
  void deliver(const mav::EncodedFrame& e) {
    std::vector<mav::EncodedFrame> answers;
    to_autopilot_parser_.feed(e.bytes.data(), e.size, [&](const mav::Frame& f) {
      const auto response = autopilot_.on_frame(f, t_);
      answers.insert(answers.end(), response.frames.begin(), response.frames.end());
    });
    to_bridge(answers);
  }
  void to_autopilot(const std::vector<mav::EncodedFrame>& frames) {
    const std::vector<mav::EncodedFrame> copy = frames;  // the bridge reuses its list
    for (const auto& e : copy) deliver(e);
  }

  cover::sim::World world_;
  SimulatedAutopilot autopilot_;
  Bridge bridge_;
  mav::StreamParser from_autopilot_;
  mav::StreamParser to_autopilot_parser_;
  double t_ = 0.0;
  long steps_ = 0;
  int requests_ = 0;
};

const cover::fc_bridge::StreamState* stream(const FcStatus& s, std::uint32_t id) {
  for (const auto& st : s.streams) {
    if (st.request.message_id == id) return &st;
  }
  return nullptr;
}

// ArduCopter sends nothing but HEARTBEAT until asked: the bridge asks, and every stream it
// reads then arrives at the asked rate (streams_missing empty, the landed state and the
// battery known, the estimator aligned).
TEST(BridgeOnSimulatedAutopilot, ArduPilotStreamsArriveAsTheBridgeAsks) {
  BridgeOnAutopilot rig(Autopilot::ArduPilot);
  rig.run(5.0);
  const FcStatus s = rig.state();
  EXPECT_TRUE(s.link_ok);
  EXPECT_EQ(s.streams_missing, "");
  for (const std::uint32_t id :
       {mav::HighresImu::kId, mav::ExtendedSysState::kId, mav::SysStatus::kId,
        mav::BatteryStatus::kId, mav::EkfStatusReport::kId}) {
    const auto* st = stream(s, id);
    ASSERT_NE(st, nullptr) << id;
    EXPECT_TRUE(st->arriving) << id;
    // The bridge's window counts the frames at both of its ends (1 Hz reads 1.5 Hz).
    EXPECT_GE(st->measured_hz, 0.95 * st->request.rate_hz) << id;
  }
  EXPECT_EQ(s.landed_state, cover::fc_bridge::LandedState::OnGround);
  EXPECT_GT(s.battery_voltage_v, 16.0);
  EXPECT_TRUE(s.estimator.attitude_ok) << s.estimator.text;
  EXPECT_EQ(s.rx_errors, 0u);
  EXPECT_EQ(s.rx_unknown, 0u);  // ArduCopter streams nothing the codec does not know
  EXPECT_EQ(s.status_text, "EKF3 IMU0 tilt alignment complete");
}

// PX4 streams ~25 types the codec does not know: skipped whole, no error, no gap.
TEST(BridgeOnSimulatedAutopilot, Px4UnknownTypesAreSkippedWhole) {
  BridgeOnAutopilot rig(Autopilot::Px4);
  rig.run(3.0);
  const FcStatus s = rig.state();
  EXPECT_EQ(s.streams_missing, "");
  EXPECT_GE(s.rx_unknown, 55u);  // ALTITUDE and VFR_HUD at 10 Hz for 3 s, less the last
  EXPECT_EQ(s.rx_errors, 0u);
  EXPECT_EQ(s.rx_dropped, 0u);
  EXPECT_NEAR(stream(s, mav::HighresImu::kId)->measured_hz, 100.0, 5.0);  // asked; default 50
}

// The parameters the bridge reads, as the simulated firmware types them: all known and as
// COVER needs them by default; a wrong ATC_ANGLE_BOOST set in sim_fc.yaml holds the flights.
TEST(BridgeOnSimulatedAutopilot, TheBridgeReadsEveryParameterAndCatchesAWrongAngleBoost) {
  for (const auto profile : {Autopilot::Px4, Autopilot::ArduPilot}) {
    BridgeOnAutopilot rig(profile);
    rig.run(2.0);
    const FcStatus s = rig.state();
    for (const auto& p : s.parameters) {
      if (p.name == "SYSID_THISMAV") continue;  // the old name of MAV_SYSID
      EXPECT_TRUE(p.known) << p.name;
      EXPECT_TRUE(p.ok) << p.name << " = " << p.value;
    }
    EXPECT_EQ(s.flight_blocker, "");
    EXPECT_DOUBLE_EQ(s.auto_disarm_s, profile == Autopilot::Px4 ? 11.0 : 10.0);
  }
  SimFcParams wrong;
  wrong.ardupilot.atc_angle_boost = 1;
  BridgeOnAutopilot rig(Autopilot::ArduPilot, wrong);
  rig.run(2.0);
  EXPECT_NE(rig.state().flight_blocker.find("ATC_ANGLE_BOOST is 1, COVER needs 0"),
            std::string::npos)
      << rig.state().flight_blocker;
}

// PX4 SITL in OFFBOARD without setpoints refused the operator's arm; its reasons came only
// as EVENTs, which the bridge puts in its answer.
TEST(BridgeOnSimulatedAutopilot, Px4ArmRefusalCarriesTheEventsReasons) {
  BridgeOnAutopilot rig(Autopilot::Px4);
  rig.run(1.0);
  mav::CommandLong offboard;
  offboard.command = mav::mav_cmd::kDoSetMode;
  offboard.param[0] = 1.0F;
  offboard.param[1] = mav::px4_mode::kMainOffboard;
  offboard.target_system = kSystem;
  offboard.target_component = 1;
  rig.ground_station(offboard);
  rig.run(1.1);
  ASSERT_EQ(rig.state().mode_name, "OFFBOARD");
  const auto replies = rig.operator_request(OperatorCommand::Arm);
  ASSERT_EQ(replies.size(), 1u);
  EXPECT_EQ(replies[0].outcome, cover::fc_bridge::CommandOutcome::Refused);
  EXPECT_NE(replies[0].message.find("Arming denied: Resolve system health failures first"),
            std::string::npos)
      << replies[0].message;
  EXPECT_NE(replies[0].message.find("No offboard signal"), std::string::npos) << replies[0].message;
}

// PX4 SITL disarmed 11 s after an arm on the ground: the bridge sees it disarmed, in words.
TEST(BridgeOnSimulatedAutopilot, Px4PreflightDisarmReachesTheBridge) {
  BridgeOnAutopilot rig(Autopilot::Px4);
  rig.run(1.0);
  const auto replies = rig.operator_request(OperatorCommand::Arm);  // in AUTO.LOITER
  ASSERT_EQ(replies.size(), 1u);
  EXPECT_EQ(replies[0].outcome, cover::fc_bridge::CommandOutcome::Accepted) << replies[0].message;
  rig.run(9.0);
  EXPECT_TRUE(rig.state().armed);
  rig.run(2.6);  // 11 s after the arm, and the next HEARTBEAT
  EXPECT_FALSE(rig.state().armed);
  EXPECT_EQ(rig.state().status_text, "Disarmed by preflight inaction");
}

}  // namespace
